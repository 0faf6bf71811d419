"""The tip frame and the polar coordinates around a crack front (skxfem.crack.frame)."""
import numpy as np
import pytest

from skxfem.crack.frame import local_coordinates, polar, polar_gradients, straight_frame, tip_frame

RNG = np.random.default_rng(29)


def random_frame(dim):
    """A random orthonormal pair (e₁, e₂) in ``dim`` dimensions."""
    Q, _ = np.linalg.qr(RNG.normal(size=(dim, dim)))
    return Q[:, 0], Q[:, 1]


@pytest.mark.parametrize("dim", [2, 3])
def test_the_frame_is_orthonormal_and_e3_runs_along_the_front(dim):
    a, b = random_frame(dim)
    f = tip_frame(3.0 * a, 0.5 * b)                      # gradients need not be unit
    assert np.allclose(f.e1, a) and np.allclose(f.e2, b)
    assert np.allclose(f.R @ f.R.T, np.eye(dim), atol=1e-14)
    if dim == 3:
        assert np.allclose(f.e3, np.cross(a, b)) and np.isclose(np.linalg.det(f.R), 1.0)
    else:
        assert f.e3 is None


def test_the_frame_keeps_the_normal_and_projects_grad_phi():
    """e₂ = ∇ψ/|∇ψ| always (the one normal); e₁ is the part of ∇φ normal to it."""
    f = tip_frame(np.array([1.0, 0.3, 0.0]), np.array([0.0, 2.0, 0.0]))
    assert f.e2.tolist() == [0.0, 1.0, 0.0]
    assert np.allclose(f.e1, [1.0, 0.0, 0.0]) and np.allclose(f.e3, [0.0, 0.0, 1.0])


def test_one_frame_per_point():
    n = 7
    a = np.stack([random_frame(3) for _ in range(n)], axis=-1)     # (2, 3, n)
    f = tip_frame(a[0], a[1])
    assert f.e1.shape == (3, n) and f.R.shape == (3, 3, n)
    assert np.allclose(np.einsum("ai...,bi...->ab...", f.R, f.R),
                       np.eye(3)[:, :, None], atol=1e-14)


@pytest.mark.parametrize("dim", [2, 3])
def test_polar_coordinates_of_points_in_a_frame(dim):
    e1, e2 = random_frame(dim)
    f, origin = straight_frame(e1, e2), RNG.normal(size=dim)
    r0, t0 = RNG.uniform(0.1, 2.0, 50), RNG.uniform(-3.1, 3.1, 50)
    along = (RNG.normal(size=50) * f.e3[:, None]) if dim == 3 else 0.0
    x = (origin[:, None] + r0 * np.cos(t0) * e1[:, None] + r0 * np.sin(t0) * e2[:, None]
         + along)
    xl = local_coordinates(x, origin, f)
    r, theta = polar(xl[0], xl[1])
    assert np.allclose(r, r0) and np.allclose(theta, t0)
    # θ > 0 on the Ω⁺ side (ψ = x₂ > 0), the side ∇ψ points to
    assert np.array_equal(theta > 0, ((x - origin[:, None]).T @ e2) > 0)


def test_theta_is_plus_or_minus_pi_on_the_faces():
    phi, psi = np.array([-1.0, -2.0, -1.0]), np.array([0.0, -0.0, 0.0])
    assert (polar(phi, psi)[1] / np.pi).tolist() == [1.0, -1.0, 1.0]          # atan2's zero
    assert (polar(phi, psi, side=-1)[1] / np.pi).tolist() == [-1.0, -1.0, -1.0]
    assert (polar(phi, psi, side=[1, 1, -1])[1] / np.pi).tolist() == [1.0, 1.0, -1.0]
    # side only matters on the faces: ahead of the tip and off Γ nothing changes
    r, t = polar(np.array([2.0, -1.0]), np.array([0.0, 1e-6]), side=-1)
    assert t[0] == 0.0 and np.pi - 2e-6 < t[1] < np.pi


