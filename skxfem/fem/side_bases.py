r"""The quadrature of the two sides of Γ: bases on Ω⁻ and Ω⁺, and the parts of a signed matrix.

An X-FEM matrix needs, for a form g, the standard matrix A = ∫ g(φᵢ, φⱼ) and
its signed version A_H = ∫ H g(φᵢ, φⱼ), H = ±1 on Ω^±.  On an uncut cell H is
the constant of its side; on a cut cell H jumps, and each side is integrated
on the sub-simplices of :mod:`skxfem.cut`.  Two ways to cover the mesh:

* :func:`side_bases`: every cell on its side, the cut cells by their
  sub-simplices of both sides; A = A⁺ + A⁻ and A_H = A⁺ - A⁻.  Any integral
  that differs on the two sides (a field of the X-FEM space, an error) needs
  this.
* :func:`parts`: the cheaper one for A and A_H.  A is the standard matrix,
  every cell integrated whole (on a cut cell too: the integrand g is a
  polynomial there), and with Aˢ the matrix of one side s,

  .. math:: A_H = s\,(2 A^s - A) .

  The X-FEM blocks read A_H only in the columns of enriched nodes (see
  :mod:`skxfem.enrich`), so Aˢ is needed only on the cells that hold an
  enriched node: the sub-simplices of side s and one layer of uncut cells.
  One side's sub-simplices instead of both: on the paper's plate at n = 32,
  436k quadrature points instead of 578k (hexahedra), 475k instead of 508k
  (prisms).  On hexahedra and prisms the cut cells of side s then take a
  moment-fitted rule (:mod:`skxfem.fem.fitted`) instead of their sub-simplices.

>>> from skfem import MeshTri1
>>> from skxfem.cut import cut as cut_mesh
>>> from skxfem.levelset import plane
>>> m = MeshTri1().refined(2)
>>> cut = cut_mesh(m, plane((0, 0.3), (0, 1)))
>>> [s for _, s in side_bases(m, cut, m.elem())]
[-1, -1, 1, 1]
>>> p = parts(m, cut, m.elem())
>>> p.whole.nelems, p.side
(32, -1)
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from skfem import Basis
from skfem.assembly import CellBasis

from .fitted import fitted_rule
from .quadrature import cell_rule, exact_orders, subcell_rule

if TYPE_CHECKING:  # the type only: sides need no cut to be computed
    from ..cut import Cut

__all__ = ["side_bases", "Parts", "parts"]


def _sub_basis(mesh, cut: Cut, elem, s: int, order: int):
    """The sub-simplices of side ``s``, each one element of the basis (its
    parent cell, repeated) with the simplex rule of ``order`` mapped into it,
    so that no quadrature point is spent on padding; None if there are none."""
    sub = np.flatnonzero(cut.sub_side == s)
    if not sub.size:
        return None
    rule = subcell_rule(cut.sub_ref[sub], np.arange(sub.size), order)
    return Basis(mesh, elem, elements=cut.sub_cell[sub], quadrature=(rule.X, rule.W))


def side_bases(mesh, cut: Cut, elem, quadrature=None, sub_order=None) -> tuple:
    """Bases covering the mesh, each lying on one side of Γ: pairs (basis, ±1).

    Uncut cells of Ω⁻ and of Ω⁺ use the cell rule ``quadrature`` (default:
    exact for the stiffness), the sub-simplices of the cut cells the simplex
    rule of ``sub_order``.
    """
    cell_q = quadrature or cell_rule(mesh, exact_orders(mesh)[0])
    pairs = []
    for s in (-1, 1):
        cells = np.flatnonzero(cut.side == s)
        if cells.size:
            pairs.append((Basis(mesh, elem, elements=cells, quadrature=cell_q), s))
        sub = _sub_basis(mesh, cut, elem, s, sub_order or exact_orders(mesh)[1])
        if sub is not None:
            pairs.append((sub, s))
    return tuple(pairs)


@dataclass(frozen=True)
class Parts:
    """The bases of A and A_H = s (2Aˢ - A): see the module notes.

    Attributes
    ----------
    whole : the basis of every cell, whole, at the cell rule (A).
    side : s = ±1, the side integrated on its own: the one with fewer
        sub-simplices.
    near : the bases of side s on the cells holding an enriched node: the
        uncut cells of side s among them (cell rule) and the part of side s
        of the cut cells (Aˢ, exact in the columns of enriched nodes only).
    """

    whole: CellBasis
    side: int
    near: tuple

    def signed(self, assemble, A=None):
        """(A, A_H) from ``assemble(basis) -> matrix or vector``; ``A``, if
        given, is the standard one, already assembled (another level set's)."""
        A = assemble(self.whole) if A is None else A
        As = sum(assemble(b) for b in self.near)
        return A, self.side * (2 * As - A)


def parts(mesh, cut: Cut, elem, quadrature=None, sub_order=None, fit: bool = True) -> Parts:
    """The :class:`Parts` of ``mesh`` cut by ``cut`` (rules as :func:`side_bases`).

    ``fit``: the cut cells of side s take their moment-fitted rule where the
    cell type has one (:func:`skxfem.fem.fitted.fitted_rule`, exact for the
    stiffness, the mass and the functions on affine cells; ``sub_order`` is
    then not used), else their sub-simplices."""
    cell_q = quadrature or cell_rule(mesh, exact_orders(mesh)[0])
    s = -1 if np.sum(cut.sub_side < 0) <= np.sum(cut.sub_side > 0) else 1
    holds = np.zeros(mesh.p.shape[1], dtype=bool)
    holds[cut.enriched] = True
    layer = np.flatnonzero((cut.side == s) & holds[mesh.t].any(axis=0))
    near = []
    if layer.size:
        near.append(Basis(mesh, elem, elements=layer, quadrature=cell_q))
    fitted = fitted_rule(cut, s, mesh.elem().refdom) if fit else None
    if fitted is not None:
        near.append(Basis(mesh, elem, elements=fitted.cells, quadrature=(fitted.X, fitted.W)))
    else:
        sub = _sub_basis(mesh, cut, elem, s, sub_order or exact_orders(mesh)[1])
        if sub is not None:
            near.append(sub)
    return Parts(Basis(mesh, elem, quadrature=cell_q), s, tuple(near))
