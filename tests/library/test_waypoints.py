"""Tests of wheelkin.waypoints against hand calculations, first-principles simulation and
symmetry properties (the lab's path, the schedule, the lab's odometry, the follower)."""

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelkin import follower as fo
from wheelkin import waypoints as wp

R_W, D = 0.04, 0.06  # the Webots tutorial robot: wheel radius, half axle (m)


# --------------------------------------------------------------------------- the lab's path
def test_lab_waypoints_are_the_documents():
    # typed from the lab's text: P0(1.5, -1.5) ... P12(0.5, -1.5)
    text = ("P0(1.5, -1.5) P1(1.5, 1.0) P2(1.0, 1.5) P3(-1.0, 1.5) P4(-1.5, 1.0) P5(-1.5, 0.5) "
            "P6(0.0, 0.5) P7(0.5, 0.0) P8(0.0, -0.5) P9(-1.0, -0.5) P10(-1.5, -1.0) "
            "P11(-1.0, -1.5) P12(0.5, -1.5)")
    pts = [tuple(float(a) for a in p.split("(")[1].rstrip(")").split(","))
           for p in text.replace(", ", ",").split()]
    assert wp.LAB_WAYPOINTS.shape == (13, 2)
    np.testing.assert_array_equal(wp.LAB_WAYPOINTS, pts)
    with pytest.raises(ValueError):
        wp.LAB_WAYPOINTS[0, 0] = 0.0  # read-only


def test_lab_plan_by_hand():
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    kinds = [s.kind for s in segs]
    assert kinds == ["straight", "arc", "straight", "arc", "straight", "turn", "straight",
                     "arc", "arc", "straight", "arc", "arc", "straight"]
    arcs = [s for s in segs if s.kind == "arc"]
    # centres read off the figure: the ends of the inner walls
    assert [s.centre for s in arcs] == [(1.0, 1.0), (-1.0, 1.0), (0.0, 0.0), (0.0, 0.0),
                                       (-1.0, -1.0), (-1.0, -1.0)]
    # left (CCW) on P1->P2, P3->P4, P9->P10->P11; right (CW) around (0, 0)
    assert [round(s.radius, 9) for s in arcs] == [0.5, 0.5, -0.5, -0.5, 0.5, 0.5]
    turn = segs[5]
    assert turn.start[:2] == (-1.5, 0.5) and turn.heading_change == pytest.approx(math.pi / 2)
    straights = [round(s.length, 9) for s in segs if s.kind == "straight"]
    assert straights == [2.5, 2.0, 0.5, 1.5, 1.0, 1.5]
    total = sum(s.length for s in segs)
    assert total == pytest.approx(9.0 + 6 * (math.pi / 2) * 0.5)
    assert segs[0].start[2] == pytest.approx(math.pi / 2)  # facing north at P0
    # net heading: +pi/2 (start north) + 3 lefts + turn + 2 rights + 2 lefts = east (2 pi)
    assert segs[-1].end[2] == pytest.approx(2 * math.pi)


def test_segments_join_and_end_on_their_waypoints():
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    for a, b in itertools.pairwise(segs):
        np.testing.assert_allclose(a.end, b.start, atol=1e-12)
    for s in segs:
        # pose_at evaluates arcs from centre and radius: independent of how `end` was set
        np.testing.assert_allclose(s.pose_at(1.0), s.end, atol=1e-12)
        np.testing.assert_allclose(s.pose_at(0.0), s.start, atol=1e-12)
        if s.target is not None:
            np.testing.assert_allclose(s.end[:2], wp.LAB_WAYPOINTS[s.target], atol=1e-12)
    assert [s.target for s in segs if s.target is not None] == list(range(1, 13))


def test_arc_points_are_on_their_circle_and_tangent():
    for s in wp.plan_segments(wp.LAB_WAYPOINTS):
        if s.kind != "arc":
            continue
        p = s.pose_at(np.linspace(0, 1, 21))
        rad = np.hypot(p[:, 0] - s.centre[0], p[:, 1] - s.centre[1])
        np.testing.assert_allclose(rad, 0.5, atol=1e-12)
        # the heading is perpendicular to the radius: tangent
        radial = np.stack([p[:, 0] - s.centre[0], p[:, 1] - s.centre[1]], axis=1)
        heading = np.stack([np.cos(p[:, 2]), np.sin(p[:, 2])], axis=1)
        np.testing.assert_allclose(np.sum(radial * heading, axis=1), 0, atol=1e-12)


