import json

import pytest
from matplotlib.figure import Figure

from skxfem.studies.frontier import (
    CONTACT_SOLVERS,
    PLANS,
    SOLVERS,
    Plan,
    Point,
    pareto,
    summary,
    sweep,
)
from skxfem.viz.frontier_plots import plot_frontier, reproduce_frontier

TINY = (Plan("strip", ("quad", "tri"), ("vital",), (None, 4), ("direct",), (4, 8)),
        Plan("plate", ("hex",), ("naive",), (None,), ("direct",), (2,)))


def point(t, e, p=None, n=8):
    return Point("strip", "tri", "vital", None, "direct", n, 1, t, e, e if p is None else p)


@pytest.fixture(scope="module")
def points():
    return sweep(TINY[0]) + sweep(TINY[1])


def test_sweep_measures_every_method_and_errors_fall_with_h(points):
    assert len(points) == 2 * 2 * 2 + 1
    assert all(p.seconds > 0 and 0 < p.energy < 1 and 0 < p.pressure < 1 for p in points)
    for cell in ("quad", "tri"):
        coarse, fine = [p for p in points if p.cell == cell and p.quadrature is None]
        assert fine.energy < 0.7 * coarse.energy and fine.dofs > coarse.dofs


def test_the_error_measure_does_not_depend_on_the_quadrature_of_the_method(points):
    # the minimal exact rule and order 4 give the same P1 stiffness on triangles
    tri = {(p.quadrature, p.n): p for p in points if p.cell == "tri"}
    for n in (4, 8):
        assert tri[None, n].energy == pytest.approx(tri[4, n].energy, rel=1e-10)


def test_pareto_keeps_exactly_the_unbeaten_points():
    pts = [point(1, 0.5), point(2, 0.6), point(3, 0.1), point(0.5, 0.9), point(4, 0.1)]
    front = pareto(pts)
    assert [(p.seconds, p.energy) for p in front] == [(0.5, 0.9), (1, 0.5), (3, 0.1)]
    for p in pts:  # every point off the front is beaten by one on it
        if p not in front:
            assert any(q.seconds <= p.seconds and q.energy <= p.energy for q in front)
    with pytest.raises(ValueError, match="error must be 'energy' or 'pressure'"):
        pareto(pts, "time")


def test_summary_counts_front_points_per_method():
    pts = [point(1, 0.5, n=8), point(2, 0.1, n=16)]
    s = summary(pts)["tri/vital/q-/direct"]
    assert s["n"] == [8, 16] and s["on_energy_front"] == 2 and s["on_pressure_front"] == 2


def test_plan_checks_its_choices():
    with pytest.raises(ValueError, match="not in SOLVERS"):
        Plan("strip", ("tri",), ("vital",), (None,), ("amg",), (4,))
    with pytest.raises(ValueError, match="problem must be 'plate' or 'strip'"):
        Plan("cube", ("tri",), ("vital",), (None,), ("direct",), (4,))
    assert all(s in SOLVERS for plan in PLANS["quick"] for s in plan.solvers)


def test_plot_and_reproduce_write_figures_and_numbers(points, tmp_path):
    fig = plot_frontier(points, "energy")
    assert isinstance(fig, Figure) and len(fig.axes) == 2
    result = reproduce_frontier(tmp_path, plans=TINY[:1])
    assert {f.name for f in tmp_path.iterdir()} == {"frontier_energy.png",
                                                    "frontier_pressure.png", "frontier.json"}
    data = json.loads((tmp_path / "frontier.json").read_text())
    assert len(data["points"]) == 8 and set(data["methods"]) == set(result)


def test_summary_takes_the_front_of_each_benchmark_separately():
    slow_plate = Point("plate", "hex", "vital", None, "direct", 4, 1, 10.0, 0.9, 0.9)
    s = summary([point(1, 0.5), slow_plate])
    assert s["hex/vital/q-/direct"]["on_energy_front"] == 1


def test_reproduce_sizes_give_small_plans_of_both_benchmarks():
    from skxfem.studies.frontier import plans

    small = plans(True, [8, 4, 8])
    assert [p.problem for p in small] == ["plate", "strip"]
    assert all(p.sizes == (4, 8) and p.quadratures == (None,) for p in small)
    assert plans(False) == PLANS["full"] and plans(True) == PLANS["quick"]


def test_the_contact_rows_give_one_answer_for_every_choice():
    """Coulomb contact on the exact plate: the answer does not depend on the linear
    solve or on ρ (an augmentation), and a looser Newton tolerance moves it by
    about that tolerance; it sticks where pressed, so its errors are the tie's order."""
    plan = Plan("plate", ("hex",), ("vital",), (None,), CONTACT_SOLVERS + ("direct",), (4,))
    points = {p.solver: p for p in sweep(plan)}
    ref = points["coulomb"]
    for name in ("coulomb/iterative", "coulomb/rho100"):
        assert abs(points[name].energy - ref.energy) <= 1e-8 * ref.energy, name
        assert abs(points[name].pressure - ref.pressure) <= 1e-8 * ref.pressure, name
    assert abs(points["coulomb/tol1e-6"].pressure - ref.pressure) <= 1e-3 * ref.pressure
    tie = points["direct"]
    assert 0.5 < ref.energy / tie.energy < 2 and ref.pressure < 2 * tie.pressure
