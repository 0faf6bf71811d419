"""The look shared by the paper's figures: one style per cell type and space.

Colours come from :data:`skxfem.viz.plotting.COLORS` (one per multiplier space);
the cell type sets the line style and marker (:data:`CELL_STYLE`: triangles
solid, quadrilaterals dashed, prisms dash-dotted, hexahedra dotted), and, where
one figure compares cell types in one space (Figure 5), the shade of the space's
colour (:func:`cell_colour`: hexahedra and quadrilaterals dark).  Curves that
coincide are said so in the legend and drawn with nested markers
(:func:`coinciding`).  Legends are :data:`~skxfem.viz.plotting.LEGEND_PT` or
larger at the size the book shows the figure
(:func:`~skxfem.viz.plotting.legend_size`).  These
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
from .plotting import COLORS, legend_size

__all__ = ["CELL_STYLE", "CELL_DIM", "DARK_CELLS", "p_ref", "curve", "reference", "shades",
           "cell_colour", "coinciding", "loglog_curves", "finish", "slope_label", "log_axes"]

#: Line style and marker of each cell type.
CELL_STYLE = {"tri": ("-", "^"), "quad": ("--", "s"), "prism": ("-.", "v"),
              "hex": (":", "D"), "tet": ((0, (1, 1)), "x")}
CELL_DIM = {name: c.dim for name, c in CELL_TYPES.items()}
#: The cell types drawn in a dark shade of their space's colour where a figure
#: compares cell types (:func:`cell_colour`): the tensor-product cells.
DARK_CELLS = ("hex", "quad")


def p_ref(s):
    """The paper's reference p(y) = 4 P_max y (1 - y), P_max = 1."""
    return 4.0 * s * (1.0 - s)


def curve(ax, s, p, space, cell=None, label=None, color=None, ms=3.5, hollow=False):
    """Plot p(s) in the colour of ``space`` and the style of ``cell`` (markers of
    size ``ms``, open with ``hollow=True``)."""
    ls, marker = CELL_STYLE.get(cell, ("-", "o"))
    color = color or COLORS.get(space, COLORS["mesh"])
    ax.plot(s, p, ls=ls, marker=marker, ms=ms, lw=1.3, label=label, color=color,
            markerfacecolor="none" if hollow else color)


def cell_colour(space, cell):
    """The colour of ``space``, darkened (0.55 of it) for the cells of :data:`DARK_CELLS`:
    two cell types of one space in one figure get two distinct colours.

    >>> cell_colour("naive", "prism") == to_rgb(COLORS["naive"]), cell_colour("naive", "hex")
    (True, (0.5, 0.09, 0.3))
    """
    c = np.array(to_rgb(COLORS[space]))
    return tuple(float(round(v, 2)) for v in c * 0.55) if cell in DARK_CELLS else tuple(c)


def coinciding(curves, rtol=0.02):
    """Group curves that the eye cannot tell apart: ``curves`` is a list of ``(x, y)``;
    returns, for each, the index of the first earlier curve it coincides with (same x,
    every y within ``rtol``), or None.

    >>> coinciding([([1, 2], [1.0, 2.0]), ([1, 2], [1.0, 2.01]), ([1, 2], [3.0, 4.0])])
    [None, 0, None]
    """
    first = []
    for k, (x, y) in enumerate(curves):
        first.append(next((j for j in range(k) if first[j] is None
                           and np.array_equal(np.asarray(curves[j][0]), np.asarray(x))
                           and np.allclose(curves[j][1], y, rtol=rtol, atol=0)), None))
    return first


def reference(ax, lo, hi, label):
    """The reference p(s) on [lo, hi], dashed black."""
    s = np.linspace(lo, hi, 201)
    ax.plot(s, p_ref(s), "--", color=COLORS["reference"], lw=1.2, label=label)


def shades(color, k):
    """k shades of ``color``, light to dark: from 60 % of it on white (the palest,
    still plainly visible on white) to 70 % of it on black.

    >>> [tuple(round(v, 2) for v in s) for s in shades("#000000", 2)]
    [(0.4, 0.4, 0.4), (0.0, 0.0, 0.0)]
    """
    c = np.array(to_rgb(color))
    out = []
    for t in np.linspace(-0.4, 0.3, k):
        out.append(tuple(float(v) for v in (c + (1 - c) * -t if t < 0 else c * (1 - t))))
    return out


def loglog_curves(ax, curves, slopes=True):
    """Draw ``curves``, ``(x, y, space, cell, name, colour)`` each (``colour`` None:
    the space's), with the slope of the last segment in the label if ``slopes``; a
    curve that :func:`coinciding` finds on an earlier one is labelled "(coincides
    with ...)" and the group is drawn with nested markers, the first largest and
    open, so that every curve of it stays visible.  Returns the abscissae drawn.

    >>> from matplotlib.figure import Figure
    >>> ax = Figure().add_subplot()
    >>> _ = loglog_curves(ax, [([1, 2], [1, .5], "naive", "tri", "naive, tri", None),
    ...                        ([1, 2], [1, .5], "vital", "tri", "vital, tri", None)])
    >>> [ln.get_label() for ln in ax.lines]
    ['naive, tri, slope -1.00', 'vital, tri, slope -1.00 (coincides with naive)']
    """
    same = coinciding([(x, y) for x, y, *_ in curves])
    for k, (x, y, space, cell, name, colour) in enumerate(curves):
        first = k if same[k] is None else same[k]
        members = [first] + [j for j in range(len(curves)) if same[j] == first]
        rank = members.index(k)            # 0: drawn first, under the others
        other = curves[first][4] if curves[first][3] != cell else curves[first][2]
        note = "" if same[k] is None else f" (coincides with {other})"
        slope = slope_label(x, y) if slopes else ""
        curve(ax, x, y, space, cell, f"{name}{slope}{note}", color=colour,
              ms=3.5 + 3.0 * (len(members) - 1 - rank), hollow=rank < len(members) - 1)
    return sorted({round(float(v), 6) for x, *_ in curves for v in x})


def finish(ax, xlabel, title, ylabel="contact pressure p = -λ", below=False):
    """Labels, title, grid and legend (below the axes with ``below=True``)."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize="medium")
    ax.grid(True, alpha=0.3)
    if below:
        ax.legend(fontsize=legend_size(ax.figure), loc="upper center", bbox_to_anchor=(0.5, -0.15),
                  ncol=1, frameon=False)
    else:
        ax.legend(fontsize=legend_size(ax.figure))


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
