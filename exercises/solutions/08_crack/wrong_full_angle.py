"""Wrong: the full angle θ in place of θ/2, F = √r {sin θ, cos θ, sin² θ, cos θ sin θ}."""
import numpy as np

EXPECT = "the half angle θ/2"


def branch_functions(r, theta):
    sr, s, c = np.sqrt(r), np.sin(theta), np.cos(theta)
    return sr * np.stack([s, c, s * s, c * s])
