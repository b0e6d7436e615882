"""The grader (tools/grade.py, ``make grade``) on the honest fixtures in ``submissions/``
(written by make_submissions.py) against ``assignments/conventions.toml``: the right points
and messages for a correct, a wrong, a library-calling, a raising, an endless, a too
talkative submission and a file that is not a notebook; Gradescope's results.json; a grader
killed half-way that resumes; an exercise's judge with its own limits."""

from __future__ import annotations

import csv
import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tools.grading import jail
from tools.grading.judge import Judges
from tools.grading.wire import encode_case
from wheelkin.exercises import get
from wheelkin.exercises.sandbox import grip_ramp_time

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]

SUBMISSIONS = HERE / "submissions"
ASSIGNMENT = HERE / "assignments" / "conventions.toml"
EXERCISES = ["conventions.rover_radius", "conventions.icr", "conventions.encoder_steps",
             "sandbox.grip_ramp_time"]
LIMIT_S = 20  # the assignment's time limit: the endless notebook's


def grade(folder: Path, out: Path, *extra: str, timeout: float = 900):
    """Run ``make grade``'s command; return (grades.csv rows by student, results by folder,
    the log)."""
    done = subprocess.run([sys.executable, "-m", "tools.grade", str(folder),
                           "--assignment", str(ASSIGNMENT), "--out", str(out), "-j", "2",
                           *extra], capture_output=True, text=True, cwd=ROOT, timeout=timeout)
    print(done.stdout)  # seconds per submission, in the log
    assert done.returncode == 0, done.stdout + done.stderr
    return (*read(out), done.stdout)


def sandbox_uids(log: str) -> list[int]:
    """The uids of a run's two workers' sandboxes, from its log (as root)."""
    found = re.search(r"sandbox uids (\d+)\.\.", log)
    assert found, log
    return [int(found.group(1)) + slot for slot in range(2)]


def read(out: Path):
    with (out / "grades.csv").open(encoding="utf-8", newline="") as f:
        rows = {row["student"]: row for row in csv.DictReader(f)}
    results = {p.parent.name: json.loads(p.read_text(encoding="utf-8"))
               for p in (out / "results").glob("*/results.json")}
    return rows, results


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    return grade(SUBMISSIONS, tmp_path_factory.mktemp("grades"))


def points(row) -> list[float]:
    return [float(row[name]) for name in EXERCISES]


def message(results, student, name) -> str:
    return next(t["output"] for t in results[student]["tests"] if t["name"] == name)


def test_every_submission_has_a_row_and_a_results_json(graded):
    rows, results, _ = graded
    students = {"correct", "wrong", "calls_library", "raises", "loops_forever",
                "prints_too_much", "not_a_notebook.txt"}
    assert set(rows) == students and set(results) == students
    first = next(iter(rows.values()))
    assert list(first) == ["student", "file", "status", *EXERCISES, "total", "out_of"]
    for result in results.values():  # Gradescope's format
        assert {"score", "tests", "execution_time"} <= set(result)
        assert result["score"] == sum(t["score"] for t in result["tests"]) <= 5
        for test in result["tests"]:
            assert set(test) >= {"name", "score", "max_score", "output", "visibility"}
            assert test["output"].startswith(("✔", "✘"))


def test_correct_submission_gets_every_point(graded):
    rows, results, _ = graded
    assert rows["correct"]["status"] == "graded"
    assert points(rows["correct"]) == [1, 2, 1, 1] and rows["correct"]["total"] == "5"
    assert "10 hidden cases" in message(results, "correct", "conventions.icr")


def test_wrong_answers_score_zero_with_the_checks_diagnosis(graded):
    rows, results, _ = graded
    assert points(rows["wrong"]) == [0, 0, 1, 0]
    assert "sign must flip" in message(results, "wrong", "conventions.rover_radius")
    # A table of the visible answers passes the notebook's check but not the hidden cases,
    # and only the verdict shown after the due date says so.
    assert "hidden case" in message(results, "wrong", "conventions.icr")
    assert message(results, "wrong", "conventions.icr: visible cases").startswith("✔")
    assert "is missing" in message(results, "wrong", "sandbox.grip_ramp_time")


def test_calling_the_library_or_the_reference_scores_zero(graded):
    rows, results, _ = graded
    assert points(rows["calls_library"]) == [0, 0, 1, 0]
    for name, statement in (("conventions.rover_radius", "from wheelkin import frames"),
                            ("conventions.icr", "import wheelkin.exercises")):
        text = message(results, "calls_library", name)
        assert "the wheelkin library is not there" in text and statement in text


