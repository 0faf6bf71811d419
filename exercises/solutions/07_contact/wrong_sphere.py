"""Wrong: g/|g| everywhere, a projection onto the unit sphere, not the unit ball."""
import numpy as np

EXPECT = "inside the unit ball"


def ball_projection(g):
    g = np.asarray(g, float)
    n, k = g.shape
    norm = np.linalg.norm(g, axis=1)
    gh = g / norm[:, None]
    return gh, (np.eye(k) - gh[:, :, None] * gh[:, None, :]) / norm[:, None, None]
