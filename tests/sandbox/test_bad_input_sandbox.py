"""Bad input in the sandbox: every public callable, record and method of ``wheelkin.sandbox``
(and the sandbox page's panel view), called with one argument at a time replaced by a bad
value (the sweep's values of tests/library/test_bad_input.py: NaN, +-inf, None, a string, True, an
empty and a wrong-shaped array, 5e-324 and 1e300).

Passing is a ValueError or TypeError whose message names a parameter of the callable, or a
finite result where the value is legitimately acceptable (``ACCEPTED`` declares each such
case). A call that only stores a command (``Robot.command_twist``, ``World.add``, ...) is
followed by two steps of the world, and the robot's state after them is the result: a value
accepted now must not turn into a NaN, an overflow or a traceback later. A boolean where a
number is meant must be refused, and a flag accepts only ``True`` and ``False``. The array
parameters that carry the physics (poses, twists, rates, angles, walls, limits) are also swept
one number at a time, the others valid (``ELEMENTS``).

Cases in the modules the coordinator is rewriting (vehicles, contact, car) that fail today are
marked ``xfail(strict=True)`` in ``COORDINATOR``: they turn red once fixed, and the mark goes.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import math
import traceback
import typing
import warnings
from functools import lru_cache

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from tests.library.test_bad_input import BAD_VALUES, _finite_leaves
from wheelkin.style import fixed_layout

SANDBOX_MODULES = ("world", "sensors", "render", "vehicles", "contact", "car", "runs")
#: Methods that take no argument, or only what a caller never passes (pymunk's callbacks).
NO_ARGUMENTS = {"remove", "close"}


# ----------------------------------------------------------------------------- valid calls

def _mod(name: str):
    """A module of the sandbox (``wheelkin.sandbox.car`` is also the name of a function)."""
    return importlib.import_module(f"wheelkin.sandbox.{name}")


@lru_cache(maxsize=1)
def _run():
    """A tiny run (three steps of the Radon Ulzer; shared by the calls that read one)."""
    from wheelkin import sandbox as sb

    world = sb.World(dt=1 / 60)
    world.add(sb.RADON_ULZER, twist=(0.2, 0.0, 0.5))
    return world.run(0.05)


def _world(spec=None, **kwargs):
    from wheelkin import sandbox as sb

    world = sb.World(dt=1 / 60, **kwargs)
    robot = world.add(spec or sb.RADON_ULZER, twist=(0.2, 0.0, 0.5))
    return world, robot


def _state(world, robot) -> tuple:
    """What a step leaves behind: the world's time and the robot's state and readings."""
    world.step(2)
    return (world.time, robot.pose, robot.twist, robot.wheel_rates, robot.wheel_angles,
            robot.slip_speed, robot.encoder_counts, robot.distance)


@lru_cache(maxsize=1)
def _ax():
    """One axes for every drawing of the sweep (each is taken off again: see ``drawn``)."""
    ax = Figure().add_subplot()
    ax.set_aspect("equal")
    return ax


def _good_values() -> dict:
    """A valid value for each parameter name of the sandbox's public callables."""
    from wheelkin import sandbox as sb

    contact = _mod("contact")
    spec = sb.RADON_ULZER
    traj = _run()
    return {
        # world
        "dt": 1 / 60, "walls": [((-1.0, -1.0), (1.0, -1.0))], "wall_thickness": 0.01,
        "wall_friction": 0.3, "spec": spec, "pose": (0.1, 0.2, 0.3), "twist": (0.2, 0.0, 0.5),
        "n": 2, "duration": 0.05, "record_every": 1, "rates": [1.0, 1.5], "left": 1.0,
        "right": 1.5, "angles": [0.1, -0.1, -0.1, 0.1], "vx": 0.2, "vy": 0.0, "omega": 0.5,
        "controller": lambda t, world: None,
        # sensors
        "steps_per_rev": 100.0, "noise": 0.5, "seed": 3, "step": [0, 1],
        "counts": [[1, 2], [3, -4]], "noise_density": 2e-4, "bias": 0.001,
        # render
        "steering": None, "show_icr": True, "labels": True, "color": "#1f77b4", "alpha": 1.0,
        "zorder": 3.0, "slipping": [False, True], "trajectory": traj, "plan": [[0, 0], [1, 0]],
        "extra_paths": {"odometry": [[0.0, 0.0], [0.01, 0.0]]}, "frames": 2, "trail": True,
        "title": "run", "figsize": (6.7, 4.2), "dpi": 100, "names": ["Radon"],
        "interval": 100.0, "limits": (-1.0, 1.0, -1.0, 1.0), "colors": 16, "dynamic": (),
        "func": lambda frame: [], "mu": 0.8,
        # runs
        "twist_at": lambda t: (0.2, 0.0, 0.5), "times": [0.0, 0.02, 0.05],
        "twists": [(0.0, 0.0, 0.0), (0.2, 0.0, 0.5), (0.2, 0.0, 0.5)], "ramp": 0.1,
        "commands": None, "wheels_of": None,
        # vehicles
        "name": "L", "position": (0.0, 0.05), "heading": 0.0, "kind": "fixed",
        "roller_angle": 0.785, "load_fraction": 0.5, "width": 0.01, "mass": 1.0,
        "inertia": 0.01, "body": spec.body, "wheels": spec.wheels, "encoder_noise": 0.0,
        "motor_time_constant": 0.0, "steered_names": None, "free_rolling": (),
        "load_fractions": (0.5, 0.5), "casters": False, "caster": True, "w": 0.5, "track_width": 0.1,
        "wheel_radius": 0.02, "caster_offset": 0.05, "caster_load": 0.2, "half_track": 0.06,
        "half_wheelbase": 0.05, "d1": 0.18, "d2": 0.27, "d3": 0.27, "d4": 0.26,
        "vertices": [(-0.1, -0.05), (0.1, -0.05), (0.1, 0.05), (-0.1, 0.05)],
        # contact
        "warm": contact._Warm(), "xi_pred": (0.2, 0.0, 0.5), "base": None, "method": "stick",
        # car
        "geometry": "ackermann", "arm_length": 0.04, "arm_angle": None, "delta": 0.2,
        "wheelbase": 0.33, "speed": 1.0, "lookahead": 0.3, "max_steering": 0.4,
        "rear_angles": [[0.0, 0.0], [1.0, 1.1]], "pose0": (0.0, 0.0, 0.0), "front_load": 0.5,
        "path": [[0.0, 0.0], [0.5, 0.0], [1.0, 0.1]], "t": 0.01,
    }


