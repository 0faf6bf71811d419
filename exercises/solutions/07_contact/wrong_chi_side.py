"""Wrong: χ the indicator of ℝ⁺ instead of ℝ⁻ (contact taken where g_n > 0)."""
import numpy as np

EXPECT = "χ(g_n) = 1 for g_n < 0"


def normal_update(g):
    g = np.asarray(g, float)
    return np.where(g > 0, g, 0.0), (g > 0).astype(float)
