"""Several interfaces in one scene: the space, the ties, contact, the files (issue 17).

Known answers on a column [0, 1]^d (ν = 0, so that a uniaxial state is exact)
with two interfaces Γ₀ (low) and Γ₁ (high), the bottom clamped and the faces
x = 0 (and y = 0) on rollers, which hold every piece sideways:

* the top pressed by p: every interface closed, traction -p e_z·n at every point;
* the top lifted by δ (imposed): an interface that can open opens by δ (gap -δ,
  pressure 0) and the other carries nothing;
* the row of nodes z = 1/2, inside the middle piece, pushed down by δ₁ (a support
  on the middle piece) and the top lifted by δ: the part below z = 1/2 is
  compressed (pressure 2Eδ₁ on Γ₀), the part above is pulled: a tie Γ₁ carries
  the tension 2E(δ + δ₁), a contact Γ₁ opens by δ + δ₁.
"""
import dataclasses
import json

import meshio
import numpy as np
import pytest

import skxfem
from skxfem.app.io import write_result
from skxfem.fem.material import Material
from skxfem.levelset import circle, plane, sphere
from skxfem.linalg.amg import rigid_modes
from skxfem.linalg.saddle import SingularSystemError
from skxfem.problem import assemble
from skxfem.scene import Box, Displacement, Interface, Scene, SurfaceLoad, clamped, rollers
from skxfem.studies.budget import estimate

CELLS = ("quad", "tri", "hex", "tet", "prism")
E, P, LIFT, PUSH = 2.0, 1.5, 0.01, 0.004


def dim_of(cell):
    return 2 if cell in ("quad", "tri") else 3


def horizontal(dim, z, tilt=0.0):
    """The plane through height z, its normal tilted by ``tilt`` towards x."""
    point, normal = [0.5] * dim, [0.0] * dim
    point[-1], normal[0], normal[-1] = z, np.sin(tilt), np.cos(tilt)
    return plane(tuple(point), tuple(normal))


def column(cell, laws=("bonded", "bonded"), top="pressed", middle=False, tilt=0.0,
           friction=(None, None), n=4):
    """The column of the module notes: Γ₀ at z = 0.37 (tilted by ``tilt``), Γ₁ at 0.7;
    ``friction``: the μ of each coulomb interface (the other laws take none)."""
    friction = [mu if law == "coulomb" else None for law, mu in zip(laws, friction)]
    dim = dim_of(cell)
    up = "xyz"[dim - 1]
    sides = tuple(rollers(f) for f in ("xmin", "ymin")[:dim - 1])
    supports = (clamped(up + "min"),) + sides
    loads = ()
    if top == "pressed":
        loads = (SurfaceLoad(up + "max", pressure=P),)
    else:
        supports += (Displacement(up + "max", {up: LIFT}),)
    if middle:  # the row of nodes z = 1/2 pushed down: a support inside the middle piece
        supports += (Displacement(lambda x: np.abs(x[-1] - 0.5) < 1e-9, {up: -PUSH}),)
    mesh = Box((2,) * (dim - 1) + (n,), cell)
    return Scene(mesh, material=Material(E, 0.0), displacements=supports, loads=loads,
                 interfaces=(Interface(horizontal(dim, 0.37, tilt), laws[0],
                                       friction=friction[0]),
                             Interface(horizontal(dim, 0.7), laws[1], friction=friction[1])),
                 name="column")


def on(r, k):
    """The points of interface k."""
    return r.interface == k


# --- the space: K is the block generalisation of one interface's --------------------

