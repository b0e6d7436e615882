"""wheelkin: kinematics of wheeled mobile robots, checked against an executable textbook.

Inside the library every quantity is SI (m, s, rad) in the REP-103 frame (x forward, y left,
z up, heading counter-clockwise from world +x), unless a module reproduces a source document's
numbers in that source's own convention, which its docstring then names. Conversions between
the sources' conventions and ours live in :mod:`wheelkin.frames` and :mod:`wheelkin.units`.
"""

__version__ = "0.1.0"


def __getattr__(name: str) -> object:
    """``import wheelkin`` then ``wheelkin.odometry``: a submodule loads on first access
    (PEP 562), so the package's import stays light and ``import wheelkin.x`` works as ever."""
    import importlib

    from wheelkin._registry import LAYERS

    if any(name in modules for _, modules in LAYERS):
        return importlib.import_module(f"wheelkin.{name}")
    raise AttributeError(f"module 'wheelkin' has no attribute {name!r}")


def __dir__() -> list[str]:
    from wheelkin._registry import LAYERS

    public = {m for _, modules in LAYERS for m in modules if not m.startswith("_")}
    return sorted(public | {"__version__"})
