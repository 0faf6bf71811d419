r"""The saddle-point solve, with an honest treatment of dependent multipliers.

Solve, for the unknowns U with some entries imposed (U[D] = g),

.. math:: K U + B^T y = F, \qquad B U = 0,

where y = -μ and μ are the multipliers.  When the rows of B restricted to the
free unknowns are linearly dependent (the naive space on tetrahedra; a
multiplier whose jump a Dirichlet condition already fixes), U is still
unique but μ is not: μ + z solves the equations for every z with Bᵀz = 0.
Rather than letting the sparse LU return whatever its pivoting makes of a
singular matrix, we

1. find a maximal set of independent rows with a rank-revealing (pivoted) QR
   of the dense interface block of Bᵀ (:func:`reduce`),
2. solve the reduced, non-singular saddle system with SuperLU
   (:func:`factorise`, :func:`refined_solve`),
3. recover the multipliers from U: they balance it (Bᵀμ = KU - F on the free
   unknowns); where that does not fix them — dependent multipliers, or
   multipliers so nearly dependent (Γ a tiny distance from a node) that
   round-off would decide — take the *smoothest*, minimising ‖G μ‖ with G the
   differences between neighbouring multipliers (:func:`smoothest_multipliers`).
   A constant traction has G μ = 0, so it is recovered exactly whenever it
   balances U (the patch test; :func:`recover`).
4. check that the reported multipliers balance U (Bᵀμ = KU - F to ``tol``).
   They may not when rows of B are *nearly* dependent — kept by the QR (its
   pivots exceed 1e-10 of the largest) but with a singular value below the
   recovery's 1e-6 — and U's reaction really loads that combination: the
   multipliers that balance U then carry a spike of the size of the reaction
   over that singular value.  The unstable naive space does this where Γ
   passes within about 1e-4 of an edge's length from a node (a 128 × 129
   triangle strip, 1.6e-4: σ_min/σ_max = 8e-9, and the balance needs a
   multiplier 3e5 times the typical one).  Such a scene is refused
   with a :class:`NearlyDependentError` (a ValueError: use a stable space);
   any other imbalance is a RuntimeError, an unexpected numerical failure.

>>> import numpy as np, scipy.sparse as sp
>>> K = sp.identity(2, format="csr"); B = sp.csr_matrix([[1.0, -1.0], [2.0, -2.0]])
>>> U, mu, info = solve(K, B, np.array([1.0, 0.0]))
>>> U.round(12).tolist(), info.removed
([0.5, 0.5], 1)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .dependent import along

__all__ = ["SaddleInfo", "SingularSystemError", "NearlyDependentError", "independent_rows",
           "smoothest_multipliers", "floating", "factorise", "reduce", "refined_solve", "recover",
           "solve"]

SMOOTH_TOL = 1e-6
"""Singular values of B below this fraction of the largest are not trusted to fix
the multipliers: :func:`smoothest_multipliers` chooses those components."""
FIXED_TOL = 1e-8
"""Where the multipliers smoothed above SMOOTH_TOL do not balance U, they are
recovered again with this threshold: only singular values below it are left to
the smoothing (the same threshold as the iterative path's dependencies); the
second recovery is kept if it changes the multipliers by less than 10 %."""


class SingularSystemError(ValueError):
    """The saddle-point system has no unique solution: the scene's supports
    leave a rigid motion of one side of Γ free, or an unknown has no
    stiffness at all (a node no cell uses).  A ValueError, since the fix is
    in the input (the mesh, the scene's displacements or its interface law).
    ``detail``: what was measured (e.g. the smallest LU pivot), when known."""

    detail: str = ""


class NearlyDependentError(ValueError):
    """The multiplier space is nearly dependent on this mesh: no smooth
    multipliers balance the displacement, only ones with a huge spike.  A
    ValueError, since the fix is in the input: a stable multiplier space."""


@dataclass(frozen=True)
class SaddleInfo:
    """Diagnostics: ``removed`` dependent multipliers, the relative ``residual``
    of the solve, and ``balance``, the relative error of the equilibrium
    Bᵀμ = K U - F that the reported multipliers must satisfy."""

    removed: int
    residual: float
    balance: float = 0.0


def independent_rows(B: sp.spmatrix, tol: float = 1e-10) -> np.ndarray:
    """Sorted indices of a maximal set of linearly independent rows of B.

    A pivoted QR of the columns of Bᵀ (only the non-zero columns of B enter
    the dense factorisation); a pivot below ``tol`` times the largest one
    counts as zero.
    """
    B = sp.csr_matrix(B)
    cols = np.unique(B.indices)
    if cols.size == 0:
        return np.arange(0)
    _, R, piv = sla.qr(B[:, cols].toarray().T, mode="economic", pivoting=True)
    d = np.abs(np.diag(R))
    return np.sort(piv[:int(np.sum(d > tol * d.max()))])


def smoothest_multipliers(B, r, G, tol: float = SMOOTH_TOL) -> np.ndarray:
    """The smoothest μ with Bᵀμ = r: a truncated SVD, then least squares.

    With B = U S Vᵀ, the components of Uᵀμ whose singular value exceeds
    ``tol`` times the largest are fixed by the equilibrium, (Uᵀμ)_k =
    V_kᵀ r / s_k, exactly as the saddle solve would; the rest — exact
    dependencies, or a node within a tiny fraction of h of Γ whose
    multipliers B barely tells apart, where round-off in r would be
    amplified by 1/s_k — are chosen to minimise ‖Gμ‖.  A constant traction
    that balances U is thus recovered exactly.  The spurious modes of an
    unstable space have singular values of order β_h ≫ ``tol`` on the meshes
    used here, so their oscillations are reported as they are.
    """
    B = sp.csr_matrix(B)
    cols = np.unique(B.indices)
    U, sv, Vt = sla.svd(B[:, cols].toarray(), full_matrices=True)
    k = int(np.sum(sv > tol * sv[0])) if sv.size else 0
    mu = U[:, :k] @ ((Vt[:k] @ r[cols]) / sv[:k])
    return along(mu, U[:, k:], G)


def _unbalanced(B, r, mu, balance: float, tol: float, scale: float) -> Exception:
    """The error for multipliers ``mu`` that do not balance ``r`` (Bᵀμ ≠ r).

    With B = U S Vᵀ, the imbalance e = Bᵀμ - r is split into its part along
    the directions V_k whose singular value is below ``SMOOTH_TOL`` (those
    :func:`smoothest_multipliers` chooses) and the rest.  If the rest balances
    (≤ ``tol`` times ``scale``), the rows of B are nearly dependent and the reaction loads
    that combination: a :class:`NearlyDependentError` naming the rows, the
    measured σ_k/σ_max and the multiplier the balance would need,
    |V_kᵀ r|/σ_k.  Otherwise a RuntimeError: an unexpected failure.
    """
    cols = np.unique(B.indices)
    U, sv, Vt = sla.svd(B[:, cols].toarray(), full_matrices=False)
    small = sv < SMOOTH_TOL * sv[0]
    e = (B.T @ mu - r)[cols]
    rest = e - Vt[small].T @ (Vt[small] @ e)
    near = np.flatnonzero(small & (sv > 0))  # nearly, not exactly, dependent
    if near.size and np.linalg.norm(rest) <= tol * scale:
        need = np.abs(Vt[near] @ r[cols]) / sv[near]
        k = near[np.argmax(need)]
        rows = np.flatnonzero(np.abs(U[:, k]) > 0.1 * np.abs(U[:, k]).max())
        typical = np.median(np.abs(mu[mu != 0])) if np.any(mu != 0) else 0.0
        return NearlyDependentError(
            f"the multipliers are nearly dependent on this mesh: the rows {rows.tolist()} "
            f"of B have a singular value {sv[k] / sv[0]:.1e} of the largest (below "
            f"{SMOOTH_TOL:.0e}), and balancing the displacement needs a multiplier "
            f"{need.max():.1e} along them (typical multiplier {typical:.1e}); smooth "
            f"multipliers leave a relative imbalance {balance:.1e} > {tol:.0e}.  The "
            f"naive space does this where Γ passes very close to a node, and so does the "
            f"winner space on tetrahedra: use the vital space (space=\"vital\")")
    return RuntimeError(
        f"the multipliers do not balance the displacement (relative error "
        f"{balance:.1e} > {tol:.0e}): the interface tractions would be wrong; "
        f"please report this scene")


def floating(detail: str, system: str = "the saddle-point system",
             also: str = "") -> SingularSystemError:
    """The error of a singular system (the one message of every solve): ``detail``
    (what was measured) is kept as its attribute, for a caller that knows more of
    the cause; ``also``: another possible cause, said after the free motion.

    >>> str(floating("a zero pivot", "the tied system"))[:57]
    'the tied system is singular (a zero pivot): a part of the'
    """
    error = SingularSystemError(
        f"{system} is singular ({detail}): a part of the body can move freely.  Either "
        f"the displacements do not remove every rigid motion of the body, or a "
        f"frictionless (bilateral) tie lets the part on the other side of Γ slide; add "
        f"displacements (supports) on each side{also}")
    error.detail = detail
    return error


_floating = floating


def factorise(A: sp.spmatrix, pivot_tol: float = 1e-11, floating=_floating,
              symmetric: bool = False):
    """SuperLU of the (scaled) sparse matrix ``A``, refused as singular if SuperLU
    finds an exactly zero pivot or a pivot below ``pivot_tol`` times the largest.

    ``floating(detail)`` makes the error raised (default: a
    :class:`SingularSystemError` saying a part of the body can move freely);
    the contact Newton step gives its own.  ``symmetric``: A is symmetric positive
    definite (no multiplier), factorised in SuperLU's symmetric mode (minimum degree
    on A + Aᵀ, diagonal pivots): less fill (the 3D crack of
    ``benchmarks/crack_solve.py``, n = 12: 13.6 against 14.9 million entries, 1.15
    against 1.50 s, one run).

    >>> lu = factorise(sp.csc_matrix([[2.0, 1.0], [1.0, 0.0]]))
    >>> lu.solve(np.array([1.0, 1.0])).tolist()
    [1.0, -1.0]
    """
    try:
        lu = (spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                        options={"SymmetricMode": True}) if symmetric
              else spla.splu(sp.csc_matrix(A), permc_spec="COLAMD"))  # least fill here
    except RuntimeError as e:  # SuperLU: "Factor is exactly singular"
        raise floating(str(e)) from e
    pivots = np.abs(lu.U.diagonal())
    if pivots.min() < pivot_tol * pivots.max():
        raise floating(f"smallest LU pivot {pivots.min() / pivots.max():.1e} of the largest")
    return lu


@dataclass(frozen=True)
class Reduced:
    """Step 1 of :func:`solve`: the Jacobi-scaled system on the free unknowns and the
    independent rows of B, ``A`` [[K_f, B_kᵀ], [B_k, 0]] and its right-hand side.
    ``s`` the unknowns' scales, ``keep`` the rows of B kept and ``r`` their scales."""

    A: sp.csc_matrix
    rhs: np.ndarray
    s: np.ndarray
    keep: np.ndarray
    r: np.ndarray


def reduce(K, B, F, U, free) -> Reduced:
    """Step 1: symmetric diagonal (Jacobi) scaling — an enriched function whose
    support Γ barely cuts has a tiny stiffness; scaling restores the
    conditioning — and the independent rows of B (:func:`independent_rows`)."""
    diag = np.abs(K.diagonal()[free])
    if np.any(diag == 0):
        raise SingularSystemError(
            f"{int(np.sum(diag == 0))} unknown(s) have no stiffness at all (a node that "
            f"no cell uses, or an enriched function with an empty support): remove "
            f"unused nodes from the mesh or impose those unknowns")
    s = 1.0 / np.sqrt(diag)
    scaling = sp.diags(s)
    Kf = scaling @ K[free][:, free] @ scaling
    Bf = B[:, free] @ scaling
    keep = independent_rows(Bf)
    r = 1.0 / np.maximum(abs(Bf[keep]).max(axis=1).toarray().ravel(), 1e-300)
    Bk = sp.diags(r) @ Bf[keep]
    rhs = np.concatenate([s * (F - K @ U)[free], -r * (B @ U)[keep]])
    return Reduced(sp.bmat([[Kf, Bk.T], [Bk, None]], format="csc"), rhs, s, keep, r)


def refined_solve(lu, A, rhs, tol: float) -> tuple[np.ndarray, float]:
    """Steps 2: x = A⁻¹ rhs with three steps of iterative refinement (X-FEM
    slivers cost digits in the LU), and its relative residual, which must be
    below ``tol``."""
    x = lu.solve(rhs)
    for _ in range(3):
        x += lu.solve(rhs - A @ x)
    residual = np.linalg.norm(A @ x - rhs) / max(np.linalg.norm(rhs), 1e-300)
    if not np.all(np.isfinite(x)) or residual > tol:
        raise _floating(f"the solve leaves a relative residual {residual:.2e}")
    return x, float(residual)


def recover(Bf, reaction, mu, G, imbalance, tol: float) -> np.ndarray:
    """Step 3: the multipliers from U, the smoothest that balance it
    (:func:`smoothest_multipliers`), as the module notes say; without ``G``,
    those of the reduced solve ``mu``."""
    if G is None:
        return mu
    mu = smoothest_multipliers(Bf, reaction, G)
    if not imbalance(mu) <= tol:
        # singular values between FIXED_TOL and SMOOTH_TOL can be genuine and
        # loaded (the vital prism plate, 8.7e-7 at n = 24): let the equilibrium
        # fix them, smooth only below FIXED_TOL, if that adjusts the multipliers
        # (by < 10 %) rather than adding the spike of a near-dependence
        retry = smoothest_multipliers(Bf, reaction, G, FIXED_TOL)
        if np.linalg.norm(retry - mu) <= 0.1 * np.linalg.norm(mu):
            mu = retry
    return mu


def solve(K, B, F, D=None, g=None, G=None, tol: float = 1e-8, pivot_tol: float = 1e-11):
    """Solve the saddle-point system in the four steps of the module notes.

    Parameters
    ----------
    K, B, F
        Stiffness (N, N), coupling (m, N) and load (N,).
    D, g
        Imposed unknowns and their values (default: none).
    G
        Differences (p, m) between neighbouring multipliers, used to recover
        them from U; without it the multipliers of the reduced system are
        returned (zero for the removed ones).
    tol
        Largest accepted relative residual.
    pivot_tol
        Smallest accepted ratio of LU pivots (after Jacobi scaling): below it
        the system is declared singular.

    Returns
    -------
    U, mu, info
        Unknowns (N,), multipliers (m,), :class:`SaddleInfo`.

    Raises
    ------
    SingularSystemError
        If a free unknown has zero stiffness, the system is singular (SuperLU
        finds an exactly zero pivot, or a pivot below ``pivot_tol``), or the
        residual exceeds ``tol``.
    NearlyDependentError
        (a ValueError) If the multipliers do not balance U (Bᵀμ = K U - F
        within ``tol``) because rows of B are nearly dependent (step 4 of the
        module notes): the space is nearly singular on this mesh.
    RuntimeError
        If they do not balance U for any other reason: a numerical failure,
        never observed, checked so it cannot pass silently.
    """
    N, m = K.shape[0], B.shape[0]
    D = np.zeros(0, int) if D is None else np.asarray(D, int)
    g = np.zeros(D.size) if g is None else np.asarray(g, float)
    free = np.setdiff1d(np.arange(N), D)
    K, B = sp.csr_matrix(K), sp.csr_matrix(B)
    U = np.zeros(N)
    U[D] = g
    red = reduce(K, B, F, U, free)                               # 1. independent rows
    lu = factorise(red.A, pivot_tol, symmetric=red.keep.size == 0)
    x, residual = refined_solve(lu, red.A, red.rhs, tol)                          # 2.
    U[free] = red.s * x[:free.size]
    mu = np.zeros(m)
    mu[red.keep] = -red.r * x[free.size:]
    if m == 0:  # no multiplier (law free): nothing to balance, step 2's residual is all
        return U, mu, SaddleInfo(0, float(residual), 0.0)
    reaction = (K @ U - F)[free]
    scale = max(np.linalg.norm(reaction), np.linalg.norm(F[free]), 1e-300)

    def imbalance(mu):
        return np.linalg.norm(B[:, free].T @ mu - reaction) / scale

    mu = recover(B[:, free], reaction, mu, G, imbalance, tol)      # 3. the multipliers
    balance = imbalance(mu)                                        # 4. they balance U
    if not np.isfinite(balance) or balance > tol:
        raise _unbalanced(B[:, free], reaction, mu, balance, tol, scale)
    return U, mu, SaddleInfo(int(m - red.keep.size), float(residual), float(balance))
