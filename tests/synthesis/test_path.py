"""Path generation: the closed-form coupler curves against the engine, and the search."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import coupler_curves, fourbar_model, path_generation
from kinelab.synthesis._path import _Objective, _timed_points

CATALOGUE = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
                                  coupler_point=(1.5, 1.0))
EXACT_TASK = kl.analyze(CATALOGUE, q=np.radians([0, 40, 80, 120, 160, 200])).position("P")


@pytest.mark.parametrize("seed", range(6))
def test_coupler_curves_against_the_engine(seed):
    rng = np.random.default_rng(seed)
    q = np.linspace(0, 2 * np.pi, 721)
    while True:     # draw random linkages until one closes somewhere (deterministic per seed)
        design = np.r_[rng.uniform(-1, 1, 4), rng.uniform(0.3, 2.5, 3), rng.uniform(-1, 1, 2),
                       rng.choice([-1.0, 1.0])]
        P, A, B, ok = coupler_curves(design[None, :], q)
        if ok.any():
            break
    i = int(np.flatnonzero(ok[0])[len(np.flatnonzero(ok[0])) // 2])
    model = fourbar_model(design[0:2], design[2:4], A[0, i], B[0, i], P[0, i])
    sol = kl.analyze(model, q=q, unreachable="mask", at_singular="flag")
    # the closed form's branch is the engine's (both read it off the sketch at sample i)
    both = ok[0] & sol.assembled
    assert both.sum() >= 0.9 * ok[0].sum()            # they differ only at the limit samples
    for name, X in (("P", P), ("A", A), ("B", B)):
        np.testing.assert_allclose(sol.position(name)[both], X[0][both], atol=1e-10)
    assert model.parameters["coupler_point"] == pytest.approx(tuple(design[7:9]), abs=1e-12)


def test_objective_is_zero_on_an_exact_design_and_penalises_the_wrong_order():
    center, scale = EXACT_TASK.mean(0), 1.0
    obj = _Objective((EXACT_TASK - center) / scale, 360, 0.0)
    design = np.array([0 - center[0], 0 - center[1], 3 - center[0], 0 - center[1],
                       1.0, 3.0, 2.5, 1.5, 1.0, 1.0])
    assert obj(design[:, None])[0] < 1e-5        # second-order sampling error, 1 deg steps
    shuffled = _Objective(obj.T[[0, 2, 1, 3, 4, 5]], 360, 0.0)
    assert shuffled(design[:, None])[0] >= 1.0   # out of order: infeasible


def test_path_generation_finds_an_exact_linkage():
    sols = path_generation(EXACT_TASK, runs=1, maxiter=60, seed=0)
    assert len(sols) == 1 and sols.reason == ""
    best = sols[0]
    assert best.valid and not best.branch_defect and not best.order_defect
    assert best.max_error < 1e-6
    # the engine, moved to the reported crank angles, puts P on the targets
    P = kl.analyze(best.model, q=best.q).position("P")
    np.testing.assert_allclose(np.linalg.norm(P - EXACT_TASK, axis=1), best.errors, atol=1e-12)


@pytest.mark.parametrize("sigma", [1.0, -1.0])
def test_timed_points_against_coupler_curves_and_finite_differences(sigma):
    rng = np.random.default_rng(7)
    T = rng.normal(size=(5, 2))
    z = np.r_[0.0, 0.0, 3.0, 0.0, 1.0, 3.0, 2.5, 1.5, 1.0, rng.uniform(0, 2 * np.pi, 5)]
    R, ok, J = _timed_points(T, z[None, :], np.array([sigma]))
    P = coupler_curves(np.r_[z[:9], sigma][None, :], z[None, 9:])[0]
    assert ok.all()
    np.testing.assert_allclose(R[0].reshape(5, 2), P[0] - T, atol=1e-14)
    # central differences, error ~ h**2 times third derivatives of order one
    h = 1e-6
    E = h * np.eye(z.size)
    plus = _timed_points(T, z + E, np.full(z.size, sigma))[0]
    minus = _timed_points(T, z - E, np.full(z.size, sigma))[0]
    np.testing.assert_allclose(J[0], ((plus - minus) / (2 * h)).T, atol=1e-8)


def _traced_task(d, q):
    """Targets traced by the coupler point of design d at crank angles q (exact task)."""
    return coupler_curves(np.asarray(d, float)[None, :], np.asarray(q, float)[None, :])[0][0]


# Each task with the transmission angle its own linkage keeps over the travel (the engine's,
# swept at 2001 samples: 41.4, 12.8 and 46.0 deg): the second goes below the default limit of
# 30 deg near its limit positions, so its search is asked for 10 deg.
TEN_POINT_TASKS = [
    # the catalogue crank-rocker over 270 deg
    (_traced_task([0, 0, 3, 0, 1.0, 3.0, 2.5, 1.5, 1.0, 1.0], np.radians(np.linspace(0, 270, 10))),
     np.radians(30)),
    # crossed, the crank stopped by limit positions near 9 and 39 deg: 290 deg of travel
    (_traced_task([0.2, -0.1, 1.1, 0.3, 0.8, 1.3, 1.6, -0.4, 0.7, -1.0],
                  np.radians(np.linspace(50, 340, 10))), np.radians(10)),
    # a small crank, a long coupler, P behind A, over 200 deg
    (_traced_task([-0.5, 0.4, 1.5, -0.2, 0.5, 2.2, 1.4, -0.6, -0.5, 1.0],
                  np.radians(np.linspace(-30, 170, 10))), np.radians(30)),
]


@pytest.mark.parametrize("k", range(len(TEN_POINT_TASKS)))
def test_ten_point_tasks_reach_the_tolerance(k):
    T, limit = TEN_POINT_TASKS[k]
    size = np.hypot(*np.ptp(T, axis=0))
    for seed in (0, 1):
        sols = path_generation(T, runs=1, seed=seed, tolerance=1e-3, min_transmission_angle=limit)
        best = sols[0]
        assert best.valid
        # the engine, moved to the reported crank angles, puts P within 1e-3 of the size
        P = kl.analyze(best.model, q=best.q).position("P")
        errors = np.linalg.norm(P - T, axis=1)
        np.testing.assert_allclose(errors, best.errors, atol=1e-12)
        assert np.sqrt(np.mean(errors ** 2)) < 1e-3 * size


def test_initial_designs_are_started_from():
    # a task far outside the search box (pivots 40 sizes away): found in one round only
    # because the round starts from the given design, slightly off
    design = np.array([0, 0, 3, 0, 1.0, 3.0, 2.5, 1.5, 1.0, 1.0])
    far = design.copy()
    far[0:4] += 100.0
    T = _traced_task(far, np.radians(np.linspace(0, 90, 6)))
    near = far + np.r_[[0.01] * 9, 0.0]
    sols = path_generation(T, runs=1, maxiter=1, initial=[near], tolerance=1e-9)
    assert sols and sols[0].valid and sols[0].rms_error < 1e-9


def test_path_generation_is_reproducible():
    a = path_generation(EXACT_TASK[:5], runs=1, maxiter=15, seed=3, refine=False)
    b = path_generation(EXACT_TASK[:5], runs=1, maxiter=15, seed=3, refine=False)
    assert len(a) == len(b)
    for s, t in zip(a, b):
        np.testing.assert_array_equal(np.r_[s.A0, s.B0, s.A1, s.B1], np.r_[t.A0, t.B0, t.A1, t.B1])


def test_transmission_angle_bound_is_kept():
    line = np.column_stack([np.linspace(0.0, 1.0, 6), np.zeros(6)])
    sols = path_generation(line, runs=1, maxiter=40, seed=0, min_transmission_angle=np.radians(30))
    for s in sols:
        assert s.valid
        # the refined design keeps 30 deg exactly over the travel; the sweep samples every 0.5 deg
        assert s.min_transmission_angle >= np.radians(30) - 1e-6


@pytest.mark.parametrize("points, kwargs, message", [
    ([(0, 0), (1, 1)], {}, r"points: expected 3 to 30 finite points \(x, y\), got shape \(2, 2\)"),
    (np.ones((31, 2)), {}, r"points: expected 3 to 30 finite points \(x, y\), got shape \(31, 2\)"),
    ([(0, 0), (1, 1), (2, 0)], dict(samples=10_001),
     r"samples: expected a whole number from 24 to 10,000, got 10001"),
    ([(0, 0), (1, 1), (0, 0)], {}, r"points: points 1 and 3 coincide"),
    ([(0, 0), (1, 1), (2, 0)], dict(runs=0), r"runs: expected a whole number from 1 to 1,000, got 0"),
    ([(0, 0), (1, 1), (2, 0)], dict(popsize=2), r"popsize: expected a whole number from 5 to 10,000, got 2"),
    ([(0, 0), (1, 1), (2, 0)], dict(initial=[[0, 0, 1]]),
     r"initial: expected finite designs of shape \(k, 10\), got \[\[0, 0, 1\]\]"),
    ([(0, 0), (1, 1), (2, 0)], dict(tolerance=-1e-3),
     r"tolerance: expected a fraction of the path's size in \[0, 1\), got -0.001"),
    ([(0, 0), (1, 1), (2, 0)], dict(min_transmission_angle=30.0),
     r"min_transmission_angle: expected an angle in \[0, pi/2\) rad, got 30.0"),
])
def test_bad_path_tasks(points, kwargs, message):
    with pytest.raises(ModelError, match=message):
        path_generation(points, **kwargs)


def test_thirty_points_the_most_a_path_takes():
    """30 points (MAX_PATH_POINTS) of the catalogue's coupler curve, over 290 deg of crank:
    the exact linkage is found again (about 3 s of one core)."""
    from kinelab.synthesis._path import MAX_PATH_POINTS
    assert MAX_PATH_POINTS == 30
    pts = kl.analyze(CATALOGUE, q=np.radians(np.linspace(0, 290, 30))).position("P")
    best = path_generation(pts, runs=1, seed=0)[0]
    assert best.valid and best.q.shape == (30,)
    # exact algebra through the engine: the targets lie on the curve
    assert best.max_error < 1e-9
    P = kl.analyze(best.model, q=best.q).position("P")
    np.testing.assert_allclose(np.linalg.norm(P - pts, axis=1), best.errors, atol=1e-12)


def test_many_points_are_refused_before_any_work():
    """8 million points (a 48 MB task file) are refused at once: no n x n array of gaps
    (931 TiB), no search; the same for 5 identical points, by rows."""
    many = np.broadcast_to([1.0, 2.0], (8_000_000, 2))
    with pytest.raises(ModelError, match=r"^points: expected 3 to 30 finite points .* got shape "
                                         r"\(8000000, 2\); a path is given by 5 to 20 points"):
        path_generation(many)
    with pytest.raises(ModelError, match=r"^points: points 1 and 2 coincide; give distinct points$"):
        path_generation(np.broadcast_to([1.0, 2.0], (5, 2)))
    with pytest.raises(ModelError, match=r"^points: points 2 and 5 coincide"):
        path_generation([(0, 0), (1, 0), (2, 1), (3, 0), (1, 1e-13)])


# -- the crank angles and the transmission angle reported, against the engine ----------------
FOURBAR_DESIGN = np.array([0, 0, 3, 0, 1.0, 3.0, 2.5, 1.5, 1.0, 1.0])   # the catalogue's


def _engine_travel(s, samples=20001):
    """The engine swept from the first reported crank angle to the last (the reported sense):
    whether it closes everywhere and the smallest transmission angle met."""
    q = np.linspace(s.q[0], s.q[-1], samples)
    sol = kl.analyze(s.model, q=q, unreachable="mask", at_singular="flag")
    return bool(sol.assembled.all()), float(np.min(kl.kinematics.transmission_angle(sol)))


def test_crank_angles_given_whole_turns_apart_are_met_within_one_turn():
    from kinelab.synthesis._path import _solution
    q = np.radians(np.linspace(0, 270, 10))
    T = _traced_task(FOURBAR_DESIGN, q)
    extra = q - 0.7 + np.r_[0.0, np.full(9, 2 * np.pi)]     # a whole turn after the first
    s = _solution(T, FOURBAR_DESIGN, extra + 0.7)
    assert s.valid and s.direction == 1
    np.testing.assert_allclose(s.q, q, atol=1e-12)
    s = _solution(T, FOURBAR_DESIGN, q + 4 * np.pi)            # two turns on, all of them
    np.testing.assert_allclose(s.q, q, atol=1e-12)


def test_a_transmission_angle_below_the_bound_is_a_defect():
    from kinelab.synthesis._path import _solution
    q = np.radians(np.linspace(0, 270, 10))
    T = _traced_task(FOURBAR_DESIGN, q)
    free = _solution(T, FOURBAR_DESIGN, q.copy())
    closes, engine_min = _engine_travel(free)
    assert free.valid and closes
    assert free.min_transmission_angle == pytest.approx(engine_min, abs=1e-6)
    assert free.transmission_limit == np.radians(30) and free.meets_transmission_limit
    low = _solution(T, FOURBAR_DESIGN, q.copy(), free.min_transmission_angle + 0.01)
    assert not low.valid and not low.branch_defect and not low.order_defect
    assert not low.meets_transmission_limit and low.state == "transmission angle defect"
    shown = f"{np.degrees(engine_min):.4g} deg"         # the engine's, as the defect says it
    limit = f"{np.degrees(free.min_transmission_angle + 0.01):.4g} deg"
    assert low.defects == (f"transmission angle defect: the transmission angle drops to {shown} "
                           f"between the first target and the last, below the limit of {limit} "
                           "(min_transmission_angle): the coupler pushes the rocker too nearly "
                           "along it; choose another linkage, or lower the limit",)
    ok = _solution(T, FOURBAR_DESIGN, q.copy(), free.min_transmission_angle - 0.01)
    assert ok.valid


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("mu", [0.5, 1.0, 1.5])
def test_path_solutions_against_the_engine(seed, mu):
    """Every linkage returned: crank angles met in order within one turn, the engine closing
    all the way with the transmission angle reported, and at least the bound asked for."""
    T = kl.analyze(CATALOGUE, q=np.radians(np.linspace(0, 270, 10))).position("P")
    sols = path_generation(T, runs=1, maxiter=2, seed=seed, min_transmission_angle=mu)
    assert len(sols) == 1 or "with a transmission angle of at least" in sols.reason
    for s in sols:
        assert s.valid and s.direction in (1, -1)
        assert -np.pi < s.q[0] <= np.pi
        steps = s.direction * np.diff(s.q)
        assert np.all(steps >= 0) and steps.sum() < 2 * np.pi
        closes, engine_min = _engine_travel(s)
        assert closes
        assert s.min_transmission_angle >= mu - 1e-9
        # the reported minimum is exact; the sweep's samples can only miss it from above
        assert engine_min >= s.min_transmission_angle - 1e-12
        assert engine_min <= s.min_transmission_angle + 1e-6
        P = kl.analyze(s.model, q=s.q).position("P")
        np.testing.assert_allclose(np.linalg.norm(P - T, axis=1), s.errors, atol=1e-12)
