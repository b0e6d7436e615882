"""Tests for wheelkin.units: unit conversions and encoder steps, against hand calculations."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from wheelkin import units
from wheelkin.units import (
    DEG,
    FOOT,
    INCH,
    MM,
    MRAD,
    UNITS,
    convert,
    distance_to_steps,
    from_si,
    steps_per_m_from,
    steps_to_distance,
    to_si,
)

finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False)
positive = st.floats(min_value=1e-3, max_value=1e4, allow_nan=False, allow_infinity=False)


def test_constants_by_definition():
    # The international inch is 25.4 mm exactly; a foot is 12 inches; a degree is pi/180.
    assert INCH == pytest.approx(25.4 * MM, rel=1e-15)
    assert FOOT == pytest.approx(12 * INCH, rel=1e-15)
    assert 180 * DEG == pytest.approx(math.pi, rel=1e-15)
    assert 1000 * MRAD == pytest.approx(1.0, rel=1e-15)


@pytest.mark.parametrize(
    ("value", "unit", "si"),
    [
        (30.0, "in", 0.762),  # the rover document's 30 in turning radius
        (15.0, "ft/s", 4.572),  # the mecanum simulator's top speed
        (85.0, "mm", 0.085),  # Radon Ulzer wheel base
        (1000.0, "mrad/s", 1.0),
        (90.0, "deg", math.pi / 2),
        (360.0, "deg/s", 2 * math.pi),
        (2.5, "m", 2.5),
        (1.25, "rad/s", 1.25),
        (12.0, "in/s", 0.3048),
        (250.0, "mm/s", 0.25),
        (-3.0, "rad", -3.0),
        (1.0, "ft", 0.3048),
        (7.0, "m/s", 7.0),
        (1500.0, "mrad", 1.5),
        (30.0, "rpm", math.pi),  # half a revolution per second
    ],
)
def test_to_si_hand_values(value, unit, si):
    assert to_si(value, unit) == pytest.approx(si, rel=1e-12)
    assert from_si(si, unit) == pytest.approx(value, rel=1e-12)


def test_every_unit_is_tested_by_hand():
    tested = {"in", "ft/s", "mm", "mrad/s", "deg", "deg/s", "m", "rad/s", "in/s", "mm/s", "rad",
              "ft", "m/s", "mrad", "rpm"}
    assert tested == set(UNITS)


@given(value=finite, unit=st.sampled_from(sorted(UNITS)))
def test_round_trip(value, unit):
    assert from_si(to_si(value, unit), unit) == pytest.approx(value, rel=1e-12, abs=1e-12)


def test_arrays_keep_their_shape():
    out = to_si(np.ones((2, 3)), "in")
    assert out.shape == (2, 3)
    np.testing.assert_allclose(out, 0.0254)
    assert isinstance(to_si(1.0, "in"), float)


def test_unknown_unit_lists_the_known_ones():
    with pytest.raises(ValueError, match=r"unit must be one of .*'in'.*'mrad/s'.*got 'inch'"):
        to_si(1.0, "inch")
    with pytest.raises(ValueError, match="unit must be one of"):
        from_si(1.0, None)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, "ten", [1.0, math.nan]])
def test_bad_values_name_the_parameter(bad):
    with pytest.raises(ValueError, match=r"^value "):
        to_si(bad, "m")
    with pytest.raises(ValueError, match=r"^value "):
        from_si(bad, "m")


def test_convert_between_units_of_one_kind():
    assert convert(1.0, "ft", "in") == pytest.approx(12.0)
    assert convert(2.0, "ft/s", "mm/s") == pytest.approx(609.6)
    assert convert(1.0, "rad", "mrad") == pytest.approx(1000.0)
    with pytest.raises(ValueError, match="to_unit must be a unit of the same kind"):
        convert(1.0, "m", "deg")
    with pytest.raises(ValueError, match="from_unit must be one of"):
        convert(1.0, "yard", "m")


def test_radon_ulzer_steps_per_metre_by_hand():
    # 12 counts per motor revolution, 75.81:1 gearing: 909.72 counts per wheel revolution,
    # over a circumference of 113.097 mm.
    expected = 12 * 75.81 / 0.113097
    assert steps_per_m_from(12, 75.81, 0.113097) == pytest.approx(expected, rel=1e-15)
    assert round(expected, 1) == 8043.7
    # The same from the wheel diameter (36 mm): pi * 0.036 m.
    assert steps_per_m_from(12, 75.81, math.pi * 0.036) == pytest.approx(8043.7, abs=0.05)


def test_firmware_constant_is_the_truncated_integer():
    # The firmware computes (ENCODER_RESOLUTION * GEAR_RATIO_x1000 * 1000) / CIRCUMFERENCE_um in
    # unsigned integer arithmetic; replicate that independently.
    circumference_um = int(36 * math.pi * 1000)  # float -> uint32 truncation
    assert circumference_um == 113097
    assert (12 * 75810 * 1000) // circumference_um == units.RADON_ULZER_STEPS_PER_M
    assert units.RADON_ULZER_WHEEL_CIRCUMFERENCE == pytest.approx(circumference_um * 1e-6, rel=1e-15)
    exact = steps_per_m_from(units.RADON_ULZER_COUNTS_PER_MOTOR_REV,
                             units.RADON_ULZER_GEAR_RATIO, units.RADON_ULZER_WHEEL_CIRCUMFERENCE)
    assert 0 < exact - units.RADON_ULZER_STEPS_PER_M < 1


def test_one_wheel_revolution_is_one_circumference():
    d = steps_to_distance(909.72, steps_per_rev=909.72, wheel_radius=0.018)
    assert d == pytest.approx(2 * math.pi * 0.018, rel=1e-14)


@given(steps=finite, per_rev=positive, radius=st.floats(min_value=1e-3, max_value=2.0))
def test_two_descriptions_of_the_encoder_agree(steps, per_rev, radius):
    per_m = per_rev / (2 * math.pi * radius)
    a = steps_to_distance(steps, steps_per_rev=per_rev, wheel_radius=radius)
    b = steps_to_distance(steps, steps_per_m=per_m)
    assert a == pytest.approx(b, rel=1e-12, abs=1e-12)


@given(distance=finite, per_m=positive)
def test_steps_round_trip(distance, per_m):
    steps = distance_to_steps(distance, steps_per_m=per_m)
    assert steps_to_distance(steps, steps_per_m=per_m) == pytest.approx(distance, rel=1e-12,
                                                                        abs=1e-12)


def test_steps_sign_and_linearity():
    d1 = steps_to_distance(100, steps_per_m=8043)
    assert steps_to_distance(-100, steps_per_m=8043) == -d1
    np.testing.assert_allclose(steps_to_distance([100, 200], steps_per_m=8043), [d1, 2 * d1])
    assert distance_to_steps(1.0, steps_per_m=8043) == pytest.approx(8043.0)


def test_rounding_cost_over_ten_metres():
    # A wheel travels 10 m: the encoder counts 10 * 8043.7 steps; a firmware dividing by 8043
    # reports a longer distance, by 10 m * (8043.7/8043 - 1), a little under a millimetre.
    exact = steps_per_m_from(12, 75.81, 0.113097)
    counted = distance_to_steps(10.0, steps_per_m=exact)
    reported = steps_to_distance(counted, steps_per_m=8043)
    assert reported - 10.0 == pytest.approx(10.0 * (exact / 8043 - 1), rel=1e-9)
    assert 0.8e-3 < reported - 10.0 < 0.9e-3


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({}, "exactly one"),
        ({"steps_per_m": 8043, "steps_per_rev": 909.72, "wheel_radius": 0.018}, "exactly one"),
        ({"steps_per_m": 8043, "wheel_radius": 0.018}, "exactly one"),
        ({"steps_per_rev": 909.72}, "^wheel_radius must be given"),
        ({"wheel_radius": 0.018}, "^steps_per_rev must be given"),
        ({"steps_per_m": 0}, "^steps_per_m must be a finite number > 0"),
        ({"steps_per_m": math.nan}, "^steps_per_m must be a finite number > 0"),
        ({"steps_per_rev": -5, "wheel_radius": 0.018}, "^steps_per_rev must be"),
        ({"steps_per_rev": 909.72, "wheel_radius": math.inf}, "^wheel_radius must be"),
    ],
)
def test_encoder_descriptions_are_validated(kwargs, match):
    with pytest.raises(ValueError, match=match):
        steps_to_distance(1.0, **kwargs)
    with pytest.raises(ValueError, match=match):
        distance_to_steps(1.0, **kwargs)


def test_bad_steps_and_distance_name_the_parameter():
    with pytest.raises(ValueError, match=r"^steps must not contain NaN"):
        steps_to_distance(math.nan, steps_per_m=8043)
    with pytest.raises(ValueError, match=r"^distance must not contain NaN or infinity"):
        distance_to_steps(math.inf, steps_per_m=8043)


@pytest.mark.parametrize(
    ("args", "name"),
    [((0, 75.81, 0.1), "counts_per_motor_rev"), ((12, -1, 0.1), "gear_ratio"),
     ((12, 75.81, math.nan), "wheel_circumference")],
)
def test_steps_per_m_from_validates(args, name):
    with pytest.raises(ValueError, match=rf"^{name} must be a finite number > 0"):
        steps_per_m_from(*args)


def test_rpm_is_a_rate_unit():
    from wheelkin import units as u

    assert u.RPM == 2 * math.pi / 60  # one revolution (2 pi rad) per 60 s
    assert u.to_si(60.0, "rpm") == pytest.approx(2 * math.pi)
    assert u.convert(1.0, "rad/s", "rpm") == pytest.approx(60 / (2 * math.pi))
    assert u.convert(360.0, "deg/s", "rpm") == pytest.approx(60.0)
    with pytest.raises(ValueError, match="to_unit"):
        u.convert(1.0, "rpm", "m/s")
