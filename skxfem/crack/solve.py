r"""One plain 2D crack problem, solved: geometry, space, assembly, solve, K.

:func:`solve_crack` runs the steps of the package's crack modules in order:

1. :func:`skxfem.crack.geometry.crack_geometry`: tips, tip and split cells, sub-cells;
2. :func:`skxfem.crack.space.crack_space`: the unknowns [a, b, c];
3. :func:`skxfem.crack.assembly.stiffness`, :func:`~skxfem.crack.assembly.traction_load`
   (and :func:`~skxfem.crack.assembly.face_load` for loaded faces,
   :func:`~skxfem.crack.assembly.body_load` for a body force),
   :func:`~skxfem.crack.assembly.supported_dofs`;
4. the scaling of :func:`skxfem.crack.space.nodal_scaling`, K_s = Sᵀ K S, and a direct
   solve of the supported system for U = S U_s;
5. :func:`skxfem.crack.sif.sif` at every tip.

It is the harness of the tests and of a later crack kind of interface; it has no
contact.

>>> from skfem import MeshTri1
>>> from skxfem.fem.material import Material
>>> m = MeshTri1.init_tensor(np.linspace(0, 1, 8), np.linspace(0, 1, 8))
>>> bottom = m.facets_satisfying(lambda x: x[1] < 1e-12)
>>> top = m.facets_satisfying(lambda x: x[1] > 1 - 1e-12)
>>> s = solve_crack(m, lambda x: x[1] - 0.5, lambda x: x[0] - 0.5, Material(1.0, 0.3),
...                 supports=[Support(bottom)],
...                 loads=[Load(top, lambda x: np.stack([0 * x[0], 1 + 0 * x[0]]))])
>>> bool(s.K_I > 0), s.U.shape == (s.space.N,)                  # tension opens it
(True, True)
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve

from ..fem.material import Material
from .assembly import (
    Load,
    Support,
    body_load,
    face_load,
    rule_groups,
    stiffness,
    supported_dofs,
    traction_load,
)
from .geometry import crack_geometry
from .sif import sif
from .space import CrackSpace, condition_number, crack_space, evaluation, nodal_scaling

__all__ = ["CrackSolution", "solve_crack", "Support", "Load"]


@dataclass(frozen=True)
class CrackSolution:
    """A solved crack problem.

    Attributes
    ----------
    U : (N,) the unknowns [a, b, c].  space : the :class:`CrackSpace`.
    material : the material.  K : (ntips, 2) (K_I, K_II) at each tip.
    condition : the condition number of the scaled, supported stiffness (if asked).
    """

    U: np.ndarray
    space: CrackSpace
    material: Material
    K: np.ndarray
    condition: float | None = field(default=None)

    @property
    def K_I(self) -> float:
        """K_I at the first tip."""
        return float(self.K[0, 0])

    @property
    def K_II(self) -> float:
        """K_II at the first tip."""
        return float(self.K[0, 1])

    def energy_error(self, grad_exact: Callable, order: int = 4) -> tuple[float, float]:
        """(relative, absolute) energy error against an exact displacement gradient.

        ‖e‖² = ∫ σ(e):ε(e), e = u_h - u, over every cell with the rules of
        :func:`skxfem.crack.assembly.rule_groups` (``order``: the plain cells' Gauss
        order); ``grad_exact(x)`` gives ∂u_i/∂x_j, (2, 2, n), at points (2, n) off the
        crack.  Relative: ‖e‖ / ‖u‖.
        """
        V, mesh = self.space, self.space.mesh
        lam, mu = self.material.lame(2)
        err = ref = 0.0
        for G in rule_groups(V, np.arange(mesh.t.shape[1]), plain_order=order):
            cells, ref_x, side, x, w = G.points()
            _, gu = evaluation(V, cells, ref_x, side).at(self.U)
            ge = np.asarray(grad_exact(x), float)
            for g, acc in ((gu - ge, "err"), (ge, "ref")):
                e = (g + np.swapaxes(g, 0, 1)) / 2
                tr = e[0, 0] + e[1, 1]
                val = w @ (2 * mu * (e * e).sum(axis=(0, 1)) + lam * tr ** 2)
                if acc == "err":
                    err += val
                else:
                    ref += val
        return float(np.sqrt(err / ref)), float(np.sqrt(err))


def solve_crack(mesh, psi, phi, material: Material, supports=(), loads=(),
                enrichment: str = "geometric", radius: float | None = None,
                scaling: str | None = "block", sif_radius: float | None = None,
                face_traction: Callable | None = None, condition: bool = False,
                body_force=None) -> CrackSolution:
    """Solve linear elasticity on a 2D mesh with a crack {ψ = 0, φ < 0} (module notes).

    Parameters
    ----------
    mesh : ``MeshTri1`` or ``MeshQuad1``.
    psi, phi : the two level sets (callables or nodal values).
    material : :class:`skxfem.fem.material.Material`.
    supports : :class:`~skxfem.crack.assembly.Support` s (imposed displacements).
    loads : :class:`~skxfem.crack.assembly.Load` s (tractions on boundary facets).
    enrichment, radius : :func:`skxfem.crack.space.crack_space`.
    scaling : :func:`skxfem.crack.space.nodal_scaling` (``"block"``, ``"jacobi"``, None).
    sif_radius : the interaction domain's r_d (:func:`skxfem.crack.sif.sif`).
    face_traction : ``(x, side) -> (2, n)`` the traction σ·m* on the crack face of
        ``side`` (:func:`skxfem.crack.assembly.face_load`): loaded in the solve and in the
        SIF's face term; None: free faces.
    condition : also measure the condition number of the scaled, supported stiffness.
    body_force : a body force b (:func:`skxfem.fem.loads.force_field`): loaded in the
        solve and in the SIF's body-force term; None: none.
    """
    if not isinstance(material, Material):
        raise ValueError(f"material must be a skxfem Material, got {type(material).__name__}")
    geometry = crack_geometry(mesh, psi, phi)
    V = crack_space(mesh, geometry, enrichment, radius)
    K = stiffness(V, material)
    f = traction_load(V, loads)
    if face_traction is not None:
        f = f + face_load(V, face_traction)
    if body_force is not None:
        f = f + body_load(V, body_force)
    D, g = supported_dofs(V, supports)
    S = nodal_scaling(K, V, scaling, D)
    Ks, fs = (S.T @ K @ S).tocsr(), S.T @ f
    Us = np.zeros(V.N)
    Us[D] = g / S.diagonal()[D]
    free = np.setdiff1d(np.arange(V.N), D)
    rhs = fs[free] - Ks[free][:, D] @ Us[D]
    Us[free] = spsolve(sp.csc_matrix(Ks[free][:, free]), rhs)
    U = S @ Us
    K_tips = np.array([sif(V, U, material, sif_radius, tip=k, face_traction=face_traction,
                           body_force=body_force) for k in range(geometry.tips.shape[1])])
    cond = condition_number(Ks, free) if condition else None
    return CrackSolution(U, V, material, K_tips, cond)
