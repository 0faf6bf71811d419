r"""A safe expression language for scene files.

Scene files describe level sets, imposed displacements and loads as short
formulas such as ``"z - 0.5 - 0.2*x"`` or ``"4*y*(1 - y)"``.  A scene file must
never run code, so the formula is *not* handed to :func:`eval`: it is parsed with
:func:`ast.parse` and the syntax tree is checked against a whitelist, then
evaluated by walking the tree over numpy arrays.

Allowed in every expression

* numbers (``1``, ``0.5``, ``1e-9``), the coordinates ``x``, ``y``, ``z`` and ``pi``;
* ``+ - * / **``, unary ``-`` and ``+``, parentheses;
* the functions of :data:`FUNCTIONS`, called by name with numbers as arguments:
  ``sqrt abs exp log sin cos tan asin acos atan sinh cosh tanh`` (one argument),
  ``atan2(y, x)``, ``min(a, b, ...)`` and ``max(a, b, ...)``; angles in radians,
  ``log`` the natural logarithm.

Allowed only in selections (``boolean=True``, e.g. ``where = "x < 1e-9"``)

* comparisons ``< <= > >= == !=`` (chains such as ``0 < x < 1`` too);
* ``and``, ``or``, ``not``.

Everything else (other functions, attribute access, subscripts, strings,
lambdas, comprehensions, keyword arguments, other names ...) is refused with a
:class:`ValueError` naming the construct.  Coordinates follow scikit-fem: ``x``
has shape ``(dim, ...)`` and ``x[0]``, ``x[1]``, ``x[2]`` are called ``x``, ``y``, ``z``.

A value that is not a finite number is refused when evaluated, never handed to a
solve: a function outside its domain (``sqrt(x - 2)`` where x < 2, ``log(0)``)
with a ValueError naming the function, its domain and a point where it failed;
a NaN or infinite result (``1/x`` at x = 0) with the point too.

>>> import numpy as np
>>> f = Expression("4*x*(1 - x)", dim=2)
>>> f(np.array([[0.0, 0.5], [0.0, 0.0]]))
array([0., 1.])
>>> Expression("sqrt(x**2 + y**2)", dim=2)(np.array([[3.0], [4.0]]))
array([5.])
>>> Expression("open('f')", dim=2)  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
ValueError: function call "open('f')" is not allowed in expression "open('f')"; allowed: ...
"""
from __future__ import annotations

import ast
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["MAX_DEPTH", "MAX_LENGTH", "FUNCTIONS", "Expression"]

MAX_LENGTH = 1000
"""Longest expression text accepted, in characters."""
MAX_DEPTH = 100
"""Deepest syntax tree accepted (nested operations)."""

FUNCTIONS = {
    "sqrt": (np.sqrt, 1, "a number >= 0"),
    "abs": (np.abs, 1, None),
    "exp": (np.exp, 1, "a number below about 709 (exp overflows above)"),
    "log": (np.log, 1, "a number > 0"),
    "sin": (np.sin, 1, None),
    "cos": (np.cos, 1, None),
    "tan": (np.tan, 1, None),
    "asin": (np.arcsin, 1, "a number in [-1, 1]"),
    "acos": (np.arccos, 1, "a number in [-1, 1]"),
    "atan": (np.arctan, 1, None),
    "atan2": (np.arctan2, 2, None),
    "sinh": (np.sinh, 1, "a number between about -710 and 710 (sinh overflows beyond)"),
    "cosh": (np.cosh, 1, "a number between about -710 and 710 (cosh overflows beyond)"),
    "tanh": (np.tanh, 1, None),
    "min": (np.minimum, 0, None),
    "max": (np.maximum, 0, None),
}
"""The functions a formula may call: ``name -> (numpy function, number of arguments
(0: two or more), the domain where it is finite, or None: everywhere)``."""

_COORDS = ("x", "y", "z")
_ARITH = {ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply,
          ast.Div: np.divide, ast.Pow: np.power}
_COMPARE = {ast.Lt: np.less, ast.LtE: np.less_equal, ast.Gt: np.greater,
            ast.GtE: np.greater_equal, ast.Eq: np.equal, ast.NotEq: np.not_equal}
