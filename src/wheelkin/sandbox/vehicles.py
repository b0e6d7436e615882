"""Vehicle geometry for the sandbox: wheels, bodies, masses, and the book's four vehicles.

A vehicle is a frozen :class:`VehicleSpec`: a rigid body (mass, yaw inertia, a convex outline)
carrying :class:`Wheel` s. All coordinates are in the body frame of REP-103 (x forward, y left,
metres), measured from the vehicle's *reference point*: the axle midpoint of a differential
drive, the geometric centre of the others. The reference point is also the rigid body's mass
centre in the simulation (a simplification: the normal load on each wheel is set separately,
by its ``load_fraction``).

Each wheel has a *rolling direction* ``e`` at angle ``heading`` (+ its steering angle, for a
steered wheel) in the body frame, and a *lateral direction* ``n`` (``e`` turned by +90 deg).
Its kind says which velocities the ground contact constrains (see :mod:`.contact`):

``"fixed"`` / ``"steered"``
    a conventional wheel: the contact point's velocity along ``e`` equals the wheel's surface
    speed ``r_w * phi``, across it zero (both friction-limited, by one Coulomb circle);
``"mecanum"``
    a wheel with passive rollers whose axes sit at ``roller_angle`` (gamma) from the wheel's
    axle, counter-clockwise seen from above, for the roller touching the ground: only the
    velocity along that roller axis ``u`` is constrained, to ``r_w * phi * (u . e)``;
``"caster"``
    a passive swivel wheel: it carries its share of the weight and exerts no force;
``"free"``
    a steered wheel that rolls freely (no drive torque, e.g. a car's front wheel): only its
    lateral velocity is constrained, to zero; along ``e`` it exerts no force. Its "rate" is
    not a command: it is the rate it rolls at in the kinematic model (what its wheel angle
    and encoder record).

Driven wheels (every kind but casters) are commanded in wheel terms: an angular rate ``phi``
(rad/s, positive = rolling forward along ``e``) per wheel in :attr:`VehicleSpec.wheel_names`
order, and a steering angle ``delta`` (rad, counter-clockwise) per steered wheel in
:attr:`VehicleSpec.steered_names` order. :func:`ideal_commands` turns a body twist into the
rates (and steering) of the ideal kinematic model.

The ready-made vehicles, with the values we assumed where the sources are silent:

========================= ========================================================= ========
spec                      geometry                                                  mass
========================= ========================================================= ========
:data:`RADON_ULZER`       diff drive, track 0.085 m, wheel circumference 0.113097 m,  0.25 kg
                          encoder 12 * 75.81 counts per wheel revolution (8043 /m)
:data:`LAB_ROBOT`         skid steer, wheels r = 0.04 m at x = +-0.05 m,             1.4 kg
                          y = +-0.06 m, body 0.2 m x 0.1 m (Webots 4-wheel robot)
:data:`MECANUM_ROBOT`     mecanum, r = 0.05 m, half wheelbase 0.15 m, half track     4.0 kg
                          0.15 m, rollers at 45 deg (a generic 30 cm platform)
:data:`OPEN_SOURCE_ROVER` six wheels, four corners steered, d1..d4 of the OSR         11 kg
                          document (7.254, 10.5, 10.5, 10.073 in), r = 0.06 m
========================= ========================================================= ========

The yaw inertia defaults to that of the body outline as a uniform plate about the reference
point. The friction coefficient defaults to 0.8 (rubber on a dry floor).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from wheelkin import _validate as V
from wheelkin.frames import fold_half_turn

__all__ = [
    "GRAVITY",
    "LAB_ROBOT",
    "MECANUM_ROBOT",
    "OPEN_SOURCE_ROVER",
    "RADON_ULZER",
    "VehicleSpec",
    "Wheel",
    "diff_drive",
    "ideal_commands",
    "mecanum",
    "polygon_inertia",
    "rover",
    "skid_steer",
]

#: Gravitational acceleration used for the wheels' normal loads, N_i = load_fraction * m * g.
GRAVITY = 9.81

WHEEL_KINDS = ("fixed", "steered", "mecanum", "caster", "free")


def _point(name: str, value) -> tuple[float, float]:
    arr = V.shaped(name, value, (2,))
    if arr.ndim != 1:
        raise ValueError(f"{name} must be one point (x, y), got shape {arr.shape}")
    return (float(arr[0]), float(arr[1]))


@dataclass(frozen=True)
class Wheel:
    """One wheel of a vehicle (body frame, SI).

    Parameters
    ----------
    name : str
        Unique within the vehicle, e.g. ``"FL"``.
    position : (float, float)
        Contact point (x, y) in the body frame, m.
    heading : float
        Angle of the rolling direction ``e`` from the body x axis at zero steering, rad.
    radius : float
        Wheel radius r_w, m (> 0).
    kind : {"fixed", "steered", "mecanum", "caster", "free"}
        See the module docstring.
    roller_angle : float
        Mecanum only: angle gamma from the wheel's axle (``n``) to the axis ``u`` of the roller
        that touches the ground, counter-clockwise seen from above, rad; 0 < |gamma| < pi/2.
    load_fraction : float
        Share of the vehicle's weight m*g resting on this wheel, in [0, 1].
    width : float, optional
        Tyre width for drawing, m (default 0.6 * radius).

    Examples
    --------
    >>> Wheel("L", (0.0, 0.05), radius=0.02, load_fraction=0.5).kind
    'fixed'
    >>> Wheel("L", (0.0, 0.05), radius=-0.02)
    Traceback (most recent call last):
    ...
    ValueError: radius must be a finite number > 0, got -0.02
    """

    name: str
    position: tuple[float, float]
    heading: float = 0.0
    radius: float = 0.05
    kind: str = "fixed"
    roller_angle: float = 0.0
    load_fraction: float = 0.25
    width: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ValueError(f"name must be a non-empty string, got {self.name!r}")
        object.__setattr__(self, "position", _point("position", self.position))
        object.__setattr__(self, "heading", V.finite("heading", self.heading))
        object.__setattr__(self, "radius", V.positive("radius", self.radius))
        V.choice("kind", self.kind, WHEEL_KINDS)
        gamma = V.finite("roller_angle", self.roller_angle)
        if self.kind == "mecanum" and not 0 < abs(gamma) < math.pi / 2:
            raise ValueError(
                f"roller_angle must satisfy 0 < |roller_angle| < pi/2 for a mecanum wheel, "
                f"got {self.roller_angle!r}"
            )
        object.__setattr__(self, "roller_angle", gamma)
        object.__setattr__(
            self, "load_fraction", V.in_range("load_fraction", self.load_fraction, 0.0, 1.0)
        )
        if self.width is not None:
            object.__setattr__(self, "width", V.positive("width", self.width))

    @property
    def driven(self) -> bool:
        """True for every kind but a caster."""
        return self.kind != "caster"

    @property
    def drawn_width(self) -> float:
        """Tyre width used for drawing, m."""
        return self.width if self.width is not None else 0.6 * self.radius


def _constrains_twist(driven) -> bool:
    """True if the driven wheels' constraints (at zero steering) have rank 3 on the twist."""
    rows = []
    for w in driven:
        px, py = w.position
        h = w.heading
        if w.kind == "mecanum":
            a = h + math.pi / 2 + w.roller_angle
            dirs = [(math.cos(a), math.sin(a))]
        elif w.kind == "free":
            dirs = [(-math.sin(h), math.cos(h))]
        else:
            dirs = [(math.cos(h), math.sin(h)), (-math.sin(h), math.cos(h))]
        rows += [(dx, dy, px * dy - py * dx) for dx, dy in dirs]
    sv = np.linalg.svd(np.array(rows), compute_uv=False)
    return len(sv) == 3 and sv[-1] > 1e-9 * sv[0]


