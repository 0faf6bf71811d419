"""Writing results: result.json parses, the VTU files read back with the right shapes."""
import json
from types import SimpleNamespace

import meshio
import numpy as np
import pytest

from skxfem.io import cell_sides, vtk_cells, write_result
from skxfem.levelset import plane
from skxfem.meshes import box
from skxfem.scene import Scene

MESHIO_TYPE = {"tri": "triangle", "quad": "quad", "tet": "tetra", "hex": "hexahedron",
               "prism": "wedge"}


def fake_result(cell, n_points=4):
    """A stand-in for skxfem.solver.Result: a box cut by the plane {last coord = 0.5}."""
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
    return SimpleNamespace(
        scene=scene, mesh=mesh, points=points, normals=normals,
        u_minus=rng.random((dim, mesh.nvertices)), u_plus=rng.random((dim, mesh.nvertices)),
        traction=-normals * np.linspace(1, 2, n_points), pressure=np.linspace(1, 2, n_points),
        facets=facets, max_jump=1e-12, n_dofs=123, n_multipliers=n_points,
        timings={"cut": 0.1, "enrich": 0.2, "assemble": 0.3, "solve": 0.4})


@pytest.mark.parametrize("cell", ["tri", "quad", "tet", "hex", "prism"])
def test_01_result_json_has_the_promised_keys(tmp_path, cell):
    r = fake_result(cell)
    paths = write_result(r, tmp_path / "out")
    assert set(paths) == {"json", "displacement", "interface"}
    data = json.loads(paths["json"].read_text())
    for key in ("scene", "points", "pressure", "max_jump", "n_dofs", "n_multipliers",
                "timings", "traction", "normals", "law", "space"):
        assert key in data, key
    assert data["scene"] == f"fake_{cell}" and data["n_dofs"] == 123
    np.testing.assert_allclose(data["points"], r.points.T)       # one list per point
    np.testing.assert_allclose(data["pressure"], r.pressure)
    assert data["timings"] == r.timings


@pytest.mark.parametrize("cell", ["tri", "quad", "tet", "hex", "prism"])
def test_02_vtu_files_read_back(tmp_path, cell):
    r = fake_result(cell)
    paths = write_result(r, tmp_path)
    mesh = r.mesh
    m = meshio.read(paths["displacement"])
    assert m.points.shape == (mesh.nvertices, 3)
    np.testing.assert_allclose(m.points[:, :mesh.dim()], mesh.p.T)
    [block] = m.cells
    assert block.type == MESHIO_TYPE[cell] and block.data.shape == mesh.t.T.shape
    for name in ("u_minus", "u_plus"):
        assert m.point_data[name].shape == (mesh.nvertices, 3)
        np.testing.assert_allclose(m.point_data[name][:, :mesh.dim()], getattr(r, name).T)
    side = m.cell_data["side"][0]
    assert side.shape == (mesh.nelements,) and set(side) == {-1, 0, 1}
    i = meshio.read(paths["interface"])
    assert i.cells[0].type == ("line" if mesh.dim() == 2 else "triangle")
    np.testing.assert_array_equal(i.cells[0].data, r.facets.T)
    assert i.point_data["pressure"].shape == (4,)
    assert i.point_data["traction"].shape == i.point_data["normal"].shape == (4, 3)


@pytest.mark.parametrize("cell", ["tri", "quad", "tet", "hex", "prism"])
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
    np.testing.assert_array_equal(np.sort(m.cells[0].data, axis=1),
                                  np.sort(vtk_cells(r.mesh)[1], axis=1))


def test_04_sides_follow_the_sign_convention():
    mesh = box((1, 4), "quad")                              # rows at y in [0, .25, ...]
    psi = mesh.p[1] - 0.6                                   # Γ in the third row
    assert cell_sides(mesh, psi)[np.argsort(mesh.p[1, mesh.t].mean(0))].tolist() == \
        [-1, -1, 0, 1]


def test_05_nan_is_written_as_null_and_stages_are_required(tmp_path):
    r = fake_result("quad")
    r.pressure = np.array([1.0, np.nan, 2.0, np.inf])
    data = json.loads(write_result(r, tmp_path)["json"].read_text())
    assert data["pressure"] == [1.0, None, 2.0, None]
    r.timings = {"cut": 0.1}
    with pytest.raises(ValueError, match="enrich"):
        write_result(r, tmp_path)
