"""The Pyslvs mechanism expression, in and out.

Pyslvs describes a linkage as a list of joints, each at a point with the links that meet
there::

    M[
      J[R, color[Green], P[0.0, 0.0], L[ground, L1]],
      J[RP, A[30.0], color[Green], P[51.38, -12.63], L[ground, L2]],
    ]

``R`` pins every listed link together at the point.  ``P`` is a slider: the first link
carries the slot (at angle ``A``, degrees, in the drawing), the second slides along it without
turning, and further links are pinned to the second at the point.  ``RP`` is a pin in a slot:
the links after the first are pinned to a block that slides along the first link's slot.
The point's numbers are Pyslvs' joint numbers; inputs are given as pairs (pivot joint, driven
joint), as Pyslvs does.  Coordinates have no unit; kinelab reads and writes them in mm unless
told otherwise.
"""
from __future__ import annotations

import math
import re
from collections.abc import Sequence

from kinelab.errors import ModelError, describe, expected_one_of, shown
from kinelab.io._imported import in_expression_terms
from kinelab.io._modelfile import LENGTH_UNITS
from kinelab.io._text import NUMBER
from kinelab.model import MAX_POINTS, Input, Joint, Link, Mechanism, Point, angle_problem

__all__ = ["from_pyslvs", "to_pyslvs", "IMPORT_SPEEDS"]

# Pyslvs' expression has no speeds; an imported input gets these (rad/s for a crank, m/s for
# a slide), so that its velocities and accelerations are not all zero.  100 rpm is the crank
# speed of the examples (600 deg/s).
IMPORT_SPEEDS = {"angle": 2.0 * math.pi * 100.0 / 60.0, "slide": 0.1}

_TOKEN = re.compile(rf"""
    (?P<space>\s+)
  | (?P<open>(?:M|J|A|P|L|color)\[)
  | (?P<close>\])
  | (?P<comma>,)
  | (?P<paren>[()])
  | (?P<number>{NUMBER})
  | (?P<name>[A-Za-z_][A-Za-z0-9_-]*)
""", re.X)
_CNAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
GROUND = "ground"


class _Tokens:
    """The expression's tokens, each read when the parser comes to it (a long expression is
    never held as a list of its tokens)."""

    def __init__(self, text: str):
        self.text, self.pos = text, 0
        self.closing: int | None = None      # the "#]" last found (-1: there is none after)
        self.current = self._next()

    def _next(self) -> tuple[str, str, int]:
        text, pos = self.text, self.pos
        while pos < len(text):
            if text[pos] == "#":
                # a comment: "#[ ... #]" and the rest of its line, or "#" to the line's end;
                # one "#]" found serves every "#[" before it (no square work)
                block = text.startswith("#[", pos)
                if block and (self.closing is None or 0 <= self.closing < pos + 2):
                    self.closing = text.find("#]", pos + 2)
                block = block and self.closing >= pos + 2
                end = text.find("\n", self.closing + 2 if block else pos)
                pos = len(text) if end < 0 else end
                continue
            m = _TOKEN.match(text, pos)
            if m is None:
                raise ModelError(f"expression: character {pos + 1}: unexpected {describe(text[pos])}; "
                                 "expected the Pyslvs form M[J[R, P[x, y], L[a, b]], ...]")
            pos = m.end()
            if m.lastgroup != "space":
                self.pos = pos
                return m.lastgroup, m.group(), m.start() + 1
        self.pos = pos
        return "end", "the end", -1

    def peek(self) -> tuple[str, str, int]:
        return self.current

    def take(self, kind: str, value: str | None = None, what: str = "") -> str:
        k, v, pos = self.peek()
        if k != kind or (value is not None and v != value):
            where = f"character {pos}" if pos > 0 else "the end"
            expected = repr(value) if value else {
                "comma": "','", "close": "']'", "number": "a number", "name": "a name",
                "paren": "a parenthesis"}.get(kind, kind)
            raise ModelError(f"expression: {where}: expected {expected}{' (' + what + ')' if what else ''}"
                             f", got {shown(v)}")
        self.current = self._next()
        return v

    def accept(self, kind: str, value: str | None = None) -> bool:
        k, v, _ = self.peek()
        if k == kind and (value is None or v == value):
            self.current = self._next()
            return True
        return False


