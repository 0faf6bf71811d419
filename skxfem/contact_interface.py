r"""The interface operators of the contact laws, on the multiplier dofs.

The laws of :mod:`skxfem.contact_laws` are imposed at the multiplier dofs μ_j
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
whose space leaves out the edges where a support holds the normal jump
(:func:`skxfem.problem.assemble`).  A support may hold a tangential jump as
well (the paper's plate: rollers u_x = 0 on the faces x = 0, 1 that Γ
crosses hold [[u]]·e_x there); a multiplier on a jump that is held anyway is
not determined (the support takes its force) and makes the Newton matrix
singular.  :func:`held_tangents` marks those (dof, tangent) pairs: their
traction is 0 and the support carries it.

>>> from skxfem.problem import assemble
>>> from skxfem.scenes import strip
>>> ops = operators(assemble(strip(n=2), law="bilateral"))
>>> round(float(ops.w.sum()), 12), ops.tangents.shape   # |Γ| = 1
(1.0, (1, 2))
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .multipliers import fixed_jumps

__all__ = ["Operators", "operators", "tangent_frames", "held_tangents"]


@dataclass(frozen=True)
class Operators:
    """Interface operators on the multiplier dofs.

    Attributes
    ----------
    Bn : (m, N) ∫ψ_j [[v]]·n.   Bt : tuple of k (m, N) ∫ψ_j [[v]]·t_a.
    w : (m,) lumped interface mass.   h : mean length of the cut edges.
    points, normals : (dim, m) mean position and unit normal of each dof.
    tangents : (k, dim) the tangents of the first dof (the frame of a plane Γ).
    held : (m, k) bool, the tangential components a support holds
        (:func:`held_tangents`).
    """

    Bn: sp.csr_matrix
    Bt: tuple
    w: np.ndarray
    h: float
    points: np.ndarray
    normals: np.ndarray
    tangents: np.ndarray
    held: np.ndarray


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
    """The operators of :class:`Operators` for an assembled bilateral problem ``pb``."""
    if pb.law != "bilateral":
        raise ValueError(f"contact needs the problem assembled with law='bilateral' "
                         f"(one multiplier component), got law={pb.law!r}")
    rule, P = pb.rule, pb.P
    dim, nq = rule.normals.shape
    NW = (rule.N.T @ sp.diags(rule.weights)).tocsr()  # (n_edges, nq)
    PNW = (P.T @ NW).tocsr()
    J = [pb.J[c * nq:(c + 1) * nq] for c in range(dim)]
    T = tangent_frames(rule.normals)
    Bt = tuple((PNW @ sum(sp.diags(t[c]) @ J[c] for c in range(dim))).tocsr() for t in T)
    w = np.asarray(P.T @ (pb.M_edges @ np.ones(P.shape[0]))).ravel()
    if np.any(w <= 0):
        raise ValueError(f"{int(np.sum(w <= 0))} multiplier dof(s) have no positive "
                         f"weight on Γ: the multiplier space does not fit this interface")
    points = (PNW @ rule.points.T).T / w
    normals = (PNW @ rule.normals.T).T
    normals /= np.linalg.norm(normals, axis=0)
    e = pb.cut.edges
    h = float(np.linalg.norm(pb.mesh.p[:, e[0]] - pb.mesh.p[:, e[1]], axis=0).mean())
    held = held_tangents(fixed_jumps(pb.V, pb.D), e, P, normals)
    return Operators(pb.B, Bt, w, h, points, normals, T[:, :, 0], held)


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
