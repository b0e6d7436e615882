r"""The one model's wheel rows in sympy, for the chapters that derive from them (chapter 8).

The first section of chapter 8 derives, for a wheel at :math:`(x_i, y_i)` whose plane points
along :math:`\psi_i` (a Swedish wheel's rollers at :math:`\gamma_i`), the rows that the body
twist :math:`\xi = (v_x, v_y, \omega)` must satisfy; the later sections apply them to whole
vehicles. :func:`general_wheel_rows` gives the three rows, :func:`vehicle_rows` stacks them
for a list of wheels. The numeric twins are :func:`wheelkin.unified.rolling_row` and
:func:`wheelkin.unified.sliding_row`. Needs sympy (in the book's environment).

>>> rows = general_wheel_rows()
>>> rows.fixed_rolling
Matrix([[cos(psi_i), sin(psi_i), x_i*sin(psi_i) - y_i*cos(psi_i)]])
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any, NamedTuple

try:
    import sympy as sp  # type: ignore[import-untyped]
except ModuleNotFoundError as exc:  # pragma: no cover - sympy is in the book's environment
    raise ModuleNotFoundError("wheelkin.symbolic needs sympy: pip install sympy") from exc

__all__ = ["WheelRows", "general_wheel_rows", "vehicle_rows"]

_KINDS = ("fixed", "steered", "swedish")


class WheelRows(NamedTuple):
    """The symbolic rows of one wheel (see :func:`general_wheel_rows`)."""

    #: The body twist :math:`(v_x, v_y, \omega)`, a 3 x 1 column.
    twist: Any
    #: The wheel's symbols :math:`(x_i, y_i, \psi_i, \gamma_i)`.
    wheel: tuple[Any, Any, Any, Any]
    #: The rolling row of a conventional wheel, :math:`J_1` (1 x 3): :math:`e^T P`.
    fixed_rolling: Any
    #: The no-sliding row :math:`C_1` (1 x 3): :math:`n^T P`.
    sliding: Any
    #: The rolling row of a Swedish wheel (1 x 3): :math:`u^T P / (u \cdot e)`.
    swedish_rolling: Any


@lru_cache(maxsize=1)
def general_wheel_rows() -> WheelRows:
    r"""The rows of a wheel at :math:`(x_i, y_i)`, plane along :math:`\psi_i`, rollers at
    :math:`\gamma_i`.

    With :math:`P = \begin{pmatrix}1 & 0 & -y_i\\ 0 & 1 & x_i\end{pmatrix}` (the contact
    point's velocity is :math:`P\xi`), the wheel's rolling direction
    :math:`e = (\cos\psi_i, \sin\psi_i)`, its axle direction
    :math:`n = (-\sin\psi_i, \cos\psi_i)` and a Swedish wheel's free-roller direction
    :math:`u = (-\sin(\psi_i + \gamma_i), \cos(\psi_i + \gamma_i))`: the rolling row
    :math:`e^T P`, the no-sliding row :math:`n^T P`, the Swedish rolling row
    :math:`u^T P / (u \cdot e)`, each simplified.

    Examples
    --------
    >>> rows = general_wheel_rows()
    >>> rows.sliding
    Matrix([[-sin(psi_i), cos(psi_i), x_i*cos(psi_i) + y_i*sin(psi_i)]])
    >>> x, y, psi, gamma = rows.wheel
    >>> sp.simplify(rows.swedish_rolling.subs({psi: 0, gamma: sp.pi / 4}))  # rollers at 45 deg
    Matrix([[1, -1, -x_i - y_i]])
    """
    vx, vy, w = sp.symbols("v_x v_y omega", real=True)
    x, y, psi, gamma = sp.symbols("x_i y_i psi_i gamma_i", real=True)
    p = sp.Matrix([[1, 0, -y], [0, 1, x]])
    e = sp.Matrix([sp.cos(psi), sp.sin(psi)])
    n = sp.Matrix([-sp.sin(psi), sp.cos(psi)])
    u = sp.Matrix([-sp.sin(psi + gamma), sp.cos(psi + gamma)])
    swedish = sp.simplify(u.T * p / u.dot(e))
    return WheelRows(sp.Matrix([vx, vy, w]), (x, y, psi, gamma), sp.simplify(e.T * p),
                     sp.simplify(n.T * p), swedish)


def vehicle_rows(wheels: list[tuple]) -> tuple[Any, Any]:
    r"""The stacked rows :math:`(J_1, C_1)` of a vehicle's wheels.

    Parameters
    ----------
    wheels : list of (x, y, kind, psi, gamma)
        Each wheel's position, kind (``"fixed"``, ``"steered"`` or ``"swedish"``), plane
        angle and roller angle: numbers or sympy expressions.

    Returns
    -------
    (sympy.Matrix, sympy.Matrix)
        :math:`J_1`, one rolling row per wheel; :math:`C_1`, one no-sliding row per
        conventional (fixed or steered) wheel (0 x 3 when there is none).

    Examples
    --------
    A differential drive of track :math:`W`: the wheels roll at :math:`v_x \mp \omega W/2`
    and neither slides sideways.

    >>> W = sp.Symbol("W", positive=True)
    >>> J1, C1 = vehicle_rows([(0, W / 2, "fixed", 0, 0), (0, -W / 2, "fixed", 0, 0)])
    >>> J1
    Matrix([
    [1, 0, -W/2],
    [1, 0,  W/2]])
    >>> C1
    Matrix([
    [0, 1, 0],
    [0, 1, 0]])
    """
    rows = general_wheel_rows()
    x, y, psi, gamma = rows.wheel
    if isinstance(wheels, str) or not hasattr(wheels, "__iter__"):
        raise ValueError(f"wheels must be a list of (x, y, kind, psi, gamma), got {wheels!r}")
    j, c = [], []
    for i, wheel in enumerate(wheels):
        if len(wheel) != 5 or wheel[2] not in _KINDS:
            raise ValueError(f"wheels[{i}] must be (x, y, kind, psi, gamma) with kind one of "
                             f"{', '.join(_KINDS)}, got {wheel!r}")
        x0, y0, kind, angle, roller = wheel
        values = {x: x0, y: y0, psi: angle, gamma: roller}
        row = rows.swedish_rolling if kind == "swedish" else rows.fixed_rolling
        j.append(sp.simplify(row.subs(values)))
        if kind in ("fixed", "steered"):
            c.append(rows.sliding.subs(values))
    if not j:
        raise ValueError("wheels must hold at least one wheel")
    return sp.Matrix.vstack(*j), (sp.Matrix.vstack(*c) if c else sp.zeros(0, 3))
