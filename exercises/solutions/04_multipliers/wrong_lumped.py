"""Wrong: the lumped (row-sum, diagonal) mass instead of the consistent one."""
import numpy as np

EXPECT = "L/6 [[2, 1], [1, 2]]"


def interface_mass(points, segments):
    points, segments = np.asarray(points, float), np.asarray(segments)
    L = np.linalg.norm(points[:, segments[1]] - points[:, segments[0]], axis=0)
    d = np.zeros(points.shape[1])
    np.add.at(d, segments.ravel(), np.tile(L / 2.0, 2))
    return np.diag(d)
