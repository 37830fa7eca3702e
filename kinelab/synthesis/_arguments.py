"""Argument checks shared by the synthesis functions.

Every public function checks its arguments here, once, before anything is computed: points
and pivots hold real numbers within the model's limits (coordinates at most ``MAX_LENGTH``
in size, so that their squares and products stay finite), angles within ``MAX_TURNS``
turns (whole numbers, flags and seeds: :mod:`kinelab.solvers._arguments`).  A bad argument
is a one-line :class:`ModelError` that names it.
"""
from __future__ import annotations

import math

import numpy as np

from kinelab.errors import ModelError, describe
from kinelab.model import MAX_LENGTH, MAX_TURNS, is_real, real_array
from kinelab.solvers._arguments import reals

__all__ = ["point", "point_array", "coordinate", "angle_array", "angle", "MAX_POSITIONS"]

MAX_POSITIONS = 1000        # positions of a motion task, as the task files take them
_MAX_RADIANS = MAX_TURNS * 2 * math.pi


def coordinate(name: str, value: object) -> float:
    """One coordinate or offset, m: a real number at most ``MAX_LENGTH`` in size."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if not is_real(value):
        raise ModelError(f"{name}: expected a finite number (m), got {describe(value)}")
    x = float(value)
    if abs(x) > MAX_LENGTH:
        raise ModelError(f"{name}: expected at most {MAX_LENGTH:g} m in size, got {x:g} m")
    return x


def point_array(name: str, value: object, shape: str = "(n, 2)") -> np.ndarray:
    """An array of points (..., 2), m: real, finite, each coordinate at most ``MAX_LENGTH``
    in size (the caller checks the leading shape)."""
    a = reals(name, value)
    if a.ndim < 1 or a.shape[-1] != 2:
        raise ModelError(f"{name}: expected points (x, y) of shape {shape}, got shape {a.shape}")
    bad = ~np.isfinite(a) | (np.abs(np.where(np.isfinite(a), a, 0.0)) > MAX_LENGTH)
    if bad.any():
        where = tuple(int(i) for i in np.argwhere(bad)[0])
        at = f"[{', '.join(map(str, where[:-1]))}]" if len(where) > 1 else ""
        raise ModelError(f"{name}{at}: expected coordinates of finite numbers at most "
                         f"{MAX_LENGTH:g} m in size, got {describe(a[where])}")
    return a


def point(name: str, value: object) -> np.ndarray:
    """A point (x, y), m, shape (2,)."""
    a = real_array(value)
    if a is None or a.shape != (2,):
        raise ModelError(f"{name}: expected a point (x, y) of two real numbers, got "
                         f"{describe(value)}")
    return point_array(name, a, "(2,)")


def angle_array(name: str, value: object, degrees: bool = False) -> np.ndarray:
    """Angles as a float array, rad (converted from degrees with ``degrees``): real, finite,
    within ``MAX_TURNS`` turns of 0."""
    a = reals(name, value)
    unit = "deg" if degrees else "rad"
    limit = MAX_TURNS * 360.0 if degrees else _MAX_RADIANS
    bad = ~np.isfinite(a) | (np.abs(np.where(np.isfinite(a), a, 0.0)) > limit)
    if bad.any():
        where = tuple(int(i) for i in np.argwhere(bad)[0])
        at = f"[{', '.join(map(str, where))}]" if where else ""
        raise ModelError(f"{name}{at}: expected finite angles within {MAX_TURNS} turns of 0 "
                         f"({limit:g} {unit}), got {describe(a[where])}")
    return np.radians(a) if degrees else a


def angle(name: str, value: object, degrees: bool = False) -> float:
    """One angle, rad (see :func:`angle_array`)."""
    a = angle_array(name, value, degrees)
    if a.ndim != 0:
        raise ModelError(f"{name}: expected one angle, got {describe(value)}")
    return float(a)
