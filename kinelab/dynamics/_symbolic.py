"""Equations of motion in symbols (sympy), for small open-chain models (closed chains:
:func:`kinelab.derive.derive`, which writes the notes' C, D and f)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from kinelab._expressions import to_sympy
from kinelab.dynamics._loads import Law, Loads
from kinelab.dynamics._masses import MassProperties
from kinelab.dynamics._terms import build_system
from kinelab.errors import ModelError, describe
from kinelab.kinematics import plan
from kinelab.model import Mechanism

__all__ = ["equations_of_motion", "EquationsOfMotion"]


@dataclass(frozen=True, eq=False)
class EquationsOfMotion:
    """Kane's equations ``tau = M(q) q'' + h(q, q') - Q(t, q, q')`` in symbols.

    Attributes
    ----------
    mechanism : Mechanism
    t : sympy.Symbol
    q, qd, qdd : tuple of sympy.Symbol
        One per input, in the model's order: ``q1, q2 ...``, their rates ``u1, u2 ...``
        (the notes' generalised speeds) and accelerations ``du1, du2 ...``.
    mass_matrix : sympy.Matrix, shape (M, M)
    velocity_terms : sympy.Matrix, shape (M, 1)
        h: the centripetal and Coriolis terms.
    load_forces : sympy.Matrix, shape (M, 1)
        Q: the generalised forces of gravity, springs, dampers, forces and torques.
    input_forces : sympy.Matrix, shape (M, 1)
        tau, the actuators' efforts.
    parameters : dict of str to sympy.Symbol
        The symbols standing for the model's data (``m_arm``, ``I_arm``, ``g``, lengths).
    values : dict of sympy.Symbol to float
        Their values in the model.
    """

    mechanism: Mechanism
    t: object
    q: tuple
    qd: tuple
    qdd: tuple
    mass_matrix: object
    velocity_terms: object
    load_forces: object
    input_forces: object
    parameters: dict = field(default_factory=dict)
    values: dict = field(default_factory=dict)

    def equations(self) -> list:
        """``tau_k = ...`` for each input, as sympy equalities."""
        import sympy as sp
        return [sp.Eq(sp.Symbol(f"tau_{name}"), e) for name, e in
                zip(self.mechanism.input_names, self.input_forces)]

    def latex(self) -> str:
        """The equations in LaTeX (one per line), with dots over the rates."""
        import sympy as sp
        names = {}
        for k, (u, du) in enumerate(zip(self.qd, self.qdd), start=1):
            names[u] = rf"\dot{{q}}_{{{k}}}"
            names[du] = rf"\ddot{{q}}_{{{k}}}"
        names.update({s: n for s, n in ((s, _latex_name(str(s))) for s in self.parameters.values())})
        return "\n".join(
            rf"\tau_{{\mathrm{{{name}}}}} = " + sp.latex(e, symbol_names=names)
            for name, e in zip(self.mechanism.input_names, self.input_forces))

    def numeric(self):
        """A vectorised function ``tau(q, qd, qdd, t=0.0)`` with the model's values, shapes as in
        :func:`kinelab.dynamics.inverse` ((N, M) in, (N, M) out)."""
        import sympy as sp
        expr = self.input_forces.subs(self.values)
        f = sp.lambdify((self.t, *self.q, *self.qd, *self.qdd), list(expr), "numpy")
        M = len(self.q)

        def tau(q, qd, qdd, t=0.0):
            q, qd, qdd = (np.reshape(np.asarray(a, float), (-1, M)) for a in (q, qd, qdd))
            t = np.broadcast_to(np.asarray(t, float), (q.shape[0],))
            cols = f(t, *q.T, *qd.T, *qdd.T)
            return np.stack([np.broadcast_to(np.asarray(c, float), t.shape) for c in cols], axis=-1)
        return tau

    def __str__(self) -> str:
        return "\n".join(f"{eq.lhs} = {eq.rhs}" for eq in self.equations())


def _latex_name(name: str) -> str:
    head, _, tail = name.partition("_")
    return f"{head}_{{\\mathrm{{{tail}}}}}" if tail else head


def _exact(x: float):
    """A sketch number as sympy shows it best: 0.5 -> 1/2, 1.5707963 -> pi/2."""
    import sympy as sp
    if abs(x) < 1e-14:
        return sp.Integer(0)
    v = sp.nsimplify(x, [sp.pi], tolerance=1e-12 * max(1.0, abs(x)))
    return v if abs(float(v) - x) <= 1e-12 * max(1.0, abs(x)) else sp.Float(x)


def spring_tension(item, length, rate):
    """The tension of a spring, ``k (l - l0)``, or of a damper, ``c dl/dt``, in symbols
    (``length`` and ``rate`` are sympy expressions)."""
    if hasattr(item, "stiffness"):
        return _exact(item.stiffness) * (length - _exact(item.free_length))
    return _exact(item.damping) * rate


def equations_of_motion(model: Mechanism, *, loads: Loads | None = None,
                        masses: MassProperties | None = None,
                        lengths: Literal["numeric", "symbols"] = "numeric") -> EquationsOfMotion:
    """Kane's equations of an open-chain mechanism, in symbols.

    Every link is placed from the ground through joints that are inputs (a serial or tree
    robot, a pendulum), so every position is an explicit function of q; the mass matrix
    ``M = sum m J_G^T J_G + I J_theta^T J_theta`` (J = dr/dq), the velocity terms
    ``h = sum m J_G^T (dJ_G/dt q') + ...`` and the loads' generalised forces follow by
    differentiation, and are simplified.  Masses, inertias and gravity are symbols;
    lengths are the model's numbers, or symbols with ``lengths="symbols"``.

    Parameters
    ----------
    model : Mechanism
    loads : Loads, optional
        Gravity, and forces, torques, springs and dampers given as numbers or expressions
        (tables and Python callables have no symbolic form).
    masses : MassProperties, optional
    lengths : {"numeric", "symbols"}
        "symbols": each point's coordinates in its link's frame, measured from the joint
        that places the link, become ``l_<joint point><point>`` (along the link) and
        ``h_<joint point><point>`` (across it, when not zero).

    Returns
    -------
    EquationsOfMotion

    Raises
    ------
    ModelError
        A closed chain, or a joint that is not an input (the explicit positions of an open
        chain are what make the symbols small); :func:`kinelab.derive.derive` writes the
        equations of a closed chain, through its loop equations.

    Examples
    --------
    >>> from kinelab.model import Mechanism, Point, Link, Joint, Input
    >>> from kinelab.dynamics import Loads, equations_of_motion
    >>> pendulum = Mechanism("pendulum", (Point("O", 0, 0), Point("G", 0.5, 0)),
    ...     (Link("ground", ("O",), ground=True),
    ...      Link("arm", ("O", "G"), mass=2.0, center_of_mass="G", inertia=0.01)),
    ...     (Joint("pivot", "R", ("ground", "arm"), point="O"),), (Input(joint="pivot"),))
    >>> eom = equations_of_motion(pendulum, loads=Loads(gravity=(0.0, -9.81)), lengths="symbols")
    >>> print(eom)
    tau_pivot = du1*(I_arm + l_OG**2*m_arm) + g*l_OG*m_arm*cos(q1)
    """
    import sympy as sp

    system = build_system(model, loads, masses)
    if system.loads.pair_loads:
        raise ModelError("loads: friction in joints and torsional springs and dampers have no "
                         "symbolic form here yet; leave them out of the symbolic equations, or use "
                         "kinelab.dynamics.inverse and simulate, which take them")
    loads, masses = system.loads, system.masses
    if lengths not in ("numeric", "symbols"):
        raise ModelError(f"lengths: expected one of 'numeric', 'symbols', got {describe(lengths)}")
    M = len(model.inputs)
    t = sp.Symbol("t")
    q = sp.symbols(f"q1:{M + 1}")
    u = sp.symbols(f"u1:{M + 1}")
    du = sp.symbols(f"du1:{M + 1}")
    params: dict[str, object] = {}
    values: dict[object, float] = {}

    def param(name, value):
        s = params.setdefault(name, sp.Symbol(name, real=True))
        values[s] = float(value)
        return s
    frame, pos = _place(model, q, lengths, param)
    qv, uv = sp.Matrix(q), sp.Matrix(u)

    def jac(r):
        return sp.Matrix(r).jacobian(qv)

    def bias(r):
        return (jac(r) * uv).jacobian(qv) * uv
    Mm = sp.zeros(M, M)
    h = sp.zeros(M, 1)
    Q = sp.zeros(M, 1)
    g = np.array(loads.gravity)
    gmag = float(np.hypot(*g))
    gvec = sp.Matrix([_exact(c / gmag) for c in g]) * param("g", gmag) if gmag else sp.zeros(2, 1)
    bodies = [(f"m_{b.link}", b.mass, pos[b.center_of_mass]) for b in masses.links]
    bodies += [(f"m_{p.point}", p.mass, pos[p.point]) for p in masses.points]
    for name, mass, r in bodies:
        m, J = param(name, mass), jac(r)
        Mm += m * J.T * J
        h += m * J.T * bias(r)
        Q += m * J.T * gvec
    for b in masses.links:
        if b.inertia > 0:
            inertia, Jt = param(f"I_{b.link}", b.inertia), jac([frame[b.link]])
            Mm += inertia * Jt.T * Jt
            h += inertia * Jt.T * bias([frame[b.link]])

    def law(lw: Law):
        if lw.constant:
            return _exact(float(lw.source))
        if isinstance(lw.source, str):
            return to_sympy(lw.source, t, q, u, where=lw.where)
        raise ModelError(f"{lw.where}: a table or a Python callable has no symbolic form; give "
                         "the law as a number or an expression")
    applied = sp.zeros(M, 1)        # forces, torques, springs and dampers, kept as derived
    for f in loads.forces:
        if isinstance(f._law, Law):
            law(f._law)             # raises: one callable for both components
        applied += jac(pos[f.point]).T * sp.Matrix([law(c) for c in f._law])
    for tq in loads.torques:
        turn = frame[tq.link] - (frame[tq.reacting] if tq.reacting else 0)
        applied += jac([turn]).T * law(tq._law)
    for s in loads.springs + loads.dampers:
        d = pos[s.points[1]] - pos[s.points[0]]
        length = sp.sqrt(sp.trigsimp(sp.expand(d.dot(d))))
        dl = jac([length])
        tension = spring_tension(s, length, (dl * uv)[0])
        applied -= dl.T * tension
    Mm, h, Q = (mat.applyfunc(lambda e: sp.trigsimp(sp.expand(e))) for mat in (Mm, h, Q))
    Q = Q + applied
    tau = (Mm * sp.Matrix(du) + h).applyfunc(lambda e: sp.collect(sp.expand(e), du)) - Q
    return EquationsOfMotion(mechanism=model, t=t, q=q, qd=u, qdd=du, mass_matrix=Mm,
                             velocity_terms=h, load_forces=Q, input_forces=tau,
                             parameters=params, values=values)


def _place(model: Mechanism, q, lengths: str, param):
    """Frame angles and point positions of an open chain as sympy expressions of q.

    The frame angle of the ground is 0 and of a moving link its angle (from its first
    point to its second); an input joint fixes the angle of one link relative to the other
    (R) or the slide of one along the other (P)."""
    import sympy as sp
    p = plan(model)
    inputs = {}
    for k, inp in enumerate(model.inputs):
        if inp.joint is None:
            raise ModelError(f"inputs[{k}]: equations_of_motion needs inputs on joints; this one is "
                             f"the angle between links {inp.links}")
        inputs[inp.joint] = k
    passive = [j.name for j in model.joints if j.name not in inputs]
    if passive:
        raise ModelError(f"equations_of_motion: joint(s) {', '.join(map(repr, passive))} are not "
                         "inputs; symbolic equations are derived for open chains whose every joint "
                         "is driven (pendulums, serial robots); for closed chains use "
                         "kinelab.derive.derive (C^T D f = 0 in symbols), inverse() and simulate()")
    ground = model.ground.name
    sk = {n: (0.0 if n == ground else float(p.sketch_angles[p.link_item[n]])) for n in model.link_names}
    xy = {pt.name: np.array(pt.xy) for pt in model.points}

    def rot(a, v):
        return sp.Matrix([sp.cos(a) * v[0] - sp.sin(a) * v[1], sp.sin(a) * v[0] + sp.cos(a) * v[1]])

    def local(link, base, point):
        """Coordinates of point in link's frame, from base (sympy numbers or symbols)."""
        v = xy[point] - xy[base]
        c, s = math.cos(sk[link]), math.sin(sk[link])
        along, across = c * v[0] + s * v[1], -s * v[0] + c * v[1]
        if lengths == "numeric":
            return [_exact(along), _exact(across)]
        return [param(f"l_{base}{point}", along) if abs(along) > 1e-14 else 0,
                param(f"h_{base}{point}", across) if abs(across) > 1e-14 else 0]
    frame = {ground: sp.Integer(0)}
    pos = {pn: sp.Matrix([_exact(c) for c in xy[pn]]) for pn in model.link(ground).points}
    todo = [j for j in model.joints]
    while todo:
        progress = False
        for j in list(todo):
            a, b = j.links
            if (a in frame) == (b in frame):
                if a in frame:
                    raise ModelError(f"equations_of_motion: joint '{j.name}' closes a loop; symbolic "
                                     "equations are derived for open chains; for closed chains use "
                                     "kinelab.derive.derive (C^T D f = 0 in symbols), inverse() "
                                     "and simulate()")
                continue
            known, new = (a, b) if a in frame else (b, a)
            qk = q[inputs[j.name]]
            if j.type == "R":
                frame[new] = frame[known] + (qk if new == b else -qk)
                base = j.point
                for pn in model.link(new).points:
                    if pn != base:
                        pos[pn] = pos[base] + rot(frame[new], local(new, base, pn))
            else:
                guide, slider = j.links
                offset = _exact(sk[slider] - sk[guide])
                frame[new] = frame[known] + (offset if new == slider else -offset)
                origin = j.origin or model.link(guide).points[0]
                u0 = np.asarray(j.axis, float) / math.hypot(*j.axis)
                c, s = math.cos(sk[guide]), math.sin(sk[guide])
                ug = [_exact(c * u0[0] + s * u0[1]), _exact(-s * u0[0] + c * u0[1])]   # in guide frame
                w = _exact(-u0[1] * (xy[j.point] - xy[origin])[0] + u0[0] * (xy[j.point] - xy[origin])[1])
                along = rot(frame[guide], ug)
                across = rot(frame[guide], [-ug[1], ug[0]])
                if new == slider:
                    pos[j.point] = pos[origin] + qk * along + w * across
                    base = j.point
                else:
                    pos[origin] = pos[j.point] - qk * along - w * across
                    base = origin
                for pn in model.link(new).points:
                    if pn != base:
                        pos[pn] = pos[base] + rot(frame[new], local(new, base, pn))
            todo.remove(j)
            progress = True
        if not progress:
            break
    return frame, pos
