"""Tests for skxfem.viz.figures: one function per paper figure, each a returned Figure.

What is drawn is checked (axes, lines, labels, colours and the data of the
curves), not pixels.  Figure 6 is also checked against the paper's numbers.
"""
import io
import re

import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure

from skxfem.cut import cut
from skxfem.fem.meshes import box
from skxfem.lbb import InfSup
from skxfem.levelset import plane, sphere
from skxfem.stabilised import multiplier_space, vital_edges, winner_nodes
from skxfem.studies.convergence import StudyRow
from skxfem.viz.figstyle import cell_colour
from skxfem.viz.figures import (
    FIG6_EDGES,
    fig5,
    fig6,
    fig7,
    fig8,
    fig9,
    fig10,
    fig_inf_sup,
    fig_vital_3d,
    figure6_graph,
    plot_space_2d,
)
from skxfem.viz.plot_space import plot_space_3d
from skxfem.viz.plotting import COLORS


def same_colour(a, b):
    return to_rgba(a) == to_rgba(b)


def curves(ax):
    """The lines of an axes that carry a legend label (the data curves)."""
    return [ln for ln in ax.lines if not ln.get_label().startswith("_")]


# 1. Figure 6: the paper's example, its numbers and its drawing
def test_figure6_graph_is_the_papers():
    edges, psi, points, nodes = figure6_graph()
    assert np.all(psi[1:8] < 0) and np.all(psi[8:] > 0), "nodes 1-7 in Ω⁻, 8-13 in Ω⁺"
    assert np.all(np.diff(points[0]) > 0), "A, B, ..., K must follow each other along Γ"
    assert np.allclose(points[1], 0.0), "the points lie on Γ: y = 0"
    vital = vital_edges(edges, psi, points, nodes)
    winner = winner_nodes(edges, psi, points, nodes)
    assert {FIG6_EDGES[e] for e in np.flatnonzero(~vital.vital)} == {(2, 8), (3, 10), (7, 12)}
    assert set(winner.winners.tolist()) == {8, 2, 3, 12, 7}
    assert vital.size == winner.size == 5, "both algorithms keep 5 multipliers"


def test_fig6_panels_and_p1_share():
    fig = fig6()
    assert isinstance(fig, Figure) and len(fig.axes) == 3
    top, algo1, algo2 = fig.axes
    edges = [ln for ln in top.lines if same_colour(ln.get_color(), COLORS["vital"])]
    solid = [ln for ln in edges if ln.get_linestyle() == "-"]
    dotted = [ln for ln in edges if ln.get_linestyle() == ":"]
    assert len(solid) == 8 and len(dotted) == 3, "8 vital edges solid, 3 non-vital dotted"
    assert len(top.patches) == 2, "two groups of connected vital edges are circled"
    share = [float(re.search(r"P1 on (\d+)%", ax.get_title()).group(1)) for ax in (algo1, algo2)]
    assert "5 multipliers" in algo1.get_title() and "5 multipliers" in algo2.get_title()
    assert share[1] > share[0], "the P1 region is larger for algo2 (the paper's point)"


# 2. pressure curves: Figures 5, 7, 8
def test_fig5_naive_hex_smooth_prism_oscillates():
    fig = fig5(n=8, nx=1)
    assert len(fig.axes) == 2
    for ax, ref in zip(fig.axes, ("paper's reference", "exact")):
        labels = [ln.get_label() for ln in ax.lines]
        assert len(labels) == 3 and ref in labels[2], labels
        assert same_colour(ax.lines[1].get_color(), COLORS["naive"])    # prism/tri
        assert same_colour(ax.lines[0].get_color(), cell_colour("naive", "hex"))
    for ax in fig.axes:
        smooth, wavy = (np.abs(np.diff(ln.get_ydata(), 2)).max() for ln in ax.lines[:2])
        assert wavy > 10 * smooth, "prisms/triangles oscillate, hexahedra/quads do not"


