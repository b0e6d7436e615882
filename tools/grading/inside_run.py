"""Runs inside the notebook's sandbox: executes a submitted notebook's code cells, top to
bottom, in an IPython shell, and reports what ran.

Usage (by the grader, inside bwrap): ``python -P -s -m tools.grading.inside_run REPORT_FD
JOB.json``, with PYTHONPATH the folders of the grader's scripts and of the library. The job
holds the code cells (index and source) and where matplotlib's font list is mounted. For
each cell it writes one JSON line on ``REPORT_FD``: ``{"cell": i, "ran": "all"}``,
``{"cell": i, "ran": LINE, "error": "..."}`` (stopped by an error raised on that line of the
cell's Python), or ``{"cell": i, "ran": 0, "error": "..."}`` (did not compile); then
``{"done": true}``. A cell that raises does not stop the notebook (as in the book's student
edition). Everything the notebook prints goes to stdout, which the grader counts and
discards. The report is trusted for nothing but which of the student's own statements ran.
"""

from __future__ import annotations

import json
import os
import shutil
import sys


def _report(stream, data: dict) -> None:
    try:
        stream.write(json.dumps(data) + "\n")
        stream.flush()
    except (OSError, ValueError):  # the notebook closed the pipe: nothing more to say
        pass


def _stopped_at(exc: BaseException) -> int:
    """The line of the cell (its Python) on which ``exc`` left the cell's own code: the first
    frame of the traceback that is a cell's (IPython names them ``<ipython-input-...>``); if
    none is (an error after the cell's code, in IPython's own hooks), every line ran."""
    tb = exc.__traceback__
    while tb is not None:
        if tb.tb_frame.f_code.co_filename.startswith("<ipython-input-"):
            return tb.tb_lineno
        tb = tb.tb_next
    return 10**9


def main() -> int:
    fd, job_path = int(sys.argv[1]), sys.argv[2]
    report = os.fdopen(fd, "w", buffering=1, encoding="utf-8")
    with open(job_path, encoding="utf-8") as f:
        job = json.load(f)
    cache = os.environ.get("MPLCONFIGDIR")
    if cache and job.get("fonts"):
        os.makedirs(cache, exist_ok=True)
        for name in os.listdir(job["fonts"]):
            shutil.copy(os.path.join(job["fonts"], name), cache)
    os.chdir(os.environ.get("HOME", "/tmp"))

    from IPython.core.interactiveshell import InteractiveShell
    from traitlets.config import Config

    class Shell(InteractiveShell):
        """A kernel's shell without the kernel: no GUI event loop to start for a plotting
        backend (``%matplotlib inline`` works; figures are not shown)."""

        def enable_gui(self, gui=None):
            return None

    config = Config()
    config.HistoryManager.enabled = False
    shell = Shell.instance(config=config)
    for index, source in job["cells"]:
        result = shell.run_cell(source, store_history=False)
        if result.error_before_exec is not None:
            exc = result.error_before_exec
            _report(report, {"cell": index, "ran": 0,
                             "error": f"{type(exc).__name__}: {exc}"[:300]})
        elif result.error_in_exec is not None:
            exc = result.error_in_exec
            _report(report, {"cell": index, "ran": _stopped_at(exc),
                             "error": f"{type(exc).__name__}: {exc}"[:300]})
        else:
            _report(report, {"cell": index, "ran": "all"})
    _report(report, {"done": True})
    return 0


if __name__ == "__main__":
    sys.exit(main())
