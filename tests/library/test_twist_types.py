"""One twist type (issue 23): a differential drive's two-component twists convert to and from
:class:`~wheelkin.frames.Twist`, and a twist with a sideways speed is refused by name."""

from __future__ import annotations

import numpy as np
import pytest

from wheelkin import diffdrive
from wheelkin.diffdrive import BodyTwist
from wheelkin.follower import BodyCommand
from wheelkin.frames import Twist, point_velocity


def test_body_twist_to_twist_by_hand():
    assert BodyTwist(0.5, 0.2).to_twist() == Twist(0.5, 0.0, 0.2)
    assert type(BodyTwist(0.5, 0.2).to_twist()) is Twist


def test_body_twist_arrays_give_an_array():
    out = BodyTwist(np.array([0.5, 1.0]), np.array([0.2, -0.1])).to_twist()
    assert isinstance(out, np.ndarray)
    np.testing.assert_array_equal(out, [[0.5, 0.0, 0.2], [1.0, 0.0, -0.1]])
    back = BodyTwist.from_twist(out)
    np.testing.assert_array_equal(back.v, [0.5, 1.0])
    np.testing.assert_array_equal(back.omega, [0.2, -0.1])


def test_the_wheel_speeds_agree_through_the_twist():
    """body_twist's (v, omega) as a Twist moves each wheel's contact point at its wheel's
    speed (the point velocity v + omega x p, worked independently by frames)."""
    track = 0.37
    v, w = diffdrive.body_twist(0.3, 0.8, track)
    twist = BodyTwist(v, w).to_twist()
    left = point_velocity(twist, (0.0, track / 2))
    right = point_velocity(twist, (0.0, -track / 2))
    assert (left[0], right[0]) == pytest.approx((0.3, 0.8))
    assert (left[1], right[1]) == pytest.approx((0.0, 0.0))


def test_body_command_round_trip():
    cmd = BodyCommand(0.3, -0.5)
    assert cmd.to_twist() == Twist(0.3, 0.0, -0.5)
    assert BodyCommand.from_twist(cmd.to_twist()) == cmd
    assert BodyCommand.from_twist((0.3, 0.0, -0.5)) == cmd


@pytest.mark.parametrize("convert", [BodyTwist.from_twist, BodyCommand.from_twist])
def test_a_sideways_speed_is_refused_by_name(convert):
    with pytest.raises(ValueError, match=r"twist must have vy = 0.*got vy = 0\.1"):
        convert(Twist(0.5, 0.1, 0.2))
    with pytest.raises(TypeError, match="twist"):
        convert(("0.5", 0.0, 0.2))
