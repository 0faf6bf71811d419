r"""Unilateral contact and Coulomb friction on Γ over a load history (paper §2–3, eq. 5–9).

:func:`solve` takes a scene whose ``law`` is one of
:data:`~skxfem.contact.laws.CONTACT_LAWS` and a load history, and returns the
:class:`~skxfem.result.Result` of every law, its fields those of the last
step, with one :class:`Step` per load step (the values at the multiplier
dofs).  Each step is
solved by the globalised semi-smooth Newton method of
:mod:`skxfem.contact.newton` (every equation at once) or, with
``method="fixed_point"``, by the paper's scheme
(:mod:`skxfem.contact.fixed_point`).

**Where the laws are imposed.** At the multiplier dofs, with the weighted
jumps d_j = ∫ψ_j [[u]]·n / ∫ψ_j (:mod:`skxfem.contact.interface`): the
pressure is a multiplier dof, the gap is tested by the same function, so the
discrete Signorini conditions λ_j ≤ 0, d_j ≤ 0, λ_j d_j = 0 hold *exactly*
at every dof, the contact residual is a function of dof values only, and the
Newton matrix is the sparse bilateral saddle matrix with rows switched
between "d_j = 0" and "λ_j = 0".  Evaluating χ at the quadrature points
instead would mix the two states inside a facet, and the pointwise
conditions could not all hold for a linear λ_h.

**ρ_n, ρ_τ.** Both are tractions per length and default to E/h, h the mean
length of the cut edges.  The solution does not depend on them (an
augmentation, not a penalty); only the iterations do.

**Load history.** A sequence of load factors (the scene's loads and imposed
displacements scaled) or of load states (scenes on the same mesh, Γ,
supports, material and space, e.g. press, then shear, then unload), each
with its own law: a state may switch the interface to another contact law,
or to ``bilateral`` (tension carried, free sliding) or ``bonded`` (no
further slip), e.g. once it is closed.  The slip rate of eq. 9b is v_τ Δt =
the increment of the tangential jump over a step.

**Rescue and step cutting.** A step whose Newton iteration does not
converge is solved again from the same start: by Newton with the default
ρ = E/h where the scene chose another (an extreme ρ_τ makes a sticking point
look sliding for many iterations), then, for Coulomb, by the paper's fixed
point, whose passes freeze the radius μp of the friction ball (Newton may
stall at a lightly pressed point on the slip limit, where that radius moves
with the pressure); from the first answer found, Newton with the scene's own
ρ confirms it (``rescued`` in the step's
:class:`~skxfem.contact.newton.NewtonInfo` counts the iterations of the first
attempt).  A step that still does not converge in ``max_iter``
iterations is solved again in two halves (loads and imposed
displacements interpolated, the state's law throughout), and so on, each
cut reported by a :class:`StepCutWarning`, down to 1/2^``max_cuts`` of the
step; then the error names the step and its load factor.

**Loads that Γ cannot hold.** Before a load state is solved, a part of the body
that no support touches is checked against its loads
(:func:`skxfem.contact.holding.check_held_by_gamma`): their resultant must lie in the
friction cone of Γ, else no equilibrium exists and no load step, ρ or iteration
can find one.  Loads that press the part on Γ but push it along Γ harder than the
friction holds are refused by a
:class:`~skxfem.contact.holding.FrictionCannotHoldError` naming μ, the part, the
direction it slides and the μ it needs; loads that pull it off Γ get the
rigid-motion diagnosis of an open Γ (:func:`check_determined`'s).

**Interfaces.** A scene's interfaces (one or more, one of them with a contact
law) are solved here as one: the dofs of every interface, each with its own
law, μ and ρ (:func:`parameters` of that interface; the ties as the kinds
``bilateral`` and ``bonded``), their operators and laws stacked
(:func:`skxfem.contact.interface.join`, :func:`skxfem.contact.newton.join_laws`).
A load state gives each interface its law.  The result's fields are those of
every interface in turn (:mod:`skxfem.result`), its ``law`` one
:class:`~skxfem.contact.newton.Law` per interface.

>>> from dataclasses import replace
>>> from skxfem.scene import Displacement
>>> from skxfem.scene.benchmarks import strip
>>> s = strip(n=3)   # the top must be held in x: a frictionless Γ lets it slide
>>> s = replace(s, law="frictionless",
...             displacements=s.displacements + (Displacement("ymax", {"x": 0.0}),))
>>> result = solve(s)
>>> step = result.steps[-1]
>>> bool(step.pressure.min() > 0), step.newton.iterations <= 4
(True, True)
"""
from __future__ import annotations

import time
import warnings
from collections.abc import Mapping, Sequence, Set
from dataclasses import dataclass, replace
from fractions import Fraction

import numpy as np
import scipy.sparse as sp
from skfem import Mesh

from ..fem.loads import scaled_force
from ..gamma import gamma
from ..linalg.amg import check_tie_held, rigid_modes, scaled_tie
from ..linalg.choice import choose_linear
from ..linalg.dependent import dependencies, unit_rows
from ..linalg.iterative import stiffness_setup
from ..linalg.rigid import check_held
from ..linalg.saddle import SingularSystemError
from ..linalg.scalars import is_integer, is_number
from ..linalg.threads import limited
from ..problem import Problem, assemble, state_loads
from ..result import Result, on_edges, result
from ..scene.laws import in_words
from ..scene.model import Interface, Scene, check_steps, resolve
from ..scene.settings import MAX_ITER
from .fixed_point import fixed_point
from .holding import check_held_by_gamma
from .interface import Operators, operators, tangent_frames
from .laws import CONTACT_LAWS, HISTORY_LAWS, OPEN, SLIP, STICK
from .newton import (
    TOL,
    ContactConvergenceError,
    Iterate,
    Law,
    NewtonInfo,
    PointLaws,
    StepProblem,
    join_laws,
    newton,
    point_laws,
    predict,
)

