r"""Assembly on the crack's unknowns [a, b, c]: stiffness, surface loads, supports.

The stiffness
-------------
With B the strain of every unknown's basis function at the points of a rule
(:func:`skxfem.crack.space.evaluation`: ε₁₁, ε₂₂, ε₁₂ rows) and W their weights,

.. math:: K = K_0 + \sum_{\text{groups}} B^\mathsf{T} \, W C\, B ,

K₀ the standard stiffness of the cells no enriched function reaches (scikit-fem's
forms, :func:`skxfem.fem.material.stiffness_matrix`, at the exact rule), and the sum
over the cells of the enriched nodes' supports, each with the rule it needs
(:func:`rule_groups`): the tip cells with the almost-polar rule, the split cells on
their sub-triangles, the uncut cells of a branch node's support at
:data:`skxfem.crack.quadrature.BRANCH_ORDER`, the others at the exact rule.  (A
``BilinearForm`` per pair of the six kinds of :mod:`skxfem.crack.space`, 20 pairs on
each group, took 10 s on the Williams square at h = 1/41; the products BᵀWCB, 0.5 s.)

Loads and supports
------------------
A traction t on boundary facets: f = ∫ t · v over each facet, split where the crack
meets it (the mouth) so that H is one value on each piece, with a Gauss rule of
:data:`FACET_POINTS` points per piece (the branch functions are not polynomials).

**Imposed displacements (what the package does at a crack mouth).**  A support
imposes the standard unknowns aᵢ = g(xᵢ) of its nodes, for its components.  The
shifted enrichments vanish at the nodes, so u_h(xᵢ) = g(xᵢ).  A Heaviside function
φⱼ(H - Hⱼ) also vanishes on every facet the crack does not meet (H = Hⱼ there): its
unknowns are not constrained there.  A branch function φ_k(F_l - F_l(x_k)) does not
vanish along a facet: on a node whose supported facets the crack does not meet, its
branch unknowns are set to zero (the trace is then the interpolant of g).  On a
facet the crack meets (the mouth) it depends on g, component by component, tested
across the crack at the facet's crossings (:func:`_shut_mouth`):

* g **continuous** there (a clamp, rollers, a rigid motion, any smooth formula): the
  support clamps the mouth shut, every enriched unknown of the facet's nodes (Heaviside
  and branch) set to zero, so that its trace is the interpolant of g on both faces, and
  a supported node on the crack itself takes g too.  (Until 29 November 2026 the mouth
  stayed free whatever g: the crack chapter's edge crack, its mouth on a clamped face,
  pulled open, h = 1/21, opened there by (0.0053, -0.0058) with K_I 0.755 against 0.750
  now, and ``examples/crack.toml``'s contact pressure was 1.072 there instead of 1.)
* g **discontinuous** across the crack (the exact near-tip field, say): the mouth stays
  free, the data imposed at the nodes only, and a supported node on the crack (ψ = 0,
  φ < 0: a mouth through a node), which has two values, one per face, is left free (a
  discontinuous g at a mouth is better imposed as a traction, as code_aster's SSLP114
  does).  Measured on the Williams square with the exact displacement imposed on all
  four faces (the cut face too): K within 0.41 % (geometric, h = 1/21, mouth
  mid-facet) and 0.35 % (h = 1/20, mouth at a node); imposing the Ω⁺ value at that node
  instead gave errors of 1 to 3.5 %.

A nodal support (``nodes``) imposes the nodal values only: it never clamps a mouth.

>>> from skfem import MeshTri1
>>> from skxfem.crack.geometry import crack_geometry
>>> from skxfem.crack.space import crack_space
>>> from skxfem.fem.material import Material
>>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
>>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
>>> K = stiffness(V, Material(1.0, 0.3))
>>> K.shape == (V.N, V.N), bool(abs(K - K.T).max() < 1e-12)
(True, True)
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.polynomial.legendre import leggauss
from numpy.typing import ArrayLike
from skfem import Basis

from ..fem.loads import force_field
from ..fem.material import Material, stiffness_matrix
from ..fem.quadrature import cell_rule, exact_orders, subcell_rule
from .quadrature import (
    BRANCH_ORDER,
    NEAR_ORDER,
    near_rule,
    near_tip_cells,
    split_rule,
    tip_rule,
)
from .space import CrackSpace, evaluation

__all__ = ["FACET_POINTS", "RuleGroup", "rule_groups", "stiffness", "coupling",
           "cut_coupling", "mass",
           "Support",
           "Load", "facet_pieces", "traction_load", "face_rule", "face_load",
           "body_load", "supported_dofs", "support_dofs", "dependent_dofs", "mouth_facets",
           "check_facets"]

FACET_POINTS = 8
"""Gauss points on each piece of a loaded boundary facet."""


@dataclass(frozen=True)
class RuleGroup:
    """Cells integrated by one per-cell rule: the ``scalar`` basis on them (its
    quadrature the rule), ``side`` (nel, nqp) the side of each point (None: the cells'
    own side, ``cell_side``)."""

    scalar: Basis
    side: np.ndarray | None
    cell_side: np.ndarray

    def points(self):
        """The points of non-zero weight: cells (n,), reference coordinates (2, n), sides
        (n,), physical coordinates (2, n) and weights dx (n,)."""
        b = self.scalar
        live = b.dx != 0                                  # a rule may weigh a point < 0
        cells = np.broadcast_to(b.tind[:, None], live.shape)[live]
        X = b.X if b.X.ndim == 3 else np.broadcast_to(b.X[:, None], (2,) + live.shape)
        side = self.side if self.side is not None else np.broadcast_to(
            self.cell_side[:, None], live.shape)
        x = b.mapping.F(X[:, live][:, :, None], tind=cells)[:, :, 0]
        return cells, X[:, live], side[live], x, b.dx[live]


def _group(space: CrackSpace, cells: np.ndarray, X, W, side=None) -> RuleGroup:
    mesh = space.mesh
    scalar = Basis(mesh, mesh.elem(), elements=cells, quadrature=(X, W))
    return RuleGroup(scalar, side, space.geometry.side[cells])


def rule_groups(space: CrackSpace, cells: np.ndarray | None = None,
                order: int = BRANCH_ORDER, plain_order: int | None = None
                ) -> tuple[RuleGroup, ...]:
    """The rule groups covering ``cells`` (default: the supports of the enriched nodes).

    Tip cells: :func:`skxfem.crack.quadrature.tip_rule`; the other cells by the
    order of their integrand: around the tip cells (sharing a node with one)
    :data:`~skxfem.crack.quadrature.NEAR_ORDER`, or, within
    :data:`~skxfem.crack.quadrature.NEAR_GAP` of a tip,
    :func:`~skxfem.crack.quadrature.near_rule`; touching a branch node ``order``;
    else ``plain_order`` (default: the exact stiffness order).  Split cells on their
    sub-triangles, uncut cells on the whole cell.
    """
    mesh, geo = space.mesh, space.geometry
    if cells is None:
        cells = space.support_cells(space.enriched_nodes())
    cells = np.unique(cells)
    nc = mesh.t.shape[1]
    level = np.zeros(nc, dtype=int)                       # 0 plain, 1 branch, 2 near tip
    level[space.support_cells(space.branch)] = 1
    level[space.support_cells(np.unique(mesh.t[:, geo.tip_cells]))] = 2
    cell_o, sub_o = exact_orders(mesh)
    plain = cell_o if plain_order is None else plain_order
    sub_plain = sub_o if plain_order is None else plain_order
    orders = {0: (sub_plain, plain), 1: (order, order), 2: (NEAR_ORDER, NEAR_ORDER)}
    groups = []
    tip = np.intersect1d(cells, geo.tip_cells)
    if tip.size:
        r = tip_rule(geo, NEAR_ORDER)
        pick = np.isin(r.cells, tip)
        groups.append(_group(space, r.cells[pick], r.X[:, pick], r.W[pick], r.V[pick]))
    near = near_tip_cells(geo, mesh, np.setdiff1d(cells[level[cells] == 2], tip))
    if near.size:
        r = near_rule(geo, mesh, near)
        groups.append(_group(space, r.cells, r.X, r.W, r.V))
    split = np.setdiff1d(np.intersect1d(cells, geo.split_cells), np.union1d(tip, near))
    uncut = np.setdiff1d(np.setdiff1d(cells, geo.cells), near)
    for lv, (o_sub, o_cell) in orders.items():
        here = split[level[split] == lv]
        if here.size:
            r = split_rule(geo, here, o_sub)
            groups.append(_group(space, r.cells, r.X, r.W, r.V))
        here = uncut[level[uncut] == lv]
        if here.size:
            X, W = cell_rule(mesh, o_cell)
            groups.append(_group(space, here, X, W))
    return tuple(groups)


def stiffness(space: CrackSpace, material: Material) -> sp.csr_matrix:
    """The stiffness ∫ σ(u):ε(v) on the unknowns [a, b, c] (module notes).

    >>> from skfem import MeshQuad1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshQuad1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5), "topological")
    >>> U = np.zeros(V.N); U[V.basis.nodal_dofs[0]] = 1.0      # a rigid translation
    >>> bool(abs(stiffness(V, Material(1.0, 0.3)) @ U).max() < 1e-12)
    True
    """
    if not isinstance(material, Material):
        raise ValueError(f"material must be a skxfem Material, got {type(material).__name__}")
    mesh = space.mesh
    lam, mu = material.lame(2)
    near = space.support_cells(space.enriched_nodes())
    rest = np.setdiff1d(np.arange(mesh.t.shape[1]), near)
    K = sp.csr_matrix((space.N, space.N))
    if rest.size:
        Ks = stiffness_matrix(material, Basis(mesh, mesh.elem(), elements=rest,
                                              quadrature=cell_rule(mesh)))
        K = sp.block_diag([Ks, sp.csr_matrix((space.N - space.n_std,) * 2)], format="csr")
    for G in rule_groups(space, near):
        cells, ref, side, _, w = G.points()
        B = evaluation(space, cells, ref, side).grad     # rows (2 i + j) npts + p
        K = K + _strain_energy(B, B, w, lam, mu)
    return K.tocsr()


def _strain_energy(Bu: sp.csr_matrix, Bv: sp.csr_matrix, w: np.ndarray, lam: float,
                   mu: float) -> sp.csr_matrix:
    """∫ σ(u):ε(v) on the points of weights w, from the gradient operators Bu, Bv (rows
    (2 i + j) npts + p, :func:`skxfem.crack.space.evaluation`): rows Bv's columns."""
    n = w.size
    u11, u22, u12 = Bu[:n], Bu[3 * n:], (Bu[n:2 * n] + Bu[2 * n:3 * n]) / 2
    v11, v22, v12 = Bv[:n], Bv[3 * n:], (Bv[n:2 * n] + Bv[2 * n:3 * n]) / 2
    W = sp.diags(w)
    return (v11.T @ W @ ((lam + 2 * mu) * u11 + lam * u22)
            + v22.T @ W @ ((lam + 2 * mu) * u22 + lam * u11)
            + 4 * mu * (v12.T @ W @ u12))


