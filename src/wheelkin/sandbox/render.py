"""Top-down drawings and animations of the sandbox's vehicles (matplotlib).

:func:`draw_vehicle` draws one vehicle at a pose (body outline, wheels at their steering
angles, mecanum rollers, caster, heading arrow, reference point, optionally the ICR with the
lines from it to each wheel, and wheel names) and returns a :class:`VehicleDrawing` whose
:meth:`~VehicleDrawing.update` moves the same artists to a new pose: live panels and
animations redraw in place, never rebuilding the figure. A slipping wheel is drawn red.

:func:`animate` turns one or several :class:`~wheelkin.sandbox.world.Trajectory` s into a
:class:`~matplotlib.animation.FuncAnimation` (trail, walls, a planned path, extra paths such as
an odometry estimate, the time); show it in a static page with
``wheelkin.animation.show``, which gives the player stable element ids and alt text. Keep
it small: 40 frames at 100 dpi and figsize (6.7, 4.2) make well under 1 MB once
``wheelkin.animation.to_html`` has stored the frames with a palette. The frames are
blitted (:class:`SandboxAnimation`): the axes are drawn once, then only what moves.

Mecanum rollers are drawn as the rollers *touching the ground* (as if seen through the wheel
from above): theirs is the axis the contact model uses, and in the X arrangement they form an
X. The rollers on top of a real wheel, the ones a camera above would see, are their mirror
image about the wheel's axle (an O).
"""

from __future__ import annotations

import base64
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from io import BytesIO
from pathlib import Path
from tempfile import TemporaryDirectory
from typing import Any

import numpy as np
from matplotlib.animation import FuncAnimation, HTMLWriter
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection
from matplotlib.colors import is_color_like
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrow, Polygon
from numpy.typing import ArrayLike

from wheelkin import _validate as V
from wheelkin._kernels import roller_axis
from wheelkin.style import fixed_layout

from .vehicles import VehicleSpec
from .world import MAX_COORDINATE, MAX_SPEED, MAX_YAW_RATE, Trajectory

__all__ = ["LEGEND_PLACES", "PALETTE", "SandboxAnimation", "VehicleDrawing", "animate",
           "draw_vehicle"]

#: Colours of successive vehicles in one animation.
PALETTE = ("#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b")
WHEEL_COLOUR = "#333333"
SLIP_COLOUR = "#d62728"
ICR_COLOUR = "#7f7f7f"
#: Figure sizes (in) and resolutions (dpi) an animation accepts; its frame interval (ms).
FIGSIZE_RANGE = (1.0, 20.0)
DPI_RANGE = (10.0, 600.0)
INTERVAL_RANGE = (1.0, 60_000.0)
#: Where an animation's legend may go: a corner or edge inside the axes (not the upper left,
#: where the clock is), or "outside" (to the right of the axes, so that it never covers a
#: vehicle).
LEGEND_PLACES = ("lower right", "lower left", "upper right", "upper center", "lower center",
                 "center left", "center right", "outside")


def _flag(name: str, value) -> bool:
    """``value`` if it is a bool; a flag is True or False, not a truthy value."""
    if not isinstance(value, bool | np.bool_):
        raise ValueError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def _points(name: str, value) -> np.ndarray:
    """An (N, 2) array of finite points within the sandbox's coordinates, N >= 1."""
    arr = V.shaped(name, value, (2,))
    if arr.ndim != 2 or len(arr) < 1:
        raise ValueError(f"{name} must have shape (N, 2), N >= 1, got shape {arr.shape}")
    if np.any(np.abs(arr) > MAX_COORDINATE):
        raise ValueError(f"{name} must be within |x|, |y| <= {MAX_COORDINATE:g} m")
    return arr


def _pose(value) -> tuple[float, float, float]:
    p = V.pose("pose", value)
    if abs(p[0]) > MAX_COORDINATE or abs(p[1]) > MAX_COORDINATE:
        raise ValueError(f"pose must be within |x|, |y| <= {MAX_COORDINATE:g} m, got {value!r}")
    return (float(p[0]), float(p[1]), float(p[2]))


