"""The grader's parts that need no sandbox (tools/grading/): the slice of a notebook a
function needs, the check that counts, the library parts an exercise may use, the data that
crosses a sandbox's wall, the assignment file, the student ids of a folder, Gradescope's
results.json, and the command that makes a sandbox."""

from __future__ import annotations

import ast
import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import numpy as np
import pytest

from tools import grade
from tools.grading import jail, library_parts, wire
from tools.grading import notebook as nbtools
from tools.grading.assignment import AssignmentError, for_notebook, parse
from tools.grading.source import needed_statements, statements_of
from wheelkin.exercises import all_exercises

ROOT = Path(__file__).resolve().parents[2]


def _slice(code: str, names: set[str]) -> list[str]:
    return [src.strip() for _, src in needed_statements(statements_of(code), names)]


# ----------------------------------------------------------------------------- the slice

def test_slice_keeps_what_the_function_needs_and_nothing_else():
    code = ("import math, os\nimport numpy as np\nK = 2\nPLOT = expensive_figure()\n"
            "def helper(x):\n    return K * x\n"
            "def f(x):\n    return helper(math.sqrt(x)) + np.pi\n"
            "K = 4\nprint(f(2))\n")
    assert _slice(code, {"f"}) == [
        "import math", "import numpy as np", "def helper(x):\n    return K * x",
        "def f(x):\n    return helper(math.sqrt(x)) + np.pi", "K = 4"]


def test_slice_follows_changes_in_place_and_global_setters():
    code = ("TABLE = {}\nTABLE['a'] = 1\nfor k in range(3):\n    TABLE[k] = k * k\n"
            "ROWS = []\nROWS.append(5)\n"
            "def setup():\n    global SCALE\n    SCALE = 3\nsetup()\n"
            "def f(x):\n    return TABLE[x] * SCALE + ROWS[0]\n")
    kept = _slice(code, {"f"})
    assert "TABLE['a'] = 1" in kept and "ROWS.append(5)" in kept and "setup()" in kept
    assert any(s.startswith("for k in range(3)") for s in kept)


def test_calling_a_module_function_does_not_pull_in_the_statement():
    """``np.max(...)`` in a plotting loop does not change ``np``: the loop is not needed."""
    code = ("import numpy as np\nRUNS = simulate_everything()\n"
            "for run in RUNS:\n    print(np.max(run))\n"
            "def f(x):\n    return np.sin(x)\n")
    assert _slice(code, {"f"}) == ["import numpy as np", "def f(x):\n    return np.sin(x)"]


def test_an_import_of_many_names_keeps_only_those_needed():
    code = "from wheelkin.unified import (\n    WheelConstraint,\n    mobility,\n    rolling_row,\n)\n"
    assert _slice(code, {"mobility"}) == ["from wheelkin.unified import mobility"]


def _cells(*sources):
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(s) for s in sources])
    return nbtools.code_cells(nb)


def test_the_check_that_counts_is_the_last_one_that_ran():
    cells = _cells(
        "def f(x):\n    return x\ncheck('demo.x', f)",
        "if False:\n    check('demo.x', g)\ndef never():\n    check('demo.y', g)",
        "x = 1 / 0\ncheck('demo.z', f)",
        "%matplotlib inline\ncheck('demo.w', lambda x: x)")
    ran = nbtools.ran(cells, {0: "all", 1: "all", 2: 1, 3: "all"})
    counted = nbtools.counted_checks(cells, ran)
    assert set(counted) == {"demo.x", "demo.w"}  # dead code, a stopped cell: not counted
    assert counted["demo.x"].expr == "f"
    assert {c.name for c in nbtools.checks(cells)} == {"demo.x", "demo.z", "demo.w"}


def test_a_redefinition_after_the_check_is_not_what_was_checked():
    cells = _cells("def f(x):\n    return 1\ncheck('demo.x', f)\ndef f(x):\n    return 2")
    ran = nbtools.ran(cells, {0: "all"})
    check = nbtools.counted_checks(cells, ran)["demo.x"]
    assert nbtools.function_slice(check, ran) == ["def f(x):\n    return 1\n"]


# ----------------------------------------------------------------------------- library parts

def _build(parts, tmp_path):
    out = library_parts.build(parts, ROOT / "src", tmp_path / "parts")
    return {p.relative_to(out).as_posix(): p.read_text(encoding="utf-8")
            for p in out.rglob("*.py")}


def _defined(text: str) -> set[str]:
    names = set()
    for node in ast.parse(text).body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            for target in getattr(node, "targets", [getattr(node, "target", None)]):
                if isinstance(target, ast.Name):
                    names.add(target.id)
    return names


