"""Which pages, notebooks and chapters the book has, derived from ``_toc.yml`` and ``notebooks/``.

Shared by the tools and tests (execution, notebook checks, exercise checks, errata, browser
tests), so that none of them hard-codes the list of chapters. Two layouts live side by side
(docs/DESIGN.md, "Chapter anatomy"):

- first edition: a chapter is one notebook, ``notebooks/03_rover.ipynb``;
- second edition: a chapter is a folder, ``notebooks/03_rover/index.md`` (the landing page)
  with section notebooks ``notebooks/03_rover/01_geometry.ipynb`` ..., listed in ``_toc.yml``
  as ``sections:`` (nested to any depth) under the landing page.

>>> chapter_of(Path("notebooks/03_rover/01_geometry.ipynb"))
'03_rover'
>>> chapter_of(Path("notebooks/03_rover.ipynb"))
'03_rover'
>>> notebook_id(NOTEBOOKS / "03_rover" / "01_geometry.ipynb")
'03_rover/01_geometry'
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
TOC = ROOT / "_toc.yml"

#: Chapters that are not chapters of the anatomy (no exercises needed), by chapter name (the
#: notebook's stem or the chapter folder's name), with the reason.
NON_CHAPTER_NOTEBOOKS: dict[str, str] = {
    "02_sandbox": "the sandbox gallery: a tour of the physics sandbox, not a chapter",
}

_NUMBERED = re.compile(r"^\d\d_")


def _strip(name: str) -> str:
    for suffix in (".md", ".ipynb", ".rst"):
        if name.endswith(suffix):
            return name[: -len(suffix)]
    return name


def toc_files(toc: Path = TOC) -> list[str]:
    """Every page of the book, in reading order, as paths without suffix (``book/intro``).

    Parts, chapters and ``sections:`` at any depth are walked in order; a page is listed before
    its sections.
    """
    data = yaml.safe_load(toc.read_text(encoding="utf-8")) or {}
    pages: list[str] = []

    def walk(node) -> None:
        if isinstance(node, list):
            for item in node:
                walk(item)
        elif isinstance(node, dict):
            if isinstance(node.get("file"), str):
                pages.append(_strip(node["file"]))
            for key in ("parts", "chapters", "sections"):
                walk(node.get(key))

    if isinstance(data.get("root"), str):
        pages.append(_strip(data["root"]))
    walk({k: v for k, v in data.items() if k != "root"})
    return pages


@dataclass(frozen=True)
class Division:
    """One top-level division of the book, as both editions number it.

    ``matter`` is ``"front"`` (the root page and the chapters of the unnumbered parts before
    the first numbered part: preface, how to use, notation), ``"main"`` (the chapters of the
    parts marked ``numbered: true``, numbered 1, 2, ... across parts) or ``"back"`` (the
    chapters of the unnumbered parts after the first numbered one: the appendices, lettered
    A, B, ...). ``pages`` is the division's page and its ``sections:``, in reading order.
    """

    page: str
    matter: str
    number: str | None
    part: str | None
    pages: tuple[str, ...]
    #: (page, the page it is listed under) for every page but the division's own.
    parents: tuple[tuple[str, str], ...] = ()

    def level(self, page: str) -> int:
        """1 for the division's page, 2 for a page listed under it, and so on."""
        parents = dict(self.parents)
        level = 1
        while page in parents:
            level, page = level + 1, parents[page]
        return level

    def has_pages(self, page: str) -> bool:
        """Whether pages are listed under ``page`` (a chapter's landing page, an index)."""
        return any(parent == page for _, parent in self.parents)

    @property
    def label(self) -> str:
        """How the text names it: "Chapter 6", "Appendix A", or "" (front matter)."""
        if self.number is None:
            return ""
        return ("Chapter " if self.matter == "main" else "Appendix ") + self.number


def _letters(index: int) -> str:
    """A, B, ..., Z, AA, AB, ... for 0, 1, ..."""
    out = ""
    index += 1
    while index:
        index, rest = divmod(index - 1, 26)
        out = chr(ord("A") + rest) + out
    return out


