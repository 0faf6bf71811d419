"""Scenes in Python: validation, boundary conditions on all five cells, benchmarks."""
import dataclasses

import meshio
import numpy as np
import pytest
from skfem import Basis, ElementVector, MeshTri1

from skxfem.fem.material import Material
from skxfem.fem.meshes import box
from skxfem.levelset import circle, nodal_values, plane, sphere
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
    traction,
)
from skxfem.scene.benchmarks import paper_plate, strip
from skxfem.scene.expr import Expression
from skxfem.scene.settings import Solver

DIM = {"tri": 2, "quad": 2, "tet": 3, "hex": 3, "prism": 3}


def small(cell):
    """A 2 x 3 (x 2) box, its vector basis and a level set cutting it."""
    mesh = box((2, 3) if DIM[cell] == 2 else (2, 3, 2), cell)
    basis = Basis(mesh, ElementVector(mesh.elem()))
    psi = plane((0.0,) * DIM[cell], (1.0,) + (0.0,) * (DIM[cell] - 1))
    return mesh, basis, psi


# --- 1. the dataclasses check their fields --------------------------------------

@pytest.mark.parametrize("kwargs, message", [
    (dict(n=2, cell="hexa"), "cell must be one of"),
    (dict(n=0, cell="quad"), "Box n"),
    (dict(n=(2, 2), cell="hex"), "3 of them"),
    (dict(n="four", cell="quad"), "Box n"),
    (dict(n=2.5, cell="quad"), "Box n"),
    (dict(n=2, cell="quad", size=(1.0, -1.0)), "Box size"),
    (dict(n=2, cell="quad", size=(1.0, 1.0, 1.0)), "Box size"),
])
def test_01_box_refuses_bad_fields(kwargs, message):
    with pytest.raises(ValueError, match=message):
        Box(**kwargs)


def test_02_box_normalises_n_and_size():
    assert Box(3, "hex").n == (3, 3, 3)
    assert Box([2, 1], "tri", [2, 1]).size == (2.0, 1.0)


@pytest.mark.parametrize("make, error, message", [
    (lambda: Displacement("xmin", {"w": 0.0}), ValueError, "component 'w'"),
    (lambda: Displacement("xmin", {3: 0.0}), ValueError, "component 3"),
    (lambda: Displacement("xmin", {}), TypeError, "non-empty mapping"),
    (lambda: Displacement("xmin", [0.0]), TypeError, "mapping"),
    (lambda: Displacement("xmin", {"x": float("nan")}), ValueError, "finite"),
    (lambda: Displacement("xmin", {"x": [0.1]}), TypeError, "number, a formula string"),
    (lambda: Displacement("xmin", {"x": "open(y)"}), ValueError,
     "Displacement component 'x': function call 'open"),
    (lambda: SurfaceLoad("ymax", pressure="x < 1"), ValueError, "SurfaceLoad pressure: cond"),
    (lambda: SurfaceLoad("ymax", traction=(0, "__import__('os')")), ValueError,
     r"traction\[1\]: function call"),
    (lambda: Displacement("xmin", {"all": 0.0, "x": 1.0}), ValueError, "either 'all'"),
    (lambda: Displacement(3, {"x": 0.0}), TypeError, "boundary must be a name"),
    (lambda: SurfaceLoad("ymax"), ValueError, "exactly one of"),
    (lambda: SurfaceLoad("ymax", pressure=1.0, traction=(0, 1)), ValueError, "exactly one"),
    (lambda: SurfaceLoad("ymax", traction=(1.0,)), TypeError, "2 or 3 components"),
    (lambda: SurfaceLoad("ymax", pressure=True), TypeError, "pressure"),
    (lambda: rollers("left"), ValueError, "axis-aligned face"),
])
def test_03_conditions_refuse_bad_fields(make, error, message):
    with pytest.raises(error, match=message):
        make()


def test_04_components_are_stored_by_name():
    assert Displacement("ymin", {0: 1, 2: 0.5}).components == {"x": 1.0, "z": 0.5}
    assert clamped("zmin").components == {"all": 0.0}
    assert rollers("ymax").components == {"y": 0.0}


QUAD = Box(2, "quad")
LINE = plane((0.0, 0.5), (0.0, 1.0))


@pytest.mark.parametrize("kwargs, error, message", [
    (dict(mesh=1.0), TypeError, "Scene mesh"),
    (dict(levelset=lambda x: x[0]), TypeError, "Scene levelset"),
    (dict(levelset=sphere((0, 0, 0), 1.0)), ValueError, "is 3D but the mesh is 2D"),
    (dict(material={"E": 1}), TypeError, "Scene material"),
    (dict(displacements=(clamped("xmin"), 1)), TypeError, "Scene displacements"),
    (dict(loads=clamped("xmin")), TypeError, "Scene loads"),
    (dict(law="glued"), ValueError, "Scene law must be one of"),
    (dict(space="fancy"), ValueError, "Scene space must be one of"),
    (dict(quadrature_order=0), ValueError, "quadrature_order"),
    (dict(quadrature_order=2.0), ValueError, "quadrature_order"),
    (dict(name=""), ValueError, "Scene name"),
    (dict(displacements=(Displacement("xmin", {"z": 0.0}),)), ValueError,
     r"displacements\[0\]: component 'z' does not exist on a 2D mesh"),
    (dict(loads=(SurfaceLoad("ymax", traction=(0, 0, 1)),)), ValueError,
     r"loads\[0\]: traction has 3 components but the mesh is 2D"),
])
def test_05_scene_refuses_bad_fields(kwargs, error, message):
    with pytest.raises(error, match=message):
        Scene(**{"mesh": QUAD, "levelset": LINE, **kwargs})


