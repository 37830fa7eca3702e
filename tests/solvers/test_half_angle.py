import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from kinelab.errors import AssemblyError, ModelError
from kinelab.solvers import half_angle

coefficient = st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False)


def residual(E, F, G, theta):
    return E * np.cos(theta) + F * np.sin(theta) + G


@given(coefficient, coefficient, coefficient)
def test_roots_satisfy_the_equation_and_count_is_right(E, F, G):
    R = np.hypot(E, F)
    scale = np.hypot(R, G)
    # Keep clear of the tangent band, where the count is a matter of tolerance.
    assume(abs(R - abs(G)) > 1e-9 * scale)
    sol = half_angle(E, F, G)
    assert sol.count == (2 if R > abs(G) else 0)
    assert np.all(np.isfinite(sol.theta)) and np.all(np.abs(sol.theta) <= np.pi)
    if sol.count == 2:
        # 1e-12: each root is a couple of atan2/sqrt operations from exact; the residual
        # is measured relative to the size of the coefficients.
        assert np.all(np.abs(residual(E, F, G, sol.theta)) <= 1e-12 * scale)
        assert sol.gap == 0
    else:
        assert sol.gap == pytest.approx(abs(G) - R, rel=1e-12, abs=1e-12 * scale)
        # The closest-approach angle misses by exactly the gap.
        assert abs(residual(E, F, G, sol.theta[0])) == pytest.approx(sol.gap, rel=1e-9,
                                                                     abs=1e-12 * scale)


@given(st.floats(0.01, 100), st.floats(-np.pi, np.pi), st.floats(-0.99, 0.99))
def test_columns_are_the_documented_branches(R, phi, c):
    # E cos θ + F sin θ + G = R cos(θ - φ) + G with G = -R c: θ = φ ∓ acos(c).
    E, F, G = R * np.cos(phi), R * np.sin(phi), -R * c
    sol = half_angle(E, F, G)
    expected = phi + np.array([-1.0, 1.0]) * np.arccos(c)
    difference = np.angle(np.exp(1j * (sol.theta - expected)))
    # 1e-6 rad: acos is ill-conditioned near |c| = 1 (d acos/dc ~ 1/sqrt(1 - c²) ~ 7 here).
    assert np.all(np.abs(difference) < 1e-6)


@given(st.floats(0.01, 100), st.floats(-np.pi, np.pi), st.sampled_from([-1.0, 1.0]))
def test_tangent_gives_one_root_in_both_columns(R, phi, sign):
    E, F = R * np.cos(phi), R * np.sin(phi)
    G = sign * np.hypot(E, F)
    sol = half_angle(E, F, G)
    assert sol.count == 1 and sol.gap == 0
    assert sol.theta[0] == sol.theta[1]
    assert abs(residual(E, F, G, sol.theta[0])) <= 1e-12 * np.sqrt(2) * R


def test_root_at_pi_lost_by_the_tangent_substitution():
    # G = E: the quadratic (G - E)u² + 2Fu + (G + E) = 0 is linear, u = -(G + E)/(2F)
    # gives one root (*Mecanismos*, §4.5 case 1); the other is θ = π (u = ∞).
    sol = half_angle(1.0, 2.0, 1.0)
    assert sol.count == 2
    assert sol.theta[1] == pytest.approx(np.pi, abs=1e-15)
    assert np.tan(sol.theta[0] / 2) == pytest.approx(-(1.0 + 1.0) / (2 * 2.0), rel=1e-14)
    # G = E and F = 0: the double root θ = π alone.
    sol = half_angle(3.0, 0.0, 3.0)
    assert sol.count == 1 and np.all(sol.theta == np.pi)


def test_small_G_minus_E_stays_accurate():
    # G - E = 1e-15: the notes' formula divides by it; the roots are ~π and one finite.
    E, F, G = 1.0, 1.0, 1.0 + 1e-15
    sol = half_angle(E, F, G)
    assert np.all(np.abs(residual(E, F, G, sol.theta)) <= 1e-15)


