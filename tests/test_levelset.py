"""Tests for skxfem/levelset.py: the sign convention and the level set helpers.

1. Sign convention: Ω⁻ = {ψ < 0}; the normal given to :func:`plane` points
   into Ω⁺ (ψ grows along it), and ∇ψ/|∇ψ| equals that unit normal.
2. Signed distances of plane, circle and sphere at points with known answers
   (including |ψ| = distance for a non-unit normal).
3. union / intersection / complement: the Ω⁻ they describe is the union,
   intersection and complement of the Ω⁻ of their arguments.
4. nodal_values on a box mesh of every cell type: one value per vertex,
   equal to ψ at the vertex coordinates.
5. Bad input is refused with a ValueError (a TypeError for the wrong kind of
   argument) whose message names the argument and says what is wrong: at
   construction, and for what ψ and its gradient return when evaluated.
6. Gradients: analytic ones (plane, circle, sphere, union, intersection,
   complement) against finite differences and known values; central
   differences for a formula, at any scale; point_normals exact for planes
   and balls, the facet-normal fallback for nodal values (O(h) on a circle).
"""
import numpy as np
import pytest

from skxfem.fem.meshes import box
from skxfem.levelset import (
    LevelSet,
    circle,
    complement,
    gradient,
    intersection,
    nodal_values,
    plane,
    sphere,
    union,
)


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


def test_level_set_constructor_checks_its_arguments():
    """A bad fun, dim or grad is refused when the LevelSet is built, not at solve time."""
    with pytest.raises(TypeError, match="fun must be a callable"):
        LevelSet(5, 2)
    for dim in ("2", True, 2.0, None):
        with pytest.raises(TypeError, match="dim must be the int 2 or 3"):
            LevelSet(lambda x: x[1], dim)
    with pytest.raises(ValueError, match="dim must be the int 2 or 3.*got 4"):
        LevelSet(lambda x: x[1], 4)
    with pytest.raises(TypeError, match="grad must be None or callable"):
        LevelSet(lambda x: x[1], 2, grad=np.ones(2))
    psi = LevelSet(lambda x: x[2], np.int64(3))  # a numpy integer is an int
    assert psi.dim == 3 and type(psi.dim) is int


def test_a_gradient_of_the_wrong_shape_or_not_finite_is_refused():
    """grad must return ∇ψ shaped like x: never broadcast along the wrong axis."""
    x = np.random.default_rng(4).uniform(size=(2, 3))
    bad = LevelSet(lambda x: x[1] - 0.5, 2, "flat", grad=lambda x: np.ones(3))
    with pytest.raises(ValueError, match=r"grad of level set 'flat'.*expected shape \(2, 3\)"):
        bad.gradient(x)  # (3,) would broadcast to (2, 3): every point's ∇ψ = (1, 1)
    per_axis = LevelSet(lambda x: x[1] - 0.5, 2, "flat", grad=lambda x: np.array([0.0, 1.0]))
    with pytest.raises(ValueError, match=r"expected shape \(2, 2\).*shape \(2,\)"):
        per_axis.gradient(x[:, :2])
    with pytest.raises(ValueError, match="grad of level set 'flat'.*real numbers"):
        LevelSet(lambda x: x[1], 2, "flat", grad=lambda x: x + 1j).gradient(x)
    with pytest.raises(ValueError, match="grad of level set 'nan'.*NaN or inf"):
        LevelSet(lambda x: x[1], 2, "nan", grad=lambda x: np.full_like(x, np.nan)).gradient(x)
    with pytest.raises(ValueError, match="grad of level set 'flat'"):
        complement(bad).gradient(x)  # combinations check through to their pieces


