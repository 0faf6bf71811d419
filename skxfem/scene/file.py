'''Scene files: a :class:`~skxfem.scene.Scene` written in TOML.

A scene file never runs code: formulas are strings checked by
:mod:`skxfem.scene.expr` (numbers, x, y, z, pi, + - * / **, functions such as sqrt, abs,
sin, cos, exp; selections may also use comparisons and and/or/not).  Every key is
checked; an unknown key or a wrong type is refused with an error naming the key.
The schema in short (all of it, with units: ``skxfem schema``, :data:`SCHEMA`)::

    name = "plate"                     # optional, default: the file name

    [mesh]                             # exactly one of:
    box = {n = [4, 4, 5], cell = "hex", size = [1, 1, 1]}  # tri quad tet hex prism
    # file = "plate.msh"               # any meshio format, relative to this file

    [levelset]                         # exactly one of (Ω⁻ = {ψ < 0}):
    plane = {point = [0, 0, 0.5], normal = [0, 0, 1]}       # normal points into Ω⁺
    # circle = {center = [0.5, 0.5], radius = 0.3}         # 2D meshes
    # sphere = {center = [0.5, 0.5, 0.5], radius = 0.3}    # 3D meshes
    # expr = "z - 0.5 - 0.2*x"

    [material]                         # optional; defaults E = 1, nu = 0.3
    E = 1.0
    nu = 0.3
    plane = "strain"                   # or "stress" (2D only)
    # plus = {E = 10.0}                # a side's own: Ω⁺ (plus) or Ω⁻ (minus)

    [body_force]                       # optional: a volume force (F/L³), e.g. gravity
    force = [0, 0, -1e-5]

    [[displacement]]                   # any number; on the nodes of a boundary
    boundary = "zmin"                  # a face xmin..zmax, or where = "x < 1e-9"
    kind = "clamped"                   # or "rollers", or components:
    # x = 0.0                          # a number or a formula such as "0.01*y"

    [[load]]                           # any number; on boundary facets
    boundary = "zmax"                  # or where = "..." (tested at facet midpoints),
    # where = "y > 0.5"                # or both: the part of zmax where y > 0.5
    pressure = "4*y*(1 - y)"           # positive in compression: t = -p n
    # traction = [0, 0, "-1"]          # or a traction vector

    [interface]
    law = "bonded"                     # one of skxfem.scene.LAWS or CONTACT_LAWS
    space = "vital"                    # one of skxfem.scene.SPACES (default vital)
    # friction = 0.5                   # coulomb only, needed: 0 or 1e-10..1e10
    # rho_n = 10.0                     # contact augmentation, > 0 (default E/h)
    # rho_t = 10.0                     # friction augmentation, > 0
    # steps = [0.5, 1.0]               # load factors of a contact solve

    [solver]                           # optional
    quadrature_order = 2               # default: the minimal exact rule
    # linear = "iterative"             # auto (default), direct or iterative
    # linear_tol = 1e-10               # the relative residual of an iterative solve
    # max_iter = 40                    # contact laws: Newton iterations per load step

Several interfaces, each with its own level set, law, μ and ρ: instead of
``[levelset]`` and ``[interface]``, one ``[[interface]]`` table per interface,
with the keys of both (``steps`` then at the top level); their Γ must not
cross or touch (:func:`skxfem.problem.assemble` refuses a cell cut by two)::

    steps = [0.5, 1.0]                 # optional: the load factors of a contact solve

    [[interface]]
    plane = {point = [0, 0.35], normal = [0, 1]}
    law = "frictionless"

    [[interface]]
    expr = "y - 0.7"
    law = "coulomb"
    friction = 0.5

A load path (press, then shear, then unload), as ``history=`` of
:func:`skxfem.contact.solve`: instead of ``steps``, one ``[[step]]`` table per
load state, in order, with its own loads and imposed displacements (added to the
``[[load]]`` and ``[[displacement]]`` tables, which hold in every state) and,
optionally, its own law; ``Scene.steps`` holds the states (scenes), and the scene
itself is the first::

    [[step]]
    name = "press"
    [[step.load]]
    boundary = "ymax"
    pressure = 1.0
    [[step.displacement]]              # every state imposes the same components
    boundary = "ymax"
    x = 0.0

    [[step]]
    name = "unload"
    law = "bonded"                     # optional: the law of this state
    [[step.displacement]]
    boundary = "ymax"
    x = 0.0

``linear``, ``linear_tol`` and ``max_iter`` are the scene's
:class:`~skxfem.scene.settings.Solver` (``Scene.solver``): ``skxfem run`` and
``skxfem.solve(load_scene(path))`` solve alike, ``skxfem run``'s ``--linear``,
``--linear-tol``, ``--max-iter`` and the keywords of ``skxfem.solve`` override
them.

Every table and key, what it takes, its unit and default are in :data:`SCHEMA`,
which the reader checks against (the keys allowed, the ones exclusive of each
other) and :func:`schema` prints (``skxfem schema``).  Units are consistent and
the user's choice (:data:`UNITS`).

Numbers the solve cannot handle in double precision are refused when read
(:mod:`skxfem.scene.magnitudes`, as in Python): a load above :data:`MAX_MAGNITUDE`
(or one whose displacements |p| L / E would be), an imposed displacement above
:data:`MAX_SHIFT` sizes of the body, a number or a formula's value at the nodes
(formulas on a box of more than :data:`BUILT_BOX` cells: when solved).  A mesh file that
is a folder, a FIFO, a device or a loop of symbolic links is named as such,
unread.

Errors name items as the file numbers them (``[[load]] #2``).  Every boundary is
checked on reading, except the ``where`` selections on a box whose grid has more
than :data:`BUILT_BOX` squares or cubes (not built before the size guard).
'''
from __future__ import annotations

