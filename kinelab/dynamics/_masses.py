"""The mass distribution the dynamics uses: links with mass and inertia, point masses."""
from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from kinelab.errors import ModelError, describe, quoted, shown
from kinelab.model import MAX_INERTIA, MAX_MASS, Mechanism, is_real

__all__ = ["LinkMass", "PointMass", "MassProperties"]

_ON_LINE = 1e-9   # relative distance of a centre of mass off the line of a lumped link's ends


def items_of(value, name: str, kind: type) -> tuple:
    """``value`` as a tuple of ``kind``, or a :class:`ModelError` naming ``name`` (and the
    first entry that is not one)."""
    if isinstance(value, (str, bytes, Mapping)) or not isinstance(value, Iterable):
        raise ModelError(f"{name}: expected a sequence of kinelab.dynamics.{kind.__name__}, got "
                         f"{describe(value)}")
    items = tuple(value)
    for i, item in enumerate(items):
        if not isinstance(item, kind):
            raise ModelError(f"{name}[{i}]: expected a kinelab.dynamics.{kind.__name__}, got "
                             f"{describe(item)}")
    return items


def _positive(v, limit: float = MAX_MASS) -> bool:
    """A real number above 0 and at most ``limit`` (see ``kinelab.model.MAX_MASS``)."""
    return is_real(v) and 0 < v <= limit


@dataclass(frozen=True)
class LinkMass:
    """A link as a rigid body.

    Parameters
    ----------
    link : str
    mass : float
        kg, > 0.
    center_of_mass : str
        A point of the link at its centre of mass.
    inertia : float
        Moment of inertia about the centre of mass, kg m^2, >= 0 (zero only for a link that
        cannot turn, or a point mass riding the link).
    """

    link: str
    mass: float
    center_of_mass: str
    inertia: float

    def __post_init__(self):
        if not _positive(self.mass):
            raise ModelError(f"link '{self.link}': mass: expected a positive number (kg) up to "
                             f"{MAX_MASS:g}, got {describe(self.mass)}")
        if not (is_real(self.inertia) and 0 <= self.inertia <= MAX_INERTIA):
            raise ModelError(f"link '{self.link}': inertia: expected a number >= 0 (kg m^2) up to "
                             f"{MAX_INERTIA:g}, got {describe(self.inertia)}")


@dataclass(frozen=True)
class PointMass:
    """A lumped mass at a named point (no moment of inertia of its own).

    Parameters
    ----------
    point : str
    mass : float
        kg, > 0.
    link : str, optional
        The link whose free body carries it, for the joint reactions when the point is a
        joint of several links.  Default: the first moving link carrying the point.
    """

    point: str
    mass: float
    link: str | None = None

    def __post_init__(self):
        if not _positive(self.mass):
            raise ModelError(f"point mass at {shown(self.point)}: mass: expected a positive number (kg) "
                             f"up to {MAX_MASS:g}, got {describe(self.mass)}")


