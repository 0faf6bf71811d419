"""skxfem.crack.space3d (its quadrature and integration): the rules of the enriched cells
(the symmetric rule of order SMOOTH_ORDER in the branch tube, the pieces' padding), the
six kinds g and their gradients evaluated once per point, the cells' stiffness batched
cell by cell against a point-by-point assembly, and u_h, ∇u_h at points."""
from math import factorial

import numpy as np
import pytest
import scipy.sparse as sp
from skfem import Basis, ElementTetP1, MeshTet1

from skxfem.crack.branch import branch, branch_local_gradient
from skxfem.crack.geometry3d import crack_geometry_3d, mesh_cells
from skxfem.crack.quadrature3d import collapsed, vertex_polar
from skxfem.crack.space3d import (
    SMOOTH_ORDER,
    _cell_values,
    _kinds,
    _levels,
    _pack,
    crack_space_3d,
    evaluation,
    field_at,
    functions_at,
    near_points,
    point_values,
    rules,
    stiffness,
    virtual_field,
)
from skxfem.fem.material import Material, stiffness_matrix
from skxfem.fem.quadrature import cell_rule, simplex_points

MAT = Material(1.0, 0.3)


def cube(n, nz):
    return MeshTet1.init_tensor(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1),
                                np.linspace(0, 1, nz + 1))


def edge_crack(m, front=0.5):
    """The crack {y = 0.5, x < front}: its front along z."""
    return crack_geometry_3d(m, lambda x: x[1] - 0.5, lambda x: x[0] - front)


def close(a, b, tol):
    """a ≈ b point by point (the first axis), relative to each point's largest entry."""
    a, b = np.asarray(a).reshape(len(a), -1), np.asarray(b).reshape(len(b), -1)
    return np.all(np.abs(a - b).max(axis=1) <= tol * np.maximum(np.abs(b).max(axis=1), 1))


def test_kinds_are_the_branch_functions_and_their_chain_rule():
    """_kinds against skxfem.crack.branch (values, and the chain rule of
    branch_local_gradient through ∇φ_h, ∇ψ_h), at random points, on the faces behind the
    front (θ = ±π by the side, in cut cells only), ahead of it on ψ = 0, and at r = 0
    (all zero)."""
    rng = np.random.default_rng(3)
    n = 400
    phi, psi = rng.uniform(-1, 1, n), rng.uniform(-1, 1, n)
    psi[:40], phi[:40] = 0.0, -rng.random(40)            # on the faces
    psi[40:50], phi[40:50] = 0.0, rng.random(10)         # ahead of the front
    phi[50:55], psi[50:55] = 0.0, 0.0                    # on the front
    side = np.where(rng.random(n) < 0.5, -1.0, 1.0)
    side[60:70] = 0.0
    cut = rng.random(n) < 0.7
    cut[:40] = True
    gphi, gpsi = rng.standard_normal((n, 3)), rng.standard_normal((n, 3))
    g, dg = _kinds(phi, psi, gphi, gpsi, side, cut)
    r = np.hypot(phi, psi)
    theta = np.arctan2(psi, phi)
    theta = np.where((phi < 0) & (np.sign(psi) != side) & (side != 0) & cut, side * np.pi,
                     theta)
    live = r > 0
    F = branch(np.where(live, r, 1.0), np.where(live, theta, 0.0)) * live
    loc = branch_local_gradient(np.where(live, r, 1.0), np.where(live, theta, 0.0)) * live
    dF = loc[:, 0, :, None] * gphi + loc[:, 1, :, None] * gpsi          # (4, n, 3)
    assert np.allclose(g[:, 0], 1.0) and np.allclose(g[:, 1], np.where(side == 0, 1, side))
    assert close(g[:, 2:], F.T, 1e-14)
    assert close(dg[:, 2:], dF.transpose(1, 0, 2), 1e-13)
    assert not np.any(dg[:, :2]) and not np.any(g[50:55, 2:]) and not np.any(dg[50:55])
    assert np.allclose(g[:40, 2], np.where(side[:40] < 0, -1, 1) * np.sqrt(r[:40]))


