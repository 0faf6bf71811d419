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

from ..fem.cells import reference_simplices
from ..fem.quadrature import SubcellRule, pack_rules, simplex_points
from .geometry import AREA_TOL, nearest_on_segments

__all__ = ["BRANCH_ORDER", "NEAR_ORDER", "NEAR_GAP", "POLAR_POINTS", "MAX_ANGLE",
           "angular_pieces", "almost_polar", "split_rule", "tip_rule", "near_tip_cells",
           "near_rule"]

BRANCH_ORDER = 8
"""Order of the triangle rule on (sub-)cells in the support of branch-enriched nodes."""

NEAR_ORDER = 16
"""Order of the triangle rule on the cells around the tip cells (sharing a node with
one): their integrand 1/r is singular a fraction of a cell away.  Measured on the exact
Williams field in a space that holds it (every node branch-enriched, 7 × 7 triangles):
energy error 3.6e-4 and K_I + 6e-6 with order 8 there, 1.6e-7 and 1e-9 with 16."""

NEAR_GAP = 0.25
"""A cell around the tip cells whose closure lies within NEAR_GAP of a tip, in its
reference coordinates (a tip just outside it, across an edge: the tip cell's far edge,
or a node the tip nearly reaches), takes :func:`near_rule` instead of the Gauss rule of
:data:`NEAR_ORDER`: 1/r peaks at its edge there.  Measured on an edge crack a = 0.5 in
a 1 × 4 plate under tension (20 × 40 quadrilaterals, crack mid-cell, K_I against
Tada's), the tip a distance d before a vertical edge: with the Gauss rule -0.14 % at
d = 0.1 h, +0.08 % at 0.03 h, +0.34 % at 0.01 h, +0.63 % from 1e-4 h down (-0.17 % on
the edge): a jump of 0.8 % in K for a move of 1e-9; with :func:`near_rule`, -0.16 %,
-0.16 %, -0.17 %, -0.17 %, -0.17 %."""

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


def _nearest(tri: np.ndarray, p: np.ndarray) -> np.ndarray:
    """The point of the triangle ``tri`` (3, 2) nearest to ``p`` (2,)."""
    a, b, c = tri
    M = np.stack([b - a, c - a], axis=1)
    lam = np.linalg.solve(M, p - a)
    if lam.min() >= 0 and lam.sum() <= 1:
        return p.copy()
    _, q, dist = nearest_on_segments(tri.T, np.roll(tri, -1, axis=0).T - tri.T, p[:, None])
    return q[:, np.argmin(dist)]                      # on its sides ab, bc, ca


def _pieces(geometry, mesh, cells: np.ndarray):
    """The reference sub-triangles (m, 3, 2) of ``cells`` (split cells: their sub-cells;
    others: the reference cell's triangles), their cell (m,) and side (m,)."""
    ref = mesh.elem().doflocs
    whole = ref[reference_simplices(mesh)]                       # (ns, 3, 2)
    tris, parent, side = [], [], []
    for c in cells:
        if c in geometry.split_cells:
            k = geometry.sub_cell == c
            tris.append(geometry.sub_ref[k])
            side.append(geometry.sub_side[k])
        else:
            tris.append(whole)
            side.append(np.full(whole.shape[0], geometry.side[c]))
        parent.append(np.full(tris[-1].shape[0], c))
    return np.concatenate(tris), np.concatenate(parent), np.concatenate(side)


