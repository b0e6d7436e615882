"""Per-call cost of the loop objects (wheelkin.kinematics, wheelkin.odometers).

Each object method is timed one call at a time, beside robotpy-wpimath's equivalent where it
has one (WPILib's kinematics and odometry classes, compiled C++ behind pybind11), a
hand-written pure-Python version of the same formula, and the chapter function the object
replaces in a loop (validated arrays).

robotpy-wpimath is not part of the book's stack: install it for this benchmark only,
``.venv/bin/pip install -r requirements-bench.txt``; then ``python -m benchmarks.objects``
(or ``make bench``). Without it the WPILib column says "not installed" and the budget's
"within 3x of WPILib" cannot be checked.

Timing: ``timeit`` batches of ``NUMBER`` calls; per round the median of ``BATCHES`` batches;
the figure is the minimum over ``ROUNDS`` rounds (the machine is shared, so the minimum of
medians is the least disturbed estimate). Budget (issue #23): every object method without
covariance under 5 us and within 3x of WPILib; the covariance step under 15 us.
"""

from __future__ import annotations

import math
import statistics
import timeit
from collections.abc import Callable

from tools.results import cpu, markers, write_section

NUMBER = 2000
BATCHES = 7
ROUNDS = 5
BUDGET_US = 5.0
COVARIANCE_BUDGET_US = 15.0


def per_call_us(fn: Callable[[], object]) -> float:
    """Minimum over rounds of the median per-call time (us) of ``fn``."""
    timer = timeit.Timer(fn)
    best = math.inf
    for _ in range(ROUNDS):
        batches = [timer.timeit(NUMBER) / NUMBER for _ in range(BATCHES)]
        best = min(best, statistics.median(batches))
    return best * 1e6


def _counter() -> Callable[[], float]:
    state = [0.0]

    def step() -> float:
        state[0] += 0.001
        return state[0]
    return step


