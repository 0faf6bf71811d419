"""Exercise 04: the naive multiplier space on a 2D interface (see README.md).

Γ_h is a polyline: ``points`` (2, ne) are the intersection points (one
multiplier λ_e each) and ``segments`` (2, nf) index pairs into them (the
interface facets, ``Cut.facets`` in skxfem.cut).  λ_h is linear on each
segment (eq. 12).  You may import numpy; not skxfem.multipliers.
"""
import numpy as np  # noqa: F401  (you will need it)


def interpolate(lam, segments, k, s):
    """λ_h at the point of parameter ``s`` along segment ``k``.

    The segment runs from point ``segments[0, k]`` (s = 0) to ``segments[1, k]``
    (s = 1); λ_h = (1 - s) λ_a + s λ_b, the P1 interpolation of eq. 12.

    Parameters
    ----------
    lam : (ne,) the multipliers at the points.
    segments : (2, nf) int array.
    k : int, the segment.
    s : float in [0, 1].

    Returns
    -------
    float

    Examples
    --------
    >>> float(interpolate(np.array([1.0, 3.0]), np.array([[0], [1]]), 0, 0.25))
    1.5
    """
    raise NotImplementedError("interpolate: not written yet (exercise 04, see README.md)")


def interface_mass(points, segments):
    """The mass matrix of the multipliers on Γ_h: M_ef = ∫_Γh N_e N_f.

    N_e is the P1 function of point e along the polyline (1 at point e, 0 at the
    other points, linear on each segment).  On a segment of length L with end
    points a, b the contribution is L/6 [[2, 1], [1, 2]] in rows/columns (a, b).

    Parameters
    ----------
    points : (2, ne) float array.
    segments : (2, nf) int array.

    Returns
    -------
    ndarray
        Shape (ne, ne), symmetric; its entries sum to |Γ_h|.

    Examples
    --------
    >>> points = np.array([[0.0, 3.0], [0.0, 0.0]])
    >>> (interface_mass(points, np.array([[0], [1]])) * 2).tolist()
    [[2.0, 1.0], [1.0, 2.0]]
    """
    raise NotImplementedError("interface_mass: not written yet (exercise 04, see README.md)")
