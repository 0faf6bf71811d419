"""Scene files (TOML): the examples parse, bad files are refused naming the key."""
import dataclasses
import os
import re
from pathlib import Path

import meshio
import numpy as np
import pytest

from skxfem.fem.material import Material
from skxfem.fem.meshes import box
from skxfem.scene import Box, Interface, Scene, clamped, resolve_mesh, rollers
from skxfem.scene import file as scenefile
from skxfem.scene.expr import Expression
from skxfem.scene.file import BUILT_BOX, MAX_MAGNITUDE, load_scene
from skxfem.scene.settings import Solver

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

MINIMAL = '''
[mesh]
box = {n = 3, cell = "quad"}
[levelset]
expr = "y - 0.5"
'''


def write(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_01_plate_example_is_the_paper_plate():
    s = load_scene(EXAMPLES / "plate.toml")
    assert isinstance(s, Scene) and s.name == "plate"
    assert s.mesh == Box((4, 4, 5), "hex", (1.0, 1.0, 1.0))
    assert s.levelset.dim == 3
    np.testing.assert_allclose(s.levelset(np.array([[0.3], [0.7], [0.9]])), [0.4])
    assert s.material == Material(1.0, 0.3, "strain")
    assert s.displacements == (clamped("zmin"), rollers("xmin"), rollers("xmax"))
    [load] = s.loads
    assert load.boundary == "zmax" and load.pressure == Expression("4*y*(1 - y)", 3)
    assert (s.law, s.space, s.quadrature_order) == ("bonded", "vital", None)


def test_02_strip_and_inclusion_examples_parse():
    s = load_scene(EXAMPLES / "strip.toml")
    assert s.mesh == Box((4, 5), "quad") and s.levelset.dim == 2
    np.testing.assert_allclose(s.levelset(np.array([[0.0], [0.2]])), [-0.3])
    i = load_scene(EXAMPLES / "inclusion.toml")
    assert i.material == Material(10.0, 0.25, "stress") and i.quadrature_order == 2
    pin = i.displacements[0]
    assert pin.boundary == Expression("x < 1e-9 and y < 1e-9", 2, boolean=True)
    assert pin.components == {"x": 0.0, "y": 0.0}
    assert i.loads[0].traction == (0.0, Expression("-0.5 - 0.5*x", 2))


def test_03_defaults_come_from_the_dataclasses(tmp_path):
    s = load_scene(write(tmp_path, MINIMAL, "my_strip.toml"))
    assert s.name == "my_strip" and s.material == Material()
    assert (s.displacements, s.loads, s.law, s.space) == ((), (), "bonded", "vital")


def test_04_a_mesh_file_is_read_relative_to_the_scene_file(tmp_path):
    (tmp_path / "meshes").mkdir()
    box((2, 2, 3), "prism").save(tmp_path / "meshes" / "plate.vtu")
    s = load_scene(write(tmp_path, '''
[mesh]
file = "meshes/plate.vtu"
[levelset]
expr = "z - 0.5 - 0.2*x"
[[displacement]]
where = "z < 1e-9"
kind = "clamped"
'''))
    assert s.mesh == (tmp_path / "meshes" / "plate.vtu").resolve()
    assert s.levelset.dim == 3                      # an expr takes the mesh's dimension
    assert resolve_mesh(s).nelements == 2 * 2 * 2 * 3


BAD = [
    # (text appended to / replacing the minimal file, exception, words the message must hold)
    ("nmae = 'x'" + MINIMAL, ValueError, ["top level", "unknown key 'nmae'", "allowed keys"]),
    (MINIMAL.replace("cell =", "cells ="), ValueError, ["[mesh] box", "unknown key 'cells'"]),
    (MINIMAL.replace("n = 3", 'n = "four"'), TypeError, ["[mesh] box.n", "'four'"]),
    (MINIMAL.replace("n = 3", "n = [3, 3, 3]"), ValueError, ["[mesh] box", "Box n"]),
    (MINIMAL.replace('"quad"', '"hexa"'), ValueError, ["[mesh] box.cell", "hexa"]),
    (MINIMAL.replace('box = {n = 3, cell = "quad"}', 'box = {n = 3, cell = "quad"}\n'
                                                    'file = "m.msh"'),
     ValueError, ["[mesh] needs exactly one of box, file"]),
    (MINIMAL.replace('box = {n = 3, cell = "quad"}', 'file = "missing.msh"'),
     ValueError, ["[mesh] file 'missing.msh' not found"]),
    (MINIMAL.replace("[mesh]\nbox", "[meshx]\nbox"), ValueError, ["unknown key 'meshx'"]),
    (MINIMAL + "[material]\nE = 'abc'", TypeError, ["[material] E", "'abc'"]),
    (MINIMAL + "[material]\nE = -1.0", ValueError, ["[material]", "E must be a positive"]),
    (MINIMAL + "[material]\nnu = 0.3\nplane = 'strian'", ValueError, ["[material]", "plane"]),
    (MINIMAL + "[material]\nG = 1.0", ValueError, ["[material]", "unknown key 'G'"]),
    (MINIMAL.replace('expr = "y - 0.5"', 'expr = "open(y)"'), ValueError,
     ["[levelset] expr", "function call"]),
    (MINIMAL.replace('expr = "y - 0.5"', 'expr = "y.real"'), ValueError,
     ["[levelset] expr", "attribute access"]),
    (MINIMAL.replace('expr = "y - 0.5"', 'expr = "z - 0.5"'), ValueError,
     ["[levelset] expr", "uses z but the mesh is 2D"]),
    (MINIMAL.replace('expr = "y - 0.5"', 'expr = 0.5'), TypeError, ["[levelset] expr"]),
    (MINIMAL.replace('expr = "y - 0.5"', 'sphere = {center = [0, 0, 0], radius = 1}'),
     ValueError, ["[levelset] sphere", "3D shape but the mesh is 2D"]),
    (MINIMAL.replace('expr = "y - 0.5"', 'plane = {point = [0, 0.5], normal = [0, 1, 0]}'),
     ValueError, ["[levelset] plane.normal", "2 numbers"]),
    (MINIMAL.replace('expr = "y - 0.5"', 'plane = {point = [0, 0.5]}'),
     ValueError, ["[levelset] plane needs normal"]),
    (MINIMAL.replace('expr = "y - 0.5"', 'circle = {center = [0, 0], radius = -1}'),
     ValueError, ["[levelset] circle", "radius"]),
    (MINIMAL.replace('expr = "y - 0.5"', 'circle = {center = [0, 0], radius = "r"}'),
     TypeError, ["[levelset] circle.radius"]),
    (MINIMAL.replace('[levelset]\nexpr = "y - 0.5"', ''), ValueError, ["missing", "[levelset]"]),
    (MINIMAL + "[[displacement]]\nboundary = 'ymin'\nz = 0.0", ValueError,
     ["[[displacement]] #1 z", "2D mesh"]),
    (MINIMAL + "[[displacement]]\nboundary = 'ymin'\nx = 'open(y)'", ValueError,
     ["[[displacement]] #1 x", "function call"]),
    (MINIMAL + "[[displacement]]\nwhere = 'x + 1'\nx = 0", ValueError,
     ["[[displacement]] #1 where", "condition"]),
    (MINIMAL + "[[displacement]]\nwhere = 1\nx = 0", TypeError, ["[[displacement]] #1 where"]),
    (MINIMAL + "[[displacement]]\nx = 0", ValueError,        # both: issue 26, test_26
     ["[[displacement]] #1 needs boundary, where, or both"]),
    (MINIMAL + "[[displacement]]\nboundary = 'ymin'\nwhere = 'x > 2'\nx = 0", ValueError,
     ["[[displacement]] #1: boundary 'ymin' where 'x > 2' selects no node of the mesh"]),
    (MINIMAL + "[[displacement]]\nboundary = 'ymin'", ValueError,
     ["[[displacement]] #1 needs kind or"]),
    (MINIMAL + "[[displacement]]\nboundary = 'ymin'\nkind = 'fixed'", ValueError,
     ["[[displacement]] #1 kind", "clamped, rollers"]),
    (MINIMAL + "[[displacement]]\nwhere = 'x < 1'\nkind = 'rollers'", ValueError,
     ["[[displacement]] #1 kind", "named boundary"]),
    (MINIMAL + "[[displacement]]\nboundary = 'ymin'\nkind = 'clamped'\nx = 1", ValueError,
     ["[[displacement]] #1", "either kind or components"]),
    (MINIMAL + "[[displacement]]\nboundary = 'ymin'\nkind = 'clamped'\n"
               "[[displacement]]\nboundary = 'ymax'\nu = 1", ValueError,
     ["[[displacement]] #2", "unknown key 'u'"]),
    (MINIMAL + "[displacement]\nboundary = 'ymin'\nkind = 'clamped'", TypeError,
     ["[[displacement]]"]),
    (MINIMAL + "[[load]]\nboundary = 'ymax'\npressure = 'x.__class__'", ValueError,
     ["[[load]] #1 pressure", "attribute access"]),
    (MINIMAL + "[[load]]\nboundary = 'ymax'\npressure = '__import__(\"os\")'", ValueError,
     ["[[load]] #1 pressure", "function call"]),
    (MINIMAL + "[[load]]\nboundary = 'ymax'\npressure = 1\ntraction = [0, 1]", ValueError,
     ["[[load]] #1 needs exactly one of pressure, traction"]),
    (MINIMAL + "[[load]]\nboundary = 'ymax'\ntraction = [0, 0, 1]", ValueError,
     ["[[load]] #1 traction", "2 numbers"]),
    (MINIMAL + "[[load]]\nboundary = 'ymax'\ntraction = [0, true]", TypeError,
     ["[[load]] #1 traction[1]"]),
    (MINIMAL + "[[load]]\nboundary = 7\npressure = 1", TypeError, ["[[load]] #1 boundary"]),
    (MINIMAL + "[interface]\nlaw = 'glued'", ValueError, ["[interface] law", "bonded"]),
    (MINIMAL + "[interface]\nspace = 'stable'", ValueError, ["[interface] space", "naive"]),
    (MINIMAL + "[interface]\nadhesion = 0.3", ValueError, ["[interface]", "'adhesion'"]),
    (MINIMAL + "[interface]\nfriction = -0.3", ValueError, ["[interface] friction"]),
    (MINIMAL + "[interface]\nrho_n = 0", ValueError, ["[interface] rho_n"]),
    (MINIMAL + "[interface]\nsteps = []", ValueError, ["[interface] steps"]),
    (MINIMAL + "[solver]\nquadrature_order = 0", ValueError, ["[solver] quadrature_order"]),
    (MINIMAL + "[solver]\nquadrature_order = '2'", ValueError, ["[solver] quadrature_order"]),
    (MINIMAL + "[solver]\ntol = 1e-9", ValueError, ["[solver]", "unknown key 'tol'"]),
    (MINIMAL + "[solver]\nmax_iter = 5", ValueError, ["[solver] max_iter", "contact laws"]),
    ("name = 3" + MINIMAL, TypeError, ["name must be a non-empty string"]),
    ("interface = 3" + MINIMAL, TypeError, ["[interface] must be a table"]),
    ("[mesh\nbox = 1", ValueError, ["invalid TOML"]),
    (MINIMAL.replace('expr = "y - 0.5"', 'plane = {point = [0, 0.5], normal = [0, 0]}'),
     ValueError, ["[levelset] plane", "normal must be non-zero"]),
    (MINIMAL + "[[displacement]]\nboundary = 'ymin'\nx = nan", ValueError,
     ["[[displacement]] #1 x", "finite"]),
    (MINIMAL + "[[displacement]]\nboundary = 'ymin'\nkind = 'clamped'\n"
               "[[displacement]]\nwhere = 'x > 5'\nx = 0", ValueError,
     ["[[displacement]] #2", "selects no node"]),
    (MINIMAL + "[[displacement]]\nboundary = 'ymin'\nkind = 'clamped'\n"
               "[[displacement]]\nboundary = 'zmin'\nx = 0", ValueError,
     ["[[displacement]] #2 boundary 'zmin'", "xmin, xmax, ymin, ymax"]),
    (MINIMAL + "[[displacement]]\nboundary = 'left'\nkind = 'rollers'", ValueError,
     ["[[displacement]] #1", "rollers needs an axis-aligned face"]),
    (MINIMAL + "[[load]]\nwhere = 'y < -1'\npressure = 1", ValueError,
     ["[[load]] #1", "selects no facet"]),
]


@pytest.mark.parametrize("text, error, words", BAD)
def test_05_bad_files_are_refused_naming_the_key(tmp_path, text, error, words):
    with pytest.raises(error) as info:
        load_scene(write(tmp_path, text, "bad.toml"))
    message = str(info.value)
    assert message.startswith("bad.toml: "), message
    assert "displacements[" not in message and "loads[" not in message, message
    for w in words:
        assert w in message, f"{w!r} not in {message!r}"


def test_06_a_circle_on_a_3d_mesh_names_the_levelset_table(tmp_path):
    text = MINIMAL.replace('"quad"', '"hex"').replace(
        'expr = "y - 0.5"', 'circle = {center = [0.5, 0.5], radius = 0.3}')
    with pytest.raises(ValueError, match=r"\[levelset\] circle is a 2D shape but the mesh "
                                         r"is 3D; use sphere or expr"):
        load_scene(write(tmp_path, text))


def test_07_nan_coordinates_in_a_mesh_file_are_refused(tmp_path):
    m = box(2, "tri")
    p = m.p.T.copy()
    p[3, 1] = np.nan
    meshio.write(tmp_path / "nan.vtu", meshio.Mesh(p, [("triangle", m.t.T)]))
    text = MINIMAL.replace('box = {n = 3, cell = "quad"}', 'file = "nan.vtu"')
    with pytest.raises(ValueError, match=r"\[mesh\] file 'nan.vtu': mesh has NaN"):
        load_scene(write(tmp_path, text))


def test_08_an_unreadable_mesh_file_is_refused(tmp_path):
    (tmp_path / "junk.msh").write_text("not a mesh")
    text = MINIMAL.replace('box = {n = 3, cell = "quad"}', 'file = "junk.msh"')
    with pytest.raises(ValueError, match=r"\[mesh\] file 'junk.msh'"):
        load_scene(write(tmp_path, text))


def test_09_a_scene_file_never_runs_code(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    attack = "__import__('os').system('touch PWNED')"
    for key in ('[levelset]\nexpr', '[[load]]\nboundary = "ymax"\npressure'):
        text = MINIMAL.replace('[levelset]\nexpr = "y - 0.5"', '[levelset]\nexpr = "y"') \
            if key.startswith("[[") else MINIMAL.replace('[levelset]\nexpr = "y - 0.5"', '')
        with pytest.raises(ValueError, match="function call"):
            load_scene(write(tmp_path, f'{text}\n{key} = "{attack}"'))
    assert not (tmp_path / "PWNED").exists()


def test_10_solve_options_are_read_and_checked(tmp_path):
    """[solver] linear and max_iter are options of the solve: load_scene reads those
    the file sets into Scene.solver, checked."""
    assert load_scene(write(tmp_path, MINIMAL)).solver == Solver()
    text = MINIMAL + "[interface]\nlaw = 'frictionless'\n[solver]\nlinear = 'iterative'\n" \
        "max_iter = 40\n"
    scene = load_scene(write(tmp_path, text))
    assert (scene.law, scene.solver) == ("frictionless", Solver("iterative", max_iter=40))
    for bad, key in (("linear = 'cholesky'", "linear"), ("max_iter = 0", "max_iter"),
                     ("max_iter = 2.5", "max_iter")):
        with pytest.raises(ValueError, match=rf"^bad.toml: \[solver\] {key} must be"):
            load_scene(write(tmp_path, MINIMAL + f"[solver]\n{bad}\n", "bad.toml"))


def test_11_a_missing_folder_or_binary_scene_file_is_named(tmp_path):
    """load_scene refuses them, naming the file and the fix."""
    (tmp_path / "folder.toml").mkdir()
    (tmp_path / "latin1.toml").write_bytes('name = "f\xfchrung"\n'.encode("latin-1"))
    cases = [("missing.toml", ["does not exist", "check the path"]),
             ("folder.toml", ["is a folder", ".toml file"]),
             ("latin1.toml", ["not UTF-8", "0xfc", "save it as UTF-8"])]
    for name, words in cases:
        with pytest.raises(ValueError) as info:
            load_scene(tmp_path / name)
        message = str(info.value)
        assert message.startswith(f"{name}: ") and "\n" not in message, message
        for w in words:
            assert w in message, f"{w!r} not in {message!r}"
    with pytest.raises(FileNotFoundError):      # also what it was before: callers catch it
        load_scene(tmp_path / "missing.toml")
    with pytest.raises(TypeError, match="path must be the path of a .toml file"):
        load_scene(None)


def test_12_boundaries_of_a_mesh_file_are_checked_with_the_file_numbering(tmp_path):
    box((2, 2), "tri").save(tmp_path / "tri.vtu")
    text = MINIMAL.replace('box = {n = 3, cell = "quad"}', 'file = "tri.vtu"')
    clamp = "[[displacement]]\nboundary = 'ymin'\nkind = 'clamped'\n"
    for extra, words in (
            (clamp + "[[displacement]]\nboundary = 'left'\nx = 0",
             ["[[displacement]] #2", "unknown boundary 'left'", "xmin"]),
            (clamp + "[[displacement]]\nwhere = 'x > 5'\nx = 0",
             ["[[displacement]] #2", "selects no node"]),
            ("[[load]]\nboundary = 'ymax'\npressure = 1\n[[load]]\nwhere = 'x > 5'\n"
             "pressure = 1", ["[[load]] #2", "selects no facet"])):
        with pytest.raises(ValueError) as info:
            load_scene(write(tmp_path, text + extra))
        message = str(info.value)
        assert "displacements[" not in message and "loads[" not in message, message
        for w in words:
            assert w in message, f"{w!r} not in {message!r}"
    assert len(load_scene(write(tmp_path, text + clamp)).displacements) == 1


def test_13_load_scene_checks_the_solve_options_too(tmp_path):
    """A bad [solver] linear is refused by load_scene (it was accepted)."""
    bad = MINIMAL + "[solver]\nlinear = 'cholesky'\n"
    with pytest.raises(ValueError, match=r"^bad.toml: \[solver\] linear must be one of"):
        load_scene(write(tmp_path, bad, "bad.toml"))


# The schema (skxfem schema): printed from the tables the reader checks.

def toml(data: dict) -> str:
    """A scene as TOML text: top-level values, then tables, then arrays of tables."""
    def value(v):
        if isinstance(v, dict):
            return "{" + ", ".join(f"{k} = {value(x)}" for k, x in v.items()) + "}"
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return f'"{v}"' if isinstance(v, str) else repr(v)

    def tables(v):
        return isinstance(v, list) and v and all(isinstance(x, dict) for x in v)

    lines = [f"{k} = {value(v)}" for k, v in data.items()
             if not isinstance(v, dict) and not tables(v)]
    for k, v in data.items():
        if isinstance(v, dict):
            lines += [f"[{k}]"] + [f"{a} = {value(b)}" for a, b in v.items()]
    for k, v in data.items():
        if tables(v):
            for item in v:
                lines += [f"[[{k}]]"] + [f"{a} = {value(b)}" for a, b in item.items()]
    return "\n".join(lines) + "\n"


def base(dim: int) -> dict:
    """A valid scene, 2D (quad) or 3D (hex), with one support and one load."""
    last = "xyz"[dim - 1]
    return {"mesh": {"box": {"n": [4, 5] if dim == 2 else [2, 2, 3],
                             "cell": "quad" if dim == 2 else "hex"}},
            "levelset": {"plane": {"point": [0.0] * (dim - 1) + [0.5],
                                   "normal": [0.0] * (dim - 1) + [1.0]}},
            "material": {}, "interface": {}, "solver": {},
            "displacement": [{"boundary": f"{last}min", "kind": "clamped"}],
            "load": [{"boundary": f"{last}max", "pressure": 1.0}]}


def schema_tables(text: str) -> dict[str, list[str]]:
    """The keys printed under each table heading of the schema text."""
    from skxfem.scene.file import SCHEMA

    tables, current = {}, None
    for line in text.splitlines():
        heading = next((t for t in SCHEMA if line == t or line.startswith(t + ":")), None)
        if heading is not None:
            current = tables.setdefault(heading, [])
        elif current is not None and line.startswith("  ") and line[2] != " ":
            current.append(line.split()[0])
    return tables


def part(data: dict, table: str) -> dict:
    """The part of ``data`` that is ``table`` (its first item for an array of tables)."""
    if table == "the top level":
        return data
    if table.startswith("[["):
        return data[table.strip("[]")][0]
    outer, _, inner = table.strip("[]").partition("] ")
    return data[outer][inner] if inner else data[outer]


def rivals(table: str, key: str) -> list[str]:
    """The keys of ``table`` that cannot be given with ``key`` (its exclusive groups)."""
    from skxfem.scene.file import SCHEMA

    out = []
    for group in SCHEMA[table].exclusive:
        first, *rest = [k for k in group if k != "..."]
        if "..." in group:        # first, or one or more of the rest
            out += rest if key == first else [first] if key in rest else []
        elif key in group:
            out += [k for k in group if k != key]
    return out


def place(table: str, key: str, example):
    """The scene (and its dimension) that uses ``key`` of ``table`` with ``example``."""
    from skxfem.scene.file import SCHEMA

    dim = 3 if key in ("sphere", "z") or table == "[levelset] sphere" else 2
    data = base(dim)
    if table == "[[interface]]":                  # several interfaces: its level set in it
        data["interface"] = [dict(data.pop("levelset"))]
    if table == "[body_force]":                   # optional: not in the base
        data["body_force"] = {}
    if table == "[[step]]":                       # a load state (of a contact law)
        data["step"] = [{"name": "press"}]
        data["interface"] = {"law": "coulomb"}
    if table.startswith("[levelset] "):           # a shape: all its keys are required
        data["levelset"] = {table.split()[1]: {k.name: k.example for k in SCHEMA[table].keys}}
    elif table == "the top level" and key != "name":
        data.setdefault(key, example)             # a table: the base has it, or its default
    else:
        target = part(data, table)
        for k in rivals(table, key):
            target.pop(k, None)
        target[key] = example
    if key in ("max_iter", "friction", "step"):   # options of the contact laws
        part(data, "[[interface]]" if table == "[[interface]]" else "[interface]")["law"] = \
            "coulomb"
    if key in ("front", "enrichment", "enrichment_radius", "sif_radius"):
        # a crack's keys: a front, law free
        own = data["interface"][0] if table == "[[interface]]" else data["levelset"]
        own.setdefault("front", "x - 0.5")
        part(data, "[[interface]]" if table == "[[interface]]" else "[interface]")["law"] = \
            "free"
    given = data.get("interface")                 # coulomb needs its friction
    for t in given if isinstance(given, list) else [given] if given else []:
        if t.get("law") == "coulomb":
            t.setdefault("friction", 0.5)
    return data, dim


def test_14_the_schema_prints_every_key_the_reader_accepts(tmp_path):
    """For every table, the keys the reader lists when it refuses an unknown key are the
    keys `skxfem schema` prints under that table, in order."""
    from skxfem.scene.file import SCHEMA, schema

    printed = schema_tables(schema())
    assert list(printed) == list(SCHEMA)
    for table in SCHEMA:
        data, _ = place(table, SCHEMA[table].keys[0].name, SCHEMA[table].keys[0].example)
        target = part(data, table)
        target["bogus"] = 1
        with pytest.raises(ValueError, match="unknown key 'bogus'") as info:
            load_scene(write(tmp_path, toml(data)))
        allowed = str(info.value).split("allowed keys: ")[1].split(", ")
        assert allowed == printed[table] == list(SCHEMA[table].names), table


def test_15_every_key_of_the_schema_is_accepted_with_its_example(tmp_path):
    """Each key, given its example value where it belongs, makes a scene that loads."""
    from skxfem.scene.file import SCHEMA

    example_file = SCHEMA["[mesh]"].keys[1].example
    box((4, 5), "quad").save(tmp_path / example_file)        # [mesh] file's example
    for table, t in SCHEMA.items():
        for key in t.keys:
            data, dim = place(table, key.name, key.example)
            try:
                scene = load_scene(write(tmp_path, toml(data)))
            except (ValueError, TypeError) as e:
                raise AssertionError(f"{table} {key.name} = {key.example!r}: {e}") from None
            assert scene.dim == dim
    assert load_scene(write(tmp_path, toml(place("the top level", "name", "plate")[0]))
                      ).name == "plate"
    e = SCHEMA["[material]"].keys[0].example
    assert load_scene(write(tmp_path, toml(place("[material]", "E", e)[0]))).material.E == e


def test_16_the_schema_states_units_choices_and_functions():
    from skxfem.linalg.choice import LINEAR
    from skxfem.scene import CELLS, CONTACT_LAWS, LAWS, SPACES
    from skxfem.scene.expr import FUNCTIONS
    from skxfem.scene.file import schema

    text = schema()
    flat = " ".join(text.split())
    assert "Units are consistent and your choice" in flat
    for unit in ("lengths in L", "F/L²", "rho_n in F/L³", "no unit"):
        assert unit in flat, unit
    for choices in (CELLS, LAWS + CONTACT_LAWS, SPACES, LINEAR, FUNCTIONS):
        assert " ".join(choices) in flat, choices
    assert all(len(line) <= 88 for line in text.splitlines())
    rows = {line.split()[0]: line for line in text.splitlines() if line.startswith("  ")}
    assert "[F/L²]" in rows["E"] and "[F/L²]" in rows["pressure"] and "[L]" in rows["size"]
    assert "[F/L³]" in rows["rho_n"] and "[L]" in rows["radius"]


def test_17_skxfem_schema_prints_it_and_run_help_points_to_it(capsys):
    from skxfem.app.cli import main
    from skxfem.scene.file import schema

    assert main(["schema"]) == 0
    assert capsys.readouterr().out == schema()
    with pytest.raises(SystemExit) as done:
        main(["run", "--help"])
    assert done.value.code == 0 and "skxfem schema" in capsys.readouterr().out
    with pytest.raises(SystemExit) as done:
        main(["--help"])
    assert done.value.code == 0 and "schema" in capsys.readouterr().out


@pytest.mark.parametrize("dim", [2, 3])
def test_18_formulas_with_functions_solve_like_the_built_in_shapes(tmp_path, dim):
    """ψ = sqrt(...) - r in a scene file is the circle (2D) or the sphere (3D): the same
    pressures to round-off; a pressure with sqrt loads and solves."""
    import skxfem

    center = [0.5, 0.45, 0.55][:dim]
    shape = "circle" if dim == 2 else "sphere"
    data = base(dim)
    data["mesh"]["box"]["n"] = 6 if dim == 2 else 4
    data["load"] = [{"boundary": f"{'xyz'[dim - 1]}max",
                     "pressure": "1 + 0.5*sqrt(abs(x - 0.3)) * cos(pi*x)"}]
    data["levelset"] = {shape: {"center": center, "radius": 0.3}}
    built = skxfem.solve(load_scene(write(tmp_path, toml(data))))
    distance = " + ".join(f"({c} - {v})**2" for c, v in zip("xyz", center, strict=False))
    data["levelset"] = {"expr": f"sqrt({distance}) - 0.3"}
    written = skxfem.solve(load_scene(write(tmp_path, toml(data))))
    np.testing.assert_allclose(written.points, built.points, atol=1e-12)
    np.testing.assert_allclose(written.pressure, built.pressure, atol=1e-9)
    assert np.ptp(built.pressure) > 0.1


def test_19_a_formula_outside_its_domain_is_refused_not_solved(tmp_path, capsys):
    """sqrt(x - 0.5) on the top of [0, 1]²: one line naming sqrt, exit 2, nothing written."""
    from skxfem.app.cli import main

    data = base(2)
    data["load"][0]["pressure"] = "sqrt(x - 0.5)"
    path = write(tmp_path, toml(data))
    assert main(["run", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "sqrt" in err and "needs a number >= 0" in err
    assert not (tmp_path / "o").exists()


def test_14_a_mesh_path_that_is_no_file_is_named_for_what_it_is(tmp_path):
    """A folder or a FIFO was "not found"; a loop of symbolic links a RuntimeError."""
    (tmp_path / "folder.msh").mkdir()
    os.mkfifo(tmp_path / "fifo.msh")
    os.symlink("loop2.msh", tmp_path / "loop1.msh")
    os.symlink("loop1.msh", tmp_path / "loop2.msh")
    for name, words in (("folder.msh", "is a folder"), ("fifo.msh", "is a FIFO"),
                        ("loop1.msh", "is a loop of symbolic links"), ("none.msh", "not found")):
        text = MINIMAL.replace('box = {n = 3, cell = "quad"}', f'file = "{name}"')
        with pytest.raises(ValueError, match=rf"^scene.toml: \[mesh\] file '{name}' {words}"):
            load_scene(write(tmp_path, text))


def test_15_an_unreadable_mesh_file_is_one_line_with_what_meshio_said(tmp_path, capfd):
    """meshio prints its own messages (on stdout and stderr) before it gives up: they are
    part of the error, and nothing else is printed."""
    (tmp_path / "junk.vtu").write_text("<VTKFile")
    text = MINIMAL.replace('box = {n = 3, cell = "quad"}', 'file = "junk.vtu"')
    with pytest.raises(ValueError, match=r"could not be read by meshio \(Error: Couldn't "
                                         r"read file .*junk.vtu as vtu\)") as info:
        load_scene(write(tmp_path, text))
    assert "\n" not in str(info.value)
    assert capfd.readouterr() == ("", "")


def loaded(E, corner, load) -> str:
    """MINIMAL, clamped below, a top corner moved by ``corner``, loaded above."""
    return MINIMAL + (f"[material]\nE = {E}\n"
                      f"[[displacement]]\nboundary = 'ymin'\nkind = 'clamped'\n"
                      f"[[displacement]]\nwhere = 'x > 0.99 and y > 0.99'\nx = {corner}\n"
                      f"[[load]]\nboundary = 'ymax'\n{load}\n")


@pytest.mark.parametrize("E, corner, load, words", [
    (1.0, 0.0, "pressure = 1e300", r"#1 pressure: 1e\+300 is beyond the largest load"),
    (1.0, 0.0, "traction = [0, -1e151]", r"#1 traction\[1\]: -1e\+151 is beyond"),
    (1e-100, 0.0, "pressure = 1e60", r"E = 1e-100 .* \|p\| L / E = 1e\+160"),
    (1.0, 9223372036854775808, "pressure = 1", r"#2 x: 9.22337e\+18 is more than 1000 times"),
    (1.0, -1001.0, "pressure = 1", r"#2 x: -1001 is more than 1000 times"),
])
def test_16_numbers_beyond_what_the_solve_handles_are_refused_when_read(
        tmp_path, E, corner, load, words):
    """pressure = 1e300 ended in a RuntimeError after three numpy warnings, a corner
    moved by 2^63 in one (exit 1); the largest values are measured (MAX_MAGNITUDE,
    MAX_SHIFT), and they are accepted."""
    with pytest.raises(ValueError, match=words):
        load_scene(write(tmp_path, loaded(E=E, corner=corner, load=load)))
    for edge in (loaded(E=1.0, corner=1000.0, load=f"pressure = {MAX_MAGNITUDE}"),
                 loaded(E=1e-100, corner=0.0, load="pressure = 1e50")):
        assert load_scene(write(tmp_path, edge)).loads[0].pressure in (MAX_MAGNITUDE, 1e50)


@pytest.mark.parametrize("corner, load, words", [
    ('"1e10*y"', "pressure = 1", r"#2 x: 1e10\*y reaches 1e\+10 at \(1, 1\), which is more "
                                 r"than 1000 times the size of the body \(1\)"),
    ('"exp(50*y)"', "pressure = 1", r"#2 x: exp\(50\*y\) reaches 5.18e\+21 at \(1, 1\)"),
    ('"1000*x*y"', "pressure = '1e151*x'", r"#1 pressure: 1e151\*x reaches 1e\+151 at "
                                          r"\(1, 1\), which is beyond the largest load"),
])
def test_16b_formulas_are_bounded_as_numbers_are_at_the_nodes(tmp_path, corner, load, words):
    """The 1000-body-sizes limit applied to numbers only: x = "1e10*y" or "exp(50*y)"
    (5e21) ran.  A formula is evaluated at the nodes it acts on (the top corner: y = 1),
    and a value at the limit (1000*x*y = 1000 there) is accepted."""
    with pytest.raises(ValueError, match=words):
        load_scene(write(tmp_path, loaded(E=1.0, corner=corner, load=load)))
    load_scene(write(tmp_path, loaded(E=1.0, corner='"1000*x*y"', load="pressure = '1e150*x'")))


@pytest.mark.parametrize("n", ["9223372036854775807", "3037000500",
                               "[4294967297, 4294967295]"])
def test_17_an_absurd_box_is_not_built_to_check_its_selections(tmp_path, monkeypatch, n):
    """np.prod(n) wrapped below BUILT_BOX, and the box was built to check a 'where'
    (IndexError, or a 32 GiB allocation): the count is exact now."""
    monkeypatch.setattr(scenefile.meshes, "box", lambda *a: pytest.fail("the box was built"))
    text = MINIMAL.replace("n = 3", f"n = {n}") + \
        "[[displacement]]\nwhere = 'x < 1e-9'\nx = 0\n"
    assert load_scene(write(tmp_path, text)).mesh.n[0] > BUILT_BOX


# Several interfaces: [[interface]] tables.

TWO = '''
steps = [0.5, 1.0]
[mesh]
box = {n = 3, cell = "quad"}
[[interface]]
plane = {point = [0, 0.3], normal = [0, 1]}
law = "frictionless"
[[interface]]
expr = "y - 0.8"
law = "coulomb"
friction = 0.4
rho_n = 3.0
space = "winner"
'''


def test_20_interface_tables_give_each_interface_its_level_set_and_law(tmp_path):
    s = load_scene(write(tmp_path, TWO))
    assert len(s.interfaces) == 2 and s.levelset is None and s.law is None
    assert s.steps == (0.5, 1.0)
    low, high = s.interfaces
    assert (low.law, low.space, low.friction, low.rho_n) == ("frictionless", "vital", None,
                                                             None)
    assert (high.law, high.space, high.friction, high.rho_n) == ("coulomb", "winner", 0.4,
                                                                 3.0)
    x = np.array([[0.2], [0.5]])
    assert np.allclose([low.levelset(x), high.levelset(x)], [[0.2], [-0.3]])
    old = load_scene(write(tmp_path, MINIMAL))
    assert old.law == "bonded" and old.interfaces == (
        Interface(old.levelset, "bonded"),)                      # the short form reads
    top = MINIMAL.replace("[mesh]", "steps = [0.5, 1.0]\n[mesh]")
    assert load_scene(write(tmp_path, top)).steps == (0.5, 1.0)


@pytest.mark.parametrize("change, message", [
    (lambda t: t.replace("[mesh]", '[levelset]\nexpr = "y"\n[mesh]'),
     r"\[levelset\] with \[\[interface\]\] tables: .* remove \[levelset\]"),
    (lambda t: t.replace('expr = "y - 0.8"', 'expr = "y - 0.8"\ncircle = {center = [0, 0], '
                         'radius = 1}'),
     r"\[\[interface\]\] #2 needs exactly one of plane, circle, sphere, expr; got circle, "
     r"expr"),
    (lambda t: t.replace('expr = "y - 0.8"\n', ''),
     r"\[\[interface\]\] #2 needs exactly one of plane, circle, sphere, expr; got none"),
    (lambda t: t.replace('law = "coulomb"', 'law = "glued"'),
     r"\[\[interface\]\] #2 law must be one of"),
    (lambda t: t.replace("friction = 0.4", "friction = -0.4"),
     r"\[\[interface\]\] #2 friction must be >= 0"),
    (lambda t: t.replace("rho_n = 3.0", "steps = [1.0]"),
     r"\[\[interface\]\] #2: unknown key 'steps'"),
    (lambda t: t.replace('expr = "y - 0.8"', 'expr = "y - 0.8 + z"'),
     r"\[\[interface\]\] #2 expr"),
    (lambda t: t.replace('normal = [0, 1]', 'normal = [0, 0, 1]'),
     r"\[\[interface\]\] #1 plane.normal must be a list of 2 numbers"),
])
def test_21_interface_tables_refused_naming_the_table(tmp_path, change, message):
    with pytest.raises((ValueError, TypeError), match=message):
        load_scene(write(tmp_path, change(TWO)))


def test_22_interface_forms_refused_together(tmp_path):
    with pytest.raises(ValueError, match="missing table \\[levelset\\]"):
        load_scene(write(tmp_path, MINIMAL.replace('[levelset]\nexpr = "y - 0.5"\n', "")))
    with pytest.raises(ValueError, match="interface is an empty list"):
        load_scene(write(tmp_path, "interface = []\n" + TWO.split("[[interface]]")[0]))
    twice = MINIMAL.replace("[mesh]", "steps = [1.0]\n[mesh]") + "[interface]\nsteps = [1.0]\n"
    with pytest.raises(ValueError, match="steps is given twice"):
        load_scene(write(tmp_path, twice))
    ties = TWO.replace('law = "frictionless"', 'law = "bonded"').replace(
        'law = "coulomb"', 'law = "bilateral"').replace("friction = 0.4\n", "") \
        + "[solver]\nmax_iter = 5\n"
    with pytest.raises(ValueError, match=r"max_iter applies to the contact laws .* the law "
                                         r"is \['bonded', 'bilateral'\]"):
        load_scene(write(tmp_path, ties))
    with_contact = TWO + "[solver]\nmax_iter = 5\n"
    assert load_scene(write(tmp_path, with_contact)).solver.max_iter == 5


# --- issue 26: what the file says ---------------------------------------------------------

@pytest.mark.parametrize("law", ["bonded", "bilateral", "frictionless", "adhesive"])
def test_26_coulomb_needs_its_friction_and_no_other_law_takes_one(tmp_path, law):
    """No default μ: law coulomb without friction is refused, naming the key, in
    [interface] and in an [[interface]] table; friction with a law without friction too."""
    for text, where in ((MINIMAL + '[interface]\nlaw = "coulomb"\n', "[interface]"),
                        (TWO.replace("friction = 0.4\n", ""), "[[interface]] #2")):
        with pytest.raises(ValueError) as info:
            load_scene(write(tmp_path, text, "bad.toml"))
        assert str(info.value).startswith(f"bad.toml: {where} law 'coulomb' needs friction "
                                          f"(Coulomb's mu, a number >= 0): add friction = ")
    for text, where in ((MINIMAL + f'[interface]\nlaw = "{law}"\nfriction = 0.0\n',
                         "[interface]"),
                        (TWO.replace('law = "frictionless"', f'law = "{law}"\nfriction = 0.2'),
                         "[[interface]] #1")):
        with pytest.raises(ValueError) as info:
            load_scene(write(tmp_path, text, "bad.toml"))
        assert str(info.value) == (f"bad.toml: {where} friction (Coulomb's mu) is taken by law "
                                   f"'coulomb' only; law '{law}' has no friction: remove "
                                   f"friction")
    zero = load_scene(write(tmp_path, MINIMAL + '[interface]\nlaw = "coulomb"\nfriction = 0\n'))
    assert (zero.law, zero.friction) == ("coulomb", 0.0)     # given on purpose: accepted


def test_26b_the_solver_table_is_the_scenes_solver(tmp_path):
    """[solver] linear, linear_tol and max_iter load into Scene.solver (else the
    defaults)."""
    assert load_scene(write(tmp_path, MINIMAL)).solver == Solver()
    text = (MINIMAL + "[interface]\nlaw = 'frictionless'\n[solver]\nlinear = 'direct'\n"
            "linear_tol = 1e-9\nmax_iter = 40\n")
    assert load_scene(write(tmp_path, text)).solver == Solver("direct", 1e-9, 40)
    for bad, key in (("linear_tol = 0", "linear_tol"), ("linear_tol = true", "linear_tol"),
                     ("max_iter = true", "max_iter")):
        with pytest.raises(ValueError, match=rf"^bad.toml: \[solver\] {key} must be"):
            load_scene(write(tmp_path, MINIMAL + "[interface]\nlaw = 'frictionless'\n"
                             f"[solver]\n{bad}\n", "bad.toml"))


# --- issue 26, item 6: scene-file traps -----------------------------------------------

@pytest.mark.parametrize("text, where", [
    (TWO.replace("steps = [0.5, 1.0]\n", "") + "steps = [0.5, 1.0]\n", "[[interface]] #2"),
    (MINIMAL + '[material]\nE = 2.0\nname = "late"\n', "[material]"),
    (MINIMAL + "[[load]]\nboundary = 'ymax'\npressure = 1\nsteps = [1]\n", "[[load]] #1"),
])
def test_25_a_top_level_key_after_a_table_is_said_to_belong_before_it(tmp_path, text, where):
    """steps written after the [[interface]] tables falls into the last one (TOML) and
    was refused as "unknown key 'steps'" only."""
    key = "steps" if "steps" in text.splitlines()[-1] else "name"
    with pytest.raises(ValueError, match=rf"{re.escape(where)}: unknown key '{key}'; allowed "
                                         rf"keys: .*\. '{key}' is a top-level key, but TOML "
                                         rf"puts every key written after a table header into "
                                         rf"that table: write the top-level keys \(name, "
                                         rf"steps\) before the first table"):
        load_scene(write(tmp_path, text))
    fixed = text.splitlines()[-1] + "\n" + "\n".join(text.splitlines()[:-1]) + "\n"
    assert load_scene(write(tmp_path, fixed))


def test_26_a_load_or_a_support_may_take_a_face_and_a_condition(tmp_path):
    """[[load]] combines boundary and where: the part of a face where the condition holds
    (the ymax face right of x = 0.5 here), as the Python selection of the same facets;
    a [[displacement]] too (the nodes of xmax above y = 0.5)."""
    import skxfem
    from skxfem.scene import Displacement, SurfaceLoad

    text = MINIMAL.replace("n = 3", "n = 4") + (
        "[[displacement]]\nboundary = 'ymin'\nkind = 'clamped'\n"
        "[[displacement]]\nboundary = 'xmax'\nwhere = 'y > 0.5'\nx = 0.01\n"
        "[[load]]\nboundary = 'ymax'\nwhere = 'x > 0.5'\npressure = 2.0\n")
    s = load_scene(write(tmp_path, text))
    load, moved = s.loads[0], s.displacements[1]
    assert (load.boundary, load.where.text, moved.boundary, moved.where.text) == \
        ("ymax", "x > 0.5", "xmax", "y > 0.5")
    top = 1 - 1e-9
    same = dataclasses.replace(s, displacements=(
        clamped("ymin"), Displacement(lambda x: (x[0] > top) & (x[1] > 0.5), {"x": 0.01})),
        loads=(SurfaceLoad(lambda x: (x[1] > top) & (x[0] > 0.5), pressure=2.0),))
    a, b = skxfem.solve(s), skxfem.solve(same)
    np.testing.assert_array_equal(a.problem.F, b.problem.F)
    np.testing.assert_array_equal(a.problem.g, b.problem.g)
    assert a.problem.D.tolist() == b.problem.D.tolist()
    down = a.problem.F[a.problem.V.basis.nodal_dofs[1]].sum()   # p times the width 0.5
    assert down == pytest.approx(-2.0 * 0.5, rel=1e-12)


# --- issue 26, item 4: a load path in the file -----------------------------------------

HISTORY = (Path(__file__).resolve().parents[1] / "examples" / "history.toml").read_text()
"""examples/history.toml: press, shear, then unload with the law changed to bonded."""


def test_27_a_file_history_of_load_states_is_the_python_history(tmp_path):
    """[[step]] tables, each with its own loads and imposed displacements (press, then
    shear), solve as skxfem.contact.solve(scene, history=[press, shear]) does, to the
    bit; a state may change the law (unload, bonded)."""
    import skxfem
    from skxfem import contact
    from skxfem.levelset import plane
    from skxfem.scene import Displacement, SurfaceLoad

    s = load_scene(write(tmp_path, HISTORY))
    assert [st.name for st in s.steps] == ["press", "shear", "unload"]
    press = Scene(Box((4, 5), "quad"), plane((0.0, 0.5), (0.0, 1.0)), name="press",
                  displacements=(clamped("ymin"), Displacement("ymax", {"x": 0.0})),
                  loads=(SurfaceLoad("ymax", pressure=1.0),), law="coulomb", friction=0.5)
    shear = dataclasses.replace(press, name="shear", displacements=(
        clamped("ymin"), Displacement("ymax", {"x": 2.0})))
    unload = dataclasses.replace(shear, name="unload", loads=(), law="bonded", friction=None)
    by_file = skxfem.solve(s)
    by_python = contact.solve(press, history=[press, shear, unload])
    assert [st.load for st in by_file.steps] == ["press", "shear", "unload"]
    for a, b in zip(by_file.steps, by_python.steps, strict=True):
        np.testing.assert_array_equal(a.U, b.U)
        np.testing.assert_array_equal(a.pressure, b.pressure)
        np.testing.assert_array_equal(a.status, b.status)
    assert by_file.steps[1].status.tolist() != by_file.steps[0].status.tolist()  # it slides
    assert [st.law for st in by_file.steps] == [("coulomb",), ("coulomb",), ("bonded",)]


@pytest.mark.parametrize("edit, words", [
    (lambda t: "steps = [1.0]\n" + t, "steps and [[step]] tables are both given"),
    (lambda t: t.replace('law = "coulomb"\nfriction = 0.5', 'law = "bonded"'),
     "[[step]] tables are the load states of a contact solve; the law is 'bonded'"),
    (lambda t: t.replace('name = "shear"', 'name = "shear"\nlaw = "glue"'),
     "[[step]] #2 law must be one of bonded, bilateral, frictionless, coulomb, adhesive"),
    (lambda t: t.replace('name = "shear"', 'name = "shear"\nfriction = -1.0'),
     "[[step]] #2: Interface friction (Coulomb's mu) must be a number >= 0"),
    (lambda t: t.replace("x = 2.0", "x = 5000.0"),
     "[[step]] #2 [[step.displacement]] #1 x: 5000 is more than 1000 times"),
    (lambda t: t.replace("x = 2.0", "x = 2.0\nbogus = 1"),
     "[[step]] #2 [[step.displacement]] #1: unknown key 'bogus'"),
])
def test_28_bad_step_tables_are_refused_naming_them(tmp_path, edit, words):
    with pytest.raises((ValueError, TypeError)) as info:
        load_scene(write(tmp_path, edit(HISTORY)))
    assert words in str(info.value), info.value


HANGING = '''
name = "hanging"
[mesh]
box = {n = [3, 6], cell = "quad", size = [1.0, 1.2]}
[levelset]
expr = "y - 0.5"
[material]
E = 2.0
nu = 0.0
[body_force]
force = [0, "-3"]                  # rho g = 3, down
[[displacement]]
boundary = "ymax"
kind = "clamped"
'''


@pytest.mark.parametrize("cell, n", [("quad", "[3, 6]"), ("hex", "[2, 2, 6]")])
def test_29_a_block_hanging_under_gravity_has_the_exact_stress_and_sag(tmp_path, cell, n):
    """A block of height H = 1.2 hangs from its clamped top under gravity ρg = 3 (ν = 0:
    a bar): σ_yy = ρg y, so Γ at y = 0.5 carries the weight below it, p = -ρg 0.5 (a
    tension), and the bottom sags by u = -ρg H²/(2E) (Q1 elements are nodally exact)."""
    import skxfem

    text = HANGING.replace('cell = "quad"', f'cell = "{cell}"').replace("[3, 6]", n)
    if cell == "hex":
        text = (text.replace("size = [1.0, 1.2]", "size = [1.0, 1.0, 1.2]")
                .replace('expr = "y - 0.5"', 'expr = "z - 0.5"')
                .replace('force = [0, "-3"]', 'force = [0, 0, "-3"]')
                .replace("ymax", "zmax"))
    s = load_scene(write(tmp_path, text))
    assert [float(b) if not callable(b) else b.text for b in s.body_force] == \
        [0.0] * (s.dim - 1) + ["-3"]
    r = skxfem.solve(s)
    np.testing.assert_allclose(r.pressure, -3 * 0.5, rtol=1e-12)
    bottom = r.mesh.p[-1] < 1e-9
    np.testing.assert_allclose(r.u_minus[-1][bottom], -3 * 1.2 ** 2 / (2 * 2.0), rtol=1e-12)
    np.testing.assert_allclose(r.u_minus[:-1], 0, atol=1e-13)    # ν = 0: no sideways motion
