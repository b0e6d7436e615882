#!/usr/bin/env python
"""Copy the accessibility tests' last measurement into the accessibility page.

Usage::

    .venv/bin/python -m tools.accessibility_report [--results _build/accessibility/audit.json]

``tests/browser/test_accessibility.py`` audits every page of both web editions and walks one
chapter by keyboard; when the whole module has run, it writes what it measured to
``_build/accessibility/audit.json`` and checks that ``book/accessibility.md`` states the same
figures. This tool writes them into the page, between the markers ``<!-- BEGIN audit -->``
and ``<!-- END audit -->``: a paragraph and a table for the reader, and the figures the test
compares in an HTML comment (:func:`summary`). Run it after the browser tests when the page's
figures are out of date (a page added, a new axe-core); then rebuild the book.
"""

from __future__ import annotations

import argparse
import datetime
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "_build" / "accessibility" / "audit.json"
PAGE = ROOT / "book" / "accessibility.md"
BEGIN, END = "<!-- BEGIN audit -->", "<!-- END audit -->"
_BLOCK = re.compile(re.escape(BEGIN) + r"\n(.*?)" + re.escape(END), re.S)
_FIGURES = re.compile(r"<!-- figures: (\{.*?\}) -->")

#: What the walk used, in the order the page lists it.
KINDS = ("sidebar toggle", "code fold", "answer fold", "dropdown", "search", "colour mode",
         "play", "player step", "frame slider", "slider", "radio", "scrolling region",
         "button")


#: How the page names each kind of control: words true on paper as on the screen (the printed
#: edition has no word for clicking or folding, tests/pdf).
NAMES = {"code fold": "code toggle", "answer fold": "answer toggle", "dropdown": "menu",
         "button": "other push control"}


def summary(results: dict) -> dict:
    """The figures the page states, which the test compares with what it measured (all of
    them but the date and Chromium's version)."""
    walk = results["walk"]
    return {
        "axe_core": results["axe_core"], "tags": list(results["tags"]),
        "rules": results["rules"],
        **{edition: {k: results[edition][k] for k in ("pages", "violations", "dark_violations",
                                                      "keyboard_problems", "figures",
                                                      "animations", "tables", "undescribed")}
           for edition in ("book", "student")},
        "walk": {**{k: walk[k] for k in ("chapter", "pages", "controls", "reached")},
                 "used": [kind for kind in KINDS if kind in walk["used"]]},
    }


def stated(page_text: str) -> dict | None:
    """The figures the page states (None when it has no measured block)."""
    block = _BLOCK.search(page_text)
    found = _FIGURES.search(block.group(1)) if block else None
    return json.loads(found.group(1)) if found else None


def _title(chapter: str) -> str:
    """A chapter's title: the first heading of its landing page."""
    index = ROOT / chapter / "index.md"
    if index.is_file():
        for line in index.read_text(encoding="utf-8").splitlines():
            if line.startswith("# "):
                return line[2:].strip()
    return chapter


def render(results: dict, date: str) -> str:
    """The block of the page: the figures for the test, a paragraph and a table for readers."""
    figures = summary(results)
    book, student, walk = results["book"], results["student"], results["walk"]
    used = ", ".join(NAMES.get(kind, kind) for kind in figures["walk"]["used"])
    chromium = results.get("chromium") or "Debian's"
    rows = [("the book", book), ("the student edition", student)]
    lines = [
        f"<!-- figures: {json.dumps(figures, sort_keys=True)} -->",
        "",
        f"Measured on {date} by the browser tests, with axe-core {results['axe_core']} "
        f"({results['rules']} rules tagged {', '.join(results['tags'])}) in Chromium "
        f"{chromium} at {results['viewport']['width']} × {results['viewport']['height']} px:",
        "",
        "| edition | pages audited | axe-core violations, light theme | the same, dark theme "
        "| controls out of the tab order or without a visible focus |",
        "| --- | ---: | ---: | ---: | ---: |",
    ]
    for name, figures_of in rows:
        lines.append(f"| {name} | {figures_of['pages']} | {figures_of['violations']} | "
                     f"{figures_of['dark_violations']} | {figures_of['keyboard_problems']} |")
    lines += [
        "",
        f"The book's pages hold {book['figures']} figures, {book['animations']} animations "
        f"and {book['tables']} data tables (the student edition's: {student['figures']}, "
        f"{student['animations']} and {student['tables']}); "
        + ("every figure's alt text and every animation's description says more than its "
           "caption, and every table has header cells."
           if book["undescribed"] + student["undescribed"] == 0 else
           f"{book['undescribed'] + student['undescribed']} of them are not described as "
           "they should be."),
        "",
        f"The keyboard-only walk went through the {walk['pages']} pages of the chapter "
        f"*{_title(walk['chapter'])}*: Tab reached {walk['reached']} of its "
        f"{walk['controls']} controls (a group of radio choices counts as reached when one "
        f"of them is), each with its focus seen on screen, and these controls were used "
        f"with the keys a reader would press: {used}.",
        "",
    ]
    return "\n".join(lines)


def write(page: Path, results: dict, date: str) -> bool:
    """Put the block into ``page``; True if the page changed."""
    text = page.read_text(encoding="utf-8")
    if not _BLOCK.search(text):
        raise SystemExit(f"{page} has no {BEGIN} ... {END} block")
    new = _BLOCK.sub(lambda m: f"{BEGIN}\n{render(results, date)}{END}", text)
    if new != text:
        page.write_text(new, encoding="utf-8")
    return new != text


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--results", type=Path, default=RESULTS)
    parser.add_argument("--page", type=Path, default=PAGE)
    args = parser.parse_args(argv)
    if not args.results.is_file():
        print(f"accessibility_report: no {args.results}: run the browser tests first "
              "(tests/browser/test_accessibility.py, the whole module)", file=sys.stderr)
        return 1
    results = json.loads(args.results.read_text(encoding="utf-8"))
    date = datetime.datetime.fromtimestamp(args.results.stat().st_mtime,
                                           tz=datetime.UTC).date().isoformat()
    changed = write(args.page, results, date)
    print(f"accessibility_report: {args.page.relative_to(ROOT)} "
          f"{'updated' if changed else 'already states this measurement'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
