"""What a mechanism *is*: named points, links carrying them, joints and inputs.

Plain, validated, immutable data.  Everything is in SI units (m, rad, kg).  The point
positions are a *sketch*: one assembled configuration of the mechanism, which fixes
every link's geometry and the assembly mode (branch) the analysis follows.
"""
from __future__ import annotations

import math
import numbers
from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Literal

import numpy as np

from kinelab.errors import PROBLEMS_SHOWN, ModelError, describe, quoted, shown, suggest
from kinelab.model._cams import cam_problems
from kinelab.model._gears import GEAR_FIELDS, gear_problems
from kinelab.model._joints import JOINT_TYPES
from kinelab.model._places import place_problems
from kinelab.model._values import (MAX_INERTIA, MAX_MASS, is_real, length_problem, name_problem,
                                   range_problem, rate_problem, real, size_problems)

__all__ = ["Point", "Link", "Joint", "Input", "Mechanism", "SPACES"]

SPACES = ("planar", "spherical", "spatial")
_LENGTH_TOL = 1e-12  # two sketch points closer than this (m) are the same place


# A model keeps its numbers as Python floats, whatever they were given as (an int, a
# Fraction, a numpy number): the engine computes with floats, and a Fraction or an object
# array would reach numpy's linear algebra.  What is not a real number is kept as given, for
# the model's check to name it.
def _float(value: Any) -> Any:
    x = real(value)
    return value if x is None else x


def _floats(value: Any) -> Any:
    if isinstance(value, (tuple, list)) and all(is_real(v) for v in value):
        return tuple(float(v) for v in value)
    return value


def _set(item: Any, **values: Any) -> None:
    for attr, value in values.items():
        object.__setattr__(item, attr, value)


