"""The exact Williams near-tip fields (skxfem.crack.williams): elastic, in equilibrium,
traction-free on the faces, with the package's signs of K_I, K_II, K_III."""
import numpy as np
import pytest

from skxfem.crack.frame import straight_frame
from skxfem.crack.williams import (
    kolosov,
    near_tip,
    near_tip_local,
    near_tip_modes,
    shear_modulus,
)
from skxfem.fem.material import Material

RNG = np.random.default_rng(2929)
CASES = [(Material(2.0, 0.3, "strain"), 2, (1.3, -0.7)),
         (Material(2.0, 0.3, "stress"), 2, (-0.4, 1.1)),
         (Material(5.0, 0.25), 3, (0.8, 0.5, -1.2))]
IDS = ["plane-strain", "plane-stress", "3d"]


def random_frame(dim):
    Q, _ = np.linalg.qr(RNG.normal(size=(dim, dim)))
    return straight_frame(Q[:, 0], Q[:, 1])


def points(frame, origin, n=60):
    """Random points at r in [0.2, 1.5], θ away from the faces, some off the plane in 3D."""
    r, t = RNG.uniform(0.2, 1.5, n), RNG.uniform(-np.pi + 0.2, np.pi - 0.2, n)
    x = origin[:, None] + r * np.cos(t) * frame.e1[:, None] + r * np.sin(t) * frame.e2[:, None]
    if frame.dim == 3:
        x = x + RNG.uniform(-1, 1, n) * frame.e3[:, None]
    return x


def fd_gradient(fun, x, h=1e-6):
    """∂f/∂x_j of a field f(x) of shape (k..., n) by central differences: (k..., dim, n)."""
    cols = []
    for j in range(x.shape[0]):
        d = np.zeros((x.shape[0], 1))
        d[j] = h
        cols.append((fun(x + d) - fun(x - d)) / (2 * h))
    return np.stack(cols, axis=-2)


@pytest.mark.parametrize("mat, dim, K", CASES, ids=IDS)
def test_the_gradient_is_that_of_the_displacement(mat, dim, K):
    f, o = random_frame(dim), RNG.normal(size=dim)
    x = points(f, o)
    fd = fd_gradient(lambda y: near_tip(y, o, f, mat, K).u, x)
    assert np.abs(fd - near_tip(x, o, f, mat, K).grad_u).max() < 1e-8


@pytest.mark.parametrize("mat, dim, K", CASES, ids=IDS)
def test_the_stress_is_hookes_law_of_the_strain(mat, dim, K):
    """σ = C ε(u), with C the package's own (Material.stress: plane strain or stress)."""
    f, o = random_frame(dim), RNG.normal(size=dim)
    x = points(f, o)
    field = near_tip(x, o, f, mat, K)
    eps = (lambda g: (g + np.swapaxes(g, 0, 1)) / 2)(
        fd_gradient(lambda y: near_tip(y, o, f, mat, K).u, x))
    assert np.abs(mat.stress(eps, dim) - field.sigma).max() < 1e-7
    assert np.abs(mat.stress(field.strain, dim) - field.sigma).max() < 1e-12


@pytest.mark.parametrize("mat, dim, K", CASES, ids=IDS)
def test_equilibrium_div_sigma_is_zero(mat, dim, K):
    f, o = random_frame(dim), RNG.normal(size=dim)
    x = points(f, o)
    ds = fd_gradient(lambda y: near_tip(y, o, f, mat, K).sigma, x, h=1e-5)   # (i, j, k, n)
    div = np.einsum("ijj...->i...", ds)
    scale = np.abs(near_tip(x, o, f, mat, K).sigma).max()
    assert np.abs(div).max() < 1e-7 * scale


@pytest.mark.parametrize("mat, dim, K", CASES, ids=IDS)
def test_the_faces_are_traction_free(mat, dim, K):
    r = RNG.uniform(0.01, 2, 20)
    for t in (np.pi, -np.pi):
        s = near_tip_local(r, np.full(20, t), mat, K, dim).sigma
        assert np.abs(s[:, 1]).max() < 1e-12 * np.abs(s).max()    # σ·e₂ = 0


@pytest.mark.parametrize("mat, dim, K", CASES, ids=IDS)
def test_the_stress_ahead_of_the_tip_is_K_over_sqrt_2_pi_r(mat, dim, K):
    r = np.array([1e-4, 0.01, 0.3, 2.0])
    s = near_tip_local(r, np.zeros(4), mat, K, dim).sigma
    k = 1 / np.sqrt(2 * np.pi * r)
    assert np.allclose(s[1, 1], K[0] * k) and np.allclose(s[0, 1], K[1] * k)
    assert np.allclose(s[0, 0], K[0] * k)                        # σ₁₁ = σ₂₂ ahead
    if dim == 3:
        assert np.allclose(s[1, 2], K[2] * k) and np.allclose(s[2, 2], mat.nu * 2 * K[0] * k)


