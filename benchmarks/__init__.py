"""Speed and fidelity benchmarks: each module with a ``main()`` writes its section of
``benchmarks/RESULTS.md`` (through :mod:`tools.results`). Run from the repository root as
modules: ``python -m benchmarks.run_all`` (``make bench``) or ``python -m benchmarks.sandbox``.
"""
