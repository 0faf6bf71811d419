"""The command line: scene file -> solve -> result.json and VTU files; clean errors.

Every error the command anticipates is one line on stderr and exit 2 and leaves no
half-written result; an unexpected one is one line and exit 1; --debug re-raises.
"""
import errno
import json
import os
import subprocess
import sys
from pathlib import Path

import meshio
import numpy as np
import pytest

import skxfem
from skxfem.app import cli, io, reproduce
from skxfem.app.cli import main
from skxfem.contact.newton import ContactConvergenceError
from skxfem.scene.file import load_scene

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def run(tmp_path, name):
    assert main(["run", str(EXAMPLES / f"{name}.toml"), "--out", str(tmp_path / name)]) == 0
    return json.loads((tmp_path / name / "result.json").read_text())


def test_01_plate_example_runs_end_to_end(tmp_path, capsys):
    data = run(tmp_path, "plate")
    out = capsys.readouterr().out
    assert out.count("\n") == 1 and out.startswith("plate: ") and "multipliers" in out
    assert data["scene"] == "plate" and data["n_dofs"] > 0 and data["n_multipliers"] > 0
    points = np.array(data["points"])
    assert points.shape[1] == 3 and np.allclose(points[:, 2], 0.5), "points lie on Γ"
    assert data["max_jump"] < 1e-10, "the bonded interface does not open"
    assert min(data["pressure"]) > 0, "the plate is compressed everywhere on Γ"
    assert set(data["timings"]) >= {"cut", "enrich", "assemble", "solve"}
    m = meshio.read(tmp_path / "plate" / "displacement.vtu")
    assert m.cells[0].type == "hexahedron"
    assert len(m.cells[0]) == 4 * 4 * 5 + 4 * 4               # the cut layer on both sides
    assert meshio.read(tmp_path / "plate" / "interface.vtu").points.shape == points.shape


def test_02_plate_with_rollers_is_the_plane_strain_strip(tmp_path):
    """plate.toml at any x equals strip.toml (its (y, z) are the strip's (x, y))."""
    plate, strip = run(tmp_path, "plate"), run(tmp_path, "strip")
    s = np.array(strip["points"])
    for point, p in zip(plate["points"], plate["pressure"], strict=True):
        [k] = np.flatnonzero(np.isclose(s[:, 0], point[1]))
        assert p == pytest.approx(strip["pressure"][k], rel=1e-6)


def test_03_interface_force_balances_the_load(tmp_path):
    """∫_Γ p dx = ∫ 4x(1 - x) dx = 2/3 (vertical equilibrium of Ω⁺), p piecewise linear."""
    strip = run(tmp_path, "strip")
    order = np.argsort(np.array(strip["points"])[:, 0])
    x = np.array(strip["points"])[order, 0]
    p = np.array(strip["pressure"])[order]
    assert np.trapezoid(p, x) == pytest.approx(2 / 3, rel=1e-8)


@pytest.mark.parametrize("text, words", [
    ("[mesh]\nbox = {n = 'four', cell = 'quad'}\n[levelset]\nexpr = 'y - 0.5'",
     ["[mesh] box.n"]),
    ("[mesh]\nbox = {n = 3, cell = 'quad'}\n[levelset]\nexpr = 'open(y)'",
     ["[levelset] expr", "function call"]),
    ("[mesh]\nbox = {n = 2, cell = 'quad'}\n[levelset]\nexpr = 'y - 5.25'",
     ["cuts no cell"]),                       # refused by the solver's cut step
    ("[mesh]\nbox = {n = [2, 3], cell = 'quad'}\n[levelset]\nexpr = 'y - 0.5'\n"
     "[[load]]\nboundary = 'ymax'\npressure = 1.0",
     ["singular", "displacements"]),          # no support: the body floats
    ("[mesh]\nfile = 'nope.msh'\n[levelset]\nexpr = 'y - 0.5'", ["nope.msh", "not found"]),
    ("[mesh\nbox = 1", ["invalid TOML"]),
])
def test_04_bad_scenes_exit_2_with_one_line(tmp_path, capsys, text, words):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("skxfem: error: ") and "Traceback" not in err
    assert all(w in err for w in words), err
    assert not (tmp_path / "out").exists()


def test_05_missing_file_exits_2_and_debug_shows_the_error(tmp_path, capsys):
    assert main(["run", str(tmp_path / "nope.toml")]) == 2
    assert "nope.toml" in capsys.readouterr().err
    for argv in (["run", str(tmp_path / "nope.toml"), "--debug"],
                 ["--debug", "run", str(tmp_path / "nope.toml")]):
        assert main(argv) == 2, "--debug keeps the exit code of an anticipated error"
        err = capsys.readouterr().err
        assert "Traceback" in err and "MissingFileError" in err
        assert err.splitlines()[-1].startswith("skxfem: error: ") and "nope.toml" in err