@pytest.mark.parametrize("cell", ["prism", "tri"])
def test_fig7_converges_to_the_exact_pressure(cell):
    fig = fig7(ns=(4, 8, 16), cell=cell)
    lines = fig.axes[0].lines
    assert len(lines) == 4 and "exact" in lines[-1].get_label()
    errors = [np.abs(ln.get_ydata() - 4 * ln.get_xdata() * (1 - ln.get_xdata())).mean()
              for ln in lines[:3]]
    assert errors[2] < errors[1] < errors[0], errors


@pytest.mark.parametrize("cell", ["prism", "tri"])
def test_fig8_whole_length_two_algorithms(cell):
    fig = fig8(ns=(4, 8), cell=cell)
    assert len(fig.axes) == 2
    for ax in fig.axes:
        winner, vital, exact_line = ax.lines
        assert same_colour(winner.get_color(), COLORS["winner"])
        assert same_colour(vital.get_color(), COLORS["vital"])
        for line in ax.lines:
            s = line.get_xdata()
            assert s.min() < 0.1 and s.max() > 0.9, "the whole length, both ends of Γ"
        assert exact_line.get_xdata().max() == pytest.approx(1.0)
        s = vital.get_xdata()
        error = np.abs(vital.get_ydata() - 4 * s * (1 - s))
        assert error.mean() < 0.2, "algo2 follows p"
        assert s[np.argmax(error)] > 0.5, \
            "the half the paper leaves out, where algo2 is worst (toward s = 1), is drawn"


def test_fig8_half_is_the_papers_first_half():
    ax = fig8(ns=(4,), half=True).axes[0]
    assert all(line.get_xdata().max() == pytest.approx(0.5) for line in ax.lines)


# 3. convergence and inf-sup plots from data
def rows(space, errors, ns=(4, 8, 16)):
    return [StudyRow(n, 1 / n, space, 0.5, 0, e, e, e, 0, 0, 0.0) for n, e in zip(ns, errors)]


def test_fig9_fig10_one_panel_per_dimension_with_slopes():
    data = {"prism": rows("vital", [0.4, 0.2, 0.1]) + rows("naive", [2.0, 2.0, 2.0]),
            "tri": rows("winner", [0.16, 0.04, 0.01])}
    for make in (fig9, fig10):
        fig = make(data)
        assert [ax.get_title()[-4:] for ax in fig.axes] == ["(3D)", "(2D)"]
        assert all(ax.get_xscale() == ax.get_yscale() == "log" for ax in fig.axes)
        labels = [ln.get_label() for ln in fig.axes[0].lines]
        assert labels == ["naive, prism, slope 0.00", "vital, prism, slope -1.00"]
        assert fig.axes[1].lines[0].get_label() == "winner, tri, slope -2.00"
        assert np.allclose(fig.axes[1].lines[0].get_xdata(), [4, 8, 16]), "abscissa 1/h"


def test_fig9_draws_the_conforming_fem_curve_in_its_dimension():
    data = {"hex": rows("naive", [0.4, 0.2, 0.1]), "quad": rows("naive", [0.3, 0.15, 0.075])}
    fem = [StudyRow(n, 1 / n, "fem", np.nan, -1, np.nan, np.nan, e, 0, 0, 0.0)
           for n, e in zip((4, 8, 16), (0.5, 0.25, 0.125))]
    fig = fig9(data, fem={"hex": fem})
    three, two = fig.axes
    line = three.lines[-1]
    assert line.get_label() == "FEM, conforming hex, slope -1.00"
    assert same_colour(line.get_color(), COLORS["reference"]), "the FEM curve is black"
    assert np.allclose(line.get_ydata(), [0.5, 0.25, 0.125])
    assert not any("FEM" in ln.get_label() for ln in two.lines), "not in the 2D panel"
    assert len(fig10(data).axes[0].lines) == 1, "fig10 has no FEM curve (no multiplier)"


def test_inf_sup_plot_two_norms():
    res = [InfSup(b, np.array([b * b]), 0, 1, 1, h) for b, h in ((0.6, 0.2), (0.6, 0.1))]
    fig = fig_inf_sup({("tri", "vital"): res}, {("tri", "vital"): res[:1]})
    assert len(fig.axes) == 2
    assert fig.axes[0].lines[0].get_label() == "vital, tri, slope 0.00"
    assert same_colour(fig.axes[1].lines[0].get_color(), COLORS["vital"])
    fig = fig_inf_sup({("tri", "vital"): res}, {("tri", "vital"): res}, {("tri", "naive"): res})
    assert len(fig.axes) == 3 and "bonded" in fig.axes[2].get_title()
    assert same_colour(fig.axes[2].lines[0].get_color(), COLORS["naive"])


