"""Tests for skxfem.fem.loads: boundary quadrature, cut facets and surface loads."""
import numpy as np
import pytest
from skfem import (
    Basis,
    ElementHex1,
    ElementQuad1,
    ElementTetP1,
    ElementTriP1,
    ElementVector,
    ElementWedge1,
    FacetBasis,
    LinearForm,
    MeshTri1,
    asm,
    condense,
    solve,
)
from skfem.helpers import dot

from skxfem.fem.loads import (
    BoundaryQuadrature,
    boundary_quadrature,
    force_field,
    pressure,
    surface_load,
)
from skxfem.fem.material import Material, stiffness_form
from skxfem.fem.meshes import box
from skxfem.fem.quadrature import cell_rule
from skxfem.scene import CELLS

ELEM = {"tri": ElementTriP1, "quad": ElementQuad1, "tet": ElementTetP1,
        "hex": ElementHex1, "prism": ElementWedge1}


def unit_box(cell):
    return box((3, 2) if CELLS[cell] == 2 else (2, 3, 3), cell)


def vector_basis(mesh, cell):
    return Basis(mesh, ElementVector(ELEM[cell]()), quadrature=cell_rule(mesh))


def sheared(mesh):
    """The same mesh under a fixed affine map (facet numbering unchanged)."""
    dim = mesh.dim()
    A = np.eye(dim) + (np.array([[0, 0.2], [0.1, 0]]) if dim == 2 else
                       np.array([[0, 0, 0.2], [0.1, 0, 0], [0, 0.3, 0]]))
    return type(mesh)(A @ mesh.p, mesh.t)


def parabola(x):
    """The paper's pressure p = 4 s (1 - s) along the second-to-last coordinate."""
    s = x[-2]
    return 4 * s * (1 - s)


# 1. geometry of the boundary rule ----------------------------------------------

def test_closed_boundary_identities(cell):
    # divergence theorem on the whole boundary: ∮ n = 0 and ∮ x·n = dim * volume
    mesh = sheared(unit_box(cell))
    dim = mesh.dim()
    q = boundary_quadrature(mesh, mesh.boundary_facets(), order=2)
    assert isinstance(q, BoundaryQuadrature)
    volume = Basis(mesh, ELEM[cell](), quadrature=cell_rule(mesh)).dx.sum()
    assert np.allclose(np.linalg.norm(q.normals, axis=0), 1.0, atol=1e-14)
    assert np.allclose(q.normals @ q.weights, 0.0, atol=1e-13)
    assert abs(q.weights @ np.sum(q.points * q.normals, axis=0) - dim * volume) < 1e-12
    # each point's reference coordinates map to its physical point
    assert np.allclose(mesh.mapping().F(q.ref[:, :, None], tind=q.cells)[:, :, 0],
                       q.points, atol=1e-14)
    assert np.all(q.side == 1)


def test_normals_point_out_of_their_cell(cell):
    mesh = sheared(unit_box(cell))
    q = boundary_quadrature(mesh, mesh.boundary_facets(), order=1)
    centroid = mesh.p[:, mesh.t].mean(axis=1)[:, q.cells]
    assert np.all(np.sum((q.points - centroid) * q.normals, axis=0) > 0)


# 2. total forces ---------------------------------------------------------------

def test_total_force_of_constant_and_parabolic_pressure(cell):
    mesh = unit_box(cell)
    top = "ymax" if CELLS[cell] == 2 else "zmax"
    basis = vector_basis(mesh, cell)
    q = boundary_quadrature(mesh, mesh.boundaries[top], order=4)
    for p, exact in ((lambda x: 1.0 + 0 * x[0], 1.0), (parabola, 2 / 3)):
        f, f_H = surface_load(basis, q, pressure(p))
        total = np.array([f[d].sum() for d in basis.nodal_dofs])
        expected = np.zeros(mesh.dim())
        expected[-1] = -exact                              # pushes down on the top face
        assert np.allclose(total, expected, atol=1e-12), total
        assert np.allclose(f_H, f, atol=1e-15), "no level set: H = +1 everywhere"