def test_06_scenes_are_frozen_and_replace_makes_variants(monkeypatch):
    s = Scene(QUAD, LINE, displacements=[clamped("ymin")])
    assert s.displacements == (clamped("ymin"),)             # lists become tuples
    assert dataclasses.replace(s, law="bilateral").law == "bilateral"
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.law = "bilateral"
    with pytest.raises(ValueError, match="space"):
        dataclasses.replace(s, space="stable")
    assert dataclasses.replace(s, space="vital").space == "vital"


LOW, HIGH = plane((0, 0.3), (0, 1)), plane((0, 0.7), (0, 1))


def test_06b_interfaces_are_a_tuple_in_either_form():
    two = Scene(QUAD, interfaces=[Interface(LOW, "frictionless"),
                                  Interface(HIGH, "coulomb", "winner", 0.4, 2.0)])
    assert isinstance(two.interfaces, tuple) and len(two.interfaces) == 2 and two.dim == 2
    assert [(i.law, i.space, i.friction, i.rho_n) for i in two.interfaces] == [
        ("frictionless", "vital", None, None), ("coulomb", "winner", 0.4, 2.0)]
    assert (two.law, two.space, two.levelset) == (None, None, None)   # each Interface's
    one = Scene(QUAD, LINE, law="bilateral", rho_n=2.0)   # the short form: a tuple of one
    assert one.interfaces == (Interface(LINE, "bilateral", rho_n=2.0),)
    alone = two.alone(1)                       # the one-interface scene of interface 1
    assert (alone.law, alone.space, alone.friction, alone.rho_n) == (
        "coulomb", "winner", 0.4, 2.0) and alone.levelset is HIGH
    assert alone.interfaces == (two.interfaces[1],)
    assert dataclasses.replace(two, name="b").interfaces == two.interfaces
    assert Scene(QUAD, interfaces=(Interface(LOW),)).interfaces[0].law == "bonded"
    # replace() on the short form builds its interface anew from the fields
    assert dataclasses.replace(one, law="bonded").interfaces == (
        Interface(LINE, "bonded", rho_n=2.0),)
    with pytest.raises(ValueError, match="both a levelset and interfaces"):
        dataclasses.replace(one, interfaces=(Interface(LOW),))
    given = dataclasses.replace(one, **one.given_interfaces((Interface(LOW),)))
    assert given.interfaces == (Interface(LOW),) and given.law is None


@pytest.mark.parametrize("kwargs, error, message", [
    (dict(levelset=LINE, interfaces=(Interface(LOW),)), ValueError,
     "both a levelset and interfaces"),
    (dict(interfaces=()), ValueError, "interfaces is empty"),
    (dict(interfaces=(LOW, HIGH)), TypeError, "tuple of skxfem.Interface"),
    (dict(interfaces=Interface(LOW)), TypeError, "tuple of skxfem.Interface"),
    (dict(interfaces=(Interface(LOW),), law="coulomb"), ValueError,
     "Scene law: with interfaces, each Interface has its own law"),
    (dict(interfaces=(Interface(LOW),), friction=0.3, rho_n=1.0), ValueError,
     "Scene friction, rho_n: with interfaces"),
    (dict(interfaces=(Interface(LOW), Interface(sphere((0, 0, 0), 1.0)))), ValueError,
     r"interfaces mix 2D and 3D level sets: .*interfaces\[1\] 'sphere.*3D"),
    (dict(interfaces=(Interface(plane((0, 0, .5), (0, 0, 1))),)), ValueError,
     r"interfaces\[0\] level set .* is 3D but the mesh is 2D"),
    (dict(), TypeError, r"Scene levelset must be .* \(several interfaces: give interfaces"),
])
def test_06c_several_interfaces_refused(kwargs, error, message):
    with pytest.raises(error, match=message):
        Scene(QUAD, **kwargs)


@pytest.mark.parametrize("kwargs, message", [
    (dict(levelset=lambda x: x[0]), "Interface levelset must be"),
    (dict(law="glued"), "Interface law must be one of"),
    (dict(space="fancy"), "Interface space must be one of"),
    (dict(friction=-0.1), "Interface friction"),
    (dict(friction=float("nan")), "Interface friction"),
    (dict(rho_n=0.0), "Interface rho_n must be a positive number"),
    (dict(rho_t="big"), "Interface rho_t must be a positive number"),
])
def test_06d_interface_refuses_bad_fields(kwargs, message):
    with pytest.raises((TypeError, ValueError), match=message):
        Interface(**{"levelset": LOW, **kwargs})


