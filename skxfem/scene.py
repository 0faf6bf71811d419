"""Problem set-ups: mesh, level set, material, boundary conditions, interface law.

A :class:`Scene` holds everything :func:`skxfem.solver.solve` needs.  Scenes are
frozen dataclasses, so ``dataclasses.replace(scene, law="bilateral")`` makes a
variant.  They are written in Python (see :mod:`skxfem.scenes`) or read from a
TOML file by :func:`load_scene` (schema in :mod:`skxfem.scenefile`).

Boundaries are named (``"xmin"``, ``"xmax"``, ``"ymin"`` ... ``"zmax"`` or a name
stored in ``mesh.boundaries``) or given as a selection ``x -> bool``.  An imposed
:class:`Displacement` acts on the *nodes* of its boundary; a :class:`SurfaceLoad`
acts on its boundary *facets*.  The pressure is positive in compression: the
traction is t = -p n with n the outward unit normal.

A value (displacement component, pressure, traction component) is a number, a
callable ``x -> array`` or a formula string such as ``"4*x*(1 - x)"``, checked
as in scene files (:mod:`skxfem.expr`) and compiled for the scene's dimension.

>>> from skxfem.levelset import plane
>>> scene = Scene(Box(3, "quad"), plane((0, 0.5), (0, 1)),
...               displacements=(clamped("ymin"),),
...               loads=(SurfaceLoad("ymax", pressure=1.0),))
>>> scene.law, scene.space
('bonded', 'naive')
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path
from typing import Callable, Mapping, Union

import numpy as np
from skfem import Mesh

from .boundary import COMPONENTS, FACES, dirichlet, load_facets, traction
from .expr import Expression
from .levelset import LevelSet
from .material import Material
from .multipliers import LAWS, SPACES

__all__ = ["Box", "Displacement", "SurfaceLoad", "Scene", "clamped", "rollers",
           "resolve_mesh", "dirichlet", "load_facets", "traction", "load_scene",
           "LAWS", "SPACES", "CELLS"]

CELLS = {"tri": 2, "quad": 2, "tet": 3, "hex": 3, "prism": 3}
"""Cell types of :class:`Box` and their dimension."""

Value = Union[float, str, Callable[[np.ndarray], np.ndarray]]


def _is_number(v) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)


def _check_value(v, what: str) -> float | Callable:
    """A finite number (as float), a callable ``x -> array`` or a formula string
    (as a 3D :class:`~skxfem.expr.Expression`; :class:`Scene` fits it to its dim)."""
    if isinstance(v, str):
        try:
            return Expression(v, 3)
        except ValueError as e:
            raise ValueError(f"{what}: {e}") from None
    if callable(v):
        return v
    if not _is_number(v):
        raise TypeError(f"{what} must be a number, a formula string such as '4*x*(1 - x)' "
                        f"or a callable x -> array, got {v!r}")
    if not np.isfinite(v):
        raise ValueError(f"{what} must be finite, got {v!r}")
    return float(v)


def _check_boundary(b, what: str):
    if not (callable(b) or (isinstance(b, str) and b)):
        raise TypeError(f"{what} boundary must be a name such as 'xmin' or a "
                        f"callable x -> bool, got {b!r}")


@dataclass(frozen=True)
class Box:
    """A built-in structured mesh of a box, built by :func:`skxfem.meshes.box`.

    ``n`` cells per direction (an int or one int per direction), ``cell`` one of
    ``CELLS``, ``size`` the box lengths (default 1 in every direction).
    """

    n: int | tuple[int, ...]
    cell: str
    size: tuple[float, ...] | None = None

    def __post_init__(self):
        if self.cell not in CELLS:
            raise ValueError(f"Box cell must be one of {tuple(CELLS)}, got {self.cell!r}")
        n = (self.n,) * self.dim if _is_number(self.n) else self.n
        if (not isinstance(n, (tuple, list)) or len(n) != self.dim
                or not all(isinstance(k, (int, np.integer)) and not isinstance(k, bool)
                           and k >= 1 for k in n)):
            raise ValueError(f"Box n must be a positive integer or {self.dim} of them "
                             f"for cell {self.cell!r}, got {self.n!r}")
        object.__setattr__(self, "n", tuple(int(k) for k in n))
        if self.size is not None:
            if (not isinstance(self.size, (tuple, list)) or len(self.size) != self.dim
                    or not all(_is_number(s) and np.isfinite(s) and s > 0 for s in self.size)):
                raise ValueError(f"Box size must be {self.dim} positive numbers, "
                                 f"got {self.size!r}")
            object.__setattr__(self, "size", tuple(float(s) for s in self.size))

    @property
    def dim(self) -> int:
        return CELLS[self.cell]


@dataclass(frozen=True)
class Displacement:
    """Imposed displacement components on the nodes of a boundary.

    ``components`` maps ``"x"``/``"y"``/``"z"`` (or 0/1/2, or ``"all"``) to a number
    or a callable ``x -> array``; it is stored with the keys ``"x"``, ``"y"``,
    ``"z"`` or ``"all"``.

    >>> Displacement("xmin", {0: 0.0, "y": 1}).components
    {'x': 0.0, 'y': 1.0}
    """

    boundary: str | Callable[[np.ndarray], np.ndarray]
    components: Mapping[str | int, Value]

    def __post_init__(self):
        _check_boundary(self.boundary, "Displacement")
        if not isinstance(self.components, Mapping) or not self.components:
            raise TypeError("Displacement components must be a non-empty mapping such as "
                            f"{{'x': 0.0}}, got {self.components!r}")
        comps = {}
        for key, value in self.components.items():
            name = COMPONENTS[key] if key in (0, 1, 2) and not isinstance(key, bool) else key
            if name not in COMPONENTS + ("all",):
                raise ValueError(f"Displacement component {key!r} is not one of "
                                 "'x', 'y', 'z', 0, 1, 2, 'all'")
            comps[name] = _check_value(value, f"Displacement component {name!r}")
        if "all" in comps and len(comps) > 1:
            raise ValueError("Displacement components: use either 'all' or single components")
        object.__setattr__(self, "components", comps)


def clamped(boundary: str | Callable) -> Displacement:
    """All displacement components zero on ``boundary``."""
    return Displacement(boundary, {"all": 0.0})


def rollers(boundary: str) -> Displacement:
    """Normal displacement zero on an axis-aligned named face such as ``"xmin"``.

    >>> rollers("zmax").components
    {'z': 0.0}
    """
    if boundary not in FACES:
        raise ValueError(f"rollers needs an axis-aligned face {FACES}, got {boundary!r}")
    return Displacement(boundary, {boundary[0]: 0.0})


@dataclass(frozen=True)
class SurfaceLoad:
    """A pressure (positive in compression, t = -p n) or a traction vector on facets."""

    boundary: str | Callable[[np.ndarray], np.ndarray]
    pressure: Value | None = None
    traction: tuple[Value, ...] | None = None

    def __post_init__(self):
        _check_boundary(self.boundary, "SurfaceLoad")
        if (self.pressure is None) == (self.traction is None):
            raise ValueError("SurfaceLoad needs exactly one of pressure= or traction=")
        if self.pressure is not None:
            object.__setattr__(self, "pressure",
                               _check_value(self.pressure, "SurfaceLoad pressure"))
        else:
            if not isinstance(self.traction, (tuple, list)) or len(self.traction) not in (2, 3):
                raise TypeError("SurfaceLoad traction must be 2 or 3 components, "
                                f"got {self.traction!r}")
            object.__setattr__(self, "traction", tuple(
                _check_value(t, f"SurfaceLoad traction[{i}]")
                for i, t in enumerate(self.traction)))


@dataclass(frozen=True)
class Scene:
    """One contact problem: what :func:`skxfem.solver.solve` takes.

    ``mesh`` is a :class:`Box`, a scikit-fem mesh or a mesh file path;
    ``law`` is one of ``LAWS``, ``space`` one of ``SPACES``;
    ``quadrature_order`` ``None`` lets the solver choose.
    """

    mesh: Box | Mesh | str | Path
    levelset: LevelSet
    material: Material = Material()
    displacements: tuple[Displacement, ...] = ()
    loads: tuple[SurfaceLoad, ...] = ()
    law: str = "bonded"
    space: str = "naive"
    quadrature_order: int | None = None
    name: str = "scene"

    def __post_init__(self):
        if not isinstance(self.mesh, (Box, Mesh, str, Path)):
            raise TypeError(f"Scene mesh must be a Box, a skfem Mesh or a file path, "
                            f"got {type(self.mesh).__name__}")
        if not isinstance(self.levelset, LevelSet):
            raise TypeError("Scene levelset must be a skxfem.levelset.LevelSet, "
                            f"got {type(self.levelset).__name__}")
        if not isinstance(self.material, Material):
            raise TypeError(f"Scene material must be a Material, got {self.material!r}")
        for field, kind in (("displacements", Displacement), ("loads", SurfaceLoad)):
            items = getattr(self, field)
            if not isinstance(items, (tuple, list)) or not all(
                    isinstance(i, kind) for i in items):
                raise TypeError(f"Scene {field} must be a tuple of {kind.__name__}")
            object.__setattr__(self, field, tuple(items))
        if self.law not in LAWS:
            raise ValueError(f"Scene law must be one of {LAWS}, got {self.law!r}")
        if self.space not in SPACES:
            raise ValueError(f"Scene space must be one of {SPACES}, got {self.space!r}")
        q = self.quadrature_order
        if q is not None and not (isinstance(q, int) and not isinstance(q, bool) and q >= 1):
            raise ValueError(f"Scene quadrature_order must be a positive integer or None, "
                             f"got {q!r}")
        if not (isinstance(self.name, str) and self.name):
            raise ValueError(f"Scene name must be a non-empty string, got {self.name!r}")
        object.__setattr__(self, "displacements", tuple(
            _for_dim(d, self.dim, f"displacements[{k}]")
            for k, d in enumerate(self.displacements)))
        object.__setattr__(self, "loads", tuple(
            _for_dim(load, self.dim, f"loads[{k}]") for k, load in enumerate(self.loads)))
        if isinstance(self.mesh, (Box, Mesh)):
            _check_dims(self, self.mesh.dim if isinstance(self.mesh, Box) else self.mesh.dim())

    @property
    def dim(self) -> int:
        """The dimension of the problem (that of the level set)."""
        return self.levelset.dim


def _for_dim(item: Displacement | SurfaceLoad, dim: int, where: str):
    """A displacement or load whose formula strings evaluate on ``dim``-D points.

    >>> load = SurfaceLoad("ymax", pressure="4*x*(1 - x)")
    >>> load.pressure.dim, _for_dim(load, 2, "loads[0]").pressure.dim
    (3, 2)
    """
    def fit(v, what: str):
        if not isinstance(v, Expression) or v.dim == dim:
            return v
        try:
            return Expression(v.text, dim)
        except ValueError as e:
            raise ValueError(f"{where} {what}: {e}") from None

    if isinstance(item, Displacement):
        return replace(item, components={c: fit(v, f"component {c!r}")
                                         for c, v in item.components.items()})
    if item.pressure is not None:
        return replace(item, pressure=fit(item.pressure, "pressure"))
    return replace(item, traction=tuple(fit(v, f"traction[{i}]")
                                        for i, v in enumerate(item.traction)))


def _check_dims(scene: Scene, dim: int):
    """Raise if the level set, components or tractions do not fit a ``dim``-D mesh."""
    if scene.levelset.dim != dim:
        raise ValueError(f"Scene levelset {scene.levelset.name!r} is {scene.levelset.dim}D "
                         f"but the mesh is {dim}D")
    for k, d in enumerate(scene.displacements):
        if "z" in d.components and dim == 2:
            raise ValueError(f"displacements[{k}]: component 'z' does not exist on a 2D "
                             "mesh (allowed: 'x', 'y')")
    for k, load in enumerate(scene.loads):
        if load.traction is not None and len(load.traction) != dim:
            raise ValueError(f"loads[{k}]: traction has {len(load.traction)} components "
                             f"but the mesh is {dim}D")


def resolve_mesh(scene: Scene) -> Mesh:
    """Build, check or read the scene's mesh and check that the scene fits it."""
    from . import meshes

    if isinstance(scene.mesh, Box):
        mesh = meshes.box(scene.mesh.n, scene.mesh.cell, scene.mesh.size)
    elif isinstance(scene.mesh, Mesh):
        mesh = scene.mesh
        meshes.check_mesh(mesh)
    else:
        mesh = meshes.read(scene.mesh)
    _check_dims(scene, mesh.dim())
    return mesh


def load_scene(path: str | Path) -> Scene:
    """Read a scene from a TOML file; the schema is in :mod:`skxfem.scenefile`."""
    from .scenefile import load_scene as load  # scenefile builds on this module

    return load(path)
