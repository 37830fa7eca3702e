"""Function generation with a four-bar: Freudenstein's equation (*Mecanismos*, §3.2, fig. 25).

The rocker angle theta4 is to follow a prescribed function of the crank angle theta2:
x in [x0, xf] is mapped linearly to the crank's travel and y = f(x) to the rocker's.  With
the ground O2O4 along +x (length d), crank a, coupler b and rocker c, the closure
|B - A| = b reads (Freudenstein, 1955)

    K1 cos theta4 - K2 cos theta2 + K3 = cos(theta2 - theta4),
    K1 = d / a,   K2 = d / c,   K3 = (a^2 - b^2 + c^2 + d^2) / (2 a c),

which is linear in K: three precision points fix the linkage; more are met in the least
squares sense.  Between the precision points the linkage misses f: the structural error,
smallest for a given number of points when they are spaced as Chebyshev's nodes.
"""
from __future__ import annotations

import math

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.kinematics import analyze, transmission_angle
from kinelab.mechanisms import Grashof
from kinelab._memory import require
from kinelab.model import MAX_TURNS, Mechanism, is_real, length_problem
from kinelab.solvers import wrap_angle
from kinelab.solvers._arguments import flag, reals, whole
from kinelab.synthesis._arguments import angle_array
from kinelab.synthesis._positions import as_xy, fmt
from kinelab.synthesis._linkage import (TRANSMISSION_LIMIT, CheckedLinkage, fourbar_model,
                                        model_grashof, planned, transmission_defects,
                                        transmission_limit)

__all__ = ["chebyshev_points", "freudenstein", "FunctionSolution", "function_generation",
           "function_generation_pairs", "function_pairs"]

_REACHED = 1e-9   # rad: the engine's rocker angle at a precision point must match to this
_WIDEST = 1e300    # x values beyond it: their differences overflow
_NARROWEST = 1e-9  # an x_range narrower than this, relative to its values, is refused
# the most precision points and Chebyshev nodes (a task file's bound on precision points)
MAX_PRECISION_POINTS = 100
MAX_NODES = 10 ** 12
MAX_SAMPLES = 1_000_000
_GRID = 4096      # intervals of x_range in which f is looked at for a pole or a jump
_STEEPEST = 8     # of them, those where f changes most, halved _HALVINGS times each:
_HALVINGS = 30    # f's change over a halved interval shrinks unless f jumps there


def chebyshev_points(x_range: tuple[float, float], n: int) -> np.ndarray:
    """Chebyshev spacing of n precision points on [x0, xf].

    ``x_j = (x0 + xf)/2 - (xf - x0)/2 cos((2j - 1) pi / (2n))``, j = 1..n: the nodes that
    make the polynomial part of the structural error as small and even as it can be.

    Examples
    --------
    >>> kl.synthesis.chebyshev_points((0.0, 1.0), 3).round(6)      # 0.5 -+ 0.5 cos 30 deg
    array([0.066987, 0.5     , 0.933013])
    """
    x0, xf = _range("x_range", x_range)
    n = whole("n", n, 1, MAX_NODES)
    require(3 * 8 * n, f"n = {n:,} Chebyshev points", "ask for fewer points")
    j = np.arange(1, n + 1)
    # halves first: no overflow for a range as wide as the floats
    return (0.5 * x0 + 0.5 * xf) - (0.5 * xf - 0.5 * x0) * np.cos((2 * j - 1) * np.pi / (2 * n))


