"""Exercises of the chapter "Driving to a pose" (notebooks/11_control/).

- ``control.polar_coordinates``: the distance and the two angles of the pose controller;
- ``control.kanayama``: Kanayama's tracking law from the error and the reference's twist;
- ``control.fails_on_car`` (a judgement): does a car's steering saturate at the end of the
  approach with these pose gains?
- ``control.parking_gains`` (a design): gains and a stop distance that park the Zumo from a
  set of starts with a noisy camera, driving in forwards and never turning its back on the
  bay. Judged by running the closed loop, not by comparing numbers.

SI units; the goal is the origin heading along +x.

>>> from wheelkin.exercises import check
>>> check("control.polar_coordinates", lambda x, y, theta: (0.0, 0.0, 0.0)).passed
False
>>> check("control.parking_gains", parking_gains).passed
True
>>> check("control.parking_gains", lambda noise: (3.0, 8.0, -1.5, 0.0)).passed
False
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from wheelkin import control
from wheelkin.exercises import UNIT_FACTORS, Case, CheckResult, Exercise, _fmt

__all__ = ["ParkingExercise", "fails_on_car", "kanayama", "parking_gains", "polar_coordinates"]

GOAL = (0.0, 0.0, 0.0)


# ------------------------------------------------------------------ 1. polar coordinates

def polar_coordinates(x: float, y: float, theta: float) -> NDArray[np.float64]:
    """(rho m, alpha rad, beta rad) of a robot at (x, y, theta) in the goal's frame, both
    angles wrapped to (-pi, pi]."""
    return np.array(control.polar_coordinates((x, y, theta), GOAL))


def _bearing_from_goal(x, y, theta):
    alpha = math.atan2(math.sin(math.atan2(y, x) - theta), math.cos(math.atan2(y, x) - theta))
    beta = -theta - alpha
    return np.array([math.hypot(x, y), alpha, math.atan2(math.sin(beta), math.cos(beta))])


def _no_wrap(x, y, theta):
    alpha = math.atan2(-y, -x) - theta
    return np.array([math.hypot(x, y), alpha, -theta - alpha])


def _beta_plus(x, y, theta):
    rho, alpha, _ = polar_coordinates(x, y, theta)
    beta = theta + alpha
    return np.array([rho, alpha, math.atan2(math.sin(beta), math.cos(beta))])


Exercise(
    "control.polar_coordinates",
    "The pose controller's (rho, alpha, beta) for a robot at (x, y, theta) in the goal's "
    "frame (m, m, rad); angles wrapped to (-pi, pi].",
    polar_coordinates,
    [Case((-1.0, 0.0, 0.0)), Case((-0.6, 0.4, 0.3)), Case((0.5, -0.2, 2.8)),
     Case((0.2, 0.7, -2.5))],
    wheel_names=("rho", "alpha", "beta"),
    mistakes=[
        (_bearing_from_goal, "alpha is the bearing of the goal seen from the robot: "
                             "atan2(-y, -x) - theta, not atan2(y, x) - theta (the robot seen "
                             "from the goal)."),
        (_no_wrap, "wrap both angles to (-pi, pi]: atan2(-y, -x) - theta can leave that "
                   "range."),
        (_beta_plus, "beta = -theta - alpha: the sum of the three angles theta + alpha + "
                     "beta is zero."),
    ],
)


# ------------------------------------------------------------------ 2. Kanayama

def kanayama(x_e: float, y_e: float, theta_e: float, v_r: float, omega_r: float, k_x: float,
             k_y: float, k_theta: float) -> NDArray[np.float64]:
    """Kanayama's (v m/s, omega rad/s) from the tracking error (x_e, y_e m, theta_e rad, the
    reference seen from the robot), the reference's v_r (m/s) and omega_r (rad/s), and the
    gains k_x (1/s), k_y (1/m^2), k_theta (1/m)."""
    # a robot at the origin, heading +x, sees the reference at (x_e, y_e, theta_e)
    tw = control.track_trajectory((0.0, 0.0, 0.0), (x_e, y_e, theta_e), (v_r, 0.0, omega_r),
                                  k_x, k_y, k_theta)
    return np.array([tw.vx, tw.omega])


def _no_vr_on_ky(x_e, y_e, theta_e, v_r, omega_r, k_x, k_y, k_theta):
    return np.array([v_r * math.cos(theta_e) + k_x * x_e,
                     omega_r + k_y * y_e + v_r * k_theta * math.sin(theta_e)])


def _theta_not_sin(x_e, y_e, theta_e, v_r, omega_r, k_x, k_y, k_theta):
    return np.array([v_r * math.cos(theta_e) + k_x * x_e,
                     omega_r + v_r * (k_y * y_e + k_theta * theta_e)])


def _no_cos(x_e, y_e, theta_e, v_r, omega_r, k_x, k_y, k_theta):
    return np.array([v_r + k_x * x_e,
                     omega_r + v_r * (k_y * y_e + k_theta * math.sin(theta_e))])


Exercise(
    "control.kanayama",
    "Kanayama's tracking law: (v, omega) from the error (x_e, y_e, theta_e), the reference's "
    "(v_r, omega_r) and the gains (k_x, k_y, k_theta).",
    kanayama,
    [Case((0.1, 0.05, 0.2, 0.3, 0.1, 2.0, 25.0, 10.0)),
     Case((-0.2, -0.1, 1.0, 0.5, -0.4, 1.0, 16.0, 8.0)),
     Case((0.0, 0.3, -0.7, 0.2, 0.0, 2.0, 4.0, 4.0))],
    wheel_names=("v", "omega"),
    mistakes=[
        (_no_vr_on_ky, "the lateral term is v_r k_y y_e: without v_r the law does not scale "
                       "with the reference's speed (and k_y has the wrong units)."),
        (_theta_not_sin, "Kanayama uses k_theta sin(theta_e), not k_theta theta_e: the same "
                         "for small errors, but the Lyapunov function needs the sine."),
        (_no_cos, "the feedforward speed is v_r cos(theta_e): the part of the reference's "
                  "motion along the robot's heading."),
    ],
)


# ------------------------------------------------------------------ 3. judgement: the car

def fails_on_car(k_rho: float, k_alpha: float, k_beta: float) -> float:
    """0.0 if the curvature a car driven by the pose controller with these (stable) gains
    asks for fades near the goal, 1.0 if it does not (it then grows without bound, and the
    steering saturates at the end, unless an angle root lies exactly at -k_rho): it fades
    when both angle roots lie left of -k_rho, k_alpha > 3 k_rho and k_alpha + k_beta < 2 k_rho."""
    fades = k_alpha > 3.0 * k_rho and k_alpha + k_beta < 2.0 * k_rho
    return 0.0 if fades else 1.0


def _first_only(k_rho, k_alpha, k_beta):
    return 0.0 if k_alpha > 3.0 * k_rho else 1.0


def _facing_margin(k_rho: float, k_alpha: float, k_beta: float) -> float:
    """k_alpha + 2 k_beta - 2 k_rho/pi (1/s): positive (with k_beta < 0), a robot that starts
    facing the goal keeps facing it (alpha-dot points inwards at |alpha| = pi/2 for every
    beta_g); Siegwart's k_alpha + 5/3 k_beta - 2 k_rho/pi > 0 does not suffice."""
    return k_alpha + 2.0 * k_beta - 2.0 / math.pi * k_rho