_NAMES = {ast.Call: "function call", ast.Attribute: "attribute access",
          ast.Subscript: "subscript", ast.Lambda: "lambda", ast.IfExp: "if-else",
          ast.ListComp: "comprehension", ast.SetComp: "comprehension",
          ast.DictComp: "comprehension", ast.GeneratorExp: "comprehension",
          ast.List: "list", ast.Tuple: "tuple", ast.Dict: "dict", ast.Set: "set",
          ast.NamedExpr: "assignment (:=)", ast.JoinedStr: "string",
          ast.Starred: "starred expression", ast.Slice: "slice",
          ast.Await: "await", ast.Yield: "yield", ast.YieldFrom: "yield"}


@dataclass(frozen=True)
class Expression:
    """A checked formula in ``x, y, z`` that evaluates on numpy arrays.

    Parameters
    ----------
    text
        The formula, at most :data:`MAX_LENGTH` characters.
    dim
        Number of coordinates (2 or 3); ``z`` is refused when ``dim == 2``.
    boolean
        ``True`` for a selection (comparisons, ``and``/``or``/``not``) that
        returns a boolean array; ``False`` for a number-valued formula.

    Raises
    ------
    ValueError
        If the text is not a valid formula of the requested kind.

    >>> import numpy as np
    >>> where = Expression("x < 0.5 and not y > 0.5", dim=2, boolean=True)
    >>> where(np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0]]))
    array([ True, False, False])
    """

    text: str
    dim: int
    boolean: bool = False
    _tree: ast.expr = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        if not isinstance(self.text, str):
            raise TypeError(f"expression must be a string, got {self.text!r}")
        if self.dim not in (2, 3):
            raise ValueError(f"expression dim must be 2 or 3, got {self.dim!r}")
        if not self.text.strip():
            raise ValueError("expression is empty")
        if len(self.text) > MAX_LENGTH:
            raise ValueError(f"expression is {len(self.text)} characters long; "
                             f"at most {MAX_LENGTH} are allowed")
        try:
            tree = ast.parse(self.text.strip(), mode="eval").body
        except SyntaxError as e:
            raise ValueError(f"expression {_short(self.text)} is not valid: {e.msg}") from None
        except (RecursionError, MemoryError):
            raise ValueError(f"expression {_short(self.text)} is nested too deeply") from None
        kind = _check(tree, self, 0)
        wanted = "bool" if self.boolean else "num"
        if kind != wanted:
            raise ValueError(
                f"expression {_short(self.text)} must be a "
                + ("condition such as 'x < 0.5'" if self.boolean else "number-valued formula"))
        object.__setattr__(self, "_tree", tree)

    def __call__(self, x: ArrayLike) -> np.ndarray:
        """Evaluate at points ``x`` of shape ``(dim, ...)``; return shape ``(...)``.

        Raises :class:`ValueError` if a number-valued result is NaN or infinite.
        """
        x = np.asarray(x, dtype=float)
        if x.ndim == 0 or x.shape[0] != self.dim:
            raise ValueError(f"expression {_short(self.text)} is {self.dim}D but got points of "
                             f"shape {x.shape}; expected ({self.dim}, ...)")
        with np.errstate(all="ignore"):
            value = _evaluate(self._tree, x, self)
        value = np.broadcast_to(value, x.shape[1:])
        if self.boolean:
            return value.astype(bool)
        value = value.astype(float)
        _finite(value, x, self, f"expression {_short(self.text)} gives NaN or inf")
        return value


def _short(text: str, limit: int = 60) -> str:
    """``text`` quoted, cut to ``limit`` characters for error messages."""
    return repr(text) if len(text) <= limit else repr(text[:limit]) + "..."


def _allowed(expr: Expression) -> str:
    names = ", ".join(_COORDS[:expr.dim] + ("pi",))
    text = (f"numbers, {names}, + - * / ** and parentheses, the functions "
            f"{' '.join(FUNCTIONS)}")
    return text + (", comparisons, and, or, not" if expr.boolean else "")


