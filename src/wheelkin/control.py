r"""Driving to a pose: kinematic feedback controllers for a unicycle (a differential drive).

The chapter "Driving to a pose" derives every law here, its closed loop and its stability.
Each controller takes the robot's pose (or a stack of poses) and returns the body twist
:math:`(v, 0, \omega)` of a vehicle that cannot move sideways; SI units and REP-103 throughout
(x forward, y left, heading :math:`\theta` counter-clockwise from world +x).

========================= ==================================================================
law                       what it drives to zero
========================= ==================================================================
:func:`move_to_pose`      the polar coordinates :math:`(\rho, \alpha, \beta_g)` of the robot
                          seen from a goal pose (Astolfi; Siegwart et al. section 3.6.2.4;
                          Corke section 4.1.1.4)
:func:`follow_line`       the signed distance to a line and the heading error to it
                          (Samson's path-following law on a straight path)
:func:`track_trajectory`  the error to a moving reference pose in the robot's frame
                          (Kanayama et al. 1990)
========================= ==================================================================

:func:`simulate` runs any of them in closed loop on the ideal unicycle (exact arcs, the command
held over each control period) for a stack of start poses at once.

Symbols (as in ``book/notation.md``): :math:`\rho` the distance from the robot's reference
point to the goal; :math:`\alpha` the bearing of the goal from the robot's heading (the same
angle pure pursuit calls :math:`\alpha`); :math:`\beta_g = -\theta - \alpha` the direction from
which the robot approaches, measured from the goal's heading; :math:`k_\rho, k_\alpha,
k_\beta` the pose controller's gains.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Literal, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _validate as V
from wheelkin._kernels import arc_step
from wheelkin._kernels import wrap_angle as _wrap
from wheelkin.frames import Pose, Twist

__all__ = [
    "LineError",
    "PolarCoordinates",
    "TrackingError",
    "follow_line",
    "line_error",
    "move_to_pose",
    "polar_coordinates",
    "simulate",
    "strong_stability_margin",
    "track_trajectory",
    "tracking_error",
]

_HALF_PI = 0.5 * math.pi
#: The largest coordinate accepted (m): beyond it a product of a gain and a distance may
#: overflow, and no robot drives that far.
_MAX_COORDINATE = 1e9


class PolarCoordinates(NamedTuple):
    r"""The robot seen from the goal (see :func:`polar_coordinates`)."""

    #: :math:`\rho`, m: the distance from the robot's reference point to the goal.
    rho: float | np.ndarray
    #: :math:`\alpha`, rad in :math:`(-\pi, \pi]`: the bearing of the goal from the heading.
    alpha: float | np.ndarray
    #: :math:`\beta_g = -\theta - \alpha`, rad in :math:`(-\pi, \pi]`, :math:`\theta` the
    #: robot's heading in the goal's frame.
    beta: float | np.ndarray


class LineError(NamedTuple):
    r"""The robot's offset from a directed line (see :func:`line_error`)."""

    #: :math:`e_y`, m: signed distance from the line, positive on its left.
    offset: float | np.ndarray
    #: :math:`e_\theta`, rad in :math:`(-\pi, \pi]`: the heading minus the line's direction.
    heading: float | np.ndarray


class TrackingError(NamedTuple):
    r"""The reference pose seen from the robot (see :func:`tracking_error`)."""

    #: :math:`e_x`, m: the reference ahead of the robot.
    x: float | np.ndarray
    #: :math:`e_y`, m: the reference to the robot's left.
    y: float | np.ndarray
    #: :math:`e_\theta`, rad in :math:`(-\pi, \pi]`: reference heading minus robot heading.
    theta: float | np.ndarray


_out = V.scalar_or_array


def _poses(name: str, value) -> np.ndarray:
    """One pose (3,) or a stack (..., 3), finite and within the coordinate range."""
    arr = V.shaped(name, value, (3,))
    if arr.size and np.max(np.abs(arr[..., :2])) > _MAX_COORDINATE:
        raise ValueError(f"{name} must have coordinates within +-{_MAX_COORDINATE:g} m, got "
                         f"a largest of {np.max(np.abs(arr[..., :2])):g} m")
    return arr


