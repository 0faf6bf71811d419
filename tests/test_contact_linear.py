"""Tests for skxfem/contact/step.py: the Newton step of a frictionless or adhesive
law solved as a tie by AMG + projected CG, and a Coulomb step by FGMRES on ties,
give the direct step's answer.

1. Partly open (frictionless), pressed (adhesive) and pulled apart (both): the
   iterative path gives the direct path's statuses, Newton iterations,
   displacement and tractions, in 2D and 3D.
2. ``linear`` through the public calls: ``skxfem.solve`` and ``contact.solve``
   record the solve taken; ``auto`` takes the iterative path on a large
   frictionless scene and the direct one for Coulomb (iterative when asked).
3. Refusals: dependent multipliers and a floating side, each with the message
   of the direct path's cause.
"""
from dataclasses import replace

import numpy as np
import pytest

import skxfem
from skxfem import contact
from skxfem.fem.material import Material
from skxfem.levelset import plane
from skxfem.scene import Box, Displacement, Scene, SurfaceLoad, clamped

pytest.importorskip("pyamg")


def scene(case, dim, law, friction=None):
    """Bottom clamped, Γ across the middle, the top moved: ``partial`` turned (pressed
    at one end, opened at the other), ``compressed`` (pressed, held tangentially),
    ``pulled`` (apart, and sheared on the right face)."""
    top = {"x": 0.0} if dim == 2 else {"x": 0.0, "y": 0.0}
    up = lambda x: -0.01 * (1 - 2.5 * x[dim - 2])  # noqa: E731  (turned about 0.4)
    moves = {"partial": {**top, "yz"[dim - 2]: up}, "compressed": top,
             "pulled": {**top, "yz"[dim - 2]: 0.1}}[case]
    loads = {"partial": (), "pulled": (SurfaceLoad("xmax", traction=(0.1,) + (0.0,) * (dim - 1)),),
             "compressed": (SurfaceLoad("ymax" if dim == 2 else "zmax", pressure=1.0),)}[case]
    box = Box((4, 5), "tri") if dim == 2 else Box((1, 4, 5), "hex")
    gamma = plane((0, 0.5), (0, 1)) if dim == 2 else plane((0, 0, 0.5), (0, 0, 1))
    return Scene(box, gamma, Material(E=1.0, nu=0.3), law=law, friction=friction, loads=loads,
                 displacements=(clamped("ymin" if dim == 2 else "zmin"),
                                Displacement("ymax" if dim == 2 else "zmax", moves)))


def rel(a, b):
    return np.abs(a - b).max() / np.abs(b).max()


CASES = [("partial", "frictionless"), ("compressed", "frictionless"),
         ("compressed", "adhesive"), ("pulled", "frictionless"), ("pulled", "adhesive")]


# 1. the direct path's answer ---------------------------------------------------------

@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("case, law", CASES)
def test_the_iterative_step_gives_the_direct_answer(case, law, dim):
    s = scene(case, dim, law)
    direct, it = (contact.solve(s, linear=lin) for lin in ("direct", "iterative"))
    assert (direct.linear, it.linear) == ("direct", "iterative")
    a, b = direct.steps[-1], it.steps[-1]
    expected = {"partial": {0, 2}, "compressed": {1 if law == "adhesive" else 2},
                "pulled": {0}}[case]
    assert set(a.status) == expected, "the case must exercise open and/or closed dofs"
    assert np.array_equal(a.status, b.status)
    assert a.newton.iterations == b.newton.iterations
    assert rel(b.U, a.U) < 1e-8
    if np.abs(a.traction).max() > 0:
        assert rel(b.traction, a.traction) < 1e-8
    else:
        assert np.abs(b.traction).max() <= 1e-12 * np.abs(b.U).max()


COULOMB = [("partial", 2), ("partial", 3), ("compressed", 2), ("compressed", 3),
           ("pulled", 2), ("pulled", 3)]


