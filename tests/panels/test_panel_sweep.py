"""Every live panel over every slider value (``wheelkin.widgets.all_panels``): every control of
every panel is moved across its whole range the way a student moves it (through the widget, so
that the panel's own observer redraws), its extremes, one step inside each extreme, zero where
the range crosses it, the values in between (``slider_values``) and every option of a choice;
then a few random combinations of all the controls (seeded). Nothing may raise, print (a
traceback or anything else, on stdout or stderr) or warn, and each redraw must leave a PNG in
the panel.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from wheelkin.widgets import all_panels, slider_values

PNG = b"\x89PNG\r\n\x1a\n"
PANELS = all_panels()
RANDOM_COMBINATIONS = 4


# ----------------------------------------------------------------------------- panels

def _is_choice(control) -> bool:
    return bool(getattr(control, "options", None))


def sweep_values(control) -> list:
    """Every value a sweep gives ``control``: its whole range, with the risky ones."""
    values = list(slider_values(control, 5))  # extremes and values in between, or options
    lo, hi = getattr(control, "min", None), getattr(control, "max", None)
    step = getattr(control, "step", None)
    if not _is_choice(control) and lo is not None and hi is not None:
        extra = [0] if lo < 0 < hi else []  # zero: a division by zero waits there
        if step:
            extra += [lo + step, hi - step]  # one step inside each extreme
        if isinstance(control.value, int) and not isinstance(control.value, bool):
            extra = [round(v) for v in extra]
        values += [v for v in extra if lo <= v <= hi]
    unique = []
    for v in values:
        if not any(type(v) is type(u) and v == u for u in unique):
            unique.append(v)
    return unique


def random_value(control, rng: np.random.Generator):
    """A random value of ``control`` (on its step grid for a slider)."""
    if _is_choice(control):
        values = slider_values(control)
        return values[int(rng.integers(len(values)))]
    lo, hi = getattr(control, "min", None), getattr(control, "max", None)
    if lo is None or hi is None:
        return [False, True][int(rng.integers(2))]
    step = getattr(control, "step", None) or (hi - lo) / 100
    k = int(rng.integers(0, round((hi - lo) / step) + 1))
    value = min(lo + k * step, hi)
    return round(value) if isinstance(control.value, int) else float(value)


def _is_png(image) -> bool:
    return bytes(image.value[:8]) == PNG


def _texts(figure) -> str:
    from matplotlib.text import Text

    return "\n".join(t.get_text() for t in figure.findobj(Text))


@pytest.mark.parametrize("name", sorted(PANELS))
def test_panel_survives_every_slider_value(name, capfd):
    rng = np.random.default_rng(20261121)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")  # recorded, not raised: a panel cannot swallow one
        panel = PANELS[name]()
        try:
            defaults = panel.values()
            swept = 0
            for key, control in panel.controls.items():
                for value in sweep_values(control):
                    control.value = value  # as a student does: the panel's observer redraws
                    assert _is_png(panel.image), (name, key, value)
                    swept += 1
                control.value = defaults[key]
            for _ in range(RANDOM_COMBINATIONS):
                combo = {key: random_value(c, rng) for key, c in panel.controls.items()}
                seconds = panel.redraw(**combo)
                assert seconds >= 0 and _is_png(panel.image), (name, combo)
            assert "Traceback" not in _texts(panel.figure)
        finally:
            panel.close()
    out, err = capfd.readouterr()
    assert swept >= 2 * len(panel.controls), "every control gets at least its two extremes"
    assert not caught, [f"{w.category.__name__}: {w.message}" for w in caught]
    assert out == "" and err == "", f"the panel printed:\n{out}{err}"


def test_sweep_values_cover_the_extremes_the_steps_inside_and_zero():
    import ipywidgets as widgets

    values = sweep_values(widgets.FloatSlider(value=0.5, min=-2.0, max=2.0, step=0.05))
    assert min(values) == -2.0 and max(values) == 2.0
    assert {0, -1.95, 1.95} <= {round(v, 9) for v in values}
    ints = sweep_values(widgets.IntSlider(value=3, min=1, max=30))
    assert {1, 2, 29, 30} <= set(ints) and all(isinstance(v, int) for v in ints)
    options = sweep_values(widgets.Dropdown(options=["a", "b", "c"], value="a"))
    assert options == ["a", "b", "c"]
    assert sweep_values(widgets.Checkbox(value=False)) == [False, True]
