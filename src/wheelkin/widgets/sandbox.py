"""The sandbox page's live panel (notebooks/02_sandbox): how much grip a turn needs.

Panel ``sandbox.slip``: the Radon Ulzer, already turning at 0.4 m/s and a yaw rate omega
(slider), keeps that command on a floor of friction coefficient mu (slider). The figure shows
the kinematic circle of the command (dashed), the sandbox's path for 2 s (red where the
wheels slip) and the robot at the end. A steady turn needs a centripetal acceleration
v omega; its two tracks carry the whole weight and can give at most mu g, so the robot holds
its circle while v omega <= mu g and slides off beyond (in the sandbox's model of the Zumo:
one rigid Coulomb contact per track). Starting from rest would add the acceleration of the
speed-up to the same friction budget.
"""

from __future__ import annotations

import math
from functools import lru_cache

import ipywidgets as widgets
import numpy as np
from matplotlib.figure import Figure

from wheelkin import _validate as V
from wheelkin import style
from wheelkin._kernels import arc_step
from wheelkin.sandbox import RADON_ULZER, World
from wheelkin.sandbox.render import draw_vehicle
from wheelkin.sandbox.vehicles import GRAVITY
from wheelkin.widgets import Panel, register
from wheelkin.widgets._blit import BlitList

__all__ = ["SlipView", "slip_panel"]

SPEED = 0.4  # m/s
DURATION = 2.0  # s
DT = 1 / 80  # a coarser step keeps a redraw within the slider budget


class SlipView:
    """The kinematic circle, the sandbox path and the robot; :meth:`update` redraws in place."""

    def __init__(self, fig: Figure) -> None:
        if not isinstance(fig, Figure):
            raise ValueError(f"fig must be a matplotlib Figure, got {type(fig).__name__}")
        self.fig = fig
        engine = fig.get_layout_engine()
        if engine is not None and not engine.adjust_compatible:
            fig.set_layout_engine(style.fixed_layout())  # the view lays its figure out by hand
        ax = self.ax = fig.add_subplot()
        fig.subplots_adjust(left=0.12, right=0.97, bottom=0.13, top=0.88)
        ax.set_aspect("equal")
        ax.set_xlim(-0.9, 1.6)
        ax.set_ylim(-0.9, 1.0)
        ax.grid(True, color="#dddddd", lw=0.6)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        (self.circle,) = ax.plot([], [], "k--", lw=1.0, label="kinematic model")
        (self.path,) = ax.plot([], [], color="#1f77b4", lw=1.5, label="sandbox")
        (self.slips,) = ax.plot([], [], ".", color="#d62728", ms=3, label="wheels slipping")
        self.robot = draw_vehicle(ax, RADON_ULZER, (0.0, 0.0, 0.0))
        ax.legend(loc="lower right", fontsize=8)
        self.title = ax.set_title("", fontsize=9)
        self.message = ax.text(0.5, 0.5, "", transform=ax.transAxes, ha="center",
                               va="center", color="#d62728")

        self._blit = BlitList(ax, [self.circle, self.path, self.slips, *self.robot.artists,
                                   self.title, self.message])

    def update(self, mu: float, omega: float) -> list:
        """Show the run for ``mu`` and ``omega``.

        Returns the artists it changed and what a full draw paints over them there (the
        frame; the legend when a path runs under it), in drawing order, for a blitting
        panel (the axes' limits are fixed). A value the model refuses (``mu`` in (0, 10],
        ``omega`` in [-1000, 1000] rad/s) is not raised but written on the figure."""
        try:
            run = _run(V.in_range("mu", mu, 0.0, 10.0), V.finite("omega", omega))
        except ValueError as exc:  # a value the model rejects: say so, do not raise
            self.message.set_text(str(exc))
            return self._blit()
        self.message.set_text("")
        ideal, pose, slipping, twist, title = run
        self.circle.set_data(ideal[:, 0], ideal[:, 1])
        self.path.set_data(pose[:, 0], pose[:, 1])
        slips = slipping.any(axis=1)
        self.slips.set_data(pose[slips, 0], pose[slips, 1])
        self.robot.update(pose[-1], twist=twist[-1], slipping=slipping[-1])
        self.title.set_text(title)
        return self._blit()


@lru_cache(maxsize=256)
def _run(mu: float, omega: float):
    """The sandbox's run and the kinematic model's path for one (mu, omega), remembered (a
    student drags a slider back and forth over the same values; a run is computed once):
    ``(ideal (N, 2), pose (N, 3), slipping (N, wheels), twist (N, 3), title)``."""
    spec = RADON_ULZER.replace(mu=mu)
    world = World(dt=DT)
    robot = world.add(spec, twist=(SPEED, 0.0, omega))  # already turning: a steady turn
    robot.command_twist(SPEED, 0.0, omega)
    traj = world.run(DURATION)
    # Kinematic model of the same constant command: the exact arc from the start.
    t = traj.t
    dx, dy, _ = arc_step(0.0, 0.0, 0.0, SPEED * t, omega * t)
    ideal = np.column_stack([dx, dy])
    need = SPEED * abs(omega)
    driven = sum(f for w, f in zip(spec.wheels, spec.load_fractions, strict=True)
                 if w.kind != "caster")  # the share of the weight on wheels that push
    grip = driven * spec.mu * GRAVITY
    off = math.dist(traj.pose[-1, :2], ideal[-1])
    title = (f"needs v·ω = {need:.2f} m/s², wheels grip ≤ {grip:.2f} m/s²; "
             f"off the model by {off * 100:.1f} cm after {DURATION:g} s")
    arrays = ideal, traj.pose, traj.slipping, traj.twist
    for array in arrays:
        array.flags.writeable = False  # shared by every later call with these values
    return (*arrays, title)


def slip_panel() -> Panel:
    """Sliders for the friction coefficient and the commanded yaw rate."""

    def setup():
        fig = Figure(figsize=(6.0, 4.6), dpi=100, layout=style.fixed_layout())
        return fig, SlipView(fig)

    def update(view: SlipView, mu: float, omega: float) -> list:
        return view.update(mu, omega)  # the moving artists: the panel blits them

    controls = {
        "mu": widgets.FloatSlider(value=0.8, min=0.05, max=1.0, step=0.05,
                                  description="friction μ",
                                  continuous_update=False),
        "omega": widgets.FloatSlider(value=2.0, min=0.0, max=6.0, step=0.25,
                                     description="yaw rate ω (rad/s)",
                                     continuous_update=False),
    }
    return Panel(controls, setup, update,
                 title="The Radon Ulzer turning at 0.4 m/s: the grip a turn needs")


register("sandbox.slip")(slip_panel)
