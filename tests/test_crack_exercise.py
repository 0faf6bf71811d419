"""Exercise 08 (the crack-tip branch functions) grades right: its reference passes, its
untouched stub fails test by test, each plausible wrong answer is rejected with the
message its file announces, and a file reusing skxfem.crack is refused.

(tests/test_exercises.py checks the same of every exercise generically; this file names
the wrong answers of 08 one by one, so that losing one is an error here.)
"""
import ast
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXERCISES = ROOT / "exercises"
FOLDER = EXERCISES / "08_crack"
WRONG = ["swapped_atan2", "full_angle", "gradient_sign", "no_sqrt"]


class Recorder:
    def __init__(self):
        self.tests = {}

    def pytest_runtest_logreport(self, report):
        if report.when == "call" or report.outcome != "passed":
            self.tests[report.nodeid] = (report.outcome, report.longreprtext)


def run(*args) -> dict:
    recorder = Recorder()
    pytest.main([*map(str, args), "-p", "no:cacheprovider", "-q"], plugins=[recorder])
    assert recorder.tests, "no test ran"
    return recorder.tests


def test_the_reference_passes_every_test():
    tests = run(FOLDER, "--impl=solution")
    assert len(tests) == 7 and all(o == "passed" for o, _ in tests.values()), tests


def test_the_stub_fails_every_test_with_not_implemented():
    tests = run(FOLDER)
    assert len(tests) == 7
    assert all(o == "failed" and "NotImplementedError" in t for o, t in tests.values())


@pytest.mark.parametrize("wrong", WRONG)
def test_each_wrong_answer_is_rejected_with_its_message(wrong):
    path = EXERCISES / "solutions" / "08_crack" / f"wrong_{wrong}.py"
    expect = ast.literal_eval(next(n.value for n in ast.parse(path.read_text("utf-8")).body
                                   if isinstance(n, ast.Assign) and n.targets[0].id == "EXPECT"))
    tests = run(FOLDER, f"--impl=wrong:{wrong}")
    failed = [t for o, t in tests.values() if o == "failed"]
    assert failed, f"no test rejects wrong_{wrong}.py"
    assert any(expect in t for t in failed), (expect, failed)


def test_reusing_skxfem_crack_fails_the_grade(tmp_path):
    target = tmp_path / "exercises"
    target.mkdir()
    shutil.copy(EXERCISES / "conftest.py", target / "conftest.py")
    shutil.copytree(FOLDER, target / "08_crack", ignore=shutil.ignore_patterns("__pycache__"))
    (target / "08_crack" / "exercise.py").write_text(
        "from skxfem.crack.branch import branch as branch_functions\n"
        "from skxfem.crack.branch import branch_local_gradient as branch_gradients\n"
        "from skxfem.crack.frame import polar as polar_coordinates\n", encoding="utf-8")
    tests = run(target / "08_crack", "--rootdir", tmp_path, "--import-mode=importlib")
    assert len(tests) == 7
    assert all(o == "failed" and "uses the library's own implementation" in t
               for o, t in tests.values()), tests
