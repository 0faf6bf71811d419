r"""The exact field of a closed inclined Griffith crack under compression, with friction.

A straight crack of length 2a (centre c, direction t = (cos β, sin β), normal
n = (-sin β, cos β)) in an infinite plate under the uniaxial compression σ_yy = -σ
(σ > 0) along the y axis: β is the angle between the load and the crack's normal.
The faces are pressed shut by p = σ cos² β and sheared by τ∞ = t·σ∞·n = -σ sin β cos β.
With Coulomb's friction μ they **stick** when |τ∞| ≤ μ p (μ ≥ tan β): the plate is
uniformly stressed and K = 0.  Otherwise they **slide**, each face carrying the shear
μ p against the slip, and the field is the uniform one plus that of a crack whose faces
are loaded by the shear τ_eff = τ∞ + sign(-τ∞) μ p left over:

.. math:: u = u^\infty + R\,[u^{II}_{\tau_{eff}} - u^{s}_{\tau_{eff}}](R^T(x - c)),

u^II the Westergaard mode II field of a crack |x'| < a under the remote shear τ_eff
(traction-free faces) and u^s the uniform shear τ_eff, both in the crack frame (x'
along t, y' along n).  Dolbow, Moës & Belytschko (2001):

.. math:: K_{II} = \sigma\sqrt{\pi a}\,(\sin\beta\cos\beta - \mu\cos^2\beta),\qquad K_I = 0,

in magnitude; in the package's tip frame (:mod:`skxfem.crack.frame`, e₂ = n) the sign
of K_II is that of -τ_eff at the tip ahead along +t and its opposite at the other.

Westergaard's mode II (Z = τ z/√(z² - a²), Ẑ = τ√(z² - a²), z = x' + i y'):
σ_x'x' = 2 Im Z + y' Re Z', σ_y'y' = -y' Re Z', σ_x'y' = Re Z - y' Im Z';
2μ u_x' = (κ+1)/2 Im Ẑ + y' Re Z, 2μ u_y' = -(κ-1)/2 Re Ẑ - y' Im Z (κ the Kolosov
constant, :func:`skxfem.crack.williams.kolosov`).  Checked: σ is Hooke's law of ∇u to
1e-10, the faces are traction-free, σ_x'y' √(2πr) → τ√(πa) at both tips.

>>> from skxfem.fem.material import Material
>>> c = InclinedCrack(a=0.2, beta=np.radians(30), sigma=1.0, friction=0.3)
>>> round(float(c.K_II), 6), round(float(c.pressure), 6), bool(c.slides)
(0.164884, 0.75, True)
>>> u, s = c.field(np.array([[0.5], [0.9]]), Material(1.0, 0.3))   # far from the crack
>>> s[:, :, 0].round(2).tolist()
[[0.0, 0.0], [0.0, -1.0]]
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..fem.material import Material
from .williams import kolosov, shear_modulus

__all__ = ["InclinedCrack", "westergaard_II"]


def westergaard_II(x: np.ndarray, a: float, tau: float, material: Material):
    """(u, σ) of Westergaard's mode II crack |x| < a, y = 0, under the remote shear
    ``tau`` (traction-free faces), at points x (2, ...) of its frame: u (2, ...),
    σ (2, 2, ...).  A point on the crack line takes the face y = +0 (x[1] = +0.0) or
    y = -0 (x[1] = -0.0).

    >>> from skxfem.fem.material import Material
    >>> u, s = westergaard_II(np.array([[0.1, 0.1], [0.0, -0.0]]), 0.3, 1.0,
    ...                       Material(1.0, 0.3))
    >>> bool(np.abs(s[:, 1]).max() < 1e-12), bool(u[0, 0] > 0 > u[0, 1])  # free; sliding
    (True, True)
    """
    x = np.asarray(x, float)
    mu, kappa = shear_modulus(material), kolosov(material)
    y = x[1]
    z = x[0] + 1j * np.where(y == 0, np.copysign(1e-300, y), y)
    R = np.sqrt(z - a) * np.sqrt(z + a)                 # cut on [-a, a] only
    Z, Zh = tau * z / R, tau * R
    Zp = tau / R - tau * z * z / R ** 3
    sxx = 2 * Z.imag + y * Zp.real
    syy = -y * Zp.real
    sxy = Z.real - y * Zp.imag
    u = np.array([((kappa + 1) / 2 * Zh.imag + y * Z.real) / (2 * mu),
                  (-(kappa - 1) / 2 * Zh.real - y * Z.imag) / (2 * mu)])
    return u, np.array([[sxx, sxy], [sxy, syy]])


@dataclass(frozen=True)
class InclinedCrack:
    """A closed inclined crack under compression with Coulomb friction (module notes).

    ``a`` the half-length, ``beta`` the angle (radians) between the load (y) and the
    crack's normal, ``sigma`` > 0 the compression, ``friction`` μ ≥ 0, ``center`` c."""

    a: float
    beta: float
    sigma: float = 1.0
    friction: float = 0.0
    center: tuple = (0.0, 0.0)

    def __post_init__(self):
        if not (self.a > 0 and self.sigma > 0 and self.friction >= 0):
            raise ValueError(f"InclinedCrack needs a > 0, sigma > 0 (a compression) and "
                             f"friction >= 0, got a={self.a!r}, sigma={self.sigma!r}, "
                             f"friction={self.friction!r}")
        if not 0 <= self.beta < np.pi / 2:
            raise ValueError(f"InclinedCrack beta must be in [0, π/2) (the crack's normal "
                             f"from the load), got {self.beta!r}")

    @property
    def tangent(self) -> np.ndarray:
        return np.array([np.cos(self.beta), np.sin(self.beta)])

    @property
    def normal(self) -> np.ndarray:
        """n = (-sin β, cos β): ψ = n·(x - c), Ω⁺ on its side."""
        return np.array([-np.sin(self.beta), np.cos(self.beta)])

    @property
    def pressure(self) -> float:
        """The contact pressure p = σ cos² β."""
        return self.sigma * np.cos(self.beta) ** 2

    @property
    def tau_inf(self) -> float:
        """τ∞ = t·σ∞·n = -σ sin β cos β."""
        return -self.sigma * np.sin(self.beta) * np.cos(self.beta)

    @property
    def slides(self) -> bool:
        """Whether the faces slide: |τ∞| > μ p (μ < tan β)."""
        return abs(self.tau_inf) > self.friction * self.pressure

    @property
    def tau_eff(self) -> float:
        """The shear the faces do not hold: τ∞ less the friction μ p (0 when they stick)."""
        if not self.slides:
            return 0.0
        return self.tau_inf - np.sign(self.tau_inf) * self.friction * self.pressure

    @property
    def K_II(self) -> float:
        """|K_II| = |τ_eff| √(πa) = σ√(πa)(sin β cos β - μ cos² β) when sliding, else 0."""
        return abs(self.tau_eff) * np.sqrt(np.pi * self.a)

    def tips(self) -> np.ndarray:
        """(2, 2) the tips c - a t and c + a t (columns)."""
        c = np.asarray(self.center, float)
        return np.stack([c - self.a * self.tangent, c + self.a * self.tangent], axis=1)

    def K_II_at(self, tip: np.ndarray) -> float:
        """K_II with its sign in the package's tip frame (e₁ ahead, e₂ = n) at ``tip``."""
        ahead = float(np.dot(np.asarray(tip, float) - np.asarray(self.center), self.tangent))
        return np.sign(ahead) * self.tau_eff * np.sqrt(np.pi * self.a)

    def psi(self, x):
        """ψ = n·(x - c) (the crack's line; Ω⁺ = {ψ > 0})."""
        c = np.asarray(self.center, float)
        return self.normal[0] * (x[0] - c[0]) + self.normal[1] * (x[1] - c[1])

    def phi(self, x):
        """φ = |t·(x - c)| - a (the crack where φ < 0; the two tips where φ = 0)."""
        c = np.asarray(self.center, float)
        return np.abs(self.tangent[0] * (x[0] - c[0]) + self.tangent[1] * (x[1] - c[1])) \
            - self.a

    def field(self, x: np.ndarray, material: Material):
        """(u, σ) of the exact field at points x (2, ...)."""
        x = np.asarray(x, float)
        lam, mu = material.lame(2)
        s_inf = np.array([[0.0, 0.0], [0.0, -self.sigma]])
        eps = (s_inf - lam / (2 * mu + 2 * lam) * np.trace(s_inf) * np.eye(2)) / (2 * mu)
        u = np.einsum("ij,j...->i...", eps, x)
        sig = np.broadcast_to(s_inf.reshape(2, 2, *(1,) * (x.ndim - 1)),
                              (2, 2) + x.shape[1:]).copy()
        tau = self.tau_eff
        if tau != 0.0:
            Rm = np.stack([self.tangent, self.normal], axis=1)   # local -> global
            d = x - np.asarray(self.center, float).reshape(2, *(1,) * (x.ndim - 1))
            xl = np.einsum("ji,j...->i...", Rm, d)
            ul, sl = westergaard_II(xl, self.a, tau, material)
            ul = ul - tau / (2 * mu) * np.stack([xl[1], xl[0]])   # less the uniform shear
            sl = sl - tau * np.array([[0.0, 1.0], [1.0, 0.0]]).reshape(
                2, 2, *(1,) * (x.ndim - 1))
            u = u + np.einsum("ij,j...->i...", Rm, ul)
            sig = sig + np.einsum("ik,kl...,jl->ij...", Rm, sl, Rm)
        return u, sig