# --- 2. meshes ------------------------------------------------------------------

def test_07_resolve_mesh_builds_checks_or_reads(tmp_path):
    m = resolve_mesh(Scene(Box((2, 3), "tri"), LINE))
    assert type(m).__name__ == "MeshTri1" and m.nelements == 12
    given = box(2, "hex")
    assert resolve_mesh(Scene(given, plane((0, 0, .5), (0, 0, 1)))) is given
    tets = box(1, "tet")
    meshio.write(tmp_path / "m.vtu", meshio.Mesh(tets.p.T, [("tetra", tets.t.T)]))
    assert resolve_mesh(Scene(tmp_path / "m.vtu", plane((0, 0, .5), (0, 0, 1)))).nelements == 6


def test_08_resolve_mesh_refuses_nan_coordinates_and_dimension_mismatch(tmp_path):
    bad = MeshTri1()
    bad.doflocs[0, 0] = np.nan          # skfem meshes are frozen; this edits p in place
    with pytest.raises(ValueError, match="NaN"):
        resolve_mesh(Scene(bad, LINE))
    box(1, "hex").save(tmp_path / "m.vtu")          # scikit-fem's writer orders the nodes
    with pytest.raises(ValueError, match="is 2D but the mesh is 3D"):
        resolve_mesh(Scene(tmp_path / "m.vtu", LINE))


# --- 3. imposed displacements on the five cell types ----------------------------

def test_09_clamped_face_imposes_every_component_of_its_nodes(cell):
    mesh, basis, psi = small(cell)
    dofs, values = dirichlet(Scene(mesh, psi, displacements=(clamped("xmin"),)), mesh, basis)
    nodes = np.flatnonzero(np.isclose(mesh.p[0], 0.0))
    assert nodes.size == (4 if DIM[cell] == 2 else 12)
    np.testing.assert_array_equal(dofs, np.sort(basis.nodal_dofs[:, nodes].ravel()))
    assert values.shape == dofs.shape and np.all(values == 0.0)


def test_10_values_selections_and_later_conditions_win(cell):
    mesh, basis, psi = small(cell)
    corner = Expression(" and ".join(f"{c} < 1e-9" for c in "xyz"[:DIM[cell]]),
                        DIM[cell], boolean=True)
    scene = Scene(mesh, psi, displacements=(
        clamped("xmin"),
        Displacement("xmin", {"y": lambda x: 2.0 * x[1]}),   # overrides u_y on xmin
        Displacement(corner, {0: 7.0}),                       # one node, u_x
        rollers("ymax")))
    dofs, values = dirichlet(scene, mesh, basis)
    u = dict(zip(dofs.tolist(), values.tolist(), strict=True))
    xmin = np.flatnonzero(np.isclose(mesh.p[0], 0.0))
    ymax = np.flatnonzero(np.isclose(mesh.p[1], 1.0))
    for i in np.setdiff1d(xmin, ymax):
        assert u[basis.nodal_dofs[1, i]] == pytest.approx(2.0 * mesh.p[1, i])
        assert u[basis.nodal_dofs[0, i]] == (7.0 if i == 0 else 0.0)
    assert np.allclose(mesh.p[:, 0], 0.0) and sum(values == 7.0) == 1
    assert all(u[basis.nodal_dofs[1, i]] == 0.0 for i in ymax)      # rollers come last
    expected = DIM[cell] * xmin.size + np.setdiff1d(ymax, xmin).size
    assert dofs.size == expected


@pytest.mark.parametrize("condition, message", [
    (clamped("left"), "unknown boundary 'left'; available: xmax, xmin, ymax, ymin"),
    (clamped(lambda x: x[0] > 5.0), "selects no node"),
    (clamped(lambda x: x[0]), "one bool per point"),
    (Displacement("xmin", {"x": lambda x: np.nan * x[0]}), "NaN"),
    (Displacement("xmin", {"x": lambda x: np.zeros(2)}), "one value per point"),
])
def test_11_bad_conditions_are_refused_on_the_mesh(condition, message):
    mesh, basis, psi = small("quad")
    with pytest.raises(ValueError, match=message):
        dirichlet(Scene(mesh, psi, displacements=(condition,)), mesh, basis)


def test_12_a_z_component_on_a_2d_mesh_is_refused_by_dirichlet():
    mesh, basis, _ = small("tri")
    scene = Scene(Box(2, "hex"), sphere((0, 0, 0), 0.5),
                  displacements=(Displacement("xmin", {"z": 0.0}),))
    with pytest.raises(ValueError, match="component 'z' does not exist on a 2D mesh"):
        dirichlet(scene, mesh, basis)


def test_13_named_faces_work_on_meshes_without_boundaries():
    mesh = MeshTri1.init_tensor(np.linspace(0, 2, 3), np.linspace(-1, 1, 3))
    assert mesh.boundaries is None
    basis = Basis(mesh, ElementVector(mesh.elem()))
    dofs, _ = dirichlet(Scene(mesh, circle((1, 0), .5), displacements=(rollers("ymin"),)),
                        mesh, basis)
    np.testing.assert_array_equal(dofs, np.sort(basis.nodal_dofs[1, mesh.p[1] == -1]))


