r"""Solve a scene: the tied interface problem as a saddle point (paper §3 with a tie law).

With K the X-FEM stiffness, F the load and B the coupling of the multiplier
space (``λ = P μ``), the discrete problem a(u, v) - ∫_Γ r·[[v]] = l(v),
∫_Γ λ*·[[u]] = 0 reads

.. math:: \begin{bmatrix} K & B^T \\ B & 0 \end{bmatrix}
          \begin{bmatrix} U \\ -\mu \end{bmatrix} =
          \begin{bmatrix} F \\ 0 \end{bmatrix},

where μ holds the interface traction r = σ(u⁻)·n (``bonded``: the vector r;
``bilateral``: its normal part λ, r = λn).  The contact pressure is -r·n.

A singular system is never returned silently.  Dependent multipliers (rows of
B that are combinations of others, e.g. the naive space on tetrahedra, where a
quadrilateral cut carries four multipliers for a three-parameter linear jump)
are found by a rank-revealing QR of B and, by default, removed from the space
(``dependent="remove"``) — the displacement is then unique and the edge
tractions reported are the smoothest ones that balance it (see
:func:`skxfem.linalg.saddle.smoothest_multipliers`); with
``dependent="raise"`` a ValueError says how many there are.  After the solve the residual
is checked.
"""
from __future__ import annotations

import time

import numpy as np
import scipy.sparse as sp

from .contact import history as contact
from .contact.laws import CONTACT_LAWS
from .linalg import iterative, saddle
from .linalg.amg import rigid_modes
from .linalg.blocks import congruence, enriched_scaling
from .linalg.choice import AUTO_ITERATIVE, LINEAR, choose_linear
from .linalg.dependent import dependencies
from .linalg.rigid import check_held
from .linalg.threads import limited
from .problem import Problem, assemble, constrained_dofs
from .result import Result, result
from .scene.laws import in_words
from .scene.model import Resolved, Scene, resolve

__all__ = ["Result", "solve", "solve_problem", "constrained_dofs", "LINEAR", "AUTO_ITERATIVE",
           "choose_linear"]


def _differences(cut, ncomp: int) -> sp.csr_matrix:
    """G: λ_i - λ_j over the sides (i, j) of the interface facets, per component (a
    side with an end -1, no cut point, has none)."""
    nv = cut.facets.shape[0]
    pairs = np.hstack([cut.facets[[i, (i + 1) % nv]] for i in range(nv if nv > 2 else 1)])
    pairs = np.unique(np.sort(pairs, axis=0), axis=1)
    pairs = pairs[:, (pairs >= 0).all(axis=0)]  # an end that is no cut point (a crack's tip)
    k = pairs.shape[1]
    G = sp.csr_matrix((np.r_[np.ones(k), -np.ones(k)],
                       (np.r_[np.arange(k), np.arange(k)], np.r_[pairs[0], pairs[1]])),
                      shape=(k, cut.points.shape[1]))
    return sp.kron(sp.identity(ncomp), G, format="csr")


