r"""Controllers for the waypoint lab: a path follower and the controllers that drive a robot.

Apart from the vehicles they drive (as the Robotics Toolbox keeps its drivers apart from its
vehicles): the lab's data, path plan and schedule are in :mod:`wheelkin.waypoints`; here are

- :class:`PathFollower`: pure pursuit along straights and arcs, heading control for turns in
  place; it maps a pose estimate to a body twist :math:`(v, \omega)` (a :class:`BodyCommand`).
- :class:`ScheduleController`: plays an open-loop schedule (:func:`wheelkin.waypoints.schedule`).
- :class:`FollowerController`: dead reckoning from the encoders with the exact arc, feeding a
  :class:`PathFollower`, the differential drive's inverse kinematics and a wheel-rate cap.
- :class:`SideDrivenRobot`: the :class:`typing.Protocol` of the robot both controllers drive
  (a sandbox robot of ``wheelkin.sandbox``, or :class:`KinematicSkidSteer`).
- :class:`KinematicSkidSteer`: a reduced model of a skid steer, fast enough for a live panel.

Everything is SI and REP-103: metres, seconds, radians, x forward, y left, headings
counter-clockwise. Wheel order FL, FR, RL, RR; the left side is the wheels at y > 0.

>>> from wheelkin.waypoints import plan_segments
>>> segments = plan_segments([[0, 0], [1, 0]])
>>> robot = KinematicSkidSteer(segments[0].start, skid_factor=1.0, motor_time_constant=0.0)
>>> ctrl = FollowerController(robot, PathFollower(segments, speed=0.2), wheel_radius=0.04,
...                           track_width=0.12, period=0.05)
>>> for k in range(200):
...     ctrl(k * 0.05)
...     robot.step(0.05)
>>> x, y, theta = robot.pose
>>> ctrl.follower.done, round(x, 2), round(y, 6)
(True, 1.0, 0.0)
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import NamedTuple, Protocol, cast, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from wheelkin import _validate as V
from wheelkin._kernels import arc_step, diff_drive_wheel_speeds, wrap_angle
from wheelkin.diffdrive import BodyTwist
from wheelkin.frames import Pose, Twist
from wheelkin.waypoints import (
    LAB_HALF_AXLE,
    LAB_HALF_WHEELBASE,
    LAB_WHEEL_RADIUS,
    Segment,
    WheelCommand,
    planned_wheel_angles,
    schedule_times,
    validate_commands,
    validate_segments,
)

__all__ = [
    "BodyCommand",
    "DrivenWheel",
    "FollowerController",
    "KinematicSkidSteer",
    "PathFollower",
    "ScheduleController",
    "SideDrivenRobot",
    "SideRates",
    "WheelLayout",
]


class BodyCommand(NamedTuple):
    """A body twist of a differential drive: forward speed (m/s) and yaw rate (rad/s,
    counter-clockwise positive).

    The command a follower sends, in the words of the lab it follows; the same two numbers
    as :class:`wheelkin.diffdrive.BodyTwist` (a differential drive has no sideways speed, so
    not a three-component :class:`~wheelkin.frames.Twist`). :meth:`to_twist` and
    :meth:`from_twist` convert.

    >>> BodyCommand(0.3, -0.5).to_twist()
    Twist(vx=0.3, vy=0.0, omega=-0.5)
    >>> BodyCommand.from_twist(Twist(0.3, 0.0, -0.5))
    BodyCommand(speed=0.3, yaw_rate=-0.5)
    """

    speed: float
    yaw_rate: float

    def to_twist(self) -> Twist:
        """The :class:`~wheelkin.frames.Twist` ``(speed, 0, yaw_rate)``."""
        return Twist(self.speed, 0.0, self.yaw_rate)

    @classmethod
    def from_twist(cls, twist: Twist | tuple[float, float, float]) -> BodyCommand:
        """The command of a twist whose ``vy`` is zero (a ValueError naming ``twist``
        otherwise)."""
        speed, yaw_rate = BodyTwist.from_twist(Twist(*V.twist("twist", twist).tolist()))
        return cls(float(speed), float(yaw_rate))


class SideRates(NamedTuple):
    """Wheel rates (rad/s) of the left wheels and of the right wheels; positive rolls forward."""

    left: float
    right: float


@dataclass(frozen=True)
class DrivenWheel:
    """A driven wheel's name and contact point ``position`` (x, y) in the body frame (m)."""

    name: str
    position: tuple[float, float]

    def __post_init__(self) -> None:
        if not isinstance(self.name, str):
            raise TypeError(f"name must be a str, got {type(self.name).__name__}")
        p = V.shaped("position", self.position, (2,))
        if p.ndim != 1:
            raise ValueError(f"position must have shape (2,), got shape {p.shape}")
        object.__setattr__(self, "position", (float(p[0]), float(p[1])))


