"""The graded exercises' functions, and what the book may show of them.

A student writes the functions of ``exercises/NN_name/exercise.py`` that the
exercise's tests call: their ``ASKED`` is the one list of what is graded
(:func:`graded`), read from the test file, which a student does not edit, so a
solved or half-solved ``exercise.py`` cannot change it.  What *answers* an exercise
is read from its reference, ``exercises/solutions/NN_name/reference.py``
(:func:`answers`): the reference's functions of those names (its own code, or the
library function it re-exports), the library functions named in its
``LIBRARY_ANSWERS`` (the same computation under another contract), and every
library or reference function that these call, however deep.  A student's
hand-out (``skxfem handout``) has no ``solutions/``: there the answers are the
library functions listed in ``exercises/library_answers.json``, which the
hand-out writes from the references (:func:`library_answers`); the library is
all a student's book could show, so the students' book check works the same.

The book never prints the code of an answer.  :func:`listing` gives a function's
contract, its signature and docstring with the body elided; in the instructors'
build (``SKXFEM_SOLUTIONS`` set: ``make book-instructor``) it gives the source,
and :func:`show_reference` adds the reference with the library code it uses;
every page of that build carries the banner :data:`BANNER` (the theme's
announcement, set when the build starts: :func:`instructor_banner`).

Each chapter offers its exercise's stub for download: the *pristine* stub
(:func:`stub`), never the student's file, which may hold a solution.  It is
``exercise.py`` while that is still a stub, else its newest committed version
that is one, else (no git) the contract the file holds (:func:`stub_of`: the
module docstring, the imports its examples use, each graded function's
signature and docstring, then ``raise NotImplementedError``).  The book build
(this module is a Sphinx extension of the book) writes them into ``book/_stubs/``
(:func:`write_stubs`), where the chapters' download links point.

:func:`check_book` reads a built book and lists every page that shows an answer
(the students' book) or every answer that no page shows (the instructors' book),
every shipped ``exercise.py`` that is not its pristine stub, and every page
without the instructors' banner (instructors' book) or with it (students');
``make book`` and ``make book-instructor`` run it after the build::

    python -m skxfem.app.graded book/_build/html                 # students: none shown
    python -m skxfem.app.graded --instructor INSTRUCTORS_HTML    # instructors: all shown
"""
from __future__ import annotations

import argparse
import ast
import doctest
import html
import importlib
import importlib.util
import inspect
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import textwrap
import types
from collections.abc import Callable
from pathlib import Path

__all__ = ["INSTRUCTORS", "STUBS", "BANNER", "LIBRARY_ANSWERS", "exercises_folder", "graded",
           "answers", "library_answers", "code_lines", "contract", "stub_of", "stub",
           "write_stubs", "listing", "show_reference", "instructor_banner", "check_book",
           "main"]

INSTRUCTORS = "SKXFEM_SOLUTIONS"   # set (non-empty) in the environment: the instructors' book
SHORTEST = 16                      # code lines shorter than this are too common to count
STUBS = "_stubs"                   # the book's build-only folder of pristine stubs (book/_stubs)
LIBRARY_ANSWERS = "library_answers.json"   # a hand-out's answers: exercises/library_answers.json
BANNER_TEXT = "Instructor edition"
BANNER = (f"<strong>{BANNER_TEXT}</strong>: this book shows the code of the graded "
          f"functions and the reference solutions. Do not hand it to students.")
"""The banner on every page of the instructors' book (sphinx-book-theme's announcement)."""


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


def _asked(folder: Path) -> tuple[str, ...]:
    """``ASKED`` of the exercise's test file: the functions its grader calls."""
    for test in sorted(folder.glob("test_*.py")):
        for node in ast.parse(test.read_text(encoding="utf-8"), filename=str(test)).body:
            if isinstance(node, ast.Assign) and any(
                    isinstance(t, ast.Name) and t.id == "ASKED" for t in node.targets):
                return tuple(ast.literal_eval(node.value))
    raise ValueError(f"no test_*.py in {folder} sets ASKED, the functions its grader calls")


def graded(root: str | Path | None = None) -> dict[str, tuple[str, ...]]:
    """The graded functions: exercise folder name -> the functions its tests ask for.

    One entry per ``NN_name/exercise.py``; the names are its test file's ``ASKED``
    (what the grader calls), not read from ``exercise.py``, so a student's helper
    functions never count as graded.  ``tests/test_graded.py`` checks that every
    stub defines exactly these.

    >>> graded()["01_levelset"]
    ('plane', 'circle', 'sphere')
    """
    folder = exercises_folder(root)
    found = {stub.parent.name: _asked(stub.parent)
             for stub in sorted(folder.glob("*/exercise.py"))}
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


