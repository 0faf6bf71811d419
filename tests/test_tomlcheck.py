"""skxfem.scene.tomlcheck: each check names the key and what it should be."""
import os
import threading

import pytest

from skxfem.scene.expr import Expression
from skxfem.scene.tomlcheck import (
    MAX_BYTES,
    array,
    choice,
    formula,
    keys,
    number,
    one_of,
    read_toml,
    table,
    vector,
)


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


def run_briefly(call, seconds=10):
    """``call()`` in a thread: its exception, or a failure if it is still running."""
    outcome = []

    def target():
        try:
            call()
            outcome.append(None)
        except Exception as e:  # noqa: BLE001  (returned to the test)
            outcome.append(e)

    t = threading.Thread(target=target, daemon=True)
    t.start()
    t.join(seconds)
    assert not t.is_alive(), "it blocks (a FIFO opened, or a device read for ever)"
    return outcome[0]


def test_a_fifo_or_a_device_is_refused_without_being_read(tmp_path):
    """A FIFO as the scene file blocked for ever; /dev/zero was read until memory ran out."""
    os.mkfifo(tmp_path / "scene.toml")
    for path, words in ((tmp_path / "scene.toml", "is a FIFO (named pipe)"),
                        ("/dev/zero", "is a character device")):
        error = run_briefly(lambda p=path: read_toml(p))
        assert isinstance(error, ValueError) and words in str(error), error
        assert "not a regular file" in str(error)


def test_deep_nesting_and_huge_files_are_one_clear_error(tmp_path):
    """TOML nested 500 deep raised RecursionError (exit 1 in the command line)."""
    deep = tmp_path / "deep.toml"
    for opening, closing in (("[", "]"), ("{a = ", "}")):
        deep.write_text("x = " + opening * 500 + "1" * (opening == "[") + closing * 500)
        with pytest.raises(ValueError, match=r"^deep.toml: invalid TOML: .*nested too deeply"):
            read_toml(deep)
    big = tmp_path / "big.toml"
    big.write_text("# " + "x" * MAX_BYTES + "\n")
    with pytest.raises(ValueError, match=f"larger than {MAX_BYTES} bytes"):
        read_toml(big)
