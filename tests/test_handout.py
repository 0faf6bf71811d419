"""skxfem handout: the course as a student gets it (issue 25, item 2).

The hand-out of this repository is written into a temporary folder, then used there
as a student would, with its own code (``PYTHONPATH`` = the hand-out): skxfem
imports from it, the exercises' tests fail as untouched stubs do (no word of a
missing solution), the grader says the same, and the students' book check passes
on a book made of the chapters' contracts, without the references.  A full book
build of the hand-out is too slow for a unit test (``make book`` there was run by
hand, see the commit that added this file).
"""
import html
import inspect
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from skxfem.app import graded
from skxfem.app.handout import INSTRUCTOR_TESTS, contents, files, main, write
from skxfem.stabilised import star_groups

ROOT = Path(__file__).resolve().parents[1]
EXERCISES = ROOT / "exercises"
NAMES = list(graded.graded())


@pytest.fixture(scope="module")
def handout(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("course") / "handout"
    assert main([str(out)]) == 0
    return out


def student(handout: Path, *args, **kwargs) -> subprocess.CompletedProcess:
    """``python ARGS`` in the hand-out, with its own skxfem (no instructor variable)."""
    env = {k: v for k, v in os.environ.items() if k != graded.INSTRUCTORS}
    env["PYTHONPATH"] = str(handout)
    return subprocess.run([sys.executable, *args], cwd=handout, env=env, capture_output=True,
                          text=True, timeout=600, **kwargs)


def test_the_handout_is_the_course_without_the_solutions(handout):
    tracked = set(files(ROOT))
    given = {p.relative_to(handout).as_posix() for p in handout.rglob("*") if p.is_file()}
    assert not any(name.startswith("exercises/solutions/") for name in given)
    assert not given & set(INSTRUCTOR_TESTS)
    assert given == {n for n in tracked if not n.startswith("exercises/solutions/")
                     and n not in INSTRUCTOR_TESTS} | {"exercises/library_answers.json"}
    for name in given - {"exercises/library_answers.json"}:
        if name.endswith("/exercise.py"):
            exercise = name.split("/")[1]
            assert (handout / name).read_text("utf-8") == graded.stub(exercise), name
        else:             # the library, the book, the tests: as they are
            assert (handout / name).read_bytes() == (ROOT / name).read_bytes(), name
    listed = json.loads((handout / "exercises" / "library_answers.json").read_text("utf-8"))
    assert listed == graded.library_answers()
    assert "skxfem.levelset.plane" in listed["exercises"]["01_levelset"]
    assert os.access(handout / ".ci" / "run", os.X_OK)
    assert not (handout / ".git").exists() and not (handout / ".venv").exists()


def test_the_handout_imports_its_own_skxfem(handout):
    done = student(handout, "-c", "import skxfem, skxfem.levelset as L; print(skxfem.__file__);"
                                  " print(L.circle((0, 0), 1)(__import__('numpy').zeros(2)))")
    assert done.returncode == 0, done.stderr
    where, value = done.stdout.split()
    assert where == str(handout / "skxfem" / "__init__.py")
    assert float(value) == -1.0                  # the library works: nothing is stripped


def test_the_handouts_stubs_fail_their_tests_as_stubs_do(handout):
    done = student(handout, "-m", "pytest", "exercises", "-p", "no:cacheprovider", "-q")
    assert done.returncode == 1, done.stdout[-3000:] + done.stderr[-3000:]
    failed = int(re.search(r"(\d+) failed", done.stdout).group(1))
    assert failed > 40 and " passed" not in done.stdout and " error" not in done.stdout
    assert done.stdout.count("NotImplementedError") >= failed
    assert "solution" not in done.stdout.lower(), done.stdout[-3000:]

    done = student(handout, "-m", "skxfem", "grade", "exercises", "--student", "ada")
    assert done.returncode == 1, done.stdout[-3000:] + done.stderr[-3000:]
    assert re.search(rf"^total\s+0/{failed}\s", done.stdout, flags=re.M), done.stdout
    assert done.stderr == ""
    report = json.loads((handout / "out" / "grades" / "exercises.json").read_text("utf-8"))
    assert report["student"] == "ada" and report["commit"] is None     # no git in it yet
    shutil.rmtree(handout / "out")

    done = student(handout, "-m", "skxfem", "grade", "exercises", "--impl=solution")
    assert done.returncode == 2 and len(done.stderr.splitlines()) == 1
    assert "the solutions stay with the instructor" in done.stderr
    done = student(handout, "-m", "skxfem", "handout", "elsewhere")  # no hand-out of a hand-out
    assert done.returncode == 2 and "no exercises/solutions/" in done.stderr


def fake_book(html: Path, pages: dict[str, str]) -> Path:
    html.mkdir(parents=True)
    for name, text in pages.items():
        (html / name).write_text(f"<html><body><pre>{text}</pre></body></html>", "utf-8")
    return html


def test_the_students_book_check_works_without_solutions(handout, tmp_path):
    """The hand-out's own check (python -m skxfem.app.graded): a book of contracts and
    stubs passes; a page showing the library's answer still fails it."""
    contracts = {f"{e}.html": html.escape("\n\n".join(
        graded.contract(f) for f in graded.answers(e).values() if f.__module__[:7] == "skxfem."))
        for e in NAMES}
    book = fake_book(tmp_path / "html", {"index.html": "skxfem", **contracts})
    stubs = graded.write_stubs(book / "_downloads", handout / "exercises")
    assert len(stubs) == len(NAMES)
    done = student(handout, "-m", "skxfem.app.graded", str(book))
    assert done.returncode == 0, done.stdout + done.stderr
    assert "none of the" in done.stdout and "8 exercises shown" in done.stdout

    (book / "stabilised.html").write_text(html.escape(inspect.getsource(star_groups)), "utf-8")
    done = student(handout, "-m", "skxfem.app.graded", str(book))
    assert done.returncode == 1 and "skxfem.stabilised.star_groups" in done.stderr, done.stderr
    assert "reference solution" not in done.stderr
    assert [p.split()[0] for p in graded.check_book(book, root=handout / "exercises")] \
        == ["stabilised.html"]
    assert graded.check_book(book, root=EXERCISES)[0].startswith("stabilised.html")

    checked = student(handout, "scripts/notebooks.py", "--check", str(book))
    assert checked.returncode == 1 and "levelset.html" in checked.stderr   # runs; no page


def test_the_handouts_makefile_builds_the_students_book_only(handout):
    if shutil.which("make") is None:
        pytest.skip("needs make")
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL")}
    done = subprocess.run(["make", "book-instructor"], cwd=handout, env=env,
                          capture_output=True, text=True)
    assert done.returncode == 2 and "make book builds the students' book" in done.stderr
    assert not (handout / ".venv").exists(), "refused before installing anything"
    done = subprocess.run(["make", "-n", "test"], cwd=handout, env=env, capture_output=True,
                          text=True)
    assert "jupyter-book build book/" in done.stdout and "SKXFEM_SOLUTIONS" not in done.stdout
    done = subprocess.run(["make", "-n", "test"], cwd=ROOT, env=env, capture_output=True,
                          text=True)
    assert "SKXFEM_SOLUTIONS=1" in done.stdout          # the instructor's clone: both books


def copy_course(tmp_path) -> Path:
    """The repository's files in a folder without git (the hand-out lists them by walking)."""
    root = tmp_path / "course"
    for name in files(ROOT):
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / name, root / name)
    return root


