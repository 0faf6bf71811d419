"""Exercise 05, the inf-sup constant: make these pass in order (``pytest exercises/05_lbb``)."""

import numpy as np
import pytest
import scipy.sparse as sp

import skxfem.lbb
from skxfem.cut import cut
from skxfem.levelset import plane
from skxfem.scene import Box, Scene, clamped, resolve_mesh

ASKED = ("inf_sup_constant", "unseen_multipliers")
LIBRARY = ("skxfem.lbb",)   # it holds the answer: write your own

B0 = np.array([[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]])


def beta(impl, A, B, M):
    got = impl.inf_sup_constant(A, B, M)
    assert np.ndim(got) == 0, f"inf_sup_constant returns one number, got {np.shape(got)}"
    return float(got)


def test_01_identity_norms(impl):
    got = beta(impl, np.eye(3), B0, np.eye(2))
    assert abs(got - 1.0) < 1e-12, (
        f"with A = I, M = I and B = [[1, 0, 0], [0, 2, 0]] the worst multiplier is μ = (1, 0): "
        f"β = 1; got {got:.6g}")


def test_02_the_multiplier_norm_counts(impl):
    A, B, M = np.eye(2), np.diag([1.0, 2.0]), np.diag([4.0, 1.0])
    got = beta(impl, A, B, M)
    assert abs(got - 0.5) < 1e-12, (
        f"A = I, B = diag(1, 2), M = diag(4, 1): B A⁻¹ Bᵀ = diag(1, 4), and β² = min(1/4, 4/1) "
        f"so β = 1/2; got {got:.6g}"
        + (". β measures μ in the norm of the multipliers, M: solve B A⁻¹ Bᵀ x = β² M x"
           if abs(got - 1.0) < 1e-12 else ""))


def test_03_scaling(impl):
    rng = np.random.default_rng(5)
    G = rng.normal(size=(5, 5))
    A, B, M = G @ G.T + 5 * np.eye(5), rng.normal(size=(3, 5)), np.diag([1.0, 2.0, 3.0])
    b = beta(impl, A, B, M)
    assert b > 0, f"a random B of full rank has β > 0, got {b}"
    b3 = beta(impl, A, 3 * B, M)
    assert abs(b3 - 3 * b) < 1e-9 * b, (
        f"β is linear in B: with 3B it must be 3 × {b:.6g} = {3 * b:.6g}, got {b3:.6g}"
        + (": you return β², not β" if abs(b3 - 9 * b) < 1e-9 * b else ""))
    b4 = beta(impl, 4 * A, B, M)
    assert abs(b4 - b / 2) < 1e-9 * b, (
        f"‖v‖_A doubles when A is multiplied by 4, so β halves: {b / 2:.6g}, got {b4:.6g} "
        f"(β² solves B A⁻¹ Bᵀ x = β² M x)")
    bm = beta(impl, A, B, 4 * M)
    assert abs(bm - b / 2) < 1e-9 * b, (
        f"‖μ‖_M doubles when M is multiplied by 4, so β halves: {b / 2:.6g}, got {bm:.6g}; "
        f"β measures μ in the norm of the multipliers, M")
    bs = beta(impl, sp.csr_matrix(A), sp.csr_matrix(B), sp.csr_matrix(M))
    assert abs(bs - b) < 1e-9 * b, "inf_sup_constant must accept scipy sparse matrices too"


def test_04_unseen_multipliers(impl):
    B = np.array([[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 1.0]])
    Z = np.asarray(impl.unseen_multipliers(B), dtype=float)
    assert Z.shape == (3, 1), (
        f"multipliers 0 and 1 see the same jump (equal rows of B): one combination, "
        f"μ = (1, -1, 0)/√2, is unseen; expected shape (3, 1), got {Z.shape}")
    assert np.allclose(B.T @ Z, 0, atol=1e-12), "an unseen multiplier μ has Bᵀμ = 0"
    assert np.allclose(Z.T @ Z, np.eye(1), atol=1e-12), "the columns must be orthonormal"
    assert np.asarray(impl.unseen_multipliers(B0)).shape == (2, 0), (
        "B = [[1, 0, 0], [0, 2, 0]] has full row rank: no unseen multiplier, shape (2, 0)")


def test_05_an_unseen_multiplier_makes_beta_zero(impl):
    B = np.array([[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    got = beta(impl, np.eye(3), B, np.eye(2))
    assert abs(got) < 1e-6, (
        f"μ = (1, -1) has Bᵀμ = 0: a multiplier that no displacement feels, so sup_v μᵀBv = 0 "
        f"and β = 0; got {got:.6g}. Do not skip the zero eigenvalues: they are the instability")


def saddle_matrices(space):
    """A, B_r, M of skxfem.lbb.inf_sup on 3³ tetrahedra cut by a tilted plane."""
    scene = Scene(Box(3, "tet"), plane((0.5, 0.5, 0.52), (0.1, 0.2, 1.0)),
                  displacements=(clamped("zmin"),), space=space)
    captured = {}

    def capture(A, B, M, **kwargs):
        captured.update(A=A, B=B, M=M)
        return original(A, B, M, **kwargs)

    original = skxfem.lbb.inf_sup_constant
    skxfem.lbb.inf_sup_constant = capture
    try:
        result = skxfem.lbb.inf_sup(scene)
    finally:
        skxfem.lbb.inf_sup_constant = original
    c = cut(resolve_mesh(scene), scene.levelset)
    return captured, result, c


@pytest.mark.points(2)
def test_06_why_the_naive_space_loses_it(impl):
    mats, result, c = saddle_matrices("naive")
    n_edges, n_nodes = c.edges.shape[1], np.unique(c.edges).size
    Z = np.asarray(impl.unseen_multipliers(mats["B"]))
    assert Z.shape[1] >= n_edges - n_nodes > 0, (
        f"3³ tetrahedra cut by a plane: {n_edges} cut edges (one naive multiplier each) but "
        f"the jump lives on {n_nodes} nodes, so at least {n_edges - n_nodes} multipliers are "
        f"unseen; unseen_multipliers found {Z.shape[1]}")
    got = beta(impl, mats["A"], mats["B"], mats["M"])
    assert abs(got) < 1e-6, (
        f"the naive space on tetrahedra has {Z.shape[1]} multipliers that no displacement feels: "
        f"β = 0, got {got:.3g}")


def test_07_the_vital_space_keeps_it(impl):
    mats, result, _ = saddle_matrices("vital")
    assert np.asarray(impl.unseen_multipliers(mats["B"])).shape[1] == 0, (
        "the vital-edge space (exercise 06) keeps no unseen multiplier")
    got = beta(impl, mats["A"], mats["B"], mats["M"])
    assert abs(got - result.beta) < 1e-8, (
        f"β of the vital space on 3³ tetrahedra is {result.beta:.6g} (skxfem.lbb), got {got:.6g}")
