"""Function generation from raw angle pairs (pylinkage's form of the task): a front of
function_pairs with the ground along +x, checked by moving the linkage with the engine."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import function_generation_pairs, function_pairs

from .helpers import wrap

LENGTHS = dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)


def _pairs(q):
    fb = kl.mechanisms.fourbar(**LENGTHS)
    return q, kl.analyze(fb, q=q).angle("rocker")


def test_three_pairs_of_a_catalogue_linkage_give_it_back():
    q, out = _pairs(np.radians([40.0, 70.0, 100.0]))
    sol = function_generation_pairs(q, out, ground=3.0)
    assert sol.fit == "exact" and sol.valid
    for k, v in LENGTHS.items():
        assert sol.lengths[k] == pytest.approx(v, rel=1e-10)
    # the engine's rocker angle at each input angle is the prescribed one
    s = kl.analyze(sol.model, q=q)
    np.testing.assert_allclose(wrap(s.angle("rocker") - out), 0.0, atol=1e-9)
    np.testing.assert_allclose(sol.precision_errors, 0.0, atol=1e-9)


def test_pairs_alone_as_pylinkage_takes_them():
    q, out = _pairs(np.radians([40.0, 70.0, 100.0]))
    apart = function_generation_pairs(q, out, ground=3.0)
    pairs = function_generation_pairs(list(zip(q, out)), ground=3.0)
    np.testing.assert_array_equal(pairs.K, apart.K)


def test_angles_are_absolute_not_relative_to_the_first_pair():
    q, out = _pairs(np.radians([40.0, 70.0, 100.0]))
    sol = function_generation_pairs(q, out, ground=3.0)
    np.testing.assert_allclose(sol.q, q, atol=1e-15)         # the model's input is theta2 itself
    # relative angles (the first pair subtracted) describe another task
    rel = function_generation_pairs(q - q[0] + 0.1, out - out[0] + 0.2, ground=3.0)
    assert not np.allclose(rel.K, sol.K)


def test_the_same_as_function_pairs_on_a_ground_along_x():
    q, out = _pairs(np.radians([40.0, 60.0, 80.0, 100.0, 120.0]))
    out = out + np.radians([0.3, -0.2, 0.1, 0.0, -0.4])
    a = function_generation_pairs(q, out, ground=3.0, O2=(1.0, 2.0))
    b = function_pairs(q, out, (1.0, 2.0), (4.0, 2.0))
    np.testing.assert_array_equal(a.K, b.K)
    np.testing.assert_array_equal(a.precision_errors, b.precision_errors)
    assert a.defects == b.defects


def test_degrees_and_radians_give_the_same_linkage():
    q, out = _pairs(np.radians([40.0, 70.0, 100.0]))
    a = function_generation_pairs(q, out, ground=3.0)
    b = function_generation_pairs(np.degrees(q), np.degrees(out), ground=3.0, degrees=True)
    np.testing.assert_allclose(b.K, a.K, rtol=1e-12)


def test_more_pairs_least_squares_with_the_engine_error_at_each_pair():
    q = np.radians([40.0, 60.0, 80.0, 100.0, 120.0])
    out = np.radians([87.0, 90.0, 95.0, 103.0, 111.0])      # the linkage's, rounded to degrees
    sol = function_generation_pairs(q, out, ground=3.0)
    assert sol.fit == "least squares" and sol.valid
    # the structural error at each pair, independently: the engine's rocker angle there
    s = kl.analyze(sol.model, q=sol.q)
    np.testing.assert_allclose(sol.precision_errors, wrap(s.angle("rocker") - out), atol=1e-12)
    assert 1e-4 < np.abs(sol.precision_errors).max() < np.radians(1.0)
    # Freudenstein's normal equations hold at the least-squares K
    M = np.column_stack([np.cos(out), -np.cos(q), np.ones_like(q)])
    np.testing.assert_allclose(M.T @ (M @ sol.K - np.cos(q - out)), 0.0, atol=1e-12)


def test_exact_pairs_of_a_linkage_fitted_by_least_squares_give_it_back():
    q, out = _pairs(np.radians(np.arange(30.0, 131.0, 10.0)))
    sol = function_generation_pairs(q, out, ground=3.0)
    assert sol.fit == "least squares"
    for k, v in LENGTHS.items():
        assert sol.lengths[k] == pytest.approx(v, rel=1e-9)
    np.testing.assert_allclose(sol.precision_errors, 0.0, atol=1e-9)


@pytest.mark.parametrize("args, kwargs, message", [
    (([[1, 2, 3], [4, 5, 6]],), {},
     r"^input_angles: expected pairs \(input, output\) of shape \(n, 2\) when output_angles is "
     r"not given, got shape \(2, 3\)"),
    (([10, 20], [30, 40]), dict(degrees=True), r"^input_angles, output_angles: expected 3 to 100 pairs, got 2$"),
    (([10, 20, 30], [30, 40, 50]), dict(ground=-1.0, degrees=True),
     r"^ground: expected a positive length \(m\), got -1\.0$"),
    (([10, 20, 30], [30, 40, 50]), dict(O2=(0, "a")), r"^O2: expected a point"),
    (([10, 30, 20], [30, 40, 50]), dict(degrees=True), r"^input_angles: expected angles in the order"),
    (([10, 20, 30], [30, 40, 50]), dict(degrees="yes"), r"^degrees: "),
])
def test_bad_input_one_line_naming_the_field(args, kwargs, message):
    with pytest.raises(ModelError, match=message) as info:
        function_generation_pairs(*args, **kwargs)
    assert "\n" not in str(info.value)
