"""Projected conjugate gradients: the Krylov kernel of :mod:`skxfem.linalg.iterative`.

CG for A x = b on an affine space x₀ + ker B, preconditioned by Π M Π with Π
the orthogonal projection onto ker B (Gould, Hribar & Nocedal), and the
interface solve that Π needs.

>>> import numpy as np, scipy.sparse as sp
>>> A = sp.diags([2.0, 3.0, 4.0]).tocsr(); Bn = sp.csr_matrix([[1.0, -1.0, 0.0]])
>>> inv = interface_solve(Bn, 1e-12, 2)
>>> project = lambda v: v - Bn.T @ inv(Bn @ v)
>>> x, history = projected_cg(A, sp.identity(3), project, np.ones(3), np.zeros(3), 1e-12, 10)
>>> np.round(x, 12).tolist()       # x₀ = x₁ (B x = 0), A x = b on ker B
[0.4, 0.4, 0.25]
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

__all__ = ["projected_cg", "interface_solve"]


def projected_cg(A, M, project, b, x, atol, maxiter):
    """CG for A x = b on x + ker B (x meets the constraint), preconditioned by
    Π M Π: x and the residuals ‖Π(b - A x)‖, one per iteration.  The true
    residual is checked before stopping (a restart if the recursive one
    drifted); a direction without energy (A singular on ker B) stops it."""
    res = project(b - A @ x)
    history = [np.linalg.norm(res)]
    while history[-1] > atol and len(history) <= maxiter:
        z = project(M @ res)
        rz, d = res @ z, z
        while history[-1] > atol and len(history) <= maxiter:
            q = A @ d
            if not d @ q > 0:  # breakdown: the caller reports the residual reached
                return x, history
            alpha = rz / (d @ q)
            x = x + alpha * d
            res = res - alpha * project(q)
            history.append(np.linalg.norm(res))
            z = project(M @ res)
            rz, rz_old = res @ z, rz
            d = z + (rz / rz_old) * d
        res = project(b - A @ x)  # the true residual
        history[-1] = np.linalg.norm(res)
    return x, history


def interface_solve(Bn, delta, refine):
    """v ↦ (B_n B_nᵀ)⁻¹ v on the range of B_n: SuperLU of B_n B_nᵀ + δI, refined."""
    m = Bn.shape[0]
    if m == 0:
        return lambda v: np.zeros(0)
    Q = (Bn @ Bn.T).tocsr()
    lu = splu((Q + delta * sp.identity(m)).tocsc())

    def apply(v):
        y = lu.solve(v)
        for _ in range(refine):
            y += lu.solve(v - Q @ y)
        return y
    return apply
