"""Contact and friction on the faces of a 3D crack up to its front (issue 29, items 4 and
7): the multiplier spaces on the crossed edges of a tetrahedral mesh and the nodes of
a crack through them (skxfem.crack.faces3d), the contact Newton through the 3D crack
kind of Γ (skxfem.crack.kind3d), the face term of the 3D interaction integral fed by the
multipliers (skxfem.crack.sif3d: a crack pressed shut gives K = 0), the closed inclined
crack with Coulomb friction through a plane-strain slab against Dolbow, Moës &
Belytschko's K_II, and the inf-sup constant of the spaces near a 3D front
(skxfem.studies.cracks3d)."""
import json

import numpy as np
import pytest
from skfem import MeshTet1

from skxfem.app.cli import main
from skxfem.crack.faces import crack_multipliers, face_multipliers, front_points, tie_front
from skxfem.crack.faces3d import face_rule, vertex_values
from skxfem.crack.geometry3d import crack_geometry_3d
from skxfem.crack.sif3d import _point_frames
from skxfem.gamma import gamma
from skxfem.problem import assemble
from skxfem.scene.file import load_scene
from skxfem.scene.model import resolve
from skxfem.solver import solve
from skxfem.studies.cracks3d import (
    MATERIAL,
    crack_inf_sup_3d,
    inclined_slab,
    pressed_penny,
    pressed_slab,
)


def _slab(n, nz):
    return MeshTet1.init_tensor(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1),
                                np.linspace(0, 1, nz + 1))


@pytest.mark.parametrize("name", ["naive", "winner", "vital"])
def test_spaces_on_the_crossed_edges_keep_a_constant_up_to_the_front(name):
    """Each space lives on the edges the crack crosses (none ahead of the front), every
    row of P sums to 1, and λ_h on the faces, front cells included, sums to 1."""
    m = _slab(11, 2)
    g = crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.53)
    assert g.edge_ids.size > 0 and np.all(g.points[0] < 0.53), "none ahead of the front"
    S = crack_multipliers(name, m, g)
    assert S.P.shape[0] == g.edge_ids.size
    assert np.allclose(np.asarray(S.P.sum(axis=1)).ravel(), 1.0)
    if name != "naive":
        assert S.size < g.edge_ids.size, "a stable space keeps fewer multipliers"
    assert np.allclose(np.asarray(vertex_values(g).sum(axis=1)).ravel(), 1.0)
    assert (g.facets < 0).any(), "the front cells' faces have vertices on the front"
    R = face_rule(m, g)
    assert np.isclose(R.weights.sum(), 0.53), "the faces' rule covers {y = 1/2, x < 0.53}"
    rule = gamma(pressed_slab(11, 2, space=name).interfaces[0]).rule(m, g)
    assert abs(rule.N.sum(axis=1) - 1).max() < 1e-12, "λ_h up to the front"


@pytest.mark.parametrize("name", ["naive", "winner", "vital"])
def test_the_points_next_to_a_3d_front_take_the_lambda_behind_them(name):
    """skxfem.crack.faces.tie_front on a 3D crack: the points on an edge with a node
    within two rings of the front cells (x = 0.36 to 0.50 for the front x = 0.53 at
    h = 1/11) lose their own multipliers; each takes a mean (weights ≥ 0, summing to
    one) of the last points behind the band (x = 0.32), the others keep their rows;
    vital edges and groups only where a point keeps its row.  The 3D crack kind of Γ
    builds its spaces so under a contact law (skxfem.crack.faces.face_multipliers; a
    crack bonded under tension, 11³ cells, opened near its front when tied: K_I 0.013
    -> 0.071, tests/test_crack_kind.py)."""
    m = _slab(11, 2)
    g = crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.53)
    tied = front_points(m, g)
    x = g.points[0]
    assert np.allclose(np.unique(x[tied].round(12)), np.arange(4, 6, 0.5) / 11)
    S = crack_multipliers(name, m, g)
    T = tie_front(S, m, g)
    assert T.name == name and T.size < S.size and T.P.shape[0] == g.edge_ids.size
    assert np.allclose(np.asarray(T.P.sum(axis=1)).ravel(), 1.0) and T.P.min() >= 0
    N = tie_front(crack_multipliers("naive", m, g), m, g).P.toarray()
    source = np.flatnonzero(~tied)[np.abs(N[tied]).sum(axis=0) > 0]   # a column per kept point
    assert np.allclose(x[source], 3.5 / 11), "the last points behind the band"
    kept = S.P[~tied].toarray()
    assert np.allclose(T.P[~tied].toarray(), kept[:, np.abs(kept).sum(axis=0) > 0])
    if name == "vital":
        assert T.vital.any() and not (T.vital & tied).any()
        assert T.groups[T.vital].max() < T.size and np.all(T.groups[~T.vital] == -1)
    q = assemble(resolve(pressed_slab(11, 2, space=name)), "bilateral").interfaces[0]
    assert q.P.shape[1] < crack_multipliers(name, q.V.mesh, q.cut).size
    for law, size in (("coulomb", T.size), ("bonded", S.size), ("bilateral", S.size)):
        assert face_multipliers(law, name, m, g).size == size, "a tie holds every point"


