"""The loop objects (wheelkin.kinematics, wheelkin.odometers) against independent values.

Each object is checked against the chapter function it stands for (a separate, vectorised
implementation with its own tests), against hand calculations and closed forms (a quarter
circle, the OSR software's spin-in-place angles), and against a user's program type-checked
with ``mypy --strict``. The bad-input part calls every method with strings (numeric ones
included), NaN, infinities, booleans, None and overflowing values.
"""

from __future__ import annotations

import math
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from wheelkin import carlike, diffdrive, mecanum, odometry, rover
from wheelkin.frames import Pose, Twist, field_relative, integrate_twist, to_field_relative
from wheelkin.kinematics import (
    AckermannKinematics,
    AckermannWheels,
    DiffDriveKinematics,
    DiffDriveWheelSpeeds,
    MecanumKinematics,
    MecanumWheelSpeeds,
    RoverKinematics,
    VehicleKinematics,
)
from wheelkin.odometers import AckermannOdometry, DiffDriveOdometry, MecanumOdometry, Odometry
from wheelkin.odometry_uncertainty import propagate_covariance

RNG = np.random.default_rng(23)
G = mecanum.MecanumGeometry(half_wheelbase=0.2, half_track=0.15, wheel_radius=0.05,
                            roller_angle=1.0)


def test_diff_drive_matches_the_chapter_functions():
    kin = DiffDriveKinematics(track_width=0.37)
    for v, w in RNG.uniform(-3, 3, (50, 2)):
        wheels = kin.inverse(Twist(v, 0.0, w))
        assert wheels == pytest.approx(diffdrive.wheel_speeds(v, w, 0.37), abs=1e-12)
        back = kin.forward(wheels)
        assert (back.vx, back.omega) == pytest.approx(diffdrive.body_twist(*wheels, 0.37))
    # by hand: 1 m/s and 2 rad/s on W = 0.5 m: 1 -+ 2 * 0.25
    assert DiffDriveKinematics(track_width=0.5).inverse((1.0, 0.0, 2.0)) == (0.5, 1.5)
    assert kin.desaturate(DiffDriveWheelSpeeds(1.0, -3.0), 2.0) == pytest.approx(
        diffdrive.desaturate(1.0, -3.0, 2.0))


def test_mecanum_matches_the_chapter_functions_times_the_wheel_radius():
    kin = MecanumKinematics(G, centre_of_rotation=(0.1, -0.05))
    for vx, vy, w in RNG.uniform(-2, 2, (50, 3)):
        rates = mecanum.inverse_kinematics(vx, vy, w, G, centre_of_rotation=(0.1, -0.05))
        wheels = kin.inverse(Twist(vx, vy, w))
        np.testing.assert_allclose(wheels, rates * G.wheel_radius, atol=1e-12)
    plain = MecanumKinematics(G)
    for rates in RNG.uniform(-20, 20, (50, 4)):
        twist = plain.forward(MecanumWheelSpeeds(*(rates * G.wheel_radius)))
        np.testing.assert_allclose(twist, mecanum.forward_kinematics(rates, G), atol=1e-12)
    speeds = MecanumWheelSpeeds(0.5, 1.0, -4.0, 2.0)
    np.testing.assert_allclose(plain.desaturate(speeds, 2.0),
                               mecanum.desaturate(list(speeds), 2.0))


