r"""Schematics of the paper's Figures 1-4, drawn from the library's own objects.

* :func:`fig1`, Figure 1: the notation of the contact problem: Ω split by Γ into
  Ω¹ = Ω⁻ and Ω² = Ω⁺, the supports Γ_u and loads Γ_t, and one point p of Γ as two
  material points p¹, p² with the normals n¹ = n, n² = -n and the efforts r¹ = -r²;
* :func:`fig2`, Figure 2: the gap d_n = [[x]]·n ≤ 0 and the contact reaction
  r = λn + r_τ (λ ≤ 0, |r_τ| ≤ μ|λ|), in the sign convention of :mod:`skxfem.levelset`;
* :func:`fig3`, Figure 3: a hexahedron and a tetrahedron cut by a plane
  (:func:`skxfem.cut.cut`), the sub-triangles of Γ_h and where the unknowns live: at the
  intersection points of the cut edges in skxfem, at the edges' middle nodes in the
  paper's Code_Aster;
* :func:`fig4`, Figure 4: the plate of :func:`skxfem.scenes.paper_plate` and its two
  meshes, hexahedra and prisms, cut by Γ = {z = 0.5}.

The paper does not give the plate's lateral supports, material or size: what Figure 4
draws as assumed (rollers on x = 0 and x = 1, the unit cube) is the toolkit's choice,
stated in :func:`skxfem.scenes.paper_plate`.  Every function returns a
:class:`matplotlib.figure.Figure` built without pyplot, in the colours of
:data:`skxfem.viz.plotting.COLORS`.

>>> [ax.get_title() for ax in fig3().axes]
['a hexahedron: 6 cut edges, 4 sub-triangles', 'a tetrahedron: 4 cut edges, 2 sub-triangles']
"""
from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection
from skfem import MeshTet1

from ..cut import cut
from ..fem.meshes import box
from ..levelset import plane
from .plotting import COLORS, legend_size

__all__ = ["fig1", "fig2", "fig3", "fig4"]

_ARROW = {"arrowstyle": "-|>", "lw": 1.6, "mutation_scale": 14, "shrinkA": 0, "shrinkB": 0}


def _arrow(ax, start, vector, color, label="", offset=(0.0, 0.0), **text):
    """An arrow from ``start`` along ``vector``, its label near the tip."""
    start, vector = np.asarray(start, float), np.asarray(vector, float)
    ax.annotate("", xy=start + vector, xytext=start, arrowprops={**_ARROW, "color": color})
    if label:
        tip = start + vector + np.asarray(offset)
        ax.text(*tip, label, color=color, ha=text.pop("ha", "center"),
                va=text.pop("va", "center"), **text)


def _interface(x):
    """The curve of Γ in Figures 1 and 2: y = 1 + 0.18 sin(1.4 x)."""
    return 1.0 + 0.18 * np.sin(1.4 * x)


def _slope(x):
    return 0.18 * 1.4 * np.cos(1.4 * x)


def _frame(x0, gap=0.0):
    """Point of Γ at x0 (raised by ``gap``), unit tangent and unit normal n (into Ω²)."""
    t = np.array([1.0, _slope(x0)]) / np.hypot(1.0, _slope(x0))
    return np.array([x0, _interface(x0) + gap]), t, np.array([-t[1], t[0]])


def _blank(ax, title):
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(title, fontsize="medium")


