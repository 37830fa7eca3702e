"""Dynamics benchmarks: inverse-dynamics samples per second, and the wall time of 10 s of
forward simulation of a slider-crank engine.  Prints numbers; never fails on speed.

    .venv/bin/python benchmarks/dynamics.py
"""
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from kinelab.dynamics import Loads, PointForce, inverse, simulate  # noqa: E402
from tests.dynamics.models import engine, fourbar  # noqa: E402


def best_of(f, repeat=3):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main():
    m = engine()
    gas = "-2000 * exp(-(((q + 2 * pi) % (4 * pi) - 2 * pi - 0.3) ** 2) / 0.2)"
    loads = Loads(gravity=(0.0, -9.81), forces=[PointForce("B", (gas, 0.0), link="slider")])
    inverse(m, np.linspace(0, 1, 10), 10.0, loads=loads)          # compile the kinematics once
    print("inverse dynamics (slider-crank engine, gravity and a gas-force expression)")
    for n in (1_000, 100_000, 1_000_000):
        q = np.linspace(0.0, 4 * np.pi, n)
        for reactions in (False, True):
            dt, _ = best_of(lambda: inverse(m, q, 300.0, 0.0, loads=loads, reactions=reactions))
            print(f"  N = {n:>9,}  reactions={str(reactions):5}  {dt * 1e3:9.1f} ms  "
                  f"{n / dt:14,.0f} samples/s")
    fb = fourbar()
    q = np.linspace(0.0, 2 * np.pi, 100_000)
    dt, _ = best_of(lambda: inverse(fb, q, 10.0, loads=Loads(gravity=(0.0, -9.81))))
    print(f"  four-bar, N = 100,000 with reactions: {dt * 1e3:.1f} ms, {1e5 / dt:,.0f} samples/s")

    print("forward dynamics: 10 s of the engine from rest (motor 20 - 0.2 q' N m, gravity, gas force)")
    for rtol, atol in ((1e-8, 1e-10), (1e-10, 1e-12)):
        t0 = time.perf_counter()
        sim = simulate(m, (0.0, 10.0), q0=0.0, qd0=0.0, inputs={"jO2": "20 - 0.2 * qd"}, loads=loads,
                       rtol=rtol, atol=atol, t_eval=np.linspace(0.0, 10.0, 1001))
        dt = time.perf_counter() - t0
        print(f"  rtol={rtol:.0e}: {dt:6.2f} s wall, {sim.nfev:,} evaluations "
              f"({dt / sim.nfev * 1e6:.0f} us each), final speed {sim.qd[-1, 0]:.2f} rad/s, "
              f"energy error {sim.energy_error:.1e}, drift {sim.drift.max():.1e} m")


if __name__ == "__main__":
    main()
