"""Wrong: θ = atan2(x₁, x₂), the arguments of atan2 swapped (the angle from e₂)."""
import numpy as np

EXPECT = "θ = atan2(x₂, x₁)"


def polar_coordinates(x1, x2):
    x1, x2 = np.asarray(x1, float), np.asarray(x2, float)
    return np.hypot(x1, x2), np.arctan2(x1, x2)