@dataclass(frozen=True)
class Point:
    """A named point, at its sketch position (m).

    ``z`` is zero for planar mechanisms.
    """

    name: str
    x: float
    y: float
    z: float = 0.0

    def __post_init__(self):
        _set(self, x=_float(self.x), y=_float(self.y), z=_float(self.z))

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
        configuration at the sketch's inputs and on its branch (``kinelab.load`` does so
        for model files; :meth:`Mechanism.with_dimensions` changes it on an assembled
        mechanism).
    local : mapping of str to (float, float), optional
        The exact place of some of its other points in its own frame, m: along the
        direction from its first point to its second, and to the left of it, from the
        first point (as ``fourbar``'s ``coupler_point``).
    sides : mapping of str to mapping, optional
        The exact place of some of its other points by the sides of a triangle: point =
        ``{A: distance, B: distance, "side": "left" or "right"}``, m, the distances from two
        points of the link placed before it (its first two, or points listed before it in
        ``points``), and the side of the line from the one of the two listed first in
        ``points`` to the other.  ``side`` may be left out only for a flat triangle (the
        point on the line of the two).  The place is worked out by the law of cosines
        (:func:`kinelab.model.exact_places`).  Points the link carries that are in neither
        ``local`` nor ``sides`` keep their place relative to the first two as the sketch
        draws it.
    """

    name: str
    points: tuple[str, ...]
    ground: bool = False
    mass: float | None = None
    center_of_mass: str | None = None
    inertia: float | None = None
    length: float | None = None
    local: Mapping[str, tuple[float, float]] | None = field(default=None, hash=False)
    sides: Mapping[str, Mapping[str, float | str]] | None = field(default=None, hash=False)

    def __post_init__(self):
        if self.local is not None and isinstance(self.local, Mapping):
            object.__setattr__(self, "local", {k: _floats(tuple(v)) if isinstance(v, (list, tuple))
                                               else v for k, v in self.local.items()})
        if isinstance(self.sides, Mapping):
            object.__setattr__(self, "sides", {
                p: {k: v if k == "side" else _float(v) for k, v in spec.items()}
                if isinstance(spec, Mapping) else spec for p, spec in self.sides.items()} or None)
        _set(self, mass=_float(self.mass), inertia=_float(self.inertia),
             length=_float(self.length),
             ground=bool(self.ground) if isinstance(self.ground, np.bool_) else self.ground)


@dataclass(frozen=True)
class Joint:
    """A kinematic pair joining two links.

    Parameters
    ----------
    name : str
    type : str
        One of ``kinelab.model.JOINT_TYPES`` (``"R"``, ``"P"``, ``"C"``, ``"U"``, ``"S"``,
        ``"H"``, ``"E"``, ``"cam"``, ``"gear"``, ``"G"``, ``"rolling"``, ``"pin_in_slot"``).
        ``"G"`` is a gear pair the planar engine solves (see ``mesh`` ... ``carrier``).
        ``"C"`` is a cylindrical pair in space, and in a planar mechanism a cam and its
        follower, which the planar engine solves (see ``program``).
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
    mesh : {'external', 'internal', 'rack'}, optional
        Gear joints (``G``): the kind of pair, ``'external'`` by default.  ``links = (a, b)``
        are the two gears (a rack and pinion: the pinion, then the rack).
    ratio : float, optional
        Gear joints: the gear ratio ``N_b / N_a`` (= ``r_b / r_a``), positive.  A spur pair
        gives one of ``ratio``, ``radii`` and ``teeth``.
    radii : (float, float), optional
        Gear joints: the pitch radii ``(r_a, r_b)``, m.
    teeth : (int, int), optional
        Gear joints: the numbers of teeth ``(N_a, N_b)``.
    radius : float, optional
        Rack and pinion: the pinion's pitch radius, m (the rack's advance per radian).
    carrier : str, optional
        Gear joints: the link carrying both axes (default the ground; the arm of an
        epicyclic train).  Both gears turn on it in R joints (a rack slides on it in a P
        joint), and ``(theta_a - theta_c) r_a = -(theta_b - theta_c) r_b`` (external; ``+``
        internal; rack ``s = r (theta_a - theta_c)`` from the sketch, a counter-clockwise
        pinion driving the rack along its joint's ``+axis``): see :mod:`kinelab.model._gears`.
        Cam joints: the guide, the link both the cam and its follower are jointed to
        (default the ground).
    program : kinelab.cams.MotionProgram, optional
        Cam joints (``C`` in a planar mechanism, ``links = (cam, follower)``): the follower's
        displacement relative to the guide, its slide along its P joint (m) or its angle
        about its R joint (rad), is ``program``'s S at the cam's angle relative to the
        guide, plus its place where S = 0 (from the sketch): see :mod:`kinelab.model._cams`.
        Plain data (``program.to_dict()``) is accepted too.
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
    mesh: str | None = None
    ratio: float | None = None
    radii: tuple[float, float] | None = None
    teeth: tuple[int, int] | None = None
    radius: float | None = None
    carrier: str | None = None
    program: Any = field(default=None, hash=False)

    def __post_init__(self):
        if isinstance(self.program, Mapping):
            from kinelab.cams import MotionProgram     # plain data (to_dict) made a program
            try:
                object.__setattr__(self, "program", MotionProgram.from_dict(self.program))
            except ModelError as exc:
                raise ModelError([f"joint {shown(self.name)}: program: {p}"
                                  for p in exc.problems]) from None
        _set(self, axis=_floats(self.axis), axis2=_floats(self.axis2), pitch=_float(self.pitch),
             offset=_float(self.offset), ratio=_float(self.ratio), radii=_floats(self.radii),
             radius=_float(self.radius),
             teeth=tuple(self.teeth) if isinstance(self.teeth, list) else self.teeth)


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

    def __post_init__(self):
        _set(self, range=_floats(self.range), speed=_float(self.speed),
             acceleration=_float(self.acceleration))

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
        problems = []
        for attr, cls in (("points", "Point"), ("links", "Link"), ("joints", "Joint"),
                          ("inputs", "Input")):
            value = getattr(self, attr)
            if isinstance(value, (str, bytes, Mapping)) or not isinstance(value, Iterable):
                problems.append(f"{attr}: expected a sequence of {cls} objects, got "
                                f"{describe(value)}")
                value = ()
            object.__setattr__(self, attr, tuple(value))
        if not isinstance(self.parameters, Mapping):
            problems.append(f"parameters: expected a mapping of name = value, got "
                            f"{describe(self.parameters)}")
            object.__setattr__(self, "parameters", {})
        object.__setattr__(self, "parameters", {
            k: float(v) if isinstance(v, numbers.Real) and not isinstance(v, numbers.Integral)
            and is_real(v) else v for k, v in self.parameters.items()})
        problems = problems or _validate(self)
        if problems:
            raise ModelError(problems, source=f"mechanism {shown(self.name)}")

    # -- lookup by name ---------------------------------------------------------------
    # by dictionaries built once: a model of many points looks each up in constant time
    @cached_property
    def _by_name(self) -> dict[str, dict[str, Any]]:
        return {kind: {item.name: item for item in reversed(items)}
                for kind, items in (("point", self.points), ("link", self.links),
                                    ("joint", self.joints))}

    def point(self, name: str) -> Point:
        return _lookup(self._by_name["point"], name, "point")

    def link(self, name: str) -> Link:
        return _lookup(self._by_name["link"], name, "link")

    def joint(self, name: str) -> Joint:
        return _lookup(self._by_name["joint"], name, "joint")

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
        return self._around[0].get(point, ())

    def joints_of(self, link: str) -> tuple[Joint, ...]:
        """The joints that touch ``link``."""
        return self._around[1].get(link, ())

    @cached_property
    def _around(self) -> tuple[dict[str, tuple[str, ...]], dict[str, tuple[Joint, ...]]]:
        """(point -> links carrying it, link -> joints touching it), built once."""
        carriers: dict[str, list[str]] = {}
        for link in self.links:
            for p in dict.fromkeys(link.points):
                carriers.setdefault(p, []).append(link.name)
        touching: dict[str, list[Joint]] = {}
        for j in self.joints:
            for n in dict.fromkeys(j.links):
                touching.setdefault(n, []).append(j)
        return ({k: tuple(v) for k, v in carriers.items()},
                {k: tuple(v) for k, v in touching.items()})

    # -- poses --------------------------------------------------------------------------
    def at(self, q) -> Mechanism:
        """The same mechanism sketched at input ``q`` (rad or m; shape () or (M,)), on the
        branch its analysis follows there: :func:`kinelab.kinematics.pose`."""
        # the one method of the model that needs the engine: imported when called, so that
        # kinelab.model itself depends on nothing above it
        from kinelab.kinematics import pose
        return pose(self, q)

    def _moved(self, points: tuple[Point, ...], joints: tuple[Joint, ...]) -> Mechanism:
        """The same mechanism with its points moved (the same names, in order) and its joints'
        axes turned: what assembly makes of it.  Only the new coordinates are checked (the
        rest is this checked mechanism's)."""
        problems = [f"point {shown(p.name)}: coordinates: {why}, got ({p.x:g}, {p.y:g}) m"
                    for p in points for why in [next(filter(None, (
                        length_problem(c, positive=False) if is_real(c) else "expected finite numbers"
                        for c in (p.x, p.y))), None)] if why]
        if problems or [p.name for p in points] != list(self.point_names) or len(joints) != len(self.joints):
            return Mechanism(self.name, points, self.links, joints, self.inputs, self.space,
                             self.parameters)
        out = object.__new__(Mechanism)
        for f in ("name", "links", "inputs", "space", "parameters"):
            object.__setattr__(out, f, getattr(self, f))
        object.__setattr__(out, "points", tuple(points))
        object.__setattr__(out, "joints", tuple(joints))
        return out

    # -- edits ----------------------------------------------------------------------------
    def with_dimensions(self, *, lengths: Mapping[str, float] | None = None,
                        local: Mapping[str, Mapping[str, tuple[float, float]]] | None = None,
                        offsets: Mapping[str, float] | None = None,
                        pivots: Mapping[str, tuple[float, float]] | None = None) -> Mechanism:
        """The same mechanism with some dimensions changed, assembled again at its inputs
        and on its branch: :func:`kinelab.kinematics.reassemble`.

        Parameters
        ----------
        lengths : mapping of str to float, optional
            Links' new lengths (first two points), m; the ground's moves its second point.
        local : mapping of str to mapping of str to (float, float), optional
            ``{link: {point: (along, left)}}``: new places of links' other points, m.
        offsets : mapping of str to float, optional
            Prismatic joints' new offsets, m.
        pivots : mapping of str to (float, float), optional
            The ground's points' new places, m.

        Returns
        -------
        Mechanism
            With the new dimensions declared (``length``, ``local``, ``offset``) and its
            points at the configuration continued from this one: every input keeps its
            value and every dyad its side.  Where that side no longer exists at the inputs,
            the nearest other assembly is taken and a warning names the dyads that changed.

        Raises
        ------
        AssemblyError
            No configuration has these dimensions at these inputs: the message says which
            loop, by how much it misses, where the inputs reach and which value would close
            it.
        ModelError
            An unknown name or a value that is not a length, place or offset.

        Examples
        --------
        >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
        >>> longer = fb.with_dimensions(lengths={"crank": 1.5})
        >>> round(math.dist(longer.point("O2").xy, longer.point("A").xy), 12)
        1.5
        >>> bool(np.allclose(np.arctan2(*longer.point("A").xy[::-1]),
        ...                  np.arctan2(*fb.point("A").xy[::-1]), rtol=0, atol=1e-12))
        True
        """
        # the edit needs the assembly of the kinematics room: imported when called, so that
        # kinelab.model itself depends on nothing above it (as in `at`)
        import warnings

        from kinelab.kinematics import reassemble
        done = reassemble(self, lengths=lengths, local=local, offsets=offsets, pivots=pivots)
        if done.switched:
            warnings.warn(f"'{self.name}': at its inputs these dimensions close only in another "
                          f"assembly mode of {', '.join(done.switched)}: assembled there",
                          UserWarning, stacklevel=2)
        return done.mechanism

    def with_lengths(self, lengths: Mapping[str, float] | None = None, /,
                     **more: float) -> Mechanism:
        """:meth:`with_dimensions` with new lengths only: ``m.with_lengths(coupler=0.25)`` or
        ``m.with_lengths({"coupler": 0.25})``, m.

        Examples
        --------
        >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
        >>> m = fb.with_lengths(rocker=2.0)
        >>> round(math.dist(m.point("O4").xy, m.point("B").xy), 12), m.link("rocker").length
        (2.0, 2.0)
        """
        if lengths is not None and not isinstance(lengths, Mapping):
            raise ModelError(f"lengths: expected a mapping of link names to lengths (m), got "
                             f"{describe(lengths)}")
        return self.with_dimensions(lengths={**(lengths or {}), **more})

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
                                 if link.local else {})
                              | ({"sides": {k: dict(v) for k, v in link.sides.items()}}
                                 if link.sides else {}))
                        for link in self.links]
        out["joints"] = [clean(dict(vars(j)) | ({"program": j.program.to_dict()}
                                                if hasattr(j.program, "to_dict") else {}))
                         for j in self.joints]
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
            points = tuple(Point(name, *xyz) for name, xyz in data["points"].items())
            links = tuple(Link(**{k: tup(v) for k, v in d.items()}) for d in data["links"])
            joints = tuple(Joint(**{k: tup(v) for k, v in d.items()}) for d in data["joints"])
            inputs = tuple(Input(**{k: tup(v) for k, v in d.items()})
                           for d in data.get("inputs", ()))
        except (KeyError, TypeError, AttributeError) as exc:
            raise ModelError(f"malformed mechanism data: {describe(str(exc))}") from None
        return cls(name=data.get("name", "mechanism"), points=points, links=links,
                   joints=joints, inputs=inputs, space=data.get("space", "planar"),
                   parameters=data.get("parameters", {}))

    def __repr__(self) -> str:
        return (f"Mechanism('{self.name}', {len(self.links)} links, {len(self.joints)} joints, "
                f"inputs={list(self.input_names)})")