@pytest.mark.parametrize("method", ["newton", "fixed_point"])
@pytest.mark.parametrize("case, dim", COULOMB)
def test_a_coulomb_step_by_fgmres_on_ties_gives_the_direct_answer(case, dim, method):
    """Coulomb (μ = 0.3): FGMRES preconditioned by the tie step, Newton or the paper's
    fixed point: the direct path's statuses, iterations and answer."""
    s = scene(case, dim, "coulomb", friction=0.3)
    direct, it = (contact.solve(s, linear=lin, method=method) for lin in ("direct", "iterative"))
    a, b = direct.steps[-1], it.steps[-1]
    expected = {"partial": {0, 2}, "compressed": {1}, "pulled": {0}}[case]
    assert set(a.status) == expected, "open, stick and slip points all occur"
    assert np.array_equal(a.status, b.status)
    assert a.newton.iterations == b.newton.iterations
    assert rel(b.U, a.U) < 1e-8
    for key in ("pressure", "traction"):
        x, y = getattr(a, key), getattr(b, key)
        assert np.abs(x - y).max() <= 1e-8 * max(np.abs(x).max(), np.abs(a.U).max())


def test_a_block_sliding_in_3d_under_friction_by_ties():
    """The 3D block of test_contact, slipping along a slanted direction (slip points with
    a 2 x 2 DP): iterative = direct."""
    mu, p, delta, phi = 0.5, 1.0, 2.0, 0.6
    d = np.array([np.cos(phi), np.sin(phi)])
    loads = [SurfaceLoad("zmax", pressure=p)]
    for face, k in (("xmax", 0), ("ymax", 1)):
        t = [0.0, 0.0, mu * p * d[k]]
        loads += [SurfaceLoad(face, traction=tuple(t)),
                  SurfaceLoad(face.replace("max", "min"), traction=(0.0, 0.0, -t[2]))]
    s = Scene(Box((1, 2, 3), "hex"), plane((0, 0, 0.5), (0, 0, 1)), Material(E=1.0, nu=0.0),
              displacements=(clamped("zmin"),
                             Displacement("zmax", {"x": delta * d[0], "y": delta * d[1]})),
              loads=tuple(loads), law="coulomb", friction=mu)
    a, b = (contact.solve(s, linear=lin).steps[-1] for lin in ("direct", "iterative"))
    assert np.all(a.status == 2) and np.array_equal(a.status, b.status)
    assert rel(b.U, a.U) < 1e-8 and rel(b.traction, a.traction) < 1e-8


# 2. the public calls ------------------------------------------------------------------

def test_linear_reaches_the_contact_solve_and_auto_follows_the_law(monkeypatch):
    s = scene("partial", 2, "frictionless")
    assert skxfem.solve(s, linear="iterative").linear == "iterative"
    assert skxfem.solve(s).linear == "direct", "auto: small scenes are solved directly"
    monkeypatch.setitem(skxfem.linalg.choice.AUTO_ITERATIVE, 2, 10)
    assert skxfem.solve(s).linear == "iterative", "auto: large frictionless scenes"
    coulomb = replace(s, law="coulomb", friction=0.3)
    assert skxfem.solve(coulomb).linear == "direct", "auto: Coulomb is solved directly"
    assert skxfem.solve(coulomb, linear="iterative").linear == "iterative", "when asked"


# 3. refusals --------------------------------------------------------------------------

def test_dependent_multipliers_are_refused_as_by_the_direct_path():
    base = replace(scene("compressed", 3, "adhesive"), mesh=Box((1, 2, 3), "tet"),
                   space="naive")
    for linear in ("direct", "iterative"):
        with pytest.raises(ValueError, match="space='vital'"):
            contact.solve(base, linear=linear)


def test_a_floating_side_is_refused():
    with pytest.raises(ValueError, match="move freely"):
        contact.solve(replace(scene("pulled", 2, "frictionless"), displacements=(
            clamped("ymin"),)), linear="iterative")
