"""Wrong: ψ_a ψ_b <= 0 also takes the edges that only touch Γ at a vertex."""
import numpy as np

EXPECT = "touches Γ at a vertex"


def cut_edges(edges, psi):
    edges, psi = np.asarray(edges), np.asarray(psi, float)
    return np.flatnonzero(psi[edges[0]] * psi[edges[1]] <= 0)