@limited
def solve(scene: Scene | Resolved, dependent: str = "remove", linear: str | None = None,
          linear_tol: float | None = None, max_iter: int | None = None,
          progress=None) -> Result:
    """Solve ``scene`` and return a :class:`~skxfem.result.Result`.

    A scene with a contact law (``frictionless``, ``coulomb``, ``adhesive``)
    is handed to :func:`skxfem.contact.solve` with its load steps: one call
    solves any scene, and returns the same kind of result.  The scene's
    settings (``scene.solver``, a scene file's ``[solver]`` table) choose the
    solve; the keywords ``linear``, ``linear_tol`` and ``max_iter`` given (not
    None) override them, as the options of ``skxfem run`` override the file,
    so that ``solve(load_scene(path))`` is the solve of ``skxfem run path``.

    Parameters
    ----------
    scene
        A :class:`skxfem.scene.Scene` (its ``quadrature_order`` sets the
        cell rule of the stiffness; ``None``: exact on affine cells).
    dependent
        ``"remove"`` (default) drops linearly dependent multipliers,
        ``"raise"`` refuses a rank-deficient coupling with a ValueError.
    linear
        The linear solve of the tie (or of each contact Newton step), one of
        :data:`LINEAR`: ``"direct"``, ``"iterative"`` (AMG + projected CG,
        pyamg), or ``"auto"``: the iterative one from :data:`AUTO_ITERATIVE`
        unknowns if pyamg is there (the direct one for a crack in 2D or with
        multipliers on its faces: :func:`skxfem.linalg.choice.choose_linear`),
        and the direct one after it where CG stalls (``"iterative"`` asked for
        then fails, naming the cure).
        ``None``: ``scene.solver.linear`` (default ``"auto"``).
    linear_tol
        The relative residual of the iterative solve, recorded in
        ``linear_info``; ``None``: ``scene.solver.linear_tol`` (default
        :data:`skxfem.linalg.choice.LINEAR_TOL`).
    max_iter
        Contact laws: the Newton iterations of a load step; ``None``:
        ``scene.solver.max_iter``, else
        :data:`skxfem.scene.settings.MAX_ITER` (30).  A scene without a
        contact law takes none.
    progress
        Contact laws: ``None`` (silent) or a callable given one line of text per
        Newton iteration and per load step (:func:`skxfem.contact.solve`), e.g.
        ``print``.

    The BLAS libraries run one thread during the solve (:mod:`skxfem.linalg.threads`:
    ``SKXFEM_THREADS`` or :func:`skxfem.linalg.threads.using` choose another number).

    Raises
    ------
    ValueError
        A scene that does not fit its mesh, a level set that cuts no cell
        or passes through nodes (from :func:`skxfem.cut.cut`), a rank
        deficient space with ``dependent="raise"``, a bad ``linear``,
        ``linear_tol`` or ``max_iter`` (or ``max_iter`` for a tie).
    skxfem.linalg.saddle.SingularSystemError
        (a ValueError) The supports and the law leave a rigid motion of a side
        free (:func:`skxfem.linalg.rigid.check_held`, which names it), or the
        system is singular for another reason.
    skxfem.contact.ContactConvergenceError
        A contact load step that does not converge, even cut.
    """
    if dependent not in ("remove", "raise"):
        raise ValueError(f"dependent must be 'remove' or 'raise', got {dependent!r}")
    scene = resolve(scene)   # checked and its mesh resolved, once
    settings = scene.scene.solver.override(linear, linear_tol, max_iter)
    laws = [i.law for i in scene.scene.interfaces]
    if any(law in CONTACT_LAWS for law in laws):
        return contact.solve(scene, linear=settings.linear, linear_tol=settings.linear_tol,
                             max_iter=settings.max_iter, progress=progress)
    if settings.max_iter is not None:
        raise ValueError(f"max_iter applies to the contact laws {CONTACT_LAWS} (Newton "
                         f"iterations per load step); the scene's law is "
                         f"{in_words(laws)}: leave max_iter unset")
    if scene.scene.steps != (1.0,):   # a tie's state is the loads', whatever the path
        steps = [f if isinstance(f, float) else f.name for f in scene.scene.steps]
        raise ValueError(f"steps (here {steps!r:.100}) are the load path of a contact solve "
                         f"(laws {CONTACT_LAWS}); the scene's law is {in_words(laws)}, "
                         f"solved once under its loads and imposed displacements (the steps "
                         f"would be ignored): leave steps out, or scale the loads")
    return solve_problem(assemble(scene), dependent, settings.linear, settings.linear_tol)


ZONE_ITERATIONS = 200
"""CG iterations that ``auto`` gives a 3D crack whose enriched zone holds more than
:data:`skxfem.linalg.choice.AUTO_ZONE` of the nodes (a coarse mesh) before it solves
directly: CG stalls there on a body held by few supports (500 iterations did not
reach 1e-12 at 91 % enriched), but a body clamped on a face converges: the edge crack of
``benchmarks/crack_solve.py`` at n = 8 (8 × 8 × 9 cells, 9 990 unknowns, 85 % of the
nodes enriched) in 79 iterations, the solve stage 0.57 s against the direct 2.85 s
(K_I at mid-front the same, 3.66886), the whole crack 1.56 s against 3.97 s.  A stalled
CG costs its 200 iterations before the direct solve (about 1 s at 7 000 unknowns)."""


