"""Serial robots: inverse against forward, Jacobians and accelerations against finite
differences, closed forms against Newton, branches against their geometric meaning."""
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import kinelab.spatial as sp
from kinelab.errors import AssemblyError, ConvergenceError, ModelError, SingularityError
from kinelab.solvers import wrap_angle

ROBOTS = {
    "RR": sp.rr(1.0, 0.7),
    "RP": sp.rp(),
    "PR": sp.pr(0.8),
    "RRR": sp.rrr(1.0, 0.6),
    "PRR": sp.prr(1.0, 0.7, D=0.1, H=0.2, V=0.05),
}
angle = st.floats(-np.pi, np.pi, allow_nan=False)
slide = st.floats(-2.0, 2.0, allow_nan=False)


def joints(robot):
    return st.tuples(*[angle if j.kind == "R" else slide for j in robot.joints]).map(np.array)


def same_joints(robot, a, b):
    """Joint coordinates equal, revolute ones modulo 2π."""
    diff = np.array(a, dtype=float) - np.array(b, dtype=float)
    revolute = np.array([j.kind == "R" for j in robot.joints])
    diff[..., revolute] = wrap_angle(diff[..., revolute])
    return np.abs(diff).max(axis=-1)


def far_from_singular(robot, q, ratio=1e-3):
    """Away from poses where solutions merge or an angle is arbitrary (well-conditioned)."""
    sv = np.linalg.svd(robot.jacobian(q), compute_uv=False)
    return sv[..., -1] > ratio * sv[..., 0]


def random_poses(robot, seed, n):
    """n joint vectors with every coordinate in [-2.5, 2.5], and their tool points."""
    q = np.random.default_rng(seed).uniform(-2.5, 2.5, (n, robot.n))
    return q, robot.forward(q)


@pytest.mark.parametrize("name", ROBOTS)
@given(data=st.data())
def test_inverse_of_forward_contains_the_pose(name, data):
    robot = ROBOTS[name]
    q = data.draw(joints(robot))
    assume(far_from_singular(robot, q))
    point = robot.forward(q)
    solutions = robot.inverse(point)
    assert solutions.shape[1:] == (robot.n,) and len(solutions) == len(robot.branches)
    assert not np.isnan(solutions).any()
    # Every solution reaches the point; one of them is the pose we started from.
    # 1e-12 m: a few ulp of a unit-size robot after the half-angle and atan2 steps.
    np.testing.assert_allclose(robot.forward(solutions), np.broadcast_to(point, (
        len(solutions), robot.dim)), rtol=0, atol=1e-12)
    assert same_joints(robot, solutions, q).min() < 1e-9   # conditioning ~1e3 times 1e-12


@pytest.mark.parametrize("name", ROBOTS)
def test_batched_inverse_has_every_branch_in_order(name):
    robot = ROBOTS[name]
    _, points = random_poses(robot, 1, 50)
    all_q = robot.inverse(points)
    assert all_q.shape == (50, len(robot.branches), robot.n)
    for b, branch in enumerate(robot.branches):
        one = robot.inverse(points, branch=branch)
        np.testing.assert_array_equal(one, all_q[:, b])
        np.testing.assert_allclose(robot.forward(one), points, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ROBOTS)
def test_closed_form_against_newton(name):
    robot = ROBOTS[name]
    rng = np.random.default_rng(2)
    _, points = random_poses(robot, 2, 40)
    for branch in robot.branches:
        exact = robot.inverse(points, branch=branch)
        # Near a singular pose two branches are close and Newton may take the other one.
        exact = exact[far_from_singular(robot, exact, ratio=0.05)]
        start = exact + rng.normal(0, 0.05, exact.shape)
        newton = robot.inverse(robot.forward(exact), guess=start)
        assert same_joints(robot, newton, exact).max() < 1e-10


