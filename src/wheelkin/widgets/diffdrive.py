"""The differential-drive chapter's live panels and their kernel-free twin (notebooks/05_diffdrive).

:class:`DiffDriveView` draws the Radon Ulzer from above (forward up the page, its right to the
right of the page, millimetres) with an arrow beside each wheel for its speed, the turning centre
(ICR), and bars of the left and right wheel speeds as three computations give them: the
correct formula, the firmware README's formula as printed, and the firmware's 32-bit integer
computation. ``update(v_steps_per_s, omega_mrad_per_s)`` moves the artists in place.

- panel ``diffdrive.wheel_speeds``: sliders for v (steps/s) and omega (mrad/s);
  :func:`sweep_animation` sweeps omega through the int32 overflow for the HTML book.
- panel ``diffdrive.speedometer``: a wheel at constant speed read by a speedometer with a
  window and a minimum step count (:func:`wheelkin.diffdrive.speed_from_counts`).
"""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.artist import Artist
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrow, Rectangle

from wheelkin import diffdrive as dd
from wheelkin.style import fixed_layout
from wheelkin.widgets import Panel, register

__all__ = ["DiffDriveView", "SpeedometerView", "speedometer_panel", "sweep_animation",
           "wheel_speeds_panel"]

W_MM = dd.RADON_ULZER_CONSTANTS.track_width_mm
ENC = dd.RADON_ULZER_CONSTANTS.steps_per_m
ARROW_MM_PER_STEP_PER_S = 0.025    # arrow length per wheel speed (mm per step/s)
#: The arrows stand beside the wheels, outboard, from the axle line: a slow wheel's short
#: arrow is never hidden under its wheel (10 mm wide; the arrow head is 9 mm wide).
ARROW_OFFSET_MM = 13.0
_LEFT_COLOUR, _RIGHT_COLOUR = "#1f77b4", "#d62728"
_XLIM = (-140.0, 140.0)            # page x: the robot's right (mm)
_YLIM = (-110.0, 150.0)            # page y: forward (mm)
_ROWS = ("correct", "as printed", "int32")
#: Half-width of the bar axis (steps/s): holds the panel's fastest wheel, 2000 + 6000 mrad/s x
#: 42.5 mm x 8.043 steps/mm = 4051 steps/s.
_BAR_LIMIT = 4200
#: Tops of the speedometer's speed axis (mm/s): the smallest that holds 2.2 x the true speed.
_SPEED_TOPS = (20, 25, 30, 40, 50, 60, 80, 100, 120, 150, 200, 250, 300, 400, 500, 600, 800,
               1000, 1200)


