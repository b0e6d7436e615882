"""The rover chapter's live panel and its kernel-free twin (notebooks/03_rover/).

:class:`RoverView` draws the Open Source Rover from above (forward up the page, its right to
the right of the page, inches) with its six wheels at their steering angles, the turning
centre (ICR), the arc each wheel rolls along while the rover turns through the same angle,
and bars of the six wheel speeds. Corner angles are labelled in the book's sign: delta > 0
turns the wheel to the LEFT (counter-clockwise seen from above); the document's delta_OSR is
-delta. ``update(command, speed)`` moves the artists in place; the panel ``rover.steering``
drives it with two sliders and :func:`sweep_animation` sweeps the command from -100 to 100 for
the HTML book.
"""

from __future__ import annotations

import math

import ipywidgets as widgets
import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Polygon

from wheelkin import rover
from wheelkin.style import fixed_layout
from wheelkin.widgets import Panel, register

__all__ = ["RoverView", "steering_panel", "sweep_animation"]

WHEEL_LENGTH = 4.7  # in, the wheel diameter assumed in the chapter (the document gives none)
WHEEL_WIDTH = 2.0   # in
ARC_LENGTH = 24.0   # in travelled by the outer middle wheel along the drawn arcs
_XLIM = (-42.0, 42.0)  # screen x: the rover's right, in
_YLIM = (-22.0, 40.0)  # screen y: the rover's forward, in
_COLOURS = ("#1f77b4", "#1f77b4", "#1f77b4", "#d62728", "#d62728", "#d62728")
_CORNER_OF_WHEEL = {0: 0, 3: 1, 2: 2, 5: 3}  # wheel index -> corner index (LF, RF, LB, RB)


def _screen(points: np.ndarray) -> np.ndarray:
    """Body (x forward, y left) -> page (right, forward)."""
    points = np.asarray(points, dtype=float)
    return np.stack([-points[..., 1], points[..., 0]], axis=-1)


