"""Tests for skxfem/levelset.py: the sign convention and the level set helpers.

1. Sign convention: Ω⁻ = {ψ < 0}; the normal given to :func:`plane` points
   into Ω⁺ (ψ grows along it), and ∇ψ/|∇ψ| equals that unit normal.
2. Signed distances of plane, circle and sphere at points with known answers
   (including |ψ| = distance for a non-unit normal).
3. union / intersection / complement: the Ω⁻ they describe is the union,
   intersection and complement of the Ω⁻ of their arguments.
4. nodal_values on a box mesh of every cell type: one value per vertex,
   equal to ψ at the vertex coordinates.
5. Bad input is refused with a ValueError whose message says what is wrong.
"""
import numpy as np
import pytest

from skxfem.levelset import (
    LevelSet,
    circle,
    complement,
    intersection,
    nodal_values,
    plane,
    sphere,
    union,
)
from skxfem.meshes import box

CELLS = ["tri", "quad", "tet", "hex", "prism"]


def dim_of(cell):
    return 2 if cell in ("tri", "quad") else 3


# 1. sign convention -------------------------------------------------------------

@pytest.mark.parametrize("dim", [2, 3])
def test_plane_normal_points_into_omega_plus(dim):
    """Stepping from a point of Γ along the given normal enters Ω⁺ (ψ > 0)."""
    rng = np.random.default_rng(0)
    for _ in range(5):
        x0 = rng.uniform(-1, 1, dim)
        normal = rng.standard_normal(dim)
        psi = plane(x0, normal)
        step = 0.1 * normal / np.linalg.norm(normal)
        assert abs(psi(x0)) < 1e-14, "the plane's point must lie on Γ (ψ = 0)"
        assert psi(x0 + step) > 0, "moving along the normal must enter Ω⁺ = {ψ > 0}"
        assert psi(x0 - step) < 0, "moving against the normal must enter Ω⁻ = {ψ < 0}"


@pytest.mark.parametrize("dim", [2, 3])
def test_plane_gradient_is_the_unit_normal(dim):
    """n = ∇ψ/|∇ψ| (finite differences) is the unit normal given to plane()."""
    rng = np.random.default_rng(1)
    normal = 3.0 * rng.standard_normal(dim)
    psi = plane(rng.uniform(size=dim), normal)
    x = rng.uniform(size=dim)
    h = 1e-6
    grad = np.array([(psi(x + h * e) - psi(x - h * e)) / (2 * h) for e in np.eye(dim)])
    assert np.allclose(grad, normal / np.linalg.norm(normal), atol=1e-8), (
        "a plane's ψ must be the signed distance: its gradient is the unit normal")


def test_docstring_example_below_and_above():
    psi = plane(point=(0.0, 0.5), normal=(0.0, 1.0))
    values = psi(np.array([[0.2, 0.2], [0.0, 1.0]]))
    assert np.allclose(values, [-0.5, 0.5]), "(0.2, 0) is 0.5 below y = 0.5, (0.2, 1) above"


# 2. signed distances -------------------------------------------------------------

def test_plane_signed_distance_values():
    # the normal (0, 0, 2) is not a unit vector: ψ must still be a distance
    psi = plane((0, 0, 0.5), (0, 0, 2))
    pts = np.array([[0.1, 0.2, 1.0], [5.0, -3.0, 0.25], [0.0, 0.0, 0.5]]).T
    assert np.allclose(psi(pts), [0.5, -0.25, 0.0]), (
        "plane ψ must be (x - point)·n/|n|: the signed distance, whatever |normal|")
    # an oblique 2D line x + y = 1, normal (1, 1): distance of the origin is 1/√2
    psi = plane((1, 0), (1, 1))
    assert abs(psi(np.array([0.0, 0.0])) + 1 / np.sqrt(2)) < 1e-14
    assert abs(psi(np.array([1.0, 1.0])) - 1 / np.sqrt(2)) < 1e-14


