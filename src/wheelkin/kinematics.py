r"""Kinematics objects a control loop holds: built and checked once, then cheap per call.

The chapters' functions (:mod:`wheelkin.diffdrive`, :mod:`wheelkin.mecanum`,
:mod:`wheelkin.carlike`, :mod:`wheelkin.rover`) take arrays and validate every argument on
every call; that is right for a notebook and slow for a robot's 100 Hz loop. The objects here
hold one vehicle's geometry, validated when they are built, and answer one command at a time
on plain floats (``math``, not NumPy), with a cheap check of what changes per call: every
number finite, and every result finite too (a result that overflows is a ``ValueError``
naming the input).

Every vehicle answers the same three calls (the habit of the Robotics Toolbox's
``VehicleBase``, with the names of WPILib's kinematics classes in mind):

- ``inverse(twist)``: the wheels' command for a body twist;
- ``forward(wheels)``: the body twist that wheel state gives (least squares where the wheels
  over-determine it);
- ``desaturate(wheels, max_speed)``: the wheel speeds scaled together so that none exceeds
  ``max_speed``, the path kept (WPILib's ``desaturateWheelSpeeds``).

Units and frame: SI and REP-103 (x forward, y left, yaw rate counter-clockwise positive).
A wheel's speed is its **ground speed** in m/s (rim speed: the wheel's rate times its radius),
for every vehicle, so that ``max_speed`` means one thing; a steering angle is in rad, positive
when the wheel's front edge turns left. A twist is a :class:`wheelkin.frames.Twist` (a tuple
``(vx, vy, omega)`` is taken too). A vehicle that cannot move sideways (the differential
drive, the car, the rover) refuses a twist with ``vy != 0`` rather than drop it.

>>> kin = DiffDriveKinematics(track_width=0.5)
>>> kin.inverse(Twist(1.0, 0.0, 2.0))
DiffDriveWheelSpeeds(left=0.5, right=1.5)
>>> kin.forward(DiffDriveWheelSpeeds(0.5, 1.5))
Twist(vx=1.0, vy=0.0, omega=2.0)
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from typing import ClassVar, Generic, NamedTuple, TypeVar

import numpy as np

from wheelkin import _validate as V
from wheelkin._records import _trusted
from wheelkin._validate import InputTypeError
from wheelkin.frames import Twist
from wheelkin.mecanum import MecanumGeometry
from wheelkin.rover import HARD_STOP, RoverGeometry

__all__ = [
    "AckermannKinematics",
    "AckermannWheels",
    "DiffDriveKinematics",
    "DiffDriveWheelSpeeds",
    "MecanumKinematics",
    "MecanumWheelSpeeds",
    "RoverKinematics",
    "RoverWheels",
    "VehicleKinematics",
]


class DiffDriveWheelSpeeds(NamedTuple):
    """Ground speeds (m/s) of a differential drive's left and right wheels."""

    left: float
    right: float


class MecanumWheelSpeeds(NamedTuple):
    """Ground (rim) speeds (m/s) of a mecanum base's wheels FL, FR, RL, RR: each wheel's rate
    times its radius, positive rolling the wheel forward."""

    fl: float
    fr: float
    rl: float
    rr: float


class AckermannWheels(NamedTuple):
    """A rear-driven car's wheels: the front wheels' steering angles (rad, positive to the
    left) and the rear wheels' ground speeds (m/s)."""

    left_angle: float
    right_angle: float
    rear_left: float
    rear_right: float


class RoverWheels(NamedTuple):
    """The six-wheel rover's wheels: ground speeds (m/s) of LF, LM, LB, RF, RM, RB, positive
    rolling forward along the wheel's steered direction, and the steering angles (rad,
    positive to the left, REP-103) of the four corners LF, RF, LB, RB."""

    lf: float
    lm: float
    lb: float
    rf: float
    rm: float
    rb: float
    steer_lf: float
    steer_rf: float
    steer_lb: float
    steer_rb: float


