r"""The local contact and friction laws of the paper (eq. 5–9) and their generalised Jacobians.

Signorini's law d_n ≤ 0, λ ≤ 0, λ d_n = 0 (eq. 5; d_n = [[u]]·n, λ ≤ 0 in
contact, p = -λ) is the single equation (eq. 6–7)

.. math:: \lambda - \chi(g_n)\, g_n = 0, \qquad g_n = \lambda - \rho_n d_n,

with χ the indicator of ℝ⁻ (χ(x) = 1 if x < 0, 0 if x ≥ 0).  Coulomb's law
(eq. 8) with r_τ = μ λ Λ (eq. 9a) is

.. math:: \Lambda - P_{B(0,1)}(\mathbf g_\tau) = 0, \qquad
          \mathbf g_\tau = \Lambda + \rho_\tau \mathbf v_\tau,

P_B the projection on the unit ball (eq. 9b–c).  Multiplied by μλ ≤ 0 this is
the same law written on the tangential *traction*, which the solver uses
because it stays bounded where the pressure vanishes (Λ = r_τ/(μλ) does not):

.. math:: \mathbf r_\tau - P_{B(0,R)}(\mathbf r_\tau - \rho_\tau \mathbf s) = 0,
          \qquad R = \mu\,\max(0, -g_n),

with s = v_τ Δt the slip increment and P_{B(0,R)} the projection on the ball
of radius R (:func:`disk_projection`; R = μp at a closed point, 0 at an open
one: Alart and Curnier's augmented form).  Its solutions are those of eq. 9
for every ρ_τ > 0, now with ρ_τ a traction per length like ρ_n.

The generalised (Clarke) Jacobians used by the semi-smooth Newton method of
:mod:`skxfem.contact.newton`:

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

from ..scene.laws import CONTACT_LAWS, LAWS, LawKind

__all__ = ["CONTACT_LAWS", "HISTORY_LAWS", "LawKind", "LAWS", "OPEN", "STICK", "SLIP",
           "STATUS_NAMES", "indicator", "normal_update", "ball_projection",
           "disk_projection", "status"]

HISTORY_LAWS = tuple(name for name, law in LAWS.items() if law.coupling != "none")
"""The laws of a load state: the contact laws, and the ties ``bilateral`` (tension
carried, free sliding) and ``bonded`` (no further slip) a state may switch to."""

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


def disk_projection(y: np.ndarray, radius: np.ndarray):
    """The projection P_{B(0,R)}(y) on the ball of radius R ≥ 0 and its derivatives.

    Parameters
    ----------
    y
        (n, k) augmented tangential tractions r_τ - ρ_τ s.
    radius
        (n,) radii R ≥ 0 (μ max(0, -g_n) for Coulomb).

    Returns
    -------
    P, DP, dP_dR
        (n, k) projections, (n, k, k) dP/dy and (n, k) dP/dR.  Inside
        (|y| ≤ R, the stick branch, R = 0 = |y| included): P = y, DP = I,
        dP/dR = 0; outside: P = R ŷ, DP = R (I - ŷŷᵀ)/|y|, dP/dR = ŷ.  For R > 0
        this is R·P_B(y/R) (:func:`ball_projection`).

    >>> P, DP, dR = disk_projection(np.array([[3.0, 4.0], [0.3, 0.4]]), np.array([2.0, 2.0]))
    >>> P.tolist(), dR.tolist()
    ([[1.2, 1.6], [0.3, 0.4]], [[0.6, 0.8], [0.0, 0.0]])
    """
    y = np.asarray(y, dtype=float)
    R = np.asarray(radius, dtype=float)
    n, k = y.shape
    norm = np.linalg.norm(y, axis=1)
    out = norm > R
    P, DP, dR = y.copy(), np.broadcast_to(np.eye(k), (n, k, k)).copy(), np.zeros((n, k))
    yh = y[out] / norm[out, None]  # ŷ, without dividing by R (R may underflow)
    scale = R[out] / norm[out]
    P[out] = R[out, None] * yh
    DP[out] = scale[:, None, None] * (np.eye(k) - yh[:, :, None] * yh[:, None, :])
    dR[out] = yh
    return P, DP, dR


def status(g_n: np.ndarray, y: np.ndarray | None, radius: np.ndarray | None,
           kinds) -> np.ndarray:
    """Status of each law point: :data:`OPEN`, :data:`STICK` or :data:`SLIP`.

    ``kinds``: a law name or (n,) of names (:data:`skxfem.scene.laws.LAWS`).  A point is open
    where its law is unilateral and g_n ≥ 0 (χ(g_n) = 0); a closed point slips
    freely (``free``), never (``stick``) or where |y| > R (``coulomb``; y, R as
    :func:`disk_projection`; a point exactly on the limit sticks).

    >>> status(np.array([1.0, -1.0, -1.0]), np.array([[0.0], [0.5], [2.0]]),
    ...        np.ones(3), "coulomb")
    array([0, 1, 2])
    """
    g_n = np.asarray(g_n, dtype=float)
    names = np.broadcast_to(np.asarray(kinds, dtype=object), g_n.shape)
    bad = set(names.tolist()) - set(LAWS)
    if bad:
        raise ValueError(f"law must be one of {HISTORY_LAWS}, got {sorted(bad)[0]!r}")
    uni = np.array([LAWS[k].unilateral for k in names.tolist()], dtype=bool)
    tang = np.array([LAWS[k].tangential for k in names.tolist()], dtype=object)
    closed = ~uni | (indicator(g_n) > 0)
    slip = tang == "free"
    if np.any(tang == "coulomb"):
        c = tang == "coulomb"
        slip[c] = np.linalg.norm(y[c], axis=1) > radius[c]
    return np.where(closed, np.where(slip, SLIP, STICK), OPEN)
