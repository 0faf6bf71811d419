"""Tests for skxfem/linalg/iterative.py (and skxfem/linalg/dependent.py): the AMG-preconditioned
projected CG solve of the tied saddle system gives the direct solve's answer.

1. ``rigid_modes``: each side's rigid motion has zero energy, vanishes on the
   other side, and the pair sums to the rigid motion of the body (b = 0).
2. On small scenes of every cell type, multiplier space and tie law,
   ``iterative.solve`` returns the U and the edge tractions λ = Pμ (hence the
   pressure) of ``saddle.solve`` to 1e-8 relative, including the naive spaces
   whose multipliers are dependent (the direct path removes some: checked).
3. ``smoothest`` picks the multipliers ``saddle.smoothest_multipliers`` picks,
   by a dense eigensolve for a few multipliers and by Lanczos for many, and
   ``dependencies`` finds as many as the direct path removes.
4. Refusals: an iteration limit too small raises ConvergenceError (a
   ValueError) reporting iterations and residual; a side that can slide
   raises SingularSystemError; a missing pyamg names ``pip install pyamg``.
"""
import dataclasses
import importlib

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import eigsh

from skxfem.enrich import split_fields
from skxfem.linalg import iterative, saddle
from skxfem.linalg.amg import rigid_modes
from skxfem.linalg.dependent import dependencies, smoothest
from skxfem.problem import assemble
from skxfem.scene import Displacement
from skxfem.scene.benchmarks import exact_plate, exact_strip, paper_plate
from skxfem.solver import _differences

CELLS = ["tri", "quad", "tet", "hex", "prism"]
SPACES = ["naive", "winner", "vital"]


def at(*coords):
    return lambda x: np.all([np.abs(x[i] - c) < 1e-12 for i, c in enumerate(coords)], axis=0)


def scene(cell, space, law="bonded", held=True):
    """The exact strip (2D, 6 cells across) or plate (3D, 3 x 3 cells, one along x).

    A frictionless tie lets the upper part slide: ``held`` adds the tangential
    supports of the top face that the patch tests use."""
    if cell in ("tri", "quad"):
        s = exact_strip(6, cell, space=space)
    else:
        s = exact_plate(3, "hex" if cell == "tet" else cell, nx=1, space=space)
        s = dataclasses.replace(s, mesh=dataclasses.replace(s.mesh, cell=cell))
    s = dataclasses.replace(s, law=law)
    if law == "bilateral" and held:
        top = (Displacement(at(0.0, 1.0), {"x": 0.0}),) if s.dim == 2 else (
            Displacement(at(0.0, 0.0, 1.0), {"x": 0.0, "y": 0.0}),
            Displacement(at(0.0, 1.0, 1.0), {"y": 0.0}))
        s = dataclasses.replace(s, displacements=s.displacements + top)
    return s


def both(problem, **kw):
    """The direct and the iterative solve of one problem."""
    p = problem
    G = _differences(p.cut, p.ncomp) @ p.P
    direct = saddle.solve(p.K, p.B, p.F, p.D, p.g, G=G)
    it = iterative.solve(p.K, p.B, p.F, p.D, p.g, G=G, modes=rigid_modes(p.V),
                         blocksize=p.mesh.dim(), bonded=p.law == "bonded", **kw)
    return direct, it


# 1. rigid modes ------------------------------------------------------------------

