"""Reference for exercise 05.

skxfem.lbb.inf_sup_constant returns the smallest *non-zero* β with the zero
modes counted apart (a report for a solver), so it is not the same contract.
"""
import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

# the library's inf_sup_constant computes β too (zero modes apart): the book shows its
# contract only (skxfem.app.graded reads this list)
LIBRARY_ANSWERS = ("skxfem.lbb.inf_sup_constant",)


def _dense(X):
    return X.toarray() if sp.issparse(X) else np.asarray(X, dtype=float)


def inf_sup_constant(A, B, M):
    A, B, M = _dense(A), _dense(B), _dense(M)
    S = B @ np.linalg.solve(A, B.T)
    ev = sla.eigh(0.5 * (S + S.T), M, eigvals_only=True)
    return float(np.sqrt(max(ev.min(), 0.0)))


def unseen_multipliers(B, tol=1e-10):
    U, s, _ = np.linalg.svd(_dense(B), full_matrices=True)
    rank = int(np.sum(s > tol * s.max())) if s.size and s.max() > 0 else 0
    return U[:, rank:]
