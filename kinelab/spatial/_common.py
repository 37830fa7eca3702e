"""Argument checks and small helpers shared by the spatial modules.

Every public function of the room checks its arguments here, so that they all refuse the
same things with the same words: text, booleans, complex numbers and objects where numbers
are expected (numpy would turn True into 1.0 and "3" into 3.0), NaN and infinity, shapes
that do not fit or do not go together, and sizes beyond the project's limits
(:mod:`kinelab.model`: coordinates within ``MAX_LENGTH``, angles within ``MAX_TURNS``
turns, rates within ``MAX_RATE``), past which sines lose every digit and squares overflow.
"""
from __future__ import annotations

import numbers
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike
from scipy.spatial.transform import Rotation

from kinelab.errors import ModelError, describe, shown
from kinelab.model import (MAX_LENGTH, MIN_LENGTH, angle_problem, coordinate_problem,
                           length_problem, name_problem, rate_problem)
from kinelab.solvers._arguments import finite, reals

__all__ = ["LENGTH", "ANGLE", "MAX_LENGTH", "MIN_LENGTH", "rate", "check_size",
           "as_array", "as_vectors", "as_number", "as_angles", "as_length",
           "as_directions", "as_rotation", "as_rotation_matrix",
           "as_transform", "as_transform_rate", "transform_dimension", "together", "indices",
           "robot_name"]

# What a size check is: the largest magnitude given -> why it is too large, or None.
Limit = Callable[[float], "str | None"]

LENGTH: Limit = coordinate_problem          # m: coordinates, offsets, translations
ANGLE: Limit = angle_problem                # rad


def rate(unit: str) -> Limit:
    """The size check of a speed or an acceleration in ``unit`` (``'m/s'``, ``'rad/s^2'``)."""
    return lambda value: rate_problem(value, unit)


# Time derivatives of transforms hold ω R and α R + ω² R: squares of rates at most.
MAX_DERIVATIVE = 1e200


def _derivative(value: float) -> str | None:
    if value > MAX_DERIVATIVE:
        return f"expected entries at most {MAX_DERIVATIVE:g} in size"
    return None


# A rotation matrix is orthonormal to this: a matrix typed from a book with two or three
# digits (0.866, 0.5; 0.71, 0.71) is a rotation to its own precision, and a scaled or sheared
# one (a factor of 2, a matrix of ones) is not.  invert() takes R's transpose, which inverts
# such a matrix to the precision it was typed with.
ORTHONORMAL = 1e-2


def _shape_text(shape, batch="") -> str:
    parts = (["..."] if batch == "any" else ["N"] if batch else []) + \
        ["N" if s is None else str(s) for s in shape]
    inner = ", ".join(parts)
    return f"({inner},)" if len(parts) == 1 else f"({inner})"


def check_size(name: str, array: np.ndarray, limit: Limit | None,
               unit: str = "") -> None:
    """Raise a :class:`ModelError` naming ``name`` when the largest magnitude in ``array``
    fails ``limit``."""
    if limit is None or array.size == 0:
        return
    magnitude = np.abs(array)
    where = np.unravel_index(int(np.argmax(magnitude)), array.shape)
    problem = limit(float(magnitude[where]))
    if problem:
        at = f" at index {tuple(int(i) for i in where)}" if array.ndim else ""
        raise ModelError(f"{name}: {problem}, got {describe(array[where])}{unit}{at}")


def as_array(name: str, value: ArrayLike, tail: tuple[int | None, ...] = (), *,
             batch: bool | str = True, limit: Limit | None = None) -> np.ndarray:
    """``value`` as a finite float array of shape ``tail``, or also ``(N, *tail)`` with
    ``batch``, or ``(..., *tail)`` with ``batch="any"``; within ``limit`` if given.

    Raises a :class:`ModelError` naming ``name``, the expected shapes and what was given.
    """
    array = reals(name, value)
    if batch == "any":
        ok = array.ndim >= len(tail) and all(
            b is None or a == b for a, b in zip(array.shape[array.ndim - len(tail):], tail))
        wanted = _shape_text(tail, "any")
    else:
        shapes = [tail] + ([(None, *tail)] if batch else [])
        ok = any(array.ndim == len(s) and all(b is None or a == b
                                              for a, b in zip(array.shape, s))
                 for s in shapes)
        wanted = " or ".join(_shape_text(s) for s in shapes)
    if not ok:
        raise ModelError(f"{name}: expected shape {wanted}, got {array.shape}")
    finite(name, array, "NaN and infinity are not positions or angles")
    check_size(name, array, limit)
    return array