def _is_result(obj) -> bool:
    """A NamedTuple a function returns (an output, not an input: nothing to sweep)."""
    return isinstance(obj, type) and issubclass(obj, tuple) and obj.__bases__ == (tuple,)


def _public_callables():
    """(qualname, object) for each public function and class the sandbox defines (not its
    re-exports, not the NamedTuples it returns)."""
    for mod_name in SANDBOX_MODULES:
        mod = _mod(mod_name)
        for name in mod.__all__:
            obj = getattr(mod, name)
            if (callable(obj) and getattr(obj, "__module__", "") == mod.__name__
                    and not _is_result(obj)):
                yield f"{mod_name}.{name}", obj


def _entries():
    """qualname -> make: ``make()`` returns the callable to sweep: the public callable
    itself, a method bound to a fresh object, or a wrapper that steps the world after the
    call (its signature is the wrapped callable's)."""
    from wheelkin import sandbox as sb
    from wheelkin.widgets import sandbox as panel

    car, contact, render, sensors, world = (_mod(m) for m in ("car", "contact", "render",
                                                               "sensors", "world"))

    good = _good_values()
    rover = sb.OPEN_SOURCE_ROVER

    def after_step(method_name, spec=None, world_kwargs=None):
        def make():
            w, r = _world(spec, **(world_kwargs or {}))
            target = w if method_name in ("add", "step", "run") else r
            method = getattr(target, method_name)

            def call(**kwargs):
                out = method(**kwargs)
                if method_name == "run":
                    return out
                if method_name == "add":
                    return _state(w, out)
                return _state(w, r)

            call.__signature__ = inspect.signature(method)
            return call
        return make

    def world_then_step():
        def call(**kwargs):
            w = world.World(**kwargs)
            robot = w.add(sb.RADON_ULZER, twist=(0.2, 0.0, 0.5))
            return _state(w, robot)

        call.__signature__ = inspect.signature(world.World)
        return call

    def robot_then_step():
        w = world.World(dt=1 / 60)

        def call(**kwargs):
            robot = world.Robot(**kwargs)
            w.space.add(robot.body, robot.shape)
            w.robots.append(robot)
            return _state(w, robot)

        call.__signature__ = inspect.signature(world.Robot)
        return call

    def encoder_method(name):
        def make():
            enc = sensors.Encoder(2, 100.0, noise=0.5, seed=1)
            return getattr(enc, name)
        return make

    def gyro_method(name):
        def make():
            return getattr(sensors.Gyro(2e-4, 0.001, seed=1), name)
        return make

    def then(make, finish):
        """``make`` with its own signature, and ``finish`` applied to what it made."""
        def call(**kwargs):
            made = make(**kwargs)
            finish(made)
            return made

        call.__signature__ = inspect.signature(make)
        return call

    def drawn(make_drawing):
        """A drawing is taken off the shared axes once made (its artists were checked)."""
        return then(make_drawing, lambda drawing: drawing.remove())

    @lru_cache(maxsize=1)
    def drawing_update():
        drawing = render.draw_vehicle(_ax(), sb.RADON_ULZER, (0.0, 0.0, 0.0))
        return drawing.update

    @lru_cache(maxsize=1)
    def slip_view_update():
        fig = Figure(figsize=(6.0, 4.6), dpi=100, layout=fixed_layout())
        FigureCanvasAgg(fig)  # as the panel gives it
        view = panel.SlipView(fig)

        def call(mu, omega):
            view.update(mu, omega)
            return view.message.get_text()

        call.__signature__ = inspect.signature(view.update)
        return call

    def animation(make_animation):
        """An animation is started (its first frame set up, no image drawn): that runs the
        frame function once, and an animation deleted unstarted would warn."""
        return then(make_animation, lambda anim: anim._init_draw())

    def to_jshtml():
        fig = Figure(figsize=(1.0, 1.0), dpi=20)
        anim = render.SandboxAnimation(fig, lambda frame: [], frames=2, colors=4)
        anim._init_draw()  # started: an animation deleted unstarted warns
        return anim.to_jshtml

    def contact_method(name):
        def make():
            model = contact.ContactModel(sb.RADON_ULZER, (), 1 / 60)
            return getattr(model, name)
        return make

    def spec_method(name):
        return lambda: getattr(rover, name)

    def driver_call():
        w, r = _world(car.RC_CAR)
        driver = car.PurePursuitDriver(r, good["path"], 1.0, 0.3, 0.4)

        def call(t, world):
            driver(t, world)
            return _state(w, r)

        call.__signature__ = inspect.signature(driver.__call__)
        return call

    entries = {q: (lambda obj=obj: obj) for q, obj in _public_callables()}
    entries |= {
        "render.draw_vehicle": lambda: drawn(render.draw_vehicle),
        "render.VehicleDrawing": lambda: drawn(render.VehicleDrawing),
        "render.animate": lambda: animation(render.animate),
        "render.SandboxAnimation": lambda: animation(render.SandboxAnimation),
        "render.SandboxAnimation.to_jshtml": to_jshtml,
        "world.World": world_then_step,
        "world.Robot": robot_then_step,
        "world.World.add": after_step("add"),
        "world.World.step": after_step("step"),
        "world.World.run": after_step("run"),
        "world.Robot.set_wheel_rates": after_step("set_wheel_rates"),
        "world.Robot.set_side_rates": after_step("set_side_rates"),
        "world.Robot.set_steering": after_step("set_steering", rover),
        "world.Robot.command_twist": after_step("command_twist"),
        "sensors.Encoder.counts": encoder_method("counts"),
        "sensors.Encoder.angles": encoder_method("angles"),
        "sensors.Gyro.variance": gyro_method("variance"),
        "sensors.Gyro.turns": gyro_method("turns"),
        "render.VehicleDrawing.update": drawing_update,
        "widgets.sandbox.SlipView.update": slip_view_update,
        "widgets.sandbox.SlipView": lambda: panel.SlipView,
        "vehicles.VehicleSpec.steering_of": spec_method("steering_of"),
        "vehicles.VehicleSpec.wheels_at": spec_method("wheels_at"),
        "car.PurePursuitDriver.__call__": driver_call,
    }
    return entries