def test_the_maze_holds_the_path_with_room_for_the_robot():
    path = wp.sample_path(wp.plan_segments(wp.LAB_WAYPOINTS), spacing=0.005)
    clearance = wp.distance_to_walls(path[:, :2])
    # the robot's footprint reaches 0.09 m along and about 0.07 m across: radius < 0.12 m
    assert clearance.min() == pytest.approx(0.5, abs=1e-6)
    # every straight leg is on a corridor's centre line: 0.5 m from two walls
    assert all(-2 <= c <= 2 for w in wp.LAB_WALLS for p in w for c in p)


def test_sample_path_spacing_and_ends():
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    p = wp.sample_path(segs, spacing=0.02)
    steps = np.hypot(*np.diff(p[:, :2], axis=0).T)
    assert steps.max() <= 0.02 + 1e-12
    np.testing.assert_allclose(p[0], segs[0].start)
    np.testing.assert_allclose(p[-1], segs[-1].end)
    assert np.all(np.abs(np.diff(p[:, 2])) <= 0.05 + 1e-12)  # headings continuous


def test_initial_heading_east_turns_first():
    segs = wp.plan_segments(wp.LAB_WAYPOINTS, initial_heading=0.0)
    assert segs[0].kind == "turn" and segs[0].heading_change == pytest.approx(math.pi / 2)
    assert [s.kind for s in segs[1:]] == [s.kind for s in wp.plan_segments(wp.LAB_WAYPOINTS)]


def test_point_behind_turns_left_by_pi_and_no_arcs_option():
    segs = wp.plan_segments([[0, 0], [1, 0], [0, 0]])
    assert segs[1].kind == "turn" and segs[1].heading_change == pytest.approx(math.pi)
    segs = wp.plan_segments([[0, 0], [1, 0], [1.5, 0.5]], arc_radius=None)
    assert [s.kind for s in segs] == ["straight", "turn", "straight"]
    assert segs[1].heading_change == pytest.approx(math.pi / 4)
    assert segs[2].length == pytest.approx(math.sqrt(0.5))


# a random motion program: start pose, then moves ("S", L), ("A", +-1), ("T", angle, L)
moves = st.lists(
    st.one_of(
        st.tuples(st.just("S"), st.floats(0.1, 3.0)),
        st.tuples(st.just("A"), st.sampled_from([-1.0, 1.0])),
        st.tuples(st.just("T"), st.floats(0.2, 3.0) | st.floats(-3.0, -0.2),
                  st.floats(0.1, 3.0)),
    ),
    min_size=1, max_size=8,
)


def _waypoints_from(program, x, y, theta, radius):
    """Drive a motion program by hand geometry; return the waypoints and the expected plan."""
    pts, expected = [(x, y)], []
    for move in program:
        if move[0] == "S":
            x, y = x + move[1] * math.cos(theta), y + move[1] * math.sin(theta)
            expected.append(("straight", move[1], 0.0))
        elif move[0] == "A":
            sign = move[1]
            # quarter circle: a chord at 45 degrees, of length R*sqrt(2)
            x += radius * (math.cos(theta) - sign * math.sin(theta))
            y += radius * (math.sin(theta) + sign * math.cos(theta))
            theta += sign * math.pi / 2
            expected.append(("arc", radius * math.pi / 2, sign * math.pi / 2))
        else:
            theta += move[1]
            x, y = x + move[2] * math.cos(theta), y + move[2] * math.sin(theta)
            expected += [("turn", 0.0, move[1]), ("straight", move[2], 0.0)]
        pts.append((x, y))
    return np.array(pts), expected


@settings(max_examples=60, deadline=None)
@given(program=moves, x=st.floats(-5, 5), y=st.floats(-5, 5), theta=st.floats(-3.1, 3.1),
       radius=st.floats(0.1, 2.0))
