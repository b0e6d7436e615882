"""The odometry chapter's live panel (notebooks/06_odometry).

``odometry.square`` drives the Radon Ulzer robot around a 1 m square with rounded corners
(kinematically: the wheels roll without slip) and dead-reckons it from its quantised encoder
counts, with three sliders: the odometry's update step (mm of wheel travel per update), a
wheel-diameter mismatch (right wheel larger than the left, %) and a track-width error (the
track width W the odometry assumes, % off the true one). It shows the true path, the exact-arc
estimate and the Euler estimate, and their end-point errors.

:func:`simulate_square` is the model behind it, usable on its own (the chapter uses it too).

The chapter's sections share three more helpers: :func:`firmware_to_ours_mm` (the
firmware's poses in our frame, in mm), :func:`wheel_increments` (the wheel travel per update
along a path of arcs, in metres) and :func:`draw_ellipse` (the error ellipse of a position
covariance).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import ipywidgets as widgets
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.patches import Ellipse
from numpy.typing import ArrayLike, NDArray

from wheelkin import frames
from wheelkin import odometry as odo
from wheelkin.widgets import Panel, register

__all__ = ["draw_ellipse", "firmware_to_ours_mm", "rounded_square", "simulate_square",
           "square_panel", "wheel_increments"]

STEPS_PER_MM = 8.043  # Radon Ulzer: ENC = 8043 steps/m
WHEEL_BASE_MM = 85.0  # Radon Ulzer: the track width W (wheel to wheel, side to side)
SIDE_MM = 1000.0
CORNER_RADIUS_MM = 150.0
STEP_OPTIONS = (1, 2, 5, 10, 20, 50, 100)  # mm of wheel travel per odometry update
#: The panel's view by direction: (x limits, y limits) in mm, where the legend and the text
#: box go. The square starts at the middle of its first side, heading +x: it spans
#: x = -500..500 and y = 0..1000 counter-clockwise, y = -1000..0 clockwise; the text box sits
#: in the free strip beside its first side, the legend in the one beside the third.
_VIEWS = {
    "counter-clockwise": ((-800, 800), (-300, 1300), "upper right", (0.02, 0.02, "bottom")),
    "clockwise": ((-800, 800), (-1300, 300), "lower right", (0.02, 0.98, "top")),
}


def firmware_to_ours_mm(rows: ArrayLike) -> NDArray[np.float64]:
    """Firmware poses (X_mm, Y_mm, orientation_rad) as ours: (x_mm, y_mm, theta_rad).

    :func:`wheelkin.frames.firmware_pose_to_ours` (Y forward, X right, orientation from +Y
    counter-clockwise, to x forward, y left, theta from +x), in millimetres.

    >>> firmware_to_ours_mm([[10.0, 250.0, 0.5]])  # 10 mm right, 250 mm forward
    array([[250. , -10. ,   0.5]])
    """
    fw = np.asarray(rows, dtype=float)
    if fw.ndim != 2 or fw.shape[1] != 3:
        raise ValueError(f"rows must have shape (N, 3): (X_mm, Y_mm, orientation_rad) per "
                         f"row, got shape {fw.shape}")
    ours = frames.firmware_pose_to_ours(fw[:, 0], fw[:, 1], fw[:, 2])
    return np.column_stack([1000 * ours[:, 0], 1000 * ours[:, 1], ours[:, 2]])


def wheel_increments(segments: ArrayLike, track_width: float,
                     max_step: float = 0.01) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The (left, right) wheel travel per update, m, along a path of arcs.

    The per-update differences of :func:`wheelkin.odometry.plan_wheel_travel` (whose lengths
    may be in any one unit; here metres): each ``(distance, turn)`` segment (m, rad) is split
    into the fewest equal updates in which no wheel travels more than ``max_step``.

    >>> left, right = wheel_increments([(0.0, math.pi / 2)], 0.085, 0.01)  # a quarter spin
    >>> len(left), round(float(right.sum()), 6), round(float(left.sum()), 6)
    (7, 0.066759, -0.066759)
    """
    travel = odo.plan_wheel_travel(segments, track_width, max_step)
    steps = np.diff(travel, axis=0)
    return steps[:, 0], steps[:, 1]


