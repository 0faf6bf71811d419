"""Known answers for the tied interface solver, :func:`skxfem.solver.solve`.

1. Uniaxial compression by an imposed displacement: the exact state is linear,
   so the traction on Γ is σ·n to round-off, on every cell type.
2. Equivalence with plain scikit-fem: with ``bonded`` the X-FEM tied space is
   a conforming space of a finer mesh, so both solves agree to round-off.
3. Dependent naive multipliers on tetrahedra: refused on request, removed by
   default without changing the (unique) displacement.
4. The paper's plate (§5) and its 2D strip: smooth pressure on quads and
   hexahedra, oscillating pressure with the naive space on triangles and prisms.
5. A level set that cuts no cell is refused with a clear message.
7. A naive space nearly dependent on a fine mesh is refused with a ValueError
   (issue 7); the stable spaces solve the same scene.
8. A circular Γ in a uniform stress state: normals from ∇ψ, and the pressure
   and tangential traction at every point converge to those of σ·n.

Conventions (see :mod:`skxfem.levelset`): Ω⁻ = {ψ < 0} below Γ, n points up
into Ω⁺, the traction is r = σ(u⁻)·n and the pressure p = -r·n.
"""
import dataclasses
import functools
import warnings

import numpy as np
import pytest
from skfem import Basis, ElementVector, condense
from skfem import solve as skfem_solve

from skxfem.cut import SNAP, SnapWarning
from skxfem.cut import cut as cut_mesh
from skxfem.enrich import stiffness, xfem_space
from skxfem.fem import meshes
from skxfem.fem.loads import boundary_quadrature, surface_load
from skxfem.fem.material import Material, stiffness_form
from skxfem.fem.quadrature import cell_rule
from skxfem.levelset import circle, plane
from skxfem.multipliers import interface_mass, interface_rule
from skxfem.scene import (
    Box,
    Displacement,
    Interface,
    Scene,
    SurfaceLoad,
    clamped,
    dirichlet,
    load_facets,
    resolve_mesh,
    rollers,
)
from skxfem.scene.benchmarks import P_MAX, paper_plate, strip
from skxfem.solver import constrained_dofs, solve
from skxfem.stabilised import multiplier_space

DELTA = 0.01  # imposed shortening of the unit block (E = 1: |σ| = DELTA)
THETA = np.deg2rad(30)


def at(*coords):
    """A selection of the node(s) at the given coordinates."""
    return lambda x: np.all([np.abs(x[i] - c) < 1e-12 for i, c in enumerate(coords)], axis=0)


def physical(result):
    """Nodal displacement (dim, nverts): u⁻ at the nodes of Ω⁻, u⁺ at those of Ω⁺."""
    below = result.V.cut.psi < 0
    return np.where(below[None, :], result.u_minus, result.u_plus)


def plain_solve(scene, mesh):
    """The same elasticity problem on ``mesh`` without interface, in plain scikit-fem.

    Returns the nodal displacement (dim, nverts) and the potential energy
    ½uᵀKu - f·u.
    """
    basis = Basis(mesh, ElementVector(mesh.elem()), quadrature=cell_rule(mesh))
    K = stiffness_form(scene.material, mesh.dim()).assemble(basis)
    f = np.zeros(basis.N)
    for facets, traction in load_facets(scene, mesh):
        f += surface_load(basis, boundary_quadrature(mesh, facets, 4), traction)[0]
    D, g = dirichlet(scene, mesh, basis)
    u = np.zeros(basis.N)
    u[D] = g
    u = skfem_solve(*condense(K, f, x=u, D=D))
    return u[basis.nodal_dofs], 0.5 * u @ K @ u - f @ u


def same_points(a, b):
    """For every column of ``a``, the index of the identical column of ``b``."""
    d = np.linalg.norm(a[:, :, None] - b[:, None, :], axis=0)
    assert d.min(axis=1).max() < 1e-12, "a point has no counterpart"
    return d.argmin(axis=1)


# ---------------------------------------------------------------------------
# 1. Uniaxial compression by an imposed displacement of the top face
# ---------------------------------------------------------------------------

def block(cell, theta=0.0, law="bonded", material=None, lateral="rollers",
          top="displacement"):
    """The unit block compressed along its last axis ("up"), Γ tilted by ``theta``.

    Bottom on rollers; top moved down by DELTA (or, ``top="pressure"``, a
    pressure DELTA).  ``lateral="rollers"`` holds the side faces (with ν = 0
    they do no work: the state is uniaxial); ``"free"`` leaves them free and
    removes the rigid motions with point supports at the bottom.
    Γ passes 0.3 h above the centre, with normal n = (sin θ, [0,] cos θ).
    Default material: E = 1, ν = 0.
    """
    dim = 2 if cell in ("tri", "quad") else 3
    n = 4 if dim == 2 else 3
    up = "xyz"[dim - 1]
    centre = np.full(dim, 0.5)
    centre[-1] += 0.3 / n
    normal = np.zeros(dim)
    normal[0], normal[-1] = np.sin(theta), np.cos(theta)
    supports = [rollers(up + "min")]
    if lateral == "rollers":
        supports += [rollers(a + s) for a in "xyz"[:dim - 1] for s in ("min", "max")]
    elif dim == 2:
        supports += [Displacement(at(0.0, 0.0), {"x": 0.0})]
    else:
        supports += [Displacement(at(0.0, 0.0, 0.0), {"x": 0.0, "y": 0.0}),
                     Displacement(at(1.0, 0.0, 0.0), {"y": 0.0})]
    if top == "displacement":
        supports.append(Displacement(up + "max", {up: -DELTA}))
        loads = ()
    else:
        loads = (SurfaceLoad(up + "max", pressure=DELTA),)
    return Scene(Box(n, cell), plane(centre, normal), material or Material(1.0, 0.0),
                 tuple(supports), loads, law)


