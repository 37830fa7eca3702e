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


# -- scale, float64's range and size ---------------------------------------------------------

@pytest.mark.parametrize("uneven", [False, True], ids=["even", "uneven"])
@pytest.mark.parametrize("sx, sy", [(1.0, 1.0), (1e-200, 1e-250), (1e200, 1e150), (1e-150, 1e-300),
                                    (1e100, 1e300), (3e-7, 5e4)])
def test_derivatives_of_a_scaled_sine_do_not_depend_on_the_scale(uneven, sx, sy):
    """y = sy sin(3 t) at x = sx (t + 3): dy/dx = 3 (sy/sx) cos(3 t), d2y/dx2 = -9 (sy/sx^2)
    sin(3 t), whatever the scales (the fits are made on x and y brought to order one).
    With a window of 21 samples of 201 the fit's own error is about 3e-6 of the velocity's
    amplitude and 1e-4 of the acceleration's; the results agree with the unscaled ones to
    rounding."""
    rng = np.random.default_rng(2)
    t = np.sort(rng.uniform(0.0, 2.0, 201)) if uneven else np.linspace(0.0, 2.0, 201)
    d = differentiate(sx * (t + 3.0), sy * np.sin(3 * t), window=21)
    ref = differentiate(t, np.sin(3 * t), window=21)
    v, a = d.velocity * (sx / sy), d.acceleration * (sx / sy) * sx
    assert np.max(np.abs(v - 3 * np.cos(3 * t))) < 1e-5 * 3
    assert np.max(np.abs(a + 9 * np.sin(3 * t))) < 3e-4 * 9
    np.testing.assert_allclose(v, ref.velocity, rtol=0, atol=1e-9 * 3)
    np.testing.assert_allclose(a, ref.acceleration, rtol=0, atol=1e-9 * 9)
    np.testing.assert_allclose(d.velocity_error * (sx / sy), ref.velocity_error, rtol=1e-6)
    assert d.noise / sy == pytest.approx(ref.noise, rel=1e-6)


def test_huge_abscissae_give_tiny_finite_derivatives():
    """x = 1e200 k, y = k: dy/dx = 1e-200 (exact for a line), d2y/dx2 = 0."""
    x, y = 1e200 * np.arange(15.0), np.arange(15.0)
    d = differentiate(x, y)
    np.testing.assert_allclose(d.velocity, 1e-200, rtol=1e-12)
    assert np.all(np.abs(d.acceleration) <= 1e-300)
    np.testing.assert_allclose(d.y, y, rtol=0, atol=1e-12)


@pytest.mark.parametrize("x, y, match", [
    # d2y/dx2's scale is 1 / (1e-200)^2 = 1e400: beyond float64
    (1e-200 * np.arange(15.0), np.arange(15.0),
     r"^y: expected the acceleration d2y/dx2 within float64's range \(up to 1.8e\+308\), got "
     r"beyond it; express y in a larger unit or x in a smaller one$"),
    # noise of about 1e308 a sample: its error bands are beyond float64
    (np.arange(30.0), 1e308 * (-1.0) ** np.arange(30),
     r"^y: expected the velocity's error band within float64's range"),
    # the smoothed curve is near 0, and the residuals near +-1.7e308 fit, but not their sum
    (np.arange(15.0), 1.7e308 * (-1.0) ** np.arange(15),
     r"^y: expected the residuals within float64's range \(up to 1.8e\+308\), got beyond it; "
     r"express y in a larger unit$"),
    # eight samples, then seven a billion later: no window of 11 spans either side
    (np.r_[np.arange(8.0), 1e9 + np.arange(8.0, 15.0)], np.arange(15.0),
     r"^x\[8\]: expected samples spread over each local fit, got a gap from x\[7\] = 7.0 to "
     r"x\[8\] = 1000000008.0 that leaves the fit of 11 samples around x\[0\] too few samples on "
     r"a side for a polynomial of degree 7; fill in the gap, or differentiate the pieces"),
    # steps of 1e-4 at 1e9, where float64's spacing is 1.2e-7
    (1e9 + 1e-4 * np.arange(15.0), np.arange(15.0),
     r"^x\[\d+\]: expected steps that float64 resolves \(at least 1000 times its spacing at the "
     r"largest \|x\|\), got .*; subtract a reference from x"),
    (np.r_[0.0, 1e-13, np.arange(1.0, 14.0)], np.arange(15.0),
     r"^x\[1\]: expected samples apart by more than 1e-12 of the range of x, got x\[1\] = 1e-13 "
     r"after x\[0\] = 0.0; merge samples this close$"),
])
def test_what_float64_cannot_differentiate_is_refused(x, y, match):
    with pytest.raises(ModelError, match=match) as info:
        differentiate(x, y)
    assert "\n" not in str(info.value)


def test_even_filter_against_per_sample_fits():
    """The evenly spaced path (one Savitzky-Golay filter, by FFT when the window is long)
    against solving every sample's least-squares problem, on the same data."""
    from kinelab.solvers._differentiate import _even_fits, _uneven_fits
    n = 3001
    u = np.linspace(0.0, 1.0, n)
    v = np.sin(5 * u) + 1e-3 * np.random.default_rng(4).standard_normal(n)
    rows = np.arange(n)
    for window in (11, 301, 2001):
        fast = _even_fits(v, rows, window, (5, 7))
        slow, bad = _uneven_fits(u, v, rows, window, (5, 7))
        assert not bad.any()
        for d in (5, 7):
            for got, want in zip(fast[d], slow[d]):        # value, dy/du, d2y/du2; their norms
                size = np.max(np.abs(want), axis=0)
                assert np.all(np.abs(got - want) <= 1e-10 * size), np.max(np.abs(got - want) / size)


def test_a_long_evenly_sampled_curve_is_fast_and_right():
    """10^5 samples of a noisy sine: seconds, not minutes, and the bands hold (4 standard
    errors: a rare sample may fall just outside, so the test counts them)."""
    import time
    n = 100_000
    t = np.linspace(0.0, 2.0, n)
    y = np.sin(3 * t) + 1e-3 * np.random.default_rng(8).standard_normal(n)
    begin = time.process_time()
    d = differentiate(t, y)
    assert time.process_time() - begin < 20.0
    outside = np.abs(d.velocity - 3 * np.cos(3 * t)) > d.velocity_error
    assert np.mean(outside) < 1e-3
    assert 0.9e-3 < d.noise < 1.1e-3


def test_size_limits():
    from kinelab.solvers._differentiate import MAX_SAMPLES, MAX_UNEVEN
    x = np.sort(np.random.default_rng(0).uniform(0.0, 1.0, MAX_UNEVEN + 1))
    with pytest.raises(ModelError, match=r"^x: expected at most 10,000 unevenly spaced samples, "
                                         r"got 10,001; resample the curve at a constant step"):
        differentiate(x, x)
    x = np.arange(MAX_SAMPLES + 1.0)
    with pytest.raises(ModelError, match=r"^x: expected at most 1,000,000 samples, got 1,000,001; "
                                         r"cut the curve into pieces"):
        differentiate(x, x)
