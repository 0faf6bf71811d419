"""The largest loads and imposed displacements a solve handles in double precision.

One check for Python scenes and scene files alike (:func:`check_magnitudes`):
every value of a load (pressure, traction component) and of an imposed
displacement, a number, a formula or a callable, is evaluated where it acts —
a load at the nodes of its facets, a displacement at its nodes — and refused
with a one-line ValueError naming it when

* a load exceeds :data:`MAX_MAGNITUDE`, or the displacements it gives, about
  |p| L / E (L the largest side of the body), do;
* an imposed displacement exceeds :data:`MAX_SHIFT` times L;
* a value is NaN or infinite there (a formula such as ``exp(1000*y)``).

:func:`skxfem.scene.model.resolve_mesh` runs it on every scene it resolves, so
``skxfem.solve`` refuses ``SurfaceLoad("ymax", pressure=1e200)`` before solving,
as ``skxfem run`` does; :func:`skxfem.scene.file.load_scene` runs it when reading,
naming the tables as the file does (``[[load]] #2``).

>>> from skxfem.scene.model import Box, Scene, SurfaceLoad
>>> from skxfem.levelset import plane
>>> s = Scene(Box(2, "quad"), plane((0, 0.5), (0, 1)),
...           loads=(SurfaceLoad("ymax", pressure="exp(400*y)"),))
>>> check_magnitudes(s, Box(2, "quad"))
Traceback (most recent call last):
...
ValueError: loads[0] pressure: exp(400*y) reaches 5.22e+173 at (0, 1), which is beyond the ...
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..fem import meshes
from .boundary import COMPONENTS, select_facets, select_nodes
from .parts import Box, Displacement, SurfaceLoad

if TYPE_CHECKING:
    from .model import Scene

__all__ = ["MAX_MAGNITUDE", "MAX_SHIFT", "BUILT_BOX", "check_magnitudes", "body_size"]

BUILT_BOX = 10_000
"""A :class:`Box` of at most this many squares or cubes is built to evaluate formulas
(and, by :mod:`skxfem.scene.file`, to check ``where`` selections) before it is solved."""

MAX_MAGNITUDE = 1e150
"""The largest load, and displacement from a load, a scene may give.  Measured: the
strip (E = 1) solves with pressure = 1e154; at 1e155 the norms of the saddle solve
overflow (a sum of squares above 1.8e308); 1e150 leaves a factor 10⁴ for the
square root of the number of unknowns."""
MAX_SHIFT = 1000
"""The largest imposed displacement, in sizes of the body.  Measured: a corner of
``examples/inclusion.toml`` moved by 1e6 (n = 8), 1e5 (n = 32), 1e4 (n = 64) breaks
the balance check of the multipliers (1e-8); 1e3 holds for n = 8 ... 128."""


def body_size(mesh) -> float:
    """The largest side of the body's bounding box (a :class:`Box` or a mesh)."""
    if isinstance(mesh, Box):
        return max(mesh.size or (1.0,))
    return float(np.ptp(mesh.p, axis=1).max())


def _values(item, x: np.ndarray) -> list[tuple[str, object, np.ndarray]]:
    """(key, value as given, values at the points ``x``) of a load or displacement."""
    if isinstance(item, SurfaceLoad):
        given = ({"pressure": item.pressure} if item.pressure is not None else
                 {f"traction[{i}]": v for i, v in enumerate(item.traction)})
    else:
        given = {("x, y, z" if k == "all" else k): v for k, v in item.components.items()}
    out = []
    for key, v in given.items():
        with np.errstate(all="ignore"):
            values = np.asarray(v(x) if callable(v) else v, dtype=float)
        out.append((key, v, np.broadcast_to(values, x.shape[1:]) if values.ndim else values))
    return out


def _text(v) -> str:
    return getattr(v, "text", None) or getattr(v, "__name__", None) or "the value"


def _is(what: str, v) -> str:
    """``what`` followed by "is" (a number) or ", which is" (a formula's value)."""
    return f"{what} is" if isinstance(v, (int, float)) else f"{what}, which is"


def _worst(where: str, key: str, v, values: np.ndarray, x: np.ndarray) -> tuple[float, str]:
    """The largest |value| and its description (where it is reached); a ValueError
    if a value is NaN or infinite."""
    values = np.atleast_1d(values)
    if values.size == 0:
        return 0.0, ""
    if not np.all(np.isfinite(values)):
        i = int(np.flatnonzero(~np.isfinite(values))[0])
        raise ValueError(f"{where} {key}: {_text(v)} is {values[i]} at "
                         f"({', '.join(f'{c:.3g}' for c in x[:, i])}); give a finite value")
    i = int(np.abs(values).argmax())
    if isinstance(v, (int, float)):
        return abs(float(values[i])), f"{float(v):g}"
    return abs(float(values[i])), (f"{_text(v)} reaches {values[i]:.3g} at "
                                   f"({', '.join(f'{c:.3g}' for c in x[:, i])})")


