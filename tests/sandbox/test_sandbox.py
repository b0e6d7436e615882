"""The sandbox: API, bad input, wheel contact and slip, encoders, walls, motor lag, determinism.

Fidelity over 10 m is in test_sandbox_fidelity.py, drawings in test_sandbox_render.py.
"""

from __future__ import annotations

import hashlib
import math
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin.sandbox import (
    LAB_ROBOT,
    MECANUM_ROBOT,
    OPEN_SOURCE_ROVER,
    RADON_ULZER,
    Trajectory,
    VehicleSpec,
    World,
    diff_drive,
    ideal_commands,
    mecanum,
    rover,
    skid_steer,
)
from wheelkin.sandbox.contact import ContactModel, _Warm, dissipation_objective
from wheelkin.sandbox.sensors import Encoder
from wheelkin.sandbox.vehicles import GRAVITY, polygon_inertia
from wheelkin.unified import WheelConstraint

DT = 1 / 240
INCH = 0.0254
ALL = [RADON_ULZER, LAB_ROBOT, MECANUM_ROBOT, OPEN_SOURCE_ROVER]
#: A differential drive with a caster (the factory's default; the Radon Ulzer has none).
CASTER_BOT = diff_drive(0.1, 0.02)
IDS = ["diff drive", "skid steer", "mecanum", "rover"]


# ----------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "make, param",
    [
        (lambda: CASTER_BOT.replace(load_fractions=(1.5, -0.25, -0.25)), "load_fractions"),
        (lambda: CASTER_BOT.replace(load_fractions=(0.5, 0.5)), "load_fractions"),
        (lambda: CASTER_BOT.replace(load_fractions=(0.5, 0.5, 0.5)), "load_fractions"),
        (lambda: RADON_ULZER.replace(load_fractions=(0.5, 0.5, 0.0)), "load_fractions"),
        (lambda: RADON_ULZER.replace(wheels=("L", "R")), "wheels"),
        (lambda: RADON_ULZER.replace(wheels=RADON_ULZER.wheels[0]), "wheels"),
        (lambda: OPEN_SOURCE_ROVER.replace(
            wheels=OPEN_SOURCE_ROVER.wheels_at([0.1, 0.0, 0.0, 0.0], casters=True)), "steering"),
        (lambda: OPEN_SOURCE_ROVER.replace(free_rolling=("LM",)), "free_rolling"),
        (lambda: OPEN_SOURCE_ROVER.replace(free_rolling="LF"), "free_rolling"),
        (lambda: OPEN_SOURCE_ROVER.wheels_at([0.1, 0.2]), "steering"),
        (lambda: OPEN_SOURCE_ROVER.wheels_at(None, casters=1), "casters"),
        (lambda: diff_drive(0.1, -0.02), "wheel_radius"),
        (lambda: diff_drive(0.0, 0.02), "track_width"),
        (lambda: diff_drive(0.1, 0.02, caster_load=1.0), "caster_load"),
        (lambda: skid_steer(half_wheelbase=-0.05, half_track=0.06, wheel_radius=0.04),
         "half_wheelbase"),
        (lambda: mecanum(half_wheelbase=0.15, half_track=0.15, wheel_radius=0.05,
                         roller_angle=math.pi / 2), "roller_angle"),
        (lambda: rover(wheel_radius=float("nan")), "wheel_radius"),
        (lambda: rover((7.0, 10.0, 10.0, 10.0)), "geometry"),
        (lambda: RADON_ULZER.replace(mu=0.0), "mu"),
        (lambda: RADON_ULZER.replace(mu=-0.5), "mu"),
        (lambda: RADON_ULZER.replace(mass=0.0), "mass"),
        (lambda: RADON_ULZER.replace(inertia=float("inf")), "inertia"),
        (lambda: RADON_ULZER.replace(steps_per_rev=0), "steps_per_rev"),
        (lambda: RADON_ULZER.replace(encoder_noise=-1.0), "encoder_noise"),
        (lambda: RADON_ULZER.replace(motor_time_constant=-0.1), "motor_time_constant"),
        (lambda: RADON_ULZER.replace(seed=1.5), "seed"),
        (lambda: RADON_ULZER.replace(body=((0, 0), (1, 0))), "body"),
        (lambda: OPEN_SOURCE_ROVER.replace(steered_names=("LF", "RF", "LB", "LM")),
         "steered_names"),
        (lambda: CASTER_BOT.replace(wheels=CASTER_BOT.wheels[:2]), "load_fractions"),
        (lambda: diff_drive(0.1, 0.02, caster=1), "caster"),
        (lambda: World(dt=0.0), "dt"),
        (lambda: World(dt=-1 / 240), "dt"),
        (lambda: World(dt=float("nan")), "dt"),
        (lambda: World(walls=[((0, 0), (1, 1), (2, 2))]), "walls"),
        (lambda: World().add(RADON_ULZER, pose=(0, 0)), "pose"),
        (lambda: World().add(RADON_ULZER, twist=(float("nan"), 0, 0)), "twist"),
    ],
)
def test_bad_input_raises_value_error_naming_the_parameter(make, param):
    with pytest.raises(ValueError, match=param):
        make()


