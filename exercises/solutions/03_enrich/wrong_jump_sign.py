"""Wrong: [[u]] = u⁺ - u⁻ = +2 Σ φ_i b_i, the opposite of the convention."""
import numpy as np

EXPECT = "[[u]] = u⁻ - u⁺"


def jump(phi, b):
    return float(2.0 * np.asarray(phi, float) @ np.asarray(b, float))
