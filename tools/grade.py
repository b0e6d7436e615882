#!/usr/bin/env python
"""Grade a folder of submitted notebooks: one row per student, one column per exercise.

Usage::

    python -m tools.grade SUBMISSIONS [--out DIR] [--timeout 120] [--jobs 2]
    make grade SUBMISSIONS=folder            # the same, results in _build/grades/

For each file of ``SUBMISSIONS`` (any file: one that is not a notebook gets a clear line):

1. **Run it, sandboxed.** The notebook is copied into a fresh temporary folder and executed
   top to bottom in a fresh kernel of this environment, with a time limit for the whole
   notebook (``--timeout``) and a limit on what it prints (``--max-output``). The kernel's
   working directory, ``HOME`` and ``TMPDIR`` are inside that folder; when the grader runs as
   root, the kernel runs as ``nobody`` (``setpriv``), so it cannot write to the repository or
   anywhere but the folder and the world-writable ``/tmp``-like places (when ``nobody`` cannot
   run this Python, e.g. a repository in a private folder, it runs as the grader's user and
   the results say so);
   ``prlimit`` caps its memory and the size of any file it writes. A cell that raises does
   not stop the run (the error is reported, the later cells still run).
2. **Find the exercises**: every ``check("chapter.name", fn)`` call in the notebook names an
   exercise and the expression of the student's function.
3. **Grade each exercise** by calling the student's function, in the student's kernel, on the
   exercise's visible cases and on hidden ones (the visible inputs changed by 5-25 %, within
   the range the visible cases span, so a hidden case stays in the exercise's regime); the
   expected values are computed here, in the grader's process, from the registry's reference,
   never in the student's kernel. While the function runs, a profiler watches it: a call into
   the ``wheelkin`` package (the library, or the registry's reference) scores 0 and says so,
   and so does touching the profiler. The student's answers come back to this process, which
   diagnoses them with the exercise's own check (sign, swapped wheels, units, the exercise's
   typical mistakes), so the feedback reads like the notebook's.

Output in ``--out``: ``grades.csv`` (``student``, ``status``, one column per exercise with
its points, ``total``) and ``results/<student>/results.json`` in Gradescope's format
(``score``, ``tests`` with ``name``, ``score``, ``max_score``, ``output``).
"""

from __future__ import annotations

import argparse
import ast
import base64
import copy
import csv
import json
import math
import os
import pickle
import pwd
import re
import secrets
import shutil
import subprocess
import sys
import tempfile
import time
import zlib
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import nbformat
import numpy as np

import wheelkin
from tools.execute_notebooks import DETERMINISTIC_ENV
from wheelkin.exercises import Case, Exercise, get

ROOT = Path(__file__).resolve().parents[1]

#: Points for an exercise that passes (all or nothing: the check stops at the first problem).
POINTS = 1.0
#: Limits per submission (defaults; the command line can change them).
TIMEOUT_S = 120
MAX_OUTPUT_BYTES = 2_000_000
MAX_FILE_BYTES = 20_000_000
MEMORY_BYTES = 4 * 2**30
MAX_WRITE_BYTES = 100 * 2**20
#: Hidden cases made from each visible one.
HIDDEN_PER_CASE = 2
CHECK_CALL = "check"
WHEELKIN_DIR = str(Path(wheelkin.__file__).resolve().parent)
SAFE_NAME = re.compile(r"[^A-Za-z0-9_.-]+")


# ----------------------------------------------------------------------------- exercises

def _python(source: str) -> str:
    from IPython.core.inputtransformer2 import TransformerManager

    return TransformerManager().transform_cell(source)


def find_exercises(nb) -> dict[str, str]:
    """``{exercise name: expression of the student's function}`` from every ``check(...)``
    call in the notebook's code cells (the last call of a name wins)."""
    found: dict[str, str] = {}
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        try:
            tree = ast.parse(_python(cell.source))
        except SyntaxError:
            continue
        for node in ast.walk(tree):
            if (isinstance(node, ast.Call) and len(node.args) == 2
                    and getattr(node.func, "id", getattr(node.func, "attr", None)) == CHECK_CALL
                    and isinstance(node.args[0], ast.Constant)
                    and isinstance(node.args[0].value, str)):
                found[node.args[0].value] = ast.unparse(node.args[1])
    return found