__all__ = ["Step", "parameters", "solve", "progress_line", "ContactConvergenceError",
           "StepCutWarning", "StepRetryWarning", "METHODS", "RHO_RANGE", "MAX_CUTS",
           "semi_multiplier", "step_results"]

METHODS = ("newton", "fixed_point")

NEGLIGIBLE = 1e-8
"""A contact multiplier whose rows, Jacobi-scaled as the tie's solve scales them,
have a singular value below this fraction of the largest is refused
(:func:`check_closed`): the tie's threshold for multipliers it leaves to the
smoothing (:data:`skxfem.linalg.saddle.FIXED_TOL`).  Measured: the paper's plate
≥ 0.06 (n = 5-15, every cell and stable space); winner on tetrahedra beside the
rollers with Γ 2e-10 off nodes, 5e-17."""

RHO_RANGE = (1e-9, 1e12)
"""The ρ_n, ρ_τ accepted, relative to their defaults E/h."""

MAX_CUTS = 6
"""A load step is cut down to 1/2^MAX_CUTS of its increment before it is refused."""


class StepCutWarning(UserWarning):
    """A load step did not converge and is solved again in smaller increments."""


class StepRetryWarning(UserWarning):
    """A load step did not converge and is solved again from the same start by another
    method (Newton at the default ρ, the paper's fixed point): module notes."""


@dataclass(frozen=True)
class Step:
    """One converged load step, all at the m multiplier dofs.

    ``pressure`` (m,) p = -λ; ``traction`` (m, k) the tangential traction
    r_τ (components on ``Result.ops.Bt``'s tangents); ``gap`` (m,)
    the weighted normal jump d (≤ 0 admissible); ``slip`` (m, k) the
    weighted tangential jump (total); ``status`` (m,) 0 open, 1 stick,
    2 slip; ``Lambda`` (m, k) the semi-multiplier Λ = r_τ/(μλ) of eq. 9a
    (``coulomb``, where p > 0; 0 elsewhere); ``law`` the law of the step, the
    name of each interface's (a tuple);
    ``increments`` how many increments the step took (1 unless cut); ``F`` the load
    vector of the step (on the unknowns: its support reactions are K U - F);
    ``body_force`` the step's body force (the scene's times its load factor, or its load
    state's; None: none), whose term the stress intensity factors hold.
    """

    load: object
    U: np.ndarray
    pressure: np.ndarray
    traction: np.ndarray
    gap: np.ndarray
    slip: np.ndarray
    status: np.ndarray
    Lambda: np.ndarray
    newton: NewtonInfo
    law: tuple = ()
    increments: int = 1
    F: np.ndarray | None = None
    body_force: object = None


def parameters(item: Interface, h: float, E: float) -> Law:
    """The :class:`~skxfem.contact.newton.Law` of an :class:`~skxfem.scene.Interface`
    with ρ defaults E/h for mesh size h and Young's modulus E.

    ``coulomb`` with μ = 0 is ``frictionless``.

    >>> from skxfem.scene.benchmarks import strip
    >>> from dataclasses import replace
    >>> s = replace(strip(), law="coulomb", friction=0.5)
    >>> law = parameters(s.interfaces[0], h=0.25, E=s.material.E)
    >>> law.name, law.mu, law.rho_n, law.rho_t
    ('coulomb', 0.5, 4.0, 4.0)
    """
    if item.law not in HISTORY_LAWS:
        raise ValueError(f"scene law must be one of {CONTACT_LAWS} for a contact solve, "
                         f"got {item.law!r} (ties are solved by skxfem.solver.solve)")
    default = E / h
    rho = {}
    for key in ("rho_n", "rho_t"):
        given = getattr(item, key)
        rho[key] = default if given is None else given
        ratio = rho[key] / default   # its ends accepted, whatever the last bit of E/h
        if not RHO_RANGE[0] * (1 - 1e-12) <= ratio <= RHO_RANGE[1] * (1 + 1e-12):
            raise ValueError(
                f"scene {key} = {rho[key]:g} is {ratio:.6g} x its default "
                f"E/h = {default:g}; it is an augmentation (the solution does not depend "
                f"on it) and outside {RHO_RANGE[0]:g}..{RHO_RANGE[1]:g} x the default the "
                f"Newton iteration loses its digits: leave it None or choose it near E/h")
    mu = 0.0 if item.friction is None else float(item.friction)  # None: no friction
    name = "frictionless" if item.law == "coulomb" and mu == 0 else item.law
    return Law(name, mu, float(rho["rho_n"]), float(rho["rho_t"]))


@dataclass(frozen=True)
class _State:
    """One entry of a load history: its label, load, imposed values, the law of each
    interface and its body force (None: none)."""

    label: object
    F: np.ndarray
    g: np.ndarray
    laws: tuple[Law, ...]
    body_force: object = None


def _spaces(scene: Scene) -> list[str]:
    """The multiplier space of each interface of ``scene``."""
    return [i.space for i in scene.interfaces]


