"""Patch tests: states the discrete space reproduces exactly give exact tractions.

Uniaxial compression (bottom on rollers, rigid motions removed at two or
three nodes, lateral faces free, pressure p on the top): σ = -p e_z ⊗ e_z, so
on an interface tilted by θ the traction is r = σn = -p cosθ e_z, whose normal
part gives the contact pressure p cos²θ and whose tangential part has
magnitude p cosθ sinθ.

A frictionless (``bilateral``) tie carries no tangential traction, so on a
tilted interface uniaxial compression is *not* an equilibrium state of the
tied body (the upper part slides).  Its patch test is hydrostatic
compression, σ = -p I: pressure p on every face, traction -p n on any plane.
A frictionless tie also leaves the upper part free to slide along Γ: the
bilateral scenes hold one or two nodes of the top face at their exact
(zero) tangential displacement, otherwise the system is singular (and the
solver says so, see test_floating_part_is_reported).
"""
import dataclasses

import numpy as np
import pytest

from skxfem.fem.material import Material
from skxfem.levelset import LevelSet, plane
from skxfem.linalg.saddle import SingularSystemError
from skxfem.scene import Box, Displacement, Scene, SurfaceLoad, rollers
from skxfem.solver import solve
from skxfem.studies.convergence import energy_error

P = 1.0


def at(*coords):
    """A selection of the node(s) at the given coordinates."""
    return lambda x: np.all([np.abs(x[i] - c) < 1e-12 for i, c in enumerate(coords)], axis=0)


def geometry(cell, theta, delta):
    """Mesh with 4 cells per side, interface at ``delta``·h above the node row
    through the centre, tilted by ``theta`` about the out-of-plane axis."""
    dim = 2 if cell in ("tri", "quad") else 3
    h = 0.25
    if dim == 2:
        normal = (np.sin(theta), np.cos(theta))
        point = (0.5, 0.5 + delta * h)
    else:
        normal = (np.sin(theta), 0.0, np.cos(theta))
        point = (0.5, 0.5, 0.5 + delta * h)
    return dim, Box(4, cell), plane(point, normal), np.array(normal)


def upper_supports(dim, law):
    """Tangential supports of the top face for a sliding (bilateral) tie."""
    if law != "bilateral":
        return ()
    if dim == 2:
        return (Displacement(at(0.0, 1.0), {"x": 0.0}),)
    return (Displacement(at(0.0, 0.0, 1.0), {"x": 0.0, "y": 0.0}),
            Displacement(at(1.0, 0.0, 1.0), {"y": 0.0}))


def uniaxial(cell, theta, delta, law):
    dim, mesh, psi, n = geometry(cell, theta, delta)
    up = "xyz"[dim - 1]
    origin = (0.0,) * dim
    if dim == 2:
        fix = (Displacement(at(*origin), {"x": 0.0}),)
    else:
        fix = (Displacement(at(*origin), {"x": 0.0, "y": 0.0}),
               Displacement(at(1.0, 0.0, 0.0), {"y": 0.0}))
    scene = Scene(mesh, psi, Material(1.0, 0.3),
                  (rollers(up + "min"),) + fix + upper_supports(dim, law),
                  (SurfaceLoad(up + "max", pressure=P),), law)
    return scene, n


def hydrostatic(cell, theta, delta, law):
    dim, mesh, psi, n = geometry(cell, theta, delta)
    faces = [a + s for a in "xyz"[:dim] for s in ("min", "max")]
    if dim == 2:
        fix = (Displacement(at(0.0, 0.0), {"x": 0.0, "y": 0.0}),
               Displacement(at(1.0, 0.0), {"y": 0.0}))
    else:
        fix = (Displacement(at(0.0, 0.0, 0.0), {"x": 0.0, "y": 0.0, "z": 0.0}),
               Displacement(at(1.0, 0.0, 0.0), {"y": 0.0, "z": 0.0}),
               Displacement(at(0.0, 1.0, 0.0), {"z": 0.0}))
    scene = Scene(mesh, psi, Material(1.0, 0.3), fix + upper_supports(dim, law),
                  tuple(SurfaceLoad(f, pressure=P) for f in faces), law)
    return scene, n


def tractions(result, n):
    """(normal pressure, tangential traction vectors) at the multiplier points."""
    r = result.traction
    pn = -(r * n[:, None]).sum(0)
    tangential = r + pn[None, :] * n[:, None]
    return pn, tangential