def _iterative(p: Problem, cracks, G, tol: float, maxiter: int = 500):
    """(U, μ, info) of the projected CG of :mod:`skxfem.linalg.iterative` on ``p``, the
    motions of every region for the AMG, a crack's enriched blocks scaled."""
    V, B, D, mesh = p.V, p.B, p.D, p.mesh
    K, F, Bs, modes, S = p.K, p.F, B, rigid_modes(V), None
    if any(cracks):  # a crack, whatever its law: its nodes' blocks scaled
        S, Sinv = enriched_scaling(K, V.enr_dofs, V.n_std, mesh.dim(), D)
        K, F, Bs, modes = congruence(K, S, mesh.dim()), S.T @ F, B @ S, Sinv @ modes
    U, mu, info = iterative.solve(K, Bs, F, D, p.g, G=G, modes=modes, blocksize=mesh.dim(),
                                  bonded=p.law == "bonded", tol=tol, maxiter=maxiter)
    return (U if S is None else S @ U), mu, info


def _direct(p: Problem, cracks, G):
    """(U, μ, info) of the direct solve (:func:`skxfem.linalg.saddle.solve`) of ``p``, a
    crack's enriched blocks scaled as for CG (:func:`_iterative`, Béchet et al. 2005).

    Far from a tip a branch node's four functions differ from combinations of one
    another by terms of order (h/r)² and beyond, the more where ∇φ_h and ∇ψ_h are nearly
    parallel (the polar coordinates of (φ_h, ψ_h) degenerate): a ring of radius 0.15 in
    the unit square cut into two arcs by φ = |y - 0.5| - 0.1 (four tips, h = 1/41, the
    default r_e = 0.28 reaching above and below the ring, where ∇ψ is vertical like ∇φ)
    has nodes whose 8 × 8 Jacobi-scaled branch block has its least eigenvalue 1.4e-12
    (a straight crack's worst at that r_e: 6e-8), and the Jacobi-scaled LU refused the
    system as singular (pivot 9.6e-12).  Likewise two arcs of R = 3 in a 20 × 20 plate,
    φ = |x - 10| - 2, h = 1/3: r_e = 5.7 enriches 51 % of the nodes, least block eigenvalue
    3.3e-13 at nodes 5.5 from the tips on the ring's horizontal axis, where the sine of
    the angle between ∇φ and ∇ψ is 0.09 to 0.18 (1.3e-8 with r_e = 2, which solved).  The
    span is sound: scaled by each node's block (the unknowns of one node orthonormal in
    energy), the same system solves, K as CG's and as with r_e = 0.2 (within 4e-4).  A
    node whose own block is singular to working precision (two cracks on one circle
    whose fronts nearly coincide where both zones reach, the ring's two arcs at h = 1/12)
    is refused as a singular system, as the unscaled LU did (pivot 5.9e-20 there)."""
    if not any(cracks):
        return saddle.solve(p.K, p.B, p.F, p.D, p.g, G=G)
    try:
        S, _ = enriched_scaling(p.K, p.V.enr_dofs, p.V.n_std, p.mesh.dim(), p.D)
    except ValueError as e:           # a node's own functions dependent: singular as well
        error = saddle.SingularSystemError(str(e))
        error.detail = "an enriched node's block is not positive definite"
        raise error from e
    U, mu, info = saddle.solve(congruence(p.K, S, p.mesh.dim()), p.B @ S, S.T @ p.F, p.D,
                               p.g, G=G)
    return S @ U, mu, info


