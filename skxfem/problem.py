r"""The assembled interface problem of a scene: one value that every solver shares.

:func:`assemble` builds, once, everything the discrete tied (or contact)
problem of a scene is made of — the X-FEM stiffness and load, the
constrained unknowns, the interface rule, the jump operator, the multiplier
space and its coupling, the interface mass — and returns it as a frozen
:class:`Problem`.  :func:`skxfem.solver.solve` (the tie),
:func:`skxfem.lbb.inf_sup` (the inf-sup test) and the contact solver take
their matrices from it and rebuild none of them.

The law decides which jump the multipliers act on (:data:`COUPLING`):
``bonded`` the vector jump [[u]] (dim multipliers per edge), ``bilateral``
the normal jump [[u]]·n (one).  A new law (contact) adds one entry there.

**Interfaces.** A scene's interfaces (:attr:`skxfem.scene.Scene.interfaces`,
one or more) make one problem: K, F, D, g on the unknowns [a, b¹, b², …] of
:class:`skxfem.enrich.XSpaces`, and, in ``interfaces``, one :class:`Part` per
interface, built by the same steps for each (its cut, rule, jump operator,
multiplier spaces, coupling, on its own unknowns [a, b^k]; ``columns`` places
them among the whole's).  The whole's B stacks the parts' couplings and P is
block-diagonal.  One interface is the case of one part; a problem with one
keeps its part's fields readable on itself (``p.cut``, ``p.rule``, ``p.J``, …),
as a convenience.

>>> from skxfem.scene.benchmarks import strip
>>> p = assemble(strip(3, cell="tri"))
>>> p.law, p.ncomp, p.B.shape[0] == p.P.shape[1], p.J.shape[1] == p.K.shape[0]
('bonded', 2, True, True)
>>> len(p.interfaces), p.interfaces[0].cut is p.cut
(1, True)
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from .crack.sif import check_clearance
from .cut import Cut, check_apart
from .enrich import XSpace, XSpaces, constrained_dofs, one_interface, stiffness
from .gamma import Gamma, gamma
from .linalg.rigid import short_pieces
from .multipliers import (
    InterfaceRule,
    Space,
    coupling,
    fixed_jumps,
    interface_mass,
    normal_fixed,
)
from .scene.laws import COUPLING
from .scene.model import Interface, Resolved, Scene, load_facets, resolve

__all__ = ["Problem", "Part", "assemble", "state_loads", "constrained_dofs", "COUPLING",
           "check_law"]


def check_law(law: str) -> str:
    """``law`` if :func:`assemble` knows it, else a ValueError listing the known ones.

    >>> check_law("bonded")
    'bonded'
    """
    if not isinstance(law, str) or law not in COUPLING:
        raise ValueError(f"law must be one of {tuple(COUPLING)}, got {law!r}")
    return law


@dataclass(frozen=True)
class Part:
    r"""One interface's part of a :class:`Problem`: its Γ_h, rule, jump and
    multiplier space (paper §4-5), on the unknowns [a, b^k] of its own X-FEM space.

    Attributes
    ----------
    interface : the scene's :class:`~skxfem.scene.Interface` (level set, law, space, …).
    gamma : its geometry, :class:`skxfem.gamma.Gamma` (the contract of a kind of Γ):
        what built ``cut``, ``V`` and the multiplier spaces, and gives the normals.
    mesh, cut : the resolved mesh and the interface's :class:`~skxfem.cut.Cut` (§4.1).
    V : :class:`~skxfem.enrich.XSpace`, the displacement space [a, b^k] of this interface.
    D, g : the constrained unknowns of [a, b^k] and their values
        (:func:`constrained_dofs`).
    rule : :class:`~skxfem.multipliers.InterfaceRule`, the quadrature on Γ_h.
    J : (dim·nq, n_k) CSR, U_k ↦ [[u_h]] at the rule's points, component-major: the
        jump of §4.1 written with the enriched dofs of [11]
        (:func:`skxfem.enrich.jump_matrix`).
    multiplier_space : :class:`~skxfem.multipliers.Space`, the multiplier space
        on all cut edges (§4.2 naive, §5 winner nodes / vital edges); None for a law
        without multipliers (``free``).
    law : the tie law P and B are built for (``"bonded"`` or ``"bilateral"``).
    ncomp : multiplier components per edge: dim (bonded) or 1 (bilateral).
    P : (ncomp·n_edges, m) CSR, the prolongation λ = P μ of the law's
        multipliers, component-major (λ_h of [12] on the cut edges, §5's
        equalities and linear relations): block-diagonal, one block per
        component, ``component_spaces[k].P``.
    B : (m, n_k) CSR, Pᵀ B_edges, the coupling ∫_Γ λ_h·[[v]] (or λ_h [[v]]·n)
        reduced to the space: the interface terms of §3's mixed formulation,
        with a tie law in place of the contact law [6].
    M_edges : (n_edges, n_edges) CSR, the interface mass ∫_Γ N_e N_f (the L²
        norm of λ_h; §5's inf-sup test scales it by h).
    held_edges : (ncomp, n_edges) bool, the (component, edge) pairs whose jump a
        support holds: both ends of the edge are fixed for that component
        (:func:`skxfem.multipliers.fixed_jumps`, from ``D``; bilateral: the normal
        jump, :func:`skxfem.multipliers.normal_fixed`).  They carry no multiplier
        of their own: their rows of P are those of a neighbour on Γ
        (:func:`skxfem.stabilised.extend_to_held`).
    component_spaces : the ncomp multiplier spaces of the law's components, each
        built on the edges it keeps (``multiplier_space`` itself where a component
        has no fixed node).
    per_edge : (n_edges,) bool or None, the edges of the pieces of Γ too small for
        the stable space, which get a multiplier each
        (:func:`skxfem.linalg.rigid.short_pieces`).
    columns : (n_k,) the whole's unknowns its own [a, b^k] are
        (:meth:`skxfem.enrich.XSpaces.columns`).
    """

    interface: Interface
    gamma: Gamma
    mesh: object
    cut: Cut
    V: XSpace
    D: np.ndarray
    g: np.ndarray
    rule: InterfaceRule
    J: sp.csr_matrix
    multiplier_space: Space | None
    law: str
    ncomp: int
    P: sp.csr_matrix
    B: sp.csr_matrix
    M_edges: sp.csr_matrix
    held_edges: np.ndarray
    component_spaces: tuple
    per_edge: np.ndarray | None = None
    columns: np.ndarray | None = None

    @property
    def space(self) -> str:
        """The name of the multiplier space (the interface's)."""
        return self.interface.space

    def normals(self) -> np.ndarray:
        """Unit normals n = ∇ψ/|∇ψ| (dim, n) at the cut points (:meth:`Gamma.normals`)."""
        return self.gamma.normals(self.cut)


_ONE = ("cut", "rule", "J", "multiplier_space", "ncomp", "M_edges", "held_edges",
        "component_spaces", "per_edge")


@dataclass(frozen=True)
class Problem:
    r"""The discrete interface problem of a scene (paper §3-5), for its tie laws.

    With U = [a, b¹, …] the X-FEM unknowns ([11], shifted enrichment) and μ
    the independent multipliers, λ = P μ on the cut edges, the problem is
    K U + Bᵀ y = F, B U = 0, U[D] = g (y = -μ; :mod:`skxfem.solver`).

    Attributes
    ----------
    scene, mesh : the scene and its resolved mesh.
    V : :class:`~skxfem.enrich.XSpaces`, the displacement space u_h of [11], one
        Heaviside enrichment per interface.
    K : (N, N) CSR, the stiffness a(u, v) = ∫ σ(u):ε(v) of §3's weak equilibrium,
        σ from the constitutive law [1].
    F : (N,), the load l(v) of the surface tractions and body force (§3).
    D, g : the constrained unknowns (int array) and their values: the scene's
        displacements, with the enriched dofs they hold on cut boundary
        facets (:func:`constrained_dofs`).
    P : block-diagonal, the parts' prolongations.
    B : (Σm, N) CSR, the parts' couplings, each on its columns.
    interfaces : the :class:`Part` of each interface, in the scene's order.
    timings : seconds per stage.

    A problem of one interface also reads its part's ``cut``, ``rule``, ``J``,
    ``multiplier_space``, ``ncomp``, ``M_edges``, ``held_edges``,
    ``component_spaces`` and ``per_edge`` on itself (``p.cut`` is
    ``p.interfaces[0].cut``).
    """

    scene: Scene
    mesh: object
    V: XSpaces
    K: sp.csr_matrix
    F: np.ndarray
    D: np.ndarray
    g: np.ndarray
    P: sp.csr_matrix
    B: sp.csr_matrix
    interfaces: tuple[Part, ...]
    timings: dict = field(default_factory=dict)

    def __getattr__(self, name):  # the one part's field (class notes)
        return one_interface(self, "interfaces", _ONE, name)

    @property
    def laws(self) -> tuple[str, ...]:
        """The tie law of each part."""
        return tuple(q.law for q in self.interfaces)

    @property
    def law(self) -> str | None:
        """The tie law of the parts if they share one, else None."""
        return self.laws[0] if len(set(self.laws)) == 1 else None


def assemble(scene: Scene | Resolved, law: str | None = None) -> Problem:
    """Assemble the interface problem of ``scene`` for ``law`` (default: each
    interface's own).

    Every interface is assembled by the same steps (module notes): its cut, its
    X-FEM enrichment, its multiplier space per component with the supports'
    fixed nodes (:func:`skxfem.stabilised.multiplier_space`); a piece of Γ on
    which it holds fewer rigid motions than the law (a corner cut off inside
    one cell: :func:`skxfem.linalg.rigid.short_pieces`) gets a multiplier per edge.

    Parameters
    ----------
    scene
        A :class:`skxfem.scene.Scene` or the :class:`~skxfem.scene.Resolved` one
        (:func:`skxfem.scene.resolve`: its mesh built once); its
        ``quadrature_order`` sets the cell rule of the stiffness (``None``: exact
        on affine cells).
    law
        A key of :data:`COUPLING` for every interface; ``None`` takes each
        interface's own.

    Returns
    -------
    Problem

    Raises
    ------
    ValueError
        An unknown law, a scene that does not fit its mesh, a level set that
        cuts no cell or vanishes on a region (from :func:`skxfem.cut.cut`), two
        interfaces that cut one cell (:func:`skxfem.cut.check_apart`), a 2D crack's
        tip within three cells of another interface
        (:func:`skxfem.crack.sif.check_clearance`).
    """
    scene, mesh = resolve(scene)
    items = scene.interfaces
    laws = [check_law(i.law if law is None else law) for i in items]
    timings, lap = _clock()
    gammas = [gamma(i) for i in items]   # the geometry of each Γ (skxfem.gamma)
    cuts = tuple(g.cut(mesh, scene.label(k)) for k, g in enumerate(gammas))
    names = [f"interfaces[{k}] ({i.levelset.name!r})" for k, i in enumerate(items)]
    check_apart(mesh, cuts, names)
    check_clearance(mesh, cuts, names)      # a crack's tips clear of the other interfaces
    lap("cut")
    V = XSpaces(tuple(g.space(mesh, cut, scene.quadrature_order)
                      for g, cut in zip(gammas, cuts)))
    lap("enrich")
    K = stiffness(V, *scene.materials())
    lap("stiffness")
    F = _load(scene, mesh, V)
    lap("load")
    D, g, local = _constraints(scene, mesh, V)
    lap("constraints")
    parts = tuple(_part(items[k], gammas[k], mesh, cuts[k], V.per_interface[k], *local[k],
                        laws[k], lap, V.columns(k)) for k in range(len(items)))
    B = sp.vstack([V.lift(k, q.B) for k, q in enumerate(parts)], format="csr")
    P = sp.block_diag([q.P for q in parts], format="csr")
    return Problem(scene=scene, mesh=mesh, V=V, K=K, F=F, D=D, g=g, P=P, B=B,
                   interfaces=parts, timings=timings)


def state_loads(pb: Problem, scene: Scene) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The load F and the constrained unknowns D and values g of ``scene`` on the space
    of the assembled problem ``pb``: a load state of a contact history, which keeps the
    problem's mesh, Γ and space and changes its loads and imposed values (the
    callers check that it does; ``pb``'s own scene gives ``pb.F``, ``pb.D``, ``pb.g``).
    """
    D, g, _ = _constraints(scene, pb.mesh, pb.V)
    return _load(scene, pb.mesh, pb.V), D, g


def _load(scene: Scene, mesh, V: XSpaces) -> np.ndarray:
    """F on [a, b¹, …]: the scene's surface loads and body force, each space's enriched
    part by its own rule (:meth:`skxfem.enrich.XSpace.load`), the standard part the
    first space's."""
    facet_loads = load_facets(scene, mesh)
    f, parts = None, []
    for Vk in V.per_interface:
        f, fk = Vk.load(facet_loads, scene.body_force, f)
        parts.append(fk)
    return np.concatenate([f] + parts)


def _constraints(scene: Scene, mesh, V: XSpaces):
    """(D, g) on [a, b¹, …] and each interface's own (D_k, g_k) on [a, b^k]
    (:func:`constrained_dofs`)."""
    local = [Vk.constraints(scene, mesh) for Vk in V.per_interface]
    std = local[0][0] < V.n_std  # the supports' standard dofs: the same for every interface
    D = np.concatenate([local[0][0][std]] + [V.columns(k)[Dk[Dk >= V.n_std]]
                                             for k, (Dk, _) in enumerate(local)])
    g = np.concatenate([local[0][1][std]] + [gk[Dk >= V.n_std] for Dk, gk in local])
    return D, g, local


def _clock():
    """A dict of seconds per stage and ``lap(name)``, which adds the time since the
    last lap to ``name``."""
    timings = {}
    clock = [time.perf_counter()]

    def lap(name):
        now = time.perf_counter()
        timings[name] = timings.get(name, 0.0) + now - clock[0]
        clock[0] = now

    return timings, lap


def _part(interface, g: Gamma, mesh, cut, V, D, values, law, lap, columns) -> Part:
    """The :class:`Part` of one interface, after its X-FEM space: its multiplier
    space (§4.2, §5), rule, jump operator, coupling and the spaces of each
    component (with the supports' fixed nodes; a multiplier per edge on the pieces
    of Γ the space leaves loose).  A law without multipliers (``free``) gives P with
    no column (dim rows per cut edge: λ = P μ = 0) and B with no row."""
    free = COUPLING[law] == "none"
    lam_space = None if free else g.multipliers(mesh, cut)
    lap("space")
    rule = g.rule(mesh, cut)
    J = g.jump(V, rule)
    if free:  # its rule and jump only, for the results
        lap("interface")
        ne, dim = cut.edge_ids.size, mesh.dim()
        q = Part(interface=interface, gamma=g, mesh=mesh, cut=cut, V=V, D=D, g=values,
                 rule=rule, J=J, multiplier_space=None, law=law, ncomp=dim,
                 P=sp.csr_matrix((dim * ne, 0)), B=sp.csr_matrix((0, V.N)),
                 M_edges=sp.csr_matrix((ne, ne)), held_edges=np.zeros((dim, ne), bool),
                 component_spaces=(), columns=columns)
        lap("prolongation")
        return q
    B_edges = coupling(V, rule, COUPLING[law], J=J)
    M_edges = interface_mass(rule)
    lap("interface")
    fixed = fixed_jumps(V, D)
    if COUPLING[law] == "bilateral":
        fixed = normal_fixed(fixed, cut)[None, :]
    held_edges = fixed[:, cut.edges[0]] & fixed[:, cut.edges[1]]

    def part(lam_space, per_edge=None):
        spaces = _component_spaces(g, mesh, cut, lam_space, fixed, per_edge)
        P = sp.block_diag([s.P for s in spaces], format="csr")  # component-major
        return Part(interface=interface, gamma=g, mesh=mesh, cut=cut, V=V, D=D, g=values,
                    rule=rule, J=J,
                    multiplier_space=lam_space, law=law, ncomp=held_edges.shape[0], P=P,
                    B=(P.T @ B_edges).tocsr(), M_edges=M_edges, held_edges=held_edges,
                    component_spaces=spaces, per_edge=per_edge, columns=columns)

    q = part(lam_space)
    # pieces of Γ the stable space leaves loose; a Γ that splits no region (a crack)
    # has no relative rigid motion of two sides to hold
    short = short_pieces(q, B_edges) if V.splits else np.zeros(cut.edge_ids.size, bool)
    if short.any():
        q = part(g.multipliers(mesh, cut, per_edge=short), short)
    lap("prolongation")
    return q


def _component_spaces(g: Gamma, mesh, cut, lam_space, fixed, per_edge=None) -> tuple:
    """The multiplier space of each component, built with that component's
    fixed nodes (``lam_space``, the space of all edges, where none is fixed; one
    build per distinct set of fixed nodes) and a multiplier per ``per_edge`` edge."""
    built = {}
    for row in fixed:
        key = row.tobytes()
        if key not in built:
            built[key] = (lam_space if not row.any() else
                          g.multipliers(mesh, cut, fixed=row, per_edge=per_edge))
    return tuple(built[row.tobytes()] for row in fixed)
