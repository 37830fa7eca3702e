import os

import numpy as np
import pytest

# The suite's numbers come from the compiled kernel, whatever the state of the compile cache
# (tests/kinematics/test_interpreter.py compares its numpy form; test_cold_start.py times
# the default, "auto").
os.environ.setdefault("KINELAB_KERNEL", "compiled")
from hypothesis import settings

# Deterministic property tests: a CI failure reproduces on any machine.
settings.register_profile("ci", derandomize=True, deadline=None, max_examples=60,
                          print_blob=True)
settings.load_profile("ci")


@pytest.fixture(autouse=True)
def _doctest_namespace(doctest_namespace):
    import kinelab as kl
    doctest_namespace["np"] = np
    doctest_namespace["kl"] = kl


@pytest.fixture(autouse=True)
def _memory_budget_restored():
    """The memory budget a test sets (``kinelab --memory-budget`` through CliRunner sets it
    for the process) ends with the test."""
    import kinelab as kl
    old = kl.memory_budget()
    yield
    kl.memory_budget(old)


@pytest.fixture(autouse=True)
def _figures_closed():
    """The figures a test leaves open (a doctest's, say) are closed when it ends: pyplot
    keeps them for the process, and past 20 it warns in whichever test comes next."""
    yield
    import sys
    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close("all")
