"""Five positions: Burmester's points and every four-bar through them."""
import numpy as np
import pytest
from scipy.optimize import fsolve

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import Positions, burmester_points, five_positions
from tests.synthesis.helpers import catalogue_poses, crank_lengths, engine_pose_errors, wrap

Q5 = np.radians([0.0, 30.0, 60.0, 90.0, 120.0])


def test_a_four_bar_is_found_again_through_five_of_its_poses():
    P, th = catalogue_poses(Q5)
    sols = five_positions(P, th)
    mine = min(sols, key=lambda s: np.linalg.norm(np.r_[s.A0, s.B0] - [0, 0, 3, 0]))
    np.testing.assert_allclose(np.r_[mine.A0, mine.B0, mine.A1], [0, 0, 3, 0, 1, 0], atol=1e-9)
    assert mine.valid and mine.grashof.kind == "crank-rocker"
    dpos, dang = engine_pose_errors(mine.model, mine.q, P, th)
    assert dpos.max() < 1e-9 and dang.max() < 1e-9


def random_tasks(n, seed):
    rng = np.random.default_rng(seed)
    return [(rng.normal(size=(5, 2)), rng.normal(size=5)) for _ in range(n)]


@pytest.mark.parametrize("points, angles", random_tasks(12, 3))
def test_every_linkage_passes_through_the_five_poses(points, angles):
    pos = Positions(points, angles)
    centers, circles = burmester_points(pos)
    assert centers.shape[0] in (0, 2, 4)
    for A0, A1 in zip(centers, circles):
        r = crank_lengths(pos, A0, A1)
        assert np.ptp(r) <= 1e-9 * r.max()                 # A_1..A_5 on one circle about A0
    sols = five_positions(pos)
    k = centers.shape[0]
    assert len(sols) == k * (k - 1) // 2
    assert (len(sols) == 0) == bool(sols.reason)
    for s in sols:
        assert {tuple(s.A0), tuple(s.B0)} <= {tuple(c) for c in centers}
        # the shorter dyad drives
        assert np.linalg.norm(s.A1 - s.A0) <= np.linalg.norm(s.B1 - s.B0)
        L = [np.linalg.norm(s.B0 - s.A0), np.linalg.norm(s.A1 - s.A0),
             np.linalg.norm(s.B1 - s.A1), np.linalg.norm(s.B1 - s.B0)]
        assert s.grashof.kind == kl.mechanisms.grashof(*L).kind
        assert np.abs(s.dyad_residuals).max() < 1e-9 * max(L)
        if not s.branch_defect:
            dpos, dang = engine_pose_errors(s.model, s.q, points, angles)
            assert dpos.max() < 1e-9 * max(L) and dang.max() < 1e-9


def crank_rows(points, angles, A0):
    """Rows [a, b, c] of |A_j - A0|^2 = |A_1 - A0|^2 (j = 2..5), linear in w = A1 - P1:
    [2 R_j^T (P_j - A0) - 2 (P_1 - A0)] . w = |P_1 - A0|^2 - |P_j - A0|^2 (derived here
    again; A0 of shape (..., 2) gives (..., 4, 3))."""
    a = angles[1:] - angles[0]
    c, s = np.cos(a), np.sin(a)
    p = points[1:] - A0[..., None, :]                    # P_j - A0
    p1 = points[0] - A0[..., None, :]
    RtP = np.stack([c * p[..., 0] + s * p[..., 1], -s * p[..., 0] + c * p[..., 1]], -1)
    lhs = 2 * RtP - 2 * p1
    rhs = np.sum(p1 * p1, -1) - np.sum(p * p, -1)
    return np.concatenate([lhs, rhs[..., None]], -1)