def _one_pose(name: str, value) -> np.ndarray:
    arr = V.pose(name, value)
    if np.max(np.abs(arr[:2])) > _MAX_COORDINATE:
        raise ValueError(f"{name} must have coordinates within +-{_MAX_COORDINATE:g} m, got "
                         f"{value!r}")
    return arr


def _twist(v: np.ndarray, omega: np.ndarray) -> Twist | np.ndarray:
    """One twist as a Twist (vy = 0), a stack of them as an array (..., 3)."""
    v, omega = np.broadcast_arrays(np.asarray(v, dtype=float) + 0.0,
                                   np.asarray(omega, dtype=float) + 0.0)
    if v.ndim == 0:
        return Twist(float(v), 0.0, float(omega))
    return np.stack([v, np.zeros_like(v), omega], axis=-1)


def _in_goal_frame(poses: np.ndarray, goal: np.ndarray):
    """(x, y, theta) of ``poses`` in the frame of ``goal``; theta not wrapped."""
    c, s = math.cos(goal[2]), math.sin(goal[2])
    dx, dy = poses[..., 0] - goal[0], poses[..., 1] - goal[1]
    return c * dx + s * dy, -s * dx + c * dy, poses[..., 2] - goal[2]


def _polar(x, y, theta):
    rho = np.hypot(x, y)
    alpha = _wrap(np.arctan2(-y, -x) - theta)
    beta = _wrap(-theta - alpha)
    return rho, alpha, beta


def polar_coordinates(pose: Pose | ArrayLike, goal: Pose | ArrayLike) -> PolarCoordinates:
    r"""The robot's pose in the polar coordinates of the pose controller.

    With :math:`(x, y, \theta)` the robot's pose expressed in the goal's frame (the goal at
    the origin, heading along +x):

    .. math::
        \rho = \sqrt{x^2 + y^2},\qquad
        \alpha = \operatorname{wrap}\big(\operatorname{atan2}(-y, -x) - \theta\big),\qquad
        \beta_g = \operatorname{wrap}(-\theta - \alpha)

    :math:`\alpha` is the bearing of the goal from the robot's heading, and
    :math:`-\beta_g` the direction of the line from the robot to the goal, measured from the
    goal's heading. At the goal (:math:`\rho = 0`) the bearing is undefined; the function
    takes :math:`\operatorname{atan2}(0, 0) = 0`, so :math:`\alpha = \operatorname{wrap}(-\theta)`
    and :math:`\beta_g = 0`. Angles are wrapped to :math:`(-\pi, \pi]`.

    Parameters
    ----------
    pose : Pose or array_like, shape (3,) or (..., 3)
        The robot's pose(s) (x, y, θ) in the world: m, m, rad.
    goal : Pose or array_like, shape (3,)
        The goal pose in the world: m, m, rad.

    Returns
    -------
    PolarCoordinates
        ``rho`` (m), ``alpha``, ``beta`` (rad): floats for one pose, arrays for a stack.

    Examples
    --------
    A robot 1 m behind the goal, facing it: the goal is straight ahead.

    >>> polar_coordinates((-1.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    PolarCoordinates(rho=1.0, alpha=0.0, beta=0.0)

    The same robot 1 m to the goal's right (y = -1), still facing +x: the goal is 90° to its
    left, and it approaches from the goal's right.

    >>> rho, alpha, beta = polar_coordinates((0.0, -1.0, 0.0), (0.0, 0.0, 0.0))
    >>> print(f"{rho:.3f} m, {math.degrees(alpha):.1f}°, {math.degrees(beta):.1f}°")
    1.000 m, 90.0°, -90.0°
    """
    p = _poses("pose", pose)
    g = _one_pose("goal", goal)
    rho, alpha, beta = _polar(*_in_goal_frame(p, g))
    return PolarCoordinates(_out(rho), _out(alpha), _out(beta))


def _gains(check: Callable[[str, object], float], **gains: object) -> tuple[float, ...]:
    """The gains as floats, in the order given, each checked by ``check`` (``V.finite``,
    ``V.positive``) under its own keyword's name, which a bad value's error names."""
    return tuple(check(name, value) for name, value in gains.items())


