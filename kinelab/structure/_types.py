"""Type synthesis (*Mecanismos*, §3): candidate architectures for a mobility and a space.

Four methods of the notes, each a function returning a :class:`TypeSynthesis`:

- :func:`number_synthesis` (§3.4): an open chain of P1 pairs (R, P); Eq. (1) relates the
  number of pairs to the number of links (Example 3.1, Table 1);
- :func:`active_chains` (§3.5): M chains between base and platform, each with an
  actuator, of total connectivity ``C_T = (lambda + 1) M - lambda`` and each
  ``M <= C_k <= lambda`` (6-UPS for lambda = M = 6);
- :func:`passive_chain` (§3.6): M active chains of connectivity lambda and one passive
  chain of connectivity M whose freedoms are the wanted motion, ``C_T = (lambda + 1) M``
  (3-UPS+UP, the tricept);
- :func:`alternative_method` (§3.7): from the passive-chain architecture, remove one
  active chain and put an actuator on the passive chain's pair nearest the base
  (RRR+PP of Example 3.4).

A chain type is a sequence of pairs from the base, such as ``UPS``.  Its connectivity is
the sum of the freedoms of its pairs, kept only when the pairs are independent in
general position (a planar PPP moves in 2 directions only, S-S spins idly about its
line: both are left out).  Which arrangement of axes gives exactly the wanted motion
(the U of UP at the base, the P radial) is the designer's next step, dimensional
synthesis.
"""
from __future__ import annotations

import itertools
import re
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from kinelab.errors import ModelError, describe
from kinelab.structure._count import LAMBDAS, pair_freedoms, whole
from kinelab.structure._screws import _rot, _trans, pair_screws, rank

__all__ = ["Architecture", "ChainType", "Motion", "TypeSynthesis", "active_chains",
           "alternative_method", "chain_types", "number_synthesis", "passive_chain",
           "type_synthesis"]

#: Rotations and translations each pair contributes (H couples them and is left out of
#: motion matching).
_MOTIONS = {"R": (1, 0), "P": (0, 1), "C": (1, 1), "U": (2, 0), "S": (3, 0), "E": (1, 2)}
_DEFAULT_JOINTS = {"planar": ("R", "P"), "spherical": ("R",), "spatial": ("R", "P", "U", "C", "S")}
_OPEN_JOINTS = {"planar": ("R", "P"), "spherical": ("R",), "spatial": ("R", "P")}
_LIMITS = {"planar": (1, 2), "spherical": (3, 0), "spatial": (3, 3)}  # (rotations, translations)
_ACTUABLE = ("R", "P")
_LOWER = {"planar": ("R", "P"), "spherical": ("R", "U", "S"),
          "spatial": ("R", "P", "H", "C", "U", "S", "E")}


def _space(space) -> tuple[str, int]:
    if space not in LAMBDAS:
        raise ModelError(f"space: expected one of 'planar', 'spherical', 'spatial', got "
                         f"{describe(space)}; type synthesis chooses pairs for a named space")
    return space, LAMBDAS[space]


def _mobility(mobility, lam: int) -> int:
    return whole(mobility, "mobility", 1, lam,
                  f"; in a space of lambda = {lam} an end link has at most {lam} freedoms")


@dataclass(frozen=True)
class Motion:
    """The motion wanted of an end link: named translations and rotations.

    ``Motion.parse("Tx Tz Ry")``; the letter after T or R names the direction (x, y,
    z, or any word such as ``r`` for radial).
    """

    tokens: tuple[str, ...]

    @property
    def rotations(self) -> int:
        return sum(t[0] == "R" for t in self.tokens)

    @property
    def translations(self) -> int:
        return sum(t[0] == "T" for t in self.tokens)

    def __len__(self) -> int:
        return len(self.tokens)

    def __str__(self) -> str:
        return "{" + ", ".join(self.tokens) + "}"

    @classmethod
    def parse(cls, motion: str | Sequence[str] | Motion, space: str) -> Motion:
        if isinstance(motion, Motion):
            tokens = motion.tokens
        else:
            raw = (re.split(r"[\s,{}]+", motion) if isinstance(motion, str)
                   else list(motion) if isinstance(motion, Sequence) else [motion])
            tokens = tuple(t for t in raw if t)
        bad = [t for t in tokens if not (isinstance(t, str) and re.fullmatch(r"[RT]\w*", t))]
        if bad or not tokens:
            raise ModelError(f"motion: expected translations and rotations such as 'Tx Tz Ry' "
                             f"(T or R, then a direction), got {describe(motion)}")
        if len(set(tokens)) < len(tokens):
            raise ModelError(f"motion: {describe(motion)} names a displacement twice")
        m = cls(tokens)
        rot, tra = _LIMITS[space]
        if m.rotations > rot or m.translations > tra:
            raise ModelError(f"motion: a {space} link has at most {rot} rotations and {tra} "
                             f"translations, got {m.rotations} and {m.translations} in {m}")
        return m