def coupling(space: CrackSpace, other: CrackSpace, material: Material) -> sp.csr_matrix:
    """The stiffness between the enrichments of two cracks of one scene: ∫ σ(u):ε(v), v
    on ``space``'s enriched unknowns (rows), u on ``other``'s (columns), an
    (N - n_std, N_other - n_std) block.

    A crack's branch functions reach r_e from its tip, past its own cells: where two
    cracks' enriched supports share cells their enrichments interact, and the whole
    stiffness holds this block (and its transpose) between them.  Each shared cell on
    the rules of the crack that cuts it or whose tip it is near (:func:`rule_groups`: the
    almost-polar rule, sub-triangles), the others on the other crack's rules at least at
    the branch functions' order.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 12), np.linspace(0, 1, 12))
    >>> a = crack_space(m, crack_geometry(m, m.p[1] - 0.3, m.p[0] - 0.45), "geometric", 0.4)
    >>> b = crack_space(m, crack_geometry(m, m.p[1] - 0.7, m.p[0] - 0.45), "geometric", 0.4)
    >>> C = coupling(a, b, Material(1.0, 0.3))
    >>> C.shape == (a.N - a.n_std, b.N - b.n_std), bool(abs(C).max() > 0)
    (True, True)
    >>> bool(abs(coupling(b, a, Material(1.0, 0.3)) - C.T).max() < 1e-12)
    True
    """
    mesh = space.mesh
    lam, mu = material.lame(2)
    shared = np.intersect1d(space.support_cells(space.enriched_nodes()),
                            other.support_cells(other.enriched_nodes()))
    block = sp.csr_matrix((space.N - space.n_std, other.N - other.n_std))
    if not shared.size:
        return block
    check_distinct(space, other)

    def own(V):                     # its cut cells and the cells around its tip cells
        near = V.support_cells(np.unique(mesh.t[:, V.geometry.tip_cells]))
        return np.union1d(np.flatnonzero(V.geometry.side == 0), near)

    mine = np.setdiff1d(np.intersect1d(shared, own(space)),
                        np.flatnonzero(other.geometry.side == 0))
    for first, cells in ((space, mine), (other, np.setdiff1d(shared, mine))):
        if not cells.size:
            continue
        for G in rule_groups(first, cells, plain_order=BRANCH_ORDER):
            c, ref, side, _, w = G.points()
            sv, su = (side, None) if first is space else (None, side)   # cut by first
            Bv = evaluation(space, c, ref, sv).grad[:, space.n_std:]
            Bu = evaluation(other, c, ref, su).grad[:, other.n_std:]
            block = block + _strain_energy(Bu, Bv, w, lam, mu)
    return block.tocsr()