#: Valid arguments that differ from the shared table, by callable.
OVERRIDES = {
    "world.Robot": {"world": "_world"},
    "world.Robot.set_steering": {"angles": [0.1, -0.1, -0.1, 0.1]},
    "render.VehicleDrawing": {"ax": "_ax", "spec": "_rover", "color": "#1f77b4",
                              "show_icr": True, "labels": True, "alpha": 1.0, "zorder": 3.0},
    "render.draw_vehicle": {"ax": "_ax", "spec": "_rover", "steering": [0.1, -0.1, -0.1, 0.1],
                            "twist": (0.2, 0.0, 0.5),
                            "slipping": [False, True, False, False, True, False]},
    "render.VehicleDrawing.update": {"steering": None, "slipping": [False, True]},
    "render.animate": {"spec": "_radon"},
    "render.SandboxAnimation.to_jshtml": {"fps": 10.0, "default_mode": "loop"},
    "world.Trajectory": "_trajectory",
    "render.SandboxAnimation": {"fig": "_fig"},
    "sensors.Encoder": {"n": 2},
    "sensors.Encoder.counts": {"angles": [[0.1, 0.2], [0.3, -0.4]]},
    "sensors.Gyro.turns": {"t": [0.0, 0.02, 0.04], "heading": [0.0, 0.01, 0.015]},
    "widgets.sandbox.SlipView": {"fig": "_fig"},
    "vehicles.VehicleSpec": {"name": "spec", "mass": 0.25, "inertia": 0.001},
    "vehicles.VehicleSpec.steering_of": {"steering": [0.1, -0.1, -0.1, 0.1]},
    "vehicles.VehicleSpec.wheels_at": {"steering": [0.1, -0.1, -0.1, 0.1]},
    "vehicles.ideal_rates": {"table": "_table", "current": ()},
    "vehicles.polygon_inertia": {"mass": 1.0},
    "vehicles.ideal_commands": {"spec": "_rover", "steering": [0.0, 0.0, 0.0, 0.0]},
    "vehicles.mecanum": {"wheel_radius": 0.05, "half_wheelbase": 0.15, "half_track": 0.15},
    "vehicles.rover": {"wheel_radius": 0.06},
    "vehicles.diff_drive": {"caster_offset": 0.05},
    "contact.ContactModel": {"steering": (), "dt": 1 / 60},
    "contact.ContactModel.solve": {"rates": [10.0, 12.0]},
    "contact.ContactModel.retarget": {"steering": ()},
    "contact.ContactResult": {"twist": [0.2, 0.0, 0.5], "slipping": (False, False),
                              "slip_speed": (0.0, 0.0)},
    "contact.constraint_rows": {"steering": ()},
    "contact.dissipation_objective": {"xi": (0.2, 0.0, 0.5), "J": "_J", "b": "_b",
                                      "mass_diag": (0.25, 0.25, 0.001), "caps": "_caps",
                                      "rows_per_wheel": 2},
    "car.car": {"wheelbase": 0.33, "track_width": 0.27, "wheel_radius": 0.05},
    "car.Steering": {"geometry": "linkage", "arm_length": 0.04, "arm_angle": 0.3},
    "car.front_angles": {"steering": "_steering", "track_width": 0.27},
    "car.drive": {"robot": "_car_robot", "steering": "_steering"},
    "car.car_odometry": {"steering": [0.1, 0.1], "wheel_radius": 0.05},
    "car.PurePursuitDriver": {"robot": "_car_robot", "speed": 1.0, "steering": "_steering"},
    "car.PurePursuitDriver.__call__": {"world": None},
}


