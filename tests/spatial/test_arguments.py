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


# -- Cardan joints, RSSR, Stewart platform --------------------------------------------------

RSSR_ARGS = dict(H1=1.0, L1=0.0, L0=1.0, L2=1.0, H3=1.0, L3=0.0)


def ring(radius, degrees):
    t = np.radians(degrees)
    return radius * np.c_[np.cos(t), np.sin(t), np.zeros(6)]


BASE = ring(1.0, [-15, 15, 105, 135, 225, 255])
TOP = ring(0.5, [-45, 45, 75, 165, 195, 285])
I = Rotation.identity()


@pytest.mark.parametrize("call, message", [
    (lambda: sp.cardan_output(np.nan, 0.3), r"phi1: " + FINITE),
    (lambda: sp.cardan_output(None, 0.3), r"phi1: " + REAL + r", got None"),
    (lambda: sp.cardan_output(np.zeros(3), np.zeros(2)),
     r"phi1, beta: shapes \(3,\), \(2,\) do not go together"),
    (lambda: sp.cardan_velocity_ratio(np.inf, 0.3), r"phi1: " + FINITE + r", got inf"),
    (lambda: sp.cardan_velocity_ratio("a", 0.3), r"phi1: " + REAL),
    (lambda: sp.cardan_output(0.3, "a"), r"beta: " + REAL),
    (lambda: sp.cardan_motion(0.3, 0.3, np.nan), r"phi1_dot: " + FINITE),
    (lambda: sp.cardan_motion(0.3, 0.3, 1e308), r"phi1_dot: expected at most 1e\+100 rad/s"),
    (lambda: sp.cardan_motion(0.3, 0.3, 0.0, 10**400), r"phi1_ddot: " + REAL),
    (lambda: sp.cardan_motion(np.zeros(3), np.zeros(2)), r"phi1, beta, .* do not go together"),
    (lambda: sp.double_cardan(1e308, 0.3, 0.3), r"phi1: expected angles within 1000 turns"),
    (lambda: sp.double_cardan(0.3, 0.3, 0.3, phase=np.nan), r"phase: " + FINITE),
    (lambda: sp.double_cardan(0.3, 0.3, 0.3, phase=None), r"phase: " + REAL + r", got None"),
    (lambda: sp.double_cardan(0.3, 0.3, 0.3, plane_angle="a"), r"plane_angle: " + REAL),
    (lambda: sp.double_cardan(0.3, 0.3, 0.3, phi1_dot=np.nan), r"phi1_dot: " + FINITE),
    (lambda: sp.double_cardan(0.3, [0.3, 0.2], 0.3), r"beta1: expected shape \(\), got \(2,\)"),
    (lambda: sp.double_cardan(np.zeros(3), 0.3, 0.3, phi1_dot=[1, 2]),
     r"phi1, phi1_dot, phi1_ddot: shapes \(3,\), \(2,\), \(\) do not go together"),
    (lambda: sp.RSSR(**RSSR_ARGS).analyze(0.1, np.nan), r"theta1_dot: " + FINITE),
    (lambda: sp.RSSR(**RSSR_ARGS).analyze(0.1, "a"), r"theta1_dot: " + REAL),
    (lambda: sp.RSSR(**RSSR_ARGS).analyze(0.1, 0.0, 1e300), r"theta1_ddot: expected at most"),
    (lambda: sp.RSSR(**RSSR_ARGS).analyze([0.1, 0.2], [1, 2, 3]),
     r"theta1, theta1_dot, theta1_ddot: shapes \(2,\), \(3,\), \(\) do not go together"),
    (lambda: sp.RSSR(**RSSR_ARGS).positions(1e300), r"theta1: expected angles within 1000"),
    (lambda: sp.RSSR(**RSSR_ARGS).analyze(0.1, branch=True), r"branch: expected one of 1, -1, "
                                                             r"got true"),
    (lambda: sp.RSSR(**dict(RSSR_ARGS, H1=10**400)), r"H1: expected a finite length in m, got "
                                                     r"a whole number of 401 digits"),
    (lambda: sp.RSSR(**dict(RSSR_ARGS, L0=1e300)), r"L0: expected at most 1e\+09 m in size"),
    (lambda: sp.RSSR(**dict(RSSR_ARGS, L2=1e-300)), r"L2: expected a length from 1e-09 m"),
    (lambda: sp.RSSR(**dict(RSSR_ARGS, L3="1")), r"L3: expected a finite length in m, got '1'"),
    (lambda: sp.stewart_leg_lengths(BASE, TOP, [1e300, 0, 1], I),
     r"position: expected at most 1e\+09 m in size, got 1e\+300 at index \(0,\)"),
    (lambda: sp.stewart_leg_lengths(BASE, TOP, [10**400, 0, 1], I), r"position: " + REAL),
    (lambda: sp.stewart_leg_lengths(BASE * 1e300, TOP, [0, 0, 1], I),
     r"base_points: expected at most 1e\+09 m"),
    (lambda: sp.stewart_leg_lengths(BASE, TOP, [0, 0, np.nan], I), r"position: " + FINITE),
    (lambda: sp.stewart_forward(BASE, TOP, [1e300] * 6, [0, 0, 1], I),
     r"leg_lengths: expected a length from 1e-09 m to 1e\+09 m, got 1e\+300"),
    (lambda: sp.stewart_forward(BASE, TOP, [-1.2] * 6, [0, 0, 1], I),
     r"leg_lengths: expected a length from .* got -1.2 at index \(0,\)"),
    (lambda: sp.stewart_forward(BASE, TOP, [1.2] * 5 + [0.0], [0, 0, 1], I),
     r"leg_lengths: .* got 0.0 at index \(5,\)"),
    (lambda: sp.stewart_forward(BASE, TOP, [[1.2] * 6] * 3, np.zeros((2, 3)) + [0, 0, 1], I),
     r"leg_lengths and position: 3 sets of leg lengths and 2 poses"),
    (lambda: sp.stewart_forward(BASE, TOP, [1.2] * 6, [0, 0, 1], I, max_iter=-1),
     r"max_iter: expected a whole number from 1 to 10,000, got -1"),
    (lambda: sp.stewart_forward(BASE, TOP, [1.2] * 6, [0, 0, 1], I, max_iter="a"),
     r"max_iter: expected a whole number .* got 'a'"),
    (lambda: sp.stewart_forward(BASE, TOP, [1.2] * 6, [0, 0, 1], I, max_iter=1.5),
     r"max_iter: expected a whole number .* got 1.5"),
    (lambda: sp.stewart_forward(BASE, TOP, [1.2] * 6, [0, 0, 1], I, max_iter=True),
     r"max_iter: expected a whole number .* got true"),
])
def test_mechanisms_refuse_bad_arguments(call, message):
    with pytest.raises(ModelError, match=message):
        call()


