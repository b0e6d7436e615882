"""The student edition (tools/student_edition.py, ``make student``): no solutions, stubs
intact, every notebook executed clean, and no solution text in its web edition."""

from __future__ import annotations

import html
import re
from pathlib import Path

import nbformat
import pytest

from tools.student_edition import (
    remove_solution_sentences,
    student_notebook,
    toc_notebooks,
)

ROOT = Path(__file__).resolve().parents[2]

NOTEBOOKS = toc_notebooks()


def _tags(cell) -> set[str]:
    return set(cell.metadata.get("tags", []))


def _solution_lines(nb) -> list[str]:
    """Distinctive lines of the solution cells (in no other cell, long enough to be unique)."""
    stubs = "\n".join(c.source for c in nb.cells if "solution" not in _tags(c))
    lines = []
    for cell in nb.cells:
        if "solution" in _tags(cell):
            for line in cell.source.splitlines():
                line = line.strip()
                if (len(line) >= 25 and line not in stubs and not line.startswith("check(")
                        and not line.startswith("def ")):
                    lines.append(line)
    return lines


def test_sentence_pointing_at_a_folded_solution_is_removed():
    text = ("Replace `raise NotImplementedError` with your code and run the cell. The\n"
            "solutions are folded away below each exercise.\n\n### Exercise 1\nWrite it "
            "(the solution is folded below). A solution of the ODE exists.")
    assert remove_solution_sentences(text) == (
        "Replace `raise NotImplementedError` with your code and run the cell.\n\n"
        "### Exercise 1\nWrite it. A solution of the ODE exists.")


def test_transform_removes_solutions_and_notes_keeps_stubs():
    stub = nbformat.v4.new_code_cell("def f(x):\n    raise NotImplementedError\n\n\n"
                                     'check("demo.f", f)')
    stub.metadata["tags"] = ["exercise"]
    solution = nbformat.v4.new_code_cell('def f(x):\n    return 2 * x\n\n\ncheck("demo.f", f)')
    solution.metadata["tags"] = ["solution", "hide-input"]
    note = nbformat.v4.new_markdown_cell("The solution is folded below.")
    note.metadata["tags"] = ["solution-note"]
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_markdown_cell("Task."), stub, note,
                                         solution])
    student, changes = student_notebook(nb)
    assert [c.source for c in student.cells] == ["Task.", stub.source]
    assert changes == {"solutions": 1, "notes": 1, "sentences": 0, "exercises": 1}
    assert len(nb.cells) == 4, "the original notebook is not changed"


def test_a_paragraph_line_that_opens_a_parenthesis_is_prose():
    """Only ``(label)=`` lines break a paragraph: a wrapped line may start with "("."""
    text = "Write it for a turn\n({ref}`a-label`). The solution is folded below.\n\n(x-y)=\n# T"
    assert remove_solution_sentences(text) == "Write it for a turn\n({ref}`a-label`).\n\n(x-y)=\n# T"


def test_a_sentence_may_start_after_a_closing_parenthesis():
    text = "Write it. (Which way does it turn?) The solution is folded below."
    assert remove_solution_sentences(text) == "Write it. (Which way does it turn?)"


def test_a_note_with_a_task_is_refused_not_deleted():
    """An exercise's prompt tagged ``solution-note`` would vanish with its pointer: the tool
    refuses the notebook and names the cell, rather than print a stub without its task."""
    note = nbformat.v4.new_markdown_cell(
        "### Exercise 1\n\nWrite `f(x)` returning twice `x`. The solution is folded\nbelow.")
    note.metadata["tags"] = ["solution-note"]
    with pytest.raises(ValueError, match=r"cell 0 .*statement.*Exercise"):
        student_notebook(nbformat.v4.new_notebook(cells=[note]))


def test_a_note_with_an_answer_goes_whole():
    """A ``solution-note`` cell that gives a verdict is removed whole, not just its pointer."""
    note = nbformat.v4.new_markdown_cell(
        "A 4 m corridor is not safe: it needs a fix on the way. The solution is folded below.")
    note.metadata["tags"] = ["solution-note"]
    student, changes = student_notebook(nbformat.v4.new_notebook(cells=[note]))
    assert student.cells == [] and changes["notes"] == 1


@pytest.mark.parametrize("rel", NOTEBOOKS, ids=lambda p: p.as_posix())
def test_student_notebook(rel, student_edition):
    out, _ = student_edition
    original = nbformat.read(ROOT / rel, as_version=4)
    student = nbformat.read(out / rel, as_version=4)
    assert not [c for c in student.cells if _tags(c) & {"solution", "solution-note"}]
    stubs = [c.source for c in original.cells if "exercise" in _tags(c)]
    assert [c.source for c in student.cells if "exercise" in _tags(c)] == stubs
    text = "\n".join(c.source for c in student.cells)
    for line in _solution_lines(original):
        assert line not in text, f"{rel}: solution line left in the student notebook: {line}"
    for index, cell in enumerate(student.cells):
        if cell.cell_type != "code":
            continue
        assert not [o for o in cell.outputs if o.output_type == "error"], (rel, index)
        if "exercise" in _tags(cell):
            assert cell.outputs == [], f"{rel}: cell {index}: an exercise stub keeps no output"
        else:
            assert cell.execution_count is not None, f"{rel}: cell {index} was not executed"


def _page_text(path: Path) -> str:
    raw = path.read_text(encoding="utf-8")
    return html.unescape(re.sub(r"<[^>]+>", "", raw))


@pytest.mark.parametrize("rel", [p for p in NOTEBOOKS if _solution_lines(
    nbformat.read(ROOT / p, as_version=4))], ids=lambda p: p.as_posix())
def test_no_solution_in_the_student_web_edition(rel, student_edition):
    out, _ = student_edition
    page = out / "html" / rel.with_suffix(".html")
    assert page.is_file(), f"no page {page.relative_to(out)} in the student web edition"
    text = _page_text(page)
    original = nbformat.read(ROOT / rel, as_version=4)
    for line in _solution_lines(original):
        assert line not in text, f"{page.name}: solution text in the student page: {line}"
    for cell in original.cells:
        if "exercise" in _tags(cell):
            first = cell.source.splitlines()[0]
            assert first in text, f"{page.name}: the exercise stub `{first}` is missing"


def test_no_instructors_page_in_the_student_web_edition(student_edition):
    out, _ = student_edition
    assert (out / "html" / "index.html").is_file() or (out / "html" / "book").is_dir()
    assert not (out / "html" / "book" / "instructors.html").exists()
