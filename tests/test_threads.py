"""skxfem.linalg.threads: the solves run BLAS on one thread, whatever the caller's setting,
unless SKXFEM_THREADS or threads.using choose another number; the caller's setting
is given back afterwards."""
from pathlib import Path

import pytest
from threadpoolctl import threadpool_info, threadpool_limits

import skxfem
from skxfem import contact, scenes
from skxfem.app import cli
from skxfem.linalg import saddle, threads
from skxfem.linalg.threads import ENV, limited, using
from skxfem.studies import budget

STRIP = scenes.strip(2, cell="quad")
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def blas() -> set[int]:
    """The thread counts of the BLAS libraries loaded (numpy's, scipy's)."""
    return {d["num_threads"] for d in threadpool_info() if d["user_api"] == "blas"}


@pytest.fixture
def spy(monkeypatch):
    """Record the BLAS threads inside a function the solves call."""
    seen = []

    def watch(module, name):
        inner = getattr(module, name)

        def spying(*args, **kwargs):
            seen.append(blas())
            return inner(*args, **kwargs)
        monkeypatch.setattr(module, name, spying)
    watch.seen = seen
    return watch


def test_blas_is_loaded_and_can_be_threaded():
    """The premise of every test below: BLAS is there and takes 2 or 3 threads."""
    assert blas(), "numpy and scipy load a BLAS"
    for n in (2, 3):
        with threadpool_limits(n):
            assert blas() == {n}


@pytest.mark.parametrize("setting, inside", [(None, 1), ("", 1), ("1", 1), ("2", 2),
                                             (" 3 ", 3), ("off", 4), ("OFF", 4)])
def test_a_tie_solve_runs_the_threads_chosen(monkeypatch, spy, setting, inside):
    if setting is None:
        monkeypatch.delenv(ENV, raising=False)
    else:
        monkeypatch.setenv(ENV, setting)
    spy(saddle, "solve")
    with threadpool_limits(4):                  # the caller's: a threaded BLAS
        r = skxfem.solve(STRIP)
        assert blas() == {4}, "given back after the solve"
    assert spy.seen == [{inside}] and r.max_jump < 1e-10


def test_using_overrides_the_environment_and_nests(monkeypatch, spy):
    monkeypatch.setenv(ENV, "3")
    spy(saddle, "solve")
    with threadpool_limits(4):
        with using(2):
            assert threads.threads() == 2
            with using(None):
                skxfem.solve(STRIP)
            skxfem.solve(STRIP)
        skxfem.solve(STRIP)
    assert spy.seen == [{4}, {2}, {3}]


def test_a_contact_solve_and_the_command_line_run_one_thread(monkeypatch, spy, tmp_path):
    monkeypatch.delenv(ENV, raising=False)
    spy(contact.history, "assemble")
    spy(budget, "check")                        # skxfem run: before its solve
    with threadpool_limits(4):
        contact.solve(skxfem.load_scene(EXAMPLES / "contact.toml"))
        assert cli.main(["run", str(EXAMPLES / "strip.toml"), "--out", str(tmp_path / "o")]) == 0
        assert blas() == {4}
    assert spy.seen == [{1}, {1}]


@pytest.mark.parametrize("bad", ["0", "-1", "two", "1.5", "²", "on"])
def test_a_bad_setting_is_refused_by_name(monkeypatch, capsys, tmp_path, bad):
    monkeypatch.setenv(ENV, bad)
    with pytest.raises(ValueError, match=f"{ENV} must be a positive integer"):
        skxfem.solve(STRIP)
    assert cli.main(["run", str(EXAMPLES / "strip.toml"), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and ENV in err and not (tmp_path / "o").exists()


@pytest.mark.parametrize("bad, error", [(0, ValueError), (-2, ValueError), (True, TypeError),
                                        (1.0, TypeError), ("2", TypeError)])
def test_using_refuses_what_is_not_a_thread_count(bad, error):
    with pytest.raises(error, match=r"using\(n\) must be a positive integer or None"):
        with using(bad):
            pass


def test_limited_keeps_the_name_and_the_docstring():
    @limited
    def f(x):
        """Doc."""
        return x

    assert f(3) == 3 and f.__name__ == "f" and f.__doc__ == "Doc."
    assert skxfem.solve.__name__ == "solve" and "Result" in skxfem.solve.__doc__
