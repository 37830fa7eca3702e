"""Motion generation through two and three positions (*Mecanismos*, §6.1, 6.2, 6.4)."""
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import (Positions, fixed_pivot, fourbar_model, moving_pivot,
                               three_positions, two_positions)
from tests.synthesis.helpers import catalogue_poses, engine_pose_errors, travel_transmission

P3 = np.array([(1.0, 1.0), (2.0, 0.5), (3.0, 1.5)])
ALPHA3 = np.radians([0.0, 0.0, 45.0])

coord = st.floats(-3, 3)


@st.composite
def three_poses(draw):
    pts = np.array(draw(st.lists(st.tuples(coord, coord), min_size=3, max_size=3)))
    ang = np.array(draw(st.lists(st.floats(-2.5, 2.5), min_size=2, max_size=2)))
    assume(np.ptp(pts, axis=0).max() > 0.1)
    assume(min(abs(ang[0]), abs(ang[1]), abs(ang[1] - ang[0])) > 0.05)   # poles finite
    return Positions(pts, ang)


def finite_pivot(construct, pos, **pivot):
    """The pivot, or skip the example where it is at infinity or too far out: far pivots
    are ill-conditioned whichever way they are found."""
    try:
        x = construct(pos, **pivot)
    except ModelError:
        assume(False)
    assume(np.abs(x).max() < 1e3)
    return x


@given(three_poses(), st.tuples(coord, coord))
def test_suh_radcliffe_against_burmester_poles(pos, A0):
    """Two methods for the same moving pivot: a linear system and a pole construction."""
    A0 = np.array(A0)
    a = finite_pivot(moving_pivot, pos, fixed=A0)
    b = moving_pivot(pos, fixed=A0, method="poles")
    # both are exact constructions; the tolerance covers their conditioning at this size
    np.testing.assert_allclose(a, b, atol=1e-7 * (1 + np.abs(a).max()))
    # and the crank keeps its length in every position (eq. 67)
    r = np.linalg.norm(pos.carry(a) - A0, axis=1)
    assert np.ptp(r) <= 1e-9 * (1 + r.max())


@given(three_poses(), st.tuples(coord, coord))
def test_fixed_pivot_inverts_moving_pivot(pos, A1):
    A1 = np.array(A1)
    A0 = finite_pivot(fixed_pivot, pos, moving=A1)
    np.testing.assert_allclose(moving_pivot(pos, fixed=A0), A1, atol=1e-7 * (1 + np.abs(A0).max()))


def test_three_positions_reaches_every_pose_with_the_engine():
    sol = three_positions(P3, ALPHA3, (5.0, 0.0), (0.0, 0.0))
    assert sol.valid and not sol.branch_defect and not sol.order_defect
    dpos, dang = engine_pose_errors(sol.model, sol.q, P3, ALPHA3)
    assert dpos.max() < 1e-9 and dang.max() < 1e-9         # the 1e-9
    # the model is in position 1 and uses the catalogue's names
    m = sol.model
    np.testing.assert_allclose([m.point("O2").xy, m.point("A").xy, m.point("B").xy,
                                m.point("O4").xy, m.point("P").xy],
                               [sol.A0, sol.A1, sol.B1, sol.B0, P3[0]], atol=0)
    assert m.link_names == ("ground", "crank", "coupler", "rocker")
    assert sol.A1.shape == sol.B1.shape == (2,)


