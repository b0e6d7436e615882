"""Wheel encoders: quantised, cumulative counts of each wheel's rotation, optionally noisy.

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
"""

from __future__ import annotations

import math

import numpy as np

from wheelkin import _validate as V

__all__ = ["Encoder"]

_BLOCK = 4096


class Encoder:
    """Encoders of ``n`` wheels.

    Parameters
    ----------
    n : int
        Number of wheels.
    steps_per_rev : float or None
        Counts per wheel revolution; None = ideal (angle in rad).
    noise : float
        Standard deviation of the edge jitter, counts.
    seed : int
        Seed of the noise generator.

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
        self.n = int(n)
        self.steps_per_rev = None if steps_per_rev is None else V.positive("steps_per_rev",
                                                                          steps_per_rev)
        self.noise = V.nonnegative("encoder_noise", noise)
        if self.steps_per_rev is None and self.noise > 0:
            raise ValueError("encoder_noise must be 0 when steps_per_rev is None (ideal encoder)")
        self._rng = np.random.default_rng(seed)
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

    def counts(self, angles, step) -> np.ndarray:
        """Readings for wheel ``angles`` (rad, shape (..., n)) at simulation ``step`` (int(s))."""
        a = np.asarray(angles, dtype=float)
        if not self.quantised:
            return a.copy()
        x = a * (self.steps_per_rev / (2 * math.pi)) + 0.5
        if self.noise > 0:
            x = x + self._noise(np.asarray(step))
        return np.floor(x).astype(np.int64)

    def angles(self, counts) -> np.ndarray:
        """The wheel angles (rad) that readings ``counts`` stand for."""
        c = np.asarray(counts, dtype=float)
        if not self.quantised:
            return c
        return c * (2 * math.pi / self.steps_per_rev)
