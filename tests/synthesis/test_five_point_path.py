"""Five path points with both fixed pivots given: the complete solution set by homotopy
continuation (Morgan and Wampler, 1990: 36 solutions)."""
import functools

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import five_point_path, fourbar_model

SEEDS = (0, 1, 2)


def random_task(seed):
    rng = np.random.default_rng(seed)
    return rng.normal(size=(5, 2)), rng.normal(size=(2, 2))


@functools.lru_cache(maxsize=None)
def solved(seed):
    points, pivots = random_task(seed)
    return five_point_path(points, pivots=(pivots[0], pivots[1]))


def loop_residuals(points, A0, B0, roots):
    """The crank's and the rocker's length kept from the first point to each other one,
    written out again here from the roots (x, xb, y, yb, Q, Qb), in isotropic form, and
    the unit rotations: relative residuals (k, 12)."""
    p = points @ np.array([1.0, 1j])
    out = []
    for s in roots:
        x, xb, y, yb, Q, Qb = s[0], s[1], s[2], s[3], s[4:8], s[8:12]
        rows = []
        for X, Xb, pivot in ((x, xb, A0), (y, yb, B0)):
            a = p - complex(*pivot)
            first = (a[0] + X) * (a[0].conjugate() + Xb)
            moved = (a[1:] + Q * X) * (a[1:].conjugate() + Qb * Xb)
            size = np.abs(a[1:] + Q * X) * np.abs(a[1:].conjugate() + Qb * Xb) + abs(first)
            rows.append(np.abs(moved - first) / size)
        rows.append(np.abs(Q * Qb - 1.0))
        out.append(np.concatenate(rows))
    return np.array(out)


@pytest.mark.parametrize("seed", SEEDS)
def test_36_distinct_finite_solutions_on_random_data(seed):
    sols = solved(seed)
    assert len(sols) == 36
    assert sols.paths == 96 and sols.failed == 0
    # every other path end is accounted for: 96 = 36 + those left out, by reason
    assert len(sols) + sum(sols.discarded.values()) == 96
    # distinct: no two roots within 1e-6 of each other
    x = sols.roots[:, :4]
    d = np.linalg.norm(x[:, None] - x[None], axis=-1) + np.eye(len(x)) * 1e9
    assert d.min() > 1e-6 * np.abs(x).max()


@pytest.mark.parametrize("seed", SEEDS)
def test_every_solution_satisfies_the_loop_equations(seed):
    points, pivots = random_task(seed)
    sols = solved(seed)
    res = loop_residuals(points, pivots[0], pivots[1], sols.roots)
    assert res.max() < 1e-10
    assert sols.residuals.max() < 1e-10


def mirrored(model):
    """The same linkage sketched on its other assembly branch: B reflected across the
    line from A to O4, P carried with the coupler."""
    O2, A, B, O4, P = (np.array(model.point(n).xy) for n in ("O2", "A", "B", "O4", "P"))
    d = (O4 - A) / np.linalg.norm(O4 - A)
    Bm = A + 2 * ((B - A) @ d) * d - (B - A)
    e, em = (B - A) / np.linalg.norm(B - A), (Bm - A) / np.linalg.norm(Bm - A)
    r = P - A
    u, v = r @ e, e[0] * r[1] - e[1] * r[0]
    Pm = A + u * em + v * np.array([-em[1], em[0]])
    return fourbar_model(O2, O4, A, Bm, Pm)


@pytest.mark.parametrize("seed", SEEDS)
def test_real_solutions_reach_the_five_points_in_the_engine(seed):
    points, pivots = random_task(seed)
    sols = solved(seed)
    assert len(sols.real) >= 1
    real_roots = np.sum((np.abs(sols.roots[:, 1] - sols.roots[:, 0].conj()) < 1e-8)
                        & (np.abs(sols.roots[:, 3] - sols.roots[:, 2].conj()) < 1e-8))
    assert len(sols.real) == real_roots
    size = np.ptp(np.vstack([points, pivots]), axis=0).max()
    for s in sols.real:
        np.testing.assert_allclose(s.model.point("O2").xy, pivots[0], atol=1e-12)
        np.testing.assert_allclose(s.model.point("O4").xy, pivots[1], atol=1e-12)
        scale = max(size, max(s.lengths.values()))
        P = [kl.analyze(m, q=s.q, unreachable="mask", at_singular="flag").position("P")
             for m in (s.model, mirrored(s.model))]
        err = np.minimum(*(np.linalg.norm(Pm - points, axis=1) for Pm in P))
        assert np.nan_to_num(err, nan=np.inf).max() < 1e-8 * scale
        # the engine on the sketch's branch reaches every point no branch defect names
        if not s.branch_defect:
            assert s.errors.max() < 1e-8 * scale


