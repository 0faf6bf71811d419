"""A body force with a crack (issue 29): the load on the enriched unknowns
(skxfem.crack.assembly.body_load, skxfem.crack.space3d.body_load) and the interaction
integral's body-force term -∫ b·u^aux_{,1} q (skxfem.crack.interaction, sif, sif3d).

The known answer is manufactured: the exact Williams field of (K_I, K_II) plus a smooth
field u_p = s (y - ½)² (1 + x, ½ - 2x) in equilibrium with the body force
b = -div σ(u_p), imposed on the Williams square (and slab).  u_p and its stress vanish on
the crack's line y = ½, so the faces stay free and the K of the sum is the Williams K;
the integral without its body-force term misses it by about 12 % (2D) and 5 % (3D)."""
import json

import numpy as np
import pytest
from skfem import MeshTet1

from skxfem.app.cli import main
from skxfem.crack.assembly import Load, Support, body_load
from skxfem.crack.frame import straight_frame
from skxfem.crack.geometry import crack_geometry
from skxfem.crack.interaction import interaction_integrals
from skxfem.crack.sif import sif
from skxfem.crack.sif3d import sif_3d, solve_crack_3d
from skxfem.crack.solve import solve_crack
from skxfem.crack.space import crack_space
from skxfem.crack.space3d import Support3D
from skxfem.crack.williams import near_tip
from skxfem.fem.material import Material
from skxfem.studies.cracks import (
    MATERIAL,
    RADIUS,
    SIF_RADIUS,
    _facets,
    straight_crack,
    unit_square,
)

TIP = np.array([0.5, 0.5])
A, C = (1.0, 1.0), (0.5, -2.0)            # u_p = s d² (A₀ + A₁x, C₀ + C₁x), d = y - ½


def smooth(x, s, dim=2):
    """(u_p, ∇u_p, b = -div σ(u_p)) at points x (dim, n): plane strain in every z-plane
    in 3D (u_p,3 = 0, b₃ = 0)."""
    lam, mu = MATERIAL.lame(dim)
    d = x[1] - 0.5
    g1, g2 = A[0] + A[1] * x[0], C[0] + C[1] * x[0]
    z = np.zeros((dim - 2,) + d.shape)
    u = s * np.concatenate([np.stack([d ** 2 * g1, d ** 2 * g2]), z])
    gu = np.zeros((dim, dim) + d.shape)
    gu[:2, :2] = s * np.array([[d ** 2 * A[1], 2 * d * g1], [d ** 2 * C[1], 2 * d * g2]])
    b = -2 * s * np.stack([(lam + mu) * C[1] * d + mu * g1,
                           (lam + mu) * A[1] * d + (lam + 2 * mu) * g2])
    return u, gu, np.concatenate([b, z])


def test_the_body_force_is_minus_the_divergence_of_the_smooth_stress():
    """The manufactured b against central differences of σ(u_p), in 2D and 3D."""
    x = np.random.default_rng(29).uniform(0, 1, (3, 20))
    for dim in (2, 3):
        def sigma(p, dim=dim):
            gu = smooth(p, 1.3, dim)[1]
            return MATERIAL.stress((gu + np.swapaxes(gu, 0, 1)) / 2, dim)
        div = np.zeros((dim, 20))
        for j in range(dim):
            e = np.zeros((dim, 1))
            e[j] = 1e-5
            div += (sigma(x[:dim] + e) - sigma(x[:dim] - e))[:, j] / 2e-5
        assert np.abs(smooth(x[:dim], 1.3, dim)[2] + div).max() < 1e-8
        gu = smooth(np.stack([x[0], 0.5 + 0 * x[0], x[2]])[:dim], 1.3, dim)[1]
        assert np.abs(gu).max() == 0, "u_p's stress vanishes on the crack: free faces"


