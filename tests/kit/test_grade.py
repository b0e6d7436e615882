"""The grader (tools/grade.py, ``make grade SUBMISSIONS=...``) on the fixtures in
``submissions/`` (written by make_submissions.py): the right points and messages for a correct,
a wrong, a library-calling, a raising, an endless, a too-talkative submission and a file that
is not a notebook; Gradescope's results.json; hidden cases that the book's solutions pass and
a memorised answer fails."""

from __future__ import annotations

import ast
import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import nbformat
import numpy as np
import pytest

from tools import grade
from tools.student_edition import toc_notebooks
from wheelkin.exercises import Exercise, all_exercises, get

ROOT = Path(__file__).resolve().parents[2]


SUBMISSIONS = Path(__file__).resolve().parent / "submissions"
EXERCISES = ["conventions.encoder_steps", "conventions.icr", "conventions.rover_radius"]
LIMIT_S = 20  # the endless loop's limit; the others take a few seconds


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    out = tmp_path_factory.mktemp("grades")
    done = subprocess.run([sys.executable, "-m", "tools.grade", str(SUBMISSIONS),
                           "--out", str(out), "--timeout", str(LIMIT_S), "-j", "2"],
                          capture_output=True, text=True, cwd=ROOT, timeout=600)
    print(done.stdout)  # seconds per submission, in the log
    assert done.returncode == 0, done.stderr
    with (out / "grades.csv").open(encoding="utf-8") as f:
        rows = {row["student"]: row for row in csv.DictReader(f)}
    results = {p.parent.name: json.loads(p.read_text(encoding="utf-8"))
               for p in (out / "results").glob("*/results.json")}
    return rows, results


def _points(row) -> list[float]:
    return [float(row[name]) for name in EXERCISES]


def _message(results, student, name) -> str:
    return next(t["output"] for t in results[student]["tests"] if t["name"] == name)


def test_every_submission_has_a_row_and_a_results_json(graded):
    rows, results = graded
    students = {"correct", "wrong", "calls_library", "raises", "loops_forever",
                "prints_too_much", "not_a_notebook.txt"}
    assert set(rows) == students and set(results) == students
    assert list(next(iter(rows.values())))[:2] == ["student", "status"]
    for result in results.values():  # Gradescope's format
        assert {"score", "tests"} <= set(result)
        for test in result["tests"]:
            assert set(test) >= {"name", "score", "max_score", "output"}
            assert test["output"].startswith(("✔", "✘"))
        assert result["score"] == sum(t["score"] for t in result["tests"])


def test_correct_submission_gets_every_point(graded):
    rows, results = graded
    assert rows["correct"]["status"] == "graded"
    assert _points(rows["correct"]) == [1, 1, 1] and rows["correct"]["total"] == "3"
    assert "hidden cases" in _message(results, "correct", "conventions.icr")


def test_wrong_answers_score_zero_with_the_checks_diagnosis(graded):
    rows, results = graded
    assert _points(rows["wrong"]) == [1, 0, 0]
    assert "sign must flip" in _message(results, "wrong", "conventions.rover_radius")
    # A table of the visible answers passes the notebook's check but not the hidden cases.
    assert "hidden case" in _message(results, "wrong", "conventions.icr")


def test_calling_the_library_or_the_reference_scores_zero(graded):
    rows, results = graded
    assert _points(rows["calls_library"]) == [1, 0, 0]
    radius = _message(results, "calls_library", "conventions.rover_radius")
    assert "calls the wheelkin library" in radius and "rover_radius_to_ours" in radius
    icr = _message(results, "calls_library", "conventions.icr")
    assert "calls the wheelkin library" in icr and "wheelkin.exercises.conventions" in icr


def test_raising_function_and_cell(graded):
    rows, results = graded
    assert rows["raises"]["status"] == "graded"
    assert _points(rows["raises"]) == [0, 1, 0]
    assert "ZeroDivisionError" in _message(results, "raises", "conventions.rover_radius")
    assert "not written yet" in _message(results, "raises", "conventions.encoder_steps")
    assert "ValueError: I gave up here" in results["raises"]["output"]


@pytest.mark.parametrize(("student", "status"), [
    ("loops_forever", f"timed out: the notebook ran longer than {LIMIT_S} s"),
    ("prints_too_much", "too much output"),
    ("not_a_notebook.txt", "not a notebook"),
])
def test_submission_that_cannot_be_graded_gets_a_clear_line(graded, student, status):
    rows, results = graded
    assert rows[student]["status"].startswith(status)
    assert _points(rows[student]) == [0, 0, 0]
    assert results[student]["output"].startswith(status)


