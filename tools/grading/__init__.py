"""The grader's parts (``tools/grade.py`` is its command line):

- ``jail.py``: the bubblewrap sandbox every piece of a submission runs in;
- ``inside_run.py``, ``inside_call.py``: the two scripts that run inside a sandbox (the
  notebook; an exercise's function on its cases);
- ``notebook.py``, ``source.py``: reading a notebook statically (the checks that ran, the
  slice of the notebook a function needs);
- ``library_parts.py``: the package of the library parts an exercise may use;
- ``wire.py``: the data that crosses a sandbox's wall (JSON only);
- ``judge.py``: the exercise's own check on the answers, with its time and memory limits;
- ``assignment.py``: the assignment file (TOML).
"""