@limited
def solve_problem(p: Problem, dependent: str = "remove", linear: str | None = None,
                  linear_tol: float | None = None) -> Result:
    """Solve an assembled :class:`skxfem.problem.Problem` (its law): see :func:`solve`
    (``None``: the settings of the problem's scene, ``p.scene.solver``)."""
    if dependent not in ("remove", "raise"):
        raise ValueError(f"dependent must be 'remove' or 'raise', got {dependent!r}")
    settings = p.scene.solver.override(linear, linear_tol)
    cracks = [not q.V.splits for q in p.interfaces]
    zone = max((q.V.space.branch.size / p.mesh.p.shape[1]
                for c, q in zip(cracks, p.interfaces) if c), default=0.0)
    on_faces = any(c and q.P.shape[1] for c, q in zip(cracks, p.interfaces))
    linear = choose_linear(settings.linear, p.mesh.dim(), p.V.N, on_faces, any(cracks), zone)
    # a zone over AUTO_ZONE of the nodes: CG first, but few iterations (ZONE_ITERATIONS)
    try_cg = linear == "direct" and choose_linear(
        settings.linear, p.mesh.dim(), p.V.N, on_faces, any(cracks)) == "iterative"
    linear_tol = settings.linear_tol
    mesh, V, B, D = p.mesh, p.V, p.B, p.D
    t0 = time.perf_counter()
    if dependent == "raise":
        Bf = B[:, np.setdiff1d(np.arange(V.N), D)]
        removed = (dependencies(Bf).shape[1] if linear == "iterative"
                   else B.shape[0] - saddle.independent_rows(Bf).size)
        if removed:
            spaces = ", ".join(repr(q.space) for q in p.interfaces)
            laws = ", ".join(repr(q.law) for q in p.interfaces)
            raise ValueError(
                f"the multiplier space is rank deficient: {removed} of {B.shape[0]} "
                f"multipliers depend on the others (space {spaces}, law "
                f"{laws}); use a stabilised space or dependent='remove'")
    check_held(p, normal=[q.law == "bilateral" for q in p.interfaces],
               full=[q.law == "bonded" for q in p.interfaces])
    G = sp.block_diag([_differences(q.cut, q.ncomp) @ q.P for q in p.interfaces],
                      format="csr")
    if linear == "iterative" or try_cg:
        try:
            U, mu, info = _iterative(p, cracks, G, linear_tol,
                                     **({"maxiter": ZONE_ITERATIONS} if try_cg else {}))
            linear = "iterative"
        except (iterative.ConvergenceError, saddle.SingularSystemError):
            if not (try_cg or settings.linear == "auto"):
                raise                     # asked for 'iterative': its failure said
            linear = "direct"             # auto: CG stalled, the direct solve decides
    if linear == "direct":                                # chosen, or CG stalled first
        try:
            U, mu, info = _direct(p, cracks, G)
        except saddle.SingularSystemError as e:
            if not e.detail:
                raise
            ties = [law for law in dict.fromkeys(p.laws) if law != "free"]
            held = f"the displacements and the {'/'.join(ties)} tie hold every rigid " \
                "motion of each side of Γ" if ties else \
                "the displacements hold every rigid motion of the body"
            branch = (f"; or, a crack's branch functions enriching {zone:.0%} of the "
                      f"nodes (nearly dependent over a zone many cells across), give it a "
                      f"smaller enrichment_radius or enrichment = 'topological'"
                      if any(cracks) else "")
            raise saddle.SingularSystemError(  # check_held found every rigid motion held
                f"the {'tied ' if ties else ''}system is singular to working precision "
                f"({e.detail}), although {held}: its conditioning is beyond double "
                f"precision (a part of the body, or a material, far stiffer or smaller "
                f"than the rest); refine the mesh there or rescale the scene{branch}") from e
    seconds = time.perf_counter() - t0
    its = getattr(info, "iterations", None)
    linear_info = {"residual": float(info.residual), "balance": float(info.balance),
                   "backward_error": getattr(info, "backward_error", None),
                   "tol": linear_tol, "iterations": its, "residuals": None if its is None
                   else [float(r) for r in info.residuals]}
    tractions, jumps = [], []
    ends = np.cumsum([0] + [q.P.shape[1] for q in p.interfaces])
    for q, start, end in zip(p.interfaces, ends[:-1], ends[1:]):  # each interface
        lam = (q.P @ mu[start:end]).reshape(q.ncomp, -1)
        normals = q.normals()
        tractions.append(lam if q.ncomp > 1 else lam * normals)
        J = (q.J @ U[q.columns]).reshape(mesh.dim(), -1)
        jn = np.abs((J * q.rule.normals).sum(0)) if q.law == "bilateral" \
            else np.linalg.norm(J, axis=0)
        jumps.append(float(jn.max()))
    traction = np.hstack(tractions)
    return result(p, U, traction, max(jumps), B.shape[0] - info.removed, seconds,
                  linear, linear_info, removed=info.removed)
