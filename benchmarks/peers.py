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
  ``pylinkage.solver.simulation.step_single`` with ``dt = 0`` (the kernel
  ``Linkage.step_fast`` loops over); a step of the Python ``Linkage.step()`` generator
  takes two to four times as long;
- a sweep: ``pylinkage.solver.simulate`` over uniformly spaced angles (crank
  increment = the spacing, ``dt = 1``), the loop ``Linkage.step_fast`` calls, without
  its copies in and out of the Python objects: some 0.2 to 0.5 us a configuration,
  30 to 50 times faster than ``Linkage.step()``.  pylinkage's closed form,
  ``pylinkage.symbolic`` (lambdified sympy expressions over an array of angles), is
  some 10 to 20 times slower than this loop;
- path synthesis: ``pylinkage.optimization.particle_swarm_optimization`` with a fitness
  function that runs that same loop on a template ``SolverData``.

pyslvs 22.7.0 (the last release, AGPL) ships only a source distribution, and a plain
``pip install pyslvs`` fails on Python 3.11: it asks for ``cython >= 3.0a6``, and the
newest Cython, which an isolated build takes, rejects its sources
("pyslvs/bfgs.pyx:104:38: Too many members for 'const Point &'").  It builds with
Cython 3.0.0 (several minutes of C++)::

    pip install cython==3.0.0 setuptools wheel
    pip install --no-build-isolation pyslvs

so it is not in the ``bench`` extra, and ``HAVE_PYSLVS`` is True only where it was built
that way.  Its path synthesis, :func:`pyslvs_path_synthesis`, runs its differential
evolution on its own objective.

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
    # x and y apart: reductions over a last axis of length 2 would dominate the cost.
    tx, ty = T[:, :1], T[:, 1:]
    seg = fin[:-1] & fin[1:]
    alone = fin.copy()                                      # finite, on no segment
    alone[:-1] &= ~seg
    alone[1:] &= ~seg
    d2 = np.full(len(T), np.inf)
    if seg.any():
        x0, y0 = C[:-1, 0][seg], C[:-1, 1][seg]
        ex, ey = C[1:, 0][seg] - x0, C[1:, 1][seg] - y0
        dx, dy = tx - x0, ty - y0                                        # (n, s)
        ee = ex * ex + ey * ey
        t = np.clip((dx * ex + dy * ey) / np.where(ee > 0, ee, 1.0), 0.0, 1.0)
        rx, ry = dx - t * ex, dy - t * ey
        d2 = (rx * rx + ry * ry).min(axis=1)
    if alone.any():
        d2 = np.minimum(d2, ((tx - C[alone, 0]) ** 2 + (ty - C[alone, 1]) ** 2).min(axis=1))
    return float(math.sqrt(np.mean(d2)) / size)


def _circle_left(X, Z, lx: float, lz: float, sigma: float = 1.0):
    """The intersection of circles (X, lx) and (Z, lz) to the left (sigma = +1) of X -> Z,
    as an array of shape (2,), or None where they do not meet."""
    dx, dy = Z[0] - X[0], Z[1] - X[1]
    D = math.hypot(dx, dy)
    if D == 0:
        return None
    a = (lx ** 2 - lz ** 2 + D ** 2) / (2 * D)
    h2 = lx ** 2 - a ** 2
    if h2 < 0:
        return None
    ex, ey, h = dx / D, dy / D, sigma * math.sqrt(h2)
    return np.array([X[0] + a * ex - h * ey, X[1] + a * ey + h * ex])


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
        """P over a full turn from the crank at +x, n + 1 samples (closed), or None."""
        ax, ay, bx, by, crank, coupler, rocker, u, v, branch = x
        dq = 2 * np.pi / n
        B = _circle_left((ax + crank, ay), (bx, by), coupler, rocker, 1.0 if branch >= 0 else -1.0)
        if B is None:
            return None
        pos = np.array([(ax, ay), (ax + crank * math.cos(dq), ay - crank * math.sin(dq)),
                        B, (bx, by), (ax + crank, ay)])
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
# pyslvs

