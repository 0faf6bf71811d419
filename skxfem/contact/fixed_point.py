r"""The paper's scheme: a fixed point on the friction threshold μp around the contact problem.

Each pass freezes the threshold S = μp̄ (the radius of the Coulomb ball) at the
pressure of the previous pass and solves the contact problem with that
radius (Tresca friction: the threshold no longer depends on the unknowns);
its contact equation is solved by the active-set iteration on χ(g_n) —
exactly what the semi-smooth Newton method of :mod:`skxfem.contact.newton`
does on that equation, so the same routine serves.  The next pass takes
S = μp.  The passes stop when S changes by less than ``tol`` relative to
its size.

**The start.** The first threshold is μ max(p, 0) with p the pressure of the
step's *bonded* state (Γ tied, no slip: one linear solve, the first Newton
iteration from an untouched interface).  A threshold of zero, the
frictionless start, would leave a side that only the friction of Γ holds
free to slide in the first pass; the bonded state holds whatever the bonded
tie holds.

**Where it fails.** The frozen threshold is the weakness: where friction
changes the pressure strongly (a large μ), a pass may have no solution at
all.  A threshold S > 0 frozen at a point that must open is not zero there as
λ → 0: closed, the point carries a traction up to S, whose moment opens it;
open, it carries none, and it closes again.  The active-set iteration of
the pass then alternates between these two states.  A code that stops after
a fixed number of passes returns the last state, with a wrong force; here
the error is raised, and the last state is kept on the exception
(``error.last``) so that it can be shown.

>>> from dataclasses import replace
>>> from skxfem import contact
>>> from skxfem.scene import Displacement, SurfaceLoad, clamped
>>> from skxfem.scene.benchmarks import strip
>>> s = replace(strip(n=3), law="coulomb", friction=0.5,
...             loads=(SurfaceLoad("ymax", pressure=1.0),),
...             displacements=(clamped("ymin"), Displacement("ymax", {"x": 1.5})))
>>> fixed = contact.solve(s, method="fixed_point").steps[-1]
>>> fixed.newton.iterations, contact.solve(s).steps[-1].newton.iterations  # passes, Newton's
(6, 2)
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from .newton import TOL, ContactConvergenceError, NewtonInfo, newton, with_threshold

__all__ = ["fixed_point"]


def fixed_point(step, start, tol=TOL, max_iter=30, **linear):
    """Solve one load step by fixed point on μp; same arguments (``linear``:
    the keywords of the linear solve) and returns as
    :func:`skxfem.contact.newton.newton` (``iterations`` counts the passes,
    the no-slip start not included).

    Raises
    ------
    ContactConvergenceError
        After ``max_iter`` passes, or when a pass with its frozen threshold
        does not converge; ``error.last`` holds the last iterate, its residual
        and info, ``error.statuses`` the statuses of the last pass and
        ``error.thresholds`` the threshold of every pass.
    """
    laws = step.laws
    if not np.any(laws.tangential == "coulomb"):
        return newton(step, start, tol=tol, max_iter=max_iter, **linear)
    coulomb = laws.tangential == "coulomb"
    bonded = replace(laws, name=np.where(coulomb, "bonded", laws.name),
                     unilateral=laws.unilateral & ~coulomb,
                     tangential=np.where(coulomb, "stick", laws.tangential))
    it, res, _ = newton(replace(step, laws=bonded), start, tol=tol, max_iter=max_iter,
                        **linear)
    S = laws.mu * np.maximum(-it.lam, 0.0)
    thresholds, residuals = [S], []
    for n in range(1, max_iter + 1):
        try:
            it, res, info = newton(with_threshold(step, S), it, tol=tol, max_iter=max_iter,
                                   **linear)
        except ContactConvergenceError as e:
            seen = e.statuses
            two = len(seen) > 3 and np.array_equal(seen[-1], seen[-3]) and np.array_equal(
                seen[-2], seen[-4])
            err = ContactConvergenceError(
                f"the fixed point on the friction threshold failed in pass {n}: with the "
                f"threshold frozen, the active-set iteration "
                f"{'alternates between two states' if two else 'does not settle'} "
                f"({len(seen) - 1} iterations). Use method='newton'")
            err.last, err.statuses = e.last, seen
            err.thresholds = np.array(thresholds)
            raise err from e
        S_new = laws.mu * np.maximum(-it.lam, 0.0)
        change = np.abs(S_new - S).max() / max(np.abs(S_new).max(), 1e-300)
        residuals.append(np.r_[info.residuals[-1][:2], change])
        S = S_new
        thresholds.append(S)
        if change <= tol:
            return it, res, NewtonInfo(n, np.array(residuals))
    err = ContactConvergenceError(
        f"the fixed point on the friction threshold did not converge in {max_iter} "
        f"passes: the threshold still changes by {change:.1e} of its size (tolerance "
        f"{tol:.0e}); the last passes alternate between "
        f"{len({tuple(np.round(t, 12)) for t in thresholds[-4:]})} thresholds. Use "
        f"method='newton'")
    err.last, err.statuses = (it, res, info), None
    err.thresholds = np.array(thresholds)
    raise err
