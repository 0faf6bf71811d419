r"""Restricted multiplier spaces (paper §5): algo2 (vital edges), algo1 (winner nodes).

One λ_e per strictly cut edge e ∈ S_e is too rich for the LBB condition.  Both
algorithms keep fewer multipliers μ, λ = P μ, P sparse with rows summing to 1
(a constant pressure is kept exactly), by graph work on the bipartite graph
whose vertices N_e = N_e⁻ ∪ N_e⁺ are the ends of the cut edges S_e.

>>> import numpy as np
>>> nodes = np.array([[0., 1., 2.], [0., 1., 0.]])   # nodes 0, 2 below Γ, 1 above
>>> psi = nodes[1] - 0.5
>>> edges, points = [[0, 2], [1, 1]], [[0.5, 1.5], [0.5, 0.5]]
>>> vital_edges(edges, psi, points, nodes).P.toarray()   # one star: one μ
array([[1.],
       [1.]])
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components, min_weight_full_bipartite_matching

from .cut import Cut
from .fem.cutgraph import check_fixed, check_graph, edges_at, incidence, interpolate, nearest
from .multipliers import SPACES, Space, naive

__all__ = ["Space", "minimum_edge_cover", "star_groups", "relations", "vital_edges",
           "winner_nodes", "multiplier_space", "extend_to_held"]


def minimum_edge_cover(edges, psi, length, fixed=None) -> np.ndarray:
    """S_ve: the fewest edges touching every node of N_e not ``fixed``, then the
    shortest.

    ``edges`` (2, ne) int, ``psi`` (nnodes,), ``length`` (ne,), ``fixed``
    (nnodes,) bool or None; returns the (ne,) bool mask of the vital edges.

    >>> minimum_edge_cover(np.array([[0, 0, 2], [1, 3, 3]]), np.array([-1, 1, -1, 1.]),
    ...                    np.array([1.0, 2.0, 1.0])).tolist()   # 0-1 and 2-3 cover all
    [True, False, True]

    Gallai: a minimum edge cover is a maximum matching M plus, for each node
    left unmatched, one edge at it (its shortest, of length m(v)).  Its length
    is Σ_v m(v) - Σ_{uv∈M} s(uv), with the saving s(uv) = m(u) + m(v) - |uv|:
    we want the maximum matching of largest saving.  That is exact: a minimum
    cover is a set of stars, and one edge per star is such a matching, with
    the other edges no shorter than the m(v) counted for them.  One sparse
    assignment solves it (LAPJVsp: the N_e graph of a plane cut is one large
    component, too big for the dense linear_sum_assignment): rows N_e⁻,
    columns N_e⁺ plus one private "unmatched" column per row, which costs
    more than any total saving, so that the matching is maximum first.
    A fixed node needs no cover: an edge with a fixed end covers one node,
    so only edges between two free nodes enter the matching.
    """
    edges, psi, length = np.asarray(edges), np.asarray(psi, float), np.asarray(length, float)
    fixed = np.zeros(psi.size, bool) if fixed is None else np.asarray(fixed, bool)
    ne = edges.shape[1]
    ell = length / length.mean()
    m = np.full(psi.size, np.inf)
    np.minimum.at(m, edges.ravel(), np.tile(ell, 2))
    vital = np.zeros(ne, dtype=bool)
    pair = np.flatnonzero(~fixed[edges[0]] & ~fixed[edges[1]])
    if pair.size:
        e0, e1 = edges[:, pair]
        cost = ell[pair] - m[e0] - m[e1]                     # minus the saving
        minus = np.where(psi[e0] < 0, e0, e1)
        rows, ri = np.unique(minus, return_inverse=True)
        cols, ci = np.unique(e0 + e1 - minus, return_inverse=True)
        alone = cols.size + np.arange(rows.size)
        shift, big = np.abs(cost).max() + 1.0, 2.0 * np.abs(cost).sum() + 1.0  # weights > 0
        A = sp.csr_matrix((np.r_[cost + shift, np.full(rows.size, big + shift)],
                           (np.r_[ri, np.arange(rows.size)], np.r_[ci, alone])),
                          shape=(rows.size, alone[-1] + 1))
        matched_rows, matched_cols = min_weight_full_bipartite_matching(A)
        paired = matched_cols < cols.size                    # matched to a node, not alone
        edge_of = sp.csr_matrix((pair + 1, (ri, ci)), shape=A.shape)
        vital[np.asarray(edge_of[matched_rows[paired], matched_cols[paired]]).ravel() - 1] = True
    covered = fixed.copy()                                   # then each unmatched node
    covered[edges[:, vital]] = True                          # takes its shortest edge
    ends, ids = edges.ravel(), np.tile(np.arange(ne), 2)
    order = np.lexsort((ids, length[ids]))                   # (ties: lowest index)
    node, first = np.unique(ends[order], return_index=True)
    vital[ids[order[first]][~covered[node]]] = True
    return vital


def vital_edges(edges, psi, points, nodes, fixed=None) -> Space:
    """Algo2 (paper §5): vital edges, star groups, distance-weighted relations.

    Parameters
    ----------
    edges : (2, ne) int, S_e: the strictly cut edges, ψ(v1) ψ(v2) < 0.
    psi : (nnodes,) nodal level set; its sign splits N_e into N_e⁻ and N_e⁺.
    points : (dim, ne) the intersection point x_e of each edge (λ_e lives there).
    nodes : (dim, nnodes) node coordinates, for the edge lengths.
    fixed : (nnodes,) bool, optional: nodes whose jump a support holds
        (:func:`skxfem.multipliers.multiplier_space`); no edge may have two
        fixed ends.  Default: none.

    Returns
    -------
    Space
        ``name="vital"``, ``vital`` (S_ve), ``groups``; one column per group.

    Notes
    -----
    1. S_ve is a minimum edge cover of (N_e, S_e): the fewest edges touching
       every node, among those the least total length (the paper's "we keep
       the shortest one").  Between covers of equal length only the matching
       solver decides: deterministic, but not specified further.  (code_aster's
       ``xrell2`` removes edges greedily instead: minimal, not always minimum.)
    2. A minimum cover is a union of stars (an edge whose two ends are covered
       twice would be superfluous).  The groups G^i_cve are its connected
       components, numbered in the order of their lowest edge index.  All λ of
       a group are equal, one μ; a lone vital edge is a group of one.
    3. A non-vital edge e = (v1, v2) takes at each end v_i the vital edge k_i
       at v_i (never none: S_ve covers v_i) whose point is nearest to x_e
       (ties: lowest index) and λ_e = d2/(d1+d2) λ_k1 + d1/(d1+d2) λ_k2,
       d_i = |x_e - x_ki|.
    4. With fixed nodes: S_ve covers the free nodes only (a fixed node has
       no jump to control), the groups connect through free nodes only, and
       a non-vital edge with a fixed end takes the λ of its other end's k_i.

    Raises
    ------
    ValueError
        If an argument has the wrong shape, an edge is not strictly cut, is
        listed twice or has length zero.
    """
    edges, psi, points, nodes = check_graph(edges, psi, points, nodes)
    fixed = check_fixed(fixed, edges, psi.size)
    ne = edges.shape[1]
    if ne == 0:
        return Space("vital", sp.csr_matrix((0, 0)), np.zeros(0, bool),
                     np.zeros(0, int))
    length = np.linalg.norm(nodes[:, edges[0]] - nodes[:, edges[1]], axis=0)
    vital = minimum_edge_cover(edges, psi, length, fixed)      # 1. the vital edges S_ve
    groups = star_groups(edges, vital, fixed)                   # 2. the groups G^i_cve
    return Space("vital", relations(edges, points, vital, groups), vital=vital,
                 groups=groups)                                 # 3. the relations


def star_groups(edges, vital, fixed=None) -> np.ndarray:
    """Step 2 of :func:`vital_edges`: the group of each vital edge, -1 elsewhere.

    The groups G^i_cve are the connected components of the vital edges (a
    minimum cover is a union of stars), numbered in the order of their lowest
    edge; a ``fixed`` end (nnodes,) bool, default none, joins no star (it is a
    node of its own).

    >>> edges = np.array([[0, 2, 4], [1, 1, 5]])
    >>> star_groups(edges, np.array([True, True, True])).tolist()
    [0, 0, 1]
    """
    edges, vital = np.asarray(edges), np.asarray(vital, bool)
    nnodes = int(edges.max()) + 1 if edges.size else 0
    fixed = np.zeros(nnodes, bool) if fixed is None else np.asarray(fixed, bool)
    nnodes = max(nnodes, fixed.size)
    iv = np.flatnonzero(vital)
    ends = edges[:, iv].copy()
    alone = fixed[ends]
    ends[alone] = nnodes + np.flatnonzero(alone.ravel())
    nn = nnodes + 2 * iv.size
    star = sp.coo_matrix((np.ones(iv.size), tuple(ends)), shape=(nn, nn))
    label = connected_components(star, directed=False)[1][ends[0]]
    _, first, inverse = np.unique(label, return_index=True, return_inverse=True)
    rank = np.empty_like(first)
    rank[np.argsort(first)] = np.arange(first.size)          # order of lowest edge
    groups = np.full(edges.shape[1], -1)
    groups[iv] = rank[inverse]
    return groups


def relations(edges, points, vital, groups) -> sp.csr_matrix:
    """Step 3 of :func:`vital_edges`: the prolongation P (n_edges, n_groups).

    A vital edge takes its group's multiplier; a non-vital edge e = (v1, v2) the
    distance-weighted mean of the vital edges k_i at its ends nearest to x_e,
    λ_e = d2/(d1+d2) λ_k1 + d1/(d1+d2) λ_k2 (d_i = |x_e - x_ki|), or the one of
    its free end where the other is fixed.

    >>> e = np.array([[0, 0, 2], [1, 3, 3]]); x = np.array([[0.0, 1.0, 2.0]])
    >>> relations(e, x, np.array([True, False, True]), np.array([0, -1, 1])).toarray()
    array([[1. , 0. ],
           [0.5, 0.5],
           [0. , 1. ]])
    """
    ne = edges.shape[1]
    nnodes = int(edges.max()) + 1 if ne else 0
    iv, nv = np.flatnonzero(vital), np.flatnonzero(~vital)
    inc = incidence(edges, nnodes, vital)
    k1, k2 = (nearest(points, nv, edges[i, nv], inc) for i in (0, 1))
    both = (k1 >= 0) & (k2 >= 0)                       # else a fixed end: none there
    rows, cols, w = interpolate(points, nv[both], k1[both], k2[both], groups[k1[both]],
                                groups[k2[both]])
    one = nv[~both]
    return sp.csr_matrix((np.r_[np.ones(iv.size + one.size), w],
                          (np.r_[iv, one, rows],
                           np.r_[groups[iv], groups[np.maximum(k1, k2)[~both]], cols])),
                         shape=(ne, int(groups.max()) + 1 if iv.size else 0))


def _pick_winners(edges, psi, fixed):
    """Algo1's greedy loop (rules 1-3 of :func:`winner_nodes`): the winners in
    the order picked and, for each edge, the position of the winner that broke it.
    A fixed node counts as degree 0 throughout, so it never wins."""
    a, b = edges
    apsi = np.abs(psi)
    deg = np.bincount(edges.ravel(), minlength=psi.size)    # unbroken edges at a node
    deg[fixed] = 0
    inc = incidence(edges, psi.size, np.ones(a.size, dtype=bool))
    diff, ratio = np.empty(a.size, dtype=np.int64), np.empty(a.size)

    def score(e):                                            # rule 1's two keys
        da, db, la, lb = deg[a[e]], deg[b[e]], apsi[a[e]], apsi[b[e]]
        diff[e] = np.abs(da - db)
        ratio[e] = np.where(da > db, la, np.where(da < db, lb, np.minimum(la, lb))) / (la + lb)

    score(np.arange(a.size))
    broken_by = np.empty(a.size, dtype=np.int64)
    winners = []
    while (top := diff.max()) >= 0:                          # broken edges: diff = -1
        best = np.flatnonzero(diff == top)
        e = best[np.argmax(ratio[best])]                    # argmax: lowest index on ties
        u, v = a[e], b[e]
        w = v if deg[v] > deg[u] or (deg[v] == deg[u] and apsi[v] < apsi[u]) else u
        broken = edges_at(inc, np.array([w]))[1]
        broken = broken[diff[broken] >= 0]
        diff[broken] = -1
        broken_by[broken] = len(winners)
        np.subtract.at(deg, edges[:, broken].ravel(), 1)
        deg[fixed] = 0
        near = edges_at(inc, edges[:, broken].ravel())[1]  # only their keys changed
        score(near[diff[near] >= 0])
        winners.append(w)
    return np.array(winners, dtype=np.int64), broken_by


def winner_nodes(edges, psi, points, nodes, fixed=None) -> Space:
    """Algo1 (Moës, Béchet & Tourbier 2006): one multiplier per winner node.

    Parameters and errors as :func:`vital_edges` (``nodes`` is only checked;
    a ``fixed`` node never wins: it counts as degree 0).

    Notes
    -----
    The rules are those of code_aster's ``xsella`` (winners) and 2006
    ``xrell1`` (relations), S. Géniaut's implementation of algo1 for this
    paper.  With deg(v) the number of unbroken cut edges at v, repeat until
    every edge is broken:

    1. take the edge of largest |deg(v1) - deg(v2)|; ties: largest
       ρ = |ψ(w)| / (|ψ(v1)| + |ψ(v2)|), w its end of larger deg (of smaller
       |ψ| if the degrees are equal); then the lowest edge index (code_aster
       takes the last of its list);
    2. its winner is its end of larger deg; ties: smaller |ψ| (nearer Γ),
       then v1;
    3. break every edge at the winner.

    The winners cover S_e.  An edge with one winner end takes that winner's
    multiplier (a P0 patch per winner).  An edge whose two ends won is
    interpolated like algo2's non-vital edges, between the single-winner
    edges at each end whose points are nearest (ties: lowest index); if an
    end has none, the edge takes the multiplier of the winner that broke it.

    A measured limit: the degree contest ignores where Γ lies.  On 4³
    tetrahedra with Γ a distance d·h/4 above a node row, most winners are
    the row above Γ, far from it, and β_h falls with d (0.36, 0.055, 0.0076
    for d = 0.5, 1e-2, 1e-3) while algo2 keeps β_h ≈ 0.41
    (tests/test_lbb.py).

    Returns
    -------
    Space
        ``name="winner"``; ``winners`` (in the order picked) labels the columns.

    >>> import numpy as np
    >>> nodes = np.array([[0., 1., 2.], [0., 1., 0.]])
    >>> lam_space = winner_nodes([[0, 2], [1, 1]], nodes[1] - 0.5, [[0.5, 1.5], [0.5, 0.5]], nodes)
    >>> lam_space.winners.tolist(), lam_space.P.toarray().ravel().tolist()
    ([1], [1.0, 1.0])
    """
    edges, psi, points, nodes = check_graph(edges, psi, points, nodes)
    fixed = check_fixed(fixed, edges, psi.size)
    ne = edges.shape[1]
    if ne == 0:
        return Space("winner", sp.csr_matrix((0, 0)), winners=np.zeros(0, int))
    winners, broken_by = _pick_winners(edges, psi, fixed)
    column = np.full(psi.size, -1)
    column[winners] = np.arange(winners.size)
    c0, c1 = column[edges]
    single = (c0 < 0) | (c1 < 0)
    one, two = np.flatnonzero(single), np.flatnonzero(~single)
    inc = incidence(edges, psi.size, single)
    k1, k2 = (nearest(points, two, edges[i, two], inc) for i in (0, 1))
    ok = (k1 >= 0) & (k2 >= 0)
    rows, cols, w = interpolate(points, two[ok], k1[ok], k2[ok], c0[two[ok]], c1[two[ok]])
    lone = two[~ok]
    P = sp.csr_matrix((np.r_[np.ones(one.size + lone.size), w],
                       (np.r_[one, lone, rows],
                        np.r_[np.maximum(c0, c1)[one], broken_by[lone], cols])),
                      shape=(ne, winners.size))
    return Space("winner", P, winners=winners)


def multiplier_space(name: str, mesh, cut: Cut, fixed=None, per_edge=None) -> Space:
    """The space ``name``: "naive", "winner" (algo1) or "vital" (algo2, §5).

    ``fixed`` (nnodes,) bool: nodes whose jump a support holds (see
    :func:`skxfem.multipliers.fixed_jumps`).  The space is built on the cut
    edges with a free end, the fixed nodes needing no multiplier of their
    own; a cut edge with two fixed ends (a *held* edge) gets no multiplier of
    its own either, but takes the λ of its nearest neighbour on Γ
    (:func:`extend_to_held`), so that every row of P still sums to 1 and a
    constant traction stays in the space.  Default: none.

    ``per_edge`` (n_edges,) bool: edges that get a multiplier each, as in the
    naive space, the stable one being built on the others (the pieces of Γ
    too small for it to hold them: :func:`skxfem.linalg.rigid.short_pieces`).
    Default: none.  A vertex on Γ (a point (v, v), edge id -1) always gets a
    multiplier of its own: it is no edge of the graph of algo1/algo2, and its
    jump is its own node's enriched dof (:func:`skxfem.enrich.edge_jumps`).
    """
    if name not in SPACES:
        raise ValueError(f"space must be one of {SPACES}, got {name!r}")
    ne = cut.edge_ids.size
    own = np.zeros(ne, dtype=bool) if per_edge is None else np.asarray(per_edge, dtype=bool)
    if own.shape != (ne,):
        raise ValueError(f"per_edge must be one bool per cut edge, shape ({ne},); "
                         f"got {own.shape}")
    own = own | (cut.edge_ids < 0)           # a vertex on Γ: a multiplier of its own
    if fixed is None or not np.any(fixed):
        fixed = None
        sub = np.arange(ne)
    else:
        fixed = np.asarray(fixed, dtype=bool)
        if fixed.shape != cut.psi.shape:
            raise ValueError(f"fixed must be one bool per node, shape {cut.psi.shape}; "
                             f"got {fixed.shape}")
        sub = np.flatnonzero(~(fixed[cut.edges[0]] & fixed[cut.edges[1]]))
    if name == "naive" or own[sub].all():
        lam_space = naive(cut) if sub.size == ne else \
            Space("naive", sp.identity(sub.size, format="csr"))
        if name != "naive":
            lam_space = Space(name, lam_space.P, np.ones(sub.size, bool), np.arange(sub.size),
                      np.zeros(0, int) if name == "winner" else None)
    else:
        build = winner_nodes if name == "winner" else vital_edges
        stable, solo = sub[~own[sub]], sub[own[sub]]
        lam_space = build(cut.edges[:, stable], cut.psi, cut.points[:, stable], mesh.p, fixed)
        if solo.size:                                        # one μ per edge there
            order = np.argsort(np.r_[stable, solo])
            P = sp.block_diag([lam_space.P, sp.identity(solo.size)], format="csr")[order]
            vital = groups = None
            if lam_space.vital is not None:
                vital = np.r_[lam_space.vital, np.ones(solo.size, bool)][order]
                groups = np.r_[lam_space.groups, lam_space.size + np.arange(solo.size)][order]
            lam_space = Space(name, P.tocsr(), vital, groups, lam_space.winners)
    if sub.size == ne:
        return lam_space
    embed = sp.csr_matrix((np.ones(sub.size), (sub, np.arange(sub.size))), shape=(ne, sub.size))
    held = np.ones(ne, dtype=bool)
    held[sub] = False
    vital = groups = None
    if lam_space.vital is not None:
        vital, groups = np.zeros(ne, dtype=bool), np.full(ne, -1)
        vital[sub], groups[sub] = lam_space.vital, lam_space.groups
    cell_nodes = mesh.t[:, cut.facet_cell]                   # (nloc, nf)
    free_cell = ~fixed[cell_nodes].all(axis=0)               # a jump left to control there
    loose = np.zeros(ne, dtype=bool)
    loose[cut.facets[:, free_cell].ravel()] = True
    return Space(name, extend_to_held((embed @ lam_space.P).tocsr(), held, cut, loose), vital,
                 groups, lam_space.winners)


def extend_to_held(P, held, cut: Cut, loose=None) -> sp.csr_matrix:
    """P with the rows of the ``held`` edges filled: each takes the row of its
    nearest neighbour on Γ, outward from the edges that have one.

    A support that holds the jump at both ends of a cut edge holds it at the
    edge's point x_e only: the hat function N_e of λ_e on Γ still meets the
    jump of the free nodes on the interface facets around x_e.  So the edge
    keeps a multiplier, but none of its own (the support leaves one jump
    fewer to control): λ_e is the λ of the cut edge nearest to x_e among those
    whose point lies in a cut cell with x_e (ties: lowest index), the
    extension of a mortar multiplier to a Dirichlet boundary (Wohlmuth).  A
    constant traction stays in the space (the patch test).  Held edges out of
    reach of any other edge (a piece of Γ whose every cut edge is held)
    share one new multiplier per connected piece, if the jump there can
    move at all (a ``loose`` edge in the piece); otherwise their rows stay
    empty: the supports hold the whole jump there, and its traction is a
    reaction of theirs.

    Parameters
    ----------
    P : (ne, m) sparse, the rows of the held edges empty.
    held : (ne,) bool.
    cut : the :class:`~skxfem.cut.Cut` (its facets say which edges share a cell).
    loose : (ne,) bool, the edges on a facet of a cell with a node whose jump
        no support holds (default: every edge).

    >>> from skfem import MeshTri1
    >>> from skxfem.cut import cut as cut_mesh
    >>> from skxfem.levelset import plane
    >>> m = MeshTri1().refined(1)
    >>> cut = cut_mesh(m, plane((0.3, 0.0), (-0.47, 1.0)))   # crosses the bottom at x = 0.3
    >>> held = np.isclose(cut.points[1], 0)                    # a support holds that edge
    >>> P = extend_to_held(sp.identity(5, format="csr")[:, ~held], held, cut)
    >>> P.toarray()[0], cut.points[:, 3].round(3)   # it takes the μ of its neighbour, edge 3
    (array([0., 0., 1., 0.]), array([0.436, 0.064]))
    """
    P, held = sp.csr_matrix(P), np.asarray(held, dtype=bool)
    ne = held.size
    cells = np.tile(cut.facet_cell, cut.facets.shape[0])     # the cell of each facet vertex
    in_cell = sp.csr_matrix((np.ones(cells.size), (cut.facets.ravel(), cells)),
                            shape=(ne, int(cells.max()) + 1 if cells.size else 0))
    near = (in_cell @ in_cell.T).tocsr()                     # edges sharing a cut cell
    done = ~held
    while True:
        pairs = near[np.flatnonzero(~done)][:, np.flatnonzero(done)].tocoo()
        if pairs.nnz == 0:
            break
        e, k = np.flatnonzero(~done)[pairs.row], np.flatnonzero(done)[pairs.col]
        dist = np.linalg.norm(cut.points[:, e] - cut.points[:, k], axis=0)
        order = np.lexsort((k, dist, e))
        first = order[np.r_[True, e[order][1:] != e[order][:-1]]]
        pick = sp.csr_matrix((np.ones(first.size), (e[first], k[first])), shape=(ne, ne))
        P = (P + pick @ P).tocsr()                           # row e (empty) := row k
        done[e[first]] = True
    if not done.all():                                       # isolated pieces of held edges
        alone = np.flatnonzero(~done)
        piece = connected_components(near[alone][:, alone], directed=False)[1]
        moves = np.zeros(piece.max() + 1, dtype=bool)
        np.logical_or.at(moves, piece, True if loose is None else np.asarray(loose)[alone])
        keep = moves[piece]
        column = np.cumsum(moves) - 1
        extra = sp.csr_matrix((np.ones(keep.sum()), (alone[keep], column[piece[keep]])),
                              shape=(ne, int(moves.sum())))
        P = sp.hstack([P, extra], format="csr")
    return P
