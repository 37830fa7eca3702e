"""Speed of the graphical methods over whole sweeps, beside references timed in the same run.

- acceleration differences of every pair of points of a four-bar's coupler over a sweep,
  against the analysis itself (what they are computed from);
- the instant centres by Kennedy's construction against the centres solved from the
  velocities (``instant_centers``), both for a whole sweep of a Watt six-bar;
- ``differentiate`` of a noisy curve of N samples against ``scipy.signal.savgol_filter``
  at the same window (which takes even sampling only and gives no error estimate).

Times are process times (best and median of several runs) after one untimed run.

    python benchmarks/graphical.py [--quick]
"""
from __future__ import annotations

import itertools
import sys
import time

import numpy as np
from scipy.signal import savgol_filter

import kinelab as kl


def timed(f, repeat):
    f()
    times = []
    for _ in range(repeat):
        t0 = time.process_time()
        f()
        times.append(time.process_time() - t0)
    return min(times), float(np.median(times))


def row(label, ours, ref, ref_label):
    print(f"{label:<48} {ours[0] * 1e3:9.2f} {ours[1] * 1e3:9.2f}   {ref_label:<24} "
          f"{ref[0] * 1e3:9.2f} {ref[1] * 1e3:9.2f}   ratio {ours[0] / ref[0]:6.2f}")


def main(quick: bool) -> None:
    n = 20_000 if quick else 200_000
    repeat = 3 if quick else 7
    print(f"{'case':<48} {'best ms':>9} {'median':>9}   {'reference':<24} {'best ms':>9} {'median':>9}")
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    q = np.linspace(0.0, 2 * np.pi, n)
    sol = kl.analyze(fb, q=q, qd=10.0, qdd=1.0)
    pairs = list(itertools.permutations(fb.link("coupler").points, 2))

    def differences():
        for p, r in pairs:
            kl.kinematics.acceleration_difference(sol, p, r)
    row(f"acceleration_difference x{len(pairs)}, N={n}", timed(differences, repeat),
        timed(lambda: kl.analyze(fb, q=q, qd=10.0, qdd=1.0), repeat), "analyze, same N")
    w6 = kl.mechanisms.watt6()
    m = n // 10
    sol6 = kl.analyze(w6, q=np.linspace(0.0, 2 * np.pi, m) + 0.013, qd=1.0)
    row(f"kennedy_construction, Watt six-bar, N={m}",
        timed(lambda: kl.kinematics.kennedy_construction(sol6), repeat),
        timed(lambda: kl.kinematics.instant_centers(sol6), repeat), "instant_centers")
    for size in ((2_001,) if quick else (2_001, 20_001)):
        x = np.linspace(0.0, 1.0, size)
        y = np.sin(6 * x) + 1e-3 * np.random.default_rng(0).standard_normal(size)
        window = kl.solvers.differentiate(x, y).window
        h = x[1] - x[0]
        row(f"differentiate, N={size} (window {window})",
            timed(lambda: kl.solvers.differentiate(x, y), repeat),
            timed(lambda: [savgol_filter(y, window, 5, deriv=k, delta=h, mode="interp")
                           for k in (0, 1, 2)], repeat), "savgol_filter x3, same w")


if __name__ == "__main__":
    main("--quick" in sys.argv)
