"""Exercises with automatic checks that explain what is wrong.

A student writes a function in a notebook cell; :func:`check` runs it on well-chosen cases
against the library's answer and reports, in plain words, the first thing that is wrong: the
function is not written yet, it raised, it returned the wrong shape or a NaN, it has the wrong
sign, the wheels swapped, the wrong units, or a mistake specific to the exercise. It never
shows a traceback and never raises: a notebook cell that calls it always runs.

Each chapter registers its exercises in a module of this package (``wheelkin.exercises.rover``
and so on); :func:`get` finds one by name, loading those modules on first use.

The instructor's grader (``tools/grade.py``) uses three more things an exercise declares:

- ``library``: the parts of ``wheelkin`` the student's function may use (dotted names such as
  ``"wheelkin.carlike.linkage_error"``; none by default). The grader calls the student's
  function where only these parts, and what they need, can be imported; the exercise's
  statement must say so.
- ``hidden``: a function of a random generator that returns the hidden cases (inputs the
  notebook does not show). By default :meth:`Exercise.hidden_cases` varies the visible cases'
  floats; an exercise whose inputs are whole numbers, words or arrays gives its own.
- ``judge_seconds`` and ``judge_memory`` (class attributes): the time and memory the grader
  grants the exercise's judge; an exercise that judges by simulating raises them.

>>> def ref(x):
...     return 2.0 * x
>>> ex = Exercise("demo.double", "Double a number.", ref, [Case((1.0,)), Case((3.0,))],
...               register=False)
>>> ex.check(lambda x: 2 * x).passed
True
>>> print(ex.check(lambda x: -2 * x).message)
✘ demo.double: for x=1 you returned -2, expected 2: the sign is wrong.
>>> print(ex.check(lambda x: 1 / 0).message)
✘ demo.double: for x=1 your function raised ZeroDivisionError: division by zero
"""

from __future__ import annotations

import copy
import inspect
import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from wheelkin._registry import load_chapter_modules

__all__ = [
    "UNIT_FACTORS",
    "Case",
    "CheckResult",
    "Exercise",
    "HiddenCases",
    "all_exercises",
    "check",
    "get",
]

#: Ratios (student / expected) that betray a unit mix-up, with the words that explain it.
UNIT_FACTORS: tuple[tuple[float, str], ...] = (
    (1000.0, "a factor of 1000 too large: millimetres for metres, or mrad for rad?"),
    (1e-3, "a factor of 1000 too small: metres for millimetres, or rad for mrad?"),
    (25.4, "a factor of 25.4 too large: millimetres where inches were meant?"),
    (1 / 25.4, "a factor of 25.4 too small: inches where millimetres were meant?"),
    (0.0254, "a factor of 0.0254: metres where inches were meant?"),
    (1 / 0.0254, "a factor of 39.37: inches where metres were meant?"),
    (12.0, "a factor of 12: inches where feet were meant?"),
    (1 / 12.0, "a factor of 1/12: feet where inches were meant?"),
    (0.3048, "a factor of 0.3048: metres where feet were meant?"),
    (1 / 0.3048, "a factor of 3.28: feet where metres were meant?"),
    (180 / math.pi, "a factor of 57.3: degrees where radians were meant?"),
    (math.pi / 180, "a factor of 1/57.3: radians where degrees were meant?"),
    (2.0, "a factor of 2 too large: a diameter for a radius, or a full width for a half?"),
    (0.5, "a factor of 2 too small: a radius for a diameter, or a half width for a full?"),
    (2 * math.pi, "a factor of 2π: revolutions and radians mixed up?"),
    (1 / (2 * math.pi), "a factor of 1/2π: radians and revolutions mixed up?"),
)

_REGISTRY: dict[str, Exercise] = {}
#: Modules of this package that hold a chapter's exercises (imported on first lookup).
CHAPTER_MODULES = ("conventions", "rover", "mecanum", "diffdrive", "odometry", "waypoints",
                   "unified", "carlike", "sandbox", "controllability", "control")


