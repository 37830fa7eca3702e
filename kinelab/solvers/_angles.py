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
