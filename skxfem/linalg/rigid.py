r"""The rigid motions of each side of Γ that the supports and the interface law leave free.

A problem has no unique solution when a rigid motion R⁻ of Ω⁻ together with
a rigid motion R⁺ of Ω⁺ (not both zero) changes no imposed displacement and
nothing the interface law holds.  :func:`check_held` refuses such a problem
before it is solved, naming the side and the motion; every solve runs it:
the tie (:func:`skxfem.solver.solve`, direct and iterative) and each
converged contact state (:func:`skxfem.contact.check_determined`).

**The motions.** :func:`skxfem.linalg.amg.rigid_modes` gives, on the unknowns
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
motions.  The message names them (:func:`describe`): those of the whole
body, else of Ω⁻ alone, else of Ω⁺ alone, each as the translations it
allows and its rotations ("can translate along y", "can translate in every
direction normal to z and rotate about an axis along z through (0.5, 0.5,
0.5)", "can rotate about z (about the point (0.5, 0.5))").

**Regions.** The modes are those of each region the interfaces split the body
into (:func:`skxfem.linalg.amg.rigid_modes`; one interface: Ω⁻ and Ω⁺), each
interface holds the relative motion of the two regions beside it (its part of
the problem, :attr:`skxfem.problem.Problem.interfaces`, on its own columns of
the modes), and the message names a region by its signs, "the part of the
body where ψ₀ > 0 and ψ₁ < 0" (ψ_k the level set of ``interfaces[k]``; one
interface: Ω⁻ and Ω⁺, :func:`side_names`).

>>> from skxfem.problem import assemble
>>> from skxfem.scene.benchmarks import strip
>>> from dataclasses import replace
>>> p = assemble(replace(strip(3, "tri"), law="bilateral"))   # the top slides in x
>>> check_held(p, normal=True)
Traceback (most recent call last):
...
skxfem.linalg.saddle.SingularSystemError: Ω⁺ (the part of the body ...) can translate along x: ...
"""
from __future__ import annotations

import itertools
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from .amg import axis_name, motion_name, rigid_modes
from .dependent import unit_rows
from .saddle import SingularSystemError

if TYPE_CHECKING:  # the problem is read through its attributes: rigid stands below it
    from ..problem import Problem

__all__ = ["TOL", "frame", "law_rows", "free_motions", "side_names", "region_names",
           "describe", "check_held", "pieces", "short_pieces"]

TOL = 1e-8
"""A combination of the modes moved by less than this fraction of the most
held one is free."""


def frame(p: Problem) -> tuple[np.ndarray, float]:
    """The rotation centre and length of the modes: the mesh's bounding box
    centre and half diagonal (so rotations and translations have columns of
    comparable size wherever the mesh lies)."""
    lo, hi = p.mesh.p.min(axis=1), p.mesh.p.max(axis=1)
    return 0.5 * (lo + hi), max(0.5 * float(np.linalg.norm(hi - lo)), 1e-300)


def _normals(p) -> np.ndarray:
    """The level set's unit normals at the interface points of a part ``p``
    (:meth:`skxfem.gamma.Gamma.normals_at`); the facets' where its gradient is not
    finite or vanishes."""
    rule = p.rule
    try:
        n = p.gamma.normals_at(rule.points)
    except (ValueError, TypeError, FloatingPointError):
        return rule.normals
    return np.where(np.isfinite(n).all(axis=0), n, rule.normals)


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


