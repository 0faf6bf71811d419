"""Progress output for long runs: one line per step with its elapsed time.

A :class:`Progress` prints, after each step, ``[label k/total] name: 1.2 s
(4.5 s in all)`` on its stream (stderr by default, so a table printed on
stdout stays clean).  It is *off* unless that stream is a terminal, so tests,
pipes, logs and book builds see nothing; ``enabled=True`` forces it on.
:func:`steps` wraps an iterable.

>>> import io
>>> out = io.StringIO()
>>> p = Progress(2, "demo", enabled=True, stream=out, clock=iter([0.0, 1.5, 4.0]).__next__)
>>> p.step("first"), p.step("second")
(1.5, 2.5)
>>> print(out.getvalue(), end="")
[demo 1/2] first: 1.5 s (1.5 s in all)
[demo 2/2] second: 2.5 s (4.0 s in all)
"""
from __future__ import annotations

import sys
import time
from typing import Callable, Iterable, Iterator, TextIO

__all__ = ["Progress", "steps"]


class Progress:
    """One line per finished step: its name, its time and the time so far.

    Parameters
    ----------
    total
        The number of steps expected (shown as ``k/total``; 0: unknown).
    label
        What runs (e.g. ``"frontier"``).
    enabled
        ``None`` (default): on only if ``stream`` is a terminal.
    stream
        Where to write; default ``sys.stderr``.
    clock
        A function returning seconds (default ``time.perf_counter``).
    """

    def __init__(self, total: int, label: str, enabled: bool | None = None,
                 stream: TextIO | None = None, clock: Callable[[], float] = time.perf_counter):
        if not (isinstance(total, int) and total >= 0):
            raise ValueError(f"total must be a non-negative integer, got {total!r}")
        self.stream = sys.stderr if stream is None else stream
        if enabled is None:
            isatty = getattr(self.stream, "isatty", None)
            enabled = bool(isatty and isatty())
        self.total, self.label, self.enabled, self.clock = total, label, enabled, clock
        self.count = 0
        self.start = self.last = clock()

    def step(self, name: str = "") -> float:
        """Mark a step as done; print its line if enabled; return its seconds."""
        now = self.clock()
        seconds, self.last = now - self.last, now
        self.count += 1
        if self.enabled:
            of = f"/{self.total}" if self.total else ""
            print(f"[{self.label} {self.count}{of}] {name}: {seconds:.1f} s "
                  f"({now - self.start:.1f} s in all)", file=self.stream, flush=True)
        return seconds


def steps(items: Iterable, label: str, name: Callable[[object], str] = str,
          enabled: bool | None = None, stream: TextIO | None = None) -> Iterator:
    """Yield ``items``, printing a :class:`Progress` line after each is processed.

    >>> import io
    >>> out = io.StringIO()
    >>> [x * 2 for x in steps([1, 2], "twice", enabled=True, stream=out)]
    [2, 4]
    >>> out.getvalue().count("[twice ")
    2
    """
    items = list(items)
    p = Progress(len(items), label, enabled, stream)
    for item in items:
        yield item
        p.step(name(item))
