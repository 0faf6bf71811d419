r"""The speed ↔ accuracy frontier: error against wall time for every choice a user makes.

A *method* is one choice of cell type, multiplier space, quadrature order
(``Scene.quadrature_order``), linear solver and mesh size.  :func:`sweep`
solves the exact benchmarks — the paper's plate (:func:`skxfem.scenes.exact_plate`
with one layer of cells along x) and the 2D strip (:func:`skxfem.scenes.exact_strip`)
— with every method of a :class:`Plan`, times the user's path (assemble and
solve, the errors excluded) and measures the relative energy error of u and the
relative L² error of the contact pressure against :mod:`skxfem.fem.exact`.
:func:`pareto` marks the points no other point beats in both time and error.

The solvers are the entries of :data:`SOLVERS`: a name and a function from a
scene to a :class:`~skxfem.result.Result` (assembly included).  The direct and
the iterative tie are there, and the contact rows: the same interface solved as
Coulomb contact (μ = 1: it sticks wherever it is pressed, and opens where the tie
pulls) by each linear solve, at another augmentation ρ and at a looser Newton
tolerance — the choices a contact user has; another is one entry;
:data:`PLANS` lists them per benchmark.

The energy error is always integrated with the same cell rule (order 4 on
uncut cells), whatever quadrature the method used, so that the measure does
not change with the method.

>>> pts = sweep(Plan("strip", ("quad",), ("vital",), (None,), ("direct",), (4,)))
>>> p = pts[0]
>>> p.method, p.dofs, p.energy < 0.3
('quad/vital/q-/direct', 80, True)
"""
from __future__ import annotations

import time
from dataclasses import dataclass, replace
from functools import partial
from typing import Callable

import numpy as np

from .. import contact
from ..contact.newton import TOL
from ..fem.exact import ExactPlate
from ..problem import assemble
from ..scene.benchmarks import exact_plate, exact_strip
from ..scene.model import Scene
from ..solver import Result, solve_problem
from .convergence import energy_error, pressure_error
from .progress import Progress

__all__ = ["SOLVERS", "CONTACT_SOLVERS", "Plan", "PLANS", "plans", "Point", "sweep", "pareto",
           "summary", "ERROR_ORDER"]

def _tie(scene: Scene, linear: str) -> Result:
    """The tie of ``scene``: assembled, then solved by the ``linear`` solve."""
    return solve_problem(assemble(scene), linear=linear)


def _coulomb(scene: Scene, linear: str, rho: float | None = None,
             tol: float = TOL) -> Result:
    """``scene``'s interface as Coulomb contact, μ = 1, each Newton step solved by
    ``linear``; ρ_n = ρ_τ = ``rho`` × E/h (None: the default E/h, h the cell
    height of a Box along its last axis), Newton to the relative residual ``tol``."""
    h = scene.mesh.size[-1] / scene.mesh.n[-1] if rho is not None else None
    aug = {} if rho is None else {"rho_n": rho * scene.material.E / h,
                                  "rho_t": rho * scene.material.E / h}
    return contact.solve(replace(scene, law="coulomb", friction=1.0, **aug), linear=linear,
                         tol=tol)


SOLVERS: dict[str, Callable[[Scene], Result]] = {
    "direct": partial(_tie, linear="direct"),
    "iterative": partial(_tie, linear="iterative"),
    "coulomb": partial(_coulomb, linear="direct"),
    "coulomb/iterative": partial(_coulomb, linear="iterative"),
    "coulomb/rho100": partial(_coulomb, linear="direct", rho=100.0),
    "coulomb/tol1e-6": partial(_coulomb, linear="direct", tol=1e-6),
}
"""The solves of a method: name → function(Scene) → Result, assembly included.  The
tie by each linear solve (:data:`skxfem.linalg.choice.LINEAR`; ``iterative``:
AMG-preconditioned projected CG, pyamg), and Coulomb contact (``coulomb``: direct
Newton steps; ``/iterative``: each step one tie; ``/rho100``: ρ = 100 E/h;
``/tol1e-6``: Newton stopped at 1e-6)."""
ERROR_ORDER = 4
"""Cell quadrature order of the energy error on uncut cells (the same for every method)."""


