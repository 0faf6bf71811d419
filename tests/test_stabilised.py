"""Tests for skxfem.stabilised: algo2 (vital edges) and algo1 (winner nodes), paper §5.

First the paper's Figure 6, number by number; then the exactness of the
minimum edge cover (brute force, then an LP on real meshes); then the
properties every space must have on cut meshes in 2D and 3D.
"""
import numpy as np
import pytest
import scipy.sparse as sp
from scipy.optimize import linprog
from scipy.sparse.csgraph import maximum_bipartite_matching
from skfem import MeshHex1, MeshLine1, MeshQuad1, MeshTet1, MeshTri1

from skxfem.stabilised import vital_edges, winner_nodes


def cut_points(edges, psi, nodes):
    """Where the linear interpolant of ψ vanishes on each edge."""
    pa, pb = psi[edges[0]], psi[edges[1]]
    return nodes[:, edges[0]] + pa / (pa - pb) * (nodes[:, edges[1]] - nodes[:, edges[0]])


# ---------------------------------------------------------------- Figure 6
# Nodes 1-7 below Γ (ψ = y < 0), 8-13 above; node 0 is unused (the paper counts
# from 1).  The multipliers a..k sit on the edges in the order Γ meets them.
FIG6_XY = {1: (0, -1), 2: (2, -1), 3: (4.5, -1), 4: (7, -1), 5: (8, -1), 6: (9, -1),
           7: (11, -0.7), 8: (1, 0.8), 9: (2, 1), 10: (3, 1), 11: (5, 1), 12: (9, 1),
           13: (12, 1)}
FIG6_EDGES = [(1, 8), (2, 8), (2, 9), (2, 10), (3, 10), (3, 11), (4, 12), (5, 12), (6, 12),
              (7, 12), (7, 13)]
ROW = {letter: i for i, letter in enumerate("abcdefghijk")}


def figure6(xy=FIG6_XY):
    nodes = np.zeros((2, 14))
    nodes[:, 0] = (-5.0, 5.0)
    for node, x in xy.items():
        nodes[:, node] = x
    psi = nodes[1].copy()
    edges = np.array(FIG6_EDGES).T
    return edges, psi, cut_points(edges, psi, nodes), nodes


def dist(points, p, q):
    return float(np.linalg.norm(points[:, ROW[p]] - points[:, ROW[q]]))


def test_fig6_geometry_is_the_papers():
    edges, psi, points, nodes = figure6()
    assert np.all(psi[1:8] < 0) and np.all(psi[8:] > 0), "nodes 1-7 in Ω⁻, 8-13 in Ω⁺"
    assert np.all(np.diff(points[0]) > 0), "A, B, ..., K must follow each other along Γ"
    length = np.linalg.norm(nodes[:, edges[0]] - nodes[:, edges[1]], axis=0)
    assert length[ROW["d"]] < length[ROW["e"]], "the paper's 2-10 is shorter than 3-10"


def test_fig6_vital_edges_and_groups():
    space = vital_edges(*figure6())
    vital = {FIG6_EDGES[i] for i in np.flatnonzero(space.vital)}
    assert vital == {(1, 8), (2, 9), (2, 10), (3, 11), (4, 12), (5, 12), (6, 12), (7, 13)}
    g = {letter: space.groups[i] for letter, i in ROW.items()}
    assert g["c"] == g["d"], "G² = {2-9, 2-10}: λ_c = λ_d"
    assert g["g"] == g["h"] == g["i"], "G¹² = {4-12, 5-12, 6-12}: λ_g = λ_h = λ_i"
    assert g["b"] == g["e"] == g["j"] == -1, "2-8, 3-10 and 7-12 are not vital"
    assert sorted({g[x] for x in "acfgk"}) == [0, 1, 2, 3, 4]
    assert space.size == 5


