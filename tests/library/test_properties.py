"""Properties of the whole library, swept across every vehicle, unit and frame at once.

The chapter test files check each module against sympy, hand calculations and the sources;
this file checks that the library as a whole keeps the symmetries any kinematics must have,
whatever the vehicle:

- inverse after forward is the identity (batches of twists, every converter both ways, every
  pair of units, paths driven back);
- mirror symmetry: a left turn mirrors a right turn for every vehicle, read off the wheel
  positions (no wheel order assumed), and in every unit system of the differential drive;
- scaling: doubling the speed doubles every wheel speed, for every vehicle and formula;
- odometry: the increments of a closed path close, exactly; a loop driven in the sandbox
  closes to within what its encoders can resolve.

Hypothesis runs derandomised (a fixed sequence of examples, no database), so the file gives
the same verdict on every run; ``max_examples`` is kept modest so it runs in seconds.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from wheelkin import diffdrive as dd
from wheelkin import frames, mecanum, rover, unified, units
from wheelkin import odometry as odo
from wheelkin.sandbox import (
    LAB_ROBOT,
    MECANUM_ROBOT,
    OPEN_SOURCE_ROVER,
    RADON_ULZER,
    World,
    ideal_commands,
)

SETTINGS = settings(derandomize=True, database=None, max_examples=60, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])

speed = st.floats(-5.0, 5.0, allow_nan=False)
rate = st.floats(-4.0, 4.0, allow_nan=False)
twist = st.tuples(speed, speed, rate)
batch = st.lists(twist, min_size=1, max_size=12).map(np.array)
length = st.floats(0.01, 2.0)
angle = st.floats(-math.pi, math.pi)
roller = st.floats(0.2, math.pi / 2 - 0.2)  # the library's range: (0, pi/2)

SANDBOX_VEHICLES = {"differential drive": RADON_ULZER, "skid steer": LAB_ROBOT,
                    "mecanum": MECANUM_ROBOT, "rover": OPEN_SOURCE_ROVER}
MIRROR = np.array([1.0, -1.0, -1.0])  # (vx, vy, omega) -> (vx, -vy, -omega); pose likewise


def close(a, b, scale=1.0, tol=1e-9):
    np.testing.assert_allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float),
                               rtol=tol, atol=tol * scale)


# --------------------------------------------------------------------------------------------
# Inverse after forward
# --------------------------------------------------------------------------------------------

@SETTINGS
@given(batch, length, length, length, roller)
def test_mecanum_forward_after_inverse_is_the_identity_on_a_batch(twists, r, a, b, gamma):
    g = mecanum.MecanumGeometry(wheel_radius=r, half_wheelbase=a, half_track=b, roller_angle=gamma)
    rates = mecanum.inverse_kinematics(twists[:, 0], twists[:, 1], twists[:, 2], g)
    assert rates.shape == (len(twists), 4)
    scale = 1 + np.abs(twists).max() * (1 + a + b)
    close(mecanum.forward_kinematics(rates, g), twists, scale)


@SETTINGS
@given(batch, length)
def test_diffdrive_body_twist_inverts_wheel_speeds_on_a_batch(twists, width):
    v, omega = twists[:, 0], twists[:, 2]
    back = np.column_stack(dd.body_twist(*dd.wheel_speeds(v, omega, width), width))
    close(back, np.column_stack([v, omega]), 1 + np.abs(twists).max())
    # ... and the skid steer's four wheels, read back through its two sides
    back4 = np.column_stack(dd.skid_steer_body_twist(*dd.skid_steer_wheel_speeds(v, omega, width),
                                                     width))
    close(back4, np.column_stack([v, omega]), 1 + np.abs(twists).max())


@SETTINGS
@given(st.lists(st.tuples(st.floats(-4e3, 4e3), st.floats(-8e3, 8e3)), min_size=1, max_size=8),
       st.floats(20.0, 400.0), st.floats(500.0, 2e4))
def test_encoder_units_are_the_si_formula_in_other_units(points, base_mm, steps_per_m):
    """wheel_speeds_steps (steps/s, mrad/s, mm) is wheel_speeds (m/s, rad/s, m) converted, and
    body_twist_steps inverts it."""
    v_steps, omega_mrad = np.array(points).T
    left, right = dd.wheel_speeds_steps(v_steps, omega_mrad, base_mm, steps_per_m)
    si_left, si_right = dd.wheel_speeds(v_steps / steps_per_m,
                                        units.to_si(omega_mrad, "mrad/s"),
                                        units.to_si(base_mm, "mm"))
    scale = 1 + np.abs(left).max() + np.abs(right).max()
    close(left, si_left * steps_per_m, scale)
    close(right, si_right * steps_per_m, scale)
    close(np.column_stack(dd.body_twist_steps(left, right, base_mm, steps_per_m)),
          np.column_stack([v_steps, omega_mrad]), scale)


_POSE = st.tuples(st.floats(-50, 50), st.floats(-50, 50), angle)
#: Every converter of a source's frame: (name, ours -> source, source -> ours).
CONVERTERS = [
    ("mecanum document twist", lambda p: frames.ours_to_mecanum_doc_twist(p),
     lambda s: frames.mecanum_doc_twist_to_ours(*s.T)),
    ("mecanum document pose", lambda p: frames.ours_to_mecanum_doc_pose(p),
     lambda s: frames.mecanum_doc_pose_to_ours(*s.T)),
    ("firmware pose", lambda p: frames.ours_to_firmware_pose(p),
     lambda s: frames.firmware_pose_to_ours(*s.T)),
    ("lab pose", lambda p: frames.ours_to_lab_pose(p),
     lambda s: frames.lab_pose_to_ours(*s.T)),
]


def _same_pose(a, b, scale=1.0) -> None:
    """Positions equal; headings equal as angles (wrapping is each converter's own choice)."""
    close(a[:, :2], b[:, :2], scale)
    close(frames.wrap_angle(a[:, 2] - b[:, 2]), 0.0, scale=1.0)


@pytest.mark.parametrize(("name", "to_source", "to_ours"), CONVERTERS,
                         ids=[c[0] for c in CONVERTERS])
@SETTINGS
@given(poses=st.lists(_POSE, min_size=1, max_size=10).map(np.array))
def test_frame_converters_round_trip_both_ways_on_a_batch(name, to_source, to_ours, poses):
    scale = 1e3 * (1 + np.abs(poses).max())  # the firmware's millimetres
    _same_pose(to_ours(np.asarray(to_source(poses))), poses, scale)
    source = np.asarray(to_source(poses))
    _same_pose(np.asarray(to_source(np.asarray(to_ours(source)))), source, scale)


@SETTINGS
@given(st.lists(st.floats(-1e4, 1e4).filter(lambda r: abs(r) > 1e-3), min_size=1,
                max_size=10).map(np.array))
def test_rover_radius_and_heading_converters_round_trip_both_ways(values):
    close(frames.ours_to_rover_radius(frames.rover_radius_to_ours(values)), values, 1e4)
    close(frames.rover_radius_to_ours(frames.ours_to_rover_radius(values)), values, 1e4)
    headings = frames.wrap_angle(values)
    close(frames.wrap_angle(frames.ours_to_mecanum_doc_heading(
        frames.mecanum_doc_heading_to_ours(headings)) - headings), 0.0)


UNIT_PAIRS = [(a, b) for a, b in itertools.permutations(sorted(units.UNITS), 2)
              if units.UNITS[a][1] == units.UNITS[b][1]]


@pytest.mark.parametrize(("a", "b"), UNIT_PAIRS, ids=[f"{a}->{b}" for a, b in UNIT_PAIRS])
def test_every_pair_of_units_converts_there_and_back(a, b):
    values = np.array([-1234.5, -1.0, -1e-6, 0.0, 0.3, 7.0, 2.5e5])
    there = units.convert(values, a, b)
    close(there, units.from_si(units.to_si(values, a), b), 1e-12)  # one path through SI
    close(units.convert(there, b, a), values, 1e-9, tol=1e-12)


@SETTINGS
@given(st.lists(twist, min_size=1, max_size=20).map(np.array), st.floats(0.01, 1.0), _POSE)
def test_a_path_driven_back_returns_to_its_start(twists, dt, start):
    """Driving the twists backwards in reverse order undoes the path (frames.integrate_twist:
    exact SE(2) steps)."""
    out = frames.integrate_twist(twists, dt, start)
    back = frames.integrate_twist(-twists[::-1], dt, out[-1])
    _same_pose(back[-1:], np.array([start]), scale=1 + 5 * len(twists) * dt)


@SETTINGS
@given(st.lists(st.tuples(st.integers(-300, 300), st.integers(-300, 300)), min_size=1,
                max_size=40).map(np.array), st.sampled_from(["exact", "midpoint"]))
def test_odometry_of_the_increments_driven_back_returns_to_the_start(inc, method):
    """Exact arcs and midpoint steps are time-reversible: the same wheel travel undone in
    reverse order brings the estimate back (Euler's steps are not)."""
    k, w = 8.043, 85.0
    out = odo.integrate(inc, k, w, method, pose=(12.0, -3.0, 0.4))
    back = odo.integrate(-inc[::-1], k, w, method, pose=tuple(out[-1]))
    _same_pose(back[-1:], np.array([[12.0, -3.0, 0.4]]), scale=1 + np.abs(inc).sum() / k)


# --------------------------------------------------------------------------------------------
# Mirror symmetry: a left turn mirrors a right turn, for every vehicle
# --------------------------------------------------------------------------------------------

def _partners(positions) -> list[int]:
    """For each wheel, the index of its mirror image across the body x axis."""
    pos = np.asarray(positions, dtype=float)
    out = []
    for x, y in pos:
        match = np.flatnonzero(np.all(np.isclose(pos, [x, -y], atol=1e-12), axis=1))
        assert match.size == 1, f"no mirror image of the wheel at ({x}, {y})"
        out.append(int(match[0]))
    return out


def _rolling_velocities(spec, twist_) -> np.ndarray:
    """Each driven wheel's rolling velocity r_w phi_i (cos, sin)(heading_i + delta_i), body frame:
    the same whether a steered wheel is turned by delta or by delta + pi and run backwards."""
    rates, steering = ideal_commands(spec, twist_)
    steer = dict(zip(spec.steered_names, steering, strict=True))
    out = []
    for wheel, phi in zip(spec.driven_wheels, rates, strict=True):
        direction = wheel.heading + steer.get(wheel.name, 0.0)
        out.append(wheel.wheel_radius * phi * np.array([math.cos(direction), math.sin(direction)]))
    return np.array(out)


@pytest.mark.parametrize("name", sorted(SANDBOX_VEHICLES))
@SETTINGS
@given(twist_=twist)
def test_every_vehicle_mirrors_a_left_turn_into_a_right_turn(name, twist_):
    spec = SANDBOX_VEHICLES[name]
    partner = _partners([w.position for w in spec.driven_wheels])
    u = _rolling_velocities(spec, twist_)
    mirrored = _rolling_velocities(spec, np.multiply(twist_, MIRROR))
    close(mirrored[partner], u * [1.0, -1.0], 1 + np.abs(u).max())


@SETTINGS
@given(batch, length, length, length, roller)
def test_mecanum_mirror_swaps_left_and_right_wheels_for_any_geometry(twists, r, a, b, gamma):
    g = mecanum.MecanumGeometry(wheel_radius=r, half_wheelbase=a, half_track=b, roller_angle=gamma)
    vx, vy, w = twists.T
    rates = mecanum.inverse_kinematics(vx, vy, w, g)
    mirrored = mecanum.inverse_kinematics(vx, -vy, -w, g)
    close(mirrored, rates[:, [1, 0, 3, 2]], 1 + np.abs(rates).max())  # FL<->FR, RL<->RR


@SETTINGS
@given(st.integers(-30000, 30000), st.integers(-30000, 30000),
       st.sampled_from(dd.INT32_METHODS))
def test_negating_omega_swaps_the_wheels_in_every_unit_system(v, omega, method):
    """SI, encoder units, the README as printed and the firmware's 32-bit integers: a turn to
    the right is the turn to the left with the wheels swapped; the int32 versions exactly,
    overflow and all (two's complement wraps symmetrically but at -2**31)."""
    base, enc = dd.RADON_ULZER_CONSTANTS.track_width_mm, dd.RADON_ULZER_CONSTANTS.steps_per_m
    for fn in (dd.wheel_speeds_steps, dd.wheel_speeds_steps_as_printed):
        left, right = fn(v, omega, base, enc)
        m_left, m_right = fn(v, -omega, base, enc)
        close([m_left, m_right], [right, left], 1 + abs(left) + abs(right))
    left, right, overflow = dd.wheel_speeds_steps_int32(v, omega, base, enc, method=method)
    m_left, m_right, m_overflow = dd.wheel_speeds_steps_int32(v, -omega, base, enc,
                                                              method=method)
    assert (m_left, m_right, m_overflow) == (right, left, overflow)
    fl, fr, rl, rr = dd.skid_steer_wheel_speeds(v / enc, omega / 1000, base / 1000)
    close(dd.skid_steer_wheel_speeds(v / enc, -omega / 1000, base / 1000), [fr, fl, rr, rl],
          1 + abs(fl) + abs(fr))


@SETTINGS
@given(st.floats(rover.min_turning_radius() + 1e-6, 1e4) | st.just(math.inf),
       st.floats(-100, 100))
def test_rover_body_twist_of_a_left_turn_mirrors_a_right_turn(radius, speed_):
    """The document's r > 0 turns right; r < 0 is its mirror image: the body twist mirrors to
    (vx, -vy, -omega) (its wheels: the every-vehicle test above)."""
    if math.isinf(radius):
        radius = -math.inf if speed_ < 0 else math.inf  # straight either way
    right = rover.document_twist(radius, speed_).as_array()
    left = rover.document_twist(-radius, speed_).as_array()
    close(left, right * MIRROR, 1 + abs(speed_))


@SETTINGS
@given(st.lists(twist, min_size=1, max_size=20).map(np.array), st.floats(0.01, 1.0))
def test_mirrored_twists_drive_the_mirrored_path(twists, dt):
    path = frames.integrate_twist(twists, dt)
    mirrored = frames.integrate_twist(twists * MIRROR, dt)
    _same_pose(mirrored, path * MIRROR, scale=1 + 5 * len(twists) * dt)


# --------------------------------------------------------------------------------------------
# Scaling: doubling the speed doubles every wheel speed
# --------------------------------------------------------------------------------------------

_G60 = mecanum.MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15, roller_angle=math.pi / 3)
#: Every formula from a body motion to wheel speeds: (name, fn(vx, vy, omega) -> array).
WHEEL_SPEED_FORMULAS = [
    ("rover, six wheels (document units)",
     lambda vx, vy, w: rover.wheel_speeds(40.0, 10 * vx)),  # a right turn, r = 40 in
    ("mecanum, 45-degree rollers",
     lambda vx, vy, w: mecanum.inverse_kinematics(vx, vy, w, mecanum.EXAMPLE_GEOMETRY)),
    ("mecanum, 60-degree rollers", lambda vx, vy, w: mecanum.inverse_kinematics(vx, vy, w, _G60)),
    ("differential drive (SI)", lambda vx, vy, w: np.array(dd.wheel_speeds(vx, w, 0.085))),
    ("differential drive (steps/s, mrad/s)",
     lambda vx, vy, w: np.array(dd.wheel_speeds_steps(vx * 8043, w * 1000, 85, 8043))),
    ("skid steer", lambda vx, vy, w: np.array(dd.skid_steer_wheel_speeds(vx, w, 0.12))),
    *[(f"unified model, {n}",
       lambda vx, vy, w, wheels=wheels: unified.wheel_rates(wheels, (vx, vy, w)))
      for n, wheels in [("differential drive", unified.diff_drive_wheels(0.085, 0.018)),
                        ("skid steer", unified.skid_steer_wheels(half_track=0.06, half_wheelbase=0.05, wheel_radius=0.04)),
                        ("mecanum", unified.mecanum_wheels(mecanum.EXAMPLE_GEOMETRY)),
                        ("rover", unified.rover_wheels(turning_radius=40.0 * units.INCH))]],
    *[(f"sandbox, {n}", lambda vx, vy, w, spec=spec: ideal_commands(spec, (vx, vy, w))[0])
      for n, spec in SANDBOX_VEHICLES.items()],
]


