"""The stored notebooks: valid, executed in order, clean, deterministic, small.

These read the committed files only (nothing is executed here: strict nbval re-runs every
notebook in its own `make test` step). A failure names the notebook and the cell, and how to
fix it, usually: re-run ``.venv/bin/python -m tools.execute_notebooks notebooks/NN_name.ipynb``.
"""

from __future__ import annotations

import re
from pathlib import Path

import nbformat
import pytest

from tools.book_pages import notebook_id, notebooks, toc_files, toc_notebooks
from tools.execute_notebooks import (
    KERNELSPEC,
    TIMING_KEYS,
    WIDGET_VIEW,
    dumps,
    normalise,
    problems,
)

ROOT = Path(__file__).resolve().parents[2]

#: A notebook file's budget (its outputs included): one section page of the reader's edition.
MAX_BYTES = 1_500_000
NOTEBOOKS = notebooks()  # both layouts: notebooks/NN_name.ipynb, notebooks/NN_name/MM_x.ipynb
IDS = [notebook_id(p) for p in NOTEBOOKS]
FIX = "re-run `.venv/bin/python -m tools.execute_notebooks {path}`"

#: Output text that must never be stored: absolute paths of this machine, memory addresses.
LEAKS = {
    "an absolute path": re.compile(r"(?<![\w.])/(?:work|tmp|root|home|usr|opt)/[\w.-]+"),
    "a memory address (end the line with `;` or assign the result)":
        re.compile(r"\bat 0x[0-9a-fA-F]{6,}"),
}


def _rel(path: Path) -> str:
    """The notebook's path from the repository root (names it in every message)."""
    return path.relative_to(ROOT).as_posix()


def _read(path: Path) -> nbformat.NotebookNode:
    return nbformat.read(path, as_version=4)


def _text(value) -> str:
    return "".join(value) if isinstance(value, list) else str(value)


def _output_texts(output) -> list[str]:
    if output.get("output_type") == "stream":
        return [_text(output.get("text", ""))]
    if output.get("output_type") == "error":
        return ["\n".join(output.get("traceback", []))]
    return [_text(v) for k, v in output.get("data", {}).items()
            if k.startswith("text/") and k != "text/html"]


def test_there_are_notebooks_to_check():
    """The book's chapters are notebooks; an empty notebooks/ means the checks ran on nothing."""
    assert NOTEBOOKS, "notebooks/ holds no NN_name.ipynb"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_valid_nbformat(path):
    nb = _read(path)
    nbformat.validate(nb)
    assert (nb.nbformat, nb.nbformat_minor) >= (4, 5), f"{_rel(path)}: nbformat 4.5+ (cell ids)"
    assert nb.metadata.get("kernelspec") == KERNELSPEC, (
        f"{_rel(path)}: kernelspec must be {KERNELSPEC}; {FIX.format(path=_rel(path))}")


@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_no_timing_metadata(path):
    nb = _read(path)
    found = [f"cell {i}: {key}" for i, cell in enumerate(nb.cells) for key in TIMING_KEYS
             if key in cell.metadata]
    assert not found, f"{_rel(path)} stores timing metadata ({found}); {FIX.format(path=_rel(path))}"
    assert "widgets" not in nb.metadata, f"{_rel(path)} stores widget state; {FIX.format(path=_rel(path))}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_executed_in_order_with_outputs(path):
    nb = _read(path)
    code = [(i, c) for i, c in enumerate(nb.cells) if c.cell_type == "code" and c.source.strip()]
    assert code, f"{_rel(path)} has no code cells"
    not_run = [i for i, c in code if c.execution_count is None]
    assert not not_run, f"{_rel(path)}: cells {not_run} were never executed; {FIX.format(path=_rel(path))}"
    counts = [c.execution_count for _, c in code]
    assert counts == list(range(1, len(code) + 1)), (
        f"{_rel(path)}: execution counts {counts} are not 1..{len(code)}: the notebook was not "
        f"run top to bottom in one fresh kernel; {FIX.format(path=_rel(path))}")
    assert any(c.outputs for _, c in code), f"{_rel(path)} is stored without outputs"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_no_errors_or_warnings_in_outputs(path):
    nb = _read(path)
    found = problems(nb)
    for i, cell in enumerate(nb.cells):
        for output in cell.get("outputs", []):
            text = "\n".join(_output_texts(output))
            if output.get("output_type") == "stream" and output.get("name") == "stderr":
                found.append(f"cell {i} printed on stderr: {text.strip()[:200]}")
            elif "Traceback (most recent call last)" in text:
                found.append(f"cell {i} shows a traceback")
    assert not found, f"{_rel(path)}:\n" + "\n".join(sorted(set(found)))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_no_machine_specific_output(path):
    nb = _read(path)
    found = []
    for i, cell in enumerate(nb.cells):
        for output in cell.get("outputs", []):
            for text in _output_texts(output):
                for what, pattern in LEAKS.items():
                    match = pattern.search(text)
                    if match:
                        found.append(f"cell {i} shows {what}: {match.group(0)!r}")
    assert not found, f"{_rel(path)}:\n" + "\n".join(found)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_widget_outputs_are_removed_from_the_book(path):
    """The HTML book has no kernel: a visible widget would look live and do nothing."""
    nb = _read(path)
    visible = [i for i, cell in enumerate(nb.cells)
               if any(WIDGET_VIEW in o.get("data", {}) for o in cell.get("outputs", []))
               and not {"remove-output", "remove-cell"} & set(cell.metadata.get("tags", []))]
    assert not visible, (f"{_rel(path)}: cells {visible} display a widget but are not tagged "
                         "remove-output")


@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_canonical_form(path):
    """The file is exactly what tools/execute_notebooks.py writes, so re-running gives no diff."""
    text = path.read_text(encoding="utf-8")
    assert dumps(normalise(_read(path), notebook_id(path))) == text, (
        f"{_rel(path)} is not in canonical form (random ids, timing or formatting); "
        f"{FIX.format(path=_rel(path))}")


@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_size_budget(path):
    size = path.stat().st_size
    assert size < MAX_BYTES, (f"{_rel(path)} is {size / 1e6:.2f} MB, over the 1.5 MB budget: "
                              "fewer or smaller animation frames (palette PNGs, at most 40 "
                              "frames), or split the section")


@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_listed_in_the_toc(path):
    """only_build_toc_files is on: a notebook missing from _toc.yml is silently left out."""
    page = f"notebooks/{notebook_id(path)}"
    assert page in toc_files(), (f"{_rel(path)} is not in _toc.yml (add `- file: {page}`, "
                                 "under `sections:` of its chapter's index)")


def test_every_notebook_in_the_toc_exists():
    """The toc's notebook pages are the notebooks checked here (none is missed by the glob)."""
    unchecked = [_rel(p) for p in toc_notebooks() if p not in NOTEBOOKS]
    assert not unchecked, f"_toc.yml lists notebooks outside notebooks/NN_*: {unchecked}"
