"""The scene-file expression language: what it evaluates and what it refuses."""
import ast
import inspect

import numpy as np
import pytest

from skxfem import expr
from skxfem.expr import MAX_DEPTH, MAX_LENGTH, Expression, compile_expression

X2 = np.array([[0.0, 0.25, 0.5, 1.0], [1.0, 0.5, 0.0, 2.0]])
X3 = np.vstack([X2, [3.0, -1.0, 0.5, 0.0]])


@pytest.mark.parametrize("text, expected", [
    ("1", lambda x, y, z: np.ones_like(x)),
    ("x", lambda x, y, z: x),
    ("-x + +y", lambda x, y, z: -x + y),
    ("z - 0.5 - 0.2*x", lambda x, y, z: z - 0.5 - 0.2 * x),
    ("4*y*(1 - y)", lambda x, y, z: 4 * y * (1 - y)),
    ("x**2 / (1 + y**2)", lambda x, y, z: x ** 2 / (1 + y ** 2)),
    ("2**-1 * pi", lambda x, y, z: np.full_like(x, np.pi / 2)),
    ("1e-3 * (x - y) ** 3", lambda x, y, z: 1e-3 * (x - y) ** 3),
])
def test_01_formulas_evaluate_like_numpy(text, expected):
    got = Expression(text, 3)(X3)
    np.testing.assert_allclose(got, expected(*X3), err_msg=text)
    assert got.shape == (4,) and got.dtype == float


@pytest.mark.parametrize("text, mask", [
    ("x < 0.3", [True, True, False, False]),
    ("x <= 0.25 and y >= 0.5", [True, True, False, False]),
    ("x == 0 or y == 0", [True, False, True, False]),
    ("not x > 0.3", [True, True, False, False]),
    ("0.2 < x < 0.6", [False, True, True, False]),
    ("x != 1 and (y < 1e-9 or x < 1e-9)", [True, False, True, False]),
    ("x - 0.5 < 0 and not y > 1", [True, True, False, False]),
])
def test_02_selections_return_boolean_masks(text, mask):
    got = Expression(text, 2, boolean=True)(X2)
    assert got.dtype == bool
    assert got.tolist() == mask, text


def test_03_shape_follows_the_points():
    """Points (dim, ncells, nqp) give values (ncells, nqp), constants too."""
    x = np.random.default_rng(0).random((2, 5, 3))
    assert Expression("x*y", 2)(x).shape == (5, 3)
    np.testing.assert_array_equal(Expression("2", 2)(x), np.full((5, 3), 2.0))
    np.testing.assert_allclose(compile_expression("x*y", 2)(x), x[0] * x[1])


@pytest.mark.parametrize("text, construct", [
    ("sin(x)", "function call"),
    ("__import__('os').system('echo pwned')", "function call"),
    ("eval('1')", "function call"),
    ("x.real", "attribute access"),
    ("x.__class__", "attribute access"),
    ("(1).__class__.__bases__", "attribute access"),
    ("x[0]", "subscript"),
    ("lambda: 1", "lambda"),
    ("'abc'", "string"),
    ("f'{x}'", "string"),
    ("b'abc'", "constant"),
    ("True", "constant"),
    ("None", "constant"),
    ("1j", "constant"),
    ("...", "constant"),
    ("foo", "name"),
    ("os", "name"),
    ("__builtins__", "name"),
    ("e", "name"),
    ("[i for i in (1, 2)]", "comprehension"),
    ("(i for i in (1, 2))", "comprehension"),
    ("[1, 2]", "list"),
    ("(x, y)", "tuple"),
    ("{1: 2}", "dict"),
    ("{1}", "set"),
    ("x if y else 1", "if-else"),
    ("(x := 1)", "assignment"),
    ("x // 2", "FloorDiv"),
    ("x % 2", "Mod"),
    ("x @ y", "MatMult"),
    ("x << 1", "LShift"),
    ("x & y", "BitAnd"),
    ("~x", "Invert"),
    ("x < 1", "condition"),
    ("x and y", "condition"),
    ("not x", "condition"),
    ("(x < 1) + 1", "condition"),
])
def test_04_everything_else_is_refused_by_name(text, construct):
    with pytest.raises(ValueError, match="not allowed") as info:
        Expression(text, 2)
    assert construct in str(info.value), str(info.value)


