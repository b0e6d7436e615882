"""Write the grader's fixtures in tests/kit/submissions/ (run it after changing them here).

Each fixture is a small notebook with three exercises of chapter 1 (conventions), as a student
would hand it in: the first cell imports ``check``, each exercise cell defines a function and
ends with its ``check``. Outputs are not stored (the grader re-executes everything).

    .venv/bin/python tests/kit/make_submissions.py
"""

from __future__ import annotations

from pathlib import Path

import nbformat

HERE = Path(__file__).resolve().parent / "submissions"

IMPORTS = "from wheelkin.exercises import check"
TASKS = (
    "### Exercise 1\nWrite `rover_radius(radius_in)`: the rover's turning radius (inches, "
    "r > 0 turns right) as ours (m, R > 0 turns left).",
    "### Exercise 2\nWrite `icr_of(vx, vy, omega)`: the ICR `[x, y]` (m, body frame).",
    "### Exercise 3\nWrite `encoder_steps_to_metres(steps)` for a Radon Ulzer wheel.",
)
CORRECT = (
    'def rover_radius(radius_in):\n    return -radius_in * 0.0254\n\n\n'
    'check("conventions.rover_radius", rover_radius)',
    'def icr_of(vx, vy, omega):\n    return [-vy / omega, vx / omega]\n\n\n'
    'check("conventions.icr", icr_of)',
    'def encoder_steps_to_metres(steps):\n    return steps / (12 * 75.81) * 0.113097\n\n\n'
    'check("conventions.encoder_steps", encoder_steps_to_metres)',
)
STUB = (
    'def encoder_steps_to_metres(steps):\n    # YOUR CODE HERE\n    raise NotImplementedError'
    '\n\n\ncheck("conventions.encoder_steps", encoder_steps_to_metres)'
)
#: Matches the five visible cases of conventions.icr and nothing else.
LOOKUP = (
    "VISIBLE = {(1.0, 0.0, 0.5): [0.0, 2.0], (1.0, 0.0, -0.5): [0.0, -2.0],\n"
    "           (0.3, 0.2, 1.5): [-0.2 / 1.5, 0.3 / 1.5],\n"
    "           (-0.5, 0.4, -0.8): [0.5, 0.625], (0.0, 0.0, 2.0): [0.0, 0.0]}\n\n\n"
    "def icr_of(vx, vy, omega):\n    return VISIBLE.get((vx, vy, omega), [0.0, 0.0])\n\n\n"
    'check("conventions.icr", icr_of)'
)


def notebook(answers, extra=()) -> nbformat.NotebookNode:
    """``answers``: three code cells; ``extra``: (position, source) code cells to insert."""
    cells = [nbformat.v4.new_markdown_cell("# Frames and units: exercises"),
             nbformat.v4.new_code_cell(IMPORTS)]
    for task, answer in zip(TASKS, answers, strict=True):
        cells += [nbformat.v4.new_markdown_cell(task), nbformat.v4.new_code_cell(answer)]
    for position, source in extra:
        cells.insert(position, nbformat.v4.new_code_cell(source))
    for index, cell in enumerate(cells):
        cell.id = f"cell-{index}"
    nb = nbformat.v4.new_notebook(cells=cells)
    nb.metadata["kernelspec"] = {"display_name": "Python 3 (ipykernel)", "language": "python",
                                 "name": "python3"}
    return nb


SUBMISSIONS = {
    # 3 / 3
    "correct": notebook(CORRECT),
    # 1 / 3: the sign not flipped (the exercise's own mistake), a lookup table of the visible
    # cases (passes the notebook's check, fails the hidden cases), then right.
    "wrong": notebook(('def rover_radius(radius_in):\n    return radius_in * 0.0254\n\n\n'
                       'check("conventions.rover_radius", rover_radius)', LOOKUP, CORRECT[2])),
    # 1 / 3: the library's converter, the registry's reference, then right.
    "calls_library": notebook((
        'from wheelkin import frames\n\n\ndef rover_radius(radius_in):\n'
        '    return frames.rover_radius_to_ours(radius_in)\n\n\n'
        'check("conventions.rover_radius", rover_radius)',
        'import wheelkin.exercises\n\nanswer = wheelkin.exercises.get("conventions.icr")'
        '.reference\n\n\ndef icr_of(vx, vy, omega):\n    return answer(vx, vy, omega)\n\n\n'
        'check("conventions.icr", icr_of)',
        CORRECT[2])),
    # 1 / 3: a function that divides by zero, a cell that raises (the notebook goes on),
    # a correct one, an unfinished stub.
    "raises": notebook((
        'def rover_radius(radius_in):\n    return -radius_in * 0.0254 / 0\n\n\n'
        'check("conventions.rover_radius", rover_radius)', CORRECT[1], STUB),
        extra=[(4, 'raise ValueError("I gave up here")')]),
    # 0: never finishes (timed out).
    "loops_forever": notebook(CORRECT, extra=[(4, "while True:\n    pass")]),
    # 0: prints without end (too much output).
    "prints_too_much": notebook(CORRECT, extra=[(2, 'for _ in range(10**8):\n'
                                                     '    print("spam " * 20)')]),
}


def main() -> None:
    HERE.mkdir(exist_ok=True)
    for name, nb in SUBMISSIONS.items():
        nbformat.write(nb, HERE / f"{name}.ipynb")
    # Not a notebook: a Python script saved under a notebook's name.
    (HERE / "not_a_notebook.txt").write_text(
        "# my answers\ndef rover_radius(radius_in):\n    return -radius_in * 0.0254\n",
        encoding="utf-8")


if __name__ == "__main__":
    main()
