"""The one registry loader: import a package's chapter modules so that they register.

:mod:`wheelkin.exercises` and :mod:`wheelkin.widgets` each keep a registry that a chapter's
module fills when it is imported; both call :func:`load_chapter_modules` before a lookup.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable

__all__ = ["load_chapter_modules"]


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
