"""Function generation: Freudenstein's equation, Chebyshev spacing, the structural error."""
import re

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import chebyshev_points, freudenstein, function_generation

LOG = dict(f=np.log10, x_range=(1.0, 2.0), input_range=(90.0, 150.0), output_range=(0.0, 90.0),
           degrees=True)


@pytest.mark.parametrize("d, a, b, c", [(3.0, 1.0, 3.0, 2.5), (2.0, 1.0, 1.0, 1.0),
                                        (1.0, 2.0, 1.0, 1.5), (4.0, 1.5, 2.0, 3.0)])
def test_freudenstein_recovers_the_lengths_of_a_catalogue_linkage(d, a, b, c):
    fb = kl.mechanisms.fourbar(ground=d, crank=a, coupler=b, rocker=c)
    lo, hi = kl.kinematics.reachable_ranges(fb)[0]
    q = np.linspace(lo, hi, 7)[2:5]
    K = freudenstein(q, kl.analyze(fb, q=q).angle("rocker"))
    # exact algebra on three points: K1 = d/a, K2 = d/c, K3 = (a^2 - b^2 + c^2 + d^2)/(2ac)
    np.testing.assert_allclose(K, [d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)],
                               rtol=1e-10)


def test_chebyshev_points_by_hand():
    # n = 3 on [1, 2]: 1.5 -+ 0.5 cos 30 deg, and 1.5
    np.testing.assert_allclose(chebyshev_points((1.0, 2.0), 3),
                               [1.5 - 0.25 * np.sqrt(3), 1.5, 1.5 + 0.25 * np.sqrt(3)], rtol=1e-15)


def test_structural_error_vanishes_at_the_precision_points():
    sol = function_generation(**LOG, samples=2001)
    assert sol.valid
    # the engine's rocker angle at the precision points (independent of sol.structural_error)
    s = kl.analyze(sol.model, q=sol.q)
    y_gen = (np.log10(1.0) + (s.angle("rocker") - sol.output_range[0])
             / (sol.output_range[1] - sol.output_range[0]) * np.log10(2.0))
    np.testing.assert_allclose(y_gen, np.log10(sol.x), atol=1e-12)
    # the sampled curve changes sign at each precision point (samples 0.0005 apart); it may
    # cross zero elsewhere too: Freudenstein's error is not a polynomial
    e = sol.structural_error
    crossings = sol.x_samples[np.flatnonzero(np.diff(np.sign(e)) != 0)]
    h = sol.x_samples[1] - sol.x_samples[0]
    assert all(np.abs(crossings - x).min() <= h for x in sol.x)


def test_structural_error_against_freudenstein_closed_form():
    """Solve Freudenstein's equation for theta4 with the half-angle formula on the model's
    branch and compare with the engine-based structural error."""
    sol = function_generation(**LOG, samples=101)
    K1, K2, K3 = sol.K
    t2 = np.radians(90 + 60 * (sol.x_samples - 1.0))
    # K1 cos t4 - K2 cos t2 + K3 = cos t2 cos t4 + sin t2 sin t4 -> E cos t4 + F sin t4 + G = 0
    E, F, G = K1 - np.cos(t2), -np.sin(t2), K3 - K2 * np.cos(t2)
    r = np.sqrt(E * E + F * F - G * G)
    roots = [2 * np.arctan2(-F + sg * r, G - E) for sg in (1, -1)]
    target = np.radians(90 * np.log10(sol.x_samples) / np.log10(2.0))
    mapped = [np.log10(2.0) * (np.angle(np.exp(1j * (t - target)))) / (np.pi / 2) for t in roots]
    # the engine's branch is one of the two closed-form roots, the same all along
    best = min(mapped, key=lambda m: np.abs(m - sol.structural_error).max())
    np.testing.assert_allclose(sol.structural_error, best, atol=1e-12)


def test_chebyshev_spacing_beats_even_spacing():
    cheb = function_generation(**LOG)
    even = function_generation(**LOG, points=[1.0, 1.5, 2.0])
    assert cheb.max_structural_error < even.max_structural_error


def test_more_points_by_least_squares():
    sol = function_generation(**LOG, points=5)
    assert sol.x.size == 5 and sol.valid
    assert sol.max_structural_error < 2 * function_generation(**LOG).max_structural_error


