r"""The X-FEM space of a crack: standard, Heaviside and branch-enriched unknowns.

With φᵢ the P1/Q1 shape functions, H = sign ψ (±1 on Ω^±) and F_l the four branch
functions (:mod:`skxfem.crack.branch`), the displacement is

.. math:: u_h = \sum_i a_i \varphi_i + \sum_{j \in J} b_j \varphi_j (H - H_j)
               + \sum_{k \in K} \sum_{l=1}^4 c_{kl}\, \varphi_k (F_l - F_l(x_k)),

*shifted* as in :mod:`skxfem.enrich`: every enriched function vanishes at the
nodes, so aᵢ is the displacement of node i.  The sets of nodes:

* K, **branch** nodes: ``"topological"``, the nodes of the tip cells;
  ``"geometric"``, the nodes within the radius r_e of a tip (and the tip cells'
  nodes): a fixed area, whatever h (Béchet et al. 2005, Laborde et al. 2005);
* J, **Heaviside** nodes: the nodes of split cells (the crack crosses their
  support completely) not in K, whose support holds a part of positive area on the
  other side of the crack (a crack along mesh edges only touches the supports of the
  nodes beside it: φⱼ(H - Hⱼ) would vanish there).  H_j = sign ψ(x_j), 0 for a node
  on the crack: φⱼ H.

Unknowns [a, b, c], node by node with the component fastest (as
:mod:`skxfem.enrich`): b_j of Heaviside node j at ``n_std + 2 j' + comp``, c_{kl}
of branch node k at ``n_std + n_heav + 8 k' + 2 l + comp``.

How the pieces are integrated: one virtual space
-------------------------------------------------
Each enriched function is a standard one times a global function g of six
*kinds*, g ∈ {1, H, F₁, F₂, F₃, F₄}, minus a multiple of the standard one:
φⱼ(H - H_j) = φⱼ H - H_j φⱼ.  So u_h = Σ_g Σ_i ũ_{g,i} φᵢ g with the *virtual*
coefficients ũ = T U, T a sparse (6 n_std, N) matrix (:attr:`CrackSpace.T`), and
every integral is that of the virtual functions φᵢ g, with

.. math:: \nabla(\varphi_i g) = g\,\nabla\varphi_i + \varphi_i\,\nabla g,\qquad
          \nabla F_l = \partial_1 F_l\, \nabla\varphi_h + \partial_2 F_l\,\nabla\psi_h ,

F_l a function of the interpolated level sets (x₁, x₂) = (φ_h, ψ_h), so that its
discontinuity lies on the crack of the mesh (r = √(φ_h² + ψ_h²), θ = atan2(ψ_h, φ_h),
θ = ±π on the faces, by the side of the sub-cell).  Matrices are then Tᵀ Ã T.

Conditioning
------------
Geometric enrichment adds many nearly dependent functions far from the tip
(F_l is smooth there and φ_k(F_l - F_l(x_k)) nearly a combination of the
neighbours' standard functions).  The cure of Béchet et al. (2005): scale each
branch node's block of unknowns [a_k, c_k] (2 + 8) by the inverse of the Cholesky
factor of its diagonal block, every other unknown by 1/√K_ii (:func:`nodal_scaling`).
Measured (:func:`condition_number` of the supported stiffness, Williams square, E = 1,
triangles, r_e = 0.3):

======  ===========  ===========  ===========  ===========  ===========  ===========
1/h     topological  topo. Jacobi topo. block  geometric    geo. Jacobi  geo. block
======  ===========  ===========  ===========  ===========  ===========  ===========
11      1.35e4       346          284          1.02e8       3.78e5       282
21      2.66e4       1.26e3       1.04e3       9.68e9       1.04e7       1.05e3
41      5.24e4       4.78e3       3.97e3       1.18e12      3.13e8       4.01e3
81      1.04e5       1.86e4       1.55e4       1.05e14      7.25e9       1.57e4
======  ===========  ===========  ===========  ===========  ===========  ===========

Jacobi alone does not cure it: the near dependence is within a node's block.

>>> from skfem import MeshTri1
>>> from skxfem.crack.geometry import crack_geometry
>>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
>>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5), "topological")
>>> V.n_std, V.heaviside.size, V.branch.size, V.N
(72, 4, 4, 112)
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementVector
from skfem.assembly import CellBasis

from ..fem.quadrature import cell_rule
from ..linalg.blocks import block_scaling
from .branch import branch, branch_local_gradient, side_angle
from .dofs import EnrichedUnknowns, virtual_map
from .geometry import AREA_TOL, CrackGeometry, check_geometry, check_mesh_2d
from .radius import ENRICHMENTS, enrichment_radius, geometric_nodes

__all__ = ["KINDS", "ENRICHMENTS", "CrackSpace",
           "crack_depth", "crack_space", "kinds_at", "evaluation", "evaluation_at", "Evaluation",
           "nodal_scaling", "condition_number"]

KINDS = ("1", "H", "F1", "F2", "F3", "F4")
"""The six kinds g of virtual functions φᵢ g (module notes)."""


@dataclass(frozen=True)
class CrackSpace(EnrichedUnknowns):
    """The enriched space of a crack (module notes).

    Attributes
    ----------
    mesh, geometry : the mesh and its :class:`skxfem.crack.geometry.CrackGeometry`.
    basis : the standard vector ``skfem.Basis`` (centroid rule): it numbers the
        standard dofs.
    heaviside : (nh,) Heaviside nodes J; ``H_node`` (nh,) H(x_j) ∈ {-1, 0, 1}.
    branch : (nb,) branch nodes K; ``F_node`` (4, nb) F_l(x_k).
    enrichment : ``"topological"`` or ``"geometric"``; ``radius`` r_e (geometric).
    T : (6 n_std, N) the virtual coefficients ũ = T U of the unknowns U = [a, b, c].
    """

    mesh: object
    geometry: CrackGeometry
    basis: CellBasis = field(repr=False)
    heaviside: np.ndarray
    H_node: np.ndarray
    branch: np.ndarray
    F_node: np.ndarray
    enrichment: str
    radius: float | None
    T: sp.csr_matrix = field(repr=False, compare=False)

    @property
    def n_std(self) -> int:
        return int(self.basis.N)

    @property
    def nodal_dofs(self) -> np.ndarray:
        """(2, nverts) the standard unknowns a of each node and component."""
        return self.basis.nodal_dofs


def _polar_nodes(geometry: CrackGeometry, nodes: np.ndarray):
    """(r, θ) at nodes from the level sets; a node on a face counts on Ω⁺ (θ = +π)."""
    phi, psi = geometry.phi[nodes], geometry.psi[nodes]
    return np.hypot(phi, psi), np.arctan2(np.where(psi == 0, 0.0, psi), phi)


def crack_depth(geometry: CrackGeometry) -> float:
    """The crack's depth a: the largest distance from a point of the crack (an end of its
    pieces) to its nearest tip; an edge crack's length, a centre crack's half-length.
    The default enrichment radius is at most :data:`skxfem.crack.radius.DEPTH_CAP` of it.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 11), np.linspace(0, 1, 11))
    >>> round(crack_depth(crack_geometry(m, m.p[1] - 0.55, m.p[0] - 0.35)), 12)
    0.35
    >>> round(crack_depth(crack_geometry(m, m.p[1] - 0.55, np.abs(m.p[0] - 0.5) - 0.2)), 12)
    0.2
    """
    x = geometry.segments.transpose(1, 0, 2).reshape(2, -1)           # the pieces' ends
    d = np.linalg.norm(x[:, :, None] - geometry.tips[:, None], axis=0)
    return float(d.min(axis=1).max())


def crack_space(mesh, geometry: CrackGeometry, enrichment: str = "geometric",
                radius: float | None = None) -> CrackSpace:
    """The :class:`CrackSpace` of a crack on ``mesh``.

    Parameters
    ----------
    mesh : the ``MeshTri1`` or ``MeshQuad1`` of ``geometry``.
    geometry : :func:`skxfem.crack.geometry.crack_geometry` of the crack.
    enrichment : ``"topological"`` (the tip cells' nodes) or ``"geometric"`` (the nodes
        within ``radius`` of a tip).
    radius : r_e > 0 for geometric enrichment; default
        :func:`skxfem.crack.radius.default_enrichment_radius` (0.2 mesh diameters, at
        most three crack depths :func:`crack_depth`, and at least 16/3 tip-cell sizes:
        the default interaction domain inside 0.75 r_e).

    Examples
    --------
    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 12), np.linspace(0, 1, 12))
    >>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5)
    >>> [crack_space(m, g, k, 0.3).branch.size for k in ENRICHMENTS]
    [4, 32]
    """
    check_geometry(geometry, check_mesh_2d(mesh), CrackGeometry, "crack_geometry")
    given = radius is not None
    radius = enrichment_radius(            # the tip cells' largest extent: h
        mesh, enrichment, radius,
        lambda: np.ptp(mesh.p[:, mesh.t[:, geometry.tip_cells]], axis=1).max(),
        lambda: crack_depth(geometry))
    d = None if radius is None else np.min(
        np.linalg.norm(mesh.p[:, :, None] - geometry.tips[:, None], axis=0), axis=1)
    branch_nodes = geometric_nodes(mesh.t[:, geometry.tip_cells].ravel(), d, radius, given)
    heav = np.setdiff1d(np.unique(mesh.t[:, geometry.split_cells]), branch_nodes)
    H_node = np.sign(geometry.psi[heav])
    keep = _far_side(mesh, geometry)[heav, (H_node > 0).astype(int)] | (H_node == 0)
    heav, H_node = heav[keep], H_node[keep]
    F_node = branch(*_polar_nodes(geometry, branch_nodes))
    basis = Basis(mesh, ElementVector(mesh.elem()), quadrature=cell_rule(mesh, 0))
    T = virtual_map(basis.nodal_dofs, heav, H_node, branch_nodes, F_node)
    return CrackSpace(mesh, geometry, basis, heav, H_node, branch_nodes, F_node,
                      enrichment, radius, T)


def _far_side(mesh, geometry: CrackGeometry) -> np.ndarray:
    """(nverts, 2): does the support of each node hold a part of positive area of Ω⁺
    (column 0: the far side of a node of Ω⁻) or of Ω⁻ (column 1: the far side of a node
    of Ω⁺)?  A crack along mesh edges touches the supports of the nodes beside it
    without crossing them: their φⱼ(H - Hⱼ) would vanish."""
    nc = mesh.t.shape[1]
    has = np.zeros((nc, 2), dtype=bool)                   # [cell, (Ω⁺, Ω⁻)]
    whole = geometry.side != 0
    has[whole, 0], has[whole, 1] = geometry.side[whole] > 0, geometry.side[whole] < 0
    d1 = geometry.sub_ref[:, 1] - geometry.sub_ref[:, 0]
    d2 = geometry.sub_ref[:, 2] - geometry.sub_ref[:, 0]
    area = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) > 2 * AREA_TOL
    np.logical_or.at(has[:, 0], geometry.sub_cell[area & (geometry.sub_side > 0)], True)
    np.logical_or.at(has[:, 1], geometry.sub_cell[area & (geometry.sub_side < 0)], True)
    out = np.zeros((mesh.p.shape[1], 2), dtype=bool)
    for k in range(mesh.t.shape[0]):                      # the 3 or 4 nodes of a cell
        np.logical_or.at(out, mesh.t[k], has)
    return out


def kinds_at(space: CrackSpace, scalar: CellBasis, side: np.ndarray | None = None
             ) -> tuple[np.ndarray, np.ndarray]:
    """The six kinds g and their gradients at the quadrature points of a scalar basis.

    ``side`` (nel, nqp): the side ±1 of each point (a sub-cell rule's ``V``); default
    the side of each cell (:attr:`CrackGeometry.side`, for cells the crack does not
    cross).  On the faces' side of the tip (φ_h < 0), in the cells the crack cuts, θ
    takes the side's sign, so a point of a sub-cell counts on its own side; a cell
    that ψ_h crosses ahead of the tip is cut by no crack, and θ is atan2's there.

    Returns
    -------
    g (6, nel, nqp), dg (6, 2, nel, nqp).
    """
    geo = space.geometry
    cells = scalar.tind
    if side is None:
        side = np.broadcast_to(geo.side[cells][:, None], scalar.dx.shape).astype(float)
        if np.any(side == 0):
            raise ValueError("side is needed on split and tip cells (a sub-cell rule's V)")
    phi, psi = scalar.interpolate(geo.phi), scalar.interpolate(geo.psi)
    phi_v, psi_v = np.asarray(phi), np.asarray(psi)
    r = np.hypot(phi_v, psi_v)
    theta = side_angle(phi_v, psi_v, side, (geo.side[cells] == 0)[:, None])
    shape = (6,) + scalar.dx.shape
    g, dg = np.zeros(shape), np.zeros((6, 2) + scalar.dx.shape)
    g[0] = 1.0
    g[1] = np.where(side == 0, 1.0, side)                 # padding points: any value
    live = r > 0
    rr, tt = np.where(live, r, 1.0), np.where(live, theta, 0.0)
    g[2:] = branch(rr, tt) * live
    loc = branch_local_gradient(rr, tt) * live            # (4, 2, nel, nqp)
    dg[2:] = loc[:, :1] * phi.grad[None] + loc[:, 1:] * psi.grad[None]
    return g, dg


@dataclass(frozen=True)
class Evaluation:
    """Operators from the unknowns U to the field at points: ``value @ U`` (2 npts,
    component-major: all u_x, then all u_y) and ``grad @ U`` (4 npts, rows
    (2 i + j) npts + p for ∂u_i/∂x_j at point p)."""

    value: sp.csr_matrix
    grad: sp.csr_matrix

    def at(self, U: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """u (2, npts) and ∇u (2, 2, npts) of the unknowns ``U``."""
        u = (self.value @ U).reshape(2, -1)
        return u, (self.grad @ U).reshape(2, 2, -1)


def evaluation(space: CrackSpace, cells: np.ndarray, ref: np.ndarray,
               side: np.ndarray | None = None) -> Evaluation:
    """Every unknown's basis function, value and gradient, at points of given cells.

    Parameters
    ----------
    cells : (npts,) the cell of each point.
    ref : (2, npts) the points in their cell's reference coordinates.
    side : (npts,) the side ±1 of each point (needed in split and tip cells).

    Returns
    -------
    Evaluation
        Sparse operators on the unknowns [a, b, c].

    Examples
    --------
    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> E = evaluation(V, np.array([0]), np.array([[0.2], [0.3]]))
    >>> U = np.zeros(V.N); U[V.basis.nodal_dofs[0]] = 1.0          # u = (1, 0)
    >>> E.at(U)[0].ravel().tolist()
    [1.0, 0.0]
    """
    cells, ref = np.asarray(cells), np.asarray(ref, float)
    npts = cells.size
    side = None if side is None else np.asarray(side, float)[:, None]
    scalar = Basis(space.mesh, space.mesh.elem(), elements=cells,
                   quadrature=(ref[:, :, None], np.ones((npts, 1))))
    g, dg = kinds_at(space, scalar, side)                 # (6, npts, 1), (6, 2, npts, 1)
    g, dg = g[..., 0], dg[..., 0]
    n = space.n_std
    nd = space.basis.nodal_dofs                           # (2, nverts)
    rows_v, rows_g, cols_v, cols_g, vals_v, vals_g = [], [], [], [], [], []
    pts = np.arange(npts)
    for k in range(scalar.Nbfun):                         # the 3 or 4 nodes of a cell
        N = np.asarray(scalar.basis[k][0])[:, 0]
        dN = scalar.basis[k][0].grad[:, :, 0]              # (2, npts)
        node = space.mesh.t[k, cells]
        for kind in range(6):
            val = N * g[kind]
            grad = dN * g[kind] + N * dg[kind]            # (2, npts)
            for c in range(2):
                col = kind * n + nd[c, node]
                rows_v.append(c * npts + pts)
                cols_v.append(col)
                vals_v.append(val)
                for j in range(2):
                    rows_g.append((2 * c + j) * npts + pts)
                    cols_g.append(col)
                    vals_g.append(grad[j])
    shape = (6 * n,)

    def assemble(rows, cols, vals, nrows):
        A = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(nrows,) + shape)
        return (A @ space.T).tocsr()

    return Evaluation(assemble(rows_v, cols_v, vals_v, 2 * npts),
                      assemble(rows_g, cols_g, vals_g, 4 * npts))


def evaluation_at(space: CrackSpace, cells: np.ndarray, x: np.ndarray,
                  side: np.ndarray | None = None) -> Evaluation:
    """:func:`evaluation` at physical points ``x`` (2, npts) of the given ``cells``
    (their reference coordinates by the inverse of each cell's map).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5), "geometric", 0.5)
    >>> U = np.zeros(V.N); U[V.branch_dofs()[:, 0, 1]] = 1.0    # c = 1 on F₁, along y
    >>> x = np.array([[0.3, 0.3], [0.5, 0.5]])        # one point of the crack, both faces
    >>> cells = m.element_finder()(*x)
    >>> u, _ = evaluation_at(V, cells, x, np.array([-1.0, 1.0])).at(U)
    >>> bool(abs(u[1, 1] - u[1, 0] - 2 * np.sqrt(0.2)) < 1e-12)   # F₁ = ±√r on the faces
    True
    """
    cells = np.asarray(cells)
    ref = space.mesh.mapping().invF(np.asarray(x, float)[:, :, None], tind=cells)[:, :, 0]
    return evaluation(space, cells, ref, side)


def nodal_scaling(K: sp.spmatrix, space: EnrichedUnknowns, kind: str | None = "block",
                  fixed: np.ndarray | None = None, inverse: bool = False):
    """The scaling S of the unknowns, K_s = Sᵀ K S, U = S U_s (module notes), of a
    :class:`CrackSpace` or a :class:`skxfem.crack.space3d.CrackSpace3D`.

    ``kind``: ``"block"`` (Béchet: each branch node's block [a_k, c_k] by the inverse
    transpose of the Cholesky factor of its diagonal block, 1/√K_ii elsewhere),
    ``"jacobi"`` (1/√K_ii everywhere) or None (the identity).  ``fixed``: the
    constrained unknowns; a branch node with one among its block is scaled by
    1/√K_ii, so that S is diagonal on every constrained unknown.  ``inverse``: return
    (S, S⁻¹).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.fem.material import Material
    >>> from skxfem.crack.assembly import stiffness
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> K = stiffness(V, Material(1.0, 0.3))
    >>> S = nodal_scaling(K, V)
    >>> blk = V.branch_blocks()[0]
    >>> bool(np.allclose((S.T @ K @ S)[blk][:, blk].toarray(), np.eye(10)))
    True
    """
    N = K.shape[0]
    if kind is None:
        I = sp.identity(N, format="csr")
        return (I, I) if inverse else I
    if kind not in ("block", "jacobi"):
        raise ValueError(f"kind must be 'block', 'jacobi' or None, got {kind!r}")
    K = K.tocsr()
    d = K.diagonal()
    if np.any(d <= 0):
        raise ValueError(f"the stiffness has {int((d <= 0).sum())} non-positive diagonal "
                         f"entries: an enriched function vanishes on its support")
    s = 1 / np.sqrt(d)
    if kind == "jacobi" or space.branch.size == 0:
        S = sp.diags(s).tocsr()
        return (S, sp.diags(1 / s).tocsr()) if inverse else S
    B = space.branch_blocks()                              # (nb, 5 d)
    if fixed is not None and len(fixed):
        B = B[~np.isin(B, fixed).any(axis=1)]
    S, Sinv = block_scaling(K, [B], s)
    return (S, Sinv) if inverse else S


def condition_number(K: sp.spmatrix, free: np.ndarray) -> float:
    """The spectral condition number λ_max/λ_min of the SPD matrix K[free][:, free]
    (Lanczos for λ_max, shift-invert at 0 for λ_min), from a fixed start vector so
    that a run repeats the last one to the digit.

    >>> condition_number(sp.diags([1.0, 2.0, 4.0, 8.0]), np.arange(4))
    8.0
    """
    from scipy.sparse.linalg import eigsh

    A = sp.csc_matrix(K)[free][:, free]
    if A.shape[0] <= 50:
        ev = np.linalg.eigvalsh(A.toarray())
        return float(ev[-1] / ev[0])
    v0 = np.random.default_rng(0).standard_normal(A.shape[0])   # reproducible
    big = eigsh(A, k=1, which="LA", return_eigenvectors=False, tol=1e-8, v0=v0)[0]
    small = eigsh(A, k=1, sigma=0.0, which="LM", return_eigenvectors=False, tol=1e-8,
                  v0=v0)[0]
    return float(big / small)