@dataclass(frozen=True)
class Plan:
    """The methods of one benchmark: every combination of the tuples.

    ``problem`` is ``"plate"`` (3D, cells hex/prism) or ``"strip"`` (2D,
    tri/quad); ``quadratures`` holds ``Scene.quadrature_order`` values
    (``None``: the minimal exact rule); ``sizes`` the n of the scenes.
    """

    problem: str
    cells: tuple
    spaces: tuple
    quadratures: tuple
    solvers: tuple
    sizes: tuple

    def __post_init__(self):
        if self.problem not in ("plate", "strip"):
            raise ValueError(f"Plan problem must be 'plate' or 'strip', got {self.problem!r}")
        unknown = [s for s in self.solvers if s not in SOLVERS]
        if unknown:
            raise ValueError(f"Plan solvers {unknown} are not in SOLVERS {tuple(SOLVERS)}")

    def scene(self, cell: str, space_name: str, quadrature, n: int):
        make = exact_plate if self.problem == "plate" else exact_strip
        kw = {"nx": 1} if self.problem == "plate" else {}
        return replace(make(n, cell, space=space_name, **kw), quadrature_order=quadrature)

    def methods(self):
        return [(c, s, q, v, n) for c in self.cells for s in self.spaces
                for q in self.quadratures for v in self.solvers for n in self.sizes]


CONTACT_SOLVERS = ("coulomb", "coulomb/iterative", "coulomb/rho100", "coulomb/tol1e-6")
"""The contact rows of the sweeps: the entries of :data:`SOLVERS` that solve Coulomb
contact."""

PLANS = {
    "quick": (Plan("plate", ("hex", "prism"), ("naive", "winner", "vital"), (None, 4),
                   ("direct",), (4, 8, 12, 16)),
              Plan("strip", ("tri", "quad"), ("naive", "winner", "vital"), (None, 4),
                   ("direct",), (8, 16, 32, 64)),
              Plan("plate", ("hex", "prism"), ("vital",), (None,), ("iterative",),
                   (4, 8, 12, 16)),
              Plan("strip", ("tri", "quad"), ("vital",), (None,), ("iterative",),
                   (8, 16, 32, 64)),
              Plan("plate", ("hex",), ("vital",), (None,), CONTACT_SOLVERS, (4, 8, 12))),
    "full": (Plan("plate", ("hex", "prism"), ("naive", "winner", "vital"), (None, 4),
                  ("direct", "iterative"), (4, 8, 12, 16, 20, 24)),
             Plan("strip", ("tri", "quad"), ("naive", "winner", "vital"), (None, 4),
                  ("direct", "iterative"), (8, 16, 32, 64, 128, 256)),
             Plan("plate", ("hex", "prism"), ("winner", "vital"), (None,), CONTACT_SOLVERS,
                  (4, 8, 12, 16))),
}
"""The sweeps of the book and ``skxfem reproduce --quick`` (``quick``: every
space and rule with the direct solve, the iterative one on the default
choices), and of ``skxfem reproduce`` (``full``: every combination)."""


def plans(quick: bool = True, sizes=None) -> tuple[Plan, ...]:
    """The plans of ``skxfem reproduce``: :data:`PLANS` ``quick`` or ``full``, or,
    with ``sizes`` (its ``--sizes``, for tests), both benchmarks at those sizes with
    the minimal rule and the direct solve only.

    >>> [(p.problem, p.sizes, p.quadratures) for p in plans(sizes=[4])]
    [('plate', (4,), (None,)), ('strip', (4,), (None,))]
    """
    if not sizes:
        return PLANS["quick" if quick else "full"]
    sizes = tuple(sorted(set(int(n) for n in sizes)))
    return tuple(replace(p, quadratures=(None,), sizes=sizes) for p in PLANS["quick"]
                 if p.solvers == ("direct",))


