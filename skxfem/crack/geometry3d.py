r"""The geometry of a 3D crack on a tetrahedral mesh: split cells, front cells, the front.

The 3D twin of :mod:`skxfem.crack.geometry`.  The crack is {ψ = 0, φ < 0}, its front
{ψ = φ = 0} (:mod:`skxfem.crack.frame`); both level sets are interpolated at the nodes
of a ``MeshTet1`` and are linear in each tetrahedron, so that in a cell

* the zero set of ψ_h is a plane polygon (a triangle or a quadrilateral), whose
  vertices are the nodes where ψ_h = 0 and the points of the edges where ψ_h changes
  sign (nodal values within :data:`~skxfem.crack.geometry.ZERO` edge lengths of zero
  are set to zero);
* φ_h is linear on that polygon: the cell is a **front cell** if φ_h takes both signs
  (or vanishes, within :data:`~skxfem.crack.geometry.ZERO` h|∇φ_h|: a front along a
  face shared by two cells makes both front cells, whatever the round-off of φ_h
  interpolated along their edges) on it, the front crossing it along the segment
  {ψ_h = φ_h = 0}; a **split cell** if φ_h < 0 on the whole polygon (the crack crosses
  it completely, or runs along one of its faces: ψ_h = 0 at three nodes); else the
  crack does not reach it (ψ_h changes sign ahead of the front).

Sub-tetrahedra
--------------
Split and front cells are split by ψ_h (:func:`skxfem.fem.simplex.split`), the
sub-tetrahedra of front cells once more by φ_h, so that each holds one sign of ψ_h
and (in front cells) one of φ_h.  Such a sub-tetrahedron lies in a quarter wedge
around the front, which it therefore meets along one of its edges, at one vertex, or
not at all: ``sub_front`` counts its vertices on the front (2, 1, 0), which come first
in its vertex order (for the almost-polar rules of :mod:`skxfem.crack.quadrature3d`).
The crack's faces are the faces of the sub-tetrahedra of Ω⁻ on {ψ_h = 0} where
φ_h ≤ 0 (``faces``).

The front
---------
In each front cell the front is a segment, the line {ψ_h = φ_h = 0} clipped to the
cell (:func:`line_segments`, from the level sets, not from the cell's pieces, whose
slivers are dropped); the segments of the cells are chained into polylines
(:func:`front_chains`, ends closer than 1e-10 of the front's extent joined,
:func:`merged_points`): one open chain for a front that ends on the boundary (a
through-thickness front), a closed one for a penny, whatever the front's place among
the nodes.

>>> from skfem import MeshTet1
>>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 2, np.linspace(0, 1, 3))
>>> g = crack_geometry_3d(m, lambda x: x[1] - 0.5, lambda x: x[0] - 0.5)
>>> chains = front_chains(g)
>>> len(chains), np.round(chains[0][0][2], 12).tolist()   # x = y = 0.5, z from 0 to 1
(1, [0.0, 0.25, 0.5, 0.75, 1.0])
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import MeshTet1

from ..fem.simplex import split
from .geometry import (
    ZERO,
    check_mesh_type,
    crack_points,
    level_set_scales,
    level_set_values,
    nearest_on_segments,
)

__all__ = ["CrackGeometry3D", "crack_geometry_3d", "check_mesh_3d", "front_chains",
           "orthonormal_on_front", "orthonormal_at_nodes", "FAR", "front_fit",
           "front_offset",
           "barycentric", "shape_gradients", "cell_gradients", "projected_diameters", "runs",
           "line_segments", "merged_points", "chain_places",
           "VOLUME_TOL"]

VOLUME_TOL = 1e-12
"""Sub-tetrahedra below VOLUME_TOL times their cell's volume are dropped (zero-volume
pieces of a level set through a node or along an edge)."""

FAR = 0.1
"""The level sets pass for signed distances along the front while |∇ψ_h|, the part β of
|∇φ_h| normal to ∇ψ_h (each within FAR of 1) and ∇φ_h·∇ψ_h/|∇ψ_h|² (within FAR of 0)
are; beyond, they are mapped to them (:func:`orthonormal_on_front`, node by node if
need be: :func:`orthonormal_at_nodes`)."""

_EDGES = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))


def check_mesh_3d(mesh, name: str = "mesh"):
    """``mesh`` if it is a ``MeshTet1``, else a ValueError naming ``name``.

    >>> check_mesh_3d(MeshTet1()).nelements
    5
    """
    return check_mesh_type(mesh, (MeshTet1,), name,
                           "a MeshTet1 (3D cracks take linear tetrahedra)")


def nodal_level_set(name: str, value, mesh) -> np.ndarray:
    """Nodal values of a level set ``value`` (callable or one value per node), checked,
    with values within :data:`~skxfem.crack.geometry.ZERO` edge lengths of zero set to
    zero (:func:`skxfem.crack.geometry.level_set_values` along the tetrahedra's edges).

    >>> m = MeshTet1()
    >>> bool(np.allclose(nodal_level_set("psi", lambda x: x[2] - 0.5, m), m.p[2] - 0.5))
    True
    """
    return level_set_values(name, value, mesh, mesh.edges)


def runs(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The runs of equal consecutive ``keys`` (n, ...) (points of one cell, in the order
    of quadrature batches; a key of several entries, such as a cell's nodes, is equal
    when all are): the first index of each run and the run of each key (n,), so that
    ``keys[first][run]`` is ``keys``.  What is computed once per cell is computed once
    per run: as ``np.unique(keys, return_inverse=True)`` without its sort.

    >>> first, run = runs(np.array([4, 4, 2, 2, 2, 4]))
    >>> first.tolist(), run.tolist()
    ([0, 2, 5], [0, 0, 1, 1, 1, 2])
    """
    keys = np.asarray(keys)
    new = np.ones(len(keys), dtype=bool)
    change = keys[1:] != keys[:-1]
    new[1:] = change.any(axis=tuple(range(1, change.ndim))) if change.ndim > 1 else change
    return np.flatnonzero(new), np.cumsum(new) - 1


def shape_gradients(mesh, cells: np.ndarray) -> np.ndarray:
    """The gradients ∇λ (nc, 4, 3) of the P1 shape functions (the barycentric
    coordinates) of ``cells`` (nc,), constant in each: the rows of A⁻¹ for ∇λ₁..₃, A the
    matrix of the edge vectors V_i - V_0 in columns, and ∇λ₀ = -(∇λ₁ + ∇λ₂ + ∇λ₃).

    >>> shape_gradients(MeshTet1(), np.array([0])).sum(axis=1).round(12).tolist()
    [[0.0, 0.0, 0.0]]
    """
    P = mesh.p[:, mesh.t[:, cells]]                      # (3, 4, nc)
    A = np.transpose(P[:, 1:] - P[:, :1], (2, 0, 1))     # (nc, 3, 3) columns V_i - V_0
    Ainv = np.linalg.inv(A)                               # rows: ∇λ₁..₃
    return np.concatenate([-Ainv.sum(axis=1, keepdims=True), Ainv], axis=1)


def projected_diameters(x: np.ndarray, grad_phi: np.ndarray, grad_psi: np.ndarray
                        ) -> np.ndarray:
    """The diameter of each tetrahedron's corners ``x`` (n, 4, 3) projected on the plane
    normal to its front direction ∇φ × ∇ψ (``grad_phi``, ``grad_psi`` (n, 3)): its size
    across the front; NaN where ∇φ ∥ ∇ψ.

    >>> x = np.array([[[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 1]]], float)
    >>> projected_diameters(x, np.array([[1.0, 0, 0]]), np.array([[0, 0, 1.0]])).round(6)
    array([1.414214])
    """
    e3 = np.cross(grad_phi, grad_psi)
    norm = np.linalg.norm(e3, axis=1, keepdims=True)
    e3 = np.divide(e3, norm, out=np.full_like(e3, np.nan), where=norm > 0)
    x = x - np.einsum("nki,ni->nk", x, e3)[:, :, None] * e3[:, None]
    i, j = np.triu_indices(x.shape[1], 1)
    return np.linalg.norm(x[:, i] - x[:, j], axis=2).max(axis=1)


def cell_gradients(mesh, nodal: np.ndarray, cells: np.ndarray | None = None) -> np.ndarray:
    """∇ (3, nc) of the P1 interpolant of the nodal values ``nodal`` (nverts,) in each of
    ``cells`` (nc,; default all), constant in a cell: Σ_k nodal_k ∇λ_k
    (:func:`shape_gradients`).

    >>> m = MeshTet1()
    >>> cell_gradients(m, 2 * m.p[0] - m.p[2]).round(12)[:, 0].tolist()
    [2.0, 0.0, -1.0]
    """
    cells = np.arange(mesh.t.shape[1]) if cells is None else np.asarray(cells)
    return np.einsum("nk,nki->in", nodal[mesh.t[:, cells]].T, shape_gradients(mesh, cells))


def barycentric(mesh, cells: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Barycentric coordinates λ (n, 4) of points x (3, n) in their ``cells`` (n,) and
    the gradients ∇λ (n, 4, 3): the P1 shape functions and their gradients.

    >>> lam, dlam = barycentric(MeshTet1(), np.array([0]), np.array([[0.1], [0.2], [0.3]]))
    >>> bool(np.isclose(lam.sum(), 1.0)), bool(np.allclose(dlam.sum(axis=1), 0.0))
    (True, True)
    """
    cells = np.asarray(cells).ravel()
    if cells.size and np.all(cells[1:] >= cells[:-1]):   # sorted (quadrature batches):
        first, inv = runs(cells)                          # no sort needed
        uc = cells[first]
    else:
        uc, inv = np.unique(cells, return_inverse=True)  # one inverse per cell
    inv = inv.ravel()
    dlam = shape_gradients(mesh, uc)[inv]
    d = x - mesh.p[:, mesh.t[0, uc]][:, inv]              # (3, n) from V_0
    lam = np.empty((cells.size, 4))
    lam[:, 1:] = sum(dlam[:, 1:, j] * d[j][:, None] for j in range(3))
    lam[:, 0] = 1 - lam[:, 1:].sum(axis=1)
    return lam, dlam


@dataclass(frozen=True)
class CrackGeometry3D:
    """A 3D crack {ψ = 0, φ < 0} on a ``MeshTet1`` (module notes).

    Attributes
    ----------
    psi, phi : (nverts,) the nodal level sets as used (near-zero values set to 0).
    front_cells : (nf,) the cells whose closure meets the front.
    split_cells : (ns,) the other cells the crack crosses completely.
    side : (ncells,) -1 / +1 for cells of one side (the sign of the mean nodal ψ), 0 for
        split and front cells.
    sub : (nsub, 4, 3) sub-tetrahedra of the split and front cells, physical
        coordinates; ``sub_cell`` (nsub,), ``sub_side`` (nsub,) ±1; ``sub_front``
        (nsub,) how many of its vertices lie on the front (they come first).
    faces : (nface, 3, 3) the crack's faces: triangles of {ψ_h = 0, φ_h ≤ 0};
        ``face_cell`` (nface,), ``face_normal`` (3, nface) unit, into Ω⁺.
    segments : (2, 3, nseg) the front's segments [end, coordinate, segment], one per
        front cell it crosses with positive length; ``segment_cell`` (nseg,).

    The fields of a :class:`skxfem.cut.Cut`, in its names, for the crack kind of Γ
    (:mod:`skxfem.crack.kind3d`):

    edge_ids : (ne,) the mesh edges (``mesh.edges``) the crack crosses strictly (ψ changes
        sign, φ < 0 at the crossing), then -1 for each node on the crack behind its
        front that is a vertex of a face (:func:`skxfem.crack.geometry.crack_points`);
        ``edges`` (2, ne) their nodes ((v, v) for a node), ``points`` (3, ne) the
        crossings and nodes.
    enriched : the nodes of the split and front cells.
    facets : (3, nface) each face's vertices as indices into ``points``, -1 for a vertex
        that is none (on the front, inside a cell's face); ``facet_cell``, ``normals``,
        ``measures`` the faces' cells, normals, areas.
    """

    psi: np.ndarray
    phi: np.ndarray
    front_cells: np.ndarray
    split_cells: np.ndarray
    side: np.ndarray
    sub: np.ndarray
    sub_cell: np.ndarray
    sub_side: np.ndarray
    sub_front: np.ndarray
    faces: np.ndarray
    face_cell: np.ndarray
    face_normal: np.ndarray
    segments: np.ndarray
    segment_cell: np.ndarray
    edge_ids: np.ndarray
    edges: np.ndarray
    points: np.ndarray
    enriched: np.ndarray
    facets: np.ndarray

    @property
    def facet_cell(self) -> np.ndarray:
        """(nface,) the cell of each face (:class:`skxfem.cut.Cut`'s name)."""
        return self.face_cell

    @property
    def normals(self) -> np.ndarray:
        """(3, nface) the faces' unit normals into Ω⁺ (:class:`skxfem.cut.Cut`'s name)."""
        return self.face_normal

    @property
    def measures(self) -> np.ndarray:
        """(nface,) the faces' areas (:class:`skxfem.cut.Cut`'s name)."""
        return self.face_areas()

    @property
    def cells(self) -> np.ndarray:
        """Split and front cells, sorted: the cells integrated on sub-tetrahedra."""
        return np.union1d(self.split_cells, self.front_cells)

    @property
    def tip_cells(self) -> np.ndarray:
        """The front cells (the 2D name: :class:`skxfem.crack.geometry.CrackGeometry`)."""
        return self.front_cells

    @property
    def pieces(self) -> np.ndarray:
        """(nface, 3, 3) the crack's faces [face, vertex, coordinate] (``faces``), in the
        order of ``facets`` (whose -1 vertices they locate: on the front, at a node)."""
        return self.faces

    def face_areas(self) -> np.ndarray:
        """(nface,) the areas of the crack's faces."""
        F = self.faces
        return 0.5 * np.linalg.norm(np.cross(F[:, 1] - F[:, 0], F[:, 2] - F[:, 0]), axis=1)


def _polygon_phi(ps, ph):
    """min and max of φ_h on the polygon {ψ_h = 0} of each cell (ps, ph (n, 4)), and
    whether it has one."""
    vals = [np.where(ps[:, i] == 0, ph[:, i], np.nan) for i in range(4)]
    for a, b in _EDGES:
        strict = ps[:, a] * ps[:, b] < 0
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(strict, ps[:, a] / (ps[:, a] - ps[:, b]), 0.0)
        vals.append(np.where(strict, ph[:, a] + t * (ph[:, b] - ph[:, a]), np.nan))
    V = np.stack(vals, axis=1)
    has = ~np.isnan(V).all(axis=1)
    with np.errstate(all="ignore"):
        lo = np.where(has, np.nanmin(np.where(has[:, None], V, 0.0), axis=1), np.nan)
        hi = np.where(has, np.nanmax(np.where(has[:, None], V, 0.0), axis=1), np.nan)
    return lo, hi, has


def _values_at(mesh, cells, X, nodal):
    """A P1 nodal field at the vertices of sub-tetrahedra X (m, 4, 3) of ``cells`` (m,)."""
    m = X.shape[0]
    lam, _ = barycentric(mesh, np.repeat(cells, 4), X.reshape(-1, 3).T)
    return (lam * nodal[mesh.t[:, np.repeat(cells, 4)]].T).sum(axis=1).reshape(m, 4)


def _volumes(X):
    d = X[:, 1:] - X[:, :1]
    return np.abs(np.linalg.det(d)) / 6


def crack_geometry_3d(mesh, psi, phi, _remap: bool = False) -> CrackGeometry3D:
    """The :class:`CrackGeometry3D` of the crack {ψ = 0, φ < 0} on a tetrahedral mesh.

    Parameters
    ----------
    mesh : a ``MeshTet1``.
    psi : the level set of the crack's surface (callable or nodal values), Ω⁺ = {ψ > 0}.
    phi : the level set of the front (callable or nodal values), φ > 0 ahead.

    Raises
    ------
    ValueError
        A mesh that is not a MeshTet1 (``mesh``), NaN level sets (``psi``, ``phi``), a
        crack that meets no cell or has no front inside the body (``psi``, ``phi``), φ ≡ 0
        on ψ = 0 in a cell (``phi``).

    Examples
    --------
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 2, np.linspace(0, 1, 3))
    >>> g = crack_geometry_3d(m, lambda x: x[1] - 0.5, lambda x: x[0] - 0.5)
    >>> bool(np.isclose(g.face_areas().sum(), 0.5)), int(g.front_cells.size) > 0
    (True, True)
    """
    check_mesh_3d(mesh)
    psi = nodal_level_set("psi", psi, mesh)
    phi = nodal_level_set("phi", phi, mesh)
    t = mesh.t
    ps, ph = psi[t].T, phi[t].T                           # (nc, 4)
    if np.any((ps == 0).all(axis=1)):
        raise ValueError("psi vanishes on a whole cell: it must be zero on a surface only")
    lo, hi, has = _polygon_phi(ps, ph)
    flat = has & (lo == 0) & (hi == 0) & ((ps == 0).sum(axis=1) < 3)
    if np.any(flat & ((ps < 0).any(axis=1) & (ps > 0).any(axis=1))):
        raise ValueError("phi vanishes on psi = 0 in a whole cell: the level sets must "
                         "cross (∇φ not parallel to ∇ψ) at the front")
    # ψ_h = 0 on a part of positive area of the cell's closure: it changes sign in the
    # cell, or vanishes on a whole face (a crack along mesh faces)
    crossed = ((ps < 0).any(axis=1) & (ps > 0).any(axis=1)) | ((ps == 0).sum(axis=1) == 3)
    # φ_h at the polygon's vertices is interpolated along edges: a front along a face
    # shared by two cells gives 0 on one side and ±1e-17 on the other.  Within the
    # tolerance of a vertex on the front (ZERO h |∇φ_h|, below) both are front cells,
    # whose pieces then get the rules graded at the front
    h = np.ptp(mesh.p[:, t], axis=1).max(axis=0)          # (nc,) cell sizes
    gphi = cell_gradients(mesh, phi)
    near = ZERO * h * np.linalg.norm(gphi, axis=0)
    front = has & (lo <= near) & (hi >= -near)
    split_ = crossed & (hi < 0) & ~front
    if not np.any(crossed & (lo < 0)):
        raise ValueError(f"the crack {{psi = 0, phi < 0}} crosses no cell of the mesh (psi in "
                         f"[{psi.min():.3g}, {psi.max():.3g}], phi in [{phi.min():.3g}, "
                         f"{phi.max():.3g}] at the nodes): check psi and phi")
    if not np.any(front):
        raise ValueError("phi < 0 all over psi = 0 in the mesh: the crack has no front "
                         "inside the body: move the front (phi = 0) into the body, or, for a "
                         "surface that cuts the body through, leave the front out (an "
                         "interface of skxfem.cut)")
    front_cells, split_cells = np.flatnonzero(front), np.flatnonzero(split_)
    side = np.where(ps.mean(axis=1) < 0, -1, 1)
    side[front_cells] = 0
    side[split_cells] = 0

    cells = np.union1d(split_cells, front_cells)
    P = np.transpose(mesh.p[:, t[:, cells]], (2, 1, 0))   # (n, 4, 3)
    sub, parent, sub_side = split(P, ps[cells])
    sub_cell = cells[parent]
    vol = _volumes(P)
    keep = _volumes(sub) > VOLUME_TOL * vol[parent]
    sub, sub_cell, sub_side = sub[keep], sub_cell[keep], sub_side[keep]
    in_front = front[sub_cell]
    fs = _values_at(mesh, sub_cell[in_front], sub[in_front], phi)
    sub2, parent2, _ = split(sub[in_front], fs)
    c2 = sub_cell[in_front][parent2]
    keep2 = _volumes(sub2) > VOLUME_TOL * _volumes(mesh_cells(mesh, c2))
    sub = np.concatenate([sub[~in_front], sub2[keep2]])
    sub_side = np.concatenate([sub_side[~in_front], sub_side[in_front][parent2][keep2]])
    sub_cell = np.concatenate([sub_cell[~in_front], c2[keep2]])

    # the vertices on the front first, counted
    pv, fv = _values_at(mesh, sub_cell, sub, psi), _values_at(mesh, sub_cell, sub, phi)
    gpsi = cell_gradients(mesh, psi)
    tol = ZERO * h[sub_cell][:, None]
    on_psi = np.abs(pv) <= _vertex_tol(tol, gpsi, ps, sub_cell)
    tol_phi = _vertex_tol(tol, gphi, ph, sub_cell)
    on_phi = np.abs(fv) <= tol_phi
    on = on_psi & on_phi & front[sub_cell][:, None]
    order = np.argsort(~on, axis=1, kind="stable")
    sub = np.take_along_axis(sub, order[:, :, None], axis=1)
    on_psi, fv, on = (np.take_along_axis(a, order, axis=1) for a in (on_psi, fv, on))
    sub_front = np.minimum(on.sum(axis=1), 2)

    faces, face_cell = _faces(sub, sub_cell, sub_side, on_psi, fv, tol_phi)
    normal = gpsi[:, face_cell] / np.linalg.norm(gpsi[:, face_cell], axis=0)
    segments, segment_cell = _segments(h, mesh, psi, phi, front_cells)
    edge_ids, edges, points, facets = _cut_edges(mesh, psi, phi, faces, face_cell, h)
    mapped = orthonormal_on_front(gpsi[:, front_cells], gphi[:, front_cells], psi, phi)
    if mapped is None:                    # no one map along the front: node by node
        if not _remap:
            return crack_geometry_3d(mesh, *orthonormal_at_nodes(mesh, psi, phi),
                                     _remap=True)
        mapped = psi, phi
    psi, phi = mapped
    return CrackGeometry3D(psi, phi, front_cells, split_cells, side, sub, sub_cell,
                           sub_side, sub_front, faces, face_cell, normal, segments,
                           segment_cell, edge_ids, edges, points,
                           np.unique(t[:, cells]), facets)


def orthonormal_on_front(gpsi: np.ndarray, gphi: np.ndarray, psi: np.ndarray,
                         phi: np.ndarray, tol: float = 1e-2
                         ) -> tuple[np.ndarray, np.ndarray] | None:
    """The nodal level sets (ψ̂, φ̂) = (ψ/γ, (φ - c ψ)/β), the same crack, with gradients
    near orthonormal on the front: γ = |∇ψ_h|, c = ∇φ_h·∇ψ_h/γ², β = |∇φ_h - c∇ψ_h| in
    the front cells (``gpsi``, ``gphi``, (3, nf)), each taken where it is one number
    along the front (within ``tol``, its mean) and more than ``tol`` from 1 (γ, β) or 0
    (c); else left out (γ = β = 1, c = 0: a level set near a signed distance is kept
    as given).  The polar coordinates of the branch functions and the front cells'
    size (:func:`skxfem.crack.sif3d.front_sizes`) read φ and ψ as distances: with
    ψ = 10 (z - z₀) the sizes came out 5 × too large and no front point got K ('under a
    cell of room'), silently but for a warning.  As the 2D
    :func:`skxfem.crack.geometry.orthonormal_at_tips`.  None where the level sets are
    more than :data:`FAR` from signed distances somewhere along the front and one of
    γ, c, β is not one number along it: no one map fits
    (:func:`orthonormal_at_nodes` then maps them node by node).

    >>> g = np.array([[0.0], [0.0], [10.0]])
    >>> psi, phi = orthonormal_on_front(g, np.array([[1.0], [0.0], [5.0]]),
    ...                                 np.array([10.0, -10.0]), np.array([1.0, 2.0]))
    >>> psi.tolist(), phi.tolist()
    ([1.0, -1.0], [-4.0, 7.0])
    """
    gamma, c, beta = level_set_scales(gpsi, gphi)

    def one_number(v):
        return np.ptp(v) <= tol * max(abs(float(v.mean())), 1.0)

    def one(v, neutral):
        m = float(v.mean())
        return m if one_number(v) and abs(m - neutral) > tol else neutral

    near = (np.abs(gamma - 1).max(initial=0) <= FAR and np.abs(beta - 1).max(initial=0)
            <= FAR and np.abs(c).max(initial=0) <= FAR)
    if not near and not all(one_number(v) for v in (gamma, c, beta)):
        return None                               # far from distances, and no one map
    g, cc, b = one(gamma, 1.0), one(c, 0.0), one(beta, 1.0)
    return psi / g, (phi - cc * psi) / b


def orthonormal_at_nodes(mesh, psi: np.ndarray, phi: np.ndarray
                         ) -> tuple[np.ndarray, np.ndarray]:
    """The nodal level sets (ψᵢ/γᵢ, (φᵢ - cᵢψᵢ)/βᵢ) with γ, c, β of
    :func:`orthonormal_on_front` averaged at each node over its cells: the map node by
    node, where no one map fits along the front (an ellipse's implicit form
    (x/a)² + (y/b)² - 1, whose |∇φ| runs from 2/a to 2/b along it).  The crack moves by
    the change of the interpolants, O(h²) where γ, c, β are smooth; the geometry is then
    built again on these values (:func:`crack_geometry_3d`).  A node whose γ or β is under
    1e-6 of their median (∇ψ = 0, or ∇φ along ∇ψ, far from the front) takes the median.

    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 5),) * 3)
    >>> psi, phi = orthonormal_at_nodes(m, 3 * (m.p[2] - 0.5), m.p[0] ** 2 - 0.25)
    >>> bool(np.allclose(psi, m.p[2] - 0.5)), round(float(phi[m.p[0] == 0.5][0]), 12)
    (True, 0.0)
    """
    gamma, c, beta = level_set_scales(cell_gradients(mesh, psi), cell_gradients(mesh, phi))
    n, t = mesh.p.shape[1], mesh.t
    count = np.bincount(t.ravel(), minlength=n)

    def at_nodes(v):
        out = np.bincount(t.ravel(), weights=np.tile(v, t.shape[0]), minlength=n)
        return out / np.maximum(count, 1)

    g, cc, b = at_nodes(gamma), at_nodes(c), at_nodes(beta)
    for v in (g, b):
        mid = float(np.median(v))
        v[~(v > 1e-6 * mid)] = mid
    return psi / g, (phi - cc * psi) / b


def _cut_edges(mesh, psi, phi, faces, face_cell, h):
    """The points that carry the crack's multipliers
    (:func:`skxfem.crack.geometry.crack_points`): the crossings of the mesh edges the
    crack crosses strictly, then the nodes on the crack behind its front that are a
    vertex of a face.  Returns (edge_ids, edges (2, ne), points (3, ne), facets (3,
    nface)): each face's vertices as indices into the points (-1: neither)."""
    a, b = mesh.edges
    strict = psi[a] * psi[b] < 0
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(strict, psi[a] / (psi[a] - psi[b]), 0.0)
    # φ < 0 at the crossing beyond rounding: a crossing on the front (φ_h = -4e-17 where
    # the front runs through it) is a front point of its faces, not a multiplier's
    ids = np.flatnonzero(strict & (phi[a] + t * (phi[b] - phi[a])
                                   < -ZERO * np.abs(phi[b] - phi[a])))
    points = mesh.p[:, a[ids]] + t[ids] * (mesh.p[:, b[ids]] - mesh.p[:, a[ids]])
    return crack_points(mesh, mesh.edges, mesh.t2e, psi, phi, ids, points,
                        np.transpose(faces, (1, 2, 0)), face_cell, ZERO * h[face_cell])


def mesh_cells(mesh, cells: np.ndarray) -> np.ndarray:
    """The tetrahedra (n, 4, 3) of ``cells``."""
    return np.transpose(mesh.p[:, mesh.t[:, cells]], (2, 1, 0))


SLIVER = 1e-3
"""A vertex of a cell's pieces is on a level set's zero within ZERO h |∇f_h|
(:func:`crack_geometry_3d`), and within SLIVER times the least nonzero |f| at the
cell's nodes (:func:`_vertex_tol`)."""


def _vertex_tol(tol: np.ndarray, grad: np.ndarray, nodal: np.ndarray,
                sub_cell: np.ndarray) -> np.ndarray:
    """(n, 1) how close to zero a level set f's value at the vertices of pieces of cells
    ``sub_cell`` (n,) counts as zero: ``tol`` (n, 1) (ZERO h) times |∇f_h| (``grad``, (3,
    nc) per cell), and at most :data:`SLIVER` times the least nonzero |f| at the cell's
    nodes (``nodal`` (nc, 4)).

    The second bound matters where f is within a few ZERO h of zero at nodes without
    vanishing there (snapped, :data:`~skxfem.crack.geometry.ZERO`): a penny 1e-9 above
    the node plane z = 0 at h = 0.2 (5e-9 h) cut its cells into slivers 1e-9 thick, and
    the vertices the front's split put on their edges, a few 1e-10 from the crack's
    plane, counted as on it: faces inside the slivers were taken for crack faces, the
    crack's area 0.9657 for the polygon's 0.9302 (32 faces too many), and the exact
    state of the penny pressed shut gave K_I = 0.32 p√(πa) (on the node plane and 1e-7
    above it: 5e-3 and 2.6e-3).  Rounding leaves f at the vertices on its zero within
    1e-16 of the cell's |f|, far below both."""
    scale = np.linalg.norm(grad[:, sub_cell], axis=0)[:, None] * tol
    least = np.where(nodal != 0, np.abs(nodal), np.inf).min(axis=1)[sub_cell]
    return np.minimum(scale, SLIVER * least[:, None])


def _faces(sub, sub_cell, sub_side, on_psi, fv, tol_phi):
    """The faces of the Ω⁻ sub-tetrahedra lying on ψ_h = 0 (``on_psi`` at their
    vertices) with φ_h ≤ 0 there (``fv`` within ``tol_phi``, :func:`_vertex_tol`)."""
    out, cell = [], []
    minus = sub_side < 0
    for drop in range(4):                                 # the face opposite each vertex
        keep = [i for i in range(4) if i != drop]
        on = on_psi[:, keep].all(axis=1) & minus
        behind = (fv[:, keep] <= tol_phi).all(axis=1)
        pick = on & behind
        out.append(sub[pick][:, keep])
        cell.append(sub_cell[pick])
    F, c = np.concatenate(out), np.concatenate(cell)
    area = 0.5 * np.linalg.norm(np.cross(F[:, 1] - F[:, 0], F[:, 2] - F[:, 0]), axis=1)
    big = area > 0 if area.size == 0 else area > 1e-12 * area.max()
    return F[big], c[big]


def line_segments(mesh, psi: np.ndarray, phi: np.ndarray, cells: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The segment (2, 3, n) where the line {ψ_h = φ_h = 0} crosses each of ``cells``
    (n,), from the nodal level sets ``psi``, ``phi`` directly, and its length (n,; 0
    where it misses the cell or ∇ψ_h ∥ ∇φ_h): the point x₀ of the line nearest the
    cell's centroid, x₀ + t (∇ψ_h × ∇φ_h) clipped by the barycentric coordinates λ ≥ 0.

    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 3),) * 3)
    >>> psi, phi = m.p[2] - 0.3, m.p[0] - 0.2
    >>> ends, length = line_segments(m, psi, phi, np.arange(m.t.shape[1]))
    >>> round(float(length.sum()), 9)             # the front y in [0, 1] at x = 0.2
    1.0
    """
    cells = np.asarray(cells)
    P = mesh_cells(mesh, cells)                           # (n, 4, 3)
    c = P.mean(axis=1)
    gpsi, gphi = (cell_gradients(mesh, f, cells).T for f in (psi, phi))   # (n, 3)
    fpsi, fphi = psi[mesh.t[:, cells]].mean(axis=0), phi[mesh.t[:, cells]].mean(axis=0)
    d = np.cross(gpsi, gphi)
    det = (d * d).sum(axis=1)
    ok = det > 1e-24 * (gpsi * gpsi).sum(axis=1) * (gphi * gphi).sum(axis=1)
    det = np.where(ok, det, 1.0)
    pp, pf, ff = ((a * b).sum(axis=1) for a, b in ((gpsi, gpsi), (gpsi, gphi),
                                                   (gphi, gphi)))
    alpha = (-fpsi * ff + fphi * pf) / det                # x₀ = c + α∇ψ + β∇φ
    beta = (-fphi * pp + fpsi * pf) / det
    x0 = c + alpha[:, None] * gpsi + beta[:, None] * gphi
    G = shape_gradients(mesh, cells)                      # (n, 4, 3)
    a = 0.25 + np.einsum("nki,ni->nk", G, x0 - c)         # λ(x₀ + t d) = a + t b
    b = np.einsum("nki,ni->nk", G, d)
    slack = 1e-12                 # a front along a face or an edge: λ = 0 to round-off
    with np.errstate(divide="ignore", invalid="ignore"):
        bound = -(a + slack) / b                          # which faces bound the segment
        exact = -a / b                                    # and where
    rows = np.arange(len(cells))
    k_lo = np.where(b > 0, bound, -np.inf).argmax(axis=1)
    k_hi = np.where(b < 0, bound, np.inf).argmin(axis=1)
    ok &= (b[rows, k_lo] > 0) & (b[rows, k_hi] < 0)
    ok &= ~((b == 0) & (a < -slack)).any(axis=1) & (bound[rows, k_lo] <= bound[rows, k_hi])
    lo = np.where(ok, exact[rows, k_lo], 0.0)
    hi = np.where(ok, np.maximum(exact[rows, k_hi], lo), 0.0)
    ends = np.stack([x0 + lo[:, None] * d, x0 + hi[:, None] * d])      # (2, n, 3)
    return np.transpose(ends, (0, 2, 1)), (hi - lo) * np.sqrt(det) * ok


def _segments(h, mesh, psi, phi, front_cells):
    """The front segment of each front cell, from the level sets (:func:`line_segments`;
    the front is straight in a cell), if longer than ZERO h.  Taken before as the two
    farthest front vertices of the cell's pieces, it lost the part in pieces dropped as
    slivers (:data:`VOLUME_TOL`): a front 1e-6 and 1e-9 off two node planes (12³ cells)
    lost 1e-3 h of its length at every node, came in twelve chains and no point got K;
    a front 1e-7 off a node plane, tilted, three chains, none."""
    ends, length = line_segments(mesh, psi, phi, front_cells)
    found = length > ZERO * h[front_cells]
    if not found.any():
        return np.zeros((2, 3, 0)), np.zeros(0, int)
    segs, cells = np.transpose(ends[:, :, found], (2, 0, 1)), front_cells[found]
    # a segment along a face shared by two front cells counts once; those shorter than
    # the merging distance all stay: their ends join their neighbours' (front_chains)
    ids = np.sort(merged_points(segs.reshape(-1, 3)).reshape(-1, 2), axis=1)
    ids[ids[:, 0] == ids[:, 1], 1] = -1 - np.arange((ids[:, 0] == ids[:, 1]).sum())
    _, keep = np.unique(ids, axis=0, return_index=True)
    keep = np.sort(keep)
    return np.transpose(segs[keep], (1, 2, 0)), cells[keep]


def merged_points(pts: np.ndarray, tol: float = 1e-10) -> np.ndarray:
    """One id (n,) per point of ``pts`` (n, 3), shared by the points closer than ``tol``
    times the points' extent (and by their neighbours' neighbours): the front's
    segments' ends that are one point, computed in two cells.  Rounding to a grid of
    that size split such a pair (1e-13 apart) across a grid line: a front just off a
    node plane came in up to twelve chains (49 of 384 fronts near node planes).

    >>> merged_points(np.array([[0, 0, 0], [1, 0, 0], [1e-12, 0, 0], [1, 1e-13, 0]]))
    array([0, 1, 0, 1])
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree
    scale = float(np.ptp(pts, axis=0).max()) if len(pts) else 0.0
    pairs = cKDTree(pts).query_pairs(tol * (scale or 1.0), output_type="ndarray")
    n = len(pts)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, ids = connected_components(graph, directed=False)
    _, first = np.unique(ids, return_index=True)     # numbered in the points' row order
    rep = pts[first]
    order = np.empty_like(first)
    order[np.lexsort(rep.T[::-1])] = np.arange(first.size)
    return order[ids]


def front_chains(geometry: CrackGeometry3D) -> list[tuple[np.ndarray, bool]]:
    """The front as polylines: a list of (points (3, m), closed), the segments of the
    front cells chained end to end (a segment shared by two cells, along their common
    face, counts once).

    >>> from skfem import MeshTet1
    >>> m = MeshTet1.init_tensor(*(np.linspace(-1, 1, 9),) * 3)
    >>> g = crack_geometry_3d(m, lambda x: x[2] - 0.01,
    ...                       lambda x: np.sqrt(x[0] ** 2 + x[1] ** 2) - 0.6)
    >>> [(c[1], c[0].shape[1] > 8) for c in front_chains(g)]      # a closed loop
    [(True, True)]
    """
    S = geometry.segments
    if S.shape[2] == 0:
        return []
    pts = np.concatenate([S[0].T, S[1].T])                # (2 nseg, 3)
    ids = merged_points(pts)
    n = S.shape[2]
    a, b = ids[:n], ids[n:]
    edges = {tuple(sorted(e)) for e in zip(a.tolist(), b.tolist()) if e[0] != e[1]}
    where = {}
    for i, j in edges:
        where.setdefault(i, []).append(j)
        where.setdefault(j, []).append(i)
    coords = np.zeros((ids.max() + 1, 3))
    coords[ids] = pts
    seen, chains = set(), []
    starts = [v for v, nb in where.items() if len(nb) == 1] + list(where)
    for s in starts:                                      # ends first, then loops
        if s in seen:
            continue
        chain, prev, cur = [s], None, s
        seen.add(s)
        while True:
            nxt = [v for v in where[cur] if v != prev and v not in seen]
            if not nxt:
                break
            prev, cur = cur, nxt[0]
            chain.append(cur)
            seen.add(cur)
        closed = len(chain) > 2 and s in where[cur] and len(where[s]) == 2
        chains.append((coords[chain].T.copy(), closed))
    return chains


def chain_places(chain: np.ndarray, closed: bool, points: np.ndarray) -> tuple:
    """The nearest place on a chain (``chain`` (3, k), ``closed``) of each of ``points``
    (3, m): the chain's vertices (3, k or k + 1: a closed one's first again at its end),
    their arc lengths s, and each point's arc length, segment and distance (m,).

    >>> chain = np.array([[0.0, 1, 1], [0, 0, 1], [0, 0, 0]])          # an L, open
    >>> _, s, at, j, dist = chain_places(chain, False, np.array([[0.5], [0.2], [0.0]]))
    >>> s.tolist(), at.tolist(), j.tolist(), dist.round(12).tolist()
    ([0.0, 1.0, 2.0], [0.5], [0], [0.2])
    """
    pts = np.hstack([chain, chain[:, :1]]) if closed else chain
    seg = np.diff(pts, axis=1)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(seg, axis=0))])
    t, _, dist = nearest_on_segments(pts[:, :-1, None], seg[:, :, None], points[:, None])
    j = np.argmin(dist, axis=0)
    cols = np.arange(points.shape[1])
    return pts, s, s[j] + t[j, cols] * (s[j + 1] - s[j]), j, dist[j, cols]


