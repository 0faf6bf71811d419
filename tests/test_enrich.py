"""Tests for skxfem/enrich.py: the X-FEM space, its matrices and its fields.

The geometry is a unit box cut by a slightly tilted plane that crosses it
from side to side (one layer of cells is cut), so Ω⁻ and Ω⁺ are two floating
bodies with known volumes (the plane's mean x position times the cross
section).  A field given separately on each side, u⁻ on Ω⁻ and u⁺ on Ω⁺, is
put into X-FEM form by hand from the shifted enrichment
u = Σ aᵢφᵢ + Σ bⱼφⱼ(H - Hⱼ): aᵢ = u^{side of i}(xᵢ), bⱼ = (u⁺ - u⁻)(xⱼ)/2.

1. The space: the enriched nodes are the nodes of the cut cells (n_std and
   n_enr on a known cut), ordered node by node; nodes whose far side is a
   sliver are left out as documented in ``space``; bad ``sliver`` refused.
2. far_side_fraction: in [0, 1], zero away from Γ, exact values for a plane
   x = const on the tensor-product cells, and Σ ∫_{Ω⁺}φⱼ = |Ω⁺| on all cells.
3. Stiffness: symmetric; its standard block is plain scikit-fem's stiffness;
   its null space is exactly the rigid motions of EACH side (3 + 3 in 2D,
   6 + 6 in 3D); the energy of a piecewise linear field is exact.
4. Mass: symmetric, and uᵀMu = |c⁻|²|Ω⁻| + |c⁺|²|Ω⁺| for a piecewise constant u.
5. split_fields / jump_matrix: the side fields are u⁻ and u⁺ at the nodes,
   [[u]] = u⁻ - u⁺ on Γ, equal to -2 Σ φⱼbⱼ and to the difference of the side
   fields interpolated there.
6. XSpace.load: Fᵀu = ∫ t·u over a loaded face cut by Γ.
"""
import functools

import numpy as np
import pytest
from skfem import Basis, ElementVector, LinearForm, asm

from skxfem.cut import cut
from skxfem.enrich import (
    far_side_fraction,
    from_fields,
    jump_matrix,
    mass,
    split_fields,
    stiffness,
    xfem_space,
)
from skxfem.fem.evaluate import evaluation_matrix
from skxfem.fem.loads import boundary_quadrature, surface_load
from skxfem.fem.material import Material, stiffness_form
from skxfem.fem.meshes import box
from skxfem.fem.quadrature import cell_rule
from skxfem.levelset import complement, plane

MATERIAL = Material(E=1.0, nu=0.3)


def dim_of(cell):
    return 2 if cell in ("tri", "quad") else 3


@functools.cache
def split_box(cell):
    """A box split in two by a tilted plane through all of it.

    2D: 3 x 3 cells, Γ through (0.45, 0.5) with normal (1, 0.1): it crosses the
    middle column of cells only, |Ω⁻| = 0.45.  3D: 2 x 2 x 2 cells, Γ through
    (0.35, 0.5, 0.5) with normal (1, 0.12, 0.07): it crosses the first layer
    of cells only, |Ω⁻| = 0.35 (the tilt averages out over the cross section).
    Returns (mesh, psi, cut, V, |Ω⁻|, x-coordinates of the enriched node layers).
    """
    if dim_of(cell) == 2:
        mesh, x0, n, layers = box(3, cell), (0.45, 0.5), (1.0, 0.1), (1 / 3, 2 / 3)
    else:
        mesh, x0, n, layers = box(2, cell), (0.35, 0.5, 0.5), (1.0, 0.12, 0.07), (0.0, 0.5)
    psi = plane(x0, n)
    c = cut(mesh, psi)
    return mesh, psi, c, xfem_space(mesh, c), x0[0], layers


def dof_table(V):
    """Component and node of every standard dof."""
    nd = V.basis.nodal_dofs                        # (dim, nverts)
    comp = np.empty(V.n_std, int)
    node = np.empty(V.n_std, int)
    comp[nd] = np.arange(nd.shape[0])[:, None]
    node[nd] = np.arange(nd.shape[1])[None, :]
    return comp, node


