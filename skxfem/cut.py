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
z = 10 on a 20-cell mesh) belongs to no side, and its edges are not strictly
cut.  As production X-FEM codes do, the nodal values are *snapped*
(:func:`snap`): a vertex closer to Γ than :data:`SNAP` times its shortest edge,
the distance measured as |ψ_i| over the steepest slope of ψ along its edges
(so that the test does not depend on the scale of ψ), is moved to that
distance on its own side (Ω⁺ where ψ_i = 0), with one :class:`SnapWarning`
giving the count and the largest shift.  The interface then passes
:data:`SNAP` edge lengths from those vertices: the answer is that of the scene
with Γ shifted by as much.  A cell whose cut edges do not form one polygon (a
saddle) is refused: refine the mesh.

>>> from skfem import MeshQuad1
>>> from skxfem.levelset import plane
>>> from skxfem.cut import cut as cut_mesh
>>> cut = cut_mesh(MeshQuad1().refined(1), plane((0, 0.4), (0, 1)))
>>> cut.points.shape, round(float(cut.measures.sum()), 12)
((2, 3), 1.0)
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .fem.cells import cell_edges, faces_of_edges, reference_simplices
from .fem.meshes import cell_name
from .fem.simplex import edge_point, split
from .levelset import nodal_values

__all__ = ["Cut", "cut", "strictly_cut_edges", "snap", "SNAP", "SnapWarning", "check_apart",
           "rescaled", "PSI_RANGE", "PSI_FLOOR"]

SNAP = 1e-9
"""Vertices closer to Γ than SNAP times their shortest edge are moved to that
distance (:func:`snap`)."""


class SnapWarning(UserWarning):
    """Vertices on (or within :data:`SNAP` edge lengths of) Γ were moved off it."""


@dataclass(frozen=True)
class Cut:
    """The geometry of a mesh cut by a level set (all arrays, no mesh copy).

    Attributes
    ----------
    psi : (nverts,) nodal level set values.
    edge_ids : (ne,) indices of the strictly cut edges S_e among the mesh edges
        (``mesh.edges`` in 3D, ``mesh.facets`` in 2D).
    edges : (2, ne) their vertices.
    points : (dim, ne) intersection points: one multiplier each.
    cells : (ncut,) cut cells.  ``side`` : (ncells,) -1 / +1 for cells in
        Ω⁻ / Ω⁺, 0 for cut cells.
    enriched : (nenr,) nodes of cut cells, which carry Heaviside dofs.
    facets : (dim, nf) interface facets as indices into ``points``
        (segments in 2D, triangles in 3D); ``facet_cell`` : (nf,) parent cell;
        ``facet_ref`` : (dim, dim, nf) their vertices in the parent's
        reference coordinates, ``[vertex, coordinate, facet]``;
        ``normals`` : (dim, nf) unit normals into Ω⁺; ``measures`` : (nf,).
    sub_ref : (nsub, dim + 1, dim) sub-simplices in parent reference
        coordinates; ``sub_cell`` : (nsub,) parent; ``sub_side`` : (nsub,) ±1.
    """

    psi: np.ndarray
    edge_ids: np.ndarray
    edges: np.ndarray
    points: np.ndarray
    cells: np.ndarray
    side: np.ndarray
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


