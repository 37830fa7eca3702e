"""Metrics of a chunk of designs, from their kinematics at the samples (arrays (D, S)).

Each metric is computed for all the designs of a chunk at once; where a sampled value is
not exact enough (the dead centres of the output, the ends of the reachable range) it is
refined by evaluating the designs again at the inputs that matter, still all at once.
"""
from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from kinelab.errors import ModelError, describe, expected_one_of
from kinelab.mechanisms import grashof_kinds
from kinelab.model import angle_problem, is_real, rate_problem, real_array
from kinelab.solvers import wrap_angle
from kinelab.sweep._batch import Batch
from kinelab.sweep._designs import DesignTable, real_values
from kinelab.sweep._family import Designs, Family, family as make_family

__all__ = ["METRICS", "metric_columns", "check_metrics", "evaluate_chunk", "descriptors",
           "DEFAULT_HARMONICS"]

MAX_SAMPLES = 1_000_000      # samples per turn, at most: as a model file's sweep (kinelab.io)
METRICS = ("assembles", "reachable", "grashof", "transmission_min", "transmission_max",
           "time_ratio", "swing", "descriptors", "peak_torque")
DEFAULT_HARMONICS = 8
_BISECTIONS = 48          # halvings of a sample step (2 pi / S): far below 1e-12 rad
_ROOT_STEPS = 40          # Illinois steps on a dead centre: converges long before


def metric_columns(metrics, harmonics: int = DEFAULT_HARMONICS) -> list[str]:
    """The result columns of a checked list of metrics, in order."""
    cols = []
    for m in metrics:
        if m == "reachable":
            cols += ["reachable_from", "reachable_to"]
        elif m == "descriptors":
            cols += descriptor_names(harmonics)
        else:
            cols.append(m)
    return cols


def descriptor_names(harmonics: int) -> list[str]:
    return [f"fd{s}{k}" for k in range(1, harmonics + 1) for s in "+-"]


def check_metrics(fam: Family, metrics, full_turn: bool) -> dict[str, object]:
    """The metrics as name -> built-in name or user function; refuses unknown ones and those
    the family cannot give."""
    if isinstance(metrics, (str, bytes)) or callable(metrics):
        metrics = (metrics,)
    items = metrics.items() if isinstance(metrics, Mapping) else ((None, m) for m in metrics)
    out: dict[str, object] = {}
    for key, m in items:
        if callable(m):
            name = key if key is not None else getattr(m, "__name__", None)
            if not isinstance(name, str) or not name or name == "<lambda>":
                raise ModelError("metrics: a function needs a name: pass metrics as a mapping "
                                 "{'name': function}")
            out[name] = m
            continue
        if m not in METRICS:
            raise ModelError(f"metrics: {expected_one_of(m, METRICS)}, or a function of the "
                             "kinematics")
        need = {"grashof": (fam.grashof, "is defined for four-bars"),
                "transmission_min": (fam.transmission is not None,
                                     "needs the links of the transmission angle: "
                                     "kl.sweep.family(..., transmission=('coupler', 'rocker'))"),
                "time_ratio": (fam.output is not None and full_turn,
                               "needs the family's output (kl.sweep.family(..., output='rocker')) "
                               "and samples over a full turn (samples=72)"),
                "reachable": (full_turn, "needs samples over a full turn (samples=72)"),
                "descriptors": (fam.point is not None,
                                "needs the family's coupler point (the four-bar's columns "
                                "coupler_point_along and coupler_point_perpendicular, or "
                                "kl.sweep.family(..., point='P'))"),
                "peak_torque": (fam.has_masses, "needs a family with masses (a model file with "
                                "mass, center_of_mass and inertia on its moving links)")}
        need["transmission_max"] = need["transmission_min"]
        need["swing"] = need["time_ratio"]
        ok, why = need.get(m, (True, ""))
        if not ok:
            raise ModelError(f"metrics: {m!r} {why}; family {fam.name!r} cannot give it")
        out[key if key is not None else m] = m
    if not out:
        raise ModelError("metrics: expected at least one metric, got none")
    return out


def check_samples(samples):
    if isinstance(samples, (int, np.integer)) and not isinstance(samples, bool):
        if not 4 <= samples <= MAX_SAMPLES:
            raise ModelError(f"samples: expected at least 4 and at most {MAX_SAMPLES:,} samples per "
                             f"turn, got {describe(int(samples))}")
        return int(samples)
    a = real_array(samples) if not isinstance(samples, (str, bytes)) else None
    if a is None or a.ndim != 1 or not 1 <= a.size <= MAX_SAMPLES or not np.isfinite(a).all():
        raise ModelError(f"samples: expected a number of samples over a turn, or a 1-D array of "
                         f"at most {MAX_SAMPLES:,} finite input values (rad), got {describe(samples)}")
    why = angle_problem(float(np.abs(a).max()))
    if why:
        raise ModelError(f"samples: {why}, got {describe(samples)}")
    return a


