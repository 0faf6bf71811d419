"""Figures of the contact chapter: the status map on Γ, in 2D and in 3D.

>>> STATUS_COLORS["open"], STATUS_COLORS["stick"], STATUS_COLORS["slip"]
('#969696', '#1b9e77', '#d95f02')
"""
from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..contact.laws import STATUS_NAMES
from .plotting import COLORS, CURVE_COLORS, legend_size
from .render3d import _figure, _pyvista, _screenshot

__all__ = ["STATUS_COLORS", "edge_status", "plot_status_2d", "plot_status_3d"]

#: One colour per point status (skxfem.contact.laws.STATUS_NAMES).
STATUS_COLORS = {"open": "#969696", "stick": "#1b9e77", "slip": "#d95f02"}


def plot_status_2d(result, step: int = -1, title: str | None = None,
                   interface: int = 0) -> Figure:
    """Status map on a 2D Γ: tractions (top) and jumps (bottom) at the multiplier dofs.

    The abscissa is the position along Γ (the coordinate along its tangent);
    each dof is drawn in the colour of its status (open, stick, slip).

    Parameters
    ----------
    result
        A contact :class:`skxfem.result.Result` of a 2D scene.
    step
        Which load step (default: the last).
    interface
        Which interface to draw (its index in the scene's ``interfaces``; default the
        first).
    """
    ops, last = result.ops, result.steps[step]
    if ops.points.shape[0] != 2:
        raise ValueError("plot_status_2d needs a 2D result")
    if interface not in range(len(ops.pieces)):
        raise ValueError(f"plot_status_2d draws one interface: give interface= one of "
                         f"0 ... {len(ops.pieces) - 1}, got {interface!r}")
    dofs = np.flatnonzero(ops.interface == interface)
    ops = ops.pieces[interface]
    s = ops.tangents[0] @ ops.points
    order = dofs[np.argsort(s)]
    s = np.sort(s)
    colors = [STATUS_COLORS[STATUS_NAMES[k]] for k in last.status[order]]
    fig = Figure(figsize=(7.0, 5.0), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    top.plot(s, last.pressure[order], "-", color=CURVE_COLORS[0], label="pressure p = -λ")
    top.plot(s, last.traction[order, 0], "--", color=CURVE_COLORS[1], label="tangential r_τ")
    bottom.plot(s, last.gap[order], "-", color=COLORS["gamma"], label="normal jump d_n")
    bottom.plot(s, last.slip[order, 0], "--", color=CURVE_COLORS[2],
                label="tangential jump [[u]]·t")
    for ax, values in ((top, (last.pressure, last.traction[:, 0])),
                       (bottom, (last.gap, last.slip[:, 0]))):
        for v in values:
            ax.scatter(s, v[order], c=colors, s=28, zorder=3, edgecolors="k", linewidths=0.4)
        ax.axhline(0.0, color=COLORS["mesh"], lw=0.6)
        ax.grid(alpha=0.3)
    top.set_ylabel("traction")
    bottom.set_ylabel("jump")
    bottom.set_xlabel("position along Γ")
    handles = [Line2D([], [], ls="", marker="o", color=c, mec="k", label=name)
               for name, c in STATUS_COLORS.items()]
    top.legend(handles=top.get_legend_handles_labels()[0] + handles, ncol=2,
               fontsize=legend_size(fig))
    bottom.legend(fontsize=legend_size(fig))
    top.set_title(title or f"status on Γ, step {last.load}")
    return fig


def edge_status(result, step: int = -1) -> np.ndarray:
    """Status (n_edges,) of every cut edge: that of the multiplier dof it depends on most."""
    P = result.problem.P.tocsr()
    status = result.steps[step].status
    rows = np.repeat(np.arange(P.shape[0]), np.diff(P.indptr))
    best = np.zeros(P.shape[0], int)
    weight = np.full(P.shape[0], -np.inf)
    for r, c, v in zip(rows, P.indices, np.abs(P.data)):  # nnz ~ n_edges
        if v > weight[r]:
            weight[r], best[r] = v, c
    return status[best]


def plot_status_3d(result, step: int = -1, window_size: tuple[int, int] = (800, 600),
                   view: tuple = (0.6, -1.0, 0.9), title: str | None = None) -> Figure:
    """Status map on a 3D Γ, rendered off-screen with pyvista (like
    :func:`skxfem.viz.render3d.plot_cut_3d`): the interface triangles, each vertex (a
    cut edge) coloured by :func:`edge_status`, over the outline of the mesh.

    pyvista (the ``viz`` extra) is imported here.
    """
    pv = _pyvista()
    pb = result.problem
    if pb.mesh.dim() != 3:
        raise ValueError("plot_status_3d needs a 3D result; use plot_status_2d")
    c = pb.cut
    faces = np.column_stack([np.full(c.facets.shape[1], 3), c.facets.T]).ravel()
    surface = pv.PolyData(c.points.T, faces)
    palette = np.array([[int(STATUS_COLORS[n][i:i + 2], 16) for i in (1, 3, 5)]
                        for n in STATUS_NAMES], dtype=np.uint8)
    surface.point_data["rgb"] = palette[edge_status(result, step)]
    plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
    plotter.add_mesh(pv.PolyData(pb.mesh.p.T).outline(), color=COLORS["mesh"], line_width=2)
    plotter.add_mesh(surface, scalars="rgb", rgb=True, show_edges=True, edge_color="#ffffff",
                     interpolate_before_map=False)
    plotter.add_mesh(pv.PolyData(c.points.T), scalars=palette[edge_status(result, step)],
                     rgb=True, point_size=10, render_points_as_spheres=True)
    plotter.add_axes(color="black")
    text = title or f"status on Γ, step {result.steps[step].load}"
    fig = _figure([_screenshot(plotter, view)], window_size, text)
    fig.legend(handles=[Line2D([], [], ls="", marker="o", color=col, label=name)
                        for name, col in STATUS_COLORS.items()], loc="upper right", ncol=3,
               fontsize=legend_size(fig))
    fig.suptitle(text, x=0.3)   # left of the legend
    return fig
