"""Change points: where two assembly modes of a dyad meet, the sweep goes on along the branch
whose K and L continue.

The checks are independent of the engine's branch logic: loop closure on the output points,
the geometric definition of each branch (a parallelogram's rocker is parallel to its crank,
an antiparallelogram is the *other* solution), K against central differences of the
positions across the change point, and whole-turn counts of the links.
"""
import math
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from tests.kinematics.checks import closure_residual, wrap

TURN = np.radians(np.arange(0.0, 360.5, 1.0))


def unwrapped(sol, link):
    return np.unwrap(sol.angle(link))


def test_parallelogram_rocker_follows_its_crank_over_the_whole_turn():
    fb = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    sol = kl.analyze(fb, q=TURN)
    assert np.max(np.abs(wrap(sol.angle("rocker") - TURN))) < 1e-9
    assert np.max(np.abs(wrap(sol.angle("coupler")))) < 1e-9
    ok = ~sol.singular
    assert np.max(np.abs(sol.K("rocker")[ok] - 1.0)) < 1e-9
    assert np.max(np.abs(sol.L("rocker")[ok])) < 1e-8
    assert closure_residual(sol) < 1e-12


@pytest.mark.parametrize("q", [np.linspace(-7.0, 9.0, 1601), np.array([3.5]), np.array([4.0, 1.0, 6.0])])
def test_parallelogram_at_any_input_and_in_any_order(q):
    """The branch at an input is the continuation from the sketch to it, whatever the
    samples around it: one value past 180 degrees, samples out of order, several turns."""
    fb = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    sol = kl.analyze(fb, q=q, at_singular="flag")
    assert np.max(np.abs(wrap(sol.angle("rocker") - q))) < 1e-9


@pytest.mark.parametrize("ground, crank", [(100, 60), (60, 100)])
def test_antiparallelogram_is_the_other_solution_all_the_way(ground, crank):
    fb = kl.mechanisms.fourbar(ground=ground, crank=crank, coupler=ground, rocker=crank,
                               branch="crossed")
    q = np.linspace(0.0, 4 * math.pi, 1441)
    sol = kl.analyze(fb, q=q)
    A, B = sol.position("A"), sol.position("B")
    parallelogram_B = A + np.array([ground, 0.0])
    apart = np.linalg.norm(B - parallelogram_B, axis=1)
    cps = np.array([c.q for c in sol.change_points])
    away = np.min(np.abs(q[:, None] - cps[None, :]), axis=1) > 0.05
    assert np.all(apart[away] > 1e-3 * ground)
    assert closure_residual(sol) < 1e-9 * ground
    # the short links turn full circle; with the long link fixed, in opposite senses
    turns_crank = (unwrapped(sol, "crank")[-1] - unwrapped(sol, "crank")[0]) / (2 * math.pi)
    turns_rocker = (unwrapped(sol, "rocker")[-1] - unwrapped(sol, "rocker")[0]) / (2 * math.pi)
    assert turns_crank == pytest.approx(2.0, abs=1e-9)
    assert abs(turns_rocker) == pytest.approx(2.0, abs=1e-9)
    if ground > crank:
        assert turns_rocker < 0


def test_parallelogram_reports_its_change_points():
    fb = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    sol = kl.analyze(fb, q=TURN)
    qs = [c.q for c in sol.change_points]
    assert qs == pytest.approx([0.0, math.pi, 2 * math.pi], abs=1e-9)
    assert all(c.links == ("coupler", "rocker") and c.followed == "smooth" for c in sol.change_points)
    assert sol.singular[[0, 180, 360]].all()        # exactly at them: K and L undefined
    assert np.isfinite(sol.position("B")).all()      # positions are defined there


