r"""The known answers of a 2D crack, measured: K errors, energy-error rates, conditioning.

Every study solves with :func:`skxfem.crack.solve.solve_crack` and returns small frozen
rows; nothing here draws (:mod:`skxfem.viz.crack_plots` does).  The problems:

* :func:`williams_square`: the unit square with a crack from its left face to the
  tip (0.5, 0.5), under the exact Williams near-tip field of modes (K_I, K_II)
  (:func:`skxfem.crack.williams.near_tip`): its displacement on the three uncut faces,
  its traction on the cut face (code_aster SSLP114).  :func:`williams_study` measures,
  per mesh and enrichment, the relative K error and the relative energy error;
  :func:`energy_rates` fits the rate (≈ h^½ topological, ≈ h¹ geometric).
* :func:`conditioning_study`: the condition number of the supported stiffness of the
  same square, raw, Jacobi-scaled and block-scaled (:func:`skxfem.crack.space.nodal_scaling`).
* :func:`edge_cracked_plate`: Moës et al.'s plate, W = 7, L = 16, an edge crack
  a = 3.5 under remote tension σ = 1; :func:`tada_study` compares K_I with
  σ√(πa) F(a/W) (:func:`tada_factor`, Tada, Paris & Irwin, 0.5 %).
* :func:`closed_crack`: the square under a uniform compression p across the crack,
  the faces loaded by p: K = 0 with the interaction integral's face term, K_I ≈
  -0.7 p√(π r_d) without it.
* :func:`tip_quadrature`: ∫ r^k over a tip cell by the almost-polar rule and by a
  plain Gauss rule, against :func:`polar_integral`.
* :func:`inclined_scene`: contact on the crack faces, the closed inclined Griffith
  crack under compression with Coulomb friction (:mod:`skxfem.crack.griffith`) in the
  unit square, its exact displacement on the four sides, solved through the one path
  (:func:`skxfem.solver.solve`, the contact Newton); :func:`friction_study` measures
  K_II against σ√(πa)(sin β cos β - μ cos² β) (0 where the faces stick), K_I and the
  contact pressure against σ cos² β.
* :func:`crack_inf_sup`: the inf-sup constant (:func:`skxfem.lbb.inf_sup`) of the
  naive, winner and vital spaces on a crack's faces up to its front.

Units: E = 1, ν = 0.3, plane strain (:data:`MATERIAL`), K = 1 in the Williams square.

>>> rows = williams_study([11], enrichments=("geometric",), modes=("I",))
>>> rows[0].enrichment, rows[0].K_error < 0.02, rows[0].energy < 0.2
('geometric', True, True)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import quad
from skfem import Basis, MeshQuad1, MeshTri1

from ..crack.assembly import Load, Support
from ..crack.frame import straight_frame
from ..crack.geometry import crack_geometry
from ..crack.griffith import InclinedCrack
from ..crack.quadrature import tip_rule
from ..crack.radius import ENRICHMENTS
from ..crack.sif import sif
from ..crack.solve import CrackSolution, solve_crack
from ..crack.williams import near_tip
from ..fem.material import Material
from ..fem.quadrature import cell_rule
from ..lbb import inf_sup
from ..levelset import LevelSet
from ..scene import Displacement, Interface, Scene
from ..solver import solve

__all__ = ["MATERIAL", "MODES", "ENRICHMENTS", "SCALINGS", "RADIUS", "SIF_RADIUS", "PLATE",
           "unit_square", "straight_crack", "williams_square", "WilliamsRow",
           "williams_study", "energy_rates", "ConditionRow", "conditioning_study",
           "tada_factor", "edge_cracked_plate", "PlateRow", "tada_study", "ClosedCrack",
           "closed_crack", "polar_integral", "TipQuadrature", "tip_quadrature", "summary",
           "inclined_scene", "FrictionRow", "friction_study", "InfSupRow", "crack_inf_sup"]

MATERIAL = Material(1.0, 0.3)
"""E = 1, ν = 0.3, plane strain."""
MODES = {"I": (1.0, 0.0), "II": (0.0, 1.0)}
"""(K_I, K_II) of the pure modes of the Williams square."""
SCALINGS = (None, "jacobi", "block")
"""The scalings of :func:`skxfem.crack.space.nodal_scaling`; None: raw."""
RADIUS = 0.4
"""r_e, the radius of geometric enrichment in the Williams square (side 1)."""
SIF_RADIUS = 0.3
"""r_d, the interaction domain's radius in the Williams square: inside the enriched
zone (0.75 r_e, :data:`skxfem.crack.sif.DOMAIN_FRACTION`; with r_e = r_d = 0.3, K_I was
+0.35 % at h = 1/21, with r_e = 0.4 +0.18 %)."""
PLATE = {"W": 7.0, "L": 16.0, "a": 3.5}
"""Moës, Dolbow & Belytschko (1999)'s edge-cracked plate."""
_CELLS = {"tri": MeshTri1, "quad": MeshQuad1}


