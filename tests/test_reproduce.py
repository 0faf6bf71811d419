"""Tests for skxfem.app.reproduce: the main job writes every figure and sane numbers.

One reduced run (meshes 1/h = 8 and 16) is shared by the tests of this file.
"""
import contextlib
import io
import json

import pytest

from skxfem.app.reproduce import LEGEND, main

FIGURES = ["fig5", "fig6", "fig7", "fig8", "fig7_2d", "fig8_2d", "fig9", "fig10", "inf_sup",
           "frontier_energy", "frontier_pressure", "fig1", "fig2", "fig3", "fig4", "block3d",
           "block3d_pressure", "vital_3d", "crack_convergence", "crack_condition", "crack_K",
           "crack_branch", "crack_friction"]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("out")
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        code = main(["--quick", "--sizes", "8", "16", "--out", str(out)])
    (out / "printed.txt").write_text(printed.getvalue())
    return code, out, json.loads((out / "summary.json").read_text())


def test_exit_code_and_files(run):
    code, out, _ = run
    assert code == 0
    for name in FIGURES:
        path = out / f"{name}.png"
        assert path.exists() and path.stat().st_size > 10_000, f"{name}.png missing or empty"


def test_summary_layout(run):
    _, _, summary = run
    assert summary["sizes"]["d2"] == [8, 16] and summary["sizes"]["d3"] == [8, 16]
    assert set(summary["studies"]) == {"tri", "quad", "prism", "hex"}
    for cell, spaces in summary["studies"].items():
        for space, t in spaces.items():
            assert t["n"] == [8, 16], (cell, space)
            assert len(t["beta_h"]) == len(t["pressure_l2"]) == len(t["energy"]) == 2
            assert len(t["pressure_l2_rates"]) == len(t["energy_rates"]) == 1
    assert summary["timings"]["total"] > 0
    assert summary["figure6"]["vital"]["multipliers"] == 5
    assert summary["figure6"]["winner"]["multipliers"] == 5
    assert summary["frontier"], "the speed-accuracy frontier is part of the reproduction"
    assert (run[1] / "frontier.json").exists()


@pytest.mark.parametrize("cell", ["tri", "prism"])
def test_summary_values_are_the_papers_findings(run, cell):
    _, _, summary = run
    t = summary["studies"][cell]
    naive = t["naive"]["beta_h"]
    assert naive[1] < 0.6 * naive[0], f"naive β_h must fall with h on {cell}: {naive}"
    assert t["naive"]["pressure_l2"][1] > 0.5, "naive pressure must not converge"
    for space in ("winner", "vital"):
        assert min(t[space]["beta_h"]) >= 0.2, (cell, space, t[space]["beta_h"])
        assert t[space]["pressure_l2_rates"][0] >= 1.0, (cell, space)
        assert t[space]["energy_rates"][0] > 0.8, (cell, space)
    assert t["vital"]["pressure_l2"][1] < t["winner"]["pressure_l2"][1], "algo2 more accurate"


@pytest.mark.parametrize("cell", ["tri", "quad", "prism", "hex"])
def test_bonded_tie_is_reported_and_stable(run, cell):
    """β_h of the bonded tie the scenes solve, next to the bilateral one
    (issue 7: ≥ 0.3 on prisms with vital edges, no zero mode)."""
    _, _, summary = run
    for space, t in summary["studies"][cell].items():
        assert len(t["beta_h_bonded"]) == len(t["n_zero_bonded"]) == 2
        if space != "naive" or cell in ("quad", "hex"):
            assert min(t["beta_h_bonded"]) >= 0.3 and max(t["n_zero_bonded"]) == 0, \
                (cell, space, t["beta_h_bonded"], t["n_zero_bonded"])


def test_quad_spaces_coincide(run):
    _, _, summary = run
    assert summary["quad_spaces_coincide"] < 1e-8


def test_conforming_fem_curve_of_figure_9(run):
    """The paper: X-FEM on hexahedra converges at the rate of FEM on a mesh that
    follows Γ (both about 1)."""
    _, _, summary = run
    fem = summary["fem_conforming"]["hex"]
    assert fem["n"] == [8, 16] and len(fem["energy"]) == 2
    xfem = summary["studies"]["hex"]["naive"]["energy_rates"][0]
    assert fem["energy_rates"][0] > 0.9 and abs(fem["energy_rates"][0] - xfem) < 0.1


