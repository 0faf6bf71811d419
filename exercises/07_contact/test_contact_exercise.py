"""Exercise 07, contact and friction updates: make these pass in order
(``pytest exercises/07_contact``)."""
import numpy as np

ASKED = ("augmented_multiplier", "contact_update", "contact_derivative", "project_unit_ball",
         "project_unit_ball_derivative")
LIBRARY = ("skxfem.contact",)   # it will hold the answer: write your own

RNG = np.random.default_rng(7)


def f(x):
    return float(np.asarray(x))


def test_01_augmented_multiplier(impl):
    got = f(impl.augmented_multiplier(-1.0, 0.5, 2.0))
    assert abs(got + 2.0) < 1e-14, f"g_n = λ - ρ_n d_n = -1 - 2·0.5 = -2, got {got:g}"
    lam, d = RNG.normal(size=5), RNG.normal(size=5)
    got = np.asarray(impl.augmented_multiplier(lam, d, 3.0))
    assert got.shape == (5,) and np.allclose(got, lam - 3.0 * d), (
        "augmented_multiplier works point by point on arrays: g_n = λ - ρ_n d_n")


def test_02_contact_update_known_values(impl):
    for g, want in ((-2.0, -2.0), (0.5, 0.0), (-1e-3, -1e-3), (0.0, 0.0)):
        got = f(impl.contact_update(np.array(g)))
        assert got == want, (
            f"χ(g_n) g_n at g_n = {g:g} should be {want:g}, got {got:g}: "
            f"χ(g_n) = 1 for g_n < 0 (contact, "
            f"λ = g_n) and 0 for g_n ≥ 0 (open, λ = 0)")


def test_03_the_update_is_signorini(impl):
    # admissible states of eq. 5: open (d_n < 0, λ = 0) or closed (d_n = 0, λ < 0)
    for lam, d in ((0.0, -0.3), (-0.8, 0.0), (0.0, -1e-4), (-2.0, 0.0)):
        for rho in (0.1, 1.0, 10.0):
            g = f(impl.augmented_multiplier(lam, d, rho))
            r = lam - f(impl.contact_update(np.array(g)))
            assert abs(r) < 1e-14, (
                f"λ = {lam:g}, d_n = {d:g} satisfy Signorini's law (eq. 5), so λ - χ(g_n) g_n "
                f"must vanish for every ρ_n; with ρ_n = {rho:g} it is {r:g}")
    # inadmissible: penetration (d_n > 0) or a tensile multiplier (λ > 0)
    for lam, d in ((0.0, 0.2), (0.5, 0.0), (0.4, -0.1)):
        g = f(impl.augmented_multiplier(lam, d, 1.0))
        r = lam - f(impl.contact_update(np.array(g)))
        assert abs(r) > 1e-3, (
            f"λ = {lam:g}, d_n = {d:g} violate eq. 5, so λ - χ(g_n) g_n must not vanish; "
            f"got {r:g}")


def test_04_contact_derivative(impl):
    g = np.array([-1.5, -0.2, 0.2, 0.7])
    got = np.asarray(impl.contact_derivative(g), dtype=float)
    assert got.shape == g.shape, f"one derivative per point: shape {g.shape}, got {got.shape}"
    for gi, di in zip(g, got):
        want = 1.0 if gi < 0 else 0.0
        assert di == want, (
            f"d(χ(g_n) g_n)/dg_n at g_n = {gi:g} is {want:g}, got {di:g}"
            + (": the interface is open there (λ = 0 whatever g_n), the Jacobian misses the "
               "inactive branch" if gi > 0 else ": in contact λ = g_n"))
    eps = 1e-7
    up, down = (np.asarray(impl.contact_update(g + s)) for s in (eps, -eps))
    fd = (up - down) / (2 * eps)
    assert np.allclose(got, fd, atol=1e-6), (
        f"contact_derivative {got.tolist()} must match the finite differences of contact_update "
        f"{np.round(fd, 6).tolist()} away from g_n = 0")