@dataclass(frozen=True)
class ChainType:
    """A serial chain from the base, named by its pairs (``'UPS'``).

    Attributes
    ----------
    joints : tuple of str
        Pair types from the base.
    connectivity : int
        Sum of the pairs' freedoms (independent in general position).
    actuated : int or None
        Index of the pair that carries the actuator (the R or P nearest the base), or
        ``None`` for a passive chain.
    """

    joints: tuple[str, ...]
    connectivity: int
    actuated: int | None = None

    @property
    def name(self) -> str:
        return "".join(self.joints)

    @property
    def rotations(self) -> int:
        return sum(_MOTIONS.get(j, (1, 0))[0] for j in self.joints)

    @property
    def translations(self) -> int:
        return sum(_MOTIONS.get(j, (0, 0))[1] for j in self.joints)

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True)
class Architecture:
    """A parallel (or serial) architecture: its chains between base and end link.

    Attributes
    ----------
    chains : tuple of ChainType
        Active chains, then the passive chain if there is one.
    """

    chains: tuple[ChainType, ...]

    @property
    def name(self) -> str:
        """As the notes write them: ``'6-UPS'``, ``'3-UPS+UP'``, ``'RRR+PP'``."""
        parts = []
        for name, group in itertools.groupby(c.name for c in self.chains):
            k = len(list(group))
            parts.append(f"{k}-{name}" if k > 1 else name)
        return "+".join(parts)

    @property
    def connectivities(self) -> tuple[int, ...]:
        return tuple(c.connectivity for c in self.chains)

    @property
    def total_connectivity(self) -> int:
        return sum(self.connectivities)

    @property
    def actuators(self) -> int:
        return sum(c.actuated is not None for c in self.chains)

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True)
class TypeSynthesis:
    """Candidate architectures from one method of type synthesis.

    Attributes
    ----------
    method : str
        ``'open chain'``, ``'active chains'``, ``'passive chain'`` or ``'alternative'``.
    space : str
    lam : int
        lambda.
    mobility : int
    total_connectivity : int
        ``C_T`` of the method (for an open chain, its number of pairs).
    connectivities : tuple of tuple of int
        The admissible connectivities of the chains, one tuple per architecture family
        (largest first; a passive chain's last).
    chains : dict of int to tuple of ChainType
        The chain types available for each connectivity.
    motion : Motion or None
        The wanted motion, where the method uses one.
    table : tuple of (int, Fraction)
        Number synthesis only: ``(nP1, Ne)`` from Eq. (1), as Table 1 of the notes.
    """

    method: str
    space: str
    lam: int
    mobility: int
    total_connectivity: int
    connectivities: tuple[tuple[int, ...], ...]
    chains: Mapping[int, tuple[ChainType, ...]]
    motion: Motion | None = None
    table: tuple[tuple[int, Fraction], ...] = ()
    _families: tuple = field(default=(), repr=False)

    def architectures(self, limit: int | None = None) -> tuple[Architecture, ...]:
        """The candidate architectures, in a fixed order (at most ``limit``).

        Chains of equal connectivity are taken of one type (``6-UPS``, not every
        mixture of six legs); each family's choices are combined.
        """
        return tuple(itertools.islice(self._iter(), limit))

    def _iter(self) -> Iterator[Architecture]:
        for family in self._families:
            # family: tuple of (count, candidates) in chain order
            for pick in itertools.product(*(cands for _, cands in family)):
                yield Architecture(tuple(c for (k, _), c in zip(family, pick)
                                         for _ in range(k)))

    @property
    def names(self) -> tuple[str, ...]:
        """Names of every candidate architecture."""
        return tuple(a.name for a in self._iter())

    def count(self) -> int:
        """How many candidate architectures there are."""
        return sum(int(np.prod([len(c) for _, c in family])) for family in self._families)


