"""The printed edition: how long ``tools/pdf_edition.py`` takes and how many pages it makes.

Usage: ``python -m benchmarks.pdf [--no-write]`` (needs Debian's TeX: ``make tex``). Builds
``_build/pdf/wheelkin.pdf`` from the stored notebooks (transformed copy, then XeLaTeX) and
writes the "Printed edition" section of benchmarks/RESULTS.md (between its markers, other
sections kept).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from tools.results import RESULTS, cpu, markers, write_section

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def main(argv: list[str] | None = None) -> int:
    from tools import pdf_edition

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--no-write", action="store_true", help="print, do not write RESULTS.md")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    summary = pdf_edition.build(ROOT / "_build" / "pdf", ROOT / "_build" / "pdf_src")
    seconds = time.perf_counter() - start
    begin, end = markers("pdf")
    section = "\n".join([
        begin,
        "## Printed edition (`make pdf`)",
        "",
        f"Machine: {cpu()}. `tools/pdf_edition.py`: transformed copy of the book "
        "(animations as frame strips, no panels, no folded code, no solutions), then Jupyter "
        "Book's LaTeX builder with XeLaTeX.",
        "",
        "| what | value |",
        "| --- | --- |",
        f"| pages | {summary['pages']} |",
        f"| PDF size | {summary['bytes'] / 1e6:.1f} MB |",
        f"| notebooks | {summary['notebooks']} |",
        f"| build time | {seconds:.0f} s |",
        end,
    ])
    print(section)
    if not args.no_write:
        write_section("pdf", section, RESULTS)
    return 0


if __name__ == "__main__":
    sys.exit(main())
