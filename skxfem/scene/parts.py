"""The parts of a scene: the mesh box, imposed displacements, surface loads, interfaces.

Boundaries are named (``"xmin"``, ``"xmax"``, ``"ymin"`` ... ``"zmax"`` or a name
stored in ``mesh.boundaries``) or given as a selection ``x -> bool``.  An imposed
:class:`Displacement` acts on the *nodes* of its boundary; a :class:`SurfaceLoad`
acts on its boundary *facets*.  The pressure is positive in compression: the
traction is t = -p n with n the outward unit normal.

A value (displacement component, pressure, traction component) is a number, a
callable ``x -> array`` or a formula string such as ``"4*x*(1 - x)"``, checked
as in scene files (:mod:`skxfem.scene.expr`); :class:`skxfem.scene.Scene` compiles it
for its dimension.

>>> SurfaceLoad("ymax", pressure="4*x*(1 - x)").pressure.text
'4*x*(1 - x)'

An :class:`Interface` is one Γ of a scene with several: its level set, its law
and the law's parameters (a scene with one interface gives them to the
:class:`~skxfem.scene.Scene` itself).
"""
from __future__ import annotations

from dataclasses import dataclass, fields, replace
from typing import Callable, Mapping, Union

import numpy as np

from ..fem.cells import CELL_TYPES
from ..levelset import LevelSet
from ..linalg.scalars import is_integer, is_number
from .expr import Expression
from .laws import CONTACT_LAWS, FRICTION_LAWS, SPACES
from .laws import TIE_LAWS as LAWS

CRACK_ENRICHMENTS = ("geometric", "topological")
#: The name of a LevelSet not given one.
UNNAMED = next(f.default for f in fields(LevelSet) if f.name == "name")
"""The enrichments of a crack's tip a scene may ask for: those of
:data:`skxfem.crack.radius.ENRICHMENTS` (a floor above; tests/test_scene.py checks they agree),
the default first."""

__all__ = ["Box", "Displacement", "SurfaceLoad", "Interface", "clamped", "rollers", "CELLS",
           "SIZE_RANGE", "FRICTION_RANGE", "COMPONENTS", "FACES", "is_number", "check_law_fields",
           "check_friction"]

COMPONENTS = ("x", "y", "z")
FACES = ("xmin", "xmax", "ymin", "ymax", "zmin", "zmax")

CELLS = {name: c.dim for name, c in CELL_TYPES.items()}
"""Cell types of :class:`Box` and their dimension (:data:`skxfem.fem.cells.CELL_TYPES`)."""

SIZE_RANGE = (1e-50, 1e50)
"""The box lengths a :class:`Box` accepts.  Measured on the patch test of every
cell type (4 to 16 cells a side, with E from 1e-100 to 1e100): exact from 1e-60
to 1e60; beyond, the cut loses cut edges to underflowing products of ψ (from
1e-150 on quadrilaterals), the stiffness of tetrahedra, hexahedra and prisms
overflows or divides by zero (1e±80), or, on hexahedra at 1e-80, the answer is
silently wrong (energy error 6e-3).  Express the lengths in another unit."""

FRICTION_RANGE = (1e-10, 1e10)
"""The Coulomb μ accepted besides 0.  Below, the friction force μp nears the Newton
tolerance times the pressure (:data:`skxfem.contact.newton.TOL`, 1e-12), below what
the solve resolves: the law is frictionless to round-off (give 0).  Measured on
``examples/contact.toml``, where every point slides (|Λ| = 1): |Λ| is 1 to 2e-16
for μ = 1e-10 ... 1e-2 (to 1.4e-8 on the strip of ``tests/test_contact_laws.py``),
to 1e-4 only at 1e-12, and at μ = 5e-324 the product μp
underflowed and Λ = r/(μp) came out NaN.  Above 1e10 a pressed point sticks to
round-off (the same answer from 1e6 to 1e200); at 1e308 μp overflowed."""

