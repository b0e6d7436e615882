"""Every exercise in every notebook, run twice: the blank stub and the solution.

A chapter's exercise is a code cell tagged ``exercise`` (the stub, which raises
NotImplementedError) followed by a code cell tagged ``solution``; both define the function and
end with ``check("chapter.name", fn)``. Each is executed in a fresh namespace after the first
code cell (its imports) of the notebook that holds it (a chapter's notebook, or the section
notebook of a chapter folder), with matplotlib's Agg backend. The stub's check must
fail with a message and nothing may raise; the solution's check must pass.

Every chapter present (a notebook ``notebooks/NN_name.ipynb`` or a folder
``notebooks/NN_name/``) is a chapter of the anatomy, except those in ``NON_CHAPTER_NOTEBOOKS``
(tools/book_pages.py), and has at least three exercises over its notebooks.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import matplotlib
import nbformat
import pytest

from tools.book_pages import NON_CHAPTER_NOTEBOOKS, chapters, notebook_id, notebooks

ROOT = Path(__file__).resolve().parents[2]

MIN_EXERCISES = 3
CHECK_CALL = re.compile(r"""\bcheck\(\s*["']([\w.]+)["']""")


def _tags(cell) -> set[str]:
    return set(cell.metadata.get("tags", []))


def _exercises(path: Path):
    """(first code cell, [(stub cell, solution cell, stub index), ...]) of one notebook."""
    nb = nbformat.read(path, as_version=4)
    code = [c for c in nb.cells if c.cell_type == "code"]
    first = code[0].source if code else ""
    pairs, stub, stub_index = [], None, None
    for index, cell in enumerate(nb.cells):
        if cell.cell_type != "code":
            continue
        if "exercise" in _tags(cell):
            assert stub is None, (f"{notebook_id(path)}: exercise cell {stub_index} has no solution cell "
                                  "(tagged `solution`) before the next exercise")
            stub, stub_index = cell.source, index
        elif "solution" in _tags(cell):
            assert stub is not None, f"{notebook_id(path)}: solution cell {index} follows no exercise"
            pairs.append((stub, cell.source, stub_index))
            stub = None
    assert stub is None, f"{notebook_id(path)}: exercise cell {stub_index} has no solution cell"
    return first, pairs


def _cases():
    for path in notebooks():
        first, pairs = _exercises(path)
        for stub, solution, index in pairs:
            name = CHECK_CALL.search(stub)
            label = name.group(1) if name else f"cell{index}"
            yield pytest.param(path, first, stub, solution, id=f"{notebook_id(path)}:{label}")


def _python(source: str) -> str:
    """Cell source as plain Python: IPython magics become calls to the stub ``get_ipython``."""
    from IPython.core.inputtransformer2 import TransformerManager

    return TransformerManager().transform_cell(source)


class _NoIPythonShell:
    """Stands in for IPython's shell: line magics (``%matplotlib inline``) do nothing here."""

    def __call__(self):  # get_ipython() returns the shell: this object
        return self

    def run_line_magic(self, *args, **kwargs):
        return None

    def run_cell_magic(self, name, line, cell):
        raise AssertionError(f"cell magic %%{name} in an exercise chapter's first cell")


def _run(source: str, namespace: dict, label: str) -> None:
    """Execute a cell in ``namespace``; it must end with the expression ``check(...)``."""
    tree = ast.parse(_python(source), filename=label)
    exec(compile(tree, label, "exec"), namespace)


def _ends_with_check(source: str) -> bool:
    tree = ast.parse(_python(source))
    last = tree.body[-1] if tree.body else None
    return (isinstance(last, ast.Expr) and isinstance(last.value, ast.Call)
            and getattr(last.value.func, "id", getattr(last.value.func, "attr", "")) == "check")


def _namespace(first: str, path: Path) -> dict:
    """A fresh namespace that has run the chapter's first code cell (its imports)."""
    matplotlib.use("Agg", force=True)
    namespace = {"__name__": "__main__", "get_ipython": _NoIPythonShell()}
    _run(first, namespace, f"{notebook_id(path)}: first code cell")
    return namespace


@pytest.fixture
def checks(monkeypatch):
    """Every CheckResult returned by wheelkin.exercises.check during the test, in order."""
    import wheelkin.exercises as exercises

    results: list = []
    original = exercises.check

    def recording_check(name, fn):
        result = original(name, fn)
        results.append(result)
        return result

    monkeypatch.setattr(exercises, "check", recording_check)
    return results


@pytest.mark.parametrize(("path", "first", "stub", "solution"), list(_cases()))
def test_stub_fails_helpfully_and_solution_passes(path, first, stub, solution, checks):
    import matplotlib.pyplot as plt

    for what, source in (("exercise", stub), ("solution", solution)):
        assert _ends_with_check(source), f"{notebook_id(path)}: the {what} cell must end with check(...)"
    try:
        _run(stub, _namespace(first, path), f"{notebook_id(path)}: exercise stub")
        stub_results = list(checks)
        assert stub_results, f"{notebook_id(path)}: the exercise cell does not call check(...)"
        for result in stub_results:
            assert not result.passed, f"{notebook_id(path)}: the blank stub passes its check: {result}"
            assert result.message.strip(), f"{notebook_id(path)}: the stub's check gives no message"

        checks.clear()
        _run(solution, _namespace(first, path), f"{notebook_id(path)}: solution")
        solution_results = list(checks)
        assert solution_results, f"{notebook_id(path)}: the solution cell does not call check(...)"
        for result in solution_results:
            assert result.passed, f"{notebook_id(path)}: the solution fails its check: {result.message}"
        assert ({r.name for r in stub_results} == {r.name for r in solution_results}), (
            f"{notebook_id(path)}: the stub and the solution check different exercises")
    finally:
        plt.close("all")


CHAPTERS = {name: paths for name, paths in chapters().items()
            if name not in NON_CHAPTER_NOTEBOOKS}


@pytest.mark.parametrize("chapter", sorted(CHAPTERS))
def test_chapter_has_enough_exercises(chapter):
    count = sum(len(_exercises(path)[1]) for path in CHAPTERS[chapter])
    assert count >= MIN_EXERCISES, (
        f"chapter {chapter} has {count} exercises (cells tagged exercise + solution) in "
        f"{[notebook_id(p) for p in CHAPTERS[chapter]]}, needs {MIN_EXERCISES}; a notebook that "
        "is not a chapter belongs in NON_CHAPTER_NOTEBOOKS (tools/book_pages.py)")