# 4. a space on a 2D mesh
@pytest.mark.parametrize("name", ["naive", "winner", "vital"])
def test_plot_space_2d_solid_and_dotted_edges(name):
    m = box(6, "tri")
    c = cut(m, plane((0, 0.52), (0.25, 1)))
    space = multiplier_space(name, m, c)
    ax = plot_space_2d(m, c, space).axes[0]
    edges = [ln for ln in ax.lines if len(ln.get_xdata()) == 2
             and same_colour(ln.get_color(), COLORS[name])
             and ln.get_linestyle() in ("-", ":")]
    solid = sum(ln.get_linestyle() == "-" for ln in edges)
    assert len(edges) == c.edges.shape[1], "one line per cut edge"
    if name == "naive":
        assert solid == len(edges), "every naive multiplier is free"
    if name == "vital":
        assert solid == space.vital.sum(), "vital edges solid, the others dotted"
    if name == "winner":
        dots = [ln for ln in ax.lines if ln.get_marker() == "o" and ln.get_alpha() == 0.45]
        assert len(dots) == 1 and len(dots[0].get_xdata()) == space.size
    assert str(space.size) in ax.get_title()


# 5. a space on a 3D mesh: a sphere through tetrahedra
@pytest.mark.parametrize("name", ["naive", "winner", "vital"])
def test_plot_space_3d_draws_every_cut_edge_once(name):
    m = box(4, "tet")
    c = cut(m, sphere((0.5, 0.5, 0.5), 0.37))
    space = multiplier_space(name, m, c)
    fig = plot_space_3d(m, c, space)
    fig.savefig(io.BytesIO())              # draws: the 3D segments are projected
    ax = fig.axes[0]
    lines = [col for col in ax.collections if type(col).__name__ == "Line3DCollection"]
    counts = {same_colour(col.get_color()[0], COLORS[name]): len(col.get_segments())
              for col in lines}
    assert sum(counts.values()) == c.edges.shape[1], "one segment per cut edge"
    if name == "naive":
        assert counts == {True: c.edges.shape[1]}, "every naive multiplier is free"
    if name == "vital":
        assert counts[True] == space.vital.sum(), "vital edges in the space's colour"
    assert str(space.size) in ax.get_title()
    fig = plot_space_3d(m, c, space, below=0.5)
    fig.savefig(io.BytesIO())
    drawn = sum(len(col.get_segments()) for col in fig.axes[0].collections
                if type(col).__name__ == "Line3DCollection")
    assert 0 < drawn < c.edges.shape[1], "the cutaway draws part of the edges"


def test_plot_space_3d_refuses_2d():
    m = box(3, "tri")
    c = cut(m, plane((0, 0.52), (0.25, 1)))
    with pytest.raises(ValueError, match="plot_space_2d"):
        plot_space_3d(m, c, multiplier_space("vital", m, c))


def test_fig_vital_3d_three_spaces_on_a_sphere():
    fig = fig_vital_3d(n=4)
    assert [ax.name for ax in fig.axes] == ["3d"] * 3
    sizes = [int(re.search(r": (\d+) multipliers", ax.get_title()).group(1))
             for ax in fig.axes]
    edges = int(re.search(r"on (\d+) cut edges", fig.axes[0].get_title()).group(1))
    assert sizes[0] == edges, "naive: one multiplier per cut edge"
    assert sizes[2] < edges // 3, "vital: far fewer multipliers than cut edges"
    assert "sphere" in fig.get_suptitle()


def test_plot_space_2d_into_given_axes():
    m = box(4, "quad")
    c = cut(m, plane((0, 0.55), (0, 1)))
    fig = Figure()
    ax = fig.add_subplot(121)
    assert plot_space_2d(m, c, multiplier_space("vital", m, c), ax=ax) is fig