def _at(where: np.ndarray, x: np.ndarray) -> tuple[str, tuple]:
    """``'k of n points'`` where ``where`` holds, and the index of the first of them."""
    where = np.broadcast_to(where, x.shape[1:])
    first = tuple(int(i) for i in np.argwhere(where)[0])
    return f"{int(where.sum())} of {where.size} points", first


def _point(x: np.ndarray, index: tuple) -> str:
    names = ", ".join(_COORDS[:x.shape[0]])
    return f"({names}) = ({', '.join(f'{c:.6g}' for c in x[(slice(None),) + index])})"


def _finite(value, x: np.ndarray, expr: Expression, what: str):
    """Refuse NaN or inf in ``value`` (an array over the points ``x``), naming a point."""
    bad = ~np.isfinite(value)
    if np.any(bad):
        count, first = _at(bad, x)
        raise ValueError(f"{what} at {count}, e.g. at {_point(x, first)}; a formula must "
                         f"give a finite number everywhere it is used")


def _refuse(node: ast.AST, expr: Expression, what: str | None = None):
    what = what or _NAMES.get(type(node), type(node).__name__)
    snippet = ast.get_source_segment(expr.text.strip(), node) or ""
    raise ValueError(f"{what} {_short(snippet)} is not allowed in expression {_short(expr.text)}; "
                     f"allowed: {_allowed(expr)}")


def _check(node: ast.AST, expr: Expression, depth: int) -> str:
    """Return ``"num"`` or ``"bool"`` for ``node``, or raise ValueError."""
    if depth > MAX_DEPTH:
        raise ValueError(f"expression {_short(expr.text)} is nested more than "
                         f"{MAX_DEPTH} levels deep")
    sub = [_check(c, expr, depth + 1) for c in _children(node, expr)]
    if isinstance(node, ast.Constant):
        if isinstance(node.value, str):
            _refuse(node, expr, "string")
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            _refuse(node, expr, "constant")
        try:
            big = not np.isfinite(float(node.value))  # 1e999 parses as inf
        except OverflowError:  # an int too large for a float
            big = True
        if big:
            text = ast.get_source_segment(expr.text.strip(), node) or str(node.value)
            raise ValueError(f"expression {_short(expr.text)}: the number {_short(text, 20)} "
                             f"is too large for floating point")
        return "num"
    if isinstance(node, ast.Name):
        if node.id == "z" and expr.dim == 2:
            raise ValueError(f"expression {_short(expr.text)} uses z but the mesh is 2D")
        if node.id in FUNCTIONS:
            raise ValueError(f"expression {_short(expr.text)}: {node.id} is a function; "
                             f"call it, e.g. {node.id}(x)")
        if node.id not in _COORDS and node.id != "pi":
            _refuse(node, expr, "name")
        return "num"
    if isinstance(node, ast.Call):
        if all(k == "num" for k in sub):
            return "num"
        _refuse(node, expr, "a condition as the argument of")
    if isinstance(node, ast.BinOp) and sub == ["num", "num"]:
        return "num"
    if (isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd))
            and sub == ["num"]):
        return "num"
    if expr.boolean:
        if isinstance(node, ast.Compare) and set(sub) == {"num"}:
            return "bool"
        if isinstance(node, ast.BoolOp) and set(sub) == {"bool"}:
            return "bool"
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not) and sub == ["bool"]:
            return "bool"
    is_condition = isinstance(node, (ast.Compare, ast.BoolOp)) or (
        isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not))
    if is_condition and not expr.boolean:
        _refuse(node, expr, "condition (comparisons, and, or, not: only in selections)")
    if isinstance(node, (ast.BinOp, ast.UnaryOp, ast.Compare, ast.BoolOp)):
        _refuse(node, expr, "mixing numbers and conditions in")
    _refuse(node, expr)


