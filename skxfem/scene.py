"""Problem set-ups: mesh, level set, material, boundary conditions, interface law.

A :class:`Scene` holds everything :func:`skxfem.solver.solve` needs.  Scenes are
frozen dataclasses, so ``dataclasses.replace(scene, law="bilateral")`` makes a
variant.  They are written in Python (see :mod:`skxfem.scenes`) or read from a
TOML file by :func:`skxfem.scenefile.load_scene` (schema there).

Its parts — :class:`Box`, :class:`Displacement`, :class:`SurfaceLoad`,
:func:`clamped`, :func:`rollers` — are defined in :mod:`skxfem.scene_parts` and
importable from here.  A formula string in a part is compiled for the scene's
dimension.

>>> from skxfem.levelset import plane
>>> scene = Scene(Box(3, "quad"), plane((0, 0.5), (0, 1)),
...               displacements=(clamped("ymin"),),
...               loads=(SurfaceLoad("ymax", pressure=1.0),))
>>> scene.law, scene.space          # the stable space unless asked otherwise
('bonded', 'vital')
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from skfem import Mesh

from . import meshes
from .boundary import dirichlet, load_facets, traction
from .expr import Expression
from .laws import CONTACT_LAWS, SPACES
from .laws import TIE_LAWS as LAWS
from .levelset import LevelSet
from .material import Material
from .scene_parts import CELLS, Box, Displacement, SurfaceLoad, clamped, rollers
from .scene_parts import is_number as _is_number

__all__ = ["Box", "Displacement", "SurfaceLoad", "Scene", "clamped", "rollers",
           "resolve_mesh", "dirichlet", "load_facets", "traction", "LAWS", "CONTACT_LAWS",
           "SPACES", "CELLS", "check_scene", "MAX_QUADRATURE_ORDER"]

MAX_QUADRATURE_ORDER = {2: 19, 3: 8}
"""The highest ``Scene.quadrature_order`` per dimension: scikit-fem's triangle
rules stop at 19 and its tetrahedron rules (the sub-cells of a cut 3D cell) at
9, which :mod:`skxfem.quadrature` takes for order 8."""

@dataclass(frozen=True)
class Scene:
    """One contact problem: what :func:`skxfem.solver.solve` takes.

    ``mesh`` is a :class:`Box`, a scikit-fem mesh or a mesh file path;
    ``law`` is one of ``LAWS`` (ties, :func:`skxfem.solver.solve`) or
    ``CONTACT_LAWS`` (unilateral, :func:`skxfem.contact.solve`), ``space`` one
    of ``SPACES``; ``quadrature_order`` ``None`` lets the solver choose.
    ``friction`` is Coulomb's μ (law ``coulomb``); ``rho_n``, ``rho_t`` the
    augmentation parameters of the contact laws (``None``: the defaults of
    :func:`skxfem.contact.parameters`); ``steps`` the load factors of a
    contact solve, in order.
    """

    mesh: Box | Mesh | str | Path
    levelset: LevelSet
    material: Material = Material()
    displacements: tuple[Displacement, ...] = ()
    loads: tuple[SurfaceLoad, ...] = ()
    law: str = "bonded"
    space: str = "vital"
    quadrature_order: int | None = None
    name: str = "scene"
    friction: float = 0.0
    rho_n: float | None = None
    rho_t: float | None = None
    steps: tuple[float, ...] = (1.0,)

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
        if self.law not in LAWS + CONTACT_LAWS:
            raise ValueError(f"Scene law must be one of {LAWS + CONTACT_LAWS}, "
                             f"got {self.law!r}")
        if not (_is_number(self.friction) and np.isfinite(self.friction)
                and self.friction >= 0):
            raise ValueError(f"Scene friction (Coulomb's mu) must be a number >= 0, "
                             f"got {self.friction!r}")
        for key in ("rho_n", "rho_t"):
            rho = getattr(self, key)
            if rho is not None and not (_is_number(rho) and np.isfinite(rho) and rho > 0):
                raise ValueError(f"Scene {key} must be a positive number or None (default "
                                 f"scaled by E/h), got {rho!r}")
        if (not isinstance(self.steps, (tuple, list)) or not self.steps
                or not all(_is_number(f) and np.isfinite(f) for f in self.steps)):
            raise ValueError(f"Scene steps must be a non-empty sequence of finite load "
                             f"factors, got {self.steps!r}")
        object.__setattr__(self, "steps", tuple(float(f) for f in self.steps))
        if self.space not in SPACES:
            raise ValueError(f"Scene space must be one of {SPACES}, got {self.space!r}")
        q, top = self.quadrature_order, MAX_QUADRATURE_ORDER.get(self.dim, 8)
        if q is not None and not (isinstance(q, int) and not isinstance(q, bool)
                                  and 1 <= q <= top):
            raise ValueError(f"Scene quadrature_order must be an integer from 1 to {top} in "
                             f"{self.dim}D, or None (the minimal exact rule, which affine "
                             f"cells need), got {q!r}")
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
    if isinstance(scene.mesh, Box):
        mesh = meshes.box(scene.mesh.n, scene.mesh.cell, scene.mesh.size)
    elif isinstance(scene.mesh, Mesh):
        mesh = scene.mesh
        meshes.check_mesh(mesh)
    else:
        mesh = meshes.read(scene.mesh)
    _check_dims(scene, mesh.dim())
    return mesh


def check_scene(scene) -> Scene:
    """``scene`` if it is a :class:`Scene`, else a TypeError that says how to get one.

    >>> check_scene("plate.toml")
    Traceback (most recent call last):
    ...
    TypeError: scene must be a skxfem.Scene, got str 'plate.toml': build one with ...
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a skxfem.Scene, got {type(scene).__name__} "
                        f"{scene!r:.60}: build one with skxfem.Scene(...), take a built-in "
                        f"one (skxfem.scenes.strip()) or read a scene file with "
                        f"skxfem.load_scene(path)")
    return scene