@dataclass(frozen=True)
class Case:
    """One input to try: positional ``args`` and keyword ``kwargs``."""

    args: tuple = ()
    kwargs: dict = field(default_factory=dict)

    def describe(self, names: Sequence[str]) -> str:
        parts = [f"{n}={_fmt(v)}" for n, v in zip(names, self.args, strict=False)]
        parts += [f"{k}={_fmt(v)}" for k, v in self.kwargs.items()]
        return ", ".join(parts) if parts else "no arguments"


@dataclass(frozen=True)
class CheckResult:
    """What :meth:`Exercise.check` found. ``passed`` is True when every case agreed."""

    name: str
    passed: bool
    message: str
    kind: str  # "pass", "not-written", "raised", "shape", "nan", "sign", "swapped",
    #            "units", "specific", "wrong"

    def __bool__(self) -> bool:
        return self.passed

    def __repr__(self) -> str:
        return self.message

    def _repr_html_(self) -> str:
        import html

        colour = "#1a7f37" if self.passed else "#b35900"
        return (f'<div class="wheelkin-check" style="color:{colour};font-weight:600">'
                f"{html.escape(self.message)}</div>")

    def assert_passed(self) -> None:
        """Raise ``AssertionError`` with the message unless the check passed (for tests)."""
        if not self.passed:
            raise AssertionError(self.message)


#: An exercise's own hidden cases: a function of a NumPy random generator (seeded by the grader
#: from a secret drawn per grading run) that returns the cases to try.
HiddenCases = Callable[[np.random.Generator], Sequence[Case]]


