"""Unilateral contact and Coulomb friction (skxfem.contact) against known answers."""
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse as sp

from skxfem import contact, solver
from skxfem.contact.newton import ContactConvergenceError
from skxfem.enrich import split_fields
from skxfem.fem.material import Material
from skxfem.levelset import plane
from skxfem.linalg import saddle
from skxfem.scene import Box, Displacement, Scene, SurfaceLoad, clamped
from skxfem.scene.benchmarks import strip

RHOS = (1e-3, 1.0, 1e6)  # × E/h


def held_top(scene, comps=("x",)):
    """``scene`` with the top held tangentially: a frictionless Γ would let it slide."""
    top = "ymax" if scene.dim == 2 else "zmax"
    return replace(scene, displacements=scene.displacements
                   + (Displacement(top, {c: 0.0 for c in comps}),))


def mu_of(law, mu):
    """The ``friction`` of a scene with ``law``: μ for coulomb, unset for the others."""
    return mu if law == "coulomb" else None


def cube(n=(1, 2, 3), law="frictionless", top=None, loads=(), mu=None, nu=0.3, **kw):
    """Unit cube, Γ at z = 0.5, bottom clamped, top displacement ``top``."""
    disp = (clamped("zmin"),) + ((Displacement("zmax", top),) if top else ())
    return Scene(Box(n, "hex"), plane((0, 0, 0.5), (0, 0, 1)), Material(E=1.0, nu=nu),
                 displacements=disp, loads=tuple(loads), law=law, friction=mu_of(law, mu),
                 **kw)


def compressed(dim):
    if dim == 2:
        return held_top(strip(n=4))
    return cube(top={"x": 0.0, "y": 0.0},
                loads=(SurfaceLoad("zmax", pressure=lambda x: 1.0 + x[1]),))


def rel(a, b):
    return np.abs(a - b).max() / np.abs(b).max()


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("law, tie", [("frictionless", "bilateral"), ("adhesive", "bonded")])
def test_compression_equals_the_tie(dim, law, tie):
    """Pressed everywhere, frictionless = bilateral and adhesive = bonded, for every ρ."""
    base = compressed(dim)
    ref = solver.solve(replace(base, law=tie))
    h = contact.solve(replace(base, law=law)).ops.h
    for rho in RHOS:
        res = contact.solve(replace(base, law=law, rho_n=rho / h, rho_t=rho / h))
        step = res.steps[-1]
        assert np.all(step.status == (1 if law == "adhesive" else 2))
        assert rel(step.U, ref.U) < 1e-8
        assert rel(step.pressure, ref.pressure) < 1e-8  # naive space: dofs = edges
        if law == "adhesive":
            t = res.ops.tangents  # (k, dim): the traction's components
            assert rel(step.traction, (t @ ref.traction).T) < 1e-8
        assert step.newton.iterations <= 15


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("law", ["frictionless", "coulomb", "adhesive"])
def test_tension_opens_the_interface(law, dim):
    """Pulled apart: λ = 0 everywhere and u is that of two bodies with a free cut."""
    if dim == 2:
        s = replace(strip(n=3), loads=(SurfaceLoad("xmax", traction=(0.1, 0.0)),),
                    displacements=(clamped("ymin"),
                                   Displacement("ymax", {"x": 0.0, "y": 0.1})))
    else:
        s = cube(top={"x": 0.0, "y": 0.0, "z": 0.1},
                 loads=(SurfaceLoad("xmax", traction=(0.1, 0.0, 0.0)),))
    res = contact.solve(replace(s, law=law, friction=mu_of(law, 0.5)))
    step = res.steps[-1]
    assert np.all(step.pressure == 0) and np.all(step.status == 0)
    assert np.all(step.gap < 0)
    pb = res.problem
    free_cut, _, _ = saddle.solve(pb.K, pb.B[:0], pb.F, pb.D, pb.g)
    assert rel(step.U, free_cut) < 1e-10
    u_minus, u_plus = split_fields(pb.V, step.U)
    top = pb.mesh.p[dim - 1] > 0.99
    assert np.allclose(u_plus[dim - 1, top], 0.1)


def partial(rho=None, n=6, delta=0.01, dim=2):
    """Top turned: pressed near x = 0 (3D: y = 0), opened near x = 1."""
    if dim == 3:
        return cube(n=(1, 4, 5), rho_n=rho, top={
            "x": 0.0, "y": 0.0, "z": lambda x: -delta * (1 - 2 * x[1])})
    s = strip(n=n)
    return replace(s, law="frictionless", loads=(), rho_n=rho, displacements=(
        clamped("ymin"), Displacement("ymax", {"x": 0.0, "y": lambda x: -delta * (1 - 2 * x[0])})))


@pytest.mark.parametrize("dim", [2, 3])
def test_partial_contact_signorini_at_every_dof(dim):
    h = contact.solve(partial(dim=dim)).ops.h
    for rho in RHOS:
        st = contact.solve(partial(rho / h, dim=dim)).steps[-1]
        scale = st.pressure.max() * np.abs(st.gap).max()
        assert set(st.status) == {0, 2}  # open and (frictionless) sliding points
        assert st.pressure.min() >= 0 and st.gap.max() <= 1e-12 * np.abs(st.gap).max()
        assert np.abs(st.pressure * st.gap).max() <= 1e-12 * scale
        assert st.newton.iterations <= 15