def test_double_cardan_at_large_legitimate_angles():
    # 999 turns and 45°: the output of a Z arrangement with equal bends follows the input
    phi1 = 999 * 2 * np.pi + np.pi / 4
    m = sp.double_cardan(phi1, 0.3, 0.3, phi1_dot=1e100)
    assert float(m.phi3) == pytest.approx(phi1, rel=0, abs=1e-9)
    assert float(m.phi3_dot) == pytest.approx(1e100, rel=1e-12)


def test_stewart_forward_with_no_samples_returns_no_poses():
    pose = sp.stewart_forward(BASE, TOP, np.zeros((0, 6)), [0, 0, 1], I)
    assert pose.position.shape == (0, 3) and pose.residual.shape == (0,)


# -- serial robots --------------------------------------------------------------------------

R_Z = sp.RobotJoint("R", (0, 0, 1))


def rr_by_hand(l1=1.0, l2=1.0):
    """The RR robot joint by joint: no closed form, so inverse() uses Newton."""
    return sp.SerialRobot("RR by hand", (R_Z, sp.RobotJoint("R", (0, 0, 1), (l1, 0, 0))),
                          tool=(l2, 0.0, 0.0), planar=True)


def chain(n):
    """A planar chain of n revolute joints, links of 0.1 m."""
    joints = [sp.RobotJoint("R", (0, 0, 1), (0.1 if i else 0.0, 0, 0)) for i in range(n)]
    return sp.SerialRobot("chain", joints, (0.1, 0.0, 0.0), planar=True)


@pytest.mark.parametrize("scale", [1e308, 1e-200, 5e-324])
def test_joint_axis_of_any_size_is_normalised(scale):
    joint = sp.RobotJoint("R", (scale, scale, 0.0))
    np.testing.assert_allclose(joint.axis, [np.sqrt(0.5), np.sqrt(0.5), 0.0], rtol=0,
                               atol=EXACT)