def test_mixing_swedish_and_conventional_wheels_is_refused():
    wheels = (WheelConstraint("A", (0.1, 0.1), kind="swedish", roller_angle=0.7),
              WheelConstraint("B", (0.1, -0.1), kind="fixed"))
    with pytest.raises(ValueError, match="wheels must not mix"):
        VehicleSpec("odd", 1.0, 0.01, ((-0.1, -0.1), (0.1, -0.1), (0.1, 0.1)), wheels)


def test_a_vehicle_whose_wheels_leave_a_motion_free_is_refused():
    # One fixed wheel: its two rows fix two velocities, the yaw rate about it stays free.
    wheels = (WheelConstraint("A", (0.0, 0.0), kind="fixed"),)
    with pytest.raises(ValueError, match="fix all three body velocities"):
        VehicleSpec("unicycle", 1.0, 0.01, ((-0.1, -0.1), (0.1, -0.1), (0.1, 0.1)), wheels)


@pytest.mark.parametrize(
    "call, param",
    [
        (lambda r: r.set_wheel_rates([float("nan"), 1.0]), "rates"),
        (lambda r: r.set_wheel_rates([1.0, 2.0, 3.0]), "rates"),
        (lambda r: r.command_twist(float("nan"), 0, 0), "vx"),
        (lambda r: r.command_twist(0, 0, float("inf")), "omega"),
        (lambda r: r.set_side_rates(1.0, float("nan")), "right"),
        (lambda r: r.set_steering([0.1]), "angles"),
        (lambda r: r.world.step(-1), "n"),
        (lambda r: r.world.run(-1.0), "duration"),
        (lambda r: r.world.run(1.0, record_every=0), "record_every"),
        (lambda r: r.world.run(1.0, controller=3), "controller"),
    ],
)
def test_bad_commands_raise_value_error_naming_the_parameter(call, param):
    robot = World().add(RADON_ULZER)
    with pytest.raises(ValueError, match=param):
        call(robot)


def test_rover_steering_out_of_range_and_nan_are_refused():
    robot = World().add(OPEN_SOURCE_ROVER)
    with pytest.raises(ValueError, match="angles"):
        robot.set_steering([4.0, 0, 0, 0])
    with pytest.raises(ValueError, match="angles"):
        robot.set_steering([float("nan"), 0, 0, 0])