def unit_square(n: int, cell: str = "tri"):
    """The unit square of n × n cells (``"tri"``: two triangles each; ``"quad"``).

    >>> unit_square(4).t.shape[1], unit_square(4, "quad").t.shape[1]
    (32, 16)
    """
    x = np.linspace(0, 1, n + 1)
    return _CELLS[cell].init_tensor(x, x)


def straight_crack(tip, beta: float) -> tuple:
    """ψ, φ (callables) and the frame of a straight crack ending at ``tip``, e₁ at the
    angle β (the crack lies behind the tip, where φ < 0).

    >>> psi, phi, frame = straight_crack((0.5, 0.5), 0.0)
    >>> float(psi(np.array([0.2, 0.7]))), float(phi(np.array([0.2, 0.7]))), frame.e2.tolist()
    (0.19999999999999996, -0.3, [-0.0, 1.0])
    """
    e1 = np.array([np.cos(beta), np.sin(beta)])
    e2 = np.array([-e1[1], e1[0]])
    O = np.asarray(tip, float)

    def psi(p):
        return e2[0] * (p[0] - O[0]) + e2[1] * (p[1] - O[1])

    def phi(p):
        return e1[0] * (p[0] - O[0]) + e1[1] * (p[1] - O[1])

    return psi, phi, straight_frame(e1, e2)


def _facets(mesh, where):
    return mesh.facets_satisfying(where, boundaries_only=True)


def williams_square(n: int, K=(1.0, 0.0), enrichment: str = "geometric", cell: str = "tri",
                    tip=(0.5, 0.5), beta: float = 0.0, radius: float = RADIUS,
                    sif_radius: float = SIF_RADIUS, scaling: str | None = "block",
                    condition: bool = False) -> tuple[CrackSolution, callable]:
    """Solve the Williams square (module notes) and return (solution, exact), ``exact(x)``
    the :class:`skxfem.crack.williams.NearTip` of the modes ``K`` at points x (2, ...).

    >>> s, exact = williams_square(7, (1.0, 0.0))
    >>> abs(s.K_I - 1) < 0.05, abs(s.K_II) < 0.01
    (True, True)
    """
    m = unit_square(n, cell)
    psi, phi, frame = straight_crack(tip, beta)
    O = np.asarray(tip, float)

    def exact(p):
        return near_tip(p, O, frame, MATERIAL, K)

    uncut = np.concatenate([_facets(m, lambda p: p[1] < 1e-12),
                            _facets(m, lambda p: p[1] > 1 - 1e-12),
                            _facets(m, lambda p: p[0] > 1 - 1e-12)])
    s = solve_crack(m, psi, phi, MATERIAL, [Support(uncut, value=lambda p: exact(p).u)],
                    [Load(_facets(m, lambda p: p[0] < 1e-12), lambda p: -exact(p).sigma[:, 0])],
                    enrichment, radius, scaling=scaling, sif_radius=sif_radius,
                    condition=condition)
    return s, exact