#: The wheel record of a vehicle: what its :class:`VehicleKinematics` returns from ``inverse``
#: and takes in ``forward`` and ``desaturate``.
WheelsT = TypeVar("WheelsT", DiffDriveWheelSpeeds, MecanumWheelSpeeds, AckermannWheels,
                  RoverWheels)


def _twist(twist: Twist | tuple[float, float, float]) -> tuple[float, float, float]:
    """A twist's three components as floats: a Twist is already checked (it validates when it
    is made), a tuple or list of three numbers is checked here."""
    if type(twist) is Twist:
        return twist
    if isinstance(twist, tuple | list) and len(twist) == 3:
        return V.real("vx", twist[0]), V.real("vy", twist[1]), V.real("omega", twist[2])
    raise InputTypeError(f"twist must be a Twist (vx, vy, omega), got the "
                         f"{type(twist).__name__} {twist!r}")


def _wheels(cls: type[WheelsT], wheels: WheelsT | tuple[float, ...]) -> WheelsT:
    """Wheel state of type ``cls``, each field a finite float (cheap when it already is)."""
    if type(wheels) is cls:
        for value in wheels:
            if type(value) is not float or value - value != 0.0:
                break
        else:
            return wheels
    if not isinstance(wheels, tuple | list) or len(wheels) != len(cls._fields):
        raise InputTypeError(f"wheels must be a {cls.__name__} {cls._fields}, got the "
                             f"{type(wheels).__name__} {wheels!r}")
    return cls(*(V.real(name, value) for name, value in zip(cls._fields, wheels,
                                                              strict=True)))


def _no_sideways(kind: str, vy: float) -> None:
    if vy != 0.0:
        raise ValueError(f"twist.vy must be 0: a {kind} cannot move sideways, got vy={vy!r}")


def _overflow(*values: float) -> bool:
    for value in values:
        if value - value != 0.0:
            return True
    return False


def _scale(values: tuple[float, ...], max_speed: float) -> tuple[float, ...]:
    """The values scaled together so that the largest size is at most ``max_speed``."""
    biggest = max(abs(v) for v in values)
    if biggest <= max_speed:
        return values
    k = max_speed / biggest
    return tuple(v * k for v in values)


class VehicleKinematics(ABC, Generic[WheelsT]):
    """The interface every kinematics object answers (see the module docstring).

    ``wheel_names`` names the wheel speeds in the order of the wheel record's fields.
    """

    #: The wheels whose speeds the record holds, in its order.
    wheel_names: ClassVar[tuple[str, ...]]

    @abstractmethod
    def inverse(self, twist: Twist) -> WheelsT:
        """The wheels' command for the body ``twist`` (m/s, m/s, rad/s)."""

    @abstractmethod
    def forward(self, wheels: WheelsT) -> Twist:
        """The body twist the wheel state gives."""

    @abstractmethod
    def desaturate(self, wheels: WheelsT, max_speed: float) -> WheelsT:
        """The wheel speeds scaled together so that none exceeds ``max_speed`` (m/s) in size;
        steering angles are kept. A command within the limit comes back unchanged."""

    @staticmethod
    def _max_speed(max_speed: float) -> float:
        value = V.real("max_speed", max_speed)
        if value <= 0.0:
            raise ValueError(f"max_speed must be a finite number > 0, got {max_speed!r}")
        return value


