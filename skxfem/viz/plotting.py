r"""Figures of the book: cut meshes, level sets and contact pressures.

Every function takes data and *returns* a :class:`matplotlib.figure.Figure`
(built directly, without pyplot, so nothing is shown twice and no backend is
chosen here).  Pass ``ax=`` to draw into an existing axes instead; the
figure of that axes is returned.

One colour scheme serves every figure of skxfem: :data:`COLORS` names the
colours of Ω⁻, Ω⁺ and Γ (sign convention in :mod:`skxfem.levelset`) and of
each multiplier space of :data:`skxfem.multipliers.SPACES`.

>>> from skxfem.multipliers import SPACES
>>> COLORS["minus"], COLORS["plus"], COLORS["gamma"]
('#9ecae1', '#fdd49e', '#a50f15')
>>> [COLORS[name] for name in SPACES]        # naive, winner, vital
['#e7298a', '#7570b3', '#1b9e77']
"""
from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.colors import LinearSegmentedColormap, TwoSlopeNorm
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.tri import Triangulation

from ..multipliers import SPACES

__all__ = [
    "BOOK_WIDTH",
    "LEGEND_PT",
    "legend_size",
    "COLORS",
    "CURVE_COLORS",
    "plot_cut_2d",
    "plot_levelset_2d",
    "plot_pressure",
]

#: The colours of skxfem, used by every figure.
COLORS = {
    "minus": "#9ecae1",       # Ω⁻ = {ψ < 0}, the paper's Ω¹
    "plus": "#fdd49e",        # Ω⁺ = {ψ > 0}, the paper's Ω²
    "minus_node": "#2171b5",  # nodes in Ω⁻
    "plus_node": "#d94801",   # nodes in Ω⁺
    "gamma": "#a50f15",       # the interface Γ and its intersection points
    "mesh": "#525252",        # mesh edges
    "naive": "#e7298a",       # multiplier spaces (skxfem.multipliers.SPACES)
    "winner": "#7570b3",
    "vital": "#1b9e77",
    "reference": "#000000",   # exact or reference curves
}

#: Colours, in order, of pressure curves whose label is not a multiplier space.
CURVE_COLORS = ("#08519c", "#e6550d", "#54278f", "#006d2c")

_MARKERS = ("o", "s", "^", "D", "v")

#: The width (inches) of a figure that the book shows at its own size: the page's
#: column at a 1200-pixel window is about 620 pixels, and a chapter's figures are
#: drawn at 100 pixels per inch; a wider figure is shown scaled down to the column.
BOOK_WIDTH = 6.2
#: The smallest legend text, in points, at the size the book shows a figure.
LEGEND_PT = 10.0


def legend_size(fig) -> float:
    """The legend font size (points) of ``fig`` that the book shows at
    :data:`LEGEND_PT` or larger: a figure wider than :data:`BOOK_WIDTH` is scaled
    down to the page's column, so its legend is drawn larger by the same factor.

    >>> legend_size(Figure(figsize=(6, 4))), legend_size(Figure(figsize=(12.4, 4)))
    (10.0, 20.0)
    """
    return float(LEGEND_PT * max(1.0, fig.get_figwidth() / BOOK_WIDTH))


def _figure_and_axes(ax, figsize):
    """A new figure with one axes, or the figure of the given axes."""
    if ax is not None:
        return ax.figure, ax
    fig = Figure(figsize=figsize, layout="constrained")
    return fig, fig.add_subplot()


def _cell_polygons(mesh, cells) -> np.ndarray:
    """Vertices (ncells, nverts, 2) of 2D cells, counter-clockwise (cells are convex)."""
    xy = np.transpose(mesh.p[:, mesh.t[:, cells]], (2, 1, 0))
    d = xy - xy.mean(axis=1, keepdims=True)
    order = np.argsort(np.arctan2(d[..., 1], d[..., 0]), axis=1)
    return np.take_along_axis(xy, order[..., None], axis=1)


def _side_colors(side) -> list:
    return [COLORS["minus"] if s < 0 else COLORS["plus"] for s in side]


def _draw_mesh_edges(ax, mesh):
    segments = np.transpose(mesh.p[:, mesh.facets], (2, 1, 0))
    ax.add_collection(LineCollection(segments, colors=COLORS["mesh"], linewidths=0.6))


def _finish_2d(ax, mesh, handles, title, ncol=3):
    ax.set_xlim(mesh.p[0].min(), mesh.p[0].max())
    ax.set_ylim(mesh.p[1].min(), mesh.p[1].max())
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    if title:
        ax.set_title(title)
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.12),
              ncol=ncol, frameon=False, fontsize=legend_size(ax.figure))