def test_prism_triangle_faces_carry_the_load_too():
    mesh = unit_box("prism")                               # x = const faces are triangles
    basis = vector_basis(mesh, "prism")
    q = boundary_quadrature(mesh, mesh.boundaries["xmax"], order=4)
    f, _ = surface_load(basis, q, pressure(parabola))      # p(y) on x = 1
    assert abs(f[basis.nodal_dofs[0]].sum() + 2 / 3) < 1e-12


@pytest.mark.parametrize("cell", ["tri", "quad", "tet", "hex"])
def test_load_vector_equals_skfem_facetbasis(cell):
    mesh0 = unit_box(cell)
    top = mesh0.boundaries["ymax" if CELLS[cell] == 2 else "zmax"]
    mesh = sheared(mesh0)
    basis = vector_basis(mesh, cell)
    shear = np.array([0.5, -0.2, 0.3][:mesh.dim()])

    def traction(x, n):
        return pressure(parabola)(x, n) + shear.reshape((-1,) + (1,) * (x.ndim - 1)) * x[0]

    f, _ = surface_load(basis, boundary_quadrature(mesh, top, order=5), traction)

    @LinearForm
    def load(v, w):
        return dot(traction(w.x, w.n), v)

    fb = FacetBasis(mesh, basis.elem, facets=top, intorder=5)
    f_skfem = asm(load, fb)
    assert np.abs(f - f_skfem).max() < 1e-12


def _by_coordinates(mesh_a, f_a, basis_a, mesh_b, f_b, basis_b, nodes_a):
    """Largest difference of two load vectors at the nodes ``nodes_a`` of mesh a,
    matched to mesh b's nodes by their coordinates."""
    d = np.linalg.norm(mesh_a.p[:, nodes_a, None] - mesh_b.p[:, None, :], axis=0)
    assert d.min(axis=1).max() < 1e-12, "every node has a twin"
    nodes_b = d.argmin(axis=1)
    return np.abs(f_a[basis_a.nodal_dofs[:, nodes_a]]
                  - f_b[basis_b.nodal_dofs[:, nodes_b]]).max()


def test_prism_load_node_by_node():
    """FacetBasis cannot load prisms, so check skxfem's prism load dof by dof.

    The quadrilateral faces of a prism carry the bilinear trace of its shape
    functions: on the top face z = 1 the load equals the hexahedral one on the
    same grid.  The triangular faces carry the linear trace: on x = 0 it equals
    the plain P1 load of the face's triangles, assembled by scikit-fem in 2D.
    """
    prism, hexa = box((2, 3, 3), "prism"), box((2, 3, 3), "hex")
    bp, bh = vector_basis(prism, "prism"), vector_basis(hexa, "hex")

    def t3(x, n):
        return np.array([x[1] * x[2], 1 + x[0] * x[1], parabola(x)])

    top_p, top_h = (m.boundaries["zmax"] for m in (prism, hexa))
    fp, _ = surface_load(bp, boundary_quadrature(prism, top_p, order=5), t3)
    fh, _ = surface_load(bh, boundary_quadrature(hexa, top_h, order=5), t3)
    top_nodes = np.unique(prism.facets[:, top_p])
    assert np.abs(fp[bp.nodal_dofs[:, top_nodes]]).max() > 0.01
    assert _by_coordinates(prism, fp, bp, hexa, fh, bh, top_nodes) < 1e-13

    side = prism.boundaries["xmin"]
    fs, _ = surface_load(bp, boundary_quadrature(prism, side, order=5), t3)
    tri_nodes = np.unique(prism.facets[:, side])
    local = np.full(prism.p.shape[1], -1)
    local[tri_nodes] = np.arange(tri_nodes.size)
    tris = prism.facets[:, side]
    assert np.all(tris[0] == tris[1]), "scikit-fem stores a triangular facet with a repeated node"
    face = MeshTri1(prism.p[1:, tri_nodes], local[tris[1:]])
    bt = Basis(face, ElementVector(ElementTriP1()), intorder=5)

    @LinearForm
    def load(v, w):
        x = np.array([0 * w.x[0], w.x[0], w.x[1]])    # (y, z) -> (0, y, z)
        t = t3(x, None)
        return t[1] * v[0] + t[2] * v[1]               # the y, z components; x below

    @LinearForm
    def load_x(v, w):
        return w.x[0] * w.x[1] * v

    ft = asm(load, bt)
    fx = asm(load_x, Basis(face, ElementTriP1(), intorder=5))
    sp_dofs = bp.nodal_dofs[:, tri_nodes]
    assert np.abs(fs[sp_dofs[0]] - fx).max() < 1e-13
    assert np.abs(fs[sp_dofs[1]] - ft[bt.nodal_dofs[0]]).max() < 1e-13
    assert np.abs(fs[sp_dofs[2]] - ft[bt.nodal_dofs[1]]).max() < 1e-13