def test_planner_recovers_a_random_motion_program(program, x, y, theta, radius):
    # a turn whose angle is +-pi/4 followed by sqrt(2) R would look like an arc: skip those
    for m in program:
        if m[0] == "T" and abs(abs(m[1]) - math.pi / 4) < 1e-3:
            return
    pts, expected = _waypoints_from(program, x, y, theta, radius)
    segs = wp.plan_segments(pts, arc_radius=radius, initial_heading=theta)
    got = [(s.kind, s.length, s.heading_change) for s in segs]
    assert [g[0] for g in got] == [e[0] for e in expected]
    np.testing.assert_allclose([g[1] for g in got], [e[1] for e in expected], atol=1e-6)
    np.testing.assert_allclose([g[2] for g in got], [e[2] for e in expected], atol=1e-6)


@settings(max_examples=40, deadline=None)
@given(alpha=st.floats(-math.pi, math.pi), shift=st.tuples(st.floats(-3, 3), st.floats(-3, 3)))
def test_plan_is_invariant_under_rotation_and_translation(alpha, shift):
    c, s = math.cos(alpha), math.sin(alpha)
    rot = np.array([[c, -s], [s, c]])
    moved = wp.LAB_WAYPOINTS @ rot.T + np.array(shift)
    a = wp.plan_segments(wp.LAB_WAYPOINTS)
    b = wp.plan_segments(moved)
    assert [s.kind for s in a] == [s.kind for s in b]
    np.testing.assert_allclose([s.length for s in a], [s.length for s in b], atol=1e-9)
    np.testing.assert_allclose([s.heading_change for s in a], [s.heading_change for s in b],
                               atol=1e-9)


def test_mirrored_path_turns_the_other_way():
    mirrored = wp.LAB_WAYPOINTS * np.array([1.0, -1.0])  # reflect in the x axis
    a = wp.plan_segments(wp.LAB_WAYPOINTS)
    b = wp.plan_segments(mirrored)
    assert [s.kind for s in a] == [s.kind for s in b]
    np.testing.assert_allclose([s.heading_change for s in b], [-s.heading_change for s in a])
    np.testing.assert_allclose([s.radius for s in b if s.kind == "arc"],
                               [-s.radius for s in a if s.kind == "arc"])
    ca, cb = schedule_rates(a), schedule_rates(b)
    np.testing.assert_allclose(cb, ca[:, ::-1])  # left and right swap


def schedule_rates(segs):
    return np.array([[c.left_rate, c.right_rate] for c in wp.schedule(segs, R_W, D)])


# --------------------------------------------------------------------------- the schedule
def _drive(pose, left_rate, right_rate, duration, r=R_W, d=D):
    """Exact pose after holding wheel rates (ideal differential drive, closed form)."""
    x, y, th = pose
    v = r * (left_rate + right_rate) / 2
    w = r * (right_rate - left_rate) / (2 * d)
    if abs(w) < 1e-12:
        return x + v * duration * math.cos(th), y + v * duration * math.sin(th), th
    th1 = th + w * duration
    return (x + v / w * (math.sin(th1) - math.sin(th)),
            y - v / w * (math.cos(th1) - math.cos(th)), th1)


def test_schedule_drives_an_ideal_robot_along_the_plan():
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    pose = segs[0].start
    for c in wp.schedule(segs, R_W, D):
        pose = _drive(pose, c.left_rate, c.right_rate, c.duration)
        np.testing.assert_allclose(pose, c.segment.end, atol=1e-9)
    np.testing.assert_allclose(pose[:2], wp.LAB_WAYPOINTS[-1], atol=1e-9)


def test_schedule_matches_the_labs_hand_formulas():
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    cmds = wp.schedule(segs, R_W, D, wheel_rate=7.5)
    V = 7.5 * 0.04  # 0.3 m/s
    R = 0.5
    for c in cmds:
        outer = max(abs(c.left_rate), abs(c.right_rate))
        assert outer == pytest.approx(7.5)
        if c.segment.kind == "straight":
            assert c.left_rate == c.right_rate == pytest.approx(7.5)
            assert c.duration == pytest.approx(c.segment.length / V)
        elif c.segment.kind == "arc":
            inner_rate = min(c.left_rate, c.right_rate)
            # the lab: yaw rate V/(R + d), inner rim speed = that times (R - d)
            assert inner_rate * R_W == pytest.approx(V / (R + D) * (R - D))
            # distances of the wheels: 2 pi (R -+ d) / 4
            assert inner_rate * R_W * c.duration == pytest.approx(2 * math.pi * (R - D) / 4)
            assert outer * R_W * c.duration == pytest.approx(2 * math.pi * (R + D) / 4)
            # left turn: the left wheel is the inner one
            left_turn = c.segment.heading_change > 0
            assert (c.left_rate < c.right_rate) == left_turn
        else:
            assert c.left_rate == pytest.approx(-c.right_rate)
            assert c.right_rate > 0  # a left (CCW) turn: right wheels forward
            assert outer * R_W * c.duration == pytest.approx(math.pi / 2 * D)  # d_rotate


