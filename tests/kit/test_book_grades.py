"""The book's own solutions pass the real grader (issue 21, guard 2), and the blank student
edition gets nothing.

Every notebook with exercises is turned into two submissions: the student edition (as
``make student`` makes it) with each exercise stub replaced by the book's solution, as a
student who solved everything hands it in, and the blank student edition. Both are graded
by ``tools/grade.py`` itself, the path ``make grade`` and Gradescope take (sandboxes, the
function rebuilt where only the exercise's declared library parts exist, hidden cases, the
exercise's judge). A solution that uses the library without its exercise declaring that
part scores 0 there, and fails this test. The assignments shipped in ``assignments/`` are
checked against the notebooks too."""

from __future__ import annotations

import csv
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

from tools.grading import notebook as nbtools
from tools.grading.assignment import load
from tools.student_edition import student_notebook, toc_notebooks
from wheelkin.exercises import all_exercises

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def _tags(cell) -> set[str]:
    return set(cell.get("metadata", {}).get("tags", []))


NOTEBOOKS = [rel for rel in toc_notebooks()
             if any("solution" in _tags(c) for c in nbformat.read(ROOT / rel, 4).cells)]


def exercises_of(rel: Path) -> list[str]:
    nb = nbformat.read(ROOT / rel, as_version=4)
    return list(dict.fromkeys(n for c in nb.cells if "exercise" in _tags(c)
                              for n in nbtools.checked_names(c)))


def solved(nb) -> nbformat.NotebookNode:
    """The student edition of ``nb`` with the book's solutions in place of the stubs."""
    return nbtools.with_solutions(student_notebook(nb)[0], nb)


def _stem(rel: Path) -> str:
    return rel.with_suffix("").as_posix().replace("/", "-")


@pytest.fixture(scope="module")
def book_graded(tmp_path_factory):
    """Every notebook, solved and blank, graded in one run against every exercise."""
    top = tmp_path_factory.mktemp("book-grades")
    folder = top / "submissions"
    folder.mkdir()
    for rel in NOTEBOOKS:
        nb = nbformat.read(ROOT / rel, as_version=4)
        nbformat.write(solved(nb), folder / f"{_stem(rel)}.solved.ipynb")
        nbformat.write(student_notebook(nb)[0], folder / f"{_stem(rel)}.blank.ipynb")
    lines = ['title = "every exercise of the book"', "time_limit = 900", "call_limit = 120"]
    for name in sorted(all_exercises()):
        lines += ["[[exercise]]", f'name = "{name}"']
    (top / "all.toml").write_text("\n".join(lines) + "\n", encoding="utf-8")
    done = subprocess.run([sys.executable, "-m", "tools.grade", str(folder),
                           "--assignment", str(top / "all.toml"), "--out", str(top / "out"),
                           "-j", "2"], capture_output=True, text=True, cwd=ROOT, timeout=3600)
    print(done.stdout)
    assert done.returncode == 0, done.stdout + done.stderr
    with (top / "out" / "grades.csv").open(encoding="utf-8", newline="") as f:
        return {row["student"]: row for row in csv.DictReader(f)}


@pytest.mark.parametrize("rel", NOTEBOOKS, ids=lambda p: p.as_posix())
def test_the_books_solutions_get_full_marks(book_graded, rel):
    row = book_graded[f"{_stem(rel)}.solved"]
    assert row["status"] == "graded", row["status"]
    names = exercises_of(rel)
    assert names, f"{rel} has solutions but no exercise stub"
    failed = [n for n in names if float(row[n]) != 1.0]
    assert not failed, f"{rel}: the book's solution scores 0 for {', '.join(failed)} " \
                       f"(see {rel.stem}.solved's results.json)"


@pytest.mark.parametrize("rel", NOTEBOOKS, ids=lambda p: p.as_posix())
def test_the_blank_student_edition_gets_zero(book_graded, rel):
    row = book_graded[f"{_stem(rel)}.blank"]
    assert row["status"] == "graded", row["status"]
    assert float(row["total"]) == 0.0


def test_every_solved_exercise_is_one_of_the_book():
    """Together the notebooks exercise every registered exercise (the runs above cover them
    all)."""
    assert sorted(n for rel in NOTEBOOKS for n in exercises_of(rel)) == sorted(all_exercises())


def test_the_shipped_assignments_match_the_notebooks():
    """``assignments/`` has one file per notebook with exercises, naming that notebook and
    exactly its exercises (make one with ``python -m tools.grade --assignment-for NOTEBOOK``)."""
    shipped = {path.stem: load(path) for path in sorted((ROOT / "assignments").glob("*.toml"))}
    for rel in NOTEBOOKS:
        stem = f"{rel.parent.name}-{rel.stem}"
        assert stem in shipped, (f"no assignments/{stem}.toml: write it with .venv/bin/python "
                                 f"-m tools.grade --assignment-for {rel.as_posix()} > "
                                 f"assignments/{stem}.toml")
        assignment = shipped.pop(stem)
        assert assignment.notebook == rel.name
        assert assignment.names == exercises_of(rel), stem
    assert not shipped, f"assignments for no notebook: {sorted(shipped)}"
