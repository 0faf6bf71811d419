"""The crack studies (skxfem.studies.cracks): known numbers first (Tada's factor, polar
integrals in closed form), then properties of each study on coarse meshes (the slow
meshes are the tests of tests/test_crack_xfem.py and the chapter)."""
import json

import numpy as np
import pytest

from skxfem.studies.cracks import (
    PLATE,
    WilliamsRow,
    closed_crack,
    conditioning_study,
    energy_rates,
    polar_integral,
    summary,
    tada_factor,
    tada_study,
    tip_quadrature,
    williams_study,
)


def test_tada_factor_known_values():
    # a short edge crack: F → 0.752 + 0.37 = 1.122 (the free-surface factor)
    assert tada_factor(1e-9, 1.0) == pytest.approx(1.122, abs=1e-6)
    # Moës, Dolbow & Belytschko (1999): W = 7, a = 3.5, σ = 1 gives K_I = 9.37
    a, W = PLATE["a"], PLATE["W"]
    assert np.sqrt(np.pi * a) * tada_factor(a, W) == pytest.approx(9.37, abs=0.005)


def test_polar_integral_matches_closed_forms():
    tri = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    assert polar_integral((0, 0), tri, 0.0) == pytest.approx(0.5, rel=1e-13)
    # ∫ 1/r from the right-angle vertex: ∫₀^{π/2} R dα, R = d / cos(α - π/4), d = 1/√2
    assert polar_integral((0, 0), tri, -1.0) == pytest.approx(np.sqrt(2) * np.arcsinh(1.0),
                                                             rel=1e-12)
    # ∫ r² about an inner point: the polar moment of area, J_c + A |c - T|²
    T, c, area = np.array([0.2, 0.3]), tri.mean(axis=0), 0.5
    J_c = area * (1 + 1) / 18                      # (a² + b²)/36 · ab for legs a = b = 1
    assert polar_integral(T, tri, 2.0) == pytest.approx(J_c + area * ((c - T) ** 2).sum(),
                                                        rel=1e-12)


def test_tip_quadrature_polar_rule_is_exact_and_the_plain_rule_is_not():
    for power in (0.5, -0.5, -1.0):
        q = tip_quadrature(power)
        assert abs(q.polar / q.exact - 1) < 1e-12, q
        assert abs(q.plain / q.exact - 1) > 1e-3, q
        assert q.plain_points < q.polar_points
    with pytest.raises(ValueError, match="inside one cell"):
        tip_quadrature(tip=(0.5, 0.5))


def test_williams_study_geometric_beats_topological():
    rows = williams_study((7, 13), modes=("I",))
    assert [(r.enrichment, r.n) for r in rows] == [("topological", 7), ("topological", 13),
                                                 ("geometric", 7), ("geometric", 13)]
    by = {(r.enrichment, r.n): r for r in rows}
    for n in (7, 13):
        assert by["geometric", n].energy < by["topological", n].energy
        assert by["geometric", n].n_dofs > by["topological", n].n_dofs
    assert all(r.K_error < 0.06 and abs(r.K[1]) < 0.01 for r in rows), rows
    rates = energy_rates(rows)
    assert rates["geometric"] > rates["topological"] + 0.2, rates


def test_energy_rates_fit_a_power_law():
    rows = [WilliamsRow(n, 1 / n, kind, "I", (1.0, 0.0), 0.0, 3 * n ** -p, 0)
            for kind, p in (("a", 1.0), ("b", 0.5)) for n in (5, 10, 40)]
    assert energy_rates(rows) == {"a": 1.0, "b": 0.5}
    assert energy_rates(rows, "II") == {}


def test_block_scaling_cures_geometric_conditioning():
    rows = conditioning_study((7, 11))
    c = {(r.enrichment, r.scaling, r.n): r.condition for r in rows}
    for n in (7, 11):
        assert c["geometric", "block", n] <= 2 * c["topological", "block", n]
        assert c["geometric", "raw", n] > 1e3 * c["geometric", "block", n]
        assert c["geometric", "jacobi", n] > 10 * c["geometric", "block", n]
    assert c["geometric", "raw", 11] > c["geometric", "raw", 7], "raw grows with 1/h"


def test_closed_crack_needs_the_face_term():
    c = closed_crack(9)
    assert np.abs(c.with_face_term).max() < 1e-6, c
    assert -0.8 < c.without_face_term[0] < -0.7, c
    assert abs(c.without_face_term[1]) < 1e-6


def test_tada_study_rows_and_summary_are_json():
    plates = tada_study((14,), cells=("quad",))
    assert plates[0].K_ref == pytest.approx(9.3728, abs=1e-4)
    assert abs(plates[0].error) < 0.03 and abs(plates[0].K_II) < 1e-6
    williams = williams_study((5,), enrichments=("geometric",), modes=("I", "II"))
    s = json.loads(json.dumps(summary(williams, conditioning_study((5,), ("geometric",),
                                                                   ("block",)), plates)))
    assert [r["mode"] for r in s["williams"]["rows"]] == ["I", "II"]
    assert s["williams"]["energy_rates"] == {}, "one mesh: no rate"
    assert s["conditioning"][0]["scaling"] == "block" and s["tada"][0]["cell"] == "quad"