import functools
import math
import os
import textwrap
from dataclasses import dataclass, replace
from pathlib import Path

from .. import levelset as ls
from ..fem import meshes
from ..fem.files import regular_file
from ..fem.material import Material
from ..linalg.choice import LINEAR
from . import model as sc
from . import tomlcheck
from .boundary import select_facets, select_nodes
from .laws import FRICTION_LAWS, in_words
from .magnitudes import BUILT_BOX, MAX_MAGNITUDE, MAX_SHIFT, check_magnitudes
from .parts import COMPONENTS, CRACK_ENRICHMENTS, FACES, check_friction
from .settings import Solver
from .tomlcheck import array, choice, formula, keys, number, one_of, table, vector

__all__ = ["load_scene", "Key", "Table", "SCHEMA", "UNITS", "schema",
           "MAX_MAGNITUDE", "MAX_SHIFT"]



@dataclass(frozen=True)
class Key:
    """One key of a scene-file table: what it takes (with its unit in brackets), what it
    means and its default, and an example value (TOML, as Python reads it)."""

    name: str
    takes: str
    text: str
    example: object


@dataclass(frozen=True)
class Table:
    """A scene-file table: its keys, in order, and the groups of keys of which exactly
    one must be given (``exclusive``; a group ending in ``...`` needs one or more)."""

    name: str
    text: str
    keys: tuple[Key, ...]
    exclusive: tuple[tuple[str, ...], ...] = ()

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(k.name for k in self.keys)


_FORMULA = "number or formula"   # a formula: a string checked by skxfem.scene.expr
UNITS = ("Units are consistent and your choice: with lengths in L and forces in F, the "
         "coordinates x, y, z, sizes, radii and displacements are in L; E, pressures and "
         "tractions in F/L²; rho_n in F/L³; nu, friction and load factors have no unit.  "
         "E = 210e9 with lengths in m gives tractions in Pa; E = 210e3 with mm, in MPa.")
"""The units of a scene file, stated by :func:`schema`."""

