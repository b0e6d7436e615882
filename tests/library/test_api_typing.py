r"""The public API is typed and its math docstrings are raw strings (issue #12, item 5).

(a) Every public callable of every public module of ``wheelkin`` (the names in a module's
    ``__all__`` that are functions or classes, and the public methods, properties and
    constructors of those classes) annotates every parameter but ``self``/``cls`` and its
    return type. A property is checked through its getter's return annotation.
(b) Every docstring (module, class, function) of every ``.py`` file under ``src/wheelkin`` that
    holds a backslash is a raw string (``r"..."`` with triple quotes): in a plain string ``\theta`` is a tab
    followed by ``heta`` and ``\nabla`` a newline. Docstrings are found with ``tokenize`` (a
    string statement that opens a module or the body of a ``def``/``class``), and the set
    found is checked against ``ast`` so that the scan cannot silently miss one.
(c) ``typing.get_type_hints`` resolves every public callable's annotations (no forward
    reference to a name the module imports only under ``TYPE_CHECKING``, or not at all).

Each check is a function of a package name / source directory, so the self-tests at the end
run it on a deliberately broken package in a temporary directory and see it fail.
"""

from __future__ import annotations

import ast
import functools
import importlib
import inspect
import io
import pkgutil
import sys
import textwrap
import tokenize
import typing
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

import wheelkin
from wheelkin._registry import FORMULA_MODULES

SRC = Path(wheelkin.__file__).resolve().parent

# ------------------------------------------------------------------------------ discovery