# --- 4. loaded facets on the five cell types ------------------------------------

def test_14_load_facets_resolve_names_and_selections(cell):
    mesh, _, psi = small(cell)
    top = "ymax" if DIM[cell] == 2 else "zmax"
    scene = Scene(mesh, psi, loads=(
        SurfaceLoad(top, pressure=2.0),
        SurfaceLoad(lambda x: x[0] > 1 - 1e-9, traction=(1.0,) + (0.0,) * (DIM[cell] - 1))))
    (f1, t1), (f2, t2) = load_facets(scene, mesh)
    np.testing.assert_array_equal(np.sort(f1), np.sort(mesh.boundaries[top]))
    np.testing.assert_array_equal(np.sort(f2), np.sort(mesh.boundaries["xmax"]))
    x = mesh.p[:, :3]
    n = np.zeros_like(x)
    n[-1] = 1.0
    np.testing.assert_array_equal(t1(x, n), -2.0 * n)            # t = -p n
    np.testing.assert_array_equal(t2(x, n)[0], [1.0, 1.0, 1.0])


def test_15_traction_evaluates_callables_and_refuses_nan():
    x = np.array([[0.0, 0.5], [1.0, 1.0]])
    n = np.array([[0.0, 0.0], [1.0, 1.0]])
    p = SurfaceLoad("ymax", pressure=Expression("4*x*(1 - x)", 2))
    np.testing.assert_allclose(traction(p, x, n), [[0.0, 0.0], [0.0, -1.0]])
    with pytest.raises(ValueError, match="NaN"):
        traction(SurfaceLoad("ymax", pressure=lambda x: np.full(x.shape[1:], np.nan)), x, n)


def test_16_a_load_selecting_no_facet_is_refused():
    mesh, _, psi = small("hex")
    scene = Scene(mesh, psi, loads=(SurfaceLoad(lambda x: x[2] > 2.0, pressure=1.0),))
    with pytest.raises(ValueError, match=r"loads\[0\].*selects no facet"):
        load_facets(scene, mesh)


# --- 5. the benchmark scenes ------------------------------------------------------

@pytest.mark.parametrize("cell", ["hex", "prism"])
def test_17_paper_plate_is_the_set_up_of_section_5(cell):
    s = paper_plate(n=4, cell=cell)
    assert s.mesh == Box((4, 4, 5), cell, (1.0, 1.0, 1.0))
    assert paper_plate(n=3).mesh.n == (3, 3, 3) and paper_plate(2, nz=7).mesh.n[2] == 7
    assert s.material == Material(1.0, 0.3, "strain") and s.law == "bonded"
    mesh = resolve_mesh(s)
    psi = nodal_values(s.levelset, mesh)
    assert np.all(np.abs(psi) > 0.05), "no node on Γ: the plane cuts a layer of cells"
    np.testing.assert_allclose(psi, mesh.p[2] - 0.5)
    basis = Basis(mesh, ElementVector(mesh.elem()))
    dofs, values = dirichlet(s, mesh, basis)
    bottom = np.flatnonzero(mesh.p[2] == 0.0)
    sides = np.flatnonzero((mesh.p[0] == 0.0) | (mesh.p[0] == 1.0))
    assert dofs.size == 3 * bottom.size + np.setdiff1d(sides, bottom).size
    assert np.all(values == 0.0)
    [(facets, t)] = load_facets(s, mesh)
    np.testing.assert_array_equal(np.sort(facets), np.sort(mesh.boundaries["zmax"]))
    y = np.array([[0.5, 0.5], [0.0, 0.5], [1.0, 1.0]])
    np.testing.assert_allclose(t(y, np.array([[0, 0], [0, 0], [1.0, 1.0]]))[2], [0, -1.0])


def test_18_strip_is_the_plate_in_the_y_z_plane():
    s = strip(n=4, cell="tri")
    assert s.mesh == Box((4, 5), "tri", (1.0, 1.0))
    mesh = resolve_mesh(s)
    assert np.all(np.abs(nodal_values(s.levelset, mesh)) > 0.05)
    x = np.array([[0.0, 0.25, 0.5], [1.0, 1.0, 1.0]])
    n = np.array([[0.0] * 3, [1.0] * 3])
    np.testing.assert_allclose(traction(s.loads[0], x, n)[1], [0.0, -0.75, -1.0])


