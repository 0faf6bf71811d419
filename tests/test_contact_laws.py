"""The local laws of skxfem.contact.laws: values and Jacobians against finite differences."""
import numpy as np
import pytest

from skxfem.contact.laws import (
    OPEN,
    SLIP,
    STICK,
    ball_projection,
    disk_projection,
    indicator,
    normal_update,
    status,
)


def test_normal_update_is_signorini():
    """λ - χ(λ - ρ d)(λ - ρ d) = 0 holds exactly for the three Signorini states."""
    rho = 7.0
    lam = np.array([-2.0, 0.0, 0.0])
    d = np.array([0.0, -1.0, 0.0])  # contact, open, grazing
    value, _ = normal_update(lam - rho * d)
    assert np.array_equal(lam - value, np.zeros(3))
    # a violation in each direction leaves a residual
    value, _ = normal_update(np.array([1.0, -1.0]) - rho * np.array([0.0, 0.1]))
    assert np.all(np.abs(np.array([1.0, -1.0]) - value) > 0)


def test_normal_jacobian_matches_finite_differences():
    g = np.random.default_rng(0).uniform(-5, 5, 200)
    g = g[np.abs(g) > 1e-3]  # away from the kink
    h = 1e-7
    fd = (normal_update(g + h)[0] - normal_update(g - h)[0]) / (2 * h)
    assert np.allclose(normal_update(g)[1], fd, atol=1e-8)
    assert set(np.unique(normal_update(g)[1])) == {0.0, 1.0}  # both branches sampled
    assert indicator(0.0) == 0.0  # χ(0) = 0 as in the paper


@pytest.mark.parametrize("k", [1, 2])
def test_ball_jacobian_matches_finite_differences(k):
    rng = np.random.default_rng(k)
    g = rng.uniform(-2.5, 2.5, (300, k))
    r = np.linalg.norm(g, axis=1)
    g = g[np.abs(r - 1) > 1e-3]
    P, DP = ball_projection(g)
    assert np.all(np.linalg.norm(P, axis=1) <= 1 + 1e-14)
    inside = np.linalg.norm(g, axis=1) < 1
    assert inside.any() and (~inside).any()
    assert np.allclose(P[inside], g[inside])
    h = 1e-7
    for b in range(k):
        e = np.zeros(k)
        e[b] = h
        fd = (ball_projection(g + e)[0] - ball_projection(g - e)[0]) / (2 * h)
        assert np.allclose(DP[:, :, b], fd, atol=1e-7)


def test_ball_projection_keeps_direction_outside():
    P, _ = ball_projection(np.array([[0.0, -4.0], [3.0, 4.0]]))
    assert np.allclose(P, [[0.0, -1.0], [0.6, 0.8]])


def test_status():
    g_n = np.array([0.0, -1.0, -1.0, 2.0])
    y = np.array([[5.0], [0.9], [-1.1], [0.0]])
    R = np.ones(4)
    assert status(g_n, y, R, "coulomb").tolist() == [OPEN, STICK, SLIP, OPEN]
    assert status(g_n, None, None, "frictionless").tolist() == [OPEN, SLIP, SLIP, OPEN]
    assert status(g_n, None, None, "adhesive").tolist() == [OPEN, STICK, STICK, OPEN]
    assert status(g_n, None, None, "bilateral").tolist() == [SLIP] * 4  # tied: never open
    assert status(g_n, None, None, "bonded").tolist() == [STICK] * 4
    assert status(g_n, np.array([[1.0]] * 4), R, "coulomb")[1] == STICK  # on the limit
    with pytest.raises(ValueError, match="law must be one of"):
        status(g_n, None, None, "glue")


@pytest.mark.parametrize("k", [1, 2])
def test_disk_projection_scales_the_ball_and_its_jacobian(k):
    """P_{B(R)}(y) = R P_B(y/R); dP/dy and dP/dR against central differences."""
    rng = np.random.default_rng(k)
    y = rng.uniform(-3, 3, (200, k))
    R = rng.uniform(0.1, 2, 200)
    keep = np.abs(np.linalg.norm(y, axis=1) - R) > 1e-3
    y, R = y[keep], R[keep]
    P, DP, dR = disk_projection(y, R)
    assert np.allclose(P, R[:, None] * ball_projection(y / R[:, None])[0])
    assert np.all(np.linalg.norm(P, axis=1) <= R * (1 + 1e-14))
    h = 1e-7
    for b in range(k):
        e = np.zeros(k)
        e[b] = h
        fd = (disk_projection(y + e, R)[0] - disk_projection(y - e, R)[0]) / (2 * h)
        assert np.allclose(DP[:, :, b], fd, atol=1e-6)
    fd = (disk_projection(y, R + h)[0] - disk_projection(y, R - h)[0]) / (2 * h)
    assert np.allclose(dR, fd, atol=1e-6)


def test_disk_projection_of_radius_zero():
    """R = 0: the traction vanishes (an open point); y = 0 too: the stick branch."""
    P, DP, dR = disk_projection(np.array([[1.0, 2.0], [0.0, 0.0]]), np.zeros(2))
    assert np.all(P == 0)
    assert np.all(DP[0] == 0) and np.allclose(dR[0], np.array([1.0, 2.0]) / np.sqrt(5))
    assert np.array_equal(DP[1], np.eye(2)) and np.all(dR[1] == 0)


def test_a_vanishing_friction_coefficient_is_frictionless():
    """μ = 1e-308 (issue 18: the Newton matrix was 'exactly singular', y/R overflowing):
    the ball of radius μp is computed without dividing by the radius.  Issue 26: below
    FRICTION_RANGE (1e-10) μp is round-off and Λ = r/(μp) was NaN at 5e-324: refused;
    at 1e-10 every point slides, |Λ| = 1, with the frictionless pressures."""
    from dataclasses import replace

    from skxfem import contact
    from skxfem.scene import Displacement, SurfaceLoad, clamped
    from skxfem.scene.benchmarks import strip
    from skxfem.scene.parts import FRICTION_RANGE

    s = replace(strip(n=3), law="frictionless", loads=(SurfaceLoad("ymax", pressure=1.0),),
                displacements=(clamped("ymin"), Displacement("ymax", {"x": 0.5})))
    ref = contact.solve(s).steps[-1]
    for mu in (1e-320, 1e-308):
        with pytest.raises(ValueError, match=r"friction \(Coulomb's mu\) must be 0 or in"):
            replace(s, law="coulomb", friction=mu)
    st = contact.solve(replace(s, law="coulomb", friction=FRICTION_RANGE[0])).steps[-1]
    assert np.all(st.status == 2) and np.abs(st.traction).max() < 1e-9
    assert np.allclose(st.pressure, ref.pressure, rtol=1e-9)
    pressed = st.pressure > 0
    np.testing.assert_allclose(np.abs(st.Lambda[pressed]), 1.0, rtol=1e-7)   # 1.4e-8