def test_fig6_linear_relations():
    edges, psi, points, nodes = figure6()
    space = vital_edges(edges, psi, points, nodes)
    P, g = space.P.toarray(), space.groups

    def expect(row, k1, k2, w1, w2):
        want = np.zeros(space.size)
        want[g[ROW[k1]]] += w1
        want[g[ROW[k2]]] += w2
        np.testing.assert_allclose(P[ROW[row]], want, rtol=1e-12, err_msg=f"λ_{row}")

    AB, BC = dist(points, "a", "b"), dist(points, "b", "c")
    DE, EF = dist(points, "d", "e"), dist(points, "e", "f")
    IJ, JK = dist(points, "i", "j"), dist(points, "j", "k")
    expect("b", "a", "c", BC / (AB + BC), AB / (AB + BC))
    expect("e", "d", "f", EF / (DE + EF), DE / (DE + EF))
    # the paper prints λ_l, but there are only a..k: the nearest of G¹² to J is I
    expect("j", "i", "k", JK / (IJ + JK), IJ / (IJ + JK))
    for x in "acdfghik":
        assert P[ROW[x], g[ROW[x]]] == 1.0 and P[ROW[x]].sum() == 1.0


def test_fig6_shorter_3_10_becomes_vital_instead():
    edges, psi, points, nodes = figure6({**FIG6_XY, 10: (4.0, 1.0)})
    space = vital_edges(edges, psi, points, nodes)
    assert space.vital[ROW["e"]] and not space.vital[ROW["d"]], "keep the shortest edge"
    assert space.groups[ROW["e"]] == space.groups[ROW["f"]], "now G³ = {3-10, 3-11}"
    assert space.size == 5


def test_fig6_winner_nodes():
    edges, psi, points, nodes = figure6()
    space = winner_nodes(edges, psi, points, nodes)
    assert set(space.winners.tolist()) == {8, 2, 3, 12, 7}
    assert space.size == 5
    P, col = space.P.toarray(), {int(w): j for j, w in enumerate(space.winners)}
    for x, w in zip("acdefghik", (8, 2, 2, 3, 3, 12, 12, 12, 7)):
        assert P[ROW[x], col[w]] == 1.0 and P[ROW[x]].sum() == 1.0, f"λ_{x} = μ_{w}"
    np.testing.assert_array_equal(P[ROW["e"]], P[ROW["f"]])     # "λ_e = λ_f" with algo1
    AB, BC = dist(points, "a", "b"), dist(points, "b", "c")     # 2-8 joins two winners
    assert P[ROW["b"], col[8]] == pytest.approx(BC / (AB + BC))
    assert P[ROW["b"], col[2]] == pytest.approx(AB / (AB + BC))


def test_fig6_algo2_has_more_linear_relations():
    data = figure6()
    interpolated = [int((np.diff(s.P.indptr) == 2).sum())
                    for s in (vital_edges(*data), winner_nodes(*data))]
    assert interpolated == [3, 2], "algo2 ties b, e, j linearly; algo1 only b and j"


def test_winners_follow_the_degree_difference():
    # the zigzag path 1-3-0-4-2: the largest |deg(v1) - deg(v2)| is on the end
    # edges, so 3 and 4 win and cover it; a plain "most edges first" greedy
    # would take the middle node 0 and then both ends 1 and 2: three multipliers
    edges = np.array([[0, 0, 1, 2], [3, 4, 3, 4]])
    nodes = np.array([[2, 0, 4, 1, 3], [-1, -1, -1, 1, 1]], dtype=float)
    psi = nodes[1].copy()
    space = winner_nodes(edges, psi, cut_points(edges, psi, nodes), nodes)
    assert space.winners.tolist() == [3, 4]


def test_winner_without_single_winner_edge_keeps_its_multiplier():
    # a hub 0 with three legs 0-4-1, 0-5-2, 0-6-3: 0 wins first, then 4, 5, 6
    edges = np.array([[0, 0, 0, 1, 2, 3], [4, 5, 6, 4, 5, 6]])
    psi = np.array([-2.0, -4.0, -6.0, -7.0, 3.0, 3.0, 2.0])
    nodes = np.array([[0, -2, 0, 2, -1, 0, 1], [0, 0, -2, 0, 0, -1, 0]], dtype=float)
    space = winner_nodes(edges, psi, cut_points(edges, psi, nodes), nodes)
    assert space.winners.tolist() == [0, 4, 5, 6]
    np.testing.assert_array_equal(space.P.toarray()[:3], [[1, 0, 0, 0]] * 3)
    assert np.linalg.matrix_rank(space.P.toarray()) == 4


