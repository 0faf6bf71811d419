r"""The saddle-point solve, with an honest treatment of dependent multipliers.

Solve, for the unknowns U with some entries imposed (U[D] = g),

.. math:: K U + B^T y = F, \qquad B U = 0,

where y = -μ and μ are the multipliers.  When the rows of B restricted to the
free unknowns are linearly dependent (the naive space on tetrahedra; a
multiplier whose jump a Dirichlet condition already fixes), U is still
unique but μ is not: μ + z solves the equations for every z with Bᵀz = 0.
Rather than letting the sparse LU return whatever its pivoting makes of a
singular matrix, we

1. find a maximal set of independent rows with a rank-revealing (pivoted) QR
   of the dense interface block of Bᵀ,
2. solve the reduced, non-singular saddle system with SuperLU,
3. among all multipliers μ that balance U, return the *smoothest*: the one
   minimising ‖G μ‖, G the differences between neighbouring multipliers.
   A constant traction has G μ = 0, so it is recovered exactly when it
   balances U (the patch test).

>>> import numpy as np, scipy.sparse as sp
>>> K = sp.identity(2, format="csr"); B = sp.csr_matrix([[1.0, -1.0], [2.0, -2.0]])
>>> U, mu, info = solve(K, B, np.array([1.0, 0.0]))
>>> U.round(12).tolist(), info.removed
([0.5, 0.5], 1)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = ["SaddleInfo", "independent_rows", "solve"]


@dataclass(frozen=True)
class SaddleInfo:
    """Diagnostics: ``removed`` dependent multipliers, the relative ``residual``."""

    removed: int
    residual: float


def independent_rows(B: sp.spmatrix, tol: float = 1e-10):
    """Split the rows of B into independent ones and a null-space basis of Bᵀ.

    Returns ``(keep, Z)``: sorted indices of a maximal set of independent rows
    and Z (nrows, nrows - len(keep)) with Bᵀ Z = 0, from a pivoted QR of the
    columns of Bᵀ (only the non-zero columns of B enter the dense factorisation).
    """
    B = sp.csr_matrix(B)
    m = B.shape[0]
    cols = np.unique(B.indices)
    if cols.size == 0:
        return np.arange(0), np.eye(m)
    _, R, piv = sla.qr(B[:, cols].toarray().T, mode="economic", pivoting=True)
    d = np.abs(np.diag(R))
    rank = int(np.sum(d > tol * d.max()))
    keep, drop = piv[:rank], piv[rank:]
    Z = np.zeros((m, m - rank))
    if drop.size:  # Bᵀ[:, keep] c + Bᵀ[:, drop] = 0  ⇔  R11 c = -R12
        Z[keep] = -sla.solve_triangular(R[:rank, :rank], R[:rank, rank:m])
        Z[drop, np.arange(drop.size)] = 1.0
    return np.sort(keep), Z


def solve(K, B, F, D=None, g=None, G=None, tol: float = 1e-8):
    """Solve the saddle-point system; see the module notes.

    Parameters
    ----------
    K, B, F
        Stiffness (N, N), coupling (m, N) and load (N,).
    D, g
        Imposed unknowns and their values (default: none).
    G
        Smoothing operator (p, m) selecting among non-unique multipliers;
        default: the minimum-norm ones.
    tol
        Largest accepted relative residual.

    Returns
    -------
    U, mu, info
        Unknowns (N,), multipliers (m,), :class:`SaddleInfo`.

    Raises
    ------
    RuntimeError
        If the solve fails or its residual exceeds ``tol``.
    """
    N, m = K.shape[0], B.shape[0]
    D = np.zeros(0, int) if D is None else np.asarray(D, int)
    g = np.zeros(D.size) if g is None else np.asarray(g, float)
    free = np.setdiff1d(np.arange(N), D)
    Bf = sp.csr_matrix(B)[:, free]
    keep, Z = independent_rows(Bf)
    U = np.zeros(N)
    U[D] = g
    Kc = sp.csr_matrix(K)
    rhs = np.concatenate([(F - Kc @ U)[free], -(sp.csr_matrix(B) @ U)[keep]])
    A = sp.bmat([[Kc[free][:, free], Bf[keep].T], [Bf[keep], None]], format="csc")
    x = spla.splu(A, permc_spec="MMD_AT_PLUS_A").solve(rhs)
    residual = np.linalg.norm(A @ x - rhs) / max(np.linalg.norm(rhs), 1e-300)
    if not np.all(np.isfinite(x)) or residual > tol:
        raise RuntimeError(
            f"the saddle-point solve failed (relative residual {residual:.2e}): the "
            f"displacement problem is singular; check that the supports remove every "
            f"rigid motion of each side of the interface")
    U[free] = x[:free.size]
    mu = np.zeros(m)
    mu[keep] = -x[free.size:]
    if Z.shape[1]:
        Gm = np.eye(m) if G is None else G
        c = np.linalg.lstsq(Gm @ Z, -(Gm @ mu), rcond=None)[0]
        mu = mu + Z @ c
    return U, mu, SaddleInfo(int(m - keep.size), float(residual))
