"""wheelkin.motion_models: Thrun's odometry model (density and sampler) and velocity sampler.

Independent references: Thrun's tables 5.5, 5.6 and 5.3 transcribed here again with
``scipy.stats.norm`` and plain trigonometry; the decomposition checked by rebuilding the pose
from it; the density integrated numerically over grids (over the motion's three numbers, and
over the pose with the Jacobian 1/delta_trans, whose absence makes the printed product
integrate to delta_trans over the pose); the sampler's moments and histogram against the
density (Monte Carlo, tolerances from the sampling distributions); the velocity sampler's
noise-free samples against ``frames.se2_exp`` and its draws recovered from the samples.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from wheelkin import frames, motion_models, odometry
from wheelkin import motion_models as M

PREV = np.array([0.3, -0.2, 0.4])
ODO_PREV = np.array([1.0, 2.0, -0.5])


def _odometry_after(rot1, trans, rot2, start=ODO_PREV):
    """The odometry pose reached from ``start`` by a turn, a line and a turn."""
    heading = start[2] + rot1
    return np.array([start[0] + trans * math.cos(heading), start[1] + trans * math.sin(heading),
                     heading + rot2])


ODO = _odometry_after(0.3, 0.5, -0.2)


def _thrun_table_5_5(pose, prev, odo, odo_prev, a):
    """Table 5.5, line by line, with scipy's normal density (independent transcription)."""
    def motion(p0, p1):
        r1 = math.atan2(p1[1] - p0[1], p1[0] - p0[0]) - p0[2]
        t = math.hypot(p1[0] - p0[0], p1[1] - p0[1])
        return r1, t, p1[2] - p0[2] - r1

    def wrap(x):
        return math.atan2(math.sin(x), math.cos(x))

    d1, dt, d2 = motion(odo_prev, odo)
    h1, ht, h2 = motion(prev, pose)
    p1 = stats.norm.pdf(wrap(d1 - h1), scale=math.sqrt(a[0] * h1**2 + a[1] * ht**2))
    p2 = stats.norm.pdf(dt - ht, scale=math.sqrt(a[2] * ht**2 + a[3] * (h1**2 + h2**2)))
    p3 = stats.norm.pdf(wrap(d2 - h2), scale=math.sqrt(a[0] * h2**2 + a[1] * ht**2))
    return p1 * p2 * p3


def test_the_decomposition_rebuilds_the_pose():
    rng = np.random.default_rng(1)
    for _ in range(200):
        a, b = rng.uniform(-3, 3, (2, 3))
        m = M.odometry_motion(a, b)
        rebuilt = _odometry_after(m.rot1, m.trans, m.rot2, a)
        assert rebuilt[:2] == pytest.approx(b[:2], abs=1e-12)
        assert frames.wrap_angle(rebuilt[2] - b[2]) == pytest.approx(0.0, abs=1e-12)
        assert -math.pi < m.rot1 <= math.pi and -math.pi < m.rot2 <= math.pi


def test_density_is_table_5_5():
    rng = np.random.default_rng(2)
    alphas = [0.05, 0.02, 0.04, 0.01]
    for _ in range(100):
        pose = PREV + np.array([*rng.normal(0.4, 0.2, 2), rng.normal(0.0, 0.4)])
        got = M.motion_model_odometry(pose, PREV, ODO, ODO_PREV, alphas)
        assert got == pytest.approx(_thrun_table_5_5(pose, PREV, ODO, ODO_PREV, alphas),
                                    rel=1e-12)
    stack = PREV + rng.normal(0.3, 0.1, (7, 3))
    assert M.motion_model_odometry(stack, PREV, ODO, ODO_PREV, alphas) == pytest.approx(
        [_thrun_table_5_5(p, PREV, ODO, ODO_PREV, alphas) for p in stack], rel=1e-12)


def test_hand_value_of_the_doctest():
    a = [0.01] * 4
    p = M.motion_model_odometry((1, 0, 0), (0, 0, 0), (1, 0, 0), (0, 0, 0), a)
    # every delta-hat is 0 but trans = 1: sigma_rot = sqrt(0.01) rad, sigma_trans = 0.1 m
    assert p == pytest.approx((1 / (0.1 * math.sqrt(2 * math.pi))) ** 3)


