r"""The numerical kernels every public function of the library calls: no validation here.

One SE(2) arc step, one small-angle strategy, one angle wrap, the differential drive's wheel
speeds, one C integer division. Public functions validate
their arguments and call these; inner loops (controllers, the sandbox, panels) call them
directly with values they have already checked.

The small-angle strategy
------------------------
For a turn :math:`\Delta\theta` the arc step needs

.. math:: a(\Delta\theta) = \frac{\sin\Delta\theta}{\Delta\theta}, \qquad
          b(\Delta\theta) = \frac{1-\cos\Delta\theta}{\Delta\theta}
                          = \frac{2\sin^2(\Delta\theta/2)}{\Delta\theta},

both 0/0 at :math:`\Delta\theta = 0`. Below :data:`SERIES_THRESHOLD` they are evaluated from
their Taylor series :math:`a = 1 - \Delta\theta^2/6 + \Delta\theta^4/120`,
:math:`b = \Delta\theta/2 - \Delta\theta^3/24 + \Delta\theta^5/720`, whose truncation errors
there are below :math:`\Delta\theta^6/5040 < 2\cdot 10^{-28}` (relative), far under one unit in
the last place; above it the closed forms are used, with :math:`1-\cos` written as
:math:`2\sin^2(\Delta\theta/2)` so that nothing cancels. Either way both factors are within
:math:`2\varepsilon` (relative; :math:`\varepsilon = 2^{-52}`) of the exact values for every
normal float :math:`\Delta\theta`, on the float and on the array path
(``tests/library/test_kernels.py`` checks this against 50-digit arithmetic; for a subnormal
:math:`\Delta\theta`, :math:`b = \Delta\theta/2` is rounded to the subnormal grid).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["SERIES_THRESHOLD", "arc_factors", "arc_step", "c_div", "desaturate",
           "diff_drive_wheel_speeds", "point_row", "roller_axis", "shift_twist", "wrap_angle"]

_TWO_PI = 2.0 * math.pi

#: Below this turn (rad) the arc factors come from their series (see the module docstring).
SERIES_THRESHOLD: float = 1e-4


def arc_factors(phi: Any) -> tuple[Any, Any]:
    r"""``(sin(phi)/phi, (1 - cos(phi))/phi)`` for a float or an array, exact at ``phi = 0``."""
    if isinstance(phi, float) or isinstance(phi, int):
        p = float(phi)
        if abs(p) < SERIES_THRESHOLD:
            p2 = p * p
            return 1.0 - p2 / 6.0 + p2 * p2 / 120.0, p * (0.5 - p2 / 24.0 + p2 * p2 / 720.0)
        s = math.sin(0.5 * p)
        return math.sin(p) / p, 2.0 * s * s / p
    arr = np.asarray(phi, dtype=float)
    small = np.abs(arr) < SERIES_THRESHOLD
    safe = np.where(small, 1.0, arr)
    p2 = arr * arr
    half_sin = np.sin(0.5 * safe)
    a = np.where(small, 1.0 - p2 / 6.0 + p2 * p2 / 120.0, np.sin(safe) / safe)
    b = np.where(small, arr * (0.5 - p2 / 24.0 + p2 * p2 / 720.0),
                 2.0 * half_sin * half_sin / safe)
    return a, b


def arc_step(x: Any, y: Any, theta: Any, distance: Any, dtheta: Any) -> tuple[Any, Any, Any]:
    r"""The pose after moving ``distance`` along an arc that turns by ``dtheta``.

    .. math::
        x' = x + \Delta s\,(a\cos\theta - b\sin\theta),\quad
        y' = y + \Delta s\,(a\sin\theta + b\cos\theta),\quad
        \theta' = \theta + \Delta\theta

    with :math:`a, b` = :func:`arc_factors` :math:`(\Delta\theta)`: the exact constant-curvature
    step (a straight line when :math:`\Delta\theta = 0`). Floats in, floats out; arrays
    broadcast. The heading is not wrapped.
    """
    a, b = arc_factors(dtheta)
    if isinstance(theta, float) and isinstance(dtheta, (float, int)):
        c, s = math.cos(theta), math.sin(theta)
    else:
        c, s = np.cos(theta), np.sin(theta)
    return (x + distance * (a * c - b * s), y + distance * (a * s + b * c), theta + dtheta)


def point_row(x: float, y: float, dx: float, dy: float) -> tuple[float, float, float]:
    r"""The row :math:`\mathbf d^T P = (d_x,\ d_y,\ x d_y - y d_x)` with
    :math:`\mathbf d^T P\,\xi` the velocity along :math:`\mathbf d` of the body point
    :math:`(x, y)` for the twist :math:`\xi = (v_x, v_y, \omega)`: every wheel constraint row
    (rolling, sliding, roller) is one of these."""
    return dx, dy, x * dy - y * dx


def roller_axis(angle: float, gamma: float) -> tuple[float, float]:
    r"""The ground roller's axis :math:`\mathbf u = (-\sin(\psi+\gamma),\ \cos(\psi+\gamma))`
    of a Swedish wheel rolling along :math:`\psi`: its axle :math:`\mathbf n` turned by
    :math:`\gamma`."""
    a = angle + gamma
    return -math.sin(a), math.cos(a)


def c_div(numerator: int, denominator: int) -> int:
    """C's integer division of two Python ints: the quotient truncated toward zero.

    ``denominator`` must be non-zero (the caller checks). Python's ``//`` floors instead, which
    differs for operands of opposite signs.
    """
    q = abs(numerator) // abs(denominator)
    return q if (numerator >= 0) == (denominator > 0) else -q


def wrap_angle(angle: Any) -> Any:
    r"""An angle (rad) wrapped to :math:`(-\pi, \pi]`; a float for a float, else an array.

    An angle already inside is returned bit for bit (so wrapping is idempotent); :math:`-\pi`
    maps to :math:`\pi`. The input must be finite (the caller checks).
    """
    if isinstance(angle, float | int) and not isinstance(angle, bool):
        a = float(angle)
        if -math.pi < a <= math.pi:
            return a
        r = math.fmod(a + math.pi, _TWO_PI)
        r = (r + _TWO_PI if r < 0.0 else r) - math.pi  # [-pi, pi] after rounding
        if r <= -math.pi:
            r += _TWO_PI
        return min(r, math.pi)
    arr = np.asarray(angle, dtype=float)
    inside = (arr > -math.pi) & (arr <= math.pi)
    wrapped = np.remainder(arr + math.pi, _TWO_PI) - math.pi  # [-pi, pi] after rounding
    wrapped = np.where(wrapped <= -math.pi, wrapped + _TWO_PI, wrapped)
    wrapped = np.minimum(wrapped, math.pi)
    return np.where(inside, arr, wrapped)


def diff_drive_wheel_speeds(v: Any, omega: Any, track_width: Any) -> tuple[Any, Any]:
    r"""Left and right wheel ground speeds :math:`v \mp \omega W/2` of a differential drive."""
    half = 0.5 * track_width
    return v - omega * half, v + omega * half


def desaturate(speeds: Any, limit: float) -> np.ndarray:
    r"""Wheel speeds (..., n) scaled together, row by row, so that none exceeds ``limit`` in
    size: :math:`s_i \cdot \min(1, \text{limit}/\max_j |s_j|)` (WPILib's
    ``desaturateWheelSpeeds``). A row within the limit is returned unchanged."""
    arr = np.asarray(speeds, dtype=float)
    biggest = np.max(np.abs(arr), axis=-1, keepdims=True)
    over = biggest > limit
    scale = np.where(over, limit / np.where(over, biggest, 1.0), 1.0)
    return np.where(over, arr * scale, arr)


def shift_twist(vx: Any, vy: Any, omega: Any, cx: Any, cy: Any) -> tuple[Any, Any, Any]:
    r"""The twist of the body-frame origin, given the velocity :math:`(v_x, v_y)` of the point
    :math:`c` and the yaw rate: :math:`v_o = v_c + \omega \times (0 - c) =
    (v_x + \omega c_y,\; v_y - \omega c_x)`."""
    return vx + omega * cy, vy - omega * cx, omega