# ----------------------------------------------------------------------------- geometry
def test_factories_place_the_wheels_as_documented():
    d1, d2, d3, d4 = 7.254 * INCH, 10.5 * INCH, 10.5 * INCH, 10.073 * INCH
    pos = [w.position for w in OPEN_SOURCE_ROVER.wheels]
    np.testing.assert_allclose(pos, [(d3, d1), (0, d4), (-d2, d1), (d3, -d1), (0, -d4),
                                     (-d2, -d1)], rtol=1e-15)
    assert OPEN_SOURCE_ROVER.wheel_names == ("LF", "LM", "LB", "RF", "RM", "RB")
    assert OPEN_SOURCE_ROVER.steered_names == ("LF", "RF", "LB", "RB")
    assert LAB_ROBOT.wheel_names == ("FL", "FR", "RL", "RR")
    np.testing.assert_allclose([w.position for w in LAB_ROBOT.wheels],
                               [(0.05, 0.06), (0.05, -0.06), (-0.05, 0.06), (-0.05, -0.06)])
    assert LAB_ROBOT.driven_wheels[0].wheel_radius == 0.04
    assert RADON_ULZER.wheel_names == ("L", "R")
    # the Zumo's two tracks, one contact each under the middle, half the weight each
    assert [w.kind for w in RADON_ULZER.wheels] == ["fixed", "fixed"]
    assert RADON_ULZER.load_fractions == (0.5, 0.5)
    # 12 * 75.81 counts per revolution of a 0.113097 m wheel: 8043 steps per metre.
    r = RADON_ULZER.driven_wheels[0].wheel_radius
    assert 2 * math.pi * r == pytest.approx(0.113097)
    assert RADON_ULZER.steps_per_rev / (2 * math.pi * r) == pytest.approx(8043, abs=1)
    for spec in ALL:
        assert sum(spec.load_fractions) == pytest.approx(1.0)
        # the static loads carry the weight m g less the casters' share
        caster_share = sum(f for w, f in zip(spec.wheels, spec.load_fractions, strict=True)
                           if w.kind == "caster")
        assert spec.normal_loads.sum() == pytest.approx(spec.mass * 9.81 * (1 - caster_share))


def test_polygon_inertia_matches_the_plate_formulas():
    # Rectangle a x b about its centre: m (a^2 + b^2) / 12; shifted by d: + m d^2.
    rect = [(-0.1, -0.05), (0.1, -0.05), (0.1, 0.05), (-0.1, 0.05)]
    assert polygon_inertia(2.0, rect) == pytest.approx(2.0 * (0.2**2 + 0.1**2) / 12)
    shifted = [(x + 0.3, y) for x, y in rect]
    assert polygon_inertia(2.0, shifted) == pytest.approx(2.0 * (0.05 / 12 + 0.09))
    assert polygon_inertia(2.0, rect[::-1]) == pytest.approx(polygon_inertia(2.0, rect))


twists = st.tuples(st.floats(-1, 1), st.floats(-1, 1), st.floats(-3, 3))


@given(twists)
def test_mecanum_ideal_rates_are_the_documented_x_arrangement(twist):
    vx, vy, w = twist
    r, k = 0.05, 0.30
    rates, _ = ideal_commands(MECANUM_ROBOT, twist)
    expected = [(vx - vy - k * w) / r, (vx + vy + k * w) / r, (vx + vy - k * w) / r,
                (vx - vy + k * w) / r]
    np.testing.assert_allclose(rates, expected, atol=1e-9)


@given(st.floats(-1, 1), st.floats(-3, 3))
def test_diff_drive_ideal_rates_invert_the_forward_kinematics(v, w):
    rates, _ = ideal_commands(RADON_ULZER, (v, 0.0, w))
    r, W = RADON_ULZER.driven_wheels[0].wheel_radius, 0.085
    assert r * (rates[0] + rates[1]) / 2 == pytest.approx(v, abs=1e-12)
    assert r * (rates[1] - rates[0]) / W == pytest.approx(w, abs=1e-12)


def test_rover_ideal_commands_reproduce_the_osr_speed_table():
    """OSR document: r = 30 in to the right, X = 100 -> motors 96.59, 100, 96.59, 62.52,
    49.73, 62.52 (1-3 left front/middle/back, 4-6 right); corner angles atan(d3/(r -+ d1))."""
    R = -30 * INCH  # right turn: negative radius in REP-103
    v = 1.0
    rates, steer = ideal_commands(OPEN_SOURCE_ROVER, (v, 0.0, v / R))
    percent = 100 * np.abs(rates) / np.abs(rates[1])
    np.testing.assert_allclose(percent, [96.59, 100, 96.59, 62.52, 49.73, 62.52], atol=0.01)
    d1, d3 = 7.254 * INCH, 10.5 * INCH
    outer, inner = math.atan(d3 / (30 * INCH + d1)), math.atan(d3 / (30 * INCH - d1))
    # Right turn: front wheels turn clockwise (negative), back wheels counter-clockwise.
    np.testing.assert_allclose(steer, [-outer, -inner, outer, inner], atol=1e-12)


