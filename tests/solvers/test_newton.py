import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from kinelab.errors import ConvergenceError, ModelError, SingularityError
from kinelab.solvers import iteration_table, newton

from tests.solvers._slider_crank import closed_form, equations


def slider_crank(L2, L3, th2):
    """Φ(θ3, l) and its Jacobian at the crank angles θ2 (one per sample)."""
    fun, jac, _ = equations(L2, L3)
    return (lambda x: fun(x, th2)), (lambda x: jac(x, th2))


@given(st.floats(0.1, 1.0), st.floats(1.5, 5.0))
def test_newton_against_closed_form_slider_crank(L2, L3):
    th2 = np.linspace(-np.pi, np.pi, 37)
    fun, jac = slider_crank(L2, L3, th2)
    sol = newton(fun, jac, np.tile([0.0, L2 + L3], (th2.size, 1)))
    th3, l = closed_form(L2, L3, th2)
    assert sol.x.shape == (37, 2) and sol.converged.all()
    # 1e-10: closed form against the engine (DESIGN.md).
    assert np.max(np.abs(sol.x[:, 0] - th3)) < 1e-10
    assert np.max(np.abs(sol.x[:, 1] - l)) < 1e-10
    assert np.all(sol.residual_norm < 1e-12 * (L2 + L3))


def test_batch_equals_samples_solved_one_by_one():
    th2 = np.array([0.1, 1.0, 2.5, -2.0])
    x0 = np.array([[0.0, 3.0], [-0.5, 2.0], [0.3, 1.0], [1.0, 4.0]])
    fun, jac = slider_crank(1.0, 2.0, th2)
    batch = newton(fun, jac, x0)
    assert len(set(batch.iterations.tolist())) > 1       # samples finish at different times
    for s in range(4):
        f1, j1 = slider_crank(1.0, 2.0, th2[s])
        one = newton(f1, j1, x0[s])
        assert one.x.shape == (2,) and one.converged.shape == ()
        assert one.iterations == batch.iterations[s]
        # Held samples are untouched, so the arithmetic is the same: equal to rounding.
        assert np.max(np.abs(one.x - batch.x[s])) <= 1e-15


def test_converged_samples_stop_changing_and_fun_sees_the_whole_batch():
    th2 = np.array([0.2, 1.2])
    fun, jac = slider_crank(1.0, 2.0, th2)
    shapes = []

    def counting(x):
        shapes.append(x.shape)
        return fun(x)
    # Sample 0 starts at its solution, sample 1 far away.
    x0 = np.array([closed_form(1.0, 2.0, 0.2), [0.0, 3.0]])
    sol = newton(counting, jac, x0, history=True)
    assert set(shapes) == {(2, 2)}
    h = sol.history
    assert sol.iterations.tolist() == [1, h.x.shape[0]]
    assert h.active[:, 0].tolist() == [True] + [False] * (h.x.shape[0] - 1)
    assert np.all(h.x[1:, 0] == sol.x[0]) and np.all(h.step[1:, 0] == 0)


def test_convergence_is_quadratic():
    fun, jac = slider_crank(1.0, 1.0, np.radians(45.0))
    sol = newton(fun, jac, [np.radians(-60.0), 1.0], history=True)
    r = np.max(np.abs(sol.history.residual), axis=1)
    # Newton: r_{k+1} <= C r_k² with C of order |J⁻¹| |Φ''| ~ 1; here C < 2 until rounding.
    ratios = r[1:4] / r[:3] ** 2
    assert np.all(ratios < 2.0), ratios


def test_singular_jacobian_is_named_or_masked():
    th2 = np.array([0.3, 0.4, 0.5])
    fun, jac = slider_crank(1.0, 1.0, th2)
    x0 = np.array([[-0.3, 2.0], [np.pi / 2, 1.0], [-0.5, 2.0]])   # cos θ3 = 0: det J = 0
    with pytest.raises(SingularityError, match=r"singular Jacobian at 1 of 3 samples \(1\) "
                                               r"\(first: sample 1, iteration 0") as info:
        newton(fun, jac, x0)
    assert info.value.result.converged.tolist() == [True, False, True]
    sol = newton(fun, jac, x0, on_failure="mask")
    assert sol.singular.tolist() == [False, True, False]
    assert np.all(sol.x[1] == x0[1]) and sol.iterations[1] == 0


