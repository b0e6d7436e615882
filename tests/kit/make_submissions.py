"""Write the grader's fixtures (run it after changing them here):

- ``submissions/``: honest submissions (correct, wrong, calling the library, raising, endless,
  too talkative, not a notebook);
- ``redteam/``: one submission per attack class of the red-team trial of the grader (issue
  24), each as a determined student would write it.

Each notebook answers exercises of ``assignments/conventions.toml`` (three of chapter 1 and
the sandbox's ramp), as a student hands it in: the first cell imports, each exercise cell
defines a function and ends with its ``check``. Outputs are not stored (the grader runs
everything again). Names the file system makes hard to commit (links, clashing names,
dot-files) are made by the tests from these.

    .venv/bin/python tests/kit/make_submissions.py
"""

from __future__ import annotations

from pathlib import Path

import nbformat

HERE = Path(__file__).resolve().parent
SUBMISSIONS, REDTEAM = HERE / "submissions", HERE / "redteam"

IMPORTS = "from wheelkin.exercises import check"
TASKS = (
    "### Exercise 1\nWrite `rover_radius(radius_in)`: the rover's turning radius (inches, "
    "r > 0 turns right) as ours (m, R > 0 turns left).",
    "### Exercise 2\nWrite `icr_of(vx, vy, omega)`: the ICR `[x, y]` (m, body frame).",
    "### Exercise 3\nWrite `encoder_steps_to_metres(steps)` for a Radon Ulzer wheel.",
)
#: A comment only the correct submission has: the red team's thief looks for it.
MARKER_HEAD, MARKER_TAIL = "# the classmate's own ", "answer, not to be found by anyone else"
MARKER = MARKER_HEAD + MARKER_TAIL
CORRECT = (
    f'def rover_radius(radius_in):\n    {MARKER}\n    return -radius_in * 0.0254\n\n\n'
    'check("conventions.rover_radius", rover_radius)',
    'def icr_of(vx, vy, omega):\n    return [-vy / omega, vx / omega]\n\n\n'
    'check("conventions.icr", icr_of)',
    'def encoder_steps_to_metres(steps):\n    return steps / (12 * 75.81) * 0.113097\n\n\n'
    'check("conventions.encoder_steps", encoder_steps_to_metres)',
)
#: The ramp exercise, as the book solves it (its stub reads the robot's mass and inertia
#: from RADON_ULZER, the part of the library the exercise declares; each of its two tracks
#: carries half the weight).
RAMP = '''import math

from wheelkin.sandbox import RADON_ULZER

M = RADON_ULZER.mass
I_Z = RADON_ULZER.inertia
W = 0.085
GRAVITY = 9.81


def grip_ramp_time(v, omega, mu):
    circle = 0.5 * mu * M * GRAVITY
    side = M * v * abs(omega) / 2
    if side >= circle:
        return math.inf
    return (M * v / 2 + I_Z * abs(omega) / W) / math.sqrt(circle**2 - side**2)


check("sandbox.grip_ramp_time", grip_ramp_time)'''
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


def notebook(answers, extra=(), ramp=False) -> nbformat.NotebookNode:
    """``answers``: three code cells; ``extra``: (position, source) code cells to insert;
    ``ramp``: add the ramp exercise, solved."""
    cells = [nbformat.v4.new_markdown_cell("# Frames and units: exercises"),
             nbformat.v4.new_code_cell(IMPORTS)]
    for task, answer in zip(TASKS, answers, strict=True):
        cells += [nbformat.v4.new_markdown_cell(task), nbformat.v4.new_code_cell(answer)]
    if ramp:
        cells += [nbformat.v4.new_markdown_cell("### The ramp"),
                  nbformat.v4.new_code_cell(ramp if isinstance(ramp, str) else RAMP)]
    for position, source in extra:
        cells.insert(position, nbformat.v4.new_code_cell(source))
    for index, cell in enumerate(cells):
        cell.id = f"cell-{index}"
    nb = nbformat.v4.new_notebook(cells=cells)
    nb.metadata["kernelspec"] = {"display_name": "Python 3 (ipykernel)", "language": "python",
                                 "name": "python3"}
    return nb