def test_06_python_m_skxfem_and_default_out_folder(tmp_path):
    done = subprocess.run([sys.executable, "-m", "skxfem", "run", str(EXAMPLES / "strip.toml")],
                          cwd=tmp_path, capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "strip" / "result.json").is_file()       # --out defaults to ./<name>
    bad = subprocess.run([sys.executable, "-m", "skxfem", "run", "missing.toml"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=300, check=False)
    assert bad.returncode == 2 and "Traceback" not in bad.stderr


STRIP = str(EXAMPLES / "strip.toml")


def one_line(capsys, start="skxfem: error: "):
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(start) and "Traceback" not in err, err
    return err


@pytest.fixture
def no_solve(monkeypatch):
    """Fail the test if the command solves: the errors below come before the solve."""
    def solve(scene, **options):
        raise AssertionError("the command solved before checking")
    monkeypatch.setattr(cli, "solve", solve)


def test_07_version(capsys):
    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0
    assert capsys.readouterr().out.strip() == f"skxfem {skxfem.__version__}"


def test_08_out_is_an_existing_file(tmp_path, capsys, no_solve):
    (tmp_path / "taken").write_text("mine")
    for out in ("taken", "taken/sub"):
        assert main(["run", STRIP, "--out", str(tmp_path / out)]) == 2
        assert "taken" in one_line(capsys)
    assert [f.name for f in tmp_path.iterdir()] == ["taken"]
    assert (tmp_path / "taken").read_text() == "mine"


def test_09_out_not_writable(tmp_path, capsys, monkeypatch, no_solve):
    """Simulated: the machines run as root, for whom a read-only folder is writable."""
    monkeypatch.setattr(os, "access", lambda path, mode: False)
    assert main(["run", STRIP, "--out", str(tmp_path / "out")]) == 2
    assert "not writable" in one_line(capsys)
    assert list(tmp_path.iterdir()) == []


def test_10_a_failed_write_keeps_the_previous_result(tmp_path, capsys, monkeypatch):
    out = tmp_path / "strip"
    assert main(["run", STRIP, "--out", str(out)]) == 0
    before = {f.name: f.read_bytes() for f in out.iterdir()}

    def full_disk(result, path):          # a simulated full disk in the second file
        path.write_bytes(b"<VTKFile")
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setitem(io._WRITERS, "displacement", full_disk)
    capsys.readouterr()
    assert main(["run", STRIP, "--out", str(out)]) == 2
    assert "No space left on device" in one_line(capsys)
    assert {f.name: f.read_bytes() for f in out.iterdir()} == before


def test_11_the_size_guard_refuses_before_solving(tmp_path, capsys, no_solve):
    assert main(["run", STRIP, "--out", str(tmp_path / "o"), "--max-memory", "10K"]) == 2
    err = one_line(capsys)
    assert "strip" in err and "needs at least" in err and "--max-memory" in err
    assert "either solve" in err, "a bound over the solvers auto may pick"
    assert not (tmp_path / "o").exists()
    with pytest.raises(SystemExit) as done:
        main(["run", STRIP, "--max-memory", "lots"])
    assert done.value.code == 2 and "--max-memory" in one_line(capsys)


@pytest.mark.parametrize("argv", [["run"], ["run", STRIP, "--frobnicate"], ["fly"]])
def test_12_usage_errors_are_one_line(capsys, argv):
    with pytest.raises(SystemExit) as done:
        main(argv)
    assert done.value.code == 2
    one_line(capsys)


@pytest.mark.parametrize("error, code", [
    (RuntimeError("the multipliers do not balance"), 1),   # a numerical failure: a bug
    (KeyError("u"), 1),
    (ZeroDivisionError("a message\nover two lines"), 1),
    (MemoryError(), 2),                                    # anticipated: lower the limit
])
def test_13_unexpected_errors_are_one_line_and_debug_shows_them(
        tmp_path, capsys, monkeypatch, error, code):
    def solve(scene, **options):
        raise error
    monkeypatch.setattr(cli, "solve", solve)
    argv = ["run", STRIP, "--out", str(tmp_path / "o")]
    assert main(argv) == code
    err = one_line(capsys, "skxfem: unexpected error: " if code == 1 else "skxfem: error: ")
    assert type(error).__name__ in err if code == 1 else "--max-memory" in err
    assert ("--debug" in err) == (code == 1)
    for debug in (argv + ["--debug"], ["--debug"] + argv):
        assert main(debug) == code, "--debug shows the traceback and keeps the exit code"
        err = capsys.readouterr().err
        assert "Traceback" in err and type(error).__name__ in err
    assert not (tmp_path / "o").exists()


def test_14_the_nearly_singular_strip_of_issue_7_never_gives_a_traceback(tmp_path):
    """A slanted Γ on a fine triangle strip, naive space: solved, refused (exit 2) or,
    while the saddle solve raises RuntimeError, one line with exit 1."""
    scene = tmp_path / "slant.toml"
    scene.write_text("[mesh]\nbox = {n = [128, 129], cell = 'tri'}\n[levelset]\n"
                     "plane = {point = [0, 0.37], normal = [-0.21, 1]}\n"
                     "[[displacement]]\nboundary = 'ymin'\nkind = 'clamped'\n"
                     "[[load]]\nboundary = 'ymax'\npressure = '4*x*(1 - x)'\n"
                     "[interface]\nlaw = 'bonded'\nspace = 'naive'\n")
    done = subprocess.run([sys.executable, "-m", "skxfem", "run", str(scene), "--out",
                           str(tmp_path / "out")], capture_output=True, text=True,
                          timeout=300, check=False)
    assert "Traceback" not in done.stderr
    if done.returncode == 0:
        assert (tmp_path / "out" / "result.json").is_file()
    else:
        assert done.stderr.count("\n") == 1 and done.returncode in (1, 2), done.stderr
        assert done.returncode == 2 or "--debug" in done.stderr
        assert not (tmp_path / "out").exists()


def test_15_reproduce_is_forwarded(tmp_path, capsys):
    assert cli.FORWARDED["reproduce"][1] == reproduce.__name__
    with pytest.raises(SystemExit) as done:
        main(["reproduce", "--help"])
    assert done.value.code == 0 and "--quick" in capsys.readouterr().out
    (tmp_path / "taken").write_text("")
    assert main(["reproduce", "--out", str(tmp_path / "taken")]) == 2   # before computing
    assert "taken" in one_line(capsys)


def test_16_interrupted(tmp_path, capsys, monkeypatch):
    def solve(scene, **options):
        raise KeyboardInterrupt
    monkeypatch.setattr(cli, "solve", solve)
    assert main(["run", STRIP, "--out", str(tmp_path / "o")]) == 130
    one_line(capsys, "skxfem: interrupted")
    assert not (tmp_path / "o").exists()


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders; "
                                              "test_09 simulates the refusal instead")
def test_17_a_read_only_folder(tmp_path, capsys, no_solve):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        assert main(["run", STRIP, "--out", str(ro / "out")]) == 2
        assert "not writable" in one_line(capsys)
        assert list(ro.iterdir()) == []
    finally:
        ro.chmod(0o700)


# --- contact laws: contact.solve over the scene's load steps --------------------------

CONTACT = str(EXAMPLES / "contact.toml")


def test_18_contact_example_runs_and_its_json_satisfies_signorini(tmp_path, capsys,
                                                                   monkeypatch):
    def tie_solve(*args, **options):
        raise AssertionError("a contact scene went to the tie solve")
    monkeypatch.setattr(skxfem.solver, "solve_problem", tie_solve)
    s = load_scene(CONTACT)
    assert (s.name, s.law, s.friction, s.steps) == ("contact", "coulomb", 0.5, (0.5, 1.0))
    data = run(tmp_path, "contact")
    out = capsys.readouterr().out
    assert out.count("\n") == 1 and out.startswith("contact: coulomb, 2 load step(s), ")
    iterations = [st["newton"]["iterations"] for st in data["steps"]]
    assert f"{sum(iterations)} Newton iterations" in out
    last = data["steps"][-1]
    c = last["counts"]
    assert (f"{c['stick'] + c['slip']} in contact ({c['stick']} stick, {c['slip']} slip), "
            f"{c['open']} open, max pressure {max(last['pressure']):.4g}") in out
    assert data["law"] == ["coulomb"] and data["interfaces"][0]["friction"] == 0.5
    assert [st["load"] for st in data["steps"]] == [0.5, 1.0]     # [interface] steps
    for st in data["steps"]:
        assert set(st["status"]) == {"open", "stick", "slip"}
        newton = st["newton"]
        assert 0 <= newton["iterations"] <= 15   # 0: the predicted start was the answer
        assert all(len(v) == newton["iterations"] + 1 and v[-1] <= 1e-10
                   for v in newton["residuals"].values())
        p, gap = np.array(st["pressure"]), np.array(st["gap"])
        scale = p.max() * np.abs(gap).max()
        assert p.min() >= 0, "Signorini: p >= 0"
        assert gap.max() <= 1e-12 * np.abs(gap).max(), "Signorini: gap <= 0"
        assert np.abs(p * gap).max() <= 1e-12 * scale, "Signorini: p gap = 0"
        assert all(g < 0 for g, s in zip(gap, st["status"], strict=True) if s == "open")
        r = np.abs(np.array(st["tangential_traction"])[:, 0])
        assert np.all(r <= 0.5 * p * (1 + 1e-10)), "Coulomb: |r_τ| <= μp"
    m = meshio.read(tmp_path / "contact" / "interface.vtu")
    codes = [data["status_codes"][s] for s in last["status"]]
    np.testing.assert_array_equal(m.point_data["status"], codes)
    assert meshio.read(tmp_path / "contact" / "displacement.vtu").cells[0].type == "quad"


CONTACT_TEXT = (EXAMPLES / "contact.toml").read_text()


