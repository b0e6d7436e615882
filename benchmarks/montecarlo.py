"""Monte Carlo odometry: 1,000 noisy runs of a 10 m path at 100 updates per metre.

Budget (DESIGN.md): <= 2 s on this machine, vectorised. The path is the one the chapter's
Monte Carlo section checks: 10 m for the Radon Ulzer (track 0.085 m), a straight metre, a
quarter circle of radius 0.5 m to the left and the rest straight, in updates of 1 cm of
centre travel (1,000 updates), with random wheel errors of variance k |Δs| per wheel
(k = 1e-6 m). :func:`wheelkin.odometry.monte_carlo_poses` draws and integrates every run
(the exact arc update, vectorised over runs and updates). Each measurement is repeated
``--repeat`` times; the best and the median are reported, with the load average.

Usage: ``python -m benchmarks.montecarlo [--repeat 7] [--runs 1000] [--no-write]``; writes the
"Monte Carlo odometry" section of benchmarks/RESULTS.md (between its markers).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import math
import os
import statistics
import sys
import time

import numpy as np

from tools.results import cpu, load_average, markers, write_section
from wheelkin import odometry as odo

BEGIN, END = markers("montecarlo")
BUDGET_S = 2.0
TRACK = 0.085  # m, the Radon Ulzer
K = 1e-6  # m: wheel error variance per metre rolled
LENGTH = 10.0  # m
PER_METRE = 100


def path_increments() -> tuple[np.ndarray, np.ndarray]:
    """(left, right) wheel travel per update of the 10 m benchmark path, m."""
    h = 1.0 / PER_METRE
    arc_length = 0.5 * math.pi / 2  # quarter circle of radius 0.5 m
    n_arc = round(arc_length * PER_METRE)
    n_straight = round(LENGTH * PER_METRE) - n_arc
    first = PER_METRE
    arc_h = arc_length / n_arc
    turn = (math.pi / 2) / n_arc
    left = np.concatenate([np.full(first, h), np.full(n_arc, arc_h - turn * TRACK / 2),
                           np.full(n_straight - first, h)])
    right = np.concatenate([np.full(first, h), np.full(n_arc, arc_h + turn * TRACK / 2),
                            np.full(n_straight - first, h)])
    return left, right


def measure(repeat: int, runs: int) -> dict:
    left, right = path_increments()
    times = []
    for i in range(repeat):
        rng = np.random.default_rng(i)
        start = time.perf_counter()
        ends = odo.monte_carlo_poses([0.0, 0.0, 0.0], left, right, TRACK, K, K, runs, rng)
        times.append(time.perf_counter() - start)
    start = time.perf_counter()
    odo.propagate_path([0.0, 0.0, 0.0], np.zeros((3, 3)), left, right, TRACK, K, K)
    propagate = time.perf_counter() - start
    return {"times": times, "updates": len(left), "runs": runs, "repeat": repeat,
            "distance": float(np.sum((left + right) / 2)), "propagate": propagate,
            "spread": float(np.std(ends[:, 1]))}


def report(result: dict, load: tuple) -> str:
    best, median = min(result["times"]), statistics.median(result["times"])
    verdict = "met" if median <= BUDGET_S else "NOT met"
    lines = [
        BEGIN,
        "## Monte Carlo odometry",
        "",
        f"Machine: {cpu()}, numpy {np.__version__}. Date: {_dt.date.today().isoformat()}. "
        f"{load_average(*load)}. "
        "Produced by `python -m benchmarks.montecarlo`.",
        "",
        f"`odometry.monte_carlo_poses`: {result['runs']} runs of a "
        f"{result['distance']:.2f} m path (1 m straight, a quarter circle of radius 0.5 m, "
        f"straight to the end) in {result['updates']} updates (100 per metre), random wheel "
        f"errors k = {K:g} m per wheel, the exact arc update vectorised over runs and updates; "
        f"repeated {result['repeat']} times.",
        "",
        "| case | runs x updates | wall time, best / median (s) | verdict (≤ 2 s) |",
        "| --- | --- | --- | --- |",
        f"| Monte Carlo, final poses | {result['runs']} x {result['updates']} | "
        f"{best:.3f} / {median:.3f} | {verdict} |",
        f"| propagated covariance (`propagate_path`), for comparison | 1 x "
        f"{result['updates']} | {result['propagate']:.3f} | |",
        "",
        f"Budget: ≤ {BUDGET_S:g} s for 1,000 runs of a 10 m path. Median above: "
        f"{median:.3f} s ({verdict}).",
        END,
    ]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--runs", type=int, default=1000)
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    before = os.getloadavg()
    result = measure(args.repeat, args.runs)
    after = os.getloadavg()
    section = report(result, (before, after))
    print(section)
    if not args.no_write:
        write_section("montecarlo", section)
    return 0 if statistics.median(result["times"]) <= BUDGET_S else 1


if __name__ == "__main__":
    sys.exit(main())
