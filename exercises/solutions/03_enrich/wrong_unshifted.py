"""Wrong: the unshifted field Σ a_i φ_i + Σ b_i φ_i H (the shift - H_i forgotten)."""
import numpy as np

EXPECT = "the shift"


def enriched_value(phi, a, b, H, H_nodes):
    phi, a, b = (np.asarray(v, float) for v in (phi, a, b))
    return float(phi @ a + H * (phi @ b))
