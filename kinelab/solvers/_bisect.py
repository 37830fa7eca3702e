"""Vectorised bisection on a boolean predicate."""
from __future__ import annotations

import numpy as np

from kinelab.solvers._arguments import finite, function, reals, tolerance, whole

__all__ = ["bisect"]


def bisect(inside, a: np.ndarray, b: np.ndarray, *, tol: float = 1e-13, iterations: int = 80):
    """Vectorised bisection: ``inside(x)`` is a boolean array, True at every ``a`` and False at
    every ``b``; returns (a, b) narrowed to ``|b - a| <= tol * max(1, |a|)``.  ``a`` and ``b``
    are finite real numbers (arrays of one shape), ``tol`` below 1, ``iterations`` from 0 to
    2,000 (a float halves at most about 2,100 times before its ends meet)."""
    function("inside", inside)
    tol = tolerance("tol", tol)
    iterations = whole("iterations", iterations, 0, 2000)
    a = np.array(finite("a", reals("a", a)))
    b = np.array(finite("b", reals("b", b)))
    for _ in range(iterations):
        with np.errstate(over="ignore"):     # ends at both extremes of the floats
            if np.all(np.abs(b - a) <= tol * np.maximum(1.0, np.abs(a))):
                break
        with np.errstate(over="ignore"):
            mid = 0.5 * (a + b)
        if not np.isfinite(mid).all():       # ends near the largest float: halve each first
            mid = np.where(np.isfinite(mid), mid, 0.5 * a + 0.5 * b)
        good = inside(mid)
        a = np.where(good, mid, a)
        b = np.where(good, b, mid)
    return a, b