def test_block3d_numbers(run):
    """The genuinely 3D validation: the block on hex, prism and tet, every space, on
    the smallest size and its half (4, 8); the naive space on tetrahedra refused at
    n = 4, and off by orders of magnitude at n = 8."""
    _, _, summary = run
    block = summary["block3d"]
    assert summary["sizes"]["block"] == [4, 8]
    assert set(block["studies"]) == {"hex", "prism", "tet"}
    for cell, spaces in block["studies"].items():
        for space in ("winner", "vital"):
            t = spaces[space]
            assert t["n"] == [4, 8] and len(t["energy_rates"]) == 1
            assert t["energy_rates"][0] > 0.75 and t["pressure_l2_rates"][0] > 0.8, \
                (cell, space, t["energy_rates"], t["pressure_l2_rates"])
    assert block["studies"]["prism"]["naive"]["pressure_max"][-1] > 10 * \
        block["studies"]["prism"]["vital"]["pressure_max"][-1], "naive oscillates on prisms"
    assert block["studies"]["tet"]["naive"]["pressure_l2"] and \
        block["studies"]["tet"]["naive"]["pressure_l2"][0] > 10
    assert [(f["cell"], f["space"], f["n"]) for f in block["failures"]] == [("tet", "naive", 4)]
    assert block["gamma"]["normal"] == [0.2, 0.3, 1.0]


def test_crack_numbers(run):
    """The crack part of a reduced run: the Williams square on 1/h = 9, 17 (the sizes made
    odd), the conditioning on the same meshes, the plate on 33 cells across."""
    _, _, summary = run
    crack = summary["crack"]
    assert summary["sizes"]["crack"] == [9, 17] and summary["timings"]["crack"] > 0
    rows = crack["williams"]["rows"]
    assert {(r["mode"], r["enrichment"], r["n"]) for r in rows} == {
        (m, e, n) for m in ("I", "II") for e in ("topological", "geometric") for n in (9, 17)}
    assert all(r["K_error"] < 0.05 for r in rows)
    rates = crack["williams"]["energy_rates"]
    assert rates["geometric"] > rates["topological"] + 0.2, rates
    kappa = {(r["enrichment"], r["scaling"], r["n"]): r["condition"]
             for r in crack["conditioning"]}
    assert len(kappa) == 12
    assert kappa["geometric", "block", 17] <= 2 * kappa["topological", "block", 17]
    assert [(r["cell"], r["nx"]) for r in crack["tada"]] == [("tri", 33), ("quad", 33)]
    assert all(abs(r["error"]) < 0.02 for r in crack["tada"])
    # contact on the faces: the closed inclined crack on 1/h = 21, β_h on the crack sizes
    friction = crack["friction"]
    assert {(r["beta"], r["friction"]) for r in friction} == {
        (b, m) for b in (20.0, 30.0) for m in (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8)}
    assert all(r["K_II_rel"] < 0.02 for r in friction if r["slides"])
    assert all(r["K_II_error"] < 3e-3 for r in friction if not r["slides"])
    beta = {(r["space"], r["n"]): r["beta"] for r in crack["inf_sup"]}
    assert min(beta["vital", n] for n in (9, 17)) > 0.5 > 0.2 > beta["naive", 17]


def test_the_printed_tables_are_sorted_explained_and_followed_by_the_failures(run):
    """Each table's rows are sorted (dimension, cell, space, 1/h), the legend explains
    every column header, and each failure is printed below the tables, whole."""
    _, out, summary = run
    text = (out / "printed.txt").read_text()
    dims = {"tri": 2, "quad": 2, "prism": 3, "hex": 3, "tet": 3}
    spaces = ["naive", "winner", "vital"]
    tables = text.split("\n\n")[:2]
    for table in tables:
        header, *rows = table.splitlines()[1:]
        keys = [(dims[c], c, spaces.index(s), int(n))
                for c, s, n, *_ in (row.split() for row in rows)]
        assert len(keys) > 10 and keys == sorted(keys), table
        for column in header.split():
            assert f"\n  {column} " in LEGEND or column in ("cell", "space"), column
    assert LEGEND in text
    failures = text[text.index("Failures"):]
    assert text.index(LEGEND) < text.index("Failures")
    for f in summary["block3d"]["failures"]:
        assert f"{f['cell']} {f['space']} 1/h = {f['n']}:" in failures
        assert " ".join(f["reason"].split()) in " ".join(failures.split()), "the whole reason"