def test_a_3d_crack_made_of_front_points_keeps_its_space():
    """A crack 1.65 cells long: every point is within two rings of the front cells, so
    tie_front keeps the space (no point to take a λ from)."""
    m = _slab(11, 2)
    g = crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.15)
    S = crack_multipliers("vital", m, g)
    assert front_points(m, g).all() and tie_front(S, m, g) is S
    assert not front_points(m, g, 1).all()


@pytest.mark.parametrize("front", [0.53, 3 / 7 + 1e-4, 0.5])
def test_the_faces_rule_integrates_the_branch_functions_powers_of_r(front):
    """r = -φ_h is linear on each face: the rule, √r uniform on the two triangles of each
    face cut by r's level line, integrates √r and 1/√r to rounding, the front mid-cell,
    1e-4 past a node (the rule graded at vertices on the front only: -2.7 % on 1/√r)
    and through the tetrahedra's diagonal faces."""
    m = _slab(7, 2)
    R = face_rule(m, crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - front))
    assert np.all(R.weights > 0) and np.allclose(R.points[1], 0.5)
    r = front - R.points[0]
    assert np.isclose((R.weights / np.sqrt(r)).sum(), 2 * np.sqrt(front), rtol=1e-10)
    assert np.isclose((R.weights * np.sqrt(r)).sum(), 2 / 3 * front ** 1.5, rtol=1e-10)


def test_the_3d_crack_contact_problem_goes_through_the_one_path():
    """assemble gives the 3D crack its multipliers on the crossed edges and a coupling on
    [a, b, c]."""
    pb = assemble(resolve(pressed_slab(7)), "bilateral")
    q = pb.interfaces[0]
    assert q.P.shape[0] == q.cut.edge_ids.size and q.B.shape == (q.P.shape[1], q.V.N)
    assert abs(q.rule.N.sum(axis=1) - 1).max() < 1e-12


@pytest.mark.parametrize("law", ["frictionless", "coulomb", "adhesive", "bilateral", "bonded"])
def test_a_through_crack_pressed_shut_gives_K_zero_with_the_face_term(law):
    """σ_yy = -p everywhere (the faces carry p, the multipliers): measured (n = 11,
    nz = 2, every law) |K_I| ≤ 0.9e-3, |K_II| ≤ 0.4e-3 p√(πa), the pressure within
    2.4e-4 of p at every crossing, the jump 1e-5; without the face term K_I ≈ -0.68
    (-0.48 with the smaller default zone before crack.space3d.cross_section: it depends
    on the domain, as the issue says)."""
    r = solve(pressed_slab(11, 2, law))
    (front,) = r.front
    scale = np.sqrt(np.pi * 0.5)
    for key in ("K_I", "K_II", "K_III"):
        assert np.abs(front[key]).max() < 1e-3 * scale, key
    p = -r.normal_traction
    assert abs(p.mean() - 1) < 1e-4 and np.abs(p - 1).max() < 1e-3
    assert np.abs(r.jump).max() < 1e-4, "the faces stay shut and stuck"
    q = r.problem.interfaces[0]
    free = gamma(q.interface).front(q.V, r.U[q.columns], MATERIAL)   # no face traction
    assert np.all((free["K_I"] > -0.8 * scale) & (free["K_I"] < -0.3 * scale)), \
        "the face term makes K vanish"


def test_a_through_crack_pressed_shut_with_its_front_on_the_cells_faces():
    """n = 21, front x = 1/2: the front runs along the tetrahedra's diagonal faces, and
    the cells ahead of it share those faces.  Measured |K_I| ≤ 0.51e-3, |K_II| ≤ 0.04e-3
    p√(πa) (0.21e-3, 0.18e-3 on a free crack's rules of the integral, which left other
    places of the front at 1.6e-3, sif3d.FACE_RULES: the integral's error moves by a few
    1e-4 with its rules, issue 29 asks 1e-3), the last crossings' pressure within 1e-4
    of p.  When round-off (φ_h = +1e-17 on
    their side of the face) left those cells out of the front cells, their plain rule
    integrated the branch functions' 1/√r gradients on their face: 0.971 p at the last
    crossings and |K_I| = 3.2e-3 (0.4e-3 with the exact pressure)."""
    r = solve(pressed_slab(21, 2, front=0.5))
    (front,) = r.front
    scale = np.sqrt(np.pi * 0.5)
    for key in ("K_I", "K_II", "K_III"):
        assert np.abs(front[key]).max() < 1e-3 * scale, key
    p = -r.normal_traction
    assert np.abs(p - 1).max() < 1e-3


@pytest.mark.parametrize("n, front", [(7, 0.5), (7, 0.5125), (9, 0.4), (11, 0.6),
                                      (13, 0.4125), (13, 0.575)])
