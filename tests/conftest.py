"""Hypothesis profiles for the property suite (tests/test_properties_*.py).

``ci`` (default): a fixed seed (``derandomize=True``) and a bounded example budget, so
the suite is reproducible and finishes in bounded time. ``dev`` and ``thorough``
run many more random examples; pick one with the environment variable
``EMBROACT_HYPOTHESIS_PROFILE`` (e.g. ``EMBROACT_HYPOTHESIS_PROFILE=thorough pytest``).
Deadlines are off in every profile: run times on a loaded 2-core machine vary.

The README's test command runs the modules in parallel (pytest-xdist, ``-n auto --dist loadfile
--no-loadscope-reorder``: each module whole in one worker, so its module fixtures are built once);
modules holding a long run (``@pytest.mark.slow``) are collected first, so no worker starts one
while the other has nothing left.
"""
import os
import signal

from hypothesis import HealthCheck, settings

#: Examples per property in the "ci" profile; tests scale this with ``strategies.budget``.
CI_EXAMPLES = 100

_COMMON = dict(deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.register_profile("ci", max_examples=CI_EXAMPLES, derandomize=True, print_blob=True, **_COMMON)
settings.register_profile("dev", max_examples=10 * CI_EXAMPLES, **_COMMON)
settings.register_profile("thorough", max_examples=100 * CI_EXAMPLES, **_COMMON)
settings.load_profile(os.environ.get("EMBROACT_HYPOTHESIS_PROFILE", "ci"))
# The tests that stop a command with Ctrl-C send SIGINT to a child process, which inherits an ignored SIGINT
# (a shell's background job ignores it): Python's own handler here, so every child starts with the default.
signal.signal(signal.SIGINT, signal.default_int_handler)


def pytest_collection_modifyitems(items):
    """Modules with a test marked slow first, each module's tests in their order (a stable sort)."""
    slow = {item.path for item in items if item.get_closest_marker("slow")}
    items.sort(key=lambda item: item.path not in slow)


if os.environ.get("EMBROACT_TEST_KINDS") == "1":  # the whole suite with a third pattern kind registered
    import kind_parallel

    kind_parallel.register_parallel()
