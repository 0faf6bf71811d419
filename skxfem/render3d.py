"""3D renders with pyvista, off-screen, as static matplotlib figures.

pyvista (the ``viz`` extra) is imported inside the functions, so that the
rest of skxfem never needs it; ``VTK_DEFAULT_OPENGL_WINDOW`` defaults to
``vtkEGLRenderWindow`` so that no display is needed.
"""
from __future__ import annotations

import os

import numpy as np
from matplotlib.figure import Figure

from .cells import cell_edges
from .plotting import COLORS

__all__ = ["plot_cut_3d"]


def plot_cut_3d(mesh, cut, window_size: tuple[int, int] = (900, 700),
                view: tuple = (1.0, -0.45, 0.55), title: str | None = None) -> Figure:
    """A 3D mesh cut by Γ, rendered off-screen with pyvista into a static figure.

    Shows the interface triangles (the polygons of the cut cells, fanned into
    triangles; their edges are drawn so the fan is visible) in the colour of
    Γ, the edges of the cut cells as a wireframe, the intersection points and
    the outline of the mesh.  pyvista (the ``viz`` extra) is imported here; the
    environment variable ``VTK_DEFAULT_OPENGL_WINDOW`` defaults to
    ``vtkEGLRenderWindow`` so that no display is needed.

    Parameters
    ----------
    mesh
        A 3D scikit-fem mesh.
    cut
        Its :class:`skxfem.cut.Cut`.
    window_size
        Size of the rendered image in pixels, (width, height).
    view
        Direction from the mesh towards the camera; z is up.
    title
        Optional title above the image.

    Returns
    -------
    Figure
        One axes holding the screenshot.

    >>> from skxfem.meshes import box
    >>> from skxfem.levelset import plane
    >>> from skxfem.cut import cut
    >>> m = box(2, "hex")
    >>> fig = plot_cut_3d(m, cut(m, plane((0.5, 0.5, 0.6), (1, 1, 1))), (400, 300))
    >>> len(fig.axes), fig.axes[0].images[0].get_array().shape
    (1, (300, 400, 3))
    """
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    if mesh.dim() != 3:
        raise ValueError(f"plot_cut_3d needs a 3D mesh, got {mesh.dim()}D; use plot_cut_2d")
    faces = np.column_stack([np.full(cut.facets.shape[1], 3), cut.facets.T]).ravel()
    interface = pv.PolyData(cut.points.T, faces)
    _, t2e, edges = cell_edges(mesh)
    cell_edge_ids = np.unique(t2e[:, cut.cells])
    lines = np.column_stack([np.full(cell_edge_ids.size, 2), edges[:, cell_edge_ids].T])
    wireframe = pv.PolyData(mesh.p.T, lines=lines.ravel())

    plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
    plotter.set_background("white")
    plotter.add_mesh(pv.PolyData(mesh.p.T).outline(), color=COLORS["mesh"], line_width=2)
    plotter.add_mesh(wireframe, color=COLORS["mesh"], line_width=1)
    plotter.add_mesh(interface, color=COLORS["gamma"], show_edges=True,
                     edge_color="#ffffff", line_width=1, opacity=0.9)
    plotter.add_mesh(pv.PolyData(cut.points.T), color=COLORS["gamma"], point_size=8,
                     render_points_as_spheres=True)
    plotter.add_axes(color="black")
    plotter.view_vector(view, viewup=(0.0, 0.0, 1.0))
    image = plotter.screenshot(return_img=True)
    plotter.close()

    width, height = window_size
    fig = Figure(figsize=(width / 100, height / 100 + (0.3 if title else 0.0)), dpi=100)
    ax = fig.add_axes((0.0, 0.0, 1.0, height / (height + (30 if title else 0))))
    ax.imshow(image)
    ax.set_axis_off()
    if title:
        fig.suptitle(title)
    return fig
