"""Arguments of the spatial functions: every bad one is a kinelab error naming it (never a
raw numpy, scipy or Python error, a NaN or a RuntimeWarning, which the test configuration
turns into errors), and large or tiny but legitimate ones give the right answer."""
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import kinelab.spatial as sp
from kinelab.errors import AssemblyError, ConvergenceError, ModelError, SingularityError

EXACT = 1e-15
T4 = np.eye(4)
RX90 = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])    # Rot(x, 90°)


def rodrigues(axis, angle):
    """Rot(u, θ) = I + sin θ [u]x + (1 - cos θ) [u]x², u a unit vector (independent of scipy)."""
    u = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


# -- transforms and rotations: large and tiny legitimate values -----------------------------

@pytest.mark.parametrize("q", [[1e200, 1e200, 0, 0], [1e308, 1e308, 0, 0], [1.0, 1.0, 0, 0],
                               [1e-300, 1e-300, 0, 0], [5e-324, 5e-324, 0, 0]])
def test_euler_parameters_of_any_size_give_the_rotation(q):
    R = sp.rotation_from_euler_parameters(q).as_matrix()
    np.testing.assert_allclose(R, RX90, rtol=0, atol=EXACT)


def test_tiny_euler_parameters_are_not_zero():
    R = sp.rotation_from_euler_parameters([1e-200, 0, 0, 0]).as_matrix()
    np.testing.assert_array_equal(R, np.eye(3))


@pytest.mark.parametrize("scale", [1e308, 1e-200, 5e-324, 1.0])
def test_axis_of_any_size_gives_the_rotation(scale):
    R = sp.rotation([scale, scale, 0.0], 1.0).as_matrix()
    np.testing.assert_allclose(R, rodrigues([1, 1, 0], 1.0), rtol=0, atol=1e-15)


def test_angles_up_to_the_limit_are_computed():
    turns = 1000 * 2 * np.pi + 0.5                     # a thousand turns and 0.5 rad
    with pytest.raises(ModelError, match=r"angle: expected angles within 1000 turns"):
        sp.rotation([0, 0, 1], turns)
    R = sp.rotation([0, 0, 2], 999 * 2 * np.pi + 0.5).as_matrix()
    np.testing.assert_allclose(R, rodrigues([0, 0, 1], 0.5), rtol=0, atol=1e-12)
    R = sp.rotation("z", 359_000.0 + 30.0, degrees=True).as_matrix()      # 997 turns + 110°
    np.testing.assert_allclose(R, rodrigues([0, 0, 1], np.radians(110.0)), rtol=0, atol=1e-12)


def test_large_translations_within_the_limits_are_exact():
    T = sp.homogeneous(sp.rotation("z", np.pi / 2), [1e9, -1e9, 0.0])
    np.testing.assert_allclose(sp.transform_points(T, [1e9, 0.0, 0.0]), [1e9, 0.0, 0.0],
                               rtol=1e-15, atol=1e-6)
    np.testing.assert_allclose(sp.invert(T) @ T, np.eye(4), rtol=0, atol=1e-6)


def test_transforms_broadcast_over_leading_dimensions():
    T = sp.homogeneous(sp.rotation("z", [0.0, np.pi / 2]), [1.0, 0.0, 0.0])   # (2, 4, 4)
    np.testing.assert_allclose(sp.transform_points(T, [1.0, 0.0, 0.0]),
                               [[2.0, 0.0, 0.0], [1.0, 1.0, 0.0]], rtol=0, atol=EXACT)
    np.testing.assert_allclose(sp.compose(T, sp.translation([0.0, 0.0, 1.0]))[:, :3, 3],
                               [[1.0, 0.0, 1.0], [1.0, 0.0, 1.0]], rtol=0, atol=EXACT)


def test_rates_broadcast_to_the_angles():
    m = sp.euler_rates("zyx", [0.0, 0.0, 0.0], np.ones((4, 3)))
    np.testing.assert_allclose(m.omega, np.ones((4, 3)), rtol=0, atol=EXACT)


# -- transforms and rotations: bad arguments ------------------------------------------------

FINITE = r"expected finite numbers"
REAL = r"expected real numbers"


