"""Exercise 08, the crack-tip branch functions: make these pass in order
(``pytest exercises/08_crack``)."""
import numpy as np

ASKED = ("polar_coordinates", "branch_functions", "branch_gradients")
LIBRARY = ("skxfem.crack",)   # it holds the answers: write your own

RNG = np.random.default_rng(8)


def polar(impl, x1, x2):
    out = impl.polar_coordinates(np.asarray(x1, float), np.asarray(x2, float))
    assert len(out) == 2, "polar_coordinates returns two arrays: (r, theta)"
    return tuple(np.asarray(v, dtype=float) for v in out)


def F(impl, r, theta):
    got = np.asarray(impl.branch_functions(np.asarray(r, float), np.asarray(theta, float)))
    assert got.shape == (4,) + np.shape(r), (
        f"branch_functions of r of shape {np.shape(r)} must have shape (4,) + "
        f"{np.shape(r)}, the index l of F_l first; got {got.shape}")
    return got


def G(impl, r, theta):
    got = np.asarray(impl.branch_gradients(np.asarray(r, float), np.asarray(theta, float)))
    assert got.shape == (4, 2) + np.shape(r), (
        f"branch_gradients of r of shape {np.shape(r)} must have shape (4, 2) + "
        f"{np.shape(r)}: [l, a] is ∂F_l/∂x_a; got {got.shape}")
    return got


def test_01_polar_coordinates_of_known_points(impl):
    cases = [((1.0, 0.0), (1.0, 0.0), "ahead of the tip"),
             ((0.0, 2.0), (2.0, np.pi / 2), "straight into Ω⁺"),
             ((0.0, -3.0), (3.0, -np.pi / 2), "straight into Ω⁻"),
             ((-1.0, 0.0), (1.0, np.pi), "on the face of Ω⁺ (x₂ = +0)"),
             ((-1.0, -0.0), (1.0, -np.pi), "on the face of Ω⁻ (x₂ = -0)"),
             ((3.0, 4.0), (5.0, np.arctan2(4.0, 3.0)), "in Ω⁺")]
    for (x1, x2), (r, t), where in cases:
        got_r, got_t = (float(v) for v in polar(impl, x1, x2))
        assert abs(got_r - r) < 1e-14 and abs(got_t - t) < 1e-14, (
            f"at (x₁, x₂) = ({x1:g}, {x2:g}), {where}, (r, θ) should be ({r:g}, {t:.6g}), "
            f"got ({got_r:g}, {got_t:.6g}): θ = atan2(x₂, x₁) = atan2(ψ, φ), the angle "
            f"from e₁ (ahead) towards e₂ (into Ω⁺)")


def test_02_polar_coordinates_on_arrays(impl):
    x1, x2 = RNG.normal(size=(3, 4)), RNG.normal(size=(3, 4))
    r, t = polar(impl, x1, x2)
    assert r.shape == t.shape == (3, 4), "r and θ have the shape of x₁ (point by point)"
    assert np.allclose(r * np.cos(t), x1) and np.allclose(r * np.sin(t), x2), (
        "x₁ = r cos θ and x₂ = r sin θ must give the points back: θ = atan2(x₂, x₁)")


def test_03_branch_functions_at_known_points(impl):
    r = np.array([4.0, 4.0, 4.0, 9.0])
    t = np.array([0.0, np.pi / 2, np.pi, -np.pi / 3])
    s, c, st = np.sin(t / 2), np.cos(t / 2), np.sin(t)
    want = np.sqrt(r) * np.array([s, c, s * st, c * st])
    got = F(impl, r, t)
    for k in range(4):
        bad = np.abs(got[:, k] - want[:, k]) > 1e-12
        if bad.any():
            l = int(np.argmax(bad)) + 1
            hint = ""
            if np.allclose(got[:, k], want[:, k] / np.sqrt(r[k])):
                hint = ": each F_l carries the factor √r"
            full = np.sqrt(r[k]) * np.array([np.sin(t[k]), np.cos(t[k]),
                                             np.sin(t[k]) ** 2, np.cos(t[k]) * np.sin(t[k])])
            if np.allclose(got[:, k], full):
                hint = ": the branch functions use the half angle θ/2, sin θ/2 and cos θ/2"
            raise AssertionError(
                f"F_{l}(r = {r[k]:g}, θ = {t[k]:.4g}) should be {want[l - 1, k]:.6g}, got "
                f"{got[l - 1, k]:.6g}{hint} (F = √r {{sin θ/2, cos θ/2, sin θ/2 sin θ, "
                f"cos θ/2 sin θ}}, in that order)")


