"""Files on disk: a regular file checked before it is read, a set of files written as one.

**Reading.**  :func:`regular_file` says why a path cannot be read as a file
— missing, a folder, a loop of symbolic links, a FIFO, a device, a socket —
without opening it (opening a FIFO blocks until a writer comes; reading
``/dev/zero`` never ends).  :func:`read_bytes` opens without blocking,
checks the open file again (the path may have changed since) and reads at
most a given size.  :func:`quiet` captures what a library prints while it
works (meshio prints before it raises), so that a command prints one line.

**Writing a set.**  :func:`write_set` writes files that belong together
(a result and its views) so that a reader never finds files of two runs side
by side.  The files are written into a new hidden folder beside the target,
``.NAME.skxfem-new-TAG``, which then takes the target's place:

1. lock the parent folder (``flock``: concurrent writers take turns; the lock
   dies with its process) and remove what killed writers left beside the
   target — putting back the previous result if a writer died between the two
   renames of step 3;
2. write every file into the new folder; an error removes it;
3. rename the previous folder aside (``.NAME.skxfem-old-TAG``), the new one
   into its place, and remove the previous one.

At every moment the target holds one whole set, or (between the two renames of
step 3) nothing.  Because the whole folder is replaced, it may hold nothing
but the set (:func:`check_folder`).

>>> import tempfile
>>> folder = Path(tempfile.mkdtemp()) / "out"
>>> paths = write_set(folder, {"a.txt": lambda p: p.write_text("1"),
...                            "b.txt": lambda p: p.write_text("2")})
>>> sorted(p.name for p in folder.iterdir()), paths["b.txt"].read_text()
(['a.txt', 'b.txt'], '2')
"""
from __future__ import annotations

import contextlib
import errno
import fnmatch
import io
import os
import re
import secrets
import shutil
import stat
from pathlib import Path
from typing import Callable, Iterator

try:
    import fcntl
except ImportError:  # Windows: no lock; a single writer is then assumed
    fcntl = None

__all__ = ["regular_file", "read_bytes", "quiet", "check_folder", "write_set"]

