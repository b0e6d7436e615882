r"""Wheel odometry and a gyro in one extended Kalman filter, and the test of its honesty.

The prediction is the book's own covariance step
(:func:`~wheelkin.odometry_uncertainty.propagate_covariance`: the exact arc update and
:math:`\Sigma' = F_p\Sigma F_p^\mathsf{T} + F_w Q F_w^\mathsf{T}`). A rate gyro, integrated
over the same update, measures the turn of the step, :math:`z = \theta_{k+1} - \theta_k + n`,
:math:`n \sim \mathcal N(0, \sigma_z^2)`: a measurement of a *change* of the state, which
depends on the state before the step as well as after it. The filter keeps a copy of the
heading before the step in its state (stochastic cloning, :cite:t:`roumeliotis2002`) so that
the update is an ordinary Kalman update of the augmented state
:math:`(x_{k+1}, y_{k+1}, \theta_{k+1}, \theta_k)` with :math:`\mathbf h = (0, 0, 1, -1)`; the
copy is dropped after the update. The chapter "Odometry: where am I?" derives it (section
"Odometry and a gyro") and shows that the update reduces to

.. math::
    \mathbf c = (F_w Q F_w^\mathsf{T})_{:,3},\quad S = c_3 + \sigma_z^2,\quad
    x^+ = x^- + \mathbf c\,\frac{z - \Delta\theta_w}{S},\quad
    \Sigma^+ = \Sigma^- - \frac{\mathbf c\,\mathbf c^\mathsf{T}}{S},

where :math:`\Delta\theta_w` is the wheels' turn: the gyro corrects only what the wheels
got wrong in this step. :func:`nees` is the normalised estimation error squared that tells
whether the covariance describes the error.

SI units (m, rad), REP-103; :math:`W` the track width. Headings are not wrapped.
"""

from __future__ import annotations

from typing import NamedTuple, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _validate as V
from wheelkin._kernels import arc_step
from wheelkin._records import Stack, _is_one
from wheelkin.frames import Pose
from wheelkin.odometry_uncertainty import _jacobians, propagate_covariance, step_jacobians

__all__ = ["FusionPath", "FusionStep", "ekf_path", "ekf_step", "nees"]

#: The largest gyro variance accepted, rad² (a turn known to within a few full turns).
_MAX_GYRO_VARIANCE = 100.0


class FusionStep(NamedTuple):
    """One step of :func:`ekf_step`."""

    #: The pose after the step (m, m, rad): a Pose for a Pose, else an array (3,).
    pose: Pose | np.ndarray
    #: Its covariance, (3, 3).
    covariance: np.ndarray
    #: The gyro's turn minus the wheels' turn, rad (None without a gyro reading).
    innovation: float | None
    #: The innovation's predicted variance :math:`S`, rad² (None without a gyro reading).
    innovation_variance: float | None


class FusionPath(NamedTuple):
    """A run of :func:`ekf_path`: the start first."""

    #: (N + 1, 3) poses, m, m, rad.
    poses: np.ndarray
    #: (N + 1, 3, 3) covariances.
    covariances: np.ndarray
    #: (N,) innovations, rad (zeros without a gyro).
    innovations: np.ndarray
    #: (N,) innovation variances, rad² (zeros without a gyro).
    innovation_variances: np.ndarray


def _gyro_variance(value) -> float:
    r = V.positive("gyro_variance", value)
    if r > _MAX_GYRO_VARIANCE:
        raise ValueError(f"gyro_variance must be in (0, {_MAX_GYRO_VARIANCE:g}] rad², got "
                         f"{value!r}")
    return r


def _update(pose: np.ndarray, sigma_pred: np.ndarray, cross: np.ndarray, sigma_before: float,
            turn_before: float, z: float, r: float):
    """Kalman update of the augmented state (pose after, heading before) by z = theta' - theta
    + n; returns the pose, the marginal covariance, the innovation and its variance."""
    aug = np.empty((4, 4))
    aug[:3, :3] = sigma_pred
    aug[:3, 3] = aug[3, :3] = cross
    aug[3, 3] = sigma_before
    h = np.array([0.0, 0.0, 1.0, -1.0])
    innovation = z - (pose[2] - turn_before)
    s = float(h @ aug @ h) + r
    gain = aug @ h / s
    state = np.concatenate([pose, [turn_before]]) + gain * innovation
    joseph = np.eye(4) - np.outer(gain, h)
    post = joseph @ aug @ joseph.T + r * np.outer(gain, gain)
    post = 0.5 * (post + post.T)
    return state[:3], post[:3, :3], float(innovation), s