def freudenstein(theta2: ArrayLike, theta4: ArrayLike) -> np.ndarray:
    """Freudenstein's constants (K1, K2, K3) from corresponding crank and rocker angles.

    Parameters
    ----------
    theta2, theta4 : array_like, shape (n,), n >= 3
        Crank and rocker angles from the ground line O2 -> O4, rad.

    Returns
    -------
    ndarray, shape (3,)
        Exact for n = 3, least squares for n > 3.

    Raises
    ------
    ModelError
        Fewer than three pairs, or pairs that do not fix the constants (repeated angles).

    Examples
    --------
    The notes' Ex. 4.2 four-bar (d = 2, a = b = c = 1: K1 = 2, K2 = 2, K3 = 2.5):

    >>> fb = kl.mechanisms.fourbar(ground=2.0, crank=1.0, coupler=1.0, rocker=1.0)
    >>> q = np.array([-0.5, 0.0, 0.5])
    >>> kl.synthesis.freudenstein(q, kl.analyze(fb, q=q).angle("rocker")).round(12) + 0.0
    array([2. , 2. , 2.5])
    """
    t2, t4 = angle_array("theta2", theta2), angle_array("theta4", theta4)
    if t2.shape != t4.shape or t2.ndim != 1 or t2.size < 3:
        raise ModelError(f"theta2, theta4: expected two arrays of the same shape (n,), n >= 3, "
                         f"got {t2.shape} and {t4.shape}")
    M = np.column_stack([np.cos(t4), -np.cos(t2), np.ones_like(t2)])
    s = np.linalg.svd(M, compute_uv=False)
    if s[-1] <= 1e-10 * s[0]:
        raise ModelError("theta2, theta4: these angle pairs do not fix Freudenstein's constants "
                         "(a repeated or symmetric pair); spread the precision points")
    K, *_ = np.linalg.lstsq(M, np.cos(t2 - t4), rcond=None)
    return K


@dataclass(frozen=True, eq=False)
class FunctionSolution(CheckedLinkage):
    """A four-bar function generator and its structural error.

    Attributes
    ----------
    model : Mechanism
        The four-bar (catalogue names; ``O2`` at the origin, ``O4`` at (ground, 0)),
        sketched at the first precision point.
    K : ndarray, shape (3,)
        Freudenstein's constants.
    x : ndarray, shape (n,)
        The precision points.
    q : ndarray, shape (n,)
        The model's crank angle at each precision point, rad.
    input_range, output_range : (float, float)
        The model's crank angle at x0 and xf and rocker angle at f(x0) and f(xf), rad.
        They are the requested ranges, turned by pi where Freudenstein's solution gives
        a negative crank (or rocker) length: that link then points the other way.
    x_samples : ndarray, shape (m,)
        Where the structural error is sampled (m points over [x0, xf]).
    structural_error : ndarray, shape (m,)
        The generated output minus f(x), in the units of y (from the engine's rocker
        angle; +inf where the linkage cannot close there).
    precision_errors : ndarray, shape (n,)
        The same at the precision points: zero (to rounding) with three of them; with more,
        the residual of the least-squares fit at each one.
    fit : str
        ``"exact"`` (three precision points) or ``"least squares"`` (more), a property.
    grashof : Grashof
    min_transmission_angle : float
        Over the whole input range, rad (the engine's, :func:`kinelab.analyze`).
    branch_defect : bool
        The linkage cannot move over the range on one branch without a limit or
        dead-centre position, or meets a precision point on the other branch.  (No order
        defect is possible: the crank angle is a monotonic function of x.)
    defects : tuple of str
        The branch defect, and a transmission angle below ``transmission_limit``.
    transmission_limit : float
        The smallest transmission angle accepted over the input range, rad (30 deg unless
        the task says otherwise); ``meets_transmission_limit`` says whether it is kept.
    """

    model: Mechanism
    K: np.ndarray
    x: np.ndarray
    q: np.ndarray
    input_range: tuple[float, float]
    output_range: tuple[float, float]
    x_samples: np.ndarray
    structural_error: np.ndarray
    precision_errors: np.ndarray
    grashof: Grashof
    min_transmission_angle: float
    branch_defect: bool
    defects: tuple[str, ...]
    transmission_limit: float = TRANSMISSION_LIMIT

    @property
    def fit(self) -> str:
        """``"exact"`` with three precision points (Freudenstein's three equations fix K),
        ``"least squares"`` with more (``precision_errors`` then holds the miss at each)."""
        return "exact" if self.x.size == 3 else "least squares"

    @property
    def max_structural_error(self) -> float:
        """Largest |structural error| over [x0, xf], units of y."""
        return float(np.max(np.abs(self.structural_error)))

    def __repr__(self) -> str:
        L = ", ".join(f"{k}={v:.6g}" for k, v in self.lengths.items())
        state = self.state
        return (f"FunctionSolution({L}, max structural error={self.max_structural_error:.3g}, "
                f"{state})")