def check_distinct(space: CrackSpace, other: CrackSpace, tol: float = 1e-12) -> None:
    """Refuse two cracks whose branch functions coincide on a node both enrich.

    The branch functions are functions of the level sets (φ_h, ψ_h) of their crack; on a
    node k whose support holds the same nodal ψ and φ for both cracks (to ``tol`` of
    their range), φ_k (F_l - F_l(x_k)) is the same function for both, and the stiffness
    is singular (LU pivot 2e-33).  A broken ring written as two cracks on one ψ = |x - c| -
    R with the fronts φ = max(|y - c_y| - d, ±(c_x - x)), equal above and below the
    ring, did that.  The message names the nodes and the cure.

    >>> from skfem import MeshQuad1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshQuad1.init_tensor(*(np.linspace(0, 1, 9),) * 2)
    >>> def crack(y):                      # an edge crack on y to x = 0.45, r_e = 0.3
    ...     return crack_space(m, crack_geometry(m, m.p[1] - y, m.p[0] - 0.45), radius=0.3)
    >>> check_distinct(crack(0.3), crack(0.7))
    >>> check_distinct(crack(0.3), crack(0.3))
    Traceback (most recent call last):
    ...
    ValueError: two cracks give 16 node(s) (e.g. (0.25, 0.125)) the same branch ...
    """
    mesh, ga, gb = space.mesh, space.geometry, other.geometry
    common = np.intersect1d(space.branch, other.branch)
    if not common.size:
        return
    scale = max(np.ptp(ga.psi), np.ptp(ga.phi), np.ptp(gb.psi), np.ptp(gb.phi))
    differ = ((np.abs(ga.psi - gb.psi) > tol * scale)
              | (np.abs(ga.phi - gb.phi) > tol * scale))[mesh.t].any(axis=0)   # per cell
    near = np.zeros(mesh.p.shape[1], dtype=bool)          # a node of a cell that differs
    near[mesh.t[:, differ].ravel()] = True
    same = ~near[common]
    if same.any():
        x = ", ".join(f"{v:.4g}" for v in mesh.p[:, common[same][0]])
        raise ValueError(
            f"two cracks give {int(same.sum())} node(s) (e.g. ({x})) the same branch "
            f"functions: their level sets psi and phi (the front) are equal over those "
            f"nodes' supports, so the stiffness is singular; give each crack a front phi "
            f"of its own there (e.g. phi vanishing on the rays through its own tips), or "
            f"enrichment_radius small enough that the enriched zones stop short of where "
            f"the level sets agree")