def test_body_load_is_the_work_of_b_on_a_field():
    """f·U = ∫ b·u for a linear field u the standard part holds and a linear b (the
    rule is exact), and the resultant of b on the standard unknowns."""
    m = unit_square(6)
    V = crack_space(m, crack_geometry(m, m.p[1] - 0.5, m.p[0] - 0.5))
    f = body_load(V, lambda x: np.stack([1 + x[1], 2 * x[0]]))
    U = np.zeros(V.N)
    U[V.basis.nodal_dofs[0]], U[V.basis.nodal_dofs[1]] = m.p[0], m.p[1]      # u = x
    assert abs(f @ U - 1.25) < 1e-12                      # ∫ (1 + y) x + 2 x y
    assert abs(f[V.basis.nodal_dofs[0]].sum() - 1.5) < 1e-12
    assert np.any(f[V.n_std:] != 0), "the enriched unknowns are loaded too"


def williams_with_body_force(n, K, s, sif_radius=SIF_RADIUS):
    """The Williams square with u_p added: its displacement on the three uncut faces, its
    traction on the cut one, b in the body; the solution and K without b's term."""
    m = unit_square(n)
    psi, phi, frame = straight_crack(TIP, 0.0)

    def u(p):
        return near_tip(p, TIP, frame, MATERIAL, K).u + smooth(p, s)[0]

    def t_left(p):
        gu = smooth(p, s)[1]
        sig = MATERIAL.stress((gu + np.swapaxes(gu, 0, 1)) / 2, 2)
        return -(near_tip(p, TIP, frame, MATERIAL, K).sigma + sig)[:, 0]

    uncut = np.concatenate([_facets(m, lambda p: p[1] < 1e-12),
                            _facets(m, lambda p: p[1] > 1 - 1e-12),
                            _facets(m, lambda p: p[0] > 1 - 1e-12)])
    sol = solve_crack(m, psi, phi, MATERIAL, [Support(uncut, value=u)],
                      [Load(_facets(m, lambda p: p[0] < 1e-12), t_left)], "geometric",
                      RADIUS, sif_radius=sif_radius,
                      body_force=lambda p: smooth(p, s)[2])
    return sol, sif(sol.space, sol.U, MATERIAL, sif_radius)


@pytest.mark.parametrize("K", [(1.0, 0.0), (0.0, 1.0)], ids=["mode I", "mode II"])
@pytest.mark.parametrize("n, tol", [(21, 0.003), (41, 0.001)])
def test_williams_plus_a_body_force_gives_the_williams_K(K, n, tol):
    """Within the tolerance the Williams square meets without a body force at that mesh
    (test_crack_xfem: 0.3 % at h = 1/21, 0.1 % at 1/41).  Measured: with the term
    K (1.0021, -0.0007) and (0.0000, 0.9978) at h = 1/21, (1.0006, -0.0002) and
    (0.0000, 0.9995) at 1/41; without it (1.0085, -0.1180) and (0.0064, 0.8806)."""
    sol, without = williams_with_body_force(n, K, 1.0)
    print(f"h = 1/{n}: K = {sol.K[0]}, without the body-force term {without}")
    assert np.allclose(sol.K[0], K, atol=tol), f"K = {sol.K[0]}, expected {K} ± {tol}"
    assert np.abs(without - K).max() > 0.1, "the body-force term is needed"


def test_with_the_term_K_does_not_depend_on_the_domain():
    """r_d = 0.15, 0.2, 0.3: K_I within 0.3 % of 1 and K_II of 0 with the term; without
    it K_II moves with the domain.  Measured (h = 1/21): with the term K_I 1.0011,
    1.0015, 1.0021, K_II -0.0003 to -0.0007; without it K_II -0.034, -0.055, -0.118."""
    m_K, m_without = [], []
    for r_d in (0.15, 0.2, 0.3):
        sol, without = williams_with_body_force(21, (1.0, 0.0), 1.0, r_d)
        m_K.append(sol.K[0])
        m_without.append(without)
    m_K, m_without = np.array(m_K), np.array(m_without)
    assert np.allclose(m_K, (1.0, 0.0), atol=0.003), m_K
    assert np.ptp(m_without[:, 1]) > 0.05, m_without


def test_a_zero_body_force_changes_nothing():
    """b = 0: the term's wider domain (every cell where q ≠ 0) adds only zeros."""
    sol, without = williams_with_body_force(11, (1.0, 0.5), 0.0)
    assert np.allclose(sol.K[0], without, rtol=1e-12, atol=1e-12)


