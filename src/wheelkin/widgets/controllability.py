r"""Chapter 10's live panel and its kernel-free twin (notebooks/10_controllability).

:class:`ManoeuvreView` draws the four-move manoeuvre of size :math:`\varepsilon` of a vehicle
from above (world x to the right, y up, metres): the path of the reference point, one colour
per move, the net motion (black arrow) and the leading-order prediction
:math:`\varepsilon^2[\mathbf f_1, \mathbf f_2]` (red, dashed) from the same start; beside it,
on logarithmic axes, the size of the net motion and of its difference from the prediction
for :math:`\varepsilon` from 1 cm to 0.5 m, with the present :math:`\varepsilon` marked.

The vehicles (:data:`VEHICLES`):

- ``"car"``: the sandbox's 1/10 car at full lock (:func:`wheelkin.nonholonomic.car_lock_fields`,
  :math:`\kappa_{max} = \tan\delta_{max}/L`): forward at left lock, forward at right lock,
  back at left lock, back at right lock, each :math:`\varepsilon` metres;
- ``"differential drive"``: the unicycle's drive and turn fields
  (:func:`wheelkin.nonholonomic.unicycle_fields`): drive :math:`\varepsilon` m, turn
  :math:`\varepsilon` rad on the spot, back :math:`\varepsilon` m, turn back.

The panel ``controllability.manoeuvre`` sets :math:`\varepsilon` and the vehicle;
:func:`manoeuvre_animation` sweeps :math:`\varepsilon` for both, without a kernel.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import ipywidgets as widgets
import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrowPatch
from matplotlib.ticker import MaxNLocator, NullFormatter, NullLocator
from numpy.typing import NDArray

from wheelkin import frames, nonholonomic
from wheelkin.sandbox.car import RC_CAR_MAX_STEERING
from wheelkin.style import fixed_layout
from wheelkin.widgets import Panel, register

__all__ = ["EPSILON_RANGE", "VEHICLES", "ManoeuvreView", "manoeuvre", "manoeuvre_animation",
           "manoeuvre_panel"]

#: The sandbox car's wheelbase (m) and its curvature at full lock (1/m).
CAR_WHEELBASE = 0.33
CAR_MAX_CURVATURE = math.tan(RC_CAR_MAX_STEERING) / CAR_WHEELBASE
#: The vehicles the panel offers.
VEHICLES = ("car", "differential drive")
#: The range of the move size the panel and the log-log curves cover, m.
EPSILON_RANGE = (0.01, 0.5)
_MOVE_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd")
_SAMPLES = 24  # path points per move


def _twists(vehicle: str) -> list[list[float]]:
    """The four moves as body twists per unit of the move's size (m or rad)."""
    if vehicle == "car":
        k = CAR_MAX_CURVATURE
        return [[1.0, 0.0, k], [1.0, 0.0, -k], [-1.0, 0.0, -k], [-1.0, 0.0, k]]
    if vehicle == "differential drive":
        return [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]]
    raise ValueError(f"vehicle must be one of {', '.join(map(repr, VEHICLES))}; "
                     f"got {vehicle!r}")


def _fields(vehicle: str) -> tuple[Any, Any]:
    if vehicle == "car":
        def left(q: NDArray[np.float64]) -> NDArray[np.float64]:
            return nonholonomic.car_lock_fields(q, CAR_MAX_CURVATURE)[:, 0]

        def right(q: NDArray[np.float64]) -> NDArray[np.float64]:
            return nonholonomic.car_lock_fields(q, CAR_MAX_CURVATURE)[:, 1]

        return left, right
    _twists(vehicle)  # names the bad vehicle
    return nonholonomic.unicycle_drive, nonholonomic.unicycle_turn


