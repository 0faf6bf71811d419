"""Execute the book's chapters before the build, several at a time, into its cache.

    python scripts/execute_book.py CACHE [--jobs N]              # make book
    SKXFEM_SOLUTIONS=1 python scripts/execute_book.py CACHE --reuse STUDENTS_CACHE
                                                                 # make book-instructor

Jupyter Book executes the chapters one after the other while Sphinx reads them.
This script executes them first, ``N`` at a time (default: 2, the machine's
cores), each in its own kernel, the longest first (as the last run into ``CACHE``
or ``--reuse`` took), and stores the executed notebooks in a new
jupyter-cache at ``CACHE``; the build (``execute_notebooks: cache`` in
``book/_config.yml``) then takes every chapter's outputs from there.  A chapter
is executed exactly as the build would execute it: the notebook myst-nb's reader
makes of the page, its kernel, ``book/`` as working folder, the build's timeout
per cell, an error stops everything.  ``CACHE`` is emptied first, so every
chapter runs against the current library (a chapter the build does not find in
the cache, it executes itself).

``--reuse STUDENTS_CACHE`` (the instructors' book, built right after the
students' one by ``make test``): a chapter whose outputs cannot depend on
``SKXFEM_SOLUTIONS`` (:func:`reads_solutions` is False) takes its executed
notebook from the students' cache, if that cache holds one of the same code; every
other chapter is executed again.  The variable is read only by three functions of
``skxfem.app.graded`` (``listing``, ``show_reference``, ``instructor_banner``),
which no other module of the library or the exercises calls
(``tests/test_execute_book.py`` checks both), so a chapter that names neither
``graded`` nor these, imports nothing by a computed name, and neither reads the
environment nor starts a process prints the same in both books.  Reuse only a
students' cache built from the same library: ``make test`` builds the two books
one after the other.
"""
from __future__ import annotations

import argparse
import re
import shutil
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context
from pathlib import Path

import nbformat
import yaml
from jupyter_cache import get_cache
from jupyter_cache.base import CacheBundleIn
from jupyter_cache.executors.utils import single_nb_execution
from myst_nb.core.read import read_myst_markdown_notebook
from myst_parser.config.main import MdParserConfig

BOOK = Path(__file__).resolve().parents[1] / "book"

SOLUTIONS_MAY_SHOW = re.compile(
    r"\bgraded\b|\blisting\b|\bshow_reference\b|\binstructor_banner\b|SKXFEM_SOLUTIONS"
    r"|\bimport_module\b|__import__|\benviron\b|\bgetenv\b|\bsubprocess\b"
    r"|\bos\.system\b|\bos\.popen\b|\bos\.exec|\bos\.spawn|^\s*!|^\s*%%?(?:env|system|sx|"
    r"bash|sh|script|run)\b", flags=re.M)
"""What, in a code cell, may make its outputs depend on ``SKXFEM_SOLUTIONS``:
``skxfem.app.graded`` or one of the functions of it that read the variable, an
import by name, the environment, another process."""


def chapters(book: Path = BOOK) -> list[Path]:
    """The pages of the table of contents that the build executes (a MyST notebook:
    its front matter has a kernelspec), in the book's order."""
    toc = (book / "_toc.yml").read_text(encoding="utf-8")
    names = re.findall(r"^\s*-?\s*(?:root|file):\s*(\S+)", toc, flags=re.M)
    pages = [book / f"{name}.md" for name in names]
    return [p for p in pages if p.is_file() and "kernelspec" in read(p, book).metadata]


def settings(book: Path = BOOK) -> dict:
    """The book's ``_config.yml``."""
    return yaml.safe_load((book / "_config.yml").read_text(encoding="utf-8"))


def read(page: Path, book: Path = BOOK) -> nbformat.NotebookNode:
    """The notebook of ``page`` as the build reads it (myst-nb's reader, the book's
    MyST extensions): the cache knows a chapter by its code cells and kernel."""
    extensions = settings(book).get("parse", {}).get("myst_enable_extensions", [])
    config = MdParserConfig(enable_extensions=set(extensions))
    return read_myst_markdown_notebook(page.read_text(encoding="utf-8"), config=config,
                                       add_source_map=True, path=str(page))