def _pose_gains(k_rho, k_alpha, k_beta) -> tuple[float, float, float]:
    kr, ka, kb = _gains(V.finite, k_rho=k_rho, k_alpha=k_alpha, k_beta=k_beta)
    needs = "(the closed loop needs k_rho > 0, k_beta < 0, k_alpha - k_rho > 0)"
    if kr <= 0:
        raise ValueError(f"k_rho must be > 0 {needs}, got {k_rho!r}")
    if kb >= 0:
        raise ValueError(f"k_beta must be < 0 {needs}, got {k_beta!r}")
    if not ka - kr > 0:
        raise ValueError(f"k_alpha - k_rho must be > 0 {needs}, got k_alpha = {k_alpha!r}, "
                         f"k_rho = {k_rho!r}")
    return kr, ka, kb


Direction = Literal["auto", "forward", "backward"]


def move_to_pose(pose: Pose | ArrayLike, goal: Pose | ArrayLike, k_rho: float, k_alpha: float,
                 k_beta: float, *, direction: Direction = "auto",
                 stop_distance: float = 0.0) -> Twist | np.ndarray:
    r"""The pose controller of Astolfi, Siegwart et al. and Corke: a twist towards ``goal``.

    In the polar coordinates of :func:`polar_coordinates`,

    .. math::
        v = k_\rho\,\rho,\qquad \omega = k_\alpha\,\alpha + k_\beta\,\beta_g .

    With :math:`v` and :math:`\omega` from this law the closed loop is (chapter "Driving to
    a pose")

    .. math::
        \dot\rho = -k_\rho\rho\cos\alpha,\quad
        \dot\alpha = k_\rho\sin\alpha - k_\alpha\alpha - k_\beta\beta_g,\quad
        \dot\beta_g = -k_\rho\sin\alpha,

    whose linearisation at the goal has the eigenvalues :math:`-k_\rho` and the roots of
    :math:`\lambda^2 + (k_\alpha - k_\rho)\lambda - k_\rho k_\beta`: all in the left half
    plane exactly when

    .. math:: k_\rho > 0,\qquad k_\beta < 0,\qquad k_\alpha - k_\rho > 0 .

    Gains outside these conditions are refused (``ValueError`` naming them). The same
    conditions make :math:`\mathcal V = 1 - \cos\alpha - \tfrac{k_\beta}{2k_\rho}\beta_g^2`
    a Lyapunov function of the angles (:math:`\dot{\mathcal V} = -\alpha\sin\alpha\,(k_\alpha
    - k_\rho\sin\alpha/\alpha) \le 0`).

    **Driving backwards.** When the goal lies behind the robot, :math:`|\alpha| > \pi/2`, the
    robot drives backwards, as :cite:t:`siegwart2011` do: the law is applied to the robot
    turned half a turn (its rear becomes its front) approaching the goal turned half a turn,
    which gives

    .. math::
        v = -k_\rho\,\rho,\qquad
        \omega = k_\alpha\operatorname{wrap}(\alpha + \pi)
                 + k_\beta\operatorname{wrap}(\beta_g + \pi),

    and ends at the same pose, facing the goal's heading. ``direction="forward"`` or
    ``"backward"`` imposes the direction instead (a controller that decides once at the start
    and keeps it, as :cite:t:`corke2017` does, avoids switching back and forth near
    :math:`|\alpha| = \pi/2`).

    **At the goal** the bearing :math:`\alpha` is undefined, and near it a measured pose's
    noise decides it: a millimetre of noise at :math:`\rho` = 1 mm turns :math:`\alpha`
    anywhere, and the law spins the robot off its heading (the chapter measures it). Within
    ``stop_distance`` of the goal the law therefore takes :math:`\rho = 0` (as at the goal
    itself): :math:`v = 0` and :math:`\omega = -k_\alpha\operatorname{wrap}(\theta)`, a
    turn on the spot to the goal's heading. The default 0 is the law as published.

    Parameters
    ----------
    pose : Pose or array_like, shape (3,) or (..., 3)
        The robot's pose(s) (x, y, θ) in the world: m, m, rad.
    goal : Pose or array_like, shape (3,)
        The goal pose: m, m, rad.
    k_rho : float
        :math:`k_\rho`, 1/s (> 0).
    k_alpha : float
        :math:`k_\alpha`, 1/s (> k_rho).
    k_beta : float
        :math:`k_\beta`, 1/s (< 0).
    direction : {"auto", "forward", "backward"}
        "auto" (default): backwards when :math:`|\alpha| > \pi/2`, else forwards.
    stop_distance : float
        m (>= 0): within this distance of the goal, only turn to its heading (default 0).

    Returns
    -------
    Twist or ndarray
        ``Twist(v, 0, omega)`` in m/s and rad/s for one pose; an array (..., 3) of
        :math:`(v, 0, \omega)` for a stack.

    Examples
    --------
    Corke's gains :math:`(k_\rho, k_\alpha, k_\beta) = (3, 8, -3)`; the robot 1 m behind
    the goal and facing it drives straight at it:

    >>> move_to_pose((-1.0, 0.0, 0.0), (0.0, 0.0, 0.0), 3.0, 8.0, -3.0)
    Twist(vx=3.0, vy=0.0, omega=0.0)

    The goal behind the robot: it backs up.

    >>> move_to_pose((1.0, 0.0, 0.0), (0.0, 0.0, 0.0), 3.0, 8.0, -3.0)
    Twist(vx=-3.0, vy=0.0, omega=0.0)

    >>> move_to_pose((0, 0, 0), (1, 0, 0), 1.0, 0.5, -1.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: k_alpha - k_rho must be > 0 (...), got k_alpha = 0.5, k_rho = 1.0
    """
    p = _poses("pose", pose)
    g = _one_pose("goal", goal)
    kr, ka, kb = _pose_gains(k_rho, k_alpha, k_beta)
    V.choice("direction", direction, ("auto", "forward", "backward"))
    stop = V.nonnegative("stop_distance", stop_distance)
    x, y, theta = _in_goal_frame(p, g)
    rho, alpha, beta = _polar(x, y, theta)
    near = rho < stop
    if direction == "auto":
        back = (np.abs(alpha) > _HALF_PI) & ~near
    else:
        back = np.full(np.shape(alpha), direction == "backward") & ~near
    alpha = np.where(near, _wrap(-theta), np.where(back, _wrap(alpha + math.pi), alpha))
    beta = np.where(near, 0.0, np.where(back, _wrap(beta + math.pi), beta))
    with np.errstate(all="ignore"):
        v = np.where(near, 0.0, np.where(back, -kr * rho, kr * rho))
        omega = ka * alpha + kb * beta
    V.finite_result("k_rho, k_alpha, k_beta", v, omega)
    return _twist(v, omega)