@pytest.mark.parametrize("mat, dim", [(m, d) for m, d, _ in CASES], ids=IDS)
def test_signs_of_the_face_displacements(mat, dim):
    """K_I > 0 opens the crack; K_II > 0: the face of Ω⁺ slides along +e₁ relative to
    that of Ω⁻; K_III > 0: along +e₃.  Measured on the faces of a random frame, in
    global components, as the package's jump [[u]] = u⁻ - u⁺, and against the crack
    opening displacement u⁺ - u⁻ = K (κ + 1)/μ √(r/2π) (K_III: 4K/μ √(r/2π))."""
    f, o = random_frame(dim), RNG.normal(size=dim)
    r = RNG.uniform(0.05, 1, 10)
    x = o[:, None] - r * f.e1[:, None]                               # on the crack's plane
    mu, kappa = shear_modulus(mat), kolosov(mat, dim)
    modes = [(0, f.e2, (kappa + 1) / mu), (1, f.e1, (kappa + 1) / mu)]
    if dim == 3:
        modes.append((2, f.e3, 4 / mu))
    for mode, direction, factor in modes:
        K = np.eye(3)[mode]
        jump = near_tip(x, o, f, mat, K, side=-1).u - near_tip(x, o, f, mat, K, side=1).u
        along = direction @ jump
        assert np.all(along < 0), f"mode {mode + 1}: [[u]]·e = {along}"   # u⁺ moves along +e
        assert np.allclose(-along, factor * np.sqrt(r / (2 * np.pi)))
        others = jump - np.outer(direction, along)
        assert np.abs(others).max() < 1e-14                              # pure mode


def test_kolosov_and_mu():
    assert kolosov(Material(1, 0.3)) == pytest.approx(1.8)
    assert kolosov(Material(1, 0.3, "stress")) == pytest.approx(2.7 / 1.3)
    assert kolosov(Material(1, 0.3, "stress"), dim=3) == pytest.approx(1.8)   # 3D: strain
    assert shear_modulus(Material(2.6, 0.3)) == pytest.approx(1.0)


@pytest.mark.parametrize("mat,dim,K", CASES, ids=IDS)
def test_the_unit_modes_at_once_are_near_tip_local_of_each_and_sum_to_a_mix(mat, dim, K):
    """near_tip_modes: the same numbers as one near_tip_local per unit mode, and the
    fields of a mix of modes are their combination."""
    r, theta = RNG.uniform(0.01, 2.0, 30), RNG.uniform(-np.pi, np.pi, 30)
    theta[:2] = -np.pi, np.pi                            # the faces
    modes = near_tip_modes(r, theta, mat, dim)
    assert len(modes) == dim
    for m, one in enumerate(modes):
        ref = near_tip_local(r, theta, mat, np.eye(dim)[m], dim)
        for name in ("u", "grad_u", "sigma"):
            assert np.array_equal(getattr(one, name), getattr(ref, name)), (m, name)
    mix = near_tip_local(r, theta, mat, K, dim)
    for name in ("u", "grad_u", "sigma"):
        combined = sum(k * getattr(one, name) for k, one in zip(K, modes))
        assert np.allclose(getattr(mix, name), combined, rtol=1e-13, atol=1e-13)


def test_bad_arguments():
    m = Material()
    with pytest.raises(ValueError, match="K_III needs dim = 3"):
        near_tip_local(1.0, 0.0, m, (0, 0, 1), dim=2)
    with pytest.raises(ValueError, match="K must be"):
        near_tip_local(1.0, 0.0, m, (1.0,))
    with pytest.raises(ValueError, match="r must be positive"):
        near_tip_local(0.0, 0.0, m)
    with pytest.raises(ValueError, match="theta holds 1 NaN"):
        near_tip_local(1.0, np.nan, m)
    with pytest.raises(TypeError, match="material must be"):
        near_tip_local(1.0, 0.0, {"E": 1})
    with pytest.raises(ValueError, match="r must be positive"):
        near_tip_modes(np.array([-1.0]), np.array([0.0]), m)
    with pytest.raises(ValueError, match="dim must be 2 or 3"):
        near_tip_modes(1.0, 0.0, m, dim=4)
