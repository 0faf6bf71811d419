r"""Contact on the faces of a 3D crack: the multipliers on the crossed edges, up to the front.

The 3D twin of :mod:`skxfem.crack.faces`, on a
:class:`~skxfem.crack.geometry3d.CrackGeometry3D`.  One λ_e lives at the crossing x_e
of every mesh edge e the crack crosses strictly (``edge_ids``: ψ changes sign along e
and φ < 0 at the crossing; an edge of a front cell crossed ahead of the front is not
one), and one at every mesh node on the crack behind its front that is a vertex of a
face (ψ = 0, φ < 0; the point (v, v), edge id -1, as a vertex on Γ of a
:class:`~skxfem.cut.Cut`: :func:`skxfem.crack.geometry.crack_points`, the same function
as in 2D).  So a crack along a mesh plane, or along the tetrahedra's diagonal faces
(the 45° crack of a structured mesh), has its multipliers at its nodes, and a plane
that crosses some edges and passes through some nodes has both.  The spaces are those
of :mod:`skxfem.stabilised` (naive, winner nodes = algo1, vital edges = algo2) on the
graph of the crossed edges, a node on the crack with a multiplier of its own
(:func:`skxfem.crack.faces.crack_multipliers`, the same function as in 2D, on the
faces' :func:`~skxfem.crack.faces.edge_graph`): its nodes are the ends of the crossed
edges, so a front cell's nodes that only edges crossed ahead
of the front reach carry no multiplier.

**Nodes on the crack** (tests/test_crack_contact_3d.py).  Before they carried a
multiplier, a crack along a mesh plane was refused, and one that crosses edges and
passes through nodes was held at its crossings only: sliding (the plane
y = 1/2 + (x - 1/2)/2 on 10 × 10 × 2 cells, frictionless, pressed by σ_yy) its faces
interpenetrated by 1.7e-2 at the nodes and 3.5e-2 at the crossings against a slip of
0.32, |K_I| = 7.7e-3 p√(πa); now 1.6e-4 and 1.5e-3, |K_I| ≤ 1.2e-3.  A uniform stress
was held either way (the pressure within 5e-5 of p, K ≈ 0).  pressed_slab at n = 10 (a
node plane) gives |K| ≤ 3.0e-4 p√(πa) and the pressure within 7.1e-5 of p with every
law and space.

**The multiplier functions on the faces.**  The crack's faces are the triangles of
{ψ_h = 0, φ_h ≤ 0} in each split or front cell (``faces``).  Their vertices are
points (crossings, nodes on the crack), or none: on the front (ψ_h = φ_h = 0), inside
a cell's face.  λ_h at such a vertex is the harmonic extension of the points' values over
the graph of the faces' sides (weights 1/length, the crossings held,
:func:`vertex_values`), so that a front point takes a mean of the crossings behind
it and of its neighbours along the front; on each face λ_h is linear between its
vertices.  Every row of the map from the edge λ to λ_h sums to one: a constant
traction stays in the space up to the front (the patch test).

**Vital edges at the front (what the package does; the paper leaves it open).**  The
edge cover of algo2 runs on the ends of the crossed edges only: no relation reaches
past the last crossings, and the faces of a front cell between its crossings and the
front take the extension above (and the points next to the front the λ behind them,
below).  The inf-sup constant of these spaces near a 3D
front is measured by :func:`skxfem.studies.cracks3d.crack_inf_sup_3d`.

**The points next to the front share the λ behind them**
(:func:`skxfem.crack.faces.tie_front`, the same function as in 2D, which the 3D crack
kind of Γ applies under a contact law: :meth:`skxfem.crack.kind3d.Crack3D.multipliers`,
:func:`skxfem.crack.faces.face_multipliers`).  A point on a
mesh edge with a node within :data:`~skxfem.crack.faces.FRONT_RINGS` (2) rings of cells
of the front cells carries no multiplier of its own: its row of P is the harmonic
extension of the others' over the faces' graph (as :func:`vertex_values`), a mean
(weights ≥ 0, summing to one) of the last untied points behind the band, mostly the
nearest; vital edges and groups stay on the untied points.  Measured, same run, before
→ after, on the closed inclined slab (:func:`skxfem.studies.cracks3d.inclined_slab`,
β = 30°, a = 1/4, nz = 3, the middle points of the two fronts; tests/test_crack_contact_3d.py):

* n = 21 (133 points, 40 → 24 multipliers): frictionless |K_I| 2.0e-3 → 0.29e-3
  σ√(πa), K_II within 0.06 % either way, the pressure 0.01 % → 0.07 % in the mean and
  2.3 % at the worst point either way; coulomb μ = 0.3 (sliding) |K_I| 0.94e-3 →
  0.15e-3, K_II 0.19 % → 0.08 %, the worst point 1.0 % either way; μ = 0.8 (sticking)
  |K_I| 2.2e-4 → 0.9e-4, |K_II| 0.8e-4 → 0.5e-4, the worst point 0.11 % → 0.02 %;
* n = 13 (91 points, 24 → 8): frictionless |K_I| 1.4e-3 → 0.72e-3 (3.3e-3 → 0.94e-3
  at every front point), the worst point 3.5 % → 0.8 %; μ = 0.3 0.97e-3 → 0.65e-3,
  1.6 % → 0.4 %; μ = 0.8 0.60e-3 → 0.59e-3; K_II within 0.95 % either way;
* the tilted crack through nodes (tests/test_crack_contact_3d.py, 10 × 10 × 2, five
  cells long, front x = 1/2 on a node plane) is where it costs: |K_I| 1.5e-3 → 5.1e-3,
  the faces interpenetrating by 5.1e-3 (not 2.3e-3) at the points that hold the band
  (the contact holds a weighted mean of the gaps of a point and those tied to it); with
  its front at x = 0.45, 0.53, 0.55 |K_I| 3.1e-3, 3.2e-3, 3.4e-3 → 4.9e-3, 1.8e-3,
  0.8e-3; at 20 × 20 × 2 (x = 0.5, 0.515, 0.525, 0.475) 0.85e-3, 2.8e-3, 3.2e-3,
  2.3e-3 → 0.07e-3, 0.19e-3, 0.16e-3, 0.06e-3 (p√(π x_f)).

Measured before the 3D default zone counted its cells by the front cells' cross-section
(main's merge of hsize9; the numbers above are with it):

* frictionless slab at n = 15, 17, 19: |K_I| 3.3e-3, 5.8e-3, 2.5e-3 → 0.26e-3, 0.43e-3,
  0.44e-3; at n = 11 (and nz = 2 at n = 11, the 45° crack at n = 10) every point is
  within the rings, the space is kept.  One ring: 0.25e-3, 0.21e-3, 2.1e-3, 1.1e-3,
  1.1e-3 at n = 13, 15, 17, 19, 21 (worse than two from n = 17 on); on the tilted
  crack 1.4e-3 (two: 4.7e-3);
* the pressed slabs: |K| unchanged to 2e-6 at n = 11, 21 (x = 1/2), 0.41e-3
  → 0.29e-3 (n = 7, x = 0.495) and 0.80e-3 → 0.56e-3 (n = 13, x = 0.575), the pressure
  within 0.09 % → 0.02 % and 0.23 % → 0.05 %; the pressed penny at h = 0.2 has every
  point within the rings: unchanged, |K_I| 2.7e-3, |K_II| 1.3e-3 p√(πa); at h = 0.125
  (239 points, 67 → 19 multipliers) |K_I| 0.82e-3 → 0.74e-3, |K_II| 0.33e-3 either
  way, the pressure within 0.35 % → 0.008 % of p.

What it costs (measured before the cross-section zone): the contact Newton takes more
iterations where most of a short crack is tied (tests/test_contact_newton.py's
pressed and sheared Coulomb crack, 2.4 cells long on 4³ cells: 6, 5, 4 per step → 10,
29, 15; 6³: 6, 8, 5 → 10, 6, 30; 8³: 7, 7, 5 → 14, 13, 4; the 2D tie leaves the 2D
crack at 3, 2, 2 → 5, 1, 2); the inclined
slab's solves take the same time (n = 21, μ = 0.3: 19.0 s, 18.7 s in one run).

A tie (``bonded``, ``bilateral``) keeps every point's multiplier
(:func:`skxfem.crack.faces.face_multipliers`): tied, a crack bonded under tension
(11³ cells, the front x = 1/2) opened near its front, K_I 0.013 → 0.071, the jump
4.4e-3 → 4.6e-2.  The inf-sup constant near the front does not fall (before the
cross-section zone, the setting of
:func:`skxfem.studies.cracks3d.crack_inf_sup_3d`, its normal multipliers, law
``frictionless`` for the tied space): vital 0.442, 0.431, 0.428 → 0.443, 0.431, 0.428
and winner 0.390, 0.373, 0.369 → 0.390, 0.374, 0.369 at n = 11, 15, 21 (24, 32, 44 →
16, 24, 36 multipliers); with the front 0.01 h past a node (n = 15) vital 0.404 →
0.431, and a sticking contact there 0.286 → 0.323.

**The faces' rule** (:func:`face_rule`).  On a face r = -φ_h, the distance to the
front, is linear; the level line of r through its middle vertex splits the face into two
triangles, each with r constant on the side opposite its apex.  Each gets 4 × 4 Gauss
points on the collapsed square with √r uniform from the apex to that side, so that √r
(the jump of the branch functions) and 1/√r (the Williams strains of the interaction
integral's face term) are integrated well wherever the front is near: at a vertex or a
side of the face, but also just past one (a crossing close to the front, a face of the
next cell), where a rule graded only at vertices on the front is not.  Measured on the
penny pressed shut (:func:`skxfem.studies.cracks3d.pressed_penny`, h = 0.2): the rule
graded at vertices on the front left |K_I| ≤ 0.0165 p√(πa), falling as 1/n with n × n
points per face (0.0097, 0.0059, 0.0043 at n = 8, 16, 32; 1/√r across a face whose
vertex lies just behind the front); this one 3.6e-3 (the same with 8 × 8), and 1.6e-3,
3.6e-3 at h = 0.125, 0.1 (before: 9.4e-3, 1.3e-2; sif_radius 0.25).  What was left there
was neither this rule nor the traction it carries but the interaction integral's own
error on the curved front (:mod:`skxfem.crack.sif3d`: the exact state gave 2.6e-3,
1.3e-3, 3.6e-3); with its auxiliary fields in the distance to the front instead of φ_h,
3.5e-3, 0.7e-3, 1.0e-3 for the exact state and 3.2e-3, 1.5e-3, 2.6e-3 solved.  At
h = 0.1 the rest was the contact's pressure, within 1.9 % of p at the crossings of the
front's first two cells (the solved U with the exact p: 0.9e-3; the exact U with the
solved λ: 2.6e-3).  That error was the stiffness's: the enriched rows of K U - F for the
exact U were not Bᵀ p.  Two causes, measured by K U₀ - Jᵀ(w p) of the exact state on the
branch rows (tests/test_crack_contact_3d.py): θ forced to ±π by the side in cells that
ψ_h crosses ahead of the front, where F then jumped inside a cell
(:func:`skxfem.crack.space3d._kinds`; 1.6e-2 -> 5.5e-3 h^2.5 p at h = 0.125), and the
plain 5³ rule of the cells near the front (:func:`skxfem.crack.space3d.near_points`)
where the front passes close to a cell or piece that does not hold it (graded,
:data:`~skxfem.crack.quadrature3d.NEAR_GRADING`: 1.4e-3).  With both, the pressure is
within 0.27 %, 0.35 %, 0.14 % of p at h = 0.2, 0.125, 0.1 and |K_I| 3.6e-3, 0.70e-3,
1.08e-3: that of the exact state (3.4e-3, 0.76e-3, 1.0e-3), the interaction integral's
own error.

**A front along the cells' faces.**  A through crack with its front on the tetrahedra's
diagonal faces (21 × 21 × 2, front x = 1/2) gave |K_I| = 3.2e-3 p√(πa) with the
multipliers, the last crossings 0.971 p, and 0.4e-3 with the exact pressure: the
enriched rows of K U - F - Bᵀ p for the exact state were 5.3e-5 (1.4e-5, 5.4e-6 with 8³,
12³ points on the cells near the front), against 3.5e-6 with the front mid-cell.  The
cells ahead of the front that share those faces were no front cells (φ_h on their crack
polygon, interpolated along their edges, came out +1e-17, not 0), so they kept the plain
rule with the singular gradients on their face.  With the tolerance of a vertex on the
front (:func:`skxfem.crack.geometry3d.crack_geometry_3d`) they are front cells: the
residual 4e-7, the last crossings within 1e-4 of p, |K_I| 0.2e-3, |K_II| 0.18e-3.

>>> from skfem import MeshTet1
>>> from skxfem.crack.geometry3d import crack_geometry_3d
>>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 8),) * 2, np.linspace(0, 1, 3))
>>> g = crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.53)
>>> E = vertex_values(g)                            # λ at each face vertex, per edge λ
>>> bool(np.allclose(E.sum(axis=1), 1.0))          # a constant is kept
True
>>> from skxfem.crack.faces import crack_multipliers
>>> S = crack_multipliers("vital", m, g)
>>> S.P.shape[0] == g.edge_ids.size, S.size < g.edge_ids.size
(True, True)
>>> from skxfem.crack.faces import tie_front
>>> T = tie_front(S, m, g)                          # x ≥ 2/7 take the λ of x = 3/14
>>> bool(np.allclose(T.P.sum(axis=1), 1.0)), T.size < S.size, bool(T.P.min() >= 0)
(True, True, True)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.polynomial.legendre import leggauss

from .faces import end_values
from .geometry3d import barycentric

__all__ = ["vertex_values", "FaceRule", "face_rule", "face_functions_3d", "FaceTraction3D",
           "face_traction_3d"]

FACE_POINTS = 4
"""Gauss points per direction of the faces' rule (16 per face)."""


