#!/usr/bin/env python
"""Grade a folder of submitted notebooks against an assignment: one row per file, one column
per exercise, each submission in sandboxes of its own.

Usage::

    python -m tools.grade SUBMISSIONS --assignment FILE.toml [--out DIR] [-j 2] [--fresh]
    python -m tools.grade --gradescope /autograder --assignment FILE.toml
    python -m tools.grade --assignment-for NOTEBOOK.ipynb     # print an assignment to edit
    make grade SUBMISSIONS=folder ASSIGNMENT=file.toml        # results in _build/grades/

The assignment (``grading/assignment.py``: TOML, which exercises and their points) says what
is graded; nothing else in a notebook counts. For each file of ``SUBMISSIONS`` (every entry,
whatever its name; a folder, a link or a file that is not a notebook gets a row saying so):

1. **The notebook runs in a sandbox** (``grading/jail.py``: bubblewrap, its own PID, mount,
   IPC and network namespaces, an unprivileged user, a read-only system, a private home and
   /tmp, a clean environment, limits on time, memory, output, file size and processes;
   everything in it is killed when it ends). It runs top to bottom in an IPython shell, with
   the library, only to find what the student's cells define and which ``check`` calls ran.
   A notebook that runs longer than the time limit, prints too much or stops its Python
   scores 0, with the reason.
2. **Each exercise is graded outside the notebook.** The check that counts is the last
   ``check("name", f)`` of the exercise, at the top level of a cell, that ran. The statements
   of the notebook that ran before it and that ``f`` needs (its ``def``, the imports and
   helpers it uses) are run in a fresh interpreter in a sandbox of their own, where
   ``wheelkin`` cannot be imported (only the parts the exercise declares, e.g. a data table),
   and ``f`` is called there on the exercise's visible cases and on hidden ones, drawn from a
   secret made for this run (kept in the output folder, never in a sandbox). Only the
   answers come back, as JSON numbers.
3. **The grader judges** the answers with the exercise's own check (sign, swapped wheels,
   units, the exercise's typical mistakes), in a judge process with the exercise's time and
   memory limit, so the feedback reads like the notebook's.

Output in ``--out`` (written as each submission is graded; a grader stopped half-way resumes
where it stopped when run again with the same folder and assignment): ``grades.csv``
(``student``, ``file``, ``status``, one column per exercise with its points, ``total``,
``out_of``) and ``results/<student>/results.json`` in Gradescope's format, where hidden
cases' verdicts are visible only after the due date.
"""

from __future__ import annotations

import argparse
import csv
import ctypes
import hashlib
import hmac
import io
import json
import multiprocessing
import os
import secrets
import shutil
import signal
import stat
import sys
import tempfile
import time
import unicodedata
from collections.abc import Iterator
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import nbformat
import numpy as np

from tools.grading import jail, library_parts, wire
from tools.grading import notebook as nbtools
from tools.grading.assignment import (
    Assignment,
    AssignmentError,
    book_title,
    for_notebook,
    load,
)
from tools.grading.judge import Judges

ROOT = Path(__file__).resolve().parents[1]
TOOLS = ROOT / "tools"
#: The library's source: the notebook's sandbox gets it whole, an exercise's the parts it
#: declares (``grading/library_parts.py``).
SRC = ROOT / "src"
#: Largest file graded (bytes).
MAX_FILE_BYTES = 20_000_000
#: Bytes a notebook may print; bytes an exercise's calls may print.
MAX_OUTPUT_BYTES = 2_000_000
CALL_OUTPUT_BYTES = 1_000_000
#: Memory of the notebook's sandbox and of an exercise's (address space).
NOTEBOOK_MEMORY = 4 * 2**30
CALL_MEMORY = 2 * 2**30
#: Shown after a hidden case's failure.
HIDDEN_HINT = (" (a hidden case: your function must work for any input, not only the ones "
               "the notebook shows)")


# ----------------------------------------------------------------------------- results

@dataclass
class Verdict:
    name: str
    points: float
    score: float
    message: str           # the verdict on every case (visible and hidden)
    visible_message: str   # the verdict on the visible cases only


@dataclass
class SubmissionResult:
    student: str           # the file's name without ".ipynb" (its full name if that clashes)
    file: str              # the file's name, exactly (undecodable bytes escaped)
    folder: str = ""       # its folder under results/
    status: str = "graded"
    verdicts: list[Verdict] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    seconds: float = 0.0
    digest: str = ""       # sha256 of the file

    def total(self) -> float:
        return sum(v.score for v in self.verdicts)


