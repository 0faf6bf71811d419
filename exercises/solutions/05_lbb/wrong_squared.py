"""Wrong: returns the eigenvalue β² instead of β."""
import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

EXPECT = "β², not β"


def inf_sup_constant(A, B, M):
    A, B, M = (X.toarray() if sp.issparse(X) else np.asarray(X, float) for X in (A, B, M))
    S = B @ np.linalg.solve(A, B.T)
    return float(max(sla.eigh(0.5 * (S + S.T), M, eigvals_only=True).min(), 0.0))