def _to_world(pose, points: np.ndarray) -> np.ndarray:
    x, y, th = pose
    c, s = math.cos(th), math.sin(th)
    return np.column_stack((x + c * points[:, 0] - s * points[:, 1],
                            y + s * points[:, 0] + c * points[:, 1]))


def _wheel_outline(wheel, angle: float) -> np.ndarray:
    """Body-frame corners of a wheel's top view (length 2 r_w, its tyre width)."""
    half_l, half_w = wheel.wheel_radius, 0.3 * wheel.wheel_radius
    c, s = math.cos(angle), math.sin(angle)
    px, py = wheel.position
    local = np.array([(-half_l, -half_w), (half_l, -half_w), (half_l, half_w), (-half_l, half_w)])
    return np.column_stack((px + c * local[:, 0] - s * local[:, 1],
                            py + s * local[:, 0] + c * local[:, 1]))


def _rollers(wheel, angle: float, count: int = 4) -> np.ndarray:
    """Body-frame segments of a Swedish wheel's ground rollers, shape (count, 2, 2)."""
    ux, uy = roller_axis(angle, wheel.roller_angle)  # the axle turned by gamma
    ex, ey = math.cos(angle), math.sin(angle)
    half_w = 0.3 * wheel.wheel_radius
    # A roller spans the tyre width: length half_w / |u . n| along u, clipped to the wheel.
    un = abs(math.cos(wheel.roller_angle))
    half = min(half_w / max(un, 1e-9), wheel.wheel_radius)
    px, py = wheel.position
    segs = []
    for i in range(count):
        off = wheel.wheel_radius * (-0.75 + 1.5 * i / (count - 1))
        cx, cy = px + off * ex, py + off * ey
        segs.append(((cx - half * ux, cy - half * uy), (cx + half * ux, cy + half * uy)))
    return np.array(segs)


