"""The scene-file expression language: what it evaluates and what it refuses."""
import ast
import inspect

import numpy as np
import pytest

from skxfem.scene import expr
from skxfem.scene.expr import MAX_DEPTH, MAX_LENGTH, Expression

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
    np.testing.assert_allclose(Expression("x*y", 2)(x), x[0] * x[1])


@pytest.mark.parametrize("text, construct", [
    ("sine(x)", "function call"),
    ("__import__('os').system('echo pwned')", "function call"),
    ("eval('1')", "function call"),
    ("open('/etc/passwd')", "function call"),
    ("exec('1')", "function call"),
    ("getattr(x, 'real')", "function call"),
    ("np.sin(x)", "function call"),
    ("math.sqrt(x)", "function call"),
    ("sqrt(x)(y)", "function call"),
    ("(lambda: 1)()", "function call"),
    ("sqrt(x=1)", "function call"),
    ("sqrt(*[x])", "function call"),
    ("sqrt.__call__(x)", "function call"),
    ("sqrt(x).__class__", "attribute access"),
    ("sqrt(x.__class__)", "attribute access"),
    ("sqrt(__builtins__)", "name"),
    ("__import__", "name"),
    ("sqrt([i for i in (1, 2)])", "comprehension"),
    ("max(x, (i for i in (1, 2)))", "comprehension"),
    ("sqrt(lambda: 1)", "lambda"),
    ("sqrt('x')", "string"),
    ("sqrt(x < 1)", "condition"),
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
    ("sine(x) < 1", "function call"),
    ("sin(x < 1) < 1", "condition"),
    ("sqrt(x) and y < 1", "mixing numbers and conditions"),
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


GRID2 = np.random.default_rng(1).uniform(-0.9, 0.9, (2, 40))
GRID3 = np.random.default_rng(2).uniform(-0.9, 0.9, (3, 5, 8))   # (dim, cells, points)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("text, expected", [
    ("sqrt(x**2 + y**2)", lambda x, y, z: np.hypot(x, y)),
    ("abs(x - y)", lambda x, y, z: np.abs(x - y)),
    ("exp(-x) * cos(pi*y)", lambda x, y, z: np.exp(-x) * np.cos(np.pi * y)),
    ("log(2 + x)", lambda x, y, z: np.log(2 + x)),
    ("sin(x) + tan(y)", lambda x, y, z: np.sin(x) + np.tan(y)),
    ("asin(x) - acos(y) + atan(x*y)", lambda x, y, z: np.arcsin(x) - np.arccos(y)
     + np.arctan(x * y)),
    ("atan2(y, x)", lambda x, y, z: np.arctan2(y, x)),
    ("sinh(x) * cosh(y) - tanh(x + y)", lambda x, y, z: np.sinh(x) * np.cosh(y)
     - np.tanh(x + y)),
    ("min(x, y)", lambda x, y, z: np.minimum(x, y)),
    ("max(x, y, 0.5)", lambda x, y, z: np.maximum(np.maximum(x, y), 0.5)),
    ("sqrt(abs(max(x, -y)))", lambda x, y, z: np.sqrt(np.abs(np.maximum(x, -y)))),
    ("2*sqrt(4)", lambda x, y, z: np.full_like(x, 4.0)),
])
def test_14_functions_evaluate_like_numpy_in_2d_and_3d(dim, text, expected):
    x = GRID2 if dim == 2 else GRID3
    got = Expression(text, dim)(x)
    assert got.shape == x.shape[1:] and got.dtype == float
    np.testing.assert_allclose(got, expected(*x[:2], None), rtol=1e-14, err_msg=text)
    if dim == 3:    # z in a function
        np.testing.assert_allclose(Expression("sqrt(x**2 + y**2 + z**2)", 3)(x),
                                   np.linalg.norm(x, axis=0), rtol=1e-14)


def test_15_functions_in_selections():
    x = GRID2
    got = Expression("sqrt((x - 0.1)**2 + y**2) < 0.5 and not abs(y) > 0.3", 2,
                     boolean=True)(x)
    np.testing.assert_array_equal(got, (np.hypot(x[0] - 0.1, x[1]) < 0.5)
                                  & ~(np.abs(x[1]) > 0.3))


@pytest.mark.parametrize("text, function, where", [
    ("sqrt(-1)", "sqrt", "sqrt(-1)"),
    ("sqrt(x - 2)", "sqrt", "sqrt(-2)"),
    ("1 + log(x)", "log", "log(0)"),
    ("log(x - 1)", "log", "log(-1)"),
    ("asin(2*y)", "asin", "asin(2)"),
    ("acos(y + 1)", "acos", "acos(2)"),
    ("exp(1000*(y + 0.5))", "exp", "exp(1500)"),
    ("cosh(800 + y)", "cosh", "cosh(801)"),
])
def test_16_a_function_outside_its_domain_is_refused_by_name(text, function, where):
    """Not a NaN handed to a solve: the function, its domain and a point where it failed."""
    x = np.array([[0.0, 0.5, 1.0], [1.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="is undefined or infinite") as info:
        Expression(text, 2)(x)
    message = str(info.value)
    assert f"{function} needs" in message and where in message, message
    assert "(x, y) = (" in message, message
    with pytest.raises(ValueError, match="is undefined or infinite"):
        Expression(f"{text} < 1", 2, boolean=True)(x)      # a selection too


@pytest.mark.parametrize("text, message", [
    ("sqrt", "sqrt is a function; call it"),
    ("x + pi*sin", "sin is a function; call it"),
    ("sqrt(x, y)", "sqrt takes 1 argument, got 2"),
    ("sqrt()", "sqrt takes 1 argument, got 0"),
    ("atan2(y)", "atan2 takes 2 arguments, got 1"),
    ("min(x)", "min takes two or more arguments, got 1"),
    ("max()", "max takes two or more arguments, got 0"),
])
def test_17_functions_need_their_arguments(text, message):
    with pytest.raises(ValueError, match=message):
        Expression(text, 2)


def test_18_a_comparison_of_nan_or_inf_is_refused():
    """It would be False silently (NaN < 1) and select nothing."""
    with pytest.raises(ValueError, match="the compared value '1/x' is NaN or inf"):
        Expression("1/x < 1", 2, boolean=True)(np.zeros((2, 2)))


def test_19_the_functions_are_the_documented_ones():
    import re
    documented = set()
    for literal in re.findall(r"``([^`]+)``", expr.__doc__.split("Allowed only")[0]):
        documented |= set(re.findall(r"([a-z][a-z0-9]*)\(", literal) or literal.split())
    assert set(expr.FUNCTIONS) <= documented, set(expr.FUNCTIONS) - documented
    assert all(callable(f) and isinstance(n, int) for f, n, _ in expr.FUNCTIONS.values())
