r"""Cutting a mesh by a level set: cut edges, interface facets and sub-cells.

Given nodal values ψ_i of the level set (sign convention in :mod:`skxfem.levelset`):

* **S_e**, the strictly cut edges, are the mesh edges with ψ(v₁)ψ(v₂) < 0 (paper §5).
  Each is cut once, at the zero of the linear interpolant of ψ along it.
  These intersection points carry the interface multipliers (paper §4.2).
* A **cut cell** has at least one strictly cut edge.  Its nodes are the
  nodes whose support Γ crosses: they get Heaviside-enriched dofs (eq. 11).
* The **interface** Γ_h in a cut cell is the polygon through the intersection
  points of its edges: a segment in 2D, a triangle to hexagon in 3D, split
  into triangles by a fan from its first vertex.  Normals point into Ω⁺.
* The **sub-cells** split each cut cell into pieces on either side, for
  integrating discontinuous integrands.  The reference cell is split into
  simplices (:func:`skxfem.fem.cells.reference_simplices`), and each simplex is
  split by :func:`skxfem.fem.simplex.split`.  Everything is done in the parent's
  reference coordinates, ready for per-cell quadrature.

For a plane ψ and affine cells (every structured box mesh) the interface
facets and the faces of the sub-cells lie on the same plane, so integrals over
Γ_h and over the sub-cell boundaries agree exactly: this is what makes the
patch tests pass to round-off.

**Vertices on Γ.** A vertex where ψ vanishes (the natural first scene: Γ at
z = 10 on a 20-cell mesh) lies *on* Γ, exactly.  A vertex closer to Γ than
:data:`SNAP` times its shortest edge (the distance measured as |ψ_i| over the
steepest slope of ψ along its edges, so that the test does not depend on the
scale of ψ) is put on it, ψ_i = 0 (:func:`snap`); only that moves Γ, by less
than :data:`SNAP` edge lengths, and one :class:`SnapWarning` gives the count
and the largest shift (a vertex with ψ_i = 0, or within the round-off of ψ,
:data:`ROUND_OFF` edge lengths, moves nothing and warns nothing).  Then, with
ψ_i = 0 at the vertices on Γ:

* a cell is **cut** if it has a vertex in Ω⁻ (ψ < 0) and one in Ω⁺ (ψ > 0);
  a cell whose other vertices all lie on one side is uncut, all of it on
  that side, even where vertices (an edge, a face) touch Γ;
* a vertex on Γ of a cut cell is a **point** of Γ_h, as the intersection
  point of a strictly cut edge is: the point list holds the cut edges' points
  first, then these vertex points, recorded as the degenerate edge (v, v)
  with edge id -1 (:class:`Cut`);
* a **mesh facet on Γ** (all its vertices on it) between a cell of Ω⁻ and one
  of Ω⁺ is a facet of Γ_h, its vertices points, integrated in the Ω⁻ cell;
* no zero-measure sub-cell is made: a sub-simplex with two equal vertices
  (a cut "point" at a vertex) is dropped.

So Γ through mesh nodes, or along mesh facets, is cut exactly and the
two sides' volumes still sum to the cell's.  A cell whose cut points do not
form one polygon (a saddle) is refused: refine the mesh.

>>> from skfem import MeshQuad1
>>> from skxfem.levelset import plane
>>> from skxfem.cut import cut as cut_mesh
>>> cut = cut_mesh(MeshQuad1().refined(1), plane((0, 0.4), (0, 1)))
>>> cut.points.shape, round(float(cut.measures.sum()), 12)
((2, 3), 1.0)
>>> on = cut_mesh(MeshQuad1().refined(1), plane((0, 0.5), (0, 1)))   # along the facets
>>> on.edge_ids.tolist(), on.cells.size, round(float(on.measures.sum()), 15)
([-1, -1, -1], 0, 1.0)
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .fem.cells import cell_edges, on_common_face, reference_simplices
from .fem.meshes import cell_name
from .fem.simplex import edge_point, split
from .levelset import nodal_values

__all__ = ["Cut", "cut", "strictly_cut_edges", "with_vertices", "snap", "SNAP", "SnapWarning",
           "check_apart", "point_lengths", "ROUND_OFF", "rescaled", "PSI_RANGE", "PSI_FLOOR"]

SNAP = 1e-9
"""Vertices closer to Γ than SNAP times their shortest edge are put on it, ψ = 0
(:func:`snap`)."""


ROUND_OFF = 64 * np.finfo(float).eps
"""Vertices closer to Γ than ROUND_OFF (1.4e-14) times their shortest edge are on it
up to the round-off of ψ (a plane through them, evaluated): put on it silently."""


class SnapWarning(UserWarning):
    """Vertices within :data:`SNAP` edge lengths of Γ, not on it, were put on it
    (ψ set to 0): Γ moved by less than SNAP edge lengths.  Vertices on Γ (ψ = 0,
    or within :data:`ROUND_OFF` edge lengths) raise none."""


@dataclass(frozen=True)
class Cut:
    """The geometry of a mesh cut by a level set (all arrays, no mesh copy).

    Attributes
    ----------
    psi : (nverts,) nodal level set values as used: 0 at the vertices on Γ
        (:func:`snap`).
    edge_ids : (ne,) for each point of Γ_h on the mesh edges, the index of its
        strictly cut edge among the mesh edges (``mesh.edges`` in 3D,
        ``mesh.facets`` in 2D), -1 for a vertex on Γ.  The cut edges S_e come
        first, then the vertices on Γ; ``ne`` counts both.
    edges : (2, ne) the ends of each point's edge; (v, v) for a vertex v on Γ.
    points : (dim, ne) the points: an edge's intersection point, or the vertex
        itself.  One multiplier each.
    cells : (ncut,) cut cells: a vertex in Ω⁻ and one in Ω⁺.  ``side`` :
        (ncells,) -1 / +1 for cells in Ω⁻ / Ω⁺ (their vertices not on Γ all
        on that side), 0 for cut cells.
    node_side : (nverts,) -1 / +1, the side of each node: the sign of ψ off
        Γ; a node on Γ is on Ω⁺ if a cell of its support has a part there,
        else on Ω⁻ (so a node on Γ split by it takes Ω⁺, one that only
        touches Γ the side of its support).
    enriched : (nenr,) nodes whose support Γ_h splits (nodes of cut cells and
        vertices of mesh facets on Γ), which carry Heaviside dofs.
    facets : (dim, nf) interface facets as indices into ``points``
        (segments in 2D, triangles in 3D), those of the cut cells first, then
        those of the mesh facets on Γ; ``facet_cell`` : (nf,) parent cell (the
        Ω⁻ cell of a mesh facet on Γ);
        ``facet_ref`` : (dim, dim, nf) their vertices in the parent's
        reference coordinates, ``[vertex, coordinate, facet]``;
        ``normals`` : (dim, nf) unit normals into Ω⁺; ``measures`` : (nf,).
    sub_ref : (nsub, dim + 1, dim) sub-simplices of the cut cells in parent
        reference coordinates, none of zero measure; ``sub_cell`` : (nsub,)
        parent; ``sub_side`` : (nsub,) ±1.
    """

    psi: np.ndarray
    edge_ids: np.ndarray
    edges: np.ndarray
    points: np.ndarray
    cells: np.ndarray
    side: np.ndarray
    node_side: np.ndarray
    enriched: np.ndarray
    facets: np.ndarray
    facet_cell: np.ndarray
    facet_ref: np.ndarray
    normals: np.ndarray
    measures: np.ndarray
    sub_ref: np.ndarray
    sub_cell: np.ndarray
    sub_side: np.ndarray


def strictly_cut_edges(edges, psi, x) -> tuple[np.ndarray, np.ndarray]:
    """S_e = {e : ψ(v₁(e)) ψ(v₂(e)) < 0} (paper §5) and the intersection points.

    Parameters
    ----------
    edges : (2, nedges) vertex pairs; psi : (nverts,) nodal values;
    x : (dim, nverts) vertex coordinates.

    Returns
    -------
    edge_ids, points
        Indices of the strictly cut edges and their points (dim, ne), where
        the linear interpolant of ψ vanishes (:func:`skxfem.fem.simplex.edge_point`).

    >>> edges, psi = np.array([[0, 1], [1, 2]]), np.array([-1., 1., 3.])
    >>> ids, pts = strictly_cut_edges(edges, psi, np.array([[0., 1., 2.]]))
    >>> ids.tolist(), pts.tolist()
    ([0], [[0.5]])
    """
    edge_ids = np.flatnonzero(np.sign(psi[edges[0]]) * np.sign(psi[edges[1]]) < 0)  # no underflow
    a, b = edges[:, edge_ids]
    return edge_ids, edge_point(x[:, a].T, x[:, b].T, psi[a], psi[b]).T


def with_vertices(all_edges, edge_ids, points, vertices, x):
    """The points that carry Γ's multipliers: the crossings ``points`` (dim, m) of the
    edges ``edge_ids`` (m,) (columns of ``all_edges``), then the ``vertices`` on Γ, each
    the degenerate edge (v, v) with id -1 at ``x[:, v]``.

    Returns
    -------
    edge_ids, edges, points, point_of_edge, point_of_vertex
        (ne,), (2, ne), (dim, ne), and the index of each mesh edge's and each vertex's
        point (-1: none).

    >>> ids, edges, pts, pe, pv = with_vertices(np.array([[0, 1], [1, 2]]), np.array([1]),
    ...                                         np.array([[1.5]]), np.array([0]),
    ...                                         np.array([[0., 1., 2.]]))
    >>> ids.tolist(), edges.tolist(), pts.tolist(), pe.tolist(), pv.tolist()
    ([1, -1], [[1, 0], [2, 0]], [[1.5, 0.0]], [-1, 0], [1, -1, -1])
    """
    ne = edge_ids.size
    point_of_edge = np.full(all_edges.shape[1], -1)
    point_of_edge[edge_ids] = np.arange(ne)
    point_of_vertex = np.full(x.shape[1], -1)
    point_of_vertex[vertices] = ne + np.arange(vertices.size)
    edges = np.hstack([all_edges[:, edge_ids], np.vstack([vertices, vertices])])
    points = np.hstack([points, x[:, vertices]])
    edge_ids = np.r_[edge_ids, np.full(vertices.size, -1)]
    return edge_ids, edges, points, point_of_edge, point_of_vertex


def snap(mesh, psi: np.ndarray, edges: np.ndarray | None = None):
    """ψ with the vertices within :data:`SNAP` edge lengths of Γ put on it (ψ_i = 0).

    The distance of vertex i to Γ is taken as |ψ_i| / g_i, g_i the steepest
    slope |ψ_j - ψ_i| / |x_j - x_i| over its edges; a vertex with d_i < SNAP h_i
    (h_i its shortest edge) gets ψ_i = 0.  ``edges`` (2, n_edges): the mesh
    edges (default: computed).

    Returns
    -------
    psi, moved, shift
        The values, the number of vertices put on Γ that were farther from it
        than round-off (d_i ≥ :data:`ROUND_OFF` h_i: Γ passes near them, not
        through them) and the largest such distance (0.0 if none).

    Raises
    ------
    ValueError
        ψ vanishes at a vertex and along all of its edges (ψ ≡ 0 around it).

    >>> from skfem import MeshQuad1
    >>> m = MeshQuad1().refined(1)                    # vertices at y = 0, 0.5, 1
    >>> psi, moved, shift = snap(m, m.p[1] - 0.5)     # Γ through a row of vertices
    >>> int((psi == 0).sum()), moved, shift           # on Γ already: nothing moves
    (3, 0, 0.0)
    >>> psi, moved, shift = snap(m, m.p[1] - 0.5 + 1e-12)
    >>> int((psi == 0).sum()), moved, shift <= 1e-12
    (3, 3, True)
    """
    cell_name(mesh)  # TypeError for an unsupported mesh type
    if edges is None:
        edges = cell_edges(mesh)[2]
    a, b = edges
    length = np.linalg.norm(mesh.p[:, a] - mesh.p[:, b], axis=0)
    slope = np.abs(psi[a] - psi[b]) / length
    n_nodes = psi.size
    g, h = np.zeros(n_nodes), np.full(n_nodes, np.inf)
    for end in (a, b):
        np.maximum.at(g, end, slope)
        np.minimum.at(h, end, length)
    flat = (psi == 0) & (g == 0)
    if flat.any():
        i = np.flatnonzero(flat)[0]
        raise ValueError(
            f"the level set vanishes at vertex {i} ({mesh.p[:, i].tolist()}) and at all its "
            f"neighbours: it is zero on a region, not on a surface; give psi a nonzero "
            f"gradient at the interface")
    with np.errstate(divide="ignore", invalid="ignore"):
        distance = np.where(g > 0, np.abs(psi) / g, np.inf)
    near = (distance < SNAP * h) & (psi != 0)
    if not near.any():
        return psi, 0, 0.0
    out = psi.copy()
    out[near] = 0.0
    moved = near & (distance >= ROUND_OFF * h)
    return out, int(moved.sum()), float(distance[moved].max()) if moved.any() else 0.0


def point_lengths(mesh, cut: Cut) -> np.ndarray:
    """(ne,) a mesh length at each point of Γ_h: its cut edge's length, or, for a
    vertex on Γ, the mean length of the mesh edges at it (the mesh size there).

    >>> from skfem import MeshQuad1
    >>> from skxfem.levelset import plane
    >>> m = MeshQuad1().refined(2)
    >>> point_lengths(m, cut(m, plane((0, 0.5), (0, 1)))).tolist()    # 5 vertices on Γ
    [0.25, 0.25, 0.25, 0.25, 0.25]
    """
    a, b = cut.edges
    lengths = np.linalg.norm(mesh.p[:, a] - mesh.p[:, b], axis=0)
    on = np.flatnonzero(a == b)
    if on.size:
        edges = cell_edges(mesh)[2]
        size = np.linalg.norm(mesh.p[:, edges[0]] - mesh.p[:, edges[1]], axis=0)
        total = np.bincount(edges.ravel(), np.tile(size, 2), minlength=mesh.p.shape[1])
        count = np.bincount(edges.ravel(), minlength=mesh.p.shape[1])
        lengths[on] = total[a[on]] / count[a[on]]
    return lengths


def cut(mesh, psi, name: str = "") -> Cut:
    """Cut ``mesh`` by the level set ``psi`` (a callable or nodal values).

    Parameters
    ----------
    mesh
        ``MeshTri1``, ``MeshQuad1``, ``MeshTet1``, ``MeshHex1`` or ``MeshWedge1``.
    psi
        A level set callable (see :mod:`skxfem.levelset`) or its nodal values.
    name
        What the :class:`SnapWarning` and errors call the interface (a scene with
        several: ``"interfaces[1] 'y - 0.7'"``); ``""``: "the level set".

    Raises
    ------
    ValueError
        If the level set cuts no cell, vanishes on a region (or on a whole
        cell), lies on the boundary, or cuts a cell in more than one piece.
        Vertices on Γ stay on it (module notes).
    """
    if callable(psi):
        psi = nodal_values(psi, mesh)
    psi = np.asarray(psi, dtype=float)
    if psi.shape != (mesh.p.shape[1],) or not np.all(np.isfinite(psi)):
        raise ValueError(f"psi must hold one finite value per vertex, shape "
                         f"({mesh.p.shape[1]},); got shape {psi.shape}")
    psi = rescaled(psi, name)
    local, t2e, all_edges = cell_edges(mesh)
    psi, moved, shift = snap(mesh, psi, all_edges)
    if (psi == 0).any():
        _check_crosses(mesh, psi, psi == 0, name)
    if moved:
        warnings.warn(
            f"{name or 'the level set'} passes within {SNAP:g} edge lengths of {moved} mesh "
            f"vertices (not through them): put them on it (psi = 0), so Γ moves by up to "
            f"{shift:.1e} (skxfem.cut.SNAP)", SnapWarning, stacklevel=2)

    edge_ids, points = strictly_cut_edges(all_edges, psi, mesh.p)
    vals = psi[mesh.t]
    neg, pos = (vals < 0).any(axis=0), (vals > 0).any(axis=0)
    if not (neg | pos).all():
        i = np.flatnonzero(~(neg | pos))[0]
        raise ValueError(
            f"{name or 'the level set'} vanishes at every vertex of cell {i} (around "
            f"{np.round(mesh.p[:, mesh.t[:, i]].mean(axis=1), 6).tolist()}): it is zero on a "
            f"region, not on a surface; give psi a nonzero gradient at the interface")
    cells = np.flatnonzero(neg & pos)
    side = np.where(neg, -1, 1)
    side[cells] = 0
    on_gamma = _facets_on_gamma(mesh, psi, side)
    if cells.size == 0 and on_gamma.size == 0:
        raise ValueError(
            f"the level set cuts no cell of the mesh (psi ranges over "
            f"[{psi.min():.3g}, {psi.max():.3g}] at the nodes, one sign at all of them "
            f"but where it vanishes): "
            f"move the interface inside the domain, or, if it is there but inside a "
            f"single cell (smaller than the mesh size), refine the mesh")

    # the points: cut edges first, then the vertices on Γ of cut cells and Γ's facets
    zero = psi == 0
    at = np.zeros(psi.size, dtype=bool)
    at[mesh.t[:, cells][zero[mesh.t[:, cells]]]] = True
    if on_gamma.size:
        at[mesh.facets[:, on_gamma]] = True
    edge_ids, edges, points, point_of_edge, point_of_vertex = with_vertices(
        all_edges, edge_ids, points, np.flatnonzero(at), mesh.p)

    # the nodes' sides, the enriched nodes
    support_plus = np.zeros(psi.size, dtype=bool)
    support_plus[mesh.t[:, side >= 0]] = True
    node_side = np.where(psi < 0, -1, 1)
    node_side[zero & ~support_plus] = -1
    enriched = np.unique(mesh.t[:, cells])
    if on_gamma.size:
        enriched = np.union1d(enriched, mesh.facets[:, on_gamma])

    slots = np.vstack([point_of_edge[t2e[:, cells]], point_of_vertex[mesh.t[:, cells]]])
    share_face = on_common_face(mesh, [*local, *np.arange(mesh.t.shape[0])[:, None]])
    facets, facet_cell, facet_ref = _interface(mesh, psi, local, slots, cells, share_face)
    direction = _plus_direction(mesh, psi, facet_cell)
    if on_gamma.size:
        f, fc, fr, fd = _gamma_facets(mesh, side, on_gamma, point_of_vertex)
        facets, facet_cell = np.hstack([facets, f]), np.r_[facet_cell, fc]
        facet_ref, direction = np.concatenate([facet_ref, fr], axis=2), np.hstack([direction, fd])
    normals, measures = _facet_geometry(mesh, facet_ref, facet_cell, direction)
    sub_ref, sub_cell, sub_side = _subcells(mesh, psi, cells)
    return Cut(psi, edge_ids, edges, points, cells, side, node_side, enriched, facets,
               facet_cell, facet_ref, normals, measures, sub_ref, sub_cell, sub_side)


def _facets_on_gamma(mesh, psi: np.ndarray, side: np.ndarray) -> np.ndarray:
    """The mesh facets with ψ = 0 at all their vertices between a cell of Ω⁻ and
    one of Ω⁺: facets of Γ_h."""
    if not (psi == 0).any():              # (the mesh's facets are not even built then)
        return np.zeros(0, dtype=np.int64)
    f2t = mesh.f2t
    inner = f2t[1] >= 0
    on = (psi[mesh.facets] == 0).all(axis=0) & inner
    on &= side[f2t[0]] * np.where(inner, side[np.maximum(f2t[1], 0)], 0) == -1
    return np.flatnonzero(on)


def _gamma_facets(mesh, side, on_gamma, point_of_vertex):
    """The interface facets of the mesh facets ``on_gamma``, in their Ω⁻ cell:
    (facets, facet_cell, facet_ref, direction) as :func:`_interface` and
    :func:`_plus_direction` give them; a quadrilateral split into two triangles."""
    f2t = mesh.f2t[:, on_gamma]
    parent = np.where(side[f2t[0]] < 0, f2t[0], f2t[1])
    verts = mesh.facets[:, on_gamma]                                   # (nfv, n)
    ordered = np.sort(verts, axis=0)                  # a prism's triangles repeat a vertex
    count = 1 + (np.diff(ordered, axis=0) != 0).sum(axis=0)
    out_f, out_c, out_r, out_d = [], [], [], []
    for k in np.unique(count):
        idx = np.flatnonzero(count == k)
        srt = ordered[:, idx]
        keep = np.vstack([np.ones(idx.size, bool), srt[1:] != srt[:-1]])
        v = np.take_along_axis(srt, np.argsort(~keep, axis=0, kind="stable")[:k], axis=0)
        local = np.argmax(mesh.t[:, parent[idx]][:, None, :] == v[None], axis=0)  # (k, n)
        r = mesh.elem().doflocs[local]                                 # (k, n, dim)
        if k > 3:   # in order around the (planar) reference face
            c = r.mean(axis=0)
            u = r[0] - c
            w = np.cross(np.cross(r[1] - r[0], r[2] - r[0]), u)
            ang = np.arctan2(((r - c) * w).sum(-1), ((r - c) * u).sum(-1))
            sel = np.argsort(ang, axis=0)
            v = np.take_along_axis(v, sel, axis=0)
            r = np.take_along_axis(r, sel[..., None], axis=0)
        out_of = (mesh.p[:, v].mean(axis=1)
                  - mesh.p[:, mesh.t[:, parent[idx]]].mean(axis=1))   # out of the Ω⁻ cell
        for tri in ([[0, 1]] if k == 2 else [[0, i, i + 1] for i in range(1, k - 1)]):
            out_f.append(point_of_vertex[v[tri]])
            out_c.append(parent[idx])
            out_r.append(np.transpose(r[tri], (0, 2, 1)))
            out_d.append(out_of)
    return (np.hstack(out_f), np.concatenate(out_c), np.concatenate(out_r, axis=2),
            np.hstack(out_d))


def _check_crosses(mesh, psi: np.ndarray, near: np.ndarray, name: str) -> None:
    """Refuse a level set that vanishes (within :data:`SNAP`) at the vertices ``near``
    and has one sign at all the others: Γ lies on the boundary of the body (or touches
    it from outside) and splits nothing (module notes)."""
    far = psi[~near]
    if far.size and not (np.all(far > 0) or np.all(far < 0)):
        return
    i = np.flatnonzero(near)[0]
    sign = "psi > 0" if far.size and far[0] > 0 else "psi < 0"
    raise ValueError(
        f"{name or 'the level set'} does not cross the body: it vanishes at {near.sum()} "
        f"mesh vertices, e.g. ({', '.join(f'{c:.6g}' for c in mesh.p[:, i])}), and has one "
        f"sign ({sign}) at all the others, so Γ lies on the boundary (or touches it from "
        f"outside); an interface must cut the body: move it inside (loads and supports "
        f"act on the boundary itself)")


PSI_RANGE = (1e-100, 1e100)
"""Nodal ψ whose largest magnitude lies outside this range is scaled into it by a
power of 2 (:func:`rescaled`): exact, and the cut does not depend on the scale of ψ."""


PSI_FLOOR = np.finfo(float).tiny * 2.0 ** 20
"""The smallest largest |ψ| at the nodes accepted (2.3e-302): a vertex 1e-9 edge lengths
from Γ (:data:`SNAP`) still has a value with 13 digits."""


def rescaled(psi: np.ndarray, name: str = "") -> np.ndarray:
    """Nodal values ``psi`` scaled by a power of 2 (exactly) if their largest magnitude
    is outside :data:`PSI_RANGE`, so that no product or sum of them over- or
    underflows (``1e300*(y - 0.5)``, ``1e-300*(y - 0.5)`` cut as ``y - 0.5`` does).

    Raises
    ------
    ValueError
        Values all below :data:`PSI_FLOOR` (but not all 0): near the smallest normal
        double, 2.2e-308, the values near Γ lose their digits and the cut would be
        wrong.  ``name`` names the level set.

    >>> x = np.array([-3e300, 1e300])
    >>> rescaled(x).tolist() == (x / 2.0 ** 999).tolist()    # the same digits
    True
    >>> rescaled(np.array([-1e-320, 1e-320]))
    Traceback (most recent call last):
    ...
    ValueError: the level set is at most 1e-320 in magnitude at the nodes, below 2.3e-302: ...
    """
    top = float(np.abs(psi).max()) if psi.size else 0.0
    if 0 < top < PSI_FLOOR:
        raise ValueError(f"{name or 'the level set'} is at most {top:.3g} in magnitude at the "
                         f"nodes, below {PSI_FLOOR:.2g}: near the smallest double (2.2e-308) "
                         f"its values near Γ lose their digits; scale psi (best a signed "
                         f"distance, in lengths of the mesh)")
    if top == 0 or PSI_RANGE[0] <= top <= PSI_RANGE[1]:
        return psi
    return np.ldexp(psi, -int(np.frexp(top)[1]))


def check_apart(mesh, cuts, names) -> None:
    """Refuse interfaces that cut a common cell: each cell may be cut by one only.

    Several interfaces of one scene (each its own :class:`Cut` in ``cuts``,
    named by ``names`` in the message) are enriched each on its own cut cells
    (:mod:`skxfem.enrich`), and a cell's sub-cells follow one level set.  Two
    that cross or touch cut a cell together, and so do two that pass closer
    to each other than about a cell.

    Raises
    ------
    ValueError
        Naming both interfaces, the number of cells they share and one of
        them with its centre.

    >>> from skfem import MeshQuad1
    >>> from skxfem.levelset import plane
    >>> m = MeshQuad1().refined(2)
    >>> a, b = cut(m, plane((0, 0.3), (0, 1))), cut(m, plane((0, 0.4), (0, 1)))
    >>> check_apart(m, (a, b), ("Γ at y = 0.3", "Γ at y = 0.4"))
    Traceback (most recent call last):
    ...
    ValueError: Γ at y = 0.3 and Γ at y = 0.4 both cut 4 mesh cell(s) (e.g. cell ...
    """
    for k in range(len(cuts)):
        for j in range(k):
            both = np.intersect1d(cuts[j].cells, cuts[k].cells)
            if both.size:
                centre = mesh.p[:, mesh.t[:, both[0]]].mean(axis=1)
                raise ValueError(
                    f"{names[j]} and {names[k]} both cut {both.size} mesh "
                    f"cell(s) (e.g. cell {both[0]} around "
                    f"{np.round(centre, 6).tolist()}): they cross, touch or pass closer "
                    f"than a cell to each other, and each cell may be cut by one interface "
                    f"only: refine the mesh or move them apart")


def _local_points(mesh, psi, local, cells):
    """Reference coordinates (ncut, nle + nv, dim) of each local edge's cut point,
    then of each local vertex."""
    ref = mesh.elem().doflocs
    pv = psi[mesh.t[:, cells]].T  # (ncut, nverts)
    a, b = local[:, 0], local[:, 1]
    with np.errstate(divide="ignore", invalid="ignore"):  # uncut edges: unused values
        X = edge_point(ref[a][None], ref[b][None], pv[:, a], pv[:, b])
    return np.concatenate([X, np.broadcast_to(ref, (cells.size,) + ref.shape)], axis=1)


def _interface(mesh, psi, local, cut_ids, cells, share_face):
    """Order each cut cell's points (``cut_ids`` (nle + nv, ncut): the point of each
    local edge, then of each local vertex, -1 for none) into a polygon and fan it."""
    dim = mesh.dim()
    X = _local_points(mesh, psi, local, cells)  # reference coordinates
    k = (cut_ids >= 0).sum(axis=0)
    facets, facet_cell, facet_ref = [], [], []
    allowed = (2,) if dim == 2 else (3, 4, 5, 6)
    bad = ~np.isin(k, allowed)
    for kk in np.unique(k):
        idx = np.flatnonzero(k == kk)
        if kk not in allowed:
            continue
        loc = np.argsort(cut_ids[:, idx] < 0, axis=0, kind="stable")[:kk].T  # (n, kk)
        R = X[idx[:, None], loc]  # (n, kk, dim)
        if dim == 3:
            # sort by angle around the centroid, in the plane normal to the
            # direction from the Ω⁻ vertices to the Ω⁺ vertices
            ref = mesh.elem().doflocs
            pv = psi[mesh.t[:, cells[idx]]].T
            neg, pos = pv < 0, pv > 0
            m = (neg @ ref) / neg.sum(1, keepdims=True)
            p = (pos @ ref) / pos.sum(1, keepdims=True)
            nrm = p - m
            helper = np.eye(3)[np.argmin(np.abs(nrm), axis=1)]
            u = np.cross(nrm, helper)
            u /= np.linalg.norm(u, axis=1, keepdims=True)
            v = np.cross(nrm, u)
            d = R - R.mean(axis=1, keepdims=True)
            ang = np.arctan2(np.einsum("nkd,nd->nk", d, v), np.einsum("nkd,nd->nk", d, u))
            order = np.argsort(ang, axis=1)
            loc = np.take_along_axis(loc, order, axis=1)
            R = np.take_along_axis(R, order[..., None], axis=1)
            ring = share_face[loc, np.roll(loc, -1, axis=1)].all(axis=1)
            bad[idx[~ring]] = True
            tris = np.array([[0, i, i + 1] for i in range(1, kk - 1)])  # fan
        else:
            tris = np.array([[0, 1]])
        gid = cut_ids[loc.T, idx].T  # (n, kk) cut-edge index of each polygon vertex
        for tri in tris:
            facets.append(gid[:, tri].T)
            facet_cell.append(cells[idx])
            facet_ref.append(np.transpose(R[:, tri], (1, 2, 0)))
    if bad.any():
        cell = cells[np.flatnonzero(bad)[0]]
        raise ValueError(
            f"{bad.sum()} cell(s) are cut into more than one piece (e.g. cell {cell}); "
            f"the interface is too curved for this mesh: refine the mesh")
    if not facets:   # Γ along mesh facets only
        return np.zeros((dim, 0), int), np.zeros(0, int), np.zeros((dim, dim, 0))
    return (np.concatenate(facets, axis=1), np.concatenate(facet_cell),
            np.concatenate(facet_ref, axis=2))


def _plus_direction(mesh, psi, facet_cell):
    """(dim, nf) a direction from Ω⁻ to Ω⁺ across each facet of a cut cell: from the
    centroid of the cell's vertices in Ω⁻ to that of those in Ω⁺."""
    pv = psi[mesh.t[:, facet_cell]]
    xc = mesh.p[:, mesh.t[:, facet_cell]]  # (dim, nverts, nf)
    w_plus, w_minus = (pv > 0), (pv < 0)
    return (xc * w_plus).sum(1) / w_plus.sum(0) - (xc * w_minus).sum(1) / w_minus.sum(0)


