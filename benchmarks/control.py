"""The pose controller from a grid of start poses: which reach the goal, model and sandbox.

Issue #20's measure: from a grid of at least 200 start poses, the fraction that reach the
goal within 1 cm and 1 degree within a time limit, in the kinematic model and in the sandbox
with slip. The grid: positions every 0.2 m on a 6 x 6 square of side 1 m around the goal (the
goal's own position is not on it), eight headings each, 288 starts; the goal at the origin
heading +x; Corke's gains (3, 8, -3) 1/s; the controller applied every 20 ms with the wheel
speeds capped at 0.3 m/s (both scaled together); 10 s. The sandbox is the Radon Ulzer (a
Zumo 32U4) on a floor of friction coefficient 0.2, where its wheels slip whenever the command
jumps. Four variants of what the controller sees and does: the true pose or an overhead
camera's (noise 1 mm and 0.2 degrees, standard deviations); the law as published, or with a
stop distance of 5 mm (`wheelkin.control.move_to_pose(..., stop_distance=0.005)`).

Usage: ``python -m benchmarks.control [--no-write]``; writes the "Driving to a pose" section
of benchmarks/RESULTS.md (between its markers).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import math
import os
import sys
import time

import numpy as np

from tools.results import cpu, load_average, markers, write_section
from wheelkin import control
from wheelkin.sandbox import RADON_ULZER
from wheelkin.widgets.control import (
    CORKE_GAINS,
    GOAL,
    converged,
    sandbox_runs,
    start_grid,
    unicycle_commands,
)

BEGIN, END = markers("control")
DURATION, PERIOD = 10.0, 0.02  # s
CAMERA = (0.001, math.radians(0.2))  # m, rad
STOP = 0.005  # m
MU = 0.2


def law(stop: float):
    def command(t, poses):
        return unicycle_commands(control.move_to_pose(poses, GOAL, *CORKE_GAINS,
                                                      stop_distance=stop))
    return command


def kinematic(starts: np.ndarray, stop: float, camera: bool) -> tuple[np.ndarray, float]:
    rng = np.random.default_rng(1)
    scale = np.array([CAMERA[0], CAMERA[0], CAMERA[1]])
    inner = law(stop)

    def seen(t, poses):
        noise = rng.standard_normal(poses.shape) * scale if camera else 0.0
        return inner(t, poses + noise)

    begin = time.perf_counter()
    ends = control.simulate(seen, starts, DURATION, PERIOD)[-1]
    return converged(ends), time.perf_counter() - begin


def sandbox(starts: np.ndarray, stop: float, camera: bool) -> tuple[np.ndarray, float, float]:
    begin = time.perf_counter()
    runs = sandbox_runs(RADON_ULZER.replace(mu=MU), starts, law(stop), DURATION,
                        period=PERIOD, camera_noise=CAMERA if camera else (0.0, 0.0), seed=1)
    wall = time.perf_counter() - begin
    ends = np.array([run.pose[-1] for run in runs])
    slip = float(np.mean([run.slipping.any(axis=1).any() for run in runs]))
    return converged(ends), wall, slip


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    starts = start_grid(6, 0.5, 8)
    before = os.getloadavg()
    rows = []
    for stop, camera in ((0.0, False), (STOP, False), (0.0, True), (STOP, True)):
        ok_k, wall_k = kinematic(starts, stop, camera)
        ok_s, wall_s, slip = sandbox(starts, stop, camera)
        rows.append((stop, camera, ok_k, wall_k, ok_s, wall_s, slip))
    after = os.getloadavg()
    lines = [
        BEGIN,
        "## Driving to a pose",
        "",
        f"Machine: {cpu()}, numpy {np.__version__}. Date: {_dt.date.today().isoformat()}. "
        f"{load_average(before, after)}. "
        "Produced by `python -m benchmarks.control`.",
        "",
        f"The pose controller (`wheelkin.control.move_to_pose`, Corke's gains (3, 8, -3) 1/s) "
        f"from {len(starts)} start poses (positions every 0.2 m within 0.5 m of the goal, eight "
        f"headings each), applied every {1000 * PERIOD:.0f} ms with wheel speeds capped at "
        f"0.3 m/s. Reached: within 1 cm and 1° of the goal after {DURATION:g} s. Kinematic "
        "model: `wheelkin.control.simulate` (exact arcs). Sandbox: the Radon Ulzer on a floor "
        f"of μ = {MU}, all robots in one world (`wheelkin.widgets.control.sandbox_runs`). The "
        "camera adds noise of 1 mm and 0.2° to the pose the controller sees.",
        "",
        "| law | the controller sees | kinematic: reached | sandbox, μ = 0.2: reached | "
        "runs in which a wheel slipped | wall time, kinematic / sandbox (s) |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    for stop, camera, ok_k, wall_k, ok_s, wall_s, slip in rows:
        name = "as published" if stop == 0.0 else f"stop distance {1000 * stop:g} mm"
        lines.append(
            f"| {name} | {'camera' if camera else 'true pose'} | "
            f"{ok_k.sum()} of {len(ok_k)} ({100 * ok_k.mean():.1f} %) | "
            f"{ok_s.sum()} of {len(ok_s)} ({100 * ok_s.mean():.1f} %) | "
            f"{100 * slip:.0f} % | {wall_k:.1f} / {wall_s:.1f} |")
    lines += [
        "",
        "The published law's failures are robots that reached the goal's position and lost "
        "its heading: the law keeps shrinking the distance until the bearing is decided by "
        "the pose's rounding (sandbox) or the camera's noise (chapter \"Driving to a pose\", "
        "section \"Where it converges\"). A stop distance of a few times the noise removes "
        "them.",
        END,
    ]
    section = "\n".join(lines) + "\n"
    print(section)
    if not args.no_write:
        write_section("control", section)
    return 0


if __name__ == "__main__":
    sys.exit(main())