def test_circle_signed_distance_values():
    psi = circle((1.0, 2.0), 0.5)
    pts = np.array([[1.0, 2.0], [1.0, 2.5], [4.0, 6.0], [1.3, 2.0]]).T
    # centre: -r; on the circle: 0; (4, 6) is 5 from the centre; (1.3, 2) is 0.3
    assert np.allclose(psi(pts), [-0.5, 0.0, 4.5, -0.2], atol=1e-14), (
        "circle ψ must be |x - c| - r: negative (Ω⁻) inside the disc")


def test_sphere_signed_distance_values():
    psi = sphere((0.0, 0.0, 1.0), 2.0)
    pts = np.array([[0, 0, 1], [2, 0, 1], [0, 3, 5], [0, 0, 0]], float).T
    assert np.allclose(psi(pts), [-2.0, 0.0, 3.0, -1.0], atol=1e-14), (
        "sphere ψ must be |x - c| - r: negative (Ω⁻) inside the ball")


def test_level_sets_keep_the_point_layout():
    """ψ of an array of shape (dim, a, b) has shape (a, b) (scikit-fem layout)."""
    x = np.random.default_rng(2).uniform(size=(3, 4, 5))
    for psi in (plane((0, 0, 0), (1, 2, 3)), sphere((0, 0, 0), 1.0)):
        v = psi(x)
        assert v.shape == (4, 5), f"{psi.name}: expected shape (4, 5), got {v.shape}"
        # and each entry is ψ of that one point
        assert abs(v[2, 3] - psi(x[:, 2, 3])) < 1e-15


# 3. combinations ------------------------------------------------------------------

def test_union_intersection_complement_semantics():
    """Membership of Ω⁻ follows set algebra, on a cloud of random points."""
    a = circle((0.0, 0.0), 1.0)
    b = circle((1.0, 0.0), 1.0)
    x = np.random.default_rng(3).uniform(-1.5, 2.5, (2, 2000))
    in_a, in_b = a(x) < 0, b(x) < 0
    assert in_a.any() and in_b.any() and (in_a & in_b).any() and (~in_a & in_b).any()
    assert np.array_equal(union(a, b)(x) < 0, in_a | in_b), "union: Ω⁻ = Ω⁻(a) ∪ Ω⁻(b)"
    assert np.array_equal(intersection(a, b)(x) < 0, in_a & in_b), (
        "intersection: Ω⁻ = Ω⁻(a) ∩ Ω⁻(b)")
    assert np.array_equal(complement(a)(x) < 0, a(x) > 0), "complement swaps Ω⁻ and Ω⁺"
    assert np.allclose(complement(a)(x), -a(x)), "complement is ψ → -ψ exactly"


def test_combinations_values_and_normal_flip():
    # two half planes y < 0.5 and x < 0.5: ψ values are min/max of the two
    a = plane((0, 0.5), (0, 1))
    b = plane((0.5, 0), (1, 0))
    x = np.array([[0.0, 0.0], [1.0, 0.25], [0.25, 2.0], [2.0, 3.0]]).T
    assert np.allclose(union(a, b)(x), [-0.5, -0.25, -0.25, 1.5])
    assert np.allclose(intersection(a, b)(x), [-0.5, 0.5, 1.5, 2.5])
    # the complement of a plane is the plane with the opposite normal
    assert np.allclose(complement(a)(x), plane((0, 0.5), (0, -1))(x))
    assert complement(a).dim == 2 and union(a, b).dim == 2


def test_cannot_combine_2d_and_3d():
    with pytest.raises(ValueError, match="2D and a 3D"):
        union(circle((0, 0), 1.0), sphere((0, 0, 0), 1.0))
    with pytest.raises(ValueError, match="3D and a 2D"):
        intersection(sphere((0, 0, 0), 1.0), circle((0, 0), 1.0))


# 4. nodal values ------------------------------------------------------------------

