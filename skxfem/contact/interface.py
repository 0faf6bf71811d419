r"""The interface operators of the contact laws, on the multiplier dofs.

The laws of :mod:`skxfem.contact.laws` are imposed at the multiplier dofs μ_j
(one per independent multiplier of the scene's space, λ = P μ on the cut
edges), with the *weighted* jumps

.. math:: d_j = \frac{1}{w_j}\int_\Gamma \psi_j\, [[u]]\cdot n, \qquad
          s_{j,a} = \frac{1}{w_j}\int_\Gamma \psi_j\, [[u]]\cdot t_a, \qquad
          w_j = \int_\Gamma \psi_j,

ψ_j = Σ_e P_ej N_e the multiplier function of dof j and w_j the row sum of
the interface mass PᵀMP (a lumped mass).  The rows of ``Bn`` and ``Bt`` are
the integrals ∫ψ_j [[v]]·n, ∫ψ_j [[v]]·t_a; Bn is the bilateral coupling
``Problem.B``.  Tangents: in 2D t = (n_y, -n_x); in 3D t₁ = (a × n)/|a × n|
with a = e_y (e_z where |n_y| > 0.9), t₂ = n × t₁.

**Supports on Γ.** The normal multipliers are those of the bilateral tie,
whose space treats the edges where a support holds the normal jump apart
(:func:`skxfem.problem.assemble`).  A support may hold a tangential jump as
well (the paper's plate: rollers u_x = 0 on the faces x = 0, 1 that Γ
crosses hold [[u]]·e_x there); a multiplier on a jump that is held anyway is
not determined (the support takes its force) and makes the Newton matrix
singular.  So each tangent t_a gets the space the tie builds for a component
with those nodes held (:func:`tangential_space`): its multipliers are a
subset of the normal dofs (the same functions off the held edges; the held
edges borrow a neighbour's value, :func:`skxfem.stabilised.extend_to_held`),
so that λ and r_τ still meet at every dof, and the dofs it leaves out are
*held*: their r_τa is 0, the support carries it.  Then a sticking contact is
the bonded tie exactly.  Where the tie's space of a held tangent is not such a
subset (tetrahedra: the stars around the held nodes are rebuilt), the normal
space is kept for that tangent and the dofs whose every edge is held are
released (:func:`held_tangents`): a stable space too, but not the tie's.

**Several interfaces.** Each interface's operators are those of its piece of
the problem (:attr:`skxfem.problem.Problem.interfaces`), on its own unknowns
[a, b^k]; lifted to the whole's unknowns and stacked, interface after
interface (:func:`join`), they are the operators of the scene: its dofs are
those of every interface, ``interface`` says whose.

>>> from skxfem.problem import assemble
>>> from skxfem.scene.benchmarks import strip
>>> ops = operators(assemble(strip(n=2), law="bilateral"))
>>> round(float(ops.w.sum()), 12), ops.tangents.shape   # |Γ| = 1
(1.0, (1, 2))
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..multipliers import direction_fixed, fixed_jumps
from ..stabilised import multiplier_space

__all__ = ["Operators", "operators", "join", "tangent_frames", "held_tangents",
           "tangential_space"]


@dataclass(frozen=True)
class Operators:
    """Interface operators on the multiplier dofs.

    Attributes
    ----------
    Bn : (m, N) ∫ψ_j [[v]]·n.   Bt : tuple of k (m, N) ∫ψ_j [[v]]·t_a.
    w : (m,) lumped interface mass.   h : mean length of the cut edges.
    points, normals : (dim, m) mean position and unit normal of each dof.
    tangents : (k, dim) the tangents of the first dof (the frame of a plane Γ).
    tangent_held : (m, k) bool, the tangential components a support holds
        (:func:`held_tangents`).
    Pt : tuple of k (n_edges, m), each tangent's prolongation from the dofs to
        the cut edges (the normal one, ``Problem.P``, where no support holds it).
    interface : (m,) the interface of each dof (0 for one interface).
    pieces : several interfaces: the operators of each, on its own unknowns
        (module notes); empty for one.
    """

    Bn: sp.csr_matrix
    Bt: tuple
    w: np.ndarray
    h: float
    points: np.ndarray
    normals: np.ndarray
    tangents: np.ndarray
    tangent_held: np.ndarray
    Pt: tuple = ()
    interface: np.ndarray | None = None
    pieces: tuple = ()


def tangent_frames(normals: np.ndarray) -> np.ndarray:
    """Unit tangents (k, dim, n) orthogonal to the unit ``normals`` (dim, n).

    >>> tangent_frames(np.array([[0.0], [0.0], [1.0]]))[:, :, 0].tolist()
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    """
    n = np.asarray(normals, float)
    if n.shape[0] == 2:
        return np.array([n[1], -n[0]])[None]
    a = np.zeros_like(n)
    a[np.where(np.abs(n[1]) > 0.9, 2, 1), np.arange(n.shape[1])] = 1.0
    t1 = np.cross(a.T, n.T).T
    t1 /= np.linalg.norm(t1, axis=0)
    return np.array([t1, np.cross(n.T, t1.T).T])


def operators(pb) -> Operators:
    """The operators of :class:`Operators` for an assembled bilateral problem ``pb``
    (several interfaces: :func:`join` of each one's)."""
    if pb.interfaces:
        return join(pb, [operators(q) for q in pb.interfaces])
    if pb.law != "bilateral":
        raise ValueError(f"contact needs the problem assembled with law='bilateral' "
                         f"(one multiplier component), got law={pb.law!r}")
    rule, P = pb.rule, pb.P
    dim, nq = rule.normals.shape
    NW = (rule.N.T @ sp.diags(rule.weights)).tocsr()  # (n_edges, nq)
    PNW = (P.T @ NW).tocsr()
    J = [pb.J[c * nq:(c + 1) * nq] for c in range(dim)]
    T = tangent_frames(rule.normals)
    PT = [(NW @ sum(sp.diags(t[c]) @ J[c] for c in range(dim))).tocsr() for t in T]
    w = np.asarray(P.T @ (pb.M_edges @ np.ones(P.shape[0]))).ravel()
    if np.any(w <= 0):
        raise ValueError(f"{int(np.sum(w <= 0))} multiplier dof(s) have no positive "
                         f"weight on Γ: the multiplier space does not fit this interface")
    points = (PNW @ rule.points.T).T / w
    normals = (PNW @ rule.normals.T).T
    normals /= np.linalg.norm(normals, axis=0)
    e = pb.cut.edges
    h = float(np.linalg.norm(pb.mesh.p[:, e[0]] - pb.mesh.p[:, e[1]], axis=0).mean())
    fixed = fixed_jumps(pb.V, pb.D)
    facet_frames = tangent_frames(pb.cut.normals)  # (k, dim, n_facets)
    fallback = held_tangents(fixed, e, P, normals)
    Bt, Pt, tangent_held = [], [], np.zeros((w.size, dim - 1), bool)
    for a in range(dim - 1):
        dofs, Pa = tangential_space(pb, direction_fixed(fixed, pb.cut, facet_frames[a]))
        if dofs is None:  # the normal space, its wholly held dofs released
            Pt.append(sp.csr_matrix(P))
            tangent_held[:, a] = fallback[:, a]
        else:
            rows = sp.csr_matrix((np.ones(dofs.size), (np.arange(dofs.size), dofs)),
                                 shape=(dofs.size, w.size))
            Pt.append((Pa @ rows).tocsr())
            tangent_held[:, a] = ~np.isin(np.arange(w.size), dofs)
        Bt.append((Pt[-1].T @ PT[a]).tocsr())
    return Operators(pb.B, tuple(Bt), w, h, points, normals, T[:, :, 0], tangent_held, tuple(Pt),
                     np.zeros(w.size, dtype=np.int64))


def join(pb, parts) -> Operators:
    """The operators of a problem with several interfaces from those of each (``parts``,
    on the unknowns of its piece of ``pb``): lifted to the whole's unknowns
    (:meth:`skxfem.problem.Problem.lift`) and stacked, dof after dof; ``h`` is the
    mean length of all cut edges, each interface's own in ``pieces``."""
    k = len(parts[0].Bt)
    sizes = [o.w.size for o in parts]
    lengths = np.concatenate([np.full(q.cut.edge_ids.size, o.h)
                              for q, o in zip(pb.interfaces, parts)])
    return Operators(
        sp.vstack([pb.lift(j, o.Bn) for j, o in enumerate(parts)], format="csr"),
        tuple(sp.vstack([pb.lift(j, o.Bt[a]) for j, o in enumerate(parts)], format="csr")
              for a in range(k)),
        np.concatenate([o.w for o in parts]), float(lengths.mean()),
        np.hstack([o.points for o in parts]), np.hstack([o.normals for o in parts]),
        parts[0].tangents, np.vstack([o.tangent_held for o in parts]),
        tuple(sp.block_diag([o.Pt[a] for o in parts], format="csr") for a in range(k)),
        np.repeat(np.arange(len(parts)), sizes), tuple(parts))


def tangential_space(pb, fixed: np.ndarray):
    """The tie's space of a tangent whose jump a support holds at the ``fixed``
    nodes, as a subset of the normal dofs: (dofs, P_a), P_a (n_edges, m_a) and
    ``dofs`` (m_a,) the normal dof of each of its columns; (None, None) if it
    is not such a subset (module notes); ``dofs`` = all and P_a = P where no
    node is fixed.

    Column j of P_a matches the normal column with the same values on the
    edges that are not held (both ends fixed); every other normal column must
    live on held edges only.
    """
    P = sp.csc_matrix(pb.P)
    if not fixed.any():
        return np.arange(P.shape[1]), P
    Pa = sp.csc_matrix(multiplier_space(pb.scene.space, pb.mesh, pb.cut, fixed=fixed,
                                        per_edge=pb.per_edge).P)
    a, b = pb.cut.edges
    free = ~(fixed[a] & fixed[b])
    keys = {}
    for j in range(P.shape[1]):
        col = P[:, j]
        ok = free[col.indices] & (col.data != 0)
        keys.setdefault((tuple(col.indices[ok]), tuple(np.round(col.data[ok], 12))),
                        []).append(j)
    dofs = []
    for j in range(Pa.shape[1]):
        col = Pa[:, j]
        ok = free[col.indices] & (col.data != 0)
        hit = keys.get((tuple(col.indices[ok]), tuple(np.round(col.data[ok], 12))), [])
        if len(hit) != 1 or not ok.any():
            return None, None
        dofs.append(hit[0])
    dofs = np.array(dofs)
    left = np.setdiff1d(np.arange(P.shape[1]), dofs)
    if np.unique(dofs).size != dofs.size or abs(P[:, left][free]).sum() > 0:
        return None, None
    return dofs, Pa


def held_tangents(fixed: np.ndarray, edges: np.ndarray, P, normals: np.ndarray,
                  tol: float = 1e-8) -> np.ndarray:
    """(m, k) bool: the tangential jumps of each multiplier dof that supports hold.

    A component c of the jump is held at dof j where both ends of every cut
    edge of its function ψ_j are fixed in c (``fixed`` (dim, nnodes) from
    :func:`skxfem.multipliers.fixed_jumps`; ``edges`` (2, n_edges); P the
    prolongation).  The directions n, t₁, t₂ of the dof (:func:`tangent_frames`
    of ``normals`` (dim, m)), restricted to the components not held, are
    orthogonalised in that order: a tangent with no part left (< ``tol``) is
    held — wholly held by the support, or moving only with the normal jump.

    >>> import numpy as np, scipy.sparse as sp
    >>> fixed = np.array([[True, True], [False, False]])   # u_x held at both ends
    >>> held_tangents(fixed, np.array([[0], [1]]), sp.identity(1), np.array([[0.0], [1.0]]))
    array([[ True]])
    """
    dim, m = normals.shape
    P = sp.csr_matrix(P)
    edge_fixed = fixed[:, edges[0]] & fixed[:, edges[1]]  # (dim, n_edges)
    support = (abs(P) > 0).astype(float)  # (n_edges, m)
    free = ((~edge_fixed).astype(float) @ support) > 0  # (dim, m): some edge free in c
    T = tangent_frames(normals)  # (k, dim, m)
    kept = [normals * free]
    held = np.zeros((m, dim - 1), bool)
    for a in range(dim - 1):
        v = T[a] * free
        for u in kept:
            nu = (u * u).sum(0)
            v = v - u * np.where(nu > 0, (u * v).sum(0) / np.where(nu > 0, nu, 1.0), 0.0)
        held[:, a] = np.linalg.norm(v, axis=0) < tol
        kept.append(np.where(held[:, a], 0.0, v))
    return held