@pytest.mark.parametrize("edits, words", [
    ({"friction = 0.5": "friction = -0.1"}, ["[interface] friction", ">= 0"]),
    ({"friction = 0.5": "friction = 0.5\nrho_n = 0"}, ["[interface] rho_n", "> 0"]),
    ({"friction = 0.5": "friction = 0.5\nrho_t = -2.0"}, ["[interface] rho_t", "> 0"]),
    ({'law = "coulomb"': 'law = "glue"'}, ["[interface] law", "glue"]),
    ({"steps = [0.5, 1.0]": "steps = []"}, ["[interface] steps", "non-empty"]),
    ({'law = "coulomb"\nfriction = 0.5': 'law = "frictionless"',  # Ω⁺ free to slide in x
      '[[displacement]]\nboundary = "ymax"\nx = 2.0': '#'}, ["singular"]),
])
def test_19_bad_contact_values_exit_2_with_one_line(tmp_path, capsys, edits, words):
    text = CONTACT_TEXT
    for old, bad in edits.items():
        assert old in text
        text = text.replace(old, bad)
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    err = one_line(capsys)
    assert all(w in err for w in words), err
    assert not (tmp_path / "out").exists()


def test_20_a_contact_newton_that_does_not_converge_exits_2(tmp_path, capsys):
    """--max-iter 1: every attempt fails.  Each retry (the paper's fixed point: the
    example keeps the default ρ) and each cut of the first step is a note, in order,
    down to 1/64 of the step; then the one error line (issue 26)."""
    argv = ["run", CONTACT, "--out", str(tmp_path / "o"), "--max-iter", "1"]
    assert main(argv) == 2
    *notes, err = capsys.readouterr().err.splitlines()
    assert err.startswith("skxfem: error: ") and "Traceback" not in err
    assert "did not converge in 1 iterations" in err and "friction" in err
    assert "down to 1/64 of its increment" in err
    where, expected = "load step 1 of 2 (load factor 0.5)", []
    for k in range(7):                 # the increments 0 to 1, 0 to 1/2 ... 0 to 1/64
        here = where if k == 0 else f"{where}, increment 0 to 1/{2 ** k}"
        failed = f"skxfem: note: {here}: Newton did not converge in 1 iterations"
        expected.append(f"{failed}; retry 1 of 1: solving it again by the paper's fixed "
                        f"point on the friction threshold")
        if k < 6:
            expected.append(f"{failed} (nor its 1 retry); cut: next increment 0 to "
                            f"1/{2 ** (k + 1)} (1/{2 ** (k + 1)} of the step)")
    assert notes == expected
    assert not (tmp_path / "o").exists()
    assert main(argv + ["--debug"]) == 2
    assert "Traceback" in capsys.readouterr().err
    assert main(["run", CONTACT, "--out", str(tmp_path / "o"), "--max-iter", "15"]) == 0


def test_21_a_non_convergence_anywhere_in_the_history_is_one_line(tmp_path, capsys,
                                                                  monkeypatch):
    """Whatever raises it (a later step, the fixed point), the error is anticipated."""
    def solve(scene, **options):   # skxfem.solve: the file's settings, no option given
        assert scene.steps == (0.5, 1.0) and options == {}
        assert scene.solver == skxfem.Solver()
        raise ContactConvergenceError("the fixed point on the friction threshold failed "
                                      "in pass 2:\nalternates between two states")
    monkeypatch.setattr(cli, "solve", solve)
    assert main(["run", CONTACT, "--out", str(tmp_path / "o")]) == 2
    assert "pass 2: alternates" in one_line(capsys)
    assert ContactConvergenceError in cli.ANTICIPATED
    assert RuntimeError not in cli.ANTICIPATED, "other numerical failures stay exit 1"


def test_22_max_iter_is_for_contact_scenes(tmp_path, capsys, no_solve):
    assert main(["run", STRIP, "--out", str(tmp_path / "o"), "--max-iter", "5"]) == 2
    assert "--max-iter" in one_line(capsys) and not (tmp_path / "o").exists()
    for bad in ("0", "many"):
        with pytest.raises(SystemExit) as done:
            main(["run", CONTACT, "--max-iter", bad])
        assert done.value.code == 2 and "--max-iter" in one_line(capsys)


def test_23_grade_is_a_subcommand(tmp_path, capsys):
    """`skxfem grade PATH` is python -m skxfem.app.grade: a score table and grade.json;
    the untouched stub of an exercise fails the grade (exit 1)."""
    import shutil

    root = Path(__file__).resolve().parents[1] / "exercises"
    shutil.copytree(root / "01_levelset", tmp_path / "01_levelset")
    shutil.copy(root / "conftest.py", tmp_path / "conftest.py")
    report = tmp_path / "grade.json"
    code = main(["grade", str(tmp_path / "01_levelset"), "--report", str(report)])
    assert code == 1
    assert "01_levelset" in capsys.readouterr().out
    assert report.exists()


def test_24_the_linear_solve_is_an_option(tmp_path, capsys):
    """`--linear iterative` solves a tie with AMG + projected CG (the same pressures as
    the direct solve), and says how it went: the CG iterations on the summary line,
    the residuals in result.json; an unknown name is a usage error (exit 2, one line)."""
    pytest.importorskip("pyamg")
    plate = Path(__file__).resolve().parents[1] / "examples" / "plate.toml"
    pressures = {}
    for linear in ("direct", "iterative"):
        assert main(["run", str(plate), "--out", str(tmp_path / linear),
                     "--linear", linear]) == 0
        out = capsys.readouterr().out
        assert f"{linear} solve" in out
        data = json.loads((tmp_path / linear / "result.json").read_text())
        pressures[linear] = np.array(data["pressure"])
        info = data["linear_solve"]
        assert info["linear"] == linear and info["residual"] <= 1e-10
        assert info["balance"] <= 1e-8
        if linear == "direct":
            assert info["iterations"] is None and info["residuals"] is None
        else:  # one residual at the start, then one per CG iteration
            its = info["iterations"]
            assert its > 0 and f"({its} CG iterations)" in out
            assert len(info["residuals"]) == its + 1
            assert info["residuals"][-1] <= 1e-10 < info["residuals"][0]
    assert np.abs(pressures["iterative"] - pressures["direct"]).max() < 1e-6
    # the scene file's [solver] linear is the default, the command line overrides it
    text = plate.read_text()
    assert "[solver]" not in text
    chosen = tmp_path / "chosen.toml"
    chosen.write_text(text + '\n[solver]\nlinear = "iterative"\n')
    for extra, expect in (([], "iterative"), (["--linear", "direct"], "direct")):
        assert main(["run", str(chosen), "--out", str(tmp_path / "chosen"), *extra]) == 0
        assert f"{expect} solve" in capsys.readouterr().out
    # so is its linear_tol, and --linear-tol overrides it; result.json records the one used
    chosen.write_text(text + '\n[solver]\nlinear = "iterative"\nlinear_tol = 1e-6\n')
    for extra, expect in (([], 1e-6), (["--linear-tol", "1e-9"], 1e-9)):
        assert main(["run", str(chosen), "--out", str(tmp_path / "tol"), *extra]) == 0
        capsys.readouterr()
        info = json.loads((tmp_path / "tol" / "result.json").read_text())["linear_solve"]
        assert info["tol"] == expect and info["residual"] <= expect
    with pytest.raises(SystemExit) as done:
        main(["run", str(plate), "--linear", "cholesky"])
    assert done.value.code == 2
    assert "invalid choice: 'cholesky'" in capsys.readouterr().err


# --- issue 18: where results go, and every anticipated error in one line -----------

STRIP_TEXT = (EXAMPLES / "strip.toml").read_text()


def scene_file(folder, text, name="scene.toml"):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_text(text)
    return str(folder / name)