def strong_stability_margin(k_rho: float, k_alpha: float, k_beta: float) -> float:
    r"""Siegwart et al.'s margin for the strong stability of the pose controller.

    .. math:: m = k_\alpha + \tfrac{5}{3}\,k_\beta - \tfrac{2}{\pi}\,k_\rho

    :cite:t:`siegwart2011` (section 3.6.2.4) state that with :math:`k_\rho > 0`,
    :math:`k_\beta < 0` and :math:`m > 0` the robot that starts facing the goal
    (:math:`|\alpha| \le \pi/2`) keeps facing it, so it never has to reverse its direction
    of travel. As stated it is not sufficient: at :math:`|\alpha| = \pi/2` the bearing's
    rate points inwards for every :math:`\beta_g \in (-\pi, \pi]` only if
    :math:`k_\alpha + 2k_\beta - \tfrac{2}{\pi}k_\rho > 0` (the factor 5/3 covers
    :math:`|\beta_g| \le 5\pi/6` only). The chapter derives that condition and drives, on a
    grid of starts, gains such as (3, 7.5, -3) that meet Siegwart's margin and still turn
    some starts away. This function reports Siegwart's margin as published.

    Parameters
    ----------
    k_rho, k_alpha, k_beta : float
        The gains of :func:`move_to_pose`, 1/s (any finite values: the margin is reported,
        not enforced).

    Returns
    -------
    float
        :math:`m`, 1/s (> 0: the condition holds).

    Examples
    --------
    Corke's gains (3, 8, -3) and Siegwart's example (3, 8, -1.5) both satisfy it:

    >>> print(f"{strong_stability_margin(3, 8, -3):.3f} {strong_stability_margin(3, 8, -1.5):.3f}")
    1.090 3.590
    """
    kr, ka, kb = _gains(V.finite, k_rho=k_rho, k_alpha=k_alpha, k_beta=k_beta)
    with np.errstate(all="ignore"):
        margin = ka + 5.0 / 3.0 * kb - 2.0 / math.pi * kr
    return float(V.finite_result("k_rho, k_alpha, k_beta", margin))


