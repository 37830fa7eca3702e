"""Other libraries doing kinelab's work, for speed ratios measured in one process.

Each peer is optional: ``HAVE_PYLINKAGE`` and ``HAVE_PYSLVS`` say whether it can be
imported, and a benchmark skips it, printing "not installed", when it cannot
(``pip install -e .[bench]`` brings pylinkage).  Imported from the scripts in
``benchmarks/`` through ``sys.path`` (the script's own folder is on it).

pylinkage (1.3) builds a mechanism from a ground, a crank and dyads, and moves it with a
numba kernel working on flat arrays (``pylinkage.solver.SolverData``).  The crank turns
by a fixed increment per step, and each RRR dyad takes the circle intersection nearest
its previous position: the assembly branch is carried from step to step, set by the
starting position.  So

- one configuration: write the crank pin, then one call of the per-step kernel
  ``pylinkage.solver.simulation.step_single`` with ``dt = 0`` (the same kernel
  ``Linkage.step_fast`` loops over; a Python ``Linkage.step()`` is some 30 times slower);
- a sweep: ``pylinkage.solver.simulate`` over uniformly spaced angles (crank
  increment = the spacing, ``dt = 1``), the loop ``Linkage.step_fast`` calls, without
  its copies in and out of the Python objects.  Its closed-form alternative,
  ``pylinkage.symbolic`` (lambdified sympy expressions), is some ten times slower;
- path synthesis: ``pylinkage.optimization.particle_swarm_optimization`` with a fitness
  function that runs that same kernel on a template ``SolverData``.

pyslvs (22.7.0, the last release) does not build on Python 3.11: its Cython sources need
a Cython 3 pre-release and fail with the current one
("pyslvs/bfgs.pyx:104:38: Too many members for 'const Point &'"), so ``HAVE_PYSLVS`` is
False unless a build of it can be imported.

Error measure of a synthesised path (:func:`path_error`), the one kinelab's benchmarks
report: the RMS distance from each target point to the nearest point of the coupler curve
(a polyline through its samples), divided by the size of the target path (the diagonal
of its bounding box).

    python benchmarks/peers.py        (checks and rough timings of the installed peers)
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

try:
    import pylinkage  # noqa: F401
    HAVE_PYLINKAGE = True
except ImportError:
    HAVE_PYLINKAGE = False

try:
    import pyslvs  # noqa: F401
    HAVE_PYSLVS = True
except ImportError:
    HAVE_PYSLVS = False

NAMES = ("O2", "A", "B", "O4", "P")     # the rows of pylinkage's positions, kinelab's names

# The ellipse 2 x 1 of benchmarks/synthesis.py: 10 points over 270 degrees.
ELLIPSE_10 = np.column_stack([2 * np.cos(np.radians(np.linspace(0, 270, 10))),
                              np.sin(np.radians(np.linspace(0, 270, 10)))])


def _require(flag: bool, name: str) -> None:
    if not flag:
        raise ImportError(f"{name} is not installed; pip install -e .[bench]")


def path_error(curve_xy, target_xy) -> float:
    """RMS distance from the targets to a curve, divided by the size of the targets.

    Parameters
    ----------
    curve_xy : array_like, shape (m, 2)
        Samples of the curve, m, joined in order by straight segments (repeat the first
        sample at the end to close it).  Rows with NaN break the polyline there.
    target_xy : array_like, shape (n, 2)
        The target points, m.

    Returns
    -------
    float
        ``sqrt(mean(d_i^2)) / size``, d_i the distance from target i to the nearest point
        of the polyline and ``size`` the diagonal of the targets' bounding box.

    Examples
    --------
    >>> a = np.linspace(0, 2 * np.pi, 9)
    >>> circle = np.column_stack([np.cos(a), np.sin(a)])
    >>> float(path_error(circle, 1.5 * circle[:8]))        # 0.5 off, box 3 x 3
    0.11785113019775792
    """
    C = np.asarray(curve_xy, float)
    T = np.asarray(target_xy, float)
    if C.ndim != 2 or C.shape[1] != 2 or T.ndim != 2 or T.shape[1] != 2 or len(T) == 0:
        raise ValueError(f"expected curve (m, 2) and targets (n, 2), got {C.shape} and {T.shape}")
    size = math.hypot(*np.ptp(T, axis=0))
    if not size > 0:
        raise ValueError("the targets are all at one point: their size is zero")
    fin = np.all(np.isfinite(C), axis=1)
    if not fin.any():
        return math.inf
    V = C[fin]
    d2 = np.min(np.sum((T[:, None, :] - V[None, :, :]) ** 2, axis=-1), axis=1)
    seg = fin[:-1] & fin[1:]
    if seg.any():
        P0, E = C[:-1][seg], (C[1:] - C[:-1])[seg]
        D = T[:, None, :] - P0[None, :, :]                                   # (n, s, 2)
        ee = np.sum(E * E, axis=-1)
        t = np.clip(np.sum(D * E, axis=-1) / np.where(ee > 0, ee, 1.0), 0.0, 1.0)
        d2 = np.minimum(d2, np.min(np.sum((D - t[..., None] * E) ** 2, axis=-1), axis=1))
    return float(math.sqrt(np.mean(d2)) / size)


def _circle_left(X, Z, lx: float, lz: float, sigma: float = 1.0):
    """The intersection of circles (X, lx) and (Z, lz) to the left (sigma = +1) of X -> Z,
    or None where they do not meet."""
    X, Z = np.asarray(X, float), np.asarray(Z, float)
    d = Z - X
    D = math.hypot(*d)
    if D == 0:
        return None
    a = (lx ** 2 - lz ** 2 + D ** 2) / (2 * D)
    h2 = lx ** 2 - a ** 2
    if h2 < 0:
        return None
    e = d / D
    return X + a * e + sigma * math.sqrt(h2) * np.array([-e[1], e[0]])


# --------------------------------------------------------------------------------------
# pylinkage

@dataclass(frozen=True, eq=False)
class PylinkageFourbar:
    """A pylinkage four-bar and the numba solver's arrays for it.

    ``data.positions`` (rows :data:`NAMES`) is the linkage's current configuration, the
    one the next :func:`pylinkage_one_step` starts from.
    """

    linkage: object                 # pylinkage.simulation.Linkage
    data: object                    # pylinkage.solver.SolverData
    crank: float
    rate_index: int                 # the crank's increment in data.constraints

    @property
    def kernel_args(self) -> tuple:
        d = self.data
        return (d.constraints, d.joint_types, d.parent_indices, d.constraint_offsets,
                d.solve_order)


def pylinkage_fourbar(ground: float, crank: float, coupler: float, rocker: float,
                      coupler_point: tuple[float, float] = (0.0, 0.0), q: float = 0.0
                      ) -> PylinkageFourbar:
    """kinelab's catalogue four-bar (``kl.mechanisms.fourbar``, open branch) in pylinkage.

    O2 at the origin, O4 at ``(ground, 0)``, crank pin A, rocker pin B (the circle
    intersection to the left of the line from A to O4, kinelab's "open" branch), and the
    coupler point P at ``coupler_point = (along AB, to the left of AB)`` from A, as a
    pylinkage ``FixedDyad`` (distance and angle from A, measured from A -> B).

    Parameters
    ----------
    ground, crank, coupler, rocker : float
        Link lengths, m.
    coupler_point : (float, float)
        P in the coupler's frame, m.
    q : float
        Crank angle of the starting configuration, rad.
    """
    _require(HAVE_PYLINKAGE, "pylinkage")
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import FixedDyad, RRRDyad
    from pylinkage.simulation import Linkage
    from pylinkage.solver import linkage_to_solver_data

    A = np.array([crank * math.cos(q), crank * math.sin(q)])
    B = _circle_left(A, (ground, 0.0), coupler, rocker)
    if B is None:
        raise ValueError(f"the four-bar does not assemble at q = {q} rad")
    px, py = coupler_point
    O2 = Ground(0.0, 0.0, name="O2")
    O4 = Ground(float(ground), 0.0, name="O4")
    cr = Crank(O2, radius=float(crank), angular_velocity=0.0, initial_angle=float(q), name="A")
    rb = RRRDyad(cr.output, O4, float(coupler), float(rocker), x=float(B[0]), y=float(B[1]),
                 name="B")
    cp = FixedDyad(cr.output, rb, distance=math.hypot(px, py), angle=math.atan2(py, px), name="P")
    linkage = Linkage([O2, cr, rb, O4, cp], name="fourbar")
    data = linkage_to_solver_data(linkage)
    fb = PylinkageFourbar(linkage, data, float(crank), int(data.constraint_offsets[1]) + 1)
    pylinkage_one_step(fb, q)                    # P from A and B
    return fb


def pylinkage_one_step(linkage: PylinkageFourbar, angle: float) -> np.ndarray:
    """Positions of O2, A, B, O4, P (rows, m), shape (5, 2), at one crank angle (rad).

    The crank pin is written at ``angle`` and the kernel solves B and P once; B is the
    intersection nearest its previous position (pylinkage's branch rule), so a call
    continues from the configuration the last one left.
    """
    from pylinkage.solver.simulation import step_single

    pos = linkage.data.positions
    pos[1, 0] = linkage.crank * math.cos(angle)
    pos[1, 1] = linkage.crank * math.sin(angle)
    step_single(pos, *linkage.kernel_args, 0.0)
    return pos.copy()


def pylinkage_sweep(linkage: PylinkageFourbar, angles) -> np.ndarray:
    """Positions of O2, A, B, O4, P over uniformly spaced crank angles, shape (N, 5, 2), m.

    The sweep starts from the linkage's current configuration (which it leaves as it
    was): the crank is set one increment before ``angles[0]`` and the numba loop turns it
    by ``angles[1] - angles[0]`` per step.
    """
    from pylinkage.solver import simulate

    q = np.asarray(angles, float)
    if q.ndim != 1 or q.size < 2:
        raise ValueError(f"angles: expected at least two angles, shape (N,), got {q.shape}")
    dq = q[1] - q[0]
    if np.abs(np.diff(q) - dq).max() > 1e-12 * max(1.0, np.abs(q).max()):
        raise ValueError("angles: pylinkage turns the crank by a fixed increment; give "
                         "uniformly spaced angles")
    d = linkage.data
    pos = d.positions.copy()
    pos[1] = linkage.crank * math.cos(q[0] - dq), linkage.crank * math.sin(q[0] - dq)
    c = d.constraints.copy()
    c[linkage.rate_index] = dq
    return simulate(pos, c, d.joint_types, d.parent_indices, d.constraint_offsets,
                    d.solve_order, q.size, 1.0)


def check_pylinkage() -> float:
    """Largest distance (m) between pylinkage's and kinelab's positions of O2, A, B, O4
    and P, over a turn of the crank-rocker 3, 1, 3, 2.5 with P = (1.5, 1.0), one step at
    a time (both senses) and as sweeps."""
    import kinelab as kl

    args = (3.0, 1.0, 3.0, 2.5)
    cp = (1.5, 1.0)
    model = kl.mechanisms.fourbar(*args, coupler_point=cp)
    worst = 0.0
    for q in (np.linspace(0.0, 2 * np.pi, 361), np.linspace(2.0, 2.0 - 2 * np.pi, 200)):
        sol = kl.analyze(model, q)
        ref = np.stack([sol.position(n) for n in NAMES], axis=1)          # (N, 5, 2)
        fb = pylinkage_fourbar(*args, coupler_point=cp, q=q[0])
        steps = np.stack([pylinkage_one_step(fb, qi) for qi in q])
        sweep = pylinkage_sweep(pylinkage_fourbar(*args, coupler_point=cp, q=q[0]), q)
        worst = max(worst, np.abs(steps - ref).max(), np.abs(sweep - ref).max())
    return float(worst)


class PeerSynthesis(NamedTuple):
    error: float            # path_error of the best linkage, on a curve of 3600 samples
    seconds: float          # wall time of the search
    evaluations: int        # fitness evaluations (linkages simulated)


_BOUNDS = ([-3.0] * 4 + [0.05, 0.05, 0.05, -4.0, -4.0, -1.0],
           [3.0] * 4 + [3.0, 6.0, 6.0, 4.0, 4.0, 1.0])      # kinelab's, for a unit-size task


def pylinkage_path_synthesis(target_points, *, n_particles: int = 100, iterations: int = 200,
                             samples: int = 180, seed: int = 0) -> PeerSynthesis:
    """A four-bar whose coupler curve passes near the targets, by pylinkage's particle swarm.

    The design is kinelab's (``kl.synthesis.path_generation``): pivots O2 and O4, crank,
    coupler and rocker lengths, coupler point (u along AB, v to its left) and the branch
    (the sign of the last entry), with kinelab's bounds, the task centred and scaled to
    unit size.  The fitness is :func:`path_error` on ``samples`` crank angles over a full
    turn; a linkage that does not assemble over the whole turn scores infinity (pylinkage
    moves only full-turn cranks, as its ``kinematic_minimization`` does).  The swarm is
    ``pylinkage.optimization.particle_swarm_optimization`` with its default coefficients.

    pylinkage's swarm draws from an unseeded ``np.random.default_rng()``; it is given
    ``default_rng(seed)`` for the run, so a result can be reproduced.

    Returns
    -------
    PeerSynthesis
        (error, seconds, evaluations).
    """
    _require(HAVE_PYLINKAGE, "pylinkage")
    from unittest import mock

    from pylinkage.optimization import particle_swarm_optimization
    from pylinkage.solver import simulate

    T = np.asarray(target_points, float)
    center = T.mean(axis=0)
    scale = float(np.linalg.norm(T - center, axis=1).max())
    Tn = (T - center) / scale
    template = pylinkage_fourbar(3.0, 1.0, 3.0, 2.5, (1.5, 1.0))
    d = template.data
    kernel = (d.joint_types, d.parent_indices, d.constraint_offsets, d.solve_order)
    offsets = d.constraint_offsets
    evaluations = 0

    def curve(x, n):
        """P over a full turn, n + 1 samples (closed), or None."""
        o2, o4 = np.array(x[0:2]), np.array(x[2:4])
        crank, coupler, rocker, u, v, branch = x[4:10]
        dq = 2 * np.pi / n
        A = o2 + crank * np.array([1.0, 0.0])
        B = _circle_left(A, o4, coupler, rocker, 1.0 if branch >= 0 else -1.0)
        if B is None:
            return None
        pos = np.empty((5, 2))
        pos[0], pos[3], pos[2] = o2, o4, B
        pos[1] = o2 + crank * np.array([math.cos(-dq), math.sin(-dq)])
        pos[4] = A
        c = d.constraints.copy()
        c[offsets[1]], c[offsets[1] + 1] = crank, dq
        c[offsets[2]], c[offsets[2] + 1] = coupler, rocker
        c[offsets[4]], c[offsets[4] + 1] = math.hypot(u, v), math.atan2(v, u)
        P = simulate(pos, c, *kernel, n + 1, 1.0)[:, 4]
        return None if np.isnan(P).any() else P

    def fitness(_linkage, params, _init_pos):
        nonlocal evaluations
        evaluations += 1
        P = curve(params, samples)
        return math.inf if P is None else path_error(P, Tn)

    real_rng = np.random.default_rng
    t0 = time.perf_counter()
    with mock.patch("numpy.random.default_rng", lambda *a, **k: real_rng(seed)):
        best = particle_swarm_optimization(
            fitness, template.linkage, dimensions=len(_BOUNDS[0]), n_particles=n_particles,
            iterations=iterations, bounds=_BOUNDS, order_relation=min, verbose=False)
    seconds = time.perf_counter() - t0
    x = np.asarray(best.dimensions[0], float)
    P = curve(x, 3600)
    error = math.inf if P is None else path_error(P, Tn)
    return PeerSynthesis(error, seconds, evaluations)


# --------------------------------------------------------------------------------------

def main():
    if not HAVE_PYLINKAGE:
        print("pylinkage: not installed")
    else:
        print(f"pylinkage {pylinkage.__version__}: largest difference from kinelab "
              f"{check_pylinkage():.1e} m")
        fb = pylinkage_fourbar(3.0, 1.0, 3.0, 2.5, (1.5, 1.0))
        q = np.linspace(0.0, 2 * np.pi, 1000)
        n = 20_000
        t0 = time.perf_counter()
        for i in range(n):
            pylinkage_one_step(fb, q[i % 1000])
        print(f"  one step: {(time.perf_counter() - t0) / n * 1e6:.2f} us")
        for m in (1_000, 100_000):
            qs = np.linspace(0.0, 2 * np.pi, m)
            best = np.inf
            for _ in range(5):
                t0 = time.perf_counter()
                pylinkage_sweep(fb, qs)
                best = min(best, time.perf_counter() - t0)
            print(f"  sweep of {m:,}: {best / m * 1e6:.3f} us per configuration")
        r = pylinkage_path_synthesis(ELLIPSE_10)
        print(f"  particle swarm on the 10-point ellipse: error {r.error:.3g}, {r.seconds:.1f} s, "
              f"{r.evaluations:,} evaluations")
    if not HAVE_PYSLVS:
        print("pyslvs: not installed")


if __name__ == "__main__":
    main()
