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


def spans(reach):
    """The reachable intervals as the messages show them."""
    return " ∪ ".join(f"[{lo:.6g}, {hi:.6g}]" for lo, hi in reach)


@pytest.mark.parametrize("end", [0, 1, 2, 3])
def test_limit_position_raises_with_the_reachable_range(end):
    m = sp.RSSR(**LIMITED)
    reach = m.reachable_inputs()
    edge = np.ravel(reach)[end]
    with pytest.raises(SingularityError) as info:
        m.analyze([0.0, edge])
    message = str(info.value)
    assert f"θ1 = {edge:.6g} rad (sample(s) 1) is a limit position" in message
    # the very numbers reachable_inputs() returns, as "[-0.898806, 0.898806] ∪ [2.24279, ..."
    assert f"reachable θ1 is {spans(reach)} rad" in message
    assert spans(reach).startswith("[-0.898806, 0.898806] ∪ [2.24279, 4.0404]")
    assert "dead" not in message


def test_output_speed_is_unbounded_at_a_limit_position():
    # Near a fold D ~ D' δ, so K ~ δ^(-1/2): K sqrt(δ) tends to a constant (here 0.618 by
    # the run itself), while at a change point K stays finite.  δ = 1e-4 .. 1e-10 keeps the
    # rounding of D (1e-16 |m0|) below 1e-6 of D.
    m = sp.RSSR(**LIMITED)
    edge = m.reachable_inputs()[0][1]
    delta = np.array([1e-4, 1e-6, 1e-8, 1e-10])
    K = m.analyze(edge - delta).K
    scaled = np.abs(K) * np.sqrt(delta)
    assert np.abs(K[-1]) > 1e4
    np.testing.assert_allclose(scaled, scaled[-1], rtol=2e-2)    # O(δ) corrections at 1e-4


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


def test_bad_change_point_choice():
    with pytest.raises(ModelError, match=r"at_change_point: expected one of 'smooth', "
                                         r"'switch', got 'jump'"):
        sp.RSSR(**LIMITED).analyze(0.0, at_change_point="jump")


# -- change points: where the two branches cross ---------------------------------------------

NOTES = dict(H1=1.0, L1=0.0, L0=1.0, L2=1.0, H3=1.0, L3=0.0)
# *Mecanismos*, §7.3.  E = -2 cos θ1, F = -2, G = 2: eq. 74 is cos θ1 cos θ3 + sin θ3 = 1.
# With u = tan(θ3/2): (1 + c1) u² - 2u + (1 - c1) = 0, so u = 1 (θ3 = 90°: B on the input
# shaft, where |AB| does not change as the input turns) or u = (1 - c1)/(1 + c1) =
# tan²(θ1/2).  The second branch, θ3 = 2 atan(t²) with t = tan(θ1/2), has
# K = 2 t (1 + t²) / (1 + t⁴) (d/dθ1 of 2 atan(t²), with dt/dθ1 = (1 + t²)/2): K = ±2 at
# θ1 = ±90°, where it crosses the first (u = 1 twice: E² + F² - G² = 4 cos² θ1 = 0 and its
# derivative too).  It is branch -1 for |θ1| < 90° (θ3 = 0 at θ1 = 0, the notes' choice)
# and branch +1 beyond.
ASKEW = dict(H1=0.3, L1=0.2, L0=0.8, L2=0.5, H3=0.6, L3=0.8)
# A change point with L3 != 0 and L1 != 0: r3 = 1, |L1 - L0| = 0.6, G = 1 + 0.36 + 0.09
# - 0.25 = 1.2 = 2 r3 |L1 - L0| (L2² = H1² + (r3 - |L1 - L0|)²; only to rounding in floats).


def notes_branch(theta1):
    t = np.tan(theta1 / 2)
    return 2 * np.arctan(t * t), 2 * t * (1 + t * t) / (1 + t**4)


def test_notes_example_turns_fully_through_its_change_points():
    m = sp.RSSR(**NOTES)
    theta1 = np.radians(np.arange(-180.0, 180.5, 1.0))          # ±90° exactly among them
    sol = m.analyze(theta1, theta1_dot=1.0, branch=-1)
    theta3, K = notes_branch(theta1)
    assert np.isfinite(sol.K).all() and np.isfinite(sol.L).all()
    # 1e-12: closed form against closed form, angles of order 1 rad
    np.testing.assert_allclose(sol.theta3, theta3, rtol=0, atol=1e-12)
    np.testing.assert_allclose(sol.K, K, rtol=0, atol=1e-12)
    at = np.flatnonzero(sol.change_point)
    np.testing.assert_array_equal(theta1[at], np.radians([-90.0, 90.0]))
    assert sol.K[at].tolist() == pytest.approx([-2.0, 2.0], abs=1e-12)
    assert m.change_points() == pytest.approx([-np.pi / 2, np.pi / 2], abs=0)
    assert m.reachable_inputs() == [(-np.pi, np.pi)]


