"""One rule for the heading (docs/DESIGN.md, "What the library returns", rule 3): no pose the
library returns is wrapped. A heading keeps its turns, as odometry over many turns needs (an
angle error is the signed difference of unwrapped headings); :func:`wheelkin.frames.wrap_angle`
wraps where a wrapped angle is meant.

The pose-returning functions are found from the registry: every public callable of the formula
modules is called with the bad-input sweep's valid arguments, and those whose result holds a
:class:`~wheelkin.frames.Pose` are swept. One with a pose parameter is called again with that
pose turned by a whole turn: a function that wraps returns the same heading, one that does not
returns a heading a whole number of turns away. One without a pose parameter must be in
:data:`BEYOND_HALF_A_TURN`, a call whose heading is worked out by hand past pi.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import test_bad_input as sweep
from test_pose_arguments import _pose_parameters

from wheelkin import frames, sources, waypoints
from wheelkin.frames import Pose, Twist

TURN = 2.0 * math.pi
SQUARE = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0], [1.0, 0.0]]


def _square_commands():
    return waypoints.schedule(waypoints.plan_segments(SQUARE), 0.04, 0.06)


def poses_in(out, depth: int = 0) -> list[Pose]:
    """The Poses in a result (itself, a record's fields, a list's items)."""
    if depth > 3:
        return []
    if isinstance(out, Pose):
        return [out]
    if dataclasses.is_dataclass(out) and not isinstance(out, type):
        return [p for f in dataclasses.fields(out)
                for p in poses_in(getattr(out, f.name), depth + 1)]
    if isinstance(out, tuple | list):
        return [p for o in out for p in poses_in(o, depth + 1)]
    return []


def _call(fn, kwargs):
    if "rng" in kwargs:
        kwargs = kwargs | {"rng": np.random.default_rng(0)}
    return fn(**kwargs)


def _pose_returning():
    good = sweep._good_values()
    for qualname, fn in sweep._public_callables():
        if isinstance(fn, type):
            continue  # a record or an object: its constructor keeps what it is given
        kwargs = sweep._resolve(qualname, sweep._good_call(qualname, fn, good)
                                | sweep.OVERRIDES.get(qualname, {}))
        if poses_in(_call(fn, kwargs)):
            names = [n for n in _pose_parameters(fn) if np.shape(kwargs.get(n)) == (3,)]
            yield qualname, fn, kwargs, names


FOUND = list(_pose_returning())
WITH_POSE = [f for f in FOUND if f[3]]

#: Calls of the pose-returning functions without a pose parameter, each with its heading
#: worked out by hand, past pi (a wrapped result would be that heading less a turn).
BEYOND_HALF_A_TURN = {
    "frames.se2_exp": (lambda: frames.se2_exp(Twist(0.0, 0.0, 2.0), 2.0), 4.0),
    "sources.lab_pose_to_ours": (lambda: sources.lab_pose_to_ours(1.0, 2.0, 4.0), 4.0),
    "sources.firmware_pose_to_ours": (lambda: sources.firmware_pose_to_ours(1.0, 2.0, 4.0),
                                      4.0),
    # psi = -3 rad (counter-clockwise of north): theta = pi/2 + 3
    "sources.mecanum_doc_pose_to_ours": (
        lambda: sources.mecanum_doc_pose_to_ours(1.0, 2.0, -3.0), math.pi / 2 + 3.0),
    # A square driven counter-clockwise and on to its second side: four left turns, 2 pi.
    "waypoints.plan_segments": (lambda: waypoints.plan_segments(SQUARE), TURN),
    "waypoints.validate_segments": (
        lambda: waypoints.validate_segments(waypoints.plan_segments(SQUARE)), TURN),
    "waypoints.schedule": (lambda: _square_commands(), TURN),
    "waypoints.validate_commands": (lambda: waypoints.validate_commands(_square_commands()),
                                    TURN),
    "waypoints.quantise": (lambda: waypoints.quantise(_square_commands(), 0.01), TURN),
    "waypoints.planned_pose": (
        lambda: waypoints.planned_pose(_square_commands(),
                                       waypoints.schedule_times(_square_commands())[-1]),
        TURN),
    # the initial heading as given: 3 pi / 2 (wrapped, it would be -pi / 2)
    "waypoints.plan_segments, initial_heading": (
        lambda: waypoints.plan_segments([[0.0, 0.0], [0.0, -1.0]],
                                        initial_heading=1.5 * math.pi)[:1], 1.5 * math.pi),
}


def test_the_sweep_finds_the_pose_returning_functions():
    found = {q for q, *_ in FOUND}
    assert {"frames.compose", "frames.inverse", "frames.relative", "frames.se2_exp",
            "odometry.pose_update", "odometry_uncertainty.propagate_covariance"} <= found
    assert len(WITH_POSE) >= 7


def test_every_pose_returning_function_is_swept():
    """A new pose-returning function without a pose parameter must be given a call above."""
    without = {q for q, _, _, names in FOUND if not names}
    assert without <= set(BEYOND_HALF_A_TURN), sorted(without - set(BEYOND_HALF_A_TURN))


@pytest.mark.parametrize(("qualname", "fn", "kwargs", "names"), WITH_POSE,
                         ids=[f[0] for f in WITH_POSE])
def test_a_whole_turn_in_is_a_whole_turn_out(qualname, fn, kwargs, names):
    name = names[0]
    x, y, theta = (float(c) for c in kwargs[name])
    before = poses_in(_call(fn, kwargs | {name: Pose(x, y, theta)}))
    after = poses_in(_call(fn, kwargs | {name: Pose(x, y, theta + TURN)}))
    for p, q in zip(before, after, strict=True):
        turns = (q.theta - p.theta) / TURN
        assert abs(round(turns)) >= 1, f"{qualname} wrapped the heading: {p.theta} {q.theta}"
        assert turns == pytest.approx(round(turns), abs=1e-9)
        assert (q.x, q.y) == pytest.approx((p.x, p.y), abs=1e-9)  # the same pose otherwise


@pytest.mark.parametrize("qualname", sorted(BEYOND_HALF_A_TURN))
def test_a_heading_past_pi_is_kept(qualname):
    call, theta = BEYOND_HALF_A_TURN[qualname]
    last = poses_in(call())[-1]  # the end of a plan, or the one pose
    assert last.theta == pytest.approx(theta, abs=1e-12)


def test_integrate_twist_keeps_the_turns():
    """A trajectory too: eight quarter turns are two whole turns, 4 pi."""
    poses = frames.integrate_twist([[0.0, 0.0, math.pi / 2]] * 8, 1.0, pose0=(0.0, 0.0, 0.0))
    assert poses[:, 2] == pytest.approx(np.arange(9) * math.pi / 2)


def test_compose_by_hand_past_pi():
    """Three quarters of a turn then half a turn: 5 pi / 2, not pi / 2."""
    p = frames.compose(Pose(0.0, 0.0, 1.5 * math.pi), Pose(1.0, 0.0, math.pi))
    assert tuple(p) == pytest.approx((0.0, -1.0, 2.5 * math.pi), abs=1e-12)