@pytest.mark.parametrize("name, folder", [
    ("../../escaped", "escaped"),
    ("ABSOLUTE", None),
    ("\x1b[31mred\x1b[0m\u202e", "31mred_0m"),
    ("a/b\\c d", "a_b_c_d"),
    ("..", "result"),
])
def test_25_without_out_the_results_stay_below_the_current_folder(
        tmp_path, capfd, monkeypatch, name, folder):
    """The scene file named the folder: '../../escaped' wrote two folders up, an absolute
    name wrote there, escape codes were echoed raw to the terminal."""
    if name == "ABSOLUTE":
        name = str(tmp_path / "elsewhere")
    scene = scene_file(tmp_path / "scenes", STRIP_TEXT.replace(
        'name = "strip"', "name = " + json.dumps(name)))
    here = tmp_path / "work" / "here"
    here.mkdir(parents=True)
    monkeypatch.chdir(here)
    assert main(["run", scene]) == 0
    out, err = capfd.readouterr()
    assert err == "" and out.count("\n") == 1
    assert "\x1b" not in out and "\u202e" not in out, "control characters are escaped"
    [written] = here.iterdir()
    assert folder is None or written.name == folder
    assert (written / "result.json").is_file()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scenes", "work"]
    assert sorted(p.name for p in (tmp_path / "work").iterdir()) == ["here"]


def test_26_an_empty_or_current_output_folder_is_refused(tmp_path, capsys, monkeypatch,
                                                         no_solve):
    """--out '' wrote into the current folder."""
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as done:
        main(["run", STRIP, "--out", ""])
    assert done.value.code == 2 and "--out" in one_line(capsys)
    for out in (".", str(tmp_path)):
        assert main(["run", STRIP, "--out", out]) == 2
        assert "current folder" in one_line(capsys)
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("keep")
    assert main(["run", STRIP, "--out", "mine"]) == 2
    assert "holds files that are not results ('notes.txt')" in one_line(capsys)
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["mine", "notes.txt"]


CORNER = "[[displacement]]\nwhere = 'x > 0.99 and y > 0.99'\nx = 9223372036854775808\n"


def anticipated(tmp_path, case):
    """(argv, words) of an error a user meets (issue 18): one line and exit 2."""
    (tmp_path / "deep.toml").write_text("x = " + "[" * 500 + "]" * 500 + "\n")
    (tmp_path / "folder.msh").mkdir()
    os.mkfifo(tmp_path / "fifo.msh")
    os.symlink("loop.msh", tmp_path / "loop.msh")
    (tmp_path / "junk.msh").write_text("garbage\n")
    (tmp_path / "cut.msh").write_text("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2\n")

    def edited(old, new, extra=""):
        return [scene_file(tmp_path, STRIP_TEXT.replace(old, new) + extra, "s.toml")]

    def mesh(name):
        return edited('box = {n = [4, 5], cell = "quad"}', f'file = "{name}"')

    pressure = 'pressure = "4*x*(1 - x)"'
    cases = {
        "deep": lambda: ([str(tmp_path / "deep.toml")], "nested too deeply"),
        "folder mesh": lambda: (mesh("folder.msh"), "[mesh] file 'folder.msh' is a folder"),
        "fifo mesh": lambda: (mesh("fifo.msh"), "[mesh] file 'fifo.msh' is a FIFO"),
        "symlink loop": lambda: (mesh("loop.msh"), "[mesh] file 'loop.msh' is a loop of"),
        "meshio prints": lambda: (mesh("junk.msh"), "Couldn't read file"),  # meshio's words
        "meshio raises": lambda: (mesh("cut.msh"), "could not be read by meshio"),
        "pressure 1e300": lambda: (edited(pressure, "pressure = 1e300"),
                                   "1e+300 is beyond the largest load"),
        "corner 2^63": lambda: (edited("", "", CORNER), "more than 1000 times the size"),
        "overflow": lambda: (edited(pressure, 'pressure = "1e300*x"'),   # was: the solve
                             "1e300*x reaches 1e+300 at (1, 1), which is beyond the largest"),
        "n wraps": lambda: (edited("n = [4, 5]", "n = [4294967297, 4294967295]",
                                   "[[displacement]]\nwhere = 'x < 1e-9'\nx = 0\n"),
                            "needs at least 8.86e+10 TB (1.84e+19 nodes, 1.84e+19 cells"),
        "max-memory 0.5": lambda: ([STRIP, "--max-memory", "0.5"], "at least one byte"),
    }
    return cases[case]()


@pytest.mark.parametrize("case", [
    "deep", "folder mesh", "fifo mesh", "symlink loop", "meshio prints", "meshio raises",
    "pressure 1e300", "corner 2^63", "overflow", "n wraps", "max-memory 0.5"])
def test_27_anticipated_errors_are_one_line_and_exit_2(tmp_path, capfd, case):
    """Each was exit 1, a traceback, a misleading message or several lines (numpy's
    warnings, meshio's messages) before the error."""
    argv, words = anticipated(tmp_path, case)
    try:
        code = main(["run", *argv, "--out", str(tmp_path / "out")])
    except SystemExit as e:                                      # a usage error
        code = e.code
    out, err = capfd.readouterr()
    assert code == 2 and out == "", (out, err)
    assert err.count("\n") == 1 and err.startswith("skxfem: error: "), err
    assert words in err, err
    assert not (tmp_path / "out").exists()


def run_command(argv, cwd, env=None, timeout=60):
    """``python -m skxfem ARGV`` with at most 2 GiB of memory (a read of /dev/zero)."""
    import resource

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (2**31, 2**31))
    return subprocess.run([sys.executable, "-m", "skxfem", *argv], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=timeout, check=False,
                          preexec_fn=limit)


def test_28_a_fifo_or_a_device_as_scene_file_is_refused_at_once(tmp_path):
    """A FIFO as the scene file blocked for ever; /dev/zero was read until memory ran
    out.  --debug keeps the exit code 2 and adds the traceback."""
    os.mkfifo(tmp_path / "scene.toml")
    for path, words in ((tmp_path / "scene.toml", "is a FIFO"),
                        ("/dev/zero", "is a character device")):
        done = run_command(["run", str(path)], tmp_path, timeout=30)
        assert done.returncode == 2 and done.stdout == "", done.stderr
        assert done.stderr.count("\n") == 1 and words in done.stderr, done.stderr
    debug = run_command(["--debug", "run", "/dev/zero"], tmp_path, timeout=30)
    assert debug.returncode == 2 and "Traceback" in debug.stderr
    assert debug.stderr.splitlines()[-1].startswith("skxfem: error: ")


def test_29_a_run_neither_imports_matplotlib_nor_prints_its_warnings(tmp_path):
    """With its config folder unwritable, matplotlib printed two lines on every run (the
    command imported it to solve a scene); `reproduce --bogus` printed argparse's usage."""
    env = {**os.environ, "MPLCONFIGDIR": "/dev/null/unwritable"}
    code = ("import sys; from skxfem.app.cli import main; "
            f"c = main(['run', {STRIP!r}, '--out', 'o']); "
            "print(c, sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib'))")
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=120, check=False)
    assert done.stderr == "" and done.stdout.splitlines()[-1] == "0 []", done
    bogus = run_command(["reproduce", "--bogus"], tmp_path, env=env)
    assert bogus.returncode == 2 and bogus.stdout == ""
    assert bogus.stderr.count("\n") == 1, bogus.stderr
    assert bogus.stderr.startswith("skxfem: error: ") and "--bogus" in bogus.stderr


