"""The built PDF as the tests of the printed edition read it (tests/pdf): its pages' text,
their printed numbers (page labels) and its outline."""

from __future__ import annotations

import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@dataclass(frozen=True)
class Entry:
    """One entry of the PDF's outline (bookmarks)."""

    level: int
    title: str
    page: int  # 0-based index of the page it opens on


@dataclass
class Printed:
    """The PDF as a reader meets it: its pages' text (in the order it was typeset, which keeps
    a line whole around a formula), their printed numbers, its outline."""

    path: Path
    pages: list[str]
    labels: list[str]
    outline: list[Entry]

    def text_in_reading_order(self, first: int, last: int) -> str:
        """Pages ``first`` to ``last`` (0-based, inclusive) column by column (an index)."""
        done = subprocess.run(["pdftotext", "-f", str(first + 1), "-l", str(last + 1),
                               str(self.path), "-"], capture_output=True, text=True, check=True)
        return done.stdout.replace("\u2019", "'")

    def body(self, index: int) -> str:
        """Page ``index``'s text without its running head and foot (the book's title; a line
        that starts or ends with the page's number)."""
        lines = self.pages[index].strip("\n").split("\n")
        label = re.escape(self.labels[index])
        while lines and (lines[0].strip() == "wheelkin: kinematics of wheeled mobile robots"
                         or re.match(rf"^{label}\s|.*\s{label}$", lines[0].strip())):
            lines = lines[1:]
        while lines and re.match(rf"^{label}(\s|$)|.*\s{label}$", lines[-1].strip()):
            lines = lines[:-1]
        return "\n".join(lines)

    def page_of_label(self, label: str) -> int:
        return self.labels.index(label)

    def chapters(self) -> list[tuple[Entry, int]]:
        """(entry, end page) of every chapter: the outline's top entries but the parts and the
        appendices' heading, and the entries under those; a chapter ends where the next
        chapter, part or the index begins."""
        heads, inside = [], False
        for entry in self.outline:
            if entry.level == 0:
                inside = is_part(entry) or entry.title == "Appendices"
                heads.append((entry, not inside))
            elif entry.level == 1 and inside:
                heads.append((entry, entry.title != "Index"))
        out = []
        for index, (entry, is_chapter) in enumerate(heads):
            if is_chapter:
                end = heads[index + 1][0].page if index + 1 < len(heads) else len(self.pages)
                out.append((entry, end))
        return out


def is_part(entry: Entry) -> bool:
    return entry.level == 0 and re.match(r"^[IVXLC]+ ", entry.title) is not None


def read_pdf(path: Path) -> Printed:
    from pypdf import PdfReader

    if shutil.which("pdftotext") is None:
        pytest.fail("pdftotext is missing: run `make tex` (poppler-utils)")
    done = subprocess.run(["pdftotext", "-raw", str(path), "-"], capture_output=True,
                          text=True, check=True)
    text = done.stdout.replace("\u2019", "'").replace("\u2018", "'")
    pages = text.split("\f")
    reader = PdfReader(str(path))
    outline: list[Entry] = []

    def walk(items, level):
        for item in items:
            if isinstance(item, list):
                walk(item, level + 1)
            else:
                outline.append(Entry(level, item.title, reader.get_destination_page_number(item)))

    walk(reader.outline, 0)
    return Printed(path, pages[:len(reader.pages)], list(reader.page_labels), outline)