def cases() -> list[tuple[str, dict[str, Callable[[], object] | None], bool]]:
    """(what, {column: call or None}, is_covariance) for every row of the table."""
    import numpy as np

    from wheelkin import diffdrive, mecanum, odometry
    from wheelkin.frames import Twist
    from wheelkin.kinematics import (
        AckermannKinematics,
        DiffDriveKinematics,
        DiffDriveWheelSpeeds,
        MecanumKinematics,
        RoverKinematics,
    )
    from wheelkin.odometers import AckermannOdometry, DiffDriveOdometry, MecanumOdometry
    from wheelkin.rover import OSR_PARAMS_GEOMETRY

    try:
        from wpimath import geometry as wg
        from wpimath import kinematics as wk
    except ImportError:
        wk = wg = None

    geo = mecanum.EXAMPLE_GEOMETRY
    dd = DiffDriveKinematics(track_width=0.5)
    mk = MecanumKinematics(geo)
    car = AckermannKinematics(wheelbase=2.5, track_width=1.5)
    rov = RoverKinematics(OSR_PARAMS_GEOMETRY)
    twist = Twist(1.0, 0.0, 0.4)
    twist_xy = Twist(1.0, 0.3, 0.4)
    dd_wheels = DiffDriveWheelSpeeds(0.9, 1.1)
    m_wheels = mk.inverse(twist_xy)
    car_wheels = car.inverse(twist)
    rov_wheels = rov.inverse(twist)

    odo = DiffDriveOdometry(dd)
    odo_gyro = DiffDriveOdometry(dd, heading=0.0)
    odo_cov = DiffDriveOdometry(dd, wheel_noise=1e-6)
    m_odo = MecanumOdometry(mk)
    m_odo_cov = MecanumOdometry(mk, wheel_noise=1e-6)
    c_odo = AckermannOdometry(car)
    c_odo_cov = AckermannOdometry(car, wheel_noise=1e-6)
    tick = _counter()

    # hand-written pure Python: the formula and nothing else
    hand_pose = [0.0, 0.0, 0.0]

    def hand_midpoint(left: float, right: float, w: float = 0.5) -> None:
        ds, dth = 0.5 * (left + right), (right - left) / w
        mid = hand_pose[2] + 0.5 * dth
        hand_pose[0] += ds * math.cos(mid)
        hand_pose[1] += ds * math.sin(mid)
        hand_pose[2] += dth

    def hand_dd_inverse(v: float, w: float, half: float = 0.25) -> tuple[float, float]:
        return v - w * half, v + w * half

    def hand_mecanum_inverse(vx: float, vy: float, w: float,
                             k: float = geo.k) -> tuple[float, float, float, float]:
        return vx - vy - k * w, vx + vy + k * w, vx + vy - k * w, vx - vy + k * w

    rows: list[tuple[str, dict[str, Callable[[], object] | None], bool]] = []

    def row(what: str, ours: Callable[[], object], wpilib: Callable[[], object] | None = None,
            hand: Callable[[], object] | None = None,
            chapter: Callable[[], object] | None = None, covariance: bool = False) -> None:
        rows.append((what, {"wheelkin object": ours, "WPILib": wpilib,
                            "hand-written": hand, "chapter function": chapter}, covariance))

    if wk is not None:
        w_dd = wk.DifferentialDriveKinematics(0.5)
        w_odo = wk.DifferentialDriveOdometry(wg.Rotation2d(0.0), 0.0, 0.0)
        w_mk = wk.MecanumDriveKinematics(
            wg.Translation2d(geo.half_wheelbase, geo.half_track),
            wg.Translation2d(geo.half_wheelbase, -geo.half_track),
            wg.Translation2d(-geo.half_wheelbase, geo.half_track),
            wg.Translation2d(-geo.half_wheelbase, -geo.half_track))
        w_modo = wk.MecanumDriveOdometry(w_mk, wg.Rotation2d(0.0),
                                         wk.MecanumDriveWheelPositions())
        speeds = wk.ChassisSpeeds(1.0, 0.0, 0.4)
        speeds_xy = wk.ChassisSpeeds(1.0, 0.3, 0.4)
        w_dd_wheels = wk.DifferentialDriveWheelSpeeds(0.9, 1.1)
        w_m_wheels = w_mk.toWheelSpeeds(speeds_xy)

        def w_odo_update() -> object:
            d = tick()
            return w_odo.update(wg.Rotation2d(0.1 * d), d, 1.1 * d)

        def w_modo_update() -> object:
            d = tick()
            positions = wk.MecanumDriveWheelPositions()
            positions.frontLeft, positions.frontRight = d, 1.1 * d
            positions.rearLeft, positions.rearRight = d, 1.1 * d
            return w_modo.update(wg.Rotation2d(0.1 * d), positions)

        wpi: dict[str, Callable[[], object] | None] = {
            "dd inverse": lambda: w_dd.toWheelSpeeds(speeds),
            "dd forward": lambda: w_dd.toChassisSpeeds(w_dd_wheels),
            "dd desaturate": lambda: w_dd_wheels.desaturate(1.0),
            "m inverse": lambda: w_mk.toWheelSpeeds(speeds_xy),
            "m forward": lambda: w_mk.toChassisSpeeds(w_m_wheels),
            "m desaturate": lambda: w_m_wheels.desaturate(1.0),
            "dd odo": w_odo_update, "m odo": w_modo_update,
        }
    else:
        wpi = {}

    row("DiffDriveKinematics.inverse", lambda: dd.inverse(twist), wpi.get("dd inverse"),
        lambda: hand_dd_inverse(1.0, 0.4), lambda: diffdrive.wheel_speeds(1.0, 0.4, 0.5))
    row("DiffDriveKinematics.forward", lambda: dd.forward(dd_wheels), wpi.get("dd forward"),
        None, lambda: diffdrive.body_twist(0.9, 1.1, 0.5))
    row("DiffDriveKinematics.desaturate", lambda: dd.desaturate(dd_wheels, 1.0),
        wpi.get("dd desaturate"), None, lambda: diffdrive.desaturate(0.9, 1.1, 1.0))
    row("MecanumKinematics.inverse", lambda: mk.inverse(twist_xy), wpi.get("m inverse"),
        lambda: hand_mecanum_inverse(1.0, 0.3, 0.4),
        lambda: mecanum.inverse_kinematics(1.0, 0.3, 0.4, geo))
    row("MecanumKinematics.forward", lambda: mk.forward(m_wheels), wpi.get("m forward"), None,
        lambda: mecanum.forward_kinematics(np.asarray(m_wheels) / geo.wheel_radius, geo))
    row("MecanumKinematics.desaturate", lambda: mk.desaturate(m_wheels, 1.0),
        wpi.get("m desaturate"), None, lambda: mecanum.desaturate(list(m_wheels), 1.0))
    row("AckermannKinematics.inverse", lambda: car.inverse(twist))
    row("AckermannKinematics.forward", lambda: car.forward(car_wheels))
    row("AckermannKinematics.desaturate", lambda: car.desaturate(car_wheels, 1.0))
    row("RoverKinematics.inverse", lambda: rov.inverse(twist))
    row("RoverKinematics.forward", lambda: rov.forward(rov_wheels))
    row("RoverKinematics.desaturate", lambda: rov.desaturate(rov_wheels, 0.5))

    def dd_update() -> object:
        d = tick()
        return odo.update(d, 1.1 * d)

    def dd_gyro_update() -> object:
        d = tick()
        return odo_gyro.update(d, 1.1 * d, heading=0.1 * d)

    def dd_cov_update() -> object:
        d = tick()
        return odo_cov.update(d, 1.1 * d)

    def hand_update() -> None:
        d = 0.001
        hand_midpoint(d, 1.1 * d)

    def chapter_update() -> object:
        return odometry.integrate_si([0.001], [0.0011], 0.5, pose=(0.0, 0.0, 0.0))

    row("DiffDriveOdometry.update", dd_update, None, hand_update, chapter_update)
    row("DiffDriveOdometry.update (gyro heading)", dd_gyro_update, wpi.get("dd odo"))

    def m_update() -> object:
        d = tick()
        return m_odo.update(d, 1.1 * d, d, 1.1 * d)

    def c_update() -> object:
        return c_odo.update(tick(), 0.2)

    row("MecanumOdometry.update", m_update, wpi.get("m odo"))
    row("AckermannOdometry.update", c_update)

    def chapter_covariance() -> object:
        from wheelkin.odometry_uncertainty import propagate_covariance

        return propagate_covariance((0.0, 0.0, 0.0), np.zeros((3, 3)), 0.001, 0.0011, 0.5,
                                    1e-6, 1e-6)

    def m_cov_update() -> object:
        d = tick()
        return m_odo_cov.update(d, 1.1 * d, d, 1.1 * d)

    row("DiffDriveOdometry.update, covariance", dd_cov_update, None, None,
        chapter_covariance, covariance=True)
    row("MecanumOdometry.update, covariance", m_cov_update, covariance=True)
    row("AckermannOdometry.update, covariance", lambda: c_odo_cov.update(tick(), 0.2),
        covariance=True)
    return rows


