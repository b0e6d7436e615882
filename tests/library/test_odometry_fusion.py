"""wheelkin.odometry_fusion: the wheel-and-gyro EKF and the NEES.

Independent references: without a gyro the step is the book's covariance step
(``propagate_covariance``); with one, the closed form of the chapter (the gyro corrects only
this step's wheel noise: c = (F_w Q F_w^T)[:, 3], S = c_3 + r), derived here again from the
joint Gaussian of the linear model (the conditional mean and covariance written out with a
plain matrix inverse); limits (a perfect gyro, a useless one); the NEES against hand values
and its chi-square law by Monte Carlo; the whole filter's consistency on the kinematic model
with the very noise it assumes (Monte Carlo NEES within the chi-square band).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from wheelkin import odometry_fusion as F
from wheelkin import odometry_uncertainty as U
from wheelkin.frames import Pose

W, K = 0.085, 1e-6


def _sigma(rng):
    a = rng.normal(0, 1e-2, (3, 3))
    return a @ a.T + 1e-6 * np.eye(3)


def test_without_a_gyro_it_is_the_covariance_step():
    rng = np.random.default_rng(1)
    for _ in range(20):
        pose, sigma = rng.uniform(-1, 1, 3), _sigma(rng)
        left, right = rng.uniform(-0.05, 0.1, 2)
        got = F.ekf_step(pose, sigma, left, right, W, K, 2 * K)
        want = U.propagate_covariance(pose, sigma, left, right, W, K, 2 * K)
        assert np.array_equal(got.pose, want.pose)
        assert np.array_equal(got.covariance, want.covariance)
        assert got.innovation is None and got.innovation_variance is None


def _joint_gaussian_update(pose, sigma, left, right, z, r):
    """The linear-Gaussian model written out: x' = f + F_p dx + F_w dw, z = dtheta_w +
    (dw's heading part) + n; condition x' on z with the textbook formulas."""
    jac = U.step_jacobians(pose, left, right, W)
    pred = U.propagate_covariance(pose, np.zeros((3, 3)), left, right, W, 0.0, 0.0).pose
    q = np.diag([K * abs(left), 2 * K * abs(right)])
    # joint covariance of (x', z): x' = F_p e + F_w w; z - dtheta_w = [F_w w]_3 + n
    fw_row = jac.wrt_wheels[2]
    cov_xx = jac.wrt_pose @ sigma @ jac.wrt_pose.T + jac.wrt_wheels @ q @ jac.wrt_wheels.T
    cov_xz = jac.wrt_wheels @ q @ fw_row
    cov_zz = fw_row @ q @ fw_row + r
    innovation = z - (pred[2] - pose[2])
    mean = np.asarray(pred) + cov_xz * innovation / cov_zz
    cov = cov_xx - np.outer(cov_xz, cov_xz) / cov_zz
    return mean, cov, innovation, cov_zz


def test_gyro_update_is_the_conditional_of_the_joint_gaussian():
    rng = np.random.default_rng(2)
    for _ in range(30):
        pose, sigma = rng.uniform(-1, 1, 3), _sigma(rng)
        left, right = rng.uniform(0.0, 0.1, 2)
        z, r = rng.normal(0, 0.05), 10.0 ** rng.uniform(-8, -4)
        got = F.ekf_step(pose, sigma, left, right, W, K, 2 * K, gyro_turn=z, gyro_variance=r)
        mean, cov, innovation, s = _joint_gaussian_update(pose, sigma, left, right, z, r)
        assert got.pose == pytest.approx(mean, abs=1e-12)
        assert got.covariance == pytest.approx(cov, rel=1e-7, abs=1e-16)
        assert got.innovation == pytest.approx(innovation)
        assert got.innovation_variance == pytest.approx(s)


def test_a_perfect_gyro_sets_the_turn_and_a_useless_one_changes_nothing():
    pose, sigma = np.array([0.2, 0.1, 0.5]), np.diag([1e-4, 1e-4, 1e-3])
    sharp = F.ekf_step(pose, sigma, 0.1, 0.12, W, K, K, gyro_turn=0.3, gyro_variance=1e-30)
    assert sharp.pose[2] == pytest.approx(0.5 + 0.3, abs=1e-9)
    blunt = F.ekf_step(pose, sigma, 0.1, 0.12, W, K, K, gyro_turn=0.3, gyro_variance=100.0)
    wheels = F.ekf_step(pose, sigma, 0.1, 0.12, W, K, K)
    assert blunt.pose == pytest.approx(np.asarray(wheels.pose), abs=1e-6)
    assert blunt.covariance == pytest.approx(wheels.covariance, rel=1e-6)


def test_a_pose_in_gives_a_pose_out():
    out = F.ekf_step(Pose(0.0, 0.0, 0.0), np.zeros((3, 3)), 0.1, 0.1, W, K, K,
                     gyro_turn=0.0, gyro_variance=1e-8)
    assert isinstance(out.pose, Pose)
    assert np.allclose(out.covariance, out.covariance.T)


def test_path_is_a_loop_of_steps():
    rng = np.random.default_rng(3)
    left, right = rng.uniform(0, 0.02, (2, 40))
    turns = (right - left) / W + rng.normal(0, 1e-3, 40)
    run = F.ekf_path((0, 0, 0.3), np.eye(3) * 1e-6, left, right, W, K, K,
                     gyro_turns=turns, gyro_variance=1e-6)
    pose, cov = np.array([0, 0, 0.3]), np.eye(3) * 1e-6
    for k in range(40):
        step = F.ekf_step(pose, cov, left[k], right[k], W, K, K, gyro_turn=turns[k],
                          gyro_variance=1e-6)
        pose, cov = np.asarray(step.pose), step.covariance
        assert run.poses[k + 1] == pytest.approx(pose, abs=1e-12)
        assert run.innovations[k] == pytest.approx(step.innovation)
    wheels = F.ekf_path((0, 0, 0.3), np.eye(3) * 1e-6, left, right, W, K, K)
    want = U.propagate_path((0, 0, 0.3), np.eye(3) * 1e-6, left, right, W, K, K)
    assert wheels.poses == pytest.approx(want.poses, abs=1e-12)
    assert wheels.covariances == pytest.approx(want.covariances, rel=1e-9, abs=1e-18)


def test_nees_hand_values_and_its_chi_square_law():
    assert F.nees([0.1, 0.0, 0.0], np.diag([0.01, 1.0, 1.0])) == pytest.approx(1.0)
    assert F.nees([1.0, 1.0], [[2.0, 1.0], [1.0, 2.0]]) == pytest.approx(2.0 / 3.0)
    rng = np.random.default_rng(4)
    sigma = _sigma(rng)
    e = rng.multivariate_normal(np.zeros(3), sigma, 20000)
    values = F.nees(e, sigma)
    assert values.shape == (20000,)
    assert values.mean() == pytest.approx(3.0, abs=4 * math.sqrt(6 / 20000))
    assert stats.kstest(values, stats.chi2(3).cdf).pvalue > 1e-3


def test_nees_refuses_a_covariance_that_claims_certainty():
    with pytest.raises(ValueError, match="positive definite"):
        F.nees([0.0, 0.0, 0.1], np.diag([1.0, 1.0, 0.0]))
    with pytest.raises(ValueError, match="covariance"):
        F.nees([0.0, 0.1], np.eye(3))


def test_the_filter_is_consistent_on_the_model_it_assumes():
    """Wheels with exactly the assumed noise, a gyro with exactly the assumed noise: the
    NEES at the end, averaged over the runs, lies in the chi-square band of 3 dof."""
    rng = np.random.default_rng(5)
    runs, steps = 200, 150
    h = 0.01
    true_left = np.full(steps, h)
    true_right = h * (1 + 0.3 * np.sin(np.linspace(0, 6, steps)))
    r = 1e-7
    values = {"gyro": [], "wheels": []}
    for _ in range(runs):
        # the truth: the nominal travels; the encoders read them with the model's errors
        truth = U.propagate_path((0, 0, 0), np.zeros((3, 3)), true_left, true_right, W, 0,
                                 0).poses
        left = true_left + np.sqrt(K * true_left) * rng.standard_normal(steps)
        right = true_right + np.sqrt(K * true_right) * rng.standard_normal(steps)
        turns = np.diff(truth[:, 2]) + math.sqrt(r) * rng.standard_normal(steps)
        fused = F.ekf_path((0, 0, 0), np.zeros((3, 3)), left, right, W, K, K,
                           gyro_turns=turns, gyro_variance=r)
        wheels = F.ekf_path((0, 0, 0), np.zeros((3, 3)), left, right, W, K, K)
        values["gyro"].append(F.nees(fused.poses[-1] - truth[-1], fused.covariances[-1]))
        values["wheels"].append(F.nees(wheels.poses[-1] - truth[-1], wheels.covariances[-1]))
    band = stats.chi2.ppf([0.001, 0.999], 3 * runs) / runs
    for name, v in values.items():
        assert band[0] < np.mean(v) < band[1], (name, np.mean(v), band)
