"""Tests for skxfem/fem/evaluate.py: the vector basis at points of known cells.

1. A linear vector field u(x) = Gx + d is in every P1/Q1 space, so the
   evaluation matrix applied to its nodal values reproduces it exactly at
   random reference points of random cells, on every cell type: on a box
   mesh (physical points computed independently of scikit-fem's mapping) and
   on a randomly distorted mesh (points from scikit-fem's mapping).
2. Rows are component-major: the first npts rows are the x values, then y, ...
   and a row of component c only touches dofs of component c.
3. Partition of unity: every row sums to 1; at a cell's vertex the matrix is
   the identity on that vertex's dofs.
4. pressure_along: the multiplier points of one line, sorted, with their pressures.
"""
import numpy as np
import pytest
from skfem import Basis, ElementVector

from skxfem.fem.evaluate import evaluation_matrix, pressure_along
from skxfem.fem.meshes import box, check_mesh
from skxfem.scene.benchmarks import paper_plate, strip
from skxfem.solver import solve


def vector_basis(mesh):
    return Basis(mesh, ElementVector(mesh.elem()))


def random_reference_points(cell, n, rng):
    """n points strictly inside the reference cell, shape (dim, n)."""
    if cell in ("quad", "hex"):
        return rng.uniform(0, 1, (2 if cell == "quad" else 3, n))
    if cell in ("tri", "tet"):
        k = 2 if cell == "tri" else 3
        bary = rng.dirichlet(np.ones(k + 1), n).T    # uniform in the simplex
        return bary[1:]
    # prism: triangle (r, s) times t in [0, 1]
    bary = rng.dirichlet(np.ones(3), n).T
    return np.vstack([bary[1:], rng.uniform(0, 1, n)])


def affine_points(mesh, cells, ref):
    """x = p(v₀) + Σ_d ref_d (p(v_d) - p(v₀)), v_d the local vertex at the
    reference point e_d (v₀ at the origin): exact for the affine cells of box()."""
    doflocs = mesh.elem().doflocs                   # (nverts, dim) reference vertices
    dim = mesh.dim()

    def local(point):
        return int(np.flatnonzero(np.all(doflocs == point, axis=1))[0])

    p0 = mesh.p[:, mesh.t[local(np.zeros(dim)), cells]]
    x = p0.copy()
    for d in range(dim):
        x += ref[d] * (mesh.p[:, mesh.t[local(np.eye(dim)[d]), cells]] - p0)
    return x


def distorted(mesh, rng):
    """The same mesh with interior nodes moved randomly by up to h/10."""
    h = 1.0 / 3.0
    p = mesh.p.copy()
    inner = np.all((p > 1e-9) & (p < 1 - 1e-9), axis=0)
    p[:, inner] += rng.uniform(-0.1 * h, 0.1 * h, (mesh.dim(), inner.sum()))
    return check_mesh(type(mesh)(p, mesh.t))


def linear_field(dim, rng):
    G, d = rng.standard_normal((dim, dim)), rng.standard_normal((dim, 1))
    return lambda x: G @ x + d


def interpolate(basis, u):
    """Dof vector of the field u (callable on (dim, n)) at the mesh nodes."""
    U = np.zeros(basis.N)
    U[basis.nodal_dofs] = u(basis.mesh.p)
    return U


def test_linear_field_is_reproduced_on_box_mesh(cell):
    rng = np.random.default_rng(0)
    mesh = box(3, cell)
    basis = vector_basis(mesh)
    dim = mesh.dim()
    npts = 50
    cells = rng.integers(0, mesh.nelements, npts)
    ref = random_reference_points(cell, npts, rng)
    Phi = evaluation_matrix(basis, cells, ref)
    assert Phi.shape == (dim * npts, basis.N), "one row per point and component"
    u = linear_field(dim, rng)
    x = affine_points(mesh, cells, ref)
    values = (Phi @ interpolate(basis, u)).reshape(dim, npts)
    err = np.abs(values - u(x)).max()
    assert err < 1e-12, (
        f"a linear field must be reproduced exactly at the points; max error {err:.3g} "
        f"(wrong cell, wrong reference point or wrong row order?)")