def _hulls(cases: list[Case]) -> dict:
    """Per argument (position or keyword): the (min, max) of its float values over ``cases``."""
    hulls: dict = {}
    for case in cases:
        for key, value in [*enumerate(case.args), *case.kwargs.items()]:
            if isinstance(value, bool) or not isinstance(value, (float, np.floating)):
                continue
            if math.isfinite(value):
                lo, hi = hulls.get(key, (value, value))
                hulls[key] = (min(lo, value), max(hi, value))
    return hulls


def _perturb(value, factor: float, hull):
    """``value`` times ``factor`` (or divided by it) if that stays inside ``hull``, the range
    the visible cases span; else unchanged. Only finite floats change."""
    if (hull is None or isinstance(value, bool)
            or not isinstance(value, (float, np.floating)) or not math.isfinite(value)):
        return value
    for new in (value * factor, value / factor):
        if hull[0] <= new <= hull[1]:
            return type(value)(new)
    return value


def _expected(exercise: Exercise, case: Case):
    value = exercise.reference(*copy.deepcopy(case.args), **copy.deepcopy(case.kwargs))
    if hasattr(value, "as_array") and callable(value.as_array):
        value = value.as_array()
    return np.asarray(value, dtype=float)


def hidden_cases(exercise: Exercise, per_case: int = HIDDEN_PER_CASE) -> list[Case]:
    """Cases the student never sees: each visible input with its numbers changed by up to
    ±25 %, deterministically (seeded by the exercise's name), each number kept inside the
    range that the visible cases span (so that a hidden case stays in the regime the exercise
    asks about: a turn stays a turn, a limit is not crossed). Integers, strings and infinite
    values are not changed. A case whose reference answer is not defined (raises, NaN) is
    dropped.
    """
    rng = np.random.default_rng(zlib.crc32(exercise.name.encode()))
    hulls = _hulls(exercise.cases)
    out: list[Case] = []
    seen = {repr(c) for c in exercise.cases}
    for case in exercise.cases:
        try:
            base = _expected(exercise, case)
        except Exception:  # pragma: no cover - a visible case the reference rejects
            continue
        for _ in range(per_case):
            args = tuple(_perturb(v, 1.0 + rng.uniform(0.05, 0.25), hulls.get(i))
                         for i, v in enumerate(case.args))
            kwargs = {k: _perturb(v, 1.0 + rng.uniform(0.05, 0.25), hulls.get(k))
                      for k, v in case.kwargs.items()}
            new = Case(args, kwargs)
            if repr(new) in seen:
                continue  # nothing could change
            try:
                want = _expected(exercise, new)
            except Exception:
                continue
            if want.shape != base.shape or np.any(np.isnan(want)):
                continue
            if np.any(~np.isfinite(want) & np.isfinite(base)):
                continue
            seen.add(repr(new))
            out.append(new)
    return out


# ----------------------------------------------------------------------------- the kernel side

#: Defined in the student's kernel after the notebook ran. Calls the student's function on
#: each case under a profiler; prints one JSON line per exercise, prefixed with a nonce the
#: notebook could not know.
HARNESS = r'''
def _wheelkin_grader_NONCE(fn_expr, payload):
    import base64 as _b64, json as _json, pickle as _pickle, sys as _sys, threading as _thr
    import numpy as _np
    _dir = WHEELKIN_DIR
    _guards = {_sys.setprofile, _sys.settrace}
    _me = _sys._getframe().f_code
    report = {"cases": [], "library": [], "tampered": False, "error": None}
    try:
        fn = eval(fn_expr, get_ipython().user_ns)
    except Exception as exc:
        report["error"] = f"{type(exc).__name__}: {exc}"
        print("NONCE" + _json.dumps(report), flush=True)
        return
    for args, kwargs in _pickle.loads(_b64.b64decode(payload)):
        seen = []

        def _profile(frame, event, arg):
            if event == "call":
                path = frame.f_code.co_filename
                if path.startswith(_dir) and len(seen) < 5:
                    module = path[len(_dir):].lstrip("/").rsplit(".", 1)[0].replace("/", ".")
                    module = ("wheelkin." + module).replace(".__init__", "")
                    seen.append(module + "." + frame.f_code.co_qualname)
            elif event == "c_call" and arg in _guards and frame.f_code is not _me:
                report["tampered"] = True

        result = {}
        _thr.setprofile(_profile)
        _sys.setprofile(_profile)
        try:
            raw = fn(*args, **kwargs)
        except NotImplementedError:
            result = {"kind": "not_written"}
        except BaseException as exc:
            result = {"kind": "raised", "ename": type(exc).__name__, "evalue": str(exc)[:300]}
        finally:
            _sys.setprofile(None)
            _thr.setprofile(None)
        report["library"] += [s for s in seen if s not in report["library"]]
        if not result:
            if raw is None:
                result = {"kind": "none"}
            else:
                try:
                    value = raw.as_array() if callable(getattr(raw, "as_array", None)) else raw
                    arr = _np.asarray(value, dtype=float)
                    result = {"kind": "value", "shape": list(arr.shape),
                              "values": arr.ravel().tolist()}
                except Exception:
                    result = {"kind": "opaque", "repr": repr(raw)[:200]}
        report["cases"].append(result)
    print("NONCE" + _json.dumps(report), flush=True)
'''


