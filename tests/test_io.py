"""Writing results: result.json parses, the VTU files read back with the right shapes;
for a contact result, every load step in the JSON and the last one in the VTU files."""
import errno
import json
import multiprocessing
import os
import re
import shutil
import signal
import threading
import time
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import meshio
import numpy as np
import pytest

from skxfem import contact
from skxfem.app import io
from skxfem.app.io import check_output, region_pieces, vtk_cells, write_result
from skxfem.enrich import split_fields
from skxfem.fem import files
from skxfem.fem.material import Material
from skxfem.fem.meshes import box
from skxfem.fem.vtu import node_regions
from skxfem.levelset import nodal_values, plane
from skxfem.scene import Box, Displacement, Scene, SurfaceLoad, clamped
from skxfem.scene.benchmarks import strip

MESHIO_TYPE = {"tri": "triangle", "quad": "quad", "tet": "tetra", "hex": "hexahedron",
               "prism": "wedge"}


def side_pieces(mesh, psi_nodes, u_minus, u_plus):
    """The pieces of displacement.vtu before the one format (issue 28), as a reference:
    cells of Ω⁻ and cut cells, then cells of Ω⁺ and cut cells (a cell is cut where ψ at
    its vertices takes both signs, else on the side of the sign of their mean), each on
    its own copy of its nodes with its side's field; the old cell data ``side`` (-1,
    +1), ``cut``, and point data ``levelset`` (ψ at the nodes).

    Returns (points, cells, side, cut, displacement, levelset, nodes, piece): the last
    two the mesh vertex and the piece (-1, +1) of each point.
    """
    _, t = vtk_cells(mesh)
    psi = psi_nodes[mesh.t]
    cut = (psi.min(axis=0) < 0) & (psi.max(axis=0) > 0)
    sides = np.where(cut, 0, np.sign(psi.mean(axis=0))).astype(np.int64)
    out = [[] for _ in range(8)]
    offset = 0
    for s, u in ((-1, u_minus), (1, u_plus)):
        keep = sides != -s
        nodes, local = np.unique(t[keep], return_inverse=True)
        for row, value in zip(out, (mesh.p[:, nodes].T, local.reshape(-1, t.shape[1]) + offset,
                                    np.full(int(keep.sum()), s), (sides[keep] == 0) * 1,
                                    np.asarray(u)[:, nodes].T, psi_nodes[nodes], nodes,
                                    np.full(nodes.size, s))):
            row.append(value)
        offset += nodes.size
    return tuple(np.concatenate(row) for row in out)


def fake_result(cell, n_points=4):
    """A stand-in for skxfem.result.Result: a box cut by the plane {last coord = 0.5}
    (no node on it), with random fields u⁻ and u⁺ of its regions Ω⁻ and Ω⁺."""
    dim = 2 if cell in ("tri", "quad") else 3
    mesh = box((2, 3) if dim == 2 else (2, 2, 3), cell)
    levelset = plane((0.0,) * (dim - 1) + (0.5,), (0.0,) * (dim - 1) + (1.0,))
    scene = Scene(mesh, levelset, name=f"fake_{cell}")
    rng = np.random.default_rng(1)
    points = np.vstack([rng.random((dim - 1, n_points)), np.full(n_points, 0.5)])
    normals = np.zeros((dim, n_points))
    normals[-1] = 1.0
    facets = (np.array([[0, 1], [1, 2], [2, 3]]).T if dim == 2
              else np.array([[0, 1, 2], [1, 3, 2]]).T)
    cut = SimpleNamespace(psi=nodal_values(levelset, mesh))
    return SimpleNamespace(
        scene=scene, mesh=mesh, points=points, normals=normals,
        regions=np.array([[-1], [1]]), u_regions=rng.random((2, dim, mesh.nvertices)),
        interface=np.zeros(n_points, dtype=np.int64),
        problem=SimpleNamespace(interfaces=(SimpleNamespace(
            cut=cut, gamma=SimpleNamespace(nodal=lambda c: c.psi, splits=True)),)),
        traction=-normals * np.linspace(1, 2, n_points), pressure=np.linspace(1, 2, n_points),
        jump=0.01 * rng.random((dim, n_points)), facets=facets, max_jump=1e-12, n_dofs=123,
        n_multipliers=n_points,
        timings={"cut": 0.1, "enrich": 0.2, "assemble": 0.3, "solve": 0.4},
        linear="direct", linear_info={"residual": 1e-15, "balance": 1e-14,
                                      "iterations": None, "residuals": None},
        is_contact=False)


def test_01_result_json_has_the_promised_keys(tmp_path, cell):
    r = fake_result(cell)
    paths = write_result(r, tmp_path / "out")
    assert set(paths) == {"json", "displacement", "interface"}
    data = json.loads(paths["json"].read_text())
    for key in ("scene", "points", "pressure", "max_jump", "n_dofs", "n_multipliers",
                "timings", "traction", "normals", "law", "space", "linear_solve",
                "interfaces", "interface", "regions"):
        assert key in data, key
    assert data["scene"] == f"fake_{cell}" and data["n_dofs"] == 123
    assert (data["law"], data["space"]) == (["bonded"], ["vital"]), "one per interface"
    assert data["regions"] == [[-1], [1]] and data["interface"] == [0] * 4
    assert data["interfaces"] == [{"levelset": r.scene.levelset.name, "law": "bonded",
                                   "space": "vital", "friction": None, "rho_n": None,
                                   "rho_t": None, "n_points": 4}]
    np.testing.assert_allclose(data["points"], r.points.T)       # one list per point
    np.testing.assert_allclose(data["pressure"], r.pressure)
    assert data["timings"] == r.timings


