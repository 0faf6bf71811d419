"""Checked reading of TOML files and values: every key known, every value of the right type.

The small checks that :mod:`skxfem.scene.file` builds a scene from.  Each
raises a ValueError or TypeError naming the key (or the file) and what it
should be.

>>> number(2, "E"), one_of({"box": {}}, ("box", "file"), "[mesh]")
(2.0, 'box')
"""
from __future__ import annotations

import math
import os
import tomllib
from pathlib import Path

from ..fem.files import read_bytes
from .expr import Expression

__all__ = ["read_toml", "MAX_BYTES", "MissingFileError", "FolderError", "labelled", "table",
           "array", "keys", "one_of", "choice", "number", "vector", "formula"]


MAX_BYTES = 2**20
"""The largest scene file read: 1 MiB (the examples are about 1 kB)."""


class MissingFileError(FileNotFoundError, ValueError):
    """No file at the path: a ValueError, and the FileNotFoundError it used to be."""


class FolderError(IsADirectoryError, ValueError):
    """A folder at the path: a ValueError, and the IsADirectoryError it used to be."""


def read_toml(path) -> tuple[Path, dict]:
    """``path`` as a Path, and the table of the TOML file there.

    Raises a ValueError starting with the file name if the file is missing
    (:class:`MissingFileError`), a folder (:class:`FolderError`), not a
    regular file (a FIFO or a device is refused without being read), a loop of
    symbolic links, unreadable, larger than :data:`MAX_BYTES`, not UTF-8, not
    TOML or nested too deeply.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be the path of a .toml file (a str or pathlib.Path), "
                        f"got {type(path).__name__} {path!r:.60}")
    path = Path(path)
    name = f"{path.name or path}: the scene file {str(path)!r}"
    try:
        data = read_bytes(path, name, MAX_BYTES)   # a FIFO or a device is never read
    except FileNotFoundError:
        raise MissingFileError(f"{name} does not exist; check the path") from None
    except IsADirectoryError:
        raise FolderError(f"{name} is a folder; give the path of a .toml file") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ValueError(f"{name} is not UTF-8 text (byte {e.object[e.start]:#04x} at "
                         f"offset {e.start}); save it as UTF-8") from None
    try:
        return path, tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ValueError(f"{path.name}: invalid TOML: {e}") from None
    except RecursionError:             # tomllib recurses once per level of nesting
        raise ValueError(f"{path.name}: invalid TOML: arrays or tables nested too deeply "
                         f"for a scene file") from None


def labelled(where: str, build, *args):
    """``build(*args)``; its ValueError or TypeError gets ``where`` in front (unless it
    already starts with it), so that it names the key as the file does."""
    try:
        return build(*args)
    except (ValueError, TypeError) as e:
        if str(e).startswith(where):
            raise
        raise (ValueError if isinstance(e, ValueError) else TypeError)(f"{where}: {e}") from None


def table(t, where: str, allowed: tuple, top: tuple = ()) -> dict:
    """``t`` if it is a table whose keys are all ``allowed`` (``top``: :func:`keys`)."""
    if not isinstance(t, dict):
        raise TypeError(f"{where} must be a table, got {t!r}")
    keys(t, allowed, where, top)
    return t


def array(data: dict, key: str) -> list:
    items = data.get(key, [])
    if not isinstance(items, list) or not all(isinstance(t, dict) for t in items):
        raise TypeError(f"{key} must be written as [[{key}]] tables")
    return items


def keys(t: dict, allowed: tuple, where: str, top: tuple = ()):
    """Refuse a key of ``t`` not ``allowed``; one of the file's ``top``-level keys is said
    to have fallen into the table (TOML puts every key after a table header into it).

    >>> keys({"steps": [1]}, ("law",), "[[interface]] #2", top=("name", "steps"))
    Traceback (most recent call last):
    ...
    ValueError: [[interface]] #2: unknown key 'steps'; allowed keys: law. 'steps' is a ...
    """
    for key in t:
        if key not in allowed:
            hint = (f". {key!r} is a top-level key, but TOML puts every key written after a "
                    f"table header into that table: write the top-level keys "
                    f"({', '.join(top)}) before the first table" if key in top else "")
            raise ValueError(f"{where}: unknown key {key!r}; allowed keys: "
                             f"{', '.join(allowed)}{hint}")


def one_of(t: dict, options: tuple, where: str) -> str:
    present = [k for k in options if k in t]
    if len(present) != 1:
        raise ValueError(f"{where} needs exactly one of {', '.join(options)}; "
                         f"got {', '.join(present) or 'none'}")
    return present[0]


def choice(v, allowed: tuple, key: str) -> str:
    if v not in allowed:
        raise ValueError(f"{key} must be one of {', '.join(allowed)}, got {v!r}")
    return v


def number(v, key: str) -> float:
    if type(v) not in (int, float):
        raise TypeError(f"{key} must be a number, got {v!r}")
    if not math.isfinite(v):
        raise ValueError(f"{key} must be a finite number, got {v!r}")
    return float(v)


def vector(v, key: str, dim: int) -> list[float]:
    if not isinstance(v, list) or len(v) != dim:
        raise ValueError(f"{key} must be a list of {dim} numbers on a {dim}D mesh, got {v!r}")
    return [number(c, key) for c in v]


def formula(v, key: str, dim: int, boolean: bool = False):
    """A number, or a string checked by :mod:`skxfem.scene.expr`."""
    if isinstance(v, str):
        try:
            return Expression(v, dim, boolean)
        except ValueError as e:
            raise ValueError(f"{key}: {e}") from None
    if boolean:
        raise TypeError(f"{key} must be a condition string such as 'x < 1e-9', got {v!r}")
    return number(v, key)
