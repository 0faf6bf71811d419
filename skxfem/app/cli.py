"""The ``skxfem`` command: run a scene file, reproduce the paper, print the version.

::

    skxfem run examples/plate.toml --out results/plate [--max-memory 8G]
    skxfem schema                              # the scene file: every key, its units
    skxfem reproduce --quick --out out/        # the same as python -m skxfem.app.reproduce
    skxfem --version
    python -m skxfem run examples/plate.toml   # the same as skxfem

``skxfem run`` reads the scene, checks the output folder (an existing file, a
folder that cannot be written or that holds other files), estimates the size of
the problem (:mod:`skxfem.studies.budget`; refused above ``--max-memory``, 4 GB by
default), and only then solves and writes the three result files as one set
(:mod:`skxfem.app.io`).  Without ``--out`` they go to a folder below the current
one named after the scene (:func:`skxfem.app.io.default_folder`: a name such as
``../x`` or ``/x`` cannot choose another place).  A
scene whose ``[interface] law`` is a contact law (``frictionless``,
``coulomb``, ``adhesive``) is solved by :func:`skxfem.contact.solve` over
its load ``steps`` (``--max-iter``: the Newton iteration limit of each step)
and the line printed gives the steps, the Newton iterations, the status
counts of the last step and its largest pressure.

Exit codes: 0 success; 2 for every error the command anticipates (a bad or
missing scene or mesh file, a scene the solver refuses — a level set that cuts
no cell, a singular system, a contact Newton method that does not converge —,
a bad output folder, a failed write, a problem over the size limit, running
out of memory, a usage error), reported as ONE
line ``skxfem: error: ...`` on stderr; 1 for an unexpected error (a bug or a
numerical failure), reported as one line with its type and message and the
hint to run again with ``--debug``, which prints the traceback too (the exit
code stays); 130 after Ctrl-C.  Control characters of a printed line (say, a
scene name holding terminal escape codes) are printed escaped (``\x1b``).

The scene is solved by :func:`skxfem.solve` with the scene file's ``[solver]``
settings (``Scene.solver``) and the options given in their place, so that
``skxfem.solve(skxfem.load_scene(path))`` gives the same answer.  skxfem's own
notices (:data:`NOTICES`: each retry and each cut of a contact load step, vertices
put on Γ, front points left without K) are printed as they are raised, one line
``skxfem: note: ...`` each on stderr.  Other Python warnings (numpy's floating-point
warnings, meshio's, scikit-fem's) are not printed: the summary line counts them
(``--debug`` shows them), and a floating-point overflow in the solve refuses the
result (exit 2): the numbers of the scene are beyond double precision.  ``skxfem run``
never imports matplotlib.

A module with ``main(argv) -> int`` becomes a subcommand with one entry in
:data:`FORWARDED` (``skxfem reproduce`` is ``skxfem.app.reproduce.main``, imported
when asked for); its errors are reported in the same way.
"""
from __future__ import annotations

import argparse
import contextlib
import importlib
import logging
import sys
import traceback
import unicodedata
import warnings
from pathlib import Path

import numpy as np

from .. import __version__
from ..contact.history import StepCutWarning, StepRetryWarning
from ..contact.laws import CONTACT_LAWS, STATUS_NAMES
from ..contact.newton import ContactConvergenceError
from ..crack.kind3d import FrontPointsWarning
from ..cut import SnapWarning
from ..linalg.choice import LINEAR_TOL
from ..linalg.threads import limited
from ..scene.file import MAX_MAGNITUDE, load_scene, schema
from ..scene.laws import in_words
from ..scene.model import Box, resolve
from ..solver import LINEAR, solve
from ..studies import budget
from . import io

__all__ = ["main", "parser", "FORWARDED"]

FORWARDED = {
    "reproduce": ("reproduce the paper's figures and summary.json "
                  "(python -m skxfem.app.reproduce)", "skxfem.app.reproduce"),
    "grade": ("grade the student exercises: a score table and a JSON report "
              "(python -m skxfem.app.grade)", "skxfem.app.grade"),
    "handout": ("write the course as a student gets it, without the solutions "
                "(python -m skxfem.app.handout)", "skxfem.app.handout"),
}
"""Subcommands handed their arguments as they are: ``name -> (help, module)``; the
module (imported only then: it may draw) has ``main(argv) -> int``."""

ANTICIPATED = (OSError, ValueError, TypeError, MemoryError, ContactConvergenceError)
"""Errors reported as a bad input (exit 2): files, scenes, refused problems, disk, memory,
a contact iteration that does not converge (its message says what to change)."""


