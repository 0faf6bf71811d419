"""Exercise 05: the inf-sup constant of a small saddle-point system (see README.md).

A (N, N) is the symmetric positive definite matrix of the displacement norm,
B (m, N) the coupling (row i: multiplier i against the jump of every
displacement dof) and M (m, m) the SPD matrix of the multiplier norm.  They may
be numpy arrays or scipy sparse matrices.  You may import numpy and scipy; not
skxfem.lbb.
"""
import numpy as np  # noqa: F401  (you will need it)


def inf_sup_constant(A, B, M):
    """The discrete inf-sup constant β = inf_μ sup_v μᵀBv / (‖μ‖_M ‖v‖_A).

    β² is the smallest eigenvalue of the generalised problem
    B A⁻¹ Bᵀ x = β² M x.  It is 0 when some multiplier μ ≠ 0 has Bᵀμ = 0.

    Parameters
    ----------
    A : (N, N) SPD, B : (m, N), M : (m, m) SPD; arrays or sparse matrices.

    Returns
    -------
    float
        β ≥ 0 (round-off below zero counts as zero).

    Examples
    --------
    >>> float(inf_sup_constant(np.eye(3), np.array([[1.0, 0, 0], [0, 2.0, 0]]), np.eye(2)))
    1.0
    """
    raise NotImplementedError("inf_sup_constant: not written yet (exercise 05, see README.md)")


def unseen_multipliers(B, tol=1e-10):
    """The multipliers that no displacement feels: an orthonormal basis of ker Bᵀ.

    Parameters
    ----------
    B : (m, N) array or sparse matrix.
    tol : singular values of B below ``tol`` times the largest count as zero.

    Returns
    -------
    ndarray
        Shape (m, k), orthonormal columns μ with Bᵀμ = 0; k = m - rank(B).

    Examples
    --------
    >>> unseen_multipliers(np.array([[1.0, 0.0], [2.0, 0.0]])).shape
    (2, 1)
    """
    raise NotImplementedError("unseen_multipliers: not written yet (exercise 05, see README.md)")