def test_least_squares_residual_at_each_precision_point():
    """Seven precision points for three unknowns: K solves the normal equations of
    Freudenstein's equation, and precision_errors are the engine's output errors there."""
    sol = function_generation(**LOG, points=7)
    assert sol.valid and sol.x.size == sol.precision_errors.size == 7
    t2 = np.radians(90 + 60 * (sol.x - 1.0))
    t4 = np.radians(90 * np.log10(sol.x) / np.log10(2.0))
    M = np.column_stack([np.cos(t4), -np.cos(t2), np.ones(7)])
    gradient = M.T @ (M @ sol.K - np.cos(t2 - t4))
    assert np.abs(gradient).max() < 1e-12 * np.abs(M).max() ** 2 * np.abs(sol.K).max()
    # the model is that least-squares linkage: its lengths give K back
    L = sol.lengths
    d, a, b, c = L["ground"], L["crank"], L["coupler"], L["rocker"]
    assert np.all(sol.K[:2] > 0)
    np.testing.assert_allclose(sol.K, [d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)],
                               rtol=1e-12)
    s = kl.analyze(sol.model, q=sol.q)
    y_gen = ((s.angle("rocker") - sol.output_range[0])
             / (sol.output_range[1] - sol.output_range[0]) * np.log10(2.0))
    np.testing.assert_allclose(sol.precision_errors, y_gen - np.log10(sol.x), atol=1e-12)
    # seven points cannot all be met: the residuals are small but not rounding
    assert 1e-7 < np.abs(sol.precision_errors).max() < 1e-3
    assert np.abs(function_generation(**LOG).precision_errors).max() < 1e-12   # three: exact


def test_precision_points_must_be_finite():
    with pytest.raises(ModelError, match=r"points: expected precision points \(x values\) from 1 "
                                         r"to 2 \(x_range\), got \[1\.1, nan, 1\.9\]"):
        function_generation(**LOG, points=[1.1, np.nan, 1.9])


def test_branch_defect_flagged():
    # y = log10 x on [1, 10], crank 45 -> 105 deg, rocker 135 -> 225 deg: Freudenstein's
    # linkage has a negative rocker and cannot move over the range on one branch
    sol = function_generation(np.log10, (1, 10), (45, 105), (135, 225), degrees=True)
    assert sol.branch_defect and not sol.valid
    assert not np.isfinite(sol.max_structural_error)


@pytest.mark.parametrize("kwargs, message", [
    (dict(f=np.cos, x_range=(-1.0, 1.0)), r"f: f\(x0\) = 0.540302 and f\(xf\) = 0.540302 must be different"),
    (dict(input_range=(0.0, 400.0)), r"input_range: the crank would turn a full circle or more"),
    (dict(points=2), r"points: expected a whole number from 3 to 100, got 2"),
    (dict(points=[1.2, 1.8]), r"points: expected at least 3 precision points, got 2"),
    (dict(x_range=(1.0, 1.0)), r"x_range: expected two different finite numbers"),
    (dict(output_range=np.radians([90.0, 90.0]), degrees=False),
     r"^output_range: expected two different finite numbers, got \[1.5707963267948966, "
     r"1.5707963267948966\] rad$"),
    (dict(output_range=(90.0, 90.0)),
     r"^output_range: expected two different finite numbers, got \(90.0, 90.0\) deg$"),
    (dict(ground=-1.0), r"ground: expected a positive length \(m\), got -1.0"),
])
def test_bad_function_tasks(kwargs, message):
    with pytest.raises(ModelError, match=message):
        function_generation(**(LOG | kwargs))


@pytest.mark.parametrize("f, where, what", [
    (lambda x: 1 / (x - 1.2345678901), "1.23456789", "has a pole"),        # between samples
    (np.tan, "1.57079633", "has a pole"),
    (lambda x: np.floor(1.5 * x), "1.33333333", "jumps by 1 "),
    (lambda x: np.where(x < 1.7, x, x + 0.01), "1.7", "jumps by 0.01 "),
])
def test_a_function_not_continuous_over_x_range_is_refused(f, where, what):
    """A pole between the samples used to give an infinite structural error (and Infinity in
    the summary); a linkage generates only a continuous function."""
    with pytest.raises(ModelError, match=rf"^f: expected a function continuous over x_range "
                                         rf"\[1, 2\], but it {what}.*near x = {where}; .* "
                                         r"choose an x_range that leaves that point out$"):
        function_generation(**(LOG | dict(f=f)))