class DiffDriveKinematics(VehicleKinematics[DiffDriveWheelSpeeds]):
    r"""A differential drive of track width :math:`W` (m, > 0).

    .. math:: v_L = v - \omega\frac{W}{2},\quad v_R = v + \omega\frac{W}{2};\qquad
              v = \frac{v_L + v_R}{2},\quad \omega = \frac{v_R - v_L}{W}

    (:func:`wheelkin.diffdrive.wheel_speeds` and :func:`~wheelkin.diffdrive.body_twist`, one
    command at a time). WPILib's ``DifferentialDriveKinematics``.

    Examples
    --------
    A loop that turns a twist into wheel speeds a motor can reach (1.2 m/s at most):

    >>> kin = DiffDriveKinematics(track_width=0.5)
    >>> for twist in (Twist(1.0, 0.0, 0.0), Twist(1.0, 0.0, 2.0), Twist(0.0, 0.0, 4.0)):
    ...     print(kin.desaturate(kin.inverse(twist), 1.2))
    DiffDriveWheelSpeeds(left=1.0, right=1.0)
    DiffDriveWheelSpeeds(left=0.4, right=1.2)
    DiffDriveWheelSpeeds(left=-1.0, right=1.0)
    >>> kin.inverse(Twist(1.0, 0.5, 0.0))
    Traceback (most recent call last):
    ...
    ValueError: twist.vy must be 0: a differential drive cannot move sideways, got vy=0.5
    """

    wheel_names: ClassVar[tuple[str, ...]] = ("left", "right")

    def __init__(self, *, track_width: float) -> None:
        self.track_width = V.positive("track_width", track_width)
        self._half = 0.5 * self.track_width

    def __repr__(self) -> str:
        return f"DiffDriveKinematics(track_width={self.track_width!r})"

    def inverse(self, twist: Twist) -> DiffDriveWheelSpeeds:
        """Left and right ground speeds (m/s) for ``twist``."""
        v, vy, w = _twist(twist)
        _no_sideways("differential drive", vy)
        left, right = v - w * self._half, v + w * self._half
        if _overflow(left, right):
            raise ValueError(f"twist is out of range: the wheel speeds overflow, got {twist!r}")
        return DiffDriveWheelSpeeds(left, right)

    def forward(self, wheels: DiffDriveWheelSpeeds) -> Twist:
        """The twist ``(v, 0, omega)`` of the wheel speeds."""
        left, right = _wheels(DiffDriveWheelSpeeds, wheels)
        v, w = 0.5 * left + 0.5 * right, (right - left) / self.track_width
        if _overflow(v, w):
            raise ValueError(f"wheels is out of range: the twist overflows, got {wheels!r}")
        return _trusted(Twist, v, 0.0, w)

    def desaturate(self, wheels: DiffDriveWheelSpeeds,
                   max_speed: float) -> DiffDriveWheelSpeeds:
        """Both speeds scaled by one factor so that neither exceeds ``max_speed``."""
        if type(max_speed) is not float or not 0.0 < max_speed < math.inf:
            max_speed = self._max_speed(max_speed)
        left, right = _wheels(DiffDriveWheelSpeeds, wheels)
        biggest = abs(left) if abs(left) > abs(right) else abs(right)
        if biggest <= max_speed:
            return DiffDriveWheelSpeeds(left, right)
        k = max_speed / biggest
        return tuple.__new__(DiffDriveWheelSpeeds, (left * k, right * k))