# 3. facets cut by a level set --------------------------------------------------

def test_cut_face_measures_both_sides(cell):
    mesh = unit_box(cell)
    if CELLS[cell] == 2:             # Γ: x = 0.3 cuts the top edge y = 1
        psi, top, plus = mesh.p[0] - 0.3, "ymax", 0.7
    else:                            # Γ: x + 2y = 1.1 cuts the top face obliquely
        psi, top, plus = mesh.p[0] + 2 * mesh.p[1] - 1.1, "zmax", 0.7
    q = boundary_quadrature(mesh, mesh.boundaries[top], order=1, psi_nodes=psi)
    assert set(np.unique(q.side)) == {-1.0, 1.0}
    assert abs(q.weights.sum() - 1.0) < 1e-14
    assert abs(q.weights[q.side > 0].sum() - plus) < 1e-14
    assert abs(q.weights @ q.side - (plus - (1 - plus))) < 1e-14
    # each point really lies on its side of Γ
    psi_x = q.points[0] - 0.3 if CELLS[cell] == 2 else q.points[0] + 2 * q.points[1] - 1.1
    assert np.all(q.side * psi_x >= -1e-14)


@pytest.mark.parametrize("cell", [c for c in CELLS if CELLS[c] == 3])
def test_enriched_load_of_the_parabolic_pressure(cell):
    # ∫ H p over the top face with Γ: y = 0.3 (not on a node line)
    mesh = unit_box(cell)
    basis = vector_basis(mesh, cell)
    q = boundary_quadrature(mesh, mesh.boundaries["zmax"], order=4,
                            psi_nodes=mesh.p[1] - 0.3)
    f, f_H = surface_load(basis, q, pressure(parabola))
    below = 2 * 0.3 ** 2 - 4 * 0.3 ** 3 / 3                 # ∫_0^0.3 4y(1-y)
    assert abs(f[basis.nodal_dofs[2]].sum() + 2 / 3) < 1e-12
    assert abs(f_H[basis.nodal_dofs[2]].sum() + (2 / 3 - 2 * below)) < 1e-12


@pytest.mark.parametrize("cell", [c for c in CELLS if CELLS[c] == 3])
def test_level_set_through_nodes_and_on_the_face(cell):
    mesh = box((2, 2, 2), cell)
    top = mesh.boundaries["zmax"]
    q = boundary_quadrature(mesh, top, order=1, psi_nodes=mesh.p[1] - 0.5)
    assert abs(q.weights.sum() - 1.0) < 1e-14, "nothing counted twice"
    assert abs(q.weights @ q.side) < 1e-14
    q = boundary_quadrature(mesh, top, order=1, psi_nodes=mesh.p[2] - 1.0)
    assert abs(q.weights.sum() - 1.0) < 1e-14 and np.all(q.side == 1)