class _Opaque:
    """A returned object that is not a number (shown with the student's repr)."""

    def __init__(self, text: str) -> None:
        self.text = text

    def __repr__(self) -> str:
        return self.text

    def __float__(self):
        raise TypeError("not a number")


def _replay(results: list[dict], used: list[int]):
    """A stand-in for the student's function that returns, call by call, what it returned in
    the student's kernel (``used`` counts the calls)."""

    def fn(*args, **kwargs):
        result = results[len(used)]
        used.append(1)
        kind = result["kind"]
        if kind == "not_written":
            raise NotImplementedError
        if kind == "raised":
            raise type(result["ename"], (Exception,), {})(result["evalue"])
        if kind == "none":
            return None
        if kind == "opaque":
            return _Opaque(result["repr"])
        return np.array(result["values"], dtype=float).reshape(result["shape"])

    return fn


@dataclass
class ExerciseGrade:
    name: str
    score: float
    message: str
    max_score: float = POINTS


def judge(name: str, report: dict, cases: list[Case], visible: int) -> ExerciseGrade:
    """The grade of one exercise from the kernel's report (``cases``: the cases tried)."""
    exercise = get(name)
    if report.get("error"):
        return ExerciseGrade(name, 0.0, f"✘ {name}: your function is not defined when the "
                             f"notebook has run ({report['error']}).")
    if report.get("tampered"):
        return ExerciseGrade(name, 0.0, f"✘ {name}: your function changes the grader's call "
                             "monitor (sys.setprofile / settrace); scored 0.")
    if report.get("library"):
        calls = ", ".join(report["library"][:3])
        return ExerciseGrade(name, 0.0, f"✘ {name}: your function calls the wheelkin library "
                             f"({calls}); the exercise asks you to write it yourself. "
                             "Scored 0.")
    results = report.get("cases", [])
    if len(results) != len(cases):
        return ExerciseGrade(name, 0.0, f"✘ {name}: the grader got {len(results)} answers for "
                             f"{len(cases)} cases; scored 0.")
    graded = copy.copy(exercise)  # its own class: an exercise may judge answers its way
    graded.cases = list(cases)
    used: list[int] = []
    result = graded.check(_replay(results, used))
    if result.passed:
        return ExerciseGrade(name, POINTS, f"✔ {name}: correct on all {visible} visible and "
                             f"{len(cases) - visible} hidden cases.")
    message = result.message
    if len(used) > visible and result.kind != "not-written":
        message += " (a hidden case: your function must work for any input, not only the "
        message += "ones the notebook shows)"
    return ExerciseGrade(name, 0.0, message)


# ----------------------------------------------------------------------------- the sandbox

def _nobody() -> tuple[int, int] | None:
    if os.geteuid() != 0:
        return None
    try:
        entry = pwd.getpwnam("nobody")
    except KeyError:
        return None
    return entry.pw_uid, entry.pw_gid


_PROBED: dict[tuple[int, int, str], bool] = {}


def _can_run_as(uid: int, gid: int, cwd: Path) -> bool:
    """Whether this Python, with wheelkin and ipykernel, runs as ``uid`` from ``cwd``."""
    key = (uid, gid, str(cwd.parent))
    if key not in _PROBED:
        _PROBED[key] = _probe(uid, gid, cwd)
    return _PROBED[key]


def _probe(uid: int, gid: int, cwd: Path) -> bool:
    if not shutil.which("setpriv"):
        return False
    cmd = ["setpriv", f"--reuid={uid}", f"--regid={gid}", "--clear-groups", "--",
           sys.executable, "-c", "import ipykernel, wheelkin, matplotlib"]
    try:
        done = subprocess.run(cmd, cwd=cwd, capture_output=True, timeout=60,
                              env={"PATH": os.environ.get("PATH", ""), "HOME": str(cwd)})
    except (OSError, subprocess.TimeoutExpired):
        return False
    return done.returncode == 0