def test_degenerate_E_F_zero_has_no_root_and_is_reported():
    sol = half_angle([0.0, 0.0], [0.0, 0.0], [2.0, 0.0])
    assert sol.count.tolist() == [0, 0]
    assert sol.gap.tolist() == [2.0, 0.0]
    assert np.all(np.isfinite(sol.theta))
    with pytest.raises(AssemblyError, match=r"every θ satisfies it"):
        half_angle(0.0, 0.0, 0.0, strict=True)


def test_broadcasting_shapes():
    E = np.ones((4, 1))
    F = np.zeros(3)
    sol = half_angle(E, F, 0.5)
    assert sol.theta.shape == (4, 3, 2)
    assert sol.count.shape == sol.gap.shape == (4, 3)
    assert half_angle(1.0, 0.0, 0.0).theta.shape == (2,)


def test_vectorised_equals_elementwise():
    rng = np.random.default_rng(3)
    E, F, G = rng.normal(size=(3, 50))
    sol = half_angle(E, F, G)
    for i in range(0, 50, 7):
        one = half_angle(E[i], F[i], G[i])
        assert np.array_equal(one.theta, sol.theta[i]) and one.count == sol.count[i]


def test_strict_raises_with_the_gap():
    with pytest.raises(AssemblyError, match=r"no real root at 1 of 3 entries; worst at index "
                                            r"\(2,\): .* = 0\.5 > 0") as info:
        half_angle([1.0, 1.0, 1.0], 0.0, [0.0, -1.0, 1.5], strict=True)
    assert info.value.gap == pytest.approx(0.5)
    assert isinstance(info.value, ValueError)
    # All roots present: strict is silent.
    assert half_angle(2.0, 0.0, 1.0, strict=True).count == 2


def test_bad_coefficients_are_rejected():
    with pytest.raises(ModelError, match=r"^E: expected finite numbers, got nan at index \(1,\)"):
        half_angle([1.0, np.nan], 0.0, 0.0)
    with pytest.raises(ModelError, match=r"^E, F, G: expected arrays of shapes that broadcast "
                                         r"together, got E \(2,\), F \(3,\), G \(\)"):
        half_angle(np.ones(2), np.ones(3), 0.0)


@pytest.mark.parametrize("E, F, G, message", [
    (np.array([1.0, None], object), 0.0, 0.0, r"^E: expected real numbers, got \[1.0, None\]$"),
    (10**400, 0.0, 1.0, r"^E: expected real numbers, got a whole number of 401 digits$"),
    (1.0, "a", 0.0, r"^F: expected real numbers, got 'a'$"),
    (1.0, 0.0, True, r"^G: expected real numbers, got true$"),
    (1.0, 0.0, np.inf, r"^G: expected finite numbers, got inf"),
])
def test_coefficients_that_are_not_finite_real_numbers_are_named(E, F, G, message):
    with pytest.raises(ModelError, match=message):
        half_angle(E, F, G)


@pytest.mark.parametrize("options, message", [
    ({"tol": None}, r"^tol: expected a number from 0 to below 0.001, got None$"),
    ({"tol": "a"}, r"^tol: expected a number from 0 to below 0.001, got 'a'$"),
    ({"tol": np.array([])}, r"^tol: expected a number from 0 to below 0.001, got \[\]$"),
    ({"tol": 1e308}, r"^tol: expected a number from 0 to below 0.001, got 1e\+308$"),
    ({"tol": np.nan}, r"^tol: expected a number from 0 to below 0.001, got nan$"),
    ({"tol": -1}, r"^tol: expected a number from 0 to below 0.001, got -1$"),
    ({"strict": np.array([True, False])}, r"^strict: expected True or False, got \[true, false\]$"),
])
def test_bad_options_are_named(options, message):
    with pytest.raises(ModelError, match=message):
        half_angle(2.0, 0.0, 1.0, **options)
