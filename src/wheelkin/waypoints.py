"""The Webots waypoint lab: the arena, the path, the open-loop schedule, a feedback follower.

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
- :class:`PathFollower`: a feedback follower (pure pursuit along straights and arcs, heading
  control for turns in place) that returns a body twist for a pose estimate.
- :class:`ScheduleController` and :class:`FollowerController`: both as controllers of the
  sandbox (``wheelkin.sandbox``), driving a skid steer's left and right wheel pairs.

Symbols (the chapter's): :math:`r_w` wheel radius, :math:`d` half the axle (the lab's
:math:`d_{mid}`, so the track is :math:`W = 2d`), :math:`R` the radius of a quarter circle
described by the robot's centre, :math:`\\dot\\varphi` the wheel rate of the outer wheel (the
lab's :math:`\\omega = 7.5` rad/s), :math:`v` forward speed, :math:`\\omega` yaw rate.

>>> segments = plan_segments(LAB_WAYPOINTS)
>>> [s.kind for s in segments[:7]]
['straight', 'arc', 'straight', 'arc', 'straight', 'turn', 'straight']
>>> commands = schedule(segments, wheel_radius=0.04, half_axle=0.06)
>>> round(sum(c.duration for c in commands), 2)
47.91
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from wheelkin import _validate as v
from wheelkin.diffdrive import _wheel_speeds_unchecked, wheel_speeds
from wheelkin.frames import wrap_angle
from wheelkin.odometry import _pose_update_unchecked

__all__ = [
    "LAB_ARC_RADIUS",
    "LAB_HALF_AXLE",
    "LAB_HALF_WHEELBASE",
    "LAB_WALLS",
    "LAB_WAYPOINTS",
    "LAB_WHEEL_RADIUS",
    "LAB_WHEEL_RATE",
    "FollowerController",
    "PathFollower",
    "ScheduleController",
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
_TWO_PI = 2.0 * math.pi
_KINDS = ("straight", "arc", "turn")


@dataclass(frozen=True)
class Segment:
    """One piece of the planned path of the robot's centre.

    Attributes
    ----------
    kind : {"straight", "arc", "turn"}
        A straight leg, a quarter circle, or a turn in place.
    start, end : tuple of float
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
        Centre (x, y) of an arc (m); None otherwise.
    target : int or None
        Index of the waypoint this segment ends on (None for a turn in place, which ends where
        it starts, before the leg to the next waypoint).
    """

    kind: str
    start: tuple[float, float, float]
    end: tuple[float, float, float]
    length: float
    heading_change: float
    radius: float
    centre: tuple[float, float] | None = None
    target: int | None = None

    def _point(self, fraction: float) -> tuple[float, float]:
        """(x, y) at one ``fraction`` in [0, 1], unchecked (the follower's inner loop)."""
        x0, y0, t0 = self.start
        if self.kind == "straight":
            d = fraction * self.length
            return x0 + d * math.cos(t0), y0 + d * math.sin(t0)
        if self.kind == "arc":
            theta = t0 + fraction * self.heading_change
            return (self.centre[0] + self.radius * math.sin(theta),
                    self.centre[1] - self.radius * math.cos(theta))
        return x0, y0

    def pose_at(self, fraction) -> np.ndarray:
        """Poses (..., 3) at ``fraction`` in [0, 1] of the segment (of its length or angle).

        >>> s = plan_segments([[0, 0], [1, 0]])[0]
        >>> s.pose_at([0.0, 0.5, 1.0]).round(3).tolist()
        [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]]
        """
        f = v.finite_array("fraction", fraction)
        if np.any((f < 0) | (f > 1)):
            raise ValueError(f"fraction must be in [0, 1], got {fraction!r}")
        x0, y0, t0 = self.start
        theta = t0 + f * self.heading_change
        if self.kind == "straight":
            x = x0 + f * self.length * math.cos(t0)
            y = y0 + f * self.length * math.sin(t0)
        elif self.kind == "arc":
            cx, cy = self.centre
            r = self.radius  # signed: the centre is on the left for r > 0
            x = cx + r * np.sin(theta)
            y = cy - r * np.cos(theta)
        else:
            x = np.full_like(f, x0)
            y = np.full_like(f, y0)
        return np.stack(np.broadcast_arrays(x, y, theta), axis=-1)


def _wrap_unchecked(angle: float) -> float:
    """:func:`wheelkin.frames.wrap_angle` of one finite Python float, unvalidated (the
    follower's inner loop): the same operations, so the same result to the last bit."""
    if -math.pi < angle <= math.pi:
        return angle
    r = float(np.remainder(angle + math.pi, _TWO_PI)) - math.pi
    if r <= -math.pi:
        r += _TWO_PI
    return min(r, math.pi)


def _snap(value: float) -> float:
    """``value`` rounded to 1e-12 (removes the 1e-16 residue of cos(pi/2)), never -0.0."""
    return round(value, 12) + 0.0


def _heading_of(d) -> float:
    return math.atan2(d[1], d[0])


def plan_segments(waypoints, arc_radius: float | None = LAB_ARC_RADIUS,
                  initial_heading: float | None = None) -> list[Segment]:
    """The path through ``waypoints`` as straight legs, quarter circles and turns in place.

    The robot starts on the first waypoint, facing ``initial_heading``. For each next waypoint,
    its offset (f, l) in the robot's frame (f ahead, l to the left) decides the motion:

    - l = 0, f > 0 (straight ahead): a straight leg of length f.
    - f = \\|l\\| = R with R = ``arc_radius`` (diagonally ahead, at the radius): a quarter
      circle of radius R, to the left if l > 0, about the centre
      :math:`(x, y) + R\\,\\mathrm{sign}(l)\\,(-\\sin\\theta, \\cos\\theta)`.
    - anything else: a turn in place by :math:`\\operatorname{atan2}(l, f)` in (-pi, pi]
      (a point straight behind gives +pi), then a straight leg.

    A point diagonally ahead (f = \\|l\\|) at another distance than ``arc_radius`` is taken as a
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
    [('straight', 1.0, 0.0), ('arc', 0.7854, 1.5708), ('turn', 0.0, -1.5708), \
('straight', 1.0, 0.0)]
    >>> segs[1].centre
    (1.0, 0.5)
    >>> plan_segments([[0, 0], [0, 0]])
    Traceback (most recent call last):
    ...
    ValueError: waypoints[1] repeats waypoints[0] at (0, 0): consecutive waypoints must differ
    """
    pts = v.finite_array("waypoints", waypoints)
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
        arc_radius = v.positive("arc_radius", arc_radius)
    if initial_heading is None:
        theta = _heading_of(pts[1] - pts[0])
    else:
        theta = float(wrap_angle(v.finite("initial_heading", initial_heading)))

    segments: list[Segment] = []
    x, y = float(pts[0, 0]), float(pts[0, 1])
    for i in range(1, len(pts)):
        px, py = float(pts[i, 0]), float(pts[i, 1])
        dx, dy = px - x, py - y
        c, s = math.cos(theta), math.sin(theta)
        ahead, left = c * dx + s * dy, -s * dx + c * dy
        if abs(left) <= _TOL and ahead > 0:
            segments.append(Segment("straight", (x, y, theta), (px, py, theta), ahead, 0.0,
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
            segments.append(Segment("arc", (x, y, theta), (px, py, theta + dtheta),
                                    arc_radius * math.pi / 2, dtheta, sign * arc_radius,
                                    centre, i))
            theta += dtheta
        else:
            dtheta = float(wrap_angle(math.atan2(left, ahead)))
            segments.append(Segment("turn", (x, y, theta), (x, y, theta + dtheta), 0.0, dtheta,
                                    0.0, None, None))
            theta += dtheta
            dist = math.hypot(dx, dy)
            segments.append(Segment("straight", (x, y, theta), (px, py, theta), dist, 0.0,
                                    math.inf, None, i))
        x, y = px, py
    return segments


def _check_segments(segments) -> list[Segment]:
    if isinstance(segments, Segment):
        segments = [segments]
    try:
        segs = list(segments)
    except TypeError:
        raise ValueError(f"segments must be a list of Segment, got {segments!r}") from None
    if not segs or not all(isinstance(s, Segment) for s in segs):
        raise ValueError("segments must be a non-empty list of Segment (from plan_segments)")
    return segs


def sample_path(segments, spacing: float = 0.01, turn_step: float = 0.05) -> np.ndarray:
    """The plan as poses (N, 3): samples at most ``spacing`` m (``turn_step`` rad) apart.

    Consecutive segments share their end point once. Headings are continuous.

    >>> p = sample_path(plan_segments(LAB_WAYPOINTS), spacing=0.05)
    >>> p.shape
    (309, 3)
    >>> bool(np.allclose(p[-1], [0.5, -1.5, 2 * np.pi]))
    True
    """
    segs = _check_segments(segments)
    spacing = v.positive("spacing", spacing)
    turn_step = v.positive("turn_step", turn_step)
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


def schedule(segments, wheel_radius: float, half_axle: float,
             wheel_rate: float = LAB_WHEEL_RATE) -> list[WheelCommand]:
    """The lab's open-loop schedule: per segment, left and right wheel rates and a duration.

    The outer wheel turns at :math:`\\dot\\varphi` = ``wheel_rate`` (both wheels on a straight
    leg; both, in opposite senses, in a turn in place), so its rim speed is
    :math:`V = r_w \\dot\\varphi`. With :math:`d` = ``half_axle``:

    - straight, length L: :math:`\\dot\\varphi_L = \\dot\\varphi_R = \\dot\\varphi`,
      :math:`t = L / V`.
    - quarter circle of radius R: yaw rate :math:`\\Omega = V / (R + d)` (the outer wheel is
      on the circle of radius R + d), inner wheel :math:`\\dot\\varphi (R - d) / (R + d)`,
      :math:`t = (\\pi/2)(R + d) / V`; the inner wheel is the left one on a left turn.
    - turn in place by :math:`\\Delta\\theta`: :math:`\\dot\\varphi_R = -\\dot\\varphi_L =
      \\mathrm{sign}(\\Delta\\theta)\\,\\dot\\varphi`, :math:`t = |\\Delta\\theta|\\, d / V`
      (each wheel rolls :math:`|\\Delta\\theta|\\, d`, the lab's :math:`d_{rotate}`).

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
        :math:`\\dot\\varphi` (rad/s), > 0; the lab's 7.5 rad/s.

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
    segs = _check_segments(segments)
    r = v.positive("wheel_radius", wheel_radius)
    d = v.positive("half_axle", half_axle)
    rate = v.positive("wheel_rate", wheel_rate)
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


def schedule_times(commands) -> np.ndarray:
    """Start time of each command and the end of the last, shape (len(commands) + 1,) (s).

    >>> cmds = schedule(plan_segments([[0, 0], [0.3, 0], [0.3, 0.3]]), 0.04, 0.06)
    >>> schedule_times(cmds).round(3).tolist()
    [0.0, 1.0, 1.314, 2.314]
    """
    cmds = _check_commands(commands)
    return np.concatenate([[0.0], np.cumsum([c.duration for c in cmds])])


def planned_pose(commands, t) -> np.ndarray:
    """Pose (..., 3) of an ideal (non-slipping) robot playing ``commands`` at times ``t`` (s).

    Before 0 it is the first segment's start, after the last command the last one's end.

    >>> cmds = schedule(plan_segments(LAB_WAYPOINTS), 0.04, 0.06)
    >>> planned_pose(cmds, [0.0, 8.3333333333]).round(4).tolist()
    [[1.5, -1.5, 1.5708], [1.5, 1.0, 1.5708]]
    """
    cmds = _check_commands(commands)
    tt = v.finite_array("t", t)
    times = schedule_times(cmds)
    k = np.clip(np.searchsorted(times, tt, side="right") - 1, 0, len(cmds) - 1)
    out = np.empty((*tt.shape, 3))
    for i, c in enumerate(cmds):
        mask = k == i
        if np.any(mask):
            frac = np.clip((tt[mask] - times[i]) / c.duration, 0.0, 1.0)
            out[mask] = c.segment.pose_at(frac)
    return out


def planned_wheel_angles(commands, t) -> np.ndarray:
    """Cumulative wheel angles (..., 2), columns (left, right), in rad, of ``commands`` at
    times ``t`` (s): the integral of the scheduled rates, held after the last command.

    >>> cmds = schedule(plan_segments([[0, 0], [0.3, 0]]), 0.04, 0.06)
    >>> planned_wheel_angles(cmds, [0.5, 2.0]).tolist()
    [[3.75, 3.75], [7.5, 7.5]]
    """
    cmds = _check_commands(commands)
    tt = v.finite_array("t", t)
    times = schedule_times(cmds)
    left = np.concatenate([[0.0], np.cumsum([c.left_rate * c.duration for c in cmds])])
    right = np.concatenate([[0.0], np.cumsum([c.right_rate * c.duration for c in cmds])])
    return np.stack([np.interp(tt, times, left), np.interp(tt, times, right)], axis=-1)


def _check_commands(commands) -> list[WheelCommand]:
    try:
        cmds = list(commands)
    except TypeError:
        raise ValueError(f"commands must be a list of WheelCommand, got {commands!r}") from None
    if not cmds or not all(isinstance(c, WheelCommand) for c in cmds):
        raise ValueError("commands must be a non-empty list of WheelCommand (from schedule)")
    return cmds


def quantise(commands, period: float) -> list[WheelCommand]:
    """``commands`` with each duration rounded up to a whole number of control periods.

    A controller that switches commands only at its time steps (a Webots controller's
    ``robot.step(timestep)`` loop, run until the time is up) holds each command for
    :math:`\\lceil t / T \\rceil T`.

    >>> cmds = schedule(plan_segments([[0, 0], [0.3, 0], [0.3, 0.3]]), 0.04, 0.06)
    >>> [round(c.duration, 3) for c in quantise(cmds, 0.064)]
    [1.024, 0.32, 1.024]
    """
    cmds = _check_commands(commands)
    period = v.positive("period", period)
    out = []
    for c in cmds:
        n = math.ceil(c.duration / period - 1e-9)
        out.append(WheelCommand(c.segment, c.left_rate, c.right_rate, n * period, c.speed,
                                c.yaw_rate))
    return out


def average_encoder_odometry(wheel_angles, wheel_radius: float, half_axle: float,
                             pose=(0.0, 0.0, 0.0), heading=None) -> np.ndarray:
    """The lab's position update, with the pieces it leaves out filled in.

    The lab averages the four wheels' encoders and updates
    :math:`x = x_0 + \\Delta x\\cos\\theta`, :math:`y = y_0 + \\Delta x\\sin\\theta`. To work,
    :math:`\\Delta x` must be the *increment* of that average since the last update, in metres:

    .. math:: \\Delta s_k = r_w\\,\\tfrac14 \\sum_{i} (\\varphi_{i,k} - \\varphi_{i,k-1}),

    and the heading needs a source the lab does not name: here the wheels,
    :math:`\\theta_k = \\theta_{k-1} + r_w(\\Delta\\bar\\varphi_R - \\Delta\\bar\\varphi_L)/(2d)`
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
    phi = v.finite_array("wheel_angles", wheel_angles)
    if phi.ndim != 2 or phi.shape[1] != 4 or phi.shape[0] < 1:
        raise ValueError(f"wheel_angles must have shape (N, 4) (FL, FR, RL, RR), "
                         f"got shape {phi.shape}")
    r = v.positive("wheel_radius", wheel_radius)
    d = v.positive("half_axle", half_axle)
    p0 = v.shaped("pose", pose, (3,))
    if p0.ndim != 1:
        raise ValueError(f"pose must have shape (3,), got shape {p0.shape}")
    dphi = np.diff(phi, axis=0)
    ds = r * dphi.mean(axis=1)
    if heading is None:
        dtheta = r * ((dphi[:, 1] + dphi[:, 3]) - (dphi[:, 0] + dphi[:, 2])) / 2 / (2 * d)
        theta = p0[2] + np.concatenate([[0.0], np.cumsum(dtheta)])
    else:
        theta = v.finite_array("heading", heading)
        if theta.shape != (phi.shape[0],):
            raise ValueError(f"heading must have shape ({phi.shape[0]},) like wheel_angles' "
                             f"rows, got shape {theta.shape}")
    x = p0[0] + np.concatenate([[0.0], np.cumsum(ds * np.cos(theta[:-1]))])
    y = p0[1] + np.concatenate([[0.0], np.cumsum(ds * np.sin(theta[:-1]))])
    return np.stack([x, y, theta], axis=1)


def distance_to_walls(points, walls=LAB_WALLS) -> np.ndarray:
    """Distance (m) from each point (..., 2) to the nearest wall segment.

    >>> distance_to_walls([[0.0, 0.5], [1.5, -1.5]]).tolist()
    [0.5, 0.5]
    """
    p = v.shaped("points", points, (2,))
    w = v.finite_array("walls", walls)
    if w.ndim != 3 or w.shape[1:] != (2, 2) or w.shape[0] < 1:
        raise ValueError(f"walls must be a list of ((x0, y0), (x1, y1)) segments, "
                         f"got shape {w.shape}")
    a, b = w[:, 0], w[:, 1]
    ab = b - a
    rel = p[..., None, :] - a
    t = np.clip(np.sum(rel * ab, axis=-1) / np.maximum(np.sum(ab * ab, axis=-1), 1e-300), 0, 1)
    nearest = a + t[..., None] * ab
    return np.min(np.linalg.norm(p[..., None, :] - nearest, axis=-1), axis=-1)


def waypoint_errors(path, waypoints=LAB_WAYPOINTS) -> np.ndarray:
    """For each waypoint, the closest approach (m) of ``path`` (N, 2 or 3) to it.

    >>> waypoint_errors([[0, 0], [1, 0], [2, 0]], [[1, 0.1], [2, 0]]).round(3).tolist()
    [0.1, 0.0]
    """
    p = v.finite_array("path", path)
    if p.ndim != 2 or p.shape[1] not in (2, 3) or len(p) < 1:
        raise ValueError(f"path must have shape (N, 2) or (N, 3), got shape {p.shape}")
    w = v.finite_array("waypoints", waypoints)
    if w.ndim != 2 or w.shape[1] != 2:
        raise ValueError(f"waypoints must have shape (M, 2), got shape {w.shape}")
    return np.min(np.linalg.norm(p[None, :, :2] - w[:, None, :], axis=-1), axis=1)


class PathFollower:
    """A feedback follower for a plan: pure pursuit on straights and arcs, turns on heading.

    Given a pose estimate, :meth:`command` returns the body twist (v, omega) to drive the
    current segment, and moves on when the segment is done:

    - straight or arc: the progress s along the segment is the projection of the position on
      it; the goal point ("carrot") lies ``lookahead`` ahead of it on the segment (beyond the
      end, on the end tangent). In the robot's frame the carrot is at (c_x, c_y), and pure
      pursuit drives the circle through it, :math:`\\kappa = 2 c_y / (c_x^2 + c_y^2)`,
      :math:`\\omega = v\\kappa` :cite:p:`corke2017`. If the carrot is behind the robot, it
      first turns in place toward it. Before a turn in place and at the goal, the speed falls
      as ``approach_gain`` times the distance left (never below ``min_speed``), so the robot
      stops on the waypoint. The segment is done when s reaches its length.
    - turn in place: :math:`\\omega = \\mathrm{clip}(k_\\theta e, \\pm\\omega_{max})` on the
      heading error e (wrapped), at least ``min_turn_rate`` in size; done when
      :math:`|e|` < ``heading_tolerance``.

    Parameters
    ----------
    segments : list of Segment
        From :func:`plan_segments`.
    speed : float
        Cruising speed v (m/s), > 0.
    lookahead : float
        Distance of the carrot ahead of the projection (m), > 0.
    heading_gain : float
        :math:`k_\\theta` (1/s), > 0, for turns in place.
    max_turn_rate : float
        :math:`\\omega_{max}` (rad/s), > 0.
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

    >>> f = PathFollower(plan_segments([[0, 0], [1, 0], [1, 1]], arc_radius=None), speed=0.2)
    >>> f.command((0.0, 0.0, 0.0))
    (0.2, 0.0)
    >>> f.command((1.0, 0.0, 0.0))  # at P1: the straight is done, turn left in place
    (0.0, 2.0)
    >>> f.index, f.done
    (1, False)
    """

    def __init__(self, segments, *, speed: float = 0.3, lookahead: float = 0.15,
                 heading_gain: float = 4.0, max_turn_rate: float = 2.0,
                 min_turn_rate: float = 0.2, heading_tolerance: float = 0.01,
                 approach_gain: float = 2.0, min_speed: float = 0.02) -> None:
        self.segments = _check_segments(segments)
        self.speed = v.positive("speed", speed)
        self.lookahead = v.positive("lookahead", lookahead)
        self.heading_gain = v.positive("heading_gain", heading_gain)
        self.max_turn_rate = v.positive("max_turn_rate", max_turn_rate)
        self.min_turn_rate = v.in_range("min_turn_rate", min_turn_rate, 0.0, self.max_turn_rate)
        self.heading_tolerance = v.positive("heading_tolerance", heading_tolerance)
        self.approach_gain = v.positive("approach_gain", approach_gain)
        self.min_speed = v.in_range("min_speed", min_speed, 0.0, self.speed)
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

    def progress(self, pose) -> float:
        """Arc length (m) along the current straight or arc of the projection of ``pose``."""
        seg = self.segments[self.index]
        x, y = pose[0], pose[1]
        x0, y0, t0 = seg.start
        if seg.kind == "straight":
            return (x - x0) * math.cos(t0) + (y - y0) * math.sin(t0)
        if seg.kind == "arc":
            cx, cy = seg.centre
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
            return seg._point(sc / seg.length)
        xe, ye, te = seg.end
        extra = sc - seg.length
        return xe + extra * math.cos(te), ye + extra * math.sin(te)

    def command(self, pose) -> tuple[float, float]:
        """Body twist (v in m/s, omega in rad/s) for the pose estimate (x, y, theta)."""
        p = v.shaped("pose", pose, (3,))
        if p.ndim != 1:
            raise ValueError(f"pose must have shape (3,), got shape {p.shape}")
        x, y, theta = (float(a) for a in p)
        return self._command_unchecked(x, y, theta)

    def _command_unchecked(self, x: float, y: float, theta: float) -> tuple[float, float]:
        """:meth:`command` for a pose of finite Python floats, unvalidated (inner loops)."""
        while not self.done:
            seg = self.segments[self.index]
            if seg.kind == "turn":
                error = _wrap_unchecked(seg.end[2] - theta)
                if abs(error) < self.heading_tolerance:
                    self.index += 1
                    continue
                return 0.0, self._turn(error)
            s = self.progress((x, y, theta))
            if s >= seg.length:
                self.index += 1
                continue
            cx, cy = self._carrot(seg, s)
            c, sn = math.cos(theta), math.sin(theta)
            ahead = c * (cx - x) + sn * (cy - y)
            left = -sn * (cx - x) + c * (cy - y)
            if ahead <= 0:
                return 0.0, self._turn(math.atan2(left, ahead))
            last = self.index + 1 >= len(self.segments)
            speed = self.speed
            if last or self.segments[self.index + 1].kind == "turn":
                speed = min(speed, max(self.min_speed, self.approach_gain * (seg.length - s)))
            curvature = 2.0 * left / (ahead * ahead + left * left)
            return float(speed), float(speed * curvature)
        return 0.0, 0.0


# --------------------------------------------------------------------------- sandbox controllers
class _Sides:
    """Which of a sandbox robot's driven wheels are on the left (y > 0) and on the right."""

    def __init__(self, robot) -> None:
        if not all(hasattr(robot, name) for name in ("set_side_rates", "encoder_angles",
                                                     "spec")):
            raise ValueError("robot must be a sandbox robot (wheelkin.sandbox.World.add) with "
                             "set_side_rates and encoder_angles")
        ys = [w.position[1] for w in robot.spec.driven_wheels]
        self.left = [i for i, y in enumerate(ys) if y > 0]
        self.right = [i for i, y in enumerate(ys) if y < 0]
        if not self.left or not self.right:
            raise ValueError("robot must have driven wheels on both sides (y > 0 and y < 0)")

    def means(self, angles) -> tuple[float, float]:
        """Mean angle (rad) of the left wheels and of the right wheels."""
        a = np.asarray(angles, dtype=float)
        return float(np.mean(a[self.left])), float(np.mean(a[self.right]))


class ScheduleController:
    """Play an open-loop schedule on a sandbox skid steer, as the lab does.

    A controller for :meth:`wheelkin.sandbox.World.run`: called before each step with the time
    ``t``, it sets the left (FL, RL) and right (FR, RR) wheel rates of the current command.

    Parameters
    ----------
    robot : wheelkin.sandbox.Robot
        A robot with driven wheels on both sides (the lab's: FL, FR, RL, RR; the left ones are
        those at y > 0).
    commands : list of WheelCommand
        From :func:`schedule` (or :func:`quantise`).
    switch : {"time", "encoders"}
        ``"time"``: each command is held for its duration (quantise the schedule first to
        mimic a controller's time step). Called with the world (as ``World.run`` does), a
        simulation step in which the command changes gets the mean rates of that step, so
        that the wheels turn exactly as scheduled whatever the step. ``"encoders"``: each
        command is held until the encoders say its wheels have turned as planned (the mean
        of the outer side's wheels, or of all wheels on a straight leg, has turned
        :math:`|\\dot\\varphi_{outer}|\\,t`), checked every ``period`` seconds.
    period : float
        Control period (s), > 0; used by ``switch="encoders"``.

    Attributes
    ----------
    switch_times : list of float
        When each command started (s); one more entry when the schedule ended.
    """

    def __init__(self, robot, commands, *, switch: str = "time", period: float = 0.064) -> None:
        self._sides = _Sides(robot)
        self.robot = robot
        self.commands = _check_commands(commands)
        self.switch = v.choice("switch", switch, ("time", "encoders"))
        self.period = v.positive("period", period)
        self._times = schedule_times(self.commands)
        self.index = 0
        self.switch_times: list[float] = []
        self._next_tick = 0.0
        self._start_angles = None

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

    def __call__(self, t: float, world=None) -> None:
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
    """Close the loop in the sandbox: dead reckoning from the encoders feeding a
    :class:`PathFollower`.

    Every ``period`` seconds it reads the encoders, updates the pose estimate with the
    exact arc (:func:`wheelkin.odometry.pose_update`) from the side means
    :math:`\\Delta s_{L,R} = r_w\\,\\Delta\\bar\\varphi_{L,R}`, with
    :math:`\\Delta s = (\\Delta s_L + \\Delta s_R)/2` and
    :math:`\\Delta\\theta = (\\Delta s_R - \\Delta s_L)/W_{odo}`, asks the follower for a body
    twist, turns it into side wheel rates with the differential drive's inverse kinematics
    (:func:`wheelkin.diffdrive.wheel_speeds`, track ``track_width``), scales both down if one
    would exceed ``max_wheel_rate`` (keeping the curvature), and holds them until the next tick.

    Parameters
    ----------
    robot : wheelkin.sandbox.Robot
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
    log_t : list of float
        Times of the control ticks (s).
    log_estimate : list of tuple
        The pose estimate at each tick (m, m, rad).
    finish_time : float or None
        When the follower reported the last segment done (s).
    """

    def __init__(self, robot, follower: PathFollower, *, wheel_radius: float,
                 track_width: float, odometry_track_width: float | None = None,
                 period: float = 0.064, max_wheel_rate: float | None = None,
                 pose=None) -> None:
        from wheelkin.odometry import pose_update

        self._pose_update = pose_update
        self._sides = _Sides(robot)
        self.robot = robot
        if not isinstance(follower, PathFollower):
            raise ValueError(f"follower must be a PathFollower, got {type(follower).__name__}")
        self.follower = follower
        self.wheel_radius = v.positive("wheel_radius", wheel_radius)
        self.track_width = v.positive("track_width", track_width)
        self.odometry_track_width = (self.track_width if odometry_track_width is None else
                                     v.positive("odometry_track_width", odometry_track_width))
        self.period = v.positive("period", period)
        self.max_wheel_rate = (None if max_wheel_rate is None else
                               v.positive("max_wheel_rate", max_wheel_rate))
        start = follower.segments[0].start if pose is None else pose
        p = v.shaped("pose", start, (3,))
        if p.ndim != 1:
            raise ValueError(f"pose must have shape (3,), got shape {p.shape}")
        self.estimate = np.array(p, dtype=float)
        self._last = None
        self._next_tick = 0.0
        self.log_t: list[float] = []
        self.log_estimate: list[tuple[float, float, float]] = []
        self.finish_time: float | None = None

    def _cap(self, left: float, right: float) -> tuple[float, float]:
        """Wheel surface speeds (m/s) to rates (rad/s), both scaled down together (the
        curvature kept) so that neither exceeds ``max_wheel_rate``."""
        left, right = left / self.wheel_radius, right / self.wheel_radius
        if self.max_wheel_rate is not None:
            biggest = max(abs(left), abs(right))
            if biggest > self.max_wheel_rate:
                left, right = (left * self.max_wheel_rate / biggest,
                               right * self.max_wheel_rate / biggest)
        return left, right

    def rates(self, speed: float, yaw_rate: float) -> tuple[float, float]:
        """Left and right wheel rates (rad/s) for a body twist, within ``max_wheel_rate``."""
        left, right = wheel_speeds(speed, yaw_rate, self.track_width)
        return self._cap(left, right)

    def __call__(self, t: float, world=None) -> None:
        if t < self._next_tick - 1e-12:
            return
        self._next_tick += self.period
        now = self._sides.means(self.robot.encoder_angles)
        if self._last is not None:
            ds_left = self.wheel_radius * (now[0] - self._last[0])
            ds_right = self.wheel_radius * (now[1] - self._last[1])
            distance = 0.5 * (ds_left + ds_right)
            dtheta = (ds_right - ds_left) / self.odometry_track_width
            self.estimate = np.asarray(self._pose_update(self.estimate, distance, dtheta,
                                                         "exact"), dtype=float)
        self._last = now
        self.log_t.append(float(t))
        self.log_estimate.append(tuple(float(a) for a in self.estimate))
        speed, yaw_rate = self.follower.command(self.estimate)
        if self.follower.done and self.finish_time is None:
            self.finish_time = float(t)
        self.robot.set_side_rates(*self.rates(speed, yaw_rate))

    def _tick_unchecked(self, t: float, left_angle: float,
                        right_angle: float) -> tuple[float, float] | None:
        """What :meth:`__call__` does at time ``t``, unvalidated, for a fast simulation loop.

        The caller passes the mean encoder angles (rad) of the left and right wheels (as Python
        floats) instead of a robot to read, and gets back the (left, right) wheel rates to hold
        from now on, or None between ticks (keep the previous rates). The estimate, the logs
        and ``finish_time`` are kept as by :meth:`__call__`, to the last bit (the tests compare
        whole laps); nothing is checked, so a NaN reading gives NaNs instead of a
        ``ValueError``. The robot passed to the constructor is not used.
        """
        if t < self._next_tick - 1e-12:
            return None
        self._next_tick += self.period
        x, y, theta = (float(a) for a in self.estimate)
        if self._last is not None:
            r = self.wheel_radius
            ds_left = r * (left_angle - self._last[0])
            ds_right = r * (right_angle - self._last[1])
            distance = 0.5 * (ds_left + ds_right)
            dtheta = (ds_right - ds_left) / self.odometry_track_width
            x, y, theta = _pose_update_unchecked(x, y, theta, distance, dtheta)
            self.estimate = np.array((x, y, theta))
        self._last = (left_angle, right_angle)
        self.log_t.append(float(t))
        self.log_estimate.append((x, y, theta))
        speed, yaw_rate = self.follower._command_unchecked(x, y, theta)
        if self.follower.done and self.finish_time is None:
            self.finish_time = float(t)
        left, right = _wheel_speeds_unchecked(speed, yaw_rate, self.track_width)
        return self._cap(left, right)
