"""The sandbox world: a top-down pymunk space, vehicles on wheels, walls, a fixed step.

One step of ``dt`` (default 1/240 s) does, for every robot:

1. wheel rates: the commanded rates, or with a motor lag tau the exact first-order response
   (the rate averaged over the step drives the step, its end value is kept);
2. contact (:mod:`.contact`): friction-limited wheel impulses turn the body's twist into the
   twist its wheels ask for, or as close as friction allows (slip flagged per wheel);
3. collisions: pymunk (the Chipmunk2D engine) steps the space and resolves contacts of the
   vehicle outlines with the walls (and each other), which may change the twist;
4. motion: the body moves along the exact SE(2) arc of its constant body twist over the step,
   not by pymunk's Euler step p += v dt (which alone costs about a millimetre over 10 m);
5. encoders: each wheel's angle advances by its rate times dt.

Each vehicle's body has a custom ``position_func``, which pymunk calls at the start of its
step in place of its Euler step: it applies only pymunk's penetration correction (when
touching). The arc itself is applied after the collision solve (step 4), so that a wall stops
a vehicle *before* it moves rather than after it has moved into the wall: with pymunk's own
order (move, then resolve) the wheels, which push again every step, would keep a vehicle
several millimetres inside a wall.

Accuracy: with commands the vehicle can follow within friction, step 2 returns the kinematic
twist exactly and step 4 integrates it exactly, so a constant command reproduces the kinematic
circle to rounding (1e-10 mm over 10 m). A command that varies in time is sampled at the middle
of each step (the controller of :meth:`World.run` is called with the step's midpoint time),
which makes the scheme the exponential midpoint rule: second order, 1e-4 to 1e-3 mm over 10 m
at 1/240 s for smooth commands, against a budget of 0.01 mm (tests/sandbox/test_sandbox_fidelity.py,
and the gallery page notebooks/02_sandbox).

Speed: the hot loop is plain floats (no numpy for 3-vectors), the body's state is written to
pymunk through its C setters, and a steering change recomputes only the steered wheels'
data; the no-slip step costs a few tens of microseconds (benchmarks/sandbox.py).

Determinism: no randomness but the seeded encoder noise, no iteration over sets or unordered
containers, plain IEEE arithmetic: the same inputs give bit-identical trajectories, in this
process or another.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import pymunk
from numpy.typing import ArrayLike

from wheelkin import _validate as V
from wheelkin.frames import Pose, Twist

from .contact import ContactModel, _Base, _Warm
from .sensors import Encoder
from .vehicles import VehicleSpec, command_table, ideal_commands, ideal_rates

__all__ = ["Robot", "Trajectory", "World"]

_ROBOT, _WALL = 1, 2

#: The ranges the sandbox accepts (outside them a float would overflow or lose the step):
#: the step dt, s; a coordinate of a pose or a wall, m; a body speed, m/s; a yaw rate, rad/s;
#: a wheel rate, rad/s; the steps of one run; a wall's thickness, m; a friction coefficient.
DT_RANGE = (1e-6, 1.0)
MAX_COORDINATE = 1e6
MAX_SPEED = 1e3
MAX_YAW_RATE = 1e3
MAX_WHEEL_RATE = 1e5
MAX_STEPS = 10**8
MAX_WALL_THICKNESS = 100.0
MAX_FRICTION = 10.0
#: A vehicle the contact solver can step: its mass, kg, and radius of gyration sqrt(I / m), m
#: (outside, the solve overflows or its matrices turn singular); its mu is at most MAX_FRICTION.
MASS_RANGE = (1e-6, 1e6)
GYRATION_RANGE = (1e-3, 1e2)


def _steppable(spec: VehicleSpec) -> None:
    """``ValueError`` naming the field unless the contact solver can step ``spec``."""
    if not 0.0 < spec.mu <= MAX_FRICTION:
        raise ValueError(f"spec.mu must be in (0, {MAX_FRICTION:g}], got {spec.mu!r}")
    if not MASS_RANGE[0] <= spec.mass <= MASS_RANGE[1]:
        raise ValueError(f"spec.mass must be in [{MASS_RANGE[0]:g}, {MASS_RANGE[1]:g}] kg, "
                         f"got {spec.mass!r}")
    gyration = math.sqrt(spec.inertia / spec.mass)
    if not GYRATION_RANGE[0] <= gyration <= GYRATION_RANGE[1]:
        raise ValueError(f"spec.inertia must give a radius of gyration sqrt(inertia / mass) in "
                         f"[{GYRATION_RANGE[0]:g}, {GYRATION_RANGE[1]:g}] m, got {gyration:g} m")


def _integer(name: str, value, low: int) -> int:
    """``value`` as an int; ``ValueError`` unless it is an integer (not a bool) >= ``low``."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < low:
        raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    return int(value)


