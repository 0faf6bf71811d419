"""Projected Krylov methods: the kernels of :mod:`skxfem.linalg.iterative`.

CG for A x = b on an affine space x₀ + ker B, preconditioned by Π M Π with Π
the orthogonal projection onto ker B (Gould, Hribar & Nocedal), and the
interface solve that Π needs.  Where the multipliers act along other
directions C than the constraints B (A x + Cᵀy = b, B x = c: the normal of a
sliding Coulomb point tilted by its friction), the system is not symmetric on
ker B: :func:`projected_gmres` solves Q(b - A x) = 0 there, Q = I - Cᵀ(B Cᵀ)⁻¹B
the projection onto ker B along the directions of the multipliers.

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

__all__ = ["projected_cg", "projected_gmres", "interface_solve", "oblique_solve"]


STALLED_RESTARTS = 3
""":func:`projected_cg` stops after this many restarts in a row that did not bring the
true residual below 0.9 of the least one before: rounding holds it there.  A 2D tie of
529 416 unknowns (``scenes.strip(512, cell="tri")``, ``tol`` 1e-12) restarted at 1.7e-12
up to the 500-iteration limit and raised after 38 s; it now stops after 77 iterations
(7.5 s), its answer within 3.6e-14 of the direct solve's (one run, 29 November 2026;
:func:`skxfem.linalg.iterative.solve` then judges it by its backward error)."""


def projected_cg(A, M, project, b, x, atol, maxiter):
    """CG for A x = b on x + ker B (x meets the constraint), preconditioned by
    Π M Π: x and the residuals ‖Π(b - A x)‖, one per iteration.  The true
    residual is checked before stopping (a restart if the recursive one
    drifted); a direction without energy (A singular on ker B), or restarts that
    no longer lower the true residual (:data:`STALLED_RESTARTS`), stop it."""
    res = project(b - A @ x)
    history = [np.linalg.norm(res)]
    least, stalled = np.inf, 0
    while history[-1] > atol and len(history) <= maxiter and stalled < STALLED_RESTARTS:
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
        stalled = stalled + 1 if history[-1] >= 0.9 * least else 0
        least = min(least, history[-1])
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


def projected_gmres(A, M, project, oblique, b, x, atol, maxiter, restart: int = 40):
    """GMRES for Q(b - A x) = 0 on x + ker B (x meets the constraint), Q =
    ``oblique`` the projection onto ker B along the multipliers' directions,
    right-preconditioned by Π M Π (Π = ``project``): x and the residual norms
    ‖Q(b - A x)‖, one per iteration, restarted every ``restart`` iterations
    from the true residual.

    >>> import numpy as np, scipy.sparse as sp
    >>> A = sp.diags([2.0, 3.0, 4.0]).tocsr(); I = sp.identity(3)
    >>> B = sp.csr_matrix([[1.0, -1.0, 0.0]]); C = sp.csr_matrix([[1.0, -0.5, 0.0]])
    >>> inv, obl = interface_solve(B, 1e-12, 2), oblique_solve(B, C)
    >>> x, h = projected_gmres(A, I, lambda v: v - B.T @ inv(B @ v),
    ...                        lambda v: v - C.T @ obl(B @ v), np.ones(3), np.zeros(3), 1e-12, 10)
    >>> y = (np.ones(3) - A @ x)[0]        # b - A x = Cᵀ y: y = 1 - 2 x₀
    >>> np.allclose(np.ones(3) - A @ x, C.T @ [y]), bool(abs(x[0] - x[1]) < 1e-12)
    (True, True)
    """
    res = oblique(b - A @ x)
    history = [np.linalg.norm(res)]
    while history[-1] > atol and len(history) <= maxiter:
        beta = history[-1]
        V, Z = [res / beta], []
        H = np.zeros((restart + 1, restart))
        cs, sn = np.zeros(restart), np.zeros(restart)
        g = np.zeros(restart + 1)
        g[0] = beta
        j = -1
        for j in range(restart):
            Z.append(project(M @ V[j]))
            w = oblique(A @ Z[j])
            for i in range(j + 1):  # modified Gram-Schmidt
                H[i, j] = V[i] @ w
                w = w - H[i, j] * V[i]
            H[j + 1, j] = h_next = np.linalg.norm(w)
            for i in range(j):  # the rotations so far, then a new one
                H[i, j], H[i + 1, j] = (cs[i] * H[i, j] + sn[i] * H[i + 1, j],
                                        -sn[i] * H[i, j] + cs[i] * H[i + 1, j])
            rho = np.hypot(H[j, j], H[j + 1, j])
            cs[j], sn[j] = (H[j, j] / rho, H[j + 1, j] / rho) if rho > 0 else (1.0, 0.0)
            H[j, j], g[j + 1], g[j] = rho, -sn[j] * g[j], cs[j] * g[j]
            history.append(abs(g[j + 1]))
            if history[-1] <= atol or len(history) > maxiter or h_next == 0:
                break  # converged, out of iterations, or the exact answer (h_next = 0)
            V.append(w / h_next)
        n = j + 1
        diag = np.abs(np.diag(H[:n, :n]))
        if n == 0 or not np.all(diag > 1e-300):  # breakdown: the caller reports it
            return x, history
        y = np.linalg.solve(np.triu(H[:n, :n]), g[:n])
        x = x + sum(yi * z for yi, z in zip(y, Z))
        res = oblique(b - A @ x)  # the true residual
        history[-1] = np.linalg.norm(res)
    return x, history


def oblique_solve(Bn, Cn):
    """v ↦ (B_n C_nᵀ)⁻¹ v: SuperLU of the interface matrix B_n C_nᵀ (nonsymmetric)."""
    if Bn.shape[0] == 0:
        return lambda v: np.zeros(0)
    lu = splu(sp.csc_matrix(Bn @ Cn.T))
    return lu.solve
