r"""One load step of unilateral contact with friction by a semi-smooth Newton method.

Unknowns: the free displacement unknowns U, the contact pressure λ (one value
per multiplier dof, λ ≤ 0 in contact) and a tangential unknown T (m, k):
the semi-multiplier Λ of eq. 9 for ``coulomb`` (r_τ = μλΛ), the tangential
traction r_τ itself for ``adhesive`` (no slip: the limit μ → ∞), none for
``frictionless``.  The equations, all solved at once (paper §3):

* equilibrium  K U - Bnᵀλ - Σ_a Bt_aᵀ r_τa - F = 0 on the free unknowns;
* contact      λ - χ(g_n) g_n = 0, g_n = λ - ρ_n d  at every dof;
* friction     Λ - χ(g_n) P_B(g_τ) = 0, g_τ = Λ + ρ_τ s  (``coulomb``), or
  r_τ - χ(g_n)(r_τ + ρ_τ s) = 0 (``adhesive``),

with d, s the weighted normal jump and tangential jump increment of
:mod:`skxfem.contact_interface` (s = v_τ Δt: the increment over the step).
The open points (χ = 0) get λ = 0 and Λ = 0: the term (1 - χ)Λ of the
paper's third equation.

Newton matrix: the exact generalised Jacobian (:mod:`skxfem.contact_laws`;
χ is taken as 1 at g_n = 0 in every block, so the first iteration from an
untouched interface is the bilateral, or bonded, solve), with one
exception: at a point just closed with λ = 0
(:func:`skxfem.contact_laws.just_closed`) Λ has
no coefficient (r_τ = μλΛ = 0 for every Λ); that iteration takes the
traction r_τ as the unknown there with the stick row ρ_τ s = 0, and sets
Λ = P_B(r_τ/(μλ)) after the step (the first iteration of a first load step
is thus the bonded solve).
Rows and columns are scaled (Jacobi on U, unit max on the others) before
SuperLU, or solved as ties by AMG + projected CG (:mod:`skxfem.contact_linear`);
a matrix unchanged since the last iteration is not factorised (or set up)
again. Step control: backtracking on
the scaled residual norm (halving up to 5 times; if no step decreases it the
full step is taken, as the active set has to change). Convergence: the
status of every point (open, stick, slip) unchanged by the last step and
every relative residual ≤ ``tol`` (equilibrium relative to max(|F|, |KU|);
contact relative to max(|λ|, ρ_n|d|); friction: |Λ| ≤ 1 is already
unit-free, the adhesive traction relative to max(|r_τ|, ρ_τ|s|)).

>>> law = Law("coulomb", mu=0.5, rho_n=1.0, rho_t=1.0)
>>> law.friction, law.threshold is None
(True, True)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from . import contact_linear
from .contact_laws import (
    ball_projection,
    friction_coefficient,
    held,
    just_closed,
    normal_update,
    status,
)

__all__ = ["Law", "NewtonInfo", "ContactConvergenceError", "residual", "newton"]


class ContactConvergenceError(RuntimeError):
    """The contact iteration did not converge; the message says how far it got.

    ``last`` holds the last iterate (U, λ, T, g_n, g_t, info) and ``statuses``
    the status of every point at every iteration, to show what went wrong.
    """


@dataclass(frozen=True)
class Law:
    """A unilateral law with its parameters (μ only for ``coulomb``).

    ``threshold`` (m,), if given, freezes the friction threshold: r_τ =
    threshold · Λ instead of μλΛ (the paper's fixed point,
    :mod:`skxfem.contact_fixed_point`); where it is 0, Λ is held.
    """

    name: str
    mu: float
    rho_n: float
    rho_t: float
    threshold: np.ndarray | None = None

    @property
    def friction(self) -> bool:
        return self.name in ("coulomb", "adhesive")


@dataclass(frozen=True)
class NewtonInfo:
    """``iterations`` (linear solves) and ``residuals`` (iterations + 1, 3): the
    relative residuals of equilibrium, contact and friction, first the start."""

    iterations: int
    residuals: np.ndarray


def _jumps(ops, U, U_prev):
    d = ops.Bn @ U / ops.w
    s = np.stack([Bt @ (U - U_prev) for Bt in ops.Bt], axis=1) / ops.w[:, None]
    return d, s


def _tangential(law, lam, T):
    """The tangential traction r_τ (m, k)."""
    if law.name == "coulomb":
        return friction_coefficient(law, lam)[:, None] * T
    return T if law.name == "adhesive" else np.zeros_like(T)


def residual(ops, law, K, F, free, U, lam, T, U_prev):
    """Residuals (R_u, R_n, R_t), the augmented g_n, g_τ and their relative sizes."""
    d, s = _jumps(ops, U, U_prev)
    g_n = lam - law.rho_n * d
    value, _ = normal_update(g_n)
    R_n = lam - value
    g_t = T + law.rho_t * s[:, :T.shape[1]]
    chi = (g_n < 0)[:, None]
    if law.name == "coulomb":
        R_t = np.where(held(law, g_n)[:, None], 0.0, T - chi * ball_projection(g_t)[0])
    elif law.name == "adhesive":
        R_t = T - chi * g_t
    else:
        R_t = np.zeros((lam.size, 0))
    tau = _tangential(law, lam, T)
    KU = K @ U
    R_u = (KU - ops.Bn.T @ lam - sum(ops.Bt[a].T @ tau[:, a] for a in range(tau.shape[1])) - F)
    R_u = R_u[free]
    tiny = 1e-300
    r_u = _max(R_u) / max(_max(F[free]), _max(KU[free]), tiny)
    r_n = _max(R_n) / max(_max(lam), law.rho_n * _max(d), tiny)
    r_t = _max(R_t) if law.name != "adhesive" else _max(R_t) / max(
        _max(T), law.rho_t * _max(s), tiny)
    return (R_u, R_n, R_t.T.ravel()), g_n, g_t, np.array([r_u, r_n, r_t])


def _max(a):
    return float(np.abs(a).max()) if np.size(a) else 0.0


def jacobian(ops, law, K, free, lam, T, g_n, g_t) -> sp.csr_matrix:
    """The generalised Jacobian of (R_u, R_n, R_t) with respect to (U_free, λ, T).

    At :func:`just_closed` points (``coulomb``) the column of T is that of the
    traction r_τ and the row is the stick condition ρ_τ s = 0; see the module notes.
    """
    m, k = T.shape
    chi = normal_update(g_n)[1]  # χ, and 1 at g_n = 0 (the contact branch)
    Bn = ops.Bn[:, free]
    Bt = [B[:, free] for B in ops.Bt]
    iw = 1.0 / ops.w
    A_ul = -Bn.T
    rows_u = [K[free][:, free], A_ul]
    rows_n = [sp.diags(chi * law.rho_n * iw) @ Bn, sp.diags(1.0 - chi)]
    if k == 0:
        return sp.bmat([rows_u, rows_n], format="csr")
    if law.name == "coulomb":
        new = just_closed(law, lam, g_n)
        mu = law.mu if law.threshold is None else 0.0  # a frozen threshold: no dλ
        rows_u[1] = A_ul - sum(mu * Bt[a].T @ sp.diags(np.where(new, 0.0, T[:, a]))
                               for a in range(k))
        coef = np.where(new, 1.0, friction_coefficient(law, lam))
        rows_u.append(sp.hstack([-Bt[a].T @ sp.diags(coef) for a in range(k)]))
        DP = ball_projection(g_t)[1]
        DP[new] = np.eye(k)  # the stick row
        chi = np.where(held(law, g_n), 0.0, chi)  # held: the row ΔΛ = 0
        t_u = [-sum(sp.diags(chi * law.rho_t * iw * DP[:, a, b]) @ Bt[b] for b in range(k))
               for a in range(k)]
        t_t = [[sp.diags(np.where(new, 0.0, (a == b) - chi * DP[:, a, b])) for b in range(k)]
               for a in range(k)]
    else:
        rows_u.append(sp.hstack([-Bt[a].T for a in range(k)]))
        t_u = [-sp.diags(chi * law.rho_t * iw) @ Bt[a] for a in range(k)]
        t_t = [[sp.diags(1.0 - chi) if a == b else None for b in range(k)] for a in range(k)]
    rows_n.append(sp.csr_matrix((m, m * k)))
    rows_t = [sp.vstack(t_u), sp.csr_matrix((m * k, m)), sp.bmat(t_t)]
    return sp.bmat([rows_u, rows_n, rows_t], format="csr")


def newton(ops, law, K, F, free, U, lam, T, U_prev, tol=1e-10, max_iter=30,
           linear="direct", modes=None, blocksize=1):
    """Solve one load step from the start (U, λ, T); U must hold the imposed values.

    ``linear``: each Newton step solved by ``"direct"`` SuperLU or
    ``"iterative"`` ties, AMG + projected CG (``modes``, ``blocksize`` as
    :func:`skxfem.iterative.solve`), see :mod:`skxfem.contact_linear`.

    Returns
    -------
    U, lam, T, g_n, g_t, NewtonInfo

    Raises
    ------
    ContactConvergenceError
        After ``max_iter`` iterations without convergence: the message gives
        the iterations, the residual of each equation and the points whose
        status kept changing.
    """
    U, lam, T = U.copy(), lam.copy(), T.copy()
    m, k = T.shape
    if law.name == "coulomb" and law.mu == 0:
        raise ValueError("coulomb with mu = 0 is frictionless: use law='frictionless'")
    nu = len(free)
    R, g_n, g_t, r = residual(ops, law, K, F, free, U, lam, T, U_prev)
    history = [r]
    st = status(g_n, g_t, law.name)
    statuses = [st]
    changes, factor = np.zeros(m, int), None  # the last LU or tie set-up, reused if unchanged
    for it in range(1, max_iter + 1):
        A = jacobian(ops, law, K, free, lam, T, g_n, g_t)
        new = just_closed(law, lam, g_n)
        if new.any():  # their rows are the stick condition -ρ_τ s = 0
            s = _jumps(ops, U, U_prev)[1]
            R = (R[0], R[1], np.where(np.tile(new, k), -law.rho_t * s.T.ravel(), R[2]))
        Rv = np.concatenate(R)
        if linear == "iterative":  # rs: the direct path's row scales, for the line search
            dx, factor = contact_linear.iterative(ops, law, K, free, R, lam, T, g_n, g_t, A,
                                                  modes, blocksize, reuse=factor)
            rs = contact_linear.scales(A, nu)[0]
        else:
            dx, rs, factor = contact_linear.direct(A, Rv, nu, reuse=factor)
        phi0 = np.linalg.norm(rs * Rv)
        for alpha in (1.0, 0.5, 0.25, 0.125, 0.0625, 0.03125, 1.0):
            U1, lam1, T1 = U.copy(), lam + alpha * dx[nu:nu + m], T + alpha * (
                dx[nu + m:].reshape(k, m).T)
            U1[free] += alpha * dx[:nu]
            if new.any():  # the unknown was r_τ there: Λ = P_B(r_τ / (μλ))
                Tn = np.zeros((m, k))
                ok = new & (lam1 < 0)
                Tn[ok] = ball_projection(T1[ok] / (law.mu * lam1[ok, None]))[0]
                T1[new] = Tn[new]
            out = residual(ops, law, K, F, free, U1, lam1, T1, U_prev)
            if np.linalg.norm(rs * np.concatenate(out[0])) <= (1 - 1e-4 * alpha) * phi0:
                break
        U, lam, T = U1, lam1, T1
        R, g_n, g_t, r = out
        history.append(r)
        new = status(g_n, g_t, law.name)
        changes += new != st
        same, st = np.array_equal(new, st), new
        statuses.append(st)
        if same and np.all(r <= tol):
            return U, lam, T, g_n, g_t, NewtonInfo(it, np.array(history))
    moving = np.flatnonzero(changes > 1)
    err = ContactConvergenceError(
        f"contact Newton did not converge in {max_iter} iterations: relative residuals "
        f"equilibrium {r[0]:.1e}, contact {r[1]:.1e}, friction {r[2]:.1e} (tolerance "
        f"{tol:.0e}); {moving.size} point(s) changed status more than once"
        f"{': dofs ' + str(moving[:10].tolist()) if moving.size else ''}. Try more load "
        f"steps, another rho_n/rho_t, or max_iter")
    err.last = (U, lam, T, g_n, g_t, NewtonInfo(max_iter, np.array(history)))
    err.statuses = np.array(statuses)
    raise err
