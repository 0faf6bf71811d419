"""Wrong: |x - center|² - radius², the right zero set and signs but not a distance."""
import numpy as np

EXPECT = "is not the distance to the sphere"


def sphere(center, radius):
    c = np.asarray(center, float)
    return lambda x: sum((np.asarray(x, float)[i] - c[i]) ** 2 for i in range(3)) - radius ** 2