@pytest.mark.parametrize("delta", [0.5, 0.1, 1e-3])
@pytest.mark.parametrize("theta", [0.0, np.deg2rad(20)])
def test_bonded_uniaxial(cell, delta, theta):
    result = solve(uniaxial(cell, theta, delta, "bonded")[0])
    _, n = uniaxial(cell, theta, delta, "bonded")
    pn, tang = tractions(result, n)
    assert np.abs(result.pressure - P * np.cos(theta) ** 2).max() < 1e-9 * P
    assert np.abs(pn - P * np.cos(theta) ** 2).max() < 1e-9 * P
    # tangential traction: magnitude p cosθ sinθ, along -e_z's tangential part
    expected = -P * np.cos(theta) * (np.eye(len(n))[-1] - np.cos(theta) * n)
    assert np.abs(tang - expected[:, None]).max() < 1e-9 * P
    assert abs(np.linalg.norm(expected) - P * np.cos(theta) * np.sin(theta)) < 1e-14
    assert result.max_jump < 1e-10


@pytest.mark.parametrize("delta", [0.5, 0.1, 1e-3])
def test_bilateral_uniaxial_horizontal(cell, delta):
    result = solve(uniaxial(cell, 0.0, delta, "bilateral")[0])
    assert np.abs(result.pressure - P).max() < 1e-9 * P
    assert result.max_jump < 1e-10


@pytest.mark.parametrize("delta", [0.5, 0.1, 1e-3])
@pytest.mark.parametrize("law", ["bonded", "bilateral"])
def test_hydrostatic_tilted(cell, delta, law):
    scene, n = hydrostatic(cell, np.deg2rad(20), delta, law)
    result = solve(scene)
    pn, tang = tractions(result, n)
    assert np.abs(result.pressure - P).max() < 1e-9 * P
    assert np.abs(tang).max() < 1e-9 * P
    assert result.max_jump < 1e-10


@pytest.mark.parametrize("law", ["bonded", "bilateral"])
def test_gamma_through_nodes_passes_the_patch_tests_to_round_off(cell, law):
    """Γ through the centre row of nodes (δ = 0, no SnapWarning): along the mesh
    facets (θ = 0) and tilted through nodes (θ = 20°), the tractions are exact to
    round-off, 1e-12 (measured ≤ 2.3e-14), where Γ moved 1e-9 h off the nodes
    gave 1e-9.  Bonded: uniaxial, θ = 0 and 20°; bilateral: horizontal uniaxial;
    both: hydrostatic at 20°."""
    import warnings

    runs = [hydrostatic(cell, np.deg2rad(20), 0.0, law)]
    runs += ([uniaxial(cell, t, 0.0, law) for t in (0.0, np.deg2rad(20))]
             if law == "bonded" else [uniaxial(cell, 0.0, 0.0, law)])
    for k, (scene, n) in enumerate(runs):
        with warnings.catch_warnings():
            warnings.simplefilter("error", UserWarning)     # no SnapWarning
            result = solve(scene)
        pn, tang = tractions(result, n)
        cos = n[-1]
        if k == 0:                                          # hydrostatic
            assert np.abs(result.pressure - P).max() < 1e-12 * P
            assert np.abs(tang).max() < 1e-12 * P
        else:
            expected = -P * cos * (np.eye(len(n))[-1] - cos * n)
            assert np.abs(result.pressure - P * cos ** 2).max() < 1e-12 * P
            assert np.abs(tang - (expected[:, None] if law == "bonded" else 0)).max() \
                < 1e-12 * P
        assert result.max_jump < 1e-12


@pytest.mark.parametrize("cell", ["quad", "hex"])
def test_floating_part_is_reported(cell):
    """Without supports on the upper part a frictionless tie lets it slide:
    the solver refuses the singular system instead of returning garbage."""
    scene, _ = uniaxial(cell, 0.0, 0.5, "bilateral")
    scene = dataclasses.replace(scene, displacements=scene.displacements[:-1 - (cell == "hex")])
    with pytest.raises(SingularSystemError, match="singular"):
        solve(scene)


@pytest.mark.parametrize("space", ["winner", "vital"])
@pytest.mark.parametrize("law", ["bonded", "bilateral"])
def test_stabilised_spaces_pass_the_patch_test(cell, space, law):
    """Every row of P sums to 1, so a constant traction is in every space:
    the restricted spaces pass the hydrostatic patch test as the naive one."""
    scene, n = hydrostatic(cell, np.deg2rad(20), 0.1, law)
    result = solve(dataclasses.replace(scene, space=space))
    pn, tang = tractions(result, n)
    assert np.abs(result.pressure - P).max() < 1e-9 * P
    assert np.abs(tang).max() < 1e-9 * P
    assert result.max_jump < 1e-10