def cut_coupling(space: CrackSpace, other, material: Material) -> sp.csr_matrix:
    """The stiffness between a crack's enrichment (rows) and the Heaviside enrichment of
    a cut interface of the same scene (``other``, a :class:`skxfem.enrich.XSpace`;
    columns): an (N - n_std, other.n_enr) block.

    The cut's shifted enrichment φⱼ(H - Hⱼ) lives on its cut cells only, and there the
    crack's own Heaviside enrichment is zero (no cell is cut by two interfaces): the
    block is the crack's branch functions against it, on the cut's sub-triangles of each
    side (H = ±1 there) at the branch functions' order.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> from skxfem.cut import cut
    >>> from skxfem.enrich import xfem_space
    >>> from skxfem.levelset import plane
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 12), np.linspace(0, 1, 12))
    >>> a = crack_space(m, crack_geometry(m, m.p[1] - 0.3, m.p[0] - 0.45), "geometric", 0.4)
    >>> b = xfem_space(m, cut(m, plane((0, 0.62), (0, 1))))
    >>> C = cut_coupling(a, b, Material(1.0, 0.3))
    >>> C.shape == (a.N - a.n_std, b.n_enr), bool(abs(C).max() > 0)
    (True, True)
    """
    mesh, ocut = space.mesh, other.cut
    lam, mu = material.lame(2)
    block = sp.csr_matrix((space.N - space.n_std, other.n_enr))
    shared = np.intersect1d(space.support_cells(space.branch), ocut.cells)
    column = np.full(other.n_std, -1)
    column[other.enr_dofs] = np.arange(other.n_enr)
    H = np.asarray(other.H_node, float)
    for s in (-1.0, 1.0):
        sub = np.flatnonzero((ocut.sub_side == s) & np.isin(ocut.sub_cell, shared))
        if not sub.size:
            continue
        rule = subcell_rule(ocut.sub_ref[sub], np.arange(sub.size), BRANCH_ORDER)
        b = Basis(mesh, mesh.elem(), elements=ocut.sub_cell[sub], quadrature=(rule.X, rule.W))
        live = b.dx != 0
        cells = np.broadcast_to(b.tind[:, None], live.shape)[live]
        ref = rule.X[:, live]
        Bv = evaluation(space, cells, ref).grad[:, space.n_std:]
        n = cells.size
        rows, cols, vals = [], [], []
        for k in range(b.Nbfun):                          # φⱼ (s - Hⱼ) eᶜ: its gradient
            dN = np.asarray(b.basis[k][0].grad)[:, live]  # (2, n)
            node = mesh.t[k, cells]
            for c in range(2):
                e = column[other.basis.nodal_dofs[c, node]]
                ok = e >= 0
                for j in range(2):
                    rows.append((2 * c + j) * n + np.flatnonzero(ok))
                    cols.append(e[ok])
                    vals.append(dN[j, ok] * (s - H[e[ok]]))
        Bu = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                           shape=(4 * n, other.n_enr))
        block = block + _strain_energy(Bu, Bv, b.dx[live], lam, mu)
    return block.tocsr()


def mass(space: CrackSpace) -> sp.csr_matrix:
    """The mass ∫ u·v on the unknowns [a, b, c] (the inf-sup test's displacement norm,
    :mod:`skxfem.lbb`): every cell on the rules of :func:`rule_groups` (the tip cells on
    the almost-polar rule, the split cells on their sub-triangles), the plain cells at
    order 4 (exact for P1 and Q1 on affine cells).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> U = np.zeros(V.N); U[V.basis.nodal_dofs[1]] = 1.0      # u = (0, 1)
    >>> round(float(U @ mass(V) @ U), 12)                      # the area
    1.0
    """
    M = sp.csr_matrix((space.N, space.N))
    for G in rule_groups(space, np.arange(space.mesh.t.shape[1]), plain_order=4):
        cells, ref, side, _, w = G.points()
        E = evaluation(space, cells, ref, side).value     # rows (component) npts + p
        n = cells.size
        W = sp.diags(w)
        M = M + E[:n].T @ W @ E[:n] + E[n:].T @ W @ E[n:]
    return M.tocsr()


