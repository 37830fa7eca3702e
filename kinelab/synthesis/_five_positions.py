"""Five prescribed positions: Burmester's points and every four-bar through them.

With five positions a dyad's fixed pivot A0 must be a centre point of positions 1-4 *and*
of positions 1, 2, 3, 5: it lies on two centre-point cubics (*Mecanismos*, eq. 71, with
the rows j = 2, 3, 4 and j = 2, 3, 5 of the Suh-Radcliffe system).  Two cubics meet in
nine points; three are the poles P12, P13, P23 that both curves pass through, two are the
circular points at infinity (the curves are circular cubics), and the other four are
Burmester's points: 0, 2 or 4 of them real.  At a Burmester point all four rows are
compatible and give the moving pivot A1.

They are found by elimination: for each abscissa x the two cubics in y have a common root
exactly where their resultant (the 6 x 6 Sylvester determinant) vanishes, a polynomial of
degree 9 in x, sampled at Chebyshev nodes and fitted exactly.  Each of its real roots gives
a candidate (x, y), polished by Newton's method on the four equations in the four unknowns
(A0, A1); candidates that do not satisfy all four (the poles) are dropped.  Every pair of
the k real dyads makes one four-bar: k (k - 1) / 2 of them, six at most, each checked by
the kinematics engine (branch, order and circuit defects, Grashof class).
"""
from __future__ import annotations

import itertools

import numpy as np

from kinelab.errors import ModelError, describe
from kinelab.solvers._arguments import flag, reals
from kinelab.synthesis._burmester import BurmesterCurves, _cubic, _normalised, burmester_curves
from kinelab.synthesis._linkage import transmission_limit
from kinelab.synthesis._motion import motion_solution
from kinelab.synthesis._pivots import suh_radcliffe_rows
from kinelab.synthesis._positions import (Positions, as_positions, check_not_one_turn, fmt,
                                          rotation)
from kinelab.synthesis._results import SolutionList

__all__ = ["burmester", "burmester_points", "five_positions"]

_NODES = 40          # Chebyshev nodes the resultant is sampled at (its degree is 9)
_SPAN = 4.0          # ... over |x| <= _SPAN task sizes
_IMAG = 1e-6         # |imaginary part| (relative) of a resultant root still taken as real
_SOLVED = 1e-10      # relative residual of the four equations at a Burmester point
_DISTINCT = 1e-8     # relative distance under which two Burmester points are one


def _five(points, angles, degrees) -> Positions:
    pos = as_positions(points, angles, degrees)
    if pos.n != 5:
        hint = {4: "; use four_positions", 3: "; use three_positions"}.get(pos.n, "")
        if pos.n > 5:
            hint = "; use approximate_positions for more than five"
        raise ModelError(f"points: expected five positions, got {pos.n}{hint}")
    check_not_one_turn(pos)
    return pos


def _rotated(pos: Positions, gamma: float) -> Positions:
    """The same task seen from a frame turned by -gamma (rotations are unchanged)."""
    return Positions(pos.points @ rotation(gamma).T, pos.alpha)


def _frame(pos: Positions) -> float:
    """A frame rotation that keeps the y^3 coefficient of both cubics away from zero, so
    that neither drops a degree in y (the resultant would lose roots)."""
    gammas = np.linspace(0.0, np.pi, 13)[:-1]
    best, score = 0.0, -1.0
    for g in gammas:
        p = _rotated(pos, g)
        c = np.stack([_cubic(p, np.zeros(1), rows)[0] for rows in ((0, 1, 2), (0, 1, 3))])
        s = float(np.min(np.abs(c[:, 0]) / np.maximum(np.abs(c).max(axis=1), 1e-300)))
        if s > score:
            best, score = float(g), s
    return best


def _sylvester(f: np.ndarray, g: np.ndarray) -> np.ndarray:
    """det of the Sylvester matrix of two cubics (coefficients (m, 4), highest first)."""
    m = f.shape[0]
    S = np.zeros((m, 6, 6))
    for k in range(3):
        S[:, k, k:k + 4] = f
        S[:, 3 + k, k:k + 4] = g
    return np.linalg.det(S)