def vertex_values(geo) -> sp.csr_matrix:
    """(3 nface, ne) λ_h at the faces' vertices from the edge multipliers: row
    k·nface + f is vertex k of face f (``geo.faces[f, k]``).

    A point (a crossing, a node on the crack) is its λ; the other vertices (on the
    front) take the harmonic extension over the faces' sides (module notes,
    :func:`skxfem.crack.faces.harmonic_extension`); a ValueError if the crack has no
    point (:func:`skxfem.crack.faces.check_crossed`): the 3D rows of
    :func:`skxfem.crack.faces.end_values`, which serves both.
    """
    return end_values(geo)


@dataclass(frozen=True)
class FaceRule:
    """Quadrature on the faces of a 3D crack (:func:`face_rule`): ``points`` (3, n),
    ``weights`` (n,), ``cells`` (n,) their cells, ``face`` (n,) their faces and ``bary``
    (3, n) their barycentric coordinates in the face (``geo.faces[face]``)."""

    points: np.ndarray
    weights: np.ndarray
    cells: np.ndarray
    face: np.ndarray
    bary: np.ndarray


def _front_distance(mesh, geo) -> np.ndarray:
    """(nface, 3) r = -φ_h at each face vertex (φ_h of the face's cell), 0 on the front
    (a vertex that is no crossing with |φ_h| ≤ 1e-9 h |∇φ_h|) and clipped at 0."""
    nf = geo.face_cell.size
    x = np.transpose(geo.faces, (2, 1, 0)).reshape(3, -1)  # vertex-major points
    cells = np.tile(geo.face_cell, 3)
    lam, dlam = barycentric(mesh, cells, x)
    nodes = mesh.t[:, cells].T
    ph = (lam * geo.phi[nodes]).sum(axis=1)
    gph = np.linalg.norm(np.einsum("nk,nki->ni", geo.phi[nodes], dlam), axis=1)
    h = np.ptp(mesh.p[:, mesh.t[:, cells]], axis=1).max(axis=0)
    on = (np.abs(ph) <= 1e-9 * h * gph).reshape(3, nf).T & (geo.facets.T < 0)
    return np.where(on, 0.0, np.maximum(-ph.reshape(3, nf).T, 0.0))