SCHEMA: dict[str, Table] = {t.name: t for t in (
    Table("the top level", "", (
        Key("name", "string", "the scene's name (default: the file name)", "plate"),
        Key("mesh", "table", "required: [mesh]", {}),
        Key("levelset", "table", "[levelset]: required, unless [[interface]] tables give "
            "each interface its own", {}),
        Key("material", "table", "[material] (default: E = 1, nu = 0.3)", {}),
        Key("body_force", "table", "[body_force] (default: none)", {"force": [0.0, -1.0]}),
        Key("displacement", "array of tables", "[[displacement]], any number", []),
        Key("load", "array of tables", "[[load]], any number", []),
        Key("interface", "table, or array of tables", "[interface] (default: bonded, "
            "vital), or several interfaces: [[interface]], one table each", {}),
        Key("steps", "list of numbers", "the load factors of a contact solve, in order, at "
            "most 1000 (default [1]; or [interface] steps)", [0.5, 1.0]),
        Key("step", "array of tables", "[[step]], the load states of a contact solve, in "
            "order, at most 1000 (instead of steps)", [{"name": "press"}]),
        Key("solver", "table", "[solver] (optional)", {}),
    )),
    Table("[mesh]", "the mesh", (
        Key("box", "table {n, cell, size}", "a box [0, size] meshed here: [mesh] box",
            {"n": 4, "cell": "quad"}),
        Key("file", "path string", "a mesh file in any meshio format, relative to the "
            "scene file", "plate.msh"),
    ), (("box", "file"),)),
    Table("[mesh] box", "a structured box mesh", (
        Key("n", "integer, or dim integers", "cells along each axis (required)", [4, 5]),
        Key("cell", "one of " + " ".join(sc.CELLS), "the cell (required): "
            + ", ".join(f"{c} {d}D" for c, d in sc.CELLS.items()), "quad"),
        Key("size", "dim numbers [L]", "the lengths of the box (default: 1 each)",
            [2.0, 1.0]),
    )),
    Table("[levelset]", "the interface Γ = {ψ = 0}; Ω⁻ = {ψ < 0}, Ω⁺ = {ψ > 0}", (
        Key("plane", "table {point, normal}", "a plane (a line in 2D); its normal points "
            "into Ω⁺", {"point": [0.0, 0.5], "normal": [0.0, 1.0]}),
        Key("circle", "table {center, radius}", "2D: Ω⁻ inside the circle",
            {"center": [0.5, 0.5], "radius": 0.3}),
        Key("sphere", "table {center, radius}", "3D: Ω⁻ inside the sphere",
            {"center": [0.5, 0.5, 0.5], "radius": 0.3}),
        Key("expr", "formula [L]", "ψ itself, best a signed distance", "y - 0.5"),
        Key("front", "formula [L]", "a crack: φ, Γ is then {ψ = 0, φ < 0}, ending inside "
            "the body at the front {ψ = φ = 0} (2D, or 3D on tet meshes; any law: free "
            "faces, or a tie or contact on the faces up to the front)", "x - 0.5"),
    ), (("plane", "circle", "sphere", "expr"),)),
    Table("[levelset] plane", "", (
        Key("point", "dim numbers [L]", "a point of the plane (required)", [0.0, 0.5]),
        Key("normal", "dim numbers", "its normal, any length but not 0 (required)",
            [0.0, 1.0]),
    )),
    Table("[levelset] circle", "", (
        Key("center", "dim numbers [L]", "the centre (required)", [0.5, 0.5]),
        Key("radius", "number > 0 [L]", "the radius (required)", 0.3),
    )),
    Table("[levelset] sphere", "", (
        Key("center", "dim numbers [L]", "the centre (required)", [0.5, 0.5, 0.5]),
        Key("radius", "number > 0 [L]", "the radius (required)", 0.3),
    )),
    Table("[material]", "linear isotropic elasticity, the same on both sides unless "
          "minus or plus gives a side its own", (
        Key("E", "number > 0 [F/L²]", "Young's modulus (default 1)", 210e3),
        Key("nu", "number in (-1, 0.5)", "Poisson's ratio (default 0.3)", 0.3),
        Key("plane", "strain or stress", "2D only: plane strain or plane stress "
            "(default strain)", "stress"),
        Key("minus", "table {E, nu}", "[material.minus]: the material of Ω⁻ = {ψ < 0} "
            "(its E and nu, each defaulting to those above); one interface only",
            {"E": 1.0}),
        Key("plus", "table {E, nu}", "[material.plus]: the material of Ω⁺ = {ψ > 0}; "
            "one interface only", {"E": 10.0}),
    )),
    Table("[body_force]", "a volume force on the whole body, scaled by the load factors "
          "as the loads are", (
        Key("force", "dim numbers or formulas [F/L³]", "the force per volume b: gravity "
            "is [0, -rho*g] in 2D, [0, 0, -rho*g] in 3D (required)", [0.0, -1.0]),
    )),
    Table("[[displacement]]", "imposed displacements, on the nodes of a boundary: "
          "boundary, where, or both (the nodes of the boundary where the condition holds)", (
        Key("boundary", "one of " + " ".join(FACES), "a face of the box (or a named "
            "boundary of the mesh file)", "xmin"),
        Key("where", "condition on x, y, z", "the nodes where it holds (of the boundary, "
            "if given)", "x < 1e-9"),
        Key("kind", "clamped or rollers", "clamped: u = 0; rollers: the normal component "
            "of u is 0 (a named face)", "clamped"),
        Key("x", f"{_FORMULA} [L]", "the imposed u_x (those of x, y, z given)", 0.0),
        Key("y", f"{_FORMULA} [L]", "the imposed u_y", "0.01*x"),
        Key("z", f"{_FORMULA} [L]", "the imposed u_z (3D)", 0.0),
    ), (("kind", "x", "y", "z", "..."),)),
    Table("[[load]]", "surface loads, on boundary facets: boundary, where (tested at the "
          "facet midpoints), or both (the facets of the boundary where the condition holds, "
          "such as the xmax face above z = 2.2)", (
        Key("boundary", "one of " + " ".join(FACES), "a face of the box (or a named "
            "boundary of the mesh file)", "ymax"),
        Key("where", "condition on x, y, z", "the boundary facets whose midpoint it "
            "holds at (of the boundary, if given)", "y > 1 - 1e-9"),
        Key("pressure", f"{_FORMULA} [F/L²]", "positive in compression: t = -p n",
            "4*x*(1 - x)"),
        Key("traction", "dim numbers or formulas [F/L²]", "the traction vector t", [0.0, "-1"]),
    ), (("pressure", "traction"),)),
    Table("[[step]]", "a load state of a contact solve (a load path: press, then shear, "
          "then unload), one table each, in order: its loads are the [[load]] tables and "
          "its own [[step.load]] tables, its imposed displacements the [[displacement]] "
          "tables and its own [[step.displacement]] tables (a later one wins on a node; "
          "every state imposes displacements on the same nodes: hold a released support "
          "at 0); these take the keys of [[load]] and [[displacement]]", (
        Key("name", "string", "the state's name in the results (default: step N)", "press"),
        Key("law", "one of " + " ".join(("bonded", "bilateral") + sc.CONTACT_LAWS),
            "the law of Γ in this state (default: [interface] law); one interface only",
            "frictionless"),
        Key("friction", "0, or 1e-10 to 1e10", "Coulomb's mu in this state (law coulomb; "
            "default: [interface] friction)", 0.5),
        Key("load", "array of tables", "[[step.load]]: its loads, keys of [[load]]",
            [{"boundary": "ymax", "pressure": 1.0}]),
        Key("displacement", "array of tables", "[[step.displacement]]: its imposed "
            "displacements, keys of [[displacement]]", [{"boundary": "ymax", "x": 0.0}]),
    )),
    Table("[interface]", "the law on Γ and its multiplier space", (
        Key("law", "one of " + " ".join(sc.LAWS + sc.CONTACT_LAWS), "ties: bonded "
            "(default), bilateral; free: traction-free faces (a crack's), no multiplier; "
            "contact: frictionless, coulomb, adhesive", "coulomb"),
        Key("space", "one of " + " ".join(sc.SPACES), "the multiplier space (default "
            "vital, the stable one)", "vital"),
        Key("friction", "0, or 1e-10 to 1e10", "Coulomb's mu: required by law coulomb (0: it "
            "slides freely), refused by the other laws", 0.5),
        Key("rho_n", "number > 0 [F/L³]", "contact augmentation (default E/h, h the cell "
            "size)", 10.0),
        Key("rho_t", "number > 0 [F/L³]", "friction augmentation (default E/h, h the mean "
            "cut-edge size)", 10.0),
        Key("steps", "list of numbers", "the load factors of a contact solve, in order, at "
            "most 1000 (default [1])", [0.5, 1.0]),
        Key("enrichment", "one of " + " ".join(CRACK_ENRICHMENTS), "a crack's tip "
            "enrichment: the nodes within a radius of the tip (geometric, default) or the "
            "tip cells' (topological)", "geometric"),
        Key("enrichment_radius", "number > 0 [L]", "a crack: r_e, the tip's enriched zone "
            "with geometric enrichment (default max(0.2 L, n h / 0.75): L the mesh's "
            "diameter in 2D (0.2 L at most three crack depths), the crack's depth in 3D, "
            "h the front cells' size, n h the "
            "default interaction domain, 4 cells in 2D and 3 in 3D: at least 5.3 and 4 "
            "cells; one that reaches no node beyond the front cells is refused)", 0.4),
        Key("sif_radius", "number > 0 [L]", "a crack: the radius of the interaction "
            "integral's domain (default 0.75 enrichment_radius, at least 4 tip cells in "
            "2D, 3 front cells in 3D; not under one; clipped to the distance to the "
            "boundary and half that to other tips; in 3D a third of that to other "
            "fronts and 1/(2 κ), κ the front's curvature)", 0.3),
    )),
    Table("[[interface]]", "several interfaces, one table each (in place of [levelset] "
          "and [interface]) with its level set (a key of [levelset], as there) and its "
          "law (the keys of [interface] but steps); no two may cut one mesh cell", (
        Key("plane", "table {point, normal}", "as [levelset] plane",
            {"point": [0.0, 0.35], "normal": [0.0, 1.0]}),
        Key("circle", "table {center, radius}", "as [levelset] circle",
            {"center": [0.5, 0.5], "radius": 0.3}),
        Key("sphere", "table {center, radius}", "as [levelset] sphere",
            {"center": [0.5, 0.5, 0.5], "radius": 0.3}),
        Key("expr", "formula [L]", "as [levelset] expr", "y - 0.7"),
        Key("law", "one of " + " ".join(sc.LAWS + sc.CONTACT_LAWS), "its law (default "
            "bonded)", "frictionless"),
        Key("space", "one of " + " ".join(sc.SPACES), "its multiplier space (default "
            "vital)", "vital"),
        Key("friction", "0, or 1e-10 to 1e10", "its Coulomb's mu: required by law coulomb, "
            "refused by the others", 0.5),
        Key("rho_n", "number > 0 [F/L³]", "its contact augmentation (default E/h)", 10.0),
        Key("rho_t", "number > 0 [F/L³]", "its friction augmentation (default E/h)", 10.0),
        Key("front", "formula [L]", "as [levelset] front: a crack (any law)", "x - 0.5"),
        Key("enrichment", "one of " + " ".join(CRACK_ENRICHMENTS), "as [interface] "
            "enrichment", "topological"),
        Key("enrichment_radius", "number > 0 [L]", "as [interface] enrichment_radius", 0.4),
        Key("sif_radius", "number > 0 [L]", "as [interface] sif_radius", 0.3),
    ), (("plane", "circle", "sphere", "expr"),)),
    Table("[solver]", "how the scene is solved, by skxfem run and skxfem.solve alike "
          "(skxfem run's --linear, --linear-tol, --max-iter and skxfem.solve's keywords "
          "override them)", (
        Key("quadrature_order", "integer >= 1", "the cell rule of the stiffness (default: "
            "the minimal exact rule)", 2),
        Key("linear", "one of " + " ".join(LINEAR), "the linear solve: direct (SuperLU), "
            "iterative (AMG + CG, needs pyamg) or auto (default)", "direct"),
        Key("max_iter", "integer >= 1", "contact laws: Newton iterations per load step "
            "(default 30)", 40),
        Key("linear_tol", "number in (0, 1)", "the relative residual of the iterative "
            "linear solve (default 1e-12), recorded in result.json", 1e-10),
    )),
)}
"""The scene-file schema: every table and key the reader accepts, by table name
(``[mesh]``, ``[mesh] box`` ...).  :func:`load_scene` takes its allowed keys and
exclusive groups from here; :func:`schema` prints it."""