def block(n=3, mu=0.5, p=1.0, delta=0.0, tau=0.0, law="coulomb", name="block"):
    """ν = 0 block: bottom clamped, top moved by δ in x under a pressure p.  With ν = 0
    the exact field is uniform shear τ and compression p in each body plus a slip s
    on Γ (u_x(top) = τ/G + s = δ); the sides carry the shear τ of that field."""
    loads = (SurfaceLoad("ymax", pressure=p), SurfaceLoad("xmax", traction=(0.0, tau)),
             SurfaceLoad("xmin", traction=(0.0, -tau)))
    return Scene(Box((n, n), "quad"), plane((0, 0.5), (0, 1)), Material(E=1.0, nu=0.0),
                 displacements=(clamped("ymin"), Displacement("ymax", {"x": delta})),
                 loads=loads, law=law, friction=mu_of(law, mu), name=name)


def test_block_sticks_then_slides():
    """τ = Gδ (stick) while Gδ < μp; then τ = μp and s = δ - μp/G."""
    G, mu, p = 0.5, 0.5, 1.0
    for delta in (0.5, 0.9, 1.5, 3.0):
        tau = min(G * delta, mu * p)
        st = contact.solve(block(mu=mu, p=p, delta=delta, tau=tau)).steps[-1]
        slip = delta - tau / G
        assert np.all(st.status == (1 if slip == 0 else 2))
        assert np.allclose(st.pressure, p, rtol=1e-10)
        assert np.allclose(st.traction, tau, rtol=1e-10)
        assert np.allclose(-st.slip, slip, atol=1e-10)  # [[u]] = u⁻ - u⁺


def test_load_history_press_shear_unload():
    """δ: 0 → 2.5 (slip) → 0 (elastic unloading, then reverse slip); by hand, μp = 0.5,
    G = 0.5: slip while |τ| = μp, s = δ - τ/G; the retained slip is 1."""
    G, mu, p = 0.5, 0.5, 1.0
    path = [  # δ, τ, status, slip: stick, slip, elastic unloading, reverse slip
        (0.0, 0.0, 1, 0.0), (0.5, 0.25, 1, 0.0), (1.5, 0.5, 2, 0.5), (2.5, 0.5, 2, 1.5),
        (1.5, 0.0, 1, 1.5), (0.75, -0.375, 1, 1.5), (0.0, -0.5, 2, 1.0)]
    for d, t, status, slip in path:  # the hand path is consistent
        assert abs(t) <= mu * p and slip == d - t / G
    states = [block(mu=mu, p=p, delta=d, tau=t, name=f"delta={d}") for d, t, _, _ in path]
    res = contact.solve(states[0], history=states)
    for (d, t, status, slip), st in zip(path, res.steps):
        assert st.load == f"delta={d}"
        assert np.all(st.status == status), (d, st.status)
        assert np.allclose(st.traction, t, atol=1e-10)
        assert np.allclose(-st.slip, slip, atol=1e-10)
    assert np.allclose(-res.steps[-1].slip, 1.0, atol=1e-10)
    assert max(st.newton.iterations for st in res.steps) <= 15


@pytest.mark.parametrize("phi", [0.0, 0.6])
def test_block_3d_slides_along_the_imposed_direction(phi):
    """δ at angle φ to x: the slip and the traction μp point along δ."""
    G, mu, p, delta = 0.5, 0.5, 1.0, 2.0
    tau, d = mu * p, np.array([np.cos(phi), np.sin(phi)])
    loads = [SurfaceLoad("zmax", pressure=p)]
    for face, k in (("xmax", 0), ("ymax", 1)):
        t = [0.0, 0.0, tau * d[k]]
        loads += [SurfaceLoad(face, traction=tuple(t)),
                  SurfaceLoad(face.replace("max", "min"), traction=(0.0, 0.0, -t[2]))]
    s = cube(law="coulomb", mu=mu, nu=0.0, loads=loads,
             top={"x": delta * d[0], "y": delta * d[1]})
    res = contact.solve(s)
    st = res.steps[-1]
    t = res.ops.tangents[:, :2]  # tangents in the plane z = const
    assert np.all(st.status == 2)
    assert np.allclose(st.pressure, p, rtol=1e-9)
    assert np.allclose(st.traction @ t, tau * d, atol=1e-9)
    assert np.allclose(-st.slip @ t, (delta - tau / G) * d, atol=1e-9)


