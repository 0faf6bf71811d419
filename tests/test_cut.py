"""Tests for skxfem/cut.py: volumes sum exactly, interface areas are exact, facet
normals follow ∇ψ."""
import itertools

import numpy as np
import pytest
from skfem import Basis, MeshLine1, MeshTri2

from skxfem.cut import cut
from skxfem.fem.meshes import box
from skxfem.fem.quadrature import cell_rule, subcell_rule
from skxfem.levelset import circle, plane, sphere


def dim_of(cell):
    return 2 if cell in ("tri", "quad") else 3


def mesh_of(cell, n=4):
    return box(n, cell)


def random_levelsets(dim, rng, k=4):
    out = []
    for _ in range(k):
        out.append(plane(rng.uniform(0.3, 0.7, dim), rng.standard_normal(dim)))
    c = rng.uniform(0.4, 0.6, dim)
    out.append(circle(c, 0.33) if dim == 2 else sphere(c, 0.33))
    return out


def test_subcell_volumes_sum_to_cell_volume(cell):
    """Each cut cell's sub-cells (both sides) add up to the cell, to 1e-12."""
    rng = np.random.default_rng(0)
    m = mesh_of(cell)
    full = Basis(m, m.elem(), quadrature=cell_rule(m, 2)).dx.sum(axis=1)
    for psi in random_levelsets(m.dim(), rng):
        c = cut(m, psi)
        rule = subcell_rule(c.sub_ref, c.sub_cell, 2, values=c.sub_side)
        b = Basis(m, m.elem(), elements=rule.cells, quadrature=(rule.X, rule.W))
        assert np.array_equal(rule.cells, c.cells)
        assert np.abs(b.dx.sum(axis=1) - full[c.cells]).max() < 1e-12
        # every sub-simplex lies on one side: the sides split the volume
        minus = (b.dx * (rule.V < 0)).sum()
        plus = (b.dx * (rule.V > 0)).sum()
        assert minus > 0 and plus > 0
        assert abs(minus + plus - full[c.cells].sum()) < 1e-12


def exact_cube_section_area(n, t):
    """Area of {x in [0,1]^3 : n·x = t}, n a unit vector with no zero entry.

    Independent of the cut algorithm: the volume of the cube below the plane is
    Σ_v (-1)^|v| max(t - n·v, 0)^3 / (6 n1 n2 n3) over the cube vertices v
    (after reflecting so that n > 0), and the area is its derivative in t.
    """
    n = np.asarray(n, float)
    flip = n < 0
    t = t - np.sum(n[flip])  # reflect x_i -> 1 - x_i where n_i < 0
    n = np.abs(n)
    area = 0.0
    for v in itertools.product((0, 1), repeat=3):
        area += (-1) ** sum(v) * max(t - n @ np.array(v), 0.0) ** 2
    return area / (2 * np.prod(n))


@pytest.mark.parametrize("cell", ["tet", "hex", "prism"])
def test_plane_section_area_is_exact(cell):
    rng = np.random.default_rng(1)
    m = mesh_of(cell, 3)
    for _ in range(5):
        n = rng.standard_normal(3)
        n /= np.linalg.norm(n)
        x0 = rng.uniform(0.35, 0.65, 3)
        c = cut(m, plane(x0, n))
        assert abs(c.measures.sum() - exact_cube_section_area(n, n @ x0)) < 1e-12
        # normals all equal n (pointing into Ω⁺)
        assert np.abs(c.normals - n[:, None]).max() < 1e-12


@pytest.mark.parametrize("cell", ["tri", "quad"])
def test_line_section_length_2d(cell):
    m = mesh_of(cell, 5)
    theta = 0.3
    n = np.array([np.sin(theta), np.cos(theta)])
    c = cut(m, plane((0.5, 0.5), n))
    # the line through the centre at angle θ from horizontal crosses x = 0 and x = 1
    assert abs(c.measures.sum() - 1 / np.cos(theta)) < 1e-12
    assert np.abs(c.normals - n[:, None]).max() < 1e-12


def test_cut_edges_and_points(cell):
    """S_e: strictly cut edges; the points lie on Γ and on their edges."""
    m = mesh_of(cell, 3)
    d = m.dim()
    n = np.ones(d) / np.sqrt(d)
    psi = plane(np.full(d, 0.52), n)
    c = cut(m, psi)
    v = psi(m.p)
    assert np.all(v[c.edges[0]] * v[c.edges[1]] < 0)
    assert np.abs(psi(c.points)).max() < 1e-14
    # every enriched node belongs to a cut cell, every cut cell has a cut edge
    assert set(np.unique(m.t[:, c.cells])) == set(c.enriched)
    assert np.all(c.side[c.cells] == 0)
    uncut = c.side != 0
    assert np.all(np.sign(v[m.t[:, uncut]]) == c.side[uncut])


