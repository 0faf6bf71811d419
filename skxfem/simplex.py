r"""Splitting a simplex by the zero of a linear function: the kernel of the cut.

A triangle or tetrahedron whose vertex values ψ change sign is split by the
plane {ψ_h = 0} of the linear interpolant ψ_h into pieces that lie entirely in
Ω⁻ or Ω⁺.  Each piece is returned as simplices again, so that standard simplex
quadrature integrates over it:

* triangle, one vertex alone on its side: a triangle and a quadrilateral
  (split into two triangles);
* tetrahedron, one vertex alone: a tetrahedron and a prism (three tetrahedra);
* tetrahedron, two against two: two prisms (three tetrahedra each).

An edge (a, b) with ψ_a ψ_b < 0 is cut at a + t (b - a), t = ψ_a / (ψ_a - ψ_b),
the zero of ψ_h on the edge.  The same rule defines the intersection points in
:mod:`skxfem.cut`, so sub-cells and interface facets agree.

>>> import numpy as np
>>> tri = np.array([[[0., 0.], [1., 0.], [0., 1.]]])
>>> sub, parent, side = split(tri, np.array([[-1., 1., 1.]]))
>>> float(sum(abs(np.linalg.det(s[1:] - s[0])) / 2 for s in sub))
0.5
"""
from __future__ import annotations

import numpy as np

__all__ = ["split", "WEDGE_TO_TETS", "edge_point"]

#: The three tetrahedra of a prism with bottom (0, 1, 2) and top (3, 4, 5),
#: lateral edges 0-3, 1-4, 2-5 (also scikit-fem's ``MeshWedge1.to_meshtet``).
WEDGE_TO_TETS = np.array([[0, 1, 2, 3], [1, 2, 3, 4], [2, 3, 4, 5]])


def edge_point(xa: np.ndarray, xb: np.ndarray, pa: np.ndarray, pb: np.ndarray) -> np.ndarray:
    """The zero of the linear interpolant of ψ on the segment [xa, xb].

    ``xa, xb`` have shape ``(..., dim)``, ``pa, pb`` shape ``(...)`` with pa·pb < 0.
    """
    t = pa / (pa - pb)
    return xa + t[..., None] * (xb - xa)


def _lone_and_others(neg: np.ndarray, lone_is_negative: np.ndarray):
    """Index of the vertex alone on its side, and the others in cyclic order."""
    nv = neg.shape[1]
    alone = np.where(lone_is_negative[:, None], neg, ~neg)
    lone = np.argmax(alone, axis=1)
    others = (lone[:, None] + np.arange(1, nv)[None, :]) % nv
    return lone, others


def split(X: np.ndarray, psi: np.ndarray):
    """Split simplices by the zero level of their linear ψ interpolant.

    Parameters
    ----------
    X
        Vertices, shape ``(n, d + 1, d)`` with d = 2 (triangles) or 3 (tetrahedra).
    psi
        Vertex values of ψ, shape ``(n, d + 1)``, none of them zero.

    Returns
    -------
    sub : ndarray
        Sub-simplices, shape ``(m, d + 1, d)``.
    parent : ndarray
        Index into ``X`` of the simplex each sub-simplex comes from, ``(m,)``.
    side : ndarray
        -1 for a piece in Ω⁻, +1 for Ω⁺, ``(m,)``.
    """
    n, nv, d = X.shape
    if nv != d + 1 or d not in (2, 3):
        raise ValueError(f"X must have shape (n, d+1, d) with d = 2 or 3, got {X.shape}")
    if np.any(psi == 0.0):
        raise ValueError("psi must not vanish at a simplex vertex")
    neg = psi < 0
    k = neg.sum(axis=1)
    rows = np.arange(n)
    subs, parents, sides = [], [], []

    def emit(verts, idx, s):
        subs.append(np.stack(verts, axis=1))
        parents.append(idx)
        sides.append(np.broadcast_to(s, idx.shape))

    whole = (k == 0) | (k == nv)
    emit([X[whole, i] for i in range(nv)], rows[whole], np.where(k[whole] == 0, 1, -1))

    lone_cases = (k == 1) | (k == nv - 1) if d == 3 else (k == 1) | (k == 2)
    idx = rows[lone_cases]
    lone, others = _lone_and_others(neg[idx], k[idx] == 1)
    s = np.where(neg[idx, lone], -1, 1)
    A, pA = X[idx, lone], psi[idx, lone]
    O = [X[idx, others[:, j]] for j in range(d)]
    cut = [edge_point(A, O[j], pA, psi[idx, others[:, j]]) for j in range(d)]
    emit([A] + cut, idx, s)
    if d == 2:
        B, C = O
        pAB, pAC = cut
        emit([B, C, pAC], idx, -s)
        emit([B, pAC, pAB], idx, -s)
    else:
        prism = np.stack(O + cut, axis=1)
        for tet in WEDGE_TO_TETS:
            emit([prism[:, i] for i in tet], idx, -s)

    if d == 3:
        idx = rows[k == 2]
        order = np.argsort(~neg[idx], axis=1, kind="stable")  # negatives first
        a, b, c, dd = (X[idx, order[:, j]] for j in range(4))
        pa, pb, pc, pd = (psi[idx, order[:, j]] for j in range(4))
        pac, pad = edge_point(a, c, pa, pc), edge_point(a, dd, pa, pd)
        pbc, pbd = edge_point(b, c, pb, pc), edge_point(b, dd, pb, pd)
        minus = np.stack([a, pac, pad, b, pbc, pbd], axis=1)
        plus = np.stack([c, pac, pbc, dd, pad, pbd], axis=1)
        for prism, s in ((minus, -1), (plus, 1)):
            for tet in WEDGE_TO_TETS:
                emit([prism[:, i] for i in tet], idx, s)

    return (np.concatenate(subs), np.concatenate(parents),
            np.concatenate(sides).astype(int))
