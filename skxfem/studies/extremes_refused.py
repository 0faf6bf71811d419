r"""What the library refuses, and why: the rows of the extremes table that must be refused.

Each row tries one input the library refuses (:func:`refused_rows`) and
records its one-line message; next to the limits it also solves the nearest
accepted input under the patch test (:func:`limit_rows`), so the table shows
both sides of every stated range:

* a nearly incompressible material, ν within 1e-6 of 0.5
  (:data:`skxfem.fem.material.NU_MAX`), and E outside :data:`skxfem.fem.material.E_RANGE`;
* box lengths outside :data:`skxfem.scene.parts.SIZE_RANGE`;
* a plane with a zero normal (one of any non-zero size is only a direction);
* a side of Γ that the supports and the law leave free to move
  (:func:`skxfem.linalg.rigid.check_held`): a disc tied by its normal jump alone (a
  bilateral tie, or frictionless contact) turns about its centre; the upper
  part of the strip slides along a bilateral Γ; a body without supports floats.

>>> [r.outcome for r in refused_rows()][:2]
['refused', 'refused']
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..fem.material import NU_MAX, Material
from ..levelset import circle, plane
from ..scene.benchmarks import strip
from ..scene.model import Box, Displacement, Scene, SurfaceLoad
from ..scene.parts import SIZE_RANGE
from ..solver import solve
from .extremes import CELL_TYPES, PATCH_TOL, Row, attempt, patch_error, patch_scene

__all__ = ["inclusion", "refused_rows", "limit_rows"]


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
    row that is not refused reports 0, or the max jump of what it solved)."""
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
        d = 2 if cell in ("tri", "quad") else 3
        flat = (0.0,) * (d - 1) + (1.0,)
        middle = (0.5,) * (d - 1) + (0.53,)
        rows.append(attempt("limits", f"{cell}, ν = {NU_MAX}", "energy error (patch)",
                            PATCH_TOL, lambda: patch_error(patch_scene(
                                Box(n, cell), plane(middle, flat),
                                material=Material(1.0, NU_MAX)))))
        huge = plane(middle, tuple(1e200 * np.r_[(0.3,) + (0.0,) * (d - 2) + (1.0,)]))
        rows.append(attempt("limits", f"{cell}, plane normal of size 1e200",
                            "energy error (patch)", PATCH_TOL,
                            lambda: patch_error(patch_scene(Box(n, cell), huge))))
        for size in SIZE_RANGE:
            rows.append(attempt("limits", f"{cell}, Box size {size:g}", "energy error (patch)",
                                PATCH_TOL, lambda: patch_error(_sized(cell, n, size))))

    def bonded():
        result = solve(inclusion("bonded"))
        return result.max_jump / np.abs(np.r_[result.u_minus, result.u_plus]).max()

    rows.append(attempt("limits", "inclusion, bonded tie", "max jump / max |u|", 1e-2, bonded))
    return rows


def _sized(cell: str, n: int, size: float) -> Scene:
    """:func:`~skxfem.studies.extremes.patch_scene` on the box of side ``size``."""
    d = 2 if cell in ("tri", "quad") else 3
    psi = plane((0.5 * size,) * (d - 1) + (0.53 * size,), (0.0,) * (d - 1) + (1.0,))
    base = patch_scene(Box(n, cell, size=(size,) * d), psi)

    def at(*c):
        return lambda x: np.all([np.abs(x[i] - v) <= 1e-9 * size for i, v in enumerate(c)],
                                axis=0)

    fix = (Displacement(at(0.0, 0.0), {"x": 0.0}),) if d == 2 else (
        Displacement(at(0.0, 0.0, 0.0), {"x": 0.0, "y": 0.0}),
        Displacement(at(size, 0.0, 0.0), {"y": 0.0}))
    return replace(base, displacements=base.displacements[:1] + fix)
