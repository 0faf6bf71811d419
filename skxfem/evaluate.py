"""Evaluating a scikit-fem vector basis at arbitrary points of known cells.

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
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem.assembly import CellBasis

__all__ = ["evaluation_matrix"]


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