_KINDS = ((stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"))


def _kind(mode: int) -> str:
    return next((name for test, name in _KINDS if test(mode)), "not a regular file")


def regular_file(path, what: str) -> Path:
    """``path`` as a Path if it names a regular file (symbolic links followed).

    Nothing is opened.  ``what`` starts the message, e.g. ``"the scene file 'a.toml'"``.

    Raises
    ------
    FileNotFoundError
        If nothing is at ``path``.
    IsADirectoryError
        If it is a folder.
    ValueError
        If it is a loop of symbolic links, a FIFO, a device or a socket, or
        cannot be examined (permissions).

    >>> regular_file("/dev/null", "the scene file")
    Traceback (most recent call last):
    ...
    ValueError: the scene file is a character device, not a regular file; give the path of a file
    """
    path = Path(path)
    try:
        mode = path.stat().st_mode
    except OSError as e:
        if e.errno == errno.ELOOP:
            raise ValueError(f"{what} is a loop of symbolic links; give the path of a "
                             f"file") from None
        if e.errno in (errno.ENOENT, errno.ENOTDIR):
            raise FileNotFoundError(errno.ENOENT, f"{what} does not exist; check the path",
                                    str(path)) from None
        raise ValueError(f"{what} cannot be read ({e.strerror or e})") from None
    if stat.S_ISDIR(mode):
        raise IsADirectoryError(errno.EISDIR, f"{what} is a folder; give the path of a file",
                                str(path))
    if not stat.S_ISREG(mode):
        raise ValueError(f"{what} is {_kind(mode)}, not a regular file; give the path of a "
                         f"file")
    return path


def read_bytes(path, what: str, max_bytes: int) -> bytes:
    """The content of the regular file ``path``, refused above ``max_bytes``.

    Checked by :func:`regular_file`, then opened without blocking and checked
    again on the open file, so that a FIFO or a device is never read.

    >>> import tempfile
    >>> f = Path(tempfile.mkdtemp()) / "a.txt"
    >>> _ = f.write_text("hello")
    >>> read_bytes(f, "a.txt", 100)
    b'hello'
    """
    path = regular_file(path, what)
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as e:
        raise ValueError(f"{what} cannot be read ({e.strerror or e}); check that it is a "
                         f"readable file") from None
    with os.fdopen(fd, "rb") as f:
        mode = os.fstat(f.fileno()).st_mode
        if not stat.S_ISREG(mode):
            raise ValueError(f"{what} is {_kind(mode)}, not a regular file; give the path "
                             f"of a file")
        data = f.read(max_bytes + 1)
    if len(data) > max_bytes:
        raise ValueError(f"{what} is larger than {max_bytes} bytes; this is not the "
                         f"file you meant")
    return data


@contextlib.contextmanager
def quiet() -> Iterator[io.StringIO]:
    """Capture what is printed on stdout and stderr inside the block, unwrapped: a
    library that formats for a terminal (meshio prints with rich, 80 columns when the
    output is no terminal) sees one of :data:`UNWRAPPED` columns, so a long path in its
    message stays whole.

    >>> with quiet() as said:
    ...     print("Error: cannot read")
    >>> said.getvalue()
    'Error: cannot read\\n'
    """
    said = io.StringIO()
    columns = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = str(UNWRAPPED)
    try:
        with contextlib.redirect_stdout(said), contextlib.redirect_stderr(said):
            yield said
    finally:
        if columns is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = columns


UNWRAPPED = 100_000
"""The terminal width :func:`quiet` announces (``COLUMNS``) while it captures."""


def _ours(name: str, names) -> bool:
    """A file of the set (a name with ``*`` is a pattern: ``displacement_*.vtu``, the
    files of a series), or a temporary one a killed earlier writer left inside it
    (``.result-PID-HEX.json``: the temporary names of skxfem up to 0.1)."""
    if name in names or any("*" in n and fnmatch.fnmatchcase(name, n) for n in names):
        return True
    return any(re.fullmatch(rf"\.{re.escape(Path(n).stem)}-\d+-[0-9a-f]{{8}}"
                            rf"{re.escape(Path(n).suffix)}", name) for n in names)


HIDDEN = len(".") + len(".skxfem-new-") + 16
"""The bytes :func:`write_set` adds to a folder's name for its hidden folders."""


def check_name_lengths(folder, longest: int = 0) -> None:
    """Refuse a folder whose name, or a name in its path, is longer in bytes than the
    file system takes (255 bytes a name on most: 85 CJK characters), keeping
    :data:`HIDDEN` bytes for the hidden folder of :func:`write_set`, and a path longer
    than 4095 bytes with a file name of ``longest`` bytes in it: so that the results
    can be written, checked before anything is solved.

    >>> check_name_lengths("results/" + "結" * 80)
    Traceback (most recent call last):
    ...
    ValueError: output folder name '結結結結結結結結結結結結...' is 240 bytes long ...
    """
    path = Path(os.path.abspath(folder))
    existing = Path(path.anchor)
    for part in path.parts[1:]:             # the deepest existing folder, from the root
        try:
            if not (existing / part).is_dir():
                break
        except OSError:                     # a name too long to look up
            break
        existing = existing / part
    try:
        name_max = os.pathconf(existing, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        name_max = 255
    try:
        path_max = os.pathconf(existing, "PC_PATH_MAX")
    except (OSError, ValueError, AttributeError):
        path_max = 4096
    parts = path.parts[1:]
    for k, part in enumerate(parts):
        size, top = len(os.fsencode(part)), name_max - (HIDDEN if k == len(parts) - 1 else 0)
        if size > top:
            shown = part if len(part) <= 12 else part[:12] + "..."
            why = (f" (its limit {name_max} less {HIDDEN} for the hidden folder the results "
                   f"are written into first)" if k == len(parts) - 1 else "")
            raise ValueError(f"output folder {'name' if why else 'path holds the name'} "
                             f"{shown!r} is {size} bytes long (UTF-8), more than the {top} "
                             f"the file system takes{why}: give a shorter --out")
    size = len(os.fsencode(str(path))) + HIDDEN + 1 + longest
    if size >= path_max:
        raise ValueError(f"output folder path is {len(os.fsencode(str(path)))} bytes long, "
                         f"too long for the file system ({path_max} bytes with the names "
                         f"of the results): give a shorter --out")


def check_folder(folder, names) -> Path:
    """``folder`` if :func:`write_set` may replace it by a set of files ``names``.

    It may be missing, or a folder holding files of the set only (an earlier
    result); nothing is created.

    Raises
    ------
    ValueError
        If ``folder`` is a file, holds anything else, or is (or contains) the
        current folder.

    >>> check_folder("results/plate", ["result.json"]).name
    'plate'
    """
    folder = Path(folder)
    check_name_lengths(folder, max(len(n) for n in names) if names else 0)
    real, here = Path(os.path.realpath(folder)), Path.cwd().resolve()
    if real == here or real in here.parents:
        raise ValueError(f"output folder {str(folder)!r} is the current folder or contains "
                         f"it; give a new folder below it (the results replace the whole "
                         f"folder)")
    if folder.is_dir():
        other = sorted(n for n in os.listdir(folder) if not _ours(n, names))
        if other:
            shown = ", ".join(repr(n) for n in other[:3]) + (", ..." if len(other) > 3 else "")
            raise ValueError(f"output folder {str(folder)!r} holds files that are not results "
                             f"({shown}); the results replace the whole folder: give a new "
                             f"folder, or one holding an earlier result only")
    elif folder.exists():
        raise ValueError(f"output folder {str(folder)!r} is a file; give another output "
                         f"folder")
    return folder


def _stale(parent: Path, name: str, target: Path):
    """Remove what killed writers of ``target`` left in ``parent`` (under the lock)."""
    pattern = re.compile(rf"\.{re.escape(name)}\.skxfem-(new|old)-[0-9a-f]{{16}}")
    for entry in sorted(os.listdir(parent), reverse=True):   # "old" before "new"
        match = pattern.fullmatch(entry)
        if match is None:
            continue
        if match.group(1) == "old" and not target.exists():
            os.rename(parent / entry, target)     # killed between the renames: put it back
        else:
            shutil.rmtree(parent / entry, ignore_errors=True)


@contextlib.contextmanager
def _locked(folder: Path):
    """An exclusive lock on ``folder`` (none without fcntl, or where the file system
    has no locks, e.g. some network mounts: a single writer is then assumed)."""
    if fcntl is None:
        yield
        return
    fd = os.open(folder, os.O_RDONLY)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX)
        except OSError as e:
            if e.errno not in (errno.ENOLCK, errno.EOPNOTSUPP, errno.EINVAL):
                raise
        yield
    finally:
        os.close(fd)                                # releases the lock


def _commit(new: Path, target: Path, aside: Path):
    """Put ``new`` in the place of ``target`` (the previous one via ``aside``)."""
    if target.exists():
        os.rename(target, aside)
        os.rename(new, target)
        shutil.rmtree(aside)
    else:
        os.rename(new, target)


def write_set(folder, writers: dict[str, Callable[[Path], None]],
              also: tuple = ()) -> dict[str, Path]:
    """Write the files ``writers`` names into ``folder``, as one set (module notes).

    Parameters
    ----------
    folder
        The target folder: missing (created, with its parents) or holding an
        earlier set only (:func:`check_folder`); it is replaced as a whole.
    writers
        ``{file name: write(path)}``: each function writes one file's content
        to the path it is given.
    also
        Other names (or patterns with ``*``) of files of such sets, which an earlier
        set in ``folder`` may hold (:func:`check_folder`): a longer series.

    Returns
    -------
    dict
        ``{file name: path}`` in ``folder``.

    Raises
    ------
    ValueError
        From :func:`check_folder`.
    OSError
        If a file cannot be written (e.g. a full disk) or is written empty;
        ``folder`` keeps its previous set (or does not exist).
    """
    given = check_folder(folder, [*writers, *also])
    target = Path(os.path.realpath(given))
    parent, tag = target.parent, secrets.token_hex(8)
    new = parent / f".{target.name}.skxfem-new-{tag}"
    aside = parent / f".{target.name}.skxfem-old-{tag}"
    created = [p for p in (parent, *parent.parents) if not p.exists()]
    parent.mkdir(parents=True, exist_ok=True)
    try:
        with _locked(parent):
            _stale(parent, target.name, target)
            check_folder(given, [*writers, *also])   # again: another writer may have gone first
            os.mkdir(new)
            if target.is_dir():
                os.chmod(new, stat.S_IMODE(target.stat().st_mode))
            for name, write in writers.items():
                write(new / name)
                if (new / name).stat().st_size == 0:
                    raise OSError(errno.EIO, f"{name} was written empty")
            _commit(new, target, aside)
    except BaseException:
        shutil.rmtree(new, ignore_errors=True)
        if aside.exists() and not target.exists():
            os.rename(aside, target)
        for path in created:                     # innermost first; only if left empty
            try:
                path.rmdir()
            except OSError:
                break
        raise
    return {name: given / name for name in writers}
