"""VTK cells for the VTU files: positively oriented, one piece of mesh per side of Γ
(per region, with several interfaces).

Shared by the writers of :mod:`skxfem.app.io`.
VTU vectors are ``(n, 3)``: 2D vectors get a zero z component.

>>> pad3(np.array([[1.0, 2.0]])).tolist()
[[1.0, 2.0, 0.0]]
"""
from __future__ import annotations

import numpy as np
from skfem.io.meshio import to_meshio

__all__ = ["cell_sides", "vtk_cells", "side_pieces", "region_pieces", "pad3", "vectors3"]

# VTK wants cells positively oriented: the simplex of these corners has det > 0
# (a wedge's face (0, 1, 2) has its right-hand normal pointing *away* from (3, 4, 5));
# scikit-fem allows either orientation, so mirrored cells get their nodes flipped.
_CORNERS = {"triangle": [0, 1, 2], "quad": [0, 1, 3], "tetra": [0, 1, 2, 3],
            "hexahedron": [0, 1, 3, 4], "wedge": [0, 2, 1, 3]}
_FLIP = {"triangle": [0, 2, 1], "quad": [0, 3, 2, 1], "tetra": [0, 2, 1, 3],
         "hexahedron": [0, 3, 2, 1, 4, 7, 6, 5], "wedge": [0, 2, 1, 3, 5, 4]}


def pad3(a: np.ndarray) -> np.ndarray:
    """(n, dim) → (n, 3) with zero z in 2D."""
    return np.hstack([a, np.zeros((a.shape[0], 3 - a.shape[1]))])


def vectors3(a: np.ndarray) -> np.ndarray:
    """(dim, n) → (n, 3), padding 2D vectors with a zero z component."""
    a = np.asarray(a, dtype=float)
    return np.vstack([a, np.zeros((3 - a.shape[0], a.shape[1]))]).T


def cell_sides(mesh, psi_nodes: np.ndarray) -> np.ndarray:
    """-1 for cells in Ω⁻, +1 in Ω⁺, 0 for cells with vertices on both sides.

    >>> from skfem import MeshTri1                # cells (0, 1, 2) and (1, 3, 2)
    >>> cell_sides(MeshTri1(), np.array([-1.5, -0.5, -0.5, 0.5])).tolist()
    [-1, 0]
    """
    psi = psi_nodes[mesh.t]
    cut = (psi.min(axis=0) < 0) & (psi.max(axis=0) > 0)
    return np.where(cut, 0, np.sign(psi.mean(axis=0))).astype(np.int64)


def vtk_cells(mesh) -> tuple[str, np.ndarray]:
    """The meshio cell type and the (ncells, nverts) cells, positively oriented for VTK.

    The node order is scikit-fem's ``to_meshio`` (which renumbers hexahedra).

    >>> from skfem import MeshTri1
    >>> kind, cells = vtk_cells(MeshTri1())
    >>> kind, cells.tolist()
    ('triangle', [[0, 1, 2], [1, 3, 2]])
    """
    block = to_meshio(mesh, encode_cell_data=False).cells[0]
    t = block.data.copy()
    corners = mesh.p[:, t[:, _CORNERS[block.type]]]            # (dim, ncells, dim + 1)
    edges = corners[:, :, 1:] - corners[:, :, :1]
    flip = np.linalg.det(np.moveaxis(edges, 0, 1)) < 0          # det of (ncells, dim, dim)
    t[flip] = t[flip][:, _FLIP[block.type]]
    return block.type, t


def side_pieces(mesh, psi_nodes: np.ndarray, u_minus: np.ndarray, u_plus: np.ndarray):
    """The mesh as two pieces, one per side of Γ, each on its own copy of its nodes.

    Piece -1 holds the cells of Ω⁻ and the cut cells, piece +1 those of Ω⁺
    and the cut cells; each carries its side's displacement at its nodes.

    Returns
    -------
    points : (n, dim) the nodes of piece -1 then those of piece +1
    cells : (ncells, nverts) VTK-oriented, indices into ``points``
    side, cut : (ncells,) the piece of each cell (-1/+1) and 1 on cut cells
    displacement : (n, dim) ``u_minus`` on piece -1, ``u_plus`` on piece +1
    levelset : (n,) ψ at the points

    >>> from skfem import MeshTri1                # cells (0, 1, 2) and (1, 3, 2)
    >>> u = np.zeros((2, 4))
    >>> p, c, side, cut, d, psi = side_pieces(MeshTri1(), np.array([-1.5, -.5, -.5, .5]), u, u)
    >>> c.tolist(), side.tolist(), cut.tolist()
    ([[0, 1, 2], [1, 3, 2], [4, 6, 5]], [-1, -1, 1], [0, 1, 1])
    """
    _, t = vtk_cells(mesh)
    sides = cell_sides(mesh, psi_nodes)
    points, cells, side, cut, disp, psi = [], [], [], [], [], []
    offset = 0
    for s, u in ((-1, u_minus), (1, u_plus)):
        keep = sides != -s
        nodes, local = np.unique(t[keep], return_inverse=True)
        points.append(mesh.p[:, nodes].T)
        cells.append(local.reshape(-1, t.shape[1]) + offset)
        side.append(np.full(int(keep.sum()), s))
        cut.append((sides[keep] == 0).astype(np.int64))
        disp.append(np.asarray(u)[:, nodes].T)
        psi.append(psi_nodes[nodes])
        offset += nodes.size
    return (np.vstack(points), np.vstack(cells), np.concatenate(side), np.concatenate(cut),
            np.vstack(disp), np.concatenate(psi))


def region_pieces(mesh, node_region: np.ndarray, fields: np.ndarray):
    """The mesh as one piece per region (several interfaces), each on its own copy of
    its nodes: :func:`side_pieces` with R regions.

    Piece r holds the cells with a vertex in region r (``node_region`` (nverts,)),
    with its field ``fields[r]`` (dim, nverts) at its nodes; a cell that an
    interface cuts is in the pieces of both its sides.

    Returns
    -------
    points : (n, dim); cells : (ncells_written, nverts), VTK-oriented;
    region : the piece of each written cell; cut : 1 on the cells of two regions;
    displacement : (n, dim); nodes : (n,) the mesh vertex of each point

    >>> from skfem import MeshTri1                # cells (0, 1, 2) and (1, 3, 2)
    >>> u = np.zeros((2, 2, 4))
    >>> p, c, region, cut, d, nodes = region_pieces(MeshTri1(), np.array([0, 0, 0, 1]), u)
    >>> c.tolist(), region.tolist(), cut.tolist(), nodes.tolist()
    ([[0, 1, 2], [1, 3, 2], [4, 6, 5]], [0, 0, 1], [0, 1, 1], [0, 1, 2, 3, 1, 2, 3])
    """
    _, t = vtk_cells(mesh)
    regions_of = node_region[mesh.t]                          # (nverts, ncells)
    points, cells, region, cut, disp, ids = [], [], [], [], [], []
    offset = 0
    for r, u in enumerate(fields):
        keep = (regions_of == r).any(axis=0)
        nodes, local = np.unique(t[keep], return_inverse=True)
        points.append(mesh.p[:, nodes].T)
        cells.append(local.reshape(-1, t.shape[1]) + offset)
        region.append(np.full(int(keep.sum()), r))
        cut.append((regions_of[:, keep] != r).any(axis=0).astype(np.int64))
        disp.append(np.asarray(u)[:, nodes].T)
        ids.append(nodes)
        offset += nodes.size
    return (np.vstack(points), np.vstack(cells), np.concatenate(region), np.concatenate(cut),
            np.vstack(disp), np.concatenate(ids))