# ----------------------------------------------------------------------------- world API
def test_run_records_a_trajectory_with_the_documented_shapes():
    world = World()
    robot = world.add(OPEN_SOURCE_ROVER, pose=(1.0, 2.0, 0.5))
    robot.command_twist(0.3, 0.0, 0.2)
    traj = world.run(1.0, record_every=10)
    assert isinstance(traj, Trajectory)
    n = len(traj)
    assert n == 25  # t = 0, 10 dt, ..., 240 dt
    assert traj.t[0] == 0.0 and traj.t[-1] == pytest.approx(1.0)
    assert traj.pose.shape == (n, 3) and traj.twist.shape == (n, 3)
    for name in ("wheel_angles", "encoder_counts", "slipping", "slip_speed",
                 "commanded_rates", "wheel_rates"):
        assert getattr(traj, name).shape == (n, 6), name
    assert traj.steering.shape == (n, 4)
    assert traj.contact.shape == (n,) and traj.distance.shape == (n,)
    assert traj.pose[0].tolist() == [1.0, 2.0, 0.5]
    assert traj.encoder_counts.dtype == np.float64  # ideal encoder: angles
    assert world.time == pytest.approx(1.0)
    assert robot.pose == tuple(traj.pose[-1])


def test_several_robots_give_a_list_of_trajectories():
    world = World()
    world.add(RADON_ULZER, pose=(0, 0, 0), twist=(0.2, 0, 0))
    world.add(LAB_ROBOT, pose=(0, 1, 0), twist=(0.1, 0, 0))
    trajs = world.run(0.5)
    assert isinstance(trajs, list) and len(trajs) == 2
    assert trajs[0].pose[-1, 0] == pytest.approx(0.1)
    assert trajs[1].pose[-1, 0] == pytest.approx(0.05)


def test_controller_is_called_at_each_step_midpoint():
    world = World(dt=0.01)
    world.add(RADON_ULZER)
    seen = []
    world.run(0.05, lambda t, w: seen.append(t))
    np.testing.assert_allclose(seen, [0.005, 0.015, 0.025, 0.035, 0.045])


def test_heading_is_unwrapped():
    world = World()
    robot = world.add(MECANUM_ROBOT, twist=(0.0, 0.0, 2.0))
    world.step(4 * 240)
    assert robot.pose[2] == pytest.approx(8.0)
    assert math.hypot(robot.pose[0], robot.pose[1]) < 1e-12


def test_command_twist_drives_each_vehicle_at_that_twist():
    for spec, twist in zip(ALL, [(0.3, 0, 0.5), (0.3, 0, 0), (0.2, -0.3, 0.4), (0.3, 0, 0.3)],
                           strict=True):
        world = World()
        robot = world.add(spec, twist=(0.0, 0.0, 0.0))
        robot.command_twist(*twist)
        world.step(480)  # accelerating within friction takes a moment
        np.testing.assert_allclose(robot.twist, twist, atol=1e-12, err_msg=spec.name)
        assert not robot.slipping.any()


# ----------------------------------------------------------------------------- slip
def kinematic_diff(v, w, T):
    return np.array([math.sin(w * T) * v / w, (1 - math.cos(w * T)) * v / w, w * T])