def check_traction(result, sigma_up, theta):
    """The traction at every multiplier point is σ·n for σ = sigma_up e_up ⊗ e_up."""
    dim = result.points.shape[0]
    n = np.zeros(dim)
    n[0], n[-1] = np.sin(theta), np.cos(theta)
    e_up = np.eye(dim)[-1]
    expected = sigma_up * n[-1] * e_up  # σ·n
    r = result.traction
    assert np.abs(result.normals - n[:, None]).max() < 1e-12
    assert np.abs(r - expected[:, None]).max() < 1e-9 * abs(sigma_up), \
        "the traction on Γ is not σ·n"
    # its normal part, as a pressure, and its tangential part
    assert np.abs(result.pressure - (-sigma_up * n[-1] ** 2)).max() < 1e-9 * abs(sigma_up)
    tangential = r - (r * n[:, None]).sum(0) * n[:, None]
    expected_t = expected - (expected @ n) * n
    assert np.abs(tangential - expected_t[:, None]).max() < 1e-9 * abs(sigma_up)
    assert abs(np.linalg.norm(expected_t) - abs(sigma_up) * np.cos(theta) * np.sin(theta)) \
        < 1e-15


@pytest.mark.parametrize("theta, law", [(0.0, "bonded"), (THETA, "bonded"),
                                        (0.0, "bilateral")])
def test_uniaxial_imposed_displacement(cell, theta, law):
    """E = 1, ν = 0, lateral rollers: u = (0, ..., -DELTA·y_up), σ = -DELTA e_up ⊗ e_up,
    so p = DELTA cos²θ.  ``bilateral`` only with a horizontal Γ: tilted, the upper
    part would slide (uniaxial compression is then not an equilibrium)."""
    result = solve(block(cell, theta, law))
    check_traction(result, -DELTA, theta)
    u = physical(result)
    exact = np.zeros_like(u)
    exact[-1] = -DELTA * result.mesh.p[-1]
    assert np.abs(u - exact).max() < 1e-9 * DELTA, "the uniaxial state is not reproduced"
    assert result.max_jump < 1e-12 * DELTA


@pytest.mark.parametrize("cell", ["tri", "quad"])
@pytest.mark.parametrize("model", ["stress", "strain"])
def test_plane_stress_and_plane_strain(cell, model):
    """ν = 0.3, lateral faces free, top moved down by DELTA, σ_xx = 0.

    plane stress: σ_yy = -E·DELTA,          u_x(1, 1) = ν·DELTA;
    plane strain: σ_yy = -E·DELTA/(1 - ν²), u_x(1, 1) = ν·DELTA/(1 - ν)
    (σ_zz = ν σ_yy keeps ε_zz = 0).  The two models must be told apart.
    """
    nu = 0.3
    result = solve(block(cell, THETA, material=Material(1.0, nu, model), lateral="free"))
    sigma, ux = (-DELTA, nu * DELTA) if model == "stress" else \
        (-DELTA / (1 - nu ** 2), nu * DELTA / (1 - nu))
    check_traction(result, sigma, THETA)
    corner = np.flatnonzero(at(1.0, 1.0)(result.mesh.p))[0]
    assert abs(physical(result)[0, corner] - ux) < 1e-9 * DELTA, \
        f"u_x at the corner is not the plane-{model} value"


# ---------------------------------------------------------------------------
# 2. Equivalence with plain scikit-fem
# ---------------------------------------------------------------------------

def prism_scene():
    """Prisms (extruded along x) cut by the plane x = 0.4, parallel to their
    triangular faces; bottom clamped, parabolic pressure on the top."""
    return Scene(Box((3, 2, 2), "prism"), plane((0.4, 0.0, 0.0), (1.0, 0.0, 0.0)),
                 Material(1.0, 0.3), (clamped("zmin"),),
                 (SurfaceLoad("zmax", pressure=lambda x: 4 * P_MAX * x[1] * (1 - x[1])),))


# scene, axis normal to Γ, position of Γ on that axis
FACE_PARALLEL = {"quad": (strip(4, "quad"), 1, 0.5),
                 "hex": (paper_plate(3, "hex"), 2, 0.5),
                 "prism": (prism_scene(), 0, 0.4)}


def conforming_mesh(box, axis, x0):
    """The structured mesh of ``box`` with the plane {x_axis = x0} inserted as a node layer."""
    xs = [np.linspace(0.0, 1.0, k + 1) for k in box.n]
    xs[axis] = np.sort(np.r_[xs[axis], x0])
    if box.cell == "prism":
        return meshes._named_boundaries(meshes._tri_prisms(*xs))
    return meshes._named_boundaries(meshes.CELLS[box.cell].init_tensor(*xs))


@functools.cache
def solved_face_parallel(cell):
    """The X-FEM result, the conforming mesh and its plain solution."""
    scene, axis, x0 = FACE_PARALLEL[cell]
    fine = conforming_mesh(scene.mesh, axis, x0)
    return solve(scene), fine, plain_solve(scene, fine)[0]


@pytest.mark.parametrize("cell", ["quad", "hex", "prism"])
def test_bonded_equals_conforming_mesh(cell):
    """Γ parallel to cell faces, non-uniform (parabolic) load: not a patch test.

    With ``bonded`` the naive multipliers tie the jump to zero on all of Γ, so
    the X-FEM space holds the fields that are Q1 (prism: P1 × Q1) on each side
    of each cut cell and continuous: exactly the space of the mesh with Γ
    inserted as a layer of nodes.  The two solutions agree at the original
    nodes and on Γ.

    The X-FEM space is *richer* than that of the original mesh without
    interface: the two differ here.  (An equality with the original mesh, as
    the issue assumed, only holds for states the standard space reproduces,
    such as the patch test: see test_patch_test_equals_plain_solve.)
    """
    scene, axis, _ = FACE_PARALLEL[cell]
    result, fine, u_fine = solved_face_parallel(cell)
    scale = np.abs(u_fine).max()
    u = physical(result)
    assert np.abs(u - u_fine[:, same_points(result.mesh.p, fine.p)]).max() < 1e-9 * scale
    # on Γ: each side's field, interpolated along the cut edges (linear on an edge)
    c = result.V.cut
    a, b = c.edges
    p = result.mesh.p
    t = (c.points[axis] - p[axis, a]) / (p[axis, b] - p[axis, a])
    on_gamma = u_fine[:, same_points(c.points, fine.p)]
    for side in (result.u_minus, result.u_plus):
        assert np.abs(side[:, a] + t * (side[:, b] - side[:, a]) - on_gamma).max() \
            < 1e-9 * scale
    u_coarse, _ = plain_solve(scene, result.mesh)
    assert np.abs(u - u_coarse).max() > 1e-4 * scale, \
        "the X-FEM space should be richer than the original mesh's"


