"""The five cell types: the one table of their facts, and their reference topology.

:data:`CELL_TYPES` holds, once, what the rest of skxfem knows of each cell type
(its name, dimension, scikit-fem mesh class, vertices, cells per cube of a box
mesh, meshio name, plural).

What :mod:`skxfem.cut` needs to know about a cell, read off scikit-fem's own
reference domains (``mesh.elem().refdom``) and mesh connectivity: the local
edges and the cell → edge table, which local edges share a face, and a split of
the reference cell into simplices with the cell's own vertices (a quadrilateral
into 2 triangles, a prism into 3 and a hexahedron into 6 tetrahedra).

>>> from skfem import MeshHex1
>>> reference_simplices(MeshHex1()).shape
(6, 4)
>>> CELL_TYPES["prism"].dim, CELL_TYPES["prism"].meshio, CELL_TYPES["prism"].nverts
(3, 'wedge', 6)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import MeshHex1, MeshQuad1, MeshTet1, MeshTri1, MeshWedge1

from .simplex import WEDGE_TO_TETS

__all__ = ["CellType", "CELL_TYPES", "CELLS", "reference_simplices", "cell_edges",
           "on_common_face"]


@dataclass(frozen=True)
class CellType:
    """A cell type: ``name`` (skxfem's), ``dim``, scikit-fem's ``mesh`` class,
    ``nverts``, ``per_cube`` cells per square or cube of :func:`skxfem.fem.meshes.box`,
    the ``meshio`` cell name and the ``plural`` for text."""

    name: str
    dim: int
    mesh: type
    nverts: int
    per_cube: int
    meshio: str
    plural: str


CELL_TYPES = {c.name: c for c in (
    CellType("tri", 2, MeshTri1, 3, 2, "triangle", "triangles"),
    CellType("quad", 2, MeshQuad1, 4, 1, "quad", "quadrilaterals"),
    CellType("tet", 3, MeshTet1, 4, 6, "tetra", "tetrahedra"),
    CellType("hex", 3, MeshHex1, 8, 1, "hexahedron", "hexahedra"),
    CellType("prism", 3, MeshWedge1, 6, 2, "wedge", "prisms"),
)}
"""Every cell type skxfem supports, by name: the one table."""

CELLS = tuple(CELL_TYPES)
"""Their names, in the order of the tables of the book."""


def reference_simplices(mesh) -> np.ndarray:
    """Local vertex indices splitting the reference cell into simplices.

    >>> reference_simplices(MeshQuad1()).tolist()
    [[0, 1, 2], [0, 2, 3]]
    """
    ref = mesh.elem().doflocs  # (nverts, dim), in the mesh's local order
    if isinstance(mesh, (MeshTri1, MeshTet1)):
        return np.arange(mesh.t.shape[0])[None, :]
    if isinstance(mesh, MeshQuad1):
        return np.array([[0, 1, 2], [0, 2, 3]])
    if isinstance(mesh, MeshWedge1):
        return WEDGE_TO_TETS
    # hexahedron: the 6 Kuhn tetrahedra around the diagonal (0,0,0)-(1,1,1)
    def vertex(c):
        return int(np.flatnonzero(np.all(ref == c, axis=1))[0])
    tets = []
    for perm in ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)):
        c = np.zeros(3)
        path = [vertex(c)]
        for axis in perm:
            c[axis] = 1.0
            path.append(vertex(c))
        tets.append(path)
    return np.array(tets)


def cell_edges(mesh):
    """Local edges of the reference cell and the cell → global edge table.

    Returns ``(local, t2e, edges)``: local vertex pairs ``(nle, 2)``, global
    edge index of each local edge ``(nle, ncells)`` and the global edges
    ``(2, nedges)``.  In 2D the edges are the mesh facets.
    """
    refdom = mesh.elem().refdom
    if mesh.dim() == 2:
        return np.array(refdom.facets), mesh.t2f, mesh.facets
    return np.array(refdom.edges), mesh.t2e, mesh.edges


def on_common_face(mesh, slots) -> np.ndarray:
    """Boolean (n, n): do two of the ``slots`` (sets of local vertices: the local
    edges, single vertices) lie on a common face of the reference cell?"""
    faces = [set(f) for f in mesh.elem().refdom.facets]
    on = np.array([[set(s) <= f for f in faces] for s in slots])
    return (on.astype(int) @ on.T.astype(int)) > 0
