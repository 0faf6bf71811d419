"""Tests for skxfem/multipliers.py: the naive space, the interface rule, M and B.

What is checked, on all five cell types, with a tilted plane Γ through the
unit square/cube (so that the normal is not a mesh direction):

1. The naive space: one multiplier per strictly cut edge, P = I.
2. The interface rule integrates exactly: Σ weights = |Γ|, a linear function
   gives |Γ| times its value at the centroid of Γ, and a polynomial of degree 4
   (the documented order) matches an independent tensor Gauss rule on Γ.
   The multiplier functions N are P1 on the facets: they sum to one and
   reproduce the coordinates of the quadrature points.
3. The interface mass M is symmetric positive definite, 1ᵀM1 = |Γ| and
   fᵀMf = ∫_Γ f² for a linear f sampled at the edge points.
4. The coupling B: for a field whose jump [[u]] = g is known (constant, or
   linear), B·U = ∫_Γ N_e g_c (bonded, component-major) and
   B·U = ∫_Γ N_e g·n (bilateral).
5. Unknown law or space names are refused with a ValueError naming the choices.
"""
import numpy as np
import pytest

from skxfem.cut import cut
from skxfem.enrich import xfem_space
from skxfem.fem.cells import cell_edges
from skxfem.fem.meshes import box
from skxfem.levelset import plane
from skxfem.multipliers import (
    LAWS,
    SPACES,
    coupling,
    fixed_jumps,
    interface_mass,
    interface_rule,
    naive,
    normal_fixed,
)
from skxfem.stabilised import multiplier_space

SLOPES = (0.1, 0.07)  # Γ: last coordinate = 0.5 + a (x - 0.5) [+ b (y - 0.5)]


def dim_of(cell):
    return 2 if cell in ("tri", "quad") else 3


def tilted(dim):
    """The tilted plane Γ through the centre and its exact length/area in the box.

    With slopes this small Γ leaves the box through its vertical faces only, so
    it is the graph of z(x, y) over the whole unit square: |Γ| = sqrt(1 + a² + b²).
    """
    a = np.array(SLOPES[:dim - 1])
    normal = np.append(-a, 1.0)
    return plane(np.full(dim, 0.5), normal), normal / np.linalg.norm(normal), \
        float(np.sqrt(1.0 + a @ a))


def on_gamma(f, dim, k=6):
    """∫_Γ f by a tensor Gauss–Legendre rule on the parameter square (exact to degree 2k-1)."""
    t, w = np.polynomial.legendre.leggauss(k)
    t, w = (t + 1) / 2, w / 2
    a = np.array(SLOPES[:dim - 1])
    jac = np.sqrt(1.0 + a @ a)
    if dim == 2:
        x = t
        pts = np.vstack([x, 0.5 + a[0] * (x - 0.5)])
        return jac * (w @ f(pts))
    X, Y = np.meshgrid(t, t, indexing="ij")
    W = np.outer(w, w)
    pts = np.stack([X, Y, 0.5 + a[0] * (X - 0.5) + a[1] * (Y - 0.5)])
    return jac * np.sum(W * f(pts))


def setup(cell, n=3):
    mesh = box(n, cell)
    psi, normal, area = tilted(mesh.dim())
    c = cut(mesh, psi)
    return mesh, psi, normal, area, c


# 1. the naive space ------------------------------------------------------------

def test_naive_space_is_one_multiplier_per_strictly_cut_edge(cell):
    mesh, psi, _, _, c = setup(cell)
    _, _, edges = cell_edges(mesh)
    v = psi(mesh.p)
    n_cut = int(np.sum(v[edges[0]] * v[edges[1]] < 0))
    S = naive(c)
    assert S.name == "naive"
    assert S.P.shape == (n_cut, n_cut) and S.size == n_cut, (
        f"the naive space should have one multiplier per strictly cut edge ({n_cut}), "
        f"got P of shape {S.P.shape}")
    assert abs(S.P - np.eye(n_cut)).max() == 0, "the naive prolongation must be P = I"
    assert abs(multiplier_space("naive", mesh, c).P - S.P).max() == 0


# 2. the interface rule ------------------------------------------------------------

def test_interface_weights_sum_to_the_measure_of_gamma(cell):
    mesh, psi, normal, area, c = setup(cell)
    rule = interface_rule(mesh, c)
    assert abs(rule.weights.sum() - area) < 1e-12, (
        f"Σ weights = {rule.weights.sum():.15f} should be |Γ| = {area:.15f}")
    assert np.all(rule.weights > 0)
    assert np.abs(psi(rule.points)).max() < 1e-13, "the quadrature points must lie on Γ"
    assert np.abs(rule.normals - normal[:, None]).max() < 1e-13, \
        "the normals of a plane Γ must all be its unit normal, pointing into Ω⁺"