@pytest.mark.parametrize("cell", ["tri", "hex"])
def test_rigid_modes_move_one_side_and_cost_no_energy(cell):
    p = assemble(scene(cell, "vital"))
    Z = rigid_modes(p.V)
    k = 3 if cell == "tri" else 6
    assert Z.shape == (p.V.N, 2 * k)
    assert np.abs(p.K @ Z).max() < 1e-12 * np.abs(p.K).max() * np.abs(Z).max(), \
        "a rigid motion of one side must have zero energy (K Z = 0)"
    enriched = np.zeros(p.mesh.p.shape[1], dtype=bool)
    enriched[np.isin(p.V.basis.nodal_dofs[0], p.V.enr_dofs)] = True
    side_of = np.sign(p.cut.psi)
    for j, side in enumerate((-1, 1)):
        u_minus, u_plus = split_fields(p.V, Z[:, j])  # translation along x of one side
        moved, still = (u_minus, u_plus) if side < 0 else (u_plus, u_minus)
        mine = (side_of == side) | enriched  # the nodes whose field on this side is defined
        other = (side_of == -side) | enriched
        assert np.allclose(moved[0, mine], 1.0) and np.allclose(moved[1:, mine], 0.0)
        assert np.abs(still[:, other]).max() == 0.0, "the other side must stay at rest"
    body = rigid_modes(p.V, sides=False)
    assert body.shape == (p.V.N, k)
    assert np.abs(body[p.V.n_std:]).max() == 0.0, "a rigid motion of the body has no jump"


# 2. the direct path's answer ---------------------------------------------------------

@pytest.mark.parametrize("law", ["bonded", "bilateral"])
@pytest.mark.parametrize("space", SPACES)
@pytest.mark.parametrize("cell", CELLS)
def test_iterative_solve_gives_the_direct_answer(cell, space, law):
    p = assemble(scene(cell, space, law))
    (Ud, mud, _), (U, mu, info) = both(p, tol=1e-12)
    assert info.residual <= 1e-12 and info.iterations > 0
    assert np.linalg.norm(U - Ud) <= 1e-8 * np.linalg.norm(Ud), "U differs from the direct U"
    lam, lam_d = p.P @ mu, p.P @ mud
    assert np.linalg.norm(lam - lam_d) <= 1e-8 * np.linalg.norm(lam_d), \
        "the edge tractions (and so the pressure) differ from the direct ones"
    assert info.balance < 1e-10


@pytest.mark.parametrize("cell", ["tet"])
def test_dependent_naive_multipliers_are_covered(cell):
    """The naive space leaves dependent multipliers on tetrahedra (the direct path
    removes them), so the comparison above covers a singular saddle system.  (On
    the hexahedral and prism plates the only dependent ones were the x-tractions
    on the roller faces, which the support-aware spaces no longer create.)"""
    p = assemble(scene(cell, "naive"))
    (Ud, _, info_d), (U, _, info) = both(p)
    assert info_d.removed > 0
    assert info.removed == info_d.removed, "both paths find the same dependencies"
    assert np.linalg.norm(U - Ud) <= 1e-8 * np.linalg.norm(Ud)


# 3. the smoothest multipliers ----------------------------------------------------

def test_smoothest_matches_the_dense_choice():
    rng = np.random.default_rng(3)
    m, n = 12, 9
    B = rng.standard_normal((m, 5)) @ rng.standard_normal((5, n))  # rank 5 < m
    G = sp.csr_matrix(np.eye(m - 1, m) - np.eye(m - 1, m, 1))
    mu0 = rng.standard_normal(m)
    mu = smoothest(sp.csr_matrix(B), mu0, G)
    dense = saddle.smoothest_multipliers(sp.csr_matrix(B), B.T @ mu0, G)
    assert np.allclose(B.T @ mu, B.T @ mu0, atol=1e-12), "μ must still balance"
    assert np.allclose(mu, dense, atol=1e-9)
    least = smoothest(sp.csr_matrix(B), mu0)
    assert np.allclose(least, np.linalg.pinv(B.T) @ (B.T @ mu0), atol=1e-9), \
        "without G: the least-norm multipliers"