def gradescope(result: SubmissionResult, assignment: Assignment, secret_id: str = "") -> dict:
    """Gradescope's ``results.json`` of one submission.

    Each exercise gives two tests: its visible cases (always shown, no points: the feedback
    the notebook's own check gives) and the exercise itself with its points, whose verdict
    covers the hidden cases and is shown after the due date (Gradescope then hides the total
    from the student until then). The score never exceeds the assignment's total.
    """
    tests = []
    for number, verdict in enumerate(result.verdicts, 1):
        tests.append({"name": f"{verdict.name}: visible cases", "number": f"{number}.1",
                      "score": 0.0, "max_score": 0.0, "output": verdict.visible_message,
                      "visibility": "visible"})
        tests.append({"name": verdict.name, "number": f"{number}.2", "score": verdict.score,
                      "max_score": verdict.points, "output": verdict.message,
                      "visibility": "after_due_date"})
    notes = ([] if result.status == "graded" else [result.status]) + result.notes
    out = {"score": round(min(result.total(), assignment.total), 6),
           "execution_time": round(result.seconds, 1), "stdout_visibility": "hidden",
           "tests": tests,
           "extra_data": {"student": result.student, "file": result.file,
                          "status": result.status, "sha256": result.digest,
                          "assignment": assignment.digest, "secret": secret_id}}
    if notes:
        out["output"] = "\n".join(notes)
    return out


# ----------------------------------------------------------------------------- the run

@dataclass
class Run:
    """What every worker needs, prepared once: the cases, the library parts, the work
    folder (root's, read-only to the sandboxes)."""

    assignment: Assignment
    cases: dict[str, list[dict]]      # visible then hidden, wire-encoded
    visible: dict[str, int]
    library: dict[str, str | None]    # exercise -> folder holding its parts (or None)
    work: str
    uid_base: int
    secret_id: str = ""


def draw_cases(assignment: Assignment, secret: bytes) -> tuple[dict, dict]:
    """Each exercise's cases: the visible ones, then hidden ones drawn with a generator
    seeded from ``secret`` and the exercise's name (the same for every submission of a run,
    unknown to anyone who does not have the secret)."""
    from wheelkin.exercises import get

    cases, visible = {}, {}
    for name in assignment.names:
        exercise = get(name)
        seed = int.from_bytes(hmac.new(secret, name.encode(), hashlib.sha256).digest(), "big")
        hidden = exercise.hidden_cases(np.random.default_rng(seed))
        if not hidden:
            raise RuntimeError(f"{name} has no hidden case: give the exercise hidden=...")
        everything = list(exercise.cases) + hidden
        cases[name] = [wire.encode_case(c.args, c.kwargs) for c in everything]
        visible[name] = len(exercise.cases)
    return cases, visible


def prepare(assignment: Assignment, secret: bytes, work: Path, uid_base: int) -> Run:
    """The run's work folder (library parts, fonts, passwd files) and cases; checks that the
    sandbox works and that the grading sandbox cannot import the library."""
    from wheelkin.exercises import get

    work.mkdir(parents=True, exist_ok=True)
    os.chmod(work, 0o755)
    library: dict[str, str | None] = {}
    for name in assignment.names:
        parts = get(name).library
        if parts:
            folder = work / "library" / name
            library_parts.build(list(parts), SRC, folder, name)
            library[name] = str(folder)
        else:
            library[name] = None
    fonts = work / "fonts"
    fonts.mkdir(exist_ok=True)
    try:
        import matplotlib

        for font_list in Path(matplotlib.get_cachedir()).glob("fontlist-*.json"):
            shutil.copy(font_list, fonts / font_list.name)
    except Exception:  # pragma: no cover - matplotlib builds its list in the sandbox then
        pass
    _readable(work)
    cases, visible = draw_cases(assignment, secret)
    run = Run(assignment, cases, visible, library, str(work), uid_base,
              secret_id=hashlib.sha256(secret).hexdigest()[:12])
    jail.probe(work, uid_base)
    _check_library_is_hidden(run)
    return run


def _readable(folder: Path) -> None:
    """Everything under ``folder`` readable by the sandboxes' users (written by us only)."""
    for path in [folder, *folder.rglob("*")]:
        os.chmod(path, 0o755 if path.is_dir() else 0o644)