def _line(line_point, line_heading) -> tuple[np.ndarray, float]:
    point = V.finite_array("line_point", line_point)
    if point.shape != (2,):
        raise ValueError(f"line_point must have shape (2,): a point (x, y) of the line, m, got "
                         f"shape {point.shape}")
    if np.max(np.abs(point)) > _MAX_COORDINATE:
        raise ValueError(f"line_point must be within +-{_MAX_COORDINATE:g} m, got "
                         f"{line_point!r}")
    return point, V.finite("line_heading", line_heading)


def _line_error(p: np.ndarray, point: np.ndarray, heading: float):
    c, s = math.cos(heading), math.sin(heading)
    dx, dy = p[..., 0] - point[0], p[..., 1] - point[1]
    return -s * dx + c * dy, _wrap(p[..., 2] - heading)


def line_error(pose: Pose | ArrayLike, line_point: ArrayLike, line_heading: float) -> LineError:
    r"""The signed offset of the robot from a directed line, and its heading error.

    The line passes through :math:`(x_l, y_l)` in the direction :math:`\theta_l`:

    .. math::
        e_y = -(x - x_l)\sin\theta_l + (y - y_l)\cos\theta_l,\qquad
        e_\theta = \operatorname{wrap}(\theta - \theta_l)

    (:math:`e_y > 0`: the robot is on the line's left, REP-103).

    Parameters
    ----------
    pose : Pose or array_like, shape (3,) or (..., 3)
        The robot's pose(s): m, m, rad.
    line_point : array_like, shape (2,)
        A point of the line, m.
    line_heading : float
        The line's direction, rad counter-clockwise from world +x.

    Returns
    -------
    LineError
        ``offset`` :math:`e_y` (m) and ``heading`` :math:`e_\theta` (rad).

    Examples
    --------
    >>> line_error((2.0, 0.5, 0.1), (0.0, 0.0), 0.0)
    LineError(offset=0.5, heading=0.1)
    """
    p = _poses("pose", pose)
    point, heading = _line(line_point, line_heading)
    e_y, e_theta = _line_error(p, point, heading)
    return LineError(_out(e_y + 0.0), _out(e_theta))


def _sinc(x):
    """sin(x)/x, 1 at 0."""
    x = np.asarray(x, dtype=float)
    small = np.abs(x) < 1e-4
    safe = np.where(small, 1.0, x)
    return np.where(small, 1.0 - x * x / 6.0, np.sin(safe) / safe)


