r"""The linear solve of one contact Newton step: direct, or iterative where the step is a tie.

:func:`direct` solves the whole Newton matrix of :mod:`skxfem.contact_newton`
by SuperLU.  :func:`iterative` uses that the step of a frictionless or
adhesive law *is* a tied problem.  In the Newton matrix, the row of a closed
dof j (χ_j = 1) is the linearised d_j = 0 and that of an open dof fixes its
multiplier:

.. math:: \frac{\rho_n}{w_j} B_{n,j} \Delta U = -R_{n,j} \quad (\chi_j = 1),
          \qquad \Delta\lambda_j = -R_{n,j} \quad (\chi_j = 0),

and ``adhesive`` adds, per tangent a, ρ_τ/w_j B_{τa,j} ΔU = R_{τa,j} at
closed dofs and ΔT_{aj} = -R_{τa,j} at open ones.  The open unknowns are
known; moved to the right-hand side of equilibrium they leave

.. math:: K \Delta U + B^T y = f, \qquad B \Delta U = c, \qquad
          (\Delta\lambda, \Delta T)_{closed} = -y,

with B the closed rows of B_n (and of the B_τa), f = -R_u + the open rows'
forces: the tie of :func:`skxfem.iterative.solve` with a right-hand side c.
A Coulomb step is not a tie: at a closed dof Δλ also moves the friction
force μλΛ, a coupling no tie has.  :class:`TieStep` solves the step without
it (J₀); at a slipping dof it eliminates ΔΛ = (I - DP)⁻¹(-R_τ + ρ_τ/w DP B_τ
ΔU), a symmetric interface stiffness.  FGMRES on the whole step, J₀⁻¹ as its
preconditioner, adds the coupling back (one AMG set-up per step, shared by
every preconditioner call).  ``auto`` keeps Coulomb direct
(:func:`skxfem.linear.choose_linear`).

>>> import numpy as np, scipy.sparse as sp
>>> x, rows, lu = direct(sp.csr_matrix([[4.0, 1.0], [1.0, 0.0]]), np.array([-1.0, 0.0]), 1)
>>> x.round(12).tolist()
[0.0, 1.0]
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .amg import pyamg
from .contact_laws import ball_projection, friction_coefficient, held, just_closed, normal_update
from .iterative import ConvergenceError
from .iterative import solve as tie_solve

__all__ = ["scales", "direct", "iterative", "TieStep", "NEAR_STICK"]

NEAR_STICK = 1e-2
"""Slip points with |g_τ| ≤ 1 + NEAR_STICK are taken as stick in the Coulomb
preconditioner: eliminating their Λ would add a stiffness ∝ 1/(|g_τ| - 1)."""


def scales(A, nu):
    """Row and column scales (r, c) of the Newton matrix ``A``: Jacobi on the
    first ``nu`` (displacement) unknowns, the others to unit max."""
    A = sp.csr_matrix(A)
    n = A.shape[0]
    diag = np.abs(A.diagonal()[:nu])
    c = np.ones(n)
    c[:nu] = 1.0 / np.sqrt(np.where(diag > 0, diag, 1.0))
    r = c.copy()
    A1 = sp.diags(r) @ A @ sp.diags(c)
    c[nu:] /= np.maximum(abs(A1[:, nu:]).max(axis=0).toarray().ravel(), 1e-300)
    A1 = A @ sp.diags(c)
    r[nu:] = 1.0 / np.maximum(abs(A1[nu:]).max(axis=1).toarray().ravel(), 1e-300)
    return r, c


def direct(A, R, nu, reuse=None):
    """Solve A x = -R by SuperLU on the scaled matrix: x, the row scales, and
    the factorisation, which ``reuse`` passes back to the next call: if A has
    not changed (a Newton step whose active set and, for Coulomb, iterate
    leave the matrix as it was), it is not factorised again."""
    A = sp.csr_matrix(A)
    if reuse is not None and reuse[0].shape == A.shape and (reuse[0] != A).nnz == 0:
        _, r, c, lu = reuse
        return c * lu.solve(-r * R), r, reuse
    r, c = scales(A, nu)
    As = sp.diags(r) @ A @ sp.diags(c)
    try:
        lu = spla.splu(As.tocsc(), permc_spec="COLAMD")
        pivots = np.abs(lu.U.diagonal())
        if pivots.min() < 1e-11 * pivots.max():
            raise RuntimeError(f"smallest LU pivot {pivots.min() / pivots.max():.1e} "
                               f"of the largest")
    except RuntimeError as e:  # SuperLU: "Factor is exactly singular"
        raise ValueError(
            f"the contact Newton matrix is singular ({e}): either a part of the body can "
            f"move freely (a frictionless or open interface leaves a rigid motion of one "
            f"side: add supports on each side), or some multipliers depend on the others "
            f"(the naive space on tetrahedra, or a support acting on a face that Γ cuts: "
            f"use space='vital' or move the support)") from e
    return c * lu.solve(-r * R), r, (A, r, c, lu)


def iterative(ops, law, K, free, R, lam, T, g_n, g_t, A, modes=None, blocksize=1,
              tol=1e-12, maxiter=50, near=NEAR_STICK, reuse=None, inner_tol=1e-6):
    """Solve the Newton step J x = -R (J = ``A``, the Newton matrix) by ties.

    ``R`` = (R_u, R_n, R_t) and (λ, T, g_n, g_τ) the iterate, as
    :func:`skxfem.contact_newton.residual`; ``modes``, ``blocksize`` as
    :func:`skxfem.iterative.solve`.  Where J₀ = J (:attr:`TieStep.exact`:
    frictionless and adhesive laws, a frozen Coulomb threshold without slip
    points near the ball's boundary): one tie solve to ``tol``.
    Coulomb: FGMRES on the scaled J, preconditioned by :class:`TieStep` (its
    ties solved to ``inner_tol``), to the relative residual ``tol`` within
    ``maxiter`` iterations (measured: 6-14 per Newton step on a 3D block).  Returns x =
    (ΔU_free, Δλ, ΔT) and the tie's :class:`skxfem.iterative.Setup`, which
    ``reuse`` passes back to the next call (the same tie: no second AMG).

    Raises
    ------
    ValueError
        Dependent multipliers (the direct path refuses them too: the law must
        hold at every dof, so its multiplier must be unique).
    skxfem.iterative.ConvergenceError, skxfem.saddle.SingularSystemError
        As :func:`skxfem.iterative.solve` (a part of the body free to move),
        or the FGMRES of a Coulomb step short of ``tol``.
    """
    step = TieStep(ops, law, K, free, lam, T, g_n, g_t, modes, blocksize, near, reuse)
    if step.exact:  # J₀ = J: one tie solve is the step
        return step(R, tol), step.setup
    Rv = np.concatenate(R)
    r, c = scales(A, len(free))
    As = (sp.diags(r) @ sp.csr_matrix(A) @ sp.diags(c)).tocsr()

    def precondition(v):  # c⁻¹ J₀⁻¹ r⁻¹ v: every call the same tie
        parts = np.split(v / r, [len(free), len(free) + lam.size])
        return step([-p for p in parts], inner_tol) / c
    M = spla.LinearOperator(As.shape, matvec=precondition, dtype=float)
    history = []
    x, _ = pyamg().krylov.fgmres(As, -r * Rv, tol=tol, restart=min(maxiter, As.shape[0]),
                                 maxiter=1, M=M, residuals=history)
    reached = np.linalg.norm(As @ x + r * Rv) / max(np.linalg.norm(r * Rv), 1e-300)
    if not reached <= 10 * tol:
        raise ConvergenceError(
            f"the Coulomb Newton step did not reach the relative residual {tol:.0e} in "
            f"{len(history) - 1} FGMRES iterations (reached {reached:.1e}): use "
            f"linear='direct'", len(history) - 1, float(reached))
    return c * x, step.setup


class TieStep:
    """J₀⁻¹ as a tie: ``step(R, tol)`` is x = J₀⁻¹(-R), J₀ = J but for Coulomb's -μTΔλ
    at closed dofs (and slip points within ``near`` of the ball taken as stick).

    Open (and held) dofs: Δλ = -R_n, ΔΛ = -R_τ.  Closed: the rows of B_n;
    stick (DP = I): the rows of B_τa, multiplier r = coef ΔΛ; slip: ΔΛ =
    (I - DP)⁻¹(-R_τ + ρ_τ/w DP B_τ ΔU), whose force adds the symmetric
    -coef ρ_τ/w B_τᵀ (I - DP)⁻¹ DP B_τ (coef = μλ ≤ 0) to K.  The tie (K, B
    and the dofs' kinds) is built once, here; the first call builds its
    :class:`skxfem.iterative.Setup` (or takes ``reuse``), kept in ``setup``
    for the next calls.  ``exact``: J₀ = J.
    """

    def __init__(self, ops, law, K, free, lam, T, g_n, g_t, modes=None, blocksize=1,
                 near=0.0, reuse=None):
        m, k = lam.size, T.shape[1]
        self.ops, self.law, self.free, self.m, self.k = ops, law, free, m, k
        self.modes, self.blocksize, self.setup = modes, blocksize, reuse
        self.closed = closed = normal_update(g_n)[1] > 0
        eye = np.eye(k)
        coef, DP, coupled = np.ones(m), np.broadcast_to(eye, (m, k, k)).copy(), np.zeros((m, k))
        friction = closed & ~held(law, g_n)  # the rows of ΔΛ that see ΔU
        approximated = np.zeros(m, bool)
        if law.name == "coulomb":
            new = just_closed(law, lam, g_n)
            coef = np.where(new, 1.0, friction_coefficient(law, lam))
            DP = ball_projection(g_t)[1]
            norm = np.linalg.norm(g_t, axis=1)
            approximated = friction & (norm > 1) & (norm <= 1 + near)
            DP[new | (norm <= 1 + near)] = eye
            if law.threshold is None:  # Δλ moves r_τ = μλΛ: known at the open dofs only
                coupled = law.mu * np.where(new[:, None], 0.0, T)
        self.exact = law.name != "coulomb" or (law.threshold is not None
                                               and not approximated.any())
        self.stick = stick = friction & np.all(np.isclose(DP, eye), axis=(1, 2))
        self.slip = slip = friction & ~stick
        self.coef, self.DP, self.coupled = coef, DP, coupled
        self.Minv = np.linalg.inv(eye - DP[slip]) if slip.any() else np.zeros((0, k, k))
        self.Bt = Bt = [ops.Bt[a] for a in range(k)]
        if slip.any():  # the slip force's ΔU part: a symmetric interface stiffness
            C = (-coef[slip] * law.rho_t / ops.w[slip])[:, None, None] * (self.Minv @ DP[slip])
            W = sp.bmat([[sp.diags(C[:, a, b]) for b in range(k)] for a in range(k)])
            Bs = sp.vstack([B[slip] for B in Bt], format="csr")
            K = (K + Bs.T @ W @ Bs).tocsr()
        self.K = K
        self.B = sp.vstack([ops.Bn[closed]] + [B[stick] for B in Bt], format="csr")
        self.fixed = np.setdiff1d(np.arange(K.shape[0]), free)

    def __call__(self, R, tol: float) -> np.ndarray:
        ops, law, k, closed, stick, slip = self.ops, self.law, self.k, self.closed, \
            self.stick, self.slip
        coef, coupled, Minv, DP, Bt = self.coef, self.coupled, self.Minv, self.DP, self.Bt
        R_u, R_n, R_t = R
        Rt = R_t.reshape(k, self.m).T
        d_lam = np.where(closed, 0.0, -R_n)
        d_T = np.where(stick[:, None], 0.0, -Rt)
        d_T[slip] = np.einsum("sab,sb->sa", Minv, -Rt[slip])
        f = np.zeros(self.K.shape[0])
        f[self.free] = -R_u
        f += ops.Bn.T @ d_lam + sum(Bt[a].T @ (coef * d_T[:, a] + coupled[:, a] * d_lam)
                                    for a in range(k))
        rhs = np.concatenate([-(ops.w / law.rho_n * R_n)[closed]]
                             + [(ops.w / law.rho_t * Rt[:, a])[stick] for a in range(k)])
        dU, mu, info = tie_solve(self.K, self.B, f, self.fixed, np.zeros(self.fixed.size),
                                 c=rhs, modes=self.modes, blocksize=self.blocksize, tol=tol,
                                 reuse=self.setup)
        self.setup = info.setup
        if info.removed:  # as the direct path: a pressure at every dof must be unique
            raise ValueError(
                f"{info.removed} contact multipliers depend on the others (the naive space "
                f"on tetrahedra, or a support acting on a face that Γ cuts): use "
                f"space='vital' or move the support")
        nc = int(closed.sum())
        d_lam[closed] = mu[:nc]
        d_T[stick] = mu[nc:].reshape(k, int(stick.sum())).T / coef[stick, None]
        if slip.any():
            jump = np.stack([B[slip] @ dU for B in Bt], axis=1) * (
                law.rho_t / ops.w[slip])[:, None]
            d_T[slip] += np.einsum("sab,sbc,sc->sa", Minv, DP[slip], jump)
        return np.concatenate([dU[self.free], d_lam, d_T.T.ravel()])
