r"""How wrong, and how sure: the uncertainty of a dead-reckoned differential drive.

The covariance of a dead-reckoned pose under random wheel errors, propagated to first order
(:func:`step_jacobians`, :func:`propagate_covariance`, :func:`propagate_path`) or sampled
(:func:`monte_carlo_poses`), and Borenstein and Feng's UMBmark correction of the two
systematic errors (:func:`umbmark_correction`). The chapter "Odometry: where am I?" derives
them (sections "How sure is the pose?", "Monte Carlo" and "UMBmark").

SI units (m, rad), REP-103 frame. :math:`W` is the track width (``track_width``): the
side-to-side distance between the wheels' contact lines. The pose update is the exact arc of
:func:`wheelkin.odometry.pose_update` (the library's arc kernel).

Every name here is importable from :mod:`wheelkin.odometry` too, where it was first
(``wheelkin.odometry.propagate_covariance`` is ``wheelkin.odometry_uncertainty
.propagate_covariance``).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from wheelkin import _validate as V
from wheelkin._kernels import SERIES_THRESHOLD as _ARC_THRESHOLD
from wheelkin._kernels import arc_factors, arc_step
from wheelkin._records import _is_one
from wheelkin.frames import Pose

__all__ = [
    "PathCovariance",
    "PoseCovariance",
    "StepJacobians",
    "UmbmarkCorrection",
    "monte_carlo_poses",
    "propagate_covariance",
    "propagate_path",
    "step_jacobians",
    "umbmark_correction",
]


class StepJacobians(NamedTuple):
    """The Jacobians of one exact-arc update (see :func:`step_jacobians`)."""

    #: :math:`F_p = \partial(x', y', \theta')/\partial(x, y, \theta)`, shape (3, 3).
    wrt_pose: np.ndarray
    #: :math:`F_w = \partial(x', y', \theta')/\partial(\Delta s_L, \Delta s_R)`, shape (3, 2).
    wrt_wheels: np.ndarray


class PoseCovariance(NamedTuple):
    """A pose (x, y, θ) in m, m, rad and its 3 x 3 covariance (m², m·rad, rad²)."""

    pose: Pose | np.ndarray
    covariance: np.ndarray


class PathCovariance(NamedTuple):
    """Poses (N + 1, 3) along a path, the start first, and their covariances (N + 1, 3, 3)."""

    poses: np.ndarray
    covariances: np.ndarray


class UmbmarkCorrection(NamedTuple):
    """Borenstein and Feng's two correction factors (see :func:`umbmark_correction`)."""

    #: :math:`E_d = D_R/D_L`, the ratio of the right to the left wheel's true diameter.
    diameter_ratio: float
    #: :math:`E_b = W_{true}/W_{assumed}`, the true track width over the assumed one.
    track_ratio: float


def _covariance(value, name: str = "covariance") -> np.ndarray:
    arr = V.finite_array(name, value)
    if arr.shape != (3, 3):
        raise ValueError(f"{name} must have shape (3, 3) (over x, y, theta), got shape "
                         f"{arr.shape}")
    scale = max(1.0, float(np.max(np.abs(arr))))
    if np.max(np.abs(arr - arr.T)) > 1e-9 * scale:
        raise ValueError(f"{name} must be symmetric, got {arr.tolist()!r}")
    sym = 0.5 * (arr + arr.T)
    if np.min(np.linalg.eigvalsh(sym)) < -1e-12 * scale:
        raise ValueError(f"{name} must be positive semi-definite (no negative eigenvalue), "
                         f"got eigenvalues {np.linalg.eigvalsh(sym).tolist()!r}")
    return sym


