r"""An iterative solve of the tied saddle-point system, for systems too large for LU.

Same equations and contract as :func:`skxfem.linalg.saddle.solve`: for U with
U[D] = g (and c = 0 for a tie),

.. math:: K U + B^T y = F, \qquad B U = c, \qquad \mu = -y .

Why this design
---------------
The direct path factorises the whole saddle matrix; in 3D its fill grows
like dofs².  A plain elasticity solve scales because algebraic multigrid
(AMG) solves K nearly optimally.  Here U minimises the energy on the
constrained space {B U = 0}, so it is the conjugate-gradient solution of K
restricted to ker B (the null-space method): the multipliers are not
unknowns of the iteration at all, and are recovered afterwards from the
residual, Bᵀy = F - K U, by a least-squares solve on the interface.

K is singular on the free unknowns whenever a side of Γ is held by the tie
alone (the paper's plate: Ω⁺ floats without the multipliers), so AMG is
built on an augmented operator instead.  With K scaled symmetrically to
unit diagonal (a sliver of an enriched support has a tiny stiffness) and
the rows of B normalised (K_s, B_n),

.. math:: K_r = K_s + r B_n^T B_n

equals K_s on ker B and is SPD on the free unknowns whenever the tied
problem is well posed (r ≈ 1: a penalty of the order of E/h).  CG needs
its iterates in ker B: the orthogonal projection

.. math:: \Pi = I - B_n^T (B_n B_n^T)^{-1} B_n ,

needs the m × m interface matrix B_n B_nᵀ, factorised once (SuperLU,
shifted by δ for exactly dependent rows and refined twice, so that nearly
dependent rows are still projected out).  CG then runs on K_r with the
projected preconditioner Π M Π, M one symmetric AMG V-cycle of K_r (Gould,
Hribar & Nocedal's projected CG): a short recurrence, restarted only where the
recursive residual drifted from the true one, no Krylov basis to keep.  Per
iteration: one V-cycle, one product with K_r, two projections (four products with
B, six triangular solves on the interface).

r trades the two parts: the larger r, the closer M Π is to the inverse of K
on ker B, but the worse the AMG does on the stiffer K_r.  On the paper's
plate (hex, n = 16; 1 run): 19, 18, 25, 62 iterations for r = 1, 3, 10,
100; hence r = 3.  The FGMRES with a block-triangular augmented-Lagrangian
preconditioner that this replaced took 28, 31, 30, 38, 45 iterations on
the plate (hex n = 16, 32; prism n = 16, 32; prism n = 16 naive), projected
CG 18, 21, 24, 32, 23; the whole hex n = 32 solve 6.2 s, now 4.3 s.

The AMG (:func:`skxfem.linalg.amg.amg`) is smoothed aggregation on nodal blocks
with a SuperLU coarse solve, its near-null space the rigid motions *of each
side of Γ separately* (:func:`skxfem.linalg.amg.rigid_modes`): K vanishes on a
rigid motion of Ω⁻ with Ω⁺ at rest and vice versa.  A bonded tie holds the
sides together, and the rigid motions of the body suffice (``bonded=True``:
half the coarse unknowns).  The same modes tell a singular system — a side
that neither the supports nor the tie hold, where CG would return an
arbitrary U — apart: :func:`solve` refuses it (:func:`skxfem.linalg.amg.check_held`).
Its smoother is a Chebyshev polynomial of degree 2 (:data:`skxfem.linalg.amg.SMOOTHER`),
that of the one hierarchy a contact solve carries over its steps (:func:`stiffness_setup`)
pyamg's symmetric block Gauss-Seidel (:data:`skxfem.linalg.amg.CARRIED_SMOOTHER`).  CG
applies one V-cycle (:func:`skxfem.linalg.amg.vcycle`).

CG stops at the relative residual ``tol`` of the scaled system.  On large systems
rounding can hold the true residual just above it, whatever the iterations (a 2D tie of
529 416 unknowns, ``scenes.strip(512, cell="tri")``: 1.7e-12 for ``tol = 1e-12``, with
either smoother); once restarts no longer lower it
(:data:`skxfem.linalg.pcg.STALLED_RESTARTS`), x is taken if its normwise backward
error ‖r‖/(‖K_r‖ ‖x‖ + ‖b‖) (:func:`backward_error`) is below ``tol``: x then solves
exactly a system within ``tol`` of the given one (the paper's plate with Ω⁺ 1000 times
stiffer, tetrahedra n = 16: 1.65e-11 after 475 iterations, U within 1.4e-12 of the
direct solve's, whose own residual is 7.7e-12; one run).  ``info.residual`` keeps the
residual reached; anything else is a :class:`ConvergenceError`.

Dependent multipliers (the naive spaces) leave ker B and U unique; the
multipliers, not unique then, are chosen by :func:`skxfem.linalg.dependent.smoothest`
(the smoothest, or the least-norm ones, that balance U): sparse, on the
interface only, nothing that grows like dofs².

>>> import numpy as np, scipy.sparse as sp
>>> K = sp.identity(2, format="csr"); B = sp.csr_matrix([[1.0, -1.0], [2.0, -2.0]])
>>> U, mu, info = solve(K, B, np.array([1.0, 0.0]))
>>> U.round(10).tolist(), np.allclose(B.T @ mu, K @ U - [1.0, 0.0])
([0.5, 0.5], True)
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from .amg import (
    CARRIED_SMOOTHER,
    MOTIONS,
    amg,
    augmented,
    check_held,
    pyamg,
    refresh,
    scaled_rows,
    scaled_tie,
    vcycle,
)
from .dependent import dependencies, smoothest
from .pcg import interface_solve, oblique_solve, projected_cg, projected_gmres
from .saddle import SingularSystemError

__all__ = ["IterativeInfo", "ConvergenceError", "Setup", "solve", "stiffness_setup",
           "backward_error"]


class ConvergenceError(ValueError):
    """The iterative solve did not reach its tolerance within its iteration limit.

    A ValueError: the remedy is in the call (``maxiter``, ``tol``, or the
    direct path).  ``iterations`` and ``residual`` say how far it got.
    """

    def __init__(self, message: str, iterations: int, residual: float):
        super().__init__(message)
        self.iterations = iterations
        self.residual = residual


@dataclass(frozen=True)
class IterativeInfo:
    """Diagnostics of :func:`solve`: CG ``iterations``, the relative
    ``residual`` of the saddle system reached, ``balance`` (the relative error
    of Bᵀμ = K U - F), ``removed`` (the dependent multipliers, whose values
    were chosen smoothest: as :class:`skxfem.linalg.saddle.SaddleInfo`), the AMG
    ``levels`` and operator ``complexity``, the penalty ``r``, the relative
    ``residuals``, one per iteration, and ``timings``: seconds of the
    ``setup`` (scaling, AMG, interface factorisation), the ``krylov``
    iterations and the choice of ``multipliers``; ``backward_error``: where rounding held
    the residual above the tolerance, the normwise backward error that accepted the
    answer instead (module notes), else None."""

    iterations: int
    residual: float
    balance: float
    removed: int
    levels: int
    complexity: float
    r: float
    residuals: tuple = ()
    timings: dict = field(default_factory=dict)
    setup: object = field(default=None, repr=False, compare=False)
    backward_error: float | None = None


@dataclass(eq=False)
class Setup:
    """What :func:`solve` builds before iterating, for one (K, B, imposed
    unknowns, r, ``bonded``): the scaling, K_r, its AMG and the interface
    solve (and, once asked for, the dependencies).  ``solve(..., reuse=info.setup)``
    takes it again when those are unchanged (a Newton step with the same
    active set): no second set-up of the same operator."""

    K: sp.csr_matrix
    B: sp.csr_matrix
    fixed: np.ndarray
    r: float
    bonded: bool
    s: np.ndarray
    Bn: sp.csr_matrix
    rows: np.ndarray
    Kr: sp.csr_matrix
    ml: object
    interface: object
    dependent: np.ndarray | None = None
    base: Setup | None = field(default=None, repr=False)
    """The :func:`stiffness_setup` this one was carried over from (``update``)."""
    S: sp.csr_matrix | None = None
    """The interface stiffness added to K (:func:`solve`'s ``S``), or None."""

    def stiffness(self, U) -> np.ndarray:
        """(K + S) U."""
        return self.K @ U if self.S is None else self.K @ U + self.S @ U

    def carries(self, K, B, fixed, r, bonded) -> bool:
        """Whether this set-up can be carried over to (K, B, fixed, r, bonded)
        (:func:`solve`'s ``update``): the same shapes, imposed unknowns, r and law."""
        return (r == self.r and bonded == self.bonded and np.array_equal(fixed, self.fixed)
                and K.shape == self.K.shape and B.shape[1] == self.B.shape[1])

    def serves(self, K, B, fixed, r, bonded, S=None) -> bool:
        """Whether this set-up is that of (K, B, fixed, r, bonded, S)."""
        return (self.carries(K, B, fixed, r, bonded) and B.shape == self.B.shape
                and _same(K, self.K) and _same(B, self.B) and _same(S, self.S))


def _same(A, B) -> bool:
    """Whether the sparse matrices (or Nones) A and B are equal."""
    if A is B:
        return True
    if A is None or B is None:
        return False
    return A.shape == B.shape and (A != B).nnz == 0


def solve(K, B, F, D=None, g=None, G=None, c=None, modes=None, blocksize: int = 1,
          bonded: bool = False, tol: float = 1e-10, maxiter: int = 500, r: float = 3.0,
          delta: float = 1e-12, refine: int = 2,
          dependent_tol: float = 1e-8, rigid_tol: float = 1e-11, reuse: Setup | None = None,
          C=None, update: bool = False, independent: bool = False, S=None):
    """Solve the tied saddle-point system by projected AMG-preconditioned CG; see the module notes.

    Parameters
    ----------
    K, B, F, D, g, G
        As :func:`skxfem.linalg.saddle.solve`: stiffness (N, N), coupling (m, N),
        load (N,), imposed unknowns and values, and the neighbour differences
        (p, m) for the smoothest multipliers (without G: the least-norm ones).
    c
        (m,) right-hand side of B U = c; default 0 (a tie).
    modes
        (N, 2k) the rigid motions of each side (:func:`skxfem.linalg.amg.rigid_modes`):
        checked to be held, and the near-null space of the AMG.  Default: no
        check, and pyamg's near-null space, the constant vector.
    blocksize
        Unknowns per node, interleaved (the space's dimension); 1: scalar AMG.
    bonded
        ``True`` when the tie holds the sides together in every direction
        (the bonded law): the AMG then needs only the rigid motions of the
        whole body (the sums of the pairs of ``modes``), a cheaper hierarchy.
    tol
        Relative residual ‖b - A x‖/‖b‖ of the (scaled) saddle system to reach (where
        rounding stops it above, the normwise backward error: module notes).
    maxiter
        CG iteration limit.
    r
        Penalty of the augmented operator K_r, relative to the unit diagonal.
    delta, refine
        Shift of B_n B_nᵀ for exactly dependent rows, and the refinement
        steps of every solve with it: each divides the error of a mode with
        singular value σ of B_n by 1 + σ²/δ.
    dependent_tol
        Singular values of B (free columns) below this times the largest
        count as dependencies, their multipliers chosen smoothest
        (:func:`skxfem.linalg.dependent.dependencies`).  Below the dense path's
        1e-6: the vital prism plate has genuine singular values of 8.7e-7 of
        the largest (n = 24), exact dependencies come out below 3e-10.
    rigid_tol
        A combination of ``modes`` whose energy in K_r (scaled) is below this
        is a rigid motion the supports and the tie leave free.
    reuse
        The :class:`Setup` of an earlier call (``info.setup``), taken again if
        it :meth:`~Setup.serves` this one (then ``modes`` are not checked again).
    update
        With a ``reuse`` that does not serve this call but has its shapes and
        imposed unknowns: carry its scaling and AMG hierarchy over to this K and
        B (:func:`skxfem.linalg.amg.refresh`, the Galerkin update of a change on
        a few rows) instead of a new set-up.  For a sequence of systems that
        differ on the interface rows only (the steps of a contact solve).
    S
        (N, N) a stiffness added to K where it is nonzero on few rows (a sliding
        contact's interface stiffness): the system is that of K + S, without a
        copy of K.
    independent
        The caller knows the rows of B to be independent (each is one of a set of
        rows checked once, as the rows a contact step ties): no search for
        dependent multipliers (``info.removed`` is 0).
    C
        (m, N) the directions of the multipliers where they are not B's:
        K U + Cᵀ y = F, B U = c (a sliding Coulomb point's normal tilted by its
        friction, :mod:`skxfem.contact.step`).  The system is then not
        symmetric on ker B: projected GMRES (:func:`skxfem.linalg.pcg.projected_gmres`)
        instead of CG, the multipliers from the interface matrix B Cᵀ, which
        must be invertible (no dependent multipliers).

    Returns
    -------
    U, mu, info : (N,), (m,), :class:`IterativeInfo`

    Raises
    ------
    ConvergenceError
        (a ValueError) ``tol`` not reached within ``maxiter`` iterations, or
        multipliers that do not balance U.
    skxfem.linalg.saddle.SingularSystemError
        (a ValueError) A free unknown without any stiffness, or a rigid
        motion of a side (of ``modes``) that neither supports nor tie hold.
    ImportError
        pyamg is not installed.
    """
    if not (tol > 0 and maxiter >= 1 and r > 0 and delta > 0 and refine >= 0):
        raise ValueError(f"tol, maxiter, r and delta must be positive and refine >= 0, got "
                         f"{tol!r}, {maxiter!r}, {r!r}, {delta!r}, {refine!r}")
    pyamg()  # an ImportError naming the install before any work
    t0 = time.perf_counter()
    N = K.shape[0]
    K, B, F = sp.csr_matrix(K), sp.csr_matrix(B), np.asarray(F, float)
    S = None if S is None else sp.csr_matrix(S)
    D = np.zeros(0, int) if D is None else np.asarray(D, int)
    fixed, U0 = np.zeros(N, dtype=bool), np.zeros(N)
    fixed[D], U0[D] = True, (0.0 if g is None else np.asarray(g, float))
    if reuse is not None and reuse.serves(K, B, fixed, r, bonded, S):
        setup = reuse
    elif update and reuse is not None and reuse.carries(K, B, fixed, r, bonded):
        setup = _carried(reuse, K, B, S, modes, delta, refine, rigid_tol)
    else:
        setup = _setup(K if S is None else (K + S).tocsr(), B, fixed, modes, blocksize,
                       bonded, r, delta, refine, rigid_tol)
        if S is not None:
            setup.K, setup.S = K, S
    if independent and setup.dependent is None:
        setup.dependent = np.zeros((B.shape[0], 0))
    oblique = None if C is None else _oblique(setup, sp.csr_matrix(C))
    t1 = time.perf_counter()
    x, history, scale, residual, accepted = _krylov(setup, F, c, U0, tol, maxiter, oblique)
    t2 = time.perf_counter()
    U = U0 + setup.s * np.where(fixed, 0.0, x)
    mu, balance = _multipliers(setup, B, F, U, G, dependent_tol, tol, len(history) - 1,
                               residual, oblique)
    timings = {"setup": t1 - t0, "krylov": t2 - t1, "multipliers": time.perf_counter() - t2}
    return U, mu, IterativeInfo(len(history) - 1, residual, balance, setup.dependent.shape[1],
                                len(setup.ml.levels), float(setup.ml.operator_complexity()),
                                float(r), tuple(np.asarray(history) / scale), timings, setup,
                                backward_error=accepted)


def _oblique(setup: Setup, C):
    """The scaled multiplier directions C_n (B's row and column scales) and the
    solve with B_n C_nᵀ, for :func:`_krylov` and :func:`_multipliers`."""
    keep = sp.diags(np.where(setup.fixed, 0.0, setup.s))
    Cn = (sp.diags(setup.rows) @ C @ keep).tocsr()
    try:
        return Cn, oblique_solve(setup.Bn, Cn)
    except RuntimeError as e:  # SuperLU: exactly singular
        raise SingularSystemError(
            f"the multipliers' directions C and the constraints B give a singular "
            f"interface matrix B Cᵀ ({e}): dependent multipliers") from e


def _krylov(setup: Setup, F, c, U0, tol: float, maxiter: int, oblique=None):
    """The scaled system K_s x + B_nᵀ y = b, B_n x = c by projected CG from the
    particular x_p = B_nᵀ(B_n B_nᵀ)⁻¹c (B_n x_p = c): x, the residual history,
    its scale ‖(b, c)‖, the relative residual reached and the backward error that
    accepted it above ``tol`` (None if it did not need to; else ConvergenceError).
    With ``oblique`` = (C_n, (B_n C_nᵀ)⁻¹) (:func:`_oblique`): K_s x + C_nᵀ y = b,
    by projected GMRES."""
    fixed, s, Bn, Kr, interface = setup.fixed, setup.s, setup.Bn, setup.Kr, setup.interface
    M = vcycle(setup.ml)

    def project(v):  # Π v = v - B_nᵀ (B_n B_nᵀ)⁻¹ B_n v, onto ker B
        return v - Bn.T @ interface(Bn @ v)

    b = np.where(fixed, 0.0, s * (F - setup.stiffness(U0)))
    c = setup.rows * ((0.0 if c is None else np.asarray(c, float)) - setup.B @ U0)
    x = Bn.T @ interface(c)
    scale = max(np.linalg.norm(np.concatenate([b, c])), 1e-300)
    if oblique is None:
        x, history = projected_cg(Kr, M, project, b, x, tol * scale, maxiter)
        balanced = project
    else:
        Cn, solve_BC = oblique

        def balanced(v):  # Q v = v - C_nᵀ (B_n C_nᵀ)⁻¹ B_n v: onto ker B along C
            return v - Cn.T @ solve_BC(Bn @ v)
        # on x + ker B, K_r x = K_s x + r B_nᵀ c: Q, unlike Π, keeps B_nᵀ c
        b = b + setup.r * (Bn.T @ c)
        x, history = projected_gmres(Kr, M, project, balanced, b, x, tol * scale, maxiter)
    iterations = len(history) - 1
    residual = float(np.hypot(np.linalg.norm(balanced(b - Kr @ x)),
                              np.linalg.norm(Bn @ x - c)) / scale)
    if np.isfinite(residual) and residual > tol and iterations < maxiter:
        eta = backward_error(Kr, x, residual * scale, scale)
        if eta <= tol:
            return x, history, scale, residual, eta   # rounding's floor, module notes
    if not np.isfinite(residual) or residual > tol:
        raise ConvergenceError(
            f"projected CG did not reach the relative residual {tol:.0e} " + (
                f"within {maxiter} iterations (reached {residual:.2e}): raise maxiter, "
                f"loosen tol, or use the direct solve" if iterations >= maxiter else
                f"(reached {residual:.2e}; after {iterations} iterations a direction had no "
                f"energy: the system is singular or nearly so, a part of the body free "
                f"to move?): use the direct solve, which tells the cause"),
            iterations, residual)
    return x, history, scale, residual, None


def backward_error(A, x: np.ndarray, r: float, b: float, steps: int = 20) -> float:
    """The normwise backward error r / (‖A‖ ‖x‖ + b) of x, for a residual of norm ``r``
    and a right-hand side of norm ``b``: the least relative change of A and b that
    x solves exactly (Rigal & Gaches 1967).  ‖A‖ (A symmetric) by ``steps`` power
    iterations, a lower bound, so that the error returned is an upper bound.

    >>> import scipy.sparse as sp
    >>> A = sp.diags([1.0, 2.0, 4.0]).tocsr()
    >>> round(backward_error(A, np.ones(3), 1e-12, 1.0) / 1e-12, 3)   # 1/(4 √3 + 1)
    0.126
    """
    v = np.random.default_rng(0).standard_normal(A.shape[0])
    norm = 0.0
    for _ in range(steps):
        w = A @ v
        norm, v = np.linalg.norm(w) / np.linalg.norm(v), w
        if norm == 0:
            break
        v = v / np.linalg.norm(v)
    return float(r / (norm * np.linalg.norm(x) + b))


def _multipliers(setup: Setup, B, F, U, G, dependent_tol: float, tol: float,
                 iterations: int, residual: float, oblique=None):
    """The multipliers that balance U, B_nᵀ y = b - K_s x in the least-squares sense,
    made the smoothest along B's dependencies, and their relative balance (else
    ConvergenceError).  With ``oblique`` (:func:`_oblique`): C_nᵀ y = b - K_s x,
    y = (B_n C_nᵀ)⁻¹ B_n (b - K_s x)."""
    fixed = setup.fixed
    free = np.flatnonzero(~fixed)
    KU = setup.stiffness(U)
    reaction = (KU - F)[free]
    rhs = setup.Bn @ np.where(fixed, 0.0, setup.s * (F - KU))
    if setup.dependent is None:  # B alone decides them: once per set-up
        setup.dependent = dependencies(B[:, free], dependent_tol)
    if oblique is None:
        mu = smoothest(B[:, free], -setup.rows * setup.interface(rhs), G, N=setup.dependent)
        directions = B[:, free]
    else:
        mu = -setup.rows * oblique[1](rhs)
        directions = sp.diags(1.0 / setup.rows) @ oblique[0][:, free] @ sp.diags(
            1.0 / setup.s[free])
    balance = float(np.linalg.norm(directions.T @ mu - reaction) / max(
        np.linalg.norm(reaction), np.linalg.norm(F[free]), 1e-300))
    if not balance <= max(10 * tol, 1e-8):
        raise ConvergenceError(
            f"the multipliers do not balance the displacement (relative error "
            f"{balance:.1e}): tighten tol", iterations, residual)
    return mu, balance


def _carried(old: Setup, K, B, S, modes, delta, refine, rigid_tol) -> Setup:
    """``old`` carried over to K + S and B (:func:`solve`'s ``update``): from the
    set-up it was itself carried over from (its ``base``), keep the scaling s,
    add the change of K_r, ΔA = s(K + S - K_base)s + r B_nᵀB_n, which lives on the
    interface rows, and update the AMG hierarchy by it
    (:func:`skxfem.linalg.amg.refresh`); the interface solve anew, the rigid
    modes checked again (a new active set may leave a side free).  A set-up
    carried from a base is done with once the next is carried: its matrices are
    let go first, so that two of them are never held at once."""
    base = old.base if old.base is not None else old
    if old is not base:
        old.Kr = old.ml = None
    fixed, s, r = base.fixed, base.s, base.r
    keep = sp.diags(np.where(fixed, 0.0, s))
    dK = sp.csr_matrix(K.shape) if _same(K, base.K) else (K - base.K).tocsr()
    if S is not None:
        dK = dK + S
    Bn, rows = scaled_rows(B, s, fixed)
    change = (keep @ dK @ keep + r * (Bn.T @ Bn)).tocsr()
    change.eliminate_zeros()
    Kr = base.Kr + (change.tobsr(blocksize=base.Kr.blocksize) if base.Kr.format == "bsr"
                    else change)
    if modes is not None:
        check_held(Kr, modes / s[:, None], rigid_tol)
    return Setup(K, B, fixed, r, base.bonded, s, Bn, rows, Kr,
                 refresh(base.ml, Kr, change), interface_solve(Bn, delta, refine),
                 base=base, S=S)


def _setup(K, B, fixed, modes, blocksize, bonded, r, delta, refine, rigid_tol) -> Setup:
    """Scale, augment, check the rigid modes, build the AMG and the interface solve."""
    s, Bn, rows, Kr = augmented(K, B, fixed, r)
    Zs = None if modes is None else modes / s[:, None]
    if Zs is not None:
        check_held(Kr, Zs, rigid_tol, blocksize)
        if bonded:  # the motions of the whole body: the sum of the R regions' own
            k = MOTIONS.get(blocksize)
            R = Zs.shape[1] // k if k else 2
            Zs = sum(Zs[:, r::R] for r in range(R))
    return Setup(K, B, fixed, r, bonded, s, Bn, rows, Kr, amg(Kr, Zs, blocksize),
                 interface_solve(Bn, delta, refine))


def stiffness_setup(K, D=None, modes=None, blocksize: int = 1, r: float = 3.0,
                    delta: float = 1e-12, refine: int = 2) -> Setup:
    """The set-up of K alone, no constraint row: the one set-up of a sequence of
    ties that share K and differ in their rows (and in a stiffness on the
    interface), as the steps of a contact solve do.

    Pass it as ``reuse`` with ``update=True``: each tie then carries it over
    (:func:`skxfem.linalg.amg.refresh`), and so does a tie given the set-up of
    another carried from it: every carried set-up refers to this one.  Its AMG
    hierarchy is built for the scaled K_s, not K_r: coarse spaces made of each
    side's rigid motions, on aggregates that do not know the tie, serve every
    set of tied rows equally well; a hierarchy built for one tie (say every row
    bonded), carried over to a sliding interface, was measured to need twice
    the Krylov iterations (the slipping block, hex n = 14, one run: 85 against
    42 over a Newton solve).  K_s may be singular here (a side held by the
    interface alone):
    the tie's rows hold it in every carried set-up, where the rigid motions
    are checked.
    """
    K = sp.csr_matrix(K)
    N = K.shape[0]
    fixed = np.zeros(N, dtype=bool)
    if D is not None:
        fixed[np.asarray(D, int)] = True
    B = sp.csr_matrix((0, N))
    s, Ks, Bn, rows = scaled_tie(K, B, fixed)
    Zs = None if modes is None else modes / s[:, None]
    ml = amg(Ks, Zs, blocksize, CARRIED_SMOOTHER)  # K_s as its finest level holds it
    return Setup(K, B, fixed, r, False, s, Bn, rows, ml.levels[0].A, ml,
                 interface_solve(Bn, delta, refine))
