#!/usr/bin/env python
"""The notation page's tables, made from the notation's data (``book/notation.yml``).

Usage::

    python -m tools.notation_table           # print the tables
    python -m tools.notation_table --write   # write them into book/notation.md
    python -m tools.notation_table --check   # exit 1 if book/notation.md is out of date

The tables sit in ``book/notation.md`` between the lines ``% notation: begin`` and
``% notation: end`` (MyST comments); everything else on the page is prose written by hand. A row's
``introduced`` is a chapter's label and becomes a ``{ref}`` to that chapter.
``tests/book/test_notation_data.py`` checks the page against the data and the chapters against
both.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "book" / "notation.yml"
PAGE = ROOT / "book" / "notation.md"
BEGIN, END = "% notation: begin", "% notation: end"


def load(path: Path = DATA) -> dict:
    """The notation's data: ``sections`` (each a title, an optional intro and rows) and
    ``sources`` (the sources' own symbols)."""
    return yaml.safe_load(path.read_text(encoding="utf-8"))


def _cell(text: object) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def _introduced(label: str) -> str:
    return f"{{ref}}`{label}`" if label.startswith("chapter-") else label


def tables(data: dict) -> str:
    """The Markdown of every table, with its section heading and intro."""
    parts = []
    for section in data["sections"]:
        parts.append(f"## {section['title']}")
        if section.get("intro"):
            parts.append(" ".join(section["intro"].split()))
        lines = ["| symbol | meaning | unit | sign | introduced |",
                 "| --- | --- | --- | --- | --- |"]
        for row in section["rows"]:
            lines.append("| " + " | ".join(_cell(row[k]) for k in ("symbol", "meaning", "unit",
                                                                    "sign"))
                         + f" | {_introduced(row['introduced'])} |")
        parts.append("\n".join(lines))
    sources = data["sources"]
    parts.append(f"## {sources['title']}")
    parts.append(" ".join(sources["intro"].split()))
    lines = ["| source | its symbol | meaning | ours |", "| --- | --- | --- | --- |"]
    for row in sources["rows"]:
        lines.append("| " + " | ".join(_cell(row[k]) for k in ("source", "symbol", "meaning",
                                                                "ours")) + " |")
    parts.append("\n".join(lines))
    return "\n\n".join(parts) + "\n"


def page_with_tables(page: str, data: dict) -> str:
    """``page`` with the region between the markers replaced by :func:`tables`."""
    if page.count(BEGIN) != 1 or page.count(END) != 1:
        raise ValueError(f"{PAGE.name} needs exactly one {BEGIN!r} and one {END!r}")
    head, rest = page.split(BEGIN)
    _, tail = rest.split(END)
    return f"{head}{BEGIN}\n\n{tables(data)}\n{END}{tail}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--write", action="store_true", help="write book/notation.md")
    group.add_argument("--check", action="store_true", help="fail if it is out of date")
    args = parser.parse_args(argv)
    data = load()
    if not (args.write or args.check):
        print(tables(data), end="")
        return 0
    page = PAGE.read_text(encoding="utf-8")
    new = page_with_tables(page, data)
    if args.check:
        if new != page:
            print("book/notation.md is out of date: run python -m tools.notation_table --write",
                  file=sys.stderr)
            return 1
        return 0
    PAGE.write_text(new, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