def test_moving_and_fixed_pivots_can_be_mixed():
    ref = three_positions(P3, ALPHA3, (5.0, 0.0), (0.0, 0.0))
    mixed = three_positions(P3, ALPHA3, A0=(5.0, 0.0), B1=ref.B1)
    np.testing.assert_allclose(mixed.B0, [0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(mixed.A1, ref.A1, atol=1e-12)
    moving = three_positions(P3, ALPHA3, A1=ref.A1, B1=ref.B1)
    np.testing.assert_allclose(np.concatenate([moving.A0, moving.B0]), [5, 0, 0, 0], atol=1e-12)


def test_branch_defect_is_found():
    """Poses 1 and 2 on the open branch of a crank-rocker, pose 3 on the crossed branch: the
    synthesis recovers that same linkage, which cannot go from 1 to 3 without disassembly."""
    Po, to = catalogue_poses([0.3, 1.0], "open")
    Pc, tc = catalogue_poses([2.0], "crossed")
    sol = three_positions(np.vstack([Po, Pc]), np.r_[to, tc], (0.0, 0.0), (3.0, 0.0))
    np.testing.assert_allclose(sol.A1, [np.cos(0.3), np.sin(0.3)], atol=1e-12)
    assert sol.branch_defect and not sol.order_defect and not sol.valid
    assert sol.position_errors[:2].max() < 1e-12 and sol.position_errors[2] > 1.0
    assert "position(s) 3 cannot be reached" in sol.defects[0]
    # open and crossed are the two circuits of a crank-rocker: no motion joins them
    assert sol.circuit_defect and "position(s) 3 lie on the other circuit" in sol.defects[-1]


def test_full_turn_crank_needs_the_right_sense():
    """Crank angles 0, 200, 100 deg: counter-clockwise order is 1, 3, 2, clockwise 1, 2, 3."""
    P, th = catalogue_poses(np.radians([0.0, 200.0, 100.0]))
    sol = three_positions(P, th, (0.0, 0.0), (3.0, 0.0))
    assert sol.valid and sol.direction == -1
    assert sol.grashof.kind == "crank-rocker"
    # the smallest transmission angle on the way, against a dense engine sweep (0 -> -160 deg)
    q = np.radians(np.linspace(0.0, -160.0, 3201))
    mu = kl.kinematics.transmission_angle(kl.analyze(sol.model, q=q))
    assert sol.min_transmission_angle == pytest.approx(mu.min(), abs=1e-4)  # 0.5 deg sweep steps


def test_two_positions_bisector_family():
    fam = two_positions([(0, 0), (1, 1)], [0, 90], A1=(0, -1), B1=(1, -1), degrees=True)
    for s, t in [(-1.0, 0.5), (0.3, 2.0)]:
        sol = fam.solution(s, t)
        for X1, X2, X0 in ((fam.A1, fam.A2, sol.A0), (fam.B1, fam.B2, sol.B0)):
            assert np.linalg.norm(X1 - X0) == pytest.approx(np.linalg.norm(X2 - X0), abs=1e-12)
        dpos, dang = engine_pose_errors(sol.model, sol.q, sol.points, sol.alpha)
        assert dpos.max() < 1e-9 and dang.max() < 1e-9
    # both bisectors pass through the pole
    for o, d in ((fam.A0_origin, fam.A0_direction), (fam.B0_origin, fam.B0_direction)):
        r = fam.pole - o
        assert abs(r[0] * d[1] - r[1] * d[0]) < 1e-12


def test_two_positions_translation_has_parallel_bisectors():
    fam = two_positions([(0, 0), (2, 0)], [0, 0], A1=(0, 1), B1=(1, 1))
    assert fam.pole is None
    np.testing.assert_allclose(abs(fam.A0_direction @ fam.B0_direction), 1.0, atol=1e-15)


def test_fourbar_model_matches_the_catalogue():
    """The same linkage built from points and by the catalogue moves the same way."""
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
                               coupler_point=(1.5, 1.0))
    q = np.linspace(0, 2 * np.pi, 50)
    ref = kl.analyze(fb, q=q)
    s0 = kl.analyze(fb, q=1.0)
    m = fourbar_model(s0.position("O2"), s0.position("O4"), s0.position("A"), s0.position("B"),
                      s0.position("P"))
    got = kl.analyze(m, q=q)
    for name in ("A", "B", "P"):
        np.testing.assert_allclose(got.position(name), ref.position(name), atol=1e-12)
    assert m.parameters["coupler_point"] == pytest.approx((1.5, 1.0), abs=1e-12)
    assert m.parameters["branch"] == "open"


@pytest.mark.parametrize("kwargs, message", [
    (dict(A0=(5, 0), A1=(1, 1), B0=(0, 0)), r"A0, A1: give exactly one of the fixed pivot A0 and the moving pivot A1, got both"),
    (dict(A0=(5, 0)), r"B0, B1: give exactly one .* got neither"),
    (dict(A0=(5, 0), B0=(5, 0)), r"ground: the fixed pivots A0 and B0 coincide at \(5, 0\)"),
    (dict(A0=(5, 0), B0="x"), r"B0: expected a point \(x, y\)"),
])
def test_three_positions_bad_pivots(kwargs, message):
    with pytest.raises(ModelError, match=message):
        three_positions(P3, ALPHA3, **kwargs)


def test_no_finite_pivot_is_an_error():
    # a pure translation along x: every point moves on a line, no circle through its positions
    with pytest.raises(ModelError, match=r"moving pivot \(0, 1\): its positions are collinear"):
        fixed_pivot([(0, 0), (1, 0), (3, 0)], [0, 0, 0], moving=(0, 1))
    # seen from the coupler, a fixed pivot on the line of a pure translation stays collinear
    with pytest.raises(ModelError, match=r"fixed pivot \(0, 5\): it gives no moving pivot"):
        moving_pivot([(0, 0), (1, 0), (3, 0)], [0, 0, 0], fixed=(0, 5))


def test_three_positions_wants_three():
    with pytest.raises(ModelError, match=r"points: expected three positions, got 4; use four_positions"):
        three_positions(np.zeros((4, 2)) + np.arange(4)[:, None], [0, 1, 2, 3], (0, 0), (1, 1))


def test_a_limit_position_narrower_than_the_sweep_step_is_found():
    """Crank 1, ground 3, coupler 2.5, rocker 1.499999: the loop cannot close for a crank angle
    within 0.094 deg of 180 deg (crank pin 4 from O4, coupler + rocker 3.999999), a gap
    narrower than the sweep's 0.5 deg steps.  The crank angles 1.9, pi - 0.01 and -2 rad are
    then met in order only through that gap: an order defect."""
    from kinelab.synthesis._motion import motion_solution
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=2.5, rocker=1.499999,
                               coupler_point=(1.5, 1.0))
    s = kl.analyze(fb, q=np.array([1.9, np.pi - 0.01, -2.0]))
    sol = motion_solution(Positions(s.position("P"), s.angle("coupler")), (0, 0), (3, 0),
                          s.position("A")[0], s.position("B")[0])
    assert sol.order_defect and not sol.branch_defect
    assert sol.position_errors.max() < 1e-12