@pytest.mark.parametrize("cell", ["quad", "prism"])
def test_bonded_tractions_are_the_conforming_reactions(cell):
    """The traction r on Γ is what the lower part of the conforming solve feels.

    Testing the X-FEM equations with v = φ_k on Ω⁻ and 0 on Ω⁺ (φ_k the hat of
    an interface node k of the conforming mesh) gives ∫_Γ r φ_k = (K⁻u - f⁻)_k,
    K⁻ and f⁻ the stiffness and load of the cells below Γ.  On quads and on
    these prisms φ_k on Γ is the P1 multiplier function N_k, so M r = K⁻u - f⁻
    with M the interface mass, at every node of Γ without imposed displacement.
    """
    scene, axis, x0 = FACE_PARALLEL[cell]
    result, fine, u_fine = solved_face_parallel(cell)
    basis = Basis(fine, ElementVector(fine.elem()), quadrature=cell_rule(fine))
    below = np.flatnonzero(fine.p[axis, fine.t].mean(axis=0) < x0)
    u = np.zeros(basis.N)
    u[basis.nodal_dofs] = u_fine
    lower = basis.with_elements(below)
    reaction = stiffness_form(scene.material, fine.dim()).assemble(lower) @ u
    for facets, traction in load_facets(scene, fine):
        facets = facets[np.isin(fine.f2t[0, facets], below)]
        if facets.size:
            reaction -= surface_load(basis, boundary_quadrature(fine, facets, 4), traction)[0]
    reaction = reaction[basis.nodal_dofs]  # (dim, nverts)
    c = result.V.cut
    M = interface_mass(interface_rule(result.mesh, c))
    node = same_points(c.points, fine.p)
    free = ~np.isin(basis.nodal_dofs[:, node], dirichlet(scene, fine, basis)[0]).any(axis=0)
    assert free.sum() >= 3
    Mr = (M @ result.traction.T).T
    assert np.abs(Mr[:, free] - reaction[:, node[free]]).max() \
        < 1e-9 * np.abs(reaction[:, node]).max()


def test_patch_test_equals_plain_solve(cell):
    """A uniform pressure on a block with free sides (ν = 0.3, Γ tilted): both the
    X-FEM and the plain solve on the same mesh reproduce the linear state."""
    scene = block(cell, THETA, material=Material(1.0, 0.3), lateral="free", top="pressure")
    result = solve(scene)
    u_plain, _ = plain_solve(scene, result.mesh)
    assert np.abs(physical(result) - u_plain).max() < 1e-9 * np.abs(u_plain).max()


def tet_scene(normal=(0.1, 0.15, 1.0)):
    """Tetrahedra cut by a tilted plane, bottom clamped, parabolic pressure on the top.

    With the default normal Γ stays within the middle layer of cells.
    """
    return Scene(Box(3, "tet"), plane((0.5, 0.5, 0.53), normal), Material(1.0, 0.3),
                 (clamped("zmin"),),
                 (SurfaceLoad("zmax", pressure=lambda x: 4 * P_MAX * x[1] * (1 - x[1])),))


SIMPLEX_SCENES = {
    "tri": dataclasses.replace(strip(4, "tri", space="naive"),
                               levelset=plane((0.5, 0.53), (0.3, 1.0))),
    "tet": dataclasses.replace(tet_scene(), space="naive"),
}


@pytest.mark.parametrize("cell", ["tri", "tet"])
def test_simplices_tie_pointwise_and_lower_energy(cell):
    """On simplices the jump on Γ is P1 on every interface facet, so it lies in
    the naive multiplier space: the bonded tie holds pointwise.  The tied
    X-FEM space contains the P1 space of the mesh, so its potential energy
    ½uᵀKu - f·u (= -½ f·u at equilibrium) is not larger."""
    scene = SIMPLEX_SCENES[cell]
    result = solve(scene)
    u = physical(result)
    assert result.max_jump < 1e-12 * np.abs(u).max()
    _, energy_plain = plain_solve(scene, result.mesh)
    K = stiffness(result.V, scene.material)
    strain_energy = 0.5 * result.U @ K @ result.U
    # the top face is not cut: there the load works on the nodal displacement
    basis = result.V.basis
    f = sum(surface_load(basis, boundary_quadrature(result.mesh, facets, 4), t)[0]
            for facets, t in load_facets(scene, result.mesh))
    u_dofs = np.zeros(basis.N)
    u_dofs[basis.nodal_dofs] = u
    work = f @ u_dofs
    assert abs(2 * strain_energy - work) < 1e-9 * work, "equilibrium: uᵀKu = f·u"
    energy = strain_energy - work
    assert energy <= energy_plain
    assert energy < energy_plain - 1e-6 * abs(energy_plain), "the enrichment is not used"


def test_a_clamped_face_that_gamma_does_not_cut_leaves_the_enrichment_free():
    """Γ cuts cells of the bottom layer but not the clamped bottom face: the
    clamp acts on u⁻ alone, so the enriched dofs stay free and the energy is
    below the plain P1 one, as in test_simplices_tie_pointwise_and_lower_energy."""
    scene = tet_scene(normal=(0.2, 0.3, 1.0))
    result = solve(scene)
    _, energy_plain = plain_solve(scene, result.mesh)
    K = stiffness(result.V, scene.material)
    energy = -0.5 * result.U @ K @ result.U  # = ½uᵀKu - f·u at equilibrium
    assert energy < energy_plain - 1e-6 * abs(energy_plain)


