"""The closing chapter's live panel and its kernel-free twins (notebooks/08_one_model).

- :class:`ConstraintView`: the book's four vehicles side by side (the sandbox's ready-made
  specs), each asked for the same body twist: its steered wheels turned for it (by
  :func:`wheelkin.unified.steer_for_twist`), the velocity of every wheel's contact point, the
  sideways slip the twist would need (red: the wheel cannot follow it by rolling), the ICR,
  and the numbers of :func:`wheelkin.unified.mobility` and
  :func:`wheelkin.unified.slip_residual`. ``update(vx, vy, omega, steer)`` moves the artists.
- Panel ``unified.constraints`` (registered): sliders for the twist and a switch for the
  steering.
- :func:`twist_tour_animation`: the same view while the twist tours forward, every direction
  of a strafe, a tightening turn and a spin on the spot, for the HTML book.
- :func:`manoeuvre_animation`: sandbox runs of the four vehicles side by side;
  :func:`run_manoeuvres` makes them (the chapter's :data:`MANOEUVRES`, each vehicle commanded
  by the one model through :func:`wheelkin.sandbox.runs.drive_twist`).

Our frame (x forward, y left, omega counter-clockwise), SI.
"""

from __future__ import annotations

import math

import ipywidgets as widgets
import numpy as np
from matplotlib.figure import Figure

from wheelkin import unified
from wheelkin.sandbox import LAB_ROBOT, MECANUM_ROBOT, OPEN_SOURCE_ROVER, RADON_ULZER
from wheelkin.sandbox.render import PALETTE, SandboxAnimation, draw_vehicle
from wheelkin.sandbox.runs import drive_twist, one_model_commands, planned_poses
from wheelkin.style import fixed_layout
from wheelkin.widgets import Panel, register

__all__ = ["MANOEUVRES", "RAMP", "VEHICLES", "ConstraintView", "constraints_panel",
           "manoeuvre_animation", "run_manoeuvres", "tour_twists", "twist_tour_animation"]

#: The book's four vehicles as the sandbox builds them, in the chapter's order.
VEHICLES = {
    "differential drive": RADON_ULZER,
    "skid steer": LAB_ROBOT,
    "mecanum": MECANUM_ROBOT,
    "rover": OPEN_SOURCE_ROVER,
}
#: The chapter's manoeuvres in the sandbox: title -> the body twist asked for, for 2 s.
MANOEUVRES = {"strafe left 0.3 m/s for 2 s": (0.0, 0.3, 0.0),
              "turn on the spot 1 rad/s for 2 s": (0.0, 0.0, 1.0)}
#: s, each manoeuvre's command is ramped in over this time.
RAMP = 0.25
SLIDE_COLOUR = "#d62728"
VELOCITY_COLOUR = "#1f77b4"
#: Side slip below this (m/s) counts as none.
SLIP_FLOOR = 1e-9


def _to_the_edge(wheels, vectors: np.ndarray) -> np.ndarray:
    """From each wheel's centre to the edge of its drawn outline (the sandbox's: half-length
    the wheel radius, half-width 0.3 of it) in the direction of its vector (zero for a zero
    vector)."""
    out = np.zeros_like(vectors, dtype=float)
    for k, (w, v) in enumerate(zip(wheels, vectors, strict=True)):
        size = math.hypot(*v)
        if size == 0.0:
            continue
        u = np.asarray(v, dtype=float) / size
        along = abs(float(u @ w.rolling_direction))
        across = abs(float(u @ w.lateral_direction))
        r = w.wheel_radius
        out[k] = u * min(r / max(along, 1e-12), 0.3 * r / max(across, 1e-12))
    return out


def _reach(spec) -> float:
    return max(max(math.hypot(*p) for p in spec.body),
               max(math.hypot(*w.position) + w.wheel_radius for w in spec.wheels))