@dataclass(frozen=True)
class WheelLayout:
    """The driven wheels of a robot, in the order of its encoder readings."""

    driven_wheels: tuple[DrivenWheel, ...]

    def __post_init__(self) -> None:
        try:
            wheels = tuple(self.driven_wheels)
        except TypeError:
            raise TypeError("driven_wheels must be a non-empty sequence of DrivenWheel, got "
                            f"{self.driven_wheels!r}") from None
        if not wheels or not all(isinstance(w, DrivenWheel) for w in wheels):
            raise TypeError("driven_wheels must be a non-empty sequence of DrivenWheel")
        object.__setattr__(self, "driven_wheels", wheels)


class _WheelLike(Protocol):
    @property
    def position(self) -> Sequence[float]: ...


class _LayoutLike(Protocol):
    @property
    def driven_wheels(self) -> Sequence[_WheelLike]: ...


@runtime_checkable
class SideDrivenRobot(Protocol):
    """The robot the controllers drive: a skid steer or differential drive whose left wheels
    and right wheels are commanded as two sides.

    A sandbox robot (``wheelkin.sandbox.World.add``) and :class:`KinematicSkidSteer` both
    are one.
    """

    @property
    def spec(self) -> _LayoutLike:
        """Has ``driven_wheels``, each with a ``position`` (x, y) in m; y > 0 is the left."""
        ...

    @property
    def encoder_angles(self) -> np.ndarray:
        """The driven wheels' encoder readings as wheel angles (rad), in ``driven_wheels``
        order."""
        ...

    def set_side_rates(self, left: float, right: float) -> None:
        """Hold the left wheels at ``left`` and the right wheels at ``right`` (rad/s)."""
        ...


def _pose3(name: str, pose: ArrayLike) -> Pose:
    if isinstance(pose, Pose):
        return pose
    return Pose(*V.pose(name, pose).tolist())