def test_a_clamped_face_that_gamma_cuts_holds_on_both_sides(cell):
    """Γ (slanted) cuts the clamped face x = 0: there u⁻ and u⁺ must both
    vanish, at every node and so between the nodes: the enriched dofs of the
    face's nodes are fixed too (free, u⁺ - u⁻ = 2b would not vanish there)."""
    dim = 2 if cell in ("tri", "quad") else 3
    psi = plane((0.5,) * dim, (0.3,) + (0.0,) * (dim - 2) + (1.0,))
    up = "ymax" if dim == 2 else "zmax"
    scene = Scene(Box(3, cell), psi, Material(1.0, 0.3), (clamped("xmin"),),
                  (SurfaceLoad(up, traction=(1.0,) + (0.0,) * (dim - 1)),))
    result = solve(scene)
    x = result.mesh.p
    face = np.abs(x[0]) < 1e-12
    assert np.abs(result.u_minus[:, face]).max() == 0.0
    assert np.abs(result.u_plus[:, face]).max() == 0.0
    assert np.abs(result.u_plus).max() > 0.0


# ---------------------------------------------------------------------------
# 3. Dependent naive multipliers on tetrahedra
# ---------------------------------------------------------------------------

def tet_patch():
    return dataclasses.replace(block("tet", THETA, material=Material(1.0, 0.3), lateral="free",
                                     top="pressure"), space="naive")


def test_rank_deficient_naive_space_is_refused_on_request():
    with pytest.raises(ValueError, match="rank deficient"):
        solve(tet_patch(), dependent="raise")


def test_dependent_multipliers_are_removed():
    """Quadrilateral cuts carry four multipliers for a three-parameter linear
    jump: some depend on the others.  Removed, the displacement is still
    unique — the exact uniaxial state u = (ν x, ν y, -z)·p/E — and the
    pressure on Γ is still exact."""
    result = solve(tet_patch())
    assert result.removed > 0
    assert result.n_multipliers + result.removed == 3 * result.points.shape[1]
    x = result.mesh.p
    nu = 0.3
    exact = DELTA * np.array([nu * x[0], nu * x[1], -x[2]])
    assert np.abs(physical(result) - exact).max() < 1e-9 * DELTA
    check_traction(result, -DELTA, THETA)


# ---------------------------------------------------------------------------
# 4. The paper's plate and its 2D strip
# ---------------------------------------------------------------------------

@functools.cache
def solved(name, n, cell):
    return solve({"plate": paper_plate, "strip": strip}[name](n, cell, space="naive"))


def profile(result):
    """(y, p): the pressure along the plate's y (the strip's x), after checking
    that it does not vary along the plate's x."""
    axis = 1 if result.points.shape[0] == 3 else 0
    y = np.round(result.points[axis], 12)
    ys = np.unique(y)
    groups = [result.pressure[y == v] for v in ys]
    assert max(np.ptp(g) for g in groups) < 1e-9, "the plate's pressure depends on x"
    return ys, np.array([g[0] for g in groups])


def force_on_gamma(result):
    """∫_Γ p for the P1 pressure on the interface facets."""
    return np.sum(result.V.cut.measures * result.pressure[result.facets].mean(axis=0))


SMOOTH = [("strip", 4, "quad"), ("strip", 8, "quad"), ("plate", 4, "hex")]
NAIVE_OSCILLATING = [("strip", 4, "tri"), ("plate", 4, "prism")]


@pytest.mark.parametrize("case", SMOOTH + NAIVE_OSCILLATING)
def test_force_balance(case):
    """∫_Γ p = ∫ p_top = ∫₀¹ 4 P y(1 - y) dy = 2P/3 (unit width): the resultant is
    exact whatever the multiplier space (the upper part's translation is in the
    X-FEM space)."""
    assert abs(force_on_gamma(solved(*case)) - 2 * P_MAX / 3) < 1e-8


@pytest.mark.parametrize("case", SMOOTH)
def test_pressure_is_smooth_on_quads_and_hexahedra(case):
    """Symmetric about y = 0.5, increasing up to it, and no more curved than the
    applied parabola (second differences below its 8 P h²)."""
    y, p = profile(solved(*case))
    h = y[1] - y[0]
    assert np.abs(p - p[::-1]).max() < 1e-9
    assert np.all(np.diff(p[y <= 0.5]) > 0)
    assert np.abs(np.diff(p, 2)).max() < 8 * P_MAX * h ** 2


def total_variation(result):
    return np.abs(np.diff(profile(result)[1])).sum()


@pytest.mark.parametrize("case", NAIVE_OSCILLATING)
def test_naive_pressure_oscillates_on_triangles_and_prisms(case):
    """The paper's Figure 5: with the naive space, Γ cutting the diagonals gives
    more multipliers than the displacement can control, and p oscillates."""
    y, p = profile(solved(*case))
    assert np.any(np.diff(p[y <= 0.5]) < 0), "expected a non-monotone pressure"
    assert total_variation(solved(*case)) > 5 * total_variation(solved("plate", 4, "hex"))


@pytest.mark.parametrize("plate_cell, strip_cell", [("prism", "tri"), ("hex", "quad")])
def test_plate_is_the_plane_strain_strip(plate_cell, strip_cell):
    """Rollers on x = 0 and x = 1 make the plate plane strain: its (y, z)
    solution is the strip's (x, y) one, pressure and displacement."""
    plate, strip_ = solved("plate", 4, plate_cell), solved("strip", 4, strip_cell)
    # the plate point (x, y, 0.5) is the strip point (y, 0.5)
    j = same_points(plate.points[1:], strip_.points)
    assert np.abs(plate.pressure - strip_.pressure[j]).max() < 1e-8
    nodes = same_points(plate.mesh.p[1:], strip_.mesh.p)
    u3, u2 = physical(plate), physical(strip_)
    assert np.abs(u3[0]).max() < 1e-12
    assert np.abs(u3[1:] - u2[:, nodes]).max() < 1e-8 * np.abs(u2).max()


