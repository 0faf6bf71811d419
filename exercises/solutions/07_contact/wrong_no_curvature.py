"""Wrong: the Jacobian outside the ball taken as I/|g|, the -ĝĝᵀ term forgotten."""
import numpy as np

EXPECT = "radial direction"


def ball_projection(g):
    g = np.asarray(g, float)
    n, k = g.shape
    norm = np.maximum(np.linalg.norm(g, axis=1), 1.0)
    return g / norm[:, None], np.eye(k)[None] / norm[:, None, None]