def test_30_warnings_are_counted_not_printed(tmp_path, capfd, monkeypatch):
    """A warning raised during a run is not printed (stderr stays empty): the summary
    line counts it and --debug shows it."""
    import warnings

    def solve(scene, **options):
        warnings.warn("a warning of some library", UserWarning)
        return cli_solve(scene, **options)

    cli_solve = cli.solve
    monkeypatch.setattr(cli, "solve", solve)
    assert main(["run", STRIP, "--out", str(tmp_path / "o")]) == 0
    out, err = capfd.readouterr()
    assert err == "" and "1 warning(s) not shown (--debug shows them)" in out
    assert main(["--debug", "run", STRIP, "--out", str(tmp_path / "o")]) == 0
    assert "a warning of some library" in capfd.readouterr().err


# --- issue 26: an engineer gets what the file says --------------------------------------

SOLVER_TABLE = '\n[solver]\nlinear = "iterative"\nlinear_tol = 1e-9\n'


def run_and_load(path, out, *options):
    """result.json of `skxfem run path` and skxfem.solve(skxfem.load_scene(path))."""
    assert main(["run", str(path), "--out", str(out), *options]) == 0
    return json.loads((out / "result.json").read_text()), skxfem.load_scene(path)


@pytest.mark.parametrize("example", ["contact", "strip"])
def test_31_one_file_one_answer(tmp_path, capsys, example):
    """The same scene file with a [solver] table gives the same linear solve, the same
    iterations and the same answer through `skxfem run` and through
    skxfem.solve(skxfem.load_scene(f)); an explicit keyword overrides the file as the
    option does."""
    pytest.importorskip("pyamg")
    contact = example == "contact"
    path = tmp_path / f"{example}.toml"
    path.write_text((EXAMPLES / f"{example}.toml").read_text() + SOLVER_TABLE
                    + ("max_iter = 40\n" if contact else ""))
    data, scene = run_and_load(path, tmp_path / "o")
    capsys.readouterr()
    assert scene.solver == skxfem.Solver("iterative", 1e-9, 40 if contact else None)
    r = skxfem.solve(scene)
    assert r.linear == data["linear_solve"]["linear"] == "iterative"
    assert r.linear_info["tol"] == data["linear_solve"]["tol"] == 1e-9
    p = np.array(data["pressure"])
    assert np.abs(r.pressure - p).max() <= 1e-12 * np.abs(p).max()
    assert np.abs(r.traction.T - np.array(data["traction"])).max() <= 1e-12 * np.abs(p).max()
    if contact:   # Newton's iterations, step by step
        assert [st.newton.iterations for st in r.steps] == [
            st["newton"]["iterations"] for st in data["steps"]]
    else:         # the CG iterations and residuals
        assert r.linear_info["iterations"] == data["linear_solve"]["iterations"] > 0
        assert np.allclose(r.linear_info["residuals"], data["linear_solve"]["residuals"],
                           rtol=1e-8, atol=0)
    # an explicit keyword overrides the file, as the option does
    data, _ = run_and_load(path, tmp_path / "d", "--linear", "direct", "--linear-tol", "1e-6")
    capsys.readouterr()
    r = skxfem.solve(scene, linear="direct", linear_tol=1e-6)
    assert r.linear == data["linear_solve"]["linear"] == "direct"
    assert r.linear_info["tol"] == data["linear_solve"]["tol"] == 1e-6
    assert np.abs(r.pressure - np.array(data["pressure"])).max() <= 1e-12 * np.abs(p).max()


def test_32_max_iter_of_the_file_reaches_the_solve_and_a_keyword_overrides_it(tmp_path,
                                                                              capsys):
    """[solver] max_iter = 1 fails the example in both (exit 2; ContactConvergenceError);
    max_iter=40 (a numpy integer too) overrides it in Python as --max-iter does."""
    path = tmp_path / "c.toml"
    path.write_text(CONTACT_TEXT + "\n[solver]\nmax_iter = 1\n")
    scene = skxfem.load_scene(path)
    assert scene.solver.max_iter == 1
    assert main(["run", str(path), "--out", str(tmp_path / "o")]) == 2
    assert "did not converge in 1 iterations" in capsys.readouterr().err
    with pytest.warns(UserWarning), pytest.raises(ContactConvergenceError,
                                                  match="did not converge in 1 iterations"):
        skxfem.solve(scene)
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--max-iter", "40"]) == 0
    data = json.loads((tmp_path / "o" / "result.json").read_text())
    capsys.readouterr()
    for max_iter in (40, np.int64(40)):
        r = skxfem.solve(scene, max_iter=max_iter)
        assert [st.newton.iterations for st in r.steps] == [
            st["newton"]["iterations"] for st in data["steps"]]


@pytest.mark.parametrize("key, bad, message", [
    ("linear", "cholesky", "linear must be one of ('auto', 'direct', 'iterative'), got "
                           "'cholesky'"),
    ("linear_tol", 2.0, "linear_tol must be a number in (0, 1)"),
    ("linear_tol", "1e-9", "linear_tol must be a number in (0, 1)"),
    ("max_iter", 0, "max_iter must be a positive integer"),
    ("max_iter", 2.5, "max_iter must be a positive integer"),
    ("max_iter", True, "max_iter must be a positive integer"),
])
def test_33_skxfem_solve_checks_its_options_as_the_command_line(key, bad, message):
    """Each option of skxfem.solve is checked before anything is solved, in the one line
    the command line gives for it; max_iter on a tie is refused as --max-iter is."""
    scene = skxfem.load_scene(CONTACT)
    with pytest.raises(ValueError) as info:
        skxfem.solve(scene, **{key: bad})
    assert str(info.value).startswith(message) and "\n" not in str(info.value)
    with pytest.raises(ValueError, match="max_iter applies to the contact laws"):
        skxfem.solve(skxfem.load_scene(STRIP), max_iter=5)
    with pytest.raises(ValueError, match="max_iter applies to the contact laws"):
        skxfem.solve(skxfem.Scene(skxfem.Box(3, "quad"), skxfem.plane((0, 0.5), (0, 1)),
                                  solver=skxfem.Solver(max_iter=5)))


def test_34_the_cli_error_for_a_bad_linear_tol_is_that_of_python(tmp_path, capsys, no_solve):
    assert main(["run", STRIP, "--out", str(tmp_path / "o"), "--linear-tol", "2"]) == 2
    err = one_line(capsys)
    with pytest.raises(ValueError) as info:
        skxfem.solve(skxfem.load_scene(STRIP), linear_tol=2.0)
    assert err.strip() == f"skxfem: error: {info.value}"


@pytest.mark.parametrize("law", ["bonded", "bilateral", "frictionless", "adhesive"])
def test_35_coulomb_needs_friction_and_no_other_law_takes_it(tmp_path, capsys, law,
                                                            no_solve):
    """`law = "coulomb"` without friction ran as μ = 0; friction with another law was
    ignored.  Both are one line naming friction, exit 2, before any solve."""
    path = tmp_path / "s.toml"
    path.write_text(CONTACT_TEXT.replace("friction = 0.5\n", ""))
    assert main(["run", str(path), "--out", str(tmp_path / "o")]) == 2
    err = one_line(capsys)
    assert "[interface] law 'coulomb' needs friction" in err and "s.toml" in err
    path.write_text(CONTACT_TEXT.replace('law = "coulomb"', f'law = "{law}"'))
    assert main(["run", str(path), "--out", str(tmp_path / "o")]) == 2
    err = one_line(capsys)
    assert "[interface] friction" in err and f"law '{law}' has no friction" in err
    assert "remove friction" in err and not (tmp_path / "o").exists()