def test_interface_weights_count_gamma_once_along_mesh_facets(cell):
    """Γ along a row of mesh facets (z = 1/2, the facets of the cells on both sides) and
    through the diagonals (x + z = 1): the weights sum to |Γ| once, 1 and √2."""
    mesh = box(4, cell)
    dim = mesh.dim()
    up = np.eye(dim)[-1]
    diagonal = np.r_[1.0, np.zeros(dim - 2), 1.0] / np.sqrt(2)
    for normal, area in ((up, 1.0), (diagonal, np.sqrt(2))):
        rule = interface_rule(mesh, cut(mesh, plane(np.full(dim, 0.5), normal)))
        assert abs(rule.weights.sum() - area) < 1e-12, (normal, rule.weights.sum())
        assert np.abs(rule.normals - normal[:, None]).max() < 1e-13


def test_interface_rule_integrates_polynomials_exactly(cell):
    mesh, _, _, area, c = setup(cell)
    dim = mesh.dim()
    rule = interface_rule(mesh, c)

    def linear(x):
        return 1.0 + 2.0 * x[0] - 3.0 * x[1] + (0.5 * x[2] if dim == 3 else 0.0)

    # Γ is symmetric about the centre of the box: ∫ linear = |Γ| linear(centre)
    exact = area * linear(np.full((dim, 1), 0.5))[0]
    got = rule.weights @ linear(rule.points)
    assert abs(got - exact) < 1e-12, f"∫_Γ of a linear function: got {got}, exact {exact}"

    def quartic(x):
        z = x[-1]
        return x[0] ** 4 - 2.0 * x[0] * x[1] * z ** 2 + 3.0 * x[1] ** 3 + z

    got, exact = rule.weights @ quartic(rule.points), on_gamma(quartic, dim)
    assert abs(got - exact) < 1e-12, (
        f"the default order 4 should integrate a quartic exactly on a planar Γ: "
        f"got {got}, exact {exact}")


def test_multiplier_functions_are_p1_on_the_facets(cell):
    """N_k: a partition of unity that interpolates linear functions exactly."""
    mesh, _, _, _, c = setup(cell)
    rule = interface_rule(mesh, c)
    N = rule.N.toarray()
    assert N.shape == (rule.weights.size, c.edge_ids.size)
    assert np.all(N >= -1e-14), "P1 facet functions are non-negative inside a facet"
    assert np.abs(N.sum(axis=1) - 1).max() < 1e-13, "the N_k must sum to one"
    assert np.abs(N @ c.points.T - rule.points.T).max() < 1e-13, \
        "Σ_k N_k(x) x_k must give back x: the N_k are linear on each facet"


# 3. the interface mass ----------------------------------------------------------------

def test_interface_mass_is_spd_and_integrates_exactly(cell):
    mesh, _, _, area, c = setup(cell)
    dim = mesh.dim()
    M = interface_mass(interface_rule(mesh, c)).toarray()
    assert M.shape == (c.edge_ids.size,) * 2
    assert np.abs(M - M.T).max() < 1e-15, "M = ∫ N_e N_f must be symmetric"
    eig = np.linalg.eigvalsh(M)
    assert eig.min() > 1e-8 * eig.max(), \
        f"M must be positive definite, smallest eigenvalue {eig.min():.2e}"
    one = np.ones(M.shape[0])
    assert abs(one @ M @ one - area) < 1e-12, "1ᵀM1 must be |Γ|"

    def f(x):
        return 0.3 + x[0] - 2.0 * x[-1]

    fe = f(c.points)  # a linear λ sampled at the multiplier points is λ itself on Γ_h
    assert abs(fe @ M @ fe - on_gamma(lambda x: f(x) ** 2, dim)) < 1e-12, \
        "fᵀMf should be ∫_Γ f² for a linear f"


# 4. the coupling ----------------------------------------------------------------------

def field_with_jump(V, g, rng):
    """U with random standard dofs and b_j = -g(x_j)/2, so [[u]] = Σ φ_j g(x_j).

    Every node of a cut cell is enriched, so on Γ the jump is the finite element
    interpolant of g: exactly g when g is linear (all five cells reproduce
    linear functions on these affine meshes).
    """
    nd = V.basis.nodal_dofs  # (dim, nverts)
    comp = np.empty(V.n_std, int)
    node = np.empty(V.n_std, int)
    for k in range(nd.shape[0]):
        comp[nd[k]] = k
        node[nd[k]] = np.arange(nd.shape[1])
    E = V.enr_dofs
    gx = g(V.mesh.p)  # (dim, nverts)
    U = np.empty(V.N)
    U[:V.n_std] = rng.standard_normal(V.n_std)
    U[V.n_std:] = -0.5 * gx[comp[E], node[E]]
    return U