def body_load(space: CrackSpace, force, order: int = 4) -> np.ndarray:
    """f = ∫ b · v over the body, on the unknowns [a, b, c]: every cell on the rules of
    :func:`rule_groups` (the tip cells on the almost-polar rule, the split cells on
    their sub-triangles, each with its side's H and θ), the plain cells at ``order``
    (4: exact for a linear b on P1 and Q1 cells).  ``force``:
    :func:`skxfem.fem.loads.force_field`'s.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> f = body_load(V, (0.0, -2.0))
    >>> round(float(f[V.basis.nodal_dofs[1]].sum()), 12)     # the weight, -2 × area 1
    -2.0
    """
    b = force_field(force, 2)
    f = np.zeros(space.N)
    for G in rule_groups(space, np.arange(space.mesh.t.shape[1]), plain_order=order):
        cells, ref, side, x, w = G.points()
        E = evaluation(space, cells, ref, side).value     # rows (component) npts + p
        f += E.T @ (b(x) * w).ravel()
    return f


@dataclass(frozen=True)
class Support:
    """Imposed displacements: on the nodes of boundary ``facets`` (indices into
    ``mesh.facets``) and/or on ``nodes``, u_c = ``value(x)[c]`` for c in ``components``
    (``value``: (2, n) points -> (2, n); None: zero)."""

    facets: ArrayLike | None = None
    nodes: ArrayLike | None = None
    value: Callable | None = None
    components: tuple = (0, 1)


@dataclass(frozen=True)
class Load:
    """A traction on boundary ``facets``: ``traction(x)`` (2, n) at points x (2, n)."""

    facets: ArrayLike
    traction: Callable


def check_facets(mesh, facets, name: str) -> np.ndarray:
    """``facets`` as indices of boundary facets of ``mesh``, else a ValueError naming
    ``name``."""
    f = np.asarray(facets)
    if f.ndim != 1 or (f.size and (f.dtype.kind not in "iu" or f.min() < 0
                                   or f.max() >= mesh.facets.shape[1])):
        raise ValueError(f"{name} must be indices into mesh.facets (0 .. "
                         f"{mesh.facets.shape[1] - 1}), got {f!r:.60}")
    if f.size and not np.all(mesh.f2t[1, f] == -1):
        raise ValueError(f"{name} must be boundary facets; {int((mesh.f2t[1, f] >= 0).sum())}"
                         f" of them lie inside the mesh")
    return f.astype(int)


def _crossing(space: CrackSpace, facets: np.ndarray):
    """For each facet: where along it (t ∈ [0, 1]) ψ_h vanishes, and whether the crack
    meets it there (ψ changes sign or vanishes, φ < 0 at that point)."""
    geo = space.geometry
    a, b = space.mesh.facets[:, facets]
    pa, pb = geo.psi[a], geo.psi[b]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(pa != pb, pa / (pa - pb), 0.5)
    f_at = geo.phi[a] + np.clip(t, 0, 1) * (geo.phi[b] - geo.phi[a])
    both_zero = (pa == 0) & (pb == 0)                     # a facet along the crack
    f_at = np.where(both_zero, np.minimum(geo.phi[a], geo.phi[b]), f_at)
    return np.clip(t, 0, 1), (pa * pb <= 0) & (f_at < 0)


def mouth_facets(space: CrackSpace, facets: ArrayLike) -> np.ndarray:
    """The boundary ``facets`` the crack meets (the mouth), a boolean per facet.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> f = m.facets_satisfying(lambda x: x[0] < 1e-12)
    >>> m.p[:, m.facets[:, f[mouth_facets(V, f)]].ravel()].T.tolist()
    [[0.0, 0.4], [0.0, 0.6000000000000001]]
    """
    f = check_facets(space.mesh, facets, "facets")
    return _crossing(space, f)[1]


def facet_pieces(space: CrackSpace, facets: ArrayLike, points: int = FACET_POINTS):
    """A rule on boundary facets cut at the crack: points (2, n), weights (n,), their
    cells (n,), reference coordinates (2, n), sides (n,).

    Each facet is cut into two pieces at the point where ψ_h vanishes if the crack
    meets it there, else at its midpoint; each piece holds ``points`` Gauss points."""
    mesh = space.mesh
    f = check_facets(mesh, facets, "facets")
    t_cut, meets = _crossing(space, f)
    t_cut = np.where(meets, t_cut, 0.5)
    s, w = leggauss(points)
    s, w = (s + 1) / 2, w / 2
    a, b = mesh.p[:, mesh.facets[0, f]], mesh.p[:, mesh.facets[1, f]]
    length = np.linalg.norm(b - a, axis=0)
    ts = np.concatenate([t_cut[:, None] * s, t_cut[:, None] + (1 - t_cut)[:, None] * s],
                        axis=1)                           # (nf, 2 points)
    ws = np.concatenate([t_cut[:, None] * w, (1 - t_cut)[:, None] * w], axis=1)
    x = a[:, :, None] + ts[None] * (b - a)[:, :, None]      # (2, nf, 2 points)
    psi = space.geometry.psi
    pa, pb = psi[mesh.facets[0, f]], psi[mesh.facets[1, f]]
    ps = pa[:, None] + ts * (pb - pa)[:, None]
    side = np.where(ps < 0, -1.0, 1.0)
    cells = np.repeat(mesh.f2t[0, f], 2 * points)
    xf = x.reshape(2, -1)
    ref = mesh.mapping().invF(xf[:, :, None], tind=cells)[:, :, 0]
    return xf, (ws * length[:, None]).ravel(), cells, ref, side.ravel()


