r"""The paper's figures, one function each (Géniaut, Massin & Moës 2007, §5).

* :func:`fig5`, Figure 5: naive multipliers, hexahedra vs prisms (and
  quadrilaterals vs triangles in 2D);
* :func:`fig6`, Figure 6: the graph example, vital edges, groups, winner nodes
  and the P0/P1 multipliers of both algorithms;
* :func:`fig7`, Figure 7: vital edges on prisms as the mesh is refined;
* :func:`fig8`, Figure 8: algo1 vs algo2 on half the length, two meshes;
* :func:`fig9`, Figure 9: energy error vs 1/h, per space and cell;
* :func:`fig10`, Figure 10: L² error of the contact pressure vs 1/h;
* :func:`fig_inf_sup` (ours): the inf-sup constant β_h vs h, in two norms;
* :func:`plot_space_2d` (ours): a multiplier space drawn on a 2D mesh.

Every function returns a :class:`matplotlib.figure.Figure` built without
pyplot.  Colours are those of :data:`skxfem.plotting.COLORS`: one per
multiplier space; the cell type sets the line style and marker
(:data:`CELL_STYLE`: triangles solid, quadrilaterals dashed, prisms
dash-dotted, hexahedra dotted).

Figures 5, 7 and 8 solve small scenes themselves; Figures 9, 10 and the
inf-sup plot take the data (:class:`skxfem.convergence.StudyRow` lists,
:class:`skxfem.lbb.InfSup` lists), which :mod:`skxfem.reproduce` computes.

Two references are used, and each plot says which: the paper's p(y) =
4y(1 - y) on its clamped plate (:func:`skxfem.scenes.paper_plate`), where it
is only approximate, and the same p(y) under the extra side loads of
:mod:`skxfem.exact` (:func:`skxfem.scenes.exact_plate`), where it is exact.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Ellipse

from .convergence import observed_rates
from .multipliers import SPACES
from .plotting import COLORS, pressure_along
from .simplex import edge_point

__all__ = ["FIG6_XY", "FIG6_EDGES", "figure6_graph", "fig5", "fig6", "fig7", "fig8",
           "fig9", "fig10", "fig_inf_sup", "plot_space_2d"]

#: Line style and marker of each cell type.
CELL_STYLE = {"tri": ("-", "^"), "quad": ("--", "s"), "prism": ("-.", "v"),
              "hex": (":", "D"), "tet": ((0, (1, 1)), "x")}
_DIM = {"tri": 2, "quad": 2, "hex": 3, "prism": 3, "tet": 3}


def _p_ref(s):
    """The paper's reference p(y) = 4 P_max y (1 - y), P_max = 1."""
    return 4.0 * s * (1.0 - s)


def _curve(ax, s, p, space, cell=None, label=None, color=None):
    ls, marker = CELL_STYLE.get(cell, ("-", "o"))
    ax.plot(s, p, ls=ls, marker=marker, ms=3.5, lw=1.3, label=label,
            color=color or COLORS.get(space, COLORS["mesh"]))


def _reference(ax, lo, hi, label):
    s = np.linspace(lo, hi, 201)
    ax.plot(s, _p_ref(s), "--", color=COLORS["reference"], lw=1.2, label=label)


def _shades(color, k):
    """k shades of ``color``, light to full."""
    from matplotlib.colors import to_rgb

    c = np.array(to_rgb(color))
    return [tuple(1 - (1 - c) * t) for t in np.linspace(0.35, 1.0, k)]


def _finish(ax, xlabel, title, ylabel="contact pressure p = -λ", below=False):
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize="medium")
    ax.grid(True, alpha=0.3)
    if below:
        ax.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.15),
                  ncol=2, frameon=False)
    else:
        ax.legend(fontsize="small")


