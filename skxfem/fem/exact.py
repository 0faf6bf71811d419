r"""An exact solution for the paper's plate: where p(y) really is the contact pressure.

The paper compares its contact pressure with "the analytical solution ...
equal to the prescribed pressure p(y)".  For an elastic block with a clamped
bottom that is only true of the resultant: the pressure spreads with depth.
This module supplies loads under which it is exactly true, so that errors
and convergence rates can be measured against a known answer.

In the 2D strip's coordinates (x across, y up; the plate's y and z), the Airy
stress function Φ = -P(2x³/3 - x⁴/3) - P y⁴/3 is biharmonic
(Φ_xxxx + Φ_yyyy = 8P - 8P = 0) and gives

.. math:: \sigma_{yy} = \Phi_{,xx} = -4P x(1-x), \quad
          \sigma_{xx} = \Phi_{,yy} = -4P y^2, \quad \sigma_{xy} = 0 :

the paper's parabolic pressure on the top y = 1, a pressure 4Py² on the sides
x = 0 and x = 1, and on *every* horizontal plane — in particular on Γ — a
contact pressure exactly p(x) = 4Px(1 - x) with no tangential traction.
Integrating the strains (E' = E/(1-ν²), ν' = ν/(1-ν) in plane strain;
E' = E, ν' = ν in plane stress) gives the displacement

.. math:: u_x = \frac{P}{E'}\Big(2y^2 - 4xy^2 + \nu'(2x^2 - \tfrac{4}{3}x^3)\Big),\quad
          u_y = \frac{P}{E'}\Big(-4x(1-x)y + \tfrac{4}{3}\nu' y^3\Big),

which the scenes impose on the bottom.  In 3D (plate coordinates x, y, z with
rollers on x = 0, 1) the same field lives in (y, z) and u_x = 0.

>>> sol = ExactPlate(Material(1.0, 0.3), dim=2)
>>> x = np.array([[0.25], [0.5]])
>>> float(sol.pressure(x)[0])           # 4 * 0.25 * 0.75
0.75
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .material import Material

__all__ = ["ExactPlate", "UniformContact"]


@dataclass(frozen=True)
class ExactPlate:
    """The exact plate/strip solution for ``material`` in ``dim`` = 2 or 3."""

    material: Material
    dim: int = 2
    P: float = 1.0

    def _plane(self, x):
        """The in-plane coordinates (across, up) of points x (dim, ...)."""
        return (x[0], x[1]) if self.dim == 2 else (x[1], x[2])

    def _constants(self):
        E, nu = self.material.E, self.material.nu
        if self.dim == 2 and self.material.plane == "stress":
            return E, nu
        return E / (1 - nu ** 2), nu / (1 - nu)

    def pressure(self, x):
        """Contact pressure -σ_nn on any horizontal plane: p = 4P s(1 - s)."""
        s, _ = self._plane(x)
        return 4 * self.P * s * (1 - s)

    def side_pressure(self, x):
        """Pressure on the vertical sides: 4P t² (t the height)."""
        _, t = self._plane(x)
        return 4 * self.P * t ** 2

    def displacement(self, x):
        """u at points x, shape (dim, ...)."""
        s, t = self._plane(x)
        Ep, nup = self._constants()
        us = self.P / Ep * (2 * t ** 2 - 4 * s * t ** 2 + nup * (2 * s ** 2 - 4 / 3 * s ** 3))
        ut = self.P / Ep * (-4 * s * (1 - s) * t + 4 / 3 * nup * t ** 3)
        if self.dim == 2:
            return np.array([us, ut])
        return np.array([0 * us, us, ut])

    def strain(self, x):
        """ε(u) at points x, shape (dim, dim, ...)."""
        s, t = self._plane(x)
        Ep, nup = self._constants()
        ess = self.P / Ep * (-4 * t ** 2 + nup * 4 * s * (1 - s))
        ett = self.P / Ep * (-4 * s * (1 - s) + nup * 4 * t ** 2)
        z = 0 * s
        if self.dim == 2:
            return np.array([[ess, z], [z, ett]])
        return np.array([[z, z, z], [z, ess, z], [z, z, ett]])


@dataclass(frozen=True)
class UniformContact:
    r"""A uniform stress on both sides of a plane Γ and a rigid jump across it.

    Exact for any contact law that admits its traction: with σ uniform and
    u⁻ = ε x, u⁺ = ε x - [[u]] (ε = C⁻¹σ, [[u]] = u⁻ - u⁺ constant), every
    equation of elasticity holds in each body, the traction r = σn (n the
    unit normal into Ω⁺) is the same at every point of Γ, and the X-FEM
    space, which holds piecewise linear fields with a constant jump, and every
    multiplier space, which holds constants, contain the solution: a discrete
    solve must reproduce it to round-off.  ``pressure`` p = -n·σn,
    ``shear`` r_τ = σn - (n·σn) n.

    >>> sol = UniformContact(Material(1.0, 0.0), np.array([[0.0, 0.5], [0.5, -1.0]]),
    ...                      (0.0, 1.0), jump=(-0.2, 0.0))
    >>> float(sol.pressure), sol.shear.tolist()
    (1.0, [0.5, 0.0])
    >>> sol.displacement(np.array([[1.0], [1.0]]), +1).ravel().tolist()  # ε x - [[u]]
    [0.7, -0.5]
    """

    material: Material
    sigma: np.ndarray
    normal: tuple
    jump: tuple = None

    def __post_init__(self):
        sigma = np.asarray(self.sigma, dtype=float)
        n = np.asarray(self.normal, dtype=float)
        dim = n.size
        if sigma.shape != (dim, dim) or not np.allclose(sigma, sigma.T):
            raise ValueError(f"sigma must be a symmetric {dim}x{dim} array, got {sigma!r}")
        object.__setattr__(self, "sigma", sigma)
        object.__setattr__(self, "normal", n / np.linalg.norm(n))
        jump = np.zeros(dim) if self.jump is None else np.asarray(self.jump, float)
        object.__setattr__(self, "jump", jump)

    @property
    def dim(self) -> int:
        return self.normal.size

    @property
    def strain(self) -> np.ndarray:
        """ε = C⁻¹σ (the material's plane strain or stress in 2D)."""
        lam, mu = self.material.lame(self.dim)
        tr = np.trace(self.sigma) / (self.dim * lam + 2 * mu)
        return (self.sigma - lam * tr * np.eye(self.dim)) / (2 * mu)

    @property
    def traction(self) -> np.ndarray:
        """r = σn, the traction on Γ (on Ω⁻'s face, the paper's r¹)."""
        return self.sigma @ self.normal

    @property
    def pressure(self) -> float:
        """p = -n·σn."""
        return float(-self.normal @ self.traction)

    @property
    def shear(self) -> np.ndarray:
        """r_τ = σn - (n·σn) n."""
        return self.traction + self.pressure * self.normal

    def displacement(self, x, side: int):
        """u at points x (dim, ...) of Ω⁻ (``side`` -1) or Ω⁺ (+1)."""
        x = np.asarray(x, dtype=float)
        u = np.einsum("ij,j...->i...", self.strain, x)
        if side > 0:
            u = u - self.jump.reshape((-1,) + (1,) * (x.ndim - 1))
        return u

    def face_traction(self, outward):
        """The traction σ·n_ext on a boundary face of outward unit normal ``outward``."""
        return self.sigma @ np.asarray(outward, dtype=float)
