r"""The geometry of a 2D crack on a mesh: split cells, tip cells, tips and sub-cells.

A crack is given by two level sets (:mod:`skxfem.crack.frame`): the crack is
{ψ = 0, φ < 0}, its front (in 2D: the tip) {ψ = φ = 0}.  On a mesh both are
interpolated at the nodes and, in each cell, read on the cell's reference
triangles (a triangle is one; a quadrilateral is split into two along its
diagonal 0-2, :func:`skxfem.fem.cells.reference_simplices`), where they are
linear.  Level sets linear in x are then exact on triangles and on
parallelogram quadrilaterals (the straight cracks of the tests).

In each reference triangle
--------------------------
* the zero set of ψ_h is a segment [P₀, P₁] (or nothing): its ends are the
  points of the edges where ψ_h changes sign and the vertices where ψ_h = 0 (a
  crack through a node is treated exactly: nodal values within :data:`ZERO` edge
  lengths of zero are set to zero, never moved off it);
* φ_h is linear along it, with values f₀, f₁ at the ends: the crack piece is
  the part where φ_h < 0, and if f₀ < 0 < f₁ the tip is
  T = P₀ + f₀/(f₀ - f₁) (P₁ - P₀) (likewise with an end at φ_h = 0 and the other
  end behind it: a tip on an edge or at a node).

In the mesh
-----------
* **tip cells**: the cells whose closure holds a tip (one cell for a tip inside
  a cell, two on an edge, every cell around a node);
* **split cells**: the other cells whose closure holds a crack piece of positive
  length: the crack crosses them completely, or runs along one of their edges;
* **one owner per piece**: a crack along a mesh edge (or a quadrilateral's
  diagonal) is the zero set of ψ_h in both triangles beside it; it is listed once,
  in the triangle on the Ω⁻ side (ψ_h < 0 at its third vertex; on the mesh boundary,
  the only one), so that ``segments``, ``facets``, the face rule and all that is
  integrated on the crack faces count it once; the cells on both sides are split cells;
* **sub-cells**: each split cell's reference triangles are split by ψ_h into
  sub-triangles of one side each (:func:`skxfem.fem.simplex.split`); in a tip
  cell, each reference triangle holding the tip is fanned from the tip T to its
  vertices and to the points where ψ_h = 0 on its edges, so that the crack
  segment [T, P] is an edge of two sub-triangles; these *fan* sub-triangles
  carry the tip as their vertex 0 (for the almost-polar rule of
  :mod:`skxfem.crack.quadrature`).  Sub-cells are in the parent's reference
  coordinates, with their side ±1 (the sign of ψ_h inside).

>>> from skfem import MeshTri1
>>> m = MeshTri1.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 1, 4))
>>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5)
>>> g.tips.ravel().tolist(), g.tip_cells.size, g.split_cells.size   # tip on a diagonal
([0.5, 0.5], 2, 2)
>>> bool(np.isclose(g.segments_length().sum(), 0.5))
True
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import Basis, MeshQuad1, MeshTri1

from ..cut import with_vertices
from ..fem.cells import reference_simplices
from ..fem.simplex import split
from ..levelset import nodal_values

__all__ = ["CrackGeometry", "crack_geometry", "check_mesh_2d", "check_mesh_type",
           "check_geometry", "orthonormal_at_tips", "level_set_scales",
           "level_set_values", "nearest_on_segments", "crack_points", "point_cells", "ZERO",
           "AREA_TOL"]

ZERO = 1e-9
"""Nodal level-set values closer to zero than ZERO times the node's shortest edge (as a
distance: |ψ_i| over the steepest slope of ψ along its edges) are set to exactly zero:
a crack through a node is treated exactly."""

AREA_TOL = 1e-13
"""Sub-triangles below AREA_TOL times the reference area are dropped (zero-area pieces
of a crack through a vertex or along an edge)."""


def check_mesh_2d(mesh, name: str = "mesh"):
    """``mesh`` if it is a 2D MeshTri1 or MeshQuad1, else a ValueError naming ``name``.

    >>> check_mesh_2d(MeshTri1()).nelements
    2
    """
    return check_mesh_type(mesh, (MeshTri1, MeshQuad1), name,
                           "a 2D MeshTri1 or MeshQuad1 (the crack modules are 2D, linear "
                           "elements)")


def check_mesh_type(mesh, types: tuple, name: str, what: str):
    """``mesh`` if it is one of ``types``, else a ValueError: ``name`` must be ``what``
    (the mesh check of :func:`check_mesh_2d` and
    :func:`skxfem.crack.geometry3d.check_mesh_3d`)."""
    if not isinstance(mesh, types):
        dim = getattr(mesh, "dim", lambda: "?")()
        raise ValueError(f"{name} must be {what}, got a {dim}D {type(mesh).__name__}")
    return mesh


def check_geometry(geometry, mesh, kind: type, maker: str):
    """``geometry`` if it is a ``kind`` (made by ``maker``) of ``mesh``, else a ValueError
    (the check of :func:`skxfem.crack.space.crack_space` and
    :func:`skxfem.crack.space3d.crack_space_3d`).

    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5)
    >>> check_geometry(g, m, CrackGeometry, "crack_geometry") is g
    True
    >>> check_geometry(g, MeshTri1(), CrackGeometry, "crack_geometry")
    Traceback (most recent call last):
    ValueError: geometry belongs to another mesh (its psi has 36 values, the mesh 4 nodes)
    """
    if not isinstance(geometry, kind):
        raise ValueError(f"geometry must be a {kind.__name__} ({maker}), got "
                         f"{type(geometry).__name__}")
    if geometry.psi.shape != (mesh.p.shape[1],):
        raise ValueError("geometry belongs to another mesh (its psi has "
                         f"{geometry.psi.size} values, the mesh {mesh.p.shape[1]} nodes)")
    return geometry


def _where_not_finite(name: str, value, mesh) -> None:
    """Raise a ValueError naming ``name`` (ψ or φ) and a vertex where the callable
    ``value`` is NaN or inf, if it is anywhere on ``mesh`` (else return)."""
    with np.errstate(all="ignore"):
        try:
            v = np.asarray(value(mesh.p), dtype=float)
        except (TypeError, ValueError):
            return
    if v.shape != mesh.p.shape[1:]:
        return
    bad = ~np.isfinite(v)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        x = ", ".join(f"{c:.4g}" for c in mesh.p[:, k])
        role = "the front's level set" if name == "phi" else "the crack's level set"
        raise ValueError(f"{name} ({role}) is NaN or inf at {int(bad.sum())} of {bad.size} "
                         f"mesh vertices, e.g. {v[k]} at ({x}): it must be finite on the "
                         f"whole mesh (a square root or a log of a negative number, a "
                         f"division by zero?)")


def level_set_values(name: str, value, mesh, edges: np.ndarray | None = None) -> np.ndarray:
    """Nodal values of a level set ``value`` (a callable or one value per node), checked:
    a ValueError naming ``name`` for NaN, inf or a wrong shape.  Values within
    :data:`ZERO` edge lengths of zero are set to zero (module notes), along ``edges``
    (2, n), the mesh's edges (default ``mesh.facets``, the edges of a 2D mesh; a 3D
    crack gives ``mesh.edges``).

    >>> level_set_values("psi", lambda x: x[1] - 0.5, MeshTri1()).tolist()
    [-0.5, -0.5, 0.5, 0.5]
    """
    if callable(value):
        try:
            v = nodal_values(value, mesh)
        except ValueError as err:
            _where_not_finite(name, value, mesh)
            raise ValueError(f"{name}: {err}") from None
    else:
        v = np.asarray(value)
        if v.dtype.kind not in "iuf" or v.shape != (mesh.p.shape[1],):
            raise ValueError(f"{name} must be a callable or one real value per mesh node, "
                             f"shape ({mesh.p.shape[1]},); got {v.dtype} of shape {v.shape}")
        v = v.astype(float)
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{name} holds {int((~np.isfinite(v)).sum())} NaN or infinite "
                         f"nodal value(s); it must be finite at every node")
    a, b = mesh.facets if edges is None else edges
    length = np.linalg.norm(mesh.p[:, a] - mesh.p[:, b], axis=0)
    slope = np.abs(v[a] - v[b]) / length
    g, h = np.zeros(v.size), np.full(v.size, np.inf)
    for end in (a, b):
        np.maximum.at(g, end, slope)
        np.minimum.at(h, end, length)
    return np.where(np.abs(v) <= ZERO * h * g, 0.0, v)


@dataclass(frozen=True)
class CrackGeometry:
    """A 2D crack {ψ = 0, φ < 0} on a mesh (module notes).

    Attributes
    ----------
    psi, phi : (nverts,) the nodal level sets as used (near-zero values set to 0).
    tips : (2, ntips) the tip points.
    tip_cells : (nt,) the cells whose closure holds a tip; ``tip_of_cell`` (nt,) which
        tip; ``tip_ref`` (2, nt) the tip in that cell's reference coordinates.
    split_cells : (ns,) the cells the crack crosses completely or runs along an edge of.
    side : (ncells,) -1 / +1 for cells on one side (the sign of the mean nodal ψ; a
        cell ψ = 0 crosses ahead of a tip has no crack and takes it too), 0 for split
        and tip cells.
    segments : (2, 2, nseg) the crack pieces [end, coordinate, piece], physical, each
        once (a piece on a mesh edge in the cell on its Ω⁻ side); ``segment_cell``
        (nseg,) their cells.
    sub_ref : (nsub, 3, 2) sub-triangles of the split and tip cells in reference
        coordinates; ``sub_cell`` (nsub,), ``sub_side`` (nsub,) ±1; ``sub_fan``
        (nsub,) True for a tip cell's fan triangle, whose vertex 0 is the tip.

    The fields of a :class:`skxfem.cut.Cut`, in its names, for the crack kind of Γ of
    :mod:`skxfem.gamma` (``psi``, ``cells``, ``side``, ``sub_*`` above too):

    edge_ids : (ne,) where the multipliers live: the mesh edges (``mesh.facets``) the
        crack crosses strictly (an edge ψ_h crosses ahead of the tip is not one), then
        -1 for each node on the crack behind the tip (ψ = 0, φ < 0) that ends a crack
        piece, as :class:`skxfem.cut.Cut` lists a vertex on Γ.  ``edges`` (2, ne) their
        nodes ((v, v) for a node), ``points`` (2, ne) the crossings and the nodes.
    enriched : the nodes of the split and tip cells (the space chooses Heaviside or
        branch for each, :mod:`skxfem.crack.space`).
    facets : (2, nseg) each crack piece's ends as indices into ``points``; -1 for an end
        that is none: the tip (the facets stop at the front) or a point of a
        quadrilateral's diagonal.  ``facet_ref``
        (2, 2, nseg) [end, coordinate, piece] in the cell's reference coordinates,
        ``facet_cell``, ``normals`` (2, nseg) unit, into Ω⁺, ``measures`` (nseg,).
    """

    psi: np.ndarray
    phi: np.ndarray
    tips: np.ndarray
    tip_cells: np.ndarray
    tip_of_cell: np.ndarray
    tip_ref: np.ndarray
    split_cells: np.ndarray
    side: np.ndarray
    segments: np.ndarray
    segment_cell: np.ndarray
    sub_ref: np.ndarray
    sub_cell: np.ndarray
    sub_side: np.ndarray
    sub_fan: np.ndarray
    edge_ids: np.ndarray
    edges: np.ndarray
    points: np.ndarray
    enriched: np.ndarray
    facets: np.ndarray
    facet_ref: np.ndarray
    normals: np.ndarray

    @property
    def facet_cell(self) -> np.ndarray:
        """(nseg,) the cell of each crack piece (:class:`skxfem.cut.Cut`'s name)."""
        return self.segment_cell

    @property
    def measures(self) -> np.ndarray:
        """(nseg,) the lengths of the crack pieces (:class:`skxfem.cut.Cut`'s name)."""
        return self.segments_length()

    @property
    def cells(self) -> np.ndarray:
        """Split and tip cells, sorted: the cells integrated on sub-cells."""
        return np.union1d(self.split_cells, self.tip_cells)

    @property
    def pieces(self) -> np.ndarray:
        """(nseg, 2, 2) the crack pieces [piece, end, coordinate], physical, in the order of
        ``facets`` (whose -1 ends they locate: the tip, a point of a diagonal)."""
        return np.transpose(self.segments, (2, 0, 1))

    def segments_length(self) -> np.ndarray:
        """(nseg,) the lengths of the crack pieces."""
        return np.linalg.norm(self.segments[1] - self.segments[0], axis=0)


def nearest_on_segments(a: np.ndarray, d: np.ndarray, x: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The nearest points of segments to points, all broadcast together: for the
    segments from ``a`` along ``d`` (dim, ...) and the points ``x`` (dim, ...), the
    parameter t = (x - a)·d/|d|² clamped to [0, 1] (...) (a foot beyond an end takes
    that end; a segment of zero length its point a), the nearest points c = a + t d
    (dim, ...) and the distances |x - c| (...), unsigned.  Each caller takes the least
    over its segments (``min``; ``argmin``: the first of equal distances).

    >>> t, c, dist = nearest_on_segments(np.array([[0.0], [0.0]]), np.array([[2.0], [0.0]]),
    ...                                  np.array([[1.0, 3.0], [1.0, 0.0]]))
    >>> t.tolist(), c[0].tolist(), dist.tolist()     # above the middle; beyond the end
    ([0.5, 1.0], [1.0, 2.0], [1.0, 1.0])
    """
    t = np.clip(((x - a) * d).sum(axis=0) / np.maximum((d * d).sum(axis=0), 1e-300), 0.0, 1.0)
    c = a + t * d
    return t, c, np.linalg.norm(x - c, axis=0)


def _zero_segments(X, ps, ph):
    """The segment {ψ_h = 0} of each reference triangle: ends (n, 2, 2), φ_h at them
    (n, 2) and whether there is one (n,).  X (n, 3, 2), ps and ph (n, 3)."""
    n = ps.shape[0]
    pts = np.zeros((n, 6, 2))
    fs = np.zeros((n, 6))
    ok = np.zeros((n, 6), dtype=bool)
    pts[:, :3], fs[:, :3], ok[:, :3] = X, ph, ps == 0
    for k, (a, b) in enumerate(((0, 1), (1, 2), (2, 0))):
        strict = ps[:, a] * ps[:, b] < 0
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(strict, ps[:, a] / (ps[:, a] - ps[:, b]), 0.0)
        pts[:, 3 + k] = X[:, a] + t[:, None] * (X[:, b] - X[:, a])
        fs[:, 3 + k] = ph[:, a] + t * (ph[:, b] - ph[:, a])
        ok[:, 3 + k] = strict
    count = ok.sum(axis=1)
    first = np.argsort(~ok, axis=1, kind="stable")[:, :2]
    ends = np.take_along_axis(pts, first[..., None], axis=1)
    f = np.take_along_axis(fs, first, axis=1)
    return ends, f, count == 2


def _crack_pieces(ends, f, has):
    """The part φ_h < 0 of each segment (n, 2, 2) with a mask, and the tips (m, 2) with
    their triangle."""
    f0, f1 = f[:, 0], f[:, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(f0 != f1, f0 / (f0 - f1), 0.0)
    T = ends[:, 0] + t[:, None] * (ends[:, 1] - ends[:, 0])
    behind0, behind1 = f0 <= 0, f1 <= 0
    both = has & behind0 & behind1 & ~((f0 == 0) & (f1 == 0))
    cross01 = has & (f0 < 0) & (f1 > 0)
    cross10 = has & (f1 < 0) & (f0 > 0)
    piece = ends.copy()
    piece[cross01, 1] = T[cross01]
    piece[cross10, 0] = T[cross10]
    mask = both | cross01 | cross10
    tip = cross01 | cross10 | (both & ((f0 == 0) | (f1 == 0)))
    tip_pt = np.where(((f0 == 0) & both)[:, None], ends[:, 0],
                      np.where(((f1 == 0) & both)[:, None], ends[:, 1], T))
    flat = has & (f0 == 0) & (f1 == 0)
    return piece, mask, tip_pt[tip], np.flatnonzero(tip), flat


def _barycentric(P, x):
    """Barycentric coordinates (n, 3) of points x (n, 2) in triangles P (n, 3, 2)."""
    A = np.stack([P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]], axis=2)       # (n, 2, 2)
    lam = np.linalg.solve(A, (x - P[:, 0])[..., None])[..., 0]
    return np.column_stack([1 - lam.sum(axis=1), lam])


def _area(T):
    """Areas (n,) of triangles T (n, 3, 2)."""
    d1, d2 = T[:, 1] - T[:, 0], T[:, 2] - T[:, 0]
    return 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])


def _fan(T, X, ps):
    """Fan of the reference triangle X (3, 2) from the point T (2,) in it: to its vertices
    and to the points where ψ_h (ps, (3,)) changes sign on its edges.  Sub-triangles
    (m, 3, 2), vertex 0 at T, and their sides (the sign of ψ_h at the centroid)."""
    ring = []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        ring.append(X[a])
        if ps[a] * ps[b] < 0:
            ring.append(X[a] + ps[a] / (ps[a] - ps[b]) * (X[b] - X[a]))
    ring = np.array(ring)
    tris = np.stack([np.broadcast_to(T, ring.shape), ring, np.roll(ring, -1, axis=0)], axis=1)
    tris = tris[_area(tris) > AREA_TOL * 0.5]
    lam = _barycentric(np.broadcast_to(X, (tris.shape[0], 3, 2)), tris.mean(axis=1))
    return tris, np.where(lam @ ps < 0, -1, 1)


def crack_geometry(mesh, psi, phi) -> CrackGeometry:
    """The :class:`CrackGeometry` of the crack {ψ = 0, φ < 0} on a 2D mesh.

    Parameters
    ----------
    mesh : a ``MeshTri1`` or ``MeshQuad1`` (linear cells).
    psi : the level set of the crack's line (callable or nodal values), Ω⁺ = {ψ > 0}.
    phi : the level set of the front (callable or nodal values), φ > 0 ahead.

    Raises
    ------
    ValueError
        A mesh that is not 2D (``mesh``), NaN level sets (``psi``, ``phi``), a crack
        that meets no cell (``psi``, ``phi``), a φ that never vanishes on it (``phi``),
        φ ≡ 0 along ψ = 0 (``phi``), two tips in one cell (refine the mesh).

    Examples
    --------
    >>> from skfem import MeshQuad1
    >>> m = MeshQuad1.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 1, 4))
    >>> g = crack_geometry(m, lambda x: x[1] - 0.5, lambda x: x[0] - 0.5)
    >>> g.tip_cells.tolist(), int(g.sub_fan.sum())   # 3 fan triangles per half
    ([4], 6)
    """
    check_mesh_2d(mesh)
    psi = level_set_values("psi", psi, mesh)
    phi = level_set_values("phi", phi, mesh)
    ref = mesh.elem().doflocs                            # (nloc, 2)
    simp = reference_simplices(mesh)                     # (ns, 3)
    nc, ns = mesh.t.shape[1], simp.shape[0]
    X = np.broadcast_to(ref[simp], (nc, ns, 3, 2)).reshape(-1, 3, 2)
    nodes = mesh.t[simp].transpose(2, 0, 1).reshape(-1, 3)    # (nc * ns, 3)
    cell_of = np.repeat(np.arange(nc), ns)
    ps, ph = psi[nodes], phi[nodes]
    if np.any((ps == 0).all(axis=1)):
        raise ValueError("psi vanishes on a whole cell: it must be zero on a line only")

    ends, f, has = _zero_segments(X, ps, ph)
    piece, mask, tip_ref, tip_tri, flat = _crack_pieces(ends, f, has)
    if np.any(flat):
        raise ValueError(f"phi vanishes along psi = 0 in {int(flat.sum())} cell(s): the "
                         f"level sets must cross (∇φ not parallel to ∇ψ) at the front")
    split_tri = mask.copy()              # every triangle holding a piece, before one owner
    mask &= _owns_edge_piece(mesh, nodes, ps, has)
    F = mesh.mapping().F
    h = np.ptp(mesh.p[:, mesh.t], axis=1).max(axis=0)
    long = ~_zero_length(mesh, piece, cell_of, h)       # pieces of positive length
    own = mask & long
    seg = np.stack([F(piece[own][:, k].T[:, :, None], tind=cell_of[own])[:, :, 0]
                    for k in (0, 1)])                    # (2, 2, nseg)
    seg_cell, seg_ref, seg_tri = cell_of[own], piece[own], np.flatnonzero(own)
    if seg_cell.size == 0:
        raise ValueError(f"the crack {{psi = 0, phi < 0}} meets no cell of the mesh (psi in "
                         f"[{psi.min():.3g}, {psi.max():.3g}], phi in [{phi.min():.3g}, "
                         f"{phi.max():.3g}] at the nodes): check psi and phi")
    if tip_tri.size == 0:
        raise ValueError("phi < 0 all along psi = 0 in the mesh: phi never vanishes on the "
                         "crack, so it has no tip inside the body: move the front (phi = 0) "
                         "into the body, or, for a Γ that cuts the body through, leave the "
                         "front out (an interface of skxfem.cut)")
    tips = _unique_points(F(tip_ref.T[:, :, None], tind=cell_of[tip_tri])[:, :, 0],
                          h[cell_of[tip_tri]])

    # tip cells: the closure of one of their reference triangles holds a tip
    P = F(np.transpose(X, (2, 0, 1)), tind=cell_of)     # (2, n, 3) physical triangles
    P = np.transpose(P, (1, 2, 0))
    tip_cells, tip_of_cell = [], []
    for k in range(tips.shape[1]):                      # the few tips
        lam = _barycentric(P, np.broadcast_to(tips[:, k], (P.shape[0], 2)))
        cells = np.unique(cell_of[(lam >= -1e-10).all(axis=1)])
        tip_cells.append(cells)
        tip_of_cell.append(np.full(cells.size, k))
    tip_cells, tip_of_cell = np.concatenate(tip_cells), np.concatenate(tip_of_cell)
    if np.unique(tip_cells).size < tip_cells.size:
        raise ValueError("two tips lie in one cell: the crack is shorter than a cell or "
                         "its tips are too close; refine the mesh")
    order = np.argsort(tip_cells)
    tip_cells, tip_of_cell = tip_cells[order], tip_of_cell[order]
    tip_ref = mesh.mapping().invF(tips[:, tip_of_cell][:, :, None], tind=tip_cells)[:, :, 0]
    split_cells = np.setdiff1d(np.unique(cell_of[split_tri & long]), tip_cells)

    side = np.where(psi[mesh.t].mean(axis=0) < 0, -1, 1)
    side[split_cells] = 0
    side[tip_cells] = 0

    # sub-cells: split cells by ψ_h, tip cells fanned from the tip
    in_split = np.isin(cell_of, split_cells)
    sub, parent, sub_side = split(X[in_split], ps[in_split])
    sub_cell = cell_of[in_split][parent]
    subs, cells_, sides, fans = [sub], [sub_cell], [sub_side], [np.zeros(sub_cell.size, bool)]
    for c, T in zip(tip_cells, tip_ref.T):              # the few tip cells
        for k in range(ns):
            i = c * ns + k
            lam = _barycentric(X[i][None], T[None])[0]
            if np.all(lam >= -1e-10):
                tris, s = _fan(T, X[i], ps[i])
                fan = np.ones(s.size, bool)
            else:
                tris, _, s = split(X[i][None], ps[i][None])
                fan = np.zeros(s.size, bool)
            subs.append(tris)
            cells_.append(np.full(s.size, c))
            sides.append(s)
            fans.append(fan)
    sub, sub_cell = np.concatenate(subs), np.concatenate(cells_)
    sub_side, sub_fan = np.concatenate(sides), np.concatenate(fans)
    keep = _area(sub) > AREA_TOL * 0.5
    edge_ids, edges, points, facets = _cut_edges(mesh, psi, phi, seg, seg_cell, h)
    normals = _segment_normals(P[seg_tri], ps[seg_tri], seg)
    psi, phi = orthonormal_at_tips(mesh, psi, phi, tip_cells, tip_of_cell, tip_ref)
    return CrackGeometry(psi, phi, tips, tip_cells, tip_of_cell, tip_ref, split_cells, side,
                         seg, seg_cell, sub[keep], sub_cell[keep], sub_side[keep],
                         sub_fan[keep], edge_ids, edges, points,
                         np.unique(mesh.t[:, np.union1d(split_cells, tip_cells)]), facets,
                         np.transpose(seg_ref, (1, 2, 0)), normals)


def level_set_scales(gpsi: np.ndarray, gphi: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """How far the level sets are from signed distances, from their gradients ``gpsi``,
    ``gphi`` (dim, ...): γ = |∇ψ|, c = ∇φ·∇ψ/γ² and β = |∇φ - c∇ψ|, the part of |∇φ|
    normal to ∇ψ (...), so that (ψ/γ, (φ - cψ)/β) have orthonormal gradients.

    >>> [float(v) for v in level_set_scales(np.array([0.0, 10.0]), np.array([1.0, 5.0]))]
    [10.0, 0.5, 1.0]
    """
    gamma = np.linalg.norm(gpsi, axis=0)
    c = (gphi * gpsi).sum(axis=0) / np.maximum(gamma, 1e-300) ** 2
    return gamma, c, np.linalg.norm(gphi - c * gpsi, axis=0)


def orthonormal_at_tips(mesh, psi: np.ndarray, phi: np.ndarray, tip_cells: np.ndarray,
                        tip_of_cell: np.ndarray, tip_ref: np.ndarray, tol: float = 1e-6
                        ) -> tuple[np.ndarray, np.ndarray]:
    """The nodal level sets (ψ̂, φ̂) = (ψ/γ, (φ - c ψ)/β) whose gradients at the tips are
    orthonormal: γ = |∇ψ_h|, c = ∇φ_h·∇ψ_h/γ², β the part of |∇φ_h| normal to ∇ψ_h, at
    the tip in its first tip cell.  The crack is the same ({ψ̂ = 0} = {ψ = 0}, and there
    φ̂ = φ/β), but the polar coordinates r = √(φ̂² + ψ̂²), θ = atan2(ψ̂, φ̂) of the branch
    functions are the tip's: with ψ = 10 (y - 0.525), or φ = x + y - 1.025 for the tip
    (0.5, 0.525), K_I of an edge crack came out 6.4 % or 1 % low (the functions were
    those of skewed coordinates).  Several tips whose (γ, c, β) differ by more than
    ``tol`` (relative) share no such map: the values are returned as they are.

    >>> from skfem import MeshTri1
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 5), np.linspace(0, 1, 5))
    >>> g = crack_geometry(m, 10 * (m.p[1] - 0.6), m.p[0] + m.p[1] - 1.1)
    >>> bool(np.allclose(g.psi, m.p[1] - 0.6)), bool(np.allclose(g.phi, m.p[0] - 0.5))
    (True, True)
    """
    maps = []
    for k in range(int(tip_of_cell.max()) + 1):
        i = np.flatnonzero(tip_of_cell == k)[0]
        b = Basis(mesh, mesh.elem(), elements=tip_cells[i:i + 1],
                  quadrature=(tip_ref[:, i:i + 1], np.ones(1)))
        gpsi, gphi = (b.interpolate(v).grad[:, 0, 0] for v in (psi, phi))
        gamma, c, beta = (float(v) for v in level_set_scales(gpsi, gphi))
        if not (gamma > 0 and beta > 0):
            return psi, phi
        maps.append((gamma, c, beta))
    gamma, c, beta = maps[0]
    if any(abs(g - gamma) > tol * gamma or abs(b - beta) > tol * beta
           or abs(cc - c) > tol * max(1.0, abs(c)) for g, cc, b in maps[1:]):
        return psi, phi
    return psi / gamma, (phi - c * psi) / beta


def _zero_length(mesh, piece, cell_of, h):
    """(n,) True where a reference triangle's crack piece ``piece`` (n, 2, 2) is shorter
    than :data:`AREA_TOL` times its cell's size ``h`` (physical)."""
    F = mesh.mapping().F
    ends = [F(piece[:, k].T[:, :, None], tind=cell_of)[:, :, 0] for k in (0, 1)]
    return np.linalg.norm(ends[1] - ends[0], axis=0) <= AREA_TOL * h[cell_of]