def test_switch_takes_the_other_branch():
    fb = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    q = np.radians(np.arange(91.0, 270.0, 1.0))       # from near the sketch past 180 deg
    smooth = kl.analyze(fb, q=q)
    switch = kl.analyze(fb, q=q, at_change_point="switch")
    before, after = q < math.pi - 1e-6, q > math.pi + 1e-6
    assert np.max(np.abs(wrap(switch.angle("rocker")[before] - q[before]))) < 1e-9
    assert np.min(np.abs(wrap(switch.angle("rocker")[after] - q[after]))) > 1e-2
    assert np.max(np.abs(wrap(smooth.angle("rocker") - q))) < 1e-9
    assert [c.followed for c in switch.change_points] == ["switch"]
    with pytest.raises(ModelError, match="at_change_point: expected one of 'smooth', 'switch'"):
        kl.analyze(fb, q=q, at_change_point="other")


def _finite_difference_K(m, q, link, h=1e-6):
    plus = kl.analyze(m, q=q + h, at_singular="flag").angle(link)
    minus = kl.analyze(m, q=q - h, at_singular="flag").angle(link)
    return wrap(plus - minus) / (2 * h)


@pytest.mark.parametrize("lengths", [(4.0, 2.0, 3.0, 5.0), (1.0, 1.0, 2.0, 2.0), (2.0, 1.0, 1.0, 2.0),
                                     (1.0, 1.0, 1.0, 1.0)])
def test_change_point_fourbars_are_smooth_through_their_change_points(lengths):
    """K continues through every change point: central differences of the positions on
    both sides of it (0.05 rad away, outside the flagged neighbourhood) agree with K there,
    and the angle moves by a small step across it (no jump to the other mode)."""
    fb = kl.mechanisms.fourbar(*lengths)
    sol = kl.analyze(fb, q=np.linspace(-2 * math.pi, 4 * math.pi, 2001))
    assert sol.change_points
    assert closure_residual(sol) < 1e-11 * max(lengths)
    for c in sol.change_points:
        sides = kl.analyze(fb, q=np.array([c.q - 0.05, c.q + 0.05]))
        for link in ("coupler", "rocker"):
            assert sides.K(link) == pytest.approx(_finite_difference_K(fb, sides.q[:, 0], link),
                                                  rel=1e-6, abs=1e-6)
        across = kl.analyze(fb, q=np.array([c.q - 1e-3, c.q + 1e-3]), at_singular="flag")
        for link in ("coupler", "rocker"):
            step = abs(wrap(np.diff(across.angle(link)))[0])
            assert step < 4e-3 * (1 + max(abs(sides.K(link)))), (link, c)


def test_change_point_fourbar_comes_back_after_two_turns():
    fb = kl.mechanisms.fourbar(ground=4.0, crank=2.0, coupler=3.0, rocker=5.0)
    q = np.radians([30.0, 30.0 + 360.0, 30.0 + 720.0])
    B = kl.analyze(fb, q=q).position("B")
    assert np.linalg.norm(B[0] - B[1]) > 0.1           # one turn on: the other mode
    assert np.linalg.norm(B[0] - B[2]) < 1e-12         # two turns on: back


def test_kite_rocker_turns_once_for_two_crank_turns():
    fb = kl.mechanisms.fourbar(ground=1.0, crank=1.0, coupler=2.0, rocker=2.0)
    q = np.linspace(0.0, 4 * math.pi, 2881)
    sol = kl.analyze(fb, q=q)
    turns = (unwrapped(sol, "rocker")[-1] - unwrapped(sol, "rocker")[0]) / (2 * math.pi)
    assert abs(turns) == pytest.approx(1.0, abs=1e-9)
    # where the crank pin passes over the rocker pivot the arms fold: the sample there is
    # singular, and its position is the limit from both sides
    i = np.flatnonzero(np.isclose(q, 2 * math.pi))[0]
    assert sol.singular[i]
    B = sol.position("B")
    assert np.linalg.norm(B[i] - 0.5 * (B[i - 1] + B[i + 1])) < 1e-3