def front_fit(geometry: CrackGeometry3D, points: np.ndarray, spacing: float,
              chains: list | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The unit tangents t (3, m) and the curvature vectors d²x/ds² (3, m) of the front
    at the places nearest to ``points`` (3, m): the front polyline sampled at 17 equal
    arcs over [s - d, s + d] (s the point's nearest place on its chain, d = ``spacing``;
    an open chain's ends clip them) and fitted by a parabola in s, least squares.  The
    fit smooths the kinks of the polyline (the chords of the P1 front cross the cells
    at any angle): t is its slope at the point's nearest place on the parabola (three
    Newton steps from s, within a segment's length of it: a point inside a curved front
    is as near two chords, and the nearest on the polyline jumped between them with
    round-off), in the direction of the chain's points; the curvature vector its second
    derivative normal to t, of size 1/ρ (ρ the radius of curvature) towards the centre,
    zero on a straight stretch.  ``chains``: the front's :func:`front_chains`, if they
    are at hand (default: built here).

    >>> from skfem import MeshTet1
    >>> m = MeshTet1.init_tensor(*(np.linspace(-1, 1, 13),) * 3)
    >>> g = crack_geometry_3d(m, lambda x: x[2] - 0.01,
    ...                       lambda x: np.sqrt(x[0] ** 2 + x[1] ** 2) - 0.6)
    >>> t, k = front_fit(g, np.array([[0.7], [0.0], [0.0]]), 0.3)
    >>> bool(abs(abs(t[1, 0]) - 1) < 0.01 and abs(k[0, 0] + 1 / 0.6) < 0.1)
    True
    """
    points = np.asarray(points, float)
    d = float(spacing)
    if not (np.isfinite(d) and d > 0):
        raise ValueError(f"spacing must be a positive number, got {spacing!r}")
    tangent, curvature = np.zeros(points.shape), np.zeros(points.shape)
    best = np.full(points.shape[1], np.inf)
    sigma = np.linspace(-1.0, 1.0, 17)
    for chain, closed in front_chains(geometry) if chains is None else chains:
        pts, s, at, j, dist = chain_places(chain, closed, points)
        total = s[-1]
        arcs = at[:, None] + min(d, total / 4) * sigma            # (m, 17)
        arcs = np.mod(arcs, total) if closed else np.clip(arcs, 0, total)
        x = np.stack([np.interp(arcs, s, pts[k]) for k in range(3)])   # (3, m, 17)
        z = (arcs - at[:, None] + total / 2) % total - total / 2 if closed else \
            arcs - at[:, None]
        V = np.stack([np.ones_like(z), z, z * z], axis=2)        # (m, 17, 3)
        c = np.linalg.solve(np.einsum("mqa,mqb->mab", V, V),
                            np.einsum("mqa,imq->mai", V, x))      # (m, 3 terms, 3)
        # the nearest place on the fitted curve x(z) = c₀ + c₁z + c₂z², not on the P1
        # polyline: a point inside a curved front is as near two chords symmetric about
        # it (the nearest segment jumped there with round-off, and with it the
        # tangent: a coarse penny's K moved 7e-4 when its polyline moved 1e-15)
        zc = np.zeros(points.shape[1])
        reach = np.diff(s)[j]                 # within a segment of the polyline's place
        for _ in range(3):                               # Newton on (x(z) - P)·x'(z) = 0
            r = c[:, 0] + zc[:, None] * c[:, 1] + zc[:, None] ** 2 * c[:, 2] - points.T
            dx = c[:, 1] + 2 * zc[:, None] * c[:, 2]
            f, df = (r * dx).sum(axis=1), (dx * dx).sum(axis=1) + 2 * (r * c[:, 2]).sum(axis=1)
            zc = np.clip(zc - f / np.where(df > 0, df, np.inf), -reach, reach)
        slope, second = (c[:, 1] + 2 * zc[:, None] * c[:, 2]).T, 2 * c[:, 2].T
        tt = (slope * slope).sum(axis=0)
        kvec = (second - (second * slope).sum(axis=0) / tt * slope) / tt
        near = dist < best
        tangent[:, near] = (slope / np.sqrt(tt))[:, near]
        curvature[:, near] = kvec[:, near]
        best = np.minimum(best, dist)
    return tangent, curvature


OFFSET_SAMPLES = 20
"""Points per mean segment length that :func:`front_offset` samples the front at."""


def front_offset(geometry: CrackGeometry3D,
                 points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The distance (n,) from ``points`` (3, n) to the front, the polyline of its
    segments (the P1 front {ψ_h = φ_h = 0}), and the unit vectors (3, n) from the
    nearest point of the front to each point (zero on the front).

    Unlike |φ_h|, whose gradient is that of the P1 interpolant of φ (on a curved front
    its size and direction change from cell to cell by up to h/ρ, ρ the radius of
    curvature), this is a distance: zero on the front, growing at unit rate away from
    it.  The nearest segment is looked for among those of the 4 nearest of points
    sampled along the front (:data:`OFFSET_SAMPLES` per mean segment length), the
    distance to it is exact.

    >>> from skfem import MeshTet1
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 4),) * 2, np.linspace(0, 1, 3))
    >>> g = crack_geometry_3d(m, lambda x: x[1] - 0.5, lambda x: x[0] - 0.5)
    >>> d, n = front_offset(g, np.array([[0.2, 0.5], [0.5, 0.9], [0.3, 0.5]]))
    >>> d.round(12).tolist(), n[:, 0].round(12).tolist()
    ([0.3, 0.4], [-1.0, 0.0, 0.0])
    """
    from scipy.spatial import cKDTree
    x = np.asarray(points, float)
    if x.ndim != 2 or x.shape[0] != 3:
        raise ValueError(f"points must have shape (3, n), got {x.shape}")
    A, B = geometry.segments[0], geometry.segments[1]
    if A.shape[1] == 0:
        raise ValueError("the geometry has no front (no segment {psi_h = phi_h = 0})")
    length = np.linalg.norm(B - A, axis=0)
    m = np.ceil(length / length.mean() * OFFSET_SAMPLES).astype(int) + 1
    seg = np.repeat(np.arange(A.shape[1]), m)
    t = (np.arange(seg.size) - np.repeat(np.cumsum(m) - m, m)) / np.repeat(m - 1, m)
    samples = A[:, seg] + t * (B - A)[:, seg]
    k = min(4, seg.size)
    cand = seg[cKDTree(samples.T).query(x.T, k=k)[1].reshape(x.shape[1], k)]
    # the nearest samples mostly lie on one or two segments: each segment of a row is
    # measured once, the first nearest kept (a repeat is never strictly nearer)
    best, c = np.full(x.shape[1], np.inf), np.full_like(x, np.nan)
    for j in range(k):
        rows = np.flatnonzero((cand[:, j, None] != cand[:, :j]).all(axis=1))
        s = cand[rows, j, None]                           # (n, 1) the segments
        _, cj, dj = nearest_on_segments(A[:, s], (B - A)[:, s], x[:, rows, None])
        nearer = dj[:, 0] < best[rows]
        rows = rows[nearer]
        best[rows], c[:, rows] = dj[nearer, 0], cj[:, nearer, 0]
    v = x - c
    return best, v / np.where(best > 0, best, 1.0)
