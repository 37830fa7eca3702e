"""Bad arguments of the synthesis functions: one-line ModelErrors naming the argument, never a
raw numpy or Python error, a warning, or a silent NaN."""
import warnings

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import MemoryBudgetError, ModelError
from kinelab.synthesis import Positions, poles, three_positions

S = kl.synthesis
TRIANGLE = np.array([(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0)])


def refused(call, message, error=ModelError):
    """call() raises ``error`` with a one-line message matching ``message``, and no warning."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(error, match=message) as info:
            call()
    assert "\n" not in str(info.value)
    return info.value


@pytest.mark.parametrize("call, message", [
    (lambda: poles([(1e308, 0), (-1e308, 0)], [0, 1]),
     r"^points\[0\]: expected coordinates at most 1e\+09 m in size, got \[1e\+308, 0\.0\]"),
    (lambda: poles([(10 ** 400, 0), (0, 0)], [0, 1]),
     r"^points: expected real numbers, got .*whole number of 401 digits"),
    (lambda: poles([(1, 0), (0, 0)], [0, 10 ** 400]), r"^angles: expected real numbers"),
    (lambda: poles([(1, 0), (0, 0)], [0, 1e20]),
     r"^angles\[1\]: expected an angle within 1000 turns of 0 \(6283\.19 rad\), got 1e\+20"),
    (lambda: Positions([(1, 0), (0, 0)], [0, 1], degrees="no"),
     r"^degrees: expected True or False, got 'no'"),
    (lambda: Positions(np.zeros((1001, 2)), np.zeros(1001)),
     r"^points: expected at most 1,000 positions, got 1,001"),
    (lambda: Positions([(1, 0), (0, 0)], ["a", "b"]), r"^angles: expected real numbers"),
])
def test_positions_are_bounded(call, message):
    refused(call, message)


@pytest.mark.parametrize("key", [(1,), (1, 2, 3), 5, None, "ab", (True, 2), (1, 1), (1, 4),
                                 (1.0, 2)])
def test_a_pole_is_asked_for_by_two_positions(key):
    p = poles(TRIANGLE, [0, 1, 2])
    refused(lambda: p[key], r"^pole: expected two different positions i, j from 1 to 3 \(as in "
                            r"poles\[1, 2\]\), got ")
    assert p[2, 1] is p[1, 2] or np.array_equal(p[2, 1], p[1, 2])


@pytest.mark.parametrize("xy, message", [
    ("x", r"^xy1: expected real numbers, got 'x'"),
    (np.zeros((2, 2, 2)), r"^xy1: expected points \(x, y\) of shape \(2,\) or \(k, 2\), got "
                          r"shape \(2, 2, 2\)"),
    (np.zeros(3), r"^xy1: expected points \(x, y\) of shape \(2,\) or \(k, 2\), got shape \(3,\)"),
    ([np.inf, 0], r"^xy1: expected coordinates of finite numbers"),
])
def test_carry_takes_points(xy, message):
    refused(lambda: Positions(TRIANGLE, [0, 1, 2]).carry(xy), message)


@pytest.mark.parametrize("first, second, message", [
    (np.zeros((0, 2)), np.zeros((0, 2)), r"^first, second: expected two arrays of the same shape "
                                         r"\(n, 2\), n at least 2, got \(0, 2\) and \(0, 2\)"),
    ([(0, 0), (np.inf, 0)], [(1, 0), (1, 1)], r"^first\[1\]: expected coordinates of finite"),
    ([(0, 0), (np.nan, 0)], [(1, 0), (1, 1)], r"^first\[1\]: expected coordinates of finite"),
    ([(0, 0), (1, 0)], [(1, 0), (1e308, 1)], r"^second\[1\]: expected coordinates .* at most "
                                             r"1e\+09 m"),
])
def test_two_points_per_position_are_checked(first, second, message):
    refused(lambda: Positions.from_two_points(first, second), message)


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1e-12])
def test_positions_too_close_together_are_refused_as_such(scale):
    refused(lambda: three_positions(TRIANGLE * scale, [0, .3, .6], A0=(0, 0), B0=(0.1 * scale, 0)),
            r"^points: the positions are at most .* apart, less than the smallest length kinelab "
            r"computes with \(1e-09 m\); give the task in smaller units")


@pytest.mark.parametrize("scale", [1e100, 1e160, 1e308])
def test_positions_far_away_are_refused_as_such(scale):
    refused(lambda: three_positions(TRIANGLE * scale, [0, .3, .6], A0=(0, 0), B0=(0.1 * scale, 0)),
            r"^points\[0\]: expected coordinates at most 1e\+09 m in size")


def test_a_linkage_outside_the_model_limits_is_named_once():
    refused(lambda: three_positions(TRIANGLE * 1e-9, [0, .3, .6], A0=(0, 0), B0=(1e-10, 0)),
            r"^the four-bar found has links \(ground 1e-10 m, .*\) outside the sizes kinelab "
            r"computes with")


@pytest.mark.parametrize("scale", [1.0, 1e-8, 1e8])
def test_three_positions_at_any_scale_within_the_limits(scale):
    sol = three_positions(TRIANGLE * scale, [0, .3, .6], A0=(0, 0), B0=(0.1 * scale, 0))
    assert np.all(sol.position_errors <= 1e-6 * scale)


PATH = [(0, 0), (1, 1), (2, 0)]


@pytest.mark.parametrize("kwargs, message", [
    (dict(seed=-1), r"^seed: expected a whole number from 0 to 4,294,967,295, got -1"),
    (dict(seed=2.5), r"^seed: expected a whole number .* got 2\.5"),
    (dict(seed=np.nan), r"^seed: expected a whole number .* got nan"),
    (dict(seed="a"), r"^seed: expected a whole number .* got 'a'"),
    (dict(seed=None), r"^seed: expected a whole number .* got None"),
    (dict(runs=10 ** 400), r"^runs: expected a whole number from 1 to 1,000, got a whole number"),
    (dict(popsize=10 ** 6), r"^popsize: expected a whole number from 5 to 10,000, got 1000000"),
    (dict(maxiter=10 ** 7), r"^maxiter: expected a whole number from 1 to 1,000,000"),
    (dict(maxiter=True), r"^maxiter: expected a whole number from 1 to 1,000,000, got true"),
    (dict(refine="no"), r"^refine: expected True or False, got 'no'"),
    (dict(min_transmission_angle=True), r"^min_transmission_angle: expected an angle in "
                                        r"\[0, pi/2\) rad, got true"),
    (dict(tolerance=np.nan), r"^tolerance: expected a fraction"),
    (dict(initial=[[1e300] * 10]), r"^initial: expected pivots, lengths and coupler points at "
                                   r"most 1e\+09 m in size"),
    (dict(initial=[["a"] * 10]), r"^initial: expected real numbers"),
])
def test_path_generation_budgets_and_seeds(kwargs, message):
    refused(lambda: S.path_generation(PATH, **kwargs), message)


@pytest.mark.parametrize("points, message", [
    ([[1e308, 0], [-1e308, 0], [0, 1e308]], r"^points\[0\]: expected coordinates .* at most "
                                            r"1e\+09 m in size, got 1e\+308"),
    ([[1e200, 0], [-1e200, 0], [0, 1e200]], r"^points\[0\]: expected coordinates"),
    ([[1e-200, 0], [-1e-200, 0], [0, 1e-200]], r"^points: the points are at most 2e-200 m apart, "
                                               r"less than the smallest length"),
    ([[1, 0], ["2", 0], [0, 1]], r"^points: expected real numbers"),
])
def test_path_points_are_bounded(points, message):
    refused(lambda: S.path_generation(points), message)


def _log_generator(**kwargs):
    args = dict(f=np.log10, x_range=(1, 2), input_range=(90, 150), output_range=(0, 90),
                degrees=True)
    return S.function_generation(**{**args, **kwargs})


@pytest.mark.parametrize("kwargs, message", [
    (dict(points=3.9), r"^points: expected a whole number from 3 to 100, got 3\.9"),
    (dict(points="5"), r"^points: expected a whole number from 3 to 100, got '5'"),
    (dict(points=np.nan), r"^points: expected a whole number from 3 to 100, got nan"),
    (dict(points=None), r"^points: expected a whole number from 3 to 100, got None"),
    (dict(points=10 ** 9), r"^points: expected a whole number from 3 to 100"),
    (dict(points=np.linspace(1, 2, 101)), r"^points: expected at most 100 precision points"),
    (dict(samples=10 ** 9), r"^samples: expected a whole number from 2 to 1,000,000"),
    (dict(output_range=(0, 360)), r"^output_range: the rocker would turn a full circle or more"),
    (dict(output_range=(0, 3600)), r"^output_range: the rocker would turn a full circle or more"),
    (dict(output_range=(0, 1e20), degrees=False), r"^output_range: expected angles within 1000 "
                                                  r"turns of 0 \(6283\.19 rad\)"),
    (dict(x_range=(1, 10 ** 400)), r"^x_range: expected two different finite numbers"),
    (dict(x_range=(1, 1 + 1e-15)), r"^x_range: expected a range wider than 1e-09 of its values"),
    (dict(x_range=(-1e308, 1e308), f=lambda x: x), r"^x_range: expected numbers at most 1e\+300"),
    (dict(ground=10 ** 400), r"^ground: expected a positive length \(m\), got a whole number"),
    (dict(ground=1e308), r"^ground: expected a length from 1e-09 m to 1e\+09 m, got 1e\+308 m"),
    (dict(ground=1e-12), r"^ground: expected a length from 1e-09 m to 1e\+09 m, got 1e-12 m"),
    (dict(ground=1e12), r"^ground: expected a length from 1e-09 m to 1e\+09 m, got 1e\+12 m"),
    (dict(f=lambda x: x + 0j), r"^f: expected real numbers, one for each x"),
    (dict(degrees="no"), r"^degrees: expected True or False, got 'no'"),
])
def test_function_generation_arguments(kwargs, message):
    refused(lambda: _log_generator(**kwargs), message)


def test_function_generation_at_the_edges_of_the_limits():
    assert _log_generator(ground=1e-6).valid and _log_generator(ground=1e6).valid
    assert _log_generator(points=100).x.size == 100


@pytest.mark.parametrize("call, message, error", [
    (lambda: S.chebyshev_points((0, 1), 10 ** 9), r"^n = 1,000,000,000 Chebyshev points would take "
                                                  r"about .* GiB, more than the memory budget",
     MemoryBudgetError),
    (lambda: S.chebyshev_points((0, 1), 10 ** 20), r"^n: expected a whole number from 1 to ",
     ModelError),
    (lambda: S.chebyshev_points((0, 1), 2.0), r"^n: expected a whole number", ModelError),
    (lambda: S.chebyshev_points((-1e308, 1e308), 3), r"^x_range: expected numbers at most 1e\+300",
     ModelError),
    (lambda: S.freudenstein([0, 1, 2], [np.nan, 1, 2]), r"^theta4\[0\]: expected finite angles",
     ModelError),
    (lambda: S.freudenstein([0, 1, 2], [np.inf, 1, 2]), r"^theta4\[0\]: expected finite angles",
     ModelError),
    (lambda: S.freudenstein([0, 1, 2], [1j, 1, 2]), r"^theta4: expected real numbers", ModelError),
    (lambda: S.freudenstein([0, 1, 10 ** 400], [0, 1, 2]), r"^theta2: expected real numbers",
     ModelError),
])
def test_chebyshev_points_and_freudenstein_arguments(call, message, error):
    refused(call, message, error)


def test_chebyshev_points_over_a_wide_range_are_finite():
    x = S.chebyshev_points((-1e300, 1e300), 3)
    assert np.all(np.isfinite(x)) and abs(x[1]) < 1e-15 * 1e300     # cos(pi / 2) is 6e-17
    np.testing.assert_allclose(x[[0, 2]], [-np.sqrt(3) / 2 * 1e300, np.sqrt(3) / 2 * 1e300], rtol=1e-15)


P4, ALPHA4 = [(0, 0), (1, 0.2), (2, 0.1), (2.5, 1)], [0, .3, .5, .9]


@pytest.mark.parametrize("value", [np.nan, np.inf, 1e308, "x", None, 1j, 10 ** 400])
def test_the_vertical_line_of_centre_points_is_checked(value):
    refused(lambda: S.center_points(P4, ALPHA4, a0x=value), r"^a0x: expected ")
    refused(lambda: S.center_point_cubic(P4, ALPHA4, a0x=value), r"^a0x: expected ")


def test_burmester_curves_within_the_memory_budget():
    refused(lambda: S.burmester_curves(P4, ALPHA4, samples=10 ** 9),
            r"^samples = 1,000,000,000 points of the Burmester curves would take about .* more "
            r"than the memory budget", MemoryBudgetError)
    refused(lambda: S.burmester_curves(P4, ALPHA4, samples=2.5), r"^samples: expected a whole")


@pytest.mark.parametrize("s, message", [
    (1e308, r"^s: expected at most 1e\+09 m in size, got 1e\+308 m"),
    (10 ** 400, r"^s: expected a finite number \(m\), got a whole number of 401 digits"),
    ("a", r"^s: expected a finite number \(m\), got 'a'"),
    (1j, r"^s: expected a finite number \(m\), got 1j"),
])
def test_a_fixed_pivot_on_its_bisector_is_checked(s, message):
    two = S.two_positions([(0, 0), (1, 1)], [0, 90], A1=(0, -1), B1=(1, -1), degrees=True)
    refused(lambda: two.solution(s, 1), message)


@pytest.mark.parametrize("value", [-1, 0.5, "2", np.nan, np.inf, None])
def test_imbalance_angle_takes_a_time_ratio(value):
    refused(lambda: S.imbalance_angle(value), r"^time_ratio: expected the slow stroke's time over "
                                              r"the fast one's, at least 1, got ")


def test_coupler_curves_within_the_memory_budget_and_degenerate_designs_not_assembled():
    designs = np.tile([0, 0, 3.0, 0, 1.0, 3.0, 2.5, 1.5, 1.0, 1], (10 ** 5, 1))
    refused(lambda: S.coupler_curves(designs, np.zeros(10 ** 5)),
            r"^the coupler curves of 100,000 designs at 100,000 crank angles would take about "
            r"1.16 TiB, more than the memory budget", MemoryBudgetError)
    refused(lambda: S.coupler_curves([["a"] * 10], [0.0]), r"^designs: expected real numbers")
    # a design of zero lengths, and one with a NaN: not assembled, and nothing printed
    _, _, _, ok = S.coupler_curves([[0] * 10, [0, 0, 3.0, 0, 1.0, 3.0, 2.5, 1.5, np.nan, 1]],
                                   [0.0, 1.0])
    assert not ok.any()


def test_a_point_moved_along_a_line_has_no_circle_to_fit():
    """A pure translation along a line: every circle point moves on a line, so no dyad."""
    found = S.approximate_positions([(i, 0) for i in range(7)], [0] * 7)
    assert len(found) == 0 and "0 dyad(s) found" in found.reason


def test_positions_that_do_not_turn_have_no_burmester_curves():
    """A translation puts every centre point at infinity: no valid sample, no warning."""
    assert not S.burmester_curves(P4, [0.0, 0.0, 0.0, 0.0]).valid.any()


def test_five_positions_that_only_translate_give_no_linkage_and_no_warning():
    found = S.five_positions([(i, 0) for i in range(5)], [2 * np.pi, 0, 2 * np.pi, -np.pi, np.pi])
    assert len(found) == 0 and "no real Burmester point" in found.reason


def test_linkages_beyond_what_floats_can_analyse_are_refused():
    two = S.two_positions([(0, 0), (1, 1)], [0, 90], A1=(0, -1), B1=(1, -1), degrees=True)
    refused(lambda: two.solution(1e9, 1), r"^the four-bar found has links from 1 m to 1e\+09 m, "
                                          r"more than 1e\+06 times apart")
    assert two.solution(1e3, 1).model.name                    # a ratio of 1000 is computed
    refused(lambda: S.offset_slider_crank(0.1, 1, rod=1e9),
            r"^rod: the design's wrist pin goes .* beyond the .* a model holds")