def main() -> int:
    """Time every row, check the budget, write the section ``objects`` of RESULTS.md."""
    columns = ["wheelkin object", "WPILib", "hand-written", "chapter function"]
    lines = ["| call | " + " | ".join(f"{c} (us)" for c in columns) + " | object / WPILib "
             "| budget |", "| --- |" + " ---: |" * (len(columns) + 1) + " --- |"]
    failures = []
    for what, calls, covariance in cases():
        times = {c: (per_call_us(fn) if fn is not None else None) for c, fn in calls.items()}
        ours, theirs = times["wheelkin object"], times["WPILib"]
        assert ours is not None
        limit = COVARIANCE_BUDGET_US if covariance else BUDGET_US
        ok = ours < limit and (theirs is None or ours <= 3.0 * theirs)
        if not ok:
            failures.append(what)
        ratio = f"{ours / theirs:.1f}x" if theirs else "-"
        cells = [f"{t:.2f}" if t is not None else "-" for t in times.values()]
        lines.append(f"| `{what}` | " + " | ".join(cells) + f" | {ratio} | "
                     f"{'met' if ok else 'MISSED'} (< {limit:g} us"
                     f"{', <= 3x WPILib' if theirs else ''}) |")
        print(lines[-1], flush=True)
    try:
        from importlib.metadata import PackageNotFoundError, version

        wpi = f"robotpy-wpimath {version('robotpy-wpimath')}"
    except PackageNotFoundError:
        wpi = "robotpy-wpimath not installed (pip install -r requirements-bench.txt)"
    verdict = "met by every call" if not failures else "MISSED: " + ", ".join(failures)
    begin, end = markers("objects")
    body = "\n".join(lines)
    section = (f"{begin}\n## Loop objects: per-call cost (`benchmarks/objects.py`)\n\n"
               f"Machine: {cpu()}; {wpi}. One call at a time (`timeit`, {NUMBER} calls a "
               f"batch); per round the median of {BATCHES} batches, the figure the minimum "
               f"over {ROUNDS} rounds (the 2 cores are shared with other work). \"-\": no "
               f"equivalent. The chapter function is the validated array function the object "
               f"replaces in a loop.\n\n{body}\n\n"
               f"Budget: {verdict}.\n{end}")
    write_section("objects", section)
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
