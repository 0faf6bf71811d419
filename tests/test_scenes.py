"""Tests for skxfem/scene/benchmarks.py: the benchmark scenes are built as documented.

What is checked for ``paper_plate(n, "hex" | "prism")`` and ``strip(n, "quad" | "tri")``:

1. Ω = [0, 1]³ (or [0, 1]²) with n cells in x (and y) and an odd number of
   cells in z (y in 2D), n itself if odd, else n + 1; the interface is the plane
   z = 0.5 (y = 0.5) with Ω⁻ below, no node lies on it, and it cuts exactly
   one layer of cells.
2. The supports: bottom clamped; rollers u_x = 0 on x = 0 and x = 1 in 3D; the
   2D sides free.  Nothing else is imposed, and every imposed value is zero.
3. The load: a pressure 4 P_max y(1 - y) (4 P_max x(1 - x) in 2D) on the top
   face only, pushing down, with resultant 2/3 P_max.
4. The prisms are the paper's (Figure 4): triangles in the (y, z) plane
   extruded along x, 2n of them per row in y ("2/h elements in the y
   direction"), so that z = 0.5 cuts the triangles' diagonal edges: every cut
   edge has dx = 0 and some are diagonal (dy ≠ 0 and dz ≠ 0).  On hexahedra
   every cut edge is vertical.
5. Bad arguments (even nz/ny, n not a positive integer, an unknown cell) are
   refused with a message that says what is expected.
"""
import numpy as np
import pytest
from skfem import Basis, ElementVector

from skxfem.cut import cut
from skxfem.fem.loads import boundary_quadrature
from skxfem.fem.material import Material
from skxfem.levelset import nodal_values
from skxfem.scene import Box, dirichlet, load_facets, resolve_mesh
from skxfem.scene.benchmarks import P_MAX, exact_plate, paper_plate, strip

PLATES = [(n, cell) for cell in ("hex", "prism") for n in (2, 3, 4)]
STRIPS = [(n, cell) for cell in ("quad", "tri") for n in (2, 3, 4)]


def built(scene):
    mesh = resolve_mesh(scene)
    return mesh, Basis(mesh, ElementVector(mesh.elem()))


def odd(n):
    return n if n % 2 else n + 1


# 1. domain, cell counts and interface ---------------------------------------------

@pytest.mark.parametrize("n, cell", PLATES + STRIPS)
def test_domain_cells_and_interface(n, cell):
    plate = cell in ("hex", "prism")
    scene = paper_plate(n, cell) if plate else strip(n, cell)
    dim = 3 if plate else 2
    nup = odd(n)
    assert scene.mesh == Box((n,) * (dim - 1) + (nup,), cell, (1.0,) * dim), (
        f"{scene.name}: expected {n} cells across and {nup} (odd) cells up, got {scene.mesh}")
    assert scene.material == Material(1.0, 0.3, "strain")
    assert (scene.law, scene.space) == ("bonded", "vital")
    mesh, _ = built(scene)
    assert np.array_equal(mesh.p.min(axis=1), np.zeros(dim))
    assert np.array_equal(mesh.p.max(axis=1), np.ones(dim)), "Ω must be the unit box"
    psi = nodal_values(scene.levelset, mesh)
    up = mesh.p[-1]
    assert np.abs(psi - (up - 0.5)).max() < 1e-15, "Γ is the plane at height 0.5, Ω⁻ below"
    assert abs(np.abs(psi).min() - 0.5 / nup) < 1e-15, (
        f"with {nup} cells up the nearest node row is half a cell ({0.5 / nup}) from Γ: "
        f"no node on Γ")
    c = cut(mesh, psi)
    # the cut cells are one whole layer: those whose height range contains 0.5
    lo, hi = up[mesh.t].min(axis=0), up[mesh.t].max(axis=0)
    layer = np.flatnonzero((lo < 0.5) & (hi > 0.5))
    assert np.array_equal(np.sort(c.cells), layer), "Γ must cut exactly the middle layer"
    per_layer = {"hex": n * n, "prism": 2 * n * n, "quad": n, "tri": 2 * n}[cell]
    assert layer.size == per_layer


# 2. supports --------------------------------------------------------------------------

@pytest.mark.parametrize("n, cell", PLATES)
def test_plate_bottom_clamped_and_rollers_on_x_faces(n, cell):
    mesh, basis = built(paper_plate(n, cell))
    dofs, values = dirichlet(paper_plate(n, cell), mesh, basis)
    x, z = mesh.p[0], mesh.p[2]
    bottom = np.flatnonzero(z == 0.0)
    sides = np.flatnonzero((x == 0.0) | (x == 1.0))
    expected = set(basis.nodal_dofs[:, bottom].ravel()) | set(basis.nodal_dofs[0, sides])
    assert set(dofs.tolist()) == expected, (
        "imposed: every component on z = 0 (clamped) and u_x on x = 0, 1 (rollers), "
        "nothing else")
    assert np.all(values == 0.0)


@pytest.mark.parametrize("n, cell", STRIPS)
def test_strip_bottom_clamped_sides_free(n, cell):
    scene = strip(n, cell)
    mesh, basis = built(scene)
    dofs, values = dirichlet(scene, mesh, basis)
    bottom = np.flatnonzero(mesh.p[1] == 0.0)
    assert set(dofs.tolist()) == set(basis.nodal_dofs[:, bottom].ravel()), \
        "the strip is clamped on y = 0 and nowhere else"
    assert np.all(values == 0.0)


# 3. the load ---------------------------------------------------------------------------

