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
whose jump is held at those nodes (:func:`tangential_space`), and a sticking
contact is the bonded tie exactly.  A node holds t_a's jump when its fixed
components and the normal span t_a (:func:`held_with_normal`): t_a along
fixed components (the plate), or, with Γ tilted about e_y beside those
rollers, e_x = sin θ n + cos θ t₁, so that [[u]]·t₁ follows [[u]]·n there
and is held wherever the point is closed.

Coulomb's law bounds the tangential traction by the pressure at the same
dof, so each of the tangent's multipliers is *placed* at a normal dof j:
where its function equals ψ_j off the held edges, there (hexahedra, prisms:
the held edges borrow a neighbour's value,
:func:`skxfem.stabilised.extend_to_held`); where the tie rebuilds the stars
around the held nodes (tetrahedra), at the dof whose function overlaps it
most, each dof used once.  The dofs no multiplier is placed at are *held*:
their r_τa is 0, the support carries it.  Where no placement exists (winner
on a coarse tetrahedral mesh), the normal space is kept for that tangent and
the dofs whose every edge is held are released (:func:`held_tangents`).
Last, any tangential dof whose sticking row still depends on the others is
released (:func:`release_dependent`): a sticking contact has no zero mode.

The law at dof j pairs r_τa (the value of the tangent's function ψ^a) with
s_a = ∫ψ^a [[u]]·t_a / w_j, the normal dof's weight for every tangent: the
friction ball then bounds the tractions whose virtual work is Σ_a r_τa ∫ψ^a
[[v]]·t_a, and the slip it allows follows the integrated slips, the maximum
dissipation of that work (a weight per tangent would scale ρ_τ per tangent,
tilting the slip, and make the sliding stiffness unsymmetric).

Measured (``benchmarks/contact_inf_sup.py``, :func:`skxfem.lbb.inf_sup` with
``law="stick"``): on the plate the sticking contact's β_h is the tie's on
every cell; with Γ tilted by 11.3° about e_y it is within 2 % of the tie's
(which holds the Cartesian u_x, a space the frame n, t₁, t₂ cannot share), with
no zero mode.

**Interfaces.** Each interface's operators are those of its part of the
problem (:attr:`skxfem.problem.Problem.interfaces`, :func:`part_operators`), on
its own unknowns [a, b^k]; lifted to the whole's unknowns and stacked, interface
after interface (:func:`join`), they are the operators of the scene: its dofs
are those of every interface, ``interface`` says whose (one interface: the
operators of its part, on the same unknowns).

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
from scipy.linalg import qr
from scipy.sparse.csgraph import min_weight_full_bipartite_matching

from ..cut import point_lengths
from ..linalg.dependent import dependencies, unit_rows
from ..multipliers import fixed_jumps

__all__ = ["Operators", "operators", "part_operators", "join", "tangent_frames", "held_tangents",
           "tangential_space", "release_dependent", "held_with_normal", "sticking_rows"]


@dataclass(frozen=True)
class Operators:
    """Interface operators on the multiplier dofs.

    Attributes
    ----------
    Bn : (m, N) ∫ψ_j [[v]]·n.   Bt : tuple of k (m, N) ∫ψ_j [[v]]·t_a.
    w : (m,) lumped interface mass.   h : mean length of the cut edges.
    points, normals : (dim, m) mean position and unit normal of each dof.
    tangents : (k, dim) the tangents of the first dof (the frame of a plane Γ).
    tangent_held : (m, k) bool, the tangential components a support holds: the
        dofs no multiplier of the tangent is placed at (:func:`tangential_space`;
        :func:`held_tangents` where none can be placed), and those
        :func:`release_dependent` releases.
    Pt : tuple of k (n_edges, m), each tangent's prolongation from the dofs to
        the cut edges (the normal one, ``Problem.P``, where no support holds it).
    interface : (m,) the interface of each dof.
    pieces : the operators of each interface, on its own unknowns (module notes).
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
    """The operators of :class:`Operators` for an assembled bilateral problem ``pb``:
    :func:`join` of those of each interface (:func:`part_operators`)."""
    return join(pb, [part_operators(q) for q in pb.interfaces])


def part_operators(pb) -> Operators:
    """The :class:`Operators` of one interface's part ``pb`` (a
    :class:`skxfem.problem.Part` assembled bilateral), on its own unknowns [a, b^k]."""
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
                         f"weight on Γ: the multiplier space does not fit this "
                         f"interface")
    points = (PNW @ rule.points.T).T / w
    normals = (PNW @ rule.normals.T).T
    normals /= np.linalg.norm(normals, axis=0)
    e = pb.cut.edges
    h = float(point_lengths(pb.mesh, pb.cut).mean())   # a vertex on Γ: the mesh size
    fixed = fixed_jumps(pb.V, pb.D)
    facet_frames = tangent_frames(pb.cut.normals)  # (k, dim, n_facets)
    fallback = held_tangents(fixed, e, P, normals)
    Bt, Pt, tangent_held = [], [], np.zeros((w.size, dim - 1), bool)
    for a in range(dim - 1):
        held = held_with_normal(fixed, pb.cut, facet_frames[a])
        dofs, Pa = tangential_space(pb, held)
        if dofs is None:  # the normal space, its wholly held dofs released
            Pt.append(sp.csr_matrix(P))
            tangent_held[:, a] = fallback[:, a]
        else:
            rows = sp.csr_matrix((np.ones(dofs.size), (np.arange(dofs.size), dofs)),
                                 shape=(dofs.size, w.size))
            Pt.append((Pa @ rows).tocsr())
            tangent_held[:, a] = ~np.isin(np.arange(w.size), dofs)
        Bt.append((Pt[-1].T @ PT[a]).tocsr())
    if fixed[:, e].any():
        tangent_held = release_dependent(pb, Bt, tangent_held)
    return Operators(pb.B, tuple(Bt), w, h, points, normals, T[:, :, 0], tangent_held,
                     tuple(Pt), np.zeros(w.size, dtype=np.int64))


def join(pb, parts) -> Operators:
    """The operators of a problem from those of each interface (``parts``, on the
    unknowns of its part of ``pb``): lifted to the whole's unknowns
    (:meth:`skxfem.enrich.XSpaces.lift`) and stacked, dof after dof; ``h`` is the
    mean length of all cut edges, each interface's own in ``pieces``."""
    k = len(parts[0].Bt)
    sizes = [o.w.size for o in parts]
    lengths = np.concatenate([point_lengths(q.mesh, q.cut) for q in pb.interfaces])
    return Operators(
        sp.vstack([pb.V.lift(j, o.Bn) for j, o in enumerate(parts)], format="csr"),
        tuple(sp.vstack([pb.V.lift(j, o.Bt[a]) for j, o in enumerate(parts)], format="csr")
              for a in range(k)),
        np.concatenate([o.w for o in parts]), float(lengths.mean()),
        np.hstack([o.points for o in parts]), np.hstack([o.normals for o in parts]),
        parts[0].tangents, np.vstack([o.tangent_held for o in parts]),
        tuple(sp.block_diag([o.Pt[a] for o in parts], format="csr") for a in range(k)),
        np.repeat(np.arange(len(parts)), sizes), tuple(parts))


