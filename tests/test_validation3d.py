"""Tests for skxfem/studies/validation3d.py: the genuinely 3D validation converges where it should.

On the block of skxfem.fem.exact3d (Γ slanted against all three axes), small
meshes n = 6 and 12 cells per side:

1. The stable spaces (winner, vital) converge on hexahedra, prisms and
   tetrahedra: energy error and L² pressure error at rate about 1.
   Margins: the pressure rate > 0.9 × 1; the energy rate > 0.8 × 1, as it is
   still rising on these meshes (tetrahedra: 0.79, 0.91 on n = 4, 8, 16 and
   0.87 on 6 → 12, measured).
2. The naive space oscillates: its largest pressure error is many times that
   of the vital space (prisms at n = 6, hexahedra at n = 12), and on
   tetrahedra the solver refuses it (nearly dependent multipliers), which
   the study keeps as a Failure.
3. The summary holds every number with its rates, and the failures.
"""
import json

import numpy as np
import pytest

from skxfem.studies.convergence import observed_rates
from skxfem.studies.validation3d import (
    CELLS,
    EXPECTED_RATES,
    NAIVE_TET_MAX_N,
    last_rates,
    study_block,
    summary,
)

NS = (6, 12)
ENERGY_MARGIN, PRESSURE_MARGIN = 0.8, 0.9


@pytest.fixture(scope="module")
def stable():
    return study_block(NS, spaces=("winner", "vital"))


@pytest.mark.parametrize("cell", CELLS)
@pytest.mark.parametrize("space", ["winner", "vital"])
def test_stable_spaces_converge_at_the_expected_rates(stable, cell, space):
    rows = [r for r in stable.rows[cell] if r.space == space]
    assert [r.n for r in rows] == list(NS)
    h = [r.h for r in rows]
    energy = observed_rates(h, [r.energy for r in rows])[-1]
    pressure = observed_rates(h, [r.pressure_l2 for r in rows])[-1]
    assert energy > ENERGY_MARGIN * EXPECTED_RATES["energy"], \
        f"{space} on {cell}: energy error rate {energy:.2f}, expected about 1"
    assert pressure > PRESSURE_MARGIN * EXPECTED_RATES["pressure_l2"], \
        f"{space} on {cell}: pressure error rate {pressure:.2f}, expected about 1"
    assert rows[-1].pressure_l2 < 0.03 and rows[-1].energy < 0.12, \
        f"{space} on {cell}: errors at n = 12 too large"
    assert last_rates(stable)[cell, space] == pytest.approx((energy, pressure))
    assert not stable.failures, "no stable space is refused"


def vital_max(stable, cell, n):
    return next(r.pressure_max for r in stable.rows[cell] if r.space == "vital" and r.n == n)


@pytest.mark.parametrize("cell, n, factor", [("prism", 6, 20), ("hex", 12, 5)])
def test_naive_space_oscillates(stable, cell, n, factor):
    naive = study_block([n], cells=(cell,), spaces=("naive",)).rows[cell][0]
    assert naive.pressure_max > factor * vital_max(stable, cell, n), (
        f"naive on {cell}: largest pressure error {naive.pressure_max:.3f}, vital "
        f"{vital_max(stable, cell, n):.3f}")
    assert naive.energy < 1.05 * min(r.energy for r in stable.rows[cell] if r.n == n), \
        "the displacement of the naive space is as good: only the pressure oscillates"


def test_naive_space_on_tetrahedra_is_refused_or_not_run():
    block = study_block([6, NAIVE_TET_MAX_N + 1], cells=("tet",), spaces=("naive",))
    assert block.rows["tet"] == []
    refused, skipped = block.failures
    assert (refused.n, skipped.n) == (6, NAIVE_TET_MAX_N + 1)
    assert "nearly dependent" in refused.reason
    assert skipped.reason.startswith("not run")


def test_summary_holds_every_number_and_is_json(stable):
    s = summary(stable)
    json.dumps(s)                                       # plain numbers only
    assert set(s["studies"]) == set(CELLS)
    for cell in CELLS:
        for space, t in s["studies"][cell].items():
            rows = [r for r in stable.rows[cell] if r.space == space]
            assert t["n"] == list(NS) and t["energy"] == [r.energy for r in rows]
            assert np.allclose(t["energy_rates"], observed_rates([1 / n for n in NS], [
                r.energy for r in rows]), atol=1e-4)
            assert len(t["pressure_l2_rates"]) == 1 and len(t["pressure_max"]) == 2
    assert s["failures"] == [] and s["expected_rates"] == EXPECTED_RATES
    assert len(s["gamma"]["normal"]) == 3


@pytest.mark.parametrize("bad", [{"cells": ("quad",)}, {"spaces": ("fancy",)}])
def test_unknown_cell_or_space_is_refused(bad):
    with pytest.raises(ValueError, match="unknown cells or spaces"):
        study_block([2], **bad)
