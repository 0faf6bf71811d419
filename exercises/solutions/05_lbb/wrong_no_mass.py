"""Wrong: the plain eigenvalues of B A⁻¹ Bᵀ, without the multiplier norm M."""
import numpy as np
import scipy.sparse as sp

EXPECT = "the norm of the multipliers, M"


def inf_sup_constant(A, B, M):
    A, B = (X.toarray() if sp.issparse(X) else np.asarray(X, float) for X in (A, B))
    S = B @ np.linalg.solve(A, B.T)
    return float(np.sqrt(max(np.linalg.eigvalsh(0.5 * (S + S.T)).min(), 0.0)))