# -- chain types -----------------------------------------------------------------------------------
def _generic_screws(joint: str, space: str, rng: np.random.Generator) -> list[np.ndarray]:
    """Freedom screws of a pair in general position (spatial twists)."""
    def unit(k=3):
        u = rng.standard_normal(k)
        return u / np.linalg.norm(u)
    if space == "planar":
        z, p = np.array([0.0, 0.0, 1.0]), np.append(rng.standard_normal(2), 0.0)
        return [_rot(z, p)] if joint == "R" else [_trans(np.append(unit(2), 0.0))]
    if space == "spherical":  # every axis through the centre, the origin
        return [_rot(unit(), np.zeros(3)) for _ in range(pair_freedoms(joint, "spatial"))]
    p, u = rng.standard_normal(3), unit()
    if joint in ("R", "P", "H", "C", "U", "S", "E"):
        return pair_screws(joint, p, u, unit(), pitch=rng.standard_normal())
    raise ModelError(f"joints: a {describe(joint)} pair has no place in a chain type; use "
                     f"{', '.join(_DEFAULT_JOINTS['spatial'])} (or H, E)")


def _independent(joints: tuple[str, ...], space: str) -> bool:
    rng = np.random.default_rng(len(joints) * 7919 + sum(map(ord, "".join(joints))))
    screws = [s for j in joints for s in _generic_screws(j, space, rng)]
    return rank(np.array(screws)) == len(screws)


def _alphabet(joints, space: str) -> tuple[str, ...]:
    joints = tuple(joints)
    for j in joints:
        pair_freedoms(j, space)  # a ModelError for pairs foreign to the space
        if j not in _LOWER[space]:
            raise ModelError(f"joints: a {space} chain type is made of "
                             f"{', '.join(_LOWER[space])}, got {describe(j)}")
    if not joints:
        raise ModelError("joints: expected at least one pair type, got none")
    return joints


def chain_types(connectivity: int, space: str, *, joints: Sequence[str] | None = None,
                max_joints: int = 3, active: bool = True,
                motion: str | Sequence[str] | Motion | None = None) -> tuple[ChainType, ...]:
    """Serial chains of a given connectivity.

    Parameters
    ----------
    connectivity : int
        Sum of the freedoms of the chain's pairs, ``1 .. lambda``.
    space : {'planar', 'spherical', 'spatial'}
    joints : sequence of str, optional
        Pair types to use; default R, P (planar), R (spherical), R, P, U, C, S (spatial).
    max_joints : int, optional
        At most this many pairs in a chain.
    active : bool, optional
        Keep only chains with an R or P pair to carry an actuator, and mark it (the one
        nearest the base).
    motion : str or sequence of str, optional
        Keep only chains whose pairs give as many rotations and translations as this
        motion (e.g. ``'Rx Ry Tr'``).

    Examples
    --------
    >>> from kinelab.structure import chain_types
    >>> [c.name for c in chain_types(2, "planar")]
    ['RR', 'RP', 'PR', 'PP']
    >>> [c.name for c in chain_types(3, "planar")]
    ['RRR', 'RRP', 'RPR', 'RPP', 'PRR', 'PRP', 'PPR']
    >>> "UPS" in [c.name for c in chain_types(6, "spatial")]
    True
    """
    space, lam = _space(space)
    c = whole(connectivity, "connectivity", 1, lam)
    alphabet = _alphabet(joints or _DEFAULT_JOINTS[space], space)
    n_max = whole(max_joints, "max_joints", 1)
    want = Motion.parse(motion, space) if motion is not None else None
    free = {j: pair_freedoms(j, space) for j in alphabet}
    out = []

    def grow(seq: tuple[str, ...], left: int) -> None:
        if left == 0:
            if active and not any(j in _ACTUABLE for j in seq):
                return
            chain = ChainType(seq, c, next((k for k, j in enumerate(seq) if j in _ACTUABLE), None)
                              if active else None)
            if want and (chain.rotations, chain.translations) != (want.rotations, want.translations):
                return
            if _independent(seq, space):
                out.append(chain)
            return
        if len(seq) == n_max:
            return
        for j in alphabet:
            if free[j] <= left:
                grow(seq + (j,), left - free[j])
    grow((), c)
    return tuple(out)


