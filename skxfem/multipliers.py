r"""Interface multipliers: the naive space and the coupling with the jump (paper §4.2).

The naive space puts one multiplier λ_e at the intersection point of every
strictly cut edge e ∈ S_e and interpolates linearly on the interface facets
(eq. 12): λ_h(x) = Σ_k λ_k N_k(x), N_k the P1 functions of a facet.

Every multiplier space of skxfem, naive or stabilised, is one mechanism: a
sparse prolongation P from independent multipliers μ to the edge multipliers,
λ = P μ (naive: P = I).  The coupling of a tie law is assembled once on the
edge multipliers and reduced by Pᵀ.

Two tie laws (for a vector multiplier the components are stored component-major):

* ``bonded``: [[u]] = 0, B[(c, e), :] = ∫_Γ N_e [[v]]_c;
* ``bilateral``: [[u]]·n = 0, B[e, :] = ∫_Γ N_e [[v]]·n.

>>> from skfem import MeshQuad1
>>> from skxfem.levelset import plane
>>> from skxfem.cut import cut
>>> m = MeshQuad1().refined(2)
>>> rule = interface_rule(m, cut(m, plane((0, 0.3), (0, 1))))
>>> round(float(rule.weights.sum()), 12)   # |Γ| = 1
1.0
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem.quadrature import get_quadrature
from skfem.refdom import RefLine, RefTri

from .cut import Cut
from .enrich import XSpace, jump_matrix
from .scene.laws import COUPLING, SPACES, TIE_LAWS

__all__ = ["Space", "naive", "fixed_jumps", "normal_fixed", "direction_fixed", "SPACES",
           "InterfaceRule", "interface_rule", "coupling", "interface_mass", "LAWS"]

LAWS = tuple(law for law in TIE_LAWS if COUPLING[law] != "none")
"""The ties whose multipliers couple the jump (``free`` has none)."""


@dataclass(frozen=True)
class Space:
    """A multiplier space: λ (one per cut edge) = P μ (the independent multipliers).

    Attributes
    ----------
    name : one of :data:`SPACES`.
    P : (n_edges, n_μ) CSR prolongation.
    vital : (n_edges,) bool, algo2's S_ve.  ``groups`` : (n_edges,) the column
        of μ of each vital edge, -1 elsewhere.
    winners : (n_μ,) algo1's winner nodes in the order picked: column j is
        the multiplier of node ``winners[j]``.
    """

    name: str
    P: sp.csr_matrix
    vital: np.ndarray | None = None
    groups: np.ndarray | None = None
    winners: np.ndarray | None = None

    @property
    def size(self) -> int:
        return self.P.shape[1]


def naive(cut: Cut) -> Space:
    """One free multiplier per cut edge: P = I."""
    return Space("naive", sp.identity(cut.edge_ids.size, format="csr"))


def fixed_jumps(V: XSpace, dofs: np.ndarray) -> np.ndarray:
    """(dim, nnodes) bool: the enriched dof of component c at node j is among
    the constrained unknowns ``dofs`` (held at zero by a support, see
    :func:`skxfem.problem.constrained_dofs`).

    On an edge only the P1/Q1 functions of its two ends do not vanish, so
    the jump [[u_h]]_c = -2 Σⱼ φⱼ bⱼ_c at the point of a cut edge whose two
    ends are fixed for c is zero for every admissible U: a support holds it.
    """
    fixed = np.zeros(V.n_std, dtype=bool)
    enr = np.asarray(dofs)
    fixed[V.enr_dofs[enr[enr >= V.n_std] - V.n_std]] = True
    return fixed[V.basis.nodal_dofs]


def normal_fixed(fixed: np.ndarray, cut: Cut, tol: float = 1e-12) -> np.ndarray:
    """(nnodes,) bool: the normal jump [[u_h]]·n is held at node j, i.e. j is
    an end of a cut edge and is fixed (``fixed`` from :func:`fixed_jumps`) in
    every component in which a normal of the interface facets around j's cut
    edges has a part (> ``tol``): :func:`direction_fixed` of the normals."""
    return direction_fixed(fixed, cut, cut.normals, tol)


def direction_fixed(fixed: np.ndarray, cut: Cut, directions: np.ndarray,
                    tol: float = 1e-12) -> np.ndarray:
    """(nnodes,) bool: the jump along ``directions`` (dim, n_facets), one unit
    vector per interface facet, is held at node j: j is an end of a cut edge
    and is fixed in every component in which the direction of a facet around
    j's cut edges has a part (> ``tol``).

    >>> import numpy as np
    >>> from skfem import MeshQuad1
    >>> from skxfem.levelset import plane
    >>> from skxfem.cut import cut as cut_mesh
    >>> m = MeshQuad1().refined(1)
    >>> cut = cut_mesh(m, plane((0, 0.3), (0, 1)))
    >>> fixed = np.zeros((2, m.p.shape[1]), bool); fixed[0, m.p[0] == 0] = True
    >>> t = np.array([[1.0], [0.0]]) * np.ones(cut.facets.shape[1])   # the tangent e_x
    >>> np.flatnonzero(direction_fixed(fixed, cut, t)).tolist() == np.flatnonzero(
    ...     (m.p[0] == 0) & np.isin(np.arange(m.p.shape[1]), cut.edges)).tolist()
    True
    """
    dim = fixed.shape[0]
    part = np.zeros((dim, cut.edge_ids.size), dtype=bool)
    for k in range(cut.facets.shape[0]):
        ok = cut.facets[k] >= 0                      # -1: no cut point (a crack's tip)
        for comp in range(dim):
            np.logical_or.at(part[comp], cut.facets[k][ok], np.abs(directions[comp][ok]) > tol)
    at_node = np.zeros(fixed.shape, dtype=bool)
    for i in (0, 1):
        for comp in range(dim):
            np.logical_or.at(at_node[comp], cut.edges[i], part[comp])
    return np.all(fixed | ~at_node, axis=0) & at_node.any(axis=0)


@dataclass(frozen=True)
class InterfaceRule:
    """Quadrature on the interface facets Γ_h.

    Attributes
    ----------
    points, normals : (dim, nq) physical points and unit normals (into Ω⁺).
    weights : (nq,) physical weights; they sum to |Γ_h|.
    cells : (nq,) parent cell; ``ref`` : (dim, nq) reference coordinates in it.
    N : (nq, n_edges) sparse: the P1 multiplier functions at the points.
    """

    points: np.ndarray
    normals: np.ndarray
    weights: np.ndarray
    cells: np.ndarray
    ref: np.ndarray
    N: sp.csr_matrix


def interface_rule(mesh, cut: Cut, order: int = 4) -> InterfaceRule:
    """Map a segment/triangle rule of ``order`` onto every interface facet.

    The default order 4 integrates exactly a P1 multiplier times the trace of
    a trilinear (hexahedral) function on a planar facet (degree 1 + 3).
    """
    dim = mesh.dim()
    if dim == 2:
        X, W = get_quadrature(RefLine, order)
        L = np.vstack([1.0 - X[0], X[0]])  # barycentric (2, nq0)
    else:
        X, W = get_quadrature(RefTri, order)
        L = np.vstack([1.0 - X[0] - X[1], X[0], X[1]])
        W = 2.0 * W  # reference triangle area 1/2 → weights summing to 1
    nf, nq0 = cut.facets.shape[1], W.size
    ref = np.einsum("vcf,vq->cfq", cut.facet_ref, L).reshape(dim, -1)
    cells = np.repeat(cut.facet_cell, nq0)
    points = mesh.mapping().F(ref[:, :, None], tind=cells)[:, :, 0]
    weights = (cut.measures[:, None] * W[None, :]).ravel()
    normals = np.repeat(cut.normals, nq0, axis=1)
    rows = np.repeat(np.arange(nf * nq0), dim)
    cols = np.repeat(cut.facets.T, nq0, axis=0).ravel()
    vals = np.tile(L.T, (nf, 1)).ravel()
    N = sp.csr_matrix((vals, (rows, cols)), shape=(nf * nq0, cut.edge_ids.size))
    return InterfaceRule(points, normals, weights, cells, ref, N)


def coupling(V: XSpace, rule: InterfaceRule, law: str, J=None) -> sp.csr_matrix:
    """B on the edge multipliers: ``(dim·n_edges, N)`` bonded, ``(n_edges, N)``
    bilateral.

    ``J`` is the jump operator at the rule's points (:func:`skxfem.enrich.jump_matrix`,
    (dim·nq, N), component-major); built here if not given.
    """
    if law not in LAWS:
        raise ValueError(f"law must be one of {LAWS}, got {law!r}")
    dim, nq = V.mesh.dim(), rule.weights.size
    if J is None:
        J = jump_matrix(V, rule.cells, rule.ref)
    NW = (rule.N.T @ sp.diags(rule.weights)).tocsr()  # (n_edges, nq)
    blocks = [NW @ J[c * nq:(c + 1) * nq] for c in range(dim)]
    if law == "bonded":
        return sp.vstack(blocks, format="csr")
    Jn = sum(sp.diags(rule.normals[c]) @ J[c * nq:(c + 1) * nq] for c in range(dim))
    return (NW @ Jn).tocsr()


def interface_mass(rule: InterfaceRule) -> sp.csr_matrix:
    """M = ∫_Γ N_e N_f on the edge multipliers."""
    return (rule.N.T @ sp.diags(rule.weights) @ rule.N).tocsr()
