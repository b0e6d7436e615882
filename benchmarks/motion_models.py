"""Thrun's odometry motion model: 10^5 samples in under 0.1 s (issue #20).

`wheelkin.odometry.sample_motion_model_odometry` (table 5.6) draws 100,000 poses for one
motion (0.5 m ahead, 0.2 m to the left, a turn of 0.6 rad), vectorised; for comparison the
velocity model's sampler (`sample_motion_model_velocity`, table 5.3) and the density
(`motion_model_odometry`, table 5.5) at 100,000 hypotheses. Each measurement is repeated
``--repeat`` times; the best and the median are reported, with the load average.

Usage: ``python -m benchmarks.motion_models [--repeat 21] [--no-write]``; writes the "Motion
models" section of benchmarks/RESULTS.md (between its markers).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import statistics
import sys
import time

import numpy as np

from tools.results import cpu, load_average, markers, write_section
from wheelkin import frames
from wheelkin import odometry as odo

BEGIN, END = markers("motion_models")
BUDGET_S = 0.1
SAMPLES = 100_000
ALPHAS = [0.02, 0.05, 0.01, 0.005]
BEFORE = np.array([2.0, 1.0, 0.3])
AFTER = np.asarray(frames.compose(frames.Pose(*BEFORE), frames.Pose(0.5, 0.2, 0.6)))


def timed(fn, repeat: int) -> list[float]:
    times = []
    for _ in range(repeat):
        begin = time.perf_counter()
        fn()
        times.append(time.perf_counter() - begin)
    return times


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=21)
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    rng = np.random.default_rng(0)
    hypotheses = odo.sample_motion_model_odometry((0, 0, 0), AFTER, BEFORE, ALPHAS, SAMPLES,
                                                  np.random.default_rng(1))
    cases = {
        ("sample_motion_model_odometry", "table 5.6, 10⁵ samples"):
            lambda: odo.sample_motion_model_odometry((0.0, 0.0, 0.0), AFTER, BEFORE, ALPHAS,
                                                     SAMPLES, rng),
        ("sample_motion_model_velocity", "table 5.3, 10⁵ samples"):
            lambda: odo.sample_motion_model_velocity(
                (0.0, 0.0, 0.0), (0.4, 0.0, 0.8), 1.5,
                [0.01, 0.005, 0.02, 0.01, 0.005, 0.005], SAMPLES, rng),
        ("motion_model_odometry", "table 5.5, 10⁵ hypotheses"):
            lambda: odo.motion_model_odometry(hypotheses, (0.0, 0.0, 0.0), AFTER, BEFORE,
                                              ALPHAS),
    }
    before = os.getloadavg()
    results = {name: timed(fn, args.repeat) for name, fn in cases.items()}
    after = os.getloadavg()
    sampler = statistics.median(results[("sample_motion_model_odometry",
                                         "table 5.6, 10⁵ samples")])
    verdict = "met" if sampler <= BUDGET_S else "NOT met"
    lines = [
        BEGIN,
        "## Motion models",
        "",
        f"Machine: {cpu()}, numpy {np.__version__}. Date: {_dt.date.today().isoformat()}. "
        f"{load_average(before, after)}. "
        "Produced by `python -m benchmarks.motion_models`.",
        "",
        f"{SAMPLES:,} samples (or hypotheses) of one motion, repeated {args.repeat} times.",
        "",
        "| call | what | wall time, best / median (ms) | verdict (sampler ≤ 100 ms) |",
        "| --- | --- | --- | --- |",
    ]
    for (name, what), times in results.items():
        mark = verdict if name == "sample_motion_model_odometry" else ""
        lines.append(f"| `odometry.{name}` | {what} | {1000 * min(times):.1f} / "
                     f"{1000 * statistics.median(times):.1f} | {mark} |")
    lines += ["", f"Budget: 10⁵ samples of the odometry model in ≤ {1000 * BUDGET_S:g} ms. "
              f"Median above: {1000 * sampler:.1f} ms ({verdict}).", END]
    section = "\n".join(lines) + "\n"
    print(section)
    if not args.no_write:
        write_section("motion_models", section)
    return 0 if sampler <= BUDGET_S else 1


if __name__ == "__main__":
    sys.exit(main())
