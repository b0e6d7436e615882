"""Sandbox speed: simulated seconds per wall second for every vehicle, at full fidelity.

Budget (DESIGN.md): >= 100 simulated seconds per wall second, every vehicle, at dt = 1/240 s
with the fidelity of the no-slip regime (<= 0.01 mm over 10 m). Each case is run ``--repeat``
times; the best and the median are reported, with the ratio to bare pymunk stepping one body
(pymunk's own Euler step, a box shape, no Python callbacks) measured in the same run. Other
jobs may share the CPU: the load average is written down with the figures.

Cases per vehicle:

* ``constant``: a constant command inside friction, ``world.step`` (no controller, no record),
  with the position error against the closed-form arc at the end (the fidelity it runs at);
* ``varying``: a smooth time-varying command inside friction, set by a controller with
  ``command_twist`` every step (sampled at the step midpoints) and recorded every step with
  ``world.run`` (the rover steers every step, so it rebuilds its contact maps every step);
* ``slip`` (skid steer only): turning, which always slips (the active-set friction solve).

Usage: ``python benchmarks/sandbox.py [--repeat 5] [--seconds 10] [--no-write]``; writes the
"Sandbox" section of benchmarks/RESULTS.md (between its markers, other sections kept).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import math
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import pymunk

from wheelkin.sandbox import LAB_ROBOT, MECANUM_ROBOT, OPEN_SOURCE_ROVER, RADON_ULZER, World

DT = 1 / 240
RESULTS = Path(__file__).with_name("RESULTS.md")
BEGIN, END = "<!-- BEGIN sandbox -->", "<!-- END sandbox -->"

VEHICLES = [  # label, spec, constant twist, smooth time-varying twist (within friction)
    ("diff drive (Radon Ulzer)", RADON_ULZER, (0.4, 0.0, 0.3),
     lambda t: (0.4 + 0.08 * math.sin(0.5 * t), 0.0, 0.3 + 0.2 * math.sin(0.3 * t))),
    ("skid steer (lab robot)", LAB_ROBOT, (0.3, 0.0, 0.0),  # straight: turning always slips
     lambda t: (0.3 + 0.06 * math.sin(0.5 * t), 0.0, 0.0)),
    ("mecanum", MECANUM_ROBOT, (0.3, 0.2, 0.2),
     lambda t: (0.3 + 0.06 * math.sin(0.5 * t), 0.2 * math.cos(0.3 * t),
                0.2 * math.sin(0.2 * t))),
    ("six-wheel rover (OSR)", OPEN_SOURCE_ROVER, (0.4, 0.0, 0.4 / 1.2),  # steers every step
     lambda t: (0.4 + 0.08 * math.sin(0.5 * t), 0.0, 0.33 + 0.1 * math.sin(0.3 * t))),
]


def arc(twist, t):
    vx, vy, w = twist
    if w == 0:
        return vx * t, vy * t
    s, c = math.sin(w * t), math.cos(w * t)
    return (vx * s - vy * (1 - c)) / w, (vx * (1 - c) + vy * s) / w


def bare_pymunk(steps: int) -> float:
    """Wall seconds for ``steps`` steps of one pymunk body with a box shape (measured over at
    least 24000 steps, scaled)."""
    space = pymunk.Space()
    body = pymunk.Body(1.0, 0.01)
    body.velocity = (0.3, 0.0)
    body.angular_velocity = 0.2
    space.add(body, pymunk.Poly.create_box(body, (0.2, 0.1)))
    count = max(steps, 24000)
    start = time.perf_counter()
    for _ in range(count):
        space.step(DT)
    return (time.perf_counter() - start) * steps / count


def constant_case(spec, twist, steps: int) -> tuple[float, float]:
    world = World(dt=DT)
    robot = world.add(spec, twist=twist)
    start = time.perf_counter()
    world.step(steps)
    wall = time.perf_counter() - start
    x, y = arc(twist, steps * DT)
    return wall, math.hypot(robot.pose[0] - x, robot.pose[1] - y)


def varying_case(spec, twist_of_t, steps: int) -> tuple[float, bool]:
    world = World(dt=DT)
    robot = world.add(spec, twist=twist_of_t(0.0))

    def controller(t, _world):
        robot.command_twist(*twist_of_t(t))

    start = time.perf_counter()
    traj = world.run(steps * DT, controller)
    return time.perf_counter() - start, bool(traj.slipping.any())


def slip_case(steps: int) -> float:
    world = World(dt=DT)
    robot = world.add(LAB_ROBOT)
    robot.set_side_rates(3.0, 7.0)
    world.step(240)  # into the steady slide
    start = time.perf_counter()
    world.step(steps)
    return time.perf_counter() - start


def measure(repeat: int, seconds: float) -> dict:
    steps = round(seconds / DT)
    rows = []
    load_before = os.getloadavg()
    bares = []
    for label, spec, twist, twist_of_t in VEHICLES:
        for case in ("constant", "varying"):
            rates, walls, errors = [], [], []
            for _ in range(repeat):
                bares.append(bare_pymunk(steps))
                if case == "constant":
                    wall, err = constant_case(spec, twist, steps)
                    errors.append(err)
                else:
                    wall, slipped = varying_case(spec, twist_of_t, steps)
                    if slipped:
                        raise RuntimeError(f"{label}: the varying command slipped")
                rates.append(seconds / wall)
                walls.append(wall)
            rows.append((label, case, rates, walls, max(errors) if errors else None))
    rates, walls = [], []
    for _ in range(repeat):
        bares.append(bare_pymunk(steps))
        wall = slip_case(steps)
        rates.append(seconds / wall)
        walls.append(wall)
    rows.append(("skid steer (lab robot)", "slip (turning)", rates, walls, None))
    bare = min(bares)
    rows = [(label, case, rates, [w / bare for w in walls], err)
            for label, case, rates, walls, err in rows]
    return {"rows": rows, "steps": steps, "seconds": seconds, "repeat": repeat,
            "load": (load_before, os.getloadavg()), "bare": seconds / bare}


def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:  # pragma: no cover
        pass
    return (f"{cpu}, {os.cpu_count()} logical CPUs; Python {platform.python_version()}, "
            f"pymunk {pymunk.version} (Chipmunk {pymunk.chipmunk_version.split('-')[0]})")


def report(result: dict) -> str:
    lines = [
        BEGIN,
        "## Sandbox",
        "",
        f"Machine: {machine()}. Date: {_dt.date.today().isoformat()}. "
        f"Each case: {result['seconds']:g} simulated s ({result['steps']} steps of 1/240 s), "
        f"run {result['repeat']} times; best and median. "
        f"Load average (1, 5, 15 min) before: "
        f"{', '.join(f'{x:.1f}' for x in result['load'][0])}; after: "
        f"{', '.join(f'{x:.1f}' for x in result['load'][1])} (other jobs shared the 2 cores, "
        "so the medians are pessimistic). Produced by `python benchmarks/sandbox.py`.",
        "",
        f"Bare pymunk, one body with a box shape, Euler step, no Python callbacks: "
        f"{result['bare']:.0f} simulated s per wall s (best of all its runs); the ratio "
        "column divides each case's wall time by that.",
        "",
        "| vehicle | case | simulated s per wall s (best / median) | "
        "wall time / bare pymunk (best / median) | position error at the end |",
        "| --- | --- | --- | --- | --- |",
    ]
    for label, case, rates, ratios, err in result["rows"]:
        err_text = ""
        if err is not None:
            speed = {v[0]: math.hypot(v[2][0], v[2][1]) for v in VEHICLES}[label]
            err_text = f"{err * 1e3:.1e} mm after {speed * result['seconds']:.1f} m"
        lines.append(
            f"| {label} | {case} | {max(rates):.0f} / {statistics.median(rates):.0f} | "
            f"{min(ratios):.1f}x / {statistics.median(ratios):.1f}x | {err_text} |"
        )
    worst = min(statistics.median(r[2]) for r in result["rows"][:-1])
    lines += [
        "",
        f"Budget: >= 100 simulated s per wall s for every vehicle in the no-slip regime. "
        f"Slowest median above: {worst:.0f} ({'met' if worst >= 100 else 'NOT met'}). "
        "The slip case (a turning skid steer, every wheel sliding) runs the active-set "
        "friction solve every step and is reported for information.",
        END,
    ]
    return "\n".join(lines) + "\n"


def write(section: str) -> None:
    text = RESULTS.read_text() if RESULTS.exists() else "# Benchmark results\n\n"
    if BEGIN in text and END in text:
        head, rest = text.split(BEGIN, 1)
        _, tail = rest.split(END, 1)
        text = head + section.rstrip("\n") + tail
    else:
        text = text.rstrip("\n") + "\n\n" + section
    RESULTS.write_text(text)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    section = report(measure(args.repeat, args.seconds))
    print(section)
    if not args.no_write:
        write(section)
    return 0


if __name__ == "__main__":
    sys.exit(main())