def as_vectors(name: str, value: ArrayLike, d: int, *,
               limit: Limit | None = None) -> np.ndarray:
    """``value`` as vectors of shape (..., d); a scalar zero stands for the zero vector."""
    array = reals(name, value)
    if array.ndim == 0 and array == 0.0:
        return np.zeros(d)
    return as_array(name, array, (d,), batch="any", limit=limit)


def as_number(name: str, value: ArrayLike, *, limit: Limit | None = None) -> float:
    """``value`` as one finite float."""
    return float(as_array(name, value, (), batch=False, limit=limit))


def as_length(name: str, value: float, *, positive: bool = False) -> float:
    """``value`` as a length in m, from ``MIN_LENGTH`` to ``MAX_LENGTH`` with
    ``positive``, else a coordinate of at most ``MAX_LENGTH`` in size; or a
    :class:`ModelError` naming ``name``."""
    kind = "a positive length" if positive else "a finite length"
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    number = None if isinstance(value, bool) else _real_number(value)
    if number is None or (positive and number <= 0.0):
        raise ModelError(f"{name}: expected {kind} in m, got {describe(value)}")
    problem = length_problem(number, positive=positive)
    if problem:
        raise ModelError(f"{name}: {problem}, got {describe(number)} m")
    return number


def _real_number(value: object) -> float | None:
    if not isinstance(value, numbers.Real):
        return None
    try:
        number = float(value)
    except (OverflowError, TypeError, ValueError):
        return None
    return number if np.isfinite(number) else None


def as_directions(name: str, value: ArrayLike, *, batch: bool = True) -> np.ndarray:
    """Unit vectors along ``value`` (shape (3,), or (N, 3) with ``batch``): each scaled by
    its largest component before it is normalised, so that neither a huge nor a tiny
    direction overflows or vanishes."""
    v = as_array(name, value, (3,), batch=batch)
    biggest = np.abs(v).max(axis=-1, keepdims=True)
    if (biggest == 0.0).any():
        raise ModelError(f"{name}: expected a nonzero direction, got (0, 0, 0); give the "
                         f"direction of the axis")
    v = v / biggest
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def as_rotation(name: str, value: object) -> Rotation:
    """``value`` when it is a scipy Rotation, else a :class:`ModelError`."""
    if not isinstance(value, Rotation):
        raise ModelError(f"{name}: expected a scipy.spatial.transform.Rotation, got "
                         f"{type(value).__name__}; build one with Rotation.from_matrix, "
                         f"from_euler or kinelab.spatial.euler_rotation")
    return value


def _orthonormal_problem(R: np.ndarray) -> str | None:
    d = R.shape[-1]
    with np.errstate(over="ignore", invalid="ignore"):
        gram = np.swapaxes(R, -1, -2) @ R
        off = np.abs(gram - np.eye(d)).max() if R.size else 0.0
    if not off <= ORTHONORMAL:
        return (f"expected orthonormal columns (a rotation; RᵀR = I to {ORTHONORMAL:g}), "
                f"but RᵀR differs from I by {describe(float(off))}; orthonormalise it, e.g. "
                f"with Rotation.from_matrix(R).as_matrix()")
    if R.size and (np.linalg.det(R) <= 0.0).any():
        return ("expected a rotation, got a reflection (determinant -1); change the sign "
                "of one column")
    return None


def as_rotation_matrix(name: str, value: ArrayLike) -> np.ndarray:
    """Rotation matrices of shape (..., 2, 2) or (..., 3, 3): finite, orthonormal, proper."""
    R = reals(name, value)
    if R.ndim < 2 or R.shape[-1] != R.shape[-2] or R.shape[-1] not in (2, 3):
        raise ModelError(f"{name}: expected a Rotation or matrices of shape (..., 2, 2) "
                         f"or (..., 3, 3), got shape {R.shape}")
    finite(name, R, "NaN and infinity are not positions or angles")
    problem = _orthonormal_problem(R)
    if problem:
        raise ModelError(f"{name}: {problem}")
    return R