def fig1() -> Figure:
    """The paper's Figure 1: the notation of the frictional contact problem.

    Left, the body: Ω¹ = Ω⁻ = {ψ < 0} below Γ, Ω² = Ω⁺ = {ψ > 0} above it, clamped on
    Γ_u, loaded by t on Γ_t and by f.  Right, one point p of Γ seen as two material
    points: p¹ on the face Γ¹ of Ω¹ and p² on the face Γ² of Ω², with the outward
    normals n¹ = n = ∇ψ/|∇ψ| and n² = -n and the effort densities r¹ = r = -r².
    """
    fig = Figure(figsize=(9.0, 4.0), layout="constrained")
    body, zoom = fig.subplots(1, 2, width_ratios=(1.45, 1.0))
    x = np.linspace(0.0, 3.0, 200)
    y = _interface(x)
    body.fill_between(x, 0.0, y, color=COLORS["minus"])
    body.fill_between(x, y, 2.0, color=COLORS["plus"])
    body.plot(x, y, color=COLORS["gamma"], lw=2.5)
    body.plot([0, 3, 3, 0, 0], [0, 0, 2, 2, 0], color=COLORS["mesh"], lw=1.2)
    for xs in np.linspace(0.05, 2.95, 25):                 # the clamped face, hatched
        body.plot([xs, xs - 0.1], [0.0, -0.1], color=COLORS["mesh"], lw=0.8)
    body.text(1.5, -0.22, "Γ_u: u = 0 (clamped)", ha="center", va="top")
    for xs in np.linspace(0.3, 2.7, 7):
        _arrow(body, (xs, 2.38), (0, -0.34), COLORS["reference"])
    body.text(1.5, 2.45, "traction t on Γ_t", ha="center", va="bottom")
    body.text(0.5, 0.45, "Ω¹ = Ω⁻\n(ψ < 0)", ha="center", va="center")
    body.text(0.55, 1.62, "Ω² = Ω⁺\n(ψ > 0)", ha="center", va="center")
    _arrow(body, (2.75, 1.8), (0, -0.3), COLORS["reference"], "f", (0.12, 0.12))
    _arrow(body, (3.0, 0.5), (0.35, 0), COLORS["mesh"], "n_ext", (0.0, 0.14))
    p, t, n = _frame(1.6)
    _arrow(body, p, 0.45 * n, COLORS["gamma"], "n = ∇ψ/|∇ψ|", (0.0, 0.14))
    body.plot(*p, "o", color=COLORS["gamma"], ms=5)
    body.text(p[0] + 0.05, p[1] - 0.12, "p", color=COLORS["gamma"], va="top")
    body.text(2.45, _interface(2.45) - 0.22, "Γ_c = Γ = {ψ = 0}", color=COLORS["gamma"],
              ha="center", va="top")
    _blank(body, "the body Ω, cut by its interface Γ")
    body.set_xlim(-0.25, 3.6)
    body.set_ylim(-0.45, 2.75)

    gap = 0.16                                             # an exploded view of Γ at p
    xs = np.linspace(1.2, 2.4, 100)
    zoom.fill_between(xs, _interface(xs) - 0.9, _interface(xs), color=COLORS["minus"])
    zoom.fill_between(xs, _interface(xs) + gap, _interface(xs) + gap + 0.9,
                      color=COLORS["plus"])
    zoom.plot(xs, _interface(xs), color=COLORS["gamma"], lw=2.5)
    zoom.plot(xs, _interface(xs) + gap, color=COLORS["gamma"], lw=2.5)
    p1, t, n = _frame(1.8)
    p2 = p1 + [0, gap]
    for point, name, dy in ((p1, "p¹", -0.1), (p2, "p²", 0.1)):
        zoom.plot(*point, "o", color=COLORS["gamma"], ms=5)
        zoom.text(point[0], point[1] + dy, name, ha="center", va="top" if dy < 0 else "bottom")
    for x0, vector, color, name, dy in (                  # normals left of p, efforts right
            (1.35, 0.5 * n, "minus_node", "n¹ = n", 0.1),
            (1.6, -0.5 * n, "plus_node", "n² = -n", -0.1),
            (2.0, -0.45 * n + 0.12 * t, "minus_node", "r¹ = r", -0.1),  # compression on Ω¹
            (2.25, 0.45 * n - 0.12 * t, "plus_node", "r² = -r", 0.1)):
        start = _frame(x0, 0.0 if color == "minus_node" else gap)[0]
        _arrow(zoom, start, vector, COLORS[color], name, (0.0, dy))
    zoom.text(2.38, _interface(2.38) - 0.05, "Γ¹", color=COLORS["gamma"], va="top")
    zoom.text(2.38, _interface(2.38) + gap + 0.05, "Γ²", color=COLORS["gamma"],
              va="bottom")
    zoom.text(1.3, _interface(1.3) - 0.55, "Ω¹", ha="center")
    zoom.text(1.3, _interface(1.3) + gap + 0.55, "Ω²", ha="center")
    _blank(zoom, "p ∈ Γ is two points, p¹ ∈ Γ¹ and p² ∈ Γ²")
    zoom.set_xlim(1.2, 2.55)
    zoom.set_ylim(0.3, 2.0)
    return fig


