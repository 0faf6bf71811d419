r"""Moment-fitted rules on the cut cells: a few points per cut cell, exact for the X-FEM.

The sub-simplices of a cut hexahedron (about 14 on each side of Γ, 11 points
each for the order-4 stiffness) hold twenty times the quadrature points of an
uncut cell.  But on an affine cell every integrand of the X-FEM matrices is a
polynomial of a known space 𝒫 in the reference coordinates: the products of
two trilinear functions or of their gradients (mass, stiffness) and the
functions themselves (:func:`skxfem.enrich.far_side_fraction`) all lie in

.. math:: Q_2 = \operatorname{span}\{x^a y^b z^c : a, b, c \le 2\} .

So a rule with fixed points x_q, the 3 × 3 × 3 Gauss points of the cell, and
weights fitted in each cell K to the *moments* of its part on side s,

.. math:: \sum_q w_q\, p_k(x_q) = \int_{K \cap \Omega^s} p_k
          \quad \text{for every monomial } p_k \text{ of } 𝒫,

integrates every such integrand exactly: 27 points instead of about 150.  The
moments come from the sub-simplex rule (numpy only, no basis); the weights
from one 27 × 27 Vandermonde solve, shared by all cells.  Some weights may be
negative: the rule is exact, not positive.  (Müller, Kummer & Oberlack, 2013,
fit moments on implicitly defined domains the same way.)  On prisms 𝒫 is
P₂(r, s) ⊗ P₂(t) (18 points); triangles, quadrilaterals and tetrahedra have
few sub-simplices of low order and keep them (:data:`FITTED` has no entry).

>>> import numpy as np
>>> from skfem import MeshHex1
>>> from skxfem.cut import cut
>>> from skxfem.levelset import plane
>>> m = MeshHex1().refined(1)
>>> rule = fitted_rule(cut(m, plane((0, 0, 0.3), (0, 0, 1))), -1, m.elem().refdom)
>>> rule.X.shape, round(float(rule.W.sum()), 12)  # 4 cut cells, each 0.3 / 0.5 below Γ
((3, 4, 27), 2.4)
"""
from __future__ import annotations

import itertools
from typing import TYPE_CHECKING

import numpy as np
from skfem.quadrature import get_quadrature
from skfem.refdom import RefHex, RefLine, RefTri, RefWedge

from .quadrature import SubcellRule, subcell_rule

if TYPE_CHECKING:  # the type only: sides need no cut to be computed
    from ..cut import Cut

__all__ = ["FITTED", "fitted_rule"]


def _gauss(n: int) -> np.ndarray:
    """The n Gauss points on [0, 1] (scikit-fem's line rule of order 2n - 1)."""
    return get_quadrature(RefLine, 2 * n - 1)[0][0]


def _hex():
    exps = np.array(list(itertools.product(range(3), repeat=3)))  # Q2
    g = _gauss(3)
    X = np.array(list(itertools.product(g, g, g))).T               # (3, 27)
    return exps, X, 6


def _wedge():
    exps = np.array([(a, b, c) for a in range(3) for b in range(3 - a) for c in range(3)])
    Xt = get_quadrature(RefTri, 4)[0]                               # 6 points, P2-unisolvent
    g = _gauss(3)
    X = np.vstack((np.repeat(Xt, g.size, axis=1), np.tile(g, Xt.shape[1])))  # (3, 18)
    return exps, X, 4


FITTED = {RefHex: _hex(), RefWedge: _wedge()}
"""For each reference cell with a fitted rule: the exponents (nmono, dim) of
𝒫, the fixed points (dim, nmono) and the order of the sub-simplex rule that
integrates 𝒫 exactly (the moments)."""


def _monomials(exps: np.ndarray, X: np.ndarray) -> np.ndarray:
    """p_k(x) for every exponent row k of ``exps``: shape (nmono,) + X.shape[1:]."""
    out = 1.0
    for d in range(X.shape[0]):
        powers = np.stack([X[d] ** k for k in range(exps[:, d].max() + 1)])
        out = out * powers[exps[:, d]]
    return out


def fitted_rule(cut: Cut, side: int, refdom) -> SubcellRule | None:
    """The moment-fitted rule of side ``side`` (±1) of every cut cell.

    Returns a :class:`skxfem.fem.quadrature.SubcellRule` (``cells`` the cut cells
    holding a sub-simplex of that side, ``X`` (dim, ncells, nq) the fixed
    points, ``W`` (ncells, nq) the fitted weights), or None where ``refdom``
    has no fitted rule or the side has no sub-simplex.
    """
    if refdom not in FITTED:
        return None
    exps, points, order = FITTED[refdom]
    sub = np.flatnonzero(cut.sub_side == side)
    if not sub.size:
        return None
    exact = subcell_rule(cut.sub_ref[sub], cut.sub_cell[sub], order)
    moments = np.einsum("kcq,cq->ck", _monomials(exps, exact.X), exact.W)  # (ncells, nmono)
    V = _monomials(exps, points)                                            # (nmono, nq)
    W = np.linalg.solve(V, moments.T).T
    X = np.broadcast_to(points[:, None, :], (points.shape[0],) + W.shape)
    return SubcellRule(exact.cells, np.ascontiguousarray(X), W)
