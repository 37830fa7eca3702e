"""More positions than exact synthesis allows: least squares over dyads."""
import numpy as np
import pytest

from kinelab.errors import ModelError
from kinelab.synthesis import (Positions, approximate_positions, burmester_points, fit_dyads)
from tests.synthesis.helpers import catalogue_poses, crank_lengths, engine_pose_errors

Q5 = np.radians([0.0, 30.0, 60.0, 90.0, 120.0])

Q8 = np.radians(np.arange(0.0, 160.0, 20.0))


def test_eight_poses_of_a_four_bar_give_it_back():
    P, th = catalogue_poses(Q8)
    sols = approximate_positions(P, th)
    best = sols[0]
    np.testing.assert_allclose(np.r_[best.A0, best.B0], [0, 0, 3, 0], atol=1e-9)
    assert best.valid and np.abs(best.dyad_residuals).max() < 1e-9
    dpos, dang = engine_pose_errors(best.model, best.q, P, th)
    assert dpos.max() < 1e-9 and dang.max() < 1e-9


def test_least_squares_residuals_and_optimality():
    """Noisy poses: the reported residuals are the dyads' own, recomputed here; no small
    change of a dyad (fixed pivot, moving pivot, length) lowers its sum of squares."""
    rng = np.random.default_rng(2)
    P, th = catalogue_poses(Q8)
    P = P + rng.normal(scale=0.02, size=P.shape)
    th = th + rng.normal(scale=0.01, size=th.shape)
    pos = Positions(P, th)
    sols = approximate_positions(pos)
    best = sols[0]
    assert best.valid
    crank, rocker = best.model.parameters["crank"], best.model.parameters["rocker"]
    res = np.column_stack([crank_lengths(pos, best.A0, best.A1) - crank,
                           crank_lengths(pos, best.B0, best.B1) - rocker])
    np.testing.assert_allclose(best.dyad_residuals, res, atol=1e-12)
    assert 1e-4 < np.abs(res).max() < 0.1                # noise 0.02: not exact, not far
    # the engine's errors at each pose, recomputed
    dpos, dang = engine_pose_errors(best.model, best.q, P, th)
    np.testing.assert_allclose(best.position_errors, dpos, atol=1e-12)
    assert dpos.max() < 0.2
    # stationarity: a step of 1e-5 along random directions never lowers the sum of squares
    for A0, A1, R in ((best.A0, best.A1, crank), (best.B0, best.B1, rocker)):
        z0 = np.r_[A0, A1, R]

        def ssq(z):
            return np.sum((crank_lengths(pos, z[:2], z[2:4]) - z[4]) ** 2)
        for d in rng.normal(size=(20, 5)):
            step = 1e-5 * d / np.linalg.norm(d)
            assert ssq(z0 + step) >= ssq(z0) - 1e-14
            assert ssq(z0 - step) >= ssq(z0) - 1e-14


def test_fit_dyads_with_five_is_burmester():
    P, th = catalogue_poses(Q5)
    centers, circles, radii, res = fit_dyads(P, th, dyads=4)
    exact, _ = burmester_points(P, th)
    assert np.abs(res[:2]).max() < 1e-9
    for c in centers[:2]:
        assert np.linalg.norm(exact - c, axis=1).min() < 1e-8


@pytest.mark.parametrize("kwargs, message", [
    (dict(n=5), r"points: expected more than five positions, got 5; use five_positions"),
    (dict(n=7, nan=True), r"points\[2\]: expected two finite numbers \(x, y\), got \[nan, "),
    (dict(n=7, dyads=1), r"dyads: expected a whole number from 2 to 100, got 1"),
])
def test_approximate_positions_bad_input(kwargs, message):
    P, th = catalogue_poses(np.linspace(0, 2, kwargs["n"]))
    if kwargs.get("nan"):
        P[2, 0] = np.nan
    with pytest.raises(ModelError, match=message):
        approximate_positions(P, th, **({"dyads": kwargs["dyads"]} if "dyads" in kwargs else {}))


def test_one_dyad_per_circle_point():
    """Poses along a smooth path with small turns: the near-slider dyads lie in flat valleys,
    where polishing stops at slightly different centres; each circle point is one dyad."""
    P = np.array([(0, 0), (5, 8), (10, 15), (18, 20), (25, 22), (30, 21)]) * 0.01
    centers, circles, radii, res = fit_dyads(P, [0, 10, 20, 30, 40, 50], dyads=8, degrees=True)
    gaps = np.linalg.norm(circles[:, None] - circles[None], axis=-1)[np.triu_indices(len(circles), 1)]
    assert gaps.size == 0 or gaps.min() > 1e-3
    rms = np.sqrt(np.mean(res ** 2, axis=1))
    assert np.all(np.diff(rms) >= 0)                    # the best first
    sols = approximate_positions(P, [0, 10, 20, 30, 40, 50], degrees=True)
    assert len(sols) == 0 and sols.reason.startswith("dyads at ")   # the pair cannot assemble
