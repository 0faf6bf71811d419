"""A crack as one more kind of interface (issue 29, 2D, law free): a scene with an
interface that has a front goes through the one path (assemble, solve, result, files)
and reproduces the harness :func:`skxfem.crack.solve.solve_crack` on the Williams square;
bad inputs are refused naming the argument."""
import json

import meshio
import numpy as np
import pytest

from skxfem.app.cli import main
from skxfem.crack.assembly import Load, Support
from skxfem.crack.solve import solve_crack
from skxfem.crack.williams import near_tip
from skxfem.gamma import Crack, Gamma, gamma
from skxfem.levelset import LevelSet, plane
from skxfem.problem import assemble
from skxfem.scene import Displacement, Interface, Scene, SurfaceLoad
from skxfem.scene.file import load_scene
from skxfem.solver import solve
from skxfem.studies.cracks import MATERIAL, _facets, straight_crack, unit_square

N, SIF_RADIUS = 11, 0.3
TIP = np.array([0.5, 0.5])


def _exact():
    _, _, frame = straight_crack(TIP, 0.0)
    return lambda p: near_tip(p, TIP, frame, MATERIAL, (1.0, 0.0))


def harness(enrichment="geometric", cell="tri"):
    """The Williams square, mode I, solved by the crack harness (radius: its default)."""
    m = unit_square(N, cell)
    psi, phi, _ = straight_crack(TIP, 0.0)
    ex = _exact()
    uncut = np.concatenate([_facets(m, lambda p: p[1] < 1e-12),
                            _facets(m, lambda p: p[1] > 1 - 1e-12),
                            _facets(m, lambda p: p[0] > 1 - 1e-12)])
    return solve_crack(m, psi, phi, MATERIAL, [Support(uncut, value=lambda p: ex(p).u)],
                       [Load(_facets(m, lambda p: p[0] < 1e-12),
                             lambda p: -ex(p).sigma[:, 0])],
                       enrichment, None, sif_radius=SIF_RADIUS)


def crack_scene(enrichment="geometric", cell="tri"):
    """The same problem as a scene: an interface with a front, law free."""
    psi, phi, _ = straight_crack(TIP, 0.0)
    ex = _exact()
    disp = tuple(Displacement(b, {"x": lambda p: ex(p).u[0], "y": lambda p: ex(p).u[1]})
                 for b in ("ymin", "ymax", "xmax"))
    load = SurfaceLoad("xmin", traction=(lambda p: -ex(p).sigma[0, 0],
                                         lambda p: -ex(p).sigma[1, 0]))
    crack = Interface(LevelSet(psi, 2, "psi"), law="free", front=LevelSet(phi, 2, "phi"),
                      enrichment=enrichment, sif_radius=SIF_RADIUS)
    return Scene(unit_square(N, cell), material=MATERIAL, displacements=disp, loads=(load,),
                 interfaces=(crack,))


def test_an_interface_with_a_front_is_a_crack_kind():
    psi, phi = plane((0, 0.5), (0, 1)), plane((0.5, 0), (1, 0))
    assert type(gamma(Interface(psi))) is Gamma
    assert type(gamma(Interface(psi, law="free", front=phi))) is Crack


@pytest.mark.parametrize("enrichment, cell", [("geometric", "tri"), ("topological", "tri"),
                                              ("geometric", "quad")])
def test_crack_scene_reproduces_the_harness(enrichment, cell):
    """The one path (assemble, solve, result) gives the harness' K, F, U and K_I, K_II."""
    s = harness(enrichment, cell)
    p = assemble(crack_scene(enrichment, cell))
    assert p.K.shape == (s.space.N, s.space.N), "the crack's unknowns [a, b, c]"
    assert p.P.shape[1] == 0 and p.B.shape[0] == 0, "law free: no multiplier"
    r = solve(crack_scene(enrichment, cell), linear="direct")
    assert np.abs(r.U - s.U).max() < 1e-10 * np.abs(s.U).max()
    (front,) = r.front
    assert np.allclose(front["points"], [TIP])
    assert abs(front["K_I"][0] - s.K_I) < 1e-10 and abs(front["K_II"][0] - s.K_II) < 1e-10
    assert abs(front["K_I"][0] - 1) < 0.05, "mode I, K_I = 1 at this mesh within 5 %"


