"""Live panels and drawings of the mecanum chapter (notebooks/04_mecanum.ipynb).

- :func:`draw_mecanum`: a top-down drawing of the vehicle (body, wheels, rollers as seen from
  above, heading arrow) that can be moved in place, for panels and animations.
- :func:`animate_poses`: a kernel-free animation of a recorded or predicted run.
- Panels (registered): ``mecanum.wheel_rates`` (drive by four wheel speeds),
  ``mecanum.waypoint`` (go to a point while turning to a heading), ``mecanum.circle`` (the
  circle mode, heading held or rotating). Each enforces the document's 15 ft/s top speed with
  :func:`wheelkin.mecanum.limit_speed` and prints what it did.

Our frame (x forward, y left), SI; wheel order FL, FR, RL, RR.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import ipywidgets as widgets
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.patches import Polygon
from matplotlib.ticker import MaxNLocator
from numpy.typing import ArrayLike, NDArray

from wheelkin import _validate as V
from wheelkin import frames
from wheelkin.mecanum import (
    DOCUMENT_MAX_SPEED,
    EXAMPLE_GEOMETRY,
    WHEEL_NAMES,
    MecanumGeometry,
    SpeedLimit,
    circle_twist,
    fighting_component,
    forward_kinematics,
    go_to_point_twist,
    limit_speed,
    max_rim_speed,
)
from wheelkin.sandbox.render import SandboxAnimation
from wheelkin.style import fixed_layout
from wheelkin.units import FOOT
from wheelkin.widgets import Panel, register

__all__ = ["MecanumDrawing", "animate_poses", "draw_mecanum", "predicted_path",
           "simulate_go_to_point"]

#: Colour of a slipping wheel (as in the sandbox's drawings).
SLIP_COLOUR = "#d62728"
_POS_SIGNS = {"FL": (1, 1), "FR": (1, -1), "RL": (-1, 1), "RR": (-1, -1)}


def _rect(cx: float, cy: float, half_x: float, half_y: float) -> np.ndarray:
    return np.array([[cx - half_x, cy - half_y], [cx + half_x, cy - half_y],
                     [cx + half_x, cy + half_y], [cx - half_x, cy + half_y]])


class MecanumDrawing:
    """Artists of one drawn vehicle; :meth:`update` moves them to a new pose in place.

    Few artists (a body polygon, one collection for the wheels, one for the rollers, the
    heading arrow), so that a panel redraws quickly.
    """

    def __init__(self, ax: Axes, geometry: MecanumGeometry, pose: ArrayLike = (0.0, 0.0, 0.0), *,
                 color: str = "C0", alpha: float = 1.0, rollers: bool = True,
                 label_wheels: bool = False, zorder: int = 3) -> None:
        g = geometry
        r, a, b, gamma = g.wheel_radius, g.half_wheelbase, g.half_track, g.roller_angle
        wheel_half_width = 0.4 * r
        body_half_y = max(b - wheel_half_width - 0.15 * r, 0.3 * b)
        self._body_pts = _rect(0.0, 0.0, a + 0.8 * r, body_half_y)
        self._body = Polygon(self._body_pts, closed=True, facecolor=color, alpha=0.25 * alpha,
                             edgecolor=color, lw=1.2, zorder=zorder)
        ax.add_patch(self._body)
        wheels, segments, self.labels = [], [], []
        for name in WHEEL_NAMES:
            sx, sy = _POS_SIGNS[name]
            cx, cy = sx * a, sy * b
            wheels.append(_rect(cx, cy, r, wheel_half_width))
            # upper rollers (what you see from above): FL, RR along (sin g, cos g);
            # FR, RL along (sin g, -cos g): an "X" pointing at the centre
            sign = 1.0 if name in ("FL", "RR") else -1.0
            d = np.array([math.sin(gamma), sign * math.cos(gamma)])
            half = 0.5 * wheel_half_width / max(abs(d[1]), 0.3)
            for off in np.linspace(-0.65 * r, 0.65 * r, 4):
                c = np.array([cx + off, cy])
                segments.append(np.array([c - half * d, c + half * d]))
            if label_wheels:
                txt = ax.text(0, 0, name, ha="center", va="center", fontsize=8,
                              zorder=zorder + 3)
                self.labels.append((txt, np.array([cx + sx * 1.7 * r, cy])))
        self._wheel_pts = np.array(wheels)
        self._wheels = PolyCollection(self._wheel_pts, facecolors="0.25", edgecolors="k",
                                      linewidths=0.8, alpha=0.85 * alpha, zorder=zorder + 1)
        ax.add_collection(self._wheels)
        self._roller_pts = np.array(segments)
        self._rollers = None
        if rollers:
            self._rollers = LineCollection(self._roller_pts, colors="0.85", linewidths=1.0,
                                           alpha=alpha, zorder=zorder + 2)
            ax.add_collection(self._rollers)
        self._arrow_pts = np.array([[0.0, 0.0], [a + 0.8 * r, 0.0]])
        (self._arrow,) = ax.plot(*self._arrow_pts.T, color=color, lw=1.5, alpha=alpha,
                                 zorder=zorder + 2, marker=(3, 0, -90), markevery=[1],
                                 ms=6)
        self.update(pose)

    @property
    def artists(self) -> list:
        """Every artist of the drawing (what moves when :meth:`update` is called)."""
        out = [self._body, self._wheels, self._arrow] + [txt for txt, _ in self.labels]
        return out + ([self._rollers] if self._rollers is not None else [])

    def update(self, pose: ArrayLike, slipping: ArrayLike | None = None) -> None:
        """Move every artist to ``pose`` (x m, y m, theta rad); paint slipping wheels red.

        ``slipping``: four booleans (FL, FR, RL, RR), or None to leave the colours alone.
        """
        x, y, th = (float(c) for c in pose)
        c, s = math.cos(th), math.sin(th)
        rot = np.array([[c, -s], [s, c]])
        shift = np.array([x, y])
        self._body.set_xy(self._body_pts @ rot.T + shift)
        self._wheels.set_verts(self._wheel_pts @ rot.T + shift)
        if self._rollers is not None:
            self._rollers.set_segments(self._roller_pts @ rot.T + shift)
        w = self._arrow_pts @ rot.T + shift
        self._arrow.set_data(w[:, 0], w[:, 1])
        self._arrow.set_marker((3, 0, math.degrees(th) - 90))
        for txt, pt in self.labels:
            txt.set_position(pt @ rot.T + shift)
        if slipping is not None:
            self._wheels.set_facecolors([SLIP_COLOUR if slip else "0.25" for slip in slipping])
            if self._rollers is not None:  # 4 rollers per wheel, FL, FR, RL, RR
                self._rollers.set_colors([SLIP_COLOUR if slip else "0.85"
                                          for slip in slipping for _ in range(4)])


def draw_mecanum(ax: Axes, geometry: MecanumGeometry = EXAMPLE_GEOMETRY,
                 pose: ArrayLike = (0.0, 0.0, 0.0), **kwargs: Any) -> MecanumDrawing:
    """Draw the vehicle top-down at ``pose``; returns a handle with ``.update(pose)``.

    Keyword arguments: ``color``, ``alpha``, ``rollers`` (draw the upper rollers),
    ``label_wheels`` (write FL, FR, RL, RR), ``zorder``.
    """
    return MecanumDrawing(ax, geometry, pose, **kwargs)


def predicted_path(twist: ArrayLike, duration: float, n: int = 121,
                   start: ArrayLike = (0.0, 0.0, 0.0)) -> np.ndarray:
    """Poses (n, 3) reached by holding the body ``twist`` for 0..``duration`` s (exact arcs)."""
    t = np.linspace(0.0, duration, n)
    deltas = frames.se2_exp(np.outer(t, np.asarray(twist, dtype=float)), 1.0)
    return frames.compose(np.asarray(start, dtype=float), deltas)


def simulate_go_to_point(
        start: ArrayLike, goal: ArrayLike, speed: float, max_omega: float, *,
        geometry: MecanumGeometry = EXAMPLE_GEOMETRY, max_speed: float = DOCUMENT_MAX_SPEED,
        dt: float = 1 / 60, max_time: float = 30.0,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], SpeedLimit | None]:
    """Drive from ``start`` to ``goal`` with the sampled go-to-point law, limited each step.

    Returns (t (N,), poses (N, 3), twists (N-1, 3), worst): ``worst`` is the
    :class:`~wheelkin.mecanum.SpeedLimit` of the step that had to be scaled most, or None if
    the limit was never reached.
    """
    pose = np.asarray(start, dtype=float)
    goal = np.asarray(goal, dtype=float)
    poses, twists, worst = [pose], [], None
    for _ in range(int(max_time / dt)):
        tw = go_to_point_twist(pose, goal, speed, max_omega, dt=dt)
        if not np.any(tw):
            break
        lim = limit_speed(tw, max_speed, geometry)
        if lim.scale < (1.0 if worst is None else worst.scale):
            worst = lim
        twists.append(np.array(lim.twist))
        pose = frames.compose(pose, frames.se2_exp(np.array(lim.twist), dt))
        poses.append(pose)
    poses_arr = np.array(poses)
    t = np.arange(len(poses_arr)) * dt
    return t, poses_arr, np.array(twists).reshape(-1, 3), worst


def animate_poses(geometry: MecanumGeometry, poses: np.ndarray, *, plan: ArrayLike | None = None,
                  plan_label: str = "predicted", path_label: str = "path",
                  extra_paths: Mapping[str, ArrayLike] | None = None, frames_count: int = 60,
                  title: str | None = None, texts: Sequence[str] | None = None,
                  limits: tuple[tuple[float, float], tuple[float, float]] | None = None,
                  slipping: ArrayLike | None = None, figsize: tuple[float, float] = (6.7, 4.2),
                  dpi: int = 100, legend: str = "upper right",
                  interval: float = 100.0) -> SandboxAnimation:
    """A kernel-free animation of the vehicle moving through ``poses`` (N, 3).

    The axes are drawn once and each frame only redraws the moving artists
    (``wheelkin.sandbox.render.SandboxAnimation``); :func:`wheelkin.animation.show` stores the
    frames as palette PNGs, so a 40-frame player stays near 0.25 MB. ``slipping`` (N, 4) bool:
    wheels drawn red while they slip (e.g. ``Trajectory.slipping`` of a sandbox run).
    ``plan`` (M, 2): drawn dashed, labelled ``plan_label`` (e.g. the predicted path); the
    vehicle's own trail is labelled ``path_label``. ``extra_paths``: {label: (N, 2)}
    drawn progressively with the vehicle (e.g. the sandbox's path). ``texts``: one caption
    string per frame (optional). ``limits``: ((xmin, xmax), (ymin, ymax)). ``legend``:
    "upper right" (inside the axes) or "outside" (right of the axes, never over the vehicle).
    ``interval``: ms between frames, in [1, 60000] (real time: the run's duration over the
    frames).
    """
    V.choice("legend", legend, ("upper right", "outside"))
    interval = V.in_range("interval", interval, 1.0, 60_000.0)
    poses = np.asarray(poses, dtype=float)
    idx = np.linspace(0, len(poses) - 1, frames_count).round().astype(int)
    fig, ax = plt.subplots(figsize=figsize, dpi=dpi, layout=fixed_layout())
    ax.set_aspect("equal")
    ax.grid(True, lw=0.4, alpha=0.5)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    pts = [poses[:, :2]]
    if plan is not None:
        plan = np.asarray(plan, dtype=float)
        ax.plot(plan[:, 0], plan[:, 1], "k--", lw=1, label=plan_label)
        pts.append(plan[:, :2])
    extra = {k: np.asarray(p, dtype=float) for k, p in (extra_paths or {}).items()}
    pts += [p[:, :2] for p in extra.values()]
    if limits is None:
        allp = np.vstack(pts)
        pad = 2.0 * (geometry.half_wheelbase + geometry.wheel_radius)
        lo, hi = allp.min(axis=0) - pad, allp.max(axis=0) + pad
        limits = ((lo[0], hi[0]), (lo[1], hi[1]))
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.xaxis.set_major_locator(MaxNLocator(5))
    ax.yaxis.set_major_locator(MaxNLocator(5))
    (trail,) = ax.plot([], [], "C0-", lw=1.5, label=path_label)
    extra_lines = {}
    for i, (label, _) in enumerate(extra.items()):
        (extra_lines[label],) = ax.plot([], [], f"C{i + 1}-", lw=1.5, label=label)
    car = draw_mecanum(ax, geometry, poses[0])
    if (plan is not None or extra) and legend == "outside":
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, fontsize=8)
    elif plan is not None or extra:
        ax.legend(loc="upper right", fontsize=8)
    if title:
        ax.set_title(title, fontsize=10, loc="left")
    label = fig.text(0.02, 0.02, "", ha="left", va="bottom", fontsize=9,
                     family="monospace")
    fig.subplots_adjust(left=0.1, right=0.97, top=0.93, bottom=0.2)

    def update(k):
        i = idx[k]
        trail.set_data(poses[: i + 1, 0], poses[: i + 1, 1])
        for name, path in extra.items():
            j = min(i, len(path) - 1)
            extra_lines[name].set_data(path[: j + 1, 0], path[: j + 1, 1])
        car.update(poses[i], None if slipping is None else slipping[i])
        if texts is not None:
            label.set_text(texts[k])
        return []

    dynamic = [*car.artists, trail, *extra_lines.values(), label]
    return SandboxAnimation(fig, update, frames=frames_count, interval=interval, blit=False,
                            dynamic=dynamic)


# --------------------------------------------------------------------------------------------
# Panels
# --------------------------------------------------------------------------------------------

def _slider(description, lo, hi, step, value, fmt=".2f"):
    return widgets.FloatSlider(min=lo, max=hi, step=step, value=value,
                               description=description, readout_format=fmt,
                               continuous_update=True,
                               style={"description_width": "initial"})


class _Views:
    """Square views of a panel's axes, chosen from a few sizes.

    The smallest view that holds ``points`` with room for the vehicle: half-size from
    ``halves`` (m), centre on a grid of ``1 / grid`` of that (``grid=None``: on the origin,
    where the vehicle starts). Neighbouring slider values usually get the same view, so the
    axes, ticks and grid stay as they are and the panel redraws only the moving artists over
    a cached picture of the rest (blitting). :meth:`fit` returns a marker (an invisible
    artist) that changes whenever the view does: the panel's update puts it in the list of
    artists it returns, so that the panel notices the change and renders the new axes once
    before blitting again.
    """

    def __init__(self, ax, geometry: MecanumGeometry,
                 halves: tuple = (2, 3, 4, 5, 6, 8, 10, 12), grid: int | None = 4) -> None:
        self.ax = ax
        self.halves = halves
        self.grid = grid
        self.pad = 1.5 * (geometry.half_wheelbase + geometry.wheel_radius)
        self._markers = (Artist(), Artist())
        for marker in self._markers:
            marker.set_visible(False)
        self._which = 0
        self._view: tuple | None = None

    @property
    def marker(self) -> Artist:
        """The current view's marker."""
        return self._markers[self._which]

    def fit(self, points) -> Artist:
        """Show ``points`` (N, >= 2; x and y in m) in the smallest view that holds them."""
        pts = np.asarray(points, dtype=float)[:, :2]
        lo, hi = pts.min(axis=0) - self.pad, pts.max(axis=0) + self.pad
        middle = (lo + hi) / 2
        for half in self.halves:
            if self.grid is None:
                centre = np.zeros(2)
            else:
                centre = np.round(middle / (half / self.grid)) * (half / self.grid)
            if np.all(centre - half <= lo) and np.all(hi <= centre + half):
                break
        else:  # larger than every view: fit it exactly
            half, centre = math.ceil(float(np.max(hi - lo)) / 2), middle
        view = (float(centre[0]) + 0.0, float(centre[1]) + 0.0, float(half))
        if view != self._view:
            self._view = view
            self._which = 1 - self._which
            self.ax.set_xlim(view[0] - half, view[0] + half)
            self.ax.set_ylim(view[1] - half, view[1] + half)
        return self.marker


def _draw_order(artists: list) -> list:
    """``artists`` (listed in the order they were created) in the order a full draw draws
    them: by zorder, creation order among equals (as matplotlib's own sort). A panel's list
    includes the axes' frame (spines): it does not move, but is drawn over the paths."""
    return sorted(artists, key=lambda artist: artist.get_zorder())


class _Memo:
    """``function`` with its most recent results remembered, by arguments (a student drags a
    slider back and forth over the same values; a run is computed once)."""

    def __init__(self, function, size: int = 128) -> None:
        self.function = function
        self.size = size
        self._results: dict = {}

    def __call__(self, *args, **kwargs):
        key = (args, tuple(sorted(kwargs.items())))
        if key in self._results:
            self._results[key] = self._results.pop(key)  # most recently used last
        else:
            self._results[key] = self.function(*args, **kwargs)
            if len(self._results) > self.size:
                del self._results[next(iter(self._results))]
        return self._results[key]


def _message_axes(fig):
    return fig.text(0.02, 0.02, "", fontsize=8, family="monospace", va="bottom")


def _floor_axes(bottom: float):
    """The panels' figure: a 10 m x 10 m floor around the start, metres, equal scale, with
    ``bottom`` of the figure left free for the panel's text."""
    fig, ax = plt.subplots(figsize=(4.9, 4.5), dpi=72,  # fits a 1366 x 768 screen
                           layout=fixed_layout())
    fig.subplots_adjust(bottom=bottom)
    ax.set_aspect("equal")
    ax.grid(True, lw=0.4, alpha=0.5)
    ax.set_xlim(-5, 5)
    ax.set_ylim(-5, 5)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    return fig, ax


@register("mecanum.wheel_rates")
def wheel_rates_panel() -> Panel:
    """Four wheel-rate sliders (rad/s); the predicted path over 2 s and the speed verdict."""
    g = EXAMPLE_GEOMETRY
    duration = 2.0
    spoken = {"FL": "front left", "FR": "front right", "RL": "rear left", "RR": "rear right"}
    controls = {name: _slider(f"{spoken[name]} {name} (rad/s)", -80.0, 80.0, 1.0, value)
                for name, value in zip(WHEEL_NAMES, (10.0, 40.0, 40.0, 10.0), strict=True)}

    def setup():
        fig, ax = _floor_axes(bottom=0.27)
        ax.set_title(f"predicted path over {duration:g} s", fontsize=10)
        start = draw_mecanum(ax, g, (0, 0, 0), color="0.5", alpha=0.5, rollers=False)
        (path,) = ax.plot([], [], "C0-", lw=1.5)
        end = draw_mecanum(ax, g, (0, 0, 0))
        msg = _message_axes(fig)
        # Views about the start: the 2 s path reaches at most 9.1 m (15 ft/s).
        return fig, {"path": path, "end": end, "start": start, "msg": msg, "ax": ax,
                     "views": _Views(ax, g, halves=(3, 6, 10), grid=None),
                     "artists": _draw_order([*start.artists, path, *end.artists, msg,
                                             *ax.spines.values()])}

    def update(state, FL, FR, RL, RR):
        try:
            rates = np.array([FL, FR, RL, RR])
            twist = forward_kinematics(rates, g)
            lim = limit_speed(twist, DOCUMENT_MAX_SPEED, g)
            path = predicted_path(lim.twist, duration)
            state["path"].set_data(path[:, 0], path[:, 1])
            state["views"].fit(path)
            state["end"].update(path[-1])
            c = float(fighting_component(rates))
            vx, vy, w = twist
            lines = [f"vx {vx:+.2f}, vy {vy:+.2f} m/s ({vx / FOOT:+.1f}, {vy / FOOT:+.1f} "
                     f"ft/s), omega {w:+.2f} rad/s",
                     f"fighting {c:+.1f} rad/s" + (": rollers slip" if abs(c) > 1e-9 else ""),
                     _wrap_reason(lim.reason, 66)]
            state["msg"].set_text("\n".join(lines))
        except Exception as exc:  # a panel must never raise
            state["msg"].set_text(f"cannot show this: {exc}")
        return [*state["artists"], state["views"].marker]  # the panel blits these

    return Panel(controls, setup, update, title="Drive by four wheel speeds (FL, FR, RL, RR)")


def _wrap_reason(reason: str, width: int = 62) -> str:
    words, lines, line = reason.split(), [], ""
    for word in words:
        if len(line) + len(word) + 1 > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}".strip()
    lines.append(line)
    return "\n".join(lines)


