"""Generated design tables and tolerance studies stay within the memory budget, and design
lengths within the model's limits, whatever numbers they are given."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import MemoryBudgetError


@pytest.mark.parametrize("make", [
    lambda: kl.sweep.sobol(10 ** 12, crank=(0.5, 1.5)),
    lambda: kl.sweep.random(10 ** 11, crank=(0.5, 1.5)),
    lambda: kl.sweep.grid(crank=(0.5, 1.5, 10 ** 11)),
    lambda: kl.sweep.grid(crank=(0.5, 1.5, 10 ** 5), rocker=(2.0, 3.0, 10 ** 6)),
    lambda: kl.sweep.tolerance("fourbar", dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5),
                               {"crank": 1e-3}, n=10 ** 10),
])
def test_huge_tables_are_refused_before_they_are_allocated(make):
    with pytest.raises(MemoryBudgetError, match="memory budget"):
        make()


def test_lengths_beyond_the_models_limits_are_reported_per_row():
    designs = np.array([[3.0, 1.0, 3.0, 2.5], [1e308, 1.0, 1.0, 1.0], [3.0, 1e-12, 3.0, 2.5]])
    with np.errstate(all="raise"):          # nothing overflows on the way
        table = kl.sweep.run("fourbar", designs)
    assert table["assembles"].tolist() == [True, False, False]
    problems = table.attrs["problems"]
    assert "1e+09 m" in problems[1] and "1e+09 m" in problems[2]


def test_lengths_beyond_the_models_limits_never_reach_the_sketches():
    designs = {"crank": [1.0, 1e308, 1.0], "rod": [3.0, 1.0, 3.0], "offset": [0.0, 0.0, -1e308]}
    with np.errstate(all="raise"):          # the reported rows are not sketched
        table = kl.sweep.run("slider_crank", designs)
    assert table["assembles"].tolist() == [True, False, False]
    problems = table.attrs["problems"]
    assert "1e+09 m" in problems[1] and "offset" in problems[2]