def slanted(theta, mu, dim):
    """Uniaxial compression σ = 1 across a plane Γ at angle θ to the horizontal."""
    c, s = np.cos(theta), np.sin(theta)
    if dim == 2:
        corner = lambda x: (x[0] < 1e-12) & (x[1] < 1e-12)  # noqa: E731
        return Scene(Box((5, 5), "quad"), plane((0.5, 0.45), (-s, c)), Material(E=1.0, nu=0.3),
                     displacements=(Displacement("ymin", {"y": 0.0}),
                                    Displacement(corner, {"x": 0.0})),
                     loads=(SurfaceLoad("ymax", pressure=1.0),), law="coulomb", friction=mu)
    corner = lambda x: (x[0] < 1e-12) & (x[1] < 1e-12)  # noqa: E731
    other = lambda x: (x[0] > 1 - 1e-12) & (x[1] < 1e-12) & (x[2] < 1e-12)  # noqa: E731
    return Scene(Box((3, 1, 3), "hex"), plane((0.5, 0.5, 0.45), (-s, 0, c)),
                 Material(E=1.0, nu=0.3),
                 displacements=(Displacement("zmin", {"z": 0.0}),
                                Displacement(corner, {"x": 0.0, "y": 0.0}),
                                Displacement(other, {"y": 0.0})),
                 loads=(SurfaceLoad("zmax", pressure=1.0),), law="coulomb", friction=mu)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("mu", [0.6, 1.0, 2.0])
def test_slanted_interface_sticks(mu, dim):
    """Uniaxial σ across Γ at θ (tan θ < μ): p = σcos²θ, |r_τ| = σ cosθ sinθ,
    |Λ| = tanθ/μ, no slip."""
    theta, sigma = np.deg2rad(25.0), 1.0
    c, s = np.cos(theta), np.sin(theta)
    st = contact.solve(slanted(theta, mu, dim)).steps[-1]
    assert np.all(st.status == 1)
    assert np.allclose(st.pressure, sigma * c**2, rtol=1e-9)
    assert np.allclose(np.linalg.norm(st.traction, axis=1), sigma * c * s, rtol=1e-9)
    assert np.allclose(np.linalg.norm(st.Lambda, axis=1), np.tan(theta) / mu, rtol=1e-9)
    assert np.abs(st.slip).max() < 1e-12


def test_bad_input_is_refused():
    base = held_top(strip(n=3))
    with pytest.raises(ValueError, match="friction"):
        replace(base, law="coulomb", friction=-0.1)
    for key in ("rho_n", "rho_t"):
        with pytest.raises(ValueError, match=key):
            replace(base, law="coulomb", friction=0.3, **{key: 0.0})
    with pytest.raises(ValueError, match="law must be one of"):
        replace(base, law="glue")
    with pytest.raises(ValueError, match="scene law must be one of"):
        contact.solve(base)  # a tie law
    with pytest.raises(ValueError, match="history must be a non-empty"):
        contact.solve(replace(base, law="frictionless"), history=())
    with pytest.raises(ValueError, match=r"history\[1\]"):
        contact.solve(replace(base, law="frictionless"), history=(1.0, "x"))
    with pytest.raises(ValueError, match="method"):
        contact.solve(replace(base, law="frictionless"), method="penalty")
    for key, value in (("rho_n", 1e300), ("rho_t", 1e-300)):  # was "matrix singular"
        with pytest.raises(ValueError, match=rf"scene {key} = .* x its default .*augmentation"):
            contact.solve(replace(base, law="coulomb", friction=0.3, **{key: value}))
    for bad in (True, 0, 2.0):  # True was taken for 1 iteration
        with pytest.raises(ValueError, match="max_iter must be a positive integer"):
            contact.solve(replace(base, law="frictionless"), max_iter=bad)
    moved = replace(base, law="frictionless", displacements=base.displacements
                    + (Displacement("xmin", {"x": 0.0}),))
    with pytest.raises(ValueError, match=r"history\[1\]: a load state must keep"):
        contact.solve(replace(base, law="frictionless"), history=(1.0, moved))


def test_non_convergence_raises_a_clear_error():
    with pytest.raises(ContactConvergenceError, match=r"did not converge in 1 iterations.*"
                       r"equilibrium .* contact .* friction"):
        contact.solve(partial(), max_iter=1)


def test_a_floating_side_is_refused():
    with pytest.raises(ValueError, match="singular"):
        contact.solve(replace(strip(n=3), law="frictionless"))


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("law", ["coulomb", "adhesive"])
def test_an_unloaded_side_held_only_by_an_open_interface_is_refused(law, dim):
    """No load, the top held normally only: Newton's first (bonded) iterate U = 0 opens
    every point, and the top may then slide by any amount; a state that does not
    determine U is refused, not returned."""
    s = cube(law=law, mu=0.3, top={"z": 0.0}) if dim == 3 else replace(
        strip(n=3), law=law, friction=mu_of(law, 0.3),
        displacements=(clamped("ymin"), Displacement("ymax", {"y": 0.0})))
    with pytest.raises(saddle.SingularSystemError, match=r"load step 1.0: Ω⁺ .* can translate "
                       r"(along x|in every direction normal to z).*the contact state found "
                       r"\(\d+ open, 0 stick, 0 slip .*not unique.*add supports"):
        contact.solve(s, linear="direct")
    held = held_top(s, ("x", "y")[:dim - 1])  # the same with the top held: U = 0, open
    st = contact.solve(held, linear="direct").steps[-1]
    assert np.all(st.status == 0) and np.abs(st.U).max() == 0