Value = Union[float, str, Callable[[np.ndarray], np.ndarray]]


def _check_value(v, what: str) -> float | Callable:
    """A finite number (as float), a callable ``x -> array`` or a formula string
    (as a 3D :class:`~skxfem.scene.expr.Expression`; :class:`Scene` fits it to its dim)."""
    if isinstance(v, str):
        try:
            return Expression(v, 3)
        except ValueError as e:
            raise ValueError(f"{what}: {e}") from None
    if callable(v):
        return v
    if not is_number(v):
        raise TypeError(f"{what} must be a number, a formula string such as '4*x*(1 - x)' "
                        f"or a callable x -> array, got {v!r}")
    if not np.isfinite(v):
        raise ValueError(f"{what} must be finite, got {v!r}")
    return float(v)


def _check_boundary(b, what: str):
    if not (callable(b) or (isinstance(b, str) and b)):
        raise TypeError(f"{what} boundary must be a name such as 'xmin' or a "
                        f"callable x -> bool, got {b!r}")


def _check_where(where, boundary, what: str):
    """``where``: None, a condition string (a 3D boolean Expression) or a callable
    x -> bool, which keeps part of a *named* boundary."""
    if where is None:
        return None
    if not isinstance(boundary, str):
        raise ValueError(f"{what} where keeps part of a named boundary; the boundary is "
                         f"already a selection: put both conditions in it")
    if isinstance(where, str):
        try:
            return Expression(where, 3, boolean=True)
        except ValueError as e:
            raise ValueError(f"{what} where: {e}") from None
    if not callable(where):
        raise TypeError(f"{what} where must be a condition such as 'z > 2.2' or a callable "
                        f"x -> bool, got {where!r}")
    return where


@dataclass(frozen=True)
class Box:
    """A built-in structured mesh of a box, built by :func:`skxfem.fem.meshes.box`.

    ``n`` cells per direction (an int or one int per direction), ``cell`` one of
    ``CELLS``, ``size`` the box lengths (default 1 in every direction).
    """

    n: int | tuple[int, ...]
    cell: str
    size: tuple[float, ...] | None = None

    def __post_init__(self):
        if not isinstance(self.cell, str) or self.cell not in CELLS:
            raise ValueError(f"Box cell must be one of {tuple(CELLS)}, got {self.cell!r}")
        for key in ("n", "size"):       # numpy arrays as lists, numpy numbers as numbers
            v = getattr(self, key)
            if isinstance(v, np.ndarray):
                object.__setattr__(self, key, tuple(v.tolist()) if v.ndim == 1 else v.item()
                                   if v.ndim == 0 else v)
        n = (self.n,) * self.dim if is_number(self.n) else self.n
        if (not isinstance(n, (tuple, list)) or len(n) != self.dim
                or not all(is_integer(k) and k >= 1 for k in n)):
            raise ValueError(f"Box n must be a positive integer or {self.dim} of them "
                             f"for cell {self.cell!r}, got {self.n!r}")
        object.__setattr__(self, "n", tuple(int(k) for k in n))
        if self.size is not None:
            if (not isinstance(self.size, (tuple, list)) or len(self.size) != self.dim
                    or not all(is_number(s) and np.isfinite(s) and s > 0 for s in self.size)):
                raise ValueError(f"Box size must be {self.dim} positive numbers, "
                                 f"got {self.size!r}")
            object.__setattr__(self, "size", tuple(float(s) for s in self.size))
            lo, hi = SIZE_RANGE
            if not all(lo <= s <= hi for s in self.size):
                raise ValueError(f"Box size must lie in [{lo:.0e}, {hi:.0e}] (beyond, the "
                                 f"cut and the stiffness leave floating point), got "
                                 f"{self.size!r}: express the lengths in another unit")
            object.__setattr__(self, "size", tuple(float(s) for s in self.size))

    @property
    def dim(self) -> int:
        return CELLS[self.cell]


