"""Positions of a moving plane, their poles and rotation angles (*Mecanismos*, §6.1-6.3).

A position of the moving plane (the coupler) is a point P_j of the plane and the plane's
orientation theta_j.  Everything that follows uses only the displacements from position 1:
a point X1 of the plane (given in position 1) is carried to

    X_j = P_j + R(alpha_j) (X1 - P1),        alpha_j = theta_j - theta_1,

which is the notes' ``A_j = P_j - R_alpha_j (P1 - A1)`` (§6.4).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.model import MAX_LENGTH, MAX_TURNS, MIN_LENGTH
from kinelab.solvers import wrap_angle
from kinelab.solvers._arguments import flag, reals
from kinelab.synthesis._arguments import MAX_POSITIONS, point, point_array

__all__ = ["Positions", "Poles", "poles", "pole"]

_COINCIDENT = 1e-12   # relative to the size of the task: two positions this close are one


def as_xy(name: str, value: ArrayLike) -> np.ndarray:
    """A point (2,) of finite numbers within the model's limits, or a ModelError naming the
    argument."""
    return point(name, value)


def fmt(xy: ArrayLike) -> str:
    """A point for a message: ``(x, y)`` with up to 9 significant digits."""
    return "(" + ", ".join(f"{float(v):.9g}" for v in np.asarray(xy, float).ravel()) + ")"


def rotation(alpha: ArrayLike) -> np.ndarray:
    """Rotation matrices R(alpha), shape alpha.shape + (2, 2)."""
    c, s = np.cos(alpha), np.sin(alpha)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def cross(u: ArrayLike, v: ArrayLike) -> np.ndarray:
    """z-component of the cross product of planar vectors, shape (...)."""
    u, v = np.asarray(u, float), np.asarray(v, float)
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


@dataclass(frozen=True, eq=False)
class Positions:
    """Prescribed positions of a moving plane: a point and an orientation each.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The point P of the plane in each position, m.
    angles : array_like, shape (n,) or (n - 1,)
        Either the orientation theta_j of the plane in every position (rad, any common
        reference: only the differences matter), or, with n - 1 values, the notes'
        rotations alpha_2 ... alpha_n from position 1 (alpha_1 = 0).
    degrees : bool
        Angles are given in degrees (converted once, here).

    Attributes
    ----------
    points : ndarray, shape (n, 2)
    alpha : ndarray, shape (n,)
        Rotation of the plane from position 1 to each position, rad; ``alpha[0] = 0``.

    Raises
    ------
    ModelError
        Fewer than two positions, shapes that do not match, non-finite values, or two
        positions that coincide (same point and same orientation).

    Examples
    --------
    >>> pos = kl.synthesis.Positions([(1, 1), (2, 0.5), (3, 1.5)], [0, 45], degrees=True)
    >>> np.degrees(pos.alpha)
    array([ 0.,  0., 45.])
    >>> pos.carry((3.0, 1.0))          # a point of the plane, followed through the positions
    array([[3.        , 1.        ],
           [4.        , 0.5       ],
           [4.41421356, 2.91421356]])
    """

    points: np.ndarray
    alpha: np.ndarray

    def __init__(self, points: ArrayLike, angles: ArrayLike, *, degrees: bool = False):
        degrees = flag("degrees", degrees)
        problems = []
        p = reals("points", points)
        a = reals("angles", angles)
        if p.ndim != 2 or p.shape[1] != 2:
            problems.append(f"points: expected shape (n, 2), got {p.shape}")
        elif p.shape[0] < 2:
            problems.append(f"points: expected at least two positions, got {p.shape[0]}")
        elif p.shape[0] > MAX_POSITIONS:
            problems.append(f"points: expected at most {MAX_POSITIONS:,} positions, got "
                            f"{p.shape[0]:,}; a motion is given by a few positions (least "
                            "squares beyond five)")
        elif not np.all(np.isfinite(p)):
            j = int(np.flatnonzero(~np.all(np.isfinite(p), axis=1))[0])
            problems.append(f"points[{j}]: expected two finite numbers (x, y), got "
                            f"{describe(p[j].tolist())}")
        elif np.abs(p).max() > MAX_LENGTH:
            j = int(np.flatnonzero(np.abs(p).max(axis=1) > MAX_LENGTH)[0])
            problems.append(f"points[{j}]: expected coordinates at most {MAX_LENGTH:g} m in "
                            f"size, got {describe(p[j].tolist())}")
        limit = MAX_TURNS * (360.0 if degrees else 2 * np.pi)
        if a.ndim != 1:
            problems.append(f"angles: expected shape (n,) or (n - 1,), got {a.shape}")
        elif not np.all(np.isfinite(a)):
            j = int(np.flatnonzero(~np.isfinite(a))[0])
            problems.append(f"angles[{j}]: expected a finite number, got {describe(float(a[j]))}")
        elif a.size and np.abs(a).max() > limit:
            j = int(np.flatnonzero(np.abs(a) > limit)[0])
            problems.append(f"angles[{j}]: expected an angle within {MAX_TURNS} turns of 0 "
                            f"({limit:g} {'deg' if degrees else 'rad'}), got {float(a[j]):g}")
        if not problems:
            n = p.shape[0]
            if a.shape[0] == n:
                a = a - a[0]
            elif a.shape[0] == n - 1:
                a = np.concatenate([[0.0], a])
            else:
                problems.append(f"angles: expected {n} orientations (one per position) or {n - 1} "
                                f"rotations alpha_2..alpha_{n} from position 1, got {a.shape[0]}")
        if problems:
            raise ModelError(problems)
        if degrees:
            a = np.radians(a)
        p = p.copy() if p is points else p
        object.__setattr__(self, "points", p)
        object.__setattr__(self, "alpha", a)
        scale = self.size
        for i in range(n - 1):          # a row at a time: no n x n array
            same = ((np.hypot(*(p[i + 1:] - p[i]).T) <= _COINCIDENT * scale)
                    & (np.abs(wrap_angle(a[i + 1:] - a[i])) <= _COINCIDENT))
            if same.any():
                j = i + 1 + int(np.argmax(same))
                raise ModelError(f"positions {i + 1} and {j + 1} coincide (same point "
                                 f"{fmt(p[i])} and same orientation); remove one of them")
        p.setflags(write=False)
        a.setflags(write=False)

    @classmethod
    def from_two_points(cls, first: ArrayLike, second: ArrayLike) -> Positions:
        """Positions given by two points of the plane each: P = first, theta = direction
        from first to second.

        Parameters
        ----------
        first, second : array_like, shape (n, 2)
            Two distinct points of the plane in each position, m (the distance between
            them must be the same in every position: the plane is rigid).

        Examples
        --------
        >>> pos = kl.synthesis.Positions.from_two_points([(0, 0), (1, 0)], [(1, 0), (1, 1)])
        >>> np.degrees(pos.alpha)
        array([ 0., 90.])
        """
        f, s = reals("first", first), reals("second", second)
        if f.shape != s.shape or f.ndim != 2 or f.shape[1] != 2 or not 2 <= f.shape[0]:
            raise ModelError(f"first, second: expected two arrays of the same shape (n, 2), n "
                             f"at least 2, got {f.shape} and {s.shape}")
        if f.shape[0] > MAX_POSITIONS:
            raise ModelError(f"first: expected at most {MAX_POSITIONS:,} positions, got "
                             f"{f.shape[0]:,}")
        f, s = point_array("first", f), point_array("second", s)
        d = s - f
        length = np.hypot(d[:, 0], d[:, 1])
        size = max(float(np.ptp(np.concatenate([f, s]), axis=0).max()), float(length.max()), 1e-300)
        if np.any(length <= _COINCIDENT * size):
            j = int(np.argmin(length))
            raise ModelError(f"second[{j}]: coincides with first[{j}], so it fixes no orientation; "
                             "give two distinct points of the plane in each position")
        if np.ptp(length) > 1e-9 * length.max():
            raise ModelError(f"first, second: the distance between the two points changes from "
                             f"{length.min():.9g} to {length.max():.9g} m; a rigid plane keeps it, "
                             "so check the points")
        return cls(f, np.arctan2(d[:, 1], d[:, 0]))

    @property
    def n(self) -> int:
        """Number of positions."""
        return self.points.shape[0]

    @property
    def size(self) -> float:
        """A length scale of the task (m): the span of the points, at least 1e-300."""
        span = float(np.ptp(self.points, axis=0).max()) if self.points.size else 0.0
        return max(span, float(np.abs(self.points).max()) * 1e-3, 1e-300)

    def carry(self, xy1: ArrayLike) -> np.ndarray:
        """Where a point of the plane, given in position 1, is in each position.

        Parameters
        ----------
        xy1 : array_like, shape (2,) or (k, 2)
            Points of the plane in position 1, m.

        Returns
        -------
        ndarray, shape (n, 2) or (n, k, 2)
        """
        x = point_array("xy1", xy1, "(2,) or (k, 2)")
        if x.ndim > 2:
            raise ModelError(f"xy1: expected points (x, y) of shape (2,) or (k, 2), got shape "
                             f"{x.shape}")
        R = rotation(self.alpha)                          # (n, 2, 2)
        rel = x - self.points[0]                          # (2,) or (k, 2)
        if x.ndim == 1:
            return self.points + np.einsum("nij,j->ni", R, rel)
        return self.points[:, None, :] + np.einsum("nij,kj->nki", R, rel)

    def __repr__(self) -> str:
        return f"Positions(n={self.n}, alpha={np.round(np.degrees(self.alpha), 6).tolist()} deg)"


def check_not_one_turn(pos: Positions, *, unit: str = "m", scale: float = 1.0) -> None:
    """Refuse three positions or more that are all turns of the plane about one point.

    Every point of the plane then stays on a circle about that point (every pole P_ij is
    there), so every crank's fixed pivot would be that same point: a single link pivoted
    there gives the motion, and no four-bar with two distinct fixed pivots does.  (The
    synthesis would otherwise divide by zero-length links or fit circles to nothing.)
    The message gives that point in ``unit``, ``scale`` m each.

    Also refuse positions spread over less than ``MIN_LENGTH`` (but not all at one point):
    the linkage would be smaller than kinelab computes with."""
    span = float(np.ptp(pos.points, axis=0).max())
    if 0.0 < span < MIN_LENGTH:
        raise ModelError(f"points: the positions are at most {span / scale:.3g} {unit} apart, "
                         f"less than the smallest length kinelab computes with "
                         f"({MIN_LENGTH:g} m); give the task in smaller units")
    alpha = wrap_angle(pos.alpha)
    j = int(np.argmax(np.abs(alpha)))
    if pos.n < 3 or abs(alpha[j]) <= _COINCIDENT:
        return              # two positions always have a pole; pure translation has none
    P = _pole_of(pos.points[0], pos.points[j], alpha[j])
    size = max(pos.size, float(np.hypot(*(P - pos.points[0]))))
    moved = pos.carry(P) - P
    if np.all(np.hypot(moved[:, 0], moved[:, 1]) <= 1e-9 * size):   # hypot: no underflow
        raise ModelError(f"positions: every position is a turn of the plane about the same point "
                         f"{fmt(P / scale)} {unit} (all the poles are there), so every crank "
                         "would be pivoted at that point and no four-bar is singled out (one link "
                         "pivoted there gives this motion); give positions that are not all turns "
                         "about one point")


def as_positions(points, angles, degrees: bool) -> Positions:
    """Accept a Positions (with angles None) or points and angles."""
    if isinstance(points, Positions):
        if angles is not None:
            raise ModelError("angles: give either a Positions object or points and angles, not both")
        return points
    if angles is None:
        raise ModelError("angles: missing; give the orientation of the plane in each position "
                         "(or the rotations alpha_2..alpha_n from position 1)")
    return Positions(points, angles, degrees=degrees)


def _pole_of(p_i, p_j, alpha_ij):
    """Fixed point of the displacement x -> p_j + R(alpha_ij)(x - p_i); alpha_ij != 0."""
    # (I - R) x = p_j - R p_i, and (I - R)^-1 = 1/2 [[1, -cot(a/2)], [cot(a/2), 1]]
    d = p_j - np.einsum("...ij,...j->...i", rotation(alpha_ij), p_i)
    cot = 1.0 / np.tan(0.5 * alpha_ij)
    return 0.5 * np.stack([d[..., 0] - cot * d[..., 1], cot * d[..., 0] + d[..., 1]], -1)


@dataclass(frozen=True, eq=False)
class Poles:
    """The poles P_ij of n positions of a moving plane and the rotations alpha_ij.

    The pole P_ij is the one point of the moving plane that is in the same place in
    positions i and j: the plane turns about it by alpha_ij = theta_j - theta_i from i
    to j.  It lies on the perpendicular bisector of A_i A_j for every point A of the
    plane, and sees A_i A_j under the angle alpha_ij (*Mecanismos*, fig. 52).

    Attributes
    ----------
    pairs : tuple of (int, int)
        The pairs (i, j), i < j, numbered from 1 as in the notes.
    P : ndarray, shape (k, 2)
        The poles, m, in the order of ``pairs``.  Where the plane only translates
        between i and j the pole is at infinity: ``finite`` is False and ``P`` holds NaN.
    alpha : ndarray, shape (k,)
        alpha_ij, rad, in (-pi, pi].
    finite : ndarray of bool, shape (k,)
    """

    pairs: tuple[tuple[int, int], ...]
    P: np.ndarray
    alpha: np.ndarray
    finite: np.ndarray

    def __getitem__(self, ij: tuple[int, int]) -> np.ndarray:
        """The pole P_ij, (2,), for 1-based i != j (P_ji = P_ij)."""
        n = self.pairs[-1][1] if self.pairs else 1
        ok = (isinstance(ij, tuple) and len(ij) == 2
              and all(isinstance(v, (int, np.integer)) and not isinstance(v, (bool, np.bool_))
                      for v in ij))
        if not ok or ij[0] == ij[1] or not all(1 <= v <= n for v in ij):
            raise ModelError(f"pole: expected two different positions i, j from 1 to {n} (as in "
                             f"poles[1, 2]), got {describe(ij)}")
        i, j = sorted(int(v) for v in ij)
        k = self.pairs.index((i, j))
        if not self.finite[k]:
            raise ModelError(f"pole P{i}{j} is at infinity: the plane does not turn between "
                             f"positions {i} and {j} (alpha_{i}{j} = 0), it only translates")
        return self.P[k]

    def __repr__(self) -> str:
        return f"Poles({', '.join(f'P{i}{j}' for i, j in self.pairs)})"


def poles(points, angles=None, *, degrees: bool = False) -> Poles:
    """Every pole P_ij and rotation alpha_ij of n positions of a moving plane.

    Parameters
    ----------
    points : array_like, shape (n, 2), or Positions
        The point P of the plane in each position, m.
    angles : array_like, shape (n,) or (n - 1,)
        Orientations of the plane, or rotations from position 1 (see :class:`Positions`).
    degrees : bool
        Angles in degrees.

    Returns
    -------
    Poles

    Examples
    --------
    A quarter turn of the unit square's corner about the origin:

    >>> p = kl.synthesis.poles([(1, 0), (0, 1)], [0, 90], degrees=True)
    >>> p[1, 2].round(12) + 0.0, np.degrees(p.alpha)
    (array([0., 0.]), array([90.]))
    """
    pos = as_positions(points, angles, degrees)
    i, j = np.triu_indices(pos.n, 1)
    alpha = wrap_angle(pos.alpha[j] - pos.alpha[i])
    finite = np.abs(alpha) > 1e-12
    P = np.full((i.size, 2), np.nan)
    if finite.any():
        P[finite] = _pole_of(pos.points[i[finite]], pos.points[j[finite]], alpha[finite])
    for a in (P, alpha, finite):
        a.setflags(write=False)
    return Poles(tuple(zip((i + 1).tolist(), (j + 1).tolist())), P, alpha, finite)


def pole(points, angles=None, *, degrees: bool = False) -> np.ndarray:
    """The pole P12 of two positions, (2,), m (see :func:`poles`).

    Raises
    ------
    ModelError
        The plane only translates (its pole is at infinity).

    Examples
    --------
    >>> kl.synthesis.pole([(2, 0), (0, 2)], [0, np.pi / 2]).round(12) + 0.0
    array([0., 0.])
    """
    pos = as_positions(points, angles, degrees)
    if pos.n != 2:
        raise ModelError(f"points: pole() takes two positions, got {pos.n}; use poles() for more")
    return poles(pos)[1, 2]