def ekf_step(pose: Pose | ArrayLike, covariance: ArrayLike, delta_left: float,
             delta_right: float, track_width: float, k_left: float, k_right: float,
             gyro_turn: float | None = None, gyro_variance: float = 1e-6) -> FusionStep:
    r"""One step of the wheel-and-gyro EKF: predict with the wheels, correct with the gyro.

    **Predict** (:func:`wheelkin.odometry_uncertainty.propagate_covariance`):
    :math:`x^- = f(x, \Delta s_L, \Delta s_R)`, the exact arc, and
    :math:`\Sigma^- = F_p\Sigma F_p^\mathsf{T} + F_w Q F_w^\mathsf{T}`,
    :math:`Q = \operatorname{diag}(k_L|\Delta s_L|, k_R|\Delta s_R|)`.

    **Update** with the gyro's turn :math:`z` over the step (variance :math:`\sigma_z^2`): the
    augmented state :math:`(x^-, \theta)` has the covariance
    :math:`\begin{pmatrix}\Sigma^- & F_p\Sigma_{:,3}\\ \cdot & \Sigma_{33}\end{pmatrix}`; with
    :math:`\mathbf h = (0, 0, 1, -1)`, :math:`S = \mathbf h P \mathbf h^\mathsf{T} + \sigma_z^2`,
    the gain :math:`\mathbf g = P\mathbf h^\mathsf{T}/S`, the Joseph form
    :math:`P^+ = (I - \mathbf g\mathbf h)P(I - \mathbf g\mathbf h)^\mathsf{T}
    + \sigma_z^2\mathbf g\mathbf g^\mathsf{T}`, and the
    pose and its covariance are the first three entries. Without a gyro reading
    (``gyro_turn=None``) the step is the prediction alone.

    Parameters
    ----------
    pose : Pose or array_like, shape (3,)
        The estimate before the step (x, y, θ): m, m, rad.
    covariance : array_like, shape (3, 3)
        Its covariance: symmetric, positive semi-definite.
    delta_left, delta_right : float
        The wheels' travels in the step (from the encoders), m.
    track_width : float
        :math:`W`, m (> 0).
    k_left, k_right : float
        The wheels' error variance per metre rolled, m (>= 0).
    gyro_turn : float, optional
        The gyro's yaw rate integrated over the step, rad (None: no reading).
    gyro_variance : float
        :math:`\sigma_z^2`, rad² (> 0): for white rate noise of density :math:`\sigma_g`
        (rad/s/√Hz) over a step of :math:`T` seconds, :math:`\sigma_g^2 T`.

    Returns
    -------
    FusionStep
        ``pose`` (a Pose for a Pose), ``covariance`` (3, 3), ``innovation`` and
        ``innovation_variance`` (None without a gyro reading).

    Examples
    --------
    The wheels say the robot drove 0.1 m straight; the gyro, 100 times surer than the
    wheels' turn, says it turned 0.01 rad. The estimate takes almost all of the gyro's turn,
    and a sideways shift with it (half the step drives at the new heading):

    >>> step = ekf_step([0, 0, 0], np.zeros((3, 3)), 0.1, 0.1, 0.085, 1e-6, 1e-6,
    ...                 gyro_turn=0.01, gyro_variance=2.768e-7)
    >>> print(np.round(step.pose, 5), f"{step.innovation:.3f} rad")
    [0.1    0.0005 0.0099] 0.010 rad
    """
    predicted = propagate_covariance(pose, covariance, delta_left, delta_right, track_width,
                                     k_left, k_right)
    if gyro_turn is None:
        V.positive("gyro_variance", gyro_variance)
        return FusionStep(predicted.pose, predicted.covariance, None, None)
    z = V.finite("gyro_turn", gyro_turn)
    if abs(z) > 1e6:
        raise ValueError(f"gyro_turn must be within +-1e6 rad, got {gyro_turn!r}")
    r = _gyro_variance(gyro_variance)
    before = V.pose("pose", pose)
    sigma = np.asarray(covariance, dtype=float)
    jac = step_jacobians(before, delta_left, delta_right, track_width)
    cross = jac.wrt_pose @ (0.5 * (sigma + sigma.T))[:, 2]
    after, post, innovation, s = _update(np.asarray(predicted.pose, dtype=float),
                                         predicted.covariance, cross, float(sigma[2, 2]),
                                         float(before[2]), z, r)
    out = Pose(*after.tolist()) if _is_one(pose, Pose) else after
    return FusionStep(out, post, innovation, s)


