"""Derivatives of sampled data: the order of convergence on a known curve, agreement with
scipy's Savitzky-Golay filter, and error bands that hold the exact derivatives of a noisy
slider-crank displacement (Flores & Claro, *Cinemática de Mecanismos — 4. Análise de
Velocidades*, §4.6.4)."""
import numpy as np
import pytest
from scipy.signal import savgol_filter

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.solvers import differentiate


def test_order_of_convergence_on_a_known_curve():
    """With a fixed window of 11 samples and degree-5 fits, halving the step divides the
    error of dy/dx by about 2^5 and of d2y/dx2 by about 2^4."""
    errors = []
    for n in (41, 81, 161, 321):
        x = np.linspace(0.0, 1.0, n)
        d = differentiate(x, np.sin(3 * x), window=11)
        errors.append((np.max(np.abs(d.velocity - 3 * np.cos(3 * x))),
                       np.max(np.abs(d.acceleration + 9 * np.sin(3 * x)))))
    errors = np.array(errors)
    order = np.log2(errors[:-1] / errors[1:])
    assert np.all(order[:, 0] > 4.7), order
    assert np.all(order[:, 1] > 3.7), order


def test_even_sampling_is_savitzky_golay():
    rng = np.random.default_rng(0)
    x = np.linspace(0.0, 2.0, 101)
    h = x[1] - x[0]
    y = np.exp(x) + 0.01 * rng.standard_normal(x.size)
    d = differentiate(x, y, window=21)
    for deriv, got in ((0, d.y), (1, d.velocity), (2, d.acceleration)):
        expected = savgol_filter(y, 21, 5, deriv=deriv, delta=h, mode="interp")
        np.testing.assert_allclose(got, expected, rtol=1e-8, atol=1e-8 * np.max(np.abs(expected)))


@pytest.mark.parametrize("uneven", [False, True], ids=["even", "uneven"])
@pytest.mark.parametrize("noise", [1e-6, 1e-5, 1e-4])
@pytest.mark.parametrize("seed", range(4))
def test_bands_hold_the_exact_slider_crank_derivatives(uneven, noise, seed):
    """Displacement of a slider-crank (crank 0.1 m, rod 0.3 m, 10 rad/s) over one turn,
    with Gaussian noise: every estimate is within its band of the engine's exact slide
    velocity and acceleration, and the noise is estimated within 30 %."""
    rng = np.random.default_rng(seed)
    period = 2 * np.pi / 10.0
    t = np.sort(rng.uniform(0.0, period, 361)) if uneven else np.linspace(0.0, period, 361)
    sol = kl.analyze(kl.mechanisms.slider_crank(crank=0.1, rod=0.3), q=10.0 * t, qd=10.0)
    x = sol.slide("slide") + noise * rng.standard_normal(t.size)
    d = differentiate(t, x)
    assert d.velocity.shape == d.acceleration_error.shape == (t.size,)
    assert np.all(np.abs(d.velocity - sol.slide_velocity("slide")) <= d.velocity_error)
    assert np.all(np.abs(d.acceleration - sol.slide_acceleration("slide")) <= d.acceleration_error)
    assert 0.7 * noise < d.noise < 1.3 * noise
    # the bands are useful, not merely wide: well under the derivatives' own size
    assert np.median(d.velocity_error) < 0.05 * np.max(np.abs(sol.slide_velocity("slide")))
    assert np.median(d.acceleration_error) < 0.2 * np.max(np.abs(sol.slide_acceleration("slide")))


def test_more_noise_chooses_a_wider_window():
    x = np.linspace(0.0, 1.0, 401)
    rng = np.random.default_rng(3)
    windows = [differentiate(x, np.sin(4 * x) + s * rng.standard_normal(x.size)).window_gcv
               for s in (1e-6, 1e-3)]
    assert windows[0] < windows[1]


@pytest.mark.parametrize("x, y, match", [
    (np.arange(10.0), np.arange(10.0), r"x: expected at least 15 samples, got 10"),
    (np.r_[np.arange(10.0), 5.0, np.arange(11.0, 20.0)], np.arange(20.0),
     r"x\[10\]: expected abscissae that increase, got 5.0 after x\[9\] = 9.0"),
    (np.arange(20.0), np.r_[np.arange(7.0), np.nan, np.arange(8.0, 20.0)],
     r"y\[7\]: expected a finite number, got nan"),
    (np.arange(20.0), np.arange(19.0), r"y: expected as many samples as x \(20\), got 19"),
    (np.arange(20.0), ["a"] * 20, r"y: expected real numbers"),
])
def test_bad_data(x, y, match):
    with pytest.raises(ModelError, match=match):
        differentiate(x, y)


def test_bad_window():
    x = np.linspace(0.0, 1.0, 30)
    with pytest.raises(ModelError, match=r"window: expected a whole number of samples from 11 to 30"):
        differentiate(x, x, window=5)
