"""Wrong: g/|g| everywhere, a projection onto the unit sphere, not the unit ball."""
import numpy as np

EXPECT = "inside the unit ball"


def project_unit_ball(g):
    g = np.asarray(g, float)
    return g / np.linalg.norm(g, axis=0)