@pytest.mark.parametrize("cell", CELLS)
def test_nodal_values_on_every_cell_type(cell):
    dim = dim_of(cell)
    mesh = box(3, cell)
    normal = np.arange(1.0, dim + 1)
    x0 = np.full(dim, 0.45)
    values = nodal_values(plane(x0, normal), mesh)
    assert values.shape == (mesh.nvertices,), "one value per mesh vertex"
    expected = (mesh.p - x0[:, None]).T @ (normal / np.linalg.norm(normal))
    assert np.allclose(values, expected, atol=1e-14), "ψ at vertex i is ψ(mesh.p[:, i])"
    ball = circle(x0, 0.3) if dim == 2 else sphere(x0, 0.3)
    values = nodal_values(ball, mesh)
    assert np.allclose(values, np.linalg.norm(mesh.p - x0[:, None], axis=0) - 0.3)
    assert (values < 0).any() and (values > 0).any()


def test_nodal_values_accepts_a_plain_callable():
    mesh = box(2, "quad")
    values = nodal_values(lambda x: x[0] - 2 * x[1], mesh)
    assert np.allclose(values, mesh.p[0] - 2 * mesh.p[1])


# 5. bad input ----------------------------------------------------------------------

def test_2d_level_set_on_3d_mesh_is_refused():
    with pytest.raises(ValueError, match="2D level set but the mesh is 3D"):
        nodal_values(circle((0.5, 0.5), 0.3), box(2, "hex"))
    with pytest.raises(ValueError, match="3D level set but the mesh is 2D"):
        nodal_values(sphere((0.5, 0.5, 0.5), 0.3), box(2, "tri"))
    # calling a level set on points of the wrong dimension is refused too
    with pytest.raises(ValueError, match="2D but got points with 3 coordinates"):
        circle((0, 0), 1.0)(np.zeros((3, 4)))


def test_nan_or_inf_from_psi_is_refused():
    mesh = box(2, "tri")
    with pytest.raises(ValueError, match="NaN or inf"):
        nodal_values(lambda x: np.where(x[0] < 0.1, -np.inf, x[0]), mesh)
    nan_at_one = LevelSet(lambda x: np.where(x[0] > 0.9, np.nan, x[0]), 2, "bad")
    with pytest.raises(ValueError, match="NaN or inf"):
        nodal_values(nan_at_one, mesh)


def test_wrong_shape_from_psi_is_refused():
    mesh = box(2, "quad")
    with pytest.raises(ValueError, match=r"expected shape \(9,\)"):
        nodal_values(lambda x: x, mesh)                     # (2, 9)
    with pytest.raises(ValueError, match="one value per point"):
        nodal_values(lambda x: x[0][:3], mesh)              # too few
    with pytest.raises(ValueError, match="one value per point"):
        nodal_values(lambda x: 1.0, mesh)                   # a scalar


def test_bad_plane_and_ball_parameters_are_refused():
    with pytest.raises(ValueError, match="normal must be non-zero"):
        plane((0, 0), (0, 0))
    with pytest.raises(ValueError, match="same dimension"):
        plane((0, 0), (0, 0, 1))
    with pytest.raises(ValueError, match="point must be finite"):
        plane((0, np.nan), (0, 1))
    with pytest.raises(ValueError, match="point must be finite"):
        plane((0, np.inf, 0), (0, 0, 1))
    with pytest.raises(ValueError, match="normal must be finite"):
        plane((0, 0), (np.inf, 1))
    with pytest.raises(ValueError, match="2- or 3-vector"):
        plane((0,), (1,))
    with pytest.raises(ValueError, match="radius must be a positive number"):
        circle((0, 0), -1.0)
    with pytest.raises(ValueError, match="radius must be a positive number"):
        sphere((0, 0, 0), 0.0)
    with pytest.raises(ValueError, match="radius must be a positive number"):
        circle((0, 0), np.nan)
    with pytest.raises(ValueError, match="center must have 2 coordinates"):
        circle((0, 0, 0), 1.0)
    with pytest.raises(ValueError, match="center must have 3 coordinates"):
        sphere((0, 0), 1.0)
    with pytest.raises(ValueError, match="center must be finite"):
        sphere((0, np.nan, 0), 1.0)