@pytest.mark.parametrize("text, message", [
    ("x + 1", "must be a condition"),
    ("x is y", "comparison Is"),
    ("x in y", "comparison In"),
    ("(x < 1) + 1", "mixing numbers and conditions"),
    ("x < 1 and y", "mixing numbers and conditions"),
    ("-(x < 1)", "mixing numbers and conditions"),
    ("sin(x) < 1", "function call"),
])
def test_05_selections_refuse_non_conditions(text, message):
    with pytest.raises(ValueError, match=message):
        Expression(text, 2, boolean=True)


@pytest.mark.parametrize("text, message", [
    ("", "empty"),
    ("   ", "empty"),
    ("x +", "not valid"),
    ("import os", "not valid"),
    ("x = 1", "not valid"),
    ("x; y", "not valid"),
    ("1 +\n2", "not valid"),
    ("x" + " + x" * 300, "at most"),          # longer than MAX_LENGTH
    ("-" * 200 + "x", "nested"),              # deeper than MAX_DEPTH
    ("(" * 250 + "x" + ")" * 250, "not valid"),  # Python's own parenthesis limit
])
def test_06_malformed_long_and_deep_text_is_refused(text, message):
    with pytest.raises(ValueError, match=message):
        Expression(text, 2)


def test_07_limits_are_what_the_module_says():
    longest = "0." + "1" * (MAX_LENGTH - 2)
    assert Expression(longest, 2)(X2).shape == (4,)            # at the limit: accepted
    with pytest.raises(ValueError, match="at most"):
        Expression(longest + "1", 2)
    Expression("-" * (MAX_DEPTH - 1) + "x", 2)
    with pytest.raises(ValueError):
        Expression("-" * (MAX_DEPTH + 1) + "x", 2)


def test_08_z_on_a_2d_mesh_is_refused():
    with pytest.raises(ValueError, match="uses z but the mesh is 2D"):
        Expression("x + z", 2)
    assert Expression("x + z", 3)(X3).shape == (4,)


def test_09_wrong_inputs_are_refused():
    with pytest.raises(TypeError, match="string"):
        Expression(1.0, 2)
    with pytest.raises(ValueError, match="dim must be 2 or 3"):
        Expression("x", 4)
    with pytest.raises(ValueError, match=r"expected \(3, ...\)"):
        Expression("x", 3)(X2)


@pytest.mark.parametrize("text", ["1/x", "9**9**9", "(-1)**0.5", "0*x/0"])
def test_10_nan_and_inf_results_are_refused(text):
    """Numbers are floats: 9**9**9 overflows to inf (never a huge Python int)."""
    f = Expression(text, 2)
    with pytest.raises(ValueError, match="NaN or inf"):
        f(np.zeros((2, 3)))


def test_11_the_module_never_calls_eval_exec_or_compile():
    tree = ast.parse(inspect.getsource(expr))
    called = {node.func.id for node in ast.walk(tree)
              if isinstance(node, ast.Call) and isinstance(node.func, ast.Name)}
    assert not called & {"eval", "exec", "compile", "__import__", "getattr"}, called


def test_12_expressions_are_frozen_and_compare_by_text():
    a, b = Expression("x + 1", 2), Expression("x + 1", 2)
    assert a == b and a != Expression("x + 1", 3)
    with pytest.raises(AttributeError):
        a.text = "y"


@pytest.mark.parametrize("text", ["1" * 400, "1e999 * x", "x - " + "9" * 320])
def test_13_numbers_too_large_for_a_float_are_refused_when_parsed(text):
    """They raised OverflowError ('int too large to convert to float') at solve time."""
    with pytest.raises(ValueError, match="too large for floating point"):
        Expression(text, 2)
