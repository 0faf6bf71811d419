"""Wrong: radius - |x - center|, positive inside: the sides are swapped."""
import numpy as np

EXPECT = "the centre of a circle is inside, in Ω⁻"


def circle(center, radius):
    c = np.asarray(center, float).reshape((2,))
    return lambda x: radius - np.sqrt(sum((np.asarray(x, float)[i] - c[i]) ** 2 for i in range(2)))
