"""Cost of ``verify=True``: the plain analysis and the verified one side by side.

For a four-bar (closed form), a Stephenson six-bar (closed form, four dyads) and the triad
six-bar of the catalogue (a Newton group), at a few sample counts: the best time of the
plain ``kl.analyze`` and of ``kl.analyze(..., verify=True)``, and their ratio.  Loop closure
runs on every sample; the other engine, the symbolic derivation and finite differences on
every sample up to ``kl.verify.SAMPLES`` and on a fixed subset beyond, so the ratio falls as
the sweep grows.  The symbolic route's derivation is made once per mechanism (sympy); its
one-time cost is printed apart, and the verified times are those of the runs after it.
Times are the best of several runs after an untimed one, which compiles the kernels.

    python benchmarks/verify.py [--quick]
"""
from __future__ import annotations

import sys
import time

import numpy as np

import kinelab as kl
from kinematics import best_time          # benchmarks/kinematics.py: the best of several runs


def main(quick: bool = False) -> None:
    cases = [("four-bar", kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
                                                coupler_point=(1.5, 1.0)), (361, 10**4, 10**5, 10**6)),
             ("Stephenson six-bar", kl.mechanisms.stephenson6(), (361, 10**4, 10**5, 10**6)),
             ("triad six-bar (Newton group)", kl.mechanisms.triad6(), (361, 10**4, 10**5))]
    if quick:
        cases = [(name, m, counts[:2]) for name, m, counts in cases]
    print(f"verify=True against the plain analysis (kl.verify.SAMPLES = {kl.verify.SAMPLES})")
    print(f"{'mechanism':30s} {'samples':>9s} {'plain':>10s} {'verified':>10s} {'ratio':>7s}")
    for name, m, counts in cases:
        lo, hi = kl.kinematics.reachable_ranges(m)[0]
        t = time.perf_counter()
        kl.analyze(m, np.linspace(lo, hi, 361), 10.0, verify=True)     # compiles, derives
        once = time.perf_counter() - t
        for n in counts:
            q = np.linspace(lo, hi, n)
            repeat = 5 if n <= 10**5 else 3
            kl.analyze(m, q, 10.0)
            plain = best_time(lambda: kl.analyze(m, q, 10.0), repeat)
            checked = best_time(lambda: kl.analyze(m, q, 10.0, verify=True), repeat)
            print(f"{name:30s} {n:9,d} {plain * 1e3:8.2f}ms {checked * 1e3:8.2f}ms "
                  f"{checked / plain:6.2f}x")
        print(f"{'':30s} first verified run (sympy's derivation, compiling): {once:.2f} s")


if __name__ == "__main__":
    main("--quick" in sys.argv)
