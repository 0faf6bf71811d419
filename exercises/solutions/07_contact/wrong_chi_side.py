"""Wrong: χ the indicator of ℝ⁺ instead of ℝ⁻ (contact taken where g_n > 0)."""
import numpy as np

EXPECT = "χ(g_n) = 1 for g_n < 0"


def contact_update(g_n):
    g_n = np.asarray(g_n, float)
    return np.where(g_n > 0, g_n, 0.0)
