"""Tests for skxfem/linalg/saddle.py: the saddle-point solve K U - Bᵀμ = F, B U = 0, U[D] = g.

What is checked, on small systems whose answer a dense solve gives:

1. ``independent_rows`` finds exactly rank(B) rows, and they are independent.
2. With an SPD K and a full-rank B, ``solve`` returns the U and μ of a dense
   solve of the KKT system [[K, Bᵀ], [B, 0]] [U; -μ] = [F; 0].
3. Dependent rows of B are removed (``info.removed`` is their known number),
   U is unchanged and μ still balances it: Bᵀμ = K U - F.
4. Dirichlet values are imposed exactly, also when a row of B only touches
   imposed unknowns (that row is dependent and removed).
5. With the neighbour differences G, a constant multiplier that balances the
   system is recovered exactly; without G it is not (so G matters).
6. A floating body (K singular, no constraint removing the rigid motion) is
   refused with a SingularSystemError, a ValueError, as documented.
7. Nearly dependent rows (σ_min/σ_max between the QR's 1e-10 and the
   recovery's 1e-6): a balancing constant is still recovered; a reaction
   along the weak combination is refused with a NearlyDependentError.
"""
import numpy as np
import pytest
import scipy.sparse as sp
from skfem import Basis, ElementVector

from skxfem.fem.material import Material, stiffness_form
from skxfem.fem.meshes import box
from skxfem.linalg.saddle import SingularSystemError, independent_rows, solve


def spd(n, rng):
    A = rng.standard_normal((n, n))
    return sp.csr_matrix(A @ A.T + n * np.eye(n))


def full_rank(m, n, rng):
    return sp.csr_matrix(rng.standard_normal((m, n)))


def dense_kkt(K, B, F, D=(), g=()):
    """U and μ from a dense solve of the KKT system on the free unknowns."""
    K, B = K.toarray(), B.toarray()
    N, m = K.shape[0], B.shape[0]
    D = np.asarray(D, int)
    free = np.setdiff1d(np.arange(N), D)
    U = np.zeros(N)
    U[D] = g
    A = np.block([[K[np.ix_(free, free)], B[:, free].T], [B[:, free], np.zeros((m, m))]])
    rhs = np.concatenate([(F - K @ U)[free], -B @ U])
    x = np.linalg.solve(A, rhs)
    U[free] = x[:free.size]
    return U, -x[free.size:]


# 1. independent rows ------------------------------------------------------------

@pytest.mark.parametrize("rank", [1, 2, 3, 5])
def test_independent_rows_finds_the_rank(rank):
    rng = np.random.default_rng(rank)
    B = rng.standard_normal((7, rank)) @ rng.standard_normal((rank, 12))
    B[:, [2, 9]] = 0.0  # zero columns do not enter the factorisation
    rows = independent_rows(sp.csr_matrix(B))
    assert rows.size == rank, f"B has rank {rank}, but {rows.size} rows were kept"
    assert np.all(np.diff(rows) > 0), "the row indices must be sorted and distinct"
    assert np.linalg.matrix_rank(B[rows]) == rank, "the kept rows must be independent"


def test_independent_rows_of_simple_matrices():
    assert independent_rows(sp.identity(4, format="csr")).tolist() == [0, 1, 2, 3]
    assert independent_rows(sp.csr_matrix((3, 5))).size == 0, "a zero B has no independent row"
    B = sp.csr_matrix([[1.0, -1.0, 0.0], [0.0, 0.0, 0.0], [2.0, -2.0, 0.0], [0.0, 1.0, 1.0]])
    rows = independent_rows(B)
    assert rows.size == 2 and 3 in rows and 1 not in rows, \
        f"rows 0 and 2 are parallel and row 1 is zero: expected 2 rows incl. 3, got {rows}"


# 2. agreement with a dense KKT solve ------------------------------------------------

def test_solve_matches_a_dense_kkt_solve():
    rng = np.random.default_rng(0)
    K, B, F = spd(9, rng), full_rank(3, 9, rng), rng.standard_normal(9)
    U, mu, info = solve(K, B, F)
    U0, mu0 = dense_kkt(K, B, F)
    assert info.removed == 0, "a full-rank B has no dependent row"
    assert info.residual < 1e-12
    assert np.abs(U - U0).max() < 1e-12 * np.abs(U0).max(), "U differs from the dense solve"
    assert np.abs(mu - mu0).max() < 1e-10 * np.abs(mu0).max(), "μ differs from the dense solve"
    assert np.abs(B @ U).max() < 1e-12, "the constraint B U = 0 must hold"
    # the same μ comes back through the smoothest-multiplier recovery: B has full rank
    G = sp.diags([-np.ones(2), np.ones(2)], [0, 1], shape=(2, 3))
    _, mu_G, _ = solve(K, B, F, G=G)
    assert np.abs(mu_G - mu0).max() < 1e-10 * np.abs(mu0).max()


# 3. dependent rows --------------------------------------------------------------------

