"""Stress intensity factors by the domain interaction integral (skxfem.crack.interaction),
on exact fields evaluated at the quadrature points of simple domains around the tip."""
import numpy as np
import pytest
from numpy.polynomial.legendre import leggauss

from skxfem.crack.frame import polar_gradients, straight_frame
from skxfem.crack.interaction import (
    CrackFace,
    effective_modulus,
    interaction_integrals,
    q_function,
    sif_from_interaction,
    stress_intensity,
)
from skxfem.crack.williams import near_tip, shear_modulus
from skxfem.fem.material import Material

RNG = np.random.default_rng(2929)
MATERIALS = [Material(2.0, 0.3, "strain"), Material(70.0, 0.25, "stress")]


def random_frame(dim, left_handed=False):
    Q, _ = np.linalg.qr(RNG.normal(size=(dim, dim)))
    return straight_frame(Q[:, 0], -Q[:, 1] if left_handed else Q[:, 1])


def gauss(a, b, n):
    s, w = leggauss(n)
    return a + (b - a) * (s + 1) / 2, w * (b - a) / 2


def polar_rule(origin, frame, r_d, plateau, nr=24, nt=64):
    """Points and weights of the ring ρ r_d < r < r_d (where ∇q ≠ 0), r = s² in s so that
    the r^½ of a uniform field times the auxiliary one is integrated exactly."""
    s, ws = gauss(np.sqrt(plateau * r_d), np.sqrt(r_d), nr)
    t, wt = gauss(-np.pi, np.pi, nt)
    S, T = np.meshgrid(s, t, indexing="ij")
    r, theta = (S ** 2).ravel(), T.ravel()
    w = (np.outer(ws * 2 * s, wt) * S ** 2).ravel()            # dr = 2s ds, dA = r dr dθ
    x = (origin[:, None] + r * np.cos(theta) * frame.e1[:, None]
         + r * np.sin(theta) * frame.e2[:, None])
    return x, w, r, theta


def cone(r, theta, frame, r_d, plateau):
    return q_function(r, polar_gradients(r, theta, frame)[0], r_d, plateau)


def williams_K(K, mat, frame, origin, r_d, plateau, dim=2):
    x, w, r, theta = polar_rule(origin, frame, r_d, plateau)
    field = near_tip(x, origin, frame, mat, K)
    q, gq = cone(r, theta, frame, r_d, plateau)
    return stress_intensity(x, w, field.grad_u, field.sigma, gq, origin, frame, mat)


@pytest.mark.parametrize("mat", MATERIALS, ids=["strain", "stress"])
@pytest.mark.parametrize("K", [(1.0, 0.0), (0.0, 1.0), (0.7, -1.9), (-0.3, 0.4)],
                         ids=["I", "II", "mixed", "closing"])
def test_K_of_the_williams_field(mat, K):
    f, o = random_frame(2), RNG.normal(size=2)
    got = williams_K(K, mat, f, o, r_d=0.8, plateau=0.25)
    assert np.abs(got - K).max() < 1e-6 * np.abs(K).max(), got


def test_K_is_independent_of_the_domain_and_of_the_frame_handedness():
    """r_d from 1e-3 to 10, cone or plateau; (e₁, e₂) either handed in 2D."""
    mat, K = MATERIALS[0], np.array([0.45, 1.2])
    for left in (False, True):
        f, o = random_frame(2, left), RNG.normal(size=2)
        got = [williams_K(K, mat, f, o, r_d, rho)
               for r_d in (1e-3, 0.1, 1.0, 10.0) for rho in (0.0, 0.5, 0.9)]
        assert np.abs(np.array(got) - K).max() < 1e-6, got


