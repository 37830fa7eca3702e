"""Instant centres found as the notes find them (primary centres from the joints, the
others by Kennedy's theorem on the circle diagram), the centrodes of a link, and the
angular-velocity-ratio theorem.

Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades* (Universidade do
Minho, 2007), §4.6.3 and §4.7.1 (eq. 4.121).

Centres are handled in homogeneous coordinates (x, y, w): a finite centre is (x, y, 1),
a centre at infinity is its direction (dx, dy, 0).  The line through two centres is their
cross product and the meeting point of two lines is theirs, so a line towards a centre at
infinity (a slide) and two parallel lines (a centre at infinity) need no special case.
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from kinelab.errors import ModelError, SingularityError, describe, quoted, suggest
from kinelab.kinematics._instant_centers import InstantCenter, InstantCenters, _centers, _model_order
from kinelab.kinematics._polygons import _q_text, _sweep
from kinelab.kinematics._solution import KinematicSolution, takes_solution
from kinelab.model import cam_pair, cam_values, gear_mesh

__all__ = ["KennedyStep", "KennedyConstruction", "Centrodes", "kennedy_construction",
           "centrodes", "velocity_ratio"]

_DEGENERATE = 1e-9   # two centres this close (relative to the mechanism's size) do not fix a
                     # line, and two lines this close to one another do not fix a point
_INFINITE = 1e-12    # a meeting point farther than 1e12 times the mechanism's size is at
                     # infinity (instant_centers uses the same ratio of angular velocities)


@dataclass(frozen=True)
class KennedyStep:
    """One secondary centre, found by Kennedy's theorem: I_ab lies on the line through
    I_ak and I_kb and on the line through I_al and I_lb, for two other links k and l.

    Attributes
    ----------
    pair : (str, str)
        Links a and b, in model order.
    thirds : tuple of (str, str)
        The pairs of third links (k, l) that give two such lines, in the order tried.
    chosen : ndarray of int, shape () or (N,)
        Index into ``thirds`` of the pair used at each sample; -1 where every pair of lines
        is degenerate (the lines coincide), and the centre was taken from the velocities.
    center : InstantCenter
    """

    pair: tuple[str, str]
    thirds: tuple[tuple[str, str], ...]
    chosen: np.ndarray
    center: InstantCenter


@dataclass(frozen=True)
class KennedyConstruction:
    """Every instant centre, found by the notes' construction.

    Number the links (the ground is 1, the others follow in model order) and place the
    numbers on a circle: each known centre is a chord.  The primary centres come from the
    joints: a revolute joint's centre is its pin, a gear pair's its pitch point, a prismatic
    joint's is at infinity, perpendicular to the slide.  Then, one at a time, the lowest-numbered unknown pair that
    closes two triangles of known chords is found by Kennedy's theorem (the three centres
    of any three links lie on one line), and becomes a chord in turn.  Pairs that never
    close two triangles are taken from the velocities (``from_velocities``).

    Attributes
    ----------
    numbers : dict of str to int
        Each link's number.
    primary : dict of (str, str) to str
        Pairs whose centre is a joint, and the joint.
    steps : tuple of KennedyStep
        The secondary centres, in the order found.
    from_velocities : tuple of (str, str)
        Pairs the construction cannot reach.
    centers : InstantCenters
        All n (n - 1) / 2 centres.  Positions at singular samples are NaN, as in
        :func:`instant_centers`.
    """

    numbers: dict[str, int]
    primary: dict[tuple[str, str], str]
    steps: tuple[KennedyStep, ...]
    from_velocities: tuple[tuple[str, str], ...]
    centers: InstantCenters

    def label(self, pair) -> str:
        """The notes' name of a centre: ``'O13'`` (``'O1,12'`` past nine links)."""
        i, j = sorted(self.numbers[x] for x in pair)
        return f"O{i}{j}" if max(i, j) < 10 else f"O{i},{j}"


