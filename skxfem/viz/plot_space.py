"""Drawing a multiplier space on its graph of cut edges, and the paper's Figure 6.

* :func:`plot_space_2d` (ours): which cut edges of a 2D mesh carry an
  independent multiplier, for any space of :mod:`skxfem.stabilised`;
* :func:`plot_space_3d` (ours): the same on a 3D mesh (matplotlib's 3D axes);
* :func:`fig6`, Figure 6 of the paper: its graph example (:data:`FIG6_XY`,
  :data:`FIG6_EDGES`, :func:`figure6_graph`), vital edges, groups, winner
  nodes and the P0/P1 multipliers of both algorithms.

Both return a :class:`matplotlib.figure.Figure` built without pyplot, in the
colours of :data:`skxfem.viz.plotting.COLORS`.
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Ellipse, Patch
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

from ..fem.simplex import edge_point
from ..stabilised import vital_edges, winner_nodes
from .plotting import COLORS, legend_size

__all__ = ["FIG6_XY", "FIG6_EDGES", "figure6_graph", "fig6", "plot_space_2d", "plot_space_3d"]

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


def _single(lam_space):
    """True for the cut edges whose λ_e equals one μ (P row with one entry)."""
    P = lam_space.P.tocsr()
    P.eliminate_zeros()
    return np.diff(P.indptr) == 1


def _draw_space(ax, nodes, edges, psi, points, lam_space, groups: str = "ellipse"):
    """Cut edges, nodes and multiplier points of ``lam_space``; returns legend handles.

    Solid edges carry an independent multiplier (vital edges; naive: all;
    winner: edges with one winner end), dotted ones an interpolated one.
    Groups of ≥ 2 vital edges are circled (``groups="ellipse"``) or their
    common node ringed (``"ring"``); winner nodes get a large dot.
    """
    color = COLORS[lam_space.name]
    solid = lam_space.vital if lam_space.vital is not None else _single(lam_space)
    for e in range(edges.shape[1]):
        ax.plot(*nodes[:, edges[:, e]], ls="-" if solid[e] else ":", lw=2.2 if solid[e] else 1.5,
                color=color, zorder=2)
    handles = [Line2D([], [], color=color, lw=2.2, label=f"{lam_space.name}: independent λ_e")]
    if not solid.all():
        handles.append(Line2D([], [], color=color, lw=1.5, ls=":", label="interpolated λ_e"))
    if lam_space.groups is not None:
        for g in range(lam_space.size):
            ends = edges[:, lam_space.groups == g]
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
    if lam_space.winners is not None:
        ax.plot(*nodes[:, lam_space.winners], "o", ms=13, color=color, alpha=0.45, zorder=3)
        handles.append(Line2D([], [], ls="", marker="o", ms=10, color=color, alpha=0.45,
                              label="winner node (one μ)"))
    ends = np.unique(edges)
    for s, key in ((-1, "minus_node"), (1, "plus_node")):
        on = ends[np.sign(psi[ends]) == s]
        ax.plot(*nodes[:, on], "o", ms=4.5, color=COLORS[key], zorder=4)
    ax.plot(*points, "o", ms=4.5, mfc="#ffffff", mec=COLORS["gamma"], zorder=5)
    return handles


def _lambda_panel(ax, points, lam_space, letters):
    """λ_h = Pμ along Γ (y = 0) for the μ nearest to a linear pressure; P0 parts shaded."""
    x = points[0]
    target = x / x.max()
    P = lam_space.P.toarray()
    lam = P @ np.linalg.lstsq(P, target, rcond=None)[0]
    flat = np.all(np.isclose(P[1:], P[:-1]), axis=1)        # segment k..k+1 is P0
    for k in np.flatnonzero(flat):
        ax.axvspan(x[k], x[k + 1], color=COLORS[lam_space.name], alpha=0.15, lw=0)
    ax.plot(x, target, ":", color=COLORS["reference"], lw=1.2, label="a linear pressure")
    ax.plot(x, lam, "-o", ms=4, color=COLORS[lam_space.name], label="λ_h = Pμ, best fit")
    for xi, li, t in zip(x, lam, letters):
        ax.annotate(t, (xi, li), textcoords="offset points", xytext=(-4, 6), fontsize=8)
    p1 = 1.0 - np.sum(np.diff(x)[flat]) / (x[-1] - x[0])
    ax.set_xlabel("x along Γ (shaded: P0, λ_h constant)")
    ax.set_ylabel("λ_h")
    ax.set_ylim(-0.15, 1.2)
    ax.legend(fontsize=legend_size(ax.figure), loc="upper left")
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
    edges, psi, points, nodes = figure6_graph()
    letters = "ABCDEFGHIJK"
    lam_spaces = (winner_nodes(edges, psi, points, nodes), vital_edges(edges, psi, points, nodes))
    fig = Figure(figsize=(9, 6.4), layout="constrained")
    grid = fig.add_gridspec(2, 2, height_ratios=(1.25, 1))
    top = fig.add_subplot(grid[0, :])
    top.axhline(0.0, color=COLORS["gamma"], lw=2, zorder=0)
    handles = _draw_space(top, nodes, edges, psi, points, lam_spaces[1])
    winners = lam_spaces[0].winners
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
    top.legend(handles=handles, fontsize=legend_size(fig), ncol=2,
               loc="upper center", bbox_to_anchor=(0.5, -0.08), frameon=False)
    top.set_axis_off()
    names = ("algo1, winner nodes", "algo2, vital edges")
    for k, (lam_space, name) in enumerate(zip(lam_spaces, names)):
        ax = fig.add_subplot(grid[1, k])
        p1 = _lambda_panel(ax, points, lam_space, letters)
        ax.set_title(f"{name}: {lam_space.size} multipliers, P1 on {100 * p1:.0f}% of Γ",
                     fontsize="medium")
    return fig


def plot_space_2d(mesh, cut, lam_space, ax=None, title: str | None = None) -> Figure:
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
    lam_space
        A :class:`skxfem.multipliers.Space` built on ``cut``.
    ax
        Axes to draw into; default a new figure.
    title
        Axes title; default the space's name and size.

    >>> from skxfem.fem.meshes import box
    >>> from skxfem.levelset import plane
    >>> from skxfem.cut import cut as cut_mesh
    >>> from skxfem.stabilised import multiplier_space
    >>> m = box(4, "tri")
    >>> cut = cut_mesh(m, plane((0, 0.52), (0.25, 1)))
    >>> fig = plot_space_2d(m, cut, multiplier_space("vital", m, cut))
    >>> len(fig.axes)
    1
    """
    if ax is None:
        fig = Figure(figsize=(5.5, 4.5), layout="constrained")
        ax = fig.add_subplot()
    fig = ax.figure
    segments = np.transpose(mesh.p[:, mesh.facets], (2, 1, 0))
    ax.add_collection(LineCollection(segments, colors="#bdbdbd", linewidths=0.6))
    gamma = np.transpose(cut.points[:, cut.facets], (2, 1, 0))
    ax.add_collection(LineCollection(gamma, colors=COLORS["gamma"], linewidths=2.0))
    handles = _draw_space(ax, mesh.p, cut.edges, cut.psi, cut.points, lam_space, groups="ring")
    handles.append(Line2D([], [], color=COLORS["gamma"], lw=2, label="Γ_h"))
    band = mesh.p[1, np.unique(cut.edges)]
    pad = 0.6 * np.ptp(band) + 1e-12
    ax.set_xlim(mesh.p[0].min() - 0.02, mesh.p[0].max() + 0.02)
    ax.set_ylim(max(band.min() - pad, mesh.p[1].min() - 0.02),
                min(band.max() + pad, mesh.p[1].max() + 0.02))
    ax.set_aspect("equal")
    ax.set_title(title or f"{lam_space.name}: {lam_space.size} multipliers on "
                 f"{cut.edges.shape[1]} cut edges", fontsize="medium")
    ax.legend(handles=handles, fontsize=legend_size(ax.figure), loc="upper center",
              bbox_to_anchor=(0.5, -0.05), ncol=2, frameon=False)
    ax.set_axis_off()
    return fig