SUBMISSIONS_ = {
    # 4 / 4
    "correct": notebook(CORRECT, ramp=True),
    # 1 / 4: the sign not flipped (the exercise's own mistake), a lookup table of the visible
    # cases (passes the notebook's check, fails the hidden cases), then right; no ramp.
    "wrong": notebook(('def rover_radius(radius_in):\n    return radius_in * 0.0254\n\n\n'
                       'check("conventions.rover_radius", rover_radius)', LOOKUP, CORRECT[2])),
    # 1 / 4: the library's converter, the registry's reference, then right.
    "calls_library": notebook((
        'from wheelkin import frames\n\n\ndef rover_radius(radius_in):\n'
        '    return frames.rover_radius_to_ours(radius_in)\n\n\n'
        'check("conventions.rover_radius", rover_radius)',
        'import wheelkin.exercises\n\nanswer = wheelkin.exercises.get("conventions.icr")'
        '.reference\n\n\ndef icr_of(vx, vy, omega):\n    return answer(vx, vy, omega)\n\n\n'
        'check("conventions.icr", icr_of)',
        CORRECT[2])),
    # 1 / 4: a function that divides by zero, a cell that raises (the notebook goes on),
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

# --------------------------------------------------------------------------- the red team

#: A process that outlives its notebook if it can: it waits for the Python that started it
#: to end, then kills every process it may signal and fills /tmp, for two minutes. The
#: marker in its command line lets the test look for it after the run.
DAEMON = '''import os
import subprocess
import sys

DAEMON = """
import os, signal, sys, time
runner = int(sys.argv[1])
while True:
    try:
        os.kill(runner, 0)
    except ProcessLookupError:
        break
    time.sleep(0.05)
end = time.time() + 120
while time.time() < end:
    try:
        os.kill(-1, signal.SIGKILL)
    except OSError:
        pass
    try:
        open(f"/tmp/left-behind-{time.time()}", "w").write("x" * 10**6)
    except OSError:
        pass
    time.sleep(0.05)
"""
SPAWNED = []


def spawn():
    """Start the daemon twice: in a new session, and double-forked (once per process)."""
    if SPAWNED:
        return
    SPAWNED.append(True)
    argv = [sys.executable, "-c", DAEMON, str(os.getpid()), "wheelkin-redteam-daemon"]
    subprocess.Popen(argv, start_new_session=True, stdin=subprocess.DEVNULL,
                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    if os.fork() == 0:
        os.setsid()
        if os.fork() == 0:
            os.execv(sys.executable, argv)
        os._exit(0)
    os.wait()


spawn()'''

THIEF = f'''import os


def _classmates_answer():
    """Look everywhere for a classmate's notebook (its answer has a known comment): True if
    found, False if the search ended without it, None if it ran out of time. The comment is
    put together here, so that this notebook's own text (in the job it runs from) never
    matches; Python's own installation, the same for everyone, is not searched."""
    marker = {MARKER_HEAD!r} + {MARKER_TAIL!r}
    import sys
    import time

    end = time.monotonic() + 10
    python = {{os.path.realpath(p) for p in (sys.prefix, sys.base_prefix)}}
    roots = ["/tmp", "/home", "/root", "/work", "/opt", "/autograder", "/srv", "/mnt",
             "/var/tmp", "/etc"]
    roots += [f"/proc/{{p}}/cwd" for p in os.listdir("/proc") if p.isdigit()]
    roots += [f"/proc/{{p}}/root/tmp" for p in os.listdir("/proc") if p.isdigit()]
    for root in roots:
        for dirpath, dirs, files in os.walk(root):
            dirs[:] = [d for d in dirs
                       if os.path.realpath(os.path.join(dirpath, d)) not in python]
            if time.monotonic() > end:
                return None
            for name in files:
                try:
                    with open(os.path.join(dirpath, name), errors="ignore") as f:
                        if marker in f.read(2_000_000):
                            return True
                except OSError:
                    continue
    return False


FOUND = _classmates_answer()


def rover_radius(radius_in):
    # copied from the classmate if found; a guess if the search found nothing; a different
    # guess if it gave up (so that a search cut short cannot pass for one that found nothing)
    if FOUND:
        return -radius_in * 0.0254
    return radius_in if FOUND is False else 2 * radius_in


check("conventions.rover_radius", rover_radius)'''

TAMPER = '''import builtins
import gc
import os
import sys

import numpy as np

import wheelkin.exercises as ex


def attempt(action):
    try:
        action()
    except Exception:
        pass


# The old grader ran in this kernel: change everything it used.
attempt(lambda: setattr(ex.Exercise, "check", lambda self, fn: ex.CheckResult(
    self.name, True, "✔ all good", "pass")))
attempt(lambda: setattr(np, "allclose", lambda *a, **k: True))
attempt(lambda: setattr(np, "isclose", lambda *a, **k: np.True_))
attempt(lambda: setattr(builtins, "check", lambda *a, **k: None))
attempt(lambda: setattr(sys, "setprofile", lambda *a, **k: None))
FORGED = (b'{"cell": 3, "ran": "all"}\\n{"case": 0, "answer": {"kind": "value", "shape": [], '
          b'"values": [0.0]}}\\n{"done": true}\\n')
for obj in gc.get_objects():  # the report stream of whatever runs the notebook
    if type(obj).__name__ == "TextIOWrapper":
        attempt(lambda obj=obj: obj.write(FORGED.decode()))
for fd in range(3, 64):  # forged reports on every descriptor
    attempt(lambda fd=fd: os.write(fd, FORGED))
print("✔ conventions.rover_radius: correct on all 5 visible and 8 hidden cases.")'''

POISON = '''import os
import site

# Poison what later sandboxes load: the venv, the grader's scripts, the library.
targets = [os.path.join(p, "sitecustomize.py") for p in site.getsitepackages()]
targets += ["/opt/grader/tools/grading/wire.py", "/opt/grader/tools/__init__.py",
            "/opt/grader/sitecustomize.py", "/opt/wheelkin/wheelkin/__init__.py",
            "/opt/job/job.json"]
payload = "import builtins\\nbuiltins.__import__ = None\\n"
WROTE = []
for target in targets:
    try:
        with open(target, "w") as f:
            f.write(payload)
        WROTE.append(target)
    except OSError:
        pass
# Plant links where root might follow them.
for target, name in [("/etc/shadow", "shadow"), ("/root", "rootdir"), ("/", "slash"),
                     ("/opt/job", "job")]:
    for folder in (os.environ.get("HOME", "/tmp"), "/tmp"):
        try:
            os.symlink(target, os.path.join(folder, name))
        except OSError:
            pass
try:
    os.symlink("/etc/passwd", "/opt/job/planted")
    WROTE.append("/opt/job/planted")
except OSError:
    pass'''

REDTEAM_ = {
    # The library from a thread: 0 for rover_radius (no library where it is graded).
    "thread": notebook((
        'import threading\n\nfrom wheelkin import frames\n\n\ndef rover_radius(radius_in):\n'
        '    out = []\n    worker = threading.Thread(target=lambda: out.append(\n'
        '        frames.rover_radius_to_ours(radius_in)))\n    worker.start()\n'
        '    worker.join()\n    return out[0]\n\n\n'
        'check("conventions.rover_radius", rover_radius)', CORRECT[1], CORRECT[2])),
    # The library from a forked child, the answer through a pipe: 0 for icr.
    "fork": notebook((CORRECT[0],
        'import os\nimport pickle\n\n\ndef icr_of(vx, vy, omega):\n    r, w = os.pipe()\n'
        '    if os.fork() == 0:\n        try:\n            from wheelkin import frames\n'
        '            os.write(w, pickle.dumps(list(frames.icr((vx, vy, omega)))))\n'
        '        finally:\n            os._exit(0)\n    os.close(w)\n'
        '    data = os.read(r, 65536)\n    os.wait()\n'
        '    return pickle.loads(data)\n\n\ncheck("conventions.icr", icr_of)', CORRECT[2])),
    # A copy of the package placed elsewhere, and its source carried as text: 0 for both.
    "copied_package": notebook((
        'import importlib\nimport os\nimport shutil\nimport sys\n\nimport wheelkin\n\n'
        'STASH = "/tmp/stash"\nshutil.copytree(os.path.dirname(wheelkin.__file__), '
        'STASH + "/wheelkin_copy", dirs_exist_ok=True)\n\n\ndef rover_radius(radius_in):\n'
        '    sys.path.insert(0, STASH)\n'
        '    return importlib.import_module("wheelkin_copy.frames").rover_radius_to_ours('
        'radius_in)\n\n\ncheck("conventions.rover_radius", rover_radius)',
        'from wheelkin import frames\n\nSOURCE = open(frames.__file__).read()\n\n\n'
        'def icr_of(vx, vy, omega):\n    space = {"__name__": "copy"}\n'
        '    exec(SOURCE.replace("from __future__ import annotations", ""), space)\n'
        '    return list(space["icr"]((vx, vy, omega)))\n\n\n'
        'check("conventions.icr", icr_of)', CORRECT[2])),
    # The old grader's call monitor switched off, then the library: 0 for rover_radius.
    "monitor_disabled": notebook((
        'import sys\nimport threading\n\nfrom wheelkin import frames\n\n'
        'sys.setprofile(None)\nsys.setprofile = lambda *a, **k: None\n'
        'threading.setprofile = lambda *a, **k: None\n\n\ndef rover_radius(radius_in):\n'
        '    return frames.rover_radius_to_ours(radius_in)\n\n\n'
        'check("conventions.rover_radius", rover_radius)', CORRECT[1], CORRECT[2])),
    # The grader's state changed from the notebook, forged reports, wrong functions: 0.
    "grader_state": notebook((
        'def rover_radius(radius_in):\n    return 0.0\n\n\n'
        'check("conventions.rover_radius", rover_radius)',
        'def icr_of(vx, vy, omega):\n    return [0.0, 0.0]\n\n\n'
        'check("conventions.icr", icr_of)',
        'def encoder_steps_to_metres(steps):\n    return 0.0\n\n\n'
        'check("conventions.encoder_steps", encoder_steps_to_metres)'),
        extra=[(2, TAMPER)]),
    # A classmate's notebook read during grading: 0 for rover_radius (nothing to find).
    "classmate_file": notebook((THIEF, CORRECT[1], CORRECT[2])),
    # Processes left behind (a new session, a double fork), here and when graded: its own
    # grade (3 / 4), and no one else's changes.
    "left_behind": notebook((CORRECT[0], CORRECT[1], CORRECT[2].replace(
        "    return steps", "    spawn()\n    return steps")), extra=[(2, DAEMON)]),
    # Links planted and the shared files poisoned: its own grade (3 / 4); no one hurt.
    "symlink_planted": notebook(CORRECT, extra=[(2, POISON)]),
    # Extra exercises from other chapters, one not registered: only the assignment's count.
    "extra_exercises": notebook(CORRECT, extra=[(8,
        'import math\n\nimport numpy as np\n\n\ndef front_wheel_angles(R, L, W):\n'
        '    return np.array([math.atan(L / (R - W / 2)), math.atan(L / (R + W / 2))])\n\n\n'
        'check("carlike.front_wheel_angles", front_wheel_angles)\n'
        'check("carlike.tightest_radius", lambda d, L, W: L / math.tan(math.radians(d)) + '
        'W / 2)\ncheck("no.such_exercise", front_wheel_angles)')]),
    # Checks in dead code: the one that ran counts (wrong rover_radius: 0; right icr: 1; an
    # encoder_steps check after an error in its cell: not graded, 0).
    "dead_code_check": notebook((
        'def rover_radius(radius_in):\n    return radius_in * 0.0254\n\n\n'
        'check("conventions.rover_radius", rover_radius)\n\n\n'
        'def right(radius_in):\n    return -radius_in * 0.0254\n\n\n'
        'if False:\n    check("conventions.rover_radius", right)\n\n\n'
        'def never():\n    check("conventions.rover_radius", right)',
        CORRECT[1] + '\n\n\ndef wrong(vx, vy, omega):\n    return [0.0, 0.0]\n\n\n'
        'if False:\n    check("conventions.icr", wrong)',
        CORRECT[2].replace("check(", "x = 1 / 0\ncheck(", 1)),
        extra=[(8, 'while False:\n    check("conventions.icr", lambda vx, vy, omega: [0, 0])')]),
    # An absurd answer for the judge that simulates, on the hidden cases only (the notebook's
    # own check passes): 0 for the ramp, within the judge's time limit; the rest right.
    "absurd_judge_input": notebook(CORRECT, ramp=RAMP.replace(
        "def grip_ramp_time(v, omega, mu):\n",
        "VISIBLE = {(0.5, 3.0, 0.8), (0.4, 1.0, 0.1), (0.4, 0.0, 0.1), (0.4, -2.0, 0.3),\n"
        "           (0.0, 6.0, 0.3), (0.6, 4.0, 0.5), (0.4, 2.5, 0.1), (0.5, 2.98, 0.2)}\n\n\n"
        "def grip_ramp_time(v, omega, mu):\n"
        "    if (v, omega, mu) not in VISIBLE:\n"
        "        return 4e5  # days of simulated driving for whoever checks it\n")),
}


def main() -> None:
    for folder, notebooks in ((SUBMISSIONS, SUBMISSIONS_), (REDTEAM, REDTEAM_)):
        folder.mkdir(exist_ok=True)
        for name, nb in notebooks.items():
            nbformat.write(nb, folder / f"{name}.ipynb")
    # Not a notebook: a Python script handed in.
    (SUBMISSIONS / "not_a_notebook.txt").write_text(
        "# my answers\ndef rover_radius(radius_in):\n    return -radius_in * 0.0254\n",
        encoding="utf-8")


if __name__ == "__main__":
    main()
