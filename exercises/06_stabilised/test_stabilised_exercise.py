"""Exercise 06, vital edges: make these pass in order (``pytest exercises/06_stabilised``)."""
import itertools

import numpy as np
import pytest

from skxfem.viz.figures import FIG6_EDGES, figure6_graph

ASKED = ("minimum_edge_cover", "star_groups")
LIBRARY = ("skxfem.stabilised",)   # it holds the answer: write your own

# The paper's Figure 6 answer (§5): S_ve and the two groups of connected vital edges.
PAPER_VITAL = {(1, 8), (2, 9), (2, 10), (3, 11), (4, 12), (5, 12), (6, 12), (7, 13)}
PAPER_GROUPS = [{(2, 9), (2, 10)}, {(4, 12), (5, 12), (6, 12)}]


def name(edges, e):
    return f"{edges[0, e]}-{edges[1, e]}"


def brute_force(edges, length):
    """(fewest edges, least length among them) over every edge cover."""
    nodes = set(edges.ravel().tolist())
    for k in range(1, edges.shape[1] + 1):
        best = [length[list(c)].sum() for c in itertools.combinations(range(edges.shape[1]), k)
                if set(edges[:, list(c)].ravel().tolist()) == nodes]
        if best:
            return k, min(best)


def cover(impl, edges, psi, length):
    got = np.asarray(impl.minimum_edge_cover(edges, psi, length))
    assert got.shape == (edges.shape[1],) and got.dtype == bool, (
        f"minimum_edge_cover returns one bool per edge, shape ({edges.shape[1]},); got "
        f"{got.dtype} {got.shape}")
    return got


def check_cover(impl, edges, psi, length, what):
    vital = cover(impl, edges, psi, length)
    touched = set(edges[:, vital].ravel().tolist())
    for v in sorted(set(edges.ravel().tolist()) - touched):
        raise AssertionError(f"{what}: node {v} is not touched by any vital edge; S_ve must "
                             f"cover every node of N_e (a matching alone is not enough)")
    k, best = brute_force(edges, length)
    if vital.sum() > k:
        count = np.bincount(edges[:, vital].ravel(), minlength=psi.size)
        spare = [name(edges, e) for e in np.flatnonzero(vital)
                 if count[edges[0, e]] > 1 and count[edges[1, e]] > 1]
        raise AssertionError(
            f"{what}: {k} edges suffice to cover the {len(touched)} nodes, yours has "
            f"{vital.sum()} ({', '.join(name(edges, e) for e in np.flatnonzero(vital))}). "
            + (f"Edge(s) {', '.join(spare)} can simply be dropped." if spare else
               "Your cover is minimal but not minimum: no edge can be dropped, yet a smaller "
               "cover exists (removing edges one by one, greedily, can end there)"))
    assert abs(length[vital].sum() - best) < 1e-9, (
        f"{what}: among the covers of {k} edges the shortest has total length {best:g}, yours "
        f"{length[vital].sum():g}: keep the shortest edges")
    return vital


def test_01_a_star_needs_all_its_edges(impl):
    edges = np.array([[0, 2, 3], [1, 1, 1]])            # node 1 in Ω⁺, 0, 2, 3 in Ω⁻
    psi = np.array([-1.0, 1.0, -1.0, -1.0])
    vital = check_cover(impl, edges, psi, np.ones(3), "a star of 3 edges at node 1")
    assert vital.all()


def test_02_fewest_edges_not_just_no_superfluous_one(impl):
    # a path 0-1-2-3-4-5 whose middle edge 2-3 is long: the minimum cover keeps it
    edges = np.array([[0, 2, 2, 4, 4], [1, 1, 3, 3, 5]])
    psi = np.array([-1.0, 1.0, -1.0, 1.0, -1.0, 1.0])
    check_cover(impl, edges, psi, np.array([1.0, 1.0, 3.0, 1.0, 1.0]), "the path 0-1-2-3-4-5")


def test_03_the_shortest_among_the_fewest(impl):
    # a 4-cycle: {0-1, 2-3} and {2-1, 0-3} both cover it with 2 edges
    edges = np.array([[0, 2, 2, 0], [1, 1, 3, 3]])
    psi = np.array([-1.0, 1.0, -1.0, 1.0])
    vital = check_cover(impl, edges, psi, np.array([1.0, 2.0, 1.0, 2.0]), "the 4-cycle")
    assert vital.tolist() == [True, False, True, False]


def test_04_small_random_graphs(impl):
    rng = np.random.default_rng(6)
    for trial in range(15):
        nm, npl = rng.integers(2, 5, size=2)
        pairs = [(i, nm + j) for i in range(nm) for j in range(npl) if rng.random() < 0.55]
        used = {v for p in pairs for v in p}
        pairs += [(i, nm) for i in range(nm) if i not in used]
        pairs += [(0, nm + j) for j in range(npl) if nm + j not in used]
        edges = np.array(sorted(set(pairs))).T
        psi = np.r_[-np.ones(nm), np.ones(npl)]
        length = rng.integers(1, 4, size=edges.shape[1]).astype(float)
        check_cover(impl, edges, psi, length, f"random graph {trial} with edges "
                    + ", ".join(name(edges, e) for e in range(edges.shape[1]))
                    + f" of lengths {length.astype(int).tolist()}")


@pytest.mark.points(2)
def test_05_figure6_of_the_paper(impl):
    edges, psi, points, nodes = figure6_graph()
    length = np.linalg.norm(nodes[:, edges[0]] - nodes[:, edges[1]], axis=0)
    vital = check_cover(impl, edges, psi, length, "Figure 6")
    got = {FIG6_EDGES[e] for e in np.flatnonzero(vital)}
    assert got == PAPER_VITAL, (
        f"Figure 6: the paper's vital edges are {sorted(PAPER_VITAL)}; you are missing "
        f"{sorted(PAPER_VITAL - got)} and have {sorted(got - PAPER_VITAL)} extra "
        f"(2-10 is shorter than 3-10)")


def test_06_star_groups_of_figure6(impl):
    edges = np.array(FIG6_EDGES).T
    vital = np.array([e in PAPER_VITAL for e in FIG6_EDGES])
    groups = np.asarray(impl.star_groups(edges, vital))
    assert groups.shape == (edges.shape[1],), f"one group label per edge, got shape {groups.shape}"
    assert np.all(groups[~vital] == -1), "non-vital edges belong to no group: label -1"
    sets = [{FIG6_EDGES[e] for e in np.flatnonzero(groups == g)} for g in np.unique(groups[vital])]
    big = [s for s in sets if len(s) > 1]
    assert sorted(map(sorted, big)) == sorted(map(sorted, PAPER_GROUPS)), (
        f"Figure 6 has two groups of connected vital edges, G² = {{2-9, 2-10}} and G¹² = "
        f"{{4-12, 5-12, 6-12}}; got {[sorted(s) for s in big]}")
    assert len(sets) == 5, (
        f"8 vital edges in 2 stars and 3 lone edges make 5 groups, got {len(sets)}")


def test_07_groups_are_numbered_by_lowest_edge(impl):
    edges = np.array([[5, 0, 2, 3, 4], [6, 1, 1, 7, 7]])
    vital = np.array([True, True, True, True, True])
    got = np.asarray(impl.star_groups(edges, vital)).tolist()
    assert got == [0, 1, 1, 2, 2], (
        f"edges 5-6 | 0-1, 2-1 | 3-7, 4-7 form three stars, numbered by their lowest edge "
        f"index: [0, 1, 1, 2, 2]; got {got}")