def _owns_edge_piece(mesh, nodes, ps, has):
    """(n,) False for a reference triangle whose piece of {ψ_h = 0} is one of its edges
    (ψ_h = 0 at two vertices) that the triangle beside it owns.

    A crack along a mesh edge, or along a quadrilateral's diagonal 0-2, is the zero set of
    ψ_h in the two triangles beside that edge; it belongs to the one on the Ω⁻ side
    (ψ_h < 0 at its third vertex, :mod:`skxfem.levelset`'s sign convention), so that each
    piece of Γ is listed, and integrated over, once.  On the mesh boundary the edge has a
    single triangle, which owns it whatever its side.  ``nodes`` (n, 3) the triangles' mesh
    nodes, ``ps`` (n, 3) the nodal ψ, ``has`` (n,) from :func:`_zero_segments`."""
    zero = ps == 0
    on_edge = has & (zero.sum(axis=1) == 2)
    third = np.where(on_edge, np.argmin(zero, axis=1), 0)
    minus = np.take_along_axis(ps, third[:, None], axis=1)[:, 0] < 0
    # the edge's two nodes, sorted, against the boundary edges of the mesh
    pair = np.sort(np.stack([nodes[np.arange(nodes.shape[0]), (third + 1) % 3],
                             nodes[np.arange(nodes.shape[0]), (third + 2) % 3]]), axis=0)
    bnd = np.sort(mesh.facets[:, mesh.boundary_facets()], axis=0)
    key = pair[0] * mesh.p.shape[1] + pair[1]
    on_boundary = np.isin(key, bnd[0] * mesh.p.shape[1] + bnd[1])
    return ~on_edge | minus | on_boundary


