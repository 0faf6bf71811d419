r"""One interface Γ as the steps below the scene see it: the contract of a kind of Γ.

A scene's :class:`~skxfem.scene.Interface` says *what* Γ is (its level set ψ, its
law, its multiplier space).  Every step that needs Γ's *geometry* — the cut
(:mod:`skxfem.cut`), the enrichment (:mod:`skxfem.enrich`), the multiplier space
(:mod:`skxfem.stabilised`), the normals at the multiplier points, the level set
written to the files — asks one object for it, the :class:`Gamma` of the
interface (:func:`gamma`).  :func:`skxfem.problem.assemble` builds one per
interface and keeps it in the interface's :class:`~skxfem.problem.Part`
(``part.gamma``); the solver, the contact Newton, the results and the writers
read the part's fields and never the level set or the kind.

**The contract of a kind.**  A new kind of Γ (a crack: a Γ = {ψ = 0, φ < 0}
that ends inside the body at a front {ψ = φ = 0}) is one more class with the
methods of :class:`Gamma`, returned by :func:`gamma` for its interfaces; nothing
else changes.  Each method must meet:

1. ``cut(mesh, label) -> Cut``: the :class:`skxfem.cut.Cut` of Γ_h on ``mesh``:
   the cut edges and their points (where the multipliers live), the interface
   facets joining them, the cut cells' sub-cells with their sides, the nodal ψ
   as used (``cut.psi``, 0 at the nodes on Γ), each node's side
   (``cut.node_side``, ±1, a node on Γ too; read for a Γ that ``splits``) and
   the nodes to enrich (``cut.enriched``).  A point at a vertex on Γ is the
   edge (v, v), edge id -1.  Refuse, with a ValueError naming ``label``, a Γ
   that does not cross the body.  A Γ that ends inside a cell cuts that cell
   partially: its facets stop at the front, and the edges it does not cross are
   not cut edges.
2. ``space(mesh, cut, order) -> XSpace``: the X-FEM space of this Γ on its own
   unknowns [a, b] (:class:`skxfem.enrich.XSpace`): ``enr_dofs``, ``H_node``
   and a ``parts`` that :func:`skxfem.enrich.stiffness` can integrate, so that
   the jump across Γ is -2 Σⱼ φⱼ bⱼ (:func:`skxfem.enrich.jump_matrix`).  A crack
   adds its tip functions as more unknowns of the same space.
3. ``multipliers(mesh, cut, fixed=None, per_edge=None) -> Space``: the
   multiplier space of its interface on the cut edges (:mod:`skxfem.stabilised`).
4. ``normals(cut) -> (dim, n)``: unit normals n = ∇ψ/|∇ψ| at the cut points,
   pointing into Ω⁺ (the sign convention of :mod:`skxfem.levelset`);
   ``normals_at(points)`` the same at any points on Γ (the interface rule's).
5. ``nodal(cut) -> (nverts,)``: the level set at the nodes, as the files write
   it (``levelset_k``): the ψ the solve used.
6. ``rule(mesh, cut) -> InterfaceRule`` and ``jump(V, rule)``: the quadrature on Γ_h
   and the operator U ↦ [[u_h]] at its points (component-major rows).
7. ``point_jumps(V, U) -> (dim, n)``: [[u]] = u⁻ - u⁺ at the cut points (the
   results' ``jump``); ``front(V, U, material, traction=None, body_force=None,
   others=()) -> dict | None``: the stress intensity factors along Γ's front, ``points``
   (m, dim), ``K_I``, ``K_II`` (m,), ``traction`` (dim, n) the interface traction at the
   cut points that loaded faces carry (the crack-face term), ``body_force`` the body
   force (its term), ``others`` the scene's other interfaces, ``(gamma, V, U)`` each (the
   field near a front is the whole field: another crack's branch functions reach into
   its domain); None for a Γ without a front.
8. ``splits``: whether Γ splits the body into regions (the files' pieces read the ψ
   of those that do; its space's ``splits`` says the same to :mod:`skxfem.enrich`).

The space a kind returns is asked, by :func:`skxfem.enrich.stiffness`,
:func:`skxfem.enrich.mass`, :func:`skxfem.problem.assemble` and
:meth:`skxfem.enrich.XSpaces.regions`, for its own ``signed_stiffness(material, A)``,
``signed_mass(A)`` and ``blocks(A, AH)`` (its enriched blocks: the Heaviside space's
arithmetic of :func:`skxfem.enrich.enriched_blocks`, a crack's own
blocks on its almost-polar rules), ``load(facet_loads, body_force, f)`` (its enriched
load), ``constraints(scene, mesh)`` (its constrained unknowns: a crack's mouth is clamped
shut only where the imposed value is continuous across it) and ``splits`` (whether Γ
splits the body into regions: a crack does not).
A law without multipliers (``free``) gives a part whose P has no column and B no row.

**The crack kind** (:class:`Crack`, issue 29, 2D, any law): an interface with a
``front`` φ; its cut is :func:`skxfem.crack.geometry.crack_geometry` (the fields of a
Cut), its space :class:`CrackXSpace` (the unknowns [a, b, c] of
:func:`skxfem.crack.space.crack_space`), its multipliers those of the crossed edges and
of the nodes on the crack up to the front (:func:`skxfem.crack.faces.crack_multipliers`),
its rule Gauss points on the crack pieces with the multiplier functions there, its
front the K of
:func:`skxfem.crack.sif.sif` with the faces' traction from the multipliers
(``Result.front``, ``result.json``'s ``front``).  A 3D front (a ``MeshTet1``) is the
kind :class:`skxfem.crack.kind3d.Crack3D` (any law: its multipliers on the crossed
edges up to the front, :mod:`skxfem.crack.faces3d`), its front K_I, K_II, K_III along
it.  A body force loads the enriched unknowns too and enters the interaction integral
(its term -∫ b·u^aux_{,1} q).

>>> from skfem import MeshTri1
>>> from skxfem.levelset import plane
>>> from skxfem.scene import Interface
>>> g = gamma(Interface(plane((0, 0.3), (0, 1))))
>>> m = MeshTri1().refined(2)
>>> c = g.cut(m, "")
>>> g.space(m, c).n_enr, g.normals(c)[:, 0].tolist()
(20, [0.0, 1.0])
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .crack.assembly import (
    FACET_POINTS,
    Load,
    Support,
    body_load,
    check_facets,
    cut_coupling,
    stiffness,
    supported_dofs,
    traction_load,
)
from .crack.assembly import coupling as crack_coupling
from .crack.assembly import face_rule as face_rule_of
from .crack.assembly import mass as crack_mass
from .crack.faces import face_functions, face_multipliers, face_traction
from .crack.geometry import crack_geometry, point_cells
from .crack.kind3d import Crack3D, FrontPointsWarning, warn_closing
from .crack.radius import check_radius
from .crack.sif import (
    CURVATURE_CELLS,
    DEFAULT_CELLS,
    check_reach,
    curvature_reach,
    sif,
    tip_radius,
    tip_reach,
    tip_room,
)
from .crack.space import CrackSpace, crack_space, evaluation
from .crack.xspace import CrackXSpaceBase
from .cut import Cut
from .cut import cut as cut_mesh
from .enrich import XSpace, edge_jumps, jump_matrix, xfem_space
from .levelset import point_normals, unit
from .multipliers import InterfaceRule, Space, interface_rule
from .scene.parts import Interface
from .stabilised import multiplier_space

__all__ = ["Gamma", "Crack", "CrackXSpace", "gamma"]


@dataclass(frozen=True)
class Gamma:
    """An interface that cuts the body through: Γ = {ψ = 0} (the paper's kind).

    ``interface`` the scene's :class:`~skxfem.scene.Interface`.  The methods are
    the contract of the module notes."""

    interface: Interface
    splits = True
    """Γ splits the body into regions (its sign is one of theirs)."""

    def cut(self, mesh, label: str = "") -> Cut:
        """The :class:`~skxfem.cut.Cut` of Γ on ``mesh`` (``label`` names it in messages)."""
        return cut_mesh(mesh, self.interface.levelset, label)

    def space(self, mesh, cut: Cut, order: int | None = None) -> XSpace:
        """The Heaviside-enriched space of Γ (:func:`skxfem.enrich.xfem_space`)."""
        return xfem_space(mesh, cut, order)

    def multipliers(self, mesh, cut: Cut, fixed=None, per_edge=None) -> Space:
        """The interface's multiplier space (:func:`skxfem.stabilised.multiplier_space`)."""
        return multiplier_space(self.interface.space, mesh, cut, fixed=fixed,
                                per_edge=per_edge)

    def normals(self, cut: Cut) -> np.ndarray:
        """Unit normals ∇ψ/|∇ψ| (dim, n) at the cut points
        (:func:`skxfem.levelset.point_normals`)."""
        return point_normals(cut, self.interface.levelset)

    def normals_at(self, points: np.ndarray) -> np.ndarray:
        """∇ψ/|∇ψ| (dim, n) at ``points`` on Γ; NaN where ∇ψ is not finite or vanishes."""
        n = np.asarray(self.interface.levelset.gradient(points), float)
        with np.errstate(all="ignore"):   # scaled first: the square of 1e300 overflows
            top = np.abs(n).max(axis=0)
            ok = np.isfinite(top) & (top > 0)
            n, _ = unit(n / np.where(ok, top, 1.0))
        return np.where(ok, n, np.nan)

    def nodal(self, cut: Cut) -> np.ndarray:
        """ψ at the nodes as the solve used it (0 at the nodes on Γ: ``cut.psi``)."""
        return cut.psi

    def rule(self, mesh, cut: Cut) -> InterfaceRule:
        """The quadrature on Γ_h (:func:`skxfem.multipliers.interface_rule`)."""
        return interface_rule(mesh, cut)

    def jump(self, V: XSpace, rule: InterfaceRule) -> sp.csr_matrix:
        """U ↦ [[u_h]] at the rule's points (:func:`skxfem.enrich.jump_matrix`)."""
        return jump_matrix(V, rule.cells, rule.ref)

    def point_jumps(self, V: XSpace, U: np.ndarray) -> np.ndarray:
        """[[u]] = u⁻ - u⁺ (dim, n) at the cut points, U on [a, b]
        (:func:`skxfem.enrich.edge_jumps`)."""
        return edge_jumps(V, U)

    def front(self, V, U: np.ndarray, material, traction=None, body_force=None, others=()
              ) -> dict | None:
        """The stress intensity factors along Γ's front: None, Γ has none."""
        return None


@dataclass(frozen=True)
class Crack(Gamma):
    """A 2D crack: Γ = {ψ = 0, φ < 0}, φ the interface's ``front``, which ends inside the
    body at the front {ψ = φ = 0} (module notes; the mathematics in :mod:`skxfem.crack`).

    Its cut is the :class:`~skxfem.crack.geometry.CrackGeometry` (the fields of a Cut),
    its space the :class:`CrackXSpace` of [a, b, c], its rule Gauss points on the
    crack pieces; any law: ``free`` faces carry no multiplier, the others multipliers
    on the crossed edges and the nodes on the crack up to the front
    (:mod:`skxfem.crack.faces`)."""

    splits = False
    """A crack ends inside the body: it splits no region."""

    def cut(self, mesh, label: str = ""):
        """The crack's geometry on ``mesh`` (:func:`skxfem.crack.geometry.crack_geometry`);
        a ValueError naming ``label`` if it crosses no cell."""
        i = self.interface
        try:
            geo = crack_geometry(mesh, i.levelset.fun, i.front.fun)
        except ValueError as err:                       # named as the 3D kind names it
            raise ValueError(f"{label or 'the crack'} ({i.levelset.name!r}, front "
                             f"{i.front.name!r}): {err}") from None
        if geo.segments.shape[-1] == 0:
            raise ValueError(f"{label or 'the crack'}: the crack {{ψ = 0, φ < 0}} "
                             f"({i.levelset.name!r}, front {i.front.name!r}) crosses no cell")
        check_reach(mesh, geo, label)                   # before the solve, not after
        if i.sif_radius is not None:
            for k in range(geo.tips.shape[1]):
                check_radius(i.sif_radius, tip_reach(mesh, geo, k)[2],
                             f"{label + ' ' if label else ''}sif_radius", 2)
        return geo

    def space(self, mesh, cut, order: int | None = None):
        """The crack's space [a, b, c] (:func:`skxfem.crack.space.crack_space` with the
        interface's ``enrichment`` and ``enrichment_radius``); ``order`` is not used (its
        own rules)."""
        return CrackXSpace(self._space(mesh, cut))

    def multipliers(self, mesh, cut, fixed=None, per_edge=None) -> Space:
        """The interface's multiplier space on the crack's crossed edges and nodes, up to
        the front (:func:`skxfem.crack.faces.crack_multipliers`), the points on an edge
        with a node near a tip cell tied to those behind them under a contact law
        (:func:`skxfem.crack.faces.face_multipliers`)."""
        i = self.interface
        return face_multipliers(i.law, i.space, mesh, cut, fixed=fixed, per_edge=per_edge)

    def normals(self, cut) -> np.ndarray:
        """∇ψ/|∇ψ| (dim, n) at the crack's cut points."""
        return self.normals_at(cut.points)

    def rule(self, mesh, cut) -> InterfaceRule:
        """Gauss points on the crack pieces (:func:`skxfem.crack.assembly.face_rule`,
        √r-graded at a tip), the normals of their pieces and the multiplier functions
        there (:func:`skxfem.crack.faces.face_functions`, constant from the last point,
        crossed edge or node, to the tip; none if the crack has no such point)."""
        x, w, cells, ref = face_rule_of(self._space(mesh, cut))
        nseg = cut.segment_cell.size
        per_piece = x.shape[1] // max(nseg, 1)
        piece = np.repeat(np.arange(nseg), per_piece)
        N = (face_functions(cut, x, piece) if cut.edge_ids.size else
             sp.csr_matrix((x.shape[1], 0)))
        return InterfaceRule(points=x, normals=np.repeat(cut.normals, per_piece, axis=1),
                             weights=w, cells=cells, ref=ref, N=N)

    def jump(self, V, rule: InterfaceRule) -> sp.csr_matrix:
        """U ↦ [[u_h]] = u⁻ - u⁺ (the Ω⁻ face's less the Ω⁺ face's) at the rule's points,
        component-major."""
        return _face_jump(V, rule.cells, rule.ref)

    def point_jumps(self, V, U: np.ndarray) -> np.ndarray:
        """[[u]] = u⁻ - u⁺ (dim, n) at the crack's cut points (the crossings of its cut
        edges, each in a cell of its edge; a node on the crack in the cell of a crack
        piece that ends there), U on [a, b, c]."""
        cut, mesh = V.cut, V.mesh
        cells = point_cells(cut, mesh.f2t[0])
        ref = mesh.mapping().invF(cut.points[:, :, None], tind=cells)[:, :, 0]
        return (_face_jump(V, cells, ref) @ U).reshape(mesh.dim(), -1)

    def front(self, V, U: np.ndarray, material, traction=None, body_force=None, others=()
              ) -> dict:
        """``points`` (m, dim) the front's points (the tips) and ``K_I``, ``K_II`` (m,) there
        (:func:`skxfem.crack.sif.sif` with the interface's ``sif_radius``).

        ``others``: the scene's other interfaces, ``(gamma, V, U)`` each.  Each tip's
        domain keeps clear of them (:func:`skxfem.crack.sif.tip_room`: two cells short of
        another Γ, half-way to another tip; a tip with under a cell of room is refused),
        and the integral takes the whole field: ∇u_h of this crack's
        unknowns plus that of the other cracks' enrichment (their branch functions reach
        r_e from their tips, into this tip's domain; a cut interface's shifted Heaviside
        enrichment vanishes outside its own cut cells, which the domain avoids).
        Without them, two collinear cracks 2 apart (half-length 1, h = 1/3) gave K_II up
        to 0.85 σ√(πa) at tips whose K_II is 0, and tips 0.2 apart K_I 4 to 14 times the
        right value.

        ``traction`` (dim, ne): the interface traction r = σ·n at the cut points (the
        multipliers of a tie or a contact, λ = P μ); the faces then carry t⁻ = r (Ω⁻'s
        face) and t⁺ = -r (Ω⁺'s), interpolated by the multiplier functions up to the
        front (:func:`skxfem.crack.faces.face_traction`), and the interaction integral
        takes them in its face term: a crack pressed shut gives K = 0.  None or all
        zero: free faces.  ``body_force``: the body force of the solved state (a scene's
        ``body_force`` values or ``x -> (dim, n)``), the interaction integral's body-force
        term (:mod:`skxfem.crack.interaction`); None: none."""
        tips = V.cut.tips
        rooms = [tip_room(V.mesh, V.cut, k, [o_V.cut for _, o_V, _ in others])[0]
                 for k in range(tips.shape[1])]
        _warn_clipped(V.space, self.interface, rooms)
        fields = [(o_V.space, _enriched_part(o_V.space, o_U)) for g, o_V, o_U in others
                  if isinstance(g, Crack)]

        def other_cracks(cells, ref):                   # ∇u of their enrichment
            return sum((evaluation(s, cells, ref).at(u)[1] for s, u in fields),
                       np.zeros((2, 2, np.size(cells))))

        faces = None
        if traction is not None and np.any(traction):
            faces = face_traction(V.cut, np.asarray(traction, float),
                                  face_rule_of(V.space)[0])
        K = np.array([sif(V.space, U, material, self.interface.sif_radius, tip=k,
                          face_traction=faces, body_force=body_force,
                          others=other_cracks if fields else None, room=rooms[k])
                      for k in range(tips.shape[1])]).reshape(-1, 2)
        warn_closing(self.interface, tips.T, K)
        return {"points": tips.T.copy(), "K_I": K[:, 0], "K_II": K[:, 1]}

    def _space(self, mesh, cut):
        return crack_space(mesh, cut, self.interface.enrichment,
                           self.interface.enrichment_radius)


CLIPPED_CELLS = 2.5
"""A 2D tip whose interaction domain the boundary or another tip clips under this many
tip cells gets a :class:`~skxfem.crack.kind3d.FrontPointsWarning` (:func:`_warn_clipped`)."""


def _enriched_part(space, U: np.ndarray) -> np.ndarray:
    """U with its standard unknowns zeroed: the part of the field its enrichment carries."""
    U = np.array(U, float)
    U[:space.n_std] = 0.0
    return U


def _warn_clipped(space: CrackSpace, interface: Interface, rooms=None) -> None:
    """Warn (:class:`~skxfem.crack.kind3d.FrontPointsWarning`) for each tip whose
    interaction domain the boundary or another tip clips under :data:`CLIPPED_CELLS`
    tip cells (the default is :data:`skxfem.crack.sif.DEFAULT_CELLS`): its K is then off
    by several per cent, silently.  Measured: a centre crack on the unit square, h =
    1/20, clipped by the other tip: K_I 11 % low at 1.2 cells, within 1 % at 1.6, 2 and
    3; an edge crack's tip 0.1 from the far side: 13 % low at 2 cells, 3.5 % at 4
    (:func:`skxfem.crack.sif.check_reach`).  A curved crack's default domain is
    clipped to a fraction of its radius of curvature, but kept at CURVATURE_CELLS cells
    (:func:`skxfem.crack.sif.tip_radius`): where the curvature would take it under, the
    mesh is too coarse for the curvature there, and the tip gets the same warning."""
    mesh, geo = space.mesh, space.geometry
    for k in range(geo.tips.shape[1]):
        reach, wall, h = tip_reach(mesh, geo, k)
        x = ", ".join(f"{v:.4g}" for v in geo.tips[:, k])
        by = "the boundary" if wall else "another tip"
        room = rooms[k] if rooms is not None else np.inf        # :func:`tip_room`
        if room < reach:
            reach, by = room, "another interface"
        curved = np.inf if interface.sif_radius else curvature_reach(space, k)[0]
        if curved < CURVATURE_CELLS * h * (1 - 1e-9):
            warnings.warn(f"{interface.front.name!r}: the crack's curvature at the tip at "
                          f"({x}) would clip its interaction domain to {curved / h:.2g} "
                          f"cells, under the {CURVATURE_CELLS:g} it keeps: its K may be off "
                          f"by several per cent; refine the mesh there (cells under "
                          f"{curved / CURVATURE_CELLS:.3g})", FrontPointsWarning, stacklevel=3)
        r_d = interface.sif_radius or tip_radius(space, k)
        if reach < min(r_d, CLIPPED_CELLS * h * (1 - 1e-9)):
            warnings.warn(f"{interface.front.name!r}: the interaction domain of the tip at "
                          f"({x}) is clipped to {reach / h:.2g} cells by {by}"
                          f" (the default: {DEFAULT_CELLS:g}): its K may be off by several "
                          f"per cent; refine the mesh there", FrontPointsWarning, stacklevel=3)


@dataclass(frozen=True)
class CrackXSpace(CrackXSpaceBase):
    r"""The X-FEM space of the crack kind of Γ: ``space`` its
    :class:`~skxfem.crack.space.CrackSpace` (the unknowns [a, b, c]: standard,
    Heaviside, branch), with the methods that :func:`skxfem.enrich.stiffness`,
    :func:`skxfem.problem.assemble`'s load and constraints, and
    :meth:`skxfem.enrich.XSpaces.regions` ask every space (module notes):

    * ``signed_stiffness(material, A)`` and ``blocks(A, K)``: the crack's own stiffness
      (:func:`skxfem.crack.assembly.stiffness`, its tip cells on the almost-polar
      rule), given as its standard block and its enriched blocks; ``signed_mass(A)``
      the same for its mass (:func:`skxfem.crack.assembly.mass`, :mod:`skxfem.lbb`);
    * ``load(facet_loads, body_force, f)``: the scene's surface loads and body force on
      [a, b, c] (:func:`skxfem.crack.assembly.traction_load`,
      :func:`~skxfem.crack.assembly.body_load`);
    * ``constraints(scene, mesh)``: the scene's displacements on [a, b, c]
      (:func:`skxfem.crack.assembly.supported_dofs`: a mouth clamped shut only where
      the imposed value is continuous across the crack);
    * ``splits = False``: a crack ends inside the body and splits no region.

    Each enriched unknown's standard dof is ``enr_dofs`` and its ``H_node`` that of its
    Heaviside node (0 for a branch unknown): the nodal fields of the regions hold
    a + Σ b(σ - H) with the crack's unknowns left out (its shifted enrichment vanishes
    at the nodes).

    >>> from skfem import MeshTri1
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 6))
    >>> V = CrackXSpace(crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5)))
    >>> V.N == V.space.N, V.enr_dofs.size == V.n_enr, V.splits
    (True, True, False)
    """

    space: CrackSpace
    _stiffness = staticmethod(stiffness)
    _mass = staticmethod(crack_mass)
    _support = Support
    _supported_dofs = staticmethod(supported_dofs)

    @property
    def basis(self):
        return self.space.basis

    def _coupling(self, other, material) -> sp.csr_matrix | None:
        """The stiffness block of this crack's enrichment with another 2D crack's
        (:func:`skxfem.crack.assembly.coupling`) or with a cut interface's Heaviside
        enrichment (:func:`skxfem.crack.assembly.cut_coupling`); None for another kind."""
        if isinstance(other, CrackXSpace):
            return crack_coupling(self.space, other.space, material)
        if isinstance(other, XSpace):
            return cut_coupling(self.space, other, material)
        return None

    def load(self, facet_loads, body_force=None, f: np.ndarray | None = None):
        """(f, f_b): the surface loads and body force on the standard dofs (``f`` if given)
        and on the enriched unknowns [b, c] (:func:`skxfem.crack.assembly.traction_load`,
        each facet's outward normal given to the traction ``t(x, n)``;
        :func:`skxfem.crack.assembly.body_load` on the crack's own rules)."""
        mesh = self.mesh
        loads = []
        for facets, traction in facet_loads:
            fac = check_facets(mesh, facets, "a load's facets")
            n = _outward_normals(mesh, fac)
            n_pts = np.repeat(n, 2 * FACET_POINTS, axis=1)  # facet_pieces' order

            def t(x, traction=traction, n_pts=n_pts):
                return np.asarray(traction(x, n_pts), float)

            loads.append(Load(fac, t))
        F = traction_load(self.space, loads)
        if body_force is not None:
            F = F + body_load(self.space, body_force)
        return (F[:self.n_std] if f is None else f), F[self.n_std:]


def _outward_normals(mesh, facets: np.ndarray) -> np.ndarray:
    """(2, nf) the outward unit normals of boundary facets of a 2D mesh."""
    a, b = mesh.p[:, mesh.facets[0, facets]], mesh.p[:, mesh.facets[1, facets]]
    d = b - a
    n = np.array([d[1], -d[0]]) / np.linalg.norm(d, axis=0)
    centre = mesh.p[:, mesh.t[:, mesh.f2t[0, facets]]].mean(axis=1)
    flip = ((centre - a) * n).sum(axis=0) > 0
    return np.where(flip, -n, n)


def _face_jump(V, cells: np.ndarray, ref: np.ndarray) -> sp.csr_matrix:
    """U ↦ u⁻ - u⁺ at points of a crack's faces (cells, reference coordinates),
    component-major rows (:func:`skxfem.crack.space.evaluation` on each side)."""
    n = cells.size
    minus, plus = (evaluation(V.space, cells, ref, np.full(n, s)).value for s in (-1.0, 1.0))
    return sp.csr_matrix(minus - plus)


def gamma(interface: Interface) -> Gamma:
    """The :class:`Gamma` of a scene's interface, by its kind: a :class:`Crack` for an
    interface with a 2D ``front``, a :class:`skxfem.crack.kind3d.Crack3D` with a 3D one,
    else a Γ that cuts the body through."""
    if not isinstance(interface, Interface):
        raise TypeError(f"interface must be a skxfem.scene.Interface, got "
                        f"{type(interface).__name__}")
    if interface.front is None:
        return Gamma(interface)
    return Crack3D(interface) if interface.front.dim == 3 else Crack(interface)