def _range(name, r, unit: str = "") -> tuple[float, float]:
    """(start, end): two different real numbers; angles (with a ``unit``) within
    ``MAX_TURNS`` turns, x values far enough apart for floats to tell the x between them
    apart."""
    try:
        a, b = r
    except (TypeError, ValueError):
        raise ModelError(f"{name}: expected (start, end), got {describe(r)}") from None
    if not (is_real(a) and is_real(b)) or float(a) == float(b):
        raise ModelError(f"{name}: expected two different finite numbers, got "
                         f"{describe(r)}{' ' + unit if unit else ''}")
    a, b = float(a), float(b)
    if unit:
        limit = MAX_TURNS * (360.0 if unit == "deg" else 2 * np.pi)
        if max(abs(a), abs(b)) > limit:
            raise ModelError(f"{name}: expected angles within {MAX_TURNS} turns of 0 "
                             f"({limit:g} {unit}), got {describe(r)} {unit}")
    elif max(abs(a), abs(b)) > _WIDEST:
        raise ModelError(f"{name}: expected numbers at most {_WIDEST:g} in size (their "
                         f"differences must stay finite), got {describe(r)}; scale x")
    elif abs(0.5 * b - 0.5 * a) <= _NARROWEST * max(abs(a), abs(b)):
        raise ModelError(f"{name}: expected a range wider than {_NARROWEST:g} of its values "
                         f"(floats cannot tell the x within it apart), got {describe(r)}; "
                         "shift or scale x")
    return a, b


def function_generation(f: Callable[[np.ndarray], np.ndarray], x_range: tuple[float, float],
                        input_range: tuple[float, float], output_range: tuple[float, float], *,
                        points: int | ArrayLike = 3, ground: float = 1.0, samples: int = 201,
                        min_transmission_angle: float | None = None,
                        degrees: bool = False) -> FunctionSolution:
    """A four-bar whose rocker angle generates y = f(x) from the crank angle.

    Parameters
    ----------
    f : callable
        The function, vectorised: ``f(x)`` for an array x.
    x_range : (float, float)
        [x0, xf], the range of x.
    input_range : (float, float)
        Crank angle at x0 and at xf, measured from the ground line O2 -> O4 (rad, or
        degrees with ``degrees=True``); |difference| < 2 pi.
    output_range : (float, float)
        Rocker angle at f(x0) and at f(xf), same units.
    points : int or array_like
        The number of precision points, spaced as Chebyshev's nodes (3 = exact), or the
        precision points themselves (x values).  With more than three (more than the three
        unknowns K1, K2, K3) Freudenstein's equation is solved in the least-squares sense,
        and ``precision_errors`` holds the residual at each point.
    ground : float
        O2O4, m (the linkage is scale-free; this sets its size).
    samples : int
        Points of the structural-error curve.
    min_transmission_angle : float, optional
        The smallest transmission angle accepted over the input range (rad, or degrees
        with ``degrees=True``); default 30 deg (:data:`TRANSMISSION_LIMIT`).  Below it the
        linkage has a transmission angle defect.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    FunctionSolution

    Raises
    ------
    ModelError
        Bad ranges, an f that is not finite or not continuous over x_range (a pole, a
        jump), f(x0) = f(xf), or no four-bar (an infinite link, a coupler whose squared
        length comes out negative, or a linkage at a dead centre at the first precision
        point: its coupler and rocker in line, as when both angles are zero there).

    Examples
    --------
    y = log10(x) on [1, 2], crank 90 -> 150 deg, rocker 0 -> 90 deg:

    >>> sol = kl.synthesis.function_generation(np.log10, (1, 2), (90, 150), (0, 90),
    ...                                        degrees=True)
    >>> sol.x.round(4)                                     # Chebyshev spacing
    array([1.067, 1.5  , 1.933])
    >>> round(sol.max_structural_error, 5), sol.valid    # y spans 0.301
    (0.00042, True)
    """
    return _function_generation(f, x_range, input_range, output_range, points, ground, samples,
                                min_transmission_angle, degrees)