def test_not_converged_names_the_samples_and_keeps_the_result():
    th2 = np.linspace(0.1, 1.0, 12)
    fun, jac = slider_crank(1.0, 2.0, th2)
    x0 = np.tile([2.0, 0.5], (12, 1))
    with pytest.raises(ConvergenceError, match=r"did not converge in 2 iterations for 12 of 12 "
                                               r"samples \(0, 1, .*, 9, … \(12 in all\)\); at "
                                               r"sample 0 the last residual max\|Φ\| = .*"
                                               r"try a closer starting guess") as info:
        newton(fun, jac, x0, max_iter=2)
    assert info.value.result.iterations.tolist() == [2] * 12
    sol = newton(fun, jac, x0, max_iter=2, on_failure="mask")
    assert not sol.converged.any() and np.all(sol.residual_norm > 0)


def test_divergence_to_non_finite_is_reported():
    # Newton on atan(x) = 0 diverges from |x0| > 1.39 (each step roughly squares |x|); this
    # fun, like a mechanism's sqrt of a negative, is undefined far out and returns NaN there.
    def fun(x):
        return np.where(np.abs(x) < 1e3, np.arctan(x), np.nan)

    def jac(x):
        return (1.0 / (1.0 + x**2))[..., None]
    with pytest.raises(ConvergenceError, match=r"diverged to non-finite values for 1 of 2 "
                                               r"samples \(1\)") as info:
        newton(fun, jac, [[0.5], [3.0]])
    assert info.value.result.converged.tolist() == [True, False]
    assert newton(fun, jac, [0.5]).x == pytest.approx([0.0], abs=1e-15)


def test_history_table_and_dataframe():
    fun, jac = slider_crank(1.0, 1.0, np.radians(45.0))
    sol = newton(fun, jac, [np.radians(-60.0), 1.0], history=True)
    frame = sol.history.to_dataframe(names=["theta3", "l"])
    assert list(frame.columns) == ["k", "theta3", "l", "phi1", "phi2", "dtheta3", "dl"]
    assert frame["k"].tolist() == list(range(sol.iterations))
    last = frame.iloc[-1]
    assert np.array_equal(last[["theta3", "l"]].to_numpy(float)
                          + last[["dtheta3", "dl"]].to_numpy(float), sol.x)
    text = iteration_table(sol.history, names=["theta3", "l"], digits=3)
    assert text.splitlines()[0].split() == ["k", "theta3", "l", "phi1", "phi2", "dtheta3", "dl"]
    assert text.splitlines()[1].split() == ["0", "-1.05", "1", "0.207", "-0.159", "0.318",
                                            "0.482"]
    with pytest.raises(ModelError, match=r"names: expected 2 names, one per unknown, got 1"):
        iteration_table(sol.history, names=["theta3"])


def test_batched_history_dataframe_has_sample_column():
    th2 = np.array([0.2, 1.2])
    fun, jac = slider_crank(1.0, 2.0, th2)
    sol = newton(fun, jac, np.array([[0.0, 3.0], [0.0, 3.0]]), history=True)
    frame = sol.history.to_dataframe()
    assert list(frame.columns[:2]) == ["k", "sample"]
    assert len(frame) == sol.iterations.sum()
    assert iteration_table(sol.history, sample=1).count("\n") == sol.iterations[1]


@pytest.mark.parametrize("kwargs, message", [
    ({"on_failure": "warn"}, r"on_failure: expected one of 'raise', 'mask', got 'warn'"),
    ({"max_iter": 0}, r"max_iter: expected a whole number from 1 to 10,000, got 0"),
    ({"max_iter": 2.5}, r"max_iter: expected a whole number from 1 to 10,000, got 2.5"),
    ({"tol": 0.0}, r"tol: expected a positive number below 1, got 0.0"),
    ({"tol": "a"}, r"tol: expected a positive number below 1, got 'a'"),
    ({"tol": np.nan}, r"tol: expected a positive number below 1, got nan"),
    ({"rcond": "a"}, r"rcond: expected a number from 0 to below 1, got 'a'"),
    ({"rcond": np.nan}, r"rcond: expected a number from 0 to below 1, got nan"),
    ({"rcond": -1}, r"rcond: expected a number from 0 to below 1, got -1"),
    ({"history": None}, r"history: expected True or False, got None"),
])
def test_bad_options(kwargs, message):
    fun, jac = slider_crank(1.0, 2.0, 0.3)
    with pytest.raises(ModelError, match=message):
        newton(fun, jac, [0.0, 3.0], **kwargs)