def test_branch_functions_are_continuous_in_cells_crossed_ahead_of_the_front():
    """The penny {z = 0.05, ρ < 0.55} at n = 16: six cells that ψ_h crosses ahead of the
    front (φ_h > 0 on their part of {ψ_h = 0}) have φ_h < 0 at a vertex whose ψ_h has
    not the cell's side.  No crack cuts them: F is atan2's there, continuous, at every
    point of the stiffness's rules (θ forced to ±π by the side made F jump inside them)."""
    m = MeshTet1.init_tensor(*(np.linspace(-1, 1, 17),) * 3)
    g = crack_geometry_3d(m, m.p[2] - 0.05, np.hypot(m.p[0], m.p[1]) - 0.55)
    ps, ph = g.psi[m.t], g.phi[m.t]
    ahead = (g.side != 0) & (ps < 0).any(axis=0) & (ps > 0).any(axis=0)
    odd = np.flatnonzero(ahead & ((ph < 0) & (np.sign(ps) != g.side)).any(axis=0))
    assert odd.size == 6
    V = crack_space_3d(m, g)
    (c, x, w, side), = rules(V, odd, symmetric=True)
    pv = point_values(V, np.repeat(c, w.shape[1]), x.reshape(-1, 3).T, side.ravel())
    wrong = (pv.phi < 0) & (np.sign(pv.psi) != side.ravel())
    assert wrong.sum() > 10, "points behind the front on the other side of {ψ_h = 0}"
    expect = branch(np.hypot(pv.phi, pv.psi), np.arctan2(pv.psi, pv.phi))
    assert close(pv.g[:, 2:], expect.T, 1e-14)


def test_cell_values_are_point_values_batched_by_cell():
    """The same values to round-off; the gradients of the branch kinds at the edge rule's
    points 7e-5 h from the front to 1e-11 (φ_h, ψ_h ∼ 1e-4 there keep fewer digits: the
    two evaluations differ by 5e-13, measured)."""
    m = cube(6, 3)
    V = crack_space_3d(m, edge_crack(m, 0.53), "geometric", 0.3)
    for cells, x, w, side in rules(V, np.arange(m.t.shape[1]), plain=2):
        nc, nq = w.shape
        lam, dlam, g, dg = _cell_values(V, cells, x, side)
        pv = point_values(V, np.repeat(cells, nq), x.reshape(-1, 3).T, side.ravel())
        assert close(lam.reshape(-1, 4), pv.lam, 1e-13)
        assert close(np.repeat(dlam, nq, axis=0), pv.dlam, 1e-13)
        assert close(g.reshape(-1, 6), pv.g, 1e-13)
        assert close(dg.reshape(-1, 6, 3), pv.dg, 1e-11)


def test_the_tube_pieces_near_the_front_take_the_graded_rule():
    """rules(tube=((1.0, 6),)): the cells and pieces of the branch tube within one longest
    edge of the front take the collapsed 6³ rule (216 points), the others keep the
    symmetric rule; every cell's weights still sum to its volume."""
    m = cube(8, 3)
    V = crack_space_3d(m, edge_crack(m, 0.53), "geometric", 0.4)
    cells = np.arange(m.t.shape[1])
    level = _levels(V)
    volume = np.abs(np.linalg.det(mesh_cells(m, cells)[:, 1:] - mesh_cells(m, cells)[:, :1])) / 6
    points = {}
    for tube in ((), ((1.0, 6),)):
        total = np.zeros(cells.size)
        count = np.zeros(cells.size, dtype=int)
        for c, x, w, side in rules(V, cells, plain=2, symmetric=8, tube=tube):
            np.add.at(total, c, w.sum(axis=1))
            np.add.at(count, c, np.count_nonzero(w, axis=1))
        assert np.allclose(total, volume, rtol=1e-12, atol=0)
        points[tube] = count
    uncut = np.setdiff1d(np.flatnonzero(level == 1), V.geometry.cells)
    graded = points[((1.0, 6),)][uncut] == 216
    assert graded.any() and not graded.all()               # the near ones only
    assert np.all(points[()][uncut] == 45)                 # the symmetric rule of order 8
    d = near_points(V, mesh_cells(m, uncut), ((1.0, 6),), default=0)
    assert np.array_equal(d == 6, graded)