# ---------------------------------------------------------------------------
# 5. A level set that cuts no cell
# ---------------------------------------------------------------------------

def test_level_set_cutting_no_cell_is_refused():
    scene = dataclasses.replace(strip(2, "quad"), levelset=plane((0.0, 2.0), (0.0, 1.0)))
    with pytest.raises(ValueError, match="cuts no cell"):
        solve(scene)


# ---------------------------------------------------------------------------
# 6. Stability at the extremes: Γ a vanishing distance from a node row
# ---------------------------------------------------------------------------

def test_gamma_closing_in_on_a_node_row_is_stable(cell):
    """As Γ approaches a row of nodes (distance d·h, d = 1e-3, 1e-5), the tied
    solution with the vital-edge space tends to a limit: the pressure changes by
    O(d), no warning is raised, nothing blows up.  Through the nodes (d = 0) Γ stays
    there, exactly, no warning: the same kind of answer.  Closer than skxfem.cut.SNAP
    edge lengths (d = 1e-12) the nodes are put on Γ, with one SnapWarning: the
    answer is that of d = 0, to the bit.  (The naive
    space is not stable, so its pressure may jump between these distances; see
    tests/test_lbb.py for algo1 on tetrahedra.)"""
    dim = 2 if cell in ("tri", "quad") else 3
    up, low = ("ymax", "ymin") if dim == 2 else ("zmax", "zmin")
    normal = (0.0,) * (dim - 1) + (1.0,)

    def scene(d):
        at_height = (0.5,) * (dim - 1) + (0.5 + d / 4,)  # h = 1/4
        return Scene(Box(4, cell), plane(at_height, normal), Material(1.0, 0.3),
                     (clamped(low),), (SurfaceLoad(up, pressure=1.0),), space="vital")

    distances = (1e-3, 1e-5, SNAP)
    pressures = []
    for d in distances:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            result = solve(scene(d))
        assert np.all(np.isfinite(result.pressure)) and np.all(np.isfinite(result.U))
        assert result.max_jump < 1e-3, "the restricted tie holds weakly: a small jump"
        assert np.abs(result.pressure - 1).max() < 0.2, "a pressure near the load p = 1"
        pressures.append(result.pressure)
    change = [np.abs(a - b).max() for a, b in zip(pressures, pressures[1:])]
    assert change[0] < distances[0] and change[1] < distances[1], \
        f"the pressure does not settle as Γ → nodes: changes {change}"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        on = solve(scene(0.0))
    assert on.max_jump < 1e-3 and np.abs(on.pressure - 1).max() < 0.2
    with pytest.warns(SnapWarning, match=r"put them on it \(psi = 0\)") as record:
        near = solve(scene(1e-12))
    assert sum(issubclass(w.category, SnapWarning) for w in record) == 1, "warned once"
    assert np.array_equal(near.U, on.U) and np.array_equal(near.pressure, on.pressure)


@pytest.mark.parametrize("cell", ["tri", "prism"])
@pytest.mark.parametrize("space", ["winner", "vital"])
def test_bonded_restricts_every_traction_component_alike(cell, space):
    """The paper: relations on λ are also imposed on the friction
    multipliers.  Bonded: each component of the traction is P_c μ_c, P_c the
    space built on the edges whose jump in c no support holds: the same P
    for every component where none is held (the strip), the x-component on
    the plate losing the own multipliers of the edges in the roller faces
    x = 0, 1 (issue 7), which take their neighbours' (issue 18).  No
    multiplier is dependent then, and each held component is the one of a
    neighbour on Γ."""
    make = strip if cell == "tri" else paper_plate
    scene = dataclasses.replace(make(4, cell), space=space)
    result = solve(scene)
    mesh = result.mesh
    c = cut_mesh(mesh, scene.levelset)
    full = multiplier_space(space, mesh, c).P.toarray()
    on_faces = np.isclose(c.points[0], 0) | np.isclose(c.points[0], 1)
    assert result.removed == 0
    size = 0
    for k, component in enumerate(result.traction):
        held = on_faces if (cell == "prism" and k == 0) else np.zeros_like(on_faces)
        fixed = None
        if held.any():
            fixed = np.zeros(mesh.p.shape[1], dtype=bool)
            fixed[np.flatnonzero(np.isclose(mesh.p[0], 0) | np.isclose(mesh.p[0], 1))] = True
        P = multiplier_space(space, mesh, c, fixed=fixed).P.toarray()
        assert held.any() or np.array_equal(P, full)
        assert np.allclose(P.sum(axis=1), 1.0, rtol=1e-12)
        for e in np.flatnonzero(held):  # a λ of its neighbours', not one of its own
            assert np.any(np.all(P[~held] == P[e], axis=1))
            assert np.any(component[~held] == component[e])
        in_range = P @ np.linalg.lstsq(P, component, rcond=None)[0]
        assert np.abs(in_range - component).max() < 1e-12 * np.abs(component).max()
        size += P.shape[1]
    assert result.n_multipliers == size


def test_separate_supports_do_not_constrain_a_facet_they_share():
    """One column of quads between rollers on x = 0 and x = 1, Γ nearly
    vertical: both ends of the loaded top facet are held in x, but by two
    different supports; the facet is not on a Dirichlet boundary, so its
    enrichment stays free.  The faces x = 0 and x = 1 themselves are not cut."""
    scene = Scene(Box((1, 3), "quad"), plane((0.5, 0.5), (1.0, 0.1)), Material(1.0, 0.3),
                  (rollers("xmin"), rollers("xmax"), Displacement(at(0.0, 0.0), {"y": 0.0})),
                  (SurfaceLoad("ymax", pressure=1.0),))
    mesh = resolve_mesh(scene)
    V = xfem_space(mesh, cut_mesh(mesh, scene.levelset))
    dofs, _ = constrained_dofs(V, scene, mesh)
    assert np.all(dofs < V.n_std), "no enriched dof is constrained"