def test_linear_field_is_reproduced_on_distorted_mesh(cell):
    rng = np.random.default_rng(1)
    mesh = distorted(box(3, cell), rng)
    basis = vector_basis(mesh)
    dim = mesh.dim()
    npts = 50
    cells = rng.integers(0, mesh.nelements, npts)
    ref = random_reference_points(cell, npts, rng)
    x = mesh.mapping().F(ref[:, :, None], tind=cells)[:, :, 0]   # scikit-fem's mapping
    u = linear_field(dim, rng)
    values = (evaluation_matrix(basis, cells, ref) @ interpolate(basis, u)).reshape(dim, npts)
    err = np.abs(values - u(x)).max()
    assert err < 1e-12, (
        f"P1 and the isoparametric Q1/prism elements reproduce linear fields on any "
        f"mesh; max error {err:.3g}")


def test_rows_are_component_major(cell):
    rng = np.random.default_rng(2)
    mesh = box(2, cell)
    basis = vector_basis(mesh)
    dim = mesh.dim()
    npts = 7
    cells = rng.integers(0, mesh.nelements, npts)
    ref = random_reference_points(cell, npts, rng)
    Phi = evaluation_matrix(basis, cells, ref).tocsr()
    component_of = np.empty(basis.N, int)
    component_of[basis.nodal_dofs] = np.arange(dim)[:, None]
    for c in range(dim):
        block = Phi[c * npts:(c + 1) * npts]
        touched = block.indices[block.data != 0]   # (explicit zeros are stored)
        assert touched.size and np.all(component_of[touched] == c), (
            f"rows {c * npts}..{(c + 1) * npts - 1} must hold component {c} only")
    # a field that is constant k in component k: row block c reads c
    U = interpolate(basis, lambda x: np.arange(dim)[:, None] + 0 * x)
    assert np.allclose(Phi @ U, np.repeat(np.arange(dim), npts)), (
        "the rows must be all x values, then all y values (component-major)")


def test_partition_of_unity_and_nodal_interpolation(cell):
    rng = np.random.default_rng(3)
    mesh = box(2, cell)
    basis = vector_basis(mesh)
    dim = mesh.dim()
    npts = 20
    cells = rng.integers(0, mesh.nelements, npts)
    ref = random_reference_points(cell, npts, rng)
    Phi = evaluation_matrix(basis, cells, ref)
    row_sums = np.asarray(Phi.sum(axis=1)).ravel()
    assert np.allclose(row_sums, 1.0, atol=1e-13), "each component's shape functions sum to 1"
    # at the reference vertex k of a cell, only the dofs of its k-th vertex are 1
    doflocs = mesh.elem().doflocs
    cell = 1
    for k, X in enumerate(doflocs):
        Phi = evaluation_matrix(basis, np.array([cell]), X[:, None]).toarray()
        expected = np.zeros((dim, basis.N))
        expected[np.arange(dim), basis.nodal_dofs[:, mesh.t[k, cell]]] = 1.0
        assert np.allclose(Phi, expected, atol=1e-14), (
            f"at local vertex {k}, φ must be 1 on that vertex's dofs and 0 elsewhere")


def test_docstring_example():
    from skfem import ElementTriP1, MeshTri1
    basis = Basis(MeshTri1(), ElementVector(ElementTriP1()))
    Phi = evaluation_matrix(basis, np.array([0]), np.array([[1 / 3], [1 / 3]]))
    assert Phi.shape == (2, 8)
    assert np.allclose(Phi.toarray().sum(axis=1), 1.0)
    # the centroid: 1/3 on each of the cell's three vertices
    nodes = MeshTri1().t[:, 0]
    assert np.allclose(Phi.toarray()[0, basis.nodal_dofs[0, nodes]], 1 / 3)


# 4. pressure along a line
def test_pressure_along_2d_takes_every_point_sorted():
    r = solve(strip(4, "tri"))
    s, p = pressure_along(r, "x")
    assert s.size == r.points.shape[1]
    assert np.all(np.diff(s) > 0)
    k = np.argmin(np.abs(r.points[0] - s[2]))
    assert p[2] == r.pressure[k]


def test_pressure_along_3d_picks_the_middle_node_plane():
    r = solve(paper_plate(2, "hex"))        # 3 x 3 intersection points on z = 0.5
    s, p = pressure_along(r, "y")
    assert s.tolist() == [0.0, 0.5, 1.0], "3 points on the line x = 0.5"
    s_all, _ = pressure_along(r, "y", where={})
    assert s_all.size == r.points.shape[1]
    _, p0 = pressure_along(r, "y", where={"x": 0.0})
    assert np.allclose(p0, p, atol=1e-8), "the plate solution does not depend on x"
    with pytest.raises(ValueError, match="no multiplier point"):
        pressure_along(r, "y", where={"x": 0.3})
    with pytest.raises(ValueError, match="axis"):
        pressure_along(r, "w")
