"""The size guard: counts are upper bounds, memory within a stated factor, refusals clear."""
import dataclasses
import json
import re
import subprocess
import sys

import meshio
import numpy as np
import pytest

from skxfem import scenes
from skxfem.fem import meshes
from skxfem.levelset import circle, plane, sphere
from skxfem.scene import Box, Scene, clamped, resolve_mesh
from skxfem.solver import solve
from skxfem.studies import budget
from skxfem.studies.budget import Estimate, TooLargeError, check, estimate, parse_bytes

FACTOR = 4
"""The estimate is at most this many times the measured peak (measured 1.1-3.1)."""


def scene_of(cell, n=4):
    if cell in ("tri", "quad"):
        return scenes.strip(n, cell=cell)
    # the naive space: the estimate counts one multiplier per cut edge and component
    hexes = scenes.paper_plate(n, cell="hex", space="naive")
    return dataclasses.replace(hexes, mesh=Box(hexes.mesh.n, cell))


def test_01_counts_are_exact_or_upper_bounds(cell):
    s = scene_of(cell)
    e = estimate(s)
    r = solve(s)
    assert (e.n_nodes, e.n_cells) == (r.mesh.nvertices, r.mesh.nelements)
    assert r.n_dofs <= e.n_dofs <= 1.5 * r.n_dofs
    m = r.n_multipliers + r.removed                       # before removing dependent ones
    assert m <= e.n_multipliers <= 3 * m
    if cell in ("quad", "hex"):                           # edges only along the axes: exact
        # (the count of every cut edge and component: the solve leaves out those
        # whose jump a support holds, here the x-jump on the plate's roller faces)
        assert e.n_multipliers == r.mesh.dim() * r.points.shape[1]


@pytest.mark.parametrize("law", ["bonded", "bilateral"])
def test_02_a_curved_interface_and_a_mesh_object_give_the_same_bounds(law):
    # the circle crosses the clamped bottom: a disc inside, tied by its normal jump
    # alone (bilateral), could turn about its centre and is refused (skxfem.linalg.rigid)
    s = Scene(Box((7, 6), "tri"), circle((0.5, 0.2), 0.31), law=law,
              displacements=(clamped("ymin"),))
    from_box = estimate(s)
    from_mesh = estimate(dataclasses.replace(s, mesh=resolve_mesh(s)))
    assert from_box.n_nodes == from_mesh.n_nodes and from_box.n_cells == from_mesh.n_cells
    assert from_mesh.n_dofs <= from_box.n_dofs        # the corners of the cut squares
    assert from_mesh.n_multipliers <= from_box.n_multipliers   # both diagonals counted
    r = solve(s)
    assert r.n_dofs <= from_mesh.n_dofs
    assert r.n_multipliers + r.removed <= from_mesh.n_multipliers


def test_03_a_mesh_file_is_counted_from_the_file(tmp_path):
    m = meshes.box(3, "tet")
    meshio.write(tmp_path / "m.vtu", meshio.Mesh(m.p.T, [("tetra", m.t.T)]))
    e = estimate(Scene(tmp_path / "m.vtu", sphere((0.5, 0.5, 0.5), 0.4)))
    assert (e.n_nodes, e.n_cells) == (64, 162) and e.n_dofs > 3 * 64


def test_04_a_box_is_never_built(monkeypatch):
    """A triangle strip of 1500 x 1501 cells: counted slab by slab, not meshed."""
    monkeypatch.setattr(meshes, "box", lambda *a, **k: pytest.fail("the box was built"))
    e = estimate(scenes.strip(1500, cell="tri"))
    assert e.n_nodes == 1501 * 1502 and e.n_cells == 2 * 1500 * 1501
    assert e.n_dofs == 2 * (1501 * 1502 + 2 * 1501)      # two rows of nodes enriched
    assert e.bytes > 2**30


def test_05_check_refuses_with_the_estimate_and_the_option():
    s = scenes.strip(10000, cell="tri")                   # 4 GB in 21 s, before the guard
    with pytest.raises(TooLargeError, match=r"the scene 'strip\w*' needs at least [\d.]+ [GT]B") \
            as e:
        check(s, 4 * 2**30, "--max-memory")
    message = str(e.value)
    assert "100030002 nodes" in message and "limit is 4 GB" in message
    assert "either solve" in message
    assert "--max-memory" in message and isinstance(e.value, ValueError)
    small = scenes.strip(4)
    assert isinstance(check(small), Estimate)
    with pytest.raises(TooLargeError, match=r"needs about .* max_bytes=\d+\)$"):
        check(small, estimate(small).bytes - 1)
    with pytest.raises(ValueError, match="max_bytes"):
        check(small, 0)


