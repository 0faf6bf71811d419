"""The graders of exercises/ proved right (issue 10), and skxfem.app.grade.

The exercises are not in the main suite's testpaths (their stubs raise); these
tests drive them: every reference passes, every untouched stub fails test by
test with its NotImplementedError, every wrong solution is rejected with the
message its file announces (``EXPECT``), a student file that reuses the
library's answer fails, and a student's path from an exercise README to a
score table works on a copy of the exercise.
"""
import ast
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from skxfem.app.grade import Result, Score, _exercise_of, find_exercises, hints, main, table

ROOT = Path(__file__).resolve().parents[1]
EXERCISES = ROOT / "exercises"
NAMES = [p.name for p in find_exercises(EXERCISES)]
WRONG = sorted((p.parent.name, p.stem.removeprefix("wrong_"))
               for p in (EXERCISES / "solutions").glob("*/wrong_*.py"))


class Recorder:
    """A pytest plugin keeping the final outcome and text of every test."""

    def __init__(self):
        self.tests, self.collect_errors = {}, []

    def pytest_runtest_logreport(self, report):
        if report.when == "call" or report.outcome != "passed":
            outcome = report.outcome if report.when == "call" else f"{report.outcome} in " \
                f"{report.when}"
            self.tests[report.nodeid] = (outcome, report.longreprtext)
        elif report.nodeid not in self.tests:
            self.tests[report.nodeid] = ("passed", "")

    def pytest_collectreport(self, report):
        if report.failed:
            self.collect_errors.append(report.longreprtext)


def run(*args) -> Recorder:
    """Run pytest in this process (fast: the library is already imported)."""
    recorder = Recorder()
    pytest.main([*map(str, args), "-p", "no:cacheprovider", "-q"], plugins=[recorder])
    assert not recorder.collect_errors, recorder.collect_errors[0]
    return recorder


def of(recorder, name):
    return {k: v for k, v in recorder.tests.items() if f"/{name}/" in f"/{k}"}


def test_the_course_has_its_exercises():
    assert NAMES == ["01_levelset", "02_cut", "03_enrich", "04_multipliers", "05_lbb",
                     "06_stabilised", "07_contact", "08_crack"]
    for name in NAMES:
        folder = EXERCISES / name
        assert (folder / "README.md").exists() and (folder / "exercise.py").exists()
        assert (EXERCISES / "solutions" / name / "reference.py").exists()
        assert sum(1 for n, _ in WRONG if n == name) >= 2, f"{name}: two wrong solutions at least"


def test_every_exercise_passes_with_its_reference():
    r = run(EXERCISES, "--impl=solution")
    for name in NAMES:
        tests = of(r, name)
        assert len(tests) >= 5, f"{name} has {len(tests)} tests"
        failed = {k: v[1] for k, v in tests.items() if v[0] != "passed"}
        assert not failed, failed


def test_every_stub_fails_test_by_test_with_not_implemented():
    """...in one line each: where the stub raised and its message, not its docstring."""
    r = run(EXERCISES, "--impl=student")
    assert len(r.tests) == sum(len(of(r, n)) for n in NAMES) > 40
    for node, (outcome, text) in r.tests.items():
        assert outcome == "failed", f"{node}: {outcome} (a failure of the test, not a crash)"
        assert "NotImplementedError" in text and "not written yet" in text, node
        assert len(text.splitlines()) == 1 and "exercise.py:" in text, text


def test_every_stub_keeps_its_docstrings():
    for name in NAMES:
        tree = ast.parse((EXERCISES / name / "exercise.py").read_text(encoding="utf-8"))
        for f in (n for n in tree.body if isinstance(n, ast.FunctionDef)):
            doc = ast.get_docstring(f) or ""
            assert ">>>" in doc and len(doc) > 100, f"{name}: {f.name} needs its full docstring"
            assert isinstance(f.body[-1], ast.Raise), f"{name}: {f.name} must raise"


@pytest.mark.parametrize("name, wrong", WRONG, ids=[f"{n}:{w}" for n, w in WRONG])
def test_each_wrong_solution_is_rejected_with_its_message(name, wrong):
    path = EXERCISES / "solutions" / name / f"wrong_{wrong}.py"
    expect = ast.literal_eval(next(
        n.value for n in ast.parse(path.read_text(encoding="utf-8")).body
        if isinstance(n, ast.Assign) and n.targets[0].id == "EXPECT"))
    r = run(EXERCISES / name, f"--impl=wrong:{wrong}")
    failed = {k: text for k, (outcome, text) in r.tests.items() if outcome != "passed"}
    assert failed, f"no test of {name} rejects wrong_{wrong}.py"
    assert all(r.tests[k][0] == "failed" for k in failed), "failures, not errors"
    assert any(expect in text for text in failed.values()), (
        f"no failure of {name} says {expect!r}:\n" + "\n".join(failed.values()))


