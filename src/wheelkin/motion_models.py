r"""Probabilistic motion models: Thrun, Burgard and Fox's odometry and velocity models.

A localisation course (particle filters, grid localisation) meets the robot's motion as a
conditional probability :math:`p(x_t \mid u_t, x_{t-1})`: where the robot may be now, given
where it was and what its odometry or its commands said. The chapter "Odometry: where am I?"
derives these models and compares them with the propagated covariance of
:mod:`wheelkin.odometry_uncertainty` (section "Motion models").

The odometry model (:cite:t:`thrun2005`, section 5.4) splits the motion between two odometry
poses :math:`\bar x_{t-1} = (\bar x, \bar y, \bar\theta)` and
:math:`\bar x_t = (\bar x', \bar y', \bar\theta')` into a turn, a straight line and a turn
(:func:`odometry_motion`):

.. math::
    \delta_{rot1} = \operatorname{atan2}(\bar y' - \bar y, \bar x' - \bar x) - \bar\theta,\quad
    \delta_{trans} = \sqrt{(\bar x' - \bar x)^2 + (\bar y' - \bar y)^2},\quad
    \delta_{rot2} = \bar\theta' - \bar\theta - \delta_{rot1},

and takes each part to be wrong by a zero-mean normal error whose variance grows with the
motion, with four parameters :math:`\alpha_1 \dots \alpha_4` (Thrun's noise parameters, not
angles; dimensionless):

.. math::
    \sigma_{rot1}^2 = \alpha_1\delta_{rot1}^2 + \alpha_2\delta_{trans}^2,\quad
    \sigma_{trans}^2 = \alpha_3\delta_{trans}^2 + \alpha_4(\delta_{rot1}^2 + \delta_{rot2}^2),\quad
    \sigma_{rot2}^2 = \alpha_1\delta_{rot2}^2 + \alpha_2\delta_{trans}^2 .

Printings and lecture notes differ here (absolute values :math:`\alpha_1|\delta_{rot1}| +
\alpha_2\delta_{trans}` in the first printing of table 5.5, squares in later ones, and
``sample(b)`` taken as a standard deviation or a variance); this module uses the squares
above, each :math:`\sigma^2` a variance, so that :math:`\alpha_1` is a variance per squared
radian turned (rad²/rad²) and :math:`\alpha_3` a variance per squared metre driven: both
dimensionless, a relative error squared. :math:`\alpha_2` (rad²/m²) and :math:`\alpha_4`
(m²/rad²) couple the two kinds of motion. Angles and angle differences are wrapped to
:math:`(-\pi, \pi]`.

SI units (m, rad), REP-103; a pose is (x, y, θ).
"""

from __future__ import annotations

import math
from typing import Literal, NamedTuple, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _validate as V
from wheelkin._kernels import arc_step
from wheelkin._kernels import wrap_angle as _wrap
from wheelkin._records import Stack
from wheelkin.frames import Pose, Twist

__all__ = [
    "OdometryMotion",
    "motion_model_odometry",
    "odometry_motion",
    "sample_motion_model_odometry",
    "sample_motion_model_velocity",
]

#: The largest coordinate (m) and number of samples accepted.
_MAX_COORDINATE = 1e6
_MAX_SAMPLES = 10**8
_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)


class OdometryMotion(NamedTuple):
    r"""A motion as a turn, a straight line and a turn (see :func:`odometry_motion`)."""

    #: :math:`\delta_{rot1}`, rad: the turn towards the direction of travel.
    rot1: float | np.ndarray
    #: :math:`\delta_{trans}`, m (>= 0): the straight line.
    trans: float | np.ndarray
    #: :math:`\delta_{rot2}`, rad: the turn to the final heading.
    rot2: float | np.ndarray


_out = V.scalar_or_array