def xfem_vector(V, u_minus, u_plus):
    """The X-FEM unknowns [a, b] of the field u⁻ on Ω⁻ and u⁺ on Ω⁺.

    u_minus, u_plus: callables x (dim, n) -> (dim, n), interpolated at the nodes.
    """
    return from_fields(V, u_minus(V.mesh.p), u_plus(V.mesh.p))


def rigid_motions(dim):
    """Callables x -> r(x) for a basis of the rigid motions (dim = 2 or 3)."""
    out = [lambda x, k=k: np.eye(dim)[k][:, None] + 0 * x for k in range(dim)]
    if dim == 2:
        out.append(lambda x: np.array([-x[1], x[0]]))
    else:
        for k in range(3):
            w = np.eye(3)[k]
            out.append(lambda x, w=w: np.cross(w, x, axis=0))
    return out


def zero(x):
    return 0 * x


def interface_points(c):
    """Points of Γ_h: facet vertices and centroids, as (cells, ref, physical)."""
    nv = c.facets.shape[0]
    ref = [c.facet_ref[v] for v in range(nv)] + [c.facet_ref.mean(axis=0)]
    phys = [c.points[:, c.facets[v]] for v in range(nv)]
    phys.append(np.mean(phys, axis=0))
    cells = np.tile(c.facet_cell, nv + 1)
    return cells, np.hstack(ref), np.hstack(phys)


# 1. the space -----------------------------------------------------------------------

def test_enriched_nodes_are_the_nodes_of_cut_cells(cell):
    mesh, psi, c, V, _, layers = split_box(cell)
    dim = mesh.dim()
    on_layer = np.isclose(mesh.p[0][:, None], layers).any(axis=1)
    expected = np.flatnonzero(on_layer)            # the two node layers of the cut cells
    assert np.array_equal(c.enriched, expected), "cut.enriched: nodes of the cut cells"
    n_layer = (4 if dim == 2 else 9)               # nodes per layer x = const
    assert V.n_std == dim * mesh.nvertices, "n_std: dim dofs per vertex"
    assert V.n_enr == dim * 2 * n_layer, (
        f"two layers of {n_layer} nodes, {dim} dofs each, are enriched; got n_enr = {V.n_enr}")
    assert V.N == V.n_std + V.n_enr
    # ordered node by node, component fastest, with H of the node
    enr = V.enr_dofs.reshape(-1, dim)
    assert np.array_equal(enr, V.basis.nodal_dofs[:, expected].T), (
        "enr_dofs must list the dofs of each enriched node, components together")
    assert np.array_equal(V.H_node, np.repeat(np.sign(psi(mesh.p[:, expected])), dim)), (
        "H_node must be H(x_j) = sign ψ(x_j) of each enriched dof's node")


def test_docstring_counts():
    from skfem import MeshTri1
    m = MeshTri1().refined(2)                      # 5 x 5 nodes
    V = xfem_space(m, cut(m, plane((0, 0.3), (0, 1))))
    # Γ: y = 0.3 cuts the row of cells between y = 0.25 and y = 0.5: 10 nodes
    assert (V.n_std, V.n_enr) == (50, 20)