@dataclass(frozen=True)
class Point:
    """One solve: the method's choices, its size and cost, its two errors."""

    problem: str
    cell: str
    space: str
    quadrature: int | None
    solver: str
    n: int
    dofs: int
    seconds: float
    energy: float
    pressure: float

    @property
    def method(self) -> str:
        """``cell/space/q<order>/solver`` (``q-``: the minimal exact rule)."""
        q = "-" if self.quadrature is None else self.quadrature
        return f"{self.cell}/{self.space}/q{q}/{self.solver}"


def _measure(result: Result) -> tuple[float, float]:
    """Energy and L² pressure errors against :class:`skxfem.fem.exact.ExactPlate`."""
    sol = ExactPlate(result.scene.material, result.scene.dim)
    return (energy_error(result, sol.strain, ERROR_ORDER),
            pressure_error(result, sol.pressure).l2)


def sweep(plan: Plan, repeat: int = 1, progress: Progress | None = None) -> list[Point]:
    """Solve every method of ``plan``; the time is the least of ``repeat`` runs.

    ``progress``: one line per method (default: on in a terminal only).
    """
    methods = plan.methods()
    progress = progress or Progress(len(methods), plan.problem)
    points = []
    for cell, space_name, q, solver, n in methods:
        scene = plan.scene(cell, space_name, q, n)
        best = np.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            result = SOLVERS[solver](scene)
            best = min(best, time.perf_counter() - t0)
        energy, pressure = _measure(result)
        points.append(Point(plan.problem, cell, space_name, q, solver, n, result.n_dofs,
                            float(best), energy, pressure))
        progress.step(f"{cell} {space_name} q={q} {solver} n={n}")
    return points


def pareto(points, error: str = "energy") -> list[Point]:
    """The points on the front of ``error`` (``"energy"`` or ``"pressure"``) against
    time: none is both faster and more accurate.  Sorted by time.

    >>> P = lambda t, e: Point("strip", "tri", "vital", None, "direct", 8, 1, t, e, e)
    >>> [p.seconds for p in pareto([P(1, 0.5), P(2, 0.6), P(3, 0.1), P(0.5, 0.9)])]
    [0.5, 1, 3]
    """
    if error not in ("energy", "pressure"):
        raise ValueError(f"error must be 'energy' or 'pressure', got {error!r}")
    front, best = [], np.inf
    for p in sorted(points, key=lambda p: (p.seconds, getattr(p, error))):
        if getattr(p, error) < best:
            front.append(p)
            best = getattr(p, error)
    return front


def summary(points) -> dict:
    """Per method: its sizes, errors and times, and how many of its points are on
    each front (the front of its own benchmark).

    >>> P = lambda t, e: Point("strip", "tri", "vital", None, "direct", 8, 1, t, e, e)
    >>> summary([P(1.0, 0.5)])["tri/vital/q-/direct"]["on_energy_front"]
    1
    """
    problems = {p.problem for p in points}
    fronts = {e: {id(p) for pb in problems
                  for p in pareto([q for q in points if q.problem == pb], e)}
              for e in ("energy", "pressure")}
    out = {}
    for p in points:
        s = out.setdefault(p.method, {"problem": p.problem, "n": [], "energy": [],
                                      "pressure": [], "seconds": [], "on_energy_front": 0,
                                      "on_pressure_front": 0})
        s["n"].append(p.n)
        s["energy"].append(p.energy)
        s["pressure"].append(p.pressure)
        s["seconds"].append(p.seconds)
        s["on_energy_front"] += id(p) in fronts["energy"]
        s["on_pressure_front"] += id(p) in fronts["pressure"]
    return out