def test_only_the_motion_matters_not_where_odometry_and_robot_are():
    alphas = [0.05, 0.02, 0.04, 0.01]
    pose = np.array([0.7, 0.1, 0.3])
    base = M.motion_model_odometry(pose, PREV, ODO, ODO_PREV, alphas)
    shift = frames.Pose(5.0, -3.0, 1.1)
    moved = [np.asarray(frames.compose(shift, frames.Pose(*p))) for p in (ODO, ODO_PREV)]
    assert M.motion_model_odometry(pose, PREV, *moved, alphas) == pytest.approx(base)
    robot = [np.asarray(frames.compose(shift, frames.Pose(*p))) for p in (pose, PREV)]
    assert M.motion_model_odometry(robot[0], robot[1], ODO, ODO_PREV, alphas) == \
        pytest.approx(base)


SMALL = [1e-4, 1e-4, 1e-4, 1e-4]  # relative errors of about 1 %
#: The sampler draws with the variances of the measured motion, the density evaluates them at
#: the hypothesis: the two distributions differ by a relative O(sqrt(alpha)) (with SMALL the
#: means differ by 1-2 % of a standard deviation, which 1e5 samples resolve). Compared at
#: TINY (0.1 %), the difference is below what the samples can see.
TINY = [1e-6, 1e-6, 1e-6, 1e-6]


def _motion_grid(n=48, width=6.0):
    """Poses on a grid in the motion's coordinates, and the cell volume (rad m rad)."""
    sd = np.sqrt([SMALL[0] * 0.3**2 + SMALL[1] * 0.5**2,
                  SMALL[2] * 0.5**2 + SMALL[3] * (0.3**2 + 0.2**2),
                  SMALL[0] * 0.2**2 + SMALL[1] * 0.5**2])
    axes = [np.linspace(c - width * s, c + width * s, n) for c, s in
            zip((0.3, 0.5, -0.2), sd, strict=True)]
    r1, t, r2 = np.meshgrid(*axes, indexing="ij")
    heading = PREV[2] + r1
    poses = np.stack([PREV[0] + t * np.cos(heading), PREV[1] + t * np.sin(heading),
                      heading + r2], axis=-1)
    volume = np.prod([ax[1] - ax[0] for ax in axes])
    return poses.reshape(-1, 3), volume


def test_the_printed_product_integrates_to_one_over_the_motion():
    poses, volume = _motion_grid()
    p = M.motion_model_odometry(poses, PREV, ODO, ODO_PREV, SMALL)
    # to within the variances' dependence on the hypothesis, a relative O(alpha) = 1e-4
    assert p.sum() * volume == pytest.approx(1.0, abs=2e-3)