class _Parser(argparse.ArgumentParser):
    """argparse, with a usage error in one line (exit 2)."""

    def error(self, message):
        self.exit(2, f"skxfem: error: {message} (see {self.prog} --help)\n")


def _memory(text: str) -> int:
    try:
        return budget.parse_bytes(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def _folder(text: str) -> Path:
    if not text.strip():
        raise argparse.ArgumentTypeError("must be a folder name such as results/plate, "
                                         "got an empty one")
    return Path(text)


def _positive(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}")
    return value


def parser() -> argparse.ArgumentParser:
    """The command line of ``skxfem``.

    >>> parser().parse_args(["run", "a.toml", "--max-memory", "1G"]).max_memory
    1073741824
    """
    p = _Parser(prog="skxfem", description="X-FEM with an interface that cuts the mesh.")
    p.add_argument("--version", action="version", version=f"skxfem {__version__}")
    p.add_argument("--debug", action="store_true",
                   help="show the traceback of an error, and the warnings")
    commands = p.add_subparsers(dest="command", required=True, parser_class=_Parser)
    run = commands.add_parser("run", help="solve a scene file (TOML)",
                              epilog="The scene file's tables, keys and units: skxfem schema.")
    run.add_argument("scene", type=Path, help="the scene file, e.g. examples/plate.toml")
    run.add_argument("--out", type=_folder, default=None,
                     help="output folder, replaced as a whole (default: ./<scene name>, "
                          "letters, digits, - _ . only)")
    run.add_argument("--max-memory", type=_memory, default=budget.DEFAULT_MAX_BYTES,
                     metavar="SIZE", help="refuse a scene whose estimated memory exceeds "
                                          "SIZE, e.g. 500M or 16G (default: 4G)")
    run.add_argument("--max-iter", type=_positive, default=None, metavar="N",
                     help="contact laws: Newton iterations allowed per load step "
                          "(default: the scene file's [solver] max_iter, else that of "
                          "skxfem.contact.solve, 30)")
    run.add_argument("--linear-tol", type=float, default=None, metavar="TOL",
                     help="the relative residual of the iterative linear solve (default: "
                          "the scene file's [solver] linear_tol, else "
                          f"{LINEAR_TOL:g})")
    run.add_argument("--linear", choices=LINEAR, default=None,
                     help="the linear solve of a tie or of each contact Newton step: direct "
                          "(SuperLU), iterative (AMG-preconditioned projected CG, needs "
                          "pyamg) or auto (iterative from "
                          "skxfem.linalg.choice.AUTO_ITERATIVE unknowns); default: the scene "
                          "file's [solver] linear, else auto")
    run.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                     help="contact: one line on stderr per Newton iteration and load step "
                          "(residuals, open/stick/slip points, Krylov iterations, time); "
                          "default: on when stderr is a terminal")
    run.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                     help="show the traceback of an error, and the warnings")
    commands.add_parser("schema", help="print the scene-file schema: every table and key, "
                                       "its values and units")
    for name, (text, _) in FORWARDED.items():
        commands.add_parser(name, help=f"{text}; `skxfem {name} --help` for its options",
                            add_help=False)
    return p


def printable(text: str) -> str:
    r"""``text`` with its control and format characters escaped, safe on a terminal.

    >>> print(printable("plate\x1b[2J\u202e"))
    plate\x1b[2J\u202e
    """
    return "".join(c.encode("unicode_escape").decode("ascii")
                   if unicodedata.category(c) in ("Cc", "Cf") else c for c in text)


def _say(text: str, stream=None):
    print(printable(text), file=stream or sys.stdout)


NOTICES = (StepRetryWarning, StepCutWarning, SnapWarning, FrontPointsWarning)
"""skxfem's own notices, printed as ``skxfem: note: ...`` lines on stderr as they are
raised: a contact load step solved again by another method or cut into smaller
increments, vertices near Γ put on it (:class:`skxfem.cut.SnapWarning`), points of a 3D
front left without K (:class:`skxfem.crack.kind3d.FrontPointsWarning`: result.json's
``front`` lists only the others)."""


@contextlib.contextmanager
def _noting(caught: list):
    """Print each notice (:data:`NOTICES`) as a ``skxfem: note: ...`` line on stderr the
    moment it is raised (the same text once), and collect every other warning into
    ``caught``."""
    seen = set()

    def show(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, NOTICES):
            text = " ".join(str(message).split())
            if text not in seen:
                seen.add(text)
                _say(f"skxfem: note: {text}", sys.stderr)
                sys.stderr.flush()
            return
        caught.append(warnings.WarningMessage(message, category, filename, lineno, file, line))

    with warnings.catch_warnings():   # restores the filters and showwarning after
        for category in NOTICES:
            warnings.simplefilter("always", category)
        warnings.showwarning = show
        yield


