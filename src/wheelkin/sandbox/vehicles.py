r"""Vehicles for the sandbox: a rigid body on the wheels of :mod:`wheelkin.unified`.

A vehicle is a frozen :class:`VehicleSpec`: a rigid body (mass, yaw inertia, a convex outline)
on wheels that are :class:`wheelkin.unified.WheelConstraint` s, the one wheel model of the
library (chapter 8), plus what physics needs and kinematics does not: the share of the weight
on each wheel (``load_fractions``) and which steered wheels roll freely (``free_rolling``).
All coordinates are in the body frame of REP-103 (x forward, y left, metres), measured from
the vehicle's *reference point*: the axle midpoint of a differential drive, the rear-axle
midpoint of a car, the geometric centre of the others. The reference point is also the rigid
body's mass centre in the simulation (a simplification: the normal load on each wheel is set
separately, by its load fraction).

What the ground contact constrains (see :mod:`.contact`), by the wheel's kind:

``"fixed"`` / ``"steered"``
    a conventional wheel: the contact point's velocity along the rolling direction
    :math:`\mathbf e` equals the rim speed :math:`r_w\dot\varphi`, across it (along
    :math:`\mathbf n`) zero, both friction-limited by one Coulomb circle
    (:func:`wheelkin.unified.rolling_row`, :func:`~wheelkin.unified.sliding_row`);
``"swedish"``
    a mecanum or omni wheel: only the velocity along the ground roller's axis :math:`\mathbf u`
    is constrained, to :math:`r_w\dot\varphi\,(\mathbf u\cdot\mathbf e)`
    (:func:`wheelkin.unified.roller_row`);
``"caster"``
    a passive swivel wheel: it carries its share of the weight and exerts no force;
a steered wheel named in ``free_rolling``
    rolls freely (no drive torque, a car's front wheel): only its sliding row is enforced.
    Its "rate" is not a command but the rate it rolls at in the kinematic model (what its
    wheel angle and encoder record).

Every wheel but a caster has a rate: commanded in wheel terms, an angular rate
:math:`\dot\varphi` (rad/s, positive rolling forward along :math:`\mathbf e`) per wheel in
:attr:`VehicleSpec.wheel_names` order, and a steering angle :math:`\delta` (rad,
counter-clockwise) per steered wheel in ``VehicleSpec.steered_names`` order. The spec holds
its wheels at zero steering; the robot's steering is state, commanded while it runs.
:func:`ideal_commands` turns a body twist into the rates (and steering) of the ideal kinematic
model.

The ready-made vehicles take their geometry from the chapters' modules; where the sources are
silent, the values are our assumptions:

========================= =========================================================== ========
spec                      geometry                                                    mass
========================= =========================================================== ========
:data:`RADON_ULZER`       diff drive, track 0.085 m, wheel circumference 0.113097 m,  0.25 kg
                          encoder 12 * 75.81 counts per wheel revolution (8043 /m);
                          the Zumo's two tracks, one contact each, no caster
:data:`LAB_ROBOT`         skid steer, wheels r = 0.04 m at x = +-0.05 m,              1.4 kg
                          y = +-0.06 m, body 0.2 m x 0.1 m (Webots 4-wheel robot)
:data:`MECANUM_ROBOT`     mecanum, r = 0.05 m, half wheelbase 0.15 m, half track      4.0 kg
                          0.15 m, rollers at 45 deg (a generic 30 cm platform)
:data:`OPEN_SOURCE_ROVER` six wheels, four corners steered,                           11 kg
                          :data:`wheelkin.rover.OSR_GEOMETRY`, r = 0.06 m
========================= =========================================================== ========

The yaw inertia defaults to that of the body outline as a uniform plate about the reference
point. The friction coefficient defaults to 0.8 (rubber on a dry floor).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from wheelkin import _validate as V
from wheelkin import rover as rover_model
from wheelkin import unified
from wheelkin.frames import fold_half_turn
from wheelkin.mecanum import MecanumGeometry
from wheelkin.unified import WheelConstraint

__all__ = [
    "GRAVITY",
    "LAB_ROBOT",
    "MECANUM_ROBOT",
    "OPEN_SOURCE_ROVER",
    "RADON_ULZER",
    "IdealCommands",
    "VehicleSpec",
    "diff_drive",
    "ideal_commands",
    "mecanum",
    "polygon_inertia",
    "rover",
    "skid_steer",
]

#: Gravitational acceleration used for the wheels' normal loads, N_i = load_fraction * m * g.
GRAVITY = 9.81


def _rank3(rows: list) -> bool:
    sv = np.linalg.svd(np.array(rows), compute_uv=False)
    return len(sv) == 3 and bool(sv[-1] > 1e-9 * sv[0])


def polygon_inertia(mass: float, vertices: npt.ArrayLike) -> float:
    r"""Yaw moment of inertia of a uniform polygonal plate about the body-frame origin.

    For the outline's vertices :math:`p_k` (counter-clockwise or clockwise),

    .. math:: I = m\,\frac{\sum_k c_k\,(p_k\cdot p_k + p_k\cdot p_{k+1}
              + p_{k+1}\cdot p_{k+1})}{6\sum_k c_k}, \qquad c_k = p_k \times p_{k+1},

    in kg m^2 (the origin need not be the centroid).

    Examples
    --------
    A 0.2 m x 0.1 m plate of 1 kg about its centre: m (a^2 + b^2) / 12.

    >>> round(polygon_inertia(1.0, [(-0.1, -0.05), (0.1, -0.05), (0.1, 0.05), (-0.1, 0.05)]), 6)
    0.004167
    """
    m = V.positive("mass", mass)
    p = V.shaped("vertices", vertices, (2,))
    if p.ndim != 2 or len(p) < 3:
        raise ValueError(f"vertices must hold at least 3 points (x, y), got shape {p.shape}")
    q = np.roll(p, -1, axis=0)
    cross = p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]
    if not abs(cross.sum()) >= 1e-15:
        raise ValueError("vertices must enclose a non-zero area")
    terms = (p * p).sum(1) + (p * q).sum(1) + (q * q).sum(1)
    inertia = float(m * (cross * terms).sum() / (6.0 * cross.sum()))
    if not math.isfinite(inertia):
        raise ValueError(f"vertices and mass give no finite inertia (got {inertia!r}): "
                         "use coordinates in metres and a mass in kg of sensible size")
    return inertia


@dataclass(frozen=True)
class VehicleSpec:
    """A vehicle: rigid body, wheels, friction, encoders and motors (SI, body frame).

    Parameters
    ----------
    name : str
        Shown in figures.
    mass : float
        kg (> 0).
    inertia : float
        Yaw moment of inertia about the reference point, kg m^2 (> 0).
    body : sequence of (x, y)
        Convex outline of the body (collision shape and drawing), m.
    wheels : tuple of wheelkin.unified.WheelConstraint
        All wheels, casters included, at zero steering (``steering`` 0). The wheels that are
        not casters must be all Swedish or all conventional (fixed/steered).
    load_fractions : tuple of float, optional
        Share of the weight m g on each wheel, in ``wheels`` order, each in [0, 1], adding up
        to 1 (default: equal shares).
    free_rolling : tuple of str
        Names of the steered wheels that roll freely (not driven), e.g. a car's front wheels.
    mu : float
        Coulomb friction coefficient of the tyres on the ground (> 0).
    steps_per_rev : float or None
        Encoder counts per wheel revolution (need not be an integer: gearboxes); None = an
        ideal encoder that reads the wheel angle in radians, unquantised.
    encoder_noise : float
        Standard deviation of the noise added to each encoder reading, in counts (>= 0).
    seed : int
        Seed of the encoder-noise generator (``numpy.random.default_rng``).
    motor_time_constant : float
        First-order lag of the wheel rates behind their commands, s; 0 = instantaneous.
    steered_names : tuple of str, optional
        Order of the steering angles (default: the steered wheels in ``wheels`` order).

    Examples
    --------
    >>> spec = diff_drive(0.1, 0.02)
    >>> spec.wheel_names, spec.steered_names, spec.load_fractions
    (('L', 'R'), (), (0.4, 0.4, 0.2))
    >>> spec.replace(mu=0.2).mu
    0.2
    >>> spec.replace(mu=0)
    Traceback (most recent call last):
    ...
    ValueError: mu must be a finite number > 0, got 0
    """

    name: str
    mass: float
    inertia: float
    body: tuple[tuple[float, float], ...]
    wheels: tuple[WheelConstraint, ...]
    load_fractions: tuple[float, ...] | None = None
    free_rolling: tuple[str, ...] = ()
    mu: float = 0.8
    steps_per_rev: float | None = None
    encoder_noise: float = 0.0
    seed: int = 0
    motor_time_constant: float = 0.0
    steered_names: tuple[str, ...] | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.name, str):
            raise ValueError(f"name must be a string, got {self.name!r}")
        object.__setattr__(self, "mass", V.positive("mass", self.mass))
        object.__setattr__(self, "inertia", V.positive("inertia", self.inertia))
        body = V.shaped("body", self.body, (2,))
        if body.ndim != 2 or len(body) < 3:
            raise ValueError(f"body must hold at least 3 vertices (x, y), got shape {body.shape}")
        polygon_inertia(1.0, body)  # raises on a degenerate outline
        object.__setattr__(self, "body", tuple((float(x), float(y)) for x, y in body))
        if isinstance(self.wheels, WheelConstraint) or not isinstance(self.wheels, Sequence):
            raise ValueError("wheels must be a non-empty sequence of WheelConstraint, got "
                             f"{type(self.wheels).__name__}")
        wheels = tuple(self.wheels)
        if not wheels or not all(isinstance(w, WheelConstraint) for w in wheels):
            raise ValueError("wheels must be a non-empty sequence of WheelConstraint")
        names = [w.name for w in wheels]
        if len(set(names)) != len(names):
            raise ValueError(f"wheels must have unique names, got {names}")
        turned = [w.name for w in wheels if w.steering != 0.0]
        if turned:
            raise ValueError(f"wheels must be at zero steering (the robot's steering is "
                             f"commanded while it runs), got steering on {turned}")
        driven = [w for w in wheels if w.kind != "caster"]
        if not driven:
            raise ValueError("wheels must include at least one wheel that is not a caster")
        if len({w.kind == "swedish" for w in driven}) > 1:
            raise ValueError("wheels must not mix swedish and conventional wheels")
        object.__setattr__(self, "wheels", wheels)
        n = len(wheels)
        if self.load_fractions is None:
            shares = (1.0 / n,) * n
        else:
            arr = V.shaped("load_fractions", self.load_fractions, (n,))
            if arr.shape != (n,):
                raise ValueError(f"load_fractions must have one share per wheel ({n}), "
                                 f"got shape {arr.shape}")
            shares = tuple(V.in_range("load_fractions", float(x), 0.0, 1.0) for x in arr)
            total = math.fsum(shares)
            if abs(total - 1.0) > 1e-9:
                raise ValueError(f"load_fractions must add up to 1, got {total!r}")
        object.__setattr__(self, "load_fractions", shares)
        if isinstance(self.free_rolling, str) or not isinstance(self.free_rolling, Sequence):
            raise ValueError("free_rolling must be a sequence of wheel names, got "
                             f"{self.free_rolling!r}")
        free = tuple(self.free_rolling)
        steerable = [w.name for w in wheels if w.kind == "steered"]
        if any(f not in steerable for f in free) or len(set(free)) != len(free):
            raise ValueError(f"free_rolling must name steered wheels ({steerable}) once each, "
                             f"got {free}")
        object.__setattr__(self, "free_rolling", free)
        rows = []
        for w in driven:
            if w.kind == "swedish":
                rows.append(unified.roller_row(w))
            else:
                if w.name not in free:
                    rows.append(unified.rolling_row(w))
                rows.append(unified.sliding_row(w))
        if not _rank3(rows):
            raise ValueError("wheels must fix all three body velocities: at least two "
                             "conventional wheels apart, or three swedish wheels")
        object.__setattr__(self, "mu", V.positive("mu", self.mu))
        if self.steps_per_rev is not None:
            object.__setattr__(self, "steps_per_rev", V.positive("steps_per_rev",
                                                                 self.steps_per_rev))
        object.__setattr__(self, "encoder_noise", V.nonnegative("encoder_noise",
                                                                self.encoder_noise))
        if isinstance(self.seed, bool) or not isinstance(self.seed, int | np.integer):
            raise ValueError(f"seed must be an integer, got {self.seed!r}")
        object.__setattr__(self, "seed", int(self.seed))
        object.__setattr__(self, "motor_time_constant",
                           V.nonnegative("motor_time_constant", self.motor_time_constant))
        order = tuple(steerable) if self.steered_names is None else tuple(self.steered_names)
        if sorted(order) != sorted(steerable):
            raise ValueError(
                f"steered_names must list the steered wheels {steerable} once each, got {order}"
            )
        object.__setattr__(self, "steered_names", order)

    @property
    def driven_wheels(self) -> tuple[WheelConstraint, ...]:
        """The wheels that have a rate (every kind but casters), in :attr:`wheel_names`
        order."""
        return tuple(w for w in self.wheels if w.kind != "caster")

    @property
    def wheel_names(self) -> tuple[str, ...]:
        """Names of the wheels that have a rate: the order of rates, encoders and slip
        flags."""
        return tuple(w.name for w in self.driven_wheels)

    @property
    def normal_loads(self) -> np.ndarray:
        """Static normal load on each wheel of :attr:`wheel_names`, N: load fraction * m * g
        (the casters' share is not among them)."""
        share = dict(zip((w.name for w in self.wheels), self.load_fractions, strict=True))
        return np.array([share[name] for name in self.wheel_names]) * self.mass * GRAVITY

    @property
    def is_swedish(self) -> bool:
        """True if the wheels that are not casters are Swedish (mecanum or omni) wheels."""
        return self.driven_wheels[0].kind == "swedish"

    def steering_of(self, steering: Sequence[float]) -> np.ndarray:
        """Per wheel of :attr:`wheel_names`: its steering angle from ``steering``
        (``steered_names`` order), 0 for an unsteered wheel."""
        k = len(self.steered_names)
        angles = V.finite_array("steering", steering)
        if angles.shape != (k,):
            raise ValueError(f"steering must have shape ({k},) "
                             f"({', '.join(self.steered_names) or 'no steered wheels'}), "
                             f"got shape {angles.shape}")
        where = dict(zip(self.steered_names, angles.tolist(), strict=True))
        return np.array([where.get(w.name, 0.0) for w in self.driven_wheels])

    def wheels_at(self, steering: npt.ArrayLike | None = None, *,
                  casters: bool = False) -> tuple[WheelConstraint, ...]:
        """The wheels steered to ``steering`` (rad, ``steered_names`` order; default 0):
        the wheels of :attr:`wheel_names` (``casters=True``: every wheel, in ``wheels``
        order), ready for :mod:`wheelkin.unified`.

        Examples
        --------
        >>> [round(w.steering, 2) for w in OPEN_SOURCE_ROVER.wheels_at([0.3, 0.2, -0.3, -0.2])]
        [0.3, 0.0, -0.3, 0.2, 0.0, -0.2]
        """
        if not isinstance(casters, bool):
            raise ValueError(f"casters must be True or False, got {casters!r}")
        k = len(self.steered_names)
        angles = np.zeros(k) if steering is None else V.shaped("steering", steering, (k,))
        if angles.shape != (k,):
            raise ValueError(f"steering must have shape ({k},) "
                             f"({', '.join(self.steered_names) or 'no steered wheels'}), "
                             f"got shape {angles.shape}")
        where = dict(zip(self.steered_names, angles.tolist(), strict=True))
        return tuple(w.steered_to(where[w.name]) if w.name in where else w
                     for w in self.wheels if casters or w.kind != "caster")

    def replace(self, **changes: object) -> VehicleSpec:
        """A copy with some fields changed (``dataclasses.replace``), validated again."""
        return dataclasses.replace(self, **changes)  # type: ignore[arg-type]


def _rectangle(x0: float, x1: float, y0: float, y1: float) -> tuple[tuple[float, float], ...]:
    return ((x0, y0), (x1, y0), (x1, y1), (x0, y1))


def _finish(name: str, mass: float, inertia: float | None, body: npt.ArrayLike,
            wheels: Sequence[WheelConstraint], loads: Sequence[float],
            **kw: object) -> VehicleSpec:
    """A spec from a builder's wheels and loads: the inertia of the outline if not given."""
    mass = V.positive("mass", mass)
    if inertia is None:
        inertia = polygon_inertia(mass, body)
    return VehicleSpec(name=name, mass=mass, inertia=inertia, body=body,  # type: ignore[arg-type]
                       wheels=tuple(wheels), load_fractions=tuple(loads), **kw)  # type: ignore[arg-type]


def diff_drive(
    track_width: float,
    wheel_radius: float,
    *,
    mass: float = 0.25,
    inertia: float | None = None,
    caster: bool = True,
    caster_offset: float | None = None,
    caster_load: float = 0.2,
    body: npt.ArrayLike | None = None,
    name: str = "differential drive",
    **kwargs: object,
) -> VehicleSpec:
    """A differential drive: the wheels of :func:`wheelkin.unified.diff_drive_wheels` (L, R
    on one axle, and a passive caster C behind unless ``caster=False``).

    The reference point is the axle midpoint; L is at (0, +W/2), R at (0, -W/2), the caster at
    (-caster_offset, 0). The caster carries ``caster_load`` of the weight and exerts no
    friction; each driven wheel carries (1 - caster_load)/2. Without a caster each driven
    wheel carries half the weight: a robot whose mass centre is on its axle and that rests on
    its two drives alone (a tracked robot seen as a differential drive, one contact per
    track, as the Radon Ulzer firmware sees its Zumo).

    Parameters
    ----------
    track_width : float
        W, distance between the wheels' contact points, m.
    wheel_radius : float
        r_w, m.
    mass, inertia : float
        kg and kg m^2 (inertia defaults to the body outline as a uniform plate).
    caster : bool
        Include the caster (``caster_offset`` and ``caster_load`` apply only then).
    caster_offset : float, optional
        Distance of the caster behind the axle, m (default 0.5 W).
    caster_load : float
        Share of the weight on the caster, in [0, 1).
    body : sequence of (x, y), optional
        Outline (default: a rectangle 0.8 W wide from the caster to 0.5 W ahead of the axle).
    **kwargs
        ``mu``, ``steps_per_rev``, ``encoder_noise``, ``seed``, ``motor_time_constant``.

    Examples
    --------
    >>> spec = diff_drive(0.085, 0.018)
    >>> [w.name for w in spec.wheels], [w.position[1] for w in spec.wheels]
    (['L', 'R', 'C'], [0.0425, -0.0425, 0.0])
    >>> diff_drive(0.085, 0.018, caster=False).load_fractions
    (0.5, 0.5)
    """
    W = V.positive("track_width", track_width)
    r = V.positive("wheel_radius", wheel_radius)
    if not isinstance(caster, bool):
        raise ValueError(f"caster must be True or False, got {caster!r}")
    offset = 0.5 * W if caster_offset is None else V.positive("caster_offset", caster_offset)
    share = V.in_range("caster_load", caster_load, 0.0, 1.0)
    if share >= 1.0:
        raise ValueError(f"caster_load must be in [0, 1), got {caster_load!r}")
    if not caster:
        if body is None:
            body = _rectangle(-0.5 * W, 0.5 * W, -0.4 * W, 0.4 * W)
        wheels = unified.diff_drive_wheels(W, r, caster=False)
        return _finish(name, mass, inertia, body, wheels, (0.5, 0.5), **kwargs)
    if body is None:
        body = _rectangle(-offset - 0.2 * W, 0.5 * W, -0.4 * W, 0.4 * W)
    wheels = unified.diff_drive_wheels(W, r, caster_offset=offset)
    drive = (1.0 - share) / 2.0
    return _finish(name, mass, inertia, body, wheels, (drive, drive, share), **kwargs)


def skid_steer(
    *,
    half_wheelbase: float,
    half_track: float,
    wheel_radius: float,
    mass: float = 1.4,
    inertia: float | None = None,
    body: npt.ArrayLike | None = None,
    name: str = "skid steer",
    **kwargs: object,
) -> VehicleSpec:
    """A four-wheel skid steer: the wheels of :func:`wheelkin.unified.skid_steer_wheels`
    ("FL", "FR", "RL", "RR", fixed), sides driven together.

    FL at (+a, +b), FR at (+a, -b), RL at (-a, +b), RR at (-a, -b) with a = half_wheelbase,
    b = half_track; each carries a quarter of the weight. While turning, the wheels cannot
    all roll without sliding sideways: a skid steer turns by slipping (see :mod:`.contact`).

    Examples
    --------
    >>> spec = skid_steer(half_wheelbase=0.05, half_track=0.06, wheel_radius=0.04)
    >>> spec.wheel_names
    ('FL', 'FR', 'RL', 'RR')
    """
    a = V.positive("half_wheelbase", half_wheelbase)
    b = V.positive("half_track", half_track)
    r = V.positive("wheel_radius", wheel_radius)
    if body is None:
        body = _rectangle(-a - r, a + r, -0.8 * b, 0.8 * b)
    wheels = unified.skid_steer_wheels(half_wheelbase=a, half_track=b, wheel_radius=r)
    return _finish(name, mass, inertia, body, wheels, (0.25,) * 4, **kwargs)


def mecanum(
    *,
    half_wheelbase: float,
    half_track: float,
    wheel_radius: float,
    roller_angle: float = math.pi / 4,
    mass: float = 4.0,
    inertia: float | None = None,
    body: npt.ArrayLike | None = None,
    name: str = "mecanum",
    **kwargs: object,
) -> VehicleSpec:
    r"""A mecanum platform: the wheels of :func:`wheelkin.unified.mecanum_wheels` for the
    :class:`wheelkin.mecanum.MecanumGeometry` of the arguments ("FL", "FR", "RL", "RR",
    rollers in the X arrangement).

    Seen from above, the rollers on top of the wheels form an X; the rollers touching the
    ground sit at :math:`+\gamma` (FL, RR) and :math:`-\gamma` (FR, RL) from the axle. With
    :math:`k = a + b` (a = half_wheelbase, b = half_track) and :math:`\gamma` = 45 deg, the
    ideal rates are

    FL = (vx - vy - k w)/r_w, FR = (vx + vy + k w)/r_w,
    RL = (vx + vy - k w)/r_w, RR = (vx - vy + k w)/r_w.

    Examples
    --------
    >>> spec = mecanum(half_wheelbase=0.15, half_track=0.15, wheel_radius=0.05)
    >>> rates, _ = ideal_commands(spec, (1.0, 1.0, 0.0))
    >>> [round(float(x), 6) for x in rates]  # forward-left: FL and RR stand still
    [0.0, 40.0, 40.0, 0.0]
    """
    geometry = MecanumGeometry(half_wheelbase=half_wheelbase, half_track=half_track,
                               wheel_radius=wheel_radius, roller_angle=roller_angle)
    a, b, r = geometry.half_wheelbase, geometry.half_track, geometry.wheel_radius
    if body is None:
        body = _rectangle(-a - 0.6 * r, a + 0.6 * r, -0.75 * b, 0.75 * b)
    wheels = unified.mecanum_wheels(geometry)
    return _finish(name, mass, inertia, body, wheels, (0.25,) * 4, **kwargs)


def rover(
    geometry: rover_model.RoverGeometry = rover_model.OSR_GEOMETRY,
    wheel_radius: float = 0.06,
    *,
    mass: float = 11.0,
    inertia: float | None = None,
    body: npt.ArrayLike | None = None,
    name: str = "six-wheel rover",
    **kwargs: object,
) -> VehicleSpec:
    """A six-wheel rover: the wheels of :func:`wheelkin.unified.rover_wheels` ("LF", "LM",
    "LB", "RF", "RM", "RB"), corners steered.

    ``geometry`` is a :class:`wheelkin.rover.RoverGeometry` in inches or metres (its
    ``unit``; default :data:`wheelkin.rover.OSR_GEOMETRY`, the document's); the wheels sit at
    :func:`wheelkin.rover.wheel_positions` in metres: LF at (d3, d1), LM at (0, d4), LB at
    (-d2, d1), RF at (d3, -d1), RM at (0, -d4), RB at (-d2, -d1). Steered wheels in ("LF",
    "RF", "LB", "RB") order; the middle wheels are fixed, so the ICR lies on the middle axle
    (y axis). Each wheel carries 1/6 of the weight.

    Examples
    --------
    >>> spec = rover(wheel_radius=0.06)
    >>> spec.steered_names, round(spec.wheels[0].position[0], 4)  # d3 = 10.5 in
    (('LF', 'RF', 'LB', 'RB'), 0.2667)
    """
    wheels = unified.rover_wheels(geometry, wheel_radius)
    r = wheels[0].wheel_radius
    if body is None:
        xs = [w.position[0] for w in wheels]
        d1 = max(w.position[1] for w in wheels if w.kind == "steered")
        body = _rectangle(min(xs) - 0.5 * r, max(xs) + 0.5 * r, -0.6 * d1, 0.6 * d1)
    kwargs.setdefault("steered_names", ("LF", "RF", "LB", "RB"))
    return _finish(name, mass, inertia, body, wheels, (1.0 / 6.0,) * 6, **kwargs)


class IdealCommands(NamedTuple):
    """Wheel rates and steering angles of the ideal kinematic model (see
    :func:`ideal_commands`)."""

    #: rad/s, shape (n,), ``spec.wheel_names`` order.
    rates: np.ndarray
    #: rad, shape (k,), ``spec.steered_names`` order.
    steering: np.ndarray


def ideal_commands(spec: VehicleSpec, twist: npt.ArrayLike,
                   steering: npt.ArrayLike | None = None) -> IdealCommands:
    r"""Wheel rates (and steering) of the ideal kinematic model for a body twist.

    The rates and angles of :func:`wheelkin.unified.steer_for_twist` and
    :func:`wheelkin.unified.wheel_rates`: for each wheel at contact point p, the contact
    velocity of the twist :math:`(v_x, v_y, \omega)` is
    :math:`v_c = (v_x - \omega p_y,\ v_y + \omega p_x)`. A steered wheel is turned to roll
    along :math:`v_c` (:math:`\delta` folded into :math:`(-\pi/2, \pi/2]`, the rate negated
    when the fold reverses it) and spins at :math:`|v_c| / r_w`; a fixed wheel spins at
    :math:`(\mathbf e\cdot v_c) / r_w`; a Swedish wheel at
    :math:`(\mathbf u\cdot v_c) / (r_w\,\mathbf u\cdot\mathbf e)`. Velocity components a
    wheel cannot follow (a fixed wheel's lateral one, e.g. a skid steer turning) are left to
    friction: the vehicle slips.

    Parameters
    ----------
    spec : VehicleSpec
    twist : (vx, vy, omega)
        Body twist: m/s, m/s, rad/s.
    steering : array_like, optional
        Current steering angles (``spec.steered_names`` order); kept for a steered wheel whose
        contact point is at rest (at the ICR).

    Returns
    -------
    IdealCommands
        ``(rates, steering)``: rad/s, shape (n,), ``spec.wheel_names`` order; rad, shape
        (k,), ``spec.steered_names`` order.

    Examples
    --------
    >>> rates, _ = ideal_commands(diff_drive(0.1, 0.02), (0.2, 0.0, 1.0))
    >>> rates.round(6).tolist()  # L = (v - w W/2)/r, R = (v + w W/2)/r
    [7.5, 12.5]
    """
    if not isinstance(spec, VehicleSpec):
        raise ValueError(f"spec must be a VehicleSpec, got {type(spec).__name__}")
    arr = V.twist("twist", twist)
    vx, vy, w = arr.tolist()
    k = len(spec.steered_names)
    if steering is None:
        current: tuple[float, ...] = (0.0,) * k
    else:
        current = tuple(V.shaped("steering", steering, (k,)).reshape(k).tolist())
    rates, angles, _ = ideal_rates(command_table(spec), vx, vy, w, current)
    return IdealCommands(np.array(rates), np.array(angles))


def command_table(spec: VehicleSpec) -> tuple[tuple, ...]:
    """Per wheel of ``spec.wheel_names``, what :func:`ideal_rates` needs, as plain floats
    computed once: (kind, x, y, heading, e_x, e_y, u_x, u_y, r_w, steering slot or -1)."""
    if not isinstance(spec, VehicleSpec):
        raise ValueError(f"spec must be a VehicleSpec, got {type(spec).__name__}")
    where = {name: i for i, name in enumerate(spec.steered_names)}
    table = []
    for wheel in spec.driven_wheels:
        ex, ey = (float(c) for c in wheel.rolling_direction)
        ux = uy = 0.0
        if wheel.kind == "swedish":
            ux, uy = (float(c) for c in wheel.roller_axis)
        table.append((wheel.kind, *wheel.position, wheel.heading, ex, ey, ux, uy,
                      wheel.wheel_radius, where.get(wheel.name, -1)))
    return tuple(table)


def ideal_rates(table: tuple[tuple, ...], vx: float, vy: float, w: float,
                current: tuple[float, ...]) -> tuple[list[float], tuple[float, ...], bool]:
    """The inner loop of :func:`ideal_commands` on a :func:`command_table`, plain floats, no
    validation: rates, steering, and whether the wheels can all roll at that twist (no
    fixed wheel's contact moves sideways)."""
    rates = []
    angles = list(current)
    rolls = True
    for kind, px, py, h, ex, ey, ux, uy, r, slot in table:
        cx, cy = vx - w * py, vy + w * px
        if kind == "steered":
            speed = math.hypot(cx, cy)
            # At rest (at the ICR) when the terms cancel to rounding: relative to their size,
            # so that a twist and its double steer alike however small they are.
            if speed <= 1e-12 * (abs(vx) + abs(vy) + abs(w) * (abs(px) + abs(py))):
                sign, speed = 1.0, 0.0
            else:
                angles[slot], sign = fold_half_turn(math.atan2(cy, cx) - h)
            rates.append(sign * speed / r)
        elif kind == "fixed":
            rates.append((ex * cx + ey * cy) / r)
            if abs(ex * cy - ey * cx) > 1e-12:
                rolls = False
        else:  # swedish
            rates.append((ux * cx + uy * cy) / (r * (ux * ex + uy * ey)))
    return rates, tuple(angles), rolls


#: The firmware robot: the Radon Ulzer firmware's Pololu Zumo 32U4, which runs on two rubber
#: tracks, modelled as the firmware models it: a differential drive with one contact per track,
#: 0.085 m apart, under the middle of the robot, each carrying half the weight (no caster; a
#: real track's length, which makes it skid in turns, is left out); drive sprockets of
#: circumference 0.113097 m, encoder 12 * 75.81 counts per sprocket revolution (8043 steps/m).
RADON_ULZER = diff_drive(
    0.085,
    0.113097 / (2 * math.pi),
    mass=0.25,
    caster=False,
    body=_rectangle(-0.05, 0.05, -0.035, 0.035),
    name="Radon Ulzer",
    steps_per_rev=12 * 75.81,
)

#: The waypoint lab's four-wheel skid steer (the Webots tutorial robot): wheel radius 0.04 m,
#: wheels at +-0.05 m along x and +-0.06 m across, body 0.2 m x 0.1 m, 1.4 kg.
LAB_ROBOT = skid_steer(
    half_wheelbase=0.05, half_track=0.06, wheel_radius=0.04, mass=1.4,
    body=_rectangle(-0.1, 0.1, -0.05, 0.05), name="lab robot"
)

#: A generic 30 cm mecanum platform: r = 0.05 m, half wheelbase and half track 0.15 m, 4 kg.
MECANUM_ROBOT = mecanum(half_wheelbase=0.15, half_track=0.15, wheel_radius=0.05,
                        name="mecanum robot")

#: The JPL Open Source Rover: :data:`wheelkin.rover.OSR_GEOMETRY` (d1 = 7.254 in,
#: d2 = d3 = 10.5 in, d4 = 10.073 in); r = 0.06 m and 11 kg are our estimates.
OPEN_SOURCE_ROVER = rover(rover_model.OSR_GEOMETRY, 0.06, mass=11.0, name="Open Source Rover")
