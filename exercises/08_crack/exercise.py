"""Exercise 08: the crack-tip branch functions and their gradients (see README.md).

Points are given by their coordinates in the tip frame, x₁ = φ (ahead of the
crack) and x₂ = ψ (into Ω⁺); every function works on arrays, point by point.
You may import numpy; not skxfem.crack.
"""
import numpy as np  # noqa: F401  (you will need it)


def polar_coordinates(x1, x2):
    """Polar coordinates (r, θ) around the tip of points of tip-frame coordinates (x₁, x₂).

    r = √(x₁² + x₂²) and θ = atan2(x₂, x₁) ∈ [-π, π]: θ = 0 ahead of the crack,
    θ > 0 on the Ω⁺ side (x₂ > 0), θ = ±π on the crack faces (x₂ = ±0, x₁ < 0).

    Parameters
    ----------
    x1, x2 : arrays of one shape.

    Returns
    -------
    tuple of ndarray
        ``(r, theta)``, each of the shape of ``x1``.

    Examples
    --------
    >>> r, theta = polar_coordinates(np.array([3.0, 0.0]), np.array([4.0, -2.0]))
    >>> r.tolist(), (theta / np.pi).tolist()
    ([5.0, 2.0], [0.2951672353008665, -0.5])
    """
    raise NotImplementedError("polar_coordinates: not written yet (exercise 08, see README.md)")


def branch_functions(r, theta):
    """The four branch functions √r {sin θ/2, cos θ/2, sin θ/2 sin θ, cos θ/2 sin θ}.

    Parameters
    ----------
    r, theta : arrays of one shape, r ≥ 0 and θ ∈ [-π, π].

    Returns
    -------
    ndarray
        Shape ``(4,) + r.shape``: F₁, F₂, F₃, F₄ in that order.

    Examples
    --------
    >>> np.round(branch_functions(np.array([4.0]), np.array([np.pi])), 12).tolist()
    [[2.0], [0.0], [0.0], [0.0]]
    """
    raise NotImplementedError("branch_functions: not written yet (exercise 08, see README.md)")


def branch_gradients(r, theta):
    """The gradients ∂F_l/∂x_a of the four branch functions, in the tip frame.

    Parameters
    ----------
    r, theta : arrays of one shape, r > 0 and θ ∈ [-π, π].

    Returns
    -------
    ndarray
        Shape ``(4, 2) + r.shape``: entry ``[l, a]`` is ∂F_{l+1}/∂x_{a+1}.

    Examples
    --------
    >>> branch_gradients(np.array([1.0]), np.array([0.0]))[:2].tolist()   # ahead, r = 1
    [[[0.0], [0.5]], [[0.5], [0.0]]]
    """
    raise NotImplementedError("branch_gradients: not written yet (exercise 08, see README.md)")