# ------------------------------------------------- the minimum edge cover is exact
def brute_force_cover(edges, length):
    """(fewest edges, least length) over all covering subsets."""
    m = edges.shape[1]
    subsets = (np.arange(2 ** m)[:, None] >> np.arange(m)) & 1
    nodes = np.unique(edges)
    touches = (edges[0][None] == nodes[:, None]) | (edges[1][None] == nodes[:, None])
    covers = subsets[np.all(subsets @ touches.T > 0, axis=1)]
    size = covers.sum(axis=1)
    return size.min(), (covers[size == size.min()] @ length).min()


def test_minimum_edge_cover_on_random_graphs_by_brute_force():
    rng = np.random.default_rng(0)
    for trial in range(400):
        n_minus, n_plus = rng.integers(1, 5, size=2)
        pairs = np.array(np.meshgrid(np.arange(n_minus),
                                     n_minus + np.arange(n_plus))).reshape(2, -1)
        edges = pairs[:, rng.permutation(pairs.shape[1])[:rng.integers(1, 10)]]
        if trial % 2:                                   # many equal lengths
            nodes = rng.integers(0, 3, size=(2, n_minus + n_plus)).astype(float)
            nodes[0, n_minus:] += 3.0
        else:                                           # lengths of all sizes
            nodes = rng.uniform(0, 1, size=(2, n_minus + n_plus))
        psi = np.r_[-rng.uniform(0.1, 1, n_minus), rng.uniform(0.1, 1, n_plus)]
        length = np.linalg.norm(nodes[:, edges[0]] - nodes[:, edges[1]], axis=0)
        space = vital_edges(edges, psi, cut_points(edges, psi, nodes), nodes)
        size, best = brute_force_cover(edges, length)
        assert space.vital.sum() == size, f"graph {trial}: not a minimum edge cover"
        assert length[space.vital].sum() == pytest.approx(best, rel=1e-12), \
            f"graph {trial}: a shorter minimum edge cover exists"


# ------------------------------------------------------- cut meshes in 2D and 3D
def mesh_graph(kind, shape, seed):
    """S_e, ψ, points and (jittered) nodes of a mesh cut by a random plane or sphere."""
    rng = np.random.default_rng(seed)
    x = np.linspace(0, 1, 7)
    mesh = {"tri": lambda: MeshTri1.init_tensor(x, x), "quad": lambda: MeshQuad1.init_tensor(x, x),
            "tet": lambda: MeshTet1.init_tensor(x, x, x),
            "hex": lambda: MeshHex1.init_tensor(x, x, x),
            "wedge": lambda: MeshTri1.init_tensor(x, x) * MeshLine1(x[None])}[kind]()
    nodes = mesh.p + rng.uniform(-0.03, 0.03, mesh.p.shape)
    centre = 0.5 + rng.uniform(-0.1, 0.1, mesh.dim())
    if shape == "plane":
        normal = rng.normal(size=mesh.dim())
        psi = (nodes - centre[:, None]).T @ (normal / np.linalg.norm(normal))
    else:
        psi = np.linalg.norm(nodes - centre[:, None], axis=0) - rng.uniform(0.2, 0.35)
    assert np.abs(psi).min() > 1e-9
    all_edges = mesh.edges if mesh.dim() == 3 else mesh.facets
    edges = all_edges[:, psi[all_edges[0]] * psi[all_edges[1]] < 0]
    return edges, psi, cut_points(edges, psi, nodes), nodes


CASES = [(kind, shape, seed) for kind in ("tri", "quad", "tet", "hex", "wedge")
         for shape in ("plane", "sphere") for seed in (1, 2)]