@pytest.mark.parametrize("text, value", [("4G", 4 * 2**30), ("1.5 GB", 3 * 2**29),
                                         ("500m", 500 * 2**20), ("2048", 2048)])
def test_06_sizes_parse(text, value):
    assert parse_bytes(text) == value


@pytest.mark.parametrize("text", ["", "G", "-1G", "lots", "nanG", "0"])
def test_07_bad_sizes_are_refused(text):
    with pytest.raises(ValueError, match="positive number"):
        parse_bytes(text)


PEAK = r"""
import json, sys
from skxfem import scenes
from skxfem.studies import budget
from skxfem.solver import solve

def status(key):                             # kB in /proc/self/status
    with open("/proc/self/status") as f:
        return 1024 * int(next(l for l in f if l.startswith(key)).split()[1])

kind, cell, n, linear = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
solve(scenes.strip(2, cell="quad"), linear=linear)   # imports and caches before measuring
scene = {"strip": scenes.strip, "plate": scenes.paper_plate}[kind](n, cell=cell)
before = status("VmRSS:")
with open("/proc/self/clear_refs", "w") as f:
    f.write("5")                             # reset the peak (VmHWM) to the current RSS
solve(scene, linear=linear)
print(json.dumps({"measured": status("VmHWM:") - before,
                  "estimate": budget.estimate(scene, linear=linear).bytes}))
"""


@pytest.mark.parametrize("case", ["strip:tri:128:direct", "strip:quad:64:direct",
                                  "plate:prism:8:direct", "plate:hex:16:direct",
                                  "strip:tri:256:iterative", "plate:hex:12:iterative"])
def test_08_memory_is_an_upper_bound_within_the_stated_factor(case):
    """Peak resident memory added by the solve, in a fresh process (Linux: the peak
    VmHWM is reset just before the solve, so import-time peaks do not count), for
    both linear solvers (the iterative model is bytes per unknown)."""
    if case.endswith("iterative"):
        pytest.importorskip("pyamg")
    done = subprocess.run([sys.executable, "-c", PEAK, *case.split(":")], capture_output=True,
                          text=True, timeout=300, check=True)
    r = json.loads(done.stdout)
    assert r["measured"] > 20 * 2**20, "large enough to be measured"
    assert r["measured"] <= r["estimate"] <= FACTOR * r["measured"], r


def test_11_the_estimate_follows_the_linear_solver():
    """auto resolves as the solve does (skxfem.linalg.choice.choose_linear); the
    iterative path needs far less than the direct one in 3D; contact takes it
    too, every law (Coulomb's GMRES basis counts)."""
    plate = scenes.paper_plate(16, cell="hex")               # 17k unknowns: iterative
    auto, direct = estimate(plate), estimate(plate, linear="direct")
    assert auto.linear == "iterative" and direct.linear == "direct"
    assert auto.bytes < direct.bytes / 4
    assert estimate(scenes.paper_plate(4, cell="hex")).linear == "direct"   # 1.6k unknowns
    contact = dataclasses.replace(plate, law="frictionless")
    assert estimate(contact).linear == estimate(contact, linear="iterative").linear \
        == "iterative"
    coulomb = dataclasses.replace(plate, law="coulomb", friction=0.3)
    assert estimate(coulomb).linear == "iterative"
    assert estimate(coulomb, linear="direct").linear == "direct"
    assert estimate(coulomb).bytes > estimate(contact).bytes
    with pytest.raises(ValueError, match="linear must be one of"):
        estimate(plate, linear="cg")


def test_09_the_estimate_grows_with_the_mesh_and_the_law():
    sizes = [estimate(scenes.paper_plate(n, cell="prism")).bytes for n in (4, 8, 16)]
    assert sizes[0] < sizes[1] < sizes[2]
    plate = scenes.paper_plate(8, cell="prism")
    tie = estimate(dataclasses.replace(plate, law="bilateral"))
    assert tie.n_multipliers * 3 == estimate(plate).n_multipliers
    assert estimate(Scene(Box(3, "hex"), plane((0, 0, 2), (0, 0, 1)))).n_dofs == 3 * 64


