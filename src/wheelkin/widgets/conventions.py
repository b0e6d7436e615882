r"""Chapter 1's live panel and its kernel-free twin (notebooks/01_conventions).

:class:`TwistView` draws a rectangular body in our world frame (x east to the right of the
page, y north up, metres) driven by a constant twist :math:`(v_x, v_y, \omega)`: the path of
its reference point, ghost outlines along it, the instantaneous centre of rotation (ICR), the
velocity of each corner (perpendicular to the line from the ICR) and the same twist in the
mecanum simulator's and the rover document's units. ``update(vx, vy, omega)`` moves the
artists in place; the panel ``conventions.twist_icr`` drives it with three sliders, and
:func:`twist_animation` shows the body turning about its ICR without a kernel.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import ipywidgets as widgets
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrowPatch, Polygon
from numpy.typing import ArrayLike

from wheelkin import frames, sources
from wheelkin.style import fixed_layout
from wheelkin.widgets import Panel, register

__all__ = ["TwistView", "angle_arc", "arrow", "body_axes", "draw_vehicle", "turn_arrow",
           "twist_animation", "twist_icr_panel"]

BODY_LENGTH = 0.6  # m, along body x
BODY_WIDTH = 0.4  # m, along body y
HORIZON = 4.0  # s of path drawn ahead
LIMIT = 2.5  # m, half the side of the plotted square
ARROW_SCALE = 1.0  # s: an arrow is the distance a corner moves in this time
_CORNERS = np.array([[BODY_LENGTH / 2, BODY_WIDTH / 2], [BODY_LENGTH / 2, -BODY_WIDTH / 2],
                     [-BODY_LENGTH / 2, -BODY_WIDTH / 2], [-BODY_LENGTH / 2, BODY_WIDTH / 2]])
_NOSE = np.array([[BODY_LENGTH / 2, 0.0], [BODY_LENGTH / 2 - 0.15, 0.1],
                  [BODY_LENGTH / 2 - 0.15, -0.1]])


class TwistView:
    """A body in our world frame under a constant twist, with its ICR and corner velocities.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Empty axes to draw in.
    start : Pose
        Pose of the body at t = 0 (default: the origin, heading 0).
    ghosts : int
        Number of outlines drawn along the path ahead.
    """

    def __init__(self, ax: Axes, start: frames.Pose | None = None, ghosts: int = 3) -> None:
        self.ax = ax
        self.start = start or frames.Pose(0.0, 0.0, 0.0)
        ax.set_xlim(-LIMIT, LIMIT)
        ax.set_ylim(-LIMIT, LIMIT)
        ax.set_aspect("equal")
        ax.set_xticks([-2.0, 0.0, 2.0])  # few tick labels: text is most of a redraw's time
        ax.set_yticks([-2.0, 0.0, 2.0])
        ax.grid(True, lw=0.3, alpha=0.5)
        ax.set_xlabel("world x (m, east)")
        ax.set_ylabel("world y (m, north)")
        self.path = ax.plot([], [], color="#1f77b4", lw=1.2, zorder=2)[0]
        self.ghosts = [ax.add_patch(Polygon(np.zeros((4, 2)), closed=True, fc="none",
                                            ec="#1f77b4", lw=0.8, ls="--", alpha=0.6,
                                            zorder=2)) for _ in range(ghosts)]
        self.body = ax.add_patch(Polygon(np.zeros((4, 2)), closed=True, fc="#dddddd",
                                         ec="#333333", lw=1.2, zorder=4))
        self.nose = ax.add_patch(Polygon(np.zeros((3, 2)), closed=True, fc="#333333",
                                         zorder=5))
        self.axes_x = ax.plot([], [], color="#d62728", lw=1.5, zorder=6)[0]
        self.axes_y = ax.plot([], [], color="#2ca02c", lw=1.5, zorder=6)[0]
        self.radii = [ax.plot([], [], color="#888888", lw=0.6, ls=":", zorder=3)[0]
                      for _ in range(4)]
        self.arrows = ax.quiver(np.zeros(4), np.zeros(4), np.zeros(4), np.zeros(4),
                                angles="xy", scale_units="xy", scale=1.0 / ARROW_SCALE,
                                color="#9467bd", width=0.006, zorder=7)
        self.icr = ax.plot([], [], marker="o", ms=7, color="k", ls="none", zorder=8)[0]
        self.icr_label = ax.text(0, 0, "", fontsize=9, ha="left", va="bottom", zorder=8)
        self.info = ax.text(0.02, 0.98, "", transform=ax.transAxes, ha="left", va="top",
                            fontsize=8, family="monospace", zorder=9,
                            bbox={"fc": "white", "ec": "#cccccc", "alpha": 0.9})
        self.message = ax.text(0.5, 0.5, "", transform=ax.transAxes, ha="center",
                               va="center", color="#b35900", fontsize=10, zorder=10,
                               bbox={"fc": "white", "ec": "#b35900"})
        self.message.set_visible(False)
        # Everything update() moves, in drawing order: a panel redraws only these over a
        # cached picture of the rest (the limits and ticks above never change).
        self.artists = sorted([self.path, *self.ghosts, self.body, self.nose, self.axes_x,
                               self.axes_y, *self.radii, self.arrows, self.icr,
                               self.icr_label, self.info, self.message,
                               *ax.spines.values()],  # the frame: drawn over the path
                              key=lambda artist: artist.get_zorder())

    def _outline(self, pose: frames.Pose, points: np.ndarray) -> np.ndarray:
        return frames.transform_points(pose, points)

    def draw_body(self, pose: frames.Pose, twist: frames.Twist) -> None:
        """Move the body, its axes, corner arrows and radii to ``pose``."""
        self.body.set_xy(self._outline(pose, _CORNERS))
        self.nose.set_xy(self._outline(pose, _NOSE))
        origin = self._outline(pose, np.array([[0.0, 0.0], [0.35, 0.0], [0.0, 0.35]]))
        self.axes_x.set_data(origin[[0, 1], 0], origin[[0, 1], 1])
        self.axes_y.set_data(origin[[0, 2], 0], origin[[0, 2], 1])
        corners = self._outline(pose, _CORNERS)
        body_vel = frames.point_velocity(twist, _CORNERS)  # body frame
        c, s = math.cos(pose.theta), math.sin(pose.theta)
        world_vel = np.column_stack([c * body_vel[:, 0] - s * body_vel[:, 1],
                                     s * body_vel[:, 0] + c * body_vel[:, 1]])
        self.arrows.set_offsets(corners)
        self.arrows.set_UVC(world_vel[:, 0], world_vel[:, 1])
        centre = frames.icr(twist)
        if centre is None:
            for line in self.radii:
                line.set_data([], [])
            self.icr.set_data([], [])
            return
        world_icr = frames.transform_points(pose, np.array(centre))
        for line, corner in zip(self.radii, corners, strict=True):
            line.set_data([corner[0], world_icr[0]], [corner[1], world_icr[1]])
        self.icr.set_data([world_icr[0]], [world_icr[1]])

    def update(self, vx: float, vy: float, omega: float) -> list:
        """Show the body at the start pose under the twist ``(vx, vy, omega)`` (SI).

        Returns :attr:`artists`, the artists it may change (for a blitting panel)."""
        try:
            twist = frames.Twist(vx, vy, omega)
        except ValueError as exc:  # never raise in a panel: say what is wrong instead
            self.message.set_text(str(exc)[:80])
            self.message.set_visible(True)
            return self.artists
        self.message.set_visible(False)
        n = 80
        poses = frames.integrate_twist(np.tile(twist.as_array(), (n, 1)), HORIZON / n,
                                       self.start)
        self.path.set_data(poses[:, 0], poses[:, 1])
        for k, ghost in enumerate(self.ghosts, start=1):
            pose = frames.Pose(*poses[k * n // len(self.ghosts)])
            ghost.set_xy(self._outline(pose, _CORNERS))
        self.draw_body(self.start, twist)
        centre = frames.icr(twist)
        if centre is None:
            where = "at rest: no ICR" if vx == 0 and vy == 0 else "ICR at infinity"
            self.icr_label.set_text("")
        else:
            world = frames.transform_points(self.start, np.array(centre))
            inside = bool(np.all(np.abs(world) < LIMIT))
            where = f"ICR ({centre[0]:+.2f}, {centre[1]:+.2f}) m"
            self.icr_label.set_position((float(np.clip(world[0], -LIMIT, LIMIT)) + 0.05,
                                         float(np.clip(world[1], -LIMIT, LIMIT)) + 0.05))
            self.icr_label.set_text("ICR" if inside else "")
        vx_doc, vy_doc, w_doc = sources.ours_to_mecanum_doc_twist(twist)
        lines = ["ours (m/s, rad/s):", f"  vx = {vx:+.2f}  vy = {vy:+.2f}",
                 f"  ω  = {omega:+.2f}", f"  {where}",
                 "mecanum sim. (ft/s):",
                 f"  Vx = {vx_doc + 0.0:+.2f}  Vy = {vy_doc + 0.0:+.2f}",
                 f"  ω  = {w_doc + 0.0:+.2f}", "rover document:"]
        if vy == 0 and omega != 0 and vx != 0:
            r_in = sources.ours_to_rover_radius(vx / omega)
            side = "right" if r_in > 0 else "left"
            lines.append(f"  r_OSR = {r_in:+.1f} in ({side})")
        elif vy == 0 and omega == 0:
            lines.append("  r_OSR = ±inf (straight)")
        else:
            lines.append("  no radius (vy ≠ 0 or spin)")
        self.info.set_text("\n".join(lines))
        return self.artists


def _text_beside(view: TwistView, fig) -> None:
    """In a wide figure: the square plot on the left, the text box on its right."""
    view.ax.set_position([0.09, 0.11, 0.55, 0.86])
    view.info.set_transform(fig.transFigure)
    view.info.set_position((0.66, 0.92))


def _figure(figsize=(5.0, 5.0), dpi=100):
    fig = plt.figure(figsize=figsize, dpi=dpi, layout=fixed_layout())
    fig.subplots_adjust(left=0.13, right=0.97, bottom=0.1, top=0.97)
    return fig


@register("conventions.twist_icr")
def twist_icr_panel() -> Panel:
    """Sliders for vx, vy (m/s) and omega (rad/s); the figure shows path, ICR and velocities."""
    style = {"description_width": "130px"}
    layout = widgets.Layout(width="420px")
    controls = {
        "vx": widgets.FloatSlider(value=0.5, min=-1.0, max=1.0, step=0.05,
                                  description="forward vx (m/s)", style=style, layout=layout),
        "vy": widgets.FloatSlider(value=0.0, min=-1.0, max=1.0, step=0.05,
                                  description="left vy (m/s)", style=style, layout=layout),
        "omega": widgets.FloatSlider(value=0.5, min=-2.0, max=2.0, step=0.05,
                                     description="yaw rate ω (rad/s)", style=style,
                                     layout=layout),
    }

    def setup():
        # A Figure outside pyplot: the panel redraws it itself, and pyplot never shows it again
        # under a later cell.
        fig = Figure(figsize=(6.7, 4.4), dpi=100, layout=fixed_layout())
        view = TwistView(fig.add_subplot(1, 1, 1))
        _text_beside(view, fig)
        return fig, view

    def update(view, vx, vy, omega):
        return view.update(vx, vy, omega)  # the moving artists: the panel blits them

    return Panel(controls, setup, update, dpi=100,
                 title="A constant twist: the path, the ICR and the corner velocities")


def twist_animation(twist: frames.Twist | None = None, frames_count: int = 40,
                    figsize: tuple[float, float] = (6.7, 4.4), dpi: int = 100) -> FuncAnimation:
    """The body turning once about its ICR under a constant ``twist`` (one full turn).

    The ICR stays fixed in the world while the body turns about it; every corner's velocity
    stays perpendicular to its line from the ICR.
    """
    twist = twist or frames.Twist(0.5, 0.2, 0.6)
    if twist.omega == 0:
        raise ValueError("twist.omega must be non-zero for a full turn about the ICR")
    if not 2 <= frames_count <= 200:
        raise ValueError(f"frames_count must be in [2, 200], got {frames_count!r}")
    fig = _figure(figsize, dpi)
    view = TwistView(fig.add_subplot(1, 1, 1), ghosts=0)
    if figsize[0] > 1.2 * figsize[1]:  # a wide frame: the square plot left, the text right
        _text_beside(view, fig)
    period = 2 * math.pi / abs(twist.omega)
    n = frames_count
    poses = frames.integrate_twist(np.tile(twist.as_array(), (n, 1)), period / n, view.start)
    trail = view.path
    centre = frames.transform_points(view.start, np.array(frames.icr(twist)))
    view.icr_label.set_position((centre[0] + 0.05, centre[1] + 0.05))
    view.icr_label.set_text("ICR")
    title = view.info

    def draw(k):
        pose = frames.Pose(*poses[k])
        view.draw_body(pose, twist)
        trail.set_data(poses[: k + 1, 0], poses[: k + 1, 1])
        title.set_text(f"vx = {twist.vx:+.2f} m/s\nvy = {twist.vy:+.2f} m/s\n"
                       f"ω  = {twist.omega:+.2f} rad/s\nt  = {k * period / n:4.1f} s")
        return []

    draw(0)
    return FuncAnimation(fig, draw, frames=n, interval=100, blit=False)


# ------------------------------------------------------------------ chapter 1's drawings
def arrow(ax: Axes, start: Sequence[float] | np.ndarray, end: Sequence[float] | np.ndarray,
          colour: str, label: str | None = None, offset: tuple[float, float] = (0.0, 0.0),
          lw: float = 1.8, fontsize: float = 11, **kw: Any) -> None:
    """An arrow from ``start`` to ``end`` with an optional label at its tip (+ ``offset``)."""
    ax.annotate("", xy=end, xytext=start,
                arrowprops={"arrowstyle": "-|>", "color": colour, "lw": lw, **kw})
    if label:
        ax.text(end[0] + offset[0], end[1] + offset[1], label, color=colour, fontsize=fontsize,
                ha="center", va="center")


def draw_vehicle(ax: Axes, pose: frames.Pose | ArrayLike, length: float, width: float,
                 wheels: Mapping[str, tuple[float, float]],
                 wheel_size: tuple[float, float] = (0.22, 0.08), body_colour: str = "#e6e6e6",
                 labels: bool = True, fontsize: float = 8,
                 label_shift: Mapping[str, tuple[float, float]] | None = None) -> None:
    """A rectangle with wheels; ``wheels`` maps a label to a body-frame position (x fwd, y left)."""
    corners = np.array([[length / 2, width / 2], [length / 2, -width / 2],
                        [-length / 2, -width / 2], [-length / 2, width / 2]])
    ax.add_patch(Polygon(frames.transform_points(pose, corners), closed=True, fc=body_colour,
                         ec="#444444", lw=1.0, zorder=2))
    wl, ww = wheel_size
    for name, (px, py) in wheels.items():
        outline = np.array([[wl / 2, ww / 2], [wl / 2, -ww / 2], [-wl / 2, -ww / 2],
                            [-wl / 2, ww / 2]]) + np.array([px, py])
        ax.add_patch(Polygon(frames.transform_points(pose, outline), closed=True,
                             fc="#555555", ec="k", lw=0.6, zorder=3))
        if labels:
            out = 1.0 if py >= 0 else -1.0
            shift = (label_shift or {}).get(name, (0.0, 0.0))
            lx, ly = frames.transform_points(
                pose, np.array([px + shift[0], py + out * (ww / 2 + 0.14) + shift[1]]))
            ax.text(lx, ly, name, fontsize=fontsize, ha="center", va="center", zorder=4)


def body_axes(ax: Axes, pose: frames.Pose, size: float, names: Sequence[str] = ("$x$", "$y$"),
              colours: Sequence[str] = ("#d62728", "#2ca02c"), lw: float = 1.8,
              directions: Sequence[tuple[float, float]] = ((1.0, 0.0), (0.0, 1.0)),
              label_gap: float = 1.25, **kw: Any) -> None:
    """A body frame's two axes at ``pose``, ``size`` long, labelled beyond their tips."""
    origin = np.array([pose.x, pose.y])
    for name, colour, d in zip(names, colours, directions, strict=True):
        end = frames.transform_points(pose, size * np.array(d))
        arrow(ax, origin, end, colour, lw=lw, **kw)
        tip = frames.transform_points(pose, size * label_gap * np.array(d))
        ax.text(tip[0], tip[1], name, color=colour, ha="center", va="center", fontsize=11)


