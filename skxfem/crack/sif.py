r"""Stress intensity factors of a solved X-FEM field: the interaction integral on the mesh.

:func:`skxfem.crack.interaction.stress_intensity` takes arrays at quadrature
points; this module makes them from a solution U on the crack's space:

1. **the tip and its frame**: the tip T of the geometry and e₁, e₂ from ∇φ_h, ∇ψ_h
   in a tip cell (:func:`skxfem.crack.frame.tip_frame`);
2. **the domain**: q is the P1/Q1 interpolant of the nodal values
   q(r_i) = :func:`skxfem.crack.interaction.q_function` of the nodes' distance to T,
   1 inside ρR, 0 beyond R, with R = min(r_d, distance from T to the boundary, half
   the distance to the other tips), the default r_d at most a tenth of a curved crack's
   radius of curvature at T (:func:`tip_radius`, below); the
   integrand holds ∇q, so the domain is the cells where the nodal q differ (a ring
   away from the tip once ρR exceeds a cell);
3. **the points**: the cells' own rules (:func:`skxfem.crack.assembly.rule_groups`:
   sub-triangles in split cells, the almost-polar rule in a tip cell, a Gauss rule of
   order 8 elsewhere): the X-FEM sub-cell weights, not whole-cell ones (crack-notes,
   trap 3);
4. **the fields**: ∇u_h at the points (:func:`skxfem.crack.space.evaluation`), σ by
   Hooke's law, ∇q;
5. **the faces**: if the faces carry a traction, its term −∫ t·u^aux_{,1} q ds on each
   face (Gauss points on the crack segments, q interpolated there); a free crack has
   none;
6. **a body force** b: its term −∫ b·u^aux_{,1} q dA over every cell where q ≠ 0 (the
   tip cells on their almost-polar rule), q interpolated at the points
   (:mod:`skxfem.crack.interaction`); without one the domain is the ring of step 2.

The auxiliary fields are a straight crack's. On a crack of curvature κ = 1/ρ they miss
the faces by about κr at r from the tip, and K follows the domain's radius R: a circular
arc (radius 3, α = asin 2/3) under equal biaxial tension, against Sih, Paris & Erdogan's
closed form (2.0772, 0.7934), quadrilaterals, r_e = 2, 29 November: K_I +1.8, +2.6,
+4.2 % and K_II -3.3, -9.4, -16.4 % with R = 0.5, 1, 1.5 at h = 1/6 on a 40 plate (the same
at h = 1/3: the error is the domain's, not the mesh's; the plate adds +0.9 % and +2.8 %,
from 20, 40 and 80 plates), so about +4.5 R/ρ per cent in K_I and -36 R/ρ in K_II. The
default 0.75 r_e (1.5 there; 4.2, 4.8 with the default r_e on the 20, 40 plates)
converged in h to that wrong K. :data:`CURVATURE_FRACTION` = 0.1 keeps K_II within about
4 % where the mesh allows (R = ρ/10 at 2 cells and more); the domain keeps
:data:`CURVATURE_CELLS` = 2 cells (on this arc K stays on the same line in R from 2
cells up: R = 0.34 at h = 1/6, K_I +1.65 %, K_II -1.5 % on the 40 plate), and
:mod:`skxfem.gamma` warns a tip whose curvature would take it under. The default on the
40 plate: K_I +2.1, +1.4, +1.6 %, K_II -6.0, -3.3, -1.5 % at h = 1/3, 1/4, 1/6
(triangles: +2.1/+0.0, +1.1/-0.4, +2.0/+1.0 % and -8.5/-5.4, -4.8/-4.0, -2.8/-1.1 % at
the two tips).

>>> from skfem import MeshTri1
>>> from skxfem.crack.geometry import crack_geometry
>>> from skxfem.crack.space import crack_space
>>> from skxfem.fem.material import Material
>>> m = MeshTri1.init_tensor(np.linspace(0, 1, 8), np.linspace(0, 1, 8))
>>> V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
>>> np.round(sif(V, np.zeros(V.N), Material(1.0, 0.3)), 12).tolist()   # no field, no K
[0.0, 0.0]
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np
from skfem import Basis

from ..fem.loads import force_field
from ..fem.material import Material
from .assembly import face_rule, rule_groups
from .frame import TipFrame, tip_frame
from .geometry import CrackGeometry, nearest_on_segments
from .interaction import CrackFace, q_function, stress_intensity
from .radius import DOMAIN_CELLS, DOMAIN_FRACTION, check_radius
from .space import CrackSpace, evaluation

__all__ = ["DEFAULT_CELLS", "DOMAIN_FRACTION", "CURVATURE_FRACTION", "CURVATURE_CELLS",
           "default_radius",
           "tip_curvature", "curvature_reach", "tip_radius", "other_tips_distance",
           "tip_and_frame", "boundary_distance", "tip_reach", "check_reach", "segments_distance",
           "gamma_segments", "tip_room", "check_clearance", "nodal_q", "sif"]

DEFAULT_CELLS = DOMAIN_CELLS[2]
"""The smallest default domain radius r_d, in sizes of the tip cell (4; the default r_e
is at least DEFAULT_CELLS / DOMAIN_FRACTION of them: :mod:`skxfem.crack.radius`)."""


def default_radius(space: CrackSpace, h: float) -> float:
    """The default r_d: :data:`DOMAIN_FRACTION` r_e with geometric enrichment, and at
    least :data:`DEFAULT_CELLS` tip-cell sizes h (a domain of one or two cells misses K
    by several per cent).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 22), np.linspace(0, 1, 22))
    >>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5)
    >>> round(default_radius(crack_space(m, g, "geometric", 0.4), 1 / 21), 4)
    0.3
    >>> round(default_radius(crack_space(m, g, "topological"), 1 / 21), 4)
    0.1905
    """
    r_e = space.radius if space.enrichment == "geometric" else 0.0
    return max(DOMAIN_FRACTION * r_e, DEFAULT_CELLS * h)


CURVATURE_FRACTION = 0.1
"""The default domain of a curved crack's tip reaches at most this fraction of the
crack's radius of curvature ρ = 1/|κ| there (:func:`tip_curvature`, :func:`tip_radius`).
The auxiliary fields are those of a straight crack: a domain of radius R around a tip
of curvature κ = 1/ρ misses K by about -36 R/ρ per cent in K_II and +4.5 R/ρ in K_I
(the arc crack under biaxial tension, module notes)."""

CURVATURE_CELLS = 2.0
"""The fewest tip-cell sizes the curvature leaves the default domain (:func:`tip_radius`);
under :data:`DEFAULT_CELLS` for a straight crack, as few as a boundary may leave it
(:mod:`skxfem.gamma`'s ``CLIPPED_CELLS``): the arc crack's K follows the same line in
R from 2 cells up."""


def tip_curvature(space: CrackSpace, tip: int, origin: np.ndarray, frame: TipFrame,
                  window: float) -> float:
    r"""The curvature κ of the crack near a tip: the circle through the tip nearest (least
    squares) the crack's points (the ends of its pieces, ``geometry.segments``) within
    ``window`` of it.

    In the tip frame (s along e₁, t along e₂) a circle through the tip is
    t = κ' (s² + t²) / 2 + u s (its centre at (-u, 1)/κ'), linear in κ' and u; a
    straight crack is κ' = 0, t = u s exactly, whatever ∇ψ_h's error in e₁.  Then
    κ = κ' / √(1 + u²), positive when the crack turns towards e₂ (Ω⁺); 0 with under two
    points off the tip.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(-1, 1, 41), np.linspace(-1, 1, 41))
    >>> psi = np.hypot(m.p[0], m.p[1] + 2) - 2.5         # a circle of radius 2.5
    >>> V = crack_space(m, crack_geometry(m, psi, m.p[0] - 0.3))
    >>> x, f, h = tip_and_frame(V, 0)
    >>> round(1 / abs(tip_curvature(V, 0, x, f, 0.5)), 2)
    2.5
    """
    p = space.geometry.segments.transpose(1, 0, 2).reshape(2, -1) - origin[:, None]
    p = p[:, np.linalg.norm(p, axis=0) <= window]
    s, t = frame.e1 @ p, frame.e2 @ p
    A = np.stack([(s ** 2 + t ** 2) / 2, s], axis=1)
    (k, u), _, rank, _ = np.linalg.lstsq(A, t, rcond=None)
    return float(k / np.hypot(1.0, u)) if rank == 2 else 0.0


def curvature_reach(space: CrackSpace, tip: int = 0) -> tuple[float, float]:
    """How far the default domain of a tip may reach for the crack's curvature there
    (:data:`CURVATURE_FRACTION` / |κ|, inf for a straight crack: :func:`tip_curvature`
    over the unclipped default domain, :func:`default_radius`), and that default.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> from skxfem.crack.space import crack_space
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 22), np.linspace(0, 1, 22))
    >>> g = crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5)    # straight: no clip
    >>> curvature_reach(crack_space(m, g, "topological"), 0)[0]
    inf
    """
    origin, frame, h = tip_and_frame(space, tip)
    r_d = default_radius(space, h)
    kappa = abs(tip_curvature(space, tip, origin, frame, r_d))
    return (CURVATURE_FRACTION / kappa if CURVATURE_FRACTION < kappa * r_d else np.inf), r_d


def tip_radius(space: CrackSpace, tip: int = 0) -> float:
    """The default domain radius at a tip: :func:`default_radius`, clipped to
    :func:`curvature_reach` (a fraction of the crack's radius of curvature) but not under
    :data:`CURVATURE_CELLS` tip-cell sizes (a mesh that coarse for the curvature gets a
    :class:`~skxfem.crack.kind3d.FrontPointsWarning` from :mod:`skxfem.gamma`).  A
    straight crack keeps :func:`default_radius` exactly."""
    reach, r_d = curvature_reach(space, tip)
    if reach >= r_d:
        return r_d
    h = tip_and_frame(space, tip)[2]
    return min(r_d, max(reach, CURVATURE_CELLS * h))


def other_tips_distance(geometry: CrackGeometry, tip: int) -> float:
    """Half the distance from a tip to the nearest other tip (inf for one tip): the
    domain of one tip must not reach another (a centre crack of half-length 0.1 on the
    unit square in tension, h = 1/41: K_I/σ√(πa) = 1.0540 with R = 0.1, 1.0561 with
    0.19, 1.0602 with 0.2 (the ring at the other tip), 1.151 with 0.25 and 1.425 with
    0.35 (holding it))."""
    tips = geometry.tips
    d = np.linalg.norm(tips - tips[:, tip:tip + 1], axis=0)
    d = np.delete(d, tip)
    return 0.5 * float(d.min()) if d.size else np.inf


def tip_and_frame(space: CrackSpace, tip: int = 0) -> tuple[np.ndarray, TipFrame, float]:
    """The tip point (2,), its frame from ∇φ_h, ∇ψ_h at the tip, the mean over its tip
    cells (one for a tip inside a cell; those on either side of the edge or around the
    node it lies on, so that a mirror image of the scene gets the mirror frame), and the
    size (diameter) of its first tip cell.

    A curved crack's ∇ψ_h turns by about h/R from cell to cell: the first cell alone
    broke the mirror symmetry of an arc crack whose tips lie on mesh lines (R = 6,
    h = 1/3, a mirror-symmetric quad mesh: K_II -1.055 and -0.934 at mirror tips)."""
    geo = space.geometry
    if not 0 <= tip < geo.tips.shape[1]:
        raise ValueError(f"tip must be in 0 .. {geo.tips.shape[1] - 1}, got {tip!r}")
    ks = np.flatnonzero(geo.tip_of_cell == tip)
    cells, ref = geo.tip_cells[ks], geo.tip_ref[:, ks]
    b = Basis(space.mesh, space.mesh.elem(), elements=cells,
              quadrature=(ref[:, :, None], np.ones((cells.size, 1))))
    gphi = b.interpolate(geo.phi).grad[:, :, 0].mean(axis=1)
    gpsi = b.interpolate(geo.psi).grad[:, :, 0].mean(axis=1)
    h = float(np.ptp(space.mesh.p[:, space.mesh.t[:, cells[0]]], axis=1).max())
    return geo.tips[:, tip], tip_frame(gphi, gpsi), h


def boundary_distance(mesh, x: np.ndarray) -> float:
    """The distance from the point x (2,) to the boundary facets of ``mesh``.

    >>> from skfem import MeshTri1
    >>> boundary_distance(MeshTri1(), np.array([0.25, 0.5]))
    0.25
    """
    f = mesh.boundary_facets()
    a, b = mesh.p[:, mesh.facets[0, f]], mesh.p[:, mesh.facets[1, f]]
    return float(nearest_on_segments(a, b - a, x[:, None])[2].min())


def tip_reach(mesh, geo, tip: int) -> tuple[float, bool, float]:
    """How far the interaction domain of tip ``tip`` of the crack geometry ``geo`` can
    reach (the distance to the boundary of ``mesh``, and half that to the nearest other
    tip: :func:`boundary_distance`, :func:`other_tips_distance`), whether the boundary
    is the nearer, and the size h of its first tip cell (its largest extent, as
    :func:`tip_and_frame`'s).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 11), np.linspace(0, 1, 11))
    >>> reach, wall, h = tip_reach(m, crack_geometry(m, m.p[1] - 0.55, m.p[0] - 0.75), 0)
    >>> round(reach, 4), wall, round(h, 4)
    (0.25, True, 0.1)
    """
    wall = boundary_distance(mesh, geo.tips[:, tip])
    other = other_tips_distance(geo, tip)
    cell = geo.tip_cells[np.flatnonzero(geo.tip_of_cell == tip)[0]]
    return min(wall, other), bool(wall <= other), float(np.ptp(mesh.p[:, mesh.t[:, cell]],
                                                         axis=1).max())


def check_reach(mesh, geo, label: str = "", tips=None) -> list[float]:
    """Refuse a tip whose interaction domain cannot reach past its own cell
    (:func:`tip_reach`: a tip within a cell of the boundary, or two tips within two
    cells): the interaction integral then has no domain, and a domain of a cell or two
    misses K by several per cent (an edge crack's tip 0.1 from the far side of the unit
    square, h = 1/20: K_I 13 % low, 1/40: 3.5 %, against 1/80's).  ``tips``: which
    (default: every tip of ``geo``).  Returns their reaches."""
    reaches = []
    for k in range(geo.tips.shape[1]) if tips is None else tips:
        reach, wall, h = tip_reach(mesh, geo, k)
        reaches.append(reach)
        if reach < h:
            x = ", ".join(f"{v:.4g}" for v in geo.tips[:, k])
            what = ("from the body's boundary" if wall else
                    f"from half-way to another tip (at {2 * reach:.3g})")
            raise ValueError(
                f"{label or 'the crack'}: the tip at ({x}) is {reach:.3g} {what}, under the "
                f"size of its cell ({h:.3g}): its stress intensity factors need an "
                f"interaction domain of a few cells around it; refine the mesh there "
                f"(cells a few times smaller than that distance) or move the front")
    return reaches


def segments_distance(x: np.ndarray, segments: np.ndarray | None) -> float:
    """The distance from the point x (2,) to the segments (2, 2, n) [end, coordinate,
    piece] of the scene's other interfaces (their Γ_h: a crack's pieces, a cut's facets);
    inf for none.

    >>> line = np.array([[[0.0], [0.8]], [[1.0], [0.8]]])      # y = 0.8, 0 <= x <= 1
    >>> round(segments_distance(np.array([0.5, 0.5]), line), 12)
    0.3
    """
    if segments is None or np.shape(segments)[-1] == 0:
        return np.inf
    a, b = segments[0], segments[1]
    return float(nearest_on_segments(a, b - a, np.asarray(x, float)[:, None])[2].min())


def gamma_segments(cut) -> np.ndarray:
    """Γ_h of an interface of a 2D scene as segments (2, 2, n) [end, coordinate, piece]:
    a crack's pieces (:class:`~skxfem.crack.geometry.CrackGeometry`), a cut's facets
    (:class:`skxfem.cut.Cut`)."""
    if hasattr(cut, "segments"):
        return cut.segments
    return np.transpose(cut.points[:, cut.facets], (1, 0, 2))


def tip_room(mesh, geo: CrackGeometry, tip: int, others) -> tuple[float, int]:
    """How far the interaction domain of tip ``tip`` of the crack ``geo`` may reach for
    the scene's other interfaces (``others``: their cuts; a crack's geometry has
    ``tips``), and which of them is the nearest (-1: none): two cells short of each
    one's Γ_h (no cell of the domain, the cells within R + h of the tip, is one it cuts:
    its own enrichment, a Heaviside jump, the domain would integrate across), and half
    the distance to a crack's tip (as to the crack's own other tips,
    :func:`other_tips_distance`: its singular field); inf for none.

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 11), np.linspace(0, 1, 11))
    >>> a = crack_geometry(m, m.p[1] - 0.55, m.p[0] - 0.25)
    >>> b = crack_geometry(m, m.p[1] - 0.55, 0.75 - m.p[0])
    >>> room, k = tip_room(m, a, 0, [b])
    >>> round(room, 4), k              # half of the 0.5 between the tips
    (0.25, 0)
    """
    h = tip_reach(mesh, geo, tip)[2]
    x = geo.tips[:, tip]
    rooms = []
    for cut in others:
        room = segments_distance(x, gamma_segments(cut)) - 2 * h
        tips = getattr(cut, "tips", None)
        if tips is not None and tips.size:
            room = min(room, 0.5 * float(np.linalg.norm(tips - x[:, None], axis=0).min()))
        rooms.append(room)
    if not rooms:
        return np.inf, -1
    k = int(np.argmin(rooms))
    return float(rooms[k]), k


def check_clearance(mesh, cuts, names) -> list[list[float]]:
    """Refuse a 2D crack's tip whose interaction domain has under a cell of room for the
    scene's other interfaces (:func:`tip_room`): two cracks' tips that close also enrich
    the same nodes with nearly the same functions (their system is singular).  ``cuts``:
    each interface's cut (a crack's geometry has ``tips``), ``names`` how the message
    names them.  Returns, for each cut, the room of each of its tips (empty for a cut
    without tips).

    >>> from skfem import MeshTri1
    >>> from skxfem.crack.geometry import crack_geometry
    >>> m = MeshTri1.init_tensor(np.linspace(0, 1, 11), np.linspace(0, 1, 11))
    >>> a = crack_geometry(m, m.p[1] - 0.55, m.p[0] - 0.45)
    >>> b = crack_geometry(m, m.p[1] - 0.55, 0.5 - m.p[0])
    >>> check_clearance(m, (a, b), ("a", "b"))
    Traceback (most recent call last):
    ...
    ValueError: a: the tip at (0.45, 0.55) is 0.05 from b: its interaction domain has ...
    """
    out = []
    for k, cut in enumerate(cuts):
        tips = getattr(cut, "tips", None)
        if mesh.dim() != 2 or tips is None:
            out.append([])
            continue
        others = [c for j, c in enumerate(cuts) if j != k]
        named = [n for j, n in enumerate(names) if j != k]
        row = []
        for i in range(tips.shape[1]):
            room, j = tip_room(mesh, cut, i, others)
            h = tip_reach(mesh, cut, i)[2]
            if room < h:
                x = ", ".join(f"{v:.4g}" for v in tips[:, i])
                d = segments_distance(tips[:, i], gamma_segments(others[j]))
                raise ValueError(
                    f"{names[k]}: the tip at ({x}) is {d:.3g} from {named[j]}: its "
                    f"interaction domain has under a cell ({h:.3g}) of room clear of it "
                    f"(two cells short of another interface, half-way to another tip), "
                    f"and enrichments that close are nearly the same functions; refine the "
                    f"mesh there (cells a few times smaller than that distance) or move the "
                    f"interfaces apart")
            row.append(room)
        out.append(row)
    return out


def nodal_q(space: CrackSpace, origin: np.ndarray, r_d: float, plateau: float,
            boundary: float) -> np.ndarray:
    """q at the nodes: :func:`skxfem.crack.interaction.q_function` of their distance."""
    d = space.mesh.p - origin[:, None]
    r = np.linalg.norm(d, axis=0)
    q, _ = q_function(r, d / np.where(r > 0, r, 1.0), r_d, plateau, boundary)
    return q


def _faces(space, q_nodes, face_traction):
    """The two :class:`CrackFace` rules of the crack pieces, with their tractions."""
    x, w, cells, ref = face_rule(space)
    b = Basis(space.mesh, space.mesh.elem(), elements=cells,
              quadrature=(ref[:, :, None], np.ones((cells.size, 1))))
    q = np.asarray(b.interpolate(q_nodes))[:, 0]
    faces = []
    for side in (1, -1):
        t = np.asarray(face_traction(x, side), float)
        if t.shape != x.shape or not np.all(np.isfinite(t)):
            raise ValueError(f"face_traction must return finite values of shape {x.shape}, "
                             f"got {t.shape}")
        faces.append(CrackFace(x, w, t, q, side))
    return faces


def sif(space: CrackSpace, U: np.ndarray, material: Material, r_d: float | None = None,
        plateau: float = 0.5, tip: int = 0, face_traction: Callable | None = None,
        body_force=None, others: Callable | None = None,
        room: float = np.inf) -> np.ndarray:
    """(K_I, K_II) at a tip of the solution U by the domain interaction integral.

    Parameters
    ----------
    space, U : the crack's space and the unknowns [a, b, c].
    material : the :class:`skxfem.fem.material.Material` (plane strain or stress).
    r_d : the domain radius; default :func:`tip_radius` (:func:`default_radius`, at most
        a fraction of a curved crack's radius of curvature); clipped to the distance from
        the tip to the boundary and half that to the other tips; one under the tip cell's
        size is refused (:func:`skxfem.crack.radius.check_radius`: no cell in the domain).
    plateau : ρ: q = 1 inside ρR (:func:`skxfem.crack.interaction.q_function`).
    tip : which tip of the geometry.
    face_traction : ``(x, side) -> (2, n)`` the traction σ·m* the face of ``side``
        (+1: Ω⁺, -1: Ω⁻) carries at points x; None for a free crack.
    body_force : the body force b the solution carries
        (:func:`skxfem.fem.loads.force_field`: ``x -> (2, n)`` or two values);
        None: none.
    others : ``(cells, ref) -> (2, 2, npts)``: ∇u of the field's parts that are not
        on this crack's unknowns (the enrichment of the scene's other cracks, whose
        branch functions reach far past their own cells), added to ∇u_h at the
        domain's points (cells and reference coordinates); None: none.
    room : how far the domain may reach for the scene's other interfaces
        (:func:`tip_room`); R is clipped to it, and one under a cell is refused.
    """
    U = np.asarray(U, float)
    if U.shape != (space.N,):
        raise ValueError(f"U must hold the {space.N} unknowns [a, b, c], got shape {U.shape}")
    origin, frame, h = tip_and_frame(space, tip)
    if r_d is not None:
        check_radius(r_d, h, "r_d (sif_radius)", 2)
    r_d = tip_radius(space, tip) if r_d is None else r_d
    boundary = check_reach(space.mesh, space.geometry, tips=[tip])[0]
    if room < h:
        x = ", ".join(f"{v:.4g}" for v in origin)
        raise ValueError(f"the tip at ({x}) has {room:.3g} of room for the scene's other "
                         f"interfaces, under a cell ({h:.3g}): refine the mesh there or move "
                         f"them apart")
    boundary = min(boundary, room)
    q_nodes = nodal_q(space, origin, r_d, plateau, boundary)
    qt = q_nodes[space.mesh.t]
    if body_force is None:
        domain = np.flatnonzero(qt.max(axis=0) > qt.min(axis=0))
    else:                                         # b's term: wherever q ≠ 0
        b = force_field(body_force, 2)
        domain = np.flatnonzero(qt.max(axis=0) > 0)
    xs, ws, gus, sigs, gqs, qs = [], [], [], [], [], []
    lam, mu = material.lame(2)
    for G in rule_groups(space, domain, plain_order=4):
        cells, ref, side, x, w = G.points()
        _, gu = evaluation(space, cells, ref, side).at(U)
        if others is not None:
            gu = gu + others(cells, ref)
        eps = (gu + np.swapaxes(gu, 0, 1)) / 2
        sig = 2 * mu * eps + lam * (eps[0, 0] + eps[1, 1]) * np.eye(2)[:, :, None]
        live = G.scalar.dx != 0                           # padding only: weights may be < 0
        xs.append(x)
        ws.append(w)
        gus.append(gu)
        sigs.append(sig)
        qh = G.scalar.interpolate(q_nodes)
        gqs.append(np.asarray(qh.grad)[:, live])
        qs.append(np.asarray(qh)[live])
    faces = () if face_traction is None else _faces(space, q_nodes, face_traction)
    x = np.hstack(xs)
    body = {} if body_force is None else {"body_force": b(x), "q": np.concatenate(qs)}
    return stress_intensity(x, np.concatenate(ws), np.concatenate(gus, axis=2),
                            np.concatenate(sigs, axis=2), np.hstack(gqs), origin, frame,
                            material, faces, **body)