def test_aggressive_command_on_low_friction_slips_visibly_unlike_its_twin():
    """From rest to 0.5 m/s and 3 rad/s at once: on mu = 0.1 the wheels spin and the body
    lags far behind the kinematic circle; with mu = 0.8 and the command ramped in 0.5 s
    (within mu g) the robot stays on the kinematic model."""
    icy = World()
    robot = icy.add(RADON_ULZER.replace(mu=0.1))
    robot.command_twist(0.5, 0.0, 3.0)
    traj = icy.run(2.0)
    assert traj.slipping[1:20].all()  # both wheels, L and R, from the first step
    end = kinematic_diff(0.5, 3.0, 2.0)
    assert math.dist(traj.pose[-1, :2], end[:2]) > 0.05

    grip = World()
    grip.add(RADON_ULZER)

    def ramp(t, world):
        s = min(t / 0.5, 1.0)
        world.robots[0].command_twist(0.5 * s, 0.0, 3.0 * s)

    traj2 = grip.run(2.0, ramp)
    assert not traj2.slipping.any()
    # After the ramp the twin turns exactly at the commanded twist.
    np.testing.assert_allclose(traj2.twist[-1], [0.5, 0.0, 3.0], atol=1e-12)


def test_slip_grows_as_friction_falls():
    """The same aggressive command: the lower mu, the more the heading lags the model's."""
    lags = []
    for mu in (0.8, 0.3, 0.1, 0.05):
        world = World()
        robot = world.add(RADON_ULZER.replace(mu=mu))
        robot.command_twist(0.5, 0.0, 3.0)
        traj = world.run(1.0, record_every=240)
        lags.append(3.0 - traj.pose[-1, 2])
    assert lags == sorted(lags)
    assert lags[-1] > 10 * lags[0] > 0


def test_only_the_mis_steered_rover_wheel_slips_and_the_rover_drives_straight():
    world = World()
    robot = world.add(OPEN_SOURCE_ROVER, twist=(0.3, 0.0, 0.0))
    robot.set_steering([0.3, 0.0, 0.0, 0.0])  # LF turned 0.3 rad, the rest straight
    traj = world.run(2.0)
    assert traj.slipping[1:].tolist() == [[True, False, False, False, False, False]] * (
        len(traj) - 1)
    # LF's surface moves at 0.3 m/s along its rolling direction, 0.3 rad off the body's
    # velocity of 0.3 m/s: the contact slides at 2 * 0.3 * sin(0.15).
    np.testing.assert_allclose(traj.slip_speed[1:, 0], 0.6 * math.sin(0.15), rtol=1e-9)
    np.testing.assert_allclose(traj.pose[-1], [0.6, 0.0, 0.0], atol=1e-12)


def test_only_the_over_driven_mecanum_wheel_slips():
    world = World()
    robot = world.add(MECANUM_ROBOT, twist=(0.3, 0.0, 0.0))
    robot.set_wheel_rates([12.0, 6.0, 6.0, 6.0])  # FL twice as fast as the others
    traj = world.run(2.0)
    assert traj.slipping[1:, 0].all() and not traj.slipping[:, 1:].any()
    np.testing.assert_allclose(traj.pose[-1], [0.6, 0.0, 0.0], atol=1e-12)


def test_skid_steer_slips_sideways_when_turning_and_turns_slower_than_ideal():
    r, b, a = 0.04, 0.06, 0.05
    left, right = 3.0, 7.0  # rad/s: ideal v = 0.2 m/s, w = r (right - left) / (2 b)
    ideal_w = r * (right - left) / (2 * b)
    world = World()
    robot = world.add(LAB_ROBOT)
    robot.set_side_rates(left, right)
    traj = world.run(3.0)
    steady = traj.twist[-240:]
    assert traj.slipping[-240:].all()
    _, vy, w = steady.mean(0)
    # The wheels slide sideways: front at vy + w a, rear at vy - w a.
    assert abs(vy + w * a) > 0.01 and abs(vy - w * a) > 0.01
    assert 0.2 * ideal_w < w < 0.9 * ideal_w
    # Straight driving does not slip.
    world2 = World()
    robot2 = world2.add(LAB_ROBOT, twist=(0.2, 0, 0))
    robot2.set_side_rates(5.0, 5.0)
    assert not world2.run(1.0).slipping.any()