@register("mecanum.waypoint")
def waypoint_panel() -> Panel:
    """Goal position and heading sliders; the straight path with the vehicle turning on it."""
    g = EXAMPLE_GEOMETRY
    controls = {
        "goal_x": _slider("goal x (m)", -4.0, 4.0, 0.1, 3.0),
        "goal_y": _slider("goal y (m)", -4.0, 4.0, 0.1, 2.0),
        "goal_heading_deg": _slider("goal heading (deg)", -180.0, 180.0, 5.0, 120.0, ".0f"),
        "speed": _slider("speed (m/s)", 0.2, 8.0, 0.1, 2.0),
    }

    def setup():
        fig, ax = _floor_axes(bottom=0.2)
        ghosts = [draw_mecanum(ax, g, (0, 0, 0), color="0.5", alpha=0.35, rollers=False)
                  for _ in range(4)]
        (path,) = ax.plot([], [], "C0-", lw=1.5)
        goal = draw_mecanum(ax, g, (0, 0, 0), color="C3", alpha=0.4, rollers=False)
        car = draw_mecanum(ax, g, (0, 0, 0))
        msg = _message_axes(fig)
        moving = [a for ghost in ghosts for a in ghost.artists]
        return fig, {"path": path, "ghosts": ghosts, "goal": goal, "car": car, "msg": msg,
                     "ax": ax, "views": _Views(ax, g), "runs": _Memo(simulate_go_to_point),
                     "artists": _draw_order([*moving, path, *goal.artists, *car.artists,
                                             *ax.spines.values(), ax.title, msg])}

    def update(state, goal_x, goal_y, goal_heading_deg, speed):
        try:
            goal = (goal_x, goal_y, math.radians(goal_heading_deg))
            t, poses, _, worst = state["runs"]((0, 0, 0), goal, speed, 1.5, dt=0.05)
            state["path"].set_data(poses[:, 0], poses[:, 1])
            state["views"].fit(np.vstack([poses[:, :2], [[-4, -4], [4, 4]]]))
            state["goal"].update(goal)
            for k, ghost in enumerate(state["ghosts"]):
                ghost.update(poses[round((k + 1) * (len(poses) - 1) / 5)])
            state["car"].update(poses[0])
            state["ax"].set_title(f"arrives after {t[-1]:.2f} s", fontsize=10)
            state["msg"].set_text(_wrap_reason(worst.reason) if worst is not None
                                  else "within the 15 ft/s limit all the way")
        except Exception as exc:
            state["msg"].set_text(f"cannot show this: {exc}")
        return [*state["artists"], state["views"].marker]  # the panel blits these

    return Panel(controls, setup, update,
                 title="Waypoint: straight to a point while turning to a heading")