def _check_library_is_hidden(run: Run) -> None:
    probe = {"statements": ["import importlib.util as _u\n",
                            "FOUND = _u.find_spec('wheelkin') is not None\n"],
             "expr": "lambda: FOUND", "cases": [wire.encode_case((), {})]}
    answers, _, _ = _call(run, 0, probe, None, 60.0)
    if not answers or answers.get(0, {}).get("values") != [0.0]:
        raise jail.SandboxUnavailable(
            "the grading sandbox can import wheelkin: install it editable (make setup) or "
            "from outside the virtual environment, so that only an exercise's declared parts "
            "are there")


# ----------------------------------------------------------------------------- one submission

_SLOT = 0
_JUDGES: Judges | None = None
_RUN: Run | None = None


def _init_worker(slots, run: Run) -> None:
    global _SLOT, _JUDGES, _RUN
    _SLOT = slots.get()
    _JUDGES = Judges(SRC)
    _RUN = run
    try:  # die with the grader: the sandboxes then die with us (--die-with-parent)
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except OSError:  # pragma: no cover - not glibc
        pass


def _work_job(run: Run, job: dict) -> Path:
    """A fresh folder holding ``job.json``, written before any sandbox sees it; the sandbox
    gets it read-only."""
    folder = Path(tempfile.mkdtemp(prefix="job-", dir=Path(run.work) / "jobs"))
    (folder / "job.json").write_text(json.dumps(job), encoding="utf-8")
    _readable(folder)
    return folder


def _sandbox(run: Run, slot: int, job_folder: Path, limits: jail.Limits,
             library: tuple[Path, str] | None) -> jail.Sandbox:
    uid = run.uid_base + slot if os.geteuid() == 0 else 65534
    etc = Path(run.work) / f"etc-{slot}"
    if not (etc / "passwd").is_file():
        jail.write_etc(etc, uid)
        _readable(etc)
    # The sandbox's scripts are modules of the tools package (tools/__init__.py and
    # tools/grading/, nothing else of the repository), found through PYTHONPATH, with the
    # library or the exercise's parts of it when there are any.
    binds = [(TOOLS / "__init__.py", f"{jail.SCRIPTS}/tools/__init__.py"),
             (TOOLS / "grading", f"{jail.SCRIPTS}/tools/grading"), (job_folder, jail.JOB)]
    path = [jail.SCRIPTS]
    if library is not None:
        binds.append(library)
        path.append(jail.LIBRARY)
    return jail.Sandbox(limits, etc, binds, slot=slot, uid_base=run.uid_base,
                        env={"PYTHONPATH": ":".join(path)})


def _inside(module: str) -> list[str]:
    """The command that runs ``tools.grading.<module>`` in a sandbox: no user site, no script
    folder or working directory on the path (``-P -s``: ``-I`` without ``-E``, since the
    sandbox's whole environment is the grader's own, PYTHONPATH included)."""
    return [jail.python_in_sandbox(), "-P", "-s", "-m", f"tools.grading.{module}",
            jail.REPORT_FD, f"{jail.JOB}/job.json"]


def read_submission(path: Path) -> bytes:
    """The bytes of a regular file, never through a link, never blocking on a FIFO."""
    fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise ValueError("not a regular file")
        if info.st_size > MAX_FILE_BYTES:
            raise OverflowError(f"the file is {info.st_size / 1e6:.1f} MB (limit "
                                f"{MAX_FILE_BYTES / 1e6:.0f} MB)")
        with os.fdopen(fd, "rb", closefd=False) as f:
            return f.read(MAX_FILE_BYTES + 1)
    finally:
        os.close(fd)


def parse_notebook(data: bytes, name: str):
    """The notebook in ``data`` or the reason it is not one."""
    try:
        nb = nbformat.reads(data.decode("utf-8"), as_version=4)
        if not isinstance(nb.get("cells"), list):
            raise ValueError("no cells")
        for cell in nb.cells:
            if not isinstance(cell, dict) or not isinstance(cell.get("source", ""),
                                                            (str, list)):
                raise ValueError("a cell without text")
    except Exception as exc:
        reason = str(exc).splitlines()[0][:80] if str(exc) else type(exc).__name__
        if "not appear to be JSON" in reason or isinstance(exc, (json.JSONDecodeError,
                                                                 UnicodeDecodeError)):
            reason = "it is not JSON" if not isinstance(exc, UnicodeDecodeError) else \
                "it is not UTF-8 text"
        return None, f"not a notebook: {name} could not be read as .ipynb ({reason})"
    return nb, ""