def test_library_parts_hold_the_declared_function_and_not_the_answer(tmp_path):
    files = _build(["wheelkin.carlike.linkage_error"], tmp_path)
    carlike = _defined(files["wheelkin/carlike.py"])
    assert "linkage_error" in carlike and "optimal_arm_angle" not in carlike
    assert "ackermann_angles" not in carlike  # another exercise's answer, not needed here
    # As in the grading sandbox: the parts on PYTHONPATH, the library's source out of reach.
    code = ("import sys; sys.path = [p for p in sys.path if not p.endswith('src')]; "
            "from wheelkin.carlike import linkage_error; "
            "print(linkage_error(0.5, wheelbase=2.5, track_width=1.5, arm_length=0.15, "
            "arm_angle=0.3))")
    env = {**os.environ, "PYTHONPATH": str(tmp_path / "parts")}
    done = subprocess.run([sys.executable, "-P", "-s", "-c", code], capture_output=True,
                          text=True, cwd=tmp_path, env=env, check=True)
    from wheelkin.carlike import linkage_error

    assert float(done.stdout) == pytest.approx(linkage_error(0.5, wheelbase=2.5, track_width=1.5,
                                                             arm_length=0.15, arm_angle=0.3))


def test_library_parts_never_hold_an_exercise_reference(tmp_path):
    for name, exercise in all_exercises().items():
        if not exercise.library:
            continue
        files = _build(list(exercise.library), tmp_path / name)
        module = exercise.reference.__module__
        path = module.replace(".", "/") + ".py"
        if path in files:
            assert exercise.reference.__name__ not in _defined(files[path]), name
        for part in exercise.library:
            module, _, attr = part.rpartition(".")
            text = files.get(module.replace(".", "/") + ".py") or files[
                module.replace(".", "/") + "/__init__.py"]
            assert attr in _defined(text) or f"import {attr}" in text, part


def test_an_unknown_library_part_is_an_error(tmp_path):
    with pytest.raises(ValueError, match="no_such_name"):
        library_parts.build(["wheelkin.carlike.no_such_name"], ROOT / "src", tmp_path)
    with pytest.raises(ValueError, match="no module"):
        library_parts.build(["wheelkin.nowhere.x"], ROOT / "src", tmp_path)


# ----------------------------------------------------------------------------- data only

def test_cases_cross_as_data_and_come_back_equal():
    for exercise in all_exercises().values():
        for case in exercise.cases:
            sent = json.loads(json.dumps(wire.encode_case(case.args, case.kwargs)))
            args, kwargs = wire.decode_case(sent)
            assert repr(args) == repr(case.args) and kwargs == case.kwargs


@pytest.mark.parametrize("bad", [
    {"kind": "value", "shape": [2], "values": [1.0]},            # shape and size disagree
    {"kind": "value", "shape": [-1], "values": []},
    {"kind": "value", "shape": [1], "values": ["1"]},            # not a number
    {"kind": "value", "shape": [1], "values": [True]},
    {"kind": "pickle", "data": "gASVCAAAAAAAAACMBHRlc3SULg=="},   # no such kind
    ["value"], "value", None,
])
def test_a_malformed_answer_is_refused(bad):
    assert wire.checked_answer(bad) is None


def test_answers_are_numbers_shapes_and_short_texts():
    assert wire.answer(np.eye(2))["shape"] == [2, 2]
    assert wire.answer(None) == {"kind": "none"}
    opaque = wire.answer(object())
    assert opaque["kind"] == "opaque" and len(opaque["repr"]) <= wire.MAX_TEXT
    long = wire.checked_answer({"kind": "raised", "ename": "E" * 500, "evalue": "x" * 10**4})
    assert len(long["ename"]) <= 60 and len(long["evalue"]) <= wire.MAX_TEXT
    back = wire.checked_answer(json.loads(wire.dumps(wire.answer([math.inf, math.nan]))))
    assert back["values"][0] == math.inf and math.isnan(back["values"][1])


# ----------------------------------------------------------------------------- assignments

GOOD = '''title = "T"
notebook = "04_units.ipynb"
[[exercise]]
name = "conventions.icr"
points = 2.5
[[exercise]]
name = "conventions.rover_radius"
'''


def test_an_assignment_lists_exercises_and_points():
    assignment = parse(GOOD)
    assert assignment.exercises == (("conventions.icr", 2.5), ("conventions.rover_radius", 1.0))
    assert assignment.total == 3.5 and assignment.notebook == "04_units.ipynb"
    assert assignment.time_limit == 120 and len(assignment.digest) == 16