@pytest.mark.parametrize(("name", "formula"), WHEEL_SPEED_FORMULAS,
                         ids=[f[0] for f in WHEEL_SPEED_FORMULAS])
@SETTINGS
@given(twist_=twist)
def test_doubling_the_speed_doubles_every_wheel_speed(name, formula, twist_):
    once = np.asarray(formula(*twist_), dtype=float)
    twice = np.asarray(formula(*(2.0 * np.array(twist_))), dtype=float)
    close(twice, 2.0 * once, 1 + np.abs(once).max(), tol=1e-12)


@pytest.mark.parametrize("name", sorted(SANDBOX_VEHICLES))
@SETTINGS
@given(twist_=twist)
def test_doubling_the_speed_keeps_every_steering_angle(name, twist_):
    spec = SANDBOX_VEHICLES[name]
    _, once = ideal_commands(spec, twist_)
    _, twice = ideal_commands(spec, 2.0 * np.array(twist_))
    close(twice, once)


# --------------------------------------------------------------------------------------------
# Odometry: closed paths close
# --------------------------------------------------------------------------------------------

@SETTINGS
@given(st.integers(3, 400), st.integers(-400, 400), st.integers(1, 200),
       st.sampled_from([-1, 1]), st.floats(2.0, 20.0))
def test_the_exact_update_closes_a_circle_of_any_radius_and_step_count(n, left, diff, turn,
                                                                        steps_per_mm):
    """n equal updates of (left, left + diff) whole steps drive a circle of radius
    R = (W/2)(2 left + diff)/diff; with W chosen so that they turn exactly 2 pi, the exact
    method comes back to the start (any radius, inside the wheels or out, either way round)."""
    right = left + turn * diff
    base_mm = n * diff / (2 * math.pi * steps_per_mm)  # total turn n (R - L)/(K W) = 2 pi
    inc = np.tile([left, right], (n, 1))
    poses = odo.integrate(inc, steps_per_mm, base_mm, "exact")
    end = poses[-1]
    path = n * (abs(left) + abs(right)) / steps_per_mm  # mm, both wheels
    assert end[2] == pytest.approx(turn * 2 * math.pi, rel=1e-12)
    close(end[:2], [0.0, 0.0], scale=1 + path, tol=1e-10)
    # every pose on the circle itself (Euler's and the midpoint's polygons close too, but
    # their corners are off it)
    radius = base_mm / 2 * (left + right) / (right - left)  # signed, > 0 to the left
    close(np.hypot(poses[:, 0], poses[:, 1] - radius), abs(radius), scale=1 + path, tol=1e-10)