def grade_file(path: Path, result: SubmissionResult, run: Run | None = None,
               slot: int | None = None, judges: Judges | None = None) -> SubmissionResult:
    """Grade the submission at ``path`` into ``result``; never raises (a problem becomes the
    status, and every exercise of the assignment still gets its line)."""
    run = run or _RUN
    slot = _SLOT if slot is None else slot
    judges = judges or _JUDGES
    start = time.monotonic()
    try:
        _grade(path, result, run, slot, judges)
    except jail.SandboxUnavailable:
        raise
    except Exception as exc:
        result.status = f"not graded: the grader failed ({type(exc).__name__}: {exc})"
    result.seconds = time.monotonic() - start
    got = {v.name for v in result.verdicts}
    for name, points in run.assignment.exercises:
        if name not in got:
            text = f"✘ {name}: {result.status}"
            result.verdicts.append(Verdict(name, points, 0.0, text, text))
    order = {name: k for k, name in enumerate(run.assignment.names)}
    result.verdicts.sort(key=lambda v: order[v.name])
    return result


def _grade(path: Path, result: SubmissionResult, run: Run, slot: int, judges: Judges) -> None:
    try:
        data = read_submission(path)
    except (OverflowError, ValueError) as exc:
        result.status = f"not graded: {exc}"
        return
    result.digest = hashlib.sha256(data).hexdigest()
    nb, problem = parse_notebook(data, result.file)
    if nb is None:
        result.status = problem
        return
    cells = nbtools.code_cells(nb)
    report = _run_notebook(run, slot, cells, result)
    if result.status != "graded":
        return
    ran = nbtools.ran(cells, report)
    counted = nbtools.counted_checks(cells, ran)
    ignored = sorted(set(counted) - set(run.assignment.names))
    if ignored:
        result.notes.append("not graded here (not in this assignment): "
                            + ", ".join(ignored))
    present = {c.name for c in nbtools.checks(cells)}
    for name, points in run.assignment.exercises:
        if name not in counted:
            why = ("never ran (it is in dead code, or its cell stopped at an error before it)"
                   if name in present else "is missing")
            text = (f"✘ {name}: the check(\"{name}\", ...) of this exercise {why}: the "
                    "exercise is not graded.")
            result.verdicts.append(Verdict(name, points, 0.0, text, text))
            continue
        result.verdicts.append(_grade_exercise(run, slot, judges, name, points,
                                               counted[name], ran))


def _reported(outcome: jail.Outcome) -> Iterator[dict]:
    """The JSON objects a sandbox reported, one a line; any other line (text that is no JSON,
    or JSON that is not an object) is passed over."""
    for line in outcome.report:
        try:
            item = json.loads(line)
        except ValueError:
            continue
        if isinstance(item, dict):
            yield item


def _run_notebook(run: Run, slot: int, cells, result: SubmissionResult) -> dict:
    """Run the notebook in its sandbox; return ``{cell index: "all" | line}`` of what ran."""
    limits = jail.Limits(seconds=run.assignment.time_limit, memory=NOTEBOOK_MEMORY,
                         output=MAX_OUTPUT_BYTES)
    job = {"cells": [[c.index, c.source] for c in cells], "fonts": "/opt/fonts"}
    folder = _work_job(run, job)
    try:
        box = _sandbox(run, slot, folder, limits, (SRC / "wheelkin", jail.LIBRARY + "/wheelkin"))
        box.binds.append((Path(run.work) / "fonts", "/opt/fonts"))
        outcome = box.run(_inside("inside_run"))
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    report: dict[int, int | str] = {}
    done = False
    indices = {c.index for c in cells}
    for item in _reported(outcome):
        if item.get("done") is True:
            done = True
        cell, how = item.get("cell"), item.get("ran")
        if cell in indices and (how == "all" or (isinstance(how, int)
                                                 and not isinstance(how, bool))):
            if cell not in report:
                report[cell] = how
                if isinstance(item.get("error"), str):
                    result.notes.append(f"cell {cell} raised {item['error'][:200]}")
    if outcome.left_behind:
        result.notes.append(f"{outcome.left_behind} processes of the notebook outlived it "
                            "and were killed")
    limit = run.assignment.time_limit
    if outcome.timed_out:
        result.status = f"timed out: the notebook ran longer than {limit:g} s"
    elif outcome.over_output:
        result.status = (f"too much output: the notebook printed more than "
                         f"{MAX_OUTPUT_BYTES / 1e6:g} MB")
    elif not done:
        result.status = ("the notebook stopped before its end (its Python ran out of memory, "
                         "or the notebook ended it)")
    return report