def fig5(n: int = 8, nx: int | None = None) -> Figure:
    """Figure 5: the naive space oscillates on prisms, not on hexahedra.

    Left: the paper's plate (:func:`~skxfem.scenes.paper_plate`: clamped
    bottom, bonded interface) with ``n`` cells in y, pressure on the line
    x = 1/2 of Γ, against the paper's reference p(y), only approximate there.
    Right: the 2D analogue, quadrilaterals vs triangles, under the loads of
    :func:`~skxfem.scenes.exact_strip`, for which p(x) is the exact pressure.

    Parameters
    ----------
    n
        Cells in y (the plate) and x (the strip).
    nx
        Cells along x of the plate; default ``n`` (the solution does not
        depend on x: ``nx=1`` gives the same curves, faster).

    >>> fig = fig5(n=4, nx=1)
    >>> len(fig.axes), [len(ax.lines) for ax in fig.axes]   # hex, prism, reference
    (2, [3, 3])
    """
    from dataclasses import replace

    from .scenes import exact_strip, paper_plate
    from .solver import solve

    fig = Figure(figsize=(9, 4.3), layout="constrained")
    left, right = fig.subplots(1, 2)
    for cell in ("hex", "prism"):
        scene = paper_plate(n, cell, space="naive")
        if nx is not None:
            scene = replace(scene, mesh=replace(scene.mesh, n=(nx,) + scene.mesh.n[1:]))
        s, p = pressure_along(solve(scene), "y")
        _curve(left, s, p, "naive", cell, f"{cell}, naive")
    _reference(left, 0, 1, "paper's reference p(y) (approximate here)")
    _finish(left, "y", f"3D plate, clamped ({n} cells in y): the paper's set-up",
            below=True)
    for cell in ("quad", "tri"):
        s, p = pressure_along(solve(exact_strip(n, cell, space="naive")), "x")
        _curve(right, s, p, "naive", cell, f"{cell}, naive")
    _reference(right, 0, 1, "exact p(x)")
    _finish(right, "x", f"2D strip, exact loads ({n} cells in x)", below=True)
    return fig


# ------------------------------------------------------------------ Figure 6
#: The paper's Figure 6: node (numbered from 1 as in the paper) -> (x, y).
#: Γ is the line y = 0 (ψ = y): nodes 1-7 lie in Ω⁻, 8-13 in Ω⁺.
FIG6_XY = {1: (0, -1), 2: (2, -1), 3: (4.5, -1), 4: (7, -1), 5: (8, -1), 6: (9, -1),
           7: (11, -0.7), 8: (1, 0.8), 9: (2, 1), 10: (3, 1), 11: (5, 1), 12: (9, 1),
           13: (12, 1)}
#: Its cut edges S_e, in the order Γ meets them: multipliers a, b, ..., k.
FIG6_EDGES = [(1, 8), (2, 8), (2, 9), (2, 10), (3, 10), (3, 11), (4, 12), (5, 12), (6, 12),
              (7, 12), (7, 13)]


def figure6_graph(xy: Mapping | None = None):
    """``(edges, psi, points, nodes)`` of the paper's Figure 6.

    Node k is column k of ``nodes`` (column 0 is unused, as the paper counts
    from 1); ``psi`` = y; ``points`` are where Γ meets the edges.

    >>> edges, psi, points, nodes = figure6_graph()
    >>> edges.shape, bool(np.all(np.diff(points[0]) > 0))
    ((2, 11), True)
    """
    xy = FIG6_XY if xy is None else xy
    nodes = np.zeros((2, 14))
    nodes[:, 0] = (-5.0, 5.0)
    for node, x in xy.items():
        nodes[:, node] = x
    psi = nodes[1].copy()
    edges = np.array(FIG6_EDGES).T
    points = edge_point(nodes[:, edges[0]].T, nodes[:, edges[1]].T,
                        psi[edges[0]], psi[edges[1]]).T
    return edges, psi, points, nodes


def _single(space):
    """True for the cut edges whose λ_e equals one μ (P row with one entry)."""
    P = space.P.tocsr()
    P.eliminate_zeros()
    return np.diff(P.indptr) == 1