@pytest.mark.parametrize("cell", CELLS)
def test_each_interface_block_is_that_interface_alone_bit_for_bit(cell):
    scene = column(cell)
    p = assemble(scene)
    assert p.V.N == p.V.n_std + sum(V.n_enr for V in p.V.per_interface) == p.K.shape[0]
    shared = np.intersect1d(*[V.cut.enriched for V in p.V.per_interface])
    assert shared.size > 0, "the two interfaces share enriched nodes (the row z = 1/2)"
    for k in range(2):
        alone = assemble(scene.alone(k))
        cols = p.V.columns(k)
        assert (p.K[cols][:, cols] != alone.K).nnz == 0
        assert np.array_equal(p.F[cols], alone.F)
        assert (p.interfaces[k].B != alone.B).nnz == 0 and (p.interfaces[k].P != alone.P).nnz == 0
    b0, b1 = (p.V.offsets[0] + np.arange(p.V.per_interface[0].n_enr),
              p.V.offsets[1] + np.arange(p.V.per_interface[1].n_enr))
    assert p.K[b0][:, b1].nnz == 0                      # the enrichments never meet
    Z = rigid_modes(p.V)                                # each of the three regions moves
    assert Z.shape[1] == 3 * (3 if dim_of(cell) == 2 else 6)
    assert np.abs(p.K @ Z).max() < 1e-12 and np.linalg.matrix_rank(Z) == Z.shape[1]


def test_one_interface_given_as_interfaces_is_the_one_interface_scene():
    ls = horizontal(2, 0.4)
    one = Scene(Box(4, "quad"), ls, displacements=(clamped("ymin"),),
                loads=(SurfaceLoad("ymax", pressure=P),))
    given = Scene(Box(4, "quad"), interfaces=(Interface(ls),), displacements=one.displacements,
                  loads=one.loads)
    a, b = assemble(one), assemble(given)
    assert (a.K != b.K).nnz == 0 and (a.B != b.B).nnz == 0 and len(b.interfaces) == 1
    ra, rb = skxfem.solve(one), skxfem.solve(given)
    assert np.array_equal(ra.traction, rb.traction) and np.array_equal(ra.U, rb.U)
    assert ra.regions.tolist() == [[-1], [1]] and np.array_equal(
        ra.u_regions, np.array([ra.u_minus, ra.u_plus]))


# --- ties ----------------------------------------------------------------------------

@pytest.mark.parametrize("cell", CELLS)
@pytest.mark.parametrize("laws", [("bonded", "bonded"), ("bilateral", "bonded"),
                                  ("bonded", "bilateral")])
def test_patch_two_planes_one_tilted_exact(cell, laws):
    """Uniaxial compression through two tied interfaces, Γ₀ tilted by 0.2 rad: the
    traction r = σn = -p n_z e_z at every point of both, to round-off.  (A bilateral
    Γ₀ carries no shear, so it lies flat; rollers hold the pieces sideways.)"""
    tilt = 0.0 if laws[0] == "bilateral" else 0.2
    r = skxfem.solve(column(cell, laws, tilt=tilt))
    dim = dim_of(cell)
    exact = np.zeros_like(r.traction)
    exact[-1] = -P * r.normals[-1]
    assert np.abs(r.traction - exact).max() < 1e-12 * 10
    assert r.max_jump < 1e-12
    assert r.points.shape[1] == r.interface.size and set(r.interface.tolist()) == {0, 1}
    assert r.regions.tolist() == [[-1, -1], [1, -1], [1, 1]] and r.u_minus is None
    uz = r.u_regions[:, -1]                            # u_z = -p z / E in every region
    z = r.mesh.p[-1]
    assert np.abs(uz + P * z / E).max() < 1e-12 and r.u_regions.shape == (3, dim, z.size)
    assert r.facets.max() == r.points.shape[1] - 1


@pytest.mark.parametrize("cell", ["quad", "tri", "hex", "tet"])
def test_tie_carries_tension_beside_a_compressed_tie(cell):
    """Middle row pushed down, top lifted: Γ₀ compressed by 2Eδ₁, Γ₁ pulled by 2E(δ+δ₁)."""
    r = skxfem.solve(column(cell, ("bonded", "bilateral"), top="lifted", middle=True))
    assert np.allclose(r.pressure[on(r, 0)], 2 * E * PUSH, rtol=0, atol=1e-12)
    assert np.allclose(r.pressure[on(r, 1)], -2 * E * (LIFT + PUSH), rtol=0, atol=1e-12)


