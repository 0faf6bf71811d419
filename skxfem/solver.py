r"""Solve a scene: the tied interface problem as a saddle point (paper §3 with a tie law).

With K the X-FEM stiffness, F the load and B the coupling of the multiplier
space (``λ = P μ``), the discrete problem a(u, v) - ∫_Γ r·[[v]] = l(v),
∫_Γ λ*·[[u]] = 0 reads

.. math:: \begin{bmatrix} K & B^T \\ B & 0 \end{bmatrix}
          \begin{bmatrix} U \\ -\mu \end{bmatrix} =
          \begin{bmatrix} F \\ 0 \end{bmatrix},

where μ holds the interface traction r = σ(u⁻)·n (``bonded``: the vector r;
``bilateral``: its normal part λ, r = λn).  The contact pressure is -r·n.

A singular system is never returned silently.  Dependent multipliers (rows of
B that are combinations of others, e.g. the naive space on tetrahedra, where a
quadrilateral cut carries four multipliers for a three-parameter linear jump)
are found by a rank-revealing QR of B and, by default, removed from the space
(``dependent="remove"``) — the displacement is then unique and the edge
tractions reported are the smoothest ones that balance it (see
:func:`skxfem.saddle.smoothest_multipliers`); with
``dependent="raise"`` a ValueError says how many there are.  After the solve the residual
is checked.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from . import saddle
from .boundary import imposed
from .cut import cut as cut_mesh
from .enrich import XSpace, enriched_load, jump_matrix, space, split_fields, stiffness
from .loads import boundary_quadrature, surface_load
from .multipliers import coupling, interface_rule, multiplier_space
from .scene import Scene, dirichlet, load_facets, resolve_mesh

__all__ = ["Result", "solve", "constrained_dofs"]


@dataclass(frozen=True)
class Result:
    """What :func:`solve` returns; the names match ``result.json``.

    ``points``, ``normals``, ``traction`` are (dim, n_points) at the
    multiplier points (cut edges); ``pressure`` = -traction·n;
    ``facets`` (dim, nf) index ``points``; ``u_minus``/``u_plus`` (dim, nverts)
    are the nodal fields of each side; ``max_jump`` is the largest constrained
    jump at the interface quadrature points (|[[u]]| bonded, |[[u]]·n|
    bilateral); ``removed`` counts the dependent multipliers removed.
    """

    scene: Scene
    mesh: object
    u_minus: np.ndarray
    u_plus: np.ndarray
    points: np.ndarray
    normals: np.ndarray
    traction: np.ndarray
    pressure: np.ndarray
    facets: np.ndarray
    max_jump: float
    n_dofs: int
    n_multipliers: int
    removed: int
    timings: dict = field(default_factory=dict)
    U: np.ndarray | None = field(default=None, repr=False)
    space: XSpace | None = field(default=None, repr=False)


def _point_normals(c) -> np.ndarray:
    """Area-weighted mean normal of the facets around each multiplier point."""
    dim = c.normals.shape[0]
    n = np.zeros((dim, c.points.shape[1]))
    for k in range(c.facets.shape[0]):
        for d in range(dim):
            np.add.at(n[d], c.facets[k], c.normals[d] * c.measures)
    return n / np.linalg.norm(n, axis=0)


def _differences(c, ncomp: int) -> sp.csr_matrix:
    """G: λ_i - λ_j over the sides (i, j) of the interface facets, per component."""
    nv = c.facets.shape[0]
    pairs = np.hstack([c.facets[[i, (i + 1) % nv]] for i in range(nv if nv > 2 else 1)])
    pairs = np.unique(np.sort(pairs, axis=0), axis=1)
    k = pairs.shape[1]
    G = sp.csr_matrix((np.r_[np.ones(k), -np.ones(k)],
                       (np.r_[np.arange(k), np.arange(k)], np.r_[pairs[0], pairs[1]])),
                      shape=(k, c.points.shape[1]))
    return sp.kron(sp.identity(ncomp), G, format="csr")


def constrained_dofs(V: XSpace, scene: Scene, mesh) -> tuple[np.ndarray, np.ndarray]:
    """Constrained unknowns of the X-FEM space and their values.

    The shifted enrichment φⱼ(H - Hⱼ) vanishes on a boundary facet that Γ
    does not cut, so there imposing aᵢ imposes u.  On a facet that Γ cuts,
    u = a + b(H - Hⱼ) takes both signs of H, so where a displacement acts on
    the whole facet (it selects all the facet's vertices) the enriched dofs
    of its components at the facet's nodes are set to zero as well.  Each
    displacement is taken on its own: two supports whose nodes together
    cover a facet do not constrain it.

    Parameters
    ----------
    V
        The X-FEM space (:func:`skxfem.enrich.space`).
    scene, mesh
        The scene and its resolved mesh.

    Returns
    -------
    dofs, values
        Indices into the unknowns [a, b] (``V.N`` of them) and imposed values.
    """
    dofs, values = dirichlet(scene, mesh, V.basis)
    psi = V.cut.psi
    bf = mesh.facets[:, mesh.boundary_facets()]
    cut_bf = bf[:, (psi[bf] < 0).any(axis=0) & (psi[bf] > 0).any(axis=0)]
    pos = np.full(V.n_std, -1)
    pos[V.enr_dofs] = np.arange(V.n_enr)
    enr = [np.zeros(0, dtype=np.int64)]
    for held, components in imposed(scene, mesh):
        selected = np.zeros(mesh.p.shape[1], dtype=bool)
        selected[held] = True
        nodes = np.unique(cut_bf[:, selected[cut_bf].all(axis=0)])
        for c in components:
            b = pos[V.basis.nodal_dofs[c, nodes]]
            enr.append(V.n_std + b[b >= 0])
    enr = np.unique(np.concatenate(enr))
    return (np.concatenate([dofs, enr]),
            np.concatenate([values, np.zeros(enr.size)]))


def solve(scene: Scene, dependent: str = "remove") -> Result:
    """Solve ``scene`` and return a :class:`Result`.

    Parameters
    ----------
    scene
        A :class:`skxfem.scene.Scene` (its ``quadrature_order`` sets the
        cell rule of the stiffness; ``None``: exact on affine cells).
    dependent
        ``"remove"`` (default) drops linearly dependent multipliers,
        ``"raise"`` refuses a rank-deficient coupling with a ValueError.

    Raises
    ------
    ValueError
        A scene that does not fit its mesh, a level set that cuts no cell
        or passes through nodes (from :func:`skxfem.cut.cut`), a rank
        deficient space with ``dependent="raise"``.
    skxfem.saddle.SingularSystemError
        (a ValueError) The supports leave a rigid motion of a side free.
    """
    if dependent not in ("remove", "raise"):
        raise ValueError(f"dependent must be 'remove' or 'raise', got {dependent!r}")
    timings = {}
    t0 = time.perf_counter()
    mesh = resolve_mesh(scene)
    c = cut_mesh(mesh, scene.levelset)
    S = multiplier_space(scene.space, mesh, c)
    timings["cut"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    V = space(mesh, c, scene.quadrature_order)
    timings["enrich"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    K = stiffness(V, scene.material)
    f, f_H = np.zeros(V.n_std), np.zeros(V.n_std)
    for facets, traction in load_facets(scene, mesh):
        q = boundary_quadrature(mesh, facets, 4, psi_nodes=c.psi)
        df, df_H = surface_load(V.basis, q, traction)
        f, f_H = f + df, f_H + df_H
    F = enriched_load(V, f, f_H)
    rule = interface_rule(mesh, c)
    B_edges = coupling(V, rule, scene.law)
    ncomp = B_edges.shape[0] // c.points.shape[1]
    P = sp.kron(sp.identity(ncomp), S.P, format="csr")  # component-major
    B = (P.T @ B_edges).tocsr()
    D, g = constrained_dofs(V, scene, mesh)
    timings["assemble"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    if dependent == "raise":
        removed = B.shape[0] - saddle.independent_rows(
            B[:, np.setdiff1d(np.arange(V.N), D)]).size
        if removed:
            raise ValueError(
                f"the multiplier space is rank deficient: {removed} of {B.shape[0]} "
                f"multipliers depend on the others (space {scene.space!r}, law "
                f"{scene.law!r}); use a stabilised space or dependent='remove'")
    U, mu, info = saddle.solve(K, B, F, D, g, G=_differences(c, ncomp) @ P)
    lam = (P @ mu).reshape(ncomp, -1)
    timings["solve"] = time.perf_counter() - t0

    normals = _point_normals(c)
    traction = lam if ncomp > 1 else lam * normals
    J = (jump_matrix(V, rule.cells, rule.ref) @ U).reshape(mesh.dim(), -1)
    jn = np.abs((J * rule.normals).sum(0)) if scene.law == "bilateral" \
        else np.linalg.norm(J, axis=0)
    u_minus, u_plus = split_fields(V, U)
    return Result(scene, mesh, u_minus, u_plus, c.points, normals, traction,
                  -(traction * normals).sum(0), c.facets, float(jn.max()), V.N,
                  B.shape[0] - info.removed, info.removed, timings, U, V)