def test_a_scene_without_a_front_has_no_front():
    from skxfem.scene.benchmarks import strip
    r = solve(strip(3, cell="tri"))
    assert r.front == () and "front" not in r.timings


def test_k_along_the_front_is_a_timed_stage():
    """K is computed in the solve: its seconds are the stage ``front``, so that the
    stages add up to the whole solve (the command line prints their sum)."""
    import time
    start = time.perf_counter()
    r = solve(crack_scene(), linear="direct")
    whole = time.perf_counter() - start
    assert set(r.timings) == {"cut", "enrich", "assemble", "solve", "front"}
    assert 0 < r.timings["front"] and sum(r.timings.values()) <= whole


WILLIAMS_TOML = """
name = "williams"
[mesh]
box = {{n = {n}, cell = "tri", size = [1, 1]}}
[levelset]
expr = "y - 0.5"
front = "x - 0.5"
[interface]
law = "free"
enrichment = "{enrichment}"
sif_radius = {sif_radius}
[material]
E = 1.0
nu = 0.3
{supports}
[[load]]
boundary = "xmin"
traction = ["{tx}", "{ty}"]
[solver]
linear = "direct"
"""

_R = "sqrt((x - 0.5)**2 + (y - 0.5)**2)"
_T = "atan2(y - 0.5, x - 0.5)"
_MU, _KAPPA = 1.0 / (2 * 1.3), 3 - 4 * 0.3
_UX = (f"1/(2*{_MU!r})*sqrt({_R}/(2*pi))*cos({_T}/2)*({_KAPPA!r} - 1 + 2*sin({_T}/2)**2)")
_UY = (f"1/(2*{_MU!r})*sqrt({_R}/(2*pi))*sin({_T}/2)*({_KAPPA!r} + 1 - 2*cos({_T}/2)**2)")
_SXX = f"1/sqrt(2*pi*{_R})*cos({_T}/2)*(1 - sin({_T}/2)*sin(3*{_T}/2))"
_SXY = f"1/sqrt(2*pi*{_R})*sin({_T}/2)*cos({_T}/2)*cos(3*{_T}/2)"


def _toml(enrichment="geometric"):
    supports = "\n".join(f'[[displacement]]\nboundary = "{b}"\nx = "{_UX}"\ny = "{_UY}"'
                         for b in ("ymin", "ymax", "xmax"))
    return WILLIAMS_TOML.format(n=N, enrichment=enrichment, sif_radius=SIF_RADIUS,
                                supports=supports, tx=f"-({_SXX})", ty=f"-({_SXY})")


def test_crack_scene_file_through_skxfem_run_writes_front(tmp_path, capsys):
    """... and its summary line gives K (it gave none, and 'pressure in [-0, -0]')."""
    path = tmp_path / "williams.toml"
    path.write_text(_toml())
    scene = load_scene(path)
    assert scene.interfaces[0].front is not None and scene.interfaces[0].law == "free"
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    data = json.loads((tmp_path / "out" / "result.json").read_text())
    s = harness()
    (front,) = data["front"]
    line = capsys.readouterr().out
    assert f"K_I {front['K_I'][0]:.4g}, K_II {front['K_II'][0]:.4g}" in line, line
    assert "pressure in [0, 0]" in line, line
    assert front["points"] == [[0.5, 0.5]]
    assert abs(front["K_I"][0] - s.K_I) < 1e-10 and abs(front["K_II"][0] - s.K_II) < 1e-10
    assert data["law"] == ["free"] and data["n_multipliers"] == 0 and front["interface"] == 0
    assert data["timings"]["front"] > 0, "K's time among the stages"
    vtu = meshio.read(tmp_path / "out" / "interface.vtu")
    (tip,) = vtu.cells_dict["vertex"][:, 0]
    assert np.allclose(vtu.points[tip], [0.5, 0.5, 0.0])
    assert vtu.point_data["K_I"][tip] == front["K_I"][0]
    assert vtu.point_data["K_II"][tip] == front["K_II"][0]
    others = np.arange(len(vtu.points)) != tip
    assert np.isnan(vtu.point_data["K_I"][others]).all(), "K only at the front point"
    assert np.isnan(vtu.point_data["pressure"][tip]) and vtu.point_data["interface"][tip] == 0
    assert np.isfinite(vtu.point_data["jump"][others]).all()