@pytest.mark.parametrize("call, message", [
    (lambda: sp.SerialRobot("x", None, (0, 0, 0)), r"robot 'x': joints: expected one or more "
                                                  r"RobotJoint, got None"),
    (lambda: sp.SerialRobot("x", 5, (0, 0, 0)), r"joints: expected one or more RobotJoint, "
                                               r"got 5"),
    (lambda: sp.SerialRobot(object(), [R_Z], (1, 0, 0)), r"name: expected a non-empty name, "
                                                         r"got an object$"),
    (lambda: sp.SerialRobot("x", [R_Z], (1, 0, 0), planar="yes"),
     r"planar: expected True or False, got 'yes'"),
    (lambda: sp.SerialRobot("x", [R_Z], (1e300, 0, 0)), r"tool: expected at most 1e\+09 m"),
    (lambda: sp.RobotJoint("R", (0, 0, 0)), r"axis: expected a nonzero direction"),
    (lambda: sp.RobotJoint("R", (0, 0, 1), ("a", 0, 0)), r"offset: " + REAL),
    (lambda: sp.RobotJoint("R", (np.nan, 0, 1)), r"axis: " + FINITE),
    (lambda: sp.rr(10**400, 1), r"l1: expected a positive length in m, got a whole number"),
    (lambda: sp.rr(1e-300, 1e-300), r"l1: expected a length from 1e-09 m to 1e\+09 m, got "
                                     r"1e-300 m"),
    (lambda: sp.pr(1e10), r"L: expected a length from 1e-09 m to 1e\+09 m"),
    (lambda: sp.prr(1, 1, D=np.inf), r"D: expected a finite length in m, got inf"),
    (lambda: sp.rr(1, 1).forward([10**400, 0]), r"q: " + REAL),
    (lambda: sp.rr(1, 1).forward([1e300, 0]), r"q: expected angles within 1000 turns"),
    (lambda: sp.prr(1, 1).forward([1e300, 0, 0]), r"q: expected at most 1e\+09 m in size, got "
                                                  r"1e\+300 at index \(0,\)"),
    (lambda: sp.rr(1, 1).inverse([1e155, 1e155]), r"point: expected at most 1e\+09 m"),
    (lambda: sp.rr(1, 1).motion([0, 0], [np.nan, 0]), r"qd: " + FINITE),
    (lambda: sp.rr(1, 1).motion([0, 0], 0.0, 1e300), r"qdd: expected at most 1e\+100"),
    (lambda: sp.rr(1, 1).motion([0, 0], "a"), r"qd: " + REAL),
    (lambda: sp.rr(1, 1).inverse_rates([0, 1], [np.nan, 0]), r"velocity: " + FINITE),
    (lambda: sp.rr(1, 1).inverse_rates([0, 1], [1e300, 1e300]),
     r"velocity: expected at most 1e\+100 m/s"),
    (lambda: sp.rr(1, 1).inverse_rates([0, 1], "ab"), r"velocity: " + REAL),
    (lambda: sp.rr(1, 1).inverse_rates([0, 1], np.ones((3, 2))),
     r"velocity: expected shape \(2,\) or \(1, 2\) like q, got \(3, 2\)"),
    (lambda: sp.rr(1, 1).inverse_rates([0, 1], [0, 0], np.ones((1, 3))),
     r"acceleration: expected shape \(\.\.\., 2\), got \(1, 3\)"),
    (lambda: sp.rr(1, 1).inverse(np.ones((3, 2)), guess=np.zeros((2, 2))),
     r"guess: 2 guesses for 3 points"),
    (lambda: sp.rr(1, 1).inverse([1, 1], guess=[np.nan, 0]), r"guess: " + FINITE),
])
def test_robots_refuse_bad_arguments(call, message):
    with pytest.raises(ModelError, match=message):
        call()


def test_a_guess_follows_each_point():
    robot = sp.rr(1.0, 1.0)
    points = np.array([[1.0, 1.0], [0.0, 1.5], [1.2, -0.3]])
    q = robot.inverse(points, guess=[0.1, 1.2])
    assert q.shape == (3, 2)
    np.testing.assert_allclose(robot.forward(q), points, rtol=0, atol=1e-12)
    q = robot.inverse([1.0, 1.0], guess=[[0.1, 1.2], [1.5, -1.5]])    # one point, two guesses
    np.testing.assert_allclose(np.degrees(q), [[0.0, 90.0], [90.0, -90.0]], rtol=0, atol=1e-9)