def _unit(h: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(h, axis=-1, keepdims=True)
    return h / np.where(n > 0, n, 1.0)


def _to_homogeneous(c: InstantCenter, size: float, n: int) -> np.ndarray:
    pos = np.reshape(c.position, (n, 2)) / size
    d = np.reshape(c.direction, (n, 2))
    inf = np.reshape(c.at_infinity, (n,))
    h = np.where(inf[:, None], np.concatenate([d, np.zeros((n, 1))], axis=1),
                 np.concatenate([pos, np.ones((n, 1))], axis=1))
    return _unit(h)


def _from_homogeneous(pair, h: np.ndarray, size: float, single: bool) -> InstantCenter:
    w = h[:, 2]
    xy = h[:, :2]
    norm = np.linalg.norm(xy, axis=1)
    inf = np.abs(w) <= _INFINITE * norm
    with np.errstate(divide="ignore", invalid="ignore"):
        position = np.where(inf[:, None], 0.0, xy / np.where(inf, 1.0, w)[:, None] * size)
        direction = np.where(inf[:, None], xy / np.where(norm > 0, norm, 1.0)[:, None], 0.0)
    nan = ~np.isfinite(h).all(axis=1)
    position[nan] = np.nan
    if single:
        return InstantCenter(pair, position[0], inf[0], direction[0])
    return InstantCenter(pair, position, inf, direction)


def _size(sol: KinematicSolution) -> float:
    """A length of the mechanism's size, to measure closeness without units."""
    xy = np.array([p.xy for p in sol.mechanism.points])
    return float(max(np.ptp(xy, axis=0).max(), 1e-300))


@takes_solution
def kennedy_construction(sol: KinematicSolution) -> KennedyConstruction:
    """Every instant centre by the notes' construction: primary centres from the joints,
    secondary ones by Kennedy's theorem in the order of the circle diagram, at every sample.

    Unlike :func:`instant_centers`, which solves the velocities for the point of equal
    velocity, this uses only the positions of the joints (and of the velocities only for
    pairs the construction cannot reach): the two agree, which the tests check.

    Parameters
    ----------
    sol : KinematicSolution

    Returns
    -------
    KennedyConstruction
        Centres shaped by the rule of ``sol``: (2,) or (N, 2) positions.

    Examples
    --------
    The four-bar: O12, O23, O34 and O14 are its pins; O13 is where O12O23 meets O14O34
    (the lines of the crank and the rocker), then O24 where O12O14 meets O23O34:

    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    >>> kc = kl.kinematics.kennedy_construction(kl.analyze(fb, q=np.radians(60.0)))
    >>> [kc.label(p) for p in kc.primary], [kc.label(s.pair) for s in kc.steps]
    (['O12', 'O23', 'O34', 'O14'], ['O13', 'O24'])
    >>> kc.steps[0].thirds           # O13 on the line O12-O23 and on the line O14-O34
    (('crank', 'rocker'),)
    """
    m = sol.mechanism
    n = sol.N
    size = _size(sol)
    links = [m.ground.name] + [lk for lk in sol.link_names if lk != m.ground.name]
    numbers = {lk: k + 1 for k, lk in enumerate(links)}

    def key(a, b):
        return _model_order(sol, a, b)
    known: dict[tuple[str, str], np.ndarray] = {}
    primary: dict[tuple[str, str], str] = {}
    for j in m.joints:
        pair = key(*j.links)
        if pair in primary:
            continue
        if j.type == "R":
            c = InstantCenter(pair, _sweep(sol, sol.position(j.point)), np.zeros(n, bool), np.zeros((n, 2)))
        elif j.type == "G":     # the pitch point, where the pitch circles roll
            c = InstantCenter(pair, _sweep(sol, _pitch_point(sol, j)), np.zeros(n, bool),
                              np.zeros((n, 2)))
        elif j.type == "C":
            known[pair] = _cam_centre(sol, j, size)
            primary[pair] = j.name
            continue
        else:
            u = _sweep(sol, sol.slide_axes(j.name))
            c = InstantCenter(pair, np.zeros((n, 2)), np.ones(n, bool),
                              np.stack([-u[:, 1], u[:, 0]], axis=1))
        known[pair] = _to_homogeneous(c, size, n)
        primary[pair] = j.name
    steps = []
    by_number = sorted(itertools.combinations(links, 2), key=lambda p: (numbers[p[0]], numbers[p[1]]))
    while True:
        todo = None
        for a, b in by_number:
            if key(a, b) in known:
                continue
            thirds = [k for k in links if k not in (a, b) and key(a, k) in known and key(k, b) in known]
            if len(thirds) >= 2:
                todo = (a, b, list(itertools.combinations(thirds, 2)))
                break
        if todo is None:
            break
        a, b, thirds = todo
        found = np.full((n, 3), np.nan)
        chosen = np.full(n, -1)
        for t, (k, l) in enumerate(thirds):
            line1 = _unit(np.cross(known[key(a, k)], known[key(k, b)]))
            line2 = _unit(np.cross(known[key(a, l)], known[key(l, b)]))
            meet = np.cross(line1, line2)
            ok = ((np.linalg.norm(np.cross(known[key(a, k)], known[key(k, b)]), axis=1) > _DEGENERATE)
                  & (np.linalg.norm(np.cross(known[key(a, l)], known[key(l, b)]), axis=1) > _DEGENERATE)
                  & (np.linalg.norm(meet, axis=1) > _DEGENERATE) & (chosen < 0))
            found[ok] = _unit(meet[ok])
            chosen[ok] = t
        pair = key(a, b)
        if (chosen < 0).any():       # every pair of lines coincides: from the velocities
            missing = chosen < 0
            found[missing] = _to_homogeneous(_centers(sol, [pair])[pair], size, n)[missing]
        found[sol.singular] = np.nan     # as instant_centers: no velocities, no centres
        known[pair] = found
        steps.append(KennedyStep(pair, tuple(thirds), chosen[0] if sol.single else chosen,
                                 _from_homogeneous(pair, found, size, sol.single)))
    rest = [key(a, b) for a, b in by_number if key(a, b) not in known]
    centers = {p: _from_homogeneous(p, known[p], size, sol.single) for p in primary}
    centers.update({s.pair: s.center for s in steps})
    if rest:
        centers.update(_centers(sol, rest))
    order = [key(a, b) for a, b in itertools.combinations(sol.link_names, 2)]
    return KennedyConstruction(numbers, primary, tuple(steps), tuple(rest),
                               InstantCenters({p: centers[p] for p in order}))


@dataclass(frozen=True)
class Centrodes:
    """The centrodes of a link over a sweep: the paths of its instant centre relative to
    the ground, traced on the ground (fixed centrode) and on the link (moving centrode).
    As the link moves, the moving centrode rolls without slipping on the fixed one; they
    touch at the instant centre.

    Attributes
    ----------
    link : str
    fixed : ndarray, shape (N, 2)
        m, in the ground frame.
    moving : ndarray, shape (N, 2)
        m, in the link's own frame: from its first point, along the direction from its
        first point to its second (its angle) and to the left of it.
    at_infinity : ndarray of bool, shape (N,)
        The link translates at that sample: its centre is at infinity.
    defined : ndarray of bool, shape (N,)
        Where the centre is finite and the sample is regular; ``fixed`` and ``moving``
        are NaN elsewhere (a gap in the curves).
    """

    link: str
    fixed: np.ndarray
    moving: np.ndarray
    at_infinity: np.ndarray
    defined: np.ndarray


def to_link_frame(sol: KinematicSolution, link: str, xy: np.ndarray) -> np.ndarray:
    """Points (N, 2) of the ground frame in the frame of ``link`` at each sample."""
    origin = _sweep(sol, sol.position(sol.mechanism.link(link).points[0]))
    theta = _sweep(sol, sol.angle(link))
    c, s = np.cos(theta), np.sin(theta)
    d = xy - origin
    return np.stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]], axis=1)


