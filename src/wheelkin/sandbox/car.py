r"""A car-like vehicle in the sandbox: free-rolling steered front wheels, driven rear wheels.

The car's wheels are those of :func:`wheelkin.unified.car_wheels`: FL, FR (steered and rolling
freely, the spec's ``free_rolling``, so each constrains only its sliding velocity) and RL, RR
(fixed, driven). The reference point is the rear-axle
midpoint, as in the bicycle model of :mod:`wheelkin.carlike` (it is also the rigid body's mass
centre in the simulation; the normal loads are set per wheel, half on each axle by default).

A car is driven like a real one: a speed ``v`` of the rear-axle midpoint and one steering
command ``delta`` (the bicycle model's angle). A :class:`Steering` geometry turns ``delta`` into
the two front wheel angles:

``"ackermann"``
    the ideal angles of :func:`wheelkin.carlike.ackermann_angles` for ``R = L / tan(delta)``;
``"linkage"``
    a trapezoidal (Jeantaud) linkage: the inner wheel at its Ackermann angle, the outer where
    the linkage puts it (:func:`wheelkin.carlike.linkage_angles`);
``"parallel"``
    both wheels at ``delta``.

The rear wheels are driven at the rates of the bicycle twist, each rate imposed (as an
electronic differential would; an open differential would share the torque instead):
``phi_RL = v (1 - kappa W/2) / r``, ``phi_RR = v (1 + kappa W/2) / r``, ``kappa = tan(delta)/L``.
With ``"ackermann"`` every wheel can roll and the car follows the bicycle model exactly while it
grips; the other two make the front wheels disagree with the rear axle, and the tyres scrub.

>>> from wheelkin.sandbox import World
>>> world = World()
>>> robot = world.add(RC_CAR, twist=(1.0, 0.0, math.tan(0.2) / 0.33))  # already rolling
>>> drive(robot, 1.0, 0.2)
>>> world.step(240)                       # one second: the arc of R = L / tan(0.2)
>>> [round(v, 6) for v in robot.pose]
[0.938287, 0.297599, 0.614273]
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from wheelkin import _validate as V
from wheelkin import carlike, unified
from wheelkin._kernels import arc_step

from .vehicles import VehicleSpec, _finish, _rectangle
from .world import Robot, World

__all__ = [
    "GEOMETRIES",
    "RC_CAR",
    "FrontAngles",
    "PurePursuitDriver",
    "Steering",
    "car",
    "car_odometry",
    "drive",
    "front_angles",
]

GEOMETRIES = ("ackermann", "linkage", "parallel")


def car(
    *,
    wheelbase: float,
    track_width: float,
    wheel_radius: float,
    mass: float = 3.5,
    inertia: float | None = None,
    front_load: float = 0.5,
    body: npt.ArrayLike | None = None,
    name: str = "car",
    **kwargs: object,
) -> VehicleSpec:
    """A four-wheel car: free-rolling steered fronts FL, FR; fixed driven rears RL, RR.

    FL at (L, W/2), FR at (L, -W/2), RL at (0, W/2), RR at (0, -W/2): the reference point is
    the rear-axle midpoint. Steered wheels in (FL, FR) order.

    Parameters
    ----------
    wheelbase, track_width, wheel_radius : float
        L, W, r, m (> 0).
    mass, inertia : float
        kg, kg m^2 (inertia: the body outline as a uniform plate about the rear axle).
    front_load : float
        Share of the weight on the front axle, in (0, 1).
    body : sequence of (x, y), optional
        Outline (default: a rectangle from r behind the rear axle to r ahead of the front
        one, 0.8 W wide).
    **kwargs
        ``mu``, ``steps_per_rev``, ``encoder_noise``, ``seed``, ``motor_time_constant``.

    Examples
    --------
    >>> spec = car(wheelbase=0.33, track_width=0.27, wheel_radius=0.05)
    >>> spec.wheel_names, spec.steered_names
    (('FL', 'FR', 'RL', 'RR'), ('FL', 'FR'))
    >>> car(wheelbase=0.33, track_width=0.27, wheel_radius=0.05, front_load=1.0)
    Traceback (most recent call last):
    ...
    ValueError: front_load must be in (0, 1), got 1.0
    """
    L = V.positive("wheelbase", wheelbase)
    W = V.positive("track_width", track_width)
    r = V.positive("wheel_radius", wheel_radius)
    f = V.finite("front_load", front_load)
    if not 0.0 < f < 1.0:
        raise ValueError(f"front_load must be in (0, 1), got {front_load!r}")
    if body is None:
        body = _rectangle(-r, L + r, -0.4 * W, 0.4 * W)
    wheels = unified.car_wheels(wheelbase=L, track_width=W, wheel_radius=r)
    kwargs.setdefault("steered_names", ("FL", "FR"))
    kwargs.setdefault("free_rolling", ("FL", "FR"))
    loads = (f / 2, f / 2, (1 - f) / 2, (1 - f) / 2)
    return _finish(name, mass, inertia, body, wheels, loads, **kwargs)


#: A 1/10-scale car-like robot (F1TENTH class): L = 0.33 m, W = 0.27 m, r = 0.05 m, 3.5 kg;
#: steering limit 0.4189 rad (24 deg) on the inner wheel (our estimates of a typical build).
RC_CAR = car(wheelbase=0.33, track_width=0.27, wheel_radius=0.05, mass=3.5, name="1/10 car")
#: The steering limit used with :data:`RC_CAR`, rad.
RC_CAR_MAX_STEERING = 0.4189


def _car_robot(robot: object) -> Robot:
    if not isinstance(robot, Robot):
        raise ValueError(f"robot must be a sandbox Robot (World.add), got {type(robot).__name__}")
    return robot


@functools.lru_cache(maxsize=64)
def _car_geometry(spec: VehicleSpec) -> tuple[float, float, float]:
    """(L, W, r) of a :func:`car` spec; ValueError for another vehicle."""
    names = {w.name: w for w in spec.wheels}
    if set(spec.wheel_names) != {"FL", "FR", "RL", "RR"} or "FL" not in spec.free_rolling:
        raise ValueError(f"spec must be a car (see wheelkin.sandbox.car.car), got {spec.name!r}")
    L = names["FL"].position[0] - names["RL"].position[0]
    W = names["RL"].position[1] - names["RR"].position[1]
    return L, W, names["RL"].wheel_radius


@dataclass(frozen=True)
class Steering:
    """How the steering command becomes the two front wheel angles.

    Parameters
    ----------
    geometry : {"ackermann", "linkage", "parallel"}
    arm_length : float
        Linkage only: steering arm length a, m (> 0).
    arm_angle : float or None
        Linkage only: arm angle beta, rad (None: the Jeantaud rule, tan beta = W / (2 L)).

    Examples
    --------
    >>> Steering("parallel").geometry
    'parallel'
    >>> Steering("rack")
    Traceback (most recent call last):
    ...
    ValueError: geometry must be one of 'ackermann', 'linkage', 'parallel'; got 'rack'
    """

    geometry: str = "ackermann"
    arm_length: float = 0.04
    arm_angle: float | None = None

    def __post_init__(self) -> None:
        V.choice("geometry", self.geometry, GEOMETRIES)
        object.__setattr__(self, "arm_length", V.positive("arm_length", self.arm_length))
        if self.arm_angle is not None:
            b = V.finite("arm_angle", self.arm_angle)
            if not 0.0 <= b < math.pi / 2:
                raise ValueError(f"arm_angle must be in [0, pi/2) rad, got {self.arm_angle!r}")
            object.__setattr__(self, "arm_angle", b)


_DEFAULT = Steering()


class FrontAngles(NamedTuple):
    """The front wheels' steering angles (rad, positive to the left), FL and FR."""

    left: float
    right: float


