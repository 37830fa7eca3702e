"""Speed of the planar kinematics engine, in configurations per second.

Each case is the full analysis: angle, omega and alpha of every link; position, velocity and
acceleration of every point; K and L of all of them.  The baseline is a plain-numpy closed
form of the four-bar written here, computing the same quantities.  Times are the best of
several runs after one untimed run at full size, which compiles the kernels.  A result
that is dropped leaves its memory to the next one (see ``kl.reuse_result_memory``), as in
any loop of analyses; the four-bar is also timed with every result in fresh memory, whose
first touch the operating system pays for by zeroing pages (on a virtual machine that can
cost about as much as the analysis).

Small calls (360 and 3,600 angles) are timed apart, in processor time: one call of the
baseline against one ``kl.analyze`` with every quantity the baseline computes read from
its result (angle, omega, alpha, K and L of the crank, coupler and rocker; position,
velocity, acceleration, K and L of A, B and P), the two taking turns, repeated; best and
median of the repeats, and the baseline's median over kinelab's (> 1: kinelab is faster).
On a shared machine only the ratios compare, and the load average is printed beside them.

    python benchmarks/kinematics.py [--quick] [--small]
"""
from __future__ import annotations

import os
import sys
import time

import numba
import numpy as np

# the steady state: the compiled kernel, compiled (or loaded from numba's cache) by the
# first call, which waits for it; benchmarks/cold_start.py measures the first calls
os.environ.setdefault("KINELAB_KERNEL", "compiled")
import kinelab as kl  # noqa: E402

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


LINKS = ("crank", "coupler", "rocker")
POINTS = ("A", "B", "P")


def read_all(sol):
    """Every quantity of the baseline, read from a solution by its accessors."""
    links = {name: (sol.angle(name), sol.omega(name), sol.alpha(name), sol.K(name), sol.L(name))
             for name in LINKS}
    points = {name: (sol.position(name), sol.velocity(name), sol.acceleration(name),
                     sol.K(name), sol.L(name)) for name in POINTS}
    return links, points


def per_call(calls, n_calls: int, repeat: int) -> list[np.ndarray]:
    """Processor time of one call (s) of each of ``calls``, for each of ``repeat`` rounds;
    in each round every call is timed over ``n_calls`` calls, the calls taking turns."""
    times = [[] for _ in calls]
    for _ in range(repeat):
        for t, call in zip(times, calls):
            t0 = time.process_time()
            for _ in range(n_calls):
                call()
            t.append((time.process_time() - t0) / n_calls)
    return [np.array(t) for t in times]


def small_calls(fb, repeat: int) -> None:
    """The four-bar over 360 and 3,600 angles, one call at a time, against the baseline."""
    load = os.getloadavg()
    print(f"small calls, processor time per call (best, median of {repeat}; the baseline's "
          f"median over this one's), load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    for n in (360, 3600):
        q = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
        whole = lambda: read_all(kl.analyze(fb, q, 10.0, 0.0))       # noqa: E731
        alone = lambda: kl.analyze(fb, q, 10.0, 0.0)                 # noqa: E731
        base = lambda: numpy_fourbar(q, 10.0, 0.0)                   # noqa: E731
        for f in (whole, base):
            f()
        t_base, t_whole, t_alone = per_call([base, whole, alone], max(1, 36_000 // n), repeat)
        ref = np.median(t_base)
        for label, t in ((f"numpy closed form (baseline), N = {n:,}", t_base),
                         (f"kinelab analyze + every accessor, N = {n:,}", t_whole),
                         (f"kinelab analyze alone, N = {n:,}", t_alone)):
            ratio = "" if t is t_base else f"{ref / np.median(t):6.2f} x"
            print(f"  {label:46s}: {np.min(t) * 1e6:9.1f} {np.median(t) * 1e6:9.1f} us  {ratio}")


def main() -> None:
    quick = "--quick" in sys.argv
    fb = kl.mechanisms.fourbar(GROUND, CRANK, COUPLER, ROCKER, coupler_point=CP)
    if "--small" in sys.argv:
        kl.analyze(fb, q=np.linspace(0.0, 1.0, 10))                    # compile
        small_calls(fb, 7 if quick else 21)
        return
    n = 10 ** 5 if quick else 10 ** 6
    n_newton = 10 ** 4 if quick else 10 ** 5
    repeat = 3 if quick else 7
    print(f"kinelab kinematics benchmark: {numba.get_num_threads()} threads, N = {n:,}")
    q = np.linspace(0.0, 2 * np.pi, n, endpoint=False)

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
    small_calls(fb, 7 if quick else 21)


def report(label, n, seconds, rate_base):
    rate = n / seconds
    print(f"  {label:34s}: {rate:12,.0f} configurations/s  "
          f"({rate / rate_base:5.2f} x baseline, {1e9 / rate:7.1f} ns each, N = {n:,})")


if __name__ == "__main__":
    main()
