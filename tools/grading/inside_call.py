"""Runs inside an exercise's grading sandbox: defines the student's function from the slice of
the notebook it needs, calls it on each case, and reports only the answers, as data.

Usage (by the grader, inside bwrap): ``python -P -s -m tools.grading.inside_call REPORT_FD
JOB.json``, with PYTHONPATH the folder that holds the grader's scripts and, if the exercise
declares library parts, the folder that holds them (the only ``wheelkin`` there is). The job
holds the statements to run (the slice), the expression of the function and the cases
(encoded by ``wire.py``). Lines written on ``REPORT_FD``:
``{"setup": [[statement, error], ...]}`` (statements of the slice that raised here),
``{"function": error}`` if the expression does not give a function, then one
``{"case": i, "answer": {...}}`` per case as soon as it is known, then ``{"done": true}``.
"""

from __future__ import annotations

import builtins
import copy
import json
import os
import sys

from tools.grading import wire


class _NoShell:
    """``get_ipython()`` for statements that use a magic: the magic does nothing here."""

    def __getattr__(self, name):
        return lambda *args, **kwargs: None


def _write(stream, data) -> None:
    try:
        stream.write(wire.dumps(data) + "\n")
        stream.flush()
    except (OSError, ValueError):  # the student's code closed the pipe
        pass


def _error(exc: BaseException) -> str:
    return f"{type(exc).__name__}: {exc}"[: wire.MAX_TEXT]


def main() -> int:
    fd, job_path = int(sys.argv[1]), sys.argv[2]
    with open(job_path, encoding="utf-8") as f:
        job = json.load(f)
    # The report stream is a private duplicate: the student's code can close fd REPORT_FD
    # and still not silence it (nor can it forge answers the grader would believe better
    # than its own function's: the verdict is computed outside from these values).
    report = os.fdopen(os.dup(fd), "w", buffering=1, encoding="utf-8")
    os.close(fd)
    os.chdir(os.environ.get("HOME", "/tmp"))
    namespace = {"__name__": "__main__", "__builtins__": builtins,
                 "get_ipython": _NoShell, "display": lambda *a, **k: None}
    failed = []
    for source in job["statements"]:
        try:
            exec(compile(source, "<notebook>", "exec"), namespace)
        except BaseException as exc:
            failed.append([source.strip().splitlines()[0][:120] if source.strip() else "",
                           _error(exc)])
    _write(report, {"setup": failed[:20]})
    try:
        fn = eval(compile(job["expr"], "<check>", "eval"), namespace)
        if not callable(fn):
            raise TypeError(f"{job['expr']} is a {type(fn).__name__}, not a function")
    except BaseException as exc:
        _write(report, {"function": _error(exc)})
        _write(report, {"done": True})
        return 0
    for index, case in enumerate(job["cases"]):
        args, kwargs = wire.decode_case(case)
        try:
            raw = fn(*copy.deepcopy(args), **copy.deepcopy(kwargs))
        except NotImplementedError:
            answer = {"kind": "not_written"}
        except BaseException as exc:
            answer = {"kind": "raised", "ename": type(exc).__name__,
                      "evalue": str(exc)[: wire.MAX_TEXT]}
        else:
            answer = wire.answer(raw)
        _write(report, {"case": index, "answer": answer})
    _write(report, {"done": True})
    return 0


if __name__ == "__main__":
    sys.exit(main())
