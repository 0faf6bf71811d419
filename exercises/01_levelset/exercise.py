"""Exercise 01: signed distances (see README.md).

Write the three functions below; each returns a level set, a function
``psi(x)`` of coordinates ``x`` of shape ``(dim, ...)`` (``x[0]`` is the first
coordinate, as in scikit-fem) returning an array of shape ``(...)``.
You may import numpy; not skxfem.levelset.
"""
import numpy as np  # noqa: F401  (you will need it)


def plane(point, normal):
    """Signed distance to the plane (a line in 2D) through ``point``.

    ψ(x) = (x - point)·n̂ with n̂ = normal/|normal|: Ω⁺ = {ψ > 0} lies on the
    side ``normal`` points to.

    Parameters
    ----------
    point : sequence of 2 or 3 floats, a point of the plane.
    normal : sequence of as many floats, non-zero, not necessarily unit.

    Returns
    -------
    callable
        ``psi(x)`` for ``x`` of shape ``(dim, ...)``, returning shape ``(...)``.

    Examples
    --------
    >>> psi = plane((0.0, 0.5), (0.0, 2.0))
    >>> psi(np.array([[0.2, 0.2], [0.0, 1.0]])).tolist()
    [-0.5, 0.5]
    """
    raise NotImplementedError("plane: not written yet (exercise 01, see README.md)")


def circle(center, radius):
    """Signed distance to a circle: negative inside (Ω⁻ is the disc).

    ψ(x) = |x - center| - radius.

    Parameters
    ----------
    center : sequence of 2 floats.
    radius : positive float.

    Returns
    -------
    callable
        ``psi(x)`` for ``x`` of shape ``(2, ...)``, returning shape ``(...)``.

    Examples
    --------
    >>> float(circle((0.0, 0.0), 1.0)(np.array([2.0, 0.0])))
    1.0
    """
    raise NotImplementedError("circle: not written yet (exercise 01, see README.md)")


def sphere(center, radius):
    """Signed distance to a sphere: negative inside (Ω⁻ is the ball).

    ψ(x) = |x - center| - radius.

    Parameters
    ----------
    center : sequence of 3 floats.
    radius : positive float.

    Returns
    -------
    callable
        ``psi(x)`` for ``x`` of shape ``(3, ...)``, returning shape ``(...)``.

    Examples
    --------
    >>> float(sphere((0.0, 0.0, 0.0), 1.0)(np.array([0.0, 0.0, 0.5])))
    -0.5
    """
    raise NotImplementedError("sphere: not written yet (exercise 01, see README.md)")