def _handed_out(exercise: str, folder: Path) -> dict[str, Callable] | None:
    """A hand-out's answers to ``exercise`` (``library_answers.json``), or None if the
    reference is there (an instructor's clone) or the list is not (then the reference
    is asked for, and its absence reported)."""
    listed = folder / LIBRARY_ANSWERS
    if (folder / "solutions" / exercise / "reference.py").is_file() or not listed.is_file():
        return None
    try:
        names = json.loads(listed.read_text(encoding="utf-8"))["exercises"][exercise]
    except (ValueError, KeyError, TypeError):
        raise ValueError(f"{listed} lists no answers of {exercise}: make the hand-out again "
                         f"(skxfem handout)") from None
    return {name: _resolve(name, listed) for name in names}


def answers(exercise: str, root: str | Path | None = None) -> dict[str, Callable]:
    """The functions whose code answers ``exercise``, by name (see the module notes).

    In a hand-out (no ``solutions/``, a ``library_answers.json``) the library ones only.

    >>> sorted(answers("07_contact"))[:2]
    ['skxfem.contact.laws.ball_projection', 'skxfem.contact.laws.indicator']
    """
    folder = exercises_folder(root)
    asked = graded(folder).get(exercise)
    if asked is None:
        raise ValueError(f"no exercise {exercise!r} in {folder}; the exercises are "
                         f"{', '.join(graded(folder))}")
    handed_out = _handed_out(exercise, folder)
    if handed_out is not None:
        return dict(sorted(handed_out.items()))
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


def library_answers(root: str | Path | None = None) -> dict:
    """What a hand-out's ``library_answers.json`` holds: for each exercise, the names
    of the library functions among its :func:`answers` (no code, and nothing of the
    references), with a note saying what the file is for.

    >>> "skxfem.levelset.plane" in library_answers()["exercises"]["01_levelset"]
    True
    """
    folder = exercises_folder(root)
    return {"note": "The library functions whose code answers each graded exercise: the "
                    "students' book must not show them (python -m skxfem.app.graded). "
                    "Written by skxfem handout from the reference solutions; do not edit.",
            "exercises": {e: [n for n in answers(e, folder) if n.startswith("skxfem.")]
                          for e in graded(folder)}}


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
    def edge_point(xa: np.ndarray, xb: np.ndarray, pa: np.ndarray,
                   pb: np.ndarray) -> np.ndarray:
        \"\"\"The zero of the linear interpolant of ψ on the segment [xa, xb].
    <BLANKLINE>
        ``xa, xb`` have shape ``(..., dim)``, ``pa, pb`` shape ``(...)`` with pa·pb < 0.
        \"\"\"
        ...   # exercise 02
    """
    lines, node = _definition(func)
    indent = re.match(r"\s*", lines[node.body[0].lineno - 1]).group()
    return "\n".join(lines[:_docstring_end(node)] + [f"{indent}...{'   ' if note else ''}{note}"])


def _names_used(code: str) -> set[str]:
    """The names a piece of code reads (none if it does not parse)."""
    try:
        tree = ast.parse(code)
    except SyntaxError:
        return set()
    return {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}


def _contract_names(docstrings: list[str], functions: list[ast.FunctionDef]) -> set[str]:
    """The names the contract needs: those its docstrings' examples and the
    graded functions' signatures use."""
    used = set()
    for doc in docstrings:
        for example in doctest.DocTestParser().get_examples(doc):
            used |= _names_used(example.source)
    for node in functions:
        parts = [node.args, *node.decorator_list] + ([node.returns] if node.returns else [])
        used |= {n.id for part in parts for n in ast.walk(part) if isinstance(n, ast.Name)}
    return used


