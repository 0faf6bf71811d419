"""Benchmark: the 3D crack's branch unknowns gathered along the front (dof gathering).

MEASURED, not in the library's defaults (issue 29: a 3D crack solve ≤ 3 × the bonded
tie on the same mesh).  The scene is :func:`crack_solve.scenes` (the unit cube's edge
crack ψ = z - 0.5, φ = x - 0.5, clamped at z = 0, pulled at z = 1).

Method
------
Dof gathering (Laborde, Pommier, Renard & Salaün 2005; in 3D Chahine, Laborde & Renard):
the twelve branch unknowns c_{i,l,c} of each branch node i (4 functions F_l × 3
components, :class:`skxfem.crack.space3d.CrackSpace3D`) are no longer free, but
interpolated along the front from a few **stations**,

    c_{i,l,c} = Σ_k M_k(s_i) b_{k,l,c},

s_i the arc position of node i's nearest point on the front, M_k the 1D P1 hats on
stations evenly spaced ``spacing`` front cells apart (the front cells' size along the
front, :func:`skxfem.crack.sif3d.front_sizes`).  In matrix terms a sparse prolongation
G (N × N_g): the identity on the standard and Heaviside unknowns, M ⊗ I₁₂ on the
branch unknowns; the system Gᵀ K G is solved for the reduced unknowns and U = G U_g is
expanded, whose K along the front is the library's
(:meth:`skxfem.crack.kind3d.Crack3D.front`, the K stage unchanged).  Variants
(:func:`prolongation`'s ``keep``; every node holding an imposed unknown keeps its own):
``gather`` every branch node gathered; ``front`` the front cells' nodes keep their
twelve (the hybrid: free near, gathered far); ``jump`` also F₁'s three (the one branch
function discontinuous across the crack) at the nodes of the split cells; ``near`` as
``jump`` and the twelve of the nodes within 2 front-cell sizes of the front; ``F1``
F₁'s three at every branch node, F₂..F₄ gathered.  ``p0`` constant coefficients per
station (Laborde's gathering); ``p1``, ``p2``: at each station polynomials of that
degree in the node's (φ, ψ)/r_e across the front (36, 72 unknowns per station).  ``--heaviside``:
each variant also on the space with Heaviside unknowns at the zone's split nodes
(:func:`zone_heaviside`, GetFEM's arrangement below), named ``H …``.

The stiffness is the library's (:func:`skxfem.problem.assemble`), so the zone's cells
are still integrated: gathering shrinks the solve only.  Each space (the current one
as G = I, in the same code) is solved by ``direct`` (:func:`skxfem.linalg.saddle.solve`,
what ``auto`` falls back on) and ``cg`` (:func:`skxfem.linalg.iterative.solve`: AMG +
CG as ``auto`` runs it, the enriched blocks scaled by the Cholesky factors of their
diagonal blocks (:func:`skxfem.linalg.blocks.block_scaling`: each node's [a, b, c] as
:func:`~skxfem.linalg.blocks.enriched_scaling`, each station's unknowns one block), the
rigid motions the near-null space, the tolerance
:data:`skxfem.linalg.choice.LINEAR_TOL`); the seconds count Gᵀ K G and the scaling.
The current space here gives the K_I at mid-front of ``crack_solve.py`` (3.7176,
3.6424, 3.6675, 3.7136 at n = 8, 12, 16, 24).

GetFEM (``tests/crack.cc`` of the GetFEM repository, Laborde et al.'s program): its
``ENRICHMENT_OPTION`` 1 is the sum of a ``mesh_fem_global_function`` of the four
singular functions with a cut-off (``isotropic_crack_singular_2D(i, ls,
cutoff_radius)``: one station for the whole tip, χ(r) F_l) and ``mesh_fem_level_set``,
the P1 space made discontinuous across the crack on every cell it cuts, the zone's
too; option 2 (the fixed area) multiplies the singular functions by the P1 partition of
unity on the nodes within ``RADIUS_ENR_AREA`` (this library's current space), with the
same discontinuous space.  There the jump in the zone is the discontinuous space's;
here the branch nodes carry no Heaviside unknowns, and the crack's opening across the
zone (beyond its √r term) is carried by the branch nodes' own coefficients.

Measured (29 November 2026, the machine shared with two other jobs: times swing by up
to 2× between runs; compare K_I, unknowns and nonzeros, and times within one block).
K_I at mid-front and its change against the current space of the same run ("d mid"; the
largest along the front's interior points is at most 0.8 points larger).
Station spacing 2, 3, 4 front cells (``--sizes 8 12 16 --keep '' front``):

=== ======== ======== ======= ============ ============== ========= =========
n   space    unknowns nnz (M) direct s     cg s (its)     K_I mid   d mid %
=== ======== ======== ======= ============ ============== ========= =========
8   current  11 718   2.19    8.25         1.73 (161)     3.7176
8   gather   3 222-46 0.34    0.08-0.22    0.14-0.17 (60) 2.98-2.99 -19.6..-19.9
8   front    3 654-78 0.45    0.15-0.17    0.14-0.23 (60) 3.04      -18.1..-18.3
12  current  22 776   4.02    18.03        2.70 (59)      3.6424
12  gather   7 224-60 0.55    0.73-0.97    0.45-0.49 (65) 2.71      -25.5..-25.6
12  front    7 848-84 0.70    0.73-1.01    0.35-0.71 (65) 2.74-2.75 -24.5..-24.7
16  current  36 312   5.52    91.4         1.62 (63)      3.6675
16  gather   15 972-  0.95    3.1-5.0      0.44-0.95 (68) 2.91      -20.7..-20.8
             16 020
16  front    16 788-  1.14    5.4-7.4      1.04-1.13 (68) 2.94      -19.8..-19.9
             16 836
=== ======== ======== ======= ============ ============== ========= =========

The tie in the same run: 2 916, 8 112, 17 340 unknowns, 0.46, 0.27, 0.65 s in all
(its solve 0.26, 0.18, 0.29 s).  The spacing moves K_I by under 0.4 %: the loss is
across the front, not along it.  Spacing 3, CG only (``--spacings 3 --no-direct --keep
front jump F1 near --degrees 0 1 2``; n = 24: ``--keep '' front jump F1 near
--degrees 0 2``), d mid % / unknowns / nnz (M) / cg s:

======== ============================= =============================
space    n = 8                         n = 12
======== ============================= =============================
current  0 / 11 718 / 2.19 / 1.58      0 / 22 776 / 4.02 / 1.63
gather0  (above)                       (above)
front0   -18.1 / 3 666 / 0.46 / 0.23   -24.7 / 7 860 / 0.71 / 0.45
jump0    -8.6 / 3 855 / 0.50 / 0.27    -9.9 / 8 211 / 0.77 / 0.62
F1 0     -2.2 / 5 679 / 0.76 / 0.41    -3.6 / 11 589 / 1.27 / 0.64
near0    -7.8 / 5 070 / 0.81 / 0.44    -8.5 / 9 966 / 1.23 / 0.58
front1   -6.9 / 3 762 / 0.89 / 0.29    -13.3 / 7 980 / 1.40 / 0.81
jump1    -5.0 / 3 951 / 0.94 / 0.34    -7.5 / 8 331 / 1.49 / 0.90
F1 1     -1.6 / 5 751 / 1.26 / 0.89    -3.2 / 11 679 / 2.09 / 1.49
near1    -4.5 / 5 166 / 1.32 / 0.51    -5.5 / 10 086 / 2.04 / 1.09
front2   -3.2 / 3 906 / 1.57 / 0.68    -5.4 / 8 160 / 2.46 / 1.00
jump2    -2.2 / 4 095 / 1.65 / 0.74    -2.4 / 8 511 / 2.61 / 1.03
F1 2     -1.1 / 5 859 / 2.02 / 2.19    -2.0 / 11 814 / 3.35 / 3.84
near2    -1.8 / 5 310 / 2.13 / 0.94    -1.8 / 10 266 / 3.29 / 1.43
======== ============================= =============================

======== ============================= =============================
space    n = 16                        n = 24
======== ============================= =============================
current  0 / 36 312 / 5.52 / 1.60      0 / 79 800 / 9.23 / 5.41
gather0  (above)                       -14.7 / 49 908 / 2.42 / 1.94
front0   -19.8 / 16 800 / 1.17 / 0.53  -13.9 / 51 108 / 2.71 / 2.14
jump0    -7.1 / 17 259 / 1.26 / 0.63   -4.8 / 51 783 / 2.83 / 1.46
F1 0     -2.1 / 21 678 / 1.92 / 0.81   -1.1 / 58 281 / 3.81 / 1.66
near0    -6.2 / 19 554 / 1.87 / 0.82   -4.4 / 55 158 / 3.73 / 1.68
front1   -9.7 / 16 944 / 2.14 / 1.04
jump1    -5.2 / 17 403 / 2.27 / 1.66
F1 1     -1.8 / 21 786 / 3.08 / 2.66
near1    -3.8 / 19 698 / 3.01 / 2.40
gather2                                -2.4 / 50 448 / 5.46 / 4.58
front2   -3.6 / 17 160 / 3.65 / 2.71   -2.2 / 51 648 / 6.08 / 5.66
jump2    -1.4 / 17 619 / 3.85 / 3.09   -0.75 / 52 323 / 6.36 / 5.66
F1 2     -1.2 / 21 948 / 4.84 / 7.36   -0.74 / 58 686 / 7.82 / 15.5
near2    -1.1 / 19 914 / 4.78 / 2.29   -0.59 / 55 698 / 7.68 / 4.27
======== ============================= =============================

(CG iterations 58-79 for all but the ``F1`` p1 and p2 spaces, 107-288.)  In the
library's space, then: Laborde's gathering (p0, with or without the front cells' nodes
free) brings the unknowns to the tie's (15 972 against 17 340 at n = 16, 49 908 against
52 500 at n = 24) and the solve's nonzeros to a sixth or a quarter, but K_I falls by
14-26 %: the branch functions there also carry the crack's opening across the zone
(r_e = 4 front cells; its branch nodes have no Heaviside unknowns), which constants per
station cannot.  No variant keeps K_I within 0.5 % at n ≤ 16; those within 2 % (degree
2 across the front, with the jump or the near nodes free) keep 70-90 % of the current
nonzeros and save little of the solve.  ``F1 0`` (F₁ free at every branch node, F₂..F₄
gathered): 35-41 % of the nonzeros, K_I 1.1-3.6 % low, like the vector enrichment of
``crack_solve.py``'s notes (3 % at n = 16).

**With GetFEM's Heaviside in the zone** (``--heaviside``, :func:`zone_heaviside`: H
also at the branch nodes of split cells that are no front cell's node, 63, 117, 153,
225 nodes at n = 8, 12, 16, 24; its stiffness by the library's own code, which follows
the map T) the loss goes.  The ``H current`` space (the twelve per node and those H) is
itself nearer K_I's limit (about 3.81): 3.7187, 3.7113, 3.7159, 3.7436, +0.03, +1.89,
+1.32, +0.81 % over the current space (189-675 more unknowns).  Its ``H F1 0``
(H at those nodes, F₁ free at every branch node, the front cells' nodes' twelve free,
F₂..F₄ gathered on stations 3 front cells apart): K_I at mid-front -1.76, -0.64, -0.10,
+0.01 % against the current space (3.6521, 3.6189, 3.6639, 3.7141), along the interior
of the front within 2.14, 0.78, 0.37, 0.30 %; 5 868, 11 940, 22 137, 58 956 unknowns
(50, 52, 61, 74 % of the current), 0.80, 1.34, 2.01, 3.94 M nonzeros (36, 33, 36, 43 %;
the tie's K 0.65 M at n = 16, 1.97 M at 24), CG 69, 68, 73, 77 iterations (the current
161, 59, 63, 69); spacing 2, 3, 4 at n = 16: -0.09, -0.10, -0.10 %.  ``H gather 0``
(every branch node gathered, H in the zone): -11.3, -12.7, -9.4, -6.2 %; ``H front 0``
-7.3, -5.4, -3.7, -2.4 %; degree 2 across brings these to +0.34 and +0.87 % at n = 16, but at 3.4
and 3.9 M nonzeros and 197 and 215 iterations.  Times (CG, least of 2, the machine
at a load of 4 on its 2 cores, so only the ratios within a run): ``H F1 0`` 1.23-1.81 s
against the current 3.39 s at n = 16 (the tie's solve 0.48 s, its whole 0.92 s) and
2.82 against 5.50 s at n = 24 (the tie's solve 1.66 s): the solve about half, 1.7 times
the tie's at n = 24, 3 times at n = 16.

**The answer**: K_I within 0.5 % of the current space, yes from n = 16 (not at n = 8,
12), but only with Heaviside unknowns at the zone's split nodes and F₁ per node: then
the unknowns are 61-74 % of the current ones and the solve half of it, not the tie's.
Gathering down to the tie's unknowns (p0 everywhere) loses 6-13 % of K_I with the
Heaviside, 15-26 % without.  And the solve is not all: with a solve as short as the
tie's, the assembly (stiffness 1.6-2.8 s at n = 16, 2.6-4.7 s at n = 24 in these runs)
and K along the front (1.4-3 s) would alone stay 6-8 and about 4 times the tie's whole
time at n = 16 and 24 (``crack_solve.py``'s 22:36 run, n = 24: assembly 1.89 s, solve
2.97 s, K 2.35 s against the tie's 1.06 s: halving the solve gives about 6.2 s of 7.66 s, a
ratio about 5.8 instead of 7.2).

The assembly left (``--zones``, one run, the stiffness stage of
:func:`skxfem.problem.assemble`; a cut-off χ(r) integrates its support, as a zone of
that radius does): the default zone r_e, r_e / 2 and the front cells' nodes only
(``topological``): the branch nodes' supports hold 100 / 50 / 11 % of the cells at
n = 8, 77 / 23 / 5 % at 12, 44 / 13 / 3 % at 16, 20 / 6 / 1 % at 24; the stiffness
0.47 / 0.29 / 0.15 s, 0.93 / 0.63 / 0.32 s, 1.94 / 0.77 / 0.31 s, 3.05 / 0.90 / 0.63 s.
A cut-off whose support is r_e / 2 would save 60-70 % of the stiffness from n = 16 (1.2
and 2.2 s at n = 16, 24: more than the tie's whole time), if a gathered space on it were
accurate (above: only with per-node freedom left, whose cells are the zone's).

    python benchmarks/crack_gather3d.py                  # n = 8, 12, 16, spacings 2 3 4
    python benchmarks/crack_gather3d.py --sizes 24 --no-direct
    python benchmarks/crack_gather3d.py --sizes 16 --no-direct --keep "" F1 --heaviside
    python benchmarks/crack_gather3d.py --sizes 8 12 16 24 --zones
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp

sys.path.insert(0, str(Path(__file__).resolve().parent))

from crack_solve import scenes  # noqa: E402


def arc_positions(space) -> tuple[np.ndarray, float]:
    """(s, L): the arc position (nb,) of each branch node's nearest point on the front
    of ``space`` (a :class:`~skxfem.crack.space3d.CrackSpace3D`) and the front's length;
    a ValueError unless the front is one open chain."""
    from skxfem.crack.geometry3d import front_chains

    chains = front_chains(space.geometry)
    if len(chains) != 1 or chains[0][1]:
        raise ValueError(f"space: gathering here needs a front of one open chain, got "
                         f"{len(chains)} chain(s), closed {[c for _, c in chains]}")
    pts = chains[0][0]                                      # (3, m)
    A, d = pts[:, :-1], np.diff(pts, axis=1)                # (3, nseg)
    ell = np.linalg.norm(d, axis=0)
    start = np.r_[0.0, np.cumsum(ell)[:-1]]
    x = space.mesh.p[:, space.branch]                       # (3, nb)
    t = np.clip(np.einsum("in,ij->nj", x, d) - (A * d).sum(axis=0), 0, None) / ell ** 2
    t = np.minimum(t, 1.0)
    near = A[:, None] + t[None] * d[:, None]                # (3, nb, nseg)
    dist = np.linalg.norm(near - x[:, :, None], axis=0)
    j = dist.argmin(axis=1)
    k = np.arange(x.shape[1])
    return start[j] + t[k, j] * ell[j], float(ell.sum())


def hats(s: np.ndarray, length: float, spacing: float) -> sp.csr_matrix:
    """M (n, ns): the P1 hats of stations evenly spaced about ``spacing`` apart on
    [0, ``length``], at the positions ``s`` (n,); each row sums to 1."""
    ns = max(2, int(round(length / spacing)) + 1)
    u = np.clip(s / length * (ns - 1), 0, ns - 1 - 1e-12)
    k = np.floor(u).astype(int)
    w, rows = u - k, np.arange(s.size)
    return sp.csr_matrix((np.r_[1 - w, w], (np.r_[rows, rows], np.r_[k, k + 1])),
                         shape=(s.size, ns))


def prolongation(V, spacing: float | None, keep: str = "", fixed=(), degree: int = 0):
    """(G, kept, stations): U = G U_g for the crack's space ``V``
    (:class:`~skxfem.crack.kind3d.CrackXSpace3D`); ``spacing`` the stations' spacing in
    front cells (None: G = I, the current space).  ``keep`` names which branch
    unknowns stay each node's own (identity columns), the rest gathered: ``front`` the
    front cells' nodes' twelve, ``jump`` also F₁'s three (the one discontinuous across
    the crack) at the nodes of the split cells, ``near`` as ``jump`` and the twelve of
    the nodes within 2 front cells' sizes (across) of the front, ``F1`` F₁'s three at
    every branch node and the front cells' nodes' twelve;
    any node with an unknown in ``fixed`` (the imposed ones) keeps its twelve.
    ``degree``: the gathered coefficients are, at each station, polynomials of this
    degree in the node's (φ, ψ)/r_e across the front (0: constants, Laborde's
    gathering; 1: 3 per function and component, 2: 6).
    ``kept`` (n,): the unknowns of U the first n columns of G are, ``stations``: a list
    of (ns, k) arrays, the columns of each station (k of them)."""
    from skxfem.crack.sif3d import front_sizes

    space, N = V.space, V.N
    n0 = V.n_std + space.n_heav
    bd = space.branch_dofs()                                # (nb, 4, 3)
    own = np.zeros((space.branch.size, 4), bool)            # (node, function) kept
    if spacing is None:
        own[:] = True
    geo, t = space.geometry, space.mesh.t
    if keep in ("front", "jump", "F1", "near"):
        own[np.isin(space.branch, t[:, geo.front_cells])] = True
    if keep == "near":
        r = np.hypot(geo.phi[space.branch], geo.psi[space.branch])
        own[r < 2 * front_sizes(space)[0]] = True
    if keep in ("jump", "near"):
        own[np.isin(space.branch, t[:, geo.split_cells]), 0] = True
    if keep == "F1":
        own[:, 0] = True
    own[np.isin(bd, fixed).reshape(own.shape[0], -1).any(axis=1)] = True
    kept = np.r_[np.arange(n0), bd[own].ravel()]
    rows, cols, vals = [kept], [np.arange(kept.size)], [np.ones(kept.size)]
    stations = []
    if not own.all():
        s, length = arc_positions(space)
        M = hats(s, length, spacing * front_sizes(space)[1])
        x = np.stack([geo.phi[space.branch], geo.psi[space.branch]]) / space.radius
        mono = np.array([x[0] ** a * x[1] ** (e - a) for e in range(degree + 1)
                         for a in range(e + 1)])            # (nm, nb)
        nm = mono.shape[0]
        M = M.tocoo()
        M = sp.csr_matrix((np.concatenate([M.data * mono[m, M.row] for m in range(nm)]),
                           (np.tile(M.row, nm), np.concatenate([nm * M.col + m
                                                                for m in range(nm)]))),
                          shape=(M.shape[0], nm * M.shape[1]))
        node, fun = np.nonzero(~own)                        # the gathered (node, function)
        Mg = M[node].tocoo()
        r = bd[node[Mg.row], fun[Mg.row]]                   # (nnz, 3)
        c = 12 * Mg.col[:, None] + 3 * fun[Mg.row][:, None] + np.arange(3)
        used, c = np.unique(c.ravel(), return_inverse=True)   # no empty column
        rows.append(r.ravel())
        cols.append(kept.size + c)
        vals.append(np.repeat(Mg.data, 3))
        station = used // (12 * nm)
        for k in np.unique(np.bincount(station)[np.unique(station)]):
            pick = np.flatnonzero(np.bincount(station, minlength=M.shape[1]) == k)
            stations.append(kept.size + np.flatnonzero(np.isin(station, pick))
                            .reshape(-1, k))
    n = kept.size + sum(b.size for b in stations)
    G = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(N, n))
    return G, kept, stations


def solve_gathered(p, G, kept, stations, method: str):
    """(U, seconds, iterations, nnz): the crack problem ``p``
    (:func:`skxfem.problem.assemble`) solved on the columns of ``G`` by ``method``
    (``direct`` or ``cg``, module notes), U = G U_g expanded; seconds from Gᵀ K G on."""
    from skxfem.linalg import iterative, saddle
    from skxfem.linalg.amg import rigid_modes
    from skxfem.linalg.blocks import block_scaling, congruence, node_blocks
    from skxfem.linalg.choice import LINEAR_TOL

    V = p.V
    pos = np.full(V.N, -1)
    pos[kept] = np.arange(kept.size)
    if (pos[p.D] < 0).any():
        raise ValueError("G: an imposed unknown is gathered (prolongation's fixed)")
    D = pos[p.D]
    t0 = time.perf_counter()
    K = (G.T @ p.K @ G).tocsr()
    F, B = G.T @ p.F, (p.B @ G).tocsr()
    if method == "direct":
        Ug, _, info = saddle.solve(K, B, F, D, p.g)
    else:
        full = rigid_modes(V)
        modes = np.zeros((G.shape[1], full.shape[1]))
        modes[:kept.size] = full[kept]
        enr = V.enr_dofs[kept[V.n_std:] - V.n_std]          # each kept enriched unknown's node
        blocks = node_blocks(enr, V.n_std, 3) + stations
        blocks = [b[~np.isin(b, D).any(axis=1)] for b in blocks]
        S, Sinv = block_scaling(K, blocks, np.ones(K.shape[0]))
        Us, _, info = iterative.solve(congruence(K, S, 3), B @ S, S.T @ F, D, p.g,
                                      modes=Sinv @ modes, blocksize=3, tol=LINEAR_TOL)
        Ug = S @ Us
    seconds = time.perf_counter() - t0
    return G @ Ug, seconds, getattr(info, "iterations", None), K.nnz


def front_K(p, U):
    """(K (m, 3), interior (m,), points (m, 3), seconds): K along the front of U
    (:meth:`skxfem.crack.kind3d.Crack3D.front`)."""
    q = p.interfaces[0]
    t0 = time.perf_counter()
    f = q.gamma.front(q.V, U[q.columns], p.scene.material)
    K = np.stack([f["K_I"], f["K_II"], f["K_III"]], axis=1)
    return K, f["interior"], f["points"], time.perf_counter() - t0


def zone_heaviside(space):
    """``space`` (a :class:`~skxfem.crack.space3d.CrackSpace3D`) with Heaviside unknowns
    also at its branch nodes of split cells that are no front cell's node (their
    supports cut through, as GetFEM's discontinuous space has them in the zone; the
    front cells' nodes not, where H would open the plane ahead of the front): the map
    T of :func:`skxfem.crack.dofs.virtual_map` rebuilt, which every operator of the
    space follows (the stiffness integrates the virtual functions T uses)."""
    from dataclasses import replace

    from skxfem.crack.dofs import virtual_map

    t, geo = space.mesh.t, space.geometry
    extra = np.setdiff1d(np.intersect1d(space.branch, t[:, geo.split_cells]),
                         t[:, geo.front_cells])
    heav = np.union1d(space.heaviside, extra)
    H_node = np.sign(geo.psi[heav])
    if not H_node.all():
        raise ValueError("space: a zone node on the crack's plane (H = 0)")
    T = virtual_map(space.nodal_dofs, heav, H_node, space.branch, space.F_node)
    return replace(space, heaviside=heav, H_node=H_node, T=T)


def assemble_with_zone_heaviside(scene):
    """:func:`skxfem.problem.assemble` of ``scene`` with its 3D crack's space made by
    :func:`zone_heaviside` (the kind's space builder wrapped for this call only)."""
    from unittest import mock

    from skxfem.crack import kind3d
    from skxfem.problem import assemble

    build = kind3d.crack_space_3d
    with mock.patch.object(kind3d, "crack_space_3d",
                           lambda *a, **k: zone_heaviside(build(*a, **k))):
        return assemble(scene)


def zone_costs(n: int) -> None:
    """Print the crack's stiffness stage (:func:`skxfem.problem.assemble`) and the cells
    of its branch nodes' supports with the default zone r_e, with r_e / 2 and with the
    front cells' nodes only (``topological``): what a cut-off χ(r) whose support is the
    smaller zone would leave to integrate."""
    from dataclasses import replace

    from skxfem.problem import assemble

    crack, _ = scenes(n)
    r_e = None
    for name in ("r_e", "r_e / 2", "topological"):
        i = crack.interfaces[0]
        if name == "r_e / 2":
            i = replace(i, enrichment_radius=r_e / 2)
        elif name == "topological":
            i = replace(i, enrichment="topological")
        p = assemble(replace(crack, interfaces=(i,)))
        space = p.V.per_interface[0].space
        r_e = space.radius if r_e is None else r_e
        cells = space.support_cells(space.branch).size
        print(f"# zone n = {n} {name:>12}: {space.branch.size:>5} branch nodes, their "
              f"supports {cells:>6} cells ({cells / p.mesh.t.shape[1]:.0%}), stiffness "
              f"{p.timings['stiffness']:.2f} s, unknowns {p.V.N}", flush=True)


def main(argv=None) -> int:
    from skxfem.problem import assemble
    from skxfem.solver import solve

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[8, 12, 16])
    ap.add_argument("--spacings", type=float, nargs="+", default=[2, 3, 4],
                    help="the stations' spacing in front cells along the front")
    ap.add_argument("--no-direct", action="store_true", help="CG only (large n)")
    ap.add_argument("--degrees", type=int, nargs="+", default=[0],
                    help="the gathered coefficients' degree across the front")
    ap.add_argument("--keep", nargs="+", default=["", "front", "jump", "F1"],
                    help="the variants (prolongation's keep; '' gathers every node)")
    ap.add_argument("--repeat", type=int, default=1, help="the least time of so many "
                    "solves of each space (a shared machine)")
    ap.add_argument("--heaviside", action="store_true", help="also every variant on "
                    "the space with Heaviside unknowns at the zone's split nodes "
                    "(zone_heaviside), named 'H ...'")
    ap.add_argument("--zones", action="store_true", help="the stiffness's cost by zone "
                    "(zone_costs) instead of the solves")
    args = ap.parse_args(argv)
    if args.zones:
        for n in args.sizes:
            zone_costs(n)
        return 0
    methods = ("cg",) if args.no_direct else ("direct", "cg")
    print(f"{'n':>3} {'space':>13} {'unknowns':>8} {'nnz K':>9} "
          + " ".join(f"{m + ' s':>8}" for m in methods)
          + f" {'its':>4} {'K s':>5} {'K_I mid':>8} {'d mid %':>8} {'d max %':>8}")
    for n in args.sizes:
        crack, tie = scenes(n)
        t0 = time.perf_counter()
        r_tie = solve(tie, linear="auto")
        t_tie = time.perf_counter() - t0
        p = assemble(crack)
        V = p.V.per_interface[0]
        if V.N != p.V.N or V.enr_dofs.size != V.N - V.n_std:
            raise ValueError("the scene: one crack, its unknowns the whole space's")
        a = p.timings
        zone = V.space.support_cells(V.space.branch).size / p.mesh.t.shape[1]
        print(f"# n = {n}: tie {r_tie.n_dofs} unknowns ({r_tie.problem.K.nnz} nonzeros in "
              f"K), {t_tie:.2f} s (solve "
              f"{r_tie.timings['solve']:.2f} s, {r_tie.linear}); crack assembly "
              f"{sum(a.values()):.2f} s (stiffness {a['stiffness']:.2f} s), branch nodes "
              f"{V.space.branch.size} of {p.mesh.p.shape[1]}, their supports {zone:.0%} of "
              f"the cells", flush=True)
        variants = [("current", None, "", 0)] + [
            (f"{k or 'gather'} {s:g} p{d}", s, k, d)
            for d in args.degrees for k in args.keep for s in args.spacings]
        runs = [(p, V, name, spacing, keep, degree)
                for name, spacing, keep, degree in variants]
        if args.heaviside:
            pH = assemble_with_zone_heaviside(crack)
            VH = pH.V.per_interface[0]
            print(f"# n = {n}: {VH.space.heaviside.size - V.space.heaviside.size} zone "
                  f"nodes with Heaviside unknowns too", flush=True)
            runs += [(pH, VH, "H " + name, spacing, keep, degree)
                     for name, spacing, keep, degree in variants]
        ref = None
        for p, V, name, spacing, keep, degree in runs:
            G, kept, stations = prolongation(V, spacing, keep, p.D, degree)
            times, U = [], None
            for m in methods:
                best = np.inf
                for _ in range(args.repeat):
                    U, sec, its, nnz = solve_gathered(p, G, kept, stations, m)
                    best = min(best, sec)
                times.append(best)
            K, interior, pts, tk = front_K(p, U)
            mid = np.argmin(np.abs(pts[:, 1] - 0.5))
            if ref is None:
                ref = K
            d_mid = 100 * (K[mid, 0] / ref[mid, 0] - 1)
            d_max = 100 * np.abs(K[interior, 0] / ref[interior, 0] - 1).max()
            print(f"{n:>3} {name:>13} {G.shape[1]:>8} {nnz:>9} "
                  + " ".join(f"{t:>8.2f}" for t in times)
                  + f" {its or '-':>4} {tk:>5.2f} {K[mid, 0]:>8.4f} {d_mid:>8.2f} "
                    f"{d_max:>8.2f}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
