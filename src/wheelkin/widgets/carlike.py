"""The car-like chapter's live panels and their kernel-free twins (notebooks/09_carlike).

:class:`SteeringView` draws a vehicle from above (x forward to the right of the page, y left up
the page, metres) with its wheels at their steering angles, the line of each wheel's axle
(dashed), the rear (or middle) axle line, and the turning centre the rear wheels impose; a bar
chart beside it compares each steered wheel's angle with the angle that would make it roll
without sliding. ``update(delta_deg, geometry)`` moves the artists in place.

- panel ``carlike.steering``: a steering slider and the geometry (ideal Ackermann, the
  trapezoidal linkage, parallel steer) of the 1/10 car;
  :func:`steering_animation` sweeps the steering for the HTML book;
- panel ``carlike.rover``: the Open Source Rover's four-corner steering beside a car of the
  same wheelbase and track (:func:`rover_animation`);
- panel ``carlike.pure_pursuit``: a look-ahead point and the arc pure pursuit steers along
  (:func:`pursuit_animation`).
"""

from __future__ import annotations

import math

import ipywidgets as widgets
import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.figure import Figure
from matplotlib.patches import Polygon

from wheelkin import carlike, rover, units
from wheelkin.sandbox.car import RC_CAR_MAX_STEERING, Steering, front_angles
from wheelkin.style import fixed_layout
from wheelkin.widgets import Panel, register

__all__ = ["PursuitView", "SteeringView", "pursuit_animation", "pursuit_panel",
           "rover_animation", "rover_panel", "steering_animation", "steering_panel"]

CAR_L, CAR_W, CAR_R = 0.33, 0.27, 0.05
_GEOMETRY_NAMES = {"ackermann": "ideal Ackermann", "linkage": "trapezoidal linkage",
                   "parallel": "parallel steer"}
_STEERED = "#d62728"
_FIXED = "#555555"
#: deg, the reach of the angle-error bars: parallel steer's inner wheel is 4.6° off at full lock
_ERROR_LIMIT = 5.0


def _wheel_outline(x, y, angle, length, width):
    c, s = math.cos(angle), math.sin(angle)
    pts = [(-length / 2, -width / 2), (length / 2, -width / 2), (length / 2, width / 2),
           (-length / 2, width / 2)]
    return [(x + c * px - s * py, y + s * px + c * py) for px, py in pts]


