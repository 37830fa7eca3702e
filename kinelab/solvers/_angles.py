"""Angles to one turn."""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.solvers._arguments import number, reals


def wrap_angle(angle: ArrayLike) -> np.ndarray | float:
    """Angles (rad) wrapped into (-pi, pi]; a float for a scalar, else an array.  Angles
    already in that range are returned unchanged, to the bit; NaN (a sample with no value)
    stays NaN.  Infinities, and anything but real numbers, raise a ModelError.

    Examples
    --------
    >>> kl.solvers.wrap_angle([3 * np.pi / 2, -np.pi, np.pi, 0.5]).round(6).tolist()
    [-1.570796, 3.141593, 3.141593, 0.5]
    """
    a = reals("angle", angle)
    if np.isinf(a).any():
        raise ModelError(f"angle: expected finite angles (rad), got {describe(a[np.isinf(a)][0])}; "
                         f"an infinite angle has no direction")
    wrapped = wrapped_angles(a)
    return float(wrapped) if wrapped.ndim == 0 else wrapped


_TURN = 2.0 * np.pi


def wrapped_angles(a: np.ndarray) -> np.ndarray:
    """:func:`wrap_angle` of a float array of finite numbers (or NaN), unchecked: a new
    array of the same shape."""
    if a.ndim == 0:
        return wrapped_angles(a.reshape(1)).reshape(())
    lo, hi = (a.min(), a.max()) if a.size else (0.0, 0.0)
    if -np.pi < lo and hi <= np.pi:
        return np.array(a)
    above, below = a > np.pi, a <= -np.pi
    if -2.5 * np.pi < lo and hi < 2.5 * np.pi:
        # within a turn either way: np.remainder(a + pi, 2 pi) - pi to the bit, in fewer
        # passes (x = a + pi; from 2 pi to 4 pi, x - 2 pi is exact, as remainder's result
        # is; below 0 remainder adds 2 pi, as here; at x = 0 both end at pi)
        x = a + np.pi
        x -= _TURN * above
        x += _TURN * below
    else:
        x = np.remainder(a + np.pi, _TURN)
    x -= np.pi
    x[x == -np.pi] = np.pi
    return np.where(above | below, x, a)


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
    around = number("around", around)
    if isinstance(intervals, (str, bytes)):
        raise ModelError(f"intervals: expected (start, stop) pairs of angles, got "
                         f"{describe(intervals)}")
    spans = reals("intervals", intervals)
    if spans.size == 0:
        return []
    if spans.ndim != 2 or spans.shape[1] != 2:
        raise ModelError(f"intervals: expected (start, stop) pairs of angles, shape (k, 2), "
                         f"got shape {spans.shape}")
    if not np.isfinite(spans).all():
        raise ModelError(f"intervals: expected finite angles, got "
                         f"{describe(spans[~np.isfinite(spans).all(axis=1)][0])}")
    turn = 2.0 * np.pi
    out = []
    for a, b in spans.tolist():
        k = np.floor((0.5 * (a + b) - around) / turn + 0.5)
        out.append((float(a - k * turn), float(b - k * turn)))
    return sorted(out)
