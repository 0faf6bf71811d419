r"""Extremes of the geometry: one cell, the largest mesh, slanted and curved Γ.

Rows of the extremes table (:mod:`skxfem.studies.extremes`):

* :func:`one_cell_rows`: a single cell of each type, cut through its middle,
  under the patch test (:func:`skxfem.studies.extremes.patch_error`);
* :func:`memory_rows`: the largest paper plate (hex, prism, tet) or strip
  (tri, quad) whose estimated memory (:func:`skxfem.studies.budget.estimate`) fits
  the default 4 GB limit with each linear solver, direct and iterative — an
  estimate, not a run — and the refusal of the next size by
  :func:`skxfem.studies.budget.check`;
* :func:`shape_rows`: Γ slanted at 45°, curved (a circle, a sphere) and
  touching or crossing the boundary, under the patch test;
* :func:`space_rows`: the naive and winner spaces near a node on the exact
  benchmark, where their multipliers become nearly dependent;
* :func:`support_rows`: Γ crossing the supported bottom face at three angles
  and cutting off its supported corner, under the patch test;
* :func:`piece_rows`: Γ cutting a small corner off the loaded end, a piece of
  the body that only the tie holds, under the patch test.

>>> [r.outcome for r in one_cell_rows(["quad"])]
['solved']
"""
from __future__ import annotations

import itertools
from dataclasses import replace

from ..fem.exact import ExactPlate
from ..levelset import circle, plane, sphere
from ..scene.benchmarks import exact_scene, paper_plate, strip
from ..scene.model import Box
from ..solver import solve
from .budget import DEFAULT_MAX_BYTES, check, estimate, format_bytes
from .convergence import pressure_error
from .extremes import CELL_TYPES, PATCH_TOL, Row, attempt, patch_error, patch_scene

__all__ = ["one_cell_rows", "memory_scene", "largest", "memory_rows", "shape_rows",
           "UNSTABLE", "space_rows", "CROSSINGS", "support_rows", "PIECES", "piece_rows"]


def _dim(cell: str) -> int:
    return 2 if cell in ("tri", "quad") else 3


def one_cell_rows(cells=CELL_TYPES) -> list[Row]:
    """One cell of each type across Γ (a plane at 0.55 of its height)."""
    rows = []
    for cell in cells:
        d = _dim(cell)
        psi = plane((0.5,) * (d - 1) + (0.55,), (0.0,) * (d - 1) + (1.0,))
        rows.append(attempt("size", f"{cell}, one cell across Γ", "energy error (patch)",
                            PATCH_TOL, lambda: patch_error(patch_scene(Box(1, cell), psi))))
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
    """For each cell type and linear solver, the largest mesh under ``max_bytes``
    and the next one refused."""
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

    A plane Γ is held to round-off (:data:`~skxfem.studies.extremes.PATCH_TOL`).  A
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
            rows.append(attempt("shape", f"{cell}, {name} (h = 1/{n})", "energy error (patch)",
                                tol, lambda: patch_error(patch_scene(Box(n, cell), psi,
                                                                     space=space))))
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
            rows.append(attempt("support", f"{cell}, Γ crossing the supported bottom, {name}",
                                "energy error (patch)", PATCH_TOL,
                                lambda: patch_error(patch_scene(Box(n, cell), psi,
                                                                space=space))))
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
            rows.append(attempt("piece", f"{cell}, a corner of {size:g} cut off the loaded end",
                                "energy error (patch)", PATCH_TOL,
                                lambda: patch_error(patch_scene(Box(n, cell), psi,
                                                                space=space))))
    return rows
