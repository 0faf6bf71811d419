"""The chapters as standalone notebooks (scripts/notebooks.py, `make notebooks`).

Every chapter is converted to an .ipynb in an empty folder and executed there by
nbclient, as a student who downloaded it would run it: no book, no build, no
relative path.  The notebooks run two at a time (the machine has 2 cores): about
40 s for the ten chapters, against 65 s one after the other.
"""
import importlib.util
import os
import re
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("book_notebooks", ROOT / "scripts" / "notebooks.py")
notebooks = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(notebooks)


def test_every_chapter_with_code_is_a_notebook():
    toc = (ROOT / "book" / "_toc.yml").read_text(encoding="utf-8")
    with_code = {p.stem for p in (ROOT / "book").glob("*.md")
                 if "```{code-cell}" in p.read_text(encoding="utf-8") and p.stem in toc}
    names = [p.stem for p in notebooks.chapters()]
    assert set(names) == with_code and len(names) == len(set(names)) >= 10
    assert names[:2] == ["levelset", "cut"]                 # in the order of the book


def test_a_notebook_is_the_chapter_without_outputs(tmp_path):
    page = ROOT / "book" / "cut.md"
    nb = notebooks.notebook(page)
    code = [c.source for c in nb.cells if c.cell_type == "code"]
    assert code and all(c.strip() in page.read_text(encoding="utf-8") for c in code)
    assert all(c.outputs == [] for c in nb.cells if c.cell_type == "code")
    assert "make install" in nb.cells[0].source and "Cutting the mesh" in nb.cells[0].source
    assert set(nb.metadata) == {"kernelspec", "language_info"}      # no jupytext pairing
    assert nb.metadata["kernelspec"]["name"] == "skxfem"            # make install's kernel
    assert notebooks.notebook(page) == nb                           # stable, cell ids too


MYST = re.compile(r"\{[a-z-]+\}`|^\s*(```|~~~)\s*\{|^:::")
LINK = re.compile(r"\]\(([^)\s]+)\)")
FENCED = re.compile(r"^```.*?^```", flags=re.S | re.M)


def test_a_notebook_reads_as_a_student_opens_it():
    """No MyST left in its Markdown: the exercise's task is there as text, a download
    is a link to the file in the clone, a link to a page leads to its notebook (or to
    its source), and every relative link resolves from the clone's notebooks/."""
    pages = notebooks.chapters()
    names = {p.stem for p in pages}
    links = 0
    for page in pages:
        nb = notebooks.notebook(page)
        text = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
        assert "{download}" not in text and "{include}" not in text, page.name
        assert not MYST.search(text), (page.name, MYST.search(text).group())
        for target in LINK.findall(FENCED.sub("", text)):        # code is no link
            if "://" in target or target.startswith("#") or "\\" in target:
                continue                                  # a web link, or maths
            links += 1
            path = target.split("#")[0]
            if path.endswith(".ipynb"):
                assert path.removesuffix(".ipynb") in names, (page.name, target)
            else:
                assert (ROOT / "notebooks" / path).resolve().is_file(), (page.name, target)
                assert not path.endswith(".md") or path.startswith("../"), (page.name, target)
    assert links >= 3 * 7                     # each exercise: its file, its README, the set-up
    levelset = notebooks.notebook(ROOT / "book" / "levelset.md")
    text = "\n".join(c.source for c in levelset.cells)
    readme = (ROOT / "exercises" / "01_levelset" / "README.md").read_text("utf-8")
    task = readme.split("<!-- exercise-start -->")[1].split("<!-- exercise-end -->")[0]
    assert task.strip() in text and "<!-- exercise-start -->" not in text
    assert "[exercises/01_levelset/exercise.py](../exercises/01_levelset/exercise.py)" in text
    assert "[Getting started](../book/getting-started.md)" in text