def test_the_pressed_slabs_exact_state_holds_K_zero_on_coarse_meshes(n, front):
    """The exact state of pressed_slab (σ = -p e_y ⊗ e_y, the faces carrying p) through
    sif_3d on coarse meshes, the front where the free crack's rules did worst: measured
    |K| ≤ 1.61e-3, 1.51e-3, 1.11e-3, 0.84e-3 p√(πa) at n = 7, 9, 11, 13 on them over 17
    fronts x = 0.40 to 0.60, ≤ 0.78e-3 on sif3d.FACE_RULES (a closed crack's K is the
    difference of the domain and face terms, each about 0.5 p√(πa))."""
    from skxfem.crack.faces3d import face_traction_3d
    from skxfem.crack.sif3d import sif_3d

    V = assemble(resolve(pressed_slab(n, 2, front=front)), "bilateral").interfaces[0].V.space
    U = np.zeros(V.N)
    p = V.mesh.p
    E, nu = MATERIAL.E, MATERIAL.nu
    U[V.nodal_dofs] = np.array([nu * p[0], -p[1], nu * p[2]]) / E
    t = np.zeros((3, V.geometry.edge_ids.size))
    t[1] = -1.0
    K = sif_3d(V, U, MATERIAL, faces=face_traction_3d(V.mesh, V.geometry, t))
    assert np.abs(K).max() < 1e-3 * np.sqrt(np.pi * front)


@pytest.mark.parametrize("n, front", [(7, 0.495), (13, 0.575)])
def test_a_through_crack_pressed_shut_on_coarse_meshes(n, front):
    """Solved, the front where a piece of a front cell passes within a hundredth of its
    size of it (the stiffness's closest grading steps, quadrature3d.NEAR_GRADING) or the
    free crack's rules of the integral did worst: measured over n = 7 to 31 and 17
    fronts |K| ≤ 0.86e-3 p√(πa), the pressure within 0.23 % (before: 1.64e-3 with the
    pressure 0.55 % off at n = 7, x = 0.495; 1.39e-3 at n = 13, x = 0.575)."""
    r = solve(pressed_slab(n, 2, front=front))
    (front_,) = r.front
    K = np.abs(np.c_[front_["K_I"], front_["K_II"], front_["K_III"]]).max()
    assert K < 1e-3 * np.sqrt(np.pi * front)
    assert np.abs(-r.normal_traction - 1).max() < 3e-3


def test_a_penny_pressed_shut():
    """The penny a = 0.55 in [-1, 1]³ at n = 10 (h = 0.2: under three cells per radius),
    sif_radius 0.25: measured |K_I| ≤ 2.7e-3, |K_II| ≤ 1.3e-3, |K_III| ≤ 0.8e-3 p√(πa)
    (1.97e-3, 2.11e-3, 0.82e-3 before the integral's rules for faces that carry a
    traction, sif3d.FACE_RULES: at under three cells per radius no rule is reliable)
    (the face term removes K_I ≈ -0.53), the pressure 1.0000 p on average, within 0.27 %
    at every crossing, the jump 1.1e-4.  h = 0.125, 0.1 (n = 16, 20, not run here: 64 s
    at n = 20): |K_I| ≤ 0.81e-3, 0.69e-3, |K_II| ≤ 0.53e-3, 0.41e-3, the pressure within
    0.35 %, 0.14 %: K is that of the exact state (the next test), the interaction
    integral's own error; issue 29's 1e-3 met from h = 0.125.  With the branch tube of
    sif_3d on the collapsed 4³ rule (skxfem.crack.sif3d.TUBE_ORDER's notes) |K_I| 3.6e-3,
    0.70e-3, 1.08e-3.  Before the near rule was graded (skxfem.crack.space3d.near_points) and θ
    was left continuous in the cells ψ_h crosses ahead of the front
    (skxfem.crack.space3d._kinds): |K_I| 3.2e-3, 1.5e-3, 2.6e-3, the pressure within
    1.6 %, 0.8 %, 1.9 %."""
    r = solve(pressed_penny(10))
    (front,) = r.front
    scale = np.sqrt(np.pi * 0.55)
    assert len(front["K_I"]) > 12, "points all along the closed front"
    assert np.abs(front["K_I"]).max() < 4e-3 * scale
    assert np.abs(front["K_II"]).max() < 2.2e-3 * scale
    assert np.abs(front["K_III"]).max() < 1.1e-3 * scale
    p = -r.normal_traction
    assert abs(p.mean() - 1) < 2e-4 and np.abs(p - 1).max() < 0.005
    assert np.abs(r.jump).max() < 2e-4
    q = r.problem.interfaces[0]
    free = gamma(q.interface).front(q.V, r.U[q.columns], MATERIAL)
    assert np.all(free["K_I"] < -0.3 * scale), "the face term makes K vanish"


def _exact_penny(n):
    """The pressed penny's mesh, geometry, space and exact state U (u = (νx, νy, -z)/E on
    the standard unknowns, E = 1, ν = 0.3, p = 1)."""
    from skxfem.crack.space3d import crack_space_3d

    m = MeshTet1.init_tensor(*(np.linspace(-1, 1, n + 1),) * 3)
    g = crack_geometry_3d(m, m.p[2] - 0.05, np.hypot(m.p[0], m.p[1]) - 0.55)
    V = crack_space_3d(m, g)
    U = np.zeros(V.N)
    for c, u in enumerate((0.3 * m.p[0], 0.3 * m.p[1], -m.p[2])):
        U[V.nodal_dofs[c]] = u
    return m, g, V, U


