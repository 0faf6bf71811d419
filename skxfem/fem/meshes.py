r"""Meshes: structured boxes of the five cell types, checks and file input.

skxfem works with five linear cells, named as in :func:`box`:

======== ============== =====================================
name     scikit-fem      cell
======== ============== =====================================
"tri"    ``MeshTri1``    triangle (2D)
"quad"   ``MeshQuad1``   quadrilateral (2D)
"tet"    ``MeshTet1``    tetrahedron
"hex"    ``MeshHex1``    hexahedron
"prism"  ``MeshWedge1``  prism (pentahedron, scikit-fem "wedge")
======== ============== =====================================

The prism box follows the paper (§5, Figure 4): the triangles lie in the
planes x = const and the prisms are extruded along x, so a horizontal plane
z = const between two layers of nodes cuts the diagonal edges of the (y, z)
squares.  Every box carries the named boundaries ``"xmin"``, ``"xmax"``,
``"ymin"``, ``"ymax"`` (and ``"zmin"``, ``"zmax"`` in 3D) as boundary facet
index arrays in ``mesh.boundaries``.

>>> m = box((2, 1, 3), "prism")
>>> m.nelements, cell_name(m)      # 1 * 3 squares, 2 triangles each, 2 layers
(12, 'prism')
>>> sorted(m.boundaries)
['xmax', 'xmin', 'ymax', 'ymin', 'zmax', 'zmin']
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import meshio
import numpy as np
from skfem import Mesh, MeshTri1, MeshWedge1
from skfem.io.meshio import from_meshio

from .cells import CELL_TYPES
from .files import quiet, regular_file

__all__ = ["CELLS", "box", "cell_name", "check_mesh", "read"]

CELLS = {name: c.mesh for name, c in CELL_TYPES.items()}
"""The supported cell names and their scikit-fem mesh classes
(:data:`skxfem.fem.cells.CELL_TYPES`)."""


def cell_name(mesh: Mesh) -> str:
    """The skxfem name of the mesh's cell type: "tri", "quad", "tet", "hex", "prism".

    >>> cell_name(MeshTri1())
    'tri'
    """
    for name, cls in CELLS.items():
        if type(mesh) is cls:
            return name
    supported = ", ".join(cls.__name__ for cls in CELLS.values())
    raise TypeError(f"mesh must be one of {supported}; got "
                    f"{type(mesh).__name__}")


def _per_direction(name: str, value, dim: int, integer: bool) -> tuple:
    values = tuple(np.atleast_1d(value).tolist())
    if len(values) == 1:
        values = values * dim
    ok = len(values) == dim and all(
        (isinstance(v, int) and v >= 1) if integer
        else (isinstance(v, (int, float)) and np.isfinite(v) and v > 0)
        for v in values)
    if not ok:
        kind = "positive integers" if integer else "positive numbers"
        raise ValueError(f"{name} must be one or {dim} {kind} (one per "
                         f"direction), got {value!r}")
    return values


def _tri_prisms(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> MeshWedge1:
    """Triangles in the (y, z) plane, extruded along x, positively oriented."""
    tri = MeshTri1.init_tensor(y, z)
    t = tri.t.copy()
    # the prism Jacobian is det = dx * det(triangle in (y, z)): make it > 0
    e1, e2 = tri.p[:, t[1]] - tri.p[:, t[0]], tri.p[:, t[2]] - tri.p[:, t[0]]
    clockwise = e1[0] * e2[1] - e1[1] * e2[0] < 0
    t[1:, clockwise] = t[2:0:-1, clockwise]
    nv, nx = tri.nvertices, len(x) - 1
    p = np.vstack((np.repeat(x, nv), np.tile(tri.p, (1, nx + 1))))
    bottom = (t[:, None, :] + nv * np.arange(nx)[None, :, None]).reshape(3, -1)
    return MeshWedge1(p, np.vstack((bottom, bottom + nv)))


def _named_boundaries(mesh: Mesh) -> Mesh:
    """Tag boundary facets lying on each face of the bounding box."""
    bnd = mesh.boundary_facets()
    fp = mesh.p[:, mesh.facets[:, bnd]]                 # (dim, nverts_facet, nbnd)
    lo, hi = mesh.p.min(axis=1), mesh.p.max(axis=1)
    tol = 1e-10 * np.max(hi - lo)
    tags = {}
    for d, axis in enumerate("xyz"[:mesh.dim()]):
        tags[axis + "min"] = bnd[np.all(np.abs(fp[d] - lo[d]) < tol, axis=0)]
        tags[axis + "max"] = bnd[np.all(np.abs(fp[d] - hi[d]) < tol, axis=0)]
    return mesh.with_boundaries(tags)


def box(n: int | Sequence[int], cell: str,
        size: float | Sequence[float] | None = None) -> Mesh:
    """Structured mesh of [0, Lx] × [0, Ly] (× [0, Lz]).

    Parameters
    ----------
    n
        Number of cells per direction: one int for all, or (nx, ny[, nz]).
        For "prism", each (y, z) square holds two triangles, so there are
        ``2 * ny * nz`` prisms per x-layer; for "tet" each cube holds six tets
        (scikit-fem's ``init_tensor``).
    cell
        "tri", "quad", "tet", "hex" or "prism".
    size
        Box lengths (Lx, Ly[, Lz]) or one length for all; default 1.

    Returns
    -------
    Mesh
        With boundaries "xmin", "xmax", "ymin", "ymax"[, "zmin", "zmax"].

    >>> box((3, 2), "quad", size=(3.0, 1.0)).nelements
    6
    """
    if cell not in CELLS:
        raise ValueError(f"cell must be one of {list(CELLS)}, got {cell!r}")
    dim = 2 if cell in ("tri", "quad") else 3
    n = _per_direction("n", n, dim, integer=True)
    size = _per_direction("size", 1.0 if size is None else size, dim, integer=False)
    x = [np.linspace(0.0, L, k + 1) for k, L in zip(n, size)]
    if cell == "prism":
        mesh = _tri_prisms(*x)
    else:
        mesh = CELLS[cell].init_tensor(*x)
    return _named_boundaries(mesh)


def _jacobians(mesh: Mesh) -> np.ndarray:
    """det DF at the reference vertices of every cell, shape (ncells, nverts)."""
    refp = mesh.elem.refdom.p
    DF = mesh.mapping().DF(refp)                       # (dim, dim, ncells, nverts)
    return np.linalg.det(np.moveaxis(DF, (0, 1), (-2, -1)))


def check_mesh(mesh: Mesh, dim: int | None = None) -> Mesh:
    """Check that ``mesh`` is a valid mesh of one of the five supported types.

    scikit-fem integrates with |det DF| and does not fix the node order of its
    cells (``MeshTri1`` even sorts it), so a consistently mirrored cell is
    fine.  A cell is rejected as *inverted* if det DF changes sign between its
    vertices (a folded quad, hex or prism), and as *degenerate* if det DF
    vanishes at a vertex (a flat cell).

    Parameters
    ----------
    mesh
        A ``MeshTri1``, ``MeshQuad1``, ``MeshTet1``, ``MeshHex1`` or ``MeshWedge1``.
    dim
        If given, the required spatial dimension (2 or 3).

    Returns
    -------
    Mesh
        The same mesh, so calls can be chained.

    Raises
    ------
    TypeError
        For any other mesh class.
    ValueError
        For NaN/inf coordinates, a wrong dimension, or inverted/degenerate cells.

    >>> check_mesh(box(2, "tri"), dim=2).nelements
    8
    """
    cell_name(mesh)                                    # TypeError if unsupported
    if not np.all(np.isfinite(mesh.p)):
        bad = np.nonzero(~np.all(np.isfinite(mesh.p), axis=0))[0]
        raise ValueError(f"mesh has NaN or inf coordinates at {bad.size} "
                         f"vertices (first: {bad[:5].tolist()}); fix mesh.p")
    if dim is not None and mesh.dim() != dim:
        raise ValueError(f"mesh must be {dim}D here, got a {mesh.dim()}D "
                         f"{type(mesh).__name__}")
    det = _jacobians(mesh)
    extent = np.ptp(mesh.p[:, mesh.t], axis=1).max(axis=0)   # cell size h
    degenerate = np.abs(det).min(axis=1) <= 1e-12 * extent ** mesh.dim()
    folded = (det.min(axis=1) < 0) & (det.max(axis=1) > 0)
    for bad, what in ((folded, "inverted (det DF changes sign)"),
                      (degenerate, "degenerate (det DF = 0)")):
        if np.any(bad):
            cells = np.nonzero(bad)[0]
            raise ValueError(f"mesh has {cells.size} {what} cells, first: "
                             f"{cells[:5].tolist()}; check the node order "
                             f"and coordinates of these cells")
    return mesh


_MESHIO_CELLS = {c.meshio: name for name, c in CELL_TYPES.items()}


def _cell_type(m: meshio.Mesh, path: Path) -> str:
    """The meshio type of the file's top-dimensional cells, checked (see :func:`read`)."""
    n = len(m.points)
    for block in m.cells:
        missing = (block.data < 0) | (block.data >= n)
        bad = np.nonzero(missing.any(axis=1))[0]
        if bad.size:
            raise ValueError(
                f"{path} has {bad.size} {block.type} cell(s) using vertices missing from "
                f"the file (first: cell {bad[0]} uses vertex {block.data[missing][0]}); the "
                f"file has {n} vertices, numbered 0 to {n - 1}: fix the cells' vertex indices")
    top = max((block.dim for block in m.cells), default=0)
    counts = {}
    for block in m.cells:
        if block.dim == top:
            counts[block.type] = counts.get(block.type, 0) + len(block)
    if len(counts) > 1:
        raise ValueError(
            f"{path} mixes {' and '.join(f'{c} {k}' for k, c in counts.items())} cells; "
            f"skxfem needs one cell type per mesh: mesh it again with a single cell type")
    kind = next(iter(counts), None)
    if kind not in _MESHIO_CELLS:
        raise ValueError(
            f"{path} has no supported cells (found {sorted(m.cells_dict)}); "
            f"skxfem reads {sorted(_MESHIO_CELLS)} (linear cells only)")
    unused = np.setdiff1d(np.arange(n), m.cells_dict[kind])
    if unused.size:
        raise ValueError(f"{path}: {unused.size} vertex(es) used by no cell (first: "
                         f"{unused[:5].tolist()}); skxfem needs every vertex in a cell: "
                         f"remove them from the file")
    return kind


def read(path) -> Mesh:
    """Read a mesh file (Gmsh ``.msh``, ``.vtu``, ... via meshio) and check it.

    The cells of the file's top dimension are used; lower-dimensional blocks
    (boundary lines, or faces of a 3D mesh) are ignored.  The top-dimensional
    cells must be of one supported type, refer only to vertices of the file
    and use every vertex.  For tri/quad/tet/hex the conversion is scikit-fem's
    (``skfem.io.meshio.from_meshio``, which keeps tagged boundaries and
    subdomains); scikit-fem 12 cannot import wedges, so prisms are built
    directly (their node order is the same in meshio and scikit-fem).

    >>> import tempfile, os, meshio
    >>> m = box(1, "prism")
    >>> path = os.path.join(tempfile.mkdtemp(), "prism.vtu")
    >>> meshio.write(path, meshio.Mesh(m.p.T, [("wedge", m.t.T)]))
    >>> read(path).nelements
    2
    """
    path = Path(path)
    what = f"mesh file {str(path)!r}"
    try:
        regular_file(path, what)    # a folder, a FIFO, a device, a loop: never opened
    except OSError as e:
        raise ValueError(f"{e.strerror}; give the path of a mesh file meshio reads "
                         f"(e.g. a Gmsh .msh)") from None
    with quiet() as said:         # meshio prints (to stdout and stderr) before it raises
        try:
            m = meshio.read(path)
        except (Exception, SystemExit) as e:  # meshio's errors (some call sys.exit)
            error = e
        else:
            error = None
    if error is not None:
        parts = [" ".join(said.getvalue().split())]   # what meshio printed, in one line
        if not isinstance(error, SystemExit):
            parts.append(f"{type(error).__name__}: {error}" if str(error)
                         else type(error).__name__)
        detail = "; ".join(p for p in parts if p) or "it gave up"
        raise ValueError(f"{what} could not be read by meshio ({detail}); give a mesh "
                         f"file meshio reads (e.g. a Gmsh .msh)") from error
    kind = _cell_type(m, path)
    if kind == "wedge":
        mesh = MeshWedge1(np.ascontiguousarray(m.points.T),
                          np.ascontiguousarray(m.cells_dict["wedge"].T))
    else:
        mesh = from_meshio(m, force_meshio_type=kind)
    if mesh.dim() == 2 and m.points.shape[1] == 3 and np.any(m.points[:, 2] != 0):
        raise ValueError(f"{path} has 2D cells on a non-flat surface (z != 0); "
                         f"skxfem needs planar 2D meshes in the (x, y) plane")
    return check_mesh(mesh)
