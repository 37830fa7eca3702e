"""Gear trains as a designer writes them, solved by the planar engine's gear joints.

A train is a list of meshes ``(driver, driven, teeth_driver, teeth_driven[, kind])``.  Its
*members* are the rigid bodies that turn: a gear, or several gears on one shaft (``shafts``),
and the arms (carriers) of an epicyclic train (``carriers``: the gears whose axes an arm
carries).  Every other axis is on the frame.  :func:`train` builds the planar mechanism —
each member a link, each mesh a ``G`` joint relative to the member that carries both axes,
centres placed by the pitch radii ``m N / 2`` — and analyses it once
(:func:`kinelab.kinematics.analyze`) with the input turning at its speed and the fixed
members driven at zero speed.  The engine solves the pairs exactly (a linear step), so the
speeds are exact to rounding.  Where the engine cannot start from those members (a mesh is
solved once two of its gears and carrier are known: a sun driven and a ring held through two
planets in series leaves no mesh so), the arms and central members are driven instead and
the speeds combined linearly to meet the given ones.
"""
from __future__ import annotations

import math
import numbers
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from kinelab.errors import ModelError, describe, expected_one_of, quoted, shown
from kinelab.kinematics import analyze
from kinelab.model import Input, Joint, Link, Mechanism, Point
from kinelab.model._values import is_real, name_problem

__all__ = ["MESH_KINDS", "FRAME", "TrainSolution", "train"]

MESH_KINDS = ("external", "internal")
"""The kinds of mesh: ``external`` (the gears turn opposite ways, relative to the member
carrying both axes) and ``internal`` (a gear in a ring: the same way)."""

FRAME = "frame"
"""The name of the frame: it carries every axis no arm carries; no member may take it."""

RPM = 2.0 * math.pi / 60.0          # rad/s per revolution per minute
DEFAULT_MODULE = 1e-3               # m: places the centres when no module is given


@dataclass(frozen=True)
class TrainSolution:
    """The speeds of a gear train's members for one input speed.

    Attributes
    ----------
    value : float
        The train value ``e = omega_output / omega_input`` (signed: negative when the output
        turns against the input).
    speeds : dict of str to float
        Every gear's and arm's angular velocity (CCW positive), rad/s, or rpm when the train
        was solved with ``rpm=True``.  The gears of one shaft have one speed; a fixed
        member's is 0.
    accelerations : dict of str to float, or None
        The angular accelerations, rad/s² (rpm per second with ``rpm=True``), when an input
        acceleration was given.
    input, output : str
        The driving and the driven member.
    fixed : tuple of str
        The members held still.
    rpm : bool
        Whether ``speeds`` and ``accelerations`` are in rpm (and rpm/s).
    center_distances : dict of (str, str) to float, or None
        The distance between the axes of each mesh ``(driver, driven)``, m, ``m (N_a ± N_b)
        / 2``, when a module was given.
    mechanism : Mechanism
        The planar model of the train (links named after the members, ``G`` joints after
        the meshes, the frame ``'frame'``); ``kl.analyze`` takes it as any other model.
        Its inputs are the input and the held members or, where the engine cannot solve
        the train from those, the arms and central members it was analysed with.
    """

    value: float
    speeds: dict[str, float]
    accelerations: dict[str, float] | None
    input: str
    output: str
    fixed: tuple[str, ...]
    rpm: bool = False
    center_distances: dict[tuple[str, str], float] | None = None
    mechanism: Mechanism | None = field(default=None, repr=False, compare=False)

    def __repr__(self) -> str:
        unit = "rpm" if self.rpm else "rad/s"
        return (f"TrainSolution(value={self.value:.6g}, input={self.input!r}, "
                f"output={self.output!r}, fixed={self.fixed!r}, {len(self.speeds)} speeds "
                f"in {unit})")


@dataclass(frozen=True)
class _Mesh:
    index: int
    a: str
    b: str
    na: int
    nb: int
    kind: str


