"""The student edition keeps every task (guard 1 of issue 21).

For every exercise of every notebook that ``_toc.yml`` lists, the student's copy
(``tools/student_edition.student_notebook``, the transformation ``make student`` applies before
it executes the notebooks) must hold:

- above the stub, the exercise's statement: a heading or a bold lead that names the exercise
  (``## Exercise 2: ...``, ``**Exercise 2.**``, ``**2. ...**``), then the task, which names the
  function the stub defines and says what to do (at least :data:`MIN_TASK_WORDS` words);
- no solution: no cell tagged ``solution`` or ``solution-note``;
- after the stub, up to the next exercise, heading or question, nothing the student has not
  written: no markdown (a folded answer, a verdict, a pointer to a solution) and no code cell
  that prints (a judgement printed in the open, an answer computed for them).

The checks read the book's stored notebooks (the outputs a kept cell prints in the student
edition are the ones it printed in the book), so they run in seconds; the kit's
``test_student_edition.py`` checks the executed edition as ``make student`` builds it. The
guard is shown to fail on planted notebooks at the end of this file.
"""

from __future__ import annotations

import re
from pathlib import Path

import nbformat
import pytest

from tools.book_text import output_text, tags
from tools.student_edition import student_notebook, toc_notebooks

ROOT = Path(__file__).resolve().parents[2]

#: An exercise's heading or bold lead, at the start of a line.
LEAD = re.compile(r"^(?:#{1,4}[ \t]+Exercise\b[^\n]*|\*\*(?:Exercise\b|\d+(?:[.:)]| \())[^\n]*)",
                  re.M)
#: What ends the part of the page that belongs to one exercise's stub.
SPAN_END = re.compile(r"^(?:#{1,4}[ \t]|[:`]{3,}\{admonition\} Check your understanding)", re.M)
DEF = re.compile(r"^def[ \t]+(\w+)\s*\(", re.M)
MIN_TASK_WORDS = 12


def _words(text: str) -> int:
    return len(re.findall(r"[A-Za-z]{2,}", text))


def task_problems(nb, name: str = "notebook") -> list[str]:
    """What is wrong with the exercises of a *student* notebook: missing statements, solutions
    left in, and anything printed or written after a stub before the next exercise."""
    problems = []
    cells = nb.cells
    stubs = [i for i, c in enumerate(cells) if c.cell_type == "code" and "exercise" in tags(c)]
    for index, cell in enumerate(cells):
        if tags(cell) & {"solution", "solution-note"}:
            problems.append(f"{name}: cell {index} is tagged {sorted(tags(cell))}: a solution "
                            "left in the student edition")
    for number, stub in enumerate(stubs):
        functions = DEF.findall(cells[stub].source)
        label = f"{name}: exercise stub {functions[0] if functions else f'cell {stub}'}"
        start = stubs[number - 1] + 1 if number else 0
        before = "\n\n".join(c.source for c in cells[start:stub] if c.cell_type == "markdown")
        leads = list(LEAD.finditer(before))
        if not leads:
            problems.append(f"{label}: no statement above it (no heading or bold lead naming "
                            "the exercise since the previous stub)")
        else:
            task = before[leads[-1].start():]
            if functions and not re.search(rf"\b{re.escape(functions[0])}\b", task):
                problems.append(f"{label}: its statement does not name `{functions[0]}`")
            if _words(task) < MIN_TASK_WORDS:
                problems.append(f"{label}: its statement has no task ({_words(task)} words)")
        for after in range(stub + 1, stubs[number + 1] if number + 1 < len(stubs)
                           else len(cells)):
            cell = cells[after]
            if cell.cell_type == "markdown":
                lead = LEAD.search(cell.source)
                end = SPAN_END.search(cell.source)
                cut = min(m.start() for m in (lead, end) if m) if (lead or end) else None
                text = cell.source if cut is None else cell.source[:cut]
                if text.strip():
                    problems.append(f"{label}: cell {after} after the stub shows "
                                    f"{' '.join(text.split())[:90]!r}")
                if cut is not None:
                    break
            elif output_text(cell).strip():
                problems.append(f"{label}: cell {after} after the stub prints "
                                f"{' '.join(output_text(cell).split())[:90]!r}")
    return problems


