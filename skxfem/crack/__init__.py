r"""Cracks with a front: the pieces that need no mesh.

One module per idea, each plain numpy functions of arrays:

* :mod:`~skxfem.crack.frame`: the tip frame e₁, e₂, e₃ from the two level sets
  φ, ψ and the polar coordinates (r, θ) around the front;
* :mod:`~skxfem.crack.branch`: the four branch functions √r {sin θ/2, cos θ/2,
  sin θ/2 sin θ, cos θ/2 sin θ} and their gradients;
* :mod:`~skxfem.crack.williams`: the exact near-tip fields of modes I, II, III;
* :mod:`~skxfem.crack.interaction`: the domain interaction integral with its
  crack-face term, and the stress intensity factors it gives.

And the X-FEM of a 2D crack on a mesh (MeshTri1, MeshQuad1), one step each:

* :mod:`~skxfem.crack.geometry`: split cells, tip cells, tips, crack pieces, sub-cells
  (fanned from the tip in the tip cells);
* :mod:`~skxfem.crack.quadrature`: sub-triangle rules and the almost-polar rule;
* :mod:`~skxfem.crack.space`: the unknowns [a, b, c] (Heaviside and branch enrichment,
  topological or geometric), evaluation at points, the nodal block scaling;
* :mod:`~skxfem.crack.assembly`: stiffness, tractions on boundary facets and on the
  crack faces, supports (a mouth is never clamped shut);
* :mod:`~skxfem.crack.sif`: K_I, K_II of a solution by the interaction integral;
* :mod:`~skxfem.crack.solve`: :func:`solve_crack`, the steps in order.
"""
from .assembly import Load, Support, face_load, stiffness, supported_dofs, traction_load
from .branch import branch, branch_gradient, branch_local_gradient, branch_polar_derivatives
from .frame import (
                    TipFrame,
                    face_tolerance,
                    local_coordinates,
                    polar,
                    polar_gradients,
                    straight_frame,
                    tip_frame,
)
from .geometry import CrackGeometry, crack_geometry
from .interaction import (
                    CrackFace,
                    effective_modulus,
                    interaction_integrals,
                    q_function,
                    sif_from_interaction,
                    stress_intensity,
)
from .sif import sif
from .solve import CrackSolution, solve_crack
from .space import CrackSpace, crack_space, evaluation, evaluation_at, nodal_scaling
from .williams import NearTip, kolosov, near_tip, near_tip_local, shear_modulus

__all__ = ["TipFrame", "tip_frame", "straight_frame", "local_coordinates", "polar",
           "polar_gradients", "face_tolerance", "branch", "branch_polar_derivatives",
           "branch_local_gradient", "branch_gradient", "NearTip", "kolosov", "shear_modulus",
           "near_tip_local", "near_tip", "CrackFace", "q_function", "interaction_integrals",
           "effective_modulus", "sif_from_interaction", "stress_intensity",
           "CrackGeometry", "crack_geometry", "CrackSpace", "crack_space", "evaluation",
           "evaluation_at", "nodal_scaling", "Load", "Support", "stiffness", "traction_load",
           "face_load", "supported_dofs", "sif", "CrackSolution", "solve_crack"]
