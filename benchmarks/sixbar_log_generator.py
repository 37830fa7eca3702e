"""A logarithmic function generator by a Stephenson III six-bar, after Svoboda.

    .venv/bin/python benchmarks/sixbar_log_generator.py [PAIRS]

y = log10(x) for x in [1, 10]: the crank turns 120 deg over the range of x, the output
(the link O6-D) 60 deg over the range of y.  ``kl.synthesis.sixbar`` fits PAIRS (21 by
default) evenly spaced pairs by least squares, and the linkage's structural error (output
turn minus the function, over 2001 inputs of the whole range) is then measured with
``kl.analyze`` of the synthesised model alone.  Prints the errors, in deg, and the time.
Numbers, not a test.
"""
from __future__ import annotations

import sys
import time

import numpy as np

import kinelab as kl


def main(pairs: int = 21) -> None:
    x = np.linspace(1.0, 10.0, pairs)
    th, ph = np.radians(120.0) * (x - 1) / 9, np.radians(60.0) * np.log10(x)
    for limit in (None, 30.0):
        t = time.perf_counter()
        found = kl.synthesis.sixbar("stephenson3", {"function": (th, ph)}, starts=3000,
                                    refine=40, iterations=40, solutions=3, seed=0,
                                    min_transmission_angle=limit, degrees=True)
        took = time.perf_counter() - t
        best = found[0]
        xs = np.linspace(1.0, 10.0, 2001)
        sol = kl.analyze(best.model, q=best.q[0] + np.radians(120.0) * (xs - 1) / 9)
        v = sol.position("D") - sol.position("O6")
        out = np.unwrap(np.arctan2(v[:, 1], v[:, 0]))
        structural = (out - out[0]) - np.radians(60.0) * np.log10(xs)
        print(f"min transmission {limit or 'free'}: {best!r}")
        print(f"  max error at the {pairs} pairs {np.degrees(best.errors.max()):.2e} deg, "
              f"structural error over [1, 10] {np.degrees(np.abs(structural).max()):.2e} deg "
              f"({np.abs(structural).max() / np.radians(60.0):.1e} of the output's span), "
              f"{took:.1f} s")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:2]))
