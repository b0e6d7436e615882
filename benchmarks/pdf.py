"""The printed edition: how long ``tools/pdf_edition.py`` takes and how many pages it makes.

Usage: ``python -m benchmarks.pdf [--no-write]`` (needs Debian's TeX: ``make tex``). Builds
``_build/pdf/wheelkin.pdf`` from the stored notebooks (transformed copy, then XeLaTeX) and
writes the "Printed edition" section of benchmarks/RESULTS.md (between its markers, other
sections kept).
"""

from __future__ import annotations

import argparse
import datetime
import os
import re
import sys
import time
from pathlib import Path

from tools.results import RESULTS, cpu, markers, write_section

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def chapter_pages(pdf: Path) -> dict[str, int]:
    """{outline title: pages} of every chapter of the PDF (not the parts, not the index)."""
    from pypdf import PdfReader

    reader = PdfReader(str(pdf))
    heads: list[tuple[str, int, bool]] = []
    inside = False

    def walk(items, level):
        nonlocal inside
        for item in items:
            if isinstance(item, list):
                walk(item, level + 1)
                continue
            page = reader.get_destination_page_number(item)
            if level == 0:
                inside = bool(re.match(r"^[IVXLC]+ ", item.title)) or item.title == "Appendices"
                heads.append((item.title, page, not inside))
            elif level == 1 and inside:
                heads.append((item.title, page, item.title != "Index"))

    walk(reader.outline, 0)
    out = {}
    for index, (title, page, is_chapter) in enumerate(heads):
        if is_chapter:
            end = heads[index + 1][1] if index + 1 < len(heads) else len(reader.pages)
            out[title] = end - page
    return out


def main(argv: list[str] | None = None) -> int:
    from tools import pdf_edition

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--no-write", action="store_true", help="print, do not write RESULTS.md")
    args = parser.parse_args(argv)
    load_before = os.getloadavg()
    start = time.perf_counter()
    summary = pdf_edition.build(ROOT / "_build" / "pdf", ROOT / "_build" / "pdf_src")
    seconds = time.perf_counter() - start
    load_after = os.getloadavg()
    chapters = chapter_pages(Path(summary["pdf"]))
    begin, end = markers("pdf")
    section = "\n".join([
        begin,
        "## Printed edition (`make pdf`)",
        "",
        f"Machine: {cpu()}. `tools/pdf_edition.py`: transformed copy of the book "
        "(animations as frame strips; no panels, figure-drawing code or solutions; answers at each "
        "chapter's end; cross-references with numbers and pages; an index), then Jupyter "
        "Book's LaTeX builder with XeLaTeX.",
        f"Run on {datetime.date.today().isoformat()}, load average "
        f"{load_before[0]:.1f} before and {load_after[0]:.1f} after (other jobs share the CPU: "
        "the build time varies with them).",
        "",
        "| what | value |",
        "| --- | --- |",
        f"| pages | {summary['pages']} |",
        f"| PDF size | {summary['bytes'] / 1e6:.1f} MB |",
        f"| notebooks | {summary['notebooks']} |",
        f"| build time | {seconds:.0f} s |",
        f"| chapters (front matter, chapters, appendices) | {len(chapters)} |",
        f"| shortest chapter | {min(chapters.values())} pages |",
        "",
        "Pages of each chapter (from its first page to the next chapter, part or the index; a",
        "chapter opens on a right-hand page, so a blank page may count):",
        "",
        "| chapter | pages |",
        "| --- | --- |",
        *[f"| {title} | {count} |" for title, count in chapters.items()],
        end,
    ])
    print(section)
    if not args.no_write:
        write_section("pdf", section, RESULTS)
    return 0


if __name__ == "__main__":
    sys.exit(main())