def _pose_grid(n=64, alphas=SMALL):
    samples = M.sample_motion_model_odometry(PREV, ODO, ODO_PREV, alphas, 20000,
                                             np.random.default_rng(9))
    lo, hi = samples.min(axis=0), samples.max(axis=0)
    pad = 0.4 * (hi - lo)
    axes = [np.linspace(a - b, c + b, n) for a, b, c in zip(lo, pad, hi, strict=True)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    return grid, axes, np.prod([ax[1] - ax[0] for ax in axes])


def test_over_the_pose_it_needs_the_jacobian_one_over_delta_trans():
    grid, _, volume = _pose_grid()
    per_pose = M.motion_model_odometry(grid, PREV, ODO, ODO_PREV, SMALL, density_of="pose")
    printed = M.motion_model_odometry(grid, PREV, ODO, ODO_PREV, SMALL)
    assert per_pose.sum() * volume == pytest.approx(1.0, abs=5e-3)
    # the product as printed integrates to delta_trans = 0.5 m over (x, y, theta)
    assert printed.sum() * volume == pytest.approx(0.5, abs=5e-3)


def test_sampler_moments_agree_with_the_density():
    n = 200_000
    samples = M.sample_motion_model_odometry(PREV, ODO, ODO_PREV, TINY, n,
                                             np.random.default_rng(3))
    grid, _, volume = _pose_grid(alphas=TINY)
    weight = M.motion_model_odometry(grid, PREV, ODO, ODO_PREV, TINY,
                                     density_of="pose") * volume
    weight = weight / weight.sum()
    mean = weight @ grid
    cov = (grid - mean).T @ ((grid - mean) * weight[:, None])
    sample_cov = np.cov(samples.T)
    sd = np.sqrt(np.diag(cov))
    # means within 4 standard errors, standard deviations within 4 of theirs (1/sqrt(2n))
    assert np.all(np.abs(samples.mean(axis=0) - mean) < 4 * sd / math.sqrt(n))
    assert np.all(np.abs(np.sqrt(np.diag(sample_cov)) / sd - 1) < 4 / math.sqrt(2 * n) + 2e-3)
    corr = sample_cov / np.outer(np.sqrt(np.diag(sample_cov)), np.sqrt(np.diag(sample_cov)))
    want = cov / np.outer(sd, sd)
    assert np.all(np.abs(corr - want) < 4 / math.sqrt(n) + 2e-3)


def test_sampler_histogram_matches_the_density():
    n, bins, sub = 100_000, 8, 10
    samples = M.sample_motion_model_odometry(PREV, ODO, ODO_PREV, TINY, n,
                                             np.random.default_rng(4))
    lo, hi = samples.min(axis=0), samples.max(axis=0)
    pad = 0.3 * (hi - lo)
    # an 8 x 8 histogram of (x, y); each bin split into 10 x 10 cells, theta into 60, and the
    # density integrated over the cells by the midpoint rule
    edges = [np.linspace(lo[i] - pad[i], hi[i] + pad[i], bins * sub + 1) for i in range(3)]
    edges[2] = np.linspace(lo[2] - pad[2], hi[2] + pad[2], 61)
    mids = [0.5 * (e[1:] + e[:-1]) for e in edges]
    grid = np.stack(np.meshgrid(*mids, indexing="ij"), axis=-1).reshape(-1, 3)
    cell = np.prod([e[1] - e[0] for e in edges])
    dens = M.motion_model_odometry(grid, PREV, ODO, ODO_PREV, TINY, density_of="pose")
    mass = dens.reshape(bins * sub, bins * sub, 60).sum(axis=2) * cell
    expected = mass.reshape(bins, sub, bins, sub).sum(axis=(1, 3))
    assert expected.sum() == pytest.approx(1.0, abs=5e-3)
    counts, _, _ = np.histogram2d(samples[:, 0], samples[:, 1],
                                  bins=[edges[0][::sub], edges[1][::sub]])
    expected = expected * n / expected.sum()
    keep = expected > 20
    chi2 = np.sum((counts[keep] - expected[keep]) ** 2 / expected[keep])
    dof = keep.sum() - 1
    assert dof >= 10
    assert chi2 < stats.chi2.ppf(0.999, dof), (chi2, dof)


def _table_5_6_motion(a, z):
    """The noisy (rot1, trans, rot2) of Probabilistic Robotics' Table 5.6, by hand, for ODO's
    motion (0.3, 0.5, -0.2) and the standard normal draws ``z`` (one row each, in order)."""
    d1, dt, d2 = 0.3, 0.5, -0.2
    s1 = math.sqrt(a[0] * d1**2 + a[1] * dt**2)
    st = math.sqrt(a[2] * dt**2 + a[3] * (d1**2 + d2**2))
    s2 = math.sqrt(a[0] * d2**2 + a[1] * dt**2)
    return d1 - s1 * z[0], dt - st * z[1], d2 - s2 * z[2]


def test_sampler_is_table_5_6_with_the_draws_in_order():
    a = [0.05, 0.02, 0.04, 0.01]
    got = M.sample_motion_model_odometry(PREV, ODO, ODO_PREV, a, 5, np.random.default_rng(7))
    z = np.random.default_rng(7).standard_normal((3, 5))
    h1, ht, h2 = _table_5_6_motion(a, z)
    want = np.column_stack([PREV[0] + ht * np.cos(PREV[2] + h1),
                            PREV[1] + ht * np.sin(PREV[2] + h1), PREV[2] + h1 + h2])
    assert got == pytest.approx(want, abs=1e-12)


def test_seeded_samplers_repeat():
    a = [0.05, 0.02, 0.04, 0.01]
    one = M.sample_motion_model_odometry(PREV, ODO, ODO_PREV, a, 50, np.random.default_rng(8))
    two = M.sample_motion_model_odometry(PREV, ODO, ODO_PREV, a, 50, np.random.default_rng(8))
    assert np.array_equal(one, two)


def test_velocity_sampler_without_noise_is_the_exact_arc():
    for twist in ((0.5, 0.0, 0.0), (0.5, 0.0, 1.2), (-0.3, 0.0, -2.0), (0.0, 0.0, 1.0)):
        s = M.sample_motion_model_velocity(PREV, twist, 0.7, [0.0] * 6, 3,
                                           np.random.default_rng(0))
        want = frames.compose(frames.Pose(*PREV), frames.se2_exp(twist, 0.7))
        for row in s:
            assert row == pytest.approx(tuple(want), abs=1e-12)


def test_velocity_sampler_draws_have_the_table_5_3_variances():
    n, dt = 200_000, 0.5
    v, w = 0.4, 0.8
    a = [0.02, 0.01, 0.03, 0.05, 0.0, 0.0]  # no final turn: theta' - theta = w_hat dt
    s = M.sample_motion_model_velocity((0, 0, 0), (v, 0, w), dt, a, n,
                                       np.random.default_rng(5))
    w_hat = s[:, 2] / dt
    chord = np.hypot(s[:, 0], s[:, 1])
    half = 0.5 * w_hat * dt
    v_hat = chord / (dt * np.sinc(half / math.pi))  # chord = v dt sin(h)/h
    var_v, var_w = a[0] * v**2 + a[1] * w**2, a[2] * v**2 + a[3] * w**2
    assert v_hat.mean() == pytest.approx(v, abs=4 * math.sqrt(var_v / n))
    assert w_hat.mean() == pytest.approx(w, abs=4 * math.sqrt(var_w / n))
    assert v_hat.var() == pytest.approx(var_v, rel=4 * math.sqrt(2 / n))
    assert w_hat.var() == pytest.approx(var_w, rel=4 * math.sqrt(2 / n))
    # the final turn alone
    g = M.sample_motion_model_velocity((0, 0, 0), (v, 0, w), dt, [0, 0, 0, 0, 0.02, 0.03], n,
                                       np.random.default_rng(6))
    gamma = (g[:, 2] - w * dt) / dt
    assert gamma.var() == pytest.approx(0.02 * v**2 + 0.03 * w**2, rel=4 * math.sqrt(2 / n))
    assert np.ptp(g[:, :2], axis=0).max() < 1e-12  # the position does not move


def test_odometry_names_them_as_the_chapter_does():
    for name in ("motion_model_odometry", "sample_motion_model_odometry",
                 "sample_motion_model_velocity", "odometry_motion", "OdometryMotion"):
        assert getattr(odometry, name) is getattr(motion_models, name)


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"alphas": [0.1, 0.1, 0.1]}, "alphas"),
    ({"alphas": [0.1, -0.1, 0.1, 0.1]}, "alphas"),
    ({"density_of": "x"}, "density_of"),
])
def test_density_bad_input(kwargs, match):
    args = {"pose": (1, 0, 0), "previous_pose": (0, 0, 0), "odometry": (1, 0, 0),
            "previous_odometry": (0, 0, 0), "alphas": [0.1] * 4} | kwargs
    with pytest.raises(ValueError, match=match):
        M.motion_model_odometry(**args)