def _parse(text: str) -> list[tuple[str, float, float, float, tuple[str, ...]]]:
    """(type, angle deg, x, y, links) of each joint."""
    t = _Tokens(text)
    t.take("open", "M[", "the mechanism")
    joints = []
    while not t.accept("close"):
        if len(joints) == MAX_POINTS:       # a joint is a point of the model
            raise ModelError(f"expression: expected at most {MAX_POINTS:,} joints, got more; "
                             "every point is solved at every sample: model the mechanism in parts")
        t.take("open", "J[", "a joint")
        kind = t.take("name", what="the joint type R, P or RP")
        if kind not in ("R", "P", "RP"):
            raise ModelError(f"expression: joint {len(joints)}: type: "
                             f"{expected_one_of(kind, ('R', 'P', 'RP'))}")
        t.take("comma")
        angle = 0.0
        if t.accept("open", "A["):
            angle = float(t.take("number", what="the slot angle, deg"))
            if why := angle_problem(math.radians(angle)):
                raise ModelError(f"expression: joint {len(joints)}: the slot angle: {why}, got "
                                 f"{angle:g} deg")
            t.take("close")
            t.take("comma")
        elif kind != "R":
            raise ModelError(f"expression: joint {len(joints)}: a {kind} joint needs its slot "
                             "angle, A[degrees]")
        if t.accept("open", "color["):
            if t.accept("paren", "("):
                for k in range(3):
                    t.take("number", what="a colour component")
                    if k < 2:
                        t.take("comma")
                t.take("paren", ")")
            else:
                t.take("name", what="a colour")
            t.take("close")
            t.take("comma")
        t.take("open", "P[", "the joint's coordinates")
        x = float(t.take("number", what="x"))
        t.take("comma")
        y = float(t.take("number", what="y"))
        t.take("close")
        t.take("comma")
        t.take("open", "L[", "the joint's links")
        links = []
        while not t.accept("close"):
            links.append(t.take("name", what="a link name"))
            if not t.accept("comma"):
                t.take("close", what="the end of the links")
                break
        t.take("close", what="the end of the joint")
        for v in (angle, x, y):
            if not math.isfinite(v):
                raise ModelError(f"expression: joint {len(joints)}: expected finite numbers")
        joints.append((kind, angle, x, y, tuple(links)))
        if not t.accept("comma"):
            t.take("close", what="the end of the mechanism")
            break
    if t.peek()[0] != "end":
        raise ModelError(f"expression: character {t.peek()[2]}: unexpected {shown(t.peek()[1])} "
                         "after the mechanism")
    return joints


