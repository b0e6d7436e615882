r"""The waypoint-lab chapter's live panel (notebooks/07_waypoints) and its fast lap model.

A lap of the sandbox takes seconds (the skid steer slips in every turn, and each slipping step
is a small optimisation), too slow to follow a slider. The panel therefore drives a *reduced*
model of the lab robot, :class:`wheelkin.follower.KinematicSkidSteer` (re-exported here): a
differential drive whose yaw rate is the wheels' ideal one divided by the skid factor
:math:`\chi` (the sandbox's, measured in the chapter: :math:`\chi = 1 + a^2/b^2` for a pure
spin with Coulomb friction), with the same first-order motor lag. It has the interface of a
sandbox robot, so the very same :class:`wheelkin.follower.FollowerController` drives it. The
chapter checks it against the sandbox's closed-loop lap.

The panel ``waypoints.lab`` runs a closed-loop lap with sliders for the cruising speed, the
look-ahead distance, the heading gain of the turns in place, the encoder resolution and the
track width the odometry assumes, and draws the maze, the plan, the true path and the estimate.

The chapter's sections share three more helpers: :func:`draw_arena` (the maze and its
waypoints on an axes), :func:`run_schedule` (an open-loop schedule played in the sandbox's
maze) and :func:`spin_test_track` (the effective track width from a spin in place).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache
from typing import NamedTuple

import ipywidgets as widgets
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.patches import Polygon
from numpy.typing import ArrayLike

from wheelkin import _validate as V
from wheelkin import waypoints as wp
from wheelkin.follower import (
    FollowerController,
    KinematicSkidSteer,
    PathFollower,
    ScheduleController,
)
from wheelkin.sandbox import LAB_ROBOT, Robot, Trajectory, VehicleSpec, World
from wheelkin.style import fixed_layout
from wheelkin.widgets import Panel, register
from wheelkin.widgets._blit import BlitList

__all__ = [
    "EFFECTIVE_TRACK",
    "LAB_SPEC",
    "SANDBOX_DT",
    "SKID_FACTOR",
    "KinematicSkidSteer",
    "LabView",
    "ScheduleRun",
    "draw_arena",
    "lab_panel",
    "run_schedule",
    "spin_test_track",
    "surrogate_lap",
]

_A, _B = wp.LAB_HALF_WHEELBASE, wp.LAB_HALF_AXLE  # half wheelbase a, half axle b = d (m)
#: Skid factor of the lab robot turning in place with Coulomb friction: 1 + a^2/b^2.
SKID_FACTOR = 1.0 + (_A / _B) ** 2
#: The lab robot's effective track (m): the geometric one, 2b, times the skid factor.
EFFECTIVE_TRACK = 2 * _B * SKID_FACTOR
MOTOR_TIME_CONSTANT = 0.05  # s, as in the chapter's sandbox runs
PERIOD = 0.064  # s, the control period (Webots tutorial controllers)
MAX_WHEEL_RATE = 10.0  # rad/s, Webots' default motor limit
ENCODER_CHOICES = (("ideal", 0), ("4096 / rev", 4096), ("256 / rev", 256), ("64 / rev", 64),
                   ("16 / rev", 16))
TRACK_CHOICES = (("effective, 0.203 m (calibrated)", EFFECTIVE_TRACK),
                 ("geometric, 0.12 m (the lab's)", 2 * _B))
#: s, the physics step of the chapter's sandbox runs (an eighth of the control period).
SANDBOX_DT = 0.008
#: The lab robot of the chapter's sandbox runs: the sandbox's, with the motor lag.
LAB_SPEC = LAB_ROBOT.replace(motor_time_constant=MOTOR_TIME_CONSTANT)


def draw_arena(ax: Axes, *, labels: bool = True) -> None:
    """Draw the reconstructed maze (walls in black) and, with ``labels``, the waypoints
    P0..P12 on ``ax``, with the chapter's limits, ticks and axis labels (x east, y north, m).

    >>> from matplotlib.figure import Figure
    >>> ax = Figure().add_subplot()
    >>> draw_arena(ax)
    >>> len(ax.lines) == len(wp.LAB_WALLS) + len(wp.LAB_WAYPOINTS)
    True
    >>> [float(x) for x in ax.get_xlim()]
    [-2.1, 2.1]
    """
    if not isinstance(labels, bool):
        raise ValueError(f"labels must be True or False, got {labels!r}")
    for (x0, y0), (x1, y1) in wp.LAB_WALLS:
        ax.plot([x0, x1], [y0, y1], color="k", lw=2.5, solid_capstyle="round")
    if labels:
        for k, (px, py) in enumerate(wp.LAB_WAYPOINTS):
            ax.plot(px, py, "o", color="0.2", ms=4, zorder=5)
            ax.annotate(f"P{k}", (px, py), xytext=(4, 4), textcoords="offset points",
                        fontsize=8)
    ax.set_xlim(-2.1, 2.1)
    ax.set_ylim(-2.1, 2.1)
    ax.set_xticks([-2, -1, 0, 1, 2])
    ax.set_yticks([-2, -1, 0, 1, 2])
    ax.set_aspect("equal")
    ax.set_xlabel("x, east (m)")
    ax.set_ylabel("y, north (m)")


class ScheduleRun(NamedTuple):
    """What :func:`run_schedule` returns."""

    #: The recorded run.
    trajectory: Trajectory
    #: The controller that played the schedule (its switch times, its log).
    controller: ScheduleController
    #: The robot, as the run left it.
    robot: Robot


def run_schedule(spec: VehicleSpec, commands: Sequence[wp.WheelCommand], *,
                 switch: str = "time", walls: Sequence = wp.LAB_WALLS,
                 dt: float = SANDBOX_DT, period: float = PERIOD,
                 extra: float = 1.0) -> ScheduleRun:
    """Play a wheel schedule open loop in the sandbox's maze, from the plan's start (P0).

    A :class:`wheelkin.follower.ScheduleController` sets the wheel rates once per control
    ``period``; the world runs the schedule's duration plus 4 % and ``extra`` seconds.

    Parameters
    ----------
    spec : VehicleSpec
        The robot, e.g. :data:`LAB_SPEC`.
    commands : sequence of WheelCommand
        The schedule (:func:`wheelkin.waypoints.schedule`).
    switch : {"time", "encoders"}
        When the controller moves to the next command: by the clock, or when the wheels have
        turned the command's angle.
    walls : sequence of ((x0, y0), (x1, y1))
        The world's walls (default: the maze).
    dt, period, extra : float
        Physics step, control period, time run beyond the schedule (s).

    Returns
    -------
    ScheduleRun
        ``(trajectory, controller, robot)``.
    """
    if not isinstance(spec, VehicleSpec):
        raise ValueError(f"spec must be a VehicleSpec, got {type(spec).__name__}")
    extra = V.nonnegative("extra", extra)
    world = World(dt=dt, walls=walls)
    robot = world.add(spec, pose=wp.plan_segments(wp.LAB_WAYPOINTS)[0].start)
    controller = ScheduleController(robot, commands, switch=switch, period=period)
    trajectory = world.run(wp.schedule_times(commands)[-1] * 1.04 + extra, controller)
    assert isinstance(trajectory, Trajectory)  # one robot: one trajectory
    return ScheduleRun(trajectory, controller, robot)


def spin_test_track(dt: float = SANDBOX_DT, *, spec: VehicleSpec = LAB_SPEC,
                    wheel_rate: float = wp.LAB_WHEEL_RATE, duration: float = 2.0) -> float:
    r"""The effective track width :math:`W_\text{eff}` (m) of a skid steer, from a spin test.

    The left wheels turn at ``-wheel_rate``, the right ones at ``+wheel_rate`` (rad/s) for
    ``duration`` seconds in the sandbox; the steady yaw rate :math:`\omega` gives
    :math:`W_\text{eff} = 2 r\,\dot\varphi / \omega`, the track width that the two-wheel
    formulas need to predict it (the wheel radius :math:`r` is the first wheel's).

    Examples
    --------
    >>> chi = spin_test_track() / (2 * wp.LAB_HALF_AXLE)  # the skid factor 1 + (a/b)^2
    >>> round(chi, 4), round(1 + (wp.LAB_HALF_WHEELBASE / wp.LAB_HALF_AXLE) ** 2, 4)
    (1.6944, 1.6944)
    """
    if not isinstance(spec, VehicleSpec):
        raise ValueError(f"spec must be a VehicleSpec, got {type(spec).__name__}")
    wheel_rate = V.positive("wheel_rate", wheel_rate)
    world = World(dt=dt)
    robot = world.add(spec)
    robot.set_side_rates(-wheel_rate, wheel_rate)
    run = world.run(V.positive("duration", duration))
    assert isinstance(run, Trajectory)
    yaw_rate = float(run.twist[-1, 2])  # steady state, rad/s
    if not yaw_rate > 0:
        raise ValueError(f"the spin test did not turn (yaw rate {yaw_rate!r} rad/s): give a "
                         "longer duration")
    return spec.wheels[0].wheel_radius * 2 * wheel_rate / yaw_rate


def surrogate_lap(*, speed: float = 0.3, lookahead: float = 0.15, heading_gain: float = 4.0,
                  steps_per_rev: int | None = None, odometry_track_width: float = EFFECTIVE_TRACK,
                  skid_factor: float = SKID_FACTOR, substeps: int = 4,
                  max_time: float | None = None) -> dict:
    """A closed-loop lap of the lab on :class:`KinematicSkidSteer`.

    Returns a dict with ``t`` (s), ``truth`` and ``estimate`` (N, 3) at the control ticks,
    ``finish_time`` (s or None), ``final_error`` (m, truth to P12), ``waypoint_errors`` (m).
    ``max_time`` (s) defaults to twice the plan's length at ``speed`` plus 30 s.

    >>> lap = surrogate_lap()
    >>> lap["finish_time"] is not None and lap["final_error"] < 0.05
    True
    """
    segments = wp.plan_segments(wp.LAB_WAYPOINTS)
    robot = KinematicSkidSteer(segments[0].start, skid_factor=skid_factor,
                               steps_per_rev=steps_per_rev,
                               motor_time_constant=MOTOR_TIME_CONSTANT)
    follower = PathFollower(segments, speed=speed, lookahead=lookahead,
                            heading_gain=heading_gain)
    ctrl = FollowerController(robot, follower, wheel_radius=wp.LAB_WHEEL_RADIUS,
                              track_width=EFFECTIVE_TRACK,
                              odometry_track_width=odometry_track_width, period=PERIOD,
                              max_wheel_rate=MAX_WHEEL_RATE)
    h = PERIOD / substeps
    if max_time is None:
        max_time = 2.0 * sum(s.length for s in segments) / speed + 30.0
    for k in range(int(max_time / h)):  # the controller ticks every `substeps` steps
        if (k % substeps == 0 and ctrl.finish_time is not None
                and k * h > ctrl.finish_time + 1.0):
            break
        ctrl(k * h + 0.5 * h)
        robot.step(h)
    truth = robot.path()[::substeps]
    estimate = np.array(ctrl.log_estimate)
    n = min(len(truth), len(estimate))
    return {
        "t": np.array(ctrl.log_t[:n]),
        "truth": truth[:n],
        "estimate": estimate[:n],
        "finish_time": ctrl.finish_time,
        "final_error": float(np.hypot(*(truth[n - 1, :2] - wp.LAB_WAYPOINTS[-1]))),
        "waypoint_errors": wp.waypoint_errors(truth[:n]),
    }


@lru_cache(maxsize=128)
def _lap_picture(speed, lookahead, heading_gain, steps_per_rev, track):
    """What the panel shows of one lap: the true path, the estimate and the summary text
    (remembered: a student drags a slider back and forth over the same values)."""
    lap = surrogate_lap(speed=speed, lookahead=lookahead, heading_gain=heading_gain,
                        steps_per_rev=steps_per_rev or None, odometry_track_width=track)
    finish = lap["finish_time"]
    clearance = float(wp.distance_to_walls(lap["truth"][:, :2]).min())
    lines = [
        f"lap time      {finish:6.2f} s" if finish is not None else "lap time      not finished",
        f"final error   {lap['final_error'] * 100:6.1f} cm",
        f"worst waypt   {lap['waypoint_errors'][1:].max() * 100:6.1f} cm",
        f"wall gap min  {clearance * 100:6.1f} cm" + ("  (touch!)" if clearance < 0.12 else ""),
    ]
    for array in (lap["truth"], lap["estimate"]):
        array.flags.writeable = False  # shared by every later call with these values
    return lap["truth"], lap["estimate"], "\n".join(lines)


def _robot_outline(pose) -> np.ndarray:
    x, y, th = pose
    c, s = math.cos(th), math.sin(th)
    body = np.asarray(LAB_ROBOT.body, dtype=float)
    return np.stack([x + c * body[:, 0] - s * body[:, 1], y + s * body[:, 0] + c * body[:, 1]],
                    axis=1)


class LabView:
    """The maze from above with the plan, a true path, an estimate and the robot."""

    def __init__(self, ax: Axes) -> None:
        self.ax = ax
        for (x0, y0), (x1, y1) in wp.LAB_WALLS:
            ax.plot([x0, x1], [y0, y1], color="k", lw=2.0, solid_capstyle="round")
        plan = wp.sample_path(wp.plan_segments(wp.LAB_WAYPOINTS), spacing=0.02)
        ax.plot(plan[:, 0], plan[:, 1], ls="--", color="0.55", lw=1.0, label="plan")
        ax.plot(wp.LAB_WAYPOINTS[:, 0], wp.LAB_WAYPOINTS[:, 1], "o", color="0.3", ms=3)
        (self.truth,) = ax.plot([], [], color="C0", lw=1.6, label="truth")
        (self.estimate,) = ax.plot([], [], color="C3", lw=1.2, ls=":", label="estimate")
        self.robot = Polygon(_robot_outline((1.5, -1.5, math.pi / 2)), closed=True,
                             fc="C0", ec="k", alpha=0.8, zorder=5)
        ax.add_patch(self.robot)
        self.text = ax.text(0.02, 0.98, "", transform=ax.transAxes, va="top", fontsize=8,
                            family="monospace",
                            bbox=dict(fc="white", ec="0.7", alpha=0.9))
        ax.set_xlim(-2.1, 2.1)
        ax.set_ylim(-2.1, 2.1)
        ax.set_aspect("equal")
        ax.set_xlabel("x, east (m)")
        ax.set_ylabel("y, north (m)")
        ax.legend(loc="lower left", fontsize=8, ncol=3, framealpha=0.9)

        self._blit = BlitList(ax, [self.truth, self.estimate, self.robot, self.text])

    def blit_artists(self) -> list:
        """What :meth:`show` changes and what a full draw paints over it there (the frame;
        the legend when a path runs under it), in drawing order: a panel redraws only these
        over a picture of the rest (the arena's limits are fixed)."""
        return self._blit()

    def show(self, truth: ArrayLike, estimate: ArrayLike | None = None, text: str = "") -> None:
        """Draw a true path (N, 3), an optional estimate, the robot at the path's end."""
        truth = np.asarray(truth, dtype=float)
        self.truth.set_data(truth[:, 0], truth[:, 1])
        if estimate is None or len(estimate) == 0:
            self.estimate.set_data([], [])
        else:
            estimate = np.asarray(estimate, dtype=float)
            self.estimate.set_data(estimate[:, 0], estimate[:, 1])
        self.robot.set_xy(_robot_outline(truth[-1]))
        self.text.set_text(text)


def _setup():
    fig, ax = plt.subplots(figsize=(4.8, 4.8), layout=fixed_layout())
    view = LabView(ax)
    ax.set_title("Closed-loop lap (fast kinematic skid-steer model)", fontsize=10)
    fig.tight_layout()
    return fig, view


def _update(view: LabView, *, speed, lookahead, heading_gain, encoder, track) -> list:
    try:
        truth, estimate, text = _lap_picture(round(float(speed), 4), round(float(lookahead), 4),
                                             round(float(heading_gain), 4), int(encoder),
                                             float(track))
    except ValueError as exc:  # pragma: no cover - every slider value is valid
        view.show(np.array([[1.5, -1.5, math.pi / 2]]), text=f"cannot run: {exc}")
    else:
        view.show(truth, estimate, text)
    return view.blit_artists()  # the panel blits these


@register("waypoints.lab")
def lab_panel() -> Panel:
    """Sliders for the closed-loop lap: speed, look-ahead, heading gain, encoders, track."""
    style = {"description_width": "150px"}
    layout = widgets.Layout(width="460px")
    controls = {
        "speed": widgets.FloatSlider(value=0.3, min=0.1, max=0.5, step=0.05,
                                     description="cruise speed (m/s)", style=style,
                                     layout=layout),
        "lookahead": widgets.FloatSlider(value=0.15, min=0.05, max=0.5, step=0.05,
                                         description="look-ahead (m)", style=style,
                                         layout=layout),
        "heading_gain": widgets.FloatSlider(value=4.0, min=1.0, max=10.0, step=1.0,
                                            description="turn gain k_θ (1/s)", style=style,
                                            layout=layout),
        "encoder": widgets.Dropdown(options=ENCODER_CHOICES, value=0,
                                    description="encoders", style=style, layout=layout),
        "track": widgets.Dropdown(options=TRACK_CHOICES, value=EFFECTIVE_TRACK,
                                  description="odometry track", style=style, layout=layout),
    }
    return Panel(controls, _setup, _update,
                 title="The waypoint lab, closed loop: change the follower and the sensors")