class DiffDriveView:
    """Top view of the Radon Ulzer with wheel-speed arrows and the ICR, and a bar chart of
    the wheel speeds from three computations.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        An empty figure; two axes are added.
    track_width_mm, steps_per_m : int
        The firmware's constants (default: the Radon Ulzer's 85 mm and 8043 steps/m).
    """

    def __init__(self, fig: Figure, track_width_mm: int = W_MM, steps_per_m: int = ENC) -> None:
        self.base = track_width_mm
        self.enc = steps_per_m
        self.fig = fig
        # The layout is set by hand below: pin it (see wheelkin.style.fixed_layout).
        fig.set_layout_engine(fixed_layout())
        gs = fig.add_gridspec(1, 2, width_ratios=(1.0, 1.2), wspace=0.3, left=0.11,
                              right=0.96, bottom=0.15, top=0.88)
        ax = self.ax = fig.add_subplot(gs[0])
        bx = self.bx = fig.add_subplot(gs[1])
        ax.set_xlim(*_XLIM)
        ax.set_ylim(*_YLIM)
        ax.set_aspect("equal")
        ax.set_xlabel("robot's right (mm)")
        ax.set_ylabel("forward (mm)")
        ax.grid(True, lw=0.3, alpha=0.5)
        half = track_width_mm / 2
        ax.add_patch(Rectangle((-half + 6, -45), 2 * half - 12, 90, fc="#dddddd", ec="#555555",
                               lw=1.0, zorder=2))
        for x, colour in ((-half, _LEFT_COLOUR), (half, _RIGHT_COLOUR)):
            ax.add_patch(Rectangle((x - 5, -18), 10, 36, fc=colour, ec="k", lw=0.8, zorder=3))
        ax.plot([-half, half], [0, 0], color="k", lw=0.8, zorder=4)
        ax.plot([0], [0], marker="+", color="k", ms=8, zorder=5)
        # wheel names under the wheels, clear of the arrows and ticks beside them
        ax.text(-half, -22, "L", ha="center", va="top", fontsize=8)
        ax.text(half, -22, "R", ha="center", va="top", fontsize=8)
        self.icr = ax.plot([], [], marker="o", color="k", ms=5, ls="none", zorder=6)[0]
        self.icr_text = ax.text(0.02, 0.02, "", transform=ax.transAxes, fontsize=8,
                                va="bottom")
        self.printed_marks = ax.plot([], [], ls="none", marker="_", ms=14, mew=2,
                                     color="#ff7f0e", zorder=7)[0]
        ax.set_title("", fontsize=9)
        self.message = ax.text(0.5, 0.5, "", transform=ax.transAxes, ha="center",
                               va="center", color="#b35900", fontsize=9, zorder=10)
        # The wheel-speed arrows: made once, moved by update() (after the ICR marker, so
        # they are drawn over it).
        self.arrows = [self._arrow(-half - ARROW_OFFSET_MM, 0.0, _LEFT_COLOUR),
                       self._arrow(half + ARROW_OFFSET_MM, 0.0, _RIGHT_COLOUR)]
        # Bars: three computations x (left, right).
        y = np.arange(len(_ROWS))
        self.left_bars = bx.barh(y + 0.15, np.zeros(3), height=0.28, color=_LEFT_COLOUR,
                                 label="left wheel")
        self.right_bars = bx.barh(y - 0.15, np.zeros(3), height=0.28, color=_RIGHT_COLOUR,
                                  label="right wheel")
        bx.set_yticks(y, _ROWS, fontsize=8)
        bx.invert_yaxis()
        bx.set_xlim(-_BAR_LIMIT, _BAR_LIMIT)
        bx.set_xticks([-4000, -2000, 0, 2000, 4000])
        self.zero_line = bx.axvline(0, color="k", lw=0.6)  # drawn over the bars
        bx.set_xlabel("wheel speed (steps/s)")
        bx.set_ylim(len(_ROWS) - 0.3, -1.3)  # headroom above the first row for the legend
        bx.legend(loc="upper center", ncol=2, fontsize=8,
                  frameon=False)
        # under each pair of bars, with a background that hides the zero line behind it
        self.bar_text = [bx.text(-_BAR_LIMIT + 100, i + 0.5, "", fontsize=8, va="center", zorder=5,
                                 bbox={"fc": "white", "ec": "none", "pad": 0.5})
                         for i in range(3)]
        self.title = ax.set_title("", fontsize=9, loc="left")  # spans both panels
        # Everything update() moves, in drawing order: a panel redraws only these over a
        # cached picture of the rest (the limits never change); and the frame and zero line
        # of the bar chart, drawn over the bars.
        self.artists = sorted([self.icr, self.icr_text, self.printed_marks, self.message,
                               *self.arrows, *self.left_bars, *self.right_bars,
                               *bx.spines.values(), self.zero_line, *self.bar_text,
                               self.title],
                              key=lambda artist: artist.get_zorder())

    def _arrow(self, x: float, speed: float, colour: str) -> FancyArrow:
        length = speed * ARROW_MM_PER_STEP_PER_S
        return self.ax.add_patch(FancyArrow(x, 0.0, 0.0, length, width=3.0, head_width=9.0,
                                            head_length=min(10.0, abs(length)) or 0.1,
                                            length_includes_head=True, color=colour,
                                            zorder=6))

    def _move_arrow(self, arrow: FancyArrow, speed: float) -> None:
        length = speed * ARROW_MM_PER_STEP_PER_S
        arrow.set_data(dy=length, head_length=min(10.0, abs(length)) or 0.1)

    def update(self, v_steps_per_s: int, omega_mrad_per_s: int) -> list:
        """Show the wheel speeds for a set point (v in steps/s, omega in mrad/s).

        Returns :attr:`artists`, the artists it may change (for a blitting panel)."""
        try:
            self._update(int(v_steps_per_s), int(omega_mrad_per_s))
            self.message.set_text("")
        except ValueError as exc:  # a value the model rejects is shown, never raised
            self.message.set_text(str(exc))
        return self.artists

    def _update(self, v: int, omega: int) -> None:
        left, right = dd.wheel_speeds_steps(v, omega, self.base, self.enc)
        p_left, p_right = dd.wheel_speeds_steps_as_printed(v, omega, self.base, self.enc)
        i_left, i_right, overflow = dd.wheel_speeds_steps_int32(v, omega, self.base, self.enc,
                                                                method="firmware")
        half = self.base / 2
        self._move_arrow(self.arrows[0], left)
        self._move_arrow(self.arrows[1], right)
        beside = half + ARROW_OFFSET_MM
        self.printed_marks.set_data([-beside, beside], [p_left * ARROW_MM_PER_STEP_PER_S,
                                                        p_right * ARROW_MM_PER_STEP_PER_S])
        # ICR on the axle line, R = v / omega (mm), positive to the left (page -x).
        if omega != 0:
            radius_mm = v * 1e6 / (self.enc * omega)
            page_x = -radius_mm
            if _XLIM[0] < page_x < _XLIM[1]:
                self.icr.set_data([page_x], [0.0])
            else:
                self.icr.set_data([], [])
            side = "left" if radius_mm > 0 else "right"
            self.icr_text.set_text(f"ICR {abs(radius_mm):.0f} mm to the {side}")
        else:
            self.icr.set_data([], [])
            self.icr_text.set_text("no ICR: straight line")
        rows = ((left, right), (p_left, p_right), (i_left, i_right))
        for k, (lv, rv) in enumerate(rows):
            self.left_bars[k].set_width(lv)
            self.right_bars[k].set_width(rv)
            centre = (lv + rv) / 2
            note = "  OVERFLOW: wrapped" if (k == 2 and overflow) else ""
            self.bar_text[k].set_text(f"centre {centre:.0f} steps/s{note}")
            self.bar_text[k].set_color("#b35900" if note else "k")
        self.title.set_text(f"v = {v} steps/s, ω = {omega} mrad/s")