def curved(dim):
    """Γ: a parabola (2D) or an elliptic paraboloid (3D), dipping to z = 0.43."""
    if dim == 2:
        return LevelSet(lambda x: x[1] - 0.43 - 0.4 * (x[0] - 0.5) ** 2, 2, "parabola")
    return LevelSet(lambda x: x[2] - 0.43 - 0.4 * ((x[0] - 0.5) ** 2
                                                   + 0.5 * (x[1] - 0.4) ** 2), 3, "paraboloid")


@pytest.mark.parametrize("space", ["naive", "winner", "vital"])
def test_curved_interface_hydrostatic_patch(cell, space):
    """Under σ = -p I the traction on any surface is -p n, so on a curved Γ
    a frictionless tie carries the constant pressure p at every point, in
    every space (the facets of Γ_h each have their own normal; no special
    case for curved interfaces anywhere).  A bonded tie would carry the
    vector -p n, which jumps at the kinks of Γ_h: no P1 space holds it."""
    scene, _ = hydrostatic(cell, 0.0, 0.1, "bilateral")
    scene = dataclasses.replace(scene, levelset=curved(scene.levelset.dim), space=space)
    result = solve(scene)
    assert np.abs(result.pressure - P).max() < 1e-9 * P
    assert result.max_jump < 1e-10


# Γ crossing a supported face (issue 18) ---------------------------------------------
#
# A support holds the whole displacement of the facets it covers, enriched part
# included, and the multiplier of a cut edge whose jump it holds at both ends is
# the λ of a neighbour on Γ: a uniform stress stays exact however Γ crosses the
# support.  (With no multiplier there, λ = 0 at that edge, the constant traction
# was out of the space: 3.4e-2 energy error on the quad patch below, max jump
# 1.6e-2, and 1e-3 to 4e-2 on every cell.)  The state is any uniform strain ε,
# shear included: u = εx imposed on the supported faces, the traction σn on the
# others; bilateral ties carry a hydrostatic one (σ = -p I: no shear on any Γ).

CROSSING_2D = {  # Γ crossing the bottom face y = 0 at 25°, 45° and 70°, and a corner cut
    "25°": plane((0.3, 0.0), (-0.47, 1.0)), "45°": plane((0.37, 0.0), (-1.0, 1.0)),
    "70°": plane((0.6, 0.0), (1.0, -0.36)), "corner": plane((0.05, 0.0), (1.0, 1.0)),
    "nodes": plane((0.25, 0.0), (-0.8, 1.0))}  # through nodes of the 4 x 5 mesh
CROSSING_3D = {  # Γ crossing the bottom face z = 0, tilted about two axes; a corner cut
    "25°": plane((0.3, 0.4, 0.0), (-0.4, 0.21, 1.0)),
    "45°": plane((0.37, 0.4, 0.0), (-0.9, 0.37, 1.0)),
    "70°": plane((0.6, 0.4, 0.0), (1.0, 0.31, -0.36)),
    "corner": plane((0.05, 0.0, 0.0), (1.0, 1.0, 1.0)),
    "nodes": plane((1 / 3, 0.0, 0.0), (-0.75, 0.0, 1.0))}  # through nodes of 3 x 3 x 4
SHEAR = {2: [[0.3, 0.2], [0.2, -0.5]], 3: [[0.3, 0.2, 0.1], [0.2, -0.5, 0.15],
                                           [0.1, 0.15, 0.2]]}


def crossing(cell, where, law, supports):
    """The uniform state of ``law`` on a box whose supported faces Γ crosses.

    ``supports``: ``"clamped"`` (the bottom, u = εx), or ``"rollers"`` (the
    normal component u·e = (εx)·e on the bottom and on x = 0, y = 0)."""
    dim = 2 if cell in ("tri", "quad") else 3
    material = Material(1.0, 0.3)
    if law == "bonded":
        eps = np.array(SHEAR[dim])
    else:
        eps = -0.2 * np.eye(dim)  # isotropic: σ = -p I in the plane of the cells
    sigma = material.stress(eps[:, :, None], dim)[..., 0]
    up = "xyz"[dim - 1]

    def value(c):
        return lambda x: np.einsum("j,j...->...", eps[c], x)

    if supports == "clamped":
        held = {up + "min": range(dim)}
    else:
        held = {f"{a}min": [i] for i, a in enumerate("xyz"[:dim])}
    displacements = tuple(Displacement(face, {c: value(c) for c in comps})
                          for face, comps in held.items())
    loads = []
    for face in [a + s for a in "xyz"[:dim] for s in ("min", "max")]:
        if supports == "clamped" and face == up + "min":
            continue
        normal = np.zeros(dim)
        normal["xyz".index(face[0])] = 1.0 if face.endswith("max") else -1.0
        loads.append(SurfaceLoad(face, traction=tuple(float(t) for t in sigma @ normal)))
    n = (4, 5) if dim == 2 else (3, 3, 4)
    psi = (CROSSING_2D if dim == 2 else CROSSING_3D)[where]
    return Scene(Box(n, cell), psi, material, displacements, tuple(loads), law), eps, sigma


