r"""Linear elastic material: Hooke's law σ = C ε (paper eq. 1) as scikit-fem forms.

In 3D, σ = 2μ ε + λ tr(ε) I with the Lamé constants of (E, ν).  In 2D the
``plane`` setting chooses plane strain (ε_zz = 0, the 3D constants) or plane
stress (σ_zz = 0, which replaces λ by 2μλ/(λ + 2μ) = Eν/(1 - ν²)).  The
constants and σ(ε) are scikit-fem's own (:mod:`skfem.models.elasticity`:
``lame_parameters``, ``plane_stress``, ``linear_stress``); this module adds
the validation and the Heaviside-signed form of the X-FEM.

>>> m = Material(E=1.0, nu=0.0)
>>> m.lame(2), m.lame(3)
((0.0, 0.5), (0.0, 0.5))
"""
from __future__ import annotations

from dataclasses import dataclass

from skfem import BilinearForm
from skfem.helpers import ddot, sym_grad
from skfem.models.elasticity import lame_parameters, linear_elasticity, linear_stress, plane_stress

__all__ = ["Material", "stiffness_form", "signed_stiffness_form"]


@dataclass(frozen=True)
class Material:
    """Isotropic linear elasticity.

    Parameters
    ----------
    E
        Young's modulus, > 0.
    nu
        Poisson's ratio, -1 < ν < 0.5.
    plane
        ``"strain"`` or ``"stress"``; used only in 2D.
    """

    E: float = 1.0
    nu: float = 0.3
    plane: str = "strain"

    def __post_init__(self):
        if not (isinstance(self.E, (int, float)) and self.E > 0):
            raise ValueError(f"material E must be a positive number, got {self.E!r}")
        if not (isinstance(self.nu, (int, float)) and -1.0 < self.nu < 0.5):
            raise ValueError(f"material nu must satisfy -1 < nu < 0.5, got {self.nu!r}")
        if self.plane not in ("strain", "stress"):
            raise ValueError(
                f"material plane must be 'strain' or 'stress', got {self.plane!r}")

    def lame(self, dim: int) -> tuple[float, float]:
        """Return (λ, μ) for a ``dim``-dimensional model."""
        if dim == 2 and self.plane == "stress":
            return plane_stress(self.E, self.nu)
        return lame_parameters(self.E, self.nu)

    def stress(self, eps, dim: int):
        """σ(ε) for a strain tensor field ``eps`` of shape ``(dim, dim, ...)``."""
        return linear_stress(*self.lame(dim))(eps)


def stiffness_form(material: Material, dim: int) -> BilinearForm:
    """The elasticity form a(u, v) = ∫ σ(u) : ε(v): scikit-fem's ``linear_elasticity``."""
    return linear_elasticity(*material.lame(dim))


def signed_stiffness_form(material: Material, dim: int) -> BilinearForm:
    """The form ∫ H σ(u) : ε(v) with the Heaviside value H passed as ``w["H"]``.

    It couples standard and Heaviside-enriched dofs (paper eq. 11).
    """

    @BilinearForm
    def signed_elasticity(u, v, w):
        return w["H"] * ddot(material.stress(sym_grad(u), dim), sym_grad(v))

    return signed_elasticity