@pytest.mark.parametrize(("text", "words"), [
    ("title = 1\n", "no [[exercise]]"),
    ('[[exercise]]\nname = "no.such"\n', "no exercise named 'no.such'"),
    ('[[exercise]]\nname = "conventions.icr"\npoints = -1\n', "points must be a number > 0"),
    ('[[exercise]]\nname = "conventions.icr"\n[[exercise]]\nname = "conventions.icr"\n',
     "named twice"),
    ('time_limit = 0\n[[exercise]]\nname = "conventions.icr"\n', "time_limit must be"),
    ('colour = "red"\n[[exercise]]\nname = "conventions.icr"\n', "unknown keys colour"),
    ('[[exercise]]\nname = "conventions.icr"\nweight = 2\n', "only have the keys"),
    ("[[exercise]\n", "not valid TOML"),
])
def test_a_bad_assignment_is_refused_with_its_reason(text, words):
    with pytest.raises(AssignmentError, match=words.replace("[", r"\[").replace("(", r"\(")):
        parse(text)


def test_an_assignment_is_made_from_a_notebook():
    nb = nbformat.read(ROOT / "notebooks/09_carlike/06_sandbox.ipynb", as_version=4)
    assignment = parse(for_notebook(nb, "Car-like", "06_sandbox.ipynb"))
    assert "carlike.best_arm_angle" in assignment.names and len(assignment.names) == 5


# ----------------------------------------------------------------------------- the folder

def test_every_name_gets_an_id_and_a_folder_of_its_own(tmp_path):
    import unicodedata

    names = ["alice.ipynb", "alice", "Bob.ipynb", "bob.ipynb", "Ünïcødé 学生.ipynb",
             unicodedata.normalize("NFC", "é.ipynb"), unicodedata.normalize("NFD", "é.ipynb"),
             "new\nline.ipynb", ".hidden.ipynb", "..ipynb", ".DS_Store"]
    items = [grade.Entry(tmp_path / n, n, "file") for n in names]
    ids = grade.student_ids(items)
    students = [ids[n][0] for n in names]
    folders = [ids[n][1] for n in names]
    assert students[:3] == ["alice.ipynb", "alice", "Bob"] and students[4] == "Ünïcødé 学生"
    assert len({f.casefold() for f in folders}) == len(names)  # told apart, even Bob/bob
    assert all("/" not in f and "\n" not in f and f not in (".", "..") for f in folders)
    assert ids[".hidden.ipynb"] == (".hidden", ".hidden")


def test_results_json_caps_the_score_and_hides_hidden_cases_until_the_due_date():
    assignment = parse(GOOD)
    result = grade.SubmissionResult("s", "s.ipynb", "s")
    result.verdicts = [grade.Verdict("conventions.icr", 2.5, 2.5, "✔ all", "✔ visible"),
                       grade.Verdict("conventions.rover_radius", 1.0, 5.0, "✔", "✔")]
    data = grade.gradescope(result, assignment)
    assert data["score"] == 3.5  # never more than the assignment's total
    assert [t["visibility"] for t in data["tests"]] == ["visible", "after_due_date"] * 2
    assert [t["max_score"] for t in data["tests"]] == [0.0, 2.5, 0.0, 1.0]
    assert data["tests"][0]["output"] == "✔ visible" and data["stdout_visibility"] == "hidden"


# ----------------------------------------------------------------------------- the sandbox

def test_two_runs_never_share_a_uid():
    """Each grading run locks a block of uids: a second run gets another block (a run's
    clean-up kills every process of its uids, so sharing one would kill a neighbour's)."""
    first, lock1 = jail.claim_uids()
    second, lock2 = jail.claim_uids()
    try:
        if lock1 is None:
            pytest.skip("an ordinary user's sandboxes run as that user")
        assert first != second and abs(first - second) >= jail.BLOCK
    finally:
        for lock in (lock1, lock2):
            if lock is not None:
                os.close(lock)


