"""The judge: an exercise's own check, run on the answers a student's function gave in its
sandbox, in a process of the grader's with its own time and memory limit.

The student's function never runs here: the check is given a stand-in that returns, call by
call, the recorded answers (numbers, ``None``, an exception's name and message), so its
diagnosis (wrong sign, swapped wheels, units, the exercise's own mistakes) reads as in the
notebook. A judge may itself be costly (``sandbox.grip_ramp_time`` runs the physics sandbox
for the ramp the student answered), so it runs in a separate process (``serve``) that the
grader kills when it goes over the exercise's ``judge_seconds``; its address space is capped
at the exercise's ``judge_memory``.
"""

from __future__ import annotations

import copy
import json
import os
import resource
import select
import subprocess
import sys
from pathlib import Path

import numpy as np

from tools.grading import wire

#: The repository (or the autograder's folder) whose tools package the judge process imports.
ROOT = Path(__file__).resolve().parents[2]


class _Opaque:
    """A returned object that is not a number (shown with the student's repr)."""

    def __init__(self, text: str) -> None:
        self.text = text

    def __repr__(self) -> str:
        return self.text

    def __float__(self):
        raise TypeError("not a number")


def replay(answers: list[dict], used: list[int]):
    """A stand-in for the student's function that gives back, call by call, its answers."""

    def fn(*args, **kwargs):
        answer = answers[len(used)]
        used.append(1)
        kind = answer["kind"]
        if kind == "not_written":
            raise NotImplementedError
        if kind == "raised":
            raise type(answer["ename"], (Exception,), {})(answer["evalue"])
        if kind == "none":
            return None
        if kind == "opaque":
            return _Opaque(answer["repr"])
        return np.array(answer["values"], dtype=float).reshape(answer["shape"])

    return fn


def judge(name: str, cases: list[dict], answers: list[dict]) -> dict:
    """The exercise's check on ``answers`` (one per case of ``cases``, wire-encoded):
    ``{"passed", "message", "kind", "at"}``, ``at`` the index of the case that failed."""
    from wheelkin.exercises import Case, get

    exercise = get(name)
    graded = copy.copy(exercise)  # its own class: an exercise may judge answers its way
    graded.cases = [Case(*wire.decode_case(c)) for c in cases]
    used: list[int] = []
    result = graded.check(replay(answers, used))
    return {"passed": bool(result.passed), "message": result.message, "kind": result.kind,
            "at": None if result.passed else max(0, len(used) - 1)}


def serve() -> int:
    """Answer judge requests, one JSON line in, one out, until stdin closes."""
    _, hard = resource.getrlimit(resource.RLIMIT_AS)
    for line in sys.stdin:
        request = json.loads(line)
        memory = int(request.get("memory", 2**31))
        resource.setrlimit(resource.RLIMIT_AS, (min(memory, hard) if hard > 0 else memory,
                                                hard))
        try:
            reply = judge(request["exercise"], request["cases"], request["answers"])
        except MemoryError:
            reply = {"error": "memory"}
        finally:
            resource.setrlimit(resource.RLIMIT_AS, (hard, hard))
        sys.stdout.write(json.dumps(reply) + "\n")
        sys.stdout.flush()
    return 0


class Judges:
    """The grader's side: one judge process, started when needed, killed and replaced when a
    verdict takes longer than its limit."""

    def __init__(self, src: Path) -> None:
        self.src = src
        self.proc: subprocess.Popen | None = None

    def _start(self) -> subprocess.Popen:
        env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), str(self.src)]),
               "MPLBACKEND": "Agg", "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
        return subprocess.Popen([sys.executable, "-m", "tools.grading.judge", "serve"],
                                stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                stderr=subprocess.DEVNULL, text=True, env=env,
                                start_new_session=True)

    def verdict(self, name: str, cases: list[dict], answers: list[dict], seconds: float,
                memory: int) -> dict:
        """The judge's reply, or ``{"error": "time"}`` / ``{"error": "memory"}``."""
        if self.proc is None or self.proc.poll() is not None:
            self.proc = self._start()
        request = {"exercise": name, "cases": cases, "answers": answers, "memory": memory}
        try:
            self.proc.stdin.write(wire.dumps(request) + "\n")
            self.proc.stdin.flush()
            ready, _, _ = select.select([self.proc.stdout], [], [], seconds)
            line = self.proc.stdout.readline() if ready else ""
        except (BrokenPipeError, OSError):
            line = ""
        if not line:
            timed_out = self.proc.poll() is None
            self.close()
            return {"error": "time" if timed_out else "memory"}
        return json.loads(line)

    def close(self) -> None:
        if self.proc is not None:
            if self.proc.poll() is None:
                self.proc.kill()
            self.proc.wait()
            for stream in (self.proc.stdin, self.proc.stdout):
                try:
                    stream.close()
                except OSError:
                    pass
            self.proc = None


if __name__ == "__main__":
    if sys.argv[1:] == ["serve"]:
        sys.exit(serve())
    sys.exit("usage: python -m tools.grading.judge serve")