def tilted_block(mu, delta, n):
    """Strip pressed by p = 1 whose top is moved by δ in x: friction tilts the pressure."""
    return replace(strip(n=n), law="coulomb", friction=mu,
                   loads=(SurfaceLoad("ymax", pressure=1.0),),
                   displacements=(clamped("ymin"), Displacement("ymax", {"x": delta})))


def test_fixed_point_agrees_with_newton_where_it_converges():
    s = tilted_block(mu=0.5, delta=2.0, n=4)
    a = contact.solve(s).steps[-1]
    b = contact.solve(s, method="fixed_point").steps[-1]
    assert set(a.status) == {0, 1, 2}  # open, stick and slip points
    assert np.array_equal(a.status, b.status)
    assert rel(b.U, a.U) < 1e-9 and rel(b.traction, a.traction) < 1e-9


def test_fixed_point_fails_where_friction_moves_the_pressure_and_stops_with_a_wrong_force():
    """μ = 5, the top pushed 5 sideways: the bonded start's threshold μp is frozen at
    points that must open, and the first pass does not settle (the module notes of
    skxfem.contact.fixed_point); Newton solves it.  The last state of the pass,
    which a code stopping after a fixed number of passes would return, has the
    wrong friction force."""
    s = tilted_block(mu=5.0, delta=5.0, n=4)
    res = contact.solve(s)
    st, w = res.steps[-1], res.ops.w
    assert set(st.status) == {0, 1, 2} and st.newton.iterations <= 15
    force = w @ st.traction[:, 0]
    assert abs(w @ st.pressure - 1.0) < 1e-12, "the pressure balances the load"
    with pytest.raises(ContactConvergenceError, match="fixed point on the friction "
                       "threshold failed in pass 1") as e:
        contact.solve(s, method="fixed_point")
    it, _, _ = e.value.last
    wrong = w @ it.r[:, 0]
    assert abs(wrong - force) > 0.01 * abs(force)
    assert len(e.value.thresholds) == 1, "the threshold of the bonded start"


def test_fixed_point_starts_from_the_bonded_state():
    """A block on a slanted Γ with free sides, held sideways by friction alone: a
    frictionless first pass would leave it free to slide; the bonded start's
    threshold holds it, and the passes reach the exact (sticking) state."""
    from skxfem.scene.benchmarks import uniaxial, uniform_block

    sol = uniaxial(2, tilt=0.2)
    s = uniform_block(sol, n=3, mu=0.5, drive="free")
    a, b = (contact.solve(s, method=m).steps[-1] for m in ("newton", "fixed_point"))
    assert np.all(b.status == 1) and np.array_equal(a.status, b.status)
    assert rel(b.U, a.U) < 1e-9
    assert np.allclose(b.pressure, sol.pressure, rtol=1e-9)


@pytest.mark.parametrize("cell, space", [("tri", "winner"), ("tri", "vital"),
                                         ("tet", "vital")])
def test_stabilised_spaces_give_the_tie(cell, space):
    """The same prolongation P carries λ and Λ: contact on a stable space = its tie."""
    base = compressed(2 if cell == "tri" else 3)
    base = replace(base, mesh=replace(base.mesh, cell=cell), space=space)
    for law, tie in (("frictionless", "bilateral"), ("adhesive", "bonded")):
        ref = solver.solve(replace(base, law=tie))
        res = contact.solve(replace(base, law=law))
        st = res.steps[-1]
        assert rel(st.U, ref.U) < 1e-8
        assert rel(res.problem.P @ st.pressure, ref.pressure) < 1e-8


def test_dependent_multipliers_are_refused():
    base = replace(compressed(3), mesh=Box((1, 2, 3), "tet"), space="naive")
    with pytest.raises(ValueError, match="space='vital'"):
        contact.solve(replace(base, law="adhesive"))


def test_scene_file_keys(tmp_path):
    from skxfem.scene.file import load_scene

    text = """
[mesh]
box = {n = [3, 3], cell = "quad"}
[levelset]
plane = {point = [0, 0.5], normal = [0, 1]}
[[displacement]]
boundary = "ymin"
kind = "clamped"
[[displacement]]
boundary = "ymax"
x = 0.0
[[load]]
boundary = "ymax"
pressure = 1.0
[interface]
law = "coulomb"
friction = 0.3
rho_n = 5.0
steps = [0.5, 1.0]
"""
    f = tmp_path / "press.toml"
    f.write_text(text)
    s = load_scene(f)
    assert (s.law, s.friction, s.rho_n, s.rho_t, s.steps) == ("coulomb", 0.3, 5.0, None,
                                                               (0.5, 1.0))
    res = contact.solve(s)
    assert [st.load for st in res.steps] == [0.5, 1.0]
    assert np.allclose(res.steps[1].pressure, 2 * res.steps[0].pressure)
    for old, bad in (("friction = 0.3", "friction = -0.1"), ("rho_n = 5.0", "rho_t = 0"),
                     ("steps = [0.5, 1.0]", "steps = []"), ('law = "coulomb"', 'law = "glue"')):
        f.write_text(text.replace(old, bad))
        with pytest.raises(ValueError, match=r"\[interface\] " + bad.split()[0]):
            load_scene(f)