def test_generic_chain_newton_finds_all_four_rrr_solutions():
    rrr = ROBOTS["RRR"]
    generic = sp.SerialRobot("generic RRR", rrr.joints, rrr.tool)   # no closed form
    point = rrr.forward([0.4, 0.9, -1.2])
    exact = rrr.inverse(point)
    found = generic.inverse(point)
    assert len(found) == 4
    for solution in exact:
        assert same_joints(rrr, found, solution).min() < 1e-10


@pytest.mark.parametrize("name", ROBOTS)
@given(data=st.data())
def test_jacobian_against_finite_differences(name, data):
    robot = ROBOTS[name]
    q = data.draw(joints(robot))
    h = 1e-6       # central difference: error ~ h² |P'''| ~ 1e-12, roundoff ~ 1e-16/h = 1e-10
    fd = np.stack([(robot.forward(q + h * e) - robot.forward(q - h * e)) / (2 * h)
                   for e in np.eye(robot.n)], axis=-1)
    np.testing.assert_allclose(robot.jacobian(q), fd, rtol=0, atol=1e-8)


@pytest.mark.parametrize("name", ROBOTS)
@given(data=st.data())
def test_tool_acceleration_against_finite_differences(name, data):
    robot = ROBOTS[name]
    q0, qd, qdd = (data.draw(joints(robot)) for _ in range(3))

    def velocity(t):
        return robot.motion(q0 + qd * t + 0.5 * qdd * t**2, qd + qdd * t).velocity

    h = 1e-5       # error ~ h² |v'''| ~ 1e-8 for rates of a few rad/s
    m = robot.motion(q0, qd, qdd)
    np.testing.assert_allclose(m.acceleration, (velocity(h) - velocity(-h)) / (2 * h),
                               rtol=0, atol=1e-6)
    np.testing.assert_allclose(m.velocity, robot.jacobian(q0) @ qd, rtol=0, atol=1e-14)


def test_rr_velocity_and_acceleration_match_notes_ex_4_5():
    # *Mecanismos*, Ex. 4.5, the components of 0_ṙ_P and 0_r̈_P written out.
    l1, l2 = 1.0, 0.7
    t1, t2, w1, w2, a1, a2 = 0.4, 1.1, 2.0, -1.5, 0.3, 0.8
    m = ROBOTS["RR"].motion([t1, t2], [w1, w2], [a1, a2])
    s1, c1, s12, c12, w12, a12 = np.sin(t1), np.cos(t1), np.sin(t1 + t2), np.cos(t1 + t2), \
        w1 + w2, a1 + a2
    v = [-l2 * s12 * w12 - l1 * s1 * w1, l2 * c12 * w12 + l1 * c1 * w1]
    a = [l2 * (-c12 * w12**2 - s12 * a12) - l1 * c1 * w1**2 - l1 * s1 * a1,
         l2 * (-s12 * w12**2 + c12 * a12) - l1 * s1 * w1**2 + l1 * c1 * a1]
    np.testing.assert_allclose(m.velocity, v, rtol=0, atol=1e-15)
    np.testing.assert_allclose(m.acceleration, a, rtol=0, atol=1e-14)


def test_rp_acceleration_matches_notes_5_5():
    # a = (q̈2 - q2 q̇1²) i1 + (2 q̇1 q̇2 + q2 q̈1) j1
    q1, q2, u1, u2, u1d, u2d = 0.9, 1.3, 0.7, -0.4, 1.2, 0.5
    m = sp.rp().motion([q1, q2], [u1, u2], [u1d, u2d])
    i1, j1 = np.array([np.cos(q1), np.sin(q1)]), np.array([-np.sin(q1), np.cos(q1)])
    np.testing.assert_allclose(m.acceleration, (u2d - q2 * u1**2) * i1
                               + (2 * u1 * u2 + q2 * u1d) * j1, rtol=0, atol=1e-15)