def test_sliver_nodes_are_not_enriched(cell):
    """Γ a hair (1e-5) past the node layer x = 1/3: the layer x = 2/3 only sees a sliver."""
    mesh = box(3, cell)
    c = cut(mesh, plane((1 / 3 + 1e-5,) + (0.5,) * (mesh.dim() - 1),
                        (1.0,) + (0.0,) * (mesh.dim() - 1)))
    frac = far_side_fraction(mesh, c)
    near = np.isclose(mesh.p[0], 1 / 3)
    far = np.isclose(mesh.p[0], 2 / 3)
    assert np.array_equal(c.enriched, np.flatnonzero(near | far))
    assert frac[far].max() < 1e-8, (
        f"far side of the x = 2/3 nodes is a sliver of width 1e-5; fraction "
        f"{frac[far].max():.3g} should be ~ (3e-5)²/2")
    assert frac[near].min() > 0.2, (
        "the x = 1/3 nodes have a large part of their support beyond Γ (1/4 to 3/4)")
    V = xfem_space(mesh, c)
    enriched_nodes = np.unique(dof_table(V)[1][V.enr_dofs])
    assert np.array_equal(enriched_nodes, np.flatnonzero(near)), (
        "xfem_space() must drop the enrichment of nodes whose far-side fraction < sliver")
    V0 = xfem_space(mesh, c, sliver=0.0)
    assert V0.n_enr == mesh.dim() * c.enriched.size, "sliver=0 keeps every node of a cut cell"


def test_bad_sliver_is_refused():
    mesh, _, c, _, _, _ = split_box("quad")
    for bad in (-1e-3, float("nan")):
        with pytest.raises(ValueError, match="sliver must be a non-negative fraction"):
            xfem_space(mesh, c, sliver=bad)


# 2. far-side fraction ----------------------------------------------------------------

@pytest.mark.parametrize("cell", ["quad", "hex", "prism"])
def test_far_side_fraction_exact_for_a_plane_x_const(cell):
    """φⱼ = (1D hat in x) × (function of the other coordinates) on these cells.

    Γ: x = 0.4 on a 3 x 3 (x 3) box, h = 1/3, δ = 0.4 - 1/3 = h/5.  The hat of a
    node at x = 2/3 has δ²/(2h²) = 0.02 of its integral on x < 0.4, the hat of a
    node at x = 1/3 has (1 - δ/h)²/2 = 0.32 on x > 0.4; all others have 0.
    """
    mesh = box(3, cell)
    dim = mesh.dim()
    c = cut(mesh, plane((0.4,) + (0.5,) * (dim - 1), (1.0,) + (0.0,) * (dim - 1)))
    frac = far_side_fraction(mesh, c)
    expected = np.zeros(mesh.nvertices)
    expected[np.isclose(mesh.p[0], 1 / 3)] = 0.32
    expected[np.isclose(mesh.p[0], 2 / 3)] = 0.02
    assert np.abs(frac - expected).max() < 1e-12, (
        f"far-side fractions wrong: max error {np.abs(frac - expected).max():.3g}")


def test_far_side_fraction_adds_up_to_the_side_volume(cell):
    """Σⱼ ∫_{Ω⁺} φⱼ = |Ω⁺| (partition of unity), with ∫_{Ω⁺} φⱼ recovered from
    the fraction: far·∫φⱼ for nodes of Ω⁻, (1 - far)·∫φⱼ for nodes of Ω⁺."""
    mesh, psi, c, _, vol_minus, _ = split_box(cell)
    frac = far_side_fraction(mesh, c)
    assert frac.shape == (mesh.nvertices,)
    assert np.all((frac >= 0) & (frac <= 1)), "a fraction lies in [0, 1]"
    uncut = np.setdiff1d(np.arange(mesh.nvertices), c.enriched)
    assert np.all(frac[uncut] == 0), "a node whose support Γ misses has no far side"
    total = asm(LinearForm(lambda v, w: v), Basis(mesh, mesh.elem(),
                                                  quadrature=cell_rule(mesh, 4)))
    on_plus = np.where(c.psi < 0, frac, 1 - frac) * total
    assert abs(on_plus.sum() - (1 - vol_minus)) < 1e-12, (
        f"Σ ∫_Ω⁺ φⱼ = {on_plus.sum():.15g}, should be |Ω⁺| = {1 - vol_minus}")
    # swapping the sides (ψ → -ψ) does not change which side is "far"
    frac2 = far_side_fraction(mesh, cut(mesh, complement(psi)))
    assert np.abs(frac2 - frac).max() < 1e-12


