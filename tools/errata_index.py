#!/usr/bin/env python
"""Write the errata index from the chapters' erratum boxes: one line per erratum, a link each.

Each erratum is told once, in its chapter, in a box under a label line
``(erratum-<source>-<slug>)=`` whose title starts with "Erratum:" (docs/DESIGN.md, "Tell each
thing once"). This rewrites the list of ``book/errata/<source>.md`` from those boxes, in reading
order: one line ``- {ref}`<the box's title> <erratum-...>` `` per box. The file's heading and
its one-paragraph introduction (everything before the list) are kept.

Usage: ``python -m tools.errata_index`` (writes), ``--check`` (exit 1 if a file would change).
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

import nbformat

from tools.book_pages import ROOT, toc_notebooks

ERRATA_DIR = ROOT / "book" / "errata"
LABEL = re.compile(r"^\((erratum-([a-z]+)-[\w-]+)\)=\s*$", re.MULTILINE)
TITLE = re.compile(r"^(?::{3,}|`{3,})\s*\{(?:admonition|warning)\}\s*(.*)$", re.MULTILINE)
LIST_START = re.compile(r"^- \{ref\}`", re.MULTILINE)


def clean_title(title: str) -> str:
    """A box title as plain link text: no "Erratum:", no markup a {ref} text cannot hold."""
    title = re.sub(r"^Erratum:\s*", "", title.strip())
    markup = title[:1] in "`$"  # starts with code or math: keep its case
    title = title.replace("`", "").replace("$", "")
    title = title.replace("<", "‹").replace(">", "›")
    if not markup and title[:1].isascii() and title[:1].islower():
        title = title[:1].upper() + title[1:]
    return title


def boxes() -> list[tuple[str, str, str]]:
    """(label, source, title) of every erratum box, in the toc's reading order."""
    found = []
    for path in toc_notebooks():
        for cell in nbformat.read(path, as_version=4).cells:
            if cell.cell_type != "markdown":
                continue
            for match in LABEL.finditer(cell.source):
                title = TITLE.search(cell.source, match.end())
                text = clean_title(title.group(1)) if title else match.group(1)
                found.append((match.group(1), match.group(2), text))
    return found


def render(path: Path, entries: list[tuple[str, str]]) -> str:
    old = path.read_text(encoding="utf-8") if path.exists() else f"# {path.stem}\n\n"
    head = old[:m.start()] if (m := LIST_START.search(old)) else old.rstrip("\n") + "\n\n"
    lines = "".join(f"- {{ref}}`{title} <{label}>`\n" for label, title in entries)
    return head.rstrip("\n") + "\n\n" + lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args(argv)
    by_source: dict[str, list[tuple[str, str]]] = {}
    seen: set[str] = set()
    for label, source, title in boxes():
        if label in seen:
            print(f"errata_index: {label} is defined twice", file=sys.stderr)
            continue
        seen.add(label)
        by_source.setdefault(source, []).append((label, title))
    changed = []
    for source, entries in sorted(by_source.items()):
        path = ERRATA_DIR / f"{source}.md"
        text = render(path, entries)
        if not path.exists() or path.read_text(encoding="utf-8") != text:
            changed.append(path)
            if not args.check:
                path.write_text(text, encoding="utf-8")
    for path in changed:
        print(f"{'would change' if args.check else 'wrote'} {path.relative_to(ROOT)}")
    return 1 if (args.check and changed) else 0


if __name__ == "__main__":
    sys.exit(main())
