r"""The paper's figures, one function each (Géniaut, Massin & Moës 2007, §5).

* :func:`fig5`, Figure 5: naive multipliers, hexahedra vs prisms (and
  quadrilaterals vs triangles in 2D);
* :func:`fig6`, Figure 6: the graph example, vital edges, groups, winner nodes
  and the P0/P1 multipliers of both algorithms (drawn by :mod:`skxfem.viz.plot_space`);
* :func:`fig7`, Figure 7: vital edges on prisms as the mesh is refined;
* :func:`fig8`, Figure 8: algo1 vs algo2 along the whole length, two meshes;
* :func:`fig9`, Figure 9: energy error vs 1/h, per space and cell, and of
  classical FEM on a mesh that follows Γ (:mod:`skxfem.studies.conforming`);
* :func:`fig10`, Figure 10: L² error of the contact pressure vs 1/h;
* :func:`fig_inf_sup` (ours): the inf-sup constant β_h vs h, in two norms;
* :func:`fig_vital_3d` (ours): the multiplier spaces on a truly 3D cut, a
  sphere through tetrahedra (drawn by :func:`~skxfem.viz.plot_space.plot_space_3d`);
* :func:`plot_space_2d` (ours, :mod:`skxfem.viz.plot_space`): a multiplier space
  drawn on a 2D mesh.

Every function returns a :class:`matplotlib.figure.Figure` built without
pyplot.  Colours are those of :data:`skxfem.viz.plotting.COLORS`: one per
multiplier space; the cell type sets the line style and marker
(:data:`skxfem.viz.figstyle.CELL_STYLE`: triangles solid, quadrilaterals dashed,
prisms dash-dotted, hexahedra dotted) and, in Figure 5, which compares cell types
in the naive space, the shade (hexahedra and quadrilaterals dark).  In Figures 9
and 10 a curve that coincides with another says so in the legend ("coincides with
naive") and is drawn with nested markers, so that both stay visible.

Figures 5, 7 and 8 solve small scenes themselves; Figures 9, 10 and the
inf-sup plot take the data (:class:`skxfem.studies.convergence.StudyRow` lists,
:class:`skxfem.lbb.InfSup` lists), which :mod:`skxfem.app.reproduce` computes.

Two references are used, and each plot says which: the paper's p(y) =
4y(1 - y) on its clamped plate (:func:`skxfem.scenes.paper_plate`), where it
is only approximate, and the same p(y) under the extra side loads of
:mod:`skxfem.fem.exact` (:func:`skxfem.scenes.exact_plate`), where it is exact.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace

import numpy as np
from matplotlib.figure import Figure

from ..cut import cut as cut_mesh
from ..fem.cells import CELL_TYPES
from ..fem.evaluate import pressure_along
from ..fem.meshes import box
from ..levelset import sphere
from ..multipliers import SPACES
from ..scene.benchmarks import exact_scene, exact_strip, paper_plate
from ..solver import solve
from ..stabilised import multiplier_space
from .figstyle import (
    CELL_DIM,
    cell_colour,
    curve,
    finish,
    log_axes,
    loglog_curves,
    reference,
    shades,
    slope_label,
)
from .plot_space import FIG6_EDGES, FIG6_XY, fig6, figure6_graph, plot_space_2d, plot_space_3d
from .plotting import COLORS, legend_size

__all__ = ["FIG6_XY", "FIG6_EDGES", "figure6_graph", "fig5", "fig6", "fig7", "fig8",
           "fig9", "fig10", "fig_inf_sup", "fig_vital_3d", "plot_space_2d"]

def fig5(n: int = 8, nx: int | None = None) -> Figure:
    """Figure 5: the naive space oscillates on prisms, not on hexahedra.

    Above: the paper's plate (:func:`~skxfem.scenes.paper_plate`: clamped
    bottom, bonded interface) with ``n`` cells in y, pressure on the line
    x = 1/2 of Γ, against the paper's reference p(y), only approximate there.
    Below: the 2D analogue, quadrilaterals vs triangles, under the loads of
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

    fig = Figure(figsize=(6.4, 8.8), layout="constrained")
    left, right = fig.subplots(2, 1)     # the plate above, the strip below
    for cell in ("hex", "prism"):
        scene = paper_plate(n, cell, space="naive")
        if nx is not None:
            scene = replace(scene, mesh=replace(scene.mesh, n=(nx,) + scene.mesh.n[1:]))
        s, p = pressure_along(solve(scene), "y")
        curve(left, s, p, "naive", cell, f"{cell}, naive", color=cell_colour("naive", cell))
    reference(left, 0, 1, "paper's reference p(y) (approximate here)")
    finish(left, "y", f"3D plate, clamped ({n} cells in y): the paper's set-up",
            below=True)
    for cell in ("quad", "tri"):
        s, p = pressure_along(solve(exact_strip(n, cell, space="naive")), "x")
        curve(right, s, p, "naive", cell, f"{cell}, naive", color=cell_colour("naive", cell))
    reference(right, 0, 1, "exact p(x)")
    finish(right, "x", f"2D strip, exact loads ({n} cells in x)", below=True)
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

    axis = _interface_axis(cell)
    fig = Figure(figsize=(6, 4), layout="constrained")
    ax = fig.add_subplot()
    for n, shade in zip(ns, shades(COLORS["vital"], len(ns))):
        s, p = pressure_along(solve(exact_scene(n, cell, "vital")), axis)
        curve(ax, s, p, "vital", cell, f"vital, 1/h = {n}", color=shade)
    reference(ax, 0, 1, f"exact p({axis})")
    finish(ax, axis, f"vital edges on {_plural(cell)}, exact loads: the oscillations vanish")
    return fig


