"""The book offers each exercise's pristine stub, whatever a student wrote (issue 25).

A student who solves an exercise in ``exercises/NN_name/exercise.py`` and then runs
``make book`` must get the same book as before: the chapters offer
``book/_stubs/NN_name/exercise.py`` (written by ``skxfem.app.graded.write_stubs``
when the build starts), never the student's file, and the check of the built book
(``skxfem.app.graded.check_book``) passes.  Everything here works on a copy of the
exercises in a temporary folder; the repository is never changed.
"""
import ast
import inspect
import re
import shutil
import subprocess
import textwrap
from pathlib import Path

import pytest

from skxfem.app.graded import (
    _definition,
    _docstring_end,
    _reference,
    answers,
    check_book,
    code_lines,
    graded,
    stub,
    stub_of,
    write_stubs,
)

ROOT = Path(__file__).resolve().parents[1]
EXERCISES = ROOT / "exercises"
NAMES = list(graded())


def copy_exercises(tmp_path: Path) -> Path:
    """A copy of the exercises (stubs, tests, solutions) outside any git repository."""
    root = tmp_path / "exercises"
    shutil.copytree(EXERCISES, root, ignore=shutil.ignore_patterns("__pycache__"))
    return root


def solved(exercise: str, root: Path) -> str:
    """``exercise.py`` as a student leaves it after solving it: every graded body
    written (the reference's code, or the library code it re-exports), the
    helpers it calls appended, its imports added; docstrings kept."""
    text = (root / exercise / "exercise.py").read_text(encoding="utf-8")
    reference = _reference(exercise, root)
    asked = graded(root)[exercise]
    for name in asked:
        lines, node = _definition(getattr(reference, name))
        body = "\n".join(lines[_docstring_end(node):node.end_lineno])
        unwritten = next(line for line in text.splitlines()
                         if f'NotImplementedError("{name}: not written yet' in line)
        text = text.replace(unwritten, body)
    helpers = [f for f in answers(exercise, root).values() if f.__name__ not in asked]
    text += "".join(f"\n\n{textwrap.dedent(inspect.getsource(f))}" for f in helpers)
    source = (root / "solutions" / exercise / "reference.py").read_text(encoding="utf-8")
    imports = [ast.get_source_segment(source, n) for n in ast.parse(source).body
               if isinstance(n, ast.Import) or (isinstance(n, ast.ImportFrom)
                                                and not n.module.startswith("skxfem"))]
    given = next(line for line in text.splitlines() if line.startswith("import numpy as np"))
    return text.replace(given, "\n".join([given, *imports]), 1)


def holds_code(text: str, exercise: str, root: Path) -> list[str]:
    """The answers to ``exercise`` whose code (half its lines or more) ``text`` holds."""
    lines = {line.strip() for line in text.splitlines()}
    found = []
    for name, func in answers(exercise, root).items():
        code = code_lines(func)
        if sum(line in lines for line in code) >= max(1, (len(code) + 1) // 2):
            found.append(name)
    return found


def test_every_committed_stub_is_its_own_stub_form():
    """The committed stubs are exactly what the book ships (and the function that
    makes the shipped text changes nothing in them)."""
    for exercise in NAMES:
        text = (EXERCISES / exercise / "exercise.py").read_text(encoding="utf-8")
        assert stub_of(text, exercise, graded()[exercise]) == text, exercise
        assert stub(exercise) == text, exercise


@pytest.mark.parametrize("exercise", NAMES)
def test_a_solved_exercise_ships_its_pristine_stub(tmp_path, exercise):
    """Without git (a hand-out): the solution in exercise.py, the stub unchanged."""
    root = copy_exercises(tmp_path)
    pristine = (root / exercise / "exercise.py").read_text(encoding="utf-8")
    (root / exercise / "exercise.py").write_text(solved(exercise, root), encoding="utf-8")
    work = (root / exercise / "exercise.py").read_text(encoding="utf-8")
    assert holds_code(work, exercise, root), "the solved file holds the solution's code"
    assert graded(root)[exercise] == graded()[exercise]
    assert stub(exercise, root) == pristine
    assert holds_code(stub(exercise, root), exercise, root) == []
    written = write_stubs(tmp_path / "book" / "_stubs", root)
    assert [p.parent.name for p in written] == NAMES
    for path in written:
        assert path.read_text(encoding="utf-8") == (EXERCISES / path.parent.name
                                                    / "exercise.py").read_text(encoding="utf-8")


def test_a_students_helpers_and_imports_change_nothing(tmp_path):
    root = copy_exercises(tmp_path)
    path = root / "05_lbb" / "exercise.py"
    pristine = path.read_text(encoding="utf-8")
    path.write_text(pristine.replace("need it)\n", "need it)\nimport os\n")
                    + "\n\ndef helper(x):\n    return x\n\n\nTOL = 1e-12\n", encoding="utf-8")
    assert graded(root) == graded()                  # a public helper is not graded
    assert stub("05_lbb", root) == pristine


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_a_whole_file_replaced_and_committed_still_ships_the_stub(tmp_path):
    """With git: a student who copies a whole solution over exercise.py (its
    docstrings gone) and commits it gets the newest committed stub."""
    root = copy_exercises(tmp_path)

    def git(*args):
        subprocess.run(["git", "-C", str(root), *args], check=True, capture_output=True)

    git("init", "-q")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "--allow-empty", "-m", "0")
    git("add", ".")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "-m", "the course")
    for exercise in NAMES:
        shutil.copy(root / "solutions" / exercise / "reference.py",
                    root / exercise / "exercise.py")
    assert stub("05_lbb", root) == (EXERCISES / "05_lbb" / "exercise.py").read_text("utf-8")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "-am", "my solutions")
    for exercise in NAMES:
        assert stub(exercise, root) == (EXERCISES / exercise / "exercise.py").read_text("utf-8")


