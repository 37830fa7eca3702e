"""wrap_angle: one turn, (-pi, pi], whole turns removed and nothing else."""
import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl


@given(st.floats(-1e3, 1e3))
def test_wraps_into_one_turn_by_whole_turns(a):
    w = kl.solvers.wrap_angle(a)
    assert -math.pi < w <= math.pi
    turns = (a - w) / (2 * math.pi)
    assert abs(turns - round(turns)) < 1e-12 * max(1.0, abs(a))


def test_edges_and_values_in_range():
    assert kl.solvers.wrap_angle(-math.pi) == math.pi
    assert kl.solvers.wrap_angle(math.pi) == math.pi
    inside = np.array([-3.14159, -1.0, 0.0, 0.1, 3.14159])
    np.testing.assert_array_equal(kl.solvers.wrap_angle(inside), inside)   # untouched, to the bit
    assert kl.solvers.wrap_angle(np.zeros((2, 3))).shape == (2, 3)
