"""The red team: one submission per attack class of the grader's red-team trial (issue 24),
graded in one run with honest submissions and copies of the correct one under awkward
names. Each gets the grade it deserves, and no one else's grade, file or process is touched:
the copies of the correct submission keep every point whatever ran beside them.

The attacks (``redteam/``, written by make_submissions.py; expected points for
rover_radius, icr (2 points), encoder_steps and the ramp):

- the library from a thread, from a forked process, from a copy of the package placed
  elsewhere or carried as text, after switching the old call monitor off: 0 for that
  exercise (no library where the function is graded);
- the grader's state changed from the notebook (check, numpy, forged reports): the grade of
  its own (wrong) functions;
- a classmate's notebook read: nothing to find, 0 for the exercise that needs it;
- processes left behind (new session, double fork) that would kill everyone later: its own
  grade; none survives the run;
- links planted and the shared files poisoned (the venv, the grader's scripts): its own
  grade; nothing outside its sandbox changes;
- extra exercises of other chapters: only the assignment's exercises count, no new column;
- checks in dead code: the check that ran counts;
- an absurd answer on the hidden cases for the judge that simulates: 0 for that exercise,
  within the judge's time or memory limit (whichever the run meets first);
- clashing names (``alice`` and ``alice.ipynb``, ``Bob``/``bob``, é in two Unicode forms),
  Unicode, a newline in a name, dot-files, a folder, links and a FIFO: a row each.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import sys
import unicodedata
from pathlib import Path

import nbformat
import pytest

from tests.kit.test_grade import EXERCISES, grade, sandbox_uids
from tools.grading import jail

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]

CORRECT = [1, 2, 1, 1]
#: Expected points (rover_radius, icr, encoder_steps, ramp) and words of the verdicts.
EXPECTED = {
    "correct": (CORRECT, []),
    "wrong": ([0, 0, 1, 0], []),
    "thread": ([0, 2, 1, 0], [("conventions.rover_radius", "wheelkin library is not there")]),
    "fork": ([1, 0, 1, 0], [("conventions.icr", "raised")]),
    "copied_package": ([0, 0, 1, 0], [("conventions.rover_radius", "No module named"),
                                      ("conventions.icr", "wheelkin library is not there")]),
    "monitor_disabled": ([0, 2, 1, 0], [("conventions.rover_radius",
                                         "wheelkin library is not there")]),
    "grader_state": ([0, 0, 0, 0], [("conventions.rover_radius", "you returned 0")]),
    "classmate_file": ([0, 2, 1, 0], [("conventions.rover_radius", "you returned 30")]),
    "left_behind": ([1, 2, 1, 0], []),
    "symlink_planted": ([1, 2, 1, 0], []),
    "extra_exercises": ([1, 2, 1, 0], []),
    "dead_code_check": ([0, 2, 0, 0], [("conventions.rover_radius", "sign must flip"),
                                       ("conventions.encoder_steps", "never ran")]),
    "absurd_judge_input": ([1, 2, 1, 0], [("sandbox.grip_ramp_time",
                                           "could not be judged within the judge's")]),
    # copies under awkward names
    "Ünïcødé 学生": (CORRECT, []),
    "alice": (CORRECT, []),
    "alice.ipynb": (CORRECT, []),
    "Bob": (CORRECT, []),
    "bob": ([0, 0, 1, 0], []),
    ".hidden": (CORRECT, []),
    "new\nline": (CORRECT, []),
}
NFC, NFD = unicodedata.normalize("NFC", "é"), unicodedata.normalize("NFD", "é")
NOT_GRADED = {
    ".DS_Store": "not a notebook",
    ".ipynb_checkpoints": "not graded: a folder",
    "planted": "not graded: a symbolic link",
    "shadow": "not graded: a symbolic link",
    "pipe": "not graded: not a regular file",
}


def _sandbox_files(top: Path) -> list[Path]:
    """Files under ``top`` owned by a sandbox's uid (there must be none)."""
    found = []
    for dirpath, dirnames, filenames in os.walk(top):
        for name in dirnames + filenames:
            path = Path(dirpath) / name
            try:
                if jail.UID_BASE <= path.lstat().st_uid < jail.UID_BASE + (
                        jail.BLOCK * jail.UID_BLOCKS):
                    found.append(path)
            except OSError:
                continue
    return found


def _daemons() -> list[int]:
    pids = []
    for entry in os.scandir("/proc"):
        if entry.name.isdigit():
            try:
                if b"wheelkin-redteam-daemon" in Path(entry.path, "cmdline").read_bytes():
                    pids.append(int(entry.name))
            except OSError:
                continue
    return pids


@pytest.fixture(scope="module")
def attacked(tmp_path_factory):
    folder = tmp_path_factory.mktemp("redteam") / "submissions"
    folder.mkdir()
    for source in (HERE / "submissions", HERE / "redteam"):
        for path in source.glob("*.ipynb"):
            shutil.copy(path, folder / path.name)
    correct = (folder / "correct.ipynb").read_bytes()
    wrong = (folder / "wrong.ipynb").read_bytes()
    for name, data in [("Ünïcødé 学生.ipynb", correct), ("alice.ipynb", correct),
                       ("alice", correct), ("Bob.ipynb", correct), ("bob.ipynb", wrong),
                       (f"{NFC}.ipynb", correct), (f"{NFD}.ipynb", wrong),
                       ("new\nline.ipynb", correct), (".hidden.ipynb", correct),
                       (".DS_Store", b"\x00\x01junk")]:
        (folder / name).write_bytes(data)
    (folder / ".ipynb_checkpoints").mkdir()
    (folder / "planted.ipynb").symlink_to("correct.ipynb")
    (folder / "shadow.ipynb").symlink_to("/etc/shadow")
    os.mkfifo(folder / "pipe.ipynb")
    before = {p: (p.lstat().st_uid, p.lstat().st_mode, hashlib.sha256(
        p.read_bytes() if p.is_file() and not p.is_symlink() else b"").hexdigest())
        for p in [*folder.iterdir(), Path("/etc/shadow"), Path("/etc/passwd")]
        if p.exists() or p.is_symlink()}
    out = folder.parent / "out"
    rows, results, log = grade(folder, out)
    return folder, out, rows, results, log, before


