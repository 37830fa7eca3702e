"""Four prescribed positions: centre points, circle points and every four-bar
(*Mecanismos*, §6.3, §6.6).

With four positions the three equations |A_j - A0| = |A_1 - A0| (j = 2, 3, 4) in the two
unknowns of A_1 are compatible only if the determinant of the augmented matrix vanishes
(eq. 71).  Each row of that matrix is *affine* in A0 (the C of eq. 68 is
``a0x^2 + a0y^2 - |r_j|^2`` with ``r_j`` affine in A0, and the squares cancel), so the
determinant is a cubic in A0: Burmester's centre-point curve.  For a given a0x it is a
cubic in a0y, whose coefficients come exactly from the multilinearity of the determinant
in its rows: with row_j = u_j + t v_j,

    det = sum over subsets S of the rows  t^|S| det(rows of v in S, rows of u elsewhere).

The curves are traced independently by the dyad's standard form (Sandor and Erdman):
with W = A_1 - A0 (the crank) and Z = P_1 - A_1, position j reads
``W (e^{i beta_j} - 1) + Z (e^{i alpha_j} - 1) = delta_j``; its compatibility
``Delta_1 + Delta_2 e^{i beta_2} + Delta_3 e^{i beta_3} + Delta_4 e^{i beta_4} = 0`` closes
a triangle for each crank rotation beta_2, giving up to two dyads: two tracks of centre
points A0 and of the matching circle points A1.
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab._memory import require
from kinelab.model import MAX_LENGTH, is_real, length_problem
from kinelab.solvers._arguments import reals, whole
from kinelab.synthesis._arguments import coordinate
from kinelab.synthesis._linkage import transmission_limit
from kinelab.synthesis._motion import motion_solution
from kinelab.synthesis._pivots import solve_rows, suh_radcliffe_rows
from kinelab.synthesis._positions import Positions, as_positions, check_not_one_turn, fmt
from kinelab.synthesis._results import SolutionList

__all__ = ["center_points", "center_point_cubic", "BurmesterCurves", "burmester_curves",
           "four_positions"]

_IMAG = 1e-7       # |imaginary part| (relative, normalised task) below which a root is real
_TRIVIAL = 1e-9    # conditioning below which a dyad of the standard form is the trivial one


def _four(points, angles, degrees) -> Positions:
    pos = as_positions(points, angles, degrees)
    if pos.n != 4:
        raise ModelError(f"points: expected four positions, got {pos.n}"
                         + ("; use three_positions" if pos.n == 3 else ""))
    check_not_one_turn(pos)
    return pos


def _normalised(pos: Positions) -> tuple[Positions, np.ndarray, float]:
    """The task moved to P1 = origin and scaled to unit size, with the origin and scale."""
    origin, L = pos.points[0].copy(), pos.size
    return Positions((pos.points - origin) / L, pos.alpha), origin, L


def center_point_cubic(points, angles=None, a0x: ArrayLike = 0.0, *,
                       degrees: bool = False) -> np.ndarray:
    """Coefficients of the compatibility determinant (*Mecanismos*, eq. 71) as a cubic in a0y.

    Parameters
    ----------
    points, angles : see :class:`Positions`
        Four positions.
    a0x : float or array_like, shape (m,)
        Abscissae of the fixed pivot, m.

    Returns
    -------
    ndarray, shape (4,) or (m, 4)
        ``c`` with ``det = c[0] a0y^3 + c[1] a0y^2 + c[2] a0y + c[3]`` (highest power
        first, as :func:`numpy.roots`), in the units of the notes' matrix (m^4).

    Examples
    --------
    The §6.7 example (in cm, the equation is homogeneous in the length unit):

    >>> P, alpha = [(0, 0), (5, 8), (10, 15), (18, 20)], np.radians([10, 20, 30])
    >>> c = kl.synthesis.center_point_cubic(P, alpha, a0x=-20.195)
    >>> float(np.polyval(c, 25.56533151756147) / np.abs(c).max()) < 1e-9
    True
    """
    pos = _four(points, angles, degrees)
    x = _abscissas(a0x)
    return _cubic(pos, x.reshape(-1)).reshape(x.shape + (4,))


def _abscissas(a0x: ArrayLike) -> np.ndarray:
    """x of vertical lines (m): real, finite, within the model's coordinates."""
    x = reals("a0x", a0x)
    bad = ~np.isfinite(x) | (np.abs(np.where(np.isfinite(x), x, 0.0)) > MAX_LENGTH)
    if bad.any():
        where = tuple(int(i) for i in np.argwhere(bad)[0])
        raise ModelError(f"a0x: expected finite numbers at most {MAX_LENGTH:g} m in size, got "
                         f"{describe(x[where])}")
    return x