def _draw_space(ax, nodes, edges, psi, points, space, groups: str = "ellipse"):
    """Cut edges, nodes and multiplier points of ``space``; returns legend handles.

    Solid edges carry an independent multiplier (vital edges; naive: all;
    winner: edges with one winner end), dotted ones an interpolated one.
    Groups of ≥ 2 vital edges are circled (``groups="ellipse"``) or their
    common node ringed (``"ring"``); winner nodes get a large dot.
    """
    color = COLORS[space.name]
    solid = space.vital if space.vital is not None else _single(space)
    for e in range(edges.shape[1]):
        ax.plot(*nodes[:, edges[:, e]], ls="-" if solid[e] else ":", lw=2.2 if solid[e] else 1.5,
                color=color, zorder=2)
    handles = [Line2D([], [], color=color, lw=2.2, label=f"{space.name}: independent λ_e")]
    if not solid.all():
        handles.append(Line2D([], [], color=color, lw=1.5, ls=":", label="interpolated λ_e"))
    if space.groups is not None:
        for g in range(space.size):
            ends = edges[:, space.groups == g]
            if ends.shape[1] < 2:
                continue
            if groups == "ellipse":
                xy = nodes[:, np.unique(ends)]
                lo, hi = xy.min(axis=1), xy.max(axis=1)
                ax.add_patch(Ellipse((lo + hi) / 2, hi[0] - lo[0] + 1.4, hi[1] - lo[1] + 0.9,
                                     fill=False, ec=color, lw=1.2, ls="--", zorder=1))
            else:
                centre = np.bincount(ends.ravel()).argmax()
                ax.plot(*nodes[:, centre], "o", ms=13, mfc="none", mec=color, mew=1.5)
        handles.append(Line2D([], [], ls="--" if groups == "ellipse" else "", marker=None
                              if groups == "ellipse" else "o", mfc="none", mec=color,
                              color=color, ms=10, label="group of vital edges (one μ)"))
    if space.winners is not None:
        ax.plot(*nodes[:, space.winners], "o", ms=13, color=color, alpha=0.45, zorder=3)
        handles.append(Line2D([], [], ls="", marker="o", ms=10, color=color, alpha=0.45,
                              label="winner node (one μ)"))
    ends = np.unique(edges)
    for s, key in ((-1, "minus_node"), (1, "plus_node")):
        on = ends[np.sign(psi[ends]) == s]
        ax.plot(*nodes[:, on], "o", ms=4.5, color=COLORS[key], zorder=4)
    ax.plot(*points, "o", ms=4.5, mfc="#ffffff", mec=COLORS["gamma"], zorder=5)
    return handles


def _lambda_panel(ax, points, space, letters):
    """λ_h = Pμ along Γ (y = 0) for the μ nearest to a linear pressure; P0 parts shaded."""
    x = points[0]
    target = x / x.max()
    P = space.P.toarray()
    lam = P @ np.linalg.lstsq(P, target, rcond=None)[0]
    flat = np.all(np.isclose(P[1:], P[:-1]), axis=1)        # segment k..k+1 is P0
    for k in np.flatnonzero(flat):
        ax.axvspan(x[k], x[k + 1], color=COLORS[space.name], alpha=0.15, lw=0)
    ax.plot(x, target, ":", color=COLORS["reference"], lw=1.2, label="a linear pressure")
    ax.plot(x, lam, "-o", ms=4, color=COLORS[space.name], label="λ_h = Pμ, best fit")
    for xi, li, t in zip(x, lam, letters):
        ax.annotate(t, (xi, li), textcoords="offset points", xytext=(-4, 6), fontsize=8)
    p1 = 1.0 - np.sum(np.diff(x)[flat]) / (x[-1] - x[0])
    ax.set_xlabel("x along Γ (shaded: P0, λ_h constant)")
    ax.set_ylabel("λ_h")
    ax.set_ylim(-0.15, 1.2)
    ax.legend(fontsize="small", loc="upper left")
    return p1