def test_a_left_turn_mirrors_a_right_turn_even_when_slipping():
    runs = []
    for left, right in ((3.0, 7.0), (7.0, 3.0)):
        world = World()
        robot = world.add(LAB_ROBOT.replace(mu=0.4))
        robot.set_side_rates(left, right)
        runs.append(world.run(2.0))
    np.testing.assert_allclose(runs[0].pose * [1, -1, -1], runs[1].pose, atol=1e-9)
    np.testing.assert_array_equal(runs[0].slipping[:, [1, 0, 3, 2]], runs[1].slipping)


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(range(4)), st.integers(0, 2**32 - 1))
def test_contact_solution_minimises_the_dissipation_objective(which, seed):
    """Independent of the solver: F is convex, so the solution must beat every nearby twist."""
    spec = ALL[which].replace(mu=0.3)
    rng = np.random.default_rng(seed)
    steering = tuple(rng.uniform(-0.5, 0.5, len(spec.steered_names)).tolist())
    model = ContactModel(spec, steering, DT)
    rates = rng.normal(0, 10, len(spec.wheel_names)).tolist()
    xp = tuple(rng.normal(0, 0.3, 3).tolist())
    res = model.solve(rates, xp, _Warm())
    xi = np.array(res.twist)
    b = model.B @ np.array(rates)
    F = lambda x: dissipation_objective(x, xp, model.J, b, model.mass_diag, model.caps,  # noqa: E731
                                        model.k)
    f0 = F(xi)
    for scale in (1e-7, 1e-5, 1e-3, 1e-1):
        for d in rng.normal(0, scale, (30, 3)):
            assert F(xi + d) >= f0 - 1e-15 * (1 + abs(f0))
    # A wheel flagged slipping slips; the others roll on their constraints.
    s = (model.J @ xi - b).reshape(model.n, model.k)
    speed = np.sqrt((s * s).sum(1))
    assert np.all(speed[~np.array(res.slipping)] < 1e-8)
    assert np.all(speed[np.array(res.slipping)] > 0)


def test_stick_impulses_respect_newtons_second_law():
    """Accelerating from rest within friction: the twist after one step is the commanded one
    and the momentum change m dv fits within the total friction mu m g dt."""
    model = ContactModel(LAB_ROBOT, (), DT)
    res = model.solve([0.5] * 4, (0.0, 0.0, 0.0), _Warm())
    assert res.method == "stick"
    assert res.twist == pytest.approx([0.02, 0.0, 0.0], abs=1e-15)
    assert LAB_ROBOT.mass * 0.02 <= LAB_ROBOT.mu * LAB_ROBOT.mass * GRAVITY * DT
    # 25 times that speed change in one step exceeds friction: slip.
    res = model.solve([12.5] * 4, (0.0, 0.0, 0.0), _Warm())
    assert all(res.slipping)
    assert res.twist[0] == pytest.approx(LAB_ROBOT.mu * GRAVITY * DT, rel=1e-9)


# ----------------------------------------------------------------------------- encoders
def test_encoder_counts_match_wheel_travel_within_one_step():
    world = World()
    world.add(RADON_ULZER)

    def drive(t, world):
        world.robots[0].command_twist(0.3 * math.sin(1.3 * t), 0.0, 2.0 * math.cos(0.7 * t))

    traj = world.run(6.0, drive, record_every=3)
    spr = RADON_ULZER.steps_per_rev
    travel = traj.wheel_angles * spr / (2 * math.pi)
    assert traj.encoder_counts.dtype == np.int64
    assert np.abs(traj.encoder_counts - travel).max() <= 0.5 + 1e-9
    # Distance from counts: within one step's length (0.113097 m / 909.72) of the truth.
    r = RADON_ULZER.driven_wheels[0].wheel_radius
    step_length = 2 * math.pi * r / spr
    dist = traj.encoder_counts * step_length
    assert np.abs(dist - traj.wheel_angles * r).max() <= step_length


def test_encoder_counts_are_cumulative_and_change_by_edges():
    enc = Encoder(1, 100)
    angles = np.linspace(0, 4 * math.pi, 1001)[:, None]
    counts = enc.counts(angles, np.arange(1001))[:, 0]
    assert counts[0] == 0 and counts[-1] == 200
    assert np.all(np.diff(counts) >= 0) and set(np.diff(counts)) <= {0, 1}