# --- refusals -------------------------------------------------------------------------

@pytest.mark.parametrize("second, why", [
    (plane((0.55, 0.5), (1.0, 0.0)), "crossing"),
    (circle((0.52, 0.56), 0.21), "touching"),        # tangent to y = 0.35 at (0.52, 0.35)
    (plane((0, 0.37), (0.0, 1.0)), "closer than a cell"),
])
def test_crossing_touching_or_too_close_refused(second, why):
    scene = Scene(Box(8, "quad"), interfaces=(Interface(plane((0, 0.35), (0, 1))),
                                              Interface(second)))
    with pytest.raises(ValueError, match=r"^interfaces\[0\] .* and "
                                         r"interfaces\[1\] .* both cut \d+ mesh cell\(s\) "
                                         r"\(e\.g\. cell \d+ around .*\): they cross, touch.*"
                                         r"refine the mesh or move them apart"):
        assemble(scene)
    apart = Scene(Box(8, "quad"), interfaces=(Interface(plane((0, 0.35), (0, 1))),
                                              Interface(plane((0, 0.6), (0, 1)))))
    assert len(assemble(apart).interfaces) == 2      # one row of cells between: accepted


def test_3d_crossing_refused():
    scene = Scene(Box(4, "hex"), interfaces=(Interface(sphere((0.5, 0.5, 0.5), 0.3)),
                                             Interface(plane((0, 0, 0.45), (0, 0, 1)))))
    with pytest.raises(ValueError, match="both cut .* mesh cell"):
        skxfem.solve(scene)


def test_a_free_middle_piece_is_named():
    """Two bilateral ties let the middle piece slide when no support holds it."""
    scene = Scene(Box(4, "quad"), material=Material(E, 0.0),
                  displacements=(clamped("ymin"), clamped("ymax")),
                  interfaces=(Interface(horizontal(2, 0.35), "bilateral"),
                              Interface(horizontal(2, 0.7), "bilateral")))
    with pytest.raises(SingularSystemError,
                       match=r"the part of the body where ψ₀ > 0 and ψ₁ < 0 can translate "
                             r"along x: .* the interfaces' ties \(bilateral, bilateral\)"):
        skxfem.solve(scene)
    held = dataclasses.replace(scene, displacements=scene.displacements + (rollers("xmin"),))
    assert skxfem.solve(held).max_jump < 1e-12


# --- contact --------------------------------------------------------------------------

@pytest.mark.parametrize("cell", ["quad", "tri", "hex", "tet"])
@pytest.mark.parametrize("laws", [("frictionless", "coulomb"), ("adhesive", "bonded"),
                                  ("bilateral", "frictionless")])
def test_pressed_column_closes_every_interface(cell, laws):
    """Top pressed: both closed, the pressure the load at every point of both."""
    r = skxfem.solve(column(cell, laws, friction=(0.0, 0.3)))
    assert r.is_contact and len(r.law) == 2 and [law.name for law in r.law] == list(laws)
    assert np.abs(r.pressure - P).max() < 1e-12 and np.abs(r.gap).max() < 1e-12
    assert (r.status > 0).all() and set(r.interface.tolist()) == {0, 1}
    assert r.iterations <= 3


@pytest.mark.parametrize("cell", ["quad", "tri", "hex", "tet"])
def test_lifted_top_opens_the_frictionless_interface_only(cell):
    """Top lifted by δ, Γ₀ frictionless, Γ₁ bonded: Γ₀ opens by δ, Γ₁ carries nothing."""
    r = skxfem.solve(column(cell, ("frictionless", "bonded"), top="lifted"))
    low, high = on(r, 0), on(r, 1)
    assert np.abs(r.gap[low] + LIFT).max() < 1e-12 and np.abs(r.pressure[low]).max() < 1e-12
    assert (r.status[low] == 0).all() and (r.status[high] == 1).all()
    assert np.abs(r.traction[:, high]).max() < 1e-12 and np.abs(r.jump[:, high]).max() < 1e-12
    assert r.iterations <= 3


