"""skxfem.fem.simplex: the one clipping kernel (cut sub-cells and load pieces)."""
import math

import numpy as np
import pytest

from skxfem.fem.simplex import edge_point, split


def measure(S):
    """k-dimensional measure of simplices (m, k+1, dim) in any dim >= k."""
    T = S[:, 1:] - S[:, :1]                         # (m, k, dim)
    if T.shape[1] == T.shape[2]:
        return np.abs(np.linalg.det(T)) / math.factorial(T.shape[1])
    gram = np.einsum("mkd,mld->mkl", T, T)          # embedded: Gram determinant
    return np.sqrt(np.maximum(np.linalg.det(gram), 0.0)) / math.factorial(T.shape[1])


def side_measures(X, psi):
    sub, parent, side = split(X, psi)
    m = measure(sub)
    return (np.bincount(parent[side < 0], m[side < 0], minlength=len(X)),
            np.bincount(parent[side > 0], m[side > 0], minlength=len(X)))


@pytest.mark.parametrize("k, dim", [(1, 1), (1, 2), (1, 3), (2, 2), (2, 3), (3, 3)])
def test_pieces_fill_the_simplex_exactly(k, dim):
    """Random simplices and linear ψ: the pieces' measures add up to the simplex's,
    and the Ω⁻ part equals the measure of {ψ_h < 0} computed by Monte Carlo-free
    means: for a segment, the fraction t = ψ_a / (ψ_a - ψ_b)."""
    rng = np.random.default_rng(k * 10 + dim)
    X = rng.normal(size=(200, k + 1, dim))
    psi = rng.normal(size=(200, k + 1))
    minus, plus = side_measures(X, psi)
    # 1e-10: the Gram determinant of an embedded random sliver loses digits
    assert np.allclose(minus + plus, measure(X), rtol=1e-10, atol=1e-14)
    assert np.all(minus[np.all(psi > 0, axis=1)] == 0)
    assert np.all(plus[np.all(psi < 0, axis=1)] == 0)
    if k == 1:
        t = np.where(psi[:, 0] * psi[:, 1] < 0, psi[:, 0] / (psi[:, 0] - psi[:, 1]), 0.0)
        frac = np.where(psi[:, 0] < 0, np.where(t > 0, t, 1.0), 1.0 - t)
        frac[np.all(psi > 0, axis=1)] = 0.0
        assert np.allclose(minus, frac * measure(X), rtol=1e-10, atol=1e-14)


def test_tetrahedron_side_volume_is_exact():
    """ψ = z - c on the unit tetrahedron: the part below is 1/6 - (1 - c)³/6."""
    X = np.array([[[0., 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]])
    for c in (0.1, 0.5, 0.9):
        minus, plus = side_measures(X, X[:, :, 2] - c)
        assert minus[0] == pytest.approx(1 / 6 - (1 - c) ** 3 / 6, abs=1e-15)


def test_zero_vertex_counts_as_plus_and_face_on_gamma_is_plus():
    """A vertex with ψ = 0 belongs to Ω⁺; a simplex lying on Γ is one + piece."""
    tri = np.array([[[0., 0.], [1., 0.], [0., 1.]]])
    minus, plus = side_measures(tri, np.array([[0.0, 1.0, -1.0]]))
    assert minus[0] + plus[0] == pytest.approx(0.5, abs=1e-15)
    assert minus[0] == pytest.approx(0.25, abs=1e-15)     # cut at the midpoint of 1-2
    sub, parent, side = split(tri, np.zeros((1, 3)))
    assert side.tolist() == [1] and np.array_equal(sub, tri)


def test_edge_point_is_the_zero_of_the_interpolant():
    xa, xb = np.array([0.0, 1.0]), np.array([2.0, 3.0])
    x = edge_point(xa, xb, np.array(-1.0), np.array(3.0))
    assert x.tolist() == [0.5, 1.5]


@pytest.mark.parametrize("X, psi, match", [
    (np.zeros((1, 5, 3)), np.ones((1, 5)), "k = 1, 2 or 3"),
    (np.zeros((1, 4, 2)), np.ones((1, 4)), "dim >= k"),
    (np.zeros((1, 3, 2)), np.ones((1, 2)), "psi must be finite"),
    (np.zeros((1, 3, 2)), np.array([[1.0, np.nan, 1.0]]), "psi must be finite"),
])
def test_bad_input(X, psi, match):
    with pytest.raises(ValueError, match=match):
        split(X, psi)