class PathFollower:
    r"""A feedback follower for a plan: pure pursuit on straights and arcs, turns on heading.

    Given a pose estimate, :meth:`command` returns the body twist (v, omega) to drive the
    current segment, and moves on when the segment is done:

    - straight or arc: the progress s along the segment is the projection of the position on
      it; the goal point ("carrot") lies ``lookahead`` ahead of it on the segment (beyond the
      end, on the end tangent). In the robot's frame the carrot is at (c_x, c_y), and pure
      pursuit drives the circle through it, :math:`\kappa = 2 c_y / (c_x^2 + c_y^2)`,
      :math:`\omega = v\kappa` :cite:p:`corke2017`. If the carrot is behind the robot, it
      first turns in place toward it. Before a turn in place and at the goal, the speed falls
      as ``approach_gain`` times the distance left (never below ``min_speed``), so the robot
      stops on the waypoint. The segment is done when s reaches its length.
    - turn in place: :math:`\omega = \mathrm{clip}(k_\theta e, \pm\omega_{max})` on the
      heading error e (wrapped), at least ``min_turn_rate`` in size; done when
      :math:`|e|` < ``heading_tolerance``.

    Parameters
    ----------
    segments : list of Segment
        From :func:`wheelkin.waypoints.plan_segments`.
    speed : float
        Cruising speed v (m/s), > 0.
    lookahead : float
        Distance of the carrot ahead of the projection (m), > 0.
    heading_gain : float
        :math:`k_\theta` (1/s), > 0, for turns in place.
    max_turn_rate : float
        :math:`\omega_{max}` (rad/s), > 0.
    min_turn_rate : float
        Smallest commanded turn rate in a turn in place (rad/s), >= 0.
    heading_tolerance : float
        (rad), > 0.
    approach_gain : float
        (1/s), > 0.
    min_speed : float
        (m/s), > 0, at most ``speed``.

    Examples
    --------
    On the line, facing along it, the follower drives straight at cruising speed:

    >>> from wheelkin.waypoints import plan_segments
    >>> f = PathFollower(plan_segments([[0, 0], [1, 0], [1, 1]], arc_radius=None), speed=0.2)
    >>> f.command((0.0, 0.0, 0.0))
    BodyCommand(speed=0.2, yaw_rate=0.0)
    >>> tuple(f.command((1.0, 0.0, 0.0)))  # at P1: the straight is done, turn left in place
    (0.0, 2.0)
    >>> f.index, f.done
    (1, False)
    """

    def __init__(self, segments: Segment | Iterable[Segment], *, speed: float = 0.3,
                 lookahead: float = 0.15, heading_gain: float = 4.0, max_turn_rate: float = 2.0,
                 min_turn_rate: float = 0.2, heading_tolerance: float = 0.01,
                 approach_gain: float = 2.0, min_speed: float = 0.02) -> None:
        self.segments = validate_segments(segments)
        self.speed = V.positive("speed", speed)
        self.lookahead = V.positive("lookahead", lookahead)
        self.heading_gain = V.positive("heading_gain", heading_gain)
        self.max_turn_rate = V.positive("max_turn_rate", max_turn_rate)
        self.min_turn_rate = V.in_range("min_turn_rate", min_turn_rate, 0.0, self.max_turn_rate)
        self.heading_tolerance = V.positive("heading_tolerance", heading_tolerance)
        self.approach_gain = V.positive("approach_gain", approach_gain)
        self.min_speed = V.in_range("min_speed", min_speed, 0.0, self.speed)
        if self.min_speed <= 0:
            raise ValueError(f"min_speed must be in (0, {self.speed:g}], got {min_speed!r}")
        self.index = 0

    def reset(self) -> None:
        """Start again at the first segment."""
        self.index = 0

    @property
    def done(self) -> bool:
        """True once the last segment is done."""
        return self.index >= len(self.segments)

    def progress(self, pose: ArrayLike) -> float:
        """Arc length (m) along the current straight or arc of the projection of ``pose``
        (0 for a turn in place or once the plan is done)."""
        x, y, _ = _pose3("pose", pose)
        return 0.0 if self.done else self._progress(self.segments[self.index], x, y)

    @staticmethod
    def _progress(seg: Segment, x: float, y: float) -> float:
        x0, y0, t0 = seg.start
        if seg.kind == "straight":
            return (x - x0) * math.cos(t0) + (y - y0) * math.sin(t0)
        if seg.kind == "arc":
            cx, cy = cast(tuple[float, float], seg.centre)  # an arc has one
            swept = math.remainder(math.atan2(y - cy, x - cx) - math.atan2(y0 - cy, x0 - cx),
                                   2 * math.pi)  # in [-pi, pi]
            return swept * math.copysign(1.0, seg.heading_change) * abs(seg.radius)
        return 0.0

    def _turn(self, error: float) -> float:
        rate = min(self.max_turn_rate, max(self.min_turn_rate, self.heading_gain * abs(error)))
        return math.copysign(rate, error)

    def _carrot(self, seg: Segment, s: float) -> tuple[float, float]:
        sc = max(s, 0.0) + self.lookahead
        if sc <= seg.length:
            px, py = seg.point_at(sc / seg.length).tolist()
            return px, py
        xe, ye, te = seg.end
        extra = sc - seg.length
        return xe + extra * math.cos(te), ye + extra * math.sin(te)

    def command(self, pose: ArrayLike) -> BodyCommand:
        """Body twist (v in m/s, omega in rad/s) for the pose estimate (x, y, theta), as a
        :class:`BodyCommand` (it unpacks as ``v, omega = follower.command(pose)``)."""
        x, y, theta = _pose3("pose", pose)
        while not self.done:
            seg = self.segments[self.index]
            if seg.kind == "turn":
                error = wrap_angle(seg.end[2] - theta)
                if abs(error) < self.heading_tolerance:
                    self.index += 1
                    continue
                return BodyCommand(0.0, self._turn(error))
            s = self._progress(seg, x, y)
            if s >= seg.length:
                self.index += 1
                continue
            cx, cy = self._carrot(seg, s)
            c, sn = math.cos(theta), math.sin(theta)
            ahead = c * (cx - x) + sn * (cy - y)
            left = -sn * (cx - x) + c * (cy - y)
            if ahead <= 0:
                return BodyCommand(0.0, self._turn(math.atan2(left, ahead)))
            last = self.index + 1 >= len(self.segments)
            speed = self.speed
            if last or self.segments[self.index + 1].kind == "turn":
                speed = min(speed, max(self.min_speed, self.approach_gain * (seg.length - s)))
            curvature = 2.0 * left / (ahead * ahead + left * left)
            return BodyCommand(float(speed), float(speed * curvature))
        return BodyCommand(0.0, 0.0)


