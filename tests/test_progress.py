import io

import pytest

from skxfem.studies.progress import Progress, steps


def test_progress_is_off_when_the_stream_is_not_a_terminal():
    out = io.StringIO()
    p = Progress(3, "run", stream=out)
    assert p.enabled is False
    assert p.step("a") >= 0
    assert out.getvalue() == ""


def test_progress_prints_one_line_per_step_with_elapsed_time():
    out = io.StringIO()
    times = iter([10.0, 10.5, 12.0])
    p = Progress(2, "study", enabled=True, stream=out, clock=lambda: next(times))
    p.step("n=8")
    p.step("n=16")
    assert out.getvalue().splitlines() == ["[study 1/2] n=8: 0.5 s (0.5 s in all)",
                                           "[study 2/2] n=16: 1.5 s (2.0 s in all)"]


def test_steps_yields_every_item_and_reports_each():
    out = io.StringIO()
    assert list(steps("abc", "letters", enabled=True, stream=out)) == ["a", "b", "c"]
    assert out.getvalue().count("\n") == 3 and "[letters 3/3] c:" in out.getvalue()


def test_progress_rejects_a_bad_total():
    with pytest.raises(ValueError, match="total must be a non-negative integer"):
        Progress(-1, "x")
