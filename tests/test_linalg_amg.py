"""The AMG preconditioner of the iterative solve (skxfem.linalg.amg): the V-cycle that
CG applies, the crack's Chebyshev smoother, and the hierarchy carried over by refresh."""
import numpy as np
import pytest
import scipy.sparse as sp

from skxfem.linalg import iterative
from skxfem.linalg.amg import (
    CRACK_SMOOTHER,
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


@pytest.mark.parametrize("smoother", [SMOOTHER, CRACK_SMOOTHER])
def test_vcycle_is_pyamg_s_preconditioner_to_the_last_bit(smoother):
    Ks, Z, _ = scaled_crack()
    ml = amg(Ks, Z, 3, smoother)
    rng = np.random.default_rng(1)
    for _ in range(3):
        r = rng.normal(size=Ks.shape[0])
        assert np.array_equal(vcycle(ml) @ r, ml.aspreconditioner(cycle="V") @ r)


def test_the_crack_s_preconditioner_is_symmetric_positive_definite():
    """CG needs M SPD: the Chebyshev pre- and post-smoothers are the same polynomial, so
    the V-cycle is symmetric; on the free unknowns it is positive definite."""
    Ks, Z, fixed = scaled_crack()
    M = vcycle(amg(Ks, Z, 3, CRACK_SMOOTHER))
    free = np.flatnonzero(~fixed)
    I = np.eye(Ks.shape[0])[:, free]
    Mf = np.column_stack([M @ e for e in I.T])[free]
    assert np.abs(Mf - Mf.T).max() < 1e-10 * np.abs(Mf).max()
    assert np.linalg.eigvalsh(0.5 * (Mf + Mf.T)).min() > 0


def test_the_crack_smoother_is_kept_by_a_refreshed_hierarchy():
    Ks, Z, _ = scaled_crack()
    ml = amg(Ks, Z, 3, CRACK_SMOOTHER)
    A = (Ks + sp.diags(np.r_[1.0, np.zeros(Ks.shape[0] - 1)])).tocsr()
    new = refresh(ml, A)
    assert new.skxfem_smoother == CRACK_SMOOTHER
    fresh = amg(A, Z, 3, CRACK_SMOOTHER)
    r = np.random.default_rng(2).normal(size=A.shape[0])
    # the same aggregates and Galerkin coarse operators for a change on one row: the
    # carried hierarchy is a preconditioner as good as a new one's
    carried = projected_cg(A, vcycle(new), lambda v: v, r, np.zeros_like(r),
                           1e-10 * np.linalg.norm(r), 200)[1]
    anew = projected_cg(A, vcycle(fresh), lambda v: v, r, np.zeros_like(r),
                        1e-10 * np.linalg.norm(r), 200)[1]
    assert carried[-1] <= 1e-10 * np.linalg.norm(r) and len(carried) <= len(anew) + 3


def test_the_solver_gives_a_crack_the_crack_smoother_and_a_tie_the_default(monkeypatch):
    seen = []
    real = iterative.solve

    def spy(*args, **kwargs):
        seen.append(kwargs["smoother"])
        return real(*args, **kwargs)
    monkeypatch.setattr(iterative, "solve", spy)
    solve(crack_2d(6), linear="iterative")
    assert seen == [CRACK_SMOOTHER]
    solve(paper_plate(3), linear="iterative")
    assert seen[-1] == SMOOTHER
