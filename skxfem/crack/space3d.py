r"""The X-FEM space of a 3D crack on tetrahedra, and its stiffness, loads and supports.

The 3D twin of :mod:`skxfem.crack.space` and :mod:`skxfem.crack.assembly`, on a
:class:`~skxfem.crack.geometry3d.CrackGeometry3D`.  With φᵢ the P1 shape functions,
H = sign ψ and F_l the four branch functions of (r, θ) around the front
(:mod:`skxfem.crack.branch`; r = √(φ_h² + ψ_h²), θ = atan2(ψ_h, φ_h): the polar
coordinates in the plane normal to the front, from the front's frame
e₁ = ∇φ/|∇φ|, e₂ = ∇ψ/|∇ψ|),

.. math:: u_h = \sum_i a_i \varphi_i + \sum_{j \in J} b_j \varphi_j (H - H_j)
               + \sum_{k \in K} \sum_{l=1}^4 c_{kl}\, \varphi_k (F_l - F_l(x_k)),

shifted so that aᵢ is the displacement of node i.  K, the **branch** nodes: the nodes
of the front cells (``"topological"``), or also every node within the radius r_e of
the front (``"geometric"``); J, the **Heaviside** nodes: the other nodes of split cells
whose support holds a part of positive volume on the far side of the crack.

Unknowns [a, b, c]: a node by node, component fastest (scikit-fem's ``ElementVector``
numbering, 3 i + c), then b (3 per Heaviside node), then c (12 per branch node, function
l then component).  As in 2D every function is φᵢ g for one of six kinds
g ∈ {1, H, F₁..F₄} less a multiple of φᵢ, so u_h = Σ_g Σ_i ũ_{g,i} φᵢ g with virtual
coefficients ũ = T U (:attr:`CrackSpace3D.T`).

Integration
-----------
Cell by cell, on the virtual functions φ_k g of a cell in use (of its 4 nodes × 6 kinds:
a node is standard, Heaviside or branch, so at most 20; cells batched by their count),
with dense arrays: the stiffness of a cell is λ G_c G′_d + μ(δ_cd G·G′ + G_d G′_c) summed over its
points, G the gradients, then gathered into the virtual space and taken to the unknowns
by Tᵀ K̃ T.  The rules (:func:`rules`): the front cells' sub-tetrahedra by the almost-polar
rules of :mod:`skxfem.crack.quadrature3d` (on the front's edge or vertex) or the
collapsed Gauss rule of :data:`~skxfem.crack.quadrature3d.NEAR_POINTS`, as the cells
around the front cells (in the support of a front cell's node) and their split cells'
sub-tetrahedra; the other split cells' sub-tetrahedra and uncut cells in a branch node's
support by the symmetric rule of order :data:`SMOOTH_ORDER` (24 points; the interaction
integral and the loads: the collapsed rule of :data:`BRANCH_POINTS`); the
sub-tetrahedra and cells outside the branch nodes' supports by the rule ``plain`` of
:func:`rules` (the stiffness: their centroid, P1 and Heaviside gradients are constant
there; the interaction integral: 64 points for its smooth Williams fields); the other
cells by scikit-fem's exact P1 stiffness.

Conditioning: each branch node's block [a_k, c_k] (3 + 12 = 15 unknowns) is scaled by the
inverse transpose of the Cholesky factor of its diagonal block (Béchet et al. 2005),
every other unknown by 1/√K_ii (:func:`nodal_scaling`).

>>> from skfem import MeshTet1
>>> from skxfem.crack.geometry3d import crack_geometry_3d
>>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 6),) * 2, np.linspace(0, 1, 3))
>>> V = crack_space_3d(m, crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.5), "topological")
>>> V.n_std, V.heaviside.size, V.branch.size, V.N == V.n_std + 3 * 12 + 12 * 12
(324, 12, 12, True)
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.polynomial.legendre import leggauss
from numpy.typing import ArrayLike
from skfem import Basis, ElementTetP1

from ..fem.loads import force_field
from ..fem.material import Material, stiffness_matrix
from ..fem.quadrature import cell_rule, simplex_points
from ..fem.simplex import split
from .assembly import check_facets, support_dofs
from .branch import branch, branch_closed_form, side_angle
from .dofs import EnrichedUnknowns, virtual_map
from .geometry import check_geometry, nearest_on_segments
from .geometry3d import (
    CrackGeometry3D,
    barycentric,
    cell_gradients,
    check_mesh_3d,
    mesh_cells,
    projected_diameters,
    shape_gradients,
)
from .quadrature3d import NEAR_GRADING, NEAR_POINTS, collapsed, edge_polar, vertex_polar
from .radius import enrichment_radius, geometric_nodes
from .space import nodal_scaling as _nodal_scaling

__all__ = ["SMOOTH_ORDER", "BRANCH_POINTS", "CrackSpace3D", "crack_space_3d", "PointValues",
           "point_values", "functions_at", "virtual_field", "evaluation", "field_at", "rules",
           "stiffness", "mass", "near_points", "Support3D", "Load3D", "outward_normals",
           "traction_load", "body_load", "supported_dofs", "nodal_scaling", "front_distance",
           "crack_depth", "cross_section"]

SMOOTH_ORDER = 6
"""The order of the symmetric rule (:func:`skxfem.fem.quadrature.simplex_points`: 24
points, positive weights, exact to degree 6) on the uncut cells and split cells'
sub-tetrahedra in a branch node's support, away from the front cells (not in the
support of a front cell's node).  The branch functions are smooth there, the cells one
or more cells from the front.  Measured against the collapsed rule of 10³ points, the
stiffness's energy on the solution of benchmarks/crack_solve.py, relative: on these
uncut cells 1.7e-6 (n = 16) and 8.3e-7 (n = 24), where the collapsed rule of 4³ points
(exact to degree 5) used before gave -2.4e-5 and -1.2e-5; on these sub-tetrahedra 5e-8
and 4e-8 (4³: -4.5e-7, -2.8e-7).  Only the stiffness takes it (:func:`rules`'s
``symmetric``): the interaction integral of :mod:`~skxfem.crack.sif3d` on these cells
has the error of its weight q's kinks (C¹ only, across r = ρR, R and |s| = L) rather
than of the rule's degree, and on it K_I along the front was within 1.4e-4 of a
reference (the cells in 8 or 64 pieces of the collapsed rule) at n = 16 but 1.1e-3 at
n = 24, against 6.1e-4 and 4.8e-4 on :data:`BRANCH_POINTS`."""

BRANCH_POINTS = 4
"""Points per direction of the collapsed Gauss rule on the cells and sub-tetrahedra in a
branch node's support away from the front cells, for the interaction integral and the
loads (64 per tetrahedron: exact to degree 5; the stiffness: :data:`SMOOTH_ORDER`)."""

CHUNK = 4096
"""Quadrature points per batch of the cells' dense arrays (whole cells, one at least): the
(points × 60) gradients of a batch stay in the processor's cache (memory-bound: 400 cells
of 64 points a batch took twice as long)."""


@dataclass(frozen=True)
class CrackSpace3D(EnrichedUnknowns):
    """The enriched space of a 3D crack (module notes).

    Attributes
    ----------
    mesh, geometry : the mesh and its :class:`~skxfem.crack.geometry3d.CrackGeometry3D`.
    heaviside : (nh,) Heaviside nodes J; ``H_node`` (nh,) H(x_j).
    branch : (nb,) branch nodes K; ``F_node`` (4, nb) F_l(x_k).
    enrichment : ``"topological"`` or ``"geometric"``; ``radius`` r_e (geometric).
    T : (6 n_std, N) the virtual coefficients ũ = T U of the unknowns U = [a, b, c].
    """

    mesh: object
    geometry: CrackGeometry3D
    heaviside: np.ndarray
    H_node: np.ndarray
    branch: np.ndarray
    F_node: np.ndarray
    enrichment: str
    radius: float | None
    T: sp.csr_matrix = field(repr=False, compare=False)

    @property
    def n_std(self) -> int:
        return 3 * self.mesh.p.shape[1]

    @property
    def nodal_dofs(self) -> np.ndarray:
        """(3, nverts) the standard unknowns a of each node and component."""
        return 3 * np.arange(self.mesh.p.shape[1])[None] + np.arange(3)[:, None]


def front_distance(geometry: CrackGeometry3D, x: np.ndarray) -> np.ndarray:
    """The distance (n,) from points x (3, n) to the front's segments.

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 2, np.linspace(0, 1, 3))
    >>> g = crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.5)
    >>> front_distance(g, np.array([[0.5], [0.8], [0.3]])).round(12).tolist()
    [0.3]
    """
    A, B = geometry.segments[0], geometry.segments[1]         # (3, nseg)
    d = B - A
    best = np.full(x.shape[1], np.inf)
    for k in range(0, A.shape[1], 256):                   # batches of segments
        dist = nearest_on_segments(A[:, None, k:k + 256], d[:, None, k:k + 256],
                                   x[:, :, None])[2]
        best = np.minimum(best, dist.min(axis=1))
    return best


def crack_depth(geometry: CrackGeometry3D) -> float:
    """The crack's depth a: the largest distance from a point of the crack (a vertex of
    its faces) to its front (:func:`front_distance`); an edge crack's depth, a penny's
    radius.  The default enrichment radius is a fraction of it
    (:mod:`skxfem.crack.radius`).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 5),) * 2, np.linspace(0, 1, 3))
    >>> round(crack_depth(crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.6)), 12)
    0.6
    """
    x = np.unique(geometry.faces.reshape(-1, 3), axis=0).T
    return float(front_distance(geometry, x).max())


def cross_section(mesh, geometry: CrackGeometry3D) -> float:
    """The front cells' mean size across the front: the diameter of each one's nodes
    projected on the plane normal to the front (e₃ = ∇φ_h × ∇ψ_h in the cell), whatever
    the front's place in the cells.  h√2 for a cube of side h split into six tetrahedra.

    The nodes' largest √(φ² + ψ²), the measure before, was 1.27 h with the front on a
    line of nodes and 0.71 h with it through the middle of the cells: the default r_e
    (4 of these) then fell from 5 to 2.8 cells, and K_I along a straight front with it,
    by 7 to 13 % against the plane-strain K of the same mesh in 2D (the edge crack of the
    unit cube on rollers, n = 7 ... 13 odd; see tests/test_crack_radius.py).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 11),) * 3)
    >>> [round(cross_section(m, crack_geometry_3d(m, m.p[1] - y, m.p[0] - y)) * 10, 6)
    ...  for y in (0.5, 0.55)]                        # on nodes, mid-cell: the same
    [1.414214, 1.414214]
    """
    cells = geometry.front_cells
    nodes = mesh.t[:, cells]
    d = projected_diameters(np.transpose(mesh.p[:, nodes], (2, 1, 0)),
                            cell_gradients(mesh, geometry.phi, cells).T,
                            cell_gradients(mesh, geometry.psi, cells).T)
    if np.isnan(d).all():            # ∇φ_h ∥ ∇ψ_h in every front cell: the nodes' distance
        return float(np.hypot(geometry.phi[nodes], geometry.psi[nodes]).max(axis=0).mean())
    return float(np.nanmean(d))


def crack_space_3d(mesh, geometry: CrackGeometry3D, enrichment: str = "geometric",
                   radius: float | None = None) -> CrackSpace3D:
    """The :class:`CrackSpace3D` of a 3D crack on ``mesh``.

    Parameters
    ----------
    mesh : the ``MeshTet1`` of ``geometry``.
    geometry : :func:`skxfem.crack.geometry3d.crack_geometry_3d` of the crack.
    enrichment : ``"topological"`` (the front cells' nodes) or ``"geometric"`` (also the
        nodes within ``radius`` of the front).
    radius : r_e > 0 for geometric enrichment; default
        :func:`skxfem.crack.radius.default_enrichment_radius` (0.2 of the crack's depth
        :func:`crack_depth`, and at least 4 front-cell sizes across the front,
        :func:`cross_section`: the
        default radial cone of :func:`skxfem.crack.sif3d.sif_3d` inside 0.75 r_e).
    """
    check_geometry(geometry, check_mesh_3d(mesh), CrackGeometry3D, "crack_geometry_3d")
    nodes = mesh.t[:, geometry.front_cells]
    given = radius is not None
    radius = enrichment_radius(            # the front cells' mean size across the front
        mesh, enrichment, radius, lambda: cross_section(mesh, geometry),
        lambda: crack_depth(geometry))
    branch_nodes = geometric_nodes(nodes.ravel(), None if radius is None else
                                   front_distance(geometry, mesh.p), radius, given)
    heav = np.setdiff1d(np.unique(mesh.t[:, geometry.split_cells]), branch_nodes)
    H_node = np.sign(geometry.psi[heav])
    keep = _far_side(mesh, geometry)[heav, (H_node > 0).astype(int)] | (H_node == 0)
    heav, H_node = heav[keep], H_node[keep]
    phi, psi = geometry.phi[branch_nodes], geometry.psi[branch_nodes]
    F_node = branch(np.hypot(phi, psi), np.arctan2(np.where(psi == 0, 0.0, psi), phi))
    T = virtual_map(3 * np.arange(mesh.p.shape[1])[None] + np.arange(3)[:, None], heav,
                    H_node, branch_nodes, F_node)
    return CrackSpace3D(mesh, geometry, heav, H_node, branch_nodes, F_node, enrichment,
                        radius, T)


def _far_side(mesh, geometry: CrackGeometry3D) -> np.ndarray:
    """(nverts, 2): does the support of each node hold a part of positive volume of Ω⁺
    (column 0) or of Ω⁻ (column 1)?"""
    nc = mesh.t.shape[1]
    has = np.zeros((nc, 2), dtype=bool)
    whole = geometry.side != 0
    has[whole, 0], has[whole, 1] = geometry.side[whole] > 0, geometry.side[whole] < 0
    np.logical_or.at(has[:, 0], geometry.sub_cell[geometry.sub_side > 0], True)
    np.logical_or.at(has[:, 1], geometry.sub_cell[geometry.sub_side < 0], True)
    out = np.zeros((mesh.p.shape[1], 2), dtype=bool)
    for k in range(4):                                    # the 4 nodes of a cell
        np.logical_or.at(out, mesh.t[k], has)
    return out


@dataclass(frozen=True)
class PointValues:
    """What the enriched functions need at points x (3, n) of cells (n,): the P1 shape
    functions ``lam`` (n, 4) and their gradients ``dlam`` (n, 4, 3), the cells' ``nodes``
    (n, 4), the interpolated level sets ``phi``, ``psi`` (n,) and their gradients
    ``gphi``, ``gpsi`` (n, 3), and the six kinds g ∈ {1, H, F₁..F₄}: values ``g`` (n, 6),
    gradients ``dg`` (n, 6, 3) (:func:`point_values`)."""

    lam: np.ndarray
    dlam: np.ndarray
    nodes: np.ndarray
    phi: np.ndarray
    psi: np.ndarray
    gphi: np.ndarray
    gpsi: np.ndarray
    g: np.ndarray
    dg: np.ndarray


def point_values(space: CrackSpace3D, cells: np.ndarray, x: np.ndarray,
                 side: np.ndarray | None = None, barycentric_=None) -> PointValues:
    """The :class:`PointValues` at points x (3, n) of ``cells`` (n,).

    ``side`` (n,) the side ±1 of each point (needed in split and front cells; default
    the cell's side).  Behind the front (φ_h < 0) in the cells the crack cuts, θ takes
    the side's sign, so a point counts on its own side of the crack (:func:`_kinds`).
    ``barycentric_``: the points'
    (:func:`~skxfem.crack.geometry3d.barycentric`) (λ, ∇λ) if already known.
    """
    mesh, geo = space.mesh, space.geometry
    cells = np.asarray(cells)
    if side is None:
        side = geo.side[cells].astype(float)
        if np.any(side == 0):
            raise ValueError("side is needed at points of split and front cells")
    side = np.asarray(side, float)
    lam, dlam = (barycentric(mesh, cells, x) if barycentric_ is None
                 else barycentric_)                       # (n, 4), (n, 4, 3)
    nodes = mesh.t[:, cells].T                            # (n, 4)
    phi = np.einsum("nk,nk->n", lam, geo.phi[nodes])
    psi = np.einsum("nk,nk->n", lam, geo.psi[nodes])
    gphi = np.einsum("nk,nki->ni", geo.phi[nodes], dlam)
    gpsi = np.einsum("nk,nki->ni", geo.psi[nodes], dlam)
    g, dg = _kinds(phi, psi, gphi, gpsi, side, geo.side[cells] == 0)
    return PointValues(lam, dlam, nodes, phi, psi, gphi, gpsi, g, dg)


def _kinds(phi, psi, gphi, gpsi, side, cut) -> tuple[np.ndarray, np.ndarray]:
    """The six kinds g ∈ {1, H, F₁..F₄} (..., 6) and their gradients (..., 6, 3) at points
    of interpolated level sets ``phi``, ``psi`` (...) with gradients ``gphi``, ``gpsi``
    (..., 3) (or broadcastable: one per cell) on ``side`` (...) (:func:`point_values`),
    ``cut`` (...) whether the point's cell is one the crack cuts (a split or front cell).

    θ = atan2(ψ_h, φ_h), and ±π by ``side`` where φ_h < 0 and ψ_h has not the side's
    sign in a cut cell (a point on a face, or rounding).  Only there: a cell that ψ_h
    crosses ahead of the front (φ_h > 0 on its part of {ψ_h = 0}) is cut by no crack,
    and atan2 is continuous in it, but φ_h < 0 can hold at points of it on either side
    of {ψ_h = 0}; forcing θ there made F jump inside the cell, and the stiffness's rows of
    the branch functions missed a face term: on the penny pressed shut
    (:func:`skxfem.studies.cracks3d.pressed_penny`) K U₀ - Jᵀ(w p) of the exact state
    reached 1.6e-2 h^2.5 p on the branch rows at h = 0.125 (six such cells; 1e-3 h^2.5 p
    without them, measured).

    F and its derivatives along φ and ψ, the local coordinates, in closed form
    (:func:`skxfem.crack.branch.branch_closed_form`; zero at r = 0), then the chain rule
    ∇F = ∂F/∂φ ∇φ_h + ∂F/∂ψ ∇ψ_h."""
    r = np.hypot(phi, psi)
    F, dphi, dpsi = branch_closed_form(r, side_angle(phi, psi, side, cut))
    shape = np.shape(r)
    g = np.empty(shape + (6,))
    g[..., 0] = 1.0
    g[..., 1] = np.where(side == 0, 1.0, side)
    g[..., 2:] = F
    dg = np.zeros(shape + (6, 3))
    dg[..., 2:, :] = (dphi[..., None] * np.expand_dims(gphi, -2)
                      + dpsi[..., None] * np.expand_dims(gpsi, -2))
    return g, dg


def _cell_values(space: CrackSpace3D, cells: np.ndarray, x: np.ndarray, side: np.ndarray):
    """At the points x (nc, nq, 3) of ``cells`` (nc,) on ``side`` (nc, nq): the P1 shape
    functions λ (nc, nq, 4), their gradients (nc, 4, 3) (one per cell), and the kinds g
    (nc, nq, 6) and their gradients (nc, nq, 6, 3) (:func:`_kinds`); as
    :func:`point_values` at each point, batched cell by cell."""
    mesh, geo = space.mesh, space.geometry
    nodes = mesh.t[:, cells].T                            # (nc, 4)
    dlam = shape_gradients(mesh, cells)                   # (nc, 4, 3)
    l123 = np.matmul(x - mesh.p[:, nodes[:, 0]].T[:, None], np.swapaxes(dlam[:, 1:], 1, 2))
    lam = np.concatenate([1 - l123.sum(axis=2, keepdims=True), l123], axis=2)
    phi = np.matmul(lam, geo.phi[nodes][:, :, None])[..., 0]
    psi = np.matmul(lam, geo.psi[nodes][:, :, None])[..., 0]
    gphi = np.einsum("nk,nki->ni", geo.phi[nodes], dlam)[:, None]
    gpsi = np.einsum("nk,nki->ni", geo.psi[nodes], dlam)[:, None]
    g, dg = _kinds(phi, psi, gphi, gpsi, side, (geo.side[cells] == 0)[:, None])
    return lam, dlam, g, dg


def functions_at(space: CrackSpace3D, cells: np.ndarray, x: np.ndarray,
                 side: np.ndarray | None = None):
    """The 24 virtual functions φ_k g of each point's cell (4 nodes × 6 kinds) at points
    x (3, n) of ``cells`` (n,): values (n, 24), gradients (n, 24, 3) and their virtual
    node index g·nverts + node (n, 24).  ``side``: as :func:`point_values`.
    """
    pv = point_values(space, cells, x, side)
    lam, dlam, g, dg = pv.lam, pv.dlam, pv.g, pv.dg
    n = lam.shape[0]
    vals = (lam[:, :, None] * g[:, None, :]).reshape(n, 24)      # index 6 k + kind
    grads = (dlam[:, :, None, :] * g[:, None, :, None]
             + lam[:, :, None, None] * dg[:, None, :, :]).reshape(n, 24, 3)
    nv = space.mesh.p.shape[1]
    vnode = (np.arange(6)[None, None, :] * nv + pv.nodes[:, :, None]).reshape(n, 24)
    return vals, grads, vnode


def virtual_field(space: CrackSpace3D, U: np.ndarray) -> np.ndarray:
    """(nverts, 6, 3) the virtual coefficients ũ = T U by node, kind and component."""
    return (space.T @ U).reshape(6, -1, 3).transpose(1, 0, 2)


def field_at(space: CrackSpace3D, U: np.ndarray, cells, x, side=None,
             values: PointValues | None = None, virtual: np.ndarray | None = None):
    """u (3, n) and ∇u (3, 3, n) (∂u_i/∂x_j) of the unknowns U at points x (3, n).

    ``values``: the :func:`point_values` of these points if already known, ``virtual``:
    :func:`virtual_field` of U (both computed if None).  With
    c_k = Σ_g g ũ_{g,k} and v_g = Σ_k λ_k ũ_{g,k}: u = Σ_k λ_k c_k and
    ∇u = Σ_k c_k ⊗ ∇λ_k + Σ_g v_g ⊗ ∇g (the branch kinds g only: 1 and H are constant).
    """
    pv = point_values(space, cells, x, side) if values is None else values
    ut = virtual_field(space, U) if virtual is None else virtual
    coef = ut[pv.nodes]                                   # (n, 4, 6, 3)
    n = coef.shape[0]
    lam = pv.lam[:, None]                                 # (n, 1, 4)
    ck = np.matmul(pv.g[:, None, None], coef)[:, :, 0]    # (n, 4, 3)
    vg = np.matmul(lam, coef[:, :, 2:].reshape(n, 4, 12)).reshape(n, 4, 3)   # ∇1 = ∇H = 0
    u = np.matmul(lam, ck)[:, 0].T
    gu = (np.matmul(np.swapaxes(ck, 1, 2), pv.dlam)
          + np.matmul(np.swapaxes(vg, 1, 2), pv.dg[:, 2:])).transpose(1, 2, 0)
    return u, gu


def evaluation(space: CrackSpace3D, cells, x, side=None) -> sp.csr_matrix:
    """The operator U ↦ u at points x (3, n): rows component-major (c n + p).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 3)
    >>> V = crack_space_3d(m, crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> U = np.zeros(V.N); U[V.nodal_dofs[2]] = 1.0                    # u = (0, 0, 1)
    >>> (evaluation(V, np.array([0]), m.p[:, m.t[:, 0]].mean(axis=1)[:, None]) @ U).tolist()
    [0.0, 0.0, 1.0]
    """
    pv = point_values(space, cells, x, side)
    n, nv = pv.lam.shape[0], space.mesh.p.shape[1]
    vals = (pv.lam[:, :, None] * pv.g[:, None, :]).reshape(n, 24)      # φ_k g, 6 k + kind
    vnode = (np.arange(6)[None, None, :] * nv + pv.nodes[:, :, None]).reshape(n, 24)
    E = sp.csr_matrix((vals.ravel(), vnode.ravel(), np.arange(0, 24 * n + 1, 24)),
                      shape=(n, 6 * nv))                  # the scalar values, 24 a row
    T = space.T                                           # virtual dof 3 vnode + c
    return sp.vstack([E @ T[c::3] for c in range(3)], format="csr")


def _levels(space: CrackSpace3D) -> np.ndarray:
    """(ncells,) 0: plain, 1: in a branch node's support, 2: around the front cells."""
    mesh, geo = space.mesh, space.geometry
    level = np.zeros(mesh.t.shape[1], dtype=int)
    level[space.support_cells(space.branch)] = 1
    level[space.support_cells(np.unique(mesh.t[:, geo.front_cells]))] = 2
    return level


def rules(space: CrackSpace3D, cells: np.ndarray, plain: int = BRANCH_POINTS,
          symmetric: bool | int = False, grading=NEAR_GRADING, tube=()):
    """The quadrature of ``cells`` (module notes), as batches of cells with as many points
    each: a list of (cells (nc,), x (nc, nq, 3), w (nc, nq), side (nc, nq)).  ``plain``:
    the points per direction of the collapsed rule on the cells and sub-tetrahedra
    outside the branch nodes' supports (1: their centroid, :func:`_plain_rule`).
    ``symmetric``: the cells and sub-tetrahedra in a branch node's support away from the
    front cells on the symmetric rule of order :data:`SMOOTH_ORDER` (True: the
    stiffness) or of the order given (the interaction integral,
    :data:`skxfem.crack.sif3d.TUBE_ORDER`), else (False) on the collapsed rule of
    :data:`BRANCH_POINTS` per direction (the loads; :data:`SMOOTH_ORDER`'s notes).  The
    cells and pieces near the front that do not meet it: :func:`near_points`, graded by
    their distance to it as ``grading`` says.  ``tube``: pairs (ratio, n) as
    ``grading``, for the cells and pieces of the branch nodes' supports away from the
    front cells: those within ratio times their longest edge of the front take the
    collapsed rule of n³ points instead (the interaction integral of a crack whose
    faces carry a traction, :data:`skxfem.crack.sif3d.FACE_RULES`)."""
    mesh, geo = space.mesh, space.geometry
    cells = np.unique(np.asarray(cells, dtype=int))
    level = _levels(space)
    order = SMOOTH_ORDER if symmetric is True else int(symmetric)
    by_level = {1: ((lambda T: simplex_points(T, order)) if order else
                    (lambda T: collapsed(T, BRANCH_POINTS))),
                0: lambda T: _plain_rule(T, plain)}
    # sub-tetrahedra of split and front cells, by rule
    pick = np.isin(geo.sub_cell, cells)
    sc, ss, sf, S = geo.sub_cell[pick], geo.sub_side[pick], geo.sub_front[pick], geo.sub[pick]
    lv = level[sc]                                        # front cells: 2
    near = np.zeros(sc.size, dtype=int)
    off = (sf == 0) & (lv == 2)
    near[off] = near_points(space, S[off], grading)
    if tube:                                              # the tube's pieces near the front
        in_tube = np.flatnonzero((sf == 0) & (lv == 1))
        near[in_tube] = near_points(space, S[in_tube], tube, default=0)
        lv = np.where(near > 0, -1, lv)                   # off the by_level rules
    kinds = [(sf == 2, edge_polar), (sf == 1, vertex_polar)] + [
        ((sf == 0) & (lv == k), rule) for k, rule in by_level.items()] + [
        (near == k, lambda T, k=k: collapsed(T, k)) for k in np.unique(near[near > 0])]
    pieces = []
    for mask, rule in kinds:
        if mask.any():
            x, w = rule(S[mask])
            pieces.append((sc[mask], x, w, np.broadcast_to(ss[mask, None], w.shape)))
    batches = _pack(pieces)
    # uncut cells
    uncut = np.setdiff1d(cells, geo.cells)
    n_uncut = np.zeros(uncut.size, dtype=int)
    ring = level[uncut] == 2
    n_uncut[ring] = near_points(space, mesh_cells(mesh, uncut[ring]), grading)
    if tube:
        in_tube = level[uncut] == 1
        n_uncut[in_tube] = near_points(space, mesh_cells(mesh, uncut[in_tube]), tube,
                                       default=0)
    groups = [(uncut[(level[uncut] == k) & (n_uncut == 0)], rule)
              for k, rule in by_level.items()]
    groups += [(uncut[n_uncut == k], lambda T, k=k: collapsed(T, k))
               for k in np.unique(n_uncut[n_uncut > 0])]
    for here, rule in groups:
        if here.size:
            x, w = rule(mesh_cells(mesh, here))
            batches.append((here, x, w, np.broadcast_to(
                geo.side[here, None].astype(float), w.shape)))
    return batches


def near_points(space: CrackSpace3D, T: np.ndarray, grading=NEAR_GRADING,
                default: int = NEAR_POINTS) -> np.ndarray:
    """(m,) the points per direction of the collapsed rule on tetrahedra T (m, 4, 3) near
    the front that do not meet it (the cells around the front cells and the front cells'
    pieces off the front): :data:`~skxfem.crack.quadrature3d.NEAR_POINTS`, more by
    ``grading`` (pairs (ratio, n), :data:`~skxfem.crack.quadrature3d.NEAR_GRADING`)
    where the front passes within ratio times the tetrahedron's longest edge (its
    distance to the front's segments at its vertices, edges' midpoints and centroid),
    and the branch functions' 1/√r gradients turn within it; ``default`` where no
    ratio is reached (0: none, the caller keeps its own rule there).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 2, np.linspace(0, 1, 3))
    >>> V = crack_space_3d(m, crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> T = np.array([[0.0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]])   # edges ≤ 0.14
    >>> near_points(V, T + np.array([[[0.5, y, 0.3]] for y in (0.51, 0.53, 0.6)])).tolist()
    [12, 8, 5]
    """
    T = np.asarray(T, float)
    out = np.full(len(T), default)
    if not len(T):
        return out
    ends = [(a, b) for a in range(4) for b in range(a + 1, 4)]
    X = np.concatenate([T] + [(T[:, [a]] + T[:, [b]]) / 2 for a, b in ends]
                       + [T.mean(axis=1, keepdims=True)], axis=1)      # (m, 11, 3)
    d = front_distance(space.geometry, X.reshape(-1, 3).T).reshape(len(T), -1).min(axis=1)
    size = np.max([np.linalg.norm(T[:, a] - T[:, b], axis=1) for a, b in ends], axis=0)
    for ratio, n in sorted(grading, reverse=True):   # the closest last
        out[d < ratio * size] = max(n, NEAR_POINTS)
    return out


def _plain_rule(T: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The rule of tetrahedra T (m, 4, 3) outside the branch nodes' supports: the
    collapsed Gauss rule of n³ points, or for n = 1 the centroid with the volume (exact
    for linear functions; the collapsed rule of one point is not: its weight is 3/4 of
    the volume)."""
    if n > 1:
        return collapsed(T, n)
    return T.mean(axis=1)[:, None], (np.abs(np.linalg.det(T[:, 1:] - T[:, :1])) / 6)[:, None]


def _pack(pieces):
    """Pieces of cells (cell (m,), x (m, nq, 3), w (m, nq), side (m, nq)) of various nq
    into batches of whole cells, each cell's points padded with zero weights up to the
    size of its batch: a quarter-octave step (a multiple of 2^(k-2) from 2^k to 2^(k+1)),
    at most a quarter more points (the 91 000 points of the pieces on the benchmark's
    cube at n = 16 took 136 000 slots padded to powers of 2, 97 000 so)."""
    if not pieces:
        return []
    flat = [(c, x.reshape(-1, 3), w.ravel(), s.ravel(), np.repeat(c, w.shape[1]))
            for c, x, w, s in pieces]
    owner = np.concatenate([f[4] for f in flat])
    X = np.concatenate([f[1] for f in flat])
    W = np.concatenate([f[2] for f in flat])
    Sd = np.concatenate([f[3] for f in flat]).astype(float)
    order = np.argsort(owner, kind="stable")
    owner, X, W, Sd = owner[order], X[order], W[order], Sd[order]
    cells, first, counts = np.unique(owner, return_index=True, return_counts=True)
    slot = np.arange(owner.size) - np.repeat(first, counts)
    row = np.repeat(np.arange(cells.size), counts)
    step = 2 ** np.maximum(np.floor(np.log2(counts)).astype(int) - 2, 0)
    size = -(-counts // step) * step                      # batches of like counts
    out = []
    for nq in np.unique(size):
        pick = size == nq
        here = pick[row]
        new_row = np.cumsum(pick) - 1
        x = np.zeros((pick.sum(), nq, 3))
        w = np.zeros((pick.sum(), nq))
        s = np.ones((pick.sum(), nq))
        r, sl = new_row[row[here]], slot[here]
        x[r, sl], w[r, sl], s[r, sl] = X[here], W[here], Sd[here]
        # padding at the points' own cell: the first point of the cell
        pad = np.arange(nq)[None, :] >= counts[pick][:, None]
        x[pad] = np.broadcast_to(x[:, :1], x.shape)[pad]
        s[pad] = np.broadcast_to(s[:, :1], s.shape)[pad]
        out.append((cells[pick], x, w, s))
    return out


def _cell_stiffness(space, cells, x, w, side, slots, pairs, lam_, mu):
    """The 3 × 3 blocks (nc, np, 3, 3) of the stiffness of the same m virtual functions
    on each cell, ``slots`` (m,) their indices 6 k + kind (k the cell's node), for the
    np pairs of functions ``pairs`` = (a (np,), b (np,)), and the virtual nodes (nc, m) of
    the functions: block [n, p, i, j] couples component i of function a_p with component
    j of function b_p.  The cells' values by :func:`_cell_values`, ∫ ∂_i f_a ∂_j f_b by
    one product of the (points × 3m) gradients per cell."""
    nc, nq = w.shape
    m = slots.size
    lam, dlam, g, dg = _cell_values(space, cells, x, side)
    k, kind = slots // 6, slots % 6                       # (m,) the same on every cell
    Gf = (dlam[:, None, k] * g[:, :, kind, None]
          + lam[:, :, k, None] * dg[:, :, kind]).reshape(nc, nq, 3 * m)
    A = np.matmul(np.swapaxes(Gf * w[:, :, None], 1, 2), Gf)   # ∫ ∂_i f_a ∂_j f_b
    a, b = pairs
    A = A.reshape(nc, m, 3, m, 3)[:, a, :, b]             # (np, nc, 3, 3) [p, n, i, j]
    trace = A[..., 0, 0] + A[..., 1, 1] + A[..., 2, 2]
    Ke = lam_ * A + mu * np.swapaxes(A, 2, 3)
    for i in range(3):
        Ke[..., i, i] += mu * trace
    vnode = kind * space.mesh.p.shape[1] + space.mesh.t[k][:, cells].T
    return np.swapaxes(Ke, 0, 1), vnode


def summed_blocks(rows: np.ndarray, cols: np.ndarray, blocks: np.ndarray,
                  n: int) -> sp.bsr_matrix:
    """The (3n, 3n) sum of the 3 × 3 ``blocks`` (k, 3, 3) at the block rows and columns
    ``rows``, ``cols`` (k,): the cells' stiffness summed node pair by node pair, nine
    times fewer entries to sort than their scalar (row, column, value) triples.

    >>> b = np.arange(27.0).reshape(3, 3, 3)
    >>> K = summed_blocks(np.array([0, 1, 0]), np.array([1, 0, 1]), b, 2)
    >>> K.toarray()[:3, 3:].tolist()[0], K.toarray()[3:, :3].tolist()[0]
    ([18.0, 20.0, 22.0], [9.0, 10.0, 11.0])
    """
    key = rows.astype(np.int64) * n + cols
    pairs, at = np.unique(key, return_inverse=True)
    summed = np.stack([np.bincount(at, weights=blocks[:, i // 3, i % 3],
                                   minlength=pairs.size) for i in range(9)], axis=1)
    indptr = np.searchsorted(pairs // n, np.arange(n + 1))
    return sp.bsr_matrix((summed.reshape(-1, 3, 3), (pairs % n).astype(np.int32),
                          indptr.astype(np.int32)), shape=(3 * n, 3 * n))


def stiffness(space: CrackSpace3D, material: Material) -> sp.csr_matrix:
    """The stiffness ∫ σ(u):ε(v) on the unknowns [a, b, c] (module notes).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 3)
    >>> V = crack_space_3d(m, crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> K = stiffness(V, Material(1.0, 0.3))
    >>> U = np.zeros(V.N); U[V.nodal_dofs[1]] = 1.0            # a rigid translation
    >>> bool(abs(K @ U).max() < 1e-12), bool(abs(K - K.T).max() < 1e-12)
    (True, True)
    """
    if not isinstance(material, Material):
        raise ValueError(f"material must be a skxfem Material, got {type(material).__name__}")
    mesh = space.mesh
    lam_, mu = material.lame(3)
    near = space.support_cells(space.enriched_nodes())
    rest = np.setdiff1d(np.arange(mesh.t.shape[1]), near)
    Ks = sp.csr_matrix((space.n_std, space.n_std))
    if rest.size:
        Ks = stiffness_matrix(material, Basis(mesh, ElementTetP1(), elements=rest,
                                              quadrature=cell_rule(mesh)))
    active = np.diff(space.T.indptr) > 0                  # virtual dofs in use
    nverts = mesh.p.shape[1]
    rows, cols, data = [], [], []
    for cells, x, w, side in rules(space, near, plain=1, symmetric=True):
        # the functions φ_k g in use on each cell (slot 6 k + kind)
        vnode = np.arange(6)[None, None, :] * nverts + mesh.t[:, cells].T[:, :, None]
        used = active[3 * vnode].reshape(cells.size, 24)
        patterns, which = np.unique(used, axis=0, return_inverse=True)
        for pattern, slot in enumerate(patterns):   # cells grouped by their functions
            pick = np.flatnonzero(which.ravel() == pattern)
            slots = np.flatnonzero(slot)
            m = slots.size
            step = max(1, CHUNK // w.shape[1])
            a, b = np.triu_indices(m)                     # the pairs a ≤ b: K is symmetric
            half = np.where(a == b, 0.5, 1.0)[:, None, None]
            for k in range(0, pick.size, step):
                sl = pick[k:k + step]
                Ke, vn = _cell_stiffness(space, cells[sl], x[sl], w[sl], side[sl], slots,
                                         (a, b), lam_, mu)
                rows.append(vn[:, a].ravel())
                cols.append(vn[:, b].ravel())
                data.append((Ke * half).reshape(-1, 3, 3))
    nv = space.T.shape[0]
    if data:  # the upper half (diagonal blocks halved) and its transpose
        Ku = summed_blocks(np.concatenate(rows), np.concatenate(cols), np.concatenate(data),
                           nv // 3)
        Kv = (Ku + Ku.T).tocsr()
    else:
        Kv = sp.csr_matrix((nv, nv))
    T = space.T
    pad = sp.block_diag([Ks, sp.csr_matrix((space.N - space.n_std,) * 2)], format="csr")
    return (T.T.tocsr() @ (Kv @ T) + pad).tocsr()    # Tᵀ in CSR: no conversion per product


def mass(space: CrackSpace3D) -> sp.csr_matrix:
    """The mass ∫ u·v on the unknowns [a, b, c] (the inf-sup test's displacement norm,
    :mod:`skxfem.lbb`): the cells in an enriched node's support on the rules of
    :func:`rules` (the almost-polar rules of the front cells are not exact for
    polynomials: a relative 2e-6 below), the other cells by scikit-fem's P1 mass at
    order 2 (exact).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 3)
    >>> V = crack_space_3d(m, crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> U = np.zeros(V.N); U[V.nodal_dofs[1]] = m.p[0]           # u = (0, x, 0)
    >>> round(float(U @ mass(V) @ U), 5)                         # ∫ x² = 1/3
    0.33333
    """
    from skfem.models import mass as p1_mass
    mesh = space.mesh
    near = space.support_cells(space.enriched_nodes())
    rest = np.setdiff1d(np.arange(mesh.t.shape[1]), near)
    Ms = sp.csr_matrix((space.n_std, space.n_std))
    if rest.size:
        basis = Basis(mesh, ElementTetP1(), elements=rest, quadrature=cell_rule(mesh, 2))
        Ms = sp.kron(p1_mass.assemble(basis), sp.identity(3), format="csr")
    nv = space.T.shape[0] // 3                      # virtual nodes
    Mn = sp.csr_matrix((nv, nv))                    # the scalar mass on them
    for cells, x, w, side in rules(space, near, plain=3):
        nc, nq = w.shape
        vals, _, vnode = functions_at(space, np.repeat(cells, nq), x.reshape(-1, 3).T,
                                      side.ravel())
        vals, vnode = vals.reshape(nc, nq, 24), vnode.reshape(nc, nq, 24)[:, 0]
        Me = np.einsum("nqa,nq,nqb->nab", vals, w, vals)          # (nc, 24, 24)
        Mn = Mn + sp.csr_matrix((Me.ravel(), (np.repeat(vnode, 24, axis=1).ravel(),
                                              np.tile(vnode, (1, 24)).ravel())),
                                shape=(nv, nv))
    Mv = sp.kron(Mn, sp.identity(3), format="csr")  # virtual dof 3 j + c
    T = space.T
    pad = sp.block_diag([Ms, sp.csr_matrix((space.N - space.n_std,) * 2)], format="csr")
    return (T.T @ Mv @ T + pad).tocsr()


@dataclass(frozen=True)
class Support3D:
    """Imposed displacements on the nodes of boundary ``facets`` (indices into
    ``mesh.facets``) and/or ``nodes``: u_c = ``value(x)[c]`` for c in ``components``
    (``value``: (3, n) points -> (3, n); None: zero)."""

    facets: ArrayLike | None = None
    nodes: ArrayLike | None = None
    value: Callable | None = None
    components: tuple = (0, 1, 2)


@dataclass(frozen=True)
class Load3D:
    """A traction on boundary ``facets``: ``traction(x)`` (3, n) at points x (3, n), or
    ``traction(x, n)`` with the facets' outward unit normals n (3, n) if ``normal``."""

    facets: ArrayLike
    traction: Callable
    normal: bool | None = None


def outward_normals(mesh, facets: np.ndarray) -> np.ndarray:
    """(3, n) the outward unit normals of boundary facets (triangles) of a tetrahedral
    mesh.

    >>> from skfem import MeshTet1
    >>> m = MeshTet1()
    >>> f = m.facets_satisfying(lambda x: x[2] > 1 - 1e-12)
    >>> outward_normals(m, f).T.tolist()
    [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]
    """
    a, b, c = (mesh.p[:, mesh.facets[k, facets]] for k in range(3))
    n = np.cross((b - a).T, (c - a).T).T
    n = n / np.linalg.norm(n, axis=0)
    centre = mesh.p[:, mesh.t[:, mesh.f2t[0, facets]]].mean(axis=1)
    flip = ((centre - a) * n).sum(axis=0) > 0
    return np.where(flip, -n, n) + 0.0


def mouth_facets(space: CrackSpace3D, facets: np.ndarray) -> np.ndarray:
    """Whether the crack meets each boundary facet (triangle): ψ_h vanishes on it at a
    point where φ_h < 0."""
    geo = space.geometry
    nodes = space.mesh.facets[:, facets]                  # (3, nf)
    ps, ph = geo.psi[nodes], geo.phi[nodes]
    lo = np.where(ps == 0, ph, np.inf).min(axis=0)
    for a, b in ((0, 1), (1, 2), (0, 2)):
        strict = ps[a] * ps[b] < 0
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(strict, ps[a] / (ps[a] - ps[b]), 0.0)
        lo = np.minimum(lo, np.where(strict, ph[a] + t * (ph[b] - ph[a]), np.inf))
    return lo < 0


def supported_dofs(space: CrackSpace3D, supports) -> tuple[np.ndarray, np.ndarray]:
    """The constrained unknowns and their values: the standard unknowns of the supported
    nodes, and the branch unknowns of supported nodes away from the mouth (the boundary
    facets the crack meets) set to zero; at the mouth the support clamps it shut where
    its value is continuous across the crack, and leaves it free where it jumps (as in
    2D: :mod:`skxfem.crack.assembly`'s notes)."""
    return support_dofs(space, supports, lambda f: mouth_facets(space, f))


def facet_rule(space: CrackSpace3D, facets: np.ndarray, n: int = 4):
    """Gauss points on boundary facets split by ψ_h where the crack meets them: points
    (3, m), weights (m,), cells (m,), sides (m,) and the facet of each point (m,)."""
    mesh, geo = space.mesh, space.geometry
    tri = np.transpose(mesh.p[:, mesh.facets[:, facets]], (2, 1, 0))   # (nf, 3, 3)
    ps = geo.psi[mesh.facets[:, facets]].T
    mouth = mouth_facets(space, facets)
    sub, parent, side = split(tri[mouth], ps[mouth])
    pieces = np.concatenate([tri[~mouth], sub])
    owner = np.concatenate([facets[~mouth], facets[mouth][parent]])
    sides = np.concatenate([np.where(ps[~mouth].mean(axis=1) < 0, -1.0, 1.0), side])
    s, w = leggauss(n)
    s, w = (s + 1) / 2, w / 2
    U, V = (a.ravel() for a in np.meshgrid(s, s, indexing="ij"))
    W = np.outer(w, w).ravel() * U
    A, B, C = pieces[:, 0], pieces[:, 1], pieces[:, 2]
    x = (A[:, None] + U[None, :, None] * (B - A)[:, None]
         + (U * V)[None, :, None] * (C - B)[:, None])
    area2 = np.linalg.norm(np.cross(B - A, C - A), axis=1)
    wts = area2[:, None] * W[None]
    cells = np.repeat(mesh.f2t[0, owner], W.size)
    return (x.reshape(-1, 3).T, wts.ravel(), cells, np.repeat(sides, W.size),
            np.repeat(owner, W.size))


def traction_load(space: CrackSpace3D, loads) -> np.ndarray:
    """f = Σ ∫ t · v over the loads' facets, on the unknowns [a, b, c].

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 3)
    >>> V = crack_space_3d(m, crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> top = m.facets_satisfying(lambda x: x[2] > 1 - 1e-12)
    >>> f = traction_load(V, [Load3D(top, lambda x: np.stack([0 * x[0], 0 * x[0], 1 + 0 * x[0]]))])
    >>> round(float(f[V.nodal_dofs[2]].sum()), 12)    # the resultant, 1 × area 1
    1.0
    """
    f = np.zeros(space.N)
    for load in loads:
        fac = check_facets(space.mesh, load.facets, "a load's facets")
        x, w, cells, side, owner = facet_rule(space, fac)
        t = (np.asarray(load.traction(x), float) if load.normal is None else
             np.asarray(load.traction(x, outward_normals(space.mesh, owner)), float))
        if t.shape != x.shape or not np.all(np.isfinite(t)):
            raise ValueError(f"a load's traction must return finite values of shape "
                             f"{x.shape} (3, n), got {t.shape}")
        f += evaluation(space, cells, x, side).T @ (t * w).ravel()
    return f


def body_load(space: CrackSpace3D, force, plain: int = 2) -> np.ndarray:
    """f = ∫ b · v over the body, on the unknowns [a, b, c]: every cell on the rules of
    :func:`rules` (the front cells' sub-tetrahedra on their almost-polar rules), the
    plain uncut cells with ``plain`` points per direction (2: exact for a linear b).
    ``force``: :func:`skxfem.fem.loads.force_field`'s, in 3D.

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 3)
    >>> V = crack_space_3d(m, crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> f = body_load(V, (0.0, 0.0, -2.0))
    >>> round(float(f[V.nodal_dofs[2]].sum()), 12)    # the weight, -2 × volume 1
    -2.0
    """
    b = force_field(force, 3)
    f = np.zeros(space.N)
    for c, x, w, side in rules(space, np.arange(space.mesh.t.shape[1]), plain):
        X = x.reshape(-1, 3).T
        f += evaluation(space, np.repeat(c, w.shape[1]), X, side.ravel()).T @ (
            b(X) * w.ravel()).ravel()
    return f


def nodal_scaling(K: sp.spmatrix, space: CrackSpace3D, fixed: np.ndarray | None = None,
                  inverse: bool = False):
    """The scaling S, K_s = Sᵀ K S, U = S U_s: each branch node's 15 × 15 block [a_k, c_k]
    by the inverse transpose of the Cholesky factor of its diagonal block, 1/√K_ii
    elsewhere (and on any block holding a constrained unknown of ``fixed``): the
    ``"block"`` scaling of :func:`skxfem.crack.space.nodal_scaling` (``inverse``: (S, S⁻¹))."""
    return _nodal_scaling(K, space, "block", fixed, inverse)