@pytest.mark.parametrize("name", ROBOTS)
def test_inverse_rates_undo_forward_rates(name):
    robot = ROBOTS[name]
    rng = np.random.default_rng(3)
    q, qd, qdd = (rng.uniform(-2, 2, (30, robot.n)) for _ in range(3))
    keep = np.array([far_from_singular(robot, qi) for qi in q])
    q, qd, qdd = q[keep], qd[keep], qdd[keep]
    m = robot.motion(q, qd, qdd)
    rates = robot.inverse_rates(q, m.velocity, m.acceleration)
    assert not rates.singular.any()
    # J conditioned better than 1e3: 1e3 × 1e-15 relative.
    np.testing.assert_allclose(rates.qd, qd, rtol=0, atol=1e-11)
    np.testing.assert_allclose(rates.qdd, qdd, rtol=0, atol=1e-10)


def test_singular_pose_is_reported():
    robot = ROBOTS["RRR"]
    stretched = [0.3, 0.5, 0.0]                      # θ3 = 0: the arm cannot lengthen
    with pytest.raises(SingularityError, match=r"singular at sample\(s\) 0 .*on_singular='flag'"):
        robot.inverse_rates(stretched, [0.0, 0.0, 1.0])
    q = np.array([stretched, [0.3, 0.5, 1.0]])
    rates = robot.inverse_rates(q, [0.0, 0.0, 1.0], on_singular="flag")
    np.testing.assert_array_equal(rates.singular, [True, False])
    assert np.isfinite(rates.qd).all() and np.isfinite(rates.qdd).all()
    # The regular sample still gets exact rates.
    np.testing.assert_allclose(robot.jacobian(q[1]) @ rates.qd[1], [0, 0, 1], rtol=0, atol=1e-14)
    # A flagged pose a hair off the singularity gets the same least-squares (minimum-norm)
    # rates as the singular pose itself, not the huge ones of a near-singular inverse.
    near = robot.inverse_rates([[0.3, 0.5, 1e-12], stretched], [0.1, 0.2, 0.3], on_singular="flag")
    assert near.singular.all()
    np.testing.assert_allclose(near.qd[0], near.qd[1], rtol=0, atol=1e-9)
    J = robot.jacobian(stretched)
    np.testing.assert_allclose(near.qd[1], np.linalg.lstsq(J, [0.1, 0.2, 0.3], rcond=1e-10)[0],
                               atol=1e-12)


def test_singular_pose_tells_a_limit_from_a_meeting_of_branches():
    """The RR arm stretched along x (l1 = l2 = 1, q = 0, tool at (2, 0)): J = [[0, 0], [2, 1]]
    gives only velocities along y.  Moving out along x is impossible there (the edge of the
    workspace); moving along y is possible, with many rates (2 q̇1 + q̇2 = 1 for v = (0, 1))."""
    robot = sp.rr(1.0, 1.0)
    with pytest.raises(SingularityError, match=r"has a part of 1 m/s that no joint rates give: "
                                               r"the tool cannot move that way from this pose"):
        robot.inverse_rates([0.0, 0.0], [1.0, 0.0])
    with pytest.raises(SingularityError, match=r"the tool can move with the velocity asked for, "
                                               r"but not with unique joint rates"):
        robot.inverse_rates([0.0, 0.0], [0.0, 1.0])
    rates = robot.inverse_rates([[0.0, 0.0]] * 3, [[1.0, 0.0], [0.0, 1.0], [0.6, 0.8]],
                                on_singular="flag")
    np.testing.assert_array_equal(rates.singular, [True, True, True])
    np.testing.assert_array_equal(rates.attainable, [False, True, False])
    # the minimum-norm solution of 2 q̇1 + q̇2 = 1: (2, 1)/5, exact
    np.testing.assert_allclose(rates.qd[1], [0.4, 0.2], rtol=0, atol=1e-15)
    regular = robot.inverse_rates([0.0, 0.5], [1.0, 0.0])
    assert regular.attainable and not regular.singular