def _whole_teeth(v) -> str | None:
    """Why ``v`` is no number of teeth, or None."""
    if isinstance(v, bool) or not (isinstance(v, numbers.Integral) or is_real(v)):
        return f"expected a whole number of teeth, got {describe(v)}"
    if not float(v).is_integer():
        return f"expected a whole number of teeth, got {describe(v)}; round it"
    if v <= 0:
        return f"expected a positive number of teeth, got {describe(v)}"
    return None


def _read_meshes(meshes) -> list[_Mesh]:
    shape = ("a list of (driver, driven, teeth_driver, teeth_driven[, kind]) with kind "
             "'external' or 'internal'")
    if isinstance(meshes, (str, bytes, Mapping)) or not isinstance(meshes, Sequence) \
            or len(meshes) == 0:
        raise ModelError(f"meshes: expected {shape}, got {describe(meshes)}")
    out, problems, seen = [], [], {}
    for i, item in enumerate(meshes):
        where = f"meshes[{i}]"
        if isinstance(item, (str, bytes, Mapping)) or not isinstance(item, Sequence) \
                or len(item) not in (4, 5):
            problems.append(f"{where}: expected (driver, driven, teeth_driver, teeth_driven"
                            f"[, kind]), got {describe(item)}")
            continue
        a, b, na, nb = item[:4]
        kind = item[4] if len(item) == 5 else "external"
        bad = False
        for label, name in (("driver", a), ("driven", b)):
            why = name_problem(name)
            if why:
                problems.append(f"{where}: {label}: {why}, got {describe(name)}")
                bad = True
            elif name == FRAME:
                problems.append(f"{where}: {label}: {shown(FRAME)} names the frame, which "
                                "carries the fixed axes; give the member another name")
                bad = True
        for label, n in (("teeth_driver", na), ("teeth_driven", nb)):
            why = _whole_teeth(n)
            if why:
                problems.append(f"{where}: {label}: {why}")
                bad = True
        if not isinstance(kind, str) or kind not in MESH_KINDS:
            problems.append(f"{where}: kind: {expected_one_of(kind, MESH_KINDS)}")
            bad = True
        if bad:
            continue
        if a == b:
            problems.append(f"{where}: member {shown(a)} meshes with itself; a mesh joins two "
                            "different members")
            continue
        if kind == "internal" and na == nb:
            problems.append(f"{where}: an internal mesh needs a ring with more teeth than the "
                            f"gear inside it, got {int(na)} and {int(nb)}")
            continue
        pair = frozenset((a, b))
        if pair in seen:
            problems.append(f"{where}: repeats the mesh of {shown(a)} and {shown(b)} in "
                            f"meshes[{seen[pair]}]; give each mesh once")
            continue
        seen[pair] = i
        out.append(_Mesh(i, a, b, int(na), int(nb), kind))
    if problems:
        raise ModelError(problems)
    return out


def _names(value, field: str) -> tuple:
    if value is None:
        return ()
    if isinstance(value, str):
        return (value,)
    if isinstance(value, Sequence):
        return tuple(value)
    raise ModelError(f"{field}: expected a member's name or a list of names, got "
                     f"{describe(value)}")


def _member(name, field: str, names: Sequence[str]) -> None:
    if not isinstance(name, str) or name not in names:
        raise ModelError(f"{field}: {expected_one_of(name, names)}")


class _Union:
    def __init__(self, items):
        self.parent = {x: x for x in items}

    def find(self, x):
        while self.parent[x] != x:
            self.parent[x] = self.parent[self.parent[x]]
            x = self.parent[x]
        return x

    def join(self, x, y):
        self.parent[self.find(y)] = self.find(x)