def test_what_psi_returns_is_checked_where_it_is_evaluated():
    """Complex, text, ragged or wrongly shaped ψ values: a ValueError naming the level set."""
    mesh = box(2, "tri")
    with pytest.raises(ValueError, match="level set 'wavy' must return real numbers.*complex"):
        nodal_values(LevelSet(lambda x: x[1] - 0.5 + 0.1j, 2, "wavy"), mesh)
    with pytest.raises(ValueError, match="psi must return real numbers.*complex"):
        nodal_values(lambda x: x[1] + 0j, mesh)
    with pytest.raises(ValueError, match="level set 'text' must return real numbers.*<U"):
        nodal_values(LevelSet(lambda x: "x - 0.5", 2, "text"), mesh)
    with pytest.raises(ValueError, match="level set 'ragged' must return real numbers"):
        LevelSet(lambda x: [[0.0, 1.0], [2.0]], 2, "ragged")(np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"'whole'.*one value per point.*shape \(5,\)"):
        LevelSet(lambda x: x, 2, "whole")(np.zeros((2, 5)))  # (2, 5) values for 5 points
    with pytest.raises(ValueError, match="psi must return real numbers.*<U"):
        gradient(lambda x: [str(v) for v in x[0]], np.ones((2, 3)))
    # a list of numbers is fine: converted, then combined and differenced like an array
    listy = LevelSet(lambda x: list(x[1] - 0.5), 2, "listy")
    assert np.allclose(nodal_values(listy, mesh), mesh.p[1] - 0.5)
    assert np.allclose(complement(listy)(mesh.p), 0.5 - mesh.p[1])
    assert np.allclose(listy.gradient(np.ones((2, 3))), [[0.0] * 3, [1.0] * 3])


@pytest.mark.parametrize("radius", ["0.3", None, np.array([0.3, 0.2]), True, 1j])
def test_a_radius_that_is_not_a_real_number_is_refused(radius):
    with pytest.raises(TypeError, match="circle radius must be a real number"):
        circle((0.5, 0.5), radius)
    with pytest.raises(TypeError, match="sphere radius must be a real number"):
        sphere((0.5, 0.5, 0.5), radius)


def test_a_numpy_scalar_radius_is_accepted():
    assert np.isclose(circle((0, 0), np.float32(0.5))(np.array([1.0, 0.0])), 0.5)
    assert sphere((0, 0, 0), np.int64(2))(np.array([0.0, 0.0, 3.0])) == 1.0


def test_points_normals_and_centres_must_be_real_numbers():
    with pytest.raises(TypeError, match="point must be a sequence of 2 or 3 real numbers"):
        plane(("a", "b"), (0, 1))
    with pytest.raises(TypeError, match="normal must be a sequence of 2 or 3 real numbers"):
        plane((0, 1), None)
    with pytest.raises(TypeError, match="center must be a sequence of 2 or 3 real numbers"):
        circle(((0, 1), 0), 1.0)  # ragged
    with pytest.raises(TypeError, match="center must be a sequence of 2 or 3 real numbers"):
        sphere((1j, 0, 0), 1.0)


def test_combinators_refuse_what_is_not_a_level_set():
    c = circle((0, 0), 1.0)
    with pytest.raises(TypeError, match="union: b must be a LevelSet.*got int 5"):
        union(c, 5)
    with pytest.raises(TypeError, match="intersection: a must be a LevelSet.*got str"):
        intersection("x < 0", c)
    with pytest.raises(TypeError, match=r"complement: a must be a LevelSet.*LevelSet\(fun, dim\)"):
        complement(lambda x: x[0])

# 6. gradients and the normal at the multiplier points ---------------------------------

def central(psi, x, h=1e-6):
    """An independent central difference, one point at a time."""
    return np.array([(psi(x + h * e) - psi(x - h * e)) / (2 * h) for e in np.eye(x.size)])


def shapes():
    """(level set, points away from its kinks and centres) for each analytic gradient."""
    a, b = circle((0.0, 0.0), 1.0), circle((1.0, 0.0), 1.0)
    pts2 = np.array([[0.3, -0.4, 1.7, 0.9, 0.2], [0.8, 0.3, -0.6, 1.1, -1.3]])
    pts3 = np.array([[0.3, -0.4, 1.7], [0.8, 0.3, -0.6], [0.1, -0.9, 0.5]])
    return [(plane((0.1, 0.2), (1.0, -2.0)), pts2), (plane((0, 0, 0.5), (1, 2, 3)), pts3),
            (circle((0.1, -0.2), 0.7), pts2), (sphere((0.1, 0.0, -0.2), 0.7), pts3),
            (union(a, b), pts2), (intersection(a, b), pts2), (complement(a), pts2),
            (complement(union(a, plane((0, 0.5), (0, 1)))), pts2)]