@pytest.mark.skipif(os.geteuid() != 0, reason="the kernel runs as nobody only under root")
def test_a_submission_cannot_write_outside_its_folder(tmp_path):
    target = ROOT / "_build" / "grader-escape.txt"
    target.unlink(missing_ok=True)
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(
        f"open({str(target)!r}, 'w').write('escaped')")])
    path = tmp_path / "escape.ipynb"
    nbformat.write(nb, path)
    result = grade.grade_submission(path, ["conventions.icr"], timeout=60)
    venv = Path(sys.executable).parent
    if not all(p.stat().st_mode & 0o001 for p in [venv, *venv.parents]):
        # A clone inside a private folder (mktemp -d makes it 0700): `nobody` cannot enter it,
        # so the grader runs the kernel as itself, and must say so.
        assert result.user != "nobody"
        assert any("cannot run this Python" in note for note in result.notes), result.notes
        pytest.skip(f"`nobody` cannot enter a folder above {venv}: the grader fell back, "
                    "as its notes say")
    assert result.user == "nobody"
    assert any("PermissionError" in note for note in result.notes), result.notes
    assert not target.exists()


def test_library_call_and_tampering_reports_score_zero():
    case_count = len(get("conventions.icr").cases)
    cases = list(get("conventions.icr").cases)
    value = {"kind": "value", "shape": [2], "values": [0.0, 2.0]}
    report = {"cases": [value] * case_count, "library": ["wheelkin.frames.icr"],
              "tampered": False}
    assert grade.judge("conventions.icr", report, cases, case_count).score == 0
    report = {**report, "library": [], "tampered": True}
    assert "call monitor" in grade.judge("conventions.icr", report, cases, case_count).message


def _solutions():
    """(exercise name, solution source, first code cell) of every solution in the book."""
    for rel in toc_notebooks():
        nb = nbformat.read(ROOT / rel, as_version=4)
        code = [c for c in nb.cells if c.cell_type == "code"]
        for cell in code:
            if "solution" in cell.metadata.get("tags", []):
                names = grade.find_exercises(nbformat.v4.new_notebook(cells=[cell]))
                for name, expr in names.items():
                    yield pytest.param(name, expr, cell.source, code[0].source,
                                       id=f"{rel.as_posix()}:{name}")


class _NoShell:
    """Stands in for IPython's shell: ``%matplotlib inline`` does nothing here."""

    @staticmethod
    def run_line_magic(*args, **kwargs):
        return None


@pytest.mark.parametrize(("name", "expr", "source", "first"), list(_solutions()))
def test_book_solutions_pass_the_hidden_cases(name, expr, source, first):
    """The hidden cases are valid inputs: the book's own solution passes them."""
    import matplotlib

    matplotlib.use("Agg", force=True)
    namespace = {"__name__": "__main__", "get_ipython": lambda: _NoShell}
    body = grade._python(first + "\n\n" + source)
    tree = ast.parse(body)
    tree.body = [n for n in tree.body if not (isinstance(n, ast.Expr) and isinstance(
        n.value, ast.Call) and getattr(n.value.func, "id", "") == "check")]
    exec(compile(tree, name, "exec"), namespace)
    fn = eval(expr, namespace)
    exercise = get(name)
    cases = list(exercise.cases) + grade.hidden_cases(exercise)
    graded = Exercise(name, exercise.prompt, exercise.reference, cases,
                      wheel_names=exercise.wheel_names, mistakes=exercise.mistakes,
                      rtol=exercise.rtol, atol=exercise.atol, register=False)
    result = graded.check(fn)
    assert result.passed, result.message


@pytest.mark.parametrize("name", sorted(all_exercises()))
def test_a_memorised_answer_fails_the_hidden_cases(name):
    """A function that returns the visible cases' answers from a table fails, wherever the
    exercise has a number to vary (an exercise of words or counts only has no hidden case)."""
    exercise = get(name)
    hidden = grade.hidden_cases(exercise)
    if not hidden:
        pytest.skip(f"{name}: no float input to vary")
    table = {repr(c): grade._expected(exercise, c) for c in exercise.cases}
    zero = np.zeros_like(next(iter(table.values())))

    def memorised(*args, **kwargs):
        from wheelkin.exercises import Case

        return table.get(repr(Case(tuple(args), kwargs)), zero)

    assert exercise.check(memorised).passed, "the memorised table passes the visible cases"
    cases = list(exercise.cases) + hidden
    graded = Exercise(name, exercise.prompt, exercise.reference, cases,
                      wheel_names=exercise.wheel_names, mistakes=exercise.mistakes,
                      rtol=exercise.rtol, atol=exercise.atol, register=False)
    assert not graded.check(memorised).passed
