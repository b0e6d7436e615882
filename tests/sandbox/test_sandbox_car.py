"""The car in the sandbox: the ideal Ackermann car against the bicycle model (closed-form arc
and an independent ODE solution), the linkage and parallel-steer cars' scrub, encoder
odometry, the free-rolling wheel kind, and bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from wheelkin import carlike
from wheelkin.sandbox import (
    RC_CAR,
    PurePursuitDriver,
    Steering,
    World,
    car,
    car_odometry,
    drive,
    front_angles,
)
from wheelkin.sandbox.contact import constraint_rows

L, W, R_W = 0.33, 0.27, 0.05


def _steady(geometry, delta=0.35, seconds=3.0, spec=RC_CAR):
    world = World(dt=1 / 240)
    robot = world.add(spec, twist=(1.0, 0.0, math.tan(delta) / L))
    st = Steering(geometry)
    return world.run(seconds, lambda t, w: drive(robot, 1.0, delta, st))


def test_constant_steering_is_the_closed_form_arc():
    traj = _steady("ackermann", 0.3, 10.0)
    R = L / math.tan(0.3)
    th = traj.t / R
    exact = np.stack([R * np.sin(th), R * (1 - np.cos(th))], axis=1)
    assert np.max(np.hypot(*(traj.pose[:, :2] - exact).T)) < 1e-9
    assert not traj.slipping.any()


def test_varying_steering_against_the_ode_over_ten_metres():
    """The sandbox budget: 0.01 mm over 10 m at 1/240 s while the car grips."""
    v = 1.0

    def delta(t):
        return 0.3 * math.sin(0.7 * t)

    ref = solve_ivp(lambda t, s: [v * math.cos(s[2]), v * math.sin(s[2]),
                                  v * math.tan(delta(t)) / L],
                    (0.0, 10.0), [0.0, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-13,
                    dense_output=True)
    world = World(dt=1 / 240)
    robot = world.add(RC_CAR, twist=(v, 0.0, 0.0))
    traj = world.run(10.0, lambda t, w: drive(robot, v, delta(t)))
    err = np.hypot(*(traj.pose[:, :2] - ref.sol(traj.t)[:2].T).T)
    assert traj.distance[-1] == pytest.approx(10.0)
    assert err.max() < 1e-5
    assert not traj.slipping.any()
    # Encoder odometry (ideal encoders): rear wheels + the steering command.
    steer = [delta((k + 0.5) / 240) for k in range(len(traj.t) - 1)]
    odo = car_odometry(traj.encoder_counts[:, 2:], steer, L, R_W)
    assert np.max(np.hypot(*(odo[:, :2] - traj.pose[:, :2]).T)) < 1e-9


@pytest.mark.parametrize("geometry, slipping", [("linkage", (False, True)),
                                                ("parallel", (True, True))])
def test_imperfect_steering_scrubs_the_front_tyres(geometry, slipping):
    traj = _steady(geometry)
    share = traj.slipping[1:].mean(axis=0)
    assert tuple(share[:2] > 0.99) == slipping
    assert np.all(share[2:] < 0.01)  # the driven rear wheels grip
    # The outer (right) front tyre is dragged sideways at about v * (its angle error).
    fr = front_angles(Steering(geometry), 0.35, L, W)[1]
    ack_r = front_angles(Steering("ackermann"), 0.35, L, W)[1]
    speed_fr = math.hypot(1 + math.tan(0.35) / L * W / 2, math.tan(0.35))
    assert traj.slip_speed[-1, 1] == pytest.approx(speed_fr * abs(math.sin(fr - ack_r)),
                                                   rel=0.05)


def test_front_angles_match_the_library():
    for d in (-0.4, -0.1, 0.2, 0.4):
        R = L / math.tan(d)
        assert front_angles(Steering(), d, L, W) == pytest.approx(
            tuple(carlike.ackermann_angles(R, wheelbase=L, track_width=W)), abs=1e-12)
        inner = carlike.ackermann_angles(R, wheelbase=L, track_width=W)[0 if d > 0 else 1]
        beta = carlike.jeantaud_arm_angle(wheelbase=L, track_width=W)
        assert front_angles(Steering("linkage"), d, L, W) == pytest.approx(
            tuple(carlike.linkage_angles(inner, track_width=W, arm_length=0.04,
                                         arm_angle=beta)), abs=1e-12)
    assert front_angles(Steering("parallel"), 0.3, L, W) == (0.3, 0.3)


def test_free_wheel_rows():
    J, B, owner = constraint_rows(RC_CAR, (0.2, 0.1))
    assert np.all(J[0] == 0) and np.all(B[0] == 0)  # FL rolls freely
    assert J[1] == pytest.approx([-math.sin(0.2), math.cos(0.2), L * math.cos(0.2)
                                  + W / 2 * math.sin(0.2)])
    assert owner.tolist() == [0, 0, 1, 1, 2, 2, 3, 3]


def test_pure_pursuit_follows_a_circle():
    R = 1.5
    s = np.linspace(0, 1.5 * math.pi, 2000)
    path = np.stack([R * np.sin(s), R * (1 - np.cos(s))], axis=1)
    world = World(dt=1 / 240)
    robot = world.add(RC_CAR, twist=(1.0, 0.0, 1.0 / R))
    driver = PurePursuitDriver(robot, path, 1.0, 0.3, 0.4189)
    traj = world.run(6.0, driver)
    dist = np.abs(np.hypot(traj.pose[:, 0], traj.pose[:, 1] - R) - R)
    assert dist.max() < 0.03
    # On a circle pure pursuit steers a little inside: kappa = 2 y / Ld^2 of a chord point.
    assert np.median(driver.log[200:]) == pytest.approx(
        carlike.steering_angle(R, wheelbase=L), rel=0.02)


@pytest.mark.parametrize("call, match", [
    (lambda: car(wheelbase=0.0, track_width=0.27, wheel_radius=0.05),
     "wheelbase must be a finite number > 0"),
    (lambda: car(wheelbase=0.33, track_width=0.27, wheel_radius=0.05, front_load=0.0), r"front_load must be in \(0, 1\)"),
    (lambda: Steering("rack"), "geometry must be one of"),
    (lambda: Steering("linkage", arm_length=-1), "arm_length"),
    (lambda: front_angles(Steering(), 2.0, L, W), "delta must be in"),
    (lambda: front_angles("ackermann", 0.2, L, W), "steering must be a Steering"),
    (lambda: RC_CAR.replace(free_rolling=("RL",)), "free_rolling must name steered wheels"),
    (lambda: car_odometry(np.zeros((3, 2)), [0.0], L, R_W), "steering must have 2 or 3"),
    (lambda: car_odometry(np.zeros((3, 3)), [0.0, 0.0], L, R_W), "rear_angles must have"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_drive_rejects_bad_commands_and_other_vehicles():
    from wheelkin.sandbox import RADON_ULZER
    world = World()
    robot = world.add(RC_CAR)
    with pytest.raises(ValueError, match="speed must be a finite number"):
        drive(robot, float("nan"), 0.1)
    with pytest.raises(ValueError, match="delta must be in"):
        drive(robot, 1.0, 1.6)
    other = world.add(RADON_ULZER, pose=(1, 1, 0))
    with pytest.raises(ValueError, match="spec must be a car"):
        drive(other, 1.0, 0.1)