def test_02_vtu_files_read_back(tmp_path, cell):
    r = fake_result(cell)
    paths = write_result(r, tmp_path)
    mesh = r.mesh
    m = meshio.read(paths["displacement"])
    [block] = m.cells
    psi = nodal_values(r.scene.levelset, mesh)[mesh.t]
    n_cut = int(np.sum((psi.min(axis=0) < 0) & (psi.max(axis=0) > 0)))
    assert block.type == MESHIO_TYPE[cell]
    assert block.data.shape == (mesh.nelements + n_cut, mesh.t.shape[0])  # cut cells twice
    assert m.point_data["displacement"].shape == m.points.shape
    assert set(m.cell_data["region"][0]) == {0, 1} and m.cell_data["cut"][0].sum() == 2 * n_cut
    assert {"levelset_0", "displacement"} == set(m.point_data)
    assert {"region", "cut"} == set(m.cell_data), "a stand-in: no strain nor stress"
    i = meshio.read(paths["interface"])
    assert i.cells[0].type == ("line" if mesh.dim() == 2 else "triangle")
    np.testing.assert_array_equal(i.cells[0].data, r.facets.T)
    assert i.point_data["pressure"].shape == (4,)
    np.testing.assert_array_equal(i.point_data["interface"], r.interface)
    assert i.point_data["traction"].shape == i.point_data["normal"].shape == (4, 3)


@pytest.mark.parametrize("mirror", [False, True])
def test_03_vtk_cells_are_positively_oriented(tmp_path, cell, mirror):
    """VTK's node orders differ from scikit-fem's, which also allows mirrored cells.

    Checked with the signed volume of a corner simplex of each written cell:
    positive for VTK's triangle (0, 1, 2), quad (0, 1, 3), tetra (0, 1, 2, 3),
    hexahedron (0, 1, 3, 4); a wedge's face (0, 1, 2) has its right-hand normal
    pointing away from (3, 4, 5), i.e. the simplex (0, 2, 1, 3) is positive.
    """
    r = fake_result(cell)
    if mirror:                      # x -> -x: every cell is mirrored, still a valid mesh
        r.mesh = type(r.mesh)(r.mesh.p * np.array([[-1.0]] + [[1.0]] * (r.mesh.dim() - 1)),
                              r.mesh.t)
    m = meshio.read(write_result(r, tmp_path)["displacement"])
    dim = r.mesh.dim()
    corners = {"triangle": [0, 1, 2], "quad": [0, 1, 3], "tetra": [0, 1, 2, 3],
               "hexahedron": [0, 1, 3, 4], "wedge": [0, 2, 1, 3]}[m.cells[0].type]
    p = m.points[:, :dim][m.cells[0].data[:, corners]]      # (ncells, dim + 1, dim)
    volumes = np.linalg.det(p[:, 1:] - p[:, :1])
    assert np.all(volumes > 0), volumes
    written = m.points[m.cells[0].data]                  # (ncells, nverts, 3) coordinates
    copies = {tuple(np.round(c, 9).ravel()) for c in written}
    for c in r.mesh.p[:, vtk_cells(r.mesh)[1]].transpose(1, 2, 0):   # every cell is written
        padded = np.hstack([c, np.zeros((c.shape[0], 3 - dim))])
        assert tuple(np.round(padded, 9).ravel()) in copies


def test_04_regions_follow_the_sign_convention():
    """Ω⁻ = {ψ < 0}: with one interface, region 0 (signs [-1]) is Ω⁻, region 1 Ω⁺; with
    two, a node's region is the row of ``regions`` its signs match."""
    mesh = box((1, 4), "quad")                              # rows at y in [0, .25, ...]
    psi = mesh.p[1] - 0.6                                   # Γ in the third row
    assert node_regions(np.array([[-1], [1]]), psi[None]).tolist() == \
        (psi > 0).astype(int).tolist()
    two = np.array([psi, mesh.p[1] - 0.3])                  # rows: two at each y
    regions = np.array([[-1, -1], [-1, 1], [1, 1]])
    assert node_regions(regions, two)[np.argsort(mesh.p[1], kind="stable")].tolist() == \
        [0, 0, 0, 0, 1, 1, 2, 2, 2, 2]
    with pytest.raises(ValueError, match="4 nodes have signs of no region"):
        node_regions(regions[:2], two)


def test_05_nan_is_never_written_and_stages_are_required(tmp_path):
    """NaN and inf were written as null (issue 26: friction = 5e-324 wrote null into
    steps[0].Lambda with exit 0): a result holding them is refused, nothing written."""
    from skxfem.app.io import NotFiniteError

    r = fake_result("quad")
    r.pressure = np.array([1.0, np.nan, 2.0, np.inf])
    with pytest.raises(NotFiniteError, match=r"the result's pressure holds NaN or inf \(2 of "
                                             r"4 values\); nothing was written"):
        write_result(r, tmp_path / "out")
    assert not (tmp_path / "out").exists()
    r = fake_result("quad")
    r.u_regions[1, 0, 3] = np.nan
    with pytest.raises(NotFiniteError, match=r"u_regions \(the fields of displacement.vtu\) "
                                             r"holds NaN"):
        write_result(r, tmp_path / "out")
    r.timings = {"cut": 0.1}
    with pytest.raises(ValueError, match="enrich"):
        write_result(r, tmp_path)


# --- one displacement field per region, to warp by --------------------------------

