"""Figures of the contact chapter (skxfem.viz.contact_plots)."""
from dataclasses import replace

import numpy as np
import pytest

from skxfem import contact
from skxfem.fem.material import Material
from skxfem.levelset import plane
from skxfem.scene import Box, Displacement, Scene, clamped
from skxfem.scene.benchmarks import strip
from skxfem.viz.contact_plots import edge_status, plot_status_2d, plot_status_3d


def turned(dim):
    if dim == 2:
        top = Displacement("ymax", {"x": 0.0, "y": lambda x: -0.01 * (1 - 2 * x[0])})
        return replace(strip(n=4), law="frictionless", loads=(),
                       displacements=(clamped("ymin"), top))
    return Scene(Box((1, 4, 3), "hex"), plane((0, 0, 0.5), (0, 0, 1)), Material(),
                 displacements=(clamped("zmin"), Displacement("zmax", {
                     "x": 0.0, "y": 0.0, "z": lambda x: -0.01 * (1 - 2 * x[1])})),
                 law="frictionless")


def test_status_2d_draws_every_dof_in_its_status_colour():
    res = contact.solve(turned(2))
    fig = plot_status_2d(res)
    top, bottom = fig.axes[:2]
    drawn = np.concatenate([c.get_offsets()[:, 0] for c in top.collections
                            if hasattr(c, "get_offsets") and len(c.get_offsets())])
    assert drawn.size == 2 * res.ops.w.size  # pressure and traction markers
    with pytest.raises(ValueError, match="2D"):
        plot_status_2d(contact.solve(turned(3)))


def test_edge_status_and_3d_render():
    res = contact.solve(turned(3))
    st = edge_status(res)
    assert np.array_equal(st, res.steps[-1].status)  # naive space: one dof per edge
    fig = plot_status_3d(res, window_size=(320, 240))
    assert fig.axes[0].images[0].get_array().shape == (240, 320, 3)


def test_status_2d_of_one_interface_among_several():
    """A column lifted at the top: the frictionless interface opens by 0.01."""
    from skxfem.scene import Interface, rollers
    from skxfem.solver import solve

    r = solve(Scene(Box((2, 4), "quad"), material=Material(1.0, 0.0),
                    displacements=(clamped("ymin"), rollers("xmin"),
                                   Displacement("ymax", {"y": 0.01})),
                    interfaces=(Interface(plane((0, 0.37), (0, 1)), "frictionless"),
                                Interface(plane((0, 0.7), (0, 1)), "bonded"))))
    fig = plot_status_2d(r, interface=0)
    gap = fig.axes[1].lines[0].get_ydata()
    assert np.allclose(gap, -0.01) and len(gap) == int((r.ops.interface == 0).sum())
    first = plot_status_2d(r)                  # the first interface unless asked
    assert np.array_equal(first.axes[1].lines[0].get_ydata(), gap)
    with pytest.raises(ValueError, match="draws one interface: give interface= one of 0 ... 1"):
        plot_status_2d(r, interface=2)
