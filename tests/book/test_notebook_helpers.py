"""A helper a second notebook needs belongs in the library, never copied (issue 22).

Read from the stored notebooks (nothing is executed): the functions each notebook defines at
the top level of its code cells (``def``, or a name bound to a ``lambda``). The guard fails

- when one name is defined in two notebooks: a helper copied instead of imported from the
  library (``wheelkin.display`` for what a page shows, the chapter's modules for the rest).
  Allowed: an exercise's name registered in ``wheelkin.exercises`` (the exercise, not a
  helper);
- when a notebook defines a name twice, unless it is an exercise's stub (a cell tagged
  ``exercise``) and its solution (tagged ``solution``);
- when a notebook defines a function named like one of ``wheelkin.display``'s: a local copy
  that shadows the library's.

Functions nested in a function are local to it and are not counted.
"""

from __future__ import annotations

import ast
import json
from collections import defaultdict
from pathlib import Path

import pytest

from wheelkin import display
from wheelkin.exercises import all_exercises

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("**/*.ipynb"))


def _parse(source: str) -> ast.Module:
    """A code cell, its IPython magics (``%matplotlib inline``) read as comments."""
    lines = ["#" + line if line.lstrip().startswith(("%", "!")) else line
             for line in source.split("\n")]
    return ast.parse("\n".join(lines))


def defined_functions(path: Path) -> list[tuple[str, int, frozenset[str]]]:
    """(name, cell index, cell tags) of every top-level function a notebook defines."""
    nb = json.loads(path.read_text(encoding="utf-8"))
    out = []
    for index, cell in enumerate(nb["cells"]):
        if cell["cell_type"] != "code":
            continue
        tags = frozenset(cell.get("metadata", {}).get("tags", []))
        for node in _parse("".join(cell["source"])).body:
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                out.append((node.name, index, tags))
            elif isinstance(node, ast.Assign) and isinstance(node.value, ast.Lambda):
                out.extend((t.id, index, tags) for t in node.targets if isinstance(t, ast.Name))
    return out


def _rel(path: Path) -> str:
    return path.relative_to(ROOT).as_posix()


@pytest.fixture(scope="module")
def definitions() -> dict[str, list[tuple[str, int, frozenset[str]]]]:
    return {_rel(p): defined_functions(p) for p in NOTEBOOKS}


def exercise_names() -> set[str]:
    return {name.split(".", 1)[1] for name in all_exercises()}


def duplicated_helpers(definitions: dict) -> dict[str, list[str]]:
    """Names defined in more than one notebook (exercise names aside): name -> notebooks."""
    where: dict[str, set[str]] = defaultdict(set)
    for notebook, found in definitions.items():
        for name, _, _ in found:
            where[name].add(notebook)
    allowed = exercise_names()
    return {name: sorted(notebooks) for name, notebooks in where.items()
            if len(notebooks) > 1 and name not in allowed}


def test_the_notebooks_are_found_and_read():
    assert len(NOTEBOOKS) >= 50
    found = defined_functions(ROOT / "notebooks" / "01_conventions" / "05_units.ipynb")
    # the exercise rover_radius: its stub, then its (folded) solution
    assert [(cell, tags) for name, cell, tags in found if name == "rover_radius"] == [
        (13, frozenset({"exercise"})), (14, frozenset({"solution", "hide-input"}))]


def test_no_helper_is_defined_in_two_notebooks(definitions):
    duplicated = duplicated_helpers(definitions)
    assert not duplicated, (
        "functions defined in more than one notebook (move each into the library and import "
        "it in the notebooks' first cell; give a function that draws or checks one section's "
        "own thing a name that says so): "
        + "; ".join(f"{name} in {', '.join(nbs)}" for name, nbs in sorted(duplicated.items())))


def test_a_name_defined_twice_in_a_notebook_is_an_exercise_and_its_solution(definitions):
    wrong = []
    for notebook, found in definitions.items():
        cells: dict[str, list[frozenset[str]]] = defaultdict(list)
        for name, _, tags in found:
            cells[name].append(tags)
        for name, tag_sets in cells.items():
            if len(tag_sets) == 1:
                continue
            pair = (len(tag_sets) == 2 and "exercise" in tag_sets[0]
                    and "solution" in tag_sets[1])
            if not pair:
                wrong.append(f"{notebook}: {name} ({len(tag_sets)} definitions)")
    assert not wrong, ("a notebook defines these names more than once, and not as an "
                       "exercise's stub followed by its solution: " + "; ".join(wrong))


def test_no_notebook_shadows_a_display_helper(definitions):
    public = set(display.__all__)
    shadows = [f"{notebook} cell {cell}: {name}" for notebook, found in definitions.items()
               for name, cell, _ in found if name in public]
    assert not shadows, ("notebooks define their own copy of a wheelkin.display helper "
                         "(import it instead): " + "; ".join(shadows))


def test_the_guard_finds_a_planted_copy():
    planted = {"notebooks/a.ipynb": [("show_figure", 1, frozenset({"hide-input"})),
                                     ("draw_arena", 1, frozenset())],
               "notebooks/b.ipynb": [("draw_arena", 1, frozenset()),
                                     ("rover_radius", 3, frozenset({"exercise"}))],
               "notebooks/c.ipynb": [("rover_radius", 2, frozenset({"exercise"}))]}
    assert duplicated_helpers(planted) == {"draw_arena": ["notebooks/a.ipynb",
                                                          "notebooks/b.ipynb"]}
    with pytest.raises(AssertionError, match=r"notebooks/a\.ipynb cell 1: show_figure"):
        test_no_notebook_shadows_a_display_helper(planted)