def _call(run: Run, slot: int, job: dict, library: str | None,
          seconds: float) -> tuple[dict[int, dict], dict, jail.Outcome]:
    """Run an exercise's job in a fresh grading sandbox: the answers by case, what else the
    sandbox said (setup errors, a function that could not be made), the outcome."""
    limits = jail.Limits(seconds=seconds, memory=CALL_MEMORY, output=CALL_OUTPUT_BYTES)
    folder = _work_job(run, job)
    try:
        box = _sandbox(run, slot, folder, limits,
                       (Path(library), jail.LIBRARY) if library else None)
        outcome = box.run(_inside("inside_call"))
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    answers: dict[int, dict] = {}
    said: dict = {"setup": [], "function": None, "done": False}
    count = len(job["cases"])
    for item in _reported(outcome):
        if item.get("done") is True:
            said["done"] = True
        elif "case" in item:
            index = item["case"]
            answer = wire.checked_answer(item.get("answer"))
            if (isinstance(index, int) and not isinstance(index, bool) and 0 <= index < count
                    and answer is not None and index not in answers):
                answers[index] = answer
        elif isinstance(item.get("setup"), list) and not said["setup"]:
            said["setup"] = [[str(x)[: wire.MAX_TEXT] for x in pair[:2]]
                             for pair in item["setup"][:20] if isinstance(pair, list)]
        elif isinstance(item.get("function"), str) and said["function"] is None:
            said["function"] = item["function"][: wire.MAX_TEXT]
    return answers, said, outcome


def _library_hint(said: dict) -> str:
    """Why a name is missing when graded: a statement of the slice that failed there."""
    for statement, error in said["setup"]:
        if "wheelkin" in statement or "wheelkin" in error:
            return (f" When graded, the wheelkin library is not there (`{statement}` raised "
                    f"{error}): this exercise asks you to write it yourself.")
    if said["setup"]:
        statement, error = said["setup"][0]
        return f" When graded, `{statement}` raised {error}."
    return ""


def _grade_exercise(run: Run, slot: int, judges: Judges, name: str, points: float, check,
                    ran) -> Verdict:
    from wheelkin.exercises import get

    exercise = get(name)
    cases = run.cases[name]
    visible = run.visible[name]
    job = {"statements": nbtools.function_slice(check, ran), "expr": check.expr,
           "cases": cases}
    limit = run.assignment.call_limit
    answers, said, outcome = _call(run, slot, job, run.library[name], limit)
    if said["function"] is not None:
        text = (f"✘ {name}: `{check.expr}` is not a function when graded "
                f"({said['function']}).{_library_hint(said)}")
        return Verdict(name, points, 0.0, text, text)
    missing = [k for k in range(len(cases)) if k not in answers]
    if missing:
        if outcome.timed_out:
            why = f"no answer within the {limit:g} s this exercise's calls may take"
        elif outcome.over_output:
            why = f"your function printed more than {CALL_OUTPUT_BYTES / 1e6:g} MB"
        else:
            why = "the grader's Python stopped (out of memory, or your function ended it)"
        stand_in = {"kind": "raised", "ename": "GradingStopped", "evalue": why}
        for k in missing:
            answers[k] = stand_in
    reply = judges.verdict(name, cases, [answers[k] for k in range(len(cases))],
                           exercise.judge_seconds, exercise.judge_memory)
    if "error" in reply:
        what = ("time" if reply["error"] == "time" else "memory")
        text = (f"✘ {name}: your answers could not be judged within the judge's {what} limit "
                f"({exercise.judge_seconds:g} s, {exercise.judge_memory / 2**30:g} GiB): an "
                "answer far outside what the exercise asks for (a huge or tiny number) can "
                "make the judge's own computation run away. Scored 0.")
        return Verdict(name, points, 0.0, text, text)
    hidden = len(cases) - visible
    if reply["passed"]:
        return Verdict(name, points, points,
                       f"✔ {name}: correct on all {visible} visible and {hidden} hidden cases.",
                       f"✔ {name}: correct on all {visible} visible cases.")
    message = reply["message"]
    answer = answers.get(reply["at"], {})
    library_missing = any("wheelkin" in statement + error for statement, error in
                          said["setup"])
    if answer.get("kind") == "raised" and (library_missing or answer.get("ename") in (
            "NameError", "ModuleNotFoundError", "ImportError", "AttributeError")):
        hint = _library_hint(said) or (
            " When graded, the wheelkin library is not there: this exercise asks you to "
            "write it yourself." if "wheelkin" in answer.get("evalue", "") else "")
        if hint:
            message = message.rstrip(".") + "." + hint
    if reply["at"] >= visible and reply["kind"] != "not-written":
        return Verdict(name, points, 0.0, message + HIDDEN_HINT,
                       f"✔ {name}: correct on all {visible} visible cases.")
    return Verdict(name, points, 0.0, message, message)