def test_crack_scene_file_in_interface_tables(tmp_path):
    text = _toml().replace('[levelset]\nexpr = "y - 0.5"\nfront = "x - 0.5"\n[interface]',
                           '[[interface]]\nexpr = "y - 0.5"\nfront = "x - 0.5"')
    path = tmp_path / "tables.toml"
    path.write_text(text)
    short = tmp_path / "short.toml"
    short.write_text(_toml())
    a, b = load_scene(path).interfaces[0], load_scene(short).interfaces[0]
    assert (a.law, a.enrichment, a.sif_radius, a.front.name) == \
        (b.law, b.enrichment, b.sif_radius, b.front.name)


@pytest.mark.parametrize("kwargs, words", [
    (dict(law="free", front="x - 0.5"), "front must be a skxfem.levelset.LevelSet"),
    (dict(law="free", front=plane((0.5, 0, 0), (1, 0, 0))), "front must have the dimension"),
    (dict(law="free", front=plane((0.5, 0), (1, 0)), enrichment="tip"), "enrichment"),
    (dict(law="free", front=plane((0.5, 0), (1, 0)), sif_radius=-1.0), "sif_radius"),
    (dict(sif_radius=0.3), "give its front"),
    (dict(enrichment_radius=0.3), "give its front"),
    (dict(law="free", front=plane((0.5, 0), (1, 0)), enrichment_radius=0.0),
     "enrichment_radius must be a positive number"),
    (dict(law="free", front=plane((0.5, 0), (1, 0)), enrichment_radius=float("nan")),
     "enrichment_radius"),
    (dict(law="free", front=plane((0.5, 0), (1, 0)), enrichment="topological",
          enrichment_radius=0.3), "leave it out with enrichment='topological'"),
])
def test_bad_crack_inputs_are_refused_naming_the_argument(kwargs, words):
    with pytest.raises(ValueError, match=words):
        Interface(plane((0, 0.5), (0, 1)), **kwargs)


def test_a_crack_with_a_material_per_side_is_refused_naming_it():
    """material_plus with a crack: the solve ended in "AttributeError: 'CrackXSpace'
    object has no attribute 'rule'"; a ValueError naming material_plus, when the scene is
    built."""
    from skxfem import Box, Material, Scene
    crack = Interface(plane((0, 0.5), (0, 1)), law="free", front=plane((0.5, 0), (1, 0)))
    with pytest.raises(ValueError, match=r"material_plus: a crack .* give one material"):
        Scene(Box(4, "tri"), interfaces=(crack,), material_plus=Material(2.0, 0.3))


def test_a_3d_crack_is_the_3d_kind_and_takes_tetrahedra_only():
    from skfem import MeshHex1, MeshTet1

    from skxfem.crack.kind3d import Crack3D

    g = gamma(Interface(plane((0, 0, 0.5), (0, 0, 1)), law="free",
                        front=plane((0.5, 0, 0), (1, 0, 0))))
    assert type(g) is Crack3D and not g.splits
    with pytest.raises(ValueError, match="MeshTet1"):
        g.cut(MeshHex1().refined(1), "interfaces[0]")
    # contact on its faces (tests/test_crack_contact_3d.py): a crack along mesh planes
    # crosses no edge strictly, its multipliers are at its nodes behind the front, as a
    # Cut lists a vertex on Γ (the point (v, v), edge id -1)
    g = gamma(Interface(plane((0, 0, 0.5), (0, 0, 1)), law="frictionless",
                        front=plane((0.5, 0, 0), (1, 0, 0))))
    m = MeshTet1.init_tensor(*(np.linspace(0, 1, 5),) * 3)            # z = 0.5: a plane
    cut = g.cut(m)
    assert np.all(cut.edge_ids == -1) and np.array_equal(cut.edges[0], cut.edges[1])
    assert np.allclose(cut.points, m.p[:, cut.edges[0]]) and np.all(cut.points[0] < 0.5)
    assert cut.edge_ids.size == 10, "x = 0, 1/4 (x = 1/2 is the front), y = 0 .. 1"
    assert g.multipliers(m, cut).P.shape == (10, 10)


