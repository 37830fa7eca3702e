"""What a mechanism *is*: named points, links carrying them, joints and inputs.

Plain, validated, immutable data.  Everything is in SI units (m, rad, kg).  The point
positions are a *sketch*: one assembled configuration of the mechanism, which fixes
every link's geometry and the assembly mode (branch) the analysis follows.
"""
from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

from kinelab.errors import ModelError, quoted, suggest
from kinelab.model._joints import JOINT_TYPES

__all__ = ["Point", "Link", "Joint", "Input", "Mechanism", "SPACES"]

SPACES = ("planar", "spherical", "spatial")
_LENGTH_TOL = 1e-12  # two sketch points closer than this (m) are the same place


@dataclass(frozen=True)
class Point:
    """A named point, at its sketch position (m).

    ``z`` is zero for planar mechanisms.
    """

    name: str
    x: float
    y: float
    z: float = 0.0

    @property
    def xy(self) -> tuple[float, float]:
        return (self.x, self.y)


@dataclass(frozen=True)
class Link:
    """A rigid body carrying named points.

    Parameters
    ----------
    name : str
    points : tuple of str
        The points the link carries.  The angle of the link is the direction from its
        first point to its second (CCW from +x, rad).  A moving link with a single point
        (a slider block) must belong to a prismatic joint; its angle is the direction of
        the axis of the joint it slides in (the one where it is the second link; else the
        one it guides), which turns with that joint's guide.  A ground with a single point
        is the frame: angle 0.
    ground : bool
        The fixed link (exactly one per mechanism).
    mass : float, optional
        kg.
    center_of_mass : str, optional
        A point of this link at its centre of mass.
    inertia : float, optional
        Moment of inertia about the centre of mass, kg m^2.
    length : float, optional
        The exact distance between its first two points, m.  With it, the sketch may be
        rough: :func:`kinelab.kinematics.assemble` moves the points to the assembled
        configuration nearest to it (``kinelab.load`` does so for model files).
    local : mapping of str to (float, float), optional
        The exact place of some of its other points in its own frame, m: along the
        direction from its first point to its second, and to the left of it, from the
        first point (as ``fourbar``'s ``coupler_point``).  Points the link carries that are
        in neither keep their place relative to the first two as the sketch draws it.
    """

    name: str
    points: tuple[str, ...]
    ground: bool = False
    mass: float | None = None
    center_of_mass: str | None = None
    inertia: float | None = None
    length: float | None = None
    local: Mapping[str, tuple[float, float]] | None = field(default=None, hash=False)

    def __post_init__(self):
        if self.local is not None and isinstance(self.local, Mapping):
            object.__setattr__(self, "local", {k: tuple(v) if isinstance(v, (list, tuple)) else v
                                               for k, v in self.local.items()})


@dataclass(frozen=True)
class Joint:
    """A kinematic pair joining two links.

    Parameters
    ----------
    name : str
    type : str
        One of ``kinelab.model.JOINT_TYPES`` (``"R"``, ``"P"``, ``"C"``, ``"U"``, ``"S"``,
        ``"H"``, ``"E"``, ``"cam"``, ``"gear"``, ``"rolling"``, ``"pin_in_slot"``).
    links : (str, str)
        The two links.  For a prismatic joint the first is the *guide* (the link the slide
        axis is fixed in) and the second the *slider*.
    point : str, optional
        Where the joint acts.  A revolute joint's point is carried by both links; a
        prismatic joint's point is carried by the slider and travels along the axis.
    axis : tuple of float, optional
        Slide direction of a prismatic joint, in the sketch (2 components in the plane,
        3 in space); rotation axis of a spatial R, C, H joint; first axis of a U joint.
    origin : str, optional
        Prismatic joints: a point of the guide from which the slide is measured,
        ``slide = axis . (point - origin)``.  Default: the guide's first point.
    axis2 : tuple of float, optional
        Second axis of a U joint.
    pitch : float, optional
        Helical joints: advance per radian (m/rad).
    offset : float, optional
        Prismatic joints: the exact distance of the slide line from ``origin``, m, to the
        left of the axis (0: the line passes through the origin).  Without it the line
        passes through ``point`` as the sketch draws it; with it the sketch may be rough
        (see :func:`kinelab.kinematics.assemble`).
    """

    name: str
    type: str
    links: tuple[str, str]
    point: str | None = None
    axis: tuple[float, ...] | None = None
    origin: str | None = None
    axis2: tuple[float, ...] | None = None
    pitch: float | None = None
    offset: float | None = None