def roughness(res):
    """Largest deviation of the edge pressures from a quadratic fit in (x, y)."""
    p = res.problem.P @ res.steps[-1].pressure
    x, y = res.problem.cut.points[:2]
    A = np.stack([np.ones_like(y), y, y**2, x, x**2, x * y], axis=1)
    return np.abs(p - A @ np.linalg.lstsq(A, p, rcond=None)[0]).max()


def test_lbb_story_holds_through_the_contact_solver():
    """The paper's plate on prisms, adhesive (its top pressure only; the bottom clamped
    holds both halves): naive oscillates, vital is smooth, each equal to its bonded tie;
    the iterations stay ≤ 15 over ρ_n."""
    from skxfem.scene.benchmarks import paper_plate

    rough = {}
    for space in ("naive", "vital"):
        s = replace(paper_plate(n=4, cell="prism", space=space),
                    displacements=(clamped("zmin"),))
        ref = solver.solve(s)
        res = contact.solve(replace(s, law="adhesive"))
        assert rel(res.steps[-1].U, ref.U) < 1e-8
        rough[space] = roughness(res)
    assert rough["naive"] > 0.5 and rough["vital"] < 0.1, rough
    for rho in RHOS:
        res = contact.solve(replace(s, law="adhesive", rho_n=rho / res.ops.h))
        assert res.steps[-1].newton.iterations <= 15


def test_contact_zone_edge_converges():
    """The edge of the contact zone lies between the last closed and the first open dof;
    these brackets nest as the mesh is refined and hold the edge of a fine mesh (n = 64)."""
    brackets = []
    for n in (8, 16, 32, 64):
        res = contact.solve(partial(n=n))
        x = res.ops.points[0]
        order = np.argsort(x)
        closed = res.steps[-1].status[order] > 0
        k = np.flatnonzero(closed).max()
        assert closed[:k + 1].all() and not closed[k + 1:].any()  # one contact zone
        brackets.append((x[order][k], x[order][k + 1]))
    fine = np.mean(brackets[-1])
    for (a, b), (c, d) in zip(brackets, brackets[1:]):
        assert a - 1e-12 <= c and d <= b + 1e-12  # nested
        assert a <= fine <= b
    assert brackets[-1][1] - brackets[-1][0] < 0.02


def test_coulomb_does_not_depend_on_rho():
    """Open, stick and slip points at once: the same solution for ρ_n, ρ_τ over 1e-3..1e6
    × E/h, in at most 15 iterations at the default ρ and 30 at any (at ρ_n = 1e-3, the
    first Newton attempt may stall and the fixed point take over: ``rescued``)."""
    s = tilted_block(mu=0.5, delta=2.0, n=4)
    first = contact.solve(s)
    ref, h = first.steps[-1], first.ops.h
    assert set(ref.status) == {0, 1, 2} and ref.newton.iterations <= 15
    for rho_n in RHOS:
        for rho_t in RHOS:
            st = contact.solve(replace(s, rho_n=rho_n / h, rho_t=rho_t / h)).steps[-1]
            assert np.array_equal(st.status, ref.status)
            assert rel(st.U, ref.U) < 1e-8 and rel(st.traction, ref.traction) < 1e-8
            assert st.newton.iterations <= 30 and st.newton.rescued <= 30


# --- issue 17: supports, load histories with laws, one result --------------------------

@pytest.mark.parametrize("cell", ["hex", "prism", "tet"])
@pytest.mark.parametrize("space", ["vital", "winner"])
@pytest.mark.parametrize("law", ["adhesive", "coulomb"])
@pytest.mark.parametrize("n", [3, 5])
def test_the_paper_plate_with_its_rollers_sticks_as_the_bonded_tie(cell, space, law, n):
    """Γ crosses the faces x = 0, 1 that carry rollers: each tangent gets the space the
    tie gives that component (on tetrahedra its rebuilt stars placed at normal dofs),
    so the sticking plate is the bonded tie exactly."""
    from skxfem.scene.benchmarks import paper_plate

    s = paper_plate(n, cell=cell, space=space)
    tie = solver.solve(s, linear="direct")
    res = contact.solve(replace(s, law=law, friction=mu_of(law, 1.0)), linear="direct")
    st = res.steps[-1]
    assert np.all(st.status == 1) and st.newton.iterations <= 2
    assert rel(st.U, tie.U) < 1e-12
    assert rel(res.pressure, tie.pressure) < 1e-12 and rel(res.traction, tie.traction) < 1e-12
    assert res.ops.tangent_held[:, 0].sum() > 0, "the rollers hold the tangent e_x"
    assert not res.ops.tangent_held[:, 1].any(), "nothing holds e_y"


