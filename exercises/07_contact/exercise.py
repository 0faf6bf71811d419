"""Exercise 07: the contact and friction updates of the paper's eq. 6-9 (see README.md).

Every function works on many law points at once: one point per row.  You may
import numpy; not skxfem.contact.laws or skxfem.contact (they hold the answers).
"""
import numpy as np  # noqa: F401  (you will need it)


def augmented_multiplier(lam, d_n, rho_n):
    """The augmented contact multiplier g_n = λ - ρ_n d_n (eq. 7).

    Parameters
    ----------
    lam : (n,) the contact multipliers λ (≤ 0 in contact).
    d_n : (n,) the normal gaps d_n = [[u]]·n (≤ 0 when admissible).
    rho_n : float > 0, the augmentation parameter.

    Returns
    -------
    ndarray
        (n,) g_n.

    Examples
    --------
    >>> augmented_multiplier(np.array([-1.0]), np.array([0.5]), 2.0).tolist()
    [-2.0]
    """
    raise NotImplementedError("augmented_multiplier: not written yet (exercise 07, see README.md)")


def normal_update(g):
    """The contact update χ(g) g (eq. 6) and its generalised derivative.

    χ is the indicator of ℝ⁻: χ(x) = 1 if x < 0, 0 if x ≥ 0.  The derivative of
    χ(g) g is χ(g) away from the kink g = 0 (1 in contact, 0 where the
    interface is open); at g = 0 any slope in [0, 1] is a generalised
    derivative (skxfem takes 1).

    Parameters
    ----------
    g : (n,) augmented multipliers g_n.

    Returns
    -------
    value, slope : (n,) arrays
        χ(g) g and d(χ(g) g)/dg.

    Examples
    --------
    >>> value, slope = normal_update(np.array([-2.0, 3.0]))
    >>> value.tolist(), slope.tolist()
    ([-2.0, 0.0], [1.0, 0.0])
    """
    raise NotImplementedError("normal_update: not written yet (exercise 07, see README.md)")


def ball_projection(g):
    """The projection P_B(0,1)(g) onto the unit ball (eq. 9c) and its Jacobian.

    P(g) = g for |g| ≤ 1 (adherence), g/|g| otherwise (sliding); its
    generalised Jacobian is I for |g| ≤ 1 and (I - ĝ ĝᵀ)/|g| for |g| > 1,
    ĝ = g/|g|.

    Parameters
    ----------
    g : (n, k) augmented semi-multipliers g_τ = Λ + ρ_τ v_τ, one per row
        (k = 1 in 2D, 2 in 3D).

    Returns
    -------
    P : (n, k) the projections.
    DP : (n, k, k) the Jacobians, DP[i, a, b] = ∂P_a/∂g_b at point i.

    Examples
    --------
    >>> P, DP = ball_projection(np.array([[0.5], [-3.0]]))
    >>> P.ravel().tolist(), DP.ravel().tolist()
    ([0.5, -1.0], [1.0, 0.0])
    """
    raise NotImplementedError("ball_projection: not written yet (exercise 07, see README.md)")