# ----------------------------------------------------------------------------- the folder

@dataclass
class Entry:
    path: Path
    name: str          # printable (undecodable bytes escaped)
    kind: str          # "file", "link", "folder", "other"


def entries(folder: Path) -> list[Entry]:
    """Every entry of ``folder`` (dot-files, folders and links included), by name."""
    out = []
    with os.scandir(folder) as it:
        for item in it:
            name = item.name.encode("utf-8", "surrogateescape").decode("utf-8",
                                                                        "backslashreplace")
            if item.is_symlink():
                kind = "link"
            elif item.is_dir(follow_symlinks=False):
                kind = "folder"
            elif item.is_file(follow_symlinks=False):
                kind = "file"
            else:
                kind = "other"
            out.append(Entry(Path(item.path), name, kind))
    return sorted(out, key=lambda e: e.name)


def student_ids(items: list[Entry]) -> dict[str, tuple[str, str]]:
    """For each entry's name: (student id, results folder). The id is the name without
    ``.ipynb`` (Unicode kept), or the whole name when two entries would share an id; the
    folder is the id made safe for a path (control characters replaced), with ``~2``,
    ``~3`` ... where two would look the same (case, Unicode normal form)."""
    stems = {}
    for item in items:
        stem = item.name[:-6] if item.name.endswith(".ipynb") and len(item.name) > 6 \
            else item.name
        stems.setdefault(stem, []).append(item.name)
    ids = {}
    for stem, names in stems.items():
        for name in names:
            ids[name] = stem if len(names) == 1 else name
    out, taken = {}, set()
    for item in items:
        student = ids[item.name]
        safe = "".join("_" if (unicodedata.category(ch)[0] == "C" or ch in "/\\") else ch
                       for ch in unicodedata.normalize("NFC", student))
        if safe in ("", ".", ".."):
            safe = "_" + safe
        folder, k = safe, 1
        while folder.casefold() in taken:
            k += 1
            folder = f"{safe}~{k}"
        taken.add(folder.casefold())
        out[item.name] = (student, folder)
    return out


def write_csv(results: list[SubmissionResult], assignment: Assignment, out: Path) -> Path:
    """``grades.csv`` (replaced whole, atomically)."""
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(["student", "file", "status", *assignment.names, "total", "out_of"])
    for r in results:
        points = {v.name: v.score for v in r.verdicts}
        writer.writerow([r.student, r.file, r.status,
                         *(f"{points.get(n, 0.0):g}" for n in assignment.names),
                         f"{min(r.total(), assignment.total):g}", f"{assignment.total:g}"])
    return _atomic_write(out / "grades.csv", buffer.getvalue())


def _atomic_write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, path)
    return path


def write_result(result: SubmissionResult, assignment: Assignment, out: Path,
                 secret_id: str) -> Path:
    return _atomic_write(out / "results" / result.folder / "results.json",
                         json.dumps(gradescope(result, assignment, secret_id), indent=1,
                                    ensure_ascii=False) + "\n")