@dataclass(frozen=True)
class Displacement:
    """Imposed displacement components on the nodes of a boundary.

    ``where`` (a condition string such as ``"z > 2.2"`` or a callable x -> bool)
    keeps the nodes of a named boundary where it holds.  ``components`` maps
    ``"x"``/``"y"``/``"z"`` (or 0/1/2, or ``"all"``) to a number or a callable
    ``x -> array``; it is stored with the keys ``"x"``, ``"y"``, ``"z"`` or ``"all"``.

    >>> Displacement("xmin", {0: 0.0, "y": 1}).components
    {'x': 0.0, 'y': 1.0}
    """

    boundary: str | Callable[[np.ndarray], np.ndarray]
    components: Mapping[str | int, Value]
    where: str | Callable[[np.ndarray], np.ndarray] | None = None

    def __post_init__(self):
        _check_boundary(self.boundary, "Displacement")
        object.__setattr__(self, "where", _check_where(self.where, self.boundary,
                                                       "Displacement"))
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


def clamped(boundary: str | Callable, where=None) -> Displacement:
    """All displacement components zero on ``boundary`` (where ``where`` holds)."""
    return Displacement(boundary, {"all": 0.0}, where)


def rollers(boundary: str, where=None) -> Displacement:
    """Normal displacement zero on an axis-aligned named face such as ``"xmin"`` (where
    ``where`` holds).

    >>> rollers("zmax").components
    {'z': 0.0}
    """
    if boundary not in FACES:
        raise ValueError(f"rollers needs an axis-aligned face {FACES}, got {boundary!r}")
    return Displacement(boundary, {boundary[0]: 0.0}, where)


@dataclass(frozen=True)
class SurfaceLoad:
    """A pressure (positive in compression, t = -p n) or a traction vector on facets.

    ``where`` (a condition string or a callable x -> bool) keeps the facets of a named
    boundary whose midpoint it holds at: the xmax face above z = 2.2 is

    >>> SurfaceLoad("xmax", pressure=1.0, where="z > 2.2").where.text
    'z > 2.2'
    """

    boundary: str | Callable[[np.ndarray], np.ndarray]
    pressure: Value | None = None
    traction: tuple[Value, ...] | None = None
    where: str | Callable[[np.ndarray], np.ndarray] | None = None

    def __post_init__(self):
        _check_boundary(self.boundary, "SurfaceLoad")
        object.__setattr__(self, "where", _check_where(self.where, self.boundary,
                                                       "SurfaceLoad"))
        if (self.pressure is None) == (self.traction is None):
            raise ValueError("SurfaceLoad needs exactly one of pressure= or traction=")
        if self.pressure is not None:
            object.__setattr__(self, "pressure",
                               _check_value(self.pressure, "SurfaceLoad pressure"))
        else:
            if isinstance(self.traction, np.ndarray) and self.traction.ndim == 1:
                object.__setattr__(self, "traction", tuple(self.traction.tolist()))
            if not isinstance(self.traction, (tuple, list)) or len(self.traction) not in (2, 3):
                raise TypeError("SurfaceLoad traction must be 2 or 3 components, "
                                f"got {self.traction!r}")
            object.__setattr__(self, "traction", tuple(
                _check_value(t, f"SurfaceLoad traction[{i}]")
                for i, t in enumerate(self.traction)))