def _poses(name: str, value, *, stack: bool) -> np.ndarray:
    arr = V.shaped(name, value, (3,)) if stack else V.pose(name, value)
    if arr.size and np.max(np.abs(arr[..., :2])) > _MAX_COORDINATE:
        raise ValueError(f"{name} must have coordinates within +-{_MAX_COORDINATE:g} m")
    return arr


def _alphas(value, count: int) -> np.ndarray:
    a = V.finite_array("alphas", value)
    if a.shape != (count,):
        raise ValueError(f"alphas must have shape ({count},): Thrun's noise parameters "
                         f"alpha_1 ... alpha_{count}, got shape {a.shape}")
    if np.any(a < 0) or np.any(a > 1e6):
        raise ValueError(f"alphas must each be in [0, 1e6], got {value!r}")
    return a


def _deltas(before: np.ndarray, after: np.ndarray):
    dx, dy = after[..., 0] - before[..., 0], after[..., 1] - before[..., 1]
    rot1 = _wrap(np.arctan2(dy, dx) - before[..., 2])
    trans = np.hypot(dx, dy)
    rot2 = _wrap(after[..., 2] - before[..., 2] - rot1)
    return rot1, trans, rot2


def odometry_motion(previous_pose: Pose | ArrayLike, pose: Pose | ArrayLike) -> OdometryMotion:
    r"""The motion between two poses as a turn, a straight line and a turn.

    .. math::
        \delta_{rot1} = \operatorname{atan2}(y' - y, x' - x) - \theta,\quad
        \delta_{trans} = \sqrt{(x' - x)^2 + (y' - y)^2},\quad
        \delta_{rot2} = \theta' - \theta - \delta_{rot1}

    (:cite:t:`thrun2005`, table 5.5), both turns wrapped to :math:`(-\pi, \pi]`. For a turn
    on the spot (:math:`\delta_{trans} = 0`) the split is arbitrary: this takes
    :math:`\operatorname{atan2}(0, 0) = 0`, so :math:`\delta_{rot1} = -\theta`.

    Parameters
    ----------
    previous_pose : Pose or array_like, shape (3,) or (..., 3)
        (x, y, θ) before: m, m, rad.
    pose : Pose or array_like, shape (3,) or (..., 3)
        (x', y', θ') after, broadcast with ``previous_pose``.

    Returns
    -------
    OdometryMotion
        ``rot1`` (rad), ``trans`` (m), ``rot2`` (rad).

    Examples
    --------
    >>> m = odometry_motion((0.0, 0.0, 0.0), (1.0, 1.0, math.pi / 2))
    >>> print(f"{math.degrees(m.rot1):.0f}° {m.trans:.4f} m {math.degrees(m.rot2):.0f}°")
    45° 1.4142 m 45°
    """
    before = _poses("previous_pose", previous_pose, stack=True)
    after = _poses("pose", pose, stack=True)
    before, after = V.broadcast(previous_pose=before, pose=after)
    rot1, trans, rot2 = _deltas(before, after)
    return OdometryMotion(_out(rot1), _out(trans), _out(rot2))


def _odometry_variances(a: np.ndarray, rot1, trans, rot2):
    r1, t2, r2 = rot1 * rot1, trans * trans, rot2 * rot2
    return (a[0] * r1 + a[1] * t2, a[2] * t2 + a[3] * (r1 + r2), a[0] * r2 + a[1] * t2)


def _normal(diff, var):
    return _INV_SQRT_2PI / np.sqrt(var) * np.exp(-0.5 * diff * diff / var)


@overload
def motion_model_odometry(pose: Pose | ArrayLike, previous_pose: Pose | ArrayLike,
                          odometry: Pose | ArrayLike, previous_odometry: Pose | ArrayLike,
                          alphas: float, *,
                          density_of: Literal["motion", "pose"] = "motion",
                          ) -> float: ...
@overload
def motion_model_odometry(pose: Pose | ArrayLike, previous_pose: Pose | ArrayLike,
                          odometry: Pose | ArrayLike, previous_odometry: Pose | ArrayLike,
                          alphas: Stack, *,
                          density_of: Literal["motion", "pose"] = "motion",
                          ) -> NDArray[np.float64]: ...