def _margin_rule(k_rho, k_alpha, k_beta):
    return 0.0 if _facing_margin(k_rho, k_alpha, k_beta) > 0 else 1.0


Exercise(
    "control.fails_on_car",
    "Judge: 0.0 if the car's curvature demand fades near the goal with the pose gains "
    "(k_rho, k_alpha, k_beta), 1.0 if it does not.",
    fails_on_car,
    [Case((3.0, 8.0, -3.0)), Case((1.0, 5.0, -4.0)), Case((3.0, 8.0, -1.5)),
     Case((0.5, 4.0, -3.4)), Case((1.0, 4.0, -1.0)), Case((1.0, 8.0, -9.0))],
    mistakes=[
        (_first_only, "k_alpha > 3 k_rho puts the roots' mean left of -k_rho, but one root "
                      "can still lie right of it: also k_alpha + k_beta < 2 k_rho."),
        (_margin_rule, "the margin k_alpha + 2 k_beta - 2 k_rho/pi says whether the robot "
                       "keeps facing the goal, not whether the angles shrink faster than the "
                       "distance."),
    ],
)


# ------------------------------------------------------------------ 4. design: parking

#: The parking task: starts facing the bay, the camera's noise (m, rad), the time limit and
#: period (s), the wheel-speed limit (m/s).
PARK_STARTS = np.array([[-0.6, 0.3, 0.0], [-0.4, 0.0, 1.0], [-0.3, -0.5, 0.9],
                        [-0.6, -0.3, 0.2], [0.47, -0.23, -3.14], [0.47, 0.0, -2.36],
                        [0.23, 0.23, 2.36], [0.47, -0.23, 2.36]])