def _state(state: Scene, scene: Scene, pb: Problem, i: int):
    """(F, g) of a load state on the problem's space, refusing one that changes what
    one solve keeps (module notes): its mesh, Γ, material, spaces and supports."""
    for key, get in (("material", lambda s: s.materials()), ("space", _spaces),
                     ("quadrature_order", lambda s: s.quadrature_order)):
        if get(state) != get(scene):
            raise ValueError(f"history[{i}]: a load state must keep the scene's {key} "
                             f"({get(scene)!r}), got {get(state)!r}: the "
                             f"solver keeps one stiffness and one multiplier space")
    same = state.mesh is scene.mesh or (not isinstance(state.mesh, Mesh)
                                         and state.mesh == scene.mesh)
    _, mesh = resolve(state, pb.mesh if same else None)   # checked, the mesh not rebuilt
    kept = (np.array_equal(mesh.p, pb.mesh.p) and np.array_equal(mesh.t, pb.mesh.t)
            and len(state.interfaces) == len(pb.interfaces)
            and all(a.levelset is q.interface.levelset
                    or np.array_equal(gamma(a).cut(mesh).psi, q.cut.psi)   # Γ as it was
                    for a, q in zip(state.interfaces, pb.interfaces)))
    F, D, g = state_loads(pb, state) if kept else (None, None, None)
    if not kept or not np.array_equal(D, pb.D):
        raise ValueError(f"history[{i}]: a load state must keep the mesh, Γ and "
                         f"the supported boundaries of the scene (same constrained "
                         f"unknowns); give a zero displacement where a support "
                         f"is released")
    return F, g


def _laws(scene: Scene, hs) -> tuple[Law, ...]:
    """The :class:`~skxfem.contact.newton.Law` of each interface of ``scene``, with the
    mean cut-edge length ``hs[k]`` of interface k."""
    for k, i in enumerate(scene.interfaces):
        if i.law == "free":
            raise ValueError(
                f"{scene.label(k) or 'the interface'}: law 'free' (a crack with free faces, "
                f"no multipliers) cannot be solved with the contact law of another "
                f"interface: the contact Newton takes a law with multipliers on each; give "
                f"it law 'frictionless' (faces that open are free, faces that meet press "
                f"instead of passing through each other)")
    return tuple(parameters(i, h, scene.material.E) for i, h in zip(scene.interfaces, hs))


def _states(scene: Scene, pb: Problem, history, hs) -> list[_State]:
    """The :class:`_State` of each entry of the history; ``hs`` the mean cut-edge
    length of each interface."""
    if isinstance(history, np.ndarray) and history.ndim == 1:
        history = history.tolist()
    if isinstance(history, (str, bytes, Mapping, Set)) or not isinstance(history, Sequence) \
            or len(history) == 0:
        raise ValueError(f"history must be a non-empty sequence (a list or tuple, in "
                         f"order) of load factors or of scenes (load states), got "
                         f"{type(history).__name__} {history!r:.100}")
    check_steps(len(history), "history")
    laws = _laws(scene, hs)
    out = []
    for i, item in enumerate(history):
        if isinstance(item, Scene):
            for j in item.interfaces:
                if j.law not in HISTORY_LAWS:
                    raise ValueError(f"history[{i}]: the law of a load state must be one "
                                     f"of {HISTORY_LAWS}, got {j.law!r}")
            out.append(_State(item.name, *_state(item, scene, pb, i), _laws(item, hs),
                              item.body_force))
        elif is_number(item) and np.isfinite(item):
            item = float(item)
            out.append(_State(item, item * pb.F, item * pb.g, laws,
                              scaled_force(scene.body_force, item, pb.mesh.dim())))
        else:
            raise ValueError(f"history[{i}] must be a finite load factor or a Scene, "
                             f"got {item!r}")
    return out