def function_pairs(input_angles: ArrayLike, output_angles: ArrayLike,
                   O2: ArrayLike = (0.0, 0.0), O4: ArrayLike = (1.0, 0.0), *,
                   samples: int = 201, min_transmission_angle: float | None = None,
                   degrees: bool = False) -> FunctionSolution:
    """A four-bar on the fixed pivots O2, O4 whose rocker meets prescribed angle pairs.

    The precision points are given as pairs of angles rather than through a function: at
    the crank angle ``input_angles[j]`` the rocker angle is to be ``output_angles[j]``.
    Both are measured CCW from +x of the ground frame, as every angle in kinelab (with O2
    at the origin and O4 on +x they are the angles from the ground line of
    :func:`function_generation`), so the linkage's ``q`` *is* the input angle when its
    crank points along the input ray.  Freudenstein's equation is written with the angles
    less the ground line's angle.

    The crank passes the pairs in the order given, turning one way: the input angles
    increase, or decrease, from the first to the last, by less than a turn.  Between two
    pairs the function is taken as the straight line joining them, so ``x`` is the input
    angle (rad), ``structural_error`` the rocker angle less that line (rad) and
    ``precision_errors`` the miss at each pair.

    Parameters
    ----------
    input_angles, output_angles : array_like, shape (n,), 3 <= n <= 100
        Crank and rocker angles from +x (rad, or degrees with ``degrees=True``).
    O2, O4 : array_like, shape (2,)
        The fixed pivots of the crank and of the rocker, m.
    samples : int
        Points of the structural-error curve.
    min_transmission_angle : float, optional
        As in :func:`function_generation`.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    FunctionSolution
        Its ``q`` is the model's crank angle at each pair: the input angle, or the input
        angle + pi where Freudenstein's crank length comes out negative (the crank points
        back along the input ray); likewise for the rocker and ``output_range``.

    Raises
    ------
    ModelError
        Fewer than three pairs, input angles not in order or over a turn or more, O2 on O4,
        or no four-bar through the pairs.

    Examples
    --------
    The pairs of a known four-bar give it back:

    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    >>> q = np.radians([40.0, 70.0, 100.0])
    >>> out = kl.analyze(fb, q=q).angle("rocker")
    >>> sol = kl.synthesis.function_pairs(q, out, (0, 0), (3, 0))
    >>> {k: round(v, 9) for k, v in sol.lengths.items()}
    {'ground': 3.0, 'crank': 1.0, 'coupler': 3.0, 'rocker': 2.5}
    """
    return _function_pairs(input_angles, output_angles, O2, O4, samples, min_transmission_angle,
                           degrees)


def function_generation_pairs(input_angles: ArrayLike, output_angles: ArrayLike | None = None,
                              *, ground: float = 1.0, O2: ArrayLike = (0.0, 0.0),
                              samples: int = 201, min_transmission_angle: float | None = None,
                              degrees: bool = False) -> FunctionSolution:
    """Function generation from raw pairs of crank and rocker angles.

    The task as pylinkage (``pylinkage.synthesis.function_generation``) and most textbooks
    state it: a list of pairs (theta2, theta4), the rocker angle theta4 the linkage must
    show when the crank is at theta2.  Both angles are **absolute**, measured CCW from the
    ground line O2 -> O4, which runs along +x from ``O2`` to ``O4 = O2 + (ground, 0)``
    (not relative to the first pair: pylinkage's convention too).  This is a front of
    :func:`function_pairs` with the ground along +x: the same Freudenstein solution, the
    same checks.

    - three pairs: Freudenstein's three linear equations fix K1, K2, K3 exactly
      (``fit == "exact"``);
    - more than three: K is the least-squares solution of the overdetermined equations
      (``fit == "least squares"``), and ``precision_errors`` holds the linkage's
      structural error at each pair: its rocker angle less the prescribed one, rad (from
      the kinematics engine, not from Freudenstein's residuals).

    The crank must pass the pairs in the order given, turning one way (input angles all
    increasing or all decreasing, over less than a turn).

    Parameters
    ----------
    input_angles : array_like, shape (n,), or shape (n, 2) without ``output_angles``
        Crank angles theta2 from the ground line (rad, or degrees with ``degrees=True``);
        or, alone, the pairs (theta2, theta4) themselves, as pylinkage's ``angle_pairs``.
    output_angles : array_like, shape (n,), optional
        Rocker angles theta4 from the ground line, same units; 3 <= n <= 100.
    ground : float
        O2O4, m (the linkage is scale-free; this sets its size).
    O2 : array_like, shape (2,)
        The crank's fixed pivot, m.
    samples : int
        Points of the structural-error curve between the first and last pair.
    min_transmission_angle : float, optional
        As in :func:`function_generation`.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    FunctionSolution
        The four-bar (catalogue names) sketched at the first pair, with its defects
        (branch, transmission angle, a crank or rocker that points back along its rays),
        ``fit``, ``precision_errors`` and the structural error.

    Raises
    ------
    ModelError
        Pairs of the wrong shape, fewer than three, input angles out of order or over a
        turn, a ground length out of range, or no four-bar through the pairs.

    Examples
    --------
    Three pairs of a known four-bar (ground 3, crank 1, coupler 3, rocker 2.5) give it back:

    >>> pairs = [(40, 87.1457), (70, 92.1681), (100, 102.6990)]     # degrees
    >>> sol = kl.synthesis.function_generation_pairs(pairs, ground=3.0, degrees=True)
    >>> sol.fit, {k: round(v, 3) for k, v in sol.lengths.items()}
    ('exact', {'ground': 3.0, 'crank': 1.0, 'coupler': 3.0, 'rocker': 2.5})

    Five pairs, the same linkage's rocker angles rounded to whole degrees: least squares,
    with the structural error at each pair (deg):

    >>> sol = kl.synthesis.function_generation_pairs([40, 60, 80, 100, 120],
    ...                                              [87, 90, 95, 103, 111],
    ...                                              ground=3.0, degrees=True)
    >>> sol.fit, np.degrees(sol.precision_errors).round(1), sol.valid
    ('least squares', array([ 0.2, -0.4,  0.3, -0.2,  0. ]), True)
    """
    degrees = flag("degrees", degrees)
    if output_angles is None:
        pairs = reals("input_angles", input_angles)
        if pairs.ndim != 2 or pairs.shape[1] != 2:
            raise ModelError(f"input_angles: expected pairs (input, output) of shape (n, 2) when "
                             f"output_angles is not given, got shape {pairs.shape}; give the "
                             "pairs, or the input and the output angles apart")
        input_angles, output_angles = pairs[:, 0], pairs[:, 1]
    if not (is_real(ground) and float(ground) > 0):
        raise ModelError(f"ground: expected a positive length (m), got {describe(ground)}")
    if why := length_problem(float(ground)):
        raise ModelError(f"ground: {why}, got {float(ground):g} m")
    O2 = as_xy("O2", O2)
    return _function_pairs(input_angles, output_angles, O2, O2 + (float(ground), 0.0), samples,
                           min_transmission_angle, degrees)