class VehicleDrawing:
    """The artists of one drawn vehicle; :meth:`update` moves them in place."""

    def __init__(self, ax: Axes, spec: VehicleSpec, *, color: str, show_icr: bool,
                 labels: bool, alpha: float, zorder: float) -> None:
        if not isinstance(ax, Axes):
            raise ValueError(f"ax must be a matplotlib Axes, got {type(ax).__name__}")
        if not isinstance(spec, VehicleSpec):
            raise ValueError(f"spec must be a VehicleSpec, got {type(spec).__name__}")
        if not isinstance(color, str) or not is_color_like(color):
            raise ValueError(f"color must be a matplotlib colour string, got {color!r}")
        show_icr, labels = _flag("show_icr", show_icr), _flag("labels", labels)
        alpha = V.in_range("alpha", alpha, 0.0, 1.0)
        zorder = V.in_range("zorder", zorder, -1e6, 1e6)
        self.ax, self.spec, self.show_icr = ax, spec, show_icr
        self._size = max(math.hypot(*p) for p in spec.body)
        self.body = Polygon(np.zeros((len(spec.body), 2)), closed=True, facecolor=color,
                            edgecolor="black", alpha=0.35 * alpha + 0.0, linewidth=1.0,
                            zorder=zorder)
        ax.add_patch(self.body)
        self.outline = Polygon(np.zeros((len(spec.body), 2)), closed=True, fill=False,
                               edgecolor="black", linewidth=1.0, alpha=alpha,
                               zorder=zorder + 0.1)
        ax.add_patch(self.outline)
        self.wheels = []
        for _wheel in spec.wheels:
            patch = Polygon(np.zeros((4, 2)), closed=True, facecolor=WHEEL_COLOUR,
                            edgecolor="black", linewidth=0.5, alpha=alpha, zorder=zorder + 0.2)
            ax.add_patch(patch)
            self.wheels.append(patch)
        self.rollers = None
        if spec.is_swedish:
            self.rollers = LineCollection([], colors="#bbbbbb", linewidths=1.0, alpha=alpha,
                                          zorder=zorder + 0.3)
            ax.add_collection(self.rollers)
        self.arrow = FancyArrow(0, 0, 1e-3, 0, width=0.04 * self._size,
                                head_width=0.18 * self._size, head_length=0.2 * self._size,
                                length_includes_head=True, color="black", alpha=alpha,
                                zorder=zorder + 0.4)
        ax.add_patch(self.arrow)
        (self.point,) = ax.plot([], [], "o", color="black", markersize=3, alpha=alpha,
                                zorder=zorder + 0.5)
        (self.icr,) = ax.plot([], [], marker="x", color=ICR_COLOUR, markersize=8,
                              linestyle="none", zorder=zorder + 0.5)
        self.icr_lines = LineCollection([], colors=ICR_COLOUR, linewidths=0.8,
                                        linestyles="dashed", zorder=zorder - 0.1)
        ax.add_collection(self.icr_lines)
        self.labels = []
        if labels:
            for wheel in spec.wheels:
                self.labels.append(ax.text(0, 0, wheel.name, fontsize=8, ha="center",
                                           va="center", zorder=zorder + 0.6))

    @property
    def artists(self) -> list:
        """Every artist of the drawing."""
        out = [self.body, self.outline, *self.wheels, self.arrow, self.point, self.icr,
               self.icr_lines, *self.labels]
        if self.rollers is not None:
            out.append(self.rollers)
        return out

    def update(self, pose: ArrayLike, steering: ArrayLike | None = None,
               twist: ArrayLike | None = None, slipping: ArrayLike | None = None) -> None:
        """Move the drawing to ``pose`` (x, y, theta) with ``steering`` (``steered_names``
        order), show the ICR of body ``twist`` (if ``show_icr``) and colour the ``slipping``
        driven wheels (bool per ``wheel_names``) red."""
        spec = self.spec
        pose = _pose(pose)
        k = len(spec.steered_names)
        steer = np.zeros(k) if steering is None else V.shaped("steering", steering, (k,))
        if steer.shape != (k,) or np.any(np.abs(steer) > math.pi):
            raise ValueError(f"steering must be {k} angles in [-pi, pi] "
                             f"({', '.join(spec.steered_names) or 'none'}), got {steering!r}")
        per_wheel = dict(zip(spec.wheel_names, spec.steering_of(steer), strict=True))
        tw = None
        if twist is not None:
            tw = V.twist("twist", twist)
            if max(abs(tw[0]), abs(tw[1])) > MAX_SPEED or abs(tw[2]) > MAX_YAW_RATE:
                raise ValueError(f"twist must be one (vx, vy, omega) within {MAX_SPEED:g} m/s "
                                 f"and {MAX_YAW_RATE:g} rad/s, got {twist!r}")
        slip = {}
        if slipping is not None:
            flags = np.asarray(slipping)
            if flags.dtype != bool:
                raise ValueError(f"slipping must be booleans (one per driven wheel), "
                                 f"got {slipping!r}")
            if flags.shape != (len(spec.wheel_names),):
                raise ValueError(f"slipping must have {len(spec.wheel_names)} flags, "
                                 f"got shape {flags.shape}")
            slip = dict(zip(spec.wheel_names, flags.tolist(), strict=True))
        body = _to_world(pose, np.array(spec.body))
        self.body.set_xy(body)
        self.outline.set_xy(body)
        roller_segments = []
        for wheel, patch in zip(spec.wheels, self.wheels, strict=True):
            angle = wheel.heading + per_wheel.get(wheel.name, 0.0)
            if wheel.kind == "caster" and tw is not None:
                px, py = wheel.position
                cx, cy = tw[0] - tw[2] * py, tw[1] + tw[2] * px
                if math.hypot(cx, cy) > 1e-9:
                    angle = math.atan2(cy, cx)
            patch.set_xy(_to_world(pose, _wheel_outline(wheel, angle)))
            patch.set_facecolor(SLIP_COLOUR if slip.get(wheel.name, False) else WHEEL_COLOUR)
            if wheel.kind == "swedish":
                for seg in _rollers(wheel, angle):
                    roller_segments.append(_to_world(pose, seg))
        if self.rollers is not None:
            self.rollers.set_segments(roller_segments)
        x, y, th = pose
        length = 0.9 * self._size
        self.arrow.set_data(x=x, y=y, dx=length * math.cos(th), dy=length * math.sin(th))
        self.point.set_data([x], [y])
        for wheel, text in zip(spec.wheels, self.labels, strict=False):
            px, py = wheel.position
            dist = max(math.hypot(px, py), 1e-9)
            scale = 1.0 + (1.4 * wheel.wheel_radius + 0.08 * self._size) / dist
            (lx, ly), = _to_world(pose, np.array([[px * scale, py * scale]]))
            text.set_position((lx, ly))
        icr = None
        if self.show_icr and tw is not None and abs(tw[2]) > 1e-9:
            local = np.array([[-tw[1] / tw[2], tw[0] / tw[2]]])
            if np.hypot(*local[0]) < 50 * self._size:
                icr = _to_world(pose, local)[0]
        if icr is None:
            self.icr.set_data([], [])
            self.icr_lines.set_segments([])
        else:
            self.icr.set_data([icr[0]], [icr[1]])
            pts = _to_world(pose, np.array([w.position for w in spec.driven_wheels]))
            self.icr_lines.set_segments([np.array([icr, p]) for p in pts])

    def remove(self) -> None:
        """Take the drawing off its axes."""
        for artist in self.artists:
            artist.remove()