def test_interaction_integrals_take_b_and_q_together():
    f, mat = straight_frame([1.0, 0.0], [0.0, 1.0]), Material(1.0, 0.3)
    x, z = np.array([[0.3], [0.1]]), np.zeros((2, 2, 1))
    gq = np.zeros((2, 1))
    b = np.array([[0.0], [2.0]])
    with pytest.raises(ValueError, match="needs q"):
        interaction_integrals(x, [1.0], z, z, gq, [0, 0], f, mat, body_force=b)
    with pytest.raises(ValueError, match="only used with a body_force"):
        interaction_integrals(x, [1.0], z, z, gq, [0, 0], f, mat, q=[1.0])
    with pytest.raises(ValueError, match="body_force must have shape"):
        interaction_integrals(x, [1.0], z, z, gq, [0, 0], f, mat, body_force=b[:1], q=[1.0])
    # one point, no field: I = -w q b·u^aux_{,1} alone
    I = interaction_integrals(x, [0.5], z, z, gq, [0, 0], f, mat, body_force=b, q=[0.8])
    aux = [near_tip(x, np.zeros(2), f, mat, k).grad_u[:, 0, 0] for k in ((1, 0), (0, 1))]
    assert np.allclose(I, [-0.5 * 0.8 * 2.0 * a[1] for a in aux], rtol=1e-14)


# ---------------------------------------------------------------- 3D: a straight front


def slab_with_body_force(K, s, n=21, nz=2):
    """The Williams slab of test_crack_3d with u_p added (plane strain in every z-plane):
    the displacement on x, y = 0, 1, u_z on z = 0, 1 (whose other tractions vanish), b;
    K at z = ½ and K there without b's term."""
    m = MeshTet1.init_tensor(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1),
                             np.linspace(0, 1, nz + 1))
    frame = straight_frame([1.0, 0, 0], [0, 1.0, 0])

    def u(x):
        return near_tip(x, np.array([0.5, 0.5, 0.0]), frame, MATERIAL, K).u + smooth(x, s, 3)[0]

    sides = m.facets_satisfying(lambda x: (x[0] < 1e-12) | (x[0] > 1 - 1e-12)
                                | (x[1] < 1e-12) | (x[1] > 1 - 1e-12))
    zf = m.facets_satisfying(lambda x: (x[2] < 1e-12) | (x[2] > 1 - 1e-12))
    P = np.array([[0.5], [0.5], [0.5]])
    sol = solve_crack_3d(m, lambda x: x[1] - 0.5, lambda x: x[0] - 0.5, MATERIAL,
                         [Support3D(sides, value=u), Support3D(zf, value=u, components=(2,))],
                         radius=0.3, points=P, sif_length=1 / nz,
                         body_force=lambda x: smooth(x, s, 3)[2])
    return sol.K[0], sif_3d(sol.space, sol.U, MATERIAL, P, None, 1 / nz)[0]


@pytest.mark.parametrize("K", [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], ids=["mode I", "mode II"])
def test_a_straight_front_with_a_body_force_gives_the_williams_K(K):
    """s = 3, h = 1/21, nz = 2, the tolerance of test_crack_3d's Williams slab (1 %).
    Measured (the default domain R = 0.75 r_e = 0.225): with the term (1.0050, 0.0013,
    -0.0025) and (-0.0001, 1.0006, -0.0023); without it (1.0063, -0.2030, -0.0025) and
    (0.0013, 0.7963, -0.0023); with s = 0 (1.0055, 0.0006, -0.0004)."""
    K_b, without = slab_with_body_force(K, 3.0)
    print(f"K = {K_b}, without the body-force term {without}")
    assert np.allclose(K_b, K, atol=0.01), f"K = {K_b}, expected {K}"
    assert np.abs(without - K).max() > 0.03, "the body-force term is needed"


# ---------------------------------------------------------------- the scene path

def _formula(v: float) -> str:
    return repr(float(v))


