"""Angles to one turn."""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike


def wrap_angle(angle: ArrayLike) -> np.ndarray | float:
    """Angles (rad) wrapped into (-pi, pi]; a float for a scalar, else an array.  Angles
    already in that range are returned unchanged, to the bit.

    Examples
    --------
    >>> kl.solvers.wrap_angle([3 * np.pi / 2, -np.pi, np.pi, 0.5]).round(6).tolist()
    [-1.570796, 3.141593, 3.141593, 0.5]
    """
    a = np.asarray(angle, dtype=float)
    inside = (a > -np.pi) & (a <= np.pi)
    if inside.all():
        wrapped = np.array(a)
    else:
        wrapped = np.remainder(a + np.pi, 2.0 * np.pi) - np.pi
        wrapped = np.where(wrapped == -np.pi, np.pi, wrapped)
        wrapped = np.where(inside, a, wrapped)
    return float(wrapped) if wrapped.ndim == 0 else wrapped


def turn_intervals(intervals, around: float = 0.0) -> list[tuple[float, float]]:
    """Angle intervals (rad) shifted by whole turns so that each one's middle is within half
    a turn of ``around``, in increasing order: the same crank positions, written where a
    person looks for them (near a sweep's range, or near zero).

    Examples
    --------
    >>> turn = 2 * np.pi
    >>> spans = kl.solvers.turn_intervals([(0.3 - turn, 0.5 - turn), (2.5 - turn, 3.0 - turn)])
    >>> [(round(a, 9), round(b, 9)) for a, b in spans]
    [(0.3, 0.5), (2.5, 3.0)]
    >>> [(round(a, 9), round(b, 9)) for a, b in kl.solvers.turn_intervals([(0.3, 0.5)], around=turn)]
    [(6.583185307, 6.783185307)]
    """
    turn = 2.0 * np.pi
    out = []
    for a, b in intervals:
        k = np.floor((0.5 * (a + b) - around) / turn + 0.5)
        out.append((float(a - k * turn), float(b - k * turn)))
    return sorted(out)