@dataclass(frozen=True)
class MassProperties:
    """Masses and inertias of a mechanism's moving parts.

    Usually read from the model's links (:meth:`from_model`); point masses and massless
    links are declared there too.  The lumped-mass models of the notes come from
    :meth:`lumped`.

    Attributes
    ----------
    links : tuple of LinkMass
    points : tuple of PointMass

    Examples
    --------
    >>> from kinelab.model import Mechanism, Point, Link, Joint, Input
    >>> m = Mechanism("pendulum", (Point("O", 0, 0), Point("G", 0.5, 0)),
    ...               (Link("ground", ("O",), ground=True),
    ...                Link("arm", ("O", "G"), mass=2.0, center_of_mass="G", inertia=0.1)),
    ...               (Joint("pivot", "R", ("ground", "arm"), point="O"),), (Input(joint="pivot"),))
    >>> MassProperties.from_model(m).total_mass
    2.0
    """

    links: tuple[LinkMass, ...] = ()
    points: tuple[PointMass, ...] = ()

    def __post_init__(self):
        object.__setattr__(self, "links", items_of(self.links, "links", LinkMass))
        object.__setattr__(self, "points", items_of(self.points, "points", PointMass))
        names = [b.link for b in self.links]
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise ModelError(f"links: {quoted(twice)} listed more than once; give each "
                             "link one LinkMass (add point masses for extra lumps)")

    @property
    def total_mass(self) -> float:
        """kg."""
        return float(sum(b.mass for b in self.links) + sum(p.mass for p in self.points))

    @classmethod
    def from_model(cls, model: Mechanism, *, massless: Iterable[str] = (),
                   point_masses: Mapping[str, float] | None = None) -> MassProperties:
        """The mass data of the model's links, checked as a whole.

        Every moving link needs ``mass``, ``center_of_mass`` and ``inertia`` (the inertia
        may be left out for a link that cannot turn, such as a piston), unless it is
        declared ``massless``.

        Parameters
        ----------
        model : Mechanism
        massless : iterable of str
            Moving links without mass (ideal, weightless bars).
        point_masses : mapping of str to float, optional
            Lumped masses (kg) at named points.

        Raises
        ------
        ModelError
            Listing every link with missing mass data, every unknown name and every
            non-positive mass at once.
        """
        massless = tuple(massless)
        problems = declaration_problems(model, massless, None)
        fixed = _non_turning(model)
        bodies = []
        for link in model.links:
            if link.ground or link.name in massless:
                continue
            where = f"link '{link.name}'"
            if link.mass is None:
                problems.append(f"{where}: mass: missing; give mass (kg), center_of_mass (one of its "
                                f"points) and inertia (kg m^2), or declare it massless")
                continue
            missing = []
            if link.center_of_mass is None:
                missing.append("center_of_mass (one of its points "
                               f"{', '.join(map(repr, link.points))})")
            if link.inertia is None and link.name not in fixed:
                missing.append("inertia (kg m^2, about the centre of mass)")
            if missing:
                problems.append(f"{where}: has a mass but no {' and no '.join(missing)}; add "
                                f"{'them' if len(missing) > 1 else 'it'} to the link")
                continue
            bodies.append(LinkMass(link.name, float(link.mass), link.center_of_mass,
                                   float(link.inertia or 0.0)))
        problems += declaration_problems(model, (), point_masses)
        if problems:
            raise ModelError(problems, source=f"mechanism '{model.name}'")
        return cls(tuple(bodies), tuple(PointMass(p, m) for p, m in (point_masses or {}).items()))

    def problems(self, model: Mechanism) -> list[str]:
        """Every name the model does not have, or a centre of mass off its link."""
        out = []
        for b in self.links:
            if b.link not in model.link_names:
                out.append(f"masses: link {shown(b.link)} is not a link of '{model.name}'")
            elif b.center_of_mass not in model.link(b.link).points:
                out.append(f"link '{b.link}': center_of_mass: expected one of its points "
                           f"{', '.join(map(repr, model.link(b.link).points))}, got {shown(b.center_of_mass)}")
            elif model.link(b.link).ground:
                out.append(f"masses: link '{b.link}' is the ground; it has no motion to give it mass")
        for p in self.points:
            if p.point not in model.point_names:
                out.append(f"masses: point mass at {shown(p.point)}: not a point of '{model.name}'")
            elif p.link is not None and p.link not in model.link_names:
                out.append(f"masses: point mass at '{p.point}': link: expected a link of "
                           f"'{model.name}', got {shown(p.link)}")
            elif p.link is not None and p.point not in model.link(p.link).points:
                out.append(f"masses: point mass at '{p.point}': link '{p.link}' does not carry it")
        return out


    def lumped(self, model: Mechanism, links: Iterable[str]) -> MassProperties:
        """Replace binary links by two statically equivalent point masses at their joints.

        A link of mass m whose centre of mass G lies on the segment between its two joint
        points A and B becomes ``m |GB| / |AB|`` at A and ``m |AG| / |AB|`` at B (same mass,
        same centre of mass); each lump rides the neighbouring link at that joint when it
        is not lumped too.  The two-point model's moment of inertia about G is
        ``m |AG| |GB|``, which replaces the link's own: the approximation of the notes
        (*Mecanismos*, §5.7).

        Examples
        --------
        >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
        >>> from kinelab.model import Link, Point
        >>> pts = sc.points + (Point("G3", *np.add(sc.point("A").xy, sc.point("B").xy) / 2),)
        >>> links = tuple(Link(l.name, l.points + ("G3",), mass=3.0, center_of_mass="G3", inertia=2.0)
        ...               if l.name == "rod" else l for l in sc.links)
        >>> sc = kl.Mechanism("sc", pts, links, sc.joints, sc.inputs)
        >>> lumps = MassProperties(links=[LinkMass("rod", 3.0, "G3", 2.0)]).lumped(sc, ["rod"]).points
        >>> [(p.point, p.mass, p.link) for p in lumps]
        [('A', 1.5, 'crank'), ('B', 1.5, 'slider')]
        """
        links = tuple(links)
        by_link = {b.link: b for b in self.links}
        problems, lumps = [], list(self.points)
        xy = {p.name: (p.x, p.y) for p in model.points}
        for name in links:
            if name not in by_link:
                problems.append(f"lumped: link {shown(name)} has no mass here; lump links that have one")
                continue
            b = by_link[name]
            hinges = [j for j in model.joints_of(name) if j.type == "R"]
            ends = list(dict.fromkeys(j.point for j in hinges))
            if len(ends) != 2 or len(model.joints_of(name)) != len(hinges):
                problems.append(f"lumped: link {shown(name)} has {len(ends)} hinge point(s) "
                                f"and {len(model.joints_of(name)) - len(hinges)} slide(s); only a "
                                "binary link hinged at two points can be lumped")
                continue
            a, c, g = (xy[p] for p in (ends[0], ends[1], b.center_of_mass))
            ab = math.dist(a, c)
            ag, gb = math.dist(a, g), math.dist(g, c)
            if abs(ag + gb - ab) > _ON_LINE * ab:
                problems.append(f"lumped: link {shown(name)}: its centre of mass {shown(b.center_of_mass)} is "
                                f"not on the segment {ends[0]}-{ends[1]}, so two masses there cannot "
                                "keep it; add a third point or keep the link whole")
                continue
            for end, share in ((ends[0], gb / ab), (ends[1], ag / ab)):
                if share == 0.0:
                    continue
                joint = next(j for j in hinges if j.point == end)
                other = joint.links[1] if joint.links[0] == name else joint.links[0]
                ride = other if (other not in links and other != model.ground.name) else name
                lumps.append(PointMass(end, b.mass * share, ride))
        keep = [b for b in self.links if b.link not in links]
        if problems:
            raise ModelError(problems, source=f"mechanism '{model.name}'")
        return MassProperties(tuple(keep), tuple(lumps))