def _fail(error: BaseException, debug: bool) -> int:
    """One line on stderr and the exit code; the traceback too with ``--debug``."""
    if debug:
        traceback.print_exception(error)
    text = " ".join(str(error).split())                 # one line, whatever the message
    if isinstance(error, ANTICIPATED):
        message = text or type(error).__name__
        if isinstance(error, MemoryError):
            message = ("out of memory" + (f" ({text})" if text else "")
                       + "; lower --max-memory so that the size guard refuses such scenes")
        _say(f"skxfem: error: {message}", sys.stderr)
        return 2
    _say(f"skxfem: unexpected error: {type(error).__name__}: {text}"
         + ("" if debug else " (run with --debug for the traceback)"), sys.stderr)
    return 1


def _closed_words(result) -> str:
    """What the closed points of the last step do, in the words of each law: Coulomb's
    ``2 stick, 3 slip``; ``free to slide`` (frictionless, bilateral); ``held`` (adhesive,
    bonded: no slip wherever closed).  Several laws: each with its name, ``coulomb: 2
    stick, 1 slip; bonded: 3 held``."""
    last = result.steps[-1]
    names, which = last.law, np.asarray(result.ops.interface)
    status = np.asarray(last.status)
    words = {}
    for k, name in enumerate(names):
        here = status[which == k]
        stick, slip = int((here == STATUS_NAMES.index("stick")).sum()), \
            int((here == STATUS_NAMES.index("slip")).sum())
        before = words.get(name, (0, 0))
        words[name] = (before[0] + stick, before[1] + slip)
    parts = []
    for name, (stick, slip) in words.items():
        if name == "coulomb":
            text = f"{stick} stick, {slip} slip"
        elif name in ("frictionless", "bilateral"):
            text = f"{stick + slip} free to slide"
        else:                                       # adhesive, bonded: no slip when closed
            text = f"{stick + slip} held"
        parts.append(text if len(words) == 1 else f"{name}: {text}")
    return "; ".join(parts)


def _contact_line(result) -> str:
    """The one-line summary of a contact result: steps, iterations, last step's statuses
    (:func:`_closed_words`)."""
    last = result.steps[-1]
    counts = {name: int((last.status == code).sum()) for code, name in enumerate(STATUS_NAMES)}
    its = [int(st.newton.iterations) for st in result.steps]
    p = (f"max pressure {last.pressure.max() + 0.0:.4g}"    # + 0.0: -0.0 printed as 0
         if last.pressure.size else "no interface point")
    name = "+".join(law.name for law in result.law)   # one law per interface
    each = ", ".join(map(str, its)) if len(its) <= 6 else \
        f"{', '.join(map(str, its[:3]))}, ..., {its[-1]}; at most {max(its)}"
    return (f"{result.problem.scene.name}: {name}, {len(its)} load step(s), "
            f"{sum(its)} Newton iterations ({each}); last step: "
            f"{counts['stick'] + counts['slip']} in contact ({_closed_words(result)}), "
            f"{counts['open']} open, {p}, {result.linear} solve")


class OverflowRefused(ValueError):
    """A solve that overflowed double precision: the scene's numbers are too large."""


def _overflowed(caught) -> OverflowRefused | None:
    """The refusal of a solve that overflowed double precision (numpy warned), or None."""
    over = [w for w in caught or () if issubclass(w.category, RuntimeWarning)
            and "overflow" in str(w.message)]
    if not over:
        return None
    return OverflowRefused(f"the solve overflowed double precision (numpy: {over[0].message}): a "
                      f"load, imposed displacement or E of the scene is too large for it; "
                      f"scale the units (loads, and displacements from them, up to "
                      f"{MAX_MAGNITUDE:g})")


