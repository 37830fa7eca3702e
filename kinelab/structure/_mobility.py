"""Mobility of a model: the Kutzbach-Gruebler count beside the exact value of its geometry."""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from kinelab.model import Mechanism
from kinelab.structure._count import checked_model, kutzbach_gruebler, pair_counts, space_dimension
from kinelab.structure._motion import moved
from kinelab.structure._screws import RTOL, _threshold, checked_rtol, null_basis, rank
from kinelab.structure._system import ConstraintSystem

__all__ = ["Mobility", "mobility"]


@dataclass(frozen=True)
class Mobility:
    """The mobility of a mechanism, counted and computed, with the reasons they differ.

    Attributes
    ----------
    kutzbach_gruebler : int
        ``M = lambda (Ne - 1) - sum (lambda - j) nPj`` from the counts alone.
    exact : int
        Independent motions at the sketch (near it, if the sketch is singular) that move
        some point of the model: the dimension of the null space of the constraint
        Jacobian, less the passive freedoms.
    explanation : str
        The count written out, the exact value, and why they differ.
    space : str
    lam : int
        lambda, the dimension of the motion space (3 planar or spherical, 6 spatial).
    links : int
        ``Ne``, links including the ground.
    pairs : dict of int to int
        ``{j: nPj}``.
    freedoms : int
        Dimension of the null space of the constraint Jacobian (``exact + passive``).
    passive : int
        Freedoms that move no point of the model, as the spin of a link between two
        spherical joints about the line through their centres.
    redundant : int
        ``freedoms - kutzbach_gruebler``: constraint equations the count takes as
        independent but which the geometry makes repeat others (over-constraint).  It is
        negative only for a spherical model whose axes do not meet at one point, or a
        linkage whose lengths let it assemble in the sketch's flat shape alone.
    local : tuple of str
        Local freedoms that count, described: a link (or links together) that can move
        while all the others stay at rest and moves some of its points doing so, e.g. a
        roller spinning on its pin or the knuckle of a suspension turning to steer.
    assumed : tuple of str
        Geometry the model leaves out and that was taken in general position.
    singular_values : tuple of float
        Of the dimensionless constraint Jacobian at the sketch, largest first; those
        below ``rtol`` times the largest count as zero.
    singular : bool
        The sketch is a singular configuration: the Jacobian there allows more motions
        than the mechanism has once moved a little (a linkage folded flat at a change
        point), and ``exact`` is the value nearby.
    """

    kutzbach_gruebler: int
    exact: int
    explanation: str
    space: str
    lam: int
    links: int
    pairs: Mapping[int, int]
    freedoms: int
    passive: int
    redundant: int
    local: tuple[str, ...] = ()
    assumed: tuple[str, ...] = ()
    singular_values: tuple[float, ...] = field(default=(), repr=False)
    singular: bool = False

    def __str__(self) -> str:
        return self.explanation

    def to_dict(self) -> dict:
        """Plain data (for JSON): every field but the singular values."""
        return {"kutzbach_gruebler": self.kutzbach_gruebler, "exact": self.exact,
                "explanation": self.explanation, "space": self.space, "lambda": self.lam,
                "links": self.links, "pairs": {f"P{j}": n for j, n in self.pairs.items()},
                "freedoms": self.freedoms, "passive": self.passive,
                "redundant": self.redundant, "local": list(self.local),
                "assumed": list(self.assumed)}


def _formula(lam: int, ne: int, pairs: Mapping[int, int], m: int) -> str:
    terms = "".join(f" − {lam - j}·{n}" for j, n in sorted(pairs.items()) if j < lam and n)
    return f"M = {lam}({ne} − 1){terms} = {m}"


def _plural(n: int, one: str, many: str) -> str:
    return f"{n} {one if n == 1 else many}"


def _collinear(points: np.ndarray, tol: float = 1e-9) -> bool:
    """At least two distinct points, all on one line (dimensionless coordinates)."""
    if len(points) < 2:
        return False
    s = np.linalg.svd(points - points.mean(axis=0), compute_uv=False)
    return s[0] > tol and (len(s) < 2 or s[1] <= tol)


def _groups(system: ConstraintSystem) -> list[tuple[str, ...]]:
    """Sets of moving links that may move on their own as one body.

    Each single moving link; in space also each connected set of moving links whose
    points all lie on one line (a leg S-P-S spins as one body about that line).
    """
    model = system.model
    groups = {(name,) for name in system.moving}
    if system.planar:
        return sorted(groups)
    pts = {n: [system.frame.point(model, p) for p in model.link(n).points] for n in system.moving}
    neighbours = {n: {m for j in model.joints_of(n) for m in j.links if m != n and m in pts}
                  for n in system.moving}
    found: set[frozenset[str]] = set()
    todo = [frozenset([n]) for n in system.moving if _collinear(np.array(pts[n]))]
    while todo and len(found) < 10_000:
        g = todo.pop()
        if g in found:
            continue
        found.add(g)
        for n in set().union(*(neighbours[m] for m in g)) - g:
            bigger = g | {n}
            if bigger not in found and _collinear(np.array([p for m in bigger for p in pts[m]])):
                todo.append(bigger)
    groups |= {tuple(sorted(g, key=system.moving.index)) for g in found}
    return sorted(groups, key=lambda g: (len(g), [system.moving.index(n) for n in g]))


