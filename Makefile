# wheelkin: one command to build the book, one to test everything. Each target sets itself up
# from a fresh clone: it creates .venv and installs the pinned stack (requirements.txt) first.
SHELL := /bin/bash
.DEFAULT_GOAL := help
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
LAB_STAMP := $(VENV)/.installed-lab
PORT ?= 8000
# `make lab`: JupyterLab's port on 127.0.0.1, and extra arguments (e.g. a fixed token).
LAB_PORT ?= 8888
LAB_ARGS ?=
# `make serve-live`: the site's port and the Jupyter server's, on 127.0.0.1 (0: a free one).
LIVE_PORT ?= 8001
KERNEL_PORT ?= 8889
# The notebooks of the book, in reading order, from _toc.yml (nested sections included).
TOC_NOTEBOOKS = $(shell $(BIN)/python -m tools.book_pages --notebooks)
# Guard for `make notebooks` (whole run, seconds); the budget is 5 minutes on 2 cores.
NOTEBOOKS_TIMEOUT ?= 900
# Every test run: no pytest cache, the summary of skips/failures at the end.
PYTEST := $(BIN)/python -m pytest -p no:cacheprovider

# Deterministic kernels for nbval, exactly as tools/execute_notebooks.py runs them.
NB_ENV := PYTHONHASHSEED=0 MPLBACKEND=module://matplotlib_inline.backend_inline \
  SOURCE_DATE_EPOCH=1767225600 TZ=UTC LC_ALL=C.UTF-8 PYDEVD_DISABLE_FILE_VALIDATION=1

# The layers of `make test`, in order. The test layers are the folders of tests/: library
# (with the doctests), sandbox, panels, book-tests (tests/book), browser, kit, pdf; lint, nbval
# and book (the build, which browser needs) are steps of their own.
LAYERS := lint library sandbox panels book-tests nbval book browser kit pdf

.PHONY: help setup book vendor test unit $(LAYERS) notebooks serve serve-live bench clean mutation lab student \
  grade autograder tex

help:
	@echo "make book       build the HTML book into _build/html (set-up included)"
	@echo "make test       every layer: $(LAYERS)"
	@echo "make unit       the fast layers: library (+ doctests), sandbox, panels, book-tests"
	@echo "make notebooks  re-execute every notebook in place, deterministically"
	@echo "make serve      build, then serve _build/html on http://127.0.0.1:$(PORT)"
	@echo "make serve-live the book with live pages (a local kernel) on http://127.0.0.1:$(LIVE_PORT)"
	@echo "make lab        JupyterLab (pinned, with jupyterlab-myst) in notebooks/ on 127.0.0.1:$(LAB_PORT)"
	@echo "make bench      run every benchmark (python -m benchmarks.run_all)"
	@echo "make mutation   mutate the formula modules; the unit tests must kill every mutant"
	@echo "make student    student edition: notebooks without solutions + web edition in _build/student"
	@echo "make grade SUBMISSIONS=dir ASSIGNMENT=file.toml   grade into _build/grades (sandboxed; resumes)"
	@echo "make autograder ASSIGNMENT=file.toml   Gradescope's autograder zip in _build/autograder"
	@echo "make pdf        the printed edition, _build/pdf/wheelkin.pdf (make tex installs TeX, as root)"
	@echo "make clean      remove build output and caches"

$(STAMP): requirements.txt pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r requirements.txt
	$(BIN)/python -m pip check
	$(BIN)/python -m ipykernel install --sys-prefix --name python3 >/dev/null
	touch $(STAMP)

setup: $(STAMP)

# JupyterLab and jupyterlab-myst (requirements-lab.txt), on top of the book's stack.
$(LAB_STAMP): $(STAMP) requirements-lab.txt
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r requirements-lab.txt
	$(BIN)/python -m pip check
	$(BIN)/jupyter labextension list 2>&1 | grep -Eq 'jupyterlab-myst v[0-9.]+ .*enabled.*OK' \
	  || { echo "jupyterlab-myst is not enabled and compatible in JupyterLab"; exit 1; }
	touch $(LAB_STAMP)