class Exercise:
    """An exercise: a reference function and the cases on which a student's answer is tried.

    Parameters
    ----------
    name : str
        Unique, ``chapter.short_name``.
    prompt : str
        One sentence: what the function must compute, with units.
    reference : callable
        The right answer, usually a library function (or a thin wrapper of one).
    cases : list of Case
        Inputs to try, in order; choose them so that common mistakes show (a right turn and a
        left turn, unequal dimensions, a non-zero angular rate ...).
    wheel_names : sequence of str, optional
        Names of the elements of a vector answer (e.g. ``("FL", "FR", "RL", "RR")``), so that
        swapped elements can be named.
    mistakes : sequence of (callable, str), optional
        Exercise-specific wrong answers: if the student's output matches ``callable(*args)``
        the message ``str`` is shown.
    rtol, atol : float
        Tolerances of the comparison.
    library : sequence of str, optional
        The parts of ``wheelkin`` the student's function may use when graded, as dotted names
        (``"wheelkin.carlike.linkage_error"``, ``"wheelkin.exercises.unified.CANDIDATES"``);
        the grader makes only these (and what they need) importable. Default: none, the
        student writes everything. The exercise's statement must name them.
    hidden : callable, optional
        ``hidden(rng)`` returns the hidden cases, drawn with the NumPy generator ``rng``. Give
        it when the inputs are not floats to vary (whole numbers, words, arrays, a finite
        set); by default :meth:`hidden_cases` varies the visible cases' floats.

    Attributes
    ----------
    judge_seconds, judge_memory : float, int
        The grader's limits for judging one student's answers to every case (seconds, bytes).
        A subclass whose judge runs a simulation sets larger ones.
    """

    #: Seconds the grader grants :meth:`check` on the recorded answers (every case).
    judge_seconds: float = 10.0
    #: Bytes of memory the grader grants the judge.
    judge_memory: int = 2 * 2**30

    def __init__(
        self,
        name: str,
        prompt: str,
        reference: Callable,
        cases: Sequence[Case],
        *,
        wheel_names: Sequence[str] | None = None,
        mistakes: Sequence[tuple[Callable, str]] = (),
        rtol: float = 1e-6,
        atol: float = 1e-9,
        library: Sequence[str] = (),
        hidden: HiddenCases | None = None,
        register: bool = True,
    ) -> None:
        if not cases:
            raise ValueError("cases must contain at least one Case")
        for part in library:
            if not (isinstance(part, str) and part.startswith("wheelkin.")
                    and part.count(".") >= 2):
                raise ValueError("library must name parts of wheelkin as "
                                 f"'wheelkin.module.name', got {part!r}")
        self.name = name
        self.prompt = prompt
        self.reference = reference
        self.cases = list(cases)
        self.wheel_names = tuple(wheel_names) if wheel_names else None
        self.mistakes = list(mistakes)
        self.rtol = rtol
        self.atol = atol
        self.library = tuple(library)
        self.hidden = hidden
        try:
            self.arg_names = list(inspect.signature(reference).parameters)
        except (TypeError, ValueError):  # pragma: no cover - builtins without a signature
            self.arg_names = []
        if register:
            if name in _REGISTRY:
                raise ValueError(f"an exercise named {name!r} is already registered")
            _REGISTRY[name] = self

    def __repr__(self) -> str:
        return f"Exercise({self.name!r}: {self.prompt})"

    def _close(self, got: np.ndarray, expected: np.ndarray) -> bool:
        return got.shape == expected.shape and bool(
            np.allclose(got, expected, rtol=self.rtol, atol=self.atol)
        )

    def _fail(self, kind: str, text: str) -> CheckResult:
        return CheckResult(self.name, False, f"✘ {self.name}: {text}", kind)

    def _answer(self, fn: Callable, case: Case, where: str) -> Any:
        """The student's answer to one case (on copies of its arguments), or the
        :class:`CheckResult` that says why there is none: not written, raised, returned None."""
        try:
            raw = fn(*copy.deepcopy(case.args), **copy.deepcopy(case.kwargs))
        except NotImplementedError:
            return self._fail("not-written", "not written yet: replace the "
                              "line 'raise NotImplementedError' with your code, then run the "
                              "check again.")
        except Exception as exc:
            return self._fail("raised",
                              f"for {where} your function raised {type(exc).__name__}: {exc}")
        if raw is None:
            return self._fail("shape", f"for {where} your function returned None: did you "
                              "forget the 'return'?")
        return raw

    def check(self, fn: Callable) -> CheckResult:
        """Try ``fn`` on every case; return the first problem found, or a pass."""
        if not callable(fn):
            return self._fail("raised", f"expected a function, got {type(fn).__name__}")
        for case in self.cases:
            where = case.describe(self.arg_names)
            raw = self._answer(fn, case, where)
            try:
                problem = raw if isinstance(raw, CheckResult) else self._judge(case, where, raw)
            except MemoryError:  # the grader's judge reports its own memory limit
                raise
            except Exception as exc:  # an answer the judge cannot even handle
                problem = self._fail("wrong", f"for {where} your answer {_fmt(raw)} could not "
                                     f"be checked ({type(exc).__name__}: {exc})")
            if problem is not None:
                return problem
        return CheckResult(self.name, True, self._passed(), "pass")

    def hidden_cases(self, rng: np.random.Generator, per_case: int = 2) -> list[Case]:
        """Cases the student never sees, drawn with ``rng``.

        The exercise's own ``hidden(rng)`` when it has one; otherwise each visible case
        ``per_case`` times with its floats changed by 5-25 %, each kept inside the range the
        visible cases span for that argument (so that a hidden case stays in the regime the
        exercise asks about: a turn stays a turn, a limit is not crossed); whole numbers,
        words and infinite values are kept. A case that repeats a visible one, or whose
        reference answer is not defined (raises, NaN, a different shape than its visible
        case's), is dropped.

        >>> ex = Exercise("demo.half", "Half.", lambda x: x / 2, [Case((1.0,)), Case((3.0,))],
        ...               register=False)
        >>> hidden = ex.hidden_cases(np.random.default_rng(1))
        >>> len(hidden), all(1.0 <= c.args[0] <= 3.0 for c in hidden)
        (4, True)
        """
        seen = {repr(c) for c in self.cases}
        if self.hidden is not None:
            out = []
            for case in self.hidden(rng):
                if not isinstance(case, Case):
                    raise TypeError(f"{self.name}: hidden(rng) must return Case objects, got "
                                    f"{type(case).__name__}")
                if repr(case) not in seen and _defined(self, case) is not None:
                    seen.add(repr(case))
                    out.append(case)
            return out
        hulls = _hulls(self.cases)
        out = []
        for case in self.cases:
            base = _defined(self, case)
            if base is None:  # pragma: no cover - a visible case the reference rejects
                continue
            for _ in range(per_case):
                args = tuple(_perturb(v, 1.0 + rng.uniform(0.05, 0.25), hulls.get(i))
                             for i, v in enumerate(case.args))
                kwargs = {k: _perturb(v, 1.0 + rng.uniform(0.05, 0.25), hulls.get(k))
                          for k, v in case.kwargs.items()}
                new = Case(args, kwargs)
                if repr(new) in seen:
                    continue  # nothing could change
                want = _defined(self, new)
                if want is None or want.shape != base.shape:
                    continue
                if np.any(~np.isfinite(want) & np.isfinite(base)):
                    continue
                seen.add(repr(new))
                out.append(new)
        return out

    def _passed(self) -> str:
        """The message of a check that every case passed."""
        return f"✔ {self.name}: correct on all {len(self.cases)} cases."

    def _judge(self, case: Case, where: str, raw: Any) -> CheckResult | None:
        """None if the answer ``raw`` to ``case`` is right, else the diagnosis: here, by
        comparing it with the reference's answer (subclasses may judge otherwise)."""
        expected = _as_array(self.reference(*case.args, **case.kwargs))
        try:
            got = _as_array(raw)
        except (TypeError, ValueError):
            return self._fail("shape", f"for {where} you returned {raw!r}, which is not a "
                              "number or an array of numbers")
        if got.shape != expected.shape:
            return self._fail("shape", f"for {where} you returned shape {got.shape} "
                              f"({_fmt(raw)}), expected shape {expected.shape}")
        if np.any(np.isnan(got)) or np.any(np.isinf(got) & np.isfinite(expected)):
            return self._fail("nan", f"for {where} your answer contains NaN or infinity: "
                              f"{_fmt(got)}")
        if self._close(got, expected):
            return None
        return self._diagnose(case, where, got, expected)

    def _diagnose(self, case: Case, where: str, got: np.ndarray,
                  expected: np.ndarray) -> CheckResult:
        head = f"for {where} you returned {_fmt(got)}, expected {_fmt(expected)}"
        for wrong, text in self.mistakes:
            try:
                candidate = _as_array(wrong(*copy.deepcopy(case.args),
                                            **copy.deepcopy(case.kwargs)))
            except Exception:  # a mistake model that cannot run on this case is skipped
                continue
            if self._close(got, candidate):
                return self._fail("specific", f"{head}: {text}")
        if np.any(expected != 0) and self._close(got, -expected):
            return self._fail("sign", f"{head}: the sign is wrong.")
        if got.ndim == 1 and got.size > 1:
            swap = self._find_swap(got, expected)
            if swap:
                return self._fail("swapped", f"{head}: {swap}")
            if np.any(expected != 0) and np.allclose(np.abs(got), np.abs(expected),
                                                     rtol=self.rtol, atol=self.atol):
                bad = [self._label(i) for i in range(got.size)
                       if not np.isclose(got[i], expected[i], rtol=self.rtol, atol=self.atol)]
                return self._fail("sign", f"{head}: the sizes are right but the sign of "
                                  f"{', '.join(bad)} is wrong.")
        ratio = _common_ratio(got, expected)
        if ratio is not None:
            for factor, text in UNIT_FACTORS:
                if math.isclose(ratio, factor, rel_tol=1e-4):
                    return self._fail("units", f"{head}: {text}")
        return self._fail("wrong", f"{head}.")

    def _label(self, i: int) -> str:
        if self.wheel_names and i < len(self.wheel_names):
            return self.wheel_names[i]
        return f"element {i}"

    def _find_swap(self, got: np.ndarray, expected: np.ndarray) -> str | None:
        n = got.size
        for i, j in itertools.combinations(range(n), 2):
            perm = expected.copy()
            perm[[i, j]] = perm[[j, i]]
            if not np.allclose(perm, expected) and self._close(got, perm):
                return f"{self._label(i)} and {self._label(j)} are swapped."
        if n % 2 == 0 and n >= 4:
            half = n // 2
            flipped = np.concatenate([expected[half:], expected[:half]])
            if not np.allclose(flipped, expected) and self._close(got, flipped):
                return "the two halves (left and right wheels?) are swapped."
        rev = expected[::-1]
        if not np.allclose(rev, expected) and self._close(got, rev):
            return "the order is reversed."
        return None