def fig2(mu: float = 0.5) -> Figure:
    """The paper's Figure 2: the gap and the contact reaction at a point of Γ.

    Left, the normal gap d_n = [[x]]·n = (x(p¹) - x(p²))·n ≤ 0 (eq. 3): negative when
    Γ opens, zero in contact.  Right, the effort on Ω¹, r = λn + r_τ (eq. 4), with
    λ ≤ 0 in contact and the Coulomb cone |r_τ| ≤ μ|λ| (eq. 8) of half-angle
    arctan μ around -n; skxfem reports the pressure p = -λ ≥ 0.
    """
    if not (isinstance(mu, (int, float)) and 0.0 < mu < 5.0):
        raise ValueError(f"mu must be a number in (0, 5) to draw the cone, got {mu!r}")
    fig = Figure(figsize=(9.0, 3.9), layout="constrained")
    left, right = fig.subplots(1, 2)
    for ax in (left, right):
        xs = np.linspace(0.6, 3.0, 100)
        ax.fill_between(xs, _interface(xs) - 1.0, _interface(xs), color=COLORS["minus"])
        ax.plot(xs, _interface(xs), color=COLORS["gamma"], lw=2.5)

    gap = 0.5                                           # Γ² lifted: the interface opens
    xs = np.linspace(0.6, 3.0, 100)
    left.fill_between(xs, _interface(xs) + gap, _interface(xs) + gap + 0.8,
                      color=COLORS["plus"])
    left.plot(xs, _interface(xs) + gap, color=COLORS["gamma"], lw=2.5)
    p1, t, n = _frame(1.5)
    p2 = _frame(2.1, gap)[0]                            # it slid too: p² is off the normal
    jump = p1 - p2
    d_n = jump @ n
    foot = p1 - d_n * n                                 # [[x]] = tangential part + d_n n
    left.plot(*np.c_[p2, foot], ":", color=COLORS["mesh"])
    _arrow(left, foot, d_n * n, COLORS["minus_node"])
    left.text(*(foot + 0.5 * d_n * n - 0.06 * t), "d_n n", color=COLORS["minus_node"],
              ha="right", va="center")
    _arrow(left, p2, jump, COLORS["reference"])
    left.text(*(p2 + 0.55 * jump + 0.1 * t - 0.05 * n), "[[x]] = x(p¹) - x(p²)",
              ha="left", va="top")
    for point, name, dy in ((p1, "x(p¹)", -0.08), (p2, "x(p²)", 0.08)):
        left.plot(*point, "o", color=COLORS["gamma"], ms=5)
        left.text(point[0], point[1] + dy, name, ha="center",
                  va="top" if dy < 0 else "bottom")
    start, _, _ = _frame(0.9)
    _arrow(left, start, 0.45 * n, COLORS["gamma"], "n", (0.08, 0.0))
    left.text(0.62, 2.2, f"d_n = [[x]]·n = {d_n:.2f} < 0: open\n"
                         f"(d_n = 0 in contact, d_n > 0 never)", va="top", ha="left")
    left.text(2.75, _interface(2.75) - 0.5, "Ω¹", ha="center")
    left.text(2.75, _interface(2.75) + gap + 0.4, "Ω²", ha="center")
    _blank(left, "the gap: d_n = [[x]]·n ≤ 0 (eq. 3)")

    p, t, n = _frame(1.8)
    lam, r_t = -0.8, 0.3                                 # λ ≤ 0, |r_τ| ≤ μ|λ|
    cone = np.arctan(mu)
    for sign in (-1, 1):                                 # the Coulomb cone around -n
        edge = -np.cos(cone) * n + sign * np.sin(cone) * t
        right.plot(*np.c_[p, p + 1.05 * edge], "--", color=COLORS["mesh"], lw=1)
    right.text(0.62, 1.85, f"dashed, the Coulomb cone (eq. 8):\n|r_τ| ≤ μ|λ|, here μ = {mu:g}",
               color=COLORS["mesh"], ha="left", va="top")
    _arrow(right, p, lam * n, COLORS["minus_node"], "λn", (-0.12, 0.0), ha="right")
    _arrow(right, p + lam * n, r_t * t, COLORS["plus_node"], "r_τ", (0.05, -0.12))
    _arrow(right, p, lam * n + r_t * t, COLORS["reference"], "r = λn + r_τ", (0.45, 0.12))
    _arrow(right, p, 0.5 * n, COLORS["gamma"], "n", (0.1, 0.08))
    right.plot(*p, "o", color=COLORS["gamma"], ms=5)
    right.text(0.62, 2.2, "λ ≤ 0 in contact (eq. 5);\nskxfem reports p = -λ ≥ 0",
               ha="left", va="top")
    right.text(2.75, _interface(2.75) - 0.3, "Ω¹", ha="center")
    _blank(right, "the reaction on Ω¹: r = λn + r_τ (eq. 4)")
    for ax in (left, right):
        ax.set_xlim(0.6, 3.0)
        ax.set_ylim(0.05, 2.25)
    return fig


