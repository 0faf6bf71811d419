"""Which linear solve ``auto`` takes (skxfem.linalg.choice): iterative from a size, direct
where projected CG stalls (multipliers on a crack's faces, a crack in 2D)."""
import numpy as np
import pytest

import skxfem.linalg.choice
import skxfem.solver
from skxfem.linalg.choice import AUTO_ITERATIVE, choose_linear
from skxfem.solver import ZONE_ITERATIONS, solve
from tests.test_crack_3d import rollers_cube
from tests.test_linalg_blocks import crack_2d, crack_3d

pytest.importorskip("pyamg")


@pytest.mark.parametrize("dim, kwargs, want", [
    (3, {}, "iterative"),
    (2, {}, "iterative"),
    (3, {"crack": True}, "iterative"),
    (2, {"crack": True}, "direct"),
    (3, {"crack_multipliers": True, "crack": True}, "direct"),
])
def test_auto_on_a_large_system(dim, kwargs, want):
    assert choose_linear("auto", dim, 10 * AUTO_ITERATIVE[dim], **kwargs) == want
    assert choose_linear("auto", dim, AUTO_ITERATIVE[dim] - 1, **kwargs) == "direct"


def test_a_method_named_is_taken_whatever_the_scene():
    assert choose_linear("iterative", 2, 10, crack=True) == "iterative"
    assert choose_linear("direct", 3, 10**7) == "direct"
    with pytest.raises(ValueError, match="linear must be one of"):
        choose_linear("cholesky", 3, 10)


def test_the_solver_asks_for_a_crack_s_choice(monkeypatch):
    monkeypatch.setitem(skxfem.linalg.choice.AUTO_ITERATIVE, 2, 10)
    monkeypatch.setitem(skxfem.linalg.choice.AUTO_ITERATIVE, 3, 10)
    assert solve(crack_2d(6), linear="auto").linear == "direct"
    # every node enriched: CG first, within ZONE_ITERATIONS (it converges here)
    auto, direct = (solve(crack_3d(4), linear=m) for m in ("auto", "direct"))
    assert auto.linear == "iterative" and auto.linear_info["iterations"] <= ZONE_ITERATIONS
    assert np.allclose(auto.front[0]["K_I"], direct.front[0]["K_I"], rtol=1e-8)
    monkeypatch.setattr(skxfem.solver, "ZONE_ITERATIONS", 1)         # stalls: direct
    assert solve(crack_3d(4), linear="auto").linear == "direct"
    monkeypatch.setattr(skxfem.linalg.choice, "AUTO_ZONE", 1.0)
    assert solve(crack_3d(4), linear="auto").linear == "iterative"


def test_auto_tries_cg_first_on_a_coarse_3d_crack_clamped_on_a_face():
    """benchmarks/crack_solve.py's edge crack at n = 8 (85 % of the nodes enriched, over
    AUTO_ZONE): clamped on a face, CG converges (79 iterations, measured), 2.5 times
    faster than the direct solve it had, with the same K."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).parents[1] / "benchmarks" / "crack_solve.py"
    spec = importlib.util.spec_from_file_location("crack_solve", path)
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    crack, _ = bench.scenes(8)
    auto, direct = (solve(crack, linear=m) for m in ("auto", "direct"))
    assert auto.linear == "iterative" and direct.linear == "direct"
    assert np.allclose(auto.front[0]["K_I"], direct.front[0]["K_I"], rtol=1e-8)


def test_auto_solves_a_coarse_3d_crack_directly():
    """:func:`tests.test_crack_3d.rollers_cube` at n = 7, default r_e: 91 % of the
    nodes branch-enriched, 7 104 unknowns (above AUTO_ITERATIVE); auto took CG, which
    stopped at 6.7e-6 after 500 iterations (a ConvergenceError from the default
    settings); now CG stalls within ZONE_ITERATIONS and the direct solve follows: K_I
    4.45 at mid-front (n = 6, direct: 4.46)."""
    r = solve(rollers_cube(7))
    assert r.n_dofs >= AUTO_ITERATIVE[3] and r.linear == "direct"
    K = r.front[0]["K_I"]
    assert 4.2 < K[K.size // 2] < 4.6
