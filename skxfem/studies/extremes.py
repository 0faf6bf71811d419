r"""The extremes table: what the solver does at the edges of its inputs (issue 11).

Each row of the table is one extreme input — Γ a hair's breadth from a node,
E = 10⁹, ν = 0.4999, ρ_n = 10⁻⁶ E/h, one cell across Γ, ... — and says what
happens, as a :class:`Row`: either the case is *solved* and one number
measures how well (with the tolerance it is held to), or it is *refused*
with the one-line message of the ValueError the library raises.  A row never
holds a NaN, and a solved row whose number misses its tolerance says so
(``outcome == "inaccurate"``), so nothing passes silently.

The accuracy of most rows is a *patch test*: uniaxial compression σ = -P e_d ⊗ e_d
(bottom on rollers, the top pressed) is in the discrete space of every cell
type, whatever Γ is, so the relative energy error of the solution
(:func:`skxfem.studies.convergence.energy_error` against the uniform strain C⁻¹σ)
must be round-off: any larger error is a wrong answer.  The scenes are built
by :func:`patch_scene`; the rows by the ``*_rows`` functions, one section of
this module per part of the table: Γ near nodes (:func:`position_rows`), the
numbers a scene carries (E, ν, ρ), the geometry (one cell, memory, slanted
and curved Γ, supports, small pieces), what is refused and the limits
accepted; :func:`table` gathers them all and :func:`markdown_rows` writes them.

>>> row = attempt("demo", "a refused case", "energy error", 1e-8,
...               lambda: (_ for _ in ()).throw(ValueError("no: fix the input")))
>>> row.outcome, row.message
('refused', 'no: fix the input')
"""
from __future__ import annotations

import itertools
import time
import warnings
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np
import scipy.sparse as sp

from ..contact.history import solve as contact_solve
from ..contact.newton import ContactConvergenceError
from ..cut import SnapWarning
from ..cut import cut as cut_mesh
from ..enrich import far_side_fraction, stiffness, xfem_space
from ..fem.cells import CELLS
from ..fem.exact import ExactPlate
from ..fem.material import NU_MAX, Material
from ..levelset import circle, plane, sphere
from ..linalg.saddle import independent_rows
from ..multipliers import coupling, interface_rule
from ..problem import constrained_dofs
from ..scene.benchmarks import P_MAX, exact_scene, paper_plate, strip
from ..scene.model import Box, Displacement, Scene, SurfaceLoad, resolve, rollers
from ..scene.parts import SIZE_RANGE
from ..solver import solve
from ..stabilised import multiplier_space
from .budget import DEFAULT_MAX_BYTES, check, estimate, format_bytes
from .convergence import energy_error, pressure_error
from .progress import Progress

__all__ = ["Row", "Conditioning", "attempt", "patch_scene", "uniform_strain", "patch_error",
           "OFFSETS", "position_rows", "conditioning", "CELL_TYPES", "MODULI", "POISSON",
           "RHO_FACTORS", "modulus_rows", "poisson_rows", "exact_strip_for", "friction_scene",
           "rho_rows", "one_cell_rows", "memory_scene", "largest", "memory_rows", "shape_rows",
           "UNSTABLE", "space_rows", "CROSSINGS", "support_rows", "PIECES", "piece_rows",
           "inclusion", "refused_rows", "limit_rows", "table", "markdown_rows"]

CELL_TYPES = CELLS
OFFSETS = (1e-14, 1e-10, 1e-6, 1e-3, 0.5)
"""Distances of Γ from a row of nodes, in units of h (:func:`position_rows`)."""
PATCH_TOL = 1e-8
"""The tolerance of a patch test: relative energy error (round-off is about 1e-13)."""
P = 1.0


@dataclass(frozen=True)
class Row:
    """One row of the extremes table.

    ``group`` (e.g. ``"position"``), ``case`` (what is extreme), ``outcome``
    (``"solved"``, ``"inaccurate"``: solved but ``value > tolerance``, or
    ``"refused"``), ``measure`` (what ``value`` is), ``value`` (``None`` when
    refused), ``tolerance``, ``message`` (the refusal, or a note), ``seconds``.
    """

    group: str
    case: str
    outcome: str
    measure: str
    value: float | None
    tolerance: float
    message: str
    seconds: float