def wheel_speeds_panel() -> Panel:
    """Sliders for v and omega in the firmware's units, driving :class:`DiffDriveView`."""

    def setup():
        fig = Figure(figsize=(6.7, 3.6), dpi=100, layout=fixed_layout())  # not pyplot's
        return fig, DiffDriveView(fig)

    def update(view: DiffDriveView, v_steps_per_s: int, omega_mrad_per_s: int) -> list:
        return view.update(v_steps_per_s, omega_mrad_per_s)  # the panel blits these

    controls = {
        "v_steps_per_s": widgets.IntSlider(value=1000, min=-2000, max=2000, step=50,
                                           description="speed v (steps/s)",
                                           continuous_update=True),
        "omega_mrad_per_s": widgets.IntSlider(value=1000, min=-6000, max=6000, step=50,
                                              description="yaw rate ω (mrad/s)",
                                              continuous_update=True),
    }
    return Panel(controls, setup, update,
                 title="Wheel speeds of the Radon Ulzer: correct, as printed, int32")


register("diffdrive.wheel_speeds")(wheel_speeds_panel)


def sweep_animation(v_steps_per_s: int = 1000, omega_max: int = 4500,
                    frames: int = 40) -> FuncAnimation:
    """Sweep omega from 0 to ``omega_max`` mrad/s at a fixed v (a FuncAnimation)."""
    fig = Figure(figsize=(6.7, 3.6), dpi=100, layout=fixed_layout())
    view = DiffDriveView(fig)
    omegas = np.round(np.linspace(0, omega_max, frames)).astype(int)

    def frame(i: int):
        view.update(v_steps_per_s, int(omegas[i]))
        return ()

    return FuncAnimation(fig, frame, frames=frames, interval=150, blit=False)


