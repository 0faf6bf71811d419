"""3D renders with pyvista, off-screen, as static matplotlib figures.

pyvista (the ``viz`` extra) is imported inside the functions, so that the
rest of skxfem never needs it; ``VTK_DEFAULT_OPENGL_WINDOW`` defaults to
``vtkEGLRenderWindow`` so that no display is needed.
"""
from __future__ import annotations

import os

import numpy as np
from matplotlib.figure import Figure

from ..fem.cells import cell_edges
from ..fem.vtu import node_regions, region_levelsets, region_pieces, vtk_cells
from .plotting import COLORS

REGION_COLORS = ("#c7e9c0", "#dadaeb", "#fcbba1")
"""The regions between the first and the last of a result with several interfaces
(the first and the last take Ω⁻'s and Ω⁺'s colours)."""

__all__ = ["plot_cut_3d", "plot_result_3d"]


def _pyvista():
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    return pv


def _screenshot(plotter, view) -> np.ndarray:
    plotter.set_background("white")
    plotter.view_vector(view, viewup=(0.0, 0.0, 1.0))
    image = plotter.screenshot(return_img=True)
    plotter.close()
    return image


def _figure(images, window_size, title) -> Figure:
    """The rendered images side by side in one figure, one axes each."""
    width, height = window_size
    top = 30 if title else 0
    fig = Figure(figsize=(len(images) * width / 100, (height + top) / 100), dpi=100)
    for k, image in enumerate(images):
        ax = fig.add_axes((k / len(images), 0.0, 1.0 / len(images), height / (height + top)))
        ax.imshow(image)
        ax.set_axis_off()
    if title:
        fig.suptitle(title)
    return fig


def plot_result_3d(result, scale: float | None = None,
                   window_size: tuple[int, int] = (640, 480),
                   view: tuple = (1.0, -0.6, 0.45), title: str | None = None) -> Figure:
    """A 3D result: each region warped by its own displacement, and the pressure on Γ.

    Left: each region, the part of its own piece of
    :func:`skxfem.fem.vtu.region_pieces` where every ψ has the region's sign
    (the cut cells clipped at each ψ = 0), moved by ``scale`` times its
    displacement: what ParaView's *Warp By Vector* shows of
    ``displacement.vtu``.  The first region and the last take Ω⁻'s and Ω⁺'s
    colours (:data:`~skxfem.viz.plotting.COLORS`; one interface: Ω⁻ and Ω⁺),
    those between :data:`REGION_COLORS`.  Right: the interface facets coloured
    by the contact pressure p = -λ.

    Parameters
    ----------
    result
        A :class:`skxfem.result.Result` of a 3D scene.
    scale
        Displacement magnification; default: the largest displacement drawn
        as 10 % of the mesh size.
    window_size, view, title
        As :func:`plot_cut_3d`.

    Returns
    -------
    Figure
        Two axes holding the screenshots.
    """
    pv = _pyvista()
    mesh = result.mesh
    if mesh.dim() != 3:
        raise ValueError(f"plot_result_3d needs a 3D result, got {mesh.dim()}D; plot "
                         f"result.pressure against result.points instead")
    psi, signs = region_levelsets(result), result.regions
    points, cells, region, _, disp, nodes = region_pieces(mesh, node_regions(signs, psi),
                                                          result.u_regions)
    psis = psi[:, nodes]
    colors = [COLORS["minus"]] + [REGION_COLORS[r % len(REGION_COLORS)]
                                  for r in range(len(signs) - 2)] + [COLORS["plus"]]
    size = float(np.ptp(mesh.p, axis=1).max())
    if scale is None:
        scale = 0.1 * size / max(float(np.abs(disp).max()), 1e-300)
    kind = {"hexahedron": pv.CellType.HEXAHEDRON, "tetra": pv.CellType.TETRA,
            "wedge": pv.CellType.WEDGE}[vtk_cells(mesh)[0]]
    plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
    for r, (sign, color) in enumerate(zip(signs, colors)):
        grid = pv.UnstructuredGrid({kind: cells[region == r]}, points)
        grid.point_data["displacement"] = disp
        for k, psi in enumerate(psis):
            grid.point_data[f"levelset_{k}"] = psi
        part = grid
        for k in range(len(psis)):  # the piece where each ψ has the region's sign
            part = part.clip_scalar(scalars=f"levelset_{k}", invert=bool(sign[k] < 0),
                                    value=0.0)
        plotter.add_mesh(part.warp_by_vector("displacement", factor=scale), color=color,
                         show_edges=True, edge_color=COLORS["mesh"], line_width=0.5)
    plotter.add_text(f"displacement x {scale:.3g}", font_size=10, color="black")
    left = _screenshot(plotter, view)

    plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
    faces = np.column_stack([np.full(result.facets.shape[1], 3), result.facets.T]).ravel()
    gamma = pv.PolyData(result.points.T, faces)
    gamma.point_data["pressure p"] = result.pressure
    plotter.add_mesh(gamma, scalars="pressure p", cmap="viridis", show_edges=True,
                     edge_color="#ffffff", scalar_bar_args={"color": "black"})
    plotter.add_mesh(pv.PolyData(mesh.p.T).outline(), color=COLORS["mesh"], line_width=2)
    return _figure([left, _screenshot(plotter, view)], window_size, title)


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

    >>> from skxfem.fem.meshes import box
    >>> from skxfem.levelset import plane
    >>> from skxfem.cut import cut
    >>> m = box(2, "hex")
    >>> fig = plot_cut_3d(m, cut(m, plane((0.5, 0.5, 0.6), (1, 1, 1))), (400, 300))
    >>> len(fig.axes), fig.axes[0].images[0].get_array().shape
    (1, (300, 400, 3))
    """
    pv = _pyvista()
    if mesh.dim() != 3:
        raise ValueError(f"plot_cut_3d needs a 3D mesh, got {mesh.dim()}D; use plot_cut_2d")
    faces = np.column_stack([np.full(cut.facets.shape[1], 3), cut.facets.T]).ravel()
    interface = pv.PolyData(cut.points.T, faces)
    _, t2e, edges = cell_edges(mesh)
    cell_edge_ids = np.unique(t2e[:, cut.cells])
    lines = np.column_stack([np.full(cell_edge_ids.size, 2), edges[:, cell_edge_ids].T])
    wireframe = pv.PolyData(mesh.p.T, lines=lines.ravel())

    plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
    plotter.add_mesh(pv.PolyData(mesh.p.T).outline(), color=COLORS["mesh"], line_width=2)
    plotter.add_mesh(wireframe, color=COLORS["mesh"], line_width=1)
    plotter.add_mesh(interface, color=COLORS["gamma"], show_edges=True,
                     edge_color="#ffffff", line_width=1, opacity=0.9)
    plotter.add_mesh(pv.PolyData(cut.points.T), color=COLORS["gamma"], point_size=8,
                     render_points_as_spheres=True)
    plotter.add_axes(color="black")
    return _figure([_screenshot(plotter, view)], window_size, title)
