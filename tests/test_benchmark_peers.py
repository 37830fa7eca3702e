"""The benchmarks' reference implementations: the path-error measure, the sympy + scipy
engine against kinelab's forward dynamics, and pylinkage's four-bar against kinelab."""
import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"


def _load(name):
    spec = importlib.util.spec_from_file_location(f"benchmarks_{name}", BENCHMARKS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module              # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


peers = _load("peers")
reference = _load("dynamics_reference")


def _circle(n, radius=1.0):
    a = np.linspace(0.0, 2 * np.pi, n)          # closed: the last sample is the first
    return radius * np.column_stack([np.cos(a), np.sin(a)])


def test_path_error_zero_on_the_curve():
    curve = _circle(3601)
    targets = curve[::360][:10]                  # samples of the curve itself
    assert peers.path_error(curve, targets) == 0.0
    # between samples: off the true circle by the chord's sag only, 1 - cos(pi/3600)
    a = np.radians(np.arange(10) * 36.0 + 0.05)
    between = np.column_stack([np.cos(a), np.sin(a)])
    assert peers.path_error(curve, between) < 1e-6


def test_path_error_known_distance():
    # Targets 0.25 m outside a unit circle, on the radii through samples: the nearest
    # point of the polyline is that sample, so every distance is 0.25 m exactly.  The
    # targets' box is 2.5 x 2.5 (points at 0, 90, 180, 270 degrees among them).
    curve = _circle(361)
    targets = 1.25 * curve[:360:45]
    expected = 0.25 / np.hypot(2.5, 2.5)
    assert peers.path_error(curve, targets) == pytest.approx(expected, rel=1e-12)


def test_path_error_scale_free_and_nan_gaps():
    curve = _circle(361)
    targets = 1.1 * curve[:360:40]
    e = peers.path_error(curve, targets)
    assert peers.path_error(3.0 * curve + 7.0, 3.0 * targets + 7.0) == pytest.approx(e, rel=1e-12)
    gapped = curve.copy()
    gapped[100:200] = np.nan                     # the curve is broken there, not joined
    assert peers.path_error(gapped, targets) > e


def test_dynamics_reference_against_kinelab():
    # 0.5 s from rest at rtol 1e-9: the two derivations (sympy Lagrange, kinelab's Kane
    # with its kinematics engine) integrate to within a few tolerances of each other;
    # the crank has turned about 52 rad by then.
    t = np.linspace(0.0, 0.5, 26)
    _, q_ref, qd_ref = reference.reference_engine(0.5, rtol=1e-9, atol=1e-11, t_eval=t)
    _, q, qd, _ = reference.kinelab_engine(0.5, rtol=1e-9, atol=1e-11, t_eval=t)
    assert q_ref[-1] > 40.0
    assert np.abs(q - q_ref).max() < 1e-6
    assert np.abs(qd - qd_ref).max() < 1e-4


def test_dynamics_reference_parameters_from_the_model():
    p = reference.engine_parameters()
    assert p["r"] == pytest.approx(0.05, abs=1e-15) and p["l"] == pytest.approx(0.18, abs=1e-15)
    assert (p["u2"], p["u3"]) == pytest.approx((0.01, 0.06), abs=1e-15)
    assert (p["v2"], p["v3"], p["e"]) == pytest.approx((0.0, 0.0, 0.0), abs=1e-15)


def test_pylinkage_against_kinelab():
    pytest.importorskip("pylinkage")
    assert peers.check_pylinkage() < 1e-9


def test_pylinkage_sweep_needs_uniform_angles():
    pytest.importorskip("pylinkage")
    fb = peers.pylinkage_fourbar(3.0, 1.0, 3.0, 2.5, (1.5, 1.0))
    with pytest.raises(ValueError, match="uniformly spaced"):
        peers.pylinkage_sweep(fb, [0.0, 0.1, 0.3])


def test_pylinkage_path_synthesis_small_budget():
    pytest.importorskip("pylinkage")
    r = peers.pylinkage_path_synthesis(peers.ELLIPSE_10, n_particles=20, iterations=5, seed=1)
    assert r.evaluations == 20 * 6
    assert 0.0 < r.error < 1.0
    again = peers.pylinkage_path_synthesis(peers.ELLIPSE_10, n_particles=20, iterations=5, seed=1)
    assert again.error == r.error                # seeded: reproducible


def test_coupler_task_is_traced_by_the_catalogue_crank_rocker():
    import kinelab as kl
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    P = kl.analyze(fb, np.radians(np.linspace(0, 270, 10))).position("P")
    np.testing.assert_allclose(peers.COUPLER_10, P, atol=1e-12)


def test_kinelab_path_synthesis_within_its_tolerance_by_the_peers_measure():
    # the search stops on the RMS distance at the targets' own crank angles; the peers'
    # measure, to the nearest point of the curve, can only be smaller (plus the chord sag)
    r = peers.kinelab_path_synthesis(peers.COUPLER_10, tolerance=1e-3, seed=0)
    assert r.error <= 1e-3


def test_time_to_an_error():
    runs = [[(0.5, 0.1), (1.0, 0.01), (2.0, 0.001)], [(0.2, 0.05)]]
    np.testing.assert_array_equal(peers._time_to(runs, 0.05), [1.0, 0.2])
    np.testing.assert_array_equal(peers._time_to(runs, 0.01), [1.0, np.inf])


def test_pylinkage_trace_improves_to_the_result():
    pytest.importorskip("pylinkage")
    r = peers.pylinkage_path_synthesis(peers.ELLIPSE_10, n_particles=20, iterations=5, seed=1)
    t = np.array([p[0] for p in r.trace])
    assert len(t) >= 1 and np.all(np.diff(t) >= 0)
    # the swarm's best is the last design that improved its fitness
    assert r.trace[-1][1] == r.error