def _function_pairs(input_angles, output_angles, O2=(0.0, 0.0), O4=(1.0, 0.0), samples=201,
                    min_transmission_angle=None, degrees=False,
                    shown: str | None = None) -> FunctionSolution:
    """:func:`function_pairs`; ``shown`` as in :func:`_function_generation`."""
    degrees = flag("degrees", degrees)
    unit = "deg" if degrees else "rad"
    t_in = angle_array("input_angles", input_angles, degrees)
    t_out = angle_array("output_angles", output_angles, degrees)
    if t_in.ndim != 1 or t_in.shape != t_out.shape:
        raise ModelError(f"input_angles, output_angles: expected two arrays of the same shape "
                         f"(n,), got {t_in.shape} and {t_out.shape}")
    if not 3 <= t_in.size <= MAX_PRECISION_POINTS:
        raise ModelError(f"input_angles, output_angles: expected 3 to {MAX_PRECISION_POINTS} "
                         f"pairs, got {t_in.size}")
    O2, O4 = as_xy("O2", O2), as_xy("O4", O4)
    if not float(np.hypot(*(O4 - O2))) > 0:
        raise ModelError(f"O4: expected a fixed pivot apart from O2, got both at {fmt(O2)}; "
                         "move one of them")
    step = np.diff(t_in)
    shown_in = np.degrees(t_in) if (shown or unit) == "deg" else t_in
    if not (np.all(step > 0) or np.all(step < 0)):
        raise ModelError(f"input_angles: expected angles in the order the crank passes them, all "
                         f"increasing or all decreasing, got "
                         f"{', '.join(f'{v:.6g}' for v in shown_in)} {shown or unit}; "
                         "order the pairs along the crank's travel")
    if abs(t_in[-1] - t_in[0]) >= 2 * np.pi:
        raise ModelError("input_angles: the crank would turn a full circle or more from the "
                         "first pair to the last, so an input angle would stand for two pairs; "
                         "keep them within less than one turn")
    samples = whole("samples", samples, 2, MAX_SAMPLES)
    limit = transmission_limit(min_transmission_angle, degrees)
    phi = math.atan2(O4[1] - O2[1], O4[0] - O2[0])
    order = np.argsort(t_in)

    def theta2(xv):
        return xv - phi

    def theta4(xv):
        return np.interp(xv, t_in[order], t_out[order]) - phi

    x = t_in.copy()
    return _generator(x, theta2, theta4, (x[0], x[-1]), (x[0] - phi, x[-1] - phi),
                      (t_out[0] - phi, t_out[-1] - phi), 1.0, O2, O4, samples, limit,
                      shown or unit, "input_angles, output_angles", lambda xv: "1",
                      name="input_angles, output_angles",
                      remedy="move the pairs (or the pivots) or add a pair", along_rays=True)