@pytest.mark.parametrize("space", ["vital", "winner"])
@pytest.mark.parametrize("n", [3, 4, 6])
def test_on_tetrahedra_a_held_tangent_has_the_ties_space_placed_at_normal_dofs(space, n):
    """The tie's space of u_x with the rollers' nodes fixed is not a subset of the normal
    one on tetrahedra; its multipliers are placed one per normal dof, each on a dof
    whose function overlaps its own, and the dofs left carry no r_τ1."""

    from skxfem.contact.interface import operators
    from skxfem.problem import assemble
    from skxfem.scene.benchmarks import paper_plate

    s = paper_plate(n, cell="tet", space=space)
    tie_x = assemble(s, law="bonded").component_spaces[0].P
    ops = operators(assemble(s, law="bilateral"))
    Pt = sp.csc_matrix(ops.Pt[0])
    placed = np.flatnonzero(~ops.tangent_held[:, 0])
    assert placed.size == tie_x.shape[1] < ops.w.size
    assert abs(Pt[:, ops.tangent_held[:, 0]]).sum() == 0
    own = Pt[:, placed]  # the tie's own columns, in another order: Σ col colᵀ agrees
    assert abs(own @ own.T - tie_x @ tie_x.T).max() < 1e-14
    P = abs(sp.csc_matrix(assemble(s, law="bilateral").P))
    assert np.all((abs(Pt[:, placed]).multiply(P[:, placed])).sum(axis=0) > 0), "overlap"
    assert np.array_equal(ops.tangent_held[:, 1], np.zeros(ops.w.size, bool))


def tilted_plate(cell, n, degrees=11.3):
    """The paper's plate with Γ tilted about e_y: the rollers on x = 0, 1 hold
    [[u]]·e_x = sin θ [[u]]·n + cos θ [[u]]·t₁, neither the normal nor a tangent."""
    from skxfem.scene.benchmarks import paper_plate

    t = np.deg2rad(degrees)
    return replace(paper_plate(n, cell, nx=2),
                   levelset=plane((0.5, 0.5, 0.5), (np.sin(t), 0.0, np.cos(t))))


def stick_dependencies(pb, ops):
    """The number of sticking contact multipliers that depend on the others."""
    from skxfem.contact.interface import sticking_rows
    from skxfem.linalg.dependent import dependencies, unit_rows

    free = np.setdiff1d(np.arange(pb.V.N), pb.D)
    rows, _ = sticking_rows(ops.Bn, ops.Bt, ops.tangent_held)
    return dependencies(unit_rows(rows[:, free])[0]).shape[1]


@pytest.mark.parametrize("cell,n", [("hex", 3), ("hex", 5), ("prism", 3), ("tet", 3),
                                    ("tet", 5)])
def test_rollers_that_hold_neither_the_normal_nor_a_tangent(cell, n):
    """Beside the rollers t₁'s jump follows the normal one, so t₁ is held there
    (held_with_normal) and gets the tie's space of a component held at those nodes:
    no multiplier is left undetermined (there were 4-6), β_h of the sticking contact
    is the tie's within 2 %, the plate sticks and its displacement is the tie's
    within the discretisation (measured ≤ 3.1e-3 of its largest value here)."""
    from skxfem.contact.interface import operators
    from skxfem.lbb import inf_sup
    from skxfem.problem import assemble

    s = tilted_plate(cell, n)
    pb = assemble(s, law="bilateral")
    ops = operators(pb)
    assert ops.tangent_held[:, 0].any() and not ops.tangent_held[:, 1].any()
    assert stick_dependencies(pb, ops) == 0
    stick, tie = inf_sup(s, law="stick"), inf_sup(s, law="bonded")
    assert stick.n_zero == 0 and abs(stick.beta - tie.beta) < 0.02 * tie.beta
    res = contact.solve(replace(s, law="adhesive"), linear="direct")
    assert np.all(res.steps[-1].status == 1)
    assert rel(res.steps[-1].U, solver.solve(s, linear="direct").U) < 5e-3


def test_tangential_dofs_that_depend_on_the_others_are_released(monkeypatch):
    """Without held_with_normal (the normal space for t₁ on the tilted plate), 4
    sticking multipliers depend on the others; release_dependent releases as many
    tangential dofs, never a normal one, and none is left."""
    import skxfem.contact.interface as interface
    from skxfem.problem import assemble

    pb = assemble(tilted_plate("hex", 3), law="bilateral")
    monkeypatch.setattr(interface, "held_with_normal",
                        lambda fixed, cut, d, tol=1e-8: np.zeros(fixed.shape[1], bool))
    with monkeypatch.context() as m:
        m.setattr(interface, "release_dependent", lambda pb, Bt, held: held)
        raw = interface.operators(pb)
    assert not raw.tangent_held.any() and stick_dependencies(pb, raw) == 4
    ops = interface.operators(pb)
    assert ops.tangent_held.sum() == 4 and stick_dependencies(pb, ops) == 0
    assert (ops.Bn != raw.Bn).nnz == 0


def test_a_contact_through_a_row_of_nodes_is_exact_and_one_near_it_warns_once():
    """Γ through the nodes z = 0.5 of a pressed cube (ν = 0: a uniform stress), solved
    over a load history: no warning, the pressure is the load, p = 1, at every dof to
    round-off.  Γ 1e-12 h above them: the nodes are put on Γ once (one SnapWarning for
    the whole solve, not one per state), the same answer."""
    import warnings

    from skxfem.cut import SnapWarning

    for z, warned in ((0.5, 0), (0.5 + 2.5e-13, 1)):
        s = Scene(Box((2, 2, 4), "hex"), plane((0, 0, z), (0, 0, 1)), Material(1.0, 0.0),
                  displacements=(clamped("zmin"), Displacement("zmax", {"x": 0.0, "y": 0.0})),
                  loads=(SurfaceLoad("zmax", pressure=1.0),), law="coulomb", friction=0.5)
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            res = contact.solve(s, history=(0.5, 1.0))
        assert sum(issubclass(w.category, SnapWarning) for w in record) == warned
        assert np.abs(res.steps[-1].pressure - 1.0).max() < 1e-13


