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

import numpy as np
import pytest

import skxfem
from skxfem.amg import rigid_modes
from skxfem.levelset import circle, plane, sphere
from skxfem.material import Material
from skxfem.problem import assemble
from skxfem.saddle import SingularSystemError
from skxfem.scene import Box, Displacement, Interface, Scene, SurfaceLoad, clamped, rollers

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
           friction=(0.0, 0.0), n=4):
    """The column of the module notes: Γ₀ at z = 0.37 (tilted by ``tilt``), Γ₁ at 0.7."""
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
    assert p.V.N == p.V.n_std + sum(V.n_enr for V in p.V.spaces) == p.K.shape[0]
    shared = np.intersect1d(*[V.cut.enriched for V in p.V.spaces])
    assert shared.size > 0, "the two interfaces share enriched nodes (the row z = 1/2)"
    for k in range(2):
        alone = assemble(scene.alone(k))
        cols = p.V.columns(k)
        assert (p.K[cols][:, cols] != alone.K).nnz == 0
        assert np.array_equal(p.F[cols], alone.F)
        assert (p.interfaces[k].B != alone.B).nnz == 0 and (p.interfaces[k].P != alone.P).nnz == 0
    b0, b1 = (p.V.offsets[0] + np.arange(p.V.spaces[0].n_enr),
              p.V.offsets[1] + np.arange(p.V.spaces[1].n_enr))
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
    assert (a.K != b.K).nnz == 0 and (a.B != b.B).nnz == 0 and not b.interfaces
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
    with pytest.raises(ValueError, match=r"the interfaces interfaces\[0\] .* and "
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
