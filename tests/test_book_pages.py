"""What a student reads: the chapters' sources (book/*.md), checked without a build.

A chapter shows equations, contracts and short code: a library function's full
source is folded (a ``{dropdown}`` holding a ``{literalinclude}`` with
``:pyobject:``, rendered highlighted), never printed; every code line the book shows
(code cells and the sources it folds) fits the page, 88 columns; the book names no
issue of the tracker; a Markdown table is one block of rows.
"""
import importlib.util
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BOOK = ROOT / "book"
PAGES = sorted(BOOK.glob("*.md"))
WIDTH = 88
"""The widest code line the book's page shows without wrapping or scrolling."""

_spec = importlib.util.spec_from_file_location("book_notebooks", ROOT / "scripts" / "notebooks.py")
notebooks = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(notebooks)

CELL = re.compile(r"^```\{code-cell\}[^\n]*\n(.*?)^```", flags=re.S | re.M)


def _line(text: str, offset: int) -> int:
    return text[:offset].count("\n") + 1


def test_there_are_chapters():
    assert len(PAGES) >= 12


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_no_source_is_printed(page):
    """Sources are folded and highlighted, not dumped by print(inspect.getsource(...))."""
    assert "getsource" not in page.read_text(encoding="utf-8"), page.name


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_code_cells_fit_the_page(page):
    text = page.read_text(encoding="utf-8")
    long = [f"{page.name}:{_line(text, m.start(1)) + i}: {len(line)} columns"
            for m in CELL.finditer(text)
            for i, line in enumerate(m.group(1).splitlines()) if len(line) > WIDTH]
    assert not long, long


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_folded_sources_are_folded_and_fit_the_page(page):
    """Each {literalinclude} of a library function sits in a {dropdown}, names a
    function of that module, and each of its lines fits the page."""
    text = page.read_text(encoding="utf-8")
    folded = [m.group(3) for m in notebooks.DROPDOWN.finditer(text)]
    for m in notebooks.LITERALINCLUDE.finditer(text):
        name = re.search(r":pyobject:\s*(\S+)", m.group(2))
        if name is None:
            continue                                   # a quoted passage (intro.md)
        assert any(m.group(0) in block for block in folded), \
            f"{page.name}:{_line(text, m.start())}: {name.group(1)} is not in a dropdown"
        code = notebooks.pyobject((BOOK / m.group(1)).read_text(encoding="utf-8"),
                                  name.group(1))
        long = [line for line in code.splitlines() if len(line) > WIDTH]
        assert not long, (page.name, name.group(1), long)


def test_a_folded_source_is_a_details_block_in_the_notebook():
    nb = notebooks.notebook(BOOK / "contact.md")
    text = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
    assert "<summary>The code of <code>residual</code>" in text
    assert "```python\ndef residual(" in text and "{literalinclude}" not in text


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_no_issue_numbers(page):
    """The book is for students: it names no issue of the project's tracker."""
    hits = [f"{page.name}:{i}: {line.strip()}"
            for i, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1)
            if re.search(r"\bissues?\b", line, flags=re.I)]
    assert not hits, hits


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_a_table_is_one_block(page):
    """Rows of one table follow each other: a blank line or a cell between two runs
    of rows splits them into two tables."""
    lines = page.read_text(encoding="utf-8").splitlines() + [""]
    rows = [i for i, line in enumerate(lines) if line.startswith("|")]
    separator = re.compile(r"\|(\s*:?-+:?\s*\|)+")
    for a, b in zip(rows, rows[1:]):
        gap = lines[a + 1:b]
        new_table = separator.fullmatch(lines[b + 1].strip()) is not None
        only_blanks = all(not line.strip() for line in gap)
        assert not (gap and only_blanks and not new_table), \
            f"{page.name}:{a + 1}-{b + 1}: one table split in two by blank lines"