@register("mecanum.circle")
def circle_panel() -> Panel:
    """Radius, lap time and heading mode; the circle, the speed, and the limit's verdict."""
    g = EXAMPLE_GEOMETRY
    controls = {
        "radius": _slider("radius (m)", -4.0, 4.0, 0.1, 2.0),
        "lap_time": _slider("lap time (s)", 0.5, 20.0, 0.1, 5.0),
        "heading": widgets.Dropdown(options=["rotating", "held"], value="rotating",
                                    description="heading"),
        "refuse": widgets.Checkbox(value=False, description="refuse instead of scaling"),
    }

    def setup():
        fig, ax = _floor_axes(bottom=0.22)
        (path,) = ax.plot([], [], "C0-", lw=1.5)
        ghosts = [draw_mecanum(ax, g, (0, 0, 0), color="0.5", alpha=0.35, rollers=False)
                  for _ in range(7)]
        car = draw_mecanum(ax, g, (0, 0, 0))
        msg = _message_axes(fig)
        moving = [a for ghost in ghosts for a in ghost.artists]
        return fig, {"path": path, "ghosts": ghosts, "car": car, "ax": ax, "msg": msg,
                     "views": _Views(ax, g), "runs": _Memo(_circle_run),
                     "artists": _draw_order([path, *moving, *car.artists,
                                             *ax.spines.values(), ax.title, msg])}

    def update(state, radius, lap_time, heading, refuse):
        try:
            if abs(radius) < 1e-9:
                raise ValueError("radius must be non-zero")
            text, poses, lap = state["runs"](g, radius, lap_time, heading, refuse)
            state["path"].set_data(poses[:, 0], poses[:, 1])
            state["views"].fit(poses)
            for k, ghost in enumerate(state["ghosts"]):
                ghost.update(poses[round((k + 1) * (len(poses) - 1) / 8)])
            state["car"].update(poses[0])
            state["ax"].set_title(f"{heading} heading; lap {lap:.2f} s" if lap
                                  else "refused: not driven", fontsize=10)
            state["msg"].set_text(text)
        except Exception as exc:
            state["msg"].set_text(f"cannot show this: {exc}")
        return [*state["artists"], state["views"].marker]  # the panel blits these

    return Panel(controls, setup, update, title="Circle mode")


def _circle_run(g, radius, lap_time, heading, refuse, n=241):
    """(message, poses over one lap, actual lap time or 0 if refused) for the circle mode."""
    t = np.linspace(0.0, lap_time, n)
    # the fastest moment of the lap: rotating heading is constant; held heading peaks when
    # the velocity is diagonal to the body
    twists = circle_twist(radius, lap_time, t, heading=heading)
    worst = twists[int(np.argmax(max_rim_speed(*twists.T, g)))]
    lim = limit_speed(worst, DOCUMENT_MAX_SPEED, g, refuse=refuse)
    speed = 2 * math.pi * abs(radius) / lap_time
    head = f"speed {speed:.2f} m/s = {speed / FOOT:.1f} ft/s\n"
    if lim.scale == 0.0:
        return head + _wrap_reason(lim.reason), np.zeros((1, 3)), 0.0
    lap = lap_time / lim.scale
    dt = lap / (n - 1)
    tw = circle_twist(radius, lap, (np.arange(n - 1) + 0.5) * dt, heading=heading)
    poses = frames.integrate_twist(tw, dt)
    return head + _wrap_reason(lim.reason), poses, lap
