r"""The smoothest multipliers that balance a displacement, by a sparse method.

When the rows of B (on the free unknowns) are dependent, the multipliers
that balance a displacement U, Bᵀμ = K U - F, form an affine space μ₀ +
ker Bᵀ.  :func:`skxfem.saddle.smoothest_multipliers` picks the smoothest
one with a dense SVD of B; here the same choice is made on the interface
unknowns only, with sparse matrices:

.. math:: \min_z \tfrac12 \|G(\mu_0 + z)\|^2 \quad\text{subject to}\quad B^T z = 0,

by the augmented Lagrangian: with L = GᵀG and Q = B Bᵀ (m × m, sparse, as
local as the multipliers), repeat

.. math:: (L + \rho Q)\, z = -L\mu_0 - \eta, \qquad \eta \leftarrow \eta + \rho Q z

until Bᵀz vanishes.  L + ρQ is positive definite when a constant traction
(the kernel of G) loads some free unknown, and is factorised once (SuperLU;
m is the interface size, not the volume's).  Where a constant traction loads
no free unknown at all (a component every support holds), the smoothest
choice is not unique: a tiny multiple of the identity added to L then picks
the least-norm one, as the dense path does.  With G = I the same iteration
returns the least-norm multipliers.  For an
independent B (the stable spaces away from supports) ker Bᵀ = {0} and the
iteration returns μ₀ itself, to round-off.

>>> import numpy as np, scipy.sparse as sp
>>> B = sp.csr_matrix([[1.0, 0.0], [1.0, 0.0], [0.0, 1.0]])  # rows 0, 1 dependent
>>> G = sp.csr_matrix([[1.0, -1.0, 0.0], [0.0, 1.0, -1.0]])
>>> smoothest(B, np.array([2.0, 0.0, 1.0]), G).round(12).tolist()
[1.0, 1.0, 1.0]
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = ["smoothest"]


def smoothest(B, mu, G=None, rho: float = 1e3, maxiter: int = 100,
              tol: float = 1e-14) -> np.ndarray:
    """The μ with Bᵀμ = Bᵀ``mu`` that minimises ‖Gμ‖ (‖μ‖ without G).

    Parameters
    ----------
    B
        (m, n) coupling on the free unknowns.
    mu
        (m,) multipliers that balance the displacement (any of them).
    G
        (p, m) differences between neighbouring multipliers; ``None``: the
        identity (least-norm multipliers).
    rho
        Penalty, relative to the ratio of the diagonals of GᵀG and BBᵀ.
    maxiter, tol
        Augmented-Lagrangian steps at most, and the relative size of Bᵀz at
        which they stop.

    Returns
    -------
    (m,) array.
    """
    B = sp.csr_matrix(B)
    mu = np.asarray(mu, float)
    m = B.shape[0]
    if m == 0:
        return mu.copy()
    cols = np.unique(B.indices)
    C = B[:, cols]
    C = C @ sp.diags(1.0 / np.sqrt(np.asarray(C.multiply(C).sum(axis=0)).ravel()))
    L = sp.identity(m, format="csc") if G is None else sp.csc_matrix(G.T @ G)
    # among equally smooth choices (a constant traction that loads no free
    # unknown), the least-norm one, as the dense path's least squares does
    L = L + 1e-10 * L.diagonal().mean() * sp.identity(m, format="csc")
    Q = (C @ C.T).tocsc()
    scale = rho * L.diagonal().mean() / max(Q.diagonal().mean(), 1e-300)
    A = (L + scale * Q).tocsc()
    lu = spla.splu(A)
    target = np.linalg.norm(C.T @ mu) * tol
    Lmu = L @ mu
    eta = np.zeros(m)
    for _ in range(maxiter):
        rhs = -Lmu - eta
        z = lu.solve(rhs)
        z += lu.solve(rhs - A @ z)  # one step of refinement: A may be ill-conditioned
        t = C.T @ z
        if np.linalg.norm(t) <= target:
            break
        eta += scale * (C @ t)
    return mu + z