@pytest.mark.parametrize("n, floor", [(10, 3e-3), (20, 1e-3)])
def test_the_pressed_pennys_exact_state_gives_the_integrals_own_floor(n, floor):
    """The exact state of the penny pressed shut (the enriched unknowns 0, the faces
    carrying the exact p) through sif_3d, sif_radius 0.25: measured |K_I| ≤ 2.6e-3,
    0.73e-3, 0.68e-3 and |K_II| ≤ 1.3e-3, 0.33e-3, 0.39e-3 p√(πa) at n = 10, 16, 20
    (h = 0.2, 0.125, 0.1) on the
    rules of faces that carry a traction (sif3d.FACE_RULES; on a free crack's rules
    |K_I| ≤ 1.8e-3, 0.81e-3, 0.71e-3 and |K_II| ≤ 2.0e-3, 0.52e-3, 0.41e-3 at n = 10,
    16, 20), the interaction integral's own error on the curved front
    (with the branch tube on the collapsed 4³ rule, sif3d.TUBE_ORDER's notes: |K_I|
    3.4e-3, 0.76e-3, 1.0e-3).
    With many more points (10³ to 14³ on every piece near the front and in the branch
    tube) |K_I| stays at about 1.7e-3, 0.8 to 1.0e-3, 0.55e-3 while |K_II| falls to
    1e-5: what is left in K_I is not the quadrature alone; the pieces' rules move it by
    ±0.4e-3 at h = 0.125 (the weight q is C¹: its kinks at r = R/2, R and |s| = L)."""
    from skxfem.crack.faces3d import face_traction_3d
    from skxfem.crack.sif3d import sif_3d

    m, g, V, U = _exact_penny(n)
    t = np.zeros((3, g.edge_ids.size))
    t[2] = -1.0
    K = sif_3d(V, U, MATERIAL, radius=0.25, faces=face_traction_3d(m, g, t)) / np.sqrt(
        np.pi * 0.55)
    assert np.abs(K[:, 0]).max() < floor and np.abs(K[:, 1:]).max() < floor
    if n == 10:
        free = sif_3d(V, U, MATERIAL, radius=0.25) / np.sqrt(np.pi * 0.55)
        assert np.all(free[:, 0] < -0.3), "the face term makes K vanish"


@pytest.mark.parametrize("z0", [0.0, 1e-9])
def test_a_penny_on_or_a_hair_off_the_node_plane_pressed_shut(z0):
    """The exact state of the penny pressed shut (as above, n = 10, sif_radius 0.25)
    on the node plane z = 0 and 1e-9 above it: measured |K_I| ≤ 5.2e-3, 3.8e-3, |K_II| ≤
    2.4e-3, 1.7e-3 p√(πa), the P1 front's error at 2.75 cells per radius as at z = 0.05
    (2.6e-3, 1.3e-3; on the node plane at n = 16, 20: 1.2e-3, 1.3e-3, against 1.6e-3 and
    2.3e-3 at z = 0.03, 0.0625, 0.68e-3 at z = 0.05).  Solved (frictionless), the same
    K to 3 digits on the node plane, 3.5e-3 and 1.7e-3 at 1e-9, the pressure within
    2.5e-4 and 8.4e-4.  At 1e-9 the crack had 3.8 % too much face
    (geometry3d._vertex_tol): K_I = 0.32 for the exact state, and solved 0.13, the
    pressure off by up to 32 %, with nothing said."""
    from skxfem.crack.faces3d import face_traction_3d
    from skxfem.crack.sif3d import sif_3d
    from skxfem.crack.space3d import crack_space_3d

    m = MeshTet1.init_tensor(*(np.linspace(-1, 1, 11),) * 3)
    g = crack_geometry_3d(m, m.p[2] - z0, np.hypot(m.p[0], m.p[1]) - 0.55)
    V = crack_space_3d(m, g)
    U = np.zeros(V.N)
    for c, u in enumerate((0.3 * m.p[0], 0.3 * m.p[1], -m.p[2])):
        U[V.nodal_dofs[c]] = u
    t = np.zeros((3, g.edge_ids.size))
    t[2] = -1.0
    K = sif_3d(V, U, MATERIAL, radius=0.25, faces=face_traction_3d(m, g, t)) / np.sqrt(
        np.pi * 0.55)
    assert np.abs(K[:, 0]).max() < 6e-3 and np.abs(K[:, 1:]).max() < 3e-3, K


