"""Transforms and rotations against the matrices of *Mecanismos*, §4.2 and §7.2, typed out
here independently, and against finite differences for the time derivatives."""
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import kinelab.spatial as sp
from kinelab.errors import ModelError

angle = st.floats(-np.pi, np.pi, allow_nan=False)
angles3 = st.tuples(angle, angle, angle)
# Middle Euler angle kept off gimbal lock, where the outer two are not unique.
tame = st.tuples(angle, st.floats(-1.4, 1.4), angle)
unit_quat = st.tuples(*[st.floats(-1, 1)] * 4).filter(lambda q: np.linalg.norm(q) > 0.1)

EXACT = 1e-14   # products of a few unit-size matrices: a few ulp


def rot_x(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(b):
    c, s = np.cos(b), np.sin(b)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_z(g):
    c, s = np.cos(g), np.sin(g)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def euler_parameter_matrix(q0, q1, q2, q3):
    """*Mecanismos*, §7.2, Rot(u, θ) from Euler parameters (Δ⁻¹ times the printed matrix)."""
    delta = q0**2 + q1**2 + q2**2 + q3**2
    return np.array([
        [q0**2 + q1**2 - q2**2 - q3**2, 2 * (-q0 * q3 + q1 * q2), 2 * (q0 * q2 + q1 * q3)],
        [2 * (q0 * q3 + q1 * q2), q0**2 - q1**2 + q2**2 - q3**2, 2 * (-q0 * q1 + q2 * q3)],
        [2 * (-q0 * q2 + q1 * q3), 2 * (q0 * q1 + q2 * q3), q0**2 - q1**2 - q2**2 + q3**2],
    ]) / delta


@given(angle)
def test_elementary_rotations_match_notes_matrices(a):
    for axis, matrix in (("x", rot_x), ("y", rot_y), ("z", rot_z)):
        np.testing.assert_allclose(sp.rotation(axis, a).as_matrix(), matrix(a),
                                   rtol=0, atol=EXACT)


def test_rotation_is_vectorised_over_angles():
    a = np.linspace(-3, 3, 7)
    R = sp.rotation("y", a).as_matrix()
    assert R.shape == (7, 3, 3)
    np.testing.assert_allclose(R, np.array([rot_y(x) for x in a]), rtol=0, atol=EXACT)


@given(angles3)
def test_fixed_axes_reading_of_notes_7_2a(gba):
    gamma, beta, alpha = gba                 # z first, then y, then x, about fixed axes
    R = sp.euler_rotation("zyx", [gamma, beta, alpha], axes="fixed").as_matrix()
    np.testing.assert_allclose(R, rot_x(alpha) @ rot_y(beta) @ rot_z(gamma), rtol=0,
                               atol=EXACT)


@given(angles3)
def test_moving_axes_reading_of_notes_7_2b(gab):
    gamma, alpha, beta = gab                 # z, then x', then z''
    R = sp.euler_rotation("zxz", [gamma, alpha, beta], axes="moving").as_matrix()
    np.testing.assert_allclose(R, rot_z(gamma) @ rot_x(alpha) @ rot_z(beta), rtol=0,
                               atol=EXACT)


@given(angles3, st.sampled_from(["zyx", "xyz", "zxz", "yzy"]))
def test_fixed_sequence_is_reversed_moving_sequence(a, seq):
    fixed = sp.euler_rotation(seq, a, axes="fixed").as_matrix()
    moving = sp.euler_rotation(seq[::-1], a[::-1], axes="moving").as_matrix()
    np.testing.assert_allclose(fixed, moving, rtol=0, atol=EXACT)


@given(tame, st.sampled_from(["zyx", "xyz", "zyz", "xzx"]), st.sampled_from(["fixed", "moving"]))
def test_euler_angles_round_trip(a, seq, axes):
    if seq[0] == seq[2]:                     # proper Euler: middle angle in (0, π)
        a = (a[0], abs(a[1]) + 0.1, a[2])
    R = sp.euler_rotation(seq, a, axes=axes)
    back = sp.euler_angles(R, seq, axes=axes)
    np.testing.assert_allclose(back, a, rtol=0, atol=1e-9)   # atan2 of rounded entries


def test_degrees_at_the_edge():
    R = sp.euler_rotation("zxz", [30, 40, 50], axes="moving", degrees=True)
    np.testing.assert_allclose(sp.euler_angles(R, "zxz", axes="moving", degrees=True),
                               [30, 40, 50], rtol=0, atol=1e-9)


@given(unit_quat)
def test_euler_parameters_match_notes_matrix(q):
    R = sp.rotation_from_euler_parameters(q).as_matrix()
    np.testing.assert_allclose(R, euler_parameter_matrix(*q), rtol=0, atol=1e-13)


@given(st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda u: np.linalg.norm(u) > 0.1),
       st.floats(0.0, np.pi))