@pytest.mark.parametrize("cell", ["quad", "tri", "hex", "tet"])
@pytest.mark.parametrize("upper", ["frictionless", "coulomb"])
def test_one_compressed_one_opening_at_once(cell, upper):
    """The middle piece pushed down by a support, the top lifted: Γ₀ closed under
    2Eδ₁, Γ₁ open by δ + δ₁, in one solve."""
    r = skxfem.solve(column(cell, ("frictionless", upper), top="lifted", middle=True,
                            friction=(0.0, 0.4)))
    low, high = on(r, 0), on(r, 1)
    assert np.abs(r.pressure[low] - 2 * E * PUSH).max() < 1e-12 and (r.status[low] > 0).all()
    assert np.abs(r.gap[high] + LIFT + PUSH).max() < 1e-12 and (r.status[high] == 0).all()
    assert np.abs(r.pressure[high]).max() < 1e-12 and np.abs(r.gap[low]).max() < 1e-12


@pytest.mark.parametrize("cell", ["quad", "hex", "tet"])
def test_a_tie_beside_a_contact_interface(cell):
    """Γ₀ Coulomb, Γ₁ the bilateral tie: Γ₀ pressed by 2Eδ₁ while the tie carries the
    tension 2E(δ + δ₁) that would open a contact interface."""
    r = skxfem.solve(column(cell, ("coulomb", "bilateral"), top="lifted", middle=True,
                            friction=(0.5, 0.0)))
    low, high = on(r, 0), on(r, 1)
    assert np.abs(r.pressure[low] - 2 * E * PUSH).max() < 1e-12
    assert np.abs(r.pressure[high] + 2 * E * (LIFT + PUSH)).max() < 1e-12
    assert np.abs(r.gap[high]).max() < 1e-12 and (r.status[high] > 0).all()


@pytest.mark.parametrize("cell", CELLS)
def test_two_non_parallel_interfaces_pressed(cell):
    """Γ₀ tilted by 0.2 rad with Coulomb μ = 0.5 > tan 0.2 (it sticks), Γ₁ flat and
    frictionless (it slides, with nothing to slide it): r = -p n_z e_z on both."""
    r = skxfem.solve(column(cell, ("coulomb", "frictionless"), tilt=0.2, friction=(0.5, 0)))
    exact = np.zeros_like(r.traction)
    exact[-1] = -P * r.normals[-1]
    assert np.abs(r.traction - exact).max() < 1e-12 * 10
    assert (r.status[on(r, 0)] == 1).all() and (r.status[on(r, 1)] == 2).all()
    tilted = r.normals[:, on(r, 0)]
    assert np.allclose(np.linalg.norm(r.tangential_traction[:, on(r, 0)], axis=0),
                       P * np.abs(tilted[-1] * tilted[0]), atol=1e-12)


@pytest.mark.parametrize("cell", ["quad", "hex"])
def test_each_interface_keeps_its_own_rho(cell):
    """Γ₀ sticking (Coulomb) and Γ₁ frictionless, each with its own ρ_n, ρ_t far from
    the default and from each other's: each interface's law carries its own, and the
    answer is that of the default ρ (an augmentation, not a penalty)."""
    s = column(cell, ("coulomb", "frictionless"), tilt=0.2, friction=(0.5, 0))
    ref = skxfem.solve(s)
    own = ((1e-2, 1e3), (1e4, 1e-1))
    moved = dataclasses.replace(s, interfaces=tuple(
        dataclasses.replace(i, rho_n=rn, rho_t=rt) for i, (rn, rt) in zip(s.interfaces, own)))
    r = skxfem.contact.solve(moved)
    assert [(law.rho_n, law.rho_t) for law in r.law] == list(own)
    assert np.array_equal(r.status, ref.status)
    assert np.abs(r.traction - ref.traction).max() < 1e-8 * np.abs(ref.traction).max()
    assert np.abs(r.U - ref.U).max() < 1e-8 * np.abs(ref.U).max()