def test_newton_finds_the_closed_form_solutions():
    point = [np.sqrt(3) / 2, 1.5]                       # Ex. 4.1: θ = (30°, 60°) or (90°, -60°)
    found = rr_by_hand().inverse(point)
    assert len(found) == 2
    expected = np.radians([[90.0, -60.0], [30.0, 60.0]])
    np.testing.assert_allclose(found[np.argsort(found[:, 1])], expected, rtol=0, atol=1e-10)


@pytest.mark.parametrize("n", [3, 7, 12])
def test_redundant_robot_without_a_guess_is_refused(n):
    with pytest.raises(ModelError, match=rf"robot 'chain': inverse: {n} joints for 2 tool "
                                         r"coordinates, so the solutions form a continuum.*"
                                         r"pass guess="):
        chain(n).inverse([0.3, 0.2])


def test_redundant_robot_with_a_guess_reaches_the_point():
    robot = chain(7)
    q = robot.inverse([0.3, 0.2], guess=np.full(7, 0.3))
    np.testing.assert_allclose(robot.forward(q), [0.3, 0.2], rtol=0, atol=1e-12)


def test_robot_whose_joints_do_not_move_the_tool_is_refused():
    zero = sp.SerialRobot("zero", (R_Z, R_Z), (0, 0, 0), planar=True)
    with pytest.raises(ModelError, match=r"robot 'zero': inverse: no joint moves the tool"):
        zero.inverse([0.0, 0.0])
    slides = sp.SerialRobot("slides", (sp.RobotJoint("P", (1, 0, 0)),
                                       sp.RobotJoint("P", (2, 0, 0))), (0, 0, 0), planar=True)
    with pytest.raises(ModelError, match=r"its 2 joints do not move the tool independently "
                                         r"\(the Jacobian has rank 1 at every start\)"):
        slides.inverse([1.0, 0.0])


def test_point_on_a_joint_axis_has_infinitely_many_solutions():
    with pytest.raises(SingularityError, match=r"robot 'RR by hand': point \[0.0, 0.0\] has "
                                               r"infinitely many solutions: it lies on the "
                                               r"axis of joints\[0\]"):
        rr_by_hand().inverse([0.0, 0.0])


def test_unreachable_point_without_a_closed_form():
    with pytest.raises(AssemblyError, match=r"Newton reached no solution .* from 9 starts"):
        rr_by_hand().inverse([3.0, 0.0])


def test_solutions_a_turn_apart_are_one():
    robot = rr_by_hand()
    q = np.array([[np.pi - 1e-9, 0.5], [-np.pi + 1e-9, 0.5], [np.pi - 1e-9, -0.5]])
    np.testing.assert_array_equal(robot._distinct(q), q[[0, 2]])


def test_many_repeated_solutions_are_sorted_out():
    robot = sp.rrr(1.0, 1.0)                              # three revolute joints
    rng = np.random.default_rng(1)
    roots = np.array([[0.1, 0.2, 0.3], [-2.0, 1.0, 3.1], [3.14159, -1.0, 0.0]])
    q = roots[rng.integers(0, 3, 3000)] + rng.uniform(-1e-9, 1e-9, (3000, 3))
    kept = robot._distinct(q)
    assert len(kept) == 3
    np.testing.assert_allclose(np.sort(kept[:, 0]), np.sort(roots[:, 0]), rtol=0, atol=1e-8)


def test_a_rotation_typed_with_three_digits_is_taken_as_it_is():
    """A book's 30 deg turn about z, typed 0.866 and 0.5: a rotation to its own precision."""
    typed = np.array([[0.866, -0.5, 0.0, 1.0], [0.5, 0.866, 0.0, 2.0], [0.0, 0.0, 1.0, 3.0],
                      [0.0, 0.0, 0.0, 1.0]])
    exact = sp.homogeneous(sp.rotation("z", 30.0, degrees=True), [1.0, 2.0, 3.0])
    np.testing.assert_allclose(sp.invert(typed) @ exact, np.eye(4), rtol=0, atol=1e-3)
    np.testing.assert_allclose(sp.compose(typed, typed), exact @ exact, rtol=0, atol=1e-3)
    with pytest.raises(ModelError, match="rotation part: expected orthonormal"):
        sp.invert(np.diag([1.05, 1.05, 1.0, 1.0]))          # scaled by 5 %: not a rotation
