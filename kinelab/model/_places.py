"""Where a link's points are in its own frame: the exact places its ``local`` and ``sides``
give, worked out in one place for every reader of a model.

A link's frame has its origin at the link's first point and its first axis towards its
second point, which is at ``(L, 0)``: ``L`` is the link's ``length``, or without one the
distance the sketch draws.  Its other points are placed in the order of the link's points:

- a point in ``local`` is at the place given, ``(along, left)``;
- a point in ``sides`` is at the given distances from two points of the link placed before
  it, on the given side of the line from the one of the two listed first in the link's points
  to the other: a triangle of three known sides, placed by the law of cosines;
- any other point keeps its place relative to the first two as the sketch draws it (its
  coordinates in the frame, in units of the first-to-second distance, times ``L``).

The side is taken from the order of the link's points, never from the order in which the two
distances are written: a table's keys have no order in TOML or JSON.
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from kinelab.errors import ModelError, describe, quoted, shown, shown_key, suggest
from kinelab.model._units import Units
from kinelab.model._values import is_real, length_problem

__all__ = ["SIDE_WORDS", "exact_places", "place_problems"]

SIDE_WORDS = ("left", "right")
"""Where a point given by its sides lies: left or right of the line from the first of its two
points (in the order of the link's points) to the second."""

_FLAT = 1e-12       # relative: a triangle this close to its inequality's bound is flat
_SAME_PLACE = 1e-12  # relative: two points of a link closer than this are at one place
_GROUND = 1e-9      # relative: a ground point this far from its exact place is misplaced

Place = tuple[float, float]


def exact_places(link, sketch: Mapping[str, Sequence[float]]) -> dict[str, Place]:
    """The exact place in a link's frame, m, of each of its points that its ``local`` or its
    ``sides`` give (see the module docstring).

    Parameters
    ----------
    link : Link
    sketch : mapping of str to (float, float)
        Every point of the link at its sketch position (x, y), m.  It gives the link's
        first-to-second distance when the link has no ``length``, and the places of the
        points that neither ``local`` nor ``sides`` gives.

    Returns
    -------
    dict of str to (float, float)
        ``(along, left)`` of each point given by ``local`` or ``sides``, m.

    Raises
    ------
    ModelError
        The places cannot be worked out (:func:`place_problems` says why).

    Examples
    --------
    A coupler point 4 from A and 3 from B, left of A -> B, on a coupler of length 5 (a 3-4-5
    triangle: along = (4² - 3² + 5²) / (2·5) = 3.2, left = sqrt(4² - 3.2²) = 2.4):

    >>> from kinelab.model import Link, exact_places
    >>> coupler = Link("coupler", ("A", "B", "P"), length=5.0,
    ...                sides={"P": {"A": 4.0, "B": 3.0, "side": "left"}})
    >>> exact_places(coupler, {"A": (0, 0), "B": (5, 0), "P": (3, 2)})
    {'P': (3.2, 2.4)}
    """
    where = f"link {shown(link.name)}"
    if missing := [p for p in link.points if p not in sketch]:
        raise ModelError(f"sketch: expected the place of every point of {where}, got none for "
                         f"{quoted(missing)}")
    places, problems = _places(link, sketch, Units())
    if problems:
        raise ModelError([f"{where}: {p}" for p in problems])
    given = set(_mapping(link.local)) | set(_mapping(link.sides))
    if given and not places:
        raise ModelError(f"{where}: its first two points are at one place in the sketch, so it "
                         "has no frame to place its other points in; move one of them")
    return {p: places[p] for p in link.points[2:] if p in given}


def place_problems(link, sketch: Mapping[str, Sequence[float]], units: Units | None = None
                   ) -> list[str]:
    """Every problem of a link's ``sides`` (and, on the ground, of the places its ``local``
    and ``sides`` give), each one line starting with the field (``sides.W.A: ...``), its
    lengths in ``units`` (default m).

    The ground's points are the frame and are never moved, so on the ground the sketch must
    already put each point where its ``local`` or ``sides`` say.  A link whose points are
    not all in ``sketch`` is checked for what needs no geometry only.
    """
    if link.sides is None and not (link.ground is True and link.local):
        return []
    return _places(link, sketch, units or Units())[1]


def _mapping(value) -> Mapping:
    return value if isinstance(value, Mapping) else {}


def _places(link, sketch, units: Units) -> tuple[dict[str, Place], list[str]]:
    """(the place of each point of the link in its frame, every problem found)."""
    problems: list[str] = []
    pts = tuple(link.points)
    sides = link.sides
    if sides is not None and not isinstance(sides, Mapping):
        return {}, [f"sides: expected a mapping of point = {{point: distance, point: distance, "
                    f"'side': 'left' or 'right'}}, got {describe(sides)}"]
    sides = sides or {}
    local = _mapping(link.local)
    order = {p: k for k, p in enumerate(pts)}
    usable = {}                    # point -> (first reference, second reference, side word)
    for p, spec in sides.items():
        where = f"sides.{shown_key(p)}"
        if order.get(p, 0) < 2:
            what = (f", its {('first', 'second')[order[p]]} point, which the link's frame "
                    "places" if p in order else "")
            problems.append(f"{where}: expected one of the link's points after its first two "
                            f"({quoted(pts[2:]) if len(pts) > 2 else 'none'}), got "
                            f"{describe(p)}{what}")
        elif p in local:
            problems.append(f"{where}: {shown(p)} is given in local too; give its place one "
                            "way: remove it from local or from sides")
        elif (refs := _spec_problems(spec, p, pts[:order[p]], where, units, problems)) is not None:
            usable[p] = refs
    if len(pts) < 2 or not all(p in sketch for p in pts):
        return {}, problems
    xy = {p: (float(sketch[p][0]), float(sketch[p][1])) for p in pts}
    a, b = pts[0], pts[1]
    ex, ey = xy[b][0] - xy[a][0], xy[b][1] - xy[a][1]
    drawn = math.hypot(ex, ey)
    if drawn == 0.0:
        return {}, problems     # a link of no length, refused where the model is checked
    L = link.length if is_real(link.length) and link.length > 0 else drawn
    places: dict[str, Place] = {a: (0.0, 0.0), b: (float(L), 0.0)}
    for p in pts[2:]:
        if p in usable:
            place = _triangle(p, usable[p], sides[p], places, units, problems)
            if place is not None:
                places[p] = place
                continue
        elif p in local and _is_place(local[p]):
            places[p] = (float(local[p][0]), float(local[p][1]))
            continue
        rx, ry = xy[p][0] - xy[a][0], xy[p][1] - xy[a][1]      # as drawn
        places[p] = ((rx * ex + ry * ey) / drawn * (L / drawn),
                     (ex * ry - ey * rx) / drawn * (L / drawn))
    if link.ground is True and abs(L - drawn) <= _GROUND * L:
        problems += _ground_problems(link, xy, places, units)
    return places, problems


def _is_place(value) -> bool:
    return isinstance(value, (tuple, list)) and len(value) == 2 and all(map(is_real, value))


def _spec_problems(spec, p: str, before: tuple[str, ...], where: str, units: Units,
                   problems: list[str]) -> tuple[str, str, str | None] | None:
    """The two points and the side word of ``sides[p]``, in the order of the link's points,
    or None after recording what is wrong."""
    example = "{A = 30, B = 40, side = 'left'}"
    if not isinstance(spec, Mapping):
        problems.append(f"{where}: expected the distances from two points of the link placed "
                        f"before it and a side, such as {example}, got {describe(spec)}")
        return None
    refs = [k for k in spec if k != "side"]
    n = len(problems)
    if len(refs) != 2:
        problems.append(f"{where}: expected the distances from two points of the link placed "
                        f"before {shown(p)} ({quoted(before)}), such as {example}, got "
                        f"{len(refs)}" + (f" ({quoted(refs)})" if refs else ""))
    for r in refs:
        d = spec[r]
        if r not in before:
            problems.append(f"{where}.{shown_key(r)}: expected one of the link's points placed "
                            f"before {shown(p)} ({quoted(before)}), got {describe(r)}"
                            f"{suggest(r, before) if isinstance(r, str) else ''}; points are "
                            "placed in the order of the link's points")
        elif not (is_real(d) and d > 0):
            problems.append(f"{where}.{shown_key(r)}: expected a positive length, got "
                            f"{describe(d)}")
        elif why := length_problem(float(d)):
            problems.append(f"{where}.{shown_key(r)}: {why}, got {_length(d, units)}")
    side = spec.get("side")
    if side is not None and side not in SIDE_WORDS:
        problems.append(f"{where}.side: expected one of {quoted(SIDE_WORDS)}, got {describe(side)}"
                        f"{suggest(side, SIDE_WORDS) if isinstance(side, str) else ''}")
    if len(problems) > n:
        return None
    first, second = sorted(refs, key=before.index)
    return first, second, side


def _triangle(p: str, refs: tuple[str, str, str | None], spec: Mapping, places, units: Units,
              problems: list[str]) -> Place | None:
    """The place of ``p`` from its distances to two placed points (the law of cosines), or
    None after recording why there is none."""
    r1, r2, side = refs
    (x1, y1), (x2, y2) = places[r1], places[r2]
    d1, d2 = float(spec[r1]), float(spec[r2])
    D = math.hypot(x2 - x1, y2 - y1)
    where = f"sides.{shown_key(p)}"
    if D <= _SAME_PLACE * max(d1, d2):
        problems.append(f"{where}: {shown(r1)} and {shown(r2)} are at one place on the link, so "
                        f"their distances fix no place for {shown(p)}; measure from two points "
                        "apart")
        return None
    # the triangle inequality's three slacks; all >= 0 for a triangle, one 0 for a flat one
    slack = (d1 + d2 - D, D + d1 - d2, D + d2 - d1)
    tol = _FLAT * max(d1, d2, D)
    if min(slack) < -tol:
        problems.append(
            f"{where}: {shown(p)} cannot be {_length(d1, units)} from {shown(r1)} and "
            f"{_length(d2, units)} from {shown(r2)}: {shown(r1)} and {shown(r2)} are "
            f"{_length(D, units)} apart; the sides must satisfy |d{r1} - d{r2}| <= {r1}{r2} <= "
            f"d{r1} + d{r2}; change a distance")
        return None
    flat = min(slack) <= tol
    if not flat and side is None:
        problems.append(f"{where}.side: missing; {shown(p)} may lie left or right of the line "
                        f"{r1} -> {r2}; say which: side = 'left' or 'right'")
        return None
    along = (d1 * d1 - d2 * d2 + D * D) / (2 * D)
    # Heron's form of the height: exact to rounding near a flat triangle, where
    # sqrt(d1² - along²) would lose every digit
    height = 0.0 if flat else math.sqrt(slack[0] * slack[1] * slack[2] * (d1 + d2 + D)) / (2 * D)
    if side == "right":
        height = -height
    ux, uy = (x2 - x1) / D, (y2 - y1) / D
    return (x1 + along * ux - height * uy, y1 + along * uy + height * ux)


def _ground_problems(link, xy, places, units: Units) -> list[str]:
    """The ground's points that the sketch does not put at their exact places."""
    out = []
    a, b = link.points[0], link.points[1]
    ex, ey = xy[b][0] - xy[a][0], xy[b][1] - xy[a][1]
    L = math.hypot(ex, ey)
    ux, uy = ex / L, ey / L
    for p in link.points[2:]:
        field = ("sides" if p in _mapping(link.sides) else "local" if p in _mapping(link.local)
                 else None)
        if field is None:
            continue
        along, left = places[p]
        x, y = xy[a][0] + along * ux - left * uy, xy[a][1] + along * uy + left * ux
        off = math.hypot(xy[p][0] - x, xy[p][1] - y)
        if off > _GROUND * max(L, math.hypot(along, left)):
            out.append(f"{field}.{shown_key(p)}: the ground's points are the frame and are not "
                       f"moved, but the sketch puts {shown(p)} {_length(off, units)} from where "
                       f"its {field} place it, ({_length(x, units, unit=False)}, "
                       f"{_length(y, units)}); move {shown(p)} there or correct its {field}")
    return out


def _length(v: float, units: Units, unit: bool = True) -> str:
    """A length for a message, in ``units``."""
    return f"{units.convert(float(v), 'm'):.6g}" + (f" {units.length}" if unit else "")