# --------------------------------------------------------------------------------------------
# controllers of a side-driven robot


class _Sides:
    """Which of a robot's driven wheels are on the left (y > 0) and on the right."""

    def __init__(self, robot: SideDrivenRobot) -> None:
        if not isinstance(robot, SideDrivenRobot):
            raise TypeError("robot must be a SideDrivenRobot (spec.driven_wheels, "
                            f"encoder_angles, set_side_rates), got {type(robot).__name__}")
        ys = [float(w.position[1]) for w in robot.spec.driven_wheels]
        self.left = [i for i, y in enumerate(ys) if y > 0]
        self.right = [i for i, y in enumerate(ys) if y < 0]
        if not self.left or not self.right:
            raise ValueError("robot must have driven wheels on both sides (y > 0 and y < 0)")

    def means(self, angles: ArrayLike) -> tuple[float, float]:
        """Mean angle (rad) of the left wheels and of the right wheels."""
        a = np.asarray(angles, dtype=float).tolist()
        return (sum(a[i] for i in self.left) / len(self.left),
                sum(a[i] for i in self.right) / len(self.right))


class ScheduleController:
    r"""Play an open-loop schedule on a sandbox skid steer, as the lab does.

    A controller for ``wheelkin.sandbox.World.run``: called before each step with the time
    ``t``, it sets the left (FL, RL) and right (FR, RR) wheel rates of the current command.

    Parameters
    ----------
    robot : SideDrivenRobot
        A robot with driven wheels on both sides (the lab's: FL, FR, RL, RR; the left ones are
        those at y > 0).
    commands : list of WheelCommand
        From :func:`wheelkin.waypoints.schedule` (or :func:`wheelkin.waypoints.quantise`).
    switch : {"time", "encoders"}
        ``"time"``: each command is held for its duration (quantise the schedule first to
        mimic a controller's time step). Called with the world (as ``World.run`` does), a
        simulation step in which the command changes gets the mean rates of that step, so
        that the wheels turn exactly as scheduled whatever the step. ``"encoders"``: each
        command is held until the encoders say its wheels have turned as planned (the mean
        of the outer side's wheels, or of all wheels on a straight leg, has turned
        :math:`|\dot\varphi_{outer}|\,t`), checked every ``period`` seconds.
    period : float
        Control period (s), > 0; used by ``switch="encoders"``.

    Attributes
    ----------
    switch_times : list of float
        When each command started (s); one more entry when the schedule ended.
    """

    def __init__(self, robot: SideDrivenRobot, commands: Sequence[WheelCommand], *,
                 switch: str = "time", period: float = 0.064) -> None:
        self._sides = _Sides(robot)
        self.robot = robot
        self.commands = validate_commands(commands)
        self.switch = V.choice("switch", switch, ("time", "encoders"))
        self.period = V.positive("period", period)
        self._times = schedule_times(self.commands)
        self.index = 0
        self.switch_times: list[float] = []
        self._next_tick = 0.0
        self._start_angles: np.ndarray | None = None

    @property
    def done(self) -> bool:
        """True once every command has been played."""
        return self.index >= len(self.commands)

    def _target_reached(self) -> bool:
        c = self.commands[self.index]
        turned = np.abs(self.robot.encoder_angles - self._start_angles)
        left, right = abs(c.left_rate), abs(c.right_rate)
        if math.isclose(left, right, rel_tol=1e-9):
            measured = float(np.mean(turned))  # all wheels: the lab's average
        else:
            side = self._sides.right if right > left else self._sides.left
            measured = float(np.mean(turned[side]))
        return measured >= max(left, right) * c.duration

    def __call__(self, t: float, world: object = None) -> None:
        """Set the robot's wheel rates for time ``t`` (s); ``world`` may give the step ``dt``."""
        t = V.finite("t", t)
        if self.done:
            self.robot.set_side_rates(0.0, 0.0)
            return
        if self.switch == "time":
            if not self.switch_times:
                self.switch_times.append(0.0)
            while not self.done and t >= self._times[self.index + 1]:
                self.index += 1
                self.switch_times.append(float(self._times[self.index]))
            dt = getattr(world, "dt", None)
            if dt is not None and (self.done or t + dt / 2 > self._times[self.index + 1]
                                   or t - dt / 2 < self._times[self.index]):
                # a switch inside the step [t - dt/2, t + dt/2]: its mean rates keep the
                # wheel angles exact at every step boundary
                angles = planned_wheel_angles(self.commands, [t - dt / 2, t + dt / 2])
                left, right = (angles[1] - angles[0]) / dt
                self.robot.set_side_rates(float(left), float(right))
                return
        else:
            if not self.switch_times:
                self.switch_times.append(t)
                self._start_angles = self.robot.encoder_angles
            if t >= self._next_tick - 1e-12:
                self._next_tick += self.period
                if self._target_reached():
                    self.index += 1
                    self.switch_times.append(t)
                    self._start_angles = self.robot.encoder_angles
        if self.done:
            self.robot.set_side_rates(0.0, 0.0)
        else:
            c = self.commands[self.index]
            self.robot.set_side_rates(c.left_rate, c.right_rate)


