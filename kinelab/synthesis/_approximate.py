"""More positions than exact synthesis allows: four-bars by least squares over dyads.

A dyad (crank) guides a point A of the moving plane on a circle.  With n > 5 positions no
point's positions A_1..A_n are on one circle in general, so each candidate dyad is the
best fit: for a circle point A_1 the centre A0 and radius R minimise

    sum_j ( |A_j - A0| - R )^2,

the geometric residual of each position being how much the crank would have to change
length to reach it.  That is a function of A_1 alone (A0 and R follow), explored over a
grid of circle points around the task (each grid point's circle fitted algebraically, all
at once), whose local minima are polished by least squares over (A_1, A0, R).  The best
distinct dyads are paired into four-bars, each built with the fitted crank and rocker and
checked by the kinematics engine, with its residual in every position.
"""
from __future__ import annotations

import itertools

import numpy as np

from kinelab.errors import ModelError, describe
from kinelab.synthesis._burmester import _normalised
from kinelab.synthesis._linkage import transmission_limit
from kinelab.synthesis._motion import motion_solution
from kinelab.synthesis._positions import (Positions, as_positions, check_not_one_turn, fmt,
                                          rotation)
from kinelab.synthesis._results import SolutionList

__all__ = ["approximate_positions", "fit_dyads"]

_GRID = 61          # circle points per side of the grid
_BOX = 3.0          # ... spanning the task's centre +- this many task sizes
_FAR = 20.0         # pivots farther than this many task sizes: a slider would do, not a crank
_POLISHED = 16      # local minima of the grid polished
_DISTINCT = 1e-5    # task sizes under which two fitted circle points are one dyad


def _fit_circles(pos: Positions, a: np.ndarray):
    """Algebraic circle fit of the positions of circle points a (m, 2): centres (m, 2), the
    geometric residuals (m, n) about their mean radius, the radii (m,)."""
    A = pos.points[None, :, :] + np.einsum("nij,mj->mni", rotation(pos.alpha),
                                           a - pos.points[0])          # (m, n, 2)
    M = np.concatenate([2.0 * A, np.ones(A.shape[:2] + (1,))], axis=-1)  # (m, n, 3)
    rhs = np.sum(A * A, axis=-1)
    MtM = np.einsum("mni,mnj->mij", M, M)
    Mtb = np.einsum("mni,mn->mi", M, rhs)
    with np.errstate(all="ignore"):
        try:
            sol = np.linalg.solve(MtM + 1e-300 * np.eye(3), Mtb[..., None])[..., 0]
        except np.linalg.LinAlgError:   # a point whose positions are on a line: no circle,
            sol = (np.linalg.pinv(MtM) @ Mtb[..., None])[..., 0]     # its residuals say so
    c = sol[:, :2]
    dist = np.linalg.norm(A - c[:, None, :], axis=-1)
    R = dist.mean(axis=1)
    return c, dist - R[:, None], R


def _polish(pos: Positions, a: np.ndarray, c: np.ndarray, R: float):
    """Least squares over (A_1, A0, R) from a grid minimum; (A_1, A0, R, residuals)."""
    from scipy.optimize import least_squares

    Rj = rotation(pos.alpha)
    P1 = pos.points[0]

    def residuals(z):
        A = pos.points + (Rj @ (z[:2] - P1))
        return np.linalg.norm(A - z[2:4], axis=1) - z[4]

    def jacobian(z):
        A = pos.points + (Rj @ (z[:2] - P1))
        d = A - z[2:4]
        u = d / np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
        return np.column_stack([np.einsum("ni,nij->nj", u, Rj), -u, -np.ones(pos.n)])

    res = least_squares(residuals, np.concatenate([a, c, [R]]), jac=jacobian, method="lm",
                        xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=2000)
    z = res.x
    return z[:2], z[2:4], float(z[4]), residuals(z)


