"""Data that crosses a sandbox's wall: inputs in, answers out, as JSON only.

Nothing the grader reads back from a sandbox is ever unpickled or evaluated: the student's
answers come back as JSON (numbers, shapes, short strings) and are checked for type and size
before anything uses them. The inputs of the cases go in the same way. This file is imported
by the grader and, inside the grading sandbox, by ``inside_call.py`` (standard library and
NumPy only).
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np

#: Largest answer (number of values) accepted from one call of a student's function.
MAX_VALUES = 200_000
#: Longest text (an exception's message, a repr) accepted from a sandbox.
MAX_TEXT = 300


def encode(value: Any) -> Any:
    """``value`` (a case's argument) as JSON-ready data; ``decode`` gives it back.

    Floats, ints, bools, None and strings are themselves (JSON's ``NaN``/``Infinity`` stand
    for non-finite floats); tuples, dicts, NumPy arrays and NumPy scalars are tagged.

    >>> decode(json.loads(json.dumps(encode((1, 2.5, [np.inf], np.arange(3.0))))))
    (1, 2.5, [inf], array([0., 1., 2.]))
    """
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, tuple):
        return {"tuple": [encode(v) for v in value]}
    if isinstance(value, list):
        return [encode(v) for v in value]
    if isinstance(value, dict):
        if not all(isinstance(k, str) for k in value):
            raise TypeError("a case's dict must have string keys")
        return {"dict": {k: encode(v) for k, v in value.items()}}
    if isinstance(value, np.ndarray):
        if value.dtype.kind not in "biuf":
            raise TypeError(f"a case's array must hold numbers, got dtype {value.dtype}")
        return {"ndarray": {"dtype": value.dtype.str, "shape": list(value.shape),
                            "data": value.ravel().tolist()}}
    raise TypeError(f"a case's argument must be plain data, got {type(value).__name__}")


def decode(data: Any) -> Any:
    """The inverse of :func:`encode`."""
    if isinstance(data, list):
        return [decode(v) for v in data]
    if isinstance(data, dict):
        if set(data) == {"tuple"}:
            return tuple(decode(v) for v in data["tuple"])
        if set(data) == {"dict"}:
            return {k: decode(v) for k, v in data["dict"].items()}
        if set(data) == {"ndarray"}:
            spec = data["ndarray"]
            return np.array(spec["data"], dtype=np.dtype(spec["dtype"])).reshape(spec["shape"])
        raise ValueError(f"unknown tagged value {sorted(data)}")
    return data


def encode_case(args: tuple, kwargs: dict) -> dict:
    return {"args": [encode(a) for a in args], "kwargs": {k: encode(v) for k, v in kwargs.items()}}


def decode_case(data: dict) -> tuple[tuple, dict]:
    return tuple(decode(a) for a in data["args"]), {k: decode(v)
                                                      for k, v in data["kwargs"].items()}


def answer(raw: Any) -> dict:
    """What a student's function returned, as data: ``{"kind": "value", "shape", "values"}``
    for numbers (an object with ``as_array()`` included), ``{"kind": "none"}``, or
    ``{"kind": "opaque", "repr"}`` for anything that is not numbers."""
    if raw is None:
        return {"kind": "none"}
    try:
        value = raw.as_array() if callable(getattr(raw, "as_array", None)) else raw
        arr = np.asarray(value, dtype=float)
    except Exception:
        return {"kind": "opaque", "repr": _short_repr(raw)}
    if arr.size > MAX_VALUES:
        return {"kind": "opaque", "repr": f"an array of {arr.size} numbers (too many)"}
    return {"kind": "value", "shape": list(arr.shape), "values": arr.ravel().tolist()}


def _short_repr(raw: Any) -> str:
    try:
        return repr(raw)[:MAX_TEXT]
    except Exception:
        return f"a {type(raw).__name__} object"


KINDS = {"value", "none", "opaque", "not_written", "raised"}


def checked_answer(data: Any) -> dict | None:
    """``data`` read back from a sandbox if it is a well-formed answer (else None): the kind
    known, the shape a list of small non-negative ints whose product is the number of
    values, every value a number, every text a short string."""
    if not isinstance(data, dict) or data.get("kind") not in KINDS:
        return None
    kind = data["kind"]
    if kind == "value":
        shape, values = data.get("shape"), data.get("values")
        if (not isinstance(shape, list) or len(shape) > 8
                or not all(isinstance(n, int) and not isinstance(n, bool) and 0 <= n
                           for n in shape)
                or not isinstance(values, list) or len(values) > MAX_VALUES
                or math.prod(shape) != len(values)
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                           for v in values)):
            return None
        return {"kind": kind, "shape": shape, "values": [float(v) for v in values]}
    if kind == "opaque":
        return {"kind": kind, "repr": _text(data.get("repr"))}
    if kind == "raised":
        return {"kind": kind, "ename": _text(data.get("ename"))[:60] or "Exception",
                "evalue": _text(data.get("evalue"))}
    return {"kind": kind}


def _text(value: Any) -> str:
    return value[:MAX_TEXT] if isinstance(value, str) else ""


def dumps(data: Any) -> str:
    """One JSON line (non-finite floats as JSON's NaN/Infinity, which Python reads back)."""
    return json.dumps(data, ensure_ascii=True, separators=(",", ":"))