@dataclass(frozen=True)
class WilliamsRow:
    """One solve of the Williams square: K (K_I, K_II) against the imposed modes, the
    K error max |K - K_exact| (relative: |K_exact| = 1), the relative energy error."""

    n: int
    h: float
    enrichment: str
    mode: str
    K: tuple
    K_error: float
    energy: float
    n_dofs: int


def williams_study(ns, enrichments=ENRICHMENTS, modes=("I", "II"), cell: str = "tri"
                   ) -> tuple[WilliamsRow, ...]:
    """The Williams square for every n (cells per side), enrichment and mode."""
    rows = []
    for mode in modes:
        for kind in enrichments:
            for n in ns:
                s, exact = williams_square(n, MODES[mode], kind, cell)
                energy = s.energy_error(lambda p: exact(p).grad_u)[0]
                rows.append(WilliamsRow(n, 1 / n, kind, mode, tuple(map(float, s.K[0])),
                                        float(np.abs(s.K[0] - MODES[mode]).max()),
                                        energy, s.space.N))
    return tuple(rows)


def energy_rates(rows, mode: str = "I") -> dict:
    """The rate of the energy error per enrichment: the slope of log e against log h,
    fitted by least squares over the meshes of ``rows`` (of one ``mode``); none for an
    enrichment with one mesh.

    >>> rows = [WilliamsRow(n, 1 / n, "x", "I", (1, 0), 0, n ** -0.5, 0) for n in (4, 16)]
    >>> energy_rates(rows)
    {'x': 0.5}
    """
    out = {}
    for kind in dict.fromkeys(r.enrichment for r in rows if r.mode == mode):
        sel = [r for r in rows if r.mode == mode and r.enrichment == kind]
        if len({r.n for r in sel}) < 2:
            continue
        out[kind] = round(float(np.polyfit(np.log([r.h for r in sel]),
                                           np.log([r.energy for r in sel]), 1)[0]), 12)
    return out


@dataclass(frozen=True)
class ConditionRow:
    """The condition number of the supported stiffness of the Williams square (mode I)
    after the nodal ``scaling`` (``"raw"``, ``"jacobi"``, ``"block"``)."""

    n: int
    h: float
    enrichment: str
    scaling: str
    condition: float


def conditioning_study(ns, enrichments=ENRICHMENTS, scalings=SCALINGS
                       ) -> tuple[ConditionRow, ...]:
    """Condition numbers (:func:`skxfem.crack.space.condition_number`) for every n,
    enrichment and scaling.

    >>> row = conditioning_study([5], ("geometric",), ("block",))[0]
    >>> row.scaling, 10 < row.condition < 1e4
    ('block', True)
    """
    rows = []
    for kind in enrichments:
        for scaling in scalings:
            for n in ns:
                s, _ = williams_square(n, MODES["I"], kind, scaling=scaling, condition=True)
                rows.append(ConditionRow(n, 1 / n, kind, scaling or "raw", s.condition))
    return tuple(rows)


def tada_factor(a: float, W: float) -> float:
    """F(a/W) of a single edge crack a in a plate of width W under tension (Tada, Paris &
    Irwin 2000, 0.5 %): K_I = σ√(πa) F.

    >>> round(float(np.sqrt(np.pi * 3.5) * tada_factor(3.5, 7.0)), 2)   # Moës et al. 1999
    9.37
    """
    t = np.pi * a / (2 * W)
    return float(np.sqrt(np.tan(t) / t) * (0.752 + 2.02 * a / W
                                           + 0.37 * (1 - np.sin(t)) ** 3) / np.cos(t))


