"""Constructors for the standard mechanisms of the course notes.

Each returns a :class:`~kinelab.model.Mechanism` whose sketch (point positions) is one
assembled configuration on the requested branch.  Names follow the notes: link 1 is the
ground, 2 the input crank, 3 the coupler or connecting rod, 4 the output; joints are
named ``j`` + the point they act at (``jO2``, ``jA`` ...), prismatic joints by their role.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Literal

import numpy as np

from kinelab.errors import ModelError, check_choice, describe, quoted
from kinelab.model import (MAX_LENGTH, MIN_LENGTH, Input, Joint, Link, Mechanism, Point, is_real,
                           length_problem)

__all__ = ["fourbar", "slider_crank", "inverted_slider_crank", "slotted_link", "whitworth",
           "fivebar", "watt6", "stephenson6", "triad6", "sketches", "SKETCHED"]


def _length_problems(**lengths: float) -> list[str]:
    """Why each of ``lengths`` is not a length kinelab computes with
    (:data:`~kinelab.model.MIN_LENGTH` to :data:`~kinelab.model.MAX_LENGTH` m): a boolean,
    text, a complex number, zero or less, or out of that range."""
    return [f"{name}: expected a positive length (m), got {describe(value)}"
            if not (is_real(value) and value > 0) else
            f"{name}: {why}, got {float(value):g} m"
            for name, value in lengths.items()
            if not (is_real(value) and value > 0) or (why := length_problem(float(value)))]


def _positive(**lengths: float) -> None:
    """Refuse anything but lengths kinelab computes with (see :func:`_length_problems`)."""
    problems = _length_problems(**lengths)
    if problems:
        raise ModelError(problems)


def _finite(**values: float) -> None:
    """Refuse anything but a real number at most :data:`~kinelab.model.MAX_LENGTH` in size
    (an offset, a coordinate)."""
    problems = [f"{name}: expected a finite number, got {describe(value)}" if not is_real(value)
                else f"{name}: {why}, got {float(value):g} m"
                for name, value in values.items()
                if not is_real(value) or (why := length_problem(float(value), positive=False))]
    if problems:
        raise ModelError(problems)


_GRID = np.radians(np.arange(0.0, 360.0, 1.0)) + 1e-3    # off the axes: no accidental symmetry


def _best_angles(quality: Callable[[np.ndarray], np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """For D designs at once: the input angle, on a 1-degree grid, where each design's
    closure quality (``quality(q)`` of shape (D, 360) for the grid's q, > 0: assembles) is
    best, (D,), and whether it closes anywhere, (D,).  Of equally good angles (to rounding),
    the first from 0: the branch a sketch shows at a change point depends on where it is."""
    v = quality(_GRID)
    return _GRID[np.argmax(np.round(v, 12), axis=1)], (v > 0).any(axis=1)


def _best_angle(quality: Callable[[np.ndarray], np.ndarray], what: str,
                near: float | None = None) -> float:
    """The input angle, on a 1-degree grid, where a closure quality (> 0: assembles) is best;
    of equally good angles (to rounding), the first from 0 (see :func:`_best_angles`).

    With ``near`` (a sketch's input angle): that angle itself when it assembles, else the
    best angle of the grid's run of assembling angles nearest to it.
    """
    if near is None:
        q0, closes = _best_angles(lambda q: quality(q)[None, :])
        if not closes[0]:
            raise _never_assembles(what)
        return float(q0[0])
    if quality(np.array([near]))[0] > 0:
        return float(near)
    q = near - math.pi + _GRID
    v = quality(q)
    closes = v > 0
    if not np.any(closes):
        raise _never_assembles(what)
    i = np.flatnonzero(closes)[np.argmin(np.abs(q[closes] - near))]
    lo, hi = i, i
    while lo > 0 and closes[lo - 1]:
        lo -= 1
    while hi < len(q) - 1 and closes[hi + 1]:
        hi += 1
    q, v = q[lo:hi + 1], v[lo:hi + 1]
    return float(q[np.argmax(np.round(v, 12))])


class NeverAssembles(ModelError):
    """Lengths that close the loop at no input angle: a design that exists and never moves,
    not a mistake in its numbers."""


def _never_assembles(what: str) -> NeverAssembles:
    return NeverAssembles(f"{what}: these lengths cannot be assembled at any input angle; check them")


def _closure(D, lb, lc):
    """How well two links lb, lc close across a distance D: 1 - |cos mu| with mu the angle
    between them, > 0 where they close, best (1) at mu = 90 degrees."""
    cos_mu = (lb * lb + lc * lc - np.square(D)) / (2 * lb * lc)
    return 1.0 - np.abs(cos_mu)


def _circle_intersection(X, Z, lb, lc, sigma):
    """The point at lb from X and lc from Z, left of the line X -> Z for sigma = +1 and right
    for -1; X and Z of shape (2,) or (2, N), and so the result."""
    X, Z = np.asarray(X, float), np.asarray(Z, float)
    d = Z - X
    D = np.hypot(d[0], d[1])
    a = (lb * lb - lc * lc + D * D) / (2 * D)
    h = np.sqrt(np.maximum(lb * lb - a * a, 0.0))
    e = d / D
    return X + a * e + sigma * h * np.stack([-e[1], e[0]])


def _pins(*names: tuple[str, str, str]) -> tuple[Joint, ...]:
    return tuple(Joint(f"j{p}", "R", (a, b), point=p) for p, a, b in names)


def _rows(*values: float) -> tuple[np.ndarray, ...]:
    """Scalars as the one design of the sketch functions' arrays (D = 1)."""
    return tuple(np.array([float(v)]) for v in values)


def _xy(x, y) -> np.ndarray:
    """(D,) coordinates (or scalars) as points (D, 2)."""
    x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
    return np.stack([x, y], -1)


def _fourbar_points(ground, crank, coupler, rocker, sigma, point=None):
    """The sketches of D four-bars (:func:`fourbar`), lengths (D,) each: the points by name,
    (D, 2) each, at the best crank angle, and whether each design closes anywhere (D,).
    ``point``: the coupler point's (along, perpendicular) columns, or None."""
    # _closure across |O4 A|, whose square is ground^2 + crank^2 - 2 ground crank cos q: one
    # product and one sum over (D, angles) for the cosine of the transmission angle
    scale = 1.0 / (2 * coupler * rocker)
    base = ((coupler * coupler + rocker * rocker - ground * ground - crank * crank) * scale)[:, None]
    slope = (2 * ground * crank * scale)[:, None]

    def quality(q):
        return 1.0 - np.abs(base + slope * np.cos(q))
    q0, closes = _best_angles(quality)
    A = _xy(crank * np.cos(q0), crank * np.sin(q0))
    O4 = _xy(ground, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        B = _circle_intersection(A.T, O4.T, coupler, rocker, sigma).T
    xy = {"O2": _xy(np.zeros_like(ground), 0.0), "A": A, "B": B, "O4": O4}
    if point is not None:
        e = (B - A) / coupler[:, None]
        n = np.stack([-e[:, 1], e[:, 0]], -1)
        xy["P"] = A + point[0][:, None] * e + point[1][:, None] * n
    return xy, closes


# --------------------------------------------------------------------------------------
def fourbar(ground: float, crank: float, coupler: float, rocker: float,
            coupler_point: tuple[float, float] | None = None,
            branch: Literal["open", "crossed"] = "open") -> Mechanism:
    """Four-bar linkage (RRRR) driven by the crank angle.

    Links ``ground, crank, coupler, rocker`` (1, 2, 3, 4); points ``O2`` (crank pivot, at
    the origin), ``A`` (crank pin), ``B`` (coupler-rocker pin), ``O4`` (rocker pivot, at
    ``(ground, 0)``) and the coupler point ``P`` when given; joints ``jO2, jA, jB, jO4``;
    the input is ``jO2``, q = theta2.

    Parameters
    ----------
    ground, crank, coupler, rocker : float
        Link lengths O2O4, O2A, AB, O4B, m.
    coupler_point : (float, float), optional
        P as (distance along AB, distance perpendicular to AB, CCW) from A, m.
    branch : {"open", "crossed"}
        Assembly mode: "open" puts B to the left of the line from A to O4 (the convex
        quadrilateral when the crank points up), "crossed" to the right.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=2.0, crank=1.0, coupler=1.0, rocker=1.0)
    >>> sol = kl.analyze(fb, q=0.0)                          # *Mecanismos*, Ex. 4.2
    >>> np.degrees([sol.angle("coupler"), sol.angle("rocker")]).round(9)
    array([ 60., 120.])
    """
    _positive(ground=ground, crank=crank, coupler=coupler, rocker=rocker)
    check_choice("branch", branch, ("open", "crossed"))
    sigma = 1.0 if branch == "open" else -1.0
    if coupler_point is not None:
        if not isinstance(coupler_point, (tuple, list, np.ndarray)) or len(coupler_point) != 2:
            raise ModelError(f"coupler_point: expected (along, perpendicular), got "
                             f"{describe(coupler_point)}")
        _finite(coupler_point_along=coupler_point[0], coupler_point_perpendicular=coupler_point[1])
    xy, closes = _fourbar_points(*_rows(ground, crank, coupler, rocker), sigma,
                                 None if coupler_point is None else _rows(*coupler_point))
    if not closes[0]:
        raise _never_assembles("fourbar")
    points = [Point(name, *(float(v) for v in at[0])) for name, at in xy.items()]
    coupler_pts = ("A", "B") if coupler_point is None else ("A", "B", "P")
    return Mechanism(
        name="fourbar",
        points=tuple(points),
        links=(Link("ground", ("O2", "O4"), ground=True), Link("crank", ("O2", "A")),
               Link("coupler", coupler_pts), Link("rocker", ("O4", "B"))),
        joints=_pins(("O2", "ground", "crank"), ("A", "crank", "coupler"),
                     ("B", "coupler", "rocker"), ("O4", "ground", "rocker")),
        inputs=(Input(joint="jO2"),),
        parameters=dict(kind="fourbar", ground=ground, crank=crank, coupler=coupler,
                        rocker=rocker, coupler_point=coupler_point, branch=branch),
    )


def slider_crank(crank: float, rod: float, offset: float = 0.0,
                 branch: Literal["right", "left"] = "right") -> Mechanism:
    """Slider-crank (RRRP), offset or in line, driven by the crank angle.

    Links ``ground, crank, rod, slider``; points ``O2`` (crank pivot, origin), ``A``
    (crank pin), ``B`` (wrist pin, on the slider); joints ``jO2, jA, jB`` and the prismatic
    joint ``slide`` along +x at y = offset, whose slide is the x of B.  Input ``jO2``.

    Parameters
    ----------
    crank, rod : float
        O2A and AB, m.
    offset : float
        Height of the slide line above O2, m.
    branch : {"right", "left"}
        "right" puts B on the +x side of A.

    Examples
    --------
    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> round(float(kl.analyze(sc, q=np.pi).slide("slide")), 12)   # inner dead centre
    2.0
    """
    _positive(crank=crank, rod=rod)
    _finite(offset=offset)
    check_choice("branch", branch, ("right", "left"))
    if abs(offset) >= crank + rod:
        raise ModelError(f"offset: |{offset}| m is beyond crank + rod = {crank + rod} m; "
                         "the rod cannot reach the slide line")
    sigma = 1.0 if branch == "right" else -1.0
    xy, closes = _slider_crank_points(*_rows(crank, rod, offset), sigma)
    if not closes[0]:
        raise _never_assembles("slider_crank")
    A, B = (tuple(float(v) for v in xy[p][0]) for p in "AB")
    return Mechanism(
        name="slider_crank",
        points=(Point("O2", 0.0, 0.0), Point("A", *A), Point("B", *B)),
        links=(Link("ground", ("O2",), ground=True), Link("crank", ("O2", "A")),
               Link("rod", ("A", "B")), Link("slider", ("B",))),
        joints=_pins(("O2", "ground", "crank"), ("A", "crank", "rod"), ("B", "rod", "slider"))
        + (Joint("slide", "P", ("ground", "slider"), point="B", axis=(1.0, 0.0), origin="O2"),),
        inputs=(Input(joint="jO2"),),
        parameters=dict(kind="slider_crank", crank=crank, rod=rod, offset=offset, branch=branch),
    )


def _slider_crank_points(crank, rod, offset, sigma):
    """The sketches of D slider-cranks (:func:`slider_crank`), as :func:`_fourbar_points`."""
    def quality(q):
        h = offset[:, None] - crank[:, None] * np.sin(q)
        return 1.0 - np.abs(h) / rod[:, None]
    q0, closes = _best_angles(quality)
    A = _xy(crank * np.cos(q0), crank * np.sin(q0))
    with np.errstate(invalid="ignore"):
        dx = sigma * np.sqrt(rod ** 2 - (offset - A[:, 1]) ** 2)
    return {"O2": _xy(np.zeros_like(crank), 0.0), "A": A, "B": _xy(A[:, 0] + dx, offset)}, closes


def _slotted_points(x2, y2, crank, offset, arm, sigma):
    """The sketches of D crank-and-slotted-lever linkages (:func:`_slotted`), as
    :func:`_fourbar_points`, with the slot's direction (D, 2) before the closure."""
    def quality(q):
        ax = x2[:, None] + crank[:, None] * np.cos(q)
        ay = y2[:, None] + crank[:, None] * np.sin(q)
        return 1.0 - np.abs(offset[:, None]) / np.maximum(np.hypot(ax, ay), 1e-300)
    q0, closes = _best_angles(quality)
    A = _xy(x2 + crank * np.cos(q0), y2 + crank * np.sin(q0))
    D = np.hypot(A[:, 0], A[:, 1])
    with np.errstate(invalid="ignore"):
        t = sigma * np.sqrt(D * D - offset * offset)   # slide of A along the slot, from O4's foot
    # lever direction u with A = t u + offset n (n = k x u):  rotate A back by atan2(offset, t)
    phi = np.arctan2(A[:, 1], A[:, 0]) - np.arctan2(offset, t)
    u = _xy(np.cos(phi), np.sin(phi))
    xy = {"O4": _xy(np.zeros_like(crank), 0.0), "O2": _xy(x2, y2), "A": A, "C": arm[:, None] * u}
    return xy, u, closes


def _slotted(name: str, ground_xy: tuple[float, float], crank: float, offset: float,
             arm: float, branch: str, lever_name: str = "lever", slot: str = "slot",
             params=None) -> Mechanism:
    """Crank O2A whose pin A slides in a slot of a lever turning about O4 = origin.

    The slot is parallel to the lever (O4 -> C) at a perpendicular distance ``offset``.
    """
    sigma = 1.0 if branch in ("positive", "open") else -1.0
    xy, u, closes = _slotted_points(*_rows(*ground_xy, crank, offset, arm), sigma)
    if not closes[0]:
        raise _never_assembles(name)
    O2, A, C, u = (tuple(float(v) for v in a[0]) for a in (xy["O2"], xy["A"], xy["C"], u))
    return Mechanism(
        name=name,
        points=(Point("O4", 0.0, 0.0), Point("O2", *O2), Point("A", *A), Point("C", *C)),
        links=(Link("ground", ("O4", "O2"), ground=True), Link("crank", ("O2", "A")),
               Link("block", ("A",)), Link(lever_name, ("O4", "C"))),
        joints=_pins(("O2", "ground", "crank"), ("A", "crank", "block"), ("O4", "ground", lever_name))
        + (Joint(slot, "P", (lever_name, "block"), point="A", axis=u, origin="O4"),),
        inputs=(Input(joint="jO2"),),
        parameters=params or {},
    )


def slotted_link(crank: float, distance: float,
                 branch: Literal["positive", "negative"] = "positive") -> Mechanism:
    """Slotted-link (crank and slotted lever, quick-return) mechanism of
    Erthal, *Mecanismos com 1 GL: análise geral de velocidade e aceleração*.

    The position equations of the notes are ``B cos A - R cos q - C = 0`` and
    ``B sin A - R sin q = 0`` with R = crank and C = distance: the lever pivot ``O4`` is at
    the origin, the crank pivot ``O2`` at ``(C, 0)``, the crank pin ``A`` slides in the
    lever's slot.  Erthal's A is ``sol.angle("lever")``, its B is ``sol.slide("slot")``
    (the distance O4A).  Links ``ground, crank, block, lever``; points ``O4, O2, A`` and
    ``C`` (the lever's end, at distance crank + distance from O4); joints ``jO2, jA, jO4``
    and the prismatic ``slot`` (guide lever, slider block).  Input ``jO2``.

    Parameters
    ----------
    crank, distance : float
        R and C of the notes, m.
    branch : {"positive", "negative"}
        The sign of B: "positive" has the lever pointing at the crank pin.

    Examples
    --------
    >>> sl = kl.mechanisms.slotted_link(crank=1.0, distance=2.0)
    >>> sol = kl.analyze(sl, q=np.pi / 2)
    >>> round(float(sol.slide("slot")), 10), round(float(np.degrees(sol.angle("lever"))), 9)
    (2.2360679775, 26.565051177)
    """
    _positive(crank=crank, distance=distance)
    check_choice("branch", branch, ("positive", "negative"))
    return _slotted("slotted_link", (distance, 0.0), crank, 0.0, crank + distance, branch,
                    params=dict(kind="slotted_link", crank=crank, distance=distance, branch=branch))


def inverted_slider_crank(ground: float, crank: float, offset: float = 0.0, rocker: float | None = None,
                          branch: Literal["positive", "negative"] = "positive") -> Mechanism:
    """Inverted slider-crank: the block on the crank pin slides along the rocker
    (Badan (IFG), *Análise de aceleração* (after Norton, ch. 7);
    Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades*
    (Universidade do Minho, 2007), §4.7.4).

    Links ``ground, crank, block, rocker``; points ``O2`` (origin), ``A`` (crank pin, on
    the block), ``O4`` at ``(ground, 0)`` and ``C`` (the rocker's end, which sets its
    direction); joints ``jO2, jA, jO4`` and the prismatic ``slide`` (guide rocker, slider
    block), parallel to O4C at perpendicular distance ``offset`` (CCW side); its slide is
    measured from the foot of O4 along O4C.  Input ``jO2``.

    Parameters
    ----------
    ground, crank : float
        O2O4 and O2A, m.
    offset : float
        Distance of the slide line from O4, m.
    rocker : float, optional
        Length O4C, m (default ground + crank).
    branch : {"positive", "negative"}
        "positive": the slide of A along O4C is positive.

    Examples
    --------
    >>> isc = kl.mechanisms.inverted_slider_crank(ground=2.0, crank=1.0)
    >>> sol = kl.analyze(isc, q=np.pi / 2)
    >>> round(float(sol.slide("slide")), 10)          # |O4A| = sqrt(1 + 4)
    2.2360679775
    """
    _positive(ground=ground, crank=crank)
    _finite(offset=offset)
    check_choice("branch", branch, ("positive", "negative"))
    rocker = ground + crank if rocker is None else rocker
    _positive(rocker=rocker)
    m = _slotted("inverted_slider_crank", (-ground, 0.0), crank, offset, rocker, branch,
                 lever_name="rocker", slot="slide")
    # shift so that O2 is at the origin and O4 at (ground, 0), as in the notes
    pts = tuple(Point(p.name, p.x + ground, p.y) for p in m.points)
    return Mechanism(name=m.name, points=pts, links=m.links, joints=m.joints, inputs=m.inputs,
                     parameters=dict(kind="inverted_slider_crank", ground=ground, crank=crank,
                                     offset=offset, rocker=rocker, branch=branch))


def _ram_point(cx, cy, rod, ram_height) -> np.ndarray:
    """The Whitworth ram's pin D (D, 2): at ``rod`` from the lever's end C, on the ram line,
    ahead of C; NaN where the rod does not reach the line (or only touches it)."""
    with np.errstate(invalid="ignore"):
        dx = np.sqrt(rod ** 2 - (ram_height - cy) ** 2)
    return _xy(np.where(dx > 0.0, cx + dx, np.nan), ram_height)


def whitworth(crank: float, distance: float, lever: float, rod: float,
              ram_height: float = 0.0) -> Mechanism:
    """Whitworth quick-return mechanism: a slotted lever turning full circle drives a ram.

    The crank O2A (O2 at ``(0, distance)`` above the lever pivot O4 at the origin, with
    distance < crank so that the lever turns fully) carries the block A that slides in the
    lever's slot; the lever end ``C`` (radius ``lever``) drives the ram ``D`` through the
    rod CD; the ram slides along +x at y = ram_height.

    Links ``ground, crank, block, lever, rod, ram``; points ``O4, O2, A, C, D``; joints
    ``jO2, jA, jO4, jC, jD``, the prismatic ``slot`` (lever/block) and ``ram_slide``
    (ground/ram; its slide is the x of D).  Input ``jO2``.

    The ram's dead centres come when C crosses the x axis, i.e. when A does:
    ``sin q = -distance / crank``, so the crank turns ``pi + 2 asin(distance/crank)`` for one
    stroke and ``pi - 2 asin(distance/crank)`` for the other; the time ratio is their
    quotient (:func:`kinelab.kinematics.time_ratio`).

    Examples
    --------
    >>> w = kl.mechanisms.whitworth(crank=1.0, distance=0.5, lever=1.0, rod=2.0)
    >>> sol = kl.analyze(w, q=np.radians(-30.0))      # A on the x axis: a dead centre
    >>> round(float(sol.slide("ram_slide")), 12)      # C = (1, 0), D = (3, 0)
    3.0
    """
    _positive(crank=crank, distance=distance, lever=lever, rod=rod)
    _finite(ram_height=ram_height)
    if distance >= crank:
        raise ModelError(f"distance: expected less than the crank ({crank} m) so that the lever "
                         f"turns full circle, got {distance} m; use slotted_link for a rocking lever")
    if abs(ram_height) >= lever + rod:
        raise ModelError("ram_height: the rod cannot reach the ram line; lower it")
    base = _slotted("whitworth", (0.0, distance), crank, 0.0, lever, "positive")
    C = base.point("C")
    D = _ram_point(*_rows(C.x, C.y, rod, ram_height))[0]
    if not np.isfinite(D[0]):
        A, O2 = base.point("A"), base.point("O2")
        q0 = math.degrees(math.atan2(A.y - O2.y, A.x - O2.x))
        raise ModelError(f"rod: expected more than {abs(ram_height - C.y):.6g} m, the distance from "
                         f"the lever's end to the ram line at crank angle {q0:.6g} deg (where the "
                         f"mechanism is first assembled), got {rod:g} m; lengthen it (a rod longer "
                         f"than lever + |ram_height| = {lever + abs(ram_height):.6g} m reaches the "
                         "ram line at every crank angle)")
    return Mechanism(
        name="whitworth",
        points=base.points + (Point("D", *(float(v) for v in D)),),
        links=base.links + (Link("rod", ("C", "D")), Link("ram", ("D",))),
        joints=base.joints + _pins(("C", "lever", "rod"), ("D", "rod", "ram"))
        + (Joint("ram_slide", "P", ("ground", "ram"), point="D", axis=(1.0, 0.0), origin="O4"),),
        inputs=base.inputs,
        parameters=dict(kind="whitworth", crank=crank, distance=distance, lever=lever, rod=rod,
                        ram_height=ram_height),
    )


# -- many designs at once -----------------------------------------------------------------
SKETCHED = ("fourbar", "slider_crank", "inverted_slider_crank", "slotted_link", "whitworth")


def sketches(kind: str, values: Mapping[str, np.ndarray], options: Mapping[str, object]
             ) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray], np.ndarray]:
    """The sketches of D designs of a catalogue kind of :data:`SKETCHED`, in array
    operations: the points the constructor would place, by name, (D, 2) each; the prismatic
    joints' axes, by name, (D, 2) each; and which designs it would build, (D,) (the others
    are the constructor's to explain: call it with their values).

    ``values`` are the constructor's numeric arguments, (D,) each (the four-bar's coupler
    point as the columns ``coupler_point_along`` and ``coupler_point_perpendicular``);
    ``options`` its other arguments (a branch, the inverted slider-crank's rocker).
    """
    v = {name: np.asarray(a, float) for name, a in values.items()}
    D = len(next(iter(v.values())))
    ok = np.ones(D, bool)
    for a in v.values():
        ok &= np.abs(a) <= MAX_LENGTH      # NaN fails too

    def lengths(*names):
        nonlocal ok
        for n in names:
            ok &= (v[n] >= MIN_LENGTH)
    axes: dict[str, np.ndarray] = {}
    if kind == "fourbar":
        lengths("ground", "crank", "coupler", "rocker")
        sigma = 1.0 if options.get("branch", "open") == "open" else -1.0
        point = tuple(v.get(c) for c in ("coupler_point_along", "coupler_point_perpendicular"))
        xy, closes = _fourbar_points(v["ground"], v["crank"], v["coupler"], v["rocker"], sigma,
                                     None if point[0] is None else point)
    elif kind == "slider_crank":
        lengths("crank", "rod")
        ok &= np.abs(v["offset"]) < v["crank"] + v["rod"]
        sigma = 1.0 if options.get("branch", "right") == "right" else -1.0
        xy, closes = _slider_crank_points(v["crank"], v["rod"], v["offset"], sigma)
        axes["slide"] = _xy(np.ones(D), 0.0)
    elif kind == "whitworth":
        lengths("crank", "distance", "lever", "rod")
        ok &= (v["distance"] < v["crank"]) & (np.abs(v["ram_height"]) < v["lever"] + v["rod"])
        xy, axes["slot"], closes = _slotted_points(np.zeros(D), v["distance"], v["crank"],
                                                   np.zeros(D), v["lever"], 1.0)
        xy["D"] = _ram_point(xy["C"][:, 0], xy["C"][:, 1], v["rod"], v["ram_height"])
        axes["ram_slide"] = _xy(np.ones(D), 0.0)
    else:
        positive = options.get("branch", "positive") == "positive"
        if kind == "slotted_link":
            lengths("crank", "distance")
            x2, offset, arm, slot = v["distance"], np.zeros(D), v["crank"] + v["distance"], "slot"
        else:                              # the inverted slider-crank
            lengths("ground", "crank")
            rocker = options.get("rocker")
            arm = v["ground"] + v["crank"] if rocker is None else np.full(D, float(rocker))
            ok &= (arm >= MIN_LENGTH) & (arm <= MAX_LENGTH)
            x2, offset, slot = -v["ground"], v["offset"], "slide"
        xy, axes[slot], closes = _slotted_points(x2, np.zeros(D), v["crank"], offset, arm,
                                                 1.0 if positive else -1.0)
        if kind == "inverted_slider_crank":      # O2 at the origin, O4 at (ground, 0)
            xy = {n: p + _xy(v["ground"], 0.0) for n, p in xy.items()}
    ok &= closes
    for p in xy.values():
        ok &= np.isfinite(p).all(axis=1)
    return xy, axes, ok


def fivebar(ground: float, crank1: float, coupler1: float, coupler2: float, crank2: float,
            branch: Literal["up", "down"] = "up",
            q0: tuple[float, float] | None = None) -> Mechanism:
    """Five-bar linkage (RRRRR) with two inputs, the two crank angles.

    Links ``ground, crank1, coupler1, coupler2, crank2``; points ``O2`` (origin), ``A``,
    ``P`` (the joint of the two couplers, the usual output), ``B``, ``O4`` at
    ``(ground, 0)``; joints ``jO2, jA, jP, jB, jO4``; inputs ``jO2`` (theta of crank1) and
    ``jO4`` (theta of crank2), so q has shape (N, 2).

    Parameters
    ----------
    ground, crank1, coupler1, coupler2, crank2 : float
        O2O4, O2A, AP, BP, O4B, m.
    branch : {"up", "down"}
        "up" puts P to the left of the line from A to B.
    q0 : (float, float), optional
        Crank angles of the sketch, rad (default: chosen where the couplers meet best).

    Examples
    --------
    >>> fb5 = kl.mechanisms.fivebar(ground=1.0, crank1=1.0, coupler1=1.5, coupler2=1.5, crank2=1.0)
    >>> kl.analyze(fb5, q=[np.pi / 2, np.pi / 2]).position("P").round(8)   # y = 1 + sqrt(2)
    array([0.5       , 2.41421356])
    """
    _positive(ground=ground, crank1=crank1, coupler1=coupler1, coupler2=coupler2, crank2=crank2)
    check_choice("branch", branch, ("up", "down"))
    sigma = 1.0 if branch == "up" else -1.0
    if q0 is not None and not (isinstance(q0, (tuple, list, np.ndarray)) and len(q0) == 2
                               and all(is_real(v) and abs(v) <= 2 * math.pi for v in q0)):
        raise ModelError(f"q0: expected two crank angles from -2 pi to 2 pi rad, got {describe(q0)}")
    if q0 is None:
        g = np.radians(np.arange(0.0, 360.0, 5.0)) + 1e-3
        t1, t2 = np.meshgrid(g, g, indexing="ij")
        D = np.hypot(ground + crank2 * np.cos(t2) - crank1 * np.cos(t1),
                     crank2 * np.sin(t2) - crank1 * np.sin(t1))
        quality = _closure(D, coupler1, coupler2)
        if not np.any(quality > 0):
            raise ModelError("fivebar: these lengths cannot be assembled at any crank angles")
        i, j = np.unravel_index(np.argmax(quality), quality.shape)
        q0 = (float(t1[i, j]), float(t2[i, j]))
    A = (crank1 * math.cos(q0[0]), crank1 * math.sin(q0[0]))
    B = (ground + crank2 * math.cos(q0[1]), crank2 * math.sin(q0[1]))
    if not abs(coupler1 - coupler2) < math.dist(A, B) < coupler1 + coupler2:
        raise ModelError(f"q0: the couplers cannot meet at crank angles {q0}; choose others")
    P = _circle_intersection(A, B, coupler1, coupler2, sigma).tolist()
    return Mechanism(
        name="fivebar",
        points=(Point("O2", 0.0, 0.0), Point("A", *A), Point("P", *P), Point("B", *B),
                Point("O4", float(ground), 0.0)),
        links=(Link("ground", ("O2", "O4"), ground=True), Link("crank1", ("O2", "A")),
               Link("coupler1", ("A", "P")), Link("coupler2", ("B", "P")), Link("crank2", ("O4", "B"))),
        joints=_pins(("O2", "ground", "crank1"), ("A", "crank1", "coupler1"),
                     ("P", "coupler1", "coupler2"), ("B", "crank2", "coupler2"), ("O4", "ground", "crank2")),
        inputs=(Input(joint="jO2"), Input(joint="jO4")),
        parameters=dict(kind="fivebar", ground=ground, crank1=crank1, coupler1=coupler1,
                        coupler2=coupler2, crank2=crank2, branch=branch),
    )


def _sketch(defaults: Mapping[str, tuple[float, float]],
            points: Mapping[str, tuple[float, float]] | None) -> dict[str, tuple[float, float]]:
    """The sketch: the defaults with the given ``points`` (m) in their place."""
    pts = dict(defaults)
    if points is not None and not isinstance(points, Mapping):
        raise ModelError(f"points: expected a mapping of name to (x, y), got {describe(points)}")
    for key, xy in (points or {}).items():
        if key not in pts:
            raise ModelError(f"points: expected some of {quoted(pts)}, got {describe(key)}")
        if not isinstance(xy, (tuple, list, np.ndarray)) or len(xy) != 2:
            raise ModelError(f"points['{key}']: expected (x, y), got {describe(xy)}")
        _finite(**{f"points['{key}'].x": xy[0], f"points['{key}'].y": xy[1]})
        pts[key] = (float(xy[0]), float(xy[1]))
    return pts


def _from_points(name: str, pts: Mapping[str, tuple[float, float]], links, input_joint: str,
                 parameters: dict) -> Mechanism:
    joints = []
    for p in pts:
        carriers = [ln for ln, lp in links if p in lp]
        for other in carriers[1:]:
            joints.append(Joint(f"j{p}" if len(carriers) == 2 else f"j{p}_{other}", "R",
                                (carriers[0], other), point=p))
    return Mechanism(
        name=name,
        points=tuple(Point(n, *xy) for n, xy in pts.items()),
        links=tuple(Link(ln, lp, ground=(ln == "ground")) for ln, lp in links),
        joints=tuple(joints), inputs=(Input(joint=input_joint),),
        parameters=parameters)


# The two dyads of a six-bar in series, in the order its plan solves them: (middle joint,
# first end, second end).  The crank places A; a ternary link's third point C lies on the
# sketch's side of its base.
_SIX_BAR_DYADS = (("B", "A", "O4"), ("D", "C", "O6"))


def _left(X, Z, P) -> float:
    """> 0 when P is left of the line X -> Z, < 0 right of it (twice the signed area)."""
    return (Z[0] - X[0]) * (P[1] - X[1]) - (Z[1] - X[1]) * (P[0] - X[0])


def _pair_lengths(pts, links, lengths) -> dict[str, float]:
    """The length of every pair of points of one moving link, ``"A-B"`` in the link's order:
    from ``lengths`` (either order) where given, else from the sketch."""
    pairs = {f"{a}-{b}": (a, b) for ln, lp in links if ln != "ground"
             for i, a in enumerate(lp) for b in lp[i + 1:]}
    ground = next(lp for ln, lp in links if ln == "ground")
    out = {key: math.dist(pts[a], pts[b]) for key, (a, b) in pairs.items()}
    if lengths is None:
        return out
    if not isinstance(lengths, Mapping):
        raise ModelError(f"lengths: expected a mapping of point pairs such as 'O2-A' to lengths (m), "
                         f"got {describe(lengths)}")
    valid = ", ".join(repr(k) for k in pairs)
    problems, seen = [], {}
    for key, value in lengths.items():
        where = f"lengths[{describe(key)}]"
        a, _, b = str(key).partition("-")
        pair = f"{a}-{b}" if f"{a}-{b}" in pairs else f"{b}-{a}"
        if pair in pairs:
            if pair in seen:
                problems.append(f"{where}: the pair {pair} is given twice (as {describe(seen[pair])} too); keep one")
                continue
            seen[pair] = key
            bad = _length_problems(**{where: value})
            if bad:
                problems += bad
                continue
            out[pair] = float(value)
        elif a != b and a in ground and b in ground:
            problems.append(f"{where}: the ground pivots {', '.join(ground)} come from the sketch; "
                            "move them with points= instead")
        elif a in pts and b in pts and a != b:
            problems.append(f"{where}: {a} and {b} are not on one link; expected one of {valid}")
        else:
            problems.append(f"{where}: expected a pair 'X-Y' of points of one link, one of {valid}, "
                            f"got {describe(key)}")
    if problems:
        raise ModelError(problems)
    for ln, lp in links:
        if ln == "ground" or len(lp) != 3:
            continue
        sides = {f"{a}-{b}": out[f"{a}-{b}"] for a, b in ((lp[0], lp[1]), (lp[0], lp[2]), (lp[1], lp[2]))}
        for side, value in sides.items():
            rest = [k for k in sides if k != side]
            total = sides[rest[0]] + sides[rest[1]]
            if value > total:
                raise ModelError(
                    f"lengths[{describe(side)}]: the triangle {'-'.join(lp)} of link '{ln}' cannot close: "
                    f"expected {side} <= {rest[0]} + {rest[1]} = {total:.6g} m, got {value:.6g} m; "
                    f"shorten {side} or lengthen {rest[0]} or {rest[1]}")
    return out


def _modes(pts, branch) -> tuple[str, str]:
    """The assembly mode of each dyad: ``branch`` checked, or the sketch's."""
    if branch is None:
        modes = []
        for P, X, Z in _SIX_BAR_DYADS:
            side = _left(pts[X], pts[Z], pts[P])
            if abs(side) <= 1e-9 * math.dist(pts[X], pts[Z]) * math.dist(pts[X], pts[P]):
                raise ModelError(f"branch: the sketch puts dyad {X}-{P}-{Z} straight, so its assembly "
                                 "mode is undefined; give branch=(..., ...) or move a point of the sketch")
            modes.append("open" if side > 0 else "crossed")
        return modes[0], modes[1]
    if isinstance(branch, str) or not isinstance(branch, (list, tuple)) or len(branch) != 2:
        raise ModelError(f"branch: expected a pair of 'open'/'crossed', one per dyad "
                         f"({', '.join(f'{X}-{P}-{Z}' for P, X, Z in _SIX_BAR_DYADS)}), got {describe(branch)}")
    for i, mode in enumerate(branch):
        check_choice(f"branch[{i}]", mode, ("open", "crossed"))
    return branch[0], branch[1]


def _six_bar(name: str, defaults, points, links, third: tuple[str, str, str], lengths,
             branch) -> Mechanism:
    """A six-bar of two dyads in series (Watt II, Stephenson III) from its sketch, or, with
    ``lengths`` or ``branch``, assembled in closed form from its lengths: the crank at the
    sketch's input angle (or the best angle near it where everything closes), then each
    dyad on its mode and the ternary link's third point ``third[0]`` on the sketch's side of
    its base ``third[1:]``."""
    pts = _sketch(defaults, points)
    if lengths is None and branch is None:
        return _from_points(name, pts, links, "jO2", dict(kind=name, points=pts))
    size = _pair_lengths(pts, links, lengths)
    modes = _modes(pts, branch)

    def pair(a, b):
        return f"{a}-{b}" if f"{a}-{b}" in size else f"{b}-{a}"

    def length(a, b):
        return size[pair(a, b)]
    # (point, circle centres, side, whether it is a dyad's middle joint), in the plan's order
    side = {"open": 1.0, "crossed": -1.0}
    P, X, Z = third
    steps = ((*_SIX_BAR_DYADS[0], side[modes[0]], True),
             (P, X, Z, 1.0 if _left(pts[X], pts[Z], pts[P]) >= 0 else -1.0, False),
             (*_SIX_BAR_DYADS[1], side[modes[1]], True))
    (_, A, O4), (_, _, O6) = _SIX_BAR_DYADS
    crank = length("O2", A)

    def place(q):
        """Every point at crank angles q (N,), shape (2, N), and each dyad's closure."""
        xy = {p: np.array(pts[p], float)[:, None] for p in ("O2", O4, O6)}
        xy[A] = xy["O2"] + crank * np.stack([np.cos(q), np.sin(q)])
        closure = []
        with np.errstate(divide="ignore", invalid="ignore"):    # A on O4: no closure there
            for P, X, Z, sigma, dyad in steps:
                lb, lc = length(X, P), length(Z, P)
                if dyad:
                    closure.append(_closure(np.hypot(*(xy[Z] - xy[X])), lb, lc))
                xy[P] = _circle_intersection(xy[X], xy[Z], lb, lc, sigma)
        return xy, closure

    q_sketch = math.atan2(pts[A][1] - pts["O2"][1], pts[A][0] - pts["O2"][0])
    try:
        q0 = _best_angle(lambda q: np.minimum(*place(q)[1]), name, near=q_sketch)
    except ModelError:
        raise ModelError(_why_not_closed(place, size, pair, pts)) from None
    xy = place(np.array([q0]))[0]
    built = {p: tuple(xy[p][:, 0].tolist()) for p in pts}
    return _from_points(name, built, links, "jO2",
                        dict(kind=name, points=pts, lengths=size, branch=modes))


def _why_not_closed(place, size, pair, pts) -> str:
    """Which inequality keeps a six-bar from closing at every crank angle."""
    (_, A, O4), _ = _SIX_BAR_DYADS
    toward = math.atan2(pts[O4][1] - pts["O2"][1], pts[O4][0] - pts["O2"][0])
    # a fine grid, with the two angles where A is nearest to and farthest from O4
    q = np.concatenate([np.radians(np.arange(0.0, 360.0, 0.1)), [toward, toward + math.pi]])
    xy, closure = place(q)
    before, where = np.ones(q.shape, bool), "over a turn of the crank"
    for (P, X, Z), c in zip(_SIX_BAR_DYADS, closure):
        D = np.hypot(*(xy[Z] - xy[X]))[before]
        a, b = pair(X, P), pair(Z, P)
        if size[a] + size[b] < D.min():
            return (f"lengths: dyad {X}-{P}-{Z} closes at no crank angle: expected {a} + {b} >= "
                    f"{D.min():.6g} m, the closest {X} comes to {Z} {where}, got "
                    f"{size[a] + size[b]:.6g} m; lengthen {a} or {b}")
        if abs(size[a] - size[b]) > D.max():
            return (f"lengths: dyad {X}-{P}-{Z} closes at no crank angle: expected |{a} - {b}| <= "
                    f"{D.max():.6g} m, the farthest {X} gets from {Z} {where}, got "
                    f"{abs(size[a] - size[b]):.6g} m; make {a} and {b} closer in length")
        before &= c > 0
        where = f"where dyad {X}-{P}-{Z} closes"
    return ("lengths: the two dyads close at no common crank angle (each closes somewhere, never "
            "both at once); change the lengths")


def watt6(points: Mapping[str, tuple[float, float]] | None = None, *,
          lengths: Mapping[str, float] | None = None,
          branch: tuple[Literal["open", "crossed"], Literal["open", "crossed"]] | None = None
          ) -> Mechanism:
    """Watt six-bar (Watt II): a crank-rocker four-bar whose ternary rocker drives a second
    four-bar.  The two ternary links, ground and rocker, are joined directly at O4.

    Links ``ground (O2, O4, O6), crank (O2, A), coupler (A, B), rocker (O4, B, C),
    link5 (C, D), output (O6, D)``; joints ``jO2, jA, jB, jO4, jC, jD, jO6``; input ``jO2``
    (q = the crank's angle).  The plan solves the dyad ``A-B-O4`` (coupler, rocker), then
    ``C-D-O6`` (link5, output).

    Parameters
    ----------
    points : mapping of str to (float, float), optional
        Sketch positions (m) that replace the defaults.  Alone, every length and both
        assembly modes come from the sketch.
    lengths : mapping of str to float, optional
        Link lengths (m) by pair of points of one link, ``"A-B"`` in either order:
        ``"O2-A"`` (crank), ``"A-B"`` (coupler), ``"O4-B"``, ``"O4-C"``, ``"B-C"`` (the
        rocker's three sides), ``"C-D"`` (link5), ``"O6-D"`` (output).  A pair not given
        keeps its sketch distance.  The ground pivots O2, O4, O6 stay where the sketch has
        them; the crank keeps the sketch's angle (or takes the best angle near it where both
        dyads close), and C keeps the sketch's side of the line O4 -> B.
    branch : (str, str), optional
        Assembly mode of each dyad, in the order above, as in :func:`fourbar`: "open" puts B
        left of the line A -> O4 (D left of C -> O6), "crossed" right of it.  Default: the
        modes the sketch shows.

    With ``lengths`` or ``branch`` the sketch is assembled in closed form (circle
    intersections), and ``parameters`` record every length and both modes.

    Raises
    ------
    ModelError
        An unknown pair, a pair not on one link or on the ground, a length that is not
        positive, a rocker triangle that cannot close, or lengths with which the dyads close
        at no crank angle (the message says which inequality fails).

    Examples
    --------
    >>> w6 = kl.mechanisms.watt6()
    >>> [s.kind for s in kl.kinematics.plan(w6).steps if s.kind in ("RRR", "newton")]
    ['RRR', 'RRR']
    >>> w6 = kl.mechanisms.watt6(lengths={"O2-A": 1.0, "D-C": 2.5}, branch=("open", "crossed"))
    >>> A, D, C = (np.array(w6.point(p).xy) for p in ("A", "D", "C"))
    >>> round(float(np.hypot(*A)), 12), round(float(np.hypot(*(D - C))), 12)   # O2 at the origin
    (1.0, 2.5)
    >>> w6.parameters["branch"]
    ('open', 'crossed')
    """
    defaults = {"O2": (0.0, 0.0), "A": (0.5, 0.866), "B": (3.52, 3.1), "O4": (5.63, -0.76),
                "C": (4.51, 1.21), "O6": (7.07, 0.04), "D": (6.32, 2.53)}
    links = (("ground", ("O2", "O4", "O6")), ("crank", ("O2", "A")), ("coupler", ("A", "B")),
             ("rocker", ("O4", "B", "C")), ("link5", ("C", "D")), ("output", ("O6", "D")))
    return _six_bar("watt6", defaults, points, links, ("C", "O4", "B"), lengths, branch)


def stephenson6(points: Mapping[str, tuple[float, float]] | None = None, *,
                lengths: Mapping[str, float] | None = None,
                branch: tuple[Literal["open", "crossed"], Literal["open", "crossed"]] | None = None
                ) -> Mechanism:
    """Stephenson six-bar (Stephenson III): a four-bar whose ternary coupler drives a dyad
    to a third ground pivot.  The ternary links, ground and coupler, are not adjacent.

    Links ``ground (O2, O4, O6), crank (O2, A), coupler (A, B, C), rocker (O4, B),
    link5 (C, D), output (O6, D)``; joints ``jO2, jA, jB, jO4, jC, jD, jO6``; input ``jO2``
    (q = the crank's angle).  The plan solves the dyad ``A-B-O4`` (coupler, rocker), then
    ``C-D-O6`` (link5, output).

    Parameters
    ----------
    points, branch
        As for :func:`watt6`: the sketch (m), and the modes of the dyads A-B-O4 and C-D-O6
        ("open": B left of the line A -> O4, D left of C -> O6).
    lengths : mapping of str to float, optional
        Link lengths (m) by pair of points of one link, in either order: ``"O2-A"``
        (crank), ``"A-B"``, ``"A-C"``, ``"B-C"`` (the coupler's three sides), ``"O4-B"``
        (rocker), ``"C-D"`` (link5), ``"O6-D"`` (output).  Assembled as :func:`watt6` is,
        with C on the sketch's side of the line A -> B.

    Raises
    ------
    ModelError
        As for :func:`watt6`; the triangle is the coupler's.

    Examples
    --------
    >>> s6 = kl.mechanisms.stephenson6()
    >>> sol = kl.analyze(s6, q=np.radians(np.arange(0, 360, 10)))
    >>> sol.position("D").shape
    (36, 2)
    >>> s6 = kl.mechanisms.stephenson6(lengths={"A-B": 4.0, "B-C": 1.5, "A-C": 3.0})
    >>> B, C = (np.array(s6.point(p).xy) for p in ("B", "C"))
    >>> round(float(np.hypot(*(C - B))), 12)
    1.5
    """
    defaults = {"O2": (0.0, 0.0), "A": (0.0, 1.0), "B": (3.68, 2.75), "O4": (5.69, -1.03),
                "C": (2.18, 3.47), "O6": (5.92, 2.14), "D": (4.34, 5.26)}
    links = (("ground", ("O2", "O4", "O6")), ("crank", ("O2", "A")), ("coupler", ("A", "B", "C")),
             ("rocker", ("O4", "B")), ("link5", ("C", "D")), ("output", ("O6", "D")))
    return _six_bar("stephenson6", defaults, points, links, ("C", "A", "B"), lengths, branch)


def triad6(points: Mapping[str, tuple[float, float]] | None = None, *,
           lengths: Mapping[str, float] | None = None) -> Mechanism:
    """A six-bar whose links beyond the crank form a triad (a class-III Assur group), which
    no sequence of dyads solves: kinelab places it by Newton-Raphson with continuation.

    A ternary link ``triad (C, D, E)`` is held by three binary links: ``link3 (A, C)`` from
    the crank pin, ``link4 (D, O4)`` and ``link5 (E, O6)`` from the ground.  Links
    ``ground (O2, O4, O6), crank (O2, A), link3, triad, link4, link5``; joints ``jO2, jA,
    jC, jD, jE, jO4, jO6``; input ``jO2``.

    Parameters
    ----------
    points : mapping of str to (float, float), optional
        Sketch positions (m) that replace the defaults.
    lengths : mapping of str to float, optional
        Link lengths (m) by pair of points of one link, ``"A-B"`` in either order:
        ``"O2-A"``, ``"A-C"``, ``"C-D"``, ``"C-E"``, ``"D-E"``, ``"D-O4"``, ``"E-O6"``; a
        pair not given keeps its sketch distance.  The crank keeps the sketch's angle, and
        the triad is assembled by Newton-Raphson from the sketch: a triad has up to six
        assembly modes and no sign picks one, so the sketch, drawn roughly on the mode
        wanted, chooses it (the ternary link keeps its orientation).

    Raises
    ------
    ModelError
        A bad pair or length (as for :func:`watt6`), or lengths with which the triad does not
        close near the sketch.

    Examples
    --------
    >>> t6 = kl.mechanisms.triad6()
    >>> [s.kind for s in kl.kinematics.plan(t6).steps if s.kind == "newton"]
    ['newton']
    >>> t6 = kl.mechanisms.triad6(lengths={"A-C": 2.9, "E-O6": 2.8})
    >>> C, E = (np.array(t6.point(p).xy) for p in "CE")
    >>> round(float(np.hypot(*(C - t6.point("A").xy))), 12), round(float(np.hypot(*(E - (5.58, 2.74)))), 12)
    (2.9, 2.8)
    """
    defaults = {"O2": (0.0, 0.0), "A": (0.0, 0.5), "C": (2.79, 0.25), "D": (2.66, 0.61),
                "E": (2.81, 2.76), "O4": (2.65, -1.65), "O6": (5.58, 2.74)}
    links = (("ground", ("O2", "O4", "O6")), ("crank", ("O2", "A")), ("link3", ("A", "C")),
             ("triad", ("C", "D", "E")), ("link4", ("D", "O4")), ("link5", ("E", "O6")))
    pts = _sketch(defaults, points)
    if lengths is None:
        return _from_points("triad6", pts, links, "jO2", dict(kind="triad6", points=pts))
    size = _pair_lengths(pts, links, lengths)
    built = _assembled_triad(pts, size)
    return _from_points("triad6", built, links, "jO2",
                        dict(kind="triad6", points=pts, lengths=size))


# the triad's distance constraints: (point, point, pair), unknowns C, D, E in that order
_TRIAD = (("A", "C", "A-C"), ("C", "D", "C-D"), ("C", "E", "C-E"), ("D", "E", "D-E"),
          ("D", "O4", "D-O4"), ("E", "O6", "E-O6"))


def _assembled_triad(pts, size) -> dict[str, tuple[float, float]]:
    """The triad6 sketch with the crank's length and the triad's lengths: A on the sketch's
    crank angle, then C, D, E by Newton-Raphson from the sketch (its assembly mode)."""
    from kinelab.solvers import newton

    O2, A0 = np.array(pts["O2"]), np.array(pts["A"])
    direction = (A0 - O2) / np.hypot(*(A0 - O2))
    fixed = {"O2": O2, "A": O2 + size["O2-A"] * direction, "O4": np.array(pts["O4"]),
             "O6": np.array(pts["O6"])}
    unknown = ("C", "D", "E")

    def xy(x, p):
        if p in unknown:
            k = 2 * unknown.index(p)
            return x[:, k:k + 2]
        return np.broadcast_to(fixed[p], (len(x), 2))

    def fun(x):
        return np.stack([np.sum((xy(x, a) - xy(x, b)) ** 2, axis=1) - size[k] ** 2
                         for a, b, k in _TRIAD], axis=1)

    def jac(x):
        J = np.zeros((len(x), len(_TRIAD), 6))
        for r, (a, b, _) in enumerate(_TRIAD):
            d = 2 * (xy(x, a) - xy(x, b))
            for p, sign in ((a, 1.0), (b, -1.0)):
                if p in unknown:
                    k = 2 * unknown.index(p)
                    J[:, r, k:k + 2] = sign * d
        return J
    x0 = np.concatenate([pts[p] for p in unknown])[None, :]
    result = newton(fun, jac, x0, on_failure="mask")
    x = result.x[0]
    C, D, E = x[0:2], x[2:4], x[4:6]
    turned = _left(C, D, E) * _left(*(np.array(pts[p]) for p in unknown)) < 0
    if not result.converged[0] or not np.all(np.isfinite(x)) or turned:
        raise ModelError("lengths: the triad C-D-E does not close with these lengths near the sketch "
                         "(or only with its ternary link turned over); check the lengths, or draw "
                         "the sketch closer to the assembly wanted with points=")
    return {**{p: tuple(float(v) for v in fixed[p]) for p in fixed},
            **{p: tuple(float(v) for v in xy(x[None, :], p)[0]) for p in unknown}}
