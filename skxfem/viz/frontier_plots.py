r"""Figures of the speed ↔ accuracy frontier (:mod:`skxfem.studies.frontier`), and its
part of ``skxfem reproduce``.

:func:`plot_frontier` draws error against wall time, log-log, one panel per
benchmark: one marker per method — its shape the cell type, its colour the
multiplier space (:data:`skxfem.viz.plotting.COLORS`), filled for the minimal
exact quadrature and hollow for a higher order — with a thin line through the
mesh sizes of a method (solid: the direct solve, dashed: the iterative one,
:data:`LINES`) and the Pareto front in black.
:func:`reproduce_frontier` runs a sweep and writes the two figures and the
numbers.

>>> from skxfem.studies.frontier import Point
>>> P = lambda n, t, e: Point("strip", "tri", "vital", None, "direct", n, 1, t, e, e)
>>> fig = plot_frontier([P(8, 0.1, 0.2), P(16, 0.3, 0.1)], "pressure")
>>> [ax.get_xscale() for ax in fig.axes], fig.axes[0].lines[0].get_linestyle()
(['log'], '-')
"""
from __future__ import annotations

import json
from dataclasses import asdict
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.ticker import FormatStrFormatter, LogLocator, NullFormatter

from ..studies.frontier import pareto, summary, sweep
from ..studies.frontier import plans as frontier_plans
from ..studies.progress import Progress
from .plotting import COLORS, legend_size

__all__ = ["MARKERS", "LINES", "plot_frontier", "reproduce_frontier"]

MARKERS = {"tri": "^", "quad": "s", "tet": "P", "hex": "D", "prism": "v"}
"""Marker of each cell type."""
LINES = {"direct": "-", "iterative": "--", "coulomb": ":", "coulomb/iterative": "-.",
         "coulomb/rho100": (0, (5, 1, 1, 1, 1, 1)), "coulomb/tol1e-6": (0, (1, 3))}
"""Line style of each solver of :data:`skxfem.studies.frontier.SOLVERS` (another: dotted)."""
_TITLES = {"plate": "paper's plate (3D, one cell along x)", "strip": "strip (2D)"}
_LABELS = {"energy": "relative energy error of u",
           "pressure": "relative L² error of the contact pressure"}


def plot_frontier(points, error: str = "energy") -> Figure:
    """Error (``"energy"`` or ``"pressure"``) against seconds, one panel per benchmark."""
    problems = [p for p in ("plate", "strip") if any(q.problem == p for q in points)]
    fig = Figure(figsize=(6.4, 5.6 * len(problems)), layout="constrained")
    axes = fig.subplots(len(problems), 1, squeeze=False)[:, 0]
    for ax, problem in zip(axes, problems):
        mine = [p for p in points if p.problem == problem]
        for method in dict.fromkeys(p.method for p in mine):
            pts = sorted((p for p in mine if p.method == method), key=lambda p: p.n)
            p0 = pts[0]
            colour = COLORS[p0.space]
            ax.plot([p.seconds for p in pts], [getattr(p, error) for p in pts], lw=0.6,
                    ls=LINES.get(p0.solver, ":"), color=colour, alpha=0.5,
                    marker=MARKERS[p0.cell], ms=6, mec=colour,
                    mfc=colour if p0.quadrature is None else "none")
        front = pareto(mine, error)
        ax.step([p.seconds for p in front], [getattr(p, error) for p in front], where="post",
                color=COLORS["reference"], lw=1.4, zorder=5)
        ax.set(xscale="log", yscale="log", xlabel="wall time of assemble + solve [s]",
               ylabel=_LABELS[error], title=_TITLES[problem])
        lo, hi = ax.get_xlim()  # labelled ticks even within one decade, not crowded over many
        ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0) if np.log10(hi / lo) > 1.5
                                              else (1.0, 1.5, 2.0, 3.0, 5.0, 7.0)))
        ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
        cells = dict.fromkeys(p.cell for p in mine)
        spaces = dict.fromkeys(p.space for p in mine)
        handles = [Line2D([], [], ls="", marker=MARKERS[c], color="grey", label=c)
                   for c in cells]
        handles += [Line2D([], [], ls="", marker="o", color=COLORS[s], label=s) for s in spaces]
        handles += [Line2D([], [], ls=LINES.get(v, ":"), lw=0.8, color="grey", label=f"{v} solve")
                    for v in dict.fromkeys(p.solver for p in mine)]
        handles += [Line2D([], [], ls="", marker="o", mfc="grey", mec="grey",
                           label="minimal exact rule"),
                    Line2D([], [], ls="", marker="o", mfc="none", mec="grey",
                           label="quadrature order 4"),
                    Line2D([], [], color=COLORS["reference"], label="Pareto front")]
        ax.legend(handles=handles, fontsize=legend_size(fig), loc="upper center",
                  bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
    return fig


def reproduce_frontier(out, quick: bool = True, sizes=None, repeat: int | None = None,
                       progress: bool | None = None, plans=None) -> dict:
    """Run the frontier sweep of ``skxfem reproduce`` and write its files.

    The plans are :func:`skxfem.studies.frontier.plans` ``(quick, sizes)`` unless
    ``plans`` is given; each time is the least of ``repeat`` runs (default 1
    with ``quick`` or ``sizes``, else 3).  Writes ``frontier_energy.png``,
    ``frontier_pressure.png`` and ``frontier.json`` (every point and the
    per-method :func:`~skxfem.studies.frontier.summary`) into ``out`` and returns the
    summary.  ``progress``: one line per solve (default: in a terminal only).
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    if repeat is None:
        repeat = 1 if (quick or sizes) else 3
    points = []
    for plan in plans or frontier_plans(quick, sizes):
        p = Progress(len(plan.methods()), f"frontier {plan.problem}", enabled=progress)
        points += sweep(plan, repeat, p)
    for error in ("energy", "pressure"):
        plot_frontier(points, error).savefig(out / f"frontier_{error}.png", dpi=120)
    result = summary(points)
    (out / "frontier.json").write_text(json.dumps(
        {"points": [asdict(p) for p in points], "methods": result}, indent=1) + "\n")
    return result
