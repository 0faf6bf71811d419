"""Exercise 07, contact and friction updates: make these pass in order
(``pytest exercises/07_contact``)."""
import numpy as np

ASKED = ("augmented_multiplier", "normal_update", "ball_projection")
LIBRARY = ("skxfem.contact.laws", "skxfem.contact")   # they hold the answers

RNG = np.random.default_rng(7)


def test_01_augmented_multiplier(impl):
    got = np.asarray(impl.augmented_multiplier(np.array([-1.0]), np.array([0.5]), 2.0))
    assert np.allclose(got, [-2.0]), f"g_n = λ - ρ_n d_n = -1 - 2·0.5 = -2, got {got.tolist()}"
    lam, d = RNG.normal(size=5), RNG.normal(size=5)
    got = np.asarray(impl.augmented_multiplier(lam, d, 3.0))
    assert got.shape == (5,) and np.allclose(got, lam - 3.0 * d), (
        "augmented_multiplier works point by point on arrays: g_n = λ - ρ_n d_n")


def update(impl, g):
    out = impl.normal_update(np.asarray(g, dtype=float))
    assert len(out) == 2, "normal_update returns two arrays: (value, slope)"
    value, slope = (np.asarray(x, dtype=float) for x in out)
    assert value.shape == slope.shape == np.shape(g), (
        f"one value and one slope per point: shape {np.shape(g)}, got {value.shape} and "
        f"{slope.shape}")
    return value, slope


def test_02_normal_update_known_values(impl):
    g = np.array([-2.0, 0.5, -1e-3, 0.0, 4.0])
    value, _ = update(impl, g)
    for gi, vi in zip(g, value):
        want = gi if gi < 0 else 0.0
        assert vi == want, (
            f"χ(g_n) g_n at g_n = {gi:g} should be {want:g}, got {vi:g}: "
            f"χ(g_n) = 1 for g_n < 0 (contact, λ = g_n) and 0 for g_n ≥ 0 (open, λ = 0)")


def test_03_the_update_is_signorini(impl):
    # admissible states of eq. 5: open (d_n < 0, λ = 0) or closed (d_n = 0, λ < 0)
    lam = np.array([0.0, -0.8, 0.0, -2.0])
    d = np.array([-0.3, 0.0, -1e-4, 0.0])
    for rho in (0.1, 1.0, 10.0):
        g = np.asarray(impl.augmented_multiplier(lam, d, rho))
        r = lam - update(impl, g)[0]
        k = int(np.argmax(np.abs(r)))
        assert np.allclose(r, 0, atol=1e-14), (
            f"λ = {lam[k]:g}, d_n = {d[k]:g} satisfy Signorini's law (eq. 5), so λ - χ(g_n) g_n "
            f"must vanish for every ρ_n; with ρ_n = {rho:g} it is {r[k]:g}")
    # inadmissible: penetration (d_n > 0) or a tensile multiplier (λ > 0)
    lam, d = np.array([0.0, 0.5, 0.4]), np.array([0.2, 0.0, -0.1])
    r = lam - update(impl, np.asarray(impl.augmented_multiplier(lam, d, 1.0)))[0]
    assert np.all(np.abs(r) > 1e-3), (
        f"λ = {lam.tolist()}, d_n = {d.tolist()} violate eq. 5, so λ - χ(g_n) g_n must not "
        f"vanish; got {r.tolist()}")


def test_04_normal_update_slope(impl):
    g = np.array([-1.5, -0.2, 0.2, 0.7])
    _, slope = update(impl, g)
    for gi, si in zip(g, slope):
        want = 1.0 if gi < 0 else 0.0
        assert si == want, (
            f"d(χ(g_n) g_n)/dg_n at g_n = {gi:g} is {want:g}, got {si:g}"
            + (": the interface is open there (λ = 0 whatever g_n), the Jacobian misses the "
               "inactive branch" if gi > 0 else ": in contact λ = g_n, slope 1"))
    eps = 1e-7
    fd = (update(impl, g + eps)[0] - update(impl, g - eps)[0]) / (2 * eps)
    assert np.allclose(slope, fd, atol=1e-6), (
        f"the slopes {slope.tolist()} must match the finite differences of χ(g) g "
        f"{np.round(fd, 6).tolist()} away from g_n = 0")
    kink = update(impl, np.array([0.0]))[1][0]
    assert 0.0 <= kink <= 1.0, f"at the kink g_n = 0 the slope lies in [0, 1], got {kink:g}"