def draw_vehicle(ax: Axes, spec: VehicleSpec, pose: ArrayLike, steering: ArrayLike | None = None, *,
                 show_icr: bool = False, twist: ArrayLike | None = None,
                 slipping: ArrayLike | None = None, labels: bool = False, color: str = PALETTE[0],
                 alpha: float = 1.0, zorder: float = 3.0) -> VehicleDrawing:
    """Draw ``spec`` top-down at ``pose`` on ``ax``; returns a handle to move it.

    Parameters
    ----------
    ax : matplotlib Axes
        Should have an equal aspect ratio (``ax.set_aspect("equal")``).
    spec : VehicleSpec
    pose : (x, y, theta)
        m, m, rad.
    steering : array_like, optional
        Steering angles, rad, ``spec.steered_names`` order (default 0).
    show_icr : bool
        Mark the instantaneous centre of rotation of ``twist`` (when omega != 0 and the ICR is
        within 50 vehicle sizes) and draw dashed lines from it to each driven wheel.
    twist : (vx, vy, omega), optional
        Body twist, for the ICR and the caster's swivel.
    slipping : array_like of bool, optional
        Per driven wheel; slipping wheels are drawn red.
    labels : bool
        Write each wheel's name beside it.
    color, alpha, zorder
        Body colour, opacity, drawing order.

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from wheelkin.sandbox import RADON_ULZER
    >>> ax = Figure().add_subplot()
    >>> drawing = draw_vehicle(ax, RADON_ULZER, (0, 0, 0), show_icr=True, twist=(0.2, 0, 1))
    >>> drawing.icr.get_data()     # ICR at (0, v / omega) = (0, 0.2)
    ([np.float64(0.0)], [np.float64(0.2)])
    >>> drawing.update((1.0, 0.0, 0.5))
    """
    drawing = VehicleDrawing(ax, spec, color=color, show_icr=show_icr, labels=labels,
                             alpha=alpha, zorder=zorder)
    drawing.update(pose, steering, twist, slipping)
    # Let the axes' autoscaling see the drawing (its artists were created empty).
    points = [drawing.body.get_xy()] + [patch.get_xy() for patch in drawing.wheels]
    points += [np.array(text.get_position())[None] for text in drawing.labels]
    icr = drawing.icr.get_data()
    if len(icr[0]):
        points.append(np.column_stack(icr))
    ax.update_datalim(np.concatenate(points))
    ax.autoscale_view()
    return drawing