def public_modules(package: str) -> list[str]:
    """Every importable module of ``package`` whose dotted name has no private part."""
    pkg = importlib.import_module(package)
    names = [package]
    for info in pkgutil.walk_packages(pkg.__path__, prefix=package + "."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            names.append(info.name)
    return sorted(names)


def _is_namedtuple(cls: type) -> bool:
    return issubclass(cls, tuple) and hasattr(cls, "_fields")


def _own(obj: object, package: str) -> bool:
    return getattr(obj, "__module__", "").split(".")[0] == package


def public_callables(package: str) -> Iterator[tuple[str, Callable, bool]]:
    """``(qualified name, function, is_method)`` for every public callable of ``package``.

    A property yields its getter (and setter), a class its constructor (``__init__``, or a
    hand-written ``__new__``) and ``__call__`` where the class defines them. Each function is
    yielded once, under the name of the module that defines it.
    """
    seen: set[int] = set()

    def emit(name: str, func: object, is_method: bool) -> Iterator[tuple[str, Callable, bool]]:
        if func is None or id(func) in seen or not _own(func, package):
            return  # e.g. the __init__ typing gives a Protocol
        seen.add(id(func))
        yield name, func, is_method

    for modname in public_modules(package):
        module = importlib.import_module(modname)
        for attr in getattr(module, "__all__", ()):
            obj = getattr(module, attr)
            if not _own(obj, package):
                continue
            if not inspect.isclass(obj) and callable(obj):
                func = inspect.unwrap(obj)  # through functools.wraps, lru_cache...
                yield from emit(f"{obj.__module__}.{obj.__qualname__}", func, False)
            elif inspect.isclass(obj):
                if id(obj) in seen:
                    continue
                seen.add(id(obj))
                for klass in inspect.getmro(obj):
                    if not _own(klass, package):
                        continue
                    for name, member in vars(klass).items():
                        if name.startswith("_") and name not in ("__init__", "__new__",
                                                                 "__call__"):
                            continue
                        if name == "__new__" and _is_namedtuple(klass):
                            continue  # generated from the annotated fields
                        qual = f"{klass.__module__}.{klass.__qualname__}.{name}"
                        if isinstance(member, staticmethod):
                            # __new__ is stored as a staticmethod but takes cls
                            yield from emit(qual, member.__func__, name == "__new__")
                        elif isinstance(member, classmethod):
                            yield from emit(qual, member.__func__, True)
                        elif isinstance(member, property):
                            yield from emit(qual, member.fget, True)
                            yield from emit(qual + ".setter", member.fset, True)
                        elif isinstance(member, functools.cached_property):
                            yield from emit(qual, member.func, True)
                        elif inspect.isfunction(member):
                            yield from emit(qual, member, True)


def public_classes(package: str) -> Iterator[tuple[str, type]]:
    """Every public class of ``package`` (defined in it), once."""
    seen: set[int] = set()
    for modname in public_modules(package):
        module = importlib.import_module(modname)
        for attr in getattr(module, "__all__", ()):
            obj = getattr(module, attr)
            if inspect.isclass(obj) and _own(obj, package) and id(obj) not in seen:
                seen.add(id(obj))
                yield f"{obj.__module__}.{obj.__qualname__}", obj


# ------------------------------------------------------------------------------ (a) and (c)


def missing_annotations(package: str) -> list[str]:
    """One line per public callable that lacks a parameter or the return annotation."""
    problems = []
    for name, func, is_method in public_callables(package):
        sig = inspect.signature(func, follow_wrapped=True)
        params = list(sig.parameters.values())
        if is_method and params and params[0].name in ("self", "cls"):
            params = params[1:]
        missing = [p.name for p in params if p.annotation is inspect.Parameter.empty]
        if sig.return_annotation is inspect.Signature.empty:
            missing.append("return")
        if missing:
            problems.append(f"{name}: {', '.join(missing)}")
    for name, cls in public_classes(package):
        if _is_namedtuple(cls):  # the fields are the constructor's parameters
            notes = inspect.get_annotations(cls)
            missing = [f for f in cls._fields if f not in notes]
            if missing:
                problems.append(f"{name}: fields {', '.join(missing)}")
    return sorted(problems)


def unresolved_annotations(package: str) -> list[str]:
    """One line per public callable or class whose annotations ``get_type_hints`` cannot
    resolve."""
    problems = []
    targets: list[tuple[str, object]] = [(n, f) for n, f, _ in public_callables(package)]
    targets += list(public_classes(package))
    for name, obj in targets:
        try:
            typing.get_type_hints(obj)
        except Exception as exc:  # NameError, TypeError, AttributeError...
            problems.append(f"{name}: {type(exc).__name__}: {exc}")
    return sorted(problems)


# ------------------------------------------------------------------------------ (b)


def _prefix(token: str) -> str:
    return token[: min(i for i in (token.find('"'), token.find("'")) if i >= 0)]


def docstring_tokens(source: str) -> list[tokenize.TokenInfo]:
    """The STRING tokens that are docstrings: a string statement that is the first statement
    of the module or of a ``def``/``class`` body."""
    skip = {tokenize.ENCODING, tokenize.NL, tokenize.COMMENT}
    lines: list[list[tokenize.TokenInfo]] = [[]]  # logical lines, with INDENT/DEDENT
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type in skip:
            continue
        lines[-1].append(tok)
        if tok.type == tokenize.NEWLINE:
            lines.append([])
    found = []
    for i, line in enumerate(lines):
        body = [t for t in line if t.type not in (tokenize.INDENT, tokenize.DEDENT)]
        strings = []
        for tok in body:
            if tok.type != tokenize.STRING:
                break
            strings.append(tok)
        # a statement of string literals alone (implicit concatenation included)
        if not strings or len(strings) + 1 != len(body) or body[-1].type != tokenize.NEWLINE:
            continue
        if i == 0:
            found.extend(strings)
            continue
        prev = [t for t in lines[i - 1] if t.type not in (tokenize.INDENT, tokenize.DEDENT)]
        opens_body = any(t.type == tokenize.INDENT for t in line)
        header = prev and (prev[0].string in ("def", "class")
                           or (prev[0].string == "async" and len(prev) > 1
                               and prev[1].string == "def"))
        if header and opens_body and len(prev) >= 2 and prev[-2].string == ":":
            found.extend(strings)
    return found


def docstring_lines_ast(source: str) -> set[int]:
    """Line numbers of every docstring, as ``ast`` sees them (the cross-check)."""
    with warnings.catch_warnings():  # an invalid escape in a plain docstring is reported below
        warnings.simplefilter("ignore")
        tree = ast.parse(source)
    lines = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            if ast.get_docstring(node, clean=False) is not None:
                lines.add(node.body[0].lineno)
    return lines


def non_raw_math_docstrings(root: Path) -> list[str]:
    """``file:line`` of every docstring under ``root`` that holds a backslash and is not raw;
    also any docstring that ``tokenize`` and ``ast`` disagree about (a scanner bug)."""
    problems = []
    for path in sorted(root.rglob("*.py")):
        source = path.read_text(encoding="utf-8")
        rel = path.relative_to(root.parent)
        tokens = docstring_tokens(source)
        if {t.start[0] for t in tokens} != docstring_lines_ast(source):
            problems.append(f"{rel}: tokenize and ast find different docstrings "
                            f"({sorted({t.start[0] for t in tokens})} vs "
                            f"{sorted(docstring_lines_ast(source))})")
        for tok in tokens:
            if "\\" in tok.string and "r" not in _prefix(tok.string).lower():
                problems.append(f"{rel}:{tok.start[0]}: docstring holds a backslash "
                                f"but is not a raw string")
    return problems


# ------------------------------------------------------------------------------ the tests


def _report(title: str, problems: list[str]) -> str:
    return f"{len(problems)} {title}:\n  " + "\n  ".join(problems)


def test_every_public_callable_is_annotated() -> None:
    problems = missing_annotations("wheelkin")
    if problems:
        pytest.fail(_report("public callables lack annotations (name: what is missing)",
                            problems), pytrace=False)


def test_every_math_docstring_is_raw() -> None:
    problems = non_raw_math_docstrings(SRC)
    if problems:
        pytest.fail(_report("docstrings hold a backslash but are not raw", problems),
                    pytrace=False)


def test_annotations_resolve() -> None:
    problems = unresolved_annotations("wheelkin")
    if problems:
        pytest.fail(_report("public callables whose annotations do not resolve", problems),
                    pytrace=False)


def test_the_walk_sees_the_whole_api() -> None:
    """The walk is not vacuous: it reaches the subpackages and the methods of classes."""
    modules = public_modules("wheelkin")
    for name in (*(f"wheelkin.{m}" for m in FORMULA_MODULES), "wheelkin.sandbox.world",
                 "wheelkin.widgets", "wheelkin.exercises.rover"):
        assert name in modules
    assert not any(part.startswith("_") for m in modules for part in m.split("."))
    without_all = [m for m in modules
                   if m != "wheelkin" and not hasattr(importlib.import_module(m), "__all__")]
    assert not without_all, f"public modules without __all__ (the walk skips them): {without_all}"
    names = {n for n, _, _ in public_callables("wheelkin")}
    assert "wheelkin.frames.compose" in names
    assert any(n.startswith("wheelkin.sandbox.world.World.") for n in names)
    assert len(names) > 200


# ------------------------------------------------------------------------------ self-tests

BROKEN = {
    "__init__.py": '"""A package for the self-test."""\n',
    "good.py": textwrap.dedent('''\
        r"""Good: :math:`\\theta`."""
        from __future__ import annotations

        from typing import NamedTuple

        __all__ = ["Pair", "Thing", "f"]


        def f(x: float, *args: int, **kw: str) -> float:
            r"""Return :math:`x \\cdot 2`."""
            return 2 * x


        class Pair(NamedTuple):
            a: float
            b: float


        class Thing:
            """No backslash here: plain is fine."""

            def __init__(self, x: float) -> None:
                self.x = x

            @property
            def double(self) -> float:
                return 2 * self.x

            @classmethod
            def make(cls, x: float) -> Thing:
                return cls(x)
        '''),
    "bad.py": textwrap.dedent('''\
        """Bad: \\theta is a tab here."""
        from __future__ import annotations

        __all__ = ["Gadget", "g", "h"]


        def g(x, y: float = 1.0):
            "one-quote docstring, \\alpha"
            return x


        async def h(x: float) -> Undefined:
            """Fine docstring, unresolvable return annotation."""
            return x


        class Gadget:
            """A class."""

            def __init__(self, x: float):
                """\\nabla."""
                self.x = x

            @property
            def half(self):
                return self.x / 2

            @staticmethod
            def helper(a: int) -> int:
                return a

            def run(self, *args, key: str) -> None:
                x = "not a docstring: \\x41"
                """not a docstring either: \\\\d"""

            def _private(self, a):
                return a
        '''),
}


@pytest.fixture
def broken_package(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    root = tmp_path / "brokenpkg"
    root.mkdir()
    for name, text in BROKEN.items():
        (root / name).write_text(text, encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    yield root
    for mod in [m for m in sys.modules if m == "brokenpkg" or m.startswith("brokenpkg.")]:
        del sys.modules[mod]


def test_self_test_missing_annotations(broken_package: Path) -> None:
    assert missing_annotations("brokenpkg") == [
        "brokenpkg.bad.Gadget.__init__: return",
        "brokenpkg.bad.Gadget.half: return",
        "brokenpkg.bad.Gadget.run: args",
        "brokenpkg.bad.g: x, return",
    ]


def test_self_test_raw_docstrings(broken_package: Path) -> None:
    assert non_raw_math_docstrings(broken_package) == [
        "brokenpkg/bad.py:1: docstring holds a backslash but is not a raw string",
        "brokenpkg/bad.py:8: docstring holds a backslash but is not a raw string",
        "brokenpkg/bad.py:21: docstring holds a backslash but is not a raw string",
    ]


def test_self_test_unresolved(broken_package: Path) -> None:
    problems = unresolved_annotations("brokenpkg")
    assert problems == ["brokenpkg.bad.h: NameError: name 'Undefined' is not defined"]