def project(impl, g):
    out = impl.ball_projection(np.asarray(g, dtype=float))
    assert len(out) == 2, "ball_projection returns two arrays: (P, DP)"
    P, DP = (np.asarray(x, dtype=float) for x in out)
    n, k = np.shape(g)
    assert P.shape == (n, k) and DP.shape == (n, k, k), (
        f"for g of shape {(n, k)}, P has shape {(n, k)} and DP {(n, k, k)}; got {P.shape} "
        f"and {DP.shape}")
    return P, DP


def test_05_projection_onto_the_unit_ball(impl):
    inside = np.array([[0.3, 0.4], [-0.5, 0.1], [0.0, 0.99]])
    P, _ = project(impl, inside)
    assert np.allclose(P, inside, atol=1e-15), (
        f"points inside the unit ball (|g| ≤ 1: adherence) are left where they are: "
        f"{inside.tolist()}, got {np.round(P, 6).tolist()}")
    outside = np.array([[3.0, 4.0], [0.0, -1.5], [-2.0, 2.0]])
    P, _ = project(impl, outside)
    want = outside / np.linalg.norm(outside, axis=1, keepdims=True)
    assert np.allclose(P, want, atol=1e-15), (
        f"points outside the ball go to g/|g| (sliding): {np.round(want, 6).tolist()}, got "
        f"{np.round(P, 6).tolist()}")


def test_06_projection_properties(impl):
    g = RNG.normal(scale=1.5, size=(200, 2))
    P, _ = project(impl, g)
    assert np.all(np.linalg.norm(P, axis=1) <= 1 + 1e-14), "|P(g)| ≤ 1 always"
    assert np.allclose(project(impl, P)[0], P, atol=1e-14), (
        "a projection is idempotent: P(P(g)) = P(g)")
    one = project(impl, np.array([[-3.0], [0.5]]))[0]
    assert np.allclose(one.ravel(), [-1.0, 0.5]), (
        f"with one tangential component (2D), P_B(0,1) clips to [-1, 1]: (-3, 0.5) → (-1, 0.5); "
        f"got {one.ravel().tolist()}")


def test_07_projection_jacobian(impl):
    g = np.array([[0.3, 0.4], [2.0, 0.0], [-1.2, 1.6]])
    _, DP = project(impl, g)
    assert np.allclose(DP[0], np.eye(2)), (
        f"inside the ball P(g) = g, its Jacobian is I; got {DP[0].tolist()}")
    for j in (1, 2):
        radial = DP[j] @ g[j]
        assert np.allclose(radial, 0, atol=1e-14), (
            f"outside the ball P(g) = g/|g| does not change along g: DP g = 0 (the radial "
            f"direction is projected away, (I - ĝĝᵀ)/|g|); at g = {g[j].tolist()} got "
            f"{np.round(radial, 6).tolist()}")
    eps = 1e-7
    for j in range(3):
        fd = np.column_stack([(project(impl, g[j:j + 1] + eps * e)[0]
                               - project(impl, g[j:j + 1] - eps * e)[0])[0] / (2 * eps)
                              for e in np.eye(2)])
        assert np.allclose(DP[j], fd, atol=1e-6), (
            f"DP at g = {g[j].tolist()} must match the finite differences "
            f"{np.round(fd, 6).tolist()}; got {np.round(DP[j], 6).tolist()}")


def test_08_the_projection_is_coulomb(impl):
    rho = 2.0
    stick = np.array([[0.3, -0.4]])               # |Λ| < 1, no slip
    assert np.allclose(stick - project(impl, stick)[0], 0), (
        "adherence (|Λ| < 1, v_τ = 0) solves Λ = P_B(0,1)(Λ + ρ_τ v_τ)")
    slide = np.array([[0.6, 0.8]])                # |Λ| = 1, slip along Λ
    assert np.allclose(slide - project(impl, slide + rho * 0.7 * slide)[0], 0), (
        "sliding (|Λ| = 1, v_τ ∥ Λ) solves Λ = P_B(0,1)(Λ + ρ_τ v_τ)")
    assert not np.allclose(slide - project(impl, slide - rho * 0.7 * slide)[0], 0), (
        "a slip against Λ violates Coulomb's law (eq. 8)")