def follow_line(pose: Pose | ArrayLike, line_point: ArrayLike, line_heading: float,
                speed: float, k_offset: float, k_heading: float) -> Twist | np.ndarray:
    r"""Follow a directed line at a constant speed: Samson's path-following law on a line.

    With the offset :math:`e_y` and heading error :math:`e_\theta` of :func:`line_error`,

    .. math::
        v = v_d,\qquad
        \omega = -k_y\,v_d\,e_y\,\frac{\sin e_\theta}{e_\theta} - k_\theta\,|v_d|\,e_\theta .

    The closed loop :math:`\dot e_y = v_d\sin e_\theta`, :math:`\dot e_\theta = \omega` has the
    Lyapunov function :math:`V = \tfrac12 k_y e_y^2 + \tfrac12 e_\theta^2` with
    :math:`\dot V = -k_\theta|v_d|\,e_\theta^2 \le 0`: every start with
    :math:`|e_\theta| < \pi` converges to the line (for :math:`v_d \ne 0`, forwards or
    backwards). Linearised, the offset obeys :math:`e_y'' + k_\theta e_y' + k_y e_y = 0` in
    the distance :math:`s` travelled, whatever the speed: the path the robot draws does not
    depend on :math:`v_d`. Critical damping is :math:`k_\theta = 2\sqrt{k_y}`.

    Parameters
    ----------
    pose : Pose or array_like, shape (3,) or (..., 3)
        The robot's pose(s): m, m, rad.
    line_point : array_like, shape (2,)
        A point of the line, m.
    line_heading : float
        The line's direction, rad.
    speed : float
        :math:`v_d`, m/s (negative: along the line backwards, the robot's rear first).
    k_offset : float
        :math:`k_y`, 1/m² (> 0).
    k_heading : float
        :math:`k_\theta`, 1/m (> 0).

    Returns
    -------
    Twist or ndarray
        ``Twist(v_d, 0, omega)`` for one pose, an array (..., 3) for a stack.

    Examples
    --------
    On the line, along it: straight on. Half a metre to its left: turn right.

    >>> follow_line((0.0, 0.0, 0.0), (0.0, 0.0), 0.0, 0.3, 4.0, 4.0)
    Twist(vx=0.3, vy=0.0, omega=0.0)
    >>> follow_line((0.0, 0.5, 0.0), (0.0, 0.0), 0.0, 0.3, 4.0, 4.0).omega
    -0.6
    """
    p = _poses("pose", pose)
    point, heading = _line(line_point, line_heading)
    v = V.finite("speed", speed)
    if abs(v) > 1e3:
        raise ValueError(f"speed must be within [-1000, 1000] m/s, got {speed!r}")
    ky, kt = _gains(V.positive, k_offset=k_offset, k_heading=k_heading)
    e_y, e_theta = _line_error(p, point, heading)
    with np.errstate(all="ignore"):
        omega = -ky * v * e_y * _sinc(e_theta) - kt * abs(v) * e_theta
    V.finite_result("k_offset, k_heading", omega)
    return _twist(np.full(np.shape(omega), v), omega)


def _tracking_error(p: np.ndarray, ref: np.ndarray):
    c, s = np.cos(p[..., 2]), np.sin(p[..., 2])
    dx, dy = ref[..., 0] - p[..., 0], ref[..., 1] - p[..., 1]
    return c * dx + s * dy, -s * dx + c * dy, _wrap(ref[..., 2] - p[..., 2])


def tracking_error(pose: Pose | ArrayLike, reference: Pose | ArrayLike) -> TrackingError:
    r"""The reference pose seen from the robot: Kanayama's error.

    .. math::
        \begin{pmatrix} e_x\\ e_y \end{pmatrix} =
        \begin{pmatrix} \cos\theta & \sin\theta\\ -\sin\theta & \cos\theta \end{pmatrix}
        \begin{pmatrix} x_r - x\\ y_r - y \end{pmatrix},\qquad
        e_\theta = \operatorname{wrap}(\theta_r - \theta)

    Parameters
    ----------
    pose : Pose or array_like, shape (3,) or (..., 3)
        The robot's pose(s): m, m, rad.
    reference : Pose or array_like, shape (3,) or (..., 3)
        The reference pose(s), broadcast with ``pose``: m, m, rad.

    Returns
    -------
    TrackingError
        ``x``, ``y`` (m, in the robot's frame) and ``theta`` (rad).

    Examples
    --------
    >>> e = tracking_error((0.0, 0.0, math.pi / 2), (0.0, 1.0, math.pi / 2))
    >>> print(f"{e.x:.3f} {e.y:.3f} {e.theta:.3f}")  # 1 m straight ahead
    1.000 0.000 0.000
    """
    p = _poses("pose", pose)
    r = _poses("reference", reference)
    p, r = V.broadcast(pose=p, reference=r)
    e_x, e_y, e_theta = _tracking_error(p, r)
    return TrackingError(_out(e_x + 0.0), _out(e_y + 0.0), _out(e_theta))