def test_04_F1_jumps_by_2_sqrt_r_and_the_others_do_not(impl):
    r = np.array([0.25, 1.0, 4.0])
    plus, minus = F(impl, r, np.full(3, np.pi)), F(impl, r, np.full(3, -np.pi))
    jump = plus[0] - minus[0]
    assert np.allclose(jump, 2 * np.sqrt(r)), (
        f"F₁(θ = π) - F₁(θ = -π) should be 2√r = {(2 * np.sqrt(r)).tolist()}, got "
        f"{jump.tolist()}: F₁ = √r sin θ/2 carries the jump across the faces")
    assert np.allclose(plus[1:], minus[1:], atol=1e-12), (
        "F₂, F₃, F₄ must take the same value on both faces (θ = ±π): only F₁ jumps")


def test_05_gradients_at_known_points(impl):
    """Ahead of the tip (θ = 0) and straight above it (θ = π/2), at r = 4."""
    r = np.array([4.0, 4.0])
    t = np.array([0.0, np.pi / 2])
    k = 1 / (2 * np.sqrt(r))
    s, c, s3, c3 = np.sin(t / 2), np.cos(t / 2), np.sin(3 * t / 2), np.cos(3 * t / 2)
    want = k * np.array([[-s, c], [c, s], [-s3 * np.sin(t), s + s3 * np.cos(t)],
                         [-c3 * np.sin(t), c + c3 * np.cos(t)]])
    got = G(impl, r, t)
    if not np.allclose(got, want, atol=1e-12):
        l, a, p = np.unravel_index(np.argmax(np.abs(got - want)), got.shape)
        hint = ""
        if np.allclose(got * np.sqrt(r), want, atol=1e-12):
            hint = (" (your values are √r times too small: the gradient of √r g(θ) is "
                    "g/(2√r) ∂r + √r g′ ∂θ with ∂θ of size 1/r, of order 1/√r)")
        elif np.allclose(got / np.sqrt(r), want, atol=1e-12):
            hint = (" (your values are √r times too large: the gradient is of order 1/√r; "
                    "did you miss a 1/√r?)")
        raise AssertionError(
            f"∂F_{l + 1}/∂x_{a + 1} at r = 4, θ = {t[p]:.4g} should be {want[l, a, p]:.6g}, "
            f"got {got[l, a, p]:.6g}{hint}")


def test_06_gradients_are_those_of_the_functions(impl):
    """Central differences of F(r(x), θ(x)) at random points, away from the faces."""
    x = RNG.uniform(-1, 1, (2, 40))
    r, t = np.hypot(x[0], x[1]), np.arctan2(x[1], x[0])
    keep = (r > 0.2) & (np.abs(t) < 3.0)
    x, r, t = x[:, keep], r[keep], t[keep]
    got = G(impl, r, t)
    h = 1e-6
    for a in range(2):
        d = np.zeros((2, 1))
        d[a] = h
        xp, xm = x + d, x - d
        fd = (F(impl, np.hypot(*xp), np.arctan2(xp[1], xp[0]))
              - F(impl, np.hypot(*xm), np.arctan2(xm[1], xm[0]))) / (2 * h)
        err = np.abs(got[:, a] - fd)
        if err.max() > 1e-6:
            l, p = np.unravel_index(np.argmax(err), err.shape)
            raise AssertionError(
                f"∂F_{l + 1}/∂x_{a + 1} at (x₁, x₂) = ({x[0, p]:.3f}, {x[1, p]:.3f}) is "
                f"{got[l, a, p]:.6g} but finite differences of your branch_functions give "
                f"{fd[l, p]:.6g}: ∂F/∂x₁ = cos θ ∂F/∂r - (sin θ/r) ∂F/∂θ, ∂F/∂x₂ = sin θ "
                f"∂F/∂r + (cos θ/r) ∂F/∂θ (check each sign, and θ/2 inside the sines)")


def test_07_gradients_grow_as_one_over_sqrt_r(impl):
    t = RNG.uniform(-3.0, 3.0, 6)
    near, far = G(impl, np.full(6, 1e-4), t), G(impl, np.full(6, 1.0), t)
    assert np.allclose(near * 1e-2, far, atol=1e-12), (
        "the gradient of √r g(θ) is of order 1/√r: at r = 1e-4 it must be 100 times its "
        "value at r = 1 (the same θ); the singular strain near the tip comes from it")