def test_the_generating_linkage_is_found_free_of_defects():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
                               coupler_point=(1.5, 1.0))
    pts = kl.analyze(fb, q=np.radians([0, 60, 120, 180, 240])).position("P")
    sols = five_point_path(pts, pivots=((0, 0), (3, 0)))
    assert len(sols) == 36
    mine = [s for s in sols.real if abs(s.lengths["crank"] - 1) < 1e-9
            and abs(s.lengths["coupler"] - 3) < 1e-9 and abs(s.lengths["rocker"] - 2.5) < 1e-9]
    assert len(mine) == 1
    s = mine[0]
    assert s.valid and s.grashof.kind == "crank-rocker" and s.direction == 1
    np.testing.assert_allclose(s.coupler_point, (1.5, 1.0), atol=1e-9)
    np.testing.assert_allclose(s.q, np.radians([0, 60, 120, 180, -120]), atol=1e-9)
    # valid linkages are listed first, by their smallest transmission angle
    assert sols.real[0].valid
    mus = [t.min_transmission_angle for t in sols.real if t.valid]
    assert mus == sorted(mus, reverse=True)
    assert "36 solutions" in repr(sols) and " s)" in repr(sols)


@pytest.mark.parametrize("order_by", ["size", "grashof"])
def test_order_by(order_by):
    points, pivots = random_task(1)
    sols = five_point_path(points, pivots=(pivots[0], pivots[1]), order_by=order_by)
    valid = [s.valid for s in sols.real]
    assert valid == sorted(valid, reverse=True)
    if order_by == "size":
        for group in (True, False):
            sizes = [s.size for s in sols.real if s.valid == group]
            assert sizes == sorted(sizes)


def test_invariant_under_moving_rotating_and_scaling_the_task():
    points, pivots = random_task(4)
    base = five_point_path(points, pivots=(pivots[0], pivots[1]))
    c, s_ = np.cos(0.7), np.sin(0.7)
    R = np.array([[c, -s_], [s_, c]])
    for k, shift in ((1e-3, (5.0, -2.0)), (1e3, (-4e3, 1e3))):
        pts = k * points @ R.T + shift
        piv = k * pivots @ R.T + shift
        moved = five_point_path(pts, pivots=(piv[0], piv[1]))
        assert len(moved) == len(base) == 36
        assert len(moved.real) == len(base.real)
        for key in ("crank", "coupler", "rocker"):
            np.testing.assert_allclose(sorted(s.lengths[key] for s in moved.real),
                                       sorted(k * s.lengths[key] for s in base.real),
                                       rtol=1e-7)
        # the rotations of the coupler do not change at all
        np.testing.assert_allclose(np.sort_complex(moved.roots[:, 4]),
                                   np.sort_complex(base.roots[:, 4]), atol=1e-7)


PTS = [(0.0, 0.0), (1.0, 0.2), (2.0, 1.0), (1.5, 2.0), (0.3, 1.5)]