@pytest.mark.parametrize("cell", ["tri", "hex", "prism"])
def test_06_each_region_is_a_piece_with_its_own_displacement(tmp_path, cell):
    """Warp by vector: each copy moves with its region's field, so Γ opens as it should."""
    r = fake_result(cell)
    m = meshio.read(write_result(r, tmp_path)["displacement"])
    dim = r.mesh.dim()
    psi = nodal_values(r.scene.levelset, r.mesh)
    np.testing.assert_allclose(m.point_data["levelset_0"], [
        psi[np.flatnonzero(np.all(np.isclose(r.mesh.p.T, q[:dim]), axis=1))[0]]
        for q in m.points])
    region, cut = m.cell_data["region"][0], m.cell_data["cut"][0]
    for k, (s, u) in enumerate(zip((-1, 1), r.u_regions)):   # Ω⁻ then Ω⁺
        nodes = np.unique(m.cells[0].data[region == k])
        for i in nodes:                            # the point is a node of the mesh ...
            [j] = np.flatnonzero(np.all(np.isclose(r.mesh.p.T, m.points[i, :dim]), axis=1))
            np.testing.assert_allclose(m.point_data["displacement"][i, :dim], u[:, j])
        assert np.sum(s * m.point_data["levelset_0"][nodes] > 0) == np.sum(s * psi > 0)
    assert np.all(cut[region == 0].sum() == cut[region == 1].sum())
    pieces = [set(np.unique(m.cells[0].data[region == k])) for k in (0, 1)]
    assert not pieces[0] & pieces[1], "the regions share no point: each warps on its own"


def test_07_region_pieces_puts_cut_cells_in_both_regions():
    mesh = box((1, 4), "quad")                                  # Γ in the third row
    fields = np.array([np.zeros((2, 10)), np.ones((2, 10))])
    node_region = node_regions(np.array([[-1], [1]]), (mesh.p[1] - 0.6)[None])
    p, c, region, cut, d, nodes = region_pieces(mesh, node_region, fields)
    assert region.tolist().count(0) == 3 and region.tolist().count(1) == 2
    assert cut.sum() == 2 and p.shape == (8 + 6, 2) and c.max() == 13
    assert np.all(d[:8] == 0) and np.all(d[8:] == 1)
    np.testing.assert_array_equal(p, mesh.p[:, nodes].T)


# --- bad output folders and failed writes ------------------------------------------

def snapshot(folder):
    return {f.name: f.read_bytes() for f in sorted(folder.iterdir())}


def test_08_an_existing_file_is_refused_before_anything_is_written(tmp_path):
    (tmp_path / "taken").write_text("mine")
    for out in (tmp_path / "taken", tmp_path / "taken" / "sub"):
        with pytest.raises(ValueError, match="taken"):
            check_output(out)
        with pytest.raises(ValueError, match="taken"):
            write_result(fake_result("tri"), out)
    assert snapshot(tmp_path) == {"taken": b"mine"}


def test_09_a_folder_that_is_not_writable_is_refused(tmp_path, monkeypatch):
    """The machines run as root, which writes into read-only folders: os.access is
    made to answer "not writable", as it does for an ordinary user."""
    (tmp_path / "ro").mkdir()
    monkeypatch.setattr(os, "access", lambda path, mode: False)
    with pytest.raises(ValueError, match="not writable"):
        check_output(tmp_path / "ro" / "new" / "out")
    with pytest.raises(ValueError, match="not writable"):
        write_result(fake_result("quad"), tmp_path / "ro")
    assert list((tmp_path / "ro").iterdir()) == []


def fail_after(monkeypatch, key, nbytes, error):
    """Make the writer of ``key`` write ``nbytes`` then raise ``error`` (a full disk)."""
    def broken(result, path):
        path.write_bytes(b"x" * nbytes)
        raise error
    monkeypatch.setitem(io._WRITERS, key, broken)


@pytest.mark.parametrize("nbytes", [0, 100])
def test_10_a_failed_second_write_leaves_the_previous_result(tmp_path, monkeypatch, nbytes):
    """Simulated full disk in the middle of the VTU: the old result stays whole."""
    old = fake_result("tri")
    write_result(old, tmp_path / "out")
    before = snapshot(tmp_path / "out")
    new = fake_result("tri")
    new.pressure = new.pressure + 1.0
    fail_after(monkeypatch, "displacement", nbytes, OSError(errno.ENOSPC, "No space left"))
    with pytest.raises(OSError, match="No space left"):
        write_result(new, tmp_path / "out")
    assert snapshot(tmp_path / "out") == before            # no temporary file left either


def test_11_a_failed_write_into_a_new_folder_leaves_nothing(tmp_path, monkeypatch):
    fail_after(monkeypatch, "displacement", 10, OSError(errno.ENOSPC, "No space left"))
    with pytest.raises(OSError):
        write_result(fake_result("hex"), tmp_path / "a" / "b")
    assert list(tmp_path.iterdir()) == []
    monkeypatch.undo()
    fail_after(monkeypatch, "interface", 10, RuntimeError("a bug in a writer"))
    with pytest.raises(RuntimeError):
        write_result(fake_result("hex"), tmp_path)
    assert list(tmp_path.iterdir()) == []


def tagged(tag: float):
    """A fake result whose every file depends on ``tag``: files of two runs differ."""
    r = fake_result("tri")
    r.pressure, r.u_regions = r.pressure + tag, r.u_regions + tag
    return r


def references(tmp_path, tags):
    """The bytes of the three files of each tagged run, written alone."""
    return {tag: snapshot(write_result(tagged(tag), tmp_path / f"ref{tag}")["json"].parent)
            for tag in tags}


def hidden(folder):
    """What writers left beside their target (temporary folders)."""
    return sorted(p.name for p in folder.iterdir() if ".skxfem-" in p.name)


KILL_POINTS = ["json", "displacement", "interface", "rename aside", "rename new", "remove old"]


def killed_writer(out, point):
    """In a forked process: write run 2 into ``out`` and SIGKILL itself at ``point``
    (after writing that file, before that rename, or while removing the previous set)."""
    def kill():
        os.kill(os.getpid(), signal.SIGKILL)

    for key in ("json", "displacement", "interface"):
        def write(result, path, key=key, writer=io._WRITERS[key]):
            writer(result, path)
            if point == key:
                kill()
        io._WRITERS[key] = write
    calls, rename, replace_, rmtree = [], os.rename, os.replace, shutil.rmtree

    def renaming(move):
        def renamed(a, b):
            calls.append(b)
            if point == ("rename aside", "rename new")[min(len(calls), 2) - 1]:
                kill()
            move(a, b)
        return renamed

    def removed(path, *args, **kwargs):
        if point == "remove old" and ".skxfem-old-" in str(path):
            kill()
        rmtree(path, *args, **kwargs)

    os.rename, os.replace, shutil.rmtree = renaming(rename), renaming(replace_), removed
    write_result(tagged(2.0), out)


