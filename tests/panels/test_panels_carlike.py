"""The car-like chapter's steering and pure-pursuit views: what their labels print."""

from __future__ import annotations

import math


def test_steering_view_never_prints_a_negative_zero():
    """Ideal Ackermann steering has no angle error: every bar reads 0.00°, never "-0.00°"."""
    from matplotlib.figure import Figure

    from wheelkin.style import fixed_layout
    from wheelkin.widgets.carlike import SteeringView

    view = SteeringView(Figure(layout=fixed_layout()), "car")
    for delta_deg in (-30.0, -12.5, 5.0, 20.0, 33.0):
        view.update(delta_deg, "ackermann")
        texts = [t.get_text() for t in view.bar_text]
        assert texts and all(t == "+0.00°" for t in texts), (delta_deg, texts)


def test_rover_steering_view_gives_the_centre_in_inches_too():
    """The rover's chapter works in inches: the centre is printed in metres and inches, and the
    two agree (1 in = 25.4 mm exactly)."""
    import re

    from matplotlib.figure import Figure

    from wheelkin.style import fixed_layout
    from wheelkin.widgets.carlike import SteeringView

    view = SteeringView(Figure(layout=fixed_layout()), "rover")
    view.update(20.0)
    m = re.search(r"y = ([-+\d.]+) m \(([-+\d.]+) in\)", view.centre)
    assert m, view.centre
    metres, inches = float(m.group(1)), float(m.group(2))
    assert math.isclose(metres / 0.0254, inches, abs_tol=0.06 + 0.005 / 0.0254)
    car = SteeringView(Figure(layout=fixed_layout()), "car")
    car.update(20.0)
    assert " in)" not in car.centre


def test_pursuit_view_writes_the_look_ahead_as_a_subscript():
    from matplotlib.figure import Figure

    from wheelkin.style import fixed_layout
    from wheelkin.widgets.carlike import PursuitView

    view = PursuitView(Figure(layout=fixed_layout()))
    view.update(1.0, 30.0)
    text = view.text.get_text()
    assert "$\\kappa = 2y/L_d^2$" in text and "L_d²" not in text
    # kappa = 2 y / L_d^2 with y = sin 30° at L_d = 1 m (hand value 1.00 1/m)
    assert "+1.00 1/m" in text
