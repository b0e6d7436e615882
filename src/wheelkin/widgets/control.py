"""The control chapter's helpers, its live panel and the panel's kernel-free twin
(notebooks/11_control).

Runs (used by the chapter's sections and by ``benchmarks/control.py``):

- :func:`start_grid`: start poses on a square grid of positions around the goal, each with
  several headings;
- :func:`unicycle_commands`: a stack of twists limited as the Zumo's wheels limit them (the
  wheel speeds scaled together, so the curvature is kept);
- :func:`car_commands`: a stack of twists as a car's speed and steering angle (the curvature
  clipped at the steering limit);
- :func:`sandbox_runs`: many robots, one per start, driven by one feedback law on their true
  poses in one sandbox world (far apart, so they never meet), with a control period;
- :func:`converged`: which final poses are within a distance and an angle of the goal;
- :func:`draw_starts`: a map of start poses, an arrow each, coloured by the outcome.

The panel ``control.pose`` drives the unicycle (the kinematic model, :func:`wheelkin.control
.simulate`) from a start pose to the goal with the pose controller; sliders set the three gains
and the start. :func:`pose_animation` sweeps the start heading for the HTML book.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import ipywidgets as widgets
import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Polygon
from numpy.typing import ArrayLike, NDArray

from wheelkin import control, frames
from wheelkin.sandbox import World
from wheelkin.sandbox.car import RC_CAR_MAX_STEERING, drive
from wheelkin.sandbox.vehicles import VehicleSpec
from wheelkin.style import fixed_layout
from wheelkin.widgets import Panel, register

__all__ = ["CORKE_GAINS", "GOAL", "PoseView", "car_commands", "converged", "draw_starts",
           "figure_eight",
           "pose_animation", "pose_panel", "sandbox_runs", "start_grid", "unicycle_commands"]

#: The chapter's goal: the origin, heading along +x.
GOAL = (0.0, 0.0, 0.0)
#: Corke's gains (k_rho, k_alpha, k_beta), 1/s.
CORKE_GAINS = (3.0, 8.0, -3.0)
#: The Zumo's track width (m) and the chapter's wheel-speed limit (m/s).
ZUMO_TRACK = 0.085
MAX_WHEEL_SPEED = 0.3

_OK, _BAD = "#2ca02c", "#d62728"


def start_grid(positions: int = 5, half_width: float = 0.5,
               headings: int = 8) -> NDArray[np.float64]:
    """Start poses: a ``positions`` x ``positions`` grid over [-half_width, half_width]² m
    (the goal's own position left out), each with ``headings`` headings evenly spaced from
    -180° (shape (N, 3))."""
    xs = np.linspace(-half_width, half_width, positions)
    angles = np.linspace(-math.pi, math.pi, headings, endpoint=False)
    return np.array([(x, y, th) for x in xs for y in xs for th in angles
                     if math.hypot(x, y) > 1e-9])


def figure_eight(t: ArrayLike, half_width: float = 0.6,
                 lap_time: float = 40.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    r"""A reference trajectory: Gerono's lemniscate (a figure eight) through the origin.

    :math:`x = a\sin\phi`, :math:`y = \tfrac{a}{2}\sin 2\phi`, :math:`\phi = 2\pi t/T`,
    driven counter-clockwise round the right loop first. Returns the reference poses (..., 3)
    (heading in :math:`(-\pi, \pi]`) and twists (..., 3) :math:`(v_r, 0, \omega_r)`,
    :math:`v_r = |\dot{\mathbf p}|`, :math:`\omega_r = (\dot x\ddot y - \dot y\ddot x)/v_r^2`
    (the speed never vanishes: :math:`\dot x` and :math:`\dot y` are never zero together).
    """
    time = np.asarray(t, dtype=float)
    a, rate = float(half_width), 2.0 * math.pi / float(lap_time)
    phi = rate * time
    dx, dy = a * np.cos(phi) * rate, a * np.cos(2 * phi) * rate
    ddx, ddy = -a * np.sin(phi) * rate**2, -2 * a * np.sin(2 * phi) * rate**2
    speed2 = dx * dx + dy * dy
    heading = np.arctan2(dy, dx)
    poses = np.stack([a * np.sin(phi), 0.5 * a * np.sin(2 * phi), heading], axis=-1)
    twists = np.stack([np.sqrt(speed2), np.zeros_like(speed2), (dx * ddy - dy * ddx) / speed2],
                      axis=-1)
    return poses, twists


def unicycle_commands(twists: ArrayLike, track_width: float = ZUMO_TRACK,
                      max_wheel_speed: float = MAX_WHEEL_SPEED) -> NDArray[np.float64]:
    r"""Twists (N, 3) as a differential drive can follow them: the wheel speeds
    :math:`v \\mp \\omega W/2` scaled together so that neither exceeds the limit (the path's
    curvature is kept; :func:`wheelkin.diffdrive.desaturate`); ``vy`` is dropped."""
    tw = np.atleast_2d(np.asarray(twists, dtype=float))
    left = tw[:, 0] - tw[:, 2] * track_width / 2
    right = tw[:, 0] + tw[:, 2] * track_width / 2
    biggest = np.maximum(np.abs(left), np.abs(right))
    scale = np.where(biggest > max_wheel_speed, max_wheel_speed / np.maximum(biggest, 1e-300),
                     1.0)
    return np.stack([tw[:, 0] * scale, np.zeros(len(tw)), tw[:, 2] * scale], axis=-1)


def car_commands(twists: ArrayLike, wheelbase: float = 0.33,
                 max_steering: float = RC_CAR_MAX_STEERING,
                 max_speed: float = 0.5) -> NDArray[np.float64]:
    r"""Twists (N, 3) as a car can follow them: the speed limited to ``max_speed`` and the
    curvature :math:`\\omega/v` clipped to :math:`\\pm\\tan\\delta_{max}/L`; at zero speed the
    car cannot turn. Returns (speed, 0, yaw rate) rows; the steering angle is
    :math:`\\arctan(L\\,\\omega/v)`."""
    tw = np.atleast_2d(np.asarray(twists, dtype=float))
    v = np.clip(tw[:, 0], -max_speed, max_speed)
    kappa_max = math.tan(max_steering) / wheelbase
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = np.where(tw[:, 0] != 0, tw[:, 2] / np.where(tw[:, 0] != 0, tw[:, 0], 1.0), 0.0)
    kappa = np.clip(kappa, -kappa_max, kappa_max)
    return np.stack([v, np.zeros(len(tw)), v * kappa], axis=-1)


def sandbox_runs(spec: VehicleSpec, starts: ArrayLike,
                 law: Callable[[float, np.ndarray], np.ndarray], duration: float, *,
                 period: float = 0.02, dt: float = 1 / 200, record_every: int = 10,
                 spacing: float = 6.0, camera_noise: tuple[float, float] = (0.0, 0.0),
                 seed: int = 0) -> list:
    """Drive one robot per start pose in one sandbox world by one feedback law.

    The robots stand ``spacing`` metres apart (each start and its goal shifted together), so
    that they never meet; every ``period`` seconds the law gets the stack of true poses,
    expressed as if every robot drove alone from its start to the chapter's goal, and returns
    the commands: for a car ``(speed, 0, yaw rate)`` rows that :func:`wheelkin.sandbox.car
    .drive` turns into a steering angle; for a differential drive the twists the robots are
    commanded (hold between periods). ``camera_noise`` = (m, rad) adds independent normal
    noise of these standard deviations to every pose the law sees (an overhead camera; drawn
    from ``numpy.random.default_rng(seed)``). Returns one :class:`~wheelkin.sandbox.Trajectory`
    per start, its poses shifted back to the start's frame (headings unwrapped).
    """
    rng = np.random.default_rng(seed)
    noise_scale = np.array([camera_noise[0], camera_noise[0], camera_noise[1]], dtype=float)
    starts = np.atleast_2d(np.asarray(starts, dtype=float))
    n = len(starts)
    side = math.ceil(math.sqrt(n))
    offsets = np.array([(spacing * (i % side), spacing * (i // side), 0.0) for i in range(n)])
    world = World(dt=dt)
    robots = [world.add(spec, pose=tuple(s + o)) for s, o in zip(starts, offsets, strict=True)]
    is_car = bool(spec.steered_names)
    wheelbase = max(w.position[0] for w in spec.wheels) if is_car else 0.0
    state = {"next": 0.0}

    def controller(t, _world):
        if t < state["next"]:
            return
        state["next"] += period
        poses = np.array([tuple(r.pose) for r in robots]) - offsets
        if np.any(noise_scale > 0):
            poses = poses + rng.standard_normal(poses.shape) * noise_scale
        commands = np.asarray(law(t, poses), dtype=float)
        for robot, (v, _, w) in zip(robots, commands, strict=True):
            if is_car:
                delta = math.atan(wheelbase * w / v) if v != 0 else 0.0
                drive(robot, float(v), delta)
            else:
                robot.command_twist(float(v), 0.0, float(w))

    runs = world.run(duration, controller, record_every=record_every)
    runs = runs if isinstance(runs, list) else [runs]
    return [dataclasses.replace(run, pose=run.pose - offset)
            for run, offset in zip(runs, offsets, strict=True)]


def converged(poses: ArrayLike, goal: ArrayLike = GOAL, distance: float = 0.01,
              angle: float = math.radians(1.0)) -> NDArray[np.bool_]:
    """True where a pose is within ``distance`` (m) and ``angle`` (rad) of ``goal``."""
    p = np.asarray(poses, dtype=float)
    g = np.asarray(goal, dtype=float)
    off = np.hypot(p[..., 0] - g[0], p[..., 1] - g[1])
    turn = np.abs(frames.wrap_angle(p[..., 2] - g[2]))
    return (off < distance) & (turn < angle)


def draw_starts(ax: Axes, starts: ArrayLike, ok: ArrayLike, *, length: float = 0.07,
                goal: ArrayLike = GOAL) -> None:
    """Each start pose as a spoke from its position along its heading, ending in a dot,
    green where ``ok``, red where not; the goal as a black arrow. Starts that share a
    position make a star whose colours show which headings succeed."""
    from matplotlib.collections import LineCollection

    s = np.asarray(starts, dtype=float)
    good = np.asarray(ok, dtype=bool)
    tips = s[:, :2] + length * np.column_stack([np.cos(s[:, 2]), np.sin(s[:, 2])])
    for mask, colour in ((good, _OK), (~good, _BAD)):
        if np.any(mask):
            segments = np.stack([s[mask, :2], tips[mask]], axis=1)
            ax.add_collection(LineCollection(segments, colors=colour, linewidths=1.6))
            ax.plot(tips[mask, 0], tips[mask, 1], "o", color=colour, ms=2.5)
    g = np.asarray(goal, dtype=float)
    ax.annotate("", xy=(g[0] + 2 * length * math.cos(g[2]), g[1] + 2 * length * math.sin(g[2])),
                xytext=(g[0], g[1]), arrowprops={"arrowstyle": "-|>", "color": "k", "lw": 2})
    ax.set_aspect("equal")


# ------------------------------------------------------------------------------ the panel

_SIM_SECONDS, _SIM_PERIOD = 12.0, 0.02


def _robot_outline(pose, size=0.06):
    x, y, th = pose
    pts = np.array([(-0.7, -0.5), (0.9, -0.5), (1.3, 0.0), (0.9, 0.5), (-0.7, 0.5)]) * size
    c, s = math.cos(th), math.sin(th)
    return np.column_stack([x + c * pts[:, 0] - s * pts[:, 1], y + s * pts[:, 0] + c * pts[:, 1]])


class PoseView:
    """The unicycle's path from a start to the goal under the pose controller, with the
    start's polar coordinates and the closed loop's eigenvalues written beside it."""

    def __init__(self, fig: Figure) -> None:
        ax = self.ax = fig.add_axes((0.1, 0.12, 0.52, 0.8))
        ax.set_xlim(-1.1, 1.1)
        ax.set_ylim(-1.1, 1.1)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.grid(True, lw=0.3, alpha=0.5)
        ax.plot([0, 0.18], [0, 0], color="k", lw=2.5)
        ax.plot([0], [0], "ko", ms=5)
        self.path = ax.plot([], [], color="#1f77b4", lw=1.8)[0]
        self.back = ax.plot([], [], color="#ff7f0e", lw=1.8)[0]
        self.robot = ax.add_patch(Polygon(_robot_outline((0, 0, 0)), closed=True,
                                          fc="#bbbbbb", ec="k", lw=0.8))
        self.end = ax.add_patch(Polygon(_robot_outline((0, 0, 0)), closed=True, fc="none",
                                        ec="#1f77b4", lw=1.0))
        self.text = fig.text(0.65, 0.9, "", fontsize=9, va="top")
        fig.text(0.65, 0.28, "blue: forwards\norange: backwards\nblack: the goal", fontsize=9,
                 va="top")

    def update(self, k_rho: float, k_alpha: float, k_beta: float, x: float, y: float,
               heading_deg: float) -> list:
        start = (float(x), float(y), math.radians(heading_deg))
        self.robot.set_xy(_robot_outline(start))
        try:
            control.move_to_pose(start, GOAL, k_rho, k_alpha, k_beta)
        except ValueError as exc:
            message = str(exc).split(" (")[0].replace(" must be ", "\nmust be ")
            self.text.set_text("gains refused:\n" + message)
            for line in (self.path, self.back):
                line.set_data([], [])
            self.end.set_visible(False)
            return self.artists
        gains = (k_rho, k_alpha, k_beta)

        def law(t, poses):
            return unicycle_commands(control.move_to_pose(poses, GOAL, *gains))

        path = control.simulate(law, start, _SIM_SECONDS, _SIM_PERIOD)
        commands = law(0.0, path[:-1])
        forward = np.append(commands[:, 0] >= 0, commands[-1, 0] >= 0)
        fwd = np.where(forward[:, None], path[:, :2], np.nan)
        bwd = np.where(~forward[:, None], path[:, :2], np.nan)
        self.path.set_data(fwd[:, 0], fwd[:, 1])
        self.back.set_data(bwd[:, 0], bwd[:, 1])
        self.end.set_xy(_robot_outline(path[-1]))
        self.end.set_visible(True)
        rho, alpha, beta = control.polar_coordinates(start, GOAL)
        lam = np.roots([1.0, k_alpha - k_rho, -k_rho * k_beta])
        if abs(lam[0].imag) > 1e-9:
            poles = f"{lam[0].real:+.2f} ± {abs(lam[0].imag):.2f}j"
        else:
            poles = f"{lam[0].real:+.2f}, {lam[1].real:+.2f}"
        done = bool(converged(path[-1]))
        self.text.set_text(
            f"start: ρ = {rho:.2f} m\n"
            f"α = {math.degrees(alpha):+.0f}°, $\\beta_g$ = {math.degrees(beta):+.0f}°\n\n"
            f"poles: {-k_rho:+.2f}\n{poles}\n\n"
            f"after {_SIM_SECONDS:.0f} s: {'at the goal' if done else 'not there'}")
        return self.artists

    @property
    def artists(self) -> list:
        return [self.path, self.back, self.robot, self.end, self.text]


def _pose_setup():
    fig = Figure(figsize=(6.7, 4.3), dpi=100, layout=fixed_layout())
    return fig, PoseView(fig)


@register("control.pose")
def pose_panel() -> Panel:
    """Sliders: the three gains and the start pose of the pose controller."""
    style = {"description_width": "initial"}
    controls = {
        "k_rho": widgets.FloatSlider(value=3.0, min=0.5, max=6.0, step=0.25,
                                     description="k_rho (1/s)", style=style),
        "k_alpha": widgets.FloatSlider(value=8.0, min=0.5, max=16.0, step=0.5,
                                       description="k_alpha (1/s)", style=style),
        "k_beta": widgets.FloatSlider(value=-3.0, min=-10.0, max=1.0, step=0.25,
                                      description="k_beta (1/s)", style=style),
        "x": widgets.FloatSlider(value=-0.6, min=-1.0, max=1.0, step=0.05,
                                 description="start x (m)", style=style),
        "y": widgets.FloatSlider(value=0.5, min=-1.0, max=1.0, step=0.05,
                                 description="start y (m)", style=style),
        "heading_deg": widgets.FloatSlider(value=90.0, min=-180.0, max=180.0, step=5.0,
                                           description="start heading (deg)", style=style),
    }
    return Panel(controls, _pose_setup, lambda view, **values: view.update(**values),
                 title="Driving to a pose", dpi=100)


def pose_animation(frames_count: int = 36, start_xy: tuple[float, float] = (-0.6, 0.5),
                   gains: tuple[float, float, float] = CORKE_GAINS) -> FuncAnimation:
    """The panel's view with the start heading swept once round (the kernel-free twin)."""
    fig, view = _pose_setup()
    headings = np.linspace(-180.0, 180.0, frames_count, endpoint=False)

    def frame(k):
        view.update(*gains, *start_xy, float(headings[k]))

    frame(0)
    return FuncAnimation(fig, frame, frames=frames_count)
