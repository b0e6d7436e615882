"""A small mutation test of the formula modules: does the unit-test suite notice a wrong formula?

Each mutant is one meaningful edit of one module (a sign flip, swapped wheels, a dropped factor,
a wrong wrap, an off-by-one in the C-integer emulation). For each, the library is copied to a
temporary directory, the edit applied there (the working tree is never touched), and the
module's own test files are run against the copy (``PYTHONPATH`` puts it first). A mutant is
*killed* when a test fails. Prints one line per mutant and the kill rate.

The set covers the formula modules and the solver core of the sandbox's contact model
(``sandbox/contact.py``: the stick shortcut, the friction-cap and slip tolerances, Newton's
method, the stick/slip partitions, projected Gauss-Seidel, the dissipation objective).
Mutants that cannot change behaviour are not in the set; ``EQUIVALENT`` lists them with the
reason. Before any mutant, the unmutated library must pass the same tests.

Usage: ``python tools/mutation.py [--only SUBSTRING] [--timeout 300]`` (``make mutation``).
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
    ("frames", "frames", "relative: heading not wrapped",
     "wrap_angle(np.asarray(th1) - th0)", "np.asarray(th1) - th0"),
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
    begin = time.perf_counter()
    # The unmutated library must pass the very tests that judge the mutants.
    files = sorted({str(ROOT / "tests" / f"test_{t}.py") for m in chosen for t in m[1].split()})
    if not _pytest(ROOT / "src", files, str(ROOT), timeout):
        print("the unmutated library fails these tests; fix that first:\n  " + "\n  ".join(files))
        return 2
    killed, stale, per_module = 0, 0, {}
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
            dead = not _pytest(src, [str(ROOT / "tests" / f"test_{t}.py") for t in tests.split()],
                               tmp, timeout)
            killed += dead
            tally = per_module.setdefault(module, [0, 0])
            tally[0] += 1
            tally[1] += dead
            print(f"{'killed ' if dead else 'SURVIVED'} {module:15s} {what} "
                  f"({time.perf_counter() - start:.0f} s)", flush=True)
    total = len(chosen) - stale
    print("\nmodule            mutants  killed")
    for module, (n, k) in per_module.items():
        print(f"{module:17s} {n:7d} {k:7d}")
    print(f"\nkilled {killed} of {total} mutants ({100 * killed / max(total, 1):.0f} %) in "
          f"{time.perf_counter() - begin:.0f} s; {len(EQUIVALENT)} equivalent mutants left out")
    if stale:
        print(f"{stale} mutants are stale: update their text to the module's")
    return 0 if killed == total and not stale else 1


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default=None)
    parser.add_argument("--timeout", type=float, default=300.0)
    args = parser.parse_args()
    raise SystemExit(run(args.only, args.timeout))