def stub_of(source: str, exercise: str, asked: tuple[str, ...],
            where: str = "exercise.py") -> str:
    r"""The stub form of an ``exercise.py`` text: its contract, every body unwritten.

    The module docstring; the top-level imports whose names the contract uses
    (its examples, the signatures); then each function of ``asked``, in that
    order, as its signature and docstring followed by ``raise
    NotImplementedError("NAME: not written yet (exercise NN, see README.md)")``.
    Bodies, helpers, other imports and module code are left out: a file whose
    bodies a student wrote gives the same text as the untouched stub, and every
    committed stub is its own stub form (``tests/test_book_stubs.py``).

    >>> print(stub_of("import os\ndef f(x):\n    'F.'\n    return os.sep + x\n",
    ...               "09_x", ("f",)))
    def f(x):
        'F.'
        raise NotImplementedError("f: not written yet (exercise 09, see README.md)")
    <BLANKLINE>
    """
    tree = ast.parse(source, filename=where)
    lines = source.splitlines()
    defined = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    missing = [n for n in asked if n not in defined]
    if missing:
        raise ValueError(f"{where} does not define {', '.join(missing)}, which its tests "
                         f"ask for (ASKED)")
    functions = [defined[n] for n in asked]
    head = []
    module_doc = ast.get_docstring(tree, clean=False)
    if module_doc is not None:
        head = lines[tree.body[0].lineno - 1:tree.body[0].end_lineno]
    used = _contract_names([module_doc or ""] + [ast.get_docstring(f) or "" for f in functions],
                           functions)
    for node in tree.body:          # the first import of each name (a student's come later)
        bound = {a.asname or a.name.split(".")[0] for a in getattr(node, "names", ())}
        if isinstance(node, (ast.Import, ast.ImportFrom)) and bound & used:
            head += lines[node.lineno - 1:node.end_lineno]
            used -= bound
    number = exercise.split("_", 1)[0]
    parts = []
    for node in functions:
        start = min([node.lineno] + [d.lineno for d in node.decorator_list])
        indent = re.match(r"\s*", lines[node.body[0].lineno - 1]).group()
        parts.append("\n".join(lines[start - 1:_docstring_end(node)] + [
            f'{indent}raise NotImplementedError("{node.name}: not written yet '
            f'(exercise {number}, see README.md)")']))
    return "\n\n\n".join(["\n".join(head)] * bool(head) + parts) + "\n"


def _committed_stub(path: Path, exercise: str, asked: tuple[str, ...]) -> str | None:
    """The newest committed version of ``path`` that is a stub (its own stub form),
    or None: no git, no history (a hand-out), or only solved versions."""
    def git(*args):
        try:
            done = subprocess.run(["git", "-C", str(path.parent), *args], capture_output=True,
                                  text=True, encoding="utf-8", timeout=60)
        except (OSError, subprocess.SubprocessError):
            return None
        return done.stdout if done.returncode == 0 else None

    for commit in (git("log", "--format=%H", "--", path.name) or "").split():
        text = git("show", f"{commit}:./{path.name}")
        try:
            if text is not None and stub_of(text, exercise, asked) == text:
                return text
        except (SyntaxError, ValueError):    # an old or broken version: look further back
            continue
    return None


def stub(exercise: str, root: str | Path | None = None) -> str:
    """The pristine stub of ``exercise``: what the book offers for download.

    Never the student's work, and the same text however much of
    ``NN_name/exercise.py`` a student wrote.  Taken from the first of:

    1. ``exercise.py`` itself, if it is a stub (its own :func:`stub_of` form:
       untouched, or a stub an instructor is editing);
    2. the newest committed version of it that is a stub, if git and the history
       are there (a student who replaced the whole file, docstrings included, or
       committed a solution);
    3. the stub form of ``exercise.py`` (a hand-out without git): the contract as
       the file holds it, its bodies, helpers and extra imports left out; only an
       edit of the contract itself (a docstring, a signature) would show.

    >>> print(stub("05_lbb").splitlines()[-1].strip())
    raise NotImplementedError("unseen_multipliers: not written yet (exercise 05, see README.md)")
    """
    folder = exercises_folder(root)
    asked = graded(folder).get(exercise)
    if asked is None:
        raise ValueError(f"no exercise {exercise!r} in {folder}; the exercises are "
                         f"{', '.join(graded(folder))}")
    path = folder / exercise / "exercise.py"
    source = path.read_text(encoding="utf-8")
    try:
        form = stub_of(source, exercise, asked, str(path))
    except (SyntaxError, ValueError):   # half written, a function renamed: try the history
        form = None
    if form == source:
        return source
    committed = _committed_stub(path, exercise, asked)
    if committed is not None:
        return committed
    if form is None:
        stub_of(source, exercise, asked, str(path))      # raises: says what is wrong
    return form


def write_stubs(out: str | Path, root: str | Path | None = None) -> list[Path]:
    """Write every exercise's pristine stub (:func:`stub`) to ``out/NN_name/exercise.py``.

    A file already holding the stub is left as it is; the others are replaced
    whole (written beside, then renamed), so a reader never sees half a file.
    Returns the paths of all the stubs.
    """
    out, folder = Path(out), exercises_folder(root)
    written = []
    for exercise in graded(folder):
        text, target = stub(exercise, folder), out / exercise / "exercise.py"
        target.parent.mkdir(parents=True, exist_ok=True)
        if not target.is_file() or target.read_text(encoding="utf-8") != text:
            with tempfile.NamedTemporaryFile("w", encoding="utf-8", dir=target.parent,
                                             suffix=".tmp", delete=False) as f:
                f.write(text)
            os.replace(f.name, target)
        written.append(target)
    return written


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