# The notebooks as the book shows them: MyST renders (jupyterlab-myst), no browser is opened.
# As root (a container, CI) Jupyter refuses to start without --allow-root.
lab: $(LAB_STAMP)
	cd notebooks && ../$(BIN)/jupyter lab --ip=127.0.0.1 --port=$(LAB_PORT) --no-browser \
	  $(if $(filter 0,$(shell id -u)),--allow-root) $(LAB_ARGS)

# JavaScript for the offline site (MathJax, require.js, widget manager) from package.json.
vendor: $(STAMP)
	$(BIN)/python -m tools.vendor_assets

book: vendor
	rm -rf _build/html _build/.doctrees _build/jupyter_execute
	$(BIN)/jupyter-book build . -W -n --keep-going

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/mypy

# One folder of tests/ per layer; the library layer runs the formula modules' doctests too.
library: $(STAMP)
	$(PYTEST) -n 2 tests/library src/wheelkin

sandbox: $(STAMP)
	$(PYTEST) -n 2 tests/sandbox

panels: $(STAMP)
	$(PYTEST) -n 2 tests/panels

book-tests: $(STAMP)
	$(PYTEST) -n 2 tests/book

unit: library sandbox panels book-tests

nbval: $(STAMP)
	$(NB_ENV) $(PYTEST) -p tools.nbval_jupyter_history \
	  --nbval $(TOC_NOTEBOOKS) -n 2 --dist loadfile --nbval-current-env \
	  --nbval-sanitize-with tools/nbval_sanitize.cfg --nbval-cell-timeout 300 \
	  -o addopts="-ra" -o testpaths=notebooks

# The student web edition that the browser layer audits, rebuilt when a source of it is newer.
STUDENT_SITE := _build/student/html/index.html
STUDENT_SOURCES = _toc.yml _config.yml package-lock.json $(wildcard notebooks/*/*.ipynb \
  notebooks/*/*.md book/*.md book/*/*.md book/_static/* book/_templates/* tools/*.py \
  src/wheelkin/*.py src/wheelkin/*/*.py)
$(STUDENT_SITE): $(STUDENT_SOURCES) | vendor
	$(BIN)/python -m tools.student_edition --out _build/student

# The browser layer also starts `make lab`'s JupyterLab once (tests/browser/test_lab.py), and
# audits the student web edition too (tests/browser/test_accessibility.py).
browser: $(STAMP) $(LAB_STAMP) $(STUDENT_SITE)
	$(PYTEST) tests/browser -o addopts="-ra" --timeout 900