def train(meshes: Sequence[Sequence], *, input: str, speed: float = 1.0,
          acceleration: float | None = None, fixed: str | Sequence[str] | None = None,
          output: str | None = None, carriers: Mapping[str, str] | None = None,
          shafts: Sequence[Sequence[str]] = (), coaxial: Sequence[Sequence[str]] = (),
          module: float | Sequence[float] | None = None, rpm: bool = False) -> TrainSolution:
    """The train value and every member's speed (and acceleration) of a gear train.

    Relative to the member that carries both its axes (the frame, or the arm of an
    epicyclic train) a mesh of gears ``a`` and ``b`` turns them in the inverse ratio of
    their teeth: ``(omega_b - omega_c) / (omega_a - omega_c) = -N_a / N_b`` (external) or
    ``+N_a / N_b`` (internal).  For a simple or compound train on the frame the train
    value is the product of the meshes' ratios, ``(-1)^(external meshes) prod(N_driver) /
    prod(N_driven)``; for an epicyclic train it is Willis' formula, each mesh read relative
    to the arm.  The train is built as a planar mechanism of ``G`` joints and analysed once
    by the engine, which solves the pairs exactly.

    Parameters
    ----------
    meshes : sequence of (str, str, int, int) or (str, str, int, int, str)
        ``(driver, driven, teeth_driver, teeth_driven, kind)``, ``kind`` ``"external"``
        (default) or ``"internal"`` (a gear in a ring: either may be the ring, the one with
        more teeth).  The driver and driven name the gears; "driver" only orders the pair.
    input : str
        The member that drives the train.
    speed : float
        The input's angular velocity, rad/s (rpm with ``rpm=True``), CCW positive.
    acceleration : float, optional
        The input's angular acceleration, rad/s² (rpm/s with ``rpm=True``); with it the
        result has ``accelerations``.
    fixed : str or sequence of str, optional
        The members held still (the ring or the sun of a planetary train, or its arm).  A
        train on the frame needs none; an epicyclic train (two degrees of freedom) one.
    output : str, optional
        The member whose speed over the input's is the train value.  Default: the driven
        gear of the last mesh; when that gear is held or is the input, the first arm that
        is neither, else the last member named that turns on the frame and is neither (the
        sun of a planetary train driven by its arm, its ring held).
    carriers : mapping of str to str, optional
        ``{gear: arm}``: the gears whose axes an arm carries (the planets); every other
        axis is on the frame.  A gear on the frame that meshes with a planet turns about
        its arm's axis (the sun and the ring of a planetary train).  An arm turns on the
        frame; it may itself be a gear of a mesh.
    shafts : sequence of sequence of str, optional
        The gears that turn together, one group per shaft (a compound train's cluster
        gears, a compound planet).  One name may also be used in several meshes for one
        member.
    coaxial : sequence of (str, str), optional
        Members on the frame that turn about one axis: the input and output of a reverted
        train.
    module : float or sequence of float, optional
        The module of every mesh, or of each mesh in order, m.  With it the centre
        distance of each mesh, ``m (N_a + N_b) / 2`` (external) or ``m |N_a - N_b| / 2``
        (internal), is reported, and the meshes that join one pair of axes must agree on
        it (a reverted train's ``m (N1 + N2) = m (N3 + N4)``; a planetary train's
        ``N_ring = N_sun + 2 N_planet``).  The speeds do not depend on it.
    rpm : bool
        ``speed``, ``acceleration`` and the results in revolutions per minute (and rpm
        per second) instead of rad/s (and rad/s²).

    Returns
    -------
    TrainSolution

    Raises
    ------
    ModelError
        A bad mesh (teeth not a positive whole number, a member meshing with itself, an
        unknown kind), an unknown member, a train that locks (more members driven or held
        than it has degrees of freedom, or meshes whose ratios disagree round a loop) or is
        not determined (too few), centre distances that disagree: one line each, naming
        the field and what to change.

    References
    ----------
    Norton, *Design of Machinery*, ch. 9 (gear trains, the tabular and formula methods
    for epicyclic trains); Willis, *Principles of Mechanism* (1841).

    Examples
    --------
    A compound train: 20 drives 50; 15, on the shaft of 50, drives 45.

    >>> t = kl.gears.train([("g1", "g2", 20, 50), ("g3", "g4", 15, 45)], input="g1",
    ...                    shafts=[("g2", "g3")], speed=1500, rpm=True)
    >>> round(t.value, 12), round(t.speeds["g4"], 9), t.output
    (0.133333333333, 200.0, 'g4')

    A planetary train, ring held: the arm turns N_s / (N_s + N_r) of the sun's speed.

    >>> p = kl.gears.train([("sun", "planet", 30, 20), ("planet", "ring", 20, 70, "internal")],
    ...                    carriers={"planet": "arm"}, fixed="ring", input="sun", speed=10.0)
    >>> p.output, round(p.value, 12), round(p.speeds["arm"], 12)
    ('arm', 0.3, 3.0)
    """
    mesh_list = _read_meshes(meshes)
    if not isinstance(rpm, (bool, np.bool_)):
        raise ModelError(f"rpm: expected True or False, got {describe(rpm)}")
    for label, v in (("speed", speed), ("acceleration", acceleration)):
        if v is not None and (isinstance(v, bool) or not is_real(v) or not math.isfinite(v)):
            raise ModelError(f"{label}: expected a finite number, got {describe(v)}")

    # --- members: gears, shafts, arms -------------------------------------------------------
    gears: list[str] = []
    for m in mesh_list:
        for g in (m.a, m.b):
            if g not in gears:
                gears.append(g)
    body = {g: g for g in gears}
    on_shaft: dict[str, int] = {}
    for s, group in enumerate(_names(shafts, "shafts")):
        group = _names(group, f"shafts[{s}]")
        if len(group) < 2:
            raise ModelError(f"shafts[{s}]: expected two or more gears on one shaft, got "
                             f"{describe(group)}")
        for g in group:
            _member(g, f"shafts[{s}]", gears)
            if g in on_shaft:
                raise ModelError(f"shafts[{s}]: gear {shown(g)} is already on shafts"
                                 f"[{on_shaft[g]}]; put it in one group")
            on_shaft[g] = s
        for g in group[1:]:
            for h, owner in body.items():
                if owner == g:
                    body[h] = group[0]
    carriers = {} if carriers is None else carriers
    if not isinstance(carriers, Mapping):
        raise ModelError(f"carriers: expected a mapping {{gear: arm}}, got {describe(carriers)}")
    arms: list[str] = []
    carrier_of: dict[str, str] = {}          # body -> the member carrying its axis
    for g, arm in carriers.items():
        _member(g, "carriers", gears)
        why = name_problem(arm)
        if why or arm == FRAME:
            raise ModelError(f"carriers[{shown(g)}]: expected the name of the arm carrying "
                             f"its axis, got {describe(arm)}")
        arm_body = body.get(arm, arm)
        if arm_body == body[g]:
            raise ModelError(f"carriers[{shown(g)}]: a gear cannot carry its own axis; name "
                             "the arm")
        if carrier_of.get(body[g], arm_body) != arm_body:
            raise ModelError(f"carriers[{shown(g)}]: the shaft of {shown(g)} is already carried "
                             f"by {shown(carrier_of[body[g]])}; one shaft has one carrier")
        carrier_of[body[g]] = arm_body
        if arm not in gears and arm not in arms:
            arms.append(arm)
            body[arm] = arm
    for b_, c in carrier_of.items():
        if c in carrier_of:
            raise ModelError(f"carriers: the arm {shown(c)} is itself carried by "
                             f"{shown(carrier_of[c])}; an arm turns on the frame")
    names = gears + arms
    bodies = list(dict.fromkeys(body[n] for n in names))
    for b_ in bodies:
        carrier_of.setdefault(b_, FRAME)

    _member(input, "input", names)
    held = _names(fixed, "fixed")
    for f in held:
        _member(f, "fixed", names)
        if body[f] == body[input]:
            raise ModelError(f"fixed: {shown(f)} is the input (or on its shaft); hold another "
                             "member")
    if len({body[f] for f in held}) != len(held):
        raise ModelError(f"fixed: {quoted(held)} name one member twice; name each once")
    if output is not None:
        _member(output, "output", names)

    # --- the carrier of each mesh -----------------------------------------------------------
    axis = _Union(bodies)
    mesh_carrier = []
    for m in mesh_list:
        ba, bb = body[m.a], body[m.b]
        where = f"meshes[{m.index}]"
        if ba == bb:
            raise ModelError(f"{where}: {shown(m.a)} and {shown(m.b)} turn on one shaft; a mesh "
                             "joins two different members")
        ca, cb = carrier_of[ba], carrier_of[bb]
        if ca == cb:
            c = ca
        elif ca == FRAME and cb != FRAME:
            c = cb
            if ba == cb:
                raise ModelError(f"{where}: the arm {shown(m.a)} meshes with the planet "
                                 f"{shown(m.b)} it carries; they cannot roll on each other")
            axis.join(cb, ba)             # a central gear turns about its arm's axis
        elif cb == FRAME and ca != FRAME:
            c = ca
            if bb == ca:
                raise ModelError(f"{where}: the arm {shown(m.b)} meshes with the planet "
                                 f"{shown(m.a)} it carries; they cannot roll on each other")
            axis.join(ca, bb)
        else:
            raise ModelError(f"{where}: {shown(m.a)} is carried by {shown(ca)} and {shown(m.b)} "
                             f"by {shown(cb)}; gears in mesh have their axes on one member")
        mesh_carrier.append(c)
    for k, pair in enumerate(_names(coaxial, "coaxial")):
        pair = _names(pair, f"coaxial[{k}]")
        if len(pair) < 2:
            raise ModelError(f"coaxial[{k}]: expected two or more members, got {describe(pair)}")
        for n in pair:
            _member(n, f"coaxial[{k}]", names)
            if carrier_of[body[n]] != carrier_of[body[pair[0]]]:
                raise ModelError(f"coaxial[{k}]: {shown(n)} and {shown(pair[0])} turn on "
                                 "different carriers; name members on one")
        for n in pair[1:]:
            axis.join(body[pair[0]], body[n])
    for m in mesh_list:
        if axis.find(body[m.a]) == axis.find(body[m.b]):
            raise ModelError(f"meshes[{m.index}]: {shown(m.a)} and {shown(m.b)} turn about one "
                             "axis; gears in mesh turn about different centres (check coaxial "
                             "and carriers)")

    # --- modules and centre distances -------------------------------------------------------
    if module is None:
        modules, given = [DEFAULT_MODULE] * len(mesh_list), False
    else:
        given = True
        if is_real(module) and not isinstance(module, bool):
            modules = [float(module)] * len(mesh_list)
        elif isinstance(module, Sequence) and not isinstance(module, str) \
                and len(module) == len(mesh_list):
            modules = list(module)
        else:
            raise ModelError(f"module: expected a module (m) or one per mesh ({len(mesh_list)}), "
                             f"got {describe(module)}")
        for k, v in enumerate(modules):
            if isinstance(v, bool) or not is_real(v) or not math.isfinite(v) or v <= 0:
                raise ModelError(f"module: expected positive modules (m), got {describe(v)}"
                                 + (f" for meshes[{k}]" if len(set(map(str, modules))) > 1 else ""))
        modules = [float(v) for v in modules]
    radius = {}                               # (mesh index, gear) -> pitch radius
    distance = []
    for m, mod in zip(mesh_list, modules):
        ra, rb = mod * m.na / 2, mod * m.nb / 2
        radius[m.index, m.a], radius[m.index, m.b] = ra, rb
        distance.append(ra + rb if m.kind == "external" else abs(ra - rb))

    if given:
        _check_centres(mesh_list, body, axis, distance)

    # --- degrees of freedom, from the meshes' linear relations ------------------------------
    col = {b_: i for i, b_ in enumerate(bodies)}
    rows = []
    for m, c in zip(mesh_list, mesh_carrier):
        k = -m.na / m.nb if m.kind == "external" else m.na / m.nb
        r = np.zeros(len(bodies))
        # (omega_b - omega_c) - k (omega_a - omega_c) = 0
        r[col[body[m.b]]] += 1.0
        r[col[body[m.a]]] -= k
        if c != FRAME:
            r[col[c]] += k - 1.0
        rows.append(r)
    A = np.array(rows)
    dof = len(bodies) - np.linalg.matrix_rank(A)
    _connected(mesh_list, body, carrier_of, input, held)
    driven = [body[input]] + [body[f] for f in held]
    if dof == 0:
        raise ModelError("meshes: the train locks: its meshes close a loop whose ratios disagree, "
                         "so nothing can turn; remove a mesh or change its teeth")
    which = f"the input {shown(input)}" + (f", the fixed {quoted(held)}" if held else "")
    if len(driven) > dof:
        raise ModelError(f"fixed: the train has {dof} degree(s) of freedom, and {len(driven)} "
                         f"members are driven or held ({which}): it locks; hold "
                         f"{len(driven) - dof} member(s) fewer")
    if len(driven) < dof:
        free = [n for n in names if body[n] not in driven and carrier_of[body[n]] == FRAME]
        raise ModelError(f"fixed: the train has {dof} degrees of freedom, and only "
                         f"{len(driven)} member(s) are driven or held ({which}): it is not "
                         f"determined; hold {dof - len(driven)} more member(s) still with "
                         f"fixed=, e.g. one of {quoted(free)}")
    E = np.zeros((len(driven), len(bodies)))
    for i, d in enumerate(driven):
        E[i, col[d]] = 1.0
    if np.linalg.matrix_rank(np.vstack([A, E])) < len(bodies):
        raise ModelError(f"fixed: the meshes tie the input {shown(input)} to the fixed "
                         f"{quoted(held)}, so they do not determine the train; hold another "
                         "member")

    # --- output -----------------------------------------------------------------------------
    if output is None:
        last = mesh_list[-1].b
        output = last
        if body[last] in driven:
            arm_names = [n for n in names if n in set(carrier_of.values())]
            options = [a for a in arm_names if body[a] not in driven] + \
                      [n for n in reversed(names) if body[n] not in driven
                       and carrier_of[body[n]] == FRAME] + \
                      [n for n in reversed(names) if body[n] not in driven]
            output = options[0]

    # --- the planar mechanism, analysed once ------------------------------------------------
    def build(drive):
        return _mechanism(mesh_list, mesh_carrier, bodies, body, carrier_of, axis, radius,
                          distance, drive, input)

    m = build(driven)
    w = speed * (RPM if rpm else 1.0)
    wd = 0.0 if acceleration is None else acceleration * (RPM if rpm else 1.0)
    D = len(driven)
    try:
        rest = [0.0] * (D - 1)                        # the held members: still
        sol = analyze(m, q=0.0 if D == 1 else np.zeros(D), qd=w if D == 1 else [w] + rest,
                      qdd=wd if D == 1 else [wd] + rest)
    except ModelError as refused:
        # The engine solves a mesh once two of its three members (two gears and the carrier)
        # are known; some choices of input and held members leave none so (a sun driven and
        # a ring held through two planets in series).  The train is linear, so drive the arms
        # and enough central members instead, and find the speeds of those that meet the
        # given input and held members: omega = K qd, with the driven rows of K set to them.
        other = _solvable_drive(A, col, bodies, carrier_of)
        if other is None or other == driven:
            raise refused
        m = build(other)
        sol = analyze(m, q=np.zeros(D))
        K = {b_: np.asarray(sol.K(b_), dtype=float).reshape(D) for b_ in bodies}
        C = np.array([K[d] for d in driven])
        qd = np.linalg.solve(C, np.r_[w, np.zeros(D - 1)])
        qdd = np.linalg.solve(C, np.r_[wd, np.zeros(D - 1)])
        per_input = np.linalg.solve(C, np.r_[1.0, np.zeros(D - 1)])
        omega = {b_: float(K[b_] @ qd) for b_ in bodies}
        alpha = {b_: float(K[b_] @ qdd) for b_ in bodies}
        for d in driven[1:]:
            omega[d] = alpha[d] = 0.0                 # held: exactly still
        omega[driven[0]], alpha[driven[0]] = w, wd
        value = float(K[body[output]] @ per_input)
    else:
        def first(x):
            return float(np.asarray(x).reshape(-1)[0])
        omega = {b_: first(sol.omega(b_)) for b_ in bodies}
        alpha = {b_: first(sol.alpha(b_)) for b_ in bodies}
        value = first(sol.K(body[output]))
    scale = 1.0 / RPM if rpm else 1.0
    speeds = {n: omega[body[n]] * scale for n in names}
    accelerations = None
    if acceleration is not None:
        accelerations = {n: alpha[body[n]] * scale for n in names}
    center = ({(mm.a, mm.b): d for mm, d in zip(mesh_list, distance)} if given else None)
    return TrainSolution(value, speeds, accelerations, input, output,
                         tuple(held), bool(rpm), center, m)