def fig6() -> Figure:
    """Figure 6: the paper's graph, vital edges and winner nodes, P0 vs P1.

    Top: the cut edges of :func:`figure6_graph`; vital edges (algo2) solid,
    non-vital dotted, groups of connected vital edges circled, winner nodes
    (algo1) as large dots.  Bottom: for each algorithm, the multiplier λ_h =
    Pμ along Γ closest (least squares at the points) to a linear pressure;
    shaded where λ_h is forced constant (P0).  The titles give the number of
    independent multipliers and the share of Γ where λ_h is P1.

    >>> fig = fig6()
    >>> len(fig.axes), fig.axes[1].get_title()
    (3, 'algo1, winner nodes: 5 multipliers, P1 on 77% of Γ')
    """
    from .stabilised import vital_edges, winner_nodes

    edges, psi, points, nodes = figure6_graph()
    letters = "ABCDEFGHIJK"
    spaces = (winner_nodes(edges, psi, points, nodes), vital_edges(edges, psi, points, nodes))
    fig = Figure(figsize=(9, 6.4), layout="constrained")
    grid = fig.add_gridspec(2, 2, height_ratios=(1.25, 1))
    top = fig.add_subplot(grid[0, :])
    top.axhline(0.0, color=COLORS["gamma"], lw=2, zorder=0)
    handles = _draw_space(top, nodes, edges, psi, points, spaces[1])
    winners = spaces[0].winners
    top.plot(*nodes[:, winners], "o", ms=13, color=COLORS["winner"], alpha=0.45, zorder=3)
    handles.append(Line2D([], [], ls="", marker="o", ms=10, color=COLORS["winner"],
                          alpha=0.45, label="winner node of algo1 (one μ)"))
    for k in np.unique(edges):
        top.annotate(str(k), nodes[:, k], textcoords="offset points", fontsize=9,
                     xytext=(6, -12 if psi[k] < 0 else 5))
    for t, pt in zip(letters, points.T):
        top.annotate(t, pt, textcoords="offset points", xytext=(3, 4), fontsize=8,
                     color=COLORS["gamma"])
    top.set_aspect("equal")
    top.set_ylim(-1.7, 1.7)
    top.set_title("cut edges of the paper's Figure 6 (Γ: y = 0, nodes 1-7 in Ω⁻, 8-13 in Ω⁺)",
                  fontsize="medium")
    top.legend(handles=handles, fontsize="small", ncol=2,
               loc="upper center", bbox_to_anchor=(0.5, -0.08), frameon=False)
    top.set_axis_off()
    for k, (space, name) in enumerate(zip(spaces, ("algo1, winner nodes", "algo2, vital edges"))):
        ax = fig.add_subplot(grid[1, k])
        p1 = _lambda_panel(ax, points, space, letters)
        ax.set_title(f"{name}: {space.size} multipliers, P1 on {100 * p1:.0f}% of Γ",
                     fontsize="medium")
    return fig


# -------------------------------------------------------------- Figures 7, 8
def fig7(ns: Sequence[int] = (4, 8, 16, 32), cell: str = "prism") -> Figure:
    """Figure 7: vital edges (algo2), converging as the mesh is refined.

    The benchmark of :func:`~skxfem.scenes.exact_scene`: the plate (3D cells,
    one layer along x, which the solution does not depend on) or the strip
    (``"tri"``, ``"quad"``), where p is the exact contact pressure; darker
    curves are finer meshes.

    >>> fig = fig7(ns=(4, 8))
    >>> len(fig.axes[0].lines)        # two meshes and the exact p(y)
    3
    >>> fig7(ns=(4,), cell="tri").axes[0].get_xlabel()
    'x'
    """
    from .scenes import exact_scene
    from .solver import solve

    axis = _interface_axis(cell)
    fig = Figure(figsize=(6, 4), layout="constrained")
    ax = fig.add_subplot()
    for n, shade in zip(ns, _shades(COLORS["vital"], len(ns))):
        s, p = pressure_along(solve(exact_scene(n, cell, "vital")), axis)
        _curve(ax, s, p, "vital", cell, f"vital, 1/h = {n}", color=shade)
    _reference(ax, 0, 1, f"exact p({axis})")
    _finish(ax, axis, f"vital edges on {_plural(cell)}, exact loads: the oscillations vanish")
    return fig


def _interface_axis(cell: str) -> str:
    """The coordinate along which the benchmarks' pressure varies."""
    return "x" if cell in ("tri", "quad") else "y"


def _plural(cell: str) -> str:
    return {"tri": "triangles", "quad": "quadrilaterals", "tet": "tetrahedra",
            "hex": "hexahedra", "prism": "prisms"}[cell]


def fig8(ns: Sequence[int] = (8, 16), cell: str = "prism", half: bool = True) -> Figure:
    """Figure 8: algo1 (winner nodes) vs algo2 (vital edges), one panel per mesh.

    Same benchmark as :func:`fig7`; only the first half of the interface is
    drawn when ``half`` (the paper's "half-length of the structure").

    >>> fig = fig8(ns=(4,))
    >>> [line.get_label() for line in fig.axes[0].lines]
    ['winner (algo1)', 'vital (algo2)', 'exact p(y)']
    >>> fig8(ns=(4,), cell="tri").axes[0].get_title()
    'triangles, 1/h = 4'
    """
    from .scenes import exact_scene
    from .solver import solve

    axis = _interface_axis(cell)
    fig = Figure(figsize=(4.5 * len(ns), 3.8), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, len(ns)))
    stop = 0.5 if half else 1.0
    for ax, n in zip(axes, ns):
        for space, algo in (("winner", "algo1"), ("vital", "algo2")):
            s, p = pressure_along(solve(exact_scene(n, cell, space)), axis)
            keep = s <= stop + 1e-12
            _curve(ax, s[keep], p[keep], space, cell, f"{space} ({algo})")
        _reference(ax, 0, stop, f"exact p({axis})")
        _finish(ax, axis, f"{_plural(cell)}, 1/h = {n}")
    return fig


