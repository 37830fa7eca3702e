"""Synthesis benchmark: time and error reached on a fixed set of path tasks.

    .venv/bin/python benchmarks/synthesis.py          (or: make bench)

Prints, for each task, the best linkage found by path_generation (differential
evolution, then least squares) with its RMS and largest distance to the targets, next to
what the global search alone reaches; then the speed of the vectorised closed-form
coupler-curve evaluator and of the motion-generation routines.  Numbers, not a test: it
never fails on speed.
"""
from __future__ import annotations

import time

import numpy as np

import kinelab as kl

BUDGET = dict(runs=3, maxiter=300, popsize=15, seed=0, min_transmission_angle=np.radians(20.0))


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
    print(f"path generation: runs={BUDGET['runs']}, maxiter={BUDGET['maxiter']}, "
          f"popsize={BUDGET['popsize']}, seed={BUDGET['seed']}, transmission angle >= "
          f"{np.degrees(BUDGET['min_transmission_angle']):.0f} deg")
    print(f"{'task':34s} {'time [s]':>9s} {'rms [m]':>10s} {'max [m]':>10s} "
          f"{'search only':>12s} {'class':>14s} {'min mu [deg]':>13s}")
    for name, pts in _tasks():
        t0 = time.perf_counter()
        sols = kl.synthesis.path_generation(pts, **BUDGET)
        dt = time.perf_counter() - t0
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


if __name__ == "__main__":
    evaluator_speed()
    motion_speed()
    path_tasks()
