r"""Linear elastic material: Hooke's law σ = C ε (paper eq. 1) as scikit-fem forms.

In 3D, σ = 2μ ε + λ tr(ε) I with the Lamé constants of (E, ν).  In 2D the
``plane`` setting chooses plane strain (ε_zz = 0, the 3D constants) or plane
stress (σ_zz = 0, which replaces λ by 2μλ/(λ + 2μ) = Eν/(1 - ν²)).  The
constants and σ(ε) are scikit-fem's own (:mod:`skfem.models.elasticity`:
``lame_parameters``, ``plane_stress``, ``linear_stress``); this module adds
the validation and a faster assembly of the same matrix from scalar forms
(:func:`stiffness_matrix`).

>>> m = Material(E=1.0, nu=0.0)
>>> m.lame(2), m.lame(3)
((0.0, 0.5), (0.0, 0.5))
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.sparse as sp
from skfem import BilinearForm
from skfem.models.elasticity import lame_parameters, linear_elasticity, linear_stress, plane_stress

from ..linalg.scalars import is_number

__all__ = ["Material", "E_RANGE", "NU_MAX", "stiffness_form", "partial_form", "stiffness_matrix"]

E_RANGE = (1e-100, 1e100)
"""The Young's moduli a :class:`Material` accepts."""

NU_MAX = 0.499999
"""The largest Poisson's ratio a :class:`Material` accepts, 0.499999.  Nearer 0.5
the material is nearly incompressible: λ/μ = 2ν/(1 - 2ν) exceeds 10⁶, the
stiffness is singular to working precision on fine meshes and the tied system
with it (measured on the patch test: 0.5 - 10⁻⁷ refused as singular on 32 × 32
triangles and quadrilaterals, 0.5 - 10⁻⁸ on every cell at 4 a side, 0.5 - 10⁻⁶
solved to 2e-8), and P1/Q1 displacements lock long before (the extremes table:
the energy error doubles near ν = 0.49 on quadrilaterals)."""


@dataclass(frozen=True)
class Material:
    """Isotropic linear elasticity.

    Parameters
    ----------
    E
        Young's modulus, in :data:`E_RANGE` (measured: a patch test solves to
        round-off from 1e-150 to 1e150; the table of extremes runs 1e-6 to 1e9).
    nu
        Poisson's ratio, -1 < ν ≤ :data:`NU_MAX` (0.5 - 10⁻⁶: nearer 0.5, a
        nearly incompressible material, which displacement elements cannot
        solve; refused, in 2D plane stress too, where the same material may
        be used in 3D).
    plane
        ``"strain"`` or ``"stress"``; used only in 2D.
    """

    E: float = 1.0
    nu: float = 0.3
    plane: str = "strain"

    def __post_init__(self):
        for key in ("E", "nu"):
            value = getattr(self, key)
            if not is_number(value):
                raise TypeError(f"material {key} must be a real number, got {value!r}")
            object.__setattr__(self, key, float(value))   # numpy's numbers as Python's
        if not E_RANGE[0] <= float(self.E) <= E_RANGE[1]:  # also refuses NaN and inf
            raise ValueError(
                f"material E must be a positive number in [{E_RANGE[0]:.0e}, "
                f"{E_RANGE[1]:.0e}], got {self.E!r}: beyond, the solve's products of "
                f"stiffnesses leave floating point; express E (and the loads) in "
                f"another unit of stress")
        if not -1.0 < float(self.nu) < 0.5:
            raise ValueError(f"material nu must satisfy -1 < nu < 0.5, got {self.nu!r}")
        if float(self.nu) > NU_MAX:
            raise ValueError(
                f"material nu = {self.nu!r} is within {0.5 - float(self.nu):.1e} of 0.5: a "
                f"nearly incompressible material (λ/μ = "
                f"{2 * float(self.nu) / (1 - 2 * float(self.nu)):.1e}), whose stiffness is "
                f"singular to working precision and whose displacement elements lock; "
                f"skxfem accepts nu up to {NU_MAX} (0.5 - 1e-6), and is accurate up to "
                f"about 0.49")
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


@lru_cache(maxsize=None)
def partial_form(a: int, b: int) -> BilinearForm:
    """The scalar form s_ab(u, v) = ∫ ∂_b u ∂_a v (``v`` the test function)."""

    @BilinearForm
    def partial(u, v, w):
        return u.grad[b] * v.grad[a]

    return partial


def stiffness_matrix(material: Material, basis) -> sp.csr_matrix:
    r"""The elasticity stiffness ∫ σ(u):ε(v) of the vector field built on the
    *scalar* basis ``basis``, as scikit-fem's ``ElementVector`` numbers it
    (node by node, component fastest).

    With u = φⱼ e_b and v = φᵢ e_a, σ(u):ε(v) = λ div u div v + μ (∇u:∇v +
    ∇u:∇vᵀ), so every entry comes from the dim² scalar matrices
    S_ab = ∫ ∂_a φᵢ ∂_b φⱼ (:func:`partial_form`):

    .. math:: K_{ia, jb} = λ S_{ab} + μ S_{ba} + δ_{ab}\, μ \sum_c S_{cc} .

    The same matrix as ``stiffness_form(material, dim).assemble(vector
    basis)``, but scikit-fem evaluates dim(dim+1)/2 one-product forms on
    n_loc² pairs instead of one tensor form on (dim n_loc)² pairs, on a basis
    that holds dim² times fewer values: measured 4.4 to 6.8 times faster on the
paper's plate (hexahedra and prisms, n = 16 and 24).

    >>> from skfem import Basis, ElementTriP1, ElementVector, MeshTri1
    >>> m, mat = MeshTri1().refined(1), Material(E=2.0, nu=0.3)
    >>> K = stiffness_form(mat, 2).assemble(Basis(m, ElementVector(ElementTriP1())))
    >>> bool(abs(stiffness_matrix(mat, Basis(m, ElementTriP1())) - K).max() < 1e-14)
    True
    """
    dim = basis.mesh.dim()
    lam, mu = material.lame(dim)
    S = {}
    for a in range(dim):
        for b in range(a, dim):
            S[a, b] = partial_form(a, b).assemble(basis).tocsr()
            S[b, a] = S[a, b].T.tocsr()  # ∫ ∂_b φᵢ ∂_a φⱼ: the transpose
    trace = sum(S[c, c] for c in range(dim))
    rows, cols, vals = [], [], []
    for a in range(dim):
        for b in range(dim):
            block = (lam * S[a, b] + mu * S[b, a] + (mu * trace if a == b else 0)).tocoo()
            rows.append(dim * block.row + a)  # vector dof of (node i, component a)
            cols.append(dim * block.col + b)
            vals.append(block.data)
    n = dim * basis.N
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n, n))