def test_a_function_not_finite_over_x_range_is_refused():
    with pytest.raises(ModelError, match=r"^f: expected finite values over x_range, got nan at "
                                         r"x = 1.5; choose an x_range where f is finite$"):
        function_generation(**(LOG | dict(f=lambda x: np.where(x == 1.5, np.nan, x))))


@pytest.mark.parametrize("f", [np.sqrt, lambda x: np.tanh(1000 * (x - 1.5)),
                               lambda x: 1 / (x - 0.999)])
def test_continuous_functions_steep_or_not_are_kept(f):
    """Steep but continuous (a pole just outside x_range, a steep step): generated, with the
    structural error checked at the precision points (three: met exactly)."""
    sol = function_generation(**(LOG | dict(f=f)))
    assert sol.valid and np.all(np.isfinite(sol.structural_error))
    assert np.abs(sol.precision_errors).max() < 1e-9


# -- precision points as pairs of angles, with the fixed pivots anywhere ----------------------
@pytest.mark.parametrize("phi, O2", [(0.0, (0.0, 0.0)), (0.7, (1.0, 2.0)), (-2.5, (-3.0, 0.5))])
def test_the_pairs_of_a_linkage_on_any_ground_line_give_it_back(phi, O2):
    """The catalogue crank-rocker turned by phi and moved to O2: its own (input, output)
    pairs, angles from +x, give it back, and the model reaches each pair (1e-10: closed form
    vs engine)."""
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    q = np.radians([40.0, 70.0, 100.0])
    out = kl.analyze(fb, q=q).angle("rocker")
    O2 = np.array(O2)
    O4 = O2 + 3.0 * np.array([np.cos(phi), np.sin(phi)])
    sol = kl.synthesis.function_pairs(q + phi, out + phi, O2, O4)
    assert {k: round(v, 10) for k, v in sol.lengths.items()} == {
        "ground": 3.0, "crank": 1.0, "coupler": 3.0, "rocker": 2.5}
    assert sol.valid and not sol.defects
    np.testing.assert_allclose(sol.q, q + phi, rtol=0, atol=1e-12)
    reached = kl.analyze(sol.model, q=q + phi).angle("rocker")
    np.testing.assert_allclose(np.angle(np.exp(1j * (reached - out - phi))), 0, atol=1e-10)
    np.testing.assert_allclose(sol.model.point("O2").xy, O2, atol=1e-12)
    np.testing.assert_allclose(sol.model.point("O4").xy, O4, atol=1e-12)


@pytest.mark.parametrize("turned", ["crank", "rocker", "both"])
def test_pairs_only_a_reversed_link_meets_are_a_defect(turned):
    """A linkage's pairs with the input (or output) rays turned by 180 deg: the pairs fix
    Freudenstein's constants, so the only four-bar on those pivots is the same linkage, its
    crank (rocker) pointing back along the rays; that is listed as a defect, and the model
    still meets the pairs with the reversed link (its angle = the ray's + 180 deg)."""
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    q = np.radians([40.0, 70.0, 100.0])
    out = kl.analyze(fb, q=q).angle("rocker")
    dq = np.pi if turned in ("crank", "both") else 0.0
    dout = np.pi if turned in ("rocker", "both") else 0.0
    sol = kl.synthesis.function_pairs(q + dq, out + dout, (0, 0), (3, 0))
    reversed_ = [d.split(" reversed")[0] for d in sol.defects if " reversed: " in d]
    assert reversed_ == {"crank": ["crank"], "rocker": ["rocker"], "both": ["crank", "rocker"]}[turned]
    np.testing.assert_allclose(np.angle(np.exp(1j * (sol.q - q))), 0, atol=1e-10)  # the crank's own
    reached = kl.analyze(sol.model, q=sol.q).angle("rocker")
    np.testing.assert_allclose(np.angle(np.exp(1j * (reached - out))), 0, atol=1e-10)


def test_pairs_in_degrees_and_decreasing_inputs():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    q = np.radians([100.0, 70.0, 40.0])
    out = np.degrees(kl.analyze(fb, q=q).angle("rocker"))
    sol = kl.synthesis.function_pairs(np.degrees(q), out, (0, 0), (3, 0), degrees=True)
    assert sol.lengths["crank"] == pytest.approx(1.0, abs=1e-10)
    assert sol.input_range == pytest.approx((q[0], q[-1]), abs=1e-12)


