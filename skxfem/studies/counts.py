"""Count what a scene's solve meets without building it: nodes, cells, enriched nodes, cut edges.

The counts behind :mod:`skxfem.studies.budget` (whose notes say what each bounds).  A
:class:`~skxfem.scene.Box` is never built: ψ is evaluated on its grid in
slabs of about 10⁶ points; a mesh is counted from its arrays.

>>> from skxfem.scene import Box
>>> from skxfem.levelset import plane
>>> box_counts(Box(2, "quad"), plane((0, 0.4), (0, 1)))   # nodes, cells, enriched, cut edges
(9, 4, 6, 3)

A crack's branch functions go to the nodes near its front {ψ = 0, φ = 0}
(:mod:`skxfem.crack.radius`); :func:`box_front_nodes` and :func:`mesh_front_nodes` count
the nodes where √(ψ² + φ²) ≤ r, the distance to the front when ψ and φ measure the
distances to two crossing surfaces (as :mod:`skxfem.levelset`'s planes, spheres and
cylinders do; a level set that grows faster than the distance gives fewer nodes).

>>> box_front_nodes(Box(4, "tri"), plane((0, 0.5), (0, 1)), plane((0.5, 0), (1, 0)), 0.3)
5
"""
from __future__ import annotations

import itertools
import math
from collections.abc import Callable

import numpy as np

from ..fem.cells import CELL_TYPES
from ..levelset import nodal_values
from ..scene.model import Box

__all__ = ["box_counts", "box_size", "mesh_counts", "box_front_nodes", "mesh_front_nodes",
           "box_crack_depth", "mesh_crack_depth", "box_crack_counts", "mesh_crack_counts",
           "NVERTS", "PER_CUBE"]

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
        last = b == n[0]
        for e in _DIRECTIONS[self.box.cell]:
            s1 = tuple(slice(0, None if (k == 0 and last) else -1) if v == 0 and k == 0
                       else slice(None) if v == 0 else slice(0, -1) if v > 0 else slice(1, None)
                       for k, v in enumerate(e))
            s2 = tuple(slice(0, None if last else -1) if v == 0 and k == 0
                       else slice(None) if v == 0 else slice(1, None) if v > 0 else slice(0, -1)
                       for k, v in enumerate(e))
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


def box_front_nodes(box: Box, levelset, front, radius: float) -> int:
    """The nodes of a Box within ``radius`` of the front {ψ = 0, φ = 0} (√(ψ² + φ²) ≤
    ``radius``, module notes), slab by slab."""
    count = 0
    for a, b, x in _slabs(box):
        x = x if b == box.n[0] else x[:, :-1]             # each node once
        count += int(np.sum(np.hypot(_on(levelset, x), _on(front, x)) <= radius))
    return count


def mesh_front_nodes(mesh, levelset, front, radius: float) -> int:
    """The nodes of a built mesh within ``radius`` of the front (module notes).

    >>> from skfem import MeshTri1
    >>> from skxfem.levelset import plane
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 5), np.linspace(0, 1, 5))
    >>> mesh_front_nodes(m, plane((0, 0.5), (0, 1)), plane((0.5, 0), (1, 0)), 0.3)
    5
    """
    d = np.hypot(nodal_values(levelset, mesh), nodal_values(front, mesh))
    return int(np.sum(d <= radius))


def _depth(psi: np.ndarray, phi: np.ndarray, band: float) -> float:
    on = (np.abs(psi) <= band) & (phi < 0)
    return float(-phi[on].min()) if on.any() else 0.0


def box_crack_depth(box: Box, levelset, front, band: float) -> float:
    """A crack's depth (the largest distance from the crack to its front,
    :func:`skxfem.crack.space3d.crack_depth`) from a Box's nodes: the largest -φ over
    the nodes within ``band`` of ψ = 0 where φ < 0 (φ the distance behind the front, as
    module notes), slab by slab; 0 if there is none.

    >>> from skxfem.levelset import plane
    >>> box_crack_depth(Box(4, "tri"), plane((0, 0.5), (0, 1)), plane((0.5, 0), (1, 0)),
    ...                 0.3)
    0.5
    """
    return max((_depth(_on(levelset, x), _on(front, x), band) for _, _, x in _slabs(box)),
               default=0.0)


def mesh_crack_depth(mesh, levelset, front, band: float) -> float:
    """:func:`box_crack_depth` on a built mesh."""
    return _depth(nodal_values(levelset, mesh), nodal_values(front, mesh), band)


def box_crack_counts(box: Box, levelset, front, band: float,
                     radius: Callable[[float], float]) -> tuple[tuple, float, int]:
    """A crack's :func:`box_counts` of ψ, its :func:`box_crack_depth` (``band``) and its
    :func:`box_front_nodes` within ``radius(depth)`` of the front, ψ and φ evaluated once
    at each node: in one sweep over the slabs, the nodes' √(ψ² + φ²) kept until the
    depth is known, when the Box is one slab (about 10⁶ nodes: most boxes); a larger
    Box is swept again for its front nodes (:func:`box_front_nodes`), so that the
    guard stays small.

    >>> from skxfem.levelset import plane
    >>> box_crack_counts(Box(4, "tri"), plane((0, 0.5), (0, 1)), plane((0.5, 0), (1, 0)),
    ...                  0.3, lambda depth: 0.6 * depth)
    ((25, 32, 15, 30), 0.5, 5)
    """
    counter, depth, r = _BoxCounter(box), 0.0, None
    for a, b, x in _slabs(box):
        psi, phi = _on(levelset, x), _on(front, x)
        counter.add(a, b, psi)
        depth = max(depth, _depth(psi, phi, band))
        if a == 0 and b == box.n[0]:                      # one slab: every node
            r = np.hypot(psi, phi)
    R = radius(depth)
    near = int(np.sum(r <= R)) if r is not None else box_front_nodes(box, levelset, front, R)
    return counter.counts(), depth, near


def mesh_crack_counts(mesh, levelset, front, band: float,
                      radius: Callable[[float], float]) -> tuple[tuple, float, int]:
    """:func:`box_crack_counts` on a built mesh: :func:`mesh_counts`,
    :func:`mesh_crack_depth` and :func:`mesh_front_nodes`, ψ and φ evaluated once."""
    psi, phi = nodal_values(levelset, mesh), nodal_values(front, mesh)
    depth = _depth(psi, phi, band)
    return _mesh_counts(mesh, psi), depth, int(np.sum(np.hypot(psi, phi) <= radius(depth)))
