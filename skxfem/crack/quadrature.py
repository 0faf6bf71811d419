r"""Quadrature of cracked cells: sub-triangle rules and the almost-polar rule at the tip.

Every rule here is a per-cell rule in reference coordinates, the form
``skfem.Basis(mesh, elem, elements=rule.cells, quadrature=(rule.X, rule.W))``
takes (:class:`skxfem.fem.quadrature.SubcellRule`); ``rule.V`` holds the side
(±1) of the sub-triangle of each point, 0 on padding.

The integrands and the orders chosen
------------------------------------
* A **split cell** whose nodes carry only the Heaviside enrichment integrates
  polynomials on each sub-triangle: P1 gradients are constant (order 0),
  Q1 gradients linear in each reference coordinate (order 2 on a sub-triangle);
  the stiffness order of :data:`skxfem.fem.quadrature.EXACT_ORDERS`.
* A cell in the support of a **branch-enriched** node integrates products of
  φᵢ F_l and their gradients: smooth away from the tip but not polynomial.  A
  Gauss rule of order :data:`BRANCH_ORDER` (8) on its sub-triangles, or on the whole
  cell when the crack does not cross it; :data:`NEAR_ORDER` (16) on the cells around
  the tip cells, where 1/r peaks within the cell's size.
* The **tip cell**: ∇F_l is of order r^{-½}, so the stiffness integrand is of
  order 1/r, the energy-error's too, and the √r of F_l·∇φ sits in between.  On
  each fan triangle (vertex V₀ at the tip, :mod:`skxfem.crack.geometry`) the
  *almost-polar* map of Béchet et al. (2005), a Duffy collapse of the unit square
  onto the triangle,

  .. math:: x(u, v) = V_0 + u\,[(1 - v)(V_1 - V_0) + v (V_2 - V_0)],\qquad
            dx = u\,|\det(V_1 - V_0, V_2 - V_0)|\,du\,dv,

  cancels the 1/r (r ∝ u along each ray), and with u = s² (du = 2s ds) every
  r^{k/2}, k ≥ -2, becomes a polynomial in s: a Gauss–Legendre rule of n_r points
  in s integrates them exactly along each ray, n_θ points in v integrate the
  smooth angular part (every θ-function is analytic in v on a fan triangle, whose
  edges carry the crack; fan triangles are first cut into pieces of at most
  :data:`MAX_ANGLE` at the tip, :func:`angular_pieces`, where Gauss in v converges
  fast).  ∫ r^{1/2}, r^{-1/2}, r^{-1} over a tip cell: exact to 1e-13 with the
  default :data:`POLAR_POINTS` (792 points in a cell fanned into 11 pieces), where a
  plain triangle rule of order 16 on the cell (61 points) misses them by 0.25 %, 2 %
  and 10 % (measured, tests/test_crack_xfem.py).

>>> import numpy as np
>>> tri = np.array([[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]])
>>> x, w = almost_polar(tri, 4, 6)
>>> x.shape, round(float(w.sum()), 14)
((1, 24, 2), 0.5)
"""
from __future__ import annotations

import numpy as np
from numpy.polynomial.legendre import leggauss

from ..fem.quadrature import SubcellRule, pack_rules, simplex_points

__all__ = ["BRANCH_ORDER", "NEAR_ORDER", "POLAR_POINTS", "MAX_ANGLE", "angular_pieces",
           "almost_polar", "split_rule", "tip_rule"]

BRANCH_ORDER = 8
"""Order of the triangle rule on (sub-)cells in the support of branch-enriched nodes."""

NEAR_ORDER = 16
"""Order of the triangle rule on the cells around the tip cells (sharing a node with
one): their integrand 1/r is singular a fraction of a cell away.  Measured on the exact
Williams field in a space that holds it (every node branch-enriched, 7 × 7 triangles):
energy error 3.6e-4 and K_I + 6e-6 with order 8 there, 1.6e-7 and 1e-9 with 16."""

POLAR_POINTS = (6, 12)
"""(n_r, n_θ): Gauss points along and across the rays of the almost-polar rule."""

MAX_ANGLE = np.pi / 4
"""Fan triangles are cut into pieces of at most this angle at the tip before the
almost-polar rule (:func:`angular_pieces`): 1/|x - V₀| along the opposite edge is analytic
in v, but the nearer that edge passes to V₀ (a wide angle) the slower Gauss converges
(measured on a right angle, ∫ 1/r: 6e-7 with 8 points; 45°: below 1e-13 with 10; ∫ √r
over a tip cell: 4e-12 with 10, 1e-13 with 12)."""


