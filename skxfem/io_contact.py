"""What the files of a contact result hold: every load step in JSON, the last one in VTU.

:func:`skxfem.io.write_result` writes a :class:`skxfem.contact.ContactResult`
into the same three files as a tie result, atomically; this module gives their
content (the file layout is described in :mod:`skxfem.io`).  Every interface
value is one value per multiplier dof (the points where the laws are imposed,
:mod:`skxfem.contact_interface`): ``pressure`` p = -λ (≥ 0), ``gap`` the
weighted normal jump d (≤ 0 admissible), ``slip`` and ``tangential_traction``
the components of the weighted tangential jump and of r_τ on the ``tangents``
of the point (k = 1 in 2D, 2 in 3D), ``status`` open / stick / slip.

>>> from dataclasses import replace
>>> from skxfem import contact
>>> from skxfem.scene import Displacement
>>> from skxfem.scenes import strip
>>> s = strip(n=3)
>>> s = replace(s, law="frictionless",
...             displacements=s.displacements + (Displacement("ymax", {"x": 0.0}),))
>>> data = contact_summary(contact.solve(s))
>>> data["steps"][-1]["status"], data["status_codes"]["slip"]
(['slip', 'slip', 'slip', 'slip'], 2)
"""
from __future__ import annotations

from dataclasses import dataclass

import meshio
import numpy as np

from .contact_interface import tangent_frames
from .contact_laws import STATUS_NAMES
from .enrich import split_fields
from .vtu import pad3

__all__ = ["is_contact", "contact_summary", "last_step_fields", "interface_mesh",
           "EQUATIONS"]

EQUATIONS = ("equilibrium", "contact", "friction")
"""The equations whose relative residuals :class:`~skxfem.contact_newton.NewtonInfo` holds."""


def is_contact(result) -> bool:
    """True for a :class:`skxfem.contact.ContactResult` (it has load ``steps``)."""
    return hasattr(result, "steps") and hasattr(result, "ops")


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
    """The content of a contact ``result.json``: the set-up, then one entry per load step.

    Arrays are numpy arrays here (:func:`skxfem.io.result_summary` turns
    them into lists, NaN into ``null``); a set of points or vectors is one
    row per point, as in the tie's file.

    Raises
    ------
    ValueError
        If the result has no load step.
    """
    if len(result.steps) == 0:
        raise ValueError("the contact result has no load step; give a non-empty history")
    pb, ops, law = result.problem, result.ops, result.law
    return {
        "scene": pb.scene.name,
        "law": pb.scene.law,
        "space": pb.scene.space,
        "friction": float(law.mu),
        "rho_n": float(law.rho_n),
        "rho_t": float(law.rho_t),
        "status_codes": {name: code for code, name in enumerate(STATUS_NAMES)},
        "points": np.asarray(ops.points, dtype=float).T,
        "normals": np.asarray(ops.normals, dtype=float).T,
        "tangents": _tangents(result),
        "weights": np.asarray(ops.w, dtype=float),
        "n_dofs": int(pb.V.N),
        "n_multipliers": int(ops.w.size),
        "n_steps": len(result.steps),
        "newton_iterations": sum(int(st.newton.iterations) for st in result.steps),
        "steps": [_step(st) for st in result.steps],
    }


@dataclass(frozen=True)
class _Fields:
    """The fields of one step, as the displacement writer reads them from a tie result."""

    mesh: object
    scene: object
    u_minus: np.ndarray
    u_plus: np.ndarray


def last_step_fields(result):
    """What the displacement VTU needs from the last step: a stand-in for a tie result.

    Returns an object with ``mesh``, ``scene`` (for the level set),
    ``u_minus`` and ``u_plus`` (dim, nverts), the fields of each side.
    """
    pb = result.problem
    u_minus, u_plus = split_fields(pb.V, result.steps[-1].U)
    return _Fields(pb.mesh, pb.scene, u_minus, u_plus)


def interface_mesh(result) -> meshio.Mesh:
    """The multiplier dofs of the last step as ``vertex`` cells, with their values.

    Point data: ``pressure``, ``gap`` (scalars), ``status`` (integer: 0 open,
    1 stick, 2 slip, ``STATUS_NAMES``), ``normal``, ``traction`` (the whole
    traction -p n + r_τ, as in a tie's file), ``tangential_traction`` r_τ and
    ``slip`` (the tangential jump vector), all (m, 3).
    """
    st = result.steps[-1]
    normals = np.asarray(result.ops.normals, dtype=float).T          # (m, dim)
    tangents = _tangents(result)                                      # (m, k, dim)
    r_t = np.einsum("mk,mkd->md", np.asarray(st.traction, float), tangents)
    slip = np.einsum("mk,mkd->md", np.asarray(st.slip, float), tangents)
    m = normals.shape[0]
    return meshio.Mesh(
        pad3(np.asarray(result.ops.points, dtype=float).T),
        [("vertex", np.arange(m).reshape(m, 1))],
        point_data={"pressure": np.asarray(st.pressure, dtype=float),
                    "gap": np.asarray(st.gap, dtype=float),
                    "status": np.asarray(st.status, dtype=np.int64),
                    "normal": pad3(normals),
                    "traction": pad3(r_t - np.asarray(st.pressure)[:, None] * normals),
                    "tangential_traction": pad3(r_t),
                    "slip": pad3(slip)})