def test_the_pressed_pennys_exact_state_balances_its_faces_on_every_row():
    """K U₀ = Jᵀ(w p) for the exact state U₀ (σ = -p e_z ⊗ e_z, the faces carrying p):
    each row is ∫ σ : ∇v over the body against ∫ p e_z · [[v]] on the faces, equal by the
    divergence theorem when the cells' and the faces' rules agree.  Measured at n = 16 on
    the branch rows, over h^2.5 p: 1.4e-3 (5.5e-3 with the 5³ rule near the front not
    graded, skxfem.crack.quadrature3d.NEAR_GRADING; 1.6e-2 with θ forced to ±π in the
    cells ψ_h crosses ahead of the front); the standard and Heaviside rows 3e-15."""
    from skxfem.crack.faces3d import face_rule
    from skxfem.crack.kind3d import _face_jump
    from skxfem.crack.space3d import stiffness

    m, g, V, U = _exact_penny(16)
    R = face_rule(m, g)
    t = np.zeros((3, R.weights.size))
    t[2] = -1.0
    res = stiffness(V, MATERIAL) @ U - _face_jump(V, R.cells, R.points).T @ (t * R.weights).ravel()
    h = 2 / 16
    first = V.n_std + 3 * V.heaviside.size
    near = np.unique(m.t[:, g.cells])                       # no load on these rows
    assert np.abs(res[V.nodal_dofs[:, near]]).max() < 1e-12 * h ** 2
    assert np.abs(res[V.n_std:first]).max(initial=0.0) < 1e-12 * h ** 2
    assert np.abs(res[first:]).max() < 2.5e-3 * h ** 2.5


@pytest.mark.parametrize("friction", [0.3, 0.8])
def test_coulomb_inclined_crack_through_a_slab(friction):
    """β = 30°, a = 1/4 at n = 21, nz = 3 (the slab 0.3 thick, the middle points a bump's
    width from its faces), the points within two rings of the front cells tied to those
    behind them (skxfem.crack.faces.tie_front).  μ = 0.3 < tan β: the faces slide;
    measured K_II/K_exact 1.0000 and 1.0008 at the middle of the two fronts, |K_I| ≤
    1.5e-4, |K_III| ≤ 4.0e-5 σ√(πa), the pressure 1.0003 σ cos²β on average, within
    1.04 % at every point.  μ = 0.8: they stick, |K_I| ≤ 0.9e-4, |K_II| ≤ 0.5e-4 σ√(πa),
    the pressure within 0.02 %.  Without the tie (every point its own multiplier):
    K_II/K_exact 1.0011, 1.0019, |K_I| ≤ 0.94e-3, the worst point 1.02 %; sticking
    |K_I| ≤ 2.2e-4, the pressure within 0.11 % (before the cross-section zone of
    crack.space3d: 1.22e-3 sliding without the tie, 2.1e-4 with it)."""
    c, scene = inclined_slab(21, 3, friction)
    r = solve(scene, linear="auto")
    assert r.n_dofs > 5000 and r.linear == "direct", "auto: direct for a crack's contact"
    (front,) = r.front
    P = np.asarray(front["points"])
    middle = np.isclose(P[:, 2], 0.15)
    assert middle.sum() == 2 and set(np.round(P[middle, 0], 3)) == {0.283, 0.717}
    scale = c.sigma * np.sqrt(np.pi * c.a)
    if c.slides:
        expect = np.array([c.K_II_at(p[:2]) for p in P[middle]])
        assert np.all(np.abs(expect) > 0.2 * scale)
        assert np.abs(front["K_II"][middle] / expect - 1).max() < 0.004
    else:
        assert np.abs(front["K_II"][middle]).max() < 3e-4 * scale
    assert np.abs(front["K_I"][middle]).max() < 5e-4 * scale
    assert np.abs(front["K_III"][middle]).max() < 3e-4 * scale
    p = -r.normal_traction
    assert abs(p.mean() / c.pressure - 1) < 0.002
    assert np.abs(p / c.pressure - 1).max() < 0.02


@pytest.mark.parametrize("n", [11, 13])
def test_centre_crack_whose_cells_straddle_the_two_fronts_bisector(n):
    """The inclined centre crack at n = 11 (nz = 2): its face points half-way between the
    two fronts lie in cells whose nodes point ahead of opposite fronts, e₁ₕ vanishes
    there; the face term stopped with 'grad_phi is zero or parallel to grad_psi'.  Those
    points take their nearest node's direction (no domain reaches them): measured
    K_II/K_exact 1.005-1.009, |K_I| ≤ 3.9e-3, 0.84e-3 σ√(πa) at n = 11, 13 (n = 11: every
    point is within two rings of the front cells, none tied; n = 13 without the tie of
    skxfem.crack.faces.tie_front: 2.0e-3, the worst point's pressure 3.4 %, now 0.64 %)."""
    c, scene = inclined_slab(n, 2, 0.0)
    (front,) = solve(scene).front
    P = np.asarray(front["points"])
    expect = np.array([c.K_II_at(p[:2]) for p in P])
    assert np.abs(front["K_II"] / expect - 1).max() < 0.02
    assert np.abs(front["K_I"]).max() < 5e-3 * c.sigma * np.sqrt(np.pi * c.a)