def track_trajectory(pose: Pose | ArrayLike, reference: Pose | ArrayLike,
                     reference_twist: Twist | ArrayLike, k_x: float, k_y: float,
                     k_theta: float) -> Twist | np.ndarray:
    r"""Kanayama's trajectory-tracking controller: follow a moving reference pose.

    With the error :math:`(e_x, e_y, e_\theta)` of :func:`tracking_error` and the reference's
    own speed and yaw rate :math:`(v_r, \omega_r)` :cite:p:`kanayama1990`,

    .. math::
        v = v_r\cos e_\theta + k_x e_x,\qquad
        \omega = \omega_r + v_r\,(k_y e_y + k_\theta\sin e_\theta).

    The error then obeys :math:`\dot e_x = \omega e_y - v + v_r\cos e_\theta`,
    :math:`\dot e_y = -\omega e_x + v_r\sin e_\theta`, :math:`\dot e_\theta = \omega_r - \omega`,
    and :math:`V = \tfrac12(e_x^2 + e_y^2) + (1 - \cos e_\theta)/k_y` decreases,
    :math:`\dot V = -k_x e_x^2 - v_r k_\theta\sin^2 e_\theta/k_y \le 0`, for a reference that
    drives forwards (:math:`v_r \ge 0`). Linearised about a straight reference
    (:math:`\omega_r = 0`) the eigenvalues are :math:`-k_x` and the roots of
    :math:`\lambda^2 + v_r k_\theta\lambda + v_r^2 k_y`: critically damped at
    :math:`k_\theta = 2\sqrt{k_y}`. A reference driven backwards (:math:`v_r < 0`) loses the
    guarantee (:math:`\dot V` can be positive).

    Parameters
    ----------
    pose : Pose or array_like, shape (3,) or (..., 3)
        The robot's pose(s): m, m, rad.
    reference : Pose or array_like, shape (3,) or (..., 3)
        The reference pose(s) at the same time: m, m, rad.
    reference_twist : Twist or array_like, shape (3,) or (..., 3)
        The reference's twist :math:`(v_r, 0, \omega_r)`: m/s, m/s, rad/s (its ``vy`` must
        be 0: a unicycle's reference).
    k_x : float
        1/s (> 0).
    k_y : float
        1/m² (> 0).
    k_theta : float
        1/m (> 0).

    Returns
    -------
    Twist or ndarray
        ``Twist(v, 0, omega)`` for one pose, an array (..., 3) for a stack.

    Examples
    --------
    On the reference: the reference's own twist.

    >>> track_trajectory((1, 2, 0.5), (1, 2, 0.5), (0.2, 0.0, 0.4), 1.0, 25.0, 10.0)
    Twist(vx=0.2, vy=0.0, omega=0.4)
    >>> track_trajectory((0, 0, 0), (0.1, 0.0, 0.0), (0.2, 0.0, 0.0), 1.0, 25.0, 10.0)
    Twist(vx=0.30000000000000004, vy=0.0, omega=0.0)
    """
    p = _poses("pose", pose)
    r = _poses("reference", reference)
    tw = V.shaped("reference_twist", reference_twist, (3,))
    if np.any(tw[..., 1] != 0.0):
        raise ValueError("reference_twist must have vy = 0 (a unicycle's reference "
                         f"(v_r, 0, omega_r)), got {reference_twist!r}")
    if np.max(np.abs(tw[..., [0, 2]]), initial=0.0) > 1e3:
        raise ValueError("reference_twist must have |v_r| <= 1000 m/s and |omega_r| <= 1000 "
                         f"rad/s, got {reference_twist!r}")
    kx, ky, kt = _gains(V.positive, k_x=k_x, k_y=k_y, k_theta=k_theta)
    p, r, tw = V.broadcast(pose=p, reference=r, reference_twist=tw)
    e_x, e_y, e_theta = _tracking_error(p, r)
    v_r, w_r = tw[..., 0], tw[..., 2]
    with np.errstate(all="ignore"):
        v = v_r * np.cos(e_theta) + kx * e_x
        omega = w_r + v_r * (ky * e_y + kt * np.sin(e_theta))
    V.finite_result("k_x, k_y, k_theta", v, omega)
    return _twist(v, omega)