def test_the_check_wants_the_pristine_stubs(tmp_path):
    """check_book flags a shipped exercise.py that is not its exercise's stub."""
    root = copy_exercises(tmp_path)
    html = tmp_path / "html"
    (html / "_downloads" / "abc").mkdir(parents=True)
    (html / "index.html").write_text("<html><body>book</body></html>")
    shipped = html / "_downloads" / "abc" / "exercise.py"
    shutil.copy(root / "04_multipliers" / "exercise.py", shipped)
    assert check_book(html, root=root) == []
    shipped.write_text(shipped.read_text("utf-8").replace("Exercise 04", "Exercise 4"), "utf-8")
    problems = check_book(html, root=root)
    assert len(problems) == 1 and "_downloads/abc/exercise.py is no exercise's pristine stub" \
        in problems[0]


def build(book: Path) -> Path:
    """A Sphinx build of ``book`` (MyST pages, the book's extension); its HTML folder."""
    from sphinx.cmd.build import build_main
    html = book / "_build" / "html"
    status = build_main(["-q", "-W", "-b", "html", "-d", str(book / "_build" / ".doctrees"),
                         str(book), str(html)])
    assert status == 0, "the Sphinx build failed"
    return html


def test_the_build_ships_the_pristine_stubs_of_solved_exercises(tmp_path):
    """A real (small) Sphinx build, as the book's: its extension writes the stubs,
    each page offers one as the chapters do; every exercise solved beforehand.
    The built book passes the check and ships the pristine stubs only; a page
    offering the student's file, as the chapters did, fails it."""
    pytest.importorskip("myst_parser")
    root = copy_exercises(tmp_path)
    for exercise in NAMES:
        (root / exercise / "exercise.py").write_text(solved(exercise, root), encoding="utf-8")
    book = tmp_path / "book"
    book.mkdir()
    (book / "conf.py").write_text(
        'extensions = ["myst_parser", "skxfem.app.graded"]\n'
        'exclude_patterns = ["_build", "_stubs"]\nproject = "t"\n', encoding="utf-8")
    (book / "index.md").write_text("# Exercises\n\n" + "".join(
        f"{{download}}`exercises/{e}/exercise.py <_stubs/{e}/exercise.py>`\n\n" for e in NAMES),
        encoding="utf-8")
    html = build(book)
    shipped = sorted((html / "_downloads").rglob("exercise.py"))
    assert len(shipped) == len(NAMES)
    pristine = {(EXERCISES / e / "exercise.py").read_text(encoding="utf-8") for e in NAMES}
    assert {p.read_text(encoding="utf-8") for p in shipped} == pristine
    for path in shipped:
        for exercise in NAMES:
            assert holds_code(path.read_text(encoding="utf-8"), exercise, root) == []
    assert check_book(html, root=root) == []

    (book / "index.md").write_text("# Exercises\n\n{download}`a <../exercises/05_lbb/"
                                   "exercise.py>`\n", encoding="utf-8")
    shutil.rmtree(book / "_build")
    problems = check_book(build(book), root=root)
    assert any("pristine stub" in p for p in problems), problems
    assert any("show(s) the code of" in p and "05_lbb" in p for p in problems), problems


def test_the_repository_book_points_at_the_stubs():
    """Every chapter's download of an exercise file is its stub in _stubs/, a folder
    that git ignores and the book does not read as pages."""
    chapters = [p for p in (ROOT / "book").glob("*.md") if "## Graded exercise" in p.read_text()]
    assert len(chapters) == len(NAMES)
    for chapter in chapters:
        text = chapter.read_text(encoding="utf-8")
        offered = re.findall(r"<([^<>]*exercise\.py)>", text)
        name = re.search(r"_stubs/(\w+)/", offered[0]).group(1) if offered else None
        assert offered == [f"_stubs/{name}/exercise.py"] and name in NAMES, chapter.name
    config = (ROOT / "book" / "_config.yml").read_text(encoding="utf-8")
    assert "- skxfem.app.graded" in config and "_stubs," in config
    assert "book/_stubs/" in (ROOT / ".gitignore").read_text(encoding="utf-8").split()