def check_magnitudes(scene: Scene, mesh=None, names: tuple[list, list] | None = None) -> None:
    """Refuse the loads and imposed displacements of ``scene`` that the solve cannot
    handle in double precision (module notes).

    ``mesh``: a scikit-fem mesh, or a :class:`Box` (built if it is small, else only
    the values given as numbers are checked), ``None``: ``scene.mesh`` as it is
    (a Box or a Mesh; a path: only the numbers, against its own size unknown, are
    skipped).  ``names``: the names of the displacements and of the loads in the
    messages (default ``displacements[k]``, ``loads[k]``).
    """
    mesh = scene.mesh if mesh is None else mesh
    if isinstance(mesh, Box) and math.prod(mesh.n) <= BUILT_BOX:
        mesh = meshes.box(mesh.n, mesh.cell, mesh.size)
    if not (isinstance(mesh, Box) or hasattr(mesh, "p")):
        return
    length = body_size(mesh)
    E = min(m.E for m in scene.materials())
    if names is None:
        names = ([f"displacements[{k}]" for k in range(len(scene.displacements))],
                 [f"loads[{k}]" for k in range(len(scene.loads))])
    for where, item in zip(names[1], scene.loads):
        for key, v, values, x in _evaluated(mesh, item, where):
            size, what = _worst(where, key, v, values, x)
            if size > MAX_MAGNITUDE:
                raise ValueError(f"{where} {key}: {_is(what, v)} beyond the largest load the "
                                 f"solver handles, {MAX_MAGNITUDE:g} in magnitude; scale "
                                 f"the units")
            if size * length / E > MAX_MAGNITUDE:
                raise ValueError(f"{where} {key}: {what} with E = {E:g} on a body of size "
                                 f"{length:g} gives displacements of about |p| L / E = "
                                 f"{size * length / E:.3g}, beyond the largest magnitude the "
                                 f"solver handles, {MAX_MAGNITUDE:g}; scale the units")
    if scene.body_force is not None and not isinstance(mesh, Box):
        x = mesh.p
        for i, v in enumerate(scene.body_force):
            with np.errstate(all="ignore"):
                values = np.broadcast_to(np.asarray(v(x) if callable(v) else v, dtype=float),
                                         x.shape[1:])
            size, what = _worst("body_force", f"[{i}]", v, values, x)
            if size * length > MAX_MAGNITUDE or size * length ** 2 / E > MAX_MAGNITUDE:
                raise ValueError(f"body_force[{i}]: {_is(what, v)} a force per volume "
                                 f"whose load on the body, |b| L = {size * length:.3g}, or "
                                 f"displacements, |b| L² / E = {size * length ** 2 / E:.3g}, "
                                 f"are beyond the largest magnitude the solver handles, "
                                 f"{MAX_MAGNITUDE:g}; scale the units")
    for where, item in zip(names[0], scene.displacements):
        for key, v, values, x in _evaluated(mesh, item, where):
            size, what = _worst(where, key, v, values, x)
            if size > MAX_SHIFT * length:
                raise ValueError(f"{where} {key}: {_is(what, v)} more than {MAX_SHIFT:g} times "
                                 f"the size of the body ({length:g}); linear elasticity is "
                                 f"a theory of small displacements, and a larger imposed one "
                                 f"drowns the strains in round-off: give it in the units of "
                                 f"the mesh")


def _evaluated(mesh, item: Displacement | SurfaceLoad, where: str):
    """(key, value, values, points) of ``item``: at its nodes on a mesh (a load: the
    nodes of its facets); on an unbuilt :class:`Box`, its numbers only."""
    if isinstance(mesh, Box):
        x = np.zeros((mesh.dim, 1))
        return [(k, v, vals, x) for k, v, vals in _values(item, x)
                if isinstance(v, (int, float))]
    if isinstance(item, SurfaceLoad):
        nodes = np.unique(mesh.facets[:, select_facets(mesh, item.boundary, where,
                                                         item.where)])
    else:
        nodes = select_nodes(mesh, item.boundary, where, item.where)
    x = mesh.p[:, nodes]
    dim = mesh.dim()
    return [(k, v, vals, x) for k, v, vals in _values(item, x)
            if k not in COMPONENTS[dim:]]