def edge_cracked_plate(nx: int = 41, cell: str = "tri", radius: float | None = None,
                       sif_radius: float | None = None, face_traction=None,
                       remote: bool = True) -> CrackSolution:
    """The plate of :data:`PLATE` on nx × ny cells, σ = 1 on its ends (``remote``), the
    crack {y = L/2, x < a}; two nodes hold the rigid modes.  ny: the odd number nearest
    above nx L/W, so that the crack runs mid-cell (nx = 41: 95).  The radii default to
    a scene's (r_e = 0.2 diameters = 3.49, r_d = 0.75 r_e = 2.62): K_I -0.36 % (tri),
    -0.16 % (quad) at nx = 41, -0.14 %, -0.09 % at 81; with r_e = 2, r_d = 2.5 (a domain
    beyond the enriched zone) -0.63 %, -0.25 % at 41.

    >>> s = edge_cracked_plate(14)
    >>> bool(abs(s.K_I / (np.sqrt(np.pi * 3.5) * tada_factor(3.5, 7.0)) - 1) < 0.05)
    True
    """
    W, L, a = PLATE["W"], PLATE["L"], PLATE["a"]
    ny = int(np.ceil(nx * L / W))
    ny += 1 - ny % 2
    m = _CELLS[cell].init_tensor(np.linspace(0, W, nx + 1), np.linspace(0, L, ny + 1))

    def up(p):
        return np.stack([0 * p[0], 1 + 0 * p[0]])

    loads = [Load(_facets(m, lambda p: p[1] > L - 1e-9), up),
             Load(_facets(m, lambda p: p[1] < 1e-9), lambda p: -up(p))] if remote else []
    c0 = int(np.argmin(np.hypot(m.p[0], m.p[1])))
    c1 = int(np.argmin(np.hypot(m.p[0] - W, m.p[1])))
    sup = [Support(nodes=np.array([c0])), Support(nodes=np.array([c1]), components=(1,))]
    return solve_crack(m, lambda p: p[1] - L / 2, lambda p: p[0] - a, MATERIAL, sup, loads,
                       "geometric", radius, sif_radius=sif_radius, face_traction=face_traction)


@dataclass(frozen=True)
class PlateRow:
    """The edge-cracked plate on one mesh: K against σ√(πa) F(a/W)."""

    cell: str
    nx: int
    h: float
    K_I: float
    K_II: float
    K_ref: float
    error: float


def tada_study(nxs=(41,), cells=("tri", "quad")) -> tuple[PlateRow, ...]:
    """:func:`edge_cracked_plate` for every mesh and cell; ``error`` = K_I / K_ref - 1."""
    W, a = PLATE["W"], PLATE["a"]
    K_ref = float(np.sqrt(np.pi * a) * tada_factor(a, W))
    rows = []
    for cell in cells:
        for nx in nxs:
            s = edge_cracked_plate(nx, cell)
            rows.append(PlateRow(cell, nx, W / nx, s.K_I, s.K_II, K_ref, s.K_I / K_ref - 1))
    return tuple(rows)


@dataclass(frozen=True)
class ClosedCrack:
    """K of a crack pressed shut by p with and without the face term, over p√(π r_d)."""

    p: float
    sif_radius: float
    with_face_term: tuple
    without_face_term: tuple


def closed_crack(n: int = 21, p: float = 1.0, sif_radius: float = SIF_RADIUS
                 ) -> ClosedCrack:
    """The square of :func:`williams_square`'s crack under σ = -p e₂⊗e₂: the uniform
    strain's displacement on the uncut faces, its traction (none) on the cut face and
    the pressure p on both crack faces (what contact would carry).  The exact field is
    uniform, K = 0.

    >>> c = closed_crack(9)
    >>> max(map(abs, c.with_face_term)) < 1e-6, -0.9 < c.without_face_term[0] < -0.5
    (True, True)
    """
    m = unit_square(n)
    psi, phi, frame = straight_crack((0.5, 0.5), 0.0)
    lam, mu = MATERIAL.lame(2)
    # σ = -p e₂⊗e₂ in plane strain: ε_yy = -p (λ + 2μ)/(4μ(λ + μ)), ε_xx = p λ/(4μ(λ + μ))
    exx, eyy = p * lam / (4 * mu * (lam + mu)), -p * (lam + 2 * mu) / (4 * mu * (lam + mu))

    def u(x):
        return np.stack([exx * x[0], eyy * x[1]])

    def pressure(x, side):                       # σ·m*, m* = -side e₂: side p e₂
        return np.stack([0 * x[0], side * p + 0 * x[0]])

    uncut = np.concatenate([_facets(m, lambda x: x[1] < 1e-12),
                            _facets(m, lambda x: x[1] > 1 - 1e-12),
                            _facets(m, lambda x: x[0] > 1 - 1e-12)])
    s = solve_crack(m, psi, phi, MATERIAL, [Support(uncut, value=u)], (), "geometric",
                    RADIUS, sif_radius=sif_radius, face_traction=pressure)
    scale = p * np.sqrt(np.pi * sif_radius)
    free = sif(s.space, s.U, MATERIAL, sif_radius)
    return ClosedCrack(p, sif_radius, tuple(float(k) for k in s.K[0] / scale),
                       tuple(float(k) for k in free / scale))


