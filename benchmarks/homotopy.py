"""Homotopy continuation benchmark: five path points with both fixed pivots given, and
nine path points (pivots free).

    .venv/bin/python benchmarks/homotopy.py [TASKS [CLASSES]]

For TASKS random tasks (points and pivots drawn from a normal distribution, seeds 0, 1,
...; 10 by default) it solves ``kl.synthesis.five_point_path`` and prints, per task, the
paths tracked, those repeated with another gamma and those that failed, the roots found
(36 for general data, Morgan and Wampler 1990) and how many are real, the wall time (the
tracking alone, and the whole call with its engine checks of every real linkage), and
the peak memory of the Python allocations made by a second, identical call
(tracemalloc); then the
totals.  Then the nine-point problem: monodromy at the base task until CLASSES cognate
classes are known (200 by default), its path segments per second, the time for them, the
time extrapolated to the complete set (1442 classes, each carried around six loops of four
segments, then one route of two segments to the given points), and the peak memory of a
smaller run (tracemalloc).  Numbers, not a test: it never fails on speed.
"""
from __future__ import annotations

import sys
import time
import tracemalloc

import numpy as np

import kinelab as kl
from kinelab.solvers._homotopy import multihomogeneous_start, track, with_rows
from kinelab.synthesis import _five_point_path as fpp
from kinelab.synthesis import _nine_point_path as npp


def tracking_only(points: np.ndarray, pivots: np.ndarray, seed: int) -> float:
    """Wall time of the 96 paths alone, s (no refinement, no engine checks)."""
    c = points.mean(axis=0)
    s = np.linalg.norm(points - c, axis=1).max()
    p = ((points - c) / s) @ np.array([1.0, 1j])
    a0, b0 = (complex(*((v - c) / s)) for v in pivots)
    F, _ = fpp._system(p, a0, b0)
    rng = np.random.default_rng(seed)
    start, patches, starts = multihomogeneous_start([[0, 1, 2], [3, 4, 5]],
                                                    np.full((4, 2), 2), rng)
    t0 = time.perf_counter()
    track(with_rows(F, patches), start, starts, gamma=np.exp(2j * np.pi * rng.random()))
    return time.perf_counter() - t0


def main(tasks: int = 10) -> None:
    # a first call outside the timings: imports and the engine's first plan
    warm = np.random.default_rng(99).normal(size=(7, 2))
    kl.synthesis.five_point_path(warm[:5], pivots=(warm[5], warm[6]))
    print("five_point_path: five random points, random A0 and B0 (normal distribution)")
    print(f"{'seed':>4s} {'paths':>6s} {'retried':>8s} {'failed':>7s} {'roots':>6s} {'real':>5s} "
          f"{'valid':>6s} {'track [s]':>10s} {'total [s]':>10s} {'peak [MB]':>10s}")
    totals = []
    for seed in range(tasks):
        rng = np.random.default_rng(seed)
        points, pivots = rng.normal(size=(5, 2)), rng.normal(size=(2, 2))
        t_track = tracking_only(points, pivots, 0)
        sols = kl.synthesis.five_point_path(points, pivots=(pivots[0], pivots[1]))
        tracemalloc.start()          # a second call for the memory: tracemalloc slows it
        kl.synthesis.five_point_path(points, pivots=(pivots[0], pivots[1]))
        peak = tracemalloc.get_traced_memory()[1] / 1e6
        tracemalloc.stop()
        valid = sum(s.valid for s in sols.real)
        print(f"{seed:4d} {sols.paths:6d} {sols.retried:8d} {sols.failed:7d} {len(sols):6d} "
              f"{len(sols.real):5d} {valid:6d} {t_track:10.3f} {sols.seconds:10.3f} {peak:10.1f}")
        totals.append((len(sols) == fpp.EXPECTED, sols.failed, t_track, sols.seconds, peak))
    ok, failed, tt, ts, peak = (np.array(c) for c in zip(*totals))
    print(f"all 36 roots on {ok.sum()} of {len(ok)} tasks; {failed.sum()} paths failed in all; "
          f"median time {np.median(tt):.3f} s tracking, {np.median(ts):.3f} s whole call "
          "(the time of a call made without tracemalloc); "
          f"largest peak memory {peak.max():.1f} MB")


def monodromy(classes: int, chunk: int = 2000) -> tuple[int, int, float]:
    """Monodromy at the nine-point base task until ``classes`` classes are known: the
    classes found, the path segments followed and the wall time, s."""
    T, r = npp.base_task()
    _, s = npp._frame(T)
    d, db = npp._displacements(T)
    p0 = np.concatenate([d, db])
    rng = np.random.default_rng(0)
    z0 = r[None] / s
    loops = np.stack([[npp._random_task(rng) for _ in range(3)] for _ in range(npp._LOOPS)])
    state = npp._Monodromy(base=p0, loops=loops, reps=z0, keys=npp._pivots_key(z0),
                           sent=np.zeros(npp._LOOPS, int))
    t0 = time.perf_counter()
    npp._monodromy(state, classes, chunk)
    return len(state.reps), state.paths, time.perf_counter() - t0


def nine_point(classes: int = 200) -> None:
    print()
    print("nine_point_path: monodromy at the base task (nine points of a known four-bar)")
    found, paths, seconds = monodromy(classes)
    rate = paths / seconds
    full = npp.CLASSES * (npp._LOOPS * 4 + 2)
    print(f"{found} classes ({paths} path segments) in {seconds:.1f} s: {rate:.1f} segments/s")
    print(f"complete set: about {full} segments, {full / rate / 60:.1f} min at that rate "
          "; optimistic: the later rounds' paths take more steps (a complete run measured "
          "37,252 segments in 21 min, about 30 a second, on a shared 2-core machine)")
    tracemalloc.start()
    monodromy(20)
    peak = tracemalloc.get_traced_memory()[1] / 1e6
    tracemalloc.stop()
    print(f"peak memory of a run to 20 classes: {peak:.1f} MB "
          f"(budget per path in nine_point_path: {npp.PATH_BYTES / 1e3:.0f} kB)")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 10)
    nine_point(int(sys.argv[2]) if len(sys.argv) > 2 else 200)
