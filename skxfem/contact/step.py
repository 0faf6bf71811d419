r"""The linear solve of one contact Newton step: direct, or iterative as one tie.

:func:`direct` solves the whole Newton matrix of :mod:`skxfem.contact.newton`
by SuperLU.  :func:`iterative` uses that every step *is* a tied problem.  In
the Newton matrix, the row of a closed dof j (χ_j = 1) is the linearised
d_j = 0 and that of an open dof fixes its multiplier:

.. math:: \frac{\rho_n}{w_j} B_{n,j} \Delta U = -R_{n,j} \quad (\chi_j = 1),
          \qquad \Delta\lambda_j = -R_{n,j} \quad (\chi_j = 0),

and a stick point adds, per tangent a, ρ_τ/w_j B_{τa,j} ΔU = -R_{τa,j}.  At a
sliding dof the tangential rows are solved for Δr_τ, which is a function of
ΔU (a symmetric interface stiffness) and of Δλ (the friction force follows the
pressure: the pressure's multiplier acts along a direction tilted by the
friction, :class:`TieStep`).  The known unknowns moved to the right-hand side
of equilibrium leave

.. math:: K' \Delta U + C^T y = f, \qquad B \Delta U = c, \qquad
          (\Delta\lambda, \Delta r_\tau)_{tied} = -y,

with B the tied rows of B_n and of the B_τa, C = B but at the sliding closed
dofs, K' = K plus the sliding stiffness: the tie of
:func:`skxfem.linalg.iterative.solve` with a right-hand side c (projected CG;
projected GMRES where C ≠ B).  The step is exact: the same Δx as
:func:`direct`, to the tie's tolerance.

Why SuperLU stays the direct solver.  ``linear="auto"`` takes :func:`direct` only
below :data:`skxfem.linalg.choice.AUTO_ITERATIVE` unknowns (5000 in 3D), where a
factorisation of the Newton matrix costs a fraction of a second; above, the
iterative step wins by a growing margin, whatever the factorisation: on the
slipping block (:func:`skxfem.scenes.slipping_block`) at 5 346 unknowns the whole
Coulomb solve took 2.5 s iterative against 5.5 s with SuperLU (27 November 2026,
one run each, loaded machine), and Intel's PARDISO (pypardiso), timed 2.5 times
faster than SuperLU on that Newton matrix when this was planned, would not close
the gap, while it pulls about 200 MB of MKL wheels in; python-mumps has no wheel
for this platform's Python in the registry (pip builds it from source and
fails).  So the only
sparse direct solver is scipy's.

>>> import numpy as np, scipy.sparse as sp
>>> x, rows, lu = direct(sp.csr_matrix([[4.0, 1.0], [1.0, 0.0]]), np.array([-1.0, 0.0]), 1)
>>> x.round(12).tolist()
[0.0, 1.0]
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..linalg.iterative import solve as tie_solve
from ..linalg.saddle import SingularSystemError, factorise, floating
from .laws import disk_projection

__all__ = ["scales", "equilibrate", "EQUILIBRATE", "direct", "linearised", "iterative", "TieStep",
           "SingularStepError", "KINK"]


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


EQUILIBRATE = 5
"""Passes of :func:`equilibrate` before the Newton matrix is factorised."""


def equilibrate(A, r, c, passes: int = EQUILIBRATE):
    """Row and column scales of ``A`` from (r, c) by ``passes`` of Ruiz's equilibration
    (each row and column divided by the square root of its largest entry), which
    :func:`direct` factorises: the LU pivots, and so the singularity test of
    :func:`skxfem.linalg.saddle.factorise`, then no longer depend on the units.  With
    :func:`scales` alone the smallest pivot of a 3D crack's Newton matrix, Coulomb faces
    sliding, fell as ρ = E/h grew (measured, smallest over the first steps: 4.5e-5 at
    E = 1, L = 1; 2.7e-8 at E = 2e11; 6.3e-13 at E = 2e11, L = 1e-3, a millimetre cube
    of steel, which was refused as singular, 'a part of the body can move freely');
    equilibrated, 1e-5 to 6e-5 for all, and that cube converges in 5 iterations.
    The row scales of the merit stay those of :func:`scales`."""
    A = abs(sp.csr_matrix(A))
    for _ in range(passes):
        col = (sp.diags(r) @ A @ sp.diags(c)).max(axis=0).toarray().ravel()
        c = c / np.sqrt(np.where(col > 0, col, 1.0))
        row = (sp.diags(r) @ A @ sp.diags(c)).max(axis=1).toarray().ravel()
        r = r / np.sqrt(np.where(row > 0, row, 1.0))
    return r, c


def direct(A, R, nu, reuse=None):
    """Solve A x = -R by SuperLU on the scaled matrix: x, the row scales
    (:func:`scales`, the merit's), and the factorisation, which ``reuse`` passes back
    to the next call: if A has not changed (a Newton step whose active set and, for
    Coulomb, iterate leave the matrix as it was), it is not factorised again.  The
    matrix factorised is scaled by :func:`equilibrate`."""
    A = sp.csr_matrix(A)
    if reuse is not None and reuse[0].shape == A.shape and (reuse[0] != A).nnz == 0:
        _, r, _, lu, (re, ce) = reuse
        return ce * lu.solve(-re * R), r, reuse
    r, c = scales(A, nu)
    re, ce = equilibrate(A, r, c)
    lu = factorise(sp.diags(re) @ A @ sp.diags(ce), floating=_singular_step)
    return ce * lu.solve(-re * R), r, (A, r, c, lu, (re, ce))


def _singular_step(detail: str) -> SingularStepError:
    error = floating(detail, "the contact Newton matrix", "; or some multipliers depend on "
                     "the others (the naive space on tetrahedra): use space='vital'")
    return SingularStepError(str(error))


def linearised(laws, res, close=None, kink: float = 0.0):
    """The derivatives of the laws at each of the m dofs, which the Newton matrix
    (:func:`skxfem.contact.newton.jacobian`) and :class:`TieStep` share: χ (m,)
    (the normal row is the linearised d = 0: closed, 1 at g_n = 0, and the points
    of ``close``), DQ (m, k, k) = ∂Q/∂y and qR (m, k) = ∂Q/∂R of the tangential law
    R_τ = r_τ - Q(y, R) (0 on the components a support holds).

    ``kink`` > 0 (3D): a Coulomb point sliding with R < |y| ≤ (1 + ``kink``) R takes
    the slip branch's derivative at the kink |y| = R⁺, a relative ``kink`` away: DQ =
    I - ŷŷᵀ (R/|y| → 1), qR = ŷ (:data:`KINK`, the fallback of an iterative step that
    did not converge: there M = I - DQ has the eigenvalue 1 - R/|y| → 0 across the
    slip, a sliding stiffness ρ_τ/w (|y|/R - 1)⁻¹ that no Krylov solve resolves; at
    the kink that row is the tie of the jump across ŷ, :class:`TieStep`)."""
    m, k = res.y.shape
    chi = np.where(laws.unilateral, res.g_n <= 0, True)
    if close is not None:
        chi = chi | close
    DQ = np.zeros((m, k, k))
    qR = np.zeros((m, k))
    stick, coulomb = laws.tangential == "stick", laws.tangential == "coulomb"
    DQ[stick] = chi[stick, None, None] * np.eye(k)
    # the ball's derivative where the point is closed or still pressed (λ < 0);
    # elsewhere r_τ = 0 whatever y: DQ = 0
    c = coulomb & (chi | (res.dR_dlam != 0))
    if c.any():
        y = res.y[c]
        if close is not None:  # a point closed by force: its ball holds it (stick)
            y = np.where((res.g_n[c] > 0)[:, None], 0.0, y)
        _, DQ[c], qR[c] = disk_projection(y, res.radius[c])
        if kink > 0 and k == 2:
            norm, R = np.linalg.norm(y, axis=1), res.radius[c]
            near = (norm > R) & (norm <= (1 + kink) * R)
            idx = np.flatnonzero(c)[near]
            yh = y[near] / norm[near, None]
            DQ[idx] = np.eye(k) - yh[:, :, None] * yh[:, None, :]
    mask = ~laws.tangent_held  # y sees r and s on the components not held
    return chi, DQ * mask[:, None, :] * mask[:, :, None], qR


KINK = 1e-4
"""The relative distance |y|/R - 1 within which a sliding Coulomb point is linearised
at the kink (the slip branch's derivative at |y| = R⁺, the jump across the slip tied)
when an iterative step failed (:func:`linearised`): measured on the 3D block pushed
exactly to its slip limit (``tests/test_contact_linear.py``), the iterates come within
1e-8 of the kink and projected CG stalls at 1e-7; taken again at the kink, the block
converges in 4-9 Newton iterations for μ = 0.1 to 5 and ρ_τ ≤ E/h (the stick branch
instead, which ignores how the friction follows the pressure, needed the fixed
point's rescue at μ = 5)."""


def iterative(step, res, modes=None, blocksize=1, close=None, tol=1e-12, reuse=None,
              kink: float = 0.0):
    """Solve the Newton step J x = -R at the residual ``res`` of the
    :class:`~skxfem.contact.newton.StepProblem` ``step`` as one tie (:class:`TieStep`).

    ``modes``, ``blocksize`` as :func:`skxfem.linalg.iterative.solve`; ``close`` as
    :func:`skxfem.contact.newton.jacobian`; ``tol`` the relative residual of the
    tie.  Returns x = (ΔU_free, Δλ, Δr_τ) and the tie's
    :class:`skxfem.linalg.iterative.Setup`, which ``reuse`` passes back to the next
    call (the same tie: no second AMG), and the Krylov iterations it took.

    Raises
    ------
    SingularStepError
        Dependent multipliers (the direct path refuses them too: the law must
        hold at every dof, so its multiplier must be unique), or a part of the
        body free in the step's active set.
    """
    tie = TieStep(step, res, modes, blocksize, reuse, close, kink)
    return tie((res.R_u, res.R_n, res.R_t), tol), tie.setup, tie.iterations


class TieStep:
    r"""The Newton step J x = -R as one tie: ``tie(R, tol)`` is x = J⁻¹(-R), R =
    (R_u, R_n, R_t (m, k)), exactly (module notes).

    Per dof, from :func:`linearised`: an open normal row fixes Δλ = -R_n, a
    closed one is the tie row ρ_n/w B_n ΔU = -R_n; a tangential component whose
    law holds it (DQ = I there: stick) is the tie row ρ_τ/w B_τa ΔU = -R_τa, one a
    support holds has Δr_a = -R_τa; at every other dof (sliding, open) the
    tangential rows are solved for Δr,

    .. math:: \Delta r = M^{-1}\big(k - DQ\,\tfrac{\rho_\tau}{w} B_\tau\Delta U
              + q_R\,\tfrac{\partial R}{\partial\lambda}\Delta\lambda\big),
              \qquad M = I - DQ,

    k = -R_τ the known part.  At a point linearised at the kink (``kink``,
    :func:`linearised`) M = ŷŷᵀ is singular across the slip: that row ties the jump
    across ŷ (one more tie row, whose multiplier is Δr along ŷ⊥) and M's
    pseudo-inverse gives the rest.
    Its force adds the symmetric stiffness ρ_τ/w B_τᵀ M⁻¹DQ B_τ to K, and, at a
    closed dof, tilts the direction of its pressure: the multiplier of the
    normal row acts along C_n = B_n + e·B_τ, e = M⁻¹ q_R ∂R/∂λ (the friction
    force that follows the pressure), which makes the tie unsymmetric
    (:func:`skxfem.linalg.iterative.solve` with ``C``).  The first call builds the
    tie's :class:`skxfem.linalg.iterative.Setup` (or takes ``reuse``), kept in
    ``setup`` for the next calls; a set-up of K alone
    (:func:`skxfem.linalg.iterative.stiffness_setup`), or one carried over from it,
    is carried over to this step's tie (``update``).  The tied rows are taken as
    independent: the contact solve refuses dependent multipliers before its
    first step (:func:`skxfem.contact.history.check_closed`), and every row a
    step ties is one of those it checked.
    """

    def __init__(self, step, res, modes=None, blocksize=1, reuse=None, close=None,
                 kink: float = 0.0):
        laws, ops = step.laws, step.ops
        m, k = res.y.shape
        self.step, self.m, self.k = step, m, k
        self.modes, self.blocksize, self.setup = modes, blocksize, reuse
        self.closed, DQ, qR = closed, DQ, qR = linearised(laws, res, close, kink)
        mask = ~laws.tangent_held
        held_eye = np.eye(k) * mask[:, :, None] * mask[:, None, :]
        stuck = np.all(np.isclose(DQ, held_eye, rtol=0, atol=1e-14), axis=(1, 2)) & \
            mask.any(axis=1) & DQ.any(axis=(1, 2))
        self.tied = stuck[:, None] & mask  # (m, k): the tangential rows of the tie
        self.solved = solved = ~stuck      # Δr solved from its rows
        # a point at the kink (KINK): M = ŷŷᵀ, singular across the slip; that row ties
        # the jump across ŷ (its multiplier is Δr there), M's pseudo-inverse the rest
        M = np.eye(k) - DQ[solved]
        self.across = across = np.zeros(m, bool)
        if k == 2:
            size = np.abs(M).max(axis=(1, 2))
            across[solved] = (np.abs(np.linalg.det(M)) < 1e-12 * size) & (size > 0)
        self.Minv = np.linalg.pinv(M) if across.any() else np.linalg.inv(M)
        self.cross = np.zeros((m, k))     # ŷ⊥ in the frame at the points across
        if across.any():
            yh = res.y[across] / np.linalg.norm(res.y[across], axis=1)[:, None]
            self.cross[across] = np.c_[-yh[:, 1], yh[:, 0]]
        self.DQ, self.qR = DQ, qR
        dR_dlam = np.where(solved, res.dR_dlam, 0.0)
        # e (m, k): how Δr follows Δλ at the dofs solved for Δr
        self.e = np.zeros((m, k))
        self.e[solved] = np.einsum("sab,sb->sa", self.Minv, qR[solved] * dR_dlam[solved, None])
        self.Bt = Bt = list(ops.Bt)
        iw = 1.0 / ops.w
        self.K, self.S = step.K, None
        soft = solved & DQ.any(axis=(1, 2))
        if soft.any():  # the sliding force's ΔU part: a symmetric interface stiffness
            Minv = self.Minv[soft[solved]]  # soft ⊂ solved: M⁻¹ is already there
            W = (laws.rho_t[soft] * iw[soft])[:, None, None] * (Minv @ DQ[soft])
            W = sp.bmat([[sp.diags(W[:, a, b]) for b in range(k)] for a in range(k)])
            Bs = sp.vstack([B[soft] for B in Bt], format="csr")
            self.S = (Bs.T @ W @ Bs).tocsr()  # kept apart: K is not copied
        across_rows = [sum(sp.diags(self.cross[across, a]) @ Bt[a][across]
                           for a in range(k))] if across.any() else []
        self.B = sp.vstack([ops.Bn[closed]] + [Bt[a][self.tied[:, a]] for a in range(k)]
                           + across_rows, format="csr")
        tilt = closed & (self.e != 0).any(axis=1)
        if tilt.any():  # the pressure of a sliding closed dof pulls its friction along
            Cn = ops.Bn + sum(sp.diags(self.e[:, a]) @ Bt[a] for a in range(k))
            self.C = sp.vstack([Cn[closed]] + [Bt[a][self.tied[:, a]] for a in range(k)]
                               + across_rows, format="csr")
        else:
            self.C = None
        self.fixed = np.setdiff1d(np.arange(step.K.shape[0]), step.free)

    def __call__(self, R, tol: float) -> np.ndarray:
        step, k = self.step, self.k
        laws, ops = step.laws, step.ops
        closed, solved = self.closed, self.solved
        Bt = self.Bt
        R_u, R_n, Rt = R
        iw = 1.0 / ops.w
        d_lam = np.where(closed, 0.0, -R_n)
        d_r = np.where(self.tied, 0.0, -Rt)
        # solved: Δλ is known at an open dof
        d_r[solved] = np.einsum("sab,sb->sa", self.Minv, -Rt[solved]) \
            + self.e[solved] * d_lam[solved, None]
        f = np.zeros(self.K.shape[0])
        f[step.free] = -R_u
        f += ops.Bn.T @ d_lam + sum(Bt[a].T @ d_r[:, a] for a in range(k))
        across = self.across
        rhs = np.concatenate([-(ops.w / laws.rho_n * R_n)[closed]]
                             + [-(ops.w / laws.rho_t * Rt[:, a])[self.tied[:, a]]
                                for a in range(k)]
                             + [-(ops.w / laws.rho_t)[across]
                                * np.einsum("sa,sa->s", Rt[across], self.cross[across])])
        try:
            dU, mu, info = tie_solve(self.K, self.B, f, self.fixed, np.zeros(self.fixed.size),
                                     c=rhs, modes=self.modes, blocksize=self.blocksize,
                                     tol=tol, reuse=self.setup, C=self.C, update=True,
                                     independent=True, S=self.S)
        except SingularSystemError as e:  # a part free in this active set
            raise SingularStepError(str(e)) from e
        self.setup, self.iterations = info.setup, info.iterations
        if info.removed:  # as the direct path: a pressure at every dof must be unique
            raise SingularStepError(
                f"{info.removed} contact multipliers depend on the others (the naive space "
                f"on tetrahedra): use space='vital'")
        nc = int(closed.sum())
        d_lam[closed] = mu[:nc]
        ends = nc + np.cumsum(self.tied.sum(axis=0))
        for a in range(k):
            d_r[self.tied[:, a], a] = mu[ends[a] - self.tied[:, a].sum():ends[a]]
        if across.any():
            d_r[across] += self.cross[across] * mu[ends[-1]:][:, None]
        if solved.any():
            jump = np.stack([B[solved] @ dU for B in Bt], axis=1) * (
                laws.rho_t[solved] * iw[solved])[:, None]
            d_r[solved] -= np.einsum("sab,sbc,sc->sa", self.Minv, self.DQ[solved], jump)
            d_r[solved] += self.e[solved] * np.where(closed, d_lam, 0.0)[solved, None]
        return np.concatenate([dU[step.free], d_lam, d_r.T.ravel()])
