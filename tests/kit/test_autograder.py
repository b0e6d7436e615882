"""Gradescope's autograder (``make autograder ASSIGNMENT=...``): the zip has Gradescope's
layout, and its ``run_autograder``, run in a folder laid out as Gradescope lays out
``/autograder`` (source/ unzipped, submission/, results/), grades the submission with the
sandboxes and writes results.json: hidden cases' verdicts shown after the due date, the
score capped, a clear line when there is nothing to grade."""

from __future__ import annotations

import json
import os
import shutil
import stat
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
ASSIGNMENT = HERE / "assignments" / "conventions.toml"


@pytest.fixture(scope="module")
def autograder_zip(tmp_path_factory):
    out = tmp_path_factory.mktemp("autograder")
    done = subprocess.run(["make", "--no-print-directory", "autograder",
                           f"ASSIGNMENT={ASSIGNMENT}"], capture_output=True, text=True,
                          cwd=ROOT, check=False)
    assert done.returncode == 0, done.stdout + done.stderr
    built = ROOT / "_build" / "autograder" / "conventions.zip"
    target = out / "conventions.zip"
    shutil.copy(built, target)
    return target


def test_the_zip_has_gradescopes_layout(autograder_zip):
    with zipfile.ZipFile(autograder_zip) as archive:
        names = set(archive.namelist())
        modes = {info.filename: info.external_attr >> 16 for info in archive.infolist()}
        setup = archive.read("setup.sh").decode()
        requirements = archive.read("requirements.txt").decode().splitlines()
    assert {"setup.sh", "run_autograder", "assignment.toml", "requirements.txt",
            "tools/__init__.py", "tools/grade.py", "tools/grading/__init__.py",
            "tools/grading/jail.py", "src/wheelkin/__init__.py"} <= names
    assert modes["run_autograder"] & stat.S_IXUSR and modes["setup.sh"] & stat.S_IXUSR
    assert not any("__pycache__" in n or n.startswith(("tests/", "notebooks/")) for n in names)
    assert "bubblewrap" in setup and "/autograder/venv" in setup
    pins = dict(line.split("==") for line in requirements if "==" in line)
    ours = dict(line.split("==") for line in (ROOT / "requirements.txt").read_text().splitlines()
                if "==" in line)
    assert {"numpy", "ipython", "nbformat", "pymunk", "matplotlib"} <= set(pins)
    for name, version in pins.items():  # pinned as the book pins them
        assert ours.get(name, version) == version, name
    bash = shutil.which("bash")
    for script in ("setup.sh", "run_autograder"):
        with zipfile.ZipFile(autograder_zip) as archive:
            text = archive.read(script)
        assert subprocess.run([bash, "-n"], input=text, check=False).returncode == 0, script


def run_autograder(autograder_zip: Path, root: Path, files: dict[str, bytes]) -> dict:
    """Lay out ``root`` as Gradescope's /autograder with ``files`` submitted; run it."""
    source = root / "source"
    with zipfile.ZipFile(autograder_zip) as archive:
        archive.extractall(source)
    shutil.copy(source / "run_autograder", root / "run_autograder")
    (root / "run_autograder").chmod(0o755)
    (root / "submission").mkdir()
    (root / "results").mkdir()
    for name, data in files.items():
        path = root / "submission" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)
    env = {"PATH": os.environ["PATH"], "AUTOGRADER_ROOT": str(root),
           "AUTOGRADER_PYTHON": sys.executable, "HOME": str(root)}
    done = subprocess.run([str(root / "run_autograder")], cwd=root, env=env,
                          capture_output=True, text=True, timeout=900, check=False)
    print(done.stdout, done.stderr)
    assert done.returncode == 0
    return json.loads((root / "results" / "results.json").read_text(encoding="utf-8"))


def notebook(name: str) -> bytes:
    for folder in ("submissions", "redteam"):
        path = HERE / folder / f"{name}.ipynb"
        if path.exists():
            return path.read_bytes()
    raise FileNotFoundError(name)


def test_a_correct_submission_gets_every_point(autograder_zip, tmp_path):
    results = run_autograder(autograder_zip, tmp_path, {"my answers.ipynb": notebook("correct")})
    assert results["score"] == 5
    hidden = [t for t in results["tests"] if t["visibility"] == "after_due_date"]
    shown = [t for t in results["tests"] if t["visibility"] == "visible"]
    assert [t["max_score"] for t in hidden] == [1, 2, 1, 1]
    assert all(t["max_score"] == 0 and t["output"].startswith("✔") for t in shown)
    assert all("hidden cases" in t["output"] for t in hidden)


def test_a_memorised_answer_passes_the_visible_test_and_fails_the_hidden_one(autograder_zip,
                                                                             tmp_path):
    results = run_autograder(autograder_zip, tmp_path, {"nb/wrong.ipynb": notebook("wrong"),
                                                        "notes.txt": b"my notes"})
    icr = {t["visibility"]: t for t in results["tests"] if t["name"].startswith(
        "conventions.icr")}
    assert icr["visible"]["output"].startswith("✔")
    assert icr["after_due_date"]["score"] == 0 and "hidden case" in icr["after_due_date"][
        "output"]
    assert results["score"] == 1


def test_the_score_never_exceeds_the_assignment(autograder_zip, tmp_path):
    results = run_autograder(autograder_zip, tmp_path,
                             {"extra.ipynb": notebook("extra_exercises")})
    assert results["score"] == 4 <= sum(t["max_score"] for t in results["tests"])
    assert len(results["tests"]) == 8  # the assignment's four exercises, nothing added


@pytest.mark.parametrize(("files", "words"), [
    ({}, "no notebook"),
    ({"a.ipynb": b"{}", "b.ipynb": b"{}"}, "several notebooks"),
    ({"a.ipynb": b"not json"}, "not a notebook"),
])
def test_nothing_to_grade_gets_a_clear_line(autograder_zip, tmp_path, files, words):
    results = run_autograder(autograder_zip, tmp_path, files)
    assert results["score"] == 0 and words in results["output"]
    assert len(results["tests"]) == 8