# -- the four methods -------------------------------------------------------------------------------
def number_synthesis(mobility: int, space: str, *, joints: Sequence[str] | None = None,
                     motion: str | Sequence[str] | None = None) -> TypeSynthesis:
    """Number synthesis of an open chain of P1 pairs (*Mecanismos*, §3.4, Example 3.1).

    With only P1 pairs (R, P), Eq. (1) reads ``M = lambda (Ne - 1) - (lambda - 1) nP1``,
    so ``Ne = (M + lambda + (lambda - 1) nP1) / lambda``.  The table lists ``Ne`` for
    ``nP1 = 1 .. M``; the first whole value is ``nP1 = M``, ``Ne = M + 1``: a serial chain
    of M pairs, each R or P.

    Parameters
    ----------
    mobility : int
        ``M``, ``1 .. lambda``.
    space : {'planar', 'spherical', 'spatial'}
    joints : sequence of str, optional
        P1 pairs to use; default R and P (R alone on the sphere).
    motion : str or sequence of str, optional
        Keep the chains with as many R as rotations and P as translations in it.

    Examples
    --------
    Example 3.1 of the notes: lambda = 6, M = 3; Table 1 and the 8 architectures of Fig. 28.

    >>> from kinelab.structure import number_synthesis
    >>> s = number_synthesis(3, "spatial")
    >>> [(n, str(ne)) for n, ne in s.table]
    [(1, '7/3'), (2, '19/6'), (3, '4')]
    >>> s.names
    ('RRR', 'RRP', 'RPR', 'RPP', 'PRR', 'PRP', 'PPR', 'PPP')
    """
    space, lam = _space(space)
    m = _mobility(mobility, lam)
    alphabet = _alphabet(joints or _OPEN_JOINTS[space], space)
    for j in alphabet:
        if pair_freedoms(j, space) != 1:
            raise ModelError(f"joints: number synthesis uses P1 pairs (R, P), got {describe(j)}")
    table = tuple((n, Fraction(m + lam + (lam - 1) * n, lam)) for n in range(1, m + 1))
    chains = chain_types(m, space, joints=alphabet, max_joints=m, active=True, motion=motion)
    return TypeSynthesis("open chain", space, lam, m, m, ((m,),), {m: chains},
                         Motion.parse(motion, space) if motion is not None else None, table,
                         (((1, chains),),))


def _sets(total: int, parts: int, low: int, high: int) -> list[tuple[int, ...]]:
    """Non-increasing tuples of ``parts`` values in [low, high] summing to total."""
    out = []

    def rec(left, k, top, acc):
        if k == 0:
            if left == 0:
                out.append(tuple(acc))
            return
        for c in range(min(top, left - low * (k - 1)), low - 1, -1):
            rec(left - c, k - 1, c, acc + [c])
    rec(total, parts, high, [])
    return out


def _families(sets, chains) -> tuple:
    return tuple(tuple((sum(1 for x in cs if x == c), chains[c])
                       for c in sorted(set(cs), key=cs.index)) for cs in sets)


def active_chains(mobility: int, space: str, *, joints: Sequence[str] | None = None,
                  max_joints: int = 3) -> TypeSynthesis:
    """Type synthesis by enumeration of active chains (*Mecanismos*, §3.5).

    M active chains join base and end link; their connectivities add up to
    ``C_T = (lambda + 1) M - lambda`` (Eq. 5), each between M and lambda (Eq. 6).

    Parameters
    ----------
    mobility : int
        ``M``, ``1 .. lambda``.
    space : {'planar', 'spherical', 'spatial'}
    joints, max_joints
        As :func:`chain_types`.

    Examples
    --------
    Example 3.2 of the notes: lambda = M = 6, so C_T = 36 and each chain has connectivity 6.

    >>> from kinelab.structure import active_chains
    >>> s = active_chains(6, "spatial")
    >>> s.total_connectivity, s.connectivities
    (36, ((6, 6, 6, 6, 6, 6),))
    >>> "6-UPS" in s.names
    True
    """
    space, lam = _space(space)
    m = _mobility(mobility, lam)
    total = (lam + 1) * m - lam
    sets = _sets(total, m, m, lam)
    chains = {c: chain_types(c, space, joints=joints, max_joints=max_joints)
              for c in sorted({c for cs in sets for c in cs})}
    return TypeSynthesis("active chains", space, lam, m, total, tuple(sets), chains,
                         _families=_families(sets, chains))


def _with_passive(method: str, motion, space: str, joints, max_joints: int, drop: int
                  ) -> TypeSynthesis:
    space, lam = _space(space)
    want = Motion.parse(motion, space)
    m = _mobility(len(want), lam)
    active = chain_types(lam, space, joints=joints, max_joints=max_joints)
    last = chain_types(m, space, joints=joints, max_joints=max_joints, active=bool(drop),
                       motion=want)
    if not last:
        raise ModelError(f"motion: no chain of at most {max_joints} pairs gives {want}; allow "
                         "more pairs (max_joints) or other pair types (joints)")
    n_active = m - drop
    cs = (lam,) * n_active + (m,)
    chains = {lam: active, m: last} if m != lam else {m: active + last}
    family = (((n_active, active),) if n_active else ()) + ((1, last),)
    return TypeSynthesis(method, space, lam, m, sum(cs), (cs,), chains, want, (), (family,))