class ConstraintView:
    """The four vehicles asked for one body twist (see the module docstring).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        An empty figure; one axes per vehicle is added, ``columns`` to a row.
    vehicles : dict of str to VehicleSpec
        Default :data:`VEHICLES`.
    columns : int
        Axes per row (default 2: four vehicles in a 2 x 2 grid that fits the text column).
    arrow_speeds : dict of str to float, optional
        m/s, per vehicle: the speed drawn as an arrow ``arrow_reach`` of the vehicle's reach
        long (default 0.5 m/s for every vehicle).
    arrow_reach : float
        The length of an arrow of the vehicle's ``arrow_speeds``, as a fraction of its reach
        (default 0.8).

    Each blue arrow starts at the edge of its wheel's outline, in the direction it points, so
    that a slow contact point still shows which way it moves.
    """

    def __init__(self, fig: Figure, vehicles: dict | None = None, columns: int = 2,
                 arrow_speeds: dict[str, float] | None = None, arrow_reach: float = 0.8
                 ) -> None:
        if isinstance(columns, bool) or not isinstance(columns, int) or columns < 1:
            raise ValueError(f"columns must be a positive integer, got {columns!r}")
        arrow_speeds = dict(arrow_speeds or {})
        for name, speed in arrow_speeds.items():
            if not (isinstance(speed, (int, float)) and math.isfinite(speed) and speed > 0):
                raise ValueError(f"arrow_speeds[{name!r}] must be a speed > 0 (m/s), "
                                 f"got {speed!r}")
        self.vehicles = dict(VEHICLES if vehicles is None else vehicles)
        self.fig = fig
        n = len(self.vehicles)
        rows = -(-n // columns)
        self.axes, self.items = [], []
        for k, (name, spec) in enumerate(self.vehicles.items()):
            ax = fig.add_subplot(rows, columns, k + 1)
            reach = _reach(spec)
            lim = 1.5 * reach
            ax.set_xlim(-lim, lim)
            ax.set_ylim(-lim, lim)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            wheels = spec.wheels
            mob = unified.mobility(wheels)
            ax.set_title(f"{name}: δm = {mob.degree_of_mobility}, "
                         f"δs = {mob.degree_of_steerability} (rank C1 = {mob.rank_sliding})",
                         fontsize=9)
            drawing = draw_vehicle(ax, spec, (0.0, 0.0, 0.0), show_icr=True,
                                   twist=(0.0, 0.0, 0.0), color=PALETTE[k])
            points = np.array([w.position for w in wheels])
            zeros = np.zeros(len(wheels))
            velocity = ax.quiver(points[:, 0], points[:, 1], zeros, zeros, angles="xy",
                                 scale_units="xy", scale=1.0, color=VELOCITY_COLOUR,
                                 units="inches", width=0.025, zorder=8)
            slide = ax.quiver(points[:, 0], points[:, 1], zeros, zeros, angles="xy",
                              scale_units="xy", scale=1.0, color=SLIDE_COLOUR, units="inches",
                              width=0.03, zorder=9)
            text = ax.text(0.02, 0.03, "", transform=ax.transAxes, ha="left", va="bottom",
                           fontsize=9, bbox={"facecolor": "white", "edgecolor": "none",
                                             "alpha": 0.85})
            # arrows: arrow_speed (0.5 m/s unless given) drawn arrow_reach of the vehicle's reach
            arrow_speed = float(arrow_speeds.get(name, 0.5))
            self.axes.append(ax)
            self.items.append({"spec": spec, "wheels": wheels, "drawing": drawing,
                               "velocity": velocity, "slide": slide, "text": text,
                               "points": points, "scale": arrow_reach * reach / arrow_speed,
                               "lim": lim})
        self.fit(left=0.01, right=0.99, bottom=0.01, top=0.94, wspace=0.03, hspace=0.14)

    def fit(self, **adjust: float) -> None:
        """Lay the axes out (``Figure.subplots_adjust(**adjust)``), then widen each one's
        limits to fill its grid cell at equal scale, the vehicle and its arrows in view."""
        self.fig.subplots_adjust(**adjust)
        width, height = self.fig.get_size_inches()
        for ax, item in zip(self.axes, self.items, strict=True):
            box = ax.get_position(original=True)
            ratio = (box.height * height) / (box.width * width)
            lim = item["lim"]
            xspan, yspan = 2 * lim, 2 * lim  # at least this much in view
            if yspan / ratio >= xspan:
                xspan = yspan / ratio
            else:
                yspan = xspan * ratio
            ax.set_xlim(-xspan / 2, xspan / 2)
            ax.set_ylim(-yspan / 2, yspan / 2)

    @property
    def artists(self) -> list:
        """Every artist that :meth:`update` changes."""
        out = []
        for item in self.items:
            out += item["drawing"].artists
            out += [item["velocity"], item["slide"], item["text"]]
        return out

    def update(self, vx: float, vy: float, omega: float, steer: bool = True) -> list:
        """Ask every vehicle for the twist (vx m/s, vy m/s, omega rad/s); with ``steer`` the
        steered wheels are turned for it, otherwise they stay straight. Returns
        :attr:`artists`."""
        twist = np.array([float(vx), float(vy), float(omega)])
        for item in self.items:
            spec = item["spec"]
            wheels = item["wheels"]
            if steer:
                wheels = unified.steer_for_twist(wheels, twist)
            else:  # casters trail whatever happens
                steered = unified.steer_for_twist(wheels, twist)
                wheels = tuple(s if w.kind == "caster" else w
                               for w, s in zip(wheels, steered, strict=True))
            by_name = {w.name: w for w in wheels}
            steering = [by_name[name].steering for name in spec.steered_names]
            residual = unified.slip_residual(wheels, twist)
            pts = item["points"]
            vel = np.column_stack([twist[0] - twist[2] * pts[:, 1],
                                   twist[1] + twist[2] * pts[:, 0]])
            lateral = np.array([w.lateral_direction for w in wheels]) * residual[:, None]
            slips = np.abs(residual) > SLIP_FLOOR
            driven = [not (w.kind == "caster") for w in wheels]
            item["drawing"].update((0.0, 0.0, 0.0), steering, twist,
                                   slips[np.array(driven)])
            scale = item["scale"]
            item["velocity"].set_offsets(pts + _to_the_edge(wheels, vel))
            item["velocity"].set_UVC(vel[:, 0] * scale, vel[:, 1] * scale)
            item["slide"].set_UVC(lateral[:, 0] * scale, lateral[:, 1] * scale)
            worst = float(np.max(np.abs(residual)))
            if worst <= SLIP_FLOOR:
                item["text"].set_text("rolls, no side slip")
                item["text"].set_color("#1a7f37")
            else:
                item["text"].set_text(f"must slide: up to {worst:.3f} m/s")
                item["text"].set_color(SLIDE_COLOUR)
        return self.artists


def constraints_panel() -> Panel:
    """Sliders vx, vy (m/s), omega (rad/s) and "steer": the four vehicles asked for the twist.
    """
    controls = {
        "vx": widgets.FloatSlider(value=0.3, min=-0.5, max=0.5, step=0.05,
                                  description="forward vx (m/s)"),
        "vy": widgets.FloatSlider(value=0.0, min=-0.5, max=0.5, step=0.05,
                                  description="left vy (m/s)"),
        "omega": widgets.FloatSlider(value=0.0, min=-2.0, max=2.0, step=0.1,
                                     description="yaw rate ω (rad/s)"),
        "steer": widgets.Checkbox(value=True, description="steer the steered wheels"),
    }

    def setup():
        # 6.7 x 4.5 in: fits the column and a 1366 x 768 screen
        fig = Figure(figsize=(6.7, 4.5), layout=fixed_layout())
        return fig, ConstraintView(fig)

    def update(view, vx, vy, omega, steer):
        return view.update(vx, vy, omega, steer)

    return Panel(controls, setup, update,
                 title="One twist asked of four vehicles: blue, the contact velocities; red, "
                       "the sideways slip a wheel would need")


register("unified.constraints")(constraints_panel)


def tour_twists(frames: int = 48) -> np.ndarray:
    """The twists of :func:`twist_tour_animation`, shape (frames, 3): a strafe whose direction
    turns once round at 0.3 m/s (half the frames), then a left turn tightening from straight
    to a radius of 0.2 m (a quarter), then the forward speed falling to zero at 1.5 rad/s: a
    spin on the spot (a quarter)."""
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 8:
        raise ValueError(f"frames must be an integer >= 8, got {frames!r}")
    n1 = frames // 2
    n2 = (frames - n1) // 2
    n3 = frames - n1 - n2
    angle = np.linspace(0.0, 2 * math.pi, n1, endpoint=False)
    strafe = np.column_stack([0.3 * np.cos(angle), 0.3 * np.sin(angle), np.zeros(n1)])
    turn = np.column_stack([np.full(n2, 0.3), np.zeros(n2), np.linspace(0.0, 1.5, n2)])
    # the spin starts one step after the turn's last twist: no frame is shown twice
    spin = np.column_stack([np.linspace(0.3, 0.0, n3 + 1)[1:], np.zeros(n3), np.full(n3, 1.5)])
    return np.vstack([strafe, turn, spin])


def twist_tour_animation(frames: int = 32, figsize: tuple[float, float] = (6.7, 4.8), dpi: int = 100
                         ) -> SandboxAnimation:
    """The :class:`ConstraintView` while the twist tours :func:`tour_twists`, steered wheels
    steered; display with :func:`wheelkin.animation.show`. Each panel has its own arrow scale:
    the fastest contact point of its vehicle over the tour is drawn 0.7 of its reach long, which
    keeps every arrow in its panel."""
    twists = tour_twists(frames)
    fig = Figure(figsize=figsize, dpi=dpi, layout=fixed_layout())
    fastest = {}
    for name, spec in VEHICLES.items():
        points = np.array([w.position for w in spec.wheels])
        fastest[name] = float(max(
            np.hypot(vx - w * points[:, 1], vy + w * points[:, 0]).max()
            for vx, vy, w in twists))
    view = ConstraintView(fig, arrow_speeds=fastest, arrow_reach=0.7)
    view.fit(left=0.01, right=0.99, bottom=0.01, top=0.85, wspace=0.03, hspace=0.14)
    stamp = fig.text(0.5, 0.985, "", ha="center", va="top", fontsize=10)

    def update(f: int):
        vx, vy, w = twists[f]
        view.update(vx, vy, w, True)
        vx, vy, w = (round(float(c), 2) + 0.0 for c in (vx, vy, w))  # never "-0.00"
        stamp.set_text(f"asked: vx = {vx:+.2f} m/s, vy = {vy:+.2f} m/s, ω = {w:+.2f} rad/s")
        return []

    update(0)
    return SandboxAnimation(fig, update, frames=len(twists), interval=250, blit=False,
                            repeat=True, colors=64, dynamic=[*view.artists, stamp])


def run_manoeuvres(manoeuvres: dict | None = None, vehicles: dict | None = None, *,
                   duration: float = 2.0, ramp: float = RAMP,
                   dt: float = 1 / 240) -> dict[str, dict[str, tuple]]:
    """Every vehicle through every manoeuvre in the sandbox, commanded by the one model.

    Each run holds its manoeuvre's twist (ramped in over ``ramp`` seconds) for ``duration``
    seconds, the wheel commands from :func:`wheelkin.sandbox.runs.one_model_commands`,
    recorded at every step; its goal is the pose the same sampled commands plan
    (:func:`wheelkin.sandbox.runs.planned_poses`).

    Parameters
    ----------
    manoeuvres : dict of str to (vx, vy, omega), optional
        Default :data:`MANOEUVRES`.
    vehicles : dict of str to VehicleSpec, optional
        Default :data:`VEHICLES`.

    Returns
    -------
    dict
        ``{manoeuvre title: {vehicle name: (spec, trajectory, goal pose)}}``, as
        :func:`manoeuvre_animation` takes it.
    """
    runs: dict[str, dict[str, tuple]] = {}
    for title, twist in (MANOEUVRES if manoeuvres is None else manoeuvres).items():
        runs[title] = {}
        goal = planned_poses(lambda t_, twist=twist: twist, duration, dt=dt, ramp=ramp)[-1]
        for name, spec in (VEHICLES if vehicles is None else vehicles).items():
            traj = drive_twist(spec, lambda t_, twist=twist: twist, duration, dt=dt, ramp=ramp,
                               commands=one_model_commands, record_every=1)
            runs[title][name] = (spec, traj, goal)
    return runs


def manoeuvre_animation(runs: dict, frames: int = 24, figsize: tuple[float, float] = (6.7, 4.0),
                        dpi: int = 100) -> SandboxAnimation:
    """Sandbox runs of several vehicles side by side: one row per manoeuvre, one column per
    vehicle, every panel scaled to its own run, all manoeuvres played at once.

    Parameters
    ----------
    runs : dict of str to dict of str to (VehicleSpec, Trajectory, goal)
        ``{manoeuvre title: {vehicle name: (spec, trajectory, goal pose)}}``; every manoeuvre
        has the same vehicles and lasts as long. ``goal`` (x, y, theta) is the pose the twist
        asked for at the end, drawn as a faint outline.
    frames : int
        Frames of the animation (at most 40).
    """
    titles = list(runs)
    if not titles:
        raise ValueError("runs must hold at least one manoeuvre")
    names = list(runs[titles[0]])
    if any(list(runs[t]) != names for t in titles):
        raise ValueError("runs must give the same vehicles, in the same order, for every "
                         "manoeuvre")
    if isinstance(frames, bool) or not isinstance(frames, int) or not 2 <= frames <= 40:
        raise ValueError(f"frames must be an integer in [2, 40], got {frames!r}")
    fig = Figure(figsize=figsize, dpi=dpi, layout=fixed_layout())
    panels = []
    for row, title in enumerate(titles):
        for col, name in enumerate(names):
            spec, traj, goal = runs[title][name]
            ax = fig.add_subplot(len(titles), len(names), row * len(names) + col + 1)
            reach = _reach(spec)
            pts = np.vstack([traj.pose[:, :2], np.asarray(goal, dtype=float)[None, :2]])
            centre = (pts.min(0) + pts.max(0)) / 2
            half = float(np.ptp(pts, axis=0).max()) / 2 + 1.3 * reach
            ax.set_xlim(centre[0] - half, centre[0] + half)
            ax.set_ylim(centre[1] - half, centre[1] + half)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            if row == 0:
                ax.set_title(name.replace(" ", "\n", 1) if len(name) > 10 else name,
                             fontsize=9)
            if col == 0:
                ax.set_ylabel(title.split(" ")[0] if title.startswith("strafe") else "spin",
                              fontsize=9)
            ghost = draw_vehicle(ax, spec, goal, traj.steering[-1], color="#cccccc",
                                 alpha=0.5, zorder=1.5)
            drawing = draw_vehicle(ax, spec, (0.0, 0.0, 0.0), color=PALETTE[col], zorder=3)
            (line,) = ax.plot([], [], color=PALETTE[col], linewidth=1.2, zorder=2)
            panels.append((traj, drawing, ghost, line))
    duration = float(runs[titles[0]][names[0]][1].t[-1])
    stamp = fig.text(0.5, 0.985, "", ha="center", va="top", fontsize=9)
    fig.subplots_adjust(left=0.04, right=0.99, bottom=0.01, top=0.8, wspace=0.06,
                        hspace=0.06)
    times = np.linspace(0.0, duration, frames)

    def update(f: int):
        for traj, drawing, _, line in panels:
            i = int(np.clip(np.searchsorted(traj.t, times[f] - 1e-12), 0, len(traj) - 1))
            drawing.update(traj.pose[i], traj.steering[i], traj.twist[i], traj.slipping[i])
            line.set_data(traj.pose[: i + 1, 0], traj.pose[: i + 1, 1])
        stamp.set_text(f"t = {times[f]:4.2f} s\nred wheel: slipping; grey: the pose asked for "
                       f"at t = {duration:g} s")
        return []

    update(0)
    dynamic = [a for _, d, _, _ in panels for a in d.artists]
    dynamic += [line for *_, line in panels] + [stamp]
    return SandboxAnimation(fig, update, frames=frames, interval=150, blit=False,
                            repeat=True, colors=64, dynamic=dynamic)