@dataclass(frozen=True)
class Input:
    """One primary (input) coordinate q.

    Give either ``joint`` or ``links``:

    - ``joint`` = a revolute joint joining links (a, b): ``q = theta_b - theta_a``, the
      angle of b measured from link a (from the +x axis when a is the ground);
    - ``joint`` = a prismatic joint: ``q`` is its slide (m);
    - ``links = (a, b)``: the relative angle ``theta_b - theta_a`` of any two links.

    ``range`` (rad or m), ``speed`` (q dot) and ``acceleration`` (q double dot) are the
    defaults a sweep uses when it is not told otherwise.
    """

    joint: str | None = None
    links: tuple[str, str] | None = None
    range: tuple[float, float] | None = None
    speed: float = 0.0
    acceleration: float = 0.0
    name: str | None = None

    @property
    def label(self) -> str:
        """The input's name: ``name`` if given, else the joint, else ``'a->b'``."""
        if self.name:
            return self.name
        if self.joint:
            return self.joint
        return f"{self.links[0]}->{self.links[1]}" if self.links else "q"


@dataclass(frozen=True)
class Mechanism:
    """A mechanism: points, links, joints and inputs, checked as a whole when built.

    Every name is unique across points, links and joints.  Build one with the
    constructors in :mod:`kinelab.mechanisms`, from a model file with :func:`kinelab.load`,
    or directly:

    Examples
    --------
    >>> from kinelab.model import Mechanism, Point, Link, Joint, Input
    >>> m = Mechanism(
    ...     name="pendulum",
    ...     points=(Point("O", 0.0, 0.0), Point("A", 1.0, 0.0)),
    ...     links=(Link("ground", ("O",), ground=True), Link("arm", ("O", "A"))),
    ...     joints=(Joint("pivot", "R", ("ground", "arm"), point="O"),),
    ...     inputs=(Input(joint="pivot"),),
    ... )
    >>> m.link("arm").points
    ('O', 'A')
    """

    name: str
    points: tuple[Point, ...]
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    inputs: tuple[Input, ...] = ()
    space: Literal["planar", "spherical", "spatial"] = "planar"
    parameters: Mapping[str, Any] = field(default_factory=dict, compare=False)

    def __post_init__(self):
        for attr in ("points", "links", "joints", "inputs"):
            object.__setattr__(self, attr, tuple(getattr(self, attr)))
        object.__setattr__(self, "parameters", dict(self.parameters))
        problems = _validate(self)
        if problems:
            raise ModelError(problems, source=f"mechanism '{self.name}'")

    # -- lookup by name ---------------------------------------------------------------
    def point(self, name: str) -> Point:
        return _lookup(self.points, name, "point")

    def link(self, name: str) -> Link:
        return _lookup(self.links, name, "link")

    def joint(self, name: str) -> Joint:
        return _lookup(self.joints, name, "joint")

    @property
    def ground(self) -> Link:
        """The fixed link."""
        return next(link for link in self.links if link.ground)

    @property
    def point_names(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.points)

    @property
    def link_names(self) -> tuple[str, ...]:
        return tuple(link.name for link in self.links)

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(j.name for j in self.joints)

    @property
    def input_names(self) -> tuple[str, ...]:
        return tuple(i.label for i in self.inputs)

    def links_carrying(self, point: str) -> tuple[str, ...]:
        """Names of the links that carry ``point``."""
        return tuple(link.name for link in self.links if point in link.points)

    def joints_of(self, link: str) -> tuple[Joint, ...]:
        """The joints that touch ``link``."""
        return tuple(j for j in self.joints if link in j.links)

    # -- poses --------------------------------------------------------------------------
    def at(self, q) -> Mechanism:
        """The same mechanism sketched at input ``q`` (rad or m; shape () or (M,)), on the
        branch its analysis follows there: :func:`kinelab.kinematics.pose`."""
        # the one method of the model that needs the engine: imported when called, so that
        # kinelab.model itself depends on nothing above it
        from kinelab.kinematics import pose
        return pose(self, q)

    # -- plain data ---------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """Plain data (SI units), the inverse of :meth:`from_dict`."""
        def clean(d: dict) -> dict:
            return {k: (list(v) if isinstance(v, tuple) else v)
                    for k, v in d.items() if v is not None and v is not False}
        out: dict[str, Any] = {"name": self.name, "space": self.space}
        out["points"] = {p.name: ([p.x, p.y] if self.space == "planar" else [p.x, p.y, p.z])
                         for p in self.points}
        out["links"] = [clean(vars(link) | {"points": list(link.points)}
                              | ({"local": {k: list(v) for k, v in link.local.items()}}
                                 if link.local else {}))
                        for link in self.links]
        out["joints"] = [clean(dict(vars(j))) for j in self.joints]
        out["inputs"] = [clean({k: v for k, v in vars(i).items()
                                if not (k in ("speed", "acceleration") and v == 0.0)})
                         for i in self.inputs]
        if self.parameters:
            out["parameters"] = dict(self.parameters)
        return out

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Mechanism:
        """Build a mechanism from plain data in SI units (the output of :meth:`to_dict`)."""
        def tup(v):
            return tuple(v) if isinstance(v, (list, tuple)) else v
        try:
            points = tuple(Point(name, *map(float, xyz)) for name, xyz in data["points"].items())
            links = tuple(Link(**{k: tup(v) for k, v in d.items()}) for d in data["links"])
            joints = tuple(Joint(**{k: tup(v) for k, v in d.items()}) for d in data["joints"])
            inputs = tuple(Input(**{k: tup(v) for k, v in d.items()})
                           for d in data.get("inputs", ()))
        except (KeyError, TypeError, AttributeError) as exc:
            raise ModelError(f"malformed mechanism data: {exc}") from None
        return cls(name=data.get("name", "mechanism"), points=points, links=links,
                   joints=joints, inputs=inputs, space=data.get("space", "planar"),
                   parameters=data.get("parameters", {}))

    def __repr__(self) -> str:
        return (f"Mechanism('{self.name}', {len(self.links)} links, {len(self.joints)} joints, "
                f"inputs={list(self.input_names)})")