def _drive(spec, plan, dt=1 / 240, record_every=1):
    """Drive ``plan`` [(duration_s, twist), ...] with constant commands in the sandbox, the
    robot already moving at the first command when it starts; every step recorded."""
    world = World(dt=dt)
    robot = world.add(spec, twist=plan[0][1])
    ends = np.cumsum([duration for duration, _ in plan])

    def controller(t, _world):
        k = min(int(np.searchsorted(ends, t)), len(plan) - 1)
        robot.command_twist(*plan[k][1])

    return world.run(float(ends[-1]), controller, record_every=record_every)


#: Radon Ulzer: wheel radius, track and travel per encoder count of the sandbox's robot.
_RU_RADIUS = RADON_ULZER.driven_wheels[0].wheel_radius
_RU_TRACK = RADON_ULZER.driven_wheels[0].position[1] - RADON_ULZER.driven_wheels[1].position[1]
_RU_COUNT_MM = 2 * math.pi * _RU_RADIUS / RADON_ULZER.steps_per_rev * 1000  # mm per count
LOOPS = {
    # one lap in 10 s (2400 steps) at 0.2 m/s: radius 0.318 m, 2 m long
    "circle": [(10.0, (0.2, 0.0, 2 * math.pi / 10.0))],
    # four times 0.5 m straight at 0.2 m/s, then a quarter turn on the spot in 1.25 s
    "square": [(2.5, (0.2, 0.0, 0.0)), (1.25, (0.0, 0.0, math.pi / 2 / 1.25))] * 4,
}