def _cubic(pos: Positions, x: np.ndarray, rows: tuple[int, int, int] = (0, 1, 2)) -> np.ndarray:
    """(m, 4) coefficients in y of det(rows(x, y)), highest power first (exact expansion);
    ``rows`` picks three of the equations j = 2..n (0-based), for n > 4 positions."""
    sel = list(rows)
    u = suh_radcliffe_rows(pos, np.stack([x, np.zeros_like(x)], -1))[..., sel, :]   # (m, 3, 3)
    v = suh_radcliffe_rows(pos, np.stack([x, np.ones_like(x)], -1))[..., sel, :] - u  # slope in y
    c = np.zeros(x.shape + (4,))
    for mask in itertools.product((0, 1), repeat=3):
        M = np.where(np.array(mask, bool)[:, None], v, u)
        c[..., 3 - sum(mask)] += np.linalg.det(M)
    return c


def _real_roots(c: np.ndarray) -> list[np.ndarray]:
    """Real roots of each row's polynomial (highest power first), polished by Newton."""
    out = []
    for row in c:
        if not np.all(np.isfinite(row)):
            out.append(np.zeros(0))     # coefficients beyond float range: no root to report
            continue
        scale = np.abs(row).max()
        if scale == 0.0:
            out.append(None)        # identically zero: the whole line lies on the curve
            continue
        lead = np.flatnonzero(np.abs(row) > 1e-12 * scale)
        r = np.roots(row[lead[0]:])
        r = r[np.abs(r.imag) <= _IMAG * (1.0 + np.abs(r))].real
        for _ in range(3):
            d = np.polyval(np.polyder(row), r)
            step = np.where(d != 0, np.polyval(row, r) / np.where(d != 0, d, 1.0), 0.0)
            r = r - step
        out.append(np.unique(np.round(r, 13)))
    return out


def center_points(points, angles=None, a0x: float = 0.0, *, degrees: bool = False) -> np.ndarray:
    """Every centre point with a given abscissa: all real roots a0y of eq. 71.

    Parameters
    ----------
    points, angles : see :class:`Positions`
        Four positions.
    a0x : float
        Abscissa of the fixed pivot, m.

    Returns
    -------
    ndarray, shape (k, 2)
        The centre points (a0x, a0y), sorted by a0y; k is 0 to 3.

    Raises
    ------
    ModelError
        The whole vertical line x = a0x lies on the centre-point curve (the curve has
        degenerated into it and a line: every point of it is a centre point).

    Examples
    --------
    *Mecanismos*, §6.7 (cm): three real roots, the middle one is Table 7's 25.566:

    >>> P, alpha = [(0, 0), (5, 8), (10, 15), (18, 20)], np.radians([10, 20, 30])
    >>> kl.synthesis.center_points(P, alpha, a0x=-20.195)[:, 1].round(3)
    array([-49.678,  25.565,  54.167])
    """
    pos = _four(points, angles, degrees)
    return _center_points(pos, np.array([coordinate("a0x", a0x)]))[0]


def _center_points(pos: Positions, xs: np.ndarray) -> list[np.ndarray]:
    npos, origin, L = _normalised(pos)
    roots = _real_roots(_cubic(npos, (xs - origin[0]) / L))
    out = []
    for x, r in zip(xs, roots):
        if r is None:
            raise ModelError(f"a0x = {float(x):.9g}: every point of this vertical line is a centre point "
                             "(the centre-point curve contains the line); choose any a0y")
        y = np.sort(origin[1] + L * r)
        out.append(np.column_stack([np.full(y.shape, x), y]))
    return out


@dataclass(frozen=True, eq=False)
class BurmesterCurves:
    """The centre-point and circle-point curves of four positions, traced.

    Attributes
    ----------
    beta2 : ndarray, shape (m,)
        Rotation of the crank from position 1 to 2, rad: the parameter of the tracing.
    center : ndarray, shape (2, m, 2)
        Centre points A0 (fixed pivots), m: two tracks, one per closure of the
        compatibility triangle.
    circle : ndarray, shape (2, m, 2)
        The matching circle points A1 (moving pivots in position 1), m.
    valid : ndarray of bool, shape (2, m)
        Where the track exists (the triangle closes and the dyad is not the trivial
        one); elsewhere ``center`` and ``circle`` hold NaN.
    """

    beta2: np.ndarray
    center: np.ndarray
    circle: np.ndarray
    valid: np.ndarray

    def __repr__(self) -> str:
        return f"BurmesterCurves(samples={self.beta2.size}, points={int(self.valid.sum())})"