@pytest.mark.parametrize("edit, words", [
    (lambda t: t.replace('enrichment = "geometric"', 'enrichment = "tip"'), "enrichment"),
    (lambda t: t.replace('front = "x - 0.5"\n', ''), "give its front"),
    (lambda t: t.replace('front = "x - 0.5"', 'front = 3'), "front must be a formula"),
])
def test_bad_crack_scene_files_are_refused(tmp_path, edit, words):
    path = tmp_path / "bad.toml"
    path.write_text(edit(_toml()))
    with pytest.raises((ValueError, TypeError), match=words):
        load_scene(path)


def test_schema_documents_the_crack_keys(capsys):
    assert main(["schema"]) == 0
    out = capsys.readouterr().out
    for key in ("front", "enrichment", "enrichment_radius", "sif_radius", "free"):
        assert key in out


@pytest.mark.parametrize("keys, radius, sif_radius", [
    ("enrichment_radius = 0.4\nsif_radius = 0.3", 0.4, 0.3),
    ("enrichment_radius = 0.35", 0.35, None),
    ("", None, None),
])
def test_a_scene_file_s_radii_are_the_harness_radii(tmp_path, keys, radius, sif_radius):
    """enrichment_radius and sif_radius of a file reach the solve; left out, both take
    the defaults (r_e 0.2 diameters, r_d 0.75 r_e), which meet K within 1 % on h = 1/11."""
    path = tmp_path / "radii.toml"
    path.write_text(_toml().replace(f"sif_radius = {SIF_RADIUS}", keys))
    r = solve(load_scene(path))
    m = unit_square(N, "tri")
    psi, phi, _ = straight_crack(TIP, 0.0)
    ex = _exact()
    uncut = np.concatenate([_facets(m, lambda p: p[1] < 1e-12),
                            _facets(m, lambda p: p[1] > 1 - 1e-12),
                            _facets(m, lambda p: p[0] > 1 - 1e-12)])
    s = solve_crack(m, psi, phi, MATERIAL, [Support(uncut, value=lambda p: ex(p).u)],
                    [Load(_facets(m, lambda p: p[0] < 1e-12), lambda p: -ex(p).sigma[:, 0])],
                    "geometric", radius, sif_radius=sif_radius)
    (front,) = r.front
    assert abs(front["K_I"][0] - s.K_I) < 1e-9 and abs(front["K_II"][0] - s.K_II) < 1e-9
    assert abs(s.K_I - 1) < 0.01 and abs(s.K_II) < 0.01


def test_law_free_on_a_through_cut_leaves_each_side_on_its_own_supports():
    """Law free on a Γ that cuts the body through: no multiplier, each side moves as its
    own supports say (Ω⁻ clamped, Ω⁺ given a uniform displacement)."""
    from skfem import MeshQuad1

    from skxfem.scene import clamped

    m = MeshQuad1.init_tensor(np.linspace(0, 1, 5), np.linspace(0, 1, 6))
    scene = Scene(m, plane((0, 0.5), (0, 1)), law="free",
                  displacements=(clamped("ymin"), Displacement("ymax", {"x": 0.1, "y": 0.2})))
    r = solve(scene, linear="direct")
    assert r.n_multipliers == 0 and r.problem.P.shape[1] == 0
    y = m.p[1]                       # Γ at 0.5 cuts the cells between 0.4 and 0.6
    assert np.allclose(r.u_minus[:, y < 0.7], 0, atol=1e-12)
    assert np.allclose(r.u_plus[:, y > 0.3], [[0.1], [0.2]], atol=1e-12)
    with pytest.raises(ValueError, match="free"):   # Ω⁺ held by nothing: named
        solve(Scene(m, plane((0, 0.5), (0, 1)), law="free",
                    displacements=(clamped("ymin"),)), linear="direct")


