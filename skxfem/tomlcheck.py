"""Checked reading of TOML values: every key known, every value of the right type.

The small checks that :mod:`skxfem.scenefile` builds a scene from.  Each
raises a ValueError or TypeError naming the key and what it should be.

>>> number(2, "E"), one_of({"box": {}}, ("box", "file"), "[mesh]")
(2.0, 'box')
"""
from __future__ import annotations

from .expr import Expression

__all__ = ["table", "array", "keys", "one_of", "choice", "number", "vector", "formula"]


def table(t, where: str, allowed: tuple) -> dict:
    """``t`` if it is a table whose keys are all ``allowed``."""
    if not isinstance(t, dict):
        raise TypeError(f"{where} must be a table, got {t!r}")
    keys(t, allowed, where)
    return t


def array(data: dict, key: str) -> list:
    items = data.get(key, [])
    if not isinstance(items, list) or not all(isinstance(t, dict) for t in items):
        raise TypeError(f"{key} must be written as [[{key}]] tables")
    return items


def keys(t: dict, allowed: tuple, where: str):
    for key in t:
        if key not in allowed:
            raise ValueError(f"{where}: unknown key {key!r}; allowed keys: {', '.join(allowed)}")


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
    return float(v)


def vector(v, key: str, dim: int) -> list[float]:
    if not isinstance(v, list) or len(v) != dim:
        raise ValueError(f"{key} must be a list of {dim} numbers on a {dim}D mesh, got {v!r}")
    return [number(c, key) for c in v]


def formula(v, key: str, dim: int, boolean: bool = False):
    """A number, or a string checked by :mod:`skxfem.expr`."""
    if isinstance(v, str):
        try:
            return Expression(v, dim, boolean)
        except ValueError as e:
            raise ValueError(f"{key}: {e}") from None
    if boolean:
        raise TypeError(f"{key} must be a condition string such as 'x < 1e-9', got {v!r}")
    return number(v, key)
