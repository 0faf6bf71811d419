r"""The smoothest multipliers that balance a displacement, by a sparse method.

When the rows of B (on the free unknowns) are dependent, the multipliers
that balance a displacement U, Bᵀμ = K U - F, form an affine space μ₀ +
ker Bᵀ.  :func:`skxfem.saddle.smoothest_multipliers` picks the smoothest
one with a dense SVD of B; here the same choice is made with sparse
matrices on the interface unknowns only.

ker Bᵀ is the null space of Q = B Bᵀ, an m × m sparse matrix (m multipliers,
coupled only where they share an enriched unknown).  Its eigenvectors with
the smallest eigenvalues come from shift-invert Lanczos (ARPACK's ``eigsh``
around a small negative shift, one sparse LU of the interface matrix); those
below ``tol``² of the largest span the dependencies — the same threshold as
the dense path's singular values of B below ``tol`` of the largest, so
multipliers that round-off could not tell apart count as dependent there
and here.  With N that basis (m × k, k the number of dependencies, a few
near supports for the stable spaces),

.. math:: \mu = \mu_0 + N c, \qquad c = \arg\min_c \|G(\mu_0 + N c)\| .

Without G, c = -Nᵀμ₀: the least-norm multipliers.  For an independent B
(k = 0) μ₀ is returned unchanged.

>>> import numpy as np, scipy.sparse as sp
>>> B = sp.csr_matrix([[1.0, 0.0], [1.0, 0.0], [0.0, 1.0]])  # rows 0, 1 dependent
>>> G = sp.csr_matrix([[1.0, -1.0, 0.0], [0.0, 1.0, -1.0]])
>>> smoothest(B, np.array([2.0, 0.0, 1.0]), G).round(12).tolist()
[1.0, 1.0, 1.0]
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import ArpackNoConvergence, eigsh

__all__ = ["smoothest", "dependencies"]


def dependencies(B, tol: float = 1e-6, k: int = 8) -> np.ndarray:
    """An orthonormal basis (m, k) of the (numerical) null space of Bᵀ.

    The eigenvectors of Q = B Bᵀ whose eigenvalues are below ``tol``² times
    the largest, i.e. the left singular vectors of B whose singular values
    are below ``tol`` times the largest.  ``k`` is the first number of
    eigenpairs asked for; it doubles until one of them is above the threshold.

    >>> import scipy.sparse as sp
    >>> dependencies(sp.csr_matrix([[1.0, 0.0], [2.0, 0.0], [0.0, 1.0]])).shape
    (3, 1)
    """
    Q = sp.csc_matrix(B @ B.T)
    m = Q.shape[0]
    if m == 0:
        return np.zeros((0, 0))
    if m <= 200:  # small: dense is cheaper than Lanczos
        w, V = np.linalg.eigh(Q.toarray())
        return V[:, w <= tol ** 2 * max(w.max(), 1e-300)]
    q_max = eigsh(Q, k=1, which="LA", return_eigenvectors=False, tol=1e-3)[0] * 1.01
    cut = tol ** 2 * q_max
    while True:
        k = min(k, m - 2)
        try:
            w, V = eigsh(Q, k=k, sigma=-100 * cut, which="LM")
        except ArpackNoConvergence as e:  # pragma: no cover - keep what converged
            w, V = e.eigenvalues, e.eigenvectors
        small = w <= cut
        if small.sum() < k or k == m - 2:
            return np.linalg.qr(V[:, small])[0] if small.any() else V[:, :0]
        k *= 2


def smoothest(B, mu, G=None, tol: float = 1e-6, N=None) -> np.ndarray:
    """The μ with Bᵀμ = Bᵀ``mu`` (up to the dependencies below ``tol``) that
    minimises ‖Gμ‖ (‖μ‖ without G).

    Parameters
    ----------
    B
        (m, n) coupling on the free unknowns.
    mu
        (m,) multipliers that balance the displacement (any of them).
    G
        (p, m) differences between neighbouring multipliers; ``None``: the
        identity (least-norm multipliers).
    tol
        Singular values of B below ``tol`` times the largest count as zero
        (:func:`dependencies`), as in :func:`skxfem.saddle.smoothest_multipliers`.
    N
        The basis of those dependencies, if already computed.

    Returns
    -------
    (m,) array.
    """
    mu = np.asarray(mu, float)
    N = dependencies(sp.csr_matrix(B), tol) if N is None else N
    if N.shape[1] == 0:
        return mu.copy()
    if G is None:
        return mu - N @ (N.T @ mu)
    GN = G @ N
    c = np.linalg.lstsq(GN, -(G @ mu), rcond=None)[0]
    return mu + N @ c
