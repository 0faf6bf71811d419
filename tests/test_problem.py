"""The assembled interface problem (skxfem/problem.py): one value for every solver."""
import dataclasses

import numpy as np
import pytest
import scipy.sparse as sp

import skxfem.lbb as lbb
import skxfem.solver as solver
from skxfem.cut import cut as cut_mesh
from skxfem.enrich import jump_matrix, stiffness, xfem_space
from skxfem.fem.quadrature import cell_rule
from skxfem.multipliers import coupling, interface_rule
from skxfem.problem import COUPLING, assemble, check_law, constrained_dofs
from skxfem.scene import resolve_mesh
from skxfem.scene.benchmarks import paper_plate, strip
from skxfem.stabilised import multiplier_space


def _spy(monkeypatch, module, seen):
    """Record every Problem that ``module`` assembles."""
    def spy(scene, law=None):
        p = assemble(scene, law)
        seen.append(p)
        return p
    monkeypatch.setattr(module, "assemble", spy)


def _same(a, b):
    return (a - b).count_nonzero() == 0 if sp.issparse(a) else np.array_equal(a, b)


def test_solve_and_inf_sup_see_the_same_problem(monkeypatch):
    """Issue 8's acceptance test: with a non-default quadrature_order the tie
    solve and the inf-sup test see one K, one B and one set of constrained dofs,
    and the K is the one of the scene's order (not the default's)."""
    scene = dataclasses.replace(strip(3, cell="quad", space="vital"), quadrature_order=4)
    seen, used = [], {}
    _spy(monkeypatch, solver, seen)
    _spy(monkeypatch, lbb, seen)
    inner = lbb.inf_sup_constant

    def record(A, B, M, **kw):
        used.update(A=A, B=B)
        return inner(A, B, M, **kw)

    monkeypatch.setattr(lbb, "inf_sup_constant", record)
    solver.solve(scene)
    lbb.inf_sup(scene, law=scene.law)
    assert len(seen) == 2
    s, i = seen
    for name in ("K", "B", "D", "g", "P", "F", "J"):
        assert _same(getattr(s, name), getattr(i, name)), name
    mesh = resolve_mesh(scene)
    V = xfem_space(mesh, cut_mesh(mesh, scene.levelset), 4)
    assert s.V.rule[0].shape == cell_rule(mesh, 4)[0].shape != cell_rule(mesh)[0].shape
    assert _same(s.K, stiffness(V, scene.material))
    free = np.setdiff1d(np.arange(s.V.N), s.D)
    assert _same(used["B"], s.B[:, free])


@pytest.mark.parametrize("law", ["bonded", "bilateral"])
def test_fields_agree_with_the_steps(law):
    """Each field is what the step modules give for the scene."""
    scene = paper_plate(3, cell="prism", space="vital")
    p = assemble(scene, law)
    mesh = resolve_mesh(scene)
    c = cut_mesh(mesh, scene.levelset)
    V = xfem_space(mesh, c)
    rule = interface_rule(mesh, c)
    assert p.law == law and p.ncomp == (3 if law == "bonded" else 1)
    assert _same(p.K, stiffness(V, scene.material))
    D, g = constrained_dofs(V, scene, mesh)
    assert _same(p.D, D) and _same(p.g, g)
    assert _same(p.J, jump_matrix(V, rule.cells, rule.ref))
    assert _same(p.B, (p.P.T @ coupling(V, rule, law)).tocsr())
    assert p.P.shape[0] == p.ncomp * c.edge_ids.size
    assert _same(p.multiplier_space.P, multiplier_space("vital", mesh, c).P)
    assert set(p.timings) >= {"cut", "space", "enrich", "stiffness", "load", "interface"}
    assert all(t >= 0 for t in p.timings.values())


def test_law_defaults_to_the_scene_and_unknown_laws_are_refused():
    scene = strip(3, cell="tri", law="bilateral")
    assert assemble(scene).law == "bilateral" and assemble(scene, "bonded").ncomp == 2
    assert check_law("bonded") in COUPLING
    with pytest.raises(ValueError, match="law must be one of"):
        assemble(scene, "sticky")


def test_problem_is_frozen():
    p = assemble(strip(3, cell="tri"))
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.law = "bilateral"


