"""The book's chapters as standalone Jupyter notebooks (.ipynb), for a course to hand out.

    python scripts/notebooks.py OUT               # `make notebooks`: OUT/NAME.ipynb per chapter
    python scripts/notebooks.py --check HTML      # the built book offers each one for download

A chapter is a page of ``book/_toc.yml`` written as a MyST notebook (its front matter
has a kernelspec).  Its notebook is the jupytext conversion of the page, without
outputs and without jupytext's pairing metadata, after one cell that says where it
comes from; it runs anywhere skxfem is installed (no chapter reads a file by a path
relative to the book).  ``tests/test_notebooks.py`` executes them all with nbclient.

A notebook reads as the student opens it, in JupyterLab, say, from the clone's
``notebooks/`` folder (:func:`plain`): the Markdown the book's MyST adds is
turned into plain Markdown, an ``{include}`` into the text it includes (an
exercise's task), a ``{download}`` role into a link to the file in the clone (an
exercise's ``exercises/NN_name/exercise.py``, the one to edit), and a link to
another page into a link to its notebook (``NAME.ipynb``, beside it) or, for a
page without code, to its source (``../book/NAME.md``), and a folded
``{dropdown}`` into an HTML ``<details>`` block, the library source it shows (a
``{literalinclude}`` with ``:pyobject:``) as a Python code block.  Its kernel is
:data:`KERNEL`, the one ``make install`` registers (``skxfem``).

This file is also a Sphinx extension of the book (``_config.yml``,
``sphinx.local_extensions``): each chapter's download button offers the same
notebook, as ``_sources/NAME.ipynb`` next to the page's Markdown source.
"""
from __future__ import annotations

import argparse
import ast
import html
import re
import sys
from pathlib import Path

import jupytext
import nbformat

BOOK = Path(__file__).resolve().parents[1] / "book"

KERNEL = {"name": "skxfem", "display_name": "skxfem", "language": "python"}
"""The notebooks' kernel: ``make install`` registers it (``python -m ipykernel install
--sys-prefix --name skxfem``), so JupyterLab runs them with the clone's ``.venv``."""

INCLUDE = re.compile(r"^```\{include\}[ \t]+(\S+)[ \t]*\n((?:[ \t]*:[\w-]+:.*\n)*)```[ \t]*$",
                     flags=re.M)
DOWNLOAD = re.compile(r"\{download\}`(?:([^`<]*?)\s*<([^`>]+)>|([^`<>]+))`")
LITERALINCLUDE = re.compile(
    r"^```\{literalinclude\}[ \t]+(\S+)[ \t]*\n((?:[ \t]*:[\w-]+:.*\n)*)```[ \t]*$", flags=re.M)
DROPDOWN = re.compile(r"^(:{3,})\{dropdown\}[ \t]*(.*)\n((?:.*\n)*?)\1[ \t]*$", flags=re.M)
PAGE_LINK = re.compile(r"\]\(([\w-]+)\.md(#[^)\s]*)?\)")
STUB = re.compile(r"^_stubs/(\w+)/exercise\.py$")


def _include(match: re.Match, book: Path) -> str:
    """The text an ``{include}`` block includes (its ``:start-after:`` and
    ``:end-before:`` honoured); a ValueError for an option it does not know."""
    text = (book / match.group(1)).read_text(encoding="utf-8")
    for line in match.group(2).splitlines():
        option, _, value = line.strip()[1:].partition(":")
        value = value.strip()
        if option == "start-after" and value in text:
            text = text.split(value, 1)[1]
        elif option == "end-before" and value in text:
            text = text.split(value, 1)[0]
        else:
            raise ValueError(f"{{include}} {match.group(1)}: option {option!r} (or its "
                             f"marker {value!r}) is not handled by scripts/notebooks.py")
    return text.strip("\n")


def pyobject(source: str, name: str) -> str:
    """The lines of the top-level function or class ``name`` of a module's ``source``
    (decorators included), as Sphinx's ``literalinclude`` with ``:pyobject:`` shows it."""
    for node in ast.parse(source).body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) \
                and node.name == name:
            first = min([node.lineno] + [d.lineno for d in node.decorator_list])
            return "\n".join(source.splitlines()[first - 1:node.end_lineno])
    raise ValueError(f"no function or class {name!r} at the top level of the module")


