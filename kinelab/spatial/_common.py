"""Argument checks and small helpers shared by the spatial modules."""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe


def as_array(name: str, value: ArrayLike, tail: tuple[int, ...] = (), *,
             batch: bool = True) -> np.ndarray:
    """``value`` as a finite float array of shape ``tail`` or, with ``batch``, ``(N, *tail)``.

    Raises a :class:`ModelError` naming ``name``, the expected shapes and what was given.
    """
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ModelError(f"{name}: expected real numbers, got {describe(value)}") from None
    shapes = [tail] + ([(None, *tail)] if batch else [])
    if not any(array.ndim == len(s) and all(a == b for a, b in zip(array.shape, s)
                                            if b is not None) for s in shapes):
        wanted = " or ".join(_shape_text(s) for s in shapes)
        raise ModelError(f"{name}: expected shape {wanted}, got {array.shape}")
    if not np.isfinite(array).all():
        raise ModelError(f"{name}: expected finite numbers, got {_first_bad(array)}; "
                         f"NaN and infinity are not positions or angles")
    return array


def as_vectors(name: str, value: ArrayLike, d: int) -> np.ndarray:
    """``value`` as vectors of shape (..., d); a scalar zero stands for the zero vector."""
    x = np.asarray(value, dtype=float)
    if x.ndim == 0 and x == 0.0:
        return np.zeros(d)
    if x.ndim == 0 or x.shape[-1] != d:
        raise ModelError(f"{name}: expected shape (..., {d}), got {x.shape}")
    return x


def as_length(name: str, value: float, *, positive: bool = False) -> float:
    """``value`` as a finite float in m (> 0 with ``positive``), or a :class:`ModelError`
    naming ``name``."""
    kind = "a positive length" if positive else "a finite length"
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ModelError(f"{name}: expected {kind} in m, got {describe(value)}") from None
    if not np.isfinite(number) or (positive and number <= 0.0):
        raise ModelError(f"{name}: expected {kind} in m, got {describe(number)}")
    return number




def indices(mask: np.ndarray, most: int = 5) -> str:
    """The first few indices where ``mask`` is true, as text for a message."""
    found = np.flatnonzero(mask)
    text = ", ".join(str(i) for i in found[:most])
    return text + (f" (and {found.size - most} more)" if found.size > most else "")


def _shape_text(shape) -> str:
    inner = ", ".join("N" if s is None else str(s) for s in shape)
    return f"({inner},)" if len(shape) == 1 else f"({inner})"


def _first_bad(array: np.ndarray) -> str:
    where = tuple(int(i) for i in np.argwhere(~np.isfinite(array))[0])
    return f"{array[where]} at index {where}" if where else f"{array[()]}"
