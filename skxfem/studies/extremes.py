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
by :func:`patch_scene`; the rows by the ``*_rows`` functions of this module
and of :mod:`skxfem.studies.extremes_scales` (E, ν, ρ) and
:mod:`skxfem.studies.extremes_shapes` (one cell, memory, slanted and curved Γ).

>>> row = attempt("demo", "a refused case", "energy error", 1e-8,
...               lambda: (_ for _ in ()).throw(ValueError("no: fix the input")))
>>> row.outcome, row.message
('refused', 'no: fix the input')
"""
from __future__ import annotations

import time
import warnings
from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.sparse as sp

from ..contact.newton import ContactConvergenceError
from ..cut import SnapWarning
from ..cut import cut as cut_mesh
from ..enrich import far_side_fraction, stiffness, xfem_space
from ..fem.cells import CELLS
from ..fem.material import Material
from ..levelset import plane
from ..linalg.saddle import independent_rows
from ..multipliers import coupling, interface_rule
from ..problem import constrained_dofs
from ..scene.model import Box, Displacement, Scene, SurfaceLoad, resolve_mesh, rollers
from ..solver import solve
from ..stabilised import multiplier_space
from .convergence import energy_error

__all__ = ["Row", "Conditioning", "attempt", "patch_scene", "uniform_strain", "patch_error",
           "OFFSETS", "position_rows", "conditioning", "CELL_TYPES"]

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

    A :class:`~skxfem.cut.SnapWarning` (vertices on Γ moved off it) is noted.
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
        note = "; ".join(filter(None, (note, "vertices on Γ snapped off it (cut.SNAP)")))
    value = float(value)
    if not np.isfinite(value):
        raise RuntimeError(f"{group} / {case}: the measured {measure} is {value}")
    outcome = "solved" if value <= tolerance else "inaccurate"
    return Row(group, case, outcome, measure, value, tolerance, note,
               time.perf_counter() - t0)


def _at(*coords):
    return lambda x: np.all([np.abs(x[i] - c) < 1e-12 for i, c in enumerate(coords)], axis=0)


def patch_scene(mesh, levelset, material: Material = Material(), space: str = "vital",
                law: str = "bonded", load: float = P) -> Scene:
    """Uniaxial compression of the unit box: the patch test of every row.

    The bottom (``ymin`` in 2D, ``zmin`` in 3D) is on rollers, the rigid
    motions left are held at one (2D) or two (3D) bottom nodes, the top is
    pressed by ``load`` and the sides are free, so σ = -load e_d ⊗ e_d.

    >>> scene = patch_scene(Box(2, "quad"), plane((0, 0.6), (0, 1)))
    >>> scene.loads[0].boundary, scene.space
    ('ymax', 'vital')
    """
    dim = levelset.dim
    up = "xyz"[dim - 1]
    if dim == 2:
        fix = (Displacement(_at(0.0, 0.0), {"x": 0.0}),)
    else:
        fix = (Displacement(_at(0.0, 0.0, 0.0), {"x": 0.0, "y": 0.0}),
               Displacement(_at(1.0, 0.0, 0.0), {"y": 0.0}))
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


def _row_plane(cell: str, n: int, offset: float) -> tuple[Box, object]:
    """The unit box of ``n`` cells and Γ ``offset``·h above its middle row of nodes."""
    dim = 2 if cell in ("tri", "quad") else 3
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
            rows.append(attempt("position", f"{cell}, Γ at {offset:g} h from a node row",
                                "energy error (patch)", PATCH_TOL,
                                lambda: patch_error(patch_scene(mesh, psi, space=space))))
        dim = 2 if cell in ("tri", "quad") else 3
        node = (0.5,) * dim
        slant = plane(node, (0.3,) + (0.0,) * (dim - 2) + (1.0,))
        rows.append(attempt("position", f"{cell}, Γ through one node", "energy error (patch)",
                            PATCH_TOL, lambda: patch_error(
                                patch_scene(Box(n, cell), slant, space=space))))
        mesh, psi = _row_plane(cell, n, 0.0)
        rows.append(attempt("position", f"{cell}, Γ along cell faces", "energy error (patch)",
                            PATCH_TOL, lambda: patch_error(patch_scene(mesh, psi,
                                                                       space=space))))
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
    mesh = resolve_mesh(scene)
    cut = cut_mesh(mesh, scene.levelset)
    V = xfem_space(mesh, cut, scene.quadrature_order, sliver=sliver)
    K = stiffness(V, scene.material)
    D, _ = constrained_dofs(V, scene, mesh)
    lam_space = multiplier_space(scene.space, mesh, cut)
    B_edges = coupling(V, interface_rule(mesh, cut), scene.law)
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
