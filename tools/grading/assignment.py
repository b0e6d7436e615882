"""An assignment: which exercises are graded, and their points, declared in a TOML file.

.. code-block:: toml

    # assignments/chapter-09.toml
    title = "Car-like robots"              # shown in the results
    notebook = "06_sandbox.ipynb"          # optional: the file a Gradescope submission holds
    time_limit = 300                       # optional: seconds the notebook may run (120)
    call_limit = 60                        # optional: seconds for one exercise's calls (60)

    [[exercise]]
    name = "carlike.front_wheel_angles"    # a registered exercise (wheelkin.exercises)
    points = 2                             # optional (1)

    [[exercise]]
    name = "carlike.best_arm_angle"
    points = 3

A submission is graded on these exercises and nothing else: a ``check`` of another exercise
in the notebook is ignored, and the total never exceeds the sum of these points.
"""

from __future__ import annotations

import hashlib
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

KEYS = {"title", "notebook", "time_limit", "call_limit", "exercise"}
EXERCISE_KEYS = {"name", "points"}


class AssignmentError(ValueError):
    """The assignment file is not valid (the message names the file and the key)."""


@dataclass(frozen=True)
class Assignment:
    title: str
    exercises: tuple[tuple[str, float], ...]   # (name, points), in the file's order
    notebook: str | None = None
    time_limit: float = 120.0
    call_limit: float = 60.0
    digest: str = ""                           # of the file's text: results say which

    @property
    def names(self) -> list[str]:
        return [name for name, _ in self.exercises]

    @property
    def points(self) -> dict[str, float]:
        return dict(self.exercises)

    @property
    def total(self) -> float:
        return sum(points for _, points in self.exercises)


def _seconds(path: Path, data: dict, key: str, default: float) -> float:
    value = data.get(key, default)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
            math.isfinite(value) and 0 < value <= 3600):
        raise AssignmentError(f"{path}: {key} must be a number of seconds in (0, 3600], "
                              f"got {value!r}")
    return float(value)


def parse(text: str, path: Path = Path("<assignment>")) -> Assignment:
    """The assignment in ``text`` (TOML), checked: every exercise registered, no name twice,
    points positive."""
    from wheelkin.exercises import all_exercises

    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise AssignmentError(f"{path}: not valid TOML: {exc}") from None
    unknown = set(data) - KEYS
    if unknown:
        raise AssignmentError(f"{path}: unknown keys {', '.join(sorted(unknown))} (known: "
                              f"{', '.join(sorted(KEYS))})")
    entries = data.get("exercise")
    if not isinstance(entries, list) or not entries:
        raise AssignmentError(f"{path}: no [[exercise]] tables: name at least one exercise")
    known = all_exercises()
    exercises: list[tuple[str, float]] = []
    for k, entry in enumerate(entries, 1):
        if not isinstance(entry, dict) or set(entry) - EXERCISE_KEYS:
            raise AssignmentError(f"{path}: exercise {k} may only have the keys name and "
                                  "points")
        name = entry.get("name")
        if name not in known:
            raise AssignmentError(f"{path}: exercise {k}: no exercise named {name!r}; known: "
                                  f"{', '.join(sorted(known))}")
        if name in dict(exercises):
            raise AssignmentError(f"{path}: exercise {name!r} is named twice")
        points = entry.get("points", 1)
        if isinstance(points, bool) or not isinstance(points, (int, float)) or not (
                math.isfinite(points) and points > 0):
            raise AssignmentError(f"{path}: exercise {name!r}: points must be a number > 0, "
                                  f"got {points!r}")
        exercises.append((name, float(points)))
    notebook = data.get("notebook")
    if notebook is not None and (not isinstance(notebook, str) or "/" in notebook
                                 or not notebook.strip()):
        raise AssignmentError(f"{path}: notebook must be a file name, got {notebook!r}")
    title = data.get("title", path.stem)
    if not isinstance(title, str):
        raise AssignmentError(f"{path}: title must be text, got {title!r}")
    return Assignment(title, tuple(exercises), notebook,
                      _seconds(path, data, "time_limit", 120.0),
                      _seconds(path, data, "call_limit", 60.0),
                      hashlib.sha256(text.encode("utf-8")).hexdigest()[:16])


def load(path: Path) -> Assignment:
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as exc:
        raise AssignmentError(f"{path}: cannot read the assignment ({exc.strerror})") from None
    return parse(text, Path(path))


def for_notebook(nb, title: str, notebook: str | None = None, source: str = "",
                 time_limit: float = 300) -> str:
    """An assignment (TOML text) of every exercise a notebook checks, one point each:
    ``source`` (the notebook's path in the book) for the header comment."""
    from tools.grading.notebook import checks, code_cells

    names = list(dict.fromkeys(c.name for c in checks(code_cells(nb))))
    lines = []
    if source:
        lines += [f"# The exercises of {source}, one point each: edit the points, drop",
                  "# exercises, or add others (make grade ASSIGNMENT=..., make autograder "
                  "ASSIGNMENT=...)."]
    lines.append(f"title = {_toml_string(title)}")
    if notebook:
        lines.append(f"notebook = {_toml_string(notebook)}")
    lines.append(f"time_limit = {time_limit:g}    # seconds the whole notebook may run (its "
                 "figures and animations included)")
    for name in names:
        lines += ["", "[[exercise]]", f"name = {_toml_string(name)}", "points = 1"]
    return "\n".join(lines) + "\n"


def book_title(nb, path) -> str:
    """``"9. The car in the sandbox, and exercises"``: the chapter's number (from its
    folder, ``09_carlike``) and the notebook's first heading."""
    import re

    heading = next((m.group(1) for cell in nb.cells if cell.get("cell_type") == "markdown"
                    for m in [re.search(r"^# (.+)$", "".join(cell.get("source", "")), re.M)]
                    if m), path.stem)
    chapter = path.parent.name.split("_")[0].lstrip("0")
    return f"{chapter}. {heading}" if chapter.isdigit() else heading


def _toml_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'
