"""Count what a scene's solve meets without building it: nodes, cells, enriched nodes, cut edges.

The counts behind :mod:`skxfem.studies.budget` (whose notes say what each bounds).  A
:class:`~skxfem.scene.Box` is never built: ψ is evaluated on its grid in
slabs of about 10⁶ points; a mesh is counted from its arrays.

>>> from skxfem.scene import Box
>>> from skxfem.levelset import plane
>>> box_counts(Box(2, "quad"), plane((0, 0.4), (0, 1)))   # nodes, cells, enriched, cut edges
(9, 4, 6, 3)

A crack {ψ = 0, φ < 0} is counted as its solve builds it (:class:`CrackCounts`): its
multiplier points are its own cut points behind the front, not the whole surface ψ = 0;
its branch functions go to the nodes of the front's cells and those within r_e of the
front (:mod:`skxfem.crack.radius`, r_e from the crack's depth and the front cells' size,
found from ψ and φ as the space finds them), counted where √(ψ² + φ²) ≤ r_e, the distance
to the front when ψ and φ measure the distances to two crossing surfaces (as
:mod:`skxfem.levelset`'s planes, spheres and cylinders do; a level set that grows faster
than the distance gives fewer nodes).

>>> c = box_crack_counts(Box(4, "tri"), plane((0, 0.5), (0, 1)), plane((0.5, 0), (1, 0)),
...                      lambda depth, h: 0.3)
>>> c.branch, c.heaviside, c.points   # the front at a node: 4 squares around it
(9, 3, 2)
"""
from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..crack.geometry import ZERO
from ..crack.geometry3d import _polygon_phi, projected_diameters
from ..fem.cells import CELL_TYPES
from ..levelset import nodal_values
from ..scene.model import Box

__all__ = ["box_counts", "box_size", "mesh_counts", "CrackCounts", "box_crack_counts",
           "mesh_crack_counts", "NVERTS", "PER_CUBE", "KUHN", "FRONT_MARGIN"]

# vertices per cell, cells per hypercube of a Box, edge directions of a Box
NVERTS = {name: c.nverts for name, c in CELL_TYPES.items()}
PER_CUBE = {name: c.per_cube for name, c in CELL_TYPES.items()}
_AXES = {2: [(1, 0), (0, 1)], 3: [(1, 0, 0), (0, 1, 0), (0, 0, 1)]}
_DIAG2 = [(1, 1), (1, -1)]
_DIRECTIONS = {
    "tri": _AXES[2] + _DIAG2, "quad": _AXES[2], "hex": _AXES[3],
    "prism": _AXES[3] + [(0, 1, 1), (0, 1, -1)],
    "tet": [e for e in itertools.product((-1, 0, 1), repeat=3)
            if any(e) and e[next(i for i, v in enumerate(e) if v)] > 0],
}
_MESH_DIRECTIONS = {**_DIRECTIONS, "tri": _AXES[2] + [(1, 1)],
                    "tet": _AXES[3] + [(0, 1, 1), (1, 0, 1), (1, 1, 0), (1, 1, 1)]}
"""The edge directions :func:`skxfem.fem.meshes.box` builds (one diagonal of a square;
the Kuhn split of a cube, :data:`KUHN`): a crack's points are counted on them.  A plain
interface's bound counts :data:`_DIRECTIONS`, both diagonals."""
_CHUNK = 10**6


def box_size(box: Box) -> tuple[int, int]:
    """Nodes and cells of a Box, in exact integers (numpy's products wrap above 2⁶³).

    >>> box_size(Box(2, "tet")), box_size(Box(2**32, "tet"))[1]
    ((27, 48), 475368975085586025561263702016)
    """
    return (math.prod(k + 1 for k in box.n), PER_CUBE[box.cell] * math.prod(box.n))


