"""Bad input to the library: every public callable of every formula module
(``wheelkin._registry.FORMULA_MODULES``), called with one argument at a time replaced by a bad
value, raises ValueError or TypeError naming a parameter, or returns finite numbers; a boolean
where a number is meant is refused. The panels' and the exercises' sweeps are in
tests/panels/test_panel_sweep.py and tests/book/test_exercise_wrong_answers.py.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import math
import typing
import warnings

import numpy as np
import pytest

from wheelkin import _registry

#: Callables that read a sandbox vehicle (the sandbox is validated on its own, not here).
SANDBOX_BOUND: set[str] = set()
FORMULA_MODULES = _registry.FORMULA_MODULES


def _good_values() -> dict:
    """A valid value for each parameter name of the formula modules' public callables."""
    from wheelkin import mecanum, nonholonomic, rover, unified, waypoints
    from wheelkin.follower import KinematicSkidSteer, PathFollower

    segs = waypoints.plan_segments([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    cmds = waypoints.schedule(segs, 0.04, 0.06)
    return {
        # units
        "value": 1.5, "unit": "m", "from_unit": "m", "to_unit": "mm", "steps": 100.0,
        "counts_per_motor_rev": 12.0, "gear_ratio": 75.81, "wheel_circumference": 0.113,
        "steps_per_m": 8043.7, "steps_per_rev": 360.0,
        # frames
        "x": 0.5, "y": -0.25, "theta": 0.3, "vx": 0.4, "vy": -0.1, "omega": 0.2,
        "angle": 2.0, "twist": (0.4, -0.1, 0.2), "twists": [[0.4, -0.1, 0.2]] * 3,
        "pose": (0.1, 0.2, 0.3), "pose0": (0.0, 0.0, 0.0), "pose_from": (0.0, 0.0, 0.1),
        "pose_to": (1.0, 0.5, 0.4), "delta": (0.3, 0.1, 0.2), "point": (0.2, 0.1),
        "points": [[0.2, 0.1], [-0.3, 0.0]], "dt": 0.1, "radius_in": 30.0, "radius_m": 2.0,
        "centre_speed_in_per_s": 10.0, "Vx_ftps": 1.0, "Vy_ftps": 0.5, "psi": 0.3,
        "X_ft": 1.0, "Y_ft": 2.0, "X_mm": 100.0, "Y_mm": 200.0,
        # rover
        "radius": 30.0, "speed": 10.0, "speed_in_per_s": 10.0, "geometry": None,
        "straight_threshold": 250.0, "max_corner_angle": 0.785, "command": 40.0,
        "mapping": "radius", "wheel_radius_in": 2.35, "v": 0.3,
        "d1": 7.0, "d2": 10.0, "d3": 10.0, "d4": 10.0,
        # mecanum
        "wheel_radius": 0.05, "half_wheelbase": 0.2, "half_track": 0.15,
        "roller_angle": 0.785, "wheel_rates": [1.0, 2.0, 3.0, 4.0], "accel_x": 0.5,
        "accel_y": 0.5, "mu": 0.8, "gravity": 9.81, "max_speed": 2.0, "refuse": False,
        "lap_time": 10.0, "t": 1.0, "heading": "rotating", "goal": (1.0, 1.0, 0.5),
        "max_omega": 1.0, "max_rate": 20.0, "centre_of_rotation": (0.1, 0.0),
        # diffdrive
        "track_width": 0.3, "v_left": 0.2, "v_right": 0.4, "fl": 0.2, "fr": 0.3, "rl": 0.2,
        "rr": 0.3, "v_steps_per_s": 1000.0, "omega_mrad_per_s": 500.0,
        "v_linear_steps_per_s": 1000.0, "track_width_mm": 85, "values": [1, 2, 3], "bits": 16,
        "numerator": [7, -7], "denominator": [2, 2], "method": "exact", "window": 0.1,
        "min_steps": 2, "counts": [0, 5, 10, 15], "times": [0.0, 0.1, 0.2, 0.3],
        "timeout": 1.0,
        # odometry
        "increments": [[10.0, 12.0], [8.0, 8.0]], "steps_per_mm": 8.0, "distance": 10.0,
        "dtheta": 0.1, "segments": segs, "max_step_mm": 5.0, "travel_mm": [[1.0, 1.5]],
        "delta_left": [0.1, 0.2], "delta_right": [0.12, 0.18], "covariance": np.eye(3) * 1e-4,
        "k_left": 1e-4, "k_right": 1e-4, "runs": 5, "rng": 3, "cw_end": (0.1, 0.05),
        "ccw_end": (0.08, -0.02), "side": 4.0,
        # waypoints and follower
        "waypoints": [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]], "arc_radius": 0.5,
        "initial_heading": 0.0, "spacing": 0.05, "turn_step": 0.1, "half_axle": 0.06,
        "wheel_rate": 7.5, "commands": cmds, "period": 0.064, "wheel_angles": [[0.0] * 4] * 3,
        "walls": waypoints.LAB_WALLS, "path": [[0.0, 0.0], [1.0, 0.0]],
        "lookahead": 0.15, "heading_gain": 4.0, "max_turn_rate": 2.0, "min_turn_rate": 0.2,
        "heading_tolerance": 0.01, "approach_gain": 2.0, "min_speed": 0.02,
        "robot": KinematicSkidSteer((0.0, 0.0, 0.0)), "switch": "time",
        "follower": PathFollower(segs), "odometry_track_width": 0.3, "max_wheel_rate": 10.0,
        "skid_factor": 1.5, "motor_time_constant": 0.05, "wheelbase": 0.1,
        "name": "FL", "position": (0.1, 0.2), "driven_wheels": None,
        # carlike
        "inner_angle": 0.3, "steering_angle": 0.2, "front_speed": 1.0, "rear_to_com": 0.05,
        "max_steering_angle": 0.5, "arm_length": 0.15, "arm_angle": 0.3, "max_inner_angle": 0.6,
        "curvature": 0.2,
        # unified
        "wheels": unified.mecanum_wheels(mecanum.EXAMPLE_GEOMETRY), "rates": [1.0] * 4,
        "wheel": unified.mecanum_wheels(mecanum.EXAMPLE_GEOMETRY)[0], "caster": True,
        "casters": True, "caster_offset": 0.05, "steering": None,
        "_rover_geometry": rover.OSR_GEOMETRY, "_mecanum_geometry": mecanum.EXAMPLE_GEOMETRY,
        # nonholonomic
        "configuration": (0.1, 0.2, 0.3), "f1": nonholonomic.unicycle_drive,
        "f2": nonholonomic.unicycle_turn, "field": nonholonomic.unicycle_drive,
        "fields": [nonholonomic.unicycle_drive, nonholonomic.unicycle_turn],
        "epsilon": 0.1, "duration": 0.5, "max_curvature": 1.35,
        # control
        "k_rho": 3.0, "k_alpha": 8.0, "k_beta": -3.0, "line_point": (0.0, 0.5),
        "line_heading": 0.3, "k_offset": 4.0, "k_heading": 4.0,
        "reference": (0.2, 0.1, 0.4), "reference_twist": (0.3, 0.0, 0.2), "k_x": 1.0,
        "k_y": 25.0, "k_theta": 10.0, "law": lambda t, p: np.tile([0.1, 0.0, 0.2], (len(p), 1)),
        "start": (0.0, 0.0, 0.0),
        # motion models and odometry fusion
        "previous_pose": (0.0, 0.0, 0.0), "odometry": (1.0, 0.5, 0.2),
        "previous_odometry": (0.0, 0.0, 0.0), "alphas": [0.01, 0.02, 0.03, 0.01], "n": 5,
        "error": [0.01, -0.02, 0.003],

        # kinematics and odometers (the kinematics object is filled in by _resolve)
        "kinematics": None,
    }


BAD_VALUES = {
    "nan": math.nan, "+inf": math.inf, "-inf": -math.inf, "None": None, "str": "abc",
    "True": True, "empty": [], "wrong-shape": np.ones((2, 2, 2)), "subnormal": 5e-324,
    "huge": 1e300,
}


def _public_callables():
    for mod_name in FORMULA_MODULES:
        mod = importlib.import_module(f"wheelkin.{mod_name}")
        for name in mod.__all__:
            obj = getattr(mod, name)
            if not callable(obj) or (isinstance(obj, type) and issubclass(obj, tuple)
                                     and not getattr(obj, "validates", False)):
                continue  # constants; NamedTuple results (outputs, not inputs; Pose and
                # Twist, which validate what they are given, are swept)
            if isinstance(obj, type) and typing.Protocol in obj.__mro__:
                continue  # a Protocol describes, it is not called
            if inspect.isabstract(obj):
                continue  # an interface (VehicleKinematics, Odometry): its classes are swept
            if getattr(obj, "__module__", "") != mod.__name__:
                continue  # a re-export: swept where it is defined
            if f"{mod_name}.{name}" in SANDBOX_BOUND:
                continue
            yield f"{mod_name}.{name}", obj


def _finite_leaves(out, allow_inf: bool = False, depth: int = 0) -> bool:
    """No NaN anywhere in ``out``, and no infinity unless ``allow_inf`` (a straight line's
    radius, the ICR of a pure translation: an infinity the valid call also returns)."""
    if depth > 4 or out is None or isinstance(out, str | bool):
        return True
    if dataclasses.is_dataclass(out) and not isinstance(out, type):
        return all(_finite_leaves(getattr(out, f.name), allow_inf, depth + 1)
                   for f in dataclasses.fields(out))
    if isinstance(out, dict):
        return all(_finite_leaves(v, allow_inf, depth + 1) for v in out.values())
    if isinstance(out, tuple | list):
        return all(_finite_leaves(v, allow_inf, depth + 1) for v in out)
    if isinstance(out, np.ndarray | float | int | np.number):
        arr = np.asarray(out)
        if arr.dtype.kind not in "fc":
            return True
        return bool(np.all(~np.isnan(arr) if allow_inf else np.isfinite(arr)))
    return True  # an object (a controller, a robot): its methods are tested elsewhere


def _good_call(qualname: str, fn, good: dict) -> dict:
    """Keyword arguments for a valid call of ``fn`` (required parameters only, plus the
    geometry a module's functions take)."""
    kwargs = {}
    for p in inspect.signature(fn).parameters.values():
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            continue
        if p.name == "geometry":
            if qualname.startswith("mecanum.") or qualname.startswith("unified."):
                kwargs[p.name] = good["_mecanum_geometry"]
            elif qualname.startswith("rover."):
                kwargs[p.name] = good["_rover_geometry"]
            continue
        if p.default is p.empty:
            kwargs[p.name] = OVERRIDES.get(qualname, {}).get(p.name, good.get(p.name, KeyError))
            if kwargs[p.name] is KeyError:
                raise KeyError(p.name)
    return kwargs


def _optional(fn, kwargs: dict) -> dict:
    """The optional parameters with a plain default (a number, a flag, a string), to be swept
    too: their defaults are valid values."""
    out = {}
    for p in inspect.signature(fn).parameters.values():
        if (p.name not in kwargs and p.default is not p.empty and p.name != "geometry"
                and isinstance(p.default, bool | int | float | str)):
            out[p.name] = p.default
    return out


#: Calls whose valid arguments differ from the shared table.
OVERRIDES = {
    "rover.RoverGeometry": {"d1": 7.0, "d2": 10.0, "d3": 10.0, "d4": 10.0},
    "rover.radius_to_command": {"radius": 100.0},
    "rover.wheel_commands": {"v": 0.3, "omega": 0.1, "geometry": None},
    "units.steps_to_distance": {"steps": 100.0, "steps_per_m": 8043.7},
    "units.distance_to_steps": {"distance": 0.5, "steps_per_m": 8043.7},
    "diffdrive.body_twist_steps": {"left": 1000.0, "right": 1200.0, "track_width_mm": 85.0,
                                   "steps_per_m": 8043.0},
    "odometry_uncertainty.monte_carlo_poses": {"rng": None},
    "odometry_uncertainty.propagate_covariance": {"delta_left": 0.1, "delta_right": 0.12},
    "odometry_uncertainty.step_jacobians": {"delta_left": 0.1, "delta_right": 0.12},
    "waypoints.Segment": {"kind": "straight", "start": (0.0, 0.0, 0.0),
                          "end": (1.0, 0.0, 0.0), "length": 1.0, "heading_change": 0.0,
                          "radius": math.inf},
    "waypoints.WheelCommand": {"segment": None, "left_rate": 1.0, "right_rate": 1.0,
                               "duration": 1.0, "speed": 0.04, "yaw_rate": 0.0},
    "follower.WheelLayout": {"driven_wheels": None},
    "unified.rover_wheels": {"geometry": None},
    "unified.sliding_row": {"wheel": None},
    "mecanum.circle_twist": {"radius": 1.0, "lap_time": 10.0},
    # the components form; the twist form is swept by test_mecanum_twist_form_bad_input
    "mecanum.inverse_kinematics": {"vx": 0.5, "vy": 0.2, "omega": 0.1},
    "mecanum.max_rim_speed": {"vx": 0.5, "vy": 0.2, "omega": 0.1},
    "mecanum.circle_speed": {"radius": 1.0, "lap_time": 10.0},
    "sources.rover_twist": {"radius_in": 30.0, "centre_speed_in_per_s": 10.0},
    "diffdrive.speed_from_counts": {"counts": [0, 5, 10, 15], "times": [0.0, 0.1, 0.2, 0.3],
                                    "window": 0.15},
    "diffdrive.wrap_int": {"values": [1, 2, 3]},
    "diffdrive.c_divide": {"numerator": 7, "denominator": 2},
    "diffdrive.DiffDriveConstants": {"track_width_mm": 85, "steps_per_m": 8043},
    "diffdrive.q16_turn_factor": {"track_width_mm": 85, "steps_per_m": 8043},
    "diffdrive.int32_omega_limit": {"track_width_mm": 85, "steps_per_m": 8043},
    "diffdrive.speed_resolution": {"window": 0.1, "steps_per_m": 8043.0},
    "diffdrive.time_to_count": {"min_steps": 2, "speed": 0.1, "steps_per_m": 8043.0},
    "odometry.plan_wheel_travel": {"segments": [(100.0, 0.0), (0.0, 1.0)],
                                   "track_width_mm": 85.0, "max_step_mm": 5.0},
    "odometry.encoder_increments": {"travel_mm": [[1.0, 1.5], [2.0, 2.0]],
                                    "steps_per_mm": 8.0},
    "unified.skid_steer_wheels": {"half_track": 0.06, "half_wheelbase": 0.05},
    "unified.diff_drive_wheels": {"track_width": 0.3, "wheel_radius": 0.05},
    "nonholonomic.car_constraints": {"configuration": (0.1, 0.2, 0.3, 0.2)},
    "nonholonomic.car_fields": {"configuration": (0.1, 0.2, 0.3, 0.2)},
    "nonholonomic.diff_drive_constraints": {"configuration": (0.1, 0.2, 0.3, 1.0, 2.0)},
    "nonholonomic.pfaffian_matrix": {"pose": (0.1, 0.2, 0.3)},
    "nonholonomic.wheel_angle_fields": {"configuration": (0.1, 0.2, 0.3, 1.0, 2.0, 3.0, 4.0)},
    "control.follow_line": {"speed": 0.3},
    "motion_models.sample_motion_model_odometry": {"rng": None},
    "motion_models.sample_motion_model_velocity": {"rng": None, "alphas": [0.01] * 6,
                                                  "twist": (0.4, 0.0, 0.2)},
    "odometry_fusion.ekf_step": {"delta_left": 0.1, "delta_right": 0.12},
    "frames.field_relative": {"heading": 0.3},
    "frames.to_field_relative": {"heading": 0.3},
}


def _resolve(qualname: str, kwargs: dict) -> dict:
    """Fill the overrides that need objects: a geometry of the right kind, a segment, ..."""
    from wheelkin import mecanum, odometry, rover, unified, waypoints
    from wheelkin.follower import DrivenWheel

    if qualname == "rover.wheel_commands":
        kwargs["geometry"] = rover.OSR_GEOMETRY_SI
    if qualname == "unified.rover_wheels":
        kwargs["geometry"] = rover.OSR_GEOMETRY
    if qualname == "odometry_uncertainty.monte_carlo_poses":
        kwargs["rng"] = np.random.default_rng(0)
        kwargs["runs"] = 5
    if qualname.startswith("motion_models.sample_"):
        kwargs["rng"] = np.random.default_rng(0)
    if qualname == "waypoints.WheelCommand":
        kwargs["segment"] = waypoints.plan_segments([[0, 0], [1, 0]])[0]
    if qualname == "follower.WheelLayout":
        kwargs["driven_wheels"] = (DrivenWheel("L", (0.0, 0.1)), DrivenWheel("R", (0.0, -0.1)))
    if qualname == "unified.sliding_row":
        kwargs["wheel"] = unified.diff_drive_wheels(0.3, 0.05)[0]
    if qualname == "nonholonomic.pfaffian_matrix":
        kwargs["wheels"] = unified.diff_drive_wheels(0.3, 0.05)
    if qualname == "kinematics.MecanumKinematics":
        kwargs["geometry"] = mecanum.EXAMPLE_GEOMETRY
    if qualname == "kinematics.RoverKinematics":
        kwargs["geometry"] = rover.OSR_GEOMETRY_SI
    if qualname.startswith("odometers."):
        kwargs["kinematics"] = _kinematics_for(qualname)
    del mecanum, odometry
    return kwargs


def _kinematics_for(qualname: str):
    """A kinematics object of the vehicle an odometry class ``qualname`` needs."""
    from wheelkin import kinematics, mecanum

    if "Mecanum" in qualname:
        return kinematics.MecanumKinematics(mecanum.EXAMPLE_GEOMETRY)
    if "Ackermann" in qualname:
        return kinematics.AckermannKinematics(wheelbase=2.5, track_width=1.5)
    return kinematics.DiffDriveKinematics(track_width=0.3)


def _calls():
    good = _good_values()
    for qualname, fn in _public_callables():
        try:
            kwargs = _resolve(qualname, _good_call(qualname, fn, good)
                              | OVERRIDES.get(qualname, {}))
        except KeyError as exc:
            yield pytest.param(qualname, fn, None, None, id=f"{qualname}-no-valid-call",
                               marks=pytest.mark.xfail(reason=f"no valid value for {exc}",
                                                       strict=True))
            continue
        optional = _optional(fn, kwargs)
        for param in [*kwargs, *optional]:
            for label in BAD_VALUES:
                yield pytest.param(qualname, fn, kwargs, (param, label),
                                   id=f"{qualname}-{param}-{label}")


CALLS = list(_calls())
_GOOD_IS_INFINITE: dict = {}


def test_every_public_callable_has_a_valid_call():
    good = _good_values()
    broken = []
    for qualname, fn in _public_callables():
        try:
            kwargs = _resolve(qualname, _good_call(qualname, fn, good)
                              | OVERRIDES.get(qualname, {}))
            out = fn(**kwargs)
        except Exception as exc:
            broken.append(f"{qualname}: {type(exc).__name__}: {exc}")
            continue
        assert _finite_leaves(out, allow_inf=True), qualname
    assert not broken, "\n".join(broken)


@pytest.mark.parametrize(("qualname", "fn", "kwargs", "bad"), CALLS)
def test_bad_argument_gets_a_clean_error_or_a_finite_result(qualname, fn, kwargs, bad):
    param, label = bad
    value = BAD_VALUES[label]
    good_value = kwargs.get(param, inspect.signature(fn).parameters[param].default)
    args = dict(kwargs) | {param: value}
    names = list(inspect.signature(fn).parameters)
    # an infinity the valid call returns too, or one passed in where the function documents
    # it (a straight line's radius) and hands it back, is not a leak; a NaN always is
    infinite_anyway = _GOOD_IS_INFINITE.setdefault(
        qualname, not _finite_leaves(fn(**kwargs))) or label in ("+inf", "-inf")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            out = fn(**args)
        except (ValueError, TypeError) as exc:
            message = str(exc)
            assert any(n in message for n in names), (
                f"{qualname}({param}={label}) raised {type(exc).__name__} naming no "
                f"parameter of {names}: {message}")
            return
    assert _finite_leaves(out, infinite_anyway), (
        f"{qualname}({param}={label}) returned non-finite {out!r}")
    number_meant = isinstance(good_value, float | int | np.floating) and not isinstance(
        good_value, bool)
    if label == "True" and number_meant:
        pytest.fail(f"{qualname} accepted True as the number {param}")
    if isinstance(good_value, bool) and label != "True":
        pytest.fail(f"{qualname} accepted {label} as the flag {param} (a flag is True or "
                    "False, not a truthy value)")


# ----------------------------------------------------------------------------- named cases

def test_the_cases_named_in_the_issue():
    from wheelkin import rover, waypoints

    segs = waypoints.plan_segments(waypoints.LAB_WAYPOINTS)
    with pytest.raises(ValueError, match="wheel_rate"):  # was a ZeroDivisionError
        waypoints.schedule(segs, 0.04, 0.06, wheel_rate=5e-324)
    with pytest.raises(ValueError, match="speed_in_per_s"):  # blamed `speed` before
        rover.document_twist(30.0, math.nan)
    with pytest.raises(ValueError, match="track_width"):  # True is not 1.0 m
        from wheelkin import diffdrive

        diffdrive.wheel_speeds([0.1, 0.2], [0.0, 1.0], True)
    with pytest.raises(ValueError, match="v"):  # nor is an array of booleans
        diffdrive.wheel_speeds([True, False], 0.0, 0.3)
    # near the 90 degree stop a corner on the ICR's line is at 90 degrees, with no warning
    stop = math.nextafter(math.pi / 2, 0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        angles = rover.corner_angles(rover.OSR_GEOMETRY.d1, max_corner_angle=stop)
    assert np.all(np.isfinite(angles)) and abs(angles[1]) == pytest.approx(math.pi / 2)


@pytest.mark.parametrize(("qualname", "fn"), [
    (q, f) for q, f in _public_callables() if q.startswith("carlike.")
    and any(p.kind is p.KEYWORD_ONLY for p in inspect.signature(f).parameters.values())])
def test_a_cars_lengths_given_by_position_are_a_type_error_naming_them(qualname, fn):
    """The valid call with every required argument given by position: a TypeError that says
    which parameters to name, not Python's count of positional arguments."""
    kwargs = _resolve(qualname, _good_call(qualname, fn, _good_values())
                      | OVERRIDES.get(qualname, {}))
    fn(**kwargs)  # valid by name
    params = [p for p in inspect.signature(fn).parameters.values() if p.name in kwargs]
    first_named = next(p.name for p in params if p.kind is p.KEYWORD_ONLY)
    with pytest.raises(TypeError, match=rf"{first_named}=\.\.\."):
        fn(*(kwargs[p.name] for p in params))


def _overflowing_calls():
    from wheelkin import diffdrive, mecanum, odometry

    g = mecanum.EXAMPLE_GEOMETRY
    return [
        ("wheel_speeds", lambda: diffdrive.wheel_speeds(1e308, 1e308, 10.0),
         "v, omega and track_width"),
        ("integrate_si", lambda: odometry.integrate_si([1e308, 1e308], [1e308, 1e308], 0.5),
         "delta_left, delta_right"),
        ("integrate_si pose", lambda: odometry.integrate_si([1e308], [1e308], 0.5,
                                                            pose=(1e308, 0.0, 0.0)),
         "and pose"),
        ("mecanum", lambda: mecanum.inverse_kinematics(1e308, 1e308, 0.0, g), "vx, vy, omega"),
        ("mecanum centre", lambda: mecanum.inverse_kinematics(
            0.0, 0.0, 1e308, g, centre_of_rotation=(1e308, 0.0)), "centre_of_rotation"),
        ("mecanum twist", lambda: mecanum.inverse_kinematics((1e308, 1e308, 0.0), g), "twist"),
    ]


@pytest.mark.parametrize(("label", "call", "names"), _overflowing_calls(),
                         ids=[c[0] for c in _overflowing_calls()])
def test_a_result_that_overflows_is_an_error_naming_the_inputs(label, call, names):
    """At 1e308 these returned inf or NaN (issue 23): now a ValueError, and no warning."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match=rf"{names}.* is out of range: the result overflows"):
            call()



@pytest.mark.parametrize("function", ["inverse_kinematics", "max_rim_speed"])
@pytest.mark.parametrize("label", [*BAD_VALUES, "Pose", "two", "component"])
def test_mecanum_twist_form_bad_input(label, function):
    """``inverse_kinematics(twist, geometry)``, the second form, with each bad value as the
    twist (and a Pose, two numbers, a lone number): a clean error naming ``twist``, or, for
    a value that broadcasts to a valid stack, a finite result."""
    from wheelkin import mecanum
    from wheelkin.frames import Pose

    value = {"Pose": Pose(0.0, 0.0, 0.0), "two": (1.0, 0.0), "component": 0.5}.get(
        label, BAD_VALUES.get(label))
    g = mecanum.EXAMPLE_GEOMETRY
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises((ValueError, TypeError), match=r"^twist\b"):
            getattr(mecanum, function)(value, g)
    for twist in ((value, 0.0, 0.0), (0.0, value, 0.0), (0.0, 0.0, value)):
        if label in ("Pose", "two", "component", "wrong-shape", "subnormal", "huge"):
            continue  # not a bad component of a tuple, or a valid one
        with pytest.raises((ValueError, TypeError), match=r"^twist\b"):
            getattr(mecanum, function)(twist, g)

def test_large_finite_inputs_still_give_the_formula():
    """Just below the overflow the same functions return the hand formula's values."""
    from wheelkin import diffdrive, mecanum, odometry

    left, right = diffdrive.wheel_speeds(1e300, 2.0, 0.5)  # v -+ omega W / 2
    assert (left, right) == (1e300 - 0.5, 1e300 + 0.5)
    path = odometry.integrate_si([1e300, 1e300], [1e300, 1e300], 0.5)
    assert path.tolist() == [[1e300, 0.0, 0.0], [2e300, 0.0, 0.0]]  # straight ahead
    g = mecanum.EXAMPLE_GEOMETRY
    rates = mecanum.inverse_kinematics(1e300, 0.0, 0.0, g)  # vx / r on every wheel
    assert rates.tolist() == pytest.approx([1e300 / g.wheel_radius] * 4, rel=1e-15)


@pytest.mark.parametrize(("call", "names"), [
    (lambda f: f.compose(np.zeros((3, 3)), np.zeros((2, 3))), ("pose", "delta")),
    (lambda f: f.relative(np.zeros((3, 3)), np.zeros((2, 3))), ("pose_from", "pose_to")),
    (lambda f: f.transform_points(np.zeros((3, 3)), np.zeros((2, 2))), ("pose", "points")),
], ids=["compose", "relative", "transform_points"])
def test_stacks_of_poses_that_do_not_match_name_both_parameters(call, names):
    """Three poses and two deltas: not NumPy's 'operands could not be broadcast'."""
    from wheelkin import frames

    with pytest.raises(ValueError, match=rf"^{names[0]} and {names[1]} must broadcast together"
                                         rf".*\(3, 3\)"):
        call(frames)


def test_stacks_that_broadcast_compose_pose_by_pose():
    """One pose and many deltas, or as many of each: row k is the single composition."""
    from wheelkin import frames

    rng = np.random.default_rng(7)
    poses, deltas = rng.normal(size=(4, 3)), rng.normal(size=(4, 3))
    many = frames.compose(poses, deltas)
    one = frames.compose(poses[0], deltas)
    for k in range(4):
        x, y, th = poses[k]
        dx, dy, dth = deltas[k]
        # by hand: rotate the delta into the world frame, add, wrap the heading
        expected = [x + math.cos(th) * dx - math.sin(th) * dy,
                    y + math.sin(th) * dx + math.cos(th) * dy,
                    math.atan2(math.sin(th + dth), math.cos(th + dth))]
        assert many[k] == pytest.approx(expected, abs=1e-12)
        assert one[k] == pytest.approx(frames.compose(poses[0], deltas[k]), abs=1e-12)


def test_flags_are_booleans_not_truthy_values():
    from wheelkin import mecanum

    with pytest.raises(ValueError, match="refuse"):
        mecanum.limit_speed((1.0, 0.0, 0.0), 2.0, refuse=1)
    with pytest.raises(ValueError, match="refuse"):
        mecanum.limit_speed((1.0, 0.0, 0.0), 2.0, refuse="yes")
    assert mecanum.limit_speed((3.0, 0.0, 0.0), 2.0, refuse=True).scale == 0.0
