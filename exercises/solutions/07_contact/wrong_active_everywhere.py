"""Wrong: the Jacobian of χ(g_n) g_n taken as 1 everywhere (the inactive branch missed)."""
import numpy as np

EXPECT = "inactive branch"


def normal_update(g):
    g = np.asarray(g, float)
    return np.where(g < 0, g, 0.0), np.ones_like(g)