def copy_exercise(tmp_path, name, student_source=None) -> Path:
    """A student's copy: exercises/conftest.py and one exercise, no solutions."""
    target = tmp_path / "exercises"
    target.mkdir(exist_ok=True)
    shutil.copy(EXERCISES / "conftest.py", target / "conftest.py")
    shutil.copytree(EXERCISES / name, target / name,
                    ignore=shutil.ignore_patterns("__pycache__"))
    if student_source is not None:
        (target / name / "exercise.py").write_text(student_source, encoding="utf-8")
    return target / name


@pytest.mark.parametrize("name, source", [
    ("01_levelset", "from skxfem.levelset import circle, plane, sphere\n"),
    ("01_levelset", "import skxfem.levelset as L\n\n\ndef plane(point, normal):\n"
                    "    return L.plane(point, normal)\n\n\n"
                    "circle = L.circle\nsphere = L.sphere\n"),
    ("07_contact", "import numpy as np\nfrom skxfem.contact import laws as contact_laws\n\n\n"
                   "def augmented_multiplier(lam, d_n, rho_n):\n    return lam - rho_n * d_n\n\n\n"
                   "normal_update = contact_laws.normal_update\n"
                   "ball_projection = contact_laws.ball_projection\n"),
    ("06_stabilised", "from skxfem.stabilised import minimum_edge_cover\n"
                      "\n\ndef star_groups(edges, vital):\n    raise NotImplementedError\n"),
])
def test_reusing_the_library_fails_the_grade(tmp_path, name, source):
    folder = copy_exercise(tmp_path, name, source)
    r = run(folder, "--rootdir", tmp_path, "--import-mode=importlib")
    assert r.tests and all(outcome == "failed" for outcome, _ in r.tests.values())
    if name in ("01_levelset", "07_contact"):
        assert all("uses the library's own implementation" in text and "skxfem." in text
                   for _, text in r.tests.values())
    else:
        assert all("uses the library's own implementation" in text
                   for _, text in r.tests.values() if "star_groups" not in text)


def test_a_student_goes_from_the_readme_to_a_score_table(tmp_path):
    """The README's commands, run on a copy of exercise 03: stub, then filled in."""
    readme = (EXERCISES / "03_enrich" / "README.md").read_text(encoding="utf-8")
    commands = [".venv/bin/pytest exercises/03_enrich",
                ".venv/bin/skxfem grade exercises/03_enrich"]
    assert all(c in readme for c in commands), "the README shows the commands run here"
    folder = copy_exercise(tmp_path, "03_enrich")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))

    def shell(command):   # .venv/bin/X: this interpreter's X (the clone's is tested apart)
        args = command.removeprefix(".venv/bin/").split()
        return subprocess.run([sys.executable, "-m", *args], cwd=tmp_path, env=env,
                              capture_output=True, text=True)

    stub = shell(commands[0])
    assert stub.returncode == 1 and "NotImplementedError" in stub.stdout, stub.stdout[-2000:]
    failures = stub.stdout.split(" FAILURES ")[1].split(" short test summary ")[0]
    lines = [line for line in failures.splitlines()[1:-1]]     # between the === rulers
    assert len(lines) == 2 * 6, failures                       # a header, one line, per test
    assert all("exercise.py:" in line for line in lines[1::2]), failures
    graded = shell(commands[1])
    assert graded.returncode == 1, graded.stdout[-2000:] + graded.stderr[-2000:]
    assert "03_enrich            0/6      0/6" in graded.stdout, graded.stdout[-2000:]

    shutil.copy(EXERCISES / "solutions" / "03_enrich" / "reference.py", folder / "exercise.py")
    graded = shell(commands[1])
    assert graded.returncode == 0, graded.stdout[-3000:] + graded.stderr[-2000:]
    assert "03_enrich            6/6      6/6" in graded.stdout, graded.stdout[-2000:]
    assert "report: out/grades/03_enrich.json" in graded.stdout, graded.stdout[-500:]
    report = json.loads((tmp_path / "out" / "grades" / "03_enrich.json").read_text("utf-8"))
    assert report["passed"] == report["total"] == 6
    assert [t["outcome"] for t in report["exercises"]["03_enrich"]["tests"]] == ["passed"] * 6


def test_grade_points_and_exit_status(tmp_path, capsys):
    folder = copy_exercise(tmp_path, "06_stabilised")
    shutil.copy(EXERCISES / "solutions" / "06_stabilised" / "reference.py",
                folder / "exercise.py")          # it imports the library: refused
    status = main([str(folder), "--report", str(tmp_path / "r.json")])
    out = capsys.readouterr().out
    assert status == 1 and "uses the library's own implementation" in out
    report = json.loads((tmp_path / "r.json").read_text(encoding="utf-8"))
    ex = report["exercises"]["06_stabilised"]
    assert ex["max_points"] == 8.0 and ex["points"] == 0.0       # Figure 6 is worth 2
    assert main([str(tmp_path / "nowhere")]) == 2


