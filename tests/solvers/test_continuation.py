import warnings

import numpy as np
import pytest

from kinelab.errors import ConvergenceError, ModelError
from kinelab.solvers import continuation

from tests.solvers._slider_crank import closed_form, equations as slider_crank


def wrapped(a):
    return np.angle(np.exp(1j * a))


@pytest.mark.parametrize("tangent", [True, False])
def test_follows_one_branch_over_a_cycle(tangent):
    L2, L3 = 1.0, 1.2
    fun, jac, dfun_dp = slider_crank(L2, L3)
    th2 = np.radians(np.arange(0.0, 361.0, 10.0))
    path = continuation(fun, jac, [0.1, 2.0], th2, dfun_dp=dfun_dp if tangent else None)
    assert path.reached.all() and path.x.shape == (37, 2)
    th3, l = closed_form(L2, L3, th2)                    # the branch started on
    # 1e-10: closed form against the engine (DESIGN.md).
    assert np.max(np.abs(wrapped(path.x[:, 0] - th3))) < 1e-10
    assert np.max(np.abs(path.x[:, 1] - l)) < 1e-10


def test_slow_contraction_halves_the_step_instead_of_changing_branch():
    # Steps of 120° with the secant predictor: the corrector from the full step reaches
    # the other assembly mode unless the contraction test sends it back to halve.
    L2, L3 = 1.0, 2.0
    fun, jac, _ = slider_crank(L2, L3)
    th2 = np.linspace(0.0, 2 * np.pi, 4)
    path = continuation(fun, jac, [0.0, 3.0], th2)
    assert path.halvings.sum() > 0
    th3, _ = closed_form(L2, L3, th2)
    assert np.max(np.abs(wrapped(path.x[:, 0] - th3))) < 1e-10


def test_several_paths_advance_together():
    fun, jac, dfun_dp = slider_crank(1.0, 3.0)
    x0 = np.array([[0.0, 4.0], [np.pi, -2.0]])          # both assembly modes
    path = continuation(fun, jac, x0, np.linspace(0, 1, 5), dfun_dp=dfun_dp)
    assert path.x.shape == (5, 2, 2)
    th3, _ = closed_form(1.0, 3.0, np.linspace(0, 1, 5))
    assert np.max(np.abs(wrapped(path.x[:, 0, 0] - th3))) < 1e-10
    assert np.max(np.abs(wrapped(path.x[:, 1, 0] - (np.pi - th3)))) < 1e-10


def test_limit_position_stops_the_path():
    # x² + p² = 1 has no real x past p = 1: the input cannot go further.
    def fun(x, p):
        return x**2 + p**2 - 1

    def jac(x, p):
        return (2 * x)[..., None]
    params = np.array([0.0, 0.3, 0.6, 0.9, 1.1])
    with pytest.raises(ConvergenceError, match=r"could not advance past p = 0\.9 toward "
                                               r"p = 1\.\d+ .*a limit position") as info:
        continuation(fun, jac, [1.0], params)
    path = info.value.result
    assert path.reached.tolist() == [True] * 4 + [False]
    assert path.halvings[4] == 12
    masked = continuation(fun, jac, [1.0], params, on_failure="mask")
    assert masked.reached.tolist() == path.reached.tolist()
    assert np.all(np.isfinite(masked.x)) and masked.x[4] == masked.x[3]
    assert masked.x[:4, 0] == pytest.approx(np.sqrt(1 - params[:4] ** 2), abs=1e-12)


@pytest.mark.parametrize("params, message", [
    ([0.0, 1.0, 0.5], r"params: expected strictly increasing or strictly decreasing"),
    ([[0.0, 1.0]], r"params: expected a 1-D array of finite values, got shape \(1, 2\)"),
])
def test_bad_params(params, message):
    fun, jac, _ = slider_crank(1.0, 2.0)
    with pytest.raises(ModelError, match=message):
        continuation(fun, jac, [0.0, 3.0], params)


def _circle():
    return (lambda x, p: x**2 + p**2 - 1), (lambda x, p: (2 * x)[..., None])


@pytest.mark.parametrize("change, message", [
    ({"max_halvings": 10**6}, r"^max_halvings: expected a whole number from 0 to 50, got 1000000$"),
    ({"max_halvings": -1}, r"^max_halvings: expected a whole number from 0 to 50, got -1$"),
    ({"max_halvings": np.nan}, r"^max_halvings: expected a whole number from 0 to 50, got nan$"),
    ({"x0": ["a"]}, r"^x0: expected real numbers, got \['a'\]$"),
    ({"x0": [10**400]}, r"^x0: expected real numbers, got \[a whole number of 401 digits\]$"),
    ({"params": ["a"]}, r"^params: expected real numbers, got \['a'\]$"),
    ({"params": [0, 10**400]}, r"^params: expected real numbers, got \[0, a whole number of 401"),
    ({"params": [0.0, np.nan]}, r"^params: expected finite numbers, got nan at index \(1,\)$"),
    ({"params": np.linspace(0.0, 0.5, 100_001)},
     r"^params: expected at most 100,000 values, got 100,001; each is one step"),
    ({"dfun_dp": 1}, r"^dfun_dp: expected a function, got 1$"),
    ({"fun": None}, r"^fun: expected a function, got None$"),
    ({"dfun_dp": lambda x, p: np.zeros(5)},
     r"^dfun_dp: expected an array of shape \(N, n\) = \(1, 1\) for x of shape \(1, 1\), got \(5,\)"),
    ({"dfun_dp": lambda x, p: np.zeros(x.shape + (1,))},
     r"^dfun_dp: expected an array of shape \(N, n\) = \(1, 1\) .*got \(1, 1, 1\)"),
    ({"tol": -1.0}, r"^tol: expected a positive number below 1, got -1.0$"),
])
def test_bad_arguments_are_named(change, message):
    fun, jac = _circle()
    arguments = {"fun": fun, "jac": jac, "x0": [1.0], "params": [0.0, 0.3, 0.6], **change}
    with pytest.raises(ModelError, match=message):
        continuation(**arguments)


def test_many_halvings_stop_at_the_resolution_of_p():
    # x² + p² = 1 has no solution past p = 1: 50 halvings of the step 0.9 -> 1.1 end at a
    # limit position, with finite values and no warning (the step never reaches zero).
    fun, jac = _circle()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        path = continuation(fun, jac, [1.0], [0.0, 0.3, 0.6, 0.9, 1.1], max_halvings=50,
                            on_failure="mask")
    assert path.reached.tolist() == [True, True, True, True, False]
    assert path.halvings[4] == 50 and np.all(np.isfinite(path.x))
    # at p = 1e16 a step of 2 cannot be halved (1e16 + 1 is 1e16): it is a step that fails
    far = continuation(lambda x, p: x**2 + (p - 1e16)**2 - 1, jac, [1.0], [1e16, 1e16 + 2.0],
                       max_halvings=50, on_failure="mask")
    assert far.reached.tolist() == [True, False] and far.halvings.tolist() == [0, 0]