def _solvable_drive(A, col, bodies, carrier_of) -> list[str] | None:
    """Members to drive so that the engine solves every mesh: the arms, then central
    members in order, each kept where it adds a freedom; None when they do not make up
    the train's freedoms."""
    arms = [b_ for b_ in bodies if b_ in set(carrier_of.values())]
    rest = [b_ for b_ in bodies if b_ not in arms and carrier_of[b_] == FRAME]
    rest += [b_ for b_ in bodies if b_ not in arms and b_ not in rest]
    dof = len(bodies) - np.linalg.matrix_rank(A)
    chosen: list[str] = []
    for b_ in arms + rest:
        E = np.zeros((len(chosen) + 1, len(bodies)))
        for i, c in enumerate(chosen + [b_]):
            E[i, col[c]] = 1.0
        if np.linalg.matrix_rank(np.vstack([A, E])) == np.linalg.matrix_rank(A) + len(chosen) + 1:
            chosen.append(b_)
        if len(chosen) == dof:
            return chosen
    return None


def _connected(mesh_list, body, carrier_of, input, held) -> None:
    """Every member is geared to the input (or to a held member)."""
    adj: dict[str, set] = {}
    for m in mesh_list:
        a, b = body[m.a], body[m.b]
        adj.setdefault(a, set()).add(b)
        adj.setdefault(b, set()).add(a)
    for b_, c in carrier_of.items():
        if c != FRAME:
            adj.setdefault(b_, set()).add(c)
            adj.setdefault(c, set()).add(b_)
    seen = set()
    todo = [body[input]] + [body[f] for f in held]
    while todo:
        x = todo.pop()
        if x in seen:
            continue
        seen.add(x)
        todo.extend(adj.get(x, ()))
    loose = [n for n, b_ in body.items() if b_ not in seen]
    if loose:
        raise ModelError(f"meshes: {quoted(loose)} not geared to the input {shown(input)}; add "
                         "the mesh that joins them to the train")


