"""The summary of a sweep: what a person reads at a glance, as data.

Ranges and extremes of the chosen outputs with the input where each occurs, singular and limit
positions, the Grashof class of a four-bar, the extreme transmission angles and the
quick-return time ratio where it applies.  Printing is the command line's business.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinelab import kinematics
from kinelab.errors import KinelabError, ModelError, check_choice, describe
from kinelab.kinematics import KinematicSolution
from kinelab.mechanisms import Grashof, grashof
from kinelab.model import Mechanism

__all__ = ["Summary", "Extreme", "Transmission", "QuickReturn", "summary", "default_outputs"]


@dataclass(frozen=True)
class Extreme:
    """Range of one quantity over the sweep, over its assembled, non-singular samples.

    ``unit`` is the SI unit of ``min`` and ``max`` (``"rad/s"``, ``"m/s^2"``: see
    :class:`kinelab.model.Units` to convert).  ``at_min`` and ``at_max`` are the input values
    (one per input, rad or m) where the minimum and maximum occur.  ``full_turn`` marks a
    link angle that turns through a whole turn (its minimum and maximum then mean nothing).
    """

    name: str
    unit: str
    min: float
    at_min: tuple[float, ...]
    max: float
    at_max: tuple[float, ...]
    full_turn: bool = False
    angle: bool = False


@dataclass(frozen=True)
class Transmission:
    """Extreme transmission angles (rad, in [0, pi/2]; 90 deg is ideal) of a pair of links,
    over the assembled, non-singular samples."""

    links: tuple[str, str]
    min: float
    at_min: tuple[float, ...]
    max: float
    at_max: tuple[float, ...]
    from_normal: bool = False    # a slider: measured from the normal to the slide


@dataclass(frozen=True)
class QuickReturn:
    """Quick-return time ratio of ``output`` (see :func:`kinelab.kinematics.time_ratio`)."""

    output: str
    ratio: float
    slow: float
    fast: float
    dead_centres: tuple[float, ...]


@dataclass(frozen=True)
class Summary:
    """A sweep at a glance (SI units: rad, m, s).

    Attributes
    ----------
    mechanism : str
    inputs : tuple of str
    input_units : tuple of str
        ``"rad"`` or ``"m"`` for each input.
    samples : int
    input_range : tuple of (float, float)
        Swept interval of each input.
    extremes : tuple of Extreme
    singular : tuple of tuple of float
        Input values of the singular positions met (det J = 0; one per run of samples).
    least_singularity : (float, tuple of float)
        The smallest distance from singularity met (a sine, 1 is far) and where.
    unassembled : int
        Samples where the loops do not close.
    reachable : tuple of (float, float), optional
        One input: the intervals where the mechanism assembles on its branch; their ends are
        the input's limit positions.  ``full_turn`` says whether it turns fully.
    full_turn : bool, optional
    grashof : Grashof, optional
        For a four-bar, with ``grashof_lengths`` (ground, crank, coupler, rocker), m.
    grashof_lengths : tuple of float
    transmission : tuple of Transmission
    quick_return : QuickReturn, optional
    change_points : tuple of ChangePoint
        Where two assembly modes of a dyad meet within the sweep, and which way it went on
        (see :func:`kinelab.kinematics.analyze`).
    """

    mechanism: str
    inputs: tuple[str, ...]
    input_units: tuple[str, ...]
    samples: int
    input_range: tuple[tuple[float, float], ...]
    extremes: tuple[Extreme, ...]
    singular: tuple[tuple[float, ...], ...]
    least_singularity: tuple[float, tuple[float, ...]]
    unassembled: int
    reachable: tuple[tuple[float, float], ...] | None
    full_turn: bool | None
    grashof: Grashof | None
    grashof_lengths: tuple[float, ...]
    transmission: tuple[Transmission, ...]
    quick_return: QuickReturn | None
    change_points: tuple = ()


def default_outputs(m: Mechanism) -> tuple[str, ...]:
    """What to report when a file does not say: moving links that no input drives directly
    (sliders excepted), every slide, and every point carried by one moving link only."""
    driven = set()
    for inp in m.inputs:
        if inp.joint is not None:
            driven.add(m.joint(inp.joint).links[1])
        elif inp.links is not None:
            driven.add(inp.links[1])
    ground = m.ground.name
    links = [link.name for link in m.links
             if not link.ground and link.name not in driven and len(link.points) >= 2]
    slides = [j.name for j in m.joints if j.type == "P"]
    points = [p for p in m.point_names
              if (c := m.links_carrying(p)) and len(c) == 1 and c[0] != ground]
    return tuple(links + slides + points)


def _rows(sol: KinematicSolution, i: int) -> tuple[float, ...]:
    return tuple(float(v) for v in sol.q[i])


def _noise(sol: KinematicSolution, unit: str) -> float:
    """Below this an extreme of a quantity in ``unit`` (SI) is rounding, not a value: 1e-9
    of the quantity's natural size (the mechanism's size for lengths, the inputs' rates for
    derivatives), so that a parallelogram's coupler angle reads 0, not 4e-13."""
    rate = float(np.max(np.abs(sol.qd))) if sol.N else 0.0
    accel = rate * rate + (float(np.max(np.abs(sol.qdd))) if sol.N else 0.0)
    size = kinematics.plan(sol.mechanism).scale if unit.startswith("m") else 1.0
    per = {"": 1.0, "s": rate, "s^2": accel}.get(unit.partition("/")[2], 1.0)
    return 1e-9 * size * per