def check_prolongation(P, ne):
    assert P.shape[0] == ne
    np.testing.assert_allclose(P.sum(axis=1).A.ravel(), 1.0, rtol=1e-12,
                               err_msg="rows of P must sum to 1 (constant pressure)")
    assert P.data.min() >= 0 and np.diff(P.indptr).max() <= 2
    assert np.linalg.matrix_rank(P.toarray()) == P.shape[1], "μ must be independent"


def maximum_matching(edges, psi):
    minus = np.where(psi[edges[0]] < 0, edges[0], edges[1])
    B = sp.csr_matrix((np.ones(edges.shape[1]), (minus, edges[0] + edges[1] - minus)),
                      shape=(psi.size,) * 2)
    return int((maximum_bipartite_matching(B, perm_type="column") >= 0).sum())


@pytest.mark.parametrize("kind, shape, seed", CASES)
def test_vital_edges_on_cut_meshes(kind, shape, seed):
    edges, psi, points, nodes = mesh_graph(kind, shape, seed)
    space = vital_edges(edges, psi, points, nodes)
    V = edges[:, space.vital]
    Ne = np.unique(edges)
    count = np.bincount(V.ravel(), minlength=psi.size)
    assert np.all(count[Ne] >= 1), "S_ve must touch every node of N_e"
    assert np.all(np.minimum(count[V[0]], count[V[1]]) == 1), \
        "S_ve must be minimal: removing any vital edge uncovers a node"
    for g in range(space.size):
        star = edges[:, space.groups == g]
        assert np.unique(star).size == star.shape[1] + 1, f"group {g} is not a tree"
        assert np.bincount(star.ravel()).max() == star.shape[1], f"group {g} is not a star"
    nu = maximum_matching(edges, psi)
    assert space.size == nu, "one μ per star: as many as a maximum matching"
    assert space.vital.sum() == Ne.size - nu, "Gallai: |min edge cover| = |N_e| - ν"
    check_prolongation(space.P, edges.shape[1])
    vital_rows = space.P[np.flatnonzero(space.vital)].toarray()
    np.testing.assert_array_equal(vital_rows.argmax(axis=1), space.groups[space.vital])


@pytest.mark.parametrize("kind, shape, seed", CASES[::3])
def test_vital_edges_have_least_length_by_linear_programming(kind, shape, seed):
    edges, psi, points, nodes = mesh_graph(kind, shape, seed)
    length = np.linalg.norm(nodes[:, edges[0]] - nodes[:, edges[1]], axis=0)
    Ne, inverse = np.unique(edges, return_inverse=True)
    ne = edges.shape[1]
    A = sp.csr_matrix((np.ones(2 * ne), (inverse.ravel(), np.tile(np.arange(ne), 2))))
    # the incidence matrix of a bipartite graph is totally unimodular: the LP is the IP
    fewest = linprog(np.ones(ne), A_ub=-A, b_ub=-np.ones(Ne.size), bounds=(0, 1)).fun
    shortest = linprog(length, A_ub=-A, b_ub=-np.ones(Ne.size), A_eq=np.ones((1, ne)),
                       b_eq=[round(fewest)], bounds=(0, 1)).fun
    space = vital_edges(edges, psi, points, nodes)
    assert space.vital.sum() == round(fewest)
    assert length[space.vital].sum() == pytest.approx(shortest, rel=1e-9)


@pytest.mark.parametrize("kind, shape, seed", CASES)
def test_winner_nodes_on_cut_meshes(kind, shape, seed):
    edges, psi, points, nodes = mesh_graph(kind, shape, seed)
    space = winner_nodes(edges, psi, points, nodes)
    won = np.isin(edges, space.winners)
    assert np.all(won.any(axis=0)), "every cut edge must have a winner end"
    assert np.unique(space.winners).size == space.size
    assert space.size >= maximum_matching(edges, psi), "König: a cover has at least ν nodes"
    check_prolongation(space.P, edges.shape[1])