def angular_pieces(tris: np.ndarray, max_angle: float = MAX_ANGLE
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Cut triangles (m, 3, 2) collapsed at vertex 0 into pieces of equal angle at
    vertex 0, at most ``max_angle`` each: the pieces (m', 3, 2), vertex 0 kept, and the
    triangle each comes from (m',).

    >>> t, k = angular_pieces(np.array([[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]]))
    >>> t.shape, k.tolist(), np.round(t[1, 1], 12).tolist()
    ((2, 3, 2), [0, 0], [0.5, 0.5])
    """
    tris = np.asarray(tris, float)
    out, parent = [], []
    for k, (a, b, c) in enumerate(tris):                # the few fan triangles of tip cells
        u, v = b - a, c - a
        angle = np.arctan2(abs(u[0] * v[1] - u[1] * v[0]), u @ v)
        n = max(1, int(np.ceil(angle / max_angle - 1e-12)))
        # the ray at angle t·angle from u meets the edge b + s (c - b): solve for s
        rot = np.sign(u[0] * v[1] - u[1] * v[0]) or 1.0
        pts = [b]
        for i in range(1, n):
            t = i * angle / n
            d = np.array([np.cos(rot * t) * u[0] - np.sin(rot * t) * u[1],
                          np.sin(rot * t) * u[0] + np.cos(rot * t) * u[1]])
            e = c - b
            s = (d[0] * (b - a)[1] - d[1] * (b - a)[0]) / (d[1] * e[0] - d[0] * e[1])
            pts.append(b + s * e)
        pts.append(c)
        for i in range(n):
            out.append([a, pts[i], pts[i + 1]])
            parent.append(k)
    return np.array(out).reshape(-1, 3, 2), np.array(parent, dtype=int)


def _gauss01(n: int) -> tuple[np.ndarray, np.ndarray]:
    s, w = leggauss(n)
    return (s + 1) / 2, w / 2


def almost_polar(tris: np.ndarray, n_r: int = POLAR_POINTS[0],
                 n_t: int = POLAR_POINTS[1]) -> tuple[np.ndarray, np.ndarray]:
    """The almost-polar rule on triangles collapsed at their vertex 0 (module notes).

    Parameters
    ----------
    tris : (m, 3, 2) triangles, vertex 0 the singular point.
    n_r, n_t : Gauss points in s = √u (along the rays) and in v (across them).

    Returns
    -------
    points (m, n_r n_t, 2), weights (m, n_r n_t) in the triangles' coordinates.

    Examples
    --------
    >>> tri = np.array([[[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]]])
    >>> x, w = almost_polar(tri, 3, 8)
    >>> r = np.linalg.norm(x[0], axis=1)
    >>> bool(abs(w[0] @ (1 / r) - 2 * np.sqrt(2) * np.log(1 + np.sqrt(2))) < 1e-6)
    True
    """
    tris = np.asarray(tris, float)
    s, ws = _gauss01(n_r)
    v, wv = _gauss01(n_t)
    S, Vv = np.repeat(s, n_t), np.tile(v, n_r)
    W0 = np.repeat(ws, n_t) * np.tile(wv, n_r) * 2 * S ** 3       # 2s ds · u, u = s²
    d1, d2 = tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]
    det = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    ray = (1 - Vv)[None, :, None] * d1[:, None] + Vv[None, :, None] * d2[:, None]
    x = tris[:, None, 0] + (S ** 2)[None, :, None] * ray
    return x, det[:, None] * W0[None]


def split_rule(geometry, cells: np.ndarray, order: int) -> SubcellRule:
    """The rule of order ``order`` on the sub-triangles of the split ``cells`` of a
    :class:`skxfem.crack.geometry.CrackGeometry`; ``V`` the side of each point.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 1, 4))
    >>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.6)
    >>> r = split_rule(g, g.split_cells, 0)
    >>> r.cells.tolist() == g.split_cells.tolist(), round(float(r.W.sum()), 14)  # 3 halves
    (True, 1.5)
    """
    pick = np.isin(geometry.sub_cell, cells) & ~geometry.sub_fan
    x, w = simplex_points(geometry.sub_ref[pick], order)
    return pack_rules(x, w, geometry.sub_cell[pick], geometry.sub_side[pick])


def tip_rule(geometry, order: int = BRANCH_ORDER, n_r: int = POLAR_POINTS[0],
             n_t: int = POLAR_POINTS[1]) -> SubcellRule:
    """The rule of the tip cells: almost-polar on the fan triangles, the triangle rule of
    ``order`` on their other sub-triangles (those of a quadrilateral's half without the
    tip), both padded to one number of points per piece; ``V`` the sides.

    >>> from skfem import MeshQuad1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshQuad1.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 1, 4))
    >>> r = tip_rule(crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.4))
    >>> r.cells.tolist(), round(float(r.W.sum()), 14)       # the reference square
    ([4], 1.0)
    """
    tip = np.isin(geometry.sub_cell, geometry.tip_cells)
    fan, other = np.flatnonzero(tip & geometry.sub_fan), tip & ~geometry.sub_fan
    pieces, of = angular_pieces(geometry.sub_ref[fan])
    fan = fan[of]
    xf, wf = almost_polar(pieces, n_r, n_t)
    xo, wo = simplex_points(geometry.sub_ref[other], order)
    nq = max(wf.shape[1], wo.shape[1])
    xs, ws = [], []
    for x, w in ((xf, wf), (xo, wo)):
        pad = nq - w.shape[1]
        xs.append(np.concatenate([x, np.full((x.shape[0], pad, 2), 1.0 / 3)], axis=1))
        ws.append(np.concatenate([w, np.zeros((w.shape[0], pad))], axis=1))
    parent = np.concatenate([geometry.sub_cell[fan], geometry.sub_cell[other]])
    side = np.concatenate([geometry.sub_side[fan], geometry.sub_side[other]])
    return pack_rules(np.concatenate(xs), np.concatenate(ws), parent, side)