@limited
def solve(scene: Scene, history=None, method: str = "newton", tol: float = TOL,
          max_iter: int | None = None, linear: str | None = None, max_cuts: int = MAX_CUTS,
          linear_tol: float | None = None, progress=None) -> Result:
    """Solve the contact ``scene`` over the load ``history``.

    Parameters
    ----------
    scene
        A scene with ``law`` in ``CONTACT_LAWS`` (and ``friction`` μ for coulomb).
    history
        Load factors (floats) and/or load states (scenes), applied in order;
        ``None``: the scene's ``steps``.
    method
        ``"newton"`` (semi-smooth Newton on all equations) or ``"fixed_point"``.
    tol, max_iter
        Relative residual tolerance of every equation
        (:func:`skxfem.contact.newton.relative_residuals`); iteration limit of
        one (sub)step (``None``: ``scene.solver.max_iter``, else
        :data:`~skxfem.scene.settings.MAX_ITER`).
    linear
        The linear solve of each Newton step (:data:`skxfem.linalg.choice.LINEAR`):
        ``"direct"``, ``"iterative"`` (pyamg) or ``"auto"``:
        :func:`skxfem.linalg.choice.choose_linear`, direct for a crack (``None``:
        ``scene.solver.linear``).
    max_cuts
        How many times a failing step may be halved (module notes); 0: never.
    linear_tol
        The relative residual of each iterative linear solve (``None``:
        ``scene.solver.linear_tol``).
    progress
        ``None`` (silent), or a callable given one line of text after each Newton
        iteration (the load step, the relative residuals of equilibrium,
        contact and friction, how many points are open, stick and slip, the
        Krylov iterations of its linear solve, the time so far) and after each
        load step (:func:`progress_line`); ``skxfem run`` prints them on stderr.

    Each retry of a step (module notes) and each cut is said as it happens, by a
    :class:`StepRetryWarning` or a :class:`StepCutWarning` (``skxfem run``
    prints them as ``skxfem: note: ...`` lines).

    Raises
    ------
    ValueError
        A tie law, an empty or bad history, an unknown method, a load state
        that changes the set-up.
    ContactConvergenceError
        A step that does not converge, cut down to 1/2^max_cuts: the message
        names the step and its load factor.
    skxfem.contact.holding.FrictionCannotHoldError
        (a ValueError) A part that only Γ holds, pushed along Γ by its loads
        harder than the friction can hold (module notes), said before solving.
    skxfem.linalg.saddle.SingularSystemError
        (a ValueError) A part that only Γ holds, pulled off Γ by its loads
        (before solving); a law that leaves a side free to move even with Γ
        closed everywhere (a frictionless Γ under a side that only Γ holds),
        or a converged step whose displacement is not unique (the open or
        sliding interface leaves a side free, :func:`check_determined`).
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    if not (is_integer(max_cuts) and max_cuts >= 0):
        raise ValueError(f"max_cuts must be an integer >= 0, got {max_cuts!r}")
    max_cuts = int(max_cuts)
    if not (isinstance(tol, float) and 0 < tol < 1):
        raise ValueError(f"tol must be a float in (0, 1), got {tol!r}")
    resolved = resolve(scene)   # checked and its mesh resolved, once
    scene = resolved.scene
    settings = scene.solver.override(linear, linear_tol, max_iter)
    max_iter = MAX_ITER if settings.max_iter is None else settings.max_iter
    if not any(i.law in CONTACT_LAWS for i in scene.interfaces):
        got = [i.law for i in scene.interfaces]
        raise ValueError(f"scene law must be one of {CONTACT_LAWS} for a contact solve, "
                         f"got {in_words(got)} (ties are solved by "
                         f"skxfem.solver.solve)")
    pb = assemble(resolved, law="bilateral")
    ops = operators(pb)
    hs = tuple(o.h for o in ops.pieces)
    states = _states(scene, pb, scene.steps if history is None else history, hs)
    cracks = any(not q.V.splits for q in pb.interfaces)  # contact: multipliers on them
    linear = choose_linear(settings.linear, pb.mesh.dim(), pb.V.N, cracks, cracks)
    linear_tol = settings.linear_tol
    modes = rigid_modes(pb.V)
    t0 = time.perf_counter()
    solve_kw = {"linear": linear} if linear == "direct" else {
        "linear": linear, "modes": modes, "blocksize": pb.mesh.dim(),
        "linear_tol": linear_tol,  # K's one set-up, every step's tie carried over from it
        "setup": stiffness_setup(pb.K, pb.D, modes, pb.mesh.dim())}
    free = np.setdiff1d(np.arange(pb.V.N), pb.D)
    scaled = _scaled(pb, solve_kw.get("setup"))
    m, k = ops.w.size, len(ops.Bt)
    # the reference ρ of the convergence test: E/h, each interface its own h
    rho_ref = scene.material.E / np.array(hs)[ops.interface]
    it = Iterate(np.zeros(pb.V.N), np.zeros(m), np.zeros((m, k)))
    F, g = np.zeros(pb.V.N), np.zeros(pb.D.size)
    steps = []
    checked = set()
    before, names_before = None, None  # the converged state before it, for the predictor
    for i, state in enumerate(states):
        laws = _point_laws(state.laws, ops)
        names = tuple(law.name for law in state.laws)
        if names not in checked:  # the law holds the body with Γ closed?
            check_closed(pb, ops, laws, modes, state.label, scaled)
            checked.add(names)
        # can Γ hold, under these loads, a part that nothing else holds?
        check_held_by_gamma(pb, ops, laws, state.F, modes, state.label,
                            lambda status, what, hint, laws=laws, label=state.label:
                            _check_rigid(pb, ops, laws, status, None, what, hint, label))

        def one(start, U_prev, F1, g1, where, guess=None, laws=laws):
            step = StepProblem(ops, pb.K, F1, free, U_prev, laws, rho_ref)
            U = start.U.copy()
            U[pb.D] = g1
            start = Iterate(U, start.lam, start.r)
            watch = {} if progress is None else {"monitor": lambda n, r, status, inner: progress(
                progress_line(where, n, r, status, inner, time.perf_counter() - t0))}
            if method == "fixed_point":
                return fixed_point(step, start, tol=tol, max_iter=max_iter, **solve_kw,
                                   **watch)
            try:
                return newton(step, start, tol=tol, max_iter=max_iter, guess=guess,
                              **solve_kw, **watch)
            except ContactConvergenceError as failed:
                return _rescue(step, start, failed, tol, max_iter, solve_kw,
                               where + _blame(failed, pb, ops))

        where = f"load step {i + 1} of {len(states)} ({_describe(state.label)})"
        if names != names_before:  # a new law: the last increment predicts nothing
            before = None
        it, res, info, pieces, before = _advance(
            one, it, F, g, state.F, state.g, max_cuts if method == "newton" else 0, where,
            "+".join(names), lambda e: _blame(e, pb, ops), before)
        F, g, names_before = state.F, state.g, names
        if progress is not None:
            progress(progress_line(where, None, None, res.status, sum(info.inner),
                                   time.perf_counter() - t0, info.iterations))
        check_determined(pb, ops, laws, res.status, res.y, modes, state.label, scaled)
        steps.append(_step(state, ops, it, res, info, pieces, laws))
    return _result(pb, ops, states[0].laws, tuple(steps), linear, linear_tol,
                   time.perf_counter() - t0)


def progress_line(where: str, n, residuals, status, inner: int, elapsed: float,
                  iterations: int | None = None) -> str:
    """One line of progress: Newton iteration ``n`` of a load step (its relative
    ``residuals``), or, with ``n`` None, the step done in ``iterations``; the
    counts of open, stick and slip points, the Krylov iterations, the time so far.

    >>> print(progress_line("step 1", 3, [1e-3, 0, 2e-5], np.array([0, 2, 2]), 7, 1.25))
    ... # doctest: +NORMALIZE_WHITESPACE
    step 1: Newton 3, residuals 1.0e-03 0.0e+00 2.0e-05; 1 open, 0 stick, 2 slip;
    7 Krylov iterations; 1.2 s
    """
    counts = np.bincount(np.asarray(status, int), minlength=3)
    points = f"{counts[OPEN]} open, {counts[STICK]} stick, {counts[SLIP]} slip"
    krylov = f"; {inner} Krylov iterations" if inner else ""
    if n is None:
        return (f"{where}: done in {iterations} Newton iteration(s); {points}{krylov}; "
                f"{elapsed:.1f} s")
    r = " ".join(f"{x:.1e}" for x in residuals)
    return f"{where}: Newton {n}, residuals {r}; {points}{krylov}; {elapsed:.1f} s"


def _point_laws(laws: tuple[Law, ...], ops: Operators) -> PointLaws:
    """The law of every dof: those of each interface (``laws``) at its dofs."""
    return join_laws([point_laws(law, ops.tangent_held[ops.interface == k])
                      for k, law in enumerate(laws)])


def _result(pb: Problem, ops: Operators, law, steps: tuple, linear: str,
            linear_tol: float, seconds: float) -> Result:
    """The :class:`~skxfem.result.Result` of the last step: the dofs' values carried
    to the cut edges by λ = P μ (the status: that of the dof weighing most)."""
    last = steps[-1]
    qs = pb.interfaces
    normals = np.hstack([q.normals() for q in qs])
    p = on_edges(pb.P, last.pressure)
    r = np.stack([on_edges(Pa, last.traction[:, a]) for a, Pa in enumerate(ops.Pt)],
                 axis=1).reshape(p.size, len(ops.Pt))  # (n, k) on each point's frame
    frames = tangent_frames(normals)  # (k, dim, n)
    traction = -p * normals + np.einsum("nk,kdn->dn", r, frames)
    owner = np.asarray(abs(pb.P).argmax(axis=1)).ravel()
    dim = pb.mesh.dim()
    Jn = np.concatenate([((q.J @ last.U[q.columns])
                          .reshape(dim, -1) * q.rule.normals).sum(0) for q in qs])
    return result(pb, last.U, traction, max(0.0, float(Jn.max())), ops.w.size, seconds,
                  linear, {"tol": linear_tol}, steps=steps, status=last.status[owner],
                  ops=ops, law=law)


def step_results(result: Result) -> list[Result]:
    """The :class:`~skxfem.result.Result` of every load step of a contact ``result``, in
    order: each with the fields, statuses and reactions of its step (the last is
    ``result`` itself, recomputed), for a series of files (:mod:`skxfem.app.io`).

    >>> from dataclasses import replace
    >>> from skxfem.scene import Displacement
    >>> from skxfem.scene.benchmarks import strip
    >>> s = strip(n=3)
    >>> s = replace(s, law="frictionless", steps=(0.5, 1.0),
    ...             displacements=s.displacements + (Displacement("ymax", {"x": 0.0}),))
    >>> first, last = step_results(solve(s))
    >>> bool(np.allclose(2 * first.pressure, last.pressure))
    True
    """
    if not result.is_contact:
        raise ValueError("step_results takes the result of a contact solve (with steps)")
    return [_result(result.problem, result.ops, result.law, result.steps[:k + 1],
                    result.linear, result.linear_info.get("tol"), result.timings["solve"])
            for k in range(len(result.steps))]


def _rescue(step: StepProblem, start: Iterate, failed: ContactConvergenceError, tol: float,
            max_iter: int, solve_kw: dict, where: str = "a load step"):
    """A step whose Newton iteration failed, solved again from the same start (module
    notes, which say why): Newton at the default ρ = E/h where the step's is another,
    then, for Coulomb, the paper's fixed point; from the first answer found, Newton
    with the step's own ρ.  Each attempt is said before it runs, by a
    :class:`StepRetryWarning` that starts with ``where``.  Re-raises ``failed`` if none
    converges (``failed.retries``: how many ran)."""
    laws = step.laws
    attempts = []
    if not (np.allclose(laws.rho_n, step.rho_ref) and np.allclose(laws.rho_t, step.rho_ref)):
        reference = replace(step, laws=replace(laws, rho_n=np.full_like(laws.rho_n,
                                                                        step.rho_ref),
                                               rho_t=np.full_like(laws.rho_t, step.rho_ref)))
        attempts.append(("Newton at the default rho = E/h", lambda: newton(
            reference, start, tol=tol, max_iter=max_iter, **solve_kw)))
    if np.any(laws.tangential == "coulomb"):
        attempts.append(("the paper's fixed point on the friction threshold",
                         lambda: fixed_point(step, start, tol=tol, max_iter=max_iter,
                                             **solve_kw)))
    reason = f"Newton {_reason(failed)}"
    for k, (name, attempt) in enumerate(attempts):
        warnings.warn(f"{where}: {reason}; retry {k + 1} of {len(attempts)}: solving it "
                      f"again by {name}", StepRetryWarning, stacklevel=3)
        try:
            near = attempt()[0]
        except ContactConvergenceError as e:
            reason = f"{name} {_reason(e)}"
            continue
        try:
            it, res, info = newton(step, near, tol=tol, max_iter=max_iter, **solve_kw)
        except ContactConvergenceError as e:
            reason = f"Newton from the answer of {name} {_reason(e)}"
            continue
        return it, res, replace(info, rescued=len(failed.statuses) - 1)
    failed.retries = len(attempts)
    raise failed


def _reason(error: ContactConvergenceError) -> str:
    """The head of a convergence error, without the words the notes say already."""
    head = str(error).split(":")[0].strip()
    for words in ("contact Newton ", "the fixed point on the friction threshold "):
        head = head.removeprefix(words)
    return head


def _blame(error: ContactConvergenceError, pb: Problem, ops: Operators) -> str:
    """The interfaces of the points that kept changing status in the failed iteration
    (else those with a contact law), as ``" on interfaces[1] 'y - 0.7' (coulomb)"``;
    ``""`` where the scene names none (one interface: :meth:`skxfem.scene.Scene.label`)."""
    items = pb.scene.interfaces
    if not pb.scene.label(0):
        return ""
    seen = getattr(error, "statuses", None)
    ks = []
    if seen is not None and len(seen) > 1:
        seen = np.asarray(seen)
        moving = ((seen[1:] != seen[:-1]).sum(axis=0) > 1)
        ks = np.unique(ops.interface[moving]).tolist()
    if not ks:
        ks = [k for k, i in enumerate(items) if i.law in CONTACT_LAWS]
    return " on " + ", ".join(f"{pb.scene.label(k)} ({items[k].law})" for k in ks)


def _describe(label) -> str:
    return f"load factor {label:g}" if isinstance(label, float) else f"state {label!r}"


def _advance(one, it, F0, g0, F1, g1, max_cuts: int, where: str, law_name: str = "",
             blame=lambda e: "", before=None):
    """Solve from the converged ``it`` (under F0, g0) to F1, g1, halving the
    increment where a step fails (module notes), each cut said by a
    :class:`StepCutWarning` as it is made.  ``one(it, U, F, g, where, guess)``
    solves an increment (``where`` names it, for its notes; ``guess`` the
    predicted state, :func:`_guess`); ``blame(error)`` names the interfaces of a
    failure (several interfaces).  ``before``: the converged (iterate, F, g)
    before ``it``, whose increment predicts the next one.  Returns the iterate,
    its residual, the NewtonInfo of the last increment, the number of increments
    and the ``before`` of the next step."""
    done, size, pieces = 0.0, 1.0, 0
    smallest = 0.5 ** max_cuts
    Fa, ga = F0, g0  # the loads of ``it``
    while done < 1.0:
        target = min(1.0, done + size)
        part = target - done    # the increment tried: size, or what is left of the step
        here = where if part == 1.0 else f"{where}, increment {_part(done, target)}"
        Ft, gt = F0 + target * (F1 - F0), g0 + target * (g1 - g0)
        try:
            new, res, info = one(it, it.U, Ft, gt, here, _guess(before, it, Fa, ga, Ft, gt))
        except ContactConvergenceError as e:
            e.law = law_name
            if part / 2 < smallest * (1 - 1e-12):
                cut = f" after cutting it down to 1/{round(1 / part)} of its increment" \
                    if max_cuts and part < 1 else ""
                hint = (" The adhesive law (no slip wherever closed) may have no solution "
                         "at the edge of a contact zone, where the pressure vanishes: a point "
                         "that stays closed pulls, one that opens penetrates; coulomb with a "
                         "large friction (1e3) has one." if "adhesive" in law_name.split("+")
                         else "")
                err = ContactConvergenceError(
                    f"{where}: {e}{cut}. Try more load steps, another rho_n/rho_t, or "
                    f"max_iter.{hint}")
                err.last, err.statuses = e.last, e.statuses
                if hasattr(e, "thresholds"):
                    err.thresholds = e.thresholds
                raise err from e
            size = part / 2
            retries = getattr(e, "retries", 0)
            tried = f" (nor its {retries} retr{'y' if retries == 1 else 'ies'})" \
                if retries else ""
            warnings.warn(f"{here}{blame(e)}: Newton {_reason(e)}{tried}; cut: next "
                          f"increment {_part(done, done + size)} (1/{round(1 / size)} of the "
                          f"step)", StepCutWarning, stacklevel=3)
            continue
        before, Fa, ga = (it, Fa, ga), Ft, gt
        it, done, pieces = new, target, pieces + 1
        size = min(1.0, 2 * size) if size < 1 else size
    return it, res, info, pieces, before


def _guess(before, it: Iterate, F0, g0, F1, g1) -> Iterate | None:
    """The predicted state under (F1, g1) from the converged ``it`` under (F0, g0) and
    ``before`` = (iterate, F, g): :func:`~skxfem.contact.newton.predict` where the
    new load increment is a positive multiple of the last (proportional loading),
    else None (Newton starts from ``it``)."""
    if before is None:
        return None
    last = np.concatenate([F0 - before[1], g0 - before[2]])
    step = np.concatenate([F1 - F0, g1 - g0])
    norm = float(last @ last)
    ratio = float(step @ last) / norm if norm > 0 else 0.0
    if not (ratio > 0 and np.linalg.norm(step - ratio * last) <= 1e-10 * np.linalg.norm(step)):
        return None
    return predict(before[0], it, ratio)


def _part(start: float, end: float) -> str:
    """A part of a load step as fractions: ``"1/2 to 3/4"`` (``"0 to 1"``: all of it).

    >>> _part(0.25, 0.5), _part(0.0, 1.0)
    ('1/4 to 1/2', '0 to 1')
    """
    return " to ".join(str(Fraction(v).limit_denominator(2 ** 20)) for v in (start, end))


def _step(state: _State, ops: Operators, it: Iterate, res, info, pieces,
          laws: PointLaws) -> Step:
    """The :class:`Step` of a converged state (``laws`` at its dofs)."""
    m, k = it.r.shape
    slip = np.stack([B @ it.U for B in ops.Bt], axis=1).reshape(m, k) / ops.w[:, None]
    p = -it.lam
    ok = (laws.name == "coulomb") & (p > 0)
    Lam = np.zeros((m, k))
    Lam[ok] = semi_multiplier(it.r[ok], laws.mu[ok], p[ok])
    names = tuple(law.name for law in state.laws)
    return Step(state.label, it.U.copy(), -it.lam, it.r.copy(), ops.Bn @ it.U / ops.w, slip,
                res.status, Lam, info, names, pieces,
                np.asarray(state.F), state.body_force)


def semi_multiplier(r: np.ndarray, mu: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Λ = -r_τ/(μp) (m, k), eq. 9a, at dofs pressed (p > 0) under Coulomb's law.

    r_τ is divided by μ, then by p (μ ≥ 1e-10, :data:`skxfem.scene.parts.FRICTION_RANGE`),
    so that the product μp never underflows; where p is so small that the quotient
    is still not finite, Λ is the unit vector -r_τ/|r_τ| (the slip limit |Λ| = 1,
    which |r_τ| ≤ μp reaches), or 0 where r_τ = 0: never NaN.

    >>> semi_multiplier(np.array([[-0.25]]), np.array([0.5]), np.array([1.0])).tolist()
    [[0.5]]
    >>> semi_multiplier(np.array([[-1e-10, 0.0]]), np.array([1.0]), np.array([5e-324]))
    array([[1., 0.]])
    """
    r = np.asarray(r, dtype=float)
    with np.errstate(all="ignore"):
        lam = -(r / np.asarray(mu)[:, None]) / np.asarray(p)[:, None]
    bad = ~np.isfinite(lam).all(axis=1)
    if bad.any():
        scale = np.abs(r[bad]).max(axis=1, keepdims=True)
        unit = -r[bad] / np.where(scale > 0, scale, 1.0)
        size = np.linalg.norm(unit, axis=1, keepdims=True)
        lam[bad] = unit / np.where(size > 0, size, 1.0)
    return lam + 0.0   # no -0.0


