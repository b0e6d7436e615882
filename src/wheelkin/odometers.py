r"""Odometry objects a control loop holds: the pose from wheel distances, update by update.

One object per vehicle, one interface (WPILib's ``DifferentialDriveOdometry`` is the model):

- ``update(*wheel_distances, heading=None)`` takes the wheels' **cumulative** distances since
  the last :meth:`~Odometry.reset` (m; or encoder counts, when the object was built with
  ``distance_per_count``), moves the pose by the exact arc of the increments (the library's
  arc kernel: :func:`wheelkin._kernels.arc_step`, exact when the wheels turn in a constant
  ratio within an update) and returns the new :class:`~wheelkin.frames.Pose`;
- an optional ``heading`` (rad, a gyro's, counter-clockwise positive and unwrapped) overrides
  the heading the wheels give, as WPILib does: the gyro's change is the update's turn, and
  the pose's heading is the gyro's plus the offset fixed at :meth:`~Odometry.reset`;
- ``reset(pose, distances, heading=None)`` starts again from ``pose``;
- ``pose``, ``twist`` (the last update's motion as a twist per update, as WPILib's
  ``Twist2d``: the distance along the arc, sideways, and the turn, in m, m, rad; its
  :func:`~wheelkin.frames.se2_exp` is the update's displacement; divide by the update's period
  for a velocity) and ``covariance``.

With ``wheel_noise`` (the variance of a wheel's distance error per metre rolled, m, the error
model of the odometry chapter's "How sure is the pose?") each update also propagates the
pose's 3 x 3 covariance to first order, with the exact-arc Jacobians of
:func:`wheelkin.odometry_uncertainty.propagate_covariance` (the differential drive's is that
step exactly; the mecanum base and the car use the same arc with their own wheel-to-body map).

The per-call path runs on plain floats and checks each distance cheaply (a finite number; a
string or a boolean is a ``TypeError``). A heading in a returned pose is never wrapped (the
library's rule): it is the start heading plus every turn since.

>>> odo = DiffDriveOdometry(DiffDriveKinematics(track_width=0.5))
>>> odo.update(0.1, 0.1)
Pose(x=0.1, y=0.0, theta=0.0)
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from wheelkin import _validate as V
from wheelkin._kernels import SERIES_THRESHOLD
from wheelkin._records import _trusted
from wheelkin._validate import InputTypeError
from wheelkin.frames import Pose, Twist
from wheelkin.kinematics import AckermannKinematics, DiffDriveKinematics, MecanumKinematics

__all__ = [
    "AckermannOdometry",
    "DiffDriveOdometry",
    "MecanumOdometry",
    "Odometry",
]

_ORIGIN = Pose(0.0, 0.0, 0.0)


def _arc_derivatives(phi: float, a: float, b: float) -> tuple[float, float]:
    r""":math:`a'(\varphi)` and :math:`b'(\varphi)` of the arc factors
    :math:`a = \sin\varphi/\varphi`, :math:`b = (1-\cos\varphi)/\varphi`, on floats (their
    series below the arc kernel's threshold)."""
    if -SERIES_THRESHOLD < phi < SERIES_THRESHOLD:
        p2 = phi * phi
        return phi * (-1.0 / 3.0 + p2 / 30.0), 0.5 - p2 / 8.0 + p2 * p2 / 144.0
    return (math.cos(phi) - a) / phi, a - b / phi


class Odometry(ABC):
    r"""What every odometry object holds and answers (see the module docstring).

    A subclass says how many wheel distances it takes (``_names``) and turns their increments
    into the body's motion (``_body``: :math:`(\\Delta x_b, \\Delta y_b, \\Delta\\theta)`
    before the arc, and the 3 x n matrix of their derivatives by the increments).
    """

    _names: tuple[str, ...]

    def __init__(self, pose: Pose, distances: Sequence[float] | None, heading: float | None,
                 distance_per_count: float | None, wheel_noise: float | Sequence[float] | None,
                 covariance: NDArray[np.float64] | Sequence[Sequence[float]] | None) -> None:
        n = len(self._names)
        self._scale = (1.0 if distance_per_count is None
                       else V.positive("distance_per_count", distance_per_count))
        if wheel_noise is None:
            self._noise: tuple[float, ...] | None = None
        elif isinstance(wheel_noise, Sequence) and not isinstance(wheel_noise, str):
            if len(wheel_noise) != n:
                raise ValueError(f"wheel_noise must be one number or {n} (one per wheel: "
                                 f"{', '.join(self._names)}), got {wheel_noise!r}")
            self._noise = tuple(V.nonnegative("wheel_noise", k) for k in wheel_noise)
        else:
            self._noise = (V.nonnegative("wheel_noise", wheel_noise),) * n
        self._track = self._noise is not None or covariance is not None
        self.reset(pose, distances, heading=heading, covariance=covariance)

    def reset(self, pose: Pose = _ORIGIN, distances: Sequence[float] | None = None, *,
              heading: float | None = None,
              covariance: NDArray[np.float64] | Sequence[Sequence[float]] | None = None
              ) -> None:
        """Start again from ``pose`` with the wheels at ``distances`` (default all zero), the
        gyro (if any) reading ``heading``, and the pose's ``covariance`` (default zero where
        the object tracks one)."""
        if not isinstance(pose, Pose):
            pose = Pose.from_array(V.pose("pose", pose))
        n = len(self._names)
        if distances is None:
            last = (0.0,) * n
        else:
            if isinstance(distances, str) or len(distances) != n:
                raise ValueError(f"distances must be {n} numbers ({', '.join(self._names)}), "
                                 f"got {distances!r}")
            last = tuple(V.real(name, d) * self._scale
                         for name, d in zip(self._names, distances, strict=True))
        self._last = last
        self._x, self._y, self._theta = pose
        self._offset = None if heading is None else pose.theta - V.real("heading", heading)
        self._twist = Twist(0.0, 0.0, 0.0)
        if covariance is not None:
            from wheelkin.odometry_uncertainty import _covariance  # the one checker

            c = _covariance(covariance)
            self._track = True
        else:
            c = np.zeros((3, 3))
        self._cov = (float(c[0, 0]), float(c[0, 1]), float(c[0, 2]), float(c[1, 1]),
                     float(c[1, 2]), float(c[2, 2]))

    @property
    def pose(self) -> Pose:
        """The pose now (m, m, rad; the heading not wrapped)."""
        return Pose(self._x, self._y, self._theta)

    @property
    def twist(self) -> Twist:
        r"""The last update's body-frame motion :math:`(\\Delta x, \\Delta y, \\Delta\\theta)`
        per update (m, m, rad), WPILib's ``Twist2d``."""
        return self._twist

    @property
    def covariance(self) -> NDArray[np.float64] | None:
        """The pose's 3 x 3 covariance over (x, y, theta), or None when the object was built
        without ``wheel_noise`` and ``covariance``."""
        if not self._track:
            return None
        s00, s01, s02, s11, s12, s22 = self._cov
        return np.array([[s00, s01, s02], [s01, s11, s12], [s02, s12, s22]])

    @abstractmethod
    def update_wheels(self, distances: Sequence[float], *,
                      heading: float | None = None) -> Pose:
        """``update`` with the measurements as one sequence, in the order of the vehicle's
        ``update`` (the one call a filter makes for any vehicle)."""

    def _measurements(self, distances: Sequence[float]) -> tuple[float, ...]:
        n = len(self._names)
        if isinstance(distances, str) or not isinstance(distances, Sequence | np.ndarray) \
                or len(distances) != n:
            raise ValueError(f"distances must be {n} numbers ({', '.join(self._names)}), "
                             f"got {distances!r}")
        return tuple(distances)

    def _reading(self, name: str, value: float) -> float:
        """One measurement in metres (the cheap check; counts times the scale)."""
        if type(value) is not float or value - value != 0.0:
            value = V.real(name, value)
        return value * self._scale

    def _advance(self, a: float, b: float, phi: float, heading: float | None,
                 inputs: Sequence[tuple[float, float, float]],
                 increments: Sequence[float]) -> Pose:
        """Move the pose by the body motion ``(a, b, phi)`` along the arc; ``inputs`` are the
        columns of d(a, b, phi)/d(measurements), ``increments`` the measurements' changes."""
        theta = self._theta
        if heading is None:
            new_theta = theta + phi
        else:
            if self._offset is None:
                raise ValueError("heading: give the gyro's heading at construction or reset "
                                 "too (the offset between the gyro and the pose is fixed "
                                 "there)")
            if type(heading) is not float or heading - heading != 0.0:
                heading = V.real("heading", heading)
            new_theta = heading + self._offset
            phi = new_theta - theta
        if a - a != 0.0 or b - b != 0.0 or phi - phi != 0.0:
            raise ValueError(f"{', '.join(self._names)} are out of range: the motion "
                             "overflows")
        if -SERIES_THRESHOLD < phi < SERIES_THRESHOLD:  # the arc kernel's two factors
            p2 = phi * phi
            ca = 1.0 - p2 / 6.0 + p2 * p2 / 120.0
            cb = phi * (0.5 - p2 / 24.0 + p2 * p2 / 720.0)
        else:
            half = math.sin(0.5 * phi)
            ca = math.sin(phi) / phi
            cb = 2.0 * half * half / phi
        bx, by = ca * a - cb * b, cb * a + ca * b  # body-frame displacement
        c, s = math.cos(theta), math.sin(theta)
        dx, dy = c * bx - s * by, s * bx + c * by
        x, y = self._x + dx, self._y + dy
        if x - x != 0.0 or y - y != 0.0 or new_theta - new_theta != 0.0 \
                or bx - bx != 0.0 or by - by != 0.0:
            raise ValueError(f"{', '.join(self._names)} are out of range: the pose overflows")
        self._x, self._y, self._theta = x, y, new_theta
        self._twist = _trusted(Twist, a, b, phi)
        if self._track:
            self._propagate(dx, dy, c, s, a, b, phi, ca, cb, inputs, increments)
        return _trusted(Pose, x, y, new_theta)

    def _propagate(self, dx: float, dy: float, c: float, s: float, a: float, b: float,
                   phi: float, ca: float, cb: float,
                   inputs: Sequence[tuple[float, float, float]],
                   increments: Sequence[float]) -> None:
        r""":math:`\Sigma' = F_p \Sigma F_p^T + \sum_k q_k g_k g_k^T` with
        :math:`F_p = I + (-\Delta y, \Delta x, 0)\,e_\theta^T`, :math:`q_k = k_k|\Delta_k|`
        and :math:`g_k` the arc's Jacobian times the k-th measurement's column."""
        s00, s01, s02, s11, s12, s22 = self._cov
        e0, e1 = -dy, dx
        n00 = s00 + 2.0 * e0 * s02 + s22 * e0 * e0
        n01 = s01 + e0 * s12 + e1 * s02 + s22 * e0 * e1
        n02 = s02 + e0 * s22
        n11 = s11 + 2.0 * e1 * s12 + s22 * e1 * e1
        n12 = s12 + e1 * s22
        n22 = s22
        if self._noise is not None:
            da, db = _arc_derivatives(phi, ca, cb)
            # d(world displacement)/d(a, b, phi): the arc rotated into the world
            pa, pb = da * a - db * b, db * a + da * b
            gax, gay = c * ca - s * cb, s * ca + c * cb
            gbx, gby = -c * cb - s * ca, -s * cb + c * ca
            gpx, gpy = c * pa - s * pb, s * pa + c * pb
            for (ua, ub, up), k, inc in zip(inputs, self._noise, increments, strict=True):
                q = k * abs(inc)
                if q == 0.0:
                    continue
                gx = gax * ua + gbx * ub + gpx * up
                gy = gay * ua + gby * ub + gpy * up
                n00 += q * gx * gx
                n01 += q * gx * gy
                n02 += q * gx * up
                n11 += q * gy * gy
                n12 += q * gy * up
                n22 += q * up * up
        self._cov = (n00, n01, n02, n11, n12, n22)


class DiffDriveOdometry(Odometry):
    r"""Odometry of a differential drive from its two wheels' distances.

    .. math::
        \Delta s = \frac{\Delta s_L + \Delta s_R}{2},\quad
        \Delta\theta = \frac{\Delta s_R - \Delta s_L}{W}

    then the exact arc (:func:`wheelkin.odometry.integrate_si`, one update at a time); with
    ``wheel_noise`` :math:`(k_L, k_R)` the covariance step is
    :func:`wheelkin.odometry_uncertainty.propagate_covariance`'s.

    Parameters
    ----------
    kinematics : DiffDriveKinematics
        The vehicle (its track width).
    pose : Pose
        The start pose (default the origin).
    distances : (float, float), optional
        The wheels' distances (or counts) at the start; default zero.
    heading : float, optional
        The gyro's heading at the start (rad); give it to pass ``heading`` to ``update``.
    distance_per_count : float, optional
        Metres per encoder count: ``update`` then takes counts.
    wheel_noise : float or (float, float), optional
        :math:`k` (m): the variance of a wheel's distance error per metre rolled.
    covariance : array_like, shape (3, 3), optional
        The start pose's covariance (default zero when ``wheel_noise`` is given).

    Examples
    --------
    A loop: the encoders count 1000 per metre; the robot drives 1 m, then turns on the spot a
    quarter turn (W = 0.5 m, each wheel 0.3927 m):

    >>> kin = DiffDriveKinematics(track_width=0.5)
    >>> odo = DiffDriveOdometry(kin, distance_per_count=0.001, wheel_noise=1e-6)
    >>> for left, right in [(500, 500), (1000, 1000), (607, 1393)]:
    ...     pose = odo.update(left, right)
    >>> print(f"{pose.x:.4f} {pose.y:.4f} {pose.theta:.4f}")
    1.0000 0.0000 1.5720
    >>> print(f"{math.sqrt(odo.covariance[2, 2]):.5f} rad")
    0.00334 rad

    With a gyro, whose heading overrides the wheels' (the wheels slipped in the turn):

    >>> odo = DiffDriveOdometry(kin, heading=0.0)
    >>> odo.update(0.5, 0.5, heading=0.0).x
    0.5
    >>> odo.update(0.2, 0.8, heading=1.0).theta
    1.0
    """

    _names = ("left", "right")

    def __init__(self, kinematics: DiffDriveKinematics, pose: Pose = _ORIGIN,
                 distances: Sequence[float] | None = None, *, heading: float | None = None,
                 distance_per_count: float | None = None,
                 wheel_noise: float | Sequence[float] | None = None,
                 covariance: NDArray[np.float64] | Sequence[Sequence[float]] | None = None
                 ) -> None:
        if not isinstance(kinematics, DiffDriveKinematics):
            raise InputTypeError(f"kinematics must be a DiffDriveKinematics, got the "
                                 f"{type(kinematics).__name__} {kinematics!r}")
        self.kinematics = kinematics
        self._w = kinematics.track_width
        self._cols = ((0.5, 0.0, -1.0 / self._w), (0.5, 0.0, 1.0 / self._w))
        super().__init__(pose, distances, heading, distance_per_count, wheel_noise,
                         covariance)

    def update_wheels(self, distances: Sequence[float], *,
                      heading: float | None = None) -> Pose:
        """:meth:`update` with ``(left, right)``."""
        left, right = self._measurements(distances)
        return self.update(left, right, heading=heading)

    def update(self, left: float, right: float, *, heading: float | None = None) -> Pose:
        """The pose after the wheels reached the cumulative distances ``left`` and ``right``
        (m, or counts); ``heading`` (rad) is a gyro's, overriding the wheels' turn."""
        left = self._reading("left", left)
        right = self._reading("right", right)
        last_left, last_right = self._last
        self._last = (left, right)
        dl, dr = left - last_left, right - last_right
        return self._advance(0.5 * (dl + dr), 0.0, (dr - dl) / self._w, heading, self._cols,
                             (dl, dr))


class MecanumOdometry(Odometry):
    r"""Odometry of a four-wheel mecanum base from its wheels' rolled distances (FL, FR, RL,
    RR, m: each wheel's angle times its radius).

    The body's motion is the least-squares map of
    :class:`~wheelkin.kinematics.MecanumKinematics` applied to the increments,

    .. math::
        \Delta x_b = \tfrac14(\Delta_{FL} + \Delta_{FR} + \Delta_{RL} + \Delta_{RR}),\quad
        \Delta y_b = \tfrac{\tan\gamma}{4}(-\Delta_{FL} + \Delta_{FR} + \Delta_{RL}
                     - \Delta_{RR}),\quad
        \Delta\theta = \tfrac{1}{4k}(-\Delta_{FL} + \Delta_{FR} - \Delta_{RL} + \Delta_{RR}),

    taken as a constant twist over the update (:func:`wheelkin.frames.se2_exp`: an arc that
    may also slide sideways), as WPILib's ``MecanumDriveOdometry`` does.

    Examples
    --------
    Strafing 0.5 m to the left while turning a quarter turn: the arc of a constant twist.

    >>> from wheelkin.mecanum import MecanumGeometry
    >>> g = MecanumGeometry(half_wheelbase=0.2, half_track=0.15, wheel_radius=0.05)
    >>> kin = MecanumKinematics(g)
    >>> odo = MecanumOdometry(kin)
    >>> step = kin.inverse(Twist(0.0, 0.5, math.pi / 2))  # distances after 1 s
    >>> pose = odo.update(*step)
    >>> print(f"{pose.x:.4f} {pose.y:.4f} {pose.theta:.4f}")
    -0.3183 0.3183 1.5708
    """

    _names = ("fl", "fr", "rl", "rr")

    def __init__(self, kinematics: MecanumKinematics, pose: Pose = _ORIGIN,
                 distances: Sequence[float] | None = None, *, heading: float | None = None,
                 distance_per_count: float | None = None,
                 wheel_noise: float | Sequence[float] | None = None,
                 covariance: NDArray[np.float64] | Sequence[Sequence[float]] | None = None
                 ) -> None:
        if not isinstance(kinematics, MecanumKinematics):
            raise InputTypeError(f"kinematics must be a MecanumKinematics, got the "
                                 f"{type(kinematics).__name__} {kinematics!r}")
        self.kinematics = kinematics
        g = kinematics.geometry
        self._t = 0.25 * math.tan(g.roller_angle)
        self._k = 0.25 / g.k
        t, k = self._t, self._k
        self._cols = ((0.25, -t, -k), (0.25, t, k), (0.25, t, -k), (0.25, -t, k))
        super().__init__(pose, distances, heading, distance_per_count, wheel_noise,
                         covariance)

    def update_wheels(self, distances: Sequence[float], *,
                      heading: float | None = None) -> Pose:
        """:meth:`update` with ``(fl, fr, rl, rr)``."""
        fl, fr, rl, rr = self._measurements(distances)
        return self.update(fl, fr, rl, rr, heading=heading)

    def update(self, fl: float, fr: float, rl: float, rr: float, *,
               heading: float | None = None) -> Pose:
        """The pose after the wheels reached the cumulative distances FL, FR, RL, RR (m, or
        counts); ``heading`` (rad) is a gyro's, overriding the wheels' turn."""
        now = (self._reading("fl", fl), self._reading("fr", fr), self._reading("rl", rl),
               self._reading("rr", rr))
        last = self._last
        self._last = now
        inc = (now[0] - last[0], now[1] - last[1], now[2] - last[2], now[3] - last[3])
        a, b, c, d = inc
        return self._advance(0.25 * (a + b + c + d), self._t * (-a + b + c - d),
                             self._k * (-a + b - c + d), heading, self._cols, inc)


class AckermannOdometry(Odometry):
    r"""Odometry of a car from the rear-axle midpoint's distance and the steering angle.

    Per update, with :math:`\Delta s` the increment of ``distance`` (the mean of the two rear
    wheels' distances) and :math:`\delta` the bicycle model's steering angle during it
    (:func:`wheelkin.carlike.bicycle_twist`: the angle of a front wheel on the centre line,
    between the two real ones):

    .. math:: \Delta\theta = \frac{\Delta s\,\tan\delta}{L}

    then the exact arc (ros2_controllers' ``SteeringOdometry`` uses the same model). The
    noise (``wheel_noise``) is on the distance alone.

    Examples
    --------
    A quarter circle of radius 5 m (L = 2.5 m, so tan δ = 0.5), in 10 updates:

    >>> car = AckermannKinematics(wheelbase=2.5, track_width=1.5)
    >>> odo = AckermannOdometry(car)
    >>> quarter = 5.0 * math.pi / 2
    >>> for k in range(1, 11):
    ...     pose = odo.update(quarter * k / 10, math.atan(0.5))
    >>> print(f"{pose.x:.6f} {pose.y:.6f} {pose.theta:.6f}")
    5.000000 5.000000 1.570796
    """

    _names = ("distance",)

    def __init__(self, kinematics: AckermannKinematics, pose: Pose = _ORIGIN,
                 distance: float | None = None, *, heading: float | None = None,
                 distance_per_count: float | None = None,
                 wheel_noise: float | Sequence[float] | None = None,
                 covariance: NDArray[np.float64] | Sequence[Sequence[float]] | None = None
                 ) -> None:
        if not isinstance(kinematics, AckermannKinematics):
            raise InputTypeError(f"kinematics must be an AckermannKinematics, got the "
                                 f"{type(kinematics).__name__} {kinematics!r}")
        self.kinematics = kinematics
        self._length = kinematics.wheelbase
        self._limit = kinematics.max_steering_angle
        super().__init__(pose, None if distance is None else (distance,), heading,
                         distance_per_count, wheel_noise, covariance)

    def update_wheels(self, distances: Sequence[float], *,
                      heading: float | None = None) -> Pose:
        """:meth:`update` with ``(distance, steering_angle)``."""
        if isinstance(distances, str) or not isinstance(distances, Sequence | np.ndarray) \
                or len(distances) != 2:
            raise ValueError(f"distances must be 2 numbers (distance, steering_angle), got "
                             f"{distances!r}")
        return self.update(distances[0], distances[1], heading=heading)

    def update(self, distance: float, steering_angle: float, *,
               heading: float | None = None) -> Pose:
        """The pose after the rear-axle midpoint reached the cumulative ``distance`` (m, or
        counts) with the bicycle steering angle ``steering_angle`` (rad, positive left);
        ``heading`` (rad) is a gyro's, overriding the model's turn."""
        delta = steering_angle
        if type(delta) is not float or delta - delta != 0.0:
            delta = V.real("steering_angle", steering_angle)
        if not abs(delta) <= self._limit or abs(delta) >= 0.5 * math.pi:
            raise ValueError(f"steering_angle must be within the car's max_steering_angle "
                             f"{self._limit:.6g} rad (and under pi/2), got {steering_angle!r}")
        now = self._reading("distance", distance)
        ds = now - self._last[0]
        self._last = (now,)
        curvature = math.tan(delta) / self._length
        return self._advance(ds, 0.0, ds * curvature, heading, ((1.0, 0.0, curvature),),
                             (ds,))