def _defined(exercise: Exercise, case: Case) -> np.ndarray | None:
    """The reference's answer to ``case`` as a float array, or None where it is not defined
    (raises, or contains NaN)."""
    try:
        value = _as_array(exercise.reference(*copy.deepcopy(case.args),
                                             **copy.deepcopy(case.kwargs)))
    except Exception:
        return None
    return None if np.any(np.isnan(value)) else value


def _hulls(cases: Sequence[Case]) -> dict:
    """Per argument (position or keyword): the (min, max) of its finite floats over ``cases``."""
    hulls: dict = {}
    for case in cases:
        for key, value in [*enumerate(case.args), *case.kwargs.items()]:
            if isinstance(value, bool) or not isinstance(value, (float, np.floating)):
                continue
            if math.isfinite(value):
                lo, hi = hulls.get(key, (value, value))
                hulls[key] = (min(lo, value), max(hi, value))
    return hulls


def _perturb(value, factor: float, hull):
    """``value`` times ``factor`` (or divided by it) if that stays inside ``hull``, the range
    the visible cases span; else unchanged. Only finite floats change."""
    if (hull is None or isinstance(value, bool)
            or not isinstance(value, (float, np.floating)) or not math.isfinite(value)):
        return value
    for new in (value * factor, value / factor):
        if hull[0] <= new <= hull[1]:
            return type(value)(new)
    return value