def _pose(value) -> tuple[float, float, float]:
    p = V.pose("pose", value)
    x, y, theta = (float(v) for v in p)
    if abs(x) > MAX_COORDINATE or abs(y) > MAX_COORDINATE:
        raise ValueError(f"pose must be within |x|, |y| <= {MAX_COORDINATE:g} m, got {value!r}")
    return x, y, theta


def _twist(names: tuple, values) -> tuple[float, float, float]:
    """(vx, vy, omega) as floats; ``ValueError`` naming the component unless finite and
    within the speed and yaw-rate ranges."""
    u, v, w = (V.finite(n, x) for n, x in zip(names, values, strict=True))
    for n, x, limit, unit in zip(names, (u, v, w), (MAX_SPEED, MAX_SPEED, MAX_YAW_RATE),
                                 ("m/s", "m/s", "rad/s"), strict=True):
        if abs(x) > limit:
            raise ValueError(f"{n} must be within [-{limit:g}, {limit:g}] {unit}, got {x!r}")
    return u, v, w


def _wheel_rate(name: str, value) -> float:
    return V.in_range(name, value, -MAX_WHEEL_RATE, MAX_WHEEL_RATE)

try:  # pymunk's C setters, without its Python property layers (called four times a step)
    from pymunk._chipmunk_cffi import lib as _lib

    _set_velocity, _set_angular_velocity = _lib.cpBodySetVelocity, _lib.cpBodySetAngularVelocity
    _set_position, _set_angle = _lib.cpBodySetPosition, _lib.cpBodySetAngle
    _C_SETTERS = True
except (ImportError, AttributeError):  # pragma: no cover - a pymunk without them
    _C_SETTERS = False

    def _set_velocity(body, v):
        body._owner.velocity = v

    def _set_angular_velocity(body, w):
        body._owner.angular_velocity = w

    def _set_position(body, p):
        body._owner.position = p

    def _set_angle(body, a):
        body._owner.angle = a


@dataclass(frozen=True)
class Trajectory:
    """One robot's recorded run (arrays over N recorded instants).

    Attributes
    ----------
    t : (N,) s.
    pose : (N, 3) world x, y (m), heading theta (rad, unwrapped).
    twist : (N, 3) body twist vx, vy (m/s), omega (rad/s).
    wheel_angles : (N, n) true cumulative wheel rotations, rad (``wheel_names`` order).
    encoder_counts : (N, n) encoder readings (int; float rad for an ideal encoder).
    slipping : (N, n) bool, friction cap hit during the step that ended at t.
    slip_speed : (N, n) slip speed at each contact over that step, m/s.
    commanded_rates : (N, n) commanded wheel rates over the step that ended at t, rad/s.
    wheel_rates : (N, n) actual wheel rates over that step (differ with a motor lag), rad/s.
    steering : (N, k) steering angles, rad (``steered_names`` order).
    contact : (N,) bool, touching a wall or another vehicle.
    distance : (N,) path length travelled by the reference point, m.
    wheel_names, steered_names : names of the columns.

    A record is checked when made: N >= 1 instants, every array of its shape, finite, the
    flags booleans, the counts integers (or, for an ideal encoder, finite angles).
    """

    t: np.ndarray
    pose: np.ndarray
    twist: np.ndarray
    wheel_angles: np.ndarray
    encoder_counts: np.ndarray
    slipping: np.ndarray
    slip_speed: np.ndarray
    commanded_rates: np.ndarray
    wheel_rates: np.ndarray
    steering: np.ndarray
    contact: np.ndarray
    distance: np.ndarray
    wheel_names: tuple
    steered_names: tuple

    def __post_init__(self) -> None:
        for field in ("wheel_names", "steered_names"):
            names = getattr(self, field)
            if not isinstance(names, tuple) or not all(isinstance(s, str) for s in names):
                raise ValueError(f"{field} must be a tuple of str, got {names!r}")
        t = V.finite_array("t", self.t)
        if t.ndim != 1 or len(t) < 1:
            raise ValueError(f"t must have shape (N,), N >= 1, got shape {t.shape}")
        n, k, count = len(self.wheel_names), len(self.steered_names), len(t)
        shapes = {"pose": (count, 3), "twist": (count, 3), "wheel_angles": (count, n),
                  "encoder_counts": (count, n), "slipping": (count, n),
                  "slip_speed": (count, n), "commanded_rates": (count, n),
                  "wheel_rates": (count, n), "steering": (count, k), "contact": (count,),
                  "distance": (count,)}
        object.__setattr__(self, "t", t)
        for field, shape in shapes.items():
            value = getattr(self, field)
            if field in ("slipping", "contact"):
                arr = np.asarray(value)
                if arr.dtype != bool:
                    raise ValueError(f"{field} must be an array of booleans, got {value!r}")
            elif field == "encoder_counts" and np.asarray(value).dtype.kind in "iu":
                arr = np.asarray(value)  # quantised counts; an ideal encoder's are angles
            else:
                arr = V.finite_array(field, value)
            if arr.shape != shape:
                raise ValueError(f"{field} must have shape {shape} (N = len(t), wheel_names, "
                                 f"steered_names), got shape {arr.shape}")
            object.__setattr__(self, field, arr)

    def __len__(self) -> int:
        return len(self.t)