def source_problems(nb, name: str = "notebook") -> list[str]:
    """Tags of the *book's* notebook that would remove a statement: a ``solution`` or
    ``solution-note`` cell that holds an exercise's heading."""
    return [f"{name}: cell {i} is tagged {sorted(tags(c) & {'solution', 'solution-note'})} "
            f"but holds the statement {LEAD.search(c.source).group(0)[:60]!r}"
            for i, c in enumerate(nb.cells)
            if c.cell_type == "markdown" and tags(c) & {"solution", "solution-note"}
            and LEAD.search(c.source)]


def _student_problems(book, name: str = "notebook") -> list[str]:
    """The guard's findings on a book notebook: its tags, then its student copy."""
    problems = source_problems(book, name)
    try:
        student, _ = student_notebook(book)
    except ValueError as error:  # the tool refuses to delete a statement
        return [*problems, f"{name}: make student refuses it: {error}"]
    return problems + task_problems(student, name)


NOTEBOOKS = [p for p in toc_notebooks() if any(
    "exercise" in tags(c) for c in nbformat.read(ROOT / p, as_version=4).cells)]


@pytest.mark.parametrize("rel", NOTEBOOKS, ids=lambda p: p.as_posix())
def test_the_student_edition_keeps_every_task(rel):
    book = nbformat.read(ROOT / rel, as_version=4)
    assert not _student_problems(book, rel.as_posix()), "\n".join(
        _student_problems(book, rel.as_posix()))


def test_there_are_exercises_to_check():
    assert len(NOTEBOOKS) >= 8


# --- the guard itself, on planted notebooks ---------------------------------------------------

def _cell(kind: str, source: str, *tag_names: str, printed: str = ""):
    cell = (nbformat.v4.new_markdown_cell(source) if kind == "md"
            else nbformat.v4.new_code_cell(source))
    if tag_names:
        cell.metadata["tags"] = list(tag_names)
    if printed:
        cell.outputs = [nbformat.v4.new_output("display_data",
                                               data={"text/markdown": printed})]
    return cell


STATEMENT = ("## Exercise 1: the turn\n\nWrite `turn(v, omega)` returning the radius of the "
             "turn in metres, positive to the left, for a forward speed and a yaw rate.")
STUB = 'def turn(v, omega):\n    raise NotImplementedError\n\n\ncheck("demo.turn", turn)'
SOLUTION = 'def turn(v, omega):\n    return v / omega\n\n\ncheck("demo.turn", turn)'


def _book(*cells):
    return nbformat.v4.new_notebook(cells=list(cells))


def test_a_well_made_exercise_passes():
    book = _book(_cell("md", STATEMENT), _cell("code", STUB, "exercise"),
                 _cell("md", "The solution is folded below.", "solution-note"),
                 _cell("code", SOLUTION, "solution", "hide-input"),
                 _cell("md", "## Summary\n\n- Radius is speed over yaw rate."))
    assert _student_problems(book) == []


def test_the_guard_catches_a_statement_tagged_as_a_solution_note():
    """Chapter 8's defect: the statements were tagged ``solution-note`` and deleted."""
    book = _book(_cell("md", STATEMENT, "solution-note"), _cell("code", STUB, "exercise"),
                 _cell("code", SOLUTION, "solution", "hide-input"))
    found = _student_problems(book)
    assert any("holds the statement" in p for p in found)
    assert any("make student refuses it" in p for p in found)
    untagged_but_gone = _book(_cell("md", "Some text."), _cell("code", STUB, "exercise"))
    assert any("no statement above it" in p for p in _student_problems(untagged_but_gone))


def test_the_guard_catches_a_heading_without_a_task():
    book = _book(_cell("md", "## Exercise 1"), _cell("code", STUB, "exercise"))
    assert any("does not name `turn`" in p for p in _student_problems(book))


def test_the_guard_catches_a_judgement_printed_in_the_open():
    """Chapter 6's defect: a design verdict printed by a cell the student edition keeps."""
    book = _book(_cell("md", STATEMENT), _cell("code", STUB, "exercise"),
                 _cell("code", SOLUTION, "solution", "hide-input"),
                 _cell("code", "verdict()", "hide-input",
                       printed="A 4 m corridor is not safe: it needs a fix on the way."),
                 _cell("md", "## Summary"))
    assert any("prints 'A 4 m corridor is not safe" in p for p in _student_problems(book))


def test_the_guard_catches_a_folded_answer():
    book = _book(_cell("md", STATEMENT), _cell("code", STUB, "exercise"),
                 _cell("md", ":::{admonition} Our answer\n:class: dropdown\nThe radius is "
                             "v/omega.\n:::\n\n## Exercise 2: more\n\nWrite `more()`."))
    assert any("after the stub shows" in p for p in _student_problems(book))