def _resolve(qualname: str, kwargs: dict) -> dict:
    """Fill the valid values that are objects made fresh for each call."""
    from wheelkin import sandbox as sb

    car, contact = _mod("car"), _mod("contact")
    makers = {
        "_world": lambda: sb.World(dt=1 / 60), "_ax": _ax, "_rover": lambda: sb.OPEN_SOURCE_ROVER,
        "_radon": lambda: sb.RADON_ULZER, "_fig": lambda: Figure(),
        "_steering": lambda: car.Steering("linkage"),
        "_car_robot": lambda: _world(car.RC_CAR)[1],
        "_J": lambda: contact.constraint_rows(sb.RADON_ULZER)[0],
        "_b": lambda: np.zeros(4), "_table": lambda: _mod("vehicles").command_table(
            sb.RADON_ULZER), "_caps": lambda: np.array([0.01, 0.01]),
    }
    out = {}
    for key, value in kwargs.items():
        out[key] = makers[value]() if isinstance(value, str) and value in makers else value
    if qualname == "car.PurePursuitDriver.__call__":
        out["world"] = None  # the driver reads its own robot; the world is for the protocol
    return out


def _signature(fn) -> inspect.Signature:
    return getattr(fn, "__signature__", None) or inspect.signature(fn)


def _good_call(qualname: str, fn, good: dict) -> tuple[dict, list[str]]:
    """Valid keyword arguments for ``fn`` and the names of the parameters to sweep: the
    required ones, those with a plain default (a number, a flag, a string, a tuple of them)
    and those given a valid value here (a controller, a plan, ...)."""
    kwargs, swept = {}, []
    overrides = OVERRIDES.get(qualname, {})
    if overrides == "_trajectory":  # a record: the fields of a real one
        traj = _run()
        overrides = {f.name: getattr(traj, f.name) for f in dataclasses.fields(traj)}
    for p in _signature(fn).parameters.values():
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD) or p.name == "self":
            continue
        if p.name in overrides:
            kwargs[p.name] = overrides[p.name]
        elif p.default is p.empty:
            if p.name not in good:
                raise KeyError(p.name)
            kwargs[p.name] = good[p.name]
        elif isinstance(p.default, bool | int | float | str):
            kwargs[p.name] = p.default
        elif p.default is None and good.get(p.name) is not None:
            kwargs[p.name] = good[p.name]
        elif p.default == () and p.name in good:
            kwargs[p.name] = good[p.name]
        elif isinstance(p.default, tuple) and p.default:  # a pose, a twist, a size
            kwargs[p.name] = good.get(p.name, p.default)
        else:
            continue
        swept.append(p.name)
    return kwargs, swept


