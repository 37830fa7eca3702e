"""The Gibbs-Appell / Kane terms of the notes (*Mecanismos*, §5) in symbols, for open and
closed chains.

The generalised coordinates are the derivation's x = (q, S) and the generalised speeds
u = x' (Kane's Y = 1).  For the N bodies (the links with mass, point masses, and links
that only carry a load), in the plane (lambda = 3):

- C (n x M) = [1; K]: the speeds of all coordinates in terms of the inputs' (eq. 59-63);
- D (n x 3N): the partial velocities, ``dv_G/du_i`` and ``domega/du_i`` of each body
  (eq. 64), from the positions of the bodies' reference points along the link graph;
- f (3N x 1): applied force minus ``m a_G`` and applied moment about G minus ``I alpha``
  of each body (eq. 65), with the accelerations in x'' and x';
- ``C^T D f + tau = 0``: the actuators act on the input coordinates themselves, so their
  efforts tau are the generalised forces of q.  With ``S' = K q'`` and
  ``S'' = K q'' + L q'^2`` that is the equation of motion.

Nothing here depends on the chain being open: a closed chain's loops are in C, through K.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from kinelab.derive._loops import _Names
from kinelab.derive._simplify import simplified
from kinelab.dynamics import DynamicsSetup, Loads, MassProperties
from kinelab.dynamics._loads import default_carrier
from kinelab.dynamics._symbolic import _exact, spring_tension
from kinelab.dynamics._terms import build_system
from kinelab.model import Mechanism

__all__ = ["Body", "KaneDerivation", "bodies_of", "kane_terms"]


@dataclass(frozen=True)
class Body:
    """One body of the notes' f: a link (with its mass, or massless but loaded) or a point
    mass riding a link."""

    name: str
    link: str            # the link whose angle is the body's
    point: str           # its reference point: the centre of mass (a massless link's first point)
    mass: float          # kg
    inertia: float       # kg m^2 about the point
    turns: bool          # a rigid body (False: a point mass, whose omega column is zero)


@dataclass(frozen=True, eq=False)
class BodyPlan:
    """What the dynamics needs from a model, found before its loop equations are written."""

    bodies: tuple[Body, ...]
    loads: Loads
    masses: MassProperties

    @property
    def points(self) -> tuple[str, ...]:
        """Every point whose position the terms use."""
        pts = [b.point for b in self.bodies]
        pts += [f.point for f in self.loads.forces]
        pts += [p for s in self.loads.springs + self.loads.dampers for p in s.points]
        return tuple(dict.fromkeys(pts))


def bodies_of(model: Mechanism, loads: Loads | None = None,
              masses: MassProperties | None = None) -> BodyPlan | None:
    """The bodies of a model with masses (None for a model without any mass data)."""
    has_mass = (masses is not None or any(link.mass is not None for link in model.links)
                or bool(DynamicsSetup.from_model(model).point_masses))
    if not has_mass:
        return None
    system = build_system(model, loads, masses)     # checks loads and masses as a whole
    if system.loads.pair_loads:
        # friction in joints and torsional springs and dampers have no symbolic form yet: the
        # derivation then stops at K and L, as for a model without masses
        return None
    loads, masses = system.loads, system.masses
    ground = model.ground.name
    bodies = [Body(b.link, b.link, b.center_of_mass, b.mass, b.inertia, True)
              for b in masses.links]
    bodies += [Body(p.point, default_carrier(model, p.point, p.link), p.point, p.mass, 0.0, False)
               for p in masses.points]
    loaded = [default_carrier(model, f.point, f.link) for f in loads.forces]
    loaded += [n for tq in loads.torques for n in (tq.link, tq.reacting) if n]
    for s in loads.springs + loads.dampers:
        loaded += [default_carrier(model, p, n) for p, n in zip(s.points, s.links)]
    have = {b.name for b in bodies if b.turns}
    for n in dict.fromkeys(loaded):
        if n != ground and n not in have:
            bodies.append(Body(n, n, model.link(n).points[0], 0.0, 0.0, True))
            have.add(n)
    return BodyPlan(tuple(bodies), loads, masses)


@dataclass(frozen=True, eq=False)
class KaneDerivation:
    """The notes' ``C^T D f = 0`` of a model, in symbols (see the module docstring).

    Attributes
    ----------
    bodies : tuple of Body
    x, u : tuple of sympy.Symbol
        The generalised coordinates (q, then S) and speeds (their rates).
    C : sympy.Matrix, shape (n, M)
        ``[1; K]``, with the derivation's K.
    D : sympy.Matrix, shape (n, 3 N)
    f : sympy.Matrix, shape (3 N, 1)
    tau : tuple of sympy.Symbol
        The actuators' efforts, one per input (N m or N).
    equations : sympy.Matrix, shape (M, 1)
        ``tau`` as functions of q, q', q'' and S, with K and L as symbols (``K_symbols``
        and ``L_symbols``): ``-C^T D f`` after ``S' = K q'``, ``S'' = K q'' + L q'^2``.
    parameters : dict
        Mass, inertia and gravity symbols -> their values (SI).
    load_values : dict
        Load symbols (forces, torques, tensions) -> (kind, load, its law: the text it was
        given as, or for a tension its expression).
    loads : kinelab.dynamics.Loads
    masses : kinelab.dynamics.MassProperties
    """

    derivation: object = field(repr=False)
    bodies: tuple
    x: tuple
    u: tuple
    C: object
    D: object
    f: object
    tau: tuple
    equations: object
    L_symbols: tuple
    parameters: dict
    load_values: dict
    loads: Loads
    masses: MassProperties
    positions: dict = field(repr=False)     # reference point -> sympy Matrix (x, y)
    _e: object = field(repr=False, default=None)      # D f, in x, x', x''

    def efforts(self, q: ArrayLike, qd: ArrayLike = 0.0, qdd: ArrayLike = 0.0,
                t: ArrayLike = 0.0) -> np.ndarray:
        """The efforts tau (N, M) from these terms at N samples: S, S', S'' from
        :func:`kinelab.analyze`, K from the derivation, loads evaluated as
        :func:`kinelab.dynamics.inverse` evaluates them (for the tests and the document)."""
        import sympy as sp
        from kinelab.kinematics import analyze
        d = self.derivation
        m = d.model
        M, n = len(d.q), len(d.S)
        q2 = np.reshape(np.asarray(q, float), (-1, M))
        N = q2.shape[0]
        qd2 = np.broadcast_to(np.reshape(np.asarray(qd, float), (-1, M)), (N, M))
        qdd2 = np.broadcast_to(np.reshape(np.asarray(qdd, float), (-1, M)), (N, M))
        tt = np.broadcast_to(np.asarray(t, float), (N,))
        sol = analyze(m, q2 if M > 1 else q2[:, 0], qd2 if M > 1 else qd2[:, 0],
                      qdd2 if M > 1 else qdd2[:, 0])
        S, Sd, Sdd = (np.zeros((N, n)) for _ in range(3))
        for i, s in enumerate(d.S):
            kind, name = d.unknowns[s]
            if kind == "angle":
                S[:, i], Sd[:, i], Sdd[:, i] = sol.angle(name), sol.omega(name), sol.alpha(name)
            else:
                S[:, i] = sol.slide(name)
                Sd[:, i], Sdd[:, i] = sol.slide_velocity(name), sol.slide_acceleration(name)
        K = d.evaluate(q2 if M > 1 else q2[:, 0]).K if n else np.zeros((N, 0, M))
        loads = self.load_values
        load_syms = [s for s in loads if loads[s][0] in ("fx", "fy", "torque")]
        load_vals = np.zeros((N, len(load_syms)))
        for k, s in enumerate(load_syms):
            kind, obj, _ = loads[s]
            if kind == "torque":
                load_vals[:, k] = obj.value(tt, q2, qd2)
            else:
                load_vals[:, k] = obj.value(tt, q2, qd2)[:, 0 if kind == "fx" else 1]
        # the tensions of springs and dampers, from the positions in symbols
        e = self._e.subs({s: loads[s][2] for s in loads if loads[s][0] == "tension"})
        rates = [d.dot(s) for s in self.x] + [d.ddot(s) for s in self.x]
        args = list(self.x) + rates + list(d.parameters) + list(self.parameters) + load_syms
        fn = sp.lambdify(args, e, modules="numpy", cse=True)
        consts = list(d.parameters.values()) + list(self.parameters.values())
        out = np.zeros((N, M))
        for k in range(N):
            ek = np.asarray(fn(*q2[k], *S[k], *qd2[k], *Sd[k], *qdd2[k], *Sdd[k], *consts,
                               *load_vals[k]), float).reshape(-1)
            C = np.vstack([np.eye(M), K[k]])
            out[k] = -C.T @ ek
        return out


def kane_terms(d, plan: BodyPlan) -> KaneDerivation:
    """The terms of :class:`KaneDerivation` for a :class:`Derivation` ``d``."""
    import sympy as sp
    eq = d.equations
    m = d.model
    x = tuple(d.q) + tuple(d.S)
    u = tuple(d.dot(s) for s in x)
    udot = tuple(d.ddot(s) for s in x)
    M, n = len(d.q), len(x)
    names = _Names({str(s) for s in x + u + udot} | {str(s) for s in eq.parameters}
                   | {str(s) for s in d.K_symbols})
    params: dict = {}
    loads: dict = {}

    def param(name, value):
        s = names(name)
        params[s] = float(value)
        return s
    g = np.asarray(plan.loads.gravity, float)
    gmag = float(np.hypot(*g))
    gvec = sp.zeros(2, 1)
    if gmag:
        gs = param("g", gmag)
        gvec = sp.Matrix([_exact(c / gmag) for c in g]) * gs
    pos = eq.position

    def vel(r):
        return sum((r.diff(xi) * ui for xi, ui in zip(x, u)), sp.zeros(2, 1))

    def acc(r):
        v = vel(r)
        return sum((v.diff(xi) * ui + v.diff(ui) * ai for xi, ui, ai in zip(x, u, udot)),
                   sp.zeros(2, 1))
    # the loads on each body: forces at points (and their moments about its point), torques
    force_on: dict[str, list] = {b.name: [] for b in plan.bodies if b.turns}
    torque_on: dict[str, list] = {b.name: [] for b in plan.bodies if b.turns}
    for i, f in enumerate(plan.loads.forces):
        label = f.name or f.point
        fx, fy = names(f"F_{label},x"), names(f"F_{label},y")
        loads[fx] = ("fx", f, _law_text(f, 0))
        loads[fy] = ("fy", f, _law_text(f, 1))
        force_on.get(default_carrier(m, f.point, f.link), []).append((f.point, sp.Matrix([fx, fy])))
    for tq in plan.loads.torques:
        T = names(f"T_{tq.name or tq.link}")
        loads[T] = ("torque", tq, _source_text(tq._law))
        torque_on.get(tq.link, []).append(T)
        if tq.reacting:
            torque_on.get(tq.reacting, []).append(-T)
    for items in (plan.loads.springs, plan.loads.dampers):
        for s in items:
            a, b = s.points
            T = names(f"T_{s.name or a + b}")
            dvec = pos[b] - pos[a]
            length = sp.sqrt(dvec.dot(dvec))
            tension = spring_tension(s, length, dvec.dot(vel(dvec)) / length)
            loads[T] = ("tension", s, tension)
            e = dvec / length
            for p, n, sign in ((a, s.links[0], 1), (b, s.links[1], -1)):
                force_on.get(default_carrier(m, p, n), []).append((p, sign * T * e))
    D_cols, f_rows = [], []
    for body in plan.bodies:
        rG = pos[body.point]
        theta = eq.angle[body.link]
        mass = param(f"m_{body.name}", body.mass) if body.mass else sp.Integer(0)
        inertia = param(f"I_{body.name}", body.inertia) if body.inertia else sp.Integer(0)
        F = mass * gvec
        moment = sp.Integer(0)
        for p, Fp in force_on.get(body.name, ()) if body.turns else ():
            F = F + Fp
            arm = pos[p] - rG
            moment += arm[0] * Fp[1] - arm[1] * Fp[0]
        for T in torque_on.get(body.name, ()) if body.turns else ():
            moment += T
        a = acc(rG)
        alpha = sum((theta.diff(xi) * ai for xi, ai in zip(x, udot)), sp.Integer(0))
        for row in (rG[0], rG[1]):
            D_cols.append([row.diff(xi) for xi in x])
        D_cols.append([theta.diff(xi) if body.turns else sp.Integer(0) for xi in x])
        f_rows += [F[0] - mass * a[0], F[1] - mass * a[1],
                   (moment - inertia * alpha) if body.turns else sp.Integer(0)]
    D = sp.Matrix(D_cols).T if D_cols else sp.zeros(n, 0)
    f = sp.Matrix(f_rows) if f_rows else sp.zeros(0, 1)
    C = sp.eye(M).col_join(d.K) if len(d.S) else sp.eye(M)
    e = (D * f).applyfunc(sp.expand)
    # the equation of motion, with K and L as symbols: S' = K q', S'' = K q'' + L q'^2
    Ks = sp.Matrix(len(d.S), M, d.K_symbols) if len(d.S) else sp.zeros(0, M)
    L_symbols = tuple(names(f"L_{s}" if M == 1 else f"L_{s},{a + 1}{b + 1}")
                      for s in d.S for a in range(M) for b in range(M))
    qd = sp.Matrix([d.dot(s) for s in d.q])
    qdd = sp.Matrix([d.ddot(s) for s in d.q])
    subs = {}
    for i, s in enumerate(d.S):
        subs[d.dot(s)] = (Ks[i, :] * qd)[0]
        acc_i = (Ks[i, :] * qdd)[0]
        for a_ in range(M):
            for b_ in range(M):
                acc_i += L_symbols[i * M * M + a_ * M + b_] * qd[a_] * qd[b_]
        subs[d.ddot(s)] = acc_i
    Csym = sp.eye(M).col_join(Ks) if len(d.S) else sp.eye(M)
    tau_expr = (-(Csym.T * e)).xreplace(subs).applyfunc(lambda ex: _tidy(ex, qdd, qd))
    tau = tuple(names(f"tau_{name}") for name in m.input_names)
    return KaneDerivation(derivation=d, bodies=plan.bodies, x=x, u=u, C=C, D=D, f=f, tau=tau,
                          equations=tau_expr, L_symbols=L_symbols, parameters=params,
                          load_values=loads, loads=plan.loads, masses=plan.masses,
                          positions={b.point: pos[b.point] for b in plan.bodies},
                          _e=e)


def _tidy(expr, qdd, qd):
    """An effort as the notes write it: a coefficient for each acceleration and each product
    of speeds, each simplified within the bounds, then the rest."""
    import sympy as sp
    from itertools import combinations_with_replacement
    expr = sp.expand(expr)
    monomials = list(qdd) + [a * b for a, b in combinations_with_replacement(qd, 2)]
    poly = sp.Poly(expr, *qdd, *qd)
    out = sp.Integer(0)
    for mono in monomials:
        c = poly.coeff_monomial(mono)
        if c != 0:
            out += simplified(c)[0] * mono
    rest = sp.expand(expr - sum((poly.coeff_monomial(mn) * mn for mn in monomials), sp.Integer(0)))
    return out + simplified(rest)[0]


def _source_text(law) -> str:
    """A law as its source reads: a number, an expression, or what kind of thing it is."""
    s = law.source
    if isinstance(s, (int, float)) or isinstance(s, str):
        return str(s)
    return "table" if isinstance(s, dict) else "function"


def _law_text(f, component: int) -> str:
    law = f._law
    if isinstance(law, tuple):
        return _source_text(law[component])
    return "function"

