"""Shared pytest configuration for the library tests."""

from hypothesis import settings

# Property tests are deterministic (the same examples on every run and every machine: a red CI
# is reproducible) and never fail for being slow on a loaded 2-core machine: speed is measured
# in benchmarks/, not asserted in tests. Individual tests may still set max_examples.
settings.register_profile("wheelkin", deadline=None, derandomize=True, database=None,
                          print_blob=True)
settings.load_profile("wheelkin")
