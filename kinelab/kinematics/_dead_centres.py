"""The two kinds of singular position of a one-input mechanism, kept apart as the notes keep
them (*Mecanismos*, §4.8, Ex. 4.6; Erthal, *Mecanismos com 1 GL*, "Singularidades"):

- a **toggle** (posição de travamento, or de alinhamento): det J = 0 of the position
  equations, where two links of the driven chain fall in line; the chain locks there (the
  input's motion ends: a limit position) or may change branch (a change point);
- a **dead centre** of an output (ponto morto): K = 0 of that output's coordinate, where the
  output stops and turns back (a rocker's extreme positions, a slider's top and bottom dead
  centres; the notes' J_I = 0 of the slider-crank driven by its slide).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from kinelab.errors import ModelError, expected_one_of
from kinelab.model import Mechanism
from kinelab.solvers import bisect
from kinelab.solvers._arguments import number, whole

__all__ = ["DeadCentres", "Toggle", "dead_centres", "toggles", "input_span"]

_SWEEP_SAMPLES = 721          # samples of the range where sign changes are looked for
_SAME = 1e-9                  # two roots closer than this (rad, or sizes of the mechanism) are one


@dataclass(frozen=True)
class DeadCentres:
    """Where an output of a one-input mechanism stops and turns back: its velocity
    coefficient K = dS/dq is zero and changes sign.

    Attributes
    ----------
    output : str
        The link (its angle) or prismatic joint (its slide).
    kind : {"angle", "slide"}
        What ``value`` is.
    q : ndarray, shape (D,)
        Input values at the dead centres, rad or m, increasing.
    value : ndarray, shape (D,)
        The output there: the link's angle (rad) or the slide (m).
    """

    output: str
    kind: Literal["angle", "slide"]
    q: np.ndarray
    value: np.ndarray

    def __len__(self) -> int:
        return len(self.q)


@dataclass(frozen=True)
class Toggle:
    """A toggle (posição de travamento): a configuration where det J = 0.

    Attributes
    ----------
    q : float
        Input value, rad or m.
    kind : {"limit position", "change point"}
        "limit position": the input cannot go on (the range it reaches ends here);
        "change point": the input goes on, and the two assembly modes of a dyad meet.
    links : tuple of str
        The links that fall in line there (empty where the plan does not say).
    label : str
        The step of the plan whose dyad folds (e.g. "dyad 'coupler'-'rocker' (RRR A-B-O4)"),
        or "".
    group : str
        That step's kind: "RRR" (its two links in line), "RRP" (its arm perpendicular to
        the slide), "RPR", ...; "" where the plan does not say.
    """

    q: float
    kind: Literal["limit position", "change point"]
    links: tuple[str, ...] = ()
    label: str = ""
    group: str = ""


def input_span(mechanism: Mechanism) -> tuple[float, float]:
    """The input range a study of singular positions covers by default: the input's
    ``range`` if the model gives one, else a turn from the sketch for a crank that turns
    fully, else the reachable interval around the sketch; rad or m.

    Raises
    ------
    ModelError
        The mechanism has more than one input.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)  # non-Grashof
    >>> [round(v, 9) for v in kl.kinematics.input_span(fb)]        # +-acos(-0.3125)
    [-1.888620031, 1.888620031]
    """
    from kinelab.kinematics._analyze import plan, reachable_ranges, turns_fully
    p = plan(mechanism)
    _one_input(mechanism, p)
    inp = mechanism.inputs[0]
    if inp.range is not None:
        lo, hi = sorted(float(v) for v in inp.range)
        return lo, hi
    ranges = reachable_ranges(mechanism)
    q0 = float(p.q_sketch[0])
    if turns_fully(mechanism, ranges):
        return q0, q0 + 2 * math.pi
    for lo, hi in ranges:
        if lo - 1e-12 <= q0 <= hi + 1e-12:
            return lo, hi
    return ranges[0]


def dead_centres(mechanism: Mechanism, output: str, lo: float | None = None,
                 hi: float | None = None, *, samples: int = _SWEEP_SAMPLES) -> DeadCentres:
    """The dead centres (pontos mortos) of an output over an input range: where the output's
    velocity coefficient K vanishes and changes sign, so that it stops and turns back.

    The range is swept (one vectorised analysis), the sign changes of K between assembled,
    non-singular samples are bracketed, and all brackets are refined together by bisection
    on the sign of K(q) (exact, from the kernel: K = -J^-1 Q, no finite differences) to
    about 1e-13.  A sign change across a singular configuration (K through infinity) is not
    a dead centre and is left out.

    Parameters
    ----------
    mechanism : Mechanism
        One input.
    output : str
        A moving link (its angle) or a prismatic joint (its slide).
    lo, hi : float, optional
        The input range, rad or m; by default the model's input range, else a turn from
        the sketch for a crank that turns fully, else the reachable interval
        (:func:`input_span`).
    samples : int
        Samples of the range searched for sign changes, 3 to 1,000,000.

    Returns
    -------
    DeadCentres

    Raises
    ------
    ModelError
        Not one input; ``output`` not a link or a prismatic joint; a bad range.

    Examples
    --------
    An in-line slider-crank, crank 1, rod 3: the slider's dead centres are where crank and
    rod fall in line, at 0 (x = 4) and 180 deg (x = 2).

    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> dc = kl.kinematics.dead_centres(sc, "slide", 0.0, 2 * np.pi)
    >>> np.degrees(dc.q).round(9) + 0.0, dc.value.round(12) + 0.0
    (array([  0., 180.]), array([4., 2.]))

    (At 360 deg the slider is at 0 deg's dead centre again: a configuration a turn after
    another is listed once.)
    """
    from kinelab.kinematics._analyze import MAX_SEARCH_SAMPLES, _branch_map, analyze, plan

    p = plan(mechanism)
    _one_input(mechanism, p)
    samples = whole("samples", samples, 3, MAX_SEARCH_SAMPLES)
    if output in p.link_item and not mechanism.link(output).ground:
        kind = "angle"
    elif output in p.slide_item:
        kind = "slide"
    else:
        choices = [n for n in p.link_item if not mechanism.link(n).ground] + list(p.slide_item)
        hint = ("; a point has no dead centre of its own: give the link or the prismatic joint "
                "that carries it" if output in p.point_item else "")
        raise ModelError(f"output: {expected_one_of(output, choices)}{hint}")
    lo, hi = _range(mechanism, lo, hi)
    # one step beyond each end, so that a dead centre at an end (where K is zero at the
    # sample itself) is seen between its two neighbours
    step = (hi - lo) / (samples - 1)
    q = np.linspace(lo - step, hi + step, samples + 2)
    item = p.link_item[output] if kind == "angle" else p.slide_item[output]
    if item not in set(p.stored_items.tolist()):
        # turned by the input itself (K = +-1) or fixed (K = 0): it never turns back
        return DeadCentres(output=output, kind=kind, q=np.empty(0), value=np.empty(0))
    bmap = _branch_map(p, 1, "smooth")

    def K(x: np.ndarray) -> np.ndarray:
        return _sweep(p, bmap, x, item)[2]
    usable, _, k = _sweep(p, bmap, q, item)
    # K within its rounding of zero is zero: a link that only translates (a parallelogram's
    # coupler) has K = 0 to rounding everywhere, and no dead centre.  A K that is not
    # flagged singular is accurate to 1e-8 (docs/kinematics.md, "Singular and limit
    # positions"), in rad or sizes of the mechanism per rad or size.
    per_input = 1.0 if p.input_kinds[0] == "angle" else 1.0 / p.scale
    noise = 1e-8 * per_input * (1.0 if kind == "angle" else p.scale)
    sign = np.sign(np.where(usable, np.where(np.abs(k) <= noise, 0.0, k), np.nan))
    both = usable[:-1] & usable[1:]
    brackets = np.flatnonzero(both & (sign[:-1] * sign[1:] < 0))
    on_sample = 1 + np.flatnonzero(both[:-1] & both[1:] & (sign[1:-1] == 0)
                                   & (sign[:-2] * sign[2:] < 0))
    roots = list(q[on_sample])
    if len(brackets):
        found = _refined(K, q[brackets], q[brackets + 1], sign[brackets])
        # K changes sign through zero, not through a singular configuration (K infinite)
        typical = float(np.max(np.abs(k[usable])))
        small = np.abs(K(found)) <= 1e-6 * typical
        roots += list(found[small])
    size = 1.0 if p.input_kinds[0] == "angle" else p.scale
    kept: list[float] = []
    for r in sorted(roots):
        if lo - _SAME * size <= r <= hi + _SAME * size and not (
                kept and abs(r - kept[-1]) <= _SAME * size):
            kept.append(float(min(max(r, lo), hi)))
    qs = np.array(kept)
    value = np.empty(0)
    if len(qs):
        at = analyze(mechanism, qs, at_singular="flag")
        value = np.reshape(np.asarray(at.angle(output) if kind == "angle" else at.slide(output),
                                      float), -1)
        if p.input_kinds[0] == "angle":
            # a turn later, the same configuration (a range of a whole turn has it at both ends)
            again = np.array([any(abs(r - 2 * math.pi - s) <= _SAME and _same_value(v, w, kind, size)
                                  for s, w in zip(qs, value)) for r, v in zip(qs, value)], bool)
            qs, value = qs[~again], value[~again]
    return DeadCentres(output=output, kind=kind, q=qs, value=value)


def _same_value(a: float, b: float, kind: str, size: float) -> bool:
    d = a - b
    if kind == "angle":
        d = math.remainder(d, 2 * math.pi)
    return abs(d) <= 1e-7 * (1.0 if kind == "angle" else size)


def toggles(mechanism: Mechanism, lo: float | None = None, hi: float | None = None, *,
            samples: int = _SWEEP_SAMPLES) -> tuple[Toggle, ...]:
    """The toggles (posições de travamento) over an input range: where det J = 0 is reached.

    They are the limit positions inside the range (the ends of
    :func:`reachable_ranges`, located by bisection to 1e-12), the change points
    (:func:`change_points`) and any other sign change of det J along a sweep of the range,
    refined by bisection on the sign of det J.  An empty tuple says that det J = 0 is not reached
    (a slider-crank whose crank is shorter than its rod less the offset; a crank-rocker
    driven by its crank).

    Parameters
    ----------
    mechanism : Mechanism
        One input.
    lo, hi : float, optional
        As :func:`dead_centres`.
    samples : int
        Samples of the range searched for sign changes of det J, 3 to 1,000,000.

    Returns
    -------
    tuple of Toggle
        In increasing q.

    Examples
    --------
    A non-Grashof four-bar driven by its longest link rocks between two limit positions,
    where coupler and rocker fall in line (|A O4| = 2.5, so cos q = -0.3125):

    >>> fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    >>> [(round(t.q, 9), t.kind, t.links) for t in kl.kinematics.toggles(fb)]
    [(-1.888620031, 'limit position', ('coupler', 'rocker')), (1.888620031, 'limit position', ('coupler', 'rocker'))]
    >>> kl.kinematics.toggles(kl.mechanisms.slider_crank(crank=1.0, rod=3.0))  # never reached
    ()
    """
    from kinelab.kinematics._analyze import (MAX_SEARCH_SAMPLES, _branch_map, change_points,
                                             plan, reachable_ranges, turns_fully)

    p = plan(mechanism)
    _one_input(mechanism, p)
    samples = whole("samples", samples, 3, MAX_SEARCH_SAMPLES)
    lo, hi = _range(mechanism, lo, hi)
    angle = p.input_kinds[0] == "angle"
    size = 1.0 if angle else p.scale
    pad = _SAME * size
    found: list[Toggle] = []
    ranges = reachable_ranges(mechanism)
    if not turns_fully(mechanism, ranges):
        turns = range(-3, 4) if angle else (0,)
        for a, b in ranges:
            for bound, inwards in ((a, 1.0), (b, -1.0)):
                for t in turns:
                    at = bound + 2 * math.pi * t
                    if lo - pad <= at <= hi + pad:
                        found.append(Toggle(float(at), "limit position",
                                            *_folded(p, at, inwards)))
    kinds = {step.label: step.kind for step in p.steps}
    for c in change_points(mechanism, lo, hi):
        found.append(Toggle(float(c.q), "change point", tuple(c.links), c.step,
                            kinds.get(c.step, "")))
    # any other zero of det J that the sweep sees change sign (Newton groups, for instance)
    q = np.linspace(lo, hi, samples)
    bmap = _branch_map(p, 1, "smooth")

    def det_J(x: np.ndarray) -> np.ndarray:
        return _sweep(p, bmap, x)[1]
    det = det_J(q)
    brackets = np.flatnonzero(np.sign(det[:-1]) * np.sign(det[1:]) < 0)
    if len(brackets):
        for r in _refined(det_J, q[brackets], q[brackets + 1], np.sign(det[brackets])):
            if not any(abs(r - t.q) <= 1e-6 * size for t in found):
                found.append(Toggle(float(r), "change point"))
    found.sort(key=lambda t: t.q)
    out: list[Toggle] = []
    for t in found:
        if not (out and abs(t.q - out[-1].q) <= pad):
            out.append(t)
    return tuple(out)


def _sweep(p, bmap, q: np.ndarray, item: int | None = None):
    """(usable, det J, K of ``item``) at the input values q (N,), each on the branch the
    analysis follows there; only that one coordinate is written out, so that a sweep of a
    model with many points takes a few bytes a sample.  ``usable``: assembled and not
    singular; det J is NaN where the loops do not close, K where the sample is not usable."""
    from kinelab.kinematics import _codes as codes
    from kinelab.kinematics._analyze import SINGULAR_TOL, _solve
    q2 = np.ascontiguousarray(np.reshape(q, (-1, 1)), float)
    zero = np.zeros((1, 1))
    stored = np.array([] if item is None else [item], np.int64)
    out = _solve(p, bmap, q2, zero, zero, stored=stored)
    assembled = out["status"] == codes.ST_OK
    det = np.where(assembled, out["diag"][:, 0], np.nan)
    usable = assembled & (out["diag"][:, 1] >= SINGULAR_TOL)
    if item is None:
        return usable, det, None
    k = np.where(usable, out["jets"][:, 0, 1], np.nan)
    usable &= np.isfinite(k)
    return usable, det, k


def _refined(f, a: np.ndarray, b: np.ndarray, sign_a: np.ndarray) -> np.ndarray:
    """The zeros of ``f`` (vectorised: an array of inputs in, of values out) in the brackets
    [a, b], where f has the sign ``sign_a`` at a and the other at b: bisected together, all
    brackets in one evaluation per step, to about 1e-13 of the input."""
    lo, hi = bisect(lambda x: np.sign(f(x)) == sign_a, a, b, tol=1e-14)
    return 0.5 * (lo + hi)


def _folded(p, bound: float, inwards: float) -> tuple[tuple[str, ...], str, str]:
    """The links of the dyad that folds at a limit position ``bound``, its step's label and
    kind:
    the branched operation whose signed measure is smallest just inside the reachable range
    (``inwards``: +1 where the range lies above the bound, -1 below)."""
    from kinelab.kinematics._analyze import _branch_map
    from kinelab.kinematics._branches import _Walker
    if p.groups is not None:
        return (), "", ""
    walker = _Walker(p, "smooth")
    if not walker.ops:
        return (), "", ""
    near = np.array([bound + 1e-7 * inwards * (1.0 if walker.angle else p.scale)])
    bmap = _branch_map(p, 1, "smooth")
    ops_f = p.ops_f
    if bmap is not None:
        index, tables = bmap.variants(near)
        ops_f = tables[int(index[0])]
    ok, m, _, _ = walker.evaluate(ops_f, near)
    if not ok[0] or not np.isfinite(m[0]).any():
        return (), "", ""
    step = p.step_of_op(walker.ops[int(np.nanargmin(np.abs(m[0])))])
    return (tuple(step.links), step.label, step.kind) if step else ((), "", "")


def _one_input(mechanism: Mechanism, p) -> None:
    if len(p.input_kinds) != 1:
        raise ModelError(f"mechanism: expected one input, got {len(p.input_kinds)} "
                         f"({', '.join(repr(n) for n in mechanism.input_names)}); dead centres "
                         "and toggles are found for mechanisms of one input")


def _range(mechanism: Mechanism, lo, hi) -> tuple[float, float]:
    """(lo, hi) checked, or the default :func:`input_span` where not given."""
    if lo is None or hi is None:
        span = input_span(mechanism)
        lo = span[0] if lo is None else lo
        hi = span[1] if hi is None else hi
    lo, hi = number("lo", lo), number("hi", hi)
    if not hi > lo:
        raise ModelError(f"lo, hi: expected lo < hi, got lo = {lo:g}, hi = {hi:g}")
    from kinelab.kinematics._analyze import Q_LIMITS, plan
    limit = Q_LIMITS[plan(mechanism).input_kinds[0]]
    for name, v in (("lo", lo), ("hi", hi)):
        if abs(v) > limit:
            raise ModelError(f"{name}: expected an input within {limit:g} of 0, got {v:g}")
    return lo, hi