@pytest.mark.parametrize("cell", ["quad", "hex"])
def test_a_load_state_changes_one_interfaces_law(cell):
    """Half the load with both frictionless (Γ₁ opens), then Γ₁ tied (bilateral): it
    closes and carries the tension, Γ₀ the same pressure as before, doubled."""
    s = column(cell, ("frictionless", "frictionless"), top="lifted", middle=True)
    tied = dataclasses.replace(s, name="tied", interfaces=(
        s.interfaces[0], dataclasses.replace(s.interfaces[1], law="bilateral")))
    r = skxfem.contact.solve(s, history=[0.5, tied])
    first, last = r.steps
    assert first.law == ("frictionless", "frictionless") and last.law == (
        "frictionless", "bilateral")
    assert [law.name for law in r.law] == ["frictionless", "frictionless"]
    dof0 = r.ops.interface == 0
    assert np.abs(first.pressure[dof0] - E * PUSH).max() < 1e-12
    assert np.abs(first.gap[~dof0] + (LIFT + PUSH) / 2).max() < 1e-12
    assert np.abs(r.pressure[on(r, 1)] + 2 * E * (LIFT + PUSH)).max() < 1e-12
    assert np.abs(r.pressure[on(r, 0)] - 2 * E * PUSH).max() < 1e-12
    other = dataclasses.replace(tied, interfaces=(tied.interfaces[1], tied.interfaces[0]))
    with pytest.raises(ValueError, match=r"history\[1\]: a load state must keep the mesh, Γ"):
        skxfem.contact.solve(s, history=[0.5, other])


def test_contact_names_a_free_middle_piece():
    """Frictionless interfaces and no support beside the pieces above Γ₀: with Γ closed
    everywhere they still slide along x, the middle alone or with the top."""
    s = column("quad", ("frictionless", "frictionless"))
    s = dataclasses.replace(s, displacements=(clamped("ymin"), rollers("ymax")))
    with pytest.raises(SingularSystemError, match=r"the part of the body where ψ₀ > 0 and "
                                                  r"ψ₁ < 0 can translate along x: neither "
                                                  r"the displacements nor the frictionless"):
        skxfem.solve(s)
    s = dataclasses.replace(column("quad", ("frictionless", "bonded")),
                            displacements=(clamped("ymin"),))
    with pytest.raises(SingularSystemError, match=r"the parts of the body where ψ₀ > 0 and "
                                                  r"ψ₁ < 0 and where ψ₀ > 0 and ψ₁ > 0, "
                                                  r"together, can translate along x: .*the "
                                                  r"laws frictionless, bonded"):
        skxfem.solve(s)


def test_iterative_and_fixed_point_solves_of_several_interfaces():
    """The AMG solve takes the motions of every region; the fixed point every law."""
    tie = skxfem.solve(column("hex", ("bonded", "bilateral")), linear="iterative")
    assert tie.linear == "iterative" and np.abs(tie.pressure - P).max() < 1e-10
    s = column("hex", ("coulomb", "frictionless"), friction=(0.5, 0.0), tilt=0.2)
    for kw in ({"linear": "iterative"}, {"method": "fixed_point"}):
        r = skxfem.contact.solve(s, **kw)
        assert np.abs(r.pressure[on(r, 1)] - P).max() < 1e-10, kw


# --- results and files ----------------------------------------------------------------