def fit_dyads(points, angles=None, *, dyads: int = 4, degrees: bool = False):
    """The best dyads (cranks) for n positions of a moving plane, by least squares.

    Parameters
    ----------
    points : array_like, shape (n, 2), or Positions
        The coupler point in each position, m (n >= 5; with five the best dyads are exact,
        Burmester's).
    angles : array_like, shape (n,) or (n - 1,)
        The coupler's orientations, or its rotations from position 1, rad.
    dyads : int
        How many distinct dyads to return at most (the best first).
    degrees : bool
        Angles in degrees.

    Returns
    -------
    centers, circles : ndarray, shape (k, 2)
        Fixed pivots A0 and moving pivots A_1 (in position 1), m.
    radii : ndarray, shape (k,)
        The fitted crank lengths, m.
    residuals : ndarray, shape (k, n)
        ``|A_j - A0| - R`` for each dyad and position, m.

    Examples
    --------
    Seven positions of a catalogue four-bar's coupler: its crank and rocker fit exactly.

    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    >>> s = kl.analyze(fb, q=np.radians(np.arange(0, 140, 20)))
    >>> A0, A1, R, res = kl.synthesis.fit_dyads(s.position("P"), s.angle("coupler"), dyads=2)
    >>> A0.round(9) + 0.0, R.round(9), bool(np.abs(res).max() < 1e-9)
    (array([[0., 0.],
           [3., 0.]]), array([1. , 2.5]), True)
    """
    pos = as_positions(points, angles, degrees)
    if pos.n < 5:
        raise ModelError(f"points: expected at least five positions for a least-squares fit, "
                         f"got {pos.n}; fewer are met exactly (two_positions, three_positions, "
                         "four_positions)")
    check_not_one_turn(pos)
    if isinstance(dyads, bool) or not isinstance(dyads, (int, np.integer)) or not 2 <= dyads <= 100:
        raise ModelError(f"dyads: expected a whole number from 2 to 100, got {describe(dyads)}")
    npos, origin, L = _normalised(pos)
    mid = npos.points.mean(axis=0)
    g = np.linspace(-_BOX, _BOX, _GRID)
    a = mid + np.stack(np.meshgrid(g, g, indexing="ij"), -1).reshape(-1, 2)
    c, res, R = _fit_circles(npos, a)
    rms = np.sqrt(np.mean(res * res, axis=1))
    far = ~np.all(np.isfinite(c), axis=1) | (np.linalg.norm(c - mid, axis=1) > _FAR)
    rms = np.where(far | ~np.isfinite(rms), np.inf, rms).reshape(_GRID, _GRID)
    padded = np.pad(rms, 1, constant_values=np.inf)
    neighbours = np.stack([padded[1 + di:_GRID + 1 + di, 1 + dj:_GRID + 1 + dj]
                           for di in (-1, 0, 1) for dj in (-1, 0, 1) if di or dj])
    minima = np.flatnonzero((rms <= neighbours.min(axis=0)) & np.isfinite(rms))
    minima = minima[np.argsort(rms.ravel()[minima])][:_POLISHED]
    fits = []
    for k in minima:
        a1, c1, r1, rj = _polish(npos, a[k], c[k], R[k])
        z = np.concatenate([a1, c1, [r1]])
        # a pivot or a pin far off (a crank almost a slider) is no crank to build
        if not (np.all(np.isfinite(z)) and np.linalg.norm(c1 - mid) <= _FAR
                and np.linalg.norm(a1 - mid) <= _FAR and 0 < r1 <= 2 * _FAR):
            continue
        # one dyad per circle point (the positions of one point are on one best circle;
        # along a flat valley the polish may stop at slightly different centres)
        if any(np.linalg.norm(a1 - f[0]) <= _DISTINCT for f in fits):
            continue
        fits.append((a1, c1, r1, rj))
    fits.sort(key=lambda f: float(np.sqrt(np.mean(f[3] ** 2))))
    fits = fits[:dyads]
    centers = origin + L * np.array([f[1] for f in fits]).reshape(-1, 2)
    circles = origin + L * np.array([f[0] for f in fits]).reshape(-1, 2)
    radii = L * np.array([f[2] for f in fits])
    residuals = L * np.array([f[3] for f in fits]).reshape(-1, pos.n)
    for arr in (centers, circles, radii, residuals):
        arr.setflags(write=False)
    return centers, circles, radii, residuals


def approximate_positions(points, angles=None, *, dyads: int = 4,
                          min_transmission_angle: float | None = None,
                          degrees: bool = False) -> SolutionList:
    """More than five positions: four-bars from the best least-squares dyads.

    The best ``dyads`` dyads (:func:`fit_dyads`) are paired into four-bars, each driven
    by the shorter of its two, built with the fitted crank and rocker lengths (assembled at
    position 1's crank angle on position 1's branch) and checked with the engine.

    Parameters
    ----------
    points : array_like, shape (n, 2), or Positions
        The coupler point P in each position, m; n >= 6.
    angles : array_like, shape (n,) or (n - 1,)
        The coupler's orientations, or its rotations from position 1, rad.
    dyads : int
        Dyads to combine (the best first): up to dyads (dyads - 1) / 2 four-bars.
    min_transmission_angle : float, optional
        The smallest transmission angle accepted between position 1 and the last (rad, or
        degrees with ``degrees=True``); default 30 deg (:data:`TRANSMISSION_LIMIT`).  A
        linkage below it has a transmission angle defect.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    SolutionList of MotionSolution
        Usable linkages first, then by the RMS of their position errors.  Each has
        ``dyad_residuals`` (n, 2): the least-squares residual of its crank and rocker in
        every position, m; ``position_errors`` and ``angle_errors``: the engine's coupler
        pose against the prescribed one at the crank angle ``q[j]`` of each position
        (where the crank dyad puts its pin nearest the prescribed circle point).

    Raises
    ------
    ModelError
        Fewer than six positions, non-finite numbers or coincident positions.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    >>> s = kl.analyze(fb, q=np.radians(np.arange(0, 140, 20)))
    >>> sols = kl.synthesis.approximate_positions(s.position("P"), s.angle("coupler"))
    >>> best = sols[0]
    >>> best.valid, bool(best.position_errors.max() < 1e-9)
    (True, True)
    """
    pos = as_positions(points, angles, degrees)
    limit = transmission_limit(min_transmission_angle, degrees)
    if pos.n < 6:
        raise ModelError(f"points: expected more than five positions, got {pos.n}; "
                         + ("use five_positions" if pos.n == 5 else "fewer are met exactly "
                            "(two_positions, three_positions, four_positions)"))
    centers, circles, radii, _ = fit_dyads(pos, dyads=dyads)
    sols, reasons = [], []
    for i, j in itertools.combinations(range(centers.shape[0]), 2):
        if radii[j] < radii[i]:
            i, j = j, i
        try:
            sols.append(motion_solution(pos, centers[i], centers[j], circles[i], circles[j],
                                        radii=(float(radii[i]), float(radii[j])), limit=limit,
                                        remedy="other pairs of dyads may still give one"))
        except ModelError as exc:
            reasons.append(f"dyads at {fmt(centers[i])} and {fmt(centers[j])} left out: {exc}")
    sols.sort(key=lambda s: (not s.valid, float(np.sqrt(np.mean(s.position_errors ** 2)))))
    if centers.shape[0] < 2:
        reasons.insert(0, f"{centers.shape[0]} dyad(s) found; a four-bar needs two")
    return SolutionList(sols, reason="; ".join(reasons))