# 4. bad input -------------------------------------------------------------------

def test_bad_input_is_rejected():
    mesh = box(2, "hex")
    interior = np.setdiff1d(np.arange(mesh.facets.shape[1]), mesh.boundary_facets())
    with pytest.raises(ValueError, match="boundary facets"):
        boundary_quadrature(mesh, interior[:2], 1)
    with pytest.raises(ValueError, match="facets must be"):
        boundary_quadrature(mesh, [0.5], 1)
    top = mesh.boundaries["zmax"]
    with pytest.raises(ValueError, match="psi_nodes"):
        boundary_quadrature(mesh, top, 1, psi_nodes=np.zeros(3))
    q = boundary_quadrature(mesh, top, 1)
    with pytest.raises(TypeError, match="vector element"):
        surface_load(Basis(mesh, ElementHex1()), q, [0, 0, 1])
    with pytest.raises(ValueError, match="traction must return"):
        surface_load(vector_basis(mesh, "hex"), q, lambda x, n: x[0])
    with pytest.raises(ValueError, match="mesh of basis"):
        surface_load(vector_basis(box(2, "quad"), "quad"), q, [0, 0])


# 5. a prism cantilever against hexahedra on the same grid ----------------------

def tip_deflection(cell):
    """Beam [0, 2] x [0, 1]^2 along x (the prisms' extrusion axis), clamped at
    x = 0, unit shear traction -e_z on x = 2 (triangular faces for prisms)."""
    mesh = box((8, 4, 4), cell, size=(2.0, 1.0, 1.0))
    basis = vector_basis(mesh, cell)
    K = asm(stiffness_form(Material(E=1000.0, nu=0.3), 3), basis)
    q = boundary_quadrature(mesh, mesh.boundaries["xmax"], order=2)
    f, _ = surface_load(basis, q, [0.0, 0.0, -1.0])
    u = solve(*condense(K, f, D=basis.get_dofs(mesh.boundaries["xmin"]).all()))
    tip = np.nonzero(mesh.p[0] == 2.0)[0]
    return u[basis.nodal_dofs[2, tip]].mean()


def test_prism_cantilever_matches_hexahedra():
    w_prism, w_hex = tip_deflection("prism"), tip_deflection("hex")
    # measured: prism -0.034885, hex -0.035188 (Timoshenko beam: -0.0382)
    assert w_prism < 0 and w_hex < 0
    assert abs(w_prism / w_hex - 1) < 0.03, (w_prism, w_hex)


# ---------------------------------------------------------------- body force fields


def test_force_field_takes_numbers_callables_and_a_whole_field():
    x = np.array([[0.0, 1.0, 2.0], [3.0, 4.0, 5.0]])
    assert force_field((0.0, -9.81), 2)(x).tolist() == [[0.0] * 3, [-9.81] * 3]
    assert force_field((lambda y: y[1], 1.0), 2)(x).tolist() == [[3.0, 4.0, 5.0], [1.0] * 3]
    assert np.array_equal(force_field(lambda y: 2 * y, 2)(x), 2 * x)
    # points of a basis, (dim, cells, quadrature points), keep their shape
    xq = np.arange(12.0).reshape(2, 2, 3)
    assert force_field((1.0, lambda y: y[0]), 2)(xq).shape == (2, 2, 3)


def test_force_field_refuses_bad_forces():
    with pytest.raises(ValueError, match="body force must be a callable"):
        force_field((1.0,), 2)
    with pytest.raises(ValueError, match="body force must be a callable"):
        force_field((1.0, 2.0), 3)
    with pytest.raises(ValueError, match="finite values of shape"):
        force_field(lambda x: x[:1], 2)(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="finite values of shape"):
        force_field((0.0, np.nan), 2)(np.zeros((2, 3)))