@limited   # BLAS threads: skxfem.linalg.threads (SKXFEM_THREADS)
def _run(args, caught: list) -> int:
    s = load_scene(args.scene)      # its [solver] table in s.solver
    given = {k: v for k, v in (("linear", args.linear), ("linear_tol", args.linear_tol),
                               ("max_iter", args.max_iter)) if v is not None}
    settings = s.solver.override(**given)  # the command line overrides the file (checked)
    laws = [i.law for i in s.interfaces]
    contact = any(law in CONTACT_LAWS for law in laws)
    if args.max_iter is not None and not contact:
        raise ValueError(f"--max-iter applies to the contact laws {CONTACT_LAWS}; the scene's "
                         f"law is {in_words(laws)}")
    out = io.check_output(args.out if args.out is not None else io.default_folder(s.name))
    # a mesh file is read once, for the estimate and the solve; a Box is estimated
    # before it is built (a box too large is refused without building it)
    target = s if isinstance(s.mesh, Box) else resolve(s)
    budget.check(target, args.max_memory, "--max-memory", linear=settings.linear)
    show = args.progress if args.progress is not None else sys.stderr.isatty()
    lines = {"progress": lambda line: _say(f"skxfem: {line}", sys.stderr)} \
        if show and contact else {}
    result = solve(target, **given, **lines)   # = skxfem.solve: the file's settings, options
    overflow = _overflowed(caught)
    if overflow is not None:
        raise overflow
    try:
        paths = io.write_result(result, out)
    except OSError as e:
        raise OSError(e.errno, f"cannot write the results to {str(out)!r}: "
                               f"{e.strerror or e}; nothing was written") from e
    shown = "on stderr" if args.debug else "not shown (--debug shows them)"
    hidden = f"; {len(caught)} warning(s) {shown}" if caught else ""
    if contact:
        _say(f"{_contact_line(result)}{_fronts(result)} -> {paths['json'].parent}{hidden}")
        return 0
    p = result.pressure + 0.0                            # + 0.0: -0.0 printed as 0
    span = f"pressure in [{p.min():.4g}, {p.max():.4g}]" if p.size else "no interface point"
    _say(f"{s.name}: {result.n_dofs} dofs, {result.n_multipliers} multipliers, "
         f"max jump {result.max_jump:.2e}, {span}{_fronts(result)}, "
         f"{result.linear} solve{_iterations(result)}, "
         f"{sum(result.timings.values()):.2f} s -> {paths['json'].parent}{hidden}")
    return 0


def _fronts(result) -> str:
    """', K_I in [a, b], K_II in [c, d]' over the front points of every crack of the
    result (and K_III in 3D), else '': the numbers a crack's scene is run for.  In 3D
    over the interior points (``interior``: K trusted, away from the free surfaces the
    front ends on) when there are any."""
    if not result.front:
        return ""
    inner = [np.asarray(f.get("interior", np.ones(len(f["points"]))), bool)
             for f in result.front]
    if not any(i.any() for i in inner):
        inner = [np.ones(i.size, bool) for i in inner]
    words = []
    for key in ("K_I", "K_II", "K_III"):
        k = np.concatenate([np.asarray(f[key], float)[i]
                            for f, i in zip(result.front, inner) if key in f] or [[]])
        if k.size:
            words.append(f"{key} {k[0] + 0.0:.4g}" if k.size == 1 else
                         f"{key} in [{k.min() + 0.0:.4g}, {k.max() + 0.0:.4g}]")
    return ", " + ", ".join(words) if words else ""


def _iterations(result) -> str:
    """' (N CG iterations)' after an iterative solve, else ''."""
    its = result.linear_info.get("iterations")
    return "" if its is None else f" ({its} CG iterations)"


def _forward(name: str, argv: list[str]) -> int:
    """Run the subcommand ``name`` of :data:`FORWARDED` on ``argv``."""
    logging.getLogger("matplotlib").setLevel(logging.ERROR)   # e.g. its unwritable config
    return importlib.import_module(FORWARDED[name][1]).main(argv)


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit code (0, 2 anticipated error, 1 unexpected).

    >>> main(["run", "no-such-scene.toml"])
    2
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = bool(argv) and argv[0] == "--debug"
    if debug:
        argv = argv[1:]
    caught = []
    try:
        if argv and argv[0] in FORWARDED:
            return _forward(argv[0], argv[1:])
        args = parser().parse_args(argv)
        debug = args.debug = debug or args.debug
        if args.command == "schema":
            print(schema(), end="")
            return 0
        with _noting(caught):
            return _run(args, caught)
    except KeyboardInterrupt:
        print("skxfem: interrupted", file=sys.stderr)
        return 130
    except Exception as e:  # every error ends as one line (and a traceback with --debug)
        overflow = _overflowed(caught)              # the cause of what followed
        if overflow is None or isinstance(e, OverflowRefused):
            return _fail(e, debug)
        overflow.__cause__ = e
        return _fail(overflow, debug)
    finally:  # the notices are printed as they come; the other warnings with --debug
        for w in caught if debug else ():
            print(warnings.formatwarning(w.message, w.category, w.filename, w.lineno),
                  end="", file=sys.stderr)


if __name__ == "__main__":      # python -m skxfem.app.cli, as python -m skxfem
    sys.exit(main())