def test_10_estimate_needs_a_scene():
    with pytest.raises(TypeError, match="Scene"):
        estimate("plate.toml")
    assert budget.DEFAULT_MAX_BYTES == 4 * 2**30
    np.testing.assert_equal(budget.format_bytes(budget.DEFAULT_MAX_BYTES), "4 GB")


@pytest.mark.parametrize("n, cell", [((3000, 3000, 3000), "hex"), ((10**8, 10**8), "quad")])
def test_12_a_huge_box_is_refused_before_its_levelset_is_evaluated(n, cell, monkeypatch):
    """Without an interface the box already needs more than the limit: refused from
    its cell counts alone ('at least'), ψ never evaluated (the grid sweep took 40 s
    and 1.7 GB at 3000³, and hung at 10⁸ × 10⁸)."""
    import skxfem.studies.budget as b
    from skxfem.levelset import plane
    from skxfem.scene import Box, Scene
    monkeypatch.setattr(b, "box_counts", lambda *a: pytest.fail("ψ was evaluated"))
    dim = len(n)
    s = Scene(Box(n, cell), plane((0.5,) * dim, (0,) * (dim - 1) + (1,)))
    for linear in ("auto", "direct", "iterative"):
        with pytest.raises(b.TooLargeError, match=r"needs at least .* the limit is 4 GB"):
            b.check(s, linear=linear)


@pytest.mark.parametrize("n, cell, nodes", [
    (9223372036854775807, "quad", "8.50e+37 nodes"),          # np.prod wrapped to 1
    (3037000500, "quad", "9.22e+18 nodes"),                   # a negative product: complex
    ((4294967297, 4294967295), "quad", "1.84e+19 nodes"),     # wrapped to -1 cells
    ((2**32,) * 3, "hex", "7.92e+28 nodes"),
    (10**200, "tri", "1.00e+400 nodes"),
])
def test_13_absurd_sizes_are_counted_exactly_and_refused_alike(n, cell, nodes, monkeypatch):
    """Counts in exact integers: refused as any box above the limit, nothing built."""
    import skxfem.studies.budget as b
    monkeypatch.setattr(b, "box_counts", lambda *a: pytest.fail("ψ was evaluated"))
    monkeypatch.setattr(meshes, "box", lambda *a, **k: pytest.fail("the box was built"))
    dim = Box(1, cell).dim
    s = Scene(Box(n, cell), plane((0.5,) * dim, (0,) * (dim - 1) + (1,)))
    for linear in ("auto", "direct", "iterative"):
        with pytest.raises(TooLargeError, match=rf"the scene 'scene' needs at least \S+ TB "
                                                rf"\({re.escape(nodes)}, .* cells, .* the "
                                                rf"limit is 4 GB: use a coarser mesh"):
            check(s, linear=linear)


def test_14_a_size_below_one_byte_is_refused_in_the_users_terms():
    """--max-memory 0.5 said "max_bytes must be a positive integer, got 0"."""
    for text in ("0.5", "0.9", "0.0001K"):
        with pytest.raises(ValueError, match=rf"at least one byte, got '{text}' \(a number "
                                             r"without a unit is in bytes"):
            parse_bytes(text)
    assert parse_bytes("1") == 1 and parse_bytes("0.5K") == 512


@pytest.mark.parametrize("enrichment", ["geometric", "topological"])
@pytest.mark.parametrize("law", ["free", "frictionless"])
def test_a_crack_counts_its_branch_unknowns(enrichment, law):
    """A crack's branch functions (4 × dim unknowns per node near the front) are in the
    bound; ``free`` has no multipliers (before: no branch unknown counted, 2 × 61
    multipliers for ``free``)."""
    from skxfem.fem.material import Material
    from skxfem.scene import Interface, SurfaceLoad

    crack = Interface(plane((0, 0.5), (0, 1)), law=law, front=plane((0.5, 0), (1, 0)),
                      enrichment=enrichment)
    s = Scene(Box((20, 21), "tri"), interfaces=(crack,), material=Material(1.0, 0.3),
              displacements=(clamped("ymin"),),
              loads=(SurfaceLoad("ymax", traction=(0.0, 1.0 if law == "free" else -1.0)),))
    from_box = estimate(s)
    from_mesh = estimate(dataclasses.replace(s, mesh=resolve_mesh(s)))
    r = solve(s)
    for e in (from_box, from_mesh):
        assert r.n_dofs <= e.n_dofs <= 2 * r.n_dofs
        assert r.n_multipliers + r.removed <= e.n_multipliers
        assert (e.n_multipliers == 0) == (law == "free")


