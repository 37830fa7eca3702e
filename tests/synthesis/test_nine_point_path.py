"""Nine-point path synthesis: the formulation against known four-bars, a tracked subset,
the cognate grouping, bad input."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import _nine_point_path as npp


def catalogue_task():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
                               coupler_point=(1.5, 1.0))
    sol = kl.analyze(fb, q=np.radians(np.arange(0, 360, 40)))
    pts = sol.position("P")
    root = npp.fourbar_root(pts, (0.0, 0.0), (3.0, 0.0), sol.position("A")[0],
                            sol.position("B")[0])
    return pts, root


def test_catalogue_fourbar_and_its_cognates_solve_the_equations():
    # exact algebra, evaluated in floating point: rounding only
    pts, root = catalogue_task()
    triple = npp.cognates(root)[0]
    assert npp.equations(pts, triple).max() < 1e-13
    assert npp.loop_residuals(pts, triple).max() < 1e-13
    # the relabelled linkages (dyads swapped) too
    assert npp.equations(pts, npp.relabel(triple)).max() < 1e-13
    # three different linkages on three fixed pivots, each pair used once
    pairs = {frozenset((round(p.real, 9), round(p.imag, 9)) for p in (z[0] - z[2], z[4] - z[6]))
             for z in triple}
    assert len(pairs) == 3 and len(frozenset().union(*pairs)) == 3


def reaches_every_point(pts, z):
    """The linkage of real root z, built by the engine in each of its nine configurations
    (from the rotations of Cramer's rule), is one linkage (same lengths, same coupler
    point) and puts its coupler point on each point, by kl.analyze."""
    P = pts @ np.array([1.0, 1j])
    th, _ = npp._rotations(z[None], P[1:] - P[0], (P[1:] - P[0]).conj())
    th = np.concatenate([[1.0], th[0]])
    A, B = P + th * z[0], P + th * z[4]
    A0, B0 = P[0] + z[0] - z[2], P[0] + z[4] - z[6]
    xy = lambda c: np.array([c.real, c.imag])
    ref, size = None, np.ptp(pts, axis=0).max()
    for j in range(9):
        m = kl.synthesis.fourbar_model(xy(A0), xy(B0), xy(A[j]), xy(B[j]), pts[j])
        q = np.angle(A[j] - A0)
        assert np.linalg.norm(kl.analyze(m, q=q).position("P") - pts[j]) <= 1e-8 * size
        par = np.array([m.parameters[k] for k in ("ground", "crank", "coupler", "rocker")]
                       + list(m.parameters["coupler_point"]))
        ref = par if ref is None else ref
        assert np.abs(par - ref).max() <= 1e-8 * size


def test_cognates_move_through_the_points():
    # each real cognate passes through the nine points (engine check); the catalogue
    # crank-rocker does so on its sketch's branch, turning its crank
    pts, root = catalogue_task()
    for z in npp.cognates(root)[0]:
        reaches_every_point(pts, z)
    link = npp._linkage(pts, root, np.radians(30))
    assert link.errors.max() <= 1e-8 * np.ptp(pts, axis=0).max() and not link.branch_defect


def test_eliminated_jacobian_against_finite_differences():
    rng = np.random.default_rng(3)
    z = rng.standard_normal((2, 8)) + 1j * rng.standard_normal((2, 8))
    p0, p1 = npp._random_task(rng), npp._random_task(rng)
    H = npp._segment(p0, p1)
    t = np.full(2, 0.4)
    E, Ez, Et = H(z, t)
    h = 1e-7       # forward difference: error about h times the second derivative
    for k in range(8):
        dz = np.zeros(8, complex)
        dz[k] = h
        assert np.abs((H(z + dz, t)[0] - E) / h - Ez[..., k]).max() <= 1e-5 * np.abs(Ez).max()
    assert np.abs((H(z, t + h)[0] - E) / h - Et).max() <= 1e-5 * np.abs(Et).max()


def test_cognate_map_is_an_involution_and_the_class_key_is_shared():
    rng = np.random.default_rng(4)
    z = rng.standard_normal((5, 8)) + 1j * rng.standard_normal((5, 8))
    assert np.allclose(npp._cognate(npp._cognate(z)), z, rtol=1e-12, atol=1e-12)
    orbit = npp._orbit(z)                      # (5, 6, 8)
    keys = np.stack([npp._pivots_key(orbit[:, k]) for k in range(6)], axis=1)
    assert np.abs(keys - keys[:, :1]).max() <= 1e-10 * np.abs(keys).max()
    # the six labelled linkages are distinct, and _unique finds one class per root
    flat = orbit.reshape(-1, 8)
    assert len(npp._unique(flat, 1e-9)) == 30
    assert len(npp._unique(keys.reshape(-1, 6), 1e-9)) == 5


def test_tracked_subset():
    pts, root = catalogue_task()
    sols = kl.synthesis.nine_point_path(pts, max_classes=2)
    assert sols.up_to_cognates == 2 and len(sols) == 6 and not sols.complete
    # every end solves the loop equations, and its cognates are in the set
    assert sols.residuals.max() <= 1e-10
    assert npp.equations(pts, sols.roots).max() <= 1e-10
    keys = npp._pivots_key(sols.roots)
    assert len(npp._unique(keys, 1e-7)) == 2
    assert len(npp._unique(sols.roots, 1e-7)) == 6
    for z in sols.roots[np.abs(sols.roots[:, 1] - sols.roots[:, 0].conj()) < 1e-8]:
        reaches_every_point(pts, z)


@pytest.mark.parametrize("points, match", [
    (np.zeros((8, 2)), r"points: expected nine points .* got shape \(8, 2\)"),
    (np.full((9, 2), np.nan), r"points\[0\]: expected coordinates of finite numbers"),
    (np.vstack([np.eye(2), np.eye(2)[:1], np.arange(12).reshape(6, 2) + 5]),
     r"points: points 1 and 3 coincide"),
    (np.column_stack([np.arange(9.0), 2 * np.arange(9.0)]),
     r"points: the nine points lie on one line"),
])
def test_bad_input(points, match):
    with pytest.raises(ModelError, match=match):
        kl.synthesis.nine_point_path(points)


def test_bad_keywords():
    pts, _ = catalogue_task()
    with pytest.raises(ModelError, match="max_classes: expected a positive whole number"):
        kl.synthesis.nine_point_path(pts, max_classes=0)
    with pytest.raises(ModelError, match="order_by"):
        kl.synthesis.nine_point_path(pts, order_by="cost")


def test_memory_budget_refuses_with_the_estimate():
    pts, _ = catalogue_task()
    old = kl.memory_budget("1M")
    try:
        with pytest.raises(kl.errors.MemoryBudgetError, match="nine_point_path"):
            kl.synthesis.nine_point_path(pts, chunk=1000)
    finally:
        kl.memory_budget(old)
