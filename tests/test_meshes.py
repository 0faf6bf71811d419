"""Tests for skxfem.fem.meshes: boxes of five cell types, mesh checks, file input."""
import meshio
import numpy as np
import pytest
from skfem import Basis, MeshHex1, MeshLine1, MeshQuad1, MeshTet1, MeshTri1, MeshTri2, MeshWedge1
from skfem.io.meshio import to_meshio

from skxfem.fem.meshes import CELLS, box, cell_name, check_mesh, read
from skxfem.fem.quadrature import cell_rule, wedge_rule

N3, SIZE3 = (2, 3, 5), (1.5, 2.0, 0.5)
N2, SIZE2 = (3, 4), (1.5, 2.0)


def shape(cell):
    return (N2, SIZE2) if cell in ("tri", "quad") else (N3, SIZE3)


def volume(mesh):
    return Basis(mesh, mesh.elem(), quadrature=cell_rule(mesh)).dx.sum()


# cells per box, and facets per named face, for n = (nx, ny[, nz])
NCELLS = {"tri": lambda n: 2 * n[0] * n[1], "quad": lambda n: n[0] * n[1],
          "tet": lambda n: 6 * np.prod(n), "hex": lambda n: np.prod(n),
          "prism": lambda n: 2 * np.prod(n)}


def faces_per_square(cell, axis):
    """Boundary facets per grid square of the face normal to ``axis``."""
    if cell in ("tri", "quad", "hex"):
        return 1
    if cell == "tet":
        return 2
    return 2 if axis == 0 else 1     # prism: triangles on x = const, quads elsewhere


def test_box_counts_volume_and_name(cell):
    n, size = shape(cell)
    mesh = box(n, cell, size=size)
    assert type(mesh) is CELLS[cell] and cell_name(mesh) == cell
    assert mesh.nelements == NCELLS[cell](n)
    assert abs(volume(mesh) - np.prod(size)) < 1e-12
    assert np.allclose(mesh.p.min(axis=1), 0) and np.allclose(mesh.p.max(axis=1), size)
    assert check_mesh(mesh, dim=len(n)) is mesh


def test_box_named_boundaries(cell):
    n, size = shape(cell)
    mesh = box(n, cell, size=size)
    dim = len(n)
    names = [a + e for a in "xyz"[:dim] for e in ("min", "max")]
    assert sorted(mesh.boundaries) == sorted(names)
    bnd = mesh.boundary_facets()
    tagged = np.concatenate([mesh.boundaries[k] for k in names])
    assert np.array_equal(np.sort(tagged), np.sort(bnd)), \
        "every boundary facet must be on exactly one face of the box"
    for d in range(dim):
        squares = np.prod([n[k] for k in range(dim) if k != d])
        for end, value in (("min", 0.0), ("max", size[d])):
            facets = mesh.boundaries["xyz"[d] + end]
            assert len(facets) == squares * faces_per_square(cell, d)
            assert np.allclose(mesh.p[d, mesh.facets[:, facets]], value)


def test_box_accepts_one_number_for_all_directions():
    mesh = box(2, "hex", size=3.0)
    assert mesh.nelements == 8 and abs(volume(mesh) - 27.0) < 1e-12


def test_prism_box_follows_the_paper():
    nx, ny, nz = 2, 3, 3
    mesh = box((nx, ny, nz), "prism")
    p, t = mesh.p, mesh.t
    # bottom (0, 1, 2) and top (3, 4, 5) triangles each lie in a plane x = const ...
    assert np.all(np.ptp(p[0, t[:3]], axis=0) == 0)
    assert np.all(np.ptp(p[0, t[3:]], axis=0) == 0)
    # ... and the prism edges 0-3, 1-4, 2-5 run along +x
    assert np.allclose(p[1:, t[3:]], p[1:, t[:3]])
    assert np.all(p[0, t[3:]] - p[0, t[:3]] > 0)
    # 2 * ny * nz triangles per x-layer
    assert mesh.nelements == nx * 2 * ny * nz
    # positive orientation at every quadrature point of the prism rule
    X, _ = wedge_rule(2)
    assert np.all(mesh.mapping().detDF(X) > 0)
    # the plane z = 0.5 (odd nz) cuts edges, some of them diagonals of (y, z) squares
    e = p[:, mesh.edges]                                # (3, 2, nedges)
    cut = (e[2, 0] - 0.5) * (e[2, 1] - 0.5) < 0
    assert np.any(cut)
    assert np.any(cut & (e[1, 0] != e[1, 1])), "some cut edges must be diagonals"
    assert np.all(e[0, 0, cut] == e[0, 1, cut]), "no cut edge runs along x"


