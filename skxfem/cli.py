"""The ``skxfem`` command: run a scene file and write its results.

::

    skxfem run examples/plate.toml --out results/plate
    python -m skxfem run examples/plate.toml

A bad scene file (unknown key, wrong type, refused formula ...) or a problem
the solver refuses is reported in one line on stderr, with exit code 2 and no
traceback; ``--debug`` shows the traceback instead.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

__all__ = ["main"]


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="skxfem", description="X-FEM with an interface that cuts the mesh.")
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("run", help="solve a scene file (TOML)")
    run.add_argument("scene", type=Path, help="the scene file, e.g. examples/plate.toml")
    run.add_argument("--out", type=Path, default=None,
                     help="output folder (default: ./<scene name>)")
    run.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    return parser


def _fail(error: Exception, debug: bool) -> int:
    if debug:
        raise error
    print(f"skxfem: error: {error}", file=sys.stderr)
    return 2


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit code (0 success, 2 bad input).

    >>> main(["run", "no-such-scene.toml"])
    2
    """
    args = _parser().parse_args(argv)
    from .io import write_result
    from .scene import load_scene

    try:
        scene = load_scene(args.scene)
    except (OSError, ValueError, TypeError) as e:  # a missing or bad scene file
        return _fail(e, args.debug)
    from .solver import solve

    try:
        result = solve(scene)
    except ValueError as e:  # a problem the solver refuses, e.g. Γ cuts no cell
        return _fail(e, args.debug)
    out = args.out if args.out is not None else Path(scene.name)
    paths = write_result(result, out)
    p = result.pressure
    span = f"pressure in [{p.min():.4g}, {p.max():.4g}]" if p.size else "no interface point"
    print(f"{scene.name}: {result.n_dofs} dofs, {result.n_multipliers} multipliers, "
          f"max jump {result.max_jump:.2e}, {span}, "
          f"{sum(result.timings.values()):.2f} s -> {paths['json'].parent}")
    return 0
