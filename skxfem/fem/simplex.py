r"""Splitting a simplex by the zero of a linear function: the one clipping kernel.

A segment, triangle or tetrahedron whose vertex values ψ change sign is split by
the zero set {ψ_h = 0} of the linear interpolant ψ_h into pieces that lie entirely
in Ω⁻ or Ω⁺.  Each piece is returned as simplices again, so that standard simplex
quadrature integrates over it:

* segment: two segments;
* triangle, one vertex alone on its side: a triangle and a quadrilateral
  (split into two triangles);
* tetrahedron, one vertex alone: a tetrahedron and a prism (three tetrahedra);
* tetrahedron, two against two: two prisms (three tetrahedra each).

The simplices may live in more coordinates than their own dimension (a boundary
triangle of a tetrahedron, in the tetrahedron's reference coordinates), so the
same kernel splits the sub-cells of :mod:`skxfem.cut` and the loaded boundary
facets of :mod:`skxfem.fem.loads`.

An edge (a, b) with ψ_a ψ_b < 0 is cut at a + t (b - a), t = ψ_a / (ψ_a - ψ_b),
the zero of ψ_h on the edge (:func:`edge_point`, the only place skxfem writes
this formula): the intersection points of :mod:`skxfem.cut`, the sub-cells and
the load pieces all agree.  A vertex with ψ = 0 counts as Ω⁺ (Ω⁻ = {ψ < 0}), so
a simplex lying on Γ is one piece on the + side.

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


def edge_point(xa: np.ndarray, xb: np.ndarray, pa: np.ndarray,
               pb: np.ndarray) -> np.ndarray:
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
        Vertices, shape ``(n, k + 1, dim)``: segments (k = 1), triangles (k = 2)
        or tetrahedra (k = 3), in ``dim ≥ k`` coordinates.
    psi
        Vertex values of ψ, shape ``(n, k + 1)``; a zero counts as Ω⁺.

    Returns
    -------
    sub : ndarray
        Sub-simplices, shape ``(m, k + 1, dim)``.  A vertex with ψ = 0 can
        leave a piece of zero measure (harmless in quadrature).
    parent : ndarray
        Index into ``X`` of the simplex each sub-simplex comes from, ``(m,)``.
    side : ndarray
        -1 for a piece in Ω⁻, +1 for Ω⁺, ``(m,)``.

    >>> seg = np.array([[[0., 0.], [4., 0.]]])
    >>> sub, parent, side = split(seg, np.array([[-1., 3.]]))
    >>> sub[:, :, 0].tolist(), side.tolist()
    ([[0.0, 1.0], [4.0, 1.0]], [-1, 1])
    """
    X, psi = np.asarray(X, dtype=float), np.asarray(psi, dtype=float)
    if X.ndim != 3 or X.shape[1] not in (2, 3, 4) or X.shape[2] < X.shape[1] - 1:
        raise ValueError(f"X must have shape (n, k+1, dim) with k = 1, 2 or 3 and "
                         f"dim >= k, got {X.shape}")
    if psi.shape != X.shape[:2] or not np.all(np.isfinite(psi)):
        raise ValueError(f"psi must be finite, of shape {X.shape[:2]}, got {psi.shape}")
    n, nv, _ = X.shape
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

    # one vertex alone on its side (a segment's cut is always of this kind)
    lone_cases = (k == 1) | (k == nv - 1)
    idx = rows[lone_cases & ~whole]
    lone, others = _lone_and_others(neg[idx], k[idx] == 1)
    s = np.where(neg[idx, lone], -1, 1)
    A, pA = X[idx, lone], psi[idx, lone]
    O = [X[idx, others[:, j]] for j in range(nv - 1)]
    cut = [edge_point(A, O[j], pA, psi[idx, others[:, j]]) for j in range(nv - 1)]
    emit([A] + cut, idx, s)
    if nv == 2:
        emit([O[0], cut[0]], idx, -s)
    elif nv == 3:
        B, C = O
        pAB, pAC = cut
        emit([B, C, pAC], idx, -s)
        emit([B, pAC, pAB], idx, -s)
    else:
        prism = np.stack(O + cut, axis=1)
        for tet in WEDGE_TO_TETS:
            emit([prism[:, i] for i in tet], idx, -s)

    if nv == 4:  # a tetrahedron, two vertices on each side
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