def check_speed(speed) -> float:
    if isinstance(speed, np.ndarray) and speed.ndim == 0:
        speed = speed[()]
    if not is_real(speed):
        raise ModelError(f"speed: expected a finite input speed (rad/s), got {describe(speed)}")
    speed = float(speed)
    why = rate_problem(speed, "rad/s")
    if why:
        raise ModelError(f"speed: {why}, got {speed:g}")
    return speed


def check_harmonics(harmonics) -> int:
    if isinstance(harmonics, bool) or not isinstance(harmonics, (int, np.integer)) or harmonics < 1:
        raise ModelError(f"harmonics: expected a whole number >= 1, got {describe(harmonics)}")
    return int(harmonics)


def _input_samples(samples, D: int) -> np.ndarray:
    if isinstance(samples, int):
        return np.broadcast_to(np.linspace(0.0, 2 * math.pi, samples, endpoint=False), (D, samples))
    return np.broadcast_to(samples, (D, len(samples)))


def evaluate_chunk(fam: Family, columns: Mapping[str, np.ndarray], problems: list[str], *,
                   samples, metrics: Mapping[str, object], speed: float = 1.0,
                   harmonics: int = DEFAULT_HARMONICS) -> dict[str, np.ndarray]:
    """Every metric of one chunk of designs: the one function a local run and a Dask
    worker call, so their results are the same.  ``columns`` are the chunk's checked
    parameter columns (D,), ``problems`` its rows' reasons ('' for a good row).

    Its arguments are checked as :func:`~kinelab.sweep.run` checks them (a chunk's checks
    cost little beside its kinematics): a family or its name, columns of the family's
    parameters, one problem (text) a row, the samples, metrics, speed and harmonics."""
    fam = make_family(fam)
    if not isinstance(columns, Mapping):
        raise ModelError(f"columns: expected a mapping of parameter to values (D,), got "
                         f"{describe(columns)}")
    table = DesignTable(dict(columns), fam)
    if isinstance(problems, (str, bytes)) or not isinstance(problems, (list, tuple, np.ndarray)) \
            or len(problems) != table.size or not all(isinstance(p, str) for p in problems):
        raise ModelError(f"problems: expected one text a design ('' for a good one), {table.size:,} "
                         f"in all, got {describe(problems)}")
    problems = [given or found for given, found in zip(problems, table.problems)]
    columns = table.columns
    samples = check_samples(samples)
    metrics = check_metrics(fam, metrics, isinstance(samples, int))
    speed, harmonics = check_speed(speed), check_harmonics(harmonics)
    designs = fam.prepare(columns, problems)
    D = len(problems)
    q = _input_samples(samples, D)
    batch = designs.batch(q)
    bad = np.array([bool(p) for p in problems], bool)
    assembled = batch.assembled.all(axis=1) & ~bad
    out: dict[str, np.ndarray] = {}
    for name, m in metrics.items():
        if callable(m):
            value = np.asarray(m(batch))
            if value.shape != (D,):
                raise ModelError(f"metrics: {name!r} returned shape {value.shape}; expected one "
                                 f"value per design, ({D},)")
            out[name] = np.where(bad, np.nan, value) if value.dtype.kind == "f" else value
        elif m == "assembles":
            out[name] = assembled
        elif m == "reachable":
            lo, hi = _reachable(designs, batch, bad)
            out["reachable_from"], out["reachable_to"] = lo, hi
        elif m == "grashof":
            kinds = grashof_kinds(*(np.asarray(columns[p], float) for p in
                                    ("ground", "crank", "coupler", "rocker")))
            out[name] = np.where(bad, None, kinds).astype(object)
        elif m in ("transmission_min", "transmission_max"):
            if "_mu" not in out:
                out["_mu"] = batch.transmission_range(fam.transmission)
            value = out["_mu"][0 if m == "transmission_min" else 1]
            out[name] = np.where(assembled, value, np.nan)
        elif m in ("time_ratio", "swing"):
            if "_dead" not in out:
                out["_dead"] = _dead_centres(fam, designs, batch, assembled)
            out[name] = out["_dead"][m]
        elif m == "descriptors":
            fd = descriptors(batch.position(fam.point), harmonics)
            fd[~assembled] = np.nan
            out.update(zip(descriptor_names(harmonics), fd.T))
        elif m == "peak_torque":
            out[name] = np.where(bad, np.nan, designs.peak_torque(q, speed))
    out.pop("_dead", None)
    out.pop("_mu", None)
    out["_problems"] = np.array(problems, object)
    return out


