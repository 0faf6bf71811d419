"""Wrong: a maximum matching only; the nodes it leaves unmatched stay uncovered."""
import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import maximum_bipartite_matching

EXPECT = "is not touched by any vital edge"


def minimum_edge_cover(edges, psi, length):
    edges, psi = np.asarray(edges), np.asarray(psi, float)
    minus = np.where(psi[edges[0]] < 0, edges[0], edges[1])
    plus = edges[0] + edges[1] - minus
    graph = sp.csr_matrix((np.ones(edges.shape[1]), (minus, plus)), shape=(psi.size,) * 2)
    match = maximum_bipartite_matching(graph, perm_type="column")
    return match[minus] == plus
