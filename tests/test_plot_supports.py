"""The figure of the edges that lose a multiplier component (skxfem/viz/plot_supports.py)."""
import numpy as np
import pytest
from matplotlib.collections import LineCollection

from skxfem.problem import assemble
from skxfem.scene.benchmarks import paper_plate, strip
from skxfem.viz.plot_supports import KINDS, plot_held_edges


def drawn(ax):
    """Number of segments of each kind of KINDS (the collections after the grey mesh)."""
    collections = [c for c in ax.collections if isinstance(c, LineCollection)][1:]
    return [len(c.get_segments()) for c in collections]


def test_roller_faces_lose_the_x_component_only():
    p = assemble(paper_plate(3, "tet", space="vital", nx=2))
    Ps = [s.P for s in p.component_spaces]
    fig = plot_held_edges(p.mesh, p.cut, Ps, held_edges=p.held_edges)
    assert len(fig.axes) == 6
    for face in (0, 1):
        x = p.cut.points[0]
        n_face = int(np.isclose(x, float(face)).sum())
        held, own, interpolated = drawn(fig.axes[3 * face])
        assert held == n_face and own == interpolated == 0, "λ_x: every face edge is held"
        for k in (1, 2):
            held, own, interpolated = drawn(fig.axes[3 * face + k])
            assert held == 0 and own + interpolated == n_face and own > 0
    assert fig.axes[1].get_title() == "λ_y on x = 0"
    assert KINDS[0][0].startswith("no λ of its own")
    default = plot_held_edges(p.mesh, p.cut, Ps)  # by P's rows alone:
    assert drawn(default.axes[0])[0] == 0, "held edges take a neighbour's λ: no empty row"
    with pytest.raises(ValueError, match="held_edges must be"):
        plot_held_edges(p.mesh, p.cut, Ps, held_edges=p.held_edges[:1])


def test_bad_input_is_refused():
    p = assemble(strip(3, "tri", sides="rollers"))
    with pytest.raises(ValueError, match="3D"):
        plot_held_edges(p.mesh, p.cut, [s.P for s in p.component_spaces])
    q = assemble(paper_plate(3, "prism"))
    with pytest.raises(ValueError, match="one row per cut edge"):
        plot_held_edges(q.mesh, q.cut, [q.P])