def test_dependent_rows_are_removed_and_u_is_unchanged():
    rng = np.random.default_rng(1)
    K, B, F = spd(10, rng), full_rank(3, 10, rng), rng.standard_normal(10)
    B2 = sp.vstack([B, B[0] + 2 * B[1], 3 * B[2]], format="csr")  # 2 dependent rows
    U, _, _ = solve(K, B, F)
    U2, mu2, info = solve(K, B2, F)
    assert info.removed == 2, f"2 rows depend on the others, info.removed = {info.removed}"
    assert np.abs(U2 - U).max() < 1e-12 * np.abs(U).max(), \
        "U is unique: removing dependent rows must not change it"
    r = K @ U2 - F
    assert np.abs(B2.T @ mu2 - r).max() < 1e-10 * np.abs(r).max(), \
        "the multipliers must balance U: Bᵀμ = K U - F"


# 4. Dirichlet conditions ---------------------------------------------------------------

def test_dirichlet_values_are_imposed_exactly():
    rng = np.random.default_rng(2)
    K, B, F = spd(10, rng), full_rank(3, 10, rng), rng.standard_normal(10)
    D, g = np.array([0, 4, 7]), np.array([0.3, -1.2, 0.5])
    U, mu, info = solve(K, B, F, D, g)
    assert np.array_equal(U[D], g), f"U[D] = {U[D]} should be exactly g = {g}"
    U0, mu0 = dense_kkt(K, B, F, D, g)
    assert info.removed == 0
    assert np.abs(U - U0).max() < 1e-12 * np.abs(U0).max()
    assert np.abs(mu - mu0).max() < 1e-10 * np.abs(mu0).max()
    assert np.abs(B @ U).max() < 1e-12, "B U = 0 includes the imposed values"


def test_a_row_on_imposed_unknowns_only_is_dependent():
    """A multiplier whose jump the Dirichlet condition already fixes is removed."""
    rng = np.random.default_rng(3)
    K, B, F = spd(8, rng), full_rank(2, 8, rng), rng.standard_normal(8)
    tie = sp.csr_matrix(([1.0, -1.0], ([0, 0], [1, 6])), shape=(1, 8))  # u1 = u6
    D, g = np.array([1, 6]), np.array([0.25, 0.25])  # ... which the values satisfy
    B2 = sp.vstack([B, tie], format="csr")
    U, mu, info = solve(K, B2, F, D, g)
    assert info.removed == 1, "the row acting on imposed unknowns only must be removed"
    assert np.array_equal(U[D], g)
    free = np.setdiff1d(np.arange(8), D)
    assert np.abs((B2.T @ mu - (K @ U - F))[free]).max() < 1e-10, \
        "μ must balance U on the free unknowns"
    U0, _ = dense_kkt(K, B, F, D, g)
    assert np.abs(U - U0).max() < 1e-12 * np.abs(U0).max()


# 5. the smoothest multipliers -----------------------------------------------------------

def test_a_balancing_constant_multiplier_is_recovered_exactly():
    rng = np.random.default_rng(4)
    N = 12
    K = spd(N, rng)
    B3 = full_rank(3, N, rng)
    B = sp.vstack([B3, B3[0] - B3[1] + B3[2]], format="csr")  # 4 rows, rank 3
    # a U0 with B U0 = 0 and a load balanced by a constant μ: K U0 - Bᵀμc = F
    null = np.linalg.svd(B.toarray())[2][3:]
    U0 = null.T @ rng.standard_normal(null.shape[0])
    mu_c = np.full(4, 0.7)
    F = K @ U0 - B.T @ mu_c
    G = sp.diags([-np.ones(3), np.ones(3)], [0, 1], shape=(3, 4))  # neighbour differences
    U, mu, info = solve(K, B, F, G=G)
    assert info.removed == 1
    assert np.abs(U - U0).max() < 1e-12 * np.abs(U0).max()
    assert np.abs(mu - mu_c).max() < 1e-10, (
        f"a constant multiplier that balances U must be recovered exactly "
        f"(Gμ = 0); got {mu}")
    _, mu_raw, _ = solve(K, B, F)
    assert np.abs(mu_raw - mu_c).max() > 0.1, \
        "without G the removed multiplier is zero: the recovery is what makes μ constant"
    assert np.abs(B.T @ (mu_raw - mu_c)).max() < 1e-10, "... though both balance U"


# 6. singular systems ----------------------------------------------------------------------

def elastic_block_stiffness():
    mesh = box(2, "quad")
    basis = Basis(mesh, ElementVector(mesh.elem()))
    return stiffness_form(Material(1.0, 0.3), 2).assemble(basis).tocsr()


def test_a_floating_elastic_body_is_refused():
    """No displacement imposed, no constraint: the rigid motions are free."""
    K = elastic_block_stiffness()
    N = K.shape[0]
    F = np.zeros(N)
    for B in (sp.csr_matrix((0, N)), sp.csr_matrix(([1.0], ([0], [0])), shape=(1, N))):
        with pytest.raises(SingularSystemError, match="singular.*move freely"):
            solve(K, B, F)
    assert issubclass(SingularSystemError, ValueError), "the fix is in the input: a ValueError"
    # holding one node (2 dofs) still leaves the rotation free
    with pytest.raises(ValueError, match="singular"):
        solve(K, sp.csr_matrix((0, N)), F, D=[0, 1], g=[0.0, 0.0])


