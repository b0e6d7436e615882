"""The one list of wheelkin's modules by layer, and the one registry loader.

:data:`FORMULA_MODULES` is the list every tool that walks the library reads: the package
test (each imports with numpy alone), the bad-input sweep, the return-type walk, the typing
test, the mutation tool (each module has mutants), and mypy's file list in pyproject.toml (a
test keeps that equal to :data:`TYPED_MODULES`). A new formula module is added here, once.

:data:`LAYERS` orders the house from the bottom up; a module may import from its own layer
and the layers below it, never from a layer above (``tests/library/test_layers.py`` checks it
from the source, and that no import circle exists).

:mod:`wheelkin.exercises` and :mod:`wheelkin.widgets` each keep a registry that a chapter's
module fills when it is imported; both call :func:`load_chapter_modules` before a lookup.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable

__all__ = ["FORMULA_MODULES", "LAYERS", "SUPPORT_MODULES", "TYPED_MODULES",
           "load_chapter_modules"]

#: The public formula modules (numpy only), in the order the book meets them.
FORMULA_MODULES: tuple[str, ...] = (
    "units", "frames", "sources", "rover", "mecanum", "diffdrive", "odometry",
    "odometry_uncertainty", "motion_models", "odometry_fusion", "waypoints", "follower",
    "unified", "carlike", "nonholonomic", "control", "kinematics", "odometers",
)

#: The private modules the formula modules are built on (numpy only, type-checked too).
SUPPORT_MODULES: tuple[str, ...] = ("_kernels", "_records", "_registry", "_validate")

#: The modules mypy checks (``[tool.mypy] files`` in pyproject.toml lists exactly these): the
#: formula modules and their support, and the display helpers every notebook imports.
TYPED_MODULES: tuple[str, ...] = tuple(sorted((*SUPPORT_MODULES, *FORMULA_MODULES, "display")))

#: The layers, bottom first: (name, top-level modules or packages of ``wheelkin``). The figure
#: style sits under the sandbox, whose renderer draws in it; it imports no wheelkin module.
LAYERS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("formula", (*SUPPORT_MODULES, *FORMULA_MODULES)),
    ("style", ("style",)),
    ("sandbox", ("sandbox",)),
    ("book", ("animation", "display", "symbolic", "widgets", "exercises")),
)


def load_chapter_modules(package: str, modules: Iterable[str]) -> None:
    """Import ``package.<name>`` for every name in ``modules``; a module that does not exist is
    skipped (a chapter without exercises or panels), any other import error propagates."""
    for mod in modules:
        name = f"{package}.{mod}"
        try:
            importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name != name:
                raise