MAX_SAMPLES = 10 ** 12      # samples of the Burmester curves (beyond the memory budget anyway)


def burmester_curves(points, angles=None, *, samples: int = 1441,
                     degrees: bool = False) -> BurmesterCurves:
    """Trace the centre-point and circle-point curves of four positions.

    Parameters
    ----------
    points, angles : see :class:`Positions`
        Four positions.
    samples : int
        Number of crank rotations beta_2 sampled over one turn.

    Returns
    -------
    BurmesterCurves

    Examples
    --------
    >>> P, alpha = [(0, 0), (5, 8), (10, 15), (18, 20)], np.radians([10, 20, 30])
    >>> cur = kl.synthesis.burmester_curves(P, alpha, samples=361)
    >>> cur.center.shape, bool(cur.valid.any())
    ((2, 361, 2), True)
    """
    pos = _four(points, angles, degrees)
    samples = whole("samples", samples, 3, MAX_SAMPLES)
    # the curves and their work arrays: about 30 floats a sample
    require(30 * 8 * samples, f"samples = {samples:,} points of the Burmester curves",
            "ask for fewer samples")
    npos, origin, L = _normalised(pos)
    delta = (npos.points[1:] - npos.points[0]) @ np.array([1.0, 1j])      # (3,) complex
    ea = np.exp(1j * npos.alpha[1:]) - 1.0
    # cofactors of the first column of [[e^{i beta_j} - 1, e^{i alpha_j} - 1, delta_j]]
    D2 = ea[1] * delta[2] - ea[2] * delta[1]
    D3 = -(ea[0] * delta[2] - ea[2] * delta[0])
    D4 = ea[0] * delta[1] - ea[1] * delta[0]
    D1 = -(D2 + D3 + D4)
    beta2 = np.linspace(0.0, 2 * np.pi, samples)
    V = -(D1 + D2 * np.exp(1j * beta2))                                    # = D3 e3 + D4 e4
    a, b, c = abs(D3), abs(D4), np.abs(V)
    cs = np.where(c > 0, c, 1.0)
    p = (a * a - b * b + c * c) / (2 * cs)
    h2 = a * a - p * p
    closes = (c > 0) & (h2 >= 0)
    h = np.sqrt(np.where(closes, h2, 0.0))
    center = np.full((2, samples, 2), np.nan)
    circle = np.full((2, samples, 2), np.nan)
    valid = np.zeros((2, samples), bool)
    for k, sgn in enumerate((1.0, -1.0)):
        # positions that do not turn (a translation) put every centre point at infinity:
        # the divisions below give no finite dyad, and no sample is valid
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            X = V / cs * (p + sgn * 1j * h)                                # D3 e^{i beta_3}
            e = np.stack([np.exp(1j * beta2), X / D3, (V - X) / D4], -1) - 1.0  # (m, 3)
            W, Z, cond = _dyads(e, ea, delta)
        ok = closes & (cond > _TRIVIAL) & np.isfinite(W) & np.isfinite(Z)
        A1 = -Z                                                            # P1 = 0 here
        A0 = A1 - W
        center[k, ok] = origin + L * np.stack([A0.real, A0.imag], -1)[ok]
        circle[k, ok] = origin + L * np.stack([A1.real, A1.imag], -1)[ok]
        valid[k] = ok
    for arr in (beta2, center, circle, valid):
        arr.setflags(write=False)
    return BurmesterCurves(beta2, center, circle, valid)


def _dyads(e, ea, delta):
    """Solve W e_j + Z ea_j = delta_j from the best-conditioned pair of positions."""
    best_W = np.zeros(e.shape[0], complex)
    best_Z = np.zeros(e.shape[0], complex)
    best = np.zeros(e.shape[0])
    for i, j in ((0, 1), (0, 2), (1, 2)):
        det = e[:, i] * ea[j] - e[:, j] * ea[i]
        norm = np.sqrt((np.abs(e[:, i]) ** 2 + abs(ea[i]) ** 2)
                       * (np.abs(e[:, j]) ** 2 + abs(ea[j]) ** 2))
        cond = np.abs(det) / np.maximum(norm, 1e-300)
        safe = np.where(det != 0, det, 1.0)
        W = (delta[i] * ea[j] - delta[j] * ea[i]) / safe
        Z = (e[:, i] * delta[j] - e[:, j] * delta[i]) / safe
        better = cond > best
        best_W = np.where(better, W, best_W)
        best_Z = np.where(better, Z, best_Z)
        best = np.where(better, cond, best)
    return best_W, best_Z, best


