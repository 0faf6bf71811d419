"""Wrong: t = ψ_b / (ψ_b - ψ_a), the point mirrored about the middle of the edge."""
import numpy as np

EXPECT = "it should be 0"


def intersection_points(nodes, edges, psi):
    nodes, edges, psi = np.asarray(nodes, float), np.asarray(edges), np.asarray(psi, float)
    pa, pb = psi[edges[0]], psi[edges[1]]
    t = pb / (pb - pa)
    return nodes[:, edges[0]] + t * (nodes[:, edges[1]] - nodes[:, edges[0]])
