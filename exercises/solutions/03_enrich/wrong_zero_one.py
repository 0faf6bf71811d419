"""Wrong: H = 0 / 1 (a plain step) instead of -1 / +1."""
import numpy as np

EXPECT = "H = ±1, not 0/1"


def heaviside(psi):
    return np.where(np.asarray(psi, float) < 0, 0.0, 1.0)