def test_files_of_several_interfaces(tmp_path):
    """result.json lists the interfaces and each point's; displacement.vtu has a piece
    per region with its own field (lifted top: 0 below Γ₀, δ above); interface.vtu
    carries the interface of each point."""
    r = skxfem.solve(column("quad", ("frictionless", "bonded"), top="lifted"))
    paths = write_result(r, tmp_path / "out")
    data = json.loads(paths["json"].read_text())
    assert data["law"] == ["frictionless", "bonded"] and data["space"] == ["vital", "vital"]
    assert [i["law"] for i in data["interfaces"]] == ["frictionless", "bonded"]
    assert [i["n_points"] for i in data["interfaces"]] == np.bincount(r.interface).tolist()
    assert data["interfaces"][0]["rho_n"] == r.law[0].rho_n and "friction" not in data
    assert data["interface"] == r.interface.tolist() and data["regions"] == r.regions.tolist()
    assert np.array_equal(np.array(data["points"]), r.points.T)
    assert data["dofs"]["interface"] == r.ops.interface.tolist()
    assert data["steps"][0]["law"] == ["frictionless", "bonded"]
    d = meshio.read(paths["displacement"])
    region = d.cell_data["region"][0]
    assert sorted(set(region.tolist())) == [0, 1, 2]
    uz = d.point_data["displacement"][:, 1]
    for r_index, expected in enumerate((0.0, LIFT, LIFT)):
        points = np.unique(d.cells[0].data[region == r_index])
        assert np.abs(uz[points] - expected).max() < 1e-12
    assert {"levelset_0", "levelset_1"} <= set(d.point_data)
    i = meshio.read(paths["interface"])
    assert i.point_data["interface"].tolist() == r.interface.tolist()
    assert i.cells[0].data.max() == r.points.shape[1] - 1


def test_one_interface_files_have_the_same_form(tmp_path):
    """One interface is the case N = 1 (issue 28): the same keys and fields as above,
    with one entry per list and the regions Ω⁻ and Ω⁺."""
    r = skxfem.solve(column("quad").alone(0))
    paths = write_result(r, tmp_path / "one")
    data = json.loads(paths["json"].read_text())
    assert data["law"] == ["bonded"] and data["space"] == ["vital"]
    assert [i["n_points"] for i in data["interfaces"]] == [r.points.shape[1]]
    assert data["interface"] == [0] * r.points.shape[1] and data["regions"] == [[-1], [1]]
    d = meshio.read(paths["displacement"])
    assert sorted(set(d.cell_data["region"][0].tolist())) == [0, 1]
    assert "levelset_0" in d.point_data and "levelset_1" not in d.point_data
    assert meshio.read(paths["interface"]).point_data["interface"].tolist() == \
        [0] * r.points.shape[1]


def test_size_guard_counts_each_interface():
    two = column("tri", n=8)
    e, e0, e1 = estimate(two), estimate(two.alone(0)), estimate(two.alone(1))
    dim_nodes = 2 * e.n_nodes
    assert e.n_dofs - dim_nodes == (e0.n_dofs - dim_nodes) + (e1.n_dofs - dim_nodes)
    assert e.n_multipliers == e0.n_multipliers + e1.n_multipliers
    p = assemble(two)
    assert p.V.N <= e.n_dofs and p.B.shape[0] <= e.n_multipliers
    mixed = dataclasses.replace(two, interfaces=(two.interfaces[0], dataclasses.replace(
        two.interfaces[1], law="bilateral")))
    assert estimate(mixed).n_multipliers == e0.n_multipliers + e1.n_multipliers // 2


def test_one_path_tools_take_several_and_one_interface_tools_refuse_clearly():
    from skxfem.lbb import inf_sup
    from skxfem.studies.conforming import solve_conforming
    from skxfem.studies.convergence import energy_error, pressure_error

    scene = column("quad")
    both = inf_sup(scene)               # the multipliers of the two interfaces at once
    assert both.beta > 0 and both.n_zero == 0
    with pytest.raises(ValueError, match="does not follow Γ"):
        solve_conforming(scene)
    r = skxfem.solve(scene)
    for measure in (energy_error, pressure_error):
        with pytest.raises(ValueError, match="one interface"):
            measure(r, lambda x: x)
    assert inf_sup(scene.alone(0)).beta > 0


