r"""Contact on the crack faces: the multipliers on the crossed edges, up to the front.

A crack's multipliers live where those of a Γ that cuts the body through live
(:mod:`skxfem.cut`): one λ_e at the crossing x_e of every mesh edge e the crack
crosses strictly (``edge_ids`` of :class:`~skxfem.crack.geometry.CrackGeometry`; an
edge ψ_h crosses ahead of the front is not one, nor is an edge of the tip cell the
crack does not reach), and one at every mesh node the crack passes through behind
its front (ψ = 0, φ < 0; the point (v, v), edge id -1, as a vertex on Γ of a
:class:`~skxfem.cut.Cut`; :func:`skxfem.crack.geometry.crack_points`, 2D and 3D),
exactly: a crack along mesh edges, planes or quadrilaterals' diagonals (the 45° crack
of a structured mesh) has its multipliers at the nodes.
The spaces are those of :mod:`skxfem.stabilised` (naive, winner nodes = algo1, vital
edges = algo2) on the graph of the crossed edges, a node on the crack with a
multiplier of its own (:func:`skxfem.stabilised.multiplier_space`): the graph's nodes
are the ends of the crossed edges, so the tip cell's nodes beyond the front carry no
multiplier, nor does a tip at a node (the jump vanishes there); in 3D
:mod:`skxfem.crack.faces3d`.

**The multiplier functions on the faces.**  A crack piece (the part of Γ_h in one
reference triangle) may end at a point that carries no multiplier: the tip, a point
of a quadrilateral's diagonal.  The value of λ_h there is the harmonic extension of
the point values along the chain of pieces (a graph with the piece ends as vertices,
weights 1/length, the points held): linear in arc length between two points,
**constant from the last point to the tip**.  On each piece λ_h is linear between its
ends.  So every row of the map from the point λ to λ_h sums to one: a constant
traction stays in the space up to the front (the patch test), and the tip piece
carries the λ of the point it enters by.

**Vital edges at the front (what the package does; the paper leaves it open).**  The
edge cover of algo2 runs on the ends of the crossed edges only: the tip cell enters by
the edge it is crossed through (or a node on the crack), and its nodes beyond the
front get no multiplier and no vital edge; the tip piece takes the λ of its entry
point (above).  No relation is
extrapolated past the last crossing.  The inf-sup constant of these spaces near the
front is measured by :func:`skxfem.studies.cracks.crack_inf_sup` (book chapter
``crack``).

**The points next to the front share the λ behind them** (:func:`tie_front`, what the
crack kinds of Γ use under a contact law, 2D and 3D: :func:`face_multipliers`;
:mod:`skxfem.crack.faces3d` for the 3D numbers).  A
point on a mesh edge with a node within :data:`FRONT_RINGS` (2) rings of cells of a tip
cell (:func:`front_points`) carries no multiplier of its own: it takes the harmonic
extension of the others along the pieces, i.e. the λ of the nearest point behind it, and
λ_h is constant from there to the tip (as it was on the tip piece).  The jump at such a
point is made by unknowns whose equilibrium also carries the discretisation error of the
stress next to the tip; a multiplier of its own there reads that error as contact
pressure (with topological enrichment it grows like h^-½), and the interaction
integral's face term weighs it by 1/√r.  Measured on the closed inclined crack
(:func:`skxfem.studies.cracks.inclined_scene`, vital space, β = 20°, 30°, 60°, μ = 0,
0.3, 0.8, triangles and quadrilaterals, 1/h = 21, 41; 28 sliding solves per enrichment),
the worst cases before → after:
geometric enrichment, |K_I| 4.1e-3 → 3.1e-4 σ√(πa), K_II 0.52 % → 0.16 %, the mean
pressure 0.76 % → 0.08 %, the worst point 5.9 % → 1.8 %; topological enrichment
(β = 20°, 30°), |K_I| 2.9e-2 → 1.4e-2, the worst point 23 % → 3.9 %.  One ring (the
tip cells' own nodes) left |K_I| at 1.6e-3 (geometric); three rings gave 7e-4 on six of
these cases.  The inf-sup constant near the front does not fall
(:func:`skxfem.studies.cracks.crack_inf_sup`).  Within those rings the faces carry one
traction and one contact state, those of the point behind: a zone that opens there only,
shut behind, is not resolved (refine the mesh).  A crack whose every point is a front
point keeps its space.  The same code ties a 3D crack's points (:func:`piece_graph`: the
faces' sides for the segments), each then a mean of the last points behind the band,
weighted by the harmonic extension over the faces.

>>> from skfem import MeshTri1
>>> from skxfem.crack.geometry import crack_geometry
>>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
>>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.55)
>>> E = end_values(g)                               # λ at each piece end, per edge λ
>>> bool(np.allclose(E.sum(axis=1), 1.0))          # a constant is kept
True
>>> crack_multipliers("vital", m, g).P.shape        # 6 crossed edges, 3 stars
(6, 3)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components
from scipy.sparse.linalg import splu
from scipy.spatial import cKDTree

from ..multipliers import Space
from ..scene.laws import LAWS
from ..stabilised import multiplier_space
from .geometry import nearest_on_segments

__all__ = ["EdgeGraph", "edge_graph", "check_crossed", "end_values", "harmonic_extension",
           "face_functions", "crack_multipliers", "FRONT_RINGS", "front_points",
           "tie_front", "face_multipliers", "face_traction"]

FRONT_RINGS = 2
"""The points on an edge with a node within this many rings of cells of the tip cells
share the λ behind them (:func:`front_points`, :func:`tie_front`; module notes)."""


@dataclass(frozen=True)
class EdgeGraph:
    """The crossed edges of a crack as :func:`skxfem.stabilised.multiplier_space`
    reads a :class:`~skxfem.cut.Cut`: ``edge_ids``, ``edges`` (2, ne), ``psi``,
    ``points`` (2, ne), and ``facets`` (2, nf) / ``facet_cell`` (nf,): the crack
    pieces that touch a crossing, each end an index into ``points`` (an end that is
    no crossing takes the piece's other end, so that the pieces say which crossed
    edges share a cell)."""

    edge_ids: np.ndarray
    edges: np.ndarray
    psi: np.ndarray
    points: np.ndarray
    facets: np.ndarray
    facet_cell: np.ndarray


def edge_graph(geo) -> EdgeGraph:
    """The :class:`EdgeGraph` of a :class:`~skxfem.crack.geometry.CrackGeometry` or, in
    3D, of a :class:`~skxfem.crack.geometry3d.CrackGeometry3D` (its faces; a vertex that
    is no crossing takes one of its face that is, a face with none is left out).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> bool(edge_graph(crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.55)).facets.min() >= 0)
    True
    """
    f = geo.facets
    f = np.where(f >= 0, f, f.max(axis=0))               # a lone crossing: all ends
    keep = (f >= 0).all(axis=0)
    return EdgeGraph(geo.edge_ids, geo.edges, geo.psi, geo.points, f[:, keep],
                     geo.facet_cell[keep])


def check_crossed(geo) -> None:
    """Refuse a crack (2D or 3D geometry) with no point to carry a multiplier: one that
    crosses no mesh edge strictly and passes through no mesh node behind its front."""
    if geo.edge_ids.size:
        return
    cells = "tip cells" if geo.points.shape[0] == 2 else "front cells"
    raise ValueError("the crack crosses no mesh edge strictly and passes through no mesh "
                     "node behind its front, so it has no point to carry multipliers: "
                     f"contact on its faces needs a crack longer than its {cells} "
                     "(refine the mesh) or law 'free'")


def piece_graph(geo) -> tuple[np.ndarray, np.ndarray, float]:
    """The graph of a crack's pieces, 2D or 3D (``geo.pieces``: segments, or a 3D
    crack's faces): ``x`` (nv·npiece, dim) the pieces' vertices, vertex-major as
    ``geo.facets.ravel()`` (row k·npiece + s is vertex k of piece s), ``sides``
    (2, m) the pairs of rows joined by a side of a piece, and the tolerance within
    which two vertices are one (1e-9 of the longest side).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> x, sides, tol = piece_graph(crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.55))
    >>> x.shape, sides.shape                  # 6 pieces of 2 ends, 1 side each
    ((12, 2), (2, 6))
    """
    pieces = geo.pieces                                   # (npiece, nv, dim)
    npiece, nv, dim = pieces.shape
    x = np.transpose(pieces, (1, 0, 2)).reshape(-1, dim)
    k = np.arange(npiece)
    pairs = ((0, 1),) if nv == 2 else tuple((i, (i + 1) % nv) for i in range(nv))
    sides = np.hstack([np.stack([i * npiece + k, j * npiece + k]) for i, j in pairs])
    length = np.linalg.norm(x[sides[0]] - x[sides[1]], axis=1)
    return x, sides, 1e-9 * (float(length.max(initial=0.0)) or 1.0)


def end_values(geo, ends: np.ndarray | None = None) -> sp.csr_matrix:
    """(nv·npiece, ne) λ_h at the vertices of the crack pieces from the point
    multipliers, 2D or 3D (:func:`piece_graph`): row k·npiece + s is end (vertex) k of
    piece s (``geo.facets[k, s]``).  ``ends`` (nv·npiece,): the point at each vertex,
    -1 for none (default ``geo.facets.ravel()``; :func:`tie_front` frees some).

    A vertex at a point (a crossing, a node on the crack) is its λ; the others (a
    tip, a point of a quadrilateral's diagonal, a vertex on a 3D front) take the
    harmonic extension over the pieces' sides (module notes): in 2D linear in arc
    length between points, constant to a tip.  Vertices of a part of the crack that
    reaches no point get 0 (no multiplier there).

    Raises
    ------
    ValueError
        If the crack has no point (:func:`check_crossed`).
    """
    check_crossed(geo)
    x, sides, tol = piece_graph(geo)
    ends = geo.facets.ravel() if ends is None else ends
    return harmonic_extension(ends, x, sides, geo.edge_ids.size, tol)


def harmonic_extension(ends: np.ndarray, x: np.ndarray, sides: np.ndarray, ne: int,
                       tol: float) -> sp.csr_matrix:
    """(n, ne) λ_h at n points of a graph from the ``ne`` edge multipliers: a point
    with ``ends`` ≥ 0 is that crossing (its λ), the others (``ends`` = -1, merged where
    their ``x`` (n, dim) lie within ``tol``) take the harmonic extension over the
    graph's ``sides`` (2, m), pairs of points, each weighted by 1/length, the crossings
    held.  Points of a part of the graph that reaches no crossing get 0.  Every row
    reached sums to one (a constant is kept).

    >>> x = np.array([[0.0], [1.0], [3.0]])             # crossings 0, 1 and a tip
    >>> harmonic_extension(np.array([0, 1, -1]), x, np.array([[0, 1], [1, 2]]), 2,
    ...                    1e-9).toarray().tolist()     # constant from 1 to the tip
    [[1.0, 0.0], [0.0, 1.0], [0.0, 1.0]]
    """
    vertex = np.asarray(ends).copy()
    other = np.flatnonzero(vertex < 0)
    if other.size:                                       # merge equal points
        pairs = cKDTree(x[other]).query_pairs(tol, output_type="ndarray")
        link = sp.csr_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])),
                             shape=(other.size,) * 2)
        _, comp = connected_components(link, directed=False)
        vertex[other] = ne + comp
    nv = max(int(vertex.max()) + 1, ne)
    a, b = vertex[sides[0]], vertex[sides[1]]
    length = np.linalg.norm(x[sides[0]] - x[sides[1]], axis=1)
    ok = (a != b) & (length > 0)
    w = 1.0 / length[ok]
    adj = sp.csr_matrix((np.r_[w, w], (np.r_[a[ok], b[ok]], np.r_[b[ok], a[ok]])),
                        shape=(nv, nv))
    lap = (sp.diags(np.asarray(adj.sum(axis=1)).ravel()) - adj).tocsr()
    values = sp.lil_matrix((nv, ne))
    values[np.arange(ne), np.arange(ne)] = 1.0
    free = np.arange(ne, nv)
    if free.size:
        _, piece = connected_components(adj, directed=False)
        f = free[np.isin(piece[free], piece[:ne])]
        if f.size:
            Y = splu(sp.csc_matrix(lap[f][:, f])).solve(-(lap[f][:, :ne]).toarray())
            Y[np.abs(Y) < 1e-14] = 0.0
            values[f] = Y
    return sp.csr_matrix(values)[vertex]


def face_functions(geo, x: np.ndarray, piece: np.ndarray) -> sp.csr_matrix:
    """(n, ne) the multiplier functions N_e at points ``x`` (2, n) of the crack pieces
    ``piece`` (n,): linear on each piece between its :func:`end_values`."""
    E = end_values(geo)
    nseg = geo.segment_cell.size
    A, B = geo.segments[0][:, piece], geo.segments[1][:, piece]
    t = nearest_on_segments(A, B - A, x)[0]               # x lies on its piece
    return (sp.diags(1 - t) @ E[piece] + sp.diags(t) @ E[nseg + piece]).tocsr()


def crack_multipliers(name: str, mesh, geo, fixed=None, per_edge=None) -> Space:
    """The multiplier space ``name`` ("naive", "winner", "vital") on the crack's
    crossed edges and nodes (:func:`skxfem.stabilised.multiplier_space` on its
    :class:`EdgeGraph`; a node on the crack has a multiplier of its own; module notes
    for the front; a 3D crack's: :mod:`skxfem.crack.faces3d`).  ``fixed``,
    ``per_edge``: as there.

    Raises
    ------
    ValueError
        If the crack has no point (:func:`check_crossed`), or ``name`` is not a space.
    """
    check_crossed(geo)
    return multiplier_space(name, mesh, edge_graph(geo), fixed=fixed, per_edge=per_edge)


def front_points(mesh, geo, rings: int = None) -> np.ndarray:
    """(ne,) bool: the points of a crack (crossings, nodes on the crack; 2D or 3D) on a
    mesh edge with a node within ``rings`` rings of cells of the tip cells
    (:attr:`~skxfem.crack.geometry.CrackGeometry.tip_cells`, a 3D crack's front cells;
    1: their own nodes; default :data:`FRONT_RINGS`).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 11), np.linspace(0, 1, 11))
    >>> g = crack_geometry(m, m.p[1] - 0.55, m.p[0] - 0.55)   # the tip cell: x = 0.5 .. 0.6
    >>> [g.points[0, front_points(m, g, k)].round(2).tolist() for k in (1, 2)]
    [[0.45, 0.5], [0.35, 0.4, 0.45, 0.5]]
    """
    rings = FRONT_RINGS if rings is None else rings
    if not isinstance(rings, (int, np.integer)) or rings < 1:
        raise ValueError(f"rings must be an integer >= 1, got {rings!r}")
    near = np.zeros(mesh.p.shape[1], dtype=bool)
    near[mesh.t[:, geo.tip_cells]] = True
    for _ in range(rings - 1):                      # the cells with a node so far
        near[mesh.t[:, near[mesh.t].any(axis=0)]] = True
    return near[geo.edges].any(axis=0)


def tie_front(space: Space, mesh, geo) -> Space:
    """The multiplier ``space`` of a crack (2D or 3D) with its :func:`front_points` tied
    to the others (module notes): the row of P of each is the harmonic extension of the
    other points' rows over the crack pieces (:func:`end_values`; in 2D the row of the
    nearest point behind it, for a point between it and the tip; in 3D a mean of the
    last points behind, weights ≥ 0), so every row still sums to one; the columns left
    without a point are dropped, ``vital``, ``groups`` and ``winners`` follow.  A point
    whose run of pieces reaches no untied point keeps its row; so does a crack with no
    front point.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 11), np.linspace(0, 1, 11))
    >>> g = crack_geometry(m, m.p[1] - 0.55, m.p[0] - 0.55)   # points at x = 0, 0.05 .. 0.5
    >>> S = tie_front(crack_multipliers("naive", m, g), m, g)
    >>> S.P.shape, S.P[7:].indices.tolist()       # x = 0.35 .. 0.5 take the λ of 0.3
    ((11, 7), [6, 6, 6, 6])
    """
    tied = front_points(mesh, geo)
    ne = tied.size
    if not tied.any() or tied.all():
        return space
    ends = geo.facets.ravel()
    E = end_values(geo, np.where(np.isin(ends, np.flatnonzero(tied)), -1, ends))
    at = np.full(ne, -1)                          # a piece end at each point
    k = np.flatnonzero(ends >= 0)[::-1]
    at[ends[k]] = k
    i = np.flatnonzero(tied & (at >= 0))
    rows = E[at[i]]
    total = np.asarray(rows.sum(axis=1)).ravel()
    reached = (rows.getnnz(axis=1) > 0) & np.isclose(total, 1.0)   # an untied point
    i, rows, total = i[reached], rows[reached], total[reached]
    own = np.ones(ne, dtype=bool)                 # the points that keep their row
    own[i] = False
    put = sp.csr_matrix((np.ones(i.size), (i, np.arange(i.size))), shape=(ne, i.size))
    X = sp.diags(own.astype(float)) + put @ sp.diags(1 / total) @ rows   # a lone λ exactly
    P = sp.csr_matrix(X @ space.P)
    P.eliminate_zeros()
    used = np.flatnonzero(np.diff(P.tocsc().indptr) > 0)
    new = np.full(space.size, -1)
    new[used] = np.arange(used.size)
    vital = None if space.vital is None else space.vital & own
    groups = None if space.groups is None else np.where(own & (space.groups >= 0),
                                                        new[space.groups], -1)
    winners = None if space.winners is None else \
        space.winners[used[used < space.winners.size]]   # the winners' columns first
    return Space(space.name, P[:, used].tocsr(), vital, groups, winners)


def face_multipliers(law: str, name: str, mesh, geo, fixed=None, per_edge=None) -> Space:
    """The multiplier space of a crack's faces under ``law`` (2D or 3D, what the crack
    kinds of Γ use): :func:`crack_multipliers` ``name``, its :func:`front_points` tied
    to those behind them (:func:`tie_front`) for a contact law (``frictionless``,
    ``coulomb``, ``adhesive``: the faces pushed together, the points' own multipliers
    next to the front reading the stress's error there as pressure), not for a tie
    (``bonded``, ``bilateral``; and ``free``, which :func:`skxfem.lbb.inf_sup` measures
    as a tie), which holds the jump at every point: tied, it held only their weighted
    mean, and a crack bonded under tension opened near its front (2D, 21 × 21
    triangles: K_I 0.0019 → 0.024, the jump 6.5e-4 → 7.2e-3; 3D, 11³ cells: K_I 0.013
    → 0.071).  ``fixed``, ``per_edge``: as :func:`crack_multipliers`.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 11), np.linspace(0, 1, 11))
    >>> g = crack_geometry(m, m.p[1] - 0.55, m.p[0] - 0.55)
    >>> [face_multipliers(law, "naive", m, g).size for law in ("coulomb", "bonded")]
    [7, 11]
    """
    if law not in LAWS:
        raise ValueError(f"law must be one of {list(LAWS)}, got {law!r}")
    space = crack_multipliers(name, mesh, geo, fixed=fixed, per_edge=per_edge)
    return space if LAWS[law].tie else tie_front(space, mesh, geo)


def face_traction(geo, traction: np.ndarray, x_rule: np.ndarray):
    """The tractions the faces carry, for :func:`skxfem.crack.sif.sif`'s
    ``face_traction``: ``(x, side) -> (2, n)`` at the points ``x_rule`` (2, n) of
    :func:`skxfem.crack.assembly.face_rule` (the points the SIF asks at).

    ``traction`` (2, ne) is the interface traction r = σ·n at the points (the
    multipliers, :mod:`skxfem.levelset`'s sign: n into Ω⁺); on the faces r_h = Σ N_e r_e
    (:func:`face_functions`, constant to the tip), and the face of Ω⁻ (outward normal
    +n) carries t⁻ = r_h, that of Ω⁺ (outward normal -n) t⁺ = -r_h
    (:mod:`skxfem.crack.interaction`).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.assembly import face_rule
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.55)
    >>> x = face_rule(crack_space(m, g))[0]
    >>> r = np.array([[0.0], [-2.0]]) * np.ones(g.edge_ids.size)   # a pressure 2
    >>> t = face_traction(g, r, x)
    >>> bool(np.allclose(t(x, 1), [[0.0], [2.0]])), bool(np.allclose(t(x, -1), -t(x, 1)))
    (True, True)
    """
    traction = np.asarray(traction, float)
    ne = geo.edge_ids.size
    if traction.shape != (2, ne) or not np.all(np.isfinite(traction)):
        raise ValueError(f"traction must hold finite values of shape (2, {ne}) (one vector "
                         f"per point: crossed edge or node on the crack), got {traction.shape}")
    nseg = geo.segment_cell.size
    piece = np.repeat(np.arange(nseg), x_rule.shape[1] // max(nseg, 1))
    r = (face_functions(geo, x_rule, piece) @ traction.T).T      # (2, n)

    def at(x, side):
        if x.shape != x_rule.shape or not np.allclose(x, x_rule):
            raise ValueError("face_traction: asked at points that are not those of the "
                             "crack's face rule (skxfem.crack.assembly.face_rule)")
        return -side * r

    return at