def attempt(group: str, case: str, measure: str, tolerance: float,
            run: Callable[[], float | tuple[float, str]]) -> Row:
    """Run ``run()`` (the measured value, or ``(value, note)``) into a :class:`Row`.

    A :class:`~skxfem.cut.SnapWarning` (vertices near Γ, not on it, put on it) is noted.
    A ValueError (the library's refusals: bad input, a singular or nearly
    dependent system, a scene too large) or a
    :class:`~skxfem.contact.newton.ContactConvergenceError` becomes a refused
    row with its message; any other exception propagates, since it is a
    failure to explain.
    A non-finite value is a failure too.
    """
    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", SnapWarning)
        try:
            out = run()
        except (ValueError, ContactConvergenceError) as e:
            return Row(group, case, "refused", measure, None, tolerance, str(e),
                       time.perf_counter() - t0)
    value, note = out if isinstance(out, tuple) else (out, "")
    if any(issubclass(w.category, SnapWarning) for w in caught):
        snapped = "vertices near Γ put on it (cut.SNAP)"
        note = "; ".join(filter(None, (note, snapped)))
    value = float(value)
    if not np.isfinite(value):
        raise RuntimeError(f"{group} / {case}: the measured {measure} is {value}")
    outcome = "solved" if value <= tolerance else "inaccurate"
    return Row(group, case, outcome, measure, value, tolerance, note,
               time.perf_counter() - t0)


def patch_scene(mesh: Box, levelset, material: Material = Material(),
                space: str = "vital", law: str = "bonded", load: float = P) -> Scene:
    """Uniaxial compression of the box ``mesh`` (the unit box unless its ``size`` says
    otherwise): the patch test of every row.

    The bottom (``ymin`` in 2D, ``zmin`` in 3D) is on rollers, the rigid
    motions left are held at one (2D) or two (3D) bottom nodes, the top is
    pressed by ``load`` and the sides are free, so σ = -load e_d ⊗ e_d.

    >>> scene = patch_scene(Box(2, "quad"), plane((0, 0.6), (0, 1)))
    >>> scene.loads[0].boundary, scene.space
    ('ymax', 'vital')
    """
    dim = levelset.dim
    up = "xyz"[dim - 1]
    size = (mesh.size or (1.0,))[0]

    def at(*c):
        return lambda x: np.all([np.abs(x[i] - v) <= 1e-9 * size
                                 for i, v in enumerate(c)], axis=0)

    if dim == 2:
        fix = (Displacement(at(0.0, 0.0), {"x": 0.0}),)
    else:
        fix = (Displacement(at(0.0, 0.0, 0.0), {"x": 0.0, "y": 0.0}),
               Displacement(at(size, 0.0, 0.0), {"y": 0.0}))
    return Scene(mesh, levelset, material, (rollers(up + "min"),) + fix,
                 (SurfaceLoad(up + "max", pressure=load),), law, space, name="patch")


def uniform_strain(material: Material, dim: int, sigma: np.ndarray) -> np.ndarray:
    """The strain C⁻¹σ of a uniform stress (dim, dim), from ``material.stress``.

    >>> eps = uniform_strain(Material(1.0, 0.0), 2, np.diag([0.0, -1.0]))
    >>> eps.round(12).tolist()
    [[0.0, 0.0], [0.0, -1.0]]
    """
    pairs = [(i, j) for i in range(dim) for j in range(i, dim)]
    M = np.zeros((len(pairs), len(pairs)))
    for a, (i, j) in enumerate(pairs):
        e = np.zeros((dim, dim, 1))
        e[i, j, 0] = e[j, i, 0] = 1.0
        s = material.stress(e, dim)[..., 0]
        M[:, a] = [s[p, q] for p, q in pairs]
    x = np.linalg.solve(M, [sigma[p, q] for p, q in pairs])
    eps = np.zeros((dim, dim))
    for a, (i, j) in enumerate(pairs):
        eps[i, j] = eps[j, i] = x[a]
    return eps


def patch_error(scene: Scene, load: float = P) -> tuple[float, str]:
    """Solve a :func:`patch_scene` and return its relative energy error and a note.

    The note counts the multipliers removed as dependent and the enriched
    nodes the small-cut rule dropped (:func:`skxfem.enrich.xfem_space`).
    """
    result = solve(scene)
    dim = scene.dim
    sigma = np.zeros((dim, dim))
    sigma[-1, -1] = -load
    eps = uniform_strain(scene.material, dim, sigma)

    def strain(x):
        return np.broadcast_to(eps.reshape(dim, dim, *([1] * (x.ndim - 1))),
                               (dim, dim) + x.shape[1:])

    V = result.V
    dropped = V.cut.enriched.size - V.n_enr // dim
    note = f"{result.removed} dependent multipliers removed" if result.removed else ""
    if dropped:
        note += ("; " if note else "") + f"{dropped} enriched nodes dropped (sliver)"
    return energy_error(result, strain), note