class SteeringView:
    """Top view of a vehicle's wheels and axle lines, and a bar chart of angle errors.

    Parameters
    ----------
    fig : Figure
        An empty figure; two axes are added.
    vehicle : {"car", "rover"}
        The 1/10 car (FL, FR steered; RL, RR fixed) or the OSR (four corners steered, the
        middle wheels fixed), in metres.
    """

    def __init__(self, fig: Figure, vehicle: str = "car") -> None:
        self.vehicle = vehicle
        if vehicle == "car":
            self.positions = {"FL": (CAR_L, CAR_W / 2), "FR": (CAR_L, -CAR_W / 2),
                              "RL": (0.0, CAR_W / 2), "RR": (0.0, -CAR_W / 2)}
            self.steered = ("FL", "FR")
            wheel_len = 2 * CAR_R
            # symmetric: the turning centre at full lock (0.74 m), and where parallel steer's
            # outer axle line meets the rear one (0.88 m), in view on either side
            xlim, ylim = (-0.25, 0.6), (-1.0, 1.0)
        else:
            g = rover.OSR_GEOMETRY
            d1, d2, d3, d4 = (v * units.INCH for v in (g.d1, g.d2, g.d3, g.d4))
            self.positions = {"LF": (d3, d1), "RF": (d3, -d1), "LB": (-d2, d1),
                              "RB": (-d2, -d1), "LM": (0.0, d4), "RM": (0.0, -d4)}
            self.steered = ("LF", "RF", "LB", "RB")
            wheel_len = 0.12
            # symmetric: the turning centre at 45° (0.45 m) in view on either side
            xlim, ylim = (-0.45, 0.45), (-0.8, 0.8)
        self.fig = fig
        gs = fig.add_gridspec(1, 2, width_ratios=(1.35, 1.0), wspace=0.45, left=0.1,
                              right=0.97, bottom=0.14, top=0.86)
        ax = self.ax = fig.add_subplot(gs[0])
        bx = self.bx = fig.add_subplot(gs[1])
        ax.set_xlim(*xlim)
        ax.set_ylim(*ylim)
        ax.set_aspect("equal")
        ax.set_xlabel("x, forward (m)")
        ax.set_ylabel("y, left (m)")
        ax.grid(True, lw=0.3, alpha=0.5)
        xs = [p[0] for p in self.positions.values()]
        ax.add_patch(Polygon([(min(xs) - 0.03, -0.1), (max(xs) + 0.03, -0.1),
                              (max(xs) + 0.03, 0.1), (min(xs) - 0.03, 0.1)],
                             closed=True, fc="#eeeeee", ec="#888888", lw=0.8, zorder=1))
        ax.axhline(0.0, color="#bbbbbb", lw=0.6, zorder=0)
        ax.axvline(0.0, color="#555555", lw=0.9, ls="-", zorder=1)
        self.wheels = {}
        self.lines = {}
        for name, (x, y) in self.positions.items():
            colour = _STEERED if name in self.steered else _FIXED
            self.wheels[name] = ax.add_patch(Polygon(_wheel_outline(x, y, 0.0, wheel_len, 0.03),
                                                     closed=True, fc=colour, ec="k", lw=0.6,
                                                     zorder=4))
            if name in self.steered:
                self.lines[name] = ax.plot([], [], color=_STEERED, lw=0.8, ls="--",
                                           zorder=2)[0]
        self.wheel_len = wheel_len
        self.icr = ax.plot([], [], marker="o", color="k", ms=5, ls="none", zorder=5)[0]
        self.centre = ""  # the turning centre, said in the title (over the view it hides a wheel)
        n = len(self.steered)
        self.bars = bx.barh(np.arange(n), np.zeros(n), height=0.6, color=_STEERED)
        bx.set_yticks(np.arange(n), self.steered, fontsize=9)
        bx.invert_yaxis()
        bx.set_xlim(-_ERROR_LIMIT, _ERROR_LIMIT)
        bx.axvline(0, color="k", lw=0.6)
        bx.set_xlabel("angle error (deg)")
        # each value is written on the side away from its bar (update() moves it)
        self.bar_text = [bx.text(-_ERROR_LIMIT + 0.1, i, "", fontsize=9, va="center",
                                 ha="left") for i in range(n)]
        self.title = fig.suptitle("", fontsize=10, y=0.98)

    def angles(self, delta: float, geometry: str) -> dict[str, float]:
        """Steering angles (rad) of the steered wheels for the command ``delta`` (rad)."""
        if self.vehicle == "car":
            fl, fr = front_angles(Steering(geometry), delta, CAR_L, CAR_W)
            return {"FL": fl, "FR": fr}
        # The rover: delta is the inner front corner's angle; the others from its centre.
        if delta == 0:
            return dict.fromkeys(self.steered, 0.0)
        x, y = self.positions["LF" if delta > 0 else "RF"]
        radius = y + x / math.tan(delta)
        return {n: math.atan(self.positions[n][0] / (radius - self.positions[n][1]))
                for n in self.steered}

    def update(self, delta_deg: float, geometry: str = "ackermann") -> None:
        delta = math.radians(delta_deg)
        angles = self.angles(delta, geometry)
        for name, (x, y) in self.positions.items():
            a = angles.get(name, 0.0)
            self.wheels[name].set_xy(_wheel_outline(x, y, a, self.wheel_len, 0.03))
        # The turning centre the fixed wheels allow: on their axle line (x = 0), where the
        # bicycle / ideal geometry puts it.
        if delta == 0:
            radius = math.inf
        elif self.vehicle == "car":
            radius = CAR_L / math.tan(delta)
        else:
            x, y = self.positions["LF" if delta > 0 else "RF"]
            radius = y + x / math.tan(delta)
        errors = []
        for name in self.steered:
            x, y = self.positions[name]
            a = angles[name]
            n = (-math.sin(a), math.cos(a))
            far = 3.0
            self.lines[name].set_data([x - far * n[0], x + far * n[0]],
                                      [y - far * n[1], y + far * n[1]])
            ideal = 0.0 if math.isinf(radius) else math.atan(x / (radius - y))
            errors.append(math.degrees(a - ideal))
        if math.isinf(radius):
            self.icr.set_data([], [])
            self.centre = "straight ahead"
        else:
            self.icr.set_data([0.0], [radius])
            # Only ideal geometry has one turning centre; otherwise the dot is the centre the
            # rear wheels impose, the bicycle's.
            whose = "" if geometry == "ackermann" else "bicycle's "
            self.centre = f"{whose}turning centre at y = {radius:.2f} m"
            if self.vehicle != "car":  # the rover's chapter works in inches
                self.centre += f" ({radius / 0.0254:.1f} in)"
        for bar, text, e in zip(self.bars, self.bar_text, errors, strict=True):
            bar.set_width(max(-_ERROR_LIMIT, min(_ERROR_LIMIT, e)))
            shown = round(e, 2) + 0.0  # never "-0.00°"
            text.set_text(f"{shown:+.2f}°")
            if shown > 0:  # a bar to the right: its value at the left end of the axis
                text.set_x(-_ERROR_LIMIT + 0.1)
                text.set_horizontalalignment("left")
            else:
                text.set_x(_ERROR_LIMIT - 0.1)
                text.set_horizontalalignment("right")
        label = _GEOMETRY_NAMES[geometry] if self.vehicle == "car" else "OSR four corners"
        self.title.set_text(f"{label}, steering {delta_deg:+.1f}°: {self.centre}")


