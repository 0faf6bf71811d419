"""The solver settings of a scene: what its file's ``[solver]`` table says about the solve.

A :class:`Solver` is held by the scene (``Scene.solver``), so that a scene file
gives the same solve through ``skxfem run`` and through
``skxfem.solve(skxfem.load_scene(path))``.  The keyword arguments of
:func:`skxfem.solve` (``linear``, ``linear_tol``, ``max_iter``) override it, as
``skxfem run``'s options ``--linear``, ``--linear-tol``, ``--max-iter`` override
the file (:meth:`Solver.override`).

>>> s = Solver(linear="iterative", max_iter=40)
>>> s.linear, s.linear_tol, s.max_iter
('iterative', 1e-12, 40)
>>> s.override(linear="direct", max_iter=None)   # None: keep the scene's
Solver(linear='direct', linear_tol=1e-12, max_iter=40)
"""
from __future__ import annotations

from dataclasses import dataclass, replace

from ..linalg.choice import LINEAR, LINEAR_TOL, check_linear_tol
from ..linalg.scalars import is_integer

__all__ = ["Solver", "MAX_ITER", "check_linear", "check_max_iter"]

MAX_ITER = 30
"""The Newton iterations a contact load step may take unless a scene or a call says
otherwise (:func:`skxfem.contact.solve`)."""


def check_linear(linear) -> str:
    """``linear`` if it is one of :data:`skxfem.linalg.choice.LINEAR`, else a ValueError.

    >>> check_linear("cholesky")
    Traceback (most recent call last):
    ...
    ValueError: linear must be one of ('auto', 'direct', 'iterative'), got 'cholesky'
    """
    if not isinstance(linear, str) or linear not in LINEAR:
        raise ValueError(f"linear must be one of {LINEAR}, got {linear!r}")
    return linear


def check_max_iter(max_iter) -> int:
    """``max_iter`` as an int if it is a positive integer (numpy's too), else a ValueError.

    >>> import numpy as np
    >>> check_max_iter(np.int64(40)), type(check_max_iter(np.int64(40))).__name__
    (40, 'int')
    >>> check_max_iter(np.array(40))
    40
    >>> check_max_iter(0)
    Traceback (most recent call last):
    ...
    ValueError: max_iter must be a positive integer (Newton iterations per load step), got 0
    """
    if not is_integer(max_iter) or max_iter < 1:
        raise ValueError(f"max_iter must be a positive integer (Newton iterations per load "
                         f"step), got {max_iter!r}")
    return int(max_iter)


@dataclass(frozen=True)
class Solver:
    """How a scene is solved: the options of ``skxfem run`` and ``skxfem.solve``.

    ``linear``: the linear solve, ``"auto"`` (default), ``"direct"`` or
    ``"iterative"`` (:mod:`skxfem.linalg.choice`); ``linear_tol``: the
    relative residual of an iterative solve (default
    :data:`skxfem.linalg.choice.LINEAR_TOL`); ``max_iter``: the Newton
    iterations of a contact load step (``None``: :data:`MAX_ITER`; a scene
    with no contact law takes none).  A bad value is refused with a
    ValueError naming the key.
    """

    linear: str = "auto"
    linear_tol: float = LINEAR_TOL
    max_iter: int | None = None

    def __post_init__(self):
        check_linear(self.linear)
        object.__setattr__(self, "linear_tol", check_linear_tol(self.linear_tol))
        if self.max_iter is not None:
            object.__setattr__(self, "max_iter", check_max_iter(self.max_iter))

    def override(self, linear: str | None = None, linear_tol: float | None = None,
                 max_iter: int | None = None) -> Solver:
        """These settings with each keyword that is not None in their place (checked)."""
        given = {k: v for k, v in (("linear", linear), ("linear_tol", linear_tol),
                                   ("max_iter", max_iter)) if v is not None}
        return replace(self, **given) if given else self
