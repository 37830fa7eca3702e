"""Speed of the planar kinematics engine, in configurations per second.

Each case is the full analysis: angle, omega and alpha of every link; position, velocity and
acceleration of every point; K and L of all of them.  The baseline is a plain-numpy closed
form of the four-bar written here, computing the same quantities.  Times are the best of
several runs after one untimed run at full size, which compiles the kernels.  A result
that is dropped leaves its memory to the next one (see ``kl.reuse_result_memory``), as in
any loop of analyses; the four-bar is also timed with every result in fresh memory, whose
first touch the operating system pays for by zeroing pages (on a virtual machine that can
cost about as much as the analysis).

    python benchmarks/kinematics.py [--quick]
"""
from __future__ import annotations

import sys
import time

import numba
import numpy as np

import kinelab as kl

GROUND, CRANK, COUPLER, ROCKER, CP = 3.0, 1.0, 3.0, 2.5, (1.5, 1.0)


def numpy_fourbar(q, w2, a2):
    """Closed-form four-bar (open branch): angles, rates, K, L and every point, in numpy."""
    a, b, c, d = CRANK, COUPLER, ROCKER, GROUND
    c2, s2 = np.cos(q), np.sin(q)
    Ax, Ay = a * c2, a * s2
    dx, dy = d - Ax, -Ay                           # O4 - A
    D2 = dx * dx + dy * dy
    D = np.sqrt(D2)
    m = (b * b - c * c + D2) / (2 * D)
    h = np.sqrt(b * b - m * m)
    ex, ey = dx / D, dy / D
    Bx, By = Ax + m * ex - h * ey, Ay + m * ey + h * ex
    t3 = np.arctan2(By - Ay, Bx - Ax)
    t4 = np.arctan2(By, Bx - d)
    c3, s3, c4, s4 = np.cos(t3), np.sin(t3), np.cos(t4), np.sin(t4)
    sin34 = np.sin(t3 - t4)
    K3 = a * np.sin(t4 - q) / (b * sin34)
    K4 = a * np.sin(q - t3) / (c * np.sin(t4 - t3))
    # L: differentiate a e^{iq} + b e^{i t3} - c e^{i t4} - d = 0 twice by q, solve by Cramer
    A_ = c * s4
    B_ = b * s3
    C_ = a * c2 + b * K3 ** 2 * c3 - c * K4 ** 2 * c4
    D_ = c * c4
    E_ = b * c3
    F_ = a * s2 + b * K3 ** 2 * s3 - c * K4 ** 2 * s4
    L3 = (C_ * D_ + A_ * F_) / (A_ * E_ - B_ * D_)
    L4 = (C_ * E_ + B_ * F_) / (A_ * E_ - B_ * D_)
    out = {"crank": (q, np.ones_like(q), np.zeros_like(q)), "coupler": (t3, K3, L3),
           "rocker": (t4, K4, L4)}
    res = {}
    for name, (t, K, L) in out.items():
        res[name] = (t, K * w2, K * a2 + L * w2 * w2, K, L)
    # points: A on the crank, B on the rocker, P on the coupler
    px, py = CP
    Px = Ax + px * c3 - py * s3
    Py = Ay + px * s3 + py * c3
    KAx, KAy = -a * s2, a * c2
    LAx, LAy = -a * c2, -a * s2
    KBx, KBy = -c * s4 * K4, c * c4 * K4
    LBx, LBy = -c * (c4 * K4 ** 2 + s4 * L4), c * (-s4 * K4 ** 2 + c4 * L4)
    rx, ry = Px - Ax, Py - Ay
    KPx, KPy = KAx - K3 * ry, KAy + K3 * rx
    LPx, LPy = LAx - L3 * ry - K3 ** 2 * rx, LAy + L3 * rx - K3 ** 2 * ry
    for name, (x, y, kx, ky, lx, ly) in {"A": (Ax, Ay, KAx, KAy, LAx, LAy), "B": (Bx, By, KBx, KBy, LBx, LBy),
                                          "P": (Px, Py, KPx, KPy, LPx, LPy)}.items():
        res[name] = (x, y, kx * w2, ky * w2, kx * a2 + lx * w2 * w2, ky * a2 + ly * w2 * w2, kx, ky, lx, ly)
    return res


def best_time(f, repeat):
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t)
    return best


def main() -> None:
    quick = "--quick" in sys.argv
    n = 10 ** 5 if quick else 10 ** 6
    n_newton = 10 ** 4 if quick else 10 ** 5
    repeat = 3 if quick else 7
    print(f"kinelab kinematics benchmark: {numba.get_num_threads()} threads, N = {n:,}")
    q = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    fb = kl.mechanisms.fourbar(GROUND, CRANK, COUPLER, ROCKER, coupler_point=CP)

    # agreement first: the baseline must compute the same numbers
    ref = numpy_fourbar(q[:1000], 10.0, 0.0)
    sol = kl.analyze(fb, q=q[:1000], qd=10.0)
    err = max(np.max(np.abs(np.angle(np.exp(1j * (ref["rocker"][0] - sol.angle("rocker")))))),
              np.max(np.abs(ref["P"][4] - sol.acceleration("P")[:, 0])),
              np.max(np.abs(ref["B"][5] - sol.acceleration("B")[:, 1])),
              np.max(np.abs(ref["coupler"][2] - sol.alpha("coupler"))),
              np.max(np.abs(ref["rocker"][4] - sol.L("rocker"))))
    print(f"  baseline vs kinelab, largest difference: {err:.1e}")

    numpy_fourbar(q, 10.0, 0.0)
    t_base = best_time(lambda: numpy_fourbar(q, 10.0, 0.0), repeat)
    rate_base = n / t_base
    print(f"  numpy closed-form four-bar (baseline): {rate_base:12,.0f} configurations/s")

    cases = [("four-bar (closed form)", fb, q),
             ("Stephenson six-bar (closed form)", kl.mechanisms.stephenson6(), q),
             ("triad six-bar (Newton engine)", kl.mechanisms.triad6(), q[:: n // n_newton])]
    for label, m, qs in cases:
        kl.analyze(m, q=qs, qd=10.0)                       # compile, take the memory
        report(label, len(qs), best_time(lambda: kl.analyze(m, q=qs, qd=10.0), repeat), rate_base)
        if m is fb:
            kept = kl.reuse_result_memory(0)
            report("four-bar, results in fresh memory", n,
                   best_time(lambda: kl.analyze(fb, q=q, qd=10.0), repeat), rate_base)
            kl.reuse_result_memory(kept)


def report(label, n, seconds, rate_base):
    rate = n / seconds
    print(f"  {label:34s}: {rate:12,.0f} configurations/s  "
          f"({rate / rate_base:5.2f} x baseline, {1e9 / rate:7.1f} ns each, N = {n:,})")


if __name__ == "__main__":
    main()