def _check_centres(mesh_list, body, axis, distance) -> None:
    """The meshes that join one pair of axes must put them at one distance."""
    pairs: dict[frozenset, list] = {}
    for m, d in zip(mesh_list, distance):
        pairs.setdefault(frozenset((axis.find(body[m.a]), axis.find(body[m.b]))), []).append((m, d))
    for group in pairs.values():
        (m0, d0) = group[0]
        for m1, d1 in group[1:]:
            if abs(d1 - d0) > 1e-9 * max(d0, d1):
                def text(mm):
                    sign = "+" if mm.kind == "external" else "-"
                    return (f"meshes[{mm.index}] ({shown(mm.a)} {mm.na} {sign} {shown(mm.b)} "
                            f"{mm.nb})")
                raise ModelError(f"module: {text(m0)} and {text(m1)} join one pair of axes at "
                                 f"{d0:.6g} m and {d1:.6g} m, m (N_a ± N_b) / 2; make them equal: "
                                 "change the teeth or the modules")


def _mechanism(mesh_list, mesh_carrier, bodies, body, carrier_of, axis, radius, distance,
               driven, input) -> Mechanism:
    """The train as a planar model: a link per member, its axis placed by the pitch radii."""
    # the axes: one place per coaxial group, each placed from one already placed through a
    # mesh (its centre distance) or, for a planet meshing only with other planets, its arm
    roots = list(dict.fromkeys(axis.find(b_) for b_ in bodies))
    edges = [(axis.find(body[m.a]), axis.find(body[m.b]), d) for m, d in zip(mesh_list, distance)]
    size = max(distance)
    soft = [(axis.find(c), axis.find(b_), size) for b_, c in carrier_of.items() if c != FRAME]
    place = {axis.find(body[input]): np.zeros(2)}
    turn = 0
    while len(place) < len(roots):
        for u, v, d in edges + [(v, u, d) for u, v, d in edges] + soft + \
                [(v, u, d) for u, v, d in soft]:
            if u in place and v not in place:
                turn += 1
                a = 2.399963229728653 * turn          # the golden angle: no two directions meet
                place[v] = place[u] + d * np.array([math.cos(a), math.sin(a)])
                break
        else:               # unreachable after the connectivity check; kept as a guard
            raise ModelError("meshes: some members are not geared to the input")
    label = {r: f"axis of {r}" for r in roots}
    points = [Point(label[r], *map(float, place[r])) for r in roots]
    marks = []
    for i, b_ in enumerate(bodies):
        rs = [radius[k] for k in radius if body[k[1]] == b_]
        r = (max(rs) if rs else size) * (1.0 + 0.01 * i)     # no two marks at one place
        p = place[axis.find(b_)]
        marks.append(Point(f"mark of {b_}", float(p[0] + r), float(p[1])))
    frame_points = [label[r] for r in roots
                    if any(carrier_of[b_] == FRAME for b_ in bodies if axis.find(b_) == r)]
    links = [Link(FRAME, tuple(frame_points), ground=True)]
    for b_ in bodies:
        pts = [label[axis.find(b_)], f"mark of {b_}"]
        pts += [label[axis.find(p)] for p, c in carrier_of.items() if c == b_]
        links.append(Link(b_, tuple(dict.fromkeys(pts))))
    joints = [Joint(f"bearing of {b_}", "R", (carrier_of[b_], b_), point=label[axis.find(b_)])
              for b_ in bodies]
    labels = [f"{m.a}-{m.b}" for m in mesh_list]
    for m, c, name in zip(mesh_list, mesh_carrier, labels):
        if labels.count(name) > 1:          # 'a-b' + 'c' and 'a' + 'b-c'
            name = f"meshes[{m.index}]"
        joints.append(Joint(name, "G", (body[m.a], body[m.b]), mesh=m.kind,
                            teeth=(m.na, m.nb), carrier=None if c == FRAME else c))
    inputs = tuple(Input(joint=f"bearing of {d}") if carrier_of[d] == FRAME
                   else Input(links=(FRAME, d)) for d in driven)
    return Mechanism("gear train", tuple(points + marks), tuple(links), tuple(joints), inputs)
