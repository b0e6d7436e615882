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


# ----------------------------------------------- mecanum: Twist in, Twist out (issue 23, item 3)

def test_mecanum_forward_kinematics_gives_a_twist_for_one_set_of_rates():
    """Hand value: r = 0.05 m, a + b = 0.35 m; strafing left at 1 m/s needs
    (-20, 20, 20, -20) rad/s, spinning at 1 rad/s needs (-7, 7, -7, 7) rad/s."""
    from wheelkin import mecanum

    g = mecanum.MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
    out = mecanum.forward_kinematics([-20.0, 20.0, 20.0, -20.0], g)
    assert type(out) is Twist
    assert out == pytest.approx((0.0, 1.0, 0.0), abs=1e-12)
    vx, vy, w = mecanum.forward_kinematics(np.array([-7.0, 7.0, -7.0, 7.0]), g)
    assert (vx, vy, w) == pytest.approx((0.0, 0.0, 1.0), abs=1e-12)
    stack = mecanum.forward_kinematics(np.array([[-20.0, 20.0, 20.0, -20.0],
                                                 [-7.0, 7.0, -7.0, 7.0]]), g)
    assert isinstance(stack, np.ndarray) and stack.shape == (2, 3)
    np.testing.assert_allclose(stack, [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], atol=1e-12)


@pytest.mark.parametrize("twist", [(0.0, 1.0, 0.0), (1.0, 0.5, 0.4), (-0.3, 0.2, -1.1)])
def test_mecanum_inverse_kinematics_takes_a_twist_or_its_components(twist):
    """The hand formula (FL = (vx - vy - k w) / r, ... at 45 degrees) for all three forms."""
    from wheelkin import mecanum

    g = mecanum.MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
    vx, vy, w = twist
    k, r = 0.35, 0.05
    hand = [(vx - vy - k * w) / r, (vx + vy + k * w) / r, (vx + vy - k * w) / r,
            (vx - vy + k * w) / r]
    for got in (mecanum.inverse_kinematics(Twist(*twist), g),
                mecanum.inverse_kinematics(twist, g),
                mecanum.inverse_kinematics(vx, vy, w, g)):
        np.testing.assert_allclose(got, hand, rtol=1e-12, atol=1e-12)
    back = mecanum.forward_kinematics(mecanum.inverse_kinematics(Twist(*twist), g), g)
    assert type(back) is Twist and back == pytest.approx(twist, abs=1e-12)
    centre = (0.2, 0.15)
    np.testing.assert_allclose(
        mecanum.inverse_kinematics(Twist(*twist), g, centre_of_rotation=centre),
        mecanum.inverse_kinematics(vx, vy, w, g, centre_of_rotation=centre), rtol=1e-12)


def test_mecanum_inverse_kinematics_takes_a_stack_of_twists():
    from wheelkin import mecanum

    g = mecanum.EXAMPLE_GEOMETRY
    twists = np.array([[1.0, 0.0, 0.0], [0.0, 0.5, 0.3]])
    np.testing.assert_allclose(mecanum.inverse_kinematics(twists, g),
                               mecanum.inverse_kinematics(twists[:, 0], twists[:, 1],
                                                          twists[:, 2], g), rtol=1e-12)


@pytest.mark.parametrize(("args", "name"), [
    ((Twist(1.0, 0.0, 0.0), 0.0, 0.0), "vx"),
    ((1.0, 0.0), "twist"),
    ((1.0,), "vy"),
    (((1.0, 0.0, 0.0), "G", 0.0), "vy"),
    ((1.0, 0.0, "G"), "omega"),
    ((1.0, 0.0, 0.0), "geometry"),
    (((1.0, 0.0), "G"), "twist"),
])
def test_mecanum_inverse_kinematics_refuses_a_wrong_combination_by_name(args, name):
    from wheelkin import mecanum

    g = mecanum.EXAMPLE_GEOMETRY
    args = tuple(g if a == "G" else a for a in args)
    with pytest.raises(TypeError, match=rf"^{name}\b"):
        mecanum.inverse_kinematics(*args)


def test_mecanum_max_rim_speed_takes_a_twist_or_its_components():
    """Hand value at 45 degrees: |vx| + |vy| + (a + b)|omega| = 1 + 0.5 + 0.35 * 0.4 m/s."""
    from wheelkin import mecanum

    g = mecanum.MecanumGeometry(wheel_radius=0.05, half_wheelbase=0.2, half_track=0.15)
    for got in (mecanum.max_rim_speed(Twist(1.0, -0.5, 0.4), g),
                mecanum.max_rim_speed((1.0, -0.5, 0.4), g),
                mecanum.max_rim_speed(1.0, -0.5, 0.4, g)):
        assert type(got) is float and got == pytest.approx(1.64, rel=1e-12)
    # the fastest wheel of inverse_kinematics, times the wheel radius, independently
    rates = mecanum.inverse_kinematics(Twist(1.0, -0.5, 0.4), g)
    assert float(np.max(np.abs(rates))) * 0.05 == pytest.approx(1.64, rel=1e-12)
    stack = mecanum.max_rim_speed(np.array([[1.0, -0.5, 0.4], [0.0, 0.0, 1.0]]), g)
    np.testing.assert_allclose(stack, [1.64, 0.35], rtol=1e-12)
    with pytest.raises(TypeError, match=r"^vx\b"):
        mecanum.max_rim_speed(Twist(1.0, 0.0, 0.0), 0.0, 0.0, g)
