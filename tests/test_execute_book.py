"""scripts/execute_book.py: the chapters executed before the build, into its cache.

The instructors' book reuses the students' outputs of a chapter only where they
cannot depend on ``SKXFEM_SOLUTIONS``: these tests check the premise (only
``skxfem.app.graded`` reads the variable), the rule on the book's chapters, and on
a small book of two chapters that the one reading it runs again and the other not.
"""
import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest
from jupyter_cache import get_cache
from jupyter_cache.base import CacheBundleIn

ROOT = Path(__file__).resolve().parents[1]


def load(name: str):
    spec = importlib.util.spec_from_file_location(f"book_{name}", ROOT / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


execute_book = load("execute_book")
notebooks = load("notebooks")


def test_only_graded_reads_the_solutions_variable():
    """The premise of the reuse: in the library and the exercises, only
    skxfem.app.graded names the variable (or INSTRUCTORS, its name), and the
    functions of it that read it are called nowhere else."""
    files = [*(ROOT / "skxfem").rglob("*.py"), *(ROOT / "exercises").rglob("*.py")]
    naming = {p.relative_to(ROOT).as_posix() for p in files
              if re.search(r"SKXFEM_SOLUTIONS|\bINSTRUCTORS\b", p.read_text("utf-8"))}
    assert naming == {"skxfem/app/graded.py"}
    calling = {p.relative_to(ROOT).as_posix() for p in files
               if re.search(r"\b(listing|show_reference|instructor_banner)\s*\(|import .*\b("
                            r"listing|show_reference|instructor_banner)\b", p.read_text("utf-8"))}
    assert calling == {"skxfem/app/graded.py"}


def test_every_chapter_that_shows_a_solution_runs_again():
    pages = execute_book.chapters()
    assert [p.stem for p in pages] == [p.stem for p in notebooks.chapters()]
    again = {p.stem for p in pages if execute_book.reads_solutions(execute_book.read(p))}
    showing = {p.stem for p in pages
               if re.search(r"listing\(|show_reference\(", p.read_text("utf-8"))}
    assert len(showing) >= 8 and showing <= again
    assert again != {p.stem for p in pages}         # some are reused, or this saves nothing


@pytest.mark.parametrize("code", [
    "import os\nprint(os.environ.get('X'))", "from os import getenv", "!ls",
    "%%bash\necho $SKXFEM_SOLUTIONS", "import subprocess", "from skxfem.app import graded",
    "import skxfem.app.graded as g", "print(listing(f))", "importlib.import_module(name)"])
def test_what_may_show_a_solution(code):
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(code)])
    assert execute_book.reads_solutions(nb)


PAGE = """---
kernelspec: {{display_name: Python 3, language: python, name: python3}}
---

# {name}

```{{code-cell}} ipython3
{code}
```
"""


def small_book(folder: Path) -> Path:
    book = folder / "book"
    book.mkdir()
    (book / "_toc.yml").write_text("format: jb-book\nroot: intro\nchapters:\n"
                                   "- file: plain\n- file: shows\n")
    (book / "_config.yml").write_text("execute:\n  timeout: 60\n")
    (book / "intro.md").write_text("# Intro\n")
    (book / "plain.md").write_text(PAGE.format(
        name="plain", code="import time\nprint(time.perf_counter_ns())"))
    (book / "shows.md").write_text(PAGE.format(
        name="shows", code="import os\nprint(os.environ.get('SKXFEM_SOLUTIONS', 'students'))"))
    return book


def printed(cache, page: Path) -> str:
    nb = cache.get_cache_bundle(cache.match_cache_notebook(execute_book.read(page)).pk).nb
    return "".join(o.get("text", "") for o in nb.cells[0].outputs)


def run(*args: str, solutions: bool = False) -> subprocess.CompletedProcess:
    """The script as the Makefile runs it (its pool pickles what it runs: a process)."""
    env = {k: v for k, v in os.environ.items() if k != "SKXFEM_SOLUTIONS"}
    if solutions:
        env["SKXFEM_SOLUTIONS"] = "1"
    return subprocess.run([sys.executable, str(ROOT / "scripts" / "execute_book.py"), *args],
                          env=env, capture_output=True, text=True, timeout=600)


def test_the_instructors_cache_reuses_only_what_cannot_show_a_solution(tmp_path):
    book = small_book(tmp_path)
    students, instructors = tmp_path / "students", tmp_path / "instructors"
    stale = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("print('old')")],
                                     metadata=execute_book.read(book / "plain.md").metadata)
    get_cache(str(students)).cache_notebook_bundle(
        CacheBundleIn(stale, str(book / "plain.md")), check_validity=False)
    done = run(str(students), "--book", str(book))
    assert done.returncode == 0, done.stderr
    done = run(str(instructors), "--book", str(book), "--jobs", "1", "--reuse", str(students),
               solutions=True)
    assert done.returncode == 0, done.stderr
    assert re.search(r"plain +from ", done.stdout), done.stdout
    assert "1 of 1 chapters executed" in done.stdout
    s, i = get_cache(str(students)), get_cache(str(instructors))
    assert printed(s, book / "shows.md") == "students\n"
    assert printed(i, book / "shows.md") == "1\n"                 # executed again
    assert printed(i, book / "plain.md") == printed(s, book / "plain.md")   # the same run
    assert len(s.list_cache_records()) == 2      # emptied first: the stale run is gone


def test_a_failing_chapter_fails_the_run(tmp_path):
    book = small_book(tmp_path)
    (book / "plain.md").write_text(PAGE.format(name="plain", code="1 / 0"))
    done = run(str(tmp_path / "cache"), "--book", str(book))
    assert done.returncode == 1 and "plain.md" in done.stderr
    assert "ZeroDivisionError" in done.stderr


def test_bad_arguments_are_refused(tmp_path, capsys):
    with pytest.raises(SystemExit):
        execute_book.main([str(tmp_path / "c"), "--jobs", "0"])
    assert "--jobs must be a positive integer" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        execute_book.main([str(tmp_path / "c"), "--reuse", str(tmp_path)])
    assert "make book" in capsys.readouterr().err

