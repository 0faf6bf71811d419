"""The graded exercises' functions, and what the book may show of them.

A student writes the functions of ``exercises/NN_name/exercise.py``: those stubs
are the one list of what is graded (:func:`graded`).  What *answers* an exercise
is read from its reference, ``exercises/solutions/NN_name/reference.py``
(:func:`answers`): the reference's functions of those names (its own code, or the
library function it re-exports), the library functions named in its
``LIBRARY_ANSWERS`` (the same computation under another contract), and every
library or reference function that these call, however deep.

The book never prints the code of an answer.  :func:`listing` gives a function's
contract, its signature and docstring with the body elided; in the instructors'
build (``SKXFEM_SOLUTIONS`` set: ``make book-instructor``) it gives the source,
and :func:`show_reference` adds the reference with the library code it uses.
:func:`check_book` reads a built book and lists every page that shows an answer
(the students' book) or every answer that no page shows (the instructors' book);
``make book`` and ``make book-instructor`` run it after the build::

    python -m skxfem.app.graded book/_build/html                 # students: none shown
    python -m skxfem.app.graded --instructor INSTRUCTORS_HTML    # instructors: all shown
"""
from __future__ import annotations

import argparse
import ast
import html
import importlib
import importlib.util
import inspect
import json
import math
import os
import re
import sys
import textwrap
import types
from collections.abc import Callable
from pathlib import Path

__all__ = ["INSTRUCTORS", "exercises_folder", "graded", "answers", "code_lines", "contract",
           "listing", "show_reference", "check_book", "main"]

INSTRUCTORS = "SKXFEM_SOLUTIONS"   # set (non-empty) in the environment: the instructors' book
SHORTEST = 16                      # code lines shorter than this are too common to count


def exercises_folder(root: str | Path | None = None) -> Path:
    """The ``exercises`` folder: ``root``, or the one next to the package in a clone.

    >>> exercises_folder().name
    'exercises'
    """
    folder = Path(root) if root is not None else Path(__file__).resolve().parents[2] / "exercises"
    if not folder.is_dir():
        raise FileNotFoundError(
            f"no exercises folder at {folder}: the exercises come with a clone of the "
            f"repository (see the book's Getting started), not with an installed package")
    return folder


def graded(root: str | Path | None = None) -> dict[str, tuple[str, ...]]:
    """The graded functions: exercise folder name -> the functions its stub asks for.

    Read from the stubs themselves (the public top-level ``def`` of each
    ``NN_name/exercise.py``), so the list cannot drift from what students write.

    >>> graded()["01_levelset"]
    ('plane', 'circle', 'sphere')
    """
    folder = exercises_folder(root)
    found = {}
    for stub in sorted(folder.glob("*/exercise.py")):
        tree = ast.parse(stub.read_text(encoding="utf-8"), filename=str(stub))
        found[stub.parent.name] = tuple(node.name for node in tree.body
                                        if isinstance(node, ast.FunctionDef)
                                        and not node.name.startswith("_"))
    if not found:
        raise FileNotFoundError(f"no exercise stub (NN_name/exercise.py) under {folder}")
    return found