def polar_integral(tip, triangle, power: float) -> float:
    """∫ r^power over ``triangle`` (3, 2) that holds ``tip``, r = |x - tip|: the sum over
    its three edges of ∫ R(α)^(power+2)/(power+2) dα in polar coordinates about the tip,
    R(α) = d / cos(α - α_n) on an edge at distance d (scipy's adaptive quad, to 1e-13).

    >>> round(polar_integral((0, 0), np.array([[0, 0], [1, 0], [0, 1]]), 0.0), 14)
    0.5
    """
    T, P = np.asarray(tip, float), np.asarray(triangle, float)
    k = power + 2
    total = 0.0
    for i in range(3):
        A, B = P[i] - T, P[(i + 1) % 3] - T
        cross = A[0] * B[1] - A[1] * B[0]
        if abs(cross) < 1e-300:                  # the tip on this edge: no area
            continue
        t = B - A
        nrm = np.array([t[1], -t[0]]) / np.linalg.norm(t)
        d = A @ nrm
        if d < 0:
            nrm, d = -nrm, -d
        an = np.arctan2(nrm[1], nrm[0])
        a0 = np.arctan2(A[1], A[0])
        span = np.arctan2(cross, A @ B)           # signed angle from A to B
        val = quad(lambda a: (d / np.cos(a - an)) ** k / k, a0, a0 + span,
                   epsabs=0, epsrel=1e-13, limit=200)[0]
        total += val
    return abs(total)


@dataclass(frozen=True)
class TipQuadrature:
    """∫ r^power over one tip cell: exact, almost-polar rule, plain Gauss rule (its
    order and point count)."""

    power: float
    exact: float
    polar: float
    polar_points: int
    plain: float
    plain_order: int
    plain_points: int


def tip_quadrature(power: float = -0.5, n: int = 5, tip=(0.513, 0.459), beta: float = 0.3,
                   plain_order: int = 16) -> TipQuadrature:
    """∫ r^power over the tip cell of a straight crack ending inside a cell of the n × n
    square, by :func:`skxfem.crack.quadrature.tip_rule` and by a Gauss rule of
    ``plain_order`` on the whole cell, against :func:`polar_integral`.

    >>> q = tip_quadrature(-0.5)
    >>> abs(q.polar / q.exact - 1) < 1e-12, abs(q.plain / q.exact - 1) > 1e-3
    (True, True)
    """
    m = unit_square(n)
    O = np.asarray(tip, float)
    psi, phi, _ = straight_crack(O, beta)
    g = crack_geometry(m, psi, phi)
    if g.tip_cells.size != 1:
        raise ValueError(f"the tip {tuple(tip)} must lie inside one cell, not on its edges")
    rule = tip_rule(g)
    b = Basis(m, m.elem(), elements=rule.cells, quadrature=(rule.X, rule.W))
    x = b.mapping.F(rule.X, tind=rule.cells)
    live = b.dx > 0
    polar = float((b.dx[live] * np.hypot(x[0] - O[0], x[1] - O[1])[live] ** power).sum())
    X, W = cell_rule(m, plain_order)
    pb = Basis(m, m.elem(), elements=g.tip_cells, quadrature=(X, W))
    xp = pb.mapping.F(X, tind=g.tip_cells)
    plain = float((pb.dx * np.hypot(xp[0] - O[0], xp[1] - O[1]) ** power).sum())
    exact = polar_integral(O, m.p[:, m.t[:, g.tip_cells[0]]].T, power)
    return TipQuadrature(power, exact, polar, int(live.sum()), plain, plain_order, W.size)