def _slabs(box: Box):
    """The Box's nodes in slabs of about 10⁶: (a, b, x), x (dim, b - a + 1, ...) the
    nodes a..b along the first axis (those of the cell layers a..b - 1)."""
    n = box.n
    size = box.size or (1.0,) * box.dim
    grid = [np.linspace(0.0, L, k + 1) for k, L in zip(n, size)]
    step = max(1, _CHUNK // (box_size(box)[0] // (n[0] + 1)))
    for a in range(0, n[0], step):
        b = min(a + step, n[0])
        yield a, b, np.stack(np.meshgrid(grid[0][a:b + 1], *grid[1:], indexing="ij"))


def _on(levelset, x: np.ndarray) -> np.ndarray:
    """A level set at the points x (dim, ...), in x's shape without its first axis."""
    return np.asarray(levelset(x.reshape(x.shape[0], -1)), dtype=float).reshape(x.shape[1:])


def _edge_ends(box: Box, last: bool, directions=_DIRECTIONS):
    """For each edge direction of the Box's cells (``directions``), the slices (s1, s2) of
    a slab's nodes (:func:`_slabs`) at the two ends of its edges, each edge in one slab
    only (``last``: the slab holds the last node layer)."""
    for e in directions[box.cell]:
        yield (tuple(slice(0, None if (k == 0 and last) else -1) if v == 0 and k == 0
                     else slice(None) if v == 0 else slice(0, -1) if v > 0 else slice(1, None)
                     for k, v in enumerate(e)),
               tuple(slice(0, None if last else -1) if v == 0 and k == 0
                     else slice(None) if v == 0 else slice(1, None) if v > 0 else slice(0, -1)
                     for k, v in enumerate(e)))


class _BoxCounter:
    """The counts of :func:`box_counts`, added up slab by slab (:meth:`add`, the slabs in
    order) from ψ at the slab's nodes."""

    def __init__(self, box: Box):
        self.box, self.enriched, self.edges = box, 0, 0
        self.carry = np.zeros([k + 1 for k in box.n[1:]], dtype=bool)
        self.corners = list(itertools.product((0, 1), repeat=box.dim))

    def add(self, a: int, b: int, psi: np.ndarray) -> None:
        """The slab of cells a..b - 1, nodes a..b (:func:`_slabs`), ψ there."""
        n = self.box.n
        s = np.sign(psi)
        cube = [s[tuple(slice(o, o + k) for o, k in zip(c, (b - a,) + n[1:]))]
                for c in self.corners]
        cut = (np.min(cube, axis=0) <= 0) & (np.max(cube, axis=0) >= 0)
        mask = np.zeros(s.shape, dtype=bool)
        mask[0] = self.carry
        for c in self.corners:
            mask[tuple(slice(o, o + k) for o, k in zip(c, (b - a,) + n[1:]))] |= cut
        self.enriched += int(mask[:-1].sum())
        self.carry = mask[-1]
        for s1, s2 in _edge_ends(self.box, b == n[0]):
            self.edges += int(np.sum(s[s1] * s[s2] <= 0))

    def counts(self) -> tuple[int, int, int, int]:
        """Nodes, cells, enriched-node bound and cut-edge bound, once every slab is added."""
        return (*box_size(self.box), self.enriched + int(self.carry.sum()), self.edges)


def box_counts(box: Box, levelset) -> tuple[int, int, int, int]:
    """Nodes, cells, enriched-node bound and cut-edge bound of a Box, slab by slab."""
    counter = _BoxCounter(box)
    for a, b, x in _slabs(box):                           # cells a..b-1, nodes a..b
        counter.add(a, b, _on(levelset, x))
    return counter.counts()


def mesh_counts(mesh, levelset) -> tuple[int, int, int, int]:
    """Nodes, cells, enriched-node bound and cut edges of a built mesh."""
    return _mesh_counts(mesh, nodal_values(levelset, mesh))


def _mesh_counts(mesh, psi: np.ndarray) -> tuple[int, int, int, int]:
    """:func:`mesh_counts` from ψ at the nodes."""
    s = np.sign(psi)
    st = s[mesh.t]
    cut = (st.min(axis=0) <= 0) & (st.max(axis=0) >= 0)
    edges = mesh.facets if mesh.dim() == 2 else mesh.edges
    n_cut_edges = int(np.sum(s[edges[0]] * s[edges[1]] <= 0))
    return int(mesh.nvertices), int(mesh.nelements), int(np.unique(mesh.t[:, cut]).size), \
        n_cut_edges


FRONT_MARGIN = 0.1
"""The nodes within r_e + FRONT_MARGIN h of the front (h the front cells' size) count
as branch nodes: the space measures r_e from its P1 front, whose chords of a curved front
come closer to nodes inside the curve (the penny of radius 0.3 on 10³ tetrahedra: 34
branch nodes more than √(ψ² + φ²) ≤ r_e; 0.1 h was the least margin that bounded the
sweep's pennies, n = 6-12, at mid-cell and node planes)."""

KUHN = ((0, 2, 3, 7), (0, 2, 6, 7), (0, 4, 6, 7), (0, 1, 3, 7), (0, 4, 5, 7), (0, 1, 5, 7))
"""The six tetrahedra of a cube of a tetrahedral Box (scikit-fem's ``init_tensor``), as
indices into its corners in ``itertools.product((0, 1), repeat=3)`` order."""


@dataclass(frozen=True)
class CrackCounts:
    """What the space and the multipliers of a crack {ψ = 0, φ < 0} hold, counted from ψ
    and φ at the nodes (:func:`box_crack_counts`, :func:`mesh_crack_counts`).

    ``nodes``, ``cells``: the mesh's.  ``crack_nodes``: the corners of the *crack cells*,
    the cells (of a Box: its squares or cubes, which hold its cells) on which ψ takes both
    signs or vanishes and φ is negative at a corner or takes both signs: the Heaviside and
    front nodes are among them, and the unknowns whose jump across the crack B reads are
    theirs (``dim`` per node: H and the one branch function that jumps, √r sin θ/2).
    ``front_nodes``: the corners of the crack cells on which φ takes both signs or
    vanishes (the front cells' nodes are among them).  ``points``: the multiplier points
    (:func:`skxfem.crack.geometry.crack_points`): the edges on which ψ changes sign
    strictly with φ < 0 at the crossing, and the nodes with ψ = 0, φ < 0.  ``depth``: the
    largest -φ at a crack node, a bound of the crack's depth
    (:func:`skxfem.crack.space3d.crack_depth`).  ``front_size``: h as the crack's space
    takes it (:mod:`skxfem.crack.radius`): in 2D the largest extent of a cell the front
    may cross, in 3D the mean over the front tetrahedra of the largest √(ψ² + φ²) at
    their nodes.  ``radius``: r_e (``None``: topological enrichment).  ``branch``: the
    nodes within r_e of the front (√(ψ² + φ²) ≤ r_e + :data:`FRONT_MARGIN` h: module
    notes) or among the front nodes,
    4 dim unknowns each; ``heaviside``: the other crack nodes, dim each.
    """

    nodes: int
    cells: int
    crack_nodes: int
    front_nodes: int
    points: int
    depth: float
    front_size: float
    radius: float | None
    branch: int
    heaviside: int


def _polygon_front(ps: np.ndarray, ph: np.ndarray) -> np.ndarray:
    """Which tetrahedra (ψ, φ at their nodes: ps, ph (n, 4)) hold a point of the front:
    φ_h takes both signs or comes within round-off of zero (:data:`ZERO` of its range
    over the cell) on their polygon {ψ_h = 0}, as
    :func:`skxfem.crack.geometry3d.crack_geometry_3d`'s front cells."""
    lo, hi, has = _polygon_phi(ps, ph)
    near = ZERO * np.ptp(ph, axis=1)
    return has & (lo <= near) & (hi >= -near)


def _cross_section(x: np.ndarray, ps: np.ndarray, ph: np.ndarray) -> float:
    """The mean size across the front of tetrahedra with corners ``x`` (n, 4, 3), ψ ``ps``
    and φ ``ph`` (n, 4) there, as :func:`skxfem.crack.space3d.cross_section` takes it:
    the diameter of the corners projected on the plane normal to ∇φ × ∇ψ."""
    E = x[:, 1:] - x[:, :1]                                            # (n, 3, 3) edges
    g = [np.linalg.solve(E, (v[:, 1:] - v[:, :1])[:, :, None])[:, :, 0] for v in (ph, ps)]
    d = projected_diameters(x, *g)
    return float(np.hypot(ps, ph).max(axis=1).mean() if np.isnan(d).all() else np.nanmean(d))


def _tally(n_nodes: int, n_cells: int, ids, ps, ph, tets, extent: float,
           count_near: Callable[[float], int], radius, corners=None) -> CrackCounts:
    """:class:`CrackCounts` from the cells on which ψ takes both signs or vanishes: their
    corners' node ``ids`` (nc, k), ψ ``ps`` and φ ``ph`` there; ``tets``: the
    tetrahedra of a cell as corner indices (None in 2D, and for 3D cells that are no
    tetrahedra, which 3D cracks refuse), ``extent`` the largest extent of a cell (h
    where ``tets`` is None), ``count_near(r)`` the nodes with √(ψ² + φ²) ≤ r,
    ``radius(depth, h)`` r_e or None and ``corners`` (k, nc or 1, 3) the cells' corners
    (with ``tets``: h, the front tetrahedra's :func:`_cross_section`)."""
    front = (ph.min(axis=0) <= 0) & (ph.max(axis=0) >= 0)
    crack = front | (ph.min(axis=0) < 0)
    node, first = np.unique(ids[:, crack], return_index=True)
    psi_n, phi_n = ps[:, crack].ravel()[first], ph[:, crack].ravel()[first]
    depth = float(max(-phi_n.min(initial=0.0), 0.0))
    at_front = np.isin(node, ids[:, front])
    if tets is None:
        h = float(extent)
    else:                                                 # the front tetrahedra
        t = np.asarray(tets)
        tp = np.moveaxis(ps[:, front][t], 2, 0).reshape(-1, 4)
        tf = np.moveaxis(ph[:, front][t], 2, 0).reshape(-1, 4)
        on = _polygon_front(tp, tf)
        xc = np.broadcast_to(corners, (corners.shape[0], ps.shape[1], 3))[:, front]
        x = np.moveaxis(xc[t], 2, 0).reshape(-1, 4, 3)
        h = _cross_section(x[on], tp[on], tf[on]) if on.any() else extent
    r = radius(depth, h)
    reach = None if r is None else r + FRONT_MARGIN * h
    d = np.hypot(psi_n, phi_n)
    far = np.ones(node.size, dtype=bool) if r is None else d > reach
    near = 0 if r is None else count_near(reach)
    branch = near + int(np.sum(at_front & far))
    return CrackCounts(n_nodes, n_cells, int(node.size), int(at_front.sum()), 0, depth, h,
                       r, branch, int(np.sum(far & ~at_front)))


def _crossings(pa, pb, fa, fb) -> int:
    """The edges (ψ and φ at their ends: pa, pb, fa, fb) that ψ crosses strictly with
    φ < 0 at the crossing (:func:`skxfem.crack.geometry.crack_points`)."""
    strict = pa * pb < 0
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(strict, pa / np.where(strict, pa - pb, 1.0), 0.0)
    return int(np.sum(strict & (fa + t * (fb - fa) < 0)))


def box_crack_counts(box: Box, levelset, front, radius: Callable) -> CrackCounts:
    """The :class:`CrackCounts` of a crack {ψ = 0, φ < 0} on a Box, slab by slab, ψ and φ
    evaluated once at each node when the Box is one slab (about 10⁶ nodes: most boxes; a
    larger Box is swept again for the nodes near its front, so that the guard stays
    small).  ``radius(depth, h)``: r_e from the crack's depth and the front cells' size,
    or None (topological enrichment).

    >>> from skxfem.levelset import plane
    >>> c = box_crack_counts(Box(4, "tri"), plane((0, 0.5), (0, 1)),
    ...                      plane((0.5, 0), (1, 0)), lambda depth, h: 0.3)
    >>> c.points, c.crack_nodes, c.front_nodes, c.branch, c.heaviside, c.depth
    (2, 12, 9, 9, 3, 0.5)
    """
    n, dim = box.n, box.dim
    corners = list(itertools.product((0, 1), repeat=dim))
    strides = np.array([math.prod(k + 1 for k in n[d + 1:]) for d in range(dim)])
    offsets = np.array(corners) @ strides
    ids, ps, ph, points, kept = [], [], [], 0, None
    for a, b, x in _slabs(box):
        psi, phi = _on(levelset, x), _on(front, x)
        shape = (b - a,) + n[1:]
        at = [tuple(slice(o, o + k) for o, k in zip(c, shape)) for c in corners]
        P = np.stack([psi[s] for s in at])
        cut = np.nonzero((P.min(axis=0) <= 0) & (P.max(axis=0) >= 0))
        ids.append((cut[0] + a) * strides[0] + sum(i * s for i, s in zip(cut[1:],
                                                                          strides[1:]))
                   + offsets[:, None])
        ps.append(P[(slice(None),) + cut])
        ph.append(np.stack([phi[tuple(i + o for i, o in zip(cut, c))] for c in corners]))
        last = b == n[0]
        for s1, s2 in _edge_ends(box, last, _MESH_DIRECTIONS):
            points += _crossings(psi[s1], psi[s2], phi[s1], phi[s2])
        own = slice(None) if last else slice(0, -1)      # each node once
        points += int(np.sum((psi[own] == 0) & (phi[own] < 0)))
        if a == 0 and last:                              # one slab: every node
            kept = np.hypot(psi, phi)
    size = box.size or (1.0,) * dim

    def count_near(r):
        if kept is not None:
            return int(np.sum(kept <= r))
        return sum(int(np.sum(np.hypot(_on(levelset, x), _on(front, x))
                              [slice(None) if b == n[0] else slice(0, -1)] <= r))
                   for a, b, x in _slabs(box))

    tets = KUHN if box.cell == "tet" else None
    spacing = np.array([L / k for L, k in zip(size, n)])
    c = _tally(*box_size(box), np.hstack(ids), np.hstack(ps), np.hstack(ph), tets,
               float(spacing.max()), count_near, radius,
               (np.array(corners) * spacing)[:, None])
    return dataclasses.replace(c, points=points)


def mesh_crack_counts(mesh, levelset, front, radius: Callable) -> CrackCounts:
    """:func:`box_crack_counts` on a built mesh (its cells themselves; 3D: tetrahedra),
    ψ and φ evaluated once at each node."""
    psi, phi = nodal_values(levelset, mesh), nodal_values(front, mesh)
    t = mesh.t
    cut = (psi[t].min(axis=0) <= 0) & (psi[t].max(axis=0) >= 0)
    edges = mesh.facets if mesh.dim() == 2 else mesh.edges
    a, b = edges
    points = _crossings(psi[a], psi[b], phi[a], phi[b]) + int(np.sum((psi == 0) & (phi < 0)))
    tip = cut & (phi[t].min(axis=0) <= 0) & (phi[t].max(axis=0) >= 0)
    extent = float(np.ptp(mesh.p[:, t[:, tip if tip.any() else slice(None)]],
                          axis=1).max())              # no front cell: the solve refuses
    d = np.hypot(psi, phi)
    tets = ((0, 1, 2, 3),) if mesh.dim() == 3 and t.shape[0] == 4 else None   # 3D: tets
    c = _tally(int(mesh.nvertices), int(mesh.nelements), t[:, cut], psi[t[:, cut]],
               phi[t[:, cut]], tets, extent, lambda r: int(np.sum(d <= r)), radius,
               np.moveaxis(mesh.p[:, t[:, cut]], 0, 2))
    return dataclasses.replace(c, points=points)
