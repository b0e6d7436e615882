"""wheelkin: kinematics of wheeled mobile robots, checked against an executable textbook.

Inside the library every quantity is SI (m, s, rad) in the REP-103 frame (x forward, y left,
z up, heading counter-clockwise from world +x), unless a module reproduces a source document's
numbers in that source's own convention, which its docstring then names. Conversions between
the sources' conventions and ours live in :mod:`wheelkin.frames` and :mod:`wheelkin.units`.
"""

__version__ = "0.1.0"