@pytest.mark.parametrize("n", [41, 81])
def test_a_short_2d_cracks_zone_is_counted_on_its_depth(n):
    """A centre crack of half-length 0.05 in the unit square: its space enriches three
    depths around the tips, not a fifth of the diameter (skxfem.crack.radius.DEPTH_CAP);
    the count follows, still a bound (the nodes' depth is a cell short of the pieces'):
    measured 5544 / 4568 and 19 960 / 18 056 unknowns (0.2 D: 8 272, 30 424)."""
    from skxfem.levelset import LevelSet
    from skxfem.scene import Displacement, Interface, SurfaceLoad

    crack = Interface(plane((0, 0.5 + 0.3 / n), (0, 1)), law="free",
                      front=LevelSet(lambda x: np.abs(x[0] - 0.5) - 0.05, 2))
    s = Scene(Box(n, "tri"), interfaces=(crack,), loads=(SurfaceLoad("ymax", traction=(
        0.0, 1.0)),), displacements=(Displacement("ymin", {"y": 0.0}),
                                     Displacement("xmin", {"x": 0.0}, where="y < 0.01")))
    r = solve(s)
    assert r.n_dofs <= estimate(s).n_dofs <= 1.25 * r.n_dofs


def test_a_3d_crack_counts_its_tube_and_auto_resolves_as_the_solve():
    """The edge crack of benchmarks/crack_solve.py at n = 8 (11 718 unknowns, the branch
    functions within r_e = 4 front cells' cross-sections; 9 990 when r_e took the nodes'
    distance to the front): its unknowns counted within 10 % (before: 12 636,
    the zone on a cell's diameter); its zone holds most nodes, so ``auto`` tries CG and
    solves directly if it stalls (skxfem.solver.solve_problem): the estimate prices the
    direct solve and bounds both.  With contact on its faces ``auto`` is the direct
    solve, as :func:`skxfem.solve` takes it."""
    from skxfem.fem.material import Material
    from skxfem.linalg.choice import AUTO_ZONE
    from skxfem.scene import Displacement, Interface, SurfaceLoad

    def scene(law):
        crack = Interface(plane((0.5, 0.5, 0.5), (0, 0, 1)), law=law,
                          front=plane((0.5, 0, 0), (1, 0, 0)))
        return Scene(Box((8, 8, 9), "tet"), interfaces=(crack,), material=Material(1.0, 0.3),
                     displacements=(Displacement("zmin", {"x": 0.0, "y": 0.0, "z": 0.0}),),
                     loads=(SurfaceLoad("zmax", traction=(0.0, 0.0, 1.0)),))

    e = estimate(scene("free"), "auto")
    r = solve(scene("free"), linear="auto")
    assert r.n_dofs == 11718 <= e.n_dofs <= 1.1 * r.n_dofs and e.n_multipliers == 0
    branch = r.problem.interfaces[0].V.space.branch.size
    assert branch > AUTO_ZONE * r.mesh.nvertices and e.linear == "direct"
    iterative = estimate(scene("free"), "iterative")
    assert iterative.bytes < e.bytes == max(e.bytes, estimate(scene("free"), "direct").bytes)
    assert estimate(scene("frictionless"), "auto").linear == "direct"


def test_a_2d_crack_is_estimated_for_the_direct_solve_that_auto_takes():
    """auto solves a 2D crack directly at any size (skxfem.linalg.choice): the estimate
    prices that LU, not the iterative solve of a plain interface that size."""
    from skxfem.scene import Interface

    def scene(front):
        return Scene(Box((400, 401), "tri"), displacements=(clamped("ymin"),),
                     interfaces=(Interface(plane((0, 0.5), (0, 1)), law="free" if front
                                           else "bonded", front=front),))

    crack, tie = estimate(scene(plane((0.5, 0), (1, 0))), "auto"), estimate(scene(None), "auto")
    assert crack.n_dofs > 10**5 and (crack.linear, tie.linear) == ("direct", "iterative")