def _lookup(items: Mapping[str, Any], name: str, kind: str):
    try:
        return items[name]
    except (KeyError, TypeError):
        pass
    raise ModelError(f"{kind} {shown(name)} not found{suggest(name, items)}; "
                     f"the {kind}s are {quoted(items)}")


def _validate(m: Mechanism) -> list[str]:
    """Every problem of the model, each as a one-line message naming the item.

    Linear in the size of the model: every lookup goes through a dictionary or a set."""
    problems: list[str] = []
    add = problems.append

    def hint(name, choices) -> str:
        # "did you mean" compares a name with every choice: only for the problems shown
        return suggest(name, choices) if len(problems) < PROBLEMS_SHOWN else ""

    if not isinstance(m.space, str) or m.space not in SPACES:
        add(f"space: expected one of {quoted(SPACES)}, got {describe(m.space)}")
    if (why := name_problem(m.name)) is not None:
        add(f"name: {why}, got {describe(m.name)}")
    problems.extend(size_problems(points=len(m.points), links=len(m.links), joints=len(m.joints)))
    if problems:
        return problems
    # -- types and names -----------------------------------------------------------------
    seen: dict[str, str] = {}
    for kind, items, cls in (("point", m.points, Point), ("link", m.links, Link),
                             ("joint", m.joints, Joint), ("input", m.inputs, Input)):
        for item in items:
            if not isinstance(item, cls):
                add(f"{kind}s: expected {cls.__name__} objects, got {describe(item)}")
            elif kind == "input":
                continue
            elif (why := name_problem(item.name)) is not None:
                add(f"{kind}s: {why}, got {describe(item.name)}")
            elif item.name in seen:
                add(f"{kind} {shown(item.name)}: name already used by a {seen[item.name]}; "
                    "names must be unique across points, links and joints")
            else:
                seen[item.name] = kind
    if problems:
        return problems      # what follows reads names and fields of well-formed items
    points = {p.name: p for p in m.points}
    links = {link.name: link for link in m.links}
    placed = set()                           # points whose coordinates are usable
    for p in m.points:
        xyz = (p.x, p.y, p.z)
        if not all(is_real(c) for c in xyz):
            add(f"point {shown(p.name)}: coordinates must be finite numbers, got "
                f"({', '.join(describe(c) for c in xyz)})")
        elif (why := next(filter(None, (length_problem(c, positive=False) for c in xyz)), None)):
            add(f"point {shown(p.name)}: coordinates: {why}, got ({p.x:g}, {p.y:g}, {p.z:g}) m")
        else:
            placed.add(p.name)
            if m.space == "planar" and p.z != 0.0:
                add(f"point {shown(p.name)}: z: expected 0 in a planar mechanism, got {p.z:g} m; "
                    "remove z, or use space = 'spatial'")
    # -- links ---------------------------------------------------------------------------
    grounds = [link.name for link in m.links if link.ground is True]
    if len(grounds) != 1:
        add(f"links: expected exactly one ground link, got {len(grounds)}"
            + (f" ({quoted(grounds)})" if grounds else "") + "; mark one link ground = true")
    # the links of prismatic joints, of those whose links are well formed (checked below)
    sliding_links = {n for j in m.joints if j.type == "P" and isinstance(j.links, (tuple, list))
                     for n in j.links if isinstance(n, str)}
    carriers: dict[str, list[str]] = {}      # point -> the links that carry it
    carried: set[tuple[str, str]] = set()     # (point, link) for each point a link carries
    for link in m.links:
        where = f"link {shown(link.name)}"
        if not isinstance(link.ground, bool):
            add(f"{where}: ground: expected true or false, got {describe(link.ground)}")
        if not isinstance(link.points, (tuple, list)) or not all(isinstance(pn, str)
                                                                   for pn in link.points):
            add(f"{where}: points: expected a tuple of point names, got {describe(link.points)}")
            continue
        for pn in link.points:
            if pn not in points:
                add(f"{where}: points: expected a declared point, got {shown(pn)}"
                    f"{hint(pn, points)}; declared points are {quoted(points)}")
            else:
                carriers.setdefault(pn, []).append(link.name)
                carried.add((pn, link.name))
        if len(set(link.points)) != len(link.points):
            add(f"{where}: points: a point is listed twice")
        if len(link.points) == 0:
            add(f"{where}: points: a link must carry at least one point")
        elif len(link.points) < 2 and not link.ground and link.name not in sliding_links:
            add(f"{where}: points: a moving link needs at least two points (one is enough for a "
                "link of a prismatic joint, whose axis gives its direction); add a second point")
        elif len(link.points) >= 2 and all(p in placed for p in link.points[:2]):
            a, b = points[link.points[0]], points[link.points[1]]
            if math.dist((a.x, a.y, a.z), (b.x, b.y, b.z)) <= _LENGTH_TOL:
                add(f"{where}: its first two points {shown(a.name)} and {shown(b.name)} coincide, "
                    "so the link has no length and no direction; move one of them")
        for attr, label in ((link.mass, "mass"), (link.inertia, "inertia"), (link.length, "length")):
            if attr is not None and not (is_real(attr) and attr > 0):
                add(f"{where}: {label}: expected a positive number, got {describe(attr)}")
            elif label == "length" and attr is not None and (why := length_problem(float(attr))):
                add(f"{where}: length: {why}, got {float(attr):g} m")
            elif label != "length" and attr is not None and attr > (limit := {
                    "mass": MAX_MASS, "inertia": MAX_INERTIA}[label]):
                add(f"{where}: {label}: expected at most {limit:g} (SI), got {float(attr):g}")
        if link.length is not None and len(link.points) < 2:
            add(f"{where}: length: a link with one point has no length; remove it")
        if link.local is not None:
            if not isinstance(link.local, Mapping):
                add(f"{where}: local: expected a mapping of point = (along, left), got "
                    f"{describe(link.local)}")
            else:
                rest = set(link.points[2:])
                for pn, v in link.local.items():
                    if pn not in rest:
                        add(f"{where}: local: expected one of the link's points after its first two "
                            f"({quoted(link.points[2:])}), got {describe(pn)}")
                    elif not (isinstance(v, tuple) and len(v) == 2 and all(map(is_real, v))):
                        add(f"{where}: local.{pn}: expected two finite numbers (along, left), got "
                            f"{describe(v)}")
                    elif (why := next(filter(None, (length_problem(float(c), positive=False)
                                                    for c in v)), None)):
                        add(f"{where}: local.{pn}: {why}, got {describe(v)}")
        for why in place_problems(link, {pn: points[pn].xy for pn in link.points if pn in placed}):
            add(f"{where}: {why}")
        if link.center_of_mass is not None and link.center_of_mass not in link.points:
            add(f"{where}: center_of_mass: expected one of the link's points "
                f"{quoted(link.points)}, got {describe(link.center_of_mass)}")
    # -- joints --------------------------------------------------------------------------
    hinged: dict[str, list[tuple[str, str]]] = {}    # point -> pairs of links pinned there
    for j in m.joints:
        where = f"joint {shown(j.name)}"
        jt = JOINT_TYPES.get(j.type) if isinstance(j.type, str) else None
        if jt is None:
            add(f"{where}: type: expected one of {quoted(JOINT_TYPES)}, got {describe(j.type)}"
                f"{hint(str(j.type), JOINT_TYPES)}")
            continue
        cam = j.type == "C" and m.space == "planar"     # C: a cam pair in the plane
        if m.space == "planar" and not jt.planar:
            add(f"{where}: a {j.type} joint ({jt.description}) cannot join links of a planar "
                "mechanism; use space = 'spatial'")
        if not isinstance(j.links, (tuple, list)) or len(j.links) != 2:
            add(f"{where}: links: expected two links, got {describe(j.links)}")
            continue
        a, b = j.links
        bad = [n for n in (a, b) if not isinstance(n, str) or n not in links]
        for n in bad:
            add(f"{where}: links: expected a declared link, got {describe(n)}{hint(n, links)}; "
                f"declared links are {quoted(links)}")
        if a == b:
            add(f"{where}: joins link {shown(a)} to itself; a joint joins two different links")
        if bad or a == b:
            continue
        if jt.needs_point and j.point is None and not cam:
            add(f"{where}: point: a {j.type} joint needs the point where it acts")
        if j.point is not None:
            if not isinstance(j.point, str) or j.point not in points:
                add(f"{where}: point: expected a declared point, got {describe(j.point)}"
                    f"{hint(j.point, points)}")
            elif j.type in ("R", "S", "U") and not all((j.point, n) in carried for n in (a, b)):
                missing = [n for n in (a, b) if (j.point, n) not in carried]
                add(f"{where}: point {shown(j.point)} must be carried by both links it joins; add "
                    f"it to the points of {quoted(missing)}")
            elif j.type == "P" and (j.point, b) not in carried:
                add(f"{where}: point {shown(j.point)} must be carried by the slider {shown(b)} "
                    "(the second link of a prismatic joint)")
            elif j.type in ("R", "S", "U"):
                hinged.setdefault(j.point, []).append((a, b))
        if cam and (j.point is not None or j.axis is not None):
            add(f"{where}: {'point' if j.point is not None else 'axis'}: a cam joint's contact "
                "moves along the cam; remove it (the cam and the follower's own joints place "
                "them)")
        elif jt.needs_axis and not cam:
            axis = j.axis
            dim = 2 if m.space == "planar" else 3
            if axis is None:
                add(f"{where}: axis: a {j.type} joint needs an axis")
            elif (not isinstance(axis, (tuple, list)) or len(axis) != dim
                  or not all(map(is_real, axis))):
                add(f"{where}: axis: expected {dim} finite numbers, got {describe(axis)}")
            elif math.hypot(*axis) <= 1e-12:
                add(f"{where}: axis: must not be the zero vector")
            elif max(abs(c) for c in axis) > 1e100:
                add(f"{where}: axis: expected a direction whose components are at most 1e100 in "
                    f"size (only its direction counts), got {describe(axis)}; scale it down")
        if j.type == "P" and j.origin is not None and (not isinstance(j.origin, str)
                                                       or (j.origin, a) not in carried):
            add(f"{where}: origin: expected a point of the guide {shown(a)} "
                f"({quoted(links[a].points)}), got {describe(j.origin)}")
        if j.pitch is not None and not is_real(j.pitch):
            add(f"{where}: pitch: expected a finite number, got {describe(j.pitch)}")
        if j.offset is not None:
            if j.type != "P":
                add(f"{where}: offset: only a prismatic joint has one (the distance of its slide "
                    "line from its origin); remove it")
            elif not is_real(j.offset):
                add(f"{where}: offset: expected a finite number, got {describe(j.offset)}")
            elif why := length_problem(float(j.offset), positive=False):
                add(f"{where}: offset: {why}, got {float(j.offset):g} m")
        if j.type == "G":
            if m.space != "planar":
                add(f"{where}: a G joint (gear pair of the planar engine) needs space = "
                    "'planar'; count a spatial mechanism's gear mesh with type 'gear'")
            elif len(grounds) == 1:
                problems.extend(gear_problems(m, j, links))
        elif cam:
            if len(grounds) == 1:
                problems.extend(cam_problems(m, j, links))
            for f in GEAR_FIELDS[:-1]:
                if getattr(j, f) is not None:
                    add(f"{where}: {f}: only a gear joint (type 'G') has one; remove it")
        else:
            for f in GEAR_FIELDS:
                if getattr(j, f) is not None:
                    add(f"{where}: {f}: only a gear joint (type 'G') or a cam joint's guide (type "
                        "'C') has one; remove it" if f == "carrier" else
                        f"{where}: {f}: only a gear joint (type 'G') has one; remove it")
        if j.program is not None and not cam:
            add(f"{where}: program: only a cam joint (type 'C' in a planar mechanism) has one; "
                "remove it")
    # -- points shared by links must be hinged together ----------------------------------
    for pn, on in carriers.items():
        if len(on) >= 2 and _components(on, hinged.get(pn, ())) > 1:
            add(f"point {shown(pn)}: carried by {quoted(on)}, which are not all joined by "
                f"revolute joints at {shown(pn)}; add the joints or give each link its own point")
    # -- inputs --------------------------------------------------------------------------
    joints = {j.name: j for j in m.joints}
    for k, inp in enumerate(m.inputs):
        where = f"inputs[{k}]"
        if (inp.joint is None) == (inp.links is None):
            add(f"{where}: give either a joint or a pair of links")
            continue
        slide = False
        if inp.joint is not None:
            j = joints.get(inp.joint) if isinstance(inp.joint, str) else None
            if j is None:
                add(f"{where}: joint: expected a declared joint, got {describe(inp.joint)}"
                    f"{hint(inp.joint, joints)}; declared joints are {quoted(joints)}")
            elif j.type not in ("R", "P"):
                add(f"{where}: joint {shown(inp.joint)} is a {j.type} joint; an input drives an R "
                    "(angle) or P (slide) joint")
            slide = j is not None and j.type == "P"
        elif (not isinstance(inp.links, (tuple, list)) or len(inp.links) != 2
              or inp.links[0] == inp.links[1]):
            add(f"{where}: links: expected two different links, got {describe(inp.links)}")
        else:
            for n in inp.links:
                if not isinstance(n, str) or n not in links:
                    add(f"{where}: links: expected a declared link, got {describe(n)}"
                        f"{hint(n, links)}")
        if inp.name is not None and (why := name_problem(inp.name)):
            add(f"{where}: name: {why}, got {describe(inp.name)}")
        if inp.range is not None:
            r = inp.range
            if not isinstance(r, (tuple, list)) or len(r) != 2 or not all(map(is_real, r)):
                add(f"{where}: range: expected two finite numbers (start, stop), got {describe(r)}")
            elif r[0] == r[1]:
                add(f"{where}: range: start and stop are equal ({float(r[0]):g}); give an interval")
            elif why := range_problem(float(r[0]), float(r[1]), angle=not slide):
                add(f"{where}: range: {why}, got ({float(r[0]):g}, {float(r[1]):g}) "
                    f"{'m' if slide else 'rad'}")
        for label, unit in (("speed", "/s"), ("acceleration", "/s^2")):
            v = getattr(inp, label)
            unit = ("m" if slide else "rad") + unit
            if not is_real(v):
                add(f"{where}: {label}: expected a finite number, got {describe(v)}")
            elif why := rate_problem(float(v), unit):
                add(f"{where}: {label}: {why}, got {float(v):g} {unit}")
    if not problems:
        for name, n in Counter(i.label for i in m.inputs).items():
            if n > 1:
                add(f"inputs: two inputs are both named {shown(name)}; give them distinct names")
    # -- connectivity --------------------------------------------------------------------
    if not problems and m.links:
        pairs = [j.links for j in m.joints]
        if _components(list(links), pairs) > 1:
            reach = _reachable(m.ground.name, pairs) if len(grounds) == 1 else set()
            loose = [n for n in links if n not in reach]
            add(f"links {quoted(loose)} are not connected to the ground by any chain of joints; "
                "join them or remove them")
    return problems


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
    around: dict[str, list[str]] = {}
    for a, b in edges:
        around.setdefault(a, []).append(b)
        around.setdefault(b, []).append(a)
    seen, todo = {start}, [start]
    while todo:
        for y in around.get(todo.pop(), ()):
            if y not in seen:
                seen.add(y)
                todo.append(y)
    return seen
