"""The chapters' shared helpers that live beside their panels (wheelkin.widgets.*), against
independent values: hand calculations, closed forms, and the chapters' own derivations.
"""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")
import numpy as np
import pytest
from matplotlib.figure import Figure

from wheelkin import waypoints as wp
from wheelkin.sandbox import MECANUM_ROBOT, RADON_ULZER
from wheelkin.widgets.odometry import draw_ellipse, firmware_to_ours_mm, wheel_increments
from wheelkin.widgets.unified import MANOEUVRES, RAMP, run_manoeuvres
from wheelkin.widgets.waypoints import LAB_SPEC, draw_arena, run_schedule, spin_test_track


def _ax():
    return Figure(figsize=(4, 4)).add_subplot()


# ----------------------------------------------------------------------------- chapter 6


def test_firmware_rows_in_our_frame_by_hand():
    # The firmware: X to the right, Y forward, orientation counter-clockwise from +Y.
    # 10 mm right and 250 mm forward is x = 250 mm, y = -10 mm in ours; the heading is the same
    # angle measured from our forward axis.
    got = firmware_to_ours_mm([[10.0, 250.0, 0.5], [0.0, 0.0, -math.pi / 2]])
    np.testing.assert_allclose(got, [[250.0, -10.0, 0.5], [0.0, 0.0, -math.pi / 2]],
                               atol=1e-12)


def test_firmware_rows_must_be_rows_of_three():
    with pytest.raises(ValueError, match=r"rows must have shape \(N, 3\)"):
        firmware_to_ours_mm([1.0, 2.0, 3.0])


def test_wheel_increments_straight_and_spin():
    left, right = wheel_increments([(1.0, 0.0)], 0.085, 0.01)
    assert len(left) == 100
    np.testing.assert_allclose(left, 0.01, rtol=1e-12)
    np.testing.assert_allclose(right, left)
    # a quarter turn on the spot: each wheel rolls W/2 x pi/2 = 66.76 mm, in opposite senses
    left, right = wheel_increments([(0.0, math.pi / 2)], 0.085, 0.01)
    assert right.sum() == pytest.approx(0.085 / 2 * math.pi / 2, rel=1e-12)
    np.testing.assert_allclose(left, -right)
    assert len(left) == math.ceil(0.085 / 2 * math.pi / 2 / 0.01)
    assert np.abs(right).max() <= 0.01


def test_wheel_increments_bad_input_names_the_parameter():
    with pytest.raises(ValueError, match="track_width"):
        wheel_increments([(1.0, 0.0)], -0.085)


def test_draw_ellipse_axes_and_angle():
    ax = _ax()
    e = draw_ellipse(ax, (1.0, 2.0), [[4.0, 0.0], [0.0, 1.0]], sigmas=2.0)
    assert (e.width, e.height) == pytest.approx((8.0, 4.0))  # 2 x 2 sigma along x, y
    assert e.get_center() == pytest.approx((1.0, 2.0)) and not e.get_fill()
    # a covariance rotated by 30 degrees: the major axis along 30 degrees
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    rot = np.array([[c, -s], [s, c]])
    e = draw_ellipse(ax, (0, 0), rot @ np.diag([9.0, 1.0]) @ rot.T, color="r")
    assert (e.width, e.height) == pytest.approx((6.0, 2.0))
    assert e.angle % 180 == pytest.approx(30.0)
    assert len(ax.patches) == 2


@pytest.mark.parametrize(("cov", "message"), [
    ([[1.0, 0.0], [0.0, -1.0]], "positive semi-definite"),
    ([[1.0, 0.0, 0.0]], r"finite 2 x 2 matrix"),
    ([[1.0, math.nan], [0.0, 1.0]], r"finite 2 x 2 matrix"),
])
def test_draw_ellipse_bad_covariance(cov, message):
    with pytest.raises(ValueError, match=message):
        draw_ellipse(_ax(), (0, 0), cov)


def test_draw_ellipse_accepts_a_singular_covariance():
    e = draw_ellipse(_ax(), (0, 0), [[1.0, 1.0], [1.0, 1.0]])  # all the spread along x = y
    assert (e.width, e.height) == pytest.approx((2 * math.sqrt(2), 0.0), abs=1e-7)