def summary(williams=(), conditioning=(), plates=(), friction=(), inf_sup=()) -> dict:
    """The numbers of the studies for ``summary.json``: per row a dict, and the fitted
    energy rates of mode I; ``friction`` (:func:`friction_study`) and ``inf_sup``
    (:func:`crack_inf_sup`) rows of contact on the faces.

    >>> summary(plates=[PlateRow("tri", 41, 7 / 41, 9.3, 0.0, 9.37, -0.0075)])["tada"][0]["cell"]
    'tri'
    """
    def rows(rs):
        return [{k: (list(v) if isinstance(v, tuple) else v) for k, v in vars(r).items()}
                for r in rs]

    return {"material": {"E": MATERIAL.E, "nu": MATERIAL.nu, "plane": MATERIAL.plane},
            "williams": {"scene": "unit square, crack from x = 0 to the tip (0.5, 0.5), exact "
                                  "Williams field: displacements on 3 faces, traction on the "
                                  f"cut face; r_e = {RADIUS}, r_d = {SIF_RADIUS}",
                         "rows": rows(williams),
                         "energy_rates": energy_rates(williams) if williams else {}},
            "conditioning": rows(conditioning),
            "tada": rows(plates),
            "friction": rows(friction),
            "inf_sup": rows(inf_sup)}


def inclined_scene(n: int = 21, beta: float = 30.0, friction: float = 0.3,
                   cell: str = "tri", a: float = 0.25, space: str = "vital",
                   enrichment: str = "geometric") -> tuple[InclinedCrack, Scene]:
    """The closed inclined crack (:class:`skxfem.crack.griffith.InclinedCrack`, β in
    degrees, half-length ``a``, centre (0.5, 0.5), σ = 1) in the unit square of n × n
    cells: its exact displacement on the four sides, law ``coulomb`` (``frictionless``
    for μ = 0) on the crack with the multiplier space ``space`` and the tip
    ``enrichment``.

    >>> c, scene = inclined_scene(11, 30.0, 0.3, enrichment="topological")
    >>> scene.interfaces[0].law, scene.interfaces[0].enrichment, round(float(c.pressure), 4)
    ('coulomb', 'topological', 0.75)
    """
    c = InclinedCrack(a=a, beta=np.radians(beta), sigma=1.0, friction=friction,
                      center=(0.5, 0.5))

    def u(k):
        return lambda p: c.field(p, MATERIAL)[0][k]

    disp = tuple(Displacement(b, {"x": u(0), "y": u(1)})
                 for b in ("xmin", "xmax", "ymin", "ymax"))
    crack = Interface(LevelSet(c.psi, 2, "crack line"),
                      law="coulomb" if friction > 0 else "frictionless", space=space,
                      friction=friction if friction > 0 else None,
                      front=LevelSet(c.phi, 2, "crack ends"), enrichment=enrichment)
    return c, Scene(unit_square(n, cell), material=MATERIAL, displacements=disp,
                    interfaces=(crack,))


@dataclass(frozen=True)
class FrictionRow:
    """One solve of :func:`inclined_scene`: ``slides`` whether the faces slide
    (μ < tan β); ``K_II`` (two tips) and ``K_I`` over σ√(πa); ``K_II_exact`` over
    σ√(πa) with the tip frame's sign; ``K_II_error`` the largest |K_II - exact| over
    σ√(πa) (relative to |exact| where it slides: ``K_II_rel``); ``pressure`` the mean
    contact pressure over σ cos² β, ``pressure_dev`` the largest deviation of a point;
    ``enrichment`` the crack's tip enrichment."""

    cell: str
    n: int
    beta: float
    friction: float
    slides: bool
    K_I: tuple
    K_II: tuple
    K_II_exact: tuple
    K_II_error: float
    K_II_rel: float | None
    pressure: float
    pressure_dev: float
    enrichment: str = "geometric"