@pytest.mark.parametrize("geometry", [NOTES, ASKEW])
@pytest.mark.parametrize("branch", [1, -1])
@pytest.mark.parametrize("at", [-np.pi / 2, np.pi / 2])
def test_K_and_L_at_a_change_point_are_the_limits_from_both_sides(geometry, branch, at):
    m = sp.RSSR(**geometry)
    h = 1e-5
    sol = m.analyze(np.array([at - 2 * h, at - h, at, at + h, at + 2 * h]), branch=branch)
    assert sol.change_point.tolist() == [False, False, True, False, False]
    t, K, L = sol.theta3, sol.K, sol.L
    # One-sided differences of positions, from the left and from the right: K + L h/2 +
    # O(h²), where L (0 at these change points, see below) and L' (<= 6 here) keep the
    # error below 3h²; rounding 1e-16/h.  So 1e-8.
    assert (t[2] - t[1]) / h == pytest.approx(K[2], abs=1e-8)
    assert (t[3] - t[2]) / h == pytest.approx(K[2], abs=1e-8)
    # L from differences of K on either side (K itself from the closed form there): one
    # sided, L ± L' h/2 with |L'| <= 6, so 5e-5; central, L + O(h²).
    assert (K[2] - K[1]) / h == pytest.approx(L[2], abs=5e-5)
    assert (K[3] - K[2]) / h == pytest.approx(L[2], abs=5e-5)
    assert (K[3] - K[1]) / (2 * h) == pytest.approx(L[2], abs=1e-9)
    # and the sample at the change point continues its neighbours: second differences of K
    assert abs(K[0] - 2 * K[1] + K[2]) < 1e-9 and abs(K[2] - 2 * K[3] + K[4]) < 1e-9


def test_change_point_against_the_loop_in_exact_arithmetic():
    """K and L at the change points of ASKEW from |A - B|² - L2² itself (not eq. 74) in
    sympy: the double root θ3c, then the quadratic and the cubic of the expansion."""
    sy = pytest.importorskip("sympy")
    r = sy.Rational
    H1, L1, L0, L2, H3, L3 = r(3, 10), r(2, 10), r(8, 10), r(5, 10), r(6, 10), r(8, 10)
    q, S, K = sy.symbols("q S K")
    A = sy.Matrix([H1 * sy.sin(q), L1, H1 * sy.cos(q)])
    B = sy.Matrix([0, L0 - L3 * sy.cos(S) - H3 * sy.sin(S), H3 * sy.cos(S) - L3 * sy.sin(S)])
    phi = (A - B).dot(A - B) - L2**2
    m = sp.RSSR(**ASKEW)
    for at in (-sy.pi / 2, sy.pi / 2):
        # at θ1 = ±90°: Φ = 6/5 - (24 cos S + 18 sin S)/25, zero only at cos S = 4/5, sin S = 3/5
        Sc = sy.atan2(r(3, 5), r(4, 5))
        point = {q: at, S: Sc}
        def d(*v):
            return sy.simplify((sy.diff(phi, *v) if v else phi).subs(point))

        assert d() == 0 and d(q) == 0 and d(S) == 0                        # a change point
        roots = sy.solve(d(S, S) * K**2 + 2 * d(q, S) * K + d(q, q), K)
        assert len(roots) == 2
        expected = {}
        for k in roots:
            L = -(d(q, q, q) + 3 * d(q, q, S) * k + 3 * d(q, S, S) * k**2 + d(S, S, S) * k**3) \
                / (3 * (d(q, S) + d(S, S) * k))
            expected[float(k)] = float(L)
        got = {}
        for branch in (1, -1):
            sol = m.analyze(float(at), branch=branch)
            assert bool(sol.change_point)
            assert float(sol.theta3) == pytest.approx(float(Sc), abs=1e-12)
            got[float(sol.K)] = float(sol.L)
        # the two branches are the two roots, each with its own L (1e-12: exact vs float)
        assert sorted(got) == pytest.approx(sorted(expected), abs=1e-12)
        for k in got:
            assert got[k] == pytest.approx(expected[min(expected, key=lambda e: abs(e - k))],
                                           abs=1e-12)


