r"""The local contact and friction laws of the paper (eq. 5–9) and their generalised Jacobians.

Signorini's law d_n ≤ 0, λ ≤ 0, λ d_n = 0 (eq. 5; d_n = [[u]]·n, λ ≤ 0 in
contact, p = -λ) is the single equation (eq. 6–7)

.. math:: \lambda - \chi(g_n)\, g_n = 0, \qquad g_n = \lambda - \rho_n d_n,

with χ the indicator of ℝ⁻ (χ(x) = 1 if x < 0, 0 if x ≥ 0).  Coulomb's law
(eq. 8) with r_τ = μ λ Λ (eq. 9a) is

.. math:: \Lambda - P_{B(0,1)}(\mathbf g_\tau) = 0, \qquad
          \mathbf g_\tau = \Lambda + \rho_\tau \mathbf v_\tau,

P_B the projection on the unit ball (eq. 9b–c).  Both maps are piecewise
smooth; their generalised (Clarke) Jacobians, used by the semi-smooth Newton
method of :mod:`skxfem.contact`, are

* d(χ(g) g)/dg = χ(g), and 1 at the kink g = 0 (any slope in [0, 1] is a
  generalised derivative there; 1, the contact branch, makes the first Newton
  iteration from an untouched interface, λ = d = 0, the bilateral solve);
* D P_B(g) = I for |g| ≤ 1, (I - ĝ ĝᵀ)/|g| for |g| > 1 (ĝ = g/|g|).

Arrays hold one law per row: ``g`` (n,) for the normal law and (n, k) for
the tangential one (k = 1 in 2D, 2 in 3D).

>>> import numpy as np
>>> value, slope = normal_update(np.array([-2.0, 3.0]))
>>> value.tolist(), slope.tolist()
([-2.0, 0.0], [1.0, 0.0])
>>> P, DP = ball_projection(np.array([[0.5], [-3.0]]))
>>> P.ravel().tolist(), DP.ravel().tolist()
([0.5, -1.0], [1.0, 0.0])
"""
from __future__ import annotations

import numpy as np

__all__ = ["CONTACT_LAWS", "OPEN", "STICK", "SLIP", "STATUS_NAMES", "indicator",
           "normal_update", "ball_projection", "status", "friction_coefficient", "held",
           "just_closed"]

CONTACT_LAWS = ("frictionless", "coulomb", "adhesive")
"""Unilateral laws: no friction, Coulomb friction (μ), no slip in contact."""

OPEN, STICK, SLIP = 0, 1, 2
STATUS_NAMES = ("open", "stick", "slip")


def indicator(x: np.ndarray) -> np.ndarray:
    """χ(x): 1.0 where x < 0, 0.0 where x ≥ 0 (the indicator of ℝ⁻)."""
    return (np.asarray(x) < 0).astype(float)


def normal_update(g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The contact update χ(g) g (eq. 6) and its generalised derivative.

    Parameters
    ----------
    g
        (n,) augmented multipliers g_n = λ - ρ_n d_n (eq. 7).

    Returns
    -------
    value, slope
        (n,) χ(g) g and d(χ(g) g)/dg: χ(g), and 1 at g = 0.
    """
    g = np.asarray(g, dtype=float)
    return indicator(g) * g, (g <= 0).astype(float)


def ball_projection(g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The projection P_B(0,1)(g) on the unit ball (eq. 9c) and its Jacobian.

    Parameters
    ----------
    g
        (n, k) augmented semi-multipliers g_τ = Λ + ρ_τ v_τ (eq. 9b).

    Returns
    -------
    P, DP
        (n, k) projections and (n, k, k) generalised Jacobians dP/dg.

    >>> P, DP = ball_projection(np.array([[3.0, 4.0]]))
    >>> P.tolist(), (DP[0] * 125).round(12).tolist()
    ([[0.6, 0.8]], [[16.0, -12.0], [-12.0, 9.0]])
    """
    g = np.asarray(g, dtype=float)
    n, k = g.shape
    norm = np.linalg.norm(g, axis=1)
    out = norm > 1.0
    P = g.copy()
    P[out] /= norm[out, None]
    DP = np.broadcast_to(np.eye(k), (n, k, k)).copy()
    gh = P[out]  # unit vectors ĝ
    DP[out] = (np.eye(k) - gh[:, :, None] * gh[:, None, :]) / norm[out, None, None]
    return P, DP


def status(g_n: np.ndarray, g_t: np.ndarray | None, law: str) -> np.ndarray:
    """Status of each law point: :data:`OPEN`, :data:`STICK` or :data:`SLIP`.

    A point is open where χ(g_n) = 0; a closed point slips where |g_τ| > 1
    (``coulomb``), always (``frictionless``) or never (``adhesive``).

    >>> status(np.array([1.0, -1.0, -1.0]), np.array([[0.0], [0.5], [2.0]]), "coulomb")
    array([0, 1, 2])
    """
    closed = indicator(g_n) > 0
    if law == "frictionless":
        slip = np.ones(closed.size, bool)
    elif law == "adhesive":
        slip = np.zeros(closed.size, bool)
    elif law == "coulomb":
        slip = np.linalg.norm(g_t, axis=1) > 1.0
    else:
        raise ValueError(f"law must be one of {CONTACT_LAWS}, got {law!r}")
    return np.where(closed, np.where(slip, SLIP, STICK), OPEN)


# The friction law's linearisation; ``law`` is a skxfem.contact_newton.Law.

def friction_coefficient(law, lam: np.ndarray) -> np.ndarray:
    """The factor of Λ in r_τ: μλ, or the frozen threshold (the paper's fixed point)."""
    return law.mu * lam if law.threshold is None else law.threshold


def held(law, g_n: np.ndarray) -> np.ndarray:
    """Closed points whose frozen threshold is 0: r_τ = 0 whatever Λ, which is held."""
    if law.threshold is None:
        return np.zeros(g_n.size, bool)
    return (normal_update(g_n)[1] > 0) & (law.threshold == 0)


def just_closed(law, lam: np.ndarray, g_n: np.ndarray) -> np.ndarray:
    """Closed points where λ = 0 (to 1e-12 of the largest |λ|): Λ has no coefficient."""
    closed = normal_update(g_n)[1] > 0
    if law.name != "coulomb" or law.threshold is not None:
        return np.zeros(lam.size, bool)
    return closed & (np.abs(lam) <= 1e-12 * (np.abs(lam).max() if lam.size else 0.0))
