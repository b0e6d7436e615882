"""The differential-drive chapter's panels: every slider combination draws, and the wheel-speed
view flags the int32 overflow."""

from __future__ import annotations


def test_panels_sweep_every_slider_without_error():
    import itertools

    from wheelkin.widgets import all_panels, slider_values

    panels = {k: f for k, f in all_panels().items() if k.startswith("diffdrive.")}
    assert set(panels) == {"diffdrive.wheel_speeds", "diffdrive.speedometer"}
    for factory in panels.values():
        panel = factory()
        try:
            values = {name: slider_values(c, n=3) for name, c in panel.controls.items()}
            for combo in itertools.product(*values.values()):
                panel.redraw(**dict(zip(values, combo, strict=True)))
                assert panel.image.value[:4] == b"\x89PNG"
        finally:
            panel.close()


def test_wheel_speed_view_flags_the_int32_overflow():
    from matplotlib.figure import Figure

    from wheelkin.widgets.diffdrive import DiffDriveView

    view = DiffDriveView(Figure())
    view.update(0, 3141)
    assert "OVERFLOW" not in view.bar_text[2].get_text()
    view.update(0, 3142)
    assert "OVERFLOW" in view.bar_text[2].get_text()
    # the as-printed row drives the centre at half the commanded speed
    view.update(1000, 0)
    assert view.bar_text[1].get_text().startswith("centre 500 ")
    assert view.bar_text[0].get_text().startswith("centre 1000 ")


def test_wheel_speed_view_holds_the_fastest_wheel_of_its_sliders():
    """At the sliders' corners (|v| = 2000 steps/s, |omega| = 6000 mrad/s) the fastest wheel turns
    at 2000 + 6.000 rad/s x 42.5 mm x 8.043 steps/mm = 4051 steps/s (by hand): its bar and its
    arrow stay inside their axes, so no value runs off the picture unmarked."""
    from matplotlib.figure import Figure

    from wheelkin.widgets import all_panels
    from wheelkin.widgets.diffdrive import DiffDriveView

    panel = all_panels()["diffdrive.wheel_speeds"]()
    try:
        v_slider = panel.controls["v_steps_per_s"]
        w_slider = panel.controls["omega_mrad_per_s"]
        corners = [(v, w) for v in (v_slider.min, v_slider.max)
                   for w in (w_slider.min, w_slider.max)]
    finally:
        panel.close()
    assert max(abs(v) for v, _ in corners) == 2000
    assert max(abs(w) for _, w in corners) == 6000
    view = DiffDriveView(Figure())
    lo, hi = view.bx.get_xlim()
    bottom, top = view.ax.get_ylim()
    fastest = 0.0
    for v, w in corners:
        view.update(v, w)
        for bar in (*view.left_bars, *view.right_bars):
            fastest = max(fastest, abs(bar.get_width()))
            assert lo < bar.get_width() < hi, (v, w, bar.get_width())
        for arrow in view.arrows:
            tip = arrow.get_xy()[:, 1]
            assert bottom < tip.min() and tip.max() < top, (v, w, tip.min(), tip.max())
    assert round(fastest) == 4051


def test_a_slow_wheels_arrow_is_not_hidden_under_its_wheel():
    """At v = 1000 steps/s, omega = 4500 mrad/s the left wheel turns backwards at
    1000 - 4.5 x 42.5 x 8.043 = -538 steps/s (by hand): a 13 mm arrow, shorter than the
    36 mm wheel. Each arrow stands beside its wheel, so no part of it lies under the wheel
    (drawn above it), and it points the way the wheel turns."""
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle

    from wheelkin.widgets.diffdrive import DiffDriveView

    view = DiffDriveView(Figure())
    view.update(1000, 4500)
    wheels = sorted((p for p in view.ax.patches if isinstance(p, Rectangle)
                     and p.get_height() == 36), key=lambda p: p.get_x())
    assert len(wheels) == 2
    for arrow, wheel, sign in zip(view.arrows, wheels, (-1, 1), strict=True):
        xs = arrow.get_xy()[:, 0]
        x0, x1 = wheel.get_x(), wheel.get_x() + wheel.get_width()
        assert xs.max() < x0 or xs.min() > x1, (xs.min(), xs.max(), x0, x1)
        assert sign * (xs.mean() - (x0 + x1) / 2) > 0  # outboard
    left_tip = float(view.arrows[0].get_xy()[:, 1].min())
    assert abs(left_tip - (-538 * 0.025)) < 0.5