def snap(mesh, psi: np.ndarray, edges: np.ndarray | None = None):
    """ψ with the vertices within :data:`SNAP` edge lengths of Γ moved off it.

    The distance of vertex i to Γ is taken as |ψ_i| / g_i, g_i the steepest
    slope |ψ_j - ψ_i| / |x_j - x_i| over its edges; a vertex with d_i < SNAP h_i
    (h_i its shortest edge) gets ψ_i = ±SNAP h_i g_i, the sign of ψ_i (+ where
    ψ_i = 0).  ``edges`` (2, n_edges): the mesh edges (default: computed).

    Returns
    -------
    psi, moved, shift
        The snapped values, the number of vertices moved and the largest
        distance moved.

    Raises
    ------
    ValueError
        ψ vanishes at a vertex and along all of its edges (ψ ≡ 0 around it).

    >>> from skfem import MeshQuad1
    >>> m = MeshQuad1().refined(1)                    # vertices at y = 0, 0.5, 1
    >>> psi, moved, shift = snap(m, m.p[1] - 0.5)     # Γ through a row of vertices
    >>> moved, float(psi[m.p[1] == 0.5].min()) > 0, shift <= SNAP * 0.5
    (3, True, True)
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
    near = distance < SNAP * h
    if not near.any():
        return psi, 0, 0.0
    out = psi.copy()
    out[near] = np.where(psi[near] < 0, -1.0, 1.0) * SNAP * h[near] * g[near]
    shift = float(np.max(SNAP * h[near] - distance[near]))
    return out, int(near.sum()), shift


def cut(mesh, psi, name: str = "") -> Cut:
    """Cut ``mesh`` by the level set ``psi`` (a callable or nodal values).

    Parameters
    ----------
    mesh
        ``MeshTri1``, ``MeshQuad1``, ``MeshTet1``, ``MeshHex1`` or ``MeshWedge1``.
    psi
        A level set callable (see :mod:`skxfem.levelset`) or its nodal values.
    name
        What the :class:`SnapWarning` calls the interface (a scene with several:
        ``"interfaces[1] 'y - 0.7'"``); ``""``: "the level set".

    Raises
    ------
    ValueError
        If the level set cuts no cell, vanishes on a region, or cuts a cell
        in more than one piece.  Vertices on Γ are snapped (:func:`snap`).
    """
    if callable(psi):
        psi = nodal_values(psi, mesh)
    psi = np.asarray(psi, dtype=float)
    if psi.shape != (mesh.p.shape[1],) or not np.all(np.isfinite(psi)):
        raise ValueError(f"psi must hold one finite value per vertex, shape "
                         f"({mesh.p.shape[1]},); got shape {psi.shape}")
    psi = rescaled(psi, name)
    local, t2e, all_edges = cell_edges(mesh)
    given = psi
    psi, moved, shift = snap(mesh, psi, all_edges)
    if moved:
        _check_crosses(mesh, given, psi != given, name)
    if moved:
        warnings.warn(
            f"{name or 'the level set'} passes within {SNAP:g} edge lengths of {moved} mesh "
            f"vertices: "
            f"moved them off it by up to {shift:.1e} (to the side psi > 0 where psi = 0), "
            f"so Γ moves by as much (skxfem.cut.SNAP)", SnapWarning, stacklevel=2)

    edge_ids, points = strictly_cut_edges(all_edges, psi, mesh.p)
    if edge_ids.size == 0:
        raise ValueError(
            f"the level set cuts no cell of the mesh (psi ranges over "
            f"[{psi.min():.3g}, {psi.max():.3g}] at the nodes, one sign at all of them): "
            f"move the interface inside the domain, or, if it is there but inside a "
            f"single cell (smaller than the mesh size), refine the mesh")
    edges = all_edges[:, edge_ids]
    is_cut = np.zeros(all_edges.shape[1], dtype=bool)
    is_cut[edge_ids] = True
    cut_index = np.full(all_edges.shape[1], -1)
    cut_index[edge_ids] = np.arange(edge_ids.size)

    # cut cells, sides, enriched nodes
    cell_cut = is_cut[t2e]  # (nle, ncells)
    cells = np.flatnonzero(cell_cut.any(axis=0))
    side = np.where(psi[mesh.t].mean(axis=0) < 0, -1, 1)
    side[cells] = 0
    enriched = np.unique(mesh.t[:, cells])

    facets, facet_cell, facet_ref = _interface(mesh, psi, local, cut_index[t2e[:, cells]],
                                               cells, faces_of_edges(mesh, local))
    normals, measures = _facet_geometry(mesh, facet_ref, facet_cell, psi)
    sub_ref, sub_cell, sub_side = _subcells(mesh, psi, cells)
    return Cut(psi, edge_ids, edges, points, cells, side, enriched, facets, facet_cell,
               facet_ref, normals, measures, sub_ref, sub_cell, sub_side)


def _check_crosses(mesh, psi: np.ndarray, near: np.ndarray, name: str) -> None:
    """Refuse a level set that vanishes (within :data:`SNAP`) at the vertices ``near``
    and has one sign at all the others: Γ lies on the boundary of the body (or touches
    it from outside), and snapping would make it a sliver of one side or no cut at all,
    depending on the sign of ψ (module notes)."""
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
    """Reference coordinates (ncut, nle, dim) of each local edge's cut point."""
    ref = mesh.elem().doflocs
    pv = psi[mesh.t[:, cells]].T  # (ncut, nverts)
    a, b = local[:, 0], local[:, 1]
    with np.errstate(divide="ignore", invalid="ignore"):  # uncut edges: unused values
        return edge_point(ref[a][None], ref[b][None], pv[:, a], pv[:, b])


def _interface(mesh, psi, local, cut_ids, cells, share_face):
    """Order each cut cell's intersection points into a polygon and fan it."""
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
            neg = pv < 0
            m = (neg @ ref) / neg.sum(1, keepdims=True)
            p = (~neg @ ref) / (~neg).sum(1, keepdims=True)
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
    return (np.concatenate(facets, axis=1), np.concatenate(facet_cell),
            np.concatenate(facet_ref, axis=2))


def _facet_geometry(mesh, facet_ref, facet_cell, psi):
    """Unit normals (into Ω⁺) and measures of the (affinely mapped) facets."""
    mapping = mesh.mapping()
    x = mapping.F(np.transpose(facet_ref, (1, 2, 0)), tind=facet_cell)  # (dim, nf, nv)
    t = x[:, :, 1:] - x[:, :, :1]
    if mesh.dim() == 2:
        n = np.array([t[1, :, 0], -t[0, :, 0]])
    else:
        n = np.cross(t[:, :, 0].T, t[:, :, 1].T).T / 2.0
    measures = np.linalg.norm(n, axis=0)
    n = n / measures
    # orient from Ω⁻ to Ω⁺: compare with the vertex centroids of the parent cell
    pv = psi[mesh.t[:, facet_cell]]
    xc = mesh.p[:, mesh.t[:, facet_cell]]  # (dim, nverts, nf)
    w_plus, w_minus = (pv > 0), (pv < 0)
    direction = ((xc * w_plus).sum(1) / w_plus.sum(0) - (xc * w_minus).sum(1) / w_minus.sum(0))
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
    return sub, cells[parent // ns], side