def test_car_matches_ackermann_angles_and_refuses_what_a_car_cannot_do():
    car = AckermannKinematics(wheelbase=2.5, track_width=1.5)
    for radius in (5.0, -7.5, 40.0, 1.0):
        v = 3.0
        wheels = car.inverse(Twist(v, 0.0, v / radius))
        expected = carlike.ackermann_angles(radius, wheelbase=2.5, track_width=1.5)
        assert (wheels.left_angle, wheels.right_angle) == pytest.approx(tuple(expected))
        assert wheels.rear_left == pytest.approx(v * (radius - 0.75) / radius)
        assert car.forward(wheels) == pytest.approx((v, 0.0, v / radius))
    assert car.inverse(Twist(0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="omega"):
        car.inverse(Twist(0.0, 0.0, 1.0))  # no turn on the spot
    with pytest.raises(ValueError, match="vy"):
        car.inverse(Twist(1.0, 0.1, 0.0))
    with pytest.raises(ValueError, match="omega"):
        car.inverse(Twist(1.0, 0.0, 2.0))  # R = 0.5 m: inside the track
    slow = car.desaturate(AckermannWheels(0.3, 0.2, 4.0, 6.0), 3.0)
    assert slow == pytest.approx((0.3, 0.2, 2.0, 3.0))
    with pytest.raises(TypeError):
        AckermannKinematics(2.5, 1.5)  # type: ignore[misc]  # the lengths are keyword-only


def test_rover_matches_wheel_commands_and_spins_as_the_osr_software_does():
    rov = RoverKinematics(rover.OSR_GEOMETRY_SI)
    for v, w in ((0.3, 0.1), (-0.2, 0.05), (0.4, -0.3), (0.5, 0.0)):
        cmd = rover.wheel_commands(v, w, rover.OSR_GEOMETRY_SI)
        wheels = rov.inverse(Twist(v, 0.0, w))
        np.testing.assert_allclose(wheels[:6], cmd.wheel_speeds, atol=1e-12)
        np.testing.assert_allclose(wheels[6:], cmd.steering_angles, atol=1e-12)
        np.testing.assert_allclose(rov.forward(wheels), (v, 0.0, w), atol=1e-12)
    # spin in place: the OSR's calculate_rotate_in_place_cmd steers the front corners to
    # atan(d3/d1) and the back ones to atan(d2/d1) (its sign: positive to the right), and
    # drives the corners at hypot(d1, d3) * omega, the middles at d4 * omega
    g = rover.OSR_PARAMS_GEOMETRY
    spin = RoverKinematics(g).inverse(Twist(0.0, 0.0, 0.8))
    assert spin.steer_lf == pytest.approx(-math.atan(g.d3 / g.d1))
    assert spin.steer_lb == pytest.approx(math.atan(g.d2 / g.d1))
    assert abs(spin.lf) == pytest.approx(math.hypot(g.d1, g.d3) * 0.8)
    assert abs(spin.lm) == pytest.approx(g.d4 * 0.8)
    assert spin.rm == pytest.approx(-spin.lm)
    with pytest.raises(ValueError, match="omega"):
        RoverKinematics(g, turn_in_place=False).inverse(Twist(0.0, 0.0, 0.8))
    with pytest.raises(ValueError, match="omega"):
        RoverKinematics(g).inverse(Twist(0.01, 0.0, 0.8))  # too tight, not a spin


def test_osr_params_geometry_is_the_document_rounded_to_the_millimetre():
    si = rover.OSR_GEOMETRY_SI
    for name in ("d1", "d2", "d3", "d4"):
        assert getattr(rover.OSR_PARAMS_GEOMETRY, name) == pytest.approx(
            getattr(si, name), abs=6e-4)
    with pytest.raises(TypeError):
        rover.RoverGeometry(0.184, 0.267, 0.267, 0.2556)  # type: ignore[call-arg]


def test_every_kinematics_answers_the_one_interface():
    objects: list[VehicleKinematics] = [  # type: ignore[type-arg]
        DiffDriveKinematics(track_width=0.5), MecanumKinematics(G),
        AckermannKinematics(wheelbase=2.5, track_width=1.5),
        RoverKinematics(rover.OSR_PARAMS_GEOMETRY)]
    for kin in objects:
        twist = Twist(0.4, 0.0, 0.1)
        wheels = kin.inverse(twist)
        np.testing.assert_allclose(kin.forward(wheels), twist, atol=1e-12)
        limited = kin.desaturate(wheels, 0.1)
        speeds = [abs(s) for name, s in zip(wheels._fields, limited, strict=True)
                  if "angle" not in name and not name.startswith("steer")]
        assert max(speeds) == pytest.approx(0.1)


def test_diff_drive_odometry_is_integrate_si_and_the_books_covariance_step():
    kin = DiffDriveKinematics(track_width=0.4)
    steps = RNG.uniform(-0.02, 0.05, (200, 2))
    path = odometry.integrate_si(steps[:, 0], steps[:, 1], 0.4, pose=(1.0, -2.0, 0.3))
    odo = DiffDriveOdometry(kin, Pose(1.0, -2.0, 0.3), wheel_noise=(1e-5, 2e-5))
    pose, cov = np.array([1.0, -2.0, 0.3]), np.zeros((3, 3))
    totals = np.cumsum(steps, axis=0)
    for (left, right), (dl, dr), expected in zip(totals, steps, path, strict=True):
        got = odo.update(float(left), float(right))
        np.testing.assert_allclose(got, expected, atol=1e-12)
        pose, cov = propagate_covariance(pose, cov, dl, dr, 0.4, 1e-5, 2e-5)
    np.testing.assert_allclose(odo.covariance, cov, rtol=1e-9, atol=1e-18)
    assert odo.twist.vy == 0.0 and odo.twist.omega == pytest.approx(
        (steps[-1, 1] - steps[-1, 0]) / 0.4)
    odo.reset(Pose(0.0, 0.0, 0.0), (5.0, 5.0))
    assert not np.any(odo.covariance)
    assert odo.update(5.5, 5.5) == Pose(0.5, 0.0, 0.0)


def test_gyro_heading_overrides_the_wheels_and_counts_are_scaled():
    kin = DiffDriveKinematics(track_width=0.5)
    odo = DiffDriveOdometry(kin, Pose(0.0, 0.0, 1.0), heading=0.25,
                            distance_per_count=0.001)
    pose = odo.update(1000, 1000, heading=0.25 + math.pi / 2)  # gyro: a quarter turn
    # the arc of 1 m that turns by pi/2 from heading 1.0: chord sqrt(2) * (2/pi)
    chord = 2.0 * math.sin(math.pi / 4) / (math.pi / 2)
    direction = 1.0 + math.pi / 4
    assert pose == pytest.approx((chord * math.cos(direction), chord * math.sin(direction),
                                  1.0 + math.pi / 2))
    with pytest.raises(ValueError, match="heading"):
        DiffDriveOdometry(kin).update(0.1, 0.1, heading=0.3)  # no gyro reading at reset


def test_mecanum_odometry_is_the_exact_twist_integration():
    kin = MecanumKinematics(G)
    odo = MecanumOdometry(kin, wheel_noise=1e-6)
    twists = RNG.uniform(-1, 1, (40, 3))
    poses = integrate_twist(twists, 0.05)
    totals = np.zeros(4)
    for twist, expected in zip(twists, poses[1:], strict=True):
        totals += np.asarray(kin.inverse(Twist(*twist))) * 0.05
        got = odo.update(*(float(t) for t in totals))
        assert got[:2] == pytest.approx(expected[:2], abs=1e-12)
        assert math.remainder(got[2] - expected[2], 2 * math.pi) == pytest.approx(0, abs=1e-12)
    assert odo.covariance is not None and np.all(np.linalg.eigvalsh(odo.covariance) >= -1e-18)


def test_car_odometry_closes_a_circle():
    car = AckermannKinematics(wheelbase=2.5, track_width=1.5)
    odo = AckermannOdometry(car)
    circle = 2 * math.pi * 5.0
    for k in range(1, 101):
        pose = odo.update(circle * k / 100, math.atan(2.5 / 5.0))
    assert pose == pytest.approx((0.0, 0.0, 2 * math.pi), abs=1e-9)  # not wrapped
    with pytest.raises(ValueError, match="steering_angle"):
        AckermannOdometry(AckermannKinematics(wheelbase=2.5, track_width=1.5,
                                              max_steering_angle=0.5)).update(1.0, 0.6)


# ------------------------------------------------------------------ bad input on every method

BAD = {"nan": math.nan, "inf": math.inf, "str": "abc", "numeric-str": "1", "None": None,
       "True": True}


def _objects():
    dd = DiffDriveKinematics(track_width=0.5)
    mk = MecanumKinematics(G)
    car = AckermannKinematics(wheelbase=2.5, track_width=1.5)
    rov = RoverKinematics(rover.OSR_PARAMS_GEOMETRY)
    return {
        "DiffDriveKinematics": (dd, [0.5, 0.0, 0.2], dd.inverse(Twist(0.5, 0.0, 0.2))),
        "MecanumKinematics": (mk, [0.5, 0.1, 0.2], mk.inverse(Twist(0.5, 0.1, 0.2))),
        "AckermannKinematics": (car, [0.5, 0.0, 0.05], car.inverse(Twist(0.5, 0.0, 0.05))),
        "RoverKinematics": (rov, [0.5, 0.0, 0.05], rov.inverse(Twist(0.5, 0.0, 0.05))),
    }


@pytest.mark.parametrize("label", list(BAD))
@pytest.mark.parametrize("name", ["DiffDriveKinematics", "MecanumKinematics",
                                  "AckermannKinematics", "RoverKinematics"])
def test_kinematics_methods_refuse_bad_numbers(name, label):
    kin, twist, wheels = _objects()[name]
    bad = BAD[label]
    for i in range(3):
        args = list(twist)
        args[i] = bad
        with pytest.raises((ValueError, TypeError), match=r"vx|vy|omega|twist"):
            kin.inverse(tuple(args))
    for i, field in enumerate(wheels._fields):
        values = list(wheels)
        values[i] = bad
        with pytest.raises((ValueError, TypeError), match=rf"{field}|wheels"):
            kin.forward(type(wheels)(*values))
        with pytest.raises((ValueError, TypeError), match=rf"{field}|wheels"):
            kin.desaturate(type(wheels)(*values), 1.0)
    with pytest.raises((ValueError, TypeError), match="max_speed"):
        kin.desaturate(wheels, bad)
    if isinstance(bad, str | bool) or bad is None:  # a TypeError, and still a ValueError
        with pytest.raises(TypeError):
            kin.inverse((0.5, 0.0, bad))


@pytest.mark.parametrize("name", ["DiffDriveKinematics", "MecanumKinematics",
                                  "AckermannKinematics", "RoverKinematics"])
def test_overflowing_results_are_errors_naming_the_input(name):
    kin, _, wheels = _objects()[name]
    huge = {"DiffDriveKinematics": Twist(1.7e308, 0.0, -1.7e308),
            "MecanumKinematics": Twist(1.7e308, 0.0, -1.7e308),
            "AckermannKinematics": Twist(1.7e308, 0.0, 1.7e307),
            "RoverKinematics": Twist(1.75e308, 0.0, 0.875e308)}[name]
    with pytest.raises(ValueError, match="twist"):
        kin.inverse(huge)
    if name in ("DiffDriveKinematics", "MecanumKinematics"):
        with pytest.raises(ValueError, match="wheels"):
            kin.forward(type(wheels)(*[1e308 if i % 2 else -1e308
                                       for i in range(len(wheels))]))


def a_none(value: object) -> bool:
    return value is None  # heading=None means "no gyro", a valid call


@pytest.mark.parametrize("label", list(BAD))
def test_odometry_updates_refuse_bad_numbers(label):
    bad = BAD[label]
    dd = DiffDriveOdometry(DiffDriveKinematics(track_width=0.5), heading=0.0)
    mk = MecanumOdometry(MecanumKinematics(G))
    car = AckermannOdometry(AckermannKinematics(wheelbase=2.5, track_width=1.5))
    for call, names in ((lambda a: dd.update(a, 0.1), "left"),
                        (lambda a: dd.update(0.1, a), "right"),
                        *([] if a_none(bad) else
                          [(lambda a: dd.update(0.1, 0.1, heading=a), "heading")]),
                        (lambda a: mk.update(0.1, 0.1, a, 0.1), "rl"),
                        (lambda a: car.update(a, 0.1), "distance"),
                        (lambda a: car.update(0.1, a), "steering_angle")):
        with pytest.raises((ValueError, TypeError), match=names):
            call(bad)
    with pytest.raises(ValueError, match="left, right"):
        dd.update(1e308, -1e308)  # the pose overflows


def test_constructors_refuse_bad_geometry_and_swapped_kinds():
    with pytest.raises(TypeError, match="kinematics"):
        DiffDriveOdometry(MecanumKinematics(G))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="geometry"):
        MecanumKinematics((0.2, 0.15, 0.05))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="track_width"):
        DiffDriveKinematics(track_width="0.5")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="wheel_noise"):
        DiffDriveOdometry(DiffDriveKinematics(track_width=0.5), wheel_noise=(1e-6,))
    assert issubclass(DiffDriveOdometry, Odometry)


