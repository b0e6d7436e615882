"""Input validation at the library's public boundary.

Every public function checks its inputs with these helpers, so that bad input is met with a
``ValueError`` that names the parameter and the accepted range, never with a NaN result, a
silent clamp, or a traceback from deep inside numpy.

>>> finite_array("speed", [1.0, 2.0])
array([1., 2.])
>>> positive("wheel_radius", -0.1)
Traceback (most recent call last):
...
ValueError: wheel_radius must be a finite number > 0, got -0.1
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence
from typing import Any

import numpy as np

#: The smallest positive normal float: a divisor below it makes 1/x overflow.
_SMALLEST_NORMAL = float(np.finfo(float).tiny)

__all__ = [
    "InputTypeError",
    "choice",
    "finite",
    "finite_array",
    "finite_result",
    "in_range",
    "nonnegative",
    "pose",
    "positive",
    "real",
    "shaped",
    "twist",
]


class InputTypeError(TypeError, ValueError):
    """A value of the wrong type: a string, ``None``, a boolean or an object where a number is
    meant. A ``TypeError``, and a ``ValueError`` too, so that code that catches the library's
    ``ValueError`` for bad input catches this as well.

    >>> finite("speed", "1")
    Traceback (most recent call last):
    ...
    wheelkin._validate.InputTypeError: speed must be a real number, got the str '1'
    """


def _type_error(name: str, value: Any, what: str = "a real number") -> InputTypeError:
    return InputTypeError(f"{name} must be {what}, got the {type(value).__name__} {value!r}")


def real(name: str, value: Any) -> float:
    """The cheap check of a loop's per-call path: ``value`` as a float, finite.

    A Python float passes with one comparison (``x - x == 0`` is false for NaN and the
    infinities); an int or a NumPy real scalar is converted; anything else (a string, even
    ``"1"``, a boolean, ``None``) is an :class:`InputTypeError`.

    >>> real("left", 2)
    2.0
    >>> real("left", float("inf"))
    Traceback (most recent call last):
    ...
    ValueError: left must be a finite number, got inf
    """
    if type(value) is float:
        if value - value == 0.0:
            return value
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return finite(name, value)


def finite(name: str, value: Any) -> float:
    """``value`` as a float; ``ValueError`` unless it is a finite real number, and an
    :class:`InputTypeError` (a ``TypeError``) when it is not a number at all: a string (even
    a numeric one: ``"1"`` is not coerced), a boolean, ``None``."""
    if isinstance(value, bool | np.bool_):
        raise _type_error(name, value, "a finite number (not a boolean)")
    if isinstance(value, numbers.Real):
        x = float(value)
    elif isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf":
        x = float(value)
    else:
        raise _type_error(name, value)
    if not math.isfinite(x):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return x


def positive(name: str, value) -> float:
    """``value`` as a float; ``ValueError`` unless finite and > 0."""
    try:
        x = finite(name, value)
    except InputTypeError:
        raise
    except ValueError:
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}") from None
    if x <= 0:
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    if x < _SMALLEST_NORMAL:  # 1/x would overflow
        raise ValueError(f"{name} must be a finite number > 0 and at least "
                         f"{_SMALLEST_NORMAL:g} (not subnormal), got {value!r}")
    return x


def nonnegative(name: str, value) -> float:
    """``value`` as a float; ``ValueError`` unless finite and >= 0."""
    try:
        x = finite(name, value)
    except InputTypeError:
        raise
    except ValueError:
        raise ValueError(f"{name} must be a finite number >= 0, got {value!r}") from None
    if x < 0:
        raise ValueError(f"{name} must be a finite number >= 0, got {value!r}")
    return x


def in_range(name: str, value, low: float, high: float, *, inclusive: bool = True) -> float:
    """``value`` as a float; ``ValueError`` unless finite and within [low, high]."""
    x = finite(name, value)
    ok = low <= x <= high if inclusive else low < x < high
    if not ok:
        br = "[]" if inclusive else "()"
        raise ValueError(f"{name} must be in {br[0]}{low:g}, {high:g}{br[1]}, got {value!r}")
    return x


def _is_boolean(value) -> bool:
    if isinstance(value, bool | np.bool_):
        return True
    if isinstance(value, np.ndarray):
        return value.dtype == bool
    if isinstance(value, list | tuple) and value:
        return any(_is_boolean(item) for item in value)
    return False


def finite_array(name: str, value: Any, *, allow_inf: bool = False) -> np.ndarray:
    """``value`` as a float array; ``ValueError`` if it holds NaN (or inf) or is ragged, and
    :class:`InputTypeError` if it is not numeric: booleans are not numbers here (a flag is
    never a length), and strings are refused, not coerced (``["1", "2"]`` is not a length)."""
    if _is_boolean(value):
        raise _type_error(name, value, "numeric (not a boolean)")
    if isinstance(value, str | bytes):
        raise _type_error(name, value, "numeric")
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numeric, got {value!r}") from None
    kind = raw.dtype.kind
    if kind in "USVMm" or (kind == "O" and any(
            isinstance(v, str | bytes) or v is None for v in raw.flat)):
        raise _type_error(name, value, "numeric")
    if kind in "c":
        raise _type_error(name, value, "real (not complex)")
    try:
        arr = raw.astype(float, copy=False)
    except (TypeError, ValueError):
        raise _type_error(name, value, "numeric") from None
    bad = np.isnan(arr) if allow_inf else ~np.isfinite(arr)
    if np.any(bad):
        what = "NaN" if allow_inf else "NaN or infinity"
        raise ValueError(f"{name} must not contain {what}, got {value!r}")
    return arr


def shaped(name: str, value, trailing: Sequence[int], *, allow_inf: bool = False) -> np.ndarray:
    """A finite float array whose last dimensions are ``trailing`` (any leading batch shape).

    >>> shaped("twist", [1, 2, 3], (3,)).shape
    (3,)
    >>> shaped("twist", [1, 2], (3,))
    Traceback (most recent call last):
    ...
    ValueError: twist must have shape (..., 3), got shape (2,)
    """
    arr = finite_array(name, value, allow_inf=allow_inf)
    k = len(trailing)
    if arr.ndim < k or tuple(arr.shape[arr.ndim - k:]) != tuple(trailing):
        want = ", ".join(str(t) for t in trailing)
        raise ValueError(f"{name} must have shape (..., {want}), got shape {arr.shape}")
    return arr


def pose(name: str, value) -> np.ndarray:
    """One pose ``(x, y, theta)`` (a :class:`~wheelkin.frames.Pose` or an array_like of shape
    (3,)) as a finite float array of shape (3,); a stack of poses is refused (use
    :func:`shaped` with ``(3,)`` where one is meant). The one message for a pose's shape.

    >>> pose("pose", (1, 2, 0.5))
    array([1. , 2. , 0.5])
    >>> pose("goal", [[0, 0, 0]])
    Traceback (most recent call last):
    ...
    ValueError: goal must have shape (3,): one pose (x, y, theta), got shape (1, 3)
    """
    return _one_of_three(name, value, "pose (x, y, theta)")


def twist(name: str, value) -> np.ndarray:
    """One twist ``(vx, vy, omega)`` (a :class:`~wheelkin.frames.Twist` or an array_like of
    shape (3,)) as a finite float array of shape (3,). The one message for a twist's shape.

    >>> twist("twist", [0.5, 0.0])
    Traceback (most recent call last):
    ...
    ValueError: twist must have shape (3,): one twist (vx, vy, omega), got shape (2,)
    """
    return _one_of_three(name, value, "twist (vx, vy, omega)")


def _one_of_three(name: str, value, what: str) -> np.ndarray:
    arr = finite_array(name, value)
    if arr.shape != (3,):
        raise ValueError(f"{name} must have shape (3,): one {what}, got shape {arr.shape}")
    return arr


def finite_result(names: str, *values):
    """``ValueError`` naming ``names`` (the inputs that set the scale) unless every value is
    finite: a result that overflowed to infinity or became NaN never leaves the library.

    Compute the values under ``np.errstate(all="ignore")`` and call this on them.

    >>> finite_result("dt", np.array([1.0, np.inf]))
    Traceback (most recent call last):
    ...
    ValueError: dt is out of range: the result overflows (not a finite number)
    """
    for value in values:
        if not np.all(np.isfinite(np.asarray(value, dtype=float))):
            raise ValueError(f"{names} is out of range: the result overflows (not a finite "
                             "number)")
    return values[0] if len(values) == 1 else values


def choice(name: str, value, options: Sequence[str]) -> str:
    """``value`` if it is one of ``options``; ``ValueError`` listing them otherwise."""
    if not isinstance(value, str) or value not in options:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, options))}; got {value!r}")
    return value


def broadcast(**arrays: Any) -> list[np.ndarray]:
    """The arrays (already validated) broadcast together; ``ValueError`` naming them and their
    shapes when they do not broadcast (never numpy's bare "shape mismatch").

    >>> broadcast(x=np.zeros(2), y=np.zeros(3))
    Traceback (most recent call last):
    ...
    ValueError: x and y must have shapes that broadcast together, got x (2,), y (3,)
    """
    try:
        return list(np.broadcast_arrays(*(np.asarray(a) for a in arrays.values())))
    except ValueError:
        shapes = ", ".join(f"{name} {np.shape(a)}" for name, a in arrays.items())
        raise ValueError(f"{' and '.join(arrays)} must have shapes that broadcast together, "
                         f"got {shapes}") from None


def scalar_or_array(value: Any) -> Any:
    """One quantity as the library returns it: a Python ``float`` for a 0-d result, the array
    otherwise (never a 0-d array or a NumPy scalar).

    >>> scalar_or_array(np.float64(2.5)), scalar_or_array(np.array([1.0]))
    (2.5, array([1.]))
    """
    arr = np.asarray(value, dtype=float)
    return float(arr) if arr.ndim == 0 else arr
