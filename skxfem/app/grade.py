"""Grade the exercises: run their tests, print a score table, write a JSON report.

    skxfem grade [PATH] [--impl student] [--student NAME] [--report FILE]
    skxfem grade --collect DIR [DIR ...] [--report FILE.csv]   # = python -m skxfem.app.grade

PATH is the ``exercises`` folder (the default) or one exercise in it
(``exercises/02_cut``).  The tests run in a ``python -m pytest`` subprocess
with a JUnit XML report, which this module reads back: pytest is a development
extra, so importing skxfem never needs it, and a crash in a student's file
cannot take the grader down with it.  ``--impl`` is passed on to the
exercises' ``conftest.py``: ``student`` (the default), ``solution`` or
``wrong:NAME``, checked here first (:func:`check_impl`), so that a misspelt
choice is one line naming the valid ones, not a column of pytest errors.

The score table has one row per exercise; below it, every test that did not
pass, once: the first of each exercise with its whole message (its hint, e.g.
"Did you normalise the normal?"), each later one in one line.  pytest's own
output is kept out of the way (it would print every failure twice more); it is
shown only when an exercise ran no test at all, as the reason.

The JSON report of a run is one file, by default ``out/grades/NAME.json`` under
the current folder, NAME the folder graded (``01_levelset``, or ``exercises``
for all; ``.`` inside an exercise is that exercise): grading one exercise never
overwrites another's report, and ``out/`` is ignored by git.  ``--report FILE``
writes it elsewhere.  A report also says whose work it graded and which: the
``student`` (``--student NAME``, else the author of the last git commit of the
folder graded, else null), the ``commit`` (git HEAD there, else null), whether
the folder graded had ``uncommitted`` changes, and the ``timestamp`` of the grading
(UTC, ISO 8601, ``2026-11-25T14:03:59Z``).

Grading a reference (``--impl=solution``) or a wrong solution
(``--impl=wrong:NAME``) never overwrites a student's report: its default report is
``out/grades/NAME.solution.json`` (``NAME.wrong-NAME.json``), and a ``--report``
FILE that holds a student's report is refused.

``--collect DIR ...`` runs no code: it reads the students' reports (every
``*.json`` grade report with ``impl`` student under each DIR, e.g. each
submission's ``out/grades/``; a DIR may also be one report file) and writes one
CSV, by default ``out/grades/collected.csv``, one row per student and exercise
(the newest report of each), with the columns :data:`COLUMNS`.  A report is only
as trustworthy as whoever wrote it: to be sure of a grade, run ``skxfem grade``
on the submission yourself (with ``--student``) and collect those reports.
The student's code runs unsandboxed, with the rights of whoever grades it.

A test is worth the points of its ``@pytest.mark.points(n)`` marker, 1
without one.  The exit status is 0 when every test passed, 1 when any failed
and 2 for a usage error (a bad PATH or ``--impl``, a report that cannot be
written or would replace a student's; one line on stderr) or when no test could
be run at all.  ``--collect`` exits 0 when it wrote the CSV, 2 if it could not.
"""
from __future__ import annotations

import argparse
import csv
import json
import subprocess
import sys
import tempfile
import textwrap
import xml.etree.ElementTree as ET
from dataclasses import asdict, dataclass
from datetime import datetime, timezone
from pathlib import Path

__all__ = ["Result", "Score", "COLUMNS", "find_exercises", "wrong_solutions", "check_impl",
           "default_report", "provenance", "read_junit", "table", "hints", "grade",
           "collect", "write_csv", "main"]

REPORTS = Path("out") / "grades"
"""Where the reports go by default, under the current folder (``out/`` is git-ignored)."""

COLLECTED = REPORTS / "collected.csv"
"""Where ``--collect`` writes its CSV by default."""

COLUMNS = ("student", "exercise", "passed", "total", "points", "max_points", "commit",
           "uncommitted", "timestamp", "report")
"""The columns of the ``--collect`` CSV, one row per student and exercise: the
student (the report's, else the name of the DIR it was found under), the exercise
folder's name, tests passed and run, points won and possible, the git commit and
whether the folder had uncommitted changes when graded (empty when unknown), when
it was graded (UTC, ISO 8601) and the report file the row comes from."""

