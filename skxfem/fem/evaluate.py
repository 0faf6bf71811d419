"""Evaluating at points: a basis at points of known cells, the pressure along a line.

X-FEM integrates on surfaces that are not mesh facets (the interface Γ, the
pieces of cut boundary faces), so the shape functions are needed at points
given by their cell and reference coordinates.  scikit-fem evaluates them: a
``CellBasis`` whose "quadrature" is one point per entry.

>>> import numpy as np
>>> from skfem import Basis, ElementTriP1, ElementVector, MeshTri1
>>> basis = Basis(MeshTri1(), ElementVector(ElementTriP1()))
>>> Phi = evaluation_matrix(basis, np.array([0]), np.array([[1 / 3], [1 / 3]]))
>>> Phi.shape, float(Phi.sum())     # x and y rows, each a partition of unity
((2, 8), 2.0)

:func:`pressure_along` extracts interface data from a result: the contact
pressure at the multiplier points lying on one line, sorted along it (what
the paper's Figures 5, 7 and 8 plot).
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import scipy.sparse as sp
from skfem.assembly import CellBasis

__all__ = ["evaluation_matrix", "pressure_along"]

_AXES = "xyz"


def evaluation_matrix(basis: CellBasis, cells: np.ndarray, ref: np.ndarray) -> sp.csr_matrix:
    """Values of a vector basis at points given in reference coordinates.

    Parameters
    ----------
    basis
        A vector ``skfem.Basis`` (``ElementVector``).
    cells
        The cell of each point, shape ``(npts,)``.
    ref
        The points in their cell's reference coordinates, shape ``(dim, npts)``.

    Returns
    -------
    csr_matrix, shape ``(dim * npts, basis.N)``
        Maps a dof vector to the field at the points, component-major rows
        (all x values, then all y values, ...).
    """
    npts = cells.size
    B = CellBasis(basis.mesh, basis.elem, elements=cells,
                  quadrature=(ref[:, :, None], np.ones((npts, 1))))
    dim = basis.mesh.dim()
    rows, cols, vals = [], [], []
    for k in range(B.Nbfun):
        value = np.asarray(B.basis[k][0])[:, :, 0]  # (dim, npts)
        for c in range(dim):
            rows.append(c * npts + np.arange(npts))
            cols.append(B.element_dofs[k])
            vals.append(value[c])
    Phi = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                        shape=(dim * npts, basis.N))
    Phi.eliminate_zeros()  # a vector function has one non-zero component
    return Phi


def _axis(name: str | int, dim: int) -> int:
    """Coordinate index of ``"x"``, ``"y"``, ``"z"`` (or of an int)."""
    a = _AXES.index(name) if isinstance(name, str) and name in _AXES else name
    if not (isinstance(a, (int, np.integer)) and 0 <= a < dim):
        raise ValueError(f"axis must be one of {list(_AXES[:dim])} or 0..{dim - 1}, "
                         f"got {name!r}")
    return int(a)


def pressure_along(result, axis: str | int = "y", where: Mapping | None = None,
                   tol: float = 1e-9) -> tuple[np.ndarray, np.ndarray]:
    """The contact pressure at the multiplier points, sorted along one coordinate.

    Parameters
    ----------
    result
        A :class:`skxfem.result.Result`, or anything with ``points``
        ``(dim, n)`` and ``pressure`` ``(n,)``.
    axis
        The coordinate to sort by: ``"x"``, ``"y"``, ``"z"`` or 0, 1, 2.
    where
        Coordinates to hold fixed, e.g. ``{"x": 0.5}``: only the points within
        ``tol`` (relative to the size of the point cloud) of those planes are
        kept.  ``{}`` keeps every point (their projection on ``axis``).
        Default: in 2D every point; in 3D every other coordinate that varies
        among the points is fixed at its middle value, the middle node plane
        of a structured mesh cut by a coordinate plane (the paper's plate:
        the line x = 0.5 of z = 0.5).
    tol
        Relative tolerance of the selection.

    Returns
    -------
    s, p
        The coordinate ``axis`` of the selected points, increasing, and their
        pressures.

    >>> from types import SimpleNamespace
    >>> pts = np.array([[0.0, 0.5, 1.0, 0.0, 0.5, 1.0], [1, 1, 1, 0, 0, 0], [0.5] * 6])
    >>> r = SimpleNamespace(points=pts, pressure=np.arange(6.0))
    >>> s, p = pressure_along(r, "x")        # y fixed at its middle value: y = 1
    >>> s.tolist(), p.tolist()
    ([0.0, 0.5, 1.0], [0.0, 1.0, 2.0])
    >>> pressure_along(r, "x", where={"y": 0.0})[1].tolist()
    [3.0, 4.0, 5.0]
    """
    points = np.asarray(result.points, dtype=float)
    pressure = np.asarray(result.pressure, dtype=float)
    dim = points.shape[0]
    a = _axis(axis, dim)
    scale = max(float(np.ptp(points, axis=1).max()), 1.0)
    if where is None:
        where = {}
        if dim == 3:
            for d in range(dim):
                values = np.unique(np.round(points[d] / (tol * scale)))
                if d != a and values.size > 1:
                    where[d] = float(values[values.size // 2] * tol * scale)
    keep = np.ones(points.shape[1], dtype=bool)
    for name, value in where.items():
        keep &= np.abs(points[_axis(name, dim)] - value) <= tol * scale
    if not keep.any():
        raise ValueError(f"no multiplier point lies on {dict(where)} (tolerance "
                         f"{tol * scale:.1e}); choose values present in result.points")
    order = np.argsort(points[a, keep], kind="stable")
    return points[a, keep][order], pressure[keep][order]
