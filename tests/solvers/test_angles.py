"""wrap_angle: one turn, (-pi, pi], whole turns removed and nothing else."""
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.solvers import bisect, turn_intervals, wrap_angle
from kinelab.solvers._angles import wrapped_angles


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


def _by_remainder(a):
    """wrap_angle as numpy's remainder writes it: the reference of its quicker passes."""
    inside = (a > -np.pi) & (a <= np.pi)
    w = np.remainder(a + np.pi, 2.0 * np.pi) - np.pi
    return np.where(inside, a, np.where(w == -np.pi, np.pi, w))


@pytest.mark.parametrize("angles", [
    np.random.default_rng(0).uniform(-3 * np.pi, 3 * np.pi, 100_000),
    np.random.default_rng(2).uniform(-2.45 * np.pi, 2.45 * np.pi, 100_000),
    np.array([np.pi, -np.pi, 2 * np.pi, -2 * np.pi, 0.0, -0.0, np.nextafter(np.pi, 4.0),
              np.nextafter(-np.pi, -4.0), np.nextafter(-np.pi, 0.0), 2.4 * np.pi, -2.4 * np.pi]),
    np.random.default_rng(1).uniform(-1e3, 1e3, 10_000),
    np.linspace(0.0, 2 * np.pi, 3600, endpoint=False).reshape(-1, 1),
    np.array([np.pi, -np.pi, 3 * np.pi, -3 * np.pi, 2 * np.pi, -2 * np.pi, 0.0, -0.0, 1e-300,
              -1e-300, np.nextafter(np.pi, 4.0), np.nextafter(-np.pi, -4.0),
              np.nextafter(3 * np.pi, 0.0), np.nextafter(-3 * np.pi, 0.0), 5 * np.pi]),
    np.array(4.0), np.array([np.nan, 1.0, 7.0])], ids=["turns", "one turn", "one turn's edges", "far", "sweep", "edges", "one", "nan"])
def test_wrap_is_remainder_to_the_bit(angles):
    w, ref = wrapped_angles(angles), _by_remainder(angles)
    assert w.shape == ref.shape
    np.testing.assert_array_equal(w.view(np.int64)[~np.isnan(ref)], ref.view(np.int64)[~np.isnan(ref)])
    assert np.array_equal(np.isnan(w), np.isnan(ref))


@pytest.mark.parametrize("angle, message", [
    (np.inf, r"^angle: expected finite angles \(rad\), got inf; an infinite angle has no direction$"),
    ([0.0, -np.inf], r"^angle: expected finite angles \(rad\), got -inf"),
    (None, r"^angle: expected real numbers, got None$"),
    ("a", r"^angle: expected real numbers, got 'a'$"),
    (1j, r"^angle: expected real numbers, got 1j$"),
    (10**400, r"^angle: expected real numbers, got a whole number of 401 digits$"),
])
def test_wrap_angle_refuses_what_is_not_an_angle(angle, message):
    with pytest.raises(ModelError, match=message):
        wrap_angle(angle)


def test_wrap_angle_keeps_nan_for_a_sample_with_no_value():
    wrapped = wrap_angle([np.nan, 1.5 * np.pi])
    assert np.isnan(wrapped[0]) and wrapped[1] == pytest.approx(-0.5 * np.pi, abs=1e-15)


@pytest.mark.parametrize("intervals, around, message", [
    (None, 0.0, r"^intervals: expected real numbers, got None$"),
    (1.0, 0.0, r"^intervals: expected \(start, stop\) pairs of angles, shape \(k, 2\), got shape \(\)$"),
    (True, 0.0, r"^intervals: expected real numbers, got true$"),
    ([[0.0]], 0.0, r"^intervals: expected \(start, stop\) pairs .*got shape \(1, 1\)$"),
    ("ab", 0.0, r"^intervals: expected \(start, stop\) pairs of angles, got 'ab'$"),
    ([(0.0, 1.0), (2.0, 3.0, 4.0)], 0.0, r"^intervals: expected real numbers in an array of regular shape"),
    ([(np.nan, 1.0)], 0.0, r"^intervals: expected finite angles, got \[nan, 1.0\]$"),
    ([(0.0, np.inf)], 0.0, r"^intervals: expected finite angles, got \[0.0, inf\]$"),
    ([(0.0, 1.0)], "a", r"^around: expected a finite number, got 'a'$"),
    ([(0.0, 1.0)], np.array([1.0, 2.0]), r"^around: expected a finite number, got \[1.0, 2.0\]$"),
    ([(0.0, 1.0)], np.nan, r"^around: expected a finite number, got nan$"),
])
def test_turn_intervals_refuses_what_is_not_an_interval(intervals, around, message):
    with pytest.raises(ModelError, match=message):
        turn_intervals(intervals, around)


def test_turn_intervals_of_nothing_is_nothing():
    assert turn_intervals([]) == []


@pytest.mark.parametrize("a, options, message", [
    (np.nan, {}, r"^a: expected finite numbers, got nan$"),
    (None, {}, r"^a: expected real numbers, got None$"),
    (10**400, {}, r"^a: expected real numbers, got a whole number of 401 digits$"),
    (2.0, {"iterations": np.nan}, r"^iterations: expected a whole number from 0 to 2,000, got nan$"),
    (2.0, {"iterations": None}, r"^iterations: expected a whole number from 0 to 2,000, got None$"),
    (2.0, {"iterations": "a"}, r"^iterations: expected a whole number from 0 to 2,000, got 'a'$"),
    (2.0, {"tol": None}, r"^tol: expected a positive number below 1, got None$"),
    (2.0, {"inside": 1}, r"^inside: expected a function, got 1$"),
])
def test_bisect_refuses_bad_arguments(a, options, message):
    arguments = {"inside": lambda x: x > 1.0, "a": a, "b": 0.0, **options}
    with pytest.raises(ModelError, match=message):
        bisect(**arguments)


def test_bisect_between_the_largest_floats():
    # the middle of the two ends is taken without overflowing their sum
    a, b = bisect(lambda x: x > 1.0, 1e308, -1e308)      # 0, then 79 halvings of 1e308
    assert np.isfinite(a) and np.isfinite(b) and b <= 1.0 < a
    assert b == 0.0 and a == 1e308 / 2.0**79