def _extreme(sol, name, unit, values, *, angle=False) -> Extreme | None:
    # singular samples are left out: there the values are undefined or meaningless spikes
    # (but an angle there still says whether the link turns fully)
    v = np.asarray(values, float)
    placed = np.isfinite(v) & sol.assembled
    ok = placed & ~sol.singular
    if not ok.any():
        return None
    full = False
    if angle:
        # angles come wrapped to (-pi, pi]: follow them continuously along the sweep
        v = v.copy()
        v[placed] = np.unwrap(v[placed])
        full = np.ptp(v[placed]) >= 2 * math.pi - 1e-9
    v = np.where(ok, v, np.nan)
    if angle:
        shift = 2 * math.pi * np.round((0.5 * (np.nanmax(v) + np.nanmin(v))) / (2 * math.pi))
        v = v - shift
    # of values equal to rounding (a symmetric motion's twin extremes), the first
    tie = 1e-12 * float(np.nanmax(np.abs(v)))
    i_min = int(np.argmax(v <= np.nanmin(v) + tie))
    i_max = int(np.argmax(v >= np.nanmax(v) - tie))
    noise = _noise(sol, unit)

    def clean(x):
        return 0.0 if abs(x) < noise else float(x)
    return Extreme(name, unit, clean(v[i_min]), _rows(sol, i_min), clean(v[i_max]),
                   _rows(sol, i_max), full, angle)


def _extremes(sol: KinematicSolution, report) -> list[Extreme]:
    out = []
    for name in report:
        if name in sol.link_item:
            items = [(f"{name}.angle", "rad", sol.angle(name), True),
                     (f"{name}.omega", "rad/s", sol.omega(name), False),
                     (f"{name}.alpha", "rad/s^2", sol.alpha(name), False)]
        elif name in sol.slide_item:
            items = [(f"{name}.slide", "m", sol.slide(name), False),
                     (f"{name}.slide_velocity", "m/s", sol.slide_velocity(name), False),
                     (f"{name}.slide_acceleration", "m/s^2", sol.slide_acceleration(name), False)]
        else:
            p, v, a = sol.position(name), sol.velocity(name), sol.acceleration(name)
            items = [(f"{name}.x", "m", p[..., 0], False), (f"{name}.y", "m", p[..., 1], False),
                     (f"{name}.speed", "m/s", np.hypot(v[..., 0], v[..., 1]), False),
                     (f"{name}.acceleration", "m/s^2", np.hypot(a[..., 0], a[..., 1]), False)]
        for label, unit, values, is_angle in items:
            e = _extreme(sol, label, unit, np.reshape(values, -1), angle=is_angle)
            if e is not None:
                out.append(e)
    return out