def _local_motions(system: ConstraintSystem, rtol: float):
    """Motions of one group with every other link at rest, split into passive and counted.

    Returns ``(passive vectors, counted vectors, passive descriptions, counted
    descriptions)``; vectors are full motions (length ``system.unknowns``).
    """
    model = system.model
    passive, counted, passive_txt, counted_txt = [], [], [], []
    for group in _groups(system):
        outside = [j for j in model.joints if (j.links[0] in group) != (j.links[1] in group)]
        if len(outside) < 2:
            continue  # the free end of an open chain: its motion is an output, not local
        w = np.vstack([system.constraints[j.name] for j in outside])
        local = null_basis(w, rtol)
        if local.shape[1] == 0:
            continue
        names = [p for n in group for p in model.link(n).points]
        v = np.vstack([system.point_velocity(p) for p in names])
        still = local @ null_basis(v @ local, rtol, scale=np.linalg.norm(v, 2))

        def full(twists: np.ndarray) -> list[np.ndarray]:
            out = []
            for t in twists.T:
                x = np.zeros(system.unknowns)
                for n in group:
                    x[system.block(n)] = t
                out.append(x)
            return out
        who = (f"link '{group[0]}'" if len(group) == 1
               else "links " + ", ".join(f"'{n}'" for n in group) + " together")
        if still.shape[1]:
            passive += full(still)
            passive_txt.append(f"{who} can spin about the line through "
                               f"{'its' if len(group) == 1 else 'their'} points without moving "
                               "any of them or any other link")
        if local.shape[1] > still.shape[1]:
            counted += full(local)
            counted_txt.append(f"{who} can move alone while every other link stays at rest "
                               "(a local freedom); that motion moves points of the model, so it "
                               "counts")
    return passive, counted, passive_txt, counted_txt


@dataclass(frozen=True)
class _State:
    """What the constraint Jacobian says at one configuration."""

    freedoms: int
    passive: int
    passive_txt: tuple[str, ...]
    counted_txt: tuple[str, ...]
    rows: int
    singular_values: tuple[float, ...]


def _state(system: ConstraintSystem, rtol: float) -> _State:
    c = system.matrix()
    s = np.linalg.svd(c, compute_uv=False) if c.size else np.zeros(0)
    passive_v, counted_v, passive_txt, counted_txt = _local_motions(system, rtol)
    return _State(system.unknowns - int(np.sum(s > _threshold(s, rtol, None))),
                  rank(np.array(passive_v), rtol) if passive_v else 0,
                  tuple(passive_txt), tuple(counted_txt) if counted_v else (), c.shape[0],
                  tuple(float(x) for x in s))


def _motions(n: int) -> str:
    return _plural(n, "independent motion", "independent motions")


