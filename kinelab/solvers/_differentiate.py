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

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.model._values import real_array

__all__ = ["Derivatives", "differentiate", "DEGREE", "MIN_WINDOW", "MIN_SAMPLES",
           "MAX_SAMPLES", "MAX_UNEVEN"]

DEGREE = 5          # of the local polynomials: their bias is small enough for the second
                    # derivative, and they leave the ends free (no boundary condition)
MIN_WINDOW = 11     # samples per fit: the degree DEGREE + 2 fit of the error estimate keeps
                    # a few degrees of freedom
MIN_SAMPLES = 15    # so that cross-validation has at least three windows to choose from
MAX_SAMPLES = 1_000_000  # about 5 s of work, evenly spaced (N log N, by FFT)
MAX_UNEVEN = 10_000  # unevenly spaced samples: each of their fits is a least-squares problem
                    # of its own, window x N work, where evenly spaced ones share one filter
UNDERSMOOTH = 0.7   # the window used is this fraction of the cross-validated one (below)
SPREAD = 4.0        # standard errors in an error band
BIAS = 2.0          # times the change with a degree DEGREE + 2 fit, added to the band
GCV_WINDOWS = 40    # candidate windows, on a geometric grid from MIN_WINDOW to N
GCV_SAMPLES = 500   # cross-validation scores are summed over at most this many samples
BLOCK = 2_000_000   # numbers per block of fits (samples x window): bounds the memory
EVEN = 1e-9         # steps equal to this fraction of their mean count as evenly spaced
DISTINCT = 1e-12    # the smallest step, as a fraction of the range of x
RESOLVED = 1000     # the smallest step, in units of float64's spacing at the largest |x|:
                    # the rounding of x is then at most 0.1 % of a step
CONDITION = 1e12    # of a fit's normal equations (degree DEGREE + 2): beyond it, too few of
                    # the window's samples are apart to determine the polynomial


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
    if len(x) > MAX_SAMPLES:
        raise ModelError(f"x: expected at most {MAX_SAMPLES:,} samples, got {len(x):,}; cut "
                         "the curve into pieces, or keep every k-th sample")
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
    return x, y


def _binary_scaled(a: np.ndarray) -> tuple[np.ndarray, int]:
    """``a / 2**e`` and ``e``, with the largest magnitude in [0.5, 1).  Dividing by a power
    of two is exact, and nothing overflows on the way: the units come back at the end, in
    :func:`_restored`, where an overflow can be named."""
    top = float(np.max(np.abs(a)))
    e = math.frexp(top)[1] if top > 0 else 0
    return np.ldexp(a, -e), e


def _abscissae(x: np.ndarray) -> tuple[np.ndarray, float, int]:
    """x mapped onto [0, 1] (u = (x - x[0]) / (range of x)), with the range of x / 2**e and
    e; refuses steps too small for float64 to tell the samples apart."""
    x1, e = _binary_scaled(x)
    span = float(x1[-1] - x1[0])
    step = np.diff(x1)
    k = int(np.argmin(step))
    pair = f"x[{k + 1}] = {float(x[k + 1])!r} after x[{k}] = {float(x[k])!r}"
    if step[k] <= DISTINCT * span:
        raise ModelError(f"x[{k + 1}]: expected samples apart by more than {DISTINCT:g} of the "
                         f"range of x, got {pair}; merge samples this close")
    spacings = float(step[k] / np.spacing(np.max(np.abs(x1))))
    if spacings < RESOLVED:
        raise ModelError(f"x[{k + 1}]: expected steps that float64 resolves (at least {RESOLVED} "
                         f"times its spacing at the largest |x|), got {pair}, {spacings:.0f} "
                         "times; subtract a reference from x (such as its first value) so that "
                         "it starts near 0")
    return (x1 - x1[0]) / span, span, e


# value, first and second derivative of each Legendre polynomial up to a degree, as matrices
# that turn its values (legvander) into theirs
_DERIVATIVES = {top: [np.array([np.pad(np.polynomial.legendre.legder(c, nu), (0, nu))
                                for c in np.eye(top + 1)]).T for nu in (0, 1, 2)]
                for top in (DEGREE, DEGREE + 2)}