@pytest.mark.parametrize("args, message", [
    (([10, 30, 20], [1, 2, 3]), "input_angles: expected angles in the order the crank passes them, "
                                "all increasing or all decreasing, got 10, 30, 20 deg"),
    (([10, 200, 380], [1, 2, 3]), "input_angles: the crank would turn a full circle or more"),
    (([10, 20], [1, 2]), "input_angles, output_angles: expected 3 to 100 pairs, got 2"),
    (([10, 20, 30], [1, 2]), "expected two arrays of the same shape (n,), got (3,) and (2,)"),
    (([10, float("nan"), 30], [1, 2, 3]), "input_angles[1]: expected finite angles"),
])
def test_bad_pairs_are_refused_saying_why(args, message):
    with pytest.raises(ModelError, match=re.escape(message)):
        kl.synthesis.function_pairs(*args, degrees=True)


def test_pivots_on_one_another_are_refused():
    with pytest.raises(ModelError, match=r"O4: expected a fixed pivot apart from O2"):
        kl.synthesis.function_pairs([10, 20, 30], [40, 50, 70], (1, 1), (1, 1), degrees=True)


def test_a_pairs_task_file_is_read_in_its_units_and_solved():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    q = np.radians([40.0, 70.0, 100.0])
    out = np.degrees(kl.analyze(fb, q=q).angle("rocker"))
    task = kl.io.read_task({"task": "function", "units": {"length": "mm", "angle": "deg"},
                            "function": {"pairs": [[a, b] for a, b in zip(np.degrees(q), out)],
                                         "O2": [0, 0], "O4": [3000, 0]}})
    (sol,), _ = kl.io.solve_task(task, verify=True)
    assert sol.lengths["crank"] == pytest.approx(1.0, abs=1e-9)            # m: SI inside
    row = kl.io.task_summary(task, [sol], {})["solutions"][0]
    assert row["lengths"]["crank"] == pytest.approx(1000.0, abs=1e-6)      # the task's mm


@pytest.mark.parametrize("function, message", [
    ({"pairs": [[10, 1], [20, 2]]}, "function.pairs: expected 3 to 100 pairs"),
    ({"pairs": [[10, 1], [20, "x"], [30, 3]]}, "function.pairs: expected finite numbers of shape (n, 2)"),
    ({"pairs": [[10, 1], [30, 2], [20, 3]]}, "function.pairs: expected angles in the order the crank passes them"),
    ({"pairs": [[10, 40], [20, 50], [30, 70]], "expression": "x"}, "function.expression: not used with pairs"),
    ({"pairs": [[10, 40], [20, 50], [30, 70]], "O2": [0, 0], "ground": 2},
     "function.ground: not used with O2 and O4"),
    ({"expression": "x", "x_range": [0, 1], "input_range": [10, 60], "output_range": [20, 80],
      "O2": [0, 0]}, "function.O2: used only with pairs"),
])
def test_a_pairs_task_typed_wrong_names_its_field(function, message):
    with pytest.raises(ModelError, match=re.escape(message)):
        task = kl.io.read_task({"task": "function", "units": {"angle": "deg"}, "function": function})
        kl.io.solve_task(task)



@pytest.mark.parametrize("scale", [1e-4, 1.0, 1e4])
def test_pairs_are_scale_free(scale):
    """The same pairs on pivots 1e-4 to 1e4 times as far apart: the same linkage to scale,
    the same defects and the same crank angles (1e-9: rounding through the engine)."""
    pairs = ([49, 79, 109], [97, 101, 112])
    O2, O4 = np.array([0.03, -0.04]), np.array([0.33, 0.01])
    one = kl.synthesis.function_pairs(*pairs, O2, O4, degrees=True)
    sol = kl.synthesis.function_pairs(*pairs, O2 * scale, O4 * scale, degrees=True)
    for k, v in one.lengths.items():
        assert sol.lengths[k] == pytest.approx(v * scale, rel=1e-9)
    assert sol.defects == one.defects
    np.testing.assert_allclose(sol.q, one.q, rtol=0, atol=1e-12)
    np.testing.assert_allclose(sol.structural_error, one.structural_error, rtol=0, atol=1e-9)