# Every layer runs even when an earlier one failed; the summary names the failed ones.
test: $(STAMP)
	@passed=(); failed=(); log=$$(mktemp); \
	for layer in $(LAYERS); do \
	  echo; echo "================ make test: $$layer ================"; \
	  start=$$(date +%s); \
	  if $(MAKE) --no-print-directory $$layer 2>&1 | tee -a $$log; \
	     test $${PIPESTATUS[0]} -eq 0; then passed+=($$layer); \
	  else failed+=($$layer); fi; \
	  echo "---------------- $$layer: $$(( $$(date +%s) - start )) s"; \
	done; \
	echo; echo "================ make test summary ================"; \
	echo "layers passed: $${passed[*]:-none}"; echo "layers failed: $${failed[*]:-none}"; \
	summary=$$(grep -E '^=+ .*[0-9]+ (passed|failed|error).* in [0-9.]+s' $$log); \
	npass=$$(echo "$$summary" | grep -oE '[0-9]+ passed' | awk '{s+=$$1} END {print s+0}'); \
	nfail=$$(echo "$$summary" | grep -oE '[0-9]+ (failed|errors?)' | awk '{s+=$$1} END {print s+0}'); \
	rm -f $$log; \
	echo "tests: $$npass passed, $$nfail failed"; \
	test $${#failed[@]} -eq 0

notebooks: $(STAMP)
	timeout $(NOTEBOOKS_TIMEOUT) $(BIN)/python -m tools.execute_notebooks $(TOC_NOTEBOOKS)

serve: book
	@echo "serving http://127.0.0.1:$(PORT)/ (Ctrl-C to stop)"
	$(BIN)/python -m http.server --bind 127.0.0.1 --directory _build/html $(PORT)

# The book with live pages: "Make this page live" runs a page's cells and panels in a local
# Jupyter server (tools/serve_live.py; jupyter_server comes with requirements-lab.txt). Builds
# the book first when it is not built; Ctrl-C stops the site, the server and its kernels.
serve-live: $(LAB_STAMP) vendor
	@test -f _build/html/index.html || $(MAKE) --no-print-directory book
	@$(BIN)/python -m tools.serve_live --port $(LIVE_PORT) --kernel-port $(KERNEL_PORT)

# benchmarks/live.py serves live pages: jupyter_server comes with the lab stack.
bench: book $(LAB_STAMP)
	$(BIN)/python -m benchmarks.run_all

# Meaningful mutants of the formula modules, one at a time in a temporary copy (tools/mutation.py).
mutation: $(STAMP)
	$(BIN)/python -m tools.mutation

# The instructor's kit (tools/student_edition.py, tools/grade.py, tools/pdf_edition.py).
student: vendor
	$(BIN)/python -m tools.student_edition --out _build/student

SUBMISSIONS ?=
ASSIGNMENT ?=
GRADE_JOBS ?= 2
# Each submission runs in bubblewrap sandboxes (Debian's bubblewrap: .ci/run installs it).
grade: $(STAMP)
	@test -n "$(SUBMISSIONS)" -a -n "$(ASSIGNMENT)" || { echo "usage: make grade SUBMISSIONS=<folder of notebooks> ASSIGNMENT=<assignments/....toml>"; exit 2; }
	$(BIN)/python -m tools.grade "$(SUBMISSIONS)" --assignment "$(ASSIGNMENT)" --out _build/grades -j $(GRADE_JOBS)

# Gradescope's autograder for one assignment: _build/autograder/<assignment>.zip.
autograder: $(STAMP)
	@test -n "$(ASSIGNMENT)" || { echo "usage: make autograder ASSIGNMENT=<assignments/....toml>"; exit 2; }
	$(BIN)/python -m tools.autograder "$(ASSIGNMENT)" --out _build/autograder

# The kit layer: the grader (in its bubblewrap sandboxes) on tests/kit/submissions and the
# red team's tests/kit/redteam, the book's solutions through the grader, Gradescope's zip run
# as Gradescope runs it, the course's CI files (actionlint), the student edition built and
# executed, stray globals before every exercise stub (tests/kit/conftest.py collects it only
# here).
kit: vendor
	$(PYTEST) tests/kit -o addopts="-ra" --timeout 3600

# Debian's TeX for the PDF, installed when missing (needs root; CI runs as root).
TEX_PACKAGES := texlive-xetex texlive-latex-extra texlive-fonts-recommended latexmk xindy \
  fonts-freefont-otf fonts-dejavu-core poppler-utils
tex:
	@if command -v xelatex >/dev/null && command -v latexmk >/dev/null \
	   && command -v xindy >/dev/null && command -v pdftotext >/dev/null \
	   && fc-list | grep -q FreeSerif && fc-list | grep -q "DejaVu Sans Mono"; then \
	  echo "tex: TeX for the PDF is installed"; \
	elif [ "$$(id -u)" = 0 ]; then \
	  DEBIAN_FRONTEND=noninteractive apt-get update -q && \
	  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $(TEX_PACKAGES) </dev/null; \
	else echo "tex: run as root, or: sudo apt-get install $(TEX_PACKAGES)"; exit 1; fi

# The printed edition, then its checks (the pdf layer of make test): tests/pdf (chapters,
# answers, wording, references, index; and the numbering both editions share).
pdf: tex $(STAMP)
	$(BIN)/python -m tools.pdf_edition --out _build/pdf
	$(PYTEST) tests/pdf -o addopts="-ra"

clean:
	rm -rf _build _vendor .pytest_cache .ruff_cache .hypothesis