def test_axis_angle_euler_parameters_and_back(u, theta):
    u = np.array(u) / np.linalg.norm(u)
    R = sp.rotation(u, theta)
    # q0 = cos(θ/2), (q1, q2, q3) = sin(θ/2) u: the notes' definition.
    q = sp.euler_parameters(R)
    np.testing.assert_allclose(q, np.r_[np.cos(theta / 2), np.sin(theta / 2) * u], rtol=0,
                               atol=1e-15)
    np.testing.assert_allclose(sp.rotation_from_euler_parameters(q).as_matrix(),
                               R.as_matrix(), rtol=0, atol=EXACT)
    aa = sp.axis_angle(R)
    np.testing.assert_allclose(aa.angle, theta, rtol=0, atol=1e-12)
    if 1e-6 < theta < np.pi - 1e-6:          # the axis is defined (and unique up to sign at π)
        np.testing.assert_allclose(aa.axis, u, rtol=0, atol=1e-9)
    np.testing.assert_allclose(sp.rotation(aa.axis, aa.angle).as_matrix(), R.as_matrix(),
                               rtol=0, atol=1e-14)


def test_axis_angle_of_identity_has_a_unit_axis():
    aa = sp.axis_angle(Rotation.identity())
    assert aa.angle == 0.0 and np.linalg.norm(aa.axis) == 1.0


@given(angles3, st.tuples(*[st.floats(-5, 5)] * 3))
def test_invert_by_transpose_is_the_inverse(a, p):
    T = sp.homogeneous(sp.euler_rotation("zyx", a), p)
    Ti = sp.invert(T)
    np.testing.assert_allclose(Ti @ T, np.eye(4), rtol=0, atol=1e-14 * 10)
    np.testing.assert_allclose(Ti, np.linalg.inv(T), rtol=0, atol=1e-13)


@given(angle, st.tuples(st.floats(-5, 5), st.floats(-5, 5)))
def test_planar_transform_and_inverse(theta, p):
    T = sp.planar_transform(theta, p)
    c, s = np.cos(theta), np.sin(theta)
    np.testing.assert_allclose(T, [[c, -s, p[0]], [s, c, p[1]], [0, 0, 1]], rtol=0, atol=0)
    # *Mecanismos*, eq. 20: B_T_A = [[Rᵀ, -Rᵀ p], [0, 1]]
    Rt = np.array([[c, s], [-s, c]])
    np.testing.assert_allclose(sp.invert(T)[:2, 2], -Rt @ p, rtol=0, atol=1e-14)


def test_rr_robot_by_chained_planar_transforms():
    # *Mecanismos*, Ex. 4.1 (eq. 21): l1 = l2 = 1, θ1 = 30°, θ2 = 60° -> P = (√3/2, 1.5).
    T = sp.compose(sp.planar_transform(np.radians(30)),
                   sp.planar_transform(np.radians(60), [1.0, 0.0]))
    np.testing.assert_allclose(sp.transform_points(T, [1.0, 0.0]), [np.sqrt(3) / 2, 1.5],
                               rtol=0, atol=1e-15)


def test_batched_transforms_compose_and_apply():
    theta = np.linspace(0, np.pi, 5)
    T = sp.compose(sp.translation([1.0, 2.0, 3.0]), sp.homogeneous(sp.rotation("z", theta),
                                                                  [0.0, 0.0, 0.0]))
    assert T.shape == (5, 4, 4)
    P = sp.transform_points(T, [1.0, 0.0, 0.0])
    np.testing.assert_allclose(P, np.c_[1 + np.cos(theta), 2 + np.sin(theta), 3 + 0 * theta],
                               rtol=0, atol=1e-15)


# -- time derivatives against finite differences ------------------------------------------

H = 1e-4   # central differences: truncation ~ h² = 1e-8, roundoff ~ 1e-16 / h² = 1e-8


def moving_frame(t, seq="zxz", axes="moving"):
    """A frame with smoothly varying Euler angles and origin (a test trajectory)."""
    a = np.array([0.3 + 1.1 * t + 0.4 * t**2, 0.7 - 0.5 * t + 0.9 * t**2, -0.2 + 2.0 * t])
    ad = np.array([1.1 + 0.8 * t, -0.5 + 1.8 * t, 2.0])
    add = np.array([0.8, 1.8, 0.0])
    p = np.array([1 + t**2, np.sin(t), 0.5 * t**3])
    pd = np.array([2 * t, np.cos(t), 1.5 * t**2])
    pdd = np.array([2.0, -np.sin(t), 3 * t])
    R = sp.euler_rotation(seq, a, axes=axes)
    return sp.homogeneous(R, p), a, ad, add, pd, pdd