@pytest.mark.parametrize("points, angles", random_tasks(6, 11))
def test_no_burmester_point_is_missed(points, angles):
    """A brute-force search: on a 500 x 500 grid six task sizes around the task, the cells
    where both determinants (rows 2, 3, 4 and rows 2, 3, 5) change sign are polished by
    fsolve; those where all four rows agree (not the poles P12, P13, P23, where the
    determinants vanish too) are Burmester points, and each must be one of ours."""
    centers, _ = burmester_points(points, angles)
    mid, size = points.mean(axis=0), np.ptp(points, axis=0).max()
    g = np.linspace(-6, 6, 501) * size
    X = mid + np.stack(np.meshgrid(g, g, indexing="ij"), -1)
    rows = crank_rows(points, angles, X)
    dets = [np.linalg.det(rows[..., sel, :]) for sel in ([0, 1, 2], [0, 1, 3])]

    def changes(d):
        corners = np.stack([d[:-1, :-1], d[1:, :-1], d[:-1, 1:], d[1:, 1:]])
        return (np.sign(corners).min(0) < 0) & (np.sign(corners).max(0) > 0)
    cells = np.argwhere(changes(dets[0]) & changes(dets[1]))

    def equations(z):
        r = crank_rows(points, angles, z)
        n = np.linalg.norm(r, axis=1).max() ** 3
        return [np.linalg.det(r[[0, 1, 2]]) / n, np.linalg.det(r[[0, 1, 3]]) / n]
    found = 0
    for i, j in cells:
        z, _, ok, _ = fsolve(equations, X[i, j] + 0.5 * (g[1] - g[0]), full_output=True,
                             xtol=1e-14)
        r = crank_rows(points, angles, z)
        sv = np.linalg.svd(r, compute_uv=False)
        if ok != 1 or sv[2] > 1e-9 * sv[0]:
            continue                        # a pole, or no convergence
        found += 1
        assert np.linalg.norm(centers - z, axis=1).min() < 1e-7 * (1 + np.abs(z).max())
    inside = np.all(np.abs(centers - mid) < 6 * size, axis=1).sum()
    assert found >= inside          # every point of ours in the box is seen by the grid too


def test_circuit_defect():
    """Four poses on the open circuit of a crank-rocker and one on the crossed circuit: the
    linkage itself is found, with a circuit defect, and the engine, turning the crank a full
    turn from pose 1, never brings the coupler to pose 5."""
    P, th = catalogue_poses(Q5[:4])
    Pc, tc = catalogue_poses(Q5[4:], "crossed")
    P, th = np.vstack([P, Pc]), np.r_[th, tc]
    mine = min(five_positions(P, th), key=lambda s: np.linalg.norm(np.r_[s.A0, s.B0] - [0, 0, 3, 0]))
    assert np.linalg.norm(np.r_[mine.A0, mine.B0] - [0, 0, 3, 0]) < 1e-9
    assert mine.circuit_defect and mine.branch_defect and not mine.valid
    assert any(d.startswith("circuit defect: position(s) 5 lie on the other circuit")
               for d in mine.defects)
    sweep = kl.analyze(mine.model, q=mine.q[0] + np.linspace(0, 2 * np.pi, 3601))
    miss = np.linalg.norm(sweep.position("P") - P[4], axis=1) + np.abs(
        wrap(sweep.angle("coupler") - sweep.angle("coupler")[0] - (th[4] - th[0])))
    assert miss.min() > 0.1


def test_fewer_than_two_burmester_points():
    for points, angles in random_tasks(40, 5):
        if burmester_points(points, angles)[0].shape[0] == 0:
            sols = five_positions(points, angles)
            assert len(sols) == 0
            assert sols.reason.startswith("no real Burmester point")
            break
    else:
        pytest.fail("no task without a real Burmester point among 40 random ones")


@pytest.mark.parametrize("n, message", [
    (4, r"points: expected five positions, got 4; use four_positions"),
    (6, r"points: expected five positions, got 6; use approximate_positions"),
])
def test_five_positions_wrong_count(n, message):
    P, th = catalogue_poses(np.linspace(0, 2, n))
    with pytest.raises(ModelError, match=message):
        five_positions(P, th)


def test_five_positions_bad_values():
    P, th = catalogue_poses(Q5)
    P[3, 1] = np.nan
    with pytest.raises(ModelError, match=r"points\[3\]: expected two finite numbers \(x, y\), got "
                                         r"\[-?[\d.]+, nan\]"):
        five_positions(P, th)
    P, th = catalogue_poses(Q5[[0, 1, 2, 1, 3]])
    with pytest.raises(ModelError, match=r"positions 2 and 4 coincide"):
        five_positions(P, th)
