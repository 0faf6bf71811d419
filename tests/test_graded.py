"""skxfem.app.graded: which functions are graded, what answers them, and the book check."""
import ast
import html
import inspect
import shutil
from pathlib import Path

import pytest
from pygments import highlight
from pygments.formatters import HtmlFormatter
from pygments.lexers import PythonLexer

from skxfem.app.graded import (
    BANNER,
    INSTRUCTORS,
    answers,
    check_book,
    code_lines,
    contract,
    exercises_folder,
    graded,
    listing,
    main,
    show_reference,
)

EXERCISES = Path(__file__).resolve().parents[1] / "exercises"
ALL = [(e, name) for e in graded() for name in answers(e)]


def asked(exercise):
    """``ASKED`` of the exercise's test file: what its grader calls."""
    test = next((EXERCISES / exercise).glob("test_*.py"))
    for node in ast.parse(test.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Assign) and node.targets[0].id == "ASKED":
            return ast.literal_eval(node.value)
    raise AssertionError(f"{test} has no ASKED")


def page(text, highlighted=True):
    """A built page showing ``text`` as Sphinx does: highlighted, HTML-escaped."""
    body = highlight(text, PythonLexer(), HtmlFormatter()) if highlighted \
        else f"<pre>{html.escape(text)}</pre>"
    return f"<html><body><p>Some prose.</p>{body}</body></html>"


def write_book(folder, pages):
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in pages.items():
        (folder / name).write_text(text, encoding="utf-8")
    return folder


def test_the_stubs_are_what_the_graders_ask_for():
    """graded() is the tests' ASKED; each stub defines exactly those, in that order."""
    found = graded()
    assert list(found) == sorted(p.parent.name for p in EXERCISES.glob("*/exercise.py"))
    assert len(found) == 8
    for exercise, names in found.items():
        assert names == asked(exercise), exercise
        tree = ast.parse((EXERCISES / exercise / "exercise.py").read_text(encoding="utf-8"))
        public = tuple(n.name for n in tree.body
                       if isinstance(n, ast.FunctionDef) and not n.name.startswith("_"))
        assert public == names, exercise


def test_answers_hold_the_library_code_the_book_printed():
    """The functions issue 20 found printed in the book are among the answers,
    and so is the reference of every graded function."""
    expected = {"01_levelset": ["skxfem.levelset.plane", "skxfem.levelset._ball"],
                "02_cut": ["skxfem.cut.strictly_cut_edges", "skxfem.fem.simplex.edge_point",
                           "skxfem.fem.simplex.split"],
                "05_lbb": ["skxfem.lbb.inf_sup_constant"],
                "06_stabilised": ["skxfem.stabilised.minimum_edge_cover"],
                "07_contact": ["skxfem.contact.laws.normal_update",
                               "skxfem.contact.laws.ball_projection",
                               "skxfem.contact.laws.indicator"]}
    for exercise, names in graded().items():
        found = answers(exercise)
        assert set(expected.get(exercise, [])) <= set(found), exercise
        for name in names:   # the reference's own code, or the library function it re-exports
            assert any(key.endswith(f":{name}") or key.endswith(f".{name}") for key in found)


@pytest.mark.parametrize("exercise, name", ALL)
def test_the_contract_hides_the_code_and_the_instructors_listing_shows_it(exercise, name):
    func = answers(exercise)[name]
    lines = code_lines(func)
    assert lines, f"{name}: no code line long enough to be recognised"
    shown = contract(func)
    source = inspect.getsource(func)
    assert shown.splitlines()[0].strip() == source.splitlines()[0].strip()   # the signature
    if func.__doc__:
        assert inspect.cleandoc(func.__doc__).splitlines()[0] in shown       # the docstring
    assert not any(line in shown for line in lines)
    assert all(line in listing(func, environ={INSTRUCTORS: "1"}) for line in lines)


def test_listing_names_the_exercise():
    from skxfem.contact.laws import ball_projection
    from skxfem.contact.newton import residual
    assert "exercise 07_contact" in listing(ball_projection, environ={})
    assert "ball_projection" in listing(ball_projection, environ={}).splitlines()[0]
    assert "an exercise's answer" in listing(residual, environ={})   # not graded: no name


def test_check_book_finds_a_shown_answer(tmp_path):
    from skxfem.fem.simplex import edge_point
    book = write_book(tmp_path / "html", {
        "index.html": page("print('hello')"),
        "cut.html": page(inspect.getsource(edge_point)),
        "levelset.html": page(contract(edge_point))})          # the contract is fine
    problems = check_book(book)
    assert len(problems) == 1
    assert problems[0].startswith("cut.html") and "skxfem.fem.simplex.edge_point" in problems[0]
    assert "02_cut" in problems[0]


def test_check_book_reads_notebooks_and_downloads(tmp_path):
    import nbformat

    from skxfem.levelset import plane
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(
        "print(1)", outputs=[nbformat.v4.new_output("stream", text=inspect.getsource(plane))])])
    book = write_book(tmp_path / "html", {"index.html": page("x = 1")})
    nbformat.write(nb, book / "levelset.ipynb")
    (book / "_downloads").mkdir()
    shutil.copy(inspect.getsourcefile(plane), book / "_downloads" / "levelset.py")
    problems = check_book(book)
    plane_shown = next(p for p in problems if "levelset.plane," in p)
    assert plane_shown.startswith("_downloads/levelset.py, levelset.ipynb show(s)")
    assert any(p.startswith("_downloads/levelset.py show(s)") and "levelset._ball" in p
               for p in problems)