def _interface_axis(cell: str) -> str:
    """The coordinate along which the benchmarks' pressure varies."""
    return "x" if cell in ("tri", "quad") else "y"


def _plural(cell: str) -> str:
    return CELL_TYPES[cell].plural


def fig8(ns: Sequence[int] = (8, 16), cell: str = "prism", half: bool = False) -> Figure:
    """Figure 8: algo1 (winner nodes) vs algo2 (vital edges), one panel per mesh.

    Same benchmark as :func:`fig7`, along the whole length of Γ: the paper
    draws "half-length of the structure" (``half=True``: the first half),
    which leaves out the end y = 1, where Γ meets the side of the plate and
    both algorithms undershoot most.

    >>> fig = fig8(ns=(4,))
    >>> [line.get_label() for line in fig.axes[0].lines]
    ['winner (algo1)', 'vital (algo2)', 'exact p(y)']
    >>> fig8(ns=(4,), cell="tri").axes[0].get_title()
    'triangles, 1/h = 4'
    """

    axis = _interface_axis(cell)
    fig = Figure(figsize=(6.4, 4.2 * len(ns)), layout="constrained")
    axes = np.atleast_1d(fig.subplots(len(ns), 1))
    stop = 0.5 if half else 1.0
    for ax, n in zip(axes, ns):
        for space, algo in (("winner", "algo1"), ("vital", "algo2")):
            s, p = pressure_along(solve(exact_scene(n, cell, space)), axis)
            keep = s <= stop + 1e-12
            curve(ax, s[keep], p[keep], space, cell, f"{space} ({algo})")
        reference(ax, 0, stop, f"exact p({axis})")
        finish(ax, axis, f"{_plural(cell)}, 1/h = {n}")
    return fig


# ----------------------------------------------------------- Figures 9, 10
def _loglog(studies, value, ylabel, title, extra=None) -> Figure:
    """One log-log panel per dimension, 3D above 2D: ``value(row)`` vs 1/h for each
    (cell, space); the slope of the last segment is in the legend, below the panel.  ``extra``
    ``{cell: rows}`` of space ``"fem"``: one black curve each, in its
    dimension's panel."""
    dims = sorted({CELL_DIM.get(cell, 3) for cell in studies}, reverse=True)
    fig = Figure(figsize=(6.4, 4.6 * len(dims)), layout="constrained")
    for ax, dim in zip(np.atleast_1d(fig.subplots(len(dims), 1)), dims):
        drawn = []   # (x, y, space, cell, name, colour) of each curve of the panel
        for cell, rows in studies.items():
            if CELL_DIM.get(cell, 3) != dim:
                continue
            for space in [s for s in SPACES if any(r.space == s for r in rows)]:
                mine = sorted((r for r in rows if r.space == space), key=lambda r: r.h,
                              reverse=True)
                x = 1 / np.array([r.h for r in mine])
                drawn.append((x, np.array([value(r) for r in mine]), space, cell,
                              f"{space}, {cell}", None))
        for cell, rows in (extra or {}).items():
            if CELL_DIM.get(cell, 3) != dim:
                continue
            mine = sorted(rows, key=lambda r: r.h, reverse=True)
            x = 1 / np.array([r.h for r in mine])
            drawn.append((x, np.array([value(r) for r in mine]), "fem", cell,
                          f"FEM, conforming {cell}", COLORS["reference"]))
        ticks = loglog_curves(ax, drawn)
        log_axes(ax)
        ax.set_xticks(ticks, [f"{t:g}" for t in ticks])
        finish(ax, "1/h", f"{title} ({dim}D)", ylabel, below=True)
    return fig


