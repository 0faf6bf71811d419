"""The course as a student gets it: ``skxfem handout DIR`` (``make handout``).

    skxfem handout DIR                  # = python -m skxfem.app.handout DIR

An instructor's clone holds the reference solutions (``exercises/solutions/``) and
what needs them.  The hand-out is a copy of the repository's files as git tracks
them (without git: every file but the build products, :data:`BUILT`) into DIR, a
new or empty folder, with

* ``exercises/solutions/`` left out: the references and the wrong solutions;
* the instructors' tests left out (:data:`INSTRUCTOR_TESTS`: they grade the
  references and the wrong solutions, or follow the instructors' commands);
* each ``exercises/NN_name/exercise.py`` written as its pristine stub
  (:func:`skxfem.app.graded.stub`): an instructor's solved file is never handed out;
* ``exercises/library_answers.json`` added: the names of the library functions that
  answer each exercise (:func:`skxfem.app.graded.library_answers`, no code), so that
  the students' book check (``make book``) works there without the references.

Everything else is the same: the library, whole (exercises 01, 06 and 07 grade
functions that ``skxfem/levelset.py``, ``skxfem/stabilised.py`` and
``skxfem/contact/laws.py`` show: a student may read them; the graders refuse a file
that imports them, and the point is to write them from the equations), the book,
the Makefile (``make book-instructor`` says it needs the solutions; ``make test``
builds the students' book only), the exercises' tests and ``conftest.py``.  In DIR,
``make install``, ``.venv/bin/pytest exercises`` (every test fails as an untouched
stub does) and ``make book`` work as in the instructor's clone.

Before DIR is written, every handed-out file is checked: none may hold the code of
a reference's own function (a solution pasted into a README, a chapter, a test).
The files are written into a hidden folder beside DIR that then takes its place:
a failed hand-out leaves nothing.  Errors are one line ``skxfem handout: error:
...``, exit 2.
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from . import graded

__all__ = ["INSTRUCTOR_TESTS", "BUILT", "repository", "files", "contents", "leaks", "write",
           "main"]

INSTRUCTOR_TESTS = ("tests/test_exercises.py", "tests/test_book_stubs.py",
                    "tests/test_graded.py", "tests/test_getting_started.py",
                    "tests/test_handout.py")
"""The tests that need the reference solutions: left out of a hand-out."""

SOLUTIONS = "exercises/solutions/"

BUILT = {".git", ".venv", "out", "notebooks", "build", "__pycache__", ".pytest_cache",
         ".ruff_cache", ".ipynb_checkpoints", "_build", "_stubs", "_mathjax"}
"""Folders never handed out when there is no git to list the files (build products)."""


def repository() -> Path:
    """The clone this skxfem comes from (the folder above the package)."""
    return Path(__file__).resolve().parents[2]


def files(root: Path) -> list[str]:
    """The repository's files, relative POSIX paths: git's tracked files, or without
    git every file outside the build products (:data:`BUILT`, ``*.egg-info``)."""
    root = Path(root)
    try:
        done = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "--cached"],
                              capture_output=True, timeout=60)
        listed = done.stdout.decode("utf-8").split("\0") if done.returncode == 0 else None
    except (OSError, subprocess.SubprocessError):
        listed = None
    if listed is None:
        listed = [p.relative_to(root).as_posix() for p in root.rglob("*") if p.is_file()
                  and not any(part in BUILT or part.endswith(".egg-info")
                              for part in p.relative_to(root).parts)]
    return sorted(f for f in listed if f and (root / f).is_file())


def contents(root: Path) -> dict[str, bytes]:
    """What the hand-out of ``root`` holds: relative path -> bytes (see the module notes)."""
    root = Path(root)
    exercises = root / "exercises"
    stubs = {f"exercises/{e}/exercise.py": graded.stub(e, exercises).encode("utf-8")
             for e in graded.graded(exercises)}
    handed = {}
    for name in files(root):
        if name.startswith(SOLUTIONS) or name in INSTRUCTOR_TESTS:
            continue
        handed[name] = stubs.get(name) or (root / name).read_bytes()
    handed[f"exercises/{graded.LIBRARY_ANSWERS}"] = (json.dumps(
        graded.library_answers(exercises), indent=2) + "\n").encode("utf-8")
    return handed


def leaks(handed: dict[str, bytes], root: Path) -> list[str]:
    """The handed-out files that show the code of a reference's own function (one line
    each), as :func:`skxfem.app.graded.check_book` finds code on a page."""
    exercises = Path(root) / "exercises"
    own = {name: graded.code_lines(f) for e in graded.graded(exercises)
           for name, f in graded.answers(e, exercises).items() if not name.startswith("skxfem.")}
    found = []
    for path, data in handed.items():
        lines = {line.strip() for line in data.decode("utf-8", "replace").splitlines()}
        found += [f"{path} shows the code of {name}" for name, code in own.items()
                  if code and graded._shown(code, lines)]
    return found


def write(out: Path, root: Path | None = None) -> list[str]:
    """Write the hand-out of ``root`` (this clone) into ``out``; the files written.

    Raises
    ------
    FileExistsError
        If ``out`` exists and is not an empty folder.
    FileNotFoundError
        If ``root`` has no ``exercises/solutions/`` (a hand-out is made from an
        instructor's clone).
    ValueError
        If a handed-out file shows a reference's code (:func:`leaks`).
    """
    root, out = Path(root) if root is not None else repository(), Path(out)
    if not (root / SOLUTIONS).is_dir():
        raise FileNotFoundError(f"no {SOLUTIONS} in {root}: a hand-out is made from the "
                                f"instructor's clone, which has the solutions")
    if out.exists() and (not out.is_dir() or any(out.iterdir())):
        raise FileExistsError(f"{out} exists and is not an empty folder: give a new one")
    if out.resolve().is_relative_to(root.resolve()) and not out.resolve().is_relative_to(
            (root / "out").resolve()):
        raise ValueError(f"{out} is inside the repository {root}: give a folder outside it "
                         f"(or under out/, which git ignores)")
    handed = contents(root)
    found = leaks(handed, root)
    if found:
        raise ValueError(f"nothing written: {found[0]}" + (f" (and {len(found) - 1} more)"
                                                           if len(found) > 1 else ""))
    out.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{out.name}.", dir=out.parent))
    try:
        for name, data in handed.items():
            target = staging / name
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
            if os.access(root / name, os.X_OK) and (root / name).is_file():
                target.chmod(0o755)                     # .ci/run, scripts
        if out.exists():
            out.rmdir()                                 # empty: checked above
        staging.replace(out)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return sorted(handed)


def main(argv: list[str] | None = None) -> int:
    """``skxfem handout DIR``: 0 when written, 2 (one line on stderr) when not."""
    parser = argparse.ArgumentParser(
        prog="skxfem handout",
        description="Write the course as a student gets it into DIR: the repository "
                    "without exercises/solutions/ and the instructors' tests, every "
                    "exercise.py its untouched stub.")
    parser.add_argument("out", type=Path, metavar="DIR",
                        help="a new (or empty) folder, outside the repository or under out/")
    args = parser.parse_args(argv)
    try:
        written = write(args.out)
    except (OSError, ValueError) as error:
        print(f"skxfem handout: error: {' '.join(str(error).split())}", file=sys.stderr)
        return 2
    print(f"skxfem handout: {len(written)} files -> {args.out} (no exercises/solutions/; "
          f"every exercise.py its stub). Next: cd {args.out} && git init && git add . && "
          f"git commit -m 'the course', then publish it to the students")
    return 0


if __name__ == "__main__":
    sys.exit(main())