def test_numeric_strings_are_refused_by_the_functions_too():
    with pytest.raises(TypeError, match="v"):
        diffdrive.wheel_speeds("1", 0, 0.5)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="track_width"):
        diffdrive.wheel_speeds(1.0, 0.0, "0.5")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="radius"):
        carlike.ackermann_angles(["2"], wheelbase=2.5, track_width=1.5)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="v"):  # a TypeError is a ValueError too
        diffdrive.wheel_speeds(None, 0, 0.5)  # type: ignore[arg-type]


# ------------------------------------------------------------------ a builder's first minutes

def test_submodules_load_on_attribute_access():
    code = ("import wheelkin, sys; assert 'wheelkin.odometry' not in sys.modules; "
            "print(wheelkin.odometry.integrate_si.__name__, wheelkin.kinematics.__name__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.split() == ["integrate_si", "wheelkin.kinematics"]


def test_field_relative_rotates_by_the_heading():
    for heading in RNG.uniform(-7, 7, 20):
        twist = Twist(*RNG.uniform(-2, 2, 3))
        body = field_relative(twist, heading)
        # the body velocity rotated into the world is the field velocity
        c, s = math.cos(heading), math.sin(heading)
        assert (c * body.vx - s * body.vy, s * body.vx + c * body.vy) == pytest.approx(
            (twist.vx, twist.vy))
        assert to_field_relative(body, heading) == pytest.approx(twist)


def test_umbmark_docstring_text_agrees_with_its_example():
    from wheelkin.odometry_uncertainty import umbmark_correction

    _, e_b = umbmark_correction([-0.08, -0.08], [-0.08, 0.08], 4.0, 0.34)
    percent = f"{(e_b - 1.0) * 100:.2f} %"
    assert percent == "0.64 %"
    assert f"the true track {percent} larger" in " ".join(umbmark_correction.__doc__.split())


# ------------------------------------------------------------------ mypy --strict, a user's loop

USER_PROGRAM = '''
    """A robot builder's loop, typed, with no casts and no isinstance."""
    import math

    from wheelkin.frames import Pose, Twist, field_relative
    from wheelkin.kinematics import DiffDriveKinematics, DiffDriveWheelSpeeds, MecanumKinematics
    from wheelkin.mecanum import MecanumGeometry, forward_kinematics, inverse_kinematics
    from wheelkin.odometers import DiffDriveOdometry, MecanumOdometry


    def wheel_command(kin: DiffDriveKinematics, speed: float, turn: float) -> tuple[float, float]:
        wheels: DiffDriveWheelSpeeds = kin.desaturate(kin.inverse(Twist(speed, 0.0, turn)), 1.2)
        return wheels.left, wheels.right


    def loop() -> float:
        kin = DiffDriveKinematics(track_width=0.5)
        odo = DiffDriveOdometry(kin, Pose(0.0, 0.0, 0.0), heading=0.0, wheel_noise=1e-6)
        total_left = total_right = 0.0
        for k in range(10):
            left, right = wheel_command(kin, 0.5, 0.1 * k)
            total_left += 0.01 * left
            total_right += 0.01 * right
            pose: Pose = odo.update(total_left, total_right, heading=0.001 * k)
        heading: float = pose.theta
        twist: Twist = odo.twist
        spread: float = 0.0 if odo.covariance is None else float(odo.covariance[2, 2])
        base = MecanumKinematics(MecanumGeometry(half_wheelbase=0.2, half_track=0.15,
                                                 wheel_radius=0.05))
        fl: float = base.inverse(field_relative(Twist(0.3, 0.2, 0.0), heading)).fl
        mecanum_odo = MecanumOdometry(base)
        x: float = mecanum_odo.update(fl, fl, fl, fl).x
        rates = inverse_kinematics(Twist(0.3, 0.2, 0.1), base.geometry)
        same = inverse_kinematics(0.3, 0.2, 0.1, base.geometry)
        back: Twist = forward_kinematics([float(r) for r in rates], base.geometry)
        vy: float = back.vy + float(same[0] - rates[0])
        return heading + twist.omega + spread + x + vy + math.pi
'''


def test_a_users_loop_passes_mypy_strict(tmp_path):
    program = tmp_path / "robot_loop.py"
    program.write_text(textwrap.dedent(USER_PROGRAM))
    done = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental",
                           "--cache-dir", str(tmp_path / ".mypy_cache"), str(program)],
                          capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    # and it runs
    namespace: dict = {}
    exec(compile(program.read_text(), str(program), "exec"), namespace)
    assert math.isfinite(namespace["loop"]())