def draw_ellipse(ax: Axes, centre: ArrayLike, covariance: ArrayLike, sigmas: float = 1.0,
                 **kwargs: Any) -> Ellipse:
    """Draw the ellipse of ``sigmas`` standard deviations of a 2 x 2 position covariance.

    Its axes lie along the covariance's eigenvectors, half-lengths ``sigmas`` times the square
    roots of the eigenvalues; it is not filled. ``kwargs`` go to the patch (colour, line
    width, ...). Returns the patch, added to ``ax``.

    >>> from matplotlib.figure import Figure
    >>> ax = Figure().add_subplot()
    >>> e = draw_ellipse(ax, (1.0, 2.0), [[4.0, 0.0], [0.0, 1.0]], sigmas=2.0)
    >>> e.width, e.height, e.angle  # 2 sigmas: 2 x 2 x sqrt(4) along x, 2 x 2 x 1 along y
    (8.0, 4.0, 0.0)
    """
    cov = np.asarray(covariance, dtype=float)
    if cov.shape != (2, 2) or not np.all(np.isfinite(cov)):
        raise ValueError(f"covariance must be a finite 2 x 2 matrix, got {covariance!r}")
    values, vectors = np.linalg.eigh(cov)
    if values[0] < -1e-9 * max(abs(values[1]), np.finfo(float).tiny):
        raise ValueError(f"covariance must be positive semi-definite, got eigenvalues {values}")
    angle = math.degrees(math.atan2(vectors[1, 1], vectors[0, 1]))
    patch = Ellipse(centre, 2 * sigmas * math.sqrt(max(values[1], 0)),
                    2 * sigmas * math.sqrt(max(values[0], 0)), angle=angle, fill=False,
                    **kwargs)
    ax.add_patch(patch)
    return patch


def rounded_square(side_mm: float = SIDE_MM, corner_radius_mm: float = CORNER_RADIUS_MM,
                   clockwise: bool = False) -> NDArray[np.float64]:
    """Segments ``(distance_mm, turn_rad)`` of a square with arcs of radius r at the corners.

    Starts at the middle of the first side, heading along it; four straight pieces of
    ``side - 2 r`` split around the start, and four quarter arcs (left turns, or right turns
    when ``clockwise``). Turn on the spot with ``corner_radius_mm=0``.
    """
    r = corner_radius_mm
    straight = side_mm - 2.0 * r
    turn = -math.pi / 2 if clockwise else math.pi / 2
    segs = [(straight / 2, 0.0)]
    for i in range(4):
        segs.append((r * abs(turn), turn))
        segs.append((straight if i < 3 else straight / 2, 0.0))
    return np.array(segs)


def simulate_square(
        step_mm: float = 10.0, diameter_error_pct: float = 0.0, base_error_pct: float = 0.0, *,
        clockwise: bool = False, corner_radius_mm: float = CORNER_RADIUS_MM,
        methods: Sequence[str] = ("exact", "euler"),
) -> tuple[NDArray[np.float64], dict[str, NDArray[np.float64]]]:
    """True path and dead-reckoned estimates of the rounded square.

    The true robot has track width W = 85 mm and wheel diameters D_L = D (1 − e/2),
    D_R = D (1 + e/2) with e = ``diameter_error_pct``/100, so an encoder step is
    (1 ∓ e/2)/ENC_mm of travel. The odometry assumes equal wheels and a track width
    W (1 + ``base_error_pct``/100).

    Returns
    -------
    truth : numpy.ndarray, shape (K + 1, 3)
        True poses (mm, mm, rad), our frame, from the start.
    estimates : dict of str to numpy.ndarray, shape (K + 1, 3)
        Odometry poses by method, from the start.
    """
    travel = odo.plan_wheel_travel(rounded_square(clockwise=clockwise,
                                                  corner_radius_mm=corner_radius_mm),
                                   WHEEL_BASE_MM, step_mm)
    start = np.zeros((1, 3))
    truth = np.vstack([start, odo.integrate(np.diff(travel, axis=0), 1.0, WHEEL_BASE_MM)])
    e = diameter_error_pct / 100.0
    counts_per_mm = STEPS_PER_MM / np.array([1.0 - e / 2.0, 1.0 + e / 2.0])
    increments = odo.encoder_increments(travel * counts_per_mm / STEPS_PER_MM, STEPS_PER_MM)
    assumed_base = WHEEL_BASE_MM * (1.0 + base_error_pct / 100.0)
    estimates = {m: np.vstack([start, odo.integrate(increments, STEPS_PER_MM, assumed_base, m)])
                 for m in methods}
    return truth, estimates