def test_an_exactly_singular_system_is_refused_with_the_documented_error():
    """A chain of springs, free at both ends: K has a rigid mode and integer entries.

    The LU then meets an exactly zero pivot.  The module documents a
    SingularSystemError for a singular system, whatever the size of the pivot.
    """
    n = 5
    K = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]).tolil()
    K[0, 0] = K[n - 1, n - 1] = 1.0
    F = np.zeros(n)
    F[0], F[-1] = 1.0, -1.0
    with pytest.raises(SingularSystemError, match="singular"):
        solve(K.tocsr(), sp.csr_matrix((0, n)), F)


def test_an_unknown_without_stiffness_is_refused():
    """A node that no cell uses has an empty row in K: named, not divided by."""
    K = sp.diags([2.0, 0.0, 3.0]).tocsr()
    with np.errstate(all="raise"):  # no division by zero on the way
        with pytest.raises(SingularSystemError, match="1 unknown.*no stiffness"):
            solve(K, sp.csr_matrix((0, 3)), np.ones(3))
    # imposed, the same unknown is harmless
    U, _, _ = solve(K, sp.csr_matrix((0, 3)), np.ones(3), D=[1], g=[0.5])
    assert np.allclose(U, [0.5, 0.5, 1 / 3])


def test_multipliers_that_do_not_balance_u_are_never_returned(monkeypatch):
    """Bᵀμ = K U - F is checked after the recovery: reported multipliers that
    did not balance the displacement (here a sabotaged recovery) stop the solve."""
    import skxfem.linalg.saddle as saddle

    K = spd(4, np.random.default_rng(3))
    B = sp.csr_matrix([[1.0, -1.0, 0.0, 0.0]])
    F = np.array([1.0, 0.0, 0.0, 0.0])
    G = sp.csr_matrix((0, 1))
    U, mu, info = solve(K, B, F, G=G)
    assert info.balance < 1e-12
    monkeypatch.setattr(saddle, "smoothest_multipliers",
                        lambda B, r, G, tol=None: np.full(B.shape[0], 1e6))
    with pytest.raises(RuntimeError, match="do not balance"):
        solve(K, B, F, G=G)


# 7. nearly dependent rows ------------------------------------------------------------------

def nearly_dependent(load_on_the_weak_row, delta=1e-7, a=1 - 1e-4):
    """B = [[1, 0, 0], [1, δ, 0]]: two rows dependent to within δ; K couples
    U₁ and U₂ (K₁₂ = -a, soft enough that the LU still sees the weak row).

    B U = 0 gives U₀ = U₁ = 0, U₂ = F₂, and the reaction r = K U - F is
    (-F₀, -a F₂ - F₁, 0), so Bᵀμ = r needs μ₁ = r₁/δ: a spike.  Without the
    load on the weak row, F₁ = δ/2 - a: r = Bᵀ(-½, -½), a constant balances."""
    K = sp.csr_matrix([[1.0, 0.0, 0.0], [0.0, 1.0, -a], [0.0, -a, 1.0]])
    B = sp.csr_matrix([[1.0, 0.0, 0.0], [1.0, delta, 0.0]])
    F = np.array([1.0, 0.0 if load_on_the_weak_row else delta / 2 - a, 1.0])
    return K, B, F, sp.csr_matrix([[1.0, -1.0]])


def test_nearly_dependent_rows_that_carry_a_reaction_are_refused():
    """σ_min/σ_max ≈ δ/2 = 5e-8 is above the QR's 1e-10 (both rows kept) but below
    the recovery's 1e-6: the smoothest μ cannot balance a reaction along the
    weak combination, and the solve says why instead of a RuntimeError."""
    from skxfem.linalg.saddle import NearlyDependentError

    K, B, F, G = nearly_dependent(True)
    with pytest.raises(NearlyDependentError, match=r"rows \[0, 1\].*5\.0e-08.*1\.4e\+07.*vital"):
        solve(K, B, F, G=G)
    assert issubclass(NearlyDependentError, ValueError), "the fix is in the input: a ValueError"
    # without the recovery the exact multipliers come back, spike included
    U, mu, info = solve(K, B, F)
    assert info.removed == 0 and abs(mu[1] / -(1 - 1e-4) * 1e-7 - 1) < 1e-6, \
        f"μ₁ = r₁/δ = -a/δ ≈ -1e7, got {mu}"


def test_nearly_dependent_rows_balanced_by_a_constant_are_smoothed():
    """The same B, loaded so that a constant μ balances U: it is recovered."""
    K, B, F, G = nearly_dependent(False)
    U, mu, info = solve(K, B, F, G=G)
    assert info.balance < 1e-12
    assert np.abs(mu + 0.5).max() < 1e-12, f"the constant μ = -½ balances U, got {mu}"
