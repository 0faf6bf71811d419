"""Figures of the genuinely 3D validation (:mod:`skxfem.studies.validation3d`).

* :func:`fig_block`: energy error, L² pressure error and largest pressure
  error vs 1/h on the block, per cell (line style) and space (colour);
* :func:`fig_block_pressure`: the computed pressure at the multiplier points
  against the exact one, naive vs vital, one panel per cell.

Both return a :class:`matplotlib.figure.Figure` built without pyplot, in the
style of :mod:`skxfem.viz.figstyle`.
"""
from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ..cut import cut
from ..fem.exact3d import ExactBlock
from ..linalg.saddle import NearlyDependentError
from ..multipliers import SPACES
from ..scene.benchmarks import P_MAX, exact_block
from ..scene.model import resolve
from ..solver import solve
from ..studies.validation3d import CELLS
from .figstyle import finish, log_axes, loglog_curves
from .plotting import COLORS, legend_size

__all__ = ["fig_block", "fig_block_pressure"]

_PANELS = (("energy", "energy error W(u_h)", True),
           ("pressure_l2", "pressure error L(λ_h), L²(Γ)", True),
           ("pressure_max", "largest pressure error / max |p|", False))


def _failures_note(block) -> str:
    """One line per (cell, space) with meshes missing from the curves."""
    missing = {}
    for f in block.failures:
        kind = "not run" if f.reason.startswith("not run") else "refused by the solver"
        missing.setdefault((f.cell, f.space, kind), []).append(f.n)
    return "; ".join(f"{space} on {cell}: {kind} at n = {', '.join(map(str, ns))}"
                     for (cell, space, kind), ns in missing.items())


def fig_block(block) -> Figure:
    """Errors vs 1/h on the block, log-log, the slope of the last segment in the legend.

    Parameters
    ----------
    block
        A :class:`skxfem.studies.validation3d.BlockStudy`; the meshes it has no result
        for (its ``failures``) are listed under the panels.

    >>> from skxfem.studies.validation3d import study_block
    >>> fig = fig_block(study_block([2, 3], cells=("hex",), spaces=("vital",)))
    >>> len(fig.axes), fig.axes[0].lines[0].get_label()[:10]
    (3, 'vital, hex')
    """
    fig = Figure(figsize=(6.4, 5.4 * len(_PANELS)), layout="constrained")
    axes = fig.subplots(len(_PANELS), 1)
    for ax, (key, label, slopes) in zip(axes, _PANELS):
        drawn = []
        for cell, rows in block.rows.items():
            for space in [s for s in SPACES if any(r.space == s for r in rows)]:
                mine = sorted((r for r in rows if r.space == space), key=lambda r: r.n)
                n = np.array([r.n for r in mine], float)
                y = np.array([getattr(r, key) for r in mine])
                drawn.append((n, y, space, cell, f"{space}, {cell}", None))
        ticks = loglog_curves(ax, drawn, slopes)
        log_axes(ax)
        ax.set_xticks(ticks, [f"{t:g}" for t in ticks])
        ax.set_xlabel("1/h (cells per side)")
        ax.set_ylabel(label)
        ax.set_title(label, fontsize="medium")
        ax.grid(True, alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=legend_size(fig), ncol=1 if slopes else 3, loc="upper center",
                      bbox_to_anchor=(0.5, -0.16), frameon=False)
    note = _failures_note(block)
    fig.suptitle("the block of skxfem.fem.exact3d (Γ slanted against all three axes): "
                 "errors against h" + (f"\n(missing: {note})" if note else ""),
                 fontsize="medium")
    return fig


def fig_block_pressure(n: int = 8, cells=CELLS, spaces=("naive", "vital")) -> Figure:
    """The contact pressure at the multiplier points against the exact one.

    On a converged, non-oscillating space the points lie on the diagonal.
    One panel per cell, :func:`~skxfem.scenes.exact_block` with ``n`` cells
    per side, one colour per space; points beyond the frame (the frame is
    twice the range of the exact pressure) are drawn on its edge as
    triangles and counted in the legend.  A space the solver refuses is
    named in the panel.

    >>> fig = fig_block_pressure(3, cells=("hex",), spaces=("vital",))
    >>> fig.axes[0].get_title()
    'hexahedra, n = 3'
    """
    exact = ExactBlock(exact_block(1).material, P_MAX)
    fig = Figure(figsize=(6.4, 5.0 * len(cells)), layout="constrained")
    names = {"hex": "hexahedra", "prism": "prisms", "tet": "tetrahedra"}
    for ax, cell in zip(np.atleast_1d(fig.subplots(len(cells), 1)), cells):
        scene = exact_block(n, cell)
        scene, mesh = resolve(scene)
        everywhere = exact.pressure(cut(mesh, scene.interfaces[0].levelset).points)
        lo, hi = everywhere.min(), everywhere.max()
        pad = 0.5 * (hi - lo)
        refused = []
        for space in spaces:
            try:
                result = solve(exact_block(n, cell, space=space))
            except NearlyDependentError:
                refused.append(space)
                continue
            p = exact.pressure(result.points)
            ph = np.clip(result.pressure, lo - pad, hi + pad)
            out = ph != result.pressure
            suffix = f" ({np.count_nonzero(out)} beyond the frame)" if out.any() else ""
            ax.plot(p[~out], ph[~out], "o", ms=3, alpha=0.7, color=COLORS[space],
                    label=f"{space}: {result.n_multipliers} multipliers{suffix}")
            for side, marker in ((result.pressure > ph, "^"), (result.pressure < ph, "v")):
                ax.plot(p[side], ph[side], marker, ms=5, color=COLORS[space])
        ax.plot([lo, hi], [lo, hi], "--", color=COLORS["reference"], lw=1.2,
                label="p_h = p (exact)")
        ax.set_xlim(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo))
        ax.set_ylim(lo - 1.05 * pad, hi + 1.05 * pad)
        if refused:
            ax.text(0.5, 0.04, f"{', '.join(refused)}: refused by the solver\n(nearly "
                    "dependent multipliers)", transform=ax.transAxes, ha="center",
                    fontsize="small", color=COLORS[refused[0]])
        finish(ax, "exact pressure p at the multiplier point",
               f"{names[cell]}, n = {n}", "computed pressure p_h", below=True)
    return fig