@given(three_poses(), st.tuples(coord, coord), st.tuples(coord, coord))
def test_every_three_position_linkage_is_checked_by_the_engine(pos, A0, B0):
    """Random tasks and fixed pivots: the synthesized model, moved by the engine, puts the
    coupler on every pose unless its checks report a branch defect; it is valid when it has
    no defect and its transmission angle, the engine's over the travel, keeps the 30 deg limit."""
    try:
        sol = three_positions(pos, A0=A0, B0=B0)
    except ModelError:              # a pivot at infinity, two pivots in one place, a dead centre
        assume(False)
    assume(max(np.abs(sol.A1).max(), np.abs(sol.B1).max()) < 1e2)
    assert sol.valid == (not sol.branch_defect and not sol.order_defect
                         and not sol.circuit_defect and sol.meets_transmission_limit)
    if not (sol.branch_defect or sol.order_defect):
        mu = travel_transmission(sol)
        assert sol.min_transmission_angle - 1e-12 <= mu <= sol.min_transmission_angle + 1e-6
        assert sol.meets_transmission_limit == (sol.min_transmission_angle >= np.radians(30) - 1e-9)
    if not sol.branch_defect:
        dpos, dang = engine_pose_errors(sol.model, sol.q, pos.points, pos.alpha)
        # 1e-9 relative to the linkage: the pivots solve 2 x 2 systems of this conditioning
        assert dpos.max() < 1e-9 * (1.0 + max(sol.lengths.values())) and dang.max() < 1e-9
