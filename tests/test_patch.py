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

from skxfem.levelset import LevelSet, plane
from skxfem.material import Material
from skxfem.saddle import SingularSystemError
from skxfem.scene import Box, Displacement, Scene, SurfaceLoad, rollers
from skxfem.solver import solve

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