# ----------------------------------------------------------- Figures 9, 10
def _slope(x, y) -> str:
    """", slope s" of the last segment of a log-log curve ('' for one point)."""
    if len(x) < 2:
        return ""
    return f", slope {round(float(observed_rates(x, y)[-1]), 2) + 0.0:.2f}"


def _log_axes(ax):
    from matplotlib.ticker import NullFormatter

    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_minor_formatter(NullFormatter())


def _loglog(studies, value, ylabel, title) -> Figure:
    """One log-log panel per dimension: ``value(row)`` vs 1/h for each (cell,
    space); the slope of the last segment is in the legend."""
    dims = sorted({_DIM.get(cell, 3) for cell in studies}, reverse=True)
    fig = Figure(figsize=(4.6 * len(dims), 4.0), layout="constrained")
    for ax, dim in zip(np.atleast_1d(fig.subplots(1, len(dims))), dims):
        ticks = set()
        for cell, rows in studies.items():
            if _DIM.get(cell, 3) != dim:
                continue
            for space in [s for s in SPACES if any(r.space == s for r in rows)]:
                mine = sorted((r for r in rows if r.space == space), key=lambda r: r.h,
                              reverse=True)
                h = np.array([r.h for r in mine])
                y = np.array([value(r) for r in mine])
                slope = _slope(1 / h, y)
                _curve(ax, 1 / h, y, space, cell, f"{space}, {cell}{slope}")
                ticks |= {round(1 / x, 6) for x in h}
        _log_axes(ax)
        ax.set_xticks(sorted(ticks), [f"{t:g}" for t in sorted(ticks)])
        _finish(ax, "1/h", f"{title} ({dim}D)", ylabel)
    return fig


def fig9(studies: Mapping[str, Sequence]) -> Figure:
    """Figure 9: relative energy error W(u_h) vs 1/h, log-log, slopes in the legend.

    Parameters
    ----------
    studies
        ``{cell: rows}``, rows from :func:`skxfem.convergence.study`; 3D cells
        (hex, prism) are drawn left, 2D cells (quad, tri) right.

    >>> from skxfem.convergence import StudyRow
    >>> rows = [StudyRow(n, 1 / n, "vital", 0.5, 0, 1 / n, 1 / n, 1 / n, 0, 0, 0.0)
    ...         for n in (4, 8)]
    >>> fig = fig9({"prism": rows})
    >>> fig.axes[0].lines[0].get_label()
    'vital, prism, slope -1.00'
    """
    return _loglog(studies, lambda r: r.energy, "energy error W(u_h)",
                   "energy error")


def fig10(studies: Mapping[str, Sequence]) -> Figure:
    """Figure 10: relative L²(Γ) error of the contact pressure vs 1/h (as :func:`fig9`).

    >>> from skxfem.convergence import StudyRow
    >>> rows = [StudyRow(n, 1 / n, s, 0.5, 0, 1.0, 1.0, 1.0, 0, 0, 0.0)
    ...         for s in ("naive", "vital") for n in (4, 8)]
    >>> len(fig10({"tri": rows}).axes[0].lines)
    2
    """
    return _loglog(studies, lambda r: r.pressure_l2, "pressure error L(λ_h)",
                   "contact pressure error")


