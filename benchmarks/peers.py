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

Run as a script, it checks pylinkage against kinelab and prints, side by side in one
process (processor time; best and median of repeats; the peer's median over kinelab's):
one four-bar configuration per call (pylinkage's step against kinelab's ``Tracker`` and
``analyze``), a sweep of 3600 crank angles, and path synthesis on two 10-point tasks, each
method's time to an error of 3e-2, 1e-2 and 1e-3 of the path's size over several seeds.

    python benchmarks/peers.py [--one]

(``--one``: the comparison of one configuration per call only.)
"""
from __future__ import annotations

import math
import os
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


# 10 points over 270 degrees of the coupler curve of kinelab's catalogue crank-rocker
# (ground 3, crank 1, coupler 3, rocker 2.5, P = (1.5, 1) from A): an exact task.
_q = np.radians(np.linspace(0, 270, 10))
_A = np.column_stack([np.cos(_q), np.sin(_q)])
_d = np.array([3.0, 0.0]) - _A
_D = np.hypot(_d[:, 0], _d[:, 1])[:, None]
_a = (9.0 - 6.25 + _D ** 2) / (2 * _D)
_e = _d / _D
_B = _A + _a * _e + np.sqrt(9.0 - _a ** 2) * np.column_stack([-_e[:, 1], _e[:, 0]])
_w = (_B - _A) / 3.0
COUPLER_10 = _A + 1.5 * _w + 1.0 * np.column_stack([-_w[:, 1], _w[:, 0]])


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


def pylinkage_with_kinematics(linkage: PylinkageFourbar, omega: float, alpha: float = 0.0):
    """pylinkage's one step with velocities and accelerations,
    ``Linkage.step_fast_with_kinematics(iterations=1)``, at the linkage's configuration and
    the crank's speed ``omega`` (rad/s) and acceleration ``alpha``: a function of no
    arguments returning (positions, velocities, accelerations), each (1, 5, 2) (rows
    :data:`NAMES`).  The crank's own angular velocity, by which a step turns it, is 0: each
    call answers the same configuration, as a tracker's call answers the one it is given."""
    from pylinkage.actuators import Crank

    crank = next(c for c in linkage.linkage.components if isinstance(c, Crank))
    linkage.linkage.set_input_velocity(crank, float(omega), float(alpha))
    return lambda: linkage.linkage.step_fast_with_kinematics(iterations=1)


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
    seconds: float          # processor time of the search (time.process_time)
    evaluations: int        # fitness evaluations (linkages simulated); -1: not counted
    trace: tuple = ()       # (seconds, error) each time the best so far improved, if known


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
        (error, seconds, evaluations, trace): the trace holds the time and the error
        (:func:`path_error`, 3600 samples) of each new best design of the swarm.
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

    improvements = []                  # (seconds, fitness, design) of each new best

    def fitness(_linkage, params, _init_pos):
        nonlocal evaluations
        evaluations += 1
        P = curve(params, samples)
        f = math.inf if P is None else path_error(P, Tn)
        if f < (improvements[-1][1] if improvements else math.inf):
            improvements.append((time.process_time() - t0, f, np.array(params, float)))
        return f

    def error_of(x):
        P = curve(x, 3600)
        return math.inf if P is None else path_error(P, Tn)

    real_rng = np.random.default_rng
    t0 = time.process_time()
    with mock.patch("numpy.random.default_rng", lambda *a, **k: real_rng(seed)):
        best = particle_swarm_optimization(
            fitness, template.linkage, dimensions=len(_BOUNDS[0]), n_particles=n_particles,
            iterations=iterations, bounds=_BOUNDS, order_relation=min, verbose=False)
    seconds = time.process_time() - t0
    trace = tuple((t, error_of(x)) for t, _, x in improvements)
    return PeerSynthesis(error_of(np.asarray(best.dimensions[0], float)), seconds, evaluations,
                         trace)


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
    t0 = time.process_time()
    de.run()
    seconds = time.process_time() - t0
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
# kinelab, measured the same way

def kinelab_path_synthesis(target_points, *, tolerance: float = 1e-3, seed: int = 0
                           ) -> PeerSynthesis:
    """``kl.synthesis.path_generation`` (one run, stopped at ``tolerance``), its error
    measured as the peers' are: :func:`path_error` of the engine's coupler curve over a
    full turn (3600 samples, broken where the loop does not close)."""
    import kinelab as kl

    T = np.asarray(target_points, float)
    t0 = time.process_time()
    # the peers keep no transmission angle limit: neither does kinelab here
    sols = kl.synthesis.path_generation(T, runs=1, seed=seed, tolerance=tolerance,
                                        min_transmission_angle=0.0)
    seconds = time.process_time() - t0
    if not sols:
        return PeerSynthesis(math.inf, seconds, -1)
    sol = kl.analyze(sols[0].model, np.linspace(0.0, 2 * np.pi, 3601), unreachable="mask",
                     at_singular="flag")
    return PeerSynthesis(path_error(sol.position("P"), T), seconds, -1)