def plot_levelset_2d(mesh, psi, ax=None, title: str | None = None) -> Figure:
    """Nodal values of a level set on a 2D mesh, with its zero contour Γ_h.

    The colours run from Ω⁻ (ψ < 0) through white (ψ = 0) to Ω⁺ (ψ > 0);
    Γ_h is the zero contour of the piecewise linear interpolant of ψ on the
    triangles (quadrilaterals are split in two for drawing).

    Parameters
    ----------
    mesh
        A 2D scikit-fem mesh (``MeshTri1`` or ``MeshQuad1``).
    psi
        Nodal values, shape ``(nverts,)`` (see :func:`skxfem.levelset.nodal_values`).
    ax
        Axes to draw into; default a new figure.
    title
        Optional axes title.

    Returns
    -------
    Figure

    >>> from skxfem.fem.meshes import box
    >>> from skxfem.levelset import circle, nodal_values
    >>> m = box(8, "tri")
    >>> fig = plot_levelset_2d(m, nodal_values(circle((0.5, 0.5), 0.3), m))
    >>> len(fig.axes)          # the plot and its colour bar
    2
    """
    psi = np.asarray(psi, dtype=float)
    if mesh.dim() != 2 or psi.shape != (mesh.p.shape[1],):
        raise ValueError(f"need a 2D mesh and one value per vertex; got a {mesh.dim()}D "
                         f"mesh and psi of shape {psi.shape}")
    tri = mesh.to_meshtri() if mesh.t.shape[0] == 4 else mesh
    triangulation = Triangulation(tri.p[0], tri.p[1], tri.t.T)
    fig, ax = _figure_and_axes(ax, (5.5, 5.5))
    cmap = LinearSegmentedColormap.from_list(
        "skxfem_sides", [COLORS["minus_node"], COLORS["minus"], "#ffffff",
                         COLORS["plus"], COLORS["plus_node"]])
    span = max(np.abs(psi).max(), 1e-300)
    image = ax.tripcolor(triangulation, psi, shading="gouraud", cmap=cmap,
                         norm=TwoSlopeNorm(0.0, -span, span))
    bar = fig.colorbar(image, ax=ax, shrink=0.7)
    bar.ax.set_title("ψ")      # upright: a label along the bar turns ψ on its side
    _draw_mesh_edges(ax, mesh)
    if psi.min() < 0 < psi.max():
        ax.tricontour(triangulation, psi, levels=[0.0], colors=COLORS["gamma"],
                      linewidths=2.0)
    for s, key in ((-1, "minus_node"), (1, "plus_node")):
        on = np.sign(psi) == s
        ax.plot(*mesh.p[:, on], "o", ms=3, color=COLORS[key])
    handles = [Line2D([], [], color=COLORS["gamma"], lw=2, label="Γ_h: ψ_h = 0"),
               Line2D([], [], ls="", marker="o", ms=4, color=COLORS["minus_node"],
                      label="node in Ω⁻ (ψ < 0)"),
               Line2D([], [], ls="", marker="o", ms=4, color=COLORS["plus_node"],
                      label="node in Ω⁺ (ψ > 0)")]
    _finish_2d(ax, mesh, handles, title, ncol=2)
    return fig