@pytest.mark.parametrize("cell", ["hex", "tet", "prism"])
def test_an_inclined_contact_through_nodes_is_exact(cell):
    """SSNV182-like (code_aster: LSN = Z + Y/2 - 15, through 66 nodes): a cube of 2 x 2
    x 4 cells pressed by p = 1 on top (ν = 0, top held in x, y), Γ = {z + y/2 = 3/4}
    through 9 nodes, Coulomb μ = 1 > tan θ = 1/2: it sticks, and the traction is the
    uniform stress's, -p n_z e_z (pressure p n_z² = 0.8), within 1e-12 at every dof
    (measured ≤ 9.3e-15 on hex, tet and prism; with Γ snapped 1e-9 h off the nodes it
    was 1.4e-9)."""
    import warnings

    s = Scene(Box((2, 2, 4), cell), plane((0, 0.5, 0.5), (0, 0.5, 1)), Material(1.0, 0.0),
              displacements=(clamped("zmin"), Displacement("zmax", {"x": 0.0, "y": 0.0})),
              loads=(SurfaceLoad("zmax", pressure=1.0),), law="coulomb", friction=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)          # through the nodes: no warning
        res = contact.solve(s, history=(0.5, 1.0))
    st = res.steps[-1]
    n = np.array([0.0, 0.5, 1.0]) / np.sqrt(1.25)
    assert np.all(st.status == 1), "stuck"
    assert np.abs(st.pressure - n[2] ** 2).max() < 1e-12
    assert np.abs(res.traction - np.array([0.0, 0.0, -n[2]])[:, None]).max() < 1e-12


def test_a_multiplier_on_a_sliver_of_gamma_is_refused_for_contact():
    """Γ tilted, 1e-9 above five nodes (farther than SNAP h: not put on Γ), the winner
    space on tetrahedra beside rollers: the tie's u_x space has a multiplier living on
    slivers, which the tie sets to its smoothest value; no contact law can fix it (it
    would be round-off over 1e-17), so contact refuses, naming the cure, and the vital
    space equals the tie.  Γ through the five nodes: no sliver, both spaces solve and
    equal the tie."""
    from skxfem.scene import rollers

    def scene(space, d):
        return Scene(Box((4, 4, 5), "tet"), plane((0, 0, 0.5 + d), (0, 0.2, 1)),
                     Material(E=1.0, nu=0.3),
                     displacements=(clamped("zmin"), rollers("xmin"), rollers("xmax")),
                     loads=(SurfaceLoad("zmax", pressure=lambda x: 1.5 - x[1]),),
                     space=space, law="coulomb", friction=5.0)

    with pytest.raises(ValueError, match=r"(?s)barely see the jump.*slivers of Γ.*"
                                         r"use space='vital'"):
        contact.solve(scene("winner", 1e-9), linear="direct")
    for space, d in (("vital", 1e-9), ("vital", 0.0), ("winner", 0.0)):
        res = contact.solve(scene(space, d), linear="direct")
        tie = solver.solve(replace(scene(space, d), law="bonded", friction=None),
                           linear="direct")
        assert np.all(res.steps[-1].status == 1)
        assert rel(res.steps[-1].U, tie.U) < 1e-8 and rel(res.traction, tie.traction) < 1e-8


def test_a_frictionless_plate_on_rollers_is_refused_naming_the_motion():
    from skxfem.scene.benchmarks import paper_plate

    with pytest.raises(saddle.SingularSystemError, match=r"(?s)Ω⁺ .*can translate along y.*"
                       r"frictionless law with Γ closed everywhere.*use a law with friction"):
        contact.solve(replace(paper_plate(3), law="frictionless"))


def test_a_history_may_change_the_law():
    """Pressed frictionless, then pulled with the interface bilateral (tension carried,
    free sliding): each step is its tie; a law change is never ignored."""
    top = Displacement("ymax", {"x": 0.0, "y": -0.01})
    base = replace(strip(n=3), law="frictionless", loads=(),
                   displacements=(clamped("ymin"), top))
    pulled = replace(base, law="bilateral", displacements=(
        clamped("ymin"), Displacement("ymax", {"x": 0.0, "y": 0.01})), name="pulled")
    res = contact.solve(base, history=(base, pulled))
    pressed, tension = res.steps
    assert (pressed.law, tension.law) == (("frictionless",), ("bilateral",))
    assert np.all(pressed.pressure > 0) and np.all(tension.pressure < 0), "tension carried"
    ref = solver.solve(pulled)
    assert rel(tension.U, ref.U) < 1e-10
    frictionless = contact.solve(base, history=(base, replace(pulled, law="frictionless")))
    assert np.all(frictionless.steps[-1].status == 0), "frictionless: it opens"