@pytest.mark.parametrize("k", range(8))
def test_analytic_gradients_match_finite_differences(k):
    psi, pts = shapes()[k]
    assert psi.grad is not None, f"{psi.name} should carry an analytic gradient"
    g = psi.gradient(pts)
    assert g.shape == pts.shape
    for j in range(pts.shape[1]):
        assert np.allclose(g[:, j], central(psi, pts[:, j]), atol=1e-8), \
            f"∇ψ of {psi.name} at {pts[:, j]}: {g[:, j]} vs differences {central(psi, pts[:, j])}"
    assert np.allclose(np.linalg.norm(g, axis=0), 1.0), "a signed distance has |∇ψ| = 1"


def test_gradients_with_known_values():
    theta = np.linspace(0, 2 * np.pi, 7)
    on = np.array([2 + 0.5 * np.cos(theta), -1 + 0.5 * np.sin(theta)])
    assert np.allclose(circle((2, -1), 0.5).gradient(on), [np.cos(theta), np.sin(theta)],
                       atol=1e-15), "the circle's gradient is the outward radial unit vector"
    n = np.array([3.0, 4.0])
    g = plane((1, 1), n).gradient(np.zeros((2, 4, 5)))
    assert g.shape == (2, 4, 5) and np.all(g == (n / 5)[:, None, None]), \
        "the plane's gradient is its unit normal at every point, in the points' layout"
    a, b = circle((0.0, 0.0), 1.0), circle((1.0, 0.0), 1.0)
    x = np.array([[0.2], [0.0]])  # closer to a's centre: ψ_a = -0.8 < ψ_b = -0.2
    assert np.allclose(union(a, b).gradient(x), a.gradient(x)), "union: the smaller ψ's ∇"
    assert np.allclose(intersection(a, b).gradient(x), b.gradient(x)), \
        "intersection: the larger ψ's ∇"
    assert np.allclose(complement(a).gradient(x), -a.gradient(x)), "complement negates ∇ψ"
    assert np.all(sphere((0, 0, 0), 1.0).gradient(np.zeros(3)) == 0), "0 at the centre"


@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e3])
def test_a_level_set_without_gradient_gets_central_differences(scale):
    """A scene-file formula has no analytic gradient: the difference step is
    ε^(1/3) max|x|, so the error stays near ε^(2/3) whatever the units (8e-11
    measured at each scale)."""
    from skxfem.levelset import gradient
    from skxfem.scene.expr import Expression

    c, r = 0.5 * scale, 0.3 * scale
    formula = LevelSet(Expression(f"((x - {c})**2 + (y - {c})**2)**0.5 - {r}", 2), 2, "formula")
    assert formula.grad is None
    theta = np.linspace(0.1, 6.0, 9)
    x = np.array([c + 0.8 * r * np.cos(theta), c + 1.3 * r * np.sin(theta)])
    exact = (x - c) / np.linalg.norm(x - c, axis=0)  # the signed distance's gradient
    for g in (formula.gradient(x), gradient(formula.fun, x)):
        assert np.abs(g - exact).max() < 1e-9, \
            f"central differences at scale {scale}: error {np.abs(g - exact).max():.1e}"


def test_point_normals_are_exact_for_planes_and_balls(cell):
    from skxfem.cut import cut
    from skxfem.levelset import point_normals

    dim = dim_of(cell)
    mesh = box(4, cell)
    normal = np.arange(1.0, dim + 1) * (-1) ** np.arange(dim)
    tilted = plane(np.full(dim, 0.47), normal)
    n = point_normals(cut(mesh, tilted), tilted)
    assert np.abs(n - (normal / np.linalg.norm(normal))[:, None]).max() < 1e-15
    x0 = np.full(dim, 0.48)
    ball = circle(x0, 0.31) if dim == 2 else sphere(x0, 0.31)
    c = cut(mesh, ball)
    d = c.points - x0[:, None]
    assert np.abs(point_normals(c, ball) - d / np.linalg.norm(d, axis=0)).max() < 1e-15, \
        "the normal at a point is the radial direction through it"
    # ψ known only at the nodes: the facets' mean normal, still exact for a plane
    c = cut(mesh, nodal_values(tilted, mesh))
    n = point_normals(c, c.psi)
    assert np.abs(n - (normal / np.linalg.norm(normal))[:, None]).max() < 1e-12