def _function_generation(f, x_range, input_range, output_range, points=3, ground=1.0,
                         samples=201, min_transmission_angle=None, degrees=False,
                         shown: str | None = None) -> FunctionSolution:
    """:func:`function_generation`; ``shown``, the angle unit its messages show angles in
    (a task file's; default the call's)."""
    if not callable(f):
        raise ModelError(f"f: expected a function of x, got {describe(f)}")
    x0, xf = _range("x_range", x_range)
    degrees = flag("degrees", degrees)
    unit = "deg" if degrees else "rad"
    t2s, t2e = _range("input_range", input_range, unit)
    t4s, t4e = _range("output_range", output_range, unit)
    if degrees:
        t2s, t2e, t4s, t4e = np.radians([t2s, t2e, t4s, t4e])
    if abs(t2e - t2s) >= 2 * np.pi:
        raise ModelError("input_range: the crank would turn a full circle or more, so an input "
                         "angle would stand for two values of x; use less than one turn")
    if abs(t4e - t4s) >= 2 * np.pi:
        raise ModelError("output_range: the rocker would turn a full circle or more, so an "
                         "output angle would stand for two values of y; use less than one turn")
    if not (is_real(ground) and ground > 0):
        raise ModelError(f"ground: expected a positive length (m), got {describe(ground)}")
    if why := length_problem(float(ground)):
        raise ModelError(f"ground: {why}, got {float(ground):g} m")
    samples = whole("samples", samples, 2, MAX_SAMPLES)
    limit = transmission_limit(min_transmission_angle, degrees)
    if np.ndim(points) == 0:
        points = whole("points", points, 3, MAX_PRECISION_POINTS)
    else:
        points = reals("points", points)
        if points.size > MAX_PRECISION_POINTS:
            raise ModelError(f"points: expected at most {MAX_PRECISION_POINTS} precision points, "
                             f"got {points.size:,}")
    _check_continuous(f, x0, xf)
    y0, yf = (float(v) for v in _values(f, np.array([x0, xf])))
    if y0 == yf:
        raise ModelError(f"f: f(x0) = {y0:.6g} and f(xf) = {yf:.6g} must be different finite "
                         "numbers to scale the output; choose another x_range")
    if np.ndim(points) == 0:
        x = chebyshev_points((x0, xf), points)
    else:
        x = np.sort(np.asarray(points, float))
        if x.ndim != 1 or not np.all((x >= min(x0, xf)) & (x <= max(x0, xf))):
            raise ModelError(f"points: expected precision points (x values) from {min(x0, xf):g} "
                             f"to {max(x0, xf):g} (x_range), got {describe(points)}")
    if x.size < 3:
        raise ModelError(f"points: expected at least 3 precision points, got {x.size}")

    def theta2(xv):
        return t2s + (xv - x0) / (xf - x0) * (t2e - t2s)

    def theta4(xv):
        return t4s + (np.asarray(f(xv), float) - y0) / (yf - y0) * (t4e - t4s)

    return _generator(x, theta2, theta4, (x0, xf), (t2s, t2e), (t4s, t4e), (yf - y0) / (t4e - t4s),
                      (0.0, 0.0), (float(ground), 0.0), samples, limit, shown or unit,
                      "input_range, output_range", lambda xv: f"x = {xv:.6g}")


