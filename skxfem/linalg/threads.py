"""BLAS threads of skxfem's own solves: one by default, overridable.

skxfem's solves factorise many small dense blocks (the interface systems, the
AMG coarse levels) and sparse matrices whose dense kernels are small.  A
threaded BLAS (OpenBLAS uses every core by default) spends more time waking
its threads than working on them: on a shared 2-core machine a threaded
OpenBLAS made solves 2-4 times slower, and once made the first solve 10 s
instead of 0.3 s.  So :func:`skxfem.solve`, :func:`skxfem.contact.solve` and
``skxfem run`` limit the BLAS libraries (OpenBLAS, MKL, BLIS: every copy
loaded, numpy's and scipy's) to :func:`threads` threads while they run, with
`threadpoolctl <https://github.com/joblib/threadpoolctl>`_, and give them back
as they were afterwards: the rest of a notebook keeps its own setting.

The number, first found of

1. :func:`using` (a ``with`` block);
2. the environment variable ``SKXFEM_THREADS``: a positive integer, or ``off``; it is
   read at each solve, so ``os.environ["SKXFEM_THREADS"] = "2"`` in a notebook
   holds for the rest of the session;
3. :data:`DEFAULT`, one thread.

``off`` (``None`` in Python) leaves the BLAS threads as they are (the
library's default, or ``OPENBLAS_NUM_THREADS``).  ``benchmarks/blas_threads.py``
measures the difference.

>>> from threadpoolctl import threadpool_info
>>> @limited
... def blas_threads_inside():
...     return {d["num_threads"] for d in threadpool_info() if d["user_api"] == "blas"}
>>> blas_threads_inside()
{1}
>>> with using(2):
...     blas_threads_inside() <= {2}     # {2}, or {} if no BLAS is loaded
True
"""
from __future__ import annotations

import contextlib
import contextvars
import functools
import os

from threadpoolctl import threadpool_limits

__all__ = ["ENV", "DEFAULT", "threads", "using", "limited"]

ENV = "SKXFEM_THREADS"
"""The environment variable that sets the BLAS threads of skxfem's solves."""

DEFAULT = 1
"""BLAS threads of skxfem's solves when nothing else is chosen."""

_UNSET = object()
_choice: contextvars.ContextVar = contextvars.ContextVar("skxfem_threads", default=_UNSET)


def _checked(n, where: str) -> int | None:
    """``n`` if a positive int or None; a ValueError/TypeError naming ``where`` otherwise."""
    if n is None:
        return None
    if isinstance(n, bool) or not isinstance(n, int):
        raise TypeError(f"{where} must be a positive integer or None (BLAS threads not "
                        f"limited), got {n!r}")
    if n < 1:
        raise ValueError(f"{where} must be a positive integer or None (BLAS threads not "
                         f"limited), got {n!r}")
    return n


def threads(environ=os.environ) -> int | None:
    """The BLAS threads skxfem's solves use now; None: not limited.

    Raises a ValueError naming ``SKXFEM_THREADS`` if that variable is set to
    anything but a positive integer or ``off``.

    >>> threads(environ={}), threads(environ={"SKXFEM_THREADS": "4"})
    (1, 4)
    >>> threads(environ={"SKXFEM_THREADS": "off"}) is None
    True
    """
    chosen = _choice.get()
    if chosen is not _UNSET:
        return chosen
    text = environ.get(ENV, "").strip()
    if not text:
        return DEFAULT
    if text.lower() == "off":
        return None
    if not (text.isascii() and text.isdigit() and int(text) >= 1):
        raise ValueError(f"the environment variable {ENV} must be a positive integer (the "
                         f"BLAS threads of skxfem's solves) or 'off', got {text!r}")
    return int(text)


@contextlib.contextmanager
def using(n: int | None):
    """Use ``n`` BLAS threads in skxfem's solves inside a ``with`` block (None: do not
    limit them); the choice before is restored after it.

    >>> with using(3):
    ...     threads()
    3
    """
    token = _choice.set(_checked(n, "using(n)"))
    try:
        yield
    finally:
        _choice.reset(token)


def limited(function):
    """Decorate a solve: the BLAS libraries run :func:`threads` threads while it runs
    (restored after), or are left alone when that is None."""
    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        n = threads()
        if n is None:
            return function(*args, **kwargs)
        with threadpool_limits(limits=n, user_api="blas"):
            return function(*args, **kwargs)
    return wrapper