def _valid(qualname: str, good: dict | None = None):
    entries = _ENTRIES
    fn = entries[qualname]()
    kwargs, swept = _good_call(qualname, fn, good or _good_values())
    return fn, _resolve(qualname, kwargs), swept


# ----------------------------------------------------------------------------- expectations

#: Bad values a callable legitimately accepts, with the reason: (qualname, param) -> labels.
ACCEPTED = {
    # Where a parameter's default is None (or ()), None (or an empty sequence) is valid and
    # accepted without being listed here; so is True for a flag, and an empty sequence where
    # the valid value is one (the steering of a vehicle without steered wheels).
    # An array of shape (2, 2, 2) is two walls, two frames, or two readings of two wheels.
    ("world.World", "walls"): {"wrong-shape"},
    ("render.animate", "walls"): {"wrong-shape"},
    ("runs.drive_twist", "walls"): {"wrong-shape"},
    ("render.SandboxAnimation", "frames"): {"wrong-shape"},
    ("sensors.Encoder.angles", "counts"): {"wrong-shape"},
    ("sensors.Encoder", "steps_per_rev"): {"None"},  # an ideal encoder
    ("world.Robot.set_steering", "angles"): set(),
    # No steering angles for a vehicle without steered wheels.
    ("render.VehicleDrawing.update", "steering"): {"empty"},
    # A title is any string.
    ("render.animate", "title"): {"str"},
    # A name is any non-empty string.
    ("vehicles.VehicleSpec", "name"): {"str"},
    ("car.car", "name"): {"str"},
    ("vehicles.diff_drive", "name"): {"str"},
    ("vehicles.skid_steer", "name"): {"str"},
    ("vehicles.mecanum", "name"): {"str"},
    ("vehicles.rover", "name"): {"str"},
    # World.run's controller protocol passes (t, world); the driver reads neither.
    ("car.PurePursuitDriver.__call__", "world"): set(BAD_VALUES),
    ("car.PurePursuitDriver.__call__", "t"): {"nan", "+inf", "-inf", "None", "str", "True",
                                             "empty", "wrong-shape"},
}