def _reachable(designs: Designs, batch: Batch, bad: np.ndarray):
    """The longest run of inputs where each design assembles, its ends refined by bisection:
    (from, to), rad, with to - from = 2 pi for a full turn and NaN for none."""
    ok = batch.assembled & ~bad[:, None]
    D, S = ok.shape
    q = batch.q
    step = 2 * math.pi / S
    # the longest cyclic run of True: over two turns, the run ending at sample j is j minus
    # the last sample before it that does not assemble
    twice = np.concatenate([ok, ok], axis=1)
    j = np.arange(2 * S)
    last_gap = np.maximum.accumulate(np.where(twice, -1, j), axis=1)
    run = np.minimum(j - last_gap, S)
    end = np.argmax(run, axis=1)
    length = run[np.arange(D), end]
    first = end - length + 1
    lo = q[:, 0] + first * step
    hi = q[:, 0] + end * step
    full = length == S
    partial = (length > 0) & ~full
    if partial.any():
        sub = np.flatnonzero(partial)
        lo[sub] = _bisect_edge(designs, sub, lo[sub], lo[sub] - step)
        hi[sub] = _bisect_edge(designs, sub, hi[sub], hi[sub] + step)
    lo = np.where(length > 0, lo, np.nan)
    hi = np.where(full, lo + 2 * math.pi, np.where(length > 0, hi, np.nan))
    return lo, hi


def _bisect_edge(designs: Designs, rows, inside, outside):
    """Where assembly ends between ``inside`` (assembles) and ``outside`` (does not), per row."""
    a, b = inside.copy(), outside.copy()
    some = designs.take(rows)
    for _ in range(_BISECTIONS):
        mid = 0.5 * (a + b)
        ok = some.batch(mid[:, None]).assembled[:, 0]
        a = np.where(ok, mid, a)
        b = np.where(ok, b, mid)
    return a


def _dead_centres(fam: Family, designs: Designs, batch: Batch, assembled: np.ndarray):
    """Time ratio and swing of the output, from the inputs where its K changes sign.

    A design turning its input fully whose output reverses exactly twice has a time ratio
    (slow over fast stroke, >= 1) and a swing (the output's travel between the reversals);
    an output angle that never reverses turns fully (swing 2 pi, no time ratio)."""
    D, S = batch.shape
    K = batch.K(fam.output)
    valid = assembled & np.isfinite(K).all(axis=1) & ~batch.singular.any(axis=1)
    positive = K > 0
    flips = positive != np.roll(positive, -1, axis=1)        # between sample j and j + 1
    count = flips.sum(axis=1)
    ratio = np.full(D, np.nan)
    swing = np.full(D, np.nan)
    angle = not fam.is_slide(fam.output)
    turning = valid & (count == 0) & angle
    swing[turning] = 2 * math.pi
    two = np.flatnonzero(valid & (count == 2))
    if len(two):
        j = np.sort(np.argsort(~flips[two], axis=1, kind="stable")[:, :2], axis=1)   # (n, 2)
        step = 2 * math.pi / S
        qa = batch.q[two, 0][:, None] + j * step
        roots, values, undefined = _roots(fam, designs, two, qa, qa + step, K[two[:, None], j],
                                          K[two[:, None], (j + 1) % S])
        first = np.mod(roots[:, 1] - roots[:, 0], 2 * math.pi)
        slow, fast = np.maximum(first, 2 * math.pi - first), np.minimum(first, 2 * math.pi - first)
        ratio[two] = np.where(undefined, np.nan, slow / fast)
        diff = values[:, 1] - values[:, 0]
        swing[two] = np.where(undefined, np.nan, np.abs(wrap_angle(diff) if angle else diff))
    return {"time_ratio": ratio, "swing": swing}


