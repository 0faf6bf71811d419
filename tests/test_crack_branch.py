"""The four branch functions and their gradients (skxfem.crack.branch)."""
import numpy as np
import pytest

from skxfem.crack.branch import (
    branch,
    branch_closed_form,
    branch_gradient,
    branch_local_gradient,
    branch_polar_derivatives,
)
from skxfem.crack.frame import local_coordinates, polar, straight_frame

RNG = np.random.default_rng(2907)


def random_frame(dim):
    Q, _ = np.linalg.qr(RNG.normal(size=(dim, dim)))
    return straight_frame(Q[:, 0], Q[:, 1])


def at(x, origin, frame):
    xl = local_coordinates(x, origin, frame)
    return polar(xl[0], xl[1])


@pytest.mark.parametrize("dim", [2, 3])
def test_gradient_by_finite_differences(dim):
    """∇F_l of the chain rule against central differences of F_l(x) at random points
    of a random frame (away from the faces, where F₁ jumps)."""
    frame, origin = random_frame(dim), RNG.normal(size=dim)
    x = origin[:, None] + RNG.uniform(-1, 1, (dim, 200))
    r, theta = at(x, origin, frame)
    keep = (r > 0.1) & (np.abs(theta) < np.pi - 0.1)
    x, r, theta = x[:, keep], r[keep], theta[keep]
    g = branch_gradient(r, theta, frame)
    assert g.shape == (4, dim, x.shape[1])
    h = 1e-5
    for i in range(dim):
        d = np.zeros((dim, 1))
        d[i] = h
        fd = (branch(*at(x + d, origin, frame)) - branch(*at(x - d, origin, frame))) / (2 * h)
        err = np.abs(fd - g[:, i]).max()
        assert err < 1e-7, f"∂F/∂x{i}: finite differences differ by {err:.1e}"


def test_gradient_with_one_frame_per_point():
    frames = [random_frame(3) for _ in range(5)]
    e1 = np.stack([f.e1 for f in frames], axis=1)
    e2 = np.stack([f.e2 for f in frames], axis=1)
    r, theta = RNG.uniform(0.1, 1, 5), RNG.uniform(-3, 3, 5)
    g = branch_gradient(r, theta, straight_frame(e1, e2))
    for k, f in enumerate(frames):
        assert np.allclose(g[..., k], branch_gradient(r[k], theta[k], f), atol=1e-15)


def test_the_jump_of_F1_is_2_sqrt_r_and_the_others_are_continuous():
    r = RNG.uniform(0.0, 3.0, 20)
    plus, minus = branch(r, np.full(20, np.pi)), branch(r, np.full(20, -np.pi))
    assert np.allclose(plus[0] - minus[0], 2 * np.sqrt(r), atol=1e-15)
    assert np.allclose(plus[1:], minus[1:], atol=1e-15)
    # approached from each side through θ(x) of points just above and below the face
    f, origin = random_frame(2), np.zeros(2)
    x = -np.outer(f.e1, r) + 1e-12 * np.array([f.e2, -f.e2])[..., None]
    above, below = (branch(*at(x[k], origin, f)) for k in (0, 1))
    assert np.allclose(above[0] - below[0], 2 * np.sqrt(r), atol=1e-9)
    assert np.allclose(above[1:], below[1:], atol=1e-9)


def test_values_at_known_points():
    F = branch(np.array([1.0, 4.0, 4.0, 9.0]), np.array([0.0, np.pi, np.pi / 2, -np.pi / 3]))
    s, c = np.sqrt(0.5), np.sqrt(0.5)
    assert np.allclose(F[:, 0], [0, 1, 0, 0], atol=1e-15)       # ahead of the tip
    assert np.allclose(F[:, 1], [2, 0, 0, 0], atol=1e-15)       # the face of Ω⁺
    assert np.allclose(F[:, 2], 2 * np.array([s, c, s, c]))    # θ = π/2
    t = -np.pi / 3
    assert np.allclose(F[:, 3], 3 * np.array([np.sin(t / 2), np.cos(t / 2),
                                              np.sin(t / 2) * np.sin(t),
                                              np.cos(t / 2) * np.sin(t)]))
    assert branch(0.0, 0.3).tolist() == [0.0] * 4              # F = 0 on the front


