"""wheelkin.sandbox.runs: the shared sandbox runs, against independent values.

- the schedule against linear interpolation written out by hand;
- the ideal path against the closed-form arc of a constant twist;
- the planned poses against the same arc (a constant twist is exact step by step);
- a gripping run against the ideal path (the sandbox's exact steps and an ODE solver agree);
- the one model's commands against the sandbox's own ideal commands (another implementation);
- the encoder odometry against the true poses of a run without slip, and against a skid
  steer's known failure (it believes the plan);
- the friction work against its definition summed by hand over the records, and zero when no
  wheel slips.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from wheelkin.sandbox import (
    LAB_ROBOT,
    MECANUM_ROBOT,
    OPEN_SOURCE_ROVER,
    RADON_ULZER,
    World,
    ideal_commands,
)
from wheelkin.sandbox.runs import (
    drive_twist,
    encoder_odometry,
    friction_work,
    ideal_path,
    one_model_commands,
    planned_poses,
    twist_schedule,
)


def arc(v: float, w: float, t: float) -> np.ndarray:
    """Pose after t s of the constant twist (v, 0, w) from the origin (closed form)."""
    if w == 0:
        return np.array([v * t, 0.0, 0.0])
    r = v / w
    return np.array([r * math.sin(w * t), r * (1 - math.cos(w * t)), w * t])


# ----------------------------------------------------------------------------- schedule


def test_twist_schedule_interpolates_and_holds():
    at = twist_schedule([0.0, 1.0, 3.0], [(0, 0, 0), (0.4, 0, 2.0), (0.4, -0.2, 0.0)])
    assert at(-1.0) == (0.0, 0.0, 0.0)
    assert at(0.25) == pytest.approx((0.1, 0.0, 0.5))
    assert at(2.0) == pytest.approx((0.4, -0.1, 1.0))
    assert at(9.0) == (0.4, -0.2, 0.0)
    assert all(isinstance(c, float) for c in at(0.5))


@pytest.mark.parametrize(("times", "twists", "message"), [
    ([0.0, 1.0], [(0, 0, 0)], r"twists must have shape \(2, 3\)"),
    ([1.0, 0.0], [(0, 0, 0), (1, 0, 0)], "times must be strictly increasing"),
    ([[0.0, 1.0]], [(0, 0, 0), (1, 0, 0)], r"times must have shape \(M,\)"),
    ([0.0, math.nan], [(0, 0, 0), (1, 0, 0)], "times"),
    ([0.0, 1.0], [(0, 0, 0), (1, 0, math.inf)], "twists"),
])
def test_twist_schedule_bad_input(times, twists, message):
    with pytest.raises(ValueError, match=message):
        twist_schedule(times, twists)


# ----------------------------------------------------------------------------- ideal path


def test_ideal_path_is_the_arc_of_a_constant_twist():
    times = np.linspace(0.0, 4.0, 9)
    got = ideal_path(lambda t: (0.3, 0.0, 0.7), times)
    want = np.array([arc(0.3, 0.7, t) for t in times])
    np.testing.assert_allclose(got, want, atol=1e-11)


def test_ideal_path_from_a_start_pose_is_the_moved_path():
    start = (1.0, -2.0, math.pi / 2)
    got = ideal_path(lambda t: (0.5, 0.0, 0.0), [0.0, 2.0], start)
    np.testing.assert_allclose(got[-1], [1.0, -1.0, math.pi / 2], atol=1e-12)


@pytest.mark.parametrize(("times", "message"), [([0.0], "times must be increasing"),
                                                ([1.0, 0.0], "times must be increasing")])
def test_ideal_path_bad_times(times, message):
    with pytest.raises(ValueError, match=message):
        ideal_path(lambda t: (1.0, 0.0, 0.0), times)


def test_ideal_path_needs_a_callable():
    with pytest.raises(ValueError, match="twist_at must be a callable"):
        ideal_path((1.0, 0.0, 0.0), [0.0, 1.0])


# ----------------------------------------------------------------------------- planned poses


def test_planned_poses_of_a_constant_twist_are_exact_arcs():
    got = planned_poses(lambda t: (0.4, 0.0, -1.2), 1.0, dt=0.01)
    assert got.shape == (101, 3)
    np.testing.assert_allclose(got[-1], arc(0.4, -1.2, 1.0), atol=1e-12)


def test_planned_poses_ramp_loses_half_the_ramp_time():
    # v ramps 0 -> 1 m/s over 0.5 s (sampled at mid-steps: exact for a linear ramp), then 1.
    got = planned_poses(lambda t: (1.0, 0.0, 0.0), 2.0, dt=0.01, ramp=0.5)
    assert got[-1, 0] == pytest.approx(2.0 - 0.25, abs=1e-12)


@pytest.mark.parametrize(("kwargs", "message"), [({"dt": 0.0}, "dt"), ({"ramp": -1.0}, "ramp"),
                                                 ({"dt": math.nan}, "dt")])
def test_planned_poses_bad_input(kwargs, message):
    with pytest.raises(ValueError, match=message):
        planned_poses(lambda t: (1.0, 0.0, 0.0), 1.0, **kwargs)


def test_planned_poses_refuses_a_twist_that_is_not_three_numbers():
    with pytest.raises(ValueError, match=r"twist_at\(0.005\) must give three finite numbers"):
        planned_poses(lambda t: (1.0, 0.0), 1.0, dt=0.01)


# ----------------------------------------------------------------------------- drive


def test_a_gripping_run_follows_the_ideal_path():
    turn = twist_schedule([0.0, 2.0, 4.0], [(0.25, 0.0, 0.0), (0.25, 0.0, 1.5),
                                            (0.25, 0.0, -1.0)])
    run = drive_twist(RADON_ULZER, turn, 4.0, twist=(0.25, 0.0, 0.0))
    assert not run.slipping.any()
    assert len(run) == 4 * 240 // 4 + 1  # every 4th step recorded by default
    np.testing.assert_allclose(run.pose, ideal_path(turn, run.t), atol=1e-5)


def test_drive_twist_with_the_one_model_matches_the_robots_own_commands():
    twist = lambda t: (0.3, 0.0, 0.4)  # noqa: E731
    own = drive_twist(OPEN_SOURCE_ROVER, twist, 1.0, twist=(0.3, 0.0, 0.4), record_every=1)
    model = drive_twist(OPEN_SOURCE_ROVER, twist, 1.0, twist=(0.3, 0.0, 0.4),
                        commands=one_model_commands, record_every=1)
    np.testing.assert_allclose(model.pose, own.pose, atol=1e-9)
    np.testing.assert_allclose(model.steering, own.steering, atol=1e-9)


def test_drive_twist_ramp_scales_the_command():
    run = drive_twist(MECANUM_ROBOT, lambda t: (0.0, 0.3, 0.0), 2.0, ramp=0.5, record_every=1)
    # 0.3 m/s for 2 s less half the 0.5 s ramp, commanded at the start of each step
    assert run.pose[-1, 1] == pytest.approx(0.3 * (2.0 - 0.25), abs=2e-3)
    assert not run.slipping.any()


def test_drive_twist_walls_stop_the_vehicle():
    wall = [((0.5, -1.0), (0.5, 1.0))]
    run = drive_twist(RADON_ULZER, lambda t: (0.3, 0.0, 0.0), 3.0, walls=wall)
    assert run.contact.any() and run.pose[-1, 0] < 0.5


@pytest.mark.parametrize(("args", "kwargs", "message"), [
    (("robot", lambda t: (0, 0, 0), 1.0), {}, "spec must be a VehicleSpec"),
    ((RADON_ULZER, (0, 0, 0), 1.0), {}, "twist_at must be a callable"),
    ((RADON_ULZER, lambda t: (0, 0, 0), 1.0), {"ramp": -0.1}, "ramp"),
    ((RADON_ULZER, lambda t: (0, 0, 0), 1.0), {"commands": 3}, "commands must be a callable"),
    ((RADON_ULZER, lambda t: (0, 0, 0), 1.0), {"dt": 0.0}, "dt"),
    ((RADON_ULZER, lambda t: (0, 0, 0), -1.0), {}, "duration"),
    ((RADON_ULZER, lambda t: (0, 0, math.nan), 1.0), {}, "must give three finite numbers"),
])
def test_drive_twist_bad_input(args, kwargs, message):
    with pytest.raises(ValueError, match=message):
        drive_twist(*args, **kwargs)


# ----------------------------------------------------------------------------- commands


@pytest.mark.parametrize("spec", [RADON_ULZER, LAB_ROBOT, MECANUM_ROBOT, OPEN_SOURCE_ROVER],
                         ids=lambda s: s.name)
@pytest.mark.parametrize("twist", [(0.3, 0.0, 0.0), (0.2, 0.1, 0.5), (0.0, 0.0, -1.0)])
def test_one_model_commands_equal_the_sandboxs_ideal_commands(spec, twist):
    rates, steering = one_model_commands(spec, twist)
    want = ideal_commands(spec, twist)
    np.testing.assert_allclose(rates, want.rates, atol=1e-12)
    np.testing.assert_allclose(steering, want.steering, atol=1e-12)


def test_one_model_commands_bad_twist():
    with pytest.raises(ValueError, match=r"twist must be one twist"):
        one_model_commands(RADON_ULZER, [[0.1, 0.0, 0.0]])


# ----------------------------------------------------------------------------- odometry


@pytest.mark.parametrize("spec", [MECANUM_ROBOT, OPEN_SOURCE_ROVER], ids=lambda s: s.name)
def test_encoder_odometry_of_a_run_without_slip_is_the_truth(spec):
    twist = (0.2, 0.0, 0.3) if spec is OPEN_SOURCE_ROVER else (0.2, 0.1, 0.5)
    run = drive_twist(spec, lambda t: twist, 2.0, twist=twist, record_every=1)
    assert not run.slipping.any()
    np.testing.assert_allclose(encoder_odometry(spec, run), run.pose, atol=1e-9)


def test_encoder_odometry_of_a_quantised_encoder_is_within_a_count():
    run = drive_twist(RADON_ULZER, lambda t: (0.2, 0.0, 1.0), 2.0, twist=(0.2, 0.0, 1.0),
                      record_every=1)
    est = encoder_odometry(RADON_ULZER, run)
    # a count is 2 pi / steps_per_rev of a wheel of radius r: about 0.12 mm of travel
    count = 2 * math.pi / RADON_ULZER.steps_per_rev * RADON_ULZER.wheels[0].wheel_radius
    assert np.hypot(*(est[-1, :2] - run.pose[-1, :2])) < 3 * count


def test_encoder_odometry_of_a_skid_steer_believes_the_plan():
    spin = lambda t: (0.0, 0.0, 1.0)  # noqa: E731
    run = drive_twist(LAB_ROBOT, spin, 2.0, record_every=1)
    est = encoder_odometry(LAB_ROBOT, run)
    assert run.slipping.any()
    assert est[-1, 2] == pytest.approx(2.0, abs=1e-9)  # what the wheels were told
    assert run.pose[-1, 2] < 1.5  # what the body did: much less


def test_encoder_odometry_needs_a_constant_step():
    world = World()
    world.add(RADON_ULZER)
    a = world.run(0.1)
    run = type(a)(**{**a.__dict__, "t": a.t ** 2})
    with pytest.raises(ValueError, match="constant step"):
        encoder_odometry(RADON_ULZER, run)


def test_encoder_odometry_bad_input():
    with pytest.raises(ValueError, match="trajectory must be a Trajectory"):
        encoder_odometry(RADON_ULZER, "run")
    with pytest.raises(ValueError, match="wheels_of must be a callable"):
        run = drive_twist(RADON_ULZER, lambda t: (0.1, 0, 0), 0.1)
        encoder_odometry(RADON_ULZER, run, wheels_of=3)


# ----------------------------------------------------------------------------- friction


def test_friction_work_is_its_definition():
    run = drive_twist(LAB_ROBOT, lambda t: (0.0, 0.0, 1.0), 1.0, record_every=1)
    by_hand = 0.0
    for k in range(1, len(run)):
        for i, load in enumerate(LAB_ROBOT.normal_loads):
            by_hand += LAB_ROBOT.mu * load * run.slip_speed[k, i] * (run.t[k] - run.t[k - 1])
    assert by_hand > 0.1
    assert friction_work(LAB_ROBOT, run) == pytest.approx(by_hand, rel=1e-12)


def test_friction_work_without_slip_is_zero():
    run = drive_twist(MECANUM_ROBOT, lambda t: (0.1, 0.2, 0.3), 1.0, twist=(0.1, 0.2, 0.3))
    assert friction_work(MECANUM_ROBOT, run) == 0.0


def test_friction_work_of_another_vehicles_run():
    run = drive_twist(RADON_ULZER, lambda t: (0.1, 0, 0), 0.1)
    with pytest.raises(ValueError, match="trajectory must be a run of spec"):
        friction_work(LAB_ROBOT, run)
