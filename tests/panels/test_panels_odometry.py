"""The odometry chapter's panels survive every slider value."""

from __future__ import annotations

from wheelkin.widgets import all_panels, slider_values


def test_every_odometry_panel_survives_every_slider_value():
    panels = {k: f for k, f in all_panels().items() if k.startswith("odometry.")}
    assert panels
    for factory in panels.values():
        panel = factory()
        try:
            for name, control in panel.controls.items():
                for value in slider_values(control):
                    panel.redraw(**{name: value})
        finally:
            panel.close()