class RoverView:
    """A top-down drawing of the rover with wheel arcs, the ICR and wheel-speed bars.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        An empty figure; two axes are added (the rover, the wheel speeds).
    geometry : wheelkin.rover.RoverGeometry
    mapping : str
        How the command becomes a radius (see :func:`wheelkin.rover.command_to_radius`).
    """

    def __init__(self, fig: Figure, geometry: rover.RoverGeometry = rover.OSR_GEOMETRY,
                 mapping: str = "radius") -> None:
        self.geometry = geometry
        self.mapping = mapping
        self.fig = fig
        gs = fig.add_gridspec(1, 2, width_ratios=(1.55, 1.0), wspace=0.3)
        ax = self.ax = fig.add_subplot(gs[0])
        bx = self.bx = fig.add_subplot(gs[1])
        ax.set_xlim(*_XLIM)
        ax.set_ylim(*_YLIM)
        ax.set_aspect("equal")
        ax.set_xlabel("to the rover's right (in)")
        ax.set_ylabel("forward (in)")
        ax.set_xticks([-40, -20, 0, 20, 40])
        ax.set_yticks([-20, 0, 20, 40])
        self.pos = rover.wheel_positions(geometry)
        scr = _screen(self.pos)
        g = geometry
        body = _screen(np.array([[g.d3 + 2, g.d1 - 2], [g.d3 + 2, -(g.d1 - 2)],
                                 [-g.d2 - 2, -(g.d1 - 2)], [-g.d2 - 2, g.d1 - 2]]))
        self.body = ax.add_patch(Polygon(body, closed=True, fc="#dddddd", ec="#555555", lw=1.0,
                                         zorder=2))
        self.centre_mark = ax.plot([0], [0], marker="+", color="k", ms=8, zorder=5)[0]
        self.arcs = [ax.plot([], [], color=c, lw=1.0, alpha=0.8, zorder=1)[0] for c in _COLOURS]
        self.rays = [ax.plot([], [], color="#888888", lw=0.6, ls="--", zorder=1)[0]
                     for _ in range(6)]
        self.centre_arc = ax.plot([], [], color="k", lw=1.0, ls=":", zorder=3)[0]
        self.wheels = []
        for i in range(6):
            patch = Polygon(np.zeros((4, 2)), closed=True, fc=_COLOURS[i], ec="k", lw=0.8,
                            zorder=4)
            ax.add_patch(patch)
            self.wheels.append(patch)
        # One label per wheel: its number, and for a corner its steering angle.
        self.labels = []
        for px, py in scr:
            left = px < 0
            self.labels.append(ax.text(px + (-2.2 if left else 2.2), py, "", fontsize=8,
                                       ha="right" if left else "left", va="center",
                                       zorder=6))
        for i, label in enumerate(self.labels):
            if i not in _CORNER_OF_WHEEL:
                label.set_text(str(i + 1))
        self.icr = ax.plot([], [], marker="o", color="k", ms=5, zorder=6, ls="none")[0]
        self.icr_text = ax.text(0, 0, "", fontsize=8, ha="center", va="top", zorder=6)
        self.title = ax.set_title("", fontsize=9, loc="left")
        self.message = ax.text(0.5, 0.5, "", transform=ax.transAxes, ha="center",
                               va="center", color="#b35900", fontsize=10, zorder=10,
                               bbox={"fc": "white", "ec": "#b35900"})
        # Wheel-speed bars.
        labels = [f"{i + 1}\n{n}" for i, n in enumerate(rover.WHEEL_NAMES)]
        self.bars = bx.bar(range(6), np.zeros(6), color=_COLOURS, edgecolor="k", lw=0.6)
        bx.set_xticks(range(6), labels, fontsize=8)
        bx.set_ylim(0, 110)
        bx.set_yticks([0, 50, 100])
        bx.set_ylabel("wheel speed (% of full)")
        bx.axhline(0, color="k", lw=0.6)
        self.centre_line = bx.axhline(0, color="k", lw=1.0, ls=":")
        # The body centre's speed is named in the title, never over the bars' values.
        self.centre_text = bx.set_title("", fontsize=9)
        self.bar_text = [bx.text(i, 0, "", ha="center", va="bottom", fontsize=8)
                         for i in range(6)]
        # Everything update() moves, in drawing order: a panel redraws only these over a
        # cached picture of the rest (fixed limits, so the axes never change). The body, its
        # centre mark, the middle wheels' labels and the frame do not change, but are drawn
        # over the rays and arcs, so they are redrawn too.
        self.artists = sorted(
            [self.body, self.centre_mark, *self.arcs, *self.rays, self.centre_arc, *self.wheels,
             *self.labels, self.icr, self.icr_text, *ax.spines.values(), self.title,
             self.message, *self.bars, self.centre_line, self.centre_text, *self.bar_text],
            key=lambda artist: artist.get_zorder())

    # ------------------------------------------------------------------ drawing helpers
    def _wheel_outline(self, i: int, steer_rep103: float) -> np.ndarray:
        c, s = math.cos(steer_rep103), math.sin(steer_rep103)
        half_l, half_w = WHEEL_LENGTH / 2, WHEEL_WIDTH / 2
        corners = np.array([[half_l, half_w], [half_l, -half_w], [-half_l, -half_w],
                            [-half_l, half_w]])
        rot = corners @ np.array([[c, s], [-s, c]])
        return _screen(self.pos[i] + rot)

    def update(self, command: float, speed: float) -> list:
        """Show the rover steered by ``command`` (-100..100) at ``speed`` (% of full).

        Returns :attr:`artists`, the artists it may change (for a blitting panel)."""
        try:
            radius = rover.command_to_radius(command, mapping=self.mapping,
                                             geometry=self.geometry)
            speeds = rover.wheel_speeds(radius, speed, self.geometry)
            angles = rover.corner_angles(radius, self.geometry)
            centre = float(rover.centre_speed(radius, speed, self.geometry))
        except ValueError as exc:  # never raise in a panel: say what is wrong instead
            self.message.set_text(str(exc)[:80])
            self.message.set_visible(True)
            return self.artists
        self.message.set_visible(False)
        straight = not np.any(angles)
        steer = np.zeros(6)
        for i, k in _CORNER_OF_WHEEL.items():
            steer[i] = -angles[k]  # the book's delta (left positive) = -delta_OSR
        for i, patch in enumerate(self.wheels):
            patch.set_xy(self._wheel_outline(i, steer[i]))
        for i in _CORNER_OF_WHEEL:
            shown = round(math.degrees(steer[i]), 1) + 0.0  # never "−0.0°"
            angle = f"{shown:+.1f}°".replace("-", "−")
            self.labels[i].set_text(f"{angle} {i + 1}" if i < 3 else f"{i + 1} {angle}")
        scr = _screen(self.pos)
        if straight:
            for i, line in enumerate(self.arcs):
                x0, y0 = scr[i]
                line.set_data([x0, x0], [y0, y0 + ARC_LENGTH])
            for ray in self.rays:
                ray.set_data([], [])
            self.centre_arc.set_data([0, 0], [0, ARC_LENGTH])
            self.icr.set_data([], [])
            self.icr_text.set_text("ICR at infinity")
            self.icr_text.set_position((0, _YLIM[0] + 5))
            self.title.set_text(f"command {command:+.0f}: straight")
        else:
            icr = np.array([radius, 0.0])  # page coordinates: r to the right
            sign = 1.0 if radius > 0 else -1.0
            theta = ARC_LENGTH / (abs(radius) + self.geometry.d4)
            t = np.linspace(0.0, theta, 40)
            rot_c, rot_s = np.cos(-sign * t), np.sin(-sign * t)
            for i, line in enumerate(self.arcs):
                rel = scr[i] - icr
                line.set_data(icr[0] + rot_c * rel[0] - rot_s * rel[1],
                              icr[1] + rot_s * rel[0] + rot_c * rel[1])
            rel = -icr
            self.centre_arc.set_data(icr[0] + rot_c * rel[0] - rot_s * rel[1],
                                     icr[1] + rot_s * rel[0] + rot_c * rel[1])
            for i, ray in enumerate(self.rays):
                ray.set_data([scr[i, 0], icr[0]], [scr[i, 1], icr[1]])
            if _XLIM[0] < radius < _XLIM[1]:
                self.icr.set_data([radius], [0.0])
                self.icr_text.set_position((radius, -2.0))
                self.icr_text.set_text("ICR")
            else:
                self.icr.set_data([], [])
                edge = _XLIM[1] - 12 if radius > 0 else _XLIM[0] + 12
                arrow = "→" if radius > 0 else "←"
                self.icr_text.set_position((edge, -2.0))
                self.icr_text.set_text(f"ICR {abs(radius):.0f} in {arrow}")
            side = "right" if radius > 0 else "left"
            self.title.set_text(f"command {command:+.0f}: r = {abs(radius):.1f} in to the "
                                f"{side}")
        for i, bar in enumerate(self.bars):
            bar.set_height(speeds[i])
            self.bar_text[i].set_position((i, max(speeds[i], 0.0) + 1.0))
            self.bar_text[i].set_text(f"{speeds[i]:.0f}")
        self.centre_line.set_ydata([centre, centre])
        self.centre_text.set_text(f"body centre (dotted): {centre:.0f}")
        return self.artists