def _steering_setup(vehicle):
    def setup():
        fig = Figure(figsize=(6.7, 3.9), dpi=100, layout=fixed_layout())
        return fig, SteeringView(fig, vehicle)
    return setup


def steering_panel() -> Panel:
    """Sliders: the bicycle steering angle and the front geometry of the 1/10 car."""
    top = round(math.degrees(RC_CAR_MAX_STEERING))
    controls = {
        "delta_deg": widgets.FloatSlider(value=15.0, min=-top, max=top, step=0.5,
                                         description="steering δ (deg)"),
        "geometry": widgets.Dropdown(options=[(v, k) for k, v in _GEOMETRY_NAMES.items()],
                                     value="ackermann", description="geometry"),
    }
    return Panel(controls, _steering_setup("car"),
                 lambda view, delta_deg, geometry: view.update(delta_deg, geometry),
                 title="Steering geometry of the 1/10 car", dpi=100)


def rover_panel() -> Panel:
    """A slider for the OSR's inner front corner angle."""
    controls = {"delta_deg": widgets.FloatSlider(value=25.0, min=-45.0, max=45.0, step=0.5,
                                                 description="corner δ (deg)")}
    return Panel(controls, _steering_setup("rover"),
                 lambda view, delta_deg: view.update(delta_deg),
                 title="The OSR's corners and its turning centre", dpi=100)


register("carlike.steering")(steering_panel)
register("carlike.rover")(rover_panel)


def steering_animation(geometry: str = "ackermann", frames: int = 36,
                       vehicle: str = "car") -> FuncAnimation:
    """The steering swept from one limit to the other and back (kernel-free twin)."""
    fig = Figure(figsize=(6.7, 3.9), dpi=100, layout=fixed_layout())
    view = SteeringView(fig, vehicle)
    top = math.degrees(RC_CAR_MAX_STEERING) if vehicle == "car" else 45.0
    values = top * np.sin(np.linspace(0.0, 2 * math.pi, frames, endpoint=False) + 0.3)

    def frame(k):
        view.update(float(values[k]), geometry)

    frame(0)
    return FuncAnimation(fig, frame, frames=frames)


def rover_animation(frames: int = 36) -> FuncAnimation:
    """The OSR's corner steering swept (kernel-free twin of ``carlike.rover``)."""
    return steering_animation("ackermann", frames, vehicle="rover")