def test_raising_function_and_cell(graded):
    rows, results, _ = graded
    assert rows["raises"]["status"] == "graded"
    assert points(rows["raises"]) == [0, 2, 0, 0]
    assert "ZeroDivisionError" in message(results, "raises", "conventions.rover_radius")
    assert "not written yet" in message(results, "raises", "conventions.encoder_steps")
    assert "ValueError: I gave up here" in results["raises"]["output"]


@pytest.mark.parametrize(("student", "status"), [
    ("loops_forever", f"timed out: the notebook ran longer than {LIMIT_S} s"),
    ("prints_too_much", "too much output"),
    ("not_a_notebook.txt", "not a notebook"),
])
def test_submission_that_cannot_be_graded_gets_a_clear_line(graded, student, status):
    rows, results, _ = graded
    assert rows[student]["status"].startswith(status)
    assert points(rows[student]) == [0, 0, 0, 0]
    assert results[student]["output"].startswith(status)


def test_a_killed_grader_resumes_where_it_stopped(tmp_path):
    """Results are written as they come; a grader killed half-way (as by the machine) keeps
    them, and the next run grades only what is left, with the same hidden cases."""
    folder = tmp_path / "in"
    folder.mkdir()
    for name in ("correct", "wrong", "raises", "calls_library", "loops_forever"):
        (folder / f"{name}.ipynb").write_bytes((SUBMISSIONS / f"{name}.ipynb").read_bytes())
    out = tmp_path / "out"
    log = tmp_path / "first.log"
    with log.open("w") as stream:
        proc = subprocess.Popen([sys.executable, "-m", "tools.grade",
                                 str(folder), "--assignment", str(ASSIGNMENT), "--out",
                                 str(out), "-j", "2"], cwd=ROOT, stdout=stream,
                                stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and len(list(out.glob("results/*/results.json"))) < 2:
        time.sleep(0.2)
    os.kill(proc.pid, signal.SIGKILL)  # the main process only: its workers must follow
    proc.wait()
    first = {p.parent.name: p.read_text() for p in out.glob("results/*/results.json")}
    assert 2 <= len(first) < 5, sorted(first)
    if os.geteuid() == 0:  # nothing of the killed run is left running, within seconds
        uids = sandbox_uids(log.read_text())
        deadline = time.monotonic() + 15
        while time.monotonic() < deadline and any(jail.processes_of(u) for u in uids):
            time.sleep(0.2)
        assert [jail.processes_of(u) for u in uids] == [[], []]
    rows, _results, log = grade(folder, out)
    assert f"{len(first)} results kept from an earlier run" in log
    assert set(rows) == {"correct", "wrong", "raises", "calls_library", "loops_forever"}
    for student, text in first.items():  # kept, not graded again
        assert (out / "results" / student / "results.json").read_text() == text
    assert points(rows["correct"]) == [1, 2, 1, 1] and points(rows["wrong"]) == [0, 0, 1, 0]


def test_the_judge_that_simulates_has_its_own_limits():
    """The ramp exercise's judge runs the sandbox for the ramp answered: a right answer is
    judged in seconds, an absurd one is stopped at the exercise's limit."""
    exercise = get("sandbox.grip_ramp_time")
    cases = [encode_case(c.args, c.kwargs) for c in exercise.cases]
    good = [{"kind": "value", "shape": [], "values": [1.2 * grip_ramp_time(*c.args)]}
            for c in exercise.cases]
    slow = [{"kind": "value", "shape": [], "values": [2 * grip_ramp_time(*c.args)]}
            for c in exercise.cases]
    absurd = [{"kind": "value", "shape": [], "values": [4e5]} for _ in exercise.cases]
    judges = Judges(ROOT / "src")
    try:
        assert judges.verdict(exercise.name, cases, good, 60, 2**31)["passed"]
        reply = judges.verdict(exercise.name, cases, slow, 60, 2**31)
        assert not reply["passed"] and "longer than needed" in reply["message"]
        start = time.monotonic()
        assert judges.verdict(exercise.name, cases, absurd, 3, 2**31) == {"error": "time"}
        assert time.monotonic() - start < 6
        assert judges.verdict(exercise.name, cases, good, 60, 2**31)["passed"]  # a new judge
    finally:
        judges.close()