@pytest.mark.parametrize("n, cell", PLATES + STRIPS)
def test_parabolic_pressure_on_the_top_face(n, cell):
    plate = cell in ("hex", "prism")
    scene = paper_plate(n, cell) if plate else strip(n, cell)
    mesh, _ = built(scene)
    top = "zmax" if plate else "ymax"
    [(facets, t)] = load_facets(scene, mesh)
    assert np.array_equal(np.sort(facets), np.sort(mesh.boundaries[top])), \
        f"the only load acts on the top face {top}"
    q = boundary_quadrature(mesh, facets, order=2)
    s = q.points[1] if plate else q.points[0]  # the plate's y, the strip's x
    tq = t(q.points, q.normals)
    expected = -4 * P_MAX * s * (1 - s)
    assert np.abs(tq[-1] - expected).max() < 1e-14, "t = -p n with p = 4 P_max s(1 - s)"
    assert np.abs(tq[:-1]).max() < 1e-14, "a pressure has no tangential part on a flat top"
    assert abs(q.weights @ tq[-1] + 2 / 3 * P_MAX) < 1e-13, \
        "the resultant of 4 P_max s(1 - s) over the unit top face is 2/3 P_max, downwards"


# 4. the paper's prisms ------------------------------------------------------------------

@pytest.mark.parametrize("n", [2, 3, 4])
def test_prisms_are_triangles_in_yz_extruded_along_x(n):
    mesh, _ = built(paper_plate(n, "prism"))
    p, t = mesh.p, mesh.t
    assert t.shape[0] == 6
    bottom, top = p[:, t[:3]], p[:, t[3:]]
    assert np.all(np.ptp(bottom[0], axis=0) == 0) and np.all(np.ptp(top[0], axis=0) == 0), \
        "each triangular face must lie in a plane x = const"
    assert np.all(top[0, 0] - bottom[0, 0] > 0), "the prisms are extruded along x"
    assert np.array_equal(bottom[1:], top[1:]), "both triangles have the same (y, z)"
    # 2n triangles per row in y ("2/h elements in the y direction"), 1 x-layer each
    nz = odd(n)
    first = np.isclose(p[0, t[0]], 0.0)
    row = np.floor(p[2, t[:3]].mean(axis=0) * nz).astype(int)
    counts = np.bincount(row[first], minlength=nz)
    assert np.all(counts == 2 * n), (
        f"each (y, z) row of one x-layer should hold 2n = {2 * n} triangles, got {counts}")
    assert mesh.nelements == n * 2 * n * nz


@pytest.mark.parametrize("n", [2, 3, 4])
def test_gamma_cuts_the_diagonal_edges_of_the_prisms(n):
    scene = paper_plate(n, "prism")
    mesh, _ = built(scene)
    d = np.abs(np.diff(mesh.p[:, cut(mesh, scene.levelset).edges], axis=1)[:, 0])
    dx, dy, dz = d
    assert np.all(dx == 0), "no cut edge runs along x: the (y, z) triangles are cut"
    diagonal = (dy > 0) & (dz > 0)
    assert diagonal.any(), "z = 0.5 must cut diagonal edges of the triangles (dy, dz ≠ 0)"
    assert np.all(dz > 0), "a cut edge must cross the plane z = 0.5"
    # one vertical and one diagonal cut edge per square of the cut row, both x-faces
    assert diagonal.sum() == n * (n + 1) and (~diagonal).sum() == (n + 1) ** 2


@pytest.mark.parametrize("n", [2, 3])
def test_on_hexahedra_every_cut_edge_is_vertical(n):
    scene = paper_plate(n, "hex")
    mesh, _ = built(scene)
    d = np.abs(np.diff(mesh.p[:, cut(mesh, scene.levelset).edges], axis=1)[:, 0])
    assert np.all(d[:2] == 0) and np.all(d[2] > 0), "hexahedra: only vertical edges are cut"
    assert d.shape[1] == (n + 1) ** 2


# 5. arguments ----------------------------------------------------------------------------

def test_arguments_are_passed_on():
    s = paper_plate(3, "prism", nz=5, law="bilateral", space="vital")
    assert s.mesh.n == (3, 3, 5) and (s.law, s.space) == ("bilateral", "vital")
    assert s.name == "paper_plate_prism_3x3x5"
    s = strip(4, "tri", ny=7, law="bilateral", space="winner")
    assert s.mesh.n == (4, 7) and (s.law, s.space) == ("bilateral", "winner")
    assert s.name == "strip_tri_4x7"
    assert exact_plate(3, nx=1).mesh.n == (1, 3, 3), "nx sets the cells along x only"


@pytest.mark.parametrize("make, message", [
    (lambda: paper_plate(3, nz=4), "nz must be an odd positive integer"),
    (lambda: paper_plate(3, nz=0), "nz must be an odd positive integer"),
    (lambda: strip(3, ny=6), "ny must be an odd positive integer"),
    (lambda: paper_plate(0), "n must be a positive integer"),
    (lambda: paper_plate(2.5), "n must be a positive integer"),
    (lambda: strip(True), "n must be a positive integer"),
    (lambda: strip(-3), "n must be a positive integer"),
    (lambda: paper_plate(3, "quad"), "cell must be 'hex', 'prism' or 'tet'"),
    (lambda: paper_plate(3, "wedge"), "cell must be 'hex', 'prism' or 'tet'"),
    (lambda: paper_plate(3, nx=0), "nx must be a positive integer"),
    (lambda: strip(3, sides="glued"), "sides must be 'free' or 'rollers'"),
    (lambda: strip(3, "hex"), "cell must be 'quad' or 'tri'"),
    (lambda: paper_plate(3, law="sticky"), "law must be one of"),
    (lambda: strip(3, space="clever"), "space must be one of"),
])
def test_bad_arguments_are_refused(make, message):
    with pytest.raises(ValueError, match=message):
        make()