def fig9(studies: Mapping[str, Sequence], fem: Mapping[str, Sequence] | None = None
         ) -> Figure:
    """Figure 9: relative energy error W(u_h) vs 1/h, log-log, slopes in the legend.

    Parameters
    ----------
    studies
        ``{cell: rows}``, rows from :func:`skxfem.studies.convergence.study`; 3D cells
        (hex, prism) are drawn above, 2D cells (quad, tri) below.
    fem
        ``{cell: rows}`` of classical FEM on a mesh that follows Γ
        (:func:`skxfem.studies.conforming.study_conforming`), drawn in black: the
        paper's FEM curve.

    >>> from skxfem.studies.convergence import StudyRow
    >>> rows = [StudyRow(n, 1 / n, "vital", 0.5, 0, 1 / n, 1 / n, 1 / n, 0, 0, 0.0)
    ...         for n in (4, 8)]
    >>> fig = fig9({"prism": rows})
    >>> fig.axes[0].lines[0].get_label()
    'vital, prism, slope -1.00'
    >>> fem = [StudyRow(n, 1 / n, "fem", 0.0, -1, 0.0, 0.0, 2 / n, 0, 0, 0.0) for n in (4, 8)]
    >>> fig9({"prism": rows}, fem={"hex": fem}).axes[0].lines[1].get_label()
    'FEM, conforming hex, slope -1.00'
    """
    return _loglog(studies, lambda r: r.energy, "energy error W(u_h)",
                   "energy error", fem)


def fig10(studies: Mapping[str, Sequence]) -> Figure:
    """Figure 10: relative L²(Γ) error of the contact pressure vs 1/h (as :func:`fig9`).

    >>> from skxfem.studies.convergence import StudyRow
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
    fig = Figure(figsize=(6.4, 4.6 * len(panels)), layout="constrained")
    for ax, (data, name) in zip(np.atleast_1d(fig.subplots(len(panels), 1)), panels):
        for (cell, space), results in data.items():
            h = np.array([r.h for r in results])
            beta = np.array([r.beta for r in results])
            slope = slope_label(h, beta)
            curve(ax, h, beta, space, cell, f"{space}, {cell}{slope}")
        log_axes(ax)
        finish(ax, "h (mean length of the cut edges)", f"β_h, {name}", "β_h", below=True)
    return fig


def fig_vital_3d(n: int = 6, radius: float = 0.37,
                 spaces: Sequence[str] = ("naive", "winner", "vital")) -> Figure:
    """The multiplier spaces on a truly 3D cut: a sphere through tetrahedra.

    The unit cube in n³ × 6 tetrahedra, Γ the sphere of ``radius`` about its
    centre (Ω⁻ inside); one panel per space of ``spaces`` (naive, winner
    nodes = algo1, vital edges = algo2), each the lower half of Γ (a cutaway
    at z = ½) with its cut edges (:func:`~skxfem.viz.plot_space.plot_space_3d`).

    >>> fig = fig_vital_3d(n=3, radius=0.4)
    >>> [ax.get_title().split(":")[0] for ax in fig.axes]
    ['naive', 'winner (algo1)', 'vital (algo2)']
    """
    names = {"naive": "naive", "winner": "winner (algo1)", "vital": "vital (algo2)"}
    unknown = [s for s in spaces if s not in names]
    if unknown or not spaces:
        raise ValueError(f"spaces must be some of {tuple(names)}, got {spaces!r}")
    mesh = box(n, "tet")
    cut = cut_mesh(mesh, sphere((0.5, 0.5, 0.5), radius))
    fig = Figure(figsize=(3.5 * len(spaces), 4.6), layout="constrained")
    legend = {}                  # one legend for all panels, below them
    for k, space in enumerate(spaces):
        lam_space = multiplier_space(space, mesh, cut)
        ax = fig.add_subplot(1, len(spaces), k + 1, projection="3d")
        plot_space_3d(mesh, cut, lam_space, ax=ax, below=0.5,
                      title=f"{names[space]}: {lam_space.size} multipliers\n"
                            f"on {cut.edges.shape[1]} cut edges")
        panel = ax.get_legend()
        legend.update(zip((t.get_text() for t in panel.get_texts()), panel.legend_handles))
        panel.remove()
    fig.legend(list(legend.values()), list(legend), loc="outside lower center", ncol=2,
               frameon=False, fontsize=legend_size(fig))
    fig.suptitle(f"a sphere (r = {radius:g}) through {mesh.nelements} tetrahedra "
                 f"({n}³ cubes): its lower half and cut edges", fontsize="medium")
    return fig