def four_positions(points, angles=None, a0x: float = None, b0x: float = None, *,
                   min_transmission_angle: float | None = None,
                   degrees: bool = False) -> SolutionList:
    """Four positions: every four-bar whose fixed pivots have the given abscissae.

    For each real root a0y of the compatibility condition (*Mecanismos*, eq. 71) at a0x, and
    each real root b0y at b0x, the moving pivots follow from the (then compatible)
    Suh-Radcliffe system (eq. 70); every pair (A0, B0) of distinct centre points gives
    one linkage, checked with the kinematics engine.

    Parameters
    ----------
    points : array_like, shape (4, 2), or Positions
        The coupler point P in positions 1..4, m.
    angles : array_like, shape (4,) or (3,)
        Orientations of the coupler, or rotations alpha_2..alpha_4 from position 1, rad.
    a0x, b0x : float
        Abscissae of the fixed pivots of the crank and of the rocker, m.
    min_transmission_angle : float, optional
        The smallest transmission angle accepted between position 1 and the last (rad, or
        degrees with ``degrees=True``); default 30 deg (:data:`TRANSMISSION_LIMIT`).  A
        linkage below it has a transmission angle defect.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    SolutionList of MotionSolution
        Ordered by a0y, then b0y; each with ``A0, B0, A1, B1``, the ``model`` and its
        checks (keep ``[s for s in sols if s.valid]`` for the usable ones).  When some
        root pairs give no linkage, or none does, ``reason`` says why.

    Examples
    --------
    *Mecanismos*, §6.7 in metres (the notes' cm times 0.01); Table 7 is one of the nine:

    >>> P = np.array([(0, 0), (5, 8), (10, 15), (18, 20)]) * 0.01
    >>> sols = kl.synthesis.four_positions(P, [10, 20, 30], -0.20195, -0.29167, degrees=True)
    >>> len(sols)
    9
    >>> s = min(sols, key=lambda s: np.hypot(*(s.A0 - [-0.20195, 0.25566])) + np.hypot(*(s.B0 - [-0.29167, 0.42355])))
    >>> (100 * np.concatenate([s.A0, s.B0, s.A1, s.B1])).round(3)
    array([-20.195,  25.565, -29.167,  42.355, -25.349,  25.379, -37.085,  36.094])
    """
    pos = _four(points, angles, degrees)
    limit = transmission_limit(min_transmission_angle, degrees)
    problems = [f"{n}: expected a finite number, got {describe(v)}" if not is_real(v)
                else f"{n}: {why}, got {float(v):g} m"
                for n, v in (("a0x", a0x), ("b0x", b0x))
                if not is_real(v) or (why := length_problem(float(v), positive=False))]
    if problems:
        raise ModelError(problems)
    roots = {}
    for name, x in (("A", float(a0x)), ("B", float(b0x))):
        roots[name] = _center_points(pos, np.array([x]))[0]
    reasons = [f"no centre point has {n.lower()}0x = {float(v):.6g} m (the centre-point curve "
               "does not cross that vertical)" for n, v in (("A", a0x), ("B", b0x))
               if roots[n].shape[0] == 0]
    if reasons:
        return SolutionList([], reason="; ".join(reasons))
    moving = {}
    for name in ("A", "B"):
        for k, X0 in enumerate(roots[name]):
            scale = float(np.ptp(np.vstack([pos.points, X0]), axis=0).max())
            try:
                moving[name, k] = solve_rows(suh_radcliffe_rows(pos, X0), scale, "",
                                             "no finite moving pivot") + pos.points[0]
            except ModelError as exc:
                reasons.append(f"centre point {fmt(X0)} left out:{exc}")
    sols = []
    for (ka, A0), (kb, B0) in itertools.product(enumerate(roots["A"]), enumerate(roots["B"])):
        if ("A", ka) not in moving or ("B", kb) not in moving:
            continue
        if np.linalg.norm(A0 - B0) <= 1e-12 * pos.size:
            reasons.append(f"A0 = B0 = {fmt(A0)} left out: a linkage needs two "
                           "distinct fixed pivots")
            continue
        try:
            sols.append(motion_solution(pos, A0, B0, moving["A", ka], moving["B", kb],
                                        limit=limit, remedy="another b0x gives other linkages"))
        except ModelError as exc:
            reasons.append(f"A0 = {fmt(A0)}, B0 = {fmt(B0)} left out: {exc}")
    return SolutionList(sols, reason="; ".join(reasons))

