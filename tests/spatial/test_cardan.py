"""Cardan joints against the yoke-pin geometry they come from (*Mecanismos*, §7.4, Fig. 59),
typed out here with plain matrices, and against finite differences."""
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab.spatial as sp
from kinelab.errors import ModelError

bend = st.floats(-1.3, 1.3, allow_nan=False)        # |β| up to ~75°
angle = st.floats(-20.0, 20.0, allow_nan=False)      # several turns either way


def rx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


Z = np.array([0.0, 0.0, 1.0])
MINUS_Y = np.array([0.0, -1.0, 0.0])


@given(angle, bend)
def test_yoke_pins_stay_perpendicular(phi1, beta):
    phi2 = sp.cardan_output(phi1, beta)
    v = rx(phi1) @ Z                              # input pin: (0, -sin φ1, cos φ1)
    u = rz(beta) @ rx(phi2) @ MINUS_Y             # output pin: (sβ cφ2, -cβ cφ2, -sφ2)
    assert abs(u @ v) < 1e-14


@given(angle, bend)
def test_output_follows_the_input_quadrant_by_quadrant(phi1, beta):
    phi2 = sp.cardan_output(phi1, beta)
    assert abs(phi2 - phi1) < np.pi / 2          # never half a turn adrift
    # tan φ2 = tan φ1 cos β (eq. 75), written without the tangent's poles; angles up to
    # 20 rad carry ulp(20) ~ 3.6e-15 into their sines and cosines.
    assert np.sin(phi2) * np.cos(phi1) == pytest.approx(np.cos(beta) * np.sin(phi1)
                                                        * np.cos(phi2), abs=1e-14)


def test_continuous_over_full_turns_and_exact_at_quarter_turns():
    beta = np.radians(40.0)
    phi1 = np.linspace(-6 * np.pi, 6 * np.pi, 120_001)
    phi2 = sp.cardan_output(phi1, beta)
    step = phi1[1] - phi1[0]
    # The largest slope is 1/cos β: no step may exceed that (no ±π jumps).
    assert np.diff(phi2).max() <= step / np.cos(beta) * (1 + 1e-9)
    assert np.diff(phi2).min() > 0
    quarters = np.arange(-24, 25) * np.pi / 2
    np.testing.assert_allclose(sp.cardan_output(quarters, beta), quarters, rtol=0, atol=1e-14)


@given(st.floats(-np.pi, np.pi), bend)
def test_velocity_ratio_eq_76_against_finite_differences(phi1, beta):
    h = 1e-6          # central difference; derivatives bounded by ~1/cos³β ~ 60: error ~1e-10
    fd = (sp.cardan_output(phi1 + h, beta) - sp.cardan_output(phi1 - h, beta)) / (2 * h)
    ratio = sp.cardan_velocity_ratio(phi1, beta)
    assert ratio == pytest.approx(fd, abs=1e-8)
    assert ratio == pytest.approx(np.cos(beta) / (1 - np.sin(beta)**2 * np.sin(phi1)**2),
                                  rel=1e-15)


@given(st.floats(-np.pi, np.pi), bend, st.floats(-10, 10), st.floats(-10, 10))
def test_angular_acceleration_against_finite_differences(phi1, beta, w, a):
    h = 1e-6

    def speed(t):
        return sp.cardan_motion(phi1 + w * t + 0.5 * a * t * t, beta, w + a * t).phi2_dot

    m = sp.cardan_motion(phi1, beta, w, a)
    assert m.phi2_ddot == pytest.approx((speed(h) - speed(-h)) / (2 * h), abs=1e-6)
    assert m.phi2_dot == pytest.approx(m.ratio * w, rel=1e-15)


def test_speed_ratio_swings_between_cos_beta_and_its_inverse():
    beta = np.radians(25.0)
    r = sp.cardan_velocity_ratio(np.linspace(0, 2 * np.pi, 3601), beta)
    assert r.min() == pytest.approx(np.cos(beta), rel=1e-15)
    assert r.max() == pytest.approx(1 / np.cos(beta), rel=1e-12)


def test_vectorised_over_input_and_bend():
    phi1 = np.linspace(0, 1, 5)[:, None]
    beta = np.radians([10.0, 20.0, 30.0])
    assert sp.cardan_output(phi1, beta).shape == (5, 3)
    assert sp.cardan_velocity_ratio(phi1, beta).shape == (5, 3)


# -- double Cardan ----------------------------------------------------------------------------

def double_joint_pins(phi1, phi2, phi3, beta1, beta2, phase, plane, arrangement):
    """The four yoke pins of a double Cardan, built from plain rotations."""
    second = -1 if arrangement == "Z" else 1
    v1 = rx(phi1) @ Z
    u_a = rz(beta1) @ rx(phi2) @ MINUS_Y
    u_b = rz(beta1) @ rx(phi2 + phase) @ MINUS_Y
    w = rz(beta1) @ rx(plane) @ rz(second * beta2) @ rx(phi3) @ Z
    shaft3 = rz(beta1) @ rx(plane) @ rz(second * beta2) @ np.array([1.0, 0.0, 0.0])
    return v1, u_a, u_b, w, shaft3


