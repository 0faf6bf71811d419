"""skxfem grade's reports say whose work they grade; --collect gathers them (issue 25).

A report carries the student, the git commit and whether the folder graded had
uncommitted changes, and a UTC timestamp; grading a reference never overwrites a
student's report; ``skxfem grade --collect DIR ...`` reads reports (it runs no code)
and writes one CSV row per student and exercise.
"""
import csv
import json
import shutil
import subprocess
from datetime import datetime, timedelta, timezone
from pathlib import Path

import pytest

from skxfem.app.grade import COLUMNS, collect, default_report, main, provenance

ROOT = Path(__file__).resolve().parents[1]
EXERCISES = ROOT / "exercises"
needs_git = pytest.mark.skipif(shutil.which("git") is None, reason="needs git")


def git(folder, *args):
    return subprocess.run(["git", "-C", str(folder), "-c", "user.name=Ada Lovelace", "-c",
                           "user.email=ada@example.org", *args], check=True,
                          capture_output=True, text=True).stdout.strip()


def submission(tmp_path, name="ada") -> Path:
    """A student's clone: exercises/conftest.py and exercise 01 (a stub), committed."""
    root = tmp_path / name
    (root / "exercises").mkdir(parents=True)
    shutil.copy(EXERCISES / "conftest.py", root / "exercises" / "conftest.py")
    shutil.copytree(EXERCISES / "01_levelset", root / "exercises" / "01_levelset",
                    ignore=shutil.ignore_patterns("__pycache__"))
    return root


def report(**fields) -> dict:
    """A grade report as main writes it, for one or more exercises."""
    exercises = fields.pop("exercises", {"01_levelset": (3, 7)})
    return {"path": "exercises", "impl": "student", "student": None, "commit": None,
            "uncommitted": None, "timestamp": "2026-11-01T10:00:00Z", **fields,
            "exercises": {e: {"passed": p, "total": t, "points": float(p),
                              "max_points": float(t), "tests": []}
                          for e, (p, t) in exercises.items()}}


def write(path: Path, data) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


@needs_git
def test_provenance_names_the_author_the_commit_and_changes(tmp_path):
    root = submission(tmp_path)
    folder = root / "exercises" / "01_levelset"
    assert provenance(folder)["commit"] is None          # no repository: nothing known
    assert provenance(folder)["student"] is None
    git(root, "init", "-q")
    assert provenance(folder)["commit"] is None          # a repository without a commit
    git(root, "add", ".")
    git(root, "commit", "-q", "-m", "the course")
    head = git(root, "rev-parse", "HEAD")
    found = provenance(folder)
    assert found["student"] == "Ada Lovelace" and found["commit"] == head
    assert found["uncommitted"] is False
    assert provenance(folder, "Grace Hopper")["student"] == "Grace Hopper"
    with open(folder / "exercise.py", "a", encoding="utf-8") as f:
        f.write("\n# my work\n")
    assert provenance(folder)["uncommitted"] is True
    assert provenance(root / "exercises")["uncommitted"] is True     # it holds the change
    git(root, "commit", "-q", "-am", "my work")
    assert provenance(root / "exercises")["uncommitted"] is False
    assert provenance(folder)["commit"] == git(root, "rev-parse", "HEAD") != head
    stamp = datetime.strptime(found["timestamp"], "%Y-%m-%dT%H:%M:%SZ")
    now = datetime.now(timezone.utc).replace(tzinfo=None)
    assert timedelta(0) <= now - stamp < timedelta(minutes=5)


@needs_git
def test_the_report_carries_student_commit_and_timestamp(tmp_path, monkeypatch, capsys):
    root = submission(tmp_path)
    git(root, "init", "-q")
    git(root, "add", ".")
    git(root, "commit", "-q", "-m", "the course")
    monkeypatch.chdir(root)
    assert main(["exercises/01_levelset"]) == 1                  # the stub fails
    data = json.loads((root / "out" / "grades" / "01_levelset.json").read_text("utf-8"))
    assert data["student"] == "Ada Lovelace"
    assert data["commit"] == git(root, "rev-parse", "HEAD") and data["uncommitted"] is False
    assert datetime.fromisoformat(data["timestamp"].replace("Z", "+00:00")).tzinfo is not None
    assert data["exercises"]["01_levelset"]["passed"] == 0
    assert main(["exercises/01_levelset", "--student", "Grace Hopper", "--report", "g.json"]) == 1
    assert json.loads((root / "g.json").read_text("utf-8"))["student"] == "Grace Hopper"
    capsys.readouterr()


@pytest.mark.skipif(not (EXERCISES / "solutions").is_dir(),
                    reason="a hand-out: no reference solutions to grade")
