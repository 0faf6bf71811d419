"""Wrong: the derivative outside the ball taken as I/|g|, the -ĝĝᵀ term forgotten."""
import numpy as np

EXPECT = "radial direction"


def project_unit_ball_derivative(g):
    g = np.asarray(g, float)
    k = g.shape[0]
    norm = np.linalg.norm(g, axis=0)
    eye = np.eye(k).reshape((k, k) + (1,) * (g.ndim - 1))
    return eye / np.maximum(norm, 1.0)
