"""Derivatives of a sampled, noisy curve: graphical differentiation done by least squares.

Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades* (Universidade do
Minho, 2007), §4.6.4 differentiate a measured displacement curve by drawing tangents over
equal intervals.  Here the tangent is a local polynomial fitted by least squares
(Savitzky-Golay smoothing, generalised to uneven sampling), the interval is chosen from the
data by generalised cross-validation, and every derivative comes with an error estimate.

This is generic numerics: it knows nothing of mechanisms, so it lives in the solvers and is
also reached as ``kinelab.kinematics.differentiate``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.model._values import real_array

__all__ = ["Derivatives", "differentiate", "DEGREE", "MIN_WINDOW", "MIN_SAMPLES"]

DEGREE = 5          # of the local polynomials: their bias is small enough for the second
                    # derivative, and they leave the ends free (no boundary condition)
MIN_WINDOW = 11     # samples per fit: the degree DEGREE + 2 fit of the error estimate keeps
                    # a few degrees of freedom
MIN_SAMPLES = 15    # so that cross-validation has at least three windows to choose from
UNDERSMOOTH = 0.7   # the window used is this fraction of the cross-validated one (below)
SPREAD = 4.0        # standard errors in an error band
BIAS = 2.0          # times the change with a degree DEGREE + 2 fit, added to the band
GCV_WINDOWS = 40    # candidate windows, on a geometric grid from MIN_WINDOW to N
GCV_SAMPLES = 500   # cross-validation scores are summed over at most this many samples
BLOCK = 2_000_000   # numbers per block of fits (samples x window): bounds the memory


@dataclass(frozen=True)
class Derivatives:
    """A sampled curve y(x), smoothed, with its first and second derivatives and their
    error estimates.

    Attributes
    ----------
    x : ndarray, shape (N,)
        The abscissae (time, or an input angle), as given.
    y : ndarray, shape (N,)
        The smoothed curve at ``x``.
    velocity, acceleration : ndarray, shape (N,)
        dy/dx and d2y/dx2 (with x the time: velocity and acceleration).
    velocity_error, acceleration_error : ndarray, shape (N,)
        Half-widths of the bands around ``velocity`` and ``acceleration`` that hold the
        exact derivatives: ``SPREAD`` (4) standard errors of the estimate, from the noise
        ``noise``, plus ``BIAS`` (2) times its change when the local polynomial's degree
        goes from 5 to 7 over the same samples (an estimate of its truncation error).
    noise : float
        The estimated standard deviation of the noise in the data, in y's unit.
    window : int
        Samples in each local fit.
    window_gcv : int
        The window generalised cross-validation chose for the curve itself.
    residual : ndarray, shape (N,)
        The data minus the smoothed curve.
    """

    x: np.ndarray
    y: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    velocity_error: np.ndarray
    acceleration_error: np.ndarray
    noise: float
    window: int
    window_gcv: int
    residual: np.ndarray

    def __repr__(self) -> str:
        return (f"Derivatives(N={len(self.x)}, window={self.window} samples, "
                f"noise={self.noise:.3g})")


def _samples(name: str, value: ArrayLike) -> np.ndarray:
    a = real_array(value)
    if a is None:
        raise ModelError(f"{name}: expected real numbers, got {describe(value)}")
    if a.ndim != 1:
        raise ModelError(f"{name}: expected one row of samples (shape (N,)), got shape {a.shape}")
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        raise ModelError(f"{name}[{bad[0]}]: expected a finite number, got {a[bad[0]]}"
                         + (f" (and {bad.size - 1} more)" if bad.size > 1 else "")
                         + "; remove or fill in those samples")
    return a


def _check(x: ArrayLike, y: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    x, y = _samples("x", x), _samples("y", y)
    if len(x) != len(y):
        raise ModelError(f"y: expected as many samples as x ({len(x)}), got {len(y)}")
    if len(x) < MIN_SAMPLES:
        raise ModelError(f"x: expected at least {MIN_SAMPLES} samples, got {len(x)}; a "
                         f"local fit takes {MIN_WINDOW} samples, and cross-validation "
                         "compares several fits")
    step = np.diff(x)
    bad = np.flatnonzero(step <= 0)
    if bad.size:
        k = int(bad[0]) + 1
        raise ModelError(f"x[{k}]: expected abscissae that increase, got {float(x[k])!r} after "
                         f"x[{k - 1}] = {float(x[k - 1])!r}; sort the samples and merge repeated ones")
    if not np.all(np.isfinite(step / np.ptp(x))) or np.min(step) <= np.ptp(x) * 1e-12:
        raise ModelError("x: expected distinct abscissae, got samples closer than 1e-12 of "
                         "the range; merge them")
    return x, y


class _Fits:
    """Local polynomial fits over ``window`` samples, at given samples, of each degree in
    ``degrees``: for each, the weights that turn the window's y into the fitted value, first
    and second derivative at that sample (``weights[degree]``, shape (rows, window, 3): rows
    of the least-squares solution, evaluated there).

    The polynomials are written in Legendre polynomials of u, the window mapped onto
    [-1, 1], which keeps the normal equations well conditioned; a lower degree's system is
    a corner of the higher one's."""

    def __init__(self, x: np.ndarray, rows: np.ndarray, window: int, degrees=(DEGREE,),
                 even: bool = False):
        from numpy.polynomial import legendre
        n, top = len(x), max(degrees)
        start = np.clip(rows - window // 2, 0, n - window)   # centred; at the ends, the first or last
        self.index = start[:, None] + np.arange(window)
        every = rows
        if even:
            # evenly spaced: the weights depend only on where the sample sits in its window,
            # so they are computed once for each place and shared
            _, first, shared = np.unique(rows - start, return_index=True, return_inverse=True)
            rows, start = rows[first], start[first]
        xw = x[start[:, None] + np.arange(window)]
        mid, half = 0.5 * (xw[:, -1] + xw[:, 0]), 0.5 * (xw[:, -1] - xw[:, 0])
        V = legendre.legvander((xw - mid[:, None]) / half[:, None], top)   # (rows, window, top + 1)
        gram = np.swapaxes(V, 1, 2) @ V
        at = legendre.legvander((x[rows] - mid) / half, top)                # (rows, top + 1)
        # value, d/du and d2/du2 of each basis polynomial at the sample
        derivative = [np.array([np.pad(legendre.legder(e, nu), (0, nu)) for e in np.eye(top + 1)]).T
                      for nu in (0, 1, 2)]
        basis = np.stack([at @ d for d in derivative], axis=2)             # (rows, top + 1, 3)
        scale = np.stack([np.ones_like(half), 1.0 / half, 1.0 / half ** 2], axis=1)[:, None, :]
        self.weights = {}
        for d in degrees:
            coef = np.linalg.solve(gram[:, :d + 1, :d + 1], basis[:, :d + 1])
            self.weights[d] = (V[:, :, :d + 1] @ coef) * scale
            if even:
                self.weights[d] = self.weights[d][shared]
        rows, start = every, self.index[:, 0]
        self.self_weight = self.weights[degrees[0]][np.arange(len(rows)), rows - start, 0]

    def apply(self, degree: int, y: np.ndarray) -> np.ndarray:
        """(rows, 3): the value, first and second derivative of the fit of ``degree``."""
        return np.einsum("rwn,rw->rn", self.weights[degree], y[self.index])

    def norms(self, degree: int) -> np.ndarray:
        """(rows, 3): the norms of the weights, which scale the noise into each estimate."""
        return np.sqrt(np.einsum("rwn,rwn->rn", self.weights[degree], self.weights[degree]))


def _blocks(rows: np.ndarray, window: int):
    """``rows`` in blocks of at most BLOCK numbers of fits each."""
    return np.array_split(rows, max(1, len(rows) * window * (DEGREE + 3) // BLOCK))


def _residuals(x: np.ndarray, y: np.ndarray, rows: np.ndarray, window: int,
               even: bool = False) -> tuple[float, float]:
    """The residual sum of squares of the fits at ``rows`` and the sum of their weights on
    their own sample (the trace of the hat matrix)."""
    rss = trace = 0.0
    for block in _blocks(rows, window):
        f = _Fits(x, block, window, even=even)
        rss += float(np.sum((y[block] - f.apply(DEGREE, y)[:, 0]) ** 2))
        trace += float(np.sum(f.self_weight))
    return rss, trace


def _gcv_window(x: np.ndarray, y: np.ndarray, even: bool = False) -> int:
    """The window that minimises the generalised cross-validation score of the smoothed
    curve, N RSS / (N - trace H)^2, summed over at most GCV_SAMPLES evenly spread samples."""
    n = len(x)
    rows = np.unique(np.linspace(0, n - 1, min(n, GCV_SAMPLES)).round().astype(int))
    windows = np.unique(np.geomspace(MIN_WINDOW, n, GCV_WINDOWS).round().astype(int) | 1)
    windows = windows[windows <= n]
    scores = []
    for w in windows:
        rss, trace = _residuals(x, y, rows, int(w), even)
        scores.append(len(rows) * rss / max(len(rows) - trace, 1e-300) ** 2)
    return int(windows[int(np.argmin(scores))])


def differentiate(x: ArrayLike, y: ArrayLike, *, window: int | None = None) -> Derivatives:
    """First and second derivatives of sampled data y(x), with an error estimate per sample.

    The graphical differentiation of Flores & Claro (§4.6.4) draws the tangent to the
    curve over an interval around each point.  Here, at each sample, a polynomial of degree
    5 is fitted by least squares to the ``window`` samples around it (at the ends, to the
    first or last ``window``): its derivatives at the sample are the estimates.  On evenly
    spaced data this is the Savitzky-Golay filter (``scipy.signal.savgol_filter`` with
    ``mode="interp"``, which the tests check); it also takes uneven sampling.

    The rule that chooses the window, from the data:

    1. generalised cross-validation (GCV) picks the window that best predicts the curve
       itself, among about 40 odd windows from 11 samples to all of them;
    2. the derivatives use 0.7 of it: a derivative amplifies the bias of smoothing, and a
       shorter window keeps it small beside the noise, so the error bands hold;
    3. the noise sigma is estimated from the residuals of step 1, RSS / (N - trace H).

    Each error is 4 standard errors of the estimate (sigma times the norm of the estimate's
    weights on the data) plus twice the change of the estimate when the polynomial's degree
    goes to 7 over the same samples, which measures its truncation error.

    Parameters
    ----------
    x : array_like, shape (N,)
        Abscissae, strictly increasing (time in s, or an input angle), evenly spaced or
        not.  N >= 15.
    y : array_like, shape (N,)
        The measured curve (a displacement), with noise.
    window : int, optional
        Samples per local fit (odd, from 11 to N), instead of the rule above.

    Returns
    -------
    Derivatives
        ``velocity`` = dy/dx, ``acceleration`` = d2y/dx2 and their errors, (N,) each.

    Raises
    ------
    ModelError
        Fewer than 15 samples, abscissae that do not increase, numbers that are not finite
        (the message names the index), or a window out of range.

    Examples
    --------
    The displacement of a slider-crank (crank 0.1 m, rod 0.3 m, 10 rad/s) sampled every
    degree of a turn, with 0.01 mm of noise: the estimates stay within their bands of the
    exact derivatives.

    >>> sc = kl.mechanisms.slider_crank(crank=0.1, rod=0.3)
    >>> t = np.linspace(0.0, 2 * np.pi / 10.0, 361)
    >>> sol = kl.analyze(sc, q=10.0 * t, qd=10.0)
    >>> x = sol.slide("slide") + 1e-5 * np.random.default_rng(1).standard_normal(361)
    >>> d = kl.kinematics.differentiate(t, x)
    >>> bool(np.all(np.abs(d.velocity - sol.slide_velocity("slide")) <= d.velocity_error))
    True
    >>> bool(np.all(np.abs(d.acceleration - sol.slide_acceleration("slide")) <= d.acceleration_error))
    True
    >>> bool(0.8e-5 < d.noise < 1.2e-5)               # the noise, estimated from the data
    True
    """
    x, y = _check(x, y)
    n = len(x)
    if window is not None:
        if isinstance(window, bool) or not isinstance(window, (int, np.integer)) or \
                not MIN_WINDOW <= window <= n:
            raise ModelError(f"window: expected a whole number of samples from {MIN_WINDOW} to "
                             f"{n}, got {describe(window)}")
    # x and y at a unit scale: the fits are scale-free, and the errors come out in y's unit
    xs = float(np.ptp(x))
    y0 = float(np.mean(y))
    ys = float(np.max(np.abs(y - y0))) or 1.0
    u, v = (x - x[0]) / xs, (y - y0) / ys
    step = np.diff(u)
    even = bool(np.ptp(step) <= 1e-9 * np.mean(step))
    gcv = _gcv_window(u, v, even) if window is None else int(window)
    used = int(window) if window is not None else max(MIN_WINDOW, int(round(UNDERSMOOTH * gcv)) | 1)
    rss, trace = _residuals(u, v, np.arange(n), gcv, even)
    sigma = np.sqrt(rss / max(n - trace, 1.0))
    fit, norm, change = np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3))
    for rows in _blocks(np.arange(n), used):
        f = _Fits(u, rows, used, (DEGREE, DEGREE + 2), even)
        fit[rows] = f.apply(DEGREE, v)
        norm[rows] = f.norms(DEGREE)
        change[rows] = fit[rows] - f.apply(DEGREE + 2, v)
    scale = np.array([ys, ys / xs, ys / xs ** 2])
    error = (SPREAD * sigma * norm + BIAS * np.abs(change)) * scale
    fit = fit * scale
    smooth = y0 + fit[:, 0]
    return Derivatives(x=x.copy(), y=smooth, velocity=fit[:, 1], acceleration=fit[:, 2],
                       velocity_error=error[:, 1], acceleration_error=error[:, 2],
                       noise=float(sigma * ys), window=used, window_gcv=gcv, residual=y - smooth)
