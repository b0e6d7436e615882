"""A small mutation test of the formula modules: does the unit-test suite notice a wrong formula?

Each mutant is one meaningful edit of one module (a sign flip, swapped wheels, a dropped factor,
a wrong wrap, an off-by-one in the C-integer emulation). For each, the library is copied to a
temporary directory, the edit applied there (the working tree is never touched), and the
module's own test files are run against the copy (``PYTHONPATH`` puts it first). A mutant is
*killed* when a test fails. Prints one line per mutant and the kill rate.

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
     "return _kernels.desaturate(rates, v.positive(\"max_rate\", max_rate))",
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


def run(only: str | None, timeout: float) -> int:
    chosen = [m for m in MUTANTS if only is None or only in f"{m[0]} {m[2]}"]
    killed = 0
    for module, tests, what, old, new in chosen:
        with tempfile.TemporaryDirectory() as tmp:
            src = Path(tmp) / "src"
            shutil.copytree(ROOT / "src", src, ignore=shutil.ignore_patterns("__pycache__"))
            path = src / "wheelkin" / f"{module}.py"
            text = path.read_text()
            if text.count(old) != 1:
                print(f"STALE    {module}: {what} (the text to mutate is not there once)")
                continue
            path.write_text(text.replace(old, new))
            files = [str(ROOT / "tests" / f"test_{t}.py") for t in tests.split()]
            env = dict(os.environ, PYTHONPATH=str(src), PYTHONDONTWRITEBYTECODE="1")
            start = time.perf_counter()
            try:
                proc = subprocess.run(
                    [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider",
                     "-o", "addopts=", "-W", "error", *files, str(path)],
                    cwd=tmp, env=env, capture_output=True, text=True, timeout=timeout)
                dead = proc.returncode != 0
            except subprocess.TimeoutExpired:
                dead = True  # a hang is noticed too
            killed += dead
            print(f"{'killed ' if dead else 'SURVIVED'} {module:10s} {what} "
                  f"({time.perf_counter() - start:.0f} s)", flush=True)
    total = len(chosen)
    print(f"\nkilled {killed} of {total} mutants ({100 * killed / max(total, 1):.0f} %)")
    return 0 if killed == total else 1


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default=None)
    parser.add_argument("--timeout", type=float, default=300.0)
    args = parser.parse_args()
    raise SystemExit(run(args.only, args.timeout))