def pyslvs_path_synthesis(target_points, *, pop_num: int = 400, max_gen: int = 1000,
                          seed: int = 0) -> PeerSynthesis:
    """A four-bar whose coupler point passes near the targets, by pyslvs' differential
    evolution (``pyslvs.metaheuristics``, DE with its default settings) on its path
    objective ``pyslvs.optimization.FPlanar``.

    pyslvs' design is the pivots O2 and O4, the lengths O2A, AB, O4B, AP, the angle of P
    from A -> B, and one crank angle per target (the timing is a variable); its fitness is
    the sum of the distances from the coupler point at those angles to the targets.  The
    mechanism is pyslvs' catalogue "Four bar linkage mechanism" (B on kinelab's "open"
    side), the task centred and scaled to unit size, the pivots in [-3, 3] and the lengths
    in [0.05, 6] as in kinelab's search.  The error returned is :func:`path_error` of the
    best linkage's coupler curve over a full turn (3600 samples, broken where the loop
    does not close), so it compares with the other peers'.

    pyslvs draws from the C library's ``rand()``, seeded from the clock when an algorithm
    is built; it is reseeded with ``srand(seed)`` before the run, so a result can be
    reproduced (glibc's ``srand(0)`` is ``srand(1)``: seeds 0 and 1 give one run).

    Returns
    -------
    PeerSynthesis
        (error, seconds, evaluations).
    """
    _require(HAVE_PYSLVS, "pyslvs")
    import ctypes

    from pyslvs import collection_list, parse_vpoints, t_config
    from pyslvs.metaheuristics import AlgorithmType, algorithm, default
    from pyslvs.optimization import FPlanar

    T = np.asarray(target_points, float)
    center = T.mean(axis=0)
    scale = float(np.linalg.norm(T - center, axis=1).max())
    Tn = (T - center) / scale
    fourbar = collection_list("Four bar linkage mechanism")
    vpoints = parse_vpoints(fourbar["expression"])
    inputs = list(fourbar["input"])
    stack = t_config(vpoints, tuple(pair for pair, _ in inputs)).as_list()
    if [e[0] for e in stack] != ["PLA", "PLLP", "PLAP"] or stack[1][4:] != ("P1", "P3"):
        raise RuntimeError(f"pyslvs' four-bar is solved in an unexpected order: {stack}")
    sketch = np.array([vp.c[0] for vp in vpoints])
    d, e = sketch[1] - sketch[2], sketch[3] - sketch[2]          # A -> O4, A -> B
    side = 1.0 if d[0] * e[1] - d[1] * e[0] > 0 else -1.0
    objective = FPlanar({"expression": vpoints, "input": inputs,
                         "placement": {0: (0.0, 0.0, 3.0), 1: (0.0, 0.0, 3.0)},
                         "target": {4: [tuple(p) for p in Tn]}, "upper": 6.0, "lower": 0.05})
    settings = default(AlgorithmType.DE)
    settings.update(pop_num=pop_num, max_gen=max_gen, report=max_gen)
    de = algorithm(AlgorithmType.DE)(objective, settings)
    ctypes.CDLL(None).srand(seed)
    t0 = time.perf_counter()
    de.run()
    seconds = time.perf_counter() - t0
    v, fitness = de.result()
    # v = [O2x, O2y, O4x, O4y, O2A, AB, O4B, AP, angle of P from A->B, crank angles...]
    o2, o4 = v[0:2], v[2:4]
    crank, coupler, rocker, ap, angle = v[4:9]

    def coupler_point(q):
        A = o2 + crank * np.array([math.cos(q), math.sin(q)])
        B = _circle_left(A, o4, coupler, rocker, side)
        if B is None:
            return (np.nan, np.nan)
        a = math.atan2(B[1] - A[1], B[0] - A[0]) + angle
        return A + ap * np.array([math.cos(a), math.sin(a)])

    at_targets = np.array([coupler_point(q) for q in v[9:]])
    if not abs(np.linalg.norm(at_targets - Tn, axis=1).sum() - fitness) <= 1e-9 * max(1.0, fitness):
        raise RuntimeError("the linkage rebuilt from pyslvs' design does not reproduce its fitness")
    curve = np.array([coupler_point(q) for q in np.linspace(0.0, 2 * np.pi, 3601)])
    return PeerSynthesis(path_error(curve, Tn), seconds, int(objective.callback))


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
    else:
        r = pyslvs_path_synthesis(ELLIPSE_10)
        print(f"pyslvs {pyslvs.__version__}: differential evolution on the 10-point ellipse: "
              f"error {r.error:.3g}, {r.seconds:.1f} s, {r.evaluations:,} evaluations")


if __name__ == "__main__":
    main()