def test_a_crack_and_a_through_cut_in_one_scene(tmp_path):
    """A crack beside a bonded Γ that cuts the body through: two regions (the crack splits
    none), the crack's front and K; the files hold only facets between cut points."""
    from dataclasses import replace

    from skxfem.app.io import write_result

    scene = crack_scene()
    scene = replace(scene, interfaces=scene.interfaces + (
        Interface(plane((0, 0.05), (0, 1)), law="bonded"),))   # 3 cells of room
    r = solve(scene, linear="direct")
    assert r.regions.tolist() == [[-1], [1]]
    assert len(r.front) == 1 and abs(r.front[0]["K_I"][0] - 1) < 0.05
    assert r.facets.min() >= 0
    files = write_result(r, tmp_path)
    assert json.loads(files["json"].read_text())["front"][0]["points"] == [[0.5, 0.5]]


def test_the_jump_at_the_crack_points_is_the_opening_of_mode_I():
    """[[u]] = u⁻ - u⁺ at the crack's cut points, against the exact Williams opening:
    mode I opens the crack, u_y(Ω⁺ face) > u_y(Ω⁻ face), so [[u]]_y < 0 behind the tip."""
    r = solve(crack_scene(), linear="direct")
    ex = _exact()
    x = r.points
    eps = 1e-9
    exact = ex(x - [[0], [eps]]).u - ex(x + [[0], [eps]]).u
    assert np.all(r.jump[1] < 0)
    assert np.abs(r.jump - exact).max() < 0.1 * np.abs(exact).max()   # 5 % at n = 11


def test_3d_front_points_near_the_free_surfaces_are_not_interior(tmp_path, capsys):
    """A through crack's front ends on the two free sides z = 0, 1: the points whose bump
    reaches them are not ``interior`` (K is not trusted there: a bonded crack, K = 0,
    gave K_III about ±0.2 at the points half a cell from the sides); result.json holds the
    flag and skxfem run's summary line ranges over the interior points."""
    from skxfem.scene import Box, Displacement
    from skxfem.scene import SurfaceLoad as Load
    crack = Interface(plane((0, 0.5, 0), (0, 1, 0)), law="bonded",
                      front=plane((0.5, 0, 0), (1, 0, 0)))
    scene = Scene(Box(7, "tet"), material=MATERIAL, interfaces=(crack,),
                  displacements=(Displacement("ymin", {"x": 0.0, "y": 0.0, "z": 0.0}),),
                  loads=(Load("ymax", traction=(0.3, 1.0, 0.2)),), name="bonded")
    r = solve(scene, linear="direct")
    (front,) = r.front
    z, inner = front["points"][:, 2], front["interior"]
    assert inner.dtype == bool and not inner[np.argmin(z)] and not inner[np.argmax(z)]
    assert inner.any() and np.all(inner == ((z > 0.2) & (z < 0.8)))
    # measured: |K_III| ≤ 0.010 inside, 0.21 and 0.20 at the ends (the tie leaves K
    # about 0.02, not 0, on this coarse mesh)
    k3 = np.abs(front["K_III"])
    assert k3[inner].max() < 0.1 * k3[~inner].min()
    from skxfem.app.io import write_result
    write_result(r, tmp_path)
    data = json.loads((tmp_path / "result.json").read_text())
    assert data["front"][0]["interior"] == inner.tolist()
    from skxfem.app.cli import _fronts
    line = _fronts(r)
    k3 = front["K_III"][inner]
    assert f"K_III in [{k3.min() + 0.0:.4g}, {k3.max() + 0.0:.4g}]" in line