# 3. stiffness -------------------------------------------------------------------------

def test_stiffness_is_symmetric_and_its_standard_block_is_plain_fem(cell):
    mesh, _, _, V, _, _ = split_box(cell)
    K = stiffness(V, MATERIAL)
    assert K.shape == (V.N, V.N)
    scale = abs(K).max()
    assert abs(K - K.T).max() < 1e-13 * scale, "the X-FEM stiffness must be symmetric"
    basis = Basis(mesh, ElementVector(mesh.elem()), quadrature=cell_rule(mesh, 4))
    K0 = asm(stiffness_form(MATERIAL, mesh.dim()), basis)
    err = abs(K[:V.n_std, :V.n_std] - K0).max()
    assert err < 1e-12 * scale, (
        f"the a-a block is ∫σ:ε over both sides = the standard stiffness; "
        f"differs by {err:.3g}")


def test_stiffness_null_space_is_the_rigid_motions_of_each_side(cell):
    mesh, _, _, V, _, _ = split_box(cell)
    dim = mesh.dim()
    K = stiffness(V, MATERIAL)
    # the rigid motions of Ω⁻ alone and of Ω⁺ alone are in the null space
    R = [xfem_vector(V, r, zero) for r in rigid_motions(dim)]
    R += [xfem_vector(V, zero, r) for r in rigid_motions(dim)]
    R = np.array(R).T
    n_rigid = 6 if dim == 2 else 12
    assert np.linalg.matrix_rank(R) == n_rigid, "the side-wise rigid motions are independent"
    scale = abs(K).max()
    assert abs(K @ R).max() < 1e-12 * scale, (
        "a rigid motion of one side, the other side fixed, must cost no energy")
    # ... and nothing else is: exactly n_rigid zero eigenvalues
    ev = np.linalg.eigvalsh(K.toarray()) / scale
    zeros = int(np.sum(np.abs(ev) < 1e-10))
    assert zeros == n_rigid, (
        f"K of two floating bodies must have {n_rigid} zero eigenvalues "
        f"({n_rigid // 2} rigid motions per side), found {zeros}; "
        f"smallest eigenvalues / max|K|: {ev[:n_rigid + 2]}")
    assert ev[n_rigid] > 1e-6, "the first non-rigid mode must be clearly positive"


def test_strain_energy_of_a_piecewise_linear_field(cell):
    """u = G⁻x on Ω⁻, G⁺x on Ω⁺: uᵀKu = Σ± |Ω±| σ(ε±):ε±, ε = sym G."""
    mesh, _, _, V, vol_minus, _ = split_box(cell)
    dim = mesh.dim()
    rng = np.random.default_rng(4)
    Gm, Gp = rng.standard_normal((2, dim, dim))
    U = xfem_vector(V, lambda x: Gm @ x, lambda x: Gp @ x)
    lam, mu = MATERIAL.lame(dim)

    def energy_density(G):
        eps = 0.5 * (G + G.T)
        return 2 * mu * np.sum(eps * eps) + lam * np.trace(eps) ** 2

    exact = vol_minus * energy_density(Gm) + (1 - vol_minus) * energy_density(Gp)
    got = U @ (stiffness(V, MATERIAL) @ U)
    assert abs(got - exact) < 1e-12 * exact, (
        f"uᵀKu = {got:.15g}, exact strain energy (x2) = {exact:.15g}")


# 4. mass ------------------------------------------------------------------------------

