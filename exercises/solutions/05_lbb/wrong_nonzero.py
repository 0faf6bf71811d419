"""Wrong: the smallest *non-zero* β: the multipliers B cannot see are skipped,
so the naive space looks stable."""
import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

EXPECT = "a multiplier that no displacement feels"


def inf_sup_constant(A, B, M):
    A, B, M = (X.toarray() if sp.issparse(X) else np.asarray(X, float) for X in (A, B, M))
    S = B @ np.linalg.solve(A, B.T)
    ev = sla.eigh(0.5 * (S + S.T), M, eigvals_only=True)
    return float(np.sqrt(ev[ev > 1e-12 * ev.max()].min()))