# ----------------------------------------------------------------- bad input
@pytest.mark.parametrize("change, name", [
    (lambda e, s, p, n: (e[:1], s, p, n), "edges"),
    (lambda e, s, p, n: (e.astype(float), s, p, n), "edges"),
    (lambda e, s, p, n: (e + 20, s, p, n), "edges"),
    (lambda e, s, p, n: (np.c_[e, [1, 2]], s, np.c_[p, [0, 0]], n), "strictly cut"),
    (lambda e, s, p, n: (np.c_[e, [8, 1]], s, np.c_[p, [0, 0]], n), "twice"),
    (lambda e, s, p, n: (e, s[:-1], p, n), "psi"),
    (lambda e, s, p, n: (e, s, p[:, :-1], n), "points"),
    (lambda e, s, p, n: (e, s, p, n[:1]), "nodes"),
    (lambda e, s, p, n: (e, s, p, np.where(np.arange(14) == 8, n[:, [1]], n)), "nodes"),
])
def test_bad_input_names_the_argument(change, name):
    for algorithm in (vital_edges, winner_nodes):
        with pytest.raises(ValueError, match=name):
            algorithm(*change(*figure6()))


def test_no_cut_edge_gives_an_empty_space():
    nodes, psi = np.zeros((2, 3)), np.ones(3)
    for algorithm in (vital_edges, winner_nodes):
        assert algorithm(np.zeros((2, 0), int), psi, np.zeros((2, 0)), nodes).P.shape == (0, 0)