@pytest.mark.parametrize("points, pivots, message", [
    (PTS[:4], ((3, 0), (-1, 0)), r"points: expected five points \(x, y\), shape \(5, 2\), got "
                                 r"shape \(4, 2\)"),
    ([1, 2, 3], ((3, 0), (-1, 0)), r"points: expected points \(x, y\)"),
    ([(0, 0), (1, 1), (2, 2), (3, 3), (4, 4)], ((3, 0), (-1, 0)), r"points: the five points "
                                                                   r"lie on one line"),
    (PTS[:4] + [PTS[1]], ((3, 0), (-1, 0)), r"points: points 2 and 5 coincide"),
    (PTS[:4] + [(np.nan, 1.0)], ((3, 0), (-1, 0)), r"points\[4\]: expected coordinates of "
                                                   r"finite numbers"),
    (PTS, ((2.0, 1.0), (-1, 0)), r"pivots: A0 is at point 3 .*; move A0 off the path points"),
    (PTS, ((3, 0), (3, 0)), r"pivots: A0 and B0 coincide"),
    (PTS, ((3, 0),), r"pivots: expected the two fixed pivots \(A0, B0\)"),
    (PTS, ((3, 0), (np.inf, 0)), r"pivots\[1\] \(B0\)"),
    (PTS, ((3, 0, 1), (1, 0)), r"pivots\[0\] \(A0\): expected a point \(x, y\)"),
])
def test_bad_input(points, pivots, message):
    with pytest.raises(ModelError, match=message) as info:
        five_point_path(points, pivots=pivots)
    assert "\n" not in str(info.value)
    assert isinstance(info.value, ValueError)


def test_bad_order_by():
    with pytest.raises(ModelError, match=r"order_by: expected one of 'transmission', 'size', "
                                         r"'grashof', got 'speed'"):
        five_point_path(PTS, pivots=((3, 0), (-1, 0)), order_by="speed")


def test_the_tracker_on_a_small_system():
    """Two conics, four roots, found by the generic kernel from a one-group start system."""
    from kinelab.solvers._homotopy import multihomogeneous_start, refine, track, with_rows

    def F(z):
        z0, x, y = z.T
        v = np.stack([x * x + y * y - 4 * z0 * z0, x * y - z0 * z0], 1)
        J = np.zeros((len(z), 2, 3), complex)
        J[:, 0] = np.stack([-8 * z0, 2 * x, 2 * y], 1)
        J[:, 1] = np.stack([-2 * z0, y, x], 1)
        return v, J

    rng = np.random.default_rng(0)
    start, patch, roots = multihomogeneous_start([[0, 1, 2]], np.array([[2], [2]]), rng)
    assert roots.shape == (4, 3)
    target = with_rows(F, patch)
    r = track(target, start, roots, gamma=np.exp(1j))
    assert r.converged.all()
    z, _, _ = refine(target, r.z)
    x = np.sort((z[:, 1] / z[:, 0]).real)
    # x^2 + 1/x^2 = 4: x^2 = 2 -+ sqrt(3)
    r1, r2 = np.sqrt(2 - np.sqrt(3)), np.sqrt(2 + np.sqrt(3))
    np.testing.assert_allclose(x, [-r2, -r1, r1, r2], atol=1e-12)


@pytest.mark.parametrize("lost_runs, calls_seen, retried", [
    (1, [96, 10], 10),               # the retry with shorter steps finds them
    (2, [96, 10, 96], 10 + 96 + 0),  # ... it does not: a whole new run with a new gamma
])
def test_paths_that_stall_are_tracked_again(monkeypatch, lost_runs, calls_seen, retried):
    """The first calls lose ten paths half-way (as a near-crossing would); they are followed
    again, and no root is missing."""
    import dataclasses

    from kinelab.synthesis import _five_point_path as module

    real_track = module.track
    calls = []

    def flaky(target, start, starts, *, gamma, **options):
        r = real_track(target, start, starts, gamma=gamma, **options)
        calls.append((len(starts), gamma))
        if len(calls) > lost_runs:
            return r
        status, t, z = r.status.copy(), r.t.copy(), r.z.copy()
        status[:10], t[:10], z[:10] = 1, 0.5, np.nan
        return dataclasses.replace(r, status=status, t=t, z=z)

    monkeypatch.setattr(module, "track", flaky)
    points, pivots = random_task(0)
    sols = five_point_path(points, pivots=(pivots[0], pivots[1]))
    assert [n for n, _ in calls] == calls_seen
    assert calls[1][1] == calls[0][1]              # the same homotopy, shorter steps
    if lost_runs == 2:
        assert calls[2][1] != calls[0][1]          # a new gamma
    assert sols.retried == retried and sols.failed == 0 and len(sols) == 36
