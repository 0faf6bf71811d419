"""Boundary conditions of a scene on a mesh: which dofs are imposed, which facets loaded.

A boundary is a name (``"xmin"`` ... ``"zmax"``, or any key of
``mesh.boundaries``) or a selection ``where(x) -> bool``.

* :func:`dirichlet` imposes displacements on the *nodes* of a boundary: a name
  selects the vertices of its facets, a selection the vertices where it is True.
* :func:`load_facets` loads boundary *facets*: a name selects its facets, a
  selection the boundary facets whose midpoint it accepts.
* A part's ``where`` (a selection too) keeps, of its boundary's nodes or facets,
  those where it holds: ``SurfaceLoad("xmax", pressure=1, where="z > 2.2")``, the
  xmax face above z = 2.2.

The named faces ``"xmin"`` ... ``"zmax"`` also work on meshes that carry no
``boundaries``: they are then the boundary facets lying on the bounding box.

>>> from skfem import MeshQuad1
>>> named_facets(MeshQuad1(), "ymin").tolist()
[0]
"""
from __future__ import annotations

import functools
from typing import TYPE_CHECKING, Callable

import numpy as np
from skfem import Mesh

from .parts import COMPONENTS, FACES, SurfaceLoad

if TYPE_CHECKING:
    from .model import Scene

__all__ = ["FACES", "COMPONENTS", "named_facets", "select_nodes", "select_facets",
           "imposed", "imposed_values", "dirichlet", "load_facets", "traction"]



def named_facets(mesh: Mesh, name: str) -> np.ndarray:
    """Facet indices of the boundary called ``name``."""
    boundaries = dict(mesh.boundaries or {})
    if name in boundaries:
        return np.asarray(boundaries[name], dtype=np.int64)
    faces = FACES[:2 * mesh.dim()]
    if name not in faces:
        available = sorted(set(boundaries) | set(faces))
        raise ValueError(f"unknown boundary {name!r}; available: {', '.join(available)}")
    axis = COMPONENTS.index(name[0])
    coords = mesh.p[axis]
    target = coords.min() if name.endswith("min") else coords.max()
    tol = 1e-10 * max(np.ptp(mesh.p, axis=1).max(), 1.0)
    candidates = mesh.boundary_facets()
    on_face = np.all(np.abs(coords[mesh.facets[:, candidates]] - target) <= tol, axis=0)
    return candidates[on_face]


def _where(where: Callable, x: np.ndarray, what: str) -> np.ndarray:
    mask = np.asarray(where(x))
    if mask.dtype != bool or mask.shape != x.shape[1:]:
        raise ValueError(f"{what}: the selection must return one bool per point, "
                         f"got dtype {mask.dtype} and shape {mask.shape}")
    return mask


def select_nodes(mesh: Mesh, boundary: str | Callable, what: str = "boundary",
                 where: Callable | None = None) -> np.ndarray:
    """Vertex indices of a named boundary or of a selection, and, with ``where``, only
    those of them where it holds; never empty."""
    if isinstance(boundary, str):
        nodes = np.unique(mesh.facets[:, named_facets(mesh, boundary)])
    else:
        nodes = np.flatnonzero(_where(boundary, mesh.p, what))
    if where is not None and nodes.size:
        nodes = nodes[_where(where, mesh.p[:, nodes], what)]
    if nodes.size == 0:
        raise ValueError(f"{what}: boundary {_label(boundary, where)} selects no node of the "
                         f"mesh")
    return nodes


def select_facets(mesh: Mesh, boundary: str | Callable, what: str = "boundary",
                  where: Callable | None = None) -> np.ndarray:
    """Boundary facet indices of a named boundary or of a selection, and, with ``where``,
    only those of them whose midpoint it holds at; never empty."""
    if isinstance(boundary, str):
        facets = named_facets(mesh, boundary)
    else:
        candidates = mesh.boundary_facets()
        midpoints = mesh.p[:, mesh.facets[:, candidates]].mean(axis=1)
        facets = candidates[_where(boundary, midpoints, what)]
    if where is not None and facets.size:
        facets = facets[_where(where, mesh.p[:, mesh.facets[:, facets]].mean(axis=1), what)]
    if facets.size == 0:
        raise ValueError(f"{what}: boundary {_label(boundary, where)} selects no facet of the "
                         f"mesh")
    return facets


