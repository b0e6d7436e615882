"""Which pages and chapters the book has, derived from ``_toc.yml`` and ``notebooks/``.

Shared by the tests (notebook checks, exercise checks, browser tests), so that none of them
hard-codes the list of chapters.
"""

from __future__ import annotations

from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"

#: Notebooks that are not chapters (they need not follow the chapter anatomy, e.g. the three
#: exercises), by file stem, with the reason. Every other notebooks/NN_*.ipynb is a chapter.
NON_CHAPTER_NOTEBOOKS: dict[str, str] = {
    "02_sandbox": "the sandbox gallery: a tour of the physics sandbox, not a chapter",
}


def toc_files(toc: Path = ROOT / "_toc.yml") -> list[str]:
    """Every page of the book, in reading order, as paths without suffix (``book/intro``)."""
    data = yaml.safe_load(toc.read_text(encoding="utf-8")) or {}
    pages: list[str] = []

    def strip(name: str) -> str:
        for suffix in (".md", ".ipynb", ".rst"):
            if name.endswith(suffix):
                return name[: -len(suffix)]
        return name

    def walk(node) -> None:
        if isinstance(node, list):
            for item in node:
                walk(item)
        elif isinstance(node, dict):
            if isinstance(node.get("file"), str):
                pages.append(strip(node["file"]))
            for key in ("parts", "chapters", "sections"):
                walk(node.get(key))

    if isinstance(data.get("root"), str):
        pages.append(strip(data["root"]))
    walk({k: v for k, v in data.items() if k != "root"})
    return pages


def notebooks() -> list[Path]:
    """Every numbered notebook present, in order (``notebooks/NN_name.ipynb``)."""
    return sorted(NOTEBOOKS.glob("[0-9][0-9]_*.ipynb"))


def chapter_notebooks() -> list[Path]:
    """The notebooks that are chapters (all but :data:`NON_CHAPTER_NOTEBOOKS`)."""
    return [p for p in notebooks() if p.stem not in NON_CHAPTER_NOTEBOOKS]
