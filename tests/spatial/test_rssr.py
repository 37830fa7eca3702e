"""RSSR: the input-output equation against the loop it comes from, rates against finite
differences, feasibility against a direct scan."""
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import kinelab.spatial as sp
from kinelab.errors import AssemblyError, ModelError, SingularityError

length = st.floats(-1.5, 1.5, allow_nan=False)
angle = st.floats(-np.pi, np.pi, allow_nan=False)


def joint_centres(H1, L1, L0, H3, L3, theta1, theta3, D3=0.37):
    """A and B straight from the frames of *Mecanismos*, §7.3 (D3 arbitrary: it cancels)."""
    T1 = sp.homogeneous(sp.rotation("y", theta1), [0.0, 0.0, 0.0])
    T3 = sp.compose(sp.translation([-D3, L0, 0.0]),
                    sp.homogeneous(sp.rotation("x", theta3), [0.0, 0.0, 0.0]))
    return sp.transform_points(T1, [0.0, L1, H1]), sp.transform_points(T3, [D3, -L3, H3])


@st.composite
def assembled(draw):
    """A random RSSR, with L2 taken from one assembled pose (θ1, θ3) so that it closes."""
    H1, L1, L0, H3, L3 = (draw(length) for _ in range(5))
    assume(abs(H1) > 0.1 and np.hypot(H3, L3) > 0.1)
    theta1, theta3 = draw(angle), draw(angle)
    A, B = joint_centres(H1, L1, L0, H3, L3, theta1, theta3)
    L2 = float(np.linalg.norm(A - B))
    assume(L2 > 0.05)
    return sp.RSSR(H1=H1, L1=L1, L0=L0, L2=L2, H3=H3, L3=L3), theta1, theta3


@given(assembled())
def test_the_assembled_pose_is_one_of_the_two_solutions(case):
    m, theta1, theta3 = case
    pos = m.positions(theta1)
    assert pos.feasible
    scale = m.L2 + abs(m.H1) + abs(m.H3) + abs(m.L3) + abs(m.L0 - m.L1)
    miss = np.abs(np.angle(np.exp(1j * (pos.theta3 - theta3)))).min()
    # The root is as well conditioned as ∂Φ/∂θ3 is large; skip the near-tangent draws.
    phi_3 = pos.F * np.cos(theta3) - pos.E * np.sin(theta3)
    assume(abs(phi_3) > 1e-3 * scale**2)
    assert miss < 1e-9


@given(assembled(), st.floats(-np.pi, np.pi))
def test_both_solutions_close_the_loop(case, theta1):
    m = case[0]
    pos = m.positions(theta1)
    assume(pos.feasible)
    for column in range(2):
        A, B = joint_centres(m.H1, m.L1, m.L0, m.H3, m.L3, theta1, pos.theta3[column])
        # 1e-12: lengths of order 1 m after a few trigonometric evaluations.
        assert abs(np.linalg.norm(A - B) - m.L2) < 1e-12 * max(1.0, 1 / m.L2)
        np.testing.assert_allclose(pos.B[column], B, rtol=0, atol=1e-14)
        np.testing.assert_allclose(pos.A, A, rtol=0, atol=1e-15)


@given(assembled(), angle, angle)
def test_equation_74_is_the_loop_length(case, theta1, theta3):
    m = case[0]
    pos = m.positions(theta1)
    A, B = joint_centres(m.H1, m.L1, m.L0, m.H3, m.L3, theta1, theta3)
    lhs = pos.E * np.cos(theta3) + pos.F * np.sin(theta3) + pos.G
    assert lhs == pytest.approx(np.sum((A - B) ** 2) - m.L2**2, abs=1e-12)


@given(assembled(), st.sampled_from([1, -1]))
def test_K_and_L_against_finite_differences(case, branch):
    m, theta1, _ = case
    # Central differences: truncation h²/6 × (third derivative, up to ~1e3 near the
    # dead points kept here) ~ 1e-10, roundoff 1e-16/h ~ 1e-10.
    h = 1e-6
    try:
        sol = m.analyze(np.array([theta1 - h, theta1, theta1 + h]), branch=branch)
    except (AssemblyError, SingularityError):
        assume(False)
    assume(np.abs(sol.K).max() < 20 and np.abs(sol.L).max() < 200)   # away from dead points
    t = np.unwrap(sol.theta3)
    # theta3's own rounding grows as 1/L3 for short output cranks (2e-8 seen at L3 = 1/128)
    assert sol.K[1] == pytest.approx((t[2] - t[0]) / (2 * h), rel=1e-7, abs=1e-7)
    assert sol.L[1] == pytest.approx((sol.K[2] - sol.K[0]) / (2 * h), rel=1e-7, abs=1e-7)


