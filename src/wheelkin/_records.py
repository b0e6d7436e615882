"""Pose and Twist, and how scalars and arrays are packed into them.

The two records live here, below :mod:`wheelkin.frames` (their public home, which re-exports
them and whose name they carry) and :mod:`wheelkin.sources` (the sources' converters), so that
both can build them without importing each other. The rule the helpers implement: components
given as scalars give a record, any array gives an array of shape ``(..., 3)``; a record given
gives a record back, an array an array.
"""

from __future__ import annotations

import functools
from typing import Any, NamedTuple, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

from wheelkin import _validate as V

__all__: list[str] = []

#: Arguments that give an array back in the overloads of the array-or-scalar functions: an
#: array or a list (a float gives a float, a Pose or a tuple of three numbers a Pose).
Stack: TypeAlias = NDArray[Any] | list[Any]


class Pose(NamedTuple):
    """A planar pose in our world frame: position ``x``, ``y`` (m), heading ``theta`` (rad).

    ``theta`` is counter-clockwise from world +x. It is stored as given (not wrapped); use
    :func:`wrap_angle` where a wrapped heading is meant. A NamedTuple: ``x, y, theta = pose``
    unpacks it, ``pose.x`` names a field, ``np.asarray(pose)`` (or :meth:`as_array`) is the
    array ``[x, y, theta]`` (use the array for arithmetic: ``pose * 2`` repeats a tuple).

    >>> x, y, theta = Pose(1.0, 2.0, 0.5)
    >>> Pose(1.0, 2.0, 0.5).as_array()
    array([1. , 2. , 0.5])
    >>> Pose(1.0, float("nan"), 0.0)
    Traceback (most recent call last):
    ...
    ValueError: y must be a finite number, got nan
    """

    #: m, world +x (east).
    x: float
    #: m, world +y (north).
    y: float
    #: rad, counter-clockwise from world +x (not wrapped).
    theta: float

    def as_array(self) -> np.ndarray:
        """``[x, y, theta]`` as a float array of shape (3,)."""
        return np.array(self, dtype=float)

    @classmethod
    def from_array(cls, values: ArrayLike) -> Pose:
        """A Pose from an array_like ``[x, y, theta]`` of shape (3,)."""
        return cls(*V.pose("pose", values).tolist())


class Twist(NamedTuple):
    """A planar twist in our body frame: ``vx``, ``vy`` (m/s), ``omega`` (rad/s, CCW +).

    A NamedTuple, like :class:`Pose`: ``vx, vy, omega = twist`` unpacks it, and
    ``np.asarray(twist)`` (or :meth:`as_array`) is the array for arithmetic.

    >>> Twist(0.5, 0.0, 0.25).as_array()
    array([0.5 , 0.  , 0.25])
    >>> Twist(0.5, 0.0, float("inf"))
    Traceback (most recent call last):
    ...
    ValueError: omega must be a finite number, got inf
    """

    #: m/s, forward (body +x).
    vx: float
    #: m/s, to the left (body +y).
    vy: float
    #: rad/s, counter-clockwise positive.
    omega: float

    def as_array(self) -> np.ndarray:
        """``[vx, vy, omega]`` as a float array of shape (3,)."""
        return np.array(self, dtype=float)

    @classmethod
    def from_array(cls, values: ArrayLike) -> Twist:
        """A Twist from an array_like ``[vx, vy, omega]`` of shape (3,)."""
        return cls(*V.twist("twist", values).tolist())


def _validating_new(cls: Any) -> None:
    """Make a NamedTuple's constructor check that every field is a finite number, naming the
    field (a NamedTuple may not define ``__new__`` in its body; it is replaced here)."""
    plain_new = cls.__new__
    fields = cls._fields

    @functools.wraps(plain_new)  # the signature (x, y, theta) for help() and the docs
    def __new__(klass, *args: float, **kwargs: float):
        values = plain_new(klass, *args, **kwargs)
        return plain_new(klass, *(V.finite(n, x) for n, x in zip(fields, values, strict=True)))

    def _replace(self, **changes: float):  # checked too (the generated one is not)
        return type(self)(**(self._asdict() | changes))

    cls.__new__ = __new__
    cls._replace = _replace
    cls._make = classmethod(lambda klass, iterable: klass(*iterable))
    cls.validates = True  # marks a record the bad-input sweep calls, not only reads


_validating_new(Pose)
_validating_new(Twist)
# Their public home is wheelkin.frames (the API reference, pickles, reprs of the class name).
Pose.__module__ = Twist.__module__ = "wheelkin.frames"


def _components(names: tuple[str, ...], values: tuple, *, allow_inf: bool = False):
    """Validate components; return (list of arrays broadcast together, all_scalar)."""
    arrays = [V.finite_array(n, x, allow_inf=allow_inf) for n, x in zip(names, values,
                                                                        strict=True)]
    scalar = all(a.ndim == 0 for a in arrays)
    try:
        arrays = list(np.broadcast_arrays(*arrays))
    except ValueError:
        shapes = ", ".join(f"{n}: {a.shape}" for n, a in zip(names, arrays, strict=True))
        raise ValueError(f"{', '.join(names)} must have the same shape, got {shapes}") from None
    return arrays, scalar


def _pack(cls, columns, scalar: bool):
    if scalar:
        return cls(*(float(c) for c in columns))
    return np.stack([np.asarray(c, dtype=float) for c in columns], axis=-1)


def _is_one(value: object, cls: type) -> bool:
    """Whether ``value`` is one record of ``cls``: an instance, or a plain ``tuple`` of three
    numbers (``(x, y, theta)`` given where a pose is meant gives a Pose back). A list or an
    array of shape (3,) is an array and gives an array; another record is neither."""
    if isinstance(value, cls):
        return True
    return (type(value) is tuple and len(value) == 3
            and all(isinstance(c, int | float | np.integer | np.floating)
                    and not isinstance(c, bool | np.bool_) for c in value))


def _unpack(name: str, value, cls):
    """(columns, is_record) from a Pose/Twist (or a tuple of three numbers) or an array
    (..., 3)."""
    if isinstance(value, cls):
        return list(value.as_array()), True
    if isinstance(value, Pose | Twist):
        raise ValueError(f"{name} must be a {cls.__name__} or an array of shape (..., 3), "
                         f"got a {type(value).__name__}")
    arr = V.shaped(name, value, (3,))
    return [arr[..., 0], arr[..., 1], arr[..., 2]], _is_one(value, cls)


def _unpack_out(columns, is_record: bool, cls):
    if is_record:
        return cls(*(float(c) for c in columns))
    return np.stack(columns, axis=-1)


def _trusted(cls, x: float, y: float, z: float):
    """A Pose or Twist of three floats the caller has already checked to be finite (the loop
    objects' per-call path: skips the constructor's re-check)."""
    return tuple.__new__(cls, (x, y, z))


def _no_negative_zero(a):
    return a + 0.0