@pytest.mark.parametrize("make, message", [
    (lambda: paper_plate(4, nz=4), "nz must be an odd"),
    (lambda: paper_plate(4, cell="quad"), "'hex', 'prism' or 'tet'"),
    (lambda: paper_plate(0), "n must be a positive"),
    (lambda: strip(4, ny=2), "ny must be an odd"),
    (lambda: strip(4, cell="hex"), "'quad' or 'tri'"),
    (lambda: paper_plate(2, law="sticky"), "law"),
])
def test_19_benchmarks_refuse_bad_arguments(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_20_a_level_set_that_cuts_no_cell_is_refused_by_the_solver():
    from skxfem.solver import solve

    s = dataclasses.replace(strip(n=2), levelset=plane((0.0, 5.25), (0.0, 1.0)))
    with pytest.raises(ValueError, match="cuts no cell"):
        solve(s)


# --- 6. formula strings in Python, as in scene files ------------------------------

def test_21_formula_strings_work_in_python_as_in_a_scene_file(tmp_path):
    """The same string gives the same scene, the same values and the same solve."""
    from skxfem.scene.file import load_scene
    from skxfem.solver import solve

    f = tmp_path / "s.toml"
    f.write_text("[mesh]\nbox = {n = [4, 5], cell = 'tri'}\n[levelset]\nexpr = 'y - 0.5'\n"
                 "[[displacement]]\nboundary = 'ymin'\nx = '0.01*x*x'\ny = 0\n"
                 "[[load]]\nboundary = 'ymax'\npressure = '4*x*(1 - x)'\n"
                 "[[load]]\nboundary = 'xmax'\ntraction = ['0.1*y', 0]\n")
    from_file = load_scene(f)
    in_python = Scene(
        Box((4, 5), "tri"), from_file.levelset, name="s",
        displacements=(Displacement("ymin", {"x": "0.01*x*x", "y": 0}),),
        loads=(SurfaceLoad("ymax", pressure="4*x*(1 - x)"),
               SurfaceLoad("xmax", traction=("0.1*y", 0))))
    assert in_python == from_file                       # formulas compiled for 2D
    assert in_python.loads[0].pressure.dim == 2
    x = np.array([[0.0, 0.25, 0.5], [1.0, 1.0, 1.0]])
    np.testing.assert_allclose(in_python.loads[0].pressure(x), [0.0, 0.75, 1.0])
    a, b = solve(from_file), solve(in_python)
    np.testing.assert_array_equal(a.pressure, b.pressure)
    assert b.pressure.max() > 0.5


def test_22_a_z_formula_is_refused_by_a_2d_scene_and_kept_by_a_3d_one():
    load = SurfaceLoad("ymax", pressure="1 + z")
    with pytest.raises(ValueError, match=r"loads\[0\] pressure: expression '1 \+ z' uses z"):
        Scene(QUAD, LINE, loads=(load,))
    s3 = Scene(Box(2, "hex"), plane((0, 0, 0.5), (0, 0, 1)), loads=(load,),
               displacements=(Displacement("zmin", {"z": "0.5*z"}),))
    assert s3.loads[0] == load and s3.loads[0].pressure(np.ones((3, 1))) == 2.0
    assert s3.displacements[0].components["z"].text == "0.5*z"


@pytest.mark.parametrize("call", ["solve", "assemble", "inf_sup", "contact", "estimate"])
@pytest.mark.parametrize("bad", ["plate.toml", None, 3])
def test_every_entry_point_says_what_a_scene_is(call, bad):
    """A path, None or a number where a Scene belongs: one TypeError that says how to
    get a Scene, from every public call that takes one (not an AttributeError)."""
    import skxfem
    import skxfem.studies.budget
    fn = {"solve": skxfem.solve, "assemble": skxfem.assemble, "inf_sup": skxfem.lbb.inf_sup,
          "contact": skxfem.contact.solve, "estimate": skxfem.studies.budget.estimate}[call]
    with pytest.raises(TypeError, match=r"scene must be a skxfem.Scene, got .*load_scene"):
        fn(bad)


def test_a_box_cell_or_a_law_of_the_wrong_type_is_named():
    from skxfem import assemble
    from skxfem.scene.benchmarks import strip
    with pytest.raises(ValueError, match="Box cell must be one of"):
        Box(2, ["quad"])
    with pytest.raises(ValueError, match="law must be one of"):
        assemble(strip(2), law=["bonded"])


@pytest.mark.parametrize("cell, top", [("tri", 19), ("quad", 19), ("tet", 8), ("hex", 8),
                                       ("prism", 8)])
def test_the_highest_quadrature_order_solves_and_one_more_is_refused(cell, top):
    """Up to MAX_QUADRATURE_ORDER the rules exist (a cut cell's sub-simplices too);
    above, a ValueError at once (order 100000 used to hang, 12 on tets raised
    scikit-fem's NotImplementedError)."""
    from skxfem import solve
    from skxfem.scene import MAX_QUADRATURE_ORDER
    from skxfem.scene.benchmarks import paper_plate, strip
    s = strip(2, cell=cell) if cell in ("tri", "quad") else paper_plate(2, cell)
    assert MAX_QUADRATURE_ORDER[s.dim] == top
    assert np.isfinite(solve(dataclasses.replace(s, quadrature_order=top)).pressure).all()
    for q in (top + 1, 100000, 0):
        with pytest.raises(ValueError, match=rf"quadrature_order must be an integer from 1 "
                                             rf"to {top} in {s.dim}D"):
            dataclasses.replace(s, quadrature_order=q)


def test_a_traction_given_as_an_array_is_a_traction():
    """np.array([0, -1]) has two components like (0, -1) (it was refused as not 2 or 3)."""
    a = SurfaceLoad("ymax", traction=np.array([0.0, -1.0]))
    assert a == SurfaceLoad("ymax", traction=(0.0, -1.0))
    with pytest.raises(TypeError, match="2 or 3 components"):
        SurfaceLoad("ymax", traction=np.zeros(4))


@pytest.mark.parametrize("size", [1e-300, 1e300, 1e-308, 1e-51, 1e51])
def test_box_sizes_outside_the_range_are_refused_naming_it(size):
    """Issue 18: 1e300 ended in scipy's "no full matching exists", 1e-300 in a
    self-contradicting "cuts no cell (psi ranges over [-5e-301, 5e-301])"."""
    with pytest.raises(ValueError, match=r"Box size must lie in \[1e-50, 1e\+50\]"):
        Box(2, "quad", size=(1.0, size))


@pytest.mark.parametrize("size", [1e-50, 1e50])
def test_the_ends_of_the_size_range_pass_the_patch_test(cell, size):
    from skxfem.scene.parts import SIZE_RANGE
    from skxfem.studies.extremes import patch_error

    assert SIZE_RANGE == (1e-50, 1e50)
    dim = DIM[cell]
    psi = plane((0.5 * size,) * (dim - 1) + (0.53 * size,), (0.0,) * (dim - 1) + (1.0,))
    up = "xyz"[dim - 1]

    def at(*c):
        return lambda x: np.all([np.abs(x[i] - v) <= 1e-9 * size for i, v in enumerate(c)],
                                axis=0)

    fix = (Displacement(at(0.0, 0.0), {"x": 0.0}),) if dim == 2 else (
        Displacement(at(0.0, 0.0, 0.0), {"x": 0.0, "y": 0.0}),
        Displacement(at(size, 0.0, 0.0), {"y": 0.0}))
    scene = Scene(Box(4, cell, size=(size,) * dim), psi, Material(),
                  (rollers(up + "min"),) + fix, (SurfaceLoad(up + "max", pressure=1.0),))
    assert patch_error(scene)[0] <= 1e-8


# --- issue 26: no silent default that changes the law; the solver settings ------------

@pytest.mark.parametrize("build", [
    lambda **kw: Scene(QUAD, LINE, **kw),
    lambda **kw: Scene(QUAD, interfaces=(Interface(LOW, "bonded"), Interface(HIGH, **kw))),
    lambda **kw: Interface(LOW, **kw),
])
def test_26_coulomb_needs_friction_and_the_other_laws_refuse_it(build):
    """law="coulomb" without friction ran as μ = 0 ("frictionless" in the summary);
    friction with a law that has none was ignored.  Both are one-line ValueErrors that
    name friction, for a one-interface scene and for an Interface of several."""
    with pytest.raises(ValueError, match=r"law 'coulomb' needs friction \(Coulomb's mu"):
        build(law="coulomb")
    for law in ("bonded", "bilateral", "frictionless", "adhesive"):
        with pytest.raises(ValueError, match=rf"friction \(Coulomb's mu\) is taken by the law "
                                             rf"'coulomb' only; law '{law}' has no friction"):
            build(law=law, friction=0.3)
        build(law=law)                               # unset: accepted
    for mu in (0, 0.0, 0.3, np.float64(2.0)):        # 0 given on purpose: frictionless
        built = build(law="coulomb", friction=mu)
        items = built.interfaces if isinstance(built, Scene) else (built,)
        assert items[-1].friction == float(mu) and type(items[-1].friction) is float


def test_26b_the_solver_settings_are_part_of_the_scene():
    """Scene.solver: the defaults unless given, checked; a keyword overrides it."""
    from skxfem import Solver

    s = Scene(QUAD, LINE)
    assert s.solver == Solver() and (s.solver.linear, s.solver.max_iter) == ("auto", None)
    t = dataclasses.replace(s, solver=Solver("direct", 1e-8, np.int64(7)))
    assert t.solver.max_iter == 7 and type(t.solver.max_iter) is int
    assert t.solver.override(linear="iterative") == Solver("iterative", 1e-8, 7)
    assert t.solver.override() is t.solver
    with pytest.raises(TypeError, match="Scene solver must be a skxfem.Solver"):
        Scene(QUAD, LINE, solver={"linear": "direct"})
    for kwargs, message in ((dict(linear="lu"), "linear must be one of"),
                            (dict(linear_tol=0.0), "linear_tol must be a number in"),
                            (dict(max_iter=0), "max_iter must be a positive integer"),
                            (dict(max_iter=np.bool_(True)), "max_iter must be a positive")):
        with pytest.raises(ValueError, match=message):
            Solver(**kwargs)


@pytest.mark.parametrize("mu", [5e-324, 1e-11, 2e10, 1e308])
def test_26c_a_friction_outside_its_range_is_refused_in_python_too(mu):
    """A μ the solve cannot resolve (μp underflows: Λ = r/(μp) was NaN; or overflows)."""
    with pytest.raises(ValueError, match=r"Scene friction \(Coulomb's mu\) must be 0 or in "
                                         r"\[1e-10, 1e\+10\]"):
        Scene(QUAD, LINE, law="coulomb", friction=mu)
    for ok in (0.0, 1e-10, 1e10):
        assert Scene(QUAD, LINE, law="coulomb", friction=ok).friction == ok


@pytest.mark.parametrize("part, message", [
    (SurfaceLoad("ymax", pressure=1e200), r"loads\[0\] pressure: 1e\+200 is beyond the "
                                          r"largest load the solver handles, 1e\+150"),
    (SurfaceLoad("ymax", traction=(0.0, lambda x: 1e151 * x[0])),
     r"loads\[0\] traction\[1\]: <lambda> reaches 1e\+151 at \(1, 1\), which is beyond"),
    (Displacement("ymax", {"x": "exp(50*y)"}), r"displacements\[1\] x: exp\(50\*y\) reaches "
                                                r"5.18e\+21 at \(0, 1\), which is more than 1000"),
])
def test_26d_python_checks_the_magnitudes_as_scene_files_do(part, message):
    """SurfaceLoad(pressure=1e200) then solve raised RuntimeError ... please report: now
    the ValueError of the scene file's check, before solving, in Python too."""
    from skxfem import solve
    s = Scene(QUAD, LINE, displacements=(clamped("ymin"),))
    s = dataclasses.replace(s, loads=(part,)) if isinstance(part, SurfaceLoad) else \
        dataclasses.replace(s, displacements=s.displacements + (part,))
    with pytest.raises(ValueError, match=message):
        solve(s)


def test_26e_a_history_is_an_ordered_sequence_of_at_most_max_steps():
    """A dict history ran its keys as load factors (0, 1), silently; a set has no order;
    10 000 steps took 152 s.  A numpy array of factors is a list of factors."""
    from skxfem import contact
    from skxfem.scene import MAX_STEPS

    s = dataclasses.replace(strip(n=3), law="frictionless", displacements=(
        clamped("ymin"), Displacement("ymax", {"x": 0.0})))
    for bad in ({0: 0.5, 1: 1.0}, {0.5, 1.0}, 1.0, "1"):
        with pytest.raises(ValueError, match=r"history must be a non-empty sequence \(a list "
                                             r"or tuple, in order\)"):
            contact.solve(s, history=bad)
    with pytest.raises(ValueError, match=rf"history has {MAX_STEPS + 1} load steps, more "
                                         rf"than {MAX_STEPS}"):
        contact.solve(s, history=[1.0] * (MAX_STEPS + 1))
    with pytest.raises(ValueError, match=rf"Scene steps has {MAX_STEPS + 1} load steps"):
        dataclasses.replace(s, steps=(1.0,) * (MAX_STEPS + 1))
    a = contact.solve(s, history=np.array([0.5, 1.0]))
    b = contact.solve(s, history=[0.5, 1.0])
    assert [st.load for st in a.steps] == [0.5, 1.0]
    np.testing.assert_array_equal(a.steps[-1].pressure, b.steps[-1].pressure)
    assert dataclasses.replace(s, steps=np.array([0.5, 1.0])).steps == (0.5, 1.0)


def test_26f_numpy_numbers_and_arrays_are_taken_where_python_ones_are():
    """A numpy Box size and max_iter=np.int64(5) were refused; each field stores the
    Python value, so that the scene equals the one built from Python numbers."""
    from skxfem import contact

    assert Box(np.array([3, 4]), "quad", np.array([1.0, 2.0])) == Box((3, 4), "quad",
                                                                      (1.0, 2.0))
    assert Box(np.int64(3), "quad", (np.float64(1), np.float64(2))) == Box(3, "quad", (1, 2))
    assert Material(np.float64(2.0), np.float64(0.25)) == Material(2.0, 0.25)
    assert type(Material(np.float64(2.0)).E) is float
    given = Scene(Box(np.array([3, 4]), "quad"), plane(np.array([0, .5]), np.array([0., 1])),
                  displacements=(clamped("ymin"), Displacement("ymax", {np.int64(0): 0.0})),
                  loads=(SurfaceLoad("ymax", traction=np.array([0.0, -1.0])),),
                  quadrature_order=np.int64(2), law="coulomb", friction=np.float64(0.3),
                  rho_n=np.float64(4.0), steps=np.array([0.5, 1.0]))
    plain = Scene(Box((3, 4), "quad"), plane((0, .5), (0, 1)),
                  displacements=(clamped("ymin"), Displacement("ymax", {"x": 0.0})),
                  loads=(SurfaceLoad("ymax", traction=(0.0, -1.0)),), quadrature_order=2,
                  law="coulomb", friction=0.3, rho_n=4.0, steps=(0.5, 1.0))
    assert (given.mesh, given.quadrature_order, given.friction, given.rho_n, given.steps) == \
        (plain.mesh, plain.quadrature_order, plain.friction, plain.rho_n, plain.steps)
    assert type(given.quadrature_order) is int and type(given.rho_n) is float
    a = contact.solve(given, max_iter=np.int64(5), linear_tol=np.float64(1e-10))
    b = contact.solve(plain, max_iter=5, linear_tol=1e-10)
    np.testing.assert_array_equal(a.steps[-1].pressure, b.steps[-1].pressure)


def test_26g_a_body_force_is_a_vector_of_the_scene_dimension():
    s = Scene(QUAD, LINE, body_force=np.array([0.0, -9.81]))
    assert s.body_force == (0.0, -9.81)
    assert Scene(QUAD, LINE, body_force=(0, "-2*y")).body_force[1].dim == 2
    for bad, message in [((0.0,), r"body_force must be 2 values"),
                         ((0.0, float("nan")), r"body_force\[1\] must be finite"),
                         ((0.0, "-z"), r"body_force\[1\]")]:
        with pytest.raises(ValueError, match=message):
            Scene(QUAD, LINE, body_force=bad)
    from skxfem import solve
    with pytest.raises(ValueError, match=r"body_force\[1\]: 1e\+200 is a force per volume"):
        solve(Scene(QUAD, LINE, displacements=(clamped("ymin"),), body_force=(0, 1e200)))


def test_a_scenes_crack_enrichments_are_the_spaces_own():
    """scene.parts (a floor below the crack's space) names the enrichments a scene may ask
    for; they must be the ones crack.radius builds, or a valid scene would fail later."""
    from skxfem.crack.radius import ENRICHMENTS
    from skxfem.scene.parts import CRACK_ENRICHMENTS
    assert sorted(CRACK_ENRICHMENTS) == sorted(ENRICHMENTS)


SCALARS = [np.float64(0.2), np.float32(0.25), np.array(0.2), np.array(2), np.int64(2)]
"""Real scalars a notebook computes with numpy: each is a number to the scene."""


@pytest.mark.parametrize("v", SCALARS, ids=repr)
def test_every_number_of_a_scene_takes_numpy_scalars_and_0d_arrays(v):
    """sif_radius, enrichment_radius, friction, ρ, loads, imposed values, E, load factors,
    box lengths, body force, linear_tol: numpy's scalars and 0-d arrays were refused
    ("must be a positive number ... got array(0.2)"); each is stored as a Python float."""
    g, front = plane((0, 0.5), (0, 1)), plane((0.5, 0), (1, 0))
    crack = Interface(g, law="coulomb", friction=v, rho_n=v, rho_t=v, front=front,
                      enrichment_radius=v, sif_radius=v)
    for key in ("friction", "rho_n", "rho_t", "enrichment_radius", "sif_radius"):
        assert type(getattr(crack, key)) is float and getattr(crack, key) == float(v), key
    short = Scene(Box(2, "quad", size=(v, v)), plane((0, 0.1), (0, 1)), law="coulomb",
                  friction=v, material=Material(E=v), steps=(v, 1.0), body_force=(v, v),
                  loads=(SurfaceLoad("ymax", pressure=v),
                         SurfaceLoad("xmax", traction=(v, v))),
                  displacements=(Displacement("ymin", {"x": v, "y": 0.0}),))
    assert type(short.friction) is float and type(short.material.E) is float
    assert short.steps[0] == float(v) and type(short.steps[0]) is float
    assert short.mesh.size == (float(v),) * 2 and type(short.mesh.size[0]) is float
    assert type(short.loads[0].pressure) is float and type(short.body_force[0]) is float
    assert type(short.displacements[0].components["x"]) is float
    if float(v) < 1:
        assert Solver(linear_tol=v).linear_tol == float(v)


@pytest.mark.parametrize("bad, error, words", [
    (True, ValueError, "must be a positive number"),
    (np.bool_(True), ValueError, "must be a positive number"),
    ("0.2", ValueError, "must be a positive number"),
    (np.nan, ValueError, "must be a positive number"),
    (np.array(np.inf), ValueError, "must be a positive number"),
    (np.array([0.2, 0.3]), ValueError, r"must be a positive number .*got array\(\[0.2, 0.3\]\)"),
    (np.array([0.2]), ValueError, r"must be a positive number .*got array\(\[0.2\]\)"),
    (0.2 + 0j, ValueError, "must be a positive number"),
], ids=repr)
def test_what_is_not_one_real_number_is_still_refused_by_name(bad, error, words):
    g, front = plane((0, 0.5), (0, 1)), plane((0.5, 0), (1, 0))
    for key in ("sif_radius", "enrichment_radius"):
        with pytest.raises(error, match=f"Interface {key} {words}"):
            Interface(g, front=front, **{key: bad})
    with pytest.raises(ValueError, match="Interface friction .*must be a number >= 0"):
        Interface(g, law="coulomb", friction=bad, front=front)
    with pytest.raises((TypeError, ValueError), match="SurfaceLoad pressure"):
        SurfaceLoad("ymax", pressure=bad if not isinstance(bad, str) else [bad])