def test_a_history_refuses_what_it_cannot_follow():
    base = held_top(replace(strip(n=3), law="frictionless"))
    for change in ({"material": Material(E=2.0)}, {"space": "winner"},
                   {"quadrature_order": 2}):
        with pytest.raises(ValueError, match=r"history\[1\]: a load state must keep"):
            contact.solve(base, history=(base, replace(base, **change)))


def test_non_convergence_names_the_step_and_its_load_factor():
    with pytest.raises(ContactConvergenceError, match=r"load step 2 of 2 \(load factor "
                       r"1\): contact Newton did not converge in 1 iterations"):
        contact.solve(partial(), history=(0.0, 1.0), max_iter=1, max_cuts=0)


def turned(a, n=8):
    """Frictionless strip whose top is pressed by 0.002 and turned by ``a``."""
    return replace(strip(n=n), law="frictionless", loads=(), name=f"a={a}", displacements=(
        clamped("ymin"),
        Displacement("ymax", {"x": 0.0, "y": lambda x: -0.002 - a * (x[0] - 0.5)})))


def test_a_failing_step_is_cut_and_the_cut_reported():
    """Turned one way, then the other: the contact zone crosses the strip, and Newton
    needs 5 iterations for the second step.  With 4 allowed, the step is halved (a
    StepCutWarning says so) and the answer is the uncut one (frictionless: no history
    to depend on)."""
    from skxfem.contact import StepCutWarning

    A, B = turned(0.02), turned(-0.02)
    ref = contact.solve(A, history=(A, B), max_cuts=0)
    assert ref.steps[-1].newton.iterations == 5
    with pytest.warns(StepCutWarning, match=r"load step 2 of 2 \(state 'a=-0.02'\).*cut"):
        cut = contact.solve(A, history=(A, B), max_iter=4)
    assert cut.steps[-1].increments == 2
    assert rel(cut.steps[-1].U, ref.steps[-1].U) < 1e-10


def test_unloading_a_sticking_slanted_block_is_linear():
    """μ above tan θ: it sticks at every load factor, so [1, 0.5] ends at half the
    first state (and equals the bonded tie at 0.5)."""
    st1, st2 = contact.solve(slanted(np.deg2rad(25.0), 1.0, 2), history=(1.0, 0.5)).steps
    assert np.all(st2.status == 1)
    assert rel(st2.U, 0.5 * st1.U) < 1e-10 and rel(st2.traction, 0.5 * st1.traction) < 1e-10


def test_one_result_for_every_law():
    """The tie and the contact result of a sticking strip: the same type, points,
    traction (whole vector and its parts), pressure and jump, and every reader works."""
    from skxfem.app import io
    from skxfem.fem import evaluate

    s = strip(3, sides="rollers")
    tie, stuck = solver.solve(s), solver.solve(replace(s, law="adhesive"))
    assert type(tie) is type(stuck) and not tie.is_contact and stuck.is_contact
    for key in ("points", "normals", "traction", "pressure", "jump", "tangential_traction",
                "normal_traction", "gap"):
        a, b = np.asarray(getattr(tie, key)), np.asarray(getattr(stuck, key))
        assert a.shape == b.shape and np.allclose(a, b, atol=1e-12), key
    assert np.allclose(stuck.traction, stuck.normal_traction * stuck.normals
                       + stuck.tangential_traction)
    assert np.array_equal(stuck.status, np.ones(stuck.points.shape[1], int))
    x, p = evaluate.pressure_along(stuck, 0)
    x0, p0 = evaluate.pressure_along(tie, 0)
    assert np.allclose(p, p0) and np.allclose(x, x0)
    assert io.result_summary(stuck).keys() >= io.result_summary(tie).keys()


def test_a_retry_that_lets_a_part_drift_off_is_cut_not_refused():
    """A tetrahedral cube whose top only friction (μ = 0.5) holds, pressed and sheared by
    (0.3, 0, -1), then by (-0.003, 0, -0.01) at once: Newton failed and the fixed point's
    answer had the top drift off by a rigid motion, refused as 'can rotate about an axis
    along z' (main).  A retry whose state leaves a part free has failed: the step is cut
    and solved; Coulomb's inequalities and the top's equilibrium hold."""
    import sys
    import warnings
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).parent))
    from test_contact_holding import unloaded

    from skxfem.contact.slide import translations
    from skxfem.linalg.amg import rigid_modes
    scene = unloaded(3, (1.0,), cell="tet")
    back = replace(scene, name="back", loads=(SurfaceLoad("zmax", traction=(-0.003, 0.0,
                                                                             -0.01)),))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = contact.solve(scene, history=(scene, back))
    last = res.steps[-1]
    assert last.increments > 1
    p, r = last.pressure, last.traction
    assert np.all(p >= 0) and np.all(np.linalg.norm(r, axis=1) <= 0.5 * p * (1 + 1e-9) + 1e-15)
    pb, ops = res.problem, res.ops
    T = translations(rigid_modes(pb.V), pb.D, 3)[0]
    forces = (ops.Bn @ T).T @ (-p) + sum((B @ T).T @ r[:, a] for a, B in enumerate(ops.Bt))
    assert np.allclose(forces, -T.T @ last.F, rtol=1e-8, atol=1e-12)
