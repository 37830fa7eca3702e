"""A reference for the forward-dynamics benchmark: the slider-crank engine of
``tests/dynamics/models.py::engine()`` derived by hand with sympy and integrated by
scipy, sharing nothing with kinelab's dynamics but the model's numbers.

The run is the one ``benchmarks/dynamics.py`` times: 10 s from rest at q = 0, motor
torque ``20 - 0.2 q'`` N m on the crank, gravity (0, -9.81) m/s^2 and a gas force on the
wrist pin B along x,

    F(q) = -2000 exp(-(((q + 2 pi) mod 4 pi) - 2 pi - 0.3)^2 / 0.2) N,

a pulse once per two turns, as in a four-stroke engine.  The one coordinate is the crank
angle q; Lagrange's equation of the second kind,

    d/dt (dT/dq') - dT/dq + dV/dq = tau + F dxB/dq,

is formed from the kinetic energy of crank, rod and piston and the potential energy of
their weights, and solved for q''.  The right-hand side is a ``sympy.lambdify``'d scalar
function (``math`` module, common subexpressions shared).

``reference_engine`` uses DOP853 by default: at rtol 1e-8 it takes about half the right-
hand-side evaluations of RK45 and so half the time (the right-hand side is a few
microseconds; the integrator's own Python is most of the cost).  ``engine_truth`` runs
DOP853 at rtol 1e-13 to measure the error of the others.

    .venv/bin/python benchmarks/dynamics_reference.py    (the comparison with kinelab)
"""
from __future__ import annotations

import math
import sys
import time
from functools import lru_cache
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

GRAVITY = 9.81          # m/s^2, along -y
TORQUE = (20.0, 0.2)    # motor torque tau = a - b q', N m and N m s
GAS = "-2000 * exp(-(((q + 2 * pi) % (4 * pi) - 2 * pi - 0.3) ** 2) / 0.2)"   # N, kinelab's form


def engine_model():
    """The benchmark's engine (``tests/dynamics/models.py::engine()``)."""
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    from tests.dynamics.models import engine
    return engine()


def engine_parameters(model=None) -> dict:
    """The numbers the equations need, read from the model's sketch and mass data.

    Lengths in m, masses in kg, inertias about the centres of mass in kg m^2.  The centres
    of mass are given in each link's frame: ``(u2, v2)`` from O2 along O2->A and to its
    left, ``(u3, v3)`` from A along A->B and to its left; the piston's is at B.
    """
    m = engine_model() if model is None else model
    xy = {p.name: np.array(p.xy) for p in m.points}

    def local(origin, toward, point):
        e = xy[toward] - xy[origin]
        e = e / np.linalg.norm(e)
        d = xy[point] - xy[origin]
        return float(d @ e), float(e[0] * d[1] - e[1] * d[0])

    crank, rod, piston = m.link("crank"), m.link("rod"), m.link("slider")
    if piston.center_of_mass != "B":
        raise ValueError(f"the piston's centre of mass must be B, got {piston.center_of_mass!r}")
    u2, v2 = local("O2", "A", crank.center_of_mass)
    u3, v3 = local("A", "B", rod.center_of_mass)
    return dict(r=float(np.linalg.norm(xy["A"] - xy["O2"])), l=float(np.linalg.norm(xy["B"] - xy["A"])),
                e=float(xy["B"][1] - xy["O2"][1]),
                m2=crank.mass, I2=crank.inertia, u2=u2, v2=v2,
                m3=rod.mass, I3=rod.inertia, u3=u3, v3=v3, m4=piston.mass)


PARAMETERS = ("r", "l", "e", "m2", "I2", "u2", "v2", "m3", "I3", "u3", "v3", "m4")