TURNED = """name = "turned"
[mesh]
box = {n = [8, 9], cell = "quad"}
[levelset]
plane = {point = [0.0, 0.5], normal = [0.0, 1.0]}
[[displacement]]
boundary = "ymin"
kind = "clamped"
[[displacement]]
boundary = "ymax"
x = 0.0
y = "-0.002 - 0.05*(x - 0.5)"
[interface]
law = "frictionless"
steps = [1.0, -0.5]
"""
"""A strip whose top is pressed and turned, then turned back the other way half as far:
the contact zone crosses Γ, and Newton needs 6 iterations for the second step."""


def test_36_every_cut_is_said_as_it_happens(tmp_path, capsys, monkeypatch):
    """With 4 Newton iterations allowed, the second step of TURNED is cut three times,
    then converges; each cut is one note, in order, printed before the next increment
    is solved; the result is the uncut one.  (Without the secant predictor of an
    increment from the last: with it, one cut is enough here.)"""
    from skxfem.contact import history

    monkeypatch.setattr(history, "_guess", lambda *args: None)

    path = tmp_path / "turned.toml"
    path.write_text(TURNED)
    ref = skxfem.solve(skxfem.load_scene(path))
    assert [st.newton.iterations for st in ref.steps] == [3, 6]
    seen = []                               # stderr when each Newton iteration starts
    newton = history.newton

    def watched(*args, **kwargs):
        seen.append(capsys.readouterr().err)
        return newton(*args, **kwargs)

    monkeypatch.setattr(history, "newton", watched)
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--max-iter", "4"]) == 0
    seen.append(capsys.readouterr().err)
    where = "load step 2 of 2 (load factor -0.5)"
    failed = "Newton did not converge in 4 iterations; cut: next increment"
    notes = [f"skxfem: note: {where}: {failed} 0 to 1/2 (1/2 of the step)",
             f"skxfem: note: {where}, increment 1/2 to 1: {failed} 1/2 to 3/4 (1/4 of the step)",
             f"skxfem: note: {where}, increment 1/2 to 3/4: {failed} 1/2 to 5/8 (1/8 of the "
             f"step)"]
    assert "".join(seen).splitlines() == notes
    printed = [k for k, err in enumerate(seen) if err]   # each before the next solve
    assert len(printed) == 3 and printed[-1] < len(seen) - 1
    data = json.loads((tmp_path / "o" / "result.json").read_text())
    assert data["steps"][-1]["increments"] == 4   # 0-1/2, 1/2-5/8, 5/8-7/8, 7/8-1
    assert np.abs(np.array(data["pressure"]) - ref.pressure).max() < 1e-10


def test_37_notes_name_the_interface_of_a_scene_with_several(tmp_path, capsys):
    """TURNED with a bonded interface below its contact one: each cut names the
    interface whose points kept changing status, interfaces[1]; the snap note of
    examples/column.toml with its upper plane moved 1e-13 off the node it passes through
    (within skxfem.cut.SNAP: the node is put on it) names its interface; through the node,
    as the example is, no note."""
    head, _, _ = TURNED.partition("[levelset]")
    supports = TURNED[TURNED.index("[[displacement]]"):TURNED.index("[interface]")]
    path = tmp_path / "two.toml"
    path.write_text("steps = [1.0, -0.5]\n" + head + supports + "[[interface]]\n"
                    "expr = 'y - 0.25'\nlaw = 'bonded'\n[[interface]]\n"
                    "plane = {point = [0.0, 0.5], normal = [0.0, 1.0]}\nlaw = 'frictionless'\n")
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--max-iter", "4"]) == 0
    notes = capsys.readouterr().err.splitlines()
    assert len(notes) >= 1 and all(
        note.startswith("skxfem: note: load step 2 of 2 (load factor -0.5)") and
        " on interfaces[1] 'plane(point=[0.0, 0.5], normal=[0.0, 1.0])' (frictionless)" in note
        and "cut: next increment" in note for note in notes), notes
    assert main(["run", str(EXAMPLES / "column.toml"), "--out", str(tmp_path / "c")]) == 0
    assert capsys.readouterr().err == ""
    column = (EXAMPLES / "column.toml").read_text()
    assert "point = [0.0, 2.1]" in column
    near = tmp_path / "near.toml"
    near.write_text(column.replace("point = [0.0, 2.1]", "point = [0.0, 2.1000000000001]"))
    assert main(["run", str(near), "--out", str(tmp_path / "n")]) == 0
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("skxfem: note: interfaces[1] 'plane(point=[0.0, "
                                               "2.1") and "passes within 1e-09 edge" in err[0]


# --- issue 26, item 5: the last holes of bad input ------------------------------------

def contact_file(tmp_path, edits, name="contact.toml"):
    text = CONTACT_TEXT
    for old, new in edits.items():
        assert old in text, old
        text = text.replace(old, new)
    return scene_file(tmp_path, text, name)


@pytest.mark.parametrize("mu, words", [
    ("5e-324", "must be 0 or in [1e-10, 1e+10], got 5e-324: below, the friction force is "
               "round-off (give 0: no friction)"),
    ("1e-11", "got 1e-11: below"),
    ("1e308", "got 1e+308: above, a pressed point sticks to round-off"),
])
def test_38_a_friction_outside_its_range_is_refused_before_solving(tmp_path, capsys, no_solve,
                                                                   mu, words):
    """friction = 5e-324 wrote null (a NaN) into steps[0].Lambda with exit 0; 1e308 was
    blamed on the loads or E."""
    path = contact_file(tmp_path, {"friction = 0.5": f"friction = {mu}"})
    assert main(["run", path, "--out", str(tmp_path / "out")]) == 2
    err = one_line(capsys)
    assert "[interface] friction (Coulomb's mu)" in err and words in err, err


@pytest.mark.parametrize("mu", ["1e-10", "0.0"])
def test_39_a_tiny_friction_slides_with_lambda_one_and_no_null(tmp_path, capsys, mu):
    """At the end of the range every point slides: |Λ| = 1 where pressed, 0 elsewhere
    (μ = 0: frictionless, Λ = 0), and result.json holds no null."""
    path = contact_file(tmp_path, {"friction = 0.5": f"friction = {mu}"})
    assert main(["run", path, "--out", str(tmp_path / "out")]) == 0
    text = (tmp_path / "out" / "result.json").read_text()
    assert "null" not in text and "NaN" not in text
    for step in json.loads(text)["steps"]:
        lam = np.abs(np.array(step["Lambda"])[:, 0])
        pressed = np.array(step["pressure"]) > 0
        assert set(step["status"]) == {"slip"}
        expected = np.where(pressed, 1.0, 0.0) if float(mu) else np.zeros_like(lam)
        np.testing.assert_allclose(lam, expected, atol=1e-12)