def _reference(exercise: str, folder: Path) -> types.ModuleType:
    path = folder / "solutions" / exercise / "reference.py"
    if not path.is_file():
        raise FileNotFoundError(f"exercise {exercise} has no reference solution at {path}")
    spec = importlib.util.spec_from_file_location(f"skxfem_reference_{exercise}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _resolve(dotted: str, where: Path) -> Callable:
    module, _, name = dotted.rpartition(".")
    try:
        found = getattr(importlib.import_module(module), name)
    except (ImportError, AttributeError, ValueError):
        raise ValueError(f"{where}: LIBRARY_ANSWERS names {dotted!r}, which is no function "
                         f"of the library (a renamed function? update the list)") from None
    if not inspect.isfunction(found):
        raise ValueError(f"{where}: LIBRARY_ANSWERS names {dotted!r}, which is not a function")
    return found


def _called(func: Callable, own: set[str]) -> list[Callable]:
    """The library (or reference) functions whose names ``func``'s code looks up."""
    names, stack = set(), [func.__code__]
    while stack:
        code = stack.pop()
        names |= set(code.co_names)
        stack += [c for c in code.co_consts if isinstance(c, types.CodeType)]
    found = (func.__globals__.get(n) for n in names)
    return [f for f in found if inspect.isfunction(f)
            and (f.__module__.startswith("skxfem.") or f.__module__ in own)]


def _name(func: Callable) -> str:
    module = func.__module__
    if module.startswith("skxfem_reference_"):
        return f"solutions/{module.removeprefix('skxfem_reference_')}/reference.py:" \
               f"{func.__qualname__}"
    return f"{module}.{func.__qualname__}"


def answers(exercise: str, root: str | Path | None = None) -> dict[str, Callable]:
    """The functions whose code answers ``exercise``, by name (see the module notes).

    >>> sorted(answers("07_contact"))[:2]
    ['skxfem.contact.laws.ball_projection', 'skxfem.contact.laws.indicator']
    """
    folder = exercises_folder(root)
    asked = graded(folder).get(exercise)
    if asked is None:
        raise ValueError(f"no exercise {exercise!r} in {folder}; the exercises are "
                         f"{', '.join(graded(folder))}")
    reference = _reference(exercise, folder)
    where = folder / "solutions" / exercise / "reference.py"
    missing = [n for n in asked if not inspect.isfunction(getattr(reference, n, None))]
    if missing:
        raise ValueError(f"{where} does not define {', '.join(missing)}, which the stub asks for")
    todo = [getattr(reference, n) for n in asked]
    todo += [_resolve(d, where) for d in getattr(reference, "LIBRARY_ANSWERS", ())]
    found: dict[str, Callable] = {}
    while todo:
        func = todo.pop()
        if _name(func) not in found:
            found[_name(func)] = func
            todo += _called(func, {reference.__name__})
    return dict(sorted(found.items()))


def _definition(func: Callable) -> tuple[list[str], ast.FunctionDef]:
    lines = textwrap.dedent(inspect.getsource(func)).splitlines()
    node = ast.parse("\n".join(lines)).body[0]
    return lines, node


def _docstring_end(node: ast.FunctionDef) -> int:
    """The line (1-based) after which the body's code starts."""
    first = node.body[0]
    if isinstance(first, ast.Expr) and isinstance(getattr(first, "value", None), ast.Constant) \
            and isinstance(first.value.value, str):
        return first.end_lineno
    return first.lineno - 1


def code_lines(func: Callable) -> tuple[str, ...]:
    """The lines of ``func``'s body that identify its code: stripped, without the
    docstring, comments and lines shorter than ``SHORTEST`` characters.

    >>> from skxfem.fem.simplex import edge_point
    >>> code_lines(edge_point)
    ('t = pa / (pa - pb)', 'return xa + t[..., None] * (xb - xa)')
    """
    lines, node = _definition(func)
    body = lines[_docstring_end(node):node.end_lineno]
    stripped = (line.strip() for line in body)
    return tuple(dict.fromkeys(s for s in stripped
                               if len(s) >= SHORTEST and not s.startswith("#")))


def contract(func: Callable, note: str = "") -> str:
    """``func``'s signature and docstring, its body elided (``...``, then ``note``).

    >>> from skxfem.fem.simplex import edge_point
    >>> print(contract(edge_point, "# exercise 02"))
    def edge_point(xa: np.ndarray, xb: np.ndarray, pa: np.ndarray, pb: np.ndarray) -> np.ndarray:
        \"\"\"The zero of the linear interpolant of ψ on the segment [xa, xb].
    <BLANKLINE>
        ``xa, xb`` have shape ``(..., dim)``, ``pa, pb`` shape ``(...)`` with pa·pb < 0.
        \"\"\"
        ...   # exercise 02
    """
    lines, node = _definition(func)
    indent = re.match(r"\s*", lines[node.body[0].lineno - 1]).group()
    return "\n".join(lines[:_docstring_end(node)] + [f"{indent}...{'   ' if note else ''}{note}"])


def _exercise_of(func: Callable) -> str | None:
    try:
        folder = exercises_folder()
        return next((e for e in graded(folder) if _name(func) in answers(e, folder)), None)
    except (FileNotFoundError, ValueError):
        return None


def listing(func: Callable, environ=os.environ) -> str:
    """What the book prints of ``func``, a function a graded exercise answers.

    Its contract (:func:`contract`), naming the exercise; the whole source in the
    instructors' build (``SKXFEM_SOLUTIONS`` set in ``environ``).

    >>> from skxfem.levelset import plane
    >>> listing(plane, environ={}).splitlines()[-1]
    "    ...   # the body is exercise 01_levelset (the instructors' book shows it)"
    """
    if environ.get(INSTRUCTORS):
        return (f"# instructors' book: the code of a graded function\n"
                f"{textwrap.dedent(inspect.getsource(func)).rstrip()}")
    exercise = _exercise_of(func)
    note = (f"# the body is exercise {exercise} (the instructors' book shows it)" if exercise
            else "# the body is an exercise's answer")
    return contract(func, note)


class _Markdown(str):
    """Text that Jupyter renders as Markdown (no IPython import needed)."""

    def _repr_markdown_(self) -> str:
        return str(self)


def show_reference(exercise: str, root: str | Path | None = None,
                   environ=os.environ) -> _Markdown | None:
    """For the book: the reference solution of ``exercise``, for instructors only.

    None (the page shows nothing) unless ``SKXFEM_SOLUTIONS`` is set in
    ``environ``; then ``reference.py`` and the source of every library function
    among its :func:`answers`.

    >>> show_reference("01_levelset", environ={}) is None
    True
    >>> "def _ball" in show_reference("01_levelset", environ={INSTRUCTORS: "1"})
    True
    """
    if not environ.get(INSTRUCTORS):
        return None
    folder = exercises_folder(root)
    path = folder / "solutions" / exercise / "reference.py"
    parts = [f"**Reference solution** (`exercises/solutions/{exercise}/reference.py`, "
             f"instructors' book):\n\n```python\n"
             f"{path.read_text(encoding='utf-8').rstrip()}\n```\n"]
    library = {n: f for n, f in answers(exercise, folder).items() if n.startswith("skxfem.")}
    if library:
        parts.append("The library code among the answers:\n\n```python\n" + "\n\n\n".join(
            f"# {name}\n{textwrap.dedent(inspect.getsource(f)).rstrip()}"
            for name, f in library.items()) + "\n```\n")
    return _Markdown("\n".join(parts))


def _page_lines(path: Path) -> set[str]:
    """The stripped lines of the text a built page shows (HTML or notebook)."""
    text = path.read_text(encoding="utf-8", errors="replace")
    if path.suffix == ".ipynb":
        cells = json.loads(text).get("cells", [])
        pieces = []
        for cell in cells:
            pieces.append("".join(cell.get("source", "")))
            for out in cell.get("outputs", []):
                pieces.append("".join(out.get("text", "")))
                pieces += ["".join(v) for v in out.get("data", {}).values()
                           if isinstance(v, (str, list))]
        text = "\n".join(pieces)
    if path.suffix in (".html", ".ipynb"):
        text = html.unescape(re.sub(r"<[^>]*>", "", text))
    return {line.strip() for line in text.splitlines()}


def _shown(lines: tuple[str, ...], page: set[str]) -> bool:
    """Half of a function's code lines (at least one) on a page: its code is shown."""
    return sum(line in page for line in lines) >= max(1, math.ceil(len(lines) / 2))


def check_book(html_dir: str | Path, instructor: bool = False,
               root: str | Path | None = None) -> list[str]:
    """The problems of a built book: pages showing an answer, or, for the
    instructors' book, answers that no page shows.  Empty when all is right.

    Every ``.html``, ``.ipynb``, ``.md``, ``.txt`` and ``.py`` file of the output
    counts as a page (downloads and notebooks included).
    """
    html_dir = Path(html_dir)
    pages = sorted(p for p in html_dir.rglob("*")
                   if p.suffix in (".html", ".ipynb", ".md", ".txt", ".py") and p.is_file())
    if not any(p.suffix == ".html" for p in pages):
        raise FileNotFoundError(f"no built page (.html) under {html_dir}: build the book first")
    text = {p.relative_to(html_dir).as_posix(): _page_lines(p) for p in pages}
    folder = exercises_folder(root)
    problems = []
    for exercise in graded(folder):
        for name, func in answers(exercise, folder).items():
            lines = code_lines(func)
            if not lines:
                problems.append(f"{name} (exercise {exercise}) has no code line of "
                                f"{SHORTEST}+ characters: the check cannot see it")
                continue
            where = [page for page, seen in text.items() if _shown(lines, seen)]
            if instructor and not where:
                problems.append(f"no page shows the code of {name} (exercise {exercise}); "
                                f"the instructors' book shows every answer (show_reference)")
            elif not instructor and where:
                problems.append(f"{', '.join(where)} show(s) the code of {name}, an answer "
                                f"to exercise {exercise}: print skxfem.app.graded.listing(...) "
                                f"(its contract) instead")
    return problems


def main(argv: list[str] | None = None) -> int:
    """``python -m skxfem.app.graded BOOK_HTML [--instructor]``: 0 if right, 1 if not."""
    parser = argparse.ArgumentParser(
        prog="python -m skxfem.app.graded",
        description="Check a built book: no page shows the code of a graded function "
                    "(or, with --instructor, every one is shown).")
    parser.add_argument("html", help="the built book's HTML folder, e.g. book/_build/html")
    parser.add_argument("--instructor", action="store_true",
                        help="the instructors' book: every answer must be shown")
    args = parser.parse_args(argv)
    try:
        problems = check_book(args.html, args.instructor)
    except (FileNotFoundError, ValueError) as error:
        print(f"skxfem.app.graded: error: {error}", file=sys.stderr)
        return 2
    book = "instructors'" if args.instructor else "students'"
    for problem in problems:
        print(f"skxfem.app.graded: {problem}", file=sys.stderr)
    exercises = graded()
    count = sum(len(answers(e)) for e in exercises)
    print(f"skxfem.app.graded: the {book} book at {args.html}: " + (
        f"{len(problems)} problem(s)" if problems else
        f"{'all' if args.instructor else 'none'} of the {count} functions answering "
        f"the {len(exercises)} exercises shown"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