class MecanumKinematics(VehicleKinematics[MecanumWheelSpeeds]):
    r"""A four-wheel mecanum base (:class:`wheelkin.mecanum.MecanumGeometry`), wheels FL, FR,
    RL, RR, rim speeds in m/s.

    .. math::
        u_{FL} = v_x - v_y\cot\gamma - k\omega,\ u_{FR} = v_x + v_y\cot\gamma + k\omega,\
        u_{RL} = v_x + v_y\cot\gamma - k\omega,\ u_{RR} = v_x - v_y\cot\gamma + k\omega

    with :math:`k = b + a\cot\gamma` (the rates of :func:`wheelkin.mecanum.inverse_kinematics`
    times the wheel radius), and the least-squares inverse of that map forward. With a
    ``centre_of_rotation`` :math:`c` the twist's :math:`(v_x, v_y)` is the velocity of the
    point :math:`c`, as in WPILib's ``MecanumDriveKinematics``.

    Examples
    --------
    Strafe, then turn about the front-left wheel, which stays still:

    >>> g = MecanumGeometry(half_wheelbase=0.2, half_track=0.15, wheel_radius=0.05)
    >>> kin = MecanumKinematics(g)
    >>> kin.inverse(Twist(0.0, 1.0, 0.0))
    MecanumWheelSpeeds(fl=-1.0, fr=1.0, rl=1.0, rr=-1.0)
    >>> pivot = MecanumKinematics(g, centre_of_rotation=(0.2, 0.15))
    >>> [round(u, 12) + 0.0 for u in pivot.inverse(Twist(0.0, 0.0, 1.0))]
    [0.0, 0.3, -0.4, 0.7]
    >>> kin.forward(MecanumWheelSpeeds(-1.0, 1.0, 1.0, -1.0))
    Twist(vx=0.0, vy=1.0, omega=0.0)
    """

    wheel_names: ClassVar[tuple[str, ...]] = ("FL", "FR", "RL", "RR")

    def __init__(self, geometry: MecanumGeometry, *,
                 centre_of_rotation: tuple[float, float] = (0.0, 0.0)) -> None:
        if not isinstance(geometry, MecanumGeometry):
            raise InputTypeError(f"geometry must be a MecanumGeometry, got the "
                                 f"{type(geometry).__name__} {geometry!r}")
        self.geometry = geometry
        c = V.finite_array("centre_of_rotation", centre_of_rotation)
        if c.shape != (2,):
            raise ValueError("centre_of_rotation must have shape (2,): (c_x, c_y) in m, got "
                             f"shape {c.shape}")
        self.centre_of_rotation = (float(c[0]), float(c[1]))
        self._cot = geometry.lateral_factor
        self._tan = math.tan(geometry.roller_angle)
        self._k = geometry.k

    def __repr__(self) -> str:
        return (f"MecanumKinematics({self.geometry!r}, "
                f"centre_of_rotation={self.centre_of_rotation!r})")

    def inverse(self, twist: Twist) -> MecanumWheelSpeeds:
        """Rim speeds FL, FR, RL, RR (m/s) for ``twist``."""
        vx, vy, w = _twist(twist)
        cx, cy = self.centre_of_rotation
        vx, vy = vx + w * cy, vy - w * cx
        side, turn = vy * self._cot, w * self._k
        out = (vx - side - turn, vx + side + turn, vx + side - turn, vx - side + turn)
        if _overflow(*out):
            raise ValueError(f"twist is out of range: the wheel speeds overflow, got {twist!r}")
        return MecanumWheelSpeeds(*out)

    def forward(self, wheels: MecanumWheelSpeeds) -> Twist:
        """The least-squares twist of the rim speeds (their fighting part moves nothing)."""
        fl, fr, rl, rr = _wheels(MecanumWheelSpeeds, wheels)
        vx = 0.25 * (fl + fr + rl + rr)
        vy = 0.25 * self._tan * (-fl + fr + rl - rr)
        w = 0.25 * (-fl + fr - rl + rr) / self._k
        if _overflow(vx, vy, w):
            raise ValueError(f"wheels is out of range: the twist overflows, got {wheels!r}")
        return _trusted(Twist, vx, vy, w)

    def desaturate(self, wheels: MecanumWheelSpeeds, max_speed: float) -> MecanumWheelSpeeds:
        """The four speeds scaled by one factor so that none exceeds ``max_speed``."""
        if type(max_speed) is not float or not 0.0 < max_speed < math.inf:
            max_speed = self._max_speed(max_speed)
        if type(wheels) is not MecanumWheelSpeeds:
            wheels = _wheels(MecanumWheelSpeeds, wheels)
        fl, fr, rl, rr = wheels
        if not (type(fl) is float and type(fr) is float and type(rl) is float
                and type(rr) is float) or fl - fl + fr - fr + rl - rl + rr - rr != 0.0:
            fl, fr, rl, rr = _wheels(MecanumWheelSpeeds, tuple(wheels))
        a, b, c, d = abs(fl), abs(fr), abs(rl), abs(rr)
        biggest = a if a > b else b
        biggest = c if c > biggest else biggest
        biggest = d if d > biggest else biggest
        if biggest <= max_speed:
            return MecanumWheelSpeeds(fl, fr, rl, rr)
        k = max_speed / biggest
        return tuple.__new__(MecanumWheelSpeeds, (fl * k, fr * k, rl * k, rr * k))