def test_K_on_a_triangle_mesh_with_a_p1_weight():
    """A scikit-fem MeshTri of [-1, 1]² whose line y = 0 carries the crack faces, its own
    quadrature (points, dx), and q the P1 interpolant of the plateau: the X-FEM's setting
    without the X-FEM (the field is the exact Williams one)."""
    from skfem import Basis, ElementTriP1, MeshTri
    m = MeshTri.init_tensor(np.linspace(-1, 1, 21), np.linspace(-1, 1, 21))
    basis = Basis(m, ElementTriP1(), intorder=10)
    x, w = basis.mapping.F(basis.X), basis.dx                   # (2, cells, qp), (cells, qp)
    f, o, mat = straight_frame([1.0, 0.0], [0.0, 1.0]), np.zeros(2), MATERIALS[1]
    for r_d, rho in ((0.9, 0.3), (0.6, 0.5)):
        qn = q_function(np.hypot(*m.p), np.zeros_like(m.p), r_d, rho)[0]
        gq = basis.interpolate(qn).grad
        for K in ((1.0, 0.0), (0.0, 1.0), (0.6, -1.7)):
            field = near_tip(x, o, f, mat, K)
            got = stress_intensity(x, w, field.grad_u, field.sigma, gq, o, f, mat)
            assert np.abs(got - K).max() < 1e-6, (r_d, rho, K, got)


def test_K_along_a_straight_front_in_3d():
    """A slab of thickness L around a straight front, q of r only: the volume integral
    is L times the local I; modes I, II and III together."""
    mat, K, L = Material(5.0, 0.25), np.array([0.8, -0.5, 1.3]), 0.7
    f, o = random_frame(3), RNG.normal(size=3)
    x2, w2, r, theta = polar_rule(o, f, 0.5, 0.2)
    z, wz = gauss(0.0, L, 2)
    x = x2[:, :, None] + f.e3[:, None, None] * z
    w = w2[:, None] * wz
    field = near_tip(x, o, f, mat, K)
    q, gq = cone(np.repeat(r[:, None], 2, 1), np.repeat(theta[:, None], 2, 1), f, 0.5, 0.2)
    I = interaction_integrals(x, w, field.grad_u, field.sigma, gq, o, f, mat) / L
    got = sif_from_interaction(I, mat, 3)
    assert np.abs(got - K).max() < 1e-6, got
    # the conversion: K_I = E′ I/2 with E′ = E/(1 - ν²), K_III = μ I
    assert got[2] == pytest.approx(shear_modulus(mat) * I[2])
    assert got[0] == pytest.approx(mat.E / (1 - mat.nu ** 2) * I[0] / 2)


def uniform_compression(mat, frame, p, n):
    """σ = -p e₂⊗e₂ everywhere and its ∇u (a uniform strain): the exact field of a closed
    crack pressed shut, or of an open one under the pressure p on its faces; K = 0."""
    e2 = frame.e2
    sigma = -p * np.outer(e2, e2)
    nu, E = mat.nu, mat.E
    if mat.plane == "strain":                                       # ε₃₃ = 0
        eps = (1 + nu) / E * (sigma - nu * np.trace(sigma) * np.eye(2))
    else:                                                           # σ₃₃ = 0
        eps = ((1 + nu) * sigma - nu * np.trace(sigma) * np.eye(2)) / E
    assert np.allclose(mat.stress(eps[..., None], 2)[..., 0], sigma)
    return (np.repeat(a[..., None], n, axis=-1) for a in (eps, sigma))


def faces(origin, frame, r_d, plateau, sigma_face, n=40):
    """Rules on the two faces r < r_d (θ = ±π), r = s² in s (u^a,₁ ~ r^-½), split where q
    kinks; the traction t = σ·m*, m* = -e₂ on the face of Ω⁺, +e₂ on that of Ω⁻."""
    rules = []
    for a, b in ((0.0, np.sqrt(plateau * r_d)), (np.sqrt(plateau * r_d), np.sqrt(r_d))):
        if b > a:
            s, ws = gauss(a, b, n)
            r, w = s ** 2, ws * 2 * s
            x = origin[:, None] - r * frame.e1[:, None]
            q = q_function(r, np.zeros((2, n)), r_d, plateau)[0]
            for side in (1, -1):
                t = -side * sigma_face @ frame.e2
                rules.append(CrackFace(x, w, np.repeat(t[:, None], n, 1), q, side))
    return rules


