"""The project's tools: notebook execution, the book's pages, the editions, the grader, the
Sphinx extensions, mutation testing, the figures file of the benchmarks.

A package, run from the repository root as modules (``python -m tools.execute_notebooks``);
``benchmarks`` builds on it, never the reverse. Nothing here is part of the ``wheelkin``
library.
"""