class AckermannKinematics(VehicleKinematics[AckermannWheels]):
    r"""A rear-driven car with Ackermann steering: wheelbase :math:`L`, track width :math:`W`
    (m, keyword-only), reference point the rear-axle midpoint.

    Inverse, with :math:`\kappa = \omega / v`:

    .. math::
        \tan\delta_L = \frac{L\kappa}{1 - \kappa W/2},\quad
        \tan\delta_R = \frac{L\kappa}{1 + \kappa W/2},\quad
        v_{RL} = v - \omega\frac{W}{2},\quad v_{RR} = v + \omega\frac{W}{2}

    (:func:`wheelkin.carlike.ackermann_angles` with :math:`R = 1/\kappa`). Forward: the speed
    is the rear wheels' mean, the curvature the mean of the two front wheels' curvatures
    :math:`\kappa_{L,R} = \tan\delta / (L \pm (W/2)\tan\delta)` (equal when the angles obey
    Ackermann's condition), :math:`\omega = v\kappa`. A car cannot turn on the spot: a twist
    with :math:`v = 0` and :math:`\omega \ne 0` is refused, and so is a turn whose centre
    would lie inside the track or that needs more than ``max_steering_angle``.

    Examples
    --------
    >>> car = AckermannKinematics(wheelbase=2.5, track_width=1.5, max_steering_angle=0.6)
    >>> wheels = car.inverse(Twist(5.0, 0.0, 1.0))  # R = 5 m to the left
    >>> print(f"{wheels.left_angle:.4f} {wheels.right_angle:.4f} {wheels.rear_left:.2f}")
    0.5317 0.4101 4.25
    >>> car.forward(wheels)
    Twist(vx=5.0, vy=0.0, omega=1.0)
    >>> car.inverse(Twist(5.0, 0.0, 3.0))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: omega: the turn needs a steering angle of 1.22 rad, beyond ...
    """

    wheel_names: ClassVar[tuple[str, ...]] = ("rear_left", "rear_right")

    def __init__(self, *, wheelbase: float, track_width: float,
                 max_steering_angle: float = math.pi / 2) -> None:
        self.wheelbase = V.positive("wheelbase", wheelbase)
        self.track_width = V.positive("track_width", track_width)
        self.max_steering_angle = V.in_range("max_steering_angle", max_steering_angle, 0.0,
                                             math.pi / 2)
        if self.max_steering_angle == 0.0:
            raise ValueError(f"max_steering_angle must be in (0, pi/2] rad, got "
                             f"{max_steering_angle!r}")
        self._half = 0.5 * self.track_width

    def __repr__(self) -> str:
        return (f"AckermannKinematics(wheelbase={self.wheelbase!r}, "
                f"track_width={self.track_width!r}, "
                f"max_steering_angle={self.max_steering_angle!r})")

    def inverse(self, twist: Twist) -> AckermannWheels:
        """Front steering angles (rad) and rear ground speeds (m/s) for ``twist``."""
        v, vy, w = _twist(twist)
        _no_sideways("car", vy)
        if v == 0.0:
            if w != 0.0:
                raise ValueError(f"omega must be 0 when vx is 0: a car cannot turn on the "
                                 f"spot, got omega={w!r}")
            return AckermannWheels(0.0, 0.0, 0.0, 0.0)
        kappa = w / v
        inner = 1.0 - abs(kappa) * self._half
        if not inner > 0.0:
            raise ValueError(f"omega: the turn's centre lies inside the track (R = v/omega = "
                             f"{1.0 / kappa:.4g} m, W/2 = {self._half:.4g} m)")
        lk = self.wheelbase * kappa
        left = math.atan2(lk, 1.0 - kappa * self._half)
        right = math.atan2(lk, 1.0 + kappa * self._half)
        steepest = max(abs(left), abs(right))
        if steepest > self.max_steering_angle:
            raise ValueError(f"omega: the turn needs a steering angle of {steepest:.3g} rad, "
                             f"beyond max_steering_angle {self.max_steering_angle:.3g} rad "
                             f"(R = v/omega = {1.0 / kappa:.4g} m)")
        out = (left, right, v - w * self._half, v + w * self._half)
        if _overflow(*out):
            raise ValueError(f"twist is out of range: the wheel speeds overflow, got {twist!r}")
        return AckermannWheels(*out)

    def forward(self, wheels: AckermannWheels) -> Twist:
        """The twist ``(v, 0, v kappa)`` of the rear speeds and the front steering angles."""
        left, right, rl, rr = _wheels(AckermannWheels, wheels)
        for name, angle in (("left_angle", left), ("right_angle", right)):
            if not abs(angle) < 0.5 * math.pi:
                raise ValueError(f"{name} must be in (-pi/2, pi/2) rad, got {angle!r}")
        tl, tr = math.tan(left), math.tan(right)
        length = self.wheelbase
        kappa = 0.5 * (tl / (length + self._half * tl) + tr / (length - self._half * tr))
        v = 0.5 * rl + 0.5 * rr
        w = v * kappa
        if _overflow(v, w):
            raise ValueError(f"wheels is out of range: the twist overflows, got {wheels!r}")
        return _trusted(Twist, v, 0.0, w)

    def desaturate(self, wheels: AckermannWheels, max_speed: float) -> AckermannWheels:
        """The rear speeds scaled by one factor so that neither exceeds ``max_speed``; the
        steering angles (the path's curvature) are kept."""
        w = _wheels(AckermannWheels, wheels)
        rl, rr = _scale((w.rear_left, w.rear_right), self._max_speed(max_speed))
        return AckermannWheels(w.left_angle, w.right_angle, rl, rr)


