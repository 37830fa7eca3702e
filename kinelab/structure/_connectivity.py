"""Connectivity of one link relative to another, chain by chain, and the Lie group method.

The connectivity of link ``b`` relative to link ``a`` along a chain (*Mecanismos*, §1.3) is
the number of independent coordinates that place ``b`` relative to ``a`` when only that
chain joins them: often the sum of the freedoms of its pairs, but never more than the
rank of their freedom screws (three parallel R joints and a P along their axes give 3,
not 4, freedoms).  Along each chain the pairs also *generate* a group of displacements
(:mod:`kinelab.structure._groups`), which is what the Lie group method of §2.2
intersects.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kinelab.errors import ModelError, shown
from kinelab.model import Mechanism
from kinelab.structure._count import checked_model, pair_freedoms
from kinelab.structure._groups import DisplacementGroup, generated_group
from kinelab.structure._screws import null_basis, rank
from kinelab.structure._system import ConstraintSystem

__all__ = ["Chain", "Connectivity", "LieMobility", "connectivity", "lie_mobility"]

_MAX_CHAINS = 1000


@dataclass(frozen=True)
class Chain:
    """One chain of links and pairs from a link to another.

    Attributes
    ----------
    links : tuple of str
        From the first link to the last, both included.
    joints : tuple of str
        The pairs in order.
    name : str
        Their types in order, as the notes name chains (``'RRR'``, ``'UPS'``).
    freedoms : int
        Sum of the pairs' freedoms.
    connectivity : int
        Independent motions of the last link relative to the first along this chain
        alone, at the sketch: the rank of the pairs' freedom screws.
    group : DisplacementGroup
        The group of displacements the pairs generate.
    """

    links: tuple[str, ...]
    joints: tuple[str, ...]
    name: str
    freedoms: int
    connectivity: int
    group: DisplacementGroup

    @property
    def is_group(self) -> bool:
        """Whether the chain moves its last link over the whole group it generates."""
        return self.group.dim == self.connectivity


@dataclass(frozen=True)
class Connectivity:
    """Connectivity of link ``b`` relative to link ``a``.

    Attributes
    ----------
    a, b : str
    chains : tuple of Chain
        Every chain (simple path of pairs) from ``a`` to ``b``.
    overall : int
        Independent motions of ``b`` relative to ``a`` that the whole mechanism allows at
        its sketch (every chain acting together).
    """

    a: str
    b: str
    chains: tuple[Chain, ...]
    overall: int


@dataclass(frozen=True)
class LieMobility:
    """Mobility of a parallel mechanism by the Lie group method (*Mecanismos*, §2.2).

    Attributes
    ----------
    base, end : str
        The fixed link and the end link (platform).
    legs : tuple of Chain
        The chains from base to end.
    group : DisplacementGroup
        The intersection of the legs' groups: the displacements the end link can make.
    mobility : int
        ``group.dim`` plus the motions internal to the legs (``freedoms - connectivity``
        of each leg, as the spin of an S-P-S leg); exact when ``valid``.
    valid : bool
        The legs share no link but the base and the end, and each leg moves over the
        whole group it generates; otherwise the method does not apply (use
        :func:`mobility`).
    explanation : str
    """

    base: str
    end: str
    legs: tuple[Chain, ...]
    group: DisplacementGroup
    mobility: int
    valid: bool
    explanation: str


def _paths(model: Mechanism, a: str, b: str) -> list[tuple[tuple[str, ...], tuple[str, ...]]]:
    """Every simple path of joints from link a to link b: (links, joints)."""
    out = []

    def walk(links, joints):
        if len(out) >= _MAX_CHAINS:
            raise ModelError(f"more than {_MAX_CHAINS} chains join '{a}' and '{b}'; ask about "
                             "two links closer together")
        here = links[-1]
        if here == b:
            out.append((tuple(links), tuple(joints)))
            return
        for j in model.joints_of(here):
            other = j.links[1] if j.links[0] == here else j.links[0]
            if other not in links:
                walk(links + [other], joints + [j.name])
    walk([a], [])
    return out


def _spatial(system: ConstraintSystem, twists: np.ndarray) -> np.ndarray:
    """Twists of the system's frame as spatial twists about the model's origin, v in
    units of the frame's scale."""
    if system.planar:
        t = np.zeros((len(twists), 6))
        t[:, 2], t[:, 3:5] = twists[:, 0], twists[:, 1:3]
        twists = t
    c = system.frame.center / system.frame.scale
    return np.hstack([twists[:, :3], twists[:, 3:] - np.cross(twists[:, :3], c)])


def _chain(system: ConstraintSystem, links, joints) -> Chain:
    model = system.model
    types = [model.joint(j).type for j in joints]
    name = "".join(types) if all(len(t) == 1 for t in types) else "-".join(types)
    screws = np.vstack([system.screws[j] for j in joints])
    return Chain(links, joints, name, sum(pair_freedoms(t, model.space) for t in types),
                 rank(screws), generated_group(_spatial(system, screws),
                                               length=system.frame.scale))


def _check_links(model: Mechanism, *names: str) -> None:
    for n in names:
        model.link(n)  # raises a ModelError naming the link and the choices
    if len(set(names)) < len(names):
        raise ModelError(f"links: expected two different links, got {shown(names[0])} twice")