class FollowerController:
    r"""Close the loop: dead reckoning from the encoders feeding a :class:`PathFollower`.

    Every ``period`` seconds it reads the encoders, updates the pose estimate with the exact
    arc (the arc kernel of :func:`wheelkin.odometry.pose_update`) from the side means
    :math:`\Delta s_{L,R} = r_w\,\Delta\bar\varphi_{L,R}`, with
    :math:`\Delta s = (\Delta s_L + \Delta s_R)/2` and
    :math:`\Delta\theta = (\Delta s_R - \Delta s_L)/W_{odo}`, asks the follower for a body
    twist, turns it into side wheel rates with the differential drive's inverse kinematics
    (:func:`wheelkin.diffdrive.wheel_speeds`, track ``track_width``), scales both down if one
    would exceed ``max_wheel_rate`` (keeping the curvature, as
    :func:`wheelkin.diffdrive.desaturate` does), and holds them until the next tick.

    Parameters
    ----------
    robot : SideDrivenRobot
        A robot with driven wheels on both sides (the lab's: FL, FR, RL, RR), placed at the
        plan's start pose.
    follower : PathFollower
    wheel_radius : float
        :math:`r_w` (m), > 0.
    track_width : float
        :math:`W` (m), > 0, used to command the wheels; for a skid steer, its effective track.
    odometry_track_width : float, optional
        :math:`W_{odo}` (m), > 0, used to dead-reckon the heading; default ``track_width``.
    period : float
        Control period (s), > 0.
    max_wheel_rate : float, optional
        (rad/s), > 0.
    pose : (x, y, theta), optional
        The initial estimate; default the follower's first segment's start.

    Attributes
    ----------
    estimate : Pose
        The pose estimate now (m, m, rad).
    log_t : list of float
        Times of the control ticks (s).
    log_estimate : list of Pose
        The pose estimate at each tick (m, m, rad).
    finish_time : float or None
        When the follower reported the last segment done (s).
    """

    def __init__(self, robot: SideDrivenRobot, follower: PathFollower, *, wheel_radius: float,
                 track_width: float, odometry_track_width: float | None = None,
                 period: float = 0.064, max_wheel_rate: float | None = None,
                 pose: ArrayLike | None = None) -> None:
        self._sides = _Sides(robot)
        self.robot = robot
        if not isinstance(follower, PathFollower):
            raise TypeError(f"follower must be a PathFollower, got {type(follower).__name__}")
        self.follower = follower
        self.wheel_radius = V.positive("wheel_radius", wheel_radius)
        self.track_width = V.positive("track_width", track_width)
        self.odometry_track_width = (self.track_width if odometry_track_width is None else
                                     V.positive("odometry_track_width", odometry_track_width))
        self.period = V.positive("period", period)
        self.max_wheel_rate = (None if max_wheel_rate is None else
                               V.positive("max_wheel_rate", max_wheel_rate))
        start = follower.segments[0].start if pose is None else pose
        self.estimate = _pose3("pose", start)
        self._last: tuple[float, float] | None = None
        self._next_tick = 0.0
        self.log_t: list[float] = []
        self.log_estimate: list[Pose] = []
        self.finish_time: float | None = None

    def rates(self, speed: float, yaw_rate: float) -> SideRates:
        """Left and right wheel rates (rad/s) for a body twist, within ``max_wheel_rate``."""
        speed = V.finite("speed", speed)
        yaw_rate = V.finite("yaw_rate", yaw_rate)
        return self._rates(speed, yaw_rate)

    def _rates(self, speed: float, yaw_rate: float) -> SideRates:
        left, right = diff_drive_wheel_speeds(speed, yaw_rate, self.track_width)
        left, right = left / self.wheel_radius, right / self.wheel_radius
        if self.max_wheel_rate is not None:
            biggest = max(abs(left), abs(right))
            if biggest > self.max_wheel_rate:
                scale = self.max_wheel_rate / biggest
                left, right = left * scale, right * scale
        return SideRates(left, right)

    def __call__(self, t: float, world: object = None) -> None:
        """A control tick at time ``t`` (s) if one is due: read, estimate, command."""
        t = V.finite("t", t)
        if t < self._next_tick - 1e-12:
            return
        self._next_tick += self.period
        left_angle, right_angle = self._sides.means(self.robot.encoder_angles)
        if not (math.isfinite(left_angle) and math.isfinite(right_angle)):
            raise ValueError("robot.encoder_angles must be finite, got "
                             f"{self.robot.encoder_angles!r}")
        x, y, theta = self.estimate
        if self._last is not None:
            r = self.wheel_radius
            ds_left = r * (left_angle - self._last[0])
            ds_right = r * (right_angle - self._last[1])
            x, y, theta = arc_step(x, y, theta, 0.5 * (ds_left + ds_right),
                                   (ds_right - ds_left) / self.odometry_track_width)
            self.estimate = Pose(x, y, theta)
        self._last = (left_angle, right_angle)
        self.log_t.append(t)
        self.log_estimate.append(Pose(x, y, theta))
        speed, yaw_rate = self.follower.command((x, y, theta))
        if self.follower.done and self.finish_time is None:
            self.finish_time = t
        self.robot.set_side_rates(*self._rates(speed, yaw_rate))