# -- 3D: the cut cells of Figure 3 and the plate of Figure 4 --------------------------

def _box_view(ax, title, limits=((0, 1), (0, 1), (0, 1))):
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.set_zlim(*limits[2])
    ax.set_box_aspect([hi - lo for lo, hi in limits])
    for axis in "xyz":                            # close to the box: no tick labels
        getattr(ax, f"set_{axis}label")(axis, labelpad=-12)
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_zticks([])
    ax.set_title(title, fontsize="medium")


def _one_tet() -> MeshTet1:
    return MeshTet1(np.array([[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0],
                              [0.0, 0.0, 0.0, 1.0]]), np.array([[0], [1], [2], [3]]))


#: The two cut cells of Figure 3: a cell and a plane (point, normal) that cuts it
#: into a hexagon (6 cut edges) and into a quadrilateral (4 cut edges, 2 against 2).
FIG3_CELLS = (("hexahedron", lambda: box(1, "hex"), ((0.5, 0.45, 0.55), (1.0, 1.2, 0.9))),
              ("tetrahedron", _one_tet, ((0.3, 0.3, 0.25), (0.15, 1.0, 1.0))))


def fig3() -> Figure:
    """The paper's Figure 3: contact sub-triangles and where their unknowns live.

    A hexahedron cut into a hexagon and a tetrahedron cut into a quadrilateral by
    :func:`skxfem.cut.cut`: the polygon Γ_h ∩ K is split into sub-triangles (a fan, as
    skxfem does), whose vertices are the intersection points of the cut edges.
    skxfem keeps the unknowns λ_i, Λ_i there; the paper's Code_Aster, whose unknowns
    must be nodal, stores them at the middle node of each cut edge (the same unknown,
    one per cut edge).
    """
    fig = Figure(figsize=(8.0, 4.6), layout="constrained")
    for k, (name, make, (point, normal)) in enumerate(FIG3_CELLS):
        mesh = make()
        c = cut(mesh, plane(point, normal))
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        edges = np.transpose(mesh.p[:, mesh.edges], (2, 1, 0))
        ax.add_collection3d(Line3DCollection(edges, colors=COLORS["mesh"], linewidths=1))
        triangles = np.transpose(c.points[:, c.facets], (2, 1, 0))
        ax.add_collection3d(Poly3DCollection(triangles, facecolors=COLORS["gamma"],
                                             edgecolors="white", linewidths=1.5, alpha=0.45))
        minus = c.psi < 0
        for side, key in ((minus, "minus_node"), (~minus, "plus_node")):
            ax.scatter(*mesh.p[:, side], color=COLORS[key], s=40, depthshade=False)
        middle = 0.5 * (mesh.p[:, c.edges[0]] + mesh.p[:, c.edges[1]])
        ax.add_collection3d(Line3DCollection(np.stack([c.points.T, middle.T], axis=1),
                                             colors=COLORS["reference"], linewidths=1,
                                             linestyles=":"))
        ax.scatter(*c.points, color=COLORS["gamma"], s=30, depthshade=False)
        ax.scatter(*middle, facecolors="none", edgecolors=COLORS["reference"], marker="s",
                   s=45, depthshade=False)
        for i, x in enumerate(c.points.T):
            ax.text(*(x + 0.04), f"λ{i + 1}", color=COLORS["gamma"], fontsize="small")
        ax.view_init(elev=24, azim=28)            # looking at Γ_h nearly face on
        _box_view(ax, f"a {name}: {c.edges.shape[1]} cut edges, "
                      f"{c.facets.shape[1]} sub-triangles")
    fig.legend(handles=[
        Patch(color=COLORS["gamma"], alpha=0.45, label="sub-triangles of Γ_h (eq. 12)"),
        Line2D([], [], ls="", marker="o", color=COLORS["gamma"],
               label="λ_i, Λ_i at the intersection points (skxfem)"),
        Line2D([], [], ls="", marker="s", mfc="none", color=COLORS["reference"],
               label="middle nodes of the cut edges (the paper's Code_Aster)"),
        Line2D([], [], ls="", marker="o", color=COLORS["minus_node"], label="node in Ω⁻"),
        Line2D([], [], ls="", marker="o", color=COLORS["plus_node"], label="node in Ω⁺")],
        loc="outside lower center", ncol=3, frameon=False, fontsize=legend_size(fig))
    return fig


