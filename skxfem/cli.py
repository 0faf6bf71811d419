"""The ``skxfem`` command: run a scene file, reproduce the paper, print the version.

::

    skxfem run examples/plate.toml --out results/plate [--max-memory 8G]
    skxfem schema                              # the scene file: every key, its units
    skxfem reproduce --quick --out out/        # the same as python -m skxfem.reproduce
    skxfem --version
    python -m skxfem run examples/plate.toml   # the same as skxfem

``skxfem run`` reads the scene, checks the output folder (an existing file, a
folder that cannot be written), estimates the size of the problem
(:mod:`skxfem.budget`; refused above ``--max-memory``, 4 GB by default), and
only then solves and writes the results atomically (:mod:`skxfem.io`).  A
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
hint to run again with ``--debug``, which shows the traceback instead; 130
after Ctrl-C.

A module with ``main(argv) -> int`` becomes a subcommand with one entry in
:data:`FORWARDED` (``skxfem reproduce`` is ``skxfem.reproduce.main``); its
errors are reported in the same way.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import __version__, budget, grade, io, reproduce
from .contact import solve as solve_contact
from .contact_laws import CONTACT_LAWS, STATUS_NAMES
from .contact_newton import ContactConvergenceError
from .scenefile import load_options, load_scene, schema
from .solver import LINEAR, solve
from .threads import limited

__all__ = ["main", "parser", "FORWARDED"]

FORWARDED = {
    "reproduce": ("reproduce the paper's figures and summary.json "
                  "(python -m skxfem.reproduce)", reproduce.main),
    "grade": ("grade the student exercises: a score table and a JSON report "
              "(python -m skxfem.grade)", grade.main),
}
"""Subcommands handed their arguments as they are: ``name -> (help, main(argv) -> int)``."""

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
    p.add_argument("--debug", action="store_true", help="show the traceback of an error")
    commands = p.add_subparsers(dest="command", required=True, parser_class=_Parser)
    run = commands.add_parser("run", help="solve a scene file (TOML)",
                              epilog="The scene file's tables, keys and units: skxfem schema.")
    run.add_argument("scene", type=Path, help="the scene file, e.g. examples/plate.toml")
    run.add_argument("--out", type=Path, default=None,
                     help="output folder (default: ./<scene name>)")
    run.add_argument("--max-memory", type=_memory, default=budget.DEFAULT_MAX_BYTES,
                     metavar="SIZE", help="refuse a scene whose estimated memory exceeds "
                                          "SIZE, e.g. 500M or 16G (default: 4G)")
    run.add_argument("--max-iter", type=_positive, default=None, metavar="N",
                     help="contact laws: Newton iterations allowed per load step "
                          "(default: the scene file's [solver] max_iter, else that of "
                          "skxfem.contact.solve, 30)")
    run.add_argument("--linear", choices=LINEAR, default=None,
                     help="the linear solve of a tie or of each contact Newton step: direct "
                          "(SuperLU), iterative (AMG-preconditioned projected CG, needs "
                          "pyamg; coulomb only when asked) or auto (iterative from "
                          "skxfem.linear.AUTO_ITERATIVE unknowns); default: the scene "
                          "file's [solver] linear, else auto")
    run.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                     help="show the traceback of an error")
    commands.add_parser("schema", help="print the scene-file schema: every table and key, "
                                       "its values and units")
    for name, (text, _) in FORWARDED.items():
        commands.add_parser(name, help=f"{text}; `skxfem {name} --help` for its options",
                            add_help=False)
    return p


def _fail(error: BaseException, debug: bool) -> int:
    """One line on stderr and the exit code; the traceback with ``--debug``."""
    if debug:
        raise error
    text = " ".join(str(error).split())                 # one line, whatever the message
    if isinstance(error, ANTICIPATED):
        message = text or type(error).__name__
        if isinstance(error, MemoryError):
            message = ("out of memory" + (f" ({text})" if text else "")
                       + "; lower --max-memory so that the size guard refuses such scenes")
        print(f"skxfem: error: {message}", file=sys.stderr)
        return 2
    print(f"skxfem: unexpected error: {type(error).__name__}: {text} "
          f"(run with --debug for the traceback)", file=sys.stderr)
    return 1


def _contact_line(result) -> str:
    """The one-line summary of a contact result: steps, iterations, last step's statuses."""
    last = result.steps[-1]
    counts = {name: int((last.status == code).sum()) for code, name in enumerate(STATUS_NAMES)}
    its = [int(st.newton.iterations) for st in result.steps]
    p = (f"max pressure {last.pressure.max() + 0.0:.4g}"    # + 0.0: -0.0 printed as 0
         if last.pressure.size else "no interface point")
    return (f"{result.problem.scene.name}: {result.law.name}, {len(its)} load step(s), "
            f"{sum(its)} Newton iterations ({', '.join(map(str, its))}); last step: "
            f"{counts['stick'] + counts['slip']} in contact ({counts['stick']} stick, "
            f"{counts['slip']} slip), {counts['open']} open, {p}, {result.linear} solve")


@limited   # BLAS threads: skxfem.threads (SKXFEM_THREADS)
def _run(args) -> int:
    s = load_scene(args.scene)
    options = load_options(args.scene)  # the command line overrides the file
    linear = args.linear or options.get("linear", "auto")
    max_iter = args.max_iter if args.max_iter is not None else options.get("max_iter")
    contact = s.law in CONTACT_LAWS
    if max_iter is not None and not contact:
        raise ValueError(f"--max-iter applies to the contact laws {CONTACT_LAWS}; the scene's "
                         f"law is {s.law!r}")
    out = io.check_output(args.out if args.out is not None else Path(s.name))
    budget.check(s, args.max_memory, "--max-memory", linear=linear)
    if contact:
        limit = {} if max_iter is None else {"max_iter": max_iter}
        result = solve_contact(s, linear=linear, **limit)
    else:
        result = solve(s, linear=linear)
    try:
        paths = io.write_result(result, out)
    except OSError as e:
        raise OSError(e.errno, f"cannot write the results to {str(out)!r}: "
                               f"{e.strerror or e}; nothing was written") from e
    if contact:
        print(f"{_contact_line(result)} -> {paths['json'].parent}")
        return 0
    p = result.pressure
    span = f"pressure in [{p.min():.4g}, {p.max():.4g}]" if p.size else "no interface point"
    print(f"{s.name}: {result.n_dofs} dofs, {result.n_multipliers} multipliers, "
          f"max jump {result.max_jump:.2e}, {span}, "
          f"{result.linear} solve{_iterations(result)}, "
          f"{sum(result.timings.values()):.2f} s -> {paths['json'].parent}")
    return 0


def _iterations(result) -> str:
    """' (N CG iterations)' after an iterative solve, else ''."""
    its = result.linear_info.get("iterations")
    return "" if its is None else f" ({its} CG iterations)"


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit code (0, 2 anticipated error, 1 unexpected).

    >>> main(["run", "no-such-scene.toml"])
    2
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = bool(argv) and argv[0] == "--debug"
    if debug:
        argv = argv[1:]
    try:
        if argv and argv[0] in FORWARDED:
            return FORWARDED[argv[0]][1](argv[1:])
        args = parser().parse_args(argv)
        debug = debug or args.debug
        if args.command == "schema":
            print(schema(), end="")
            return 0
        return _run(args)
    except KeyboardInterrupt:
        print("skxfem: interrupted", file=sys.stderr)
        return 130
    except Exception as e:  # every error ends as one line (or a traceback with --debug)
        return _fail(e, debug)