def _sticking(laws: PointLaws, status) -> np.ndarray:
    """(m,) the dofs whose whole jump a state holds: closed under a no-slip law, or
    sticking under Coulomb's."""
    return (((status != OPEN) & (laws.tangential == "stick"))
            | ((status == STICK) & (laws.tangential == "coulomb")))


def _held_rows(ops: Operators, laws: PointLaws, status, y, dofs: bool = False):
    """The rows of the tie that a contact state imposes: the normal jump at
    closed points, the tangential jumps where they stick (not those a support
    holds); a point sliding in 3D holds the tangent across its slip direction.
    With ``dofs``, also the dof of each row."""
    closed = status != OPEN
    rows, of = [ops.Bn[closed]], [np.flatnonzero(closed)]
    k = len(ops.Bt)
    free = ~ops.tangent_held
    stick = _sticking(laws, status)
    for a in range(k):
        rows.append(ops.Bt[a][stick & free[:, a]])
        of.append(np.flatnonzero(stick & free[:, a]))
    slip = (status == SLIP) & (laws.tangential == "coulomb") & free.all(axis=1)
    if k == 2 and slip.any():
        yh = y[slip] / np.linalg.norm(y[slip], axis=1)[:, None]
        rows.append(sp.diags(-yh[:, 1]) @ ops.Bt[0][slip]
                    + sp.diags(yh[:, 0]) @ ops.Bt[1][slip])
        of.append(np.flatnonzero(slip))
    rows = sp.vstack(rows, format="csr")
    return (rows, np.concatenate(of)) if dofs else rows