def test_local_gradient_is_the_classic_closed_form():
    """Moës, Dolbow & Belytschko 1999: ∂F/∂x₁, ∂F/∂x₂ of the four functions."""
    r, t = RNG.uniform(0.05, 2, 30), RNG.uniform(-np.pi, np.pi, 30)
    k = 1 / (2 * np.sqrt(r))
    s, c, s3, c3 = np.sin(t / 2), np.cos(t / 2), np.sin(3 * t / 2), np.cos(3 * t / 2)
    want = k * np.array([[-s, c],
                         [c, s],
                         [-s3 * np.sin(t), s + s3 * np.cos(t)],
                         [-c3 * np.sin(t), c + c3 * np.cos(t)]])
    assert np.allclose(branch_local_gradient(r, t), want, atol=1e-13)


def test_polar_derivatives():
    r, t = RNG.uniform(0.05, 2, 30), RNG.uniform(-3, 3, 30)
    d_r, d_t = branch_polar_derivatives(r, t)
    assert np.allclose(d_r, branch(r, t) / (2 * r))
    h = 1e-6
    assert np.allclose(d_t, (branch(r, t + h) - branch(r, t - h)) / (2 * h), atol=1e-8)


def test_bad_arguments_are_named():
    with pytest.raises(ValueError, match="r holds 1 NaN"):
        branch(np.array([np.nan]), np.array([0.0]))
    with pytest.raises(ValueError, match="theta must lie in"):
        branch(1.0, 4.0)
    with pytest.raises(ValueError, match="r must be non-negative"):
        branch(-1.0, 0.0)
    with pytest.raises(ValueError, match="r and theta must have the same shape"):
        branch(np.ones(2), np.ones(3))
    with pytest.raises(ValueError, match="singular on the front"):
        branch_local_gradient(0.0, 0.0)


def test_side_angle_forces_the_face_only_in_cut_cells():
    """θ = ±π by the side where φ < 0 and ψ has not the side's sign, in cut cells only
    (the one rule of skxfem/crack/space.py, space3d.py and sif3d.py); elsewhere atan2."""
    from skxfem.crack.branch import side_angle
    phi = np.array([-1.0, -1.0, -1.0, 1.0, -1.0])
    psi = np.array([1e-17, -1e-17, 0.3, -0.2, 0.3])
    side = np.array([-1.0, 1.0, -1.0, 1.0, 0.0])
    got = side_angle(phi, psi, side, np.ones(5, bool))
    want = np.arctan2(psi, phi)
    want[:3] = [-np.pi, np.pi, -np.pi]          # the side's face; φ > 0 and padding: atan2
    assert np.array_equal(got, want)
    assert np.array_equal(side_angle(phi, psi, side, np.zeros(5, bool)), np.arctan2(psi, phi))


def test_the_closed_form_is_the_branch_functions_and_their_chain_rule():
    """branch_closed_form against branch and branch_local_gradient (l last), at random
    points, on both faces (θ = ±π), and zero at r = 0."""
    r, theta = RNG.uniform(0, 2, (30, 7)), RNG.uniform(-np.pi, np.pi, (30, 7))
    theta[0], theta[1], r[2, :3] = np.pi, -np.pi, 0.0
    F, d1, d2 = branch_closed_form(r, theta)
    assert F.shape == d1.shape == d2.shape == (30, 7, 4)
    live = r > 0
    assert not np.any(F[~live]) and not np.any(d1[~live]) and not np.any(d2[~live])
    assert np.allclose(F, np.moveaxis(branch(r, theta), 0, -1), rtol=1e-14, atol=1e-15)
    g = branch_local_gradient(r[live], theta[live])                  # (4, 2, n)
    scale = np.abs(g).max(axis=(0, 1))[:, None]
    assert np.all(np.abs(d1[live] - g[:, 0].T) <= 1e-14 * scale)
    assert np.all(np.abs(d2[live] - g[:, 1].T) <= 1e-14 * scale)