def _roots(fam, designs, rows, a, b, fa, fb):
    """Zeros of the output's K between a and b (n, 2), where K has the signs fa and fb: Newton
    steps on K with its derivative L while they stay inside the bracket, else the Illinois
    variant of regula falsi; the output's value there; and whether K was not defined at
    some step (n,): a sign change of K through a pole, a singular configuration, where
    there is no time ratio."""
    x = _falsi(a, b, fa, fb, 0.5 * (a + b))
    value = np.full(a.shape, np.nan)
    side = np.zeros(a.shape)           # +1: the last step moved a, -1: it moved b
    undefined = np.zeros(len(rows), bool)
    some = designs.take(rows)
    for _ in range(_ROOT_STEPS):
        sub = some.batch(x)
        fx, slope = sub.K(fam.output), sub.L(fam.output)
        value = sub.value(fam.output)
        # no zero of K there: the steps go on with a finite stand-in
        lost = ~np.isfinite(fx) | sub.singular
        undefined |= lost.any(axis=1)
        fx = np.where(lost, fa, fx)
        move_a = np.sign(fx) == np.sign(fa)
        fb = np.where(move_a & (side > 0), 0.5 * fb, fb)        # Illinois: halve the end kept
        fa = np.where(~move_a & (side < 0), 0.5 * fa, fa)
        a, fa = np.where(move_a, x, a), np.where(move_a, fx, fa)
        b, fb = np.where(move_a, b, x), np.where(move_a, fb, fx)
        side = np.where(move_a, 1.0, -1.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = x - fx / slope
        inside = ~lost & (np.minimum(a, b) < newton) & (newton < np.maximum(a, b))
        x_new = np.where(inside, newton, _falsi(a, b, fa, fb, x))
        if np.all(np.abs(x_new - x) <= 1e-14 * (1 + np.abs(x))):
            break
        x = x_new
    return x, value, undefined


def _falsi(a, b, fa, fb, fallback):
    """The regula falsi point of brackets [a, b] with K = fa, fb at their ends."""
    denom = fb - fa
    return np.where(denom != 0, (a * fb - b * fa) / np.where(denom != 0, denom, 1.0), fallback)


def descriptors(points: np.ndarray, harmonics: int = DEFAULT_HARMONICS) -> np.ndarray:
    """Normalised Fourier descriptors of closed curves: the magnitudes of the harmonics
    +1, -1, +2, -2 ... of the curve traced at uniform speed along its length, as a complex
    function z = x + i y, divided by the norm of them all.  They do not change when the
    curve moves, turns or scales, nor (to the O(h^2) of resampling along the chords between
    samples h apart) when it starts elsewhere; tracing it backwards swaps +k and -k.

    Parameters
    ----------
    points : array_like, shape (D, S, 2) or (S, 2)
        Samples along each closed curve, in order (the last joins the first), m.
    harmonics : int

    Returns
    -------
    ndarray, shape (D, 2 * harmonics) or (2 * harmonics,)

    Examples
    --------
    >>> t = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    >>> ellipse = np.column_stack([3 * np.cos(t), np.sin(t)])
    >>> a = kl.sweep.descriptors(ellipse)
    >>> b = kl.sweep.descriptors(5.0 + 2 * ellipse[::-1] @ [[0, 1], [-1, 0]])   # moved, turned, reversed
    >>> bool(np.allclose(a[0::2], b[1::2], atol=1e-4))    # to the chords' O(h^2) from another start
    True
    """
    harmonics = check_harmonics(harmonics)
    P = real_values("points", points)
    single = P.ndim == 2
    if single:
        P = P[None]
    if P.ndim != 3 or P.shape[-1] != 2 or P.shape[1] < 2 * harmonics + 1:
        raise ModelError(f"points: expected shape (D, S, 2) with S >= {2 * harmonics + 1}, got "
                         f"{describe(P)}")
    D, S, _ = P.shape
    z, usable = resample_closed(P, S)
    c = np.fft.fft(z[..., 0] + 1j * z[..., 1], axis=1) / S
    k = np.arange(1, harmonics + 1)
    mags = np.abs(np.stack([c[:, k], c[:, -k]], axis=-1)).reshape(D, 2 * harmonics)
    norm = np.linalg.norm(mags, axis=1, keepdims=True)
    fd = np.where(usable[:, None] & (norm > 0), mags / np.where(norm > 0, norm, 1.0), np.nan)
    return fd[0] if single else fd


def resample_closed(P: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Closed curves (D, S, 2) resampled at n points evenly along their chords from their
    first sample, (D, n, 2); and which curves could be (finite, of non-zero length)."""
    D, S, _ = P.shape
    seg = np.hypot(*(np.roll(P, -1, axis=1) - P).transpose(2, 0, 1))       # (D, S)
    total = seg.sum(axis=1, keepdims=True)
    usable = np.isfinite(total[:, 0]) & (total[:, 0] > 0)
    total = np.where(usable[:, None], total, 1.0)
    seg = np.where(usable[:, None], seg, 1.0 / S)
    # arc length at each sample, as a fraction of the whole, then n points evenly along it
    s = np.concatenate([np.zeros((D, 1)), np.cumsum(seg, axis=1) / total], axis=1)   # (D, S+1)
    closed = np.concatenate([P, P[:, :1]], axis=1)
    rows = np.arange(D)[:, None]
    target = np.arange(n) / n
    # one searchsorted for all rows: each row's fractions shifted by its row number
    idx = np.searchsorted((s[:, 1:] + rows).ravel(), np.broadcast_to(target + rows, (D, n)).ravel(),
                          side="right")
    idx = np.clip(idx.reshape(D, n) - rows * S, 0, S - 1)
    s0, s1 = s[rows, idx], s[rows, idx + 1]
    w = np.where(s1 > s0, (target - s0) / np.where(s1 > s0, s1 - s0, 1.0), 0.0)[..., None]
    return closed[rows, idx] + w * (closed[rows, idx + 1] - closed[rows, idx]), usable
