"""Grade the exercises: run their tests, print a score table, write a JSON report.

    python -m skxfem.grade [PATH] [--impl student] [--report grade.json]

PATH is the ``exercises`` folder (the default) or one exercise in it
(``exercises/02_cut``).  The tests run in a ``python -m pytest`` subprocess
with a JUnit XML report, which this module reads back: pytest is a development
extra, so importing skxfem never needs it, and a crash in a student's file
cannot take the grader down with it.  ``--impl`` is passed on to the
exercises' ``conftest.py`` (``student``, ``solution`` or ``wrong:NAME``).

A test is worth the points of its ``@pytest.mark.points(n)`` marker, 1
without one.  The exit status is 0 when every test passed, 1 when any failed
and 2 when no test could be run at all.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from dataclasses import asdict, dataclass
from pathlib import Path

__all__ = ["Result", "Score", "find_exercises", "read_junit", "table", "grade", "main"]


@dataclass(frozen=True)
class Result:
    """One test: its name, ``passed`` / ``failed`` / ``error`` / ``skipped``,
    its points and the first line of its failure message."""

    name: str
    outcome: str
    points: float = 1.0
    message: str = ""


@dataclass(frozen=True)
class Score:
    """The results of one exercise's tests, in the order they ran."""

    exercise: str
    results: tuple[Result, ...]

    @property
    def passed(self) -> int:
        return sum(r.outcome == "passed" for r in self.results)

    @property
    def total(self) -> int:
        return len(self.results)

    @property
    def points(self) -> float:
        return sum((r.points for r in self.results if r.outcome == "passed"), 0.0)

    @property
    def max_points(self) -> float:
        return sum((r.points for r in self.results), 0.0)


def find_exercises(path: Path) -> list[Path]:
    """The exercise folders under ``path`` (or ``path`` itself): those holding test files."""
    path = Path(path)
    if any(path.glob("test_*.py")):
        return [path]
    return sorted(p for p in path.iterdir() if p.is_dir() and any(p.glob("test_*.py")))


def _exercise_of(classname: str, names: list[str]) -> str | None:
    """The exercise a JUnit classname belongs to (its dotted path names the folder).

    >>> _exercise_of("exercises.02_cut.test_cut_exercise", ["01_levelset", "02_cut"])
    '02_cut'
    """
    parts = classname.split(".")
    return next((n for n in names if n in parts), None)


def read_junit(xml_path: Path, names: list[str]) -> dict[str, list[Result]]:
    """The results of a JUnit XML report, grouped by exercise folder name."""
    results: dict[str, list[Result]] = {n: [] for n in names}
    for case in ET.parse(xml_path).getroot().iter("testcase"):
        exercise = _exercise_of(case.get("classname", ""), names)
        if exercise is None:
            continue
        outcome, message = "passed", ""
        for tag in ("failure", "error", "skipped"):
            node = case.find(tag)
            if node is not None:
                outcome = {"failure": "failed"}.get(tag, tag)
                message = (node.get("message") or node.text or "").strip().splitlines()
                message = message[0] if message else ""
                break
        points = 1.0
        for prop in case.iter("property"):
            if prop.get("name") == "points":
                points = float(prop.get("value"))
        results[exercise].append(Result(case.get("name", "?"), outcome, points, message))
    return results


def _number(x: float) -> str:
    return f"{x:g}"