@pytest.mark.parametrize("friction", [0.0, 1.2])
def test_a_45_degree_centre_crack_centred_on_a_node(friction):
    """inclined_slab(10, 2, μ, 45°): the centre (1/2, 1/2) is a node, where φ = |t·(x - c)|
    - a has its kink, and ∇φ_h vanishes in the cells around it; the front's nodal
    directions stopped with 'grad_phi is zero or parallel to grad_psi at 96 point(s)'
    (with any law).  Those cells now give no sign to their nodes.  Measured: sliding
    (μ = 0) K_II within 1.1 % of Dolbow et al.'s, |K_I| ≤ 0.7e-3 σ√(πa), the pressure
    within 0.44 %; sticking (μ = 1.2) |K_II| ≤ 1.1e-3 σ√(πa), the pressure
    within 0.03 %."""
    c, scene = inclined_slab(10, 2, friction, 45.0)
    r = solve(scene)
    (front,) = r.front
    scale = c.sigma * np.sqrt(np.pi * c.a)
    if c.slides:
        expect = np.array([c.K_II_at(p[:2]) for p in front["points"]])
        assert np.abs(front["K_II"] / expect - 1).max() < 0.02
    else:
        assert np.abs(front["K_II"]).max() < 3e-3 * scale
    assert np.abs(front["K_I"]).max() < 2e-3 * scale
    assert np.abs(-r.normal_traction / c.pressure - 1).max() < 0.01


def test_point_frames_between_two_fronts_take_the_nearest_node():
    """A point of a cell whose nodal directions cancel takes its nearest node's, ∂e₁ = 0."""
    e1_nodes = np.array([[1.0, 0, 0], [-1.0, 0, 0], [1.0, 0, 0], [-1.0, 0, 0]])
    nodes = np.array([[0, 1, 2, 3], [0, 1, 2, 3]])
    lam = np.array([[0.25, 0.25, 0.25, 0.25], [0.7, 0.1, 0.1, 0.1]])
    dlam = np.zeros((2, 4, 3))
    e1, G, R = _point_frames(e1_nodes, nodes, lam, dlam, np.array([[0.0, 0], [1, 1], [0, 0]]))
    assert np.allclose(R[0, :, 0], [1, 0, 0]) and np.allclose(G[:, :, 0], 0)
    assert np.allclose(R[0, :, 1], [1, 0, 0])             # 0.6 of a unit vector: its own


def test_inf_sup_of_the_3d_crack_spaces_near_the_front():
    """β_h up to the front, cells of one size h = 1/n, the enriched zone 4 h: measured
    vital 0.516, 0.442, 0.431, 0.428, 0.426 and winner 0.450, 0.390, 0.373, 0.369, 0.366
    at n = 7, 11, 15, 21, 31 (bounded); naive has zero modes (14 at n = 7: four
    multipliers on a quadrilateral cut of a tetrahedron).  The front just past a node
    (0.01 h) at n = 15: vital 0.405, winner 0.271; a sticking contact (the tangents'
    multipliers too) vital 0.287 there, 0.323 with the front mid-cell."""
    rows = crack_inf_sup_3d([11, 21])
    beta = {(r.space, r.n): r for r in rows}
    for name, low in (("vital", 0.4), ("winner", 0.35)):
        assert all(beta[name, n].n_zero == 0 and beta[name, n].beta > low for n in (11, 21))
        assert beta[name, 21].beta > 0.9 * beta[name, 11].beta
    assert beta["naive", 11].n_zero > 0
    (near,) = crack_inf_sup_3d([15], ("vital",), offset=0.01, law="stick")
    assert near.n_zero == 0 and near.beta > 0.25


SLAB_TOML = """
name = "slab-contact"
mesh = {box = {n = [7, 7, 2], cell = "tet"}}
levelset = {expr = "y - 0.5", front = "x - 0.5"}
interface = {law = "frictionless"}
material = {E = 1.0, nu = 0.3}
displacement = [{boundary = "ymin", y = 0.0}, {boundary = "xmin", x = 0.0},
                {boundary = "zmin", z = 0.0}]
load = [{boundary = "ymax", traction = [0.0, -1.0, 0.0]}]
solver = {linear = "direct"}
"""


def test_a_3d_contact_crack_scene_file_through_skxfem_run_writes_front(tmp_path):
    """A 3D crack with law frictionless in a scene file: pressed shut, result.json's
    front has K ≈ 0 at its points, the traction the pressure 1, as in Python."""
    path = tmp_path / "slab.toml"
    path.write_text(SLAB_TOML)
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    data = json.loads((tmp_path / "out" / "result.json").read_text())
    (front,) = data["front"]
    assert data["law"] == ["frictionless"] and len(front["points"]) == 2
    scale = np.sqrt(np.pi * 0.5)
    for key in ("K_I", "K_II", "K_III"):
        assert np.abs(front[key]).max() < 2e-3 * scale, key
    t = np.array(data["traction"])
    assert abs(t[:, 1].mean() + 1) < 1e-3, "the contact pressure p = 1"
    r = solve(load_scene(path))
    assert np.allclose(r.front[0]["K_I"], front["K_I"], atol=1e-12)


