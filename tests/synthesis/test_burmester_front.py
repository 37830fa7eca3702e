"""kl.synthesis.burmester: every real Burmester dyad pair of five poses, the curves of four."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import BurmesterCurves, Positions, burmester, burmester_curves, five_positions

from .helpers import catalogue_poses, crank_lengths, engine_pose_errors

Q5 = np.radians([0.0, 30.0, 60.0, 90.0, 120.0])


def _tasks():
    P, th = catalogue_poses(Q5)
    rng = np.random.default_rng(11)
    return [(P, th)] + [(rng.normal(size=(5, 2)), rng.normal(size=5)) for _ in range(10)]


@pytest.mark.parametrize("points, angles", _tasks())
def test_as_many_as_five_positions_and_each_reaches_every_pose(points, angles):
    sols = burmester(np.column_stack([points, angles]), all_solutions=True)
    today = five_positions(points, angles)
    assert len(sols) == len(today)
    assert sols.reason == today.reason
    centers, _ = kl.synthesis.burmester_points(points, angles)
    k = centers.shape[0]
    assert len(sols) + sols.reason.count("left out:") == k * (k - 1) // 2
    pos = Positions(points, angles)
    for s, t in zip(sols, today):
        np.testing.assert_array_equal(np.r_[s.A0, s.B0, s.A1, s.B1], np.r_[t.A0, t.B0, t.A1, t.B1])
        # both dyads keep their lengths through the five poses (independent of the solver)
        for X0, X1 in ((s.A0, s.A1), (s.B0, s.B1)):
            r = crank_lengths(pos, X0, X1)
            assert np.ptp(r) <= 1e-9 * r.max()
        # and the engine carries the coupler through them where the linkage can move there
        if not (s.branch_defect or s.circuit_defect):
            dpos, dang = engine_pose_errors(s.model, s.q, points, angles)
            assert dpos.max() < 1e-9 * max(1.0, pos.size) and dang.max() < 1e-9


def test_the_catalogue_linkage_is_among_them():
    P, th = catalogue_poses(Q5)
    sols = burmester(P, th)
    mine = min(sols, key=lambda s: np.linalg.norm(np.r_[s.A0, s.B0] - [0, 0, 3, 0]))
    np.testing.assert_allclose(np.r_[mine.A0, mine.B0], [0, 0, 3, 0], atol=1e-9)
    assert mine.valid


def test_only_the_valid_ones_when_asked():
    for points, angles in _tasks():
        every = burmester(points, angles)
        kept = burmester(points, angles, all_solutions=False)
        assert [s.A0.tolist() for s in kept] == [s.A0.tolist() for s in every if s.valid]
        if len(kept) < len(every):
            assert "left out for their defects" in kept.reason


def test_the_pose_forms_agree():
    P, th = catalogue_poses(Q5)
    a = burmester(np.column_stack([P, np.degrees(th)]), degrees=True)
    b = burmester(Positions(P, th))
    c = burmester(P, th[1:] - th[0])                 # rotations from pose 1
    for x in (b, c):
        assert len(x) == len(a)
        for s, t in zip(x, a):
            np.testing.assert_allclose(s.A0, t.A0, atol=1e-9)


def test_four_poses_give_the_curves():
    P, alpha = [(0, 0), (5, 8), (10, 15), (18, 20)], np.radians([0, 10, 20, 30])
    cur = burmester(np.column_stack([P, alpha]), samples=361)
    ref = burmester_curves(P, alpha, samples=361)
    assert isinstance(cur, BurmesterCurves)
    np.testing.assert_array_equal(cur.center, ref.center)
    np.testing.assert_array_equal(cur.valid, ref.valid)


@pytest.mark.parametrize("args, kwargs, message", [
    ((np.zeros((5, 4)),), {}, r"^poses: expected rows \(x, y, angle\) of shape \(n, 3\), or points "
     r"\(n, 2\) with angles, got shape \(5, 4\)$"),
    (([[0, 0, 0], [1, 0, np.nan], [2, 1, 0], [3, 1, 1], [4, 0, 2]],), {},
     r"^poses\[1\]: expected three finite numbers \(x, y, angle\), got \[1\.0, 0\.0, nan\]$"),
    (([[0, 0, 0], [1, 0, 1], [2, 1, 0]],), {}, r"^poses: expected four or five poses, got 3; use "
     r"three_positions"),
    ((np.arange(18.0).reshape(6, 3),), {}, r"^poses: expected four or five poses, got 6; use "
     r"approximate_positions$"),
    ((np.arange(15.0).reshape(5, 3),), dict(all_solutions="yes"), r"^all_solutions: "),
    (("abc",), {}, r"^poses: expected real numbers"),
])
def test_bad_poses_one_line_naming_the_field(args, kwargs, message):
    with pytest.raises(ModelError, match=message) as info:
        burmester(*args, **kwargs)
    assert "\n" not in str(info.value)
