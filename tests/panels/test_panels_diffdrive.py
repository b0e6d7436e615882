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