def book_structure(toc: Path = TOC) -> list[Division]:
    """The book's divisions in reading order, numbered as both editions number them.

    Derived from the toc's parts alone, so a new chapter or back-matter page needs nothing
    else: a part marked ``numbered: true`` holds chapters; the unnumbered parts before the
    first numbered part are front matter, those after it back matter (appendices).

    >>> [(d.page, d.matter, d.number) for d in book_structure()][:4]  # doctest: +ELLIPSIS
    [('book/intro', 'front', None), ('book/how_to_use', 'front', None), ...]
    """
    data = yaml.safe_load(Path(toc).read_text(encoding="utf-8")) or {}

    def pages_of(entry) -> tuple[tuple[str, ...], tuple[tuple[str, str], ...]]:
        found: list[str] = []
        parents: list[tuple[str, str]] = []

        def walk(node, parent: str | None) -> None:
            if isinstance(node, list):
                for item in node:
                    walk(item, parent)
            elif isinstance(node, dict):
                page = parent
                if isinstance(node.get("file"), str):
                    page = _strip(node["file"])
                    found.append(page)
                    if parent is not None:
                        parents.append((page, parent))
                walk(node.get("sections"), page)

        walk(entry, None)
        return tuple(found), tuple(parents)

    out: list[Division] = []
    if isinstance(data.get("root"), str):
        root = _strip(data["root"])
        out.append(Division(root, "front", None, None, (root,)))
    parts = data.get("parts") or [{"chapters": data.get("chapters") or [],
                                   "numbered": True}]
    seen_numbered = False
    chapter = appendix = 0
    for part in parts:
        numbered = bool(part.get("numbered"))
        seen_numbered = seen_numbered or numbered
        for entry in part.get("chapters") or []:
            if not isinstance(entry.get("file"), str):
                continue
            if numbered:
                chapter += 1
                matter, number = "main", str(chapter)
            elif seen_numbered:
                matter, number = "back", _letters(appendix)
                appendix += 1
            else:
                matter, number = "front", None
            out.append(Division(_strip(entry["file"]), matter, number, part.get("caption"),
                                *pages_of(entry)))
    return out


def page_title(page: str, root: Path = ROOT) -> str | None:
    """A page's title as both editions show it: its first level-one heading (a markdown file,
    or a notebook's markdown cells), None when it has none."""
    from tools.book_text import page_markdown  # book_text builds on this module

    for suffix in (".md", ".ipynb"):
        path = root / f"{page}{suffix}"
        if not path.is_file():
            continue
        for text in page_markdown(path):
            found = re.search(r"^#[ \t]+(.+?)[ \t]*$", text, re.M)
            if found:
                return found.group(1)
        return None
    return None


def toc_notebooks(toc: Path = TOC, root: Path = ROOT) -> list[Path]:
    """The notebooks the toc lists, in reading order (pages with an ``.ipynb`` file)."""
    return [root / f"{page}.ipynb" for page in toc_files(toc)
            if (root / f"{page}.ipynb").is_file()]


def notebooks(folder: Path = NOTEBOOKS) -> list[Path]:
    """Every numbered notebook present, in path order, in both layouts.

    ``notebooks/NN_name.ipynb`` and ``notebooks/NN_name/MM_topic.ipynb`` (any depth below a
    numbered folder); checkpoints and unnumbered scratch files are not notebooks of the book.
    """
    found = []
    for path in folder.rglob("*.ipynb"):
        parts = path.relative_to(folder).parts
        if any(p.startswith(".") for p in parts):
            continue
        if all(_NUMBERED.match(p) for p in parts):
            found.append(path)
    return sorted(found)


def notebook_id(path: Path, folder: Path = NOTEBOOKS) -> str:
    """A notebook's name in the book: its path below ``notebooks/`` without the suffix.

    Unique across the book (two chapters may both have ``01_geometry.ipynb``), the same on
    every machine; ids derived from it (widgets, animation players) are unique too. For a
    notebook outside ``notebooks/`` it is the file's stem.
    """
    path = Path(path).resolve()
    try:
        return path.relative_to(folder.resolve()).with_suffix("").as_posix()
    except ValueError:
        return path.stem


def chapter_of(path: Path) -> str:
    """The chapter a notebook belongs to: the numbered folder below ``notebooks/``, or the
    notebook's own stem in the first-edition layout."""
    path = Path(path)
    parts = list(path.with_suffix("").parts)
    if "notebooks" in parts:
        parts = parts[len(parts) - parts[::-1].index("notebooks"):]
    return parts[0] if parts else path.stem


def chapters(folder: Path = NOTEBOOKS) -> dict[str, list[Path]]:
    """Every chapter present, by name, with its notebooks in order."""
    out: dict[str, list[Path]] = {}
    for path in notebooks(folder):
        out.setdefault(chapter_of(path), []).append(path)
    return out


def chapter_notebooks() -> list[Path]:
    """The notebooks of chapters (all but those of :data:`NON_CHAPTER_NOTEBOOKS`)."""
    return [p for p in notebooks() if chapter_of(p) not in NON_CHAPTER_NOTEBOOKS]


if __name__ == "__main__":  # `python -m tools.book_pages [--notebooks]`: for the Makefile
    import sys

    if "--notebooks" in sys.argv[1:]:
        print("\n".join(p.relative_to(ROOT).as_posix() for p in toc_notebooks()))
    else:
        print("\n".join(toc_files()))