def _scene_toml(n: int) -> str:
    """The 2D manufactured problem (mode I, s = 1) as a scene file: the displacements of
    the Williams field plus u_p as formulas, the traction on xmin, [body_force]."""
    lam, mu = (_formula(v) for v in MATERIAL.lame(2))
    kappa = _formula(3 - 4 * MATERIAL.nu)
    r, t = "sqrt((x - 0.5)**2 + (y - 0.5)**2)", "atan2(y - 0.5, x - 0.5)"
    ux = f"1/(2*{mu})*sqrt({r}/(2*pi))*cos({t}/2)*({kappa} - 1 + 2*sin({t}/2)**2)"
    uy = f"1/(2*{mu})*sqrt({r}/(2*pi))*sin({t}/2)*({kappa} + 1 - 2*cos({t}/2)**2)"
    sxx = f"1/sqrt(2*pi*{r})*cos({t}/2)*(1 - sin({t}/2)*sin(3*{t}/2))"
    sxy = f"1/sqrt(2*pi*{r})*sin({t}/2)*cos({t}/2)*cos(3*{t}/2)"
    d, g1, g2 = "(y - 0.5)", f"({A[0]} + {A[1]}*x)", f"({C[0]} + {C[1]}*x)"
    # σ(u_p) on x = 0: σ₁₁ = (λ + 2μ) d² A₁ + 2λ d g₂, σ₂₁ = μ (2 d g₁ + d² C₁)
    pxx = f"(({lam} + 2*{mu})*{d}**2*{A[1]} + 2*{lam}*{d}*{g2})"
    pxy = f"({mu}*(2*{d}*{g1} + {d}**2*{C[1]}))"
    bx = f"-2*(({lam} + {mu})*{C[1]}*{d} + {mu}*{g1})"
    by = f"-2*(({lam} + {mu})*{A[1]}*{d} + ({lam} + 2*{mu})*{g2})"
    supports = "\n".join(f'[[displacement]]\nboundary = "{b}"\nx = "{ux} + {d}**2*{g1}"\n'
                         f'y = "{uy} + {d}**2*{g2}"' for b in ("ymin", "ymax", "xmax"))
    return f"""
name = "williams-body"
mesh = {{box = {{n = {n}, cell = "tri", size = [1, 1]}}}}
levelset = {{expr = "y - 0.5", front = "x - 0.5"}}
interface = {{law = "free", enrichment = "geometric", enrichment_radius = {RADIUS}, \
sif_radius = {SIF_RADIUS}}}
material = {{E = {MATERIAL.E}, nu = {MATERIAL.nu}}}
body_force = {{force = ["{bx}", "{by}"]}}
load = [{{boundary = "xmin", traction = ["-({sxx}) - {pxx}", "-({sxy}) - {pxy}"]}}]
{supports}
"""


def test_a_scene_file_with_a_body_force_and_a_crack_runs(tmp_path):
    """``skxfem run`` on the manufactured problem: K of result.json is the harness's (the
    same body load and term) and the Williams K (h = 1/21: 0.3 %)."""
    path = tmp_path / "body.toml"
    path.write_text(_scene_toml(21))
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    (front,) = json.loads((tmp_path / "out" / "result.json").read_text())["front"]
    sol, _ = williams_with_body_force(21, (1.0, 0.0), 1.0)
    assert abs(front["K_I"][0] - sol.K_I) < 1e-8 and abs(front["K_II"][0] - sol.K_II) < 1e-8
    assert abs(front["K_I"][0] - 1) < 0.003 and abs(front["K_II"][0]) < 0.003