def test_a_point_mass_has_no_density():
    with pytest.raises(ValueError, match="alphas"):
        M.motion_model_odometry((0, 0, 0), (0, 0, 0), (1, 0, 0), (0, 0, 0), [0.1] * 4)
    with pytest.raises(ValueError, match="pose"):
        M.motion_model_odometry((0, 0, 0.1), (0, 0, 0), (1, 0, 0), (0, 0, 0), [0.1] * 4,
                                density_of="pose")


def test_sampler_bad_input():
    with pytest.raises(ValueError, match="n must"):
        M.sample_motion_model_odometry(PREV, ODO, ODO_PREV, SMALL, 0, np.random.default_rng())
    with pytest.raises(TypeError, match="rng"):
        M.sample_motion_model_odometry(PREV, ODO, ODO_PREV, SMALL, 5, 3)
    with pytest.raises(ValueError, match="twist"):
        M.sample_motion_model_velocity(PREV, (0.1, 0.2, 0.0), 1.0, [0.0] * 6, 5,
                                       np.random.default_rng())


def test_a_particle_set_moves_each_particle_by_one_sample():
    a = [0.05, 0.02, 0.04, 0.01]
    particles = np.random.default_rng(9).normal(0.0, 0.1, (6, 3))
    got = M.sample_motion_model_odometry(particles, ODO, ODO_PREV, a, 6,
                                         np.random.default_rng(10))
    z = np.random.default_rng(10).standard_normal((3, 6))
    h1, ht, h2 = _table_5_6_motion(a, z)
    heading = particles[:, 2] + h1
    want = np.column_stack([particles[:, 0] + ht * np.cos(heading),
                            particles[:, 1] + ht * np.sin(heading), heading + h2])
    assert got == pytest.approx(want, abs=1e-12)
    with pytest.raises(ValueError, match="n must equal"):
        M.sample_motion_model_odometry(particles, ODO, ODO_PREV, a, 5,
                                       np.random.default_rng(10))
