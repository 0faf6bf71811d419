"""Wrong: (x - point)·normal without dividing by |normal|: not a distance."""
import numpy as np

EXPECT = "normalise the normal"


def plane(point, normal):
    p, n = np.asarray(point, float), np.asarray(normal, float)

    def psi(x):
        x = np.asarray(x, float)
        return sum(n[i] * (x[i] - p[i]) for i in range(n.size))

    return psi