WIDTH = 88
"""Width the hints below the score table are wrapped to (whole words, nothing cut)."""


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
    """The exercise folders under ``path`` (or ``path`` itself): those holding test files.

    Absolute, so that ``.`` inside an exercise is that exercise, named by its folder.
    """
    path = Path(path).resolve()
    if any(path.glob("test_*.py")):
        return [path]
    return sorted(p for p in path.iterdir() if p.is_dir() and any(p.glob("test_*.py")))


def wrong_solutions(exercises: list[Path]) -> dict[str, list[str]]:
    """The wrong solutions kept for ``exercises``: NAME -> the exercises that have
    ``solutions/<exercise>/wrong_NAME.py`` (beside the exercise folders).

    >>> wrong_solutions([Path("course") / "01_levelset"])   # no course/solutions/ here
    {}
    """
    found: dict[str, list[str]] = {}
    for e in exercises:
        for f in sorted((Path(e).parent / "solutions" / Path(e).name).glob("wrong_*.py")):
            found.setdefault(f.stem.removeprefix("wrong_"), []).append(Path(e).name)
    return dict(sorted(found.items()))


def check_impl(impl: str, exercises: list[Path]) -> list[Path]:
    """The exercises to grade for ``--impl``; a ValueError naming the valid choices.

    ``wrong:NAME`` grades the exercises that have that wrong solution (the others
    have nothing to grade); ``solution`` needs the ``solutions`` folder beside them.

    >>> all_ = find_exercises(Path(__file__).parents[2] / "exercises")
    >>> check_impl("student", all_) == all_
    True
    >>> check_impl("bogus", all_)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: --impl must be student, solution or wrong:NAME ...; got 'bogus'
    """
    wrong = wrong_solutions(exercises)
    listed = ", ".join(wrong) or "none here"
    usage = (f"--impl must be student, solution or wrong:NAME (NAME one of: {listed}); "
             f"got {impl!r}")
    if impl == "student":
        return exercises
    if impl == "solution":
        missing = [e for e in exercises
                   if not (e.parent / "solutions" / e.name / "reference.py").is_file()]
        if missing:
            raise ValueError(f"--impl=solution: no reference solution for "
                             f"{', '.join(e.name for e in missing)} (looked in "
                             f"{missing[0].parent / 'solutions'}); the solutions stay with "
                             f"the instructor: grade your own files with --impl=student")
        return exercises
    if impl.startswith("wrong:") and impl.removeprefix("wrong:") in wrong:
        having = wrong[impl.removeprefix("wrong:")]
        return [e for e in exercises if e.name in having]
    raise ValueError(usage)


def default_report(path: Path, impl: str = "student") -> Path:
    """The default report of grading ``path``: ``out/grades/NAME.json``, NAME its folder;
    ``NAME.solution.json`` or ``NAME.wrong-WRONG.json`` for the instructors' ``impl``,
    so that grading them never overwrites a student's report.

    >>> default_report(Path("exercises/02_cut/")).as_posix()
    'out/grades/02_cut.json'
    >>> default_report(Path("exercises/02_cut/"), "solution").as_posix()
    'out/grades/02_cut.solution.json'
    >>> default_report(Path("exercises"), "wrong:sides").as_posix()
    'out/grades/exercises.wrong-sides.json'
    """
    suffix = "" if impl == "student" else "." + impl.replace(":", "-")
    return REPORTS / f"{Path(path).resolve().name or 'exercises'}{suffix}.json"


def _git(folder: Path, *args: str) -> str | None:
    """The output of ``git -C folder ARGS`` stripped, or None (no git, no repository)."""
    try:
        done = subprocess.run(["git", "-C", str(folder), *args], capture_output=True,
                              text=True, encoding="utf-8", errors="replace", timeout=60)
    except (OSError, subprocess.SubprocessError):
        return None
    return done.stdout.strip() if done.returncode == 0 else None