@pytest.mark.parametrize("seq, axes", [("zxz", "moving"), ("zyx", "fixed"), ("xy", "moving")])
def test_euler_rates_and_transform_rates_against_finite_differences(seq, axes):
    if len(seq) == 2:
        def frame(t):
            T, a, ad, add, pd, pdd = moving_frame(t, "zxz", "moving")
            return sp.homogeneous(sp.euler_rotation(seq, a[:2], axes=axes), T[:3, 3]), \
                a[:2], ad[:2], add[:2], pd, pdd
    else:
        def frame(t):
            return moving_frame(t, seq, axes)
    t = 0.37
    T, a, ad, add, pd, pdd = frame(t)
    w = sp.euler_rates(seq, a, ad, add, axes=axes)
    rates = sp.transform_rates(T, w.omega, pd, w.alpha, pdd)
    Tp, Tm = frame(t + H)[0], frame(t - H)[0]
    np.testing.assert_allclose(rates.Td, (Tp - Tm) / (2 * H), rtol=0, atol=1e-7)
    np.testing.assert_allclose(rates.Tdd, (Tp - 2 * T + Tm) / H**2, rtol=0, atol=1e-6)


def test_point_in_moving_frame_against_finite_differences():
    def point(t):
        return np.array([0.5 + t, -0.2 * t**2, np.cos(t)]), np.array([1.0, -0.4 * t, -np.sin(t)]), \
            np.array([0.0, -0.4, -np.cos(t)])

    def world(t):
        T = moving_frame(t)[0]
        return sp.transform_points(T, point(t)[0])

    t = 0.8
    T, a, ad, add, pd, pdd = moving_frame(t)
    w = sp.euler_rates("zxz", a, ad, add, axes="moving")
    rates = sp.transform_rates(T, w.omega, pd, w.alpha, pdd)
    r, rd, rdd = point(t)
    m = sp.point_motion(T, rates.Td, rates.Tdd, r, rd, rdd)
    np.testing.assert_allclose(m.position, world(t), rtol=0, atol=1e-15)
    np.testing.assert_allclose(m.velocity, (world(t + H) - world(t - H)) / (2 * H), rtol=0,
                               atol=1e-7)
    np.testing.assert_allclose(m.acceleration,
                               (world(t + H) - 2 * world(t) + world(t - H)) / H**2, rtol=0,
                               atol=1e-6)
    # Coriolis is 2 ω × (R ṙ), the textbook form, computed independently here.
    np.testing.assert_allclose(m.coriolis_acceleration,
                               2 * np.cross(w.omega, T[:3, :3] @ rd), rtol=0, atol=1e-14)
    np.testing.assert_allclose(m.velocity, m.drag_velocity + m.relative_velocity, rtol=0,
                               atol=0)


def test_planar_point_motion_matches_notes_rp_robot():
    # *Mecanismos*, §5.5: a point sliding along a turning arm, r = q2 i1:
    # a = (q̈2 - q2 q̇1²) i1 + (2 q̇1 q̇2 + q2 q̈1) j1.
    q1, q1d, q1dd, q2, q2d, q2dd = 0.6, 1.5, -0.7, 0.8, 0.3, 0.2
    T = sp.planar_transform(q1)
    rates = sp.transform_rates(T, q1d, [0.0, 0.0], q1dd, [0.0, 0.0])
    m = sp.point_motion(T, rates.Td, rates.Tdd, [q2, 0.0], [q2d, 0.0], [q2dd, 0.0])
    i1, j1 = T[:2, 0], T[:2, 1]
    expected = (q2dd - q2 * q1d**2) * i1 + (2 * q1d * q2d + q2 * q1dd) * j1
    np.testing.assert_allclose(m.acceleration, expected, rtol=0, atol=1e-15)


# -- errors ---------------------------------------------------------------------------------

@pytest.mark.parametrize("call, message", [
    (lambda: sp.rotation("w", 1.0), r"axis: expected one of 'x', 'y', 'z', got 'w'"),
    (lambda: sp.rotation([0, 0, 0], 1.0), r"axis: expected a nonzero direction"),
    (lambda: sp.rotation("x", np.nan), r"angle: expected finite numbers"),
    (lambda: sp.euler_rotation("zqx", [1, 2, 3]), r"sequence: expected 1 to 3 of the letters"),
    (lambda: sp.euler_rotation("zyx", [1, 2]), r"angles: expected shape \(3,\) or \(N, 3\)"),
    (lambda: sp.euler_rotation("zyx", [1, 2, 3], axes="body"),
     r"axes: expected one of 'fixed', 'moving', got 'body'"),
    (lambda: sp.rotation_from_euler_parameters([0, 0, 0, 0]), r"not all zero"),
    (lambda: sp.invert(np.eye(5)), r"expected homogeneous transforms"),
    (lambda: sp.homogeneous(np.eye(3), [1.0, 2.0]), r"translation: expected shape \(\.\.\., 3\)"),
])
def test_bad_arguments_name_the_field(call, message):
    with pytest.raises(ModelError, match=message):
        call()
