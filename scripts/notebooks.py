"""The book's chapters as standalone Jupyter notebooks (.ipynb), for a course to hand out.

    python scripts/notebooks.py OUT               # `make notebooks`: OUT/NAME.ipynb per chapter
    python scripts/notebooks.py --check HTML      # the built book offers each one for download

A chapter is a page of ``book/_toc.yml`` written as a MyST notebook (its front matter
has a kernelspec).  Its notebook is the jupytext conversion of the page, without
outputs and without jupytext's pairing metadata, after one cell that says where it
comes from; it runs anywhere skxfem is installed (no chapter reads a file by a path
relative to the book).  ``tests/test_notebooks.py`` executes them all with nbclient.

This file is also a Sphinx extension of the book (``_config.yml``,
``sphinx.local_extensions``): each chapter's download button offers the same
notebook, as ``_sources/NAME.ipynb`` next to the page's Markdown source.
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

import jupytext
import nbformat

BOOK = Path(__file__).resolve().parents[1] / "book"


def chapters(book: Path = BOOK) -> list[Path]:
    """The pages of the book's table of contents that are notebooks, in its order."""
    toc = (book / "_toc.yml").read_text(encoding="utf-8")
    pages = [book / f"{name}.md" for name in re.findall(r"^\s*-?\s*(?:root|file):\s*(\S+)",
                                                        toc, flags=re.M)]
    return [p for p in pages if p.is_file() and "kernelspec" in jupytext.read(p).metadata]


def notebook(page: Path) -> nbformat.NotebookNode:
    """The standalone notebook of one chapter (no outputs, stable cell ids)."""
    nb = jupytext.read(page)
    title = next((c.source.splitlines()[0].lstrip("# ") for c in nb.cells
                  if c.cell_type == "markdown" and c.source.startswith("# ")), page.stem)
    nb.cells.insert(0, nbformat.v4.new_markdown_cell(
        f"*The chapter \"{title}\" of the skxfem book, as a notebook. It needs skxfem "
        f"installed: in a clone of the repository, `make install` (the book's Getting "
        f"started), then open this notebook with the kernel of `.venv`.*"))
    for i, cell in enumerate(nb.cells):
        cell.id = f"{page.stem}-{i}"
        if cell.cell_type == "code":
            cell.outputs, cell.execution_count = [], None
    nb.metadata = nbformat.from_dict({"kernelspec": nb.metadata["kernelspec"],
                                      "language_info": {"name": "python"}})
    nbformat.validate(nb)
    return nb


def write(out: Path, book: Path = BOOK) -> list[Path]:
    """Write every chapter's notebook into ``out``; the paths written."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for page in chapters(book):
        path = out / f"{page.stem}.ipynb"
        nbformat.write(notebook(page), path)
        written.append(path)
    return written


def check(html: Path, book: Path = BOOK) -> list[str]:
    """The chapters whose built page does not offer its notebook for download."""
    problems = []
    for page in chapters(book):
        built, offered = html / f"{page.stem}.html", html / "_sources" / f"{page.stem}.ipynb"
        if not built.is_file():
            problems.append(f"{built} is missing (build the book first)")
        elif f"_sources/{page.stem}.ipynb" not in built.read_text(encoding="utf-8"):
            problems.append(f"{built.name} has no download button for {offered.name}")
        elif not offered.is_file() or (nbformat.reads(offered.read_text(encoding="utf-8"), 4)
                                       != nbformat.reads(nbformat.writes(notebook(page)), 4)):
            problems.append(f"{offered} is not the notebook of {page.name}")
    return problems


def _offer_notebook(app, pagename, templatename, context, doctree):
    """html-page-context: write the chapter's notebook where the download button finds it."""
    source = Path(app.env.doc2path(pagename))
    if source.suffix != ".md" or "kernelspec" not in app.env.metadata.get(pagename, {}):
        return
    target = Path(app.outdir) / "_sources" / f"{pagename}.ipynb"
    target.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(notebook(source), target)
    context["ipynb_source"] = f"{pagename}.ipynb"


def setup(app):
    # before sphinx-book-theme's header buttons (priority 501), which read ipynb_source
    app.connect("html-page-context", _offer_notebook, priority=500)
    return {"parallel_read_safe": True, "parallel_write_safe": True}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", help="the folder to write the notebooks into (or, with "
                                    "--check, the built book's HTML folder)")
    parser.add_argument("--check", action="store_true",
                        help="check that the built book offers every chapter's notebook")
    args = parser.parse_args(argv)
    if args.check:
        problems = check(Path(args.out))
        for problem in problems:
            print(f"notebooks: {problem}", file=sys.stderr)
        print(f"notebooks: {len(chapters())} chapters, "
              f"{'every one' if not problems else f'{len(problems)} not'} offered as .ipynb")
        return 1 if problems else 0
    for path in write(Path(args.out)):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