def mobility(model: Mechanism, *, rtol: float = RTOL) -> Mobility:
    """Mobility of a mechanism: Kutzbach-Gruebler's count and the exact value.

    The count ``M = lambda (Ne - 1) - sum (lambda - j) nPj`` (*Mecanismos*, Eq. 1) assumes
    that every constraint a pair imposes is independent of the others.  The exact value
    is the dimension of the space of motions the mechanism allows at its sketch: each
    moving link gets a twist (3 unknowns in the plane, 6 in space), each joint requires
    the relative twist of its links to lie in the span of its freedom screws, and the
    motions are the null space of the resulting constraint Jacobian ``C`` (its rank is
    found by SVD, with singular values below ``rtol`` times the largest taken as zero).
    The count and the rank differ exactly by the number of constraint equations that
    repeat others, which is what special geometry (parallel or concurrent axes, equal
    lengths, Bennett's conditions) produces.  Freedoms that move no point of the model
    (the spin of an S-S link about the line through its centres) are passive and are
    reported apart.

    Parameters
    ----------
    model : Mechanism
        Planar models use planar twists (R, P and the planar higher pairs); spherical and
        spatial models use spatial ones (R, P, H, C, U, S, E and the higher pairs).  The
        sketch is the configuration examined.  At a singular one (a linkage folded flat
        at a change point) the rank drops and the motions at that instant exceed the
        mechanism's; so a mechanism with lower pairs only (and pins in slots) is also
        moved a little along its motion, by Gauss-Newton on its finite-displacement
        constraints, and where the sketch proves singular the value nearby is reported
        (``singular``).  Cam, gear and rolling contacts need profiles the model does not
        hold: draw such mechanisms in a general position.
    rtol : float, optional
        Relative tolerance on the singular values of the dimensionless ``C``, from
        ``1e-13`` (above the roundings of the sketch) to ``1e-3`` (a geometry that far from
        special is not taken as special); default ``1e-9``.

    Returns
    -------
    Mobility
        ``kutzbach_gruebler``, ``exact``, ``explanation`` and the breakdown.

    Raises
    ------
    ModelError
        If a joint's pair has no meaning in the model's space, or ``rtol`` is outside
        ``[1e-13, 1e-3]``.

    Notes
    -----
    A spatial R joint without an axis, a U joint without ``axis2`` or a contact pair
    without a point or normal is taken in general position (reproducibly); the result
    says so in ``assumed``.  In a spherical model an R joint without an axis turns about
    the line from the origin (the centre) through its point.  For cam and gear pairs the
    ``axis`` is the common normal at the contact (the line of action of gear teeth).

    Examples
    --------
    A four-bar: count and rank agree.

    >>> m = mobility(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5))
    >>> m.kutzbach_gruebler, m.exact
    (1, 1)
    >>> print(m.explanation)
    Kutzbach-Gruebler (planar, λ = 3): M = 3(4 − 1) − 2·4 = 1.
    Exact (rank of the constraint Jacobian at the sketch): M = 1, as counted: no constraint repeats another and no freedom is passive.
    """
    model, rtol = checked_model(model), checked_rtol(rtol)
    lam = space_dimension(model.space)
    pairs = pair_counts(model)
    ne = len(model.links)
    count = kutzbach_gruebler(ne, pairs, lam)
    system = ConstraintSystem.of(model)
    here = _state(system, rtol)
    state, singular, note = here, False, ""
    # The rank can only drop at special configurations, so the motions nearby are at
    # least unknowns - rows; a sketch that already has that few is not singular.
    if here.freedoms > max(0, system.unknowns - here.rows):
        moved_models = moved(system, seed=0)
        if moved_models is None:
            pass  # contact profiles or assumed geometry: the sketch is taken as general
        elif not moved_models:
            state, singular = replace(here, freedoms=0, passive=0, counted_txt=()), True
            note = (f"at the sketch the constraint Jacobian allows {_motions(here.freedoms)}, "
                    "but none goes any distance: the sketch is a singular configuration of a "
                    "structure that cannot move (a shaky structure: the lengths allow only "
                    "this assembly)")
        else:
            systems = [ConstraintSystem.of(m) for m in moved_models]
            free = [sy.unknowns - rank(sy.matrix(), rtol) for sy in systems]
            nearest = int(np.argmin(free))
            if free[nearest] < here.freedoms:
                state = _state(systems[nearest], rtol)
                singular = True
                note = (f"at the sketch the constraint Jacobian allows "
                        f"{_motions(here.freedoms)}: it is a singular configuration (folded "
                        "flat, a change point); moved a little along its motion the "
                        f"mechanism allows {_motions(state.freedoms)}")
            else:
                state = here
    freedoms, passive = state.freedoms, state.passive
    exact = freedoms - passive
    redundant = freedoms - count

    lines = [f"Kutzbach-Gruebler ({model.space}, λ = {lam}): {_formula(lam, ne, pairs, count)}."]
    where = "near" if singular else "at"
    head = f"Exact (rank of the constraint Jacobian {where} the sketch): M = {exact}"
    reasons = [note] if note else []
    special = freedoms - max(count, 0)
    if count < 0:
        reasons.append(
            f"a negative count only says there are {-count} more constraint equations than "
            "needed to make the structure rigid; a mobility is never below 0")
    if special > 0:
        if count < 0:
            of, more = "", "beyond those, "
        else:
            of, more = (f" of the {state.rows}" if lam == system.dim else ""), ""
        reasons.append(
            f"{more}{_plural(special, 'constraint equation', 'constraint equations')}{of} "
            f"{'repeats' if special == 1 else 'repeat'} others because the geometry is special "
            "(over-constraint: parallel or concurrent axes, equal lengths, ...), which the "
            "count cannot see")
    elif special < 0 and not singular:
        reasons.append(
            f"the geometry gives {_plural(-special, 'freedom', 'freedoms')} fewer than the "
            "count: the joint axes do not all pass through one point, so the linkage is not "
            "the spherical one the count assumes")
    if passive:
        reasons.append(f"{_plural(passive, 'freedom is', 'freedoms are')} passive and not "
                       "counted: " + "; ".join(state.passive_txt))
    reasons += state.counted_txt
    if exact == count and not reasons:
        lines.append(f"{head}, as counted: no constraint repeats another and no freedom is "
                     "passive.")
    else:
        verdict = "as counted" if exact == count else f"not {count} as counted"
        lines.append(f"{head}, {verdict}: " + "; ".join(reasons) + ".")
    if system.notes:
        lines.append("Assumed: " + "; ".join(system.notes) + ".")
    return Mobility(count, exact, "\n".join(lines), model.space, lam, ne, pairs, freedoms,
                    passive, redundant, state.counted_txt, system.notes, here.singular_values,
                    singular)