def passive_chain(motion: str | Sequence[str], space: str, *,
                  joints: Sequence[str] | None = None, max_joints: int = 3) -> TypeSynthesis:
    """Type synthesis by addition of a passive chain (*Mecanismos*, §3.6).

    A passive chain (no actuator) of connectivity ``M`` whose freedoms are the wanted
    motion (Eq. 7) joins base and end link, beside M active chains of connectivity
    lambda (Eq. 8) that do not restrict it further: ``C_T = (lambda + 1) M`` (Eq. 9).

    Parameters
    ----------
    motion : str or sequence of str
        The end link's wanted motion, e.g. ``'Rx Ry Tr'``; M is its length.
    space : {'planar', 'spherical', 'spatial'}
    joints, max_joints
        As :func:`chain_types`.

    Examples
    --------
    Example 3.3 of the notes: two rotations and a radial translation in space, the tricept.

    >>> from kinelab.structure import passive_chain
    >>> s = passive_chain("Rx Ry Tr", "spatial")
    >>> s.total_connectivity, "3-UPS+UP" in s.names
    (21, True)
    """
    return _with_passive("passive chain", motion, space, joints, max_joints, drop=0)


def alternative_method(motion: str | Sequence[str], space: str, *,
                       joints: Sequence[str] | None = None, max_joints: int = 3
                       ) -> TypeSynthesis:
    """Type synthesis by the alternative method (*Mecanismos*, §3.7).

    Start from the passive-chain architecture, remove one active chain, and put an
    actuator on the passive chain's R or P pair nearest the base: M - 1 chains of
    connectivity lambda (Eq. 11) and one of connectivity M (Eq. 10), so
    ``C_T = (lambda + 1) M - lambda`` (Eq. 12), as for active-chain enumeration.

    Examples
    --------
    Example 3.4 of the notes: a planar end link translating in x and y.

    >>> from kinelab.structure import alternative_method
    >>> s = alternative_method("Tx Ty", "planar")
    >>> s.total_connectivity, s.names[0]
    (5, 'RRR+PP')
    """
    return _with_passive("alternative", motion, space, joints, max_joints, drop=1)


_METHODS = {"open": number_synthesis, "active": active_chains, "passive": passive_chain,
            "alternative": alternative_method}


def type_synthesis(space: str, mobility: int | None = None, *, method: str = "active",
                   motion: str | Sequence[str] | None = None, **options) -> TypeSynthesis:
    """One entry to the four methods, as the command line uses it.

    Parameters
    ----------
    space : {'planar', 'spherical', 'spatial'}
    mobility : int, optional
        Needed by ``'open'`` and ``'active'``; for ``'passive'`` and ``'alternative'`` it
        is the length of ``motion`` (and must agree if given).
    method : {'open', 'active', 'passive', 'alternative'}
    motion : str or sequence of str, optional
        The wanted motion (required by ``'passive'`` and ``'alternative'``).
    **options
        ``joints``, ``max_joints``.

    Examples
    --------
    >>> from kinelab.structure import type_synthesis
    >>> type_synthesis("planar", 3).names[:3]
    ('3-RRR', '3-RRP', '3-RPR')
    """
    if method not in _METHODS:
        raise ModelError(f"method: expected one of {', '.join(map(repr, _METHODS))}, got {describe(method)}")
    if method in ("passive", "alternative"):
        if motion is None:
            raise ModelError(f"motion: the {method} method needs the wanted motion, e.g. 'Tx Ty'")
        space_, _ = _space(space)
        want = Motion.parse(motion, space_)
        if mobility is not None and mobility != len(want):
            raise ModelError(f"mobility: {mobility} does not match the motion {want}, which has "
                             f"{len(want)} displacements")
        return _METHODS[method](want, space, **options)
    if mobility is None:
        raise ModelError(f"mobility: the {method} method needs a mobility")
    if method == "open":
        return number_synthesis(mobility, space, motion=motion, **options)
    if motion is not None:
        raise ModelError("motion: active-chain enumeration uses the mobility only; drop the "
                         "motion or use method 'passive' or 'alternative'")
    return active_chains(mobility, space, **options)