def test_40_many_load_steps_are_bounded_and_the_summary_stays_one_short_line(
        tmp_path, capsys):
    """10 000 steps took 152 s and printed a 30 KB summary line: at most MAX_STEPS, and
    the Newton iterations of the first three and the last step, and their maximum."""
    from skxfem.scene import MAX_STEPS

    many = [round((k + 1) / 1001, 6) for k in range(1001)]
    path = contact_file(tmp_path, {"steps = [0.5, 1.0]": f"steps = {many}"})
    assert main(["run", path, "--out", str(tmp_path / "out")]) == 2
    err = one_line(capsys)
    assert f"[interface] steps has 1001 load steps, more than {MAX_STEPS}" in err, err
    forty = [(k + 1) / 40 for k in range(40)]
    path = contact_file(tmp_path, {"steps = [0.5, 1.0]": f"steps = {forty}"})
    assert main(["run", path, "--out", str(tmp_path / "out")]) == 0
    line = capsys.readouterr().out
    assert line.count("\n") == 1 and len(line) < 400, line
    data = json.loads((tmp_path / "out" / "result.json").read_text())
    its = [s["newton"]["iterations"] for s in data["steps"]]
    assert len(its) == 40
    assert (f"40 load step(s), {sum(its)} Newton iterations ({its[0]}, {its[1]}, {its[2]}, "
            f"..., {its[-1]}; at most {max(its)})") in line, line


def strip_with(tmp_path, levelset, name="strip.toml"):
    assert 'expr = "y - 0.5"' in STRIP_TEXT
    text = STRIP_TEXT.replace('expr = "y - 0.5"', f'expr = "{levelset}"')
    return scene_file(tmp_path, text, name)


@pytest.mark.parametrize("scale", ["1e-300", "1e300", "1e308"])
def test_41_the_scale_of_the_level_set_does_not_matter(tmp_path, capsys, scale):
    """1e-300*(y - 0.5) was refused by "edges must be strictly cut, psi(v1) psi(v2) < 0"
    printing values that satisfy it; 1e300*(y - 0.5) was blamed on the loads or E.
    Both are y = 0.5, and give its answer (ψ is scaled by a power of 2, exactly)."""
    base = run_and_load(strip_with(tmp_path / "a", "y - 0.5"), tmp_path / "base")[0]
    scaled = run_and_load(strip_with(tmp_path / "b", f"{scale}*(y - 0.5)"), tmp_path / "out")[0]
    np.testing.assert_allclose(scaled["pressure"], base["pressure"], rtol=1e-12)
    np.testing.assert_allclose(scaled["points"], base["points"], rtol=1e-12)


def test_42_a_level_set_below_the_doubles_is_refused_naming_it(tmp_path, capsys):
    path = strip_with(tmp_path, "1e-320*(y - 0.5)")
    assert main(["run", path, "--out", str(tmp_path / "out")]) == 2
    err = one_line(capsys)
    assert "the level set is at most 5e-321 in magnitude at the nodes, below 2.3e-302" in err
    assert "scale psi" in err and "strictly cut" not in err


@pytest.mark.parametrize("levelset, vertex, sign", [
    ("y - 1", "(0, 1)", "psi < 0"), ("y", "(0, 0)", "psi > 0"), ("1 - y", "(0, 1)", "psi > 0"),
    ("x - 1", "(1, 0)", "psi < 0"), ("(x - 0.5)**2 + (y - 1.25)**2 - 0.0625", "(0.5, 1)",
                                     "psi > 0")])
