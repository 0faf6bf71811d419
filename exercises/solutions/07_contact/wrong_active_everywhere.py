"""Wrong: the Jacobian of χ(g_n) g_n taken as 1 everywhere (the inactive branch missed)."""
import numpy as np

EXPECT = "inactive branch"


def contact_derivative(g_n):
    return np.ones_like(np.asarray(g_n, float))
