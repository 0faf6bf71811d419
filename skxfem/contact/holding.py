r"""Whether Γ can hold a part of the body that nothing else holds: its loads and the friction cone.

A part of the body that no support touches (a side of Γ whose rigid motions
move no imposed unknown) is held by Γ alone.  Its rigid translations e move
no stiffness (K Z_e = 0, :func:`skxfem.linalg.amg.rigid_modes`), so the
equilibrium K U - Bnᵀλ - Σ Bt_aᵀ r_τa = F, tested with Z_e, says that the
interface forces balance the resultant of the loads on it, f = Z_Tᵀ F:

.. math:: f = \sum_j p_j\, a_j - \sum_j \sum_a r_{ja}\, t_{ja}, \qquad
          a_j = B_n Z_T|_j,\; t_{ja} = B_{t_a} Z_T|_j,

with p_j = -λ_j ≥ 0 and |r_j| ≤ μ p_j at every dof (Coulomb).  Each dof
contributes a cone about a_j (the direction Γ pushes the part there) of
half-angle atan μ (a_j ⊥ t_ja, |a_j| = |t_ja| = w_j: the weights of
:mod:`skxfem.contact.interface`), and f must lie in their sum.  This is a
*necessary* condition of every discrete solution, whatever ρ, the load steps or
the iteration: where it fails, no equilibrium exists and :func:`check_held_by_gamma`
says so before Newton starts, naming the part, the way its loads push it and
what would hold it.  Without it, Newton chases the part sliding away for
minutes: a state sliding by a huge rigid motion even passed the convergence
test, whose force scale grows with |U|, and was then refused as "not unique".

**The test.** An outer cone of the sum: its axis ν the weighted mean of the
a_j, its half-angle β the largest angle of a dof's axis from ν plus that
dof's half-angle (exact for a plane Γ: every a_j along the normal, β = atan μ;
a rigorous bound for a curved one).  If β < 90°, f outside it (angle θ > β)
has no equilibrium: with θ ≤ 90° the loads press the part on Γ but push it
along Γ harder than friction can hold (it slides as a rigid body), with
θ > 90° they pull it off Γ, which can only press on it (then
:func:`skxfem.contact.history.check_determined`'s rigid-motion diagnosis,
Γ open, names the motion).  Where a dof can hold any tangential force
(``adhesive``, ``bonded``) its half-angle is 90°, and only the pull is
refused; a dof that carries tension (``bilateral``, ``bonded``) or a part that
a support touches is left to the solve.

**No load.** Loads with no resultant (f = 0: a load history unloaded to zero, or
loads that cancel) under a pointed cone (β < 90°) leave every p_j = 0: Γ carries no
force, friction holds nothing (zero pressure, zero friction force), and any rigid
motion that keeps Γ open is an equilibrium, so the part's place is not determined.
:func:`check_held_by_gamma` refuses that state by name (:attr:`Holding.unloaded`),
before Newton, which otherwise met a singular matrix or returned one of those states.
Unloaded in several steps to a small load instead, the part tends to where friction
leaves it (``tests/test_contact_holding.py``).

Only the translations are tested (the moments are a further condition, not
tested here), so a part whose loads lie inside the cone can still fail to
be held (it could tip); the test never refuses a problem that has a
solution.

>>> import numpy as np
>>> round(float(np.degrees(_half_angle(np.array([0.0, 0.0, 2.0]),
...                                    np.array([[2.0, 0.0], [0.0, 2.0], [0.0, 0.0]]), 0.3))), 4)
16.6992
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..linalg.amg import axis_name
from ..linalg.rigid import region_names
from .laws import OPEN

__all__ = ["Holding", "holding", "check_held_by_gamma", "FrictionCannotHoldError",
           "ANGLE_TOL"]

ANGLE_TOL = 1e-9
"""A resultant is refused only if its angle from the cone's axis exceeds the
half-angle by more than this (radians): a part loaded exactly at the
friction limit may still have an equilibrium."""

RIGHT = np.pi / 2


class FrictionCannotHoldError(ValueError):
    """The loads on a part that only Γ holds lie outside the friction cone of Γ: no
    equilibrium exists (module notes)."""


@dataclass(frozen=True)
class Holding:
    """What Γ can do for one part of the body that only Γ holds.

    ``part`` its index (0 Ω⁻, 1 Ω⁺; several interfaces: the region);
    ``force`` (dim,) the resultant of the loads on it; ``axis`` (dim,) the unit
    direction Γ pushes it (mean); ``half_angle`` β of the outer friction cone;
    ``angle`` θ of the resultant from the axis; ``planar``: every dof's cone
    shares the axis (β is then exactly atan μ).
    """

    part: int
    force: np.ndarray
    axis: np.ndarray
    half_angle: float
    angle: float
    planar: bool

    @property
    def held(self) -> bool:
        """The resultant lies in the cone (or β ≥ 90° without a pull): the test passes."""
        if self.half_angle > RIGHT + ANGLE_TOL:
            return True                   # no conclusion
        if self.unloaded:
            return False                  # a pointed cone balances nothing but p = 0
        return self.angle <= self.half_angle + ANGLE_TOL

    @property
    def unloaded(self) -> bool:
        """The loads on the part have no resultant (``angle`` NaN): with β < 90° every
        pressure on Γ is then 0, Γ holds nothing and the part's place is not
        determined (module notes)."""
        return bool(np.isnan(self.angle))

    @property
    def pulled(self) -> bool:
        """The loads pull the part off Γ (θ > 90°)."""
        return self.angle > RIGHT + ANGLE_TOL


def _half_angle(a: np.ndarray, T: np.ndarray, mu: float) -> float:
    """The half-angle of the cone {p a + T c : |c| ≤ μ p, p ≥ 0} about a, or a bound
    of it: exact, atan(μ|T c|/|a|), where T's columns are orthogonal to a and of equal
    length; else the lateral reach over the least axial one (module notes)."""
    size = np.linalg.norm(a)
    if T.size == 0 or mu == 0:
        return 0.0
    if not np.isfinite(mu):
        return RIGHT
    ah = a / size
    along = ah @ T
    lateral = T - np.outer(ah, along)
    reach = mu * np.linalg.norm(lateral, 2)
    axial = size - mu * np.linalg.norm(along)
    return float(np.arctan2(reach, axial)) if axial > 0 else RIGHT


def _angle(u: np.ndarray, v: np.ndarray) -> float:
    """The angle between u and v (to round-off near 0 as well, unlike arccos)."""
    vh = v / np.linalg.norm(v)
    along = float(u @ vh)
    return float(np.arctan2(np.linalg.norm(u - along * vh), along))


def holding(pb, ops, laws, F, modes) -> list[Holding]:
    """The :class:`Holding` of every part that only Γ holds under the loads ``F``.

    ``modes``: :func:`skxfem.linalg.amg.rigid_modes` of ``pb.V`` (column R i + r the
    i-th motion of part r); ``laws`` the :class:`~skxfem.contact.newton.PointLaws`
    of the dofs.  A part whose dofs on Γ include one that carries tension gets none;
    one whose loads have no resultant gets ``angle`` NaN (:attr:`Holding.unloaded`).
    """
    dim = pb.mesh.dim()
    parts = modes.shape[1] // (3 if dim == 2 else 6)
    out = []
    for r in range(parts):
        T = modes[:, [parts * i + r for i in range(dim)]]
        if np.any(T[pb.D] != 0):          # a support touches it
            continue
        f = T.T @ F
        unloaded = np.linalg.norm(f) <= 1e-10 * max(
            float(np.abs(T).T @ np.abs(F) @ np.ones(dim)), 1e-300)  # or loads that cancel
        a = ops.Bn @ T                    # (m, dim): where Γ pushes the part at each dof
        t = [B @ T for B in ops.Bt]
        size = np.linalg.norm(a, axis=1)
        on = size > 1e-10 * size.max() if size.size and size.max() > 0 else size > 0
        if not on.any() or not laws.unilateral[on].all():
            continue                      # Γ does not touch it, or carries tension there
        axis = (a[on]).sum(axis=0)
        if np.linalg.norm(axis) == 0:
            continue
        axis = axis / np.linalg.norm(axis)
        beta, planar = 0.0, True
        for j in np.flatnonzero(on):
            kind = laws.tangential[j]
            mu = {"free": 0.0, "stick": np.inf}.get(kind, laws.mu[j])
            cols = [t[b][j] for b in range(len(t)) if not laws.tangent_held[j, b]]
            Tj = np.array(cols).T if cols else np.zeros((dim, 0))
            tilt = _angle(a[j], axis)
            planar &= tilt < 1e-9
            beta = max(beta, tilt + _half_angle(a[j], Tj, mu))
        out.append(Holding(r, 0.0 * f if unloaded else f, axis, beta,
                           np.nan if unloaded else _angle(f, axis), bool(planar)))
    return out


def _vector(v) -> str:
    v = np.where(np.abs(v) < 5e-4 * np.abs(v).max(), 0.0, v) + 0.0   # no -0
    return "(" + ", ".join(f"{x:.3g}" for x in v) + ")"


def _friction(laws, pb) -> str:
    """The friction of Γ in words: "Coulomb friction μ = 0.3", "a frictionless Γ"."""
    mus = np.unique(laws.mu[laws.tangential == "coulomb"])
    if mus.size == 1:
        return f"Coulomb friction μ = {mus[0]:g}"
    if mus.size:
        return f"Coulomb friction μ = {mus.min():g} to {mus.max():g}"
    return "a frictionless Γ"


def check_held_by_gamma(pb, ops, laws, F, modes, label=None, check_rigid=None) -> None:
    """Refuse loads ``F`` that no contact state can balance on a part that only Γ holds.

    The necessary condition of the module notes, before the step is solved.
    ``check_rigid(status, what, hint)`` raises the rigid-motion diagnosis of the
    state ``status`` (:func:`skxfem.contact.history._check_rigid`): used for a part the
    loads pull off Γ, with Γ open.

    Raises
    ------
    FrictionCannotHoldError
        (a ValueError) The loads press the part on Γ but push it along Γ harder
        than the friction can hold: the message names the part, the direction
        it slides, the ratio of the tangential to the normal force and the cure.
    skxfem.linalg.saddle.SingularSystemError
        (a ValueError) The loads pull the part off Γ: the rigid motions left
        free with Γ open (via ``check_rigid``).
    """
    names = region_names(pb)
    for h in holding(pb, ops, laws, F, modes):
        if h.held:
            continue
        who, f = names[h.part], h.force
        if h.unloaded:
            _refuse_unloaded(who, ops, laws, pb, label, check_rigid)
        if h.pulled:
            what = (f"Γ, which the loads on it pull open (their resultant {_vector(f)} points "
                    f"away from Γ, {np.degrees(h.angle - RIGHT):.3g}° beyond its plane, and Γ "
                    f"can only press on it: no contact state balances them)")
            if check_rigid is not None:
                check_rigid(np.full(ops.w.size, OPEN), what,
                            "hold that part with a support, or load it so that it "
                            "presses on Γ")
            raise FrictionCannotHoldError(
                f"load step {label!r}: {who} is held by nothing but {what}: hold that part "
                f"with a support, or load it so that it presses on Γ")
        normal = float(f @ h.axis)
        along = f - normal * h.axis
        friction = _friction(laws, pb)
        if h.planar and normal > 1e-12 * np.linalg.norm(f):
            mu = np.tan(h.half_angle)
            need = np.linalg.norm(along) / normal
            force = (f"with a tangential force {need / mu if mu > 0 else np.inf:.3g} × μ "
                     f"times the normal one ({np.linalg.norm(along):.3g} against μ × "
                     f"{normal:.3g} = {mu * normal:.3g})")
            cure = f"raise μ to at least {need:.3g}"
        else:
            force = (f"at {np.degrees(h.angle):.3g}° from the direction Γ pushes it "
                     f"{axis_name(h.axis)}, beyond the {np.degrees(h.half_angle):.3g}° "
                     f"that the friction cone of every point of Γ allows")
            cure = "raise μ"
        raise FrictionCannotHoldError(
            f"load step {label!r}: {friction} cannot hold {who}: nothing but Γ holds it, "
            f"and the loads on it (resultant {_vector(f)}) push it along "
            f"{_vector(along / np.linalg.norm(along))} {force}, so it slides along Γ as a "
            f"rigid body and no equilibrium exists (more load steps, another rho_n/rho_t "
            f"or max_iter cannot help): hold it with a support, {cure}, or change the loads")


def _refuse_unloaded(who: str, ops, laws, pb, label, check_rigid) -> None:
    """Refuse a state with no load on a part that only Γ holds (module notes): every
    pressure on Γ is 0, so Γ holds nothing and the part's place is not determined;
    the step, the part, the motion left free (via ``check_rigid``) and the cure."""
    what = (f"Γ (the loads on it have no resultant in this state: zero load, or loads "
            f"that cancel; so no point of Γ is pressed, and with zero pressure "
            f"{_friction(laws, pb)} holds nothing)")
    hint = ("hold that part with a support, or stop the load history before zero load "
            "(unloaded in several steps, e.g. to 0.1 then 0.01 of the load, the part "
            "tends to the place where friction leaves it)")
    if check_rigid is not None:
        check_rigid(np.full(ops.w.size, OPEN), what, hint)
    raise FrictionCannotHoldError(
        f"load step {label!r}: {who} is held by nothing but {what}: {hint}")
