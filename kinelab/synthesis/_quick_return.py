"""Linkages for a rocker swing or a stroke and a time ratio: the crank-rocker, the offset
slider-crank and the slotted-lever quick returns (Norton, *Design of Machinery*, ch. 3;
Shigley and Uicker, *Theory of Machines and Mechanisms*, ch. 1 and 10).

A crank-driven output that reverses at two limit positions takes the crank angles
``pi + delta`` and ``pi - delta`` for its two strokes, so its time ratio is

    Q = (pi + delta) / (pi - delta),        delta = pi (Q - 1) / (Q + 1).

In a crank-rocker and a slider-crank the limit positions are where crank and coupler are
in line: the crank pivot O2 is ``b - a`` from the output pin in one (folded) and ``b + a``
in the other (extended), and the two lines O2-B1, O2-B2 meet at the angle ``delta`` (the
imbalance angle).  So O2 lies on the arc through B1 and B2 from which the chord B1B2 is
seen under ``delta`` (on the line B1B2 itself when Q = 1), and every point of that arc is
a design: the classical construction.  Its one free choice is where on the arc O2 is: the
angle at B1 between the chord B1 -> B2 and the line B1 -> O2 (the construction line that
Norton draws through B1 "at any convenient angle"), or, equivalently, one length.

Not every point of the arc works: the two limit positions must lie on the same assembly
branch, which for the four-bar means that B1 and B2 lie on the same side of the line
O2O4 (at a limit position the crank pin A is on the line O2B, so the side of B seen from
A is the side seen from O2).  The arcs where they do are the families searched here, by
a dense scan refined around its best sample (every value of the family is a closed form,
evaluated for a whole array of designs at once); each design is then built as a kinelab
model and measured by the kinematics engine: :func:`kinelab.kinematics.time_ratio` and
the output at its two dead centres.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from kinelab.errors import ModelError, SingularityError, describe
from kinelab.kinematics import analyze, time_ratio as engine_time_ratio, transmission_angle
from kinelab.mechanisms import Grashof, fourbar, grashof, slider_crank, slotted_link
from kinelab.mechanisms import whitworth as whitworth_mechanism
from kinelab.model import MAX_LENGTH, MIN_LENGTH, Mechanism, Units, is_real, length_problem
from kinelab.solvers import bisect, wrap_angle
from kinelab.synthesis._results import SolutionList

__all__ = ["CrankRocker", "QuickReturn", "crank_rocker", "crank_rockers", "offset_slider_crank",
           "slotted_lever", "whitworth", "imbalance_angle", "max_time_ratio"]

_SCAN = 4001        # samples of a family's dense scan (per arc)
_ZOOM = 41          # samples of each refinement around the best one
_LN_MIN = 1e-9      # |O2B1| / |B1B2| at the near end of a family's scan
_LN_MAX = 1e6       # ... and at most this at the far end (a crank a millionth of the rest)


def imbalance_angle(time_ratio: float) -> float:
    """delta = pi (Q - 1) / (Q + 1), rad: the angle between the two limit-position lines
    O2-B1 and O2-B2 of a crank-driven quick return of time ratio Q.

    Examples
    --------
    >>> round(float(np.degrees(kl.synthesis.imbalance_angle(1.25))), 12)   # Q = 1.25: 20 deg
    20.0
    """
    time_ratio = _ratio(time_ratio)
    return math.pi * ((time_ratio - 1.0) / (time_ratio + 1.0))     # the ratio first: no overflow


def max_time_ratio(swing: float, *, degrees: bool = False) -> float:
    """The time ratio that no crank-rocker of rocker swing ``swing`` reaches:
    (3 pi + swing) / (pi - swing).

    Up to it the imbalance angle delta is below (pi + swing) / 2, so that the arc of crank
    pivots still has a part where both limit positions are on one assembly branch; that
    part shrinks to the folded limit position B1 as Q approaches it (and so does the
    transmission angle, to 0).

    Examples
    --------
    >>> round(kl.synthesis.max_time_ratio(45, degrees=True), 12)     # (540 + 45) / (180 - 45)
    4.333333333333
    """
    psi = _swing(_radians(swing, degrees), _shown(degrees))
    return (3.0 * math.pi + psi) / (math.pi - psi)


# -- results -------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class CrankRocker:
    """A crank-rocker designed for a rocker swing and a time ratio, measured by the engine.

    Angles are in the unit of the call (radians, or degrees with ``degrees=True``).

    Attributes
    ----------
    ground, crank, coupler, rocker : float
        Link lengths O2O4, O2A, AB, O4B, m.
    swing : float
        The rocker's swing between its limit positions, measured by the engine.
    time_ratio : float
        Slow-stroke over fast-stroke crank angle, measured by the engine
        (:func:`kinelab.kinematics.time_ratio`).
    transmission_min : float
        The smallest transmission angle over the cycle (folded to (0, pi/2]), measured by
        the engine where it occurs: with the crank along the ground line, towards O4 and
        away from it.
    pivot_angle : float
        Where the construction puts the crank pivot: the angle at B1 (the rocker pin at the
        folded limit position) from the chord B1 -> B2 to the line B1 -> O2; positive when
        O2 is on O4's side of the chord.  NaN when Q = 1 (O2 is on the line B1B2).
    dead_centres : ndarray, shape (2,)
        The crank angles of the two limit positions (folded first), in [0, 2 pi) from the
        ground line O2 -> O4.
    model : Mechanism
        :func:`kinelab.mechanisms.fourbar` with these lengths (O2 at the origin, O4 at
        (ground, 0), the "open" branch; the "crossed" one is its mirror image and has
        the same swing and time ratio).
    grashof : Grashof
        Its class: always a crank-rocker.
    degrees : bool
        Whether the angles above are in degrees.
    """

    ground: float
    crank: float
    coupler: float
    rocker: float
    swing: float
    time_ratio: float
    transmission_min: float
    pivot_angle: float
    dead_centres: np.ndarray
    model: Mechanism
    grashof: Grashof
    degrees: bool = False

    @property
    def lengths(self) -> dict[str, float]:
        """``ground, crank, coupler, rocker``, m."""
        return {k: getattr(self, k) for k in ("ground", "crank", "coupler", "rocker")}

    def __repr__(self) -> str:
        unit = "deg" if self.degrees else "rad"
        L = ", ".join(f"{k}={v:.6g}" for k, v in self.lengths.items())
        return (f"CrankRocker({L} m, swing={self.swing:.6g} {unit}, time_ratio="
                f"{self.time_ratio:.6g}, transmission_min={self.transmission_min:.6g} {unit})")


@dataclass(frozen=True, eq=False)
class QuickReturn:
    """A quick-return mechanism designed for a time ratio, measured by the engine.

    Angles are in the unit of the call (radians, or degrees with ``degrees=True``).

    Attributes
    ----------
    kind : str
        "offset slider-crank", "slotted lever" or "whitworth".
    lengths : dict of str to float
        The catalogue constructor's lengths, m (``crank, rod, offset``; ``crank,
        distance``; ``crank, distance, lever, rod``).
    time_ratio : float
        Measured by the engine (:func:`kinelab.kinematics.time_ratio`).
    stroke : float or None
        The slider's (ram's) travel between its dead centres, measured by the engine, m.
    swing : float or None
        The slotted lever's swing between its limit positions, measured by the engine.
    transmission_min : float or None
        Slider-crank: the smallest angle between the rod and the normal to the slide over
        the cycle (90 deg minus the rod's largest inclination), measured by the engine.
    dead_centres : ndarray, shape (2,)
        Crank angles of the two dead centres, in [0, 2 pi).
    model : Mechanism
        The catalogue mechanism (:func:`kinelab.mechanisms.slider_crank`,
        :func:`~kinelab.mechanisms.slotted_link`, :func:`~kinelab.mechanisms.whitworth`).
    degrees : bool
    """

    kind: str
    lengths: dict
    time_ratio: float
    stroke: float | None
    swing: float | None
    transmission_min: float | None
    dead_centres: np.ndarray
    model: Mechanism
    degrees: bool = False

    def __repr__(self) -> str:
        L = ", ".join(f"{k}={v:.6g}" for k, v in self.lengths.items())
        return f"QuickReturn({self.kind}: {L} m, time_ratio={self.time_ratio:.6g})"


# -- checks of the arguments ----------------------------------------------------------------
def _len(u: Units, value: float) -> str:
    """A length (m) for a message, in the units of the call (a task file's)."""
    return f"{u.convert(value, 'm'):.6g} {u.length}"


def _ang(u: Units, value: float) -> str:
    """An angle (rad) for a message, in the units of the call."""
    return f"{u.convert(value, 'rad'):.6g} {u.angle}"


def _shown(degrees) -> Units:
    """The units of messages and results for ``degrees``."""
    return Units(angle="deg" if _flag("degrees", degrees) else "rad")


def _radians(value, degrees: bool):
    """An angle given by a caller, in rad (left as it is when it is not a number: the check
    that follows names it)."""
    return math.radians(value) if degrees and is_real(value) else value


def _length(name: str, value) -> float:
    if not is_real(value):
        raise ModelError(f"{name}: expected a length in m, got {describe(value)}")
    if why := length_problem(float(value)):
        raise ModelError(f"{name}: {why}, got {float(value):g} m")
    return float(value)


def _flag(name: str, value) -> bool:
    if not isinstance(value, bool):
        raise ModelError(f"{name}: expected true or false, got {describe(value)}")
    return value


def _swing(psi, u: Units) -> float:
    """The rocker's swing (rad), strictly between 0 and pi."""
    if not (is_real(psi) and 0.0 < psi < math.pi):
        got = _ang(u, float(psi)) if is_real(psi) else describe(psi)
        raise ModelError(f"swing: expected an angle between 0 and {_ang(u, math.pi)} (both "
                         f"excluded), got {got}; a rocker that swings half a turn or more has no "
                         "limit positions")
    return float(psi)


def _ratio(time_ratio, *, above_one: bool = False, below: float = math.inf,
           why: str = "") -> float:
    """A time ratio: at least 1 (more with ``above_one``) and less than ``below``; ``why``
    says what to do when it is too large."""
    ok = is_real(time_ratio) and (time_ratio > 1.0 if above_one else time_ratio >= 1.0)
    if not (ok and time_ratio < below):
        span = "more than 1" if above_one else "at least 1"
        if math.isfinite(below):
            span += f" and less than {below:.6g}"
        raise ModelError(f"time_ratio: expected the slow stroke's time over the fast one's, "
                         f"{span}, got {describe(time_ratio)}"
                         + (f"; {why}" if ok and why else ""))
    return float(time_ratio)


# -- one-parameter families, searched by scan and refinement --------------------------------
@dataclass(frozen=True)
class _Arc:
    """One arc of crank pivots: ``designs(t)`` for t in (lo, hi), vectorised."""

    lo: float
    hi: float
    designs: Callable[[np.ndarray], dict]


def _scan(arc: _Arc, n: int = _SCAN) -> tuple[np.ndarray, dict]:
    t = np.linspace(arc.lo, arc.hi, n + 2)[1:-1]
    return t, arc.designs(t)


def _refined_max(arc: _Arc, value: Callable[[dict], np.ndarray]) -> tuple[float, float]:
    """(t, value) at the largest ``value`` over the arc: a dense scan, then scans of
    ``_ZOOM`` samples around the best one, each over the two steps beside it, down to
    rounding.  Every refinement keeps the best sample so far, so the answer is never worse
    than the dense scan."""
    t, d = _scan(arc)
    v = np.where(d["feasible"], value(d), -np.inf)
    k = int(np.argmax(v))
    best_t, best_v = float(t[k]), float(v[k])
    step = t[1] - t[0]
    for _ in range(60):
        if step <= 1e-15 * max(1.0, abs(best_t)):
            break
        tt = np.linspace(max(best_t - step, arc.lo), min(best_t + step, arc.hi), _ZOOM)
        dd = arc.designs(tt)
        vv = np.where(dd["feasible"], value(dd), -np.inf)
        j = int(np.argmax(vv))
        if vv[j] >= best_v:
            best_t, best_v = float(tt[j]), float(vv[j])
        step = tt[1] - tt[0]
    return best_t, best_v


def _refined_range(arcs: list[_Arc], value: Callable[[dict], np.ndarray]) -> tuple[float, float]:
    """The smallest and largest ``value`` over the feasible designs of ``arcs``."""
    hi = max(_refined_max(a, value)[1] for a in arcs)
    lo = -max(_refined_max(a, lambda d: -value(d))[1] for a in arcs)
    return lo, hi


def _roots(arc: _Arc, value: Callable[[dict], np.ndarray], target: float) -> np.ndarray:
    """Parameters t where ``value`` crosses ``target`` between feasible samples of the scan,
    bisected to rounding."""
    t, d = _scan(arc)
    g = value(d) - target
    ok = d["feasible"]
    k = np.flatnonzero(ok[:-1] & ok[1:] & (np.sign(g[:-1]) * np.sign(g[1:]) <= 0)
                       & (g[:-1] != 0))
    exact = t[ok & (g == 0)]
    if k.size == 0:
        return exact
    s0 = np.sign(g[k])
    a, b = bisect(lambda x: np.sign(value(arc.designs(x)) - target) == s0, t[k], t[k + 1],
                  tol=1e-15)
    return np.unique(np.concatenate([exact, 0.5 * (a + b)]))


# -- crank-rocker ---------------------------------------------------------------------------
def _cross(u, v):
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def _fourbar_transmission_min(a, b, c, d):
    """Smallest folded transmission angle over a crank-rocker's cycle, rad: it is met with
    the crank along the ground line, where the crank pin is nearest O4 (d - a) or farthest
    from it (d + a), because the angle grows with that distance."""
    out = np.full(np.shape(a), np.pi / 2)
    for e in (d - a, d + a):
        cos_mu = np.clip((b * b + c * c - e * e) / (2.0 * b * c), -1.0, 1.0)
        mu = np.arccos(cos_mu)
        out = np.minimum(out, np.minimum(mu, np.pi - mu))
    return out


def _crank_rocker_arcs(psi: float, delta: float) -> list[_Arc]:
    """The feasible arcs of crank pivots for swing psi and imbalance angle delta, in the
    construction's frame: rocker 1, O4 at the origin, B1 = (sin psi/2, cos psi/2) the pin at
    the folded limit position, B2 its mirror image.  Parameter t = ln(|O2B1| / |B1B2|)."""
    s, h = math.sin(psi / 2), math.cos(psi / 2)
    B1, B2 = np.array([s, h]), np.array([-s, h])
    chord = 2.0 * s
    # |O2B1| = chord sin(phi + delta) / sin(delta) runs from 0 (phi = pi - delta) to
    # chord / (2 sin(delta/2)) (phi = (pi - delta)/2, where the crank vanishes)
    r1_top = chord / (2.0 * math.sin(delta / 2)) if delta > 0 else math.inf
    hi = math.log(min(r1_top / chord * (1.0 - 1e-12), _LN_MAX))
    lo = math.log(_LN_MIN)
    arcs = []
    # O2 on O4's side of the chord exists for delta < (pi + psi)/2, on the other side for
    # delta < (pi - psi)/2 (there the arc starts at B1 with both pins on one side of O2O4);
    # with Q = 1 both are the line B1B2 beyond B1
    for side, limit in ((1.0, (math.pi + psi) / 2), (-1.0, (math.pi - psi) / 2)):
        if delta >= limit or (side < 0 and delta == 0.0):
            continue

        def designs(t, side=side):
            r1 = chord * np.exp(t)
            phi = np.pi - delta - np.arcsin(np.clip(r1 * math.sin(delta) / chord, 0.0, 1.0))
            O2 = B1 + r1[:, None] * np.stack([-np.cos(phi), -side * np.sin(phi)], -1)
            r2 = np.hypot(O2[:, 0] - B2[0], O2[:, 1] - B2[1])
            # r2 - r1 from the law of cosines, without cancellation when r1 is large
            a = 0.5 * (chord * chord - 2.0 * r1 * chord * np.cos(phi)) / (r2 + r1)
            b = 0.5 * (r1 + r2)
            d = np.hypot(O2[:, 0], O2[:, 1])
            same = _cross(O2 - B1, -B1) * _cross(O2 - B2, -B2) > 0
            return dict(crank=a, coupler=b, rocker=np.ones_like(a), ground=d,
                        pivot=side * phi, feasible=same & (a > 0),
                        mu=_fourbar_transmission_min(a, b, 1.0, d))
        arcs.append(_Arc(lo, hi, designs))
    return arcs


def _pivot_arc_angles(arc: _Arc) -> tuple[float, float]:
    """The range of pivot angles of an arc's feasible designs (the arc starts feasible at
    B1 and ends where a limit position changes branch)."""
    t, d = _scan(arc)
    ok = np.flatnonzero(d["feasible"])
    last = ok[-1]
    if last + 1 < t.size:
        _, end = bisect(lambda x: arc.designs(x)["feasible"], t[last:last + 1],
                        t[last + 1:last + 2], tol=1e-15)
        edge = float(arc.designs(end)["pivot"][0])
    else:
        edge = float(arc.designs(np.array([arc.hi]))["pivot"][0])
    start = float(arc.designs(np.array([arc.lo]))["pivot"][0])
    return min(start, edge), max(start, edge)


def _measured_crank_rocker(d: dict, ground: float, degrees: bool, choice: str,
                           u: Units) -> CrankRocker:
    """Build the design ``d`` (one sample of a family) at the given ground length and measure
    it with the engine; ``choice`` names the argument that picked it, for the message when
    the design all but locks."""
    k = ground / float(d["ground"][0])
    L = {n: float(d[n][0]) * k for n in ("ground", "crank", "coupler", "rocker")}
    L["ground"] = float(ground)
    model = _built("crank-rocker", fourbar, L, "ground", u, "swing or time ratio")
    try:
        tr = engine_time_ratio(model, "rocker")
    except SingularityError:
        mu = math.degrees(float(d["mu"][0]))
        raise ModelError(f"{choice}: the crank-rocker it gives has a smallest transmission angle "
                         f"of {mu:.3g} deg: it all but locks at a dead centre, where the engine "
                         "finds it singular and cannot measure it; lower the time ratio, widen "
                         "the swing" + ("" if choice == "time_ratio" else f" or change the {choice}"))
    # the folded limit position first: there the crank points away from B
    sol = analyze(model, q=tr.dead_centres)
    A, B = sol.position("A"), sol.position("B")
    folded = np.einsum("ij,ij->i", A, B - A) < 0
    dc = tr.dead_centres if folded[0] or not folded[1] else tr.dead_centres[::-1]
    th = sol.angle("rocker")
    swing = abs(wrap_angle(th[1] - th[0]))
    mu = float(np.min(transmission_angle(analyze(model, q=np.array([0.0, np.pi])))))
    conv = np.degrees if degrees else (lambda v: v)
    dc = np.array(conv(dc), float)
    dc.setflags(write=False)
    pivot = float(d["pivot"][0]) if np.isfinite(d["pivot"][0]) else math.nan
    return CrankRocker(**L, swing=float(conv(swing)), time_ratio=tr.ratio,
                       transmission_min=float(conv(mu)), pivot_angle=float(conv(pivot)),
                       dead_centres=dc, model=model, grashof=grashof(**L), degrees=degrees)


def _pick(arc: _Arc, t: float) -> dict:
    return arc.designs(np.array([t]))


def _crank_rocker_task(ground, psi, time_ratio, u: Units) -> tuple[float, float, list[_Arc]]:
    ground = _length("ground", ground)
    psi = _swing(psi, u)
    Q = _ratio(time_ratio, below=max_time_ratio(psi),
               why=f"no crank-rocker with a swing of {_ang(u, psi)} reaches "
               "(3 pi + swing) / (pi - swing): lower the time ratio or widen the swing")
    delta = imbalance_angle(Q)
    arcs = _crank_rocker_arcs(psi, delta)
    if Q == 1.0:
        # no quick return: O2 is on the line B1B2, so no pivot angle places it
        arcs = [_Arc(a.lo, a.hi, lambda t, f=a.designs: {**f(t), "pivot": np.full(t.shape, np.nan)})
                for a in arcs]
    return ground, Q, arcs


def crank_rockers(ground: float, swing: float, time_ratio: float, crank: float, *,
                  degrees: bool = False) -> SolutionList:
    """Every crank-rocker with a given crank for a rocker swing and a time ratio.

    The crank is one length of the one-parameter family of the classical construction
    (see :mod:`kinelab.synthesis._quick_return`), so it can be met at several points of it:
    each is a design.

    Parameters
    ----------
    ground : float
        O2O4, m.
    swing : float
        The rocker's swing between its limit positions, rad (degrees with ``degrees=True``),
        strictly between 0 and pi.
    time_ratio : float
        Slow-stroke time over fast-stroke time, at least 1.
    crank : float
        O2A, m.
    degrees : bool
        Angles in (and out) in degrees.

    Returns
    -------
    SolutionList of CrankRocker
        Best (largest ``transmission_min``) first.

    Raises
    ------
    ModelError
        A bad swing or time ratio (the message gives the feasible range), or a crank that
        no design has (the message gives the range of cranks that do).

    Examples
    --------
    >>> designs = kl.synthesis.crank_rockers(1.0, 45, 1.25, crank=0.3, degrees=True)
    >>> [round(d.crank, 12) for d in designs]
    [0.3, 0.3]
    >>> all(abs(d.time_ratio - 1.25) < 1e-9 and abs(d.swing - 45) < 1e-9 for d in designs)
    True
    """
    u = _shown(degrees)
    return _crank_rockers(ground, _radians(swing, degrees), time_ratio, crank, degrees, u)


def _crank_rockers(ground, psi, time_ratio, crank, degrees: bool, u: Units) -> SolutionList:
    """:func:`crank_rockers` with the swing in rad; results in degrees with ``degrees``,
    messages in ``u``."""
    ground, Q, arcs = _crank_rocker_task(ground, psi, time_ratio, u)
    crank = _length("crank", crank)
    rho = crank / ground

    def ratio(d):
        return d["crank"] / d["ground"]
    found = [(arc, t) for arc in arcs for t in _roots(arc, ratio, rho)]
    if not found:
        lo, hi = _refined_range(arcs, ratio)
        raise ModelError(f"crank: expected a crank between {_len(u, lo * ground)} and "
                         f"{_len(u, hi * ground)} (both excluded) for ground {_len(u, ground)}, "
                         f"swing {_ang(u, psi)} and time ratio {Q:g}, got {_len(u, crank)}; no "
                         "crank-rocker of this family has it")
    designs = [_measured_crank_rocker(_pick(arc, t), ground, degrees, "crank", u)
               for arc, t in found]
    designs.sort(key=lambda s: -s.transmission_min)
    return SolutionList(designs)


def crank_rocker(ground: float, swing: float, time_ratio: float, *, crank: float | None = None,
                 pivot_angle: float | None = None, degrees: bool = False) -> CrankRocker:
    """A crank-rocker whose rocker swings ``swing`` with time ratio ``time_ratio``.

    The classical construction through the two limit positions (Norton, *Design of
    Machinery*, §3.5; Shigley and Uicker, ch. 10): the rocker pin's limit positions B1
    (crank and coupler folded) and B2 (extended) are ``swing`` apart on the rocker's circle;
    the crank pivot O2 sees the chord B1B2 under the imbalance angle
    ``delta = pi (Q - 1)/(Q + 1)``; then ``O2B2 - O2B1 = 2 crank`` and ``O2B2 + O2B1 =
    2 coupler``.  One choice is free: the crank, or the pivot angle that places O2 on its
    arc; left open, it is made to **maximise the smallest transmission angle** over the
    cycle.  That optimum is found over the whole family by a dense scan (4001 designs on each
    arc of crank pivots) refined around its best sample down to rounding; the smallest
    transmission angle of a crank-rocker is met with the crank along the ground line, so
    each design's value is exact.

    Parameters
    ----------
    ground : float
        O2O4, m: it fixes the size (the construction is scale-free).
    swing : float
        The rocker's swing, rad (degrees with ``degrees=True``), strictly between 0 and pi.
    time_ratio : float
        Q, the slow stroke's time over the fast one's: from 1 up to (not including)
        :func:`max_time_ratio` of the swing.
    crank : float, optional
        O2A, m.  Several designs may have it: this returns the one with the largest
        ``transmission_min`` (:func:`crank_rockers` returns them all).
    pivot_angle : float, optional
        The angle at B1 from the chord B1 -> B2 to the construction line B1 -> O2 (rad, or
        degrees), positive when O2 is on the rocker pivot's side of the chord.  Not with
        Q = 1 (O2 is then on the line B1B2).
    degrees : bool
        Angles in (and out) in degrees.

    Returns
    -------
    CrankRocker
        With ``ground, crank, coupler, rocker``, ``transmission_min``, the engine's
        ``swing`` and ``time_ratio`` (equal to the request to 1e-9) and the ``model``.

    Raises
    ------
    ModelError
        A swing outside (0, pi), a time ratio below 1 or at or above
        :func:`max_time_ratio`, both ``crank`` and ``pivot_angle``, a crank or pivot angle
        outside its feasible range (which the message gives), or Q = 1 with no free
        choice: the transmission angle then keeps growing as the crank shrinks, towards
        90 deg - swing/2, and no design is best.

    Examples
    --------
    A rocker swing of 45 deg with a time ratio of 1.25:

    >>> cr = kl.synthesis.crank_rocker(ground=1.0, swing=45, time_ratio=1.25, degrees=True)
    >>> round(cr.swing, 9), round(cr.time_ratio, 9)          # measured by the engine
    (45.0, 1.25)
    >>> round(cr.transmission_min, 3), cr.grashof.kind
    (41.813, 'crank-rocker')
    >>> {k: round(v, 4) for k, v in cr.lengths.items()}
    {'ground': 1.0, 'crank': 0.3457, 'coupler': 0.8336, 'rocker': 0.9666}
    """
    u = _shown(degrees)
    return _crank_rocker(ground, _radians(swing, degrees), time_ratio, crank,
                         _radians(pivot_angle, degrees), degrees, u)


def _crank_rocker(ground, psi, time_ratio, crank, pivot_angle, degrees: bool,
                  u: Units) -> CrankRocker:
    """:func:`crank_rocker` with the angles in rad; results in degrees with ``degrees``,
    messages in ``u``."""
    if crank is not None and pivot_angle is not None:
        raise ModelError("crank, pivot_angle: give at most one free choice, got both; the "
                         "other follows from the construction")
    if crank is not None:
        return _crank_rockers(ground, psi, time_ratio, crank, degrees, u)[0]
    ground, Q, arcs = _crank_rocker_task(ground, psi, time_ratio, u)
    if pivot_angle is not None:
        return _by_pivot_angle(ground, psi, Q, arcs, pivot_angle, degrees, u)
    if Q == 1.0:
        raise ModelError("crank: with time_ratio = 1 the smallest transmission angle keeps "
                         "growing as the crank shrinks (towards 90 deg - swing/2) and no design "
                         "is best; give the crank")
    best = [(arc, *_refined_max(arc, lambda d: d["mu"])) for arc in arcs]
    arc, t, _ = max(best, key=lambda b: b[2])
    return _measured_crank_rocker(_pick(arc, t), ground, degrees, "time_ratio", u)


def _by_pivot_angle(ground, psi, Q, arcs, phi, degrees: bool, u: Units) -> CrankRocker:
    if Q == 1.0:
        raise ModelError("pivot_angle: with time_ratio = 1 the crank pivot is on the line "
                         "B1B2 in every design, so no angle places it; give the crank instead")
    if not is_real(phi):
        raise ModelError(f"pivot_angle: expected an angle, got {describe(phi)}")
    spans = [_pivot_arc_angles(a) for a in arcs]
    for arc, (lo, hi) in zip(arcs, spans):
        if lo < phi < hi:
            t = _roots(arc, lambda d: d["pivot"], phi)
            if t.size:
                return _measured_crank_rocker(_pick(arc, float(t[0])), ground, degrees,
                                              "pivot_angle", u)
    ranges = " or ".join(f"({u.convert(lo, 'rad'):.6g}, {u.convert(hi, 'rad'):.6g})"
                         for lo, hi in spans)
    raise ModelError(f"pivot_angle: expected an angle in {ranges} {u.angle} for swing "
                     f"{_ang(u, psi)} and time ratio {Q:g}, got {_ang(u, phi)}; elsewhere the "
                     "two limit positions are on different assembly branches")


# -- offset slider-crank --------------------------------------------------------------------
def _slider_crank_arc(delta: float) -> _Arc:
    """Stroke 1, B1 = (0, 0) (folded), B2 = (1, 0), O2 above the slide's left end at the angle
    phi in (pi/2, pi - delta) from the chord; parameter t = phi.  The limit positions are on
    one branch when O2's foot on the slide is outside B1B2, that is phi > pi/2."""
    def designs(phi):
        r1 = np.sin(phi + delta) / math.sin(delta)
        O2 = r1[:, None] * np.stack([np.cos(phi), np.sin(phi)], -1)
        r2 = np.hypot(O2[:, 0] - 1.0, O2[:, 1])
        r, l, e = 0.5 * (r2 - r1), 0.5 * (r2 + r1), O2[:, 1]
        mu = np.pi / 2 - np.arcsin(np.clip((e + r) / l, -1.0, 1.0))
        return dict(crank=r, rod=l, offset=e, stroke=np.ones_like(r), mu=mu,
                    feasible=(r > 0) & (e >= 0) & (e + r < l))
    return _Arc(math.pi / 2, math.pi - delta, designs)


_CALLED = {"whitworth": "Whitworth quick return"}     # a kind as a sentence names it


def _built(kind: str, make: Callable[..., Mechanism], lengths: dict, size: str, u: Units,
           others: str = "") -> Mechanism:
    """The catalogue model of a design's lengths.  The user gave a task, not these lengths:
    a design beyond the sizes kinelab computes with is refused in the task's terms, naming
    ``size``, the argument that sets the design's scale (and ``others`` that shape it)."""
    try:
        return make(**lengths)
    except ModelError as exc:
        shown = ", ".join(f"{k} {_len(u, v)}" for k, v in lengths.items())
        raise ModelError(f"{size}: the {_CALLED.get(kind, kind)} it gives ({shown}) lies outside "
                         f"the sizes kinelab computes with (lengths from {_len(u, MIN_LENGTH)} to "
                         f"{_len(u, MAX_LENGTH)}, every point within {_len(u, MAX_LENGTH)} of "
                         f"the origin); give the task in other units, or another {size}"
                         + (f" or {others}" if others else "")) from exc


def _measured(kind: str, model: Mechanism, lengths: dict, output: str, slide: bool,
              degrees: bool, rod: bool = False, remedy: str = "lower the time ratio"
              ) -> QuickReturn:
    """Measure a quick return with the engine: its time ratio and dead centres, the stroke
    (``slide``) or swing of ``output`` between them and, with ``rod``, the smallest angle
    between the rod and the normal to the slide (met with the crank at right angles to
    the slide, where the rod leans most).  ``remedy``: what the task's author is told to
    change when the design locks at a dead centre on its turn."""
    try:
        tr = engine_time_ratio(model, output)
    except SingularityError as exc:
        raise ModelError(f"time_ratio: the {_CALLED.get(kind, kind)} it gives all but locks at a "
                         "dead centre on its turn, where the engine finds it singular and cannot "
                         f"measure its time ratio; {remedy}") from exc
    sol = analyze(model, q=tr.dead_centres)
    conv = np.degrees if degrees else (lambda v: v)
    if slide:
        x = sol.slide(output)
        stroke, swing = float(abs(x[1] - x[0])), None
    else:
        th = sol.angle(output)
        stroke, swing = None, float(conv(abs(wrap_angle(th[1] - th[0]))))
    mu = None
    if rod:
        rod = analyze(model, q=np.array([np.pi / 2, -np.pi / 2])).angle("rod")
        tilt = np.abs(wrap_angle(rod))
        mu = float(conv(np.pi / 2 - np.max(np.minimum(tilt, np.pi - tilt))))
    dc = np.array(conv(tr.dead_centres), float)
    dc.setflags(write=False)
    return QuickReturn(kind=kind, lengths=lengths, time_ratio=tr.ratio, stroke=stroke,
                       swing=swing, transmission_min=mu, dead_centres=dc, model=model,
                       degrees=degrees)


def offset_slider_crank(stroke: float, time_ratio: float, *, rod: float | None = None,
                        degrees: bool = False) -> QuickReturn:
    """An offset slider-crank with a given stroke and time ratio.

    The construction of the crank-rocker with the rocker's circle replaced by the slide
    line: the wrist pin's dead centres B1 (folded) and B2 (extended) are ``stroke`` apart,
    and the crank pivot O2 sees them under the imbalance angle delta.  O2 must be beyond
    B1 (its foot on the slide outside B1B2), so delta < 90 deg: Q < 3.  The rod is the free
    choice; left open, it is the one that maximises the smallest transmission angle (the
    angle between the rod and the normal to the slide, 90 deg minus the rod's largest
    inclination asin((offset + crank) / rod)).

    Parameters
    ----------
    stroke : float
        The slider's travel, m.
    time_ratio : float
        Q, from 1 to 3 (excluded); with Q = 1 the slider-crank is in line (offset 0,
        crank = stroke / 2) and the rod must be given.
    rod : float, optional
        AB, m.
    degrees : bool
        Angles out in degrees.

    Returns
    -------
    QuickReturn
        ``lengths`` = ``crank, rod, offset``; the model is
        :func:`kinelab.mechanisms.slider_crank` (the slide at y = offset above O2).

    Examples
    --------
    >>> sc = kl.synthesis.offset_slider_crank(stroke=0.1, time_ratio=1.4, degrees=True)
    >>> round(sc.stroke, 12), round(sc.time_ratio, 9)
    (0.1, 1.4)
    >>> {k: round(v, 5) for k, v in sc.lengths.items()}, round(sc.transmission_min, 3)
    ({'crank': 0.0455, 'rod': 0.09214, 'offset': 0.0321}, 32.632)
    """
    return _offset_slider_crank(stroke, time_ratio, rod, degrees, _shown(degrees))


def _offset_slider_crank(stroke, time_ratio, rod, degrees: bool, u: Units) -> QuickReturn:
    """:func:`offset_slider_crank`, messages in ``u``."""
    S = _length("stroke", stroke)
    Q = _ratio(time_ratio, below=3.0, why="an offset slider-crank's limit-position lines meet "
               "at less than 90 deg, so its time ratio stays below 3: use a slotted lever "
               "(slotted_lever, whitworth)")
    if rod is not None:
        rod = _length("rod", rod)
    if Q == 1.0:
        if rod is None:
            raise ModelError("rod: with time_ratio = 1 the slider-crank is in line and its "
                             "transmission angle keeps growing with the rod, so no design is "
                             "best; give the rod")
        if not rod > S / 2:
            raise ModelError(f"rod: expected more than half the stroke ({_len(u, S / 2)}), got "
                             f"{_len(u, rod)}")
        lengths = dict(crank=S / 2, rod=rod, offset=0.0)
    else:
        arc = _slider_crank_arc(imbalance_angle(Q))
        if rod is None:
            t, _ = _refined_max(arc, lambda d: d["mu"])
        else:
            roots = _roots(arc, lambda d: d["rod"] * S, rod)
            if roots.size == 0:
                lo, hi = _refined_range([arc], lambda d: d["rod"] * S)
                raise ModelError(f"rod: expected a rod between {_len(u, lo)} and {_len(u, hi)} "
                                 f"(both excluded) for stroke {_len(u, S)} and time ratio {Q:g}, "
                                 f"got {_len(u, rod)}")
            t = max(roots, key=lambda x: float(_pick(arc, x)["mu"][0]))
        d = _pick(arc, t)
        lengths = {k: float(d[k][0]) * S for k in ("crank", "rod", "offset")}
    reach = lengths["crank"] + lengths["rod"] + abs(lengths["offset"])
    if reach > MAX_LENGTH:
        raise ModelError(f"rod: the design's wrist pin goes {_len(u, reach)} from the crank's "
                         f"pivot, beyond the {_len(u, MAX_LENGTH)} a model holds; give a shorter "
                         "rod or stroke")
    model = _built("offset slider-crank", slider_crank, lengths, "stroke", u)
    return _measured("offset slider-crank", model, lengths, "slide", True, degrees, rod=True,
                     remedy="lower the time ratio" + (" or lengthen the rod" if rod else ""))


# -- slotted levers -------------------------------------------------------------------------
def slotted_lever(time_ratio: float, distance: float, *, degrees: bool = False) -> QuickReturn:
    """A crank and oscillating slotted lever (the crank-shaper quick return) for a time ratio.

    The lever's limit positions are tangent to the crank circle, where the crank is at
    right angles to the lever: the crank turns ``2 acos(crank/distance)`` for the fast
    stroke, so ``crank = distance cos(pi / (Q + 1))``, and the lever swings
    ``pi (Q - 1)/(Q + 1)``.

    Parameters
    ----------
    time_ratio : float
        Q > 1.
    distance : float
        O2O4, the distance between the crank's and the lever's pivots, m.
    degrees : bool
        Angles out in degrees.

    Returns
    -------
    QuickReturn
        ``lengths`` = ``crank, distance``; the model is
        :func:`kinelab.mechanisms.slotted_link`; ``swing`` is the lever's.

    Examples
    --------
    >>> sl = kl.synthesis.slotted_lever(2.0, distance=0.5, degrees=True)
    >>> round(sl.lengths["crank"], 12), round(sl.time_ratio, 9), round(sl.swing, 9)
    (0.25, 2.0, 60.0)
    """
    degrees = _flag("degrees", degrees)
    Q = _ratio(time_ratio, above_one=True)
    C = _length("distance", distance)
    R = C * math.cos(math.pi / (Q + 1.0))
    if why := length_problem(R):
        raise ModelError(f"time_ratio: the crank would be {R:.3g} m ({why}); raise the time "
                         "ratio or the distance")
    lengths = dict(crank=R, distance=C)
    model = _built("slotted lever", slotted_link, lengths, "distance", _shown(degrees))
    return _measured("slotted lever", model, lengths, "lever", False, degrees)


def whitworth(time_ratio: float, distance: float, stroke: float, *, rod: float | None = None,
              degrees: bool = False) -> QuickReturn:
    """A Whitworth quick return (crank and fully turning slotted lever driving a ram) for a
    time ratio and a ram stroke.

    The ram reverses when the lever end crosses the ram's line, that is when the crank pin
    does: ``sin q = -distance/crank``, so the strokes take ``pi +- 2 asin(distance/crank)``
    of the crank's turn and ``crank = distance / sin(pi (Q - 1) / (2 (Q + 1)))``; the
    lever's radius is half the stroke (the ram's line passes through the lever pivot).

    Parameters
    ----------
    time_ratio : float
        Q > 1.
    distance : float
        O4O2, m (less than the crank, which this gives).
    stroke : float
        The ram's travel, m.
    rod : float, optional
        The rod from the lever end to the ram, m; default the stroke.
    degrees : bool
        Angles out in degrees.

    Returns
    -------
    QuickReturn
        ``lengths`` = ``crank, distance, lever, rod``; the model is
        :func:`kinelab.mechanisms.whitworth`.

    Examples
    --------
    >>> w = kl.synthesis.whitworth(2.0, distance=0.05, stroke=0.3)
    >>> round(w.lengths["crank"], 12), round(w.time_ratio, 9), round(w.stroke, 12)
    (0.1, 2.0, 0.3)
    """
    return _whitworth(time_ratio, distance, stroke, rod, degrees, _shown(degrees))


def _whitworth(time_ratio, distance, stroke, rod, degrees: bool, u: Units) -> QuickReturn:
    """:func:`whitworth`, messages in ``u``."""
    Q = _ratio(time_ratio, above_one=True)
    d = _length("distance", distance)
    S = _length("stroke", stroke)
    rod = S if rod is None else _length("rod", rod)
    if not rod > S / 2:
        raise ModelError(f"rod: expected more than half the stroke ({_len(u, S / 2)}) so that it "
                         f"reaches the ram's line, got {_len(u, rod)}")
    R = d / math.sin(0.5 * imbalance_angle(Q))
    if why := length_problem(R):
        raise ModelError(f"time_ratio: the crank would be {R:.3g} m ({why}); raise the time "
                         "ratio or shorten the distance")
    lengths = dict(crank=R, distance=d, lever=S / 2, rod=rod)
    model = _built("whitworth", whitworth_mechanism, lengths, "stroke", u)
    return _measured("whitworth", model, lengths, "ram_slide", True, degrees,
                     remedy="lengthen the rod or lower the time ratio")