def _children(node: ast.AST, expr: Expression) -> list[ast.AST]:
    """The operands of an allowed node; refuse disallowed operators early."""
    if isinstance(node, ast.BinOp):
        if type(node.op) not in _ARITH:
            _refuse(node, expr, f"operator {type(node.op).__name__}")
        return [node.left, node.right]
    if isinstance(node, ast.UnaryOp):
        if not isinstance(node.op, (ast.USub, ast.UAdd, ast.Not)):
            _refuse(node, expr, f"operator {type(node.op).__name__}")
        return [node.operand]
    if isinstance(node, ast.Compare):
        for op in node.ops:
            if type(op) not in _COMPARE:
                _refuse(node, expr, f"comparison {type(op).__name__}")
        return [node.left, *node.comparators]
    if isinstance(node, ast.BoolOp):
        return list(node.values)
    if isinstance(node, ast.Call):
        name = node.func.id if isinstance(node.func, ast.Name) else None
        if name not in FUNCTIONS or node.keywords or any(
                isinstance(a, ast.Starred) for a in node.args):
            _refuse(node, expr)
        arity = FUNCTIONS[name][1]
        if (len(node.args) != arity) if arity else (len(node.args) < 2):
            wanted = f"{arity} argument{'s' * (arity > 1)}" if arity else "two or more arguments"
            snippet = ast.get_source_segment(expr.text.strip(), node) or name
            raise ValueError(f"expression {_short(expr.text)}: {name} takes {wanted}, got "
                             f"{len(node.args)} in {_short(snippet)}")
        return list(node.args)
    return []


def _evaluate(node: ast.AST, x: np.ndarray, expr: Expression):
    """Walk a checked tree; numbers become floats so ``9**9**9`` overflows to inf.
    A function outside its domain, or a comparison of a NaN or inf, is refused."""
    if isinstance(node, ast.Constant):
        return np.float64(node.value)
    if isinstance(node, ast.Name):
        return np.pi if node.id == "pi" else x[_COORDS.index(node.id)]
    if isinstance(node, ast.Call):
        return _call(node, [_evaluate(a, x, expr) for a in node.args], x, expr)
    if isinstance(node, ast.BinOp):
        return _ARITH[type(node.op)](_evaluate(node.left, x, expr),
                                     _evaluate(node.right, x, expr))
    if isinstance(node, ast.UnaryOp):
        value = _evaluate(node.operand, x, expr)
        if isinstance(node.op, ast.Not):
            return np.logical_not(value)
        return -value if isinstance(node.op, ast.USub) else +value
    if isinstance(node, ast.Compare):
        values = (node.left, *node.comparators)
        operands = [_evaluate(v, x, expr) for v in values]
        for v, operand in zip(values, operands, strict=True):
            snippet = ast.get_source_segment(expr.text.strip(), v) or "an operand"
            _finite(operand, x, expr, f"expression {_short(expr.text)}: the compared value "
                                      f"{_short(snippet)} is NaN or inf")
        result, left = True, operands[0]
        for op, right in zip(node.ops, operands[1:], strict=True):
            result = np.logical_and(result, _COMPARE[type(op)](left, right))
            left = right
        return result
    if isinstance(node, ast.BoolOp):
        combine = np.logical_and if isinstance(node.op, ast.And) else np.logical_or
        values = [_evaluate(v, x, expr) for v in node.values]
        result = values[0]
        for v in values[1:]:
            result = combine(result, v)
        return result
    raise AssertionError(f"unchecked node {type(node).__name__}")  # _check prevents this


def _call(node: ast.Call, args: list, x: np.ndarray, expr: Expression):
    """``name(*args)`` from :data:`FUNCTIONS`; refused where it is not finite but its
    arguments are (outside its domain), naming a point and the argument there."""
    name = node.func.id
    function, arity, domain = FUNCTIONS[name]
    value = function(*args) if arity else _reduce(function, args)
    bad = ~np.isfinite(value) & _reduce(np.logical_and, [np.isfinite(a) for a in args])
    if np.any(bad):
        count, first = _at(bad, x)
        given = ", ".join(f"{np.broadcast_to(a, x.shape[1:])[first]:.6g}" for a in args)
        snippet = ast.get_source_segment(expr.text.strip(), node) or name
        part = "" if snippet == expr.text.strip() else f": {_short(snippet)}"
        raise ValueError(f"expression {_short(expr.text)}{part} is undefined "
                         f"or infinite at {count}, e.g. {name}({given}) at "
                         f"{_point(x, first)}; {name} needs {domain or 'finite arguments'}")
    return value


def _reduce(function, args: list):
    result = args[0]
    for a in args[1:]:
        result = function(result, a)
    return result