def _seed_font_cache(target: Path) -> None:
    """Copy matplotlib's font list into the kernel's config folder (saves rebuilding it)."""
    import matplotlib

    target.mkdir(parents=True, exist_ok=True)
    for font_list in Path(matplotlib.get_cachedir()).glob("fontlist-*.json"):
        shutil.copy(font_list, target / font_list.name)


def kernel_argv(user: tuple[int, int] | None, memory: int, max_write: int) -> list[str]:
    argv = []
    if shutil.which("prlimit"):
        argv += ["prlimit", f"--as={memory}", f"--fsize={max_write}", "--core=0"]
    if user is not None:
        argv += ["setpriv", f"--reuid={user[0]}", f"--regid={user[1]}", "--clear-groups", "--"]
    return [*argv, sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"]


def _manager_class(argv: list[str], env: dict, work: Path, user):
    from jupyter_client.kernelspec import KernelSpec, KernelSpecManager
    from jupyter_client.manager import AsyncKernelManager

    class Specs(KernelSpecManager):
        def get_kernel_spec(self, kernel_name):
            return KernelSpec(argv=argv, env=env, display_name="grader", language="python")

    class Manager(AsyncKernelManager):
        def __init__(self, **kwargs):
            kwargs.setdefault("kernel_spec_manager", Specs())
            kwargs.setdefault("transport", "ipc")
            kwargs.setdefault("ip", str(work / "run" / "kernel"))
            kwargs.setdefault("connection_file", str(work / "run" / "kernel.json"))
            super().__init__(**kwargs)

        def write_connection_file(self, **kwargs):
            result = super().write_connection_file(**kwargs)
            if user is not None:
                os.chown(self.connection_file, *user)
            return result

    return Manager


def _client_class():
    from nbclient import NotebookClient

    class Client(NotebookClient):
        printed = 0
        over_limit = False
        max_output = MAX_OUTPUT_BYTES
        lines: list[str]

        def output(self, outs, msg, display_id, cell_index):
            content = msg.get("content", {})
            size = len(json.dumps(content.get("data", content.get("text", ""))))
            self.printed += size
            if self.printed > self.max_output:
                if not self.over_limit:  # stop the kernel: nbclient then reports it dead
                    self.over_limit = True
                    process = getattr(self.km.provisioner, "process", None)
                    if process is not None:
                        process.kill()
                return None
            if msg.get("msg_type") == "stream":
                self.lines.extend(str(content.get("text", "")).splitlines())
            return super().output(outs, msg, display_id, cell_index)

    return Client


@dataclass
class SubmissionResult:
    student: str
    status: str
    grades: list[ExerciseGrade] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    seconds: float = 0.0
    user: str = ""


def _student_id(path: Path) -> str:
    stem = path.name[: -len(".ipynb")] if path.name.endswith(".ipynb") else path.name
    return SAFE_NAME.sub("_", stem) or "submission"


def grade_submission(path: Path, names: list[str], timeout: float = TIMEOUT_S,
                     max_output: int = MAX_OUTPUT_BYTES) -> SubmissionResult:
    """Run and grade one submission; never raises (problems become the status)."""
    start = time.monotonic()
    result = SubmissionResult(_student_id(path), "graded")
    try:
        _grade(path, names, timeout, max_output, result)
    except Exception as exc:  # the grader's own failure on this file: say so, go on
        result.status = f"not graded: the grader failed ({type(exc).__name__}: {exc})"
    result.seconds = time.monotonic() - start
    if result.status != "graded":
        got = {g.name for g in result.grades}
        for name in names:
            if name not in got:
                result.grades.append(ExerciseGrade(name, 0.0, f"✘ {name}: {result.status}"))
    return result


def _read_notebook(path: Path, result: SubmissionResult):
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        result.status = f"not graded: the file is {size / 1e6:.1f} MB (limit " \
                        f"{MAX_FILE_BYTES / 1e6:.0f} MB)"
        return None
    try:
        text = path.read_text(encoding="utf-8")
        nb = nbformat.reads(text, as_version=4)
        if not isinstance(nb.get("cells"), list):
            raise ValueError("no cells")
    except Exception as exc:
        reason = str(exc).splitlines()[0][:80] if str(exc) else type(exc).__name__
        if "not appear to be JSON" in reason:
            reason = "it is not JSON"
        result.status = f"not a notebook: {path.name} could not be read as .ipynb ({reason})"
        return None
    return nb


def _grade(path: Path, names: list[str], timeout: float, max_output: int,
           result: SubmissionResult) -> None:
    nb = _read_notebook(path, result)
    if nb is None:
        return
    found = find_exercises(nb)
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.outputs, cell.execution_count = [], None
    work = Path(tempfile.mkdtemp(prefix="wheelkin-grade-"))
    try:
        _run_sandboxed(nb, work, found, names, timeout, max_output, result)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def _run_sandboxed(nb, work: Path, found: dict[str, str], names: list[str], timeout: float,
                   max_output: int, result: SubmissionResult) -> None:
    from nbclient.exceptions import CellTimeoutError, DeadKernelError

    user = _nobody()
    for sub in ("home", "tmp", "run"):
        (work / sub).mkdir()
    nbformat.write(nb, work / "submission.ipynb")
    if user is not None:
        for p in [work, *work.rglob("*")]:
            os.chown(p, *user)
    if user is not None and not _can_run_as(*user, cwd=work):
        result.notes.append("the kernel ran as the grader's user: `nobody` cannot run "
                            "this Python (check the permissions of the repository's "
                            "folders)")
        user = None
    result.user = "nobody" if user else pwd.getpwuid(os.geteuid()).pw_name
    env = {**DETERMINISTIC_ENV, "PATH": os.environ.get("PATH", "/usr/bin:/bin"),
           "HOME": str(work / "home"), "TMPDIR": str(work / "tmp"),
           "MPLCONFIGDIR": str(work / "home" / ".matplotlib"),
           "IPYTHONDIR": str(work / "home" / ".ipython"),
           "JUPYTER_RUNTIME_DIR": str(work / "run"), "MPLBACKEND": "Agg",
           "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    _seed_font_cache(work / "home" / ".matplotlib")
    if user is not None:
        for p in [work, *work.rglob("*")]:
            os.chown(p, *user)  # again: the font cache is new
    argv = kernel_argv(user, MEMORY_BYTES, MAX_WRITE_BYTES)
    client = _client_class()(
        nb, kernel_manager_class=_manager_class(argv, env, work, user),
        kernel_name="grader", timeout=int(timeout), startup_timeout=60,
        allow_errors=True, record_timing=False, store_widget_state=False,
        shutdown_kernel="immediate",
        resources={"metadata": {"path": str(work)}})
    client.max_output, client.lines = max_output, []
    deadline = time.monotonic() + timeout
    with client.setup_kernel():
        try:
            for index, cell in enumerate(nb.cells):
                if cell.cell_type != "code":
                    continue
                client.timeout = max(1, math.ceil(deadline - time.monotonic()))
                client.execute_cell(cell, index)
                for out in cell.outputs:
                    if out.get("output_type") == "error":
                        result.notes.append(f"cell {index} raised {out.get('ename')}: "
                                            f"{str(out.get('evalue'))[:200]}")
                cell.outputs = []
            _grade_in_kernel(client, found, names, deadline, result)
        except CellTimeoutError:
            result.status = f"timed out: the notebook ran longer than {timeout:g} s"
        except DeadKernelError:
            result.status = "the kernel died (out of memory, or the notebook exited it)"
        if client.over_limit:
            result.status = (f"too much output: the notebook printed more than "
                             f"{max_output / 1e6:g} MB")


def _grade_in_kernel(client, found: dict[str, str], names: list[str], deadline: float,
                     result: SubmissionResult) -> None:
    nonce = secrets.token_hex(16)
    harness = (HARNESS.replace("NONCE", nonce)
               .replace("WHEELKIN_DIR", repr(WHEELKIN_DIR + os.sep)))
    _run(client, harness, deadline)
    for name in names:
        if name not in found:
            result.grades.append(ExerciseGrade(name, 0.0, f"✘ {name}: no check(\"{name}\", ...) "
                                               "call in the notebook: the exercise is missing."))
            continue
        exercise = get(name)
        cases = list(exercise.cases) + hidden_cases(exercise)
        payload = base64.b64encode(pickle.dumps([(c.args, c.kwargs) for c in cases])).decode()
        client.lines = []
        _run(client, f"_wheelkin_grader_{nonce}({found[name]!r}, {payload!r})", deadline)
        reports = [json.loads(line[len(nonce):]) for line in client.lines
                   if line.startswith(nonce)]
        if not reports:
            result.grades.append(ExerciseGrade(name, 0.0, f"✘ {name}: the grader got no "
                                               "answer from the notebook's kernel."))
            continue
        result.grades.append(judge(name, reports[-1], cases, len(exercise.cases)))


def _run(client, source: str, deadline: float) -> None:
    cell = nbformat.v4.new_code_cell(source)
    client.timeout = max(1, math.ceil(deadline - time.monotonic()))
    client.nb.cells.append(cell)
    client.execute_cell(cell, len(client.nb.cells) - 1)


# ----------------------------------------------------------------------------- output

def gradescope(result: SubmissionResult) -> dict:
    """The Gradescope autograder ``results.json`` of one submission."""
    tests = [{"name": g.name, "score": g.score, "max_score": g.max_score, "output": g.message}
             for g in result.grades]
    out = {"score": sum(g.score for g in result.grades),
           "execution_time": round(result.seconds, 1), "tests": tests}
    notes = ([] if result.status == "graded" else [result.status]) + result.notes
    if notes:
        out["output"] = "\n".join(notes)
    return out


def write_outputs(results: list[SubmissionResult], names: list[str], out: Path) -> Path:
    out.mkdir(parents=True, exist_ok=True)
    csv_path = out / "grades.csv"
    with csv_path.open("w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(["student", "status", *names, "total"])
        for r in results:
            points = {g.name: g.score for g in r.grades}
            writer.writerow([r.student, r.status, *(f"{points.get(n, 0.0):g}" for n in names),
                             f"{sum(points.values()):g}"])
    for r in results:
        folder = out / "results" / r.student
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "results.json").write_text(json.dumps(gradescope(r), indent=1,
                                                        ensure_ascii=False) + "\n",
                                             encoding="utf-8")
    return csv_path


def exercise_names(paths: list[Path], given: list[str] | None) -> list[str]:
    """The CSV's columns: the exercises named, or every exercise any submission checks."""
    if given:
        for name in given:
            get(name)  # ValueError listing the known names
        return list(given)
    from wheelkin.exercises import all_exercises

    names: set[str] = set()
    known = set(all_exercises())
    for path in paths:
        try:
            nb = nbformat.reads(path.read_text(encoding="utf-8"), as_version=4)
        except Exception:
            continue
        names |= {n for n in find_exercises(nb) if n in known}
    return sorted(names)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("submissions", type=Path, help="folder of submitted notebooks")
    parser.add_argument("--out", type=Path, default=ROOT / "_build" / "grades")
    parser.add_argument("--timeout", type=float, default=TIMEOUT_S,
                        help=f"seconds per notebook, grading included ({TIMEOUT_S})")
    parser.add_argument("--max-output", type=int, default=MAX_OUTPUT_BYTES,
                        help=f"bytes a notebook may print ({MAX_OUTPUT_BYTES})")
    parser.add_argument("--exercise", action="append", dest="exercises",
                        help="grade this exercise (repeat); default: every exercise checked "
                             "in any submission")
    parser.add_argument("-j", "--jobs", type=int, default=2)
    args = parser.parse_args(argv)
    if not args.submissions.is_dir():
        print(f"grade: {args.submissions} is not a folder of submissions", file=sys.stderr)
        return 2
    paths = sorted(p for p in args.submissions.iterdir() if p.is_file()
                   and not p.name.startswith("."))
    if not paths:
        print(f"grade: no files in {args.submissions}", file=sys.stderr)
        return 2
    names = exercise_names(paths, args.exercises)
    ids = [_student_id(p) for p in paths]
    dupes = {i for i in ids if ids.count(i) > 1}
    if dupes:
        print(f"grade: two files give the same student id: {', '.join(sorted(dupes))}",
              file=sys.stderr)
        return 2
    print(f"grade: {len(paths)} submissions, exercises: {', '.join(names) or 'none found'}")
    start = time.monotonic()
    results = []
    with ProcessPoolExecutor(max_workers=max(1, min(args.jobs, len(paths)))) as pool:
        futures = [pool.submit(grade_submission, p, names, args.timeout, args.max_output)
                   for p in paths]
        for future in futures:
            r = future.result()
            results.append(r)
            total = sum(g.score for g in r.grades)
            print(f"{r.student:24s} {total:4g}/{len(names) * POINTS:g}  {r.seconds:5.1f} s  "
                  f"{r.status}", flush=True)
    csv_path = write_outputs(results, names, args.out)
    print(f"grade: wrote {csv_path} and {len(results)} results.json in "
          f"{args.out / 'results'} ({time.monotonic() - start:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