def _names(table: str) -> tuple[str, ...]:
    return SCHEMA[table].names


def _exclusive(table: str, i: int = 0) -> tuple[str, ...]:
    return tuple(k for k in SCHEMA[table].exclusive[i] if k != "...")


_TOP = _names("the top level")
_TOP_KEYS = tuple(k.name for k in SCHEMA["the top level"].keys if k.takes != "table"
                  and "tables" not in k.takes)
"""The top-level keys that are not tables (name, steps): written after a table header,
TOML puts them into that table, and the error says so."""


def schema(width: int = 88) -> str:
    """The scene-file schema as text: what ``skxfem schema`` prints.

    >>> text = schema()
    >>> "[mesh] box" in text and "rho_n" in text and "F/L³" in text
    True
    """
    from .expr import FUNCTIONS

    wrap = functools.partial(textwrap.fill, width=width, break_long_words=False,
                             break_on_hyphens=False)
    out = [wrap("The scene file of skxfem run (TOML): every table and key, what it takes "
                "[its unit], what it means and its default.  Unknown keys are refused."),
           "", wrap(UNITS), "",
           wrap("A formula is a string in the coordinates x, y, z with numbers, pi, "
                "+ - * / ** and the functions " + " ".join(FUNCTIONS) + " (angles in "
                "radians); a condition (where) may also use < <= > >= == != and, or, not.  "
                "No formula runs code.  'dim' is the dimension of the mesh, 2 or 3."), ""]
    name_w = max(len(k.name) for t in SCHEMA.values() for k in t.keys) + 2
    takes_w = 30
    for t in SCHEMA.values():
        head = t.name + (f": {t.text}" if t.text else "")
        for group in t.exclusive:
            keys = [k for k in group if k != "..."]
            head += (f"; one or more of {', '.join(keys[1:])}, or {keys[0]}" if "..." in group
                     else f"; exactly one of {', '.join(keys)}")
        out.append(wrap(head))
        for k in t.keys:
            indent = " " * (2 + name_w + takes_w + 1)
            text = textwrap.fill(k.text, width=width, initial_indent=indent,
                                 subsequent_indent=indent, break_long_words=False)
            row = f"  {k.name:<{name_w}}{k.takes:<{takes_w}} "
            if len(row) > len(indent):      # a long 'takes': the meaning on the next line
                out += [row.rstrip(), text]
            else:
                out.append(row + text.lstrip())
        out.append("")
    return "\n".join(out).rstrip() + "\n"