def ekf_path(pose: Pose | ArrayLike, covariance: ArrayLike, delta_left: ArrayLike,
             delta_right: ArrayLike, track_width: float, k_left: float, k_right: float,
             gyro_turns: ArrayLike | None = None, gyro_variance: float = 1e-6) -> FusionPath:
    r""":func:`ekf_step` over a sequence of updates.

    Parameters
    ----------
    pose : Pose or array_like, shape (3,)
        The start estimate: m, m, rad.
    covariance : array_like, shape (3, 3)
        Its covariance.
    delta_left, delta_right : array_like, shape (N,)
        The wheels' travels of each update, m.
    track_width : float
        :math:`W`, m (> 0).
    k_left, k_right : float
        The wheels' error variance per metre rolled, m (>= 0).
    gyro_turns : array_like, shape (N,), optional
        The gyro's turn over each update, rad (None: wheels only, the propagation of
        :func:`wheelkin.odometry_uncertainty.propagate_path`).
    gyro_variance : float
        The variance of one gyro turn, rad² (> 0).

    Returns
    -------
    FusionPath
        ``poses`` (N + 1, 3), ``covariances`` (N + 1, 3, 3), ``innovations`` and
        ``innovation_variances`` (N,), the start first.

    Examples
    --------
    >>> h = np.full(100, 0.01)
    >>> run = ekf_path([0, 0, 0], np.zeros((3, 3)), h, h, 0.085, 1e-6, 1e-6,
    ...                gyro_turns=np.zeros(100), gyro_variance=1e-8)
    >>> wheels = ekf_path([0, 0, 0], np.zeros((3, 3)), h, h, 0.085, 1e-6, 1e-6)
    >>> print(f"{np.sqrt(run.covariances[-1, 2, 2]) * 1e3:.2f} mrad with the gyro, "
    ...       f"{np.sqrt(wheels.covariances[-1, 2, 2]) * 1e3:.2f} without")
    1.00 mrad with the gyro, 16.64 without
    """
    left = V.finite_array("delta_left", delta_left)
    right = V.finite_array("delta_right", delta_right)
    if left.ndim != 1 or right.shape != left.shape or left.size == 0:
        raise ValueError("delta_left and delta_right must be 1-D arrays of the same length "
                         f"N >= 1 (m), got shapes {left.shape} and {right.shape}")
    turns = None
    if gyro_turns is not None:
        turns = V.finite_array("gyro_turns", gyro_turns)
        if turns.shape != left.shape:
            raise ValueError(f"gyro_turns must have shape {left.shape} (one turn per update, "
                             f"rad), got shape {turns.shape}")
        if np.any(np.abs(turns) > 1e6):
            raise ValueError("gyro_turns must be within +-1e6 rad")
    # Validate once through the public step (its first update), then run the same arithmetic
    # without re-validating every update.
    first = ekf_step(pose, covariance, float(left[0]), float(right[0]), track_width, k_left,
                     k_right, None if turns is None else float(turns[0]), gyro_variance)
    w = float(track_width)
    kl, kr = float(k_left), float(k_right)
    r = float(gyro_variance)
    n = left.size
    poses = np.empty((n + 1, 3))
    covs = np.empty((n + 1, 3, 3))
    innov = np.zeros(n)
    svar = np.zeros(n)
    poses[0] = V.pose("pose", pose)
    covs[0] = 0.5 * (np.asarray(covariance, dtype=float) + np.asarray(covariance).T)
    ds_all = 0.5 * (left + right)
    dth_all = (right - left) / w
    if np.any(np.abs(dth_all) > 1e6) or np.any(np.abs(left) > 1e6) or np.any(
            np.abs(right) > 1e6):
        raise ValueError("delta_left and delta_right must be wheel travels within +-1e6 m "
                         "(and turns within +-1e6 rad for track_width)")
    for k in range(n):
        if k == 0:
            poses[1] = np.asarray(first.pose, dtype=float)
            covs[1] = first.covariance
            if first.innovation is not None:
                innov[0], svar[0] = first.innovation, float(first.innovation_variance or 0.0)
            continue
        p, sigma = poses[k], covs[k]
        f_pose, f_wheels = _jacobians(p[2], ds_all[k], dth_all[k], w)
        q = np.diag([kl * abs(left[k]), kr * abs(right[k])])
        pred_cov = f_pose @ sigma @ f_pose.T + f_wheels @ q @ f_wheels.T
        pred_cov = 0.5 * (pred_cov + pred_cov.T)
        x, y, th = arc_step(float(p[0]), float(p[1]), float(p[2]), float(ds_all[k]),
                            float(dth_all[k]))
        pred = np.array([x, y, th])
        if turns is None:
            poses[k + 1], covs[k + 1] = pred, pred_cov
            continue
        cross = f_pose @ sigma[:, 2]
        after, post, innov[k], svar[k] = _update(pred, pred_cov, cross, float(sigma[2, 2]),
                                                 float(p[2]), float(turns[k]), r)
        poses[k + 1], covs[k + 1] = after, post
    return FusionPath(poses, covs, innov, svar)


