"""Dynamics benchmarks: inverse-dynamics samples per second; 10 s of forward simulation
of a slider-crank engine side by side with a sympy + solve_ivp model of the same engine
(speed, and the error of each after 10 s against a tight-tolerance solution); a batch of
1000 runs against a loop of single runs.  Prints numbers; never fails on speed.

    .venv/bin/python benchmarks/dynamics.py [--quick]
"""
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

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

    forward(m, loads, quick="--quick" in sys.argv)


GAS = "-2000 * exp(-(((q + 2 * pi) % (4 * pi) - 2 * pi - 0.3) ** 2) / 0.2)"
MOTOR = "20 - 0.2 * qd"


def reference_engine():
    """The sympy + solve_ivp engine of benchmarks/dynamics_reference.py where present,
    else the same model built here: Lagrange's equation of the crank angle from the kinetic
    and potential energy of crank, rod and piston, lambdified, integrated by solve_ivp."""
    try:
        import dynamics_reference as ref                      # noqa: F401
        return lambda rtol, atol, t_eval: ref.reference_engine(10.0, rtol, atol, t_eval)[1]
    except ImportError:
        pass
    import sympy as sp
    from scipy.integrate import solve_ivp

    m = engine()
    xy = {p.name: np.array(p.xy) for p in m.points}
    crank, rod, piston = m.link("crank"), m.link("rod"), m.link("slider")

    def local(origin, toward, point):          # a centre of mass in its link's frame
        e = (xy[toward] - xy[origin]) / np.linalg.norm(xy[toward] - xy[origin])
        d = xy[point] - xy[origin]
        return float(d @ e), float(e[0] * d[1] - e[1] * d[0])
    r, l = np.linalg.norm(xy["A"] - xy["O2"]), np.linalg.norm(xy["B"] - xy["A"])
    e = float(xy["B"][1] - xy["O2"][1])
    (u2, v2), (u3, v3) = local("O2", "A", crank.center_of_mass), local("A", "B", rod.center_of_mass)
    q, qd = sp.symbols("q qd", real=True)
    h = e - r * sp.sin(q)
    w = sp.sqrt(l ** 2 - h ** 2)
    A = sp.Matrix([r * sp.cos(q), r * sp.sin(q)])
    phi = sp.atan2(h, w)

    def at(a, u, v):
        return sp.Matrix([u * sp.cos(a) - v * sp.sin(a), u * sp.sin(a) + v * sp.cos(a)])
    G2, G3, xB = at(q, u2, v2), A + at(phi, u3, v3), A[0] + w

    def sq(P):
        d = P.diff(q)
        return d.dot(d)
    mass = (crank.mass * sq(G2) + crank.inertia + rod.mass * sq(G3) + rod.inertia * phi.diff(q) ** 2
            + piston.mass * xB.diff(q) ** 2)
    V = 9.81 * (crank.mass * G2[1] + rod.mass * G3[1] + piston.mass * e)
    gas = -2000 * sp.exp(-(sp.Mod(q + 2 * sp.pi, 4 * sp.pi) - 2 * sp.pi - sp.Rational(3, 10)) ** 2
                         / sp.Rational(1, 5))
    qdd = (20 - sp.Rational(1, 5) * qd + gas * xB.diff(q) - mass.diff(q) * qd ** 2 / 2 - V.diff(q)) / mass
    f = sp.lambdify((q, qd), qdd, modules="math", cse=True)

    def run(rtol, atol, t_eval):
        out = solve_ivp(lambda _t, y: (y[1], f(y[0], y[1])), (0.0, 10.0), [0.0, 0.0], method="DOP853",
                        rtol=rtol, atol=atol, t_eval=t_eval)
        return out.y[0]
    return run


def repeats(f, n):
    """f() n times: (best, median) process time in s, and the last result."""
    times = []
    for _ in range(n):
        t0 = time.process_time()
        out = f()
        times.append(time.process_time() - t0)
    return min(times), statistics.median(times), out