def _names(laws: PointLaws) -> str:
    """The law of the dofs in words: "the coulomb law", or "the laws a, b"."""
    names = list(dict.fromkeys(laws.name.tolist()))
    return f"the {names[0]} law" if len(names) == 1 else f"the laws {', '.join(names)}"


def _check_rigid(pb: Problem, ops: Operators, laws: PointLaws, status, y, what: str, hint: str,
                 label) -> None:
    """:func:`skxfem.linalg.rigid.check_held` of a contact state: the normal jump held at
    the edges of closed dofs, the whole jump at those of sticking ones, and a
    3D sliding point's tangent across its slip; the message names the motion."""
    closed = status != OPEN
    full = _sticking(laws, status)
    edges_of = abs(pb.P).tocsc()
    slip = (status == SLIP) & (laws.tangential == "coulomb") & ~ops.tangent_held.any(axis=1)
    rows = sp.csr_matrix((0, pb.V.N))
    if len(ops.Bt) == 2 and y is not None and slip.any():
        yh = y[slip] / np.linalg.norm(y[slip], axis=1)[:, None]
        rows = (sp.diags(-yh[:, 1]) @ ops.Bt[0][slip]
                + sp.diags(yh[:, 0]) @ ops.Bt[1][slip]).tocsr()
    try:
        check_held(pb, normal=np.asarray(edges_of[:, closed].sum(axis=1)).ravel() > 0,
                   full=np.asarray(edges_of[:, full].sum(axis=1)).ravel() > 0,
                   rows=rows, what=what, hint=hint)
    except SingularSystemError as e:
        raise SingularSystemError(f"load step {label!r}: {e}") from None