@pytest.mark.parametrize("shape", sorted(LOOPS))
def test_encoder_odometry_of_a_closed_loop_in_the_sandbox_closes(shape):
    """The Radon Ulzer drives a closed loop with constant commands; odometry from its encoders
    (exact arcs, 20 Hz) returns to the start within what the encoders can resolve.

    On the circle the robot itself closes too (no slip at any step). On the square each
    switch of command is an instant change of the wheel rates, which the body follows only as
    fast as friction lets it: the wheels slip for a few steps, and the robot ends off its
    start, by more than the encoders' bound. Odometry cannot see that slip: the estimate
    still closes, as the wheels' own loop does.

    The tolerance, from the resolution alone: a reading is the wheel's travel rounded to the
    nearest count (c = 0.124 mm of travel). The estimated heading depends only on the two
    current readings, so at every update it is within c/W = 1.5 mrad of the wheels' true
    heading (less than one count between the two wheels, over the track W = 85 mm): that
    bounds the heading's gap at the end. Each position step is its travel along the estimated
    heading; the heading error, over the loop's length L, moves the end by at most L c/W; the
    travel's rounding (half a count at each end of each step) telescopes, by Abel summation, to
    at most c/2 + c/2 + (c/2) times the total turn (2 pi). So the gap is at most
    L c/W + (1 + pi) c, 3.4 mm for these 2 m loops (we see 0.06 mm: the bound is the worst
    case). With ideal encoders the same estimate closes to the sandbox's 0.01 mm."""
    plan = LOOPS[shape]
    run = _drive(RADON_ULZER, plan)
    assert not run.contact.any()
    c, w = _RU_COUNT_MM, _RU_TRACK * 1000  # mm
    counts = run.encoder_counts[::12]  # 20 Hz readings, (L, R)
    est = odo.integrate(np.diff(counts, axis=0), 1.0 / c, w, "exact")
    loop_mm = 1000 * run.distance[-1]
    gap = math.hypot(est[-1, 0], est[-1, 1])
    bound = loop_mm * c / w + (1 + math.pi) * c
    assert gap <= bound, (gap, bound)
    assert abs(est[-1, 2] - 2 * math.pi) <= c / w
    robot_gap = 1000 * math.hypot(run.pose[-1, 0], run.pose[-1, 1])
    if shape == "circle":  # one constant command from the start: the robot closes too
        assert not run.slipping.any()
        close(run.pose[-1] - [0.0, 0.0, 2 * math.pi], 0.0, tol=1e-8)
    else:  # the switches slip; the robot's own heading misses by more than odometry's bound
        assert run.slipping.any()
        assert abs(run.pose[-1, 2] - 2 * math.pi) > c / w, robot_gap
    # ... and the gap is the quantisation: ideal encoders (the wheel angles) close to 0.01 mm
    ideal = _drive(RADON_ULZER.replace(steps_per_rev=None), plan)
    travel = np.diff(ideal.encoder_counts, axis=0) * _RU_RADIUS  # m, (L, R)
    steps = np.column_stack([travel.mean(axis=1), np.zeros(len(travel)),
                             (travel[:, 1] - travel[:, 0]) / _RU_TRACK])
    end = frames.integrate_twist(steps, 1.0)[-1]  # exact arcs
    assert math.hypot(end[0], end[1]) < 1e-5
