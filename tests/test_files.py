"""Files on disk: what cannot be read is named without being opened; a set of files is
written as one (the result files' tests, with kills and concurrent writers, are in
tests/test_io.py)."""
import errno
import os
import threading

import pytest

from skxfem.fem.files import check_folder, quiet, read_bytes, regular_file, write_set


def test_01_what_is_not_a_regular_file_is_named(tmp_path):
    (tmp_path / "folder").mkdir()
    os.mkfifo(tmp_path / "fifo")
    os.symlink(tmp_path / "loop2", tmp_path / "loop1")
    os.symlink(tmp_path / "loop1", tmp_path / "loop2")
    os.symlink(tmp_path / "missing", tmp_path / "dangling")
    cases = {"folder": (IsADirectoryError, "is a folder"),
             "fifo": (ValueError, "is a FIFO"),
             "loop1": (ValueError, "loop of symbolic links"),
             "dangling": (FileNotFoundError, "does not exist"),
             "nothing": (FileNotFoundError, "does not exist"),
             "/dev/zero": (ValueError, "is a character device"),
             "/dev/null": (ValueError, "is a character device")}
    for name, (error, words) in cases.items():
        with pytest.raises(error, match=words):
            regular_file(tmp_path / name, f"the file {name!r}")
    (tmp_path / "plain").write_text("x")
    os.symlink(tmp_path / "plain", tmp_path / "link")
    assert regular_file(tmp_path / "link", "the link") == tmp_path / "link"


def test_02_a_fifo_or_a_device_is_never_read(tmp_path):
    """A FIFO with no writer would block open() for ever, /dev/zero read() for ever:
    both are refused at once (run in a thread, so that a hang fails the test)."""
    os.mkfifo(tmp_path / "fifo")
    outcome = {}

    def attempt(path):
        try:
            read_bytes(path, "the scene file", 1000)
        except ValueError as e:
            outcome[path] = str(e)

    for path in (str(tmp_path / "fifo"), "/dev/zero"):
        t = threading.Thread(target=attempt, args=(path,), daemon=True)
        t.start()
        t.join(10)
        assert not t.is_alive(), f"reading {path} blocks"
        assert "not a regular file" in outcome[path]


def test_03_a_file_above_the_size_limit_is_refused(tmp_path):
    (tmp_path / "big").write_bytes(b"a" * 101)
    with pytest.raises(ValueError, match="larger than 100 bytes"):
        read_bytes(tmp_path / "big", "big", 100)
    assert read_bytes(tmp_path / "big", "big", 101) == b"a" * 101


def test_04_quiet_captures_both_streams(capfd):
    import sys
    with quiet() as said:
        print("out")
        print("err", file=sys.stderr)
    assert said.getvalue() == "out\nerr\n"
    assert capfd.readouterr() == ("", "")


def test_05_a_set_replaces_an_earlier_set_and_keeps_the_folder_mode(tmp_path):
    out = tmp_path / "a" / "b"
    write_set(out, {"x.txt": lambda p: p.write_text("1"), "y.txt": lambda p: p.write_text("1")})
    out.chmod(0o750)
    paths = write_set(out, {"x.txt": lambda p: p.write_text("2"),
                            "y.txt": lambda p: p.write_text("2")})
    assert {p.name: p.read_text() for p in out.iterdir()} == {"x.txt": "2", "y.txt": "2"}
    assert paths == {"x.txt": out / "x.txt", "y.txt": out / "y.txt"}
    assert out.stat().st_mode & 0o777 == 0o750
    assert sorted(p.name for p in (tmp_path / "a").iterdir()) == ["b"]


def test_06_a_failed_or_empty_write_leaves_the_earlier_set_or_nothing(tmp_path):
    def broken(path):
        path.write_text("half")
        raise OSError(errno.ENOSPC, "No space left on device")

    with pytest.raises(OSError, match="No space"):
        write_set(tmp_path / "new" / "out", {"x.txt": broken})
    assert list(tmp_path.iterdir()) == []                   # the parents created went too
    write_set(tmp_path / "out", {"x.txt": lambda p: p.write_text("1")})
    with pytest.raises(OSError, match="written empty"):
        write_set(tmp_path / "out", {"x.txt": lambda p: p.write_text("")})
    assert (tmp_path / "out" / "x.txt").read_text() == "1"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_07_check_folder_names_what_is_in_the_way(tmp_path, monkeypatch):
    (tmp_path / "file").write_text("")
    with pytest.raises(ValueError, match="is a file"):
        check_folder(tmp_path / "file", ["x.txt"])
    (tmp_path / "busy").mkdir()
    for name in ("a", "b", "c", "d"):
        (tmp_path / "busy" / name).write_text("")
    with pytest.raises(ValueError, match=r"\('a', 'b', 'c', \.\.\.\)"):
        check_folder(tmp_path / "busy", ["x.txt"])
    assert check_folder(tmp_path / "busy", ["a", "b", "c", "d"]) == tmp_path / "busy"
    monkeypatch.chdir(tmp_path / "busy")
    with pytest.raises(ValueError, match="current folder"):
        check_folder(tmp_path, ["x.txt"])


def test_08_a_file_system_without_locks_still_gets_its_set(tmp_path, monkeypatch):
    """Some network mounts refuse flock (ENOLCK): the set is written, unlocked."""
    from skxfem.fem import files

    def flock_fails(code, text):
        def flock(fd, operation):
            raise OSError(code, text)
        return flock

    monkeypatch.setattr(files.fcntl, "flock", flock_fails(errno.ENOLCK, "No locks available"))
    write_set(tmp_path / "out", {"x.txt": lambda p: p.write_text("1")})
    assert (tmp_path / "out" / "x.txt").read_text() == "1"
    monkeypatch.setattr(files.fcntl, "flock", flock_fails(errno.EBADF, "Bad file descriptor"))
    with pytest.raises(OSError, match="Bad file descriptor"):    # other errors are errors
        write_set(tmp_path / "out", {"x.txt": lambda p: p.write_text("2")})
    assert (tmp_path / "out" / "x.txt").read_text() == "1"