@settings(max_examples=30, deadline=None)
@given(k=st.floats(0.1, 10.0), rate=st.floats(0.5, 20.0))
def test_schedule_scales_with_the_wheel_rate(k, rate):
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    a = wp.schedule(segs, R_W, D, wheel_rate=rate)
    b = wp.schedule(segs, R_W, D, wheel_rate=k * rate)
    np.testing.assert_allclose([c.left_rate * k for c in a], [c.left_rate for c in b])
    np.testing.assert_allclose([c.duration / k for c in a], [c.duration for c in b])


def test_schedule_times_and_quantise():
    cmds = wp.schedule(wp.plan_segments(wp.LAB_WAYPOINTS), R_W, D)
    times = wp.schedule_times(cmds)
    assert times[0] == 0 and np.all(np.diff(times) > 0)
    assert times[-1] == pytest.approx(sum(c.duration for c in cmds))
    q = wp.quantise(cmds, 0.064)
    for a, b in zip(cmds, q, strict=True):
        n = b.duration / 0.064
        assert n == pytest.approx(round(n))
        assert a.duration <= b.duration + 1e-12 < a.duration + 0.064 + 1e-12
        assert (a.left_rate, a.right_rate) == (b.left_rate, b.right_rate)
    exact = wp.quantise(wp.schedule(wp.plan_segments([[0, 0], [0.3, 0]]), R_W, D), 0.25)
    assert exact[0].duration == pytest.approx(1.0)  # already a whole number of periods


# ---------------------------------------------------------------------- the lab's odometry
def _circle_wheels(n, radius, angle, r=R_W, d=D):
    """Cumulative wheel angles FL, FR, RL, RR of an ideal robot on a left circle."""
    s = np.linspace(0, angle, n + 1)  # heading swept
    left = s * (radius - d) / r
    right = s * (radius + d) / r
    return np.stack([left, right, left, right], axis=1), s


def test_average_encoder_odometry_converges_to_the_circle():
    for n, tol in [(50, 0.03), (2000, 1e-3)]:
        phi, s = _circle_wheels(n, 0.5, math.pi / 2)
        est = wp.average_encoder_odometry(phi, R_W, D, pose=(0.0, 0.0, 0.0))
        np.testing.assert_allclose(est[:, 2], s, atol=1e-12)  # heading from the wheels: exact
        exact = np.stack([0.5 * np.sin(s), 0.5 * (1 - np.cos(s))], axis=1)
        err = np.max(np.hypot(*(est[:, :2] - exact).T))
        assert err < tol
    # Euler error is first order: it halves when the number of updates doubles
    e = []
    for n in (200, 400):
        phi, s = _circle_wheels(n, 0.5, math.pi / 2)
        est = wp.average_encoder_odometry(phi, R_W, D)
        e.append(math.hypot(est[-1, 0] - 0.5, est[-1, 1] - 0.5))
    assert e[0] / e[1] == pytest.approx(2.0, rel=0.05)


def test_average_encoder_odometry_with_a_compass_and_bad_input():
    phi, s = _circle_wheels(10, 1.0, 1.0)
    est = wp.average_encoder_odometry(phi, R_W, D, heading=s + 0.1)
    np.testing.assert_allclose(est[:, 2], s + 0.1)
    with pytest.raises(ValueError, match="heading"):
        wp.average_encoder_odometry(phi, R_W, D, heading=s[:-1])
    with pytest.raises(ValueError, match="wheel_angles"):
        wp.average_encoder_odometry(phi[:, :2], R_W, D)
    with pytest.raises(ValueError, match="half_axle"):
        wp.average_encoder_odometry(phi, R_W, 0.0)
    with pytest.raises(ValueError, match="pose"):
        wp.average_encoder_odometry(phi, R_W, D, pose=(0, 0))


