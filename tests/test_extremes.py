"""The extremes table: every row solved within its tolerance or refused with a
one-line message, never a NaN (small meshes; the book runs the full table)."""
import math

import pytest

from skxfem.levelset import plane
from skxfem.scene import Box
from skxfem.studies.extremes import (
    Row,
    attempt,
    conditioning,
    largest,
    markdown_rows,
    memory_rows,
    modulus_rows,
    one_cell_rows,
    patch_error,
    patch_scene,
    poisson_rows,
    position_rows,
    rho_rows,
    shape_rows,
    space_rows,
)


def check_rows(rows):
    """No NaN anywhere; refusals carry a one-line message; solved rows meet their tolerance."""
    for r in rows:
        assert isinstance(r, Row)
        assert r.value is None or math.isfinite(r.value), r
        assert math.isfinite(r.tolerance) and math.isfinite(r.seconds), r
        assert "\n" not in r.message, f"{r.case}: the message is not one line"
        if r.outcome == "refused":
            assert r.value is None and len(r.message) > 20, r
        else:
            assert r.outcome == ("solved" if r.value <= r.tolerance else "inaccurate"), r
    return {r.case: r for r in rows}


def test_position_rows_solve_to_round_off_with_nodes_on_gamma():
    """Γ through nodes (through one node, along faces) is cut exactly; Γ within SNAP
    edge lengths of a node row (1e-10 h) puts the row on Γ, which is noted; 1e-14 h
    is within the round-off of ψ (cut.ROUND_OFF = 1.4e-14 h): on Γ, silently.  All
    pass the patch test to round-off, 1e-12 (measured ≤ 5e-15)."""
    rows = check_rows(position_rows(["tri", "hex"], n=2))
    for cell in ("tri", "hex"):
        for case in (f"{cell}, Γ at 1e-14 h from a node row",
                     f"{cell}, Γ at 1e-10 h from a node row", f"{cell}, Γ through one node",
                     f"{cell}, Γ along cell faces"):
            assert rows[case].outcome == "solved" and rows[case].value < 1e-12, rows[case]
            noted = "put on it" in rows[case].message
            assert noted == ("1e-10" in case), rows[case]
        for offset in ("1e-06", "0.001", "0.5"):
            r = rows[f"{cell}, Γ at {offset} h from a node row"]
            assert r.outcome == "solved" and r.value < 1e-12, r
            assert "put on it" not in r.message
        assert "dropped (sliver)" in rows[f"{cell}, Γ at 1e-06 h from a node row"].message


def test_unstable_spaces_near_a_node_are_refused_as_nearly_dependent():
    rows = check_rows(space_rows((("tri", "naive", 1e-3), ("tet", "winner", 1e-6),
                                  ("tet", "vital", 1e-6))))
    for case in ("tri naive, exact, Γ at 0.001 h from a node row",
                 "tet winner, exact, Γ at 1e-06 h from a node row"):
        r = rows[case]
        assert r.outcome == "refused"
        assert r.message.startswith("the multipliers are nearly dependent on this mesh")
        assert 'use the vital space (space="vital")' in r.message
    assert rows["tet vital, exact, Γ at 1e-06 h from a node row"].outcome == "solved"


def test_conditioning_without_the_small_cut_rule_is_singular_on_slivers():
    rows = conditioning(["quad", "tri"], [1e-9, 0.5], n=2)
    assert all(math.isfinite(r.with_rule) and r.with_rule < 1e4 for r in rows)
    tri_sliver = rows[2]
    assert tri_sliver.dropped > 0 and tri_sliver.without is None
    for r in (rows[1], rows[3]):  # Γ mid-cell: nothing dropped, the same matrix
        assert r.dropped == 0 and r.without == pytest.approx(r.with_rule, rel=1e-10)


def test_modulus_rows_are_scale_invariant():
    rows = check_rows(modulus_rows([1e-6, 1e9], n=2))
    assert all(r.outcome == "solved" and r.value < 1e-12 for r in rows.values())


def test_poisson_rows_show_locking_on_quadrilaterals():
    rows = check_rows(poisson_rows((0.3, 0.4999), n=4, cells=("quad",)))
    assert rows["quad, ν = 0.3"].outcome == "solved"
    locked = rows["quad, ν = 0.4999"]
    assert locked.outcome == "inaccurate" and locked.value > 2 * rows["quad, ν = 0.3"].value