def _figure(figsize=(6.7, 3.5), dpi=100) -> Figure:
    # A figure unknown to pyplot: the inline backend never shows it by itself (a live panel
    # renders it into its own image; an animation into its HTML player).
    fig = Figure(figsize=figsize, dpi=dpi, layout=fixed_layout())
    FigureCanvasAgg(fig)
    fig.subplots_adjust(left=0.09, right=0.99, bottom=0.15, top=0.92)
    return fig


@register("rover.steering")
def steering_panel() -> Panel:
    """Sliders: the steering command (-100..100) and the speed (0..100 % of full)."""
    controls = {
        "command": widgets.IntSlider(value=60, min=-100, max=100, step=1,
                                     description="command", continuous_update=True),
        "speed": widgets.IntSlider(value=100, min=0, max=100, step=5,
                                   description="speed (%)", continuous_update=True),
    }

    def setup():
        fig = _figure()
        return fig, RoverView(fig)

    def update(view: RoverView, command: int, speed: int) -> list:
        return view.update(command, speed)  # the moving artists: the panel blits them

    return Panel(controls, setup, update, dpi=100,
                 title="Open Source Rover: steering command and speed")


def sweep_animation(frames: int = 33, speed: float = 100.0, *, mapping: str = "radius",
                    figsize: tuple[float, float] = (6.7, 3.5), dpi: int = 100,
                    interval: int = 250) -> FuncAnimation:
    """The steering command swept from -100 to 100 in ``frames`` steps (0 included when
    ``frames`` is odd), as a FuncAnimation for :func:`wheelkin.animation.show`."""
    commands = np.linspace(-100.0, 100.0, frames)
    fig = _figure(figsize, dpi)
    view = RoverView(fig, mapping=mapping)

    def draw(k: int):
        view.update(float(commands[k]), speed)
        return []

    draw(0)
    return FuncAnimation(fig, draw, frames=len(commands), interval=interval, blit=False)