def test_fun_with_the_wrong_shape_is_explained():
    fun, jac = slider_crank(1.0, 2.0, 0.3)
    with pytest.raises(ModelError, match=r"fun: expected an array of shape \(N, n\) = \(1, 2\) "
                                         r"for x of shape \(1, 2\), got \(2,\)"):
        newton(lambda x: fun(x)[0], jac, [0.0, 3.0])
    with pytest.raises(ModelError, match=r"x0: expected shape \(n,\) or \(N, n\)"):
        newton(fun, jac, np.zeros((1, 1, 2)))


def test_complex_start_iterates_in_complex_arithmetic():
    # z² + 1 = 0 has no real root; from a complex start Newton finds i.
    def fun(z):
        return z**2 + 1

    def jac(z):
        return (2 * z)[..., None]
    sol = newton(fun, jac, [0.5 + 0.5j])
    assert sol.converged and abs(sol.x[0] - 1j) < 1e-15
    with pytest.raises(ModelError, match=r"fun: expected real values for a real x, got "
                                         r"complex ones; pass a complex x0"):
        newton(lambda x: x + 1j, jac, [1.0])


def test_unknowns_of_different_scales_converge_each_on_its_own():
    # x0 = 1e13 solves the first equation exactly; the first step of x1 (5 -> 2.7) is far
    # smaller than 1e-12 of the largest unknown, but it is not a converged x1.
    def fun(x):
        return np.stack([x[:, 0] - 1e13, x[:, 1] ** 2 - 2], -1)

    def jac(x):
        one, zero = np.ones(len(x)), np.zeros(len(x))
        return np.stack([np.stack([one, zero], -1), np.stack([zero, 2 * x[:, 1]], -1)], -2)
    sol = newton(fun, jac, [1e13, 5.0])
    assert sol.converged
    assert sol.x[0] == 1e13
    assert sol.x[1] == pytest.approx(np.sqrt(2.0), rel=1e-15)
    assert sol.residual_norm < 1e-14
    assert sol.iterations > 1


def test_a_small_step_that_leaves_a_large_residual_is_not_convergence():
    # A Jacobian 1e15 times too large (a slip in jac): every step is below tol, but x stays
    # near 0 where Φ = -1; the old step test alone called that a root.
    def fun(x):
        return x - 1.0

    def jac(x):
        return np.full((len(x), 1, 1), 1e15)
    with pytest.raises(ConvergenceError, match=r"did not converge in 50 iterations.*"
                                               r"residual max\|Φ\| = 1"):
        newton(fun, jac, [0.0])


@pytest.mark.parametrize("change, message", [
    ({"x0": ["a", 1.0]}, r"^x0: expected numbers, got \['a', 1.0\]$"),
    ({"x0": [10**400, 1.0]}, r"^x0: expected numbers, got \[a whole number of 401 digits, 1.0\]$"),
    ({"x0": [np.inf, 1.0]}, r"^x0: expected finite numbers, got inf at index \(0,\)"),
    ({"fun": 1}, r"^fun: expected a function, got 1$"),
    ({"jac": None}, r"^jac: expected a function, got None$"),
    ({"fun": lambda x: "abc"}, r"^fun: expected an array of numbers, got 'abc'"),
    ({"fun": lambda x: [[None, 1.0]]}, r"^fun: expected an array of numbers, got \[\[None, 1.0\]\]"),
])
def test_bad_arguments_are_named(change, message):
    fun, jac = slider_crank(1.0, 2.0, 0.3)
    arguments = {"fun": fun, "jac": jac, "x0": [0.0, 3.0], **change}
    with pytest.raises(ModelError, match=message):
        newton(**arguments)


@pytest.mark.parametrize("change, message", [
    ({"digits": -1}, r"^digits: expected a whole number from 1 to 17, got -1$"),
    ({"digits": "a"}, r"^digits: expected a whole number from 1 to 17, got 'a'$"),
    ({"names": ["a\nb", "c"]}, r"^names: expected a name of printable characters .*got 'a\\nb'$"),
    ({"names": "ab"}, r"^names: expected a list of 2 names, one per unknown, got 'ab'$"),
    ({"history": None}, r"^history: expected the history of a solve"),
    ({"sample": "a"}, r"^sample: expected the index of a sample, got 'a'$"),
])
def test_bad_table_arguments_are_named(change, message):
    fun, jac = slider_crank(1.0, 2.0, 0.3)
    sol = newton(fun, jac, [0.0, 3.0], history=True)
    arguments = {"history": sol.history, **change}
    with pytest.raises(ModelError, match=message):
        iteration_table(**arguments)