def test_nodal_values_fall_back_to_the_area_weighted_facet_normals():
    """The fallback is Σ |F| n_F over the facets F at the point, normalised:
    checked against a loop; on a circle it is O(h) from the radial direction,
    worst at the end points (where Γ leaves the mesh only one facet is there)."""
    from skxfem.cut import cut
    from skxfem.levelset import point_normals

    ball = circle((-0.2, -0.3), 0.9137)  # Γ leaves the unit square on two sides
    errors = []
    for n_cells in (8, 16, 32):
        mesh = box(n_cells, "tri")
        c = cut(mesh, nodal_values(ball, mesh))
        ref = np.zeros_like(c.points)
        for f in range(c.facets.shape[1]):
            for v in c.facets[:, f]:
                ref[:, v] += c.measures[f] * c.normals[:, f]
        ref /= np.linalg.norm(ref, axis=0)
        n = point_normals(c)
        assert np.abs(n - ref).max() < 1e-14
        assert np.array_equal(n, point_normals(c, c.psi)), "nodal values: the same fallback"
        d = c.points - np.array([[-0.2], [-0.3]])
        errors.append(np.abs(n - d / np.linalg.norm(d, axis=0)).max())
    h = 1 / np.array([8, 16, 32])
    assert np.all(np.array(errors) < h) and errors[-1] < errors[0] / 2, \
        f"the facet normals are O(h) from the exact ones: errors {errors}"
    exact = point_normals(c, ball)
    assert np.abs(exact - d / np.linalg.norm(d, axis=0)).max() < 1e-15


def test_a_vanishing_gradient_on_gamma_is_refused():
    from skxfem.cut import cut
    from skxfem.levelset import point_normals

    flat = LevelSet(lambda x: x[1] - 0.43, 2, "flat", grad=lambda x: np.zeros_like(x))
    with pytest.raises(ValueError, match="∇ψ vanishes.*no normal"):
        point_normals(cut(box(2, "quad"), flat), flat)
    with pytest.raises(ValueError, match="2D but got points with 3"):
        circle((0, 0), 1.0).gradient(np.zeros((3, 2)))


def test_a_gradient_that_is_not_finite_on_gamma_is_named_so():
    """NaN in ∇ψ at interface points is said to be NaN, not that ∇ψ vanishes."""
    from skfem import MeshTri1

    from skxfem.cut import cut
    from skxfem.levelset import point_normals
    c = cut(MeshTri1().refined(2), plane((0.0, 0.45), (0.0, 1.0)))
    with pytest.raises(ValueError, match="∇ψ is NaN or inf at interface points"):
        point_normals(c, lambda x: np.where(x[0] > 0.6, np.nan, x[1] - 0.45))
    with pytest.raises(ValueError, match="∇ψ vanishes at interface points"):
        point_normals(c, lambda x: 0.0 * x[0])


@pytest.mark.parametrize("scale", [1e200, 1e-200, 1e-320, 1e300])
def test_only_the_direction_of_a_planes_normal_counts_at_any_size(scale):
    """Issue 18: normal = (1e200, 1e200) overflowed |normal| to inf, n̂ to 0 and
    ψ to 0 everywhere, silently; a tiny normal underflowed the same way."""
    x = np.random.default_rng(3).uniform(size=(2, 20))
    ref = plane((0.3, 0.4), (1.0, 2.0))
    big = plane((0.3, 0.4), (scale, 2 * scale))
    assert np.allclose(big(x), ref(x), rtol=0, atol=1e-15)
    assert np.allclose(big.gradient(x), ref.gradient(x), rtol=0, atol=1e-15)
    with pytest.raises(ValueError, match="normal must be non-zero"):
        plane((0.3, 0.4, 0.5), (0.0, -0.0, 0.0))