def forward(m, loads, quick=False):
    """The engine from rest: motor 20 - 0.2 q' N m, gravity, a gas force at the wrist pin."""
    t_eval = np.linspace(0.0, 10.0, 1001)
    inputs = {"jO2": MOTOR}

    def kinelab_run(rtol, atol, method="DOP853"):
        return simulate(m, (0.0, 10.0), q0=0.0, qd0=0.0, inputs=inputs, loads=loads, rtol=rtol,
                        atol=atol, t_eval=t_eval, method=method)
    reference = reference_engine()
    truth = kinelab_run(1e-13, 1e-13).q[:, 0]
    check = reference(1e-13, 1e-13, t_eval)
    print("forward dynamics: 10 s of the engine from rest (motor 20 - 0.2 q' N m, gravity, gas force), "
          "DOP853, process time")
    print(f"  tight-tolerance solutions (rtol 1e-13): kinelab and the reference differ by "
          f"{np.max(np.abs(truth - check)):.1e} rad over the run; errors below against kinelab's")
    n = 3 if quick else 5
    for rtol, atol in ((1e-8, 1e-10), (1e-10, 1e-12)):
        kb, km, sim = repeats(lambda: kinelab_run(rtol, atol), n)
        rb, rm, q_ref = repeats(lambda: reference(rtol, atol, t_eval), n)
        ek, er = abs(sim.q[-1, 0] - truth[-1]), abs(q_ref[-1] - truth[-1])
        print(f"  rtol={rtol:.0e}  kinelab   best {kb * 1e3:7.1f} ms  median {km * 1e3:7.1f} ms  "
              f"{sim.nfev:,} evaluations ({kb / sim.nfev * 1e6:.2f} us each)  error at 10 s {ek:.1e} rad  "
              f"energy error {sim.energy_error:.1e}")
        print(f"  rtol={rtol:.0e}  reference best {rb * 1e3:7.1f} ms  median {rm * 1e3:7.1f} ms  "
              f"error at 10 s {er:.1e} rad")
        print(f"  rtol={rtol:.0e}  ratio reference / kinelab: {rb / kb:.1f}x (best), {rm / km:.1f}x "
              f"(median); error kinelab / reference: {ek / er:.2f}")
    kb, _, sim = repeats(lambda: kinelab_run(1e-8, 1e-10, method="RK45"), 1)
    print(f"  rtol=1e-08  kinelab through solve_ivp (method='RK45', the Python right-hand side): "
          f"{kb:.2f} s, {sim.nfev:,} evaluations ({kb / sim.nfev * 1e6:.0f} us each)")

    B = 1000
    rng = np.random.default_rng(1)
    q0 = rng.uniform(0.0, 2 * np.pi, (B, 1))
    qd0 = rng.uniform(0.0, 20.0, (B, 1))
    for t_end in (1.0,) if quick else (1.0, 10.0):
        te = np.linspace(0.0, t_end, 101)

        def batch():
            return simulate(m, (0.0, t_end), q0, qd0, inputs=inputs, loads=loads, rtol=1e-8,
                            atol=1e-10, t_eval=te)

        def single(i):
            return simulate(m, (0.0, t_end), q0[i], qd0[i], inputs=inputs, loads=loads, rtol=1e-8,
                            atol=1e-10, t_eval=te)
        t0, c0 = time.perf_counter(), time.process_time()
        runs = batch()
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        sample = 20 if quick else 50
        picks, times, loop, worst = loop_of_single_runs(single, runs, sample)
        c0 = time.process_time()
        simulate(m, (0.0, t_end), q0, qd0, inputs=inputs, loads=loads, rtol=1e-8, atol=1e-10,
                 t_eval=te, threads=1)
        cpu_1 = time.process_time() - c0
        print(f"batch of {B} runs of {t_end:g} s (random initial angle and speed, rtol 1e-8, 101 outputs):")
        print(f"  batch: {cpu_1:.2f} s process time on 1 thread; on 2 threads {wall:.2f} s wall "
              f"({cpu:.2f} s process time); {int(np.sum(runs.nfev)):,} evaluations")
        print(f"  loop of single runs, estimated from {sample} of them: {loop:.2f} s process time "
              f"(best {min(times) * 1e3:.1f} ms, median {statistics.median(times) * 1e3:.1f} ms per run)")
        print(f"  ratio loop / batch (process time, 1 thread): {loop / cpu_1:.2f}x; "
              f"largest |batch - single| {worst:.1e} rad")
        if t_end == 1.0:
            t1 = time.process_time()
            slow = [simulate(m, (0.0, t_end), q0[i], qd0[i], inputs={"jO2": lambda t, q, qd: 20 - 0.2 * qd},
                             loads=loads, rtol=1e-8, atol=1e-10, t_eval=te) for i in picks[:3]]
            python_loop = (time.process_time() - t1) / len(slow) * B
            print(f"  loop of single runs with the right-hand side in Python (a callable motor law, "
                  f"solve_ivp), estimated from 3: {python_loop:.0f} s; ratio to the batch "
                  f"{python_loop / cpu_1:.0f}x")
    designs(B, quick)


def loop_of_single_runs(single, runs, sample):
    """A loop of single runs over the batch ``runs``, estimated from ``sample`` of them:
    the runs timed, their process times, the loop's estimated time and the largest
    difference from the batch (rad)."""
    B = len(runs)
    picks = np.linspace(0, B - 1, sample).astype(int)
    times, worst = [], 0.0
    for i in picks:
        t1 = time.process_time()
        one = single(i)
        times.append(time.process_time() - t1)
        worst = max(worst, float(np.max(np.abs(one.q - runs.q[i]))))
    return picks, times, statistics.mean(times) * B, worst


def designs(B, quick):
    """B engines, each with its own flywheel and motor, from rest: a model and a law per run."""
    from tests.dynamics.models import engine as engine_of

    rng = np.random.default_rng(2)
    inertias, torques = rng.uniform(0.004, 0.1, B), rng.uniform(10.0, 30.0, B)
    loads = Loads(gravity=(0.0, -9.81), forces=[PointForce("B", (GAS, 0.0), link="slider")])
    te = np.linspace(0.0, 1.0, 101)
    t0 = time.process_time()
    models = [engine_of(crank_inertia=j) for j in inertias]
    laws = [f"{tq:.6g} - 0.2 * qd" for tq in torques]
    built = time.process_time() - t0

    def run(i):     # a model of its own, as a loop would build it (a model keeps its plan)
        return simulate(engine_of(crank_inertia=inertias[i]), (0.0, 1.0), 0.0, 0.0,
                        inputs={"jO2": laws[i]}, loads=loads, rtol=1e-8, atol=1e-10, t_eval=te)
    c0 = time.process_time()
    runs = simulate(models, (0.0, 1.0), 0.0, 0.0, inputs={"jO2": laws}, loads=loads, rtol=1e-8,
                    atol=1e-10, t_eval=te, threads=1)
    cpu = time.process_time() - c0
    sample = 20 if quick else 50
    _, _, loop, worst = loop_of_single_runs(run, runs, sample)
    print(f"batch of {B} engines of 1 s, each its own flywheel (0.004-0.1 kg m^2) and motor torque "
          f"(models built in {built:.2f} s):")
    print(f"  batch: {cpu:.2f} s process time on 1 thread; loop of single runs, estimated from "
          f"{sample}: {loop:.2f} s; ratio {loop / cpu:.2f}x; largest |batch - single| {worst:.1e} rad")


if __name__ == "__main__":
    main()
