"""The book's Getting started page: one set-up path, followed from a fresh clone.

The page's commands are read from the page itself.  The fresh-clone test clones
this repository into a temporary folder and runs the student's commands there, one
by one, in the clone: ``make install``, the exercise's tests, its score table; then
the instructor's commands that need no book build.  To stay fast and offline for the
dependencies, the clone's ``.venv`` is created beforehand with this environment's
packages visible (a ``.pth`` line to its site-packages) and the ``pytest`` entry point
that their install would have written; ``make install`` then really runs
``pip install -e '.[viz,book,dev]'``, which finds every dependency there and installs
skxfem from the clone (its build back-end, setuptools, is fetched by pip as usual).
"""
import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "book" / "getting-started.md"


def commands(section: str) -> list[str]:
    """The commands of the bash blocks under ``## section``, comments removed."""
    text = PAGE.read_text(encoding="utf-8")
    body = re.search(rf"^## {section}\n(.*?)(?=^## |\Z)", text, flags=re.S | re.M).group(1)
    blocks = re.findall(r"```bash\n(.*?)```", body, flags=re.S)
    lines = (line.split("  #", 1)[0].strip() for block in blocks for line in block.splitlines())
    return [line for line in lines if line and not line.startswith("#")]


STUDENT, INSTRUCTOR, COMMAND_LINE = (commands(s) for s in
                                     ("Student", "Instructor", "Command line"))
EXERCISE_READMES = sorted((ROOT / "exercises").glob("0*/README.md"))


def test_the_page_gives_one_path():
    assert STUDENT[:3] == ["git clone REPOSITORY skxfem", "cd skxfem", "make install"]
    assert STUDENT[3:5] == [".venv/bin/pytest exercises/01_levelset",
                            ".venv/bin/skxfem grade exercises/01_levelset"]
    assert "- file: getting-started" in (ROOT / "book" / "_toc.yml").read_text()
    targets = set(re.findall(r"^([\w-]+):", (ROOT / "Makefile").read_text(), flags=re.M))
    used = {c.split()[1] for c in STUDENT + INSTRUCTOR + COMMAND_LINE if c.startswith("make ")}
    assert used <= targets and {"install", "book", "book-instructor", "notebooks"} <= used
    cli = subprocess.run([sys.executable, "-m", "skxfem", "--help"], capture_output=True,
                         text=True).stdout
    for c in STUDENT + INSTRUCTOR + COMMAND_LINE:
        if c.startswith(".venv/bin/skxfem ") and not c.split()[1].startswith("-"):
            assert c.split()[1] in cli, c
    assert (ROOT / "examples" / "plate.toml").is_file()


@pytest.mark.parametrize("readme", EXERCISE_READMES, ids=lambda p: p.parent.name)
def test_every_exercise_readme_says_the_same(readme):
    name = readme.parent.name
    text = readme.read_text(encoding="utf-8")
    assert f".venv/bin/pytest exercises/{name}" in text
    assert f".venv/bin/skxfem grade exercises/{name}" in text
    assert "make install" in text
    assert "](../../" not in text, "a handout has no book or code next to it: no relative link"


def test_readme_book_and_exercises_have_no_other_path():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "make install" in readme and "book/getting-started.md" in readme
    assert ".venv/bin/pytest exercises/01_levelset" in readme
    assert ".venv/bin/skxfem grade exercises/01_levelset" in readme
    chapters = [p for p in (ROOT / "book").glob("*.md") if "## Graded exercise" in p.read_text()]
    assert len(chapters) == len(EXERCISE_READMES) == 8
    for chapter in chapters:
        text = chapter.read_text(encoding="utf-8")
        name = re.search(r"exercises/(\d\d_\w+)/exercise\.py", text).group(1)
        assert f".venv/bin/skxfem grade exercises/{name}" in text, chapter.name
        assert "(getting-started.md)" in text, chapter.name
    texts = [ROOT / "README.md", ROOT / "exercises" / "README.md", *EXERCISE_READMES,
             *(ROOT / "book").glob("*.md")]
    for path in texts:
        text = path.read_text(encoding="utf-8")
        for other in ("pip install -e", "python -m skxfem.app.grade ", "`pytest exercises"):
            assert other not in text, f"{path.relative_to(ROOT)} says {other!r}"


