r"""The linear solve of one contact Newton step: direct, or iterative where the step is a tie.

:func:`direct` solves the whole Newton matrix of :mod:`skxfem.contact.newton`
by SuperLU.  :func:`iterative` uses that the step of a frictionless or
adhesive law *is* a tied problem.  In the Newton matrix, the row of a closed
dof j (χ_j = 1) is the linearised d_j = 0 and that of an open dof fixes its
multiplier:

.. math:: \frac{\rho_n}{w_j} B_{n,j} \Delta U = -R_{n,j} \quad (\chi_j = 1),
          \qquad \Delta\lambda_j = -R_{n,j} \quad (\chi_j = 0),

and a stick point adds, per tangent a, ρ_τ/w_j B_{τa,j} ΔU = -R_{τa,j}, where
an open (or free, or held) one has Δr_{τa,j} = -R_{τa,j}.  The known
unknowns moved to the right-hand side of equilibrium leave

.. math:: K \Delta U + B^T y = f, \qquad B \Delta U = c, \qquad
          (\Delta\lambda, \Delta r_\tau)_{tied} = -y,

with B the tied rows of B_n and of the B_τa and f = -R_u + the known
multipliers' forces: the tie of :func:`skxfem.linalg.iterative.solve` with a
right-hand side c.  A Coulomb step is not a tie: at a slipping dof, the
radius μp of its ball moves with Δλ, a coupling no tie has.
:class:`TieStep` solves the step without it (J₀; the radius' dependence on
ΔU is known from the normal row there, ρ_n B_n ΔU/w = -R_n); at a slipping
dof it eliminates Δr_τ = (I - DP)⁻¹(-R_τ - ρ_τ/w DP B_τ ΔU + ...), a
symmetric interface stiffness ρ_τ/w B_τᵀ(I - DP)⁻¹DP B_τ.  FGMRES on the whole
step, J₀⁻¹ as its preconditioner, adds the coupling back (one AMG set-up per
step, shared by every preconditioner call).  ``auto`` keeps Coulomb direct
(:func:`skxfem.linalg.choice.choose_linear`).

>>> import numpy as np, scipy.sparse as sp
>>> x, rows, lu = direct(sp.csr_matrix([[4.0, 1.0], [1.0, 0.0]]), np.array([-1.0, 0.0]), 1)
>>> x.round(12).tolist()
[0.0, 1.0]
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..linalg.amg import pyamg
from ..linalg.iterative import ConvergenceError
from ..linalg.iterative import solve as tie_solve
from ..linalg.saddle import SingularSystemError, factorise, floating
from .laws import disk_projection

__all__ = ["scales", "direct", "iterative", "TieStep", "NEAR_STICK", "SingularStepError"]

NEAR_STICK = 1e-2
"""Slip points with |y| ≤ (1 + NEAR_STICK) R are taken as stick in the Coulomb
preconditioner: eliminating their r_τ would add a stiffness ∝ 1/(|y|/R - 1)."""


class SingularStepError(ValueError):
    """A singular Newton matrix: a part of the body free in the step's active
    set, or multipliers that depend on the others."""


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
    lu = factorise(sp.diags(r) @ A @ sp.diags(c), floating=_singular_step)
    return c * lu.solve(-r * R), r, (A, r, c, lu)


def _singular_step(detail: str) -> SingularStepError:
    error = floating(detail, "the contact Newton matrix", "; or some multipliers depend on "
                     "the others (the naive space on tetrahedra): use space='vital'")
    return SingularStepError(str(error))


def iterative(step, it, res, A, modes=None, blocksize=1, close=None, tol=1e-12, maxiter=50,
              near=NEAR_STICK, reuse=None, inner_tol=1e-6):
    """Solve the Newton step J x = -R (J = ``A``, at the iterate ``it`` with
    residual ``res`` of the :class:`~skxfem.contact.newton.StepProblem` ``step``) by ties.

    ``modes``, ``blocksize`` as :func:`skxfem.linalg.iterative.solve`; ``close`` as
    :func:`skxfem.contact.newton.jacobian`.  Where J₀ = J
    (:attr:`TieStep.exact`: frictionless and adhesive laws, a frozen Coulomb
    threshold, no slip point near the ball's boundary): one tie solve to
    ``tol``.  Coulomb: FGMRES on the scaled J, preconditioned by
    :class:`TieStep` (its ties solved to ``inner_tol``), to the relative
    residual ``tol`` within ``maxiter`` iterations.  Returns x = (ΔU_free, Δλ,
    Δr_τ) and the tie's :class:`skxfem.linalg.iterative.Setup`, which ``reuse``
    passes back to the next call (the same tie: no second AMG).

    Raises
    ------
    SingularStepError
        Dependent multipliers (the direct path refuses them too: the law must
        hold at every dof, so its multiplier must be unique), or a part of the
        body free in the step's active set.
    skxfem.linalg.iterative.ConvergenceError
        The FGMRES of a Coulomb step short of ``tol``.
    """
    tie = TieStep(step, res, modes, blocksize, near, reuse, close)
    R = (res.R_u, res.R_n, res.R_t)
    if tie.exact:  # J₀ = J: one tie solve is the step
        return tie(R, tol), tie.setup
    Rv = res.vector
    r, c = scales(A, step.nu)
    As = (sp.diags(r) @ sp.csr_matrix(A) @ sp.diags(c)).tocsr()
    m, k = res.R_t.shape

    def precondition(v):  # c⁻¹ J₀⁻¹ r⁻¹ v: every call the same tie
        parts = np.split(v / r, [step.nu, step.nu + m])
        return tie((-parts[0], -parts[1], -parts[2].reshape(k, m).T), inner_tol) / c
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
    return c * x, tie.setup


class TieStep:
    """J₀⁻¹ as a tie: ``tie(R, tol)`` is x = J₀⁻¹(-R), R = (R_u, R_n, R_t (m, k)),
    J₀ = J but for the Δλ in the radius of Coulomb's ball at slipping dofs (and
    slip points within ``near`` of the ball taken as stick).

    Open dofs: Δλ = -R_n; tangential components free, held or open: Δr = -R_t.
    Closed: the rows of B_n; stick (DQ = I): the rows of B_τa, multiplier Δr;
    slip: Δr = (I - DQ)⁻¹(-R_τ - ρ_τ/w DQ B_τ ΔU - q_R μ R_n), whose force adds
    the symmetric ρ_τ/w B_τᵀ (I - DQ)⁻¹ DQ B_τ to K.  The tie (K, B and the
    dofs' kinds) is built once, here; the first call builds its
    :class:`skxfem.linalg.iterative.Setup` (or takes ``reuse``), kept in ``setup``
    for the next calls.  ``exact``: J₀ = J.
    """

    def __init__(self, step, res, modes=None, blocksize=1, near=0.0, reuse=None, close=None):
        laws, ops = step.laws, step.ops
        m, k = res.y.shape
        self.step, self.m, self.k = step, m, k
        self.modes, self.blocksize, self.setup = modes, blocksize, reuse
        chi = np.where(laws.unilateral, res.g_n <= 0, True)
        if close is not None:
            chi = chi | close
        self.closed = chi
        eye = np.eye(k)
        DQ = np.zeros((m, k, k))
        qR = np.zeros((m, k))
        stick_law, coulomb = laws.tangential == "stick", laws.tangential == "coulomb"
        DQ[stick_law & chi] = eye
        approximated = np.zeros(m, bool)
        c = coulomb & (chi | (res.dR_dlam != 0))
        if c.any():
            y = res.y[c]
            if close is not None:
                y = np.where((res.g_n[c] > 0)[:, None], 0.0, y)
            _, DQ[c], qR[c] = disk_projection(y, res.radius[c])
            norm = np.zeros(m)
            norm[c] = np.linalg.norm(y, axis=1)
            approximated = c & (norm > res.radius) & (norm <= (1 + near) * res.radius)
            DQ[approximated] = eye
            qR[approximated] = 0.0
        mask = ~laws.tangent_held
        DQ = DQ * mask[:, None, :] * mask[:, :, None]
        dR_dlam = np.where(c, res.dR_dlam, 0.0)
        dR_dU = np.where(c, res.dR_dU, 0.0)
        self.exact = not ((np.abs(qR).sum(axis=1) * dR_dlam != 0).any() or approximated.any())
        nz = DQ.any(axis=(1, 2))
        eyem = eye * mask[:, :, None] * mask[:, None, :]
        self.stick = stick = chi & nz & np.all(np.isclose(DQ, eyem), axis=(1, 2))
        self.slip = slip = chi & nz & ~stick
        self.tied = tied = stick[:, None] & mask  # (m, k): the tangential rows of the tie
        self.DQ, self.qR, self.dR_dU = DQ, qR, dR_dU
        Iminus = eye - DQ[slip]
        self.Minv = np.linalg.inv(Iminus) if slip.any() else np.zeros((0, k, k))
        self.Bt = Bt = [ops.Bt[a] for a in range(k)]
        K = step.K
        iw = 1.0 / ops.w
        if slip.any():  # the slip force's ΔU part: a symmetric interface stiffness
            C = (laws.rho_t[slip] * iw[slip])[:, None, None] * (self.Minv @ DQ[slip])
            W = sp.bmat([[sp.diags(C[:, a, b]) for b in range(k)] for a in range(k)])
            Bs = sp.vstack([B[slip] for B in Bt], format="csr")
            K = (K + Bs.T @ W @ Bs).tocsr()
        self.K = K
        self.B = sp.vstack([ops.Bn[chi]] + [Bt[a][tied[:, a]] for a in range(k)],
                           format="csr")
        self.fixed = np.setdiff1d(np.arange(K.shape[0]), step.free)

    def __call__(self, R, tol: float) -> np.ndarray:
        step, k = self.step, self.k
        laws, ops = step.laws, step.ops
        closed, slip = self.closed, self.slip
        Minv, DQ, Bt = self.Minv, self.DQ, self.Bt
        R_u, R_n, Rt = R
        iw = 1.0 / ops.w
        d_lam = np.where(closed, 0.0, -R_n)
        d_r = np.where(self.tied, 0.0, -Rt)
        # slip: the radius' ΔU part is known from the normal row, ρ_n B_n ΔU/w = -R_n
        known = -Rt[slip] - (self.qR[slip] * (self.dR_dU[slip] * R_n[slip])[:, None])
        d_r[slip] = np.einsum("sab,sb->sa", Minv, known)
        f = np.zeros(self.K.shape[0])
        f[step.free] = -R_u
        f += ops.Bn.T @ d_lam + sum(Bt[a].T @ d_r[:, a] for a in range(k))
        rhs = np.concatenate([-(ops.w / laws.rho_n * R_n)[closed]]
                             + [-(ops.w / laws.rho_t * Rt[:, a])[self.tied[:, a]]
                                for a in range(k)])
        try:
            dU, mu, info = tie_solve(self.K, self.B, f, self.fixed, np.zeros(self.fixed.size),
                                     c=rhs, modes=self.modes, blocksize=self.blocksize,
                                     tol=tol, reuse=self.setup)
        except SingularSystemError as e:  # a part free in this active set
            raise SingularStepError(str(e)) from e
        self.setup = info.setup
        if info.removed:  # as the direct path: a pressure at every dof must be unique
            raise SingularStepError(
                f"{info.removed} contact multipliers depend on the others (the naive space "
                f"on tetrahedra): use space='vital'")
        nc = int(closed.sum())
        d_lam[closed] = mu[:nc]
        ends = nc + np.cumsum(self.tied.sum(axis=0))
        for a in range(k):
            d_r[self.tied[:, a], a] = mu[ends[a] - self.tied[:, a].sum():ends[a]]
        if slip.any():
            jump = np.stack([B[slip] @ dU for B in Bt], axis=1) * (
                laws.rho_t[slip] * iw[slip])[:, None]
            d_r[slip] -= np.einsum("sab,sbc,sc->sa", Minv, DQ[slip], jump)
        return np.concatenate([dU[step.free], d_lam, d_r.T.ravel()])