@takes_solution
def centrodes(sol: KinematicSolution, link: str) -> Centrodes:
    """The fixed and moving centrodes of ``link`` over the sweep of ``sol``.

    Parameters
    ----------
    sol : KinematicSolution
        A sweep (or one configuration, N = 1).
    link : str
        A moving link.

    Returns
    -------
    Centrodes
        Arrays with the sample axis, (N, 2) and (N,), whatever the shape of ``sol``.

    Raises
    ------
    ModelError
        An unknown link, or the ground.

    Examples
    --------
    The crossed parallelogram (antiparallelogram) on its short link: the coupler's
    centrodes are two equal ellipses, with foci at the pivots and at the coupler's pins and
    a major axis as long as the crossed links (Flores & Claro's rolling curves):

    >>> ap = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=2.0, branch="crossed")
    >>> sol = kl.analyze(ap, q=np.radians(np.arange(20.0, 160.0, 10.0)))
    >>> c = kl.kinematics.centrodes(sol, "coupler")
    >>> O2, O4 = np.array([0.0, 0.0]), np.array([1.0, 0.0])
    >>> focal = np.linalg.norm(c.fixed - O2, axis=1) + np.linalg.norm(c.fixed - O4, axis=1)
    >>> bool(np.allclose(focal, 2.0)), bool(c.defined.all())
    (True, True)
    """
    m = sol.mechanism
    if link not in sol.link_item:
        raise ModelError(f"link: expected one of {quoted(sol.link_names)}, got {describe(link)}"
                         f"{suggest(str(link), sol.link_names)}")
    if link == m.ground.name:
        raise ModelError(f"link: expected a moving link, got the ground {describe(link)}; its "
                         "centrodes are those of the ground relative to itself")
    pair = _model_order(sol, m.ground.name, link)
    c = _centers(sol, [pair])[pair]
    fixed = _sweep(sol, c.position)
    at_infinity = np.reshape(c.at_infinity, (-1,))
    defined = ~at_infinity & ~sol.singular & sol.assembled & np.isfinite(fixed).all(axis=1)
    fixed = np.where(defined[:, None], fixed, np.nan)
    moving = to_link_frame(sol, link, fixed)
    return Centrodes(link, fixed, moving, at_infinity.copy(), defined)