PARK_NOISE = (0.001, math.radians(0.2))
PARK_TIME, PARK_PERIOD, PARK_SPEED = 15.0, 0.02, 0.3


def parking_gains(camera_noise: float) -> tuple[float, float, float, float]:
    """Design: (k_rho, k_alpha, k_beta, stop_distance) that park the Zumo when the camera's
    position noise is ``camera_noise`` (m, its heading noise 0.2 degrees): Siegwart's gains,
    whose margin k_alpha + 2 k_beta - 2 k_rho/pi > 0 keeps every start facing the bay, and a
    stop distance five times the noise."""
    return (3.0, 8.0, -1.5, 5.0 * camera_noise)


def _park(gains: tuple[float, float, float, float], noise: float) -> dict[str, Any]:
    """Run the parking task with the camera's position noise ``noise`` (m)."""
    from wheelkin.widgets.control import unicycle_commands

    kr, ka, kb, stop = gains
    rng = np.random.default_rng(2026)
    scale = np.array([noise, noise, PARK_NOISE[1]])

    def law(t, poses):
        seen = poses + rng.standard_normal(poses.shape) * scale
        return unicycle_commands(control.move_to_pose(seen, GOAL, kr, ka, kb,
                                                      direction="forward",
                                                      stop_distance=stop),
                                 max_wheel_speed=PARK_SPEED)

    path = control.simulate(law, PARK_STARTS, PARK_TIME, PARK_PERIOD)
    polar = control.polar_coordinates(path.reshape(-1, 3), GOAL)
    rho = polar.rho.reshape(path.shape[:2])
    alpha = np.where(rho > 0.02, np.abs(polar.alpha.reshape(path.shape[:2])), 0.0)
    worst_alpha = alpha.max(axis=0)
    end = path[-1]
    distance = np.hypot(end[:, 0], end[:, 1])
    heading = np.abs(np.arctan2(np.sin(end[:, 2]), np.cos(end[:, 2])))
    return {"turned": worst_alpha > math.pi / 2, "distance": distance, "heading": heading,
            "worst_alpha": worst_alpha}