def test_an_include_option_it_does_not_know_is_refused(tmp_path):
    (tmp_path / "t.md").write_text("a\nb\n", encoding="utf-8")
    assert notebooks.plain("```{include} t.md\n```", set(), tmp_path) == "a\nb"
    with pytest.raises(ValueError, match="'heading-offset'"):
        notebooks.plain("```{include} t.md\n:heading-offset: 1\n```", set(), tmp_path)
    with pytest.raises(ValueError, match="'start-after'"):
        notebooks.plain("```{include} t.md\n:start-after: nowhere\n```", set(), tmp_path)


def test_the_check_of_the_built_book(tmp_path):
    html = tmp_path / "html"
    (html / "_sources").mkdir(parents=True)
    pages = notebooks.chapters()
    for page in pages:
        (html / f"{page.stem}.html").write_text(f'<a href="_sources/{page.stem}.ipynb">')
        nbformat.write(notebooks.notebook(page), html / "_sources" / f"{page.stem}.ipynb")
    assert notebooks.check(html) == []
    (html / "_sources" / "cut.ipynb").write_text(
        nbformat.writes(notebooks.notebook(ROOT / "book" / "lbb.md")))
    (html / "lbb.html").write_text("<p>no button</p>")
    (html / "enrich.html").unlink()
    problems = notebooks.check(html)
    assert len(problems) == 3
    assert any("cut.ipynb is not the notebook of cut.md" in p for p in problems)
    assert any("lbb.html has no download button" in p for p in problems)
    assert any("enrich.html is missing" in p for p in problems)
    assert notebooks.main(["--check", str(html)]) == 1


def run(path: Path, env: dict) -> tuple[str, float, str]:
    """Execute one notebook as a student would (``jupyter execute NAME.ipynb``, nbclient's
    command line, with the kernel it names) in its own process and folder, keeping its
    outputs (``--inplace``, for :func:`printed`); its name, seconds and error ('' if
    none)."""
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "jupyter", "execute", "--timeout=600",
                           "--inplace", path.name], cwd=path.parent, env=env,
                          capture_output=True, text=True)
    error = "" if done.returncode == 0 else (done.stdout + done.stderr)[-4000:]
    return path.stem, time.perf_counter() - start, error


def test_every_chapter_runs_as_a_standalone_notebook(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "SKXFEM_SOLUTIONS"}   # students'
    env.setdefault("MPLBACKEND", "Agg")
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    env.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    # the kernel the notebooks name, registered as make install does (here in a folder
    # of this test's own, found through JUPYTER_PATH: the environment is left alone)
    subprocess.run([sys.executable, "-m", "ipykernel", "install", "--prefix",
                    str(tmp_path / "jupyter"), "--name", "skxfem", "--display-name", "skxfem"],
                   check=True, capture_output=True)
    env["JUPYTER_PATH"] = str(tmp_path / "jupyter" / "share" / "jupyter")
    assert notebooks.main([str(tmp_path)]) == 0
    paths = sorted(tmp_path.glob("*.ipynb"))
    assert all(nbformat.read(p, 4).metadata["kernelspec"]["name"] == "skxfem" for p in paths)
    for path in paths:
        text = path.read_text(encoding="utf-8")
        assert "{download}" not in text and "{include}" not in text, path.name
    assert [p.stem for p in paths] == sorted(p.stem for p in notebooks.chapters())
    with ThreadPoolExecutor(max_workers=2) as pool:      # two kernels at a time
        results = list(pool.map(lambda path: run(path, env), paths))
    print("\n".join(f"{name:16} {seconds:5.1f} s" for name, seconds, _ in results))
    failed = [f"{name}: {error}" for name, _, error in results if error]
    assert not failed, "\n\n".join(failed)
    wide = [f"{path.stem}: {line}" for path in paths for line in printed(path)
            if len(line) > 88]
    assert not wide, "printed lines wider than the book's 88 columns:\n" + "\n".join(wide)


def printed(path: Path) -> list[str]:
    """The lines a chapter prints (its text outputs, not its figures or tables)."""
    lines = []
    for cell in nbformat.read(path, 4).cells:
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            if out.get("output_type") == "stream":
                lines += out["text"].splitlines()
            elif "text/plain" in data and not any(k.startswith(("image/", "text/markdown",
                                                                "text/html")) for k in data):
                lines += data["text/plain"].splitlines()
    return lines