def load_scene(path: str | Path) -> sc.Scene:
    """Read and check a scene file: the :class:`~skxfem.scene.Scene`, with its
    ``[solver]`` table's ``linear``, ``linear_tol`` and ``max_iter`` in
    ``Scene.solver`` (so that ``skxfem.solve(load_scene(path))`` solves as
    ``skxfem run path`` does).

    Raises
    ------
    ValueError, TypeError
        For a bad file; the message starts with the file name and names the key.

    >>> import pathlib, tempfile
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "strip.toml"
    >>> _ = f.write_text('''
    ... [mesh]
    ... box = {n = 3, cell = "quad"}
    ... [levelset]
    ... expr = "y - 0.5"
    ... ''')
    >>> s = load_scene(f)
    >>> s.name, s.solver.linear, s.solver.max_iter
    ('strip', 'auto', None)
    """
    path, data = tomlcheck.read_toml(path)
    try:
        return _scene(data, path)
    except (ValueError, TypeError) as e:
        raise type(e)(f"{path.name}: {e}") from e


def _options(solver: dict) -> dict:
    """The ``linear``, ``linear_tol`` and ``max_iter`` of a ``[solver]`` table, checked
    (by :class:`~skxfem.scene.settings.Solver`'s checks, the messages naming the table)."""
    out = {k: solver[k] for k in ("linear", "max_iter", "linear_tol") if k in solver}
    if "max_iter" in out and type(out["max_iter"]) is not int:   # 2.5, true, "40"
        raise ValueError(f"[solver] max_iter must be a positive integer, got {out['max_iter']!r}")
    try:
        Solver(**out)
    except ValueError as e:          # "linear must be ...": "[solver] linear must be ..."
        raise ValueError(f"[solver] {e}") from None
    return out


def _law_fields(t: dict, where: str) -> dict:
    """The law, space, friction, rho_n and rho_t of an [interface] (or [[interface]])
    table, checked, as keywords of a Scene (or an Interface)."""
    fields = {"law": choice(t.get("law", "bonded"), sc.LAWS + sc.CONTACT_LAWS,
                            f"{where} law")}
    fields.update({k: number(t[k], f"{where} {k}")
                   for k in ("friction", "rho_n", "rho_t") if k in t})
    if fields["law"] in FRICTION_LAWS and "friction" not in fields:
        raise ValueError(f"{where} law {fields['law']!r} needs friction (Coulomb's mu, a "
                         f"number >= 0): add friction = 0.3, say (friction = 0 slides "
                         f"freely, as law \"frictionless\")")
    if "friction" in fields and fields["law"] not in FRICTION_LAWS:
        raise ValueError(f"{where} friction (Coulomb's mu) is taken by law "
                         f"{' or '.join(map(repr, FRICTION_LAWS))} only; law "
                         f"{fields['law']!r} has no friction: remove friction")
    if "friction" in fields and fields["friction"] < 0:
        raise ValueError(f"{where} friction must be >= 0, got {fields['friction']!r}")
    if "friction" in fields:
        check_friction(where, fields["law"], fields["friction"])
    for key in ("rho_n", "rho_t"):
        if key in fields and not fields[key] > 0:
            raise ValueError(f"{where} {key} must be > 0, got {fields[key]!r}")
    fields["space"] = choice(t.get("space", "vital"), sc.SPACES, f"{where} space")
    return fields


def _crack_fields(front, t: dict, dim: int, where: str) -> dict:
    """The ``front`` (a formula φ), ``enrichment``, ``enrichment_radius`` and
    ``sif_radius`` of a crack, as
    keywords of an :class:`~skxfem.scene.Interface` (which checks them together);
    ``t`` the [interface] or [[interface]] table ``where``; {} if none is given."""
    out = {}
    if front is not None:
        if not isinstance(front, str):
            raise TypeError(f"{where} front must be a formula string (φ: the crack where "
                            f"φ < 0), got {front!r}")
        out["front"] = ls.LevelSet(formula(front, f"{where} front", dim), dim, front)
    if "enrichment" in t:
        out["enrichment"] = choice(t["enrichment"], CRACK_ENRICHMENTS, f"{where} enrichment")
    for key in ("enrichment_radius", "sif_radius"):
        if key in t:
            out[key] = number(t[key], f"{where} {key}")
    return out


def _steps(steps, where: str) -> tuple:
    if not (isinstance(steps, list) and steps and all(
            isinstance(f, (int, float)) and not isinstance(f, bool) for f in steps)):
        raise ValueError(f"{where} must be a non-empty list of load factors, got "
                         f"{steps!r:.200}")
    sc.check_steps(len(steps), where)
    return tuple(steps)


