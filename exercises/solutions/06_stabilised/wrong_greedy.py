"""Wrong: greedy, drop the longest edge whose two ends stay covered, until none can
be dropped (code_aster's xrell2 style): a minimal cover, not always a minimum one."""
import numpy as np

EXPECT = "minimal but not minimum"


def minimum_edge_cover(edges, psi, length):
    edges, length = np.asarray(edges), np.asarray(length, float)
    keep = np.ones(edges.shape[1], dtype=bool)
    for e in np.argsort(-length, kind="stable"):
        count = np.bincount(edges[:, keep].ravel(), minlength=np.size(psi))
        if count[edges[0, e]] > 1 and count[edges[1, e]] > 1:
            keep[e] = False
    return keep
