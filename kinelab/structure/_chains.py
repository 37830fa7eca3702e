"""Structural synthesis: every planar kinematic chain with simple revolute joints.

A chain is a graph: links are vertices, joints are edges (a simple joint joins two
links).  With ``N`` links and ``J`` joints its mobility is ``F = 3(N - 1) - 2J``, so
``J = (3N - 3 - F) / 2``.  Counted are the chains that are *proper*: connected, every
link carrying at least two joints, and no part rigid (every subset of ``k`` links with
``e`` joints among them keeps ``3(k - 1) - 2e >= 1``: no triangle, no five links with
six joints, ...).  The classical counts for F = 1 are 1 (4 links), 2 (6: Watt and
Stephenson), 16 (8) and 230 (10).

Enumeration follows the classical route through *contracted graphs*: chains of binary
links (two joints) are paths between the links of three or more joints, so each chain
is a multigraph ``H`` on those links (its edges may be parallel, or loops) with a number
of binary links placed along each edge.  ``H`` has the chain's number of independent
loops ``L = J - N + 1`` and every vertex of degree >= 3, so at most ``2(L - 1)``
vertices.  Steps:

1. the link assortments: how many links of each number of joints (``sum n_i = N``,
   ``sum i n_i = 2J``);
2. the non-isomorphic contracted graphs for each assortment of multiple links;
3. the ways to place the binary links on their edges, up to the symmetries of the
   contracted graph (two placements give isomorphic chains exactly when a symmetry of
   ``H`` maps one onto the other), keeping the chains with no rigid part.
"""
from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache, cached_property
from numbers import Integral

import numpy as np

from kinelab.errors import ModelError, describe, quoted
from kinelab.model import Input, Joint, Link, Mechanism, Point
from kinelab.structure._canon import canonical_form, orbits
from kinelab.structure._count import checked_model, whole
from kinelab.structure._screws import rank
from kinelab.structure._system import ConstraintSystem

__all__ = ["Inversion", "KinematicChain", "chain_of", "count_chains", "planar_chains"]


# -- checks on the counts ---------------------------------------------------------------------
MAX_CHAIN_LINKS = 12   # chains enumerated: every (N, F) within these takes seconds at most
MAX_CHAIN_LOOPS = 4    # independent loops, (N - F - 1) / 2
_WRITTEN_OUT = 10 ** 15  # counts the messages write out in full (and as floats, J = 5.5)


def _joints_for(links, mobility) -> int:
    n, f = whole(links, "links", 4), whole(mobility, "mobility", 1)
    if max(n, f) > _WRITTEN_OUT:     # too long to write out in the messages below
        what, v, fewer = (("links", n, "fewer links") if n > _WRITTEN_OUT
                          else ("mobility", f, "less mobility"))
        raise ModelError(f"{what}: {describe(v)} is beyond what is enumerated: at most "
                         f"{MAX_CHAIN_LINKS} links and {MAX_CHAIN_LOOPS} loops; use {fewer}")
    if (3 * n - 3 - f) % 2:
        raise ModelError(f"mobility {f} is impossible with {n} links: J = (3N - 3 - F) / 2 = "
                         f"{(3 * n - 3 - f) / 2} joints is not a whole number; with simple "
                         "revolute joints N + F must be odd (try "
                         f"{n - 1} or {n + 1} links, or mobility {f - 1 if f > 1 else f + 1})")
    if f > n - 3:
        raise ModelError(f"mobility {f} is impossible with {n} links: a chain in which every "
                         f"link carries two joints has at most N - 3 = {n - 3} freedoms (a "
                         f"single loop); use at least {f + 3} links")
    loops = (n - f - 1) // 2
    if n > MAX_CHAIN_LINKS or loops > MAX_CHAIN_LOOPS:
        raise ModelError(f"links: {n} links with mobility {f} ({loops} independent loops) are "
                         f"beyond what is enumerated: at most {MAX_CHAIN_LINKS} links and "
                         f"{MAX_CHAIN_LOOPS} loops (12 links with mobility 1 alone make 6,856 "
                         "chains of 5 loops, minutes of work); use fewer links or more mobility")
    return (3 * n - 3 - f) // 2


# -- rigid parts --------------------------------------------------------------------------------
@cache
def _subset_bits(n: int) -> np.ndarray:
    masks = np.arange(1 << n, dtype=np.int64)
    return ((masks[:, None] >> np.arange(n)) & 1).astype(np.int16)