def test_switch_takes_the_other_branch_at_change_points():
    m = sp.RSSR(**NOTES)
    theta1 = np.radians(np.arange(-180.0, 180.5, 5.0))
    smooth = m.analyze(theta1, branch=-1)
    switch = m.analyze(theta1, branch=-1, at_change_point="switch")
    inside, beyond = np.abs(theta1) < np.pi / 2, np.abs(theta1) > np.pi / 2
    np.testing.assert_array_equal(switch.theta3[inside], smooth.theta3[inside])
    # beyond ±90° the sign of ∂Φ/∂θ3 stays -1: the branch u = 1 (θ3 = 90°, K = 0)
    np.testing.assert_allclose(switch.theta3[beyond], np.pi / 2, rtol=0, atol=1e-15)
    np.testing.assert_allclose(switch.K[beyond], 0.0, rtol=0, atol=1e-15)
    # at the change points, the branch followed past them towards larger θ1
    at = m.analyze(np.radians([-90.0, 90.0]), branch=-1, at_change_point="switch")
    assert at.K.tolist() == pytest.approx([-2.0, 0.0], abs=1e-12)


def test_the_branch_depends_only_on_the_input():
    m = sp.RSSR(**ASKEW)
    theta1 = np.radians([170.0, -100.0, 10.0, 90.0, -90.0, 250.0])
    for mode in ("smooth", "switch"):
        batch = m.analyze(theta1, branch=1, at_change_point=mode)
        shuffled = m.analyze(theta1[::-1], branch=1, at_change_point=mode)
        turned = m.analyze(theta1 + 4 * np.pi, branch=1, at_change_point=mode)
        for i, t in enumerate(theta1):
            one = m.analyze(t, branch=1, at_change_point=mode)
            assert float(one.theta3) == batch.theta3[i] == shuffled.theta3[-1 - i]
            assert float(one.K) == batch.K[i]
            # two turns on: the same branch (to the rounding of cos and sin of θ1 + 4π)
            assert turned.theta3[i] == pytest.approx(batch.theta3[i], abs=1e-13)
            assert turned.K[i] == pytest.approx(batch.K[i], abs=1e-12)


@given(st.floats(0.2, 1.5), st.floats(0.2, 1.5), st.floats(-1.5, 1.5), st.floats(0.2, 1.5),
       st.floats(-np.pi, np.pi), st.sampled_from([1.0, -1.0]), st.sampled_from([1, -1]),
       st.sampled_from([-np.pi / 2, np.pi / 2]))
def test_random_change_points_against_finite_differences(H1, r3, L1, d, alpha, near, branch,
                                                         at):
    """Crossing geometries: L2² = H1² + (r3 ∓ |L1 - L0|)² makes |G| = 2 r3 |L1 - L0|."""
    L2 = float(np.hypot(H1, r3 - near * d))
    assume(L2 > 0.05)
    m = sp.RSSR(H1=H1, L1=L1, L0=L1 + d, L2=L2, H3=r3 * np.sin(alpha), L3=r3 * np.cos(alpha))
    assert m.change_points() == [-np.pi / 2, np.pi / 2]
    h = 1e-6
    sol = m.analyze(np.array([at - h, at, at + h]), branch=branch)
    assume(np.abs(sol.K).max() < 20 and np.abs(sol.L).max() < 200)
    assert sol.change_point.tolist() == [False, True, False]
    t = np.unwrap(sol.theta3)
    # central differences across the change point, as in the test above away from it
    assert sol.K[1] == pytest.approx((t[2] - t[0]) / (2 * h), rel=1e-7, abs=1e-7)
    assert sol.L[1] == pytest.approx((sol.K[2] - sol.K[0]) / (2 * h), rel=1e-6, abs=1e-6)


def test_reachable_inputs_split_at_limit_positions_not_at_change_points():
    for geometry, pieces in ((NOTES, 1), (ASKEW, 1), (LIMITED, 2)):
        m = sp.RSSR(**geometry)
        reach = m.reachable_inputs()
        assert len(reach) == pieces
        for lo, hi in reach:
            inner = np.linspace(lo, hi, 201)[1:-1]
            for branch in (1, -1):
                sol = m.analyze(inner, branch=branch)
                assert np.isfinite(sol.K).all() and np.isfinite(sol.L).all()
            if pieces == 2:                  # limit positions at both ends
                for end in (lo, hi):
                    with pytest.raises(SingularityError, match="limit position"):
                        m.analyze(end)


@pytest.mark.parametrize("dL2, pieces, crossing", [
    (1e-13, 1, True),       # a crossing geometry to rounding: the branches cross at ±90°
    (1e-9, 1, False),       # the coupler a little longer: the branches pass close by
    (-1e-9, 2, False),      # a little shorter: two limit positions a gap apart at ±90°
])
def test_only_rounding_makes_a_crossing_geometry(dL2, pieces, crossing):
    m = sp.RSSR(**dict(NOTES, L2=1.0 + dL2))
    reach = m.reachable_inputs()
    assert len(reach) == pieces and (m.change_points() != []) == crossing
    if pieces == 2:
        # by hand: G = 3 - L2², and D = 0 where cos² θ1 = (G² - 4)/4
        G = 3.0 - (1.0 + dL2) ** 2
        a = np.arccos(np.sqrt((G * G - 4.0) / 4.0))
        assert reach[0] == pytest.approx((-a, a), abs=1e-12)
        assert np.pi / 2 - a == pytest.approx(np.sqrt(-2 * dL2), rel=1e-3)
        with pytest.raises(AssemblyError, match="cannot close"):
            m.analyze(np.pi / 2)
    else:
        assert np.isfinite(m.analyze(np.radians(np.arange(-180.0, 181.0)), branch=-1).K).all()