def test_fig_vital_3d_chosen_spaces_and_refusal():
    fig = fig_vital_3d(n=3, radius=0.4, spaces=("naive", "vital"))
    assert [ax.get_title().split(":")[0] for ax in fig.axes] == ["naive", "vital (algo2)"]
    with pytest.raises(ValueError, match="spaces must be some of"):
        fig_vital_3d(n=3, spaces=("fancy",))


# 4. readable at the size the book shows them
def legend_points_in_the_book(fig):
    """The smallest legend text of ``fig``, in points, at the size the book shows it
    (a figure wider than BOOK_WIDTH is scaled down to the page's column)."""
    from skxfem.viz.plotting import BOOK_WIDTH
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend()] + list(fig.legends)
    assert legends, "the figure has a legend"
    scale = min(1.0, BOOK_WIDTH / fig.get_figwidth())
    return min(t.get_fontsize() * scale for lg in legends for t in lg.get_texts())


def study_data():
    return {"prism": rows("naive", [0.4, 0.2, 0.1]) + rows("vital", [0.4, 0.2, 0.1])
            + rows("winner", [0.5, 0.2, 0.05]), "tri": rows("vital", [0.16, 0.04, 0.01])}


@pytest.mark.parametrize("make", [
    lambda: fig5(n=4, nx=1), fig6, lambda: fig7(ns=(4, 8)), lambda: fig8(ns=(4, 8)),
    lambda: fig9(study_data()), lambda: fig10(study_data()),
    lambda: fig_inf_sup(*[{("tri", "naive"): [InfSup(b, np.array([b * b]), 0, 1, 1, h)
                                              for b, h in ((0.1, 0.2), (0.05, 0.1))]}] * 3),
    lambda: fig_vital_3d(n=3, radius=0.4)],
    ids=["fig5", "fig6", "fig7", "fig8", "fig9", "fig10", "inf_sup", "vital_3d"])
def test_legends_are_10_points_at_book_size(make):
    assert legend_points_in_the_book(make()) >= 10 - 1e-9


def test_every_legend_of_viz_follows_the_book_size_rule():
    """Every legend skxfem.viz draws takes its size from legend_size (the figures of
    other modules are tested in their own files; this keeps them all to the rule)."""
    from pathlib import Path

    import skxfem.viz
    folder = Path(skxfem.viz.__file__).parent
    calls = [(path.name, m.group(0)) for path in sorted(folder.glob("*.py"))
             for m in re.finditer(r"\.legend\((?:[^()]|\([^()]*(?:\([^()]*\))*[^()]*\))*\)",
                                  path.read_text(encoding="utf-8"))]
    assert len(calls) >= 12
    assert all("fontsize=legend_size(" in call for _, call in calls), \
        [c for c in calls if "fontsize=legend_size(" not in c[1]]


def test_fig5_colours_differ_per_cell_type():
    fig = fig5(n=4, nx=1)
    for ax in fig.axes:
        smooth, wavy = ax.lines[:2]                     # hex/quad, prism/tri
        assert not same_colour(smooth.get_color(), wavy.get_color())
        assert same_colour(wavy.get_color(), COLORS["naive"]), "the naive space's colour"


def test_coinciding_curves_are_marked_and_both_visible():
    fig = fig9(study_data())
    naive, winner, vital = fig.axes[0].lines[:3]
    assert "coincides" not in naive.get_label() and "coincides" not in winner.get_label()
    assert vital.get_label() == "vital, prism, slope -1.00 (coincides with naive)"
    assert naive.get_markersize() > vital.get_markersize(), "nested markers"
    assert naive.get_markerfacecolor() == "none", "the one below is open"


def test_fig7_palest_shade_is_visible_on_white():
    def luminance(c):
        lin = [v / 12.92 if v <= 0.03928 else ((v + 0.055) / 1.055) ** 2.4
               for v in to_rgba(c)[:3]]
        return 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2]
    palest = fig7(ns=(4, 8, 16)).axes[0].lines[0].get_color()
    contrast = 1.05 / (luminance(palest) + 0.05)      # WCAG contrast against white
    assert contrast >= 1.8, (palest, contrast)
