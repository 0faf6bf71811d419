"""Exercise 04, naive multipliers: make these pass in order
(``pytest exercises/04_multipliers``)."""
import numpy as np
from skfem import MeshTri1

from skxfem.cut import cut
from skxfem.levelset import circle
from skxfem.multipliers import interface_mass, interface_rule

ASKED = ("interpolate", "interface_mass")
LIBRARY = ("skxfem.multipliers",)   # it holds the answer: write your own

# a polyline of three segments through four points, given out of order
POINTS = np.array([[0.0, 2.0, 1.0, 2.0], [0.0, 1.0, 0.0, 3.0]])
SEGMENTS = np.array([[0, 2, 1], [2, 1, 3]])          # 0-2 (L=1), 2-1 (L=√2), 1-3 (L=2)
LENGTHS = np.array([1.0, np.sqrt(2.0), 2.0])


def test_01_interpolate_at_the_ends(impl):
    lam = np.array([1.0, 5.0, 2.0, -3.0])
    for k in range(3):
        a, b = SEGMENTS[:, k]
        for s, want, end in ((0.0, lam[a], "start"), (1.0, lam[b], "end")):
            got = impl.interpolate(lam, SEGMENTS, k, s)
            assert abs(got - want) < 1e-12, (
                f"on segment {k} = ({a}, {b}), λ_h at s = {s:g} (the {end} of the segment, "
                f"point {a if s == 0 else b}) must be λ_{a if s == 0 else b} = {want:g}, got "
                f"{got:g}")


def test_02_interpolate_is_linear(impl):
    lam = np.array([1.0, 5.0, 2.0, -3.0])
    for s in (0.25, 0.5, 0.9):
        got = impl.interpolate(lam, SEGMENTS, 2, s)
        want = (1 - s) * lam[1] + s * lam[3]
        assert abs(got - want) < 1e-12, (
            f"λ_h on segment 2 = (1, 3) at s = {s:g} is (1 - s) λ_1 + s λ_3 = {want:g}, "
            f"got {got:g}")


def mass(impl, points, segments):
    M = np.asarray(impl.interface_mass(points, segments), dtype=float)
    n = points.shape[1]
    assert M.shape == (n, n), (
        f"interface_mass must return ({n}, {n}), one row per point; got {M.shape}")
    return M


def test_03_mass_of_one_segment(impl):
    M = mass(impl, np.array([[0.0, 0.0], [0.0, 3.0]]), np.array([[0], [1]]))
    want = 3.0 / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])
    assert np.allclose(M, want, atol=1e-12), (
        f"a segment of length L = 3 has the mass L/6 [[2, 1], [1, 2]] = {want.tolist()}, got "
        f"{np.round(M, 6).tolist()}")


def test_04_mass_is_symmetric_and_sums_to_the_length(impl):
    M = mass(impl, POINTS, SEGMENTS)
    assert np.allclose(M, M.T, atol=1e-12), "M_ef = ∫ N_e N_f is symmetric"
    total = LENGTHS.sum()
    assert abs(M.sum() - total) < 1e-12, (
        f"Σ_ef M_ef = ∫ (Σ N_e)(Σ N_f) = ∫ 1 = |Γ_h| = {total:.6g}, the length of Γ_h; got "
        f"{M.sum():.6g}")


def test_05_mass_of_a_polyline(impl):
    M = mass(impl, POINTS, SEGMENTS)
    row = M.sum(axis=1)                       # ∫ N_e: half of each neighbouring segment
    want = np.zeros(4)
    np.add.at(want, SEGMENTS.ravel(), np.tile(LENGTHS / 2, 2))
    assert np.allclose(row, want, atol=1e-12), (
        f"the rows of M sum to ∫ N_e, half the length of the segments at point e: "
        f"{np.round(want, 6).tolist()}; got {np.round(row, 6).tolist()}")
    assert abs(M[0, 2] - 1 / 6) < 1e-12 and M[0, 1] == 0, (
        f"M[0, 2] couples the two ends of segment (0, 2) of length 1: 1/6, and points 0 and 1 "
        f"share no segment, M[0, 1] = 0; got {M[0, 2]:.6g} and {M[0, 1]:.6g} (on a segment, "
        f"L/6 [[2, 1], [1, 2]])")


def test_06_mass_of_a_cut_mesh(impl):
    mesh = MeshTri1().refined(3)
    c = cut(mesh, circle((0.5, 0.5), 0.31))
    M = mass(impl, c.points, c.facets)
    want = interface_mass(interface_rule(mesh, c)).toarray()
    k = np.unravel_index(np.argmax(np.abs(M - want)), M.shape)
    assert np.allclose(M, want, atol=1e-12), (
        f"on a mesh cut by a circle, M[{k[0]}, {k[1]}] should be {want[k]:.6g} (skxfem's "
        f"interface_mass), got {M[k]:.6g}")