def held_with_normal(fixed: np.ndarray, cut, directions: np.ndarray,
                     tol: float = 1e-8) -> np.ndarray:
    """(nnodes,) bool: the jump along ``directions`` (dim, n_facets) is held at node
    j up to the normal jump: j is an end of a cut edge and, for every facet around
    its cut edges, the direction restricted to the components not fixed at j
    (``fixed`` (dim, nnodes), :func:`skxfem.multipliers.fixed_jumps`) is parallel to
    the facet's normal restricted so (or vanishes).  Then [[u]]·t = c [[u]]·n at j:
    where the normal jump is held (closed), so is the tangential one.  With the
    direction along fixed components only, this is
    :func:`skxfem.multipliers.direction_fixed`; it also holds the tangent t₁ of a
    plane tilted about e_y beside rollers u_x = 0, e_x = sin θ n + cos θ t₁.

    >>> import numpy as np
    >>> from skfem import MeshQuad1
    >>> from skxfem.levelset import plane
    >>> from skxfem.cut import cut as cut_mesh
    >>> m = MeshQuad1().refined(1)
    >>> cut = cut_mesh(m, plane((0.5, 0.5), (-0.2, 1.0)))   # tilted
    >>> fixed = np.zeros((2, m.p.shape[1]), bool); fixed[0, m.p[0] == 0] = True
    >>> t = np.array([cut.normals[1], -cut.normals[0]])       # the tangent
    >>> held = held_with_normal(fixed, cut, t)
    >>> bool(held.any()), bool(np.all(m.p[0, held] == 0))
    (True, True)
    """
    held = np.ones(fixed.shape[1], bool)
    touched = np.zeros(fixed.shape[1], bool)
    for k in range(cut.facets.shape[0]):
        ok = cut.facets[k] >= 0                      # -1: no cut point (a crack's tip)
        e = cut.facets[k][ok]
        for i in (0, 1):
            node = cut.edges[i, e]
            free = ~fixed[:, node]
            d, n = directions[:, ok] * free, cut.normals[:, ok] * free
            nn = (n * n).sum(axis=0)
            c = np.where(nn > 0, (n * d).sum(axis=0) / np.where(nn > 0, nn, 1.0), 0.0)
            np.logical_and.at(held, node, np.linalg.norm(d - c * n, axis=0) < tol)
            touched[node] = True
    return held & touched


