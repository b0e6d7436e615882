# wheelkin: one command to build the book, one to test everything. Each target sets itself up.
SHELL := /bin/bash
.DEFAULT_GOAL := help
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: help setup book test lint unit notebooks nbval browser serve bench clean

help:
	@echo "make book       build the HTML book into _build/html (set-up included)"
	@echo "make test       ruff, library tests, strict nbval, book build, browser tests"
	@echo "make notebooks  re-execute every notebook in place, deterministically"
	@echo "make serve      serve _build/html on http://127.0.0.1:8000"
	@echo "make bench      run the benchmarks and update benchmarks/RESULTS.md"

$(STAMP): requirements.txt pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -r requirements.txt
	$(BIN)/python -m pip check
	$(BIN)/python -m ipykernel install --sys-prefix --name python3 >/dev/null
	touch $(STAMP)

setup: $(STAMP)

book: $(STAMP)
	$(BIN)/python tools/vendor_assets.py
	rm -rf _build/html
	$(BIN)/jupyter-book build . -W -n --keep-going

lint: $(STAMP)
	$(BIN)/ruff check .

unit: $(STAMP)
	$(BIN)/python -m pytest -n 2 tests src/wheelkin --ignore=tests/browser

nbval: $(STAMP)
	$(BIN)/python -m pytest --nbval notebooks -n 2 --dist loadfile -p no:randomly \
	  --nbval-sanitize-with tools/nbval_sanitize.cfg -o addopts="" -o testpaths=notebooks

browser: $(STAMP)
	$(BIN)/python -m pytest tests/browser -o addopts="" -p no:cacheprovider

test: lint unit nbval book browser

notebooks: $(STAMP)
	timeout 900 $(BIN)/python tools/execute_notebooks.py notebooks/*.ipynb

serve: book
	$(BIN)/python -m http.server --bind 127.0.0.1 --directory _build/html 8000

bench: $(STAMP)
	$(BIN)/python benchmarks/run_all.py

clean:
	rm -rf _build _vendor .pytest_cache .ruff_cache .hypothesis