#: Cases of the modules being rewritten that fail today: (qualname, param) -> the labels of
#: BAD_VALUES that fail ("all": every one), each marked xfail(strict=True).
COORDINATOR: dict[tuple[str, str], str] = {
}


def _coordinator(qualname: str, param: str) -> set[str]:
    labels = COORDINATOR.get((qualname, param), "")
    return set(BAD_VALUES) if labels == "all" else set(labels.split())


def _calls():
    good = _good_values()
    for qualname in sorted(_ENTRIES):
        try:
            fn, kwargs, swept = _valid(qualname, good)
        except KeyError as exc:
            yield pytest.param(qualname, None, id=f"{qualname}-no-valid-call",
                               marks=pytest.mark.xfail(reason=f"no valid value for {exc}",
                                                       strict=True))
            continue
        del fn, kwargs
        for param in swept:
            for label in BAD_VALUES:
                marks = []
                if label in _coordinator(qualname, param):
                    module = qualname.split(".")[0]
                    marks = [pytest.mark.xfail(strict=True,
                                               reason=f"coordinator: sandbox/{module}.py")]
                yield pytest.param(qualname, (param, label), id=f"{qualname}-{param}-{label}",
                                   marks=marks)


_ENTRIES = _entries()
CALLS = list(_calls())


def _public_methods(cls) -> list[str]:
    out = []
    for name, member in vars(cls).items():
        if name.startswith("_") and name != "__call__":
            continue
        if isinstance(member, property | staticmethod | classmethod) or not callable(member):
            continue
        if name in NO_ARGUMENTS or len(inspect.signature(member).parameters) <= 1:
            continue
        out.append(name)
    return out


def test_every_public_callable_and_method_is_swept():
    """A new public function, class or method of the sandbox is in the sweep (or fails here)."""
    missing = []
    for qualname, obj in _public_callables():
        if qualname not in _ENTRIES:
            missing.append(qualname)
        if isinstance(obj, type) and typing.Protocol not in obj.__mro__:
            for method in _public_methods(obj):
                if f"{qualname}.{method}" not in _ENTRIES and method != "replace":
                    missing.append(f"{qualname}.{method}")
    assert not missing, missing


def test_every_swept_callable_has_a_valid_call():
    broken = []
    for qualname in sorted(_ENTRIES):
        try:
            fn, kwargs, _ = _valid(qualname)
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                out = fn(**kwargs)
        except Exception as exc:
            broken.append(f"{qualname}: {type(exc).__name__}: {exc}")
            continue
        if not _finite_leaves(out):
            broken.append(f"{qualname}: a valid call returned {out!r}")
    assert not broken, "\n".join(broken)


# ----------------------------------------------------------------------------- the sweep

def _is_flag(value) -> bool:
    return isinstance(value, bool)


@pytest.mark.parametrize(("qualname", "bad"), CALLS)
def test_bad_argument_gets_a_clean_error_or_a_finite_result(qualname, bad):
    problem = _problem(qualname, *bad)
    if problem:  # a one-line report: a traceback of each of hundreds of cases costs seconds
        pytest.fail(problem, pytrace=False)


def _where(exc: BaseException) -> str:
    frame = traceback.extract_tb(exc.__traceback__)[-1]
    return f"{frame.filename.rsplit('/', 1)[-1]}:{frame.lineno}"