def _edge_rows(p: Problem, Z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The weighted jumps (1/∫N_e) ∫ N_e w of the modes ``Z`` at every cut
    edge: their normal part (ne, 2k), and their components (dim, ne, 2k)."""
    rule = p.rule
    dim, nq = rule.normals.shape
    W = (rule.N.T @ sp.diags(rule.weights)).tocsr()
    W = (sp.diags(1.0 / np.maximum(np.asarray(W.sum(axis=1)).ravel(), 1e-300)) @ W).tocsr()
    jumps = (p.J @ Z).reshape(dim, nq, -1)
    normal = W @ np.einsum("cq,cqm->qm", _normals(p), jumps)
    return normal, np.stack([W @ jumps[c] for c in range(dim)])


def law_rows(p: Problem, Z: np.ndarray, normal=None, full=None, edge_rows=None) -> np.ndarray:
    """What the law holds, applied to the modes ``Z``: dense (r, 2k).

    ``normal``, ``full``: the cut edges whose normal jump, or whole jump, the
    law holds (``True``: all).  One row per held edge and part, (1/∫N_e)
    ∫ N_e w·n (or each component of w): the weighted jump of the mode, a
    displacement.  ``edge_rows``: :func:`_edge_rows` of ``Z``, if already made.
    """
    ne = p.cut.edge_ids.size
    normal, full = _edges(normal, ne), _edges(full, ne)
    if not (normal.any() or full.any()):
        return np.zeros((0, Z.shape[1]))
    n_rows, c_rows = edge_rows if edge_rows is not None else _edge_rows(p, Z)
    return np.vstack([n_rows[normal]] + [c[full] for c in c_rows])


def _null(A: np.ndarray, tol: float) -> np.ndarray:
    """Orthonormal basis (columns) of the c that A moves by less than ``tol``
    times its largest singular value (every c if A is zero)."""
    A = np.vstack([A, np.zeros((max(A.shape[1] - A.shape[0], 0), A.shape[1]))])
    _, sv, Vt = np.linalg.svd(A, full_matrices=False)     # Vt square: A has rows enough
    return Vt[sv <= tol * sv.max()].T


def free_motions(p: Problem, normal=None, full=None, rows=None, tol: float = TOL,
                 Z: np.ndarray | None = None) -> np.ndarray:
    """(2k, d): a basis of the coefficients c of the modes ``Z`` (default
    :func:`skxfem.linalg.amg.rigid_modes` in :func:`frame`) that no support and
    nothing the law holds moves, and that move the body (Z c ≠ 0); d = 0
    when every rigid motion is held.

    ``normal``, ``full`` as :func:`law_rows`; ``rows``: more (r, N) sparse
    rows on the unknowns that the law holds as they are (a sliding contact
    point in 3D holds the tangent across its slip).
    """
    if Z is None:
        centre, length = frame(p)
        Z = rigid_modes(p.V, centre=centre, length=length)
    # each interface holds what its law holds, on its columns of the modes
    blocks = [Z[p.D]] + [law_rows(q, Z[q.columns], n, f) for q, n, f in
                         zip(p.interfaces, _split(p, normal), _split(p, full))]
    if rows is not None and rows.shape[0]:
        blocks.append(unit_rows(rows)[0] @ Z)
    N = _null(np.vstack(blocks), tol)
    if N.shape[1] == 0:
        return N
    # a combination the space cannot represent (Z c = 0: a piece of Γ so small that
    # its nodes lost their enrichment, skxfem.enrich.xfem_space) is no motion at all
    _, sv, Vt = np.linalg.svd(Z @ N, full_matrices=False)
    return N @ Vt[sv > tol * np.linalg.norm(Z, axis=0).max()].T


def _split(p: Problem, mask) -> list:
    """A mask over the cut edges of every interface in turn (or True / None / False
    for all, or a list of one such per interface) as one per interface."""
    if mask is None or mask is True or mask is False:
        return [mask] * len(p.interfaces)
    if isinstance(mask, (list, tuple)) and len(mask) == len(p.interfaces):
        return list(mask)
    mask = np.asarray(mask, dtype=bool)
    ends = np.cumsum([q.cut.edge_ids.size for q in p.interfaces])
    if mask.shape != (ends[-1],):
        raise ValueError(f"the held edges must be one bool per cut edge of every interface "
                         f"({ends[-1]}), got shape {mask.shape}")
    return np.split(mask, ends[:-1])


_SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def region_names(p: Problem) -> list[str]:
    """How a message names each region of a problem (in the order of
    :meth:`skxfem.enrich.XSpaces.regions`): "the part of the body where ψ₀ > 0 and
    ψ₁ < 0", ψ_k the level set of ``interfaces[k]``; with one level set, Ω⁻ and Ω⁺
    by :func:`side_names` (the wording alone depends on the count).  Only the interfaces
    that split the body count: a crack (a front) splits no region."""
    patterns = p.V.regions()[0]
    split = [k for k, q in enumerate(p.interfaces) if q.V.splits]   # a crack splits none
    if len(split) == 1:
        return list(side_names(p.interfaces[split[0]]))
    return ["the part of the body where " + " and ".join(
        f"ψ{str(k).translate(_SUB)} {'<' if s < 0 else '>'} 0" for k, s in zip(split, row))
        for row in patterns.tolist()]


def side_names(p) -> tuple[str, str]:
    """How a message names Ω⁻ and Ω⁺ of one interface (``p`` a problem of one or a
    :class:`skxfem.problem.Part`): "the part of the body inside Γ" for a side on no
    boundary node (Γ encloses it; the other is then "outside Γ"), else by the sign
    of ψ."""
    boundary = np.unique(p.mesh.facets[:, p.mesh.boundary_facets()])
    signs = set(np.asarray(p.cut.node_side[boundary], float).tolist())
    names = []
    for sign, sym in ((-1.0, "⁻"), (1.0, "⁺")):
        where = ("inside Γ" if sign not in signs else "outside Γ" if len(signs) == 1
                 else f"where ψ {'<' if sign < 0 else '>'} 0")
        names.append(f"Ω{sym} (the part of the body {where})")
    return names[0], names[1]


def _orth(A: np.ndarray, tol: float = 1e-6) -> np.ndarray:
    """Orthonormal basis of the column space of ``A``."""
    if A.size == 0:
        return A
    U, sv, _ = np.linalg.svd(A, full_matrices=False)
    return U[:, sv > tol * max(sv.max(), 1e-300)]


def _side_motions(motions: np.ndarray, dim: int, centre, length: float) -> str:
    """The ``motions`` (k, d) of one side, in words: the translations they
    allow (a direction, a plane, every direction) and each rotation, about
    an axis through the point it leaves at rest (:func:`skxfem.linalg.amg.motion_name`)."""
    T, W = motions[:dim], motions[dim:]
    Y = _null(W, 1e-6) if W.any() else np.eye(motions.shape[1])  # combinations that only translate
    moves = _orth(T @ Y)
    words = []
    if moves.shape[1] == dim:
        words.append("translate in every direction")
    elif moves.shape[1] == 2:
        words.append(f"translate in every direction normal to "
                     f"{axis_name(np.cross(moves[:, 0], moves[:, 1]))}")
    elif moves.shape[1] == 1:
        words.append(motion_name(np.r_[moves[:, 0], np.zeros(motions.shape[0] - dim)], dim))
    rest = _null(Y.T, 1e-6) if Y.shape[1] else np.eye(motions.shape[1])  # the rest: rotations
    for y in (motions @ rest).T:
        t = y[:dim] - moves @ (moves.T @ y[:dim])               # no free translation in it
        words.append(motion_name(np.r_[t, y[dim:]], dim, centre, length))
    return " and ".join(words)


def describe(p: Problem, N: np.ndarray, centre, length: float) -> str:
    """The free motions of the basis ``N`` (orthonormal columns of mode
    coefficients, R regions, the motion i of region r at column R i + r, as
    :func:`skxfem.linalg.amg.rigid_modes` orders them), in words: those of the whole
    body, else of the fewest regions that move as one body (one interface: Ω⁻
    alone, else Ω⁺ alone), each as its translations and rotations, else of each
    region that moves."""
    names = region_names(p)
    R, dim, I = len(names), p.mesh.dim(), np.eye(N.shape[0])
    groups = [tuple(range(R))] + [g for size in range(1, R) for g in
                                  itertools.combinations(range(R), size)]
    for group in groups:
        E = np.vstack([I[group[0]::R] - I[r::R] for r in group[1:]]
                      + [I[r::R] for r in range(R) if r not in group] or [I[:0]])
        _, sv, Vt = np.linalg.svd(E @ N, full_matrices=True)
        motions = N @ Vt[np.r_[sv, np.zeros(Vt.shape[0] - sv.size)] < 1e-6].T
        if motions.shape[1]:
            who = ("the whole body" if len(group) == R else names[group[0]] if
                   len(group) == 1 else "the parts of the body where " + " and where ".join(
                       names[r].removeprefix("the part of the body where ") for r in group)
                   + ", together,")
            return f"{who} can {_side_motions(motions[group[0]::R], dim, centre, length)}"
    c = N[:, 0]
    moving = [r for r in range(R) if np.abs(c[r::R]).max() > 1e-6 * np.abs(c).max()]
    return " as ".join(f"{names[r]} {motion_name(c[r::R], dim, centre, length, verb=False)}"
                       if i else f"{names[r]} can {motion_name(c[r::R], dim, centre, length)}"
                       for i, r in enumerate(moving))


def check_held(p: Problem, normal=None, full=None, rows=None, what: str | None = None,
               hint: str | None = None, tol: float = TOL) -> None:
    """Refuse ``p`` if the supports and what the law holds leave a rigid motion free.

    ``normal``, ``full``, ``rows`` as :func:`free_motions` (a tie: ``full=True``
    bonded, ``normal=True`` bilateral); ``what`` names the law in the message
    (default: the problem's tie) and ``hint`` the remedy.

    Raises
    ------
    skxfem.linalg.saddle.SingularSystemError
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
                f"hold that {'part' if len(p.interfaces) > 1 else 'side'} with a displacement "
                f"(support), or tie it with a law that holds the tangential jump too "
                f"(bonded)")
    if what is None:                         # a free crack's faces hold nothing: no tie
        laws = [law for law in p.laws if law != "free"]
        what = (None if not laws else f"the {laws[0]} tie" if len(laws) == 1 else
                f"the interfaces' ties ({', '.join(laws)})")
    held = ("the displacements do not hold it" if what is None else
            f"neither the displacements nor {what} hold it")
    raise SingularSystemError(
        f"{text}: {held}, so "
        f"the problem is singular (a part of the body can move freely, its displacement "
        f"is not unique); {hint}")


def pieces(cut) -> np.ndarray:
    """(ne,) the connected piece of Γ_h of each cut edge (edges that share a
    cut cell are in one piece), numbered from 0.

    >>> from skfem import MeshTri1
    >>> from skxfem.cut import cut
    >>> from skxfem.levelset import plane
    >>> int(pieces(cut(MeshTri1().refined(2), plane((0.5, 0.4), (0.0, 1.0)))).max())  # one
    0
    """
    ne = cut.edge_ids.size
    cells = np.tile(cut.facet_cell, cut.facets.shape[0])
    ends = cut.facets.ravel()
    ok = ends >= 0                                   # -1: no cut point (a crack's tip)
    in_cell = sp.csr_matrix((np.ones(ok.sum()), (ends[ok], cells[ok])),
                            shape=(ne, int(cells.max()) + 1 if cells.size else 0))
    return connected_components(in_cell @ in_cell.T, directed=False)[1]


def _rank(A: np.ndarray, tol: float = TOL) -> int:
    if A.size == 0:
        return 0
    sv = np.linalg.svd(A, compute_uv=False)
    return int(np.sum(sv > tol * sv.max())) if sv.max() > 0 else 0


def short_pieces(p: Problem, B_edges, tol: float = TOL) -> np.ndarray:
    """(ne,) bool: the cut edges of the pieces of Γ_h whose multipliers hold
    fewer relative rigid motions of the two sides than the law does there.

    On each piece, the law (``p.law``: the whole jump bonded, its normal part
    bilateral) holds the relative motions w with w = 0 (w·n = 0) at its
    points; the space holds those whose weighted jumps ∫ψ_j w, one per
    multiplier μ_j of the piece (``B_edges`` reduced by ``p.P``), vanish.
    Each taken with the supports (what they hold needs no multiplier), the
    two must hold as many rigid motions.  A stable space gives a small piece
    too few multipliers: a corner of one cell that Γ cuts off (``x + y =
    1.95`` on the unit square) gets one star of vital edges, one μ per
    component, whose mean jump cannot hold the piece's turning, and the tied
    system was singular.  Such a piece needs a multiplier per edge
    (:func:`skxfem.stabilised.multiplier_space`'s ``per_edge``).
    """
    ne = p.cut.edge_ids.size
    label = pieces(p.cut)
    centre, length = frame(p)
    Z = rigid_modes(p.V, centre=centre, length=length)
    edge_rows = _edge_rows(p, Z)
    ncomp = B_edges.shape[0] // ne
    bonded = p.law == "bonded"
    P = sp.csr_matrix(p.P)
    weight = np.asarray(p.rule.N.T @ p.rule.weights).ravel()   # ∫ N_e
    supports = np.linalg.qr(Z[p.D], mode="r")                 # the same rank with any rows
    short = np.zeros(ne, dtype=bool)
    for k in range(label.max() + 1 if ne else 0):
        edges = label == k
        law = law_rows(p, Z, normal=None if bonded else edges, full=edges if bonded else None,
                       edge_rows=edge_rows)
        rows = np.flatnonzero(np.tile(edges, ncomp))
        Pk = P[rows]
        used = np.flatnonzero(np.asarray(abs(Pk).sum(axis=0)).ravel() > 0)
        w = Pk[:, used].T @ np.tile(weight, ncomp)[rows]
        restrained = (sp.diags(1.0 / w) @ (Pk[:, used].T @ B_edges[rows])) @ Z
        if _rank(np.vstack([supports, restrained]), tol) < _rank(np.vstack([supports, law]), tol):
            short |= edges
    return short
