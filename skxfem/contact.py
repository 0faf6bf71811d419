r"""Unilateral contact and Coulomb friction on Γ over a load history (paper §2–3, eq. 5–9).

:func:`solve` takes a scene whose ``law`` is one of
:data:`~skxfem.contact_laws.CONTACT_LAWS` and a load history, and returns a
:class:`ContactResult` with one :class:`Step` per load step.  Each step is
solved by the semi-smooth Newton method of :mod:`skxfem.contact_newton`
(every equation at once) or, with ``method="fixed_point"``, by the paper's
scheme (:mod:`skxfem.contact_fixed_point`).

**Where the laws are imposed.** At the multiplier dofs, with the weighted
jumps d_j = ∫ψ_j [[u]]·n / ∫ψ_j (:mod:`skxfem.contact_interface`): the
pressure is a multiplier dof, the gap is tested by the same function, so the
discrete Signorini conditions λ_j ≤ 0, d_j ≤ 0, λ_j d_j = 0 hold *exactly*
at every dof, the contact residual is a function of dof values only, and the
Newton matrix is the sparse bilateral saddle matrix with rows switched
between "d_j = 0" and "λ_j = 0".  Evaluating χ at the quadrature points
instead would mix the two states inside a facet, and the pointwise
conditions could not all hold for a linear λ_h.

**ρ_n, ρ_τ.** ``rho_n`` (a traction per length) defaults to E/h, h the mean
length of the cut edges; ``rho_t`` defaults to 1/h for ``coulomb`` (Λ is
dimensionless, so ρ_τ is an inverse length) and to E/h for ``adhesive``
(where the tangential unknown is a traction).  The solution does not depend
on them (an augmentation, not a penalty); only the iterations do.

**Load history.** A sequence of load factors (the scene's loads and imposed
displacements scaled) or of load states (scenes on the same mesh and Γ
with the same supports, e.g. press, then shear, then unload).  The slip
rate of eq. 9b is v_τ Δt = the increment of the tangential jump over a step.

>>> from dataclasses import replace
>>> from skxfem.scene import Displacement
>>> from skxfem.scenes import strip
>>> s = strip(n=3)   # the top must be held in x: a frictionless Γ lets it slide
>>> s = replace(s, law="frictionless",
...             displacements=s.displacements + (Displacement("ymax", {"x": 0.0}),))
>>> result = solve(s)
>>> step = result.steps[-1]
>>> bool(step.pressure.min() > 0), step.newton.iterations <= 4
(True, True)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .amg import check_tie_held, rigid_modes
from .contact_fixed_point import fixed_point
from .contact_interface import Operators, operators
from .contact_laws import CONTACT_LAWS, OPEN, SLIP, STICK, status
from .contact_newton import ContactConvergenceError, Law, NewtonInfo, newton
from .linear import choose_linear
from .problem import Problem, assemble
from .rigid import check_held
from .saddle import SingularSystemError
from .scene import Scene, check_scene
from .threads import limited

__all__ = ["Step", "ContactResult", "parameters", "solve", "ContactConvergenceError",
           "METHODS", "RHO_RANGE"]

METHODS = ("newton", "fixed_point")

RHO_RANGE = (1e-9, 1e12)
"""The ρ_n, ρ_τ accepted, relative to their defaults (the table of extremes: 1e-6 to
1e9 solved, but ρ_τ = 1e9/h, whose Newton stalls at 5e-9)."""


@dataclass(frozen=True)
class Step:
    """One converged load step, all at the m multiplier dofs.

    ``pressure`` (m,) p = -λ; ``traction`` (m, k) the tangential traction
    r_τ (components on ``ContactResult.ops.Bt``'s tangents); ``gap`` (m,)
    the weighted normal jump d (≤ 0 admissible); ``slip`` (m, k) the
    weighted tangential jump (total); ``status`` (m,) 0 open, 1 stick,
    2 slip; ``Lambda`` (m, k) the semi-multiplier (``coulomb``).
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


@dataclass(frozen=True)
class ContactResult:
    """``problem`` (the assembled bilateral problem), ``ops``, ``law``, ``steps``
    and the ``linear`` solve of the Newton steps."""

    problem: Problem
    ops: Operators
    law: Law
    steps: tuple
    linear: str = "direct"


def parameters(scene: Scene, h: float) -> Law:
    """The :class:`~skxfem.contact_newton.Law` of ``scene`` with ρ defaults for mesh size h.

    ``coulomb`` with μ = 0 is ``frictionless``.

    >>> from skxfem.scenes import strip
    >>> from dataclasses import replace
    >>> law = parameters(replace(strip(), law="coulomb", friction=0.5), h=0.25)
    >>> law.name, law.mu, law.rho_n, law.rho_t
    ('coulomb', 0.5, 4.0, 4.0)
    """
    if scene.law not in CONTACT_LAWS:
        raise ValueError(f"scene law must be one of {CONTACT_LAWS} for a contact solve, "
                         f"got {scene.law!r} (ties are solved by skxfem.solver.solve)")
    E = scene.material.E
    defaults = {"rho_n": (E / h, "E/h"), "rho_t": (1.0 / h, "1/h") if scene.law == "coulomb"
                else (E / h, "E/h")}
    rho = {}
    for key, (default, unit) in defaults.items():
        given = getattr(scene, key)
        rho[key] = default if given is None else given
        if not RHO_RANGE[0] <= rho[key] / default <= RHO_RANGE[1]:
            raise ValueError(
                f"scene {key} = {rho[key]:g} is {rho[key] / default:.1e} x its default "
                f"{unit} = {default:g}; it is an augmentation (the solution does not depend "
                f"on it) and outside {RHO_RANGE[0]:g}..{RHO_RANGE[1]:g} x the default the "
                f"Newton iteration loses its digits: leave it None or choose it near {unit}")
    rho_n, rho_t = rho["rho_n"], rho["rho_t"]
    name = "frictionless" if scene.law == "coulomb" and scene.friction == 0 else scene.law
    return Law(name, float(scene.friction), float(rho_n), float(rho_t))


def _states(scene: Scene, pb: Problem, history):
    """(label, F, g) for each entry of the history."""
    if isinstance(history, (str, bytes)) or not hasattr(history, "__len__") \
            or len(history) == 0:
        raise ValueError(f"history must be a non-empty sequence of load factors or of "
                         f"scenes (load states), got {history!r}")
    out = []
    for i, item in enumerate(history):
        if isinstance(item, Scene):
            state = assemble(item, law="bilateral")
            if state.V.N != pb.V.N or not np.array_equal(state.D, pb.D):
                raise ValueError(f"history[{i}]: a load state must keep the mesh, Γ and "
                                 f"the supported boundaries of the scene (same constrained "
                                 f"unknowns); give a zero displacement where a support "
                                 f"is released")
            out.append((item.name, state.F, state.g))
        elif isinstance(item, (int, float, np.integer, np.floating)) and \
                not isinstance(item, bool) and np.isfinite(item):
            out.append((float(item), item * pb.F, item * pb.g))
        else:
            raise ValueError(f"history[{i}] must be a finite load factor or a Scene, "
                             f"got {item!r}")
    return out


@limited
def solve(scene: Scene, history=None, method: str = "newton", tol: float = 1e-10,
          max_iter: int = 30, linear: str = "auto") -> ContactResult:
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
        Relative residual tolerance of every equation; iteration limit.
    linear
        The linear solve of each Newton step (:data:`skxfem.linear.LINEAR`):
        ``"direct"``, ``"iterative"`` (frictionless and adhesive laws, pyamg)
        or ``"auto"``: :func:`skxfem.linear.choose_linear`.

    Raises
    ------
    ValueError
        A tie law, an empty or bad history, an unknown method, ``"iterative"``
        for a Coulomb law.
    ContactConvergenceError
        A step that does not converge within ``max_iter`` iterations.
    skxfem.saddle.SingularSystemError
        (a ValueError) A converged step whose displacement is not unique: the
        open (or sliding) interface leaves a side free to move
        (:func:`check_determined`).
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    if not (isinstance(max_iter, int) and not isinstance(max_iter, bool) and max_iter >= 1):
        raise ValueError(f"max_iter must be a positive integer, got {max_iter!r}")
    if not (isinstance(tol, float) and 0 < tol < 1):
        raise ValueError(f"tol must be a float in (0, 1), got {tol!r}")
    if check_scene(scene).law not in CONTACT_LAWS:
        parameters(scene, 1.0)  # raises the message naming the law
    pb = assemble(scene, law="bilateral")
    ops = operators(pb)
    law = parameters(scene, ops.h)
    linear = choose_linear(linear, pb.mesh.dim(), pb.V.N, law.name)
    modes = rigid_modes(pb.V)
    solve_kw = {"linear": linear} if linear == "direct" else {
        "linear": linear, "modes": modes, "blocksize": pb.mesh.dim()}
    states = _states(scene, pb, scene.steps if history is None else history)
    free = np.setdiff1d(np.arange(pb.V.N), pb.D)
    m, k = ops.w.size, len(ops.Bt)
    U, lam = np.zeros(pb.V.N), np.zeros(m)
    T = np.zeros((m, k if law.friction else 0))
    step_solver = fixed_point if method == "fixed_point" else newton
    steps = []
    for label, F, g in states:
        U_prev = U.copy()
        U[pb.D] = g
        U, lam, T, g_n, g_t, info = step_solver(ops, law, pb.K, F, free, U, lam, T, U_prev,
                                                tol=tol, max_iter=max_iter, **solve_kw)
        tau = law.mu * lam[:, None] * T if law.name == "coulomb" else (
            T if law.name == "adhesive" else np.zeros((m, k)))
        slip = np.stack([B @ U for B in ops.Bt], axis=1) / ops.w[:, None]
        Lam = T if law.name == "coulomb" else np.zeros((m, k))
        st = status(g_n, g_t if law.friction else None, law.name)
        check_determined(pb, ops, law, st, g_t, modes, label)
        steps.append(Step(label, U.copy(), -lam, tau, ops.Bn @ U / ops.w, slip, st, Lam, info))
    return ContactResult(pb, ops, law, tuple(steps), linear)


def check_determined(pb: Problem, ops: Operators, law: Law, st, g_t, modes, label=None
                     ) -> None:
    """Refuse a converged contact state that leaves a side of Γ free to move.

    Newton may converge to a state whose displacement is not unique: an
    unloaded side held only by an interface that ends up open (``st`` all
    OPEN) may slide by any rigid motion, and a disc in contact all round
    may turn about its centre.  The state holds what its closed points hold:
    the normal jump, and the whole jump where they stick (``adhesive``:
    wherever closed); a point sliding in 3D holds the tangent across its slip
    direction ĝ_τ.  :func:`skxfem.rigid.check_held` tests that with the level
    set's normals and names the motion left free; then
    :func:`skxfem.amg.check_tie_held` tests the discrete rows themselves.
    """
    closed = st != OPEN
    full = closed if law.name == "adhesive" else (
        st == STICK if law.name == "coulomb" else np.zeros_like(closed))
    rows = [ops.Bn[closed]]
    slip_rows = sp.csr_matrix((0, pb.V.N))
    if law.name == "adhesive":
        rows += [B[closed] for B in ops.Bt]
    elif law.name == "coulomb":
        rows += [B[st == STICK] for B in ops.Bt]
        slip = st == SLIP
        if len(ops.Bt) == 2 and slip.any():
            gh = g_t[slip] / np.linalg.norm(g_t[slip], axis=1)[:, None]
            slip_rows = (sp.diags(-gh[:, 1]) @ ops.Bt[0][slip]
                         + sp.diags(gh[:, 0]) @ ops.Bt[1][slip]).tocsr()
            rows.append(slip_rows)
    counts = np.bincount(st, minlength=3)
    found = (f"({counts[OPEN]} open, {counts[STICK]} stick, {counts[SLIP]} slip of "
             f"{st.size} points)")
    hint = "add supports on each side of Γ or a load that closes it"
    edges_of = abs(pb.P).tocsc()
    try:
        check_held(pb, normal=np.asarray(edges_of[:, closed].sum(axis=1)).ravel() > 0,
                   full=np.asarray(edges_of[:, full].sum(axis=1)).ravel() > 0,
                   rows=slip_rows, what=f"the contact state found {found}", hint=hint)
    except SingularSystemError as e:
        raise SingularSystemError(f"load step {label!r}: {e}") from None
    fixed = np.zeros(pb.V.N, bool)
    fixed[pb.D] = True
    try:
        check_tie_held(pb.K, sp.vstack(rows, format="csr"), fixed, modes)
    except SingularSystemError as e:
        raise SingularSystemError(
            f"load step {label!r}: the contact state found {found} leaves a part of the "
            f"body free to move, so its displacement is not unique (a side that only the "
            f"interface holds, while Γ opens or slides): {hint}") from e