def _setup():
    fig, ax = plt.subplots(figsize=(5.6, 4.5), dpi=100, layout="tight")
    ax.set_aspect("equal")
    (xlim, ylim, where, _) = _VIEWS["counter-clockwise"]
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_xlabel("x (mm), forward at the start")
    ax.set_ylabel("y (mm), left at the start")
    ax.grid(True, lw=0.3, alpha=0.5)
    truth = ax.plot([], [], color="k", lw=2.0, label="true path")[0]
    exact = ax.plot([], [], color="#1f77b4", lw=1.3, label="odometry, exact arc")[0]
    euler = ax.plot([], [], color="#ff7f0e", lw=1.1, ls="--", label="odometry, Euler")[0]
    origin = ax.plot([0], [0], marker="o", color="k", ms=5, ls="none")[0]
    ends = ax.plot([], [], marker="x", color="#1f77b4", ms=8, ls="none")[0]
    legend = ax.legend(loc=where, fontsize=8)
    text = ax.text(0.02, 0.02, "", transform=ax.transAxes, fontsize=8, va="bottom",
                   family="monospace", bbox={"fc": "white", "ec": "#999999", "alpha": 0.9})
    message = ax.text(0.5, 0.5, "", transform=ax.transAxes, ha="center", va="center",
                      color="#b35900", fontsize=10, bbox={"fc": "white", "ec": "#b35900"})
    message.set_visible(False)
    # What _update moves, in drawing order: the panel redraws only these over a cached
    # picture of the rest (axes, ticks, grid). The start mark, the frame and the legend do not
    # move but are drawn over the paths. A change of direction changes the view: the marker of the
    # view (an invisible artist) changes with it, so that the panel renders the axes anew.
    moving = sorted([truth, exact, euler, origin, ends, *ax.spines.values(), legend, text,
                     message],
                    key=lambda artist: artist.get_zorder())
    markers = (Artist(), Artist())
    for marker in markers:
        marker.set_visible(False)
    return fig, {"ax": ax, "truth": truth, "exact": exact, "euler": euler, "ends": ends,
                 "text": text, "message": message, "legend": legend, "artists": moving,
                 "markers": markers, "view": "counter-clockwise", "marker": markers[0]}


def _show_view(state, direction: str) -> None:
    """Limits, legend and text box for ``direction`` (a new marker when they change)."""
    if direction == state["view"] or direction not in _VIEWS:
        return
    xlim, ylim, where, (x, y, va) = _VIEWS[direction]
    state["ax"].set_xlim(*xlim)
    state["ax"].set_ylim(*ylim)
    state["legend"].set_loc(where)
    state["text"].set_position((x, y))
    state["text"].set_verticalalignment(va)
    state["view"] = direction
    a, b = state["markers"]
    state["marker"] = b if state["marker"] is a else a


def _update(state, step_mm, diameter_error_pct, base_error_pct, direction):
    _show_view(state, direction)
    try:
        truth, est = simulate_square(float(step_mm), float(diameter_error_pct),
                                     float(base_error_pct),
                                     clockwise=(direction == "clockwise"))
    except ValueError as exc:  # a value the model rejects: say so, draw nothing
        state["message"].set_text(str(exc))
        state["message"].set_visible(True)
        for key in ("truth", "exact", "euler", "ends"):
            state[key].set_data([], [])
        state["text"].set_text("")
        return [*state["artists"], state["marker"]]
    state["message"].set_visible(False)
    state["truth"].set_data(truth[:, 0], truth[:, 1])
    state["exact"].set_data(est["exact"][:, 0], est["exact"][:, 1])
    state["euler"].set_data(est["euler"][:, 0], est["euler"][:, 1])
    state["ends"].set_data([est["exact"][-1, 0]], [est["exact"][-1, 1]])
    err = {m: float(np.hypot(*(p[-1, :2] - truth[-1, :2]))) for m, p in est.items()}
    head = {m: math.degrees(p[-1, 2] - truth[-1, 2]) for m, p in est.items()}
    state["text"].set_text(
        f"{len(truth) - 1} updates of <= {float(step_mm):g} mm\n"
        f"end error, exact: {err['exact']:7.1f} mm {head['exact']:+6.2f} deg\n"
        f"end error, Euler: {err['euler']:7.1f} mm {head['euler']:+6.2f} deg")
    return [*state["artists"], state["marker"]]  # the panel blits these


@register("odometry.square")
def square_panel() -> Panel:
    """Step size, wheel-diameter mismatch and track-width error on a 1 m rounded square."""
    style = {"description_width": "initial"}
    layout = widgets.Layout(width="420px")
    controls = {
        "step_mm": widgets.SelectionSlider(options=list(STEP_OPTIONS), value=10,
                                           description="update step (mm)", style=style,
                                           layout=layout),
        "diameter_error_pct": widgets.FloatSlider(value=0.0, min=-2.0, max=2.0, step=0.1,
                                                  description="right wheel larger by (%)",
                                                  style=style, layout=layout),
        "base_error_pct": widgets.FloatSlider(value=0.0, min=-10.0, max=10.0, step=0.5,
                                              description="assumed track width off by (%)",
                                              style=style, layout=layout),
        "direction": widgets.Dropdown(options=["counter-clockwise", "clockwise"],
                                      value="counter-clockwise", description="direction",
                                      style=style),
    }
    return Panel(controls, _setup, _update,
                 title="Dead reckoning a 1 m square (rounded corners, r = 150 mm)")