def test_box_rejects_bad_input():
    with pytest.raises(ValueError, match="cell"):
        box(2, "wedge")
    with pytest.raises(ValueError, match="n must"):
        box((2, 2), "hex")
    with pytest.raises(ValueError, match="n must"):
        box(0, "tri")
    with pytest.raises(ValueError, match="size must"):
        box(2, "quad", size=(1.0, -1.0))


# check_mesh --------------------------------------------------------------------

def test_check_mesh_rejects_unsupported_types():
    for mesh in (MeshTri2(), MeshLine1()):
        with pytest.raises(TypeError, match="MeshTri1, MeshQuad1, MeshTet1"):
            check_mesh(mesh)


def test_check_mesh_rejects_nan_and_wrong_dimension():
    p = MeshTri1().p.copy()
    p[0, 1] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        check_mesh(MeshTri1(p, MeshTri1().t))
    with pytest.raises(ValueError, match="3D"):
        check_mesh(box(1, "quad"), dim=3)


def test_check_mesh_accepts_skfem_node_orders():
    # scikit-fem's own meshes mix orientations (MeshTri1 sorts its cells):
    # they are valid and must pass
    x = np.linspace(0, 1, 3)
    for mesh in (MeshTri1.init_tensor(x, x), MeshQuad1.init_tensor(x, x),
                 MeshTet1.init_tensor(x, x, x), MeshHex1.init_tensor(x, x, x),
                 MeshWedge1()):
        check_mesh(mesh)


def test_check_mesh_rejects_folded_and_flat_cells():
    hex_ = MeshHex1()
    p = hex_.p.copy()
    corner = np.argmax(p.sum(axis=0))                  # vertex (1, 1, 1)
    p[:, corner] = [-0.5, -0.5, -0.5]                  # pulled through the cell
    with pytest.raises(ValueError, match="inverted"):
        check_mesh(MeshHex1(p, hex_.t))
    wedge = box(1, "prism")
    p = wedge.p.copy()
    p[0, wedge.t[3, 0]] = -1.0                          # a top vertex behind the bottom
    with pytest.raises(ValueError, match="inverted"):
        check_mesh(MeshWedge1(p, wedge.t))
    flat = MeshTri1(np.array([[0.0, 1.0, 2.0, 0.0], [0.0, 0.0, 0.0, 1.0]]),
                    np.array([[0, 1, 2], [0, 1, 3]]).T)
    with pytest.raises(ValueError, match="degenerate"):
        check_mesh(flat)


# read ---------------------------------------------------------------------------

@pytest.mark.parametrize("cell, meshio_type", [("tri", "triangle"), ("quad", "quad"),
                                               ("tet", "tetra"), ("hex", "hexahedron"),
                                               ("prism", "wedge")])
def test_read_gmsh_file(tmp_path, cell, meshio_type):
    n, size = shape(cell)
    mesh = box(n, cell, size=size)
    written = to_meshio(mesh)          # scikit-fem knows meshio's node orders
    points = np.c_[written.points, np.zeros((mesh.nvertices, 3 - mesh.dim()))]
    assert written.cells[0].type == meshio_type
    tags = {"gmsh:physical": [np.ones(mesh.nelements, int)],
            "gmsh:geometrical": [np.ones(mesh.nelements, int)]}
    path = str(tmp_path / "box.msh")
    meshio.write(path, meshio.Mesh(points, written.cells, cell_data=tags),
                 file_format="gmsh22", binary=False)
    back = read(path)
    assert type(back) is CELLS[cell] and back.nelements == mesh.nelements
    assert back.dim() == mesh.dim()
    assert abs(volume(back) - np.prod(size)) < 1e-12


def test_read_rejects_files_without_supported_cells(tmp_path):
    path = str(tmp_path / "lines.vtu")
    meshio.write(path, meshio.Mesh(np.eye(3), [("line", np.array([[0, 1], [1, 2]]))]))
    with pytest.raises(ValueError, match="no supported cells"):
        read(path)


