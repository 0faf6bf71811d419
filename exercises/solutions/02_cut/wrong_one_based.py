"""Wrong: an off-by-one in the edge list (1-based indices, as the paper counts)."""
import numpy as np

EXPECT = "is not cut"


def cut_edges(edges, psi):
    edges, psi = np.asarray(edges), np.asarray(psi, float)
    return np.flatnonzero(psi[edges[0]] * psi[edges[1]] < 0) + 1