def seed_venv(clone: Path) -> Path:
    """The clone's .venv, with this environment's packages instead of a download."""
    venv = clone / ".venv"
    subprocess.run([sys._base_executable, "-m", "venv", "--without-pip", str(venv)],
                   check=True)
    python = venv / "bin" / "python"
    site = subprocess.run([python, "-c", "import sysconfig; print(sysconfig.get_paths()"
                           "['purelib'])"], check=True, capture_output=True, text=True)
    Path(site.stdout.strip(), "_seed_packages.pth").write_text(
        sysconfig.get_paths()["purelib"] + "\n")
    pytest_script = venv / "bin" / "pytest"
    pytest_script.write_text(f"#!{python}\nimport sys\nfrom pytest import console_main\n"
                             f"sys.exit(console_main())\n")
    pytest_script.chmod(0o755)
    return venv


@pytest.mark.skipif(shutil.which("git") is None or shutil.which("make") is None,
                    reason="needs git and make, as the page says")
def test_a_fresh_clone_follows_the_page_to_a_score_table(tmp_path):
    env = {k: v for k, v in os.environ.items()
           if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "VIRTUAL_ENV", "PYTHONPATH",
                        "SKXFEM_SOLUTIONS")}
    env["PATH"] = os.pathsep.join(p for p in env.get("PATH", "").split(os.pathsep)
                                  if not p.startswith(str(ROOT)))

    def shell(command, cwd):
        return subprocess.run(command, shell=True, cwd=cwd, env=env, capture_output=True,
                              text=True, timeout=600)

    clone_command, cd, install, tests, grade = STUDENT[:5]
    done = shell(clone_command.replace("REPOSITORY", str(ROOT)), tmp_path)
    assert done.returncode == 0, done.stderr
    clone = tmp_path / cd.split()[1]
    assert (clone / "exercises" / "01_levelset" / "exercise.py").is_file()
    assert not (clone / ".venv").exists()
    seed_venv(clone)

    done = shell(install, clone)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    where = shell(".venv/bin/python -c 'import skxfem; print(skxfem.__file__)'", clone)
    assert where.stdout.strip() == str(clone / "skxfem" / "__init__.py"), where.stderr
    assert (clone / ".venv" / "bin" / "skxfem").is_file()       # written by make install
    kernel = clone / ".venv" / "share" / "jupyter" / "kernels" / "skxfem" / "kernel.json"
    assert kernel.is_file(), "make install registers the notebooks' kernel"  # in .venv

    done = shell(tests, clone)                       # the stub: every test fails
    assert done.returncode == 1 and "NotImplementedError" in done.stdout, done.stdout[-3000:]
    assert "7 failed" in done.stdout
    done = shell(grade, clone)                       # and the score table says so
    assert done.returncode == 1, done.stdout[-3000:] + done.stderr[-3000:]
    assert re.search(r"^01_levelset\s+0/7\s+0/7\s", done.stdout, flags=re.M), done.stdout
    assert re.search(r"^total\s+0/7\s+0/7$", done.stdout, flags=re.M), done.stdout

    graded_references = [c for c in INSTRUCTOR if "--impl=solution" in c]
    assert len(graded_references) == 2
    for command in graded_references:                # the references: full marks
        done = shell(command, clone)
        assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert re.search(r"^total\s+(\d+)/\1\s+(\d+)/\2$", done.stdout, flags=re.M), done.stdout

    assert "make notebooks" in INSTRUCTOR
    done = shell("make notebooks", clone)
    assert done.returncode == 0, done.stderr[-3000:]
    assert len(list((clone / "notebooks").glob("*.ipynb"))) >= 10