# ----------------------------------------------------------------------------- chapter 7


def test_draw_arena_draws_the_walls_and_the_waypoints():
    ax = _ax()
    draw_arena(ax)
    assert len(ax.lines) == len(wp.LAB_WALLS) + len(wp.LAB_WAYPOINTS)
    assert [t.get_text() for t in ax.texts] == [f"P{k}" for k in range(13)]
    assert ax.get_xlim() == pytest.approx((-2.1, 2.1)) and ax.get_aspect() == 1.0
    ax = _ax()
    draw_arena(ax, labels=False)
    assert len(ax.lines) == len(wp.LAB_WALLS) and not ax.texts
    with pytest.raises(ValueError, match="labels must be True or False"):
        draw_arena(_ax(), labels="yes")


def test_run_schedule_drives_the_first_straight_to_its_end():
    segments = wp.plan_segments(wp.LAB_WAYPOINTS)
    commands = wp.schedule(segments[:1], wp.LAB_WHEEL_RADIUS, wp.LAB_HALF_AXLE)
    run = run_schedule(LAB_SPEC, commands, walls=())
    assert run.controller.done
    np.testing.assert_allclose(run.trajectory.pose[0], segments[0].start, atol=1e-12)
    # a straight line: no slip, and the motor lag loses at the start what it gains at the stop
    np.testing.assert_allclose(run.trajectory.pose[-1], segments[0].end, atol=1e-6)
    assert run.trajectory.t[1] - run.trajectory.t[0] == pytest.approx(0.008)


def test_run_schedule_bad_input():
    with pytest.raises(ValueError, match="spec must be a VehicleSpec"):
        run_schedule("lab robot", [])
    commands = wp.schedule(wp.plan_segments(wp.LAB_WAYPOINTS)[:1], 0.04, 0.06)
    with pytest.raises(ValueError, match="extra"):
        run_schedule(LAB_SPEC, commands, extra=-1.0)
    with pytest.raises(ValueError, match="switch"):
        run_schedule(LAB_SPEC, commands, switch="sometimes")


def test_spin_test_track_is_the_skid_factor_times_the_track():
    # Chapter 7 derives chi = 1 + (a / b)^2 for a skid steer spinning with Coulomb friction.
    a, b = wp.LAB_HALF_WHEELBASE, wp.LAB_HALF_AXLE
    assert spin_test_track() / (2 * b) == pytest.approx(1 + (a / b) ** 2, rel=1e-6)
    assert spin_test_track(0.004) / (2 * b) == pytest.approx(1 + (a / b) ** 2, rel=1e-6)


def test_spin_test_track_of_a_differential_drive_is_its_track():
    # Two wheels and a caster: nothing scrubs, the effective track is the geometric one.
    track = 2 * RADON_ULZER.wheels[0].position[1]
    assert spin_test_track(spec=RADON_ULZER, wheel_rate=5.0, duration=1.0) == pytest.approx(
        track, rel=1e-3)


def test_spin_test_track_bad_input():
    with pytest.raises(ValueError, match="wheel_rate"):
        spin_test_track(wheel_rate=0.0)
    with pytest.raises(ValueError, match="spec must be a VehicleSpec"):
        spin_test_track(spec="lab")


# ----------------------------------------------------------------------------- chapter 8


def test_run_manoeuvres_asks_the_ramped_twist_and_the_mecanum_delivers_it():
    runs = run_manoeuvres(vehicles={"mecanum": MECANUM_ROBOT})
    assert list(runs) == list(MANOEUVRES)
    full = 2.0 - RAMP / 2  # s at the full command: the linear ramp loses half its time
    for title, twist in MANOEUVRES.items():
        spec, traj, goal = runs[title]["mecanum"]
        assert spec is MECANUM_ROBOT and len(traj) == 481  # every step of 2 s at 240 Hz
        axis = 1 if twist[1] else 2
        assert goal[axis] == pytest.approx(max(twist) * full, abs=1e-9)
        assert traj.pose[-1, axis] == pytest.approx(goal[axis], rel=1e-3)
        assert not traj.slipping.any()