def provenance(path: Path, student: str | None = None) -> dict:
    """Whose work grading ``path`` grades, and which: the report's ``student``,
    ``commit``, ``uncommitted`` and ``timestamp`` (see the module notes).

    ``student`` is the name given, else the author of the last commit of the git
    repository holding ``path``; ``commit`` its HEAD; ``uncommitted`` whether
    ``path`` differs from it (None, each, where there is no git or no commit).

    >>> sorted(provenance(Path("no-such-folder"), "ada"))
    ['commit', 'student', 'timestamp', 'uncommitted']
    """
    folder = Path(path).resolve()
    while not folder.is_dir() and folder != folder.parent:   # git -C needs a folder
        folder = folder.parent
    commit = _git(folder, "rev-parse", "--verify", "-q", "HEAD") or None
    status = _git(folder, "status", "--porcelain", "--", ".") if commit else None
    return {"student": student if student is not None else
            ((_git(folder, "log", "-1", "--format=%an") or None) if commit else None),
            "commit": commit,
            "uncommitted": None if status is None else bool(status),
            "timestamp": datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")}


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

    The messages of the failures are not in it: :func:`hints` prints them in full.

    >>> print(table([Score("01_levelset", (Result("test_01", "passed", 2.0),
    ...                                    Result("test_02", "failed", 1.0, "no")))]))
    exercise           tests   points
    01_levelset          1/2      2/3   first failure: test_02 (below)
    total                1/2      2/3
    """
    def row(name, passed, total, points, best, note=""):
        return (f"{name:16} {f'{passed}/{total}':>7} "
                f"{f'{_number(points)}/{_number(best)}':>8}{note}")

    rows = [f"{'exercise':16} {'tests':>7} {'points':>8}"]
    for s in scores:
        failed = next((r for r in s.results if r.outcome != "passed"), None)
        note = f"   first failure: {failed.name} (below)" if failed else ""
        if s.total == 0:
            note = "   no test ran (see the pytest output above)"
        rows.append(row(s.exercise, s.passed, s.total, s.points, s.max_points, note))
    rows.append(row("total", sum(s.passed for s in scores), sum(s.total for s in scores),
                    sum(s.points for s in scores), sum(s.max_points for s in scores)))
    return "\n".join(rows)


def hints(scores: list[Score], width: int = WIDTH) -> str:
    """Every test that did not pass, once each, or '' if all passed.

    Per exercise, the first one with its whole message, wrapped to ``width`` columns
    between words (a hint is never cut), then one line per later one (its message
    is in the JSON report; ``pytest`` on the exercise shows them all).

    >>> print(hints([Score("01_levelset", (Result("test_02", "failed", 1.0,
    ...     "AssertionError: psi should be 0.5, got 1. Did you normalise the normal?"),
    ...     Result("test_03", "error", 1.0, "later")))], width=40))
    01_levelset: test_02 failed:
        AssertionError: psi should be 0.5,
        got 1. Did you normalise the normal?
    01_levelset: test_03 could not run
    """
    said = {"failed": "failed", "error": "could not run", "skipped": "was skipped"}
    lines = []
    for s in scores:
        failed = [r for r in s.results if r.outcome != "passed"]
        if not failed:
            continue
        first, *later = failed
        text = textwrap.fill(first.message or "(no message)", width, initial_indent="    ",
                             subsequent_indent="    ", break_long_words=False,
                             break_on_hyphens=False)
        lines.append(f"{s.exercise}: {first.name} {said.get(first.outcome, first.outcome)}"
                     f":\n{text}")
        lines += [f"{s.exercise}: {r.name} {said.get(r.outcome, r.outcome)}" for r in later]
    return "\n".join(lines)


def grade(path: Path, impl: str = "student", pytest_args: tuple[str, ...] = ()) -> list[Score]:
    """Run the exercises under ``path`` with pytest in a subprocess; their scores.

    pytest's output is captured, not shown (the scores say it all), except when an
    exercise ran no test: then it is printed, as the reason.

    Raises
    ------
    FileNotFoundError
        If ``path`` holds no exercise (no folder with test files).
    ValueError
        If ``impl`` is not a valid choice for these exercises (:func:`check_impl`).
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
    exercises = check_impl(impl, exercises)
    names = [e.name for e in exercises]
    root = exercises[0].parent   # where exercises/conftest.py is: it defines --impl
    with tempfile.TemporaryDirectory() as tmp:
        xml_path = Path(tmp) / "junit.xml"
        command = [sys.executable, "-m", "pytest", *map(str, exercises), f"--impl={impl}",
                   f"--junitxml={xml_path}", "-o", "junit_family=xunit1",
                   f"--rootdir={root}", "-p", "no:cacheprovider", "-q", "--tb=line",
                   *pytest_args]
        done = subprocess.run(command, capture_output=True, text=True, errors="replace")
        if not xml_path.exists():
            said = (done.stderr.strip() or done.stdout.strip()).splitlines()
            raise RuntimeError(
                f"pytest did not run (exit status {done.returncode}): {said[-1]}" if said else
                f"pytest did not run (exit status {done.returncode}); is it installed? "
                f"pip install 'skxfem[dev]' (or: pip install pytest)")
        results = read_junit(xml_path, names)
    scores = [Score(n, tuple(results[n])) for n in names]
    if any(s.total == 0 for s in scores):
        print(done.stdout, end="")
        print(done.stderr, end="", file=sys.stderr)
    return scores


def _is_report(data) -> bool:
    """Whether ``data`` (a parsed JSON file) is a grade report of :func:`main`."""
    return (isinstance(data, dict) and isinstance(data.get("exercises"), dict)
            and isinstance(data.get("impl"), str)
            and all(isinstance(e, dict) and {"passed", "total", "points", "max_points"} <= set(e)
                    for e in data["exercises"].values()))


def _read_report(path: Path):
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return data if _is_report(data) else None


def collect(places: list[Path], warn=None) -> list[dict]:
    """The rows of the ``--collect`` CSV: one per student and exercise (:data:`COLUMNS`).

    Each of ``places`` is a submission folder, searched for grade reports
    (``*.json`` files that are reports of :func:`main` with ``impl`` student; the
    instructors' ``solution`` and ``wrong:NAME`` reports are left out), or one
    report file.  A report without a student (no ``--student``, no git) counts for
    the place it was found in, by its folder's name.  When several reports grade the
    same student's exercise, the newest (``timestamp``) gives the row.  ``warn`` is
    called with a line for each place that holds no report.

    Raises
    ------
    FileNotFoundError
        If a place does not exist.
    ValueError
        If two places hold reports of the same student (two submissions would be
        merged): grade them again with ``--student``.
    """
    rows: dict[tuple[str, str], dict] = {}
    owner: dict[str, Path] = {}
    for place in map(Path, places):
        if place.is_file():
            files = [place]
        elif place.is_dir():
            files = sorted(f for f in place.rglob("*.json") if f.is_file())
        else:
            raise FileNotFoundError(f"--collect: {place} is no folder or report file")
        reports = [(f, r) for f in files
                   if (r := _read_report(f)) is not None and r["impl"] == "student"]
        if not reports and warn is not None:
            warn(f"no student's grade report under {place} (skxfem grade writes "
                 f"out/grades/NAME.json)")
        for path, report in reports:
            student = str(report.get("student") or place.resolve().name)
            first = owner.setdefault(student, place)
            if first.resolve() != place.resolve():
                raise ValueError(f"--collect: {first} and {place} both hold reports of the "
                                 f"student {student!r}; grade the submissions with "
                                 f"--student NAME, one name each")
            for exercise, ex in report["exercises"].items():
                row = {"student": student, "exercise": exercise,
                       "passed": ex["passed"], "total": ex["total"],
                       "points": _number(float(ex["points"])),
                       "max_points": _number(float(ex["max_points"])),
                       "commit": report.get("commit") or "",
                       "uncommitted": {True: "yes", False: "no"}.get(report.get("uncommitted"),
                                                                     ""),
                       "timestamp": report.get("timestamp") or "", "report": str(path)}
                kept = rows.get((student, exercise))
                if kept is None or row["timestamp"] > kept["timestamp"]:
                    rows[(student, exercise)] = row
    return [rows[k] for k in sorted(rows)]


def write_csv(rows: list[dict], where: Path) -> Path:
    """Write ``rows`` (:func:`collect`) as a CSV with a header of :data:`COLUMNS`."""
    where = Path(where)
    where.parent.mkdir(parents=True, exist_ok=True)
    with open(where, "w", encoding="utf-8", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    return where


class _Parser(argparse.ArgumentParser):
    """argparse, with a usage error in one line (exit 2)."""

    def error(self, message):
        self.exit(2, f"skxfem grade: error: {message} (see skxfem grade --help)\n")


def _usage_error(message: str) -> int:
    print(f"skxfem grade: error: {' '.join(str(message).split())}", file=sys.stderr)
    return 2


def _collect(places: list[Path], where: Path | None) -> int:
    """``--collect``: the CSV of every student's reports under ``places``."""
    def note(text):
        print(f"skxfem grade: note: {text}", file=sys.stderr)

    try:
        rows = collect(places, warn=note)
    except (FileNotFoundError, ValueError) as error:
        return _usage_error(error)
    where = where if where is not None else COLLECTED
    try:
        write_csv(rows, where)
    except OSError as e:
        return _usage_error(f"cannot write the CSV to {str(where)!r} ({e.strerror or e}); "
                            f"give another --report FILE")
    students = len({r["student"] for r in rows})
    print(f"collected: {len(rows)} row(s), {students} student(s) x exercise -> {where}")
    return 0


def main(argv: list[str] | None = None) -> int:
    """The command line: ``skxfem grade [PATH] [--impl ...] [--student ...] [--report ...]``
    or ``skxfem grade --collect DIR ... [--report FILE.csv]``.

    >>> main(["no-such-folder"])
    2
    """
    parser = _Parser(
        prog="skxfem grade",
        description="Run the exercises' tests, print a score table per exercise and the "
                    "message of each exercise's first failure, and write a JSON report; "
                    "or, with --collect, gather the students' reports into one CSV.",
        epilog="The graded code runs unsandboxed, with your rights: grade a student's "
               "submission as you would run any code of theirs.")
    parser.add_argument("path", nargs="?", default=None,
                        help="the exercises folder or one exercise (default: exercises)")
    parser.add_argument("--impl", default="student",
                        help="student (default: NN_name/exercise.py), solution, or "
                             "wrong:NAME (a known wrong solution, instructors' test data)")
    parser.add_argument("--student", default=None, metavar="NAME",
                        help="whose work it is, for the report (default: the author of the "
                             "last git commit of the folder graded)")
    parser.add_argument("--report", type=Path, default=None, metavar="FILE",
                        help=f"where to write the JSON report (default: "
                             f"{REPORTS}/NAME.json under the current folder, NAME the "
                             f"folder graded, NAME.solution.json for --impl=solution; out/ is "
                             f"ignored by git); with --collect the CSV (default: {COLLECTED})")
    parser.add_argument("--collect", nargs="+", type=Path, default=None, metavar="DIR",
                        help="run nothing: gather the students' grade reports found under "
                             "each DIR (a submission, or one report file) into one CSV, one "
                             "row per student and exercise")
    args = parser.parse_args(argv)
    if args.collect is not None:
        given = [o for o, v in (("PATH", args.path), ("--student", args.student))
                 if v is not None] + (["--impl"] if args.impl != "student" else [])
        if given:
            return _usage_error(f"--collect grades nothing: it takes no {', '.join(given)}")
        return _collect(args.collect, args.report)
    path = Path(args.path if args.path is not None else "exercises")
    where = args.report if args.report is not None else default_report(path, args.impl)
    if args.impl != "student":
        kept = _read_report(where) if where.is_file() else None
        if where.exists() and (kept is None or kept["impl"] == "student"):
            return _usage_error(f"--impl={args.impl} never overwrites a student's report: "
                                f"{str(where)!r} exists; give another --report FILE")
    try:
        scores = grade(path, args.impl)
    except (FileNotFoundError, RuntimeError, ValueError) as error:
        return _usage_error(error)
    print()
    print(table(scores))
    if any(s.passed < s.total for s in scores):
        print()
        print(hints(scores))
    report = {
        "path": str(path), "impl": args.impl,
        **provenance(path, args.student),
        "passed": sum(s.passed for s in scores), "total": sum(s.total for s in scores),
        "points": sum((s.points for s in scores), 0.0),
        "max_points": sum((s.max_points for s in scores), 0.0),
        "exercises": {s.exercise: {"passed": s.passed, "total": s.total, "points": s.points,
                                   "max_points": s.max_points,
                                   "tests": [asdict(r) for r in s.results]} for s in scores},
    }
    try:
        where.parent.mkdir(parents=True, exist_ok=True)
        where.write_text(json.dumps(report, indent=2, ensure_ascii=False) + "\n",
                         encoding="utf-8")
    except OSError as e:
        return _usage_error(f"cannot write the report to {str(where)!r} "
                            f"({e.strerror or e}); give another --report FILE")
    print(f"report: {where}")
    if report["total"] == 0:
        return 2
    return 0 if report["passed"] == report["total"] else 1


if __name__ == "__main__":
    sys.exit(main())
