"""The errata page and the chapters agree.

A chapter states each erratum in a markdown cell that starts with a label line
``(erratum-<source>-<slug>)=``; ``book/errata/<source>.md`` lists it with a ``{ref}`` link to
that label, and ``book/errata.md`` includes every ``book/errata/*.md``. Here: every label is
listed, every listed ref points to a label that exists, and every errata file is included.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
from book_pages import notebooks  # noqa: E402

ERRATA_PAGE = ROOT / "book" / "errata.md"
ERRATA_DIR = ROOT / "book" / "errata"
LABEL = re.compile(r"^\((erratum-[\w-]+)\)=\s*$", re.MULTILINE)
#: {ref}`erratum-x` or {ref}`text <erratum-x>`
REF = re.compile(r"\{ref\}`(?:([^`<]*?)\s*<)?(erratum-[\w-]+)>?`")
INCLUDE = re.compile(r"^[`:]{3,}\s*\{include\}\s+(\S+)\s*$", re.MULTILINE)


def _labels() -> dict[str, str]:
    """Every erratum label in a notebook's markdown, with the notebook that defines it."""
    found: dict[str, str] = {}
    for path in notebooks():
        for cell in nbformat.read(path, as_version=4).cells:
            if cell.cell_type != "markdown":
                continue
            for label in LABEL.findall(cell.source):
                assert label not in found, f"{label} is defined in {found[label]} and {path.name}"
                found[label] = path.name
    return found


def _refs() -> dict[str, list[tuple[str, str]]]:
    """Every erratum ref in book/errata/*.md: label -> [(file, link text), ...]."""
    refs: dict[str, list[tuple[str, str]]] = {}
    for path in sorted(ERRATA_DIR.glob("*.md")):
        for text, label in REF.findall(path.read_text(encoding="utf-8")):
            refs.setdefault(label, []).append((path.name, text))
    return refs


def test_every_erratum_label_is_listed_on_the_errata_page():
    labels, refs = _labels(), _refs()
    missing = [f"{label} (in {nb})" for label, nb in labels.items() if label not in refs]
    assert not missing, ("errata stated in a chapter but not listed in book/errata/<source>.md "
                         "with a {ref}: " + ", ".join(missing))


def test_every_listed_erratum_exists_in_a_chapter():
    labels, refs = _labels(), _refs()
    dangling = [f"{label} (from {', '.join(f for f, _ in where)})"
                for label, where in refs.items() if label not in labels]
    assert not dangling, "book/errata/ refers to labels no notebook defines: " + ", ".join(dangling)


def test_erratum_refs_carry_their_own_text():
    """A label before an admonition has no title, so {ref} needs explicit text."""
    bare = [f"{f}: {label}" for label, where in _refs().items() for f, text in where if not text]
    assert not bare, ("write {ref}`short title <erratum-...>`, not {ref}`erratum-...`: "
                      + ", ".join(bare))


def test_errata_page_includes_every_source_file():
    assert ERRATA_PAGE.is_file(), "book/errata.md is missing"
    included = {Path(p).name for p in INCLUDE.findall(ERRATA_PAGE.read_text(encoding="utf-8"))
                if Path(p).parent.name == "errata"}
    files = {p.name for p in ERRATA_DIR.glob("*.md")}
    missing = sorted(files - included)
    assert not missing, f"book/errata.md does not include {missing} (use an {{include}} directive)"
    unknown = sorted(included - files)
    assert not unknown, f"book/errata.md includes files that do not exist: {unknown}"
