r"""Sandbox runs the chapters share: a vehicle driven through a twist schedule, and what its
run is compared with (the ideal path, the planned poses, its own odometry, the friction work).

- :func:`twist_schedule`: a body twist that changes linearly between set points;
- :func:`drive_twist`: one vehicle driven open loop by a twist schedule, with the sandbox's
  ideal wheel commands (:meth:`~wheelkin.sandbox.world.Robot.command_twist`) or with any other
  command law (chapter 8 passes :func:`one_model_commands`);
- :func:`ideal_path`: where the schedule takes a body that follows it exactly (an adaptive
  8th-order Runge-Kutta integration, independent of the sandbox's exact steps);
- :func:`planned_poses`: the same commands sampled once per step, each held for the step and
  integrated exactly (what :func:`drive_twist` commands, without the physics);
- :func:`encoder_odometry`: dead reckoning from a run's encoders through the one model's
  forward kinematics (:func:`wheelkin.unified.body_twist`), the exact arc per step;
- :func:`friction_work`: the work friction does on the sliding tyres of a run.

Our frame (x forward, y left, heading counter-clockwise), SI.

>>> from wheelkin.sandbox import RADON_ULZER
>>> turn = twist_schedule([0.0, 1.0], [(0.2, 0.0, 0.0), (0.2, 0.0, 1.0)])
>>> turn(0.5)
(0.2, 0.0, 0.5)
>>> run = drive_twist(RADON_ULZER, turn, 1.0, twist=(0.2, 0.0, 0.0))  # already rolling
>>> ideal = ideal_path(turn, run.t)
>>> bool(abs(run.pose - ideal).max() < 1e-6)  # it grips: it follows the ideal path
True
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from wheelkin import _validate as V
from wheelkin import frames, unified

from .vehicles import IdealCommands, VehicleSpec
from .world import Trajectory, World

__all__ = [
    "drive_twist",
    "encoder_odometry",
    "friction_work",
    "ideal_path",
    "one_model_commands",
    "planned_poses",
    "twist_schedule",
]

#: A twist schedule: time (s) -> body twist (vx m/s, vy m/s, omega rad/s).
TwistAt = Callable[[float], Any]
#: A command law: (spec, twist) -> (wheel rates in ``spec.wheel_names`` order (rad/s),
#: steering angles in ``spec.steered_names`` order (rad)).
CommandLaw = Callable[[VehicleSpec, np.ndarray], tuple[Any, Any]]


def _spec(spec: object) -> VehicleSpec:
    if not isinstance(spec, VehicleSpec):
        raise ValueError(f"spec must be a VehicleSpec, got {type(spec).__name__}")
    return spec


def _schedule(twist_at: object) -> TwistAt:
    if not callable(twist_at):
        raise ValueError(f"twist_at must be a callable t -> (vx, vy, omega), got {twist_at!r}")
    return twist_at


def _twist_value(twist_at: TwistAt, t: float) -> np.ndarray:
    """The schedule's twist at ``t``, checked: three finite numbers."""
    value = np.asarray(twist_at(t), dtype=float)
    if value.shape != (3,) or not np.all(np.isfinite(value)):
        raise ValueError(f"twist_at({float(t):g}) must give three finite numbers (vx, vy, omega), "
                         f"got {value!r}")
    return value


def _ramp_factor(t: float, ramp: float) -> float:
    """min(1, t / ramp), 1 without a ramp; no overflow for a tiny ramp."""
    return 1.0 if t >= ramp else t / ramp


def twist_schedule(times: npt.ArrayLike, twists: npt.ArrayLike) -> Callable[[float], tuple]:
    r"""A body twist interpolated linearly between set points, held before the first and
    after the last.

    Parameters
    ----------
    times : array_like, shape (M,)
        Times of the set points, s, increasing.
    twists : array_like, shape (M, 3)
        The twist :math:`(v_x, v_y, \omega)` at each time (m/s, m/s, rad/s).

    Returns
    -------
    callable
        ``t -> (vx, vy, omega)``, a tuple of three floats.

    Examples
    --------
    A start from rest over 0.5 s, then a constant 0.25 m/s:

    >>> ramp = twist_schedule([0.0, 0.5, 2.0], [(0, 0, 0), (0.25, 0, 0), (0.25, 0, 0)])
    >>> ramp(0.25), ramp(1.0), ramp(3.0)
    ((0.125, 0.0, 0.0), (0.25, 0.0, 0.0), (0.25, 0.0, 0.0))
    """
    t = V.finite_array("times", times)
    tw = V.finite_array("twists", twists)
    if t.ndim != 1 or len(t) < 1:
        raise ValueError(f"times must have shape (M,), M >= 1, got shape {t.shape}")
    if tw.shape != (len(t), 3):
        raise ValueError(f"twists must have shape ({len(t)}, 3): one (vx, vy, omega) per time, "
                         f"got shape {tw.shape}")
    if np.any(np.diff(t) <= 0):
        raise ValueError("times must be strictly increasing")
    columns = [tw[:, i].copy() for i in range(3)]

    def twist_at(when: float) -> tuple[float, float, float]:
        return tuple(float(np.interp(when, t, column)) for column in columns)  # type: ignore

    return twist_at


