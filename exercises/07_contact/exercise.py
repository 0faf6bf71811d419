"""Exercise 07: the contact and friction updates of the paper's eq. 6-9 (see README.md).

Every function works point by point on arrays.  A tangential vector field has
its components first: shape (k, ...) with k = 1 or 2 tangential components
(skxfem's layout).  You may import numpy; not skxfem.contact.
"""
import numpy as np  # noqa: F401  (you will need it)


def augmented_multiplier(lam, d_n, rho_n):
    """The augmented contact multiplier g_n = λ - ρ_n d_n (eq. 7).

    Parameters
    ----------
    lam : float or array, the contact multiplier λ (≤ 0 in contact).
    d_n : float or array, the normal gap d_n = [[u]]·n (≤ 0 when admissible).
    rho_n : float > 0, the augmentation parameter.

    Returns
    -------
    ndarray or float, like ``lam``.

    Examples
    --------
    >>> float(augmented_multiplier(-1.0, 0.5, 2.0))
    -2.0
    """
    raise NotImplementedError("augmented_multiplier: not written yet (exercise 07, see README.md)")


def contact_update(g_n):
    """χ(g_n) g_n, the value eq. 6 gives λ: g_n in contact (g_n < 0), 0 when open.

    χ is the indicator function of ℝ⁻: χ(x) = 1 if x < 0 and 0 if x ≥ 0.

    Examples
    --------
    >>> contact_update(np.array([-2.0, 0.5])).tolist()
    [-2.0, 0.0]
    """
    raise NotImplementedError("contact_update: not written yet (exercise 07, see README.md)")


def contact_derivative(g_n):
    """The generalised derivative of g_n ↦ χ(g_n) g_n: 1 where g_n < 0, 0 where g_n ≥ 0.

    This is the Newton Jacobian of the contact term: the active branch (contact)
    and the inactive branch (open) differ.

    Examples
    --------
    >>> contact_derivative(np.array([-2.0, 0.5])).tolist()
    [1.0, 0.0]
    """
    raise NotImplementedError("contact_derivative: not written yet (exercise 07, see README.md)")


def project_unit_ball(g):
    """P_B(0,1)(g): the projection onto the unit ball (eq. 9c).

    g if |g| ≤ 1 (adherence), g/|g| otherwise (sliding).

    Parameters
    ----------
    g : (k, ...) array, the augmented semi-multiplier of friction g_τ = Λ + ρ_τ v_τ.

    Returns
    -------
    ndarray
        Shape (k, ...).

    Examples
    --------
    >>> project_unit_ball(np.array([[0.3, 3.0], [0.4, 4.0]])).tolist()
    [[0.3, 0.6], [0.4, 0.8]]
    """
    raise NotImplementedError("project_unit_ball: not written yet (exercise 07, see README.md)")


def project_unit_ball_derivative(g):
    """The generalised derivative of P_B(0,1) at g: a (k, k) matrix per point.

    I inside the ball (|g| < 1); (I - ĝ ĝᵀ)/|g| outside, ĝ = g/|g| (take the
    outside formula at |g| = 1).

    Parameters
    ----------
    g : (k, ...) array.

    Returns
    -------
    ndarray
        Shape (k, k, ...): entry [i, j] is ∂P_i/∂g_j.

    Examples
    --------
    >>> project_unit_ball_derivative(np.array([2.0, 0.0])).tolist()
    [[0.0, 0.0], [0.0, 0.5]]
    """
    raise NotImplementedError(
        "project_unit_ball_derivative: not written yet (exercise 07, see README.md)")