@pytest.mark.parametrize("where", ["25°", "45°", "70°", "corner", "nodes"])
@pytest.mark.parametrize("law, supports", [("bonded", "clamped"), ("bonded", "rollers"),
                                           ("bilateral", "clamped")])
def test_gamma_crossing_a_supported_face_keeps_a_uniform_state_exact(cell, where, law,
                                                                    supports):
    """``where = "nodes"``: Γ through rows of nodes, meeting the supported bottom at a
    node (or a row of them), so that boundary facets of one side touch Γ at a node of
    the other side (its enriched dofs held there too: enrich.constrained_dofs)."""
    scene, eps, sigma = crossing(cell, where, law, supports)
    result = solve(scene)
    assert patch_energy_error(result, eps) <= 1e-8
    own = np.where(scene.levelset(result.mesh.p) < 0, result.u_minus, result.u_plus)
    exact = eps @ result.mesh.p
    scale = np.abs(exact).max()
    assert np.abs(own - exact).max() <= 1e-9 * scale, "u = εx at every node, on its side"
    assert result.max_jump <= 1e-9 * scale
    r = sigma @ result.normals
    peak = np.abs(sigma).max()
    if law == "bonded":
        assert np.abs(result.traction - r).max() <= 1e-8 * peak, "the traction σn everywhere"
    else:
        assert np.abs(result.pressure + (r * result.normals).sum(0)).max() <= 1e-8 * peak


def patch_energy_error(result, eps):
    """The relative energy error of ``result`` against the uniform strain ``eps``."""
    dim = eps.shape[0]
    return energy_error(result, lambda x: np.broadcast_to(
        eps.reshape(dim, dim, *([1] * (x.ndim - 1))), (dim, dim) + x.shape[1:]))


@pytest.mark.parametrize("space", ["naive", "winner"])
def test_gamma_crossing_a_supported_face_in_the_other_spaces(cell, space):
    scene, eps, _ = crossing(cell, "25°", "bonded", "rollers")
    result = solve(dataclasses.replace(scene, space=space))
    assert patch_energy_error(result, eps) <= 1e-8
    assert result.max_jump <= 1e-9 * np.abs(eps).max()


# A small piece of the body that only the tie holds (issue 18) -----------------------
#
# Γ cuts off a corner of the loaded, unsupported end of the box, inside one cell.  A
# stable space gave that piece of Γ one star of vital edges (one μ per component):
# its mean jump cannot hold the piece's turning, and the tied system was refused as
# singular ("a part of the body can move freely").  Such a piece gets a multiplier
# per edge (skxfem.linalg.rigid.short_pieces), and the patch test holds to round-off, down
# to pieces whose nodes lose their enrichment (skxfem.enrich.xfem_space's sliver rule).

@pytest.mark.parametrize("size", [0.05, 1e-3, 1e-6])
@pytest.mark.parametrize("space", ["winner", "vital"])
def test_a_small_corner_piece_held_by_the_tie_alone_is_solved(cell, size, space):
    dim = 2 if cell in ("tri", "quad") else 3
    psi = plane((dim - size,) + (0.0,) * (dim - 1), (1.0,) * dim)  # Σ x_i = dim - size
    scene, _ = uniaxial(cell, 0.0, 0.5, "bonded")
    result = solve(dataclasses.replace(scene, levelset=psi, space=space))
    sigma = np.zeros((dim, dim))
    sigma[-1, -1] = -P
    eps = uniform_strain_of(scene.material, sigma)
    assert patch_energy_error(result, eps) <= 1e-8


def uniform_strain_of(material, sigma):
    from skxfem.studies.extremes import uniform_strain

    return uniform_strain(material, sigma.shape[0], sigma)


def test_a_small_corner_piece_with_a_frictionless_tie_slides_and_says_so():
    scene, _ = uniaxial("quad", 0.0, 0.5, "bilateral")
    scene = dataclasses.replace(scene, levelset=plane((1.95, 0.0), (1.0, 1.0)))
    with pytest.raises(SingularSystemError, match=r"Ω⁺ .* can translate along "
                       r"\(0\.707, -0\.707\)"):
        solve(scene)