def _generator(x, theta2, theta4, x_range, input_range, output_range, y_per_rad, O2, O4,
               samples, limit, shown, where, name_point, name="points",
               remedy="change the angle ranges or the number of points",
               along_rays: bool = False) -> FunctionSolution:
    """The four-bar through the precision points ``x`` (n,), checked over ``x_range``:
    ``theta2(x)``, ``theta4(x)`` the crank and rocker angles from the ground line O2 -> O4
    (rad), ``input_range``, ``output_range`` those at the ends of ``x_range``, ``y_per_rad``
    the units of y per radian of output (for the structural error); ``where`` names the
    task's items in a dead centre's message, ``name_point(x)`` a precision point; ``name``
    the argument a linkage that cannot be found is blamed on, ``remedy`` what to change;
    ``along_rays``: the angles are the links' own directions (angle pairs), so a link that
    Freudenstein's solution turns round is a defect."""
    x0, xf = x_range
    t2s, t2e = input_range
    t4s, t4e = output_range
    O2, O4 = np.asarray(O2, float), np.asarray(O4, float)
    phi = math.atan2(O4[1] - O2[1], O4[0] - O2[0])      # the ground line's angle from +x
    e = lambda t: np.array([np.cos(t), np.sin(t)])      # noqa: E731
    K = freudenstein(theta2(x), theta4(x))
    if np.any(np.abs(K[:2]) <= 1e-12):
        raise ModelError(f"{name}: Freudenstein's solution has K1 or K2 = 0, an infinitely long "
                         f"crank or rocker; {remedy}")
    d = float(np.hypot(*(O4 - O2)))
    a, c = d / K[0], d / K[1]                 # signed: negative means the link points back
    b2 = a * a + c * c + d * d - 2 * a * c * K[2]
    if b2 <= (1e-12 * d) ** 2:
        raise ModelError(f"{name}: no four-bar generates these precision points (the coupler's "
                         f"squared length comes out {b2:.3g} m^2); {remedy}")
    A = O2 + a * e(theta2(x[0]) + phi)
    B = O4 + c * e(theta4(x[0]) + phi)
    if x.size > 3:
        # least squares: the linkage of Freudenstein's lengths (coupler sqrt(b2)), assembled
        # at the first point's crank angle where its rocker pin is nearest the prescribed one
        B = _assembled(A, O4, math.sqrt(b2), abs(c), B, name, remedy)
    model = fourbar_model(O2, O4, A, B, name="function generator")
    at = [theta2(x[0]) + phi, theta4(x[0]) + phi]
    at = np.degrees(at) if shown == "deg" else at
    start, other = ("10 deg", "20 deg") if shown == "deg" else ("0.2 rad", "0.4 rad")
    planned(model, f"{where}: at the precision point {name_point(x[0])} (input "
            f"angle {at[0]:.6g} {shown}, output angle {at[1]:.6g} {shown})",
            f"offset the angle ranges (start the input at, say, {start} and the output at "
            f"{other}) or choose other precision points")
    q_off = np.pi if a < 0 else 0.0
    out_off = np.pi if c < 0 else 0.0

    xs = np.linspace(x0, xf, samples)
    # also where the crank points along the ground line (crank pin nearest and farthest from
    # O4): a limit position or the worst transmission angle in between cannot be missed
    k = np.arange(np.floor((min(t2s, t2e) + q_off) / np.pi), np.ceil((max(t2s, t2e) + q_off) / np.pi) + 1)
    along = (k * np.pi - q_off - t2s) / (t2e - t2s)
    turns = x0 + along[(along > 0) & (along < 1)] * (xf - x0)
    grid = np.concatenate([xs, x, turns])
    sol = analyze(model, theta2(grid) + phi + q_off, unreachable="mask", at_singular="flag")
    miss = wrap_angle(sol.angle("rocker") - out_off - phi - theta4(grid))
    error = np.where(sol.assembled, miss * y_per_rad, np.inf)
    sign0 = np.sign(sol.det_J[samples])            # at the first precision point (the sketch)
    good = sol.assembled & ~sol.singular & (np.sign(sol.det_J) == sign0)
    defects = []
    # three points are met exactly, so a miss there means the other branch; with more (least
    # squares) the sweep alone decides
    exact = x.size == 3
    if not good.all() or (exact and np.any(np.abs(miss[samples:samples + x.size]) > _REACHED)):
        defects.append("branch defect: the linkage cannot move over the whole input range on the "
                       "branch of the first precision point (a limit or dead-centre position, "
                       "or a precision point on the other branch)")
    branch_defect = bool(defects)
    mu = transmission_angle(sol)[sol.assembled]
    mu_min = float(mu.min()) if mu.size else float("nan")
    defects += transmission_defects(mu_min, limit, "over the input range")
    if along_rays:
        # the pairs fix Freudenstein's constants, so no other four-bar on these pivots meets
        # them: a negative length means the link points back along its rays
        defects += [f"{link} reversed: no four-bar on these pivots has its {link} along the "
                    f"{side} rays; this one's {link} points back along them (at each pair's "
                    f"{side} angle + 180 deg)"
                    for link, side, off in (("crank", "input", q_off), ("rocker", "output", out_off))
                    if off]
    q = theta2(x) + phi + q_off
    for arr in (K, x, q, xs):
        arr.setflags(write=False)
    err = error[:samples]
    at_points = error[samples:samples + x.size]
    for arr in (err, at_points):
        arr.setflags(write=False)
    return FunctionSolution(
        model=model, K=K, x=x, q=q, input_range=(t2s + phi + q_off, t2e + phi + q_off),
        output_range=(t4s + phi + out_off, t4e + phi + out_off), x_samples=xs, structural_error=err,
        precision_errors=at_points,
        grashof=model_grashof(model),
        min_transmission_angle=mu_min, branch_defect=branch_defect, defects=tuple(defects),
        transmission_limit=limit)


