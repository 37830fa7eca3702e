"""Path generation: a four-bar whose coupler point passes near prescribed points
(*Mecanismos*, §3.2, fig. 26), by global search and least squares.

The timing is free (the crank angle at each point is not prescribed).  A design is the
fixed pivots A0, B0, the crank, coupler and rocker lengths, the coupler point (u along AB,
v to its left) and the assembly branch.  Its coupler curve is evaluated in closed form
for many designs at once (:func:`coupler_curves`); each target point is matched to the
nearest sample of the curve, and the screening objective is the RMS distance, with a
penalty when the matched samples are not met in order by one sense of crank rotation
without a limit position in between (order and branch defects) or when the transmission
angle drops below a bound.  Quasi-random designs are screened with it; least squares
(Levenberg-Marquardt on the whole batch, analytic Jacobian) then takes the best of them
over the design *and* the crank angles of the points, with the travel's constraints as
residuals; the best results are built as models and checked with the engine.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab import _memory as memory
from kinelab import _progress as progress
from kinelab.errors import ModelError, describe
from kinelab.kinematics import analyze
from kinelab.kinematics._interpreter import rrr_closure
from kinelab.mechanisms import Grashof
from kinelab.model import MAX_LENGTH, MIN_LENGTH, Mechanism, is_real
from kinelab.solvers._arguments import flag, reals, whole
from kinelab.solvers._arguments import seed as check_seed
from kinelab.synthesis._arguments import point_array
from kinelab.solvers import wrap_angle
from kinelab.synthesis._linkage import (TRANSMISSION_LIMIT, CheckedLinkage, at_inputs,
                                        finite_or_inf, fourbar_model, model_grashof,
                                        transmission_defects, transmission_limit, travel)
from kinelab.synthesis._results import SolutionList

__all__ = ["coupler_curves", "curve_distances", "PathSolution", "path_generation",
           "MAX_PATH_POINTS"]

# The most targets and crank samples a search takes.  A path is given by 5 to 20 points as a
# rule (9 + n unknowns: at most nine are met exactly); each round's work grows with both
# (at 30 points and the default 180 samples a round takes about 0.3 s), and the
# screen holds arrays of designs x targets x samples.
MAX_PATH_POINTS = 30
MAX_PATH_SAMPLES = 10_000
# the most runs, rounds and size of a round, as a task file takes them
MAX_RUNS, MAX_ROUNDS, MAX_POPSIZE = 1000, 1_000_000, 10_000
_SCREENED = 2_000_000  # designs x targets x samples screened at once: bounds the memory

_INFEASIBLE = 1.0      # added to the objective (task normalised to unit size) of a design
                       # whose points are not met in order on one branch
_NOWHERE = 100.0       # objective of a design that assembles at no sample
_MU_FLOOR = np.radians(1.0)   # least squares keep the transmission angle above this at least
_REACHED = 1e-8        # relative distance engine vs closed form at a matched crank angle


def coupler_curves(designs: ArrayLike, q: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                               np.ndarray]:
    """Coupler-point positions of many four-bars at many crank angles, in closed form.

    Parameters
    ----------
    designs : array_like, shape (D, 10)
        Per design: ``a0x, a0y, b0x, b0y`` (fixed pivots, m), ``crank, coupler, rocker``
        (m), ``u, v`` (coupler point from A, along AB and to its left, m, as the
        catalogue's ``coupler_point``) and the branch (``>= 0``: "open", B to the left of
        the line from A to O4; ``< 0``: "crossed").
    q : array_like, shape (m,) or (D, m)
        Crank angles from +x, rad.

    Returns
    -------
    P, A, B : ndarray, shape (D, m, 2)
        Coupler point, crank pin and rocker pin, m (where the loop cannot close, the
        values are those of the nearest closure and ``assembled`` is False).
    assembled : ndarray of bool, shape (D, m)

    Examples
    --------
    The catalogue crank-rocker (O2 = origin, O4 = (3, 0)) at q = 90 deg:

    >>> d = [[0, 0, 3, 0, 1.0, 3.0, 2.5, 1.5, 1.0, 1.0]]
    >>> P, A, B, ok = kl.synthesis.coupler_curves(d, [np.pi / 2])
    >>> P.shape, bool(ok[0, 0])
    ((1, 1, 2), True)
    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
    ...                            coupler_point=(1.5, 1.0))
    >>> bool(np.allclose(P[0, 0], kl.analyze(fb, q=np.pi / 2).position("P"), atol=1e-12))
    True
    """
    x = reals("designs", designs)          # a design with NaN is simply not assembled
    if x.ndim != 2 or x.shape[1] != 10:
        raise ModelError(f"designs: expected shape (D, 10), got {x.shape}")
    q = reals("q", q)
    if q.ndim not in (1, 2) or (q.ndim == 2 and q.shape[0] != x.shape[0]):
        raise ModelError(f"q: expected shape (m,) or ({x.shape[0]}, m), got {q.shape}")
    D, m = x.shape[0], q.shape[-1]
    memory.require(16 * 8 * D * m, f"the coupler curves of {D:,} designs at {m:,} crank angles",
                   "give fewer designs or angles at a time")
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return _curves(x, q)


def _curves(x: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`coupler_curves` of checked arrays; a design with a zero or non-finite length,
    or one that overflows, is not assembled."""
    a0x, a0y, b0x, b0y, r2, r3, r4, u, v, branch = (x[:, k][:, None] for k in range(10))
    sigma = np.where(branch >= 0, 1.0, -1.0)
    Ax = a0x + r2 * np.cos(q)             # q (m,) is shared by every design: one cos, one sin
    Ay = a0y + r2 * np.sin(q)
    dx, dy = b0x - Ax, b0y - Ay
    # the engine's closure of the dyad (coupler, rocker) across A -> B0: B where kl.analyze
    # puts it, closed where it closes (at the straight position of a change point too)
    D2 = dx * dx + dy * dy
    folded, alpha, beta2, low, fail = rrr_closure(r3, r4, D2)
    assembled = ~fail & ~folded             # A on B0: B's direction is the motion's, not here
    beta = sigma * np.sqrt(np.where(low, 0.0, beta2))
    Bx = Ax + alpha * dx - beta * dy
    By = Ay + alpha * dy + beta * dx
    wx, wy = (Bx - Ax) / r3, (By - Ay) / r3
    P = np.stack([Ax + u * wx - v * wy, Ay + u * wy + v * wx], -1)
    assembled &= np.isfinite(P).all(-1) & (r3 != 0)
    return P, np.stack([Ax, Ay], -1), np.stack([Bx, By], -1), assembled


