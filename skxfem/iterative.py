r"""An iterative solve of the tied saddle-point system, for systems too large for LU.

Same equations and contract as :func:`skxfem.saddle.solve`: for U with
U[D] = g,

.. math:: K U + B^T y = F, \qquad B U = 0, \qquad \mu = -y .

Why this design
---------------
The direct path factorises the whole saddle matrix; in 3D its fill grows
like dofs².  A plain elasticity solve scales because algebraic multigrid
(AMG) solves K nearly optimally.  Two obstacles stand between K and AMG here:

* K is singular on the free unknowns whenever a side of Γ is held by the
  tie alone (the paper's plate: Ω⁺ floats without the multipliers), so K
  itself cannot be the (1,1) block of a block preconditioner;
* the multipliers need a Schur-complement approximation, and B K⁻¹ Bᵀ is
  an H^{-1/2}-like operator that no interface mass approximates uniformly.

The augmented Lagrangian removes both.  Since B U = 0 at the solution, the
system is unchanged if r BᵀWB U is added to the first equation:

.. math:: K_r = K + r B^T W B, \qquad
          \begin{bmatrix} K_r & B^T \\ B & 0 \end{bmatrix}
          \begin{bmatrix} U \\ y \end{bmatrix} =
          \begin{bmatrix} F \\ 0 \end{bmatrix} .

K_r is SPD on the free unknowns whenever the tied problem is well posed, and
its Schur complement is S_r = B K_r⁻¹ Bᵀ = (S⁻¹ + rW)⁻¹, so rW approximates
S_r⁻¹ better the larger r (Benzi & Olshanskii's augmented-Lagrangian
preconditioner).  We scale K symmetrically to unit diagonal (a sliver of
an enriched support has a tiny stiffness) and normalise the rows of B, so
that W = I and r is a plain number: r ≈ 1 means a penalty of the order of the
local stiffness E/h.  FGMRES then runs on the augmented system,
preconditioned by the block upper-triangular

.. math:: P = \begin{bmatrix} \tilde K_r & B^T \\ 0 & -\tilde S_r \end{bmatrix},
          \qquad \tilde S_r^{-1} = r I + (B_n B_n^T + \delta I)^{-1},

with K̃_r⁻¹ one AMG V-cycle, and S̃_r⁻¹ Woodbury's S⁻¹ + rI with S
replaced by B diag(K)⁻¹ Bᵀ = B_n B_nᵀ (the SIMPLE approximation; δ shifts
the exactly dependent rows).  That second term matters where rows of B are
nearly dependent (the vital space on prisms: singular values of B down to
5e-5 of the largest), where S is tiny and rI alone is a poor S_r⁻¹; it is a
sparse m × m interface matrix, factorised once.  Per iteration: one
V-cycle, two products with B, two triangular solves on the interface.

r trades the two blocks: the larger r, the better the multipliers' block,
but the stiffer the penalty and the worse the AMG does on K_r.  Measured on
the paper's plate (hex, n = 16): AMG-CG on K_r alone took 11, 27, 71
iterations for r = 1, 10, 100; the whole solve (with rI alone on the
multipliers) 37, 29, 25, 23, 32 FGMRES iterations for r = 1, 2, 3, 5, 10,
where block-diagonal MINRES needed 60-75.  On the prism plate (n = 8) the
SIMPLE term took FGMRES from 118 to 39 iterations (hex n = 12: 24 → 27).
Hence r = 3 and FGMRES, which needs no symmetric preconditioner; its
memory is 2 × ``restart`` vectors (30: see ``restart`` below).

The AMG is pyamg's smoothed aggregation on nodal blocks, its near-null space
the rigid motions *of each side of Γ separately*
(:func:`skxfem.amg.rigid_modes`): on the
free unknowns, K vanishes on a rigid motion of Ω⁻ with Ω⁺ at rest and vice
versa, and these are expressed in [a, b] (a rigid motion of the whole body is
their sum, with b = 0).  K_r is near-singular only on their combinations that
the tie lets slide (a frictionless tie); a bonded tie holds both sides
together and the rigid motions of the whole body suffice (``bonded=True``:
half the coarse unknowns).  The same modes tell a system that is singular —
a side that neither the supports nor the tie hold, where an iterative
method would return an arbitrary U — apart: :func:`solve` refuses it
(:func:`skxfem.amg.check_held`).  The coarse grid is solved by SuperLU
(``coarse_solver="splu"``; pyamg's default pseudo-inverse was 13× slower
on the plain baseline, as measured in issue 11).

Dependent multipliers (the naive spaces) make the system singular but
consistent: U is still unique, and FGMRES converges to a solution.  The
multipliers reported are then chosen by :func:`skxfem.smoothest.smoothest`
(the smoothest, or the least-norm ones that balance U), a sparse computation
on the interface unknowns only — no dense step, nothing that grows like dofs².

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
from scipy.sparse.linalg import LinearOperator, splu

from .amg import amg, check_held, pyamg
from .saddle import SingularSystemError
from .smoothest import dependencies, smoothest

__all__ = ["IterativeInfo", "ConvergenceError", "solve"]


class ConvergenceError(ValueError):
    """The iterative solve did not reach its tolerance within its iteration limit.

    A ValueError, since the remedy is in the call: more iterations
    (``maxiter``), a looser ``tol``, or the direct path
    (:func:`skxfem.saddle.solve`) for a system that is singular or nearly so.
    ``iterations`` and ``residual`` (the relative residual reached) say how far
    it got.
    """

    def __init__(self, message: str, iterations: int, residual: float):
        super().__init__(message)
        self.iterations = iterations
        self.residual = residual


@dataclass(frozen=True)
class IterativeInfo:
    """Diagnostics of :func:`solve`: FGMRES ``iterations``, the relative
    ``residual`` of the saddle system reached, ``balance`` (the relative error
    of Bᵀμ = K U - F), ``removed`` (the dependent multipliers, whose values
    were chosen smoothest: as :class:`skxfem.saddle.SaddleInfo`), the AMG
    ``levels`` and operator ``complexity``, the penalty ``r``, the relative
    ``residuals``, one per iteration, and ``timings``: seconds of the
    ``setup`` (scaling, AMG), the ``krylov`` iterations and the choice of
    ``multipliers``."""

    iterations: int
    residual: float
    balance: float
    removed: int
    levels: int
    complexity: float
    r: float
    residuals: tuple = ()
    timings: dict = field(default_factory=dict)


def solve(K, B, F, D=None, g=None, G=None, modes=None, blocksize: int = 1,
          bonded: bool = False, tol: float = 1e-10, maxiter: int = 500, r: float = 3.0,
          restart: int = 30, delta: float = 1e-8, refine: int = 3,
          dependent_tol: float = 1e-8, rigid_tol: float = 1e-11):
    """Solve the tied saddle-point system by AMG-preconditioned FGMRES; see the module notes.

    Parameters
    ----------
    K, B, F, D, g, G
        As :func:`skxfem.saddle.solve`: stiffness (N, N), coupling (m, N),
        load (N,), imposed unknowns and values, and the neighbour differences
        (p, m) for the smoothest multipliers (without G: the least-norm ones).
    modes
        (N, 2k) the rigid motions of each side (:func:`skxfem.amg.rigid_modes`):
        checked to be held, and the near-null space of the AMG.  Default: no
        check, and pyamg's near-null space, the constant vector.
    blocksize
        Unknowns per node, interleaved (the space's dimension); 1: scalar AMG.
    bonded
        ``True`` when the tie holds the sides together in every direction
        (the bonded law): the AMG then needs only the rigid motions of the
        whole body (the sums of the pairs of ``modes``), a cheaper hierarchy.
    tol
        Relative residual ‖b - A x‖/‖b‖ of the (scaled) saddle system to reach.
    maxiter
        Krylov iteration limit (all restarts together).
    r
        Penalty of the augmented Lagrangian, relative to the unit diagonal.
    restart
        Krylov vectors kept before FGMRES restarts (memory: 2 × restart × (N + m),
        the basis and its preconditioned vectors).  On the triangle strip,
        n = 512 (530k unknowns, 1 run): 100 → 55 iterations, 15.5 s, peak
        1937 MB; 30 → 59, 13.4 s, 1439 MB; 15 → 64, 13.2 s, 1194 MB; on the
        plate at n = 24 (hex 29, prism 36 iterations) 30 changed nothing.
    delta
        Shift of B_n B_nᵀ (unit diagonal) in the multipliers' block.
    refine
        Least-squares corrections of the multipliers against K U - F.
    dependent_tol
        Singular values of B (free columns) below this times the largest
        count as dependencies, their multipliers chosen smoothest
        (:func:`skxfem.smoothest.dependencies`).  Smaller than the dense
        path's 1e-6: the vital space on the prism plate has genuine singular
        values of 3.4e-6 (n = 16) and 8.7e-7 (n = 24) of the largest, which
        must balance U (with 1e-6 both paths left an imbalance of 1.8e-8 at
        n = 24), while exact dependencies come out below 3e-10 (measured).
    rigid_tol
        A combination of ``modes`` whose energy in K_r (scaled) is below this
        is a rigid motion the supports and the tie leave free.

    Returns
    -------
    U, mu, info
        Unknowns (N,), multipliers (m,), :class:`IterativeInfo`.

    Raises
    ------
    ConvergenceError
        (a ValueError) ``tol`` not reached within ``maxiter`` iterations, or
        multipliers that do not balance U.
    skxfem.saddle.SingularSystemError
        (a ValueError) A free unknown without any stiffness, or a rigid
        motion of a side (a combination of ``modes``) that neither the
        supports nor the tie hold: an iterative method would return an
        arbitrary U there.
    ImportError
        pyamg is not installed.
    """
    if not (tol > 0 and maxiter >= 1 and r > 0 and restart >= 1):
        raise ValueError(f"tol, maxiter, r and restart must be positive, got "
                         f"{tol!r}, {maxiter!r}, {r!r}, {restart!r}")
    fgmres = pyamg().krylov.fgmres
    t0 = time.perf_counter()
    N, m = K.shape[0], B.shape[0]
    K, B, F = sp.csr_matrix(K), sp.csr_matrix(B), np.asarray(F, float)
    fixed = np.zeros(N, dtype=bool)
    fixed[np.zeros(0, int) if D is None else np.asarray(D, int)] = True
    U0 = np.zeros(N)
    if D is not None:
        U0[np.asarray(D, int)] = 0.0 if g is None else np.asarray(g, float)
    s, Ks, Bn, rows = _scaled(K, B, fixed)
    Kr = (Ks + r * (Bn.T @ Bn)).tocsr()
    c = -rows * (B @ U0)
    rhs = np.concatenate([np.where(fixed, 0.0, s * (F - K @ U0)) + r * (Bn.T @ c), c])
    Zs = None if modes is None else modes / s[:, None]
    if Zs is not None:
        check_held(Kr, Zs, rigid_tol)
        if bonded:
            Zs = Zs[:, 0::2] + Zs[:, 1::2]
    ml = amg(Kr, Zs, blocksize)
    M1 = ml.aspreconditioner(cycle="V")

    # S_r⁻¹ = S⁻¹ + r I, with S ≈ B diag(K)⁻¹ Bᵀ = B_n B_nᵀ (K_s has a unit
    # diagonal), shifted by delta for dependent rows: an m x m interface matrix
    simple = splu((Bn @ Bn.T + delta * sp.identity(m)).tocsc())

    def triangular(v):  # [[K̃_r, Bᵀ], [0, -S̃_r]]⁻¹
        y = -(r * v[N:] + simple.solve(v[N:]))
        return np.concatenate([M1 @ (v[:N] - Bn.T @ y), y])

    A = sp.bmat([[Kr, Bn.T], [Bn, None]], format="csr")
    P = LinearOperator((N + m, N + m), matvec=triangular, dtype=float)
    t1 = time.perf_counter()
    history = []
    x, _ = fgmres(A, rhs, tol=tol, restart=min(restart, maxiter, N + m), M=P,
                  maxiter=-(-maxiter // min(restart, maxiter, N + m)), residuals=history)
    nrhs = max(np.linalg.norm(rhs), 1e-300)
    residual = float(np.linalg.norm(A @ x - rhs) / nrhs)
    iterations = max(len(history) - 1, 0)
    if not np.isfinite(residual) or residual > tol:
        raise ConvergenceError(
            f"FGMRES did not reach the relative residual {tol:.0e} within {maxiter} "
            f"iterations (reached {residual:.2e} after {iterations}): raise maxiter, "
            f"loosen tol, or use the direct solve (skxfem.saddle.solve), which also "
            f"tells a singular system (a part of the body free to move) apart",
            iterations, residual)
    t2 = time.perf_counter()
    U = U0 + s * np.where(fixed, 0.0, x[:N])
    free = np.flatnonzero(~fixed)
    reaction = (K @ U - F)[free]
    # the multipliers must balance U itself, B_nᵀ ŷ = S (K U - F): a few least-squares
    # corrections with the factorised B_n B_nᵀ + δI sharpen the Krylov ones (where rows
    # of B are nearly dependent, the residual alone leaves them less accurate)
    y, target = x[N:].copy(), np.where(fixed, 0.0, s * (K @ U - F))
    for _ in range(refine):
        y -= simple.solve(Bn @ (Bn.T @ y + target))
    dependent = dependencies(B[:, free], dependent_tol)
    mu = smoothest(B[:, free], -rows * y, G, N=dependent)
    balance = float(np.linalg.norm(B[:, free].T @ mu - reaction) / max(
        np.linalg.norm(reaction), np.linalg.norm(F[free]), 1e-300))
    if not balance <= max(10 * tol, 1e-8):
        raise ConvergenceError(
            f"the multipliers do not balance the displacement (relative error "
            f"{balance:.1e}): tighten tol", iterations, residual)
    timings = {"setup": t1 - t0, "krylov": t2 - t1, "multipliers": time.perf_counter() - t2}
    return U, mu, IterativeInfo(iterations, residual, balance, dependent.shape[1],
                                len(ml.levels), float(ml.operator_complexity()), float(r),
                                tuple(np.asarray(history) / nrhs), timings)


def _scaled(K, B, fixed):
    """Jacobi-scaled K (imposed unknowns as identity rows, so nodal blocks stay
    whole) and B with unit rows: s, K_s = S K S, B_n = R B S, the row scales R."""
    diag = np.abs(K.diagonal())
    if np.any(diag[~fixed] == 0):
        raise SingularSystemError(
            f"{int(np.sum(diag[~fixed] == 0))} unknown(s) have no stiffness at all (a node "
            f"that no cell uses, or an enriched function with an empty support): remove "
            f"unused nodes from the mesh or impose those unknowns")
    s = np.where(fixed, 1.0, 1.0 / np.sqrt(np.where(diag > 0, diag, 1.0)))
    keep = sp.diags(np.where(fixed, 0.0, s))
    Ks = (keep @ K @ keep + sp.diags(fixed.astype(float))).tocsr()
    Bs = (B @ keep).tocsr()
    norms = np.sqrt(np.asarray(Bs.multiply(Bs).sum(axis=1)).ravel())
    rows = 1.0 / np.where(norms > 0, norms, 1.0)
    return s, Ks, (sp.diags(rows) @ Bs).tocsr(), rows