# ------------------------------------------------- mypy --strict, the array-or-scalar functions

ARRAY_PROGRAM = '''
    """A builder's typed code over the formula functions: a float in gives a float, a Pose (or
    a tuple of three numbers) gives a Pose, an array gives an array; no casts, no isinstance."""
    import numpy as np
    from numpy.typing import NDArray

    from wheelkin import carlike, mecanum, odometry, rover, units
    from wheelkin.frames import (Pose, Twist, compose, inverse, relative, se2_exp, se2_log,
                                 wrap_angle)


    def one() -> float:
        heading: float = wrap_angle(7.0)
        metres: float = units.to_si(12.0, "in")
        curvature: float = carlike.pure_pursuit_curvature(1.0, 0.5)
        rim: float = mecanum.circle_speed(2.0, 10.0)
        chord: float = odometry.chord_factor(0.1)
        command: float = rover.radius_to_command(100.0)
        end: Pose = compose(Pose(1.0, 2.0, 0.5), se2_exp(Twist(0.4, 0.0, 0.2), 0.1))
        back: Pose = relative((1.0, 2.0, 0.5), end)
        twist: Twist = se2_log(inverse(back))
        return heading + metres + curvature + rim + chord + command + end.theta + twist.omega


    def many() -> float:
        headings: NDArray[np.float64] = wrap_angle(np.linspace(-7.0, 7.0, 5))
        metres: NDArray[np.float64] = units.to_si(np.ones(3), "in")
        curvature: NDArray[np.float64] = carlike.pure_pursuit_curvature(np.ones(3), 0.5)
        poses: NDArray[np.float64] = compose(np.zeros((4, 3)), Pose(1.0, 0.0, 0.1))
        twists: NDArray[np.float64] = se2_log(relative(poses, np.zeros((4, 3))))
        return float(headings.sum() + metres.sum() + curvature.sum() + twists.sum())
'''

