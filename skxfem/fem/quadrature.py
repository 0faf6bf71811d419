r"""Quadrature rules: whole cells, and the sub-cells of X-FEM cut cells.

scikit-fem integrates a form with a rule in the *reference* cell: points ``X``
of shape ``(dim, nqp)`` and weights ``W`` of shape ``(nqp,)`` (one rule for all
cells), or ``X`` of shape ``(dim, ncells, nqp)`` and ``W`` of shape
``(ncells, nqp)`` (one rule per cell).  Both are accepted by
``skfem.Basis(mesh, elem, quadrature=(X, W))``.

Three rules live here:

* :func:`wedge_rule` -- a correct rule for the prism ``RefWedge``; scikit-fem
  12's own wedge rule is wrong (its weights sum to 1/4 instead of the volume 1/2).
* :func:`cell_rule` -- the rule we pass explicitly for any of the five cells.
* :func:`subcell_rule` -- X-FEM sub-cell integration: a cut cell is split into
  sub-simplices on each side of Γ, each gets a simplex rule, and all of them
  are packed into one per-cell rule in the parent's reference coordinates.

>>> X, W = wedge_rule(2)
>>> X.shape, round(float(W.sum()), 12)
((3, 6), 0.5)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from skfem.quadrature import get_quadrature
from skfem.refdom import RefHex, RefLine, RefQuad, RefTet, RefTri, RefWedge

from ..linalg.scalars import is_integer

__all__ = [
    "DEFAULT_ORDER",
    "simplex_or_tensor_rule",
    "EXACT_ORDERS",
    "exact_orders",
    "SubcellRule",
    "cell_rule",
    "subcell_rule",
    "pack_rules",
    "simplex_points",
    "wedge_rule",
]

#: The one table of quadrature orders that integrate exactly, on affine
#: cells, a product of two P1/Q1/prism gradients (``"stiffness"``) or of two
#: P1/Q1/prism functions (``"mass"``).  Each entry is (cell rule order,
#: sub-simplex rule order): the cell rule counts per direction on quads,
#: hexahedra and prisms (scikit-fem's tensor rules); a sub-simplex rule maps
#: a simplex rule into the parent's reference coordinates, where the same
#: integrand has a higher total degree.  Stiffness: P1 gradients are
#: constant (0, 0); a Q1 gradient on an affine quad/hex is linear in each
#: coordinate, so the integrand is quadratic in each — a 2-point Gauss rule
#: per direction is exact (4 points on a quad, 8 on a hex, where
#: scikit-fem's default for ElementHex1 uses 64) — and of total degree 2
#: (quad) or 4 (trilinear hex) on a sub-simplex; on a right prism the
#: gradients are linear in (r, s) and in t: order 2 gives a 3-point triangle
#: rule times 2 Gauss points, and degree 2 on a sub-simplex.  Mass: two
#: functions give degree 2 per variable in the cell, total degree 2
#: (simplices), 4 (quad, prism) or 6 (hexahedron) on a sub-simplex.
EXACT_ORDERS = {
    "stiffness": {RefTri: (0, 0), RefTet: (0, 0), RefQuad: (2, 2), RefWedge: (2, 2),
                  RefHex: (2, 4)},
    "mass": {RefTri: (2, 2), RefTet: (2, 2), RefQuad: (2, 4), RefWedge: (2, 4),
             RefHex: (2, 6)},
}

#: Default cell rule order: the stiffness column of :data:`EXACT_ORDERS`.
DEFAULT_ORDER = {refdom: cell for refdom, (cell, _) in EXACT_ORDERS["stiffness"].items()}


def _check_order(order) -> int:
    if not is_integer(order) or order < 0:
        raise ValueError(f"order must be a non-negative integer, got {order!r}")
    return int(order)


def wedge_rule(order: int) -> tuple[np.ndarray, np.ndarray]:
    """Tensor-product rule on scikit-fem's reference prism ``RefWedge``.

    The prism is the triangle {r, s ≥ 0, r + s ≤ 1} extruded along t ∈ [0, 1]
    (volume 1/2).  The rule is scikit-fem's triangle rule in (r, s) times a
    Gauss rule in t, so it is exact for r^a s^b t^c with a + b ≤ ``order``
    and c ≤ ``order``.

    Parameters
    ----------
    order
        Polynomial order integrated exactly in each factor.

    Returns
    -------
    X : ndarray, shape (3, nqp)
        Points (r, s, t).
    W : ndarray, shape (nqp,)
        Weights, summing to 1/2.

    >>> X, W = wedge_rule(1)
    >>> float(W @ X[2])      # ∫ t = 1/2 · 1/2
    0.25
    """
    order = _check_order(order)
    Xt, Wt = get_quadrature(RefTri, order)    # (2, ntri), (ntri,)
    Xl, Wl = get_quadrature(RefLine, order)   # (1, nline), (nline,)
    ntri, nline = Wt.size, Wl.size
    X = np.vstack((np.repeat(Xt, nline, axis=1),      # each (r, s) ...
                   np.tile(Xl, (1, ntri))))            # ... with every t
    W = np.repeat(Wt, nline) * np.tile(Wl, ntri)
    return X, W


def _refdom(mesh_or_elem):
    """The reference domain of a mesh, mesh class, element or element class."""
    elem = getattr(mesh_or_elem, "elem", mesh_or_elem)   # Mesh -> its element
    refdom = getattr(elem, "refdom", None)
    if refdom not in DEFAULT_ORDER:
        raise TypeError(
            f"mesh_or_elem must be a tri, quad, tet, hex or wedge mesh or "
            f"element, got {mesh_or_elem!r}")
    return refdom


def exact_orders(mesh_or_elem, integrand: str = "stiffness") -> tuple[int, int]:
    """(cell rule order, sub-simplex rule order) of :data:`EXACT_ORDERS`.

    >>> from skfem import MeshHex1
    >>> exact_orders(MeshHex1()), exact_orders(MeshHex1(), "mass")
    ((2, 4), (2, 6))
    """
    if integrand not in EXACT_ORDERS:
        raise ValueError(f"integrand must be one of {tuple(EXACT_ORDERS)}, got {integrand!r}")
    return EXACT_ORDERS[integrand][_refdom(mesh_or_elem)]


def cell_rule(mesh_or_elem, order: int | None = None
              ) -> tuple[np.ndarray, np.ndarray]:
    """The quadrature rule to pass explicitly to ``skfem.Basis``.

    Parameters
    ----------
    mesh_or_elem
        A scikit-fem mesh or element (instance or class) of one of the five
        cell types: triangle, quadrilateral, tetrahedron, hexahedron, wedge.
    order
        Polynomial order integrated exactly; by default :data:`DEFAULT_ORDER`,
        the order of the P1/Q1 stiffness matrix (see there).

    Returns
    -------
    X, W
        Reference points ``(dim, nqp)`` and weights ``(nqp,)``.

    >>> from skfem import MeshHex1
    >>> X, W = cell_rule(MeshHex1())
    >>> W.size          # 2 x 2 x 2 Gauss points
    8
    """
    refdom = _refdom(mesh_or_elem)
    if order is None:
        order = DEFAULT_ORDER[refdom]
    order = _check_order(order)
    if refdom is RefWedge and order > 0:
        return wedge_rule(order)
    return simplex_or_tensor_rule(refdom, order)


_VOLUME = {RefTri: 0.5, RefQuad: 1.0, RefTet: 1.0 / 6.0, RefHex: 1.0, RefWedge: 0.5}


def simplex_or_tensor_rule(refdom, order: int) -> tuple[np.ndarray, np.ndarray]:
    """scikit-fem's rule of ``order`` on ``refdom``, except order 0: the
    one-point centroid rule on every cell (scikit-fem returns 3 points on a
    triangle, 8 on a hexahedron), exact for the constant gradients of P1
    functions and for every (multi)linear function; and on a tetrahedron from
    order 5 on, scikit-fem's rule one order up (its rules of order 5 to 9 are
    exact only to degree 4 to 8: measured, tests/test_quadrature.py).

    >>> from skfem.refdom import RefTri
    >>> X, W = simplex_or_tensor_rule(RefTri, 0)
    >>> X.ravel().round(6).tolist(), W.tolist()
    ([0.333333, 0.333333], [0.5])
    """
    if order == 0:
        return np.mean(refdom.p, axis=1)[:, None], np.array([_VOLUME[refdom]])
    if refdom is RefTet and order >= 5:
        order += 1  # scikit-fem 12's tetrahedron rules of order 5-9 are exact to order - 1
    return get_quadrature(refdom, order)


@dataclass(frozen=True)
class SubcellRule:
    """One quadrature rule per parent cell, built from its sub-simplices.

    Pass ``elements=rule.cells, quadrature=(rule.X, rule.W)`` to
    ``skfem.Basis``.

    Attributes
    ----------
    cells : ndarray, shape (ncells,)
        Parent cell indices, sorted and unique.
    X : ndarray, shape (dim, ncells, nqp)
        Points in the reference coordinates of each parent cell.
    W : ndarray, shape (ncells, nqp)
        Reference weights; zero on padding points.
    V : ndarray, shape (ncells, nqp), or None
        The value attached to each sub-simplex (e.g. its Heaviside sign),
        repeated at its points, 0 on padding; None if no values were given.
    """

    cells: np.ndarray
    X: np.ndarray
    W: np.ndarray
    V: np.ndarray | None = None


def subcell_rule(ref_simplices: ArrayLike, parent: ArrayLike, order: int,
                 values: ArrayLike | None = None) -> SubcellRule:
    """Pack the rules of sub-simplices into one rule per parent cell.

    Each sub-simplex with vertices V₀ … V_d (reference coordinates of its
    parent) is the image of the reference simplex under the affine map
    x = V₀ + A ξ, A = [V₁ - V₀, …, V_d - V₀].  The simplex rule of ``order`` is
    mapped by it and its weights are multiplied by |det A|.  The points of
    all sub-simplices of a parent are packed side by side; cells with fewer
    sub-simplices are padded with zero-weight points placed at the centroid of
    the reference simplex, which lies inside every reference cell (triangle,
    square, tetrahedron, cube, prism).

    Parameters
    ----------
    ref_simplices
        Sub-triangles (dim 2) or sub-tetrahedra (dim 3), shape
        ``(nsub, dim + 1, dim)``, in parent reference coordinates.
    parent
        Parent cell index of each sub-simplex, shape ``(nsub,)``.
    order
        Polynomial order of the simplex rule.
    values
        Optional value per sub-simplex, shape ``(nsub,)``.

    Returns
    -------
    SubcellRule

    >>> halves = [[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]]
    >>> rule = subcell_rule(halves, [3, 3], order=1, values=[-1, 1])
    >>> rule.cells.tolist(), rule.X.shape, round(float(rule.W.sum()), 12)
    ([3], (2, 1, 6), 1.0)
    >>> rule.V.tolist()      # 3 points per half
    [[-1.0, -1.0, -1.0, 1.0, 1.0, 1.0]]
    """
    simplices = np.asarray(ref_simplices, dtype=float)
    shape = simplices.shape
    if simplices.ndim != 3 or shape[2] not in (2, 3) or shape[1] != shape[2] + 1:
        raise ValueError(
            "ref_simplices must have shape (nsub, dim + 1, dim) with dim 2 "
            f"(triangles) or 3 (tetrahedra), got {simplices.shape}")
    if not np.all(np.isfinite(simplices)):
        raise ValueError("ref_simplices contains NaN or inf; check the cut")
    nsub = simplices.shape[0]
    parent = np.asarray(parent)
    if parent.shape != (nsub,) or not np.issubdtype(parent.dtype, np.integer) \
            or (nsub and parent.min() < 0):
        raise ValueError(
            f"parent must be {nsub} non-negative integer cell indices, one per "
            f"sub-simplex, got shape {parent.shape} and dtype {parent.dtype}")
    if values is not None:
        values = np.asarray(values, dtype=float)
        if values.shape != (nsub,):
            raise ValueError(f"values must have shape ({nsub},), one per "
                             f"sub-simplex, got {values.shape}")

    return pack_rules(*simplex_points(simplices, order), parent, values)


def simplex_points(simplices: ArrayLike, order: int) -> tuple[np.ndarray, np.ndarray]:
    """The simplex rule of ``order`` mapped into each of ``simplices`` (m, dim + 1, dim)
    by x = V₀ + A ξ, A = [V₁ - V₀, …]: points (m, nq, dim) and weights × |det A| (m, nq).

    >>> x, w = simplex_points(np.array([[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]]), 2)
    >>> round(float(w.sum()), 15), round(float(w[0] @ x[0, :, 0]), 15)   # ∫ x = 1/3
    (0.5, 0.333333333333333)
    """
    simplices = np.asarray(simplices, dtype=float)
    dim = simplices.shape[2]
    Xs, Ws = simplex_or_tensor_rule(RefTri if dim == 2 else RefTet, _check_order(order))
    A = np.transpose(simplices[:, 1:] - simplices[:, :1], (0, 2, 1))  # columns V_i - V_0
    return (simplices[:, None, 0] + np.einsum("kij,jq->kqi", A, Xs),
            np.abs(np.linalg.det(A))[:, None] * Ws)


def pack_rules(points: np.ndarray, weights: np.ndarray, parent: np.ndarray,
               values: ArrayLike | None = None) -> SubcellRule:
    """Pack the rules of pieces of cells into one rule per parent cell: ``points``
    (m, nq, dim) in parent reference coordinates, ``weights`` (m, nq), the ``parent``
    cell of each piece (m,) and, optionally, a value per piece (m,).  The pieces of a
    parent sit side by side; cells with fewer pieces are padded with zero-weight points
    at the centroid of the reference simplex, which lies inside every reference cell.

    >>> r = pack_rules(np.full((2, 1, 2), 0.25), np.ones((2, 1)), np.array([4, 4]))
    >>> r.cells.tolist(), r.X.shape, r.W.tolist()
    ([4], (2, 1, 2), [[1.0, 1.0]])
    """
    parent = np.asarray(parent)
    m, nq, dim = points.shape
    order_ = np.argsort(parent, kind="stable")   # each piece's slot: its rank in its parent
    cells, first, counts = np.unique(parent[order_], return_index=True,
                                     return_counts=True)
    group = np.repeat(np.arange(cells.size), counts)
    slot = np.arange(m) - first[group]
    nslots = int(counts.max()) if m else 0
    X = np.full((cells.size, nslots, nq, dim), 1.0 / (dim + 1))   # padding
    X[group, slot] = points[order_]
    W = np.zeros((cells.size, nslots, nq))
    W[group, slot] = weights[order_]
    V = None
    if values is not None:
        V = np.zeros((cells.size, nslots, nq))
        V[group, slot] = np.asarray(values, float)[order_, None]
        V = V.reshape(cells.size, -1)
    X = np.moveaxis(X.reshape(cells.size, -1, dim), 2, 0)
    return SubcellRule(cells, X, W.reshape(cells.size, -1), V)