def test_the_sandbox_command_isolates_and_limits(tmp_path):
    box = jail.Sandbox(jail.Limits(seconds=9, memory=10**9, output=10), tmp_path,
                       [(tmp_path, "/opt/job")], slot=3)
    cmd = box.command(["python", "x.py"])
    for flag in ("--die-with-parent", "--new-session", "--unshare-pid", "--unshare-net",
                 "--unshare-ipc", "--clearenv", "--proc", "--dev"):
        assert flag in cmd, flag
    assert ["--ro-bind", str(tmp_path), "/opt/job"] == cmd[cmd.index(str(tmp_path)) - 1:
                                                           cmd.index(str(tmp_path)) + 2]
    assert "--bind" not in cmd, "nothing of the host is writable inside"
    assert "--as=1000000000" in cmd and "--cpu=14" in cmd and "--core=0" in cmd
    tmpfs = [cmd[k + 1] for k, a in enumerate(cmd) if a == "--tmpfs"]
    assert tmpfs == ["/tmp", jail.HOME]
    if box.as_root:  # a uid of its own, no capabilities, no new privileges
        assert f"--reuid={jail.UID_BASE + 3}" in cmd and "--no-new-privs" in cmd
        assert "--bounding-set=-all" in cmd and "--nproc=64" in cmd
    else:
        assert "--unshare-user" in cmd and "--disable-userns" in cmd
    env = {cmd[k + 1] for k, a in enumerate(cmd) if a == "--setenv"}
    assert env <= {"PATH", "HOME", "USER", "LOGNAME", "TMPDIR", "LANG", "LC_ALL", "TZ",
                   "PYTHONHASHSEED", "PYTHONDONTWRITEBYTECODE", "MPLBACKEND", "MPLCONFIGDIR",
                   "IPYTHONDIR", "OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS",
                   "PYDEVD_DISABLE_FILE_VALIDATION"}


def test_a_bind_under_tmp_is_seen_inside_the_private_tmp(tmp_path):
    """A fresh clone in ``mktemp -d`` has its venv under /tmp: the sandbox's own /tmp holds it
    read-only, and stays writable."""
    shown = tmp_path / "venv-like"
    shown.mkdir()
    (shown / "marker").write_text("here\n", encoding="utf-8")
    uid_base, lock = jail.claim_uids()  # a block of uids no other run uses
    try:
        etc = jail.write_etc(tmp_path / "etc", uid_base)
        box = jail.Sandbox(jail.Limits(seconds=30), etc, [(shown, str(shown))],
                           uid_base=uid_base)
        done = box.run(["/bin/sh", "-c", f"cat {shown}/marker; touch /tmp/x && echo tmp-ok; "
                        f"touch {shown}/y 2>/dev/null || echo read-only; ls /tmp"])
    finally:
        if lock is not None:
            os.close(lock)
    assert done.returncode == 0, done.tail
    words = done.tail.split()
    assert words[:3] == ["here", "tmp-ok", "read-only"], done.tail
    # the private /tmp holds the file written there, the bind's top folder, and (when the
    # grader's own Python lives under /tmp, as in a fresh clone made by mktemp) its venv's
    expected = {"x", shown.relative_to("/tmp").parts[0]}
    prefix = Path(sys.prefix).resolve()
    if prefix.is_relative_to("/tmp"):
        expected.add(prefix.relative_to("/tmp").parts[0])
    assert set(words[3:]) == expected, done.tail


@pytest.mark.skipif(os.geteuid() != 0, reason="needs root to start it as an ordinary user")
def test_an_ordinary_user_gets_the_sandbox_from_a_user_namespace(tmp_path):
    """The grader run by an ordinary user: bwrap's user namespace, the same isolation."""

    class AsUser(jail.Sandbox):
        as_root = False

    import tempfile

    etc = Path(tempfile.mkdtemp(prefix="grade-etc-"))  # not pytest's: that one is 0700
    try:
        etc.chmod(0o755)
        jail.write_etc(etc, 65534)
        box = AsUser(jail.Limits(seconds=30), etc, python=False)
        done = _as_nobody(box)
    finally:
        shutil.rmtree(etc)
    if "No permissions to create new namespace" in done.stderr or (
            "Operation not permitted" in done.stderr):
        pytest.skip(f"unprivileged user namespaces are off here: {done.stderr.strip()}")
    lines = done.stdout.split("\n")
    assert done.returncode == 0, done.stderr
    assert lines[0] == "65534" and "No such file" in lines[1]  # no /work, no /root
    # nobody inside; outside, the user who started it (an unprivileged user can map no
    # other uid: the kernel's rule)
    assert lines[2].split()[0] == "65534"
    assert int(lines[3]) <= 4  # its own processes only: bwrap's init, sh, ls, grep


def _as_nobody(box):
    cmd = box.command(["/bin/sh", "-c", "id -u; ls /work /root 2>&1 | head -1; "
                       "cat /proc/self/uid_map; ls /proc | grep -c '^[0-9]'"])
    assert "setpriv" not in cmd and "--unshare-user" in cmd
    return subprocess.run(["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups",
                           *cmd], capture_output=True, text=True, check=False, timeout=60)
