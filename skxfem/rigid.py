r"""The rigid motions of each side of Γ that the supports and the interface law leave free.

A problem has no unique solution when a rigid motion R⁻ of Ω⁻ together with
a rigid motion R⁺ of Ω⁺ (not both zero) changes no imposed displacement and
nothing the interface law holds.  :func:`check_held` refuses such a problem
before it is solved, naming the side and the motion; every solve runs it:
the tie (:func:`skxfem.solver.solve`, direct and iterative) and each
converged contact state (:func:`skxfem.contact.check_determined`).

**The motions.** :func:`skxfem.amg.rigid_modes` gives, on the unknowns
[a, b], each rigid motion of Ω⁻ with Ω⁺ at rest and of Ω⁺ with Ω⁻ at rest,
2k columns Z (k = 3 in 2D, 6 in 3D); a combination Z c is free when

1. it moves no imposed unknown: Z[D] c = 0 (supports hold standard and, on
   the cut facets they cover, enriched dofs: :func:`skxfem.problem.constrained_dofs`);
2. it moves nothing the law holds on Γ.  The jump of a mode is the relative
   motion w = R⁻ - R⁺ (exact at every point: the cells reproduce rigid
   motions), so, at the interface quadrature points, w = 0 where the whole
   jump is held (``bonded``, a closed point that sticks) and w·n = 0 where
   only its normal part is (``bilateral``, a closed contact point), each
   edge's rows weighted by its multiplier function N_e as the coupling is.

The normal n is the level set's, ∇ψ/|∇ψ| (:meth:`skxfem.levelset.LevelSet.gradient`),
not the polygon Γ_h's: the question is about the body, not its mesh.  A
normal-only tie on a circle leaves the disc free to turn about its centre
(w·n = 0 on the circle), but Γ_h's facet normals are off the radius by
O(h), so the discrete system is not singular: it is held by the
discretisation error alone, and a solve returned the disc turned by an
arbitrary amount (``examples/inclusion.toml`` with ``law = "bilateral"``:
max jump 1.05 and |u| 5.19, bonded 2.8e-4 and 0.098).

The modes turn about the centre of the mesh's bounding box and are scaled
by its half diagonal (:func:`frame`), so every column moves the body by
about 1; the right singular vectors of the stacked matrix [Z[D]; law rows]
whose singular value is below ``tol`` times the largest span the free
motions.  The message names one of them, looked for in this order: a
motion of the whole body, of Ω⁻ alone, of Ω⁺ alone, of the two sides
apart (:func:`skxfem.amg.motion_name` says "can rotate about z (about the
point ...)", "can translate along y").

>>> from skxfem.problem import assemble
>>> from skxfem.scenes import strip
>>> from dataclasses import replace
>>> p = assemble(replace(strip(3, "tri"), law="bilateral"))   # the top slides in x
>>> check_held(p, normal=True)
Traceback (most recent call last):
...
skxfem.saddle.SingularSystemError: Ω⁺ (the part of the body where ψ > 0) can translate along x: ...
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .amg import motion_name, rigid_modes
from .problem import Problem
from .saddle import SingularSystemError

__all__ = ["TOL", "frame", "law_rows", "free_motions", "side_names", "describe", "check_held"]

TOL = 1e-8
"""A combination of the modes moved by less than this fraction of the most
held one is free."""


def frame(p: Problem) -> tuple[np.ndarray, float]:
    """The rotation centre and length of the modes: the mesh's bounding box
    centre and half diagonal (so rotations and translations have columns of
    comparable size wherever the mesh lies)."""
    lo, hi = p.mesh.p.min(axis=1), p.mesh.p.max(axis=1)
    return 0.5 * (lo + hi), max(0.5 * float(np.linalg.norm(hi - lo)), 1e-300)


def _normals(p: Problem) -> np.ndarray:
    """The level set's unit normals at the interface points; the facets' where
    its gradient is not finite or vanishes."""
    rule = p.rule
    try:
        n = np.asarray(p.scene.levelset.gradient(rule.points), float)
    except (ValueError, TypeError, FloatingPointError):
        return rule.normals
    size = np.linalg.norm(n, axis=0)
    ok = np.isfinite(size) & (size > 0)
    return np.where(ok, n / np.where(ok, size, 1.0), rule.normals)


def _edges(mask, ne: int) -> np.ndarray:
    """An (ne,) bool mask from ``True`` (every edge), ``None``/``False`` (none) or a mask."""
    if mask is None or mask is False:
        return np.zeros(ne, dtype=bool)
    if mask is True:
        return np.ones(ne, dtype=bool)
    mask = np.asarray(mask, dtype=bool)
    if mask.shape != (ne,):
        raise ValueError(f"the held edges must be one bool per cut edge ({ne}), "
                         f"got shape {mask.shape}")
    return mask


def law_rows(p: Problem, Z: np.ndarray, normal=None, full=None) -> np.ndarray:
    """What the law holds, applied to the modes ``Z``: dense (r, 2k).

    ``normal``, ``full``: the cut edges whose normal jump, or whole jump, the
    law holds (``True``: all).  One row per held edge and part, (1/∫N_e)
    ∫ N_e w·n (or each component of w): the weighted jump of the mode, a
    displacement.
    """
    ne, rule = p.cut.edge_ids.size, p.rule
    normal, full = _edges(normal, ne), _edges(full, ne)
    dim, nq = rule.normals.shape
    W = (rule.N.T @ sp.diags(rule.weights)).tocsr()
    W = (sp.diags(1.0 / np.maximum(np.asarray(W.sum(axis=1)).ravel(), 1e-300)) @ W).tocsr()
    jumps = (p.J @ Z).reshape(dim, nq, -1)
    rows = [np.zeros((0, Z.shape[1]))]
    if normal.any():
        rows.append(W[normal] @ np.einsum("cq,cqm->qm", _normals(p), jumps))
    rows += [W[full] @ jumps[c] for c in range(dim) if full.any()]
    return np.vstack(rows)


def _null(A: np.ndarray, tol: float) -> np.ndarray:
    """Orthonormal basis (columns) of the c that A moves by less than ``tol``
    times its largest singular value (every c if A is zero)."""
    A = np.vstack([A, np.zeros((max(A.shape[1] - A.shape[0], 0), A.shape[1]))])
    _, sv, Vt = np.linalg.svd(A, full_matrices=False)     # Vt square: A has rows enough
    return Vt[sv <= tol * sv.max()].T


def free_motions(p: Problem, normal=None, full=None, rows=None, tol: float = TOL,
                 Z: np.ndarray | None = None) -> np.ndarray:
    """(2k, d): a basis of the coefficients c of the modes ``Z`` (default
    :func:`skxfem.amg.rigid_modes` in :func:`frame`) that no support and
    nothing the law holds moves; d = 0 when every rigid motion is held.

    ``normal``, ``full`` as :func:`law_rows`; ``rows``: more (r, N) sparse
    rows on the unknowns that the law holds as they are (a sliding contact
    point in 3D holds the tangent across its slip).
    """
    if Z is None:
        centre, length = frame(p)
        Z = rigid_modes(p.V, centre=centre, length=length)
    blocks = [Z[p.D], law_rows(p, Z, normal, full)]
    if rows is not None and rows.shape[0]:
        R = sp.csr_matrix(rows)
        norms = np.sqrt(np.asarray(R.multiply(R).sum(axis=1)).ravel())
        blocks.append(sp.diags(1.0 / np.where(norms > 0, norms, 1.0)) @ R @ Z)
    return _null(np.vstack(blocks), tol)


def side_names(p: Problem) -> tuple[str, str]:
    """How a message names Ω⁻ and Ω⁺: "the part of the body inside Γ" for a
    side that no boundary node lies on (Γ encloses it), else by the sign of ψ."""
    psi = p.cut.psi
    boundary = np.unique(p.mesh.facets[:, p.mesh.boundary_facets()])
    names = []
    for sign, sym, other in ((-1, "⁻", "+"), (1, "⁺", "-")):
        on_boundary = np.any(np.sign(psi[boundary]) == sign)
        enclosed_other = not np.any(np.sign(psi[boundary]) == -sign)
        where = ("inside Γ" if not on_boundary else
                 "outside Γ" if enclosed_other else f"where ψ {'<' if sign < 0 else '>'} 0")
        names.append(f"Ω{sym} (the part of the body {where})")
    return names[0], names[1]


def describe(p: Problem, N: np.ndarray, centre, length: float) -> str:
    """The free motions of the basis ``N`` (orthonormal columns of mode
    coefficients, Ω⁻ and Ω⁺ interleaved as :func:`skxfem.amg.rigid_modes`
    orders them), in words: those of the whole body, else of Ω⁻ alone, else
    of Ω⁺ alone, each translation and rotation (about the frame's centre)
    among them by name, or else one combination."""
    minus, plus = side_names(p)
    dim, I = p.mesh.dim(), np.eye(N.shape[0])
    k = N.shape[0] // 2
    looks = [("the whole body", I[0::2] - I[1::2], I[0::2] + I[1::2], 0),   # c⁻ = c⁺
             (minus, I[1::2], I[0::2], 0),                                  # c⁺ = 0
             (plus, I[0::2], I[1::2], 1)]                                   # c⁻ = 0
    for who, E, pure, side in looks:
        _, sv, Vt = np.linalg.svd(E @ N, full_matrices=True)
        S = N @ Vt[np.r_[sv, np.zeros(Vt.shape[0] - sv.size)] < 1e-6].T   # orthonormal
        if S.shape[1] == 0:
            continue
        named = [motion_name(np.eye(k)[j], dim, centre, length) for j in range(k)
                 if np.linalg.norm(pure[j] - S @ (S.T @ pure[j])) < 1e-6 * np.linalg.norm(pure[j])]
        if named:
            return f"{who} can {', '.join(named[:-1]) + ' and ' if len(named) > 1 else ''}" \
                   f"{named[-1]}"
        return f"{who} can {motion_name(S[side::2, 0], dim, centre, length)}"
    c = N[:, 0]
    return (f"{minus} can {motion_name(c[0::2], dim, centre, length)} as {plus} "
            f"{motion_name(c[1::2], dim, centre, length, verb=False)}")


def check_held(p: Problem, normal=None, full=None, rows=None, what: str | None = None,
               hint: str | None = None, tol: float = TOL) -> None:
    """Refuse ``p`` if the supports and what the law holds leave a rigid motion free.

    ``normal``, ``full``, ``rows`` as :func:`free_motions` (a tie: ``full=True``
    bonded, ``normal=True`` bilateral); ``what`` names the law in the message
    (default: the problem's tie) and ``hint`` the remedy.

    Raises
    ------
    skxfem.saddle.SingularSystemError
        (a ValueError) naming the side and the motion left free.
    """
    centre, length = frame(p)
    Z = rigid_modes(p.V, centre=centre, length=length)
    N = free_motions(p, normal, full, rows, tol, Z)
    if N.shape[1] == 0:
        return
    text = describe(p, N, centre, length)
    if hint is None:
        hint = ("add a displacement (support) that holds it" if "whole body" in text else
                "hold that side with a displacement (support), or tie it with a law that "
                "holds the tangential jump too (bonded)")
    raise SingularSystemError(
        f"{text}: neither the displacements nor {what or f'the {p.law} tie'} hold it, so "
        f"the problem is singular (a part of the body can move freely, its displacement "
        f"is not unique); {hint}")
