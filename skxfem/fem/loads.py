r"""Loads: surface loads ∫ t·v and ∫ H t·v on the boundary, for all five cell types, and
a body force given as numbers or formulas made a field b(x) (:func:`force_field`).

scikit-fem's ``FacetBasis`` does not support prisms, so boundary integrals
are done here with scikit-fem's own pieces: the reference cell
(``mesh.elem.refdom``: its facets and outward normals), the cell mapping
(``mesh.mapping()``: F, DF, DF⁻¹) and the element (``elem.gbasis``).

Every boundary facet is described in the reference coordinates of its
parent cell and split into reference simplices: a segment (2D), a triangle,
or a quadrilateral cut along its diagonal into two triangles (3D).  With a
level set, each simplex is clipped by the zero of the linearly interpolated
ψ with the X-FEM cut's own kernel (:func:`skxfem.fem.simplex.split`): an edge
is cut when ψ(v₁)ψ(v₂) < 0, at the point where the linear interpolant
vanishes.  Each piece gets its own
simplex rule and its side H = ±1.  A point x = F(X) with X = V₀ + Σ ξᵢ Tᵢ
gets the weight w·|DF T₁| (2D) or w·|DF T₁ × DF T₂| (3D), and the outward
unit normal n ∝ DF⁻ᵀ n̂ of the reference facet.

For a ψ that is linear on the facet (a plane cutting a planar face) the
pieces are exact, so ∫ H t·v is exact for polynomial tractions.

>>> from skxfem.fem.meshes import box
>>> mesh = box(2, "prism")
>>> q = boundary_quadrature(mesh, mesh.boundaries["zmax"], order=2)
>>> round(float(q.weights.sum()), 12), (q.normals[:, 0].round(12) + 0.0).tolist()
(1.0, [0.0, 0.0, 1.0])
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from skfem.element import ElementVector
from skfem.quadrature import get_quadrature
from skfem.refdom import RefLine, RefTri

from .evaluate import evaluation_matrix
from .meshes import cell_name
from .simplex import split

__all__ = ["BoundaryQuadrature", "boundary_quadrature", "pressure", "surface_load",
           "force_field"]


@dataclass(frozen=True)
class BoundaryQuadrature:
    """Quadrature points on (part of) the boundary, with their parent cells.

    Attributes
    ----------
    points : ndarray, shape (dim, nq)
        Physical coordinates.
    weights : ndarray, shape (nq,)
        Weights including the physical surface (2D: length) measure.
    normals : ndarray, shape (dim, nq)
        Outward unit normals.
    cells : ndarray, shape (nq,)
        Parent cell of each point.
    ref : ndarray, shape (dim, nq)
        Each point in its parent cell's reference coordinates.
    side : ndarray, shape (nq,)
        Heaviside value H = ±1 of the piece holding each point (+1 without ψ).
    """

    points: np.ndarray
    weights: np.ndarray
    normals: np.ndarray
    cells: np.ndarray
    ref: np.ndarray
    side: np.ndarray


def _facet_simplices(refdom) -> tuple[np.ndarray, np.ndarray]:
    """Local facets of a reference cell as simplices of local node ids.

    Returns ``nodes`` (m, dim) and ``owner`` (m,), the local facet of each.
    Wedge triangles repeat a node in ``refdom.facets``; quadrilaterals
    (listed in cyclic order) become two triangles.
    """
    nodes, owner = [], []
    for k, facet in enumerate(refdom.facets):
        facet = list(dict.fromkeys(facet))             # drop the repeated node
        if len(facet) == 4:
            pieces = [facet[:3], [facet[0], facet[2], facet[3]]]
        else:
            pieces = [facet]
        nodes += pieces
        owner += [k] * len(pieces)
    return np.array(nodes), np.array(owner)


def boundary_quadrature(mesh, facets: ArrayLike, order: int,
                        psi_nodes: ArrayLike | None = None) -> BoundaryQuadrature:
    """Quadrature on boundary facets, optionally split by a level set.

    Parameters
    ----------
    mesh
        A tri, quad, tet, hex or prism mesh.
    facets
        Indices into ``mesh.facets`` of boundary facets, e.g.
        ``mesh.boundaries["zmax"]``.
    order
        Rule order on each piece: exact for polynomials of this total degree
        in the piece's coordinates (on a hexahedron face a bilinear field
        times a traction of degree k needs ``order = k + 2``).
    psi_nodes
        Optional level set values at the mesh vertices, shape ``(nverts,)``.

    Returns
    -------
    BoundaryQuadrature

    >>> from skxfem.fem.meshes import box
    >>> mesh = box(2, "quad")
    >>> q = boundary_quadrature(mesh, mesh.boundaries["ymax"], 1,
    ...                         psi_nodes=mesh.p[0] - 0.25)
    >>> float(q.weights @ q.side)       # 0.75 - 0.25
    0.5
    """
    cell_name(mesh)                                    # TypeError if unsupported
    facets = np.asarray(facets)
    if facets.ndim != 1 or not np.issubdtype(facets.dtype, np.integer) \
            or np.any((facets < 0) | (facets >= mesh.facets.shape[1])):
        raise ValueError("facets must be a 1D array of facet indices in "
                         f"[0, {mesh.facets.shape[1]}), e.g. mesh.boundaries['xmin']")
    interior = facets[mesh.f2t[1, facets] != -1]
    if interior.size:
        raise ValueError(f"facets must be boundary facets; {interior.size} are "
                         f"interior (first: {interior[:5].tolist()}); use "
                         "mesh.boundary_facets() or mesh.boundaries[name]")
    dim = mesh.dim()
    refdom = mesh.elem.refdom

    # 1. every facet as reference simplices in its parent cell
    cells = mesh.f2t[0, facets]
    local = np.argmax(mesh.t2f[:, cells] == facets, axis=0)
    nodes, owner = _facet_simplices(refdom)
    fi, si = np.nonzero(owner[None, :] == local[:, None])
    V = np.transpose(refdom.p[:, nodes[si]], (1, 2, 0))     # (ns, D, dim)
    source, side = np.arange(len(fi)), np.ones(len(fi))

    # 2. optional cut by the level set
    if psi_nodes is not None:
        psi_nodes = np.asarray(psi_nodes, dtype=float)
        if psi_nodes.shape != (mesh.nvertices,) or not np.all(np.isfinite(psi_nodes)):
            raise ValueError(f"psi_nodes must be finite, of shape ({mesh.nvertices},) "
                             f"(one value per vertex), got shape {psi_nodes.shape}")
        psi = psi_nodes[mesh.t[nodes[si], cells[fi, None]]]   # (ns, D)
        V, source, side = split(V, psi)

    # 3. the simplex rule on every piece, in reference coordinates of the parent
    Xs, Ws = get_quadrature(RefLine if dim == 2 else RefTri, order)
    nq0 = Ws.size
    T = V[:, 1:] - V[:, :1]                                 # (np, D-1, dim) tangents
    ref = V[:, None, 0] + np.einsum("kq,pkd->pqd", Xs, T)   # (np, nq0, dim)
    tind = np.repeat(cells[fi[source]], nq0)
    X = ref.reshape(-1, dim).T[:, :, None]                  # (dim, nq, 1): one point per row
    mapping = mesh.mapping()

    # 4. physical points, surface measure and outward normals via the mapping
    x = mapping.F(X, tind=tind)[:, :, 0]
    DF = mapping.DF(X, tind=tind)[:, :, :, 0]               # (dim, dim, nq)
    t = np.einsum("ijq,qkj->kiq", DF, np.repeat(T, nq0, axis=0))  # (D-1, dim, nq)
    measure = np.linalg.norm(t[0] if dim == 2 else np.cross(t[0], t[1], axis=0), axis=0)
    nref = np.asarray(refdom.normals, dtype=float)[np.repeat(local[fi[source]], nq0)].T
    n = np.einsum("ijq,iq->jq", mapping.invDF(X, tind=tind)[:, :, :, 0], nref)
    return BoundaryQuadrature(
        points=x, weights=np.tile(Ws, len(V)) * measure,
        normals=n / np.linalg.norm(n, axis=0), cells=tind,
        ref=X[:, :, 0], side=np.repeat(side, nq0))


Traction = Callable[[np.ndarray, np.ndarray], np.ndarray]


def pressure(p: Callable[[np.ndarray], np.ndarray]) -> Traction:
    """The traction t = -p n of a pressure p(x); positive p pushes into the body.

    >>> t = pressure(lambda x: 2.0 + 0 * x[0])
    >>> t(np.zeros((2, 1)), np.array([[0.0], [1.0]])).tolist()
    [[-0.0], [-2.0]]
    """
    def traction(x, n):
        return -p(x) * n
    return traction


def surface_load(basis, quad: BoundaryQuadrature,
                 traction: Traction | ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Load vectors f = ∫ t·v and f_H = ∫ H t·v for a vector basis.

    Parameters
    ----------
    basis
        A ``skfem.Basis`` of an ``ElementVector`` on the mesh of ``quad``.
    quad
        From :func:`boundary_quadrature`.
    traction
        ``traction(x, n) -> t`` with x, n of shape ``(dim, nq)`` (points and
        outward normals) and t of shape ``(dim, nq)``; or a constant vector.

    Returns
    -------
    f, f_H : ndarray, shape (basis.N,)

    >>> from skfem import Basis, ElementQuad1, ElementVector
    >>> from skxfem.fem.meshes import box
    >>> mesh = box(2, "quad")
    >>> basis = Basis(mesh, ElementVector(ElementQuad1()))
    >>> q = boundary_quadrature(mesh, mesh.boundaries["ymax"], 2)
    >>> f, f_H = surface_load(basis, q, [0.0, -3.0])
    >>> round(float(f[basis.nodal_dofs[1]].sum()), 12)     # total force: -3 * 1
    -3.0
    """
    elem, dim = basis.elem, basis.mesh.dim()
    if not isinstance(elem, ElementVector):
        raise TypeError("basis must use a vector element, e.g. "
                        f"ElementVector(ElementHex1()); got {type(elem).__name__}")
    if quad.ref.shape[0] != dim or (quad.cells.size and
                                    quad.cells.max() >= basis.mesh.nelements):
        raise ValueError("quad does not belong to the mesh of basis; build it "
                         "with boundary_quadrature(basis.mesh, ...)")
    if callable(traction):
        t = np.asarray(traction(quad.points, quad.normals), dtype=float)
    else:
        t = np.asarray(traction, dtype=float).reshape(-1, 1) + 0 * quad.points
    if t.shape != quad.points.shape:
        raise ValueError(f"traction must return shape {quad.points.shape} "
                         f"(dim, nq), got {t.shape}")

    # f = Σ_c Φ_cᵀ (w t_c), Φ_c the values of the basis' c-components at the points
    Phi = evaluation_matrix(basis, quad.cells, quad.ref)
    wt = (t * quad.weights).ravel()
    return Phi.T @ wt, Phi.T @ (wt * np.tile(quad.side, dim))


