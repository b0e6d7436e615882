"""The instructor's kit: student edition and grader (``make kit``; the printed edition's
tests are in tests/pdf, ``make pdf``).

These tests build whole editions (minutes, not seconds), so they run in their own layer of
``make test``: they are collected only when pytest is pointed at ``tests/kit`` (or a file in
it), never by a run over the other layers' folders.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.own_layer import ignored_unless_asked

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def pytest_ignore_collect(collection_path, config):
    return ignored_unless_asked(HERE, collection_path, config)


@pytest.fixture(scope="session")
def student_edition(tmp_path_factory):
    """The student edition, built once (notebooks executed, web edition), as ``make student``
    builds it: ``(folder, stray globals found before each exercise stub)``. Set
    ``WHEELKIN_STUDENT_EDITION`` to a built edition's folder to test that one instead."""
    given = os.environ.get("WHEELKIN_STUDENT_EDITION")  # reuse a built one (make student)
    if given:
        out = Path(given).resolve()
        stray = json.loads((out / "stray_globals.json").read_text(encoding="utf-8"))
        return out, stray
    out = tmp_path_factory.mktemp("student") / "edition"
    done = subprocess.run([sys.executable, "-m", "tools.student_edition",
                           "--out", str(out), "-j", "2"], capture_output=True, text=True,
                          cwd=ROOT, timeout=3600)
    assert done.returncode == 0, (f"student_edition.py failed:\n{done.stdout[-3000:]}\n"
                                  f"{done.stderr[-3000:]}")
    stray = json.loads((out / "stray_globals.json").read_text(encoding="utf-8"))
    (ROOT / "_build").mkdir(exist_ok=True)
    (ROOT / "_build" / "stray_globals.json").write_text(json.dumps(stray, indent=1) + "\n",
                                                        encoding="utf-8")
    return out, stray


def pytest_terminal_summary(terminalreporter):
    """List the short or generic globals that visible cells leave before an exercise (not a
    failure: a derivation may name its symbols; hidden cells must not, and fail the test)."""
    report = ROOT / "_build" / "stray_globals.json"
    if not report.is_file():
        return
    stray = json.loads(report.read_text(encoding="utf-8"))
    lines = []
    for notebook, stubs in sorted(stray.items()):
        names = {}
        for at in stubs.values():
            for name, where in at.items():
                names.setdefault(name, where)
        if names:
            lines.append(f"{notebook}: " + ", ".join(
                f"{n} (cell {w['cell']}{', hidden' if w['hidden'] else ''})"
                for n, w in sorted(names.items())))
    if lines:
        terminalreporter.section("globals left before exercise stubs")
        for line in lines:
            terminalreporter.write_line(line)