def _surface_edges(mesh, faces=(("x", 1), ("y", 0), ("z", 1))) -> np.ndarray:
    """The mesh edges lying on the given faces of its bounding box (those in view)."""
    ends = mesh.p[:, mesh.edges]                                   # (3, 2, nedges)
    on = np.zeros(mesh.edges.shape[1], bool)
    for axis, value in faces:
        d = "xyz".index(axis)
        on |= np.all(np.isclose(ends[d], value), axis=0)
    return np.transpose(ends[:, :, on], (2, 1, 0))


def _gamma_plane(ax, z=0.5):
    square = [[(0, 0, z), (1, 0, z), (1, 1, z), (0, 1, z)]]
    ax.add_collection3d(Poly3DCollection(square, facecolors=COLORS["gamma"], alpha=0.22,
                                         edgecolors=COLORS["gamma"], linewidths=1.5))


def _mesh_panel(ax, cell, n, nz):
    mesh = box((n, n, nz), cell)
    c = cut(mesh, plane((0.0, 0.0, 0.5), (0.0, 0.0, 1.0)))
    ax.add_collection3d(Line3DCollection(_surface_edges(mesh), colors=COLORS["mesh"],
                                         linewidths=0.7))
    _gamma_plane(ax)
    seen = np.isclose(c.points[0], 1.0) | np.isclose(c.points[1], 0.0)
    ax.scatter(*c.points[:, seen], color=COLORS["gamma"], s=14, depthshade=False)
    ax.view_init(elev=18, azim=-52)
    per_layer = "n × n" if cell == "hex" else "n × 2n"
    _box_view(ax, f"{cell}: {mesh.nelements} cells, {c.edges.shape[1]} cut edges\n"
                  f"({per_layer} per layer, n = {n}, {nz} layers in z)")
    return c


