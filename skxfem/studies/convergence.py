r"""Error measures and convergence rates (paper §5, Figures 9 and 10).

* The L² error of the contact pressure on Γ, relative (paper's L(λʰ)):

  .. math:: L = \Big(\int_\Gamma (p_h - p)^2 \Big/ \int_\Gamma p^2\Big)^{1/2},

  with p_h the P1 interpolant of the pressures at the multiplier points on
  the interface facets, and its maximum at those points (oscillations).
* The relative energy error of the displacement (paper's W(uʰ)), integrated
  on each side of Γ with the sub-cell quadrature.
* Observed rates log(e₁/e₂)/log(h₁/h₂) between successive meshes.

>>> observed_rates([0.5, 0.25, 0.125], [1.0, 0.25, 0.0625]).tolist()
[2.0, 2.0]
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable

import numpy as np
from skfem.helpers import ddot

from ..enrich import signed_bases
from ..fem.exact import ExactPlate
from ..lbb import inf_sup
from ..multipliers import interface_rule
from ..solver import solve
from .progress import Progress

__all__ = ["PressureError", "pressure_error", "energy_error", "observed_rates", "StudyRow",
           "study", "summary_rates", "summary_columns"]


@dataclass(frozen=True)
class PressureError:
    """``l2`` relative L²(Γ) error, ``max`` largest error at the points / max|p|."""

    l2: float
    max: float


def pressure_error(result, exact: Callable) -> PressureError:
    """Pressure error of a :class:`skxfem.result.Result` against ``exact(x)``."""
    V = result.V
    if len(result.regions) != 2:
        raise ValueError("pressure_error measures a result with one interface; this one "
                         "has several")
    rule = interface_rule(V.mesh, V.cut)
    ph = rule.N @ result.pressure
    p = exact(rule.points)
    l2 = np.sqrt(np.sum(rule.weights * (ph - p) ** 2) / np.sum(rule.weights * p ** 2))
    pts = exact(result.points)
    return PressureError(float(l2), float(np.abs(result.pressure - pts).max()
                                         / np.abs(pts).max()))


def energy_error(result, exact_strain: Callable, order: int = 4) -> float:
    """Relative energy norm of u_h - u, exact strain ``exact_strain(x)``.

    ∇u_h = ∇(Πa) + H ∇(Πb) - ∇(Π(Hⱼ b)) on each side, Π the standard interpolant.
    The integrals use their own rule of ``order``, on the cells and on the
    sub-simplices, never the solver's (which is only exact for the
    stiffness): the default 4 is exact for the quadratic strain of
    :mod:`skxfem.fem.exact` against P1, Q1 and prism fields on affine cells.
    """
    V, material = result.V, result.scene.material
    if len(result.regions) != 2:
        raise ValueError("energy_error measures a result with one interface; this one has "
                         "several")
    dim = V.mesh.dim()
    a = result.U[:V.n_std]
    b = np.zeros(V.n_std)
    b[V.enr_dofs] = result.U[V.n_std:]
    hb = np.zeros(V.n_std)
    hb[V.enr_dofs] = V.H_node * result.U[V.n_std:]
    num = den = 0.0
    for basis, H in signed_bases(V, (order, order)):
        G = basis.interpolate(a).grad + H * basis.interpolate(b).grad \
            - basis.interpolate(hb).grad
        eps_h = 0.5 * (G + np.swapaxes(G, 0, 1))
        eps = exact_strain(basis.mapping.F(basis.X, tind=basis.tind))
        e = eps_h - eps
        num += np.sum(ddot(material.stress(e, dim), e) * basis.dx)
        den += np.sum(ddot(material.stress(eps, dim), eps) * basis.dx)
    return float(np.sqrt(num / den))


def observed_rates(h, errors) -> np.ndarray:
    """Slopes log(eᵢ/eᵢ₊₁) / log(hᵢ/hᵢ₊₁) between successive meshes."""
    h, e = np.asarray(h, float), np.asarray(errors, float)
    return np.log(e[:-1] / e[1:]) / np.log(h[:-1] / h[1:])


def summary_rates(h, errors) -> list[float]:
    """:func:`observed_rates` as ``summary.json`` stores them: rounded to 4 digits,
    none for a single mesh."""
    return [round(float(r), 4) for r in observed_rates(h, errors)] if len(h) > 1 else []


@dataclass(frozen=True)
class StudyRow:
    """One mesh of a convergence study (see :func:`study`)."""

    n: int
    h: float
    space: str
    beta: float
    n_zero: int
    pressure_l2: float
    pressure_max: float
    energy: float
    n_dofs: int
    n_multipliers: int
    seconds: float


def study(make_scene: Callable, ns, spaces=("naive", "winner", "vital"),
          exact=None, with_inf_sup: bool = True, progress: Progress | None = None
          ) -> list[StudyRow]:
    """Solve ``make_scene(n, space)`` for every n and space and measure it.

    ``exact`` is an :class:`skxfem.fem.exact.ExactPlate` (default: built for the
    scene's material and dimension).  h = 1/n.  ``progress``: one line per
    mesh (default: a :class:`skxfem.studies.progress.Progress`, on in a terminal only).

    >>> from skxfem.scene.benchmarks import exact_strip
    >>> rows = study(lambda n, s: exact_strip(n, "quad", space=s), [4], ["naive"])
    >>> rows[0].n, rows[0].pressure_l2 < 0.05
    (4, True)
    """
    rows = []
    progress = progress or Progress(len(spaces) * len(ns), "study")
    for space in spaces:
        for n in ns:
            scene = make_scene(n, space)
            sol = exact or ExactPlate(scene.material, scene.dim)
            t0 = time.perf_counter()
            result = solve(scene)
            p = pressure_error(result, sol.pressure)
            e = energy_error(result, sol.strain)
            seconds = time.perf_counter() - t0
            I = inf_sup(scene) if with_inf_sup else None
            rows.append(StudyRow(n, 1.0 / n, space, I.beta if I else float("nan"),
                                 I.n_zero if I else -1, p.l2, p.max, e, result.n_dofs,
                                 result.n_multipliers, seconds))
            progress.step(f"{scene.name} ({space})")
    return rows


def summary_columns(rows: list[StudyRow]) -> dict:
    """The columns of ``summary.json`` of one space's rows, coarsest first: ``n``, ``h``,
    the errors with their rates (:func:`summary_rates`), the sizes and the solve time.

    >>> row = lambda n: StudyRow(n, 1 / n, "vital", 0.0, 0, 1 / n, 0.0, 1 / n**2, 0, 0, 0.0)
    >>> summary_columns([row(2), row(4)])["energy_rates"]
    [2.0]
    """
    h = [r.h for r in rows]
    return {"n": [r.n for r in rows], "h": h,
            "energy": [r.energy for r in rows],
            "energy_rates": summary_rates(h, [r.energy for r in rows]),
            "pressure_l2": [r.pressure_l2 for r in rows],
            "pressure_l2_rates": summary_rates(h, [r.pressure_l2 for r in rows]),
            "pressure_max": [r.pressure_max for r in rows],
            "n_dofs": [r.n_dofs for r in rows],
            "n_multipliers": [r.n_multipliers for r in rows],
            "seconds_solve": [round(r.seconds, 3) for r in rows]}