def force_field(force, dim: int) -> Callable:
    """A body force as ``b(x) -> (dim, n)`` at points x (dim, n): ``force`` a callable
    of that kind, or ``dim`` values each a number or a callable ``x -> (n,)`` (a
    scene's ``body_force``: numbers and formulas).

    >>> b = force_field((0.0, lambda x: -x[0]), 2)
    >>> b(np.array([[1.0, 2.0], [0.0, 0.0]])).tolist()
    [[0.0, 0.0], [-1.0, -2.0]]
    """
    if not callable(force) and (not isinstance(force, (tuple, list, np.ndarray))
                                or len(force) != dim):
        raise ValueError(f"body force must be a callable x -> ({dim}, n) or {dim} values "
                         f"(numbers or callables x -> (n,)), got {force!r:.80}")

    def b(x):
        if callable(force):
            v = np.asarray(force(x), float)
        else:
            v = np.stack([np.broadcast_to(np.asarray(c(x) if callable(c) else c, float),
                                          x.shape[1:]) for c in force])
        if v.shape != x.shape or not np.all(np.isfinite(v)):
            raise ValueError(f"the body force must give finite values of shape {x.shape} "
                             f"(dim, n), got {v.shape}")
        return v
    return b


def scaled_force(force, factor: float, dim: int) -> object:
    """A body force ``force`` (a scene's: numbers or formulas per component, or None)
    times a load ``factor``: ``force`` itself at 1 or None, else a callable x ↦ factor
    b(x) (:func:`force_field`).

    >>> scaled_force((0.0, -1.0), 2.0, 2)(np.array([[0.0], [1.0]])).tolist()
    [[0.0], [-2.0]]
    >>> scaled_force(None, 2.0, 2) is None
    True
    """
    if force is None or factor == 1.0:
        return force
    b = force_field(force, dim)
    return lambda x: factor * b(x)