def reads_solutions(nb: nbformat.NotebookNode) -> bool:
    """Whether a chapter's outputs may depend on ``SKXFEM_SOLUTIONS``: one of its code
    cells names ``skxfem.app.graded`` or its functions that read the variable, imports
    by a computed name, reads the environment or starts a process
    (:data:`SOLUTIONS_MAY_SHOW`).

    >>> reads_solutions(nbformat.v4.new_notebook(cells=[
    ...     nbformat.v4.new_code_cell("from skxfem.app.graded import listing")]))
    True
    >>> reads_solutions(nbformat.v4.new_notebook(cells=[
    ...     nbformat.v4.new_code_cell("from skxfem.solver import solve"),
    ...     nbformat.v4.new_markdown_cell("os.environ in a text cell runs nothing")]))
    False
    """
    return any(SOLUTIONS_MAY_SHOW.search(c.source) for c in nb.cells
               if c.cell_type == "code")


def seconds(cache: Path | None) -> dict[str, float]:
    """How long each chapter (by path) took in an earlier run into ``cache``: the
    longest run first, the pool ends sooner.  Empty if there is none."""
    if cache is None or not (cache / "global.db").is_file():
        return {}
    return {r.uri: float(r.data.get("execution_seconds", 0.0))
            for r in get_cache(str(cache)).list_cache_records()}


def execute(page: Path, timeout: int) -> tuple[nbformat.NotebookNode, float, str]:
    """Execute one chapter as the build would (in ``book/``); the executed notebook,
    its seconds and its error ('' if none)."""
    nb = read(page, page.parent)
    result = single_nb_execution(nb, cwd=str(page.parent), timeout=timeout,
                                 allow_errors=False, meta_override=True)
    return nb, result.time, result.exc_string or ("" if result.err is None
                                                  else repr(result.err))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python scripts/execute_book.py",
        description="Execute the book's chapters, several at a time, into the cache the "
                    "build reads (execute_notebooks: cache).")
    parser.add_argument("cache", type=Path,
                        help="the build's jupyter-cache, emptied first, e.g. "
                             "book/_build/.jupyter_cache")
    parser.add_argument("--jobs", type=int, default=2,
                        help="chapters executed at a time (default 2)")
    parser.add_argument("--reuse", type=Path, metavar="STUDENTS_CACHE",
                        help="take the chapters that cannot show a solution from this "
                             "students' cache, built from the same library")
    parser.add_argument("--book", type=Path, default=BOOK, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error(f"--jobs must be a positive integer, not {args.jobs}")
    if args.reuse is not None and not (args.reuse / "global.db").is_file():
        parser.error(f"--reuse {args.reuse}: no jupyter-cache there (build the students' "
                     f"book first: make book)")
    book = args.book.resolve()
    timeout = int(settings(book).get("execute", {}).get("timeout", 30))
    students = get_cache(str(args.reuse)) if args.reuse is not None else None
    took = {**seconds(args.cache), **seconds(args.reuse)}
    shutil.rmtree(args.cache, ignore_errors=True)
    cache = get_cache(str(args.cache))

    todo, start, pages = [], time.perf_counter(), chapters(book)
    for page in pages:
        nb = read(page, book)
        if students is not None and not reads_solutions(nb):
            try:
                record = students.match_cache_notebook(nb)
            except KeyError:          # its code changed since the students' build
                record = None
            if record is not None:
                bundle = students.get_cache_bundle(record.pk)
                cache.cache_notebook_bundle(
                    CacheBundleIn(bundle.nb, str(page), data=record.data),
                    check_validity=False, overwrite=True)
                print(f"execute_book: {page.stem:16} from {args.reuse}")
                continue
        todo.append(page)

    todo.sort(key=lambda page: -took.get(str(page), float("inf")))   # longest first
    failed = []
    with ProcessPoolExecutor(max_workers=args.jobs, mp_context=get_context("spawn")) as pool:
        runs = {page: pool.submit(execute, page, timeout) for page in todo}
        for page, run in runs.items():
            nb, took_now, error = run.result()
            if error:
                failed.append(f"{page.name}:\n{error}")
                continue
            cache.cache_notebook_bundle(
                CacheBundleIn(nb, str(page), data={"execution_seconds": took_now}),
                check_validity=False, overwrite=True)
            print(f"execute_book: {page.stem:16} {took_now:6.1f} s")
    for failure in failed:
        print(f"execute_book: executing {failure}", file=sys.stderr)
    print(f"execute_book: {len(todo) - len(failed)} of {len(todo)} chapters executed "
          f"({args.jobs} at a time) in {time.perf_counter() - start:.0f} s" +
          (f", the {len(pages) - len(todo)} others reused" if students else "") +
          f", into {args.cache}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