@pytest.mark.parametrize("point", KILL_POINTS)
def test_12_a_writer_killed_at_any_point_never_leaves_two_runs(tmp_path, monkeypatch, point):
    """Kill -9 between any two steps of a write: the folder holds the previous set, the
    new one (once committed), or nothing (between the two renames); the next write puts
    the previous set back if needed and removes what the killed writer left."""
    ref = references(tmp_path / "ref", (1.0, 2.0, 3.0))
    out = tmp_path / "out"
    write_result(tagged(1.0), out)
    child = multiprocessing.get_context("fork").Process(target=killed_writer,
                                                        args=(out, point))
    child.start()
    child.join(60)
    assert child.exitcode == -signal.SIGKILL
    committed = point == "remove old"
    if point == "rename new":
        assert not out.exists(), "between the renames: nothing rather than a mix"
    else:
        assert snapshot(out) == ref[2.0 if committed else 1.0]
    assert hidden(tmp_path), "the killed writer left its temporary folder"
    fail_after(monkeypatch, "interface", 10, OSError(errno.ENOSPC, "No space left"))
    with pytest.raises(OSError, match="No space left"):          # a failed write ...
        write_result(tagged(3.0), out)
    assert snapshot(out) == ref[2.0 if committed else 1.0]       # ... restores the set
    monkeypatch.undo()
    write_result(tagged(3.0), out)
    assert snapshot(out) == ref[3.0] and hidden(tmp_path) == []


def test_12b_a_rename_failing_between_the_two_keeps_the_previous_result(tmp_path,
                                                                         monkeypatch):
    write_result(tagged(1.0), tmp_path / "out")
    before = snapshot(tmp_path / "out")
    rename = os.rename

    def second_fails(a, b):
        if ".skxfem-new-" in str(a):
            raise OSError(errno.EIO, "I/O error")
        rename(a, b)

    monkeypatch.setattr(files.os, "rename", second_fails)
    with pytest.raises(OSError, match="I/O error"):
        write_result(tagged(2.0), tmp_path / "out")
    assert snapshot(tmp_path / "out") == before and hidden(tmp_path) == []


def test_13_files_get_the_usual_permissions(tmp_path):
    """Written under temporary names, the files are still created with open()'s mode."""
    umask = os.umask(0o022)
    os.umask(umask)
    for path in write_result(fake_result("tri"), tmp_path).values():
        assert path.stat().st_mode & 0o777 == 0o666 & ~umask


# --- contact results: every load step in result.json, the last one in the VTU files ---

def coulomb_strip():
    """Pressed and sheared strip with Coulomb friction (μ = 0.5): open, stick and slip
    points on Γ (the tilted block of tests/test_contact.py), in two load steps."""
    s = strip(n=4)
    return replace(s, law="coulomb", friction=0.5, steps=(0.5, 1.0),
                   loads=(SurfaceLoad("ymax", pressure=1.0),),
                   displacements=(clamped("ymin"), Displacement("ymax", {"x": 2.0})))


def partial_cube():
    """Unit cube, Γ at z = 0.5, top turned: pressed near y = 0, open near y = 1."""
    return Scene(Box((1, 4, 5), "hex"), plane((0, 0, 0.5), (0, 0, 1)), Material(E=1.0),
                 displacements=(clamped("zmin"), Displacement(
                     "zmax", {"x": 0.0, "y": 0.0, "z": lambda x: -0.01 * (1 - 2 * x[1])})),
                 law="frictionless", name="partial_cube")


@pytest.fixture(scope="module")
def contact_results():
    return {2: contact.solve(coulomb_strip()), 3: contact.solve(partial_cube())}


@pytest.mark.parametrize("dim", [2, 3])
def test_14_contact_json_holds_every_step(tmp_path, contact_results, dim):
    r = contact_results[dim]
    data = json.loads(write_result(r, tmp_path)["json"].read_text())
    m, k = r.ops.w.size, dim - 1
    assert data["scene"] == r.problem.scene.name and data["law"] == [r.problem.scene.law]
    [law] = r.law                                                   # one per interface
    [entry] = data["interfaces"]
    assert (entry["friction"], entry["rho_n"], entry["rho_t"]) == (law.mu, law.rho_n,
                                                                   law.rho_t)
    assert not {"friction", "rho_n", "rho_t"} & set(data), "μ and ρ only in interfaces"
    assert data["dofs"]["interface"] == [0] * m
    assert data["status_codes"] == {"open": 0, "stick": 1, "slip": 2}
    assert data["n_multipliers"] == m and data["n_dofs"] == r.problem.V.N
    np.testing.assert_allclose(data["points"], r.points.T)          # the cut edges' points
    np.testing.assert_allclose(data["dofs"]["points"], r.ops.points.T)  # one row per dof
    dofs = data["dofs"]
    normals, tangents = np.array(dofs["normals"]), np.array(dofs["tangents"])
    assert normals.shape == (m, dim) and tangents.shape == (m, k, dim)
    frame = np.concatenate([tangents, normals[:, None]], axis=1)     # (m, dim, dim)
    np.testing.assert_allclose(frame @ frame.transpose(0, 2, 1), np.broadcast_to(
        np.eye(dim), (m, dim, dim)), atol=1e-12, err_msg="(t, n) is orthonormal")
    assert sum(dofs["weights"]) == pytest.approx(1.0, rel=1e-12), "|Γ| = 1"
    assert data["n_steps"] == len(data["steps"]) == len(r.steps)
    assert {"open", "slip"} <= set(data["steps"][-1]["status"]), "a partial contact"
    assert data["newton_iterations"] == sum(st.newton.iterations for st in r.steps)
    for got, st in zip(data["steps"], r.steps, strict=True):
        assert got["load"] == st.load and got["law"] == list(st.law) == [law.name]
        for key, value in (("pressure", st.pressure), ("gap", st.gap), ("slip", st.slip),
                           ("tangential_traction", st.traction), ("Lambda", st.Lambda)):
            assert np.shape(got[key]) == np.shape(value) and np.shape(value)[0] == m, key
            np.testing.assert_array_equal(got[key], value, err_msg=key)
        assert got["status"] == [["open", "stick", "slip"][s] for s in st.status]
        assert got["counts"] == {name: got["status"].count(name)
                                 for name in ("open", "stick", "slip")}
        newton = got["newton"]
        assert newton["iterations"] == st.newton.iterations >= 0  # 0: predicted exactly
        assert list(newton["residuals"]) == ["equilibrium", "contact", "friction"]
        for i, name in enumerate(newton["residuals"]):
            residuals = newton["residuals"][name]
            assert len(residuals) == st.newton.iterations + 1, "the start, then each iteration"
            np.testing.assert_array_equal(residuals, st.newton.residuals[:, i])
            assert residuals[-1] <= 1e-10, "converged"


