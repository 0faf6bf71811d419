"""The grading switch: which implementation the exercise tests import.

    pytest exercises                        # your code, NN_name/exercise.py (the default)
    pytest exercises --impl=solution        # the reference solutions (instructors)
    pytest exercises --impl=wrong:NAME      # a known wrong solution (instructors' test data)

Every test file names its exercise's functions (``ASKED``) and the library modules that
already implement them (``LIBRARY``).  The fixture ``impl`` hands the tests the module to
grade.  A student file that imports one of those library modules gets, in place of each
asked function, one that fails with a message saying so: reusing the library's answer is
not solving the exercise (a README says where reuse is allowed).

References live in ``solutions/NN_name/reference.py`` (some simply re-export the library,
whose function has the same contract); wrong solutions in
``solutions/NN_name/wrong_NAME.py``: each redefines one or two functions of the
reference and says in ``EXPECT`` what the grader's message must point at.

Failures are reported short: a function still raising ``NotImplementedError``
is one line (where it raised, and its message), not its whole docstring per
test; other failures show the failing lines only (``--tb=short``, unless you
ask for another ``--tb``).  A misspelt ``--impl`` is a usage error naming the
choices.
"""
from __future__ import annotations

import ast
import importlib.util
import os
import types
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
SOLUTIONS = HERE / "solutions"

# the student files and the solutions are imported by the fixture, never collected
# (the repository's --doctest-modules would otherwise run the stubs' examples)
collect_ignore_glob = ["*/exercise.py", "solutions/*"]


def pytest_addoption(parser):
    parser.addoption("--impl", default="student",
                     help="what to grade: student (NN_name/exercise.py), solution, "
                          "or wrong:NAME (solutions/NN_name/wrong_NAME.py)")


def _wrong_names() -> list[str]:
    return sorted({p.stem.removeprefix("wrong_") for p in SOLUTIONS.glob("*/wrong_*.py")})


def pytest_configure(config):
    config.addinivalue_line("markers", "points(n): the test is worth n points (default 1)")
    if config.option.tbstyle == "auto":      # not chosen on the command line
        config.option.tbstyle = "short"
    choice = config.getoption("impl")
    names = _wrong_names()
    wrong = choice.startswith("wrong:") and choice.removeprefix("wrong:") in names
    if choice not in ("student", "solution") and not wrong:
        raise pytest.UsageError(
            f"--impl must be student, solution or wrong:NAME (NAME one of: "
            f"{', '.join(names) or 'none here'}); got {choice!r}")


class Unwritten:
    """A function not written yet, reported in one line: where it raised, and its message.

    Stands in for pytest's report of the failure (``longrepr``), which would print the
    stub's whole docstring for every test that calls it.
    """

    def __init__(self, path: str, lineno: int, message: str):
        self.path, self.lineno, self.message = path, lineno, message

    @property
    def reprcrash(self):      # what --tb=line and the JUnit report read
        return self

    def __str__(self) -> str:
        return f"{self.path}:{self.lineno}: {self.message}"

    def toterminal(self, tw) -> None:
        tw.line(str(self))


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item, call):
    """A test that fails on a ``NotImplementedError`` is reported in one line."""
    report = yield
    excinfo = call.excinfo
    if report.failed and excinfo is not None and excinfo.errisinstance(NotImplementedError):
        entry = excinfo.traceback[-1]
        try:
            path = os.path.relpath(entry.path)
        except ValueError:    # another drive (Windows)
            path = str(entry.path)
        report.longrepr = Unwritten(path, entry.lineno + 1, excinfo.exconly().strip())
    return report


@pytest.fixture(autouse=True)
def _points(request):
    """Record each test's points for the score table (skxfem.app.grade reads them)."""
    marker = request.node.get_closest_marker("points")
    request.node.user_properties.append(("points", marker.args[0] if marker else 1))


def _load(path: Path, name: str, namespace: dict | None = None) -> types.ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    module.__dict__.update(namespace or {})
    spec.loader.exec_module(module)
    return module


def _public(module) -> dict:
    return {k: v for k, v in vars(module).items() if not k.startswith("__")}


def library_uses(source: str, library) -> list[str]:
    """Where ``source`` imports (or names) one of the modules in ``library``."""
    found = []

    def hit(name):
        return any(name == m or name.startswith(m + ".") for m in library)

    for node in ast.walk(ast.parse(source)):
        where = f"line {getattr(node, 'lineno', '?')}"
        if isinstance(node, ast.Import):
            found += [f"{where}: import {a.name}" for a in node.names if hit(a.name)]
        elif isinstance(node, ast.ImportFrom) and node.module:
            names = [f"{node.module}.{a.name}" for a in node.names]
            if hit(node.module) or any(hit(n) for n in names):
                found.append(f"{where}: from {node.module} import "
                             + ", ".join(a.name for a in node.names))
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
            if hit(f"{node.value.id}.{node.attr}"):
                found.append(f"{where}: {node.value.id}.{node.attr}")
        elif (isinstance(node, ast.Constant) and isinstance(node.value, str)
              and not any(c.isspace() for c in node.value) and hit(node.value)):
            found.append(f"{where}: {node.value!r}")
    return found


def _refusal(name: str, message: str):
    def refuse(*args, **kwargs):
        pytest.fail(message, pytrace=False)

    refuse.__name__ = name
    return refuse


def load_student(folder: Path, asked, library) -> types.ModuleType:
    """The student's module, with every asked function refused if it reuses the library."""
    path = folder / "exercise.py"
    module = _load(path, f"exercise_{folder.name}")
    uses = library_uses(path.read_text(encoding="utf-8"), library)
    uses += [f"{name} is {f.__module__}.{f.__qualname__}" for name in asked
             if (f := getattr(module, name, None)) is not None
             and any(getattr(f, "__module__", "").startswith(m) for m in library)]
    if uses:
        message = (f"exercise.py uses the library's own implementation of this exercise "
                   f"({'; '.join(uses)}). Write {', '.join(asked)} yourself: the README "
                   f"lists what you may import ({', '.join(library)} is not allowed here).")
        for name in asked:
            setattr(module, name, _refusal(name, message))
    return module


def load_reference(folder: Path) -> types.ModuleType:
    path = SOLUTIONS / folder.name / "reference.py"
    if not path.exists():
        pytest.fail(f"no reference solution at {path}: the solutions stay with the "
                    f"instructor; grade your own file with --impl=student", pytrace=False)
    return _load(path, f"reference_{folder.name}")


def load_wrong(folder: Path, name: str) -> types.ModuleType:
    path = SOLUTIONS / folder.name / f"wrong_{name}.py"
    if not path.exists():
        pytest.skip(f"{folder.name} has no wrong solution {name!r}")
    reference = load_reference(folder)
    return _load(path, f"wrong_{folder.name}_{name}", _public(reference))


@pytest.fixture(scope="module")
def impl(request):
    """The module under test, chosen by ``--impl``."""
    folder = Path(request.node.path).resolve().parent   # the file collected, not a cached module
    choice = request.config.getoption("impl")
    if choice == "student":
        return load_student(folder, request.module.ASKED, request.module.LIBRARY)
    if choice == "solution":
        return load_reference(folder)
    if choice.startswith("wrong:"):
        return load_wrong(folder, choice.removeprefix("wrong:"))
    raise pytest.UsageError(f"--impl must be student, solution or wrong:NAME; got {choice!r}")
