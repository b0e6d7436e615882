"""Layers of tests that run only when asked for (tests/kit, tests/pdf: ``make kit``,
``make pdf``), never as part of a run over the other layers' folders."""

from __future__ import annotations

from pathlib import Path


def ignored_unless_asked(folder: Path, collection_path: Path, config) -> bool | None:
    """``pytest_ignore_collect`` for the conftest of ``folder``: True (leave it out) for
    ``folder`` and everything in it, unless pytest was pointed at ``folder`` or at something in
    it; None (pytest decides) otherwise."""
    asked = [Path(str(a).split("::")[0]).resolve() for a in config.args]
    if any(a == folder or folder in a.parents for a in asked):
        return None
    path = collection_path.resolve()
    if path == folder or folder in path.parents:
        return True
    return None
