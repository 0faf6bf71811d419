"""Plotting: figures are returned (never shown), with one colour scheme.

The tests check what is drawn (numbers of axes, polygons, segments, lines and
their colours), not pixels.
"""
import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure

from skxfem.cut import cut
from skxfem.fem.meshes import box
from skxfem.levelset import circle, nodal_values, plane
from skxfem.multipliers import SPACES
from skxfem.viz.plotting import (
    COLORS,
    plot_cut_2d,
    plot_levelset_2d,
    plot_pressure,
)


# 1. one colour scheme
def test_colours_cover_sides_interface_and_every_space():
    for key in ("minus", "plus", "gamma") + SPACES:
        assert key in COLORS, f"COLORS must name a colour for {key!r}"
    used = [to_rgba(COLORS[k]) for k in ("minus", "plus", "gamma") + SPACES]
    assert len(set(used)) == len(used), "each side, Γ and each space needs its own colour"


# 2. the 2D cut figure
@pytest.mark.parametrize("cell", ["tri", "quad"])
def test_cut_2d_draws_every_cell_subcell_and_facet(cell):
    m = box(6, cell)
    c = cut(m, circle((0.5, 0.5), 0.3))
    fig = plot_cut_2d(m, c)
    assert isinstance(fig, Figure) and len(fig.axes) == 1
    cells, subcells, edges, gamma = fig.axes[0].collections
    assert len(cells.get_paths()) == np.count_nonzero(c.side), "one polygon per uncut cell"
    assert len(subcells.get_paths()) == c.sub_ref.shape[0], "one polygon per sub-cell"
    assert len(edges.get_segments()) == m.facets.shape[1], "one segment per mesh edge"
    assert len(gamma.get_segments()) == c.facets.shape[1], "one segment per Γ facet"
    assert to_rgba(gamma.get_colors()[0]) == to_rgba(COLORS["gamma"])


def test_cut_2d_subcells_fill_the_cut_cells():
    m = box(5, "quad")
    c = cut(m, circle((0.5, 0.5), 0.3))
    subcells = plot_cut_2d(m, c).axes[0].collections[1]
    area = 0.0
    for path in subcells.get_paths():
        (x0, y0), (x1, y1), (x2, y2) = path.vertices[:3]
        area += abs((x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)) / 2
    assert abs(area - c.cells.size * 0.2 ** 2) < 1e-12, \
        "the sub-cells, mapped to physical coordinates, must tile the cut cells"


def test_draw_into_given_axes():
    m = box(4, "tri")
    fig = Figure()
    ax = fig.add_subplot(121)
    assert plot_cut_2d(m, cut(m, plane((0, 0.3), (0, 1))), ax=ax) is fig
    assert len(fig.axes) == 1


def test_cut_2d_refuses_3d():
    m = box(2, "hex")
    with pytest.raises(ValueError, match="plot_cut_3d"):
        plot_cut_2d(m, cut(m, plane((0, 0, 0.3), (0, 0, 1))))


def test_levelset_figure_has_plot_and_colorbar():
    m = box(6, "quad")
    fig = plot_levelset_2d(m, nodal_values(circle((0.5, 0.5), 0.3), m))
    assert len(fig.axes) == 2
    bar = fig.axes[1]                  # ψ stands upright above the bar, not along it
    assert bar.get_title() == "ψ" and bar.get_ylabel() == ""
    assert bar.title.get_rotation() == 0
    with pytest.raises(ValueError, match="one value per vertex"):
        plot_levelset_2d(m, np.zeros(3))


# 3. pressure curves
def test_plot_pressure_lines_and_colours():
    s = np.linspace(0, 1, 5)
    fig = plot_pressure({"hex": (s, s), "vital": (s, 1 - s)}, reference=(s, s ** 2))
    lines = fig.axes[0].lines
    assert [ln.get_label() for ln in lines] == ["hex", "vital", "reference"]
    assert to_rgba(lines[1].get_color()) == to_rgba(COLORS["vital"])
    assert to_rgba(lines[2].get_color()) == to_rgba(COLORS["reference"])
    with pytest.raises(ValueError, match="at least one"):
        plot_pressure({})
    with pytest.raises(ValueError, match="same length"):
        plot_pressure({"bad": (s, s[:3])})