def check_friction(who: str, law: str, friction) -> None:
    """Refuse a ``coulomb`` law without ``friction`` (Coulomb's μ: no default
    changes the law) and a ``friction`` given to a law that has none
    (:data:`skxfem.scene.laws.FRICTION_LAWS`); ``who`` names the owner.

    >>> check_friction("Scene", "coulomb", None)
    Traceback (most recent call last):
    ...
    ValueError: Scene law 'coulomb' needs friction (Coulomb's mu, a number >= 0): ...
    """
    if friction is None:
        if law in FRICTION_LAWS:
            raise ValueError(f"{who} law {law!r} needs friction (Coulomb's mu, a number >= 0): "
                             f"give friction=0.3, say (friction=0 slides freely, as law "
                             f"'frictionless')")
        return
    if law not in FRICTION_LAWS:
        raise ValueError(f"{who} friction (Coulomb's mu) is taken by the law "
                         f"{' or '.join(map(repr, FRICTION_LAWS))} only; law {law!r} has no "
                         f"friction: leave friction unset (None), or use law 'coulomb'")
    if not (is_number(friction) and np.isfinite(friction) and friction >= 0):
        raise ValueError(f"{who} friction (Coulomb's mu) must be a number >= 0, "
                         f"got {friction!r}")
    lo, hi = FRICTION_RANGE
    if friction != 0 and not lo <= friction <= hi:
        raise ValueError(f"{who} friction (Coulomb's mu) must be 0 or in [{lo:g}, {hi:g}], "
                         f"got {friction!r}: " + (
                             "below, the friction force is round-off (give 0: no friction)"
                             if friction < lo else "above, a pressed point sticks to "
                             "round-off (use law 'adhesive', or a smaller mu)"))


def check_law_fields(who: str, law, space, friction, rho_n, rho_t) -> None:
    """Refuse a law, space, Coulomb μ or augmentation ρ that no solve takes; ``who``
    names the owner in the message (``"Scene"``, ``"Interface"``).

    >>> check_law_fields("Interface", "glued", "vital", None, None, None)
    Traceback (most recent call last):
    ...
    ValueError: Interface law must be one of ('bonded', 'bilateral', 'free', 'frictionless', ...
    """
    if law not in LAWS + CONTACT_LAWS:
        raise ValueError(f"{who} law must be one of {LAWS + CONTACT_LAWS}, got {law!r}")
    check_friction(who, law, friction)
    for key, rho in (("rho_n", rho_n), ("rho_t", rho_t)):
        if rho is not None and not (is_number(rho) and np.isfinite(rho) and rho > 0):
            raise ValueError(f"{who} {key} must be a positive number or None (default "
                             f"scaled by E/h), got {rho!r}")
    if space not in SPACES:
        raise ValueError(f"{who} space must be one of {SPACES}, got {space!r}")


@dataclass(frozen=True)
class Interface:
    """One interface Γ = {ψ = 0} of a scene with several, and its law.

    ``levelset`` ψ (Ω⁻ = {ψ < 0} on its side, n = ∇ψ/|∇ψ|); ``law`` one of
    ``LAWS`` (ties) or ``CONTACT_LAWS``; ``space`` its multiplier space;
    ``friction`` Coulomb's μ, required by law ``coulomb`` and refused by
    the others (``None``); ``rho_n``, ``rho_t`` the
    augmentations of a contact law (``None``: E/h).  The fields and their
    checks are those of a one-interface :class:`~skxfem.scene.Scene`.

    A crack: ``front`` a second level set φ; Γ is then {ψ = 0, φ < 0}, which ends
    inside the body at the front {ψ = φ = 0} (2D, any law; 3D on tetrahedra, law
    ``free``: :func:`check_crack_fields`);
    ``enrichment`` the tip enrichment (``"geometric"``: the nodes within a radius of
    the tip, or ``"topological"``: the tip cells'); ``enrichment_radius`` that radius
    r_e (None: one rule in 2D and 3D, :func:`skxfem.crack.radius.default_enrichment_radius`:
    0.2 of the mesh's diameter in 2D (at most three crack depths), of the crack's depth in
    3D, and at least 4/3 of the default
    interaction domain, 16/3 tip cells in 2D, 4 front cells in 3D);
    ``sif_radius`` the interaction integral's radius (None: 0.75 r_e and at least a few
    cells, :func:`skxfem.crack.sif.default_radius`).

    >>> from skxfem.levelset import plane
    >>> i = Interface(plane((0, 0.3), (0, 1)), law="frictionless")
    >>> i.law, i.space, i.friction
    ('frictionless', 'vital', None)
    >>> Interface(plane((0, 0.3), (0, 1)), law="coulomb", friction=0.4).friction
    0.4
    """

    levelset: LevelSet
    law: str = "bonded"
    space: str = "vital"
    friction: float | None = None
    rho_n: float | None = None
    rho_t: float | None = None
    front: LevelSet | None = None
    enrichment: str = "geometric"
    enrichment_radius: float | None = None
    sif_radius: float | None = None

    def __post_init__(self):
        if not isinstance(self.levelset, LevelSet):
            raise TypeError("Interface levelset must be a skxfem.levelset.LevelSet, "
                            f"got {type(self.levelset).__name__}")
        check_law_fields("Interface", self.law, self.space, self.friction, self.rho_n,
                         self.rho_t)
        for key in ("friction", "rho_n", "rho_t"):
            if getattr(self, key) is not None:
                object.__setattr__(self, key, float(getattr(self, key)))
        check_crack_fields(self)
        if self.front is not None and self.front.name == UNNAMED:
            object.__setattr__(self, "front", replace(self.front, name="phi"))  # not 'psi'
        for key in ("enrichment_radius", "sif_radius"):
            if getattr(self, key) is not None:
                object.__setattr__(self, key, float(getattr(self, key)))