def test_a_3d_crack_scene_with_gravity_runs(tmp_path):
    """The slab of test_crack_3d, pulled at its top, under its weight (and a small
    sideways force): the scene's front is the 3D harness's with the same body force, and
    the weight of the part above the crack, which rests on the clamped base, lowers K_I."""
    from skxfem.crack.space3d import Load3D
    text = """
name = "heavy slab"
mesh = {box = {n = [7, 7, 3], cell = "tet"}}
levelset = {expr = "z - 0.5", front = "x - 0.5"}
interface = {law = "free", enrichment = "topological"}
material = {E = 1.0, nu = 0.3}
body_force = {force = [0.0, "0.5*x", -1.0]}
displacement = [{boundary = "zmin", kind = "clamped"}]
load = [{boundary = "zmax", traction = [0.0, 0.0, 1.0]}]
"""
    path = tmp_path / "slab.toml"
    path.write_text(text)
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    (front,) = json.loads((tmp_path / "out" / "result.json").read_text())["front"]
    m = MeshTet1.init_tensor(np.linspace(0, 1, 8), np.linspace(0, 1, 8), np.linspace(0, 1, 4))
    bottom = m.facets_satisfying(lambda x: x[2] < 1e-12)
    top = m.facets_satisfying(lambda x: x[2] > 1 - 1e-12)
    b = (0.0, lambda x: 0.5 * x[0], -1.0)
    s = solve_crack_3d(m, lambda x: x[2] - 0.5, lambda x: x[0] - 0.5, MATERIAL,
                       [Support3D(bottom)],
                       [Load3D(top, lambda x: np.stack([0 * x[0], 0 * x[0], 1 + 0 * x[0]]))],
                       enrichment="topological", body_force=b)
    free = solve_crack_3d(m, lambda x: x[2] - 0.5, lambda x: x[0] - 0.5, MATERIAL,
                          [Support3D(bottom)],
                          [Load3D(top, lambda x: np.stack([0 * x[0], 0 * x[0], 1 + 0 * x[0]]))],
                          enrichment="topological")
    for k, key in enumerate(("K_I", "K_II", "K_III")):
        assert np.allclose(front[key], s.K[:, k], rtol=1e-8, atol=1e-10), key
    mid = np.argmin(np.abs(np.array(front["points"])[:, 1] - 0.5))
    print(f"K_I at the middle {front['K_I'][mid]}, without the weight {free.K[mid, 0]}")
    assert 0 < front["K_I"][mid] < free.K[mid, 0] - 0.1


def test_a_load_factor_scales_the_body_force_of_K(tmp_path):
    """A contact law on the open crack (linear while it stays open) over load factors
    0.5, 1: each step's K is its factor times the last's, so the interaction integral
    took each step's scaled body force (the scene's alone would miss K_II of the half
    step by about 0.06)."""
    from skxfem.contact.history import step_results
    from skxfem.scene.file import load_scene
    from skxfem.solver import solve

    path = tmp_path / "steps.toml"
    path.write_text("steps = [0.5, 1.0]\n" + _scene_toml(21).replace(
        'law = "free"', 'law = "frictionless"'))
    half, last = (r.front[0] for r in step_results(solve(load_scene(path))))
    assert abs(last["K_I"][0] - 1) < 0.003 and abs(last["K_II"][0]) < 0.003
    for key in ("K_I", "K_II"):
        assert abs(half[key][0] - 0.5 * last[key][0]) < 1e-6, (key, half, last)


def test_load_states_keep_the_body_force_of_K(tmp_path):
    """[[step]] load states (which keep the scene's body force): the last state's K is
    the Williams K, the body force's term in it."""
    from skxfem.scene.file import load_scene
    from skxfem.solver import solve

    path = tmp_path / "states.toml"
    path.write_text(_scene_toml(21).replace('law = "free"', 'law = "frictionless"')
                    + '[[step]]\nname = "first"\n[[step]]\nname = "again"\n')
    r = solve(load_scene(path))
    assert [s.load for s in r.steps] == ["first", "again"]
    assert abs(r.front[0]["K_I"][0] - 1) < 0.003 and abs(r.front[0]["K_II"][0]) < 0.003


def test_load_states_given_apart_from_the_scene_keep_their_own_body_force(tmp_path):
    """States given to contact.solve (not in the scene's steps): K takes the last state's
    body force, not the scene's (without it, K_II of the Williams field is off by ~0.12)."""
    from dataclasses import replace

    from skxfem.contact import solve as contact_solve
    from skxfem.scene.file import load_scene

    path = tmp_path / "state.toml"
    path.write_text(_scene_toml(21).replace('law = "free"', 'law = "frictionless"'))
    loaded = load_scene(path)
    assert loaded.body_force is not None
    weightless = replace(loaded, body_force=None, name="weightless")
    r = contact_solve(weightless, history=[weightless, replace(loaded, name="loaded")])
    assert [s.load for s in r.steps] == ["weightless", "loaded"]
    assert abs(r.front[0]["K_I"][0] - 1) < 0.003 and abs(r.front[0]["K_II"][0]) < 0.003