def _graded(s: np.ndarray, r0: np.ndarray, r1: np.ndarray):
    """u(s) and du/ds on [0, 1] with √r uniform in s for r = r0 + u (r1 - r0): u = s(2σ₀
    + s d)/(2σ₀ + d), σ₀ = √r0, d = √r1 - √r0 (u = s when r is constant)."""
    s0, d = np.sqrt(r0)[:, None], (np.sqrt(r1) - np.sqrt(r0))[:, None]
    den = 2 * s0 + d
    flat = den <= 0                                       # r = 0 throughout: u = s
    s0, d, den = np.where(flat, 0.5, s0), np.where(flat, 0.0, d), np.where(flat, 1.0, den)
    return s * (2 * s0 + s * d) / den, (2 * s0 + 2 * s * d) / den


def face_rule(mesh, geo, n: int = FACE_POINTS) -> FaceRule:
    """The faces' rule of a 3D crack, graded at the front (module notes).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 6),) * 2, np.linspace(0, 1, 3))
    >>> g = crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.53)
    >>> R = face_rule(m, g)
    >>> round(float(R.weights.sum()), 12), bool(np.allclose(R.bary.sum(axis=0), 1.0))
    (0.53, True)
    """
    s, w = leggauss(n)
    s, w = (s + 1) / 2, w / 2
    S, T = (a.ravel() for a in np.meshgrid(s, s, indexing="ij"))
    Wst = np.outer(w, w).ravel()
    nf = geo.face_cell.size
    r = _front_distance(mesh, geo)
    order = np.argsort(r, axis=1, kind="stable")          # A (r least), B, C (r most)
    rA, rB, rC = (np.take_along_axis(r, order[:, k, None], axis=1)[:, 0] for k in range(3))
    span = rC - rA
    tau = np.where(span > 0, (rB - rA) / np.where(span > 0, span, 1.0), 0.0)
    eye = np.eye(3)[order]                                # (nf, 3, 3) bary of A, B, C
    bA, bB, bC = eye[:, 0], eye[:, 1], eye[:, 2]
    bD = (1 - tau)[:, None] * bA + tau[:, None] * bC      # on A C where r = r_B
    xs, ws, bs = [], [], []
    # two triangles split by the level line of r through B: apex A (r_A) and apex C
    # (r_C), each with r constant on the side B D opposite its apex
    for apex, r0 in ((bA, rA), (bC, rC)):
        U, dU = _graded(S[None], r0, rB)
        V_ = T[None]
        lam = (1 - U)[:, :, None] * apex[:, None] \
            + (U * (1 - V_))[:, :, None] * bB[:, None] + (U * V_)[:, :, None] * bD[:, None]
        E1, E2 = geo.faces.transpose(0, 2, 1) @ (bB - apex)[:, :, None], \
            geo.faces.transpose(0, 2, 1) @ (bD - apex)[:, :, None]
        area2 = np.linalg.norm(np.cross(E1[:, :, 0], E2[:, :, 0]), axis=1)
        xs.append(np.einsum("fqk,fki->fqi", lam, geo.faces))
        ws.append(area2[:, None] * Wst[None] * U * dU)
        bs.append(lam)
    x = np.concatenate(xs, axis=1)                        # (nf, 2 nq, 3)
    weights = np.concatenate(ws, axis=1)
    bary = np.concatenate(bs, axis=1)                     # (nf, 2 nq, 3)
    face = np.repeat(np.arange(nf), weights.shape[1])
    keep = weights.ravel() > 0                            # not on a triangle of no area
    return FaceRule(x.reshape(-1, 3)[keep].T.copy(), weights.ravel()[keep],
                    geo.face_cell[face[keep]], face[keep], bary.reshape(-1, 3)[keep].T.copy())