class RoverKinematics(VehicleKinematics[RoverWheels]):
    r"""The six-wheel, four-corner-steered rover (the Open Source Rover), in SI and REP-103.

    Each wheel at :math:`(x_i, y_i)` moves with :math:`(v - \omega y_i,\ \omega x_i)`; a
    corner steers to that direction, :math:`\delta_i = \arctan\frac{\omega x_i}{v - \omega
    y_i}`, and rolls at :math:`(v - \omega y_i)/\cos\delta_i` (the middle wheels do not steer:
    :math:`x_i = 0`). :func:`wheelkin.rover.wheel_commands`, one command at a time.

    **Turning in place.** With :math:`v = 0` every corner points along the circle through it,
    :math:`\delta = \mp\arctan(d_3/d_1)` at the front and :math:`\pm\arctan(d_2/d_1)` at the
    back (about 55 degrees on the OSR), further than the document's 45 degree stop; the OSR's
    own software steers there to spin (``calculate_rotate_in_place_cmd`` in
    ``osr_control/rover.py`` of nasa-jpl/osr-rover-code). So ``turn_in_place=True`` (the
    default) allows that one command past ``max_corner_angle``; every other turn that needs
    more than ``max_corner_angle`` is refused.

    ``forward`` is the least-squares twist of the six wheels' velocities
    :math:`u_i(\cos\delta_i, \sin\delta_i)` (:math:`v_y` included: it is near zero when the
    wheels agree).

    Examples
    --------
    The OSR (``osr_params.yaml``'s geometry) spinning at 0.5 rad/s:

    >>> from wheelkin.rover import OSR_PARAMS_GEOMETRY
    >>> rover = RoverKinematics(OSR_PARAMS_GEOMETRY)
    >>> spin = rover.inverse(Twist(0.0, 0.0, 0.5))
    >>> print(f"{math.degrees(spin.steer_lf):.2f} {spin.lm:.4f} {spin.lf:.4f}")
    -55.43 -0.1278 -0.1620
    >>> [round(c, 12) + 0.0 for c in rover.forward(spin)]
    [0.0, 0.0, 0.5]
    """

    wheel_names: ClassVar[tuple[str, ...]] = ("LF", "LM", "LB", "RF", "RM", "RB")

    def __init__(self, geometry: RoverGeometry, *, max_corner_angle: float = HARD_STOP,
                 turn_in_place: bool = True) -> None:
        if not isinstance(geometry, RoverGeometry):
            raise InputTypeError(f"geometry must be a RoverGeometry, got the "
                                 f"{type(geometry).__name__} {geometry!r}")
        if not isinstance(turn_in_place, bool):
            raise InputTypeError(f"turn_in_place must be True or False, got the "
                                 f"{type(turn_in_place).__name__} {turn_in_place!r}")
        self.geometry = geometry
        self.max_corner_angle = V.in_range("max_corner_angle", max_corner_angle, 0.0,
                                           math.pi / 2, inclusive=False)
        self.turn_in_place = turn_in_place
        g = geometry.in_unit("m")
        #: Wheel positions (x, y) in m, LF, LM, LB, RF, RM, RB.
        self.positions: tuple[tuple[float, float], ...] = (
            (g.d3, g.d1), (0.0, g.d4), (-g.d2, g.d1),
            (g.d3, -g.d1), (0.0, -g.d4), (-g.d2, -g.d1))
        rows = []
        for x, y in self.positions:
            rows += [[1.0, 0.0, -y], [0.0, 1.0, x]]
        a = np.array(rows)
        self._pinv = tuple(tuple(float(c) for c in row) for row in np.linalg.pinv(a))

    def __repr__(self) -> str:
        return (f"RoverKinematics({self.geometry!r}, max_corner_angle="
                f"{self.max_corner_angle!r}, turn_in_place={self.turn_in_place!r})")

    def inverse(self, twist: Twist) -> RoverWheels:
        """Six ground speeds (m/s) and four corner angles (rad) for ``twist``."""
        v, vy, w = _twist(twist)
        _no_sideways("rover", vy)
        speeds: list[float] = []
        angles: list[float] = []
        for x, y in self.positions:
            along, across = v - w * y, w * x
            if along == 0.0:
                delta = 0.0 if across == 0.0 else math.copysign(0.5 * math.pi, across)
                speed = abs(across) if across != 0.0 else 0.0
            else:
                delta = math.atan(across / along)
                speed = along / math.cos(delta)
            speeds.append(speed)
            if x != 0.0:
                angles.append(delta)
        spinning = v == 0.0 and w != 0.0 and self.turn_in_place
        steepest = max(abs(a) for a in angles)
        if steepest > self.max_corner_angle * (1.0 + 1e-12) and not spinning:
            raise ValueError(f"omega: the turn needs a corner angle of "
                             f"{math.degrees(steepest):.4g} degrees, beyond the "
                             f"{math.degrees(self.max_corner_angle):.4g} degree stop (R = "
                             f"v/omega too tight); got v={v!r}, omega={w!r}")
        if _overflow(*speeds):
            raise ValueError(f"twist is out of range: the wheel speeds overflow, got {twist!r}")
        u = speeds
        return RoverWheels(u[0], u[1], u[2], u[3], u[4], u[5],
                           angles[0], angles[2], angles[1], angles[3])

    def forward(self, wheels: RoverWheels) -> Twist:
        """The least-squares twist of the six wheels' velocities."""
        w = _wheels(RoverWheels, wheels)
        steer = (w.steer_lf, 0.0, w.steer_lb, w.steer_rf, 0.0, w.steer_rb)
        b: list[float] = []
        for speed, delta in zip(w[:6], steer, strict=True):
            b += [speed * math.cos(delta), speed * math.sin(delta)]
        out = [sum(p * q for p, q in zip(row, b, strict=True)) + 0.0 for row in self._pinv]
        if _overflow(*out):
            raise ValueError(f"wheels is out of range: the twist overflows, got {wheels!r}")
        return _trusted(Twist, out[0], out[1], out[2])

    def desaturate(self, wheels: RoverWheels, max_speed: float) -> RoverWheels:
        """The six speeds scaled by one factor so that none exceeds ``max_speed``; the corner
        angles are kept."""
        w = _wheels(RoverWheels, wheels)
        u = _scale(tuple(w[:6]), self._max_speed(max_speed))
        return w._replace(lf=u[0], lm=u[1], lb=u[2], rf=u[3], rm=u[4], rb=u[5])