def fig4(n: int = 4, nz: int | None = None) -> Figure:
    """The paper's Figure 4: the plate and its two meshes, cut by Γ = {z = 0.5}.

    Left, the geometry of :func:`skxfem.scenes.paper_plate`: clamped bottom, the
    pressure p(y) = 4y(1 - y) on top, Γ at z = 0.5 and, assumed by skxfem (the
    paper gives neither), rollers u_x = 0 on x = 0 and x = 1 and the unit cube.
    Middle and right, the hexahedra and the prisms (triangles in the (y, z) plane
    extruded along x, two per square), with the intersection points on the faces in
    view: the prisms' diagonal edges add the multipliers that oscillate (Figure 5).

    Parameters
    ----------
    n
        Cells in x and y (squares, for prisms), as ``paper_plate(n)``.
    nz
        Cells in z, odd so that Γ cuts a layer of cells; default n if odd, else n + 1.
    """
    if not (isinstance(n, (int, np.integer)) and not isinstance(n, bool) and 1 <= n <= 12):
        raise ValueError(f"n must be an integer from 1 to 12 (cells per side), got {n!r}")
    nz = (n if n % 2 else n + 1) if nz is None else nz
    if not (isinstance(nz, (int, np.integer)) and not isinstance(nz, bool)
            and nz % 2 == 1 and 1 <= nz <= 13):
        raise ValueError(f"nz must be an odd integer from 1 to 13, so that Γ = {{z = 0.5}} "
                         f"cuts a layer of cells; got {nz!r}")
    fig = Figure(figsize=(8.0, 8.4), layout="constrained")
    grid = fig.add_gridspec(2, 2)
    geometry = fig.add_subplot(grid[0, 0], projection="3d")
    key = fig.add_subplot(grid[0, 1])
    key.set_axis_off()
    box_edges = np.transpose(box(1, "hex").p[:, box(1, "hex").edges], (2, 1, 0))
    geometry.add_collection3d(Line3DCollection(box_edges, colors=COLORS["mesh"], lw=1.2))
    _gamma_plane(geometry)
    y = np.linspace(0.1, 0.9, 9)
    for yk in y:                                          # p(y) on the top face, at x = 1/2
        length = 0.35 * 4 * yk * (1 - yk)
        geometry.quiver(0.5, yk, 1.0 + length, 0, 0, -length, color=COLORS["reference"],
                        arrow_length_ratio=0.3, lw=1.2)
    s = np.linspace(0, 1, 50)
    geometry.plot(np.full(50, 0.5), s, 1.0 + 0.35 * 4 * s * (1 - s),
                  color=COLORS["reference"], lw=1)
    geometry.text(0.5, 0.5, 1.45, "p(y) = 4 P_max y(1 - y)", ha="center")
    yy, zz = np.meshgrid(*2 * [np.linspace(0.1, 0.9, 4)])
    for x0 in (0.0, 1.0):                                 # rollers: u_x = 0 (assumed)
        geometry.scatter(np.full(yy.size, x0), yy.ravel(), zz.ravel(), s=25,
                         facecolors="none", edgecolors=COLORS["mesh"], depthshade=False)
    for xs in np.linspace(0.0, 1.0, 6):                   # the clamped bottom
        geometry.plot([xs, xs], [0, 1], [0, 0], color=COLORS["mesh"], lw=0.5)
    key.legend(handles=[
        Patch(color=COLORS["gamma"], alpha=0.3, label="Γ = {z = 0.5}, Ω⁻ below it"),
        Line2D([], [], color=COLORS["reference"], label="p(y) on z = 1, P_max = 1"),
        Line2D([], [], color=COLORS["mesh"], lw=0.5, label="clamped bottom: u = 0 on z = 0"),
        Line2D([], [], ls="", marker="o", mfc="none", color=COLORS["mesh"],
               label="assumed: rollers u_x = 0 on x = 0, 1")],
        loc="center left", frameon=False, title="skxfem.scenes.paper_plate", alignment="left",
        fontsize=legend_size(fig), title_fontsize=legend_size(fig))
    geometry.view_init(elev=18, azim=-52)
    _box_view(geometry, "the plate (P_max = 1; unit cube assumed)",
              limits=((0, 1), (0, 1), (0, 1.45)))
    for k, cell in enumerate(("hex", "prism")):
        _mesh_panel(fig.add_subplot(grid[1, k], projection="3d"), cell, n, nz)
    return fig