def test_a_selection_holding_one_side_of_a_cut_face_leaves_the_other_free():
    """A support given as a selection of the nodes of x = 0 below Γ only: it
    covers no whole cut facet, so b stays free; u⁻ is held at those nodes,
    u⁺ is not."""
    psi = plane((0.5, 0.53), (0.3, 1.0))
    below = lambda x: (np.abs(x[0]) < 1e-12) & (psi(x) < 0)  # noqa: E731
    scene = Scene(Box(4, "quad"), psi, Material(1.0, 0.3),
                  (Displacement(below, {"all": 0.0}),),
                  (SurfaceLoad("xmax", traction=(0.0, 1.0)),))
    result = solve(scene)
    held = below(result.mesh.p)
    assert np.abs(result.u_minus[:, held]).max() == 0.0
    cut_face = held & np.isin(np.arange(held.size), result.V.cut.enriched)
    assert cut_face.any() and np.abs(result.u_plus[:, cut_face]).max() > 0.0


@pytest.mark.parametrize("cell", ["prism", "tet"])
@pytest.mark.parametrize("space", ["winner", "vital"])
def test_no_tangential_traction_on_the_roller_faces(cell, space):
    """Issue 7: on the roller faces x = 0 and x = 1 the exact shear σ_xz is 0.
    With the stable spaces built once for all components the bonded plate
    reported up to 0.02 (vital) and 0.54 (winner) there on prisms.  The
    edges in those faces now take the λ_x of their neighbour on Γ (issue 18),
    so the shear there is no larger than inside: on prisms (an extrusion
    along x, whose discrete solution does not depend on x) small everywhere."""
    for n in (3, 5):
        result = solve(paper_plate(n, cell, space=space))
        on_faces = np.isclose(result.points[0], 0) | np.isclose(result.points[0], 1)
        assert on_faces.sum() > 0 and np.allclose(result.normals[:2], 0)
        peak = np.abs(result.pressure).max()
        shear = np.abs(result.traction[0])
        assert shear[on_faces].max() <= shear[~on_faces].max() + 1e-12 * peak
        if cell == "prism":
            assert shear.max() < 1e-3 * peak
        assert result.removed == 0


# ---------------------------------------------------------------------------
# 7. A nearly singular naive space is refused, not crashed on (issue 7)
# ---------------------------------------------------------------------------

def test_a_nearly_dependent_naive_space_is_refused_and_stable_spaces_solve_it():
    """The 128 × 129 triangle strip cut by a slanted Γ through (0, 0.37) with
    normal (-0.21, 1): Γ passes 1.6e-4 of an edge from a node near x = 0.047,
    where two naive multipliers are nearly dependent (σ/σ_max = 8e-9).  The
    multipliers that balance U there need a spike 3e5 times the typical
    traction: the solve refuses with a ValueError naming the cause and the
    remedy.  The stable spaces solve the same scene, and their traction on Γ
    balances the top load: ∫_Γ r = (0, -∫ p) = (0, -2P/3)."""
    from skxfem.linalg.saddle import NearlyDependentError

    scene = dataclasses.replace(strip(128, "tri", space="naive"),
                                levelset=plane((0.0, 0.37), (-0.21, 1.0)))
    with pytest.raises(NearlyDependentError, match=r"nearly dependent.*8\.1e-09.*space=\"vital\""):
        solve(scene)
    for name in ("vital", "winner"):
        result = solve(dataclasses.replace(scene, space=name))
        r = result.traction[:, result.facets].mean(axis=1)
        force = (r * result.V.cut.measures).sum(axis=1)
        assert np.abs(force - (0.0, -2 * P_MAX / 3)).max() < 1e-8, \
            f"{name}: the traction on Γ must balance the top load, ∫_Γ r = {force}"


# ---------------------------------------------------------------------------
# 8. A curved Γ in a uniform stress state: traction σ·n at every point
# ---------------------------------------------------------------------------

SIGMA = np.array([[1.0, 0.3], [0.3, -0.5]])


def uniform_stress(n, psi):
    """The unit square loaded by t = σ·n_out on its four sides (σ = SIGMA),
    held against rigid motion at two corners, Γ = {ψ = 0} bonded: the exact
    state is σ everywhere (a linear u, in the X-FEM space), so the traction
    on Γ is σ·n exactly, with normal and tangential parts that vary along Γ."""
    sides = [("xmin", (-1, 0)), ("xmax", (1, 0)), ("ymin", (0, -1)), ("ymax", (0, 1))]
    loads = tuple(SurfaceLoad(f, traction=tuple(SIGMA @ np.array(m, float))) for f, m in sides)
    supports = (Displacement(at(0.0, 0.0), {"x": 0.0, "y": 0.0}),
                Displacement(at(1.0, 0.0), {"y": 0.0}))
    return Scene(Box(n, "tri"), psi, Material(1.0, 0.3), supports, loads, space="vital")


@pytest.mark.parametrize("centre, radius", [((0.5, 0.5), 0.31416), ((-0.2, -0.3), 0.9137)],
                         ids=["closed", "leaving"])
