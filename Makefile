# skxfem: the whole set-up on a fresh machine is `make figures` and `make test`.
#
#   make figures   create .venv, install skxfem, reproduce the paper's figures in out/
#   make test      create .venv, install skxfem, lint (ruff, import floors), run pytest
#                  (in two processes: pytest-xdist),
#                  then build and check the students' and the instructors' books (a
#                  hand-out, without exercises/solutions/, the students' book only)
#   make book      build the students' book (executes every chapter) into
#                  book/_build/html and check it: no page shows a graded solution
#   make book-instructor
#                  build the instructors' book, with the solutions, into
#                  book/_build/instructor/_build/html and check it shows them all
#   make notebooks write every chapter as a notebook (.ipynb) into notebooks/
#                  (open them with .venv/bin/jupyter lab notebooks/, kernel "skxfem")
#   make handout   write what a student gets into out/handout (HANDOUT=DIR for another
#                  folder): no exercises/solutions/, every exercise.py its stub
#   make install   only create .venv, install skxfem[viz,book,dev] and register
#                  its Jupyter kernel "skxfem"
#   make clean     remove the built books and notebooks
#
# Everything is non-interactive.  PYTHON picks the interpreter for the venv.

SHELL := bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := help

PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.skxfem-installed
MATHJAX := book/_mathjax/mathjax/tex-chtml.js

# Headless: matplotlib draws without a display (chapters still show figures:
# they start with `%matplotlib inline`), VTK uses EGL instead of X.
export MPLBACKEND := Agg
export VTK_DEFAULT_OPENGL_WINDOW := vtkEGLRenderWindow
export PIP_DISABLE_PIP_VERSION_CHECK := 1
# One BLAS thread: the dense interface factorisations are small, and a
# threaded OpenBLAS on a busy 2-core machine was measured 100x slower on them.
export OPENBLAS_NUM_THREADS := 1
export PATH := $(abspath $(BIN)):$(PATH)

INSTRUCTOR_BUILD := book/_build/instructor
# Where each build finds its executed chapters (scripts/execute_book.py fills them).
STUDENTS_CACHE := book/_build/.jupyter_cache
INSTRUCTOR_CACHE := $(INSTRUCTOR_BUILD)/_build/.jupyter_cache
HANDOUT ?= out/handout
# A hand-out (make handout) has no solutions: it builds the students' book only.
SOLUTIONS := $(wildcard exercises/solutions)

.PHONY: help install figures test book book-instructor notebooks handout clean needs-solutions

help:
	@sed -n 's/^#   //p' Makefile

install: $(STAMP)

$(BIN)/python:
	$(PYTHON) -m venv $(VENV) || { rm -rf $(VENV); exit 1; }

# Reinstall whenever pyproject.toml changes.
# The kernel "skxfem" (in .venv/share/jupyter): the notebooks of make notebooks name it.
$(STAMP): pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e '.[viz,book,dev]'
	$(BIN)/python -m ipykernel install --sys-prefix --name skxfem --display-name skxfem \
	    > /dev/null
	touch $@

figures: $(STAMP)
	$(BIN)/python -m skxfem.app.reproduce --quick --out out/

test: $(STAMP)
	$(BIN)/ruff check skxfem tests exercises
	$(BIN)/lint-imports
	$(BIN)/pytest -q -n 2
	$(MAKE) --no-print-directory book \
	    $(if $(SOLUTIONS),book-instructor REUSE=$(STUDENTS_CACHE))

$(MATHJAX):
	bash scripts/fetch_mathjax.sh book/_mathjax

# Every chapter is executed against the current library, two at a time, into a
# new cache (scripts/execute_book.py), where the build takes its outputs from;
# --all: re-read every page; a cell that raises or any Sphinx warning fails the
# build.  Then the checks of the built pages: no page shows the code of a graded
# exercise's solution (skxfem.app.graded), every chapter offers its notebook for
# download.
book: $(STAMP) $(MATHJAX)
	$(BIN)/python scripts/execute_book.py $(STUDENTS_CACHE)
	$(BIN)/jupyter-book build book/ --all --warningiserror --keep-going
	$(BIN)/python -m skxfem.app.graded book/_build/html
	$(BIN)/python scripts/notebooks.py --check book/_build/html

# The same book with SKXFEM_SOLUTIONS set: the chapters print the graded
# functions' code and the reference solutions, and the check wants them all.
# REUSE=STUDENTS_CACHE (make test, right after make book): the chapters that
# cannot show a solution (no skxfem.app, no environment, no process: see
# scripts/execute_book.py) keep the students' build's outputs; the others run again.
book-instructor: needs-solutions $(STAMP) $(MATHJAX)
	SKXFEM_SOLUTIONS=1 $(BIN)/python scripts/execute_book.py $(INSTRUCTOR_CACHE) \
	    $(if $(REUSE),--reuse $(REUSE))
	SKXFEM_SOLUTIONS=1 $(BIN)/jupyter-book build book/ --all --warningiserror --keep-going \
	    --path-output $(INSTRUCTOR_BUILD)
	$(BIN)/python -m skxfem.app.graded --instructor $(INSTRUCTOR_BUILD)/_build/html

notebooks: $(STAMP)
	$(BIN)/python scripts/notebooks.py notebooks/

# The course as a student gets it (skxfem.app.handout): a new folder, then git init
# and publish it.  It installs, its stubs fail their tests, and make book builds.
handout: $(STAMP)
	$(BIN)/skxfem handout $(HANDOUT)

needs-solutions:
	@test -d exercises/solutions || { echo "make: the instructors' book needs the reference \
	solutions (exercises/solutions/), which a hand-out has not: make book builds the \
	students' book" >&2; exit 2; }

clean:
	rm -rf book/_build book/_stubs notebooks