def _scaled(pb: Problem, setup=None):
    """(s, K_s): K scaled to unit diagonal, imposed unknowns as identity rows
    (:func:`skxfem.linalg.amg.scaled_tie`), the stiffness set-up's if there is one:
    one scaling for every check of a contact solve."""
    if setup is not None:
        return setup.s, setup.Kr
    fixed = np.zeros(pb.V.N, bool)
    fixed[pb.D] = True
    return scaled_tie(pb.K, sp.csr_matrix((0, pb.V.N)), fixed)[:2]


def check_closed(pb: Problem, ops: Operators, laws: PointLaws, modes, label=None,
                 scaled=None) -> None:
    """Refuse a law that cannot determine a state even where Γ is closed
    everywhere (every point in contact, sticking where the law can): a side
    it leaves free to move (a frictionless Γ under a side that only Γ holds
    tangentially; :func:`skxfem.linalg.rigid.check_held` names the motion),
    multipliers that depend on the others (the naive space on tetrahedra), or
    multipliers that barely see the jump (:data:`NEGLIGIBLE`: functions living on
    slivers of Γ, which the tie sets to their smoothest values).
    ``laws``: the :class:`~skxfem.contact.newton.PointLaws` of the dofs; ``scaled``:
    (s, K_s) of K (:func:`_scaled`), if the caller has them."""
    status = np.where(laws.tangential == "free", SLIP, STICK)
    text = _names(laws)
    _check_rigid(pb, ops, laws, status, None, f"{text} with Γ closed everywhere",
                 "hold each side of Γ, or use a law with friction", label)
    fixed = np.zeros(pb.V.N, bool)
    fixed[pb.D] = True
    rows, row_dofs = _held_rows(ops, laws, status, None, dofs=True)
    try:
        check_tie_held(pb.K, rows, fixed, modes, scaled=scaled)
    except SingularSystemError as e:
        raise SingularSystemError(
            f"load step {label!r}: even with Γ closed everywhere, {text} leaves "
            f"a part of the body free to move ({e}): hold each side of Γ, or use a law "
            f"with friction") from e
    free = rows[:, ~fixed]
    N = dependencies(unit_rows(free)[0])
    if N.shape[1]:
        raise ValueError(
            f"load step {label!r}: {N.shape[1]} contact multipliers depend on the others "
            f"(space {_spaces(pb.scene)!r}: the naive space on tetrahedra carries four "
            f"multipliers on a quadrilateral cut, for three parameters of a linear jump), so "
            f"the pressure is not unique where the laws must hold: use space='vital'")
    # scaled as the tie's solve scales them (Jacobi): a multiplier whose row is
    # negligible there lives on a sliver of Γ; the tie picks the smoothest value
    # for it, a contact law would take its value from round-off
    stiffness = np.abs(pb.K.diagonal()[~fixed])
    scaled = free @ sp.diags(1.0 / np.sqrt(np.where(stiffness > 0, stiffness, 1.0)))
    N = dependencies(scaled, NEGLIGIBLE)
    if N.shape[1]:
        dofs = np.unique(row_dofs[np.abs(N).max(axis=1) > 0.1 * np.abs(N).max()])
        raise ValueError(
            f"load step {label!r}: {N.shape[1]} contact multiplier(s) barely see the jump "
            f"(a singular value below {NEGLIGIBLE:.0e} of the largest, dofs "
            f"{dofs[:10].tolist()} near {np.round(ops.points[:, dofs[0]], 6).tolist()}): "
            f"their functions live on slivers of Γ, where Γ passes within a tiny distance "
            f"of nodes, so no contact law can fix their values (a tie takes the smoothest); "
            f"space {_spaces(pb.scene)!r} builds such functions there: use space='vital', "
            f"or move Γ away from the nodes")


