"""skxfem.gamma: every step below the scene takes Γ's geometry from one object.

1. The through-cut kind meets the contract of the module notes: its cut is
   skxfem.cut's, its normals are unit and point into Ω⁺, its nodal ψ is the one
   the solve used.
2. A kind is the one place geometry comes from: a kind that wraps the through-cut
   one and counts its calls is used by assemble for the cut, the space, every
   multiplier space and the normals of the results, for one and for two
   interfaces, tie and contact, and the answers are those of the plain kind.
3. The scene is checked and its mesh resolved once per solve (issue 28 item 3),
   load states of a contact history included.
"""
from dataclasses import replace

import numpy as np
import pytest

import skxfem
import skxfem.problem as problem_module
import skxfem.scene.model as model
from skxfem.cut import cut as cut_mesh
from skxfem.gamma import Gamma, gamma
from skxfem.levelset import circle, plane
from skxfem.scene import Box, Interface, Scene, SurfaceLoad, clamped, rollers
from skxfem.scene.benchmarks import strip


def test_the_through_cut_kind_meets_the_contract():
    ls = circle((0.5, 0.5), 0.3)
    g = gamma(Interface(ls, law="bilateral"))
    mesh = skxfem.fem.meshes.box(6, "tri")
    c = g.cut(mesh, "")
    ref = cut_mesh(mesh, ls)
    assert np.array_equal(c.points, ref.points) and np.array_equal(c.facets, ref.facets)
    n = g.normals(c)
    assert np.allclose(np.linalg.norm(n, axis=0), 1.0, atol=1e-14)
    outward = (c.points - 0.5) / np.linalg.norm(c.points - 0.5, axis=0)
    assert np.allclose(n, outward, atol=1e-14)             # into Ω⁺ = {ψ > 0}, outside
    assert np.allclose(g.normals_at(c.points), n, atol=1e-14)
    assert g.nodal(c) is c.psi
    V = g.space(mesh, c)
    assert V.n_enr == mesh.dim() * c.enriched.size
    assert g.multipliers(mesh, c).P.shape[0] == c.edge_ids.size
    with pytest.raises(TypeError, match="skxfem.scene.Interface"):
        gamma(ls)


class Counting(Gamma):
    """The through-cut kind, counting the calls of each method of the contract."""

    calls: dict = {}

    def _count(self, name):
        Counting.calls[name] = Counting.calls.get(name, 0) + 1

    def cut(self, mesh, label=""):
        self._count("cut")
        return super().cut(mesh, label)

    def space(self, mesh, cut, order=None):
        self._count("space")
        return super().space(mesh, cut, order)

    def multipliers(self, mesh, cut, fixed=None, per_edge=None):
        self._count("multipliers")
        return super().multipliers(mesh, cut, fixed, per_edge)

    def normals(self, cut):
        self._count("normals")
        return super().normals(cut)


def _two(law="bonded"):
    return Scene(Box(6, "quad"), interfaces=(Interface(plane((0, 0.3), (0, 1)), law),
                                              Interface(plane((0, 0.7), (0, 1)), "bonded")),
                 displacements=(clamped("ymin"), rollers("xmin")),
                 loads=(SurfaceLoad("ymax", pressure=1.0),))


@pytest.mark.parametrize("scene", [strip(4, "tri"), replace(strip(4, "quad"),
                                   law="frictionless", displacements=strip(4).displacements
                                   + (rollers("xmin"),)), _two(), _two("frictionless")],
                         ids=["one tie", "one contact", "two ties", "two, contact"])
def test_assemble_takes_every_geometry_from_the_kind(monkeypatch, scene):
    plain = skxfem.solve(scene)
    Counting.calls = {}
    monkeypatch.setattr(problem_module, "gamma", lambda i: Counting(i))
    counted = skxfem.solve(scene)
    n = len(scene.interfaces)
    assert Counting.calls["cut"] == Counting.calls["space"] == n
    assert Counting.calls["multipliers"] >= n and Counting.calls["normals"] >= n
    assert all(isinstance(q.gamma, Counting) for q in counted.problem.interfaces)
    assert np.array_equal(plain.U, counted.U)
    assert np.array_equal(plain.traction, counted.traction)


@pytest.mark.parametrize("scene", [strip(3, "quad"), _two(),
                                   replace(strip(3), law="frictionless", steps=(0.5, 1.0),
                                           displacements=strip(3).displacements
                                           + (rollers("xmin"),))],
                         ids=["tie", "two interfaces", "contact, two steps"])