def test_a_3d_crack_through_nodes_lists_them_as_points_after_the_crossings():
    """A crack through mesh nodes (crack.geometry.crack_points, as a Cut lists a vertex
    on Γ): the crossings first, then each node on the crack behind the front that is a
    vertex of a face, the point (v, v) with edge id -1; the faces index them, a node on
    the front is none.  Along a mesh plane (n even) every point is a node; the plane
    y = 1/2 + (x - 1/2)/2 crosses some edges strictly and passes through some nodes."""
    m = _slab(10, 2)
    g = crack_geometry_3d(m, m.p[1] - 0.5, m.p[0] - 0.5)
    assert np.all(g.edge_ids == -1) and np.array_equal(g.edges[0], g.edges[1])
    assert np.allclose(g.points, m.p[:, g.edges[0]])
    behind = (m.p[1] == 0.5) & (m.p[0] < 0.5)
    assert np.array_equal(np.sort(g.edges[0]), np.flatnonzero(behind))
    front = np.isclose(g.faces[..., 0], 0.5).T                    # (3, nface)
    assert np.all((g.facets >= 0) == ~front), "a face vertex behind the front is a point"
    S = crack_multipliers("vital", m, g)
    assert S.P.shape == (15, 15), "a node has a multiplier of its own"
    g = crack_geometry_3d(m, m.p[1] - 0.5 - 0.5 * (m.p[0] - 0.5), m.p[0] - 0.5)
    node = g.edge_ids < 0
    assert node.sum() == 6 and (~node).sum() == 15 and not node[:15].any()
    assert np.allclose(g.points[:, node], m.p[:, g.edges[0, node]])
    E = vertex_values(g)
    assert np.allclose(np.asarray(E.sum(axis=1)).ravel(), 1.0)
    at_node = np.flatnonzero(np.isin(g.facets.ravel(), np.flatnonzero(node)))
    assert np.allclose(E[at_node].max(axis=1).toarray(), 1.0), "a node holds its own λ"


@pytest.mark.parametrize("law, space", [
    ("frictionless", "vital"), ("coulomb", "vital"), ("adhesive", "vital"),
    ("bilateral", "vital"), ("bonded", "vital"), ("frictionless", "naive"),
    ("frictionless", "winner"), ("bonded", "winner")])
def test_a_crack_along_a_mesh_plane_pressed_shut(law, space):
    """pressed_slab at n = 10: the crack y = 1/2 runs along a node plane, its multipliers
    at the nodes (refused before: 'crosses no mesh edge strictly').  Measured, every law
    and space: |K_I| ≤ 3.0e-4, |K_II| ≤ 7.3e-5 p√(πa), the pressure within 7.1e-5 of p at
    every node, the jump ≤ 1.1e-5 (n = 12: |K_I| ≤ 0.8e-4)."""
    r = solve(pressed_slab(10, 2, law, space))
    q = r.problem.interfaces[0]
    assert np.all(q.cut.edge_ids == -1) and q.cut.edge_ids.size == 15
    (front,) = r.front
    scale = np.sqrt(np.pi * 0.5)
    for key in ("K_I", "K_II", "K_III"):
        assert np.abs(front[key]).max() < 1e-3 * scale, key
    assert np.abs(-r.normal_traction - 1).max() < 2e-4
    assert np.abs(r.jump).max() < 5e-5


def _tilted(law, load="uniaxial", shift=0.0):
    """The crack y = 1/2 + (x - 1/2)/2 (- shift), x < 1/2, through the unit cube of
    10 × 10 × 2 cells, on rollers at x, y, z = 0, pressed by 1 on y = 1 (uniaxial) or on
    x, y, z = 1 (hydrostatic)."""
    from skxfem.levelset import LevelSet
    from skxfem.scene import Displacement, Interface, Scene, Solver, SurfaceLoad

    crack = Interface(LevelSet(lambda x: x[1] - 0.5 - 0.5 * (x[0] - 0.5) - shift, 3, "tilt"),
                      law=law, friction=0.8 if law == "coulomb" else None,
                      front=LevelSet(lambda x: x[0] - 0.5, 3, "x - 0.5"))
    loads = [SurfaceLoad("ymax", traction=(0.0, -1.0, 0.0))]
    if load == "hydrostatic":
        loads += [SurfaceLoad("xmax", traction=(-1.0, 0.0, 0.0)),
                  SurfaceLoad("zmax", traction=(0.0, 0.0, -1.0))]
    disp = (Displacement("ymin", {"y": 0.0}), Displacement("xmin", {"x": 0.0}),
            Displacement("zmin", {"z": 0.0}))
    return solve(Scene(_slab(10, 2), material=MATERIAL, displacements=disp,
                       loads=tuple(loads), interfaces=(crack,), solver=Solver(linear="direct")))


@pytest.mark.parametrize("law, load, p", [("frictionless", "hydrostatic", 1.0),
                                          ("coulomb", "uniaxial", 0.8),
                                          ("bonded", "uniaxial", 0.8)])