def test_a_solved_exercise_and_a_leaked_solution_are_never_handed_out(tmp_path, capsys):
    root = copy_course(tmp_path)
    assert set(files(root)) == set(files(ROOT))
    mine = root / "exercises" / "03_enrich" / "exercise.py"       # the instructor's try
    pristine = mine.read_text("utf-8")
    solved = re.sub(r'raise NotImplementedError\("heaviside[^\n]*',
                    "return np.where(phi < 0, -1.0, 1.0)  # solved", pristine)
    mine.write_text(solved + "\n\ndef helper():\n    return 1\n", encoding="utf-8")
    assert "# solved" in mine.read_text("utf-8")
    handed = contents(root)
    assert handed["exercises/03_enrich/exercise.py"].decode("utf-8") == pristine

    readme = root / "exercises" / "03_enrich" / "README.md"
    reference = (root / "exercises" / "solutions" / "03_enrich" / "reference.py").read_text()
    readme.write_text(readme.read_text("utf-8") + "\n```python\n" + reference + "```\n")
    out = tmp_path / "out"
    with pytest.raises(ValueError, match="exercises/03_enrich/README.md shows the code of "
                                         "solutions/03_enrich/reference.py"):
        write(out, root)
    assert not out.exists() and [p.name for p in tmp_path.iterdir()] == ["course"]

    readme.write_text("# 03\n", encoding="utf-8")
    (out / "x").mkdir(parents=True)
    with pytest.raises(FileExistsError, match="not an empty folder"):
        write(out, root)
    with pytest.raises(ValueError, match="inside the repository"):
        write(root / "handout", root)
    shutil.rmtree(out)
    assert "exercises/03_enrich/README.md" in write(out, root)
    assert main([str(out)]) == 2 and "not an empty folder" in capsys.readouterr().err