def test_traction_on_a_circle_in_uniform_stress_converges_at_every_point(centre, radius):
    """Γ a circle inside the square (closed) or an arc centred outside it that
    leaves the mesh through two sides (its end points are multiplier points).
    At every multiplier point x the reported normal is the exact n = (x - c)/|x - c|,
    and the pressure p = -t·n and tangential traction t·τ (τ = (-n_y, n_x))
    converge to those of σ·n.  Theory: the vital space holds one traction per
    group of edges, a stretch of Γ of length O(h) over which σ·n varies by
    |σ| h/R, so the error at a point is O(h): rate 1.  Measured over n = 20, 40,
    80 (n = 10 is not yet asymptotic on the closed circle): 1.3 (p) and 1.4 (t·τ)
    closed, 1.4 and 1.1 leaving; asserted > 0.9, with every error below 2h
    (measured: at most 1.4h).  The vital space ties Γ only weakly, so U is not
    exactly the linear state: its jump on Γ is O(h²) (measured 2e-3, 5e-4, 5e-5
    closed, at most 0.8h²)."""
    c = np.array(centre)[:, None]
    ns, errors = np.array([20, 40, 80]), []
    for n in ns:
        result = solve(uniform_stress(n, circle(centre, radius)))
        normal = (result.points - c) / np.linalg.norm(result.points - c, axis=0)
        assert np.abs(result.normals - normal).max() < 1e-14, "n = ∇ψ/|∇ψ| at each point"
        t = SIGMA @ normal
        tau = np.array([-normal[1], normal[0]])
        errors.append([np.abs(result.pressure + (t * normal).sum(0)).max(),
                       np.abs(((result.traction - t) * tau).sum(0)).max()])
        assert result.max_jump < 2 / n ** 2, "the vital tie holds weakly: a jump O(h²)"
    on_boundary = np.isclose(result.points, 0, atol=1e-12).any(axis=0)
    assert on_boundary.sum() == (2 if centre[0] < 0 else 0), "the arc's two end points"
    errors = np.array(errors)
    rate = -np.polyfit(np.log(ns), np.log(errors), 1)[0]
    assert np.all(rate > 0.9), f"errors {errors.tolist()} converge at rates {rate}, not ≥ 1"
    assert np.all(errors < 2 / ns[:, None]), f"errors {errors.tolist()}: not below 2h"


# ---------------------------------------------------------------------------
# 8. The linear solve: direct, iterative (AMG + projected CG), auto
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("make", [lambda: strip(6, "tri"), lambda: paper_plate(3, "prism")])
def test_iterative_linear_solve_gives_the_direct_answer(make):
    pytest.importorskip("pyamg")
    scene = make()
    direct = solve(scene, linear="direct")
    it = solve(scene, linear="iterative")
    assert (direct.linear, it.linear) == ("direct", "iterative")
    assert np.abs(it.U - direct.U).max() <= 1e-8 * np.abs(direct.U).max()
    assert np.abs(it.pressure - direct.pressure).max() <= 1e-6 * np.abs(direct.pressure).max()


def test_the_linear_tolerance_is_the_users_and_is_recorded(tmp_path):
    """Issue 17 item 9: a bonded block in uniform compression (p = 5, λ = -5 at every
    point) solved iteratively.  The default tolerance gives the multipliers to 1e-10;
    a loose one, asked for, gives away accuracy (1e-5 measured) as asked; each run
    records its tolerance in ``linear_info`` and in result.json."""
    import json

    from skxfem.app.io import write_result
    from skxfem.linalg.choice import LINEAR_TOL
    from skxfem.scene.benchmarks import uniaxial, uniform_block

    pytest.importorskip("pyamg")
    scene = dataclasses.replace(uniform_block(uniaxial(3, p=5.0), law="bonded"),
                                mesh=Box((5, 9, 9), "hex"))
    for tol, worst in ((None, 1e-10), (1e-6, 1e-3)):
        r = (solve(scene, linear="iterative") if tol is None
             else solve(scene, linear="iterative", linear_tol=tol))
        error = np.abs(r.pressure - 5.0).max() / 5.0
        assert r.linear == "iterative" and error <= worst
        chosen = LINEAR_TOL if tol is None else tol
        assert r.linear_info["tol"] == chosen and r.linear_info["residual"] <= chosen
        write_result(r, tmp_path / str(tol))
        data = json.loads((tmp_path / str(tol) / "result.json").read_text())
        assert data["linear_solve"]["tol"] == chosen
    assert error > 1e-10, "a loose tolerance is honoured, not tightened behind the user"


def test_auto_takes_the_direct_solve_on_small_scenes_and_bad_names_are_refused():
    from skxfem.solver import AUTO_ITERATIVE

    r = solve(strip(4, "quad"))
    assert r.linear == "direct" and r.n_dofs < AUTO_ITERATIVE[2]
    with pytest.raises(ValueError, match="linear must be one of"):
        solve(strip(4, "quad"), linear="cholesky")


@pytest.mark.parametrize("law", ["bonded"])
def test_load_steps_given_to_a_tie_are_refused_not_ignored(law):
    """steps = [1, 0] on a tie (or a free crack) were ignored: the result was the state
    at load factor 1, with nothing said.  Refused by name, with the cure; the default
    path (one step at 1) solves as before."""
    s = dataclasses.replace(strip(n=3), law=law)
    for steps in ((1.0, 0.0), (2.0,), (0.5, 1.0)):
        with pytest.raises(ValueError, match=r"steps \(here \[.*\]\) are the load path of a "
                           r"contact solve .*leave steps out, or scale the loads"):
            solve(dataclasses.replace(s, steps=steps))
    assert solve(s).U.shape == solve(dataclasses.replace(s, steps=(1,))).U.shape


def test_auto_falls_back_to_the_direct_solve_where_cg_stalls(monkeypatch):
    """``linear='auto'`` chose CG for a 3D crack (zone under AUTO_ZONE) and, where CG did
    not reach 1e-12 in 500 iterations, stopped with 'use the direct solve' (a slab on
    rollers, n = 10: 5.3e-4): auto is the solve's own choice, so a stalled CG now hands
    the solve to the direct one; asked for by name, 'iterative' still fails, naming the
    cure.  (CG is made to stall here; the slab itself takes 10 s.)"""
    import skxfem.linalg.iterative as iterative
    import skxfem.solver as solver

    scene = strip(8, cell="quad")
    monkeypatch.setattr(solver, "choose_linear",       # auto chooses CG, whatever the size
                        lambda method, *a, **k: "iterative" if method == "auto" else method)

    def stalls(*args, **kwargs):
        raise iterative.ConvergenceError("projected CG did not reach 1e-12 (test)", 500, 5e-4)

    monkeypatch.setattr(iterative, "solve", stalls)
    r = solve(scene, linear="auto")
    assert r.linear == "direct"
    direct = solve(scene, linear="direct")
    assert np.allclose(r.pressure, direct.pressure, rtol=1e-12, atol=1e-14)
    with pytest.raises(iterative.ConvergenceError, match="did not reach"):
        solve(scene, linear="iterative")