@pytest.mark.parametrize("scale", [1e-4, 1e4])
@pytest.mark.parametrize("geometry", [NOTES, ASKEW, LIMITED])
def test_scale_free(geometry, scale):
    m, big = sp.RSSR(**geometry), sp.RSSR(**{k: v * scale for k, v in geometry.items()})
    np.testing.assert_allclose(big.reachable_inputs(), m.reachable_inputs(), rtol=0, atol=1e-12)
    assert big.change_points() == m.change_points()
    lo, hi = m.reachable_inputs()[0]
    theta1 = np.concatenate([np.linspace(lo, hi, 41)[1:-1], [-np.pi / 2, np.pi / 2]])
    theta1 = theta1[m.positions(theta1).feasible]
    a, b = m.analyze(theta1, branch=-1), big.analyze(theta1, branch=-1)
    np.testing.assert_array_equal(a.change_point, b.change_point)
    # angles and coefficients are dimensionless: equal to rounding (a few ulp of K ~ 1e3)
    np.testing.assert_allclose(b.theta3, a.theta3, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b.K, a.K, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(b.L, a.L, rtol=1e-9, atol=1e-12)


def test_branches_that_cross_a_line_of_solutions():
    """L1 = L0, G = 0: |AB|² - L2² = -1.5 cos θ1 cos θ3 (A = (0.75 s1, L0, 0.75 c1),
    B = (0, L0 - s3, c3)), so θ3 = ±90° for every θ1, and at θ1 = ±90° every θ3 closes the
    loop: each branch crosses that line of solutions, and the sign of ∂Φ/∂θ3 = 1.5 c1 s3
    turns there."""
    m = sp.RSSR(H1=0.75, L1=0.5, L0=0.5, L2=1.25, H3=1.0, L3=0.0)
    theta1 = np.radians(np.arange(-180.0, 180.5, 1.0))
    for branch in (1, -1):
        sol = m.analyze(theta1, 1.0, 1.0, branch=branch)
        np.testing.assert_allclose(sol.theta3, branch * np.pi / 2, rtol=0, atol=1e-15)
        np.testing.assert_allclose(np.c_[sol.K, sol.L], 0.0, rtol=0, atol=1e-15)
        assert sol.change_point.sum() == 2
        switch = m.analyze(theta1, branch=branch, at_change_point="switch")
        beyond = np.cos(theta1) < 0
        np.testing.assert_allclose(switch.theta3[beyond], -branch * np.pi / 2, atol=1e-15)


def test_input_crank_on_its_axis():
    # H1 = 0: A = (0, L1, 0) whatever θ1, so θ3 is constant and K = L = 0, also when the
    # coupler is just stretched (L2 = |d| + r3 = 2, the two branches one) ...
    for L2 in (2.0, 1.5):
        m = sp.RSSR(H1=0.0, L1=0.0, L0=1.0, L2=L2, H3=1.0, L3=0.0)
        sol = m.analyze(np.linspace(-np.pi, np.pi, 9), 2.0, 3.0)
        assert np.ptp(sol.theta3) == 0.0 and not sol.K.any() and not sol.L.any()
        assert m.reachable_inputs() == [(-np.pi, np.pi)] and m.change_points() == []
    # ... and with A at the centre of B's circle no θ3 is singled out
    with pytest.raises(ModelError, match=r"A stays at the centre of B's circle"):
        sp.RSSR(H1=0.0, L1=0.5, L0=0.5, L2=1.25, H3=1.0, L3=0.75)


def test_a_loop_that_closes_only_at_two_inputs():
    # G = 0.36 + 1 + 0.64 - 4 = -2 = -2 r3 sqrt((L1 - L0)² + H1²): A reaches B only at
    # θ1 = 0 and π, with the coupler stretched along the line of the two centres
    m = sp.RSSR(H1=0.6, L1=0.0, L0=0.8, L2=2.0, H3=1.0, L3=0.0)
    assert m.reachable_inputs() == [(0.0, 0.0), (np.pi, np.pi)]
    for at in (0.0, np.pi):
        assert m.positions(at).feasible
        with pytest.raises(SingularityError, match=r"isolated configuration: the loop closes "
                                                   r"only at θ1 = 0 and π"):
            m.analyze(at)
    with pytest.raises(AssemblyError, match=r"reachable θ1 is \[0, 0\] ∪ \[3\.14159, 3\.14159\]"):
        m.analyze(0.1)