def simulate(law: Callable[[float, np.ndarray], ArrayLike], start: ArrayLike, duration: float,
             period: float, *, max_speed: float | None = None,
             max_yaw_rate: float | None = None) -> NDArray[np.float64]:
    r"""Run a feedback law in closed loop on the ideal unicycle, for many starts at once.

    Every ``period`` the law is asked for a twist at the current poses; the twist is held
    over the period and the poses move along its exact arc (:math:`x' = x + v\,T(a\cos\theta
    - b\sin\theta)`, ..., with :math:`a, b` the arc factors of :math:`\omega T`, the
    library's arc kernel): a sampled controller on a robot that does exactly what it is told.
    Optional limits scale :math:`v` and :math:`\omega` *together* (the curvature
    :math:`\omega/v` is kept, so the robot drives the same path, slower).

    Parameters
    ----------
    law : callable (t, poses) -> twists
        ``t`` in s; ``poses`` an array (N, 3); returns twists (N, 3) (or a Twist for N = 1)
        whose ``vy`` is ignored (a unicycle).
    start : array_like, shape (3,) or (N, 3)
        Start pose(s): m, m, rad.
    duration : float
        s (> 0, at most 1e6 periods).
    period : float
        The control period T, s (> 0).
    max_speed, max_yaw_rate : float, optional
        Limits on :math:`|v|` (m/s) and :math:`|\omega|` (rad/s), > 0.

    Returns
    -------
    ndarray
        Poses, shape (K + 1, N, 3) for K periods (the start first; heading not wrapped), or
        (K + 1, 3) for one start.

    Examples
    --------
    A robot told to drive at 0.5 m/s for 2 s in 0.1 s periods ends 1 m ahead:

    >>> path = simulate(lambda t, p: np.tile([0.5, 0.0, 0.0], (len(p), 1)),
    ...                 (0.0, 0.0, 0.0), 2.0, 0.1)
    >>> path.shape, path[-1].round(12).tolist()
    ((21, 3), [1.0, 0.0, 0.0])
    """
    if not callable(law):
        raise ValueError(f"law must be callable (t, poses) -> twists, got {law!r}")
    p0 = _poses("start", start)
    one = p0.ndim == 1
    poses = np.atleast_2d(p0).astype(float)
    if poses.ndim != 2:
        raise ValueError(f"start must have shape (3,) or (N, 3), got shape {p0.shape}")
    T = V.positive("period", period)
    total = V.positive("duration", duration)
    steps = math.ceil(total / T - 1e-9)
    if steps > 1_000_000:
        raise ValueError(f"duration / period must be at most 1e6 periods, got {steps}")
    vmax = None if max_speed is None else V.positive("max_speed", max_speed)
    wmax = None if max_yaw_rate is None else V.positive("max_yaw_rate", max_yaw_rate)
    out = np.empty((steps + 1, len(poses), 3))
    out[0] = poses
    for k in range(steps):
        raw = np.asarray(law(k * T, poses.copy()), dtype=float)
        twist = np.broadcast_to(raw, poses.shape) if raw.shape == (3,) else raw
        if twist.shape != poses.shape or not np.all(np.isfinite(twist)):
            raise ValueError(f"law must return finite twists of shape {poses.shape}, got "
                             f"shape {raw.shape}")
        v, w = twist[:, 0], twist[:, 2]
        scale = np.ones_like(v)
        if vmax is not None:
            scale = np.minimum(scale, vmax / np.maximum(np.abs(v), 1e-300))
        if wmax is not None:
            scale = np.minimum(scale, wmax / np.maximum(np.abs(w), 1e-300))
        v, w = v * scale, w * scale
        x, y, th = arc_step(poses[:, 0], poses[:, 1], poses[:, 2], v * T, w * T)
        poses = np.stack([x, y, th], axis=-1)
        out[k + 1] = poses
    return out[:, 0] if one else out