def angle_arc(ax: Axes, centre: Sequence[float] | np.ndarray, radius: float, start: float,
              end: float, colour: str, label: str, label_radius: float | None = None,
              lw: float = 1.2) -> None:
    """An arrowed arc from angle ``start`` to ``end`` (rad) about ``centre``, labelled."""
    t = np.linspace(start, end, 40)
    ax.plot(centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t), color=colour, lw=lw)
    ax.annotate("", xy=(centre[0] + radius * np.cos(t[-1]), centre[1] + radius * np.sin(t[-1])),
                xytext=(centre[0] + radius * np.cos(t[-3]), centre[1] + radius * np.sin(t[-3])),
                arrowprops={"arrowstyle": "-|>", "color": colour, "lw": lw})
    mid = (start + end) / 2
    lr = label_radius or radius * 1.25
    ax.text(centre[0] + lr * np.cos(mid), centre[1] + lr * np.sin(mid), label, color=colour,
            ha="center", va="center", fontsize=11)


def turn_arrow(ax: Axes, centre: Sequence[float] | np.ndarray, radius: float, start: float,
               end: float, colour: str, label: str, label_pos: tuple[float, float]) -> None:
    """A curved arrow showing a sense of rotation, labelled at ``label_pos``."""
    a = (centre[0] + radius * np.cos(start), centre[1] + radius * np.sin(start))
    b = (centre[0] + radius * np.cos(end), centre[1] + radius * np.sin(end))
    rad = 0.45 if end > start else -0.45
    ax.add_patch(FancyArrowPatch(a, b, connectionstyle=f"arc3,rad={rad}", arrowstyle="-|>",
                                 mutation_scale=12, color=colour, lw=1.4, zorder=5))
    ax.text(*label_pos, label, color=colour, ha="center", va="center", fontsize=10)