def face_functions_3d(geo, rule: FaceRule) -> sp.csr_matrix:
    """(n, ne) the multiplier functions N_e at the points of a :func:`face_rule`:
    linear on each face between its :func:`vertex_values`."""
    E = vertex_values(geo)
    nf = geo.face_cell.size
    return sum(sp.diags(rule.bary[k]) @ E[k * nf + rule.face] for k in range(3)).tocsr()


@dataclass(frozen=True)
class FaceTraction3D:
    """The traction the faces of a 3D crack carry, for the face term of
    :func:`skxfem.crack.sif3d.sif_3d`: at the points ``x`` (3, n) of a :func:`face_rule`
    with ``weights`` (n,) in ``cells`` (n,), ``traction`` (3, n) the interface traction
    r = σ·n (n into Ω⁺): the face of Ω⁻ carries t⁻ = r, that of Ω⁺ t⁺ = -r
    (:mod:`skxfem.crack.interaction`)."""

    x: np.ndarray
    weights: np.ndarray
    cells: np.ndarray
    traction: np.ndarray


def face_traction_3d(mesh, geo, traction: np.ndarray) -> FaceTraction3D:
    """The :class:`FaceTraction3D` of the interface traction ``traction`` (3, ne) at the
    crossings (the multipliers): r_h = Σ N_e r_e on the faces (:func:`face_functions_3d`
    on the points of :func:`face_rule`).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 6),) * 2, np.linspace(0, 1, 3))
    >>> g = crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.53)
    >>> r = np.array([[0.0], [-2.0], [0.0]]) * np.ones(g.edge_ids.size)   # a pressure 2
    >>> bool(np.allclose(face_traction_3d(m, g, r).traction[1], -2.0))
    True
    """
    traction = np.asarray(traction, float)
    ne = geo.edge_ids.size
    if traction.shape != (3, ne) or not np.all(np.isfinite(traction)):
        raise ValueError(f"traction must hold finite values of shape (3, {ne}) (one vector "
                         f"per point: crossed edge or node on the crack), got "
                         f"{traction.shape}")
    rule = face_rule(mesh, geo)
    r = (face_functions_3d(geo, rule) @ traction.T).T
    return FaceTraction3D(rule.points, rule.weights, rule.cells, r)
