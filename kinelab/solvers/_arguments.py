"""Argument checks shared by the solvers.

Every public solver checks its arguments here, once per call (never per sample), so that
they all refuse the same things with the same words: text, booleans, complex numbers, None
and objects where numbers are expected (numpy would turn True into 1.0 and "3" into 3.0),
whole numbers beyond the range of floats, NaN and infinity, tolerances that are negative or
so large that nothing is left to compare, and callbacks that cannot be called.
"""
from __future__ import annotations

import numbers
from collections.abc import Callable

import numpy as np

from kinelab.errors import ModelError, describe
from kinelab.model import real

__all__ = ["number", "tolerance", "whole", "flag", "function", "reals", "finite", "seed",
           "MAX_SEED"]

MAX_SEED = 2 ** 32 - 1      # the largest seed of the random draws (numpy's and scipy's)


def number(name: str, value: object) -> float:
    """``value`` as one finite float (an int, a float, a numpy number or a 0-d array)."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    x = real(value)
    if x is None:
        raise ModelError(f"{name}: expected a finite number, got {describe(value)}")
    return x


def tolerance(name: str, value: object, *, zero: bool = False, below: float = 1.0) -> float:
    """``value`` as a relative tolerance: a number above 0 (from 0 with ``zero``) and below
    ``below``; a tolerance of a whole unit or more would leave nothing to compare."""
    x = real(value)
    if x is None or not (x >= 0.0 if zero else x > 0.0) or not x < below:
        kind = "a number from 0 to" if zero else "a positive number"
        raise ModelError(f"{name}: expected {kind} below {below:g}, got {describe(value)}")
    return x


def whole(name: str, value: object, low: int, high: int) -> int:
    """``value`` as a whole number from ``low`` to ``high``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral) \
            or not low <= value <= high:
        raise ModelError(f"{name}: expected a whole number from {low} to {high:,}, got "
                         f"{describe(value)}")
    return int(value)


def seed(value: object, *, none: bool = False) -> int | None:
    """A seed of the random draws: a whole number from 0 to ``MAX_SEED`` (or None, fresh
    entropy, when ``none``)."""
    return None if none and value is None else whole("seed", value, 0, MAX_SEED)


def flag(name: str, value: object) -> bool:
    """``value`` as a bool: True or False (numpy's too), not something that merely has a
    truth value."""
    if not isinstance(value, (bool, np.bool_)):
        raise ModelError(f"{name}: expected True or False, got {describe(value)}")
    return bool(value)


def function(name: str, value: object) -> Callable:
    """``value`` when it can be called."""
    if not callable(value):
        raise ModelError(f"{name}: expected a function, got {describe(value)}")
    return value


def reals(name: str, value: object, *, complex_ok: bool = False) -> np.ndarray:
    """``value`` as a float array (complex with ``complex_ok`` when it holds complex
    numbers), without a copy when it already is one; a :class:`ModelError` naming ``name``
    when it holds anything but numbers (None, text, booleans, objects, whole numbers beyond
    the range of floats)."""
    try:
        a = np.asarray(value)
    except (TypeError, ValueError, OverflowError):      # ragged nesting, and the like
        raise ModelError(f"{name}: expected real numbers in an array of regular shape, got "
                         f"{describe(value)}") from None
    kinds = "iufc" if complex_ok else "iuf"
    if a.dtype.kind not in kinds:
        what = "numbers" if complex_ok else "real numbers"
        raise ModelError(f"{name}: expected {what}, got {describe(value)}")
    with np.errstate(over="ignore", invalid="ignore"):   # a long double beyond floats
        return a.astype(np.result_type(a.dtype, float) if a.dtype.kind == "c" else float,
                        copy=False)


def finite(name: str, a: np.ndarray, hint: str = "") -> np.ndarray:
    """``a`` when all its entries are finite, else a :class:`ModelError` naming ``name``, the
    first entry that is not and where it is."""
    if not np.isfinite(a).all():
        where = tuple(int(i) for i in np.argwhere(~np.isfinite(a))[0])
        at = f" at index {where}" if where else ""
        raise ModelError(f"{name}: expected finite numbers, got {describe(a[where])}{at}"
                         f"{'; ' + hint if hint else ''}")
    return a
