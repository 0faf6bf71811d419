"""Tests for skxfem/viz/validation3d_plots.py: the figures of the 3D validation.

What is drawn is checked (panels, curves, colours, the data and the notes),
not pixels.
"""
import numpy as np
from matplotlib.colors import to_rgba

from skxfem.fem.exact3d import ExactBlock
from skxfem.scene.benchmarks import P_MAX, exact_block
from skxfem.solver import solve
from skxfem.studies.validation3d import study_block
from skxfem.viz.plotting import COLORS
from skxfem.viz.validation3d_plots import fig_block, fig_block_pressure


def same_colour(a, b):
    return np.allclose(to_rgba(a), to_rgba(b))


def test_fig_block_three_panels_one_curve_per_cell_and_space():
    block = study_block([2, 3], cells=("hex", "tet"), spaces=("naive", "vital"))
    fig = fig_block(block)
    assert len(fig.axes) == 3
    energy, pressure, largest = fig.axes
    labels = [ln.get_label() for ln in energy.lines]
    assert labels[0].startswith("naive, hex, slope") and labels[-1].startswith("vital, tet")
    solved = {(c, r.space) for c, rows in block.rows.items() for r in rows}
    assert len(energy.lines) == len(pressure.lines) == len(largest.lines) == len(solved)
    assert all(ax.get_xscale() == ax.get_yscale() == "log" for ax in fig.axes)
    vital_hex = [r for r in block.rows["hex"] if r.space == "vital"]
    line = next(ln for ln in pressure.lines if ln.get_label().startswith("vital, hex"))
    assert same_colour(line.get_color(), COLORS["vital"])
    assert np.allclose(line.get_xdata(), [2, 3])
    assert np.allclose(line.get_ydata(), [r.pressure_l2 for r in vital_hex])
    if block.failures:
        assert "missing" in fig.get_suptitle()


def test_fig_block_names_the_missing_meshes():
    block = study_block([6, 9], cells=("tet",), spaces=("naive",))  # refused, then not run
    title = fig_block(block).get_suptitle()
    assert "naive on tet: refused by the solver at n = 6" in title
    assert "naive on tet: not run at n = 9" in title


def test_fig_block_pressure_vital_on_the_diagonal():
    fig = fig_block_pressure(4, cells=("prism",), spaces=("vital",))
    ax = fig.axes[0]
    points = ax.lines[0]
    assert same_colour(points.get_color(), COLORS["vital"])
    result = solve(exact_block(4, "prism", space="vital"))
    exact = ExactBlock(exact_block(1).material, P_MAX).pressure(result.points)
    assert np.allclose(np.sort(points.get_xdata()), np.sort(exact))
    assert np.abs(points.get_ydata() - points.get_xdata()).mean() < 0.05
    assert "beyond" not in points.get_label()


def test_fig_block_pressure_counts_points_beyond_the_frame_and_refusals():
    fig = fig_block_pressure(6, cells=("prism", "tet"), spaces=("naive",))
    prism, tet = fig.axes
    assert "beyond the frame" in prism.lines[0].get_label()
    assert any("refused by the solver" in t.get_text() for t in tet.texts)
