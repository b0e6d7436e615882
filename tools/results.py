"""What every benchmark shares: the machine's description and writing its RESULTS.md section.

Each benchmark (and :mod:`tools.time_build`) owns one section of ``benchmarks/RESULTS.md``,
delimited by ``<!-- BEGIN name -->`` / ``<!-- END name -->``, and replaces only that section.
It lives in ``tools`` so that ``benchmarks`` depends on ``tools`` and never the reverse.
"""

from __future__ import annotations

import os
import platform
from pathlib import Path

#: The file every benchmark writes its figures into.
RESULTS = Path(__file__).resolve().parents[1] / "benchmarks" / "RESULTS.md"


def cpu() -> str:
    """The CPU's model name (from /proc/cpuinfo where there is one) and its logical count."""
    name = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                name = line.split(":", 1)[1].strip()
                break
    except OSError:  # pragma: no cover - not Linux
        pass
    return f"{name}, {os.cpu_count()} logical CPUs; Python {platform.python_version()}"


def load_average(before: tuple[float, ...], after: tuple[float, ...]) -> str:
    """The sentence every benchmark writes down about the machine's load, from
    ``os.getloadavg()`` taken before and after the measurement.

    >>> load_average((1.0, 0.5, 0.25), (2.0, 1.04, 0.96))
    'Load average (1, 5, 15 min) before: 1.0, 0.5, 0.2; after: 2.0, 1.0, 1.0'
    """
    def three(load: tuple[float, ...]) -> str:
        return ", ".join(f"{x:.1f}" for x in load)

    return f"Load average (1, 5, 15 min) before: {three(before)}; after: {three(after)}"


def markers(name: str) -> tuple[str, str]:
    """The comment lines that delimit section ``name``."""
    return f"<!-- BEGIN {name} -->", f"<!-- END {name} -->"


def write_section(name: str, section: str, results: Path = RESULTS) -> None:
    """Replace section ``name`` of ``results`` with ``section`` (appended if it is new).

    ``section`` must start with the BEGIN and end with the END marker of ``name``.
    """
    begin, end = markers(name)
    if not (section.lstrip().startswith(begin) and section.rstrip().endswith(end)):
        raise ValueError(f"section must be delimited by {begin!r} and {end!r}")
    text = results.read_text(encoding="utf-8") if results.exists() else "# Benchmark results\n"
    if begin in text and end in text:
        head, rest = text.split(begin, 1)
        _, tail = rest.split(end, 1)
        text = head + section.strip("\n") + tail
    else:
        text = text.rstrip("\n") + "\n\n" + section.strip("\n") + "\n"
    results.write_text(text, encoding="utf-8")