@pytest.mark.parametrize("dim", [2, 3])
def test_free_faces_passing_through_each_other_are_said(dim):
    """An edge crack pressed shut with free faces: K_I < 0 (the faces interpenetrate,
    -3.54 in 2D) was returned with nothing said.  A FrontPointsWarning names the front,
    K_I and the cure; pulled open, or with frictionless faces (K_I = 0), nothing."""
    import warnings

    from skxfem.crack.kind3d import FrontPointsWarning
    from skxfem.scene import Box, clamped
    top, bottom = ("ymax", "ymin") if dim == 2 else ("zmax", "zmin")
    gamma_ = plane(np.r_[np.zeros(dim - 1), 0.52], np.eye(dim)[-1])
    front = plane(np.r_[0.5, np.zeros(dim - 1)], np.eye(dim)[0])

    def pressed(p, law="free"):
        return Scene(Box(10 if dim == 2 else 6, "tri" if dim == 2 else "tet"),
                     interfaces=(Interface(gamma_, law=law, front=front),),
                     material=MATERIAL, displacements=(clamped(bottom),),
                     loads=(SurfaceLoad(top, pressure=p),))

    with pytest.warns(FrontPointsWarning, match=r"'plane\(.*\)': K_I < 0 \(down to -.*front "
                      r"points.*law 'free', pass through each other.*law = 'frictionless'"):
        (fr,) = solve(pressed(1.0)).front
    assert np.all(fr["K_I"] < 0)
    for scene in (pressed(-1.0), pressed(1.0, "frictionless")):
        with warnings.catch_warnings():
            warnings.filterwarnings("error", category=FrontPointsWarning,
                                    message=".*pass through")
            (fr,) = solve(scene).front
        if scene.interfaces[0].law == "free":
            assert np.all(fr["K_I"] > 0), "pulled open"


@pytest.mark.parametrize("dim", [2, 3])
def test_a_level_set_not_finite_or_a_front_outside_is_refused_by_name(dim):
    """φ NaN on part of the mesh (a square root of a negative number) was 'phi: psi
    returned NaN or inf at some mesh vertices' (the front called psi, no place); a front
    that never meets the crack named no key to change.  Both now name the crack, the
    level set, a vertex and the cure."""
    from skxfem.scene import Box, clamped
    top, bottom = ("ymax", "ymin") if dim == 2 else ("zmax", "zmin")
    psi = LevelSet(lambda x: x[-1] - 0.52, dim, "crack")

    def scene(front):
        return Scene(Box(6, "tri" if dim == 2 else "tet"),
                     interfaces=(Interface(psi, law="free", front=front),),
                     material=MATERIAL, displacements=(clamped(bottom),),
                     loads=(SurfaceLoad(top, pressure=-1.0),))

    with pytest.raises(ValueError, match=r"the crack \('crack', front 'root'\): phi \(the "
                       r"front's level set\) is NaN or inf at \d+ of \d+ mesh vertices, e.g. "
                       r"nan at \(0, 0.*must be finite"), np.errstate(invalid="ignore"):
        solve(scene(LevelSet(lambda x: np.sqrt(x[0] - 0.3) - 0.2, dim, "root")))
    with pytest.raises(ValueError, match=r"the crack \('crack', front 'far'\): phi < 0 all "
                       r".*move the front \(phi = 0\) into the body, or.*leave the front out"):
        solve(scene(LevelSet(lambda x: x[0] - 2.0, dim, "far")))


def _two_collinear(gap: float, n: int = 30):
    """Two collinear centre cracks of half-length 1 on y = 5 in a 10 x 10 plate pulled by
    σ = 1, mirror images of each other about x = 5, ``gap`` between their inner tips."""
    from skxfem.scene import Box
    c = 1 + gap / 2
    items = tuple(Interface(plane((0, 5), (0, 1)), law="free",
                            front=LevelSet(lambda x, s=s: np.abs(x[0] - 5 - s * c) - 1, 2,
                                           f"crack {s:+d}"))
                  for s in (-1, 1))
    return Scene(Box(n, "tri", size=(10.0, 10.0)), interfaces=items, material=MATERIAL,
                 displacements=(Displacement("ymin", {"x": 0.0, "y": 0.0}, where="x < 1e-9"),
                                Displacement("ymin", {"y": 0.0}, where="x > 10 - 1e-9")),
                 loads=(SurfaceLoad("ymax", traction=(0.0, 1.0)),
                        SurfaceLoad("ymin", traction=(0.0, -1.0))))