def _problem(qualname: str, param: str, label: str, element: int | None = None) -> str | None:
    """What is wrong with calling ``qualname`` with the bad value ``label`` for ``param`` (or
    for its ``element``-th number, the others valid), or None if it is refused cleanly or
    legitimately accepted."""
    value = BAD_VALUES[label]
    fn, kwargs, _ = _valid(qualname)
    good_value = kwargs[param]
    names = [p for p in _signature(fn).parameters if p != "self"]
    call = f"{qualname}({param}={label})"
    if element is not None:
        flat = np.asarray(good_value, dtype=float).ravel().tolist()
        flat[element] = value
        value = np.array(flat, dtype=object).reshape(np.shape(good_value)).tolist()
        good_value = 0.0  # a number is meant
        call = f"{qualname}({param}[{element}]={label})"
    args = dict(kwargs) | {param: value}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            out = fn(**args)
        except (ValueError, TypeError) as exc:
            if not any(n in str(exc) for n in names):
                return (f"{call} raised {type(exc).__name__} naming no parameter of {names} "
                        f"(at {_where(exc)}): {exc}")
            return None
        except Exception as exc:
            return f"{call} leaked {type(exc).__name__} (at {_where(exc)}): {exc}"
    if qualname == "widgets.sandbox.SlipView.update":
        # a panel never raises: it writes the refusal into the figure, naming the slider
        if out and param not in out:
            return f"{call} showed {out!r}"
        if not out and label not in ("subnormal", "huge"):
            return f"{call}: accepted {label}"
        return None
    if not _finite_leaves(out):
        return f"{call} returned non-finite {out!r}"
    default = _signature(fn).parameters[param].default
    declared = label in ACCEPTED.get((qualname, param), ())
    accepted = declared or (value is None and default is None) or (
        label == "empty" and default == ()) or (label == "True" and _is_flag(good_value)) or (
        label == "empty" and isinstance(good_value, tuple | list) and not good_value)
    if _is_flag(good_value) and label != "True" and not accepted:
        return f"{call}: accepted {label} as a flag (a flag is True or False, not truthy)"
    number_meant = isinstance(good_value, float | int | np.floating) and not _is_flag(good_value)
    if label == "True" and number_meant and not declared:
        return f"{call}: accepted True as a number"
    if not accepted and label in ("nan", "+inf", "-inf", "None", "str", "True", "empty",
                                  "wrong-shape"):
        return f"{call}: accepted {label} (declare it in ACCEPTED if it is a valid value)"
    return None


#: Array parameters swept one number at a time (the others valid): (qualname, param).
ELEMENTS = [
    ("world.World.add", "pose"), ("world.World.add", "twist"), ("world.World", "walls"),
    ("world.Robot.set_wheel_rates", "rates"), ("world.Robot.set_steering", "angles"),
    ("sensors.Encoder.counts", "angles"), ("sensors.Encoder.angles", "counts"),
    ("render.draw_vehicle", "pose"), ("render.draw_vehicle", "twist"),
    ("render.draw_vehicle", "steering"), ("render.animate", "figsize"),
    ("render.animate", "limits"), ("render.animate", "plan"),
]
ELEMENT_LABELS = ("nan", "+inf", "-inf", "None", "str", "True", "subnormal", "huge")


def _element_calls():
    good = _good_values()
    for qualname, param in ELEMENTS:
        _, kwargs, _ = _valid(qualname, good)
        for element in range(np.size(kwargs[param])):
            for label in ELEMENT_LABELS:
                yield pytest.param(qualname, param, element, label,
                                   id=f"{qualname}-{param}[{element}]-{label}")


@pytest.mark.parametrize(("qualname", "param", "element", "label"), list(_element_calls()))
def test_one_bad_number_in_an_array_is_refused_or_computed(qualname, param, element, label):
    problem = _problem(qualname, param, label, element)
    if problem:
        pytest.fail(problem, pytrace=False)


def test_the_sweep_is_big_enough():
    """Every parameter that matters is swept (a lost override would drop it silently)."""
    counts: dict[str, int] = {}
    for case in CALLS:
        counts[case.values[0]] = counts.get(case.values[0], 0) + 1
    assert counts.get("world.World.run", 0) >= 3 * len(BAD_VALUES)
    assert counts.get("world.Robot.command_twist", 0) == 3 * len(BAD_VALUES)
    assert counts.get("render.animate", 0) >= 10 * len(BAD_VALUES)
    assert len(CALLS) >= 1000