def test_facet_normals_follow_the_level_set_gradient(cell):
    """The facets' normals obey the one convention n = ∇ψ/|∇ψ| (into Ω⁺): equal
    to it for a plane; for a circle or sphere on the side ∇ψ points to at every
    facet.  (At the multiplier points themselves the solver uses ∇ψ:
    :func:`skxfem.levelset.point_normals`.)"""
    dim = dim_of(cell)
    normal = np.linspace(-1.0, 1.0, dim) + np.eye(dim)[-1]
    psi = plane(np.full(dim, 0.47), normal)
    c = cut(mesh_of(cell), psi)
    assert np.abs(c.normals - psi.gradient(c.points[:, :1])).max() < 1e-14
    x0 = np.full(dim, 0.48)
    ball = circle(x0, 0.33) if dim == 2 else sphere(x0, 0.33)
    c = cut(mesh_of(cell, 6), ball)
    centroid = c.points[:, c.facets].mean(axis=1)
    assert np.all((c.normals * ball.gradient(centroid)).sum(0) > 0.5), \
        "every facet normal points out of the ball, into Ω⁺, as ∇ψ does"


def test_sphere_volume_converges():
    """Ω⁻ of a sphere: the discrete volume tends to 4/3 π r³ at second order."""
    r, errs = 0.3, []
    for n in (6, 12):
        m = mesh_of("hex", n)
        c = cut(m, sphere((0.5, 0.5, 0.5), r))
        rule = subcell_rule(c.sub_ref, c.sub_cell, 2, values=c.sub_side)
        b = Basis(m, m.elem(), elements=rule.cells, quadrature=(rule.X, rule.W))
        full = Basis(m, m.elem(), quadrature=cell_rule(m, 2)).dx.sum(axis=1)
        vol = (b.dx * (rule.V < 0)).sum() + full[c.side < 0].sum()
        errs.append(abs(vol - 4 / 3 * np.pi * r ** 3))
    assert errs[1] < errs[0] / 3  # rate close to 2


def test_errors_are_clear():
    m = mesh_of("quad", 4)
    with pytest.raises(ValueError, match="cuts no cell"):
        cut(m, plane((0, 5.0), (0, 1)))
    with pytest.raises(ValueError, match="inside a single cell .* refine the mesh"):
        cut(m, circle((0.6, 0.6), 0.05))  # a circle inside one cell of h = 1/4
    with pytest.raises(ValueError, match="zero on a region, not on a surface"):
        cut(m, lambda x: np.maximum(x[1] - 0.5, 0.0))  # ψ ≡ 0 on the lower half
    with pytest.raises(ValueError, match="2D level set but the mesh is 3D|is 2D"):
        cut(mesh_of("hex", 3), circle((0.5, 0.5), 0.3))
    with pytest.raises(ValueError, match="NaN"):
        cut(m, lambda x: np.full(x.shape[1], np.nan))
    with pytest.raises(TypeError, match="mesh must be one of"):
        cut(MeshTri2(), lambda x: x[0] - 0.3)
    with pytest.raises(TypeError, match="mesh must be one of"):
        cut(MeshLine1(), lambda x: x[0] - 0.3)
    # a saddle: the four edges of a quad are cut, the cut is ambiguous
    with pytest.raises(ValueError, match="more than one piece"):
        cut(mesh_of("quad", 1), lambda x: (x[0] - 0.5) * (x[1] - 0.5))


def side_volumes(m, c):
    """(|Ω⁻_h|, |Ω⁺_h|): the uncut cells of each side and the sub-cells of the cut ones."""
    full = Basis(m, m.elem(), quadrature=cell_rule(m, 2)).dx.sum(axis=1)
    vol = [full[c.side == s].sum() for s in (-1, 1)]
    if c.sub_ref.size:
        rule = subcell_rule(c.sub_ref, c.sub_cell, 2, values=c.sub_side)
        b = Basis(m, m.elem(), elements=rule.cells, quadrature=(rule.X, rule.W))
        vol = [vol[0] + (b.dx * (rule.V < 0)).sum(), vol[1] + (b.dx * (rule.V > 0)).sum()]
    return vol