def _label(boundary, where=None) -> str:
    if where is not None:
        return f"{_label(boundary)} where {_label(where)}"
    if isinstance(boundary, str):
        return repr(boundary)
    text = getattr(boundary, "text", None)  # an skxfem.scene.expr.Expression
    return repr(text) if text else getattr(boundary, "__name__", "selection")


def imposed_values(value, x: np.ndarray, what: str) -> np.ndarray:
    """A number or ``value(x)`` as a finite array of shape ``x.shape[1:]``."""
    v = np.asarray(value(x) if callable(value) else value, dtype=float)
    try:
        v = np.broadcast_to(v, x.shape[1:])
    except ValueError:
        raise ValueError(f"{what}: expected one value per point, got shape {v.shape}") from None
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{what}: the imposed values contain NaN or inf")
    return v


def imposed(scene: Scene, mesh: Mesh) -> list[tuple[np.ndarray, dict]]:
    """For each displacement of the scene: its nodes and ``{component index: value}``.

    ``"all"`` is expanded to every component of the mesh; a component the
    mesh does not have is refused, naming the displacement.
    """
    dim = mesh.dim()
    out = []
    for k, d in enumerate(scene.displacements):
        what = f"displacements[{k}]"
        nodes = select_nodes(mesh, d.boundary, what, d.where)
        components = dict.fromkeys(COMPONENTS[:dim], d.components["all"]) \
            if "all" in d.components else d.components
        values = {}
        for name, value in components.items():
            c = COMPONENTS.index(name)
            if c >= dim:
                raise ValueError(f"{what}: component {name!r} does not exist on a {dim}D "
                                 f"mesh (allowed: {', '.join(COMPONENTS[:dim])})")
            values[c] = (value, f"{what} component {name!r}")
        out.append((nodes, values))
    return out


def dirichlet(scene: Scene, mesh: Mesh, basis) -> tuple[np.ndarray, np.ndarray]:
    """Imposed dofs and their values for a vector basis ``Basis(mesh, ElementVector(e))``.

    Component ``c`` of vertex ``i`` is ``basis.nodal_dofs[c, i]``.  When several
    conditions set the same dof, the later one in ``scene.displacements`` wins.

    Returns
    -------
    dofs, values
        Sorted dof indices (int array) and the imposed values (float array).
    """
    values = np.zeros(basis.N)
    is_imposed = np.zeros(basis.N, dtype=bool)
    for nodes, components in imposed(scene, mesh):
        for c, (value, what) in components.items():
            dofs = basis.nodal_dofs[c, nodes]
            values[dofs] = imposed_values(value, mesh.p[:, nodes], what)
            is_imposed[dofs] = True
    dofs = np.flatnonzero(is_imposed)
    return dofs, values[dofs]


def traction(load: SurfaceLoad, x: np.ndarray, n: np.ndarray) -> np.ndarray:
    """The traction of ``load`` at points ``x`` with outward unit normals ``n``.

    Both arrays have shape ``(dim, ...)``; so has the result: t = -p n for a
    pressure, else the given vector.

    >>> traction(SurfaceLoad("ymax", pressure=2.0), np.zeros((2, 1)), np.array([[0.], [1.]]))
    array([[-0.],
           [-2.]])
    """
    if load.pressure is not None:
        return -imposed_values(load.pressure, x, "load pressure") * n
    return np.array([imposed_values(t, x, f"load traction[{i}]")
                     for i, t in enumerate(load.traction)])


def load_facets(scene: Scene, mesh: Mesh) -> list[tuple[np.ndarray, Callable]]:
    """For every load of the scene: its boundary facet indices and ``t(x, n)``.

    ``t(x, n)`` is :func:`traction` with the load bound to it.
    """
    dim = mesh.dim()
    out = []
    for k, load in enumerate(scene.loads):
        if load.traction is not None and len(load.traction) != dim:
            raise ValueError(f"loads[{k}]: traction has {len(load.traction)} components "
                             f"but the mesh is {dim}D")
        facets = select_facets(mesh, load.boundary, f"loads[{k}]", load.where)
        out.append((facets, functools.partial(traction, load)))
    return out