def _patch_row(group: str, case: str, mesh: Box, levelset, tol: float = PATCH_TOL,
               **scene) -> Row:
    """The patch test (:func:`patch_error`) of ``mesh`` cut by ``levelset`` as a row;
    ``scene``: more keywords of :func:`patch_scene`."""
    return attempt(group, case, "energy error (patch)", tol,
                   lambda: patch_error(patch_scene(mesh, levelset, **scene)))


def _row_plane(cell: str, n: int, offset: float) -> tuple[Box, object]:
    """The unit box of ``n`` cells and Γ ``offset``·h above its middle row of nodes."""
    dim = _dim(cell)
    y0 = (n // 2) / n + offset / n
    point, normal = (0.5,) * (dim - 1) + (y0,), (0.0,) * (dim - 1) + (1.0,)
    return Box(n, cell), plane(point, normal)


def position_rows(cells=CELL_TYPES, offsets=OFFSETS, n: int = 4,
                  space: str = "vital") -> list[Row]:
    """Γ at ``offsets``·h from a row of nodes, through one node, along cell faces.

    For every cell type, the patch test (:func:`patch_error`) with Γ parallel
    to a row of nodes at each offset; then Γ slanted through a single node,
    and Γ lying on the faces of a row of cells (``offset`` 0).  ``n`` even.

    >>> rows = position_rows(["quad"], [0.5], n=2)
    >>> [(r.case, r.outcome) for r in rows][:1]
    [('quad, Γ at 0.5 h from a node row', 'solved')]
    """
    rows = []
    for cell in cells:
        for offset in offsets:
            mesh, psi = _row_plane(cell, n, offset)
            rows.append(_patch_row("position", f"{cell}, Γ at {offset:g} h from a node row",
                                   mesh, psi, space=space))
        dim = _dim(cell)
        node = (0.5,) * dim
        slant = plane(node, (0.3,) + (0.0,) * (dim - 2) + (1.0,))
        rows.append(_patch_row("position", f"{cell}, Γ through one node", Box(n, cell),
                               slant, space=space))
        mesh, psi = _row_plane(cell, n, 0.0)
        rows.append(_patch_row("position", f"{cell}, Γ along cell faces", mesh, psi,
                               space=space))
    return rows


@dataclass(frozen=True)
class Conditioning:
    """The 2-norm condition number of the Jacobi-scaled saddle matrix.

    ``fraction``: the smallest far-side fraction of an enriched node
    (:func:`skxfem.enrich.far_side_fraction`); ``with_rule``: with the
    small-cut rule (enrichment of fractions below ``sliver`` removed),
    ``without``: every node of a cut cell enriched (``None``: singular, an
    enriched unknown has no stiffness at all); ``dropped``: nodes the rule removed.
    """

    cell: str
    offset: float
    fraction: float
    with_rule: float
    without: float | None
    dropped: int


def _condition(scene: Scene, sliver: float) -> tuple[float | None, int, float]:
    """cond₂ of the scaled saddle matrix as :func:`skxfem.linalg.saddle.solve` factors it
    (``None``: singular, an unknown without stiffness), nodes dropped, least fraction."""
    scene, mesh = resolve(scene)
    (gamma,) = scene.interfaces   # the sliver scenes have one interface (sliver_rows)
    cut = cut_mesh(mesh, gamma.levelset)
    V = xfem_space(mesh, cut, scene.quadrature_order, sliver=sliver)
    K = stiffness(V, scene.material)
    D, _ = constrained_dofs(V, scene, mesh)
    lam_space = multiplier_space(gamma.space, mesh, cut)
    B_edges = coupling(V, interface_rule(mesh, cut), gamma.law)
    ncomp = B_edges.shape[0] // cut.points.shape[1]
    B = sp.kron(sp.identity(ncomp), lam_space.P, format="csr").T @ B_edges
    free = np.setdiff1d(np.arange(V.N), D)
    frac = float(far_side_fraction(mesh, cut)[cut.enriched].min())
    dropped = cut.enriched.size - V.n_enr // mesh.dim()
    diag = np.abs(K.diagonal()[free])
    if np.any(diag == 0):  # an enriched function whose far side has zero measure
        return None, dropped, frac
    s = 1.0 / np.sqrt(diag)
    Kf = sp.diags(s) @ K[free][:, free] @ sp.diags(s)
    Bf = sp.csr_matrix(B[:, free] @ sp.diags(s))
    Bk = Bf[independent_rows(Bf)]
    Bk = sp.diags(1.0 / abs(Bk).max(axis=1).toarray().ravel()) @ Bk
    A = sp.bmat([[Kf, Bk.T], [Bk, None]]).toarray()
    return float(np.linalg.cond(A)), dropped, frac


def conditioning(cells=CELL_TYPES, offsets=(1e-11, 1e-9, 1e-7, 1e-5, 1e-3, 1e-1, 0.5), n: int = 4,
                 space: str = "vital", sliver: float = 1e-8) -> list[Conditioning]:
    """Condition numbers with and without the small-cut rule, Γ at ``offsets``·h
    from a node row (the patch scene of :func:`position_rows`; dense, so small n).

    >>> r = conditioning(["tri"], [1e-9], n=2)[0]
    >>> r.dropped > 0, r.with_rule < 1e4, r.without   # without the rule: singular
    (True, True, None)
    """
    out = []
    for cell in cells:
        for offset in offsets:
            mesh, psi = _row_plane(cell, n, offset)
            scene = patch_scene(mesh, psi, space=space)
            with_rule, dropped, frac = _condition(scene, sliver)
            without = _condition(scene, 0.0)[0]
            out.append(Conditioning(cell, offset, frac, with_rule, without, dropped))
    return out


# -----------------------------------------------------------------------------
# Extremes of the numbers a scene carries: E, ν and the contact laws' ρ_n, ρ_τ.
# -----------------------------------------------------------------------------


MODULI = (1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9)
POISSON = (0.3, 0.45, 0.49, 0.499, 0.4999)
RHO_FACTORS = (1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9)
SCALE_TOL = 1e-8


def _loaded_strip(n: int, E: float, load: float):
    """:func:`skxfem.scenes.strip` (quadrilaterals) with modulus E and peak pressure ``load``."""
    base = strip(n, "quad")
    return replace(base, material=replace(base.material, E=E), loads=(SurfaceLoad(
        "ymax", pressure=lambda x: load * 4 * x[0] * (1 - x[0])),))


def _deviation(result, ref, u_factor: float, p_factor: float) -> float:
    """Largest relative deviation of u/u_factor and p/p_factor from ``ref``."""
    du = np.abs(result.U / u_factor - ref.U).max() / np.abs(ref.U).max()
    dp = np.abs(result.pressure / p_factor - ref.pressure).max() / np.abs(ref.pressure).max()
    return float(max(du, dp))


def modulus_rows(moduli=MODULI, n: int = 8) -> list[Row]:
    """E over ``moduli`` on the strip, loads scaled alike (u unchanged, p ∝ E) and
    unscaled (u ∝ 1/E): the relative deviation from the E = 1 solution, held to 1e-8.

    >>> rows = modulus_rows([1e6], n=2)
    >>> [r.outcome for r in rows]
    ['solved', 'solved']
    """
    ref = solve(_loaded_strip(n, 1.0, P_MAX))
    rows = []
    for E in moduli:
        rows.append(attempt("E", f"E = {E:g}, load scaled alike", "deviation from E = 1",
                            SCALE_TOL, lambda: _deviation(
                                solve(_loaded_strip(n, E, E * P_MAX)), ref, 1.0, E)))
        rows.append(attempt("E", f"E = {E:g}, load unscaled", "deviation from E = 1",
                            SCALE_TOL, lambda: _deviation(
                                solve(_loaded_strip(n, E, P_MAX)), ref, 1.0 / E, 1.0)))
    return rows


def exact_strip_for(material: Material, n: int = 8, cell: str = "quad"):
    """:func:`skxfem.scenes.exact_strip` for another ``material``: its loads and
    bottom displacement are those of :class:`skxfem.fem.exact.ExactPlate` for it."""
    sol = ExactPlate(material, 2, P_MAX)
    base = strip(n, cell)
    bottom = Displacement("ymin", {c: (lambda x, i=i: sol.displacement(x)[i])
                                   for i, c in enumerate("xy")})
    loads = (SurfaceLoad("ymax", pressure=sol.pressure),
             SurfaceLoad("xmin", pressure=sol.side_pressure),
             SurfaceLoad("xmax", pressure=sol.side_pressure))
    return replace(base, material=material, displacements=(bottom,), loads=loads,
                   name=f"exact_strip_{cell}_nu{material.nu:g}")


def _energy(material: Material, n: int, cell: str) -> float:
    sol = ExactPlate(material, 2, P_MAX)
    return energy_error(solve(exact_strip_for(material, n, cell)), sol.strain)


def poisson_rows(ratios=POISSON, n: int = 8, cells=("tri", "quad")) -> list[Row]:
    """ν over ``ratios`` (the first must be the reference, 0.3): the energy error
    against the exact solution, held to twice its value at the first ν: the first
    "inaccurate" row is where volumetric locking starts."""
    rows = []
    for cell in cells:
        first = _energy(Material(1.0, ratios[0]), n, cell)
        for nu in ratios:
            rows.append(attempt(
                "nu", f"{cell}, ν = {nu:g}", "energy error (exact)", 2 * first,
                lambda: (lambda e: (e, f"{e / first:.2f} × the error at ν = {ratios[0]:g}"))(
                    _energy(Material(1.0, nu), n, cell))))
    return rows


def friction_scene(n: int = 8, shear: float = 0.1):
    """The exact strip with Coulomb friction μ = 0.3 and a shear ``shear`` on the top:
    stick in the middle of Γ, slip near the ends where the pressure vanishes."""
    base = exact_strip_for(Material(1.0, 0.3), n)
    top = SurfaceLoad("ymax", traction=(shear, 0.0))
    return replace(base, law="coulomb", friction=0.3, loads=base.loads + (top,),
                   name="friction_strip")


def _tractions(step) -> np.ndarray:
    return np.column_stack([step.pressure, step.traction])


def rho_rows(factors=RHO_FACTORS, n: int = 8) -> list[Row]:
    """ρ_n and ρ_τ over ``factors`` × their default E/h, the other at its
    default, on :func:`friction_scene`: deviation of the interface tractions
    from those of the default ρ, and the Newton iterations."""
    scene = friction_scene(n)
    ref = contact_solve(scene)
    h, t_ref = ref.ops.h, _tractions(ref.steps[-1])
    defaults = {"rho_n": ref.law[0].rho_n, "rho_t": ref.law[0].rho_t}
    rows = []
    for key, name in (("rho_n", "ρ_n"), ("rho_t", "ρ_τ")):
        unit = "E/h"
        for k in factors:
            def run(key=key, k=k):
                r = contact_solve(replace(scene, **{key: k * defaults[key]}))
                step = r.steps[-1]
                dev = np.abs(_tractions(step) - t_ref).max() / np.abs(t_ref).max()
                slip = int(np.sum(step.status == 2))
                return dev, f"{step.newton.iterations} Newton iterations, {slip} slipping"
            rows.append(attempt("rho", f"{name} = {k:g} {unit} (h = {h:.3g})",
                                "deviation from default ρ", SCALE_TOL, run))
    return rows


# -----------------------------------------------------------------------------
# Extremes of the geometry: one cell, the largest mesh, slanted and curved Γ,
# Γ across a support, small pieces.
# -----------------------------------------------------------------------------


def _dim(cell: str) -> int:
    return 2 if cell in ("tri", "quad") else 3


def one_cell_rows(cells=CELL_TYPES) -> list[Row]:
    """One cell of each type across Γ (a plane at 0.55 of its height).

    >>> [r.outcome for r in one_cell_rows(["quad"])]
    ['solved']
    """
    rows = []
    for cell in cells:
        d = _dim(cell)
        psi = plane((0.5,) * (d - 1) + (0.55,), (0.0,) * (d - 1) + (1.0,))
        rows.append(_patch_row("size", f"{cell}, one cell across Γ", Box(1, cell), psi))
    return rows


def memory_scene(cell: str, n: int):
    """The strip (tri, quad) or the paper plate (hex, prism; tet: the plate's box of
    tetrahedra) with ``n`` cells per direction."""
    if cell in ("tri", "quad"):
        return strip(n, cell)
    if cell == "tet":
        base = paper_plate(n, "hex")
        return replace(base, mesh=replace(base.mesh, cell="tet"), name=f"paper_plate_tet_{n}")
    return paper_plate(n, cell)


def largest(cell: str, max_bytes: int = DEFAULT_MAX_BYTES, linear: str = "direct") -> int:
    """The largest n whose :func:`memory_scene` is estimated to fit ``max_bytes``
    with the ``linear`` solver.

    >>> largest("quad", 2**20) < largest("quad", 2**24)
    True
    >>> largest("hex", 2**30) < largest("hex", 2**30, linear="iterative")
    True
    """
    def fits(n):
        return estimate(memory_scene(cell, n), linear).bytes <= max_bytes

    lo, hi = 1, 2
    while fits(hi):
        lo, hi = hi, 2 * hi
    while hi - lo > 1:  # lo fits, hi does not
        mid = (lo + hi) // 2
        lo, hi = (mid, hi) if fits(mid) else (lo, mid)
    return lo


def memory_rows(cells=CELL_TYPES, max_bytes: int = DEFAULT_MAX_BYTES,
                solvers=("direct", "iterative")) -> list[Row]:
    """For each cell type and linear solver, the largest :func:`memory_scene` under
    ``max_bytes`` (estimated, :func:`skxfem.studies.budget.estimate`: not run) and
    the next one refused (:func:`skxfem.studies.budget.check`)."""
    rows = []
    for cell, linear in itertools.product(cells, solvers):
        n = largest(cell, max_bytes, linear)
        e = estimate(memory_scene(cell, n), linear)
        rows.append(attempt(
            "size", f"{cell}, largest n under {format_bytes(max_bytes)}: n = {n} ({linear})",
            "estimated bytes", max_bytes,
            lambda: (e.bytes, f"{format_bytes(e.bytes)}: {e}")))
        rows.append(attempt(
            "size", f"{cell}, n = {n + 1} ({linear})", "estimated bytes", max_bytes,
            lambda: check(memory_scene(cell, n + 1), max_bytes, linear=linear).bytes))
    return rows


def _shapes(dim: int) -> dict:
    """Named level sets of the unit square (cube): slanted, curved, at the boundary."""
    if dim == 2:
        return {"slanted 45°": plane((0.5, 0.53), (1.0, 1.0)),
                "circle inside": circle((0.5, 0.5), 0.3),
                "circle crossing the top": circle((0.5, 1.0), 0.37),
                "circle touching the bottom": circle((0.55, 0.3), 0.3)}
    return {"slanted 45°": plane((0.5, 0.5, 0.53), (1.0, 0.0, 1.0)),
            "sphere inside": sphere((0.5, 0.5, 0.5), 0.3),
            "sphere crossing the top": sphere((0.5, 0.5, 1.0), 0.37),
            "sphere touching the bottom": sphere((0.55, 0.45, 0.3), 0.3)}


def shape_rows(cells=CELL_TYPES, n2: int = 8, n3: int = 4, space: str = "vital") -> list[Row]:
    """The patch test with the interfaces of :func:`_shapes` on ``n2``/``n3`` cells a side.

    A plane Γ is held to round-off (:data:`PATCH_TOL`).  A
    curved Γ is cut into a polygon Γ_h, whose facet normals jump from cell to
    cell: the uniform stress is then not in the discrete problem (its
    traction σn_h is not a P1 multiplier), the patch test is not exact, and
    the error is the O(h) of the interface approximation: held to h.
    """
    rows = []
    for cell in cells:
        d = _dim(cell)
        n = n2 if d == 2 else n3
        for name, psi in _shapes(d).items():
            tol = PATCH_TOL if name.startswith("slanted") else 1.0 / n
            rows.append(_patch_row("shape", f"{cell}, {name} (h = 1/{n})", Box(n, cell), psi,
                                   tol, space=space))
    return rows


UNSTABLE = (("tri", "naive", 1e-3), ("tri", "naive", 0.5), ("quad", "naive", 1e-3),
            ("quad", "naive", 0.5), ("tet", "winner", 1e-6), ("tet", "vital", 1e-6))
"""(cell, space, offset) of :func:`space_rows`: where a space is nearly dependent, and
the same scenes with a space that is not."""


def space_rows(cases=UNSTABLE, n: int = 4) -> list[Row]:
    """The exact benchmark (:func:`skxfem.scenes.exact_scene`) of each (cell, space)
    with Γ at ``offset``·h above a node row: the L² pressure error against
    :mod:`skxfem.fem.exact` (held to 1, i.e. below the pressure itself), or the
    refusal of nearly dependent multipliers."""
    rows = []
    for cell, space_name, offset in cases:
        base = exact_scene(n, cell, space_name)
        d = _dim(cell)
        h = 1.0 / base.mesh.n[-1]
        psi = plane((0.0,) * (d - 1) + (2 * h + offset * h,), (0.0,) * (d - 1) + (1.0,))

        def run(scene=replace(base, levelset=psi)):
            sol = ExactPlate(scene.material, scene.dim)
            return pressure_error(solve(scene), sol.pressure).l2

        rows.append(attempt("position", f"{cell} {space_name}, exact, Γ at {offset:g} h "
                            f"from a node row", "pressure L2 error (exact)", 1.0, run))
    return rows


CROSSINGS = ("25°", "45°", "70°", "corner")
"""The planes of :func:`support_rows`: crossing the bottom at 25°, 45°, 70° to it,
and cutting off its corner at the origin (Σ xᵢ = 0.05)."""


def _crossing(dim: int, name: str):
    """The plane Γ of :data:`CROSSINGS` ``name`` in ``dim`` dimensions."""
    if name == "corner":
        return plane((0.05,) + (0.0,) * (dim - 1), (1.0,) * dim)
    x, slope = {"25°": (0.3, 0.47), "45°": (0.37, 1.0), "70°": (0.6, 2.75)}[name]
    tilt = (-slope, 0.31 * slope) if dim == 3 else (-slope,)
    return plane((x,) + (0.4,) * (dim - 2) + (0.0,), tilt + (1.0,))


def support_rows(cells=CELL_TYPES, n: int = 4, space: str = "vital") -> list[Row]:
    """The patch test with Γ crossing the bottom face, on rollers, at :data:`CROSSINGS`.

    A support holds the jump of a cut edge in its face at both ends, but only
    at the edge's point: the edge takes its neighbour's multiplier
    (:func:`skxfem.stabilised.extend_to_held`).  With no multiplier there the
    uniform traction left the space (energy error 1e-3 to 4e-2, issue 18).
    """
    rows = []
    for cell in cells:
        for name in CROSSINGS:
            psi = _crossing(_dim(cell), name)
            rows.append(_patch_row("support", f"{cell}, Γ crossing the supported bottom, "
                                   f"{name}", Box(n, cell), psi, space=space))
    return rows


PIECES = (0.05, 1e-3, 1e-6)
"""The sizes (Σ xᵢ = dim - size) of the corner pieces of :func:`piece_rows`."""


def piece_rows(cells=CELL_TYPES, sizes=PIECES, n: int = 4, space: str = "vital") -> list[Row]:
    """The patch test with Γ cutting a corner of ``size`` off the loaded top,
    inside one cell: a piece of the body that only the tie holds.  Its piece of
    Γ gets a multiplier per edge (:func:`skxfem.linalg.rigid.short_pieces`); one star
    of vital edges left it free to turn (refused as singular, issue 18)."""
    rows = []
    for cell in cells:
        d = _dim(cell)
        for size in sizes:
            psi = plane((d - size,) + (0.0,) * (d - 1), (1.0,) * d)
            rows.append(_patch_row("piece", f"{cell}, a corner of {size:g} cut off the "
                                   f"loaded end", Box(n, cell), psi, space=space))
    return rows


# -----------------------------------------------------------------------------
# What the library refuses, and the nearest inputs it accepts: both sides of every
# stated range.
# -----------------------------------------------------------------------------


def inclusion(law: str = "bonded") -> Scene:
    """The disc of radius 0.3 in the unit square of ``examples/inclusion.toml``:
    pinned at one corner, the bottom on rollers, squeezed from the top."""
    pin = Displacement(lambda x: (x[0] < 1e-9) & (x[1] < 1e-9), {"x": 0.0, "y": 0.0})
    return Scene(Box(8, "tri"), circle((0.5, 0.5), 0.3), Material(10.0, 0.25, "stress"),
                 (pin, Displacement("ymin", {"y": 0.0})),
                 (SurfaceLoad("ymax", traction=(0.0, lambda x: -0.5 - 0.5 * x[0])),),
                 law, name="inclusion")


def _made(build) -> float:
    """0 if ``build()`` is accepted (then the row is not refused, and says so)."""
    build()
    return 0.0


def _max_jump(scene) -> float:
    result = solve(scene)
    return result.max_jump if hasattr(result, "max_jump") else 0.0


def refused_rows() -> list[Row]:
    """The inputs the library refuses, each with its message (measure: none; a
    row that is not refused reports 0, or the max jump of what it solved): ν too
    close to 0.5 (:data:`~skxfem.fem.material.NU_MAX`), E outside
    :data:`~skxfem.fem.material.E_RANGE`, box lengths outside
    :data:`~skxfem.scene.parts.SIZE_RANGE`, a plane of zero normal, and a side of Γ
    left free to move (:func:`skxfem.linalg.rigid.check_held`: a disc tied by its
    normal jump alone turns, the strip's top slides along a bilateral Γ, a body
    without supports floats).

    >>> [r.outcome for r in refused_rows()][:2]
    ['refused', 'refused']
    """
    tie_top_free = replace(strip(4, "tri"), law="bilateral")
    floating = replace(strip(4, "quad"), displacements=())
    cases = [
        ("material", "ν = 0.49999999999", lambda: _made(lambda: Material(1.0, 0.49999999999))),
        ("material", "E = 1e300", lambda: _made(lambda: Material(1e300))),
        ("geometry", f"Box size {SIZE_RANGE[0] * 1e-250:g}",
         lambda: _made(lambda: Box(4, "quad", size=(SIZE_RANGE[0] * 1e-250,) * 2))),
        ("geometry", f"Box size {SIZE_RANGE[1] * 1e250:g}",
         lambda: _made(lambda: Box(4, "quad", size=(SIZE_RANGE[1] * 1e250,) * 2))),
        ("geometry", "plane normal (0, 0)", lambda: _made(lambda: plane((0, 0), (0, 0)))),
        ("rigid", "inclusion, bilateral tie", lambda: _max_jump(inclusion("bilateral"))),
        ("rigid", "inclusion, frictionless contact",
         lambda: _max_jump(inclusion("frictionless"))),
        ("rigid", "strip, bilateral tie, the top free in x", lambda: _max_jump(tie_top_free)),
        ("rigid", "strip without supports", lambda: _max_jump(floating)),
    ]
    return [attempt("refused", f"{what}: {case}", "-", 0.0, run) for what, case, run in cases]


def limit_rows(cells=CELL_TYPES, n: int = 4) -> list[Row]:
    """The nearest accepted inputs, under the patch test on every cell type:
    ν = :data:`~skxfem.fem.material.NU_MAX`, the box lengths at both ends of
    :data:`~skxfem.scene.parts.SIZE_RANGE`, a plane normal of size 1e200;
    and the bonded inclusion (its max jump, held to 1e-2 of its |u|)."""
    rows = []
    for cell in cells:
        d = _dim(cell)
        flat = (0.0,) * (d - 1) + (1.0,)
        middle = (0.5,) * (d - 1) + (0.53,)
        rows.append(_patch_row("limits", f"{cell}, ν = {NU_MAX}", Box(n, cell),
                               plane(middle, flat), material=Material(1.0, NU_MAX)))
        huge = plane(middle, tuple(1e200 * np.r_[(0.3,) + (0.0,) * (d - 2) + (1.0,)]))
        rows.append(_patch_row("limits", f"{cell}, plane normal of size 1e200", Box(n, cell),
                               huge))
        for size in SIZE_RANGE:
            sized = (0.5 * size,) * (d - 1) + (0.53 * size,)
            rows.append(_patch_row("limits", f"{cell}, Box size {size:g}",
                                   Box(n, cell, size=(size,) * d), plane(sized, flat)))

    def bonded():
        result = solve(inclusion("bonded"))
        return result.max_jump / np.abs(result.u_regions).max()

    rows.append(attempt("limits", "inclusion, bonded tie", "max jump / max |u|", 1e-2, bonded))
    return rows


# -----------------------------------------------------------------------------
# The whole extremes table of issue 11, and its Markdown form.
# -----------------------------------------------------------------------------


def table(cells=CELL_TYPES, progress: Progress | None = None) -> list[Row]:
    """Every row of the extremes table (about 25 s here), each section above in turn;
    ``progress`` (by default a :class:`~skxfem.studies.progress.Progress` that is on in
    a terminal only) reports each part."""
    parts = [("Γ near nodes", lambda: position_rows(cells) + space_rows()),
             ("E", modulus_rows), ("ν", poisson_rows), ("ρ", rho_rows),
             ("one cell, memory", lambda: one_cell_rows(cells) + memory_rows(cells)),
             ("shapes", lambda: shape_rows(cells)),
             ("supports, pieces", lambda: support_rows(cells) + piece_rows(cells)),
             ("refused, limits", lambda: refused_rows() + limit_rows(cells))]
    progress = progress or Progress(len(parts), "extremes")
    rows = []
    for name, make in parts:
        rows += make()
        progress.step(name)
    return rows


def markdown_rows(rows) -> str:
    """The rows as a Markdown table (for the book): every message in full.

    >>> print(markdown_rows([Row("E", "E = 1", "solved", "energy error", 1e-15, 1e-8, "", 0.1)]))
    | group | case | outcome | value | tolerance | message or note |
    |---|---|---|---|---|---|
    | E | E = 1 | solved | 1.00e-15 | 1e-08 |  |
    """
    lines = ["| group | case | outcome | value | tolerance | message or note |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        value = "-" if r.value is None else f"{r.value:.2e}"
        note = r.message.replace("|", "\\|").replace("\n", " ")
        lines.append(f"| {r.group} | {r.case} | {r.outcome} | {value} | {r.tolerance:.3g} "
                     f"| {note} |")
    return "\n".join(lines)