def table(scores: list[Score]) -> str:
    """The score table: one row per exercise, then the total.

    >>> print(table([Score("01_levelset", (Result("test_01", "passed", 2.0),
    ...                                    Result("test_02", "failed", 1.0, "no")))]))
    exercise           tests   points
    01_levelset          1/2      2/3   first failure: test_02: no
    total                1/2      2/3
    """
    def row(name, passed, total, points, best, note=""):
        return (f"{name:16} {f'{passed}/{total}':>7} "
                f"{f'{_number(points)}/{_number(best)}':>8}{note}"[:200])

    rows = [f"{'exercise':16} {'tests':>7} {'points':>8}"]
    for s in scores:
        failed = next((r for r in s.results if r.outcome != "passed"), None)
        note = f"   first failure: {failed.name}: {failed.message}" if failed else ""
        if s.total == 0:
            note = "   no test ran (see the pytest output above)"
        rows.append(row(s.exercise, s.passed, s.total, s.points, s.max_points, note))
    rows.append(row("total", sum(s.passed for s in scores), sum(s.total for s in scores),
                    sum(s.points for s in scores), sum(s.max_points for s in scores)))
    return "\n".join(rows)


def grade(path: Path, impl: str = "student", pytest_args: tuple[str, ...] = ()) -> list[Score]:
    """Run the exercises under ``path`` with pytest in a subprocess; their scores.

    Raises
    ------
    FileNotFoundError
        If ``path`` holds no exercise (no folder with test files).
    RuntimeError
        If pytest could not run (not installed, or a usage error): no report.
    """
    path = Path(path)
    if not path.is_dir():
        raise FileNotFoundError(f"{path} is not a folder: give the exercises folder or one "
                                f"exercise in it, e.g. exercises/01_levelset")
    exercises = find_exercises(path)
    if not exercises:
        raise FileNotFoundError(f"no exercise under {path}: an exercise is a folder with "
                                f"test_*.py files, e.g. exercises/01_levelset")
    names = [e.name for e in exercises]
    root = exercises[0].parent   # where exercises/conftest.py is: it defines --impl
    with tempfile.TemporaryDirectory() as tmp:
        xml_path = Path(tmp) / "junit.xml"
        command = [sys.executable, "-m", "pytest", str(path), f"--impl={impl}",
                   f"--junitxml={xml_path}", "-o", "junit_family=xunit1",
                   f"--rootdir={root}", "-p", "no:cacheprovider", "-q", "--tb=line",
                   *pytest_args]
        done = subprocess.run(command)
        if not xml_path.exists():
            raise RuntimeError(
                f"pytest did not run (exit status {done.returncode}); is it installed? "
                f"pip install 'skxfem[dev]' (or: pip install pytest)")
        results = read_junit(xml_path, names)
    return [Score(n, tuple(results[n])) for n in names]


def main(argv: list[str] | None = None) -> int:
    """The command line: ``python -m skxfem.grade [PATH] [--impl ...] [--report ...]``."""
    parser = argparse.ArgumentParser(
        prog="python -m skxfem.grade",
        description="Run the exercises' tests and print a score table per exercise.")
    parser.add_argument("path", nargs="?", default="exercises",
                        help="the exercises folder or one exercise (default: exercises)")
    parser.add_argument("--impl", default="student",
                        help="student (default), solution or wrong:NAME")
    parser.add_argument("--report", default="grade.json",
                        help="where to write the JSON report (default: grade.json)")
    args = parser.parse_args(argv)
    try:
        scores = grade(Path(args.path), args.impl)
    except (FileNotFoundError, RuntimeError) as error:
        print(f"skxfem grade: {error}", file=sys.stderr)
        return 2
    print()
    print(table(scores))
    report = {
        "path": str(args.path), "impl": args.impl,
        "passed": sum(s.passed for s in scores), "total": sum(s.total for s in scores),
        "points": sum((s.points for s in scores), 0.0),
        "max_points": sum((s.max_points for s in scores), 0.0),
        "exercises": {s.exercise: {"passed": s.passed, "total": s.total, "points": s.points,
                                   "max_points": s.max_points,
                                   "tests": [asdict(r) for r in s.results]} for s in scores},
    }
    Path(args.report).write_text(json.dumps(report, indent=2, ensure_ascii=False) + "\n",
                                 encoding="utf-8")
    print(f"report: {args.report}")
    if report["total"] == 0:
        return 2
    return 0 if report["passed"] == report["total"] else 1


if __name__ == "__main__":
    sys.exit(main())
