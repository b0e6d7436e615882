"""One rule for what the library returns (docs/DESIGN.md, "What the library returns"):

1. one quantity: a Python ``float`` (``int`` in the integer emulation) for scalar input, an
   ``ndarray`` for array input; never a 0-d array or a NumPy scalar;
2. several named quantities: a ``NamedTuple`` whose fields follow rule 1; never a bare tuple;
   a pose or a twist is a :class:`~wheelkin.frames.Pose` or :class:`~wheelkin.frames.Twist`
   (NamedTuples too) when it is one, computed from scalars or from a Pose/Twist;
3. a fixed-layout vector given or computed as an array (poses and twists of shape (..., 3),
   wheel rates in a vehicle's wheel order, points, matrices) stays an ``ndarray``;
4. geometry and records: frozen dataclasses; a vehicle's wheels, a plan: a tuple or list of
   them.

Every public callable of the formula modules is called with valid scalar arguments (the
bad-input sweep's table) and its result walked; then the pose and twist functions are called
with Pose/Twist objects and with stacks of arrays.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest
import test_bad_input as sweep

from wheelkin import carlike, frames, mecanum, rover
from wheelkin.frames import Pose, Twist


def violations(out, where: str = "result", depth: int = 0) -> list[str]:
    """Where ``out`` breaks the rule (an empty list when it keeps it)."""
    if depth > 5:
        return []
    if isinstance(out, np.ndarray):
        return [f"{where} is a 0-d array"] if out.ndim == 0 else []
    if isinstance(out, np.generic):
        return [f"{where} is a NumPy scalar ({type(out).__name__})"]
    if isinstance(out, tuple) and hasattr(out, "_fields"):
        return [v for name, value in zip(out._fields, out, strict=True)
                for v in violations(value, f"{where}.{name}", depth + 1)]
    if isinstance(out, tuple | list):
        if out and all(dataclasses.is_dataclass(o) and not isinstance(o, type) for o in out):
            return []  # a collection of records: a vehicle's wheels, a plan's segments
        return [f"{where} is a bare {type(out).__name__} of "
                f"{', '.join(sorted({type(o).__name__ for o in out}))}"]
    return []


def test_the_walk_finds_each_kind_of_violation():
    assert violations(np.array(1.0)) == ["result is a 0-d array"]
    assert violations(np.float64(1.0)) == ["result is a NumPy scalar (float64)"]
    assert violations((1.0, 2.0)) == ["result is a bare tuple of float"]
    assert violations(Twist(1.0, 0.0, 0.0)) == []
    assert violations(frames.HalfTurn(np.float64(0.1), 1.0)) == [
        "result.angle is a NumPy scalar (float64)"]
    assert violations([frames.Pose(0, 0, 0)]) == ["result is a bare list of Pose"]
    assert violations(1.0) == violations(np.zeros(3)) == violations(3) == []


def _formula_calls():
    good = sweep._good_values()
    for qualname, fn in sweep._public_callables():
        kwargs = sweep._resolve(qualname, sweep._good_call(qualname, fn, good)
                                | sweep.OVERRIDES.get(qualname, {}))
        yield qualname, fn, kwargs


CALLS = list(_formula_calls())


@pytest.mark.parametrize(("qualname", "fn", "kwargs"), CALLS, ids=[c[0] for c in CALLS])
def test_every_public_callable_follows_the_return_rule(qualname, fn, kwargs):
    out = fn(**kwargs)
    assert violations(out) == [], qualname


def test_the_table_reaches_every_formula_module():
    modules = {q.split(".")[0] for q, _, _ in CALLS}
    assert modules == set(sweep.FORMULA_MODULES)
    assert len(CALLS) > 120


# --------------------------------------------------------------------------------------------
# Poses and twists: one is a Pose/Twist, a stack is an array (..., 3)

def _car(fn):
    """A car-like function with its wheelbase (a keyword) given: 2.5 m."""
    @functools.wraps(fn)
    def call(*args):
        return fn(*args, wheelbase=2.5)
    return call


#: (function, arguments with Pose/Twist objects, the record type it must return).
ONE = [
    (frames.se2_exp, (Twist(1.0, 0.2, 0.5), 0.5), Pose),
    (frames.se2_log, (Pose(1.0, 0.2, 0.5),), Twist),
    (frames.compose, (Pose(1.0, 2.0, 0.3), Pose(0.5, 0.0, 0.1)), Pose),
    (frames.inverse, (Pose(1.0, 2.0, 0.3),), Pose),
    (frames.relative, (Pose(1.0, 2.0, 0.3), Pose(0.5, 0.0, 0.1)), Pose),
    (frames.pose_rate, (0.3, Twist(1.0, 0.2, 0.5)), frames.PoseRate),
    (frames.ours_to_lab_pose, (Pose(1.0, 2.0, 0.3),), Pose),
    (frames.ours_to_firmware_pose, (Pose(1.0, 2.0, 0.3),), frames.FirmwarePose),
    (frames.ours_to_mecanum_doc_pose, (Pose(1.0, 2.0, 0.3),), frames.MecanumDocPose),
    (frames.ours_to_mecanum_doc_twist, (Twist(1.0, 2.0, 0.3),), frames.MecanumDocTwist),
    (frames.lab_pose_to_ours, (1.0, 2.0, 0.3), Pose),
    (frames.firmware_pose_to_ours, (1.0, 2.0, 0.3), Pose),
    (frames.mecanum_doc_pose_to_ours, (1.0, 2.0, 0.3), Pose),
    (frames.mecanum_doc_twist_to_ours, (1.0, 2.0, 0.3), Twist),
    (frames.rover_twist, (30.0, 10.0), Twist),
    (rover.document_twist, (30.0, 10.0), Twist),
    (_car(carlike.bicycle_twist), (1.0, 0.2), Twist),
    (_car(carlike.tricycle_twist), (1.0, 0.2), Twist),
    (mecanum.circle_twist, (2.0, 10.0), Twist),
    (mecanum.go_to_point_twist, (Pose(0.0, 0.0, 0.0), Pose(1.0, 1.0, 0.5), 1.0, 1.0), Twist),
]


@pytest.mark.parametrize(("fn", "args", "kind"), ONE, ids=[f[0].__name__ for f in ONE])
def test_one_pose_or_twist_is_a_record_that_unpacks(fn, args, kind):
    out = fn(*args)
    assert type(out) is kind
    assert all(type(c) is float for c in out)
    first, _, last = out  # unpacks
    assert (first, last) == (out[0], out[2])
    assert np.asarray(out).shape == (3,)


def _stack(record) -> np.ndarray:
    return np.stack([np.asarray(record, dtype=float)] * 4) + np.linspace(0, 0.1, 4)[:, None]


#: (function, arguments with stacks of shape (4, 3) or (4,)).
MANY = [
    (frames.se2_exp, lambda: (_stack(Twist(1.0, 0.2, 0.5)), 0.5)),
    (frames.se2_log, lambda: (_stack(Pose(1.0, 0.2, 0.5)),)),
    (frames.compose, lambda: (_stack(Pose(1.0, 2.0, 0.3)), _stack(Pose(0.5, 0.0, 0.1)))),
    (frames.inverse, lambda: (_stack(Pose(1.0, 2.0, 0.3)),)),
    (frames.pose_rate, lambda: (np.full(4, 0.3), _stack(Twist(1.0, 0.2, 0.5)))),
    (frames.ours_to_firmware_pose, lambda: (_stack(Pose(1.0, 2.0, 0.3)),)),
    (frames.firmware_pose_to_ours, lambda: (np.ones(4), np.ones(4), np.zeros(4))),
    (frames.rover_twist, lambda: (np.full(4, 30.0), np.full(4, 10.0))),
    (_car(carlike.bicycle_twist), lambda: (np.ones(4), np.full(4, 0.2))),
    (_car(carlike.tricycle_twist), lambda: (np.ones(4), np.full(4, 0.2))),
    (mecanum.circle_twist, lambda: (np.full(4, 2.0), 10.0)),
    (mecanum.forward_kinematics, lambda: (np.ones((4, 4)), mecanum.EXAMPLE_GEOMETRY)),
]


@pytest.mark.parametrize(("fn", "args"), MANY, ids=[f[0].__name__ for f in MANY])
def test_a_stack_of_poses_or_twists_is_an_array(fn, args):
    out = fn(*args())
    assert isinstance(out, np.ndarray) and out.shape == (4, 3)


def test_a_record_and_its_array_agree():
    """The record and the array paths are one computation: row k of the stack is the record
    of row k."""
    twists = _stack(Twist(1.0, 0.2, 0.5))
    for k in range(4):
        one = frames.se2_exp(Twist(*twists[k]), 0.5)
        assert np.array_equal(np.asarray(one), frames.se2_exp(twists, 0.5)[k])
    bike = carlike.bicycle_twist(np.ones(4), np.full(4, 0.2), wheelbase=2.5)
    assert np.array_equal(np.asarray(carlike.bicycle_twist(1.0, 0.2, wheelbase=2.5)), bike[0])
    assert math.isclose(carlike.bicycle_twist(1.0, 0.2, wheelbase=2.5).omega, math.tan(0.2) / 2.5)


#: Sandbox entries whose sweep wrapper returns the world's state after the call (the call
#: itself returns None or the object it built).
STATE_WRAPPERS = ("world.", "car.PurePursuitDriver.__call__")


def test_every_sandbox_callable_follows_the_return_rule():
    from tests.sandbox import test_bad_input_sandbox as sandbox_sweep

    checked, broken = 0, []
    for qualname in sorted(sandbox_sweep._ENTRIES):
        if qualname.startswith(STATE_WRAPPERS):
            continue
        fn, kwargs, _ = sandbox_sweep._valid(qualname)
        broken += [f"{qualname}: {v}" for v in violations(fn(**kwargs))]
        checked += 1
    assert not broken, "\n".join(broken)
    assert checked > 25


def test_state_and_plan_records_are_poses_and_twists():
    """What a robot, a plan and a follower report: a Pose and a Twist, not bare tuples."""
    from wheelkin import follower, odometry, sandbox, waypoints

    world = sandbox.World(dt=1 / 60)
    robot = world.add(sandbox.RADON_ULZER, pose=Pose(0.1, 0.2, 0.3), twist=Twist(0.2, 0, 0.5))
    world.step()
    assert type(robot.pose) is Pose and type(robot.twist) is Twist
    segments = waypoints.plan_segments(waypoints.LAB_WAYPOINTS)
    assert all(type(s.start) is Pose and type(s.end) is Pose for s in segments)
    assert type(segments[1].pose_at(0.5)) is Pose
    assert segments[1].pose_at([0.0, 1.0]).shape == (2, 3)
    assert segments[1].point_at(0.5).shape == (2,)
    commands = waypoints.schedule(segments, 0.04, 0.06)
    assert type(waypoints.planned_pose(commands, 1.0)) is Pose
    assert waypoints.planned_pose(commands, [1.0, 2.0]).shape == (2, 3)
    skid = follower.KinematicSkidSteer((0.0, 0.0, 0.0))
    skid.step(0.01)
    assert type(skid.pose) is Pose and type(skid.start) is Pose
    assert type(odometry.pose_update(Pose(0.0, 0.0, 0.0), 0.1, 0.1)) is Pose
    assert isinstance(odometry.pose_update([0.0, 0.0, 0.0], 0.1, 0.1), np.ndarray)
    assert type(waypoints.distance_to_walls([0.5, -0.5])) is float


def test_optional_results_are_named_too():
    from wheelkin import diffdrive

    out = diffdrive.speed_from_counts([0, 4, 8, 13, 18], [0.0, 0.01, 0.02, 0.03, 0.04], 0.02,
                                      return_updates=True)
    assert type(out) is diffdrive.CountSpeeds
    assert out.updated.tolist() == [False, False, True, False, True]
    assert violations(out) == []


def test_a_pose_given_as_a_pose_comes_back_as_one():
    """Second cold review: the covariance step and the follower's estimate."""
    from wheelkin import diffdrive, follower, odometry, waypoints

    step = odometry.propagate_covariance(Pose(0.0, 0.0, 0.0), np.zeros((3, 3)), 0.1, 0.12, 0.3,
                                         1e-4, 1e-4)
    assert type(step.pose) is Pose
    as_array = odometry.propagate_covariance((0.0, 0.0, 0.0), np.zeros((3, 3)), 0.1, 0.12, 0.3,
                                             1e-4, 1e-4)
    np.testing.assert_array_equal(as_array.pose, np.asarray(step.pose))
    segments = waypoints.plan_segments(waypoints.LAB_WAYPOINTS)
    robot = follower.KinematicSkidSteer(segments[0].start)
    controller = follower.FollowerController(robot, follower.PathFollower(segments),
                                             wheel_radius=0.04, track_width=0.12)
    for k in range(3):
        controller(k * controller.period)
        robot.step(controller.period)
    assert type(controller.estimate) is Pose
    assert all(type(p) is Pose for p in controller.log_estimate)
    constants = diffdrive.DiffDriveConstants(np.int64(85), np.int64(8043))
    assert type(constants.track_width_mm) is int and type(constants.track_width) is float