def test_smoothest_by_lanczos_matches_the_direct_choice():
    """Above 200 multipliers the dependencies come from shift-invert Lanczos:
    the naive tetrahedral plate has many (247 multipliers, 109 dependent)."""
    p = assemble(paper_plate(6, "tet", space="naive", nx=3))
    free = np.setdiff1d(np.arange(p.V.N), p.D)
    G = _differences(p.cut, p.ncomp) @ p.P
    _, mu_d, info = saddle.solve(p.K, p.B, p.F, p.D, p.g, G=G)
    assert p.B.shape[0] > 200 and info.removed > 0
    N = dependencies(p.B[:, free])
    assert N.shape[1] == info.removed, "as many dependencies as the direct path removes"
    # B^T N = 0 to the accuracy the iterative path counts a dependency with (its
    # dependent_tol, 1e-8 of the largest singular value of B; Lanczos on B B^T resolves
    # about that much: |B^T N| was 5e-9 to 1.25e-8 of max|B| over random starts)
    sigma = np.sqrt(eigsh(p.B[:, free] @ p.B[:, free].T, k=1, return_eigenvectors=False)[0])
    assert np.linalg.norm(p.B[:, free].T @ N, axis=0).max() < 1e-8 * sigma
    noisy = mu_d + N @ np.random.default_rng(0).standard_normal(N.shape[1])
    mu = smoothest(p.B[:, free], noisy, G)
    assert np.linalg.norm(mu - mu_d) <= 1e-8 * np.linalg.norm(mu_d)


@pytest.mark.parametrize("cell", ["quad", "prism"])
def test_a_setup_is_reused_for_the_same_operator_only(cell, monkeypatch):
    """solve(..., reuse=info.setup): the same K, B and imposed unknowns take the earlier
    set-up (no second AMG), with another load the answer of a fresh solve; another B
    builds its own."""
    p = assemble(scene(cell, "vital"))
    G = _differences(p.cut, p.ncomp) @ p.P
    kw = dict(G=G, modes=rigid_modes(p.V), blocksize=p.mesh.dim(), bonded=True)
    built, real = [], iterative._setup
    monkeypatch.setattr(iterative, "_setup", lambda *a: built.append(1) or real(*a))
    _, _, first = iterative.solve(p.K, p.B, p.F, p.D, p.g, **kw)
    U2, mu2, again = iterative.solve(p.K, p.B, 2 * p.F, p.D, p.g, reuse=first.setup, **kw)
    assert len(built) == 1 and again.setup is first.setup
    U, mu, fresh = iterative.solve(p.K, p.B, 2 * p.F, p.D, p.g, **kw)
    assert len(built) == 2 and fresh.setup is not first.setup
    assert np.abs(U2 - U).max() <= 1e-9 * np.abs(U).max()
    assert np.abs(mu2 - mu).max() <= 1e-8 * np.abs(mu).max()
    other = iterative.solve(p.K, p.B[1:], p.F, p.D, p.g, reuse=first.setup,
                            **{**kw, "G": None})[2]
    assert len(built) == 3 and other.setup is not first.setup


# 4. refusals ------------------------------------------------------------------------

def test_too_few_iterations_raise_a_clear_error():
    p = assemble(scene("hex", "vital"))
    with pytest.raises(iterative.ConvergenceError, match="maxiter") as err:
        both(p, maxiter=2)
    assert isinstance(err.value, ValueError)
    assert err.value.iterations == 2 and err.value.residual > 1e-10


@pytest.mark.parametrize("cell", ["quad", "prism"])
def test_a_sliding_side_is_refused(cell):
    p = assemble(scene(cell, "vital", "bilateral", held=False))
    with pytest.raises(saddle.SingularSystemError, match="slide"):
        iterative.solve(p.K, p.B, p.F, p.D, p.g, modes=rigid_modes(p.V),
                        blocksize=p.mesh.dim())


def test_missing_pyamg_names_the_install(monkeypatch):
    real = importlib.import_module

    def no_pyamg(name, *args):
        if name == "pyamg":
            raise ImportError("No module named 'pyamg'")
        return real(name, *args)

    monkeypatch.setattr(importlib, "import_module", no_pyamg)
    p = assemble(scene("tri", "vital"))
    with pytest.raises(ImportError, match="pip install pyamg"):
        iterative.solve(p.K, p.B, p.F, p.D, p.g)