def _points(row) -> list[float]:
    return [float(row[name]) for name in EXERCISES]


@pytest.mark.parametrize("student", sorted(EXPECTED))
def test_each_submission_gets_the_grade_it_deserves(attacked, student):
    _, _out, rows, results, _, _ = attacked
    expected, words = EXPECTED[student]
    row = rows[student]
    assert row["status"] == "graded", row["status"]
    result = next(r for r in results.values() if r["extra_data"]["student"] == student)
    assert _points(row) == expected, {t["name"]: t["output"] for t in result["tests"]}
    for name, text in words:
        verdict = next(t["output"] for t in result["tests"] if t["name"] == name)
        assert text in verdict, verdict


def test_the_two_unicode_forms_of_a_name_are_two_rows(attacked):
    _, _, rows, _, _, _ = attacked
    assert _points(rows[NFC]) == CORRECT and _points(rows[NFD]) == [0, 0, 1, 0]


@pytest.mark.parametrize(("student", "status"), sorted(NOT_GRADED.items()))
def test_what_is_not_a_notebook_gets_a_row_that_says_why(attacked, student, status):
    _, _, rows, _, _, _ = attacked
    assert rows[student]["status"].startswith(status)
    assert _points(rows[student]) == [0, 0, 0, 0]


def test_every_entry_of_the_folder_has_its_own_row_and_results(attacked):
    folder, _out, rows, results, _, _ = attacked
    entries = os.listdir(folder)
    assert len(rows) == len(entries) == len(results)
    assert sorted(r["file"] for r in rows.values()) == sorted(entries)


def test_extra_exercises_add_no_column_and_no_point(attacked):
    _, out, rows, results, _, _ = attacked
    header = (out / "grades.csv").read_text(encoding="utf-8").splitlines()[0]
    assert header == ",".join(["student", "file", "status", *EXERCISES, "total", "out_of"])
    assert all(float(r["total"]) <= 5 for r in rows.values())
    assert "carlike.front_wheel_angles" in results["extra_exercises"]["output"]
    assert results["extra_exercises"]["score"] == 4


def test_nothing_outlives_the_run_and_nothing_outside_changed(attacked):
    folder, _out, _, _, _, before = attacked
    assert _daemons() == [], "a process left behind by a submission is still running"
    if os.geteuid() == 0:
        for uid in sandbox_uids(attacked[4]):
            assert jail.processes_of(uid) == []
        for top in (folder.parent, Path("/tmp"), ROOT / ".venv", ROOT / "src",
                    ROOT / "tools"):
            assert _sandbox_files(top) == [], top
    for path, (uid, mode, digest) in before.items():
        info = path.lstat()
        assert (info.st_uid, info.st_mode) == (uid, mode), path
        if path.is_file() and not path.is_symlink() and path.name != "shadow":
            assert hashlib.sha256(path.read_bytes()).hexdigest() == digest, path
    assert os.readlink(folder / "planted.ipynb") == "correct.ipynb"
    venv = Path(sys.prefix)
    assert not list(venv.glob("lib/python*/site-packages/sitecustomize.py"))
    assert "builtins.__import__ = None" not in (ROOT / "tools/grading/wire.py").read_text()


@pytest.mark.parametrize("planted", [True, False])
def test_the_thief_finds_a_classmate_where_one_is_visible(tmp_path, planted):
    """The classmate_file attack is a real search: in a sandbox that shows it a classmate's
    job (a grader that leaked one), it finds the answer; without one, its whole search ends
    in time and finds nothing, its own job's text included. So its 0 in the attacked run
    means nothing was visible, not a search that gave up or was blind."""
    cells = nbformat.read(HERE / "redteam" / "classmate_file.ipynb", as_version=4).cells
    thief = next(c.source for c in cells if "def _classmates_answer" in c.source)
    thief = thief.split("FOUND = _classmates_answer()")[0] + "print(_classmates_answer())\n"
    job, leak = tmp_path / "job", tmp_path / "leak"
    job.mkdir(), leak.mkdir()
    (job / "thief.py").write_text(thief, encoding="utf-8")
    (job / "job.json").write_text(json.dumps({"cells": [[0, thief]]}), encoding="utf-8")
    binds = [(job, jail.JOB)]
    if planted:
        classmate = nbformat.read(HERE / "submissions" / "correct.ipynb", as_version=4)
        (leak / "job.json").write_text(json.dumps(
            {"cells": [[i, c.source] for i, c in enumerate(classmate.cells)]}),
            encoding="utf-8")
        binds.append((leak, "/srv/leaked-job"))
    for path in (tmp_path, job, leak, *job.iterdir(), *leak.iterdir()):
        path.chmod(0o755 if path.is_dir() else 0o644)
    uid_base, lock = jail.claim_uids()
    try:
        etc = jail.write_etc(tmp_path / "etc", uid_base if os.geteuid() == 0 else 65534)
        box = jail.Sandbox(jail.Limits(seconds=60), etc, binds, uid_base=uid_base)
        outcome = box.run([jail.python_in_sandbox(), f"{jail.JOB}/thief.py"])
    finally:
        if lock is not None:
            os.close(lock)
    assert outcome.returncode == 0, outcome.tail
    assert outcome.tail.strip() == str(planted), outcome.tail
