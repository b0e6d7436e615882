"""One list of formula modules (wheelkin._registry).

Every tool that walks the library reads ``FORMULA_MODULES``; here the list is checked against
the source tree (no module left out, none that does not exist), against mypy's file list in
pyproject.toml, against the layers, and against the mutation tool's mutants.
"""

from __future__ import annotations

import importlib
import tomllib
from pathlib import Path

import wheelkin
from wheelkin import _registry

ROOT = Path(__file__).resolve().parents[2]
SRC = Path(wheelkin.__file__).resolve().parent


def top_level_modules(src: Path = SRC) -> set[str]:
    """The modules and packages directly under ``src`` (``__init__`` aside)."""
    names = {p.stem for p in src.glob("*.py") if p.stem != "__init__"}
    names |= {p.parent.name for p in src.glob("*/__init__.py")}
    return names


def test_the_layers_place_every_module_once():
    placed = [m for _, modules in _registry.LAYERS for m in modules]
    assert len(placed) == len(set(placed)), "a module is in two layers"
    missing = top_level_modules() - set(placed)
    assert not missing, (f"modules in no layer (add them to wheelkin._registry: a formula "
                         f"module to FORMULA_MODULES): {sorted(missing)}")


def test_the_formula_list_names_modules_that_exist():
    present = top_level_modules()
    for name in (*_registry.FORMULA_MODULES, *_registry.SUPPORT_MODULES):
        assert name in present, name
        importlib.import_module(f"wheelkin.{name}")


def test_mypy_checks_exactly_the_listed_modules():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    files = config["tool"]["mypy"]["files"]
    assert sorted(files) == [f"src/wheelkin/{m}.py" for m in _registry.TYPED_MODULES]


def test_the_mutation_tool_covers_every_formula_module_with_live_texts():
    from tools import mutation

    assert mutation.uncovered() == []
    assert mutation.stale(mutation.MUTANTS) == []
    for _, tests, _, _, _ in mutation.MUTANTS:
        assert mutation.test_files(tests)  # each named test file exists, once