def _per_call(call, args, repeats: int = 15) -> np.ndarray:
    """Processor time of one call (s), for each of ``repeats`` loops over ``args``."""
    out = []
    for _ in range(repeats):
        t0 = time.thread_time()
        for a in args:
            call(a)
        out.append((time.thread_time() - t0) / len(args))
    return np.array(out)


def _row(name: str, t: np.ndarray, *refs: np.ndarray | None, unit: float = 1e6) -> str:
    """best, median, and each reference's median over this one's (> 1: this is faster)."""
    ratios = "".join("" if ref is None else f"{np.median(ref) / np.median(t):9.2f}x" for ref in refs)
    return f"  {name:56s} {np.min(t) * unit:9.3f} {np.median(t) * unit:9.3f} {ratios}"


def compare_one_configuration(model, fb, repeats: int = 15):
    """kinelab's Tracker and analyze against pylinkage's one step, one crank angle a call:
    positions against ``step_single``, the whole analysis against
    ``step_fast_with_kinematics(iterations=1)``; and a tracker of the Stephenson six-bar."""
    import kinelab as kl

    q = [float(x) for x in np.linspace(0.0, 2 * np.pi, 2000)]
    track = kl.kinematics.Tracker(model)
    six = kl.mechanisms.stephenson6()
    track6 = kl.kinematics.Tracker(six)
    q6 = [float(x) for x in np.linspace(0.0, 2 * np.pi, 2000)]
    track(q[0], 10.0, 0.0), track.positions(q[0]), kl.analyze(model, q[0], 10.0, 0.0)   # warm
    track6(q6[0], 10.0, 0.0)
    pylinkage_one_step(fb, q[0])
    kinematics = pylinkage_with_kinematics(fb, 10.0)
    kinematics()
    load = os.getloadavg()
    print(f"one configuration per call, processor time, us (best, median; pylinkage's "
          f"medians over this one's: step_single, step_fast_with_kinematics), load average "
          f"{load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    ref = _per_call(lambda x: pylinkage_one_step(fb, x), q, repeats)
    ref_kin = _per_call(lambda x: kinematics(), q, repeats)
    print(_row(f"pylinkage {pylinkage.__version__} step_single (O2, A, B, O4, P)", ref))
    print(_row("pylinkage step_fast_with_kinematics(iterations=1)", ref_kin))
    print(_row("kinelab Tracker.positions(q) (every point)", _per_call(track.positions, q, repeats),
               ref, ref_kin))
    print(_row("kinelab Tracker(q, qd, qdd) (whole analysis)",
               _per_call(lambda x: track(x, 10.0, 0.0), q, repeats), ref, ref_kin))
    print(_row("kinelab Tracker(q, qd, qdd), then P's position, velocity, acc.",
               _per_call(lambda x: _read_p(track(x, 10.0, 0.0)), q, repeats), ref, ref_kin))
    print(_row("kinelab Tracker(q, qd, qdd), Stephenson six-bar",
               _per_call(lambda x: track6(x, 10.0, 0.0), q6, repeats), ref, ref_kin))
    print(_row("kinelab analyze(model, q, qd, qdd)",
               _per_call(lambda x: kl.analyze(model, x, 10.0, 0.0), q[:500], repeats), ref, ref_kin))


def _read_p(sol):
    return sol.position("P"), sol.velocity("P"), sol.acceleration("P")


def compare_sweep(model, fb, n: int = 3600, repeats: int = 15):
    """kinelab's analyze against pylinkage's numba loop over n crank angles."""
    import kinelab as kl

    q = np.linspace(0.0, 2 * np.pi, n)
    kl.analyze(model, q, 10.0, 0.0), pylinkage_sweep(fb, q)               # warm
    print(f"a sweep of {n:,} crank angles, us per configuration (best, median; ratio)")
    ref = _per_call(lambda _: pylinkage_sweep(fb, q), [None] * 5, repeats) / n
    print(_row("pylinkage simulate (positions)", ref, None))
    print(_row("kinelab analyze (positions, velocities, accelerations)",
               _per_call(lambda _: kl.analyze(model, q, 10.0, 0.0), [None] * 5, repeats) / n, ref))


def _time_to(runs, error: float) -> np.ndarray:
    """Per seed, the time at which a method first held a design within ``error`` (inf:
    never).  ``runs``: per seed, a list of (seconds, error) points."""
    return np.array([min((t for t, e in points if e <= error), default=math.inf)
                     for points in runs])


def compare_path_synthesis(targets, name: str, errors=(3e-2, 1e-2, 1e-3), seeds: int = 10,
                           peer_seeds: int = 3):
    """Processor time to reach each error (path_error) on one task, per method and seed."""
    rows = {}
    kinelab_path_synthesis(targets, tolerance=1e-1, seed=0)                   # warm
    # kinelab: one run per seed and error, stopped there
    runs = [[] for _ in range(seeds)]
    final, total = [], []
    for s in range(seeds):
        for e in errors:
            r = kinelab_path_synthesis(targets, tolerance=e, seed=s)
            runs[s].append((r.seconds, r.error))
        final.append(r.error)
        total.append(r.seconds)
    rows["kinelab path_generation"] = (runs, final, total)
    if HAVE_PYLINKAGE:
        runs, final, total = [], [], []
        for s in range(peer_seeds):
            r = pylinkage_path_synthesis(targets, seed=s)
            runs.append(list(r.trace))
            final.append(r.error)
            total.append(r.seconds)
        rows["pylinkage particle swarm (100 x 200)"] = (runs, final, total)
    if HAVE_PYSLVS:
        runs, final, total = [], [], []
        for s in range(1, peer_seeds + 1):               # srand(0) is srand(1) in glibc
            points = []
            for gens in (125, 250, 500, 1000):           # each budget its own run
                r = pyslvs_path_synthesis(targets, max_gen=gens, seed=s)
                points.append((r.seconds, r.error))
            runs.append(points)
            final.append(points[-1][1])
            total.append(points[-1][0])
        rows["pyslvs differential evolution (400 x 1000)"] = (runs, final, total)
    print(f"path synthesis, {name}: processor time to an error of (s; best / median over "
          f"seeds, '-': not reached), and the median last error and whole run's time")
    head = "".join(f"{'<= ' + format(e, 'g'):>16s}" for e in errors)
    print(f"  {'':56s}{head}   {'last error':>10s} {'run [s]':>8s}")
    ref = {e: _time_to(rows["kinelab path_generation"][0], e) for e in errors}
    for label, (runs, final, total) in rows.items():
        cells = []
        for e in errors:
            t = _time_to(runs, e)
            cells.append(f"{_fmt_s(t.min())} / {_fmt_s(np.median(t))}")
        print(f"  {label:56s}" + "".join(f"{c:>16s}" for c in cells)
              + f"   {np.median(final):10.2g} {np.median(total):8.2f}")
        if not label.startswith("kinelab"):
            ratios = []
            for e in errors:
                t = np.median(_time_to(runs, e))
                ratios.append("-" if not math.isfinite(t) else f"{t / np.median(ref[e]):.0f}x")
            print(f"  {'  its median time / kinelab median':56s}"
                  + "".join(f"{c:>16s}" for c in ratios))
    if not HAVE_PYLINKAGE:
        print("  pylinkage: not installed (pip install -e .[bench])")
    if not HAVE_PYSLVS:
        print("  pyslvs: not installed; pip install pyslvs fails on Python 3.11 (its Cython "
              "sources need Cython 3.0.0, see this file's docstring)")


def _fmt_s(t: float) -> str:
    return "-" if not math.isfinite(t) else f"{t:.2f}"


def main():
    # the steady state: kinelab's compiled kernel, compiled (or loaded from the cache) by the
    # first call, which waits for it; benchmarks/cold_start.py measures the first calls
    os.environ.setdefault("KINELAB_KERNEL", "compiled")
    import sys

    import kinelab as kl
    if "--one" in sys.argv:                     # one configuration per call only
        if not HAVE_PYLINKAGE:
            print("pylinkage: not installed (pip install -e .[bench])")
            return
        compare_one_configuration(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)),
                                  pylinkage_fourbar(3.0, 1.0, 3.0, 2.5, (1.5, 1.0)))
        return

    print(f"kinelab against its peers, one process; numpy {np.__version__}")
    if HAVE_PYLINKAGE:
        print(f"pylinkage {pylinkage.__version__}: largest difference from kinelab "
              f"{check_pylinkage():.1e} m")
        model = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
        fb = pylinkage_fourbar(3.0, 1.0, 3.0, 2.5, (1.5, 1.0))
        compare_one_configuration(model, fb)
        compare_sweep(model, fb)
    else:
        print("pylinkage: not installed (pip install -e .[bench])")
    if HAVE_PYSLVS:
        print(f"pyslvs {pyslvs.__version__}")
    compare_path_synthesis(ELLIPSE_10, "10 points of a 2 x 1 ellipse over 270 deg")
    compare_path_synthesis(COUPLER_10, "10 points of the crank-rocker's coupler curve "
                           "(an exact solution exists)")


if __name__ == "__main__":
    main()
