r"""The four branch functions of the crack tip and their gradients.

Near the front the displacement of every mode is √r times a function of θ
(:mod:`skxfem.crack.williams`); the four functions

.. math:: F_l(r, \theta) = \sqrt r \,\Bigl\{\sin\frac\theta2,\ \cos\frac\theta2,\
          \sin\frac\theta2 \sin\theta,\ \cos\frac\theta2 \sin\theta\Bigr\},
          \qquad l = 1..4,

span them all (Moës, Dolbow & Belytschko 1999), so the X-FEM adds them to the
nodes near the front.  (r, θ) are the polar coordinates of the tip frame
(:mod:`skxfem.crack.frame`): θ = ±π on the faces.  Only F₁ is discontinuous
there: F₁(θ = π) - F₁(θ = -π) = 2√r, while F₂, F₃, F₄ take the same value on
both faces (cos(±π/2) = 0 and sin(±π) = 0).  F₁ gives the jump, the others the
singular strain.

Derivatives in polar coordinates
--------------------------------
With s = sin(θ/2), c = cos(θ/2),

.. math::
   \partial_r F_l = \frac{F_l}{2r}, \qquad
   \partial_\theta F_l = \sqrt r \,\Bigl\{\frac c2,\ -\frac s2,\
   \frac c2 \sin\theta + s\cos\theta,\ -\frac s2 \sin\theta + c \cos\theta\Bigr\}.

Gradient in the tip frame, then in the global frame
---------------------------------------------------
By the chain rule through r = √(x₁² + x₂²), θ = atan2(x₂, x₁), whose
gradients are ∇r = cos θ e₁ + sin θ e₂ and ∇θ = (-sin θ e₁ + cos θ e₂)/r,

.. math::
   \frac{\partial F}{\partial x_1} = \cos\theta\,\partial_r F - \frac{\sin\theta}{r}\,
   \partial_\theta F, \qquad
   \frac{\partial F}{\partial x_2} = \sin\theta\,\partial_r F + \frac{\cos\theta}{r}\,
   \partial_\theta F,

and in the global frame ∇F = ∂F/∂x₁ e₁ + ∂F/∂x₂ e₂.  For F₁ and F₂ this is
the classic ∇F₁ = (-s e₁ + c e₂)/(2√r), ∇F₂ = (c e₁ + s e₂)/(2√r).  Every
gradient is of order 1/√r: square-integrable, so the enriched energy is finite.
In 3D the functions do not vary along e₃ (the front is straight at the scale of
the frame; a curved front adds terms of order √r times its curvature, neglected).

>>> import numpy as np
>>> F = branch(4.0, np.pi)                       # on the face of Ω⁺, r = 4
>>> np.round(F, 12).tolist()
[2.0, 0.0, 0.0, 0.0]
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .frame import TipFrame, as_real

__all__ = ["branch", "branch_polar_derivatives", "branch_local_gradient", "branch_gradient",
           "branch_closed_form", "side_angle"]


def _polar(r: ArrayLike, theta: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    r, theta = as_real("r", r), as_real("theta", theta)
    if r.shape != theta.shape:
        raise ValueError(f"r and theta must have the same shape, got {r.shape} and "
                         f"{theta.shape}")
    if np.any(r < 0):
        raise ValueError("r must be non-negative: it is the distance to the front")
    if np.any(np.abs(theta) > np.pi):
        raise ValueError("theta must lie in [-pi, pi] (±pi on the crack faces)")
    return r, theta


def branch(r: ArrayLike, theta: ArrayLike) -> np.ndarray:
    """The four branch functions F_l(r, θ), shape (4, ...).

    Parameters
    ----------
    r, theta : arrays of one shape: polar coordinates of the tip frame, r ≥ 0,
        θ ∈ [-π, π] (:func:`skxfem.crack.frame.polar`).

    Returns
    -------
    ndarray
        √r {sin θ/2, cos θ/2, sin θ/2 sin θ, cos θ/2 sin θ}, the index l first.

    Examples
    --------
    >>> np.round(branch(1.0, np.pi / 2), 12).tolist()
    [0.707106781187, 0.707106781187, 0.707106781187, 0.707106781187]
    """
    r, theta = _polar(r, theta)
    sr, s, c, st = np.sqrt(r), np.sin(theta / 2), np.cos(theta / 2), np.sin(theta)
    return sr * np.stack([s, c, s * st, c * st])


def branch_polar_derivatives(r: ArrayLike, theta: ArrayLike
                             ) -> tuple[np.ndarray, np.ndarray]:
    """∂F_l/∂r and ∂F_l/∂θ, each of shape (4, ...); r > 0.

    Examples
    --------
    >>> dr, dt = branch_polar_derivatives(4.0, 0.0)
    >>> dr.tolist(), dt.tolist()
    ([0.0, 0.25, 0.0, 0.0], [1.0, -0.0, 0.0, 2.0])
    """
    r, theta = _polar(r, theta)
    if np.any(r == 0):
        raise ValueError("r must be positive: the branch functions' derivatives are "
                         "singular on the front (r = 0)")
    sr, s, c = np.sqrt(r), np.sin(theta / 2), np.cos(theta / 2)
    st, ct = np.sin(theta), np.cos(theta)
    d_r = np.stack([s, c, s * st, c * st]) / (2 * sr)
    d_theta = sr * np.stack([c / 2, -s / 2, c / 2 * st + s * ct, -s / 2 * st + c * ct])
    return d_r, d_theta


def branch_local_gradient(r: ArrayLike, theta: ArrayLike) -> np.ndarray:
    """∂F_l/∂x_a in the tip frame, shape (4, 2, ...): l the function, a = 1, 2.

    The chain rule of the module notes; r > 0.

    Examples
    --------
    >>> g = branch_local_gradient(1.0, 0.0)          # ahead of the tip, r = 1
    >>> g[:2].tolist()                               # ∇F₁ = e₂/2, ∇F₂ = e₁/2
    [[0.0, 0.5], [0.5, 0.0]]
    """
    r, theta = _polar(r, theta)
    d_r, d_theta = branch_polar_derivatives(r, theta)
    ct, st = np.cos(theta), np.sin(theta)
    return np.stack([ct * d_r - st / r * d_theta, st * d_r + ct / r * d_theta], axis=1)


def branch_gradient(r: ArrayLike, theta: ArrayLike, frame: TipFrame) -> np.ndarray:
    """∇F_l in the global frame, shape (4, dim, ...): ∂F/∂x₁ e₁ + ∂F/∂x₂ e₂.

    ``frame`` is one frame (vectors (dim,)) or one per point (dim, ...) of the
    shape of ``r``.

    Examples
    --------
    >>> from skxfem.crack.frame import straight_frame
    >>> f = straight_frame([0.0, 1.0], [-1.0, 0.0])  # e₁ = y, e₂ = -x
    >>> branch_gradient(1.0, 0.0, f)[0].tolist()    # ∇F₁ = e₂/2 ahead of the tip
    [-0.5, 0.0]
    """
    g = branch_local_gradient(r, theta)
    e1, e2 = (e.reshape(e.shape[:1] + (1,) * (g.ndim - 2 - e.ndim + 1) + e.shape[1:])
              for e in (frame.e1, frame.e2))
    return g[:, 0:1] * e1[None] + g[:, 1:2] * e2[None]


def branch_closed_form(r: np.ndarray, theta: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""F_l and ∂F_l/∂x₁, ∂F_l/∂x₂ in the tip frame at once, each (..., 4) (the index l
    last, for the arrays of cells and points), in closed form: one sine and one cosine of
    θ/2 per point.  Zero where r = 0.  No checks: for the loops over quadrature points
    (the 3D space, :mod:`skxfem.crack.space3d`); r ≥ 0 and θ ∈ [-π, π] as :func:`branch`.

    With s, c = sin, cos θ/2 the chain rule of :func:`branch_local_gradient` reads

    .. math::
       \frac{\partial F}{\partial x_1} = \frac{\{-s,\ c,\ -\sin\tfrac{3\theta}2
       \sin\theta,\ -\cos\tfrac{3\theta}2 \sin\theta\}}{2\sqrt r}, \qquad
       \frac{\partial F}{\partial x_2} = \frac{\{c,\ s,\ s + \sin\tfrac{3\theta}2
       \cos\theta,\ c + \cos\tfrac{3\theta}2 \cos\theta\}}{2\sqrt r},

    sin θ, cos θ and sin, cos 3θ/2 taken from s and c by the double- and triple-angle
    formulas.

    >>> F, d1, d2 = branch_closed_form(np.array([1.0, 0.0]), np.array([0.0, 0.0]))
    >>> F.tolist()                                    # ahead of the tip, r = 1; r = 0
    [[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]]
    >>> (d1[0] + 0.0).tolist(), d2[0].tolist()        # ∇F₂ = e₁/2, ∇F₁ = e₂/2
    ([0.0, 0.5, 0.0, 0.0], [0.5, 0.0, 0.0, 1.0])
    """
    live = r > 0
    sr = np.sqrt(np.where(live, r, 1.0))
    half = np.where(live, theta, 0.0) / 2
    s, c = np.sin(half), np.cos(half)
    st, ct = 2 * s * c, 1 - 2 * s * s                    # sin θ, cos θ
    s3, c3 = s * (3 - 4 * s * s), c * (4 * c * c - 3)     # sin 3θ/2, cos 3θ/2
    on = (live / (2 * sr))[..., None]
    F = np.stack([s, c, s * st, c * st], axis=-1) * (sr * live)[..., None]
    d1 = np.stack([-s, c, -s3 * st, -c3 * st], axis=-1) * on
    d2 = np.stack([c, s, s + s3 * ct, c + c3 * ct], axis=-1) * on
    return F, d1, d2


def side_angle(phi: ArrayLike, psi: ArrayLike, side: ArrayLike, cut: ArrayLike) -> np.ndarray:
    """θ = atan2(ψ, φ) at points of a crack's cells, from the interpolated level sets
    ``phi``, ``psi``, on ``side`` (±1: the side of the point's cell or sub-cell; 0:
    padding), ``cut`` whether the point's cell is one the crack cuts (a split, tip or
    front cell).  In a cut cell, where φ < 0 and ψ has not the side's sign (a point on
    a face, or rounding), θ is ±π by the side, so a point counts on its own face; only
    there: a cell that ψ crosses ahead of the front is cut by no crack, and atan2 is
    continuous in it (forcing θ there made the branch functions jump inside it).  The
    one rule of the 2D and 3D spaces and of the 3D interaction integral.

    >>> side_angle([-1.0, -1.0], [1e-17, 1e-17], [-1.0, -1.0], [True, False]).tolist()
    [-3.141592653589793, 3.141592653589793]
    """
    phi, psi, side = (np.asarray(v, float) for v in (phi, psi, side))
    wrong = (phi < 0) & (np.sign(psi) != side) & (side != 0) & np.asarray(cut, bool)
    return np.where(wrong, side * np.pi, np.arctan2(psi, phi))
