#!/usr/bin/env python
"""Gradescope's autograder for one assignment, as the zip Gradescope asks for.

Usage::

    python -m tools.autograder ASSIGNMENT.toml [--out _build/autograder]
    make autograder ASSIGNMENT=assignments/chapter-01.toml

The zip holds, at its root (Gradescope's layout, https://gradescope-autograders.readthedocs.io):

- ``setup.sh``: run once by Gradescope, as root, when it builds the image: installs Python
  (3.11 or later: choose the Ubuntu 24.04 base image), bubblewrap and util-linux from apt,
  and the grader's Python packages, pinned, into ``/autograder/venv``;
- ``run_autograder``: run for each submission: grades the notebook found in
  ``/autograder/submission`` with ``python -m tools.grade --gradescope`` (the same sandboxes and
  judge as ``make grade``; a secret drawn for the run) and writes
  ``/autograder/results/results.json``, where each exercise's hidden cases are shown only
  after the due date and the score never exceeds the assignment's total; if the grader
  itself fails, a results.json that says so and scores 0;
- ``assignment.toml``, ``requirements.txt``, the grader (``tools/__init__.py``,
  ``tools/grade.py``, ``tools/grading/``) and the library (``src/wheelkin``, on the grader's
  PYTHONPATH: the image installs no wheelkin).
"""

from __future__ import annotations

import argparse
import importlib.metadata as metadata
import stat
import sys
import zipfile
from pathlib import Path

from packaging.markers import default_environment
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

from tools.grading.assignment import AssignmentError, load

ROOT = Path(__file__).resolve().parents[1]

#: What a student's notebook and the grader import (with what these need).
PACKAGES = ("numpy", "pymunk", "matplotlib", "ipywidgets", "ipython", "sympy", "scipy",
            "mpmath", "nbformat", "matplotlib-inline", "traitlets")

SETUP = """#!/usr/bin/env bash
# Gradescope runs this once, as root, while it builds the autograder's image.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
apt-get install -y -q --no-install-recommends python3 python3-venv python3-pip bubblewrap \\
  util-linux ca-certificates </dev/null
python3 -c 'import sys; sys.exit(0 if sys.version_info >= (3, 11) else
  "the grader needs Python 3.11 or later: choose the Ubuntu 24.04 base image")'
python3 -m venv /autograder/venv
/autograder/venv/bin/python -m pip install --quiet --disable-pip-version-check \\
  -r /autograder/source/requirements.txt
"""

RUN = """#!/usr/bin/env bash
# Gradescope runs this for each submission (as root, in /autograder): grade the notebook in
# submission/ into results/results.json. AUTOGRADER_ROOT and AUTOGRADER_PYTHON let it run
# outside Gradescope's container (the kit's tests lay out such a folder).
set -uo pipefail
ROOT="${AUTOGRADER_ROOT:-/autograder}"
PYTHON="${AUTOGRADER_PYTHON:-$ROOT/venv/bin/python}"
cd "$ROOT/source" || exit 1
PYTHONPATH="$ROOT/source/src" "$PYTHON" -m tools.grade --gradescope "$ROOT" \\
  --assignment assignment.toml
status=$?
if [ "$status" -ne 0 ] || [ ! -s "$ROOT/results/results.json" ]; then
  mkdir -p "$ROOT/results"
  printf '{"score": 0.0, "tests": [], "output": "%s (exit status %s). %s"}\\n' \\
    "The autograder could not grade this submission" "$status" \\
    "Nothing was graded; your instructor has been shown why." > "$ROOT/results/results.json"
fi
exit 0
"""


def pinned_requirements(names=PACKAGES) -> list[str]:
    """``name==version`` for ``names`` and everything they need, as installed here (the
    versions of requirements.txt)."""
    environment = default_environment()
    seen: dict[str, str] = {}
    todo = list(names)
    while todo:
        name = canonicalize_name(todo.pop())
        if name in seen:
            continue
        dist = metadata.distribution(name)
        seen[name] = f"{dist.metadata['Name']}=={dist.version}"
        for text in dist.requires or []:
            requirement = Requirement(text)
            if requirement.marker is None or requirement.marker.evaluate(
                    {**environment, "extra": ""}):
                todo.append(requirement.name)
    return sorted(seen.values(), key=str.lower)


def _add(archive: zipfile.ZipFile, name: str, text: str, executable: bool = False) -> None:
    info = zipfile.ZipInfo(name, date_time=(2026, 1, 1, 0, 0, 0))
    info.external_attr = ((0o755 if executable else 0o644) | stat.S_IFREG) << 16
    info.compress_type = zipfile.ZIP_DEFLATED
    archive.writestr(info, text)


def build(assignment_path: Path, out: Path) -> Path:
    """Write the autograder zip of ``assignment_path`` into ``out``; return its path."""
    assignment = load(assignment_path)  # checked before anything is written
    out.mkdir(parents=True, exist_ok=True)
    target = out / f"{assignment_path.stem}.zip"
    files = [ROOT / "tools" / "__init__.py", ROOT / "tools" / "grade.py",
             *sorted((ROOT / "tools" / "grading").glob("*.py")),
             *sorted(p for p in (ROOT / "src" / "wheelkin").rglob("*")
                     if p.is_file() and "__pycache__" not in p.parts)]
    with zipfile.ZipFile(target, "w") as archive:
        _add(archive, "setup.sh", SETUP, executable=True)
        _add(archive, "run_autograder", RUN, executable=True)
        _add(archive, "assignment.toml", assignment_path.read_text(encoding="utf-8"))
        _add(archive, "requirements.txt", "# The grader's packages, pinned as the book's "
             "requirements.txt pins them.\n" + "\n".join(pinned_requirements()) + "\n")
        for path in files:
            _add(archive, path.relative_to(ROOT).as_posix(),
                 path.read_text(encoding="utf-8") if path.suffix != ".typed" else "")
    print(f"autograder: {target} ({assignment.title}: {len(assignment.exercises)} exercises, "
          f"{assignment.total:g} points)")
    return target


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("assignment", type=Path)
    parser.add_argument("--out", type=Path, default=ROOT / "_build" / "autograder")
    args = parser.parse_args(argv)
    try:
        build(args.assignment, args.out)
    except AssignmentError as exc:
        print(f"autograder: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())


__all__ = ["build", "pinned_requirements"]
