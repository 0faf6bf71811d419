r"""Dependent multipliers: the dependencies of B, and the smoothest multipliers that
balance a displacement among them, by a sparse method.

When the rows of B (on the free unknowns) are dependent, the multipliers
that balance a displacement U, Bᵀμ = K U - F, form an affine space μ₀ +
ker Bᵀ.  :func:`skxfem.linalg.saddle.smoothest_multipliers` picks the smoothest
one with a dense SVD of B; here the same choice is made with sparse
matrices on the interface unknowns only.

ker Bᵀ is the null space of Q = B Bᵀ, an m × m sparse matrix (m multipliers,
coupled only where they share an enriched unknown).  Its eigenvectors with
the smallest eigenvalues come from shift-invert Lanczos (ARPACK's ``eigsh``
around a small negative shift, one sparse LU of the interface matrix); a
Rayleigh-Ritz step on their span keeps the singular values of B below
``tol`` of the largest (:func:`dependencies`) — by default the dense path's
threshold, so that multipliers round-off could not tell apart count as
dependent there and here.  With N that basis (m × k, k the number of dependencies, a few
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

__all__ = ["smoothest", "dependencies", "along", "unit_rows"]


def unit_rows(B) -> tuple[sp.csr_matrix, np.ndarray]:
    """B with its rows scaled to unit length (rows of zeros left as they are), and
    the scales: the form in which dependent rows are counted whatever each row's size.

    >>> scaled, scales = unit_rows(sp.csr_matrix([[3.0, 4.0], [0.0, 0.0]]))
    >>> scaled.toarray().round(12).tolist(), scales.tolist()
    ([[0.6, 0.8], [0.0, 0.0]], [0.2, 1.0])
    """
    B = sp.csr_matrix(B)
    norms = np.sqrt(np.asarray(B.multiply(B).sum(axis=1)).ravel())
    scales = 1.0 / np.where(norms > 0, norms, 1.0)
    return (sp.diags(scales) @ B).tocsr(), scales


def dependencies(B, tol: float = 1e-6, k: int = 8) -> np.ndarray:
    """An orthonormal basis (m, k) of the (numerical) null space of Bᵀ: the left
    singular vectors of B whose singular values are below ``tol`` times the largest.

    Few rows (m ≤ 200): a dense SVD.  Many: the eigenvectors of Q = B Bᵀ
    below (10⁻⁶)² of its largest eigenvalue (the candidates; ``k`` is the
    first number asked for, doubled until one is above), then a
    Rayleigh-Ritz step, the SVD of Bᵀ on their span, which measures the
    singular values of B to round-off (those of Q only resolve them down to
    about 1e-8), and keeps those below ``tol``.

    >>> import scipy.sparse as sp
    >>> dependencies(sp.csr_matrix([[1.0, 0.0], [2.0, 0.0], [0.0, 1.0]])).shape
    (3, 1)
    """
    B = sp.csr_matrix(B)
    m = B.shape[0]
    if m == 0:
        return np.zeros((0, 0))
    if m <= 200:  # few rows: dense is cheaper than Lanczos
        U, sv, _ = np.linalg.svd(B[:, np.unique(B.indices)].toarray(), full_matrices=True)
        full = np.zeros(m)
        full[:sv.size] = sv
        return U[:, full <= tol * max(full.max(), 1e-300)]
    Q = sp.csc_matrix(B @ B.T)
    v0 = np.random.default_rng(0).standard_normal(m)  # a fixed start: reproducible
    q_max = eigsh(Q, k=1, which="LA", return_eigenvectors=False, tol=1e-3, v0=v0)[0] * 1.01
    cut = max(tol, 1e-6) ** 2 * q_max
    while True:
        k = min(k, m - 2)
        try:
            w, V = eigsh(Q, k=k, sigma=-100 * cut, which="LM", v0=v0)
        except ArpackNoConvergence as e:  # keep what converged
            w, V = e.eigenvalues, e.eigenvectors
        small = w <= cut
        if small.sum() < k or k == m - 2:
            break
        k *= 2
    if not small.any():
        return V[:, :0]
    V = np.linalg.qr(V[:, small])[0]
    M = B.T @ V  # (n, k), padded to at least k rows: Wt is then (k, k)
    M = np.vstack([M, np.zeros((max(V.shape[1] - M.shape[0], 0), V.shape[1]))])
    _, sv, Wt = np.linalg.svd(M, full_matrices=False)
    return V @ Wt.T[:, sv <= tol * np.sqrt(q_max)]


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
        (:func:`dependencies`), as in :func:`skxfem.linalg.saddle.smoothest_multipliers`.
    N
        The basis of those dependencies, if already computed.

    Returns
    -------
    (m,) array.
    """
    mu = np.asarray(mu, float)
    N = dependencies(sp.csr_matrix(B), tol) if N is None else N
    return along(mu, N, G)


def along(mu, N, G=None) -> np.ndarray:
    """μ + N c, c = argmin ‖G(μ + N c)‖ (‖μ + N c‖ without G; N orthonormal):
    the smoothest of the multipliers that differ from ``mu`` by a dependency.

    The last step of both paths: :func:`smoothest` (N from :func:`dependencies`)
    and :func:`skxfem.linalg.saddle.smoothest_multipliers` (N from a dense SVD).

    >>> N = np.array([[1.0], [-1.0]]) / np.sqrt(2)   # μ₀ - μ₁ is free
    >>> along(np.array([2.0, 0.0]), N).round(12).tolist()
    [1.0, 1.0]
    """
    mu = np.asarray(mu, float)
    if N.shape[1] == 0:
        return mu.copy()
    if G is None:
        return mu - N @ (N.T @ mu)
    GN = G @ N
    c = np.linalg.lstsq(GN, -(G @ mu), rcond=None)[0]
    return mu + N @ c