def check_determined(pb: Problem, ops: Operators, laws: PointLaws, status, y, modes, label=None,
                     scaled=None) -> None:
    """Refuse a converged contact state that leaves a side of Γ free to move.

    Newton may converge to a state whose displacement is not unique: an
    unloaded side held only by an interface that ends up open (``status`` all
    OPEN) may slide by any rigid motion, and a disc in contact all round
    may turn about its centre.  The state holds what its closed points hold:
    the normal jump, and the whole jump where they stick (``adhesive``:
    wherever closed); a point sliding in 3D holds the tangent across its slip
    direction ŷ.  :func:`skxfem.linalg.rigid.check_held` tests that with the level
    set's normals and names the motion left free; then
    :func:`skxfem.linalg.amg.check_tie_held` tests the discrete rows themselves.
    ``laws``: the :class:`~skxfem.contact.newton.PointLaws` of the dofs; ``scaled`` as
    :func:`check_closed`.
    """
    counts = np.bincount(status, minlength=3)
    found = (f"({counts[OPEN]} open, {counts[STICK]} stick, {counts[SLIP]} slip of "
             f"{status.size} points)")
    hint = "add supports on each side of Γ or a load that closes it"
    _check_rigid(pb, ops, laws, status, y, f"the contact state found {found}", hint, label)
    fixed = np.zeros(pb.V.N, bool)
    fixed[pb.D] = True
    try:
        check_tie_held(pb.K, _held_rows(ops, laws, status, y), fixed, modes, scaled=scaled)
    except SingularSystemError as e:
        raise SingularSystemError(
            f"load step {label!r}: the contact state found {found} leaves a part of the "
            f"body free to move, so its displacement is not unique (a side that only the "
            f"interface holds, while Γ opens or slides): {hint}") from e
