"""Wheel encoders (quantised, cumulative counts of each wheel's rotation, optionally noisy)
and a rate gyro (the body's yaw rate, with a bias and white noise).

An incremental encoder with ``steps_per_rev`` counts per wheel revolution reports, after the
wheel has turned by the (unwrapped, cumulative) angle phi since the start,

    count = floor(phi * steps_per_rev / (2 pi) + 1/2 + e_k),

that is the travel rounded to the nearest count: the wheel starts in the middle of a count, so
without noise a reading is within half a count of the true travel, and the count changes each
time the wheel passes an edge, in either direction. ``e_k`` is the optional noise: independent
N(0, sigma^2) counts per wheel and per simulation step (a jitter of the edges' positions, which
does not accumulate). It is drawn from ``numpy.random.default_rng(seed)`` in fixed blocks of
steps, so the reading at step k is the same whenever and however often it is read.

With ``steps_per_rev=None`` the encoder is ideal: the "count" is the wheel angle in radians,
unquantised and noise-free.

Convert counts to travel with :meth:`Encoder.angles` (rad) and multiply by the wheel radius.

A :class:`Gyro` reads the body's true yaw rate, which slipping wheels do not corrupt, plus a
constant bias and white noise of a given density; :meth:`Gyro.turns` integrates it over the
intervals of a recorded run, as a robot's firmware does between two odometry updates.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from wheelkin import _validate as V

__all__ = ["Encoder", "Gyro"]

_BLOCK = 4096
#: Counts per revolution an encoder may have (an ideal one aside), and the largest noise, counts.
STEPS_PER_REV_RANGE = (1.0, 1e9)
MAX_NOISE = 1e6
#: The largest reading: counts stay exact integers of int64 (and of a float) below it.
MAX_COUNT = 2.0**52


def _integer(name: str, value, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < low:
        raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    return int(value)


class Encoder:
    """Encoders of ``n`` wheels.

    Parameters
    ----------
    n : int
        Number of wheels (>= 1).
    steps_per_rev : float or None
        Counts per wheel revolution, in [1, 1e9]; None = ideal (angle in rad).
    noise : float
        Standard deviation of the edge jitter, counts (in [0, 1e6]; 0 for an ideal encoder).
    seed : int
        Seed of the noise generator (>= 0).

    Readings stay below 2**52 counts in magnitude (``ValueError`` naming ``angles`` beyond:
    an integer count would no longer be exact).

    Examples
    --------
    >>> enc = Encoder(2, steps_per_rev=100)
    >>> enc.counts([2 * math.pi, -0.01], step=0).tolist()   # one turn; a hair backwards
    [100, 0]
    >>> enc.counts([0.2 * math.pi, -0.1 * math.pi], step=0).tolist()
    [10, -5]
    """

    def __init__(self, n: int, steps_per_rev: float | None, noise: float = 0.0,
                 seed: int = 0) -> None:
        self.n = _integer("n", n, 1)
        self.steps_per_rev = None if steps_per_rev is None else V.in_range(
            "steps_per_rev", steps_per_rev, *STEPS_PER_REV_RANGE)
        self.noise = V.in_range("noise", noise, 0.0, MAX_NOISE)
        if self.steps_per_rev is None and self.noise > 0:
            raise ValueError("noise (a VehicleSpec's encoder_noise) must be 0 when "
                             "steps_per_rev is None (ideal encoder)")
        self._rng = np.random.default_rng(_integer("seed", seed, 0))
        self._blocks: list[np.ndarray] = []

    @property
    def quantised(self) -> bool:
        """True unless the encoder is ideal."""
        return self.steps_per_rev is not None

    def _noise(self, steps: np.ndarray) -> np.ndarray:
        steps = np.asarray(steps, dtype=np.int64)
        need = int(steps.max()) // _BLOCK + 1 if steps.size else 0
        while len(self._blocks) < need:
            self._blocks.append(self._rng.normal(0.0, self.noise, size=(_BLOCK, self.n)))
        table = np.concatenate(self._blocks[:need]) if need else np.zeros((0, self.n))
        return table[steps]

    def _wheels(self, name: str, value) -> np.ndarray:
        arr = V.shaped(name, value, (self.n,))
        scale = 1.0 if self.steps_per_rev is None else self.steps_per_rev / (2 * math.pi)
        if np.any(np.abs(arr) * scale > MAX_COUNT):
            raise ValueError(f"{name} must stay within {MAX_COUNT:g} counts "
                             f"({MAX_COUNT / scale:g} rad) of zero")
        return arr

    def counts(self, angles: ArrayLike, step: ArrayLike) -> np.ndarray:
        """Readings for wheel ``angles`` (rad, shape (..., n)) at simulation ``step`` (an int
        >= 0, or one per reading: shape ``angles.shape[:-1]``)."""
        a = self._wheels("angles", angles)
        s = np.asarray(step)
        if s.dtype == bool or s.dtype.kind not in "iu" or np.any(s < 0):
            raise ValueError(f"step must be an integer >= 0 (or an array of them), got {step!r}")
        if s.shape not in ((), a.shape[:-1]):
            raise ValueError(f"step must be one integer or have shape {a.shape[:-1]} "
                             f"(angles' readings), got shape {s.shape}")
        if not self.quantised:
            return a.copy()
        x = a * (self.steps_per_rev / (2 * math.pi)) + 0.5
        if self.noise > 0:
            x = x + self._noise(np.broadcast_to(s, a.shape[:-1]))
        return np.floor(x).astype(np.int64)

    def angles(self, counts: ArrayLike) -> np.ndarray:
        """The wheel angles (rad) that readings ``counts`` (shape (..., n)) stand for."""
        c = V.shaped("counts", counts, (self.n,))
        if np.any(np.abs(c) > MAX_COUNT):
            raise ValueError(f"counts must be within {MAX_COUNT:g} of zero")
        if not self.quantised:
            return c
        return c * (2 * math.pi / self.steps_per_rev)


#: The largest gyro noise density (rad/s/sqrt(Hz)) and bias (rad/s) accepted.
MAX_GYRO_NOISE = 10.0
MAX_GYRO_BIAS = 100.0


class Gyro:
    r"""A rate gyro about the vertical axis, integrated over intervals.

    Over an interval of :math:`\Delta t` seconds in which the body's heading changed by
    :math:`\Delta\theta`, the integrated reading is

    .. math:: z = \Delta\theta + b\,\Delta t + n,\qquad n \sim \mathcal N(0,\ \sigma_g^2\,\Delta t):

    white rate noise of density :math:`\sigma_g` (rad/s/√Hz) integrates to a random walk whose
    variance grows with the time (:meth:`variance`), and a bias :math:`b` (rad/s, what is left
    after the calibration at rest) adds a drift. The body's turn comes from the true heading, so
    the gyro sees the robot's rotation whether its wheels grip or slip.

    Parameters
    ----------
    noise_density : float
        :math:`\sigma_g`, rad/s/√Hz (in [0, 10]).
    bias : float
        :math:`b`, rad/s (within +-100).
    seed : int
        Seed of the noise (>= 0): every call of :meth:`turns` draws the same noise.

    Examples
    --------
    >>> gyro = Gyro(noise_density=0.0, bias=0.01)
    >>> gyro.turns([0.0, 1.0, 3.0], [0.0, 0.5, 0.5]).tolist()
    [0.51, 0.02]
    """

    def __init__(self, noise_density: float = 0.0, bias: float = 0.0, seed: int = 0) -> None:
        self.noise_density = V.in_range("noise_density", noise_density, 0.0, MAX_GYRO_NOISE)
        self.bias = V.in_range("bias", bias, -MAX_GYRO_BIAS, MAX_GYRO_BIAS)
        self.seed = _integer("seed", seed, 0)

    def variance(self, interval: float) -> float:
        r"""The variance of one integrated reading over ``interval`` seconds, rad²:
        :math:`\sigma_g^2\,\Delta t` (the bias is not noise: it is the same every time)."""
        dt = V.positive("interval", interval)
        if dt > 1e6:
            raise ValueError(f"interval must be at most 1e6 s, got {interval!r}")
        return self.noise_density**2 * dt

    def turns(self, t: ArrayLike, heading: ArrayLike) -> np.ndarray:
        """The integrated readings between consecutive times ``t`` (s, increasing, shape (N,))
        of a run whose true, unwrapped ``heading`` (rad, shape (N,)) is recorded: shape
        (N - 1,), rad."""
        times = V.finite_array("t", t)
        theta = V.finite_array("heading", heading)
        if times.ndim != 1 or times.size < 2 or np.any(np.diff(times) <= 0):
            raise ValueError("t must be a 1-D array of at least two increasing times, s")
        if np.max(np.abs(times)) > 1e9:
            raise ValueError("t must be within +-1e9 s")
        if theta.shape != times.shape:
            raise ValueError(f"heading must have the shape of t {times.shape}, got "
                             f"{theta.shape}")
        if np.max(np.abs(theta)) > 1e9:
            raise ValueError("heading must be within +-1e9 rad")
        dt = np.diff(times)
        noise = np.random.default_rng(self.seed).standard_normal(dt.size)
        return np.diff(theta) + self.bias * dt + self.noise_density * np.sqrt(dt) * noise
