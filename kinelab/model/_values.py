"""What a value of a model may be: the numbers and names kinelab computes with.

One place for the limits, so that a model file, a catalogue constructor and a model built in
Python refuse the same things: booleans, complex numbers, text and dates where a number is
expected; numbers whose squares overflow in the accelerations; names that would break a
message, a table header or a terminal.
"""
from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

__all__ = ["MIN_LENGTH", "MAX_LENGTH", "MAX_RATE", "MAX_TURNS", "is_real", "real", "real_array",
           "coordinate_problem", "angle_problem",
           "length_problem", "rate_problem", "range_problem", "name_problem", "MAX_NAME"]

# Sizes kinelab computes with, in SI.  Lengths: a nanometre to a million kilometres; with
# them, squared lengths and products of lengths stay far from overflow (1e308) and underflow
# (1e-308), and a length is well above the 1e-12 m under which two points coincide.
MIN_LENGTH = 1e-9     # m
MAX_LENGTH = 1e9      # m, also the largest coordinate of a point
# Input rates: accelerations take the square of a speed times a length, so a speed of at
# most 1e100 (rad/s or m/s) keeps them finite (1e9 m x 1e200 = 1e209).
MAX_RATE = 1e100
# An angle input's range: at most this many turns from 0 at either end.  Beyond it the
# samples of an angle are too far apart, or the angle too large for its sine to mean anything.
MAX_TURNS = 1000
# Masses (kg) and moments of inertia (kg m^2): with the lengths and rates above, momenta,
# forces and energies (m v^2 <= 1e30 x (1e100 x 1e9)^2) stay finite; gravity is bounded
# like a rate.
# A model's size: its mobility check and plan take dense SVDs of its constraint Jacobian
# (3 unknowns a link, a few rows a joint), which grow as the cube of the size: 200 links
# take about a second, 800 about a minute.  Points carried by a link cost next to nothing.
MAX_LINKS = 200
MAX_JOINTS = 400
# Points are solved at every sample: a sweep of 361 samples of 2000 points takes a second or
# two, and a model's points are its joints and the few points it reports or draws.
MAX_POINTS = 2000
MAX_MASS = 1e30
MAX_INERTIA = MAX_MASS * MAX_LENGTH ** 2


def is_real(value: Any) -> bool:
    """A real number (int, float, numpy's), not a boolean, that is finite as a float."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    try:
        return math.isfinite(float(value))
    except (OverflowError, TypeError, ValueError):
        return False


def real(value: Any) -> float | None:
    """``float(value)`` when :func:`is_real`, else None."""
    return float(value) if is_real(value) else None


def real_array(value: Any) -> np.ndarray | None:
    """``value`` as a float array when it holds real numbers only, else None: numpy itself
    would turn True into 1.0, "3" into 3.0 and drop the imaginary part of a complex number,
    and lists nested more than 32 deep (numpy's most dimensions) are no array at all."""
    try:
        a = np.asarray(value)
        if a.dtype == object and a.size and all(
                isinstance(v, numbers.Integral) and not isinstance(v, bool) for v in a.flat):
            a = a.astype(float)         # whole numbers beyond 64 bits (beyond floats: refused)
        if a.dtype.kind in "iuf" and isinstance(value, (list, tuple)) and a.size and any(
                isinstance(v, (bool, np.bool_)) for v in np.asarray(value, dtype=object).flat):
            return None                 # numpy made a True among numbers into 1
    except (TypeError, ValueError, OverflowError, RuntimeError, RecursionError):
        return None
    return a.astype(float) if a.dtype.kind in "iuf" else None


def length_problem(value: float, *, positive: bool = True) -> str | None:
    """Why ``value`` (m) cannot be a length (``positive``) or a coordinate, or None."""
    if positive and not MIN_LENGTH <= value <= MAX_LENGTH:
        return f"expected a length from {MIN_LENGTH:g} m to {MAX_LENGTH:g} m"
    if not positive and abs(value) > MAX_LENGTH:
        return f"expected at most {MAX_LENGTH:g} m in size"
    return None


def coordinate_problem(value: float) -> str | None:
    """Why ``value`` (m) cannot be a coordinate or an offset, or None."""
    return length_problem(value, positive=False)


def angle_problem(value: float) -> str | None:
    """Why ``value`` (rad) cannot be an angle of a drawing or a range, or None: far beyond a
    turn, its sine and cosine lose every digit."""
    if abs(value) > MAX_TURNS * 2 * math.pi:
        return f"expected angles within {MAX_TURNS} turns of 0 either way"
    return None


def rate_problem(value: float, unit: str) -> str | None:
    """Why ``value`` (SI, per s or per s^2) cannot be an input's speed or acceleration."""
    if abs(value) > MAX_RATE:
        why = ("times a length it must stay far from overflow" if unit.endswith("^2")
               else "accelerations take its square")
        return f"expected at most {MAX_RATE:g} {unit} in size ({why})"
    return None


def range_problem(start: float, stop: float, angle: bool) -> str | None:
    """Why ``(start, stop)`` (rad, or m) cannot be an input's range (other than being
    empty), or None."""
    if angle:
        return angle_problem(max(abs(start), abs(stop)))
    if not angle and max(abs(start), abs(stop)) > MAX_LENGTH:
        return f"expected a slide within {MAX_LENGTH:g} m of 0"
    return None


def size_problems(*, points: int = 0, links: int = 0, joints: int = 0) -> list[str]:
    """Why a model of so many points, links and joints is refused: one problem per count
    beyond its limit (MAX_POINTS, MAX_LINKS, MAX_JOINTS), each naming the section."""
    out = []
    for kind, n, most in (("links", links, MAX_LINKS), ("joints", joints, MAX_JOINTS)):
        if n > most:
            out.append(f"{kind}: expected at most {most:,}, got {n:,}; a model that large "
                       "takes minutes to plan (its constraint Jacobian grows as the cube of "
                       "the size): model the mechanism in parts")
    if points > MAX_POINTS:
        out.append(f"points: expected at most {MAX_POINTS:,}, got {points:,}; every point is "
                   "solved at every sample: keep the joints' points and those you report or draw")
    return out


MAX_NAME = 200     # characters of a name: names head table columns, label figures and make
                   # file names (a label of 10^4 characters takes matplotlib half a minute)


def name_problem(name: Any) -> str | None:
    """Why ``name`` cannot name a point, link, joint, input or mechanism, or None: names
    head table columns, lines of messages and labels of figures, so they are non-empty,
    printable text (no newline, tab, control or escape character, lone surrogate) of at
    most :data:`MAX_NAME` characters."""
    if not isinstance(name, str) or not name.strip():
        return "expected a non-empty name"
    if not name.isprintable():
        return "expected a name of printable characters (no newline, tab, control character)"
    if len(name) > MAX_NAME:
        return f"expected a name of at most {MAX_NAME} characters, got {len(name):,}; shorten it"
    return None