class SpeedometerView:
    """A wheel at constant speed, its encoder counts, and two speedometers' readings."""

    def __init__(self, fig: Figure, steps_per_m: int = ENC, duration: float = 0.6,
                 task_period: float = 0.002) -> None:
        self.enc = steps_per_m
        self.t = np.arange(0.0, duration, task_period)
        self.ax = fig.add_subplot(1, 1, 1)
        ax = self.ax
        (self.true_line,) = ax.plot([], [], color="k", lw=1.2, label="true speed")
        (self.fixed_line,) = ax.step([], [], where="post", color="#1f77b4", lw=1.0,
                                     label="fixed window")
        (self.min_line,) = ax.step([], [], where="post", color="#d62728", lw=1.0,
                                   label="min. step count")
        ax.set_xlim(0, duration * 1000)
        ax.set_xlabel("time (ms)")
        ax.set_ylabel("speed (mm/s)")
        ax.grid(True, lw=0.3, alpha=0.5)
        legend = ax.legend(loc="upper right", fontsize=8)
        self.text = ax.text(0.02, 0.97, "", transform=ax.transAxes, fontsize=8, va="top")
        # The speed axis takes a few fixed tops (not 2.2 x every speed), so that a panel can
        # redraw only the lines and the text over a cached picture of the axes while the top
        # holds; ``view`` (an invisible marker) changes whenever the top does, so that the
        # panel then renders the new axes once.
        self._views = (Artist(), Artist())
        for marker in self._views:
            marker.set_visible(False)
        self.view = self._views[0]
        self._top: float | None = None
        # The frame and the legend do not change but are drawn over the lines.
        self.lines = sorted([self.true_line, self.fixed_line, self.min_line,
                             *ax.spines.values(), self.text, legend],
                            key=lambda artist: artist.get_zorder())

    @property
    def artists(self) -> list:
        """What update() may change, in drawing order (the marker of the view last)."""
        return [*self.lines, self.view]

    def update(self, speed_mm_per_s: float, window_ms: float, min_steps: int) -> list:
        """Show the readings; returns :attr:`artists` (for a blitting panel)."""
        try:
            speed = float(speed_mm_per_s) * 1e-3
            counts = np.floor(speed * self.enc * self.t + 0.5)
            fixed = dd.speed_from_counts(counts, self.t, window=window_ms * 1e-3)
            waiting = dd.speed_from_counts(counts, self.t, window=0.0,
                                           min_steps=int(min_steps))
        except ValueError as exc:
            self.text.set_text(str(exc))
            return self.artists
        ms = self.t * 1000
        to_mm = 1000.0 / self.enc
        self.true_line.set_data(ms, np.full_like(ms, speed * 1000))
        self.fixed_line.set_data(ms, fixed * to_mm)
        self.min_line.set_data(ms, waiting * to_mm)
        need = max(speed * 1000 * 2.2, 20.0)
        top = next((t for t in _SPEED_TOPS if t >= need), need)
        if top != self._top:
            self._top = top
            self.ax.set_ylim(-0.05 * top, top)
            self.view = self._views[1] if self.view is self._views[0] else self._views[0]
        resolution = dd.speed_resolution(window_ms * 1e-3, self.enc) * 1000
        self.text.set_text(f"fixed {window_ms:.0f} ms window: resolution {resolution:.1f} mm/s"
                           f"\nwaiting for {int(min_steps)} steps")
        return self.artists


def speedometer_panel() -> Panel:
    """Sliders for the wheel speed, the window and the minimum step count."""

    def setup():
        fig = Figure(figsize=(6.0, 3.4), dpi=100)
        return fig, SpeedometerView(fig)

    def update(view: SpeedometerView, speed_mm_per_s: float, window_ms: float,
               min_steps: int) -> list:
        return view.update(speed_mm_per_s, window_ms, min_steps)  # the panel blits these

    controls = {
        "speed_mm_per_s": widgets.FloatSlider(value=50.0, min=5.0, max=500.0, step=5.0,
                                              description="speed (mm/s)"),
        "window_ms": widgets.FloatSlider(value=10.0, min=2.0, max=100.0, step=2.0,
                                         description="window (ms)"),
        "min_steps": widgets.IntSlider(value=6, min=1, max=30, description="min steps"),
    }
    return Panel(controls, setup, update, title="Speedometer: window vs minimum step count")


register("diffdrive.speedometer")(speedometer_panel)
