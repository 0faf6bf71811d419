"""Problem set-ups: mesh, level set, material, boundary conditions, interface law.

A :class:`Scene` holds everything :func:`skxfem.solver.solve` needs.  Scenes are
frozen dataclasses, so ``dataclasses.replace(scene, law="bilateral")`` makes a
variant.  They are written in Python (see :mod:`skxfem.scenes`) or read from a
TOML file by :func:`skxfem.scene.file.load_scene` (schema there).

Its parts — :class:`Box`, :class:`Displacement`, :class:`SurfaceLoad`,
:func:`clamped`, :func:`rollers` — are defined in :mod:`skxfem.scene.parts` and
importable from here.  A formula string in a part is compiled for the scene's
dimension.

>>> from skxfem.levelset import plane
>>> scene = Scene(Box(3, "quad"), plane((0, 0.5), (0, 1)),
...               displacements=(clamped("ymin"),),
...               loads=(SurfaceLoad("ymax", pressure=1.0),))
>>> scene.law, scene.space          # the stable space unless asked otherwise
('bonded', 'vital')

**Interfaces.** Every scene holds its interfaces as a tuple, ``Scene.interfaces``,
an :class:`Interface` each (its level set, law, space, μ and ρ); everything below
the scene reads them there, and a scene with one interface is the case of a tuple
of one.  ``Scene(mesh, levelset, law=...)`` is the short form of one interface:
it builds ``interfaces=(Interface(levelset, law, ...),)`` at once and keeps its
fields readable (``scene.law``, ``scene.levelset``, ...).  ``Scene(mesh,
interfaces=(Interface(ψ₁, law=...), Interface(ψ₂, ...)))`` gives each Γ its
own, and leaves the short fields unset (None).  Their Γ must not cross or
touch: :func:`skxfem.problem.assemble` refuses a mesh cell that two of them cut.

>>> two = Scene(Box(3, "quad"), interfaces=(Interface(plane((0, 0.3), (0, 1))),
...                                          Interface(plane((0, 0.7), (0, 1)), "bilateral")))
>>> [i.law for i in two.interfaces], [i.law for i in scene.interfaces]
(['bonded', 'bilateral'], ['bonded'])

A scene is checked when it is built; :func:`resolve` builds or reads its mesh
once, checks that the scene fits it and returns a :class:`Resolved` scene, which
:func:`skxfem.problem.assemble`, :func:`skxfem.lbb.inf_sup` and the solvers take
as they take a scene (they resolve a scene given once, at the top).
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from skfem import Mesh

from ..fem import meshes
from ..fem.material import Material
from ..levelset import LevelSet
from ..linalg.scalars import is_integer
from ..linalg.scalars import is_number as _is_number
from .boundary import dirichlet, load_facets, traction
from .expr import Expression
from .laws import CONTACT_LAWS, SPACES
from .laws import TIE_LAWS as LAWS
from .magnitudes import check_magnitudes
from .parts import (
    CELLS,
    Box,
    Displacement,
    Interface,
    SurfaceLoad,
    _check_value,
    check_law_fields,
    clamped,
    rollers,
)
from .settings import Solver

__all__ = ["Box", "Displacement", "SurfaceLoad", "Interface", "Scene", "clamped", "rollers",
           "resolve_mesh", "dirichlet", "load_facets", "traction", "LAWS", "CONTACT_LAWS",
           "SPACES", "CELLS", "check_scene", "MAX_QUADRATURE_ORDER", "Solver", "MAX_STEPS",
           "check_steps", "Resolved", "resolve"]

MAX_STEPS = 1000
"""The most load steps a contact solve takes (``Scene.steps``, a scene file's ``steps``, a
``history``).  Each step is at least one linear solve and one entry of ``result.json``:
10 000 steps of ``examples/contact.toml`` took 152 s and 100 000 about 25 minutes, for
increments no law needs (a load path is a few states; give fewer, larger steps)."""


def check_steps(n: int, what: str) -> None:
    """Refuse a history of more than :data:`MAX_STEPS` load steps, naming ``what``.

    >>> check_steps(1001, "steps")
    Traceback (most recent call last):
    ...
    ValueError: steps has 1001 load steps, more than 1000 (skxfem.scene.MAX_STEPS): ...
    """
    if n > MAX_STEPS:
        raise ValueError(f"{what} has {n} load steps, more than {MAX_STEPS} "
                         f"(skxfem.scene.MAX_STEPS): each is a solve and an entry of the "
                         f"results; a load path needs a few states: give fewer, larger steps")


MAX_QUADRATURE_ORDER = {2: 19, 3: 8}
"""The highest ``Scene.quadrature_order`` per dimension: scikit-fem's triangle
rules stop at 19 and its tetrahedron rules (the sub-cells of a cut 3D cell) at
9, which :mod:`skxfem.fem.quadrature` takes for order 8."""

class _ShortForm(tuple):
    """The interfaces a scene built from its short form (``levelset``, ``law``, ...):
    a tuple of one, marked so that ``replace(scene, law=...)`` builds it anew."""


@dataclass(frozen=True)
class Scene:
    """One contact problem: what :func:`skxfem.solver.solve` takes.

    ``mesh`` is a :class:`Box`, a scikit-fem mesh or a mesh file path;
    ``law`` is one of ``LAWS`` (ties, :func:`skxfem.solver.solve`) or
    ``CONTACT_LAWS`` (unilateral, :func:`skxfem.contact.solve`), ``space`` one
    of ``SPACES`` (left ``None``, they are ``bonded`` and ``vital``);
    ``quadrature_order`` ``None`` lets the solver choose.
    ``friction`` is Coulomb's μ, required by law ``coulomb`` and refused by
    the laws without friction (leave it ``None``); ``rho_n``, ``rho_t`` the
    augmentation parameters of the contact laws (``None``: the defaults of
    :func:`skxfem.contact.parameters`); ``steps`` the load history of a
    contact solve, in order: load factors (the scene's loads and imposed
    displacements scaled) or load states (scenes, each with its own loads,
    imposed displacements and law: a scene file's ``[[step]]`` tables), as
    ``history=`` of :func:`skxfem.contact.solve`; ``solver`` how it is solved (a
    :class:`~skxfem.scene.settings.Solver`: ``linear``, ``linear_tol``,
    ``max_iter``, a scene file's ``[solver]`` table), which the keywords of
    :func:`skxfem.solve` override.

    ``interfaces``: several interfaces, an :class:`Interface` each (its level
    set, law, space, μ and ρ), given instead of ``levelset`` and the law's
    fields (module notes).

    ``material_plus``: the material of Ω⁺ = {ψ > 0}, then ``material`` is that of
    Ω⁻ (``None``: ``material`` on both sides; one interface only).

    ``body_force``: a volume force b (F/L³: gravity is (0, -ρg) in 2D, (0, 0, -ρg)
    in 3D), ``dim`` values, each a number, a formula or a callable x -> array;
    ``None``: none.  Scaled by the load factors as the loads are.
    """

    mesh: Box | Mesh | str | Path
    levelset: LevelSet | None = None
    material: Material = Material()
    displacements: tuple[Displacement, ...] = ()
    loads: tuple[SurfaceLoad, ...] = ()
    law: str | None = None
    space: str | None = None
    quadrature_order: int | None = None
    name: str = "scene"
    friction: float | None = None
    rho_n: float | None = None
    rho_t: float | None = None
    steps: tuple[float | Scene, ...] = (1.0,)
    interfaces: tuple[Interface, ...] | None = None
    solver: Solver = Solver()
    body_force: tuple | None = None
    material_plus: Material | None = None

    def __post_init__(self):
        if not isinstance(self.mesh, (Box, Mesh, str, Path)):
            raise TypeError(f"Scene mesh must be a Box, a skfem Mesh or a file path, "
                            f"got {type(self.mesh).__name__}")
        if self.levelset is not None or self.interfaces is None or isinstance(
                self.interfaces, _ShortForm):
            self._short_form()
        else:
            self._check_interfaces()
        if not isinstance(self.material, Material):
            raise TypeError(f"Scene material must be a Material, got {self.material!r}")
        if self.material_plus is not None:
            if not isinstance(self.material_plus, Material):
                raise TypeError(f"Scene material_plus must be a Material (that of Ω⁺) or "
                                f"None, got {self.material_plus!r:.80}")
            if len(self.interfaces) > 1:
                raise ValueError("Scene material_plus: a material per side of Γ is for a "
                                 "scene with one interface; with several, the regions are "
                                 "more than two (give one material)")
            if self.interfaces[0].front is not None:
                raise ValueError("Scene material_plus: a crack (an interface with a front) "
                                 "splits no region, so it has no side to give a material; "
                                 "a crack between two materials is not modelled (its near-tip "
                                 "field is not the Williams field of its K): give one material")
            if self.material_plus.plane != self.material.plane:
                raise ValueError(f"Scene material_plus plane {self.material_plus.plane!r} "
                                 f"differs from material's {self.material.plane!r}: a 2D "
                                 f"body is plane strain or plane stress throughout")
        for field, kind in (("displacements", Displacement), ("loads", SurfaceLoad)):
            items = getattr(self, field)
            if not isinstance(items, (tuple, list)) or not all(
                    isinstance(i, kind) for i in items):
                raise TypeError(f"Scene {field} must be a tuple of {kind.__name__}")
            object.__setattr__(self, field, tuple(items))
        if not isinstance(self.solver, Solver):
            raise TypeError(f"Scene solver must be a skxfem.Solver (linear, linear_tol, "
                            f"max_iter), got {self.solver!r:.80}")
        if isinstance(self.steps, np.ndarray) and self.steps.ndim == 1:
            object.__setattr__(self, "steps", tuple(self.steps.tolist()))
        if (not isinstance(self.steps, (tuple, list)) or not self.steps
                or not all(isinstance(f, Scene) or (_is_number(f) and np.isfinite(f))
                           for f in self.steps)):
            raise ValueError(f"Scene steps must be a non-empty sequence of finite load "
                             f"factors or of load states (Scenes), got {self.steps!r:.200}")
        check_steps(len(self.steps), "Scene steps")
        object.__setattr__(self, "steps", tuple(f if isinstance(f, Scene) else float(f)
                                                for f in self.steps))
        q, top = self.quadrature_order, MAX_QUADRATURE_ORDER.get(self.dim, 8)
        if q is not None and not (is_integer(q) and 1 <= q <= top):
            raise ValueError(f"Scene quadrature_order must be an integer from 1 to {top} in "
                             f"{self.dim}D, or None (the minimal exact rule, which affine "
                             f"cells need), got {q!r}")
        if q is not None:
            object.__setattr__(self, "quadrature_order", int(q))
        if not (isinstance(self.name, str) and self.name):
            raise ValueError(f"Scene name must be a non-empty string, got {self.name!r}")
        object.__setattr__(self, "displacements", tuple(
            _for_dim(d, self.dim, f"displacements[{k}]")
            for k, d in enumerate(self.displacements)))
        object.__setattr__(self, "loads", tuple(
            _for_dim(load, self.dim, f"loads[{k}]") for k, load in enumerate(self.loads)))
        if self.body_force is not None:
            object.__setattr__(self, "body_force", _body_force(self.body_force, self.dim))
        if isinstance(self.mesh, (Box, Mesh)):
            _check_dims(self, self.mesh.dim if isinstance(self.mesh, Box) else self.mesh.dim())

    def _short_form(self):
        """The checks of the short form of one interface, and the tuple it builds."""
        if not isinstance(self.levelset, LevelSet):
            raise TypeError("Scene levelset must be a skxfem.levelset.LevelSet, "
                            f"got {type(self.levelset).__name__} (several interfaces: "
                            f"give interfaces=(Interface(...), ...) instead)")
        if self.interfaces is not None and not isinstance(self.interfaces, _ShortForm):
            raise ValueError("Scene got both a levelset and interfaces: give either "
                             "levelset= (one interface, its law in law=) or interfaces=("
                             "Interface(levelset, law=...), ...), not both")
        object.__setattr__(self, "law", "bonded" if self.law is None else self.law)
        object.__setattr__(self, "space", "vital" if self.space is None else self.space)
        check_law_fields("Scene", self.law, self.space, self.friction, self.rho_n, self.rho_t)
        for key in ("friction", "rho_n", "rho_t"):   # numpy's numbers as Python's
            if getattr(self, key) is not None:
                object.__setattr__(self, key, float(getattr(self, key)))
        object.__setattr__(self, "interfaces", _ShortForm((Interface(
            self.levelset, self.law, self.space, self.friction, self.rho_n, self.rho_t),)))

    def _check_interfaces(self):
        """The checks of ``interfaces`` (several interfaces, module notes)."""
        items = self.interfaces
        if not isinstance(items, (tuple, list)) or not all(
                isinstance(i, Interface) for i in items):
            raise TypeError(f"Scene interfaces must be a tuple of skxfem.Interface, "
                            f"got {items!r:.80}")
        if not items:
            raise ValueError("Scene interfaces is empty: give one Interface per interface "
                             "(or a levelset for a scene with one)")
        object.__setattr__(self, "interfaces", tuple(items))
        given = [k for k in ("law", "space", "friction", "rho_n", "rho_t")
                 if getattr(self, k) is not None]
        if given:
            raise ValueError(f"Scene {', '.join(given)}: with interfaces, each Interface "
                             f"has its own law, space, friction, rho_n and rho_t; give "
                             f"them there (Interface(levelset, law=..., friction=...))")
        dims = {i.levelset.dim for i in items}
        if len(dims) > 1:
            raise ValueError("Scene interfaces mix 2D and 3D level sets: "
                             + ", ".join(f"interfaces[{k}] {i.levelset.name!r} is "
                                         f"{i.levelset.dim}D" for k, i in enumerate(items)))

    @property
    def dim(self) -> int:
        """The dimension of the problem (that of the level sets)."""
        return self.interfaces[0].levelset.dim

    def given_interfaces(self, items) -> dict:
        """The fields that give this scene the interfaces ``items`` in place of its own,
        for ``dataclasses.replace(scene, **scene.given_interfaces(items))`` (the short
        form's fields unset).

        >>> from skxfem.levelset import plane
        >>> s = Scene(Box(3, "quad"), plane((0, 0.5), (0, 1)))
        >>> t = replace(s, **s.given_interfaces((Interface(s.levelset, "bilateral"),)))
        >>> t.law, [i.law for i in t.interfaces]
        (None, ['bilateral'])
        """
        return {"levelset": None, "law": None, "space": None, "friction": None,
                "rho_n": None, "rho_t": None, "interfaces": tuple(items)}

    def label(self, k: int) -> str:
        """How a message names interface ``k``: ``"interfaces[1] 'y - 0.7'"``, or ``""``
        for the one interface of a scene with one (a message then says "the level set").
        The one place the wording depends on the count; nothing else does."""
        if len(self.interfaces) == 1:
            return ""
        return f"interfaces[{k}] {self.interfaces[k].levelset.name!r}"

    def materials(self) -> tuple[Material, Material]:
        """The materials of Ω⁻ and Ω⁺ (the same one unless ``material_plus``)."""
        return self.material, self.material_plus or self.material

    def alone(self, k: int) -> Scene:
        """The scene with its interface ``k`` only (a one-interface scene, the
        same mesh, material, supports, loads and steps).

        >>> from skxfem.levelset import plane
        >>> s = Scene(Box(3, "quad"), interfaces=(Interface(plane((0, 0.3), (0, 1))),
        ...           Interface(plane((0, 0.7), (0, 1)), "frictionless")))
        >>> s.alone(1).law, s.alone(1).levelset.name == s.interfaces[1].levelset.name
        ('frictionless', True)
        """
        if not -len(self.interfaces) <= k < len(self.interfaces):
            raise IndexError(f"the scene has {len(self.interfaces)} interface(s), "
                             f"no interface {k}")
        i = self.interfaces[k]
        return replace(self, levelset=i.levelset, law=i.law, space=i.space,
                       friction=i.friction, rho_n=i.rho_n, rho_t=i.rho_t, interfaces=None)


def _body_force(force, dim: int) -> tuple:
    """``force`` as a tuple of ``dim`` values (numbers, callables, formulas for ``dim``).

    >>> _body_force(np.array([0, -9.81]), 2)
    (0.0, -9.81)
    """
    if isinstance(force, np.ndarray) and force.ndim == 1:
        force = tuple(force.tolist())
    if not isinstance(force, (tuple, list)) or len(force) != dim:
        raise ValueError(f"Scene body_force must be {dim} values (a vector in F/L³, such "
                         f"as gravity (0, -rho*g) in 2D), got {force!r:.80}")
    out = []
    for i, v in enumerate(force):
        v = _check_value(v, f"Scene body_force[{i}]")
        if isinstance(v, Expression):
            try:
                v = Expression(v.text, dim)
            except ValueError as e:
                raise ValueError(f"Scene body_force[{i}]: {e}") from None
        out.append(v)
    return tuple(out)


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

    if isinstance(item.where, Expression) and item.where.dim != dim:
        try:
            item = replace(item, where=Expression(item.where.text, dim, boolean=True))
        except ValueError as e:
            raise ValueError(f"{where} where: {e}") from None
    if isinstance(item, Displacement):
        return replace(item, components={c: fit(v, f"component {c!r}")
                                         for c, v in item.components.items()})
    if item.pressure is not None:
        return replace(item, pressure=fit(item.pressure, "pressure"))
    return replace(item, traction=tuple(fit(v, f"traction[{i}]")
                                        for i, v in enumerate(item.traction)))


def _check_dims(scene: Scene, dim: int):
    """Raise if the level set, components or tractions do not fit a ``dim``-D mesh."""
    for k, i in enumerate(scene.interfaces):
        if i.levelset.dim != dim and isinstance(scene.interfaces, _ShortForm):
            raise ValueError(f"Scene levelset {i.levelset.name!r} is {i.levelset.dim}D "
                             f"but the mesh is {dim}D")
        if i.levelset.dim != dim:
            raise ValueError(f"Scene interfaces[{k}] level set {i.levelset.name!r} is "
                             f"{i.levelset.dim}D but the mesh is {dim}D")
    for k, d in enumerate(scene.displacements):
        if "z" in d.components and dim == 2:
            raise ValueError(f"displacements[{k}]: component 'z' does not exist on a 2D "
                             "mesh (allowed: 'x', 'y')")
    for k, load in enumerate(scene.loads):
        if load.traction is not None and len(load.traction) != dim:
            raise ValueError(f"loads[{k}]: traction has {len(load.traction)} components "
                             f"but the mesh is {dim}D")


def resolve_mesh(scene: Scene) -> Mesh:
    """Build, check or read the scene's mesh and check that the scene fits it: its
    dimension, and loads and imposed displacements the solve handles
    (:func:`skxfem.scene.magnitudes.check_magnitudes`)."""
    if isinstance(scene.mesh, Box):
        mesh = meshes.box(scene.mesh.n, scene.mesh.cell, scene.mesh.size)
    elif isinstance(scene.mesh, Mesh):
        mesh = scene.mesh
        meshes.check_mesh(mesh)
    else:
        mesh = meshes.read(scene.mesh)
    _check_dims(scene, mesh.dim())
    check_magnitudes(scene, mesh)
    return mesh


@dataclass(frozen=True)
class Resolved:
    """A scene with its mesh built, read or checked once (:func:`resolve`): what the
    steps below :func:`skxfem.solve` take, so that none resolves it again.  It
    unpacks as ``scene, mesh = resolved``."""

    scene: Scene
    mesh: Mesh

    def __iter__(self):
        return iter((self.scene, self.mesh))


def resolve(scene: Scene | Resolved, mesh: Mesh | None = None) -> Resolved:
    """The scene checked (:func:`check_scene`) with its mesh resolved
    (:func:`resolve_mesh`), once; a :class:`Resolved` scene is returned as it is.
    ``mesh``: the mesh of the scene, already resolved (a load state of a solve: the
    scene is checked against it, not built again).

    >>> from skxfem.levelset import plane
    >>> r = resolve(Scene(Box(2, "quad"), plane((0, 0.5), (0, 1))))
    >>> scene, mesh = r
    >>> int(mesh.nvertices), resolve(r) is r
    (9, True)
    """
    if isinstance(scene, Resolved):
        return scene
    scene = check_scene(scene)
    if mesh is None:
        return Resolved(scene, resolve_mesh(scene))
    _check_dims(scene, mesh.dim())
    check_magnitudes(scene, mesh)
    return Resolved(scene, mesh)


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
