"""A tuple where a pose is meant (docs/DESIGN.md, "What the library returns", issue 23).

Every public callable of the formula modules with a pose parameter (annotated ``Pose``, or named
as one: ``pose``, ``pose0``, ``delta``, ``goal``, ...) is called
twice with the bad-input sweep's valid arguments: once with each pose as a
:class:`~wheelkin.frames.Pose`, once as the plain tuple ``(x, y, theta)`` of the same numbers.
Both calls must give the same kind of result (a Pose for a Pose, and for the tuple too; an
array for both where the function returns a trajectory) and the same numbers. The functions
are found from the registry, so a new pose-taking function is swept without being listed.
"""

from __future__ import annotations

import dataclasses
import inspect

import numpy as np
import pytest
import test_bad_input as sweep

from wheelkin import frames, sources
from wheelkin._records import _is_one
from wheelkin.frames import Pose, Twist


def kind(out, depth: int = 0):
    """What ``out`` is, as a comparable description (types and shapes, not values)."""
    if depth > 4:
        return "..."
    if isinstance(out, np.ndarray):
        return ("ndarray", out.shape)
    if isinstance(out, tuple) and hasattr(out, "_fields"):
        return (type(out).__name__, tuple(kind(v, depth + 1) for v in out))
    if isinstance(out, tuple | list):
        return (type(out).__name__, tuple(kind(v, depth + 1) for v in out))
    if dataclasses.is_dataclass(out) and not isinstance(out, type):
        return type(out).__name__
    return type(out).__name__


def numbers(out, depth: int = 0) -> list[float]:
    """The floats in ``out``, flattened (records and arrays)."""
    if depth > 4:
        return []
    if isinstance(out, np.ndarray) and out.dtype.kind in "fiu":
        return [float(v) for v in out.ravel()]
    if isinstance(out, float | int) and not isinstance(out, bool):
        return [float(out)]
    if isinstance(out, tuple | list):
        return [v for o in out for v in numbers(o, depth + 1)]
    return []


def _pose_parameters(fn) -> list[str]:
    try:
        params = inspect.signature(fn).parameters.values()
    except (TypeError, ValueError):
        return []
    return [p.name for p in params
            if ("Pose" in str(p.annotation) or "pose" in p.name or p.name in POSE_NAMES)
            and "Pose]" not in str(p.annotation)]  # a pose, not a list of poses


#: Parameters that are a pose without the word in their name or annotation.
POSE_NAMES = frozenset({"delta", "goal", "before", "after", "start", "reference"})


def _pose_calls():
    good = sweep._good_values()
    for qualname, fn in sweep._public_callables():
        names = _pose_parameters(fn)
        if not names:
            continue
        kwargs = sweep._resolve(qualname, sweep._good_call(qualname, fn, good)
                                | sweep.OVERRIDES.get(qualname, {}))
        names = [n for n in names if n in kwargs and np.shape(kwargs[n]) == (3,)]
        if names:
            yield qualname, fn, kwargs, names


CALLS = list(_pose_calls())


def test_the_sweep_finds_the_pose_taking_functions():
    found = {q for q, *_ in CALLS}
    assert {"frames.compose", "frames.inverse", "frames.relative", "frames.se2_log",
            "sources.ours_to_lab_pose", "mecanum.go_to_point_twist",
            "odometry_uncertainty.propagate_covariance"} <= found
    assert len(found) > 20


@pytest.mark.parametrize(("qualname", "fn", "kwargs", "names"), CALLS,
                         ids=[c[0] for c in CALLS])
def test_a_tuple_gives_what_a_pose_gives(qualname, fn, kwargs, names):
    as_pose = kwargs | {n: Pose(*(float(c) for c in kwargs[n])) for n in names}
    as_tuple = kwargs | {n: tuple(float(c) for c in kwargs[n]) for n in names}
    if "rng" in kwargs:  # the same draws for both calls
        as_pose["rng"], as_tuple["rng"] = np.random.default_rng(0), np.random.default_rng(0)
    with_pose, with_tuple = fn(**as_pose), fn(**as_tuple)
    assert kind(with_tuple) == kind(with_pose), qualname
    assert numbers(with_tuple) == pytest.approx(numbers(with_pose), rel=1e-12, abs=1e-12)


# Hand-checked cases: the tuple's result is the Pose the record gives, worked out by hand.

def test_compose_of_tuples_is_the_pose_by_hand():
    out = frames.compose((1.0, 2.0, np.pi / 2), (0.5, 0.0, 0.25))
    assert type(out) is Pose
    assert tuple(out) == pytest.approx((1.0, 2.5, np.pi / 2 + 0.25))


def test_se2_exp_of_a_tuple_is_a_pose_and_back_a_twist():
    d = frames.se2_exp((np.pi / 2, 0.0, np.pi / 2), 1.0)  # a quarter circle of radius 1 m
    assert type(d) is Pose and tuple(d) == pytest.approx((1.0, 1.0, np.pi / 2))
    back = frames.se2_log(tuple(d))
    assert type(back) is Twist and tuple(back) == pytest.approx((np.pi / 2, 0.0, np.pi / 2))


def test_a_list_or_an_array_stays_an_array():
    for pose in ([1.0, 2.0, 0.3], np.array([1.0, 2.0, 0.3])):
        assert isinstance(frames.inverse(pose), np.ndarray)
        assert isinstance(sources.ours_to_lab_pose(pose), np.ndarray)


def test_what_counts_as_one_record():
    assert _is_one((1, 2.0, np.float64(0.3)), Pose)
    assert _is_one(Pose(0.0, 0.0, 0.0), Pose)
    assert not _is_one(Twist(0.0, 0.0, 0.0), Pose)  # a twist is refused where a pose is meant
    assert not _is_one([1.0, 2.0, 0.3], Pose)
    assert not _is_one((1.0, 2.0), Pose)
    assert not _is_one((True, 2.0, 0.3), Pose)
    assert not _is_one(((1.0, 2.0, 0.3),), Pose)


def test_a_tuple_with_a_bad_number_names_the_parameter():
    with pytest.raises(ValueError, match="pose"):
        frames.inverse((1.0, 2.0, float("nan")))
    with pytest.raises(ValueError, match="pose"):
        sources.ours_to_lab_pose((1.0, float("inf"), 0.0))
    with pytest.raises(TypeError, match="delta"):
        frames.compose((0.0, 0.0, 0.0), (0.0, "1", 0.0))
