"""The mecanum chapter's panels redraw over their sliders without raising."""

from __future__ import annotations


def test_panels_sweep_without_raising():
    import matplotlib

    matplotlib.use("Agg")
    from wheelkin.widgets import all_panels, slider_values

    panels = {n: f for n, f in all_panels().items() if n.startswith("mecanum.")}
    assert len(panels) >= 3
    for factory in panels.values():
        panel = factory()
        try:
            for cname, control in panel.controls.items():
                for value in slider_values(control, n=3):
                    panel.redraw(**{cname: value})
        finally:
            panel.close()