def _interfaces(data: dict, dim: int) -> tuple[sc.Interface, ...]:
    """The [[interface]] tables of a scene file (one or more interfaces)."""
    if "levelset" in data:
        raise ValueError("[levelset] with [[interface]] tables: with [[interface]] tables "
                         "each gives its own level set (plane, circle, sphere or expr); "
                         "remove [levelset]")
    out = []
    for k, t in enumerate(array(data, "interface")):
        where = f"[[interface]] #{k + 1}"
        t = table(t, where, _names("[[interface]]"), _TOP_KEYS)
        kind = one_of(t, _exclusive("[[interface]]"), where)
        levelset = _levelset({kind: t[kind]}, dim, where)
        fields = {**_law_fields(t, where), **_crack_fields(t.get("front"), t, dim, where)}
        out.append(tomlcheck.labelled(where, lambda: sc.Interface(levelset, **fields)))
    if not out:
        raise ValueError("interface is an empty list: give [[interface]] tables, one per "
                         "interface, or [levelset] and [interface] for one")
    return tuple(out)


def _scene(data: dict, path: Path) -> sc.Scene:
    keys(data, _TOP, "the top level")
    tables = isinstance(data.get("interface"), list)   # [[interface]], else the short form
    for key in ("mesh",) + (() if tables else ("levelset",)):
        if key not in data:
            raise ValueError(f"missing table [{key}]")
    mesh, dim, checked = _mesh(table(data["mesh"], "[mesh]", _names("[mesh]"), _TOP_KEYS),
                                  path.parent)
    solver = table(data.get("solver", {}), "[solver]", _names("[solver]"), _TOP_KEYS)
    if tables:
        interfaces = _interfaces(data, dim)
        fields, laws = {"interfaces": interfaces}, [i.law for i in interfaces]
    else:
        interface = table(data.get("interface", {}), "[interface]", _names("[interface]"),
                          _TOP_KEYS)
        fields = _law_fields(interface, "[interface]")
        laws = [fields["law"]]
        if "steps" in interface:
            if "steps" in data:
                raise ValueError("steps is given twice, in [interface] and at the top "
                                 "level: keep one")
            fields["steps"] = _steps(interface["steps"], "[interface] steps")
        fields["levelset"] = _levelset(data["levelset"], dim)
        crack = _crack_fields(data["levelset"].get("front"), interface, dim, "[interface]")
        if crack:   # a crack in the short form: the interfaces form at once
            own = {k: fields.pop(k) for k in ("levelset", "law", "space", "friction",
                                               "rho_n", "rho_t") if k in fields}
            interfaces = (tomlcheck.labelled("[interface]", lambda: sc.Interface(
                own.pop("levelset"), **own, **crack)),)
            fields["interfaces"] = interfaces
    if "steps" in data:
        fields["steps"] = _steps(data["steps"], "steps")
    options = _options(solver)
    if "max_iter" in options and not any(law in sc.CONTACT_LAWS for law in laws):
        raise ValueError(f"[solver] max_iter applies to the contact laws {sc.CONTACT_LAWS}; "
                         f"the law is {in_words(laws)}")
    order = solver.get("quadrature_order")
    if order is not None and (type(order) is not int or order < 1):
        raise ValueError(f"[solver] quadrature_order must be a positive integer, got {order!r}")
    name = data.get("name", path.stem)
    if not isinstance(name, str) or not name:
        raise TypeError(f"name must be a non-empty string, got {name!r}")
    items = {"displacement": [], "load": []}           # (name in the file, item) pairs
    for key, build in (("displacement", _displacement), ("load", _load)):
        for i, t in enumerate(array(data, key)):
            where = f"[[{key}]] #{i + 1}"
            items[key].append((where, tomlcheck.labelled(where, build, t, dim, where)))
    _check_boundaries(items, checked, dim)
    material, fields["material_plus"] = _material(table(
        data.get("material", {}), "[material]", _names("[material]"), _TOP_KEYS))
    if fields["material_plus"] is not None and len(fields.get("interfaces", ())) > 1:
        raise ValueError("[material] minus, plus: a material per side of Γ is for a scene "
                         "with one interface; with several [[interface]] tables, give "
                         "one material")
    if "body_force" in data:
        fields["body_force"] = _body_force(table(data["body_force"], "[body_force]",
                                                 _names("[body_force]"), _TOP_KEYS), dim)
    scene = sc.Scene(
        mesh=mesh,
        material=material,
        displacements=tuple(d for _, d in items["displacement"]),
        loads=tuple(load for _, load in items["load"]),
        quadrature_order=order, name=name, solver=Solver(**options), **fields)
    check_magnitudes(scene, checked, tuple([where for where, _ in items[key]]
                                           for key in ("displacement", "load")))
    if "step" in data:
        states = _states(data, scene, items, checked, dim, laws)
        scene = replace(scene, displacements=states[0].displacements, loads=states[0].loads,
                        steps=states)     # the scene is its first state, with the history
    return scene