def traction_load(space: CrackSpace, loads) -> np.ndarray:
    """f = Σ ∫ t · v over the loads' facets, on the unknowns [a, b, c] (module notes).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> top = m.facets_satisfying(lambda x: x[1] > 1 - 1e-12)
    >>> f = traction_load(V, [Load(top, lambda x: np.stack([0 * x[0], 1 + 0 * x[0]]))])
    >>> round(float(f[V.basis.nodal_dofs[1]].sum()), 12)    # the resultant, 1 × length 1
    1.0
    """
    f = np.zeros(space.N)
    for load in loads:
        x, w, cells, ref, side = facet_pieces(space, load.facets)
        t = np.asarray(load.traction(x), float)
        if t.shape != x.shape or not np.all(np.isfinite(t)):
            raise ValueError(f"a load's traction must return finite values of shape "
                             f"{x.shape} (2, n), got {t.shape}")
        E = evaluation(space, cells, ref, side)
        f += E.value.T @ (t * w).ravel()
    return f


def face_rule(space: CrackSpace, points: int = FACET_POINTS):
    """Gauss points on the crack pieces of the geometry: points (2, n), weights (n,),
    cells (n,), reference coordinates (2, n); the same for both faces.

    On a piece that ends at a tip T the integrands hold √r (the branch functions) or
    1/√r (the auxiliary strain of the SIF's face term): there x = T + s²(P - T), so that
    r^{k/2} ds becomes a polynomial in s (as the almost-polar rule does in the tip cell).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> x, w, _, _ = face_rule(V)
    >>> bool(abs(w @ (1 / np.sqrt(0.5 - x[0])) - 2 * np.sqrt(0.5)) < 1e-12)  # ∫ 1/√r
    True
    """
    geo, mesh = space.geometry, space.mesh
    s, w = leggauss(points)
    s, w = (s + 1) / 2, w / 2
    A, B = geo.segments[0].copy(), geo.segments[1].copy()  # (2, nseg)
    L = np.linalg.norm(B - A, axis=0)

    def near(P):                                          # ends (2, nseg) at a tip
        d = np.linalg.norm(P[:, :, None] - geo.tips[:, None], axis=0)
        return (d <= 1e-9 * L[:, None]).any(axis=1)

    at_b = near(B)
    A[:, at_b], B[:, at_b] = B[:, at_b], A[:, at_b].copy()  # the tip end first
    tip = near(A)
    t = np.where(tip[:, None], s ** 2, s)                  # (nseg, points)
    dt = np.where(tip[:, None], 2 * s * w, w)
    x = (A[:, :, None] + t * (B - A)[:, :, None]).reshape(2, -1)
    wts = (L[:, None] * dt).ravel()
    cells = np.repeat(geo.segment_cell, points)
    ref = mesh.mapping().invF(x[:, :, None], tind=cells)[:, :, 0]
    return x, wts, cells, ref


def face_load(space: CrackSpace, face_traction: Callable) -> np.ndarray:
    """f = Σ_± ∫_{face ±} t± · v± ds: the load of tractions on the crack faces.

    ``face_traction(x, side)`` gives t = σ·m* (2, n) on the face of ``side`` (+1: the
    face of Ω⁺, whose outward normal is m* = -n; -1: that of Ω⁻, m* = +n); a pressure p
    in the crack is t = -p m*, i.e. ``side * p * n``.  The test functions are taken on
    the face's own side (H = ±1, θ = ±π).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
    >>> f = face_load(V, lambda x, side: np.stack([0 * x[0], side + 0 * x[0]]))  # p = 1
    >>> round(float(f[V.basis.nodal_dofs[1]].sum()), 12)      # pressures balance
    0.0
    """
    x, w, cells, ref = face_rule(space)
    f = np.zeros(space.N)
    for side in (1, -1):
        t = np.asarray(face_traction(x, side), float)
        if t.shape != x.shape or not np.all(np.isfinite(t)):
            raise ValueError(f"face_traction must return finite values of shape {x.shape} "
                             f"(2, n), got {t.shape}")
        E = evaluation(space, cells, ref, np.full(cells.size, float(side)))
        f += E.value.T @ (t * w).ravel()
    return f