class Robot:
    """A vehicle in a :class:`World` (create it with :meth:`World.add`)."""

    def __init__(self, world: World, spec: VehicleSpec, pose: ArrayLike, twist: ArrayLike) -> None:
        if not isinstance(world, World):
            raise ValueError(f"world must be a World, got {type(world).__name__}")
        if not isinstance(spec, VehicleSpec):
            raise ValueError(f"spec must be a VehicleSpec, got {type(spec).__name__}")
        _steppable(spec)
        self._x, self._y, self._theta = _pose(pose)
        tw = V.twist("twist", twist)
        tw = _twist(("twist[0] (vx)", "twist[1] (vy)", "twist[2] (omega)"), tw)
        self.world = world
        self.spec = spec
        self._dt = world.dt
        self._n = len(spec.wheel_names)
        self._u, self._v, self._w = (float(v) for v in tw)
        self._steer = (0.0,) * len(spec.steered_names)
        self._table = command_table(spec)
        rates, steer = ideal_commands(spec, tw, self._steer)
        self._steer = tuple(float(a) for a in steer)
        self._cmd = [float(r) for r in rates]
        self._rates = list(self._cmd)
        self._step_rates = self._rates
        self._angles = [0.0] * self._n
        self._slipping = (False,) * self._n
        self._slip_speed = (0.0,) * self._n
        self._distance = 0.0
        self._touching = 0
        self._model = ContactModel(spec, self._steer, self._dt, _Base(spec, self._dt))
        self._warm = _Warm()
        tau = spec.motor_time_constant
        if tau > 0:  # expm1: the mean stays exact for a lag much longer than a step
            decay = math.exp(-self._dt / tau)
            self._lag = (decay, -tau * math.expm1(-self._dt / tau) / self._dt)
        else:
            self._lag = None
        self.encoder = Encoder(self._n, spec.steps_per_rev, spec.encoder_noise, spec.seed)
        body = pymunk.Body(spec.mass, spec.inertia)
        body.position = (self._x, self._y)
        body.angle = self._theta
        c, s = math.cos(self._theta), math.sin(self._theta)
        body.velocity = (c * self._u - s * self._v, s * self._u + c * self._v)
        body.angular_velocity = self._w
        shape = pymunk.Poly(body, spec.body)
        shape.friction = world.wall_friction
        shape.elasticity = 0.0
        shape.collision_type = _ROBOT
        body.position_func = self._position_func
        self.body, self.shape = body, shape
        self._handle = body._body if _C_SETTERS else _Owner(body)

    # ------------------------------------------------------------------ commands
    def set_wheel_rates(self, rates: ArrayLike) -> None:
        """Command the driven wheels' rates, rad/s (each at most 1e5 in size), in
        ``spec.wheel_names`` order."""
        r = V.shaped("rates", rates, (self._n,))
        if r.ndim != 1:
            raise ValueError(f"rates must have shape ({self._n},), got shape {r.shape}")
        if np.any(np.abs(r) > MAX_WHEEL_RATE):
            raise ValueError(f"rates must be within [-{MAX_WHEEL_RATE:g}, {MAX_WHEEL_RATE:g}] "
                             f"rad/s, got {r.tolist()}")
        self._cmd = r.tolist()

    def set_side_rates(self, left: float, right: float) -> None:
        """Skid steer: drive the left wheels (FL, RL) at ``left``, the right (FR, RR) at
        ``right``, rad/s. Works for any vehicle, by the sign of each wheel's y position."""
        lv, rv = _wheel_rate("left", left), _wheel_rate("right", right)
        self._cmd = [lv if w.position[1] > 0 else rv for w in self.spec.driven_wheels]

    def set_steering(self, angles: ArrayLike) -> None:
        """Steer the steered wheels, rad, ``spec.steered_names`` order (+ = counter-clockwise)."""
        k = len(self.spec.steered_names)
        a = V.shaped("angles", angles, (k,))
        if a.ndim != 1:
            raise ValueError(f"angles must have shape ({k},), got shape {a.shape}")
        if np.any(np.abs(a) > math.pi):
            raise ValueError(f"angles must be in [-pi, pi], got {a.tolist()}")
        self._steer_to(tuple(a.tolist()))

    def _steer_to(self, steer: tuple) -> None:
        if steer != self._steer:
            self._steer = steer
            self._model.retarget(steer)
            self._warm.consistent_key = None

    def command_twist(self, vx: float, vy: float, omega: float) -> None:
        """Command the ideal wheel rates (and steering) of a body twist (m/s, m/s, rad/s).

        See :func:`~wheelkin.sandbox.vehicles.ideal_commands`: what the wheels cannot follow
        (a skid steer's or a differential drive's sideways velocity) is left to friction.
        """
        given = (vx, vy, omega)
        try:  # plain floats first: a controller calls this every step
            valid = not isinstance(vx, bool) and not isinstance(vy, bool) \
                and not isinstance(omega, bool)
            vx, vy, omega = float(vx), float(vy), float(omega)
            valid = valid and abs(vx) <= MAX_SPEED and abs(vy) <= MAX_SPEED \
                and abs(omega) <= MAX_YAW_RATE  # False for NaN too
        except (TypeError, ValueError):
            valid = False
        if not valid:
            _twist(("vx", "vy", "omega"), given)  # raises, naming the parameter
        rates, steer, rolls = ideal_rates(self._table, vx, vy, omega, self._steer)
        self._steer_to(steer)
        self._cmd = rates
        # The ideal rates of a twist all the wheels can roll at need no consistency check.
        warm = self._warm
        warm.consistent_key, warm.consistent_rates, warm.consistent = self._model, rates, rolls

    # ------------------------------------------------------------------ state
    @property
    def pose(self) -> Pose:
        """(x, y, theta): world position of the reference point (m), heading (rad, unwrapped)."""
        return Pose(self._x, self._y, self._theta)

    @property
    def twist(self) -> Twist:
        """(vx, vy, omega): body-frame twist (m/s, m/s, rad/s)."""
        return Twist(self._u, self._v, self._w)

    @property
    def wheel_angles(self) -> np.ndarray:
        """True cumulative wheel rotations, rad (``spec.wheel_names`` order)."""
        return np.array(self._angles)

    @property
    def wheel_rates(self) -> np.ndarray:
        """Actual wheel rates over the last step, rad/s."""
        return np.array(self._rates)

    @property
    def commanded_rates(self) -> np.ndarray:
        """The current wheel-rate command, rad/s."""
        return np.array(self._cmd)

    @property
    def steering(self) -> np.ndarray:
        """Current steering angles, rad (``spec.steered_names`` order)."""
        return np.array(self._steer)

    @property
    def encoder_counts(self) -> np.ndarray:
        """Encoder readings now (cumulative, quantised; see :mod:`.sensors`)."""
        return self.encoder.counts(self._angles, self.world.steps)

    @property
    def encoder_angles(self) -> np.ndarray:
        """The wheel angles the encoder readings stand for, rad."""
        return self.encoder.angles(self.encoder_counts)

    @property
    def slipping(self) -> np.ndarray:
        """Per driven wheel: the friction cap was hit in the last step."""
        return np.array(self._slipping)

    @property
    def slip_speed(self) -> np.ndarray:
        """Per driven wheel: speed of the contact point relative to the wheel surface, m/s."""
        return np.array(self._slip_speed)

    @property
    def contact(self) -> bool:
        """Touching a wall or another vehicle."""
        return self._touching > 0

    @property
    def distance(self) -> float:
        """Path length travelled by the reference point, m."""
        return self._distance

    # ------------------------------------------------------------------ stepping
    def _pre_step(self) -> None:
        dt = self._dt
        if self._lag is None:
            rates = self._cmd
        else:
            decay, mean = self._lag
            old = self._rates
            rates = [c + (r - c) * mean for c, r in zip(self._cmd, old, strict=True)]
            self._end_rates = [c + (r - c) * decay for c, r in zip(self._cmd, old, strict=True)]
        # Free flight: the world velocity is kept while the frame turns by w dt.
        u, v, w = self._u, self._v, self._w
        a = w * dt
        if a != 0.0:
            ca, sa = math.cos(a), math.sin(a)
            u, v = ca * u + sa * v, -sa * u + ca * v
        res = self._model.solve(rates, (u, v, w), self._warm)
        u, v, w = res.twist
        self._slipping, self._slip_speed = res.slipping, res.slip_speed
        self._u, self._v, self._w = u, v, w
        th = self._theta
        c, s = math.cos(th), math.sin(th)
        handle = self._handle
        _set_velocity(handle, (c * u - s * v, s * u + c * v))
        _set_angular_velocity(handle, w)
        if self._lag is None:
            self._rates = rates
        else:
            self._rates = self._end_rates
        angles = self._angles
        for i, r in enumerate(rates):
            angles[i] += r * dt
        self._step_rates = rates

    def _position_func(self, body: pymunk.Body, dt: float) -> None:
        """Replaces pymunk's Euler step p += (v + v_bias) dt: no motion here, only pymunk's
        penetration correction (v_bias) when touching. The motion is the exact arc, applied in
        :meth:`_post_step` once pymunk has resolved the collisions of this step."""
        if self._touching:
            vel, av = body.velocity, body.angular_velocity
            p0, a0 = body.position, body.angle
            body.velocity, body.angular_velocity = (0.0, 0.0), 0.0
            pymunk.Body.update_position(body, dt)
            p1, a1 = body.position, body.angle
            body.velocity, body.angular_velocity = vel, av
            self._x += p1[0] - p0[0]
            self._y += p1[1] - p0[1]
            self._theta += a1 - a0

    def _post_step(self) -> None:
        th = self._theta
        c, s = math.cos(th), math.sin(th)
        if self._touching or self._hit:
            # A wall or another vehicle pushed back: take the twist pymunk left us.
            self._hit = False
            vx, vy = self.body.velocity
            self._u, self._v = c * vx + s * vy, -s * vx + c * vy
            self._w = self.body.angular_velocity
        u, v, w = self._u, self._v, self._w
        dt = self._dt
        # The exact SE(2) arc of the constant body twist (u, v, w) over dt.
        a = w * dt
        if a == 0.0:
            fs, fc = dt, 0.0
        else:
            half = math.sin(0.5 * a)
            fs, fc = math.sin(a) / w, 2.0 * half * half / w
        dxb, dyb = u * fs - v * fc, u * fc + v * fs
        self._x += c * dxb - s * dyb
        self._y += s * dxb + c * dyb
        self._theta = th + a
        self._distance += math.hypot(u, v) * dt
        _set_position(self._handle, (self._x, self._y))
        _set_angle(self._handle, self._theta)

    _hit = False


