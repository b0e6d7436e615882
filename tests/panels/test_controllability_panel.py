"""The controllability panel draws what the library computes: its four-move path ends where
the exact arcs end (hand-written for the car, the drive-turn closed form for the differential
drive), its red arrow is eps^2 [f1, f2], and its log-log curves have the measured orders."""

from __future__ import annotations

import math

import numpy as np
import pytest

from wheelkin import nonholonomic, style
from wheelkin.widgets import controllability as C


@pytest.mark.parametrize("epsilon", [0.05, 0.2, 0.5])
def test_the_paths_end_where_the_closed_forms_do(epsilon):
    k = C.CAR_MAX_CURVATURE
    _, ends, predicted = C.manoeuvre("car", epsilon)
    shift = 4 * (1 - math.cos(k * epsilon)) / k
    np.testing.assert_allclose(ends[-1], [0.0, shift, 0.0], atol=1e-12)
    np.testing.assert_allclose(ends, nonholonomic.parallel_parking([0, 0, 0], epsilon, k),
                               atol=1e-12)
    np.testing.assert_allclose(predicted, [0.0, 2 * k * epsilon**2, 0.0], atol=1e-9)
    _, ends, predicted = C.manoeuvre("differential drive", epsilon)
    np.testing.assert_allclose(
        ends[-1], [epsilon * (1 - math.cos(epsilon)), -epsilon * math.sin(epsilon), 0.0],
        atol=1e-12)
    np.testing.assert_allclose(predicted, [0.0, -epsilon**2, 0.0], atol=1e-9)


def test_the_curves_have_the_orders_of_the_chapter():
    for vehicle, order in (("car", 4.0), ("differential drive", 3.0)):
        eps, net, rest = C._curves(vehicle)
        small = eps < 0.05
        assert abs(np.polyfit(np.log(eps[small]), np.log(net[small]), 1)[0] - 2.0) < 0.01
        assert abs(np.polyfit(np.log(eps[small]), np.log(rest[small]), 1)[0] - order) < 0.02


def test_the_animation_is_legible_and_short():
    style.setup()
    anim = C.manoeuvre_animation()
    assert anim._save_count <= 40
    for k in (0, anim._save_count - 1):
        anim._func(k)
        assert style.check_figure(anim._fig) == []
    with pytest.raises(ValueError, match="frames"):
        C.manoeuvre_animation(frames=41)
    with pytest.raises(ValueError, match="vehicle"):
        C.manoeuvre("bicycle", 0.1)
    with pytest.raises(ValueError, match="epsilon"):
        C.manoeuvre("car", 0.0)
