"""The errata page is an index of the chapters' erratum boxes: one line per box, and back.

A chapter tells each erratum once, in a box under a label line ``(erratum-<source>-<slug>)=``
(in a markdown cell of a notebook, or a chapter's landing page). ``book/errata/<source>.md``
lists it in one short line, ``- {ref}`short title <erratum-<source>-<slug>>` ``, and retells
nothing; ``book/errata.md`` includes every ``book/errata/*.md``. Here: every label is defined
once and has exactly one index line, in its source's file; every index line links to a label
that exists; lines are short and carry their own link text. ``tools/errata_index.py`` writes
the lists from the boxes.
"""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import nbformat

from tools.book_pages import NOTEBOOKS, notebook_id, notebooks

ROOT = Path(__file__).resolve().parents[2]

ERRATA_PAGE = ROOT / "book" / "errata.md"
ERRATA_DIR = ROOT / "book" / "errata"
LABEL = re.compile(r"^\((erratum-[\w-]+)\)=\s*$", re.MULTILINE)
#: {ref}`erratum-x` or {ref}`text <erratum-x>`
REF = re.compile(r"\{ref\}`(?:([^`<]*?)\s*<)?(erratum-[\w-]+)>?`")
INCLUDE = re.compile(r"^[`:]{3,}\s*\{include\}\s+(\S+)\s*$", re.MULTILINE)
#: An index line: a list item that is one link, with nothing retold around it.
INDEX_LINE = re.compile(r"^- \{ref\}`([^`<]+?) <(erratum-[\w-]+)>`\s*$")
MAX_TITLE_CHARS = 90
MAX_LINE_CHARS = 140


def _labels() -> dict[str, list[str]]:
    """Every erratum label in the chapters, with every place that defines it."""
    found: dict[str, list[str]] = {}
    for path in notebooks():
        for cell in nbformat.read(path, as_version=4).cells:
            if cell.cell_type == "markdown":
                for label in LABEL.findall(cell.source):
                    found.setdefault(label, []).append(notebook_id(path))
    for page in sorted(NOTEBOOKS.rglob("*.md")):
        for label in LABEL.findall(page.read_text(encoding="utf-8")):
            found.setdefault(label, []).append(page.relative_to(ROOT).as_posix())
    return found


def _index_lines() -> list[tuple[str, int, str]]:
    """(file, line number, line) of every line of book/errata/*.md that links an erratum."""
    out = []
    for path in sorted(ERRATA_DIR.glob("*.md")):
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if REF.search(line):
                out.append((path.name, number, line))
    return out


def test_every_erratum_is_defined_once():
    twice = {label: where for label, where in _labels().items() if len(where) > 1}
    assert not twice, "erratum labels defined more than once (tell it once): " + "; ".join(
        f"{label} in {', '.join(where)}" for label, where in twice.items())


def test_every_erratum_box_has_exactly_one_index_line():
    counts = Counter(label for _, _, line in _index_lines() for _, label in REF.findall(line))
    missing = [f"{label} (in {where[0]})" for label, where in _labels().items()
               if counts[label] == 0]
    repeated = [f"{label} ({counts[label]} lines)" for label in _labels() if counts[label] > 1]
    assert not missing, ("erratum boxes with no line in book/errata/<source>.md (run "
                         "`.venv/bin/python -m tools.errata_index`): " + ", ".join(missing))
    assert not repeated, "errata listed more than once in the index: " + ", ".join(repeated)


def test_every_index_line_links_to_a_box():
    labels = _labels()
    dangling = [f"{f}:{n}: {label}" for f, n, line in _index_lines()
                for _, label in REF.findall(line) if label not in labels]
    assert not dangling, "index lines link to labels no chapter defines: " + ", ".join(dangling)


def test_index_lines_are_one_short_link_each():
    """One list item, one {ref} with its own short text, nothing retold."""
    bad = []
    for name, number, line in _index_lines():
        match = INDEX_LINE.match(line)
        if not match:
            bad.append(f"{name}:{number}: not a bare index line: {line[:100]}")
        elif len(match.group(1)) > MAX_TITLE_CHARS or len(line) > MAX_LINE_CHARS:
            bad.append(f"{name}:{number}: too long ({len(line)} characters): {line[:100]}")
    assert not bad, ("write each erratum as `- {ref}`short title <erratum-...>``:\n"
                     + "\n".join(bad))


def test_index_lines_are_filed_under_their_source():
    wrong = [f"{name}:{number}: {label}" for name, number, line in _index_lines()
             for _, label in REF.findall(line) if label.split("-")[1] != Path(name).stem]
    assert not wrong, "index lines in another source's file: " + ", ".join(wrong)


def test_errata_page_includes_every_source_file():
    assert ERRATA_PAGE.is_file(), "book/errata.md is missing"
    text = ERRATA_PAGE.read_text(encoding="utf-8")
    included = {Path(p).name for p in INCLUDE.findall(text) if Path(p).parent.name == "errata"}
    files = {p.name for p in ERRATA_DIR.glob("*.md")}
    missing = sorted(files - included)
    assert not missing, f"book/errata.md does not include {missing} (use an {{include}} directive)"
    unknown = sorted(included - files)
    assert not unknown, f"book/errata.md includes files that do not exist: {unknown}"
    assert not REF.search(text), "book/errata.md itself lists errata: list them in book/errata/"