def _facet_geometry(mesh, facet_ref, facet_cell, direction):
    """Unit normals (into Ω⁺, along ``direction`` (dim, nf)) and measures of the
    (affinely mapped) facets."""
    mapping = mesh.mapping()
    x = mapping.F(np.transpose(facet_ref, (1, 2, 0)), tind=facet_cell)  # (dim, nf, nv)
    t = x[:, :, 1:] - x[:, :, :1]
    if mesh.dim() == 2:
        n = np.array([t[1, :, 0], -t[0, :, 0]])
    else:
        n = np.cross(t[:, :, 0].T, t[:, :, 1].T).T / 2.0
    measures = np.linalg.norm(n, axis=0)
    n = n / measures
    n = n * np.where((n * direction).sum(0) < 0, -1.0, 1.0)
    return n, measures


def _subcells(mesh, psi, cells):
    """Sub-simplices of the cut cells, in reference coordinates, with sides."""
    ref = mesh.elem().doflocs
    simp = reference_simplices(mesh)  # (ns, dim + 1)
    ns, nv = simp.shape
    X = np.broadcast_to(ref[simp], (cells.size, ns, nv, mesh.dim())).reshape(-1, nv, mesh.dim())
    pv = psi[mesh.t[:, cells]].T[:, simp].reshape(-1, nv)
    sub, parent, side = split(X, pv)
    if not (pv == 0).any():
        return sub, cells[parent // ns], side
    # a vertex on Γ makes pieces with two equal vertices (zero measure): drop them
    same = (sub[:, :, None, :] == sub[:, None, :, :]).all(axis=-1)
    keep = ~np.triu(same, 1).any(axis=(1, 2))
    return sub[keep], cells[parent[keep] // ns], side[keep]