def from_pyslvs(expression: str, *, inputs: Sequence[tuple[int, int]] | None = None,
                length: str = "mm", name: str = "pyslvs") -> Mechanism:
    """A mechanism from a Pyslvs mechanism expression.

    Joint ``i`` becomes point ``P{i}``; links keep their names.  A pin joining several links is
    one point with an R joint from the first link (the ground, when it is among them) to each
    other; an ``RP`` joint adds a slider block ``P{i}_block``; a slotted link with no second
    point gets one, ``P{i}_on_{link}``, on its slot line.  A link's points start with its
    ground pivot, so that a crank's or rocker's angle is measured from its pivot.

    The expression has no speeds: each input gets ``IMPORT_SPEEDS``, 100 rpm (10 pi / 3
    rad/s, the 600 deg/s of the examples) for an angle, 0.1 m/s for a slide; change
    ``Input.speed`` (or ``speed`` in the model file) to your own.

    Parameters
    ----------
    expression : str
        ``M[J[...], ...]``.
    inputs : sequence of (int, int), optional
        Pyslvs' input pairs (pivot joint, driven joint): the link through both is driven about
        the pivot, measured from the ground; a pair (i, i) at a slider drives its slide.
        Default: the pairs of a comment ``# ... inputs (pivot joint, driven joint) = [(1, 2)]``
        as :func:`to_pyslvs` writes, else the first link pinned to the ground.
    length : {"mm", "cm", "m", "in"}
        What one unit of the expression's coordinates is.
    name : str

    Examples
    --------
    >>> m = kl.io.from_pyslvs('''M[
    ...     J[R, P[0, 0], L[ground, crank]],
    ...     J[R, P[0, 10], L[crank, coupler]],
    ...     J[R, P[26.15, 24.70], L[coupler, rocker]],
    ...     J[R, P[30, 0], L[ground, rocker]],
    ... ]''')
    >>> m.point_names, m.inputs[0].joint, m.point("P1").xy
    (('P0', 'P1', 'P2', 'P3'), 'jP0', (0.0, 0.01))
    >>> round(float(np.degrees(m.inputs[0].speed)), 9)          # deg/s: 100 rpm
    600.0
    """
    if length not in LENGTH_UNITS:
        raise ModelError(f"length: {expected_one_of(length, LENGTH_UNITS)}")
    if not isinstance(expression, str):
        raise ModelError(f"expression: expected text, got {type(expression).__name__}")
    scale = LENGTH_UNITS[length]
    vpoints = _parse(expression)
    if inputs is None:
        inputs = _commented_inputs(expression)
    points = [Point(f"P{i}", x * scale, y * scale) for i, (_, _, x, y, _) in enumerate(vpoints)]
    carried: dict[str, dict[str, None]] = {}    # link -> its points, in order (a dict: fast in)
    joints: list[Joint] = []

    def carry(link: str, point: str) -> None:
        carried.setdefault(link, {})[point] = None

    def pins(point: str, links: list[str]) -> None:
        links = sorted(links, key=lambda n: n != GROUND)     # the ground first, for inputs
        for other in links[1:]:
            jname = f"j{point}" if len(links) == 2 else f"j{point}_{other}"
            joints.append(Joint(jname, "R", (links[0], other), point=point))

    slots = []
    for i, (kind, angle, x, y, links) in enumerate(vpoints):
        p = f"P{i}"
        if not links:
            raise ModelError(f"expression: joint {i}: it joins no link; attach it or delete it")
        if kind == "R":
            for link in links:
                carry(link, p)
            pins(p, list(links))
            continue
        if len(links) < 2:
            raise ModelError(f"expression: joint {i}: a {kind} joint needs the slotted link and "
                             "at least one link on the slot")
        axis = (math.cos(math.radians(angle)), math.sin(math.radians(angle)))
        slot, rest = links[0], list(links[1:])
        if kind == "P":
            slider = rest[0]
        else:
            slider = f"{p}_block"
            rest = [slider] + rest
        for link in rest:
            carry(link, p)
        pins(p, rest)
        joints.append(Joint(f"s{p}", "P", (slot, slider), point=p, axis=axis))
        slots.append((slot, i))
    extra = []
    for slot, i in slots:
        if slot != GROUND and len(carried.get(slot, [])) < 2:
            aux = f"P{i}_on_{slot}"
            extra.append(Point(aux, points[i].x, points[i].y))
            carry(slot, aux)
    if GROUND not in carried:
        raise ModelError("expression: no joint is on the ground link; name the fixed link 'ground'")
    # a link's angle runs from its first point to its second: start at its ground pivot, as
    # cranks and rockers are measured
    on_ground = set(carried[GROUND])
    links = [Link(GROUND, tuple(carried[GROUND]), ground=True)]
    links += [Link(n, tuple(sorted(pts, key=lambda q: q not in on_ground)))
              for n, pts in carried.items() if n != GROUND]
    sliding = {n for j in joints if j.type == "P" for n in j.links}
    lonely = [f"expression: link {shown(n)}: it is in joint {pts[0][1:]} only, and a moving "
              "link needs two joints (one is enough for a link on a slider's slot, whose angle "
              "gives its direction); name it in a second joint's L[...]"
              for n, pts in ((n, list(p)) for n, p in carried.items())
              if n != GROUND and len(pts) == 1 and n not in sliding]
    if lonely:
        raise ModelError(lonely)
    model_inputs = _inputs(vpoints, joints, carried, inputs)
    try:
        return Mechanism(name=name, points=tuple(points + extra), links=tuple(links),
                         joints=tuple(joints), inputs=tuple(model_inputs))
    except ModelError as exc:
        # kinelab's names for the expression's joints (P3, jP3 ...) said as its joint numbers
        raise ModelError([f"expression: {in_expression_terms(p)}" for p in exc.problems]) from exc


_INPUTS_COMMENT = re.compile(r"inputs \(pivot joint, driven joint\) = (\[[0-9\s(),]*\])")


def _commented_inputs(expression: str):
    match = next((m for m in _INPUTS_COMMENT.finditer(expression)
                  if "#" in expression[expression.rfind("\n", 0, m.start()) + 1:m.start()]), None)
    if match is None:
        return None
    import ast
    try:
        return [tuple(p) for p in ast.literal_eval(match.group(1))]
    except (ValueError, SyntaxError, TypeError):
        raise ModelError(f"expression: the inputs comment {shown(match.group(1))} is not a list "
                         "of pairs like [(0, 1)]") from None


