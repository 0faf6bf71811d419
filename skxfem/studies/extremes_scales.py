r"""Extremes of the numbers a scene carries: E, ν and the contact laws' ρ_n, ρ_τ.

Rows of the extremes table (:mod:`skxfem.studies.extremes`):

* :func:`modulus_rows`: E from 10⁻⁶ to 10⁹ on the strip, with the load scaled
  alike (the displacement must not change) and unscaled (it must scale as
  1/E); the measure is the relative deviation from the E = 1 solution, held
  to 1e-8;
* :func:`poisson_rows`: ν up to 0.4999 against the exact solution of
  :mod:`skxfem.fem.exact`; the energy error is held to twice its value at ν = 0.3,
  so the first "inaccurate" row is where volumetric locking starts;
* :func:`rho_rows`: ρ_n and ρ_τ from 10⁻⁶ to 10⁹ × E/h on a frictional
  contact case (:func:`skxfem.contact.solve`); the measure is the deviation
  of the contact tractions from those of the default ρ, held to 1e-8, and the
  note gives the Newton iterations.

>>> rows = modulus_rows([1e6], n=2)
>>> [r.outcome for r in rows]
['solved', 'solved']
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..contact.history import solve as contact_solve
from ..fem.exact import ExactPlate
from ..fem.material import Material
from ..scene.benchmarks import P_MAX, strip
from ..scene.model import Displacement, SurfaceLoad
from ..solver import solve
from .convergence import energy_error
from .extremes import Row, attempt

__all__ = ["MODULI", "POISSON", "RHO_FACTORS", "modulus_rows", "poisson_rows", "exact_strip_for",
           "friction_scene", "rho_rows"]

MODULI = (1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9)
POISSON = (0.3, 0.45, 0.49, 0.499, 0.4999)
RHO_FACTORS = (1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9)
SCALE_TOL = 1e-8


def _loaded_strip(n: int, E: float, load: float):
    """:func:`skxfem.scenes.strip` (quadrilaterals) with modulus E and peak pressure ``load``."""
    base = strip(n, "quad")
    return replace(base, material=replace(base.material, E=E), loads=(SurfaceLoad(
        "ymax", pressure=lambda x: load * 4 * x[0] * (1 - x[0])),))


def _deviation(result, ref, u_factor: float, p_factor: float) -> float:
    """Largest relative deviation of u/u_factor and p/p_factor from ``ref``."""
    du = np.abs(result.U / u_factor - ref.U).max() / np.abs(ref.U).max()
    dp = np.abs(result.pressure / p_factor - ref.pressure).max() / np.abs(ref.pressure).max()
    return float(max(du, dp))


def modulus_rows(moduli=MODULI, n: int = 8) -> list[Row]:
    """E over ``moduli``, loads scaled alike (u unchanged, p ∝ E) and unscaled (u ∝ 1/E)."""
    ref = solve(_loaded_strip(n, 1.0, P_MAX))
    rows = []
    for E in moduli:
        rows.append(attempt("E", f"E = {E:g}, load scaled alike", "deviation from E = 1",
                            SCALE_TOL, lambda: _deviation(
                                solve(_loaded_strip(n, E, E * P_MAX)), ref, 1.0, E)))
        rows.append(attempt("E", f"E = {E:g}, load unscaled", "deviation from E = 1",
                            SCALE_TOL, lambda: _deviation(
                                solve(_loaded_strip(n, E, P_MAX)), ref, 1.0 / E, 1.0)))
    return rows


def exact_strip_for(material: Material, n: int = 8, cell: str = "quad"):
    """:func:`skxfem.scenes.exact_strip` for another ``material``: its loads and
    bottom displacement are those of :class:`skxfem.fem.exact.ExactPlate` for it."""
    sol = ExactPlate(material, 2, P_MAX)
    base = strip(n, cell)
    bottom = Displacement("ymin", {c: (lambda x, i=i: sol.displacement(x)[i])
                                   for i, c in enumerate("xy")})
    loads = (SurfaceLoad("ymax", pressure=sol.pressure),
             SurfaceLoad("xmin", pressure=sol.side_pressure),
             SurfaceLoad("xmax", pressure=sol.side_pressure))
    return replace(base, material=material, displacements=(bottom,), loads=loads,
                   name=f"exact_strip_{cell}_nu{material.nu:g}")


def _energy(material: Material, n: int, cell: str) -> float:
    sol = ExactPlate(material, 2, P_MAX)
    return energy_error(solve(exact_strip_for(material, n, cell)), sol.strain)


def poisson_rows(ratios=POISSON, n: int = 8, cells=("tri", "quad")) -> list[Row]:
    """ν over ``ratios`` (the first must be the reference, 0.3): the energy error
    against the exact solution, held to twice its value at the first ν."""
    rows = []
    for cell in cells:
        first = _energy(Material(1.0, ratios[0]), n, cell)
        for nu in ratios:
            rows.append(attempt(
                "nu", f"{cell}, ν = {nu:g}", "energy error (exact)", 2 * first,
                lambda: (lambda e: (e, f"{e / first:.2f} × the error at ν = {ratios[0]:g}"))(
                    _energy(Material(1.0, nu), n, cell))))
    return rows


def friction_scene(n: int = 8, shear: float = 0.1):
    """The exact strip with Coulomb friction μ = 0.3 and a shear ``shear`` on the top:
    stick in the middle of Γ, slip near the ends where the pressure vanishes."""
    base = exact_strip_for(Material(1.0, 0.3), n)
    top = SurfaceLoad("ymax", traction=(shear, 0.0))
    return replace(base, law="coulomb", friction=0.3, loads=base.loads + (top,),
                   name="friction_strip")


def _tractions(step) -> np.ndarray:
    return np.column_stack([step.pressure, step.traction])


def rho_rows(factors=RHO_FACTORS, n: int = 8) -> list[Row]:
    """ρ_n and ρ_τ over ``factors`` × their default E/h, the other at its
    default, on :func:`friction_scene`: deviation of the interface tractions
    from those of the default ρ, and the Newton iterations."""
    scene = friction_scene(n)
    ref = contact_solve(scene)
    h, t_ref = ref.ops.h, _tractions(ref.steps[-1])
    defaults = {"rho_n": ref.law.rho_n, "rho_t": ref.law.rho_t}
    rows = []
    for key, name in (("rho_n", "ρ_n"), ("rho_t", "ρ_τ")):
        unit = "E/h"
        for k in factors:
            def run(key=key, k=k):
                r = contact_solve(replace(scene, **{key: k * defaults[key]}))
                step = r.steps[-1]
                dev = np.abs(_tractions(step) - t_ref).max() / np.abs(t_ref).max()
                slip = int(np.sum(step.status == 2))
                return dev, f"{step.newton.iterations} Newton iterations, {slip} slipping"
            rows.append(attempt("rho", f"{name} = {k:g} {unit} (h = {h:.3g})",
                                "deviation from default ρ", SCALE_TOL, run))
    return rows