def instructor_banner(config, environ=os.environ) -> bool:
    """Put :data:`BANNER` on every page of the instructors' book: the html theme's
    ``announcement`` (sphinx-book-theme, pydata-sphinx-theme) when ``SKXFEM_SOLUTIONS``
    is set in ``environ``, as ``make book-instructor`` sets it; the students' book is
    left as it is.  Whether it was put there.

    >>> from types import SimpleNamespace
    >>> config = SimpleNamespace(html_theme_options={"home_page_in_navbar": True})
    >>> instructor_banner(config, environ={}), config.html_theme_options
    (False, {'home_page_in_navbar': True})
    >>> instructor_banner(config, environ={INSTRUCTORS: "1"})
    True
    >>> config.html_theme_options["announcement"].startswith("<strong>Instructor edition")
    True
    """
    if not environ.get(INSTRUCTORS):
        return False
    config.html_theme_options = {**(config.html_theme_options or {}), "announcement": BANNER}
    return True


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
    counts as a page (downloads and notebooks included); every ``exercise.py`` in it
    must be an exercise's pristine stub (:func:`stub`), as the chapters offer it.
    """
    html_dir = Path(html_dir)
    pages = sorted(p for p in html_dir.rglob("*")
                   if p.suffix in (".html", ".ipynb", ".md", ".txt", ".py") and p.is_file())
    if not any(p.suffix == ".html" for p in pages):
        raise FileNotFoundError(f"no built page (.html) under {html_dir}: build the book first")
    text = {p.relative_to(html_dir).as_posix(): _page_lines(p) for p in pages}
    folder = exercises_folder(root)
    problems = []
    built = [p for p in pages if p.suffix == ".html"     # not _static/, _downloads/ ...
             and not any(part.startswith("_") for part in p.relative_to(html_dir).parts)
             and not _redirect(p)]
    bannered = [instructor == (BANNER in html.unescape(p.read_text(
        encoding="utf-8", errors="replace"))) for p in built]
    if not all(bannered):
        problems.append(f"{bannered.count(False)} of the {len(bannered)} pages "
                        + (f"lack the instructors' banner ({BANNER_TEXT!r}): build with "
                           "SKXFEM_SOLUTIONS set (make book-instructor)" if instructor else
                           f"carry the instructors' banner ({BANNER_TEXT!r}): this is the "
                           f"instructors' book, built with SKXFEM_SOLUTIONS set"))
    stubs = {stub(e, folder) for e in graded(folder)}
    for path in (p for p in pages if p.name == "exercise.py"):
        if path.read_text(encoding="utf-8", errors="replace") not in stubs:
            problems.append(f"{path.relative_to(html_dir).as_posix()} is no exercise's pristine "
                            f"stub (a student's file?): a chapter offers "
                            f"{STUBS}/NN_name/exercise.py (skxfem.app.graded.stub)")
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


def _write_book_stubs(app) -> None:
    """builder-inited: the pristine stubs into ``book/_stubs``, before any page is read
    (a chapter's ``{download}`` of ``_stubs/NN_name/exercise.py`` needs the file)."""
    book = Path(app.srcdir)
    write_stubs(book / STUBS, book.parent / "exercises")


def _redirect(page: Path) -> bool:
    """Whether ``page`` only sends the browser on (Jupyter Book's ``index.html``: a
    ``<meta http-equiv="Refresh">`` and nothing else), a page without a banner.

    >>> import tempfile
    >>> p = Path(tempfile.mkdtemp()) / "index.html"
    >>> _ = p.write_text('<meta http-equiv="Refresh" content="0; url=intro.html" />')
    >>> _redirect(p)
    True
    """
    text = page.read_text(encoding="utf-8", errors="replace")
    return len(text) < 1000 and 'http-equiv="refresh"' in text.lower()


def _banner(app, config) -> None:
    """config-inited: the instructors' banner, when SKXFEM_SOLUTIONS is set."""
    instructor_banner(config)


def setup(app):
    """The book's Sphinx extension (``_config.yml``, ``sphinx.extra_extensions``)."""
    app.connect("config-inited", _banner)
    app.connect("builder-inited", _write_book_stubs)
    return {"parallel_read_safe": True, "parallel_write_safe": True}


if __name__ == "__main__":
    sys.exit(main())