def friction_study(ns=(21,), betas=(30.0,), frictions=(0.0, 0.3, 0.8), cells=("tri",),
                   enrichment: str = "geometric") -> tuple[FrictionRow, ...]:
    """:func:`inclined_scene` solved (:func:`skxfem.solver.solve`) for every mesh,
    angle β (degrees), friction μ and cell, with the tip ``enrichment``.

    >>> (r,) = friction_study([11], frictions=[0.3])
    >>> r.slides, r.K_II_rel < 0.05, abs(r.pressure - 1) < 0.01
    (True, True, True)
    """
    rows = []
    for cell in cells:
        for n in ns:
            for beta in betas:
                for mu in frictions:
                    c, scene = inclined_scene(n, beta, mu, cell, enrichment=enrichment)
                    r = solve(scene)
                    (front,) = r.front
                    scale = c.sigma * np.sqrt(np.pi * c.a)
                    exact = np.array([c.K_II_at(p) for p in front["points"]])
                    err = np.abs(front["K_II"] - exact)
                    p = -r.normal_traction / c.pressure
                    rows.append(FrictionRow(
                        cell, n, float(beta), float(mu), bool(c.slides),
                        tuple(float(k) for k in front["K_I"] / scale),
                        tuple(float(k) for k in front["K_II"] / scale),
                        tuple(float(k) for k in exact / scale), float(err.max() / scale),
                        float((err / np.abs(exact)).max()) if c.slides else None,
                        float(p.mean()), float(np.abs(p - 1).max()), enrichment))
    return tuple(rows)


@dataclass(frozen=True)
class InfSupRow:
    """The inf-sup constant β_h (:class:`skxfem.lbb.InfSup`) of a multiplier ``space``
    on a crack's faces: ``h`` the mean crossed-edge length, ``size`` the multipliers,
    ``n_zero`` the spurious modes, ``enrichment`` the crack's tip enrichment."""

    space: str
    cell: str
    n: int
    h: float
    beta: float
    size: int
    n_zero: int
    enrichment: str = "geometric"


def crack_inf_sup(ns=(11, 21, 41, 81), spaces=("naive", "winner", "vital"),
                  cell: str = "tri", enrichment: str = "geometric"
                  ) -> tuple[InfSupRow, ...]:
    """β_h of each space on an edge crack from x = 0 to the tip (0.5, 0.5) of the unit
    square of n × n cells (n odd: the crack runs mid-cell), the bottom clamped, the normal
    multipliers of a contact on the faces (law ``frictionless``, whose space ties the
    points next to the tip to those behind them, :func:`skxfem.crack.faces.face_multipliers`;
    measured as the ``bilateral`` tie on that space), the tip ``enrichment`` of
    :class:`skxfem.scene.Interface`: :func:`skxfem.lbb.inf_sup` with the crack's mass.

    >>> rows = crack_inf_sup([11], ("naive", "vital"))
    >>> [(r.space, r.size, round(r.beta, 2)) for r in rows]
    [('naive', 7, 0.26), ('vital', 4, 0.9)]
    """
    rows = []
    for n in ns:
        for name in spaces:
            crack = Interface(LevelSet(lambda x: x[1] - 0.5, 2, "y - 0.5"),
                              law="frictionless", space=name,
                              front=LevelSet(lambda x: x[0] - 0.5, 2, "x - 0.5"),
                              enrichment=enrichment)
            scene = Scene(unit_square(n, cell), material=MATERIAL,
                          displacements=(Displacement("ymin", {"x": 0.0, "y": 0.0}),),
                          interfaces=(crack,))
            r = inf_sup(scene, law="bilateral")
            rows.append(InfSupRow(name, cell, n, r.h, r.beta, r.size, r.n_zero, enrichment))
    return tuple(rows)
