r"""One load step of unilateral contact with friction by a globalised semi-smooth Newton method.

Unknowns: the free displacement unknowns U, the contact pressure λ (one value
per multiplier dof, λ ≤ 0 in contact) and the tangential traction r_τ (m, k),
k = dim - 1 (Coulomb's r_τ = μλΛ, eq. 9a: the solver keeps the traction,
which stays bounded where the pressure vanishes, and reports Λ).  The
equations, all solved at once (paper §3), at every multiplier dof j:

* equilibrium  K U - Bnᵀλ - Σ_a Bt_aᵀ r_τa - F = 0 on the free unknowns;
* contact      λ - χ(g_n) g_n = 0,  g_n = λ - ρ_n d  (a tied normal: ρ_n d = 0);
* friction     r_τ - P_{B(0,R)}(r_τ - ρ_τ s) = 0,  R = μ max(0, -g_n)  (Coulomb);
  r_τ - χ(g_n)(r_τ - ρ_τ s) = 0 (no slip where closed); r_τ = 0 (free sliding),

with d, s the weighted normal jump and tangential jump increment of
:mod:`skxfem.contact.interface` (s = v_τ Δt: the increment over the step) and
the laws of :mod:`skxfem.contact.laws`.  Tangential components that a support
holds (:attr:`~skxfem.contact.interface.Operators.tangent_held`) carry r_τa = 0: the
support takes that force.

**The iteration** (:func:`newton`), one pass of five named steps:

1. :func:`residual` of every equation at the iterate;
2. :func:`jacobian`, the exact generalised Jacobian (χ taken as 1 at g_n = 0,
   so that the first iteration from an untouched interface is the bonded
   solve);
3. the linear step J Δx = -R (:mod:`skxfem.contact.step`: SuperLU on J, a
   matrix unchanged since the last iteration not factorised again; or one
   tie, solved only as accurately as the iterate needs, :func:`forcing`; at a
   singular one, an active set that leaves a part of the body free, a part
   that only Γ holds, its every Coulomb point sliding, is first slid as a
   rigid body to where friction holds it, a point sticking
   (:mod:`skxfem.contact.slide`: the slip branch does not see how far it
   slides); if the matrix stays singular, it is
   replaced by the Jacobian that keeps the points closed at the last iterate,
   then every point closed, then (Coulomb) every point closed and sticking (a
   part that only Γ holds, its every point sliding, is free along Γ in the
   slip branch's Jacobian); if that is singular too, the law or the space is
   at fault and the :class:`~skxfem.contact.step.SingularStepError`, a
   ValueError, is raised);
4. :func:`line_search`: the largest α ∈ {1, ½, …, 2⁻⁸} that decreases the
   merit ‖D R‖ by the Armijo factor (1 - 10⁻⁴α), D the row scales of the
   step's first Newton matrix, kept for the whole step (a merit that changed
   with the iterate would let a cycle of active sets decrease it); if none
   does, the α of the smallest merit, and the full step if no α decreases it
   (the active set has to change) — unless that step returns to an active set
   already left: then a step down the merit's gradient (:func:`descent`), off
   the kink the cycle turns around;
5. :func:`relative_residuals`, the convergence test: the residual of every
   equation in force units (the interface rows times the lumped weight w)
   divided by a force that cannot vanish, max(|F|, |K U|, max diag K · |U|),
   at least :data:`FLOOR` of that of the step's start (a step to zero load),
   each ≤ ``tol``.  The interface equations are measured with the *reference*
   ρ = E/h, not the step's ρ: their zeros are the same for every ρ > 0, so the
   test does not depend on the augmentation, and it does not look at the
   statuses, which may flip at a point exactly on the slip limit.

The start of a load step is the converged state of the last, or the secant
prediction from the last two (:func:`predict`) where the loads are proportional
and it lowers the residuals.

>>> law = Law("coulomb", mu=0.5, rho_n=1.0, rho_t=1.0)
>>> law.friction, law.threshold is None
(True, True)
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from ..linalg.iterative import ConvergenceError
from . import step as linear_step
from .laws import LAWS, disk_projection, status
from .slide import slide, slips

__all__ = ["Law", "PointLaws", "point_laws", "join_laws", "StepProblem", "Iterate", "Residual",
           "NewtonInfo", "ContactConvergenceError", "jumps", "residual", "jacobian",
           "line_search", "relative_residuals", "newton", "predict", "LINE_SEARCH", "TOL",
           "FLOOR"]

TOL = 1e-12
"""The default tolerance of :func:`relative_residuals`.  Measured on the known
answers of ``tests/test_contact_newton.py``: at 1e-10, Newton may stop one
iteration early with tractions 1e-8 to 6e-8 off (3D slip, μ = 5); at 1e-12 every
case is exact to 1e-12, at the cost of that one iteration."""

FLOOR = 1e-2
"""The least force scale of a load step's convergence test, as a fraction of the
scale of the state it starts from (:func:`force_scale`): a step is converged when
its residuals are ``tol`` of its own forces or ``tol`` × 1e-2 (1e-14) of those it
started from.  Its slip increments are differences from that state, so their
round-off is of that state's size.  Without the floor a step to zero load (a crack
unloaded, its faces reopening) had a scale that vanished with the answer (U → 0):
Newton reached |U| = 1e-206 and never passed the test ("did not converge", every
cut of the step too).  A step whose forces stay above 1/100 of its start's
is tested as before."""

LINE_SEARCH = tuple(0.5 ** np.arange(9))
"""The step lengths tried by :func:`line_search`, longest first."""


class ContactConvergenceError(RuntimeError):
    """The contact iteration did not converge; the message says how far it got.

    ``last`` holds the last (:class:`Iterate`, :class:`Residual`, :class:`NewtonInfo`)
    and ``statuses`` the status of every point at every iteration, to show what
    went wrong.
    """


@dataclass(frozen=True)
class Law:
    """A law of :data:`skxfem.scene.laws.LAWS` with its parameters (μ: ``coulomb``).

    ``rho_n``, ``rho_t``: the augmentations, tractions per length.
    ``threshold`` (m,), if given, freezes the friction threshold: the radius
    of the Coulomb ball is ``threshold`` at a closed point instead of μp (the
    paper's fixed point, :mod:`skxfem.contact.fixed_point`).
    """

    name: str
    mu: float
    rho_n: float
    rho_t: float
    threshold: np.ndarray | None = None

    @property
    def friction(self) -> bool:
        return LAWS[self.name].tangential != "free"


@dataclass(frozen=True)
class PointLaws:
    """The law at each of the m multiplier dofs, as arrays.

    ``name`` (m,) law names, ``unilateral`` (m,) Signorini or a tied normal,
    ``tangential`` (m,) ``"free"``, ``"stick"`` or ``"coulomb"``; ``mu``,
    ``rho_n``, ``rho_t`` (m,); ``threshold`` (m,) the frozen radius of the
    fixed point or None; ``tangent_held`` (m, k) the tangential components a support
    holds (their r_τ is 0).
    """

    name: np.ndarray
    unilateral: np.ndarray
    tangential: np.ndarray
    mu: np.ndarray
    rho_n: np.ndarray
    rho_t: np.ndarray
    tangent_held: np.ndarray
    threshold: np.ndarray | None = None

    @property
    def k(self) -> int:
        return self.tangent_held.shape[1]


def point_laws(law: Law, tangent_held: np.ndarray) -> PointLaws:
    """One :class:`Law` at every dof; ``tangent_held`` (m, k) as :attr:`PointLaws.tangent_held`.

    >>> pl = point_laws(Law("adhesive", 0.0, 2.0, 3.0), np.zeros((4, 1), bool))
    >>> bool(pl.unilateral.all()), pl.tangential[0], float(pl.rho_t[0])
    (True, 'stick', 3.0)
    """
    m = tangent_held.shape[0]
    kind = LAWS[law.name]
    full = lambda v: np.full(m, float(v))  # noqa: E731
    return PointLaws(np.full(m, law.name, dtype=object), np.full(m, kind.unilateral),
                     np.full(m, kind.tangential, dtype=object), full(law.mu),
                     full(law.rho_n), full(law.rho_t), np.asarray(tangent_held, bool),
                     law.threshold)


def join_laws(parts) -> PointLaws:
    """The :class:`PointLaws` of several interfaces' dofs, stacked in order (each
    from :func:`point_laws`; no frozen threshold).

    >>> a = point_laws(Law("frictionless", 0.0, 1.0, 1.0), np.zeros((2, 1), bool))
    >>> b = point_laws(Law("coulomb", 0.5, 1.0, 1.0), np.zeros((3, 1), bool))
    >>> j = join_laws([a, b])
    >>> j.name.tolist(), j.mu.tolist()
    (['frictionless', 'frictionless', 'coulomb', 'coulomb', 'coulomb'], [0.0, 0.0, 0.5, 0.5, 0.5])
    """
    if any(p.threshold is not None for p in parts):
        raise ValueError("join_laws stacks laws without a frozen threshold")
    return PointLaws(*(np.concatenate([getattr(p, f) for p in parts]) for f in
                       ("name", "unilateral", "tangential", "mu", "rho_n", "rho_t")),
                     np.vstack([p.tangent_held for p in parts]))


@dataclass(frozen=True)
class StepProblem:
    """What one load step solves: the interface ``ops``, the stiffness ``K``
    and load ``F`` on all unknowns, the ``free`` unknowns, ``U_prev`` (the
    converged state the slip increments start from), the ``laws`` and
    ``rho_ref`` (the reference ρ of the convergence test, E/h; several
    interfaces: (m,), each dof its interface's); ``slides`` the translations (N, dim)
    of each part that only Γ holds (:func:`skxfem.contact.slide.translations`), which
    a singular step slides to where friction holds them (:func:`newton`)."""

    ops: object
    K: sp.csr_matrix
    F: np.ndarray
    free: np.ndarray
    U_prev: np.ndarray
    laws: PointLaws
    rho_ref: float | np.ndarray
    slides: tuple = ()

    @property
    def nu(self) -> int:
        return len(self.free)


@dataclass(frozen=True)
class Iterate:
    """U (N,) with the imposed values, λ (m,), r_τ (m, k)."""

    U: np.ndarray
    lam: np.ndarray
    r: np.ndarray

    def moved(self, free, dx, alpha: float) -> Iterate:
        """The iterate x + α Δx, Δx = (ΔU_free, Δλ, Δr_τ component-major)."""
        nu, (m, k) = len(free), self.r.shape
        U = self.U.copy()
        U[free] += alpha * dx[:nu]
        return Iterate(U, self.lam + alpha * dx[nu:nu + m],
                       self.r + alpha * dx[nu + m:].reshape(k, m).T)


@dataclass(frozen=True)
class Residual:
    """The residuals at an iterate: R_u (free unknowns), R_n (m,), R_t (m, k)
    (tractions), and what the laws saw: g_n (m,), y = r_τ - ρ_τ s on the
    components not held (m, k), the Coulomb radius R (m,), the status (m,) and
    dR/dλ (m,)."""

    R_u: np.ndarray
    R_n: np.ndarray
    R_t: np.ndarray
    g_n: np.ndarray
    y: np.ndarray
    radius: np.ndarray
    status: np.ndarray
    dR_dlam: np.ndarray = None

    @property
    def vector(self) -> np.ndarray:
        """(R_u, R_n, R_t component-major), the order of the unknowns."""
        return np.concatenate([self.R_u, self.R_n, self.R_t.T.ravel()])


@dataclass(frozen=True)
class NewtonInfo:
    """``iterations`` (linear solves), ``residuals`` (iterations + 1, 3): the
    relative residuals of equilibrium, contact and friction, first the start;
    ``steps`` the line-search step length α of each iteration; ``rescued``: the
    Newton iterations of a first attempt that failed before the fixed point
    took over (:func:`skxfem.contact.solve`), 0 if none; ``inner`` the Krylov
    iterations of each iterative linear solve (empty for direct ones)."""

    iterations: int
    residuals: np.ndarray
    steps: tuple = ()
    rescued: int = 0
    inner: tuple = ()


def jumps(ops, U, U_prev):
    """d (m,) and s (m, k): the weighted normal jump and tangential jump increment."""
    d = ops.Bn @ U / ops.w
    return d, slips(ops, U, U_prev).reshape(d.size, len(ops.Bt))


def _radius(laws: PointLaws, lam, g_n):
    """The radius R of the friction ball and dR/dλ: μ max(0, -λ) (Coulomb; slope -μ
    where λ < 0), or the frozen threshold where g_n < 0 (slope 0)."""
    if laws.threshold is not None:
        return np.where(g_n < 0, laws.threshold, 0.0), np.zeros(g_n.size)
    return laws.mu * np.maximum(0.0, -lam), np.where(lam < 0, -laws.mu, 0.0)


def residual(step: StepProblem, it: Iterate, rho_n=None, rho_t=None) -> Residual:
    """Step 1: the residual of every equation at ``it``; ρ defaults to the laws'."""
    laws, ops = step.laws, step.ops
    rho_n = laws.rho_n if rho_n is None else rho_n
    rho_t = laws.rho_t if rho_t is None else rho_t
    d, s = jumps(ops, it.U, step.U_prev)
    g_n = it.lam - rho_n * d
    chi = np.where(laws.unilateral, g_n < 0, True)
    R_n = it.lam - chi * g_n
    y = np.where(laws.tangent_held, 0.0, it.r - rho_t[:, None] * s)
    radius, dR_dlam = _radius(laws, it.lam, g_n)
    Q = np.zeros_like(y)
    stick, coulomb = laws.tangential == "stick", laws.tangential == "coulomb"
    Q[stick] = chi[stick, None] * y[stick]
    if coulomb.any():
        Q[coulomb] = disk_projection(y[coulomb], radius[coulomb])[0]
    R_t = it.r - Q
    tau = it.r
    R_u = (step.K @ it.U - ops.Bn.T @ it.lam
           - sum(ops.Bt[a].T @ tau[:, a] for a in range(laws.k)) - step.F)[step.free]
    point_status = status(g_n, y, radius, laws.name)
    return Residual(R_u, R_n, R_t, g_n, y, radius, point_status, dR_dlam)


def jacobian(step: StepProblem, it: Iterate, res: Residual, close=None,
             K=None) -> sp.csr_matrix:
    """Step 2: the generalised Jacobian of (R_u, R_n, R_t) in (U_free, λ, r_τ).

    ``close`` (m,) bool: points whose unilateral normal takes the contact
    branch whatever g_n (the fallback of a singular step, see the module notes).
    ``K``: the block of the free unknowns, if not K's own (:func:`_linear_step`
    puts K's diagonal there for the scales of a step it does not form).
    """
    laws, ops, free = step.laws, step.ops, step.free
    m, k = res.y.shape
    iw = 1.0 / ops.w
    chi, DQ, qR = linear_step.linearised(laws, res, close)
    Bn = ops.Bn[:, free]
    Bt = [B[:, free] for B in ops.Bt]
    K = step.K[free][:, free] if K is None else K
    rows_u = [K, -Bn.T] + [-Bt[a].T for a in range(k)]
    rows_n = [sp.diags(chi * laws.rho_n * iw) @ Bn, sp.diags(1.0 - chi)] + [None] * k
    # dR_t/dU = DQ ρ_t Bt/w;  dR_t/dλ = -qR dR/dλ
    rows_t = []
    for a in range(k):
        du = sum(sp.diags(DQ[:, a, b] * laws.rho_t * iw) @ Bt[b] for b in range(k))
        rows_t.append([du, sp.diags(-qR[:, a] * res.dR_dlam)]
                      + [sp.diags((a == b) - DQ[:, a, b]) for b in range(k)])
    return sp.bmat([rows_u, rows_n] + rows_t, format="csr")


def line_search(step: StepProblem, it: Iterate, dx, merit0: float, rows,
                alphas=LINE_SEARCH):
    """Step 4: the iterate along ``dx`` whose merit ‖rows·R‖ decreases (module notes).

    Returns the new iterate, its residual, the step length α and whether the
    merit decreased (if not: the full step, its residual and α = 1).
    """
    best = None
    for alpha in alphas:
        trial = it.moved(step.free, dx, alpha)
        res = residual(step, trial)
        merit = np.linalg.norm(rows * res.vector)
        if merit <= (1 - 1e-4 * alpha) * merit0:
            return trial, res, alpha, True
        if best is None or merit < best[0]:
            best = (merit, trial, res, alpha)
    if best[0] < merit0:
        return best[1], best[2], best[3], True
    trial = it.moved(step.free, dx, 1.0)
    return trial, residual(step, trial), 1.0, False


def descent(A, R, rows, cols, dx) -> np.ndarray:
    """The steepest descent of the merit ½‖rows·R‖² in the scaled unknowns,
    -cols²·Aᵀ(rows²·R), as long as the Newton step ``dx`` (scaled): the way off a
    kink where the Newton step decreases no merit (module notes)."""
    g = -cols ** 2 * (A.T @ (rows ** 2 * R))
    norm = np.linalg.norm(g / cols)
    return g * (np.linalg.norm(dx / cols) / norm if norm > 0 else 0.0)


def force_scale(step: StepProblem, U) -> float:
    """A force that cannot vanish unless the whole state does: max(|F|, |K U|,
    max diag K · |U|) (an interface opened by imposed displacements has F = 0
    and K U = 0 on the free unknowns, but not U), and at least :data:`FLOOR` times
    that of the state the step starts from, ``U_prev``."""
    diag = np.abs(step.K.diagonal()).max() if step.K.shape[0] else 0.0
    start = max(_max(step.K @ step.U_prev), diag * _max(step.U_prev))
    return max(_max(step.F), _max(step.K @ U), diag * _max(U), FLOOR * start, 1e-300)


def relative_residuals(step: StepProblem, it: Iterate) -> np.ndarray:
    """Step 5: (equilibrium, contact, friction) residuals relative to
    :func:`force_scale`, the interface equations at the reference ρ (module notes)."""
    ref = np.full(it.lam.size, step.rho_ref)
    res = residual(step, it, ref, ref)
    w = step.ops.w
    scale = force_scale(step, it.U)
    forces = [_max(res.R_u), _max(w * res.R_n), _max(w[:, None] * res.R_t)]
    return np.array(forces) / scale


def _max(a) -> float:
    return float(np.abs(a).max()) if np.size(a) else 0.0


def newton(step: StepProblem, start: Iterate, tol: float = TOL, max_iter: int = 30,
           linear: str = "direct", modes=None, blocksize: int = 1,
           linear_tol: float = 1e-12, guess: Iterate | None = None, setup=None,
           monitor=None):
    """Solve one load step from ``start`` (its U holds the imposed values).

    ``setup``: iterative steps, the :func:`skxfem.linalg.iterative.stiffness_setup` of
    K that every step's tie is carried over from (default: each builds its own).
    ``monitor(n, residuals, status, inner)``: called after each iteration n with
    its relative residuals (3,), the status of every point and the Krylov
    iterations of its linear solve (0: direct), for progress output.
    ``guess``: a predicted state of the step (:func:`predict`), taken as the start
    instead where its relative residuals are smaller (an extrapolation that
    went wrong costs one residual, never an iteration).

    ``linear``: each Newton step solved by ``"direct"`` SuperLU or
    ``"iterative"`` ties, AMG + projected CG (``modes``, ``blocksize`` as
    :func:`skxfem.linalg.iterative.solve`, to the relative residual ``linear_tol``),
    see :mod:`skxfem.contact.step`.

    Returns
    -------
    Iterate, Residual, NewtonInfo

    Raises
    ------
    ContactConvergenceError
        After ``max_iter`` iterations without convergence: the message gives
        the iterations, the residual of each equation and the points whose
        status kept changing.
    skxfem.contact.step.SingularStepError
        (a ValueError) A Newton matrix singular even with every point closed.
    """
    it, res, first = _start(step, start, guess)
    history = [first]
    statuses, alphas = [res.status], []
    closed_before = res.status != 0
    factor = setup  # the last LU or tie set-up, reused while the matrix is unchanged
    merit_rows = None
    inner = []
    for n in range(1, max_iter + 2):
        info = NewtonInfo(n - 1, np.array(history), tuple(alphas), inner=tuple(inner))
        if np.all(history[-1] <= tol):
            return it, res, info
        if n > max_iter:
            raise _not_converged(f"did not converge in {max_iter} iterations", history,
                                 statuses, tol, (it, res, info))
        eta = forcing(history[-1], linear_tol)
        try:
            dx, scaled, factor, krylov = _linear_step(
                step, it, res, None, linear, modes, blocksize, factor, eta)
        except linear_step.SingularStepError as e:
            slid = slide(step, it, res, step.F) if step.slides else None
            if slid is not None:  # every point of a part only Γ holds slides: move it
                it = Iterate(slid[0], it.lam, slid[1])
                res = residual(step, it)
            try:
                if slid is None:
                    raise e
                dx, scaled, factor, krylov = _linear_step(
                    step, it, res, None, linear, modes, blocksize, factor, eta)
            except linear_step.SingularStepError as e2:
                dx, scaled, factor, krylov = _singular_fallback(
                    step, it, res, closed_before, linear, modes, blocksize, e2, eta,
                    setup)
        if linear == "iterative":
            inner.append(krylov)
        if merit_rows is None:  # one merit for the whole step: no cycle can decrease it
            merit_rows = scaled()[0]
        merit0 = np.linalg.norm(merit_rows * res.vector)
        closed_before = res.status != 0
        new = line_search(step, it, dx, merit0, merit_rows)
        if not new[3] and any(np.array_equal(new[1].status, seen) for seen in statuses):
            # no step along Newton's decreases the merit, and the full step returns to
            # an active set already left: a cycle; descend the merit instead
            _, cols, A = scaled(full=True)
            down = line_search(step, it, descent(A, res.vector, merit_rows, cols, dx),
                               merit0, merit_rows, 0.5 ** np.arange(20))
            new = down if down[3] else new
        it, res, alpha = new[:3]
        alphas.append(alpha)
        history.append(relative_residuals(step, it))
        statuses.append(res.status)
        if monitor is not None:
            monitor(n, history[-1], res.status, krylov)


ETA = (1e-2, 1.0)
"""The forcing of the inexact Newton steps (iterative linear solves): each is
solved to the relative residual η = min(ETA[0], max(linear_tol, ETA[1]·r)), r the
largest relative residual of the iterate, so that Newton stays quadratic (the
error of a step is η r ≲ r²) while the early steps, far from the answer, cost a
few Krylov iterations instead of the full ``linear_tol``.  The convergence test
looks at the true residuals, so the answer is as exact as with exact steps.
Loosening the last step further (η = tol/(10 r), only as far as the tolerance
needs) saved two Krylov iterations on the slipping block but, at the slip limit's
kink, cost five more Newton iterations and a rescue (the 3D block at its slip
limit, μ = 1): not taken."""


def forcing(residuals, linear_tol: float) -> float:
    """The relative residual η of the next iterative linear solve (:data:`ETA`).

    >>> forcing(np.array([1.0, 0, 0]), 1e-12), forcing(np.array([1e-7, 0, 0]), 1e-12)
    (0.01, 1e-07)
    """
    return float(min(ETA[0], max(linear_tol, ETA[1] * float(np.max(residuals)))))


def _start(step: StepProblem, start: Iterate, guess: Iterate | None):
    """The start of :func:`newton`: ``start``, or ``guess`` where its largest relative
    residual is smaller; the iterate, its residual and its relative residuals."""
    first = relative_residuals(step, start)
    if guess is not None:
        predicted = relative_residuals(step, guess)
        if predicted.max() < first.max():
            start, first = guess, predicted
    return start, residual(step, start), first


def predict(before: Iterate, now: Iterate, ratio: float) -> Iterate:
    """The secant predictor of the next load step: ``now`` + ``ratio`` (``now`` −
    ``before``), the last converged increment scaled by the ratio of the next load
    increment to the last (exact where the loads are proportional and no status
    changes: the laws are then linear in the state).

    >>> a = Iterate(np.zeros(2), np.zeros(1), np.zeros((1, 1)))
    >>> b = Iterate(np.ones(2), -np.ones(1), np.ones((1, 1)))
    >>> predict(a, b, 0.5).U.tolist(), predict(a, b, 0.5).lam.tolist()
    ([1.5, 1.5], [-1.5])
    """
    return Iterate(now.U + ratio * (now.U - before.U), now.lam + ratio * (now.lam - before.lam),
                   now.r + ratio * (now.r - before.r))


def _linear_step(step, it, res, close, linear, modes, blocksize, factor, linear_tol=1e-12):
    """Step 3: Δx = -J⁻¹R, ``scaled``, the factorisation to reuse and the Krylov
    iterations of the solve (0: direct).

    ``scaled(full=False)`` gives the row and column scales of J and J: the
    direct solve has them; an iterative step never forms J, so they are
    computed when asked for, the scales from J with K's diagonal in place of
    K (the same scales, :func:`skxfem.contact.step.scales` reads only K's
    diagonal), J itself only with ``full``."""
    if linear == "iterative":
        kw = dict(close=close, reuse=factor, tol=linear_tol)
        try:
            dx, factor, krylov = linear_step.iterative(step, res, modes, blocksize, **kw)
        except ConvergenceError:  # a point a hair past its slip limit: see KINK
            dx, factor, krylov = linear_step.iterative(step, res, modes, blocksize, **kw,
                                                       kink=linear_step.KINK)

        def scaled(full=False):
            free = step.free
            K = step.K[free][:, free] if full else sp.diags(step.K.diagonal()[free])
            A = jacobian(step, it, res, close, K=K)
            return (*linear_step.scales(A, step.nu), A)
        return dx, scaled, factor, krylov
    A = jacobian(step, it, res, close)
    n = step.nu + res.R_n.size
    if np.all(step.laws.tangential == "free"):  # no friction: r_τ = 0 is known, Δr = -R_t
        dx, rows, factor = linear_step.direct(A[:n, :n], res.vector[:n], step.nu,
                                              reuse=factor)
        ones = np.ones(res.R_t.size)
        rows, cols = np.r_[rows, ones], np.r_[factor[2], ones]
        return np.r_[dx, -res.R_t.T.ravel()], lambda full=False: (rows, cols, A), factor, 0
    dx, rows, factor = linear_step.direct(A, res.vector, step.nu, reuse=factor)
    return dx, lambda full=False: (rows, factor[2], A), factor, 0


def _singular_fallback(step, it, res, closed_before, linear, modes, blocksize, error,
                       linear_tol=1e-12, setup=None):
    """A singular Newton matrix (the active set leaves a part of the body free):
    the Jacobian that keeps closed the points closed at the last iterate, then
    the one with every unilateral point closed, then, with Coulomb points, the
    one with every point closed and sticking (its tangential law linearised at
    y = 0, inside the friction ball: a part that only Γ holds, every point of it
    sliding, is free along Γ in the slip branch's Jacobian, e.g. unloaded towards
    zero).  The residual stays the step's own, so the answer does not change,
    only the path to it.  If the last is singular too, no active set helps: the
    law or the space is at fault (``error`` re-raised)."""
    chi = np.where(step.laws.unilateral, res.g_n <= 0, True)
    everywhere = np.ones(chi.size, bool)
    tried = [chi]
    attempts = [(closed_before, res), (everywhere, res)]
    if np.any(step.laws.tangential == "coulomb"):
        attempts.append((everywhere, replace(res, y=np.zeros_like(res.y))))
    for close, seen in attempts:
        if seen is res and any(np.array_equal(chi | close, t) for t in tried):
            continue
        tried.append(chi | close)
        try:
            return _linear_step(step, it, seen, close, linear, modes, blocksize, setup,
                                linear_tol)
        except linear_step.SingularStepError as e:
            error = e
    raise error


def _not_converged(what, history, statuses, tol, last, detail=""):
    """The ContactConvergenceError of a step: residuals and the points that kept flipping."""
    r = history[-1]
    seen = np.array(statuses)
    changes = ((seen[1:] != seen[:-1]).sum(axis=0) if len(seen) > 1
               else np.zeros(seen.shape[1], int))
    moving = np.flatnonzero(changes > 1)
    err = ContactConvergenceError(
        f"contact Newton {what}{detail}: relative residuals equilibrium {r[0]:.1e}, "
        f"contact {r[1]:.1e}, friction {r[2]:.1e}"
        f"{'' if not np.isfinite(tol) else f' (tolerance {tol:.0e})'}; {moving.size} "
        f"point(s) changed status more than once"
        f"{': dofs ' + str(moving[:10].tolist()) if moving.size else ''}")
    err.last = last
    err.statuses = seen
    return err


def with_threshold(step: StepProblem, threshold) -> StepProblem:
    """``step`` with the friction radius frozen at ``threshold`` (m,) where closed."""
    return replace(step, laws=replace(step.laws, threshold=np.asarray(threshold, float)))
