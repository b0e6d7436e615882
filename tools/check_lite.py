#!/usr/bin/env python
"""Can the book run in the browser alone (JupyterLite, Pyodide) yet? Ask the registries.

The live pages need a kernel; JupyterLite would run Python in the reader's browser instead
(Pyodide: CPython compiled to WebAssembly with Emscripten). It can only install wheels built
for Emscripten, and since PEP 783 PyPI accepts them under the platform tags
``pyemscripten_<year>_<patch>_wasm32`` (Pyodide's earlier ``pyodide_<year>_<patch>_wasm32``
wheels could not be uploaded). This script asks PyPI, through pip, for a WebAssembly wheel of
every package the book's kernel imports that is not pure Python, for each tag and CPython
version of :data:`TARGETS`; a pure-Python package (sympy, mpmath) installs from its
``py3-none-any`` wheel anywhere. It also asks npm what its ``pyodide`` package ships (the
runtime, or the runtime and its package repository).

It is not a test (it asks live registries, whose answer changes with time): run it by hand,
``.venv/bin/python tools/check_lite.py``, and read its table. The day every row says "yes"
for one target, ``make lite`` is a small step (docs/DESIGN.md, "Running in the browser
alone"). Exit status: 0 when some target has every package, 1 otherwise, 2 when pip or npm
could not be asked.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

#: What the book's kernel needs (requirements.txt): the compiled packages and their compiled
#: dependencies, and two pure-Python ones as a control (they must always say "yes").
PACKAGES: tuple[str, ...] = ("numpy", "matplotlib", "pillow", "kiwisolver", "contourpy",
                             "cffi", "pymunk", "scipy", "pyzmq", "sympy", "mpmath")
#: (CPython version, ABI tag, platform tag): Pyodide 314 (PEP 783's first tag) and 0.28
#: (the last pyodide_* tag), each with the CPython it embeds.
TARGETS: tuple[tuple[str, str, str], ...] = (
    ("3.14", "cp314", "pyemscripten_2026_0_wasm32"),
    ("3.13", "cp313", "pyemscripten_2025_0_wasm32"),
    ("3.13", "cp313", "pyodide_2025_0_wasm32"),
)
#: The kernel itself: JupyterLite's Pyodide kernel does not use pyzmq (it talks to the page),
#: so a missing pyzmq wheel does not block; every other package does.
NOT_BLOCKING = {"pyzmq"}


def wheel_for(package: str, python: str, abi: str, platform: str) -> str | None:
    """The file name of the wheel pip would download for that target, or None."""
    with tempfile.TemporaryDirectory() as out:
        command = [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps",
                   "--only-binary=:all:", "--disable-pip-version-check",
                   "--python-version", python, "--implementation", "cp", "--abi", abi,
                   "--abi", "none", "--platform", platform, "--platform", "any",
                   "--dest", out, package]
        done = subprocess.run(command, capture_output=True, text=True, check=False)
        wheels = sorted(p.name for p in Path(out).glob("*.whl"))
        if done.returncode == 0 and wheels:
            return wheels[0]
        if "No matching distribution" in done.stderr or "Could not find a version" \
                in done.stderr:
            return None
        raise RuntimeError(f"pip could not be asked about {package}: "
                           f"{done.stderr.strip().splitlines()[-1:]}")


def npm_pyodide() -> str:
    """What npm's pyodide package holds: its version and whether it ships packages."""
    npm = shutil.which("npm")
    if npm is None:
        return "npm not found"
    done = subprocess.run([npm, "view", "pyodide", "--json"], capture_output=True, text=True,
                          check=False)
    if done.returncode != 0:
        return f"npm view pyodide failed: {done.stderr.strip()[:200]}"
    info = json.loads(done.stdout)
    files = info.get("files", []) if isinstance(info, dict) else []
    wheels = [f for f in files if f.endswith(".whl")]
    return (f"pyodide {info.get('version')} on npm ships {len(files)} files, "
            f"{len(wheels)} of them wheels: " + (", ".join(wheels) if wheels else
                                                 "the runtime and its standard library alone"))


def main() -> int:
    rows, verdicts = [], {}
    try:
        for python, abi, platform in TARGETS:
            missing = []
            for package in PACKAGES:
                wheel = wheel_for(package, python, abi, platform)
                rows.append((f"cp{python.replace('.', '')} {platform}", package,
                             "yes: " + wheel if wheel else "no"))
                if wheel is None and package not in NOT_BLOCKING:
                    missing.append(package)
            verdicts[platform] = missing
    except RuntimeError as exc:
        print(f"check_lite: {exc}", file=sys.stderr)
        return 2
    width = max(len(r[0]) for r in rows)
    for target, package, answer in rows:
        print(f"{target:<{width}}  {package:<11} {answer}")
    print()
    print(npm_pyodide())
    ready = [p for p, missing in verdicts.items() if not missing]
    for platform, missing in verdicts.items():
        print(f"{platform}: " + ("every package has a wheel: JupyterLite can be tried"
                                 if not missing else "blocked by " + ", ".join(missing)))
    return 0 if ready else 1


if __name__ == "__main__":
    sys.exit(main())
