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

**Several interfaces.** A scene with several (:attr:`skxfem.scene.Scene.interface_list`)
is one problem too: K, F, D, g on the unknowns [a, b¹, b², …] of
:class:`skxfem.enrich.XSpaces`, and, in ``interfaces``, one :class:`Problem`
per interface, built by the same steps as a scene with that interface alone
(its cut, rule, jump operator, multiplier spaces, coupling, on its own
unknowns [a, b^k]; ``columns`` places them among the whole's).  The whole's B
stacks the interfaces' couplings and P is block-diagonal; the fields of one
interface (``cut``, ``rule``, ``J``, ``multiplier_space``, ``ncomp``, ``M_edges``,
``held_edges``) are those of the pieces.

>>> from skxfem.scene.benchmarks import strip
>>> p = assemble(strip(3, cell="tri"))
>>> p.law, p.ncomp, p.B.shape[0] == p.P.shape[1], p.J.shape[1] == p.K.shape[0]
('bonded', 2, True, True)
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from .cut import Cut, check_apart
from .cut import cut as cut_mesh
from .enrich import (
    XSpace,
    XSpaces,
    body_load,
    enriched_load,
    jump_matrix,
    stiffness,
    xfem_space,
)
from .fem.loads import boundary_quadrature, surface_load
from .linalg.rigid import short_pieces
from .multipliers import (
    InterfaceRule,
    Space,
    coupling,
    fixed_jumps,
    interface_mass,
    interface_rule,
    normal_fixed,
)
from .scene.boundary import imposed
from .scene.laws import COUPLING
from .scene.model import Scene, check_scene, dirichlet, load_facets, resolve_mesh
from .stabilised import multiplier_space

__all__ = ["Problem", "assemble", "constrained_dofs", "COUPLING", "check_law"]


def check_law(law: str) -> str:
    """``law`` if :func:`assemble` knows it, else a ValueError listing the known ones.

    >>> check_law("bonded")
    'bonded'
    """
    if not isinstance(law, str) or law not in COUPLING:
        raise ValueError(f"law must be one of {tuple(COUPLING)}, got {law!r}")
    return law


@dataclass(frozen=True)
class Problem:
    r"""The discrete interface problem of a scene (paper §3-5), for one tie law.

    With U = [a, b] the X-FEM unknowns ([11], shifted enrichment) and μ
    the independent multipliers, λ = P μ on the cut edges, the problem is
    K U + Bᵀ y = F, B U = 0, U[D] = g (y = -μ; :mod:`skxfem.solver`).

    Attributes
    ----------
    scene, mesh, cut : the scene, its resolved mesh and :class:`~skxfem.cut.Cut` (§4.1).
    V : :class:`~skxfem.enrich.XSpace`, the displacement space u_h of [11].
    K : (N, N) CSR, the stiffness a(u, v) = ∫ σ(u):ε(v) of §3's weak equilibrium,
        σ from the constitutive law [1].
    F : (N,), the load l(v) = ∫_{Γ_t} t·v of the surface tractions (§3).
    D, g : the constrained unknowns (int array) and their values: the scene's
        displacements, with the enriched dofs they hold on cut boundary
        facets (:func:`constrained_dofs`).
    rule : :class:`~skxfem.multipliers.InterfaceRule`, the quadrature on Γ_h.
    J : (dim·nq, N) CSR, U ↦ [[u_h]] at the rule's points, component-major: the
        jump of §4.1 written with the enriched dofs of [11]
        (:func:`skxfem.enrich.jump_matrix`).
    multiplier_space : :class:`~skxfem.multipliers.Space`, the scene's multiplier
        space on all cut edges (§4.2 naive, §5 winner nodes / vital edges).
    law : the tie law P and B are built for (``"bonded"`` or ``"bilateral"``).
    ncomp : multiplier components per edge: dim (bonded) or 1 (bilateral).
    P : (ncomp·n_edges, m) CSR, the prolongation λ = P μ of the law's
        multipliers, component-major (λ_h of [12] on the cut edges, §5's
        equalities and linear relations):
        block-diagonal, one block per component, ``component_spaces[k].P``.
    B : (m, N) CSR, Pᵀ B_edges, the coupling ∫_Γ λ_h·[[v]] (or λ_h [[v]]·n)
        reduced to the space: the interface terms of §3's mixed formulation,
        with a tie law in place of the contact law [6].
    M_edges : (n_edges, n_edges) CSR, the interface mass ∫_Γ N_e N_f (the
        L² norm of λ_h; §5's inf-sup test scales it by h).
    held_edges : (ncomp, n_edges) bool, the (component, edge) pairs whose jump a
        support holds: both ends of the edge are fixed for that component
        (:func:`skxfem.multipliers.fixed_jumps`, from ``D``; bilateral: the
        normal jump, :func:`skxfem.multipliers.normal_fixed`).  They carry
        no multiplier of their own: their rows of P are those of a neighbour
        on Γ (:func:`skxfem.stabilised.extend_to_held`).
    component_spaces : the ncomp multiplier spaces of the law's components, each
        built on the edges it keeps (``multiplier_space`` itself where a
        component has no fixed node).
    timings : seconds per stage.
    per_edge : (n_edges,) bool or None, the edges of the pieces of Γ too small
        for the stable space, which get a multiplier each
        (:func:`skxfem.linalg.rigid.short_pieces`).
    interfaces : several interfaces (module notes): the :class:`Problem` of
        each, on its own unknowns [a, b^k] (its ``K`` and ``F`` None: the
        whole's are here); then ``V`` is an :class:`~skxfem.enrich.XSpaces`,
        ``B`` (Σm, N) stacks theirs, ``P`` is block-diagonal, ``law`` is the law
        they were assembled for if it is one for all (else None), and ``cut``,
        ``rule``, ``J``, ``multiplier_space``, ``ncomp``, ``M_edges``, ``held_edges`` are None.
        Empty for one interface.
    columns : for a piece of ``interfaces``, the whole's unknowns its own
        [a, b^k] are (:meth:`skxfem.enrich.XSpaces.columns`); None otherwise.
    """

    scene: Scene
    mesh: object
    cut: Cut
    V: XSpace
    K: sp.csr_matrix
    F: np.ndarray
    D: np.ndarray
    g: np.ndarray
    rule: InterfaceRule
    J: sp.csr_matrix
    multiplier_space: Space
    law: str
    ncomp: int
    P: sp.csr_matrix
    B: sp.csr_matrix
    M_edges: sp.csr_matrix
    held_edges: np.ndarray
    component_spaces: tuple
    timings: dict = field(default_factory=dict)
    per_edge: np.ndarray | None = None
    interfaces: tuple = ()
    columns: np.ndarray | None = None

    @property
    def per_interface(self) -> tuple:
        """The problem of each interface: ``interfaces``, or ``(self,)`` for one."""
        return self.interfaces or (self,)

    def lift(self, k: int, A) -> sp.csr_matrix:
        """An operator on the unknowns of interface ``k``'s piece, [a, b^k], as one on
        the whole's, A @ select(k) (:meth:`skxfem.enrich.XSpaces.select`); A itself
        for one interface."""
        if not self.interfaces:
            return sp.csr_matrix(A)
        return (sp.csr_matrix(A) @ self.V.select(k)).tocsr()


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
        The X-FEM space (:func:`skxfem.enrich.xfem_space`).
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
    for support_nodes, components in imposed(scene, mesh):
        selected = np.zeros(mesh.p.shape[1], dtype=bool)
        selected[support_nodes] = True
        nodes = np.unique(cut_bf[:, selected[cut_bf].all(axis=0)])
        for comp in components:
            b = pos[V.basis.nodal_dofs[comp, nodes]]
            enr.append(V.n_std + b[b >= 0])
    enr = np.unique(np.concatenate(enr))
    return (np.concatenate([dofs, enr]),
            np.concatenate([values, np.zeros(enr.size)]))


def assemble(scene: Scene, law: str | None = None) -> Problem:
    """Assemble the interface problem of ``scene`` for ``law`` (default: ``scene.law``).

    The multiplier space is the scene's, per component with the supports'
    fixed nodes (:func:`skxfem.stabilised.multiplier_space`); a piece of Γ on
    which it holds fewer rigid motions than the law (a corner cut off inside
    one cell: :func:`skxfem.linalg.rigid.short_pieces`) gets a multiplier per edge.

    Parameters
    ----------
    scene
        A :class:`skxfem.scene.Scene`; its ``quadrature_order`` sets the cell
        rule of the stiffness (``None``: exact on affine cells).  With several
        interfaces, one piece each (module notes).
    law
        A key of :data:`COUPLING`; ``None`` takes the scene's (each interface's).

    Returns
    -------
    Problem

    Raises
    ------
    ValueError
        An unknown law, a scene that does not fit its mesh, a level set that
        cuts no cell or vanishes on a region (from :func:`skxfem.cut.cut`), two
        interfaces that cut one cell (:func:`skxfem.cut.check_apart`).
    """
    if check_scene(scene).several:
        return _assemble_several(scene, law)
    scene = scene.alone(0)  # a scene given one Interface: its one-interface form
    law = check_law(scene.law if law is None else law)
    timings, lap = _clock()
    mesh = resolve_mesh(scene)
    cut = cut_mesh(mesh, scene.levelset)
    lap("cut")
    V = xfem_space(mesh, cut, scene.quadrature_order)
    lap("enrich")
    K = stiffness(V, scene.material, scene.material_plus)
    lap("stiffness")
    f, f_H = np.zeros(V.n_std), np.zeros(V.n_std)
    for facets, traction in load_facets(scene, mesh):
        q = boundary_quadrature(mesh, facets, 4, psi_nodes=cut.psi)
        df, df_H = surface_load(V.basis, q, traction)
        f, f_H = f + df, f_H + df_H
    if scene.body_force is not None:
        df, df_H = body_load(V, scene.body_force)
        f, f_H = f + df, f_H + df_H
    F = enriched_load(V, f, f_H)
    lap("load")
    D, g = constrained_dofs(V, scene, mesh)
    lap("constraints")
    return _interface_problem(scene, mesh, cut, V, K, F, D, g, law, timings, lap)


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


def _interface_problem(scene, mesh, cut, V, K, F, D, g, law, timings, lap, columns=None):
    """The :class:`Problem` of one interface, after its X-FEM space: its multiplier
    space (§4.2, §5), rule, jump operator, coupling and the spaces of each
    component (with the supports' fixed nodes; a multiplier per edge on the pieces
    of Γ the space leaves loose)."""
    lam_space = multiplier_space(scene.space, mesh, cut)
    lap("space")
    rule = interface_rule(mesh, cut)
    J = jump_matrix(V, rule.cells, rule.ref)
    B_edges = coupling(V, rule, COUPLING[law], J=J)
    M_edges = interface_mass(rule)
    lap("interface")
    fixed = fixed_jumps(V, D)
    if COUPLING[law] == "bilateral":
        fixed = normal_fixed(fixed, cut)[None, :]
    held_edges = fixed[:, cut.edges[0]] & fixed[:, cut.edges[1]]

    def problem(lam_space, per_edge=None):
        spaces = _component_spaces(scene.space, mesh, cut, lam_space, fixed, per_edge)
        P = sp.block_diag([s.P for s in spaces], format="csr")  # component-major
        return Problem(scene=scene, mesh=mesh, cut=cut, V=V, K=K, F=F, D=D, g=g, rule=rule,
                       J=J, multiplier_space=lam_space, law=law, ncomp=held_edges.shape[0], P=P,
                       B=(P.T @ B_edges).tocsr(), M_edges=M_edges, held_edges=held_edges,
                       component_spaces=spaces, timings=timings, per_edge=per_edge,
                       columns=columns)

    p = problem(lam_space)
    short = short_pieces(p, B_edges)  # pieces of Γ the stable space leaves loose
    if short.any():
        p = problem(multiplier_space(scene.space, mesh, cut, per_edge=short), short)
    lap("prolongation")
    return p


def _assemble_several(scene: Scene, law: str | None) -> Problem:
    """:func:`assemble` of a scene with several interfaces (module notes)."""
    items = scene.interface_list
    laws = [check_law(i.law if law is None else law) for i in items]
    timings, lap = _clock()
    mesh = resolve_mesh(scene)
    cuts = tuple(cut_mesh(mesh, i.levelset, f"interfaces[{k}] {i.levelset.name!r}")
                 for k, i in enumerate(items))
    check_apart(mesh, cuts, [f"interfaces[{k}] ({i.levelset.name!r})"
                             for k, i in enumerate(items)])
    lap("cut")
    alone = [scene.alone(k) for k in range(len(items))]
    V = XSpaces(tuple(xfem_space(mesh, cut, scene.quadrature_order) for cut in cuts))
    lap("enrich")
    K = stiffness(V, scene.material)
    lap("stiffness")
    f, f_H = np.zeros(V.n_std), [np.zeros(V.n_std) for _ in cuts]
    for facets, traction in load_facets(scene, mesh):
        for k, cut in enumerate(cuts):
            q = boundary_quadrature(mesh, facets, 4, psi_nodes=cut.psi)
            df, df_H = surface_load(V.basis, q, traction)
            f = f + df if k == 0 else f
            f_H[k] = f_H[k] + df_H
    if scene.body_force is not None:
        for k, Vk in enumerate(V.per_interface):
            df, df_H = body_load(Vk, scene.body_force)
            f = f + df if k == 0 else f
            f_H[k] = f_H[k] + df_H
    F = enriched_load(V, f, f_H)
    lap("load")
    local = [constrained_dofs(Vk, s, mesh) for Vk, s in zip(V.per_interface, alone)]
    std = local[0][0] < V.n_std  # the supports' standard dofs: the same for every interface
    D = np.concatenate([local[0][0][std]] + [V.columns(k)[Dk[Dk >= V.n_std]]
                                             for k, (Dk, _) in enumerate(local)])
    g = np.concatenate([local[0][1][std]] + [gk[Dk >= V.n_std] for Dk, gk in local])
    lap("constraints")
    pieces = tuple(_interface_problem(alone[k], mesh, cuts[k], V.per_interface[k], None, None,
                                      *local[k], laws[k], timings, lap, V.columns(k))
                   for k in range(len(items)))
    B = sp.vstack([p.B @ V.select(k) for k, p in enumerate(pieces)], format="csr")
    P = sp.block_diag([p.P for p in pieces], format="csr")
    return Problem(scene=scene, mesh=mesh, cut=None, V=V, K=K, F=F, D=D, g=g, rule=None,
                   J=None, multiplier_space=None, law=laws[0] if len(set(laws)) == 1 else None,
                   ncomp=None, P=P, B=B, M_edges=None, held_edges=None, component_spaces=(),
                   timings=timings, interfaces=pieces)


def _component_spaces(name, mesh, cut, lam_space, fixed, per_edge=None) -> tuple:
    """The multiplier space of each component, built with that component's
    fixed nodes (``lam_space``, the space of all edges, where none is fixed; one
    build per distinct set of fixed nodes) and a multiplier per ``per_edge`` edge."""
    built = {}
    for row in fixed:
        key = row.tobytes()
        if key not in built:
            built[key] = (lam_space if not row.any() else
                          multiplier_space(name, mesh, cut, fixed=row, per_edge=per_edge))
    return tuple(built[row.tobytes()] for row in fixed)