def connectivity(model: Mechanism, a: str, b: str) -> Connectivity:
    """Connectivity of link ``b`` relative to link ``a``, along each chain and overall.

    Parameters
    ----------
    model : Mechanism
    a, b : str
        Link names.

    Returns
    -------
    Connectivity
        One :class:`Chain` per simple path of pairs from ``a`` to ``b``, each with its
        freedoms, its connectivity and the group it generates, and the connectivity
        the whole mechanism leaves.

    Examples
    --------
    In a four-bar the coupler has 2 freedoms relative to the ground along either side
    (a planar RR chain) and 1 with both sides acting.

    >>> c = connectivity(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), "ground", "coupler")
    >>> [(ch.joints, ch.connectivity, ch.group.label) for ch in c.chains]
    [(('jO2', 'jA'), 2, '{Tx, Ty, Rz}'), (('jO4', 'jB'), 2, '{Tx, Ty, Rz}')]
    >>> c.overall
    1
    """
    _check_links(checked_model(model), a, b)
    system = ConstraintSystem.of(model)
    chains = tuple(_chain(system, links, joints) for links, joints in _paths(model, a, b))
    motions = null_basis(system.matrix()) if system.unknowns else np.zeros((0, 0))
    overall = rank(system.relative(a, b) @ motions, scale=1.0) if motions.size else 0
    return Connectivity(a, b, chains, overall)


def lie_mobility(model: Mechanism, end: str, *, base: str | None = None) -> LieMobility:
    """Mobility of a parallel mechanism by intersecting the groups of its legs.

    Each leg (chain from ``base`` to ``end``) generates a group of displacements; when
    every leg moves its end over the whole of that group and the legs share only the
    base and the end, the end link moves over their intersection (*Mecanismos*, §2.2), and
    the mobility is the dimension of the intersection plus the motions internal to the
    legs.  The method fails where a leg's motions are not a group (Bennett's linkage);
    :func:`mobility` is exact in every case.

    Parameters
    ----------
    model : Mechanism
    end : str
        The end link (platform).
    base : str, optional
        The fixed link; default the ground.

    Examples
    --------
    The RRRRRR mechanism of the notes (Fig. 12): legs 1-2-3-4 with axes along y and
    1-5-6-4 with axes along x.

    >>> from kinelab.model import Mechanism, Point, Link, Joint
    >>> from kinelab.structure import lie_mobility
    >>> P = [Point("A1", 1, 0, 0), Point("A2", 1.6, 0.3, 0.4), Point("A3", 1.1, -0.2, 1),
    ...      Point("B1", 0, 1, 0), Point("B2", 0.2, 1.7, 0.6), Point("B3", -0.1, 1.2, 1)]
    >>> L = [Link("1", ("A1", "B1"), ground=True), Link("2", ("A1", "A2")),
    ...      Link("3", ("A2", "A3")), Link("4", ("A3", "B3")), Link("5", ("B1", "B2")),
    ...      Link("6", ("B2", "B3"))]
    >>> J = [Joint(a + b, "R", (a, b), point=p, axis=ax) for a, b, p, ax in [
    ...      ("1", "2", "A1", (0, 1, 0)), ("2", "3", "A2", (0, 1, 0)), ("3", "4", "A3", (0, 1, 0)),
    ...      ("1", "5", "B1", (1, 0, 0)), ("5", "6", "B2", (1, 0, 0)), ("6", "4", "B3", (1, 0, 0))]]
    >>> r = lie_mobility(Mechanism("RRRRRR", P, L, J, space="spatial"), "4")
    >>> [leg.group.label for leg in r.legs], r.group.label, r.mobility
    (['{Tx, Tz, Ry}', '{Ty, Tz, Rx}'], '{Tz}', 1)
    """
    base = checked_model(model).ground.name if base is None else base
    _check_links(model, base, end)
    system = ConstraintSystem.of(model)
    legs = tuple(_chain(system, links, joints) for links, joints in _paths(model, base, end))
    group = legs[0].group
    for leg in legs[1:]:
        group = group & leg.group
    inner = [set(leg.links[1:-1]) for leg in legs]
    disjoint = all(not (inner[i] & inner[k]) for i in range(len(legs)) for k in range(i))
    covered = {j for leg in legs for j in leg.joints} == set(model.joint_names)
    valid = disjoint and covered and all(leg.is_group for leg in legs)
    internal = sum(leg.freedoms - leg.connectivity for leg in legs)
    m = group.dim + internal
    lines = [f"leg {'-'.join(leg.links)} ({leg.name}) generates {leg.group.label} "
             f"({leg.group.kind or 'not a standard group'}, dimension {leg.group.dim}"
             + (")" if leg.is_group else f", but the leg has only {leg.connectivity} "
                "independent freedoms there, so its motions are not a group)")
             for leg in legs]
    lines.append(f"intersection: {group.label} ({group.kind or 'no standard group'}), so link "
                 f"'{end}' has {group.dim} independent displacements relative to '{base}'")
    if internal:
        lines.append(f"the legs add {internal} internal freedoms (beyond their connectivity), "
                     f"so M = {group.dim} + {internal} = {m}")
    else:
        lines.append(f"M = {m}")
    if not valid:
        why = ("the legs share links other than the base and the end" if not disjoint else
               "some pairs lie on no leg from base to end" if not covered else
               "a leg's motions are not a group")
        lines.append(f"the Lie group method does not apply here ({why}); this value is only a "
                     "guide: use kinelab.structure.mobility for the exact one")
    return LieMobility(base, end, legs, group, m, valid, ".\n".join(lines) + ".")