# --------------------------------------------------------------------------- the follower
def _kinematic_run(follower, pose, *, period=8, dt=1 / 240, tau=0.05, max_time=120.0,
                   scale_yaw=1.0):
    """First-principles unicycle with a first-order motor lag, controlled every `period`
    steps; `scale_yaw` < 1 mimics a robot that turns less than commanded."""
    pose = np.array(pose, dtype=float)
    vel = np.zeros(2)
    cmd = (0.0, 0.0)
    out = [pose.copy()]
    for k in range(int(max_time / dt)):
        if k % period == 0:
            cmd = follower.command(pose)
            if follower.done and np.allclose(vel, 0, atol=1e-3):
                break
        vel += (np.array(cmd) - vel) * dt / tau
        th = pose[2]
        pose = pose + dt * np.array([vel[0] * math.cos(th), vel[0] * math.sin(th),
                                     scale_yaw * vel[1]])
        out.append(pose.copy())
    return np.array(out), k * dt


@pytest.mark.parametrize("start, scale_yaw", [
    ((1.5, -1.5, math.pi / 2), 1.0),
    ((1.55, -1.45, math.pi / 2 + 0.2), 1.0),  # displaced and misaligned
    ((1.5, -1.5, math.pi / 2), 0.6),  # turns only 60 % of what it is told
])
def test_follower_reaches_every_waypoint_without_touching_a_wall(start, scale_yaw):
    f = fo.PathFollower(wp.plan_segments(wp.LAB_WAYPOINTS))
    path, t = _kinematic_run(f, start, scale_yaw=scale_yaw)
    assert f.done
    assert np.max(wp.waypoint_errors(path)[1:]) < 0.02  # P0 is where it was put
    assert np.hypot(*(path[-1, :2] - wp.LAB_WAYPOINTS[-1])) < 0.02
    assert wp.distance_to_walls(path[:, :2]).min() > 0.4  # footprint radius < 0.12 m
    # the lap is no faster than the plan at the cruising speed
    assert t > 13.7 / 0.3
    assert f.command(path[-1]) == (0.0, 0.0)


def test_follower_turns_toward_a_carrot_behind_and_reset():
    f = fo.PathFollower(wp.plan_segments([[0, 0], [1, 0]]), max_turn_rate=1.5)
    v, w = f.command((0.5, 0.0, math.pi))  # facing backwards
    assert v == 0 and abs(w) == pytest.approx(1.5)
    f.index = 1
    assert f.done
    f.reset()
    assert f.index == 0 and not f.done


def test_follower_bad_input():
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    for name in ("speed", "lookahead", "heading_gain", "max_turn_rate", "heading_tolerance",
                 "approach_gain"):
        with pytest.raises(ValueError, match=name):
            fo.PathFollower(segs, **{name: 0.0})
    with pytest.raises(ValueError, match="min_speed"):
        fo.PathFollower(segs, min_speed=0.0)
    with pytest.raises(ValueError, match="min_speed"):
        fo.PathFollower(segs, speed=0.1, min_speed=0.2)
    with pytest.raises(ValueError, match="segments"):
        fo.PathFollower([1, 2])
    with pytest.raises(ValueError, match="pose"):
        fo.PathFollower(segs).command((0.0, float("nan"), 0.0))


# --------------------------------------------------------------------------- helpers
def test_distance_to_walls_and_waypoint_errors_by_hand():
    walls = [((0, 0), (1, 0))]
    np.testing.assert_allclose(wp.distance_to_walls([[0.5, 2], [2, 0], [-3, -4]], walls),
                               [2, 1, 5])
    np.testing.assert_allclose(wp.waypoint_errors([[0, 0], [3, 4]], [[0, 1], [3, 5]]), [1, 1])
    with pytest.raises(ValueError, match="walls"):
        wp.distance_to_walls([[0, 0]], [(0, 0)])
    with pytest.raises(ValueError, match="path"):
        wp.waypoint_errors([1, 2, 3, 4])


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("points, match", [
    ([[0, 0]], "at least two"),
    ([[0, 0], [0, 0]], r"waypoints\[1\] repeats waypoints\[0\]"),
    ([[0, 0], [1, 1], [1, 1]], r"waypoints\[2\] repeats"),
    ([[0, 0], [1, float("nan")]], "waypoints must not contain NaN"),
    ([0, 1, 2], r"waypoints must have shape \(N, 2\)"),
    ([["a", "b"], [1, 1]], "waypoints must be numeric"),
])
def test_plan_rejects_bad_waypoints(points, match):
    with pytest.raises(ValueError, match=match):
        wp.plan_segments(points)