def motion_model_odometry(pose: Pose | ArrayLike, previous_pose: Pose | ArrayLike,
                          odometry: Pose | ArrayLike, previous_odometry: Pose | ArrayLike,
                          alphas: ArrayLike, *,
                          density_of: Literal["motion", "pose"] = "motion",
                          ) -> float | NDArray[np.float64]:
    r"""The odometry motion model's density :math:`p(x_t \mid u_t, x_{t-1})`: Thrun's table 5.5.

    The odometry :math:`u_t` is the pair of odometry poses (``previous_odometry``,
    ``odometry``); its motion :math:`(\delta_{rot1}, \delta_{trans}, \delta_{rot2})` and the
    hypothesised motion :math:`(\hat\delta_{rot1}, \hat\delta_{trans}, \hat\delta_{rot2})`
    from ``previous_pose`` to ``pose`` come from :func:`odometry_motion`, and

    .. math::
        p = \mathcal N(\delta_{rot1} - \hat\delta_{rot1};\ \alpha_1\hat\delta_{rot1}^2
            + \alpha_2\hat\delta_{trans}^2)\;
            \mathcal N(\delta_{trans} - \hat\delta_{trans};\ \alpha_3\hat\delta_{trans}^2
            + \alpha_4(\hat\delta_{rot1}^2 + \hat\delta_{rot2}^2))\;
            \mathcal N(\delta_{rot2} - \hat\delta_{rot2};\ \alpha_1\hat\delta_{rot2}^2
            + \alpha_2\hat\delta_{trans}^2),

    with :math:`\mathcal N(d; \sigma^2)` the zero-mean normal density of variance
    :math:`\sigma^2`, the angle differences wrapped to :math:`(-\pi, \pi]` (the variances of
    the module's docstring; printings differ).

    **What it is a density of.** The product is a density over the three numbers of the
    motion, in rad · m · rad: integrated over :math:`(\hat\delta_{rot1}, \hat\delta_{trans},
    \hat\delta_{rot2})` it gives 1 (to within the variances' dependence on the hypothesis,
    a relative :math:`O(\alpha)`). Over the pose :math:`(x', y', \theta')` it does not: the
    map from the motion to the pose stretches volume by
    :math:`|\partial(x', y', \theta')/\partial(\delta_{rot1}, \delta_{trans}, \delta_{rot2})|
    = \hat\delta_{trans}`, so the density of the pose is the product divided by
    :math:`\hat\delta_{trans}` (``density_of="pose"``, in 1/(m² rad)). The default,
    ``"motion"``, is the table as printed. In a particle filter the difference is a weight
    that varies with :math:`1/\hat\delta_{trans}` across the particles; the chapter measures it.

    Parameters
    ----------
    pose : Pose or array_like, shape (3,) or (..., 3)
        The hypothesis :math:`x_t` (x', y', θ'): m, m, rad; a stack evaluates many at once.
    previous_pose : Pose or array_like, shape (3,)
        :math:`x_{t-1}`: m, m, rad.
    odometry, previous_odometry : Pose or array_like, shape (3,)
        The odometry poses :math:`\bar x_t` and :math:`\bar x_{t-1}` (in the odometry's own
        frame; only their difference matters): m, m, rad.
    alphas : array_like, shape (4,)
        :math:`\alpha_1 \dots \alpha_4` (each >= 0; see the module's docstring for their
        units).
    density_of : {"motion", "pose"}
        "motion" (default): Thrun's product; "pose": divided by :math:`\hat\delta_{trans}`.

    Returns
    -------
    float or ndarray
        The density (a float for one hypothesis).

    Raises
    ------
    ValueError
        Bad input, or a hypothesis whose variance is zero (no motion, or all the alphas that
        matter zero: the model is then a point mass, with no density), or
        ``density_of="pose"`` at :math:`\hat\delta_{trans} = 0`.

    Examples
    --------
    Odometry says 1 m straight ahead; the hypothesis is exactly that motion. With
    :math:`\alpha = (0.01, 0.01, 0.01, 0.01)`: :math:`\sigma_{rot} = 0.1` rad and
    :math:`\sigma_{trans} = 0.1` m, so each factor is :math:`1/(0.1\sqrt{2\pi})`.

    >>> a = [0.01, 0.01, 0.01, 0.01]
    >>> p = motion_model_odometry((1, 0, 0), (0, 0, 0), (1, 0, 0), (0, 0, 0), a)
    >>> print(f"{p:.4f} {(1 / (0.1 * math.sqrt(2 * math.pi))) ** 3:.4f}")
    63.4936 63.4936
    """
    hyp = _poses("pose", pose, stack=True)
    prev = _poses("previous_pose", previous_pose, stack=False)
    odo = _poses("odometry", odometry, stack=False)
    odo_prev = _poses("previous_odometry", previous_odometry, stack=False)
    a = _alphas(alphas, 4)
    V.choice("density_of", density_of, ("motion", "pose"))
    rot1, trans, rot2 = _deltas(odo_prev, odo)
    h_rot1, h_trans, h_rot2 = _deltas(prev, hyp)
    variances = _odometry_variances(a, h_rot1, h_trans, h_rot2)
    for name, var in zip(("rot1", "trans", "rot2"), variances, strict=True):
        if np.any(np.asarray(var) <= 0):
            raise ValueError(f"alphas and pose give a zero variance of delta_{name} (no motion "
                             "in the hypothesis, or the alphas that scale it are zero): the "
                             "model is a point mass there, with no density")
    with np.errstate(all="ignore"):
        p = (_normal(_wrap(rot1 - h_rot1), variances[0])
             * _normal(trans - h_trans, variances[1])
             * _normal(_wrap(rot2 - h_rot2), variances[2]))
        if density_of == "pose":
            if np.any(h_trans == 0):
                raise ValueError("pose must differ in position from previous_pose for "
                                 "density_of='pose' (the density of the pose is infinite "
                                 "where the hypothesis does not move: delta_trans = 0)")
            p = p / h_trans
    return _out(V.finite_result("alphas", p))