class KinematicSkidSteer:
    r"""A reduced model of a four-wheeled skid steer, with the interface of a sandbox robot.

    A differential drive whose yaw rate is the wheels' ideal one divided by the skid factor
    :math:`\chi` (for a pure spin with Coulomb friction :math:`\chi = 1 + L^2/W^2`, the
    default), with a first-order motor lag and optionally quantised encoders. Each
    :meth:`step` of ``h`` seconds: the wheel rates approach their commands with the lag
    :math:`\tau` (exactly, over the step); with the step's mean rates
    :math:`\bar\varphi_{L,R}`, the body moves on the arc (the library's arc kernel) of the
    constant twist

    .. math:: v = r_w\,\frac{\bar\varphi_L + \bar\varphi_R}{2}, \qquad
              \omega = r_w\,\frac{\bar\varphi_R - \bar\varphi_L}{W\chi}.

    The left wheels (FL, RL) get the same commands, and so turn alike, as do the right ones
    (FR, RR).

    Parameters
    ----------
    pose : (x, y, theta)
        Start pose (m, m, rad), world frame.
    wheel_radius : float
        :math:`r_w` (m), > 0; default the lab robot's.
    track_width : float
        :math:`W` (m), > 0, between the left and right wheel contact lines; default the lab
        robot's 0.12 m.
    wheelbase : float
        :math:`L` (m), > 0, between the front and rear axles; default the lab robot's 0.1 m.
    skid_factor : float, optional
        :math:`\chi` >= 1 (1: an ideal differential drive); default :math:`1 + L^2/W^2`.
    steps_per_rev : int, optional
        Encoder counts per wheel revolution (a reading is the nearest count); None (default)
        for ideal encoders.
    motor_time_constant : float
        :math:`\tau` (s), >= 0.

    Examples
    --------
    >>> robot = KinematicSkidSteer((0.0, 0.0, 0.0), skid_factor=2.0, motor_time_constant=0.0)
    >>> robot.set_side_rates(-5.0, 5.0)
    >>> for _ in range(100):
    ...     robot.step(0.01)
    >>> round(robot.pose[2], 6)  # ideal: 0.04 * 10 / 0.12 = 3.333 rad/s for 1 s; halved
    1.666667
    """

    def __init__(self, pose: ArrayLike, *, wheel_radius: float = LAB_WHEEL_RADIUS,
                 track_width: float = 2 * LAB_HALF_AXLE,
                 wheelbase: float = 2 * LAB_HALF_WHEELBASE, skid_factor: float | None = None,
                 steps_per_rev: int | None = None, motor_time_constant: float = 0.05) -> None:
        self.start = _pose3("pose", pose)
        self.wheel_radius = V.positive("wheel_radius", wheel_radius)
        self.track_width = V.positive("track_width", track_width)
        self.wheelbase = V.positive("wheelbase", wheelbase)
        if skid_factor is None:
            with np.errstate(all="ignore"):
                ratio = np.float64(self.wheelbase) / self.track_width
                skid_factor = float(V.finite_result("wheelbase and track_width",
                                                    1.0 + ratio * ratio))
        self.skid_factor = V.finite("skid_factor", skid_factor)
        if self.skid_factor < 1.0:
            raise ValueError(f"skid_factor must be a finite number >= 1, got {skid_factor!r}")
        if steps_per_rev is not None and (isinstance(steps_per_rev, bool)
                                          or not isinstance(steps_per_rev, int | np.integer)
                                          or steps_per_rev < 1):
            raise ValueError(f"steps_per_rev must be a whole number >= 1 or None, "
                             f"got {steps_per_rev!r}")
        self.steps_per_rev = None if steps_per_rev is None else int(steps_per_rev)
        self.tau = V.nonnegative("motor_time_constant", motor_time_constant)
        a, b = 0.5 * self.wheelbase, 0.5 * self.track_width
        self.spec = WheelLayout((DrivenWheel("FL", (a, b)), DrivenWheel("FR", (a, -b)),
                                 DrivenWheel("RL", (-a, b)), DrivenWheel("RR", (-a, -b))))
        self._command = (0.0, 0.0)  # (left, right) rad/s
        self._rate = (0.0, 0.0)
        self._angle = (0.0, 0.0)
        self._poses: list[tuple[float, float, float]] = [self.start]
        self.steps = 0

    def set_side_rates(self, left: float, right: float) -> None:
        """Left wheels (FL, RL) at ``left``, right wheels (FR, RR) at ``right``, rad/s."""
        self._command = (V.finite("left", left), V.finite("right", right))

    @property
    def encoder_angles(self) -> np.ndarray:
        """The encoders' readings as wheel angles (rad), FL, FR, RL, RR."""
        left, right = self._angle
        if self.steps_per_rev is not None:
            per_count = 2 * math.pi / self.steps_per_rev
            left = math.floor(left / per_count + 0.5) * per_count
            right = math.floor(right / per_count + 0.5) * per_count
        return np.array([left, right, left, right])

    def step(self, h: float) -> None:
        """Advance ``h`` seconds (> 0)."""
        h = V.positive("h", h)
        (cmd_l, cmd_r), (rate_l, rate_r) = self._command, self._rate
        if self.tau > 0:
            decay = math.exp(-h / self.tau)
            lag = self.tau * (1 - decay) / h
            mean_l, mean_r = cmd_l + (rate_l - cmd_l) * lag, cmd_r + (rate_r - cmd_r) * lag
            self._rate = (cmd_l + (rate_l - cmd_l) * decay, cmd_r + (rate_r - cmd_r) * decay)
        else:
            mean_l, mean_r = self._rate = self._command
        r = self.wheel_radius
        distance = r * (mean_l + mean_r) / 2 * h
        dtheta = r * (mean_r - mean_l) / (self.track_width * self.skid_factor) * h
        self._poses.append(arc_step(*self._poses[-1], distance, dtheta))
        self._angle = (self._angle[0] + mean_l * h, self._angle[1] + mean_r * h)
        self.steps += 1

    def path(self) -> np.ndarray:
        """Poses (steps + 1, 3) from the start, after each step (m, m, rad; not wrapped)."""
        return np.array(self._poses)

    @property
    def pose(self) -> Pose:
        """The pose now (x, y, theta) (m, m, rad; heading not wrapped)."""
        return Pose(*self._poses[-1])
