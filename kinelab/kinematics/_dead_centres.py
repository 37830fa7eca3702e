"""The two kinds of singular position of a one-input mechanism, kept apart as the notes keep
them (*Mecanismos*, §4.8, Ex. 4.6; Erthal, *Mecanismos com 1 GL*, "Singularidades"):

- a **toggle** (posição de travamento, or de alinhamento): det J = 0 of the position
  equations, where two links of the driven chain fall in line; the chain locks there (the
  input's motion ends: a limit position) or may change branch (a change point);
- a **dead centre** of an output (ponto morto): K = 0 of that output's coordinate, where the
  output stops and turns back (a rocker's extreme positions, a slider's top and bottom dead
  centres; the notes' J_I = 0 of the slider-crank driven by its slide).

With several inputs the toggles are no longer isolated input values but curves (surfaces, with
three inputs) in the space of the inputs: :func:`toggles` then returns a :class:`ToggleLocus`,
points on them found over the box of the inputs' ranges.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from collections.abc import Sequence
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, expected_one_of
from kinelab.model import Mechanism
from kinelab.solvers import bisect
from kinelab.solvers._arguments import number, whole

__all__ = ["DeadCentres", "Toggle", "ToggleLocus", "dead_centres", "toggles", "input_span"]

_SWEEP_SAMPLES = 721          # samples of the range where sign changes are looked for
_SAME = 1e-9                  # two roots closer than this (rad, or sizes of the mechanism) are one
_GRID_SAMPLES = 61            # samples of each input's range on the grid of several inputs
_MAX_GRID = 1_000_000         # samples of that grid, all inputs together
_ZERO = 1e-12                 # a singularity measure (a sine) this small is zero: det J has no sign
_TOUCH = 1e-6                 # ... and this small at a grid sample, zero to the rounding of a fold:
                              # the measure grows like the square root of the distance to a limit
                              # position, so a rounding of 1e-16 in the inputs shows as 1e-8


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


@dataclass(frozen=True)
class ToggleLocus:
    """Where det J = 0 is reached over a box of the inputs of a mechanism of several inputs:
    points on its toggle curves (surfaces, with three inputs) in the space of the inputs, as
    :func:`toggles` finds them.  Empty (``len(locus) == 0``, ``locus.reached`` False): det J = 0
    is not reached in the box, as far as the grid sees.

    Attributes
    ----------
    inputs : tuple of str
        The inputs' names, in the order of the columns of ``q``.
    lo, hi : ndarray, shape (M,)
        The box searched, rad or m per input.
    samples : tuple of int
        Samples of each input's range on the grid searched.
    q : ndarray, shape (P, M)
        The points found, rad or m per input; sorted by the first input, then the next.
    kind : ndarray of str, shape (P,)
        "limit position": the loops stop closing there (they close on one side of it only,
        along the grid line the point was found on); "change point": det J changes sign
        there, the loops closing on both sides; "touch": det J = 0 (to rounding: a
        singularity measure below 1e-6) at a sample of the grid itself, with neither change
        beside it (an isolated singular configuration, or where a limit curve touches a
        grid line).
    axis : ndarray of int, shape (P,)
        The input (column of ``q``) along whose grid line the point was bisected; -1 for a
        touch, which is the grid sample itself.
    links : tuple of tuple of str, length P
        The links that fall in line there, where the plan says (a limit position's dyad,
        the one that cannot close beyond it), else ().
    nearest_q : ndarray, shape (M,)
        The assembled grid sample closest to singular (smallest ``nearest``); NaN where no
        sample of the grid assembles.
    nearest : float
        Its singularity measure, |det J| scaled to [0, 1] (the sine of the transmission
        angle of its dyad closest to folding, as ``KinematicSolution.singularity``); NaN where
        no sample assembles.
    """

    inputs: tuple[str, ...]
    lo: np.ndarray
    hi: np.ndarray
    samples: tuple[int, ...]
    q: np.ndarray
    kind: np.ndarray
    axis: np.ndarray
    links: tuple[tuple[str, ...], ...]
    nearest_q: np.ndarray
    nearest: float

    def __len__(self) -> int:
        return len(self.q)

    @property
    def reached(self) -> bool:
        """Whether det J = 0 is reached in the box (any point found)."""
        return len(self.q) > 0

    def __repr__(self) -> str:
        counts = ", ".join(f"{int(np.count_nonzero(self.kind == k))} {k}"
                           for k in ("limit position", "change point", "touch")
                           if np.any(self.kind == k))
        return (f"ToggleLocus({len(self)} points over {' x '.join(map(str, self.samples))} "
                f"samples of {', '.join(self.inputs)}" + (f": {counts}" if counts else "") + ")")


def input_span(mechanism: Mechanism) -> tuple[float, float] | tuple[np.ndarray, np.ndarray]:
    """The input range a study of singular positions covers by default: the input's
    ``range`` if the model gives one, else a turn from the sketch for a crank that turns
    fully, else the reachable interval around the sketch; rad or m.

    With several inputs, the box of their ranges: (lo, hi), each an array of shape (M,),
    each input's ``range`` if the model gives one, else a turn from the sketch for an angle
    and ten sizes of the mechanism either side of the sketch for a slide.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)  # non-Grashof
    >>> [round(v, 9) for v in kl.kinematics.input_span(fb)]        # +-acos(-0.3125)
    [-1.888620031, 1.888620031]
    >>> five = kl.mechanisms.fivebar(ground=1.0, crank1=1.0, coupler1=1.5, coupler2=1.5,
    ...                              crank2=1.0, q0=(np.pi / 2, np.pi / 2))
    >>> lo, hi = kl.kinematics.input_span(five)                    # a turn of each crank
    >>> np.degrees(lo).round(9), np.degrees(hi).round(9)
    (array([90., 90.]), array([450., 450.]))
    """
    from kinelab.kinematics._analyze import plan, reachable_ranges, turns_fully
    p = plan(mechanism)
    if len(p.input_kinds) > 1:
        lo = np.empty(len(p.input_kinds))
        hi = np.empty(len(p.input_kinds))
        for k, (inp, kind, q0) in enumerate(zip(mechanism.inputs, p.input_kinds, p.q_sketch)):
            if inp.range is not None:
                lo[k], hi[k] = sorted(float(v) for v in inp.range)
            elif kind == "angle":
                lo[k], hi[k] = q0, q0 + 2 * math.pi
            else:
                lo[k], hi[k] = q0 - 10.0 * p.scale, q0 + 10.0 * p.scale
        return lo, hi
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


def toggles(mechanism: Mechanism, lo: ArrayLike | None = None, hi: ArrayLike | None = None, *,
            samples: int | Sequence[int] | None = None) -> tuple[Toggle, ...] | ToggleLocus:
    """The toggles (posições de travamento) over an input range: where det J = 0 is reached.

    **One input.**  They are the limit positions inside the range (the ends of
    :func:`reachable_ranges`, located by bisection to 1e-12), the change points
    (:func:`change_points`) and any other sign change of det J along a sweep of the range,
    refined by bisection on the sign of det J.  An empty tuple says that det J = 0 is not reached
    (a slider-crank whose crank is shorter than its rod less the offset; a crank-rocker
    driven by its crank).

    **Several inputs** (M of them: a five-bar driven at both cranks, M = 2).  det J = 0 is
    then one equation in M inputs: its solutions are curves in the (q1, q2) plane (surfaces
    for M = 3), and what is returned is points on them, a :class:`ToggleLocus`.  The box
    ``[lo, hi]`` is covered by a grid of ``samples`` values of each input, analysed in one
    batch; along every grid line (each input in turn varying, the others held at grid
    values) two neighbouring samples bracket a point of the locus where

    - the loops close at one and not at the other: a **limit position**, where the
      chain reaches the end of its reach and a dyad falls in line (det J = 0 there, as at a
      one-input mechanism's limit positions), bisected on whether the loops close; or
    - both close and det J has opposite signs: a **change point**, bisected on the sign of
      det J;

    all brackets bisected together (one batched analysis a step) to about 1e-13 rad (or
    sizes of the mechanism, for a slide) along their grid line.  A grid sample where det J
    is zero to rounding without either change beside it is a **touch** (an isolated
    singular configuration, or where a limit curve touches a grid line).  A curve
    that crosses no grid line, or crosses one twice between two samples, is not seen: a
    finer grid (``samples``) sees more.  Mechanisms of several inputs are searched when
    their plan is in closed form (dyads), as each sample is then solved on its own.

    *Toggles are the parallel singularities of a parallel robot.*  For a mechanism whose
    inputs are its actuated joints (a five-bar robot), det J = 0 is what Gosselin and
    Angeles call a singularity of the second type (a "parallel" singularity): J relates the
    secondary velocities to the inputs' (J Sd = -Q qd), so where det J = 0 the secondary
    coordinates, the output included, can move with the inputs locked, and the actuators
    lose control of the output.  In a five-bar driven at its cranks that is where the two
    distal links (the couplers) fall in line: their joint P can move across the line
    they make.  The loops stop closing exactly there, stretched out or folded back, so
    in the (q1, q2) plane the boundary of the assembled region is made of these toggles
    (the limit positions above).  The other type, the "serial" singularities (first type),
    is not det J = 0: there a crank and its coupler fall in line, P is at the boundary of
    its workspace in the plane and cannot move along some direction whatever the inputs do
    (P's velocity coefficients, its rows of K, lose rank), while det J stays away from 0;
    they are the analogue of an output's dead centres (:func:`dead_centres`, K = 0), not
    toggles, and are not returned here.

    Parameters
    ----------
    mechanism : Mechanism
    lo, hi : float or array_like, shape (M,) with several inputs, optional
        The input range (the box of the inputs' ranges), rad or m; by default the model's
        input ranges, else as :func:`input_span` gives them.  With several inputs either
        may be None, or hold None for an input, to take that input's default.
    samples : int or sequence of M int, optional
        One input: samples of the range searched for sign changes of det J, 3 to 1,000,000
        (default 721).  Several: samples of each input's range on the grid (default 61 each,
        61 x 61 for two inputs), 3 to 1,000,000 altogether.

    Returns
    -------
    tuple of Toggle
        One input: in increasing q.
    ToggleLocus
        Several inputs: the points found on det J = 0 in the box, empty when it is not
        reached there.

    Raises
    ------
    ModelError
        A bad range or ``samples``; several inputs in a plan with Newton-Raphson groups.

    References
    ----------
    C. Gosselin and J. Angeles, "Singularity analysis of closed-loop kinematic chains",
    IEEE Transactions on Robotics and Automation 6(3), 281-290, 1990.

    Examples
    --------
    A non-Grashof four-bar driven by its longest link rocks between two limit positions,
    where coupler and rocker fall in line (|A O4| = 2.5, so cos q = -0.3125):

    >>> fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    >>> [(round(t.q, 9), t.kind, t.links) for t in kl.kinematics.toggles(fb)]
    [(-1.888620031, 'limit position', ('coupler', 'rocker')), (1.888620031, 'limit position', ('coupler', 'rocker'))]
    >>> kl.kinematics.toggles(kl.mechanisms.slider_crank(crank=1.0, rod=3.0))  # never reached
    ()

    A five-bar, ground 1, cranks 1, couplers 1.2, over a turn of each crank: the couplers
    fall in line where the crank pins A and B are 2.4 apart, a closed curve around
    (q1, q2) = (180, 0) deg, beyond which the loops do not close:

    >>> five = kl.mechanisms.fivebar(ground=1.0, crank1=1.0, coupler1=1.2, coupler2=1.2,
    ...                              crank2=1.0, q0=(np.pi / 2, np.pi / 2))
    >>> locus = kl.kinematics.toggles(five, [0.0, -np.pi], [2 * np.pi, np.pi])
    >>> locus
    ToggleLocus(126 points over 61 x 61 samples of jO2, jO4: 124 limit position, 2 touch)
    >>> limit = locus.q[locus.kind == "limit position"]
    >>> A = np.stack([np.cos(limit[:, 0]), np.sin(limit[:, 0])], axis=1)
    >>> B = np.stack([1.0 + np.cos(limit[:, 1]), np.sin(limit[:, 1])], axis=1)
    >>> bool(np.all(np.abs(np.linalg.norm(B - A, axis=1) - 2.4) <= 1e-11))
    True
    >>> {links for links, kind in zip(locus.links, locus.kind) if kind == "limit position"}
    {('coupler1', 'coupler2')}

    and, where the crank pins meet (A = B) and the couplers fold onto each other, two
    isolated singular configurations, which the grid happens to hit:

    >>> np.degrees(locus.q[locus.kind == "touch"]).round(9) + 0.0
    array([[  60.,  120.],
           [ 300., -120.]])
    >>> kl.kinematics.toggles(five, [1.2, 1.2], [2.0, 2.0]).reached     # near the sketch
    False
    """
    from kinelab.kinematics._analyze import (MAX_SEARCH_SAMPLES, _branch_map, change_points,
                                             plan, reachable_ranges, turns_fully)

    p = plan(mechanism)
    if len(p.input_kinds) > 1:
        return _locus(mechanism, p, lo, hi, samples)
    samples = whole("samples", _SWEEP_SAMPLES if samples is None else samples, 3,
                    MAX_SEARCH_SAMPLES)
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


def _locus(mechanism: Mechanism, p, lo, hi, samples) -> ToggleLocus:
    """:func:`toggles` of a mechanism of several inputs (see there)."""
    from kinelab.kinematics import _codes as codes
    from kinelab.kinematics._analyze import _NOTHING, _solve
    M = len(p.input_kinds)
    if p.groups is not None:
        raise ModelError("mechanism: expected a plan in closed form (dyads) for toggles of "
                         f"several inputs, got one with Newton-Raphson groups ({M} inputs); "
                         "toggles of several inputs are searched sample by sample, which "
                         "continuation does not allow")
    n = _grid_samples(samples, M)
    lo, hi = _box(mechanism, p, lo, hi)
    # bisection in units of the inputs (rad, or sizes of the mechanism): scale-free
    unit = np.array([1.0 if kind == "angle" else p.scale for kind in p.input_kinds])
    zero = np.zeros((1, M))

    def run(q: np.ndarray):
        """(assembled, sign of det J (0 where it is zero to rounding; NaN where the loops do
        not close), singularity measure, failed operation) at the rows of q (N, M)."""
        out = _solve(p, None, np.ascontiguousarray(q, float), zero, zero, stored=_NOTHING)
        ok = out["status"] == codes.ST_OK
        measure = np.where(ok, out["diag"][:, 1], np.nan)
        sign = np.where(ok, np.sign(np.where(measure <= _ZERO, 0.0, out["diag"][:, 0])), np.nan)
        return ok, sign, measure, out["fail"][:, 1]

    axes = [np.linspace(lo[k], hi[k], n[k]) for k in range(M)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)      # (n1, ..., nM, M)
    ok, sign, measure, _ = (a.reshape(grid.shape[:-1]) for a in run(grid.reshape(-1, M)))
    inner, outer, along, limit, sign_in = [], [], [], [], []
    bracketed = np.zeros(ok.shape, bool)
    for k in range(M):
        first = tuple(slice(None, -1) if j == k else slice(None) for j in range(M))
        second = tuple(slice(1, None) if j == k else slice(None) for j in range(M))
        ok_a, ok_b = ok[first], ok[second]
        with np.errstate(invalid="ignore"):
            change = ok_a & ok_b & (sign[first] * sign[second] < 0)
        ends = (ok_a != ok_b) | change
        # the inner end: the one where the loops close (the first, for a change point)
        a_in = ok_a[..., None]
        inner.append(np.where(a_in, grid[first], grid[second])[ends])
        outer.append(np.where(a_in, grid[second], grid[first])[ends])
        sign_in.append(np.where(ok_a, sign[first], sign[second])[ends])
        limit.append((ok_a != ok_b)[ends])
        along.append(np.full(int(ends.sum()), k))
        bracketed[first] |= ends
        bracketed[second] |= ends
    inner, outer = np.concatenate(inner), np.concatenate(outer)
    axis, limit, sign_in = np.concatenate(along), np.concatenate(limit), np.concatenate(sign_in)
    rows = np.arange(len(axis))
    q = np.empty((0, M))
    links: list[tuple[str, ...]] = []
    if len(axis):
        u = unit[axis]

        def at(t: np.ndarray) -> np.ndarray:
            x = inner.copy()
            x[rows, axis] = t * u
            return x

        def closes_as_inner(t: np.ndarray) -> np.ndarray:
            ok_t, sign_t, _, _ = run(at(t))
            return np.where(limit, ok_t, ok_t & (sign_t == sign_in))
        a, b = bisect(closes_as_inner, inner[rows, axis] / u, outer[rows, axis] / u, tol=1e-14)
        # a limit position: the last input that closes (det J is zero there to rounding: the
        # kernel takes a discriminant within rounding of zero as zero); a change point: the
        # middle of the last bracket
        q = at(np.where(limit, a, 0.5 * (a + b)))
        failed = run(at(b))[3]
        for lim, op in zip(limit.tolist(), failed.tolist()):
            step = p.step_of_op(int(op)) if lim else None
            links.append(tuple(step.links) if step is not None and step.kind != "newton" else ())
    kind = np.where(limit, "limit position", "change point").astype(object)
    # det J zero at a grid sample with neither change beside it
    touch = ok & (measure <= _TOUCH) & ~bracketed
    if touch.any():
        q = np.concatenate([q, grid[touch]])
        kind = np.concatenate([kind, np.full(int(touch.sum()), "touch", object)])
        axis = np.concatenate([axis, np.full(int(touch.sum()), -1)])
        links += [()] * int(touch.sum())
    order = np.lexsort(q.T[::-1] / unit[::-1, None]) if len(q) else np.empty(0, int)
    q, kind, axis = q[order], kind[order], axis[order]
    links = [links[i] for i in order.tolist()]
    # the same point found along two grid lines (a curve through a grid sample) is one
    same = np.zeros(len(q), bool)
    if len(q) > 1:
        same[1:] = np.all(np.abs(np.diff(q, axis=0)) <= _SAME * unit, axis=1)
    keep = ~same
    if ok.any():
        i = np.unravel_index(np.nanargmin(np.where(ok, measure, np.nan)), ok.shape)
        nearest_q, nearest = grid[i].copy(), float(measure[i])
    else:
        nearest_q, nearest = np.full(M, np.nan), math.nan
    return ToggleLocus(inputs=tuple(mechanism.input_names), lo=lo, hi=hi, samples=tuple(n),
                       q=q[keep], kind=np.asarray(kind[keep], str), axis=axis[keep],
                       links=tuple(l for l, k in zip(links, keep.tolist()) if k),
                       nearest_q=nearest_q, nearest=nearest)


def _grid_samples(samples, M: int) -> list[int]:
    """``samples`` of :func:`toggles` with several inputs: one count per input."""
    if samples is None:
        n = [_GRID_SAMPLES] * M
    elif isinstance(samples, (list, tuple, np.ndarray)):
        if len(samples) != M:
            raise ModelError(f"samples: expected one whole number or {M} (one per input), got "
                             f"{len(samples)}")
        n = [whole(f"samples[{k}]", v, 3, _MAX_GRID) for k, v in enumerate(samples)]
    else:
        n = [whole("samples", samples, 3, _MAX_GRID)] * M
    if math.prod(n) > _MAX_GRID:
        raise ModelError(f"samples: expected a grid of at most {_MAX_GRID:,} samples, got "
                         f"{' x '.join(map(str, n))} = {math.prod(n):,}; take fewer per input")
    return n


def _box(mechanism: Mechanism, p, lo, hi) -> tuple[np.ndarray, np.ndarray]:
    """(lo, hi) of several inputs, each (M,), checked; an input not given takes
    :func:`input_span`'s."""
    from kinelab.kinematics._analyze import Q_LIMITS
    M = len(p.input_kinds)
    span = input_span(mechanism)
    box = []
    for name, given, default in (("lo", lo, span[0]), ("hi", hi, span[1])):
        if given is None:
            given = [None] * M
        elif not isinstance(given, (list, tuple, np.ndarray)) or len(given) != M:
            raise ModelError(f"{name}: expected {M} input values (one per input, or None for "
                             f"its default), got {given!r}")
        box.append(np.array([default[k] if v is None else number(f"{name}[{k}]", v)
                             for k, v in enumerate(given)], float))
    lo, hi = box
    for k in range(M):
        if not hi[k] > lo[k]:
            raise ModelError(f"lo, hi: expected lo < hi for every input, got lo = {lo[k]:g}, "
                             f"hi = {hi[k]:g} for {mechanism.input_names[k]!r}")
        limit = Q_LIMITS[p.input_kinds[k]]
        for name, v in (("lo", lo[k]), ("hi", hi[k])):
            if abs(v) > limit:
                raise ModelError(f"{name}[{k}]: expected an input within {limit:g} of 0, got "
                                 f"{v:g}")
    return lo, hi


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