#: Programs that misuse what comes back: each must fail mypy --strict (with the error named).
MISUSES = {
    "an array is not a float": (
        "from wheelkin.frames import wrap_angle\nimport numpy as np\n"
        "x: float = wrap_angle(np.zeros(3))\n", "variable has type \"float\""),
    "a Pose has no omega": (
        "from wheelkin.frames import Pose, compose\n"
        "w: float = compose(Pose(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)).omega\n",
        "\"Pose\" has no attribute \"omega\""),
    "a float has no x": (
        "from wheelkin import units\nx = units.to_si(1.0, 'm').x\n", "\"float\" has no attribute \"x\""),
}


def _mypy_strict(tmp_path, name: str, source: str) -> subprocess.CompletedProcess[str]:
    program = tmp_path / f"{name}.py"
    program.write_text(source)
    return subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental",
                           "--cache-dir", str(tmp_path / ".mypy_cache"), str(program)],
                          capture_output=True, text=True, cwd=tmp_path)


def test_the_array_functions_pass_mypy_strict(tmp_path):
    source = textwrap.dedent(ARRAY_PROGRAM)
    done = _mypy_strict(tmp_path, "array_user", source)
    assert done.returncode == 0, done.stdout + done.stderr
    namespace: dict = {}
    exec(compile(source, "array_user.py", "exec"), namespace)
    assert math.isfinite(namespace["one"]()) and math.isfinite(namespace["many"]())


@pytest.mark.parametrize("case", sorted(MISUSES))
def test_a_misused_return_type_fails_mypy_strict(tmp_path, case):
    source, named = MISUSES[case]
    done = _mypy_strict(tmp_path, "misuse", source)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "error:" in done.stdout and named in done.stdout, done.stdout