def test_43_an_interface_on_a_boundary_face_is_refused_on_every_face(
        tmp_path, capsys, levelset, vertex, sign):
    """Γ on y = 1 was accepted as a 2e-10 sliver of Ω⁺, on y = 0 refused as cutting no
    cell: which one depended on the sign of ψ.  Both are one message now."""
    path = strip_with(tmp_path, levelset)
    assert main(["run", path, "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.splitlines()[-1]
    assert err.startswith("skxfem: error: the level set does not cross the body: it vanishes "
                          "at ") and f"e.g. {vertex}, and has one sign ({sign})" in err, err
    assert "Γ lies on the boundary" in err


@pytest.mark.parametrize("rho, ok", [("5e-9", True), ("4.9999e-9", False), ("5e12", True),
                                     ("5.0001e12", False)])
def test_44_the_ends_of_the_rho_range_are_accepted(tmp_path, capsys, rho, ok):
    """rho_n at 1e12 x its default E/h (E = 1, h = 0.2 here: 5) was refused as outside
    1e-09..1e+12 (E/h rounded up by its last bit): an inclusive bound accepts its ends."""
    path = contact_file(tmp_path, {"friction = 0.5": f"friction = 0.5\nrho_n = {rho}"})
    assert main(["run", path, "--out", str(tmp_path / "out")]) == (0 if ok else 2)
    if not ok:
        err = one_line(capsys)
        assert "is 9.9998e-10 x its default E/h = 5" in err or "is 1.00002e+12 x" in err, err


def test_45_a_cjk_name_gives_a_default_folder_the_file_system_takes(tmp_path, capfd,
                                                                     monkeypatch):
    """A 100-character CJK name gave a 300-byte folder, refused after the solve with
    "[Errno 36] File name too long": the default folder is at most 100 bytes."""
    scene = scene_file(tmp_path / "scenes", STRIP_TEXT.replace(
        'name = "strip"', 'name = "' + "結" * 100 + '"'))
    here = tmp_path / "here"
    here.mkdir()
    monkeypatch.chdir(here)
    assert main(["run", scene]) == 0
    [written] = here.iterdir()
    assert written.name == "結" * 33 and (written / "result.json").is_file()


@pytest.mark.parametrize("name, words", [
    ("a" * 227, "output folder name 'aaaaaaaaaaaa...' is 227 bytes long (UTF-8), more than "
                "the 226 the file system takes (its limit 255 less 29 for the hidden folder"),
    ("結" * 76, "is 228 bytes long (UTF-8)"),
])
def test_46_a_too_long_out_is_refused_before_solving(tmp_path, capsys, no_solve, name, words):
    """An --out of 230 characters passed the check and failed after the solve: the names
    are checked in bytes, keeping room for the hidden folder the results go to first."""
    assert main(["run", STRIP, "--out", str(tmp_path / name)]) == 2
    err = one_line(capsys)
    assert words in err and "give a shorter --out" in err, err
    assert main(["run", STRIP, "--out", str(tmp_path / ("a" * 300) / "x")]) == 2
    assert "output folder path holds the name 'aaaaaaaaaaaa...' is 300 bytes" in one_line(capsys)


def test_47_the_longest_out_the_file_system_takes_is_written(tmp_path, capsys):
    assert main(["run", STRIP, "--out", str(tmp_path / ("a" * 226))]) == 0
    assert (tmp_path / ("a" * 226) / "result.json").is_file()


def test_48_the_summary_says_what_closed_points_do_in_the_words_of_their_law(tmp_path,
                                                                             capsys):
    """The summary called the closed points of a bonded interface "stick" and those of a
    frictionless one "slip": each law its own words."""
    path = contact_file(tmp_path, {'law = "coulomb"\nfriction = 0.5': 'law = "frictionless"',
                                   "x = 2.0": "x = 0.0"})
    assert main(["run", path, "--out", str(tmp_path / "a")]) == 0
    assert "last step: 5 in contact (5 free to slide), 0 open" in capsys.readouterr().out
    assert main(["run", str(EXAMPLES / "column.toml"), "--out", str(tmp_path / "b")]) == 0
    out = capsys.readouterr().out
    data = json.loads((tmp_path / "b" / "result.json").read_text())
    ks = np.array(data["dofs"]["interface"])
    status = np.array(data["steps"][-1]["status"])
    held, free = ((status[ks == k] != "open").sum() for k in (0, 1))
    assert [i["law"] for i in data["interfaces"]] == ["bonded", "frictionless"]
    assert f"in contact (bonded: {held} held; frictionless: {free} free to slide)" in out, out
    assert "stick" not in out and "slip" not in out


# --- issue 26, item 4: what an engineer expects in the files ----------------------------

@pytest.mark.parametrize("example", ["plate", "strip", "inclusion", "contact", "column"])
def test_49_the_reactions_balance_the_loads(tmp_path, capsys, example):
    """result.json's reactions: each support's resultant and their total, which balances
    the applied loads to 1e-10; displacement.vtu's point data reaction sums to it."""
    data = run(tmp_path, example)
    rx = data["reactions"]
    applied, total = np.array(rx["applied"]), np.array(rx["total"])
    scale = max(np.abs(applied).max(), 1.0)
    np.testing.assert_allclose(total + applied, 0, atol=1e-10 * scale)
    supports = np.array([s["force"] for s in rx["supports"]])
    np.testing.assert_allclose(supports.sum(axis=0), total, atol=1e-12 * scale)
    scene = load_scene(EXAMPLES / f"{example}.toml")
    assert len(rx["supports"]) == len(scene.displacements)
    m = meshio.read(tmp_path / example / "displacement.vtu")
    dim = len(applied)
    np.testing.assert_allclose(m.point_data["reaction"].sum(axis=0)[:dim], total,
                               atol=1e-12 * scale)


def test_50_a_bi_material_bar_has_the_exact_jump_in_strain(tmp_path, capsys):
    """A bar pulled by t = 1, E = 1 left of Γ (x = 0.7) and 4 right of it ([material.plus]),
    ν = 0: σ_xx = 1 throughout, ε_xx = 1 on Ω⁻ and 1/4 on Ω⁺ (cell data strain and stress
    of displacement.vtu, each region's piece its own), and the end moves by 0.7 + 1.3/4."""
    text = '''
name = "bar"
[mesh]
box = {n = [4, 2], cell = "quad", size = [2.0, 1.0]}
[levelset]
expr = "x - 0.7"
[material]
nu = 0.0
[material.minus]
E = 1.0
[material.plus]
E = 4.0
[[displacement]]
boundary = "xmin"
kind = "rollers"
[[displacement]]
boundary = "ymin"
kind = "rollers"
[[load]]
boundary = "xmax"
traction = [1.0, 0.0]
'''
    path = scene_file(tmp_path, text, "bar.toml")
    s = load_scene(path)
    assert (s.material.E, s.material_plus.E, s.material_plus.nu) == (1.0, 4.0, 0.0)
    assert main(["run", path, "--out", str(tmp_path / "out")]) == 0
    m = meshio.read(tmp_path / "out" / "displacement.vtu")
    region = m.cell_data["region"][0]                               # 0: Ω⁻, 1: Ω⁺
    strain, stress = m.cell_data["strain"][0], m.cell_data["stress"][0]
    np.testing.assert_allclose(strain[:, 0], np.where(region == 0, 1.0, 0.25), rtol=1e-12)
    np.testing.assert_allclose(stress[:, 0], 1.0, rtol=1e-12)
    np.testing.assert_allclose(np.delete(stress, 0, axis=1), 0, atol=1e-12)
    np.testing.assert_allclose(m.cell_data["von_mises"][0], 1.0, rtol=1e-12)
    end = (m.points[:, 0] > 2 - 1e-9)
    np.testing.assert_allclose(m.point_data["displacement"][end, 0], 0.7 + 1.3 / 4,
                               rtol=1e-12)
    data = json.loads((tmp_path / "out" / "result.json").read_text())
    np.testing.assert_allclose(data["pressure"], -1.0, rtol=1e-12)       # a tension of 1


def test_51_every_load_step_is_a_file_of_a_paraview_series(tmp_path, capsys):
    """The VTU files held the last step only: a contact result adds displacement.pvd and
    interface.pvd, collections of one file per load step, each that step's fields (its
    pressures those of result.json's step); a later run with fewer steps replaces it."""
    import xml.etree.ElementTree as ET

    path = str(EXAMPLES / "history.toml")
    out = tmp_path / "out"
    assert main(["run", path, "--out", str(out)]) == 0
    data = json.loads((out / "result.json").read_text())
    for kind in ("displacement", "interface"):
        sets = ET.parse(out / f"{kind}.pvd").getroot().find("Collection").findall("DataSet")
        assert [d.get("file") for d in sets] == [f"{kind}_{k:04d}.vtu" for k in (1, 2, 3)]
        assert [d.get("timestep") for d in sets] == ["1", "2", "3"]
    last = meshio.read(out / "interface.vtu").point_data["pressure"]
    for k, step in enumerate(data["steps"]):
        m = meshio.read(out / f"interface_{k + 1:04d}.vtu")
        p = m.point_data["pressure"]
        assert p.size == len(data["points"])
        assert np.abs(p).max() == pytest.approx(max(np.abs(step["pressure"])), rel=1e-9)
        d = meshio.read(out / f"displacement_{k + 1:04d}.vtu")
        assert {"displacement", "reaction"} <= set(d.point_data)
        assert {"strain", "stress", "von_mises"} <= set(d.cell_data)
    np.testing.assert_array_equal(meshio.read(out / "interface_0003.vtu").point_data["pressure"],
                                  last)
    assert main(["run", str(EXAMPLES / "contact.toml"), "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == [
        "displacement.pvd", "displacement.vtu", "displacement_0001.vtu",
        "displacement_0002.vtu", "interface.pvd", "interface.vtu", "interface_0001.vtu",
        "interface_0002.vtu", "result.json"]


def test_52_progress_is_one_line_per_newton_iteration_and_load_step(tmp_path, capsys):
    """Issue 27 item 3: --progress prints, on stderr, one line per Newton iteration
    (residuals, open/stick/slip counts, time) and one per load step; without it, and
    not on a terminal, nothing."""
    assert main(["run", CONTACT, "--out", str(tmp_path / "a"), "--progress"]) == 0
    err = capsys.readouterr().err.splitlines()
    data = json.loads((tmp_path / "a" / "result.json").read_text())
    its = [st["newton"]["iterations"] for st in data["steps"]]
    newton = [line for line in err if ": Newton " in line]
    done = [line for line in err if ": done in " in line]
    assert len(newton) == sum(its) and len(done) == len(its) == 2
    assert all(line.startswith("skxfem: load step ") and "residuals" in line
               and " open, " in line and " slip; " in line for line in newton)
    assert done[0].startswith("skxfem: load step 1 of 2") and f"in {its[0]} Newton" in done[0]
    assert main(["run", CONTACT, "--out", str(tmp_path / "b")]) == 0
    assert not [line for line in capsys.readouterr().err.splitlines() if "Newton" in line]


def test_front_points_left_without_K_are_a_note(tmp_path, capsys):
    """A penny under two cells across its radius: no K along its front (its interaction
    domain has no cell of room); skxfem run says why on stderr, and result.json's front
    lists no point."""
    path = scene_file(tmp_path, """
[mesh]
box = {n = [6, 6, 3], cell = "tet"}
[material]
E = 1.0
nu = 0.3
[levelset]
expr = "z - 0.5"
front = "sqrt((x - 0.5)**2 + (y - 0.5)**2) - 0.3"
[interface]
law = "free"
[[displacement]]
boundary = "zmin"
x = 0.0
y = 0.0
z = 0.0
[[load]]
boundary = "zmax"
traction = [0.0, 0.0, 1.0]
""")
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    err = capsys.readouterr().err
    assert "skxfem: note: " in err and "no K at 10 of 10 front points" in err
    (front,) = json.loads((tmp_path / "out" / "result.json").read_text())["front"]
    assert front["points"] == [] and front["K_I"] == []
