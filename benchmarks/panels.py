"""Slider response: the redraw time of every live panel, every control swept over its range.

Budget (DESIGN.md): <= 50 ms median from a value change to the redrawn figure. For each
registered panel (:func:`wheelkin.widgets.all_panels`), one *sweep* moves every control in turn
across its whole range (:func:`wheelkin.widgets.slider_values`, the others at their defaults,
then back to its default) and records :meth:`wheelkin.widgets.Panel.redraw`'s wall time: the
model update, the (blitted or full) draw and the PNG encoding, i.e. what a student waits for
between moving a slider and seeing the new picture (less the widget's round trip to the
browser, which is not ours to speed up). Building the panel (its first, full draw) is not
counted.

The machine is shared (other jobs on the same cores), so each panel is swept ``--repeat``
times: the table gives the median and the 90th percentile over all redraws of all sweeps, and
the best sweep's median (the least disturbed one; the verdict uses it, and says whether the
median over everything meets the budget as well). The load average is written down with
the figures.

Usage: ``python -m benchmarks.panels [--repeat 5] [--points 9] [--only NAME ...]
[--no-write]``; writes the "Slider response" section of benchmarks/RESULTS.md (between its
markers, other sections kept).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import sys
import time

import matplotlib
import numpy as np

from tools.results import RESULTS, cpu, load_average, markers, write_section
from wheelkin.widgets import all_panels, slider_values

BUDGET_MS = 50.0

BEGIN, END = markers("panels")


def sweep(panel, points: int) -> list[float]:
    """Redraw times (s) of one sweep: every control over its range, then back to default."""
    times = []
    defaults = panel.values()
    for name, control in panel.controls.items():
        for value in slider_values(control, points):
            times.append(panel.redraw(**{name: value}))
        times.append(panel.redraw(**{name: defaults[name]}))
    return times


def measure_panel(factory, repeat: int, points: int) -> dict:
    """Sweep a fresh panel ``repeat`` times (fresh: nothing remembered from the last sweep)."""
    sweeps, builds = [], []
    for _ in range(repeat):
        start = time.perf_counter()
        panel = factory()
        builds.append(time.perf_counter() - start)
        try:
            sweeps.append(sweep(panel, points))
            png_kb = len(panel.image.value) / 1024
            blitted = panel._blit is not None  # reported, not relied upon
        finally:
            panel.close()
    build = min(builds)
    every = np.concatenate(sweeps) * 1e3
    return {
        "redraws": every.size,
        "median": float(np.median(every)),
        "p90": float(np.percentile(every, 90)),
        "best_median": min(float(np.median(s)) * 1e3 for s in sweeps),
        "best_p90": min(float(np.percentile(s, 90)) * 1e3 for s in sweeps),
        "max": float(every.max()),
        "build": build * 1e3,
        "png_kb": png_kb,
        "blitted": blitted,
    }


def measure(repeat: int, points: int, only: list[str] | None = None) -> dict:
    factories = all_panels()
    if only:
        unknown = sorted(set(only) - set(factories))
        if unknown:
            raise SystemExit(f"no panel named {', '.join(unknown)}; known: "
                             f"{', '.join(sorted(factories))}")
        factories = {k: v for k, v in factories.items() if k in only}
    load_before = os.getloadavg()
    rows = {}
    for name in sorted(factories):
        rows[name] = measure_panel(factories[name], repeat, points)
        print(f"{name:28s} median {rows[name]['median']:6.1f} ms  p90 {rows[name]['p90']:6.1f} "
              f"ms  best sweep {rows[name]['best_median']:6.1f} ms", file=sys.stderr, flush=True)
    return {"rows": rows, "repeat": repeat, "points": points,
            "load": (load_before, os.getloadavg())}


def machine() -> str:
    return (f"{cpu()}, "
            f"matplotlib {matplotlib.__version__} (Agg)")


def verdict(row: dict) -> str:
    if row["best_median"] > BUDGET_MS:
        return "**NOT met**"
    if row["median"] > BUDGET_MS:
        return "met on the best sweep only (load)"
    return "met"


def report(result: dict) -> str:
    lines = [
        BEGIN,
        "## Slider response",
        "",
        f"Machine: {machine()}. Date: {_dt.date.today().isoformat()}. "
        f"{load_average(*result['load'])} (other jobs shared "
        "the cores, so the figures over all sweeps are pessimistic). "
        "Produced by `python -m benchmarks.panels`.",
        "",
        f"Every control of every registered panel swept over its range ({result['points']} "
        "values of a numeric slider, every option of a choice, then back to its default; the "
        f"others at their defaults), {result['repeat']} times. A redraw is "
        "`Panel.redraw`: the model update, the drawing (*blitted*: only the moving artists "
        "over a cached background, or a full draw) and the PNG encoding.",
        "",
        "| panel | drawing | redraws | median (ms) | p90 (ms) | best sweep: median / p90 (ms) "
        "| slowest (ms) | verdict (≤ 50 ms median) |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for name, row in result["rows"].items():
        lines.append(
            f"| `{name}` | {'blitted' if row['blitted'] else 'full'} | {row['redraws']} | "
            f"{row['median']:.1f} | {row['p90']:.1f} | {row['best_median']:.1f} / "
            f"{row['best_p90']:.1f} | {row['max']:.0f} | {verdict(row)} |")
    rows = result["rows"].values()
    missed = [n for n, r in result["rows"].items() if r["best_median"] > BUDGET_MS]
    worst = max(r["median"] for r in rows) if rows else float("nan")
    lines += [
        "",
        f"Budget: ≤ {BUDGET_MS:.0f} ms median redraw for every panel. "
        + (f"Not met by: {', '.join(f'`{n}`' for n in missed)}. " if missed
           else "Met by every panel (best sweep). ")
        + f"Slowest median over all sweeps: {worst:.1f} ms.",
        END,
    ]
    return "\n".join(lines) + "\n"


def write(section: str) -> None:
    write_section("panels", section, RESULTS)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--points", type=int, default=9)
    parser.add_argument("--only", nargs="*", default=None, help="panel names (default: all)")
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    if args.repeat < 1 or args.points < 2:
        parser.error("--repeat must be >= 1 and --points >= 2")
    result = measure(args.repeat, args.points, args.only)
    section = report(result)
    print(section)
    if not args.no_write and not args.only:
        write(section)
    return 0  # measured, not asserted: the verdicts are in the table


if __name__ == "__main__":
    sys.exit(main())