def _from_results(path: Path, entry: Entry, assignment: Assignment,
                  secret_id: str) -> SubmissionResult | None:
    """A result written by an earlier run of the same grading (same file bytes, assignment
    and secret), to resume from; else None."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        extra = data["extra_data"]
        if extra["assignment"] != assignment.digest or extra["secret"] != secret_id:
            return None
        if entry.kind == "file":
            digest = hashlib.sha256(read_submission(entry.path)).hexdigest()
            if digest != extra["sha256"]:
                return None
        elif extra["sha256"]:
            return None
        result = SubmissionResult(extra["student"], extra["file"], path.parent.name,
                                  extra["status"], digest=extra["sha256"],
                                  seconds=float(data.get("execution_time", 0.0)))
        result.notes = [n for n in data.get("output", "").splitlines()
                        if n != result.status]
        tests = data["tests"]
        for k in range(0, len(tests), 2):
            seen, full = tests[k], tests[k + 1]
            result.verdicts.append(Verdict(full["name"], float(full["max_score"]),
                                           float(full["score"]), full["output"],
                                           seen["output"]))
        if [v.name for v in result.verdicts] != assignment.names:
            return None
        return result
    except (OSError, ValueError, KeyError, IndexError, TypeError):
        return None


def _secret(out: Path, fresh: bool) -> bytes:
    """The run's secret: kept (mode 0600) in the output folder so that a resumed run draws
    the same hidden cases; a new one with ``fresh``."""
    state = out / ".grader"
    state.mkdir(parents=True, exist_ok=True)
    os.chmod(state, 0o700)
    path = state / "secret"
    if path.is_file() and not fresh:
        return bytes.fromhex(path.read_text().strip())
    secret = secrets.token_bytes(32)
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    with os.fdopen(fd, "w") as f:
        f.write(secret.hex())
    return secret


def not_graded(entry: Entry) -> str:
    if entry.kind == "link":
        return "not graded: a symbolic link (the grader never follows links)"
    if entry.kind == "folder":
        return "not graded: a folder, not a notebook"
    return "not graded: not a regular file"


def grade_folder(folder: Path, assignment: Assignment, out: Path, jobs: int = 2,
                 fresh: bool = False, log=print) -> list[SubmissionResult]:
    """Grade every entry of ``folder``; write each result as soon as it exists."""
    items = entries(folder)
    ids = student_ids(items)
    if fresh and (out / "results").exists():
        shutil.rmtree(out / "results")
    secret = _secret(out, fresh)
    secret_id = hashlib.sha256(secret).hexdigest()[:12]
    results: dict[str, SubmissionResult] = {}
    todo = []
    for entry in items:
        student, results_folder = ids[entry.name]
        previous = _from_results(out / "results" / results_folder / "results.json", entry,
                                 assignment, secret_id)
        if previous is not None:
            results[entry.name] = previous
            continue
        result = SubmissionResult(student, entry.name, results_folder)
        if entry.kind != "file":
            result.status = not_graded(entry)
            result.verdicts = _nothing_graded(assignment, result.status)
            results[entry.name] = result
            write_result(result, assignment, out, secret_id)
            log(_line(result, assignment))
        else:
            todo.append((entry, result))
    kept = len(items) - len(todo) - sum(e.kind != "file" for e in items)
    if kept:
        log(f"grade: {kept} results kept from an earlier run of this grading")
    write_csv([results[e.name] for e in items if e.name in results], assignment, out)
    if not todo:
        return [results[e.name] for e in items]
    with _grading_run(assignment, secret) as (run, claimed):
        if claimed:
            log(f"grade: sandbox uids {run.uid_base}..{run.uid_base + jail.BLOCK - 1}")
        context = multiprocessing.get_context("fork")
        slots = context.Queue()
        workers = max(1, min(jobs, len(todo)))
        for slot in range(workers):
            slots.put(slot)
        with ProcessPoolExecutor(max_workers=workers, mp_context=context,
                                 initializer=_init_worker, initargs=(slots, run)) as pool:
            futures = {pool.submit(grade_file, entry.path, result): entry
                       for entry, result in todo}
            for future in as_completed(futures):
                entry = futures[future]
                result = future.result()
                results[entry.name] = result
                write_result(result, assignment, out, secret_id)
                write_csv([results[e.name] for e in items if e.name in results], assignment,
                          out)
                log(_line(result, assignment))
    return [results[e.name] for e in items]


def _nothing_graded(assignment: Assignment, why: str) -> list[Verdict]:
    """Every exercise of the assignment at 0 points, for ``why`` (the submission was not run)."""
    return [Verdict(n, p, 0.0, f"✘ {n}: {why}", f"✘ {n}: {why}") for n, p in assignment.exercises]


@contextmanager
def _grading_run(assignment: Assignment, secret: bytes) -> Iterator[tuple[Run, bool]]:
    """A grading run's work folder (prepared, its jobs folder open to the sandboxes) and block
    of sandbox uids: ``(run, whether the block was claimed by a lock)``; the folder is removed
    and the block given back when the run ends."""
    work = Path(tempfile.mkdtemp(prefix="wheelkin-grade-"))
    (work / "jobs").mkdir()
    uid_base, lock = jail.claim_uids()
    try:
        run = prepare(assignment, secret, work, uid_base)
        (work / "jobs").chmod(0o755)
        yield run, lock is not None
    finally:
        shutil.rmtree(work, ignore_errors=True)
        if lock is not None:
            os.close(lock)


def _line(result: SubmissionResult, assignment: Assignment) -> str:
    name = result.student.encode("unicode_escape").decode("ascii") if not \
        result.student.isprintable() else result.student
    return (f"{name:24s} {min(result.total(), assignment.total):5g}/{assignment.total:g}  "
            f"{result.seconds:5.1f} s  {result.status}")


# ----------------------------------------------------------------------------- Gradescope

def pick_notebook(submission: Path, wanted: str | None) -> tuple[Path | None, str]:
    """The notebook of a Gradescope submission: the file the assignment names, else the only
    ``.ipynb`` (links never followed)."""
    found = []
    for dirpath, dirnames, filenames in os.walk(submission, followlinks=False):
        dirnames[:] = [d for d in dirnames if d != ".ipynb_checkpoints"]
        for name in filenames:
            path = Path(dirpath) / name
            if name.endswith(".ipynb") and not path.is_symlink():
                found.append(path)
    if wanted:
        named = [p for p in found if p.name == wanted]
        if named:
            return sorted(named)[0], ""
    if len(found) == 1:
        return found[0], ""
    if not found:
        return None, ("no notebook (.ipynb) in your submission"
                      + (f": hand in {wanted}" if wanted else ""))
    names = ", ".join(sorted(str(p.relative_to(submission)) for p in found))
    return None, (f"several notebooks in your submission ({names}): hand in "
                  + (wanted if wanted else "one"))


def gradescope_run(root: Path, assignment: Assignment) -> int:
    """Gradescope's ``run_autograder``: grade ``root/submission``, write
    ``root/results/results.json``. A fresh secret per run, never written anywhere."""
    results_dir = root / "results"
    results_dir.mkdir(parents=True, exist_ok=True)
    path, problem = pick_notebook(root / "submission", assignment.notebook)
    result = SubmissionResult("submission", path.name if path else "")
    secret = secrets.token_bytes(32)
    secret_id = hashlib.sha256(secret).hexdigest()[:12]
    if path is None:
        result.status = problem
        result.verdicts = _nothing_graded(assignment, problem)
    else:
        with _grading_run(assignment, secret) as (run, _claimed):
            judges = Judges(SRC)
            try:
                grade_file(path, result, run, slot=0, judges=judges)
            finally:
                judges.close()
    _atomic_write(results_dir / "results.json",
                  json.dumps(gradescope(result, assignment, secret_id), indent=1,
                             ensure_ascii=False) + "\n")
    print(f"graded {result.file or 'nothing'}: {min(result.total(), assignment.total):g}/"
          f"{assignment.total:g} ({result.status})")
    return 0


# ----------------------------------------------------------------------------- command line

def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("submissions", type=Path, nargs="?", help="folder of submissions")
    parser.add_argument("--assignment", type=Path, help="the assignment (TOML)")
    parser.add_argument("--out", type=Path, default=ROOT / "_build" / "grades")
    parser.add_argument("-j", "--jobs", type=int, default=2,
                        help="submissions graded at once (2)")
    parser.add_argument("--fresh", action="store_true",
                        help="grade everything again with a new secret (default: resume)")
    parser.add_argument("--gradescope", type=Path, metavar="ROOT",
                        help="grade ROOT/submission into ROOT/results (Gradescope)")
    parser.add_argument("--assignment-for", type=Path, metavar="NOTEBOOK",
                        help="print an assignment of every exercise this notebook checks "
                             "(for assignments/<chapter>-<section>.toml)")
    args = parser.parse_args(argv)
    if args.assignment_for:
        path = args.assignment_for
        nb = nbformat.read(path, as_version=4)
        try:
            shown = path.resolve().relative_to(ROOT).as_posix()
        except ValueError:
            shown = path.as_posix()
        sys.stdout.write(for_notebook(nb, book_title(nb, path), path.name, shown))
        return 0
    if args.assignment is None:
        parser.error("--assignment FILE.toml is required (which exercises, their points)")
    try:
        assignment = load(args.assignment)
    except AssignmentError as exc:
        print(f"grade: {exc}", file=sys.stderr)
        return 2
    try:
        if args.gradescope:
            return gradescope_run(args.gradescope, assignment)
        if args.submissions is None or not args.submissions.is_dir():
            print(f"grade: {args.submissions} is not a folder of submissions", file=sys.stderr)
            return 2
        start = time.monotonic()
        print(f"grade: {args.submissions} against {args.assignment} "
              f"({', '.join(assignment.names)})", flush=True)
        results = grade_folder(args.submissions, assignment, args.out, args.jobs, args.fresh,
                               log=lambda text: print(text, flush=True))
    except jail.SandboxUnavailable as exc:
        print(f"grade: the sandbox is not available, nothing was graded: {exc}",
              file=sys.stderr)
        return 3
    print(f"grade: {len(results)} rows in {args.out / 'grades.csv'}, results.json in "
          f"{args.out / 'results'} ({time.monotonic() - start:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