@pytest.mark.parametrize("cell", ["tri", "quad", "tet", "hex", "prism"])
def test_a_level_set_through_nodes_is_cut_exactly(cell):
    """Γ through mesh nodes stays there (ψ = 0, no warning).  Along a row of mesh
    facets (z = 1/2, z = 1/4): no cell is cut, the points are the row's vertices
    (edge id -1, edge (v, v)), the facets of Γ_h the mesh facets, area 1; across
    the diagonals (x + z = 1: through nodes, cutting cells through them): the two
    sides' volumes are exact, 1/2 each, to 1e-14, with no zero-measure sub-cell."""
    import warnings

    m = mesh_of(cell, 4)
    dim = m.dim()
    up = np.eye(dim)[-1]
    for height in (0.5, 0.25):
        row = np.isclose(m.p[-1], height)
        with warnings.catch_warnings():
            warnings.simplefilter("error")                 # no SnapWarning
            c = cut(m, plane((0.5,) * (dim - 1) + (height,), up))
        assert np.array_equal(c.psi[row], np.zeros(row.sum()))
        assert c.cells.size == 0 and c.sub_ref.shape[0] == 0
        assert np.array_equal(np.sort(c.edges[0]), np.flatnonzero(row))
        assert np.array_equal(c.edges[0], c.edges[1]) and np.all(c.edge_ids == -1)
        assert np.array_equal(c.points, m.p[:, c.edges[0]])
        assert np.array_equal(np.sort(c.enriched), np.flatnonzero(row))
        assert abs(c.measures.sum() - 1.0) < 1e-14
        assert np.abs(c.normals - up[:, None]).max() < 1e-15
        minus, plus = side_volumes(m, c)
        assert abs(minus - height) < 1e-14 and abs(plus - (1 - height)) < 1e-14
        assert np.array_equal(c.node_side, np.where(m.p[-1] < height, -1, 1))
    n = np.r_[1.0, np.zeros(dim - 2), 1.0] / np.sqrt(2)
    c = cut(m, plane((0.5,) * dim, n))
    assert np.sum(c.psi == 0) == (5 if dim == 2 else 25)
    assert np.all(c.edge_ids[c.edges[0] == c.edges[1]] == -1)
    minus, plus = side_volumes(m, c)
    assert abs(minus - 0.5) < 1e-14 and abs(plus - 0.5) < 1e-14
    assert abs(c.measures.sum() - np.sqrt(2)) < 1e-14
    assert np.abs(c.normals - n[:, None]).max() < 1e-15
    size = np.abs(np.linalg.det(c.sub_ref[:, 1:] - c.sub_ref[:, :1]))
    assert size.min() > 1e-3                               # no zero-measure sub-cell


@pytest.mark.parametrize("cell", ["tri", "quad", "tet", "hex", "prism"])
def test_a_vertex_near_gamma_is_put_on_it_with_one_warning(cell):
    """Γ 1e-12 h from a row of nodes (within SNAP = 1e-9 h): those nodes are put on
    Γ (ψ = 0), one SnapWarning gives the count and the shift, and the cut is that of
    Γ through them; 1e-15 h (within ROUND_OFF = 1.4e-14 h) the same, silently."""
    import warnings

    from skxfem.cut import SnapWarning

    m = mesh_of(cell, 4)
    dim = m.dim()
    up = np.eye(dim)[-1]
    row = np.isclose(m.p[-1], 0.5)
    with pytest.warns(SnapWarning, match=rf"{row.sum()} mesh vertices \(not through them\): "
                      r"put them on it \(psi = 0\), so Γ moves by up to 2\.5e-13") as record:
        near = cut(m, plane((0.5,) * (dim - 1) + (0.5 + 2.5e-13,), up))
    assert sum(issubclass(w.category, SnapWarning) for w in record) == 1, "warned once"
    on = cut(m, plane((0.5,) * dim, up))
    assert np.array_equal(near.psi[row], np.zeros(row.sum()))
    assert np.array_equal(near.edge_ids, on.edge_ids)
    assert np.array_equal(near.points, on.points)
    with warnings.catch_warnings():                        # 1e-15 h: the round-off of ψ
        warnings.simplefilter("error")
        rounded = cut(m, plane((0.5,) * (dim - 1) + (0.5 + 2.5e-16,), up))
    assert np.array_equal(rounded.points, on.points)


def test_a_quad_cut_along_its_diagonal():
    """ψ = x - y on one quad: ψ = 0 at two corners, the cell is cut along its
    diagonal (no edge is strictly cut): two vertex points, one facet of length √2,
    two sides of area 1/2."""
    from skfem import MeshQuad1

    m = MeshQuad1()
    c = cut(m, lambda x: x[0] - x[1])
    assert c.cells.tolist() == [0] and np.all(c.edge_ids == -1)
    assert c.facets.shape == (2, 1) and abs(c.measures[0] - np.sqrt(2)) < 1e-15
    minus, plus = side_volumes(m, c)
    assert abs(minus - 0.5) < 1e-15 and abs(plus - 0.5) < 1e-15


def test_snapping_measures_distance_not_the_scale_of_psi():
    """ψ = 1e-13 (y - 0.5) puts Γ in the middle of cells: no node is near it, whatever
    the size of ψ (issue 18: it was refused as vanishing at 30 vertices)."""
    from skxfem.cut import snap

    m = mesh_of("quad", 5)
    psi = 1e-13 * (m.p[1] - 0.5)
    assert snap(m, psi)[1] == 0
    assert cut(m, lambda x: 1e-13 * (x[1] - 0.5)).edge_ids.size == 6


def test_a_tiny_level_set_cuts_the_same_edges():
    """ψ·1e-200: the product ψ(v1)ψ(v2) underflows to 0 (issue 18); the signs do not."""
    m = mesh_of("tri", 4)
    big = cut(m, plane((0, 0.4), (0.3, 1)))
    tiny = cut(m, lambda x: 1e-200 * (0.3 * x[0] + (x[1] - 0.4)) / np.hypot(0.3, 1))
    assert np.array_equal(big.edge_ids, tiny.edge_ids)
    assert np.allclose(big.points, tiny.points, atol=1e-14)
