"""Exercises fail for the right reason: before each exercise stub, the cells a student does
not see (folded, ``hide-input``) leave no short or generic global (``a``, ``ax``, ``fig`` ...),
so that a student's undefined name raises a plain ``NameError``.

The names are recorded while the student edition executes (tools/student_edition.py: after
every cell, before every stub). Names left by visible cells (a derivation's symbols) are
listed in the terminal summary, not failed.
"""

from __future__ import annotations

from pathlib import Path

import nbformat
import pytest

from tools.student_edition import is_stray, toc_notebooks

ROOT = Path(__file__).resolve().parents[2]


def _has_exercises(rel: Path) -> bool:
    nb = nbformat.read(ROOT / rel, as_version=4)
    return any("exercise" in c.metadata.get("tags", []) for c in nb.cells)


EXERCISE_NOTEBOOKS = [p for p in toc_notebooks() if _has_exercises(p)]


def test_short_and_generic_names():
    assert all(is_stray(n) for n in ("a", "x", "D", "fig", "ax", "axes", "anim", "t", "xs"))
    assert not any(is_stray(n) for n in ("rover_radius", "track_width", "np", "_", "Pose"))


@pytest.mark.parametrize("rel", EXERCISE_NOTEBOOKS, ids=lambda p: p.as_posix())
def test_no_stray_global_from_a_hidden_cell(rel, student_edition):
    _, stray = student_edition
    found = stray.get(rel.as_posix(), {})
    hidden = sorted({f"{name} (from cell {where['cell']})" for at in found.values()
                     for name, where in at.items() if where["hidden"]})
    assert not hidden, (f"{rel}: folded cells leave {', '.join(hidden)} in the namespace of "
                        "its exercises: draw inside a function, or `del` them at the end of "
                        "the cell")