def _transmission(A, B, b0):
    """Folded transmission angle at B, (D, m)."""
    ux, uy = A[..., 0] - B[..., 0], A[..., 1] - B[..., 1]
    vx, vy = b0[:, None, 0] - B[..., 0], b0[:, None, 1] - B[..., 1]
    mu = np.arctan2(np.abs(ux * vy - uy * vx), ux * vx + uy * vy)
    return np.minimum(mu, np.pi - mu)


class _Objective:
    """RMS distance of the targets to a population's coupler curves, with defect penalties.

    Called by differential evolution with x of shape (10, S) (parameters x population)."""

    def __init__(self, targets: np.ndarray, samples: int, mu_min: float):
        self.T = targets                                   # (n, 2), normalised
        self.q = np.linspace(0.0, 2 * np.pi, samples, endpoint=False)
        self.mu_min = mu_min

    def match(self, designs):
        """Per design: matched sample of each target, distances, penalty (D,)."""
        P, A, B, ok = coupler_curves(designs, self.q)
        dx = P[:, None, :, 0] - self.T[None, :, 0, None]                        # (D, n, m)
        dy = P[:, None, :, 1] - self.T[None, :, 1, None]
        d2 = np.where(ok[:, None, :], dx * dx + dy * dy, np.inf)
        k = np.argmin(d2, axis=-1)                                              # (D, n)
        dist2, frac = self._to_segments(P, ok, k)
        mu = _transmission(A, B, designs[:, 2:4])
        m = self.q.size
        penalty = np.full(designs.shape[0], np.inf)
        idx = np.arange(m)
        for sense in (1, -1):
            steps = np.mod(sense * np.diff(k, axis=1), m)                       # (D, n-1)
            travel = steps.sum(axis=1)                                          # (D,)
            offset = np.mod(sense * (idx[None, :] - k[:, :1]), m)               # (D, m)
            on_way = offset <= travel[:, None]
            blocked = np.sum(on_way & ~ok, axis=1)
            low = np.sum(on_way & ok & (mu < self.mu_min), axis=1)
            wrong = np.maximum(travel - (m - 1), 0)
            penalty = np.minimum(penalty, (wrong + blocked + low) / m)
        return k + frac, dist2, penalty

    def _to_segments(self, P, ok, k):
        """Squared distance of each target to the curve's two chords at its nearest sample,
        and where along them (in samples, -1..1): the sampling error drops from first to
        second order in the crank step."""
        rows = np.arange(P.shape[0])[:, None]
        T = self.T[None, :, :]
        Pk = P[rows, k]
        best = np.sum((T - Pk) ** 2, -1)
        frac = np.zeros(k.shape)
        for step in (1, -1):
            j = np.mod(k + step, self.q.size)
            Q = P[rows, j]
            e = Q - Pk
            ee = np.sum(e * e, -1)
            t = np.clip(np.sum((T - Pk) * e, -1) / np.where(ee > 0, ee, 1.0), 0.0, 1.0)
            d2 = np.sum((T - Pk - t[..., None] * e) ** 2, -1)
            better = ok[rows, j] & (d2 < best)
            best = np.where(better, d2, best)
            frac = np.where(better, step * t, frac)
        return np.where(ok[rows, k], best, np.inf), frac

    def __call__(self, x):
        designs = np.atleast_2d(np.asarray(x).T)
        _, dist2, penalty = self.match(designs)
        rms = np.sqrt(np.mean(dist2, axis=1))
        f = rms + np.where(penalty > 0, _INFEASIBLE + penalty, 0.0)
        return np.where(np.isfinite(rms), f, _NOWHERE)