def test_wrong_solutions_and_impl_choices():
    """(Once doctests: a hand-out has no solutions/ to show them on.)"""
    from skxfem.app.grade import check_impl, wrong_solutions
    assert wrong_solutions([EXERCISES / "01_levelset"])["unnormalised"] == ["01_levelset"]
    assert [e.name for e in check_impl("wrong:unnormalised", [EXERCISES / n for n in NAMES])] \
        == ["01_levelset"]


def test_table_and_junit_names():
    assert _exercise_of("exercises.05_lbb.test_lbb_exercise", NAMES) == "05_lbb"
    assert _exercise_of("tests.test_cut", NAMES) is None
    text = table([Score("x", (Result("t", "passed", 2.0),))])
    assert text.splitlines()[-1].split() == ["total", "1/1", "2/2"]


def test_grade_usage_errors_name_the_choices(tmp_path, capsys, monkeypatch):
    """A bad --impl is one line naming the valid choices, exit 2, and runs nothing; the
    same for pytest itself (a usage error, not an error per test)."""
    monkeypatch.chdir(tmp_path)
    for impl in ("bogus", "wrong:nosuch", "wrong:", "Student"):
        for argv, names in (([str(EXERCISES), f"--impl={impl}"], [w for _, w in WRONG]),
                            ([str(EXERCISES / "01_levelset"), "--impl", impl],
                             [w for n, w in WRONG if n == "01_levelset"])):
            assert main(argv) == 2, argv
            out, err = capsys.readouterr()
            assert out == "" and len(err.splitlines()) == 1, (out, err)
            assert err.startswith("skxfem grade: error: --impl must be student, solution or "
                                  "wrong:NAME") and repr(impl) in err, err
            assert all(name in err for name in names), err
            assert ("touching" in err) == (argv[0] == str(EXERCISES)), err   # 02_cut's
        assert pytest.main([str(EXERCISES / "01_levelset"), f"--impl={impl}", "-p",
                            "no:cacheprovider", "-q"]) == pytest.ExitCode.USAGE_ERROR
        capsys.readouterr()
    assert not (tmp_path / "out").exists(), "a usage error writes no report"
    # the command line's subcommand is the same; so is an unknown option (argparse)
    from skxfem.app.cli import main as cli
    assert cli(["grade", str(EXERCISES), "--impl=bogus"]) == 2
    assert len(capsys.readouterr().err.splitlines()) == 1
    with pytest.raises(SystemExit) as done:
        main([str(EXERCISES), "--bogus"])
    err = capsys.readouterr().err
    assert done.value.code == 2 and len(err.splitlines()) == 1 and "--bogus" in err
    # solution: refused where the solutions are not (a student's copy)
    folder = copy_exercise(tmp_path, "02_cut")
    assert main([str(folder), "--impl=solution"]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "--impl=student" in err and "02_cut" in err


def test_wrong_name_grades_the_exercises_that_have_it(tmp_path, capsys):
    report = tmp_path / "r.json"
    assert main([str(EXERCISES), "--impl=wrong:unnormalised", "--report", str(report)]) == 1
    data = json.loads(report.read_text(encoding="utf-8"))
    assert list(data["exercises"]) == ["01_levelset"] and data["total"] == 7
    assert "02_cut" not in capsys.readouterr().out


def test_hints_are_printed_whole_below_the_table(tmp_path, capsys):
    """The failure message (the hint) of each exercise is printed in full, wrapped
    between words; the rows of the table stay short."""
    status = main([str(EXERCISES / "01_levelset"), "--impl=wrong:unnormalised",
                   "--report", str(tmp_path / "r.json")])
    out = capsys.readouterr().out
    assert status == 1
    table_text = out.split("exercise           tests   points")[1].split("\n\n")[0]
    assert all(len(line) <= 99 for line in table_text.splitlines()), table_text
    hint = out.split(table_text)[1]
    assert "Did you normalise the normal (n/|n|)?" in " ".join(hint.split()), hint
    assert all(len(line) <= 88 for line in hint.splitlines()), hint
    report = json.loads((tmp_path / "r.json").read_text(encoding="utf-8"))
    message = report["exercises"]["01_levelset"]["tests"][1]["message"]
    assert " ".join(message.split()) in " ".join(hint.split())


@pytest.mark.parametrize("width", [20, 40, 88])
def test_hints_never_cut_a_word(width):
    words = ("AssertionError: ψ of plane((0, 0, 0.5), (0, 0, 2)) should be 0.5, got 1. "
             "Did you normalise the normal (n/|n|)? " + "x" * 50).split()
    text = hints([Score("01_levelset", (Result("t1", "passed"),
                                        Result("t2", "failed", 1.0, " ".join(words)),
                                        Result("t3", "failed", 1.0, "later")))], width)
    head, *body, last = text.splitlines()
    assert head == "01_levelset: t2 failed:" and "later" not in text
    assert last == "01_levelset: t3 failed"          # a later failure: one line, no message
    assert " ".join(body).split() == words
    assert all(len(line) <= width or len(line.split()) == 1 for line in body)
    assert hints([Score("x", (Result("t", "passed"),))]) == ""


def test_grade_prints_the_table_and_each_failure_once(tmp_path, capfd):
    """Untouched stubs: nothing of pytest's before the table (no column of
    NotImplementedError, no summary repeating it), then one line per failing test,
    the first of each exercise with its message."""
    for name in ("01_levelset", "02_cut"):
        copy_exercise(tmp_path, name)
    status = main([str(tmp_path / "exercises"), "--report", str(tmp_path / "r.json")])
    out, err = capfd.readouterr()
    assert status == 1 and err == "", err
    assert out.lstrip().startswith("exercise           tests   points"), out[:2000]
    assert "short test summary" not in out and "FAILED" not in out, out
    assert out.count("NotImplementedError") == 2, out          # one hint per exercise
    report = json.loads((tmp_path / "r.json").read_text(encoding="utf-8"))
    below = out.split("\ntotal ")[1].splitlines()[1:]
    failing = [f"{e}: {t['name']} " for e, ex in report["exercises"].items()
               for t in ex["tests"] if t["outcome"] != "passed"]
    assert len(failing) == report["total"] > 10
    for test in failing:
        assert sum(line.startswith(test) for line in below) == 1, (test, out)
    named = [line for line in below if line.split(":")[0] in report["exercises"]]
    assert len(named) == len(failing), below


def test_grade_dot_inside_an_exercise_counts_its_tests(tmp_path, capfd, monkeypatch):
    """cd exercises/05_lbb && skxfem grade . grades that exercise, by its name."""
    from skxfem.app.cli import main as cli
    folder = copy_exercise(tmp_path, "05_lbb")
    monkeypatch.chdir(folder)
    assert cli(["grade", "."]) == 1
    out = capfd.readouterr().out
    found = re.search(r"^05_lbb\s+0/(\d+)\s+0/\d+\s+first failure: test_01", out, flags=re.M)
    assert found and int(found.group(1)) >= 5, out
    assert "no test ran" not in out and "report: out/grades/05_lbb.json" in out, out
    report = json.loads((folder / "out" / "grades" / "05_lbb.json").read_text("utf-8"))
    assert report["total"] == int(found.group(1)) and list(report["exercises"]) == ["05_lbb"]

    monkeypatch.chdir(EXERCISES / "05_lbb")                       # the references: full marks
    assert main([".", "--impl=solution", "--report", str(tmp_path / "r.json")]) == 0
    report = json.loads((tmp_path / "r.json").read_text(encoding="utf-8"))
    assert report["passed"] == report["total"] == int(found.group(1))


def test_reports_go_to_an_ignored_folder_one_per_exercise(tmp_path, capsys, monkeypatch):
    """Without --report: out/grades/NAME.json under the current folder, so grading
    02 keeps 01's report; out/ is ignored by git. --report FILE writes FILE; a report
    that cannot be written is one line, exit 2."""
    folders = [copy_exercise(tmp_path, n) for n in ("01_levelset", "02_cut")]
    monkeypatch.chdir(tmp_path)
    for folder in folders:
        assert main([str(folder)]) == 1
        assert f"report: out/grades/{folder.name}.json" in capsys.readouterr().out
    for folder in folders:
        data = json.loads((tmp_path / "out" / "grades" / f"{folder.name}.json").read_text())
        assert list(data["exercises"]) == [folder.name] and data["passed"] == 0
    assert main([str(tmp_path / "exercises")]) == 1
    assert (tmp_path / "out" / "grades" / "exercises.json").exists()
    capsys.readouterr()
    assert main([str(folders[0]), "--report", str(tmp_path / "mine" / "a.json")]) == 1
    assert json.loads((tmp_path / "mine" / "a.json").read_text())["total"] == 7
    capsys.readouterr()
    (tmp_path / "file").write_text("")
    assert main([str(folders[0]), "--report", str(tmp_path / "file" / "a.json")]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "cannot write the report" in err
    if shutil.which("git") and (ROOT / ".git").exists():
        ignored = subprocess.run(["git", "-C", str(ROOT), "check-ignore", "-q", "--no-index",
                                  "out/grades/01_levelset.json"])
        assert ignored.returncode == 0, "out/grades/ must be ignored by git"
    assert "out/" in (ROOT / ".gitignore").read_text(encoding="utf-8").split()