@lru_cache(maxsize=1)
def equations():
    """q'' as a sympy expression of ``q, qd`` and the symbols of :data:`PARAMETERS`.

    The geometry (right-hand branch, B to the +x side of A; slide line y = e):

        A = r (cos q, sin q),   B = (r cos q + sqrt(l^2 - (e - r sin q)^2), e),
        phi = atan2(e - r sin q, sqrt(l^2 - (e - r sin q)^2))   (the rod's angle),
        G2 = R(q) (u2, v2),     G3 = A + R(phi) (u3, v3).

    With one coordinate every velocity is a position's derivative times q', so
    T = 1/2 M(q) q'^2 with M = m2 |dG2/dq|^2 + I2 + m3 |dG3/dq|^2 + I3 (dphi/dq)^2
    + m4 (dxB/dq)^2, and Lagrange's equation d/dt (dT/dq') - dT/dq + dV/dq = Q reads

        M q'' + 1/2 M'(q) q'^2 + V'(q) = tau(q') + F(q) dxB/dq,

    with V = g (m2 yG2 + m3 yG3 + m4 e).

    Returns
    -------
    q, qd : sympy.Symbol
    params : tuple of sympy.Symbol, in the order of :data:`PARAMETERS`
    qdd : sympy.Expr
    """
    import sympy as sp

    q, qd = sp.symbols("q qd", real=True)
    params = sp.symbols(PARAMETERS, real=True)
    r, l, e, m2, I2, u2, v2, m3, I3, u3, v3, m4 = params
    h = e - r * sp.sin(q)
    w = sp.sqrt(l ** 2 - h ** 2)
    A = sp.Matrix([r * sp.cos(q), r * sp.sin(q)])
    xB = A[0] + w
    phi = sp.atan2(h, w)

    def rot(a, u, v):
        return sp.Matrix([u * sp.cos(a) - v * sp.sin(a), u * sp.sin(a) + v * sp.cos(a)])

    G2 = rot(q, u2, v2)
    G3 = A + rot(phi, u3, v3)

    def sq(P):
        d = P.diff(q)
        return d.dot(d)

    M = m2 * sq(G2) + I2 + m3 * sq(G3) + I3 * phi.diff(q) ** 2 + m4 * xB.diff(q) ** 2
    V = GRAVITY * (m2 * G2[1] + m3 * G3[1] + m4 * e)
    gas = -2000 * sp.exp(-(sp.Mod(q + 2 * sp.pi, 4 * sp.pi) - 2 * sp.pi - sp.Rational(3, 10)) ** 2
                         / sp.Rational(1, 5))
    Q = TORQUE[0] - TORQUE[1] * qd + gas * xB.diff(q)
    qdd = (Q - M.diff(q) * qd ** 2 / 2 - V.diff(q)) / M
    return q, qd, params, qdd


@lru_cache(maxsize=1)
def _compiled():
    import sympy as sp

    q, qd, params, qdd = equations()
    return sp.lambdify((q, qd) + params, qdd, modules="math", cse=True)


def reference_engine(t_end: float = 10.0, rtol: float = 1e-8, atol: float = 1e-10,
                     t_eval=None, method: str = "DOP853", params: dict | None = None):
    """The engine's motion from rest at q = 0, by the sympy equations and ``solve_ivp``.

    Parameters
    ----------
    t_end : float
        End time, s (the run starts at 0).
    rtol, atol : float
        ``solve_ivp``'s tolerances.
    t_eval : array_like, shape (N,), optional
        Output times, s (default: the integrator's steps).
    method : str
        A ``solve_ivp`` method ("DOP853", "RK45", "Radau", ...).
    params : dict, optional
        From :func:`engine_parameters` (default: the benchmark's engine).

    Returns
    -------
    t : ndarray, shape (N,)
    q, qd : ndarray, shape (N,)
        Crank angle (rad) and speed (rad/s).
    """
    from scipy.integrate import solve_ivp

    p = engine_parameters() if params is None else params
    f = _compiled()
    values = tuple(float(p[k]) for k in PARAMETERS)

    def rhs(_t, y):
        return (y[1], f(y[0], y[1], *values))

    sol = solve_ivp(rhs, (0.0, t_end), [0.0, 0.0], method=method, rtol=rtol, atol=atol,
                    t_eval=None if t_eval is None else np.asarray(t_eval, float))
    if not sol.success:
        raise RuntimeError(f"solve_ivp ({method}) failed: {sol.message}")
    return sol.t, sol.y[0], sol.y[1]


