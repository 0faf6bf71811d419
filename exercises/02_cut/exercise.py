"""Exercise 02: cut edges, intersection points and sub-cell volumes (see README.md).

You may import numpy; not skxfem.cut or skxfem.fem.simplex (they hold the answers).
"""
import numpy as np  # noqa: F401  (you will need it)


def cut_edges(edges, psi):
    """Indices of the strictly cut edges S_e = {e : ψ(v₁(e)) ψ(v₂(e)) < 0}.

    An edge with ψ = 0 at a vertex touches Γ but is not strictly cut.

    Parameters
    ----------
    edges : (2, ne) int array, the two vertices of each edge.
    psi : (nverts,) float array, ψ at the vertices.

    Returns
    -------
    ndarray of int
        The indices ``e`` into ``edges`` of the cut edges, increasing.

    Examples
    --------
    >>> cut_edges(np.array([[0, 1, 0], [1, 2, 2]]), np.array([-1.0, 1.0, 2.0])).tolist()
    [0, 2]
    """
    raise NotImplementedError("cut_edges: not written yet (exercise 02, see README.md)")


def intersection_points(nodes, edges, psi):
    """Where Γ_h crosses each edge: the zero of the linear interpolant of ψ.

    For an edge (a, b) with ψ_a ψ_b < 0, x = x_a + t (x_b - x_a), t = ψ_a / (ψ_a - ψ_b).

    Parameters
    ----------
    nodes : (dim, nverts) float array, vertex coordinates.
    edges : (2, ne) int array, edges that are all strictly cut.
    psi : (nverts,) float array.

    Returns
    -------
    ndarray
        Shape ``(dim, ne)``: column e is the intersection point of edge e.

    Examples
    --------
    >>> nodes = np.array([[0.0, 1.0], [0.0, 0.0]])
    >>> intersection_points(nodes, np.array([[0], [1]]), np.array([-1.0, 3.0])).ravel().tolist()
    [0.25, 0.0]
    """
    raise NotImplementedError("intersection_points: not written yet (exercise 02, see README.md)")


def subcell_volumes(X, psi):
    """Measures of the parts of one simplex on either side of Γ_h = {ψ_h = 0}.

    ψ_h is the linear interpolant of the vertex values.  A triangle with one
    vertex alone on its side splits into a triangle and a quadrilateral; a
    tetrahedron into a tetrahedron and a prism (one vertex alone) or two
    prisms (two against two).

    Parameters
    ----------
    X : (d + 1, d) float array, the vertices of a triangle (d = 2) or a tetrahedron (d = 3).
    psi : (d + 1,) float array, ψ at the vertices, none of them zero.

    Returns
    -------
    tuple of float
        ``(v_minus, v_plus)``: area (2D) or volume (3D) of Ω⁻ = {ψ_h < 0} and of
        Ω⁺ = {ψ_h > 0} inside the simplex.

    Examples
    --------
    >>> X = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    >>> [float(v) for v in subcell_volumes(X, np.array([-1.0, 1.0, 1.0]))]
    [0.125, 0.375]
    """
    raise NotImplementedError("subcell_volumes: not written yet (exercise 02, see README.md)")
