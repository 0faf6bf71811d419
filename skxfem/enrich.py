r"""The X-FEM displacement space: standard plus Heaviside-enriched dofs (eq. 11).

The paper's approximation is u_h = Σᵢ aᵢ φᵢ + Σⱼ bⱼ φⱼ H, with j over the
enriched nodes (the nodes of cut cells).  We use the *shifted* form

.. math:: u_h = \sum_i a_i \varphi_i + \sum_j b_j \varphi_j (H - H_j),
          \qquad H_j = H(x_j),

which spans exactly the same space (φⱼH and φⱼ are both in it), so every
result of the paper is unchanged, while aᵢ is now the displacement *at node i*:
Dirichlet conditions are imposed on aᵢ alone.  The jump is the paper's:

.. math:: [[u_h]] = u_h^- - u_h^+ = -2 \sum_j \varphi_j b_j .

Assembly uses scikit-fem throughout.  With K the standard stiffness
∫ σ(φᵢ):ε(φⱼ), K_H the signed stiffness ∫ H σ(φᵢ):ε(φⱼ) and D = diag(H_j),

.. math:: K_{ab} = K_H[:, E] - K[:, E] D, \qquad
          K_{bb} = K[E,E] + D K[E,E] D - D K_H[E,E] - K_H[E,E] D,

because H² = 1.  K_H needs the sub-cell quadrature of :mod:`skxfem.cut`; on
uncut cells H is the cell's constant side.  With K^± the stiffness of Ω^±,
K = K⁺ + K⁻ and K_H = K⁺ - K⁻ = s(2Kˢ - K) for either side s.  Only the
columns of enriched dofs of K_H enter, so K is assembled on every cell whole
(the integrand is a polynomial on a cut cell too) and Kˢ on one side, on the
cells of enriched nodes only (:func:`skxfem.sides.parts`; on hexahedra and
prisms with a moment-fitted rule, :mod:`skxfem.moments`).  The stiffness runs
on *scalar* bases (built once by :func:`space` and shared with
:func:`far_side_fraction`), from scalar forms (:func:`skxfem.material.stiffness_matrix`).

>>> from skfem import MeshTri1
>>> from skxfem.levelset import plane
>>> from skxfem.cut import cut
>>> m = MeshTri1().refined(2)
>>> V = space(m, cut(m, plane((0, 0.3), (0, 1))))
>>> V.n_std, V.n_enr
(50, 20)
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from skfem import Basis, BilinearForm, ElementVector, LinearForm
from skfem.assembly import CellBasis
from skfem.helpers import dot

from .cut import Cut
from .evaluate import evaluation_matrix
from .material import Material, stiffness_matrix
from .quadrature import cell_rule, exact_orders
from .sides import Parts, parts, side_bases

__all__ = ["XSpace", "space", "stiffness", "mass", "enriched_matrix", "enriched_blocks",
           "signed_bases", "far_side_fraction", "enriched_load",
           "jump_matrix", "split_fields"]


@dataclass(frozen=True)
class XSpace:
    """An X-FEM vector displacement space on a cut mesh.

    Attributes
    ----------
    mesh, cut
        The mesh and its :class:`skxfem.cut.Cut`.
    basis
        The standard vector ``skfem.Basis``: it numbers the dofs and evaluates
        fields.  Its quadrature is the one-point centroid rule, so that it
        holds one value per cell; every integral over the cells uses
        :func:`side_bases` (the stiffness, at ``rule``).
    enr_dofs : (n_enr,) standard dofs of the enriched nodes, ordered node by
        node (component fastest); unknown ``n_std + k`` is the enriched dof of
        ``enr_dofs[k]``.
    H_node : (n_enr,) H(x_j) of the node of each enriched dof.
    rule : (X, W), the cell rule of the stiffness on uncut cells.
    parts : the scalar :class:`skxfem.sides.Parts` at ``rule``, which
        :func:`stiffness` reuses (None: built when needed).
    """

    mesh: object
    cut: Cut
    basis: CellBasis
    enr_dofs: np.ndarray
    H_node: np.ndarray
    rule: tuple = field(repr=False, compare=False, default=None)
    parts: Parts | None = field(default=None, repr=False, compare=False)

    @property
    def n_std(self) -> int:
        return int(self.basis.N)

    @property
    def n_enr(self) -> int:
        return self.enr_dofs.size

    @property
    def N(self) -> int:
        return self.n_std + self.n_enr


@LinearForm
def _signed_mass(v, w):
    return w["H"] * v


def far_side_fraction(mesh, cut: Cut, scalar_parts: Parts | None = None) -> np.ndarray:
    """For each node j: ∫ φⱼ over the side of Γ opposite to the node, / ∫ φⱼ.

    The shifted enrichment φⱼ(H - Hⱼ) lives on that far side only; where it is
    a sliver the enriched dof carries no information but spoils the
    conditioning (see :func:`space`).  A node of no cut cell has no far
    side: 0.  ``scalar_parts``: :func:`skxfem.sides.parts` of the scalar
    element at a rule exact for φⱼ (default: the stiffness' rule).
    """
    p = scalar_parts or parts(mesh, cut, mesh.elem())
    total, signed = p.signed(lambda b: _signed_mass.assemble(b, H=np.ones(b.dx.shape)))
    j = cut.enriched  # signed is exact there only
    frac = np.zeros(mesh.p.shape[1])
    frac[j] = 0.5 * (total[j] - np.sign(cut.psi[j]) * signed[j]) / total[j]
    return np.clip(frac, 0.0, 1.0)


def space(mesh, cut: Cut, order: int | None = None, sliver: float = 1e-8) -> XSpace:
    """Build the X-FEM space of ``mesh`` cut by ``cut``.

    Nodes of cut cells are enriched, except those whose far-side fraction
    (:func:`far_side_fraction`) is below ``sliver``: Γ only grazes a corner of
    their support (a plane a tiny distance from a node), the enriched
    function is numerically zero and the other nodes' enrichment carries the
    jump there.
    """
    if not sliver >= 0:
        raise ValueError(f"sliver must be a non-negative fraction, got {sliver!r}")
    rule = cell_rule(mesh, order or exact_orders(mesh)[0])
    basis = Basis(mesh, ElementVector(mesh.elem()), quadrature=cell_rule(mesh, 0))
    scalar = parts(mesh, cut, mesh.elem(), rule)
    nodes = cut.enriched[far_side_fraction(mesh, cut, scalar)[cut.enriched] >= sliver]
    enr = basis.nodal_dofs[:, nodes].T  # (nenr_nodes, dim)
    H_node = np.repeat(np.sign(cut.psi[nodes]), mesh.dim())
    return XSpace(mesh, cut, basis, enr.ravel(), H_node, rule, scalar)


def signed_bases(V: XSpace, orders: tuple[int, int] | None = None):
    """The pairs (basis, H) covering the mesh, H = ±1 the constant value of
    the Heaviside function on that basis: see :func:`skxfem.sides.side_bases`.

    ``orders`` (cell, sub-simplex): the quadrature orders; default those of
    ``V`` (its stiffness rule and the stiffness' sub-simplex order)."""
    if orders is None:
        return side_bases(V.mesh, V.cut, V.basis.elem, V.rule)
    return side_bases(V.mesh, V.cut, V.basis.elem, cell_rule(V.mesh, orders[0]), orders[1])


def enriched_blocks(V: XSpace, A, AH) -> sp.csr_matrix:
    """The X-FEM matrix on [a, b] from A = ∫ g(φᵢ, φⱼ) and A_H = ∫ H g(φᵢ, φⱼ)
    on the standard dofs: the blocks of the module notes (H² = 1).  Only the
    columns of the enriched dofs of A_H are read."""
    A, AH = A.tocsr(), AH.tocsr()
    E = V.enr_dofs
    D = sp.diags(V.H_node)
    Aab = AH[:, E] - A[:, E] @ D
    AEE, AHEE = A[E][:, E], AH[E][:, E]
    Abb = AEE + D @ AEE @ D - D @ AHEE - AHEE @ D
    return sp.bmat([[A, Aab], [Aab.T, Abb]], format="csr")


def enriched_matrix(V: XSpace, form, orders: tuple[int, int] | None = None) -> sp.csr_matrix:
    """The X-FEM matrix on [a, b] of a form that reads the Heaviside value w["H"].

    The form must be linear in H, H·g(u, v) (as the stiffness and the mass
    are).  With A = the form at H = 1 (standard) and A_H its signed version, and
    D = diag(Hⱼ), the blocks follow from H² = 1 (see the module notes); A and
    A_H come from :func:`skxfem.sides.parts`.  ``orders``: see :func:`signed_bases`.
    """
    cell_q = V.rule if orders is None else cell_rule(V.mesh, orders[0])
    p = parts(V.mesh, V.cut, V.basis.elem, cell_q, None if orders is None else orders[1])
    A, AH = p.signed(lambda b: form.assemble(b, H=np.ones(b.dx.shape)))
    return enriched_blocks(V, A, AH)


def stiffness(V: XSpace, material: Material) -> sp.csr_matrix:
    """The X-FEM stiffness on the unknowns [a, b]: ∫ σ(u):ε(v), each part
    assembled from scalar forms (:func:`skxfem.material.stiffness_matrix`)."""
    p = V.parts or parts(V.mesh, V.cut, V.basis.elem.elem, V.rule)
    A, AH = p.signed(lambda b: stiffness_matrix(material, b))
    return enriched_blocks(V, A, AH)


@BilinearForm
def _signed_vector_mass(u, v, w):
    return w["H"] * dot(u, v)


def mass(V: XSpace) -> sp.csr_matrix:
    """The X-FEM mass matrix on the unknowns [a, b]: ∫ u·v, integrated
    exactly on affine cells (its own orders, :data:`skxfem.quadrature.EXACT_ORDERS`, not the
    stiffness' of ``V``'s basis)."""
    return enriched_matrix(V, _signed_vector_mass, exact_orders(V.mesh, "mass"))


def enriched_load(V: XSpace, f: np.ndarray, f_H: np.ndarray) -> np.ndarray:
    """Load on [a, b] from f = ∫ t·φ and f_H = ∫ H t·φ (standard dofs)."""
    E = V.enr_dofs
    return np.concatenate([f, f_H[E] - V.H_node * f[E]])


def jump_matrix(V: XSpace, cells: np.ndarray, ref: np.ndarray) -> sp.csr_matrix:
    """The operator U ↦ [[u_h]] = -2 Σⱼ φⱼ bⱼ at points on Γ (component-major rows)."""
    Phi = evaluation_matrix(V.basis, cells, ref)
    return sp.hstack([sp.csr_matrix((Phi.shape[0], V.n_std)),
                      -2.0 * Phi[:, V.enr_dofs]], format="csr")


def split_fields(V: XSpace, U: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nodal values (dim, nverts) of the Ω⁻ and Ω⁺ fields, u± = a + b(±1 - H_j)."""
    a = U[:V.n_std].copy()
    minus, plus = a.copy(), a.copy()
    b = U[V.n_std:]
    minus[V.enr_dofs] += b * (-1.0 - V.H_node)
    plus[V.enr_dofs] += b * (1.0 - V.H_node)
    nd = V.basis.nodal_dofs
    return minus[nd], plus[nd]