def test_mass_of_piecewise_constant_fields(cell):
    mesh, _, _, V, vol_minus, _ = split_box(cell)
    dim = mesh.dim()
    M = mass(V)
    assert abs(M - M.T).max() < 1e-15, "the mass matrix must be symmetric"
    e0 = np.eye(dim)[0]
    # u = (1, 0[, 0]) everywhere: a only, b = 0
    U = xfem_vector(V, lambda x: e0[:, None] + 0 * x, lambda x: e0[:, None] + 0 * x)
    assert np.all(U[V.n_std:] == 0)
    assert abs(U @ M @ U - 1.0) < 1e-13, f"∫ 1 over the unit box is 1, got {U @ M @ U}"
    # u = c⁻ on Ω⁻, c⁺ on Ω⁺ (the enriched dofs now matter)
    rng = np.random.default_rng(5)
    cm, cp = rng.standard_normal((2, dim))
    U = xfem_vector(V, lambda x: cm[:, None] + 0 * x, lambda x: cp[:, None] + 0 * x)
    exact = cm @ cm * vol_minus + cp @ cp * (1 - vol_minus)
    assert abs(U @ M @ U - exact) < 1e-13, (
        f"∫|u|² = {U @ M @ U:.15g}, should be |c⁻|²|Ω⁻| + |c⁺|²|Ω⁺| = {exact:.15g}")
    # u = 0 on Ω⁻, e0 on Ω⁺: only the volume of Ω⁺ counts
    U = xfem_vector(V, zero, lambda x: e0[:, None] + 0 * x)
    assert abs(U @ M @ U - (1 - vol_minus)) < 1e-13


# 5. split_fields and jump_matrix -------------------------------------------------------

def test_split_fields_recovers_each_side(cell):
    mesh, _, c, V, _, _ = split_box(cell)
    dim = mesh.dim()
    rng = np.random.default_rng(6)
    Gm, Gp = rng.standard_normal((2, dim, dim))
    dm, dp = rng.standard_normal((2, dim, 1))
    U = xfem_vector(V, lambda x: Gm @ x + dm, lambda x: Gp @ x + dp)
    minus, plus = split_fields(V, U)
    assert minus.shape == plus.shape == (dim, mesh.nvertices)
    p = mesh.p
    in_minus = (c.psi < 0) | np.isin(np.arange(mesh.nvertices), c.enriched)
    in_plus = (c.psi > 0) | np.isin(np.arange(mesh.nvertices), c.enriched)
    assert np.abs(minus[:, in_minus] - (Gm @ p + dm)[:, in_minus]).max() < 1e-13, (
        "split_fields' Ω⁻ field must be u⁻ at the nodes of Ω⁻ and the enriched nodes")
    assert np.abs(plus[:, in_plus] - (Gp @ p + dp)[:, in_plus]).max() < 1e-13, (
        "split_fields' Ω⁺ field must be u⁺ at the nodes of Ω⁺ and the enriched nodes")
    # shifted enrichment: a node's own side field is its standard dof a_i
    U = rng.standard_normal(V.N)
    minus, plus = split_fields(V, U)
    a = U[:V.n_std][V.basis.nodal_dofs]
    own = np.where(c.psi < 0, minus, plus)
    assert np.array_equal(own, a), "aᵢ must be the displacement at node i on its own side"


def test_jump_of_piecewise_rigid_motion(cell):
    """[[u]] = u⁻ - u⁺ = r⁻(x) - r⁺(x) at points of Γ."""
    mesh, psi, c, V, _, _ = split_box(cell)
    dim = mesh.dim()
    cells, ref, x = interface_points(c)
    assert np.abs(psi(x)).max() < 1e-12, "the test points must lie on Γ"
    rng = np.random.default_rng(7)
    wm, wp = rng.standard_normal((2, len(rigid_motions(dim))))

    def rm(y):
        return sum(w * r(y) for w, r in zip(wm, rigid_motions(dim)))

    def rp(y):
        return sum(w * r(y) for w, r in zip(wp, rigid_motions(dim)))

    U = xfem_vector(V, rm, rp)
    J = jump_matrix(V, cells, ref)
    assert J.shape == (dim * cells.size, V.N)
    jump = (J @ U).reshape(dim, -1)                # component-major rows
    assert np.abs(jump - (rm(x) - rp(x))).max() < 1e-12, (
        "[[u]] must be u⁻ - u⁺ (Ω⁻ minus Ω⁺), not the other way round")