def _inputs(vpoints, joints: list[Joint], carried, pairs) -> list[Input]:
    turn = IMPORT_SPEEDS["angle"]
    if pairs is None:
        for j in joints:
            if j.type == "R" and j.links[0] == GROUND:
                return [Input(joint=j.name, speed=turn)]
        return []
    out = []
    slides = {j.point: j for j in reversed(joints) if j.type == "P"}
    pivots = {(j.point, frozenset(j.links)): j for j in reversed(joints) if j.type == "R"}
    links_at: dict[str, list[str]] = {}
    for n, pts in carried.items():
        for p in pts:
            links_at.setdefault(p, []).append(n)
    for k, pair in enumerate(pairs):
        if (not isinstance(pair, (tuple, list)) or len(pair) != 2
                or not all(isinstance(v, int) and 0 <= v < len(vpoints) for v in pair)):
            raise ModelError(f"inputs[{k}]: expected a pair of joint numbers from 0 to "
                             f"{len(vpoints) - 1}, got {describe(pair)}")
        b, d = pair
        if b == d:
            slide = slides.get(f"P{b}")
            if slide is None:
                raise ModelError(f"inputs[{k}]: ({b}, {b}) drives a slide, but joint {b} is no slider")
            out.append(Input(joint=slide.name, speed=IMPORT_SPEEDS["slide"]))
            continue
        common = [n for n in links_at.get(f"P{b}", ()) if n != GROUND and f"P{d}" in carried[n]]
        if not common:
            raise ModelError(f"inputs[{k}]: no link carries both joint {b} and joint {d}")
        link = common[0]
        pivot = pivots.get((f"P{b}", frozenset((GROUND, link))))
        out.append(Input(joint=pivot.name, speed=turn) if pivot else
                   Input(links=(GROUND, link), speed=turn))
    return out


def _num(v: float) -> str:
    s = f"{v:.12g}"
    return s if any(c in s for c in ".en") else s + ".0"


def to_pyslvs(model: Mechanism, *, length: str = "mm") -> str:
    """The Pyslvs mechanism expression of a planar mechanism with R and P joints.

    A slider block carried only by its prismatic joint and pins becomes an ``RP`` joint; a
    comment line gives Pyslvs' input pairs.  Link names must be Pyslvs names (letters, digits,
    underscores); the ground link is written as ``ground``.

    Examples
    --------
    >>> sc = kl.mechanisms.slider_crank(crank=0.05, rod=0.2)
    >>> print(kl.io.to_pyslvs(sc).splitlines()[-2])
      J[RP, A[0.0], color[Green], P[249.99996875, 0.0], L[ground, rod]],
    """
    if length not in LENGTH_UNITS:
        raise ModelError(f"length: {expected_one_of(length, LENGTH_UNITS)}")
    if not isinstance(model, Mechanism) or model.space != "planar":
        raise ModelError("model: expected a planar kinelab Mechanism")
    scale = LENGTH_UNITS[length]
    names = {}
    for link in model.links:
        n = GROUND if link.ground else link.name
        if not _CNAME.match(n) or (n == GROUND and not link.ground):
            raise ModelError(f"link '{link.name}': Pyslvs names links with letters, digits and "
                             "underscores, and calls only the fixed link 'ground'; rename it")
        names[link.name] = n
    for j in model.joints:
        if j.type not in ("R", "P"):
            raise ModelError(f"joint '{j.name}': Pyslvs has R and P joints only, got '{j.type}'")
    blocks = {}
    for j in model.joints:
        if j.type != "P":
            continue
        s = j.links[1]
        own = model.link(s).points == (j.point,)
        others = [k for k in model.joints_of(s) if k is not j]
        if own and all(k.type == "R" and k.point == j.point for k in others):
            blocks[s] = j
    rows, index = [], {}
    for p in model.points:
        carriers = [n for n in model.links_carrying(p.name) if n not in blocks]
        slide = next((j for j in model.joints if j.type == "P" and j.point == p.name), None)
        if not carriers and slide is None:
            continue
        xy = f"P[{_num(p.x / scale)}, {_num(p.y / scale)}]"
        if slide is None:
            links = sorted(carriers, key=lambda n: not model.link(n).ground)
            rows.append(f"J[R, color[Green], {xy}, L[{', '.join(names[n] for n in links)}]]")
        else:
            guide, slider = slide.links
            angle = _num(math.degrees(math.atan2(slide.axis[1], slide.axis[0])))
            if slider in blocks:
                on = [n for n in carriers if n != guide]
                kind = "RP"
            else:
                on = [slider] + [n for n in carriers if n not in (guide, slider)]
                kind = "P"
            rows.append(f"J[{kind}, A[{angle}], color[Green], {xy}, "
                        f"L[{', '.join(names[n] for n in [guide] + on)}]]")
        index[p.name] = len(rows) - 1
    pairs = []
    for inp in model.inputs:
        if inp.joint is not None and model.joint(inp.joint).type == "P":
            i = index[model.joint(inp.joint).point]
            pairs.append((i, i))
            continue
        link = model.joint(inp.joint).links[1] if inp.joint is not None else inp.links[1]
        pivot = model.joint(inp.joint).point if inp.joint is not None else model.link(link).points[0]
        other = next(q for q in model.link(link).points if q != pivot)
        pairs.append((index[pivot], index[other]))
    title = " ".join(str(model.name).split())      # one line: it is a comment
    head = f"# {title}: inputs (pivot joint, driven joint) = {pairs}"
    return head + "\nM[\n" + "".join(f"  {r},\n" for r in rows) + "]\n"
