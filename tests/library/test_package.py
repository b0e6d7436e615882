"""wheelkin as a robot builder installs it: a wheel, a fresh virtual environment, numpy only.

Builds the wheel (``pip wheel --no-deps``, with this environment's setuptools so that nothing
is downloaded for the build), installs it into a new virtual environment together with its
runtime dependencies only, and checks there that

- nothing but wheelkin and numpy was installed;
- every formula module (``wheelkin._registry.FORMULA_MODULES``, the one list) imports, and
  none of them pulls in matplotlib, pymunk, ipywidgets, sympy or scipy;
- the package ships ``py.typed``;
- the formula modules' doctests pass (pytest is added to the environment for this last step,
  after the import check).

numpy (and pytest) come from the same package index this environment uses.
"""

from __future__ import annotations

import os
import subprocess
import sys
import venv
from pathlib import Path

import pytest

from wheelkin._registry import FORMULA_MODULES, SUPPORT_MODULES

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("matplotlib", "pymunk", "ipywidgets", "sympy", "scipy", "IPython")

pytestmark = pytest.mark.package


def _run(*args: str | Path, cwd: Path | None = None, timeout: float = 120.0) -> str:
    env = {k: val for k, val in os.environ.items() if not k.startswith(("PYTHON", "VIRTUAL"))}
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    proc = subprocess.run([str(a) for a in args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=timeout, check=False)
    assert proc.returncode == 0, f"{args} failed:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    return proc.stdout


_WHEEL: list[Path] = []


@pytest.fixture(scope="module")
def installed(tmp_path_factory) -> Path:
    """The python of a fresh venv holding the wheelkin wheel and its runtime dependencies."""
    tmp = tmp_path_factory.mktemp("package")
    wheels = tmp / "wheels"
    _run(sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
         "-w", wheels, ROOT)
    (wheel,) = wheels.glob("wheelkin-*.whl")
    _WHEEL.append(wheel)
    env_dir = tmp / "venv"
    venv.EnvBuilder(with_pip=True, clear=True).create(env_dir)
    python = env_dir / "bin" / "python"
    try:
        _run(python, "-m", "pip", "install", "-q", wheel, timeout=240.0)
    except AssertionError as exc:  # no package index reachable: say so, do not pass
        if "No matching distribution" in str(exc) or "connection" in str(exc).lower():
            pytest.skip(f"no package index to install numpy from: {exc}")
        raise
    return python


def test_only_numpy_is_installed_beside_wheelkin(installed):
    import json

    listed = json.loads(_run(installed, "-m", "pip", "list", "--format=json"))
    names = {item["name"].lower() for item in listed}
    assert names - {"pip", "setuptools", "wheel"} == {"wheelkin", "numpy"}


def test_formula_modules_import_with_numpy_alone_and_ship_py_typed(installed, tmp_path):
    code = (
        "import importlib, sys, pathlib\n"
        f"for name in {FORMULA_MODULES!r}:\n"
        "    importlib.import_module('wheelkin.' + name)\n"
        f"heavy = sorted(m for m in {HEAVY!r} if m in sys.modules)\n"
        "assert not heavy, heavy\n"
        "import wheelkin\n"
        "root = pathlib.Path(wheelkin.__file__).parent\n"
        "assert (root / 'py.typed').is_file()\n"
        "assert 'site-packages' in str(root), root\n"
        "print('ok')\n"
    )
    assert _run(installed, "-c", code, cwd=tmp_path).strip() == "ok"


def test_a_module_that_needs_an_extra_says_which(installed, tmp_path):
    code = (
        "for name, extra in (('sandbox', '[sandbox]'), ('widgets', '[notebook]'),\n"
        "                    ('animation', '[plot]')):\n"
        "    try:\n"
        "        __import__('wheelkin.' + name)\n"
        "    except ModuleNotFoundError as exc:\n"
        "        assert extra in str(exc), (name, str(exc))\n"
        "    else:\n"
        "        raise AssertionError(name + ' imported without its extra')\n"
        "print('ok')\n"
    )
    assert _run(installed, "-c", code, cwd=tmp_path).strip() == "ok"


def test_formula_modules_doctests_pass_in_the_installed_package(installed, tmp_path):
    _run(installed, "-m", "pip", "install", "-q", "pytest", timeout=240.0)
    out = _run(installed, "-m", "pytest", "-q", "-p", "no:cacheprovider", "--doctest-modules",
               "-o", "doctest_optionflags=NORMALIZE_WHITESPACE NUMBER ELLIPSIS",
               "-o", "addopts=", "-W", "error",
               "--pyargs",
               *(f"wheelkin.{name}" for name in (*SUPPORT_MODULES, *FORMULA_MODULES)),
               cwd=tmp_path, timeout=240.0)
    assert " passed" in out and "failed" not in out and "deselected" not in out


def test_the_wheel_ships_the_licence_and_the_library_readme(installed):
    import zipfile

    (wheel,) = _WHEEL
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
        licences = [n for n in names if n.endswith(".dist-info/LICENSE")
                    or "/licenses/LICENSE" in n]
        assert licences, f"no LICENSE in the wheel: {names}"
        assert archive.read(licences[0]) == (ROOT / "LICENSE").read_bytes()
        (metadata,) = [n for n in names if n.endswith(".dist-info/METADATA")]
        text = archive.read(metadata).decode()
    # the package's own description (docs/PYPI.md), not the book's README
    assert "Objects a control loop holds" in text
    assert (ROOT / "docs" / "PYPI.md").read_text().splitlines()[0] in text
    assert "jupyter-book" not in text.lower()