def _pulled(crack, n: int, size: float) -> Scene:
    """The square of side ``size`` (n × n cells of two triangles) with ``crack`` (an
    Interface or a tuple of them), pulled by σ_yy = 1 on its top and bottom, held at its
    two lower corners (E = 1, ν = 0.3)."""
    held = (Displacement("ymin", {"x": 0.0, "y": 0.0}, where="x < 1e-9"),
            Displacement("ymin", {"y": 0.0}, where=f"x > {size} - 1e-9"))
    pull = tuple(SurfaceLoad(b, traction=(0.0, t)) for b, t in (("ymax", 1.0), ("ymin", -1.0)))
    cracks = crack if isinstance(crack, tuple) else (crack,)
    return Scene(Box(n, "tri", size=(size, size)), interfaces=cracks,
                 material=Material(1.0, 0.3), displacements=held, loads=pull)


def test_the_four_tip_ring_of_the_sweep_solves_with_its_default_zone():
    """Two arcs of one circle (R = 3) as one crack with four tips in a 20 x 20 plate, h =
    1/3: the default zone enriches half the nodes with branch functions, nearly
    dependent far from the tips, and the Jacobi-scaled LU found the system singular
    (only enrichment_radius = 2 solved).  The direct solve now scales each enriched
    node's block: the default solves, its tips mirrored through the centre within 1e-3
    (K_I 1.2159 to 1.2161, K_II -1.5137 to -1.5162)."""
    from skxfem.levelset import LevelSet

    crack = Interface(LevelSet(lambda x: np.hypot(x[0] - 10, x[1] - 10) - 3, 2, "ring"),
                      law="free", front=LevelSet(lambda x: np.abs(x[0] - 10) - 2, 2, "ends"))
    (front,) = solve(_pulled(crack, 60, 20.0), linear="direct").front
    order = np.lexsort(front["points"].T[::-1])          # (8, 7.8), (8, 12.2), (12, ...)
    for k in ("K_I", "K_II"):                            # the mesh: symmetric through the
        K = front[k][order]                              # centre, its diagonals not in x
        assert max(abs(K[0] - K[3]), abs(K[1] - K[2])) < 1e-3 * np.abs(K).max(), k
        assert np.ptp(K) < 3e-3 * np.abs(K).max(), k
    assert front["K_I"].min() > 1.0


def _ring(n):
    """A ring crack of radius 0.15 cut into two arcs by φ = |y - 0.5| - 0.1 (four tips)
    in the unit square of n × n triangle pairs, :func:`_pulled`."""
    from skxfem.levelset import LevelSet
    ring = Interface(LevelSet(lambda x: np.hypot(x[0] - 0.5, x[1] - 0.5) - 0.15, 2, "ring"),
                     law="free", front=LevelSet(lambda x: np.abs(x[1] - 0.5) - 0.1, 2, "band"))
    return _pulled(ring, n, 1.0)


def test_a_four_tip_ring_crack_solves_directly_with_its_default_zone():
    """The default zone of the ring's four tips (r_e = 0.28, 51 % of the nodes at h = 1/41)
    reaches above and below the ring, where ∇ψ is parallel to ∇φ: branch nodes there have
    an 8 × 8 Jacobi-scaled block down to 1.4e-12, and the Jacobi-scaled LU refused the
    system as singular (pivot 9.6e-12).  The direct solve now scales each enriched node's
    block (as CG does): K is CG's, and the tips mirrored through the centre agree."""
    from skxfem.linalg.saddle import SingularSystemError
    from skxfem.linalg.saddle import solve as saddle_solve
    from skxfem.problem import assemble
    p = assemble(_ring(41))
    with pytest.raises(SingularSystemError, match="smallest LU pivot"):
        saddle_solve(p.K, p.B, p.F, p.D, p.g)                  # Jacobi scaling alone
    (direct,) = solve(_ring(41), linear="direct").front
    (cg,) = solve(_ring(41), linear="iterative").front
    for k in ("K_I", "K_II"):
        assert np.abs(direct[k] - cg[k]).max() < 1e-4 * np.abs(direct["K_I"]).max()
    order = np.lexsort(direct["points"].T[::-1])               # by x, then y
    K_I = direct["K_I"][order]                                 # (-,-), (-,+), (+,-), (+,+)
    assert abs(K_I[0] - K_I[3]) < 5e-3 * K_I.max() and abs(K_I[1] - K_I[2]) < 5e-3 * K_I.max()
    assert K_I.min() > 0.1


def test_two_cracks_whose_branch_functions_nearly_coincide_are_a_singular_system():
    """The ring's two arcs as two cracks whose fronts differ by 1e-9 x above and below
    the ring, where both zones reach: the nodes there hold two nearly equal sets of
    branch functions.  Their own block (scaled by node) is not positive definite: the
    solve refuses the system as singular and names the zone's cure."""
    from skxfem.levelset import LevelSet
    from skxfem.linalg.saddle import SingularSystemError

    def arc(s):
        return Interface(LevelSet(lambda x: np.hypot(x[0] - 0.5, x[1] - 0.5) - 0.2, 2, "o"),
                         law="free", front=LevelSet(lambda x: np.maximum(
                             np.abs(x[1] - 0.5) - 0.1, s * (0.5 - x[0])) + 1e-9 * s * x[0],
                             2, f"arc {s}"))
    with pytest.raises(SingularSystemError, match=r"singular to working precision .*"
                       r"smaller enrichment_radius"):
        solve(_pulled((arc(1), arc(-1)), 21, 1.0), linear="direct")