def manoeuvre(vehicle: str, epsilon: float, start: tuple[float, float, float] = (0, 0, 0)
              ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    r"""The manoeuvre of size ``epsilon`` from ``start``: its path (the four moves, each
    sampled), the pose after each move (start first, shape (5, 3)) and the prediction
    :math:`\varepsilon^2[\mathbf f_1, \mathbf f_2]` (shape (3,)). Exact: every move is a
    constant twist (:func:`wheelkin.frames.integrate_twist`)."""
    eps = float(epsilon)
    if not (math.isfinite(eps) and eps > 0):
        raise ValueError(f"epsilon must be a finite number > 0, got {epsilon!r}")
    pieces, pose = [np.array([start], dtype=float)], np.array(start, dtype=float)
    ends = [pose]
    for twist in _twists(vehicle):
        piece = frames.integrate_twist([twist] * _SAMPLES, eps / _SAMPLES, pose)
        piece[:, 2] = pose[2] + np.cumsum([0.0] + [twist[2] * eps / _SAMPLES] * _SAMPLES)
        pieces.append(piece[1:])
        pose = piece[-1]
        ends.append(pose)
    predicted = nonholonomic.bracket_prediction(*_fields(vehicle), list(start), eps)
    return np.vstack(pieces), np.array(ends), predicted


@functools.lru_cache(maxsize=4)
def _curves(vehicle: str) -> tuple[NDArray[np.float64], NDArray[np.float64],
                                   NDArray[np.float64]]:
    """(epsilon, |net motion|, |net motion - prediction|) over :data:`EPSILON_RANGE`."""
    eps = np.geomspace(*EPSILON_RANGE, 40)
    net, rest = [], []
    for e in eps:
        _, ends, predicted = manoeuvre(vehicle, float(e))
        motion = ends[-1] - ends[0]
        net.append(float(np.linalg.norm(motion)))
        rest.append(float(np.linalg.norm(motion - predicted)))
    return eps, np.array(net), np.array(rest)


class ManoeuvreView:
    """The manoeuvre's path and arrows (left), the sizes against epsilon (right)."""

    def __init__(self, fig: Figure) -> None:
        gs = fig.add_gridspec(1, 2, width_ratios=(1.25, 1.0), wspace=0.34, left=0.12,
                              right=0.98, bottom=0.15, top=0.9)
        ax = self.ax = fig.add_subplot(gs[0])
        bx = self.bx = fig.add_subplot(gs[1])
        ax.grid(True, lw=0.3, alpha=0.5)
        ax.xaxis.set_major_locator(MaxNLocator(4))
        ax.yaxis.set_major_locator(MaxNLocator(4))
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        self.moves = [ax.plot([], [], color=c, lw=2.0, solid_capstyle="round",
                              label=f"move {i + 1}")[0]
                      for i, c in enumerate(_MOVE_COLOURS)]
        self.start = ax.plot([], [], "o", color="k", ms=5, zorder=5)[0]
        self.net = ax.add_patch(FancyArrowPatch((0, 0), (0, 0), arrowstyle="-|>",
                                                mutation_scale=12, color="k", lw=1.6,
                                                zorder=6))
        self.pred = ax.add_patch(FancyArrowPatch((0, 0), (0, 0), arrowstyle="-|>",
                                                 mutation_scale=12, color="#d62728", lw=1.4,
                                                 ls="--", zorder=7))
        ax.legend(handles=self.moves, fontsize=8, loc="lower left", ncol=2,
                  handlelength=1.2, columnspacing=0.8)
        self.text = ax.text(0.02, 0.98, "", transform=ax.transAxes, va="top", fontsize=8.5,
                            bbox={"fc": "white", "ec": "none", "alpha": 0.85, "pad": 1})
        self.title = ax.set_title("", fontsize=10)
        bx.set_xscale("log")
        bx.set_yscale("log")
        # A fifth beyond the largest move, so that its dot is drawn whole, not on the spine.
        bx.set_xlim(EPSILON_RANGE[0], 1.2 * EPSILON_RANGE[1])
        bx.set_ylim(1e-9, 1.0)
        bx.set_xticks([0.01, 0.03, 0.1, 0.3], ["0.01", "0.03", "0.1", "0.3"])
        # Plain-text labels: mathtext ones (10^-9) cost most of a frame's drawing time.
        bx.set_yticks([1e-9, 1e-6, 1e-3, 1.0], ["10⁻⁹", "10⁻⁶", "10⁻³", "1"])
        bx.xaxis.set_minor_formatter(NullFormatter())
        bx.yaxis.set_minor_locator(NullLocator())
        bx.set_xlabel("ε (m)")
        bx.set_ylabel("size (m)")
        bx.grid(True, which="major", lw=0.3, alpha=0.5)
        self.net_curve = bx.plot([], [], color="k", lw=1.4, label="net motion")[0]
        self.rest_curve = bx.plot([], [], color="#d62728", lw=1.4,
                                  label="net − ε²[f₁, f₂]")[0]
        self.marks = bx.plot([], [], "o", color="#555555", ms=5, zorder=5)[0]
        bx.legend(fontsize=8, loc="lower right")
        self.slope = bx.text(0.04, 0.96, "", transform=bx.transAxes, va="top", fontsize=8.5)

    def update(self, epsilon: float, vehicle: str = "car") -> None:
        path, ends, predicted = manoeuvre(vehicle, epsilon)
        for i, line in enumerate(self.moves):
            piece = path[i * _SAMPLES:(i + 1) * _SAMPLES + 1]
            line.set_data(piece[:, 0], piece[:, 1])
            # A turn on the spot has no path: a ring marks where it happens.
            line.set_marker("o" if np.ptp(piece[:, :2], axis=0).max() < 1e-12 else "None")
            line.set_markerfacecolor("none")
            line.set_markersize(9 if i == 1 else 13)
        x0, y0 = ends[0, :2]
        x1, y1 = ends[-1, :2]
        self.start.set_data([x0], [y0])
        self.net.set_positions((x0, y0), (x1, y1))
        self.pred.set_positions((x0, y0), (x0 + predicted[0], y0 + predicted[1]))
        motion = ends[-1] - ends[0]
        rest = motion - predicted
        self.text.set_text(
            f"net motion {1000 * np.linalg.norm(motion[:2]):.1f} mm "
            f"(black)\nε²[f₁, f₂]: {1000 * np.linalg.norm(predicted[:2]):.1f} mm (red)\n"
            f"difference {1000 * np.linalg.norm(rest):.2g} mm")
        pts = np.vstack([path[:, :2], ends[-1:, :2], ends[:1, :2] + predicted[:2]])
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        mid = 0.5 * (lo + hi)
        # Equal scales on both axes: the spans in the ratio of the axes' box, with room for
        # the legend below and the numbers above.
        box = self.ax.get_position()
        fig_w, fig_h = self.ax.figure.get_size_inches()
        ratio = (box.height * fig_h) / (box.width * fig_w)
        half_x = max(0.7 * float(hi[0] - lo[0]), 0.7 * float(hi[1] - lo[1]) / ratio, 1e-3)
        half_y = half_x * ratio
        self.ax.set_xlim(mid[0] - half_x, mid[0] + half_x)
        self.ax.set_ylim(mid[1] - 0.42 * half_y * 2, mid[1] + 0.58 * half_y * 2)
        name = "car at full lock" if vehicle == "car" else "differential drive"
        self.title.set_text(f"{name}, ε = {1000 * epsilon:.0f} mm")
        eps, net, rest_curve = _curves(vehicle)
        self.net_curve.set_data(eps, net)
        self.rest_curve.set_data(eps, rest_curve)
        self.marks.set_data([epsilon, epsilon],
                            [np.linalg.norm(motion), max(np.linalg.norm(rest), 1e-12)])
        order = 4 if vehicle == "car" else 3
        self.slope.set_text(f"slopes 2 and {order}")


def _setup() -> tuple[Figure, ManoeuvreView]:
    fig = Figure(figsize=(6.7, 3.6), dpi=100, layout=fixed_layout())
    return fig, ManoeuvreView(fig)


def manoeuvre_panel() -> Panel:
    """Sliders: the size of each move (m) and the vehicle."""
    controls = {
        "epsilon": widgets.FloatSlider(value=0.2, min=0.05, max=0.5, step=0.01,
                                       description="move size ε (m)"),
        "vehicle": widgets.Dropdown(options=list(VEHICLES), value="car",
                                    description="vehicle"),
    }
    return Panel(controls, _setup,
                 lambda view, epsilon, vehicle: view.update(epsilon, vehicle),
                 title="Four moves and their Lie bracket", dpi=100)


register("controllability.manoeuvre")(manoeuvre_panel)


def manoeuvre_animation(frames: int = 24) -> FuncAnimation:
    """Kernel-free twin of ``controllability.manoeuvre``: epsilon swept from 5 cm to 0.5 m
    for the car, then for the differential drive."""
    if isinstance(frames, bool) or not isinstance(frames, int) or not 4 <= frames <= 40:
        raise ValueError(f"frames must be an integer in [4, 40], got {frames!r}")
    fig, view = _setup()
    half = frames // 2
    eps = np.concatenate([np.geomspace(0.05, 0.5, half), np.geomspace(0.05, 0.5, frames - half)])
    which = ["car"] * half + ["differential drive"] * (frames - half)

    def frame(k: int) -> None:
        view.update(float(eps[k]), which[k])

    frame(0)
    return FuncAnimation(fig, frame, frames=frames)
