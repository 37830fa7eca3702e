"""Counting: the motion space lambda, the freedoms of each pair, Kutzbach-Gruebler.

The criterion of Kutzbach-Gruebler (*Mecanismos*, §2.1, Eq. 1) counts freedoms and
constraints without looking at the geometry::

    M = lambda (Ne - 1) - sum_{j=1}^{lambda-1} (lambda - j) nPj

with ``lambda`` the dimension of the space the links move in (3 in the plane and on the
sphere, 6 in space), ``Ne`` the number of links including the fixed one, and ``nPj`` the
number of pairs that allow ``j`` relative freedoms (class ``Pj``).
"""
from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from numbers import Integral

from kinelab.errors import ModelError, describe
from kinelab.model import JOINT_TYPES, Mechanism

__all__ = ["LAMBDAS", "PairClass", "joint_catalogue", "kutzbach_gruebler", "pair_counts",
           "pair_freedoms", "space_dimension"]

LAMBDAS = {"planar": 3, "spherical": 3, "spatial": 6}
"""The dimension lambda of each motion space a model can name."""

_VALID_LAMBDAS = (2, 3, 6)
# On the sphere every link turns about one centre, so only the pairs whose motion is a
# rotation about that centre (or a contact between two such links) keep a meaning there.
_SPHERICAL_PAIRS = ("R", "U", "S", "cam", "gear", "rolling", "pin_in_slot")


def space_dimension(space: str | int) -> int:
    """The dimension lambda of a motion space.

    Parameters
    ----------
    space : {'planar', 'spherical', 'spatial'} or int
        A named space, or lambda itself: 2 (e.g. the translations of a plane), 3 or 6.

    Returns
    -------
    int

    Raises
    ------
    ModelError
        For any other name or number.

    Examples
    --------
    >>> from kinelab.structure import space_dimension
    >>> space_dimension("planar"), space_dimension("spherical"), space_dimension("spatial")
    (3, 3, 6)
    >>> space_dimension(2)
    2
    """
    if isinstance(space, str):
        if space in LAMBDAS:
            return LAMBDAS[space]
    elif isinstance(space, Integral) and not isinstance(space, bool) and int(space) in _VALID_LAMBDAS:
        return int(space)
    raise ModelError(f"space: expected one of 'planar', 'spherical', 'spatial' or lambda = 2, 3 "
                     f"or 6, got {describe(space)}; lambda is 3 for planar and spherical mechanisms "
                     "and 6 for spatial ones")


def pair_freedoms(joint_type: str, space: str) -> int:
    """Relative freedoms a pair allows in a motion space (its class ``Pj``).

    Lower pairs keep their spatial freedoms.  The higher pairs of planar mechanisms
    (cam, gear, rolling contact, pin in slot) allow 2, 2, 1 and 2 freedoms in the plane
    and on the sphere, and 5, 5, 3 and 4 in space (point contact; point contact without
    slip; a ball kept on the slot's line).

    Parameters
    ----------
    joint_type : str
        A symbol of :data:`kinelab.model.JOINT_TYPES`.
    space : {'planar', 'spherical', 'spatial'}

    Raises
    ------
    ModelError
        For an unknown type, or a pair that has no meaning in that space.

    Examples
    --------
    >>> from kinelab.structure import pair_freedoms
    >>> pair_freedoms("R", "planar"), pair_freedoms("S", "spatial"), pair_freedoms("cam", "planar")
    (1, 3, 2)
    >>> pair_freedoms("cam", "spatial")
    5
    """
    if space not in LAMBDAS:
        raise ModelError(f"space: expected one of 'planar', 'spherical', 'spatial', got {describe(space)}")
    jt = JOINT_TYPES.get(joint_type)
    if jt is None:
        raise ModelError(f"joint type: expected one of {', '.join(map(repr, JOINT_TYPES))}, "
                         f"got {describe(joint_type)}")
    if space == "planar":
        if not jt.planar:
            raise ModelError(f"a {joint_type} pair ({jt.description}) does not exist in a planar "
                             "mechanism; use R, P or a planar higher pair, or space 'spatial'")
        return jt.freedoms
    if space == "spherical":
        if joint_type not in _SPHERICAL_PAIRS:
            raise ModelError(f"a {joint_type} pair ({jt.description}) has no meaning in a "
                             f"spherical mechanism; use one of {', '.join(_SPHERICAL_PAIRS)} "
                             "or space 'spatial'")
        return jt.freedoms
    return jt.spatial_freedoms or jt.freedoms


@dataclass(frozen=True)
class PairClass:
    """One row of the joint catalogue: a pair and the freedoms it allows in each space.

    Attributes
    ----------
    symbol, description : str
    higher : bool
        Point or line contact rather than surface contact.
    planar, spherical, spatial : int or None
        Freedoms in that space, ``None`` where the pair has no meaning.
    """

    symbol: str
    description: str
    higher: bool
    planar: int | None
    spherical: int | None
    spatial: int | None

    @property
    def pair_class(self) -> str:
        """``'P1'`` ... ``'P5'``: the class of the pair in space."""
        return f"P{self.spatial}"


