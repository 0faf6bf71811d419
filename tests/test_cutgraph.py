"""The shared queries on the graph of the cut edges (skxfem/fem/cutgraph.py)."""
import numpy as np
import pytest

from skxfem.fem.cutgraph import check_fixed, edges_at, incidence, interpolate, nearest

# nodes 0, 2, 4 below Γ, 1, 3 above; edges 0-1, 2-1, 2-3, 4-3
EDGES = np.array([[0, 2, 2, 4], [1, 1, 3, 3]])
POINTS = np.array([[0.5, 1.5, 2.5, 3.5], [0.0, 0.0, 0.0, 0.0]])


def test_edges_at_and_nearest():
    inc = incidence(EDGES, 5, np.array([True, False, True, True]))
    rows, edges = edges_at(inc, np.array([1, 3]))
    assert rows.tolist() == [0, 1, 1] and edges.tolist() == [0, 2, 3]
    # for edge 1 (point x = 1.5): the kept edge at node 2 nearest to it is 2,
    # at node 1 it is 0; node 0 has none but edge 0 itself is kept
    assert nearest(POINTS, np.array([1, 1]), np.array([2, 1]), inc).tolist() == [2, 0]
    assert nearest(POINTS, np.array([1]), np.array([0]), incidence(EDGES, 5, EDGES[0] > 0)
                   ).tolist() == [-1]


def test_interpolate_weights_by_distance():
    r, c, w = interpolate(POINTS, np.array([1]), np.array([0]), np.array([3]),
                          np.array([7]), np.array([8]))
    assert r.tolist() == [1, 1] and c.tolist() == [7, 8]
    assert w == pytest.approx([2 / 3, 1 / 3])          # 1 from edge 0, 2 from edge 3


def test_fixed_nodes_are_checked():
    assert not check_fixed(None, EDGES, 5).any()
    with pytest.raises(ValueError, match="both ends of edge 1"):
        check_fixed(np.isin(np.arange(5), [1, 2]), EDGES, 5)