CRACK_PEAK = r"""
import json, sys
import numpy as np
from skxfem import scenes
from skxfem.fem.material import Material
from skxfem.levelset import plane
from skxfem.scene import Box, Interface, Scene, SurfaceLoad, clamped
from skxfem.solver import solve
from skxfem.studies import budget
from skxfem.studies.cracks import inclined_scene

def status(key):                             # kB in /proc/self/status
    with open("/proc/self/status") as f:
        return 1024 * int(next(l for l in f if l.startswith(key)).split()[1])

kind, cell, n, law = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
if kind == "inclined":                       # two tips, Coulomb or frictionless faces
    scene = inclined_scene(n, 30.0, 0.3 if law == "coulomb" else 0.0, cell=cell)[1]
else:                                        # an edge crack to the middle, mid-cell
    dim = 2 if cell in ("tri", "quad") else 3
    e = np.eye(dim)
    crack = Interface(plane((0.5,) * (dim - 1) + ((n // 2 + 0.5) / n,), e[-1]), law=law,
                      front=plane((0.5,) * dim, e[0]))
    top, bottom = ("ymax", "ymin") if dim == 2 else ("zmax", "zmin")
    load = SurfaceLoad(top, traction=tuple(e[-1])) if law == "free" else \
        SurfaceLoad(top, pressure=1.0)
    scene = Scene(Box((n,) * dim, cell), interfaces=(crack,), material=Material(1.0, 0.3),
                  displacements=(clamped(bottom),), loads=(load,))
solve(scenes.strip(2, cell="quad"))          # imports and caches before measuring
before = status("VmRSS:")
with open("/proc/self/clear_refs", "w") as f:
    f.write("5")                             # reset the peak (VmHWM) to the current RSS
solve(scene)
print(json.dumps({"measured": status("VmHWM:") - before,
                  "estimate": budget.estimate(scene).bytes}))
"""


@pytest.mark.parametrize("case", ["edge:tet:6:frictionless", "edge:tet:6:free",
                                  "edge:tri:41:free", "inclined:tri:21:coulomb",
                                  "inclined:quad:21:frictionless"])
def test_a_cracks_memory_is_an_upper_bound_within_the_stated_factor(case):
    """As test_08 for cracks (auto, as ``skxfem run``), 2D and 3D, free and contact
    faces.  Before, the 3D free crack was below its peak (0.44 times: priced for the
    iterative solve that auto, its zone most of the cube, gives up for the direct one)
    and the contact cracks 3-6 times above (the whole plane's edges as multipliers)."""
    done = subprocess.run([sys.executable, "-c", CRACK_PEAK, *case.split(":")],
                          capture_output=True, text=True, timeout=300, check=True)
    r = json.loads(done.stdout)
    assert r["measured"] > 15 * 2**20, "large enough to be measured"
    assert r["measured"] <= r["estimate"] <= FACTOR * r["measured"], r


CUBE = """name = "cube"
[mesh]
box = {{n = {n}, cell = "tet"}}
[levelset]
expr = "z - 0.5"
front = "x - 0.5"
[interface]
law = "frictionless"
[material]
E = 1.0
nu = 0.3
[[displacement]]
boundary = "zmin"
kind = "clamped"
[[load]]
boundary = "zmax"
{load}
"""


@pytest.mark.parametrize("n, peak", [(10, 1.54), (11, 1.90)])
@pytest.mark.parametrize("load", ["pressure = 1.0", "traction = [0.0, 0.0, 1.0]"])
def test_a_contact_crack_scene_passes_the_clis_default_limit(n, peak, load, tmp_path):
    """The edge crack on the 10³ (through nodes) and 11³ (mid-cell) cubes of
    tetrahedra, frictionless faces, the top pressed or pulled: the check ``skxfem run``
    makes (budget.check at the default 4 GB) refused them at 11.2 and 12.7 GB; their
    peaks, pressed, measured with ``scripts/calibrate_budget.py`` (its notes), are 1.54
    and 1.90 GB (crack:tet:10:edge:node:frictionless, crack:tet:11:edge:mid:frictionless;
    1.35 and 0.43 GB when the 3D r_e took the nodes' distance to the front, 2.8 cells
    wide through the cells' middle: crack.space3d.cross_section), estimated 2.41 and
    3.36 GB."""
    from skxfem.app.cli import load_scene

    path = tmp_path / "cube.toml"
    path.write_text(CUBE.format(n=n, load=load))
    e = check(load_scene(path), budget.DEFAULT_MAX_BYTES, "--max-memory")
    assert e.linear == "direct" and e.n_multipliers > 0
    assert peak * 2**30 <= e.bytes <= 3 * peak * 2**30