def front_angles(steering: Steering, delta: float, wheelbase: float, track_width: float
                 ) -> FrontAngles:
    """(FL, FR) wheel angles, rad, for the bicycle steering command ``delta`` (rad).

    Examples
    --------
    >>> [round(math.degrees(a), 4) for a in front_angles(Steering(), 0.3, 0.33, 0.27)]
    [19.5018, 15.3543]
    """
    if not isinstance(steering, Steering):
        raise ValueError(f"steering must be a Steering, got {type(steering).__name__}")
    d = V.finite("delta", delta)
    if abs(d) >= math.pi / 2:
        raise ValueError(f"delta must be in (-pi/2, pi/2) rad, got {delta!r}")
    L = V.in_range("wheelbase", wheelbase, 1e-3, 1e3)
    W = V.in_range("track_width", track_width, 1e-3, 1e3)
    if steering.geometry == "parallel" or d == 0.0:
        return FrontAngles(d, d)
    t = math.tan(d)
    left = math.atan2(L * t, L - 0.5 * W * t)  # the ICR at (0, L/t) on the rear axle line
    right = -math.atan2(-L * t, L + 0.5 * W * t)
    if steering.geometry == "ackermann":
        return FrontAngles(left, right)
    inner = left if d > 0 else right
    beta = steering.arm_angle
    if beta is None:
        beta = math.atan2(W / 2, L)
    lk = carlike.linkage_angles(inner, track_width=W, arm_length=steering.arm_length,
                                arm_angle=beta)
    return FrontAngles(float(lk.left), float(lk.right))


