"""Tests for skxfem/contact/step.py: every contact Newton step solved as one tie
(AMG + projected CG, projected GMRES where the friction tilts the pressure) is
the Newton step, and the contact solves it drives give the direct answers.

1. The step: at iterates off the answer (open, stick and slip points), the
   iterative step equals the direct solve of the Newton matrix, for every
   contact law, cell type and stable space.
2. The solve: partly open (frictionless), pressed (adhesive) and pulled apart
   (both), Coulomb in 2D and 3D: the iterative path gives the direct path's
   statuses, displacement and tractions (its Newton iterations may differ by a
   few: the early steps are solved inexactly, :data:`skxfem.contact.newton.ETA`).
3. What is set up: K once per contact solve, every step carried over from it.
4. ``linear`` through the public calls.
5. Refusals: dependent multipliers and a floating side, each with the message
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


# 1. the step ------------------------------------------------------------------------

def _step_problem(s):
    """The StepProblem of scene ``s`` at its full load, its converged direct answer."""
    from skxfem.contact.history import parameters
    from skxfem.contact.interface import operators
    from skxfem.contact.newton import StepProblem, point_laws
    from skxfem.problem import assemble

    pb = assemble(s, law="bilateral")
    ops = operators(pb)
    law = parameters(s.interfaces[0], ops.h, s.material.E)
    free = np.setdiff1d(np.arange(pb.V.N), pb.D)
    step = StepProblem(ops, pb.K, pb.F, free, np.zeros(pb.V.N),
                       point_laws(law, ops.tangent_held), law.rho_n)
    return pb, step, contact.solve(s, linear="direct").steps[-1]


STEP_CASES = [(law, cell, space) for law in ("frictionless", "adhesive", "coulomb")
              for cell in ("tri", "quad", "tet", "hex", "prism")
              for space in ("vital", "winner")]


@pytest.mark.parametrize("law, cell, space", STEP_CASES)
def test_the_iterative_step_is_the_newton_step(law, cell, space):
    """J x = -R by the tie (CG, or GMRES with the tilted pressure) = SuperLU on J, to
    1e-9, at iterates scattered about the answer: open, stick and slip points."""
    import scipy.sparse.linalg as spla

    from skxfem.contact import step as linear_step
    from skxfem.contact.newton import Iterate, jacobian, residual
    from skxfem.linalg.amg import rigid_modes

    dim = 2 if cell in ("tri", "quad") else 3
    box = Box((4, 5), cell) if dim == 2 else Box((2, 3, 5), cell)
    s = replace(scene("partial", dim, law, 0.3 if law == "coulomb" else None), mesh=box,
                space=space)
    pb, step, answer = _step_problem(s)
    rng = np.random.default_rng(1)
    m, k = answer.traction.shape
    seen = set()
    for _ in range(3):
        it = Iterate(answer.U * (1 + 0.5 * rng.standard_normal(answer.U.size)),
                     -answer.pressure * (1 + rng.standard_normal(m)) - 1e-3 * rng.random(m),
                     answer.traction + 1e-3 * rng.standard_normal((m, k)))
        res = residual(step, it)
        seen |= set(res.status.tolist())
        exact = spla.spsolve(jacobian(step, it, res).tocsc(), -res.vector)
        tie, _, _ = linear_step.iterative(step, res, rigid_modes(pb.V), dim, tol=1e-13)
        assert rel(tie, exact) < 1e-9
    assert len(seen) >= 2, "the iterates must mix statuses"


# 2. the direct path's answer --------------------------------------------------------

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
    assert b.newton.iterations <= a.newton.iterations + 3, "inexact early steps: a few more"
    assert rel(b.U, a.U) < 1e-8
    if np.abs(a.traction).max() > 0:
        assert rel(b.traction, a.traction) < 1e-8
    else:
        assert np.abs(b.traction).max() <= 1e-12 * np.abs(b.U).max()


COULOMB = [("partial", 2), ("partial", 3), ("compressed", 2), ("compressed", 3),
           ("pulled", 2), ("pulled", 3)]


@pytest.mark.parametrize("method", ["newton", "fixed_point"])
@pytest.mark.parametrize("case, dim", COULOMB)
def test_a_coulomb_solve_by_ties_gives_the_direct_answer(case, dim, method):
    """Coulomb (μ = 0.3): each step one tie, its pressure tilted by the friction
    (projected GMRES), Newton or the paper's fixed point: the direct path's
    statuses and answer."""
    s = scene(case, dim, "coulomb", friction=0.3)
    direct, it = (contact.solve(s, linear=lin, method=method) for lin in ("direct", "iterative"))
    a, b = direct.steps[-1], it.steps[-1]
    expected = {"partial": {0, 2}, "compressed": {1}, "pulled": {0}}[case]
    assert set(a.status) == expected, "open, stick and slip points all occur"
    assert np.array_equal(a.status, b.status)
    assert b.newton.iterations <= a.newton.iterations + 3, "inexact early steps: a few more"
    assert rel(b.U, a.U) < 1e-8
    for key in ("pressure", "traction"):
        x, y = getattr(a, key), getattr(b, key)
        assert np.abs(x - y).max() <= 1e-8 * max(np.abs(x).max(), np.abs(a.U).max())


@pytest.mark.parametrize("mu", [0.3, 1.0, 2.0, 5.0])
def test_a_block_pushed_exactly_to_its_slip_limit_by_ties(mu):
    """Issue 27 item 5: the 3D block of test_contact_newton pushed exactly to the slip
    limit |r_τ| = μp (no slip): the iterates come within 1e-8 of the kink |y| = R,
    where the sliding stiffness ρ_τ/w (|y|/R - 1)⁻¹ stalled projected CG (every ρ, every
    μ); that step is taken again with the slip branch's derivative at the kink, the jump
    across the slip tied (skxfem.contact.step.KINK).  At the default ρ, ρ_n = 1e-2 E/h
    and ρ_τ = 1e-3 E/h: the exact state to 1e-8 in at most 10 iterations, neither
    rescued nor cut, while points flip between stick and slip on the limit."""
    import sys
    import warnings
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).parent))
    from test_contact_newton import CASES, errors

    from skxfem.scene.benchmarks import uniform_block

    sol, drive = CASES["at the limit"](3, mu)
    base = uniform_block(sol, n=3, mu=mu, drive=drive)
    h = 1.0 / 3
    for rho in ((1.0, 1.0), (1e-2, 1.0), (1.0, 1e-3)):
        s = replace(base, rho_n=rho[0] * base.material.E / h, rho_t=rho[1] * base.material.E / h)
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # no retry, no cut
            res = contact.solve(s, linear="iterative")
        st = res.steps[-1]
        assert res.linear == "iterative"
        assert max(errors(sol, res)) < 1e-8, rho
        assert st.newton.rescued == 0 and st.increments == 1 and st.newton.iterations <= 10
        assert np.all(np.linalg.norm(st.traction, axis=1)
                      <= mu * st.pressure * (1 + 1e-10) + 1e-14)


def test_the_step_at_the_kink_is_the_newton_step_of_that_linearisation(monkeypatch):
    """The fallback step (skxfem.contact.step.KINK): at points a relative 1e-6 past the
    slip limit, the tie with the jump across the slip tied equals SuperLU on the Newton
    matrix built with the same derivative at the kink, to 1e-9."""
    import functools
    import sys
    from pathlib import Path

    import scipy.sparse.linalg as spla

    sys.path.insert(0, str(Path(__file__).parent))
    from test_contact_newton import CASES

    from skxfem.contact import newton as contact_newton
    from skxfem.contact import step as linear_step
    from skxfem.contact.newton import Iterate, jacobian, residual
    from skxfem.linalg.amg import rigid_modes
    from skxfem.scene.benchmarks import uniform_block

    sol, drive = CASES["at the limit"](3, 2.0)
    pb, step, answer = _step_problem(uniform_block(sol, n=3, mu=2.0, drive=drive))
    rng = np.random.default_rng(2)
    U = answer.U.copy()
    U[step.free] += 1e-9 * rng.standard_normal(step.free.size)
    it = Iterate(U, -answer.pressure, answer.traction * (1 + 1e-6))
    res = residual(step, it)
    y, R = np.linalg.norm(res.y, axis=1), res.radius
    near = (y > R) & (y <= (1 + linear_step.KINK) * R)
    assert near.sum() >= 4, "points just past the slip limit"
    tie, _, _ = linear_step.iterative(step, res, rigid_modes(pb.V), 3, tol=1e-13,
                                      kink=linear_step.KINK)
    monkeypatch.setattr(contact_newton.linear_step, "linearised",
                        functools.partial(linear_step.linearised, kink=linear_step.KINK))
    exact = spla.spsolve(jacobian(step, it, res).tocsc(), -res.vector)
    assert rel(tie, exact) < 1e-9


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


# 3. what is set up -------------------------------------------------------------------

@pytest.mark.parametrize("law", ["coulomb", "frictionless", "adhesive"])
def test_k_is_set_up_once_per_contact_solve(monkeypatch, law):
    """The AMG hierarchy of K is built once per contact solve, however many load steps
    and Newton iterations; every step's tie is carried over from it (a Galerkin
    update of its interface rows), none is set up anew."""
    import skxfem.linalg.amg as amg
    import skxfem.linalg.iterative as iterative

    built, anew, carried = [], [], []
    real_amg, real_setup, real_carried = amg.amg, iterative._setup, iterative._carried
    monkeypatch.setattr(iterative, "amg", lambda *a: built.append(1) or real_amg(*a))
    monkeypatch.setattr(iterative, "_setup", lambda *a: anew.append(1) or real_setup(*a))
    monkeypatch.setattr(iterative, "_carried",
                        lambda *a: carried.append(1) or real_carried(*a))
    s = replace(scene("partial", 3, law, 0.3 if law == "coulomb" else None),
                steps=(0.25, 0.5, 0.75, 1.0))
    res = contact.solve(s, linear="iterative")
    iterations = sum(st.newton.iterations for st in res.steps)
    assert iterations >= 3, "several Newton iterations over the load steps"
    assert (len(built), len(anew)) == (1, 0), "K's AMG once, no tie set up anew"
    assert 1 <= len(carried) <= iterations, "each step carried over (or reused)"
    direct = contact.solve(s, linear="direct")
    assert rel(res.steps[-1].U, direct.steps[-1].U) < 1e-8


# 4. the public calls ------------------------------------------------------------------

def test_linear_reaches_the_contact_solve_and_auto_follows_the_size(monkeypatch):
    s = scene("partial", 2, "frictionless")
    assert skxfem.solve(s, linear="iterative").linear == "iterative"
    assert skxfem.solve(s).linear == "direct", "auto: small scenes are solved directly"
    monkeypatch.setitem(skxfem.linalg.choice.AUTO_ITERATIVE, 2, 10)
    assert skxfem.solve(s).linear == "iterative", "auto: large frictionless scenes"
    coulomb = replace(s, law="coulomb", friction=0.3)
    assert skxfem.solve(coulomb).linear == "iterative", "auto: large scenes, every law"
    assert skxfem.solve(coulomb, linear="direct").linear == "direct", "when asked"


# 5. refusals --------------------------------------------------------------------------

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