def _equations(pos: Positions, z: np.ndarray):
    """The four equations |A_j - A0|^2 = |A_1 - A0|^2 (j = 2..5) in z = (A0, A1) relative to
    P1, and their Jacobian (4, 4)."""
    a0, a = z[:2], z[2:]
    rows = suh_radcliffe_rows(pos, a0 + pos.points[0])          # (4, 3)
    e = rows[:, :2] @ a - rows[:, 2]
    R = rotation(pos.alpha[1:])
    d = pos.points[1:] - pos.points[0]
    d_a0 = 2.0 * (a - np.einsum("kij,j->ki", R, a)) - 2.0 * d     # d e_j / d a0
    return e, np.concatenate([d_a0, rows[:, :2]], axis=1), rows


def _polish(pos: Positions, a0: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Newton's method on the four equations from a candidate centre point; the dyad
    (A0, A1) relative to P1, or None when it does not converge to one."""
    rows = suh_radcliffe_rows(pos, a0 + pos.points[0])
    a, *_ = np.linalg.lstsq(rows[:, :2], rows[:, 2], rcond=None)
    z = np.concatenate([a0, a])
    with np.errstate(over="ignore", invalid="ignore"):    # a diverging start: None below
        for _ in range(50):
            e, J, rows = _equations(pos, z)
            if not (np.all(np.isfinite(e)) and np.all(np.isfinite(J))):
                return None
            try:
                step = np.linalg.solve(J, -e)
            except np.linalg.LinAlgError:
                return None
            z = z + step
            if not np.all(np.isfinite(z)):
                return None
            if np.abs(step).max() <= 1e-15 * (1.0 + np.abs(z).max()):
                break
        e, _, rows = _equations(pos, z)
        if not np.all(np.isfinite(e)):
            return None
    scale = np.linalg.norm(rows, axis=1).max() * (1.0 + np.abs(z).max())
    s = np.linalg.svd(rows[:, :2], compute_uv=False)
    if np.abs(e).max() > _SOLVED * scale or s[-1] <= 1e-9 * s[0]:
        return None
    return z[:2], z[2:]


def burmester_points(points, angles=None, *, degrees: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Burmester's points of five positions: every real centre point and its circle point.

    Parameters
    ----------
    points : array_like, shape (5, 2), or Positions
        The coupler point P in the five positions, m.
    angles : array_like, shape (5,) or (4,)
        The coupler's orientations, or its rotations alpha_2..alpha_5 from position 1, rad.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    centers, circles : ndarray, shape (k, 2)
        The fixed pivots A0 and the matching moving pivots A1 (in position 1), m, sorted
        by the abscissa of A0; k is 0, 2 or 4 (an odd count when two points coincide).

    Examples
    --------
    Five positions of a catalogue four-bar's coupler: its own pivots are among the points.

    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    >>> s = kl.analyze(fb, q=np.radians([0, 30, 60, 90, 120]))
    >>> A0, A1 = kl.synthesis.burmester_points(s.position("P"), s.angle("coupler"))
    >>> bool(np.linalg.norm(A0 - [0, 0], axis=1).min() < 1e-9)       # O2
    True
    >>> bool(np.linalg.norm(A0 - [3, 0], axis=1).min() < 1e-9)       # O4
    True
    """
    pos = _five(points, angles, degrees)
    npos, origin, L = _normalised(pos)
    gamma = _frame(npos)
    rpos = _rotated(npos, gamma)
    x = _SPAN * np.cos(np.pi * (np.arange(_NODES) + 0.5) / _NODES)
    f, g = _cubic(rpos, x, (0, 1, 2)), _cubic(rpos, x, (0, 1, 3))
    cheb = np.polynomial.chebyshev
    coef = cheb.chebfit(x / _SPAN, _sylvester(f, g), 9)
    coef[np.abs(coef) <= 1e-13 * np.abs(coef).max()] = 0.0
    found = []
    if np.any(coef != 0):
        roots = cheb.chebroots(np.trim_zeros(coef, "b")) * _SPAN
        roots = roots[np.abs(roots.imag) <= _IMAG * (1.0 + np.abs(roots))].real
        for xr in roots:
            fx = _cubic(rpos, np.array([xr]), (0, 1, 2))[0]
            lead = np.flatnonzero(np.abs(fx) > 1e-12 * np.abs(fx).max())
            if lead.size == 0:
                continue
            # every root y of the first cubic is tried: two intersections may share (nearly)
            # the same x, and Newton's method tells the genuine ones
            ys = np.roots(fx[lead[0]:])
            for y in ys[np.abs(ys.imag) <= 1e-3 * (1.0 + np.abs(ys))].real:
                z = _polish(rpos, np.array([xr, y]))
                if z is not None:
                    found.append(z)
    centers, circles = [], []
    back = rotation(-gamma)
    for a0, a in found:
        A0 = origin + L * (back @ a0)
        if any(np.linalg.norm(A0 - c) <= _DISTINCT * max(L, np.linalg.norm(A0 - origin))
               for c in centers):
            continue
        centers.append(A0)
        circles.append(origin + L * (back @ a))
    order = np.argsort([c[0] for c in centers])
    centers = np.array(centers, float).reshape(-1, 2)[order]
    circles = np.array(circles, float).reshape(-1, 2)[order]
    for arr in (centers, circles):
        arr.setflags(write=False)
    return centers, circles


def five_positions(points, angles=None, *, min_transmission_angle: float | None = None,
                   degrees: bool = False) -> SolutionList:
    """Five positions: every four-bar whose coupler passes through them (Burmester).

    Each pair of the real Burmester points (:func:`burmester_points`) makes one four-bar,
    driven by the shorter of its two dyads (the more likely to turn fully); each is built
    as a model sketched in position 1 and checked with the engine.

    Parameters
    ----------
    points, angles, degrees : see :func:`burmester_points`
        The five positions.
    min_transmission_angle : float, optional
        The smallest transmission angle accepted between position 1 and the last (rad, or
        degrees with ``degrees=True``); default 30 deg (:data:`TRANSMISSION_LIMIT`).  A
        linkage below it has a transmission angle defect.

    Returns
    -------
    SolutionList of MotionSolution
        Up to six linkages, each with ``A0, B0, A1, B1``, the ``model``, its defects
        (branch, order, circuit, transmission angle) and Grashof class (keep
        ``[s for s in sols if s.valid]`` for the usable ones); when there are fewer than
        two real Burmester points the list is empty and ``reason`` says so.

    Raises
    ------
    ModelError
        Not five positions, or two positions that coincide.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    >>> s = kl.analyze(fb, q=np.radians([0, 30, 60, 90, 120]))
    >>> sols = kl.synthesis.five_positions(s.position("P"), s.angle("coupler"))
    >>> mine = min(sols, key=lambda x: np.linalg.norm(np.r_[x.A0, x.B0] - [0, 0, 3, 0]))
    >>> mine.valid, bool(mine.position_errors.max() < 1e-9)
    (True, True)
    """
    pos = _five(points, angles, degrees)
    limit = transmission_limit(min_transmission_angle, degrees)
    centers, circles = burmester_points(pos)
    k = centers.shape[0]
    if k < 2:
        return SolutionList([], reason=f"{'no' if k == 0 else 'only one'} real Burmester point "
                            "(centre point common to the five positions); a four-bar needs two: "
                            "change the positions")
    sols, reasons = [], []
    for i, j in itertools.combinations(range(k), 2):
        # the shorter dyad drives
        if np.linalg.norm(circles[j] - centers[j]) < np.linalg.norm(circles[i] - centers[i]):
            i, j = j, i
        try:
            sols.append(motion_solution(pos, centers[i], centers[j], circles[i], circles[j],
                                        limit=limit,
                                        remedy="other pairs of Burmester points may give one"))
        except ModelError as exc:
            reasons.append(f"Burmester points {fmt(centers[i])} and {fmt(centers[j])} left "
                           f"out: {exc}")
    return SolutionList(sols, reason="; ".join(reasons))


def _poses(poses, angles, degrees: bool) -> Positions:
    """Poses as Positions: a Positions, rows (x, y, angle), or points with ``angles``."""
    if isinstance(poses, Positions) or angles is not None:
        return as_positions(poses, angles, degrees)
    a = reals("poses", poses)
    if a.ndim != 2 or a.shape[1] != 3:
        raise ModelError(f"poses: expected rows (x, y, angle) of shape (n, 3), or points (n, 2) "
                         f"with angles, got shape {a.shape}")
    bad = ~np.all(np.isfinite(a), axis=1)
    if bad.any():
        j = int(np.flatnonzero(bad)[0])
        raise ModelError(f"poses[{j}]: expected three finite numbers (x, y, angle), got "
                         f"{describe(a[j].tolist())}")
    return Positions(a[:, :2], a[:, 2], degrees=degrees)


def burmester(poses, angles=None, *, all_solutions: bool = True, samples: int = 1441,
              min_transmission_angle: float | None = None,
              degrees: bool = False) -> SolutionList | BurmesterCurves:
    """Burmester's theory for four or five poses: the curves, or every real four-bar.

    - **five poses**: every real Burmester point (centre point common to the five poses,
      :func:`burmester_points`) is the fixed pivot of a dyad that reaches all five; each
      pair of them is a four-bar (:func:`five_positions`), built as a model in pose 1
      and checked by the engine;
    - **four poses**: the dyads form one-parameter families, the centre-point and
      circle-point curves (:func:`burmester_curves`), returned traced.

    Parameters
    ----------
    poses : array_like, shape (n, 3), or shape (n, 2) with ``angles``, or Positions
        The poses of the coupler, n = 4 or 5: rows (x, y, angle) (m, and rad or degrees
        with ``degrees=True``), or the points of the coupler point P with the
        orientations (or the rotations from pose 1) in ``angles``.
    angles : array_like, shape (n,) or (n - 1,), optional
        With points in ``poses``: see :class:`Positions`.
    all_solutions : bool
        True (default): every real dyad pair, whatever its defects (branch, order,
        circuit, transmission angle), as :func:`five_positions` returns them; False: only
        those without a defect (``valid``), the others named in ``reason``.  Four poses:
        no effect.
    samples : int
        Four poses: the crank rotations beta_2 sampled over one turn along the curves.
    min_transmission_angle : float, optional
        Five poses: as in :func:`five_positions`.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    SolutionList of MotionSolution (five poses) or BurmesterCurves (four poses)
        For five poses: up to six four-bars (k (k - 1) / 2 of k = 0, 2 or 4 real
        Burmester points), with ``reason`` saying why the list is empty or what was left
        out.

    Raises
    ------
    ModelError
        Not four or five poses, poses of the wrong shape, or two poses that coincide.

    Examples
    --------
    Five poses of the coupler of a catalogue four-bar: its own pivots are among the
    solutions.

    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    >>> s = kl.analyze(fb, q=np.radians([0, 30, 60, 90, 120]))
    >>> poses = np.column_stack([s.position("P"), s.angle("coupler")])      # (5, 3)
    >>> sols = kl.synthesis.burmester(poses)
    >>> len(sols) == len(kl.synthesis.five_positions(s.position("P"), s.angle("coupler")))
    True
    >>> any(np.allclose(np.r_[x.A0, x.B0], [0, 0, 3, 0], atol=1e-9) for x in sols)
    True
    >>> kl.synthesis.burmester(poses[:4], samples=361).center.shape      # four: the curves
    (2, 361, 2)
    """
    degrees = flag("degrees", degrees)
    all_solutions = flag("all_solutions", all_solutions)
    pos = _poses(poses, angles, degrees)
    if pos.n == 4:
        return burmester_curves(pos, samples=samples)
    if pos.n != 5:
        hint = ("; use three_positions (or two_positions)" if pos.n < 4
                else "; use approximate_positions")
        raise ModelError(f"poses: expected four or five poses, got {pos.n}{hint}")
    sols = five_positions(pos, min_transmission_angle=min_transmission_angle, degrees=degrees)
    if all_solutions:
        return sols
    kept = [x for x in sols if x.valid]
    why = [sols.reason] if sols.reason else []
    if len(kept) < len(sols):
        why.append(f"{len(sols) - len(kept)} of the {len(sols)} four-bars left out for their "
                   "defects (all_solutions=True keeps them)")
    return SolutionList(kept, reason="; ".join(why))