def test_a_crack_that_crosses_edges_and_passes_through_nodes_held_shut(law, load, p):
    """The tilted crack (15 crossings, 6 nodes): a uniform stress solves it, the faces
    carry p = 1 (hydrostatic) or n_y² = 0.8 (σ_yy = -1; stuck, μ = 0.8 > tan = 1/2, or
    tied).  Measured: the pressure within 4.7e-5 of p at every point, nodes included
    (before, with no multiplier at the nodes, as good at the crossings: a uniform stress
    is in both spaces), the jump ≤ 2.2e-5, |K_I| ≤ 0.8e-4,
    |K_II| ≤ 0.8e-4 p√(πa) (uniaxial: |K_III| = 3.3e-2 at the front's ends, as with the
    crack moved off the nodes)."""
    r = _tilted(law, load)
    q = r.problem.interfaces[0]
    node = q.cut.edge_ids < 0
    assert node.sum() == 6 and (~node).sum() == 15
    assert np.abs(-r.normal_traction - p).max() < 1e-4
    assert np.abs(r.jump).max() < 5e-5, "the faces stay shut, the nodes too"
    (front,) = r.front
    scale = np.sqrt(np.pi * 0.5)
    for key in ("K_I", "K_II") + (("K_III",) if load == "hydrostatic" else ()):
        assert np.abs(front[key]).max() < 1e-3 * scale, key


def test_a_crack_through_nodes_sliding_does_not_interpenetrate_there():
    """The tilted crack, frictionless, pressed by σ_yy = -1: its faces slide.  With no
    multiplier at the 6 nodes on it, they interpenetrated ([[u]]·n up to 1.7e-2 at the
    nodes, 3.5e-2 at the crossings, against a slip of 0.32) and |K_I| was 7.7e-3 p√(πa);
    with theirs, [[u]]·n ≤ 1.6e-4 at the nodes, 1.5e-3 at the crossings, |K_I| ≤ 1.2e-3
    and K_II within 0.4 % of the crack moved 1e-3 off the nodes (which crosses edges
    only: |K_I| ≤ 0.8e-3); with the cross-section zone (crack.space3d) 0.9e-4, 2.3e-3,
    1.5e-3 (1.8e-3 off the nodes).  The points within two rings of the front cells
    (x ≥ 0.3: two of the crack's five cells; its front x = 1/2 on a node plane) now take
    the λ of those at x = 0.2 (skxfem.crack.faces.tie_front), which hold the faces shut
    on their weighted mean only: [[u]]·n ≤ 1.8e-3 at the nodes, 5.1e-3 at x = 0.2,
    |K_I| ≤ 5.1e-3 (the same off the nodes), K_II within 0.3 %.  This coarse crack is
    where the tie costs: with the front at x = 0.45, 0.53, 0.55 it takes |K_I| from
    3.1e-3, 3.2e-3, 3.4e-3 to 4.9e-3, 1.8e-3, 0.8e-3, and at 20 × 20 × 2 cells (x = 0.5,
    0.515, 0.525, 0.475) from 0.85e-3, 2.8e-3, 3.2e-3, 2.3e-3 to 0.07e-3, 0.19e-3,
    0.16e-3, 0.06e-3 (skxfem.crack.faces3d's notes)."""
    r = _tilted("frictionless")
    q = r.problem.interfaces[0]
    node = q.cut.edge_ids < 0
    jn = q.cut.face_normal[:, 0] @ r.jump                # > 0: interpenetration
    assert np.abs(r.jump).max() > 0.3, "the faces slide"
    assert jn[node].max() < 3e-3 and jn.max() < 7e-3
    off = _tilted("frictionless", shift=1e-3)
    assert np.all(off.problem.interfaces[0].cut.edge_ids >= 0)
    (front,), (ref,) = r.front, off.front
    scale = np.sqrt(np.pi * 0.5)
    assert np.abs(front["K_I"]).max() < 7e-3 * scale
    assert np.abs(front["K_II"] / ref["K_II"] - 1).max() < 0.01


@pytest.mark.parametrize("friction", [0.0, 1.2])
def test_the_45_degree_inclined_crack_along_the_tetrahedras_faces(friction):
    """The inclined crack β = 45° on a 10 × 10 × 2 slab runs along the tetrahedra's
    diagonal faces: its multipliers are all at nodes (refused before).  Centre (0.53,
    0.53), a = 1/4 (centred at a node, (1/2, 1/2), sif3d's nodal front directions find
    ∇φ_h ∥ ∇ψ_h in the cells along the bisector, with any law, 'free' too).  Measured:
    μ = 0 slides, K_II/K_exact 0.986 to 1.015, |K_I| ≤ 1.5e-3 σ√(πa), the pressure
    within 4.7 % of σ cos²β; μ = 1.2 sticks, |K_I|, |K_II| ≤ 1.8e-3, the pressure within
    0.05 %."""
    c, scene = inclined_slab(10, 2, friction, 45.0, center=(0.53, 0.53))
    r = solve(scene)
    assert np.all(r.problem.interfaces[0].cut.edge_ids == -1)
    (front,) = r.front
    scale = c.sigma * np.sqrt(np.pi * c.a)
    p = -r.normal_traction / c.pressure
    if c.slides:
        expect = np.array([c.K_II_at(x[:2]) for x in np.asarray(front["points"])])
        assert np.abs(front["K_II"] / expect - 1).max() < 0.02
        assert np.abs(p - 1).max() < 0.06
    else:
        assert np.abs(front["K_II"]).max() < 4e-3 * scale
        assert np.abs(p - 1).max() < 1e-3
    assert np.abs(front["K_I"]).max() < 4e-3 * scale
