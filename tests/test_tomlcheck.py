"""skxfem.tomlcheck: each check names the key and what it should be."""
import pytest

from skxfem.expr import Expression
from skxfem.tomlcheck import array, choice, formula, keys, number, one_of, table, vector


def test_accepted_values():
    assert table({"E": 1}, "[material]", ("E", "nu")) == {"E": 1}
    assert array({"load": [{"boundary": "ymax"}]}, "load") == [{"boundary": "ymax"}]
    assert array({}, "load") == []
    assert one_of({"file": "m.msh"}, ("box", "file"), "[mesh]") == "file"
    assert choice("vital", ("naive", "vital"), "space") == "vital"
    assert number(3, "E") == 3.0 and isinstance(number(3, "E"), float)
    assert vector([0, 1.5], "point", 2) == [0.0, 1.5]
    assert formula(2, "x", 2) == 2.0
    f = formula("4*x*(1 - x)", "pressure", 2)
    assert isinstance(f, Expression) and f.dim == 2
    assert isinstance(formula("x < 1e-9", "where", 2, boolean=True), Expression)


@pytest.mark.parametrize("call, error, match", [
    (lambda: table([1], "[material]", ("E",)), TypeError, r"\[material\] must be a table"),
    (lambda: keys({"G": 1}, ("E", "nu"), "[material]"), ValueError, "unknown key 'G'; allowed"),
    (lambda: array({"load": {"a": 1}}, "load"), TypeError, r"\[\[load\]\] tables"),
    (lambda: one_of({"box": 1, "file": 2}, ("box", "file"), "[mesh]"), ValueError,
     "exactly one of box, file; got box, file"),
    (lambda: choice("magic", ("naive", "vital"), "space"), ValueError, "space must be one of"),
    (lambda: number(True, "E"), TypeError, "E must be a number"),
    (lambda: number("1", "E"), TypeError, "E must be a number"),
    (lambda: vector([0, 1], "point", 3), ValueError, "list of 3 numbers on a 3D mesh"),
    (lambda: formula("__import__('os')", "pressure", 2), ValueError, "^pressure: "),
    (lambda: formula(1.0, "where", 2, boolean=True), TypeError, "condition string"),
])
def test_refusals_name_the_key(call, error, match):
    with pytest.raises(error, match=match):
        call()