def _pointwise_stiffness(V, material):
    """The stiffness summed point by point from functions_at's 24 gradients per point, on
    the same rules (the reference the batched assembly must reproduce)."""
    mesh = V.mesh
    lam_, mu = material.lame(3)
    near = V.support_cells(V.enriched_nodes())
    nv = V.T.shape[0]
    parts = []
    for cells, x, w, side in rules(V, near, plain=1, symmetric=True):
        nq = w.shape[1]
        _, G_, vnode_ = functions_at(V, np.repeat(cells, nq), x.reshape(-1, 3).T,
                                     side.ravel())
        wq_ = w.ravel()
        for k in range(0, wq_.size, 2048):     # points in chunks: 5184 numbers a point
            G, vnode, wq = G_[k:k + 2048], vnode_[k:k + 2048], wq_[k:k + 2048]
            A = np.einsum("q,qai,qbj->qaibj", wq, G, G)      # ∂_i f_a ∂_j f_b, each point
            Ke = (lam_ * A + mu * A.transpose(0, 1, 4, 3, 2)
                  + mu * np.einsum("qakbk->qab", A)[:, :, None, :, None]
                  * np.eye(3)[None, None, :, None, :])       # [q, a, i, b, j]
            dof = 3 * vnode[:, :, None] + np.arange(3)       # (q, 24, 3)
            rows = np.broadcast_to(dof[:, :, :, None, None], Ke.shape).ravel()
            cols = np.broadcast_to(dof[:, None, None], Ke.shape).ravel()
            parts.append(sp.coo_matrix((Ke.ravel(), (rows, cols)), shape=(nv, nv)).tocsr()
                         .tocoo())                          # summed within the chunk
    K = sp.csr_matrix((np.concatenate([c.data for c in parts]),
                       (np.concatenate([c.row for c in parts]),
                        np.concatenate([c.col for c in parts]))), shape=(nv, nv))
    rest = np.setdiff1d(np.arange(mesh.t.shape[1]), near)
    Ks = stiffness_matrix(material, Basis(mesh, ElementTetP1(), elements=rest,
                                          quadrature=cell_rule(mesh)))
    pad = sp.block_diag([Ks, sp.csr_matrix((V.N - V.n_std,) * 2)])
    return (V.T.T @ K @ V.T + pad).tocsr()


@pytest.mark.parametrize("front, enrichment", [(0.53, "geometric"), (0.5, "topological"),
                                               (0.5 + 1e-3, "geometric")])
def test_stiffness_is_the_point_by_point_sum(front, enrichment):
    """The batched assembly (cells grouped by their functions, blocks of node pairs on the
    upper half) gives the matrix of the plain sum over every quadrature point, to
    round-off; a front mid-cell, through nodes, and just past them."""
    m = cube(5, 3)
    V = crack_space_3d(m, edge_crack(m, front), enrichment,
                       0.3 if enrichment == "geometric" else None)
    K = stiffness(V, MAT)
    K0 = _pointwise_stiffness(V, MAT)
    assert abs(K - K0).max() < 1e-13 * abs(K0).max()


def test_field_at_is_the_sum_of_the_functions():
    """u_h and ∇u_h of field_at (and u_h of evaluation's operator) against the 24
    functions φ_k g of functions_at with the virtual coefficients ũ = T U (random U,
    points on both sides of the faces)."""
    m = cube(6, 3)
    V = crack_space_3d(m, edge_crack(m, 0.53), "geometric", 0.3)
    U = np.random.default_rng(1).standard_normal(V.N)
    ut = virtual_field(V, U)
    for cells, x, w, side in rules(V, np.arange(m.t.shape[1]), plain=2):
        nq = w.shape[1]
        c, X, S = np.repeat(cells, nq), x.reshape(-1, 3).T, side.ravel()
        u, gu = field_at(V, U, c, X, S)
        vals, grads, vnode = functions_at(V, c, X, S)
        coef = ut[vnode % m.p.shape[1], vnode // m.p.shape[1]]      # by node and kind
        assert close(u.T, np.einsum("na,nac->nc", vals, coef), 1e-13)
        assert close(gu.transpose(2, 0, 1), np.einsum("naj,nac->ncj", grads, coef), 1e-13)
        assert close((evaluation(V, c, X, S) @ U).reshape(3, -1).T, u.T, 1e-13)


def test_smooth_rule_is_exact_to_degree_6_with_positive_weights():
    T = np.array([[[0.1, 0.0, 0.2], [1.0, 0.1, 0.0], [0.2, 0.9, 0.1], [0.0, 0.3, 1.1]]])
    x, w = simplex_points(T, SMOOTH_ORDER)
    xr, wr = collapsed(T, 6)                              # exact to degree 9
    assert w.shape == (1, 24) and np.all(w > 0)
    worst = {}
    for d in (5, 6, 7):
        worst[d] = max(abs(w[0] @ np.prod(x[0] ** e, axis=1) - wr[0] @ np.prod(xr[0] ** e, axis=1))
                       for a in range(d + 1) for b in range(d + 1 - a)
                       for e in [np.array([a, b, d - a - b])])
    assert worst[5] < 1e-15 and worst[6] < 1e-15 and worst[7] > 1e-8
    # on the unit tetrahedron: ∫ x²y²z² = 2!2!2!/9!
    xu, wu = simplex_points(np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]]), 6)
    assert np.isclose(wu[0] @ np.prod(xu[0] ** 2, axis=1),
                      factorial(2) ** 3 / factorial(9), rtol=1e-13)