@dataclass(frozen=True, eq=False)
class PathSolution(CheckedLinkage):
    """A four-bar whose coupler point passes near prescribed points, with its checks.

    Attributes
    ----------
    A0, B0 : ndarray, shape (2,)
        Fixed pivots of the crank and of the rocker, m.
    A1, B1 : ndarray, shape (2,)
        Moving pivots when the coupler point is nearest the first target, m.
    points : ndarray, shape (n, 2)
        The target points, m.
    model : Mechanism
        The four-bar (catalogue names), sketched at the first target's crank angle.
    q : ndarray, shape (n,)
        Crank angle at which the coupler point is nearest each target, rad: ``q[0]`` in
        (-pi, pi], the others following it in the sense ``direction``, less than a turn on.
    errors : ndarray, shape (n,)
        Distance from each target to the engine's coupler point at ``q``, m.
    coupler_point : (float, float)
        P from A, along AB and to its left, m.
    grashof : Grashof
    min_transmission_angle : float
        The smallest transmission angle over the travel from the first target to the
        last, rad (the engine's, :func:`kinelab.analyze`).
    branch_defect, order_defect : bool
    direction : int
        +1 / -1: the crank turns counter-clockwise / clockwise through the targets.
    defects : tuple of str
        Branch and order defects, and a transmission angle below ``transmission_limit``
        on the way.
    transmission_limit : float
        The task's ``min_transmission_angle``, rad (30 deg unless it says otherwise);
        ``meets_transmission_limit`` says whether the linkage keeps it.
    """

    A0: np.ndarray
    B0: np.ndarray
    A1: np.ndarray
    B1: np.ndarray
    points: np.ndarray
    model: Mechanism
    q: np.ndarray
    errors: np.ndarray
    coupler_point: tuple[float, float]
    grashof: Grashof
    min_transmission_angle: float
    branch_defect: bool
    order_defect: bool
    direction: int
    defects: tuple[str, ...]
    transmission_limit: float = TRANSMISSION_LIMIT

    @property
    def rms_error(self) -> float:
        """Root-mean-square distance of the targets from the coupler curve, m."""
        return float(np.sqrt(np.mean(self.errors ** 2)))

    @property
    def max_error(self) -> float:
        """Largest distance of a target from the coupler curve, m."""
        return float(self.errors.max())

    def curve_distances(self, points: ArrayLike) -> np.ndarray:
        """Distance from each of ``points`` (n, 2), m, to the linkage's coupler curve, m
        (see :func:`curve_distances`)."""
        return curve_distances(self.model, points)

    def __repr__(self) -> str:
        state = self.state
        return (f"PathSolution(rms error={self.rms_error:.3g} m, max error={self.max_error:.3g} m, "
                f"{self.grashof.kind}, {state})")


_CURVE_SAMPLES = 3600     # crank angles of the coupler curve a point is first matched to
_GOLDEN = 40              # golden-section steps from there: the bracket shrinks by 0.618^40
_NEWTON = 3               # Gauss-Newton steps after them: the distance to rounding