@overload
def nees(error: float, covariance: float) -> float: ...  # type: ignore[overload-overlap]
@overload
def nees(error: float | Stack, covariance: float | Stack) -> NDArray[np.float64]: ...
def nees(error: ArrayLike, covariance: ArrayLike) -> float | NDArray[np.float64]:
    r"""The normalised estimation error squared, :math:`\epsilon = e^\mathsf{T}\Sigma^{-1}e`.

    For an estimator whose covariance :math:`\Sigma` describes its error :math:`e` (estimate
    minus truth, angles unwrapped), :math:`\epsilon` follows the chi-square law with as many
    degrees of freedom as :math:`e` has entries: its mean is that number (3 for a pose), and
    the mean over :math:`M` independent runs lies, 95 % of the time, between the chi-square
    quantiles of :math:`3M` degrees of freedom divided by :math:`M`
    :cite:p:`barshalom2001`. A mean well above means the filter is overconfident (its
    covariance too small for its errors); well below, too timid.

    Parameters
    ----------
    error : array_like, shape (..., k)
        Estimate minus truth (for a pose: m, m, rad).
    covariance : array_like, shape (..., k, k)
        The estimate's covariance, symmetric positive definite.

    Returns
    -------
    float or ndarray
        :math:`\epsilon` (dimensionless), shape ``error.shape[:-1]``.

    Examples
    --------
    An error of one standard deviation in each of three independent coordinates:

    >>> nees([0.01, -0.02, 0.003], np.diag([0.01, 0.02, 0.003]) ** 2)
    3.0
    """
    e = V.finite_array("error", error)
    sigma = V.finite_array("covariance", covariance)
    if e.ndim < 1 or e.shape[-1] == 0:
        raise ValueError(f"error must have shape (..., k), k >= 1, got shape {e.shape}")
    k = e.shape[-1]
    if sigma.shape[-2:] != (k, k):
        raise ValueError(f"covariance must have shape (..., {k}, {k}) to match error, got "
                         f"shape {sigma.shape}")
    if np.max(np.abs(sigma - np.swapaxes(sigma, -1, -2)), initial=0.0) > 1e-9 * max(
            1.0, float(np.max(np.abs(sigma), initial=0.0))):
        raise ValueError("covariance must be symmetric")
    try:
        chol = np.linalg.cholesky(sigma)
    except np.linalg.LinAlgError:
        raise ValueError("covariance must be positive definite (it has a zero or negative "
                         "eigenvalue: an estimate claimed exact)") from None
    try:
        e_b = np.broadcast_to(e, (*np.broadcast_shapes(e.shape[:-1], sigma.shape[:-2]), k))
        chol_b = np.broadcast_to(chol, (*e_b.shape[:-1], k, k))
    except ValueError:
        raise ValueError(f"error and covariance must have shapes that broadcast, got "
                         f"{e.shape} and {sigma.shape}") from None
    with np.errstate(all="ignore"):
        w = np.linalg.solve(chol_b, e_b[..., None])[..., 0]
        out = np.sum(w * w, axis=-1)
    out = V.finite_result("error and covariance", out)
    return float(out) if np.ndim(out) == 0 else out