@pytest.mark.parametrize("dim", [2, 3])
def test_polar_gradients_by_finite_differences(dim):
    e1, e2 = random_frame(dim)
    f, origin = straight_frame(e1, e2), RNG.normal(size=dim)
    x = origin[:, None] + RNG.uniform(-1, 1, (dim, 20))

    def rt(y):
        xl = local_coordinates(y, origin, f)
        return polar(xl[0], xl[1])

    r, t = rt(x)
    x, r, t = x[:, np.abs(t) < 3.0], r[np.abs(t) < 3.0], t[np.abs(t) < 3.0]
    gr, gt = polar_gradients(r, t, f)
    h = 1e-6
    for i in range(dim):
        d = np.zeros((dim, 1))
        d[i] = h
        (rp, tp), (rm, tm) = rt(x + d), rt(x - d)
        assert np.allclose((rp - rm) / (2 * h), gr[i], atol=1e-8)
        assert np.allclose((tp - tm) / (2 * h), gt[i], atol=1e-7)


def test_bad_arguments_are_named():
    with pytest.raises(ValueError, match="phi holds 1 NaN"):
        polar(np.array([np.nan, 1.0]), np.array([0.0, 1.0]))
    with pytest.raises(ValueError, match="psi holds"):
        polar(np.array([1.0]), np.array([np.inf]))
    with pytest.raises(ValueError, match="phi and psi must have the same shape"):
        polar(np.zeros(3), np.zeros(2))
    with pytest.raises(ValueError, match="side must be"):
        polar(np.zeros(2), np.zeros(2), side=0)
    with pytest.raises(ValueError, match="grad_psi is zero"):
        tip_frame([1.0, 0.0], [0.0, 0.0])
    with pytest.raises(ValueError, match="parallel"):
        tip_frame([1.0, 1.0], [2.0, 2.0])
    with pytest.raises(ValueError, match="grad_phi and grad_psi must have the same shape"):
        tip_frame([1.0, 0.0, 0.0], [0.0, 1.0])
    with pytest.raises(ValueError, match="grad_phi must be a vector field"):
        tip_frame(np.zeros((4, 2)), np.zeros((4, 2)))
    with pytest.raises(ValueError, match="grad_phi holds 1 NaN"):
        tip_frame([np.nan, 0.0], [0.0, 1.0])
    with pytest.raises(ValueError, match="origin must have shape"):
        local_coordinates(np.zeros((2, 3)), [0.0, 0.0, 0.0], straight_frame([1, 0], [0, 1]))
    with pytest.raises(ValueError, match="r must be positive"):
        polar_gradients(0.0, 1.0, straight_frame([1, 0], [0, 1]))
    with pytest.raises(ValueError, match="must be an array of real numbers"):
        polar("a", 1.0)


def test_side_puts_points_computed_on_a_face_on_it():
    """A face point in global coordinates has ψ of round-off: side still decides θ."""
    f, origin = straight_frame(*[np.array(v) for v in random_frame(3)]), RNG.normal(size=3)
    r = RNG.uniform(0.01, 10, 40)
    x = origin[:, None] - r * f.e1[:, None]
    xl = local_coordinates(x, origin, f)
    assert np.any(xl[1] != 0)                                 # round-off, not zero
    for s in (1, -1):
        assert np.array_equal(polar(xl[0], xl[1], side=s)[1], np.full(40, s * np.pi))
    off = polar(np.array([-1.0]), np.array([1e-6]), side=-1)[1]
    assert 0 < off[0] < np.pi                                 # truly off the face: Ω⁺


def test_face_tolerance_covers_points_near_a_far_tip():
    """Close to a tip far from the origin of coordinates (r = 1e-6, |origin| = 1e3) the
    round-off of ψ is relative to the coordinates, not to r: face_tolerance is."""
    from skxfem.crack.frame import face_tolerance
    f, origin = straight_frame(*[np.array(v) for v in random_frame(2)]), np.array([1e3, -7e2])
    r = np.geomspace(1e-6, 1.0, 30)
    x = origin[:, None] - r * f.e1[:, None]
    xl = local_coordinates(x, origin, f)
    for s in (1, -1):
        t = polar(xl[0], xl[1], side=s, tol=face_tolerance(x, origin))[1]
        assert np.array_equal(t, np.full(30, s * np.pi))
