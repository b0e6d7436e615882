"""Tests of wheelkin.follower: the pure-pursuit follower, the controllers, the robot Protocol
and the reduced skid-steer model, against hand values, closed forms and the plan."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin import follower as fo
from wheelkin import waypoints as wp

R_W, D = 0.04, 0.06  # the Webots tutorial robot: wheel radius, half axle (m)


# --------------------------------------------------------------------------- the seam
def test_waypoints_holds_plans_only_and_the_follower_builds_on_it():
    # follower imports waypoints, never the reverse (tests/library/test_layers.py checks the
    # whole house for circles): the controllers are not reachable through waypoints
    for name in ("FollowerController", "PathFollower", "ScheduleController"):
        assert not hasattr(wp, name), name
    assert fo.PathFollower.__module__ == "wheelkin.follower"


# --------------------------------------------------------------------------- the follower
@settings(max_examples=100)
@given(st.floats(0.05, 0.5), st.floats(-0.3, 0.3), st.floats(-0.6, 0.6))
def test_pure_pursuit_curvature_is_the_circle_through_the_carrot(lookahead, offset, heading):
    """On a long straight along +x the carrot is the point `lookahead` beyond the projection;
    the commanded curvature is the one of the circle tangent to the heading through it."""
    segs = wp.plan_segments([[0.0, 0.0], [10.0, 0.0]])
    f = fo.PathFollower(segs, speed=0.25, lookahead=lookahead)
    x, y = 1.0, offset
    cx, cy = x + lookahead, 0.0  # the projection is (x, 0)
    c, s = math.cos(heading), math.sin(heading)
    ahead, left = c * (cx - x) + s * (cy - y), -s * (cx - x) + c * (cy - y)
    speed, yaw_rate = f.command((x, y, heading))
    if ahead <= 0:
        assert speed == 0.0
        return
    # the circle through the origin, tangent to x, and through (ahead, left): radius
    # R = (ahead^2 + left^2) / (2 left)
    assert speed == 0.25
    assert yaw_rate == pytest.approx(speed * 2 * left / (ahead**2 + left**2), rel=1e-12)


def test_follower_command_is_a_named_pair():
    f = fo.PathFollower(wp.plan_segments([[0, 0], [1, 0]]), speed=0.2)
    cmd = f.command(np.array([0.0, 0.0, 0.0]))
    assert isinstance(cmd, fo.BodyCommand) and cmd.speed == 0.2 and cmd.yaw_rate == 0.0
    v, w = cmd
    assert (v, w) == (0.2, 0.0)
    assert f.progress((0.3, 0.1, 0.0)) == pytest.approx(0.3)


@pytest.mark.parametrize("pose, match", [
    ((0.0, math.nan, 0.0), "pose"), ((0.0, 0.0), "pose"), ("abc", "pose"), (None, "pose"),
])
def test_follower_rejects_bad_poses(pose, match):
    f = fo.PathFollower(wp.plan_segments([[0, 0], [1, 0]]))
    with pytest.raises(ValueError, match=match):
        f.command(pose)
    with pytest.raises(ValueError, match=match):
        f.progress(pose)


# --------------------------------------------------------------------------- the reduced model
def test_reduced_model_is_an_ideal_diff_drive_with_chi_one():
    # chi = 1, no lag, ideal encoders: the schedule drives it exactly along the plan
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    cmds = wp.schedule(segs, R_W, D)
    robot = fo.KinematicSkidSteer(segs[0].start, skid_factor=1.0, motor_time_constant=0.0)
    for c in cmds:
        robot.set_side_rates(c.left_rate, c.right_rate)
        n = 50
        for _ in range(n):
            robot.step(c.duration / n)
        np.testing.assert_allclose(robot.pose, c.segment.end, atol=1e-9)
    # the encoders read the wheel angles (FL, FR, RL, RR) the schedule planned
    planned = wp.planned_wheel_angles(cmds, 1e9)
    np.testing.assert_allclose(robot.encoder_angles, planned[[0, 1, 0, 1]], atol=1e-9)


def test_reduced_model_turns_chi_times_less_and_quantises_its_encoders():
    robot = fo.KinematicSkidSteer((0, 0, 0), steps_per_rev=64, motor_time_constant=0.0)
    chi = 1 + (0.10 / 0.12) ** 2  # 1 + L^2 / W^2 of the lab robot
    assert robot.skid_factor == pytest.approx(chi)
    robot.set_side_rates(-5.0, 5.0)
    for _ in range(10):
        robot.step(0.1)
    ideal = 0.04 * 10.0 / 0.12 * 1.0  # rad after 1 s
    assert robot.pose[2] == pytest.approx(ideal / chi)
    counts = robot.encoder_angles / (2 * math.pi / 64)
    np.testing.assert_allclose(counts, np.round(counts))  # whole counts
    assert np.all(np.abs(robot.encoder_angles - [-5, 5, -5, 5]) <= math.pi / 64 + 1e-12)


def test_reduced_model_motor_lag_is_the_first_order_response():
    tau, h = 0.05, 0.01
    robot = fo.KinematicSkidSteer((0, 0, 0), motor_time_constant=tau)
    robot.set_side_rates(2.0, 2.0)
    for _ in range(30):
        robot.step(h)
    t = 30 * h
    # the wheel angle is the integral of 2 (1 - exp(-t / tau))
    want = 2.0 * (t - tau * (1 - math.exp(-t / tau)))
    np.testing.assert_allclose(robot.encoder_angles, want, rtol=1e-12)
    x, y, theta = robot.pose
    assert (x, y, theta) == pytest.approx((0.04 * want, 0.0, 0.0), abs=1e-15)


def test_reduced_model_and_a_sandbox_robot_are_side_driven_robots():
    robot = fo.KinematicSkidSteer((0, 0, 0))
    assert isinstance(robot, fo.SideDrivenRobot)
    assert [w.name for w in robot.spec.driven_wheels] == ["FL", "FR", "RL", "RR"]
    assert [w.position for w in robot.spec.driven_wheels] == [
        (0.05, 0.06), (0.05, -0.06), (-0.05, 0.06), (-0.05, -0.06)]
    sb = pytest.importorskip("wheelkin.sandbox")
    assert isinstance(sb.World().add(sb.LAB_ROBOT), fo.SideDrivenRobot)
    assert not isinstance(object(), fo.SideDrivenRobot)


@pytest.mark.parametrize("kwargs, match", [
    ({"pose": (0, 0)}, "pose"),
    ({"wheel_radius": 0.0}, "wheel_radius"),
    ({"track_width": math.nan}, "track_width"),
    ({"wheelbase": -1.0}, "wheelbase"),
    ({"skid_factor": 0.5}, "skid_factor"),
    ({"skid_factor": True}, "skid_factor"),
    ({"steps_per_rev": 0}, "steps_per_rev"),
    ({"steps_per_rev": 2.5}, "steps_per_rev"),
    ({"steps_per_rev": True}, "steps_per_rev"),
    ({"motor_time_constant": -0.1}, "motor_time_constant"),
])
def test_reduced_model_rejects_bad_input(kwargs, match):
    args = {"pose": (0.0, 0.0, 0.0)} | kwargs
    pose = args.pop("pose")
    with pytest.raises(ValueError, match=match):
        fo.KinematicSkidSteer(pose, **args)


def test_reduced_model_methods_reject_bad_input():
    robot = fo.KinematicSkidSteer((0, 0, 0))
    with pytest.raises(ValueError, match="left"):
        robot.set_side_rates(math.nan, 0.0)
    with pytest.raises(ValueError, match="right"):
        robot.set_side_rates(0.0, "fast")
    for h in (0.0, -0.1, math.inf, 5e-324 * -1, None):
        with pytest.raises(ValueError, match="h"):
            robot.step(h)


def test_wheel_layout_records_validate():
    with pytest.raises(TypeError, match="name"):
        fo.DrivenWheel(3, (0.0, 0.1))
    with pytest.raises(ValueError, match="position"):
        fo.DrivenWheel("FL", (0.0, math.nan))
    with pytest.raises(ValueError, match="position"):
        fo.DrivenWheel("FL", (0.0, 0.1, 0.2))
    with pytest.raises(TypeError, match="driven_wheels"):
        fo.WheelLayout(())
    with pytest.raises(TypeError, match="driven_wheels"):
        fo.WheelLayout(((0.0, 0.1),))


# --------------------------------------------------------------------------- the controllers
def test_follower_controller_caps_both_sides_together():
    robot = fo.KinematicSkidSteer((0, 0, 0))
    ctrl = fo.FollowerController(robot, fo.PathFollower(wp.plan_segments([[0, 0], [1, 0]])),
                                 wheel_radius=0.05, track_width=0.2, max_wheel_rate=10.0)
    # v = 1 m/s, omega = 2 rad/s: rims 0.8 and 1.2 m/s = 16 and 24 rad/s; scaled by 10/24
    left, right = ctrl.rates(1.0, 2.0)
    assert (left, right) == pytest.approx((16 * 10 / 24, 10.0))
    assert ctrl.rates(0.1, 0.0) == pytest.approx((2.0, 2.0))  # under the cap: unchanged
    with pytest.raises(ValueError, match="yaw_rate"):
        ctrl.rates(0.1, math.inf)
    with pytest.raises(ValueError, match="t"):
        ctrl(math.nan)


def test_closed_loop_on_the_reduced_model_reaches_every_waypoint():
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    robot = fo.KinematicSkidSteer(segs[0].start, skid_factor=1.0, motor_time_constant=0.0)
    ctrl = fo.FollowerController(robot, fo.PathFollower(segs), wheel_radius=R_W,
                                 track_width=2 * D, max_wheel_rate=10.0)
    h = 0.016
    for k in range(6000):
        ctrl(k * h)
        robot.step(h)
        if ctrl.finish_time is not None:
            break
    truth = robot.path()
    assert ctrl.finish_time is not None
    assert wp.waypoint_errors(truth).max() < 0.02  # every waypoint within 2 cm
    assert wp.distance_to_walls(truth[:, :2]).min() > 0.1  # never near a wall
    # an ideal robot, no lag, ideal encoders: rates held over a tick make one arc, so the
    # estimate is the truth at each tick
    est = np.array(ctrl.log_estimate)
    ticks = np.round(np.array(ctrl.log_t) / h).astype(int)
    np.testing.assert_allclose(est[:, :2], truth[ticks, :2], atol=1e-9)


def test_schedule_controller_plays_the_plan_on_the_reduced_model():
    segs = wp.plan_segments([[0, 0], [1, 0], [1, 1]], arc_radius=None)
    cmds = wp.schedule(segs, R_W, D)
    robot = fo.KinematicSkidSteer(segs[0].start, skid_factor=1.0, motor_time_constant=0.0)
    ctrl = fo.ScheduleController(robot, cmds)
    h = 0.001
    end = float(wp.schedule_times(cmds)[-1])
    for k in range(int(end / h) + 10):
        ctrl(k * h)
        robot.step(h)
    x, y, theta = robot.pose
    assert (x, y) == pytest.approx((1.0, 1.0), abs=0.02)
    assert theta == pytest.approx(math.pi / 2, abs=0.03)