def test_a_solve_checks_the_scene_and_resolves_its_mesh_once(monkeypatch, scene):
    counts = {"resolve_mesh": 0, "check_scene": 0}

    def counted(name):
        real = getattr(model, name)

        def wrapper(*args, **kwargs):
            counts[name] += 1
            return real(*args, **kwargs)
        return wrapper

    for name in counts:
        monkeypatch.setattr(model, name, counted(name))
    skxfem.solve(scene)
    assert counts == {"resolve_mesh": 1, "check_scene": 1}


def test_load_states_are_checked_against_the_resolved_mesh(monkeypatch):
    base = replace(strip(3), law="frictionless",
                   displacements=strip(3).displacements + (rollers("xmin"),))
    state = replace(base, name="twice", loads=(SurfaceLoad("ymax", pressure=2.0),))
    calls = []
    real = model.resolve_mesh
    monkeypatch.setattr(model, "resolve_mesh", lambda s: calls.append(s.name) or real(s))
    r = skxfem.contact.solve(base, history=[base, state])
    assert calls == [base.name]                  # the states reuse the scene's mesh
    alone = skxfem.contact.solve(state)           # frictionless: the path does not matter
    assert np.allclose(r.steps[1].pressure, alone.steps[-1].pressure, atol=1e-10)
    bad = replace(base, loads=(SurfaceLoad("ymax", pressure=1e300),))
    with pytest.raises(ValueError, match="beyond the largest load"):
        skxfem.contact.solve(base, history=[base, bad])   # still checked


def test_load_states_take_the_problems_space_and_refuse_another_gamma_or_mesh(monkeypatch):
    """A load state is not assembled again: its loads and imposed values are taken on
    the scene's space (skxfem.problem.state_loads); a Γ given by another but equal level
    set is the same Γ, a moved Γ or another mesh is refused."""
    base = replace(strip(3), law="frictionless",
                   displacements=strip(3).displacements + (rollers("xmin"),))
    twice = replace(base, name="twice", loads=tuple(
        replace(load, pressure=f"2*({load.pressure.text})") for load in base.loads))
    assembled = []
    real = problem_module.assemble
    monkeypatch.setattr(skxfem.contact.history, "assemble",
                        lambda *a, **k: assembled.append(1) or real(*a, **k))
    r = skxfem.contact.solve(base, history=[base, twice])
    assert len(assembled) == 1                     # the scene's, not the states'
    assert np.allclose(r.steps[1].pressure, 2 * r.steps[0].pressure, atol=1e-12)
    gamma0 = base.interfaces[0].levelset
    equal = replace(twice, levelset=plane((0.0, 0.5), (0.0, 1.0)))   # another object
    assert equal.levelset is not gamma0
    again = skxfem.contact.solve(base, history=[base, equal])
    assert np.array_equal(again.steps[1].pressure, r.steps[1].pressure)
    for bad in (replace(twice, levelset=plane((0.0, 0.45), (0.0, 1.0))),
                replace(twice, mesh=Box(4, "quad"))):
        with pytest.raises(ValueError, match=r"history\[1\]: a load state must keep"):
            skxfem.contact.solve(base, history=[base, bad])


@pytest.mark.parametrize("a, warned", [(0.06, True), (0.2, False)])
def test_a_2d_tip_whose_domain_is_clipped_under_a_few_cells_warns(a, warned):
    """A centre crack of half-length a on the unit square (h = 1/20): at a = 0.06 each
    tip's domain stops half-way to the other, 1.2 cells, and K_I came out 11 % low
    (against Tada's centre crack), silently; now a FrontPointsWarning names the tip.  At
    a = 0.2 (4 cells) no warning."""
    import warnings

    from skxfem import Box, Displacement, Interface, Material, Scene, SurfaceLoad
    from skxfem.crack.kind3d import FrontPointsWarning
    from skxfem.levelset import LevelSet, plane
    front = LevelSet(lambda x: np.abs(x[0] - 0.5) - a, 2, "centre crack")
    scene = Scene(Box(20, "tri"), material=Material(1.0, 0.3), interfaces=(
        Interface(plane((0, 0.525), (0, 1)), law="free", front=front),),
        displacements=(Displacement("ymin", {"y": 0.0}),
                       Displacement("ymin", {"x": 0.0}, where="x < 1e-9")),
        loads=(SurfaceLoad("ymax", traction=(0.0, 1.0)),))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        skxfem.solve(scene)
    texts = [str(w.message) for w in caught if issubclass(w.category, FrontPointsWarning)]
    assert len(texts) == (2 if warned else 0), texts
    assert all("clipped to 1.2 cells by another tip" in t for t in texts)
