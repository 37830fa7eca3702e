"""Path generation: a four-bar whose coupler point passes near prescribed points
(*Mecanismos*, §3.2, fig. 26), by global optimisation.

The timing is free (the crank angle at each point is not prescribed).  A design is the
fixed pivots A0, B0, the crank, coupler and rocker lengths, the coupler point (u along AB,
v to its left) and the assembly branch.  Its coupler curve is evaluated in closed form
for a whole population of designs at once (:func:`coupler_curves`); each target point is
matched to the nearest sample of the curve, and the objective is the RMS distance, with a
penalty when the matched samples are not met in order by one sense of crank rotation
without a limit position in between (order and branch defects) or when the transmission
angle drops below a bound.  scipy's differential evolution searches the space with that
vectorised objective; the best design is then refined by least squares over the design
*and* the crank angles of the points, built as a model, and checked with the engine.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.mechanisms import Grashof
from kinelab.model import Mechanism
from kinelab.synthesis._linkage import (CheckedLinkage, at_inputs, finite_or_inf, fourbar_model,
                                        model_grashof, travel)
from kinelab.synthesis._results import SolutionList

__all__ = ["coupler_curves", "PathSolution", "path_generation"]

_INFEASIBLE = 1.0      # added to the objective (task normalised to unit size) of a design
                       # whose points are not met in order on one branch
_NOWHERE = 100.0       # objective of a design that assembles at no sample
_MU_FLOOR = np.radians(1.0)   # the polish keeps the transmission angle above this at least
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
    x = np.asarray(designs, float)
    if x.ndim != 2 or x.shape[1] != 10:
        raise ModelError(f"designs: expected shape (D, 10), got {x.shape}")
    q = np.asarray(q, float)
    if q.ndim not in (1, 2) or (q.ndim == 2 and q.shape[0] != x.shape[0]):
        raise ModelError(f"q: expected shape (m,) or ({x.shape[0]}, m), got {q.shape}")
    a0x, a0y, b0x, b0y, r2, r3, r4, u, v, branch = (x[:, k][:, None] for k in range(10))
    sigma = np.where(branch >= 0, 1.0, -1.0)
    Ax = a0x + r2 * np.cos(q)             # q (m,) is shared by every design: one cos, one sin
    Ay = a0y + r2 * np.sin(q)
    dx, dy = b0x - Ax, b0y - Ay
    L = np.hypot(dx, dy)
    Ls = np.where(L > 0, L, 1.0)
    ex, ey = dx / Ls, dy / Ls
    p = (r3 * r3 - r4 * r4 + L * L) / (2 * Ls)
    h2 = r3 * r3 - p * p
    assembled = (L > 0) & (h2 >= 0)
    h = np.sqrt(np.maximum(h2, 0.0))
    Bx = Ax + p * ex - sigma * h * ey
    By = Ay + p * ey + sigma * h * ex
    wx, wy = (Bx - Ax) / r3, (By - Ay) / r3
    P = np.stack([Ax + u * wx - v * wy, Ay + u * wy + v * wx], -1)
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
        Crank angle at which the coupler point is nearest each target, rad.
    errors : ndarray, shape (n,)
        Distance from each target to the engine's coupler point at ``q``, m.
    coupler_point : (float, float)
        P from A, along AB and to its left, m.
    grashof : Grashof
    min_transmission_angle : float
        Over the travel from the first target to the last, rad.
    branch_defect, order_defect : bool
    direction : int
        +1 / -1: the crank turns counter-clockwise / clockwise through the targets.
    defects : tuple of str
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

    @property
    def rms_error(self) -> float:
        """Root-mean-square distance of the targets from the coupler curve, m."""
        return float(np.sqrt(np.mean(self.errors ** 2)))

    @property
    def max_error(self) -> float:
        """Largest distance of a target from the coupler curve, m."""
        return float(self.errors.max())

    def __repr__(self) -> str:
        state = self.state
        return (f"PathSolution(rms error={self.rms_error:.3g} m, max error={self.max_error:.3g} m, "
                f"{self.grashof.kind}, {state})")


def _refine(obj: _Objective, design: np.ndarray, q: np.ndarray):
    """Least squares over the design (branch kept) and the targets' crank angles.

    Besides the distances to the targets, the residuals keep what the global search
    made sure of: the crank angles stay in the sense of travel found there, and the loop
    closes all the way from the first target to the last, with a transmission angle of at
    least max(min_transmission_angle, 1 deg), which keeps the motion off the limit
    positions.  That is checked exactly: the transmission angle is a monotonic function of
    the distance L from the crank pin to B0, and L is monotonic between its extremes, met
    where the crank points at B0 or away from it; so only the ends of the travel and those
    two angles (when they are on the way) need checking."""
    from scipy.optimize import least_squares

    n = obj.T.shape[0]
    branch = design[9]
    cos_floor = np.cos(max(obj.mu_min, _MU_FLOOR))
    # unwrap the angles along the sense in which they are met
    steps = {d: np.mod(d * np.diff(q), 2 * np.pi) for d in (1, -1)}
    sense = min((1, -1), key=lambda d: steps[d].sum())
    q = q[0] + sense * np.concatenate([[0.0], np.cumsum(steps[sense])])

    def residuals(Z):
        """Residuals of a batch of variable vectors Z (K, 9 + n) -> (K, 3n + 1)."""
        d = np.column_stack([Z[:, :9], np.full(Z.shape[0], branch)])
        qz = Z[:, 9:]
        P, A, _, _ = coupler_curves(d, qz)
        a0, b0, r2, r3, r4 = d[:, 0:2], d[:, 2:4], d[:, 4], d[:, 5], d[:, 6]
        g = b0 - a0
        G = np.hypot(g[:, 0], g[:, 1])
        phi = np.arctan2(g[:, 1], g[:, 0])
        L = np.hypot(b0[:, None, 0] - A[..., 0], b0[:, None, 1] - A[..., 1])      # (K, n)
        span = sense * (qz[:, -1] - qz[:, 0])
        on_way = [np.mod(sense * (psi - qz[:, 0]), 2 * np.pi) <= span for psi in (phi, phi + np.pi)]
        L_min = np.where(on_way[0], np.abs(G - r2), np.minimum(L[:, 0], L[:, -1]))
        L_max = np.where(on_way[1], G + r2, np.maximum(L[:, 0], L[:, -1]))
        # mu >= mu_floor all the way <=> L within the band where the law of cosines gives it
        L_hi = np.sqrt(r3 * r3 + r4 * r4 + 2 * r3 * r4 * cos_floor)
        L_lo = np.sqrt(np.maximum(r3 * r3 + r4 * r4 - 2 * r3 * r4 * cos_floor, 0.0))
        gap = (np.maximum(L_max - L_hi, 0) + np.maximum(L_lo - L_min, 0))[:, None]
        back = np.maximum(-sense * np.diff(qz, axis=1), 0)
        return np.concatenate([(P - obj.T).reshape(len(Z), -1), 10.0 * gap, 10.0 * back],
                              axis=1)

    def jacobian(z):
        # central differences, every column in one vectorised evaluation
        h = 1e-6 * np.maximum(1.0, np.abs(z))
        E = np.diag(h)
        R = residuals(np.concatenate([z + E, z - E]))
        return ((R[:z.size] - R[z.size:]) / (2 * h[:, None])).T

    z0 = np.concatenate([design[:9], q])
    lo = np.r_[[-np.inf] * 4, [1e-3] * 3, [-np.inf] * 2, [-np.inf] * n]
    try:
        res = least_squares(lambda z: residuals(z[None, :])[0], z0, jac=jacobian,
                            bounds=(lo, np.inf), method="trf", max_nfev=100 * (9 + n))
    except (ValueError, np.linalg.LinAlgError):
        return None
    return np.concatenate([res.x[:9], [branch]]), res.x[9:]


def _solution(targets: np.ndarray, design: np.ndarray, q: np.ndarray) -> PathSolution:
    """Build and check the linkage of a design (physical units) through its crank angles."""
    P, A, B, ok = coupler_curves(design[None, :], q[None, :])
    if not ok[0, 0]:
        raise ModelError("the linkage does not close at the first target")
    model = fourbar_model(design[0:2], design[2:4], A[0, 0], B[0, 0], P[0, 0],
                          name="path generator")
    scale = max(float(np.ptp(targets, axis=0).max()), float(design[4:7].max()))

    def reached(sol, idx):
        return np.linalg.norm(sol.position("P")[idx] - P[0], axis=-1) <= _REACHED * scale

    t = travel(model, q, reached)
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
        defects=t.defects)


def path_generation(points: ArrayLike, *, runs: int = 3, maxiter: int = 300, popsize: int = 15,
                    samples: int = 180, min_transmission_angle: float = 0.0, seed: int = 0,
                    refine: bool = True, initial: ArrayLike | None = None) -> SolutionList:
    """Four-bars whose coupler point passes near prescribed points, in order.

    Parameters
    ----------
    points : array_like, shape (n, 2), n >= 3 (5 to 10 is typical)
        The target points, m, in the order the coupler point is to meet them.
    runs : int
        Independent differential-evolution runs (seeds ``seed, seed + 1, ...``); each
        gives at most one linkage.
    maxiter, popsize : int
        Budget of each run (scipy's ``differential_evolution``; a population of
        ``popsize * 10`` designs is evaluated at once, vectorised).
    samples : int
        Crank angles per coupler curve in the global search.
    min_transmission_angle : float
        Designs whose transmission angle drops below this (rad) between the first and
        last target are penalised like defective ones.
    seed : int
        Seed of the first run: the result is reproducible.
    refine : bool
        Polish each run's best design by least squares over the design and the crank
        angles of the targets (exact when an exact solution is near).
    initial : array_like, shape (k, 10), optional
        Designs to start from (the form of :func:`coupler_curves`, m), e.g. the nearest
        curves of an atlas (:meth:`kinelab.sweep.Atlas.refine`): they join each run's first
        population, the rest of which is drawn as usual (Latin hypercube), in a search box
        grown to hold them.

    Returns
    -------
    SolutionList of PathSolution
        The linkages free of branch and order defects, best (lowest RMS error) first;
        ``reason`` says why a run gave none.

    Raises
    ------
    ModelError
        Fewer than three points, coincident points, or a bad budget.

    Examples
    --------
    Six points of a known coupler curve (so an exact linkage exists):

    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
    ...                            coupler_point=(1.5, 1.0))
    >>> pts = kl.analyze(fb, q=np.radians([0, 40, 80, 120, 160, 200])).position("P")
    >>> sols = kl.synthesis.path_generation(pts, runs=1, maxiter=60, seed=0)
    >>> best = sols[0]
    >>> best.valid, bool(best.max_error < 1e-6)
    (True, True)
    """
    T = np.asarray(points, float)
    if T.ndim != 2 or T.shape[1] != 2 or T.shape[0] < 3 or not np.all(np.isfinite(T)):
        raise ModelError(f"points: expected at least three finite points, shape (n, 2), got "
                         f"{T.shape}")
    size = float(np.ptp(T, axis=0).max())
    gaps = np.linalg.norm(T[:, None] - T[None, :], axis=-1)
    np.fill_diagonal(gaps, np.inf)
    if size == 0 or gaps.min() <= 1e-12 * size:
        i, j = np.unravel_index(np.argmin(gaps), gaps.shape)
        raise ModelError(f"points: points {min(i, j) + 1} and {max(i, j) + 1} coincide; give "
                         "distinct points")
    for name, v, low in (("runs", runs, 1), ("maxiter", maxiter, 1), ("popsize", popsize, 5),
                         ("samples", samples, 24)):
        if not (isinstance(v, (int, np.integer)) and v >= low):
            raise ModelError(f"{name}: expected an integer >= {low}, got {describe(v)}")
    mu = min_transmission_angle
    if not (isinstance(mu, (int, float)) and 0.0 <= mu < np.pi / 2):
        raise ModelError(f"min_transmission_angle: expected an angle in [0, pi/2) rad, got {describe(mu)}")
    from scipy.optimize import differential_evolution

    center = T.mean(axis=0)
    scale = float(np.linalg.norm(T - center, axis=1).max())
    obj = _Objective((T - center) / scale, samples, float(min_transmission_angle))
    bounds = [(-3, 3)] * 4 + [(0.05, 3.0), (0.05, 6.0), (0.05, 6.0), (-4, 4), (-4, 4), (-1, 1)]
    starts = None
    if initial is not None:
        starts = np.array(initial, float, ndmin=2)
        if starts.ndim != 2 or starts.shape[1] != 10 or not np.all(np.isfinite(starts)):
            raise ModelError(f"initial: expected finite designs of shape (k, 10), got {describe(initial)}")
        starts[:, 0:4] = ((starts[:, 0:4].reshape(-1, 2, 2) - center) / scale).reshape(-1, 4)
        starts[:, 4:9] /= scale
        starts[:, 9] = np.where(starts[:, 9] >= 0, 0.5, -0.5)
        starts = starts[: popsize * 10]
        # the search box grows to hold them (a long ground beside a small path, say)
        lo, hi = np.array(bounds).T
        lo, hi = np.minimum(lo, starts.min(axis=0)), np.maximum(hi, starts.max(axis=0))
        bounds = list(zip(lo, hi))
    found, reasons = [], []
    for r in range(runs):
        init = "latinhypercube"
        if starts is not None:
            from scipy.stats import qmc
            lo, hi = np.array(bounds).T
            init = lo + qmc.LatinHypercube(d=10, seed=seed + r).random(popsize * 10) * (hi - lo)
            init[: len(starts)] = starts
        res = differential_evolution(obj, bounds, maxiter=maxiter, popsize=popsize, seed=seed + r,
                                     vectorized=True, updating="deferred", polish=False, tol=0.0,
                                     init=init)
        design = res.x
        k = obj.match(design[None, :])[0]
        q = k[0] * (2 * np.pi / samples)        # crank angles of the matched curve points
        candidates = []
        if refine:
            refined = _refine(obj, design, q)
            if refined is not None:
                candidates.append(refined)
        candidates.append((design, q))
        sol = None
        for d, q in candidates:
            phys = d.copy()
            phys[0:4] = (center + scale * d[0:4].reshape(2, 2)).ravel()
            phys[4:9] *= scale
            try:
                s = _solution(T, phys, np.asarray(q, float).copy())
            except ModelError:
                continue
            if s.valid and (sol is None or s.rms_error < sol.rms_error):
                sol = s
        if sol is None:
            reasons.append(f"run {r + 1} (seed {seed + r}) found no linkage free of branch and "
                           "order defects; raise maxiter or popsize")
        else:
            found.append(sol)
    found.sort(key=lambda s: s.rms_error)
    return SolutionList(found, reason="; ".join(reasons))