def test_rho_rows_do_not_change_the_answer():
    """Even ρ_τ = 1e9 × E/h, where the first Newton attempt stalls (a sticking point looks
    sliding), is solved: the rescue at the default ρ (issue 17)."""
    rows = check_rows(rho_rows((1e-6, 1e9), n=4))
    for case, r in rows.items():
        assert r.outcome == "solved" and "Newton iterations" in r.message, r


def test_one_cell_and_shapes():
    rows = check_rows(one_cell_rows(["tri", "prism"]) + shape_rows(["quad"], n2=4))
    assert all(r.outcome == "solved" for r in rows.values())
    assert rows["quad, slanted 45° (h = 1/4)"].value < 1e-12
    assert 1e-6 < rows["quad, circle inside (h = 1/4)"].value < 0.25


@pytest.mark.parametrize("linear", ["direct", "iterative"])
def test_memory_rows_name_the_largest_mesh_and_refuse_the_next(linear):
    n = largest("quad", 2**26, linear)
    rows = check_rows(memory_rows(["quad"], 2**26, solvers=(linear,)))
    fits, refused = rows.values()
    assert fits.outcome == "solved" and fits.value <= 2**26 and f"n = {n} ({linear})" in fits.case
    assert refused.outcome == "refused" and refused.message.startswith("the scene 'strip_quad_")
    assert "the limit is 64 MB" in refused.message and f"{linear} solve" in refused.message


def test_the_iterative_solver_fits_larger_meshes():
    for cell in ("quad", "hex"):
        assert largest(cell, 2**28, "iterative") > largest(cell, 2**28, "direct")


def test_attempt_never_hides_a_failure():
    with pytest.raises(RuntimeError, match="is nan"):
        attempt("g", "c", "m", 1.0, lambda: float("nan"))
    with pytest.raises(ZeroDivisionError):
        attempt("g", "c", "m", 1.0, lambda: 1 / 0)
    row = attempt("g", "c", "m", 1.0, lambda: (2.0, "note"))
    assert (row.outcome, row.value, row.message) == ("inaccurate", 2.0, "note")


def test_patch_error_is_round_off_and_format_is_one_line_per_row():
    scene = patch_scene(Box(2, "quad"), plane((0.5, 0.6), (0.0, 1.0)))
    error, note = patch_error(scene)
    assert error < 1e-12 and note == ""
    row = attempt("position", "quad", "energy error (patch)", 1e-8, lambda: error)
    assert len(markdown_rows([row, row]).splitlines()) == 4


# issue 18: Γ across a support, small pieces, what is refused -------------------------

@pytest.mark.parametrize("n", [4, 16])
def test_a_slanted_gamma_crossing_the_supported_bottom_passes_the_patch_test(n):
    """The issue's case: 3.4e-2 at n = 4, 2.3e-3 at n = 16 (not converging)."""
    scene = patch_scene(Box((n, n + 1), "quad"), plane((0.3, 0.0), (-0.47, 1.0)))
    assert patch_error(scene)[0] <= 1e-12


def test_support_and_piece_rows_are_solved_to_round_off():
    from skxfem.studies.extremes import CROSSINGS, PIECES, piece_rows, support_rows

    rows = check_rows(support_rows(["quad", "hex"]) + piece_rows(["tri", "prism"]))
    assert len(rows) == 2 * len(CROSSINGS) + 2 * len(PIECES)
    assert all(r.outcome == "solved" and r.value < 1e-12 for r in rows.values())


def test_refused_rows_are_refused_and_the_limits_solved():
    from skxfem.studies.extremes import limit_rows, refused_rows

    refused = check_rows(refused_rows())
    assert all(r.outcome == "refused" for r in refused.values())
    assert "nearly incompressible" in refused["material: ν = 0.49999999999"].message
    assert "rotate about z" in refused["rigid: inclusion, bilateral tie"].message
    assert "rotate about z" in refused["rigid: inclusion, frictionless contact"].message
    assert "translate along x" in refused["rigid: strip, bilateral tie, the top free in x"].message
    assert "Box size must lie in" in refused["geometry: Box size 1e-300"].message
    limits = check_rows(limit_rows(["tri", "hex"]))
    assert all(r.outcome == "solved" for r in limits.values())
