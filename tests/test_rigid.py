"""Tests for skxfem/linalg/rigid.py: the rigid motions the supports and the law leave free.

1. A normal-only tie (bilateral, or frictionless contact) on a circle or a
   sphere leaves the inclusion free to turn: refused before any solve, direct
   or iterative, naming the side (inside Γ) and the rotation (issue 18: the
   inclusion example returned a disc turned by an arbitrary amount, max jump
   1.05).  The bonded inclusion solves.
2. The translations refused before are refused still, now naming the side
   and the direction (the strip and the paper's plate with a bilateral tie,
   a body without supports).
3. ``free_motions`` counts: as many free motions as the problem leaves; the
   sides are named inside / outside Γ when Γ encloses one of them.
4. ``short_pieces``: a piece of Γ whose stable space cannot hold what the law
   holds (a corner cut off inside one cell) gets a multiplier per edge; a long
   Γ never does.
"""
import dataclasses

import numpy as np
import pytest
import scipy.sparse as sp

from skxfem.fem.material import Material
from skxfem.levelset import plane, sphere
from skxfem.linalg.rigid import free_motions, side_names
from skxfem.linalg.saddle import SingularSystemError
from skxfem.problem import assemble
from skxfem.scene import Box, Displacement, Interface, Scene, SurfaceLoad, clamped, rollers
from skxfem.scene.benchmarks import paper_plate, strip
from skxfem.scene.file import load_scene
from skxfem.solver import solve

INCLUSION = "examples/inclusion.toml"


def inclusion(law):
    return dataclasses.replace(load_scene(INCLUSION), law=law)


# 1. rotations -----------------------------------------------------------------------

@pytest.mark.parametrize("linear", ["direct", "iterative"])
def test_a_disc_tied_by_its_normal_jump_alone_is_refused_as_free_to_turn(linear):
    with pytest.raises(SingularSystemError,
                       match=r"Ω⁻ \(the part of the body inside Γ\) can rotate about z \(about "
                             r"the point \(0\.5, 0\.5\)\): neither the displacements nor the "
                             r"bilateral tie hold it"):
        solve(inclusion("bilateral"), linear=linear)


def test_a_disc_in_frictionless_contact_is_refused_as_free_to_turn():
    """Refused before any Newton iteration: even closed everywhere, a frictionless Γ
    cannot hold the disc's rotation."""
    with pytest.raises(SingularSystemError,
                       match=r"load step 1.0: Ω⁻ \(the part of the body inside Γ\) can rotate "
                             r"about z .*frictionless law with Γ closed everywhere"):
        solve(inclusion("frictionless"), linear="direct")


def test_the_bonded_disc_is_held():
    result = solve(inclusion("bonded"))
    assert result.max_jump < 1e-2 * np.abs(result.u_minus).max()
    assert free_motions(assemble(inclusion("bonded")), full=True).shape[1] == 0


def test_a_ball_tied_by_its_normal_jump_can_turn_about_every_axis():
    scene = Scene(Box(4, "hex"), sphere((0.5, 0.5, 0.5), 0.3), Material(1.0, 0.3),
                  (clamped("zmin"),), (SurfaceLoad("zmax", pressure=1.0),), "bilateral")
    p = assemble(scene)
    assert free_motions(p, normal=True).shape[1] == 3, "three rotations of the ball"
    with pytest.raises(SingularSystemError, match=r"Ω⁻ \(the part of the body inside Γ\) "
                       r"can rotate about an axis") as err:
        solve(scene)
    assert str(err.value).count("rotate about an axis along") == 3
    assert str(err.value).count("through (0.5, 0.5, 0.5)") == 3, "about the centre"


def test_a_slightly_elliptic_disc_is_held_by_its_shape():
    """An ellipse holds the rotation of what it encloses: not refused."""
    from skxfem.levelset import LevelSet

    ellipse = LevelSet(lambda x: ((x[0] - 0.5) / 0.33) ** 2 + ((x[1] - 0.5) / 0.27) ** 2 - 1,
                       2, "ellipse")
    scene = dataclasses.replace(inclusion("bilateral"), levelset=ellipse)
    assert free_motions(assemble(scene), normal=True).shape[1] == 0
    assert np.isfinite(solve(scene).max_jump)


# 2. translations --------------------------------------------------------------------

@pytest.mark.parametrize("linear", ["direct", "iterative"])
def test_a_bilateral_strip_free_to_slide_names_the_side_and_direction(linear):
    scene = dataclasses.replace(strip(4, "tri"), law="bilateral")
    with pytest.raises(SingularSystemError, match=r"Ω⁺ \(the part of the body where ψ > 0\) "
                       r"can translate along x: .*singular"):
        solve(scene, linear=linear)


def test_the_bilateral_plate_slides_along_y():
    with pytest.raises(SingularSystemError, match=r"Ω⁺ .* can translate along y:"):
        solve(dataclasses.replace(paper_plate(3, "prism"), law="bilateral"))


