"""Count what a scene's solve meets without building it: nodes, cells, enriched nodes, cut edges.

The counts behind :mod:`skxfem.studies.budget` (whose notes say what each bounds).  A
:class:`~skxfem.scene.Box` is never built: ψ is evaluated on its grid in
slabs of about 10⁶ points; a mesh is counted from its arrays.

>>> from skxfem.scene import Box
>>> from skxfem.levelset import plane
>>> box_counts(Box(2, "quad"), plane((0, 0.4), (0, 1)))   # nodes, cells, enriched, cut edges
(9, 4, 6, 3)
"""
from __future__ import annotations

import itertools
import math

import numpy as np

from ..fem.cells import CELL_TYPES
from ..levelset import nodal_values
from ..scene.model import Box

__all__ = ["box_counts", "box_size", "mesh_counts", "NVERTS", "PER_CUBE"]

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


def box_counts(box: Box, levelset) -> tuple[int, int, int, int]:
    """Nodes, cells, enriched-node bound and cut-edge bound of a Box, slab by slab."""
    n = box.n
    size = box.size or (1.0,) * box.dim
    grid = [np.linspace(0.0, L, k + 1) for k, L in zip(n, size)]
    n_nodes, n_cells = box_size(box)
    layer = n_nodes // (n[0] + 1)
    step = max(1, _CHUNK // layer)
    carry = np.zeros([k + 1 for k in n[1:]], dtype=bool)
    enriched = edges = 0
    corners = list(itertools.product((0, 1), repeat=box.dim))
    for a in range(0, n[0], step):
        b = min(a + step, n[0])                           # cells a..b-1, nodes a..b
        x = np.stack(np.meshgrid(grid[0][a:b + 1], *grid[1:], indexing="ij"))
        psi = np.asarray(levelset(x.reshape(box.dim, -1)), dtype=float).reshape(x.shape[1:])
        s = np.sign(psi)
        cube = [s[tuple(slice(o, o + k) for o, k in zip(c, (b - a,) + n[1:]))]
                for c in corners]
        cut = (np.min(cube, axis=0) <= 0) & (np.max(cube, axis=0) >= 0)
        mask = np.zeros(s.shape, dtype=bool)
        mask[0] = carry
        for c in corners:
            mask[tuple(slice(o, o + k) for o, k in zip(c, (b - a,) + n[1:]))] |= cut
        enriched += int(mask[:-1].sum())
        carry = mask[-1]
        last = b == n[0]
        for e in _DIRECTIONS[box.cell]:
            s1 = tuple(slice(0, None if (k == 0 and last) else -1) if v == 0 and k == 0
                       else slice(None) if v == 0 else slice(0, -1) if v > 0 else slice(1, None)
                       for k, v in enumerate(e))
            s2 = tuple(slice(0, None if last else -1) if v == 0 and k == 0
                       else slice(None) if v == 0 else slice(1, None) if v > 0 else slice(0, -1)
                       for k, v in enumerate(e))
            edges += int(np.sum(s[s1] * s[s2] <= 0))
    return n_nodes, n_cells, enriched + int(carry.sum()), edges


def mesh_counts(mesh, levelset) -> tuple[int, int, int, int]:
    """Nodes, cells, enriched-node bound and cut edges of a built mesh."""
    s = np.sign(nodal_values(levelset, mesh))
    st = s[mesh.t]
    cut = (st.min(axis=0) <= 0) & (st.max(axis=0) >= 0)
    edges = mesh.facets if mesh.dim() == 2 else mesh.edges
    n_cut_edges = int(np.sum(s[edges[0]] * s[edges[1]] <= 0))
    return int(mesh.nvertices), int(mesh.nelements), int(np.unique(mesh.t[:, cut]).size), \
        n_cut_edges