def supported_dofs(space: CrackSpace, supports) -> tuple[np.ndarray, np.ndarray]:
    """The constrained unknowns and their values (module notes: what a support does at a
    crack mouth).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5)
    >>> V = crack_space(m, g, enrichment="topological")       # the tip cells' nodes
    >>> left = m.facets_satisfying(lambda x: x[0] < 1e-12)
    >>> D, g = supported_dofs(V, [Support(left)])                 # u = 0: a clamp
    >>> D.size, bool(np.isin(V.heaviside_dofs(), D).any())      # mouth clamped shut
    (16, True)
    >>> jumps = Support(left, value=lambda x: np.stack([np.sign(x[1] - 0.5), 0 * x[0]]))
    >>> D, g = supported_dofs(V, [jumps])
    >>> bool(np.isin(V.heaviside_dofs()[:, 0], D).any())        # x: its mouth left free
    False
    """
    return support_dofs(space, supports, lambda f: _crossing(space, f)[1])


def support_dofs(space, supports, mouth: Callable[[np.ndarray], np.ndarray]
                 ) -> tuple[np.ndarray, np.ndarray]:
    """The constrained unknowns and their values of ``supports`` on a crack's ``space``
    in 2D or 3D (:func:`supported_dofs`,
    :func:`skxfem.crack.space3d.supported_dofs`): the standard unknowns of the
    supported nodes, and the branch unknowns of supported nodes away from the mouth set
    to zero; at the mouth, where the support's value is continuous across the crack
    (:func:`_shut_mouth`), the enriched unknowns of its nodes are set to zero too and a
    node on the crack (ψ = 0 and φ < 0) takes the value, else they stay free and such a
    node, which has two values, is left free (module notes); when every node is a branch node, the
    branch unknowns of :func:`dependent_dofs` are set to zero too (the system is
    singular otherwise).  ``mouth(facets)``: whether the crack meets each of the checked
    boundary ``facets``.
    """
    mesh, geo = space.mesh, space.geometry
    d = mesh.dim()
    nd = space.nodal_dofs
    branch_of = np.full(mesh.p.shape[1], -1)
    branch_of[space.branch] = np.arange(space.branch.size)
    heaviside_of = np.full(mesh.p.shape[1], -1)
    heaviside_of[space.heaviside] = np.arange(space.heaviside.size)
    cd, hd = space.branch_dofs(), space.heaviside_dofs()
    dofs, vals = [], []
    for k, s in enumerate(supports):
        comps = np.asarray(s.components, dtype=int)
        if comps.size == 0 or not np.all(np.isin(comps, tuple(range(d)))):
            raise ValueError(f"supports[{k}].components must be among {tuple(range(d))}, "
                             f"got {s.components!r}")
        nodes, clamp, shut = [], [], [np.zeros(0, int)] * d
        if s.facets is not None:
            f = check_facets(mesh, s.facets, f"supports[{k}].facets")
            fn = np.unique(mesh.facets[:, f])
            at = mouth(f)
            nodes.append(fn)
            clamp.append(np.setdiff1d(fn, np.unique(mesh.facets[:, f[at]])))
            shut = _shut_mouth(mesh, geo.psi, geo.phi, mesh.facets[:, f[at]], s.value, d)
        if s.nodes is not None:
            nn = np.asarray(s.nodes)
            if nn.ndim != 1 or nn.dtype.kind not in "iu" or (
                    nn.size and (nn.min() < 0 or nn.max() >= mesh.p.shape[1])):
                raise ValueError(f"supports[{k}].nodes must be node indices, got {nn!r:.60}")
            nodes.append(nn.astype(int))
        nodes = np.unique(np.concatenate(nodes)) if nodes else np.zeros(0, int)
        on_crack = (geo.psi[nodes] == 0) & (geo.phi[nodes] < 0)
        x = mesh.p[:, nodes]
        g = np.zeros_like(x) if s.value is None else np.asarray(s.value(x), float)
        if g.shape != x.shape or not np.all(np.isfinite(g)):
            raise ValueError(f"supports[{k}].value must return finite values of shape "
                             f"{x.shape} ({d}, n), got {g.shape}")
        clamp = np.concatenate(clamp) if clamp else np.zeros(0, int)
        for c in comps:
            # a node on the crack has a value per face: one only where the mouth is shut
            here = ~on_crack | np.isin(nodes, shut[c])
            kb = branch_of[np.union1d(clamp, shut[c])]
            kh = heaviside_of[shut[c]]
            kb, kh = kb[kb >= 0], kh[kh >= 0]
            dofs += [nd[c, nodes[here]], cd[kb][:, :, c].ravel(), hd[kh, c]]
            vals += [g[c, here], np.zeros(kb.size * 4 + kh.size)]
    D, first = np.unique(np.concatenate(dofs or [np.zeros(0, int)]), return_index=True)
    g = np.concatenate(vals or [np.zeros(0)])[first]
    dep = dependent_dofs(space, D)
    return np.concatenate([D, dep]), np.concatenate([g, np.zeros(dep.size)])