def plot_cut_2d(mesh, cut, ax=None, title: str | None = None) -> Figure:
    """A 2D mesh cut by Γ: sides, sub-cells, interface facets, intersection points.

    Uncut cells are filled with the colour of their side; each cut cell is
    drawn as its sub-triangles (``cut.sub_ref`` mapped to physical
    coordinates), each filled with the colour of its side.  The interface
    facets are drawn in the colour of Γ with the intersection points
    ``cut.points`` (one per strictly cut edge); the enriched nodes
    ``cut.enriched`` are marked with the colour of their side.

    Parameters
    ----------
    mesh
        A 2D scikit-fem mesh.
    cut
        Its :class:`skxfem.cut.Cut`.
    ax
        Axes to draw into; default a new figure.
    title
        Optional axes title.

    Returns
    -------
    Figure

    >>> from skxfem.fem.meshes import box
    >>> from skxfem.levelset import circle
    >>> from skxfem.cut import cut
    >>> m = box(6, "quad")
    >>> fig = plot_cut_2d(m, cut(m, circle((0.5, 0.5), 0.3)))
    >>> len(fig.axes), len(fig.axes[0].collections)   # cells, sub-cells, edges, Γ
    (1, 4)
    """
    if mesh.dim() != 2:
        raise ValueError(f"plot_cut_2d needs a 2D mesh, got {mesh.dim()}D; use plot_cut_3d")
    fig, ax = _figure_and_axes(ax, (5.0, 5.5))
    uncut = np.flatnonzero(cut.side != 0)
    ax.add_collection(PolyCollection(_cell_polygons(mesh, uncut),
                                     facecolors=_side_colors(cut.side[uncut]),
                                     edgecolors="none"))
    X = np.transpose(cut.sub_ref, (2, 0, 1))  # (dim, nsub, nverts), reference coordinates
    sub = mesh.mapping().F(X, tind=cut.sub_cell)
    ax.add_collection(PolyCollection(np.transpose(sub, (1, 2, 0)),
                                     facecolors=_side_colors(cut.sub_side),
                                     edgecolors="#ffffff", linewidths=0.5))
    _draw_mesh_edges(ax, mesh)
    segments = np.transpose(cut.points[:, cut.facets], (2, 1, 0))
    ax.add_collection(LineCollection(segments, colors=COLORS["gamma"], linewidths=2.0))
    ax.plot(*cut.points, "o", ms=4, mfc="#ffffff", mec=COLORS["gamma"], mew=1.2)
    for s, key in ((-1, "minus_node"), (1, "plus_node")):
        nodes = cut.enriched[cut.node_side[cut.enriched] == s]
        ax.plot(*mesh.p[:, nodes], "s", ms=4, color=COLORS[key])
    handles = [Patch(color=COLORS["minus"], label="Ω⁻ (ψ < 0)"),
               Patch(color=COLORS["plus"], label="Ω⁺ (ψ > 0)"),
               Line2D([], [], color=COLORS["gamma"], lw=2, label="Γ_h facets"),
               Line2D([], [], ls="", marker="o", ms=5, mfc="#ffffff", mec=COLORS["gamma"],
                      label="intersection points"),
               Line2D([], [], ls="", marker="s", ms=4, color=COLORS["minus_node"],
                      label="enriched node in Ω⁻"),
               Line2D([], [], ls="", marker="s", ms=4, color=COLORS["plus_node"],
                      label="enriched node in Ω⁺")]
    _finish_2d(ax, mesh, handles, title)
    return fig


def plot_pressure(curves: Mapping[str, tuple], reference: Callable | tuple | None = None,
                  xlabel: str = "y", ax=None, title: str | None = None,
                  colors: Mapping[str, str] | None = None) -> Figure:
    """Contact pressure along a line: several labelled curves and a reference.

    The paper's Figures 5, 7 and 8.  A curve labelled with a multiplier space
    ("naive", "winner", "vital") gets that space's colour from :data:`COLORS`;
    other curves take :data:`CURVE_COLORS` in order, unless ``colors`` names
    their colour.

    Parameters
    ----------
    curves
        ``{label: (s, p)}``, e.g. from :func:`pressure_along`.
    reference
        A reference pressure: a callable ``p(s)`` (drawn over the range of the
        curves) or a pair ``(s, p)``; drawn as a black dashed line.
    xlabel
        Label of the abscissa.
    ax
        Axes to draw into; default a new figure.
    title
        Optional axes title.
    colors
        Optional ``{label: colour}`` overriding the defaults.

    Returns
    -------
    Figure

    >>> s = np.linspace(0, 1, 5)
    >>> fig = plot_pressure({"hex": (s, 0 * s), "naive": (s, s)}, lambda y: 4 * y * (1 - y))
    >>> len(fig.axes[0].lines), fig.axes[0].lines[1].get_color() == COLORS["naive"]
    (3, True)
    """
    if not curves:
        raise ValueError("curves must hold at least one {label: (s, p)} entry")
    colors = dict(colors or {})
    fig, ax = _figure_and_axes(ax, (6.0, 4.0))
    others = iter(CURVE_COLORS * (len(curves) // len(CURVE_COLORS) + 1))
    lo, hi = np.inf, -np.inf
    for k, (label, (s, p)) in enumerate(curves.items()):
        s, p = np.asarray(s, dtype=float), np.asarray(p, dtype=float)
        if s.shape != p.shape or s.ndim != 1:
            raise ValueError(f"curve {label!r}: s and p must be 1D arrays of the same "
                             f"length, got shapes {s.shape} and {p.shape}")
        color = colors.get(label) or (COLORS[label] if label in SPACES else next(others))
        ax.plot(s, p, marker=_MARKERS[k % len(_MARKERS)], ms=4, lw=1.3, color=color,
                label=label)
        lo, hi = min(lo, s.min()), max(hi, s.max())
    if reference is not None:
        if callable(reference):
            s_ref = np.linspace(lo, hi, 201)
            p_ref = np.asarray(reference(s_ref), dtype=float)
        else:
            s_ref, p_ref = (np.asarray(v, dtype=float) for v in reference)
        ax.plot(s_ref, p_ref, "--", color=COLORS["reference"], lw=1.2, label="reference")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("contact pressure p = -λ")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=legend_size(fig))
    if title:
        ax.set_title(title)
    return fig
