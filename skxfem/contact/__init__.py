"""Unilateral contact and Coulomb friction on Γ (paper §2–3, eq. 5–9).

The modules, in the order of the contact chapter: :mod:`~skxfem.contact.laws`
(the local laws and their generalised Jacobians), :mod:`~skxfem.contact.interface`
(where they are imposed: the operators at the multiplier dofs),
:mod:`~skxfem.contact.newton` (one load step by a globalised semi-smooth Newton
method), :mod:`~skxfem.contact.step` (the linear solve of a Newton step),
:mod:`~skxfem.contact.slide` (the rigid slide of a part that only Γ holds, where
its every point slides and the Newton matrix is singular),
:mod:`~skxfem.contact.fixed_point` (the paper's scheme),
:mod:`~skxfem.contact.holding` (whether Γ can hold, under its loads, a part that
nothing else holds) and :mod:`~skxfem.contact.history` (a load history:
:func:`solve`, which this package exports).
"""
from .history import (
    MAX_CUTS,
    METHODS,
    RHO_RANGE,
    ContactConvergenceError,
    Step,
    StepCutWarning,
    StepRetryWarning,
    check_closed,
    check_determined,
    parameters,
    solve,
)

__all__ = ["solve", "parameters", "Step", "ContactConvergenceError", "StepCutWarning",
           "StepRetryWarning",
           "check_closed", "check_determined", "METHODS", "RHO_RANGE", "MAX_CUTS"]
