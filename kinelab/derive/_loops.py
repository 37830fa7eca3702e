"""The position equations of a planar model, written from its link graph as the notes do.

The links are the nodes of a graph and the joints its edges.  A spanning tree from the
ground leaves one joint out of each independent circuit (as many circuits as joints minus
links plus one); each left-out joint closes one vector loop.  Going round a loop, every
link contributes the vector between the two joints it is entered and left by, a length
along a direction that turns with the link, and every prismatic joint contributes its
slide along its axis (and the constant offset across it).  The sum is zero: two scalar
equations per loop, projected on x and y (Erthal, *Mecanismos com 1 GL: análise geral de
velocidade e aceleração*).

The coordinates are the notes': one angle per group of links that turn together (links
joined by a prismatic joint keep their relative angle), and one slide per prismatic joint.
An angle fixed by an input (``theta_b - theta_a = q``) and a driven slide are not unknowns;
what remains is S.  Lengths, offsets and the ground's coordinates are named symbols;
constants that are exactly zero (a pivot at the origin, an offset-free slide) drop out.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from collections.abc import Iterable, Mapping

from kinelab.errors import ModelError, describe, expected_one_of
from kinelab.kinematics import plan as engine_plan
from kinelab.model import Joint, Mechanism, name_problem
from kinelab.solvers import wrap_angle

__all__ = ["LoopEquations", "Loop", "loop_equations"]

_ANGLE_TOL = 1e-14   # rad: a constant angle this close to a multiple of pi/2 is that multiple
_LENGTH_TOL = 1e-14  # relative to the model's size: a constant this small is zero


@dataclass(frozen=True, eq=False)
class Loop:
    """One independent circuit: the links and joints in the order the loop goes round,
    and its vector terms (each a 2-vector of sympy expressions) in that order."""

    links: tuple[str, ...]
    joints: tuple[str, ...]
    terms: tuple[tuple[str, object], ...]     # (what it comes from, sympy Matrix 2x1)

    @property
    def closure(self):
        """The sum of the terms, x and y (sympy Matrix 2x1)."""
        import sympy as sp
        total = sp.zeros(2, 1)
        for _, v in self.terms:
            total += v
        return total


@dataclass(frozen=True, eq=False)
class LoopEquations:
    """Everything the loop equations of a model are made of (see the module docstring)."""

    model: Mechanism
    q: tuple                       # input symbols
    S: tuple                       # unknowns' symbols
    unknowns: dict                 # symbol of S -> ("angle", link) or ("slide", joint)
    inputs: dict                   # symbol of q -> the input's joint (its name without one)
    parameters: dict               # symbol -> value, SI
    meaning: dict                  # symbol -> (kind, *names): what each symbol stands for
    loops: tuple[Loop, ...]
    rows: tuple                    # every scalar equation (two per loop), sympy expressions
    independent: tuple[int, ...]   # the rows kept in Phi (all unless some are redundant)
    angle: dict                    # link -> its angle, a sympy expression of q, S and constants
    roots: dict                    # link -> the link whose angle its group turns with
    slide: dict                    # P joint -> its slide (a symbol of S or q)
    position: dict                 # point -> (x, y) sympy Matrix, of the points asked for
    sketch: dict                   # symbol of q and S -> its value at the model's sketch


class _Names:
    """Unique sympy symbols with given names (a model may name two things alike)."""

    def __init__(self, reserved=()):
        self.used: set[str] = set(reserved)

    def __call__(self, name: str):
        import sympy as sp
        base, k = name, 1
        while name in self.used:
            k += 1
            name = f"{base}'" if k == 2 else f"{base}'{k - 1}"
        self.used.add(name)
        return sp.Symbol(name)


def _zero(v: float, scale: float) -> bool:
    return abs(v) <= _LENGTH_TOL * scale


def _exact_angle(a: float):
    """A constant angle as sympy shows it: the multiples of pi/2 exactly, else None."""
    import sympy as sp
    k = round(a / (math.pi / 2))
    if abs(a - k * math.pi / 2) <= _ANGLE_TOL * max(1.0, abs(a)):
        return sp.pi * sp.Rational(k % 4, 2) if k % 4 != 3 else -sp.pi / 2
    return None


def loop_equations(model: Mechanism, notation: dict | None = None,
                   points=()) -> LoopEquations:
    """The loop equations of ``model`` (any planar model kinelab analyses), and the
    positions of ``points`` (placed along the spanning tree, for the dynamics).

    ``notation`` maps keys such as ``("angle", "lever")``, ``("slide", "slot")``,
    ``("length", "crank")``, ``("x", "O2")``, ``("input", 0)``, or the names kinelab would
    write (``"theta_lever"``, ``"s_slot"``, ``"L_crank"``, ``"x_O2"``, ``"q"``), to symbol
    names (the notes' letters for the catalogue); everything else is named after the
    model's own names.

    Raises
    ------
    ModelError
        What :func:`kinelab.analyze` raises for a model it cannot analyse; a ``notation``
        that is not a mapping of keys to names, or names a symbol the equations do not have;
        ``points`` the model does not have.
    """
    gears = [j.name for j in model.joints if j.type == "G"]
    if gears:
        raise ModelError(f"joints {', '.join(repr(n) for n in gears)}: the derivation writes the loop "
                         "equations of R and P joints; gear joints (G) are not derived (kinelab.analyze "
                         "solves them: a gear pair's relation is linear in the angles)")
    cams = [j.name for j in model.joints if j.type == "C"]
    if cams:
        raise ModelError(f"joints {', '.join(repr(n) for n in cams)}: the derivation writes the loop "
                         "equations of R and P joints; cam joints (C) are not derived yet (kinelab."
                         "analyze solves them from the cam's motion program)")
    builder = _Builder(model, _notation(notation))
    out = builder.build(_points(model, points))
    unknown = sorted(k for k in builder.notation if isinstance(k, str) and k not in builder.seen)
    if unknown:
        raise ModelError([f"notation: {k}: not a symbol of the equations of '{model.name}'; "
                          f"its symbols are {', '.join(sorted(builder.seen))}" for k in unknown])
    return out


def _notation(notation) -> dict:
    """``notation`` as a dict of key to symbol name, checked."""
    if notation is None:
        return {}
    if not isinstance(notation, Mapping):
        raise ModelError(f"notation: expected a mapping of keys such as ('angle', 'coupler') to "
                         f"symbol names, or None, got {describe(notation)}")
    for key, name in notation.items():
        problem = name_problem(name)
        if problem:
            raise ModelError(f"notation[{describe(key)}]: {problem} for the symbol, got "
                             f"{describe(name)}")
    return dict(notation)


def _points(model: Mechanism, points) -> tuple[str, ...]:
    """``points`` (a name, or names) as a tuple of the model's point names."""
    if isinstance(points, str):
        points = (points,)
    if not isinstance(points, Iterable) or isinstance(points, Mapping):
        raise ModelError(f"points: expected a sequence of point names, got {describe(points)}")
    points = tuple(points)
    known = model.point_names
    for p in points:
        if p not in known:
            raise ModelError(f"points: {expected_one_of(p, known)}")
    return points


class _Builder:
    def __init__(self, m: Mechanism, notation: dict):
        import sympy as sp
        self.sp = sp
        self.plan = engine_plan(m)     # the engine's checks: the same ModelError as analyze
        self.m = m
        self.notation = notation
        self.seen: set[str] = set()           # the names kinelab gives, renamed or not
        self.names = _Names()
        self.ground = m.ground.name
        self.xy = {p.name: np.array(p.xy, float) for p in m.points}
        self.scale = self.plan.scale
        self.theta_s = {n: float(self.plan.sketch_angles[self.plan.link_item[n]])
                        for n in m.link_names}
        self.parameters: dict = {}
        self.meaning: dict = {}
        self._params: dict = {}

    # -- symbols -----------------------------------------------------------------------------
    def name(self, key: tuple, default: str) -> str:
        """The symbol of ``key``: the notation's, by the name kinelab would give it or by
        key, else that name."""
        self.seen.add(default)
        return self.notation.get(default, self.notation.get(key, default))

    def param(self, key: tuple, default: str, value: float, meaning: tuple):
        if key not in self._params:
            s = self.names(self.name(key, default))
            self._params[key] = s
            self.parameters[s] = float(value)
            self.meaning[s] = meaning
        return self._params[key]

    # -- angles ------------------------------------------------------------------------------
    def angle_classes(self) -> dict[str, str]:
        """Links that turn together (joined by prismatic joints): the root of each group,
        the ground where it is in the ground's group, else the link listed first with two
        points (a lever rather than its slider block)."""
        m = self.m
        root = {n: n for n in m.link_names}

        def find(n):
            while root[n] != n:
                n = root[n]
            return n

        def rank(r):
            return (r != self.ground, len(m.link(r).points) < 2, m.link_names.index(r))
        for j in m.joints:
            if j.type == "P":
                ra, rb = find(j.links[0]), find(j.links[1])
                if ra != rb:      # (a cycle of slides keeps its relative angles by itself)
                    keep, other = sorted((ra, rb), key=rank)
                    root[other] = keep
        return {n: find(n) for n in m.link_names}

    def constant(self, link: str, direction: float, key: tuple, default: str, meaning: tuple):
        """The angle of a direction fixed in a link (``direction`` at the sketch, rad) from
        its group's root link (from the x axis in the ground's group): exact when a multiple
        of pi/2, else a symbol."""
        r = self.classes[link]
        c = float(wrap_angle(direction - (self.theta_s[r] if r != self.ground else 0.0)))
        exact = _exact_angle(c)
        return exact if exact is not None else self.param(key, default, c, meaning)

    def turning(self, link: str, direction: float, key: tuple, default: str, meaning: tuple):
        """The angle of a direction fixed in a link: its group's angle plus a constant."""
        return self.root_angle[self.classes[link]] + self.constant(link, direction, key, default,
                                                                     meaning)

    def build(self, points: tuple[str, ...]) -> LoopEquations:
        sp, m = self.sp, self.m
        M = len(m.inputs)
        qs = tuple(self.names(self.name(("input", k), "q" if M == 1 else f"q_{k + 1}"))
                   for k in range(M))
        inputs = {s: inp.joint or inp.label for s, inp in zip(qs, m.inputs)}
        classes = self.classes = self.angle_classes()
        # the angle of each class's root: 0 for the ground's class (angles absolute there),
        # an input where one drives it, else an unknown
        bound: dict[str, object] = {self.ground: sp.Integer(0)}
        driven_slides: dict[str, object] = {}
        pending = []
        for k, inp in enumerate(m.inputs):
            if inp.joint is not None and m.joint(inp.joint).type == "P":
                driven_slides[inp.joint] = qs[k]
            else:
                a, b = m.joint(inp.joint).links if inp.joint is not None else inp.links
                pending.append((a, b, qs[k]))
        placeholders = {}
        for n in m.link_names:
            r = classes[n]
            if r not in bound and r not in placeholders:
                placeholders[r] = sp.Dummy(r)

        def input_angle(n):
            """theta_n as inputs measure it (the ground's frame is 0)."""
            if n == self.ground:
                return sp.Integer(0)
            return bound.get(classes[n], placeholders.get(classes[n])) + offset(n)

        def offset(n):
            """theta_n minus the angle of its group's root (absolute in the ground's)."""
            return self.constant(n, self.theta_s[n], ("link_offset", n), f"delta_{n}",
                                 ("link_offset", n))
        for a, b, qk in pending:
            ra, rb = classes[a], classes[b]
            if rb not in bound:
                bound[rb] = input_angle(a) + qk - offset(b)
            elif ra not in bound:
                bound[ra] = input_angle(b) - qk - offset(a)
            else:
                raise ModelError(f"inputs: the input {qk} fixes the angle between links '{a}' and "
                                 f"'{b}', which other inputs fix already; drop one of them")
        # unknown angles (one per free class, model order of roots), then unknown slides
        S, unknowns = [], {}
        for n in m.link_names:
            r = classes[n]
            if r == n and r not in bound:
                s = self.names(self.name(("angle", r), f"theta_{r}"))
                bound[r] = s
                S.append(s)
                unknowns[s] = ("angle", r)
        # resolve the placeholders (an input between two free classes binds one to the other)
        subs = {placeholders[r]: bound[r] for r in placeholders}
        for _ in range(len(subs) + 1):
            done = True
            for r in list(bound):
                new = sp.sympify(bound[r]).xreplace(subs)
                if new != bound[r]:
                    bound[r], done = new, False
            if done:
                break
        slides: dict[str, object] = {}
        for j in m.joints:
            if j.type != "P":
                continue
            if j.name in driven_slides:
                slides[j.name] = driven_slides[j.name]
            else:
                s = self.names(self.name(("slide", j.name), f"s_{j.name}"))
                slides[j.name] = s
                S.append(s)
                unknowns[s] = ("slide", j.name)
        self.slides = slides
        self.root_angle = bound
        # the angle of every link, for its angular velocity: its group's plus a constant
        angle = {n: bound[classes[n]] + sp.Float(self.theta_s[n] - (
                     self.theta_s[classes[n]] if classes[n] != self.ground else 0.0))
                 if n != self.ground else sp.Integer(0) for n in m.link_names}
        loops = self.loops()
        rows = []
        for lp in loops:
            c = lp.closure
            rows += [c[0], c[1]]
        position = self.positions(points) if points else {}
        sketch = self.sketch_values(qs, S, unknowns, inputs)
        independent = self.independent_rows(rows, S, sketch)
        return LoopEquations(model=m, q=qs, S=tuple(S), unknowns=unknowns, inputs=inputs,
                             parameters=self.parameters, meaning=self.meaning,
                             loops=tuple(loops), rows=tuple(rows), independent=independent,
                             angle=angle, roots=dict(classes), slide=slides, position=position,
                             sketch=sketch)

    # -- vectors -----------------------------------------------------------------------------
    def direction(self, phi):
        sp = self.sp
        return sp.Matrix([sp.cos(phi), sp.sin(phi)])

    def rigid(self, link: str, X: str, Y: str):
        """The vector from point X to point Y of a link, in symbols."""
        sp = self.sp
        if X == Y:
            return sp.zeros(2, 1)
        if link == self.ground:
            out = []
            for axis, k in (("x", 0), ("y", 1)):
                parts = []
                for p, sign in ((Y, 1), (X, -1)):
                    v = float(self.xy[p][k])
                    if not _zero(v, self.scale):
                        parts.append(sign * self.param((axis, p), f"{axis}_{p}", v, (axis, p)))
                out.append(sp.Add(*parts))
            return sp.Matrix(out)
        pts = self.m.link(link).points
        # each pair of points has one canonical direction: from the point listed first
        first, second = (X, Y) if pts.index(X) < pts.index(Y) else (Y, X)
        sign = 1 if first == X else -1
        d = self.xy[second] - self.xy[first]
        size = float(np.hypot(*d))
        if pts[:2] == (first, second):
            r = self.param(("length", link), f"L_{link}", size, ("length", link))
        else:
            r = self.param(("distance", link, first, second), f"r_{first}{second}", size,
                           ("distance", link, first, second))
        phi = self.turning(link, math.atan2(d[1], d[0]), ("direction", link, first, second),
                           f"gamma_{first}{second}", ("direction", link, first, second))
        return sign * r * self.direction(phi)

    def slide_vector(self, j: Joint):
        """From the origin of a prismatic joint (on its guide) to its point (on its slider):
        the slide along the axis and the constant offset across it."""
        sp = self.sp
        guide = j.links[0]
        origin = j.origin or self.m.link(guide).points[0]
        u = np.asarray(j.axis, float) / math.hypot(*j.axis)
        d = self.xy[j.point] - self.xy[origin]
        e = float(u[0] * d[1] - u[1] * d[0])
        phi = self.turning(guide, math.atan2(u[1], u[0]), ("axis", j.name), f"beta_{j.name}",
                           ("axis", j.name))
        v = self.slides[j.name] * self.direction(phi)
        if not _zero(e, self.scale):
            ep = self.param(("offset", j.name), f"e_{j.name}", e, ("offset", j.name))
            v = v + ep * self.direction(phi + sp.pi / 2)
        return v

    def anchor(self, j: Joint, link: str) -> str:
        """Where a joint sits on one of its links: its point, or a prismatic joint's origin
        on the guide."""
        if j.type == "P" and link == j.links[0]:
            return j.origin or self.m.link(link).points[0]
        return j.point

    def cross(self, j: Joint, frm: str):
        """The vector across a joint from its anchor on link ``frm`` to the other's."""
        if j.type == "R":
            return self.sp.zeros(2, 1)
        v = self.slide_vector(j)
        return v if frm == j.links[0] else -v

    # -- the graph ---------------------------------------------------------------------------
    def tree(self):
        """Breadth-first spanning tree from the ground, joints in model order: parent joint
        and depth of each link, and the joints left out (one per independent loop)."""
        m = self.m
        parent = {self.ground: None}
        depth = {self.ground: 0}
        todo = [self.ground]
        used = set()
        while todo:
            nxt = []
            for n in todo:
                for j in m.joints:
                    if n not in j.links or j.name in used:
                        continue
                    other = j.links[1] if j.links[0] == n else j.links[0]
                    if other in parent:
                        continue
                    parent[other] = j
                    depth[other] = depth[n] + 1
                    used.add(j.name)
                    nxt.append(other)
            todo = nxt
        chords = [j for j in m.joints if j.name not in used]
        return parent, depth, chords

    def loops(self) -> list[Loop]:
        m = self.m
        parent, depth, chords = self.tree()
        self.parent, self.depth = parent, depth

        def path_up(n):
            out = [n]
            while parent[out[-1]] is not None:
                j = parent[out[-1]]
                out.append(j.links[1] if j.links[0] == out[-1] else j.links[0])
            return out
        loops = []
        for chord in chords:
            a, b = chord.links
            pa, pb = path_up(a), path_up(b)
            common = next(x for x in pa if x in pb)
            up = pa[:pa.index(common) + 1]               # a ... common
            down = pb[:pb.index(common)][::-1]           # ... b (common excluded)
            cyc_links = up + down                        # a -> common -> b, then chord b -> a
            cyc_joints = [parent[x] for x in pa[:pa.index(common)]]
            cyc_joints += [parent[x] for x in pb[:pb.index(common)]][::-1]
            cyc_joints.append(chord)
            # cyc_joints[i] joins cyc_links[i] and cyc_links[i + 1] (cyclically)
            loops.append(self.traverse(cyc_links, cyc_joints))
        return loops

    def traverse(self, links: list[str], joints: list[Joint]) -> Loop:
        """Go round a cycle from the ground (or the link nearest it), leaving it by the
        joint whose point it lists first: the notes' order for the slotted link
        (``B cos A - R cos q - C``) and the four-bar (``r2 + r3 - r4 - r1``)."""
        m, n = self.m, len(links)
        start = min(range(n), key=lambda i: (self.depth[links[i]], m.link_names.index(links[i])))
        L0 = links[start]
        before, after = joints[start - 1], joints[start]     # the two joints at the start link
        pts = m.link(L0).points

        def key(j):
            p = self.anchor(j, L0)
            return (pts.index(p) if p in pts else len(pts), m.joint_names.index(j.name))
        # order the cycle as a list of (link, joint leaving it)
        seq_links = links[start:] + links[:start]
        seq_joints = joints[start:] + joints[:start]
        if key(before) < key(after):                          # go the other way round
            seq_links = [L0] + seq_links[1:][::-1]
            seq_joints = seq_joints[::-1]
        terms, point = [], None
        p0 = self.anchor(seq_joints[0], L0)
        point = p0
        for i, (L, j) in enumerate(zip(seq_links, seq_joints)):
            exit_p = self.anchor(j, L)
            v = self.rigid(L, point, exit_p)
            if any(e != 0 for e in v):
                terms.append((L, v))
            nxt = seq_links[(i + 1) % n]
            v = self.cross(j, L)
            if any(e != 0 for e in v):
                terms.append((j.name, v))
            point = self.anchor(j, nxt)
        v = self.rigid(L0, point, p0)
        if any(e != 0 for e in v):
            terms.append((L0, v))
        return Loop(links=tuple(seq_links) + (L0,), joints=tuple(j.name for j in seq_joints),
                    terms=tuple(terms))

    # -- positions ---------------------------------------------------------------------------
    def positions(self, points: tuple[str, ...]) -> dict:
        """The positions of ``points``, placed along the spanning tree, in symbols."""
        sp, m = self.sp, self.m
        anchor = {}
        # the ground's first point, from the origin
        g0 = m.ground.points[0]
        origin = sp.Matrix([self.param(("x", g0), f"x_{g0}", self.xy[g0][0], ("x", g0))
                            if not _zero(self.xy[g0][0], self.scale) else 0,
                            self.param(("y", g0), f"y_{g0}", self.xy[g0][1], ("y", g0))
                            if not _zero(self.xy[g0][1], self.scale) else 0])
        anchor[self.ground] = (g0, origin)
        order = sorted(self.parent, key=lambda n: self.depth[n])
        for n in order:
            j = self.parent[n]
            if j is None:
                continue
            a = j.links[1] if j.links[0] == n else j.links[0]
            pa, ra = anchor[a]
            here = self.anchor(j, a)
            at = ra + self.rigid(a, pa, here) + self.cross(j, a)
            anchor[n] = (self.anchor(j, n), at)
        pos = {}
        for p in points:
            link = m.links_carrying(p)[0]
            p0, r0 = anchor[link]
            pos[p] = r0 + self.rigid(link, p0, p)
        return pos

    def sketch_values(self, qs, S, unknowns, inputs) -> dict:
        out = {s: float(v) for s, v in zip(qs, self.plan.q_sketch)}
        for s in S:
            kind, name = unknowns[s]
            if kind == "angle":
                out[s] = self.theta_s[name]
            else:
                j = self.m.joint(name)
                origin = j.origin or self.m.link(j.links[0]).points[0]
                u = np.asarray(j.axis, float) / math.hypot(*j.axis)
                out[s] = float(u @ (self.xy[j.point] - self.xy[origin]))
        return out

    def independent_rows(self, rows, S, sketch) -> tuple[int, ...]:
        """The rows of the loop equations that are independent at the sketch (all of them
        unless the model has redundant constraints, as a parallelogram's extra link)."""
        sp = self.sp
        if len(rows) == len(S):
            return tuple(range(len(rows)))
        values = {**sketch, **self.parameters}
        J = np.array(sp.Matrix(rows).jacobian(sp.Matrix(S)).subs(values).evalf(), float) \
            if S else np.zeros((len(rows), 0))
        keep: list[int] = []
        for i in range(len(rows)):
            trial = J[keep + [i]]
            if np.linalg.matrix_rank(trial, tol=1e-9 * max(1.0, np.abs(J).max())) == len(keep) + 1:
                keep.append(i)
            if len(keep) == len(S):
                break
        if len(keep) != len(S):
            raise ModelError(f"the loop equations of '{self.m.name}' have rank {len(keep)} at the "
                             f"sketch for {len(S)} unknowns; move the sketch off a singular "
                             "configuration")
        return tuple(keep)