def test_two_cracks_whose_enriched_zones_overlap_are_coupled():
    """Two collinear cracks 2 apart, mirror images: each one's branch functions reach
    the other's tips (r_e = 2.83), and the stiffness held no block between two cracks'
    enrichments nor their K the other crack's field.  K came out lopsided (at h = 1/3 on
    the 20-wide plate of the sweep: K_II up to 0.85 σ√(πa) where it is 0, outer tips
    1.65 and 1.80); now the mirror tips agree and K_II vanishes."""
    r = solve(_two_collinear(2.0), linear="direct")
    tips = np.hstack([f["points"].T for f in r.front])
    K_I = np.concatenate([f["K_I"] for f in r.front])
    K_II = np.concatenate([f["K_II"] for f in r.front])
    order = np.argsort(tips[0])                    # outer, inner, inner, outer
    K_I, K_II = K_I[order], K_II[order]
    scale = np.sqrt(np.pi)
    assert abs(K_I[0] - K_I[3]) < 1e-3 * scale and abs(K_I[1] - K_I[2]) < 1e-3 * scale
    assert np.abs(K_II).max() < 5e-3 * scale
    assert K_I[1] > K_I[0] > scale                 # the inner tips feel each other most


def test_a_crack_tip_too_near_another_interface_is_refused_before_the_solve():
    """Tips 0.2 apart (h = 1/3): their K came out 4 to 14 times too large, with nothing
    said (or the system was singular); now refused by name, before the solve."""
    with pytest.raises(ValueError, match=r"interfaces\[0\] \('plane.*'\): the tip at \(4\.9, "
                       r"5\) is 0\.2 from interfaces\[1\].*under a cell"):
        assemble(_two_collinear(0.2))


def test_a_crack_beside_a_free_cut_is_coupled_to_it():
    """An edge crack in the part x < 5.1 of a plate that a free Γ at x = 5.1 cuts off: the
    crack's branch functions reach the cut's cells, whose Heaviside enrichment had no
    block with them (K_I -6.3 % at h = 1/3, +50 % at h = 1/6 against the body of width
    5.1 meshed alone); now within 0.2 %."""
    from skxfem.scene import Box

    def scene(full: bool, h: float = 1 / 3):
        W = 7.0 if full else 5.1
        crack = Interface(plane((0, 8), (0, 1)), law="free", front=plane((2.5, 0), (1, 0)))
        cut = (Interface(plane((5.1, 0), (1, 0)), law="free"),) if full else ()
        held = (Displacement("ymin", {"x": 0.0, "y": 0.0}, where="x > 5.1"),) if full else ()
        pull = lambda s: (0.0, lambda p: s * (p[0] < 5.1))      # noqa: E731
        return Scene(Box((round(W / h), 49), "tri", size=(W, 16.0)),
                     interfaces=(crack,) + cut, material=MATERIAL,
                     displacements=(Displacement("ymin", {"x": 0.0, "y": 0.0},
                                                 where="x < 1e-9"),
                                    Displacement("ymin", {"y": 0.0}, where="x > 4 and x < 4.5"),
                                    ) + held,
                     loads=(SurfaceLoad("ymax", traction=pull(1.0)),
                            SurfaceLoad("ymin", traction=pull(-1.0))))

    alone = solve(scene(False), linear="direct").front[0]["K_I"][0]
    cut_off = solve(scene(True), linear="direct").front[0]["K_I"][0]
    assert abs(cut_off / alone - 1) < 3e-3, (cut_off, alone)