def one_model_commands(spec: VehicleSpec, twist: npt.ArrayLike) -> IdealCommands:
    r"""Wheel rates and steering of a body twist from the one model of chapter 8.

    :func:`wheelkin.unified.steer_for_twist` turns the steered wheels of
    ``spec.wheels_at()`` (the spec's wheels, steering 0) to roll along their contact
    velocities, and :func:`wheelkin.unified.wheel_rates` gives every driven wheel's rate. The
    sandbox's own :func:`~wheelkin.sandbox.vehicles.ideal_commands` computes the same numbers
    from a table of plain floats, for speed.

    Parameters
    ----------
    spec : VehicleSpec
    twist : array_like, shape (3,)
        :math:`(v_x, v_y, \omega)`, m/s, m/s, rad/s.

    Returns
    -------
    IdealCommands
        ``(rates, steering)``: rad/s in ``spec.wheel_names`` order; rad in
        ``spec.steered_names`` order.

    Examples
    --------
    >>> from wheelkin.sandbox import RADON_ULZER, ideal_commands
    >>> rates, steering = one_model_commands(RADON_ULZER, (0.2, 0.0, 1.0))
    >>> bool(np.allclose(rates, ideal_commands(RADON_ULZER, (0.2, 0.0, 1.0)).rates)), steering
    (True, array([], dtype=float64))
    """
    spec = _spec(spec)
    arr = V.shaped("twist", twist, (3,))
    if arr.shape != (3,):
        raise ValueError(f"twist must be one twist (vx, vy, omega), shape (3,), got shape "
                         f"{arr.shape}")
    wheels = unified.steer_for_twist(spec.wheels_at(), arr)
    steering = {wheel.name: wheel.steering for wheel in wheels}
    return IdealCommands(unified.wheel_rates(wheels, arr),
                         np.array([steering[name] for name in spec.steered_names]))


def drive_twist(
    spec: VehicleSpec,
    twist_at: TwistAt,
    duration: float,
    *,
    dt: float = 1 / 240,
    pose: npt.ArrayLike = (0.0, 0.0, 0.0),
    twist: npt.ArrayLike = (0.0, 0.0, 0.0),
    walls: Sequence = (),
    ramp: float = 0.0,
    commands: CommandLaw | None = None,
    record_every: int = 4,
) -> Trajectory:
    r"""Drive one vehicle open loop through a twist schedule; its recorded run.

    At every step of the world the vehicle is commanded the schedule's twist at the middle of
    the step (the world calls its controller at ``world.time + dt/2``), scaled by
    :math:`\min(1, t/\text{ramp})` when ``ramp`` > 0 (a smooth start).

    Parameters
    ----------
    spec : VehicleSpec
        The vehicle.
    twist_at : callable
        ``t -> (vx, vy, omega)`` (s -> m/s, m/s, rad/s), e.g. a :func:`twist_schedule`.
    duration : float
        s (>= 0).
    dt : float
        The world's step, s (default 1/240 s).
    pose, twist : array_like, shape (3,)
        Start pose (m, m, rad) and start twist (the wheels start at its rates).
    walls : sequence of ((x0, y0), (x1, y1))
        Wall segments of the world.
    ramp : float
        s (>= 0): the commanded twist grows linearly from zero over this time (0: no ramp).
    commands : callable, optional
        ``(spec, twist) -> (rates, steering)``, e.g. :func:`one_model_commands`; each distinct
        twist is computed once. Default: the robot's
        :meth:`~wheelkin.sandbox.world.Robot.command_twist` (the sandbox's ideal commands).
    record_every : int
        Record every this many steps (default 4: 60 records a second at the default step).

    Returns
    -------
    Trajectory

    Examples
    --------
    >>> from wheelkin.sandbox import MECANUM_ROBOT
    >>> strafe = drive_twist(MECANUM_ROBOT, lambda t: (0.0, 0.3, 0.0), 2.0, ramp=0.25,
    ...                      commands=one_model_commands, record_every=1)
    >>> round(float(strafe.pose[-1, 1]), 4)  # 0.3 m/s for 2 s, less half the ramp
    0.5625
    """
    spec = _spec(spec)
    twist_at = _schedule(twist_at)
    ramp = V.nonnegative("ramp", ramp)
    if commands is not None and not callable(commands):
        raise ValueError(f"commands must be a callable (spec, twist) -> (rates, steering) or "
                         f"None, got {commands!r}")
    world = World(dt=dt, walls=walls)
    robot = world.add(spec, pose=pose, twist=twist)
    cache: dict[tuple, tuple] = {}

    def controller(t: float, _world: World) -> None:
        wanted = _twist_value(twist_at, t) * _ramp_factor(t, ramp)
        if commands is None:
            robot.command_twist(*wanted)
            return
        key = tuple(wanted.round(12))
        if key not in cache:
            cache[key] = tuple(commands(spec, wanted))
        rates, steering = cache[key]
        if len(steering):
            robot.set_steering(steering)
        robot.set_wheel_rates(rates)

    out = world.run(duration, controller, record_every=record_every)
    assert isinstance(out, Trajectory)  # one robot: one trajectory
    return out


