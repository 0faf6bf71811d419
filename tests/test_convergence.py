"""Convergence (skxfem/studies/convergence.py) on the exact plate: the paper's
Figures 9-10, quantitatively.  Naive multipliers on triangles/prisms do not
converge in pressure; winner nodes (algo1) and vital edges (algo2) do, at a
rate of at least 1, with algo2 the more accurate; displacements converge at
rate 1 in energy for every space."""
import numpy as np
import pytest

from skxfem.fem.exact import ExactPlate
from skxfem.fem.material import Material
from skxfem.scene.benchmarks import exact_plate, exact_strip
from skxfem.solver import solve
from skxfem.studies.convergence import observed_rates, study

NS = [8, 16, 32, 64]


def rates(rows, attr):
    return observed_rates([r.h for r in rows], [getattr(r, attr) for r in rows])


@pytest.fixture(scope="module", params=["tri", "prism"])
def table(request):
    cell = request.param
    if cell == "tri":
        make = lambda n, s: exact_strip(n, "tri", space=s)  # noqa: E731
    else:
        make = lambda n, s: exact_plate(n, "prism", nx=1, space=s)  # noqa: E731
    rows = study(make, NS, with_inf_sup=False)
    return {s: [r for r in rows if r.space == s] for s in ("naive", "winner", "vital")}


def test_naive_pressure_does_not_converge(table):
    err = [r.pressure_l2 for r in table["naive"]]
    assert min(err) > 0.5 and err[-1] >= 0.95 * err[0], err


@pytest.mark.parametrize("space", ["winner", "vital"])
def test_stabilised_pressure_converges(table, space):
    r = rates(table[space], "pressure_l2")
    assert np.all(r >= 1.0), r


def test_oscillation_amplitude(table):
    """The largest pointwise error (relative to max p): O(1) and growing for
    the naive space, the oscillation; falling for the stabilised ones."""
    naive = [r.pressure_max for r in table["naive"]]
    assert min(naive) > 1.0 and naive[-1] >= naive[0], naive
    for space in ("winner", "vital"):
        err = [r.pressure_max for r in table[space]]
        assert np.all(np.diff(err) < 0) and err[-1] < 0.5 * err[0], (space, err)


def test_vital_more_accurate_than_winner(table):
    for w, v in zip(table["winner"], table["vital"]):
        assert v.pressure_l2 < w.pressure_l2


def test_energy_rate_one_for_every_space(table):
    for space, rows in table.items():
        r = rates(rows, "energy")
        assert np.all(r > 0.85) and r[-1] > 0.9, (space, r)


def test_exact_solution_is_an_elastic_solution():
    """The manufactured loads reproduce the exact field: on quads the X-FEM
    pressure error falls at second order towards the exact p(x)."""
    errs = [study(lambda n, s: exact_strip(n, "quad", space=s), [n], ["naive"],
                  with_inf_sup=False)[0].pressure_l2 for n in (16, 32)]
    assert errs[1] < errs[0] / 2.4


def test_plate_equals_strip():
    """Rollers on x = 0, 1 make the 3D plate the 2D plane-strain strip."""
    r3 = solve(exact_plate(8, "prism", nx=1, space="naive"))
    r2 = solve(exact_strip(8, "tri", space="naive"))
    p3 = r3.pressure[np.isclose(r3.points[0], 0.0)]
    s3 = r3.points[1][np.isclose(r3.points[0], 0.0)]
    order2, order3 = np.argsort(r2.points[0]), np.argsort(s3)
    assert np.allclose(s3[order3], r2.points[0][order2], atol=1e-12)
    assert np.allclose(p3[order3], r2.pressure[order2], atol=1e-9)
    assert np.isclose(ExactPlate(Material(), 3).pressure(np.array([[0.], [0.5], [0.5]]))[0], 1.0)
