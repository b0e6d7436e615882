"""Sandbox speed and fidelity for every vehicle.

Budgets (DESIGN.md): >= 100 simulated seconds per wall second, every vehicle, at dt = 1/240 s
with the fidelity of the no-slip regime: <= 0.01 mm from the exact kinematic path over 10 m.

Speed. Each case is run ``--repeat`` times; the best and the median are reported, with the
ratio to bare pymunk stepping one body (pymunk's own Euler step, a box shape, no Python
callbacks) measured in the same run. Other jobs may share the CPU: the load average is written
down with the figures. Cases per vehicle:

* ``constant``: a constant command inside friction, ``world.step`` (no controller, no record),
  with the position error against the closed-form arc at the end (the fidelity it runs at);
* ``varying``: a smooth time-varying command inside friction, set by a controller with
  ``command_twist`` every step (sampled at the step midpoints) and recorded every step with
  ``world.run`` (the rover steers every step, so it rebuilds its contact maps every step);
* ``slip`` (skid steer only): turning, which always slips (the active-set friction solve).

Fidelity. Each vehicle drives 10 m of path (the duration comes from the reference) under a
command inside friction, recorded every step; the figure is the largest distance between the
sandbox's reference point and the exact kinematic path at any step, at dt = 1/240 s and at
1/120 s (their ratio shows the order of the scheme). Everything on the reference side is
written here, independently of the sandbox and of the library: the wheel commands come from
each vehicle's inverse kinematics written out from the source's geometry (:data:`GEOMETRY`,
checked against the sandbox's vehicles), and the exact path is the closed-form arc for a
constant twist, or scipy's DOP853 (``solve_ivp``, rtol 1e-13, atol 1e-14) for a time-varying
one, whose own error is estimated against a run at rtol 1e-11, atol 1e-12 and reported.

Usage: ``python -m benchmarks.sandbox [--repeat 5] [--seconds 10] [--no-write]``; writes the
"Sandbox" section of benchmarks/RESULTS.md (between its markers, other sections kept).
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
import pymunk
from scipy.integrate import solve_ivp

from tools.results import RESULTS, cpu, load_average, markers, write_section
from wheelkin.sandbox import (
    LAB_ROBOT,
    MECANUM_ROBOT,
    OPEN_SOURCE_ROVER,
    RADON_ULZER,
    RC_CAR,
    World,
)

DT = 1 / 240

BEGIN, END = markers("sandbox")

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
    ("car (1/10, ideal Ackermann)", RC_CAR, (0.8, 0.0, 0.8 / 1.2),  # steers every step
     lambda t: (0.8 + 0.1 * math.sin(0.5 * t), 0.0,
                (0.8 + 0.1 * math.sin(0.5 * t)) / (1.5 + 0.5 * math.sin(0.2 * t)))),
]


DISTANCE = 10.0  # m of path per fidelity case
FIDELITY_DTS = (1 / 240, 1 / 120)
FIDELITY_BUDGET = 1e-5  # m (0.01 mm)


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


def measure(repeat: int, seconds: float, only: str | None = None) -> dict:
    steps = round(seconds / DT)
    rows = []
    load_before = os.getloadavg()
    bares = []
    for label, spec, twist, twist_of_t in VEHICLES:
        if only and only not in label:
            continue
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
    for _ in range(repeat if not only else 0):
        bares.append(bare_pymunk(steps))
        wall = slip_case(steps)
        rates.append(seconds / wall)
        walls.append(wall)
    if rates:
        rows.append(("skid steer (lab robot)", "slip (turning)", rates, walls, None))
    bare = min(bares)
    rows = [(label, case, rates, [w / bare for w in walls], err)
            for label, case, rates, walls, err in rows]
    return {"rows": rows, "steps": steps, "seconds": seconds, "repeat": repeat,
            "load": (load_before, os.getloadavg()), "bare": seconds / bare}


# ----------------------------------------------------------------------------- fidelity
INCH = 0.0254

#: Each vehicle's geometry, written out from its source (m): wheel radius r, and the wheel
#: contact points (x, y) in the body frame, in the sandbox's wheel order.
GEOMETRY = {
    # Radon Ulzer firmware: track 0.085 m, wheel circumference 0.113097 m; L, R.
    "diff drive": (0.113097 / (2 * math.pi), {"L": (0.0, 0.0425), "R": (0.0, -0.0425)}),
    # Webots lab robot: r = 0.04 m, wheels at x = +-0.05 m, y = +-0.06 m; FL, FR, RL, RR.
    "skid steer": (0.04, {"FL": (0.05, 0.06), "FR": (0.05, -0.06), "RL": (-0.05, 0.06),
                          "RR": (-0.05, -0.06)}),
    # Generic mecanum platform: r = 0.05 m, half wheelbase = half track = 0.15 m.
    "mecanum": (0.05, {"FL": (0.15, 0.15), "FR": (0.15, -0.15), "RL": (-0.15, 0.15),
                       "RR": (-0.15, -0.15)}),
    # JPL Open Source Rover: d1 = 7.254 in, d2 = d3 = 10.5 in, d4 = 10.073 in; r = 0.06 m.
    "rover": (0.06, {"LF": (10.5 * INCH, 7.254 * INCH), "LM": (0.0, 10.073 * INCH),
                     "LB": (-10.5 * INCH, 7.254 * INCH), "RF": (10.5 * INCH, -7.254 * INCH),
                     "RM": (0.0, -10.073 * INCH), "RB": (-10.5 * INCH, -7.254 * INCH)}),
    # The 1/10 car: L = 0.33 m, W = 0.27 m, r = 0.05 m; reference point the rear-axle midpoint.
    "car": (0.05, {"FL": (0.33, 0.135), "FR": (0.33, -0.135), "RL": (0.0, 0.135),
                   "RR": (0.0, -0.135)}),
}
SPECS = {"diff drive": RADON_ULZER, "skid steer": LAB_ROBOT, "mecanum": MECANUM_ROBOT,
         "rover": OPEN_SOURCE_ROVER, "car": RC_CAR}


#: The mecanum rollers touching the ground, from the wheel's axle (X arrangement, 45 deg).
ROLLERS = {"FL": math.pi / 4, "FR": -math.pi / 4, "RL": -math.pi / 4, "RR": math.pi / 4}


def check_geometry() -> None:
    """Fail loudly if a sandbox vehicle is not the geometry the references are written for."""
    for key, (radius, wheels) in GEOMETRY.items():
        spec = SPECS[key]
        actual = {w.name: w for w in spec.driven_wheels}
        if list(actual) != list(wheels) or any(
                math.dist(actual[n].position, p) > 1e-12
                or abs(actual[n].wheel_radius - radius) > 1e-12
                or actual[n].heading != 0.0
                or (key == "mecanum" and abs(actual[n].roller_angle - ROLLERS[n]) > 1e-12)
                for n, p in wheels.items()):
            raise RuntimeError(f"{spec.name}: its wheels are not the geometry in GEOMETRY")


def diff_rates(v, w):
    """Differential drive, (L, R): phi = (v -+ w W/2) / r."""
    r, wheels = GEOMETRY["diff drive"]
    half = wheels["L"][1]
    return [(v - w * half) / r, (v + w * half) / r]


def skid_rates(v):
    """Skid steer driving straight: every wheel at v / r (FL, FR, RL, RR)."""
    r, _ = GEOMETRY["skid steer"]
    return [v / r] * 4


def mecanum_rates(vx, vy, w):
    """Mecanum, X arrangement, rollers at 45 deg, k = a + b; (FL, FR, RL, RR)."""
    r, wheels = GEOMETRY["mecanum"]
    a, b = wheels["FL"]
    k = a + b
    return [(vx - vy - k * w) / r, (vx + vy + k * w) / r, (vx + vy - k * w) / r,
            (vx - vy + k * w) / r]


def rover_commands(v, radius):
    """Rover turning left about (0, radius) at speed v of the reference point: wheel rates
    (LF, LM, LB, RF, RM, RB) and steering (LF, RF, LB, RB). A wheel at (x, y) is steered to
    delta = atan(x / (R - y)) and rolls at w |ICR - p| / r = w (R - y) / (r cos delta)."""
    r, wheels = GEOMETRY["rover"]
    w = v / radius
    rates, steer = {}, {}
    for name, (x, y) in wheels.items():
        steer[name] = math.atan(x / (radius - y))
        rates[name] = w * (radius - y) / (r * math.cos(steer[name]))
    return ([rates[n] for n in ("LF", "LM", "LB", "RF", "RM", "RB")],
            [steer[n] for n in ("LF", "RF", "LB", "RB")])


def _rover_speed(t):
    return 0.35 + 0.1 * math.sin(0.5 * t)


def _rover_radius(t):
    return 1.5 + 0.5 * math.sin(0.2 * t)


CAR_L = GEOMETRY["car"][1]["FL"][0]


def car_commands(v, delta):
    """Car at rear-axle speed v and bicycle steering delta: wheel rates (FL, FR, RL, RR) and
    steering (FL, FR). The turning centre is at (0, R), R = L / tan(delta); a wheel at (x, y)
    is steered to atan(x / (R - y)) and rolls at w |ICR - p| / r (the free fronts' rates are
    not commands; they are given their rolling rates)."""
    r, wheels = GEOMETRY["car"]
    if delta == 0.0:
        return [v / r] * 4, [0.0, 0.0]
    radius = CAR_L / math.tan(delta)
    w = v / radius
    rates = [w * math.hypot(x, radius - y) / r * math.copysign(1.0, v * radius)
             for x, y in wheels.values()]
    rates[2:] = [w * (radius - y) / r for x, y in list(wheels.values())[2:]]
    steer = [math.atan(x / (radius - y)) for x, y in list(wheels.values())[:2]]
    return rates, steer


def _car_speed(t):
    return 0.8 + 0.1 * math.sin(0.5 * t)


def _car_steering(t):
    return 0.3 * math.sin(0.3 * t)


def _set(robot, rates, steering=None):
    if steering is not None:
        robot.set_steering(steering)
    robot.set_wheel_rates(rates)


#: vehicle, command, sandbox spec, twist (a constant (vx, vy, w), or a function of t, in
#: m/s, m/s, rad/s), and the wheel command of that twist: command(robot, t).
FIDELITY = [
    ("diff drive (Radon Ulzer)", "constant: v 0.4 m/s, ω 0.3 rad/s", RADON_ULZER,
     (0.4, 0.0, 0.3), lambda robot, t: _set(robot, diff_rates(0.4, 0.3))),
    ("diff drive (Radon Ulzer)", "varying: v 0.4 ± 0.1 m/s, ω 0 ± 0.5 rad/s", RADON_ULZER,
     lambda t: (0.4 + 0.1 * math.sin(0.5 * t), 0.0, 0.5 * math.sin(0.3 * t)),
     lambda robot, t: _set(robot, diff_rates(0.4 + 0.1 * math.sin(0.5 * t),
                                             0.5 * math.sin(0.3 * t)))),
    ("skid steer (lab robot)", "constant, straight: v 0.3 m/s", LAB_ROBOT, (0.3, 0.0, 0.0),
     lambda robot, t: _set(robot, skid_rates(0.3))),
    ("skid steer (lab robot)", "varying, straight: v 0.3 ± 0.1 m/s", LAB_ROBOT,
     lambda t: (0.3 + 0.1 * math.sin(0.4 * t), 0.0, 0.0),
     lambda robot, t: _set(robot, skid_rates(0.3 + 0.1 * math.sin(0.4 * t)))),
    ("mecanum", "constant: vx 0.3, vy 0.2 m/s, ω 0.2 rad/s", MECANUM_ROBOT, (0.3, 0.2, 0.2),
     lambda robot, t: _set(robot, mecanum_rates(0.3, 0.2, 0.2))),
    ("mecanum", "varying: vx 0.3 ± 0.1, vy 0 ± 0.2 m/s, ω 0 ± 0.3 rad/s", MECANUM_ROBOT,
     lambda t: (0.3 + 0.1 * math.sin(0.5 * t), 0.2 * math.cos(0.3 * t), 0.3 * math.sin(0.2 * t)),
     lambda robot, t: _set(robot, mecanum_rates(0.3 + 0.1 * math.sin(0.5 * t),
                                                0.2 * math.cos(0.3 * t),
                                                0.3 * math.sin(0.2 * t)))),
    ("six-wheel rover (OSR)", "constant: v 0.4 m/s, R 1.2 m", OPEN_SOURCE_ROVER,
     (0.4, 0.0, 0.4 / 1.2), lambda robot, t: _set(robot, *rover_commands(0.4, 1.2))),
    ("six-wheel rover (OSR)", "varying speed: v 0.35 ± 0.1 m/s, R 1.5 m", OPEN_SOURCE_ROVER,
     lambda t: (_rover_speed(t), 0.0, _rover_speed(t) / 1.5),
     lambda robot, t: _set(robot, *rover_commands(_rover_speed(t), 1.5))),
    ("six-wheel rover (OSR)", "varying radius: v 0.35 ± 0.1 m/s, R 1.5 ± 0.5 m",
     OPEN_SOURCE_ROVER,
     lambda t: (_rover_speed(t), 0.0, _rover_speed(t) / _rover_radius(t)),
     lambda robot, t: _set(robot, *rover_commands(_rover_speed(t), _rover_radius(t)))),
    # The car is commanded as a car: rear-axle speed v and bicycle steering delta, every
    # wheel at its ideal Ackermann angle and rate; the reference is the bicycle model,
    # twist (v, 0, v tan(delta) / L).
    ("car (1/10, ideal Ackermann)", "constant: v 0.8 m/s, R 1.2 m", RC_CAR,
     (0.8, 0.0, 0.8 / 1.2),
     lambda robot, t: _set(robot, *car_commands(0.8, math.atan(CAR_L / 1.2)))),
    ("car (1/10, ideal Ackermann)", "varying: v 0.8 ± 0.1 m/s, δ 0 ± 0.3 rad", RC_CAR,
     lambda t: (_car_speed(t), 0.0, _car_speed(t) * math.tan(_car_steering(t)) / CAR_L),
     lambda robot, t: _set(robot, *car_commands(_car_speed(t), _car_steering(t)))),
]


def _rhs(twist_of_t):
    def rhs(t, q):
        vx, vy, w = twist_of_t(t)
        c, s = math.cos(q[2]), math.sin(q[2])
        return [c * vx - s * vy, s * vx + c * vy, w, math.hypot(vx, vy)]
    return rhs


def duration_for(twist, distance: float = DISTANCE) -> float:
    """Time for the reference point to travel ``distance`` of path, s."""
    if not callable(twist):
        return distance / math.hypot(twist[0], twist[1])

    def reached(t, q):
        return q[3] - distance
    reached.terminal, reached.direction = True, 1
    sol = solve_ivp(_rhs(twist), (0.0, 1e3), [0.0] * 4, method="DOP853", events=reached,
                    rtol=1e-13, atol=1e-14)
    return float(sol.t_events[0][0])


def reference(twist, times: np.ndarray, rtol: float = 1e-13, atol: float = 1e-14) -> np.ndarray:
    """Exact (x, y) of the reference point at ``times``, starting at the origin heading +x."""
    if not callable(twist):
        return np.array([arc(twist, t) for t in times])
    sol = solve_ivp(_rhs(twist), (times[0], times[-1]), [0.0] * 4, method="DOP853",
                    t_eval=times, rtol=rtol, atol=atol)
    if not sol.success:
        raise RuntimeError(f"solve_ivp: {sol.message}")
    return sol.y[:2].T


def fidelity_case(spec, twist, command, dt: float) -> dict:
    """Run one case at step ``dt`` over DISTANCE of path; the largest position error."""
    world = World(dt=dt)
    twist0 = twist(0.0) if callable(twist) else twist
    robot = world.add(spec, twist=twist0)
    command(robot, 0.0)
    duration = duration_for(twist)
    if callable(twist):
        traj = world.run(duration, lambda t, _world: command(robot, t))
    else:
        traj = world.run(duration)
    ref = reference(twist, traj.t)
    err = np.hypot(*(traj.pose[:, :2] - ref).T)
    out = {"error": float(err.max()), "distance": float(traj.distance[-1]),
           "duration": float(traj.t[-1]), "slipped": bool(traj.slipping.any())}
    if callable(twist):  # the reference's own error, estimated by a looser run
        loose = reference(twist, traj.t, rtol=1e-11, atol=1e-12)
        out["reference"] = float(np.hypot(*(loose - ref).T).max())
    return out


def measure_fidelity(only: str | None = None) -> list[dict]:
    check_geometry()
    rows = []
    for label, what, spec, twist, command in FIDELITY:
        if only and only not in label:
            continue
        runs = {dt: fidelity_case(spec, twist, command, dt) for dt in FIDELITY_DTS}
        rows.append({"label": label, "command": what, "varying": callable(twist),
                     "runs": runs})
    return rows


def machine() -> str:
    return (f"{cpu()}, "
            f"pymunk {pymunk.version} (Chipmunk {pymunk.chipmunk_version.split('-')[0]})")


def _mm(metres: float) -> str:
    return f"{metres * 1e3:.1e}"


def fidelity_report(rows: list[dict]) -> list[str]:
    fine, coarse = FIDELITY_DTS
    lines = [
        "### Fidelity",
        "",
        f"Each vehicle drives {DISTANCE:g} m of path under a command inside friction; the "
        "figure is the largest distance, over every step, between the sandbox's reference "
        "point and the exact kinematic path. The wheel commands come from each vehicle's "
        "inverse kinematics written out in the benchmark from the source's geometry (not the "
        "library's); the exact path is the closed-form arc for a constant twist and scipy's "
        "DOP853 (`solve_ivp`, rtol 1e-13, atol 1e-14) for a time-varying one. A time-varying "
        "command is sampled at the middle of each step (`World.run`), so halving the step "
        "should divide its error by about 4 (second order); a constant one is integrated "
        "exactly, to rounding, at any step.",
        "",
        "| vehicle | command | path (m) | largest position error at dt = 1/240 s (mm) | "
        "at dt = 1/120 s (mm) | error ratio 1/120 s : 1/240 s (order) | "
        "verdict (≤ 0.01 mm at 1/240 s) |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    worst, reference_error, all_met = 0.0, 0.0, True
    slipped = any(run["slipped"] for row in rows for run in row["runs"].values())
    for row in rows:
        a, b = row["runs"][fine], row["runs"][coarse]
        if row["varying"]:
            ratio = b["error"] / a["error"]
            order = f"{ratio:.2f} ({math.log2(ratio):.2f})"
            reference_error = max(reference_error, a["reference"], b["reference"])
        else:
            order = "rounding"
        met = a["error"] <= FIDELITY_BUDGET and not (a["slipped"] or b["slipped"])
        all_met = all_met and met
        worst = max(worst, a["error"])
        verdict = "met" if met else "NOT met"
        if a["slipped"] or b["slipped"]:
            verdict += " (a wheel slipped)"
        lines.append(f"| {row['label']} | {row['command']} | {a['distance']:.3f} | "
                     f"{_mm(a['error'])} | {_mm(b['error'])} | {order} | {verdict} |")
    lines += [
        "",
        f"Budget: ≤ 0.01 mm from the exact kinematic path over 10 m, every vehicle, at "
        f"1/240 s. Largest error above: {_mm(worst)} mm "
        f"({'met by every case' if all_met else 'NOT met by every case'}). "
        f"{'A wheel slipped in the cases marked.' if slipped else 'No wheel slipped.'} "
        f"The time-varying references' own error (against DOP853 at rtol 1e-11, atol 1e-12) is "
        f"at most {_mm(reference_error)} mm.",
    ]
    return lines


def report(result: dict) -> str:
    lines = [
        BEGIN,
        "## Sandbox",
        "",
        f"Machine: {machine()}. Date: {_dt.date.today().isoformat()}. "
        f"{load_average(*result['load'])} (other jobs shared the 2 cores, "
        "so the medians are pessimistic). Produced by `python -m benchmarks.sandbox`.",
        "",
        "### Speed",
        "",
        f"Each case: {result['seconds']:g} simulated s ({result['steps']} steps of 1/240 s), "
        f"run {result['repeat']} times; best and median. "
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
    no_slip = [r for r in result["rows"] if r[1] != "slip (turning)"]
    worst = min(statistics.median(r[2]) for r in no_slip)
    lines += [
        "",
        f"Budget: ≥ 100 simulated s per wall s for every vehicle in the no-slip regime. "
        f"Slowest median above: {worst:.0f} ({'met' if worst >= 100 else 'NOT met'}). "
        "The slip case (a turning skid steer, every wheel sliding) runs the active-set "
        "friction solve every step and is reported for information.",
        "",
    ]
    if result.get("fidelity"):
        lines += fidelity_report(result["fidelity"])
    lines.append(END)
    return "\n".join(lines) + "\n"


def write(section: str) -> None:
    write_section("sandbox", section, RESULTS)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--no-write", action="store_true")
    parser.add_argument("--only", default=None,
                        help="only the vehicles whose label contains this text (e.g. car); "
                             "prints the rows and writes nothing")
    args = parser.parse_args(argv)
    result = measure(args.repeat, args.seconds, args.only)
    result["fidelity"] = measure_fidelity(args.only)
    section = report(result)
    print(section)
    if not args.no_write and not args.only:
        write(section)
    return 0


if __name__ == "__main__":
    sys.exit(main())
