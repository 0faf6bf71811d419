"""Wrong: the parameter runs from the second end, λ_h = s λ_a + (1 - s) λ_b."""
import numpy as np

EXPECT = "at s = 0 (the start of the segment"


def interpolate(lam, segments, k, s):
    a, b = np.asarray(segments)[:, k]
    return float(s * lam[a] + (1.0 - s) * lam[b])