def _values(f: Callable, x: np.ndarray) -> np.ndarray:
    """f at x (n,), checked finite."""
    try:
        y = np.asarray(f(x))
        if y.dtype.kind not in "iuf":
            raise ModelError(f"f: expected real numbers, one for each x, got {describe(y)}")
        y = np.broadcast_to(y.astype(float), x.shape)
    except ModelError:
        raise                   # the function's own message (a parsed formula's, say)
    except (TypeError, ValueError, OverflowError):
        raise ModelError("f: expected a function of x that gives one number for each x") from None
    if not np.all(np.isfinite(y)):
        bad = float(x[np.flatnonzero(~np.isfinite(y))[0]])
        raise ModelError(f"f: expected finite values over x_range, got {float(y[~np.isfinite(y)][0])} "
                         f"at x = {bad:.9g}; choose an x_range where f is finite")
    return y


def _check_continuous(f: Callable, x0: float, xf: float) -> None:
    """Refuse an f that is not finite, or not continuous (a pole, a jump), over [x0, xf].

    f is sampled on a fine grid, and the intervals where it changes most are halved again
    and again, keeping the half where it changes more: for a continuous f that change
    shrinks towards zero; across a jump it stays, and across a pole it grows.  (A linkage
    generates only a continuous function, and between two samples a pole would pass
    unseen: the structural error would be measured on either side of it.)"""
    x = np.linspace(x0, xf, _GRID + 1)
    y = _values(f, x)
    change = np.abs(np.diff(y))
    k = np.argsort(change)[-_STEEPEST:]
    a, b, ya, yb = x[k], x[k + 1], y[k], y[k + 1]
    start = change[k]
    for _ in range(_HALVINGS):
        m = 0.5 * (a + b)
        ym = _values(f, m)
        left = np.abs(ym - ya) >= np.abs(yb - ym)
        a, ya = np.where(left, a, m), np.where(left, ya, ym)
        b, yb = np.where(left, m, b), np.where(left, ym, yb)
    end = np.abs(yb - ya)
    scale = float(np.abs(y).max())
    jumps = (end > 0.25 * start) & (end > 1e-9 * scale)
    if jumps.any():
        i = int(np.argmax(np.where(jumps, end, -np.inf)))
        at = float(0.5 * (a[i] + b[i]))
        what = ("has a pole (it grows without bound)" if end[i] > 1e3 * start[i]
                else f"jumps by {end[i]:.6g}")
        raise ModelError(f"f: expected a function continuous over x_range [{x0:g}, {xf:g}], "
                         f"but it {what} near x = {at:.9g}; a linkage generates only a continuous "
                         "function, so choose an x_range that leaves that point out")


def _assembled(A: np.ndarray, O4: np.ndarray, coupler: float, rocker: float,
               near: np.ndarray, name: str, remedy: str) -> np.ndarray:
    """The rocker pin B at |B - A| = coupler, |B - O4| = rocker nearest ``near``."""
    D = O4 - A
    L = float(np.hypot(*D))
    if not abs(coupler - rocker) < L < coupler + rocker:
        raise ModelError(f"{name}: the least-squares linkage cannot be assembled at the first "
                         f"precision point; {remedy}")
    along = (L * L + coupler * coupler - rocker * rocker) / (2 * L)
    h = math.sqrt(max(coupler * coupler - along * along, 0.0))
    mid, n = A + along * D / L, np.array([-D[1], D[0]]) / L
    return min((mid + h * n, mid - h * n), key=lambda B: float(np.hypot(*(B - near))))