def test_read_names_a_missing_or_unreadable_file(tmp_path, capfd):
    with pytest.raises(ValueError, match="does not exist"):
        read(tmp_path / "nope.msh")
    garbled = tmp_path / "garbled.msh"
    garbled.write_text("this is not a mesh\n")
    with pytest.raises(ValueError, match="could not be read by meshio"):
        read(garbled)
    assert capfd.readouterr() == ("", ""), "meshio's messages are in the error, not printed"


def test_read_names_what_is_not_a_file_without_opening_it(tmp_path):
    """A FIFO would block meshio's open() for ever; a folder was "does not exist"."""
    import os
    os.mkfifo(tmp_path / "fifo.msh")
    (tmp_path / "folder.msh").mkdir()
    os.symlink("loop.msh", tmp_path / "loop.msh")
    for name, words in (("fifo.msh", "is a FIFO"), ("folder.msh", "is a folder"),
                        ("loop.msh", "loop of symbolic links"), ("/dev/zero", "device")):
        with pytest.raises(ValueError, match=words):
            read(tmp_path / name)


# a 3 x 2 grid of 12 vertices: 5 quads and 2 triangles, as in a tester's file
GRID = np.array([[0, 0], [1, 0], [2, 0], [0, 1], [1, 1], [2, 1], [0, 2], [1, 2], [2, 2],
                 [3, 0], [3, 1], [3, 2]], dtype=float)
QUADS = np.array([[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7], [2, 9, 10, 5]])
TRIANGLES = np.array([[5, 10, 11], [5, 11, 8]])


def write_mesh(tmp_path, name, points, cells):
    path = tmp_path / name
    meshio.write(path, meshio.Mesh(np.c_[points, np.zeros(len(points))], cells))
    return path


def test_read_refuses_mixed_cell_types(tmp_path):
    path = write_mesh(tmp_path, "mixed.vtu", GRID, [("quad", QUADS), ("triangle", TRIANGLES)])
    with pytest.raises(ValueError) as info:
        read(path)
    message = str(info.value)
    for words in ("mixed.vtu", "5 quad", "2 triangle", "one cell type per mesh"):
        assert words in message, message


def test_read_ignores_lower_dimensional_blocks(tmp_path):
    mesh = box(1, "tet")
    faces = mesh.facets[:, mesh.boundary_facets()].T
    path = tmp_path / "tets.vtu"
    meshio.write(path, meshio.Mesh(mesh.p.T, [("tetra", mesh.t.T), ("triangle", faces)]))
    assert read(path).nelements == mesh.nelements


def test_read_refuses_unused_vertices(tmp_path):
    points = np.vstack([GRID[:11], [[5.0, 5.0]]])   # the quads use 0..10: 11 is in no cell
    path = write_mesh(tmp_path, "unused.vtu", points, [("quad", QUADS)])
    with pytest.raises(ValueError, match=r"unused.vtu: 1 vertex\(es\) used by no cell "
                                         r"\(first: \[11\]\).*remove them"):
        read(path)


def test_read_refuses_cells_past_the_last_vertex(tmp_path):
    quads = QUADS.copy()
    quads[1, 2] = 999
    path = write_mesh(tmp_path, "broken.vtu", GRID, [("quad", quads)])
    with pytest.raises(ValueError) as info:
        read(path)
    message = str(info.value)
    assert "out of bounds" not in message, message
    for words in ("broken.vtu", "1 quad cell(s)", "cell 1 uses vertex 999", "12 vertices"):
        assert words in message, message


def test_what_meshio_says_of_an_unreadable_file_keeps_a_long_path_whole(tmp_path, capfd):
    """meshio prints with rich, wrapped at 80 columns when the output is no terminal: a
    path longer than that, cut by a line break, would show with a space inside it."""
    folder = tmp_path / ("a_long_folder_name_" * 6)
    folder.mkdir()
    path = folder / "junk.vtu"
    path.write_text("<VTKFile")
    with pytest.raises(ValueError, match="could not be read by meshio") as info:
        read(path)
    assert f"Couldn't read file {path} as vtu" in str(info.value)
    assert capfd.readouterr() == ("", "")