JUMPS = {
    "constant": lambda x: np.array([0.3, -0.7, 1.1][:x.shape[0]])[:, None] + 0 * x,
    "linear": lambda x: np.array([0.2 + x[0] - x[-1], -0.5 + 2 * x[1], 0.4 * x[0] + x[1]]
                                 [:x.shape[0]]),
}


@pytest.mark.parametrize("jump", JUMPS)
def test_coupling_of_a_known_jump(cell, jump):
    mesh, _, normal, _, c = setup(cell)
    dim = mesh.dim()
    rng = np.random.default_rng(3)
    V = xfem_space(mesh, c)
    assert V.n_enr == dim * c.enriched.size, "no node should be dropped as a sliver here"
    rule = interface_rule(mesh, c)
    M = interface_mass(rule)
    g = JUMPS[jump]
    U = field_with_jump(V, g, rng)
    ne = c.edge_ids.size
    gp = g(c.points)  # (dim, ne): g at the multiplier points; λ_h of g is g on Γ_h

    B = coupling(V, rule, "bonded")
    assert B.shape == (dim * ne, V.N), "bonded: one row per (component, edge)"
    expected = np.concatenate([M @ gp[k] for k in range(dim)])  # component-major
    err = np.abs(B @ U - expected).max()
    assert err < 1e-12, (f"bonded B·U must be ∫_Γ N_e [[u]]_c for a {jump} jump "
                         f"(component-major rows); max error {err:.2e}")

    B = coupling(V, rule, "bilateral")
    assert B.shape == (ne, V.N), "bilateral: one row per edge"
    err = np.abs(B @ U - M @ (normal @ gp)).max()
    assert err < 1e-12, (f"bilateral B·U must be ∫_Γ N_e [[u]]·n for a {jump} jump; "
                         f"max error {err:.2e}")


# 5. clear errors ----------------------------------------------------------------------

def test_unknown_law_or_space_is_refused():
    mesh, _, _, _, c = setup("quad")
    V = xfem_space(mesh, c)
    rule = interface_rule(mesh, c)
    with pytest.raises(ValueError, match="law must be one of") as err:
        coupling(V, rule, "sticky")
    assert all(law in str(err.value) for law in LAWS), "the message should list the laws"
    with pytest.raises(ValueError, match="space must be one of") as err:
        multiplier_space("clever", mesh, c)
    assert all(s in str(err.value) for s in SPACES), "the message should list the spaces"


# 6. supports: the jumps they hold (issue 7) --------------------------------------------

def _assembled(scene):
    from skxfem.problem import assemble

    return assemble(scene), assemble(scene, "bilateral")


def _takes_a_neighbours_row(P, c, e, held) -> bool:
    """Row e of P is the row of a cut edge that is not held and shares a cut cell with e."""
    P = P.tocsr()
    cells = c.facet_cell[np.any(c.facets == e, axis=0)]
    near = np.unique(c.facets[:, np.isin(c.facet_cell, cells)])
    return any(abs(P[e] - P[k]).max() == 0 for k in near if k != e and not held[k])


def test_rollers_hold_the_tangential_jump_on_the_strips_sides():
    """The strip with rollers on x = 0, 1: the enriched x-dofs of the cut
    cells' nodes on those sides are constrained, so the x-jump at the two
    cut edges lying in the sides is held: they get no multiplier of their
    own, but the λ_x of the cut edge next to them on Γ (their hat function
    still meets the free jump of their cell); the y-jump (the normal one,
    bilateral) is held nowhere."""
    from skxfem.scene.benchmarks import strip

    p, pn = _assembled(strip(5, cell="tri", space="vital", sides="rollers"))
    fixed = fixed_jumps(p.V, p.D)
    side = np.isclose(p.mesh.p[0], 0) | np.isclose(p.mesh.p[0], 1)
    assert set(np.flatnonzero(fixed[0])) == set(p.cut.enriched[side[p.cut.enriched]])
    assert not fixed[1].any()
    in_side = np.isclose(p.cut.points[0], 0) | np.isclose(p.cut.points[0], 1)
    assert in_side.sum() == 2
    assert np.array_equal(p.held_edges[0], in_side) and not p.held_edges[1].any()
    assert not pn.held_edges.any() and not normal_fixed(fixed, p.cut).any()
    ne = p.cut.edge_ids.size
    Px = p.P[:ne, :p.component_spaces[0].size]
    assert all(_takes_a_neighbours_row(Px, p.cut, e, in_side) for e in np.flatnonzero(in_side))
    assert np.allclose(Px.sum(axis=1), 1.0, rtol=1e-12), "a constant λ_x stays in the space"
    Py = p.P[ne:, p.component_spaces[0].size:]
    assert abs(Py - p.multiplier_space.P).max() == 0, "y keeps the space"