def drive(robot: Robot, speed: float, delta: float, steering: Steering | None = None) -> None:
    """Command a car robot: rear-axle speed ``speed`` (m/s), steering ``delta`` (rad).

    The front wheels are steered by ``steering`` (default ideal Ackermann); the rear wheels
    turn at the bicycle twist's rates; the free front wheels' rates are their kinematic ones.
    Called every step by controllers, so it checks its arguments with plain floats.
    """
    L, W, r = _car_geometry(_car_robot(robot).spec)
    try:
        ok = not isinstance(speed, bool) and not isinstance(delta, bool)
        v, d = float(speed), float(delta)
        ok = ok and math.isfinite(v) and abs(d) < math.pi / 2
    except (TypeError, ValueError):
        ok = False
    if not ok:
        V.finite("speed", speed)
        raise ValueError(f"delta must be in (-pi/2, pi/2) rad, got {delta!r}")
    st = _DEFAULT if steering is None else steering
    fl, fr = front_angles(st, d, L, W)
    k = math.tan(d) / L
    w = v * k
    # Front wheels: the speed of their contact points in the bicycle twist (v, 0, w).
    sgn = 1.0 if v >= 0 else -1.0
    rates = [sgn * math.hypot(v - w * W / 2, w * L) / r,
             sgn * math.hypot(v + w * W / 2, w * L) / r,
             v * (1 - k * W / 2) / r, v * (1 + k * W / 2) / r]
    robot._steer_to((fl, fr))
    robot._cmd = rates
    if st.geometry == "ackermann":  # every wheel rolls: no consistency check needed
        warm = robot._warm
        warm.consistent_key, warm.consistent_rates, warm.consistent = robot._model, rates, True


def car_odometry(rear_angles: npt.ArrayLike, steering: npt.ArrayLike, wheelbase: float,
                 wheel_radius: float, pose0: npt.ArrayLike = (0.0, 0.0, 0.0)) -> np.ndarray:
    r"""Dead reckoning of a car from its rear wheel angles and its steering command.

    Per interval k: the rear-axle midpoint travels
    :math:`\Delta s_k = r(\Delta\varphi_{RL} + \Delta\varphi_{RR})/2` and turns by
    :math:`\Delta\theta_k = \Delta s_k \tan\delta_k / L` (the bicycle model with the steering
    :math:`\delta_k` held over the interval); the pose moves along that arc
    (:func:`wheelkin._kernels.arc_step`).

    Parameters
    ----------
    rear_angles : array_like (N, 2)
        Cumulative rear wheel angles (RL, RR), rad (e.g. encoder readings converted).
    steering : array_like (N - 1,) or (N,)
        Bicycle steering angle over each interval, rad (a length-N array: its first N - 1).
    wheelbase, wheel_radius : float
        L, r, m.
    pose0 : (x, y, theta)
        Start pose.

    Returns
    -------
    ndarray (N, 3)

    Examples
    --------
    >>> phi = np.array([[0.0, 0.0], [20.0, 20.0]])
    >>> car_odometry(phi, [0.0], 0.33, 0.05).round(6).tolist()
    [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
    """
    phi = V.shaped("rear_angles", rear_angles, (2,))
    if phi.ndim != 2 or len(phi) < 1:
        raise ValueError(f"rear_angles must have shape (N, 2), got shape {phi.shape}")
    n = len(phi) - 1
    d = V.finite_array("steering", steering).reshape(-1)
    if len(d) == n + 1:
        d = d[:n]
    if len(d) != n:
        raise ValueError(f"steering must have {n} or {n + 1} values, got {len(d)}")
    if np.any(np.abs(d) >= math.pi / 2):
        raise ValueError("steering must be in (-pi/2, pi/2) rad")
    L = V.in_range("wheelbase", wheelbase, 1e-3, 1e3)
    r = V.in_range("wheel_radius", wheel_radius, 1e-4, 1e2)
    p0 = V.pose("pose0", pose0)
    ds = r * np.diff(phi, axis=0).mean(axis=1)
    dth = ds * np.tan(d) / L
    theta = p0[2] + np.concatenate([[0.0], np.cumsum(dth)])
    dx, dy, _ = arc_step(0.0, 0.0, theta[:-1], ds, dth)
    out = np.empty((n + 1, 3))
    out[:, 0] = p0[0] + np.concatenate([[0.0], np.cumsum(dx)])
    out[:, 1] = p0[1] + np.concatenate([[0.0], np.cumsum(dy)])
    out[:, 2] = theta
    return out