def _states(data: dict, scene: sc.Scene, items: dict, checked, dim: int, laws) -> tuple:
    """The load states of the [[step]] tables: each the scene with its own loads, imposed
    displacements, law and friction (:data:`SCHEMA` ``[[step]]``)."""
    if "steps" in data or "steps" in (data.get("interface") or {}):
        raise ValueError("steps and [[step]] tables are both given: give either steps (load "
                         "factors: the loads scaled) or [[step]] tables (load states)")
    if not any(law in sc.CONTACT_LAWS for law in laws):
        raise ValueError(f"[[step]] tables are the load states of a contact solve; the law "
                         f"is {in_words(laws)}, a tie, which is linear "
                         f"(one state): give its loads as [[load]] tables")
    tables = array(data, "step")
    if not tables:
        raise ValueError("step is an empty list: give [[step]] tables, one per load state")
    sc.check_steps(len(tables), "[[step]] tables")
    states = []
    for k, t in enumerate(tables):
        where = f"[[step]] #{k + 1}"
        t = table(t, where, _names("[[step]]"), _TOP_KEYS)
        name = t.get("name", f"step {k + 1}")
        if not isinstance(name, str) or not name:
            raise TypeError(f"{where} name must be a non-empty string, got {name!r}")
        own = {"displacement": list(items["displacement"]), "load": list(items["load"])}
        for key, build in (("displacement", _displacement), ("load", _load)):
            if key in t and not (isinstance(t[key], list)
                                 and all(isinstance(i, dict) for i in t[key])):
                raise TypeError(f"{where} {key} must be written as [[step.{key}]] tables")
            for i, item in enumerate(t.get(key, [])):
                label = f"{where} [[step.{key}]] #{i + 1}"
                own[key].append((label, tomlcheck.labelled(label, build, item, dim, label)))
        _check_boundaries({k: v[len(items[k]):] for k, v in own.items()}, checked, dim)
        fields = {}
        if "law" in t or "friction" in t:
            if len(scene.interfaces) > 1:
                raise ValueError(f"{where} law, friction: a state's law is given in scene "
                                 f"files for one interface only; with several, give the "
                                 f"history in Python (skxfem.contact.solve(scene, "
                                 f"history=[...]))")
            gamma = scene.interfaces[0]
            law = choice(t.get("law", gamma.law), ("bonded", "bilateral") + sc.CONTACT_LAWS,
                         f"{where} law")
            friction = number(t["friction"], f"{where} friction") if "friction" in t else \
                gamma.friction if law in FRICTION_LAWS else None
            if law in FRICTION_LAWS and friction is None:
                raise ValueError(f"{where} law 'coulomb' needs friction (Coulomb's mu): "
                                 f"add friction = 0.3, say")
            gamma = tomlcheck.labelled(where, lambda: replace(gamma, law=law, friction=friction))
            fields = scene.given_interfaces((gamma,))
        state = tomlcheck.labelled(where, lambda: replace(
            scene, name=name, displacements=tuple(d for _, d in own["displacement"]),
            loads=tuple(x for _, x in own["load"]), steps=(1.0,), **fields))
        check_magnitudes(state, checked, tuple([w for w, _ in own[key]]
                                               for key in ("displacement", "load")))
        states.append(state)
    return tuple(states)


def _check_boundaries(items: dict, mesh, dim: int):
    """Each boundary exists and selects nodes (facets for a load); see the module notes."""
    if isinstance(mesh, sc.Box):
        faces = FACES[:2 * dim]
        for where, item in items["displacement"] + items["load"]:
            if isinstance(item.boundary, str) and item.boundary not in faces:
                raise ValueError(f"{where} boundary {item.boundary!r} is not a face of the "
                                 f"box; use one of {', '.join(faces)}, or where")
        plain = all(isinstance(i.boundary, str) and i.where is None
                    for v in items.values() for _, i in v)
        if plain or math.prod(mesh.n) > BUILT_BOX:
            return
        mesh = meshes.box(mesh.n, mesh.cell, mesh.size)
    for key, select in (("displacement", select_nodes), ("load", select_facets)):
        for where, item in items[key]:
            tomlcheck.labelled(where, select, mesh, item.boundary, where, item.where)


def _mesh(t: dict, folder: Path) -> tuple[sc.Box | Path, int, object]:
    """The scene's mesh, its dimension, and what to check boundaries on (Box or Mesh)."""
    if one_of(t, _exclusive("[mesh]"), "[mesh]") == "box":
        box = table(t["box"], "[mesh] box", _names("[mesh] box"))
        if "n" not in box or "cell" not in box:
            raise ValueError("[mesh] box needs n and cell, e.g. {n = 4, cell = \"quad\"}")
        n, cell, size = box["n"], box["cell"], box.get("size")
        if not (type(n) is int or isinstance(n, list) and all(type(k) is int for k in n)):
            raise TypeError(f"[mesh] box.n must be an integer or a list of integers, got {n!r}")
        choice(cell, tuple(sc.CELLS), "[mesh] box.cell")
        if size is not None:
            size = vector(size, "[mesh] box.size", sc.CELLS[cell])
        b = tomlcheck.labelled("[mesh] box", sc.Box, tuple(n) if isinstance(n, list) else n,
                               cell, size)
        return b, sc.CELLS[cell], b
    if not isinstance(t["file"], str):
        raise TypeError(f"[mesh] file must be a path string, got {t['file']!r}")
    path = Path(os.path.abspath(folder / t["file"]))
    try:
        path = regular_file(path, f"[mesh] file {t['file']!r}").resolve()
    except FileNotFoundError:
        raise ValueError(f"[mesh] file {t['file']!r} not found (looked for {path})") from None
    except IsADirectoryError:
        raise ValueError(f"[mesh] file {t['file']!r} is a folder ({path}); give the path "
                         f"of a mesh file") from None
    try:
        mesh = meshes.read(path)
    except Exception as e:  # any reader error is a bad scene file
        raise ValueError(f"[mesh] file {t['file']!r}: {e}") from None
    return path, mesh.dim(), mesh