@takes_solution
def velocity_ratio(sol: KinematicSolution, link_i: str, link_j: str, *,
                   reference: str | None = None) -> np.ndarray:
    """omega_j / omega_i from the instant centres (the angular-velocity-ratio theorem).

    The centre I_ij has the same velocity on both links, so with r the reference link
    (default: the ground), ``(omega_j - omega_r) / (omega_i - omega_r) = I_ri I_ij / I_rj I_ij``,
    lengths along the line of the three centres: positive when I_ij lies outside the two
    centres with r, negative between them (Flores & Claro, eq. 4.121).

    Parameters
    ----------
    sol : KinematicSolution
    link_i, link_j : str
        Two links, other than the reference.
    reference : str, optional
        The third link the angular velocities are measured from (default: the ground).

    Returns
    -------
    ndarray, shape () or (N,)
        The ratio, 1 where I_ij is at infinity (the two links translate relative to each
        other) and 0 where I_rj is (link j translates relative to the reference).

    Raises
    ------
    SingularityError
        At a singular sample, or where link i translates relative to the reference (I_ri at
        infinity: omega_i = omega_r and the ratio is infinite); the message names the first
        such sample.
    ModelError
        Unknown links, or two of the three links the same.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    >>> sol = kl.analyze(fb, q=np.radians([30.0, 60.0]), qd=1.0)
    >>> ratio = kl.kinematics.velocity_ratio(sol, "crank", "rocker")
    >>> bool(np.allclose(ratio, sol.omega("rocker") / sol.omega("crank"), rtol=1e-10, atol=0))
    True
    """
    m = sol.mechanism
    r = m.ground.name if reference is None else reference
    names = {"link_i": link_i, "link_j": link_j, "reference": r}
    for what, name in names.items():
        if name not in sol.link_item:
            raise ModelError(f"{what}: expected one of {quoted(sol.link_names)}, got "
                             f"{describe(name)}{suggest(str(name), sol.link_names)}")
    if len({link_i, link_j, r}) < 3:
        raise ModelError(f"velocity_ratio: expected three different links, got link_i "
                         f"{describe(link_i)}, link_j {describe(link_j)} and reference "
                         f"{describe(r)}; the theorem relates two links to a third")
    pairs = [_model_order(sol, r, link_i), _model_order(sol, r, link_j), _model_order(sol, link_i, link_j)]
    ri, rj, ij = (_centers(sol, pairs)[p] for p in pairs)
    pos = {k: _sweep(sol, c.position) for k, c in (("ri", ri), ("rj", rj), ("ij", ij))}
    inf = {k: np.reshape(c.at_infinity, (-1,)) for k, c in (("ri", ri), ("rj", rj), ("ij", ij))}
    bad = sol.singular | ~sol.assembled
    if bad.any():
        i = int(np.argmax(bad))
        raise SingularityError(f"velocity_ratio: {int(bad.sum())} sample(s) are singular or do not "
                               f"assemble, the first sample {i} at {_q_text(sol, i)}; angular "
                               "velocities are not defined there; leave them out of the sweep")
    if inf["ri"].any():
        i = int(np.argmax(inf["ri"]))
        raise SingularityError(
            f"velocity_ratio: {describe(link_i)} translates relative to {describe(r)} at "
            f"{int(inf['ri'].sum())} sample(s), the first sample {i} at {_q_text(sol, i)}: "
            f"their centre is at infinity, omega of {describe(link_i)} is that of "
            f"{describe(r)} and the ratio is infinite; swap link_i and link_j")
    a = pos["ij"] - pos["ri"]
    b = pos["ij"] - pos["rj"]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.einsum("ij,ij->i", a, b) / np.einsum("ij,ij->i", b, b)
    ratio = np.where(inf["ij"], 1.0, np.where(inf["rj"], 0.0, ratio))
    return sol._out(ratio)


