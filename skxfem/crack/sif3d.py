r"""K_I, K_II, K_III along a 3D front by the domain interaction integral, and a 3D solve.

The 3D twin of :mod:`skxfem.crack.sif` and :mod:`skxfem.crack.solve`.

The integral at a point P of the front
--------------------------------------
The domain form of :mod:`skxfem.crack.interaction` over a volume A around the front,

.. math:: \int_A \bigl[\sigma_{ij}\, u^a_{i,1} + \sigma^a_{ij}\, u_{i,1}
          - \sigma_{ik}\, \varepsilon^a_{ik}\, \delta_{1j}\bigr]\, q_{,j}\, dV
          = \int_{\text{front}} I(s)\, q(s)\, ds ,

with the weight (the virtual extension of the front along e₁)

.. math:: q = q_r(r)\; \Lambda(s),\qquad
          \Lambda(s) = \cos^2\frac{\pi s}{2L}\ (|s| < L),\quad s = e_3(P)\cdot(x - P),

q_r the radial weight in the plane normal to the front (1 inside ρR, 0 beyond R, the
smooth step 3t² - 2t³ of t = (R - r)/(R - ρR) between) and Λ the bump along the front,
of half-width L.  Both are C¹ (:func:`_radial`, :func:`_bump`): the quadrature of cells
that a kink of ∇q would cross is then accurate, which the face term of a closed crack
needs (a linear cone and hat left |K_I| ≈ 4.5e-3 σ√(πa) on a crack pressed shut at
n = 11 cells, the C¹ weights 0.9e-3).  The local I(P) is the integral divided by
∫ Λ ds along the front (Gauss points on its segments): the **smoothing** is this
bump-weighted mean of I(s) over |s| < L, exact for an I linear along the front.
Then K_I = E′I_I/2, K_II = E′I_II/2, K_III = μ I_III
(:func:`skxfem.crack.interaction.sif_from_interaction`, E′ = E/(1 - ν²)).

**Coordinates of the auxiliary fields.**  At every quadrature point the Williams fields
(:mod:`skxfem.crack.williams`, 3D: mode III along e₃) are written in the point's own
front frame and polar coordinates r = √(x₁² + ψ_h²), θ = atan2(ψ_h, x₁) (±π on the faces
by the side of the point's sub-tetrahedron), x₁ the signed distance to the front in the
crack's plane (:func:`front_coordinate`: the distance of the point's projection on
{ψ_h = 0} to the P1 front's segments, negative behind it), e₂ = ∇ψ_h/|∇ψ_h|, e₁ the P1
interpolant of nodal directions made normal to e₂, e₃ = e₁ × e₂.  The nodal e₁ is
e₂ × t, t the tangent of the front at the node's nearest place, fitted over a few cells
(:func:`fitted_frame`, :func:`skxfem.crack.geometry3d.front_fit`): a smooth field, whose
lines are the normal lines of the front (the gradient of the P1 φ_h turns from cell to
cell by up to h/ρ_f, ρ_f the front's radius of curvature).  The same e₁ is the extension
direction, and q_r is a function of this r.

**Why x₁ and not φ_h.**  The interaction integral of a uniform state (σ constant, the
faces carrying its traction) vanishes exactly in the curvilinear coordinates below, with
the curvature terms (checked by an independent quadrature of the same integrand on the
exact penny: 1e-5 of its domain and face terms, each about 0.53 σ√(πa)).  With x₁ = φ_h,
the P1 interpolant of φ = ρ - a, it did not: on the penny pressed shut
(:func:`skxfem.studies.cracks3d.pressed_penny`, a = 0.55, sif_radius 0.25) the exact
state (u = (νx, νy, -z)σ/E, the faces carrying σ) left |K_I| = 2.6e-3, 1.3e-3, 3.6e-3
σ√(πa) at h = 0.2, 0.125, 0.1, not falling with h.  ∇φ_h·e₁ ranges over 0.72 to 1.15
from cell to cell there (0.97 to 0.98 on average, by domain or by face): the Williams
fields' planar derivatives are then not those of the field they define, by an amount
that the domain and the face terms do not share (each off the exact-geometry value by
0.1 to 0.6 %, their sum by 0.2 to 0.7 %; more quadrature points changed it by 0.3e-3).
With the distance x₁ the same exact state gives 3.4e-3, 0.76e-3, 1.0e-3.  Part of it is
quadrature, part not: with 10³ to 14³ points on every piece near the front and in the
branch tube (and 10 to 16 on the almost-polar rules' directions) |K_II| falls to 1e-5
but |K_I| stays at about 1.7e-3, 0.8 to 1.0e-3, 0.55e-3 (falling as h^1.6), and the
pieces' rule counts move it by ±0.4e-3 at h = 0.125 without converging (the weight q is
C¹ only; a C² q, the step 10t³ - 15t⁴ + 6t⁵ and cos⁴, converged with the points to the
same values).  The solved penny pressed shut gives the exact state's K since the
stiffness's near rule is graded (:data:`skxfem.crack.quadrature3d.NEAR_GRADING`):
3.6e-3, 0.70e-3, 1.08e-3 with the branch tube on the collapsed 4³ rule, 1.9e-3,
0.81e-3, 0.69e-3 on the symmetric rule of order 8 (:data:`TUBE_ORDER`, 45 points; the
exact state 1.8e-3, 0.81e-3, 0.71e-3), which also holds the through crack pressed shut
within 0.86e-3 (``benchmarks/crack_radius3d.py --parts pressed``, n = 21, 31, the front
at 0.49, 0.5, 0.51: 1.1e-3 on 4³) and costs the straight front a little (the Williams
slab, n = 11, 21, 31: worst 0.94, 0.52, 0.80 % against 0.86, 0.45, 0.64 %).  The open
penny (:mod:`skxfem.studies.cracks3d`) stays within 0.3 % of before (h = 0.2: median
1.0010, worst 1.0259; h = 0.1: 0.9917, 0.9904).

**Curvature terms.**  In these curvilinear coordinates (x₁ along e₁, x₂ = ψ,
x₃ along the front, its metric h₃ = 1 + κx₁ with κ = 1/ρ_f the front's curvature in the
crack's plane, > 0 when it bends away from e₁) the plane Williams fields are neither in
equilibrium nor compatible: div σᵃ = (κ/h₃)(σᵃ₁₁ - σᵃ₃₃, σᵃ₁₂, 2σᵃ₁₃) and the true
gradient of uᵃ has the extra components (κ/h₃)(-uᵃ₃ e₁⊗e₃ + uᵃ₁ e₃⊗e₃), while εᵃ
= C⁻¹σᵃ stays the plane one.  The divergence of the integrand then leaves, per unit q
along e₁ (Gosz & Moran 2002, for a planar crack),

.. math:: \frac{\kappa}{h_3}\bigl[\sigma_{33}\, u^a_{1,1} - \sigma_{13}\, u^a_{3,1}
          + (\sigma^a_{11} - \sigma^a_{33})\, u_{1,1} + \sigma^a_{12}\, u_{2,1}
          + 2\sigma^a_{13}\, u_{3,1}\bigr]

(:func:`_curvature_integrand`; the κ² terms of the true gradient cancel against those of
∂ⱼe₁ along the front), added with weight q.  They are of order κR against the integral
(6 % on a penny at R = 0.68 a); the terms of a varying κ along the front and of a curved
crack surface (∇e₂ ≠ 0) are left out.  κ at each front point is the fitted one.

The integrand holds σ uᵃ,₁ ∼ 1/r near the front, integrated by the
almost-polar rules of the front cells.  Faces that carry a traction (a contact or a tie
on them, :mod:`skxfem.crack.faces3d`) add the face term -∫ tᵢ uᵃᵢ,₁ q dS on both faces
(:mod:`skxfem.crack.interaction`), on the faces' rule graded at the front; free faces
none.  The free surfaces the front meets add a boundary term when the domain reaches them
(K is reported there but is only trusted where the domain stays clear of them: a bump's
width inside for a front square to them, farther for one that meets them obliquely,
:func:`domain_reach`, :func:`end_reach`).

>>> from skfem import MeshTet1
>>> from skxfem.crack.geometry3d import crack_geometry_3d
>>> from skxfem.crack.space3d import crack_space_3d
>>> from skxfem.fem.material import Material
>>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 8),) * 2, np.linspace(0, 1, 3))
>>> V = crack_space_3d(m, crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.5))
>>> K = sif_3d(V, np.zeros(V.N), Material(1.0, 0.3), np.array([[0.5], [0.5], [0.5]]))
>>> np.round(K, 12).tolist()                        # no field, no K
[[0.0, 0.0, 0.0]]
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.polynomial.legendre import leggauss
from scipy.sparse.csgraph import connected_components

from ..fem.loads import force_field
from ..fem.material import Material
from .branch import side_angle
from .frame import TipFrame, tip_frame
from .geometry import nearest_on_segments
from .geometry3d import (
    barycentric,
    cell_gradients,
    chain_places,
    crack_geometry_3d,
    front_chains,
    front_fit,
    front_offset,
    runs,
)
from .interaction import sif_from_interaction
from .radius import DOMAIN_FRACTION, check_radius
from .space3d import (
    body_load,
    crack_space_3d,
    field_at,
    front_distance,
    nodal_scaling,
    point_values,
    rules,
    stiffness,
    supported_dofs,
    traction_load,
    virtual_field,
)
from .williams import near_tip_modes

__all__ = ["DEFAULT_RADIUS", "MIN_RADIUS", "DEFAULT_LENGTH", "TUBE_ORDER", "FACE_RULES",
           "default_radius_3d",
           "front_points", "front_frame", "fitted_frame", "front_coordinate", "front_sizes",
           "END_SURFACE_TURN", "END_SURFACE_SPREAD", "END_CROSSING", "boundary_samples",
           "end_surfaces",
           "surface_reach", "boundary_reach", "end_reach", "other_fronts", "FACING",
           "check_radius",
           "domain_reach", "sif_3d", "CrackSolution3D", "solve_crack_3d"]

DEFAULT_RADIUS = 3.0
"""The default radius R of the radial cone with topological enrichment, in front-cell
sizes across the front (:func:`front_sizes`)."""

MIN_RADIUS = 1.5
"""With geometric enrichment the default R is
:data:`~skxfem.crack.radius.DOMAIN_FRACTION` r_e (the domain inside the enriched zone, as
in 2D), and at least MIN_RADIUS front-cell sizes.  Measured on the penny
(:mod:`skxfem.studies.cracks3d`, h = a/5, r_e = 0.5 a): R = 1.65 h (0.75 r_e) K_I/K
1.000 to 1.019; R = 3 h (beyond r_e) 0.982 to 1.035, 4 h 0.957 to 1.050; r_e = 0.3 a:
R = 1.5 h 0.985 to 1.025, 3 h 0.947 to 1.047, 1 h 1.04 to 1.06 (too few cells)."""

TUBE_ORDER = 8
"""The order of the symmetric rule (:func:`skxfem.fem.quadrature.simplex_points`, 45
points) on the cells of the branch tube away from the front cells in :func:`sif_3d`
(:func:`skxfem.crack.space3d.rules`).  The collapsed 4³ rule there (64 points, exact to
degree 5) left a through crack pressed shut (:func:`skxfem.studies.cracks3d.pressed_slab`,
K = 0) at |K| up to 1.1e-3 p√(πa) (n = 31, front at x = 0.51, r_e = 4 h), the penny
pressed shut at 1.08e-3 (h = 0.1); on this rule 1.6e-4 and 0.69e-3 (module notes)."""

FACE_RULES = {"grading": ((0.3, 8), (0.1, 12)), "tube": ((0.5, 6),)}
"""The rules of :func:`sif_3d` when the crack's faces carry a traction (a contact or a
tie: ``faces`` given), for :func:`skxfem.crack.space3d.rules`: the pieces near the front
graded by their distance to it as the stiffness's first steps
(:data:`skxfem.crack.quadrature3d.NEAR_GRADING`; else 5³ points each), and the branch
tube's cells within half their longest edge of the front on the collapsed 6³ rule
(``tube``; else the symmetric rule of :data:`TUBE_ORDER`).  A crack pressed shut has
K = 0 only as the difference of the domain and face terms, each about 0.5 p√(πa): the
integral must hold each to 1e-3 of it, on every mesh.  Measured on the exact state of
:func:`skxfem.studies.cracks3d.pressed_slab` (σ = -p e_y ⊗ e_y, the faces carrying p),
the front at x = 0.40 to 0.60 by 0.0125 (17 places): the worst |K| over p√(πa) at
n = 7, 9, 11, 13 was 1.61e-3, 1.51e-3, 1.11e-3, 0.84e-3 on a free crack's rules, is
0.77e-3, 0.72e-3, 0.78e-3, 0.72e-3 on these (the pieces' grading alone: 1.15e-3 at
n = 7; the tube's alone: 1.13e-3 at n = 9); solved, 0.86e-3, 0.71e-3, 0.78e-3, 0.80e-3,
0.61e-3, 0.51e-3, 0.39e-3 at n = 7, 9, 11, 13, 15, 21, 31 (1.64e-3 at n = 7, x = 0.495
before, with the stiffness's closest steps).  The points of K: 59 000 -> 268 000
(n = 11), 72 000 -> 424 000 (n = 21), 298 000 -> 826 000 (the pressed penny at
h = 0.2), K's time 0.13 -> 0.63 s, 0.14 -> 1.15 s, 0.94 -> 2.68 s, against a contact
solve of 0.5 to 10 s.  Finer steps ((0.5, 8), (0.3, 10), (0.1, 16) and a tube of one
edge) held the slab alike (0.74e-3) for twice the points; on the penny pressed shut at
h = 0.2 (2.75 cells per radius, R = 0.25) no rule is reliable: its exact state gave
|K_I| 1.85e-3, 2.56e-3, 1.07e-3 p√(πa) on the free rules, these and the finer ones
(0.81e-3, 0.73e-3, 1.02e-3 at h = 0.125; solved 1.97e-3, 2.71e-3, 1.08e-3 at h = 0.2
and 0.81e-3, 0.82e-3, 1.13e-3 at h = 0.125), the P1 front's own error (module notes).
A free crack keeps the rules above: its K is the domain term alone, and 1e-3 of that
is 1e-3 of K."""

DEFAULT_LENGTH = 1.5
"""The default half-width L of the bump along the front, in front-cell sizes along it."""

POINT_CHUNK = 8192
"""Quadrature points per chunk of :func:`sif_3d`'s fields (:func:`_point_chunks`)."""

FACING = 1.5
"""A vertex of a front's own chain faces a point P of it (:func:`other_fronts`) when
its arc from P along the chain exceeds FACING times their distance: on a circle, the
points more than 171° round; never on a straight front, nor round a right angle (√2)."""


def front_sizes(space) -> tuple[float, float]:
    """(across, along): the mean size of the front cells across the front (the largest
    distance √(φ² + ψ²) of their nodes to it) and along it (the extent of their nodes
    along e₃ of their frame).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> from skxfem.crack.space3d import crack_space_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 11),) * 2, np.linspace(0, 1, 3))
    >>> V = crack_space_3d(m, crack_geometry_3d(m, m.p[1] - 0.55, m.p[0] - 0.55))
    >>> [round(v, 3) for v in front_sizes(V)]
    [0.071, 0.5]
    """
    mesh, geo = space.mesh, space.geometry
    nodes = mesh.t[:, geo.front_cells]
    across = np.hypot(geo.phi[nodes], geo.psi[nodes]).max(axis=0).mean()
    e3 = front_frame(space, mesh.p[:, nodes].mean(axis=1)).e3          # (3, nf)
    along = np.ptp(np.einsum("in,ikn->kn", e3, mesh.p[:, nodes]), axis=0).mean()
    return float(across), float(along)


def front_points(space, spacing: float | None = None, chains: list | None = None
                 ) -> np.ndarray:
    """Points (3, m) along the front where K is computed: each chain of
    :func:`skxfem.crack.geometry3d.front_chains` (``chains``, default: built here) sampled
    at equal arc lengths about ``spacing`` apart (default: the mean size of the front
    cells), the ends of an open chain excluded."""
    h = front_sizes(space)[1] if spacing is None else float(spacing)
    out = []
    for pts, closed in front_chains(space.geometry) if chains is None else chains:
        if closed:
            pts = np.hstack([pts, pts[:, :1]])
        seg = np.linalg.norm(np.diff(pts, axis=1), axis=0)
        s = np.concatenate([[0.0], np.cumsum(seg)])
        total = s[-1]
        m = max(1, int(round(total / h)))
        at = (np.arange(m) + (0.0 if closed else 0.5)) * total / m
        out.append(np.stack([np.interp(at, s, pts[k]) for k in range(3)]))
    return np.hstack(out)


def front_frame(space, points: np.ndarray) -> TipFrame:
    """The frames (vectors (3, m)) at points (3, m) near the front, from ∇φ_h and ∇ψ_h in
    the front cell of the nearest front segment."""
    geo, mesh = space.geometry, space.mesh
    A, B = geo.segments[0], geo.segments[1]
    dist = nearest_on_segments(A[:, None], (B - A)[:, None], points[:, :, None])[2]
    cells = geo.segment_cell[np.argmin(dist, axis=1)]
    return tip_frame(cell_gradients(mesh, geo.phi, cells), cell_gradients(mesh, geo.psi, cells))


END_SURFACE_TURN = 30.0
"""The largest angle (degrees) between the normals of two boundary facets that share an
edge on one smooth surface (:func:`end_surfaces`): the faces of a cube meet at 90°, a
curved surface meshed at a few cells per radius turns by under 20° from facet to facet."""

END_SURFACE_SPREAD = 60.0
"""The largest angle (degrees) between a facet's normal and the normal where the front
meets the surface, for the facet to count as part of that end surface
(:func:`end_surfaces`): it stops the surface at the far side of a round bar, which is a
side wall for the points across it."""


END_CROSSING = 0.2
"""The least cosine of the angle between the front, leaving the body at its end, and the
outward normal of a facet the end lies on, for that facet to be a surface the front
ends on (:func:`end_surfaces`; the front within 78° of its normal): a front running
along a face (its end on the edge where that face meets the one it crosses) does not
end on it, and that face stays a side wall its domain is clipped to."""


def boundary_samples(mesh) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The boundary facets' samples (3, 7 nf) (their vertices, edge midpoints and
    centroids), the outward normals (3, nf) and the boundary facets (nf,) (the samples
    are facet-major in blocks of nf: sample j of facet k is column j nf + k)."""
    from .space3d import outward_normals
    f = mesh.boundary_facets()
    a, b, c = (mesh.p[:, mesh.facets[k, f]] for k in range(3))
    samples = np.hstack([a, b, c, (a + b) / 2, (b + c) / 2, (a + c) / 2, (a + b + c) / 3])
    return samples, outward_normals(mesh, f), f


def end_surfaces(mesh, chains: list) -> np.ndarray:
    """(nf,) whether each boundary facet (``mesh.boundary_facets()``) lies on a surface
    that an open chain of ``chains`` (:func:`~skxfem.crack.geometry3d.front_chains`) ends
    on: the facets that hold a chain's end and that the front crosses there
    (:data:`END_CROSSING`), and those reached from them across edges where the normal
    turns by under :data:`END_SURFACE_TURN` degrees, their normal within
    :data:`END_SURFACE_SPREAD` degrees of the end's.  The surface is the one the front
    ends on whatever its angle to the front (a through crack whose front is tilted in
    its plane meets the sides obliquely); a closed front ends on none.

    >>> from skfem import MeshTet1
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 3),) * 3)
    >>> chain = np.array([[0.5, 0.7], [0.0, 1.0], [0.5, 0.5]])    # y = 0 to y = 1
    >>> ends = end_surfaces(m, [(chain, False)])
    >>> from skxfem.crack.space3d import outward_normals
    >>> n = outward_normals(m, m.boundary_facets())
    >>> np.array_equal(ends, np.abs(n[1]) > 0.5)             # the faces y = 0 and y = 1
    True
    """
    samples, n, f = boundary_samples(mesh)
    out = np.zeros(f.size, dtype=bool)
    E = [pts[:, [0, -1]] for pts, closed in chains if not closed]
    if not E:
        return out
    E = np.hstack(E)
    T = np.hstack([np.stack([pts[:, 0] - pts[:, 1], pts[:, -1] - pts[:, -2]], axis=1)
                   for pts, closed in chains if not closed])
    T = T / np.linalg.norm(T, axis=0)                       # outward along the front
    # the facets each end lies on: within 1e-9 of the mesh's size of the facet's plane
    # and inside it (its barycentric coordinates ≥ -1e-9)
    a, b, c = (mesh.p[:, mesh.facets[k, f]] for k in range(3))
    size = np.ptp(mesh.p, axis=1).max()
    u, v = b - a, c - a
    uu, uv, vv = (u * u).sum(0), (u * v).sum(0), (v * v).sum(0)
    det = uu * vv - uv * uv
    seeds = np.zeros(f.size, dtype=bool)
    for k in range(E.shape[1]):
        w = E[:, k, None] - a
        off = np.abs((w * n).sum(axis=0))
        wu, wv = (w * u).sum(0), (w * v).sum(0)
        l1, l2 = (vv * wu - uv * wv) / det, (uu * wv - uv * wu) / det
        on = ((off <= 1e-9 * size) & (l1 >= -1e-9) & (l2 >= -1e-9) & (l1 + l2 <= 1 + 1e-9)
              & ((n * T[:, k, None]).sum(axis=0) >= END_CROSSING))
        seeds |= on
    # boundary facets sharing an edge, the normal turning by under END_SURFACE_TURN
    edges = mesh.f2e[:, f]                                     # (3, nf)
    order = np.argsort(edges.ravel(), kind="stable")
    key = edges.ravel()[order]
    pair = np.flatnonzero(key[1:] == key[:-1])
    i, j = order[pair] % f.size, order[pair + 1] % f.size
    smooth = (n[:, i] * n[:, j]).sum(axis=0) >= np.cos(np.radians(END_SURFACE_TURN))
    spread = np.cos(np.radians(END_SURFACE_SPREAD))
    for s in np.flatnonzero(seeds):
        near = (n * n[:, s, None]).sum(axis=0) >= spread
        keep = smooth & near[i] & near[j]
        g = sp.coo_matrix((np.ones(keep.sum()), (i[keep], j[keep])), shape=(f.size,) * 2)
        _, label = connected_components(g, directed=False)
        out |= label == label[s]
    return out


def surface_reach(samples: np.ndarray, points: np.ndarray, e3: np.ndarray,
                  length: float) -> np.ndarray:
    """For each point P (3, m) with its tangent e₃ (3, m): the least distance, in the
    plane normal to e₃, from P to the ``samples`` (3, k) within ``length`` of that plane;
    inf where none is."""
    out = np.empty(points.shape[1])
    for k in range(points.shape[1]):
        d = samples - points[:, k, None]
        along = e3[:, k] @ d
        radial = np.sqrt(np.maximum((d * d).sum(axis=0) - along ** 2, 0.0))
        use = np.abs(along) <= length
        out[k] = radial[use].min() if use.any() else np.inf
    return out


def boundary_reach(mesh, points: np.ndarray, e3: np.ndarray, length: float,
                   chains: list | None = None) -> np.ndarray:
    """For each front point P (3, m) with its tangent e₃ (3, m): the distance, in the plane
    normal to the front, from P to the boundary facets within ``length`` of that plane
    (sampled at their vertices, edge midpoints and centroids), leaving out the surfaces
    the front ends on (:func:`end_surfaces` of the open chains of ``chains``; None: none
    left out).  The radial cone is clipped to it, so that q vanishes on the rest of the
    boundary (the surfaces the front ends on: :func:`domain_reach`).

    >>> from skfem import MeshTet1
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 5),) * 3)
    >>> boundary_reach(m, np.array([[0.5], [0.3], [0.5]]), np.array([[0.0], [0.0], [1.0]]),
    ...                0.25).round(12).tolist()
    [0.3]
    """
    samples = boundary_samples(mesh)[0]
    if chains is not None:
        samples = samples[:, ~np.tile(end_surfaces(mesh, chains), 7)]
    return surface_reach(samples, points, e3, length)


def end_reach(mesh, points: np.ndarray, e3: np.ndarray, length: float,
              chains: list) -> np.ndarray:
    """For each front point P (3, m) with its tangent e₃ (3, m): the distance, in the plane
    normal to the front, from P to the surfaces the front ends on (:func:`end_surfaces`
    of ``chains``, sampled as in :func:`boundary_reach`) within ``length`` of that plane;
    inf where none is (a relative margin of 1e-9 inside).  A domain of radius R and
    half-width ``length`` reaches such a surface where it is under R: a front square to
    the surface, when P is within ``length`` of the front's end; a front meeting it
    obliquely, farther (the domain's cylinder cuts the surface a distance R tan α past
    the end, α the angle between the front and the surface's normal).

    >>> from skfem import MeshTet1
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 5),) * 3)
    >>> chain = np.array([[0.5, 0.5], [0.0, 1.0], [0.5, 0.5]])      # along y
    >>> P = np.array([[0.5, 0.5], [0.1, 0.5], [0.5, 0.5]])
    >>> e3 = np.array([[0.0, 0.0], [1.0, 1.0], [0.0, 0.0]])
    >>> end_reach(m, P, e3, 0.25, [(chain, False)]).tolist()      # y = 0 within 0.25
    [0.0, inf]
    """
    samples, _, _ = boundary_samples(mesh)
    # a sample at the bump's edge (|s| = length, where Λ = 0) is not in the domain
    return surface_reach(samples[:, np.tile(end_surfaces(mesh, chains), 7)], points, e3,
                         length * (1 - 1e-9))


def _rotate(R: np.ndarray, T: np.ndarray) -> np.ndarray:
    """R T Rᵀ of tensors T (3, 3, n) in per-point frames R (3, 3, n) (rows e₁, e₂, e₃):
    their components in the frames.  T is made contiguous first: the gradients come
    point by point ((n, 3, 3) in memory), on which einsum is ten times slower."""
    T = np.ascontiguousarray(T)
    return np.einsum("ain,ibn->abn", R, np.einsum("ijn,bjn->ibn", T, R))


def _contract(S: np.ndarray, T: np.ndarray, G: np.ndarray) -> np.ndarray:
    """Σ_ijk S_ij T_ik G_jk of tensors (3, 3, n)."""
    return np.einsum("ijn,ikn,jkn->n", S, T, G)


def fitted_frame(space, points: np.ndarray, spacing: float,
                 chains: list | None = None) -> tuple[TipFrame, np.ndarray]:
    """The frames at ``points`` (3, m) near the front with e₃ along the front's fitted
    tangent (:func:`skxfem.crack.geometry3d.front_fit` over ± ``spacing``), e₂ = n of
    :func:`front_frame` and e₁ = e₂ × e₃, and the front's curvature κ (m,) in the plane
    normal to e₂, positive when it bends away from e₁ (a penny's front: 1/a).  The
    tangent of the nearest front cell's level sets (:func:`front_frame`) turns with the
    P1 chords of a curved front, by up to h/ρ; the fit does not.  ``chains``: the
    front's :func:`~skxfem.crack.geometry3d.front_chains` if at hand."""
    cell = front_frame(space, points)
    t, kvec = front_fit(space.geometry, points, spacing, chains)
    e3 = t * np.where((t * cell.e3).sum(axis=0) < 0, -1.0, 1.0)
    e1 = np.cross(cell.e2, e3, axis=0)
    e1 /= np.linalg.norm(e1, axis=0)
    frame = TipFrame(e1, cell.e2, np.cross(e1, cell.e2, axis=0))
    return frame, -(kvec * e1).sum(axis=0)


def _nodal_directions(space, cells: np.ndarray, spacing: float, chains=None) -> np.ndarray:
    """(nverts, 3) e₁ at the nodes of ``cells`` (zero at the other nodes): e₂ × e₃ with
    e₂ the mean of the cells' n around each node and e₃ the front's fitted tangent at
    its nearest place (:func:`fitted_frame`), so that the direction field is smooth
    and the normal lines of a curved front are straight lines along it."""
    mesh, geo = space.mesh, space.geometry
    gphi, gpsi = (cell_gradients(mesh, f, cells) for f in (geo.phi, geo.psi))   # (3, nc)
    n = gpsi / np.linalg.norm(gpsi, axis=0)
    ahead = gphi - (gphi * n).sum(axis=0) * n             # ∇φ_h's part in the crack's plane
    size = np.linalg.norm(ahead, axis=0)
    # a cell where ∇φ_h has none (a centre crack's φ = |t·(x - c)| - a at its kink, far
    # from both fronts) gives no sign: its nodes take it from their other cells
    ahead = np.where(size > 1e-12 * np.linalg.norm(gphi, axis=0), ahead / np.where(
        size > 0, size, 1.0), 0.0)
    e1, e2 = np.zeros((mesh.p.shape[1], 3)), np.zeros((mesh.p.shape[1], 3))
    for k in range(4):                                    # the 4 nodes of a cell
        np.add.at(e1, mesh.t[k, cells], ahead.T)
        np.add.at(e2, mesh.t[k, cells], n.T)
    nodes = np.unique(mesh.t[:, cells])
    t, _ = front_fit(geo, mesh.p[:, nodes], spacing, chains)
    d = np.cross(e2[nodes].T, t, axis=0)
    d *= np.where((d * e1[nodes].T).sum(axis=0) < 0, -1.0, 1.0) / np.linalg.norm(d, axis=0)
    out = np.zeros((mesh.p.shape[1], 3))
    out[nodes] = d.T
    return out


def _bump(s: np.ndarray, L: float) -> tuple[np.ndarray, np.ndarray]:
    """Λ(s) = cos²(πs/2L) for |s| < L, else 0, and Λ′(s) (module notes)."""
    inside = np.abs(s) < L
    c = np.pi / (2 * L)
    return (np.where(inside, np.cos(c * s) ** 2, 0.0),
            np.where(inside, -c * np.sin(2 * c * s), 0.0))


def _radial(r: np.ndarray, R: float, inner: float) -> tuple[np.ndarray, np.ndarray]:
    """q_r(r): 1 inside ``inner``, 0 beyond R, the smooth step 3t² - 2t³ of
    t = (R - r)/(R - inner) between, and q_r′(r)."""
    t = np.clip((R - r) / (R - inner), 0.0, 1.0)
    return t * t * (3 - 2 * t), -6 * t * (1 - t) / (R - inner)


def other_fronts(geo, P: np.ndarray, chains: list | None = None) -> np.ndarray:
    """The distance (m,) from each point P (3, m) of the front to the nearest point of
    another front or of a part of its own front that faces it; inf where there is none.
    Another front is another chain of :func:`skxfem.crack.geometry3d.front_chains`
    (the second front of a centre crack); a facing part is a vertex Q of P's own chain
    whose arc from P along the chain is more than :data:`FACING` times the straight
    distance |Q - P| (the far side of a loop, the other arm of a U; a straight front has
    none, a circle only its points more than 171° round).  ``chains``: the front's
    chains if at hand (default: built here).

    The far side of a closed front is where the nearest front point, whose polar
    coordinates the branch functions and the auxiliary fields take, jumps across the
    crack: an ellipse of semi-axes 0.35 and 0.25 in the unit cube (18³ cells, the minor
    axis 4.5 cells) gave K_I 0.85-0.87 at the minor axis' ends (0.75 with the domain
    kept to a third of the 0.5 across, as here) and an outlier 0.58 between 0.86s.

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 8),) * 2, np.linspace(0, 1, 3))
    >>> g = crack_geometry_3d(m, m.p[1] - 0.5, np.abs(m.p[0] - 0.5) - 0.2)   # two fronts
    >>> other_fronts(g, np.array([[0.3], [0.5], [0.5]])).round(12).tolist()
    [0.4]
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 17),) * 3)
    >>> ell = lambda x: np.hypot((x[0] - 0.5) / 0.35, (x[1] - 0.5) / 0.25) - 1
    >>> g = crack_geometry_3d(m, m.p[2] - 0.53, ell(m.p))         # the minor axis' end
    >>> other_fronts(g, np.array([[0.5], [0.25], [0.53]])).round(2).tolist()
    [0.5]
    """
    chains = front_chains(geo) if chains is None else chains
    if not chains:
        return np.full(P.shape[1], np.inf)
    dist = np.stack([np.linalg.norm(c[:, None] - P[:, :, None], axis=0).min(axis=1)
                     for c, _ in chains])                # (nchains, m)
    own = np.argmin(dist, axis=0)
    dist[own, np.arange(P.shape[1])] = np.inf
    out = dist.min(axis=0)
    for k, (c, closed) in enumerate(chains):             # the facing parts of one's own
        at = np.flatnonzero(own == k)
        if at.size == 0 or c.shape[1] < 3:
            continue
        c, s, sP, _, _ = chain_places(c, closed, P[:, at])     # P's arc length
        d = np.linalg.norm(c[:, None] - P[:, at, None], axis=0)    # (len(at), nv)
        arc = np.abs(s[None] - sP[:, None])
        if closed:
            arc = np.minimum(arc, s[-1] - arc)
        facing = np.where(arc > FACING * d, d, np.inf).min(axis=1)
        out[at] = np.minimum(out[at], facing)
    return out


def domain_reach(space, P: np.ndarray, e3: np.ndarray, kappa: np.ndarray, length: float,
                 chains: list | None = None, h: float | None = None) -> np.ndarray:
    """How far (m,) the interaction domain of each front point P (3, m), tangent e₃
    (3, m), curvature κ (m,) (:func:`fitted_frame`), can reach: the distance to the
    boundary in the plane normal to the front (:func:`boundary_reach` within the bump's
    half-width ``length``), a third of the distance to another front or to a part of
    its own that faces it (:func:`other_fronts`) and half the radius of curvature
    1/(2|κ|).  :func:`sif_3d` clips its radius R to it.

    The surfaces the front ends on (:func:`end_surfaces`) clip it too where that leaves
    a front cell's size ``h`` of room or more (default :func:`front_sizes`; the domain
    then stays off them, as off any wall, and the point is interior); where it would
    leave less (the points near the end, all of them for a front square to the
    surface), they do not, and the domain is clipped to the body there
    (:func:`end_reach`: such a point is not interior).  A front meeting them obliquely
    had its points within about R tan α + ``length`` of its ends without K (α the angle
    from square; the test was |n·e₃| ≤ 0.9, α over 26°): at slope 0.49 (α = 26.1°) on
    the cube of ``benchmarks/crack_solve.py``, n = 10, 4 of 8 points.

    The curvature keeps a curved front's domain off its centre of curvature, where the
    stretch h₃ = 1 + κ x₁ along the front vanishes: a penny of radius a = 0.2 in the
    unit cube (clamped below, pulled above) gave K_I/2σ√(a/π) = 1.05-1.08 with R ≤ 2a/3
    at n = 12, 16, 24, but 0.63-0.66 with R = a, and its default R (0.25, 0.20, 0.13)
    gave a median 0.80 and 0.77 at n = 12 and 16 (1.07 at n = 24, where R < 2a/3)."""
    chains = front_chains(space.geometry) if chains is None else chains
    h = front_sizes(space)[0] if h is None else float(h)
    samples, _, _ = boundary_samples(space.mesh)
    ends = np.tile(end_surfaces(space.mesh, chains), 7)
    walls, at_ends = (surface_reach(samples[:, k], P, e3, length) for k in (~ends, ends))
    return np.minimum.reduce([walls, np.where(at_ends >= h, at_ends, np.inf),
                              other_fronts(space.geometry, P, chains) / 3,
                              0.5 / np.maximum(np.abs(kappa), 1e-300)])


def _along(x: np.ndarray, P: np.ndarray, e3: np.ndarray, R: float):
    """s = e₃·(x - P) at points x (3, ...) and whether they lie within 2R of the line
    through P along e₃ (the part of the front near P: another front, or the far side of
    a closed one, is left out of P's domain)."""
    d = x - P.reshape((3,) + (1,) * (x.ndim - 1))
    s = np.einsum("i,i...->...", e3, d)
    rho2 = (d * d).sum(axis=0) - s * s
    return s, rho2 < (2 * R) ** 2


def _point_chunks(batches):
    """The points of quadrature ``batches`` (:func:`skxfem.crack.space3d.rules`) of
    nonzero weight, in order, as (cells (n,), x (3, n), w (n,), side (n,)) of at most
    :data:`POINT_CHUNK` points: every point's terms are its own, and a chunk's arrays stay
    in the processor's cache (at n = 24 on the benchmark cube, 1.5 million points)."""
    for c, x, w, side in batches:
        live = w != 0
        cc = np.broadcast_to(c[:, None], w.shape)[live]
        X, W, S = x[live].T, w[live], side[live]
        for k in range(0, W.size, POINT_CHUNK):
            sl = slice(k, k + POINT_CHUNK)
            yield cc[sl], X[:, sl], W[sl], S[sl]


def _hat_candidates(X: np.ndarray, P: np.ndarray, e3: np.ndarray, L: float,
                    size: float | None = None) -> np.ndarray:
    """(m, n) whether the points X (3, n) can lie within the bump of each front point P
    (3, m) with its tangent e₃ (3, m): |s| < L by s = e₃·x - e₃·P, one product for all
    (not :func:`_along`'s e₃·(x - P)), so with a margin of 1e-9 of L and of the
    coordinates' size (``size``: max |X| if at hand), above the difference of the two
    roundings."""
    s = e3.T @ X - (e3 * P).sum(axis=0)[:, None]
    size = np.abs(X).max(initial=0.0) if size is None else size
    margin = 1e-9 * (L + size + np.abs(P).max(initial=0.0))
    return np.abs(s) < L + margin


def _in_support(space, cells, X, R, P, e3, L):
    """Which points X (3, n) of ``cells`` can lie in the support of some q of
    :func:`sif_3d` (r < R and |s| < L for a front point; a relative margin of 1e-9): the
    others add nothing, and their fields are not computed.  Also, at the points kept
    only, their barycentric λ and ∇λ (:func:`skxfem.crack.geometry3d.barycentric`), for
    :func:`point_values`, and x₁ and ∇x₁ (:func:`front_coordinate`).  The bump's test
    comes first (:func:`_hat_candidates`): it needs only the points, the others their
    cells' values and the distance to the front."""
    mesh, geo = space.mesh, space.geometry
    on = np.flatnonzero(_hat_candidates(X, P, e3, L).any(axis=0))
    lam, dlam = barycentric(mesh, cells[on], X[:, on])
    nodes = mesh.t[:, cells[on]].T
    ph, ps = (lam * geo.phi[nodes]).sum(axis=1), (lam * geo.psi[nodes]).sum(axis=1)
    # |φ_h| ≤ 1.15 x₁ measured on the penny at h = 0.2 (P1 on a curved front): 1.5 is safe
    near = np.flatnonzero(np.hypot(ph, ps) < 1.5 * R)
    gph, gps = (np.einsum("nk,nki->in", f[nodes[near]], dlam[near])
                for f in (geo.phi, geo.psi))
    maybe = _x1_bound(space, cells[on[near]], X[:, on[near]], ps[near], gps) < R * (1 + 1e-9)
    near, gph, gps = near[maybe], gph[:, maybe], gps[:, maybe]
    x1, gx1 = front_coordinate(geo, X[:, on[near]], ps[near], gph, gps)
    inside = np.hypot(x1, ps[near]) < R * (1 + 1e-9)
    keep = np.zeros(X.shape[1], dtype=bool)
    keep[on[near[inside]]] = True
    kept = near[inside]
    return keep, lam[kept], dlam[kept], x1[inside], gx1[:, inside]


def _x1_bound(space, cells, X, psi, grad_psi) -> np.ndarray:
    """A lower bound (n,) of r = √(x₁² + ψ_h²) at points X (3, n) of ``cells`` with ψ_h
    ``psi`` and ∇ψ_h ``grad_psi`` (3, n) (:func:`front_coordinate`), made smaller by
    1e-9 of its size against rounding: x₁ ≥ d(c) - |y - c|, y the point's projection on
    {ψ_h = 0}, c that of its cell's centroid (the projection is affine in a cell), d the
    distance to the front (:func:`skxfem.crack.space3d.front_distance`, once per run of
    points of one cell).  The points it puts beyond R need no x₁."""
    mesh, geo = space.mesh, space.geometry
    if cells.size == 0:
        return np.zeros(0)
    first, inv = runs(cells)
    g2 = (grad_psi * grad_psi).sum(axis=0)
    y = X - psi / g2 * grad_psi
    uc = cells[first]
    c = (mesh.p[:, mesh.t[:, uc]].mean(axis=1)
         - geo.psi[mesh.t[:, uc]].mean(axis=0) / g2[first] * grad_psi[:, first])
    x1 = np.maximum(front_distance(geo, c)[inv] - np.linalg.norm(y - c[:, inv], axis=0), 0)
    return np.hypot(x1, psi) * (1 - 1e-9)


def _cell_r_bound(space, cells: np.ndarray) -> np.ndarray:
    """A lower bound (nc,) of r = √(x₁² + ψ_h²) over each of ``cells`` (as
    :func:`_x1_bound`, made smaller by 1e-9 of its size): x₁ ≥ d(c) - ρ, c the
    projection on {ψ_h = 0} of the cell's centroid, ρ the largest distance from c to the
    projections of its vertices (the projection is affine in a cell: the cell's image is
    their hull), |ψ_h| ≥ its least nodal |ψ| if they share a sign.  0 for a cell where
    ∇ψ_h = 0 (no projection).  The cells it puts beyond R hold no point of the domain."""
    mesh, geo = space.mesh, space.geometry
    out = np.zeros(cells.size)
    for k in range(0, cells.size, 4096):                  # blocks: nc × nseg distances
        cc = cells[k:k + 4096]
        psi, V = geo.psi[mesh.t[:, cc]], mesh.p[:, mesh.t[:, cc]]      # (4, nc), (3, 4, nc)
        g = cell_gradients(mesh, geo.psi, cc)
        g2 = (g * g).sum(axis=0)
        ok = g2 > 0
        Y = V - psi / np.where(ok, g2, 1.0) * g[:, None]  # the vertices' projections
        c = Y.mean(axis=1)
        rho = np.linalg.norm(Y - c[:, None], axis=0).max(axis=0)
        x1 = np.maximum(front_distance(geo, c) - rho, 0.0)
        least = np.where(psi.min(axis=0) > 0, psi.min(axis=0),
                         np.where(psi.max(axis=0) < 0, -psi.max(axis=0), 0.0))
        out[k:k + 4096] = np.where(ok, np.hypot(x1, least) * (1 - 1e-9), 0.0)
    return out


def _hat_integral(geo, P, e3, L, Rk):
    """∫ Λ ds along the front's segments near each point (m,) (:func:`_along` with the
    point's radius in ``Rk``)."""
    s, w = leggauss(6)
    s, w = (s + 1) / 2, w / 2
    A, B = geo.segments[0], geo.segments[1]
    x = A[:, :, None] + s * (B - A)[:, :, None]           # (3, nseg, 6)
    length = np.linalg.norm(B - A, axis=0)
    out = []
    for k in range(P.shape[1]):
        sk, near = _along(x, P[:, k], e3[:, k], Rk[k])
        out.append(((_bump(sk, L)[0] * near * w).sum(axis=1) * length).sum())
    return np.array(out)


def default_radius_3d(space, h: float) -> float:
    """The default radius R of the radial cone: :data:`MIN_RADIUS` h at least, and
    :data:`~skxfem.crack.radius.DOMAIN_FRACTION` r_e with geometric enrichment,
    :data:`DEFAULT_RADIUS` h with topological (``h`` the front cells' size across the
    front, :func:`front_sizes`).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> from skxfem.crack.space3d import crack_space_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 11),) * 2, np.linspace(0, 1, 3))
    >>> g = crack_geometry_3d(m, m.p[1] - 0.55, m.p[0] - 0.55)
    >>> default_radius_3d(crack_space_3d(m, g, "geometric", 0.4), 0.1)
    0.30000000000000004
    >>> default_radius_3d(crack_space_3d(m, g, "topological"), 0.1)
    0.30000000000000004
    """
    if space.enrichment == "geometric":
        return max(DOMAIN_FRACTION * space.radius, MIN_RADIUS * h)
    return DEFAULT_RADIUS * h


def front_coordinate(geo, x: np.ndarray, psi: np.ndarray, grad_phi: np.ndarray,
                     grad_psi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """x₁ (n,) at points x (3, n), the signed distance to the front in the crack's
    plane (module notes), and its gradient (3, n): the distance
    (:func:`skxfem.crack.geometry3d.front_offset`) of the point's projection on
    {ψ_h = 0} (along ∇ψ_h, by ψ_h/|∇ψ_h|) to the front, negative where the direction from
    the front to the projection is against ∇φ_h (behind the front; ψ_h ``psi``, ∇φ_h
    ``grad_phi`` and ∇ψ_h ``grad_psi`` (3, n) at the points).  The side is that of the
    projection, not the sign of φ_h at the point: they differ where the surface
    {φ_h = 0} leans on the crack's plane, and θ = atan2(ψ_h, x₁) would jump there.

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 2, np.linspace(0, 1, 3))
    >>> g = crack_geometry_3d(m, lambda x: x[1] - 0.5, lambda x: x[0] - 0.5)
    >>> x1, grad = front_coordinate(g, np.array([[0.2], [0.6], [0.3]]), np.array([0.1]),
    ...                             np.array([[1.0], [0.0], [0.0]]),
    ...                             np.array([[0.0], [1.0], [0.0]]))
    >>> x1.round(12).tolist(), (grad[:, 0] + 0.0).round(12).tolist()
    ([-0.3], [1.0, 0.0, 0.0])
    """
    g2 = (grad_psi * grad_psi).sum(axis=0)
    dist, unit = front_offset(geo, x - psi / g2 * grad_psi)
    sign = np.where((unit * grad_phi).sum(axis=0) < 0, -1.0, 1.0)
    return sign * dist, sign * unit


def _curvature_integrand(sl, gl, aux) -> np.ndarray:
    """(n,) the terms of the divergence of the integrand, per unit κ/h₃, that the
    auxiliary fields leave in the curvilinear frame of a curved front (module notes):
    σ₃₃ uᵃ₁,₁ - σ₁₃ uᵃ₃,₁ + (σᵃ₁₁ - σᵃ₃₃) u₁,₁ + σᵃ₁₂ u₂,₁ + 2 σᵃ₁₃ u₃,₁, from σ (3, 3, n)
    and uₐ,₁ (3, n) of the solution in the frame, ``aux`` the Williams field there."""
    ag, asg = aux.grad_u, aux.sigma
    return (sl[2, 2] * ag[0, 0] - sl[0, 2] * ag[2, 0]
            + (asg[0, 0] - asg[2, 2]) * gl[0] + asg[0, 1] * gl[1] + 2 * asg[0, 2] * gl[2])


def sif_3d(space, U: np.ndarray, material: Material, points: np.ndarray | None = None,
           radius: float | None = None, length: float | None = None,
           plateau: float = 0.5, body_force=None, faces=None) -> np.ndarray:
    """(m, 3) K_I, K_II, K_III at ``points`` (3, m) of the front (default
    :func:`front_points`) by the domain interaction integral (module notes).

    ``radius`` R of the radial cone (default :func:`default_radius_3d`),
    clipped at each point to the distance to the boundary (:func:`boundary_reach`) and
    to a third of the distance to another front or a facing part of its own
    (:func:`other_fronts`: P's domain, the points within 2R of its tangent line,
    :func:`_along`, then holds no other front);
    ``length`` L the bump's half-width (default :data:`DEFAULT_LENGTH` sizes), ``plateau``
    ρ: q_r = 1 inside ρR.  ``body_force``: the body force b the solution carries
    (:func:`skxfem.fem.loads.force_field`, in 3D), whose term -∫ b·uᵃ,₁ q dV
    (:mod:`skxfem.crack.interaction`) joins the integrand's part in q; None: none.
    ``faces``: the traction the crack's faces carry
    (:class:`skxfem.crack.faces3d.FaceTraction3D`, from a contact or a tie), its term
    -∫ tᵢ uᵃᵢ,₁ q dS on both faces (:mod:`skxfem.crack.interaction`); None: free faces.

    K is NaN at a point whose domain has under a front cell's size h of room
    (:func:`domain_reach`, within a cell of the boundary: its domain would hold no
    cell); :meth:`skxfem.crack.kind3d.Crack3D.front` leaves such points out and warns.
    """
    if not isinstance(material, Material):
        raise ValueError(f"material must be a skxfem Material, got {type(material).__name__}")
    U = np.asarray(U, float)
    if U.shape != (space.N,):
        raise ValueError(f"U must hold the {space.N} unknowns [a, b, c], got shape {U.shape}")
    chains = front_chains(space.geometry)                # once: fits, points, fronts
    h, h_along = front_sizes(space)
    P = (front_points(space, h_along, chains) if points is None
         else np.asarray(points, float))
    if P.ndim != 2 or P.shape[0] != 3:
        raise ValueError(f"points must have shape (3, m), got {P.shape}")
    R = default_radius_3d(space, h) if radius is None else float(radius)
    L = DEFAULT_LENGTH * h_along if length is None else float(length)
    for name, v in (("radius", R), ("length", L)):
        if not (np.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be a positive number, got {v!r}")
    check_radius(R, h)
    if not 0 <= plateau < 1:
        raise ValueError(f"plateau must be in [0, 1), got {plateau!r}")
    mesh, geo = space.mesh, space.geometry
    spacing = max(L, 2 * h_along)
    frames, kappa = fitted_frame(space, P, spacing, chains)
    # the cells of every point's domain
    reach = np.hypot(R, L) + 2 * h
    d = np.linalg.norm(mesh.p[:, :, None] - P[:, None], axis=0).min(axis=1)
    radial = np.hypot(geo.phi, geo.psi)                   # r of the nodes (q_r = 0 beyond R)
    cells = np.flatnonzero((d[mesh.t] <= reach).any(axis=0)
                           & (radial[mesh.t] <= R + 2 * h).any(axis=0))
    lam_, mu = material.lame(3)
    e1_nodes = _nodal_directions(space, cells, spacing, chains)
    ut = virtual_field(space, U)
    eye = np.eye(3)[:, :, None]
    b = None if body_force is None else force_field(body_force, 3)
    # the cells that can hold points of a domain (r < R; the nodal directions above
    # use all of them).  plain=4: the smooth Williams fields on the ring of uncut cells
    # (3 left |K_I| ≈ 1.5e-3 σ√(πa) on a crack pressed shut with its front 0.3 h past a
    # node, 4: 1e-3)
    within = cells[_cell_r_bound(space, cells) < R * (1 + 1e-9)]
    # a free crack's near rule not graded (grading=()): its K is the domain term alone;
    # faces with a traction: FACE_RULES (the difference of two terms)
    traction = faces is not None
    batches = rules(space, within, plain=4, symmetric=TUBE_ORDER,
                    grading=FACE_RULES["grading"] if traction else (),
                    tube=FACE_RULES["tube"] if traction else ())
    # the points' terms, filled chunk by chunk (at most every point of the rules)
    total = sum(int(np.count_nonzero(w)) for _, _, w, _ in batches)
    X_, e1_, gr_, B_, C_, D_ = (np.empty((3, total)) for _ in range(6))
    W_, r_, x1_ = (np.empty(total) for _ in range(3))
    A_ = np.empty((3, 3, total))                          # (3 modes, 3, n)
    n = 0
    for cc, X, W, S in _point_chunks(batches):
        on, lam, dlam, ph, gph = _in_support(space, cc, X, R, P, frames.e3, L)
        if not on.any():
            continue
        sl = slice(n, n + int(on.sum()))
        n = sl.stop
        cc, X, W, S = cc[on], X[:, on], W[on], S[on]
        pv = point_values(space, cc, X, S, barycentric_=(lam, dlam))
        _, gu = field_at(space, U, cc, X, S, values=pv, virtual=ut)
        ps, gps = pv.psi, pv.gpsi.T                       # x₁ = ph, ∇x₁ = gph
        e1, G, Rf = _point_frames(e1_nodes, pv.nodes, pv.lam, pv.dlam, gps)
        bx = 0.0 if b is None else np.einsum("ain,in->an", Rf, b(X))   # in the frames
        r = np.hypot(ph, ps)
        theta = side_angle(ph, ps, S, geo.side[cc] == 0)   # the branch functions' θ
        r = np.maximum(r, 1e-300)
        # the field in each point's frame, where the auxiliary fields are given
        gu_l, G_l = _rotate(Rf, gu), _rotate(Rf, G)
        eps = (gu_l + np.swapaxes(gu_l, 0, 1)) / 2
        sig = 2 * mu * eps + lam_ * np.trace(eps)[None, None] * eye
        e1_l = np.einsum("ain,in->an", Rf, e1)
        du1 = np.einsum("ijn,jn->in", gu_l, e1_l)
        trace_G = np.trace(G)
        for mode, aux in enumerate(near_tip_modes(r, theta, material, dim=3)):
            agu, asig = aux.grad_u, aux.sigma
            aeps = (agu + np.swapaxes(agu, 0, 1)) / 2
            dua1 = np.einsum("ijn,jn->in", agu, e1_l)
            work = np.einsum("ijn,ijn->n", sig, aeps)
            A_l = np.einsum("in,ijn->jn", dua1, sig) + np.einsum("in,ijn->jn", du1, asig)
            A_[mode, :, sl] = np.einsum("ain,an->in", Rf, A_l)   # global components
            B_[mode, sl] = work
            C_[mode, sl] = (_contract(sig, agu, G_l) + _contract(asig, gu_l, G_l)
                            - work * trace_G - (bx * dua1).sum(axis=0))   # the body force's
            D_[mode, sl] = _curvature_integrand(sig, gu_l[:, 0], aux)
        X_[:, sl], W_[sl], e1_[:, sl], r_[sl], x1_[sl] = X, W, e1, r, ph
        gr_[:, sl] = (ph * gph + ps * gps) / r
    X, W, e1, r, gr, x1 = X_[:, :n], W_[:n], e1_[:, :n], r_[:n], gr_[:, :n], x1_[:n]
    A, B, C, D = A_[:, :, :n], B_[:, :n], C_[:, :n], D_[:, :n]
    if faces is not None:
        xf, wf, rf, Df = _face_terms(space, faces, material, e1_nodes, cells)
    Rk = np.minimum(R, domain_reach(space, P, frames.e3, kappa, L, chains, h))
    den = _hat_integral(geo, P, frames.e3, L, Rk)
    K = np.zeros((P.shape[1], 3))
    size = np.abs(X).max(initial=0.0)
    for k in range(P.shape[1]):
        if Rk[k] < h:                                     # no room: no cell in its domain
            K[k] = np.nan
            continue
        R, inner = Rk[k], plateau * Rk[k]
        cand = np.flatnonzero(_hat_candidates(X, P[:, k, None], frames.e3[:, k, None],
                                              L, size)[0])
        s, near = _along(X[:, cand], P[:, k], frames.e3[:, k], R)
        inq = (np.abs(s) < L) & (r[cand] < R) & near
        on = cand[inq]                                    # the support of q
        s, rk = s[inq], r[on]
        qr, dqr = _radial(rk, R, inner)
        hat, dhat = _bump(s, L)
        gq = hat * dqr * gr[:, on] + qr * dhat * frames.e3[:, k, None]
        q1 = (gq * e1[:, on]).sum(axis=0)
        # κ/h₃ at each quadrature point, h₃ = 1 + κ x₁ the stretch along the front (at
        # least ½: a domain reaching half-way to the centre of curvature is too wide)
        k3 = kappa[k] / np.maximum(1 + kappa[k] * x1[on], 0.5)
        I = (np.einsum("min,in->mn", A[:, :, on], gq) - B[:, on] * q1
             + qr * hat * (C[:, on] + k3 * D[:, on])) @ W[on]
        if faces is not None:
            sf, near_f = _along(xf, P[:, k], frames.e3[:, k], R)
            qf = _radial(rf, R, inner)[0] * _bump(sf, L)[0] * near_f
            I = I - Df @ (wf * qf)
        K[k] = sif_from_interaction(I / den[k], material, 3)
    return K


DEGENERATE = 0.1
"""The length of e₁ₕ (the P1 interpolant of unit nodal directions, made normal to e₂)
under which a point's direction is taken from its nearest node (:func:`_point_frames`)."""


def _point_frames(e1_nodes: np.ndarray, nodes: np.ndarray, lam: np.ndarray,
                  dlam: np.ndarray, grad_psi: np.ndarray):
    """The frames of points of cells with nodes ``nodes`` (n, 4), barycentric λ (n, 4)
    and ∇λ (n, 4, 3), ∇ψ_h ``grad_psi`` (3, n), for the domain's points and the faces'
    alike: e₁ₕ (3, n), the P1 interpolant of the nodal ``e1_nodes``
    (:func:`_nodal_directions`; the extension direction Q/q), its gradient ∂ⱼe₁ₖ
    [j, k, n], and R (3, 3, n), rows e₁, e₂ = ∇ψ_h/|∇ψ_h| and e₃ (e₁ₕ made normal to
    e₂, unit).

    Between two fronts (a centre crack's) the nodes' directions turn round, each node
    pointing ahead of its nearest front: in a cell across the line where the nearest
    front changes, e₁ₕ of opposite nodal directions nearly vanishes (under
    :data:`DEGENERATE` of a unit vector) and has no direction.  Such a point takes the
    direction of its nearest node (the largest λ) and ∂e₁ = 0: it lies half-way between
    the fronts, where no domain reaches (:func:`domain_reach` clips R to a third of the
    distance to another front), so q = 0 there and K does not depend on it."""
    e1n = e1_nodes[nodes]                                 # (n, 4, 3)
    e1 = np.einsum("nk,nki->in", lam, e1n)
    # G is constant in a cell: once per run of points of one cell
    first, run = runs(nodes)
    G = np.einsum("nkj,nki->jin", dlam[first], e1n[first])[:, :, run]
    e2 = grad_psi / np.linalg.norm(grad_psi, axis=0)
    flat = np.linalg.norm(e1 - (e1 * e2).sum(axis=0) * e2, axis=0) < DEGENERATE
    if flat.any():
        nearest = np.argmax(lam[flat], axis=1)
        e1[:, flat] = e1n[flat, nearest].T
        G[:, :, flat] = 0.0
    return e1, G, tip_frame(e1, grad_psi).R


def _face_terms(space, faces, material: Material, e1_nodes: np.ndarray,
                cells_in: np.ndarray):
    """The faces' points x (3, n) in the domain's cells ``cells_in``, their weights (n,),
    distances r to the front (n,) and D (3, n): Σ over both faces of t·∂uᵃ/∂x₁ for the
    auxiliary modes I, II, III (the face of Ω⁻ at θ = -π carries t⁻ = r, that of Ω⁺ at
    θ = +π t⁺ = -r), in each point's frame."""
    mesh, geo = space.mesh, space.geometry
    x, w, cells = (np.asarray(a) for a in (faces.x, faces.weights, faces.cells))
    t = np.asarray(faces.traction, float)
    if x.ndim != 2 or x.shape[0] != 3 or t.shape != x.shape or w.shape != (x.shape[1],) \
            or cells.shape != w.shape or not np.all(np.isfinite(t)):
        raise ValueError("faces must hold points x (3, n), weights (n,), cells (n,) and a "
                         "finite traction (3, n) (skxfem.crack.faces3d.face_traction_3d)")
    keep = np.isin(cells, cells_in)                       # q = 0 elsewhere
    x, w, cells, t = x[:, keep], w[keep], cells[keep], t[:, keep]
    lam, dlam = barycentric(mesh, cells, x)
    nodes = mesh.t[:, cells].T
    gph, gps = (np.einsum("nk,nki->in", f[nodes], dlam) for f in (geo.phi, geo.psi))
    ph = front_coordinate(geo, x, (lam * geo.psi[nodes]).sum(axis=1), gph, gps)[0]
    e1, _, Rf = _point_frames(e1_nodes, nodes, lam, dlam, gps)   # as the domain's
    e1_l = np.einsum("ain,in->an", Rf, e1)
    t_l = np.einsum("ain,in->an", Rf, t)
    r = np.maximum(np.abs(ph), 1e-300)                    # on the faces ψ_h = 0
    D = np.zeros((3, r.size))
    for side in (1.0, -1.0):
        for mode, aux in enumerate(near_tip_modes(r, np.full(r.size, side * np.pi),
                                                  material, dim=3)):
            dua1 = np.einsum("ijn,jn->in", aux.grad_u, e1_l)
            D[mode] += (-side * t_l * dua1).sum(axis=0)
    return x, w, r, D


@dataclass(frozen=True)
class CrackSolution3D:
    """A solved 3D crack problem: ``U`` the unknowns [a, b, c] of ``space``, ``points``
    (3, m) front points and ``K`` (m, 3) K_I, K_II, K_III there, ``info`` (the solver's
    figures: unknowns, times)."""

    U: np.ndarray
    space: object
    material: Material
    points: np.ndarray
    K: np.ndarray
    info: dict


def _solve(V, Ks, fs, Sinv, D, gs, solver: str, tol: float):
    """U_s of the scaled system K_s U_s = f_s with U_s[D] = g_s, and the iterations (0
    for the direct solve).

    ``"cg"``: :func:`skxfem.linalg.iterative.solve` (no constraint rows), the package's
    CG with a smoothed-aggregation AMG on the nodes' 3 × 3 blocks, its near-null space
    the six rigid motions of the body in the scaled unknowns, S⁻¹ Z (Z: a = R(xᵢ) on the
    standard unknowns, b = c = 0, which the shifted enrichment leaves rigid), and its
    Chebyshev smoother.  Where rounding holds the residual just above ``tol``, the
    answer is accepted by its backward error (that module's notes).  On the penny of
    :mod:`skxfem.studies.cracks3d` to 1e-10 (``benchmarks/crack_penny.py --solver cg
    --sizes ...``; one run each, before and after, 29 November): h = 0.2, 0.125,
    0.08, 0.0714 (14 574 to 101 850 unknowns) took 95, 380, 1382, 1757 iterations and
    0.3, 2.3, 23.1, 35.9 s of solve, where the scalar AMG (pyamg's defaults, constant
    near-null space) that this replaced took 132, 470, 1571 iterations and 0.3, 3.5,
    51.2 s, and did not converge in 2000 at 0.0714; K_I the same to its 4 printed
    digits.  Not a gain everywhere: the Williams slab of tests/test_crack_body_force
    (n = 11, nz = 2, radius 0.3: 96 branch nodes of 2502 unknowns, every side imposed)
    took 924 iterations against 811; there U's standard unknowns were within 7e-10 of
    the direct solve's (relative), its enriched ones within 2e-5 (3e-5 before: nearly
    dependent branch functions, which the field hardly sees), K within 2e-10.
    """
    if solver == "direct":
        from scipy.sparse.linalg import spsolve
        Us = np.zeros(V.N)
        Us[D] = gs
        free = np.setdiff1d(np.arange(V.N), D)
        rhs = fs[free] - Ks[free][:, D] @ Us[D]
        Us[free] = spsolve(sp.csc_matrix(Ks[free][:, free]), rhs)
        return Us, 0
    from ..linalg.amg import body_motions
    from ..linalg.iterative import solve
    x = V.mesh.p - V.mesh.p.mean(axis=1, keepdims=True)
    x = x / max(np.abs(x).max(), 1e-300)           # rotations of the size of translations
    motions = np.array(body_motions(x))                                 # (6, 3, nverts)
    Z = np.zeros((V.N, 6))
    Z[:V.n_std] = motions.transpose(2, 1, 0).reshape(V.n_std, 6)      # a: 3 i + component
    Us, _, info = solve(Ks, sp.csr_matrix((0, V.N)), fs, D, gs, modes=Sinv @ Z,
                        blocksize=3, tol=tol, maxiter=2000)
    return Us, info.iterations


def solve_crack_3d(mesh, psi, phi, material: Material, supports=(), loads=(),
                   enrichment: str = "geometric", radius: float | None = None,
                   points: np.ndarray | None = None, sif_radius: float | None = None,
                   sif_length: float | None = None, solver: str = "direct",
                   tol: float = 1e-10, body_force=None) -> CrackSolution3D:
    """Linear elasticity on a ``MeshTet1`` with a crack {ψ = 0, φ < 0}, law free: geometry,
    space, stiffness, loads, supports, block scaling, solve, K along the front.

    ``supports``, ``loads``: :class:`~skxfem.crack.space3d.Support3D`,
    :class:`~skxfem.crack.space3d.Load3D`; ``solver`` ``"direct"`` (SuperLU) or ``"cg"``
    (CG with a block AMG on the scaled system, to ``tol``: :func:`_solve`);
    ``body_force`` b (:func:`skxfem.crack.space3d.body_load`, and its term in K).
    """
    import time
    if not isinstance(material, Material):
        raise ValueError(f"material must be a skxfem Material, got {type(material).__name__}")
    if solver not in ("direct", "cg"):
        raise ValueError(f"solver must be 'direct' or 'cg', got {solver!r}")
    t0 = time.perf_counter()
    geometry = crack_geometry_3d(mesh, psi, phi)
    V = crack_space_3d(mesh, geometry, enrichment, radius)
    K = stiffness(V, material)
    f = traction_load(V, loads)
    if body_force is not None:
        f = f + body_load(V, body_force)
    D, g = supported_dofs(V, supports)
    S, Sinv = nodal_scaling(K, V, D, inverse=True)
    Ks, fs = (S.T @ K @ S).tocsr(), S.T @ f
    t1 = time.perf_counter()
    Us, iterations = _solve(V, Ks, fs, Sinv, D, g / S.diagonal()[D], solver, tol)
    U = S @ Us
    t2 = time.perf_counter()
    P = front_points(V) if points is None else np.asarray(points, float)
    Kf = sif_3d(V, U, material, P, sif_radius, sif_length, body_force=body_force)
    t3 = time.perf_counter()
    info = {"unknowns": V.N, "enriched": V.N - V.n_std, "assembly_s": t1 - t0,
            "solve_s": t2 - t1, "sif_s": t3 - t2, "iterations": iterations}
    return CrackSolution3D(U, V, material, P, Kf, info)
