"""Exercise 01, signed distances: make these pass in order (``pytest exercises/01_levelset``)."""
import numpy as np

ASKED = ("plane", "circle", "sphere")
LIBRARY = ("skxfem.levelset",)     # its plane/circle/sphere are the answers: write your own

RNG = np.random.default_rng(1)


def value(psi, x):
    """ψ at one point, as a float."""
    return float(np.asarray(psi(np.asarray(x, dtype=float))))


def test_01_plane_vanishes_on_the_plane(impl):
    psi = impl.plane((0.2, 0.5), (1.0, 2.0))
    for t in (0.0, 1.0, -0.7):
        x = np.array([0.2, 0.5]) + t * np.array([2.0, -1.0])   # along the line
        got = value(psi, x)
        assert abs(got) < 1e-12, (
            f"plane((0.2, 0.5), (1, 2)): the point {x.tolist()} lies on the line, but ψ "
            f"there is {got:.3g}; it should be 0")


def test_02_plane_is_a_signed_distance(impl):
    psi = impl.plane((0.0, 0.0, 0.5), (0.0, 0.0, 2.0))
    for s in (0.5, -0.25):
        x = [0.3, 0.1, 0.5 + s]
        got = value(psi, x)
        assert abs(got - s) < 1e-12, (
            f"plane((0, 0, 0.5), (0, 0, 2)): the point {x} is at distance {abs(s)} "
            f"{'above' if s > 0 else 'below'} the plane, so ψ should be {s} (positive on "
            f"the side the normal points to), got {got:.6g}. "
            + ("Did you normalise the normal (n/|n|)? " if abs(abs(got) - 2 * abs(s)) < 1e-9
               else ""))


def test_03_plane_gradient_is_the_unit_normal(impl):
    psi = impl.plane((0.5, 0.5, 0.5), (1.0, 2.0, 2.0))
    x, eps = np.array([0.2, 0.7, 0.1]), 1e-6
    grad = np.array([value(psi, x + eps * e) - value(psi, x - eps * e)
                     for e in np.eye(3)]) / (2 * eps)
    assert np.allclose(grad, np.array([1.0, 2.0, 2.0]) / 3.0, atol=1e-8), (
        f"∇ψ of plane(..., normal=(1, 2, 2)) should be the unit normal (1, 2, 2)/3, got "
        f"{np.round(grad, 6).tolist()}: normalise the normal")


def test_04_plane_works_on_arrays_of_points(impl):
    psi = impl.plane((0.0, 0.5), (0.0, 1.0))
    x = RNG.random((2, 4, 3))                       # scikit-fem's (dim, cells, points)
    got = np.asarray(psi(x))
    assert got.shape == (4, 3), (
        f"ψ of points of shape (2, 4, 3) must have shape (4, 3), one value per point; got "
        f"{got.shape}. x[0] is the array of first coordinates")
    assert np.allclose(got, x[1] - 0.5), "ψ(x) of plane((0, 0.5), (0, 1)) should be y - 0.5"


def test_05_circle_known_values(impl):
    psi = impl.circle((0.5, 0.5), 0.3)
    centre = value(psi, [0.5, 0.5])
    assert abs(centre + 0.3) < 1e-12, (
        f"ψ at the centre of circle((0.5, 0.5), 0.3) should be -0.3, got {centre:.6g}: the "
        f"centre of a circle is inside, in Ω⁻ (ψ < 0)")
    outside = value(psi, [1.0, 0.5])
    assert abs(outside - 0.2) < 1e-12, (
        f"(1, 0.5) is 0.2 outside circle((0.5, 0.5), 0.3), so ψ there should be +0.2, got "
        f"{outside:.6g}")


def test_06_circle_is_a_distance_everywhere(impl):
    center, r = np.array([0.1, -0.2]), 0.7
    psi = impl.circle(center, r)
    x = RNG.normal(size=(2, 50))
    got = np.asarray(psi(x))
    assert got.shape == (50,), (
        f"ψ of 50 points (shape (2, 50)) must have shape (50,), got {got.shape}")
    want = np.linalg.norm(x - center[:, None], axis=0) - r
    k = int(np.argmax(np.abs(got - want)))
    assert np.allclose(got, want, atol=1e-12), (
        f"at x = {np.round(x[:, k], 4).tolist()} the signed distance to circle({center.tolist()}, "
        f"{r}) is {want[k]:.6g}, got {got[k]:.6g}")


def test_07_sphere_is_a_distance_everywhere(impl):
    center, r = np.array([0.5, 0.5, 0.5]), 0.25
    psi = impl.sphere(center, r)
    x = RNG.random((3, 40))
    got = np.asarray(psi(x))
    assert got.shape == (40,), (
        f"ψ of 40 points (shape (3, 40)) must have shape (40,), got {got.shape}")
    want = np.linalg.norm(x - center[:, None], axis=0) - r
    assert np.all(np.sign(got) == np.sign(want)), (
        "the sign of ψ is wrong at some points: ψ < 0 inside the sphere (Ω⁻), > 0 outside")
    k = int(np.argmax(np.abs(got - want)))
    assert np.allclose(got, want, atol=1e-12), (
        f"at x = {np.round(x[:, k], 4).tolist()}, {want[k]:.6g} from the sphere, ψ is "
        f"{got[k]:.6g}: ψ has the right sign but is not the distance to the sphere "
        f"(|x - c| - r, not |x - c|² - r²)")