def _samples(n) -> int:
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or not 1 <= n <= _MAX_SAMPLES:
        raise ValueError(f"n must be a whole number in [1, {_MAX_SAMPLES:g}], got {n!r}")
    return int(n)


def _generator(rng) -> np.random.Generator:
    if not isinstance(rng, np.random.Generator):
        raise TypeError("rng must be a numpy.random.Generator (np.random.default_rng(seed)), "
                        f"got {type(rng).__name__}")
    return rng


def sample_motion_model_odometry(previous_pose: Pose | ArrayLike, odometry: Pose | ArrayLike,
                                 previous_odometry: Pose | ArrayLike, alphas: ArrayLike,
                                 n: int, rng: np.random.Generator) -> NDArray[np.float64]:
    r"""Samples of :math:`x_t \sim p(x_t \mid u_t, x_{t-1})`: Thrun's table 5.6.

    The motion :math:`(\delta_{rot1}, \delta_{trans}, \delta_{rot2})` of the odometry (from
    ``previous_odometry`` to ``odometry``, :func:`odometry_motion`) is perturbed by normal
    errors whose variances are those of the module's docstring, computed from the
    *measured* motion:

    .. math::
        \hat\delta_{rot1} = \delta_{rot1} - \varepsilon_1,\quad
        \hat\delta_{trans} = \delta_{trans} - \varepsilon_2,\quad
        \hat\delta_{rot2} = \delta_{rot2} - \varepsilon_3,

    and applied to the previous pose:

    .. math::
        x' = x + \hat\delta_{trans}\cos(\theta + \hat\delta_{rot1}),\quad
        y' = y + \hat\delta_{trans}\sin(\theta + \hat\delta_{rot1}),\quad
        \theta' = \theta + \hat\delta_{rot1} + \hat\delta_{rot2}.

    The draws come from ``rng`` in a fixed order (all :math:`\varepsilon_1`, then all
    :math:`\varepsilon_2`, then all :math:`\varepsilon_3`), so a seeded generator gives the
    same samples every time. The headings are not wrapped.

    Parameters
    ----------
    previous_pose : Pose or array_like, shape (3,) or (n, 3)
        :math:`x_{t-1}`: m, m, rad; a particle set (n, 3) moves each particle by one sample
        (the particle filter's prediction step).
    odometry, previous_odometry : Pose or array_like, shape (3,)
        The odometry poses :math:`\bar x_t`, :math:`\bar x_{t-1}`: m, m, rad.
    alphas : array_like, shape (4,)
        :math:`\alpha_1 \dots \alpha_4` (each >= 0).
    n : int
        Number of samples (>= 1; equal to the number of particles for a particle set).
    rng : numpy.random.Generator
        The source of the errors, e.g. ``np.random.default_rng(7)``.

    Returns
    -------
    ndarray
        Shape (n, 3): the sampled poses (x', y', θ').

    Examples
    --------
    >>> s = sample_motion_model_odometry((0, 0, 0), (1, 0, 0), (0, 0, 0),
    ...                                  [0.01, 0.0, 0.01, 0.0], 100_000,
    ...                                  np.random.default_rng(1))
    >>> s.shape, round(float(s[:, 0].mean()), 2), round(float(s[:, 0].std()), 2)
    ((100000, 3), 1.0, 0.1)
    """
    prev = _poses("previous_pose", previous_pose, stack=True)
    if prev.ndim > 2:
        raise ValueError(f"previous_pose must have shape (3,) or (n, 3), got shape "
                         f"{prev.shape}")
    odo = _poses("odometry", odometry, stack=False)
    odo_prev = _poses("previous_odometry", previous_odometry, stack=False)
    a = _alphas(alphas, 4)
    count = _samples(n)
    if prev.ndim == 2 and len(prev) != count:
        raise ValueError(f"n must equal the number of particles in previous_pose "
                         f"({len(prev)}), got {n!r}")
    prev = prev.T if prev.ndim == 2 else prev
    gen = _generator(rng)
    rot1, trans, rot2 = (float(d) for d in _deltas(odo_prev, odo))
    sd = np.sqrt(_odometry_variances(a, rot1, trans, rot2))
    noise = gen.standard_normal((3, count)) * np.asarray(sd)[:, None]
    h_rot1 = rot1 - noise[0]
    h_trans = trans - noise[1]
    h_rot2 = rot2 - noise[2]
    heading = prev[2] + h_rot1
    out = np.empty((count, 3))
    out[:, 0] = prev[0] + h_trans * np.cos(heading)
    out[:, 1] = prev[1] + h_trans * np.sin(heading)
    out[:, 2] = heading + h_rot2
    return V.finite_result("alphas", out)


