r"""The whole extremes table of issue 11, and its text form.

:func:`table` gathers the rows of :mod:`skxfem.studies.extremes` (Γ near nodes),
:mod:`skxfem.studies.extremes_scales` (E, ν, ρ), :mod:`skxfem.studies.extremes_shapes`
(one cell, memory, slanted and curved Γ, Γ across a support, small pieces) and
:mod:`skxfem.studies.extremes_refused` (what is refused, and the limits accepted);
:func:`format_rows` prints them, one line each, with the refusal messages cut
to a width (the rows keep them whole).  ``progress`` (a
:class:`skxfem.studies.progress.Progress`; by default one that is on in a terminal
only) reports each part.

>>> from skxfem.studies.extremes import Row
>>> print(format_rows([Row("E", "E = 1", "solved", "deviation", 0.0, 1e-8, "", 0.01)]))
group    case                                               outcome        value      tol  note
E        E = 1                                              solved      0.00e+00    1e-08
"""
from __future__ import annotations

from .extremes import CELL_TYPES, Row, position_rows
from .extremes_refused import limit_rows, refused_rows
from .extremes_scales import modulus_rows, poisson_rows, rho_rows
from .extremes_shapes import (
    memory_rows,
    one_cell_rows,
    piece_rows,
    shape_rows,
    space_rows,
    support_rows,
)
from .progress import Progress

__all__ = ["table", "format_rows", "markdown_rows"]


def table(cells=CELL_TYPES, progress: Progress | None = None) -> list[Row]:
    """Every row of the extremes table (about 25 s here)."""
    parts = [("Γ near nodes", lambda: position_rows(cells) + space_rows()),
             ("E", modulus_rows), ("ν", poisson_rows), ("ρ", rho_rows),
             ("one cell, memory", lambda: one_cell_rows(cells) + memory_rows(cells)),
             ("shapes", lambda: shape_rows(cells)),
             ("supports, pieces", lambda: support_rows(cells) + piece_rows(cells)),
             ("refused, limits", lambda: refused_rows() + limit_rows(cells))]
    progress = progress or Progress(len(parts), "extremes")
    rows = []
    for name, make in parts:
        rows += make()
        progress.step(name)
    return rows


def format_rows(rows, width: int = 90) -> str:
    """The rows as a fixed-width text table; notes and messages cut to ``width``."""
    lines = [f"{'group':8} {'case':50} {'outcome':10} {'value':>9} {'tol':>8}  note"]
    for r in rows:
        value = "-" if r.value is None else f"{r.value:.2e}"
        note = r.message if len(r.message) <= width else r.message[:width - 3] + "..."
        lines.append(f"{r.group:8} {r.case:50} {r.outcome:10} {value:>9} {r.tolerance:>8.3g}"
                     f"  {note}".rstrip())
    return "\n".join(lines)


def markdown_rows(rows) -> str:
    """The rows as a Markdown table (for the book): every message in full.

    >>> from skxfem.studies.extremes import Row
    >>> print(markdown_rows([Row("E", "E = 1", "solved", "energy error", 1e-15, 1e-8, "", 0.1)]))
    | group | case | outcome | value | tolerance | message or note |
    |---|---|---|---|---|---|
    | E | E = 1 | solved | 1.00e-15 | 1e-08 |  |
    """
    lines = ["| group | case | outcome | value | tolerance | message or note |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        value = "-" if r.value is None else f"{r.value:.2e}"
        note = r.message.replace("|", "\\|").replace("\n", " ")
        lines.append(f"| {r.group} | {r.case} | {r.outcome} | {value} | {r.tolerance:.3g} "
                     f"| {note} |")
    return "\n".join(lines)
