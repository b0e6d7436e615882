r"""The Webots waypoint lab: the arena, the path, the open-loop schedule.

The lab :cite:p:`webots_waypoint_lab` drives a four-wheeled differential-drive (skid-steer)
robot through thirteen waypoints P0 .. P12 of a 4 m x 4 m maze, using straight legs, quarter
circles and turns in place, each run open loop for a computed time at a fixed wheel rate of
7.5 rad/s. This module rebuilds it in our convention: SI units, the arena frame with x east and
y north, headings counter-clockwise from +x (REP-103). The lab itself works in metres in the
same kind of frame, so its numbers enter unchanged.

The pieces, in the order the chapter uses them:

- :data:`LAB_WAYPOINTS` and :data:`LAB_WALLS`: the waypoints (from the lab's text) and the maze
  walls (a reconstruction: the lab's figure is not available; see :data:`LAB_WALLS`).
- :func:`plan_segments`: the path read from the waypoints, as straight legs, quarter arcs and
  turns in place (:class:`Segment`); :func:`sample_path` samples it densely.
- :func:`schedule`: the lab's open-loop plan, per segment the left and right wheel rates and the
  duration (:class:`WheelCommand`); :func:`quantise` rounds the durations to a control period.
- :func:`average_encoder_odometry`: the lab's position update, with the pieces it leaves out.

Plans and schedules only: what drives a robot along them (the feedback follower
:class:`~wheelkin.follower.PathFollower`, the controllers
:class:`~wheelkin.follower.ScheduleController` and
:class:`~wheelkin.follower.FollowerController`) is in :mod:`wheelkin.follower`, which builds on
this module (never the reverse).

Symbols (the chapter's): :math:`r_w` wheel radius, :math:`d` half the axle (the lab's
:math:`d_{mid}`, so the track is :math:`W = 2d`), :math:`R` the radius of a quarter circle
described by the robot's centre, :math:`\dot\varphi` the wheel rate of the outer wheel (the
lab's :math:`\omega = 7.5` rad/s), :math:`v` forward speed, :math:`\omega` yaw rate.

>>> segments = plan_segments(LAB_WAYPOINTS)
>>> [s.kind for s in segments[:7]]
['straight', 'arc', 'straight', 'arc', 'straight', 'turn', 'straight']
>>> commands = schedule(segments, wheel_radius=0.04, half_axle=0.06)
>>> round(sum(c.duration for c in commands), 2)
47.91
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from typing import cast

import numpy as np
from numpy.typing import ArrayLike

from wheelkin import _validate as V
from wheelkin.diffdrive import wheel_speeds
from wheelkin.frames import Pose, wrap_angle

__all__ = [
    "LAB_ARC_RADIUS",
    "LAB_HALF_AXLE",
    "LAB_HALF_WHEELBASE",
    "LAB_WALLS",
    "LAB_WAYPOINTS",
    "LAB_WHEEL_RADIUS",
    "LAB_WHEEL_RATE",
    "Segment",
    "WheelCommand",
    "average_encoder_odometry",
    "distance_to_walls",
    "plan_segments",
    "planned_pose",
    "planned_wheel_angles",
    "quantise",
    "sample_path",
    "schedule",
    "schedule_times",
    "validate_commands",
    "validate_segments",
    "waypoint_errors",
]

#: The lab's waypoints P0 .. P12 (m), in the arena frame (x east, y north), one row each.
LAB_WAYPOINTS = np.array(
    [
        [1.5, -1.5],  # P0 start
        [1.5, 1.0],  # P1
        [1.0, 1.5],  # P2
        [-1.0, 1.5],  # P3
        [-1.5, 1.0],  # P4
        [-1.5, 0.5],  # P5
        [0.0, 0.5],  # P6
        [0.5, 0.0],  # P7
        [0.0, -0.5],  # P8
        [-1.0, -0.5],  # P9
        [-1.5, -1.0],  # P10
        [-1.0, -1.5],  # P11
        [0.5, -1.5],  # P12 goal
    ]
)
LAB_WAYPOINTS.flags.writeable = False

#: The maze as wall segments ((x0, y0), (x1, y1)) in metres: the four outer walls of the
#: 4 m x 4 m arena, then four inner walls. The lab's figure is not available; this is a
#: reconstruction consistent with its path: a single corridor 1 m wide whose centre line holds
#: every straight leg, each quarter circle of radius 0.5 m turning about the end of an inner
#: wall, and the start and goal separated by the wall x = 1.
LAB_WALLS: tuple[tuple[tuple[float, float], tuple[float, float]], ...] = (
    ((-2.0, -2.0), (2.0, -2.0)),  # south
    ((2.0, -2.0), (2.0, 2.0)),  # east
    ((2.0, 2.0), (-2.0, 2.0)),  # north
    ((-2.0, 2.0), (-2.0, -2.0)),  # west
    ((-1.0, 1.0), (1.0, 1.0)),  # under the top corridor
    ((1.0, -2.0), (1.0, 1.0)),  # beside the start column, between start and goal
    ((-2.0, 0.0), (0.0, 0.0)),  # under the middle corridor
    ((-1.0, -1.0), (1.0, -1.0)),  # above the bottom corridor
)

#: The lab's quarter circles: radius of the robot centre's path (m).
LAB_ARC_RADIUS = 0.5
#: The lab's wheel rate on straights and of the outer wheel on curves (rad/s).
LAB_WHEEL_RATE = 7.5
#: Our robot (the Webots four-wheeled tutorial robot): wheel radius (m).
LAB_WHEEL_RADIUS = 0.04
#: Half the axle: wheel centres at +-0.06 m across (m), the lab's d_mid.
LAB_HALF_AXLE = 0.06
#: Wheel centres at +-0.05 m along the body (m).
LAB_HALF_WHEELBASE = 0.05

_TOL = 1e-6  # m: two waypoints closer than this are "the same"; offsets within it "match"
_KINDS = ("straight", "arc", "turn")


@dataclass(frozen=True)
class Segment:
    """One piece of the planned path of the robot's centre.

    Attributes
    ----------
    kind : {"straight", "arc", "turn"}
        A straight leg, a quarter circle, or a turn in place.
    start, end : Pose
        Poses (x, y, theta) in m, m, rad at the two ends. Headings are continuous along a plan
        (each is the previous one plus ``heading_change``), so that they can be compared with
        an unwrapped simulated heading; wrap them with ``wrap_angle`` if you need (-pi, pi].
    length : float
        Path length of the robot's centre (m); 0 for a turn in place.
    heading_change : float
        Rotation over the segment (rad), counter-clockwise positive.
    radius : float
        Signed turning radius of the centre (m): > 0 turning left, < 0 turning right,
        ``inf`` for a straight leg, 0 for a turn in place.
    centre : tuple of float or None
        Centre (x, y) of an arc (m); None otherwise (a tuple: a record holds points as
        tuples, so that it stays hashable).
    target : int or None
        Index of the waypoint this segment ends on (None for a turn in place, which ends where
        it starts, before the leg to the next waypoint).
    """

    kind: str
    start: Pose
    end: Pose
    length: float
    heading_change: float
    radius: float
    centre: tuple[float, float] | None = None
    target: int | None = None

    def __post_init__(self) -> None:
        V.choice("kind", self.kind, _KINDS)
        for name in ("start", "end"):
            object.__setattr__(self, name, Pose(*V.pose(name, getattr(self, name)).tolist()))
        object.__setattr__(self, "length", V.nonnegative("length", self.length))
        object.__setattr__(self, "heading_change",
                           V.finite("heading_change", self.heading_change))
        r = V.finite_array("radius", self.radius, allow_inf=True)
        if r.ndim != 0:
            raise ValueError(f"radius must be one number (inf for a straight), got {r!r}")
        object.__setattr__(self, "radius", float(r))
        if self.centre is not None:
            c = V.shaped("centre", self.centre, (2,))
            if c.ndim != 1:
                raise ValueError(f"centre must be a point (x, y) or None, got {self.centre!r}")
            object.__setattr__(self, "centre", tuple(c.tolist()))
        if self.kind == "arc" and self.centre is None:
            raise ValueError("centre must be given for an arc")
        if self.target is not None and (isinstance(self.target, bool)
                                        or not isinstance(self.target, int | np.integer)
                                        or self.target < 0):
            raise ValueError(f"target must be a waypoint index >= 0 or None, "
                             f"got {self.target!r}")

    def point_at(self, fraction: float) -> np.ndarray:
        """The point (x, y) (m) at one ``fraction`` in [0, 1] of the segment, shape (2,).

        >>> plan_segments([[0, 0], [2, 0]])[0].point_at(0.25)
        array([0.5, 0. ])
        """
        fraction = V.in_range("fraction", fraction, 0.0, 1.0)
        x0, y0, t0 = self.start
        if self.kind == "straight":
            d = fraction * self.length
            return np.array([x0 + d * math.cos(t0), y0 + d * math.sin(t0)])
        if self.kind == "arc":
            theta = t0 + fraction * self.heading_change
            cx, cy = cast(tuple[float, float], self.centre)  # an arc has one (checked above)
            return np.array([cx + self.radius * math.sin(theta),
                             cy - self.radius * math.cos(theta)])
        return np.array([x0, y0])

    def pose_at(self, fraction: ArrayLike) -> Pose | np.ndarray:
        """The pose at ``fraction`` in [0, 1] of the segment (of its length or angle): a
        :class:`~wheelkin.frames.Pose` for one fraction, an array (..., 3) for an array.

        >>> s = plan_segments([[0, 0], [1, 0]])[0]
        >>> s.pose_at(0.5)
        Pose(x=0.5, y=0.0, theta=0.0)
        >>> s.pose_at([0.0, 0.5, 1.0]).round(3).tolist()
        [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]]
        """
        f = V.finite_array("fraction", fraction)
        if np.any((f < 0) | (f > 1)):
            raise ValueError(f"fraction must be in [0, 1], got {fraction!r}")
        x0, y0, t0 = self.start
        theta = t0 + f * self.heading_change
        if self.kind == "straight":
            x = x0 + f * self.length * math.cos(t0)
            y = y0 + f * self.length * math.sin(t0)
        elif self.kind == "arc":
            cx, cy = cast(tuple[float, float], self.centre)
            r = self.radius  # signed: the centre is on the left for r > 0
            x = cx + r * np.sin(theta)
            y = cy - r * np.cos(theta)
        else:
            x = np.full_like(f, x0)
            y = np.full_like(f, y0)
        out = np.stack(np.broadcast_arrays(x, y, theta), axis=-1) + 0.0
        return Pose(*out.tolist()) if out.ndim == 1 else out


def _snap(value: float) -> float:
    """``value`` rounded to 1e-12 (removes the 1e-16 residue of cos(pi/2)), never -0.0."""
    return round(value, 12) + 0.0


def _heading_of(d) -> float:
    return math.atan2(d[1], d[0])


def plan_segments(waypoints: ArrayLike, arc_radius: float | None = LAB_ARC_RADIUS,
                  initial_heading: float | None = None) -> list[Segment]:
    r"""The path through ``waypoints`` as straight legs, quarter circles and turns in place.

    The robot starts on the first waypoint, facing ``initial_heading``. For each next waypoint,
    its offset (f, l) in the robot's frame (f ahead, l to the left) decides the motion:

    - l = 0, f > 0 (straight ahead): a straight leg of length f.
    - f = \|l\| = R with R = ``arc_radius`` (diagonally ahead, at the radius): a quarter
      circle of radius R, to the left if l > 0, about the centre
      :math:`(x, y) + R\,\mathrm{sign}(l)\,(-\sin\theta, \cos\theta)`.
    - anything else: a turn in place by :math:`\operatorname{atan2}(l, f)` in (-pi, pi]
      (a point straight behind gives +pi), then a straight leg.

    A point diagonally ahead (f = \|l\|) at another distance than ``arc_radius`` is taken as a
    quarter circle that does not fit the radius, and raises ``ValueError``; pass
    ``arc_radius=None`` to plan no arcs at all (every change of direction a turn in place).

    Parameters
    ----------
    waypoints : array_like, shape (N, 2)
        Points (x, y) in metres, N >= 2, no two consecutive ones equal.
    arc_radius : float or None
        Radius of the quarter circles (m), > 0; the lab's is 0.5 m.
    initial_heading : float, optional
        Heading at the first waypoint (rad, counter-clockwise from +x). Default: the direction
        of the first leg (the lab does not state it; for its waypoints this is north, pi/2).

    Returns
    -------
    list of Segment

    Examples
    --------
    A left quarter circle of radius 0.5 m, then a leg to a point behind and to the right:

    >>> segs = plan_segments([[0, 0], [1, 0], [1.5, 0.5], [2.5, 0.5]])
    >>> [(s.kind, round(s.length, 4), round(s.heading_change, 4)) for s in segs]
    [('straight', 1.0, 0.0), ('arc', 0.7854, 1.5708), ('turn', 0.0, -1.5708),
     ('straight', 1.0, 0.0)]
    >>> segs[1].centre
    (1.0, 0.5)
    >>> plan_segments([[0, 0], [0, 0]])
    Traceback (most recent call last):
    ...
    ValueError: waypoints[1] repeats waypoints[0] at (0, 0): consecutive waypoints must differ
    """
    pts = V.finite_array("waypoints", waypoints)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise ValueError(f"waypoints must have shape (N, 2), got shape {pts.shape}")
    if pts.shape[0] < 2:
        raise ValueError(f"waypoints must hold at least two points, got {pts.shape[0]}")
    for i in range(1, len(pts)):
        if math.hypot(*(pts[i] - pts[i - 1])) <= _TOL:
            raise ValueError(
                f"waypoints[{i}] repeats waypoints[{i - 1}] at ({pts[i, 0]:g}, {pts[i, 1]:g}): "
                "consecutive waypoints must differ"
            )
    if arc_radius is not None:
        arc_radius = V.positive("arc_radius", arc_radius)
    if initial_heading is None:
        theta = _heading_of(pts[1] - pts[0])
    else:
        theta = V.finite("initial_heading", initial_heading)  # kept as given, not wrapped

    segments: list[Segment] = []
    x, y = float(pts[0, 0]), float(pts[0, 1])
    for i in range(1, len(pts)):
        px, py = float(pts[i, 0]), float(pts[i, 1])
        dx, dy = px - x, py - y
        c, s = math.cos(theta), math.sin(theta)
        ahead, left = c * dx + s * dy, -s * dx + c * dy
        if abs(left) <= _TOL and ahead > 0:
            segments.append(Segment("straight", Pose(x, y, theta), Pose(px, py, theta), ahead, 0.0,
                                    math.inf, None, i))
        elif arc_radius is not None and ahead > _TOL and abs(ahead - abs(left)) <= _TOL:
            if abs(ahead - arc_radius) > _TOL:
                raise ValueError(
                    f"waypoints[{i}] is a quarter circle of radius {ahead:g} m from "
                    f"waypoints[{i - 1}], which does not fit arc_radius={arc_radius:g} m; "
                    "pass the matching arc_radius, or arc_radius=None to turn in place instead"
                )
            sign = 1.0 if left > 0 else -1.0
            centre = (_snap(x - sign * arc_radius * s), _snap(y + sign * arc_radius * c))
            dtheta = sign * math.pi / 2
            segments.append(Segment("arc", Pose(x, y, theta), Pose(px, py, theta + dtheta),
                                    arc_radius * math.pi / 2, dtheta, sign * arc_radius,
                                    centre, i))
            theta += dtheta
        else:
            dtheta = float(wrap_angle(math.atan2(left, ahead)))
            segments.append(Segment("turn", Pose(x, y, theta), Pose(x, y, theta + dtheta), 0.0,
                                    dtheta, 0.0, None, None))
            theta += dtheta
            dist = math.hypot(dx, dy)
            segments.append(Segment("straight", Pose(x, y, theta), Pose(px, py, theta), dist, 0.0,
                                    math.inf, None, i))
        x, y = px, py
    return segments


def validate_segments(segments: Segment | Iterable[Segment]) -> list[Segment]:
    """``segments`` as a list of :class:`Segment`; ``ValueError`` unless it is a non-empty
    sequence of them (one Segment alone is a list of one).

    >>> first = plan_segments([[0, 0], [1, 0]])[0]
    >>> validate_segments(first) == [first]
    True
    >>> validate_segments([])
    Traceback (most recent call last):
    ...
    ValueError: segments must be a non-empty list of Segment (from plan_segments)
    """
    if isinstance(segments, Segment):
        segments = [segments]
    try:
        segs = list(segments)
    except TypeError:
        raise ValueError(f"segments must be a list of Segment, got {segments!r}") from None
    if not segs or not all(isinstance(s, Segment) for s in segs):
        raise ValueError("segments must be a non-empty list of Segment (from plan_segments)")
    return segs


def sample_path(segments: Segment | Iterable[Segment], spacing: float = 0.01,
                turn_step: float = 0.05) -> np.ndarray:
    """The plan as poses (N, 3): samples at most ``spacing`` m (``turn_step`` rad) apart.

    Consecutive segments share their end point once. Headings are continuous.

    >>> p = sample_path(plan_segments(LAB_WAYPOINTS), spacing=0.05)
    >>> p.shape
    (309, 3)
    >>> bool(np.allclose(p[-1], [0.5, -1.5, 2 * np.pi]))
    True
    """
    segs = validate_segments(segments)
    spacing = V.positive("spacing", spacing)
    turn_step = V.positive("turn_step", turn_step)
    parts = []
    for k, seg in enumerate(segs):
        if seg.kind == "turn":
            n = max(2, math.ceil(abs(seg.heading_change) / turn_step) + 1)
        else:
            n = max(2, math.ceil(seg.length / spacing) + 1)
        poses = seg.pose_at(np.linspace(0.0, 1.0, n))
        parts.append(poses if k == 0 else poses[1:])
    return np.concatenate(parts, axis=0)


@dataclass(frozen=True)
class WheelCommand:
    """One step of the open-loop schedule: wheel rates held for a duration.

    Attributes
    ----------
    segment : Segment
        What this command drives.
    left_rate, right_rate : float
        Wheel angular rates (rad/s) of the left wheels (FL, RL) and the right wheels (FR, RR);
        positive rolls the robot forward.
    duration : float
        How long to hold them (s).
    speed, yaw_rate : float
        The body twist they give an ideal (non-slipping) robot: forward speed v (m/s) and yaw
        rate omega (rad/s, counter-clockwise positive).
    """

    segment: Segment
    left_rate: float
    right_rate: float
    duration: float
    speed: float
    yaw_rate: float

    def __post_init__(self) -> None:
        if not isinstance(self.segment, Segment):
            raise TypeError(f"segment must be a Segment, got {type(self.segment).__name__}")
        for name in ("left_rate", "right_rate", "speed", "yaw_rate"):
            object.__setattr__(self, name, V.finite(name, getattr(self, name)))
        object.__setattr__(self, "duration", V.nonnegative("duration", self.duration))


def schedule(segments: Segment | Iterable[Segment], wheel_radius: float, half_axle: float,
             wheel_rate: float = LAB_WHEEL_RATE) -> list[WheelCommand]:
    r"""The lab's open-loop schedule: per segment, left and right wheel rates and a duration.

    The outer wheel turns at :math:`\dot\varphi` = ``wheel_rate`` (both wheels on a straight
    leg; both, in opposite senses, in a turn in place), so its rim speed is
    :math:`V = r_w \dot\varphi`. With :math:`d` = ``half_axle``:

    - straight, length L: :math:`\dot\varphi_L = \dot\varphi_R = \dot\varphi`,
      :math:`t = L / V`.
    - quarter circle of radius R: yaw rate :math:`\Omega = V / (R + d)` (the outer wheel is
      on the circle of radius R + d), inner wheel :math:`\dot\varphi (R - d) / (R + d)`,
      :math:`t = (\pi/2)(R + d) / V`; the inner wheel is the left one on a left turn.
    - turn in place by :math:`\Delta\theta`: :math:`\dot\varphi_R = -\dot\varphi_L =
      \mathrm{sign}(\Delta\theta)\,\dot\varphi`, :math:`t = |\Delta\theta|\, d / V`
      (each wheel rolls :math:`|\Delta\theta|\, d`, the lab's :math:`d_{rotate}`).

    The left and right rates come from the body twist (v, omega) through the differential
    drive's inverse kinematics with track :math:`W = 2d` (``wheelkin.diffdrive``).

    Parameters
    ----------
    segments : list of Segment
        From :func:`plan_segments`.
    wheel_radius : float
        :math:`r_w` (m), > 0.
    half_axle : float
        :math:`d` (m), > 0: half the distance between the left and right wheels.
    wheel_rate : float
        :math:`\dot\varphi` (rad/s), > 0; the lab's 7.5 rad/s.

    Returns
    -------
    list of WheelCommand

    Examples
    --------
    The lab's first quarter circle (P1 -> P2 turns left, so the left wheel is inner):

    >>> arc = plan_segments(LAB_WAYPOINTS)[1]
    >>> c = schedule([arc], wheel_radius=0.04, half_axle=0.06)[0]
    >>> round(c.left_rate, 4), round(c.right_rate, 4), round(c.duration, 4)
    (5.8929, 7.5, 2.9322)
    """
    segs = validate_segments(segments)
    r = V.positive("wheel_radius", wheel_radius)
    d = V.positive("half_axle", half_axle)
    rate = V.positive("wheel_rate", wheel_rate)
    outer_speed = r * rate
    out = []
    for seg in segs:
        if seg.kind == "straight":
            speed, yaw_rate = outer_speed, 0.0
            duration = seg.length / outer_speed
        elif seg.kind == "arc":
            big_r = abs(seg.radius)
            body_rate = outer_speed / (big_r + d)
            speed, yaw_rate = body_rate * big_r, math.copysign(body_rate, seg.heading_change)
            duration = abs(seg.heading_change) / body_rate
        else:
            speed, yaw_rate = 0.0, math.copysign(outer_speed / d, seg.heading_change)
            duration = abs(seg.heading_change) * d / outer_speed
        left, right = wheel_speeds(speed, yaw_rate, 2 * d)
        out.append(WheelCommand(seg, left / r, right / r, duration, speed, yaw_rate))
    return out


def schedule_times(commands: Iterable[WheelCommand]) -> np.ndarray:
    """Start time of each command and the end of the last, shape (len(commands) + 1,) (s).

    >>> cmds = schedule(plan_segments([[0, 0], [0.3, 0], [0.3, 0.3]]), 0.04, 0.06)
    >>> schedule_times(cmds).round(3).tolist()
    [0.0, 1.0, 1.314, 2.314]
    """
    cmds = validate_commands(commands)
    return np.concatenate([[0.0], np.cumsum([c.duration for c in cmds])])


def planned_pose(commands: Iterable[WheelCommand], t: ArrayLike) -> Pose | np.ndarray:
    """Pose of an ideal (non-slipping) robot playing ``commands`` at times ``t`` (s): a
    :class:`~wheelkin.frames.Pose` for one time, an array (..., 3) for an array of times.

    Before 0 it is the first segment's start, after the last command the last one's end.

    >>> cmds = schedule(plan_segments(LAB_WAYPOINTS), 0.04, 0.06)
    >>> planned_pose(cmds, [0.0, 8.3333333333]).round(4).tolist()
    [[1.5, -1.5, 1.5708], [1.5, 1.0, 1.5708]]
    """
    cmds = validate_commands(commands)
    tt = V.finite_array("t", t)
    times = schedule_times(cmds)
    k = np.clip(np.searchsorted(times, tt, side="right") - 1, 0, len(cmds) - 1)
    out = np.empty((*tt.shape, 3))
    for i, c in enumerate(cmds):
        mask = k == i
        if np.any(mask):
            frac = np.clip((tt[mask] - times[i]) / c.duration, 0.0, 1.0)
            out[mask] = c.segment.pose_at(frac)
    return Pose(*out.tolist()) if out.ndim == 1 else out


def planned_wheel_angles(commands: Iterable[WheelCommand], t: ArrayLike) -> np.ndarray:
    """Cumulative wheel angles (..., 2), columns (left, right), in rad, of ``commands`` at
    times ``t`` (s): the integral of the scheduled rates, held after the last command.

    >>> cmds = schedule(plan_segments([[0, 0], [0.3, 0]]), 0.04, 0.06)
    >>> planned_wheel_angles(cmds, [0.5, 2.0]).tolist()
    [[3.75, 3.75], [7.5, 7.5]]
    """
    cmds = validate_commands(commands)
    tt = V.finite_array("t", t)
    times = schedule_times(cmds)
    left = np.concatenate([[0.0], np.cumsum([c.left_rate * c.duration for c in cmds])])
    right = np.concatenate([[0.0], np.cumsum([c.right_rate * c.duration for c in cmds])])
    return np.stack([np.interp(tt, times, left), np.interp(tt, times, right)], axis=-1)


def validate_commands(commands: Iterable[WheelCommand]) -> list[WheelCommand]:
    """``commands`` as a list of :class:`WheelCommand`; ``ValueError`` unless it is a
    non-empty sequence of them.

    >>> cmds = schedule(plan_segments([[0, 0], [0.3, 0]]), 0.04, 0.06)
    >>> len(validate_commands(tuple(cmds)))
    1
    >>> validate_commands([cmds[0].segment])
    Traceback (most recent call last):
    ...
    ValueError: commands must be a non-empty list of WheelCommand (from schedule)
    """
    try:
        cmds = list(commands)
    except TypeError:
        raise ValueError(f"commands must be a list of WheelCommand, got {commands!r}") from None
    if not cmds or not all(isinstance(c, WheelCommand) for c in cmds):
        raise ValueError("commands must be a non-empty list of WheelCommand (from schedule)")
    return cmds


def quantise(commands: Iterable[WheelCommand], period: float) -> list[WheelCommand]:
    r"""``commands`` with each duration rounded up to a whole number of control periods.

    A controller that switches commands only at its time steps (a Webots controller's
    ``robot.step(timestep)`` loop, run until the time is up) holds each command for
    :math:`\lceil t / T \rceil T`.

    >>> cmds = schedule(plan_segments([[0, 0], [0.3, 0], [0.3, 0.3]]), 0.04, 0.06)
    >>> [round(c.duration, 3) for c in quantise(cmds, 0.064)]
    [1.024, 0.32, 1.024]
    """
    cmds = validate_commands(commands)
    period = V.positive("period", period)
    out = []
    for c in cmds:
        n = math.ceil(c.duration / period - 1e-9)
        out.append(WheelCommand(c.segment, c.left_rate, c.right_rate, n * period, c.speed,
                                c.yaw_rate))
    return out


def average_encoder_odometry(wheel_angles: ArrayLike, wheel_radius: float, half_axle: float,
                             pose: ArrayLike = (0.0, 0.0, 0.0),
                             heading: ArrayLike | None = None) -> np.ndarray:
    r"""The lab's position update, with the pieces it leaves out filled in.

    The lab averages the four wheels' encoders and updates
    :math:`x = x_0 + \Delta x\cos\theta`, :math:`y = y_0 + \Delta x\sin\theta`. To work,
    :math:`\Delta x` must be the *increment* of that average since the last update, in metres:

    .. math:: \Delta s_k = r_w\,\tfrac14 \sum_{i} (\varphi_{i,k} - \varphi_{i,k-1}),

    and the heading needs a source the lab does not name: here the wheels,
    :math:`\theta_k = \theta_{k-1} + r_w(\Delta\bar\varphi_R - \Delta\bar\varphi_L)/(2d)`
    (side averages), unless ``heading`` is given (a compass). The position update uses the
    heading at the start of the step (Euler), as the lab's equations are written.

    Parameters
    ----------
    wheel_angles : array_like, shape (N, 4)
        Cumulative wheel rotations (rad) at N updates, columns FL, FR, RL, RR.
    wheel_radius : float
        :math:`r_w` (m), > 0.
    half_axle : float
        :math:`d` (m), > 0 (use an effective value for a skid steer, see the chapter).
    pose : (x, y, theta)
        The pose at the first update (m, m, rad).
    heading : array_like, shape (N,), optional
        Measured headings (rad) to use instead of the wheels'.

    Returns
    -------
    ndarray, shape (N, 3)
        Estimated poses (x, y, theta); the first row is ``pose``.

    Examples
    --------
    A quarter turn in place (left wheels back, right wheels forward by d*pi/2), then 1 m ahead:

    >>> d, r = 0.06, 0.04
    >>> q = d * np.pi / 2 / r
    >>> phi = [[0, 0, 0, 0], [-q, q, -q, q], [-q + 25, q + 25, -q + 25, q + 25]]
    >>> average_encoder_odometry(phi, r, d).round(6).tolist()
    [[0.0, 0.0, 0.0], [0.0, 0.0, 1.570796], [0.0, 1.0, 1.570796]]
    """
    phi = V.finite_array("wheel_angles", wheel_angles)
    if phi.ndim != 2 or phi.shape[1] != 4 or phi.shape[0] < 1:
        raise ValueError(f"wheel_angles must have shape (N, 4) (FL, FR, RL, RR), "
                         f"got shape {phi.shape}")
    r = V.positive("wheel_radius", wheel_radius)
    d = V.positive("half_axle", half_axle)
    p0 = V.pose("pose", pose)
    dphi = np.diff(phi, axis=0)
    ds = r * dphi.mean(axis=1)
    if heading is None:
        dtheta = r * ((dphi[:, 1] + dphi[:, 3]) - (dphi[:, 0] + dphi[:, 2])) / 2 / (2 * d)
        theta = p0[2] + np.concatenate([[0.0], np.cumsum(dtheta)])
    else:
        theta = V.finite_array("heading", heading)
        if theta.shape != (phi.shape[0],):
            raise ValueError(f"heading must have shape ({phi.shape[0]},) like wheel_angles' "
                             f"rows, got shape {theta.shape}")
    x = p0[0] + np.concatenate([[0.0], np.cumsum(ds * np.cos(theta[:-1]))])
    y = p0[1] + np.concatenate([[0.0], np.cumsum(ds * np.sin(theta[:-1]))])
    return np.stack([x, y, theta], axis=1)


def distance_to_walls(points: ArrayLike, walls: ArrayLike = LAB_WALLS) -> np.ndarray:
    """Distance (m) from each point (..., 2) to the nearest wall segment.

    >>> distance_to_walls([[0.0, 0.5], [1.5, -1.5]]).tolist()
    [0.5, 0.5]
    """
    p = V.shaped("points", points, (2,))
    w = V.finite_array("walls", walls)
    if w.ndim != 3 or w.shape[1:] != (2, 2) or w.shape[0] < 1:
        raise ValueError(f"walls must be a list of ((x0, y0), (x1, y1)) segments, "
                         f"got shape {w.shape}")
    a, b = w[:, 0], w[:, 1]
    ab = b - a
    rel = p[..., None, :] - a
    t = np.clip(np.sum(rel * ab, axis=-1) / np.maximum(np.sum(ab * ab, axis=-1), 1e-300), 0, 1)
    nearest = a + t[..., None] * ab
    return V.scalar_or_array(np.min(np.linalg.norm(p[..., None, :] - nearest, axis=-1), axis=-1))


def waypoint_errors(path: ArrayLike, waypoints: ArrayLike = LAB_WAYPOINTS) -> np.ndarray:
    """For each waypoint, the closest approach (m) of ``path`` (N, 2 or 3) to it.

    >>> waypoint_errors([[0, 0], [1, 0], [2, 0]], [[1, 0.1], [2, 0]]).round(3).tolist()
    [0.1, 0.0]
    """
    p = V.finite_array("path", path)
    if p.ndim != 2 or p.shape[1] not in (2, 3) or len(p) < 1:
        raise ValueError(f"path must have shape (N, 2) or (N, 3), got shape {p.shape}")
    w = V.finite_array("waypoints", waypoints)
    if w.ndim != 2 or w.shape[1] != 2:
        raise ValueError(f"waypoints must have shape (M, 2), got shape {w.shape}")
    return np.min(np.linalg.norm(p[None, :, :2] - w[:, None, :], axis=-1), axis=1)