def _cut_edges(mesh, psi, phi, seg, seg_cell, h):
    """The points that carry the crack's multipliers (:func:`crack_points`): the
    crossings of the mesh edges the crack crosses strictly (ψ changes sign, φ < 0 at the
    crossing), then the nodes on the crack that end a crack piece.  Returns (edge_ids,
    edges (2, ne), points (2, ne), facets): each crack piece's ends as indices into the
    points (-1: an end that is neither, the tip or a point of a quadrilateral's
    diagonal)."""
    a, b = mesh.facets
    strict = psi[a] * psi[b] < 0
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(strict, psi[a] / (psi[a] - psi[b]), 0.0)
    ids = np.flatnonzero(strict & (phi[a] + t * (phi[b] - phi[a]) < 0))
    points = mesh.p[:, a[ids]] + t[ids] * (mesh.p[:, b[ids]] - mesh.p[:, a[ids]])
    return crack_points(mesh, mesh.facets, mesh.t2f, psi, phi, ids, points, seg, seg_cell,
                        1e-9 * h[seg_cell])


def crack_points(mesh, edges, cell_edges, psi, phi, ids, points, ends, cells, tol):
    """The points that carry a crack's multipliers, 2D or 3D, as :class:`skxfem.cut.Cut`
    lists them: the crossings ``points`` (dim, m) of the mesh edges ``ids`` (m,) (columns
    of ``edges`` (2, n_edges); ``cell_edges`` (k, ncells) each cell's edges: ``mesh.t2f``
    in 2D, ``mesh.t2e`` in 3D), then the nodes on the crack (ψ = 0, φ < 0: behind its
    front) that are a vertex of a crack piece, each the degenerate edge (v, v) with
    edge id -1.  ``ends`` (nv, dim, npiece) the pieces' vertices (a 2D piece's two ends,
    a 3D face's three), ``cells`` (npiece,) their cells, ``tol`` (npiece,) how near a
    vertex lies to a point that it is.

    Returns (edge_ids (ne,), edges (2, ne), points (dim, ne), facets (nv, npiece)): each
    piece's vertices as indices into the points (-1: no point, e.g. on the front).

    >>> from skfem import MeshTri1
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 3), np.linspace(0, 1, 3))
    >>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.75)      # along mesh edges
    >>> g.edge_ids.tolist(), g.points.T.tolist()                 # its nodes behind the tip
    ([-1, -1], [[0.0, 0.5], [0.5, 0.5]])
    """
    on = (psi == 0) & (phi < 0)                           # nodes on the crack
    nodes = np.where(on[mesh.t[:, cells]], mesh.t[:, cells], -1)   # (nloc, npiece)
    vertex = np.zeros(nodes.shape, dtype=bool)            # a node that is a piece vertex
    for end in ends:
        d = np.linalg.norm(mesh.p[:, np.maximum(nodes, 0)] - end[:, None], axis=0)
        vertex |= (nodes >= 0) & (d <= tol)
    ids, edges, points, index, node_index = with_vertices(
        edges, ids, points, np.unique(nodes[vertex]), mesh.p)
    cand = np.vstack([index[cell_edges[:, cells]], node_index[mesh.t[:, cells]]])
    facets = np.full((len(ends), cells.size), -1)
    if ids.size == 0:                                     # no point behind the front
        return ids, edges, points, facets
    for k, end in enumerate(ends):
        d = np.linalg.norm(points[:, np.maximum(cand, 0)] - end[:, None], axis=0)
        d = np.where(cand >= 0, d, np.inf)
        j = np.argmin(d, axis=0)
        hit = d[j, np.arange(j.size)] <= tol
        facets[k] = np.where(hit, cand[j, np.arange(j.size)], -1)
    return ids, edges, points, facets