def test_double_parallelogram_checks_and_follows_its_crank(tmp_path):
    text = Path(__file__).with_name("double_parallelogram.toml").read_text()
    path = tmp_path / "dp.toml"
    path.write_text(text)
    m = kl.load(path)
    sol = kl.analyze(m, q=TURN)
    for link in ("rocker", "link5"):
        assert np.max(np.abs(wrap(sol.angle(link) - TURN))) < 1e-9
    with pytest.raises(kl.errors.AssemblyError, match="joint 'jO6' is redundant"):
        kl.analyze(m, q=TURN, at_change_point="switch")     # no antiparallelogram here


def test_slotted_link_whose_crank_pin_passes_the_lever_pivot():
    """crank = distance: the pin goes through O4 at 180 degrees; the lever turns on smoothly
    and the slide changes sign (the lever swings through its pivot's other side)."""
    sl = kl.mechanisms.slotted_link(crank=1.0, distance=1.0)
    q = np.linspace(math.pi - 0.5, math.pi + 0.5, 101)
    sol = kl.analyze(sl, q=q, at_singular="flag")
    # the pin A = O2 + (cos q, sin q) seen from O4: the lever along it, B = |O4A| signed
    A = np.stack([1.0 + np.cos(q), np.sin(q)], axis=1)
    assert np.max(np.abs(sol.position("A") - A)) < 1e-12
    slide = sol.slide("slot")
    assert slide[0] * slide[-1] < 0
    ok = ~sol.singular
    assert np.max(np.abs(np.diff(unwrapped(sol, "lever")[ok]))) < 0.03


def test_no_change_point_no_cost():
    """A crank-rocker has no change point: nothing reported, the sweep as before."""
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    sol = kl.analyze(fb, q=TURN)
    assert sol.change_points == ()
    assert not sol.singular.any()


@pytest.mark.parametrize("lengths, branch", [((100, 60, 100, 60), "open"), ((100, 60, 100, 60), "crossed"),
                                             ((4.0, 2.0, 3.0, 5.0), "open")])
def test_newton_engine_follows_the_same_branch_through_change_points(lengths, branch):
    """The general Newton engine, continuing along the samples, goes through the change
    points on the same branch as the closed forms.  The samples exactly at them, where
    Newton's method cannot converge, are placed from predictions either side (whose K and
    L are near-singular): to about 1e-8 there, against rounding elsewhere."""
    fb = kl.mechanisms.fourbar(*lengths, branch=branch)
    q = np.linspace(0.0, 4 * math.pi, 721)
    a = kl.analyze(fb, q)
    b = kl.analyze(fb, q, method="newton")
    assert b.assembled.all()
    ok = ~a.singular & ~b.singular
    for link in ("coupler", "rocker"):
        d = np.abs(wrap(a.angle(link) - b.angle(link)))
        assert np.max(d[ok]) < 1e-9 and np.max(d) < 1e-7
    assert np.max(np.abs(a.K("rocker")[ok] - b.K("rocker")[ok])) < 1e-8
    assert closure_residual(b) < 1e-9 * max(lengths)


def test_newton_engine_covers_an_arc_that_straddles_the_window():
    """A triple-rocker whose crank reaches [-5.097, -1.186] rad: swept over [-pi, pi] its arc
    shows as two pieces; continuation from the sketch reaches one directly and the other a
    turn away, as the closed forms do."""
    fb = kl.mechanisms.fourbar(2.0, 1.5, 1.0, 3.0)
    q = np.linspace(-math.pi, math.pi, 721)
    a = kl.analyze(fb, q, unreachable="mask")
    b = kl.analyze(fb, q, unreachable="mask", method="newton")
    assert np.array_equal(a.assembled, b.assembled) and a.assembled.sum() == 450
    ok = a.assembled
    assert np.max(np.abs(wrap(a.angle("rocker")[ok] - b.angle("rocker")[ok]))) < 1e-10