def _uneven_fits(u: np.ndarray, v: np.ndarray, rows: np.ndarray, window: int,
                 degrees: tuple[int, ...]) -> tuple[dict, np.ndarray]:
    """Local least-squares polynomials over ``window`` samples, at ``rows`` (centred; at the
    ends, over the first or last ``window``), each a problem of its own.

    Returns ``{degree: (fit, norm2)}``, both (rows, 3): the fitted value, first and second
    derivative (in u) at the sample, and the squared norms of their weights on the data,
    c^T G^-1 c (G the normal equations, c the basis evaluated there), which scale the noise
    into each estimate; and a (rows,) mask of the fits too ill-conditioned to trust.

    The polynomials are written in Legendre polynomials of the window mapped onto [-1, 1],
    which keeps the normal equations well conditioned; a lower degree's system is a corner
    of the higher one's."""
    from numpy.polynomial import legendre
    n, top = len(u), max(degrees)
    start = np.clip(rows - window // 2, 0, n - window)
    index = start[:, None] + np.arange(window)
    uw = u[index]
    mid, half = 0.5 * (uw[:, -1] + uw[:, 0]), 0.5 * (uw[:, -1] - uw[:, 0])
    V = legendre.legvander((uw - mid[:, None]) / half[:, None], top)   # (rows, window, top + 1)
    gram = np.swapaxes(V, 1, 2) @ V
    # the top degree's system bounds the condition of every corner of it (interlacing)
    eig = np.linalg.eigvalsh(gram)
    bad = ~(eig[:, 0] > eig[:, -1] / CONDITION)
    gram[bad] = np.eye(top + 1)                     # refused by the caller, solved harmlessly
    at = legendre.legvander((u[rows] - mid) / half, top)               # (rows, top + 1)
    basis = np.stack([at @ d for d in _DERIVATIVES[top]], axis=2)      # (rows, top + 1, 3)
    moments = np.einsum("rwt,rw->rt", V, v[index])
    scale = np.stack([np.ones_like(half), 1.0 / half, 1.0 / half ** 2], axis=1)
    out = {}
    for d in degrees:
        c = basis[:, :d + 1]
        solved = np.linalg.solve(gram[:, :d + 1, :d + 1],
                                 np.concatenate([moments[:, :d + 1, None], c], axis=2))
        out[d] = (np.einsum("rt,rtk->rk", solved[:, :, 0], c) * scale,
                  np.einsum("rtk,rtk->rk", c, solved[:, :, 1:]) * scale ** 2)
    return out, bad


def _correlated(v: np.ndarray, kernel: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """(starts, m): sum over j of kernel[j] v[start + j], directly for a few starts, else
    for every start at once by FFT (N log N, whatever the window)."""
    n, w = len(v), len(kernel)
    if len(starts) * w <= 2 * (n + w) * np.log2(n + w):
        view = np.lib.stride_tricks.sliding_window_view(v, w)
        parts = np.array_split(starts, max(1, len(starts) * w // BLOCK))
        return np.concatenate([view[p] @ kernel for p in parts])
    from scipy.signal import fftconvolve
    return fftconvolve(v[:, None], kernel[::-1], mode="valid", axes=0)[starts]


def _even_fits(v: np.ndarray, rows: np.ndarray, window: int, degrees: tuple[int, ...],
               derivatives: bool = True) -> dict:
    """As :func:`_uneven_fits`, for evenly spaced samples on [0, 1]: the weights depend only
    on a sample's place in its window, so one system serves every window; the centred fits
    are one filter (Savitzky-Golay), applied by :func:`_correlated`, and the fits at the
    ends are the first and last window's polynomials.  Without ``derivatives``, the centred
    fits' derivatives are left out (NaN): cross-validation needs only the values."""
    from numpy.polynomial import legendre
    n, top = len(v), max(degrees)
    columns = 3 if derivatives else 1
    s = np.linspace(-1.0, 1.0, window)
    V = legendre.legvander(s, top)                                     # (window, top + 1)
    half = 0.5 * (window - 1) / (n - 1)
    scale = np.array([1.0, 1.0 / half, 1.0 / half ** 2])
    start = np.clip(rows - window // 2, 0, n - window)
    place = rows - start
    ends = [(start == 0, 0), (start == n - window, n - window)]
    centred = ~(ends[0][0] | ends[1][0])
    gram = {d: V[:, :d + 1].T @ V[:, :d + 1] for d in degrees}
    places, which = np.unique(place, return_inverse=True)
    out = {}
    for d in degrees:
        coef = [np.linalg.solve(gram[d], V[:, :d + 1].T @ v[s0:s0 + window]) for _, s0 in ends]
        # the basis at each place a sample has, by blocks: a window may hold every sample
        norm2 = np.empty((len(places), 3))
        for block in np.array_split(np.arange(len(places)), max(1, len(places) * 24 // BLOCK)):
            at = legendre.legvander(s[places[block]], d)
            c = np.stack([at @ m[:d + 1, :d + 1] for m in _DERIVATIVES[top]], axis=2)
            norm2[block] = np.einsum("ptk,ptk->pk", c, np.linalg.solve(gram[d], c)) * scale ** 2
        fit = np.empty((len(rows), 3))
        for (mask, _), co in zip(ends, coef):
            fit[mask] = np.stack([legendre.legval(s[place[mask]], legendre.legder(co, k))
                                  for k in (0, 1, 2)], axis=1) * scale
        if centred.any():
            at = legendre.legvander(s[window // 2:window // 2 + 1], d)[0]
            centre = np.stack([at @ m[:d + 1, :d + 1] for m in _DERIVATIVES[top]], axis=1)
            kernel = (V[:, :d + 1] @ np.linalg.solve(gram[d], centre)) * scale   # (window, 3)
            fit[centred] = np.nan
            fit[centred, :columns] = _correlated(v, kernel[:, :columns], start[centred])
        out[d] = (fit, norm2[which])
    return out


def _fits(u: np.ndarray, v: np.ndarray, rows: np.ndarray, window: int, degrees: tuple[int, ...],
          even: bool, derivatives: bool = True) -> tuple[dict, np.ndarray]:
    """The local fits at ``rows``, by blocks of at most BLOCK numbers when uneven: see
    :func:`_uneven_fits`."""
    if even:
        return _even_fits(v, rows, window, degrees, derivatives), np.zeros(len(rows), bool)
    out = {d: (np.empty((len(rows), 3)), np.empty((len(rows), 3))) for d in degrees}
    bad = np.empty(len(rows), bool)
    for block in np.array_split(np.arange(len(rows)),
                                max(1, len(rows) * window * (DEGREE + 3) // BLOCK)):
        part, bad[block] = _uneven_fits(u, v, rows[block], window, degrees)
        for d in degrees:
            out[d][0][block], out[d][1][block] = part[d]
    return out, bad


def _refuse_gap(x: np.ndarray, u: np.ndarray, row: int, window: int) -> None:
    start = int(np.clip(row - window // 2, 0, len(x) - window))
    g = start + int(np.argmax(np.diff(u[start:start + window])))
    raise ModelError(f"x[{g + 1}]: expected samples spread over each local fit, got a gap from "
                     f"x[{g}] = {float(x[g])!r} to x[{g + 1}] = {float(x[g + 1])!r} that leaves "
                     f"the fit of {window} samples around x[{row}] too few samples on a side "
                     f"for a polynomial of degree {DEGREE + 2}; fill in the gap, or "
                     "differentiate the pieces on either side of it separately")


def _residuals(u: np.ndarray, v: np.ndarray, rows: np.ndarray, window: int,
               even: bool) -> tuple[float, float, np.ndarray]:
    """The residual sum of squares of the fits at ``rows``, the sum of their weights on
    their own sample (the trace of the hat matrix) and the mask of ill-conditioned fits."""
    fits, bad = _fits(u, v, rows, window, (DEGREE,), even, derivatives=False)
    fit, norm2 = fits[DEGREE]
    # a value's weight on its own sample is c^T G^-1 c, the squared norm of its weights
    return float(np.sum((v[rows] - fit[:, 0]) ** 2)), float(np.sum(norm2[:, 0])), bad


def _gcv_window(x: np.ndarray, u: np.ndarray, v: np.ndarray, even: bool) -> int:
    """The window that minimises the generalised cross-validation score of the smoothed
    curve, N RSS / (N - trace H)^2, summed over at most GCV_SAMPLES evenly spread samples;
    windows with an ill-conditioned fit among them are not candidates."""
    n = len(u)
    rows = np.unique(np.linspace(0, n - 1, min(n, GCV_SAMPLES)).round().astype(int))
    windows = np.unique(np.geomspace(MIN_WINDOW, n, GCV_WINDOWS).round().astype(int) | 1)
    windows = windows[windows <= n]
    scores, first_bad = [], None
    for w in windows:
        rss, trace, bad = _residuals(u, v, rows, int(w), even)
        if bad.any():
            first_bad = first_bad or (int(rows[np.argmax(bad)]), int(w))
            scores.append(np.inf)
        else:
            scores.append(len(rows) * rss / max(len(rows) - trace, 1e-300) ** 2)
    if not np.isfinite(np.min(scores)):
        _refuse_gap(x, u, *first_bad)
    return int(windows[int(np.argmin(scores))])


def _restored(a: np.ndarray, factor: float, exponent: int, what: str, hint: str) -> np.ndarray:
    """``a * factor * 2**exponent``, refused when it leaves float64's range."""
    with np.errstate(over="ignore", under="ignore"):
        out = np.ldexp(a * factor, exponent)
    if not np.all(np.isfinite(out)):
        raise ModelError(f"y: expected {what} within float64's range (up to "
                         f"{np.finfo(float).max:.3g}), got beyond it; {hint}")
    return out


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

    The fits are made on x and y shifted and scaled to order one, so the results do not
    depend on the units (1e-200 s or 1e200 s alike); the scales are applied at the end, and
    a result beyond float64's range is refused rather than returned as inf.  Evenly spaced
    samples share one filter, applied by FFT (10^5 samples take a second or two); unevenly
    spaced ones need a fit each, and are limited to ``MAX_UNEVEN`` (10,000).

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
        Fewer than 15 samples or more than ``MAX_SAMPLES`` (1,000,000; ``MAX_UNEVEN``,
        10,000, unevenly spaced), abscissae that do not increase, numbers that are not
        finite (the message names the index), a window out of range; steps too small for
        float64 to resolve beside |x|, a gap that leaves a local fit too few samples on a
        side, or derivatives, error bands or residuals beyond float64's range.

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
    # x and y shifted and scaled to [0, 1] and [-1, 1]: the fits are scale-free, and the
    # scales come back at the end, as powers of two apart (so nothing overflows before)
    u, span, e = _abscissae(x)
    y1, f = _binary_scaled(y)
    y0 = float(np.mean(y1))
    ys = float(np.max(np.abs(y1 - y0))) or 1.0
    v = (y1 - y0) / ys
    step = np.diff(u)
    even = bool(np.ptp(step) <= EVEN * np.mean(step))
    if not even and n > MAX_UNEVEN:
        raise ModelError(f"x: expected at most {MAX_UNEVEN:,} unevenly spaced samples, got "
                         f"{n:,}; resample the curve at a constant step (evenly spaced samples "
                         "have no limit) or cut it into pieces")
    gcv = _gcv_window(x, u, v, even) if window is None else int(window)
    used = int(window) if window is not None else max(MIN_WINDOW, int(round(UNDERSMOOTH * gcv)) | 1)
    rss, trace, bad = _residuals(u, v, np.arange(n), gcv, even)
    if bad.any():
        _refuse_gap(x, u, int(np.argmax(bad)), gcv)
    sigma = np.sqrt(rss / max(n - trace, 1.0))
    fits, bad = _fits(u, v, np.arange(n), used, (DEGREE, DEGREE + 2), even)
    if bad.any():
        _refuse_gap(x, u, int(np.argmax(bad)), used)
    fit, norm2 = fits[DEGREE]
    error = SPREAD * sigma * np.sqrt(norm2) + BIAS * np.abs(fit - fits[DEGREE + 2][0])
    larger = "express y in a larger unit"
    smaller = larger + " or x in a smaller one"
    smooth = _restored(y0 + ys * fit[:, 0], 1.0, f, "the smoothed curve", larger)
    residual = _restored((y1 - y0) - ys * fit[:, 0], 1.0, f, "the residuals", larger)
    noise = float(_restored(np.array(sigma), ys, f, "the noise", larger))
    rates = [_restored(a[:, k], ys / span ** k, f - k * e, f"{what}", smaller)
             for k, what in ((1, "the velocity dy/dx"), (1, "the velocity's error band"),
                             (2, "the acceleration d2y/dx2"), (2, "the acceleration's error band"))
             for a in [fit if "band" not in what else error]]
    return Derivatives(x=x.copy(), y=smooth, velocity=rates[0], acceleration=rates[2],
                       velocity_error=rates[1], acceleration_error=rates[3], noise=noise,
                       window=used, window_gcv=gcv, residual=residual)