class _PaletteHTMLWriter(HTMLWriter):
    """HTMLWriter that draws frames fast, optionally with a small colour palette.

    The figure's static part (axes, grid, walls, plan, legend) is drawn once; each frame then
    restores it and draws only the moving artists (blitting), several times faster than
    redrawing the figure. With ``colors``, frames are stored as palette PNGs (no dithering),
    3-4 times smaller (``wheelkin.animation.to_html`` does that too, by default).
    """

    def __init__(self, *args, colors: int | None = None, dynamic=(), **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.colors = colors
        self.dynamic = sorted(dynamic, key=lambda a: a.get_zorder())
        self._background = None

    def setup(self, fig, outfile, dpi=None, frame_dir=None) -> None:
        super().setup(fig, outfile, dpi, frame_dir)
        self.frame_format = "png"
        if not isinstance(fig.canvas, FigureCanvasAgg):
            FigureCanvasAgg(fig)

    def grab_frame(self, **savefig_kwargs) -> None:
        from PIL import Image

        canvas = self.fig.canvas
        if self._background is None:
            shown = [artist.get_visible() for artist in self.dynamic]
            for artist in self.dynamic:
                artist.set_visible(False)  # the background: everything that does not move
            canvas.draw()
            self._background = canvas.copy_from_bbox(self.fig.bbox)
            for artist, visible in zip(self.dynamic, shown, strict=True):
                artist.set_visible(visible)
        canvas.restore_region(self._background)
        for artist in self.dynamic:
            self.fig.draw_artist(artist)
        image = Image.frombuffer("RGBA", canvas.get_width_height(), canvas.buffer_rgba(),
                                 "raw", "RGBA", 0, 1).convert("RGB")
        if self.colors is not None:
            image = image.quantize(colors=self.colors, method=Image.Quantize.MEDIANCUT,
                                   dither=Image.Dither.NONE)
        out = BytesIO()
        image.save(out, format="png", compress_level=9 if self.colors else 6)
        data = base64.encodebytes(out.getvalue()).decode("ascii")
        self._total_bytes += len(data)
        self._saved_frames.append(data)


def _colors(value) -> int | None:
    if value is not None and (isinstance(value, bool) or not isinstance(value, int | np.integer)
                              or not 2 <= value <= 256):
        raise ValueError(f"colors must be an integer in [2, 256] or None, got {value!r}")
    return None if value is None else int(value)


class SandboxAnimation(FuncAnimation):
    """A FuncAnimation whose :meth:`to_jshtml` blits its frames (``dynamic`` lists the artists
    that move; the rest is drawn once) and optionally stores them with a palette of
    ``colors`` colours (2..256, or None for full colour).

    ``fig``, ``func`` and ``frames`` (an int >= 1, a non-empty sequence or an iterator; not
    None: the player needs an end) are matplotlib's; further keyword arguments go to
    :class:`~matplotlib.animation.FuncAnimation`.
    """

    def __init__(self, fig: Figure, func: Callable[..., Any], frames: Any, *,
                 colors: int | None = None, dynamic: Iterable[Artist] = (),
                 **kwargs: Any) -> None:
        if not isinstance(fig, Figure):
            raise ValueError(f"fig must be a matplotlib Figure, got {type(fig).__name__}")
        if not callable(func):
            raise ValueError(f"func must be callable (frame) -> artists, got {func!r}")
        if frames is None or isinstance(frames, bool | float | str | bytes) or (
                isinstance(frames, int | np.integer) and frames < 1) or (
                isinstance(frames, Sequence | np.ndarray) and len(frames) == 0) or not (
                isinstance(frames, int | np.integer) or hasattr(frames, "__iter__")):
            raise ValueError(f"frames must be an integer >= 1, a non-empty sequence or an "
                             f"iterator, got {frames!r}")
        self._colors = _colors(colors)
        if isinstance(dynamic, str) or not hasattr(dynamic, "__iter__"):
            raise ValueError(f"dynamic must be a sequence of matplotlib artists, got {dynamic!r}")
        self._dynamic = list(dynamic)
        if not all(isinstance(a, Artist) for a in self._dynamic):
            raise ValueError(f"dynamic must be a sequence of matplotlib artists, got {dynamic!r}")
        super().__init__(fig, func, frames, **kwargs)

    _grabbing = False

    def _post_draw(self, framedata, blit) -> None:
        if not self._grabbing:  # the palette writer draws each frame itself
            super()._post_draw(framedata, blit)

    def to_jshtml(self, fps: float | None = None, embed_frames: bool = True,
                  default_mode: str | None = None) -> str:
        """The animation as an HTML player (matplotlib's), its frames blitted; ``fps`` in
        [0.01, 1000] (default: from the interval), ``default_mode`` "loop", "once" or
        "reflect"."""
        if fps is not None:
            fps = V.in_range("fps", fps, 0.01, 1000.0)
        _flag("embed_frames", embed_frames)
        if default_mode is not None:
            V.choice("default_mode", default_mode, ("loop", "once", "reflect"))
        if not embed_frames:  # pragma: no cover - the book always embeds
            return super().to_jshtml(fps, embed_frames, default_mode)
        if fps is None:
            fps = 1000 / self._interval
        if default_mode is None:
            default_mode = "loop" if getattr(self, "_repeat", False) else "once"
        if not hasattr(self, "_html_representation"):
            with TemporaryDirectory() as tmpdir:
                path = Path(tmpdir, "temp.html")
                writer = _PaletteHTMLWriter(fps=fps, embed_frames=True,
                                            default_mode=default_mode, colors=self._colors,
                                            dynamic=self._dynamic)
                self._grabbing = True
                try:
                    self.save(str(path), writer=writer, dpi=self._fig.dpi)
                finally:
                    self._grabbing = False
                self._html_representation = path.read_text()
        return self._html_representation


def _as_list(value, kind, name):
    if isinstance(value, kind):
        return [value]
    if isinstance(value, Sequence) and value and all(isinstance(v, kind) for v in value):
        return list(value)
    raise ValueError(f"{name} must be a {kind.__name__} or a non-empty list of them, "
                     f"got {type(value).__name__}")


def animate(
    trajectory: Trajectory | Sequence[Trajectory],
    spec: VehicleSpec | Sequence[VehicleSpec],
    *,
    walls: Sequence = (),
    plan: ArrayLike | None = None,
    extra_paths: Mapping | None = None,
    frames: int = 60,
    trail: bool = True,
    title: str | None = None,
    figsize: tuple[float, float] = (6.7, 4.2),
    dpi: int = 100,
    show_icr: bool = False,
    names: Sequence[str] | None = None,
    interval: float | None = None,
    limits: ArrayLike | None = None,
    colors: int | None = None,
    legend: str = "lower right",
    until: float | None = None,
) -> SandboxAnimation:
    """Animate recorded trajectories top-down.

    Parameters
    ----------
    trajectory : Trajectory or list of Trajectory
        Several are drawn together (e.g. a slipping vehicle beside its no-slip twin); they are
        sampled at the same frame times, so record them with the same step and duration.
    spec : VehicleSpec or list of VehicleSpec
        One per trajectory.
    walls : sequence of ((x0, y0), (x1, y1))
        Wall segments drawn as thick grey lines.
    plan : (M, 2) array_like, optional
        A planned path, drawn dashed.
    extra_paths : {label: (N, 2) or (N, 3) array_like}, optional
        Further paths (e.g. an odometry estimate) drawn progressively with the animation
        (a path's points are spread evenly over the animation's duration).
    frames : int
        Number of frames (2..400), spread evenly over the trajectory (up to ``until``).
    trail : bool
        Draw the path travelled so far.
    title : str, optional
    figsize, dpi
        Figure size (in, each side in [1, 20]) and resolution (in [10, 600]).
    show_icr : bool
        Mark the ICR of each vehicle.
    names : list of str, optional
        Legend labels (default: the specs' names when there are several vehicles).
    interval : float, optional
        Milliseconds between frames, in [1, 60000] (default: real time, within 40-250 ms).
    limits : (xmin, xmax, ymin, ymax), optional
        Axes limits, xmin < xmax, ymin < ymax (default: fitted to everything drawn).
    colors : int or None
        Palette size of the frames ``to_jshtml`` embeds (2..256), or None for full colour
        (``wheelkin.animation.to_html`` re-encodes them with a palette anyway).
    legend : str
        Where the legend goes (one of :data:`LEGEND_PLACES`): a place inside the axes where no
        vehicle drives, or "outside" (to the right of the axes, which shrink to make room).
    until : float, optional
        Last time shown, s, in (0, end of the longest trajectory] (default: that end), e.g.
        the moment a lap is finished; ``extra_paths`` are then spread over 0..until, so pass
        only their points up to that time.

    Returns
    -------
    SandboxAnimation
        A matplotlib FuncAnimation of a figure not registered with pyplot (it is not shown
        by itself); display it with ``wheelkin.animation.show(anim, name=..., alt=...)``.
    """
    trajs = _as_list(trajectory, Trajectory, "trajectory")
    specs = _as_list(spec, VehicleSpec, "spec")
    if len(specs) != len(trajs):
        raise ValueError(f"spec must give one VehicleSpec per trajectory ({len(trajs)}), "
                         f"got {len(specs)}")
    if isinstance(frames, bool) or not isinstance(frames, int | np.integer) \
            or not 2 <= frames <= 400:
        raise ValueError(f"frames must be an integer in [2, 400], got {frames!r}")
    dpi = V.in_range("dpi", dpi, *DPI_RANGE)
    size = V.shaped("figsize", figsize, (2,))
    if size.shape != (2,) or np.any(size < FIGSIZE_RANGE[0]) or np.any(size > FIGSIZE_RANGE[1]):
        raise ValueError(f"figsize must be (width, height) in inches, each in "
                         f"[{FIGSIZE_RANGE[0]:g}, {FIGSIZE_RANGE[1]:g}], got {figsize!r}")
    trail, show_icr = _flag("trail", trail), _flag("show_icr", show_icr)
    if title is not None and not isinstance(title, str):
        raise ValueError(f"title must be a string or None, got {title!r}")
    if isinstance(walls, str | bytes) or not isinstance(walls, Sequence | np.ndarray):
        raise ValueError(f"walls must be a sequence of segments ((x0, y0), (x1, y1)), "
                         f"got {walls!r}")
    wall_list = [_points(f"walls[{i}]", w) for i, w in enumerate(walls)]
    if any(w.shape != (2, 2) for w in wall_list):
        raise ValueError("walls must be segments ((x0, y0), (x1, y1))")
    plan_arr = None if plan is None else _points("plan", plan)
    if extra_paths is not None and not isinstance(extra_paths, Mapping):
        raise ValueError(f"extra_paths must be a mapping {{label: path}}, got {extra_paths!r}")
    extras = {}
    for label, path in (extra_paths or {}).items():
        arr = V.finite_array(f"extra_paths[{label!r}]", path)
        if arr.ndim != 2 or arr.shape[1] not in (2, 3) or len(arr) < 1:
            raise ValueError(f"extra_paths[{label!r}] must have shape (N, 2) or (N, 3), "
                             f"got {arr.shape}")
        extras[str(label)] = _points(f"extra_paths[{label!r}]", arr[:, :2])
    if names is None:
        names = [s.name for s in specs] if len(specs) > 1 else [None]
    if isinstance(names, str) or not isinstance(names, Sequence) \
            or not all(n is None or isinstance(n, str) for n in names):
        raise ValueError(f"names must be a list of str (or None entries), got {names!r}")
    names = list(names)
    if len(names) != len(trajs):
        raise ValueError(f"names must give one label per trajectory ({len(trajs)})")

    t_end = max(float(tr.t[-1]) for tr in trajs)
    if until is not None:
        last = V.finite("until", until)
        if not 0.0 < last <= t_end:
            raise ValueError(f"until must be in (0, {t_end:g}] s (the end of the longest "
                             f"trajectory), got {until!r}")
        t_end = last
    legend = V.choice("legend", legend, LEGEND_PLACES)
    times = np.linspace(0.0, t_end, frames)
    picks = [np.clip(np.searchsorted(tr.t, times - 1e-12), 0, len(tr) - 1) for tr in trajs]
    if interval is None:
        interval = min(250.0, max(40.0, 1000.0 * t_end / max(frames - 1, 1)))
    interval = V.in_range("interval", interval, *INTERVAL_RANGE)
    colors = _colors(colors)
    lim = None
    if limits is not None:
        lim = V.shaped("limits", limits, (4,))
        if lim.shape != (4,) or not (lim[0] < lim[1] and lim[2] < lim[3]) \
                or np.any(np.abs(lim) > MAX_COORDINATE):
            raise ValueError(f"limits must be (xmin, xmax, ymin, ymax) with xmin < xmax, "
                             f"ymin < ymax, within {MAX_COORDINATE:g} m, got {limits!r}")

    fig = Figure(figsize=tuple(size), dpi=dpi, layout=fixed_layout())
    ax = fig.add_subplot()
    ax.set_aspect("equal")
    ax.grid(True, color="#dddddd", linewidth=0.6)
    ax.set_axisbelow(True)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    if title:
        ax.set_title(title, fontsize=10)
    for w in wall_list:
        ax.plot(w[:, 0], w[:, 1], color="#555555", linewidth=3, solid_capstyle="round",
                zorder=1)
    if plan_arr is not None:
        ax.plot(plan_arr[:, 0], plan_arr[:, 1], "--", color="#999999", linewidth=1.2,
                label="plan", zorder=1.5)
    # Limits: everything that will be drawn, plus the vehicles' size.
    pts = [tr.pose[:, :2] for tr in trajs] + list(extras.values())
    pts += [w for w in wall_list]
    if plan_arr is not None:
        pts.append(plan_arr)
    allp = np.concatenate(pts)
    reach = max(max(math.hypot(*p) for p in s.body) + max(w.wheel_radius for w in s.wheels)
                for s in specs)
    if limits is None:
        lo, hi = allp.min(0) - 1.3 * reach, allp.max(0) + 1.3 * reach
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
    else:
        ax.set_xlim(lim[0], lim[1])
        ax.set_ylim(lim[2], lim[3])

    drawings, trails = [], []
    for i, (tr, sp) in enumerate(zip(trajs, specs, strict=True)):
        colour = PALETTE[i % len(PALETTE)]
        if trail:
            (line,) = ax.plot([], [], color=colour, linewidth=1.5, zorder=2, label=names[i])
            trails.append(line)
        elif names[i]:
            ax.plot([], [], color=colour, linewidth=6, label=names[i])
        drawings.append(draw_vehicle(ax, sp, tr.pose[0], tr.steering[0], show_icr=show_icr,
                                     twist=tr.twist[0], color=colour, zorder=3 + i))
    extra_lines = []
    for j, (label, arr) in enumerate(extras.items()):
        (line,) = ax.plot([], [], ":", color=PALETTE[(len(trajs) + j) % len(PALETTE)],
                          linewidth=1.5, label=label, zorder=2.5)
        extra_lines.append((line, arr))
    stamp = ax.text(0.03, 0.965, "", transform=ax.transAxes, ha="left", va="top", fontsize=9,
                    bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8,
                          "boxstyle": "square,pad=0.2"})  # clear of the spine and ticks
    if any(names) or extras or plan_arr is not None:
        if legend == "outside":
            ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                      fontsize=8, framealpha=0.8)
        else:
            ax.legend(loc=legend, fontsize=8, framealpha=0.8)
    fig.tight_layout()

    def update(f: int):
        for tr, idx, drawing in zip(trajs, picks, drawings, strict=True):
            i = int(idx[f])
            drawing.update(tr.pose[i], tr.steering[i], tr.twist[i], tr.slipping[i])
        for tr, idx, line in zip(trajs, picks, trails, strict=True):
            i = int(idx[f])
            line.set_data(tr.pose[: i + 1, 0], tr.pose[: i + 1, 1])
        frac = f / (frames - 1)
        for line, arr in extra_lines:
            j = round(frac * (len(arr) - 1)) + 1
            line.set_data(arr[:j, 0], arr[:j, 1])
        stamp.set_text(f"t = {times[f]:5.2f} s")
        return []

    dynamic = [a for d in drawings for a in d.artists] + trails
    dynamic += [line for line, _ in extra_lines] + [stamp]
    return SandboxAnimation(fig, update, frames=frames, interval=interval, blit=False,
                            repeat=True, colors=colors, dynamic=dynamic)