def polygon_inertia(mass: float, vertices) -> float:
    """Yaw moment of inertia of a uniform polygonal plate about the body-frame origin.

    For the outline's vertices p_k (counter-clockwise or clockwise),

    I = m * sum_k c_k (p_k.p_k + p_k.p_{k+1} + p_{k+1}.p_{k+1}) / (6 * sum_k c_k),
    c_k = p_k x p_{k+1},

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
    if abs(cross.sum()) < 1e-15:
        raise ValueError("vertices must enclose a non-zero area")
    terms = (p * p).sum(1) + (p * q).sum(1) + (q * q).sum(1)
    return float(m * (cross * terms).sum() / (6.0 * cross.sum()))


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
    wheels : tuple of Wheel
        All wheels, casters included. The driven ones must be all mecanum or all conventional
        (fixed/steered), and the load fractions must add up to 1.
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

    Attributes
    ----------
    wheel_names : tuple of str
        Names of the driven wheels: the order of rates, encoders and slip flags.

    Examples
    --------
    >>> spec = diff_drive(0.1, 0.02)
    >>> spec.wheel_names, spec.steered_names
    (('L', 'R'), ())
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
    wheels: tuple[Wheel, ...]
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
        wheels = tuple(self.wheels)
        if not wheels or not all(isinstance(w, Wheel) for w in wheels):
            raise ValueError("wheels must be a non-empty sequence of Wheel")
        names = [w.name for w in wheels]
        if len(set(names)) != len(names):
            raise ValueError(f"wheels must have unique names, got {names}")
        driven = [w for w in wheels if w.driven]
        if not driven:
            raise ValueError("wheels must include at least one driven (non-caster) wheel")
        kinds = {w.kind == "mecanum" for w in driven}
        if len(kinds) > 1:
            raise ValueError("wheels must not mix mecanum and conventional driven wheels")
        total = sum(w.load_fraction for w in wheels)
        if abs(total - 1.0) > 1e-9:
            raise ValueError(f"wheels' load_fraction must add up to 1, got {total!r}")
        if not _constrains_twist(driven):
            raise ValueError("wheels must fix all three body velocities: at least two "
                             "conventional wheels apart, or three mecanum wheels")
        object.__setattr__(self, "wheels", wheels)
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
        steered = [w.name for w in wheels if w.kind in ("steered", "free")]
        order = tuple(steered) if self.steered_names is None else tuple(self.steered_names)
        if sorted(order) != sorted(steered):
            raise ValueError(
                f"steered_names must list the steered wheels {steered} once each, got {order}"
            )
        object.__setattr__(self, "steered_names", order)

    @property
    def driven_wheels(self) -> tuple[Wheel, ...]:
        """The driven wheels (every kind but casters), in :attr:`wheel_names` order."""
        return tuple(w for w in self.wheels if w.driven)

    @property
    def wheel_names(self) -> tuple[str, ...]:
        """Names of the driven wheels: the order of rates, encoders and slip flags."""
        return tuple(w.name for w in self.wheels if w.driven)

    def steering_of(self, steering) -> tuple[float, ...]:
        """Per driven wheel (``wheel_names`` order): its steering angle from ``steering``
        (``steered_names`` order), 0 for an unsteered wheel."""
        where = {name: i for i, name in enumerate(self.steered_names)}
        return tuple(float(steering[where[w.name]]) if w.name in where else 0.0
                     for w in self.driven_wheels)

    @property
    def is_mecanum(self) -> bool:
        """True if the driven wheels are mecanum wheels."""
        return self.driven_wheels[0].kind == "mecanum"

    def replace(self, **changes) -> VehicleSpec:
        """A copy with some fields changed (``dataclasses.replace``), validated again."""
        return dataclasses.replace(self, **changes)


def _rectangle(x0: float, x1: float, y0: float, y1: float) -> tuple[tuple[float, float], ...]:
    return ((x0, y0), (x1, y0), (x1, y1), (x0, y1))


def _finish(name, mass, inertia, body, wheels, **kw) -> VehicleSpec:
    mass = V.positive("mass", mass)
    if inertia is None:
        inertia = polygon_inertia(mass, body)
    return VehicleSpec(name=name, mass=mass, inertia=inertia, body=body, wheels=tuple(wheels),
                       **kw)


def diff_drive(
    track_width: float,
    wheel_radius: float,
    *,
    mass: float = 0.25,
    inertia: float | None = None,
    caster_offset: float | None = None,
    caster_load: float = 0.2,
    body=None,
    name: str = "differential drive",
    **kwargs,
) -> VehicleSpec:
    """A differential drive: wheels ("L", "R") on one axle, a passive caster "C" behind.

    The reference point is the axle midpoint; L is at (0, +W/2), R at (0, -W/2), the caster at
    (-caster_offset, 0). The caster carries ``caster_load`` of the weight and exerts no
    friction; each driven wheel carries (1 - caster_load)/2.

    Parameters
    ----------
    track_width : float
        W, distance between the wheels' contact points, m.
    wheel_radius : float
        r_w, m.
    mass, inertia : float
        kg and kg m^2 (inertia defaults to the body outline as a uniform plate).
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
    """
    W = V.positive("track_width", track_width)
    r = V.positive("wheel_radius", wheel_radius)
    offset = 0.5 * W if caster_offset is None else V.positive("caster_offset", caster_offset)
    share = V.in_range("caster_load", caster_load, 0.0, 1.0)
    if share >= 1.0:
        raise ValueError(f"caster_load must be in [0, 1), got {caster_load!r}")
    if body is None:
        body = _rectangle(-offset - 0.2 * W, 0.5 * W, -0.4 * W, 0.4 * W)
    drive = (1.0 - share) / 2.0
    wheels = [
        Wheel("L", (0.0, W / 2), 0.0, r, "fixed", load_fraction=drive),
        Wheel("R", (0.0, -W / 2), 0.0, r, "fixed", load_fraction=drive),
        Wheel("C", (-offset, 0.0), 0.0, 0.4 * r, "caster", load_fraction=share),
    ]
    return _finish(name, mass, inertia, body, wheels, **kwargs)


def skid_steer(
    half_track: float,
    half_wheelbase: float,
    wheel_radius: float,
    *,
    mass: float = 1.4,
    inertia: float | None = None,
    body=None,
    name: str = "skid steer",
    **kwargs,
) -> VehicleSpec:
    """A four-wheel skid steer: fixed wheels ("FL", "FR", "RL", "RR"), sides driven together.

    FL at (+a, +b), FR at (+a, -b), RL at (-a, +b), RR at (-a, -b) with a = half_wheelbase,
    b = half_track; each carries a quarter of the weight. While turning, the wheels cannot
    all roll without sliding sideways: a skid steer turns by slipping (see :mod:`.contact`).

    Examples
    --------
    >>> spec = skid_steer(0.06, 0.05, 0.04)
    >>> spec.wheel_names
    ('FL', 'FR', 'RL', 'RR')
    """
    b = V.positive("half_track", half_track)
    a = V.positive("half_wheelbase", half_wheelbase)
    r = V.positive("wheel_radius", wheel_radius)
    if body is None:
        body = _rectangle(-a - r, a + r, -0.8 * b, 0.8 * b)
    wheels = [
        Wheel("FL", (a, b), 0.0, r, "fixed", load_fraction=0.25),
        Wheel("FR", (a, -b), 0.0, r, "fixed", load_fraction=0.25),
        Wheel("RL", (-a, b), 0.0, r, "fixed", load_fraction=0.25),
        Wheel("RR", (-a, -b), 0.0, r, "fixed", load_fraction=0.25),
    ]
    return _finish(name, mass, inertia, body, wheels, **kwargs)


def mecanum(
    wheel_radius: float,
    half_wheelbase: float,
    half_track: float,
    roller_angle: float = math.pi / 4,
    *,
    mass: float = 4.0,
    inertia: float | None = None,
    body=None,
    name: str = "mecanum",
    **kwargs,
) -> VehicleSpec:
    """A mecanum platform: wheels ("FL", "FR", "RL", "RR") with rollers in the X arrangement.

    Seen from above, the rollers on top of the wheels form an X; the rollers touching the
    ground sit at +gamma (FL, RR) and -gamma (FR, RL) from the axle. With k = a + b
    (a = half_wheelbase, b = half_track) and gamma = 45 deg, the ideal rates are

    FL = (vx - vy - k w)/r_w, FR = (vx + vy + k w)/r_w,
    RL = (vx + vy - k w)/r_w, RR = (vx - vy + k w)/r_w.

    Examples
    --------
    >>> spec = mecanum(0.05, 0.15, 0.15)
    >>> rates, _ = ideal_commands(spec, (1.0, 1.0, 0.0))
    >>> [round(float(x), 6) for x in rates]  # forward-left: FL and RR stand still
    [0.0, 40.0, 40.0, 0.0]
    """
    r = V.positive("wheel_radius", wheel_radius)
    a = V.positive("half_wheelbase", half_wheelbase)
    b = V.positive("half_track", half_track)
    g = V.finite("roller_angle", roller_angle)
    if not 0 < g < math.pi / 2:
        raise ValueError(f"roller_angle must be in (0, pi/2), got {roller_angle!r}")
    if body is None:
        body = _rectangle(-a - 0.6 * r, a + 0.6 * r, -0.75 * b, 0.75 * b)
    wheels = [
        Wheel("FL", (a, b), 0.0, r, "mecanum", roller_angle=g, load_fraction=0.25),
        Wheel("FR", (a, -b), 0.0, r, "mecanum", roller_angle=-g, load_fraction=0.25),
        Wheel("RL", (-a, b), 0.0, r, "mecanum", roller_angle=-g, load_fraction=0.25),
        Wheel("RR", (-a, -b), 0.0, r, "mecanum", roller_angle=g, load_fraction=0.25),
    ]
    return _finish(name, mass, inertia, body, wheels, **kwargs)


def rover(
    d1: float,
    d2: float,
    d3: float,
    d4: float,
    wheel_radius: float,
    *,
    mass: float = 11.0,
    inertia: float | None = None,
    body=None,
    name: str = "six-wheel rover",
    **kwargs,
) -> VehicleSpec:
    """A six-wheel rover: wheels ("LF", "LM", "LB", "RF", "RM", "RB"), corners steered.

    The OSR document's distances, in metres: d1 lateral offset of the corner wheels, d2
    longitudinal offset of the back corners, d3 of the front corners, d4 lateral offset of the
    middle wheels. LF at (d3, d1), LM at (0, d4), LB at (-d2, d1), RF at (d3, -d1), RM at
    (0, -d4), RB at (-d2, -d1). Steered wheels in ("LF", "RF", "LB", "RB") order; the middle
    wheels are fixed, so the ICR lies on the middle axle (y axis). Each wheel carries 1/6 of
    the weight.

    Examples
    --------
    >>> spec = rover(0.184, 0.267, 0.267, 0.256, 0.06)
    >>> spec.steered_names
    ('LF', 'RF', 'LB', 'RB')
    """
    d1 = V.positive("d1", d1)
    d2 = V.positive("d2", d2)
    d3 = V.positive("d3", d3)
    d4 = V.positive("d4", d4)
    r = V.positive("wheel_radius", wheel_radius)
    if body is None:
        body = _rectangle(-d2 - 0.5 * r, d3 + 0.5 * r, -0.6 * d1, 0.6 * d1)
    sixth = 1.0 / 6.0
    wheels = [
        Wheel("LF", (d3, d1), 0.0, r, "steered", load_fraction=sixth),
        Wheel("LM", (0.0, d4), 0.0, r, "fixed", load_fraction=sixth),
        Wheel("LB", (-d2, d1), 0.0, r, "steered", load_fraction=sixth),
        Wheel("RF", (d3, -d1), 0.0, r, "steered", load_fraction=sixth),
        Wheel("RM", (0.0, -d4), 0.0, r, "fixed", load_fraction=sixth),
        Wheel("RB", (-d2, -d1), 0.0, r, "steered", load_fraction=sixth),
    ]
    kwargs.setdefault("steered_names", ("LF", "RF", "LB", "RB"))
    return _finish(name, mass, inertia, body, wheels, **kwargs)


def ideal_commands(spec: VehicleSpec, twist, steering=None) -> tuple[np.ndarray, np.ndarray]:
    """Wheel rates (and steering) of the ideal kinematic model for a body twist.

    For each driven wheel at contact point p, the contact velocity of the twist
    (vx, vy, w) is v_c = (vx - w p_y, vy + w p_x). A steered wheel is turned to roll along v_c
    (delta folded into (-pi/2, pi/2], the rate negated when the fold reverses it) and spins at
    phi = |v_c| / r_w; a fixed wheel spins at phi = (e . v_c) / r_w; a mecanum wheel at
    phi = (u . v_c) / (r_w (u . e)). Velocity components a wheel cannot follow (a fixed wheel's
    lateral one, e.g. a skid steer turning) are left to friction: the vehicle slips.

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
    rates : ndarray (n,)
        rad/s, ``spec.wheel_names`` order.
    steering : ndarray (k,)
        rad, ``spec.steered_names`` order.

    Examples
    --------
    >>> rates, _ = ideal_commands(diff_drive(0.1, 0.02), (0.2, 0.0, 1.0))
    >>> rates.round(6).tolist()  # L = (v - w W/2)/r, R = (v + w W/2)/r
    [7.5, 12.5]
    """
    vx, vy, w = (float(x) for x in V.shaped("twist", twist, (3,)).reshape(3))
    k = len(spec.steered_names)
    if steering is None:
        current = (0.0,) * k
    else:
        current = tuple(V.shaped("steering", steering, (k,)).reshape(k).tolist())
    rates, angles, _ = _ideal(command_table(spec), vx, vy, w, current)
    return np.array(rates), np.array(angles)


def command_table(spec: VehicleSpec) -> tuple:
    """Per driven wheel, what :func:`ideal_commands` needs (plain floats, computed once)."""
    where = {name: i for i, name in enumerate(spec.steered_names)}
    table = []
    for wheel in spec.driven_wheels:
        px, py = wheel.position
        h = wheel.heading
        ex, ey = math.cos(h), math.sin(h)
        ux = uy = 0.0
        if wheel.kind == "mecanum":
            a = h + math.pi / 2 + wheel.roller_angle
            ux, uy = math.cos(a), math.sin(a)
        table.append((wheel.kind, px, py, h, ex, ey, ux, uy, wheel.radius,
                      where.get(wheel.name, -1)))
    return tuple(table)


def _ideal(table: tuple, vx: float, vy: float, w: float, current: tuple
           ) -> tuple[list, tuple, bool]:
    """:func:`ideal_commands` on plain floats (no validation), and whether the wheels can all
    roll at that twist (no fixed wheel's contact moves sideways)."""
    rates = []
    angles = list(current)
    rolls = True
    for kind, px, py, h, ex, ey, ux, uy, r, slot in table:
        cx, cy = vx - w * py, vy + w * px
        if kind == "steered" or kind == "free":
            speed = math.hypot(cx, cy)
            if speed < 1e-12:
                sign, speed = 1.0, 0.0
            else:
                angles[slot], sign = fold_half_turn(math.atan2(cy, cx) - h)
            rates.append(sign * speed / r)
        elif kind == "fixed":
            rates.append((ex * cx + ey * cy) / r)
            if abs(ex * cy - ey * cx) > 1e-12:
                rolls = False
        else:  # mecanum
            rates.append((ux * cx + uy * cy) / (r * (ux * ex + uy * ey)))
    return rates, tuple(angles), rolls


#: The firmware robot (Radon Ulzer, a Zumo-class differential drive): track 0.085 m, wheel
#: circumference 0.113097 m, encoder 12 * 75.81 counts per wheel revolution (8043 steps/m).
RADON_ULZER = diff_drive(
    0.085,
    0.113097 / (2 * math.pi),
    mass=0.25,
    caster_offset=0.045,
    caster_load=0.2,
    body=_rectangle(-0.06, 0.04, -0.035, 0.035),
    name="Radon Ulzer",
    steps_per_rev=12 * 75.81,
)

#: The waypoint lab's four-wheel skid steer (the Webots tutorial robot): wheel radius 0.04 m,
#: wheels at +-0.05 m along x and +-0.06 m across, body 0.2 m x 0.1 m, 1.4 kg.
LAB_ROBOT = skid_steer(
    0.06, 0.05, 0.04, mass=1.4, body=_rectangle(-0.1, 0.1, -0.05, 0.05), name="lab robot"
)

#: A generic 30 cm mecanum platform: r = 0.05 m, half wheelbase and half track 0.15 m, 4 kg.
MECANUM_ROBOT = mecanum(0.05, 0.15, 0.15, name="mecanum robot")

#: The JPL Open Source Rover: d1 = 7.254 in, d2 = d3 = 10.5 in, d4 = 10.073 in; r = 0.06 m
#: and 11 kg are our estimates.
OPEN_SOURCE_ROVER = rover(
    7.254 * 0.0254, 10.5 * 0.0254, 10.5 * 0.0254, 10.073 * 0.0254, 0.06,
    mass=11.0, name="Open Source Rover",
)