def _shut_mouth(mesh, psi: np.ndarray, phi: np.ndarray, facets: np.ndarray, value,
                d: int) -> list[np.ndarray]:
    """Per component (d arrays), the nodes of the mouth ``facets`` (nodes per facet, nf)
    where the imposed ``value`` (None: zero) is continuous across the crack: there the
    support clamps the mouth shut.

    The test, at each crossing x_c of a facet's side with ψ_h = 0 behind the front
    (φ_h < 0; e the side's unit direction from ψ < 0 to ψ > 0): the jump
    J(δ) = g(x_c + δe) - g(x_c - δe) at δ = 1e-3 h and 1e-6 h (h the side's length).
    A continuous g has J → 0 with δ; a discontinuous one keeps its jump: it is one where
    |J(1e-6 h)| > ½ |J(1e-3 h)| and above 1e-12 of g's size."""
    if facets.shape[1] == 0:
        return [np.zeros(0, int)] * d
    pairs = [(i, j) for i in range(facets.shape[0]) for j in range(i + 1, facets.shape[0])]
    a = np.concatenate([facets[i] for i, _ in pairs])
    b = np.concatenate([facets[j] for _, j in pairs])
    owner = np.tile(np.arange(facets.shape[1]), len(pairs))
    lo, hi = np.where(psi[a] <= psi[b], a, b), np.where(psi[a] <= psi[b], b, a)
    crossed = (psi[lo] <= 0) & (psi[hi] >= 0) & (psi[lo] < psi[hi])
    lo, hi, owner = lo[crossed], hi[crossed], owner[crossed]
    t = psi[lo] / (psi[lo] - psi[hi])
    behind = phi[lo] + t * (phi[hi] - phi[lo]) < 0
    lo, hi, owner, t = lo[behind], hi[behind], owner[behind], t[behind]
    xa, xb = mesh.p[:, lo], mesh.p[:, hi]
    xc = xa + t * (xb - xa)
    length = np.linalg.norm(xb - xa, axis=0)
    e = (xb - xa) / length

    def g(x):
        return np.zeros_like(x) if value is None else np.asarray(value(x), float)

    def jump(delta):
        return np.abs(g(xc + delta * length * e) - g(xc - delta * length * e))

    coarse, fine = jump(1e-3), jump(1e-6)
    size = np.abs(g(xc)).max(initial=0.0)
    broken = (fine > 0.5 * coarse) & (fine > 1e-12 * max(size, 1e-300))   # (d, n)
    # a facet with no crossing behind the front stays open
    return [np.unique(facets[:, np.setdiff1d(owner, owner[broken[c]])]) for c in range(d)]


def dependent_dofs(space, fixed: np.ndarray) -> np.ndarray:
    r"""The branch unknowns that are linear combinations of the others when every node of
    the mesh is a branch node, to be set to zero (which leaves the space unchanged).

    The four branch functions of (r, θ), the polar coordinates of (φ_h, ψ_h), satisfy at
    every point

    .. math:: \psi_h F_1 + \varphi_h F_3 - \psi_h F_4 = 0,\qquad
              \psi_h F_2 - \psi_h F_3 - \varphi_h F_4 = 0

    (φ_h = r cos θ, ψ_h = r sin θ, F₃ = sin θ F₁, F₄ = sin θ F₂), and the shape
    functions N_k reproduce φ_h and ψ_h: so Σ_k N_k [ψ_k (F₁ - F₁(x_k)) + φ_k (F₃ -
    F₃(x_k)) - ψ_k (F₄ - F₄(x_k))] vanishes on every cell whose nodes are all branch
    nodes (likewise the second).  When they all are (a radius r_e
    beyond the farthest node, or the default r_e on a mesh of a few cells across),
    these two combinations per component are exact null vectors of the stiffness: the
    system is singular.  Dropping F₃ and F₄ of one node k (the farthest from the front,
    where the 2 × 2 matrix of their coefficients, det = -(φ_k² + ψ_k²), is best
    conditioned) removes both without changing the span.  A component with a branch
    unknown among ``fixed`` (a clamped support) has no such null vector (it would be
    non-zero there) and keeps its unknowns.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 5), np.linspace(0, 1, 5))
    >>> g = crack_geometry(m, m.p[1] - 0.55, m.p[0] - 0.5)
    >>> dependent_dofs(crack_space(m, g, "geometric", 0.3), np.zeros(0, int)).size
    0
    >>> V = crack_space(m, g, "geometric", 2.0)                     # every node
    >>> dependent_dofs(V, np.zeros(0, int)).size                    # F₃, F₄ of one node
    4
    """
    mesh, geo = space.mesh, space.geometry
    if not np.isin(np.unique(mesh.t), space.branch).all():
        return np.zeros(0, int)
    cd = space.branch_dofs()                               # (nb, 4, d)
    k = int(np.argmax(geo.phi[space.branch] ** 2 + geo.psi[space.branch] ** 2))
    out = [cd[k, 2:, c] for c in range(mesh.dim())
           if not np.isin(cd[:, :, c], fixed).any()]
    return np.concatenate(out).astype(int) if out else np.zeros(0, int)
