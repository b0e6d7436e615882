#!/usr/bin/env python
"""Time `make book`, `make notebooks` and `make test` on a fresh clone; record the figures.

Usage: ``.venv/bin/python -m tools.time_build [--no-write]`` (about 10 minutes). Clones the
committed HEAD into a temporary folder and runs there, as a new user would:

1. ``make book`` from nothing (creates .venv, installs, vendors the JavaScript, builds);
2. ``make book`` again (set-up done: the build from the committed outputs alone);
3. ``make notebooks`` (re-executes every notebook), then ``make notebooks`` again, which must
   leave ``git status`` clean (deterministic execution);
4. ``make test`` (every layer, with the seconds of each).

Writes the "Build and test timings" section of benchmarks/RESULTS.md (between its markers,
other sections kept) unless ``--no-write``. Exit status 1 if a command failed.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import platform
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from tools.results import load_average, markers, write_section

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "RESULTS.md"

BEGIN, END = markers("build")

LAYER_TIME = re.compile(r"^-+ (\w+): (\d+) s$", re.MULTILINE)


def _run(command: list[str], cwd: Path) -> tuple[int, float, str]:
    start = time.perf_counter()
    done = subprocess.run(command, cwd=cwd, capture_output=True, text=True, check=False,
                          stdin=subprocess.DEVNULL)
    output = done.stdout + done.stderr
    return done.returncode, time.perf_counter() - start, output


def measure(clone: Path) -> tuple[list[tuple[str, float, str]], dict[str, int], bool]:
    rows: list[tuple[str, float, str]] = []
    ok = True
    steps = [
        ("`make book`, fresh clone (venv, install, npm, build)", ["make", "book"]),
        ("`make book`, set-up done (build from committed outputs)", ["make", "book"]),
        ("`make notebooks` (re-execute all, 2 at a time)", ["make", "notebooks"]),
        ("`make notebooks` again", ["make", "notebooks"]),
        ("`make test` (all layers, set-up done, on the re-executed notebooks)",
         ["make", "test"]),
    ]
    layers: dict[str, int] = {}
    for label, command in steps:
        print(f"time_build: {label} ...", flush=True)
        status, seconds, output = _run(command, clone)
        note = "ok" if status == 0 else f"FAILED (exit {status})"
        if command == ["make", "notebooks"] and status == 0:
            changed = subprocess.run(["git", "status", "--porcelain", "notebooks"], cwd=clone,
                                     capture_output=True, text=True, check=True).stdout.split("\n")
            changed = [line for line in changed if line.strip()]
            note += f"; {len(changed)} notebook(s) differ from the commit" if changed else \
                "; no notebook differs from the commit"
            subprocess.run(["git", "add", "-A", "notebooks"], cwd=clone, check=True)
            subprocess.run(["git", "-c", "user.name=time_build", "-c", "user.email=none",
                            "commit", "-q", "--allow-empty", "-m", "re-executed"], cwd=clone,
                           check=True)
        if command == ["make", "test"]:
            layers = {name: int(s) for name, s in LAYER_TIME.findall(output)}
            summary = [line for line in output.splitlines() if line.startswith("layers:")]
            note += f"; {summary[-1]}" if summary else ""
        ok = ok and status == 0
        rows.append((label, seconds, note))
        print(f"time_build: {seconds:.0f} s, {note}", flush=True)
    return rows, layers, ok


def report(rows, layers, commit: str, before: tuple[float, ...],
           after: tuple[float, ...]) -> str:
    lines = [
        BEGIN,
        "## Build and test timings",
        "",
        f"Machine: {platform.processor() or platform.machine()}, {os.cpu_count()} logical CPUs; "
        f"Python {platform.python_version()}. Date: {_dt.date.today().isoformat()}. Commit "
        f"{commit}, cloned fresh. {load_average(before, after)} "
        "(other jobs may share the cores). Produced by `python -m tools.time_build`.",
        "",
        "| command | wall time (s) | result |",
        "| --- | --- | --- |",
    ]
    lines += [f"| {label} | {seconds:.0f} | {note} |" for label, seconds, note in rows]
    if layers:
        lines += ["", "`make test`, per layer (s): "
                  + ", ".join(f"{name} {s}" for name, s in layers.items()) + "."]
    lines += ["", "Budgets (DESIGN.md): `make book` from committed outputs ≤ 60 s; `make "
              "notebooks` ≤ 5 min on 2 cores; strict nbval ≤ 3 min on 2 cores.", END]
    return "\n".join(lines) + "\n"


def write(section: str) -> None:
    write_section("build", section, RESULTS)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True, check=True).stdout.strip()
    with tempfile.TemporaryDirectory(prefix="wheelkin-timing-") as tmp:
        clone = Path(tmp) / "repo"
        subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
        before = os.getloadavg()
        rows, layers, ok = measure(clone)
        after = os.getloadavg()
    section = report(rows, layers, commit, before, after)
    print(section)
    if not args.no_write:
        write(section)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