def _branch_energy(x, w):
    """∫ |∇(λ F₁)|² + |∇(λ F₄)|² over a tetrahedron, λ a linear function and F the branch
    functions of a front along the z-axis (√r type: ∇F ∼ r^{-1/2})."""
    r, th = np.hypot(x[0, :, 0], x[0, :, 1]), np.arctan2(x[0, :, 1], x[0, :, 0])
    F, dF = branch(r, th), branch_local_gradient(r, th)
    lam, dlam = 1 - 0.3 * x[0, :, 0] - 0.5 * x[0, :, 2], np.array([-0.3, 0.0, -0.5])
    out = 0.0
    for k in (0, 3):
        grad = dlam[:, None] * F[k] + lam * np.vstack([dF[k, 0], dF[k, 1], 0 * r])
        out += w[0] @ (grad ** 2).sum(axis=0)
    return out


@pytest.mark.parametrize("distance, bound", [(1.0, 3e-5), (2.0, 2e-5), (3.0, 1e-6)])
def test_smooth_rule_on_branch_functions_a_cell_from_the_front(distance, bound):
    """Tetrahedra of size h = 1 whose nearest point is ``distance`` h from the front, the
    z-axis (the cells of SMOOTH_ORDER are a cell or more away), two shapes: the symmetric
    rule's relative error on the √r-type stiffness integrand, measured 1.0e-5 and 2.0e-5
    at h, 1.4e-6 and 1.1e-5 at 2h, 6e-7 and 8e-7 at 3h (the collapsed rule of 4³ points it
    replaced: 5.7e-6 and 1.4e-4, 3.1e-7 and 5.4e-5, 1.5e-7 and 4.1e-6; it depends on
    which vertex it collapses to)."""
    shift = np.array([distance, 0.0, 0.0])
    for T in ([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
              [[0.0, -0.5, 0], [1, -0.5, 0], [1, 0.5, 0], [1, 0.5, 1]]):
        T = np.array([T]) + shift
        ref = _branch_energy(*collapsed(T, 16))
        assert abs(_branch_energy(*simplex_points(T, SMOOTH_ORDER)) / ref - 1) < bound


def test_vertex_rule_on_the_front_singularity():
    """The vertex rule (VERTEX_POINTS) on a piece meeting the front (the z-axis) at its
    vertex V₀ only: ∫ |∇F₁|² = ∫ 1/(4r) to 1e-4 (the default (4, 5); (4, 4) 3e-4)."""
    T = np.array([[[0.0, 0, 0], [0.6, 0.1, 0.3], [0.2, 0.7, 0.1], [0.1, 0.2, 0.9]]])

    def quarter_over_r(x, w):
        return w[0] @ (0.25 / np.hypot(x[0, :, 0], x[0, :, 1]))

    ref = quarter_over_r(*vertex_polar(T, 14, 14))
    err = abs(quarter_over_r(*vertex_polar(T)) / ref - 1)
    assert err < abs(quarter_over_r(*vertex_polar(T, 4, 4)) / ref - 1) and err < 1e-4


def test_pack_pads_each_cell_to_a_quarter_octave():
    """Pieces of 1 to 40 × 24 points: each cell's points in one row, its weights summed
    as given, at most a quarter more slots than points (powers of 2: up to twice)."""
    rng = np.random.default_rng(0)
    counts = rng.integers(1, 41, 60)
    cells = np.repeat(np.arange(60), counts)
    x = rng.random((cells.size, 24, 3))
    w = rng.random((cells.size, 24))
    out = _pack([(cells, x, w, np.ones_like(w))])
    slots = sum(b[2].size for b in out)
    assert slots <= 1.25 * w.size
    got = np.concatenate([b[0] for b in out])
    sums = np.concatenate([b[2].sum(axis=1) for b in out])
    assert np.array_equal(np.sort(got), np.arange(60))
    assert np.allclose(sums[np.argsort(got)], np.bincount(cells, w.sum(axis=1)))