def test_jump_matrix_agrees_with_split_fields(cell):
    mesh, _, c, V, _, _ = split_box(cell)
    dim = mesh.dim()
    cells, ref, _ = interface_points(c)
    U = np.random.default_rng(8).standard_normal(V.N)
    J = jump_matrix(V, cells, ref)
    assert J[:, :V.n_std].nnz == 0, "the jump does not depend on the standard dofs a"
    # [[u]] = -2 Σ φⱼ bⱼ
    Phi = evaluation_matrix(V.basis, cells, ref)
    b_std = np.zeros(V.n_std)
    b_std[V.enr_dofs] = U[V.n_std:]
    assert np.abs(J @ U - (-2.0) * (Phi @ b_std)).max() < 1e-13
    # = difference of the side fields interpolated at the points
    minus, plus = split_fields(V, U)
    um, up = np.zeros(V.n_std), np.zeros(V.n_std)
    um[V.basis.nodal_dofs], up[V.basis.nodal_dofs] = minus, plus
    assert np.abs(J @ U - Phi @ (um - up)).max() < 1e-12, (
        "jump_matrix and split_fields must describe the same u⁻ and u⁺")
    # pure enrichment b = e_k at every enriched node: [[u]] = -2 e_k on Γ
    for k in range(dim):
        U = np.zeros(V.N)
        U[V.n_std:][np.arange(V.n_enr) % dim == k] = 1.0
        jump = (J @ U).reshape(dim, -1)
        assert np.abs(jump - (-2.0 * np.eye(dim)[k][:, None])).max() < 1e-13, (
            "the enriched nodes' hats sum to 1 on Γ, so [[u]] = -2 b there")


# 6. the load of a space ----------------------------------------------------------------

def test_load_work_of_a_constant_traction(cell):
    """Fᵀu = ∫_top t·u for u = c⁻ on Ω⁻, c⁺ on Ω⁺, on the top face cut by Γ."""
    mesh, _, c, V, _, _ = split_box(cell)
    dim = mesh.dim()
    top = "ymax" if dim == 2 else "zmax"
    # the part of the top face in Ω⁻: x < x_Γ(top), x_Γ the line where Γ meets it
    if dim == 2:
        top_minus = 0.45 - 0.1 * (1 - 0.5)                    # = 0.4
    else:
        top_minus = 0.35 - 0.07 * (1 - 0.5)                   # mean over y of x_Γ
    q = boundary_quadrature(mesh, mesh.boundaries[top], order=4, psi_nodes=c.psi)
    rng = np.random.default_rng(9)
    t, cm, cp = rng.standard_normal((3, dim))
    f, _ = surface_load(V.basis, q, t)
    F = np.concatenate(V.load([(mesh.boundaries[top], t)]))
    assert F.shape == (V.N,)
    U = xfem_vector(V, lambda x: cm[:, None] + 0 * x, lambda x: cp[:, None] + 0 * x)
    exact = (t @ cm) * top_minus + (t @ cp) * (1 - top_minus)
    assert abs(F @ U - exact) < 1e-13, (
        f"work of the load = {F @ U:.15g}, should be t·c⁻|top⁻| + t·c⁺|top⁺| = {exact:.15g}")
    # the standard part is the plain load
    assert np.array_equal(F[:V.n_std], f)


def test_mass_integrates_linear_fields_exactly(cell):
    """The mass has its own quadrature orders (issue 7: the inf-sup norm was
    integrated with the stiffness' rule, one point on a simplex): u⁻ = y e₀,
    u⁺ = 2y e₀ gives ∫|u|² = 1/3 + 3 ∫_{Ω⁺} y², and with Γ: x = x₀ - a(y - ½)
    [- b(z - ½)] inside the box, ∫_{Ω⁺} y² = (1 - x₀)/3 + a/12."""
    mesh, _, _, V, x0, _ = split_box(cell)
    a = 0.1 if mesh.dim() == 2 else 0.12
    e0 = np.eye(mesh.dim())[0][:, None]
    U = xfem_vector(V, lambda x: e0 * x[1], lambda x: 2 * e0 * x[1])
    exact = 1 / 3 + 3 * ((1 - x0) / 3 + a / 12)
    got = U @ mass(V) @ U
    assert abs(got - exact) < 1e-13, f"∫|u|² = {got:.15g}, exact {exact:.15g}"