# ------------------------------------------------ fixed nodes (issue 7: supports)
def fixed_nodes(edges, psi, seed):
    """A random set of nodes of N_e, no two joined by an edge (an independent set)."""
    rng = np.random.default_rng(seed)
    fixed = np.zeros(psi.size, dtype=bool)
    for v in rng.permutation(np.unique(edges))[:np.unique(edges).size // 3]:
        neighbours = edges[:, (edges == v).any(axis=0)].ravel()
        if not fixed[neighbours].any():
            fixed[v] = True
    assert fixed.any()
    return fixed


@pytest.mark.parametrize("kind, shape, seed", CASES[::2])
def test_vital_edges_with_fixed_nodes_cover_the_free_ones_least(kind, shape, seed):
    """A fixed node needs no cover: S_ve is a minimum cover of the free nodes
    (an LP, exact as the incidence matrix is totally unimodular), of least
    length, and its stars meet only at free nodes."""
    edges, psi, points, nodes = mesh_graph(kind, shape, seed)
    fixed = fixed_nodes(edges, psi, seed)
    space = vital_edges(edges, psi, points, nodes, fixed=fixed)
    free = np.setdiff1d(np.unique(edges), np.flatnonzero(fixed))
    count = np.bincount(edges[:, space.vital].ravel(), minlength=psi.size)
    assert np.all(count[free] >= 1), "S_ve must touch every free node"
    length = np.linalg.norm(nodes[:, edges[0]] - nodes[:, edges[1]], axis=0)
    ne = edges.shape[1]
    rows = np.searchsorted(free, edges)
    at = np.isin(edges, free)
    A = sp.csr_matrix((np.ones(at.sum()), (rows[at], np.tile(np.arange(ne), (2, 1))[at])),
                      shape=(free.size, ne))
    fewest = linprog(np.ones(ne), A_ub=-A, b_ub=-np.ones(free.size), bounds=(0, 1)).fun
    shortest = linprog(length, A_ub=-A, b_ub=-np.ones(free.size), A_eq=np.ones((1, ne)),
                       b_eq=[round(fewest)], bounds=(0, 1)).fun
    assert space.vital.sum() == round(fewest)
    assert length[space.vital].sum() == pytest.approx(shortest, rel=1e-9)
    for g in range(space.size):
        star = edges[:, space.groups == g]
        shared = np.flatnonzero(np.bincount(star.ravel()) > 1)
        assert not fixed[shared].any(), f"group {g} is joined through a fixed node"
    check_prolongation(space.P, ne)


@pytest.mark.parametrize("kind, shape, seed", CASES[::2])
def test_fixed_nodes_never_win(kind, shape, seed):
    edges, psi, points, nodes = mesh_graph(kind, shape, seed)
    fixed = fixed_nodes(edges, psi, seed)
    space = winner_nodes(edges, psi, points, nodes, fixed=fixed)
    assert not fixed[space.winners].any()
    assert np.all(np.isin(edges, space.winners).any(axis=0)), "every edge has a winner end"
    check_prolongation(space.P, edges.shape[1])


def test_no_fixed_node_is_the_default():
    graph = figure6()
    none = np.zeros(14, dtype=bool)
    for algorithm in (vital_edges, winner_nodes):
        assert abs(algorithm(*graph).P - algorithm(*graph, fixed=none).P).max() == 0


@pytest.mark.parametrize("fixed, message", [
    (np.ones(3, dtype=bool), "one bool per node"),
    (np.arange(14) % 2, "one bool per node"),
    (np.isin(np.arange(14), [1, 8]), "both ends of edge 0"),
])
def test_bad_fixed_nodes_are_refused(fixed, message):
    for algorithm in (vital_edges, winner_nodes):
        with pytest.raises(ValueError, match=message):
            algorithm(*figure6(), fixed=fixed)


# ---------------------------------------------------------------- a μ per edge
@pytest.mark.parametrize("name", ["winner", "vital"])
def test_per_edge_edges_get_a_multiplier_each_and_the_rest_keeps_its_space(name):
    """``per_edge``: those cut edges get their own column (as in the naive
    space), the others the stable space built on them alone; rows sum to 1."""
    from skxfem.cut import cut
    from skxfem.levelset import plane
    from skxfem.stabilised import multiplier_space

    mesh = MeshTri1().refined(3)
    c = cut(mesh, plane((0.5, 0.43), (0.2, 1.0)))
    own = np.zeros(c.edge_ids.size, dtype=bool)
    own[:3] = True
    S = multiplier_space(name, mesh, c, per_edge=own)
    P = S.P.toarray()
    assert np.allclose(P.sum(axis=1), 1.0)
    solo = P[own]
    assert np.all(np.sort(solo, axis=1)[:, -1] == 1.0) and np.all((solo > 0).sum(axis=1) == 1)
    assert not np.any(P[~own][:, np.flatnonzero(solo.any(axis=0))]), "their columns are theirs"
    assert np.linalg.matrix_rank(P) == S.size
    with pytest.raises(ValueError, match="per_edge must be one bool per cut edge"):
        multiplier_space(name, mesh, c, per_edge=own[:-1])


# ---------------------------------------------------------------- Γ through nodes
@pytest.mark.parametrize("name", ["naive", "winner", "vital"])
def test_a_vertex_on_gamma_gets_a_multiplier_of_its_own(name):
    """Γ through mesh nodes: a vertex point (edge id -1) takes its own column, the
    cut edges the space built on them alone (a vertex is no edge of the graph);
    rows sum to 1, P has full column rank.  Along the facets every point is a
    vertex: P = I, one μ per node on Γ."""
    from skxfem.cut import cut
    from skxfem.levelset import plane
    from skxfem.stabilised import multiplier_space

    mesh = MeshTri1().refined(3)                         # h = 1/8
    c = cut(mesh, plane((0.5, 0.5), (0.2, 1.0)))         # through the node (1/2, 1/2)
    vertex = c.edge_ids < 0
    assert vertex.sum() >= 1 and (~vertex).sum() > 3
    S = multiplier_space(name, mesh, c)
    P = S.P.toarray()
    assert np.allclose(P.sum(axis=1), 1.0)
    solo = P[vertex]
    assert np.all(solo.max(axis=1) == 1.0) and np.all((solo != 0).sum(axis=1) == 1)
    assert not np.any(P[~vertex][:, np.flatnonzero(solo.any(axis=0))])
    assert np.linalg.matrix_rank(P) == S.size
    flat = cut(mesh, plane((0.5, 0.5), (0.0, 1.0)))      # along the facets y = 1/2
    assert np.all(flat.edge_ids == -1)
    assert np.array_equal(multiplier_space(name, mesh, flat).P.toarray(), np.eye(9))