def fig_inf_sup(h_scaled: Mapping[tuple, Sequence], l2_scaled: Mapping[tuple, Sequence],
                bonded: Mapping[tuple, Sequence] | None = None) -> Figure:
    """The inf-sup constant β_h vs h, per space: the bilateral tie with
    M = h·(interface mass) and with the L² mass, and the bonded tie if given.

    Parameters
    ----------
    h_scaled, l2_scaled
        ``{(cell, space): [InfSup, ...]}`` from :func:`skxfem.lbb.inf_sup` with
        ``law="bilateral"`` and ``scaling="h"``, ``"l2"``; h is each result's ``h``.
    bonded
        The same for ``law="bonded"``, ``scaling="h"`` (a third panel).

    >>> from skxfem.lbb import InfSup
    >>> r = [InfSup(b, np.array([b * b]), 0, 1, 1, h) for b, h in ((0.1, 0.2), (0.05, 0.1))]
    >>> fig = fig_inf_sup({("tri", "naive"): r}, {("tri", "naive"): r})
    >>> len(fig.axes), fig.axes[0].lines[0].get_label()
    (2, 'naive, tri, slope 1.00')
    """
    panels = [(h_scaled, "bilateral tie, M = h × interface mass"),
              (l2_scaled, "bilateral tie, M = L² mass")]
    if bonded is not None:
        panels.append((bonded, "bonded tie, M = h × interface mass"))
    fig = Figure(figsize=(4.75 * len(panels), 4.2), layout="constrained")
    for ax, (data, name) in zip(np.atleast_1d(fig.subplots(1, len(panels))), panels):
        for (cell, space), results in data.items():
            h = np.array([r.h for r in results])
            beta = np.array([r.beta for r in results])
            slope = _slope(h, beta)
            _curve(ax, h, beta, space, cell, f"{space}, {cell}{slope}")
        _log_axes(ax)
        _finish(ax, "h (mean length of the cut edges)", f"β_h, {name}", "β_h")
    return fig


def plot_space_2d(mesh, cut, space, ax=None, title: str | None = None) -> Figure:
    """A multiplier space on a 2D mesh: which cut edges carry independent multipliers.

    Solid cut edges carry their own μ (naive: every edge; vital: the vital
    edges; winner: edges with one winner end), dotted ones are interpolated;
    the common node of each group of ≥ 2 vital edges is ringed, winner nodes
    get a large dot.  Nodes of N_e in the colours of their side, the
    multiplier points (white) and Γ_h in the colour of Γ.

    Parameters
    ----------
    mesh
        A 2D scikit-fem mesh.
    cut
        Its :class:`skxfem.cut.Cut`.
    space
        A :class:`skxfem.multipliers.Space` built on ``cut``.
    ax
        Axes to draw into; default a new figure.
    title
        Axes title; default the space's name and size.

    >>> from skxfem.meshes import box
    >>> from skxfem.levelset import plane
    >>> from skxfem.cut import cut
    >>> from skxfem.stabilised import multiplier_space
    >>> m = box(4, "tri")
    >>> c = cut(m, plane((0, 0.52), (0.25, 1)))
    >>> fig = plot_space_2d(m, c, multiplier_space("vital", m, c))
    >>> len(fig.axes)
    1
    """
    from matplotlib.collections import LineCollection

    if ax is None:
        fig = Figure(figsize=(5.5, 4.5), layout="constrained")
        ax = fig.add_subplot()
    fig = ax.figure
    segments = np.transpose(mesh.p[:, mesh.facets], (2, 1, 0))
    ax.add_collection(LineCollection(segments, colors="#bdbdbd", linewidths=0.6))
    gamma = np.transpose(cut.points[:, cut.facets], (2, 1, 0))
    ax.add_collection(LineCollection(gamma, colors=COLORS["gamma"], linewidths=2.0))
    handles = _draw_space(ax, mesh.p, cut.edges, cut.psi, cut.points, space, groups="ring")
    handles.append(Line2D([], [], color=COLORS["gamma"], lw=2, label="Γ_h"))
    band = mesh.p[1, np.unique(cut.edges)]
    pad = 0.6 * np.ptp(band) + 1e-12
    ax.set_xlim(mesh.p[0].min() - 0.02, mesh.p[0].max() + 0.02)
    ax.set_ylim(max(band.min() - pad, mesh.p[1].min() - 0.02),
                min(band.max() + pad, mesh.p[1].max() + 0.02))
    ax.set_aspect("equal")
    ax.set_title(title or f"{space.name}: {space.size} multipliers on "
                 f"{cut.edges.shape[1]} cut edges", fontsize="medium")
    ax.legend(handles=handles, fontsize="small", loc="upper center",
              bbox_to_anchor=(0.5, -0.05), ncol=2, frameon=False)
    ax.set_axis_off()
    return fig
