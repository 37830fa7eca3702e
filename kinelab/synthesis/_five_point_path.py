"""Five path points, both fixed pivots given: every four-bar, by homotopy continuation.

The coupler point P is to pass through P_0..P_4 (timing free) with the crank's fixed pivot
A0 and the rocker's B0 given.  In complex numbers (isotropic coordinates: a point z and its
conjugate zb taken as independent unknowns), let ``x = A - P`` and ``y = B - P`` be the
moving pivots seen from the coupler point in position 0, and ``Q_j`` the coupler's rotation
from position 0 to j (``Qb_j = 1 / Q_j``).  With ``a_j = P_j - A0`` and ``b_j = P_j - B0``,
the crank keeps its length, ``|a_j + Q_j x|^2 = |a_0 + x|^2``, and so does the rocker:

    (ab_j x) Q_j + (a_j xb) Qb_j = c_j,   c_j = |a_0|^2 - |a_j|^2 + a_0 xb + ab_0 x
    (bb_j y) Q_j + (b_j yb) Qb_j = d_j,   d_j = |b_0|^2 - |b_j|^2 + b_0 yb + bb_0 y

for j = 1..4 (the loop equations).  They are linear in (Q_j, Qb_j); by Cramer's rule
``Q_j = u_j / w_j``, ``Qb_j = v_j / w_j``, and ``Q_j Qb_j = 1`` becomes

    E_j = u_j v_j - w_j^2 = 0,   u_j = b_j c_j yb - a_j xb d_j,
                                  v_j = ab_j x d_j - bb_j y c_j,
                                  w_j = ab_j b_j x yb - a_j bb_j xb y,

four equations in (x, xb, y, yb), each of degree 2 in (x, xb) and 2 in (y, yb): their
two-homogeneous Bezout number is 6 * 2^4 = 96, the number of paths tracked (total degree:
256).  Of the 96 roots, 36 are finite and nondegenerate (Morgan and Wampler, 1990); the
others lie at infinity or on the trivial families of the elimination, ``x = y = 0`` and
``xb = yb = 0``, where ``w_j`` vanishes and the rotations are undetermined.

Each root is refined by Newton's method on the twelve loop equations in (x, xb, y, yb, Q,
Qb), which it must satisfy to rounding.  A real root (``xb = conj(x)``, ``yb = conj(y)``)
is a four-bar, built as a kinelab model and checked by the kinematics engine.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, check_choice
from kinelab.mechanisms import Grashof
from kinelab.model import MIN_LENGTH, Mechanism
from kinelab.solvers._arguments import seed as check_seed
from kinelab.solvers._homotopy import (multihomogeneous_start, distinct, refine, track,
                                       with_rows)
from kinelab.synthesis._arguments import point, point_array
from kinelab.synthesis._linkage import (TRANSMISSION_LIMIT, CheckedLinkage, at_inputs, circuits,
                                        finite_or_inf, fourbar_model, model_grashof, planned,
                                        transmission_defects, transmission_limit, travel)
from kinelab.synthesis._positions import fmt
from kinelab.synthesis._results import SolutionList

__all__ = ["FivePointLinkage", "FivePointSolutions", "five_point_path", "loop_residuals"]

PATHS = 96            # two-homogeneous Bezout number of the eliminated system
EXPECTED = 36         # its finite nondegenerate roots for general data (Morgan, Wampler 1990)
_RETRIES = 3          # new gammas when paths still stall before the end
_NEAR_END = 0.999     # a path stalled beyond this t is heading for a singular end
_AT_INFINITY = 1e-8   # |homogenising coordinate| / |group| below which a root is at infinity
_TRIVIAL = 1e-8       # relative |w_j| below which the rotations are undetermined
_SINGULAR = 1e-10     # reciprocal condition number (homogeneous coordinates) of a singular end
_SOLVED = 1e-10       # relative residual of the loop equations a root must reach
_DISTINCT = 1e-8      # relative distance under which two roots are one
_REAL = 1e-8          # relative |xb - conj(x)| under which a root is real
_REACHED = 1e-8       # relative distance engine vs prescribed point
_ORDERS = ("transmission", "size", "grashof")


def _gaps(p: np.ndarray, pivot: complex) -> np.ndarray:
    """|p_0 - pivot|^2 - |p_j - pivot|^2 (j = 1..4), as the product of a difference and a sum:
    no cancellation when the pivot is far from the points."""
    return ((p[0] - p[1:]) * (p[0] + p[1:] - 2 * pivot).conjugate()).real


def _system(p: np.ndarray, A0: complex, B0: complex):
    """The eliminated system E_j (j = 1..4) in z = (x0, x, xb, y0, y, yb), homogeneous of
    degree (2, 2), and its Jacobian; ``p`` the five points (complex)."""
    a, b = p - A0, p - B0
    ac, bc = a.conj(), b.conj()
    k, l_ = _gaps(p, A0), _gaps(p, B0)                           # (4,)
    aj, bj, acj, bcj = a[1:], b[1:], ac[1:], bc[1:]

    def F(z):
        N = len(z)
        x0, x, xb, y0, y, yb = (z[:, i, None] for i in range(6))
        c = k * x0 + a[0] * xb + ac[0] * x                       # (N, 4)
        d = l_ * y0 + b[0] * yb + bc[0] * y
        u = bj * c * yb - aj * xb * d
        v = acj * x * d - bcj * y * c
        w = acj * bj * x * yb - aj * bcj * xb * y
        E = u * v - w * w
        # gradients (N, 4, 6) of c, d (constant), u, v, w, column by column
        gc = np.array([k, np.full(4, ac[0]), np.full(4, a[0]), 0 * k, 0 * k, 0 * k]).T
        gd = np.array([0 * k, 0 * k, 0 * k, l_, np.full(4, bc[0]), np.full(4, b[0])]).T
        gu = (bj * yb)[..., None] * gc - (aj * xb)[..., None] * gd
        gu[..., 5] += bj * c
        gu[..., 2] -= aj * d
        gv = (acj * x)[..., None] * gd - (bcj * y)[..., None] * gc
        gv[..., 1] += acj * d
        gv[..., 4] -= bcj * c
        gw = np.zeros((N, 4, 6), complex)
        gw[..., 1] = acj * bj * yb
        gw[..., 5] = acj * bj * x
        gw[..., 2] = -aj * bcj * y
        gw[..., 4] = -aj * bcj * xb
        J = v[..., None] * gu + u[..., None] * gv - 2.0 * w[..., None] * gw
        return E, J

    def rotations(s):
        """Q_j, Qb_j (N, 4) of affine roots s = (x, xb, y, yb) (N, 4), and |w_j| relative
        to the size of its terms."""
        x, xb, y, yb = (s[:, i, None] for i in range(4))
        c = k + a[0] * xb + ac[0] * x
        d = l_ + b[0] * yb + bc[0] * y
        u = bj * c * yb - aj * xb * d
        v = acj * x * d - bcj * y * c
        w = acj * bj * x * yb - aj * bcj * xb * y
        # |w| against the size it has away from the families x = y = 0 and xb = yb = 0
        size = (np.abs(acj * bj) + np.abs(aj * bcj)) * (np.abs(x) + np.abs(xb)) \
            * (np.abs(y) + np.abs(yb))
        with np.errstate(all="ignore"):
            return u / w, v / w, np.abs(w) / np.where(size > 0, size, 1.0)

    return F, rotations


def _loop(p: np.ndarray, A0: complex, B0: complex):
    """The twelve loop equations in s = (x, xb, y, yb, Q_1..4, Qb_1..4), their Jacobian, and
    the size of their terms (for relative residuals)."""
    a, b = p - A0, p - B0
    ac, bc = a.conj(), b.conj()
    k, l_ = -_gaps(p, A0), -_gaps(p, B0)
    aj, bj, acj, bcj = a[1:], b[1:], ac[1:], bc[1:]

    def G(s):
        N = len(s)
        x, xb, y, yb = (s[:, i, None] for i in range(4))
        Q, Qb = s[:, 4:8], s[:, 8:12]
        LA = acj * Q * x + aj * Qb * xb + k - a[0] * xb - ac[0] * x
        LB = bcj * Q * y + bj * Qb * yb + l_ - b[0] * yb - bc[0] * y
        U = Q * Qb - 1.0
        J = np.zeros((N, 12, 12), complex)
        r = np.arange(4)
        J[:, r, 0] = acj * Q - ac[0]
        J[:, r, 1] = aj * Qb - a[0]
        J[:, r, 4 + r] = acj * x
        J[:, r, 8 + r] = aj * xb
        J[:, 4 + r, 2] = bcj * Q - bc[0]
        J[:, 4 + r, 3] = bj * Qb - b[0]
        J[:, 4 + r, 4 + r] = bcj * y
        J[:, 4 + r, 8 + r] = bj * yb
        J[:, 8 + r, 4 + r] = Qb
        J[:, 8 + r, 8 + r] = Q
        return np.concatenate([LA, LB, U], axis=1), J

    def scale(s):
        x, xb, y, yb = (s[:, i, None] for i in range(4))
        Q, Qb = s[:, 4:8], s[:, 8:12]
        SA = (np.abs(acj * Q * x) + np.abs(aj * Qb * xb) + np.abs(a[1:]) ** 2 + abs(a[0]) ** 2
              + np.abs(a[0] * xb) + np.abs(ac[0] * x))
        SB = (np.abs(bcj * Q * y) + np.abs(bj * Qb * yb) + np.abs(b[1:]) ** 2 + abs(b[0]) ** 2
              + np.abs(b[0] * yb) + np.abs(bc[0] * y))
        return np.concatenate([SA, SB, 1.0 + np.abs(Q * Qb)], axis=1)

    return G, scale


def loop_residuals(points: ArrayLike, A0: ArrayLike, B0: ArrayLike,
                   roots: ArrayLike) -> np.ndarray:
    """Relative residuals of the twelve loop equations at roots (x, xb, y, yb, Q_1..4,
    Qb_1..4), shape (N, 12) complex in (N, 12) out: each equation's value over the sum of
    the sizes of its terms (see :mod:`kinelab.synthesis._five_point_path`).  ``points``
    (5, 2), ``A0``, ``B0`` (2,) in m; the roots are in the frame of the points as given."""
    p = np.asarray(points, float) @ np.array([1.0, 1j])
    G, scale = _loop(p, complex(*A0), complex(*B0))
    s = np.atleast_2d(np.asarray(roots, complex))
    return np.abs(G(s)[0]) / scale(s)


@dataclass(frozen=True, eq=False)
class FivePointLinkage(CheckedLinkage):
    """A real four-bar whose coupler point passes through five points, with its checks.

    Attributes
    ----------
    A0, B0 : ndarray, shape (2,)
        Fixed pivots (as given), m.
    A1, B1 : ndarray, shape (2,)
        Crank pin and rocker pin when the coupler point is at the first point, m.
    points : ndarray, shape (5, 2)
        The path points, m.
    model : Mechanism
        The four-bar (catalogue names ``O2 = A0, A, B, O4 = B0, P``), sketched at the
        first point.
    q : ndarray, shape (5,)
        The crank angle at each point, rad.
    rotations : ndarray, shape (5,)
        The coupler's rotation from the first point, rad.
    errors : ndarray, shape (5,)
        Distance from each point to the engine's coupler point at ``q`` on the sketch's
        assembly branch, m (+inf where the loop does not close there).
    coupler_point : (float, float)
        P from A, along AB and to its left, m.
    grashof : Grashof
    min_transmission_angle : float
        Smallest transmission angle from the first point to the last, rad (the engine's).
    branch_defect, order_defect, circuit_defect : bool
    direction : int
        +1 / -1: the crank turns counter-clockwise / clockwise through the points; 0 when
        no sense passes them in order.
    defects : tuple of str
    transmission_limit : float
    """

    A0: np.ndarray
    B0: np.ndarray
    A1: np.ndarray
    B1: np.ndarray
    points: np.ndarray
    model: Mechanism
    q: np.ndarray
    rotations: np.ndarray
    errors: np.ndarray
    coupler_point: tuple[float, float]
    grashof: Grashof
    min_transmission_angle: float
    branch_defect: bool
    order_defect: bool
    circuit_defect: bool
    direction: int
    defects: tuple[str, ...]
    transmission_limit: float = TRANSMISSION_LIMIT

    @property
    def size(self) -> float:
        """The longest link, m."""
        return max(self.lengths.values())

    def __repr__(self) -> str:
        f = np.array2string
        return (f"FivePointLinkage(A1={f(self.A1, precision=6)}, B1={f(self.B1, precision=6)}, "
                f"{self.grashof.kind}, min transmission "
                f"{math.degrees(self.min_transmission_angle):.1f} deg, {self.state})")


@dataclass(frozen=True, eq=False)
class FivePointSolutions:
    """Every four-bar whose coupler point passes through five points, A0 and B0 given.

    ``len()`` is the number of distinct finite nondegenerate roots found, complex ones
    included (36 for general data).

    Attributes
    ----------
    roots : ndarray, shape (k, 12), complex
        Each root (x, xb, y, yb, Q_1..4, Qb_1..4): ``x = A1 - P_0``, ``y = B1 - P_0`` as
        complex numbers, their isotropic partners, the coupler rotations to points 2..5.
    residuals : ndarray, shape (k,)
        Largest relative residual of the twelve loop equations at each root.
    real : SolutionList of FivePointLinkage
        The real roots as checked four-bars, best first by ``order_by``; ``reason`` says
        which real roots were left out, and why.
    order_by : str
    paths : int
        Paths of one run (96: the start system's roots).
    failed : int
        Paths of the last run that stalled before the end, after their retry with shorter
        steps (0 unless every run with a new gamma left some).
    retried : int
        Paths followed again: those retried with shorter steps, and 96 for each run
        repeated with a new gamma.
    discarded : dict of str to int
        Path ends left out, by reason (at infinity, trivial family, singular, repeats), over
        every run.
    seconds : float
        Wall time of the whole solve (tracking, refining, building and checking), s.
    """

    roots: np.ndarray
    residuals: np.ndarray
    real: SolutionList
    order_by: str
    paths: int
    failed: int
    retried: int
    discarded: dict
    seconds: float

    def __len__(self) -> int:
        return len(self.roots)

    def __repr__(self) -> str:
        valid = sum(s.valid for s in self.real)
        return (f"FivePointSolutions({len(self)} solutions, {len(self.real)} real "
                f"({valid} free of defects), {self.paths} paths tracked, {self.failed} failed, "
                f"{self.seconds:.2f} s)")


def _order_key(order_by: str):
    rank = {"crank-rocker": 0, "double-crank": 1, "rocker-crank": 2, "double-rocker": 3}

    def key(s: FivePointLinkage):
        mu = s.min_transmission_angle
        mu = -mu if np.isfinite(mu) else 0.0
        if order_by == "transmission":
            return (not s.valid, mu)
        if order_by == "size":
            return (not s.valid, s.size)
        return (not s.valid, rank.get(s.grashof.kind, 4) if s.grashof.margin > 0 else 4, mu)
    return key


def _points(points) -> np.ndarray:
    T = point_array("points", points, "(5, 2)")
    if T.shape != (5, 2):
        raise ModelError(f"points: expected five points (x, y), shape (5, 2), got shape {T.shape}; "
                         "give exactly five path points")
    return T


def _check(T: np.ndarray, A0: np.ndarray, B0: np.ndarray) -> float:
    """The task's size, m, after the checks that make it a general five-point task."""
    allp = np.vstack([T, A0, B0])
    size = float(np.ptp(allp, axis=0).max())
    if size < MIN_LENGTH:
        raise ModelError(f"points: the points and pivots are at most {size:.3g} m apart, less than "
                         f"the smallest length kinelab computes with ({MIN_LENGTH:g} m); give the "
                         "task in smaller units")
    spread = float(np.ptp(T, axis=0).max())
    for i in range(5):
        gaps = np.hypot(*(T[i + 1:] - T[i]).T) if i < 4 else np.array([np.inf])
        if gaps.min() <= 1e-9 * size:
            j = i + 1 + int(np.argmin(gaps))
            raise ModelError(f"points: points {i + 1} and {j + 1} coincide at {fmt(T[i])}; give "
                             "five distinct points")
    c = T.mean(axis=0)
    s = np.linalg.svd(T - c, compute_uv=False)
    if s[1] <= 1e-9 * max(s[0], spread):
        raise ModelError("points: the five points lie on one line, which no four-bar's coupler "
                         "curve passes through in general (the task is degenerate); give points "
                         "off a common line")
    problems = []
    if np.hypot(*(A0 - B0)) <= 1e-9 * size:
        problems.append(f"pivots: A0 and B0 coincide at {fmt(A0)}; give two distinct fixed pivots")
    for name, X in (("A0", A0), ("B0", B0)):
        d = np.hypot(*(T - X).T)
        if d.min() <= 1e-9 * size:
            link = "crank" if name == "A0" else "rocker"
            problems.append(f"pivots: {name} is at point {int(np.argmin(d)) + 1} {fmt(X)}: the "
                            f"coupler point would pass over the {link}'s fixed pivot, where the "
                            f"{link}'s equation for that point degenerates; move {name} off the "
                            "path points")
    if problems:
        raise ModelError(problems if len(problems) > 1 else problems[0])
    return size


def _pivots(pivots) -> tuple[np.ndarray, np.ndarray]:
    try:
        n = len(pivots)
    except TypeError:
        n = None
    if n != 2 or isinstance(pivots, str):
        raise ModelError("pivots: expected the two fixed pivots (A0, B0), each a point (x, y), "
                         f"got {pivots!r:.60}; give pivots=((x, y), (x, y))")
    return point("pivots[0] (A0)", pivots[0]), point("pivots[1] (B0)", pivots[1])


def five_point_path(points: ArrayLike, pivots: tuple[ArrayLike, ArrayLike], *,
                    order_by: str = "transmission",
                    min_transmission_angle: float = TRANSMISSION_LIMIT,
                    seed: int = 0) -> FivePointSolutions:
    """Every four-bar whose coupler point passes through five points, with both fixed
    pivots given: the complete solution set, by polynomial homotopy continuation.

    The loop equations (see :mod:`kinelab.synthesis._five_point_path`) are reduced to four
    polynomial equations in the moving pivots and their isotropic partners; their 96 roots
    (two-homogeneous Bezout number) are followed from a random linear-product start system
    (:mod:`kinelab.solvers._homotopy`), all at once.  A path that stalls before the end is
    followed again with steps four times shorter; if some still stall, the whole run is
    repeated with a new gamma (up to three times) and the ends of all runs pooled.  Each end
    is refined by Newton's method on the twelve loop equations; ends at infinity, on the
    trivial families of the formulation (where the coupler rotations are undetermined),
    singular ones and repeats are left out, and counted in ``discarded`` by reason.  For
    general data 36 roots remain (Morgan and Wampler, 1990); the real ones are four-bars,
    built as kinelab models and checked by the kinematics engine (branch, order and circuit
    defects, Grashof class, transmission angle).  The timing is free: the crank angles at
    the points come out of the solution.

    Parameters
    ----------
    points : array_like, shape (5, 2)
        The path points, m, in the order the coupler point is to meet them.
    pivots : (array_like, array_like)
        The fixed pivots (A0, B0) of the crank and of the rocker, each (x, y), m.
    order_by : {"transmission", "size", "grashof"}
        How ``real`` is sorted, linkages free of defects always first: the largest
        smallest transmission angle first; the smallest longest link first; or by Grashof
        class (crank-rocker, double-crank, rocker-crank, double-rocker, non-Grashof), then
        transmission angle.
    min_transmission_angle : float
        Below this (rad, default 30 deg) between the first point and the last, a linkage
        has a transmission angle defect.
    seed : int
        Seed of the random start system and gammas: the result is reproducible.

    Returns
    -------
    FivePointSolutions
        ``len()`` roots (complex included); ``.real`` the four-bars; its repr gives the
        count and the time taken.

    Raises
    ------
    ModelError
        Not five finite points; repeated or collinear points; a pivot at a point; the two
        pivots in one place; an unknown ``order_by``.

    Notes
    -----
    The count is 36 for general data; special data give fewer (five points and the two
    pivots mirror-symmetric about one line: 28 in the task tried; five points on a circle
    about a pivot: none, every end singular), and ``discarded`` says where the other ends
    went.  The task is solved in a frame of the points' size, so it is scale-free; but
    pivots far from the points (more than about 100 times the points' spread away) make the
    equations ill-conditioned: from about 300 times, paths stall and roots may be lost,
    which ``failed`` and a count below 36 show.

    References
    ----------
    A. P. Morgan and C. W. Wampler, "Solving a planar four-bar design problem using
    continuation", ASME J. Mech. Des. 112 (1990): 36 solutions.

    Examples
    --------
    Five points of the catalogue crank-rocker's coupler curve, its own pivots given: the
    catalogue linkage is among the real solutions.

    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
    ...                            coupler_point=(1.5, 1.0))
    >>> pts = kl.analyze(fb, q=np.radians([0, 60, 120, 180, 240])).position("P")
    >>> sols = kl.synthesis.five_point_path(pts, pivots=((0, 0), (3, 0)))
    >>> len(sols)
    36
    >>> any(abs(s.lengths["crank"] - 1.0) < 1e-9 and abs(s.lengths["rocker"] - 2.5) < 1e-9
    ...     for s in sols.real)
    True
    """
    t0 = time.perf_counter()
    T = _points(points)
    A0, B0 = _pivots(pivots)
    check_choice("order_by", order_by, _ORDERS)
    limit = transmission_limit(min_transmission_angle)
    seed = check_seed(seed)
    size = _check(T, A0, B0)
    # a frame of unit size about the points' centroid: the tracking is scale-free
    center = T.mean(axis=0)
    scale = float(np.linalg.norm(T - center, axis=1).max())
    to_c = np.array([1.0, 1j])
    p = ((T - center) / scale) @ to_c
    a0, b0 = complex(*((A0 - center) / scale)), complex(*((B0 - center) / scale))
    F, rotations = _system(p, a0, b0)
    G, loop_scale = _loop(p, a0, b0)
    rng = np.random.default_rng(seed)
    start, patches, starts = multihomogeneous_start([[0, 1, 2], [3, 4, 5]],
                                                    np.full((4, 2), 2), rng)
    target = with_rows(F, patches)
    # One run follows the 96 paths with one gamma.  A path that stalls short of the end
    # (a near-crossing) is followed again in the same homotopy with steps four times
    # shorter, so that it still ends at its own root.  If some still stall, the whole run
    # is repeated with a new gamma (which pairs start roots and ends anew, so a part of
    # the paths would not do) and the ends of every run are pooled: repeats go below.
    # A path that stalls at the very end is heading for a singular end and is kept.
    runs, retried, failed = [], 0, 0
    for attempt in range(1 + _RETRIES):
        gamma = np.exp(2j * np.pi * rng.random())
        r = track(target, start, starts, gamma=gamma)
        z, t, status = r.z.copy(), r.t.copy(), r.status.copy()
        again = np.flatnonzero((status != 0) & (t < _NEAR_END))
        if again.size:
            retried += again.size
            r = track(target, start, starts[again], gamma=gamma, first_step=0.005,
                      max_step=0.025, max_correction=0.005, max_steps=12000)
            z[again], t[again], status[again] = r.z, r.t, r.status
        lost = (status != 0) & (t < _NEAR_END)
        runs.append(z[~lost])
        failed = int(lost.sum())
        if not failed or attempt == _RETRIES:
            break
        retried += len(starts)
    ends = np.concatenate(runs)
    discarded: dict[str, int] = {}

    def drop(reason, count):
        if count:
            discarded[reason] = discarded.get(reason, 0) + int(count)

    keep = np.ones(len(ends), bool)
    z, _, rcond = refine(target, ends)
    fin = np.all(np.isfinite(z), axis=1)
    drop("did not converge", np.sum(keep & ~fin))
    keep &= fin
    X, Y = z[:, 0:3], z[:, 3:6]
    with np.errstate(all="ignore"):
        inf = ((np.abs(X[:, 0]) <= _AT_INFINITY * np.linalg.norm(X, axis=1))
               | (np.abs(Y[:, 0]) <= _AT_INFINITY * np.linalg.norm(Y, axis=1)))
        drop("at infinity", np.sum(keep & inf))
        keep &= ~inf
        aff = np.column_stack([X[:, 1] / X[:, 0], X[:, 2] / X[:, 0],
                               Y[:, 1] / Y[:, 0], Y[:, 2] / Y[:, 0]])
        Q, Qb, wrel = rotations(aff)
    trivial = np.any(~(wrel > _TRIVIAL), axis=1) | ~np.all(np.isfinite(Q) & np.isfinite(Qb),
                                                           axis=1)
    drop("trivial family: the coupler rotations are undetermined (x = y = 0 or xb = yb = 0)",
         np.sum(keep & trivial))
    keep &= ~trivial
    s = np.column_stack([aff, Q, Qb])[keep]
    s, _, _ = refine(G, s)
    with np.errstate(all="ignore"):
        res = np.max(np.abs(G(s)[0]) / loop_scale(s), axis=1)
    # singular or not is judged in the homogeneous coordinates, where a root far out (a
    # rocker pin 1e4 times the task's size away, nearly a slider) is as well conditioned
    # as any other
    ok = (res <= _SOLVED) & (rcond[keep] > _SINGULAR)
    drop("singular: Newton's method on the loop equations does not converge there", np.sum(~ok))
    s, res = s[ok], res[ok]
    order = np.argsort(np.abs(s[:, 0]) + np.abs(s[:, 2]))
    s, res = s[order], res[order]
    first = distinct(s[:, :4], _DISTINCT)
    drop("repeats", len(s) - len(first))
    s, res = s[first], res[first]
    # zero-length crank, rocker or coupler (as squared lengths, also for complex roots)
    x, xb, y, yb = s[:, 0], s[:, 1], s[:, 2], s[:, 3]
    sq = [(p[0] - a0 + x) * (p[0].conjugate() - a0.conjugate() + xb),
          (p[0] - b0 + y) * (p[0].conjugate() - b0.conjugate() + yb),
          (x - y) * (xb - yb), x * xb, y * yb]
    flat = np.zeros(len(s), bool)
    for q in sq:
        flat |= np.abs(q) <= 1e-10
    drop("a link of zero length, or the coupler point at a moving pivot", np.sum(flat))
    s, res = s[~flat], res[~flat]
    # back to the task's frame: x, y scale; Q does not change
    roots = s.copy()
    roots[:, :4] *= scale
    roots.setflags(write=False)
    res.setflags(write=False)
    real_rows = (np.abs(s[:, 1] - s[:, 0].conj()) <= _REAL * (1 + np.abs(s[:, 0]))) \
        & (np.abs(s[:, 3] - s[:, 2].conj()) <= _REAL * (1 + np.abs(s[:, 2])))
    linkages, reasons = [], []
    for i in np.flatnonzero(real_rows):
        try:
            linkages.append(_linkage(T, A0, B0, roots[i], size, limit))
        except ModelError as exc:
            reasons.append(f"real root {i + 1}: {exc}")
    linkages.sort(key=_order_key(order_by))
    seconds = time.perf_counter() - t0
    return FivePointSolutions(roots=roots, residuals=res, real=SolutionList(linkages,
                              reason="; ".join(reasons)), order_by=order_by, paths=len(starts),
                              failed=failed, retried=retried, discarded=discarded,
                              seconds=seconds)


def _linkage(T: np.ndarray, A0: np.ndarray, B0: np.ndarray, root: np.ndarray, size: float,
             limit: float) -> FivePointLinkage:
    """The four-bar of a real root, built and checked by the engine."""
    x, y = complex(root[0]), complex(root[2])
    Q = np.concatenate([[1.0], root[4:8] / np.abs(root[4:8])])
    pc = T @ np.array([1.0, 1j])
    Aj = pc + Q * x
    Bj = pc + Q * y
    A = np.column_stack([Aj.real, Aj.imag])
    B = np.column_stack([Bj.real, Bj.imag])
    model = fourbar_model(A0, B0, A[0], B[0], T[0], name="five-point path generator")
    planned(model, "points: at the first point", "choose other pivots")
    q = np.arctan2(A[:, 1] - A0[1], A[:, 0] - A0[0])
    scale = max(size, max(model.parameters[k] for k in ("ground", "crank", "coupler", "rocker")))

    def reached(sol, idx):
        return np.linalg.norm(sol.position("P")[idx] - T, axis=-1) <= _REACHED * scale

    t = travel(model, q, reached)
    defects = t.defects
    circuit = circuits(A0, B0, A, B, model_grashof(model))
    if circuit is not None and np.any(circuit != circuit[0]):
        lost = ", ".join(str(j + 1) for j in np.flatnonzero(circuit != circuit[0]))
        defects += (f"circuit defect: point(s) {lost} are met on the other circuit of the "
                    "linkage; it cannot move there from the first point without being taken "
                    "apart",)
    circuit_defect = len(defects) > len(t.defects)
    defects += transmission_defects(t.min_transmission_angle, limit,
                                    "between the first point and the last")
    errors = finite_or_inf(np.linalg.norm(at_inputs(model, q).position("P") - T, axis=-1))
    rot = np.angle(Q)
    for arr in (q, rot, errors, A, B):
        arr.setflags(write=False)
    return FivePointLinkage(
        A0=A0, B0=B0, A1=A[0], B1=B[0], points=T, model=model, q=q, rotations=rot,
        errors=errors, coupler_point=model.parameters["coupler_point"],
        grashof=model_grashof(model), min_transmission_angle=t.min_transmission_angle,
        branch_defect=t.branch_defect, order_defect=t.order_defect,
        circuit_defect=circuit_defect, direction=t.direction, defects=defects,
        transmission_limit=limit)
