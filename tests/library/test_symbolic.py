"""wheelkin.symbolic: the one model's rows in sympy, against wheelkin.unified's numeric rows
(another implementation) at random wheels, and against rows written out by hand.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from wheelkin.symbolic import general_wheel_rows, vehicle_rows
from wheelkin.unified import WheelConstraint, rolling_row, sliding_row


@pytest.mark.parametrize("seed", range(5))
def test_rows_equal_the_numeric_rows(seed):
    rows = general_wheel_rows()
    x, y, psi, gamma = rows.wheel
    rng = np.random.default_rng(seed)
    px, py = rng.uniform(-0.5, 0.5, 2)
    heading = rng.uniform(-math.pi, math.pi)
    roller = rng.choice([-1, 1]) * rng.uniform(0.2, math.pi / 2)
    values = {x: px, y: py, psi: heading, gamma: roller}
    fixed = WheelConstraint("w", (px, py), heading=heading, kind="fixed")
    swedish = WheelConstraint("w", (px, py), heading=heading, kind="swedish",
                              roller_angle=roller)
    for symbolic, numeric in ((rows.fixed_rolling, rolling_row(fixed)),
                              (rows.sliding, sliding_row(fixed)),
                              (rows.swedish_rolling, rolling_row(swedish))):
        got = np.array(symbolic.subs(values).evalf(), dtype=float).ravel()
        np.testing.assert_allclose(got, numeric, atol=1e-12)


def test_the_twist_and_the_wheel_symbols():
    rows = general_wheel_rows()
    assert [str(s) for s in rows.twist] == ["v_x", "v_y", "omega"]
    assert [str(s) for s in rows.wheel] == ["x_i", "y_i", "psi_i", "gamma_i"]
    assert general_wheel_rows() is rows  # derived once


def test_vehicle_rows_of_a_mecanum_platform_by_hand():
    a, b, g = sp.symbols("a b gamma", positive=True)
    wheels = [(a, b, "swedish", 0, g), (a, -b, "swedish", 0, -g),
              (-a, b, "swedish", 0, -g), (-a, -b, "swedish", 0, g)]
    j1, c1 = vehicle_rows(wheels)
    # v_x - v_y cot(gamma) - (a cot(gamma) + b) omega for the front left, signs mirrored
    cot = sp.cot(g)
    want = sp.Matrix([[1, -cot, -(a * cot + b)], [1, cot, a * cot + b],
                      [1, cot, -(a * cot + b)], [1, -cot, a * cot + b]])
    assert sp.simplify(j1 - want) == sp.zeros(4, 3)
    assert c1.shape == (0, 3)  # Swedish wheels have no sliding row


def test_vehicle_rows_of_a_steered_wheel():
    d = sp.Symbol("delta", real=True)
    j1, c1 = vehicle_rows([(1, 0, "steered", d, 0)])
    assert sp.simplify(j1 - sp.Matrix([[sp.cos(d), sp.sin(d), sp.sin(d)]])) == sp.zeros(1, 3)
    assert sp.simplify(c1 - sp.Matrix([[-sp.sin(d), sp.cos(d), sp.cos(d)]])) == sp.zeros(1, 3)


@pytest.mark.parametrize(("wheels", "message"), [
    ([(0, 1, "castor", 0, 0)], r"wheels\[0\] must be \(x, y, kind, psi, gamma\)"),
    ([(0, 1, "fixed", 0)], r"wheels\[0\] must be"),
    ([], "at least one wheel"),
    ("fixed", "wheels must be a list"),
])
def test_vehicle_rows_bad_input(wheels, message):
    with pytest.raises(ValueError, match=message):
        vehicle_rows(wheels)
