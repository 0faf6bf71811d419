"""The look shared by the paper's figures: one style per cell type and space.

Colours come from :data:`skxfem.viz.plotting.COLORS` (one per multiplier space);
the cell type sets the line style and marker (:data:`CELL_STYLE`: triangles
solid, quadrilaterals dashed, prisms dash-dotted, hexahedra dotted).  These
small helpers draw into a given axes; the figures of :mod:`skxfem.viz.figures`
and :mod:`skxfem.viz.plot_space` are built from them.

>>> from matplotlib.figure import Figure
>>> ax = Figure().add_subplot()
>>> curve(ax, [0, 1], [0, 1], "vital", "prism", "vital, prism")
>>> ax.lines[0].get_linestyle(), ax.lines[0].get_marker()
('-.', 'v')
"""
from __future__ import annotations

import numpy as np
from matplotlib.colors import to_rgb
from matplotlib.ticker import NullFormatter

from ..fem.cells import CELL_TYPES
from ..studies.convergence import observed_rates
from .plotting import COLORS

__all__ = ["CELL_STYLE", "CELL_DIM", "p_ref", "curve", "reference", "shades", "finish",
           "slope_label", "log_axes"]

#: Line style and marker of each cell type.
CELL_STYLE = {"tri": ("-", "^"), "quad": ("--", "s"), "prism": ("-.", "v"),
              "hex": (":", "D"), "tet": ((0, (1, 1)), "x")}
CELL_DIM = {name: c.dim for name, c in CELL_TYPES.items()}


def p_ref(s):
    """The paper's reference p(y) = 4 P_max y (1 - y), P_max = 1."""
    return 4.0 * s * (1.0 - s)


def curve(ax, s, p, space, cell=None, label=None, color=None):
    """Plot p(s) in the colour of ``space`` and the style of ``cell``."""
    ls, marker = CELL_STYLE.get(cell, ("-", "o"))
    ax.plot(s, p, ls=ls, marker=marker, ms=3.5, lw=1.3, label=label,
            color=color or COLORS.get(space, COLORS["mesh"]))


def reference(ax, lo, hi, label):
    """The reference p(s) on [lo, hi], dashed black."""
    s = np.linspace(lo, hi, 201)
    ax.plot(s, p_ref(s), "--", color=COLORS["reference"], lw=1.2, label=label)


def shades(color, k):
    """k shades of ``color``, light to full."""
    c = np.array(to_rgb(color))
    return [tuple(1 - (1 - c) * t) for t in np.linspace(0.35, 1.0, k)]


def finish(ax, xlabel, title, ylabel="contact pressure p = -λ", below=False):
    """Labels, title, grid and legend (below the axes with ``below=True``)."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize="medium")
    ax.grid(True, alpha=0.3)
    if below:
        ax.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.15),
                  ncol=2, frameon=False)
    else:
        ax.legend(fontsize="small")


def slope_label(x, y) -> str:
    """", slope s" of the last segment of a log-log curve ('' for one point)."""
    if len(x) < 2:
        return ""
    return f", slope {round(float(observed_rates(x, y)[-1]), 2) + 0.0:.2f}"


def log_axes(ax):
    """Log scales on both axes, no minor tick labels."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_minor_formatter(NullFormatter())