def ideal_path(twist_at: TwistAt, times: npt.ArrayLike,
               pose: npt.ArrayLike = (0.0, 0.0, 0.0)) -> np.ndarray:
    r"""The path of a body that follows a time-varying twist exactly.

    .. math:: \dot x = v_x\cos\theta - v_y\sin\theta, \quad
              \dot y = v_x\sin\theta + v_y\cos\theta, \quad \dot\theta = \omega

    integrated by scipy's DOP853 (relative tolerance 1e-13, steps of at most 0.05 s), a method
    independent of the sandbox's exact SE(2) steps.

    Parameters
    ----------
    twist_at : callable
        ``t -> (vx, vy, omega)``.
    times : array_like, shape (N,)
        Increasing times (s); the first is the start.
    pose : array_like, shape (3,)
        The pose at ``times[0]`` (default the origin).

    Returns
    -------
    numpy.ndarray, shape (N, 3)
        :math:`(x, y, \theta)` at ``times``.

    Examples
    --------
    A quarter circle of radius 1 m:

    >>> ideal_path(lambda t: (1.0, 0.0, 1.0), [0.0, math.pi / 2])[-1].round(9) + 0.0
    array([1.        , 1.        , 1.57079633])
    """
    from scipy.integrate import solve_ivp

    twist_at = _schedule(twist_at)
    t = V.finite_array("times", times)
    if t.ndim != 1 or len(t) < 2 or np.any(np.diff(t) <= 0):
        raise ValueError(f"times must be increasing, shape (N,), N >= 2, got {t!r}")
    start = V.shaped("pose", pose, (3,))
    if start.shape != (3,):
        raise ValueError(f"pose must have shape (3,), got shape {start.shape}")

    def rhs(when: float, q: np.ndarray) -> list[float]:
        vx, vy, w = twist_at(when)
        c, s = math.cos(q[2]), math.sin(q[2])
        return [c * vx - s * vy, s * vx + c * vy, w]

    sol = solve_ivp(rhs, (t[0], t[-1]), start.tolist(), method="DOP853", t_eval=t,
                    rtol=1e-13, atol=1e-14, max_step=0.05)
    return sol.y.T


def planned_poses(twist_at: TwistAt, duration: float, *, dt: float = 1 / 240,
                  ramp: float = 0.0, pose: npt.ArrayLike = (0.0, 0.0, 0.0)) -> np.ndarray:
    r"""The poses a twist schedule plans, sampled as :func:`drive_twist` commands it.

    The twist of each step is the schedule's at the step's middle (scaled by the ramp), held
    for the step: :func:`wheelkin.frames.integrate_twist` composes the exact arcs.

    Parameters
    ----------
    twist_at : callable
        ``t -> (vx, vy, omega)``.
    duration : float
        s (> 0), rounded to whole steps.
    dt : float
        The step, s (> 0).
    ramp : float
        s (>= 0), as in :func:`drive_twist`.
    pose : array_like, shape (3,)
        The start pose.

    Returns
    -------
    numpy.ndarray, shape (round(duration / dt) + 1, 3)
        :math:`(x, y, \theta)` at 0, dt, 2 dt, ... (headings wrapped).

    Examples
    --------
    >>> planned_poses(lambda t: (0.5, 0.0, 0.0), 2.0, dt=0.5)[:, 0].tolist()
    [0.0, 0.25, 0.5, 0.75, 1.0]
    """
    twist_at = _schedule(twist_at)
    duration = V.positive("duration", duration)
    dt = V.positive("dt", dt)
    ramp = V.nonnegative("ramp", ramp)
    steps = round(duration / dt)
    if not 1 <= steps <= 10**7:
        raise ValueError(f"duration / dt must give 1 to 1e7 steps, got {steps}")
    mid = (np.arange(steps) + 0.5) * dt
    twists = np.array([_twist_value(twist_at, s) * _ramp_factor(s, ramp)
                       for s in mid])
    return frames.integrate_twist(twists, dt, V.shaped("pose", pose, (3,)))


