r"""A genuinely 3D exact solution: a block whose answer varies in x, y and z.

The plate of :mod:`skxfem.fem.exact` is a plane-strain field: nothing depends on
x, so its prisms give the triangles' numbers and its hexahedra the
quadrilaterals'.  This module gives an elastic field that varies in all three
directions, with no body force, for a unit cube [0, 1]³ cut by a plane Γ
slanted against all three axes (:data:`GAMMA_POINT`, :data:`GAMMA_NORMAL`).

It is Love's solution (Papkovich–Neuber with the potential ψ e_z): for any
harmonic ψ (Δψ = 0) the displacement, in coordinates (ξ, η, ζ) = x - c
centred at c = (½, ½, ½),

.. math:: \mathbf u = \frac{P}{2\mu}\Big((3 - 4\nu)\,\psi\,\mathbf e_z
          - \zeta\,\nabla\psi\Big)

satisfies Navier's equations μΔu + (λ + μ)∇(∇·u) = 0 for every E, ν:
div u = (2 - 4ν) ψ_z, Δu = -2∇ψ_z, and (λ + μ)(2 - 4ν) = 2μ.  Its stress is

.. math:: \sigma_{ij} = P\Big(2\nu\,\psi_{,z}\,\delta_{ij}
          + (1 - 2\nu)(\psi_{,i}\delta_{jz} + \psi_{,j}\delta_{iz})
          - \zeta\,\psi_{,ij}\Big).

With the harmonic cubic

.. math:: \psi = -\frac{1}{2(1-\nu)}\Big(\zeta
          + \tfrac{2}{3}\big(\zeta^3 - \tfrac32\zeta(\xi^2 + \eta^2)\big)
          - \tfrac12\,\xi\eta\zeta\Big)

the normal stress on the horizontal plane through c is a dome,
σ_zz(ξ, η, 0) = -P (1 - ξ² - η² - ½ ξη), between -P at the centre and
-0.375 P at a corner; u is cubic and σ quadratic in (x, y, z).  On Γ the
traction σ·n has a normal part -p (the contact pressure :meth:`ExactBlock.pressure`
= -n·σ·n) that varies along Γ in every direction, and a tangential part:
the tied (``bonded``) interface carries both, the field is continuous
across Γ.

>>> sol = ExactBlock(Material(1.0, 0.3))
>>> centre = np.full((3, 1), 0.5)
>>> float(sol.stress(centre)[2, 2, 0])        # -P at the centre
-1.0
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .material import Material

__all__ = ["ExactBlock", "GAMMA_POINT", "GAMMA_NORMAL", "CENTRE"]

CENTRE = (0.5, 0.5, 0.5)
"""c, the centre of the unit cube: the origin of (ξ, η, ζ)."""

GAMMA_POINT = (0.5, 0.5, 0.5515)
"""A point of Γ, just above c: chosen so that Γ keeps off every node of the
meshes of :func:`skxfem.scenes.exact_block` with n = 2 ... 64 cells per side
(by at least 0.0028 h; 0.006 h, 0.011 h, 0.023 h for n = 4, 8, 16)."""

GAMMA_NORMAL = (0.2, 0.3, 1.0)
"""The normal of Γ (not unit): Γ is slanted against all three axes, 20° from
horizontal, and stays within 0.3 < z < 0.81 in the cube, away from the
bottom (held) and the top."""


@dataclass(frozen=True)
class ExactBlock:
    """Love's solution above for ``material`` (its 3D constants) and scale ``P``.

    ``normal``: Γ's normal, for :meth:`pressure` (default :data:`GAMMA_NORMAL`).
    """

    material: Material
    P: float = 1.0
    normal: tuple = GAMMA_NORMAL

    dim = 3

    def _psi(self, x):
        """ψ, its gradient (3, ...) and Hessian (3, 3, ...) at points x (3, ...)."""
        xi, eta, zeta = (x[i] - CENTRE[i] for i in range(3))
        k = -1.0 / (2 * (1 - self.material.nu))
        r2 = xi ** 2 + eta ** 2
        psi = k * (zeta + 2 / 3 * zeta ** 3 - zeta * r2 - 0.5 * xi * eta * zeta)
        grad = k * np.array([-2 * xi * zeta - 0.5 * eta * zeta,
                             -2 * eta * zeta - 0.5 * xi * zeta,
                             1 + 2 * zeta ** 2 - r2 - 0.5 * xi * eta])
        z = 0 * xi
        hess = k * np.array([[-2 * zeta, -0.5 * zeta + z, -2 * xi - 0.5 * eta],
                             [-0.5 * zeta + z, -2 * zeta, -2 * eta - 0.5 * xi],
                             [-2 * xi - 0.5 * eta, -2 * eta - 0.5 * xi, 4 * zeta]])
        return psi, grad, hess

    def _scale(self):
        _, mu = self.material.lame(3)
        return self.P / (2 * mu)

    def displacement(self, x):
        """u at points x, shape (3, ...)."""
        psi, grad, _ = self._psi(x)
        zeta = x[2] - CENTRE[2]
        u = -zeta * grad
        u[2] += (3 - 4 * self.material.nu) * psi
        return self._scale() * u

    def gradient(self, x):
        """∇u at points x, shape (3, 3, ...): entry (i, j) is ∂u_i/∂x_j."""
        _, grad, hess = self._psi(x)
        zeta = x[2] - CENTRE[2]
        G = -zeta * hess
        G[:, 2] -= grad                                    # -δ_jz ψ_,i
        G[2] += (3 - 4 * self.material.nu) * grad          # (3 - 4ν) δ_iz ψ_,j
        return self._scale() * G

    def strain(self, x):
        """ε(u) at points x, shape (3, 3, ...)."""
        G = self.gradient(x)
        return 0.5 * (G + np.swapaxes(G, 0, 1))

    def stress(self, x):
        """σ = C ε(u) at points x, shape (3, 3, ...)."""
        return self.material.stress(self.strain(x), 3)

    def traction(self, x, n):
        """σ·n at points x with unit normals n, both (3, ...)."""
        return np.einsum("ij...,j...->i...", self.stress(x), n)

    def pressure(self, x):
        """The contact pressure p = -n·σ·n on Γ, n the unit normal of Γ."""
        n = np.asarray(self.normal, float)
        n = n / np.linalg.norm(n)
        return -np.einsum("i,ij...,j->...", n, self.stress(x), n)