@pytest.mark.parametrize("cell", ["quad", "tet"])
def test_a_body_without_supports_names_every_motion_of_the_whole_body(cell):
    dim = 2 if cell == "quad" else 3
    psi = plane((0.5,) * dim, (0.0,) * (dim - 1) + (1.0,))
    scene = Scene(Box(3, cell), psi, Material(1.0, 0.3), (),
                  (SurfaceLoad("xyz"[dim - 1] + "max", pressure=1.0),))
    p = assemble(scene)
    assert free_motions(p, full=True).shape[1] == 3 * (dim - 1)
    with pytest.raises(SingularSystemError, match="the whole body can translate in every "
                       "direction and rotate about") as err:
        solve(scene)
    assert str(err.value).count("rotate about") == 3 * (dim - 1) - dim


@pytest.mark.parametrize("linear", ["direct", "iterative"])
def test_a_free_crack_is_no_tie_in_the_message(linear):
    """A crack whose faces are free holds nothing: the body held only along z is
    refused naming the displacements alone (it read 'nor the free tie')."""
    from skfem import MeshTet1
    m = MeshTet1.init_tensor(*(np.linspace(0, 1, 5),) * 3)
    crack = Interface(plane((0.5, 0.5, 0.5), (0, 0, 1)), law="free",
                      front=plane((0.5, 0, 0), (1, 0, 0)))
    scene = Scene(m, material=Material(1.0, 0.3), interfaces=(crack,),
                  displacements=(Displacement("zmin", {"z": 0.0}),),
                  loads=(SurfaceLoad("zmax", traction=(0.0, 0.0, 1.0)),))
    with pytest.raises(SingularSystemError, match=r"the whole body can translate .*: the "
                       r"displacements do not hold it, so the problem is singular") as e:
        solve(scene, linear=linear)
    assert "tie" not in str(e.value)


def test_rollers_on_one_side_leave_the_other_free_only_where_they_do_not_reach():
    """Bottom on rollers, Γ horizontal, bilateral: Ω⁻ slides along x (rollers
    hold y only), Ω⁺ too, and the whole body with them; held at one node in x,
    the body is held, but a frictionless Γ still lets Ω⁺ slide."""
    base = Scene(Box(4, "quad"), plane((0.5, 0.55), (0.0, 1.0)), Material(1.0, 0.3),
                 (rollers("ymin"),), (SurfaceLoad("ymax", pressure=1.0),), "bilateral")
    assert free_motions(assemble(base), normal=True).shape[1] == 2
    pinned = dataclasses.replace(base, displacements=base.displacements + (
        Displacement(lambda x: (np.abs(x[0]) < 1e-12) & (np.abs(x[1]) < 1e-12), {"x": 0.0}),))
    p = assemble(pinned)
    assert free_motions(p, normal=True).shape[1] == 1
    assert free_motions(p, full=True).shape[1] == 0, "a bonded tie holds Ω⁺"


# 3. names ---------------------------------------------------------------------------

def test_sides_are_named_inside_and_outside_for_a_closed_gamma():
    minus, plus = side_names(assemble(inclusion("bonded")))
    assert "inside Γ" in minus and "outside Γ" in plus
    minus, plus = side_names(assemble(strip(3, "tri")))
    assert "ψ < 0" in minus and "ψ > 0" in plus


# 4. pieces of Γ too small for a stable space ----------------------------------------

def test_a_corner_piece_that_one_star_cannot_hold_gets_a_multiplier_per_edge():
    """Γ cuts off the corner (1, 1) inside one cell: two cut edges, one star of
    vital edges, one μ per component, whose mean jump cannot hold the corner's
    turning; the law (bonded) holds it.  short_pieces finds the piece, and the
    assembled space gives each of its edges a μ of its own."""
    from skxfem.linalg.rigid import pieces, short_pieces
    from skxfem.multipliers import coupling
    from skxfem.stabilised import multiplier_space

    scene = Scene(Box(4, "quad"), plane((1.95, 0.0), (1.0, 1.0)), Material(1.0, 0.3),
                  (clamped("ymin"),), (SurfaceLoad("ymax", pressure=1.0),))
    p = assemble(scene)
    assert p.cut.edge_ids.size == 2 and pieces(p.cut).max() == 0
    one_star = multiplier_space("vital", p.mesh, p.cut)
    assert one_star.size == 1
    q = p.interfaces[0]            # the interface's part of the problem
    loose = dataclasses.replace(q, P=sp.block_diag([one_star.P] * 2, format="csr"))
    assert short_pieces(loose, coupling(q.V, q.rule, "bonded", J=q.J)).all()
    assert p.P.shape[1] == 4 and p.multiplier_space.size == 2, "a μ per edge and component"
    assert np.isfinite(solve(scene).max_jump)


@pytest.mark.parametrize("law", ["bonded", "bilateral"])
def test_a_stable_space_on_a_long_gamma_is_never_short(law):
    from skxfem.linalg.rigid import short_pieces
    from skxfem.multipliers import coupling

    for scene in (strip(8, "tri"), strip(8, "quad"), paper_plate(3, "prism"),
                  paper_plate(3, "tet"), inclusion("bonded")):
        q = assemble(scene, law=law).interfaces[0]
        assert not short_pieces(q, coupling(q.V, q.rule, law, J=q.J)).any(), scene.name