def curve_distances(model: Mechanism, points: ArrayLike) -> np.ndarray:
    """Distance from each point to the coupler curve of a four-bar model, m, by the engine.

    The coupler curve is where the coupler point ``P`` goes as the crank turns through every
    angle at which the loop closes on the model's assembly branch: the whole closed curve of
    a crank that turns fully, the arc between its limit positions otherwise.  Each point is
    matched to the nearest of 3600 engine samples of a turn, then the crank angle is refined
    around it by golden-section search and Gauss-Newton steps (``kl.analyze`` at every step,
    with the velocity coefficient of ``P`` for the slope), so the distance is exact to
    rounding, not to the sampling.

    Parameters
    ----------
    model : Mechanism
        A four-bar with a coupler point ``P`` and one crank input.
    points : array_like, shape (n, 2)
        m.

    Returns
    -------
    ndarray, shape (n,)
        m; +inf for every point when the loop closes nowhere.
    """
    T = np.asarray(reals("points", points), float)
    if T.ndim != 2 or T.shape[1] != 2 or not np.all(np.isfinite(T)):
        raise ModelError(f"points: expected finite points of shape (n, 2), got {describe(points)}")
    h = 2 * np.pi / _CURVE_SAMPLES
    q = np.arange(_CURVE_SAMPLES) * h - np.pi
    sol = at_inputs(model, q)
    P, ok = sol.position("P"), sol.assembled
    if not ok.any() or len(T) == 0:
        return np.full(len(T), np.inf)
    Q, qs = P[ok], q[ok]
    best = np.empty(len(T))
    k = np.empty(len(T), int)
    step = max(1, 2_000_000 // len(Q))           # points matched at once: bounds the memory
    for i in range(0, len(T), step):
        d2 = np.sum((T[i:i + step, None, :] - Q[None]) ** 2, axis=-1)
        k[i:i + step] = np.argmin(d2, axis=1)
        best[i:i + step] = np.sqrt(d2[np.arange(len(d2)), k[i:i + step]])
    q_best = qs[k]

    def distance(angles):
        # at unit crank speed, so that the velocity of P is dP/dq
        s = analyze(model, angles, qd=1.0, unreachable="mask", at_singular="flag")
        d = np.linalg.norm(s.position("P") - T, axis=1)
        return np.where(s.assembled & np.isfinite(d), d, np.inf), s

    # golden-section search on the bracket one sample either side (the curve is smooth
    # there; where the loop stops closing the distance is +inf, and the search stays out)
    g = (np.sqrt(5.0) - 1.0) / 2.0
    a, b = q_best - h, q_best + h
    c, e = b - g * (b - a), a + g * (b - a)
    fc, fe = distance(c)[0], distance(e)[0]
    for _ in range(_GOLDEN):
        left = fc <= fe
        a, b = np.where(left, a, c), np.where(left, e, b)
        c_new, e_new = np.where(left, b - g * (b - a), e), np.where(left, c, a + g * (b - a))
        f_new = distance(np.where(left, c_new, e_new))[0]
        fc, fe = np.where(left, f_new, fe), np.where(left, fc, f_new)
        c, e = c_new, e_new
    for angles, f in ((c, fc), (e, fe)):
        better = f < best
        best, q_best = np.where(better, f, best), np.where(better, angles, q_best)
    for _ in range(_NEWTON):
        d, s = distance(q_best)
        r, dP = s.position("P") - T, s.velocity("P")
        slope = np.sum(dP * dP, axis=1)
        with np.errstate(invalid="ignore"):
            trial = q_best - np.sum(r * dP, axis=1) / np.where(slope > 0, slope, 1.0)
        trial = np.where(np.isfinite(trial), trial, q_best)
        f = distance(trial)[0]
        better = f < best
        best, q_best = np.where(better, f, best), np.where(better, trial, q_best)
    return best


def _unwrapped(q: np.ndarray):
    """Crank angles (K, n) unwrapped along the sense (K,) in which they are met with the
    least travel: each next angle follows the last in that sense, less than a turn on."""
    steps = [np.mod(d * np.diff(q, axis=1), 2 * np.pi) for d in (1, -1)]
    ccw = steps[0].sum(axis=1) <= steps[1].sum(axis=1)
    sense = np.where(ccw, 1.0, -1.0)
    travel = np.where(ccw[:, None], steps[0], steps[1])
    cumulative = np.concatenate([np.zeros((len(q), 1)), np.cumsum(travel, axis=1)], axis=1)
    return q[:, :1] + sense[:, None] * cumulative, sense


def _travel_gap(Z: np.ndarray, sense: np.ndarray, cos_floor: float):
    """How far each candidate's loop is from closing, with a transmission angle of at least
    the floor, all the way from the first target to the last, (K,) (0 when it does).

    ``Z`` (K, 11) holds the design's nine numbers and the crank angles at the first and
    last targets.  The floor keeps the motion off the limit positions.  The check is
    exact: the transmission angle is a monotonic function of the distance L from the
    crank pin to B0, and L is monotonic between its extremes, met where the crank points
    at B0 or away from it; so only the ends of the travel and those two angles (when they
    are on the way) need checking."""
    a0x, a0y, b0x, b0y, r2, r3, r4 = Z[:, :7].T
    q0, q1 = Z[:, 9], Z[:, 10]
    gx, gy = b0x - a0x, b0y - a0y
    G = np.hypot(gx, gy)
    phi = np.arctan2(gy, gx)
    # from the crank pin to B0 at the two ends of the travel
    L0 = np.hypot(gx - r2 * np.cos(q0), gy - r2 * np.sin(q0))
    L1 = np.hypot(gx - r2 * np.cos(q1), gy - r2 * np.sin(q1))
    span = sense * (q1 - q0)
    on_way = [np.mod(sense * (psi - q0), 2 * np.pi) <= span for psi in (phi, phi + np.pi)]
    L_min = np.where(on_way[0], np.abs(G - r2), np.minimum(L0, L1))
    L_max = np.where(on_way[1], G + r2, np.maximum(L0, L1))
    # mu >= floor all the way <=> L within the band where the law of cosines gives it
    L_hi = np.sqrt(r3 * r3 + r4 * r4 + 2 * r3 * r4 * cos_floor)
    L_lo = np.sqrt(np.maximum(r3 * r3 + r4 * r4 - 2 * r3 * r4 * cos_floor, 0.0))
    return np.maximum(L_max - L_hi, 0) + np.maximum(L_lo - L_min, 0)


def _travel_residuals(Z: np.ndarray, sense: np.ndarray, cos_floor: float):
    """Residuals that vanish when a candidate's travel is right (K, n), and their
    Jacobian (K, n, 9 + n).

    The first is :func:`_travel_gap` (its Jacobian by central differences, every column of
    every candidate in one evaluation); the other n - 1 keep the crank angles following
    each other in the candidate's sense of rotation (piecewise linear: exact)."""
    K, m = Z.shape
    n = m - 9
    ends = np.concatenate([Z[:, :10], Z[:, -1:]], axis=1)                       # (K, 11)
    gap = _travel_gap(ends, sense, cos_floor)
    h = 1e-6 * np.maximum(1.0, np.abs(ends))
    E = h[:, :, None] * np.eye(11)
    shifted = np.concatenate([ends[:, None, :] + E, ends[:, None, :] - E], axis=1).reshape(-1, 11)
    both = _travel_gap(shifted, np.repeat(sense, 22), cos_floor)
    both = both.reshape(K, 2, 11)
    J = np.zeros((K, n, m))
    J[:, 0, :10] = (both[:, 0, :10] - both[:, 1, :10]) / (2 * h[:, :10])
    J[:, 0, -1] += (both[:, 0, 10] - both[:, 1, 10]) / (2 * h[:, 10])
    ahead = -sense[:, None] * np.diff(Z[:, 9:], axis=1)                         # (K, n - 1)
    active = np.where(ahead > 0, sense[:, None], 0.0)
    i = np.arange(n - 1)
    J[:, 1 + i, 9 + i] = active
    J[:, 1 + i, 10 + i] = -active
    return 10.0 * np.column_stack([gap, np.maximum(ahead, 0)]), 10.0 * J


def _solution(targets: np.ndarray, design: np.ndarray, q: np.ndarray,
              mu_min: float = TRANSMISSION_LIMIT) -> PathSolution:
    """Build and check the linkage of a design (physical units) through its crank angles;
    a transmission angle below ``mu_min`` on the way is a defect."""
    P, A, B, ok = coupler_curves(design[None, :], q[None, :])
    if not ok[0, 0]:
        raise ModelError("the linkage does not close at the first target")
    model = fourbar_model(design[0:2], design[2:4], A[0, 0], B[0, 0], P[0, 0],
                          name="path generator")
    scale = max(float(np.ptp(targets, axis=0).max()), float(design[4:7].max()))

    def reached(sol, idx):
        return np.linalg.norm(sol.position("P")[idx] - P[0], axis=-1) <= _REACHED * scale

    t = travel(model, q, reached)
    defects = t.defects
    if t.direction:
        # the angles as the crank meets them, the travel's own sense, each less than a turn
        # after the first (least squares may leave whole turns between them)
        q0 = float(wrap_angle(q[0]))
        q = q0 + t.direction * np.mod(t.direction * (q - q[0]), 2 * np.pi)
        q[0] = q0
    defects += transmission_defects(t.min_transmission_angle, mu_min,
                                    "between the first target and the last")
    engine = at_inputs(model, q).position("P")
    errors = np.linalg.norm(engine - targets, axis=-1)
    errors = finite_or_inf(errors)
    for arr in (q, errors):
        arr.setflags(write=False)
    return PathSolution(
        A0=design[0:2].copy(), B0=design[2:4].copy(), A1=A[0, 0], B1=B[0, 0], points=targets,
        model=model, q=q, errors=errors, coupler_point=(float(design[7]), float(design[8])),
        grashof=model_grashof(model), min_transmission_angle=t.min_transmission_angle,
        branch_defect=t.branch_defect, order_defect=t.order_defect, direction=t.direction,
        defects=defects, transmission_limit=mu_min)



def _timed_points(T: np.ndarray, Z: np.ndarray, sigma: np.ndarray):
    """Coupler point minus target at each target's own crank angle, and its Jacobian.

    ``Z`` (K, 9 + n) holds K candidates: ``a0x, a0y, b0x, b0y, crank, coupler, rocker, u,
    v`` and the n crank angles; ``sigma`` (K,) their branches (+1 / -1, as in
    :func:`coupler_curves`).  Returns the residuals (K, 2n) (x and y of target 1, then of
    target 2, ...), whether the loop closes at each target (K, n), and the Jacobian
    (K, 2n, 9 + n).

    The Jacobian is analytic.  With unit vectors e(q), e3 along the coupler (A to B) and
    e4 along the rocker (O4 to B), the loop ``a0 + r2 e(q) + r3 e3 - r4 e4 - b0 = 0``
    differentiated gives ``c + r3 e3' dth3 - r4 e4' dth4 = 0`` (' turns a vector by +90
    deg), c being the change of ``a0 - b0 + r2 e(q) + r3 e3 - r4 e4`` at fixed link
    angles.  Dotted with e4 it leaves ``dth3 = -(c . e4) / (r3 (e3 x e4))`` (e3 x e4 is
    the sine of the transmission angle); and ``P = A + R(th3) (u, v)`` changes by
    ``dA + R(th3) (du, dv) + (P - A)' dth3``.
    """
    K, n = Z.shape[0], T.shape[0]
    a0x, a0y, b0x, b0y, r2, r3, r4, u, v = (Z[:, k, None] for k in range(9))
    q = Z[:, 9:]
    sg = sigma[:, None]
    c, s = np.cos(q), np.sin(q)
    Ax, Ay = a0x + r2 * c, a0y + r2 * s
    dx, dy = b0x - Ax, b0y - Ay
    D2 = dx * dx + dy * dy
    folded, alpha, beta2, low, fail = rrr_closure(r3, r4, D2)     # the engine's closure
    assembled = ~fail & ~folded
    L = np.sqrt(D2)
    Ls = np.where(L > 0, L, 1.0)
    with np.errstate(invalid="ignore"):        # where folded (A on B0): 0, not inf x 0
        p = np.where(folded, 0.0, alpha * L)    # B along and across A -> B0, m
        h = np.where(folded | low, 0.0, np.sqrt(np.abs(beta2)) * L)
    ex, ey = dx / Ls, dy / Ls
    r3s = np.where(r3 != 0, r3, 1.0)
    wx, wy = (p * ex - sg * h * ey) / r3s, (p * ey + sg * h * ex) / r3s           # e3
    gx, gy = u * wx - v * wy, u * wy + v * wx                                     # P - A
    R = np.stack([Ax + gx - T[:, 0], Ay + gy - T[:, 1]], -1).reshape(K, 2 * n)
    r4s = np.where(r4 != 0, r4, 1.0)
    fx, fy = (Ax + r3 * wx - b0x) / r4s, (Ay + r3 * wy - b0y) / r4s                # e4
    S = r3 * (wx * fy - wy * fx)
    inv = 1.0 / np.where(np.abs(S) > 1e-12, S, 1e-12)
    J = np.zeros((K, n, 2, 9 + n))
    # per design variable: dth3, and the change of P at fixed th3 (x, y)
    columns = ((-fx * inv, 1.0, 0.0), (-fy * inv, 0.0, 1.0), (fx * inv, 0.0, 0.0),
               (fy * inv, 0.0, 0.0), (-(c * fx + s * fy) * inv, c, s),
               (-(wx * fx + wy * fy) * inv, 0.0, 0.0), (inv, 0.0, 0.0),
               (0.0, wx, wy), (0.0, -wy, wx))
    for k, (dth, px, py) in enumerate(columns):
        J[:, :, 0, k] = px - gy * dth
        J[:, :, 1, k] = py + gx * dth
    dth = -r2 * (c * fy - s * fx) * inv                   # the target's own crank angle
    i = np.arange(n)
    J[:, i, 0, 9 + i] = -r2 * s - gy * dth
    J[:, i, 1, 9 + i] = r2 * c + gx * dth
    return R, assembled, J.reshape(K, 2 * n, 9 + n)


def _levenberg_marquardt(T: np.ndarray, Z: np.ndarray, sigma: np.ndarray, sense: np.ndarray,
                         cos_floor: float, iterations: int):
    """Least squares of a batch of candidates at once: the distances of
    :func:`_timed_points` and the travel's constraints of :func:`_travel_residuals`.

    Levenberg-Marquardt with Marquardt's scaling and a damping of its own for each
    candidate; a step is taken only where it lowers the sum of squares, keeps the three
    lengths positive and the loop closed at every target.  Returns the candidates (K,
    9 + n), the sums of squares of their distances (K,) (inf for a candidate that never
    closed) and of their constraints (K,).  It stops early once no candidate makes
    progress."""
    K, m = Z.shape

    def evaluate(Z):
        R, ok, J = _timed_points(T, Z, sigma)
        C, JC = _travel_residuals(Z, sense, cos_floor)
        distance, violation = np.sum(R * R, axis=1), np.sum(C * C, axis=1)
        R, J = np.concatenate([R, C], axis=1), np.concatenate([J, JC], axis=1)
        good = ok.all(axis=1) & np.all(Z[:, 4:7] > 0, axis=1) & np.isfinite(distance) \
            & np.isfinite(violation) & np.all(np.isfinite(J), axis=(1, 2))
        return (np.where(good, distance, np.inf), np.where(good, violation, np.inf),
                np.where(good[:, None], R, 0.0), np.where(good[:, None, None], J, 0.0))

    distance, violation, R, J = evaluate(Z)
    damping = np.full(K, 1e-3)
    eye = np.eye(m)
    idle = 0
    for _ in range(iterations):
        H = np.matmul(J.transpose(0, 2, 1), J)
        g = np.einsum("kij,ki->kj", J, R)
        D = np.diagonal(H, axis1=1, axis2=2)
        scale = D + 1e-9 * D.max(axis=1, keepdims=True) + 1e-300
        step = np.linalg.solve(H + damping[:, None, None] * scale[:, :, None] * eye,
                               -g[..., None])[..., 0]
        trial = Z + np.where(np.isfinite(step), step, 0.0)
        d2, v2, R2, J2 = evaluate(trial)
        cost, c2 = distance + violation, d2 + v2
        better = c2 < cost
        progress = better & (c2 < cost * (1 - 1e-12))
        Z = np.where(better[:, None], trial, Z)
        R = np.where(better[:, None], R2, R)
        J = np.where(better[:, None, None], J2, J)
        distance, violation = np.where(better, d2, distance), np.where(better, v2, violation)
        damping = np.clip(np.where(better, damping / 3, damping * 4), 1e-12, 1e12)
        idle = 0 if progress.any() else idle + 1
        if idle == 3:               # every candidate has converged or stalled
            break
    return Z, distance, violation


_STARTS = 32          # designs screened per unit of popsize in each round
_KEEP = 8             # least-squares starts per unit of popsize in each round
_POLISHED = 16        # of those, carried on by the longer least squares
_BRIEF, _LONG = 20, 50    # their Levenberg-Marquardt iterations
_NEAR = 0.25          # share of a round's starts drawn near the best designs so far
_ELITE = 8            # how many of those are kept
_PATIENCE = 3         # rounds without progress after which they are forgotten
_CHECKED = 3          # of the polished, built as models and checked with the engine
_CHUNK = 1024         # designs screened (or started from) at once: bounds the memory
_BOUNDS = np.array([(-3, 3)] * 4 + [(0.05, 3.0), (0.05, 6.0), (0.05, 6.0), (-4, 4), (-4, 4),
                    (-1, 1)], float)      # the designs drawn, for a task of unit size


class _Search:
    """One run of :func:`path_generation`: rounds of screened quasi-random starts, each
    followed by batched least squares."""

    def __init__(self, obj: _Objective, popsize: int, seed: int, bounds: np.ndarray,
                 initial: np.ndarray | None = None):
        from scipy.stats import qmc
        self.obj = obj
        self.popsize = popsize
        self.bounds = bounds
        self.initial = initial          # designs the first round starts from, whatever the screen
        self.draw = qmc.Halton(d=10, scramble=True, seed=seed)
        self.rng = np.random.default_rng(seed)
        self.cos_floor = float(np.cos(max(obj.mu_min, _MU_FLOOR)))
        self.elite = self.elite_score = None

    def screen(self, designs: np.ndarray):
        """The objective of each design (D,) and the crank angles of its matched samples
        (D, n), a chunk at a time."""
        f = np.empty(len(designs))
        q = np.empty((len(designs), self.obj.T.shape[0]))
        chunk = max(1, min(_CHUNK, _SCREENED // (self.obj.T.shape[0] * self.obj.q.size)))
        for i in range(0, len(designs), chunk):
            k, dist2, penalty = self.obj.match(designs[i:i + chunk])
            rms = np.sqrt(np.mean(dist2, axis=1))
            f[i:i + chunk] = np.where(np.isfinite(rms),
                                      rms + np.where(penalty > 0, _INFEASIBLE + penalty, 0.0),
                                      _NOWHERE)
            q[i:i + chunk] = k * (2 * np.pi / self.obj.q.size)
        return f, q

    def round(self, refine: bool):
        """Candidates (design (10,), crank angles (n,), RMS distance to the targets at
        those angles), most promising first."""
        lo, hi = self.bounds[:, 0], self.bounds[:, 1]
        X = lo + self.draw.random(self.popsize * _STARTS) * (hi - lo)
        given = 0
        if self.initial is not None:
            given = len(self.initial)
            X[:given] = self.initial
            self.initial = None
        if self.elite is not None and _NEAR > 0:
            # some starts near the best linkages met so far, at scales from 1% to 20%
            m = int(_NEAR * len(X))
            pick = self.elite[self.rng.integers(len(self.elite), size=m)]
            spread = np.exp(self.rng.uniform(np.log(0.01), np.log(0.2), (m, 1))) * (hi - lo)
            X[:m, :9] = pick[:, :9] + spread[:, :9] * self.rng.standard_normal((m, 9))
            X[:m, 9] = pick[:, 9]
        f, q = self.screen(X)
        f[:given] = -np.inf
        if not refine:
            best = int(np.argmin(f))
            return [(X[best], q[best], f[best])]
        keep = np.argsort(f)[:self.popsize * _KEEP]
        sigma = np.where(X[keep, 9] >= 0, 1.0, -1.0)
        q, sense = _unwrapped(q[keep])
        T, floor = self.obj.T, self.cos_floor
        Z = np.column_stack([X[keep, :9], q])
        distance, violation = np.empty(len(keep)), np.empty(len(keep))
        for i in range(0, len(keep), _CHUNK):
            part = slice(i, i + _CHUNK)
            Z[part], distance[part], violation[part] = _levenberg_marquardt(
                T, Z[part], sigma[part], sense[part], floor, _BRIEF)
        top = np.argsort(distance + violation)[:_POLISHED]
        Z, distance, violation = _levenberg_marquardt(T, Z[top], sigma[top], sense[top], floor,
                                                      _LONG)
        designs = np.column_stack([Z[:, :9], sigma[top]])
        # order, limit positions and transmission angle on the way, as the screen judges them
        penalty = self.obj.match(designs)[2] + (violation > 1e-20)
        score = np.sqrt(distance / T.shape[0]) + np.where(penalty > 0, _INFEASIBLE + penalty, 0.0)
        order = np.argsort(score)[:_CHECKED]
        if self.elite is None:
            self.elite, self.elite_score = designs[order], score[order]
            self.stalled = 0
        else:
            # rounds that improve on none of the best so far, in a row, forget them: the
            # starts near them have led into one basin, and that basin may be the wrong one
            improved = score[order[0]] < self.elite_score[0] * (1 - 1e-3)
            self.stalled = 0 if improved else self.stalled + 1
            both = np.concatenate([self.elite_score, score[order]])
            best = np.argsort(both)[:_ELITE]
            self.elite = np.concatenate([self.elite, designs[order]])[best]
            self.elite_score = both[best]
            if self.stalled >= _PATIENCE:
                self.elite = self.elite_score = None
        return [(designs[i], Z[i, 9:], score[i]) for i in order if np.isfinite(score[i])]


def path_generation(points: ArrayLike, *, runs: int = 3, maxiter: int = 15, popsize: int = 15,
                    samples: int = 180, min_transmission_angle: float = TRANSMISSION_LIMIT,
                    seed: int = 0,
                    refine: bool = True, tolerance: float = 1e-4,
                    initial: ArrayLike | None = None) -> SolutionList:
    """Four-bars whose coupler point passes near prescribed points, in order.

    Each run searches in rounds.  A round draws ``popsize * 32`` designs (a scrambled
    Halton sequence over the fixed pivots, the lengths, the coupler point and the branch,
    for the task scaled to unit size; after the first round a quarter of them near the
    best linkages found so far), scores them on their sampled coupler curves and starts
    least squares from the best ``popsize * 8`` of them, all at once: the unknowns are
    the design and the crank angle at each target, the residuals the distances from the
    coupler point to the targets at those angles and the travel's constraints (the sense
    of rotation; no limit position between the first target and the last, with a
    transmission angle of at least ``min_transmission_angle`` and 1 deg), solved by
    Levenberg-Marquardt on the whole batch with an analytic Jacobian.  The best few
    results are built as models and checked with the engine.  The run stops once it
    holds a valid linkage within ``tolerance`` of the targets, or after ``maxiter``
    rounds.

    Parameters
    ----------
    points : array_like, shape (n, 2), 3 <= n <= 30 (5 to 20 is typical)
        The target points, m, in the order the coupler point is to meet them
        (``MAX_PATH_POINTS``).
    runs : int
        Independent runs (seeds ``seed, seed + 1, ...``), 1 to 1000; each gives at most one
        linkage.
    maxiter : int
        The most rounds of each run, 1 to 1,000,000.
    popsize : int
        Size of a round, 5 to 10,000: ``popsize * 32`` designs screened, least squares from
        ``popsize * 8`` of them.
    samples : int
        Crank angles per coupler curve when designs are screened, 24 to 10,000.
    min_transmission_angle : float
        The smallest transmission angle accepted between the first target and the last,
        rad, in [0, pi/2); default 30 deg (:data:`TRANSMISSION_LIMIT`, a rule of thumb
        for smooth running).  Designs below it are penalised like defective ones while
        searching, and left out of the result (the engine's check flags them with a
        transmission angle defect); a run that finds only such linkages says in
        ``reason`` how low the best of them goes.
    seed : int
        Seed of the first run, 0 to 2**32 - 1: the result is reproducible.
    refine : bool
        Least squares from the screened designs (False: each round keeps only its best
        screened design, the sampled curve's accuracy).
    tolerance : float
        A run stops when its best linkage's RMS distance to the targets is below
        ``tolerance`` times the size of the path (the diagonal of the targets' bounding
        box).  0 runs every round.
    initial : array_like, shape (k, 10), optional
        Designs to start from (the form of :func:`coupler_curves`, m), e.g. the nearest
        curves of an atlas (:meth:`kinelab.sweep.Atlas.refine`): each run's first round
        starts least squares from them (at most ``popsize * 8``), besides its own draws,
        in a search box grown to hold them.

    Returns
    -------
    SolutionList of PathSolution
        The linkages free of branch and order defects whose transmission angle stays at
        least ``min_transmission_angle``, best (lowest RMS error) first;
        ``reason`` says why a run gave none.

    Raises
    ------
    ModelError
        Fewer than three points or more than 30, coincident points, or a bad budget.

    Examples
    --------
    Six points of a known coupler curve (so an exact linkage exists):

    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
    ...                            coupler_point=(1.5, 1.0))
    >>> pts = kl.analyze(fb, q=np.radians([0, 40, 80, 120, 160, 200])).position("P")
    >>> sols = kl.synthesis.path_generation(pts, runs=1, seed=0)
    >>> best = sols[0]
    >>> best.valid, bool(best.max_error < 1e-6)
    (True, True)
    """
    T = reals("points", points)
    if T.ndim != 2 or T.shape[1] != 2 or not 3 <= T.shape[0] <= MAX_PATH_POINTS \
            or not np.all(np.isfinite(T)):
        raise ModelError(f"points: expected 3 to {MAX_PATH_POINTS} finite points (x, y), got "
                         f"shape {T.shape}; a path is given by 5 to 20 points as a rule")
    T = point_array("points", T)
    size = float(np.ptp(T, axis=0).max())
    if 0.0 < size < MIN_LENGTH:
        raise ModelError(f"points: the points are at most {size:.3g} m apart, less than the "
                         f"smallest length kinelab computes with ({MIN_LENGTH:g} m); give the "
                         "path in smaller units")
    for i in range(T.shape[0] - 1):      # a row at a time: no n x n array
        gaps = np.hypot(*(T[i + 1:] - T[i]).T)
        if size == 0 or gaps.min() <= 1e-12 * size:
            j = i + 1 + int(np.argmin(gaps))
            raise ModelError(f"points: points {i + 1} and {j + 1} coincide; give distinct points")
    # the bounds of the task files' search section: a typo cannot ask for days of search
    runs = whole("runs", runs, 1, MAX_RUNS)
    maxiter = whole("maxiter", maxiter, 1, MAX_ROUNDS)
    popsize = whole("popsize", popsize, 5, MAX_POPSIZE)
    samples = whole("samples", samples, 24, MAX_PATH_SAMPLES)
    seed = check_seed(seed)
    refine = flag("refine", refine)
    mu = transmission_limit(min_transmission_angle)
    if not (is_real(tolerance) and 0.0 <= tolerance < 1.0):
        raise ModelError(f"tolerance: expected a fraction of the path's size in [0, 1), got "
                         f"{describe(tolerance)}")
    center = T.mean(axis=0)
    scale = float(np.linalg.norm(T - center, axis=1).max())
    obj = _Objective((T - center) / scale, samples, mu)
    goal = tolerance * float(np.hypot(*np.ptp(T, axis=0)))
    bounds, starts = _BOUNDS, None
    if initial is not None:
        starts = np.array(reals("initial", initial), float, ndmin=2)
        if starts.ndim != 2 or starts.shape[1] != 10 or not np.all(np.isfinite(starts)):
            raise ModelError(f"initial: expected finite designs of shape (k, 10), got "
                             f"{describe(initial)}")
        if np.abs(starts[:, :9]).max() > MAX_LENGTH:
            raise ModelError(f"initial: expected pivots, lengths and coupler points at most "
                             f"{MAX_LENGTH:g} m in size, got {np.abs(starts[:, :9]).max():g} m")
        starts[:, 0:4] = ((starts[:, 0:4].reshape(-1, 2, 2) - center) / scale).reshape(-1, 4)
        starts[:, 4:9] /= scale
        starts[:, 9] = np.where(starts[:, 9] >= 0, 0.5, -0.5)
        starts = starts[:popsize * _KEEP]
        # the search box grows to hold them (a long ground beside a small path, say)
        bounds = np.column_stack([np.minimum(_BOUNDS[:, 0], starts.min(axis=0)),
                                  np.maximum(_BOUNDS[:, 1], starts.max(axis=0))])
    found, reasons = [], []
    for r in range(runs):
        search = _Search(obj, popsize, seed + r, bounds, starts)
        sol = low = None        # the best valid linkage; the best one only the limit rejects
        for k in range(maxiter):
            progress.report(f"run {r + 1} of {runs}, round {k + 1} of {maxiter}",
                            (r * maxiter + k) / (runs * maxiter))
            for design, q, rms in search.round(refine):
                if sol is not None and rms * scale >= sol.rms_error:
                    continue
                phys = design.copy()
                phys[0:4] = (center + scale * design[0:4].reshape(2, 2)).ravel()
                phys[4:9] *= scale
                try:
                    s = _solution(T, phys, np.asarray(q, float).copy(), mu)
                except ModelError:
                    continue
                if s.valid and (sol is None or s.rms_error < sol.rms_error):
                    sol = s
                elif (not s.branch_defect and not s.order_defect
                      and (low is None or s.rms_error < low.rms_error)):
                    low = s
            if sol is not None and sol.rms_error <= goal:
                break
        if sol is None:
            bound = (f" with a transmission angle of at least {np.degrees(mu):.4g} deg"
                     if mu > 0 else "")
            best = ("" if low is None else
                    f" (its best, {low.rms_error:.3g} m from the points in RMS, has a smallest "
                    f"transmission angle of {np.degrees(low.min_transmission_angle):.4g} deg)")
            reasons.append(f"run {r + 1} (seed {seed + r}) found no linkage free of branch and "
                           f"order defects{bound}{best}; raise maxiter or popsize"
                           + (", or lower min_transmission_angle" if mu > 0 else ""))
        else:
            found.append(sol)
    found.sort(key=lambda s: s.rms_error)
    return SolutionList(found, reason="; ".join(reasons))