def _has_rigid_part(n: int, edges) -> bool:
    """Some set of k >= 3 links with e joints among them has 3(k - 1) - 2e <= 0."""
    bits = _subset_bits(n)
    k = bits.sum(axis=1)
    e = np.zeros(len(bits), dtype=np.int16)
    for u, v in edges:
        e += bits[:, u] & bits[:, v]
    return bool(np.any((k >= 3) & (3 * (k - 1) - 2 * e <= 0)))


# -- contracted graphs ------------------------------------------------------------------------------
def _degree_sequences(v: int, total: int, top: int) -> Iterator[tuple[int, ...]]:
    """Non-increasing sequences of v degrees >= 3 summing to total, each <= top."""
    if v == 0:
        if total == 0:
            yield ()
        return
    for d in range(min(top, total - 3 * (v - 1)), 2, -1):
        for rest in _degree_sequences(v - 1, total - d, d):
            yield (d,) + rest


def _fill(degrees: tuple[int, ...]) -> Iterator[list[list[int]]]:
    """Symmetric multiplicity matrices (loops on the diagonal count twice) with these degrees."""
    v = len(degrees)
    m = [[0] * v for _ in range(v)]
    left = list(degrees)

    def row(i: int, j: int) -> Iterator[None]:
        if i == v:
            yield None
            return
        if j == v:
            if left[i] == 0:
                yield from row(i + 1, i + 1)
            return
        if j == i:
            for loops in range(left[i] // 2, -1, -1):
                m[i][i] = loops
                left[i] -= 2 * loops
                yield from row(i, j + 1)
                left[i] += 2 * loops
            m[i][i] = 0
            return
        for k in range(min(left[i], left[j]), -1, -1):
            m[i][j] = m[j][i] = k
            left[i] -= k
            left[j] -= k
            yield from row(i, j + 1)
            left[i] += k
            left[j] += k
        m[i][j] = m[j][i] = 0

    for _ in row(0, 0):
        yield [r[:] for r in m]


def _connected(m: list[list[int]]) -> bool:
    seen, todo = {0}, [0]
    while todo:
        i = todo.pop()
        for j, k in enumerate(m[i]):
            if k and j not in seen:
                seen.add(j)
                todo.append(j)
    return len(seen) == len(m)


def _min_binaries(m: list[list[int]]) -> int:
    # A loop needs 3 binary links (with 2 it closes a triangle); k parallel edges need k
    # (two edges with 0 and 1 binary links, or both with 0, close a triangle or double a
    # joint).
    v = len(m)
    need = sum(3 * m[i][i] for i in range(v))
    return need + sum(m[i][j] for i in range(v) for j in range(i + 1, v) if m[i][j] > 1)


def _contracted_graphs(v: int, loops: int, binaries: int) -> list[list[list[int]]]:
    """Non-isomorphic contracted graphs on v vertices with the given cycle rank."""
    edges = v + loops - 1
    found: dict[tuple, list[list[int]]] = {}
    for degrees in _degree_sequences(v, 2 * edges, 2 * edges):
        for m in _fill(degrees):
            if _connected(m) and _min_binaries(m) <= binaries:
                found.setdefault(canonical_form(m)[0], m)
    return [found[k] for k in sorted(found)]


# -- binary links along the edges -------------------------------------------------------------------
def _splits(total: int, parts: int, loop: bool) -> Iterator[tuple[int, ...]]:
    """Non-increasing counts of binary links on ``parts`` parallel edges (or loops)."""
    def rec(left: int, k: int, top: int) -> Iterator[tuple[int, ...]]:
        if k == 0:
            if left == 0:
                yield ()
            return
        for b in range(min(top, left), -1, -1):
            for rest in rec(left - b, k - 1, b):
                yield (b,) + rest
    for counts in rec(total, parts, total):
        if loop and counts[-1] < 3:
            continue
        if not loop and parts > 1 and (counts[-1] + counts[-2] < 2):
            continue
        yield counts


def _placements(m: list[list[int]], binaries: int) -> Iterator[dict]:
    classes = [(i, j) for i in range(len(m)) for j in range(i, len(m)) if m[i][j]]

    def rec(k: int, left: int, chosen: dict) -> Iterator[dict]:
        if k == len(classes):
            if left == 0:
                yield dict(chosen)
            return
        i, j = classes[k]
        sizes = range(left, left + 1) if k == len(classes) - 1 else range(left + 1)
        for s in sizes:
            for counts in _splits(s, m[i][j], loop=(i == j)):
                chosen[(i, j)] = counts
                yield from rec(k + 1, left - s, chosen)
        chosen.pop((i, j), None)
    yield from rec(0, binaries, {})


def _expand(v: int, placement: dict) -> tuple[int, list[tuple[int, int]]]:
    """The chain: multiple links 0..v-1, then the binary links along each edge."""
    edges, n = [], v
    for (i, j), counts in sorted(placement.items()):
        for b in counts:
            path = [i, *range(n, n + b), j]
            n += b
            edges += list(zip(path[:-1], path[1:]))
    return n, edges


# -- the chain ------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Inversion:
    """A mechanism obtained from a chain by fixing one of its links.

    Attributes
    ----------
    chain : KinematicChain
    ground : int
        The fixed link (index in the chain).
    equivalent : tuple of int
        Every link whose fixing gives the same mechanism (its orbit under the chain's
        symmetries).
    description : str
        The fixed link's kind and neighbours.
    """

    chain: KinematicChain
    ground: int
    equivalent: tuple[int, ...]
    description: str

    def to_mechanism(self, *, name: str | None = None, seed: int = 0) -> Mechanism:
        """The mechanism with a valid sketch; see :meth:`KinematicChain.to_mechanism`."""
        return self.chain.to_mechanism(self.ground, name=name, seed=seed)


_KINDS = {2: "binary", 3: "ternary", 4: "quaternary", 5: "pentagonal", 6: "hexagonal"}


def _kind(d: int) -> str:
    return _KINDS.get(d, f"{d}-joint")


@dataclass(frozen=True)
class KinematicChain:
    """A planar kinematic chain with simple revolute joints.

    Attributes
    ----------
    links : int
        ``N``.
    joints : tuple of (int, int)
        The links each joint joins (links numbered 0 .. N-1 in a canonical order, so
        that isomorphic chains have equal ``joints``).
    mobility : int
        ``F = 3(N - 1) - 2J``.
    name : str
        ``'four-bar'``, ``'Watt'``, ``'Stephenson'``, or ``'N-link chain no. k'``.
    """

    links: int
    joints: tuple[tuple[int, int], ...]
    mobility: int
    name: str = ""

    @cached_property
    def adjacency(self) -> np.ndarray:
        """``(N, N)`` 0/1 matrix: which links share a joint."""
        a = np.zeros((self.links, self.links), dtype=int)
        for u, v in self.joints:
            a[u, v] = a[v, u] = 1
        return a

    @property
    def degrees(self) -> tuple[int, ...]:
        """Joints carried by each link."""
        return tuple(int(d) for d in self.adjacency.sum(axis=1))

    @property
    def assortment(self) -> dict[int, int]:
        """``{joints per link: number of such links}``, e.g. ``{2: 4, 3: 2}``."""
        out: dict[int, int] = {}
        for d in self.degrees:
            out[d] = out.get(d, 0) + 1
        return dict(sorted(out.items()))

    @property
    def loops(self) -> int:
        """Independent loops, ``J - N + 1``."""
        return len(self.joints) - self.links + 1

    def inversions(self) -> tuple[Inversion, ...]:
        """The distinct mechanisms obtained by fixing each link in turn.

        Fixing links that a symmetry of the chain exchanges gives the same mechanism;
        one inversion is kept per class.

        Examples
        --------
        >>> from kinelab.structure import planar_chains
        >>> [(c.name, len(c.inversions())) for c in planar_chains(6)]
        [('Watt', 2), ('Stephenson', 3)]
        """
        deg = self.degrees
        out = []
        for orbit in orbits(self.adjacency.tolist()):
            g = orbit[0]
            near = sorted(deg[w] for w in range(self.links) if self.adjacency[g, w])
            kinds = ", ".join(f"{near.count(d)} {_kind(d)}" for d in sorted(set(near)))
            out.append(Inversion(self, g, tuple(orbit), f"fixed link: {_kind(deg[g])}, "
                                 f"joined to {kinds}"))
        return tuple(out)

    def to_mechanism(self, ground: int = 0, *, name: str | None = None,
                     seed: int = 0) -> Mechanism:
        """A planar model of the chain with link ``ground`` fixed, and a valid sketch.

        Links are named ``link1`` (the fixed one, as link 1 of the notes) to ``linkN`` in
        breadth-first order from it; joints ``jA``, ``jB``, ... act at points ``A``,
        ``B``, ...  The sketch places the links around a circle with the joints between
        them, moved by small reproducible random amounts (``seed``) so that no special
        geometry creeps in: the sketch is checked to have exactly ``mobility`` freedoms
        and ``mobility`` inputs that drive it (joints of the fixed link first).

        Examples
        --------
        >>> from kinelab.structure import planar_chains, mobility
        >>> watt = planar_chains(6)[0]
        >>> m = watt.to_mechanism(ground=0)
        >>> m.ground.name, len(m.links), len(m.joints), mobility(m).exact
        ('link1', 6, 7, 1)
        """
        if isinstance(ground, bool) or not isinstance(ground, Integral) or not 0 <= ground < self.links:
            raise ModelError(f"ground: expected a link of the chain, 0 to {self.links - 1}, "
                             f"got {describe(ground)}")
        return _sketch(self, int(ground), name, whole(seed, "seed", 0))

    def __repr__(self) -> str:
        a = ", ".join(f"{n} {_kind(d)}" for d, n in self.assortment.items())
        return (f"KinematicChain({self.name!r}, {self.links} links, {len(self.joints)} "
                f"joints, F = {self.mobility}: {a})")


def _canonical_chain(n: int, edges, mobility: int) -> tuple[tuple, KinematicChain]:
    a = [[0] * n for _ in range(n)]
    for u, v in edges:
        a[u][v] = a[v][u] = 1
    form, order = canonical_form(a)
    where = {v: k for k, v in enumerate(order)}
    joints = tuple(sorted(tuple(sorted((where[u], where[v]))) for u, v in edges))
    return form, KinematicChain(n, joints, mobility)


def _name(chain: KinematicChain, index: int) -> str:
    if chain.links == 4 and chain.mobility == 1:
        return "four-bar"
    if chain.links == 5 and chain.mobility == 2:
        return "five-bar"
    if chain.links == 6 and chain.mobility == 1:
        t = [k for k, d in enumerate(chain.degrees) if d == 3]
        return "Watt" if chain.adjacency[t[0], t[1]] else "Stephenson"
    return f"{chain.links}-link chain no. {index}"


@cache
def _enumerate(n: int, f: int) -> tuple[KinematicChain, ...]:
    j = _joints_for(n, f)
    loops = j - n + 1
    found: dict[tuple, KinematicChain] = {}
    if loops == 1:
        form, chain = _canonical_chain(n, [(k, (k + 1) % n) for k in range(n)], f)
        found[form] = chain
    for v in range(1, 2 * (loops - 1) + 1):
        binaries = n - v
        if binaries < 0:
            break
        for m in _contracted_graphs(v, loops, binaries):
            seen = set()
            for placement in _placements(m, binaries):
                size, edges = _expand(v, placement)
                if _has_rigid_part(size, edges):
                    continue
                deco = [[tuple(placement.get((min(a, b), max(a, b)), ())) for b in range(v)]
                        for a in range(v)]
                key = canonical_form(deco, absent=())[0]
                if key in seen:
                    continue
                seen.add(key)
                form, chain = _canonical_chain(size, edges, f)
                found.setdefault(form, chain)
    chains = sorted(found.values(), key=lambda c: (sorted(c.assortment.items(), reverse=True),
                                                   c.joints))
    return tuple(KinematicChain(c.links, c.joints, f, _name(c, k + 1))
                 for k, c in enumerate(chains))


def planar_chains(links: int, mobility: int = 1) -> tuple[KinematicChain, ...]:
    """Every non-isomorphic planar chain with simple revolute joints, ``links`` links and
    the given mobility, without rigid parts.

    Parameters
    ----------
    links : int
        ``N >= 4``.
    mobility : int, optional
        ``F >= 1``; ``N + F`` must be odd and ``F <= N - 3``.

    Returns
    -------
    tuple of KinematicChain
        In a fixed order: by link assortment (most joints on one link last), then by
        canonical joint list.

    Raises
    ------
    ModelError
        When no chain can have these numbers, or beyond 12 links or 4 independent loops
        (``(N - F - 1) / 2``), where the chains number thousands and take minutes to list.

    Examples
    --------
    >>> from kinelab.structure import planar_chains
    >>> planar_chains(6)
    (KinematicChain('Watt', 6 links, 7 joints, F = 1: 4 binary, 2 ternary), KinematicChain('Stephenson', 6 links, 7 joints, F = 1: 4 binary, 2 ternary))
    >>> [len(planar_chains(n)) for n in (4, 6, 8)]
    [1, 2, 16]
    """
    _joints_for(links, mobility)  # before the cache, where 6.0 would find 6
    return _enumerate(int(links), int(mobility))


def count_chains(links: int, mobility: int = 1) -> int:
    """How many non-isomorphic planar chains with simple revolute joints there are.

    See :func:`planar_chains`.

    Examples
    --------
    >>> from kinelab.structure import count_chains
    >>> count_chains(4), count_chains(6), count_chains(8)
    (1, 2, 16)
    """
    return len(planar_chains(links, mobility))


def chain_of(model: Mechanism) -> KinematicChain:
    """The kinematic chain of a planar model with revolute joints only, named as in
    :func:`planar_chains` when it is one of them.

    Raises
    ------
    ModelError
        If the model has other joints than R, or two joints between the same links.

    Examples
    --------
    >>> from kinelab.structure import planar_chains, chain_of
    >>> chain_of(planar_chains(6)[1].to_mechanism(ground=2)).name
    'Stephenson'
    """
    other = [j.name for j in checked_model(model).joints if j.type != "R"]
    if other:
        raise ModelError(f"joints {quoted(other)}: a kinematic chain here has revolute joints "
                         "only")
    names = list(model.link_names)
    edges = [tuple(sorted(names.index(x) for x in j.links)) for j in model.joints]
    if len(set(edges)) < len(edges):
        raise ModelError("two joints join the same two links; they make one rigid joint")
    n, j = len(names), len(edges)
    f = 3 * (n - 1) - 2 * j
    form, chain = _canonical_chain(n, edges, f)
    try:
        for known in planar_chains(n, f):
            if known.joints == chain.joints:
                return known
    except ModelError:
        pass
    return chain


# -- a model with a sketch -------------------------------------------------------------------------
def _letters(k: int) -> str:
    out = ""
    k += 1
    while k:
        k, r = divmod(k - 1, 26)
        out = chr(ord("A") + r) + out
    return out


def _sketch(chain: KinematicChain, ground: int, name: str | None, seed: int) -> Mechanism:
    n = chain.links
    order, todo = [ground], [ground]
    while todo:  # breadth first from the fixed link: link1, link2, ...
        u = todo.pop(0)
        for w in np.flatnonzero(chain.adjacency[u]):
            if int(w) not in order:
                order.append(int(w))
                todo.append(int(w))
    label = {u: f"link{k + 1}" for k, u in enumerate(order)}
    joints = sorted(chain.joints, key=lambda e: sorted(order.index(x) for x in e))
    for attempt in range(20):
        rng = np.random.default_rng(seed + 1000 * attempt)
        angle = 2 * np.pi * np.arange(n) / n - np.pi / 2  # the fixed link at the bottom
        centre = {u: np.array([np.cos(angle[k]), np.sin(angle[k])]) + 0.15 * rng.standard_normal(2)
                  for k, u in enumerate(order)}
        pts, carried = [], {u: [] for u in range(n)}
        for k, (u, v) in enumerate(joints):
            p = 0.5 * (centre[u] + centre[v]) + 0.1 * rng.standard_normal(2)
            pts.append(Point(_letters(k), float(p[0]), float(p[1])))
            carried[u].append(_letters(k))
            carried[v].append(_letters(k))
        xy = np.array([p.xy for p in pts])
        gaps = np.linalg.norm(xy[:, None] - xy[None], axis=-1) + np.eye(len(pts))
        if gaps.min() < 0.05:  # joints drawn on top of one another: draw again
            continue
        links = tuple(Link(label[u], tuple(carried[u]), ground=(u == ground)) for u in order)
        js = tuple(Joint(f"j{_letters(k)}", "R", (label[u], label[v]), point=_letters(k))
                   for k, (u, v) in enumerate(joints))
        m = Mechanism(name or f"{chain.name} with link {ground} fixed",
                      tuple(pts), links, js)
        system = ConstraintSystem.of(m)
        c = system.matrix()
        r = rank(c)
        if system.unknowns - r != chain.mobility:  # a special sketch: draw again
            continue
        chosen = []
        for j in sorted(js, key=lambda j: "link1" not in j.links):  # the fixed link's first
            lock = system.relative(*j.links)[:1]  # the joint's relative rotation
            if rank(np.vstack([c, lock])) > r:
                c = np.vstack([c, lock])
                r += 1
                chosen.append(j.name)
            if len(chosen) == chain.mobility:
                return Mechanism(m.name, m.points, m.links, m.joints,
                                 tuple(Input(joint=name) for name in chosen))
    raise ModelError(f"could not draw a generic sketch of {chain.name}; try another seed")