class _Owner:  # pragma: no cover - only with a pymunk lacking the C setters
    def __init__(self, body):
        self._owner = body


def _segments(walls) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    out = []
    if isinstance(walls, str | bytes) or not isinstance(walls, Sequence | np.ndarray):
        raise ValueError(f"walls must be a sequence of segments ((x0, y0), (x1, y1)), "
                        f"got {walls!r}")
    for i, wall in enumerate(walls):
        arr = V.finite_array(f"walls[{i}]", wall)
        if arr.shape != (2, 2):
            raise ValueError(f"walls[{i}] must be a segment ((x0, y0), (x1, y1)), got {wall!r}")
        if np.any(np.abs(arr) > MAX_COORDINATE):
            raise ValueError(f"walls[{i}] must be within |x|, |y| <= {MAX_COORDINATE:g} m, "
                             f"got {wall!r}")
        out.append(((float(arr[0, 0]), float(arr[0, 1])), (float(arr[1, 0]), float(arr[1, 1]))))
    return out


class World:
    """A top-down world without gravity: vehicles on a flat floor, static walls.

    Parameters
    ----------
    dt : float
        Fixed step, s (in [1e-6, 1]; default 1/240).
    walls : sequence of ((x0, y0), (x1, y1))
        Static wall segments, m (coordinates within +-1e6 m).
    wall_thickness : float
        Full thickness of the walls, m (in [0, 100]).
    wall_friction : float
        Friction coefficient between vehicle bodies and walls (in [0, 10]).

    A robot is placed within +-1e6 m and commanded within 1e3 m/s and 1e3 rad/s (its body) or
    1e5 rad/s (its wheels), and one run lasts at most 1e8 steps; its vehicle has mu <= 10, a
    mass in [1e-6, 1e6] kg and a radius of gyration in [1e-3, 100] m. Beyond these ranges the
    arithmetic overflows or loses the step (``ValueError``, naming the parameter).

    Examples
    --------
    >>> from wheelkin.sandbox import World, RADON_ULZER
    >>> world = World()
    >>> robot = world.add(RADON_ULZER, pose=(0, 0, 0), twist=(0.2, 0, 0))
    >>> world.step(240)
    >>> [round(v, 9) for v in robot.pose]
    [0.2, 0.0, 0.0]
    >>> World(dt=0)
    Traceback (most recent call last):
    ...
    ValueError: dt must be in [1e-06, 1], got 0
    """

    def __init__(self, dt: float = 1 / 240, walls: Sequence = (), *, wall_thickness: float = 0.01,
                 wall_friction: float = 0.3) -> None:
        self.dt = V.in_range("dt", dt, *DT_RANGE)
        self.wall_thickness = V.in_range("wall_thickness", wall_thickness, 0.0,
                                         MAX_WALL_THICKNESS)
        self.wall_friction = V.in_range("wall_friction", wall_friction, 0.0, MAX_FRICTION)
        self.walls = tuple(_segments(walls))
        self.space = pymunk.Space()
        self.space.gravity = (0.0, 0.0)
        self.space.collision_slop = 1e-4
        self.space.iterations = 20
        for a, b in self.walls:
            seg = pymunk.Segment(self.space.static_body, a, b, self.wall_thickness / 2)
            seg.friction = 1.0
            seg.elasticity = 0.0
            seg.collision_type = _WALL
            self.space.add(seg)
        self.robots: list[Robot] = []
        self._by_body: dict = {}
        self.steps = 0
        self.space.on_collision(_ROBOT, _WALL, begin=self._begin, separate=self._separate)
        self.space.on_collision(_ROBOT, _ROBOT, begin=self._begin, separate=self._separate)

    @property
    def time(self) -> float:
        """Simulated time, s (steps * dt)."""
        return self.steps * self.dt

    def _touch(self, arbiter: pymunk.Arbiter, delta: int) -> None:
        for shape in arbiter.shapes:
            robot = self._by_body.get(shape.body)
            if robot is not None:
                robot._touching += delta
                if delta > 0:
                    robot._hit = True

    def _begin(self, arbiter, space, data) -> None:
        self._touch(arbiter, +1)

    def _separate(self, arbiter, space, data) -> None:
        self._touch(arbiter, -1)

    def add(self, spec: VehicleSpec, pose: ArrayLike = (0.0, 0.0, 0.0),
            twist: ArrayLike = (0.0, 0.0, 0.0)) -> Robot:
        """Put a vehicle in the world at ``pose`` (x, y, theta) moving with body ``twist``.

        The wheels start at the ideal rates (and steering) of ``twist``, so that the vehicle
        keeps it until commanded otherwise.
        """
        robot = Robot(self, spec, pose, twist)
        self.space.add(robot.body, robot.shape)
        self.robots.append(robot)
        self._by_body[robot.body] = robot
        return robot

    def step(self, n: int = 1) -> None:
        """Advance ``n`` steps of ``dt``, holding every command."""
        n = _integer("n", n, 0)
        advance = self._advance
        for _ in range(n):
            advance()

    def _advance(self) -> None:
        """One step of every robot (see the module docstring)."""
        robots = self.robots
        for robot in robots:
            robot._pre_step()
        self.space.step(self.dt)
        for robot in robots:
            robot._post_step()
        self.steps += 1

    def run(
        self,
        duration: float,
        controller: Callable[[float, World], None] | None = None,
        record_every: int = 1,
    ) -> Trajectory | list[Trajectory]:
        """Simulate ``duration`` seconds and record every robot.

        Parameters
        ----------
        duration : float
            s (>= 0, at most 1e8 steps), rounded to a whole number of steps.
        controller : callable (t, world) -> None, optional
            Called before each step to set the robots' commands; ``t`` is the time at the
            *middle* of that step (``world.time + dt/2``), so a command that is a smooth
            function of time is integrated to second order, and a schedule switching at a
            multiple of dt switches exactly there.
        record_every : int
            Record every k-th step (the initial and the final state always).

        Returns
        -------
        Trajectory, or a list of them (one per robot, in the order added) if there are several.
        """
        longest = MAX_STEPS * self.dt
        duration = V.in_range("duration", duration, 0.0, longest)
        if controller is not None and not callable(controller):
            raise ValueError(f"controller must be callable (t, world) -> None, got {controller!r}")
        record_every = _integer("record_every", record_every, 1)
        if not self.robots:
            raise ValueError("the world has no robots: add one with world.add(spec)")
        steps = max(0, math.ceil(duration / self.dt - 1e-9))
        logs = [[] for _ in self.robots]
        stamps = []
        pairs = list(zip(self.robots, logs, strict=True))

        def record():
            stamps.append(self.steps)
            for robot, log in pairs:
                # One flat tuple of floats per record (split into arrays at the end).
                log.append((robot._x, robot._y, robot._theta, robot._u, robot._v, robot._w,
                            robot._distance, robot._touching > 0, *robot._angles,
                            *robot._slipping, *robot._slip_speed, *robot._cmd,
                            *robot._step_rates, *robot._steer))

        record()
        dt = self.dt
        advance = self._advance
        for k in range(1, steps + 1):
            if controller is not None:
                controller((self.steps + 0.5) * dt, self)
            advance()
            if k % record_every == 0 or k == steps:
                record()
        stamps_arr = np.array(stamps, dtype=np.int64)
        out = [self._trajectory(robot, log, stamps_arr) for robot, log in pairs]
        return out[0] if len(out) == 1 else out

    def _trajectory(self, robot: Robot, log: list, stamps: np.ndarray) -> Trajectory:
        n, k = robot._n, len(robot.spec.steered_names)
        table = np.array(log, dtype=float).reshape(len(log), 8 + 5 * n + k)
        cols = iter(np.split(table, np.cumsum([3, 3, 1, 1, n, n, n, n, n]), axis=1))
        pose, twist, distance, contact = next(cols), next(cols), next(cols), next(cols)
        angles, slipping, slip_speed, commanded, rates, steering = (next(cols) for _ in range(6))
        return Trajectory(
            t=stamps * self.dt,
            pose=pose.copy(),
            twist=twist.copy(),
            wheel_angles=angles.copy(),
            encoder_counts=robot.encoder.counts(angles, stamps),
            slipping=slipping.astype(bool),
            slip_speed=slip_speed.copy(),
            commanded_rates=commanded.copy(),
            wheel_rates=rates.copy(),
            steering=steering.copy(),
            contact=contact[:, 0].astype(bool),
            distance=distance[:, 0].copy(),
            wheel_names=robot.spec.wheel_names,
            steered_names=robot.spec.steered_names,
        )