@given(angle, st.floats(0, 1.2), st.floats(0, 1.2), st.floats(-np.pi, np.pi),
       st.floats(-np.pi, np.pi), st.sampled_from(["Z", "W"]))
def test_double_cardan_pins_stay_perpendicular(phi1, beta1, beta2, phase, plane, arrangement):
    m = sp.double_cardan(phi1, beta1, beta2, arrangement=arrangement, phase=phase,
                         plane_angle=plane)
    v1, u_a, u_b, w, shaft3 = double_joint_pins(phi1, m.phi2, m.phi3, beta1, beta2, phase,
                                                plane, arrangement)
    assert abs(u_a @ v1) < 1e-14 and abs(u_b @ w) < 1e-14
    assert abs(w @ shaft3) < 1e-15                  # the output pin turns with its shaft
    np.testing.assert_allclose(m.output_axis, shaft3, rtol=0, atol=1e-15)


@pytest.mark.parametrize("arrangement, plane", [("Z", 0.0), ("W", 0.0), ("Z", 0.7), ("W", -1.1)])
def test_double_cardan_uniform_when_conditions_hold(arrangement, plane):
    phi1 = np.linspace(-4 * np.pi, 4 * np.pi, 801)
    beta = np.radians(35.0)
    m = sp.double_cardan(phi1, beta, beta, arrangement=arrangement, phase=plane,
                         plane_angle=plane, phi1_dot=12.0, phi1_ddot=3.0)
    assert m.uniform
    np.testing.assert_allclose(m.phi3, phi1, rtol=0, atol=1e-13)
    np.testing.assert_allclose(m.ratio, 1.0, rtol=0, atol=1e-14)
    np.testing.assert_allclose(m.phi3_ddot, 3.0, rtol=0, atol=1e-11)
    # ... while the intermediate shaft itself fluctuates.
    assert np.ptp(m.phi2 - phi1) > 0.1


def test_z_is_parallel_and_w_doubles_the_angle():
    beta = np.radians(20.0)
    z = sp.double_cardan(0.0, beta, beta, arrangement="Z")
    w = sp.double_cardan(0.0, beta, beta, arrangement="W")
    np.testing.assert_allclose(z.output_axis, [1, 0, 0], rtol=0, atol=1e-15)
    np.testing.assert_allclose(w.output_axis, [np.cos(2 * beta), np.sin(2 * beta), 0], rtol=0,
                               atol=1e-15)


@pytest.mark.parametrize("beta2, phase, spread", [
    (np.radians(20.0), 0.0, (np.cos(np.radians(30)) / np.cos(np.radians(20)),
                             np.cos(np.radians(20)) / np.cos(np.radians(30)))),
    # Yokes a quarter turn out of phase: the two fluctuations add, cos²β .. 1/cos²β.
    (np.radians(30.0), np.pi / 2, (np.cos(np.radians(30))**2, 1 / np.cos(np.radians(30))**2)),
])
def test_double_cardan_fluctuates_when_conditions_fail(beta2, phase, spread):
    phi1 = np.linspace(0, 2 * np.pi, 7201)
    m = sp.double_cardan(phi1, np.radians(30.0), beta2, phase=phase)
    assert not m.uniform
    assert m.ratio.min() == pytest.approx(spread[0], rel=1e-9)
    assert m.ratio.max() == pytest.approx(spread[1], rel=1e-9)


def test_double_cardan_rates_against_finite_differences():
    kwargs = dict(beta1=0.5, beta2=0.3, arrangement="W", phase=0.4, plane_angle=-0.2)
    h, phi1, w, a = 1e-6, 0.9, 4.0, -1.5
    m = sp.double_cardan(phi1, phi1_dot=w, phi1_ddot=a, **kwargs)

    def out(t):
        return sp.double_cardan(phi1 + w * t + 0.5 * a * t * t, phi1_dot=w + a * t, **kwargs)

    assert m.phi3_dot == pytest.approx((out(h).phi3 - out(-h).phi3) / (2 * h), abs=1e-8)
    assert m.phi3_ddot == pytest.approx((out(h).phi3_dot - out(-h).phi3_dot) / (2 * h),
                                        abs=1e-6)


@pytest.mark.parametrize("call, message", [
    (lambda: sp.cardan_output(0.3, np.pi / 2), r"beta: expected \|β\| < π/2 rad"),
    (lambda: sp.cardan_velocity_ratio(0.3, [0.1, np.nan]), r"beta: expected \|β\| < π/2 rad .*"
                                                           r"got nan rad"),
    (lambda: sp.double_cardan(0.3, 0.2, 2.0), r"beta2: expected \|β\| < π/2"),
    (lambda: sp.double_cardan(0.3, 0.2, 0.2, arrangement="U"),
     r"arrangement: expected one of 'Z', 'W', got 'U'"),
])
def test_bad_arguments(call, message):
    with pytest.raises(ModelError, match=message):
        call()