def encoder_odometry(
    spec: VehicleSpec,
    trajectory: Trajectory,
    wheels_of: Callable[[np.ndarray], Sequence[unified.WheelConstraint]] | None = None,
) -> np.ndarray:
    r"""Dead reckoning from a run's encoders through the one model's forward kinematics.

    Per recorded step, the wheel rates are the encoder increments over the step's duration
    (counts turned into radians with ``spec.steps_per_rev``); the body twist is
    :func:`wheelkin.unified.body_twist` of the wheels at the step's steering (least squares
    on the rolling rows), and :func:`wheelkin.frames.integrate_twist` composes the exact arcs
    from the run's first pose.

    Parameters
    ----------
    spec : VehicleSpec
        The vehicle of the run.
    trajectory : Trajectory
        A run recorded at a constant step (``record_every`` fixed).
    wheels_of : callable, optional
        ``steering -> wheels`` believed by the odometry (default ``spec.wheels_at``), e.g. a
        skid steer with an effective track width.

    Returns
    -------
    numpy.ndarray, shape (N, 3)
        Estimated :math:`(x, y, \theta)` at the recorded times, the heading unwrapped.

    Examples
    --------
    >>> from wheelkin.sandbox import MECANUM_ROBOT
    >>> run = drive_twist(MECANUM_ROBOT, lambda t: (0.2, 0.1, 0.5), 1.0,
    ...                   twist=(0.2, 0.1, 0.5), record_every=1)
    >>> bool(abs(encoder_odometry(MECANUM_ROBOT, run) - run.pose).max() < 1e-9)
    True
    """
    spec = _spec(spec)
    if not isinstance(trajectory, Trajectory):
        raise ValueError(f"trajectory must be a Trajectory, got {type(trajectory).__name__}")
    if wheels_of is not None and not callable(wheels_of):
        raise ValueError(f"wheels_of must be a callable steering -> wheels, got {wheels_of!r}")
    t = trajectory.t
    if len(t) < 2:
        raise ValueError("trajectory must hold at least two records")
    dt = float(t[1] - t[0])
    if not np.allclose(np.diff(t), dt, rtol=1e-9, atol=0.0):
        raise ValueError("trajectory must be recorded at a constant step")
    angles = trajectory.encoder_counts.astype(float)
    if spec.steps_per_rev is not None:
        angles = angles * (2 * math.pi / spec.steps_per_rev)
    rates = np.diff(angles, axis=0) / np.diff(t)[:, None]
    steering = trajectory.steering[1:]
    twists = np.zeros((len(rates), 3))
    for state in np.unique(steering, axis=0):
        rows = np.all(steering == state, axis=1)
        wheels = (wheels_of or spec.wheels_at)(state)
        twists[rows] = unified.body_twist(wheels, rates[rows])
    estimate = frames.integrate_twist(twists, dt, trajectory.pose[0])
    estimate[:, 2] = np.unwrap(estimate[:, 2])  # a heading, not a wrapped angle
    return estimate


def friction_work(spec: VehicleSpec, trajectory: Trajectory) -> float:
    r"""The work friction does on the sliding tyres of a run, J.

    .. math:: E = \sum_k \sum_i \mu N_i\,|v_{s,i,k}|\,\Delta t_k

    over the recorded steps :math:`k` (slip speed :math:`|v_{s,i,k}|` of wheel :math:`i`
    over the step, normal load :math:`N_i`, friction coefficient :math:`\mu` of ``spec``).
    Exact when the run is recorded at every step.

    Examples
    --------
    >>> from wheelkin.sandbox import LAB_ROBOT, MECANUM_ROBOT
    >>> spin = lambda t: (0.0, 0.0, 1.0)
    >>> friction_work(MECANUM_ROBOT, drive_twist(MECANUM_ROBOT, spin, 1.0, record_every=1))
    0.0
    >>> friction_work(LAB_ROBOT, drive_twist(LAB_ROBOT, spin, 1.0, record_every=1)) > 0.1
    True
    """
    spec = _spec(spec)
    if not isinstance(trajectory, Trajectory):
        raise ValueError(f"trajectory must be a Trajectory, got {type(trajectory).__name__}")
    loads = spec.mu * np.asarray(spec.normal_loads, dtype=float)
    if trajectory.slip_speed.shape[1] != len(loads):
        raise ValueError(f"trajectory must be a run of spec ({len(loads)} wheels), got "
                         f"{trajectory.slip_speed.shape[1]} wheels")
    power = trajectory.slip_speed[1:] @ loads
    return float(np.sum(power * np.diff(trajectory.t)))
