#!/usr/bin/env python
"""Run every benchmark: each benchmarks/*.py that defines a top-level ``main()``.

Usage: ``python -m benchmarks.run_all [NAME ...]`` (``make bench``); with names (file stems,
e.g. ``sandbox``), only those. Each benchmark runs in its own process, with its default
options (``main()`` called with no arguments), so one cannot disturb another's timings; each
writes its own section of benchmarks/RESULTS.md. Exit status 1 if any benchmark failed.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

#: Runs ``main()`` of the file named by WHEELKIN_BENCHMARK (not its ``__main__`` block).
_RUNNER = (
    "import os, runpy, sys\n"
    "path = os.environ['WHEELKIN_BENCHMARK']\n"
    "sys.argv = [path]\n"
    "result = runpy.run_path(path, run_name='wheelkin_benchmark')['main']()\n"
    "sys.exit(result if isinstance(result, int) else 0)\n"
)


def benchmarks(directory: Path = HERE) -> list[Path]:
    """The benchmark files: every *.py here (but this one) with a top-level ``def main``."""
    found = []
    for path in sorted(directory.glob("*.py")):
        if path.name == Path(__file__).name or path.name.startswith("_"):
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        if any(isinstance(node, ast.FunctionDef) and node.name == "main" for node in tree.body):
            found.append(path)
    return found


def run(path: Path) -> tuple[int, float]:
    """Run one benchmark's ``main()`` in a fresh interpreter; return (exit status, seconds)."""
    env = dict(os.environ, WHEELKIN_BENCHMARK=str(path))
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", _RUNNER], cwd=ROOT, env=env, check=False)
    return done.returncode, time.perf_counter() - start


def main(argv: list[str] | None = None) -> int:
    names = sys.argv[1:] if argv is None else argv
    paths = benchmarks()
    if names:
        unknown = sorted(set(names) - {p.stem for p in paths})
        if unknown:
            known = ", ".join(p.stem for p in paths) or "none"
            print(f"run_all: no benchmark named {', '.join(unknown)} (there are: {known})",
                  file=sys.stderr)
            return 1
        paths = [p for p in paths if p.stem in names]
    if not paths:
        print("run_all: no benchmarks/*.py defines main()", file=sys.stderr)
        return 1
    results = []
    for path in paths:
        print(f"\n======== benchmark: {path.stem} ========", flush=True)
        status, seconds = run(path)
        results.append((path.stem, status, seconds))
        print(f"-------- {path.stem}: {'ok' if status == 0 else f'FAILED (exit {status})'}, "
              f"{seconds:.1f} s", flush=True)
    failed = [name for name, status, _ in results if status != 0]
    print(f"\nrun_all: {len(results) - len(failed)} ok, {len(failed)} failed"
          + (f" ({', '.join(failed)})" if failed else "")
          + "; results in benchmarks/RESULTS.md")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
