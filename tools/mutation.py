"""A small mutation test of the formula modules: does the unit-test suite notice a wrong formula?

Each mutant is one meaningful edit of one module (a sign flip, swapped wheels, a dropped factor,
a wrong wrap, an off-by-one in the C-integer emulation). For each, the library is copied to a
temporary directory, the edit applied there (the working tree is never touched), and the
module's own test files are run against the copy (``PYTHONPATH`` puts it first). A mutant is
*killed* when a test fails. Prints one line per mutant and the kill rate.

The set covers every formula module of ``wheelkin._registry.FORMULA_MODULES`` (the one list:
:func:`uncovered` names a module without a mutant, and the run refuses to start while there is
one), the arc and integer kernels, and the solver core of the sandbox's contact model
(``sandbox/contact.py``: the stick shortcut, the friction-cap and slip tolerances, Newton's
method, the stick/slip partitions, projected Gauss-Seidel, the dissipation objective).
Mutants that cannot change behaviour are not in the set; ``EQUIVALENT`` lists them with the
reason. Before any mutant, the unmutated library must pass the same tests.

A mutant names its test files by their stem (``frames`` is ``test_frames.py``), found in
whichever layer folder of ``tests/`` holds it.

Usage: ``python -m tools.mutation [--only SUBSTRING] [--timeout 300] [--check]``
(``make mutation``); ``--check`` only verifies that every mutant's text is in its module once.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# (module, tests, description, text in the module, its replacement); each text must occur once.
MUTANTS = [
    ("_kernels", "kernels odometry frames", "arc: sign of the lateral factor",
     "distance * (a * s + b * c)", "distance * (a * s - b * c)"),
    ("_kernels", "kernels odometry frames", "arc: series drops its second term",
     "1.0 - p2 / 6.0 + p2 * p2 / 120.0, p * (0.5", "1.0 + p2 * p2 / 120.0, p * (0.5"),
    ("_kernels", "kernels odometry frames", "arc: b without the factor 2",
     "return math.sin(p) / p, 2.0 * s * s / p", "return math.sin(p) / p, s * s / p"),
    ("_kernels", "kernels diffdrive odometry", "C division floors instead of truncating",
     "return q if (numerator >= 0) == (denominator > 0) else -q",
     "return q if (numerator >= 0) == (denominator > 0) else -q - 1"),
    ("_kernels", "kernels frames waypoints", "wrap: -pi stays -pi",
     "        if r <= -math.pi:\n            r += _TWO_PI\n        return min(r, math.pi)",
     "        return min(r, math.pi)"),
    ("_kernels", "kernels diffdrive follower", "desaturate: never scales",
     "over = biggest > limit", "over = biggest > 2 * limit"),
    ("frames", "frames", "se2_log: sign of the cross term",
     "out = ((h * dx + half * dy) / t, (-half * dx + h * dy) / t, phi / t)",
     "out = ((h * dx - half * dy) / t, (-half * dx + h * dy) / t, phi / t)"),
    ("frames", "frames", "pose_rate: y rate with a minus",
     "vx * s + vy * c, w + 0.0 * th", "vx * s - vy * c, w + 0.0 * th"),
    ("frames", "frames", "relative: headings added",
     "np.asarray(th1) - th0)", "np.asarray(th1) + th0)"),
    ("diffdrive", "diffdrive", "body twist: omega from left minus right",
     "_out((right - left) / w))", "_out((left - right) / w))"),
    ("diffdrive", "diffdrive", "skid steer: rear wheels swapped",
     "return SkidSteerWheelSpeeds(left, right, left, right)",
     "return SkidSteerWheelSpeeds(left, right, right, left)"),
    ("mecanum", "mecanum", "centre of rotation: sign of the shift",
     "vx_a, vy_a, w_a = shift_twist(vx_a, vy_a, w_a, c[0], c[1])",
     "vx_a, vy_a, w_a = shift_twist(vx_a, vy_a, w_a, -c[0], -c[1])"),
    ("mecanum", "mecanum", "desaturate: limit ignored",
     "return _kernels.desaturate(rates, V.positive(\"max_rate\", max_rate))",
     "return rates"),
    ("odometry", "odometry", "body motion: half track",
     "return BodyMotion(0.5 * (left + right), (right - left) / w)",
     "return BodyMotion(0.5 * (left + right), (right - left) / (2 * w))"),
    ("odometry", "odometry", "midpoint: heading at the start",
     "phi, length = theta + 0.5 * dth, ds", "phi, length = theta, ds"),
    ("rover", "rover", "REP-103 steering: document sign kept",
     "return RoverCommand(speeds, corners + 0.0)", "return RoverCommand(speeds, -corners + 0.0)"),
    ("rover", "rover", "wheel commands: speed without the cosine",
     "speeds = np.where(along == 0.0, across, along / np.cos(delta)) + 0.0",
     "speeds = np.where(along == 0.0, across, along) + 0.0"),
    ("follower", "follower waypoints", "pure pursuit: curvature halved",
     "curvature = 2.0 * left / (ahead * ahead + left * left)",
     "curvature = left / (ahead * ahead + left * left)"),
    ("follower", "follower waypoints", "reduced model: skid factor ignored",
     "dtheta = r * (mean_r - mean_l) / (self.track_width * self.skid_factor) * h",
     "dtheta = r * (mean_r - mean_l) / self.track_width * h"),
    ("units", "units", "rpm: per second instead of per minute",
     "RPM = 2.0 * math.pi / 60.0", "RPM = 2.0 * math.pi"),
    ("sources", "frames", "firmware pose: X kept as our y (not its negative)",
     "(y_fw * MM, _no_negative_zero(-x_fw * MM), th)",
     "(y_fw * MM, _no_negative_zero(x_fw * MM), th)"),
    ("sources", "frames", "mecanum twist: the document's rightward speed kept as leftward",
     "_no_negative_zero(-vx_doc * FOOT)", "_no_negative_zero(vx_doc * FOOT)"),
    ("sources", "frames", "rover twist: the document's radius sign kept",
     "big_r = np.where(straight, 1.0, -r * INCH)", "big_r = np.where(straight, 1.0, r * INCH)"),
    ("sources", "frames", "mecanum heading: clockwise read as counter-clockwise",
     "return _wrap(_no_negative_zero(math.pi / 2 - p))",
     "return _wrap(_no_negative_zero(p - math.pi / 2))"),
    ("odometry_uncertainty", "odometry_uncertainty", "covariance: wheel noise not per metre",
     "q = np.diag([kl * abs(left), kr * abs(right)])", "q = np.diag([kl, kr])"),
    ("odometry_uncertainty", "odometry_uncertainty", "jacobian: heading's effect on x reversed",
     "f_pose[..., 0, 2] = -dy", "f_pose[..., 0, 2] = dy"),
    ("odometry_uncertainty", "odometry_uncertainty", "monte carlo: variance used as the spread",
     "sd = np.sqrt(np.array([kl, kr]) * np.abs(np.stack([left, right], axis=-1)))",
     "sd = np.array([kl, kr]) * np.abs(np.stack([left, right], axis=-1))"),
    ("odometry_uncertainty", "odometry_uncertainty", "umbmark: sign of alpha from x",
     "alpha_x = -(cw[0] + ccw[0]) / (4.0 * length)",
     "alpha_x = (cw[0] + ccw[0]) / (4.0 * length)"),
    ("waypoints", "waypoints", "schedule: arc's yaw rate about the centre, not the outer wheel",
     "body_rate = outer_speed / (big_r + d)", "body_rate = outer_speed / big_r"),
    ("waypoints", "waypoints", "schedule: a turn in place timed on the whole axle",
     "duration = abs(seg.heading_change) * d / outer_speed",
     "duration = abs(seg.heading_change) * 2 * d / outer_speed"),
    ("waypoints", "waypoints", "quantise: rounds to the nearest period, not up",
     "n = math.ceil(c.duration / period - 1e-9)", "n = round(c.duration / period)"),
    ("waypoints", "waypoints", "average-encoder odometry: heading change doubled",
     "/ 2 / (2 * d)", "/ (2 * d)"),
    ("unified", "unified", "rolling row: a Swedish row not scaled by u.e",
     "return roller_row(w) / float(w.roller_axis @ w.rolling_direction)",
     "return roller_row(w)"),
    ("unified", "unified", "wheel rates: rim speeds not divided by the radius",
     "return (xi @ rolling_matrix(w).T) / radii", "return xi @ rolling_matrix(w).T"),
    ("unified", "unified", "mobility: steerability not capped by 2 - rank C1f",
     "delta_s = max(0, min(rank_s, 2 - rank_f))", "delta_s = max(0, rank_s)"),
    ("unified", "unified", "steering for a twist: lever of y with the wrong sign",
     "cx, cy = vx - omega * y, vy + omega * x", "cx, cy = vx + omega * y, vy + omega * x"),
    ("unified", "unified", "mecanum wheels: roller angles mirrored",
     "roller_angle=-float(s) * geometry.roller_angle",
     "roller_angle=float(s) * geometry.roller_angle"),
    ("carlike", "carlike", "bicycle: yaw rate with sin instead of tan",
     "v * np.tan(d) / L + 0.0], axis=-1)", "v * np.sin(d) / L + 0.0], axis=-1)"),
    ("carlike", "carlike", "ackermann: outer angle without the track",
     "np.arctan(L * t / (L + W * t)) + 0.0)", "np.arctan(L * t / L) + 0.0)"),
    ("carlike", "carlike", "ackermann pair: inner and outer radii swapped",
     "_out(np.arctan(L / (R - W / 2)) + 0.0)", "_out(np.arctan(L / (R + W / 2)) + 0.0)"),
    ("carlike", "carlike", "pure pursuit: curvature halved",
     "out = 2.0 * py / (px * px + py * py) + 0.0", "out = py / (px * px + py * py) + 0.0"),
    ("carlike", "carlike", "side slip: from the front axle instead of the rear",
     "np.arctan(lr * np.tan(d) / L) + 0.0)", "np.arctan((L - lr) * np.tan(d) / L) + 0.0)"),
    ("carlike", "carlike", "linkage: tie rod with one arm's projection",
     "    tie = W - 2.0 * a * math.sin(b)\n", "    tie = W - a * math.sin(b)\n"),
    ("nonholonomic", "nonholonomic", "Pfaffian rows: body-to-world rotation, not its inverse",
     "[[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]",
     "[[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]"),
    ("nonholonomic", "nonholonomic", "unicycle: sideways row with the wrong sign of x",
     "row = np.stack([-np.sin(th), np.cos(th), np.zeros_like(th)], axis=-1)",
     "row = np.stack([np.sin(th), np.cos(th), np.zeros_like(th)], axis=-1)"),
    ("nonholonomic", "nonholonomic", "diff drive: left rolling row with the right lever",
     "[c, s, -W / 2, -r, 0.0]", "[c, s, W / 2, -r, 0.0]"),
    ("nonholonomic", "nonholonomic", "car: front row's lever without cos(delta)",
     "math.cos(th + d), L * math.cos(d), 0.0]", "math.cos(th + d), L, 0.0]"),
    ("nonholonomic", "nonholonomic", "car fields: yaw rate with sin instead of tan",
     "np.tan(d) / L, zero], axis=-1)", "np.sin(d) / L, zero], axis=-1)"),
    ("nonholonomic", "nonholonomic", "bracket: the two terms in the other order",
     "return _directional(f2, names[1], q, a, step) - _directional(f1, names[0], q, b, step)",
     "return _directional(f1, names[0], q, b, step) - _directional(f2, names[1], q, a, step)"),
    ("nonholonomic", "nonholonomic", "bracket: the difference quotient's divisor halved",
     "- values[3]) / (12.0 * t)", "- values[3]) / (6.0 * t)"),
    ("nonholonomic", "nonholonomic", "flow: Runge-Kutta without the middle weights",
     "(k1 + 2.0 * k2 + 2.0 * k3 + k4)", "(k1 + k2 + k3 + k4)"),
    ("nonholonomic", "nonholonomic", "parking: the two backward moves swapped",
     "[-1.0, 0.0, -kappa], [-1.0, 0.0, kappa]]", "[-1.0, 0.0, kappa], [-1.0, 0.0, -kappa]]"),
    ("nonholonomic", "nonholonomic", "parking shift: 4 sin^2 instead of 8 sin^2",
     "out = 8.0 * half * half / kappa", "out = 4.0 * half * half / kappa"),
    ("nonholonomic", "nonholonomic", "wheel angle fields: the world-to-body rotation",
     "body_to_world = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])",
     "body_to_world = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])"),
    ("control", "control", "polar: bearing from the goal, not to it",
     "alpha = _wrap(np.arctan2(-y, -x) - theta)", "alpha = _wrap(np.arctan2(y, x) - theta)"),
    ("control", "control", "pose law: beta with the sign of alpha",
     "beta = _wrap(-theta - alpha)", "beta = _wrap(-theta + alpha)"),
    ("control", "control", "backwards: beta not turned half a turn",
     "np.where(back, _wrap(beta + math.pi), beta)", "np.where(back, beta, beta)"),
    ("control", "control", "gains: k_alpha > 0 accepted for k_alpha - k_rho > 0",
     "if not ka - kr > 0:", "if not ka > 0:"),
    ("control", "control", "line: the offset to the right counted positive",
     "return -s * dx + c * dy, _wrap(p[..., 2] - heading)",
     "return s * dx - c * dy, _wrap(p[..., 2] - heading)"),
    ("control", "control", "line: heading term without |v|",
     "- kt * abs(v) * e_theta", "- kt * v * e_theta"),
    ("control", "control", "Kanayama: k_y term without v_r",
     "omega = w_r + v_r * (ky * e_y + kt * np.sin(e_theta))",
     "omega = w_r + ky * e_y + v_r * kt * np.sin(e_theta)"),
    ("control", "control", "simulate: limits scale v only",
     "v, w = v * scale, w * scale", "v, w = v * scale, w"),
    ("motion_models", "motion_models", "odometry model: rot2 measured from the new heading",
     "rot2 = _wrap(after[..., 2] - before[..., 2] - rot1)",
     "rot2 = _wrap(after[..., 2] - rot1)"),
    ("motion_models", "motion_models", "variance of trans: alpha_4 on trans, not the turns",
     "a[2] * t2 + a[3] * (r1 + r2)", "a[2] * t2 + a[3] * (t2 + r2)"),
    ("motion_models", "motion_models", "density: Jacobian multiplied, not divided",
     "p = p / h_trans", "p = p * h_trans"),
    ("motion_models", "motion_models", "sampler: standard deviations used as variances",
     "sd = np.sqrt(_odometry_variances(a, rot1, trans, rot2))",
     "sd = np.asarray(_odometry_variances(a, rot1, trans, rot2))"),
    ("motion_models", "motion_models", "velocity sampler: final turn not scaled by dt",
     "th + g_hat * step], axis=-1)", "th + g_hat], axis=-1)"),
    ("odometry_fusion", "odometry_fusion", "EKF: the clone's cross term dropped",
     "aug[:3, 3] = aug[3, :3] = cross", "aug[:3, 3] = aug[3, :3] = 0.0"),
    ("odometry_fusion", "odometry_fusion", "EKF: innovation against the new heading alone",
     "innovation = z - (pose[2] - turn_before)", "innovation = z - pose[2]"),
    ("odometry_fusion", "odometry_fusion", "EKF: gyro variance left out of S",
     "s = float(h @ aug @ h) + r", "s = float(h @ aug @ h) + 0.0 * r + 1e-30"),
    ("odometry_fusion", "odometry_fusion", "NEES: the covariance not inverted",
     "w = np.linalg.solve(chol_b, e_b[..., None])[..., 0]",
     "w = (chol_b @ e_b[..., None])[..., 0]"),
    # -- the loop objects (kinematics.py, odometers.py)
    ("kinematics", "objects", "diff drive inverse: the wheels swapped",
     "left, right = v - w * self._half, v + w * self._half",
     "left, right = v + w * self._half, v - w * self._half"),
    ("kinematics", "objects", "diff drive forward: turn over half the track",
     "(right - left) / self.track_width", "(right - left) / self._half"),
    ("kinematics", "objects", "diff drive desaturate: scaled by the slower wheel",
     "biggest = abs(left) if abs(left) > abs(right) else abs(right)",
     "biggest = abs(left) if abs(left) < abs(right) else abs(right)"),
    ("kinematics", "objects", "mecanum inverse: centre of rotation's y with the wrong sign",
     "vx, vy = vx + w * cy, vy - w * cx", "vx, vy = vx - w * cy, vy - w * cx"),
    ("kinematics", "objects", "mecanum forward: vy from the wrong diagonal",
     "vy = 0.25 * self._tan * (-fl + fr + rl - rr)",
     "vy = 0.25 * self._tan * (fl - fr + rl - rr)"),
    ("kinematics", "objects", "car inverse: the inner wheel steered like the outer",
     "left = math.atan2(lk, 1.0 - kappa * self._half)",
     "left = math.atan2(lk, 1.0 + kappa * self._half)"),
    ("kinematics", "objects", "rover inverse: a corner's speed without 1/cos(delta)",
     "speed = along / math.cos(delta)", "speed = along"),
    ("odometers", "objects", "diff drive odometry: the turn's sign",
     "(dr - dl) / self._w, heading", "(dl - dr) / self._w, heading"),
    ("odometers", "objects", "odometry: increments taken as totals",
     "dl, dr = left - last_left, right - last_right", "dl, dr = left, right"),
    ("odometers", "objects", "arc step: the lateral factor halved",
     "cb = 2.0 * half * half / phi", "cb = half * half / phi"),
    ("odometers", "objects", "gyro: the reset's offset subtracted",
     "new_theta = heading + self._offset", "new_theta = heading - self._offset"),
    ("odometers", "objects", "mecanum odometry: lateral increment from the wrong diagonal",
     "self._t * (-a + b + c - d)", "self._t * (a - b + c - d)"),
    ("odometers", "objects", "car odometry: curvature with sin instead of tan",
     "curvature = math.tan(delta) / self._length", "curvature = math.sin(delta) / self._length"),
    ("odometers", "objects", "covariance: the heading's cross term counted once",
     "n00 = s00 + 2.0 * e0 * s02 + s22 * e0 * e0", "n00 = s00 + e0 * s02 + s22 * e0 * e0"),
]

# The contact solver (sandbox/contact.py): its solver core only (the stick shortcut, the
# tolerances, Newton, the partitions, projected Gauss-Seidel, acceptance, the objective).
CT = "contact_solver sandbox"
MUTANTS += [
    # -- the stick shortcut (ContactModel.solve)
    ("sandbox/contact", CT, "stick: lever arm of y with the wrong sign",
     "lx, ly = hx - py * hw, hy + px * hw", "lx, ly = hx + py * hw, hy + px * hw"),
    ("sandbox/contact", CT, "stick: lever arm of x with the wrong sign",
     "lx, ly = hx - py * hw, hy + px * hw", "lx, ly = hx - py * hw, hy - px * hw"),
    ("sandbox/contact", CT, "stick: friction circle checked on x only",
     "q = lx * lx + ly * ly", "q = lx * lx"),
    ("sandbox/contact", CT, "stick: roller impulse along the mirrored axis",
     "q = dx * lx + dy * ly", "q = dx * lx - dy * ly"),
    ("sandbox/contact", CT, "stick: cap 0.5 % too generous",
     "if q > cap2:", "if q > 1.01 * cap2:"),
    ("sandbox/contact", CT, "stick: yaw impulse ignores the free-flight spin",
     "mw * (w - xi_pred[2])", "mw * w"),
    ("sandbox/contact", CT, "stick: rolling consistency not checked",
     "if abs(dx * cx + dy * cy - coef * phi) > SLIP_TOLERANCE or (",
     "if False or ("),
    ("sandbox/contact", CT, "stick: contact velocity lever of y with the wrong sign",
     "cx, cy = u - py * w, v + px * w", "cx, cy = u + py * w, v + px * w"),
    ("sandbox/contact", CT, "stick: consistency cached across new rates",
     "if warm.consistent_key is not self or warm.consistent_rates != rates:",
     "if warm.consistent_key is not self:"),
    # -- tolerances
    ("sandbox/contact", CT, "cap tolerance 1e-4 instead of 1e-9",
     "CAP_TOLERANCE = 1e-9", "CAP_TOLERANCE = 1e-4"),
    ("sandbox/contact", CT, "slip tolerance 1e-4 m/s instead of 1e-9",
     "SLIP_TOLERANCE = 1e-9", "SLIP_TOLERANCE = 1e-4"),
    # -- Newton on the reduced problem (_newton) and its linear solve (_solve_small)
    ("sandbox/contact", CT, "newton: friction gradient of a two-row wheel reversed",
     "g[i] += c * (a0 * r0[i] + a1 * r1[i])", "g[i] -= c * (a0 * r0[i] + a1 * r1[i])"),
    ("sandbox/contact", CT, "newton: friction gradient of a one-row wheel reversed",
     "sg = c if s[w] > 0 else -c", "sg = c if s[w] < 0 else -c"),
    ("sandbox/contact", CT, "newton: stops after one iteration",
     "for _it in range(60):", "for _it in range(1):"),
    ("sandbox/contact", CT, "newton: convergence test 1e-3 instead of 1e-12",
     "if max(abs(v) for v in step) <= 1e-12 * (1.0 + max(abs(v) for v in y)):",
     "if max(abs(v) for v in step) <= 1e-3 * (1.0 + max(abs(v) for v in y)):"),
    ("sandbox/contact", CT, "newton: line search ignores the friction term",
     "return quad + sum(c * v for c, v in zip(caps, nrm, strict=True))", "return quad"),
    ("sandbox/contact", CT, "newton: undamped (every full step accepted)",
     "if value(y1, nrm1) <= f0 + 1e-4 * t * slope + 1e-15 * abs(f0):", "if True:"),
    ("sandbox/contact", CT, "solve_small: elimination adds the pivot row",
     "ar[j] -= f * ac[j]", "ar[j] += f * ac[j]"),
    ("sandbox/contact", CT, "solve_small: negative factors skipped",
     "            if f:\n", "            if f > 0:\n"),
    ("sandbox/contact", CT, "solve_small: back substitution skips a column",
     "for j in range(c + 1, d):\n            acc -=",
     "for j in range(c + 2, d):\n            acc -="),
    # -- partitions (_Partition, toggled, _partition_solve)
    ("sandbox/contact", CT, "partition: range instead of null space of the stuck rows",
     "N = vt[rank:].T", "N = vt[:rank].T"),
    ("sandbox/contact", CT, "partition: slip measured from minus the request",
     "self.s0_map = JS @ self.x0_map - PS", "self.s0_map = JS @ self.x0_map + PS"),
    ("sandbox/contact", CT, "partition: a toggled wheel always slips",
     "new[wheel] = not new[wheel]", "new[wheel] = True"),
    ("sandbox/contact", CT, "partition: inconsistent stuck wheels accepted",
     "if np.abs(res).max() > SLIP_TOLERANCE:", "if False:"),
    ("sandbox/contact", CT, "partition: friction along the slip",
     "friction = -(s * (P.caps / nrm)[:, None]).reshape(-1)",
     "friction = (s * (P.caps / nrm)[:, None]).reshape(-1)"),
    ("sandbox/contact", CT, "partition: stuck wheel over its cap accepted",
     "if per.max() > 1 + CAP_TOLERANCE:", "if per.max() > 1.5:"),
    ("sandbox/contact", CT, "partition: slipping wheels' friction not in the balance",
     "rhs = rhs - P.JS.T @ friction", "rhs = rhs + 0.0 * friction.sum()"),
    ("sandbox/contact", CT, "partition: slip speeds not reported",
     "speeds[P.slide] = nrm", "speeds[P.slide] = 0.0"),
    ("sandbox/contact", CT, "partition: a stalled Newton accepted",
     "if np.abs(miss).max() > 1e-9 * (1.0 + np.abs(M * (xi - xp)).max()):", "if False:"),
    # -- projected Gauss-Seidel (_pgs) and acceptance (_accept)
    ("sandbox/contact", CT, "pgs: a one-row wheel's impulse clamped to one sign",
     "l0 = min(cap, max(-cap, lam[i0] - Ainv[0][0] * s0))",
     "l0 = min(cap, max(0.0, lam[i0] - Ainv[0][0] * s0))"),
    ("sandbox/contact", CT, "pgs: a one-row wheel's update with the wrong sign",
     "l0 = min(cap, max(-cap, lam[i0] - Ainv[0][0] * s0))",
     "l0 = min(cap, max(-cap, lam[i0] + Ainv[0][0] * s0))"),
    ("sandbox/contact", CT, "pgs: a two-row wheel's disc twice too large",
     "if math.hypot(l0, l1) > cap:", "if math.hypot(l0, l1) > 2 * cap:"),
    ("sandbox/contact", CT, "pgs: the plain projection onto the disc, not the exact step",
     "l0, l1 = _disc_step(Ainv, l0, l1, cap)",
     "l0, l1 = l0 * cap / math.hypot(l0, l1), l1 * cap / math.hypot(l0, l1)"),
    ("sandbox/contact", CT, "disc step: Newton's step on the secular equation reversed",
     "        mu -= step\n", "        mu += step\n"),
    ("sandbox/contact", CT, "pgs: a one-row wheel moves the body on the wrong axis",
     "xi[1] += w0[1] * d0\n", "xi[1] += w0[0] * d0\n"),
    ("sandbox/contact", CT, "accept: slip flags dropped",
     "return ContactResult(xi.tolist(), guess, tuple(speeds.tolist()), method)",
     "return ContactResult(xi.tolist(), self.stick_flags, tuple(speeds.tolist()), method)"),
    # -- the objective
    ("sandbox/contact", CT, "objective: squared slip instead of its length",
     "c @ np.sqrt((s * s).sum(1))", "c @ (s * s).sum(1)"),
    ("sandbox/contact", CT, "objective: friction box instead of circle",
     "c @ np.sqrt((s * s).sum(1))", "c @ np.abs(s).sum(1)"),
    ("sandbox/contact", CT, "objective: kinetic term without the half",
     "value = float(0.5 * dx @", "value = float(dx @"),
    ("sandbox/contact", CT, "newton: curvature across the slip without 1/|s|",
     "cw = c * inv", "cw = c"),
    ("sandbox/contact", CT, "newton: no step limit at a slip's apex",
     "if 0 < root < t:\n                    t = root", "if False:\n                    t = root"),
    ("sandbox/contact", CT, "newton: the alternative start is not used at a kink",
     "        y = y_alt\n", "        pass\n"),
]


# Mutants left out because they cannot change what the solver answers (equivalent), each with
# its reason; kept here so that the next reader does not add them again.
EQUIVALENT = [
    ("sandbox/contact", "stick: lateral consistency not checked",
     "P phi is the least-squares twist and lateral rows ask for 0, so |lateral residual|^2 = "
     "-(J_roll xi).(rolling residual): both vanish together, to within the 1e-9 m/s tolerance"),
    ("sandbox/contact", "solve_small: no row pivoting",
     "H is symmetric positive definite: elimination without pivoting is exact and stable"),
]


def test_files(names: str) -> list[str]:
    """The test files named by stem (``"frames odometry"``), wherever under tests/ they are."""
    out = []
    for name in names.split():
        found = sorted((ROOT / "tests").rglob(f"test_{name}.py"))
        if len(found) != 1:
            raise SystemExit(f"mutation: test_{name}.py is in {len(found)} places under tests/")
        out.append(str(found[0]))
    return out


def uncovered() -> list[str]:
    """The formula modules (wheelkin._registry.FORMULA_MODULES) that no mutant edits."""
    from wheelkin._registry import FORMULA_MODULES

    mutated = {m[0] for m in MUTANTS}
    return [name for name in FORMULA_MODULES if name not in mutated]


def stale(mutants: list[tuple[str, str, str, str, str]]) -> list[str]:
    """The mutants whose text is not in their module exactly once."""
    out = []
    for module, _, what, old, _ in mutants:
        text = (ROOT / "src" / "wheelkin" / f"{module}.py").read_text(encoding="utf-8")
        if text.count(old) != 1:
            out.append(f"{module}: {what} (found {text.count(old)} times)")
    return out


def _pytest(src: Path, files: list[str], tmp: str, timeout: float) -> bool:
    """True if the test files pass against the library in ``src``."""
    env = dict(os.environ, PYTHONPATH=str(src), PYTHONDONTWRITEBYTECODE="1")
    try:
        proc = subprocess.run(
            [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider",
             "-o", "addopts=", "-W", "error", *files],
            cwd=tmp, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return False  # a hang is noticed too
    return proc.returncode == 0


def run(only: str | None, timeout: float) -> int:
    chosen = [m for m in MUTANTS if only is None or only in f"{m[0]} {m[2]}"]
    missing = uncovered()
    if missing:
        print(f"formula modules without a mutant (add some to MUTANTS): {', '.join(missing)}")
        return 2
    begin = time.perf_counter()
    # The unmutated library must pass the very tests that judge the mutants.
    files = sorted({f for m in chosen for f in test_files(m[1])})
    if not _pytest(ROOT / "src", files, str(ROOT), timeout):
        print("the unmutated library fails these tests; fix that first:\n  " + "\n  ".join(files))
        return 2
    killed, stale, per_module = 0, 0, {}
    width = max((len(m[0]) for m in chosen), default=6)  # the module column fits every name
    for module, tests, what, old, new in chosen:
        with tempfile.TemporaryDirectory() as tmp:
            src = Path(tmp) / "src"
            shutil.copytree(ROOT / "src", src, ignore=shutil.ignore_patterns("__pycache__"))
            path = src / "wheelkin" / f"{module}.py"
            text = path.read_text()
            if text.count(old) != 1:
                print(f"STALE    {module}: {what} (the text to mutate is not there once)")
                stale += 1
                continue
            path.write_text(text.replace(old, new))
            start = time.perf_counter()
            dead = not _pytest(src, test_files(tests), tmp, timeout)
            killed += dead
            tally = per_module.setdefault(module, [0, 0])
            tally[0] += 1
            tally[1] += dead
            print(f"{'killed ' if dead else 'SURVIVED'} {module:{width}s} {what} "
                  f"({time.perf_counter() - start:.0f} s)", flush=True)
    total = len(chosen) - stale
    print(f"\n{'module':{width}s}  mutants  killed")
    for module, (n, k) in per_module.items():
        print(f"{module:{width}s} {n:8d} {k:7d}")
    print(f"\nkilled {killed} of {total} mutants ({100 * killed / max(total, 1):.0f} %) in "
          f"{time.perf_counter() - begin:.0f} s; {len(EQUIVALENT)} equivalent mutants left out")
    if stale:
        print(f"{stale} mutants are stale: update their text to the module's")
    return 0 if killed == total and not stale else 1


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default=None)
    parser.add_argument("--timeout", type=float, default=300.0)
    parser.add_argument("--check", action="store_true",
                        help="only check that every mutant's text is in its module once")
    args = parser.parse_args()
    if args.check:
        problems = stale(MUTANTS) + [f"{m}: no mutant" for m in uncovered()]
        print("\n".join(problems) or f"{len(MUTANTS)} mutants, every formula module covered")
        raise SystemExit(1 if problems else 0)
    raise SystemExit(run(args.only, args.timeout))