def test_a_support_holding_the_normal_jump_removes_the_normal_multiplier():
    """Γ: x = 0.45 crosses the bottom y = 0, where u_x (the normal
    component) is held: bilateral's bottom cut edge loses its own multiplier
    and takes that of the edge above it; a support on the other component
    (u_y) changes nothing."""
    from skxfem.scene import Box, Displacement, Scene, SurfaceLoad

    def scene(component):
        return Scene(Box((4, 4), "quad"), plane((0.45, 0.0), (1.0, 0.0)),
                     displacements=(Displacement("ymin", {component: 0.0}),
                                    Displacement("xmin", {"all": 0.0}),
                                    Displacement("xmax", {"all": 0.0})),
                     loads=(SurfaceLoad("ymax", pressure=1.0),), space="vital",
                     law="bilateral")

    p, _ = _assembled(scene("x"))
    bottom = np.isclose(p.cut.points[1], 0)
    assert bottom.sum() == 1 and np.array_equal(p.held_edges[0], bottom)
    assert _takes_a_neighbours_row(p.P, p.cut, np.flatnonzero(bottom)[0], bottom)
    assert p.P.shape[1] == p.multiplier_space.size - 1, "one multiplier fewer than unsupported"
    q, _ = _assembled(scene("y"))
    assert not q.held_edges.any() and abs(q.P - q.multiplier_space.P).max() == 0


@pytest.mark.parametrize("name", SPACES)
def test_a_space_without_fixed_nodes_is_the_space(name):
    mesh, _, _, _, c = setup("tet")
    none = np.zeros(mesh.p.shape[1], dtype=bool)
    assert abs(multiplier_space(name, mesh, c).P
               - multiplier_space(name, mesh, c, fixed=none).P).max() == 0


@pytest.mark.parametrize("name", SPACES)
def test_edges_with_two_fixed_ends_take_a_neighbours_multiplier(name):
    """Fix the nodes of the face x = 0: the cut edges in it lose their own
    multiplier and take that of a neighbour on Γ, so that every row of P
    still sums to 1 (a constant traction stays in the space: issue 18) and
    the columns stay independent."""
    mesh, _, _, _, c = setup("tet")
    fixed = np.isclose(mesh.p[0], 0)
    S = multiplier_space(name, mesh, c, fixed=fixed)
    held = fixed[c.edges[0]] & fixed[c.edges[1]]
    assert held.any() and S.P.shape[0] == c.edge_ids.size
    assert np.allclose(S.P.sum(axis=1), 1.0, rtol=1e-12)
    assert all(_takes_a_neighbours_row(S.P, c, e, held) for e in np.flatnonzero(held))
    if name == "naive":
        assert S.size == c.edge_ids.size - held.sum(), "no multiplier of their own"
    assert np.linalg.matrix_rank(S.P.toarray()) == S.size
    if S.winners is not None:
        assert not fixed[S.winners].any()
    with pytest.raises(ValueError, match="one bool per node"):
        multiplier_space(name, mesh, c, fixed=fixed[:-1])


def test_a_piece_of_held_edges_alone_shares_one_multiplier_if_its_jump_can_move():
    """Γ cuts off a corner whose three cut edges all lie in fixed faces: no
    edge of the piece has a free end to borrow from, so they share one new
    multiplier while a node of their cell is free (its jump still moves on
    the facet), and none when every node of the cell is fixed (the supports
    hold the whole jump there)."""
    mesh = box(3, "hex")
    c = cut(mesh, plane((0.1, 0.0, 0.0), (1.0, 1.0, 1.0)))
    faces = np.isclose(mesh.p, 0).any(axis=0)
    assert np.all(faces[c.edges]), "every cut edge lies in a face through the corner"
    S = multiplier_space("vital", mesh, c, fixed=faces)
    assert S.P.shape == (3, 1) and np.allclose(S.P.toarray(), 1.0)
    every = np.ones(mesh.p.shape[1], dtype=bool)
    assert multiplier_space("vital", mesh, c, fixed=every).P.nnz == 0
