"""The sandbox's rate gyro: its integrated readings against the true turn of a sandbox run,
a bias by hand, and the white noise's random-walk variance by Monte Carlo (the sample
variance of many seeds against noise_density^2 * dt, within its sampling tolerance)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from wheelkin.sandbox import RADON_ULZER, World
from wheelkin.sandbox.sensors import Gyro


def _spin_run():
    world = World(dt=1 / 200)
    robot = world.add(RADON_ULZER.replace(mu=0.1), pose=(0.0, 0.0, 0.0))
    robot.command_twist(0.3, 0.0, 6.0)  # slips on mu = 0.1: the wheels' turn is wrong
    return world.run(2.0, record_every=4)


def test_a_perfect_gyro_reads_the_true_turn_even_when_the_wheels_slip():
    run = _spin_run()
    assert run.slipping.any()
    turns = Gyro().turns(run.t, run.pose[:, 2])
    assert turns.sum() == pytest.approx(run.pose[-1, 2] - run.pose[0, 2], abs=1e-12)
    wheels = np.diff(run.wheel_angles, axis=0) @ np.array([-1.0, 1.0]) * (
        RADON_ULZER.wheels[0].wheel_radius / 0.085)
    assert abs(wheels.sum() - turns.sum()) > 0.1  # what the encoders believe differs


def test_bias_adds_a_drift_by_hand():
    turns = Gyro(bias=0.02).turns([0.0, 0.5, 2.0], [0.0, 0.0, 0.0])
    assert turns.tolist() == pytest.approx([0.01, 0.03])


def test_white_noise_integrates_to_a_random_walk():
    density, dt, n = 0.003, 0.02, 4000
    t = np.arange(n + 1) * dt
    readings = np.concatenate([Gyro(noise_density=density, seed=s).turns(t, np.zeros(n + 1))
                               for s in range(5)])
    var = Gyro(noise_density=density).variance(dt)
    assert var == pytest.approx(density**2 * dt)
    assert readings.var() == pytest.approx(var, rel=4 * math.sqrt(2 / readings.size))
    # the same seed reads the same noise
    one = Gyro(noise_density=density, seed=7).turns(t, np.zeros(n + 1))
    assert np.array_equal(one, Gyro(noise_density=density, seed=7).turns(t, np.zeros(n + 1)))


def test_bad_times_are_refused():
    with pytest.raises(ValueError, match="t must"):
        Gyro().turns([0.0, 0.0], [0.0, 0.1])
    with pytest.raises(ValueError, match="heading"):
        Gyro().turns([0.0, 1.0], [0.0])