def test_05_projection_onto_the_unit_ball(impl):
    inside = np.array([[0.3, -0.5, 0.0], [0.4, 0.1, 0.99]])
    got = np.asarray(impl.project_unit_ball(inside), dtype=float)
    assert got.shape == inside.shape, (
        f"shape (k, ...) in, (k, ...) out: {inside.shape}, got {got.shape}")
    assert np.allclose(got, inside, atol=1e-15), (
        f"points inside the unit ball (|g| ≤ 1: adherence) are left where they are: "
        f"{inside.T.tolist()}, got {got.T.tolist()}")
    outside = np.array([[3.0, 0.0, -2.0], [4.0, -1.5, 2.0]])
    got = np.asarray(impl.project_unit_ball(outside), dtype=float)
    want = outside / np.linalg.norm(outside, axis=0)
    assert np.allclose(got, want, atol=1e-15), (
        f"points outside the ball go to g/|g| (sliding): {np.round(want, 6).T.tolist()}, got "
        f"{np.round(got, 6).T.tolist()}")


def test_06_projection_properties(impl):
    g = RNG.normal(scale=1.5, size=(2, 200))
    p = np.asarray(impl.project_unit_ball(g))
    assert np.all(np.linalg.norm(p, axis=0) <= 1 + 1e-14), "|P(g)| ≤ 1 always"
    assert np.allclose(np.asarray(impl.project_unit_ball(p)), p, atol=1e-14), (
        "a projection is idempotent: P(P(g)) = P(g)")
    one = np.asarray(impl.project_unit_ball(np.array([[-3.0, 0.5]])))
    assert np.allclose(one, [[-1.0, 0.5]]), (
        f"with one tangential component (2D), P_B(0,1) clips to [-1, 1]: (-3, 0.5) → (-1, 0.5); "
        f"got {one.ravel().tolist()}")


def test_07_projection_derivative(impl):
    g = np.array([[0.3, 2.0, -1.2], [0.4, 0.0, 1.6]])
    D = np.asarray(impl.project_unit_ball_derivative(g), dtype=float)
    assert D.shape == (2, 2, 3), f"a (k, k) matrix per point: shape (2, 2, 3), got {D.shape}"
    assert np.allclose(D[:, :, 0], np.eye(2)), (
        f"inside the ball P(g) = g, its derivative is I; got {D[:, :, 0].tolist()}")
    for j in (1, 2):
        radial = D[:, :, j] @ g[:, j]
        assert np.allclose(radial, 0, atol=1e-14), (
            f"outside the ball P(g) = g/|g| does not change along g: P'(g) g = 0 (the radial "
            f"direction is projected away, (I - ĝĝᵀ)/|g|); at g = {g[:, j].tolist()} got "
            f"{np.round(radial, 6).tolist()}")
    eps = 1e-7
    for j in range(3):
        P = impl.project_unit_ball
        fd = np.column_stack([(np.asarray(P(g[:, j] + eps * e)) - np.asarray(P(g[:, j] - eps * e)))
                              / (2 * eps) for e in np.eye(2)])
        assert np.allclose(D[:, :, j], fd, atol=1e-6), (
            f"P'(g) at g = {g[:, j].tolist()} must match the finite differences "
            f"{np.round(fd, 6).tolist()}; got {np.round(D[:, :, j], 6).tolist()}")


def test_08_the_projection_is_coulomb(impl):
    rho = 2.0
    # adherence: |Λ| < 1 and no slip
    lam_t = np.array([0.3, -0.4])
    r = lam_t - np.asarray(impl.project_unit_ball(lam_t + rho * np.zeros(2)))
    assert np.allclose(r, 0), "adherence (|Λ| < 1, v_τ = 0) solves Λ = P_B(0,1)(Λ + ρ_τ v_τ)"
    # sliding: |Λ| = 1 and the slip along Λ (v_τ = -α r_τ, r_τ = μλΛ with λ < 0)
    lam_t = np.array([0.6, 0.8])
    r = lam_t - np.asarray(impl.project_unit_ball(lam_t + rho * 0.7 * lam_t))
    assert np.allclose(r, 0), "sliding (|Λ| = 1, v_τ ∥ Λ) solves Λ = P_B(0,1)(Λ + ρ_τ v_τ)"
    r = lam_t - np.asarray(impl.project_unit_ball(lam_t - rho * 0.7 * lam_t))
    assert not np.allclose(r, 0), "a slip against Λ violates Coulomb's law (eq. 8)"
