"""The block scaling of enriched nodes (skxfem.linalg.blocks) and the iterative solve of
a crack scene it serves (skxfem.solver): the scaled blocks are the identity, the change
of unknowns is exact, and AMG + CG reaches the direct answer on a 3D and a 2D crack."""
import numpy as np
import pytest
import scipy.sparse as sp
from skfem import MeshTet1

from skxfem.fem.material import Material
from skxfem.levelset import LevelSet, plane
from skxfem.linalg import iterative
from skxfem.linalg.amg import rigid_modes
from skxfem.linalg.blocks import congruence, enriched_scaling, node_blocks
from skxfem.problem import assemble
from skxfem.scene import Displacement, Interface, Scene, SurfaceLoad
from skxfem.solver import solve
from skxfem.studies.cracks import MATERIAL, straight_crack, unit_square

pytest.importorskip("pyamg")


def crack_3d(n=6):
    """The edge crack {z = 0.5, x < 0.5} of benchmarks/crack_solve.py, cube pulled at z = 1."""
    m = n | 1
    mesh = MeshTet1.init_tensor(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1),
                                np.linspace(0, 1, m + 1))
    crack = Interface(plane((0.5, 0.5, 0.5), (0.0, 0.0, 1.0)), law="free",
                      front=plane((0.5, 0.0, 0.0), (1.0, 0.0, 0.0)))
    return Scene(mesh, material=Material(1.0, 0.3), interfaces=(crack,),
                 displacements=(Displacement("zmin", {"x": 0.0, "y": 0.0, "z": 0.0}),),
                 loads=(SurfaceLoad("zmax", traction=(0.0, 0.0, 1.0)),))


def crack_2d(n=12):
    """A 2D edge crack to the square's centre, clamped below and pulled above."""
    psi, phi, _ = straight_crack(np.array([0.5, 0.5]), 0.0)
    crack = Interface(LevelSet(psi, 2, "psi"), law="free", front=LevelSet(phi, 2, "phi"))
    return Scene(unit_square(n, "tri"), material=MATERIAL, interfaces=(crack,),
                 displacements=(Displacement("ymin", {"x": 0.0, "y": 0.0}),),
                 loads=(SurfaceLoad("ymax", traction=(0.0, 1.0)),))


def test_node_blocks_group_a_node_s_standard_and_enriched_unknowns():
    # node 0 (dofs 0, 1) has 2 enriched unknowns, node 2 (dofs 4, 5) has 4
    blocks = node_blocks(np.array([4, 0, 5, 1, 4, 5]), 6, 2)
    assert [b.tolist() for b in blocks] == [[[0, 1, 7, 9]], [[4, 5, 6, 8, 10, 11]]]


@pytest.mark.parametrize("kwargs, words", [
    (dict(enr_dofs=np.array([6]), n_std=6, dim=2), "enr_dofs"),
    (dict(enr_dofs=np.array([0]), n_std=5, dim=2), "dim"),
])
def test_bad_blocks_are_refused_naming_the_argument(kwargs, words):
    with pytest.raises(ValueError, match=words):
        node_blocks(**kwargs)


def test_scaled_blocks_are_the_identity_and_fixed_blocks_are_left():
    rng = np.random.default_rng(0)
    A = rng.normal(size=(10, 10))
    K = sp.csr_matrix(A @ A.T + 10 * np.eye(10))
    enr = np.array([0, 1, 0, 1, 2, 3])                   # nodes 0 and 1 (dim 2), n_std 4
    S, Sinv = enriched_scaling(K, enr, 4, 2)
    Ks = (S.T @ K @ S).toarray()
    for b in node_blocks(enr, 4, 2):
        for block in b:
            assert np.allclose(Ks[np.ix_(block, block)], np.eye(block.size))
    assert np.allclose((S @ Sinv).toarray(), np.eye(10))
    S, _ = enriched_scaling(K, enr, 4, 2, fixed=np.array([2]))   # node 1's block holds 2
    assert np.allclose(S.toarray()[np.ix_([2, 3, 8, 9], [2, 3, 8, 9])], np.eye(4))
    with pytest.raises(ValueError, match="positive definite"):
        enriched_scaling(sp.csr_matrix(np.diag([1.0, 0.0, 1.0])), np.array([0]), 1, 1)


def test_block_scaling_is_what_makes_cg_converge_on_a_3d_crack():
    """Jacobi alone needs several times the iterations (123 against 33 measured with
    an enriched zone of 0.1 diameters; with the default's floor of 4 front cells plain CG
    does not reach 1e-10 in 500 iterations)."""
    p = assemble(crack_3d())
    modes = rigid_modes(p.V)
    S, Sinv = enriched_scaling(p.K, p.V.enr_dofs, p.V.n_std, 3, p.D)
    _, _, scaled = iterative.solve((S.T @ p.K @ S).tocsr(), p.B @ S, S.T @ p.F, p.D, p.g,
                                   modes=Sinv @ modes, blocksize=3)
    budget = 2 * scaled.iterations
    with pytest.raises(iterative.ConvergenceError):
        iterative.solve(p.K, p.B, p.F, p.D, p.g, modes=modes, blocksize=3, maxiter=budget)


@pytest.mark.parametrize("scene", [crack_3d, crack_2d])
def test_the_iterative_solve_of_a_crack_reaches_the_direct_answer(scene):
    direct = solve(scene(), linear="direct")
    it = solve(scene(), linear="iterative", linear_tol=1e-10)
    assert it.linear_info["iterations"] is not None and it.linear_info["residual"] < 1e-10
    assert np.abs(it.U - direct.U).max() < 1e-8 * np.abs(direct.U).max()
    for a, b in zip(it.front, direct.front):
        assert np.allclose(a["K_I"], b["K_I"], rtol=1e-7)


@pytest.mark.parametrize("blocksize", [1, 2, 3])
def test_congruence_is_st_k_s_by_blocks(blocksize):
    p = assemble(crack_3d(4))
    S, _ = enriched_scaling(p.K, p.V.enr_dofs, p.V.n_std, 3, p.D)
    want = (S.T @ p.K @ S).tocsr()
    got = congruence(p.K, S, blocksize)
    assert got.format == "csr" and got.has_sorted_indices and got.nnz == want.nnz
    # two orders of the same sums: a few units in the last place (1.01e-14 measured)
    assert abs(got - want).max() <= 4e-14 * abs(want).max()
    with pytest.raises(ValueError, match="blocksize"):
        congruence(p.K, S, p.K.shape[0] + 1)