@pytest.mark.parametrize("call, message", [
    # not numbers, or numbers beyond float
    (lambda: sp.rotation("z", 10**400), r"angle: " + REAL + r", got a whole number of 401"),
    (lambda: sp.rotation("z", object()), r"angle: " + REAL + r", got an object$"),
    (lambda: sp.euler_rotation("zyx", object()), r"angles: " + REAL + r", got an object$"),
    (lambda: sp.planar_transform("x"), r"angle: " + REAL + r", got 'x'"),
    (lambda: sp.planar_transform(None), r"angle: " + REAL + r", got None"),
    (lambda: sp.planar_transform(10**400), r"angle: " + REAL),
    (lambda: sp.skew(1j), r"vector: " + REAL + r", got 1j"),
    (lambda: sp.skew([10**400, 0, 0]), r"vector: " + REAL),
    (lambda: sp.translation(["a", 0]), r"vector: " + REAL),
    (lambda: sp.homogeneous("abc", [0, 0, 0]), r"rotation: " + REAL + r", got 'abc'"),
    (lambda: sp.homogeneous(np.eye(3), [[], 0, 0]), r"translation: " + REAL),
    (lambda: sp.compose("a"), r"transforms\[0\]: " + REAL),
    (lambda: sp.invert("abc"), r"transform: " + REAL),
    (lambda: sp.transform_points(T4, "x"), r"points: " + REAL),
    (lambda: sp.transform_rates(T4, "a", [0, 0, 0]), r"omega: " + REAL),
    (lambda: sp.transform_rates(T4, [0, 0, 0], "abc"), r"velocity: " + REAL),
    (lambda: sp.point_motion(T4, "x", 0 * T4, [1, 0, 0]), r"Td: " + REAL),
    (lambda: sp.euler_rates("zyx", [0, 0, 0], [1, 1, 1], "a"), r"accelerations: " + REAL),
    (lambda: sp.rotation("z", True), r"angle: " + REAL + r", got true"),
    # NaN and infinity
    (lambda: sp.planar_transform(np.nan), r"angle: " + FINITE + r", got nan"),
    (lambda: sp.planar_transform(np.inf), r"angle: " + FINITE + r", got inf"),
    (lambda: sp.translation([np.nan, 0]), r"vector: " + FINITE + r", got nan at index \(0,\)"),
    (lambda: sp.homogeneous(np.eye(3), [0, np.nan, 0]), r"translation: " + FINITE),
    (lambda: sp.homogeneous(np.full((3, 3), np.nan), [0, 0, 0]), r"rotation: " + FINITE),
    (lambda: sp.compose(T4, np.full((4, 4), np.nan)), r"transforms\[1\]: " + FINITE),
    (lambda: sp.invert(np.full((4, 4), np.nan)), r"transform: " + FINITE),
    (lambda: sp.transform_points(T4, [np.nan, 0, 0]), r"points: " + FINITE),
    (lambda: sp.transform_rates(T4, [np.nan, 0, 0], [0, 0, 0]), r"omega: " + FINITE),
    (lambda: sp.transform_rates(T4, [0, 0, 0], [np.inf, 0, 0]), r"velocity: " + FINITE),
    (lambda: sp.point_motion(T4, 0 * T4, 0 * T4, [np.nan, 0, 0]), r"point: " + FINITE),
    (lambda: sp.euler_rates("zyx", [0, 0, 0], [1, 1, 1], [np.nan, 0, 0]),
     r"accelerations: " + FINITE),
    # beyond the limits
    (lambda: sp.rotation([0, 0, 1], 1e300), r"angle: expected angles within 1000 turns"),
    (lambda: sp.rotation("z", 1e300), r"angle: expected angles within 1000 turns"),
    (lambda: sp.rotation("z", 1e7, degrees=True), r"angle: expected angles within 1000 turns "
                                                   r"of 0 either way, got 10000000.0 deg"),
    (lambda: sp.translation([1e300, 0.0]), r"vector: expected at most 1e\+09 m in size"),
    (lambda: sp.transform_rates(T4, [0, 0, 0], [1e300, 0, 0]),
     r"velocity: expected at most 1e\+100 m/s in size"),
    # shapes that do not fit or do not go together
    (lambda: sp.compose([1, 2, 3], [1, 2, 3]), r"transforms\[0\]: expected homogeneous "
                                               r"transforms of shape \(\.\.\., 3, 3\)"),
    (lambda: sp.compose(5), r"transforms\[0\]: expected homogeneous transforms"),
    (lambda: sp.compose(np.eye(2)), r"transforms\[0\]: expected homogeneous transforms"),
    (lambda: sp.compose(np.eye(4), np.eye(3)), r"transforms\[1\]: expected shape "
                                               r"\(\.\.\., 4, 4\) like the other transforms"),
    (lambda: sp.homogeneous(np.stack([np.eye(3)] * 2), np.zeros((3, 3))),
     r"rotation, translation: shapes \(2, 3, 3\), \(3, 3\) do not go together"),
    (lambda: sp.transform_points(np.stack([T4] * 2), np.zeros((3, 3))),
     r"transform, points: shapes \(2, 4, 4\), \(3, 3\) do not go together"),
    (lambda: sp.transform_rates(np.stack([T4] * 2), np.zeros((3, 3)), [0, 0, 0]),
     r"transform, omega, .* do not go together"),
    (lambda: sp.point_motion(T4, 0 * T4, 0 * T4, np.zeros((2, 3)), np.zeros((5, 3))),
     r"point, point_velocity.* do not go together"),
    (lambda: sp.point_motion(T4, np.eye(3), 0 * T4, [1, 0, 0]),
     r"Td: expected shape \(\.\.\., 4, 4\) like the transform"),
    (lambda: sp.euler_rates("zyx", [0, 0, 0], [1, 1, 1], [1, 0]),
     r"accelerations: expected shape \(3,\) or \(N, 3\), got \(2,\)"),
    (lambda: sp.euler_rates("zyx", np.zeros((2, 3)), np.ones((4, 3))),
     r"angles, rates, accelerations: shapes \(2, 3\), \(4, 3\), \(3,\) do not go together"),
    # not rigid transforms
    (lambda: sp.invert(np.diag([2.0, 2.0, 2.0, 1.0])),
     r"transform: rotation part: expected orthonormal columns .* Rotation.from_matrix"),
    (lambda: sp.homogeneous(np.ones((3, 3)), [0, 0, 0]), r"rotation: expected orthonormal"),
    (lambda: sp.homogeneous(np.diag([1.0, 1.0, -1.0]), [0, 0, 0]),
     r"rotation: expected a rotation, got a reflection"),
    (lambda: sp.compose(T4, np.array([[1, 0, 0], [0, 1, 0], [1, 0, 1.0]])),
     r"transforms\[1\]: expected shape \(\.\.\., 4, 4\)"),
    (lambda: sp.transform_points(np.array([[1, 0, 0], [0, 1, 0], [1, 0, 1.0]]), [0, 0]),
     r"transform: expected a homogeneous transform, with last row \(0, 0, 1\)"),
    (lambda: sp.point_motion(T4, T4, 0 * T4, [1, 0, 0]),
     r"Td: expected the time derivative of a transform, whose last row is zero"),
    # not rotations
    (lambda: sp.axis_angle(np.eye(3)), r"rotation: expected a scipy.spatial.transform."
                                       r"Rotation, got ndarray"),
    (lambda: sp.euler_angles(None, "zyx"), r"rotation: expected a scipy.*got NoneType"),
    (lambda: sp.euler_parameters("R"), r"rotation: expected a scipy.*got str"),
    # sequences, flags
    (lambda: sp.euler_rotation("zzz", [1, 2, 3]), r"sequence: expected consecutive axes to "
                                                  r"differ.*got 'zzz'"),
    (lambda: sp.euler_angles(Rotation.identity(), "zzx"), r"sequence: expected consecutive"),
    (lambda: sp.euler_rates("zzz", [0, 0, 0], [1, 1, 1]), r"sequence: expected consecutive"),
    (lambda: sp.rotation("z", 1.0, degrees="yes"), r"degrees: expected True or False, got "
                                                   r"'yes'"),
    (lambda: sp.euler_angles(Rotation.identity(), "zyx", degrees=1),
     r"degrees: expected True or False, got 1"),
])
def test_transforms_refuse_bad_arguments(call, message):
    with pytest.raises(ModelError, match=message):
        call()


def test_tiny_directions_are_not_called_zero():
    # the message says (0, 0, 0) only when the direction is zero
    with pytest.raises(ModelError, match=r"axis: expected a nonzero direction, got \(0, 0, 0\)"):
        sp.rotation([0.0, -0.0, 0.0], 1.0)
    with pytest.raises(ModelError, match=r"q: expected Euler parameters not all zero"):
        sp.rotation_from_euler_parameters([0.0, 0.0, 0.0, 0.0])
