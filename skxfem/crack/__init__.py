r"""Cracks with a front: the pieces that need no mesh.

One module per idea, each plain numpy functions of arrays:

* :mod:`~skxfem.crack.frame`: the tip frame e₁, e₂, e₃ from the two level sets
  φ, ψ and the polar coordinates (r, θ) around the front;
* :mod:`~skxfem.crack.branch`: the four branch functions √r {sin θ/2, cos θ/2,
  sin θ/2 sin θ, cos θ/2 sin θ} and their gradients;
* :mod:`~skxfem.crack.williams`: the exact near-tip fields of modes I, II, III;
* :mod:`~skxfem.crack.interaction`: the domain interaction integral with its
  crack-face term, and the stress intensity factors it gives.
"""
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
from .interaction import (
                    CrackFace,
                    effective_modulus,
                    interaction_integrals,
                    q_function,
                    sif_from_interaction,
                    stress_intensity,
)
from .williams import NearTip, kolosov, near_tip, near_tip_local, shear_modulus

__all__ = ["TipFrame", "tip_frame", "straight_frame", "local_coordinates", "polar",
           "polar_gradients", "face_tolerance", "branch", "branch_polar_derivatives",
           "branch_local_gradient", "branch_gradient", "NearTip", "kolosov", "shear_modulus",
           "near_tip_local", "near_tip", "CrackFace", "q_function", "interaction_integrals",
           "effective_modulus", "sif_from_interaction", "stress_intensity"]