def _levelset(t: dict, dim: int, where: str = "[levelset]") -> ls.LevelSet:
    """The level set of a [levelset] table (or of the level-set key of the
    [[interface]] table ``where``)."""
    kinds = _exclusive("[levelset]")
    t = table(t, where, _names("[levelset]"), _TOP_KEYS)
    kind = one_of(t, kinds, where)
    key = f"{where} {kind}"
    if kind == "expr":
        if not isinstance(t[kind], str):
            raise TypeError(f"{key} must be a formula string, got {t[kind]!r}")
        return ls.LevelSet(formula(t[kind], key, dim), dim, t[kind])
    if kind in ("circle", "sphere") and dim != {"circle": 2, "sphere": 3}[kind]:
        other = "sphere" if kind == "circle" else "circle"
        raise ValueError(f"{key} is a {5 - dim}D shape but the mesh is {dim}D; "
                         f"use {other} or expr")
    args = _names(f"[levelset] {kind}")
    spec = table(t[kind], key, args)
    for a in args:
        if a not in spec:
            raise ValueError(f"{key} needs {a}")
    if kind == "plane":
        args = (vector(spec["point"], f"{key}.point", dim),
                vector(spec["normal"], f"{key}.normal", dim))
    else:
        args = (vector(spec["center"], f"{key}.center", dim),
                number(spec["radius"], f"{key}.radius"))
    return tomlcheck.labelled(key, getattr(ls, kind), *args)


def _body_force(t: dict, dim: int) -> tuple:
    if "force" not in t:
        raise ValueError("[body_force] needs force, e.g. force = [0, -9.81e-6] (F/L³)")
    v = t["force"]
    if not isinstance(v, list) or len(v) != dim:
        raise ValueError(f"[body_force] force must be a list of {dim} numbers or formulas "
                         f"on a {dim}D mesh, got {v!r}")
    return tuple(formula(c, f"[body_force] force[{i}]", dim) for i, c in enumerate(v))


def _material(t: dict) -> tuple[Material, Material | None]:
    """The material of a [material] table, and that of Ω⁺ if a side has its own (then
    the first is Ω⁻'s)."""
    def made(t, where, base=None):
        args = {k: number(t[k], f"{where} {k}") for k in ("E", "nu") if k in t}
        try:
            return Material(**{**(base or {}), **args}, plane=plane)
        except ValueError as e:
            raise ValueError(f"{where} {e}") from None

    plane = t.get("plane", "strain")
    both = made(t, "[material]")
    sides = {}
    for side in ("minus", "plus"):
        if side in t:
            own = table(t[side], f"[material.{side}]", ("E", "nu"))
            sides[side] = made(own, f"[material.{side}]", {"E": both.E, "nu": both.nu})
    if not sides:
        return both, None
    return sides.get("minus", both), sides.get("plus", both)


def _where(t: dict, dim: int, where: str):
    """The ``boundary`` and ``where`` of a [[displacement]] or [[load]] table: a named
    boundary (or None), and a condition (or None); one of them at least."""
    if "boundary" not in t and "where" not in t:
        raise ValueError(f"{where} needs boundary, where, or both (a face such as "
                         f"boundary = 'xmax', a condition such as where = 'z > 2.2', or "
                         f"both: the part of the face where the condition holds)")
    cond = formula(t["where"], f"{where} where", dim, boolean=True) if "where" in t else None
    if "boundary" not in t:
        return None, cond
    if not isinstance(t["boundary"], str):
        raise TypeError(f"{where} boundary must be a name such as 'xmin', "
                        f"got {t['boundary']!r}")
    return t["boundary"], cond


def _part(build, boundary, cond, *args, **kwargs):
    """``build(boundary, ...)``, its ``where`` the condition if a boundary is named too."""
    if boundary is None:
        return build(cond, *args, **kwargs)
    return build(boundary, *args, **kwargs, where=cond)


def _displacement(t: dict, dim: int, where: str) -> sc.Displacement:
    keys(t, _names("[[displacement]]"), where, _TOP_KEYS)
    boundary, cond = _where(t, dim, where)
    given = [c for c in COMPONENTS if c in t]
    if "z" in given and dim == 2:
        raise ValueError(f"{where} z: component 'z' does not exist on a 2D mesh")
    if "kind" in t:
        if given:
            raise ValueError(f"{where}: give either kind or components ({', '.join(given)})")
        kind = choice(t["kind"], ("clamped", "rollers"), f"{where} kind")
        if kind == "rollers" and boundary is None:
            raise ValueError(f"{where} kind: rollers needs a named boundary, not where alone")
        return _part(sc.clamped if kind == "clamped" else sc.rollers, boundary, cond)
    if not given:
        raise ValueError(f"{where} needs kind or at least one of x, y, z")
    return _part(sc.Displacement, boundary, cond,
                 {c: formula(t[c], f"{where} {c}", dim) for c in given})


def _load(t: dict, dim: int, where: str) -> sc.SurfaceLoad:
    keys(t, _names("[[load]]"), where, _TOP_KEYS)
    boundary, cond = _where(t, dim, where)
    if one_of(t, _exclusive("[[load]]"), where) == "pressure":
        return _part(sc.SurfaceLoad, boundary, cond,
                     pressure=formula(t["pressure"], f"{where} pressure", dim))
    v = t["traction"]
    if not isinstance(v, list) or len(v) != dim:
        raise ValueError(f"{where} traction must be a list of {dim} numbers or formulas "
                         f"on a {dim}D mesh, got {v!r}")
    return _part(sc.SurfaceLoad, boundary, cond, traction=tuple(
        formula(c, f"{where} traction[{i}]", dim) for i, c in enumerate(v)))