def test_output_motion_from_K_and_L():
    m = sp.RSSR(H1=1.0, L1=0.2, L0=1.0, L2=1.3, H3=0.8, L3=0.3)
    theta1 = np.linspace(-np.pi, np.pi, 9)
    sol = m.analyze(theta1, theta1_dot=3.0, theta1_ddot=-2.0, branch=-1)
    np.testing.assert_allclose(sol.theta3_dot, 3.0 * sol.K, rtol=0, atol=0)
    np.testing.assert_allclose(sol.theta3_ddot, -2.0 * sol.K + 9.0 * sol.L, rtol=0, atol=1e-15)
    assert sol.theta3.shape == (9,)


def test_branch_sign_is_the_sign_of_the_loop_derivative():
    m = sp.RSSR(H1=1.0, L1=0.2, L0=1.0, L2=1.3, H3=0.8, L3=0.3)
    theta1, h = 0.4, 1e-6
    for branch in (1, -1):
        theta3 = m.analyze(theta1, branch=branch).theta3
        A, Bp = joint_centres(m.H1, m.L1, m.L0, m.H3, m.L3, theta1, theta3 + h)
        _, Bm = joint_centres(m.H1, m.L1, m.L0, m.H3, m.L3, theta1, theta3 - h)
        # Turning the output crank forward pulls B away from A on branch +1.
        assert np.sign(np.linalg.norm(A - Bp) - np.linalg.norm(A - Bm)) == branch


# -- feasibility ----------------------------------------------------------------------------

LIMITED = dict(H1=1.0, L1=0.0, L0=0.5, L2=0.8, H3=0.6, L3=0.2)
# G = 1.65 - 0.64 = 1.01, E² + F² = 1.6 (0.25 + cos² θ1): closes where cos² θ1 >= 0.38756,
# |θ1| <= 0.89881 rad.


def test_reachable_inputs_by_hand():
    (lo, hi), (lo2, hi2) = sp.RSSR(**LIMITED).reachable_inputs()
    a = np.arccos(np.sqrt((1.01**2 / 1.6 - 0.25)))
    assert (lo, hi, lo2, hi2) == pytest.approx((-a, a, np.pi - a, np.pi + a), abs=1e-15)


@pytest.mark.parametrize("geometry", [LIMITED, dict(H1=1.0, L1=0.0, L0=1.0, L2=1.0, H3=1.0,
                                                    L3=0.0), dict(H1=0.2, L1=0.0, L0=3.0,
                                                                  L2=1.0, H3=0.5, L3=0.0)])
def test_reachable_inputs_agree_with_a_scan(geometry):
    m = sp.RSSR(**geometry)
    theta1 = np.linspace(-np.pi, np.pi, 2001)
    feasible = m.positions(theta1).feasible
    inside = np.zeros_like(feasible)
    for lo, hi in m.reachable_inputs():
        inside |= (np.angle(np.exp(1j * (theta1 - lo))) % (2 * np.pi) <= (hi - lo) + 1e-12)
    np.testing.assert_array_equal(feasible, inside)


def test_infeasible_input_raises_with_the_reachable_range():
    m = sp.RSSR(**LIMITED)
    with pytest.raises(AssemblyError, match=r"cannot close at θ1 = 1\.5 rad .* reachable θ1 is "
                                            r"\[-0\.8988\d*, 0\.8988\d*\] ∪ \[2\.2427") as info:
        m.analyze([0.0, 1.5])
    assert info.value.reachable == m.reachable_inputs()
    assert not m.positions(1.5).feasible
    assert not np.isnan(m.positions(1.5).theta3).any()


def test_dead_position_raises():
    m = sp.RSSR(**LIMITED)
    edge = m.reachable_inputs()[0][1]
    with pytest.raises(SingularityError, match=r"dead position"):
        m.analyze(edge)


@pytest.mark.parametrize("kwargs, message", [
    (dict(LIMITED, H3=0.0, L3=0.0), r"H3, L3: the output crank has zero length"),
    (dict(LIMITED, L2=0.0), r"L2: expected a positive length in m, got 0\.0"),
    (dict(LIMITED, H1=np.nan), r"H1: expected a finite length in m"),
])
def test_bad_geometry(kwargs, message):
    with pytest.raises(ModelError, match=message):
        sp.RSSR(**kwargs)


def test_bad_branch():
    with pytest.raises(ModelError, match=r"branch: expected one of 1, -1, got 0"):
        sp.RSSR(**LIMITED).analyze(0.0, branch=0)
