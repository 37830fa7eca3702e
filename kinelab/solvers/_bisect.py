"""Vectorised bisection on a boolean predicate."""
from __future__ import annotations

import numpy as np

__all__ = ["bisect"]


def bisect(inside, a: np.ndarray, b: np.ndarray, *, tol: float = 1e-13, iterations: int = 80):
    """Vectorised bisection: ``inside(x)`` is a boolean array, True at every ``a`` and False at
    every ``b``; returns (a, b) narrowed to ``|b - a| <= tol * max(1, |a|)``."""
    a = np.array(a, float)
    b = np.array(b, float)
    for _ in range(iterations):
        if np.all(np.abs(b - a) <= tol * np.maximum(1.0, np.abs(a))):
            break
        mid = 0.5 * (a + b)
        good = inside(mid)
        a = np.where(good, mid, a)
        b = np.where(good, b, mid)
    return a, b