def tangential_space(pb, fixed: np.ndarray):
    """The tie's space of a tangent whose jump a support holds at the ``fixed``
    nodes, each of its multipliers placed at a normal dof: (dofs, P_a), P_a
    (n_edges, m_a) the tie's prolongation and ``dofs`` (m_a,) distinct normal
    dofs, the one of each column; (None, None) if some column cannot be placed;
    ``dofs`` = all and P_a = P where no node is fixed.

    A column equal to a normal column off the held edges (both ends fixed) is
    placed at that dof; the others (tetrahedra: the stars the tie rebuilds
    around the fixed nodes) at the dofs left, one each, so that the columns
    overlap their dofs' functions most, ∫|ψ^a_i||ψ_j| summed over the placed
    columns as large as it can be (an assignment problem); each must overlap
    its dof's function.  The normal dofs that get no column are *held* for
    this tangent.
    """
    P = sp.csc_matrix(pb.P)
    if not fixed.any():
        return np.arange(P.shape[1]), P
    Pa = sp.csc_matrix(pb.gamma.multipliers(pb.mesh, pb.cut, fixed=fixed,
                                            per_edge=pb.per_edge).P)
    a, b = pb.cut.edges
    free = ~(fixed[a] & fixed[b])

    def key(col):
        ok = free[col.indices] & (col.data != 0)
        return tuple(col.indices[ok]), tuple(np.round(col.data[ok], 12))

    keys = {}
    for j in range(P.shape[1]):
        keys.setdefault(key(P[:, j]), []).append(j)
    same = [keys.get(key(Pa[:, i]), []) for i in range(Pa.shape[1])]
    dofs = np.array([s[0] if len(s) == 1 else -1 for s in same])
    if np.all(dofs >= 0) and np.unique(dofs).size == dofs.size:
        return dofs, Pa
    # some column is new: place every column, equal ones first, then by overlap
    overlap = (abs(Pa).T @ pb.M_edges @ abs(P)).tocoo()
    norm_a = np.sqrt((abs(Pa).T @ pb.M_edges @ abs(Pa)).diagonal())
    norm_n = np.sqrt((abs(P).T @ pb.M_edges @ abs(P)).diagonal())
    weight = overlap.data / (norm_a[overlap.row] * norm_n[overlap.col])  # in (0, 1]
    equal = dofs[overlap.row] == overlap.col
    weight = weight + np.where(equal, Pa.shape[1] + 1.0, 0.0)  # an equal column outweighs all
    keep = overlap.data > 0
    graph = sp.csr_matrix((weight[keep], (overlap.row[keep], overlap.col[keep])),
                          shape=overlap.shape)
    try:
        rows, cols = min_weight_full_bipartite_matching(graph, maximize=True)
    except ValueError:  # no placement in which every column overlaps its dof
        return None, None
    dofs = np.full(Pa.shape[1], -1)
    dofs[rows] = cols
    if np.any(dofs < 0):
        return None, None
    return dofs, Pa


def sticking_rows(Bn, Bt, tangent_held: np.ndarray):
    """The rows a contact imposes where every dof sticks, [Bn; Bt_a at the dofs whose
    tangent a is not held, a = 1, …], and those dofs of each tangent.

    >>> Bn, Bt = sp.identity(2, format="csr"), (2 * sp.identity(2, format="csr"),)
    >>> rows, where = sticking_rows(Bn, Bt, np.array([[True], [False]]))
    >>> rows.toarray().tolist(), [w.tolist() for w in where]
    ([[1.0, 0.0], [0.0, 1.0], [0.0, 2.0]], [[1]])
    """
    where = [np.flatnonzero(~tangent_held[:, a]) for a in range(tangent_held.shape[1])]
    return sp.vstack([Bn] + [B[d] for B, d in zip(Bt, where)], format="csr"), where


def release_dependent(pb, Bt, tangent_held: np.ndarray) -> np.ndarray:
    """``tangent_held`` with the tangential dofs released (held) whose rows, on the
    unknowns the supports leave free, depend on the others when every dof sticks.

    A support that holds a mix of the normal and tangential jumps ties the rows
    of the dofs beside it; their multipliers are then not all determined (the
    support takes that force).  :func:`held_with_normal` gives such tangents the
    tie's space; where that space cannot be placed (the normal one is kept) rows
    may still depend on each other.  Their null space
    (:func:`skxfem.linalg.dependent.dependencies`, rows scaled to unit length) is
    removed by releasing as many tangential dofs, chosen by a pivoted QR of its
    tangential part; the normal rows, which the Signorini law needs, stay.
    """
    free = np.ones(pb.V.N, bool)
    free[pb.D] = False
    held = tangent_held.copy()
    rows, where = sticking_rows(pb.B, Bt, held)
    N = dependencies(unit_rows(rows[:, free])[0])
    if not N.shape[1]:
        return held
    tangential = N[pb.B.shape[0]:]
    _, R, piv = qr(tangential.T, mode="economic", pivoting=True)
    d = np.abs(np.diag(R))
    take = piv[:int(np.sum(d > 1e-8 * max(d.max(), 1e-300)))]
    comp = np.repeat(np.arange(held.shape[1]), [w.size for w in where])
    dof = np.concatenate(where)
    held[dof[take], comp[take]] = True
    return held


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
