"""Synthesis benchmark: time and error reached on a fixed set of path tasks.

    .venv/bin/python benchmarks/synthesis.py          (or: make bench)

Prints the speed of the vectorised closed-form coupler-curve evaluator and of the
motion-generation routines; then, for each of a few path tasks, the best linkage found by
path_generation (screened designs, then batched least squares) with its RMS and largest
distance to the targets, next to what the screen alone reaches; then how reliably and how
fast path_generation reaches an error of 1e-3 of the path's size on many 10-point tasks
(targets traced by random four-bars, so an exact solution exists), several seeds each.
Numbers, not a test: it never fails on speed.  benchmarks/peers.py sets path_generation
beside pylinkage's and pyslvs' searches.
"""
from __future__ import annotations

import os
import time

import numpy as np

import kinelab as kl

BUDGET = dict(runs=3, seed=0, min_transmission_angle=np.radians(20.0))


def _tasks():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
                               coupler_point=(1.5, 1.0))
    t = np.radians(np.linspace(0, 270, 10))
    yield "coupler curve, 6 points (exact)", kl.analyze(
        fb, q=np.radians([0, 40, 80, 120, 160, 200])).position("P")
    yield "circular arc, 5 points (exact)", np.column_stack(
        [np.cos(np.radians([0, 30, 60, 90, 120])), np.sin(np.radians([0, 30, 60, 90, 120]))])
    yield "straight line, 8 points", np.column_stack([np.linspace(0.0, 1.0, 8), np.zeros(8)])
    yield "ellipse 2 x 1, 10 points", np.column_stack([2 * np.cos(t), np.sin(t)])
    x = np.linspace(0.0, 2.0, 7)
    yield "sine wave, 7 points", np.column_stack([x, 0.3 * np.sin(np.pi * x)])


def path_tasks():
    print(f"path generation: runs={BUDGET['runs']}, seed={BUDGET['seed']}, transmission "
          f"angle >= {np.degrees(BUDGET['min_transmission_angle']):.0f} deg, the other settings "
          "path_generation's defaults; processor time")
    print(f"{'task':34s} {'time [s]':>9s} {'rms [m]':>10s} {'max [m]':>10s} "
          f"{'search only':>12s} {'class':>14s} {'min mu [deg]':>13s}")
    for name, pts in _tasks():
        t0 = time.process_time()
        sols = kl.synthesis.path_generation(pts, **BUDGET)
        dt = time.process_time() - t0
        raw = kl.synthesis.path_generation(pts, **(BUDGET | dict(runs=1, refine=False)))
        raw_rms = f"{raw[0].rms_error:.3g}" if raw else "-"
        if not sols:
            print(f"{name:34s} {dt:9.2f} {'none':>10s}   ({sols.reason})")
            continue
        b = sols[0]
        print(f"{name:34s} {dt:9.2f} {b.rms_error:10.3g} {b.max_error:10.3g} {raw_rms:>12s} "
              f"{b.grashof.kind:>14s} {np.degrees(b.min_transmission_angle):13.1f}")


def evaluator_speed():
    rng = np.random.default_rng(0)
    D, m = 2000, 360
    designs = np.column_stack([rng.uniform(-1, 1, (D, 4)), rng.uniform(0.3, 2.5, (D, 3)),
                               rng.uniform(-1, 1, (D, 2)), rng.choice([-1.0, 1.0], D)])
    q = np.linspace(0, 2 * np.pi, m, endpoint=False)
    kl.synthesis.coupler_curves(designs[:10], q)
    t0 = time.perf_counter()
    reps = 5
    for _ in range(reps):
        kl.synthesis.coupler_curves(designs, q)
    dt = (time.perf_counter() - t0) / reps
    print(f"closed-form coupler curves: {D} designs x {m} crank angles in {dt * 1e3:.1f} ms "
          f"({D * m / dt / 1e6:.1f} M configurations/s)")


def motion_speed():
    P = np.array([(0, 0), (5, 8), (10, 15), (18, 20)]) * 0.01
    t0 = time.perf_counter()
    sols = kl.synthesis.four_positions(P, [10, 20, 30], -0.20195, -0.29167, degrees=True)
    dt = time.perf_counter() - t0
    print(f"four_positions (seed 003 §6.7): {len(sols)} linkages built and checked with the "
          f"engine in {dt * 1e3:.0f} ms ({sum(s.valid for s in sols)} valid)")
    t0 = time.perf_counter()
    cur = kl.synthesis.burmester_curves(P, [10, 20, 30], degrees=True, samples=3601)
    dt = time.perf_counter() - t0
    print(f"burmester_curves: {int(cur.valid.sum())} centre/circle point pairs in {dt * 1e3:.1f} ms")


def traced_tasks(count: int, n: int = 10, seed: int = 5):
    """``count`` path tasks of ``n`` points traced by random four-bars whose crank turns
    fully, over 180 to 340 deg of crank travel (an exact solution exists)."""
    rng = np.random.default_rng(seed)
    q = np.linspace(0.0, 2 * np.pi, 721)
    while count:
        d = np.r_[rng.uniform(-1, 1, 4), rng.uniform(0.3, 2.5, 3), rng.uniform(-1, 1, 2),
                  rng.choice([-1.0, 1.0])]
        if np.hypot(d[2] - d[0], d[3] - d[1]) < 0.2 or not kl.synthesis.coupler_curves(
                d[None], q)[3].all():
            continue
        start = rng.uniform(0.0, 2 * np.pi)
        travel = np.radians(rng.uniform(180.0, 340.0))
        count -= 1
        yield kl.synthesis.coupler_curves(d[None], start + np.linspace(0.0, travel, n))[0][0]


def reliability(count: int = 20, seeds: int = 3, error: float = 1e-3):
    """Time to ``error`` (RMS distance over the diagonal of the targets' box) on many
    10-point tasks, one run per task and seed."""
    tasks = list(traced_tasks(count))
    # and one whose crank stops at limit positions just outside the travel
    stops = [[0.2, -0.1, 1.1, 0.3, 0.8, 1.3, 1.6, -0.4, 0.7, -1.0]]
    tasks.append(kl.synthesis.coupler_curves(stops, np.radians(np.linspace(50, 340, 10)))[0][0])
    kl.synthesis.path_generation(tasks[0], runs=1, maxiter=1)                 # warm
    times, reached = [], []
    for T in tasks:
        size = np.hypot(*np.ptp(T, axis=0))
        for seed in range(seeds):
            t0 = time.process_time()
            # the limit off: the traced tasks' own linkages may go below 30 deg, and this
            # measures the search
            sols = kl.synthesis.path_generation(T, runs=1, seed=seed, tolerance=error,
                                                min_transmission_angle=0.0)
            times.append(time.process_time() - t0)
            reached.append(bool(sols) and sols[0].rms_error <= error * size)
    t = np.array(times)
    print(f"path generation to {error:g} of the path's size, {len(tasks)} traced 10-point "
          f"tasks x {seeds} seeds (defaults, runs=1, no transmission limit): reached "
          f"{sum(reached)} of {len(t)}; "
          f"processor time best {t.min():.2f} s, median {np.median(t):.2f} s, 90% "
          f"{np.percentile(t, 90):.2f} s, worst {t.max():.2f} s; {int(np.sum(t > 2.0))} over 2 s")


if __name__ == "__main__":
    # the steady state: the compiled kernel, waited for by the first call
    os.environ.setdefault("KINELAB_KERNEL", "compiled")
    evaluator_speed()
    motion_speed()
    path_tasks()
    reliability()