def plot_space_3d(mesh, cut, lam_space, ax=None, title: str | None = None,
                  below: float | None = None,
                  view: tuple[float, float] = (38.0, -60.0)) -> Figure:
    """A multiplier space on a 3D mesh: the cut edges that carry their own μ.

    Γ_h (the interface triangles) is drawn translucent in the colour of Γ;
    the cut edges that carry an independent multiplier (vital edges; naive:
    all; winner: edges with one winner end) solid in the colour of the space,
    the others (interpolated) thin and grey; the common node of each group of
    ≥ 2 vital edges, and each winner node, as a dot in the space's colour.
    Drawn with matplotlib's 3D axes (no pyvista needed).

    Parameters
    ----------
    mesh, cut, lam_space
        A 3D scikit-fem mesh, its :class:`skxfem.cut.Cut` and a
        :class:`skxfem.multipliers.Space` built on it.
    ax
        A 3D axes to draw into (``projection="3d"``); default a new figure.
    title
        Axes title; default the space's name and size.
    below
        A cutaway: draw only the edges, facets and nodes whose midpoint has
        z ≤ ``below`` (default: everything).
    view
        Elevation and azimuth of the camera, in degrees.

    >>> from skxfem.fem.meshes import box
    >>> from skxfem.levelset import sphere
    >>> from skxfem.cut import cut as cut_mesh
    >>> from skxfem.stabilised import multiplier_space
    >>> m = box(3, "tet")
    >>> cut = cut_mesh(m, sphere((0.5, 0.5, 0.5), 0.4))
    >>> fig = plot_space_3d(m, cut, multiplier_space("vital", m, cut), below=0.5)
    >>> fig.axes[0].name
    '3d'
    """
    if mesh.dim() != 3:
        raise ValueError(f"plot_space_3d needs a 3D mesh, got {mesh.dim()}D; use plot_space_2d")
    if ax is None:
        fig = Figure(figsize=(6.0, 5.6), layout="constrained")
        ax = fig.add_subplot(projection="3d")
    fig = ax.figure
    top = np.inf if below is None else below
    color = COLORS[lam_space.name]
    solid = lam_space.vital if lam_space.vital is not None else _single(lam_space)
    ends = np.transpose(mesh.p[:, cut.edges], (2, 1, 0))             # (ne, 2, 3)
    shown = ends.mean(axis=1)[:, 2] <= top
    triangles = np.transpose(cut.points[:, cut.facets], (2, 1, 0))   # (nf, 3, 3)
    ax.add_collection3d(Poly3DCollection(triangles[triangles.mean(axis=1)[:, 2] <= top],
                                         facecolor=COLORS["gamma"], alpha=0.15,
                                         edgecolor=COLORS["gamma"], linewidths=0.2))
    own = {"naive": "naive: each λ_e its own μ", "winner": "winner: λ_e = μ of a winner node",
           "vital": "vital edge: λ_e = μ of its group"}.get(lam_space.name, lam_space.name)
    handles = [Line2D([], [], color=color, lw=2, label=own)]
    if np.any(shown & ~solid):
        ax.add_collection3d(Line3DCollection(ends[shown & ~solid], colors="#969696",
                                             linewidths=0.6))
        handles.append(Line2D([], [], color="#969696", lw=0.6, label="interpolated λ_e"))
    if np.any(shown & solid):
        ax.add_collection3d(Line3DCollection(ends[shown & solid], colors=color, linewidths=2))
    centres = []
    if lam_space.groups is not None:
        centres = [np.bincount(cut.edges[:, lam_space.groups == g].ravel()).argmax()
                   for g in range(lam_space.size) if np.count_nonzero(lam_space.groups == g) >= 2]
    if lam_space.winners is not None:
        centres = list(lam_space.winners)
    centres = [k for k in centres if mesh.p[2, k] <= top]
    if centres:
        ax.scatter(*mesh.p[:, centres], s=22, color=color, depthshade=False)
        handles.append(Line2D([], [], ls="", marker="o", ms=4.5, color=color,
                              label="winner node" if lam_space.winners is not None
                              else "common node of a group (one μ)"))
    handles.append(Patch(facecolor=COLORS["gamma"], alpha=0.3, label="Γ_h"))
    drawn = ends[shown].reshape(-1, 3)
    lo, hi = drawn.min(axis=0), drawn.max(axis=0)
    for set_lim, a, b in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), lo, hi):
        set_lim(a, b)
    ax.set_box_aspect(hi - lo)
    ax.view_init(*view)
    for set_label, name in zip((ax.set_xlabel, ax.set_ylabel, ax.set_zlabel), "xyz"):
        set_label(name)
    ax.set_title(title or f"{lam_space.name}: {lam_space.size} multipliers on "
                 f"{cut.edges.shape[1]} cut edges", fontsize="medium")
    ax.legend(handles=handles, fontsize=legend_size(ax.figure), loc="upper center",
              bbox_to_anchor=(0.5, 0.02), ncol=2, frameon=False)
    return fig