def _non_turning(model: Mechanism) -> set[str]:
    """Links whose angle is locked to the ground through prismatic joints: they only
    translate, so their moment of inertia never matters."""
    fixed = {model.ground.name}
    grew = True
    while grew:
        grew = False
        for j in model.joints:
            if j.type == "P":
                a, b = j.links
                for x, y in ((a, b), (b, a)):
                    if x in fixed and y not in fixed:
                        fixed.add(y)
                        grew = True
    return fixed - {model.ground.name}


def declaration_problems(model: Mechanism, massless: Iterable[str],
                         point_masses: Mapping[str, float] | None) -> list[str]:
    """What is wrong with the links declared massless and the point masses of a
    ``[dynamics]`` section, for ``model``: names it does not have, a massless link that has
    a mass, a mass that is not a positive number.  (Links that lack mass data are a matter
    for the dynamics alone: :meth:`MassProperties.from_model`.)"""
    problems = []
    for n in massless:
        if n not in model.link_names:
            problems.append(f"massless: expected a link of '{model.name}', got {shown(n)}; its links "
                            f"are {', '.join(map(repr, model.link_names))}")
        elif model.link(n).mass is not None:
            problems.append(f"link '{n}': declared massless but has mass {model.link(n).mass} kg; "
                            "remove it from massless or remove its mass")
    for p, mass in (point_masses or {}).items():
        if p not in model.point_names:
            problems.append(f"point_masses: expected a point of '{model.name}', got {shown(p)}")
            continue
        try:
            PointMass(p, mass)
        except ModelError as exc:
            problems.extend(exc.problems)
    return problems