def joint_catalogue() -> tuple[PairClass, ...]:
    """Every pair kinelab knows, with its freedoms in the plane, on the sphere, in space.

    Examples
    --------
    >>> from kinelab.structure import joint_catalogue
    >>> [(c.symbol, c.pair_class) for c in joint_catalogue()][:6]
    [('R', 'P1'), ('P', 'P1'), ('H', 'P1'), ('C', 'P2'), ('U', 'P2'), ('S', 'P3')]
    >>> next(c for c in joint_catalogue() if c.symbol == "cam")
    PairClass(symbol='cam', description='cam and follower (rolling and sliding contact)', higher=True, planar=2, spherical=2, spatial=5)
    """
    def freedoms(symbol: str, space: str) -> int | None:
        try:
            return pair_freedoms(symbol, space)
        except ModelError:
            return None
    return tuple(PairClass(t.symbol, t.description, t.higher, freedoms(t.symbol, "planar"),
                           freedoms(t.symbol, "spherical"), freedoms(t.symbol, "spatial"))
                 for t in JOINT_TYPES.values())


def pair_counts(model: Mechanism) -> dict[int, int]:
    """``{j: nPj}``: how many pairs of the model allow ``j`` freedoms in its space.

    Raises
    ------
    ModelError
        Naming every joint whose pair has no meaning in the model's space.

    Examples
    --------
    >>> from kinelab.structure import pair_counts
    >>> from kinelab.model import Mechanism, Point, Link, Joint
    >>> m = Mechanism("pendulum", (Point("O", 0, 0), Point("A", 1, 0)),
    ...               (Link("ground", ("O",), ground=True), Link("arm", ("O", "A"))),
    ...               (Joint("pivot", "R", ("ground", "arm"), point="O"),))
    >>> pair_counts(m)
    {1: 1}
    """
    model = checked_model(model)
    counts: dict[int, int] = {}
    problems = []
    for j in model.joints:
        try:
            f = pair_freedoms(j.type, model.space)
        except ModelError as exc:
            problems.append(f"joint '{j.name}': {exc}")
            continue
        counts[f] = counts.get(f, 0) + 1
    if problems:
        raise ModelError(problems, source=f"mechanism '{model.name}'")
    return dict(sorted(counts.items()))


def checked_model(model, name: str = "model") -> Mechanism:
    """``model``, or a :class:`ModelError` unless it is a :class:`kinelab.model.Mechanism`."""
    if not isinstance(model, Mechanism):
        raise ModelError(f"{name}: expected a kinelab.model.Mechanism, got {describe(model)}; "
                         "build one with kinelab.mechanisms, kinelab.load or kinelab.model")
    return model


def whole(value, what: str, low: int, high: int | None = None, hint: str = "") -> int:
    """``value`` as an int, or a :class:`ModelError` naming ``what`` unless it is a whole
    number from ``low`` (to ``high``)."""
    if (not isinstance(value, Integral) or isinstance(value, bool) or value < low
            or (high is not None and value > high)):
        span = f"from {low} to {high}" if high is not None else f">= {low}"
        raise ModelError(f"{what}: expected a whole number {span}, got {describe(value)}{hint}")
    return int(value)


def kutzbach_gruebler(links: int, pairs: Mapping[int, int], space: str | int) -> int:
    """Mobility by the criterion of Kutzbach-Gruebler, from counts alone.

    ``M = lambda (Ne - 1) - sum_j (lambda - j) nPj`` (*Mecanismos*, Eq. 1): each moving link
    brings lambda freedoms and each pair of class ``Pj`` takes away ``lambda - j``.  The
    count ignores the geometry, so it is wrong wherever constraints repeat one another
    (parallel or intersecting axes, equal lengths); see :func:`mobility` for the exact
    value.

    Parameters
    ----------
    links : int
        ``Ne``, the number of links including the fixed one.
    pairs : mapping of int to int
        ``{j: nPj}``: how many pairs allow ``j`` freedoms, ``1 <= j <= lambda`` (the
        classes may also be written ``'P1'``, ``'P2'``, ...).
    space : {'planar', 'spherical', 'spatial'} or int
        The motion space, or lambda itself (2, 3 or 6).

    Returns
    -------
    int
        The mobility ``M`` (negative for a structure constrained more than enough to
        be rigid).

    Raises
    ------
    ModelError
        For a space other than those above, negative counts, or a pair class outside
        ``1 .. lambda``.

    Examples
    --------
    Slider-crank (*Mecanismos*, Ex. 2.1): four links, four pairs of class P1.

    >>> from kinelab.structure import kutzbach_gruebler
    >>> kutzbach_gruebler(4, {1: 4}, "planar")
    1

    Disk cam with a flat-faced follower (Ex. 2.2): the cam contact is a P2 pair.

    >>> kutzbach_gruebler(3, {1: 2, 2: 1}, "planar")
    1

    Double-wishbone suspension (Ex. 2.3) and the RRRRRR mechanism (§2.2):

    >>> kutzbach_gruebler(4, {1: 2, 3: 2}, "spatial"), kutzbach_gruebler(6, {1: 6}, "spatial")
    (2, 0)
    """
    lam = space_dimension(space)
    ne = whole(links, "links", 1)
    if not isinstance(pairs, Mapping):
        raise ModelError(f"pairs: expected a mapping {{freedoms of the pair: count}}, got "
                         f"{type(pairs).__name__}; e.g. {{1: 4}} for four R or P pairs")
    removed = 0
    for key, n in pairs.items():
        j = int(key[1]) if isinstance(key, str) and re.fullmatch(r"P[1-6]", key) else key
        if not isinstance(j, Integral) or isinstance(j, bool) or not 1 <= j <= lam:
            raise ModelError(f"pairs: a pair allows 1 to {lam} freedoms when lambda = {lam}, "
                             f"got {describe(key)}")
        removed += (lam - int(j)) * whole(n, f"pairs[{describe(key)}]", 0)
    return lam * (ne - 1) - removed
