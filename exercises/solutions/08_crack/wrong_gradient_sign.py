"""Wrong: ∂F/∂x₁ = cos θ ∂F/∂r + (sin θ/r) ∂F/∂θ, the sign of ∂θ/∂x₁ = -sin θ/r lost."""
import numpy as np

EXPECT = "finite differences of your branch_functions"


def branch_gradients(r, theta):
    r, theta = np.asarray(r, float), np.asarray(theta, float)
    sr, s, c = np.sqrt(r), np.sin(theta / 2), np.cos(theta / 2)
    st, ct = np.sin(theta), np.cos(theta)
    d_r = np.stack([s, c, s * st, c * st]) / (2 * sr)
    d_t = sr * np.stack([c / 2, -s / 2, c / 2 * st + s * ct, -s / 2 * st + c * ct])
    return np.stack([ct * d_r + st / r * d_t, st * d_r + ct / r * d_t], axis=1)