def _runs(mask: np.ndarray) -> list[int]:
    """The middle sample of each run of True in ``mask``."""
    idx = np.flatnonzero(mask)
    if idx.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(idx) > 1)
    starts = np.concatenate([[idx[0]], idx[breaks + 1]])
    ends = np.concatenate([idx[breaks], [idx[-1]]])
    return [int((a + b) // 2) for a, b in zip(starts, ends)]


def _fourbar_lengths(m: Mechanism) -> tuple[float, float, float, float] | None:
    """(ground, crank, coupler, rocker) of a four-bar driven at a ground pivot, from the sketch."""
    if len(m.links) != 4 or len(m.joints) != 4 or len(m.inputs) != 1 or m.space != "planar":
        return None
    if any(j.type != "R" for j in m.joints) or m.inputs[0].joint is None:
        return None
    ground = m.ground.name
    j_in = m.joint(m.inputs[0].joint)
    if ground not in j_in.links:
        return None
    crank = j_in.links[1] if j_in.links[0] == ground else j_in.links[0]

    def other(link, joint):
        js = [j for j in m.joints_of(link) if j is not joint]
        return js[0] if len(js) == 1 else None
    j_a = other(crank, j_in)
    if j_a is None:
        return None
    coupler = next(n for n in j_a.links if n != crank)
    j_b = other(coupler, j_a)
    if j_b is None:
        return None
    rocker = next(n for n in j_b.links if n != coupler)
    j_d = other(rocker, j_b)
    if j_d is None or ground not in j_d.links:
        return None
    xy = {p.name: p.xy for p in m.points}
    O2, A, B, O4 = (xy[j.point] for j in (j_in, j_a, j_b, j_d))
    return (math.dist(O2, O4), math.dist(O2, A), math.dist(A, B), math.dist(O4, B))


def _is_slider(m: Mechanism, link: str) -> bool:
    return len(m.link(link).points) == 1 and any(j.type == "P" for j in m.joints_of(link))


def _default_pairs(m: Mechanism) -> list[tuple[str, str]]:
    """Pin-jointed dyads whose link directions run along their arms (and slider dyads)."""
    pairs = []
    for step in kinematics.plan(m).steps:
        if step.kind == "RRR" and len(step.points) == 3:
            b, c = step.links
            X, Y, Z = step.points
            if (set(m.link(b).points[:2]) == {X, Y} and set(m.link(c).points[:2]) == {Y, Z}):
                pairs.append((b, c))
        elif step.kind == "RRP" and len(step.points) == 2:
            b, c = step.links
            if set(m.link(b).points[:2]) == set(step.points) and _is_slider(m, c):
                pairs.append((b, c))
    return pairs


def _transmission_values(sol: KinematicSolution, pair: tuple[str, str]) -> np.ndarray:
    """Transmission angle of a pair, (N,) rad in [0, pi/2]; for a slider, the rod's angle
    from the normal to the slide (90 deg when it pushes straight along the slide)."""
    mu = np.reshape(kinematics.transmission_angle(sol, tuple(pair)), -1)
    m = sol.mechanism
    return 0.5 * math.pi - mu if any(_is_slider(m, n) for n in pair) else mu


def _transmission(sol: KinematicSolution, pairs) -> list[Transmission]:
    out = []
    for a, b in pairs:
        e = _extreme(sol, f"{a}-{b}", "rad", _transmission_values(sol, (a, b)))
        if e is not None:
            slider = any(_is_slider(sol.mechanism, n) for n in (a, b))
            out.append(Transmission((a, b), e.min, e.at_min, e.max, e.at_max, slider))
    return out


def _quick_return(sol: KinematicSolution, output: str | None, full_turn: bool | None) -> QuickReturn | None:
    m = sol.mechanism
    if not full_turn or len(m.inputs) != 1:
        return None
    candidates = [output] if output else (
        [j.name for j in m.joints if j.type == "P"][-1:] or
        [n for n in kinematics.plan(m).steps[-1].links if not _is_slider(m, n)][-1:])
    for name in candidates:
        try:
            tr = kinematics.time_ratio(m, name)
        except KinelabError:
            continue
        return QuickReturn(name, float(tr.ratio), float(tr.slow), float(tr.fast),
                           tuple(float(v) for v in tr.dead_centres))
    return None


def summary(sol: KinematicSolution, *, report: tuple[str, ...] | None = None,
            transmission: tuple[tuple[str, str], ...] | None = None,
            time_ratio: str | None = None) -> Summary:
    """Summarise a sweep for people: ranges, extremes, singular and limit positions, Grashof
    class, transmission angles and time ratio.

    Extremes and transmission angles are taken over the samples that assemble and are not
    singular (``sol.singular``: there rates are undefined); the singular positions are listed
    apart.  Values are SI; ``kinelab analyze`` prints them in the model file's units.

    Parameters
    ----------
    sol : KinematicSolution
        A sweep (N samples).
    report : tuple of str, optional
        Links, slides and points to summarise (default :func:`default_outputs`).
    transmission : tuple of (str, str), optional
        Link pairs for the transmission angle (default: the pin-jointed and slider dyads).
    time_ratio : str, optional
        Output whose quick-return time ratio is wanted (default: the last slide, else the
        last link placed); reported when the crank turns fully.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    >>> s = kl.io.summary(kl.analyze(fb, q=np.radians(np.arange(0, 361, 1.0)), qd=1.0))
    >>> s.grashof.kind, s.full_turn, round(s.quick_return.ratio, 3)   # (180 + 17.15) / (180 - 17.15) deg
    ('crank-rocker', True, 1.211)
    >>> [e.name for e in s.extremes][:3]
    ['coupler.angle', 'coupler.omega', 'coupler.alpha']
    """
    if not isinstance(sol, KinematicSolution):
        raise ModelError(f"sol: expected a KinematicSolution (kinelab.analyze(model, q)), got "
                         f"{describe(sol)}")
    if sol.N == 0:
        raise ModelError("sol: expected a sweep of at least one sample, got none; analyze the "
                         "model at some input values")
    m = sol.mechanism
    if isinstance(report, str):         # one name, not its letters
        report = (report,)
    report = tuple(report) if report else default_outputs(m)
    if time_ratio is not None:
        # a name the caller gives must be an output that moves; whether it has a time ratio
        # is the summary's answer (quick_return None when it has none)
        slides = [j.name for j in m.joints if j.type == "P"]
        check_choice("time_ratio", time_ratio,
                     [n for n in m.link_names if n != m.ground.name] + slides)
    spans = full = None
    if len(m.inputs) == 1:
        spans = tuple(kinematics.reachable_ranges(m))
        full = kinematics.turns_fully(m, spans)
    lengths = _fourbar_lengths(m)
    pairs = list(transmission) if transmission else _default_pairs(m)
    for k, pair in enumerate(pairs):
        if not (isinstance(pair, (tuple, list)) and len(pair) == 2 and pair[0] != pair[1]):
            raise ModelError(f"transmission[{k}]: expected two different links (a coupler and "
                             f"an output), got {describe(pair)}")
    least = np.where(np.isfinite(sol.singularity), sol.singularity, np.inf)
    i_least = int(np.argmin(least))
    return Summary(
        mechanism=m.name,
        inputs=tuple(sol.input_names),
        input_units=tuple("rad" if k == "angle" else "m" for k in kinematics.plan(m).input_kinds),
        samples=sol.N,
        input_range=tuple((float(sol.q[:, k].min()), float(sol.q[:, k].max())) for k in range(sol.M)),
        extremes=tuple(_extremes(sol, report)),
        singular=tuple(_rows(sol, i) for i in _runs(sol.singular)),
        change_points=sol.change_points,
        least_singularity=(float(least[i_least]), _rows(sol, i_least)),
        unassembled=int((~sol.assembled).sum()),
        reachable=spans,
        full_turn=full,
        grashof=grashof(*lengths) if lengths else None,
        grashof_lengths=lengths or (),
        transmission=tuple(_transmission(sol, pairs)),
        quick_return=_quick_return(sol, time_ratio, full),
    )
