r"""The bipartite graph of the cut edges (paper §5): checked input and the
queries that algo1 and algo2 (:mod:`skxfem.stabilised`) share.

The graph has the strictly cut edges S_e as edges and their ends N_e as
vertices; ``edges`` (2, ne) are node indices, ``psi`` the nodal level set,
``points`` (dim, ne) the intersection points, ``nodes`` (dim, nnodes) the
coordinates.  A ``fixed`` node (one whose jump a support holds) needs no
multiplier of its own.

>>> import numpy as np
>>> inc = incidence(np.array([[0, 2], [1, 1]]), 3, np.array([True, True]))
>>> edges_at(inc, np.array([1]))[1].tolist()     # the edges at node 1
[0, 1]
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["check_graph", "check_fixed", "incidence", "edges_at", "nearest", "interpolate"]


def check_graph(edges, psi, points, nodes):
    """The graph as arrays (edges int64), or a ValueError naming the bad argument."""
    nodes, psi, edges = np.asarray(nodes, float), np.asarray(psi, float), np.asarray(edges)
    points = np.asarray(points, float)
    if nodes.ndim != 2 or nodes.shape[0] not in (2, 3) or not np.isfinite(nodes).all():
        raise ValueError(f"nodes must be finite, shape (dim, nnodes); got {nodes.shape}")
    if psi.shape != nodes.shape[1:] or not np.isfinite(psi).all():
        raise ValueError(f"psi must be finite, shape ({nodes.shape[1]},); got {psi.shape}")
    if edges.ndim != 2 or edges.shape[0] != 2 or (edges.size and edges.dtype.kind not in "iu"):
        raise ValueError(f"edges must be node indices, shape (2, ne); got {edges.dtype} "
                         f"{edges.shape}")
    edges = edges.astype(np.int64)
    if points.shape != (nodes.shape[0], edges.shape[1]) or not np.isfinite(points).all():
        raise ValueError(f"points must be finite, shape ({nodes.shape[0]}, {edges.shape[1]});"
                         f" got {points.shape}")
    if edges.size and (edges.min() < 0 or edges.max() >= psi.size):
        raise ValueError(f"edges refer to nodes outside 0..{psi.size - 1}")
    signs = np.sign(psi[edges[0]]) * np.sign(psi[edges[1]])    # no underflow, as products
    for e in np.flatnonzero(signs >= 0)[:1]:
        raise ValueError(f"edges must be strictly cut, psi(v1) psi(v2) < 0; edge {e} = "
                         f"{edges[:, e].tolist()} has psi {psi[edges[:, e]].tolist()}")
    if np.unique(np.sort(edges, axis=0), axis=1).shape[1] < edges.shape[1]:
        raise ValueError("edges lists the same edge twice")
    for e in np.flatnonzero(np.all(nodes[:, edges[0]] == nodes[:, edges[1]], axis=0))[:1]:
        raise ValueError(f"nodes: the two ends of edge {e} coincide")
    return edges, psi, points, nodes


def check_fixed(fixed, edges, nnodes):
    """``fixed`` as an (nnodes,) bool array (default: no node fixed)."""
    if fixed is None:
        return np.zeros(nnodes, dtype=bool)
    fixed = np.asarray(fixed)
    if fixed.shape != (nnodes,) or fixed.dtype != bool:
        raise ValueError(f"fixed must be one bool per node, shape ({nnodes},); "
                         f"got {fixed.dtype} {fixed.shape}")
    for e in np.flatnonzero(fixed[edges[0]] & fixed[edges[1]])[:1]:
        raise ValueError(f"fixed: both ends of edge {e} = {edges[:, e].tolist()} are fixed; "
                         f"leave such an edge out (it carries no multiplier)")
    return fixed


def incidence(edges, nnodes, keep):
    """(nnodes, ne) CSR with an entry (v, e) for each kept edge e and end v."""
    k = np.flatnonzero(keep)
    return sp.csr_matrix((np.ones(2 * k.size), (edges[:, k].ravel(), np.tile(k, 2))),
                         shape=(nnodes, edges.shape[1]))


def edges_at(inc, v):
    """The rows ``v`` of ``inc`` laid end to end: (row position, edge) pairs."""
    start = inc.indptr[v]
    count = inc.indptr[v + 1] - start
    at = np.repeat(start - np.cumsum(count) + count, count) + np.arange(count.sum())
    return np.repeat(np.arange(v.size), count), inc.indices[at]


def nearest(points, query, ends, inc):
    """For each edge q = query[i]: the edge of ``inc`` at node ends[i] whose point
    is nearest to q's (ties: lowest index), -1 if there is none."""
    i, k = edges_at(inc, ends)
    dist = np.linalg.norm(points[:, query[i]] - points[:, k], axis=0)
    order = np.lexsort((k, dist, i))
    first = order[np.r_[True, i[order][1:] != i[order][:-1]]] if i.size else order
    best = np.full(ends.size, -1)
    best[i[first]] = k[first]
    return best


def interpolate(points, query, k1, k2, col1, col2):
    """COO rows of λ_e = d2/(d1+d2) λ_k1 + d1/(d1+d2) λ_k2, d_i = |x_e - x_ki| (§5)."""
    d1 = np.linalg.norm(points[:, query] - points[:, k1], axis=0)
    d2 = np.linalg.norm(points[:, query] - points[:, k2], axis=0)
    same = d1 + d2 == 0                                     # coincident points: halves
    d1[same] = d2[same] = 1.0
    return np.r_[query, query], np.r_[col1, col2], np.r_[d2, d1] / np.tile(d1 + d2, 2)
