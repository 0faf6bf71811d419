r"""The 3D crack kind of Γ: a crack with a front on a tetrahedral mesh, for the scene.

The objects :func:`skxfem.gamma.gamma` returns for an interface with a 3D ``front``:
:class:`Crack3D`, with the methods of the contract of :mod:`skxfem.gamma`, and its space
:class:`CrackXSpace3D`, with the methods :func:`skxfem.enrich.stiffness`,
:func:`skxfem.problem.assemble` and :meth:`skxfem.enrich.XSpaces.regions` ask every space.
They wrap the modules of the 3D crack (:mod:`~skxfem.crack.geometry3d`,
:mod:`~skxfem.crack.space3d`, :mod:`~skxfem.crack.sif3d`) as :class:`skxfem.gamma.Crack`
wraps the 2D ones.  Any law: ``free`` faces carry no multiplier, the others (a tie,
contact with or without friction, adhesion) multipliers on the crossed edges and the
nodes on the crack up to the front (:mod:`~skxfem.crack.faces3d`: the stable spaces on
the faces' graph, λ_h extended harmonically to the front); a body force loads every
unknown and enters K; the front's ``K_I``, ``K_II``, ``K_III`` at
:func:`~skxfem.crack.sif3d.front_points` (``result.json``'s ``front``), with the faces'
traction from the multipliers in the interaction integral's face term.

>>> from skfem import MeshTet1
>>> from skxfem.levelset import plane
>>> from skxfem.scene import Interface
>>> i = Interface(plane((0, 0.5, 0), (0, 1, 0)), law="free",
...               front=plane((0.5, 0, 0), (1, 0, 0)))
>>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 6),) * 2, np.linspace(0, 1, 3))
>>> g = Crack3D(i)
>>> c = g.cut(m, "")
>>> V = g.space(m, c)
>>> V.N == V.n_std + V.n_enr, g.normals(c)[:, 0].tolist()
(True, [0.0, 1.0, 0.0])
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementTetP1, ElementVector

from ..fem.quadrature import cell_rule
from ..levelset import unit
from ..multipliers import InterfaceRule
from .faces import face_multipliers
from .faces3d import face_functions_3d, face_rule, face_traction_3d
from .geometry import point_cells
from .geometry3d import barycentric, crack_geometry_3d, front_chains
from .sif3d import (
    DEFAULT_LENGTH,
    check_radius,
    default_radius_3d,
    domain_reach,
    end_reach,
    fitted_frame,
    front_points,
    front_sizes,
    sif_3d,
)
from .space3d import (
    CrackSpace3D,
    Load3D,
    Support3D,
    body_load,
    crack_space_3d,
    evaluation,
    mass,
    stiffness,
    supported_dofs,
    traction_load,
)
from .xspace import CrackXSpaceBase

__all__ = ["Crack3D", "CrackXSpace3D", "FrontPointsWarning", "front_reach", "front_on_boundary",
           "interior_points", "room_advice", "warn_closing", "CLOSING"]


class FrontPointsWarning(UserWarning):
    """Some points of a 3D front get no K: their interaction domain would hold no cell
    (:func:`front_reach`); or a 2D tip's domain is clipped under the default by the
    boundary or another tip, and its K is doubtful (:mod:`skxfem.gamma`); or a free
    crack's faces pass through each other at front points (K_I < 0,
    :func:`warn_closing`)."""


CLOSING = 1e-3
"""A K_I below -CLOSING × the largest |K| of the front counts as negative
(:func:`warn_closing`); above, it is round-off of a K_I = 0 (pure shear)."""


def warn_closing(interface, points: np.ndarray, K: np.ndarray) -> None:
    """Warn (:class:`FrontPointsWarning`) where a crack with ``free`` faces has K_I < 0:
    its faces pass through each other near those ``points`` (m, dim) (the law puts
    nothing between them), so that K_I is not a physical one.  ``K`` (m, 2 or 3): K_I,
    K_II (, K_III) at the points.  A crack pressed shut needs a contact law on its
    faces (``frictionless``, or ``coulomb`` with its friction), whose K_I is 0 there.
    Measured: an edge crack to the middle of the unit square, pressed by 1 on top, free
    faces: K_I = -3.54, with nothing said (frictionless faces: 0)."""
    if interface.law != "free" or not K.size:
        return
    scale = np.abs(K).max()
    closing = K[:, 0] < -CLOSING * scale
    if not closing.any():
        return
    where = "; ".join("(" + ", ".join(f"{v:.3g}" for v in x) + ")"
                      for x in points[closing][:4]) + (" …" if closing.sum() > 4 else "")
    warnings.warn(f"{interface.front.name!r}: K_I < 0 (down to {K[:, 0].min():.4g}) at "
                  f"{int(closing.sum())} of {closing.size} front points (at {where}): the "
                  f"faces of this crack, law 'free', pass through each other there (nothing "
                  f"stops them), so K_I is not a physical one; for faces pressed together "
                  f"give the crack a contact law (law = 'frictionless', or 'coulomb' with "
                  f"its friction)", FrontPointsWarning, stacklevel=3)


def interior_points(P: np.ndarray, chains: list, length: float) -> np.ndarray:
    """(m,) whether the bump along the front of each point P (3, m) (half-width
    ``length``) stays clear of the free surfaces the front ends on: its distance to the
    ends of every open chain of ``chains`` (:func:`~skxfem.crack.geometry3d.front_chains`)
    is at least that half-width.  K is trusted there only (:mod:`skxfem.crack.sif3d`'s
    notes: the surfaces add a term to the integral where the bump reaches them, and the
    field has its own singularity where the front meets a surface): on a bonded through
    crack (7³ cells), the points half a cell from the sides gave K_III = 0.21, -0.20, the
    others at most 0.010 in size.

    >>> chain = np.array([[0.5, 0.5], [0.5, 0.5], [0.0, 1.0]])      # x = y = 1/2
    >>> P = np.array([[0.5] * 4, [0.5] * 4, [0.05, 0.2, 0.5, 0.95]])
    >>> interior_points(P, [(chain, False)], 0.15).tolist()
    [False, True, True, False]
    """
    ends = [pts[:, [0, -1]] for pts, closed in chains if not closed]
    if not ends:
        return np.ones(P.shape[1], dtype=bool)
    E = np.hstack(ends)
    d = np.linalg.norm(P[:, :, None] - E[:, None], axis=0).min(axis=1)
    return d >= length * (1 - 1e-9)


def room_advice(reach: np.ndarray, h: float) -> str:
    """What limits the interaction domain of front points whose ``reach`` (n,)
    (:func:`skxfem.crack.sif3d.domain_reach`) is under the front cells' size ``h``, and
    what gives them K: cells across the front smaller than the least reach there (the
    reach is the geometry's: the body's boundary beside the front, a third of the
    distance to another front, half the radius of curvature; not the surfaces the front
    ends on, whatever its angle to them); none on the boundary itself.

    >>> print(room_advice(np.array([0.03, 0.05]), 0.125)[:55])
    their interaction domain has 0.03 of room at the least,
    """
    least = float(np.min(reach))
    return (f"their interaction domain has {least:.3g} of room at the least, under the "
            f"front cells' size {h:.3g} across the front (the body's boundary beside the "
            f"front, another front three times as far or the centre of curvature twice "
            f"as far; not a surface the front ends on, at any angle); cells across the "
            f"front under {least:.3g} there give those points K (refine the mesh about "
            f"the front there); a front on the boundary itself has none on any mesh")


def front_reach(space, radius: float | None = None
                ) -> tuple[np.ndarray, np.ndarray, float, np.ndarray]:
    """The front's points (3, m) where K is computed (:func:`skxfem.crack.sif3d.front_points`),
    how far each one's interaction domain can reach (:func:`skxfem.crack.sif3d.domain_reach`,
    with :func:`skxfem.crack.sif3d.sif_3d`'s default bump), the front cells' size h
    across the front (:func:`skxfem.crack.sif3d.front_sizes`) and whether each point is
    interior: its domain (``radius``, default :func:`skxfem.crack.sif3d.default_radius_3d`,
    clipped to the reach; that bump's half-width) clear of the surfaces the front ends on
    (:func:`interior_points` and :func:`skxfem.crack.sif3d.end_reach`: a front meeting a
    surface obliquely has its domain cut by it farther from its end than a bump's
    half-width).  A point whose reach is under h gets no K (:meth:`Crack3D.front` leaves
    it out and warns; a front with no point left has none, the solve's other results
    stand): its domain would hold no cell, and K came out anywhere between
    0 and the right value (a penny of radius 0.49 centred in the unit cube, h = 1/8, 0.01
    from four sides: K_I from 0.009 to 2.4 along its front; an edge crack's straight
    front 0.03 from the far side: K_I 48 to 55, with 1/8's default domain of 0.19).  The
    surfaces the front ends on limit the reach only where they leave a cell of room, at
    any angle to the front (:func:`skxfem.crack.sif3d.domain_reach`)."""
    chains = front_chains(space.geometry)
    h, h_along = front_sizes(space)
    P = front_points(space, h_along, chains)
    L = DEFAULT_LENGTH * h_along
    frame, kappa = fitted_frame(space, P, max(L, 2 * h_along), chains)
    reach = domain_reach(space, P, frame.e3, kappa, L, chains, h)
    R = np.minimum(default_radius_3d(space, h) if radius is None else float(radius), reach)
    clear = end_reach(space.mesh, P, frame.e3, L, chains) >= R
    return P, reach, h, interior_points(P, chains, L) & clear


def front_on_boundary(mesh, geo) -> np.ndarray:
    """Whether each front segment of the 3D crack ``geo`` lies on the body's boundary (nseg,):
    both its ends within round-off (1e-9 of its cell's size) of the plane of a boundary
    face of its cell.  A front all on the boundary is a crack that cuts the body through
    (:meth:`Crack3D.cut` refuses it, as the 2D kind refuses a tip on the boundary).

    >>> from skfem import MeshTet1
    >>> from skxfem.crack.geometry3d import crack_geometry_3d
    >>> m = MeshTet1.init_tensor(*(np.linspace(0, 1, 5),) * 3)
    >>> g = crack_geometry_3d(m, lambda x: x[2] - 0.52, lambda x: x[0] - 1.0)
    >>> bool(front_on_boundary(m, g).all())
    True
    >>> g = crack_geometry_3d(m, lambda x: x[2] - 0.52, lambda x: x[0] - 0.6)
    >>> bool(front_on_boundary(m, g).any())
    False
    """
    ends, cells = geo.segments, geo.segment_cell              # (2, 3, nseg), (nseg,)
    boundary = np.zeros(mesh.facets.shape[1], dtype=bool)
    boundary[mesh.boundary_facets()] = True
    size = np.ptp(mesh.p[:, mesh.t[:, cells]], axis=1).max(axis=0)      # (nseg,)
    on = np.zeros(cells.size, dtype=bool)
    for f in mesh.t2f[:, cells]:                              # each face of each cell
        a, b, c = (mesh.p[:, mesh.facets[k, f]] for k in range(3))
        n = np.cross(b - a, c - a, axis=0)
        n = n / np.linalg.norm(n, axis=0)
        d = np.abs(((ends - a[None]) * n[None]).sum(axis=1)).max(axis=0)   # (nseg,)
        on |= boundary[f] & (d <= 1e-9 * size)
    return on


@dataclass(frozen=True)
class Crack3D:
    """A 3D crack: Γ = {ψ = 0, φ < 0} on a ``MeshTet1``, φ the interface's ``front``
    (module notes; the contract's methods in :mod:`skxfem.gamma`)."""

    interface: object
    splits = False
    """A crack ends inside the body: it splits no region."""

    def cut(self, mesh, label: str = ""):
        """The crack's geometry (:func:`skxfem.crack.geometry3d.crack_geometry_3d`); a
        ValueError naming ``label`` if it crosses no cell."""
        i = self.interface
        try:
            geo = crack_geometry_3d(mesh, i.levelset.fun, i.front.fun)
        except ValueError as err:
            raise ValueError(f"{label or 'the crack'} ({i.levelset.name!r}, front "
                             f"{i.front.name!r}): {err}") from None
        if geo.segments.shape[-1] and front_on_boundary(mesh, geo).all():
            raise ValueError(
                f"{label or 'the crack'} ({i.levelset.name!r}, front {i.front.name!r}): its "
                f"front lies on the body's boundary all along, so the crack cuts the body "
                f"through (held together along that line only, and no K anywhere): for a "
                f"surface that cuts the body through leave the front out (an interface of "
                f"skxfem.cut), or move the front (phi = 0) into the body")
        return geo

    def space(self, mesh, cut, order: int | None = None):
        """The crack's space [a, b, c] (:func:`skxfem.crack.space3d.crack_space_3d` with the
        interface's ``enrichment`` and, if it has one, its ``enrichment_radius``);
        ``order`` is not used (its own rules)."""
        i = self.interface
        radius = getattr(i, "enrichment_radius", None) if i.enrichment == "geometric" else None
        space = crack_space_3d(mesh, cut, i.enrichment, radius)
        if i.sif_radius is not None:                    # before the solve, not after
            check_radius(i.sif_radius, front_sizes(space)[0], "sif_radius")
        return CrackXSpace3D(space)

    def multipliers(self, mesh, cut, fixed=None, per_edge=None):
        """The interface's multiplier space on the crack's crossed edges and nodes, up to
        the front (:func:`skxfem.crack.faces.crack_multipliers` on its faces' graph,
        :mod:`skxfem.crack.faces3d`), the points on an edge with a node within
        :data:`~skxfem.crack.faces.FRONT_RINGS` rings of the front cells tied to those
        behind them under a contact law (:func:`skxfem.crack.faces.face_multipliers`, as
        in 2D)."""
        i = self.interface
        return face_multipliers(i.law, i.space, mesh, cut, fixed=fixed, per_edge=per_edge)

    def normals_at(self, points: np.ndarray) -> np.ndarray:
        """∇ψ/|∇ψ| (3, n) at ``points`` on Γ."""
        n = np.asarray(self.interface.levelset.gradient(points), float)
        return unit(n)[0]

    def normals(self, cut) -> np.ndarray:
        """∇ψ/|∇ψ| (3, n) at the crack's cut points."""
        return self.normals_at(cut.points)

    def nodal(self, cut) -> np.ndarray:
        """ψ at the nodes as the solve used it."""
        return cut.psi

    def rule(self, mesh, cut) -> InterfaceRule:
        """Gauss points on the crack's faces, graded at the front
        (:func:`skxfem.crack.faces3d.face_rule`), their normals and the multiplier
        functions there (:func:`skxfem.crack.faces3d.face_functions_3d`; none if the
        crack has no point: no crossed edge, no node behind its front)."""
        R = face_rule(mesh, cut)
        lam, _ = barycentric(mesh, R.cells, R.points)
        N = (face_functions_3d(cut, R) if cut.edge_ids.size else
             sp.csr_matrix((R.weights.size, 0)))
        return InterfaceRule(points=R.points, normals=cut.face_normal[:, R.face],
                             weights=R.weights, cells=R.cells, ref=lam[:, 1:].T.copy(), N=N)

    def jump(self, V, rule: InterfaceRule) -> sp.csr_matrix:
        """U ↦ [[u_h]] = u⁻ - u⁺ at the rule's points, component-major."""
        return _face_jump(V.space, rule.cells, rule.points)

    def point_jumps(self, V, U: np.ndarray) -> np.ndarray:
        """[[u]] = u⁻ - u⁺ (3, n) at the crack's cut points (the crossings of its cut
        edges, each in a cell of its edge; a node on the crack in the cell of a face it is
        a vertex of)."""
        mesh, cut = V.mesh, V.cut
        owner = np.full(mesh.edges.shape[1], -1)
        for k in range(6):                                # the 6 edges of a cell
            owner[mesh.t2e[k]] = np.arange(mesh.t.shape[1])
        return (_face_jump(V.space, point_cells(cut, owner), cut.points) @ U).reshape(3, -1)

    def front(self, V, U: np.ndarray, material, traction=None, body_force=None, others=()
              ) -> dict:
        """``points`` (m, 3) along the front (:func:`skxfem.crack.sif3d.front_points`),
        ``K_I``, ``K_II``, ``K_III`` (m,) there (:func:`skxfem.crack.sif3d.sif_3d`, the
        interface's ``sif_radius`` the radial cone's radius; ``body_force`` the body
        force of the solved state, its term in the interaction integral) and
        ``interior`` (m,): whether K is trusted there, the point's bump clear of the free
        surfaces the front ends on (:func:`interior_points`).

        ``traction`` (3, ne): the interface traction r = σ·n at the cut points (the
        multipliers of a tie or a contact); the faces then carry t⁻ = r and t⁺ = -r,
        interpolated by the multiplier functions up to the front
        (:func:`skxfem.crack.faces3d.face_traction_3d`), in the interaction integral's
        face term: a crack pressed shut gives K = 0.  None or all zero: free faces."""
        faces = None
        if traction is not None and np.any(traction):
            faces = face_traction_3d(V.mesh, V.cut, np.asarray(traction, float))
        P, reach, h, interior = front_reach(V.space, self.interface.sif_radius)
        if not np.all(reach >= h):
            far = reach >= h
            near = int((~far).sum())
            where = "; ".join("(" + ", ".join(f"{v:.3g}" for v in x) + ")"
                              for x in P[:, ~far].T[:4]) + (" …" if near > 4 else "")
            warnings.warn(f"{self.interface.front.name!r}: no K at {near} of {far.size} "
                          f"front points (at {where}): {room_advice(reach[~far], h)}",
                          FrontPointsWarning, stacklevel=2)
            P, interior = P[:, far], interior[far]
        K = (sif_3d(V.space, U, material, P, self.interface.sif_radius,
                    body_force=body_force, faces=faces) if P.shape[1] else np.zeros((0, 3)))
        warn_closing(self.interface, P.T, K)
        return {"points": P.T.copy(), "K_I": K[:, 0], "K_II": K[:, 1], "K_III": K[:, 2],
                "interior": interior}


def _face_jump(space: CrackSpace3D, cells: np.ndarray, x: np.ndarray) -> sp.csr_matrix:
    n = cells.size
    minus, plus = (evaluation(space, cells, x, np.full(n, s)) for s in (-1.0, 1.0))
    return (minus - plus).tocsr()


@dataclass(frozen=True)
class CrackXSpace3D(CrackXSpaceBase):
    """The X-FEM space of the 3D crack kind: ``space`` its
    :class:`~skxfem.crack.space3d.CrackSpace3D`, with the methods every space is asked
    (as :class:`skxfem.gamma.CrackXSpace` in 2D)."""

    space: CrackSpace3D
    _stiffness = staticmethod(stiffness)
    _mass = staticmethod(mass)
    _support = Support3D
    _supported_dofs = staticmethod(supported_dofs)

    @property
    def basis(self):
        """The standard vector basis (it numbers the standard dofs as the space does)."""
        m = self.space.mesh
        return Basis(m, ElementVector(ElementTetP1()), quadrature=cell_rule(m, 0))

    def load(self, facet_loads, body_force=None, f: np.ndarray | None = None):
        """(f, f_b): the surface loads and body force on the standard dofs (``f`` if
        given) and on the enriched unknowns (:func:`skxfem.crack.space3d.traction_load`,
        :func:`skxfem.crack.space3d.body_load`)."""
        loads = [Load3D(facets, lambda x, n, t=t: t(x, n), normal=True)
                 for facets, t in facet_loads]
        F = traction_load(self.space, loads)
        if body_force is not None:
            F = F + body_load(self.space, body_force)
        return (F[:self.n_std] if f is None else f), F[self.n_std:]