def point_cells(geo, edge_cell: np.ndarray) -> np.ndarray:
    """(ne,) a cell of each point of a crack's geometry ``geo`` (2D or 3D, its
    :func:`crack_points`): a crossing's, the cell ``edge_cell`` (one per mesh edge) gives
    its edge; a node's, the cell of a crack piece (a face in 3D) it is a vertex of.

    >>> from skfem import MeshTri1
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 3), np.linspace(0, 1, 3))
    >>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.75)      # two nodes on the crack
    >>> c = point_cells(g, m.f2t[0])
    >>> bool(np.all([np.isin(v, m.t[:, k]) for v, k in zip(g.edges[0], c)]))
    True
    """
    strict = geo.edge_ids >= 0
    cells = np.zeros(geo.edge_ids.size, dtype=np.int64)
    cells[strict] = edge_cell[geo.edge_ids[strict]]
    vertex = geo.facets.ravel()
    piece_cell = np.tile(geo.facet_cell, geo.facets.shape[0])
    at_node = vertex >= 0
    at_node[at_node] = ~strict[vertex[at_node]]
    cells[vertex[at_node]] = piece_cell[at_node]
    return cells


def _segment_normals(P, ps, seg):
    """Unit normals (2, nseg) of the crack pieces, pointing into Ω⁺ (along ∇ψ_h of the
    physical triangle P (nseg, 3, 2) with ψ values ps (nseg, 3) that holds each)."""
    A = np.stack([P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]], axis=1)   # rows: edge vectors
    grad = np.linalg.solve(A, (ps[:, 1:] - ps[:, :1])[..., None])[..., 0]
    d = seg[1] - seg[0]
    n = np.stack([-d[1], d[0]]) / np.linalg.norm(d, axis=0)
    return n * np.where((n * grad.T).sum(axis=0) < 0, -1.0, 1.0)


def _unique_points(x: np.ndarray, h: np.ndarray) -> np.ndarray:
    """The distinct points among the columns of x (2, m), within 1e-9 of the cell size."""
    out = []
    for k in range(x.shape[1]):                          # a few candidates per tip
        if not any(np.linalg.norm(x[:, k] - y) <= 1e-9 * h[k] for y in out):
            out.append(x[:, k])
    return np.array(out).T