def test_a_students_book_without_answers_passes(tmp_path):
    pages = {"index.html": page("import skxfem")}
    for exercise in graded():
        for func in answers(exercise).values():
            pages[f"{exercise}_{func.__name__}.html"] = page(contract(func), highlighted=False)
    book = write_book(tmp_path / "html", pages)
    assert check_book(book) == []
    assert main([str(book)]) == 0


def test_the_instructors_book_shows_every_answer(tmp_path, capsys):
    references = {f"{e}.html": page(str(show_reference(e, environ={INSTRUCTORS: "1"})))
                  .replace("<body>", f"<body><div>{BANNER}</div>") for e in graded()}
    book = write_book(tmp_path / "html", references)
    assert check_book(book, instructor=True) == []
    assert main([str(book), "--instructor"]) == 0
    assert "all of the" in capsys.readouterr().out

    (book / "contact.html").write_text(page("no solution here"))
    (book / "07_contact.html").unlink()
    problems = check_book(book, instructor=True)
    assert problems and all("07_contact" in p for p in problems[1:])
    assert problems[0].startswith("1 of the 8 pages lack the instructors' banner")
    assert {p.split()[6].rstrip(";") for p in problems[1:]} == set(answers("07_contact"))
    assert main([str(book), "--instructor"]) == 1
    assert main([str(book)]) == 1           # a students' book must show none of them


def test_the_instructors_book_carries_its_banner_on_every_page(tmp_path, monkeypatch):
    """A real (small) Sphinx build with the book's theme and extension: built with
    SKXFEM_SOLUTIONS set, as make book-instructor builds it, every page (the index,
    the search page too) carries the banner; without, none does.  check_book wants
    exactly that."""
    pytest.importorskip("sphinx_book_theme")
    from sphinx.cmd.build import build_main
    shutil.copytree(EXERCISES, tmp_path / "exercises",
                    ignore=shutil.ignore_patterns("__pycache__"))
    book = tmp_path / "book"
    book.mkdir()
    (book / "conf.py").write_text(
        'extensions = ["myst_parser", "skxfem.app.graded"]\nhtml_theme = "sphinx_book_theme"\n'
        'exclude_patterns = ["_build", "_stubs"]\nproject = "t"\n', encoding="utf-8")
    (book / "index.md").write_text("# Home\n\n[Other](other.md)\n", encoding="utf-8")
    (book / "other.md").write_text("# Other\n\nText.\n", encoding="utf-8")
    built = {}
    for who, environ in (("instructors", "1"), ("students", None)):
        if environ:
            monkeypatch.setenv(INSTRUCTORS, environ)
        else:
            monkeypatch.delenv(INSTRUCTORS, raising=False)
        out = built[who] = tmp_path / who
        assert build_main(["-q", "-b", "html", "-E", "-d", str(tmp_path / f"{who}.doctrees"),
                           str(book), str(out)]) == 0
        pages = sorted(out.glob("*.html"))
        assert {p.name for p in pages} >= {"index.html", "other.html", "search.html"}
        shown = [BANNER in html.unescape(p.read_text("utf-8")) for p in pages]
        assert shown == [who == "instructors"] * len(pages), (who, pages)
    assert "bd-header-announcement" in (built["instructors"] / "other.html").read_text("utf-8")

    def banner_problems(out, instructor):
        return [p for p in check_book(out, instructor, tmp_path / "exercises")
                if "banner" in p]
    assert banner_problems(built["instructors"], True) == []
    assert banner_problems(built["students"], False) == []
    assert "lack the instructors' banner" in banner_problems(built["students"], True)[0]
    assert "carry the instructors' banner" in banner_problems(built["instructors"], False)[0]


def test_show_reference_is_for_instructors_only():
    assert show_reference("03_enrich", environ={}) is None
    text = show_reference("03_enrich", environ={INSTRUCTORS: "1"})
    assert "def jump(phi, b):" in text and text._repr_markdown_() == str(text)
    assert "def _ball" in show_reference("01_levelset", environ={INSTRUCTORS: "1"})


def test_bad_folders_and_lists_are_refused(tmp_path, capsys):
    with pytest.raises(FileNotFoundError, match="no exercises folder"):
        exercises_folder(tmp_path / "nowhere")
    with pytest.raises(FileNotFoundError, match="build the book first"):
        check_book(tmp_path)
    assert main([str(tmp_path / "nowhere")]) == 2
    assert "build the book first" in capsys.readouterr().err
    with pytest.raises(ValueError, match="no exercise '08_x'"):
        answers("08_x")

    root = tmp_path / "exercises"
    shutil.copytree(EXERCISES / "04_multipliers", root / "04_multipliers")
    shutil.copytree(EXERCISES / "solutions" / "04_multipliers",
                    root / "solutions" / "04_multipliers")
    reference = root / "solutions" / "04_multipliers" / "reference.py"
    text = reference.read_text(encoding="utf-8")
    reference.write_text(text.replace('"skxfem.multipliers.interface_mass"',
                                      '"skxfem.multipliers.mass_of_interface"'))
    with pytest.raises(ValueError, match="mass_of_interface.*renamed"):
        answers("04_multipliers", root)
    reference.write_text(text.replace("def interpolate(", "def _interpolate("))
    with pytest.raises(ValueError, match="does not define interpolate"):
        answers("04_multipliers", root)
    (reference).unlink()
    with pytest.raises(FileNotFoundError, match="no reference solution"):
        answers("04_multipliers", root)
