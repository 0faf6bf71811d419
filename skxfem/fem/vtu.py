"""VTK cells for the VTU files: positively oriented, one piece of mesh per region
(one interface: Ω⁻ then Ω⁺).

Shared by the writers of :mod:`skxfem.app.io`.
VTU vectors are ``(n, 3)``: 2D vectors get a zero z component.

>>> pad3(np.array([[1.0, 2.0]])).tolist()
[[1.0, 2.0, 0.0]]
"""
from __future__ import annotations

import numpy as np
from skfem.io.meshio import to_meshio

__all__ = ["vtk_cells", "interface_levelsets", "region_levelsets", "node_regions",
           "region_pieces", "pad3", "vectors3"]

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


def interface_levelsets(result) -> np.ndarray:
    """(n_interfaces, nverts) ψ of each interface of ``result`` at the nodes, as its
    solve used it (:meth:`skxfem.gamma.Gamma.nodal`: the cut's ψ, 0 at the nodes on
    Γ, :func:`skxfem.cut.snap`)."""
    return np.array([q.gamma.nodal(q.cut) for q in result.problem.interfaces])


def region_levelsets(result) -> np.ndarray:
    """(n_splitting, nverts) the rows of :func:`interface_levelsets` whose Γ splits the
    body (:attr:`skxfem.gamma.Gamma.splits`; a crack does not): the signs
    ``result.regions`` holds."""
    psi = interface_levelsets(result)
    keep = [bool(q.gamma.splits) for q in result.problem.interfaces]
    return psi[keep].reshape(-1, psi.shape[-1])


def node_regions(regions: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """(nverts,) the region of each node: the row of ``regions`` (R, n_interfaces),
    the sign (±1) of each level set in each region, that the node's signs of ``psi``
    (n_interfaces, nverts) match (Ω⁻ = {ψ < 0}).

    >>> node_regions(np.array([[-1], [1]]), np.array([[-0.5, 0.25, -1.0]])).tolist()
    [0, 1, 0]

    Raises
    ------
    ValueError
        If a node's signs are those of no region.
    """
    signs = np.where(np.asarray(psi) < 0, -1, 1).T                  # (nverts, n_interfaces)
    match = (signs[:, None, :] == np.asarray(regions)[None]).all(axis=2)
    if not match.any(axis=1).all():
        raise ValueError(f"{int((~match.any(axis=1)).sum())} nodes have signs of no region "
                         f"of {np.asarray(regions).tolist()}")
    return match.argmax(axis=1)


def region_pieces(mesh, node_region: np.ndarray, fields: np.ndarray):
    """The mesh as one piece per region, each on its own copy of its nodes.

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