# 4. Γ through mesh nodes ----------------------------------------------------------------

@pytest.mark.parametrize("normal", ["along facets", "through diagonals"])
def test_gamma_through_nodes_splits_the_space_exactly(cell, normal):
    """Γ through mesh nodes (ψ = 0 there, :mod:`skxfem.cut`): along the facets x = 1/2
    the enriched nodes are the nodes on Γ, each of side Ω⁺ (H_j = +1, its support split);
    through the diagonals (x + y = 1) the nodes of the cut cells.  Either way K has
    the rigid motions of each side as null space, nothing else, and the jump of a
    piecewise rigid motion is exact on Γ_h and at the points (vertices on Γ too)."""
    from skxfem.enrich import edge_jumps

    dim = dim_of(cell)
    mesh = box(4, cell)
    n = np.r_[1.0, np.zeros(dim - 1)] if normal == "along facets" else \
        np.r_[1.0, 1.0, np.zeros(dim - 2)] / np.sqrt(2)
    psi = plane((0.5,) * dim, n)
    c = cut(mesh, psi)
    V = xfem_space(mesh, c)
    on = np.flatnonzero(c.psi == 0)
    assert on.size == (5 if dim == 2 else 25)
    if normal == "along facets":
        assert np.array_equal(c.enriched, on) and c.cells.size == 0
    assert np.all(np.isin(on, c.enriched))
    assert np.array_equal(c.node_side[on], np.ones(on.size, int))
    assert np.array_equal(V.H_node, np.repeat(c.node_side[c.enriched], dim).astype(float))
    K = stiffness(V, MATERIAL)
    R = np.array([xfem_vector(V, r, zero) for r in rigid_motions(dim)]
                 + [xfem_vector(V, zero, r) for r in rigid_motions(dim)]).T
    n_rigid = 6 if dim == 2 else 12
    scale = abs(K).max()
    assert abs(K @ R).max() < 1e-12 * scale
    ev = np.linalg.eigvalsh(K.toarray()) / scale
    assert int(np.sum(np.abs(ev) < 1e-10)) == n_rigid and ev[n_rigid] > 1e-6
    rng = np.random.default_rng(8)
    wm, wp = rng.standard_normal((2, len(rigid_motions(dim))))

    def rm(y):
        return sum(w * r(y) for w, r in zip(wm, rigid_motions(dim)))

    def rp(y):
        return sum(w * r(y) for w, r in zip(wp, rigid_motions(dim)))

    U = xfem_vector(V, rm, rp)
    cells, ref, x = interface_points(c)
    assert np.abs(psi(x)).max() < 1e-15
    jump = (jump_matrix(V, cells, ref) @ U).reshape(dim, -1)
    assert np.abs(jump - (rm(x) - rp(x))).max() < 1e-12
    assert np.abs(edge_jumps(V, U) - (rm(c.points) - rp(c.points))).max() < 1e-12


def test_body_load_refuses_a_force_of_the_wrong_length():
    """A force with fewer components than the mesh's dimension is refused (it loaded
    only its first components, silently)."""
    from skfem import MeshQuad1

    from skxfem.cut import cut
    from skxfem.enrich import body_load, xfem_space
    from skxfem.levelset import plane

    m = MeshQuad1().refined(1)
    V = xfem_space(m, cut(m, plane((0, 0.3), (0, 1))))
    with pytest.raises(ValueError, match="body force must be a callable"):
        body_load(V, (-2.0,))
    f, f_H = body_load(V, (0.0, lambda x: -2.0 * np.ones_like(x[0])))
    assert np.isclose(f[V.basis.nodal_dofs[1]].sum(), -2.0)
