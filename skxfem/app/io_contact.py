"""What ``result.json`` adds for a contact result: the law, and every load step at the dofs.

:func:`skxfem.app.io.write_result` writes a contact result into the same three
files as a tie result, with the same fields at the cut edges' points (the last
step's); this module gives what a contact ``result.json`` adds (the file layout
is described in :mod:`skxfem.app.io`): the law's parameters, the ``status`` of each
point, and ``dofs`` and ``steps``, the values at the multiplier dofs (the
points where the laws are imposed, :mod:`skxfem.contact.interface`):
``pressure`` p = -λ (≥ 0), ``gap`` the weighted normal jump d (≤ 0
admissible), ``slip`` and ``tangential_traction`` the components of the
weighted tangential jump and of r_τ on the ``tangents`` of the dof (k = 1 in
2D, 2 in 3D), ``status`` open / stick / slip.

>>> from dataclasses import replace
>>> from skxfem import contact
>>> from skxfem.scene import Displacement
>>> from skxfem.scene.benchmarks import strip
>>> s = strip(n=3)
>>> s = replace(s, law="frictionless",
...             displacements=s.displacements + (Displacement("ymax", {"x": 0.0}),))
>>> data = contact_summary(contact.solve(s))
>>> data["steps"][-1]["status"], data["status_codes"]["slip"]
(['slip', 'slip', 'slip', 'slip'], 2)
>>> data["status"] == data["steps"][-1]["status"]   # quads: one dof per cut edge
True
"""
from __future__ import annotations

import numpy as np

from ..contact.interface import tangent_frames
from ..contact.laws import STATUS_NAMES

__all__ = ["is_contact", "contact_summary", "EQUATIONS"]

EQUATIONS = ("equilibrium", "contact", "friction")
"""The equations whose relative residuals :class:`~skxfem.contact.newton.NewtonInfo` holds."""


def is_contact(result) -> bool:
    """True for the result of a contact solve (it has load ``steps``)."""
    return len(getattr(result, "steps", ())) > 0


def _tangents(result) -> np.ndarray:
    """(m, k, dim): the tangent frame of each multiplier dof's normal.

    On a plane Γ it is the frame of ``ops.Bt``; on a curved Γ the components
    are ψ_j-weighted means over frames that turn with n, close to this one.
    """
    return np.moveaxis(tangent_frames(result.ops.normals), 2, 0)


def _step(step) -> dict:
    """One load step's entry of ``result.json``."""
    residuals = np.asarray(step.newton.residuals, dtype=float).reshape(-1, len(EQUATIONS))
    status = [STATUS_NAMES[k] for k in np.asarray(step.status)]
    return {
        "load": step.load if isinstance(step.load, str) else float(step.load),
        "law": step.law if isinstance(step.law, str) else list(step.law),
        "increments": int(step.increments),
        "pressure": np.asarray(step.pressure, dtype=float),
        "tangential_traction": np.asarray(step.traction, dtype=float),
        "gap": np.asarray(step.gap, dtype=float),
        "slip": np.asarray(step.slip, dtype=float),
        "Lambda": np.asarray(step.Lambda, dtype=float),
        "status": status,
        "counts": {name: status.count(name) for name in STATUS_NAMES},
        "newton": {"iterations": int(step.newton.iterations),
                   "residuals": dict(zip(EQUATIONS, residuals.T, strict=True))},
    }


def contact_summary(result) -> dict:
    """What a contact ``result.json`` adds to a tie's: the law, the ``status`` of
    each point, the multiplier ``dofs`` and one entry per load step.

    Arrays are numpy arrays here (:func:`skxfem.app.io.result_summary` turns
    them into lists, NaN into ``null``); a set of points or vectors is one
    row per point, as in the tie's file.

    Raises
    ------
    ValueError
        If the result has no load step.
    """
    if len(result.steps) == 0:
        raise ValueError("the contact result has no load step; give a non-empty history")
    ops, law = result.ops, result.law
    dofs = {"points": np.asarray(ops.points, dtype=float).T,
            "normals": np.asarray(ops.normals, dtype=float).T,
            "tangents": _tangents(result),
            "weights": np.asarray(ops.w, dtype=float)}
    if isinstance(law, tuple):  # several interfaces: μ and ρ per interface (skxfem.app.io)
        dofs["interface"] = np.asarray(ops.interface).tolist()
        law = law[0]
    return {
        "friction": float(law.mu),
        "rho_n": float(law.rho_n),
        "rho_t": float(law.rho_t),
        "status_codes": {name: code for code, name in enumerate(STATUS_NAMES)},
        "status": [STATUS_NAMES[k] for k in np.asarray(result.status)],
        "dofs": dofs,
        "n_steps": len(result.steps),
        "newton_iterations": result.iterations,
        "steps": [_step(st) for st in result.steps],
    }
