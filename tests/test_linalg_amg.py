"""The AMG preconditioner of the iterative solve (skxfem.linalg.amg): the V-cycle that
CG applies, its Chebyshev smoother (Gauss-Seidel for the hierarchy a contact solve
carries over), and the hierarchy carried over by refresh."""
import numpy as np
import pytest
import scipy.sparse as sp

from skxfem.linalg import iterative
from skxfem.linalg.amg import (
    CARRIED_SMOOTHER,
    SMOOTHER,
    amg,
    refresh,
    rigid_modes,
    scaled_tie,
    vcycle,
)
from skxfem.linalg.blocks import enriched_scaling
from skxfem.linalg.pcg import projected_cg
from skxfem.problem import assemble
from skxfem.scene.benchmarks import paper_plate
from skxfem.solver import solve
from tests.test_linalg_blocks import crack_2d, crack_3d

pytest.importorskip("pyamg")


def scaled_crack(n=4):
    """The block- and Jacobi-scaled K of a small 3D crack, its near-null space and its
    imposed unknowns, as :func:`skxfem.solver.solve_problem` hands them to the AMG."""
    p = assemble(crack_3d(n))
    S, Sinv = enriched_scaling(p.K, p.V.enr_dofs, p.V.n_std, 3, p.D)
    K = (S.T @ p.K @ S).tocsr()
    fixed = np.zeros(K.shape[0], dtype=bool)
    fixed[p.D] = True
    s, Ks, _, _ = scaled_tie(K, sp.csr_matrix((0, K.shape[0])), fixed)
    return Ks, (Sinv @ rigid_modes(p.V)) / s[:, None], fixed


@pytest.mark.parametrize("smoother", [SMOOTHER, CARRIED_SMOOTHER])
def test_vcycle_is_pyamg_s_preconditioner_to_the_last_bit(smoother):
    Ks, Z, _ = scaled_crack()
    ml = amg(Ks, Z, 3, smoother)
    rng = np.random.default_rng(1)
    for _ in range(3):
        r = rng.normal(size=Ks.shape[0])
        assert np.array_equal(vcycle(ml) @ r, ml.aspreconditioner(cycle="V") @ r)


def test_the_chebyshev_preconditioner_is_symmetric_positive_definite():
    """CG needs M SPD: the Chebyshev pre- and post-smoothers are the same polynomial, so
    the V-cycle is symmetric; on the free unknowns it is positive definite."""
    Ks, Z, fixed = scaled_crack()
    M = vcycle(amg(Ks, Z, 3))
    free = np.flatnonzero(~fixed)
    I = np.eye(Ks.shape[0])[:, free]
    Mf = np.column_stack([M @ e for e in I.T])[free]
    assert np.abs(Mf - Mf.T).max() < 1e-10 * np.abs(Mf).max()
    assert np.linalg.eigvalsh(0.5 * (Mf + Mf.T)).min() > 0


@pytest.mark.parametrize("smoother", [SMOOTHER, CARRIED_SMOOTHER])
def test_the_smoother_is_kept_by_a_refreshed_hierarchy(smoother):
    Ks, Z, _ = scaled_crack()
    ml = amg(Ks, Z, 3, smoother)
    A = (Ks + sp.diags(np.r_[1.0, np.zeros(Ks.shape[0] - 1)])).tocsr()
    new = refresh(ml, A)
    assert new.skxfem_smoother == smoother
    fresh = amg(A, Z, 3, smoother)
    r = np.random.default_rng(2).normal(size=A.shape[0])
    # the same aggregates and Galerkin coarse operators for a change on one row: the
    # carried hierarchy is a preconditioner as good as a new one's
    carried = projected_cg(A, vcycle(new), lambda v: v, r, np.zeros_like(r),
                           1e-10 * np.linalg.norm(r), 200)[1]
    anew = projected_cg(A, vcycle(fresh), lambda v: v, r, np.zeros_like(r),
                        1e-10 * np.linalg.norm(r), 200)[1]
    assert carried[-1] <= 1e-10 * np.linalg.norm(r) and len(carried) <= len(anew) + 3


def test_ties_and_cracks_are_smoothed_by_chebyshev_a_contact_by_gauss_seidel(monkeypatch):
    """Every hierarchy built for one operator (a tie, a crack) takes SMOOTHER; the one
    a contact solve carries over its Newton steps CARRIED_SMOOTHER, and so does every
    step's refreshed hierarchy.  A Chebyshev smoother keeps the finest level in CSR."""
    from skxfem import contact
    from skxfem.scene.benchmarks import slipping_block

    built, refreshed = [], []
    real_amg, real_refresh = iterative.amg, iterative.refresh
    monkeypatch.setattr(iterative, "amg", lambda *a: built.append(real_amg(*a)) or built[-1])
    monkeypatch.setattr(iterative, "refresh",
                        lambda *a: refreshed.append(real_refresh(*a)) or refreshed[-1])
    solve(crack_2d(6), linear="iterative")
    solve(paper_plate(3), linear="iterative")
    assert [ml.skxfem_smoother for ml in built] == [SMOOTHER, SMOOTHER]
    assert SMOOTHER[0] == "chebyshev"
    assert CARRIED_SMOOTHER[0] == "block_gauss_seidel"
    assert all(ml.levels[0].A.format == "csr" for ml in built)
    built.clear()
    contact.solve(slipping_block(3, law="frictionless"), linear="iterative")
    assert [ml.skxfem_smoother for ml in built] == [CARRIED_SMOOTHER] and refreshed
    assert all(ml.skxfem_smoother == CARRIED_SMOOTHER for ml in refreshed)
    assert all(ml.levels[0].A.format == "bsr" for ml in built + refreshed)