def sample_motion_model_velocity(previous_pose: Pose | ArrayLike, twist: Twist | ArrayLike,
                                 dt: float, alphas: ArrayLike, n: int,
                                 rng: np.random.Generator) -> NDArray[np.float64]:
    r"""Samples of the velocity motion model: Thrun's table 5.3.

    The commanded speed and yaw rate :math:`(v, \omega)` are perturbed, and a final turn
    :math:`\hat\gamma` is added (without it, every sample would lie on a two-dimensional
    surface of the three-dimensional pose space):

    .. math::
        \hat v = v + \varepsilon(\alpha_1 v^2 + \alpha_2\omega^2),\quad
        \hat\omega = \omega + \varepsilon(\alpha_3 v^2 + \alpha_4\omega^2),\quad
        \hat\gamma = \varepsilon(\alpha_5 v^2 + \alpha_6\omega^2),

    :math:`\varepsilon(\sigma^2)` a zero-mean normal draw of variance :math:`\sigma^2`. The
    pose moves along the arc of :math:`(\hat v, \hat\omega)` for :math:`\Delta t`, then turns
    by :math:`\hat\gamma\Delta t`:

    .. math::
        x' = x - \frac{\hat v}{\hat\omega}\sin\theta + \frac{\hat v}{\hat\omega}
             \sin(\theta + \hat\omega\Delta t),\quad
        y' = y + \frac{\hat v}{\hat\omega}\cos\theta - \frac{\hat v}{\hat\omega}
             \cos(\theta + \hat\omega\Delta t),\quad
        \theta' = \theta + \hat\omega\Delta t + \hat\gamma\Delta t,

    evaluated with the library's arc kernel, so a draw with :math:`\hat\omega = 0` (a straight
    line) is exact instead of 0/0. Units: :math:`\alpha_1` and :math:`\alpha_4, \alpha_6`
    are dimensionless (a relative error squared), :math:`\alpha_2` is in m²/rad² and
    :math:`\alpha_3, \alpha_5` in rad²/m². The same printing caveat as the odometry model
    applies: these are variances, of squared speeds.

    Parameters
    ----------
    previous_pose : Pose or array_like, shape (3,)
        :math:`x_{t-1}`: m, m, rad.
    twist : Twist or array_like, shape (3,)
        The command :math:`(v, 0, \omega)`: m/s, m/s, rad/s (``vy`` must be 0).
    dt : float
        :math:`\Delta t`, s (> 0).
    alphas : array_like, shape (6,)
        :math:`\alpha_1 \dots \alpha_6` (each >= 0).
    n : int
        Number of samples (>= 1).
    rng : numpy.random.Generator
        The source of the errors (draws in the order v̂, ω̂, γ̂, each for all samples).

    Returns
    -------
    ndarray
        Shape (n, 3): the sampled poses (x', y', θ'), headings not wrapped.

    Examples
    --------
    A noise-free quarter circle of radius 1 m: every sample ends at (1, 1, π/2).

    >>> s = sample_motion_model_velocity((0, 0, 0), (math.pi / 2, 0, math.pi / 2), 1.0,
    ...                                  [0.0] * 6, 3, np.random.default_rng(0))
    >>> s.round(12).tolist()[0] == [1.0, 1.0, round(math.pi / 2, 12)]
    True
    """
    prev = _poses("previous_pose", previous_pose, stack=False)
    tw = V.twist("twist", twist)
    if tw[1] != 0.0:
        raise ValueError(f"twist must have vy = 0 (a command (v, 0, omega)), got {twist!r}")
    if abs(tw[0]) > 1e3 or abs(tw[2]) > 1e3:
        raise ValueError(f"twist must have |v| <= 1000 m/s and |omega| <= 1000 rad/s, got "
                         f"{twist!r}")
    step = V.positive("dt", dt)
    if step > 1e6:
        raise ValueError(f"dt must be at most 1e6 s, got {dt!r}")
    a = _alphas(alphas, 6)
    count = _samples(n)
    gen = _generator(rng)
    v, w = float(tw[0]), float(tw[2])
    v2, w2 = v * v, w * w
    sd = np.sqrt([a[0] * v2 + a[1] * w2, a[2] * v2 + a[3] * w2, a[4] * v2 + a[5] * w2])
    noise = gen.standard_normal((3, count)) * sd[:, None]
    v_hat, w_hat, g_hat = v + noise[0], w + noise[1], noise[2]
    with np.errstate(all="ignore"):
        x, y, th = arc_step(prev[0], prev[1], prev[2], v_hat * step, w_hat * step)
        out = np.stack([np.broadcast_to(x, (count,)), np.broadcast_to(y, (count,)),
                        th + g_hat * step], axis=-1)
    return V.finite_result("twist, dt and alphas", out)