def engine_truth(t_eval, t_end: float | None = None):
    """The high-accuracy run (DOP853, rtol 1e-13, atol 1e-13) at ``t_eval``: t, q, qd.

    ``t_end`` defaults to the last of ``t_eval``.  Agrees with Radau at rtol 1e-13 to
    about 1e-9 rad after 10 s (``__main__`` prints it).
    """
    t_eval = np.asarray(t_eval, float)
    return reference_engine(float(t_eval[-1]) if t_end is None else t_end, rtol=1e-13,
                            atol=1e-13, t_eval=t_eval, method="DOP853")


def kinelab_engine(t_end: float = 10.0, rtol: float = 1e-8, atol: float = 1e-10, t_eval=None,
                   method: str = "DOP853"):
    """The same run by ``kinelab.dynamics.simulate`` (as ``benchmarks/dynamics.py`` does):
    t, q, qd, and the Simulation."""
    from kinelab.dynamics import Loads, PointForce, simulate

    loads = Loads(gravity=(0.0, -GRAVITY), forces=[PointForce("B", (GAS, 0.0), link="slider")])
    sim = simulate(engine_model(), (0.0, t_end), q0=0.0, qd0=0.0,
                   inputs={"jO2": f"{TORQUE[0]} - {TORQUE[1]} * qd"}, loads=loads,
                   method=method, rtol=rtol, atol=atol, t_eval=t_eval)
    return sim.t, sim.q[:, 0], sim.qd[:, 0], sim


def main():
    t_eval = np.linspace(0.0, 10.0, 1001)
    t0 = time.perf_counter()
    _, q_true, qd_true = engine_truth(t_eval)
    print(f"truth (DOP853, rtol 1e-13): {time.perf_counter() - t0:.2f} s wall; final q = "
          f"{q_true[-1]:.9f} rad, q' = {qd_true[-1]:.9f} rad/s")
    _, q_radau, _ = reference_engine(10.0, 1e-13, 1e-13, t_eval, method="Radau")
    print(f"  Radau at rtol 1e-13 differs from it by {np.abs(q_radau - q_true).max():.1e} rad")
    print("sympy + scipy reference against the truth")
    for method in ("DOP853", "RK45"):
        for rtol, atol in ((1e-8, 1e-10), (1e-10, 1e-12)):
            best = np.inf
            for _ in range(3):
                t0 = time.perf_counter()
                _, q, qd = reference_engine(10.0, rtol, atol, t_eval, method=method)
                best = min(best, time.perf_counter() - t0)
            print(f"  {method:6s} rtol={rtol:.0e}: {best:6.3f} s wall, |q - truth| "
                  f"{np.abs(q - q_true).max():.1e} rad, |q' - truth| {np.abs(qd - qd_true).max():.1e} rad/s")
    print("kinelab.dynamics.simulate against the truth and the reference")
    for rtol, atol in ((1e-8, 1e-10), (1e-10, 1e-12)):
        t0 = time.perf_counter()
        _, q, qd, sim = kinelab_engine(10.0, rtol, atol, t_eval)
        dt = time.perf_counter() - t0
        _, q_ref, qd_ref = reference_engine(10.0, rtol, atol, t_eval)
        print(f"  rtol={rtol:.0e}: {dt:6.2f} s wall, {sim.nfev:,} evaluations; |q - truth| "
              f"{np.abs(q - q_true).max():.1e} rad, |q - reference| {np.abs(q - q_ref).max():.1e} rad, "
              f"|q' - reference| {np.abs(qd - qd_ref).max():.1e} rad/s")


if __name__ == "__main__":
    main()