@pytest.mark.parametrize("order", ["crack", "crack, full", "full, crack", "two cracks"])
def test_rigid_modes_of_cracks_and_full_interfaces_cost_no_energy(order):
    """A crack (front) splits no region: its unknowns are 0 in every rigid motion.  The
    modes set its Heaviside unknowns as a splitting Γ's (a side moving alone), and took
    one bit per interface, not per splitting one: K Z was up to 2 (E = 1, h = 1/20) with
    a crack whose support holds Heaviside nodes (alone, or with a full Γ), and two cracks
    crashed skxfem.solve with numpy's 'operands could not be broadcast together'."""
    crack = Interface(plane((0, 0.325), (0, 1)), law="free", front=plane((0.6, 0), (1, 0)))
    other = Interface(plane((0, 0.725), (0, 1)), law="free", front=plane((0.4, 0), (-1, 0)))
    full = Interface(plane((0, 0.725), (0, 1)), law="bonded")
    items = {"crack": (crack,), "crack, full": (crack, full), "full, crack": (full, crack),
             "two cracks": (crack, other)}[order]
    scene = Scene(Box(20, "tri"), interfaces=items, material=Material(1.0, 0.3),
                  displacements=(Displacement("ymin", {"y": 0.0}),
                                 Displacement("ymin", {"x": 0.0}, where="x < 1e-9")),
                  loads=(SurfaceLoad("ymax", traction=(0.0, 1.0)),))
    p = assemble(scene)
    assert sum(V.heaviside.size for V in (q.V.space for q in p.interfaces
                                          if not q.V.splits)) > 0
    Z = rigid_modes(p.V)
    assert Z.shape[1] == 3 * p.V.regions()[0].shape[0]
    assert np.abs(p.K @ Z).max() < 1e-11 and np.linalg.matrix_rank(Z) == Z.shape[1]
    assert all(np.all(f["K_I"] > 0) for f in skxfem.solve(scene).front)


def _crack_and_full(crack_law, full_law, friction=None):
    crack = Interface(plane((0, 0.325), (0, 1)), law=crack_law, front=plane((0.4, 0), (1, 0)))
    full = Interface(plane((0, 0.725), (0, 1)), law=full_law, friction=friction)
    return Scene(Box(20, "tri"), interfaces=(crack, full), material=Material(1.0, 0.3),
                 displacements=(Displacement("ymin", {"y": 0.0}),
                                Displacement("ymin", {"x": 0.0}, where="x < 1e-9")),
                 loads=(SurfaceLoad("ymax", traction=(0.0, -1.0)),))


def test_a_crack_and_a_free_full_interface_name_the_part_left_free():
    """A crack first and a full Γ with law 'free': the message named the sides of the
    crack (interfaces[0]), which has none: AttributeError 'CrackGeometry' object has no
    attribute 'node_side'.  Now the sides of the Γ that splits the body."""
    with pytest.raises(SingularSystemError, match=r"Ω⁺ \(the part of the body where ψ > 0\) "
                       r"can translate in every direction"):
        skxfem.solve(_crack_and_full("free", "free"))


def test_a_free_crack_with_a_contact_interface_is_refused_naming_the_fix():
    """A free crack with a contact law elsewhere went to the contact solve, which said
    "scene law must be one of ('frictionless', 'coulomb', 'adhesive') ..., got 'free'"
    without naming the interface; now it names it and the law that does the same where
    the faces open ('frictionless'), which solves."""
    with pytest.raises(ValueError, match=r"interfaces\[0\] .*: law 'free' .* give it law "
                       r"'frictionless'"):
        skxfem.solve(_crack_and_full("free", "coulomb", 0.5))
    front = skxfem.solve(_crack_and_full("frictionless", "coulomb", 0.5)).front[0]
    assert abs(front["K_I"][0]) < 1e-3 and abs(front["K_II"][0]) < 1e-3   # pressed shut