class PursuitView:
    """The car at the origin, a look-ahead point, and the arc pure pursuit steers along."""

    def __init__(self, fig: Figure) -> None:
        ax = self.ax = fig.add_subplot(1, 1, 1)
        fig.subplots_adjust(left=0.12, right=0.97, bottom=0.13, top=0.9)
        ax.set_xlim(-0.3, 1.6)
        ax.set_ylim(-1.05, 1.05)  # the look-ahead point of the sweep (at most 0.92 m) in view
        ax.set_aspect("equal")
        ax.set_xlabel("x, forward (m)")
        ax.set_ylabel("y, left (m)")
        ax.grid(True, lw=0.3, alpha=0.5)
        for name, (x, y) in {"RL": (0.0, CAR_W / 2), "RR": (0.0, -CAR_W / 2)}.items():
            ax.add_patch(Polygon(_wheel_outline(x, y, 0.0, 0.1, 0.03), closed=True,
                                 fc=_FIXED, ec="k", lw=0.6, zorder=4))
            del name
        self.front = [ax.add_patch(Polygon(_wheel_outline(CAR_L, s * CAR_W / 2, 0.0, 0.1, 0.03),
                                           closed=True, fc=_STEERED, ec="k", lw=0.6, zorder=4))
                      for s in (1, -1)]
        ax.plot([0, CAR_L], [0, 0], color="#888888", lw=1.0, zorder=3)
        self.arc = ax.plot([], [], color="#1f77b4", lw=1.6, zorder=2)[0]
        self.chord = ax.plot([], [], color="#888888", lw=0.8, ls=":", zorder=2)[0]
        self.goal = ax.plot([], [], marker="*", ms=12, color="#ff7f0e", ls="none",
                            zorder=5)[0]
        # The numbers beside the view, clear of the arc and the star at every bearing: the
        # view keeps to the left of the figure.
        ax.set_anchor("W")
        self.text = ax.text(1.04, 0.97, "", transform=ax.transAxes, va="top", ha="left",
                            fontsize=9,
                            bbox={"fc": "white", "ec": "none", "alpha": 0.85, "pad": 1})
        self.title = ax.set_title("", fontsize=10)

    def update(self, lookahead: float, bearing_deg: float) -> None:
        b = math.radians(bearing_deg)
        gx, gy = lookahead * math.cos(b), lookahead * math.sin(b)
        kappa = carlike.pure_pursuit_curvature(gx, gy)
        delta = carlike.steering_from_curvature(kappa, wheelbase=CAR_L)
        clipped = max(-RC_CAR_MAX_STEERING, min(RC_CAR_MAX_STEERING, delta))
        s = np.linspace(0.0, 2.5 * lookahead, 200)
        if abs(kappa) < 1e-9:
            xs, ys = s, 0 * s
        else:
            th = s * kappa
            xs, ys = np.sin(th) / kappa, (1 - np.cos(th)) / kappa
        self.arc.set_data(xs, ys)
        self.chord.set_data([0, gx], [0, gy])
        self.goal.set_data([gx], [gy])
        fl, fr = front_angles(Steering(), clipped, CAR_L, CAR_W)
        for patch, a, sgn in zip(self.front, (fl, fr), (1, -1), strict=True):
            patch.set_xy(_wheel_outline(CAR_L, sgn * CAR_W / 2, a, 0.1, 0.03))
        note = " (beyond the steering limit)" if clipped != delta else ""
        self.text.set_text(f"$\\kappa = 2y/L_d^2$ = {kappa:+.2f} 1/m"
                           f"\nδ = {math.degrees(delta):+.1f}°"
                           + note)
        self.title.set_text(f"look-ahead $L_d$ = {lookahead:.2f} m at {bearing_deg:+.0f}°")


def pursuit_panel() -> Panel:
    """Sliders: the look-ahead distance and the bearing of the look-ahead point."""
    controls = {
        "lookahead": widgets.FloatSlider(value=0.8, min=0.2, max=1.5, step=0.05,
                                         description="look-ahead L_d (m)"),
        "bearing_deg": widgets.FloatSlider(value=20.0, min=-60.0, max=60.0, step=1.0,
                                           description="bearing (deg)"),
    }

    def setup():
        fig = Figure(figsize=(6.7, 4.2), dpi=100, layout=fixed_layout())
        return fig, PursuitView(fig)

    return Panel(controls, setup, lambda view, lookahead, bearing_deg:
                 view.update(lookahead, bearing_deg), title="Pure pursuit", dpi=100)


register("carlike.pure_pursuit")(pursuit_panel)


def pursuit_animation(frames: int = 36) -> FuncAnimation:
    """The look-ahead point swept across the bearing at two distances (kernel-free twin)."""
    fig = Figure(figsize=(6.7, 4.2), dpi=100, layout=fixed_layout())
    view = PursuitView(fig)
    half = frames // 2
    bearings = np.concatenate([np.linspace(-50, 50, half), np.linspace(50, -50, frames - half)])
    dists = np.concatenate([np.full(half, 0.5), np.full(frames - half, 1.2)])

    def frame(k):
        view.update(float(dists[k]), float(bearings[k]))

    frame(0)
    return FuncAnimation(fig, frame, frames=frames)