def _arc_derivatives(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r""":math:`(a'(\varphi), b'(\varphi))` of the kernel's arc factors, exact at 0."""
    small = np.abs(phi) < _ARC_THRESHOLD
    safe = np.where(small, 1.0, phi)
    a, b = arc_factors(safe)
    p2 = phi * phi
    da = np.where(small, phi * (-1.0 / 3.0 + p2 / 30.0), (np.cos(safe) - a) / safe)
    db = np.where(small, 0.5 - p2 / 8.0 + p2 * p2 / 144.0, a - b / safe)
    return da, db


def _jacobians(theta, ds, dth, track_width: float) -> tuple[np.ndarray, np.ndarray]:
    """F_pose (..., 3, 3) and F_wheels (..., 3, 2) for validated, broadcast arrays."""
    theta, ds, dth = np.broadcast_arrays(*(np.asarray(q, dtype=float) for q in
                                           (theta, ds, dth)))
    a, b = arc_factors(dth)
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    da, db = _arc_derivatives(dth)
    c, s = np.cos(theta), np.sin(theta)
    dx = ds * (a * c - b * s)
    dy = ds * (a * s + b * c)
    shape = theta.shape
    f_pose = np.zeros((*shape, 3, 3))
    f_pose[..., 0, 0] = f_pose[..., 1, 1] = f_pose[..., 2, 2] = 1.0
    f_pose[..., 0, 2] = -dy
    f_pose[..., 1, 2] = dx
    f_wheels = np.empty((*shape, 3, 2))
    for column, sign in ((0, -1.0), (1, 1.0)):  # left, right
        d_a = 0.5 * a + sign * ds * da / track_width
        d_b = 0.5 * b + sign * ds * db / track_width
        f_wheels[..., 0, column] = d_a * c - d_b * s
        f_wheels[..., 1, column] = d_a * s + d_b * c
        f_wheels[..., 2, column] = sign / track_width
    return f_pose, f_wheels


def _body(delta_left, delta_right, track_width: float):
    return 0.5 * (delta_left + delta_right), (delta_right - delta_left) / track_width


def step_jacobians(pose: ArrayLike, delta_left: float, delta_right: float,
                   track_width: float) -> StepJacobians:
    r"""The Jacobians of one exact-arc update with respect to the pose and the wheel travels.

    The update (the chord form of :func:`wheelkin.odometry.pose_update`, ``method="exact"``) is

    .. math::
        \Delta s = \frac{\Delta s_L + \Delta s_R}{2},\quad
        \Delta\theta = \frac{\Delta s_R - \Delta s_L}{W},\quad
        \begin{aligned}
        x' &= x + \Delta s\,(a\cos\theta - b\sin\theta)\\
        y' &= y + \Delta s\,(a\sin\theta + b\cos\theta)\\
        \theta' &= \theta + \Delta\theta
        \end{aligned}

    with :math:`a = \sin\Delta\theta/\Delta\theta` and
    :math:`b = (1 - \cos\Delta\theta)/\Delta\theta`. Its Jacobians are

    .. math::
        F_p = \begin{pmatrix} 1 & 0 & -(y' - y)\\ 0 & 1 & x' - x\\ 0 & 0 & 1\end{pmatrix},
        \qquad
        F_w = \begin{pmatrix}
        A_L\cos\theta - B_L\sin\theta & A_R\cos\theta - B_R\sin\theta\\
        A_L\sin\theta + B_L\cos\theta & A_R\sin\theta + B_R\cos\theta\\
        -1/W & 1/W \end{pmatrix}

    with :math:`A_{L,R} = a/2 \mp \Delta s\,a'/W` and :math:`B_{L,R} = b/2 \mp \Delta s\,b'/W`
    (upper sign: left), :math:`a' = (\cos\Delta\theta - a)/\Delta\theta`,
    :math:`b' = a - b/\Delta\theta`. Below :data:`wheelkin._kernels.SERIES_THRESHOLD`
    (:math:`|\Delta\theta| < 10^{-4}`, the arc kernel's switch) :math:`a'` and :math:`b'` come
    from their series :math:`-\Delta\theta/3 + \Delta\theta^3/30` and
    :math:`1/2 - \Delta\theta^2/8 + \Delta\theta^4/144`, so a straight step is exact.

    Parameters
    ----------
    pose : array_like, shape (3,)
        (x, y, θ) before the step: m, m, rad, REP-103 (θ counter-clockwise from +x).
    delta_left, delta_right : float
        Travel of the left and right wheel in the step, m (negative: backwards).
    track_width : float
        W, the side-to-side distance between the wheels' contact lines, m (> 0).

    Returns
    -------
    StepJacobians
        ``wrt_pose`` (3, 3) and ``wrt_wheels`` (3, 2), columns (left, right).

    Examples
    --------
    A straight step of 0.1 m at heading 0 on a 0.085 m track: the heading changes by
    :math:`\pm 1/W` per metre of wheel travel, and a wheel moves the robot sideways by
    :math:`\Delta s/(2W)` per metre.

    >>> jac = step_jacobians([0.0, 0.0, 0.0], 0.1, 0.1, 0.085)
    >>> print(np.round(jac.wrt_pose, 4) + 0.0)  # + 0.0: no "-0."
    [[1.  0.  0. ]
     [0.  1.  0.1]
     [0.  0.  1. ]]
    >>> print(np.round(jac.wrt_wheels, 4))
    [[  0.5      0.5   ]
     [ -0.5882   0.5882]
     [-11.7647  11.7647]]
    """
    p = V.pose("pose", pose)
    left = _travel("delta_left", delta_left)
    right = _travel("delta_right", delta_right)
    w = V.positive("track_width", track_width)
    ds, dth = _body(left, right, w)
    _turns(dth, w)
    f_pose, f_wheels = _jacobians(p[2], ds, dth, w)
    return StepJacobians(f_pose, f_wheels)


#: The largest wheel travel of one update (m) and error variance per metre (m) accepted.
_MAX_TRAVEL, _MAX_K = 1e6, 1.0


def _wheel_noise(name: str, value) -> float:
    k = V.nonnegative(name, value)
    if k > _MAX_K:
        raise ValueError(f"{name} must be in [0, {_MAX_K:g}] m (an error variance per metre "
                         f"rolled), got {value!r}")
    return k


def _travel(name: str, value) -> float:
    travel = V.finite(name, value)
    if abs(travel) > _MAX_TRAVEL:
        raise ValueError(f"{name} must be a wheel travel in [-{_MAX_TRAVEL:g}, "
                         f"{_MAX_TRAVEL:g}] m, got {value!r}")
    return travel


def _turns(dth, track_width: float) -> None:
    if np.any(np.abs(dth) > _MAX_TRAVEL):
        raise ValueError("delta_left, delta_right and track_width give a turn of more than "
                         f"{_MAX_TRAVEL:g} rad in one update (track_width = "
                         f"{track_width!r} m): check the units")


def propagate_covariance(pose: ArrayLike, covariance: ArrayLike, delta_left: float,
                         delta_right: float, track_width: float, k_left: float,
                         k_right: float) -> PoseCovariance:
    r"""One exact-arc update of a pose and of its covariance, with random wheel errors.

    Each wheel's travel in the step has an independent, zero-mean error whose variance grows
    with the distance it rolled (the error model of :cite:t:`siegwart2011`):

    .. math::
        Q = \begin{pmatrix} k_L\,|\Delta s_L| & 0\\ 0 & k_R\,|\Delta s_R| \end{pmatrix},
        \qquad
        \Sigma' = F_p\,\Sigma\,F_p^\mathsf{T} + F_w\,Q\,F_w^\mathsf{T}

    with the Jacobians :math:`F_p, F_w` of :func:`step_jacobians` (first order: exact for
    a linear update, an approximation where the update bends the distribution). The pose
    comes from the library's arc kernel. ``k_left`` and ``k_right`` are in m (variance in m²
    per m rolled): a wheel's error after 1 m has the standard deviation :math:`\sqrt{k}`.

    Parameters
    ----------
    pose : array_like, shape (3,)
        (x, y, θ) in m, m, rad (REP-103).
    covariance : array_like, shape (3, 3)
        Covariance of the pose over (x, y, θ), symmetric, positive semi-definite.
    delta_left, delta_right : float
        Wheel travels of the step, m.
    track_width : float
        W, m (> 0).
    k_left, k_right : float
        Error variance per metre rolled of each wheel, m (>= 0).

    Returns
    -------
    PoseCovariance
        ``pose`` after the step (a Pose for a Pose, else an array (3,)) and its
        ``covariance`` (3, 3), symmetric.

    Examples
    --------
    A 1 m straight step from a certain pose with 1 mm per metre on each wheel (k = 1e-6 m):
    the distance error is the mean of the two wheels' errors, the heading error their
    difference over W.

    >>> new = propagate_covariance([0, 0, 0], np.zeros((3, 3)), 1.0, 1.0, 0.085, 1e-6, 1e-6)
    >>> print(new.pose)
    [1. 0. 0.]
    >>> print(f"{np.sqrt(new.covariance[0, 0]) * 1e3:.4f} mm, "
    ...       f"{np.sqrt(new.covariance[2, 2]) * 1e3:.3f} mrad")
    0.7071 mm, 16.638 mrad
    """
    p = V.pose("pose", pose)
    sigma = _covariance(covariance)
    left = _travel("delta_left", delta_left)
    right = _travel("delta_right", delta_right)
    w, kl, kr = _noise_model(track_width, k_left, k_right)
    ds, dth = _body(left, right, w)
    _turns(dth, w)
    f_pose, f_wheels = _jacobians(p[2], ds, dth, w)
    q = np.diag([kl * abs(left), kr * abs(right)])
    new = _covariance_step(f_pose, sigma, f_wheels @ q @ f_wheels.T)
    x, y, theta = arc_step(float(p[0]), float(p[1]), float(p[2]), ds, dth)
    after = Pose(x, y, theta) if _is_one(pose, Pose) else np.array([x, y, theta])
    return PoseCovariance(after, new)


def _noise_model(track_width, k_left, k_right) -> tuple[float, float, float]:
    """The validated track width and the two wheels' error variances per metre."""
    return (V.positive("track_width", track_width), _wheel_noise("k_left", k_left),
            _wheel_noise("k_right", k_right))


def _covariance_step(f_pose: np.ndarray, sigma: np.ndarray, noise: np.ndarray) -> np.ndarray:
    """One propagation step, F Σ Fᵀ + noise, made exactly symmetric."""
    step = f_pose @ sigma @ f_pose.T + noise
    return 0.5 * (step + step.T)


def _increment_pair(delta_left, delta_right) -> tuple[np.ndarray, np.ndarray]:
    left = V.finite_array("delta_left", delta_left)
    right = V.finite_array("delta_right", delta_right)
    if left.ndim != 1 or right.ndim != 1 or left.shape != right.shape or left.size == 0:
        raise ValueError("delta_left and delta_right must be 1-D arrays of the same length "
                         "N >= 1 (one wheel travel per update, m), got shapes "
                         f"{left.shape} and {right.shape}")
    for name, arr in (("delta_left", left), ("delta_right", right)):
        if np.any(np.abs(arr) > _MAX_TRAVEL):
            raise ValueError(f"{name} must hold wheel travels in [-{_MAX_TRAVEL:g}, "
                             f"{_MAX_TRAVEL:g}] m, got a largest of {np.abs(arr).max():g}")
    return left, right


def _path_poses(p0: np.ndarray, ds: np.ndarray, dth: np.ndarray) -> np.ndarray:
    """Poses after every update (..., N, 3) from Δs, Δθ (..., N): cumulative arc steps."""
    theta_after = p0[2] + np.cumsum(dth, axis=-1)
    theta_before = np.concatenate(
        [np.full((*dth.shape[:-1], 1), p0[2]), theta_after[..., :-1]], axis=-1)
    dx, dy, _ = arc_step(0.0, 0.0, theta_before, ds, dth)
    return np.stack([p0[0] + np.cumsum(dx, axis=-1), p0[1] + np.cumsum(dy, axis=-1),
                     theta_after], axis=-1)


def propagate_path(pose: ArrayLike, covariance: ArrayLike, delta_left: ArrayLike,
                   delta_right: ArrayLike, track_width: float, k_left: float,
                   k_right: float) -> PathCovariance:
    r"""Propagate a pose and its covariance along a sequence of wheel increments.

    :func:`propagate_covariance` applied once per update:
    :math:`\Sigma_{k+1} = F_{p,k}\Sigma_k F_{p,k}^\mathsf{T} + F_{w,k} Q_k F_{w,k}^\mathsf{T}`,
    with the poses of the exact arc update (heading not wrapped).

    On a straight run of length :math:`s` in :math:`N` equal updates of :math:`h = s/N`
    from a certain start at heading 0, this gives exactly (derived in the chapter)

    .. math::
        \sigma_\theta^2 = \frac{(k_L + k_R)\,s}{W^2},\qquad
        \sigma_y^2 = \frac{k_L + k_R}{W^2}\Big(\frac{s^3}{3} - \frac{s h^2}{12}\Big),
        \qquad \sigma_x^2 = \frac{(k_L + k_R)\,s}{4}:

    the lateral variance grows with the cube of the distance.

    Parameters
    ----------
    pose : array_like, shape (3,)
        Start pose (x, y, θ): m, m, rad.
    covariance : array_like, shape (3, 3)
        Covariance of the start pose (zeros for a known start).
    delta_left, delta_right : array_like, shape (N,)
        Wheel travel of each update, m.
    track_width : float
        W, m (> 0).
    k_left, k_right : float
        Error variance per metre rolled of each wheel, m (>= 0).

    Returns
    -------
    PathCovariance
        ``poses`` (N + 1, 3) and ``covariances`` (N + 1, 3, 3), the start first.

    Examples
    --------
    10 m straight ahead in 1000 updates, 1 mm per metre on each wheel, a 0.085 m track: the
    lateral standard deviation is :math:`\sqrt{2k s^3/(3W^2)}`, 30 cm.

    >>> h = np.full(1000, 0.01)
    >>> run = propagate_path([0, 0, 0], np.zeros((3, 3)), h, h, 0.085, 1e-6, 1e-6)
    >>> print(f"{np.sqrt(run.covariances[-1, 1, 1]):.4f} m")
    0.3038 m
    """
    p0 = V.pose("pose", pose)
    sigma = _covariance(covariance)
    left, right = _increment_pair(delta_left, delta_right)
    w, kl, kr = _noise_model(track_width, k_left, k_right)
    ds, dth = _body(left, right, w)
    _turns(dth, w)
    after = _path_poses(p0, ds, dth)
    poses = np.vstack([p0[None, :], after])
    f_pose, f_wheels = _jacobians(poses[:-1, 2], ds, dth, w)
    q = np.stack([kl * np.abs(left), kr * np.abs(right)], axis=-1)  # (N, 2) diagonals
    noise = np.einsum("nik,nk,njk->nij", f_wheels, q, f_wheels)
    out = np.empty((len(poses), 3, 3))
    out[0] = sigma
    for k in range(len(ds)):
        out[k + 1] = _covariance_step(f_pose[k], out[k], noise[k])
    return PathCovariance(poses, out)


#: Runs per block of :func:`monte_carlo_poses` (memory bound; the result does not depend on it).
_MC_BLOCK = 256


def monte_carlo_poses(pose: ArrayLike, delta_left: ArrayLike, delta_right: ArrayLike,
                      track_width: float, k_left: float, k_right: float, runs: int,
                      rng: np.random.Generator, *, at: ArrayLike | None = None) -> np.ndarray:
    r"""Poses of ``runs`` noisy repetitions of a drive: the sampled counterpart of
    :func:`propagate_path`.

    Each run integrates the wheel increments with independent errors drawn per update and
    per wheel, :math:`\Delta s_{L,k} + \sqrt{k_L|\Delta s_{L,k}|}\,z`, :math:`z \sim N(0, 1)`
    (the same model :func:`propagate_covariance` propagates), with the exact arc update of
    the library's kernel, vectorised over runs and updates (cumulative sums, as
    :func:`wheelkin.odometry.integrate`). The draws come from ``rng`` in a fixed order, so a
    seeded generator gives the same poses every time.

    Parameters
    ----------
    pose : array_like, shape (3,)
        Start pose (x, y, θ): m, m, rad (the same for every run).
    delta_left, delta_right : array_like, shape (N,)
        The nominal wheel travel of each update, m.
    track_width : float
        W, m (> 0).
    k_left, k_right : float
        Error variance per metre rolled of each wheel, m (>= 0).
    runs : int
        Number of runs (>= 1).
    rng : numpy.random.Generator
        The source of the errors, e.g. ``np.random.default_rng(7)``.
    at : array_like of int, optional
        Numbers of updates (0 .. N) after which to report the poses; default: only the end.

    Returns
    -------
    numpy.ndarray
        Shape (runs, 3), the final poses; or (len(at), runs, 3) with ``at``.

    Examples
    --------
    >>> h = np.full(100, 0.01)
    >>> ends = monte_carlo_poses([0, 0, 0], h, h, 0.085, 1e-6, 1e-6, 2000,
    ...                          np.random.default_rng(1))
    >>> ends.shape
    (2000, 3)
    >>> print(f"{ends[:, 2].std() * 1e3:.2f} mrad (propagated: "
    ...       f"{np.sqrt(2e-6 * 1.0) / 0.085 * 1e3:.2f})")
    16.67 mrad (propagated: 16.64)
    """
    p0 = V.pose("pose", pose)
    left, right = _increment_pair(delta_left, delta_right)
    w, kl, kr = _noise_model(track_width, k_left, k_right)
    if isinstance(runs, bool) or not isinstance(runs, int | np.integer) or runs < 1:
        raise ValueError(f"runs must be a whole number >= 1, got {runs!r}")
    if not isinstance(rng, np.random.Generator):
        raise TypeError("rng must be a numpy.random.Generator (np.random.default_rng(seed)), "
                        f"got {type(rng).__name__}")
    _turns(_body(left, right, w)[1] + 6.0 * np.sqrt(kl + kr) * np.sqrt(
        np.abs(left) + np.abs(right)) / w, w)
    n = left.size
    if at is None:
        steps = np.array([n])
    else:
        steps = V.finite_array("at", at)
        if steps.ndim != 1 or steps.size == 0 or np.any(steps != np.round(steps)) or np.any(
                (steps < 0) | (steps > n)):
            raise ValueError(f"at must be a 1-D list of whole numbers of updates in [0, {n}], "
                             f"got {at!r}")
        steps = steps.astype(np.int64)
    sd = np.sqrt(np.array([kl, kr]) * np.abs(np.stack([left, right], axis=-1)))  # (N, 2)
    out = np.empty((len(steps), int(runs), 3))
    for start in range(0, int(runs), _MC_BLOCK):
        count = min(_MC_BLOCK, int(runs) - start)
        z = rng.standard_normal((count, n, 2))
        noisy_left = left + sd[:, 0] * z[..., 0]
        noisy_right = right + sd[:, 1] * z[..., 1]
        ds, dth = _body(noisy_left, noisy_right, w)
        poses = _path_poses(p0, ds, dth)
        full = np.concatenate([np.broadcast_to(p0, (count, 1, 3)), poses], axis=1)
        out[:, start:start + count] = np.moveaxis(full[:, steps], 1, 0)
    return out[0] if at is None else out


def umbmark_correction(cw_end: ArrayLike, ccw_end: ArrayLike, side: float, track_width: float, *,
                       components: str = "xy") -> UmbmarkCorrection:
    r"""Borenstein and Feng's correction factors from the returns of the bidirectional square.

    UMBmark :cite:p:`borenstein1996umbmark`: the robot drives a square of side :math:`L`,
    steered by its own odometry, once clockwise (CW, right turns on the spot) and once
    counter-clockwise (CCW, left turns), several times each. At the end the true position
    is measured; the *return error* is true minus odometry,
    :math:`\varepsilon = (x_{true} - x_{odo},\; y_{true} - y_{odo})`, and its mean over the
    runs of one direction (the paper's "centre of gravity") is ``cw_end`` or ``ccw_end``.

    **The paper's conventions, and ours.** The paper calls the track "the wheelbase
    :math:`b`"; in this book the wheelbase is the front-to-back distance, so its :math:`b` is
    our track width :math:`W` (``track_width``). Its equations take :math:`x` along the
    robot's heading at the start and :math:`y` to its left (the CCW square lies on the
    :math:`+y` side): the REP-103 frame of the start pose. If the robot starts at a heading
    :math:`\theta_0` in a world frame, rotate the errors by :math:`-\theta_0` first. Two
    error types:

    - *type A*, the track: the robot turns :math:`90^\circ - \alpha` at every corner in both
      directions (:math:`\alpha > 0`: less than it believes), :math:`E_b = W_{true}/W =
      (\pi/2)/(\pi/2 - \alpha)`;
    - *type B*, unequal wheel diameters: every straight leg bends by :math:`\beta`
      (:math:`\beta > 0`: to the left), the arc of radius :math:`R = (L/2)/\sin(\beta/2)`,
      and :math:`E_d = D_R/D_L = (R + E_b W/2)/(R - E_b W/2)`.

    To first order in :math:`\alpha, \beta` the returns are
    :math:`\varepsilon_{CW} = -2L(\alpha + \beta)\,(1, 1)` and
    :math:`\varepsilon_{CCW} = 2L(\alpha - \beta)\,(-1, 1)`, so

    .. math::
        \alpha = -\frac{x_{CW} + x_{CCW}}{4L} = -\frac{y_{CW} - y_{CCW}}{4L},\qquad
        \beta = -\frac{x_{CW} - x_{CCW}}{4L} = -\frac{y_{CW} + y_{CCW}}{4L}.

    The paper states these in degrees; here they are in radians. ``components="x"`` uses
    the :math:`x` forms, ``"y"`` the :math:`y` forms, ``"xy"`` (default) their mean, the
    least-squares solution of all four equations. To apply the correction, scale the
    distance per encoder count of the left and right wheel by :math:`2/(E_d + 1)` and
    :math:`2/(1/E_d + 1)` (their mean diameter unchanged) and use the track :math:`E_b W`.

    Parameters
    ----------
    cw_end, ccw_end : array_like, shape (2,)
        Mean return errors (x, y), true minus odometry, m, in the start pose's frame.
    side : float
        L, the side of the square, m (> 0).
    track_width : float
        W assumed by the odometry during the test, m (> 0).
    components : {"xy", "x", "y"}
        Which of the paper's equations give :math:`\alpha` and :math:`\beta`.

    Returns
    -------
    UmbmarkCorrection
        ``diameter_ratio`` :math:`E_d` and ``track_ratio`` :math:`E_b`.

    Raises
    ------
    ValueError
        Bad input, or returns so large (:math:`|\alpha|` or :math:`|\beta| \ge \pi/4`, or
        :math:`W|\sin(\beta/2)| \ge L`) that the first-order model does not apply.

    Examples
    --------
    A 4 m square, a 0.34 m track; both runs return 8 cm off, CW at (-0.08, -0.08) m and CCW
    at (-0.08, 0.08) m: a pure type A error (the robot turns too little in both
    directions), the true track 0.64 % larger than assumed (E_b = 90/(90 - alpha) with
    alpha = (x_cw + x_ccw)/(-4 L) = 0.01 rad = 0.573 deg).

    >>> E_d, E_b = umbmark_correction([-0.08, -0.08], [-0.08, 0.08], 4.0, 0.34)
    >>> print(f"E_d = {E_d:.6f}, E_b = {E_b:.6f}")
    E_d = 1.000000, E_b = 1.006407
    """
    cw = V.finite_array("cw_end", cw_end)
    ccw = V.finite_array("ccw_end", ccw_end)
    for name, arr in (("cw_end", cw), ("ccw_end", ccw)):
        if arr.shape != (2,):
            raise ValueError(f"{name} must have shape (2,): the mean return error (x, y) in m, "
                             f"got shape {arr.shape}")
    length = V.positive("side", side)
    w = V.positive("track_width", track_width)
    V.choice("components", components, ("xy", "x", "y"))
    alpha_x = -(cw[0] + ccw[0]) / (4.0 * length)
    alpha_y = -(cw[1] - ccw[1]) / (4.0 * length)
    beta_x = -(cw[0] - ccw[0]) / (4.0 * length)
    beta_y = -(cw[1] + ccw[1]) / (4.0 * length)
    if components == "x":
        alpha, beta = alpha_x, beta_x
    elif components == "y":
        alpha, beta = alpha_y, beta_y
    else:
        alpha, beta = 0.5 * (alpha_x + alpha_y), 0.5 * (beta_x + beta_y)
    limit = 0.25 * math.pi
    if abs(alpha) >= limit or abs(beta) >= limit:
        raise ValueError(
            f"cw_end and ccw_end are too large for UMBmark's first-order model: alpha = "
            f"{alpha:.3g} rad, beta = {beta:.3g} rad (each must be below pi/4 in size); "
            "check the units (m) and the side of the square")
    track_ratio = (0.5 * math.pi) / (0.5 * math.pi - alpha)
    half_bend = track_ratio * w * math.sin(0.5 * beta)
    if abs(half_bend) >= length:
        raise ValueError(
            f"cw_end and ccw_end give a leg bent to a radius ({0.5 * length:.3g} m / "
            f"sin({0.5 * beta:.3g})) smaller than half the track: the first-order model "
            "does not apply")
    # E_d = (R + b/2)/(R - b/2) with R = (L/2)/sin(beta/2), multiplied through by sin(beta/2)
    diameter_ratio = (length + half_bend) / (length - half_bend)
    return UmbmarkCorrection(float(diameter_ratio), float(track_ratio))