def check_crack_fields(interface: Interface) -> None:
    """Refuse a crack's ``front``, ``enrichment``, ``enrichment_radius`` or ``sif_radius``
    that no solve takes.

    A front φ is a :class:`~skxfem.levelset.LevelSet` of ψ's dimension, with any law
    (``free`` faces, or a tie or contact on the faces up to the front): 2D
    (:mod:`skxfem.crack.faces`), or 3D on a tetrahedral mesh (:mod:`skxfem.crack.kind3d`,
    :mod:`skxfem.crack.faces3d`); ``enrichment`` is ``"geometric"`` or ``"topological"``
    (:mod:`skxfem.crack.space`); ``enrichment_radius`` (geometric only) and
    ``sif_radius`` positive numbers or None, and all of them only with a front.

    >>> from skxfem.levelset import plane
    >>> Interface(plane((0, 0.5), (0, 1)), law="coulomb", friction=0.3,
    ...           front=plane((0.5, 0), (1, 0))).law                 # contact on its faces
    'coulomb'
    >>> Interface(plane((0, 0.5), (0, 1)), sif_radius=0.2)
    Traceback (most recent call last):
    ...
    ValueError: Interface sif_radius, enrichment and enrichment_radius are those of a crack: ...
    """
    front = interface.front
    if interface.enrichment not in CRACK_ENRICHMENTS:
        raise ValueError(f"Interface enrichment must be one of {CRACK_ENRICHMENTS}, got "
                         f"{interface.enrichment!r}")
    r, r_e = interface.sif_radius, interface.enrichment_radius
    for key, v in (("sif_radius", r), ("enrichment_radius", r_e)):
        if v is not None and not (is_number(v) and np.isfinite(v) and v > 0):
            raise ValueError(f"Interface {key} must be a positive number or None (the "
                             f"default), got {v!r}")
    if front is None:
        if r is not None or r_e is not None or interface.enrichment != "geometric":
            raise ValueError("Interface sif_radius, enrichment and enrichment_radius are "
                             "those of a crack: give its front (a level set φ, the crack "
                             "where φ < 0)")
        return
    if r_e is not None and interface.enrichment != "geometric":
        raise ValueError("Interface enrichment_radius is the radius of geometric "
                         "enrichment: leave it out with enrichment='topological'")
    if not isinstance(front, LevelSet):
        raise ValueError(f"Interface front must be a skxfem.levelset.LevelSet (the crack "
                         f"where φ < 0), got {type(front).__name__}")
    if front.dim != interface.levelset.dim:
        raise ValueError(f"Interface front must have the dimension of the level set "
                         f"({interface.levelset.dim}), got {front.dim}")