# ----------------------------------------------------------------------------- named cases

def test_the_cases_that_leaked_before():
    """Each was an overflow, a NaN, an endless loop or a traceback from inside numpy."""
    from wheelkin import sandbox as sb

    sensors = _mod("sensors")
    world, robot = _world()
    with pytest.raises(ValueError, match="vx"):  # a RuntimeWarning (overflow) one step later
        robot.command_twist(1e300, 0.0, 0.0)
    with pytest.raises(ValueError, match="vx"):  # was 1 m/s
        robot.command_twist(True, 0.0, 0.0)
    with pytest.raises(ValueError, match="rates"):
        robot.set_wheel_rates([1e300, 1e300])
    with pytest.raises(ValueError, match="duration"):  # would have run for ever
        world.run(1e300)
    with pytest.raises(ValueError, match="dt"):  # an OverflowError in the first step
        sb.World(dt=1e300)
    with pytest.raises(ValueError, match="twist"):  # 8e297 m after two steps
        world.add(sb.RADON_ULZER, twist=(1e300, 0.0, 0.0))
    # a vehicle the contact solve cannot step: an OverflowError, an overflow in a square, a
    # singular matrix (for a rover of 1e6 kg and 1e-12 kg m^2)
    with pytest.raises(ValueError, match="mu"):
        world.add(sb.RADON_ULZER.replace(mu=1e300))
    with pytest.raises(ValueError, match="mass"):
        world.add(sb.RADON_ULZER.replace(mass=1e300))
    with pytest.raises(ValueError, match="inertia"):
        world.add(sb.RADON_ULZER.replace(inertia=1e300))
    with pytest.raises(ValueError, match="inertia"):
        world.add(sb.OPEN_SOURCE_ROVER.replace(mass=1e6, inertia=1e-12))
    with pytest.raises(ValueError, match="walls"):  # 'float' object is not iterable
        sb.World(walls=1e300)
    with pytest.raises(ValueError, match="n"):  # cannot convert float NaN to integer
        sensors.Encoder(math.nan, 100)
    with pytest.raises(ValueError, match="seed"):  # numpy's "expected non-negative integer"
        sensors.Encoder(2, 100, seed=-1)
    with pytest.raises(ValueError, match="angles"):  # a RuntimeWarning (invalid cast)
        sensors.Encoder(2, 100).counts([math.nan, 1.0], 0)
    with pytest.raises(ValueError, match="steps_per_rev"):  # counts beyond int64
        sensors.Encoder(2, 1e300)
    with pytest.raises(ValueError, match="step"):  # an IndexError from the noise table
        sensors.Encoder(2, 100, noise=0.5).counts([1.0, 1.0], -1)


def test_a_motor_lag_much_longer_than_the_step_keeps_the_mean_rate_exact():
    """Over one step from rate r towards the command c, a first-order lag tau averages
    c + (r - c) tau (1 - exp(-dt/tau)) / dt = c + (r - c) (1 - dt/(2 tau) + ...): for
    tau = 1e12 s the wheels keep r to 1e-15. Written as 1 - exp(-dt/tau), the factor lost
    its digits to rounding (a few per cent)."""
    from wheelkin import sandbox as sb

    dt, tau = 1 / 240, 1e12
    world = sb.World(dt=dt)
    robot = world.add(sb.RADON_ULZER.replace(motor_time_constant=tau), twist=(0.2, 0.0, 0.0))
    start = robot.wheel_rates.copy()
    robot.set_wheel_rates([0.0, 0.0])
    traj = world.run(dt)
    expected = start * (1.0 - dt / (2.0 * tau))
    np.testing.assert_allclose(traj.wheel_rates[-1], expected, rtol=1e-13)
    assert start[0] == pytest.approx(0.2 / sb.RADON_ULZER.driven_wheels[0].wheel_radius, rel=1e-12)