def _literalinclude(match: re.Match, book: Path) -> str:
    """A ``{literalinclude}`` of a library function as a fenced Python block."""
    options = dict(line.strip()[1:].partition(":")[::2] for line in match.group(2).splitlines())
    options = {k: v.strip() for k, v in options.items()}
    if set(options) - {"pyobject", "language"} or "pyobject" not in options:
        raise ValueError(f"{{literalinclude}} {match.group(1)}: only :pyobject: (and "
                         f":language:) are handled by scripts/notebooks.py, not {options}")
    code = pyobject((book / match.group(1)).read_text(encoding="utf-8"), options["pyobject"])
    return f"```{options.get('language', 'python')}\n{code}\n```"


def _dropdown(match: re.Match) -> str:
    """A folded ``{dropdown}`` as an HTML ``<details>`` block (Markdown inside)."""
    title = re.sub(r"`([^`]+)`", r"<code>\1</code>", html.escape(match.group(2).strip(),
                                                                   quote=False))
    return f"<details><summary>{title}</summary>\n\n{match.group(3).strip()}\n\n</details>"


def _target(path: str) -> str:
    """A file the book offers, as a link from the clone's notebooks/ folder: the book's
    stub of an exercise is the student's own file; any other is relative to book/,
    a sibling of notebooks/, so its link is the same."""
    stub = STUB.match(path)
    return f"../exercises/{stub.group(1)}/exercise.py" if stub else path


def plain(markdown: str, names: set[str], book: Path = BOOK) -> str:
    """A Markdown cell of a chapter as plain Markdown (see the module notes); ``names``
    are the chapters that are notebooks.

    >>> plain("{download}`a stub <_stubs/01_levelset/exercise.py>`, [Scenes](scenes.md)"
    ...       " and [Start](getting-started.md#student)", {"scenes"})
    '[a stub](../exercises/01_levelset/exercise.py), [Scenes](scenes.ipynb) and [Start](../book/getting-started.md#student)'
    """
    markdown = INCLUDE.sub(lambda m: _include(m, book), markdown)
    markdown = LITERALINCLUDE.sub(lambda m: _literalinclude(m, book), markdown)
    markdown = DROPDOWN.sub(_dropdown, markdown)
    markdown = DOWNLOAD.sub(lambda m: f"[{m.group(1) or m.group(3)}]"
                                      f"({_target(m.group(2) or m.group(3))})", markdown)
    return PAGE_LINK.sub(lambda m: f"]({m.group(1)}.ipynb{m.group(2) or ''})"
                         if m.group(1) in names else
                         f"](../book/{m.group(1)}.md{m.group(2) or ''})", markdown)


def chapters(book: Path = BOOK) -> list[Path]:
    """The pages of the book's table of contents that are notebooks, in its order."""
    toc = (book / "_toc.yml").read_text(encoding="utf-8")
    pages = [book / f"{name}.md" for name in re.findall(r"^\s*-?\s*(?:root|file):\s*(\S+)",
                                                        toc, flags=re.M)]
    return [p for p in pages if p.is_file() and "kernelspec" in jupytext.read(p).metadata]


def notebook(page: Path) -> nbformat.NotebookNode:
    """The standalone notebook of one chapter (no outputs, stable cell ids)."""
    nb = jupytext.read(page)
    book = page.parent
    names = {p.stem for p in chapters(book)}
    title = next((c.source.splitlines()[0].lstrip("# ") for c in nb.cells
                  if c.cell_type == "markdown" and c.source.startswith("# ")), page.stem)
    nb.cells.insert(0, nbformat.v4.new_markdown_cell(
        f"*The chapter \"{title}\" of the skxfem book, as a notebook. It needs skxfem "
        f"installed: in a clone of the repository, `make install` (the book's Getting "
        f"started), then `.venv/bin/jupyter lab notebooks/` and the kernel **skxfem**. "
        f"Its links lead to the other chapters' notebooks and to the clone's files from "
        f"the clone's `notebooks/` folder, where `make notebooks` writes it.*"))
    for i, cell in enumerate(nb.cells):
        cell.id = f"{page.stem}-{i}"
        if cell.cell_type == "code":
            cell.outputs, cell.execution_count = [], None
        elif cell.cell_type == "markdown":
            cell.source = plain(cell.source, names, book)
    nb.metadata = nbformat.from_dict({"kernelspec": dict(KERNEL),
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
