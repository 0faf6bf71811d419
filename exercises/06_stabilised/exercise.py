"""Exercise 06: the vital edges of algo2, a minimum edge cover (see README.md).

The cut edges S_e form a bipartite graph: each edge joins a node of
N_e⁻ (ψ < 0) to a node of N_e⁺ (ψ > 0).  You may import numpy, scipy and
itertools; not skxfem.stabilised (it holds the answer).  skxfem.viz.figures'
``figure6_graph`` (the paper's Figure 6) is there for you to try things on.
"""
import numpy as np  # noqa: F401  (you will need it)


def minimum_edge_cover(edges, psi, length):
    """S_ve: the fewest cut edges touching every node of N_e, then the shortest.

    Among all sets of edges that touch every node of N_e (edge covers), take
    those with the fewest edges (minimum, not merely minimal: no edge can be
    dropped from a minimal cover, yet a smaller cover may exist), and among
    those one of least total length (the paper: "we keep the shortest one").

    Parameters
    ----------
    edges : (2, ne) int array, the cut edges S_e; psi(v1) psi(v2) < 0 for each.
    psi : (nnodes,) float array, the nodal level set (its sign gives the sides).
    length : (ne,) float array, the edge lengths.

    Returns
    -------
    ndarray of bool
        Shape (ne,): True for the vital edges.

    Examples
    --------
    >>> edges = np.array([[0, 2], [1, 1]])          # a star at node 1: both needed
    >>> minimum_edge_cover(edges, np.array([-1.0, 1.0, -1.0]), np.ones(2)).tolist()
    [True, True]
    """
    raise NotImplementedError("minimum_edge_cover: not written yet (exercise 06, see README.md)")


def star_groups(edges, vital):
    """The groups G_cve of connected vital edges (stars), one label per edge.

    Vital edges sharing a node belong to one group (in a minimum edge cover the
    groups are stars); a lone vital edge is a group of one.  Groups are numbered
    0, 1, ... in the order of their lowest edge index.

    Parameters
    ----------
    edges : (2, ne) int array.
    vital : (ne,) bool array.

    Returns
    -------
    ndarray of int
        Shape (ne,): the group of each vital edge, -1 for the non-vital ones.

    Examples
    --------
    >>> edges = np.array([[0, 2, 3, 4], [1, 1, 5, 6]])
    >>> star_groups(edges, np.array([True, True, False, True])).tolist()
    [0, 0, -1, 1]
    """
    raise NotImplementedError("star_groups: not written yet (exercise 06, see README.md)")