def _cam_centre(sol: KinematicSolution, j, size: float) -> np.ndarray:
    """A cam joint's instant centre, homogeneous (n, 3): on the line of centres of cam (about
    O) and follower, where the program's ``k = S'(theta)`` puts it, as a gear pair's pitch
    point: ``(O - k A) / (1 - k)`` for a follower turning about A, ``O - k (k x u)`` for one
    sliding along u (at infinity where an oscillating follower turns with the cam)."""
    m = sol.mechanism
    c = cam_pair(m, j)

    def angle(link):
        return 0.0 if link == m.ground.name else _sweep(sol, sol.angle(link))
    k = cam_values(c.table, angle(c.cam) - angle(c.guide))[1]
    o = _sweep(sol, sol.position(m.joint(c.pivot).point)) / size
    k = np.broadcast_to(k, o.shape[:1])
    f = m.joint(c.follower_joint)
    if c.motion == "translating":
        u = _sweep(sol, sol.slide_axes(f.name))
        n = np.stack([-u[:, 1], u[:, 0]], axis=1)
        h = np.concatenate([o - k[:, None] * n / size,
                            np.ones((len(k), 1))], axis=1)
    else:
        a = _sweep(sol, sol.position(f.point)) / size
        h = np.concatenate([o - k[:, None] * a, (1.0 - k)[:, None]], axis=1)
    return _unit(h)


def _pitch_point(sol: KinematicSolution, j) -> np.ndarray:
    """A gear joint's pitch point, the instant centre of its two gears: on the line of centres,
    ``(O_a - k O_b) / (1 - k)``; a rack's, its pinion's pitch radius to the right of the rack's
    axis from the pinion's centre (m, the shape of a point's position)."""
    g = gear_mesh(sol.mechanism, j)
    oa = np.asarray(sol.position(g.centre_a))
    if g.mesh == "rack":
        u = np.asarray(sol.slide_axes(g.slide))
        return oa + g.k * np.stack([u[..., 1], -u[..., 0]], axis=-1)
    return (oa - g.k * np.asarray(sol.position(g.centre_b))) / (1.0 - g.k)