def test_encoder_noise_is_seeded_and_independent_of_how_often_it_is_read():
    spec = RADON_ULZER.replace(encoder_noise=2.0, seed=7)
    a = World()
    a.add(spec, twist=(0.2, 0, 0))
    every = a.run(2.0)
    b = World()
    b.add(spec, twist=(0.2, 0, 0))
    sparse = b.run(2.0, record_every=40)
    np.testing.assert_array_equal(every.encoder_counts[::40], sparse.encoder_counts)
    other = World()
    other.add(spec.replace(seed=8), twist=(0.2, 0, 0))
    assert not np.array_equal(other.run(2.0).encoder_counts, every.encoder_counts)
    spr = spec.steps_per_rev
    error = every.encoder_counts - every.wheel_angles * spr / (2 * math.pi)
    assert abs(error.mean()) < 0.3 and 1.7 < error.std() < 2.3


# ----------------------------------------------------------------------------- motor lag
def test_motor_lag_is_the_exact_first_order_response():
    tau, rate = 0.1, 10.0
    world = World()
    robot = world.add(LAB_ROBOT.replace(motor_time_constant=tau))
    robot.set_side_rates(rate, rate)
    traj = world.run(0.5, record_every=12)
    t = traj.t
    expected_angle = rate * (t - tau * (1 - np.exp(-t / tau)))
    np.testing.assert_allclose(traj.wheel_angles[:, 0], expected_angle, atol=1e-12)
    assert robot.wheel_rates[0] == pytest.approx(rate * (1 - math.exp(-0.5 / tau)))
    assert not traj.slipping.any()  # 10 rad/s in 0.1 s is 4 m/s^2 < mu g


# ----------------------------------------------------------------------------- walls
def test_a_wall_stops_the_robot_and_its_wheels_slip():
    world = World(walls=[((0.5, -1.0), (0.5, 1.0))], wall_thickness=0.02)
    robot = world.add(LAB_ROBOT, twist=(0.3, 0.0, 0.0))
    traj = world.run(3.0)
    front = 0.1  # body reaches 0.1 m ahead of the reference point
    assert traj.pose[:, 0].max() + front <= 0.49 + 2e-3  # no tunnelling through the wall
    assert traj.contact[-1] and not traj.contact[0]
    assert traj.slipping[-1].all()
    assert abs(robot.twist[0]) < 1e-3
    assert abs(traj.pose[-1, 1]) < 1e-5 and abs(traj.pose[-1, 2]) < 1e-5


def test_driving_beside_a_wall_does_not_touch_it():
    world = World(walls=[((-1.0, 0.2), (3.0, 0.2))])
    world.add(RADON_ULZER, twist=(0.3, 0.0, 0.0))
    traj = world.run(2.0)
    assert not traj.contact.any()
    assert traj.pose[-1, 0] == pytest.approx(0.6)


# ----------------------------------------------------------------------------- determinism
SCRIPT = textwrap.dedent(
    """
    import hashlib, math
    from wheelkin.sandbox import World, LAB_ROBOT, RADON_ULZER
    world = World(walls=[((1.0, -1.0), (1.0, 1.0))])
    world.add(LAB_ROBOT.replace(mu=0.3, steps_per_rev=500, encoder_noise=0.7, seed=3))
    world.add(RADON_ULZER.replace(encoder_noise=1.0, seed=5), pose=(0.0, 0.5, 0.0))
    def ctl(t, w):
        w.robots[0].set_side_rates(8 + 4 * math.sin(t), 8 - 4 * math.sin(t))
        w.robots[1].command_twist(0.4, 0.0, math.cos(2 * t))
    h = hashlib.sha256()
    for tr in world.run(3.0, ctl):
        for name in ("pose", "twist", "wheel_angles", "encoder_counts", "slipping", "contact"):
            h.update(getattr(tr, name).tobytes())
    print(h.hexdigest())
    """
)


def test_trajectories_are_bit_identical_across_processes():
    runs = [subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                           check=True).stdout.strip() for _ in range(2)]
    namespace: dict = {}
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        exec(SCRIPT, namespace)
    assert runs[0] == runs[1] == buf.getvalue().strip()
    assert len(runs[0]) == len(hashlib.sha256().hexdigest())