def _lookup(items: Sequence, name: str, kind: str):
    for item in items:
        if item.name == name:
            return item
    names = [i.name for i in items]
    raise ModelError(f"{kind} '{name}' not found{suggest(name, names)}; "
                     f"the {kind}s are {quoted(names)}")


def _validate(m: Mechanism) -> list[str]:
    """Every problem of the model, each as a one-line message naming the item."""
    problems: list[str] = []
    add = problems.append
    if m.space not in SPACES:
        add(f"space: expected one of {quoted(SPACES)}, got '{m.space}'")
    # -- names ---------------------------------------------------------------------------
    seen: dict[str, str] = {}
    for kind, items in (("point", m.points), ("link", m.links), ("joint", m.joints)):
        for item in items:
            if not isinstance(item.name, str) or not item.name:
                add(f"{kind}s: every {kind} needs a non-empty name, got {item.name!r}")
            elif item.name in seen:
                add(f"{kind} '{item.name}': name already used by a {seen[item.name]}; "
                    "names must be unique across points, links and joints")
            else:
                seen[item.name] = kind
    points = {p.name: p for p in m.points}
    links = {link.name: link for link in m.links}
    for p in m.points:
        if not all(isinstance(c, (int, float)) and math.isfinite(c) for c in (p.x, p.y, p.z)):
            add(f"point '{p.name}': coordinates must be finite numbers, got ({p.x}, {p.y}, {p.z})")
    # -- links ---------------------------------------------------------------------------
    grounds = [link.name for link in m.links if link.ground]
    if len(grounds) != 1:
        add(f"links: expected exactly one ground link, got {len(grounds)}"
            + (f" ({quoted(grounds)})" if grounds else "") + "; mark one link ground = true")
    sliding_links = {n for j in m.joints if j.type == "P" for n in j.links}
    for link in m.links:
        where = f"link '{link.name}'"
        for pn in link.points:
            if pn not in points:
                add(f"{where}: points: expected a declared point, got '{pn}'{suggest(pn, points)}; "
                    f"declared points are {quoted(points)}")
        if len(set(link.points)) != len(link.points):
            add(f"{where}: points: a point is listed twice")
        if len(link.points) == 0:
            add(f"{where}: points: a link must carry at least one point")
        elif len(link.points) < 2 and not link.ground and link.name not in sliding_links:
            add(f"{where}: points: a moving link needs at least two points (one is enough for a "
                "link of a prismatic joint, whose axis gives its direction); add a second point")
        elif len(link.points) >= 2 and all(p in points for p in link.points[:2]):
            a, b = points[link.points[0]], points[link.points[1]]
            if math.dist((a.x, a.y, a.z), (b.x, b.y, b.z)) <= _LENGTH_TOL:
                add(f"{where}: its first two points '{a.name}' and '{b.name}' coincide, so the link "
                    "has no length and no direction; move one of them")
        for attr, label in ((link.mass, "mass"), (link.inertia, "inertia"), (link.length, "length")):
            if attr is not None and not (_is_number(attr) and attr > 0 and math.isfinite(attr)):
                add(f"{where}: {label}: expected a positive number, got {attr!r}")
        if link.length is not None and len(link.points) < 2:
            add(f"{where}: length: a link with one point has no length; remove it")
        if link.local is not None:
            if not isinstance(link.local, Mapping):
                add(f"{where}: local: expected a mapping of point = (along, left), got "
                    f"{type(link.local).__name__}")
            else:
                for pn, v in link.local.items():
                    if pn not in link.points[2:]:
                        add(f"{where}: local: expected one of the link's points after its first two "
                            f"({quoted(link.points[2:]) or 'none'}), got {pn!r}")
                    elif not (isinstance(v, tuple) and len(v) == 2 and all(
                            _is_number(c) and math.isfinite(c) for c in v)):
                        add(f"{where}: local.{pn}: expected two finite numbers (along, left), got {v!r}")
        if link.center_of_mass is not None and link.center_of_mass not in link.points:
            add(f"{where}: center_of_mass: expected one of the link's points "
                f"{quoted(link.points)}, got '{link.center_of_mass}'")
    # -- joints --------------------------------------------------------------------------
    for j in m.joints:
        where = f"joint '{j.name}'"
        jt = JOINT_TYPES.get(j.type)
        if jt is None:
            add(f"{where}: type: expected one of {quoted(JOINT_TYPES)}, got '{j.type}'"
                f"{suggest(str(j.type), JOINT_TYPES)}")
            continue
        if m.space == "planar" and not jt.planar:
            add(f"{where}: a {j.type} joint ({jt.description}) cannot join links of a planar "
                "mechanism; use space = 'spatial'")
        if len(j.links) != 2:
            add(f"{where}: links: expected two links, got {len(j.links)}")
            continue
        a, b = j.links
        bad = [n for n in (a, b) if n not in links]
        for n in bad:
            add(f"{where}: links: expected a declared link, got '{n}'{suggest(n, links)}; "
                f"declared links are {quoted(links)}")
        if a == b:
            add(f"{where}: joins link '{a}' to itself; a joint joins two different links")
        if bad or a == b:
            continue
        if jt.needs_point and j.point is None:
            add(f"{where}: point: a {j.type} joint needs the point where it acts")
        if j.point is not None:
            if j.point not in points:
                add(f"{where}: point: expected a declared point, got '{j.point}'"
                    f"{suggest(j.point, points)}")
            elif j.type in ("R", "S", "U") and not all(j.point in links[n].points for n in (a, b)):
                missing = [n for n in (a, b) if j.point not in links[n].points]
                add(f"{where}: point '{j.point}' must be carried by both links it joins; add it "
                    f"to the points of {quoted(missing)}")
            elif j.type == "P" and j.point not in links[b].points:
                add(f"{where}: point '{j.point}' must be carried by the slider '{b}' (the second "
                    "link of a prismatic joint)")
        if jt.needs_axis:
            axis = j.axis
            dim = 2 if m.space == "planar" else 3
            if axis is None:
                add(f"{where}: axis: a {j.type} joint needs an axis")
            elif (len(axis) != dim or not all(isinstance(c, (int, float)) and math.isfinite(c)
                                              for c in axis)):
                add(f"{where}: axis: expected {dim} finite numbers, got {list(axis)}")
            elif math.hypot(*axis) <= 1e-12:
                add(f"{where}: axis: must not be the zero vector")
        if j.type == "P" and j.origin is not None and j.origin not in links[a].points:
            add(f"{where}: origin: expected a point of the guide '{a}' "
                f"({quoted(links[a].points)}), got '{j.origin}'")
        if j.offset is not None:
            if j.type != "P":
                add(f"{where}: offset: only a prismatic joint has one (the distance of its slide "
                    "line from its origin); remove it")
            elif not (_is_number(j.offset) and math.isfinite(j.offset)):
                add(f"{where}: offset: expected a finite number, got {j.offset!r}")
    # -- points shared by links must be hinged together ----------------------------------
    for p in m.points:
        carriers = [link.name for link in m.links if p.name in link.points]
        if len(carriers) < 2:
            continue
        hinged = [j.links for j in m.joints
                  if j.point == p.name and j.type in ("R", "S", "U") and all(n in links for n in j.links)]
        if _components(carriers, hinged) > 1:
            add(f"point '{p.name}': carried by {quoted(carriers)}, which are not all joined by "
                f"revolute joints at '{p.name}'; add the joints or give each link its own point")
    # -- inputs --------------------------------------------------------------------------
    joints = {j.name: j for j in m.joints}
    for k, inp in enumerate(m.inputs):
        where = f"inputs[{k}]"
        if (inp.joint is None) == (inp.links is None):
            add(f"{where}: give either a joint or a pair of links")
            continue
        if inp.joint is not None:
            j = joints.get(inp.joint)
            if j is None:
                add(f"{where}: joint: expected a declared joint, got '{inp.joint}'"
                    f"{suggest(inp.joint, joints)}; declared joints are {quoted(joints)}")
            elif j.type not in ("R", "P"):
                add(f"{where}: joint '{inp.joint}' is a {j.type} joint; an input drives an R "
                    "(angle) or P (slide) joint")
        else:
            if len(inp.links) != 2 or inp.links[0] == inp.links[1]:
                add(f"{where}: links: expected two different links, got {list(inp.links)}")
            for n in inp.links:
                if n not in links:
                    add(f"{where}: links: expected a declared link, got '{n}'{suggest(n, links)}")
        if inp.range is not None:
            r = inp.range
            if len(r) != 2 or not all(isinstance(v, (int, float)) and math.isfinite(v) for v in r):
                add(f"{where}: range: expected two finite numbers (start, stop), got {r!r}")
            elif r[0] == r[1]:
                add(f"{where}: range: start and stop are equal ({r[0]}); give an interval")
        for label in ("speed", "acceleration"):
            v = getattr(inp, label)
            if not (isinstance(v, (int, float)) and math.isfinite(v)):
                add(f"{where}: {label}: expected a finite number, got {v!r}")
    labels = [i.label for i in m.inputs]
    for name in {n for n in labels if labels.count(n) > 1}:
        add(f"inputs: two inputs are both named '{name}'; give them distinct names")
    # -- connectivity --------------------------------------------------------------------
    if not problems and m.links:
        pairs = [j.links for j in m.joints]
        if _components(list(links), pairs) > 1:
            reach = _reachable(m.ground.name, pairs) if len(grounds) == 1 else set()
            loose = [n for n in links if n not in reach]
            add(f"links {quoted(loose)} are not connected to the ground by any chain of joints; "
                "join them or remove them")
    return problems


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _components(nodes: list[str], edges: Iterable[tuple[str, str]]) -> int:
    parent = {n: n for n in nodes}

    def find(n):
        while parent[n] != n:
            parent[n] = parent[parent[n]]
            n = parent[n]
        return n
    for a, b in edges:
        if a in parent and b in parent:
            parent[find(a)] = find(b)
    return len({find(n) for n in nodes})


def _reachable(start: str, edges: Sequence[tuple[str, str]]) -> set[str]:
    seen, todo = {start}, [start]
    while todo:
        n = todo.pop()
        for a, b in edges:
            for x, y in ((a, b), (b, a)):
                if x == n and y not in seen:
                    seen.add(y)
                    todo.append(y)
    return seen