def test_an_attainable_velocity_at_a_singular_pose_is_where_branches_cross():
    """The tool path P(t) = (2 - t², t) touches the edge of the RR arm's workspace at t = 0
    from inside (|P|² = 4 - 3t² + t⁴), with v = (0, 1), a = (-2, 0) there.  The elbow-up and
    elbow-down solutions meet at t = 0 and the motion goes on along two smooth branches,
    each from one to the other, with finite rates: 2 q̇1 + q̇2 = 1 (J q̇ = v) and, from
    the x part of the acceleration, q̇1² + (q̇1 + q̇2)² = 2, so q̇1 = (1 ± √3)/2."""
    robot = sp.rr(1.0, 1.0)
    assert robot.inverse_rates([0.0, 0.0], [0.0, 1.0], on_singular="flag").attainable
    # h = 1e-3: near the edge of the workspace the inverse has rounding eps/t (1e-13 here),
    # so the central differences below carry 1e-10 of it, and h² q'''/6 (q''' <= 10) of
    # truncation: 1e-5.
    h = 1e-3
    before = {b: robot.inverse([2 - h * h, -h], branch=b) for b in robot.branches}
    after = {b: robot.inverse([2 - h * h, h], branch=b) for b in robot.branches}
    found = []
    for b in robot.branches:
        # the continuation of branch b: the solution after t = 0 nearest its straight line
        ahead = 2 * robot.inverse([2.0, 0.0])[0] - before[b]
        c = min(after, key=lambda k: np.abs(after[k] - ahead).max())
        assert c != b                      # up becomes down, and down becomes up
        found.append((after[c] - before[b]) / (2 * h))
    np.testing.assert_allclose(sorted(qd[0] for qd in found),
                               [(1 - np.sqrt(3)) / 2, (1 + np.sqrt(3)) / 2], rtol=0, atol=1e-5)
    for qd in found:
        assert 2 * qd[0] + qd[1] == pytest.approx(1.0, abs=1e-5)


# -- branches mean what their names say ---------------------------------------------------

def test_rr_up_has_the_elbow_left_of_the_chord():
    robot = ROBOTS["RR"]
    point = np.array([0.9, 0.8])
    for branch, sign in (("up", 1), ("down", -1)):
        t1, t2 = robot.inverse(point, branch=branch)
        elbow = np.array([np.cos(t1), np.sin(t1)])
        assert np.sign(point[0] * elbow[1] - point[1] * elbow[0]) == sign
        assert np.sign(t2) == -sign


@given(st.floats(-3, 3), st.floats(0.2, 1.5), st.floats(-1.5, 1.5))
def test_rrr_branches_front_back_up_down(theta1, r, z):
    robot = ROBOTS["RRR"]
    point = np.array([-r * np.sin(theta1), r * np.cos(theta1), z])
    assume(robot.reachable(point))
    assume(abs(np.hypot(r, z) - 1.6) > 1e-3 and abs(np.hypot(r, z) - 0.4) > 1e-3)
    for branch in robot.branches:
        t1, t2, t3 = robot.inverse(point, branch=branch)
        arm = np.array([-np.sin(t1), np.cos(t1)])            # direction of the arm plane
        elbow = 1.0 * np.array([arm[0] * np.cos(t2), arm[1] * np.cos(t2), np.sin(t2)])
        facing = np.sign(arm @ point[:2])
        horizontal = elbow[:2] @ point[:2] / r                # elbow along the chord's plane
        above = r * elbow[2] - z * horizontal > 0             # left of the chord in (r, z)
        assert facing == (1 if branch.startswith("front") else -1)
        assert above == branch.endswith("up")


# -- unreachable and degenerate points: errors, never NaN ---------------------------------

@pytest.mark.parametrize("name, point, message", [
    ("RR", [2.0, 0.0], r"0\.3 m outside the workspace \(distance from the origin between "
                       r"0\.3 m and 1\.7 m\)"),
    ("RR", [0.1, 0.0], r"0\.2 m outside the workspace"),
    ("PR", [0.0, 1.0], r"0\.2 m outside the workspace \(the strip \|y\| <= 0\.8 m\)"),
    ("RRR", [0.0, 1.0, 1.4], r"outside the workspace \(distance from the shoulder"),
    ("PRR", [2.0, 0.0, 0.0], r"0\.2 m outside the workspace"),
])
def test_unreachable_point_raises_with_the_gap(name, point, message):
    robot = ROBOTS[name]
    with pytest.raises(AssemblyError, match=message):
        robot.inverse(point)
    assert not robot.reachable(point)