def _collapse_points(geometry, mesh, cells: np.ndarray):
    """The sub-triangles of ``cells`` (:func:`_pieces`) and, in each, its point P nearest
    the nearest tip T (found on the triangle of its mapped vertices, carried back by its
    barycentric coordinates), in reference coordinates (m, 2), and |P - T| over the
    cell's size (m,)."""
    tris, parent, side = _pieces(geometry, mesh, cells)
    F = mesh.mapping().F
    phys = np.stack([F(tris[:, k].T[:, :, None], tind=parent)[:, :, 0].T for k in range(3)],
                    axis=1)                                      # (m, 3, 2)
    d = np.linalg.norm(phys.mean(axis=1)[:, :, None] - geometry.tips[None], axis=1)
    T = geometry.tips[:, np.argmin(d, axis=1)].T                 # (m, 2)
    h = np.ptp(mesh.p[:, mesh.t[:, parent]], axis=1).max(axis=0)
    P_ref, gap = np.empty((tris.shape[0], 2)), np.empty(tris.shape[0])
    for k in range(tris.shape[0]):                      # the few cells next to a tip
        P = _nearest(phys[k], T[k])
        M = np.stack([phys[k, 1] - phys[k, 0], phys[k, 2] - phys[k, 0]], axis=1)
        lam = np.linalg.solve(M, P - phys[k, 0])
        P_ref[k] = tris[k, 0] + lam @ (tris[k, 1:] - tris[k, 0])
        gap[k] = np.linalg.norm(P - T[k]) / h[k]
    return tris, parent, side, P_ref, gap


def near_tip_cells(geometry, mesh, cells: np.ndarray, gap: float = NEAR_GAP) -> np.ndarray:
    """Those of ``cells`` (none a tip cell) that lie within ``gap`` cell sizes of a tip
    (:data:`NEAR_GAP`).

    >>> from skfem import MeshQuad1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshQuad1.init_tensor(np.linspace(0, 1, 5), np.linspace(0, 1, 5))
    >>> g = crack_geometry(m, m.p[1] - 0.6, m.p[0] - (0.5 - 1e-7))   # just before x = 0.5
    >>> others = np.setdiff1d(np.arange(m.t.shape[1]), g.tip_cells)
    >>> near = near_tip_cells(g, m, others)
    >>> near.size, m.p[:, m.t[:, near[0]]].min(axis=1).tolist()      # the next cell
    (1, [0.5, 0.5])
    """
    cells = np.asarray(cells, dtype=int)
    if cells.size == 0:
        return cells
    _, parent, _, _, d = _collapse_points(geometry, mesh, cells)
    return np.unique(parent[d < gap])


def near_rule(geometry, mesh, cells: np.ndarray, n_r: int = POLAR_POINTS[0],
              n_t: int = POLAR_POINTS[1]) -> SubcellRule:
    """The rule of cells near a tip but not holding it (:func:`near_tip_cells`): each of
    their sub-triangles fanned from its point P nearest the tip T, and the almost-polar
    rule on the fan.  For x in a sub-triangle |x - T|² ≥ |x - P|² + |P - T|² (P is the
    projection of T on a convex set), so the collapse at P cancels the 1/|x - T| of the
    branch functions' gradients up to a layer of the size |P - T|, where the
    Gauss rule of :data:`NEAR_ORDER` lost it; ``V`` the sides.

    >>> from skfem import MeshQuad1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshQuad1.init_tensor(np.linspace(0, 1, 5), np.linspace(0, 1, 5))
    >>> g = crack_geometry(m, m.p[1] - 0.6, m.p[0] - (0.5 - 1e-7))
    >>> r = near_rule(g, m, np.array([9]))
    >>> r.cells.tolist(), round(float(r.W.sum()), 12)              # the reference square
    ([9], 1.0)
    """
    cells = np.unique(np.asarray(cells, dtype=int))
    tris, parent, side, P_ref, _ = _collapse_points(geometry, mesh, cells)
    fans, fan_parent, fan_side = [], [], []
    for tri, c, sd, P in zip(tris, parent, side, P_ref):
        for i in range(3):
            f = np.array([P, tri[i], tri[(i + 1) % 3]])
            d1, d2 = f[1] - f[0], f[2] - f[0]
            if abs(d1[0] * d2[1] - d1[1] * d2[0]) > 2 * AREA_TOL:
                fans.append(f)
                fan_parent.append(c)
                fan_side.append(sd)
    pieces, of = angular_pieces(np.array(fans))
    x, w = almost_polar(pieces, n_r, n_t)
    return pack_rules(x, w, np.array(fan_parent)[of], np.array(fan_side)[of])