@pytest.mark.parametrize("mat", MATERIALS, ids=["strain", "stress"])
def test_a_closed_crack_under_compression_has_K_zero_with_the_face_term(mat):
    p = 3.0
    f, o = random_frame(2, left_handed=bool(RNG.integers(2))), RNG.normal(size=2)
    seen = []
    for r_d, rho in ((1.0, 0.0), (1.0, 0.5), (0.3, 0.2), (4.0, 0.25)):
        x, w, r, theta = polar_rule(o, f, r_d, rho)
        grad_u, sigma = uniform_compression(mat, f, p, r.size)
        q, gq = cone(r, theta, f, r_d, rho)
        with_faces = stress_intensity(x, w, grad_u, sigma, gq, o, f, mat,
                                      faces(o, f, r_d, rho, sigma[..., 0]))
        assert np.abs(with_faces).max() <= 1e-6 * p * np.sqrt(np.pi * r_d), with_faces
        without = stress_intensity(x, w, grad_u, sigma, gq, o, f, mat)
        seen.append(without[0] / (p * np.sqrt(np.pi * r_d)))
        assert abs(without[1]) < 1e-12 * p
    # without the face term: K_I ≈ -0.6 to -0.78 p√(π r_d), and it changes with the domain
    assert all(-0.8 < k < -0.55 for k in seen), seen
    assert max(seen) - min(seen) > 0.1, seen


def test_a_pressure_on_the_faces_superposed_on_a_williams_field():
    """Mode I and II plus the uniform compression: the face term removes the pressure's
    share, K is that of the Williams field; without it K_I is off by ≈ -0.7 p√(π r_d)."""
    mat, K, p, r_d, rho = MATERIALS[0], np.array([1.0, -0.6]), 0.5, 0.6, 0.25
    f, o = random_frame(2), RNG.normal(size=2)
    x, w, r, theta = polar_rule(o, f, r_d, rho)
    grad_u, sigma = uniform_compression(mat, f, p, r.size)
    field = near_tip(x, o, f, mat, K)
    q, gq = cone(r, theta, f, r_d, rho)
    args = (x, w, grad_u + field.grad_u, sigma + field.sigma, gq, o, f, mat)
    got = stress_intensity(*args, faces(o, f, r_d, rho, sigma[..., 0]))
    assert np.abs(got - K).max() < 1e-6, got
    off = (stress_intensity(*args)[0] - K[0]) / (p * np.sqrt(np.pi * r_d))
    assert -0.75 < off < -0.65, off


def test_q_function_is_clipped_by_the_boundary():
    r = np.array([0.05, 0.2, 0.35, 0.5, 0.8])
    gr = np.stack([np.ones(5), np.zeros(5)])
    q, gq = q_function(r, gr, r_d=1.0, plateau=0.5, boundary=0.4)   # R = 0.4, plateau 0.2
    assert np.allclose(q, [1.0, 1.0, 0.25, 0.0, 0.0])
    assert np.allclose(gq[0], [0.0, 0.0, -5.0, 0.0, 0.0]) and not gq[1].any()
    with pytest.raises(ValueError, match="r_d must be a positive number"):
        q_function(r, gr, 0.0)
    with pytest.raises(ValueError, match="plateau must be in"):
        q_function(r, gr, 1.0, plateau=1.0)
    with pytest.raises(ValueError, match="grad_r must have shape"):
        q_function(r, gr[:, :3], 1.0)


def test_bad_arguments_are_named():
    f, mat = straight_frame([1.0, 0.0], [0.0, 1.0]), Material()
    x, z = np.ones((2, 3)), np.zeros((2, 2, 3))
    with pytest.raises(ValueError, match="sigma must have shape"):
        interaction_integrals(x, np.ones(3), z, z[..., :2], np.zeros((2, 3)), [0, 0], f, mat)
    with pytest.raises(ValueError, match="grad_u holds 1 NaN"):
        bad = z.copy()
        bad[0, 0, 0] = np.nan
        interaction_integrals(x, np.ones(3), bad, z, np.zeros((2, 3)), [0, 0], f, mat)
    with pytest.raises(ValueError, match="face traction must have shape"):
        CrackFace(x, np.ones(3), np.ones((2, 2)), np.ones(3), 1)
    with pytest.raises(ValueError, match="face side must be"):
        CrackFace(x, np.ones(3), x, np.ones(3), 0)
    with pytest.raises(ValueError, match="I must hold 3 values"):
        sif_from_interaction([1.0, 2.0], mat, 3)
    assert effective_modulus(Material(0.96, 0.2)) == pytest.approx(1.0)