def test_builds_only_what_the_scene_requires(monkeypatch):
    """Issue 11, item 4: a 2D scene gets a 2D model, the enriched unknowns are
    those of the nodes of cut cells only, a tie solve factorises once, and a
    frictionless contact solve carries no friction unknowns."""
    import scipy.sparse.linalg as spla

    import skxfem.contact.newton as contact_newton
    import skxfem.linalg.saddle as saddle
    from skxfem.contact.laws import CONTACT_LAWS

    scene = strip(6, cell="tri", space="vital")
    p = assemble(scene)
    nodes = p.mesh.p.shape[1]
    assert p.mesh.dim() == 2 and p.V.n_std == 2 * nodes
    assert p.V.n_enr == 2 * np.unique(p.mesh.t[:, p.cut.side == 0]).size
    assert set(p.timings) == {"cut", "space", "enrich", "stiffness", "load", "constraints",
                              "interface", "prolongation"}

    calls = []
    real = spla.splu
    monkeypatch.setattr(saddle.spla, "splu", lambda *a, **k: calls.append(1) or real(*a, **k))
    solver.solve(scene, linear="direct")
    assert len(calls) == 1, "one factorisation per tie solve"

    assert "frictionless" in CONTACT_LAWS
    shapes = []
    real_solve = contact_newton.linear_step.direct
    monkeypatch.setattr(contact_newton.linear_step, "direct",
                        lambda A, R, nu, reuse=None: shapes.append((A.shape[0], nu))
                        or real_solve(A, R, nu, reuse))
    from skxfem.scene import Displacement
    held = scene.displacements + (Displacement("ymax", {"x": 0.0}),)  # Ω⁺ slides otherwise
    result = solver.solve(dataclasses.replace(scene, law="frictionless", displacements=held))
    m = result.ops.w.size
    assert shapes and all(n == nu + m for n, nu in shapes), "U and λ_n only: no friction rows"
    assert result.steps[-1].newton.iterations == len(shapes), "one linear solve an iteration"


@pytest.mark.parametrize("law, linear", [("frictionless", "direct"), ("adhesive", "direct"),
                                         ("coulomb", "direct"), ("frictionless", "iterative"),
                                         ("adhesive", "iterative")])
def test_contact_newton_factorises_a_matrix_once(monkeypatch, law, linear):
    """Issue 11, item 4: a Newton matrix unchanged since the last iteration (the same
    active set, after a damped step) is not factorised (or set up) again: solving a
    step twice with the same matrix costs one factorisation and gives the answer of
    a fresh one; a pressed strip takes one iteration, one factorisation."""
    import scipy.sparse.linalg as spla

    import skxfem.contact.step as linear_step
    import skxfem.linalg.iterative as iterative
    from skxfem import contact
    from skxfem.contact.newton import Iterate, StepProblem, jacobian, point_laws, residual
    from skxfem.scene import Displacement, SurfaceLoad

    if linear == "iterative":
        pytest.importorskip("pyamg")
    scene = dataclasses.replace(
        strip(4, cell="quad"), law=law, friction=0.5 if law == "coulomb" else None,
        displacements=strip(4).displacements + (Displacement("ymax", {"x": 0.0}),),
        loads=(SurfaceLoad("ymax", pressure=1.0),))
    calls = []
    if linear == "direct":
        real = spla.splu
        monkeypatch.setattr(spla, "splu", lambda *a, **k: calls.append(1) or real(*a, **k))
        res = contact.solve(scene, linear=linear)
        assert res.steps[-1].newton.iterations == 1 and len(calls) == 1
    else:  # K set up once (its AMG), each step's tie carried over from it, none set up anew
        import skxfem.linalg.amg as amg
        real, real_amg = iterative._setup, amg.amg
        monkeypatch.setattr(iterative, "_setup", lambda *a: calls.append(1) or real(*a))
        built = []
        monkeypatch.setattr(iterative, "amg", lambda *a: built.append(1) or real_amg(*a))
        res = contact.solve(scene, linear=linear)
        assert res.steps[-1].newton.iterations <= 3 and len(calls) == 0 and len(built) == 1
    pb, ops = res.problem, res.ops
    free = np.setdiff1d(np.arange(pb.V.N), pb.D)
    step = StepProblem(ops, pb.K, pb.F, free, np.zeros(pb.V.N),
                       point_laws(res.law[0], ops.tangent_held), res.law[0].rho_n)
    U = res.steps[-1].U.copy()
    U[free] *= 0.9  # off the answer, in the same active set
    it = Iterate(U, -res.steps[-1].pressure, res.steps[-1].traction)
    r = residual(step, it)
    A = jacobian(step, it, r)
    calls.clear()
    if linear == "direct":
        x1, _, factor = linear_step.direct(A, r.vector, step.nu)
        x2, _, _ = linear_step.direct(A, 2 * r.vector, step.nu, reuse=factor)
        x1 = 2 * x1  # the second right-hand side is twice the first
    else:
        x1, setup, _ = linear_step.iterative(step, r, reuse=None)
        x2, _, _ = linear_step.iterative(step, r, reuse=setup)
    assert len(calls) == 1, "the same matrix: one factorisation (set-up)"
    assert np.abs(x2 - x1).max() <= 1e-8 * np.abs(x1).max()