def transform_dimension(name: str, T: np.ndarray) -> int:
    """d of transforms of shape (..., d + 1, d + 1), d = 2 or 3."""
    if T.ndim < 2 or T.shape[-1] != T.shape[-2] or T.shape[-1] not in (3, 4):
        raise ModelError(f"{name}: expected homogeneous transforms of shape (..., 3, 3) or "
                         f"(..., 4, 4), got shape {T.shape}")
    return T.shape[-1] - 1


def as_transform(name: str, value: ArrayLike, d: int | None = None) -> np.ndarray:
    """Rigid homogeneous transforms ``[[R, p], [0, 1]]`` of shape (..., d + 1, d + 1):
    finite, R a rotation, p within the limits of a coordinate, last row (0, ..., 0, 1)."""
    T = reals(name, value)
    k = transform_dimension(name, T)
    if d is not None and k != d:
        raise ModelError(f"{name}: expected shape (..., {d + 1}, {d + 1}) like the other "
                         f"transforms, got shape {T.shape}")
    finite(name, T, "NaN and infinity are not positions or angles")
    bottom = np.zeros(k + 1)
    bottom[k] = 1.0
    if not (T[..., k, :] == bottom).all():
        raise ModelError(f"{name}: expected a homogeneous transform, with last row "
                         f"{tuple(bottom.astype(int).tolist())}, got "
                         f"{describe(T.reshape(-1, k + 1, k + 1)[0, k])}; build it with "
                         f"kinelab.spatial.homogeneous")
    problem = _orthonormal_problem(T[..., :k, :k])
    if problem:
        raise ModelError(f"{name}: rotation part: {problem}")
    check_size(f"{name}: translation part", T[..., :k, k], LENGTH)
    return T


def as_transform_rate(name: str, value: ArrayLike, d: int) -> np.ndarray:
    """Time derivatives of transforms, shape (..., d + 1, d + 1), with a zero last row."""
    M = reals(name, value)
    if transform_dimension(name, M) != d:
        raise ModelError(f"{name}: expected shape (..., {d + 1}, {d + 1}) like the "
                         f"transform, got shape {M.shape}")
    finite(name, M, "NaN and infinity are not positions or angles")
    if (M[..., d, :] != 0.0).any():
        raise ModelError(f"{name}: expected the time derivative of a transform, whose last "
                         f"row is zero, got {describe(M.reshape(-1, d + 1, d + 1)[0, d])}; "
                         f"kinelab.spatial.transform_rates builds it")
    check_size(name, M, _derivative)
    return M


def together(*items: tuple[str, np.ndarray, int]) -> list[np.ndarray]:
    """Arrays ``(name, array, core)`` broadcast over their leading dimensions (all but the
    last ``core``), or a :class:`ModelError` naming them when those do not agree."""
    leads = [a.shape[:a.ndim - core] for _, a, core in items]
    try:
        lead = np.broadcast_shapes(*leads)
    except ValueError:
        names = ", ".join(n for n, _, _ in items)
        shapes = ", ".join(str(a.shape) for _, a, _ in items)
        raise ModelError(f"{names}: shapes {shapes} do not go together; give N of each, "
                         f"or one of any") from None
    return [np.broadcast_to(a, lead + a.shape[a.ndim - core:]) for _, a, core in items]


def indices(mask: np.ndarray, most: int = 5) -> str:
    """The first few indices where ``mask`` is true, as text for a message."""
    found = np.flatnonzero(mask)
    text = ", ".join(str(i) for i in found[:most])
    return text + (f" (and {found.size - most} more)" if found.size > most else "")


def robot_name(name: object) -> str:
    """``'name'`` for a message, after checking it is a name."""
    problem = name_problem(name)
    if problem:
        raise ModelError(f"name: {problem}, got {describe(name)}")
    return shown(name)



def as_angles(name: str, value: ArrayLike, tail: tuple[int | None, ...] = (), *,
              batch: bool | str = True, degrees: bool = False) -> np.ndarray:
    """Angles as :func:`as_array` checks them, within ``MAX_TURNS`` turns of 0, in rad
    (converted from degrees with ``degrees``, after the check, which shows them as given)."""
    a = as_array(name, value, tail, batch=batch)
    if degrees:
        check_size(name, a, lambda v: angle_problem(float(np.radians(v))), " deg")
        return np.radians(a)
    check_size(name, a, ANGLE)
    return a