class PurePursuitDriver:
    r"""A pure-pursuit controller for :meth:`wheelkin.sandbox.world.World.run`: steer towards
    a look-ahead point.

    Each call finds the path point closest to the rear-axle midpoint (searching forward from
    the last one), walks ``lookahead`` metres along the path, expresses that point in the car's
    frame and steers with :math:`\delta = \arctan(L\,\kappa)`,
    :math:`\kappa = 2y/L_d^2` (:func:`wheelkin.carlike.pure_pursuit_curvature`), clipped to
    ``max_steering``. It stops the car at the end of the path.

    Parameters
    ----------
    robot : Robot
        A car (:func:`car`).
    path : array_like (M, 2)
        Densely sampled path, m.
    speed : float
        m/s.
    lookahead : float
        :math:`L_d`, m (> 0).
    max_steering : float
        rad, in (0, pi/2).
    steering : Steering, optional
        Front geometry (default ideal Ackermann).

    Attributes
    ----------
    log : list of float
        The steering command of each call (rad).
    """

    def __init__(self, robot: Robot, path: npt.ArrayLike, speed: float, lookahead: float,
                 max_steering: float, steering: Steering | None = None) -> None:
        self.robot = _car_robot(robot)
        self.L, self.W, self.r = _car_geometry(robot.spec)
        p = V.shaped("path", path, (2,))
        if p.ndim != 2 or len(p) < 2:
            raise ValueError(f"path must have shape (M, 2), M >= 2, got shape {p.shape}")
        self.path = p
        seg = np.hypot(*np.diff(p, axis=0).T)
        self.s = np.concatenate([[0.0], np.cumsum(seg)])
        self.speed = V.finite("speed", speed)
        self.lookahead = V.positive("lookahead", lookahead)
        self.max_steering = V.finite("max_steering", max_steering)
        if not 0 < self.max_steering < math.pi / 2:
            raise ValueError(f"max_steering must be in (0, pi/2), got {max_steering!r}")
        if steering is not None and not isinstance(steering, Steering):
            raise ValueError(f"steering must be a Steering or None, got {steering!r}")
        self.steering = Steering() if steering is None else steering
        self.index = 0
        self.log: list[float] = []
        self.done = False

    def __call__(self, t: float, world: World) -> None:
        x, y, th = self.robot.pose
        p = self.path
        hi = min(len(p), self.index + 400)
        d2 = (p[self.index:hi, 0] - x) ** 2 + (p[self.index:hi, 1] - y) ** 2
        self.index += int(np.argmin(d2))
        target_s = self.s[self.index] + self.lookahead
        if self.index >= len(p) - 2 or self.done:
            self.done = True
            drive(self.robot, 0.0, 0.0, self.steering)
            self.log.append(0.0)
            return
        j = int(np.searchsorted(self.s, target_s))
        gx, gy = p[min(j, len(p) - 1)]
        c, s = math.cos(th), math.sin(th)
        bx, by = c * (gx - x) + s * (gy - y), -s * (gx - x) + c * (gy - y)
        k = 2.0 * by / (bx * bx + by * by)
        delta = max(-self.max_steering, min(self.max_steering, math.atan(self.L * k)))
        self.log.append(delta)
        drive(self.robot, self.speed, delta, self.steering)