def test_reachable_mask_for_a_batch():
    robot = ROBOTS["RRR"]
    mask = robot.reachable([[0.0, 1.0, 0.5], [0.0, 3.0, 0.0], [0.0, 0.5, 0.0]])
    np.testing.assert_array_equal(mask, [True, False, True])


@pytest.mark.parametrize("robot, point, message", [
    (sp.rrr(1.0, 1.0), [0.0, 0.0, 1.2], r"on the θ1 axis \(x = y = 0\), so θ1 is arbitrary"),
    (sp.rr(1.0, 1.0), [0.0, 0.0], r"at the origin, so θ1 is arbitrary"),
    (sp.rp(), [0.0, 0.0], r"at the origin"),
    (sp.prr(1.0, 1.0, D=0.5), [0.5, 0.0, 0.3], r"on the first revolute axis"),
])
def test_infinitely_many_solutions_raise(robot, point, message):
    with pytest.raises(SingularityError, match=message):
        robot.inverse(point)


def test_singular_point_can_still_be_solved_from_a_guess():
    robot = sp.rrr(1.0, 1.0)
    q = robot.inverse([0.0, 0.0, 1.2], guess=[0.7, 1.0, -1.0])
    np.testing.assert_allclose(robot.forward(q), [0.0, 0.0, 1.2], rtol=0, atol=1e-12)


def test_edge_of_workspace_gives_the_merged_solutions_once():
    robot = ROBOTS["RRR"]
    point = robot.forward([0.2, 0.5, 0.0])           # arm stretched: elbows merge
    solutions = robot.inverse(point)
    assert len(solutions) == 2                       # front and back
    np.testing.assert_allclose(robot.forward(solutions), [point, point], rtol=0, atol=1e-12)


def test_newton_failure_is_reported():
    with pytest.raises(ConvergenceError, match=r"did not converge for sample\(s\) 0"):
        ROBOTS["RRR"].inverse([0.0, 3.0, 0.0], guess=[0.0, 0.1, 0.1])


def test_shapes_follow_the_input():
    robot = ROBOTS["RRR"]
    assert robot.forward([0.1, 0.2, 0.3]).shape == (3,)
    assert robot.forward(np.zeros((7, 3))).shape == (7, 3)
    assert robot.jacobian(np.zeros((7, 3))).shape == (7, 3, 3)
    assert robot.motion(np.zeros(3), 1.0).acceleration.shape == (3,)
    assert ROBOTS["RR"].jacobian([0.1, 0.2]).shape == (2, 2)


@pytest.mark.parametrize("call, error, message", [
    (lambda: sp.rrr(1.0, -1.0), ModelError, r"L3: expected a positive length in m, got -1\.0"),
    (lambda: ROBOTS["RRR"].forward([0.1, 0.2]), ModelError,
     r"q: expected shape \(3,\) or \(N, 3\), got \(2,\)"),
    (lambda: ROBOTS["RRR"].inverse([0.1, 0.2, 0.3], branch="elbow"), ModelError,
     r"branch: expected one of 'front-up', 'front-down', 'back-up', 'back-down', got 'elbow'"),
    (lambda: sp.SerialRobot("bad", (sp.RobotJoint("R", (1, 0, 0)),), (1, 0, 0), planar=True),
     ModelError, r"joints\[0\]: a planar robot turns about z"),
    (lambda: sp.RobotJoint("H", (0, 0, 1)), ModelError, r"kind: expected one of 'R', 'P'"),
    (lambda: ROBOTS["RRR"].motion(np.zeros(3), [1.0, 2.0]), ModelError,
     r"qd: expected a number or shape \(3,\) or \(1, 3\) like q, got \(2,\)"),
])
def test_bad_arguments(call, error, message):
    with pytest.raises(error, match=message):
        call()
