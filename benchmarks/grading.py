"""Grading speed: seconds per submission with the sandbox, the projected time for a class of
300, and what the sandbox costs.

Usage: ``python -m benchmarks.grading [--copies 12] [--no-write]``. Grades ``--copies``
copies of one realistic submission (the student edition of the mecanum exercises,
notebooks/04_mecanum/07_exercises.ipynb, solved with the book's solutions: 5 exercises)
with ``tools.grade``'s folder grading and its default number of workers, twice: in the
bubblewrap sandboxes, then (for this measurement only, the grader has no such option) with
every sandboxed command run directly, as the same Python, the same limits, the same
pipeline. Also times one sandboxed start of Python against a plain one. Writes the
"Grading" section of benchmarks/RESULTS.md.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import nbformat

from tools.results import RESULTS, cpu, markers, write_section

ROOT = Path(__file__).resolve().parents[1]

NOTEBOOK = "notebooks/04_mecanum/07_exercises.ipynb"
CLASS = 300


def _p95(values: list[float]) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(0.95 * (len(ordered) - 1)))]


def submission_folder(work: Path, copies: int) -> tuple[Path, Path]:
    """``copies`` copies of the solved notebook, and an assignment of its exercises."""
    from tools.grading.assignment import for_notebook
    from tools.grading.notebook import with_solutions
    from tools.student_edition import student_notebook

    book = nbformat.read(ROOT / NOTEBOOK, as_version=4)
    solved = with_solutions(student_notebook(book)[0], book)
    folder = work / "submissions"
    folder.mkdir(parents=True)
    for k in range(copies):
        nbformat.write(solved, folder / f"student-{k:03d}.ipynb")
    assignment = work / "assignment.toml"
    assignment.write_text(for_notebook(book, "mecanum"), encoding="utf-8")
    return folder, assignment


def unsandboxed():
    """A stand-in for ``jail.Sandbox`` that runs the same command without bwrap and setpriv
    (paths inside mapped back to the host's), to measure what the sandbox costs."""
    from tools.grading import jail

    class Direct(jail.Sandbox):
        def command(self, argv: list[str]) -> list[str]:
            home = Path(tempfile.mkdtemp(prefix="bench-home-"))
            mapping = {inside: str(host) for host, inside in self.binds}
            mapping[jail.SCRIPTS] = str(ROOT)  # tools/ is the repository's own
            job = next(Path(host) for host, inside in self.binds if inside == jail.JOB)
            text = (job / "job.json").read_text(encoding="utf-8")
            for inside, host in sorted(mapping.items(), key=lambda kv: -len(kv[0])):
                text = text.replace(inside, host)
            (job / "job.json").write_text(text, encoding="utf-8")
            env = {"HOME": str(home), "TMPDIR": str(home), "PATH": "/usr/bin:/bin",
                   "MPLBACKEND": "Agg", "MPLCONFIGDIR": str(home / "mpl"),
                   "IPYTHONDIR": str(home / "ipython"), "OPENBLAS_NUM_THREADS": "1",
                   "PYTHONHASHSEED": "0"}
            for key, value in self.env.items():  # PYTHONPATH: the scripts, the library
                for inside, host in sorted(mapping.items(), key=lambda kv: -len(kv[0])):
                    value = value.replace(inside, host)
                env[key] = value
            args = []
            for arg in argv:
                for inside, host in sorted(mapping.items(), key=lambda kv: -len(kv[0])):
                    arg = arg.replace(inside, host)
                args.append(arg)
            return ["env", "-i", *(f"{k}={v}" for k, v in env.items()),
                    "prlimit", f"--as={self.limits.memory}", "--", *args]

    return Direct


def grade_once(folder: Path, assignment: Path, out: Path, sandboxed: bool) -> dict:
    from tools import grade
    from tools.grading import jail
    from tools.grading.assignment import load

    saved = (jail.Sandbox, jail.probe, grade._check_library_is_hidden)
    if not sandboxed:
        jail.Sandbox = unsandboxed()
        jail.probe = lambda work, uid_base=0: None
        grade._check_library_is_hidden = lambda run: None
    try:
        start = time.perf_counter()
        results = grade.grade_folder(folder, load(assignment), out, fresh=True,
                                     log=lambda text: None)
        wall = time.perf_counter() - start
    finally:
        jail.Sandbox, jail.probe, grade._check_library_is_hidden = saved
    seconds = [r.seconds for r in results]
    scores = {r.total() for r in results}
    return {"wall": wall, "median": statistics.median(seconds), "p95": _p95(seconds),
            "scores": sorted(scores), "n": len(results)}


def start_cost(repeats: int = 15, trivial: int = 50) -> dict[str, float]:
    """Median seconds to start a sandbox: around ``/bin/true`` (the sandbox alone) and around
    Python importing numpy, each against the same command run plainly (interleaved)."""
    from tools.grading import jail

    work = Path(tempfile.mkdtemp(prefix="bench-start-"))
    uid_base, lock = jail.claim_uids()
    times: dict[str, list[float]] = {"true": [], "true_plain": [], "python": [],
                                      "python_plain": []}
    try:
        box = jail.Sandbox(jail.Limits(seconds=60), jail.write_etc(work / "etc", uid_base),
                           uid_base=uid_base)
        for key, argv, count in (("true", ["/bin/true"], trivial),
                                 ("python", [jail.python_in_sandbox(), "-I", "-c",
                                             "import numpy"], repeats)):
            for _ in range(count):
                t = time.perf_counter()
                assert box.run(argv).returncode == 0
                times[key].append(time.perf_counter() - t)
                t = time.perf_counter()
                subprocess.run(argv, check=True)
                times[key + "_plain"].append(time.perf_counter() - t)
    finally:
        shutil.rmtree(work, ignore_errors=True)
        if lock is not None:
            os.close(lock)
    return {key: statistics.median(values) for key, values in times.items()}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--copies", type=int, default=12)
    parser.add_argument("--no-write", action="store_true", help="print, do not write RESULTS.md")
    args = parser.parse_args(argv)
    work = Path(tempfile.mkdtemp(prefix="bench-grading-"))
    try:
        folder, assignment = submission_folder(work, args.copies)
        boxed = grade_once(folder, assignment, work / "out-sandboxed", sandboxed=True)
        direct = grade_once(folder, assignment, work / "out-direct", sandboxed=False)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    start = start_cost()
    load = os.getloadavg()[0]
    print(json.dumps({"sandboxed": boxed, "unsandboxed": direct, "start": start}, indent=1))
    assert boxed["scores"] == direct["scores"] == [5.0], "every copy must get every point"
    per = boxed["wall"] / boxed["n"]
    sandboxes = 1 + 5  # the notebook, and one per exercise
    setup = start["true"] - start["true_plain"]
    difference = boxed["median"] - direct["median"]
    begin, end = markers("grading")
    section = "\n".join([
        begin,
        "## Grading (`make grade`)",
        "",
        f"Machine: {cpu()}; load average {load:.1f} at the end of the run (the machine is "
        f"shared with other jobs). `python -m benchmarks.grading`: {boxed['n']} copies of one "
        f"submission, the student edition of `{NOTEBOOK}` solved with the book's solutions "
        "(5 exercises, the notebook's figures and animations included), graded by "
        "`tools/grade.py` with its default 2 workers: per submission, one sandbox runs the "
        "notebook and one per exercise calls the student's function on its visible and "
        "hidden cases; the judge runs outside.",
        "",
        "| | per submission, median | p95 | wall time for the folder |",
        "| --- | --- | --- | --- |",
        f"| sandboxed (bubblewrap) | {boxed['median']:.1f} s | {boxed['p95']:.1f} s | "
        f"{boxed['wall']:.1f} s |",
        f"| the same commands without the sandbox | {direct['median']:.1f} s | "
        f"{direct['p95']:.1f} s | {direct['wall']:.1f} s |",
        "",
        f"- A class of {CLASS} with the default 2 workers: about {CLASS * per / 60:.0f} min "
        f"({per:.1f} s of wall time per submission).",
        f"- The sandbox's overhead: {difference:+.1f} s per submission end to end "
        f"({100 * difference / direct['median']:+.0f} % of the unsandboxed median; one run "
        "each, on a shared machine). Making a sandbox costs "
        f"{1000 * setup:.0f} ms (`/bin/true` in bwrap, {1000 * start['true']:.0f} ms, "
        f"against plainly, {1000 * start['true_plain']:.0f} ms; medians of 50), "
        f"{sandboxes} sandboxes per submission: {sandboxes * setup:.2f} s; starting Python "
        f"with numpy takes {1000 * start['python']:.0f} ms in a sandbox and "
        f"{1000 * start['python_plain']:.0f} ms plainly (medians of 15).",
        end,
    ])
    if args.no_write:
        print(section)
    else:
        write_section("grading", section, RESULTS)
    return 0


if __name__ == "__main__":
    sys.exit(main())
