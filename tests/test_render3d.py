"""skxfem.viz.render3d: 3D renders with pyvista, off-screen."""
import numpy as np
import pytest
from matplotlib.colors import to_rgba

from skxfem.cut import cut
from skxfem.fem.meshes import box
from skxfem.levelset import plane
from skxfem.viz.plotting import COLORS
from skxfem.viz.render3d import plot_cut_3d


def test_cut_3d_renders_the_interface():
    pytest.importorskip("pyvista")
    m = box(2, "hex")
    fig = plot_cut_3d(m, cut(m, plane((0.5, 0.5, 0.6), (1, 1, 1))), window_size=(320, 240))
    image = fig.axes[0].images[0].get_array()
    assert image.shape == (240, 320, 3)
    gamma = np.array(to_rgba(COLORS["gamma"])[:3]) * 255
    near = np.abs(image.astype(float) - gamma).max(axis=2) < 40
    assert near.mean() > 0.02, "the interface (drawn in COLORS['gamma']) must be visible"


def test_cut_3d_refuses_2d():
    m = box(2, "quad")
    with pytest.raises(ValueError, match="3D mesh"):
        plot_cut_3d(m, cut(m, plane((0.5, 0.4), (0, 1))))


def test_result_3d_renders_both_sides_and_the_pressure():
    pytest.importorskip("pyvista")
    from skxfem.scene.benchmarks import paper_plate, strip
    from skxfem.solver import solve
    from skxfem.viz.render3d import plot_result_3d

    for law in ("bonded", "adhesive"):  # a tie and a contact result alike (issue 17, item 8)
        fig = plot_result_3d(solve(paper_plate(2, "hex", law=law)), window_size=(320, 240))
        assert len(fig.axes) == 2
        left = fig.axes[0].images[0].get_array().astype(float)
        assert left.shape == (240, 320, 3)
        # both sides are drawn in their (shaded) colours: Ω⁻ blue, Ω⁺ orange
        bluish = (left[..., 2] - left[..., 0] > 30).mean()
        orange = (left[..., 0] - left[..., 2] > 30).mean()
        assert bluish > 0.05 and orange > 0.05, (law, bluish, orange)
    with pytest.raises(ValueError, match="3D result"):
        plot_result_3d(solve(strip(2, "quad")))


def test_result_3d_renders_each_region_of_several_interfaces():
    pytest.importorskip("pyvista")
    from skxfem.levelset import plane
    from skxfem.scene import Box, Interface, Scene, SurfaceLoad, clamped
    from skxfem.solver import solve
    from skxfem.viz.render3d import plot_result_3d

    scene = Scene(Box((2, 2, 4), "hex"), displacements=(clamped("zmin"),),
                  loads=(SurfaceLoad("zmax", pressure=1.0),),
                  interfaces=(Interface(plane((0, 0, 0.37), (0, 0, 1))),
                              Interface(plane((0, 0, 0.7), (0.1, 0, 1)))))
    fig = plot_result_3d(solve(scene), window_size=(320, 240))
    left = fig.axes[0].images[0].get_array().astype(float)
    bluish = (left[..., 2] - left[..., 0] > 30).mean()     # the bottom region, Ω⁻'s colour
    orange = (left[..., 0] - left[..., 2] > 30).mean()     # the top one, Ω⁺'s
    greenish = ((left[..., 1] - left[..., 0] > 15) & (left[..., 1] - left[..., 2] > 15)).mean()
    assert min(bluish, orange, greenish) > 0.02, (bluish, orange, greenish)