def test_the_reference_never_overwrites_a_students_report(tmp_path, monkeypatch, capsys):
    """--impl=solution writes NAME.solution.json; a --report FILE holding a student's
    report is refused before anything runs."""
    monkeypatch.chdir(tmp_path)
    folder = EXERCISES / "05_lbb"
    student = write(tmp_path / "out" / "grades" / "05_lbb.json", report(student="ada"))
    before = student.read_bytes()
    assert default_report(folder, "solution") == Path("out/grades/05_lbb.solution.json")
    assert main([str(folder), "--impl=solution"]) == 0
    assert "report: out/grades/05_lbb.solution.json" in capsys.readouterr().out
    assert student.read_bytes() == before
    solution = json.loads((tmp_path / default_report(folder, "solution")).read_text("utf-8"))
    assert solution["impl"] == "solution" and solution["passed"] == solution["total"] > 4

    assert main([str(folder), "--impl=solution", "--report", str(student)]) == 2
    out, err = capsys.readouterr()
    assert out == "" and len(err.splitlines()) == 1 and "never overwrites" in err, err
    assert student.read_bytes() == before
    for other in ("notes.json", "notes.txt"):          # not a report: kept too
        kept = tmp_path / other
        kept.write_text("[1, 2]", encoding="utf-8")
        assert main([str(folder), "--impl=solution", "--report", str(kept)]) == 2
        assert kept.read_text(encoding="utf-8") == "[1, 2]"
    capsys.readouterr()


def test_collect_three_submissions_into_one_csv(tmp_path, monkeypatch, capsys):
    """Three submissions → one CSV row per student and exercise, the newest report of
    each; instructors' reports and other JSON files are left out."""
    monkeypatch.chdir(tmp_path)
    subs = tmp_path / "submissions"
    grades = Path("out") / "grades"
    write(subs / "ada" / grades / "exercises.json",
          report(student="Ada", commit="a" * 40, uncommitted=False,
                 exercises={"01_levelset": (3, 7), "02_cut": (8, 8)}))
    write(subs / "ada" / grades / "01_levelset.json",          # newer: it gives the row
          report(student="Ada", commit="b" * 40, uncommitted=True,
                 timestamp="2026-11-02T09:00:00Z", exercises={"01_levelset": (7, 7)}))
    write(subs / "ada" / grades / "01_levelset.solution.json",   # the instructor's: left out
          report(impl="solution", student="Ada", timestamp="2026-11-03T09:00:00Z",
                 exercises={"01_levelset": (0, 7)}))
    write(subs / "bob" / grades / "02_cut.json",                  # no student: the folder
          report(exercises={"02_cut": (2, 8)}))
    write(subs / "bob" / "notes.json", {"exercises": "not a report"})
    write(subs / "cy" / "elsewhere" / "r.json",
          report(student="Cy", exercises={"07_contact": (1, 9)}))
    (subs / "dee").mkdir()                                        # nothing handed in

    assert main(["--collect", *(str(p) for p in sorted(subs.iterdir()))]) == 0
    out, err = capsys.readouterr()
    assert "collected: 4 row(s), 3 student(s)" in out and "out/grades/collected.csv" in out
    assert err.count("skxfem grade: note: no student's grade report under") == 1
    assert "dee" in err
    with open(tmp_path / "out" / "grades" / "collected.csv", encoding="utf-8", newline="") as f:
        reader = csv.DictReader(f)
        assert tuple(reader.fieldnames) == COLUMNS
        rows = [(r["student"], r["exercise"], r["passed"], r["total"], r["points"],
                 r["max_points"], r["commit"][:1], r["uncommitted"]) for r in reader]
    assert rows == [("Ada", "01_levelset", "7", "7", "7", "7", "b", "yes"),
                    ("Ada", "02_cut", "8", "8", "8", "8", "a", "no"),
                    ("Cy", "07_contact", "1", "9", "1", "9", "", ""),
                    ("bob", "02_cut", "2", "8", "2", "8", "", "")]
    assert collect([subs / "cy" / "elsewhere" / "r.json"])[0]["student"] == "Cy"


def test_collect_refuses_what_it_cannot_tell_apart(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    for name in ("one", "two"):          # two clones whose last commit is the course's
        write(tmp_path / name / "out" / "grades" / "exercises.json",
              report(student="The course"))
    assert main(["--collect", "one", "two"]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "'The course'" in err and "--student" in err
    assert not (tmp_path / "out").exists()
    assert main(["--collect", "one", "nowhere"]) == 2
    assert "nowhere is no folder or report file" in capsys.readouterr().err
    assert main(["--collect", "one", "--impl=solution"]) == 2
    assert "--collect grades nothing" in capsys.readouterr().err
    (tmp_path / "file").write_text("")           # an unwritable CSV (root writes anywhere)
    assert main(["--collect", "one", "--report", "file/grades.csv"]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "cannot write the CSV" in err