def _as_array(value) -> np.ndarray:
    """A float array from a number, a sequence, or an object with ``as_array()`` (a Pose ...)."""
    if hasattr(value, "as_array") and callable(value.as_array):
        value = value.as_array()
    return np.asarray(value, dtype=float)


def _common_ratio(got: np.ndarray, expected: np.ndarray) -> float | None:
    if not (np.all(np.isfinite(got)) and np.all(np.isfinite(expected))):
        return None
    mask = np.abs(expected) > 1e-12
    if not np.any(mask) or np.any(np.abs(got[~mask]) > 1e-12):
        return None
    ratios = got[mask] / expected[mask]
    if np.allclose(ratios, ratios.flat[0], rtol=1e-6):
        return float(ratios.flat[0])
    return None


def _fmt(value) -> str:
    arr = np.asarray(value) if not isinstance(value, str) else None
    if arr is None or arr.dtype == object:
        return repr(value)
    if np.issubdtype(arr.dtype, np.floating):
        arr = arr + 0.0  # no "-0." in messages
    if arr.ndim == 0:
        return f"{float(arr):.6g}" if np.issubdtype(arr.dtype, np.number) else repr(value)
    with np.printoptions(precision=6, suppress=True):
        return np.array2string(arr, separator=", ")


def _load_chapters() -> None:
    load_chapter_modules(__name__, CHAPTER_MODULES)


def get(name: str) -> Exercise:
    """The registered exercise called ``name`` (``ValueError`` listing the names if unknown)."""
    _load_chapters()
    try:
        return _REGISTRY[name]
    except KeyError:
        raise ValueError(
            f"no exercise named {name!r}; known: {', '.join(sorted(_REGISTRY))}"
        ) from None


def all_exercises() -> dict[str, Exercise]:
    """Every registered exercise, by name."""
    _load_chapters()
    return dict(_REGISTRY)


def check(name: str, fn: Callable) -> CheckResult:
    """Check a student's function ``fn`` against exercise ``name``; never raises."""
    return get(name).check(fn)