def test_plan_rejects_bad_radius_and_heading():
    for bad in (0.0, -0.5, float("inf")):
        with pytest.raises(ValueError, match="arc_radius"):
            wp.plan_segments(wp.LAB_WAYPOINTS, arc_radius=bad)
    with pytest.raises(ValueError, match=r"does not fit arc_radius=0\.3"):
        wp.plan_segments(wp.LAB_WAYPOINTS, arc_radius=0.3)
    with pytest.raises(ValueError, match="initial_heading"):
        wp.plan_segments(wp.LAB_WAYPOINTS, initial_heading=float("nan"))


def test_schedule_rejects_bad_input():
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    for kwargs, name in [(dict(wheel_radius=0.0), "wheel_radius"),
                         (dict(half_axle=-0.06), "half_axle"),
                         (dict(wheel_rate=0.0), "wheel_rate"),
                         (dict(wheel_rate=float("nan")), "wheel_rate")]:
        args = dict(wheel_radius=R_W, half_axle=D) | kwargs
        with pytest.raises(ValueError, match=name):
            wp.schedule(segs, **args)
    with pytest.raises(ValueError, match="segments"):
        wp.schedule([], R_W, D)
    with pytest.raises(ValueError, match="segments"):
        wp.schedule(3, R_W, D)
    with pytest.raises(ValueError, match="commands"):
        wp.quantise([1], 0.1)
    with pytest.raises(ValueError, match="period"):
        wp.quantise(wp.schedule(segs, R_W, D), 0.0)
    with pytest.raises(ValueError, match="fraction"):
        segs[0].pose_at(1.5)


# --------------------------------------------------------------------------- the plan, driven


def test_planned_pose_and_wheel_angles_follow_the_ideal_robot():
    segs = wp.plan_segments(wp.LAB_WAYPOINTS)
    cmds = wp.schedule(segs, R_W, D)
    times = wp.schedule_times(cmds)
    rng = np.random.default_rng(3)
    for i, c in enumerate(cmds):
        # closed-form drive from the segment's start for part of the command
        tau = rng.uniform(0, c.duration)
        expected = _drive(c.segment.start, c.left_rate, c.right_rate, tau)
        np.testing.assert_allclose(wp.planned_pose(cmds, times[i] + tau), expected, atol=1e-9)
    np.testing.assert_allclose(wp.planned_pose(cmds, [-1.0, times[-1] + 5]),
                               [segs[0].start, segs[-1].end])
    # wheel angles: the rates integrated; at the end, the left side rolled the path length
    # minus the turns (left turns: the left wheel is inner) -- check by summing by hand
    ang = wp.planned_wheel_angles(cmds, times)
    by_hand = np.cumsum([[c.left_rate * c.duration, c.right_rate * c.duration] for c in cmds],
                        axis=0)
    np.testing.assert_allclose(ang[1:], by_hand)
    # heading from the wheels equals the planned heading (ideal robot)
    heading = segs[0].start[2] + R_W * (ang[:, 1] - ang[:, 0]) / (2 * D)
    np.testing.assert_allclose(heading, wp.planned_pose(cmds, times)[:, 2], atol=1e-9)


# --------------------------------------------------------------------------- sandbox controllers
def _sandbox():
    return pytest.importorskip("wheelkin.sandbox")


def test_schedule_controller_drives_a_rolling_robot_along_the_plan():
    sb = _sandbox()
    spec = sb.diff_drive(0.12, 0.04, mass=1.4)
    segs = wp.plan_segments([[0, 0], [0.3, 0], [0.8, 0.5], [0.8, 0.9]])  # straight, left arc
    cmds = wp.schedule(segs, 0.04, 0.06, wheel_rate=2.0)
    world = sb.World(dt=1 / 240)
    # start already rolling at the first command's speed: no start-up slip
    robot = world.add(spec, pose=segs[0].start, twist=(cmds[0].speed, 0.0, 0.0))
    ctrl = fo.ScheduleController(robot, cmds)
    world.run(wp.schedule_times(cmds)[-1] + 0.5, ctrl)
    assert ctrl.done
    np.testing.assert_allclose(ctrl.switch_times, wp.schedule_times(cmds))
    # the wheels turned exactly as scheduled, whatever the step boundaries
    planned = wp.planned_wheel_angles(cmds, 1e9)
    np.testing.assert_allclose(robot.wheel_angles[:2], planned, atol=1e-9)
    # and, rolling without slip, the robot is where the plan ends
    np.testing.assert_allclose(robot.pose[:2], segs[-1].end[:2], atol=1e-3)
    assert robot.pose[2] == pytest.approx(segs[-1].end[2], abs=1e-3)
    np.testing.assert_allclose(robot.commanded_rates[:2], 0.0)