def test_a_3d_front_on_the_boundary_is_refused_as_the_2d_tip_is():
    """φ = x - 1 on the unit cube: the crack z = 0.52 cuts the body through, its front on
    the face x = 1.  The 2D kind refuses a tip on the boundary; the 3D kind solved a body
    held along that line only (max jump 687 under a unit traction) and said only that no
    front point had room for K.  Now refused before the solve, naming the cure; a front
    0.01 inside is solved (its K left out, with the note)."""
    from skxfem.scene import Box, clamped

    def scene(x_front):
        return Scene(Box(4, "tet"), material=MATERIAL, displacements=(clamped("zmin"),),
                     loads=(SurfaceLoad("zmax", traction=(0.0, 0.0, 1.0)),),
                     interfaces=(Interface(LevelSet(lambda x: x[2] - 0.52, 3, "crack"),
                                           law="free", front=LevelSet(
                                               lambda x: x[0] - x_front, 3, "front")),))

    with pytest.raises(ValueError, match=r"the crack \('crack', front 'front'\): its front "
                       r"lies on the body's boundary.*leave the front out"):
        assemble(scene(1.0))
    assert assemble(scene(0.99)).interfaces[0].cut.segments.shape[-1] > 0


def _broken_ring(fronts):
    """A ring of radius 0.2 in the unit square (Box(21, 'quad')) broken into two cracks,
    the arcs |y - 0.5| < 0.1 right and left of x = 0.5, with the ``fronts`` φ of each
    (right, left); pulled by σ_yy = 1."""
    from skxfem.scene import Box
    items = tuple(Interface(LevelSet(lambda x: np.hypot(x[0] - 0.5, x[1] - 0.5) - 0.2, 2,
                                     f"ring {s}"), law="free", front=LevelSet(f, 2, s))
                  for s, f in zip(("right", "left"), fronts))
    return Scene(Box(21, "quad"), interfaces=items, material=MATERIAL,
                 displacements=(Displacement("ymin", {"x": 0.0, "y": 0.0}, where="x < 1e-9"),
                                Displacement("ymin", {"y": 0.0}, where="x > 1 - 1e-9")),
                 loads=(SurfaceLoad("ymax", traction=(0.0, 1.0)),
                        SurfaceLoad("ymin", traction=(0.0, -1.0))))


def test_a_broken_ring_of_two_cracks_with_one_front_above_the_ring_is_refused():
    """Fronts φ = max(|y - 0.5| - 0.1, ±(0.5 - x)) are equal above and below the ring,
    where both zones reach: there the two cracks' branch functions are the same functions
    of the same (φ, ψ), and the LU found the system singular (pivot 2e-33), its message
    blaming the zone's size (enrichment_radius = 2 was singular too).  Refused before the
    solve, naming the cure; fronts of their own (φ = 0 on the rays through each crack's
    tips) solve, the tips mirrored through the centre equal."""
    band = (lambda x: np.maximum(np.abs(x[1] - 0.5) - 0.1, 0.5 - x[0]),
            lambda x: np.maximum(np.abs(x[1] - 0.5) - 0.1, x[0] - 0.5))
    with pytest.raises(ValueError, match=r"two cracks give \d+ node\(s\) .* the same branch "
                       r"functions.*give each crack a front phi of its own"):
        solve(_broken_ring(band), linear="direct")
    s, c = 0.5, np.sqrt(0.75)                                # sin, cos of the tips' 30°
    rays = (lambda x: np.abs(x[1] - 0.5) * c - (x[0] - 0.5) * s,
            lambda x: np.abs(x[1] - 0.5) * c + (x[0] - 0.5) * s)
    right, left = solve(_broken_ring(rays), linear="direct").front
    for k in ("K_I", "K_II"):          # mirrored through the centre (the quads' diagonals)
        a = right[k][np.argsort(right["points"][:, 1])]
        b = left[k][np.argsort(-left["points"][:, 1])]
        assert np.abs(a - b).max() < 1e-3 * np.abs(a).max(), k
    assert right["K_I"].min() > 0.05