def test_an_iterative_solve_is_reproducible_to_the_last_bit():
    """pyamg draws random start vectors (np.random) to estimate the smoothers' spectral
    radii; with the seed fixed (amg.AMG_SEED) two solves of one system agree bit for bit
    (before, the naive prism block's pressure moved by 2e-11 between runs of
    summary.json), and the caller's random numbers are not disturbed."""
    p = assemble(scene("prism", "naive"))
    K, B, F = p.K, p.B, p.F
    np.random.seed(123)
    expected_next = np.random.rand()
    np.random.seed(123)
    runs = []
    for _ in range(2):
        np.random.rand(7)  # a different global state before each solve
        runs.append(iterative.solve(K, B, F, p.D, p.g, tol=1e-12)[:2])
    assert np.array_equal(runs[0][0], runs[1][0]) and np.array_equal(runs[0][1], runs[1][1])
    np.random.seed(123)
    iterative.solve(K, B, F, p.D, p.g, tol=1e-12)
    assert np.random.rand() == expected_next


def _laplace_1d(N=4000):
    """A tie of the two ends of a 1D Laplacian (κ ~ N²) loaded by K x, x a sine."""
    K = sp.diags([-np.ones(N - 1), 2 * np.ones(N), -np.ones(N - 1)], [-1, 0, 1]).tocsr() * N
    x = np.sin(np.pi * np.arange(1, N + 1) / (N + 1))
    B = sp.csr_matrix(np.r_[1.0, np.zeros(N - 2), -1.0][None, :])
    return K, B, x


@pytest.mark.parametrize("tol", [1e-12, 1e-15])
def test_rounding_floor_is_accepted_by_its_backward_error(tol):
    """κ ~ 10⁷: rounding holds the relative residual near 2.6e-10 whatever the
    iterations; the answer is exact to rounding (its backward error below tol), so it
    is taken after the restarts stall (it raised after 500 iterations before)."""
    from skxfem.linalg.iterative import backward_error

    K, B, x = _laplace_1d()
    U, mu, info = iterative.solve(K, B, K @ x, tol=tol)
    assert info.residual > 1e-11 and info.iterations < 100 and info.backward_error <= tol
    assert np.abs(U - x).max() < 1e-12
    assert backward_error(K, U, np.linalg.norm(K @ U - K @ x), np.linalg.norm(K @ x)) < 1e-14


def test_an_unconverged_solve_still_raises():
    """The backward error does not excuse a solve cut short by maxiter."""
    K, B, x = _laplace_1d()
    with pytest.raises(iterative.ConvergenceError, match="within 5 iterations"):
        iterative.solve(K, B, K @ x, maxiter=5)


def test_a_stiffness_contrast_solves_to_the_direct_answer():
    """Ω⁺ 300 times stiffer than Ω⁻ (the paper's plate, hexahedra n = 12): rounding
    holds the residual at 1.6e-12, above the default 1e-12, with either smoother (it
    raised after 500 iterations); accepted by its backward error, U as the direct's."""
    import skxfem
    from skxfem.fem.material import Material
    from skxfem.scene.benchmarks import paper_plate

    s = dataclasses.replace(paper_plate(12, "hex"),
                            material_plus=Material(300.0, 0.3, plane="strain"))
    r, d = skxfem.solve(s, linear="iterative"), skxfem.solve(s, linear="direct")
    assert r.linear_info["iterations"] < 500 and r.linear_info["backward_error"] <= 1e-12
    assert np.abs(r.U - d.U).max() < 1e-10 * np.abs(d.U).max()
    assert np.abs(r.traction - d.traction).max() < 1e-10 * np.abs(d.traction).max()