class ParkingExercise(Exercise):
    """A design judged by running it: the student's gains must park every start of the task
    within 1 cm and 1 degree in 15 s, driving forwards, without the bay's bearing ever
    exceeding 90 degrees (further than 2 cm from the bay)."""

    def _passed(self) -> str:
        return (f"✔ {self.name}: all {len(PARK_STARTS)} starts park within 1 cm and 1° in "
                f"{PARK_TIME:g} s, facing the bay all the way, for both cameras (each run in "
                "closed loop with the noisy camera).")

    def _judge(self, case: Case, where: str, raw: Any) -> CheckResult | None:
        noise = float(case.args[0])
        try:
            gains = tuple(float(g) for g in raw)
        except (TypeError, ValueError):
            return self._fail("shape", f"for {where} you returned {raw!r}: return four "
                              "numbers (k_rho, k_alpha, k_beta, stop_distance)")
        if len(gains) != 4:
            return self._fail("shape", f"for {where} you returned {len(gains)} numbers: "
                              "return four, (k_rho, k_alpha, k_beta, stop_distance)")
        if not all(math.isfinite(g) for g in gains):
            return self._fail("nan", f"for {where} you returned {gains!r}: every number "
                              "must be finite")
        head = (f"for {where}, with (k_rho, k_alpha, k_beta, stop_distance) = "
                f"{_fmt(np.array(gains))}")
        got = np.array(gains)
        if gains[0] < 0 and gains[2] > 0:
            return self._fail("sign", f"{head}: the signs are wrong: k_rho > 0, "
                              "k_alpha > k_rho and k_beta < 0.")
        expected = np.array(self.reference(*case.args))
        if (not np.allclose(got, expected) and np.allclose(np.sort(got), np.sort(expected))):
            return self._fail("swapped", f"{head}: the right numbers, swapped: the "
                              "order is (k_rho, k_alpha, k_beta, stop_distance).")
        ratio = got / expected
        if np.allclose(ratio, ratio[0], rtol=1e-6) and not math.isclose(ratio[0], 1.0):
            for factor, text in UNIT_FACTORS:
                if math.isclose(ratio[0], factor, rel_tol=1e-4):
                    return self._fail("units", f"{head}: {text}")
        try:
            result = _park(gains, noise)  # type: ignore[arg-type]
        except ValueError as exc:
            return self._fail("specific", f"{head}: the controller refuses: {exc}")
        if np.any(result["turned"]):
            k = int(np.argmax(result["turned"]))
            margin = _facing_margin(*gains[:3])
            return self._fail("specific", f"{head}: the start {_fmt(PARK_STARTS[k])} turns its "
                              f"back on the bay (bearing up to "
                              f"{math.degrees(result['worst_alpha'][k]):.0f}°): the margin "
                              f"k_alpha + 2 k_beta - 2 k_rho/pi is {margin:.2f}, make it "
                              "positive (Siegwart's k_alpha + 5 k_beta/3 - 2 k_rho/pi > 0 is "
                              "not enough).")
        far = result["distance"] >= 0.01
        if np.any(far):
            k = int(np.argmax(far))
            why = ("the stop distance is larger than the tolerance" if gains[3] >= 0.01
                   else "the robot is too slow to arrive in time: larger gains")
            return self._fail("specific", f"{head}: the start {_fmt(PARK_STARTS[k])} ends "
                              f"{100 * result['distance'][k]:.1f} cm from the bay: {why}.")
        off = result["heading"] >= math.radians(1.0)
        if np.any(off):
            k = int(np.argmax(off))
            return self._fail("specific", f"{head}: the start {_fmt(PARK_STARTS[k])} reaches "
                              "the bay but ends "
                              f"{math.degrees(result['heading'][k]):.1f}° off its heading: "
                              "either the camera's noise decides the bearing near the goal "
                              "(stop driving, and only turn, within several times the noise), "
                              "or the angles settle too slowly (make them faster than the "
                              "distance: a larger k_alpha).")
        return None


ParkingExercise(
    "control.parking_gains",
    "Design: (k_rho, k_alpha, k_beta, stop_distance) that park the Zumo from every start "
    "facing the bay, within 1 cm and 1 degree in 15 s, seen by a camera of position noise "
    "camera_noise (m), never turning its back on the bay.",
    parking_gains,
    [Case((0.001,)), Case((0.0005,))],
)