def test_15_contact_json_statuses_of_the_friction_case(tmp_path, contact_results):
    """The Coulomb strip: all three statuses; |r_τ| = μp where it slips, < μp where it
    sticks; proportional loading: the second step is twice the first."""
    data = json.loads(write_result(contact_results[2], tmp_path)["json"].read_text())
    first, last = data["steps"]
    assert set(last["status"]) == {"open", "stick", "slip"}
    p, r = np.array(last["pressure"]), np.abs(np.array(last["tangential_traction"])[:, 0])
    status = np.array(last["status"])
    np.testing.assert_allclose(r[status == "slip"], 0.5 * p[status == "slip"], rtol=1e-10)
    assert np.all(r[status == "stick"] < 0.5 * p[status == "stick"])
    assert np.all(p[status == "open"] == 0)
    np.testing.assert_allclose(last["pressure"], 2 * np.array(first["pressure"]), atol=1e-12)
    assert np.dot(data["dofs"]["weights"], p) == pytest.approx(1.0, rel=1e-10), "∫_Γ p = load"
    assert data["status"] == last["status"], "the naive space: the points are the dofs"


@pytest.mark.parametrize("dim", [2, 3])
def test_16_contact_vtu_files_read_back(tmp_path, contact_results, dim):
    r = contact_results[dim]
    st, m = r.steps[-1], r.ops.w.size
    paths = write_result(r, tmp_path)
    i = meshio.read(paths["interface"])      # the facets on the cut edges' points, as a tie's
    assert i.cells[0].type == {2: "line", 3: "triangle"}[dim]
    np.testing.assert_array_equal(i.cells[0].data.T, r.facets)
    np.testing.assert_allclose(i.points[:, :dim], r.points.T)
    assert m == len(r.pressure), "the naive space: one dof per point"
    assert i.point_data["status"].dtype.kind == "i"
    np.testing.assert_array_equal(i.point_data["status"], st.status)
    np.testing.assert_allclose(i.point_data["pressure"], st.pressure)
    np.testing.assert_allclose(i.point_data["gap"], r.gap)
    n = i.point_data["normal"]
    traction, tangential = i.point_data["traction"], i.point_data["tangential_traction"]
    assert traction.shape == tangential.shape == i.point_data["jump"].shape == (m, 3)
    np.testing.assert_allclose((traction * n).sum(1), -st.pressure, atol=1e-12)
    np.testing.assert_allclose(traction - tangential, -st.pressure[:, None] * n, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(tangential, axis=1),
                               np.linalg.norm(st.traction, axis=1), atol=1e-12)
    np.testing.assert_allclose(i.point_data["jump"][:, :dim], r.jump.T)  # at the points
    np.testing.assert_array_equal(i.point_data["interface"], 0)
    d = meshio.read(paths["displacement"])                # the last step, region by region
    mesh = r.problem.mesh
    pieces = side_pieces(mesh, nodal_values(r.problem.scene.levelset, mesh),
                         *split_fields(r.problem.V, st.U))           # the former pieces
    np.testing.assert_allclose(d.points[:, :dim], pieces[0])
    np.testing.assert_allclose(d.point_data["displacement"][:, :dim], pieces[4])
    np.testing.assert_array_equal(d.cell_data["region"][0], (pieces[2] + 1) // 2)


@pytest.mark.parametrize("example", ["strip", "inclusion", "plate"])
def test_16b_one_interface_writes_the_pieces_users_saw(tmp_path, example):
    """The one format (issue 28) changed names, not numbers: with one interface
    displacement.vtu's region pieces are the former side pieces, point for point
    (region 0 = side -1 = Ω⁻, region 1 = side +1 = Ω⁺), with the same displacements,
    cut flags and reactions, and levelset_0 is the former levelset (ψ at the nodes;
    the cut's ψ, equal where no node lies on Γ, as in these scenes)."""
    from skxfem import solve
    from skxfem.scene.file import load_scene

    examples = Path(__file__).resolve().parents[1] / "examples"
    r = solve(load_scene(examples / f"{example}.toml"))
    mesh, dim = r.mesh, r.mesh.dim()
    psi = nodal_values(r.scene.levelset, mesh)
    assert np.all(psi != 0), "no node on Γ: the cut's ψ is the level set's"
    points, cells, side, cut, disp, levelset, nodes, piece = side_pieces(mesh, psi,
                                                                         r.u_minus, r.u_plus)
    d = meshio.read(write_result(r, tmp_path)["displacement"])
    np.testing.assert_array_equal(d.points[:, :dim], points)
    np.testing.assert_array_equal(d.cells[0].data, cells)
    np.testing.assert_array_equal(d.cell_data["region"][0], (side + 1) // 2)
    np.testing.assert_array_equal(d.cell_data["cut"][0], cut)
    np.testing.assert_array_equal(d.point_data["displacement"][:, :dim], disp)
    np.testing.assert_array_equal(d.point_data["levelset_0"], levelset)
    own = np.where(levelset < 0, -1, 1) == piece          # a node's copy on its own side
    reaction = np.where(own[:, None], r.reactions[:, nodes].T, 0.0)
    np.testing.assert_array_equal(d.point_data["reaction"][:, :dim], reaction)
    assert not {"side", "levelset"} & {*d.cell_data, *d.point_data}


def test_17_contact_results_are_written_all_or_nothing(tmp_path, monkeypatch, contact_results):
    r = contact_results[2]
    write_result(r, tmp_path / "out")
    before = snapshot(tmp_path / "out")
    fail_after(monkeypatch, "interface", 100, OSError(errno.ENOSPC, "No space left"))
    with pytest.raises(OSError, match="No space left"):
        write_result(contact_results[3], tmp_path / "out")
    assert snapshot(tmp_path / "out") == before


# --- the three files as one set: concurrent writers, stale files, other files ----------

def slow_writer(out, tags):
    """In a forked process: write each tagged run into ``out``, pausing between every
    step (writes and renames), so that two writers interleave if they can."""
    rename, replace_ = os.rename, os.replace

    def slowly(move):
        def moved(a, b):
            time.sleep(0.01)
            move(a, b)
        return moved

    os.rename, os.replace = slowly(rename), slowly(replace_)
    for tag in tags:
        write_result(tagged(tag), out)


def read_set(folder):
    """The three files as a reader sees them: through one open handle of the folder
    (so a reader is not itself fooled by a swap); None if one is not there."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except FileNotFoundError:
        return None
    try:
        def opener(path, flags):
            return os.open(path, flags, dir_fd=fd)
        data = {}
        for name in ("displacement.vtu", "interface.vtu", "result.json"):
            with open(name, "rb", opener=opener) as f:
                data[name] = f.read()
        return data
    except FileNotFoundError:        # not written yet, or the folder was removed
        return None
    finally:
        os.close(fd)


def test_18_two_concurrent_writers_never_mix_their_files(tmp_path):
    """Two processes write five results each into one folder: both succeed, and a
    reader that looks all the while sees whole sets, each from one run."""
    a, b = (1.0, 2.0, 3.0, 4.0, 5.0), (11.0, 12.0, 13.0, 14.0, 15.0)
    ref = list(references(tmp_path / "ref", a + b).values())
    out = tmp_path / "out"
    context = multiprocessing.get_context("fork")
    writers = [context.Process(target=slow_writer, args=(out, tags)) for tags in (a, b)]
    for w in writers:
        w.start()
    seen = 0
    while any(w.is_alive() for w in writers):
        now = read_set(out)
        if now is not None:
            assert now in ref, f"a mix of two runs: {sorted(now)}"
            seen += 1
    for w in writers:
        w.join()
    assert [w.exitcode for w in writers] == [0, 0]
    assert snapshot(out) in (ref[4], ref[9]) and hidden(tmp_path) == []
    assert seen > 0


def test_19_threads_writing_the_same_folder_take_turns(tmp_path):
    ref = list(references(tmp_path / "ref", (1.0, 2.0, 3.0, 4.0)).values())
    errors = []

    def write(tag):
        try:
            write_result(tagged(tag), tmp_path / "out")
        except Exception as e:  # noqa: BLE001  (reported below)
            errors.append(e)

    threads = [threading.Thread(target=write, args=(t,)) for t in (1.0, 2.0, 3.0, 4.0)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == [] and snapshot(tmp_path / "out") in ref and hidden(tmp_path) == []


def test_20_stale_temporary_files_of_killed_runs_are_removed(tmp_path):
    """Temporary files of a killed run: a new-style temporary folder beside the target,
    and the temporary names that versions up to 0.1 left inside it."""
    out = tmp_path / "out"
    write_result(tagged(1.0), out)
    (out / ".result-4242-0123abcd.json").write_text("{")
    (out / ".displacement-4242-89abcdef.vtu").write_text("<VTK")
    (tmp_path / f".out.skxfem-new-{'0' * 16}").mkdir()
    (tmp_path / f".out.skxfem-new-{'0' * 16}" / "result.json").write_text("{")
    (tmp_path / "mine.txt").write_text("kept")                    # not ours: kept
    write_result(tagged(2.0), out)
    assert sorted(p.name for p in out.iterdir()) == ["displacement.vtu", "interface.vtu",
                                                      "result.json"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.txt", "out"]


def test_21_a_folder_holding_other_files_or_the_current_one_is_refused(tmp_path,
                                                                        monkeypatch):
    """The whole folder is replaced: a folder with files of its own is refused (named,
    escaped), and so is the current folder or one above it, before anything is written."""
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes\x1b.txt").write_text("keep me")
    with pytest.raises(ValueError, match=r"holds files that are not results.*notes\\x1b"):
        check_output(tmp_path / "mine")
    with pytest.raises(ValueError, match="holds files"):
        write_result(tagged(1.0), tmp_path / "mine")
    assert (tmp_path / "mine" / "notes\x1b.txt").read_text() == "keep me"
    (tmp_path / "here" / "deeper").mkdir(parents=True)
    monkeypatch.chdir(tmp_path / "here" / "deeper")
    for out in (".", "..", str(tmp_path / "here"), ""):
        with pytest.raises(ValueError, match="current folder|empty"):
            check_output(out)
    assert list((tmp_path / "here" / "deeper").iterdir()) == []


# --- issue 28: one interface is the case N = 1, in the files too ------------------------

SHORT_AND_TABLE = {   # the body of a scene file, with {interface}: its one interface
    "tie 2D": ('[mesh]\nbox = {n = [4, 5], cell = "quad"}\n[material]\nE = 1.0\nnu = 0.3\n'
               '[[displacement]]\nboundary = "ymin"\nkind = "clamped"\n'
               '[[load]]\nboundary = "ymax"\ntraction = [0.5, -1.0]\n{interface}',
               'plane = {point = [0.0, 0.4], normal = [0.2, 1.0]}', 'law = "bonded"', ""),
    "coulomb 2D": ('[mesh]\nbox = {n = [4, 5], cell = "quad"}\n[material]\nE = 1.0\n'
                   'nu = 0.3\n[[displacement]]\nboundary = "ymin"\nkind = "clamped"\n'
                   '[[displacement]]\nboundary = "ymax"\nx = 2.0\n'
                   '[[load]]\nboundary = "ymax"\npressure = 1.0\n{interface}',
                   'plane = {point = [0.0, 0.5], normal = [0.0, 1.0]}',
                   'law = "coulomb"\nfriction = 0.5', "[0.5, 1.0]"),
    "frictionless 3D hex": (
        '[mesh]\nbox = {n = [1, 4, 5], cell = "hex"}\n[material]\nE = 1.0\n'
        '[[displacement]]\nboundary = "zmin"\nkind = "clamped"\n'
        '[[displacement]]\nboundary = "zmax"\nx = 0.0\ny = 0.0\nz = "-0.01 * (1 - 2 * y)"\n'
        '{interface}', 'plane = {point = [0.0, 0.0, 0.5], normal = [0.0, 0.0, 1.0]}',
        'law = "frictionless"', ""),
}


def one_interface_files(body, levelset, law, steps):
    """The scene ``body`` with its interface (at ``{interface}``) written in the short
    form ([levelset] and [interface], the ``steps`` in [interface]) and as one
    [[interface]] table (the steps at the top level, as with several)."""
    steps = f"steps = {steps}\n" if steps else ""
    short = body.replace("{interface}", f"[levelset]\n{levelset}\n[interface]\n{law}\n{steps}")
    table = steps + body.replace("{interface}", f"[[interface]]\n{levelset}\n{law}\n")
    return 'name = "one"\n' + short, 'name = "one"\n' + table


def _without_clock(text: str) -> str:
    """result.json's text with the numbers of ``timings`` (wall clock) blanked."""
    data = json.loads(text)
    assert set(data["timings"]) == {"cut", "enrich", "assemble", "solve"}
    head, rest = text.split('"timings": {', 1)
    block, tail = rest.split("}", 1)
    return head + '"timings": {' + re.sub(r"-?\d[\d.e+-]*", "T", block) + "}" + tail


@pytest.mark.parametrize("case", list(SHORT_AND_TABLE))
def test_22_one_interface_short_form_or_one_table_give_the_same_files(tmp_path, capsys,
                                                                      case):
    """Issue 28: the same scene file with its one interface written as [levelset] +
    [interface] or as one [[interface]] table gives, through `skxfem run`, the same
    result.json byte for byte (the wall-clock timings aside) and the same VTU files
    (points, cells, every point and cell data array exactly), series included."""
    from skxfem.app.cli import main

    out = {}
    for form, text in zip(("short", "table"), one_interface_files(*SHORT_AND_TABLE[case])):
        path = tmp_path / f"{form}.toml"
        path.write_text(text)
        assert main(["run", str(path), "--out", str(tmp_path / form)]) == 0, text
        out[form] = tmp_path / form
    capsys.readouterr()
    short, table = out["short"], out["table"]
    assert sorted(f.name for f in short.iterdir()) == sorted(f.name for f in table.iterdir())
    a, b = ((d / "result.json").read_text() for d in (short, table))
    assert _without_clock(a) == _without_clock(b)
    data = json.loads(a)
    assert len(data["law"]) == len(data["space"]) == len(data["interfaces"]) == 1
    assert data["regions"] == [[-1], [1]]
    assert len(list(short.glob("displacement_*.vtu"))) == data.get("n_steps", 0) == \
        (2 if case == "coulomb 2D" else 1 if "3D" in case else 0), "the series too"
    for f in sorted(short.glob("*.vtu")):
        m, n = meshio.read(f), meshio.read(table / f.name)
        np.testing.assert_array_equal(m.points, n.points, err_msg=f.name)
        assert [c.type for c in m.cells] == [c.type for c in n.cells]
        np.testing.assert_array_equal(m.cells[0].data, n.cells[0].data, err_msg=f.name)
        assert set(m.point_data) == set(n.point_data) and set(m.cell_data) == set(n.cell_data)
        for key in m.point_data:
            np.testing.assert_array_equal(m.point_data[key], n.point_data[key],
                                          err_msg=f"{f.name} {key}")
        for key in m.cell_data:
            np.testing.assert_array_equal(m.cell_data[key][0], n.cell_data[key][0],
                                          err_msg=f"{f.name} {key}")
        if f.name == "displacement.vtu":
            assert {"region", "cut"} <= set(m.cell_data) and "levelset_0" in m.point_data
            assert not {"side", "levelset"} & {*m.cell_data, *m.point_data}
        if f.name.startswith("interface"):
            assert "interface" in m.point_data
    for f in short.glob("*.pvd"):
        assert f.read_text() == (table / f.name).read_text()


CRACK_TOML = """name = "crack"
[mesh]
box = {{n = {n}, cell = "{cell}"}}
[levelset]
expr = "{psi}"
front = "{phi}"
[interface]
law = "free"
enrichment = "topological"
[material]
E = 1.0
nu = 0.3
[[displacement]]
boundary = "{lo}"
kind = "clamped"
[[load]]
boundary = "{hi}"
traction = {t}
[solver]
linear = "direct"
"""


def _crack_file(tmp_path, n, cell, psi, phi):
    dim = len(n)
    lo, hi = ("ymin", "ymax") if dim == 2 else ("zmin", "zmax")
    path = tmp_path / "crack.toml"
    path.write_text(CRACK_TOML.format(n=n, cell=cell, psi=psi, phi=phi, lo=lo, hi=hi,
                                      t=[0.0] * (dim - 1) + [1.0]))
    return path


def _measure(vtu) -> float:
    """The length of the line cells or the area of the triangle cells of a VTU file."""
    P = vtu.points
    if "triangle" in vtu.cells_dict:
        a, b, c = (P[vtu.cells_dict["triangle"][:, k]] for k in range(3))
        return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    a, b = (P[vtu.cells_dict["line"][:, k]] for k in range(2))
    return np.linalg.norm(b - a, axis=1).sum()


def _front_data(vtu, keys):
    """The front points (vertex cells) of interface.vtu: K finite there, NaN elsewhere."""
    tips = vtu.cells_dict["vertex"][:, 0]
    others = np.setdiff1d(np.arange(len(vtu.points)), tips)
    for key in keys:
        assert np.isfinite(vtu.point_data[key][tips]).all(), key
        assert np.isnan(vtu.point_data[key][others]).all(), key
    assert np.isfinite(vtu.point_data["jump"][others]).all(), "jump at every crack point"
    return tips


@pytest.mark.parametrize("n, cell, psi, phi, exact", [
    ([10, 10], "tri", "y - 0.47", "x - 0.53", 0.53),     # tip inside a cell
    ([10, 10], "quad", "y - 0.47", "x - 0.53", 0.53),
    ([10, 10], "tri", "y - 0.5", "x - 0.5", 0.5),        # along mesh edges, tip at a node
    ([7, 7, 3], "tet", "z - 0.5", "x - 0.45", 0.45),     # through-thickness front: a × 1
    ([8, 8, 4], "tet", "z - 0.5", "x - 0.5", 0.5),       # along mesh faces, front on edges
])
def test_interface_vtu_shows_a_crack_up_to_its_front(tmp_path, capsys, n, cell, psi, phi,
                                                      exact):
    """interface.vtu of `skxfem run` holds the whole crack {ψ = 0, φ < 0}, the pieces in
    the front's cells clipped there: its length (2D) or area (3D) is the crack's to
    round-off; the front points carry K_I, K_II (K_III), and the jump is 0 at the front
    (topological enrichment: the front cells' nodes carry only the √r branch functions)."""
    from skxfem.app.cli import main
    from skxfem.scene.expr import Expression

    assert main(["run", str(_crack_file(tmp_path, n, cell, psi, phi)),
                 "--out", str(tmp_path / "out")]) == 0
    capsys.readouterr()
    vtu = meshio.read(tmp_path / "out" / "interface.vtu")
    assert abs(_measure(vtu) - exact) < 1e-12
    keys = ("K_I", "K_II") if len(n) == 2 else ("K_I", "K_II", "K_III")
    tips = _front_data(vtu, keys)
    front = json.loads((tmp_path / "out" / "result.json").read_text())["front"][0]
    assert np.allclose(vtu.point_data["K_I"][tips], front["K_I"], rtol=1e-12)
    jump = vtu.point_data["jump"]
    phi_at = Expression(phi, dim=len(n))(vtu.points[:, :len(n)].T)
    on_front = (np.abs(phi_at) < 1e-12) & ~np.isin(np.arange(len(phi_at)), tips)
    assert on_front.any(), "the pieces reach the front"
    # √r of a round-off r: 1e-9 of the largest jump on quadrilaterals (their inverse map)
    assert np.abs(jump[on_front]).max() < 1e-7 * np.abs(jump[np.isfinite(jump)]).max()


def test_interface_vtu_of_a_penny_is_its_polygon(tmp_path):
    """A penny (a = 0.3, centre (0.5, 0.5, 0.5), h = 1/6): the area written is that of the
    polygon the solve cuts, {φ_h < 0} on ψ = 0 (φ_h the P1 interpolant of the distance to
    the centre), to round-off, by the shoelace formula of the front's closed chain;
    against πa² it is 0.945 (measured: the polygon lies inside the circle, O(h²)).  The
    penny is under two cells across its radius: its K needs a domain of a cell at least,
    and half the radius of curvature leaves less (skxfem.crack.kind3d.front_reach): no
    K, a warning, the rest written."""
    from skxfem.crack.geometry3d import front_chains
    from skxfem.crack.kind3d import FrontPointsWarning
    from skxfem.scene.file import load_scene
    from skxfem.solver import solve

    a = 0.3
    path = _crack_file(tmp_path, [6, 6, 3], "tet", "z - 0.5",
                       f"sqrt((x - 0.5)**2 + (y - 0.5)**2) - {a}")
    with pytest.warns(FrontPointsWarning, match=r"no K at (\d+) of \1 front points"):
        r = solve(load_scene(path))
    assert r.front[0]["K_I"].size == 0 and r.front[0]["points"].shape == (0, 3)
    write_result(r, tmp_path / "out")
    vtu = meshio.read(tmp_path / "out" / "interface.vtu")
    ((chain, closed),) = front_chains(r.problem.interfaces[0].cut)
    x, y = chain[0], chain[1]
    polygon = 0.5 * abs(x @ np.roll(y, -1) - y @ np.roll(x, -1))
    assert closed and abs(_measure(vtu) - polygon) < 1e-12
    assert 0.94 < _measure(vtu) / (np.pi * a ** 2) < 0.95
    assert "vertex" not in vtu.cells_dict and np.isnan(vtu.point_data["K_I"]).all()