def test_schedule_controller_switching_on_encoders():
    sb = _sandbox()
    spec = sb.diff_drive(0.12, 0.04, mass=1.4)
    segs = wp.plan_segments([[0, 0], [0.5, 0]])
    cmds = wp.schedule(segs, 0.04, 0.06, wheel_rate=2.0)  # 0.08 m/s
    world = sb.World(dt=1 / 240)
    robot = world.add(spec, pose=segs[0].start, twist=(0.08, 0.0, 0.0))
    ctrl = fo.ScheduleController(robot, cmds, switch="encoders", period=0.05)
    world.run(8.0, ctrl)
    assert ctrl.done
    # it stops at the first check after the wheels rolled 0.5 m: at most one period later
    travelled = 0.04 * float(np.mean(robot.wheel_angles[:2]))
    assert 0.5 <= travelled <= 0.5 + 0.08 * (0.05 + 1 / 240) + 1e-9
    assert ctrl.switch_times[-1] - ctrl.switch_times[0] == pytest.approx(0.5 / 0.08, abs=0.06)


def test_follower_controller_reaches_a_corner_on_a_skid_steer():
    sb = _sandbox()
    a, b = 0.05, 0.06  # the lab robot: half wheelbase, half track
    chi = 1 + (a / b) ** 2  # Coulomb friction, pure spin: yaw rate / ideal = b^2 / (a^2 + b^2)
    segs = wp.plan_segments([[0, 0], [0.6, 0], [0.6, 0.4]], arc_radius=None)
    world = sb.World(dt=0.008)
    robot = world.add(sb.LAB_ROBOT.replace(motor_time_constant=0.05), pose=segs[0].start)
    ctrl = fo.FollowerController(robot, fo.PathFollower(segs), wheel_radius=0.04,
                                 track_width=0.12 * chi, max_wheel_rate=10.0)
    traj = world.run(8.0, ctrl)
    assert ctrl.finish_time is not None and ctrl.follower.done
    assert np.max(wp.waypoint_errors(traj.pose, [[0.6, 0.0], [0.6, 0.4]])) < 0.02
    est = np.array(ctrl.log_estimate)
    assert np.hypot(*(est[-1, :2] - traj.pose[-1, :2])) < 0.02
    assert np.all(np.abs(traj.commanded_rates) <= 10.0 + 1e-9)
    np.testing.assert_allclose(ctrl.log_t[1] - ctrl.log_t[0], 0.064, atol=0.008)


def test_controllers_reject_bad_input():
    sb = _sandbox()
    world = sb.World()
    robot = world.add(sb.LAB_ROBOT)
    segs = wp.plan_segments([[0, 0], [1, 0]])
    cmds = wp.schedule(segs, 0.04, 0.06)
    with pytest.raises(TypeError, match="robot"):
        fo.ScheduleController(object(), cmds)
    with pytest.raises(ValueError, match="switch"):
        fo.ScheduleController(robot, cmds, switch="distance")
    with pytest.raises(ValueError, match="commands"):
        fo.ScheduleController(robot, segs)
    with pytest.raises(TypeError, match="follower"):
        fo.FollowerController(robot, segs, wheel_radius=0.04, track_width=0.12)
    f = fo.PathFollower(segs)
    with pytest.raises(ValueError, match="track_width"):
        fo.FollowerController(robot, f, wheel_radius=0.04, track_width=0.0)
    with pytest.raises(ValueError, match="max_wheel_rate"):
        fo.FollowerController(robot, f, wheel_radius=0.04, track_width=0.12, max_wheel_rate=-1)
    with pytest.raises(ValueError, match="pose"):
        fo.FollowerController(robot, f, wheel_radius=0.04, track_width=0.12, pose=(0, 0))
