"""The routes that recompute inverse dynamics and simulations, and their certificate.

The reported efforts come from Kane's equations (generalised inertia and load forces built
from K and L).  The routes here share none of that code:

- **power balance**: the actuators' power against d(kinetic + potential)/dt + dissipation -
  the loads' power, every term from the bodies' velocities and accelerations (``sum m v.a +
  I omega alpha``), the springs' and dampers' lengths and the loads' values;
- **Newton-Euler**: the free-body equations of every link, solved for the efforts and
  reactions (computed by :func:`kinelab.dynamics.inverse` beside Kane's);
- **link balance**: each moving link under the reported reactions, efforts, weights, loads
  and inertia forces, summed here force by force;
- **momentum**: the shaking force and moment from the whole mechanism's change of
  momentum and the external loads, without any joint reaction;
- **energies** from the bodies' speeds and heights and the springs' stretch;
- for a simulation, **inverse dynamics** of its motion (q, q', q'') give back the efforts
  that were applied, and the integrated work balances the change of energy to within the
  integration's tolerance.
"""
from __future__ import annotations

import math

import numpy as np

from kinelab.kinematics import KinematicSolution
from kinelab.verify._certificate import Certificate, Comparison, Quantity
from kinelab.verify._kinematics import certify_kinematics

__all__ = ["certify_dynamics"]

EPS = np.finfo(float).eps
BALANCE_BOUND = 1e-9
"""Relative to the largest term: sums of a few dozen products of K, L and the rates, each
rounded (~1e-15), and a solve of the free-body equations whose condition grows near
singular configurations (samples flagged singular are left out)."""
ENERGY_BOUND = 1e-12
"""Relative to the largest energy: the same formula, summed in another order."""
INTEGRATION_FACTOR = 100.0
"""The integrated energy balance of a simulation may miss by this many times its rtol: the
integrator keeps each step's error in q and q' within rtol of their size, and the energy,
quadratic in q', accumulates it over the steps."""


class _Sums:
    """The independent terms of the balances, at every sample (arrays over samples)."""

    def __init__(self, sol: KinematicSolution, t: np.ndarray, loads, masses):
        from kinelab.dynamics._loads import default_carrier
        m = sol.mechanism
        self.model, self.sol = m, sol
        N = sol.N
        self.ground = m.ground.name
        g = np.array(loads.gravity, float)
        q, qd = sol.q, sol.qd
        self.kinetic = np.zeros(N)
        self.potential = np.zeros(N)
        self.kinetic_rate = np.zeros(N)
        self.potential_rate = np.zeros(N)
        self.load_power = np.zeros(N)
        self.dissipation = np.zeros(N)
        self.force = {n: np.zeros((N, 2)) for n in m.link_names}     # on each link, N
        self.moment = {n: np.zeros(N) for n in m.link_names}         # about the origin, N m
        self.scale_force = 0.0
        self.scale_power = 0.0
        self.shaking_force = np.zeros((N, 2))      # what the momentum balance says
        self.shaking_moment = np.zeros(N)

        def point(p):
            return sol.position(p).reshape(N, 2), sol.velocity(p).reshape(N, 2), \
                sol.acceleration(p).reshape(N, 2)

        def on(link, f, at, moment=None, external=True):
            """A force f (N, 2) at ``at`` (N, 2) and a moment on ``link``; an external one
            counts in the shaking force and moment when a moving link takes it."""
            if f is not None:
                self.force[link] += f
                self.moment[link] += _cross(at, f)
                self.scale_force = max(self.scale_force, float(np.nanmax(np.abs(f), initial=0)))
            if moment is not None:
                self.moment[link] += moment
            if external and link != self.ground:
                if f is not None:
                    self.shaking_force += f
                    self.shaking_moment += _cross(at, f)
                if moment is not None:
                    self.shaking_moment += moment

        bodies = [(b.link, b.mass, b.center_of_mass, b.inertia) for b in masses.links]
        bodies += [(default_carrier(m, p.point, p.link), p.mass, p.point, 0.0) for p in masses.points]
        for link, mass, where, inertia in bodies:
            r, v, a = point(where)
            self.kinetic += 0.5 * mass * _dot(v, v)
            self.kinetic_rate += mass * _dot(v, a)
            self.potential -= mass * (r @ g)
            self.potential_rate -= mass * (v @ g)
            if inertia:
                w, al = sol.omega(link).reshape(N), sol.alpha(link).reshape(N)
                self.kinetic += 0.5 * inertia * w ** 2
                self.kinetic_rate += inertia * w * al
            else:
                al = np.zeros(N)
            if link != self.ground:       # the ground's masses do not move
                on(link, mass * (g - a), r, -inertia * al)
        for f in loads.forces:
            r, v, _ = point(f.point)
            value = f.value(t, q, qd)
            self.load_power += _dot(value, v)
            link = default_carrier(m, f.point, f.link)
            if link != self.ground:       # a force on the ground does not load the linkage
                on(link, value, r)
        for tq in loads.torques:
            T = tq.value(t, q, qd)
            w = sol.omega(tq.link).reshape(N)
            if tq.reacting is not None:
                w = w - sol.omega(tq.reacting).reshape(N)
            self.load_power += T * w
            if tq.link != self.ground:
                on(tq.link, None, None, T)
            if tq.reacting is not None:
                # the stator's torque: on the ground it is the shaking moment's directly
                on(tq.reacting, None, None, -T, external=tq.reacting != self.ground)
                if tq.reacting == self.ground:
                    self.shaking_moment -= T
        for s in tuple(loads.springs) + tuple(loads.dampers):
            (ra, va, _), (rb, vb, _) = point(s.points[0]), point(s.points[1])
            d = rb - ra
            length = np.linalg.norm(d, axis=-1)
            e = d / length[:, None]
            rate = _dot(e, vb - va)
            k, c = getattr(s, "stiffness", 0.0), getattr(s, "damping", 0.0)
            stretch = length - getattr(s, "free_length", 0.0)
            self.potential += 0.5 * k * stretch ** 2
            self.potential_rate += k * stretch * rate
            self.dissipation += c * rate ** 2
            pull = (k * stretch + c * rate)[:, None] * e          # on the first end
            for end, sign in ((0, 1.0), (1, -1.0)):
                link = default_carrier(m, s.points[end], s.links[end])
                on(link, sign * pull, (ra, rb)[end], external=False)
                # a spring's two ends pull equally and oppositely along one line: nothing
                # of it reaches the whole mechanism's balance
        # friction in R joints and torsional springs and dampers: a torque on the second
        # link and its opposite on the first, from the relative angle and speed
        pairs = [(m.joint(f.joint).links, "friction", f) for f in loads.friction
                 if m.joint(f.joint).type == "R"]
        pairs += [(sp.links, "spring", sp) for sp in loads.torsional_springs]
        pairs += [(d.links, "damper", d) for d in loads.torsional_dampers]
        for (a, b), kind, item in pairs:
            w = sol.omega(b).reshape(N) - sol.omega(a).reshape(N)
            if kind == "friction":
                T = -item.magnitude * np.tanh(w / item.smoothing)
                self.dissipation -= T * w
            elif kind == "damper":
                T = -item.damping * w
                self.dissipation -= T * w
            else:
                phi = sol.angle(b).reshape(N) - sol.angle(a).reshape(N)
                x = np.angle(np.exp(1j * (phi - item.free_angle)))      # within half a turn
                T = -(item.stiffness * x + item.preload)
                self.potential += 0.5 * item.stiffness * x ** 2 + item.preload * x
                self.potential_rate -= T * w
            on(b, None, None, T, external=False)
            on(a, None, None, -T, external=False)
        for f in loads.friction:                 # in P joints: a force along the slide
            j = m.joint(f.joint)
            if j.type != "P":
                continue
            v = sol.slide_velocity(j.name).reshape(N)
            F = -f.magnitude * np.tanh(v / f.smoothing)
            self.dissipation -= F * v
            u = sol.slide_axes(j.name).reshape(N, 2)
            r = sol.position(j.point).reshape(N, 2)
            on(j.links[1], F[:, None] * u, r, external=False)
            on(j.links[0], -F[:, None] * u, r, external=False)
        self.energy_rate = self.kinetic_rate + self.potential_rate

    def power_terms(self, actuator_power: np.ndarray) -> np.ndarray:
        """Every term of the power balance, (N, 5), for its scale."""
        return np.stack([actuator_power, self.load_power, self.kinetic_rate,
                         self.potential_rate, self.dissipation], axis=-1)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("ni,ni->n", a, b)


def _cross(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    return r[:, 0] * f[:, 1] - r[:, 1] * f[:, 0]


def _largest(diff: np.ndarray, scale: float, rows: np.ndarray) -> float:
    d = np.abs(np.asarray(diff)[rows]) / (scale if scale > 0 else 1.0)
    if d.size == 0:
        return 0.0
    return math.nan if np.isnan(d).any() else float(d.max())


def _scale(*arrays, rows) -> float:
    """The largest |value| of the arrays at ``rows`` (1 where every one is zero)."""
    s = max((float(np.max(np.abs(np.asarray(a)[rows]), initial=0.0)) for a in arrays),
            default=0.0)
    return s if s > 0 else 1.0


def _efforts_power(sol: KinematicSolution, tau: np.ndarray) -> np.ndarray:
    return np.einsum("nm,nm->n", tau, sol.qd)


def certify_dynamics(result, *, loads=None, masses=None, rtol: float | None = None) -> Certificate:
    """The certificate of an :class:`~kinelab.dynamics.InverseDynamics`, a
    :class:`~kinelab.dynamics.Simulation` or a :class:`~kinelab.dynamics.SimulationBatch`
    (see the module docstring for the routes).  ``loads`` and ``masses`` default to the
    model's ``[dynamics]`` section, as the dynamics' own do; ``rtol`` (a simulation's
    tolerance) adds the integrated energy balance."""
    from kinelab.dynamics import InverseDynamics, SimulationBatch
    from kinelab.dynamics._terms import build_system
    if isinstance(result, SimulationBatch):
        return Certificate.merge(
            [certify_dynamics(result[i], loads=loads, masses=masses, rtol=rtol)
             for i in range(len(result.status))],
            f"{len(result.status)} simulations of '{result.mechanism.name}'", "run")
    sol = result.kinematics
    system = build_system(sol.mechanism, loads, masses)
    loads, masses = system.loads, system.masses
    sums = _Sums(sol, np.asarray(result.t, float), loads, masses)
    rows = sol.assembled & ~sol.singular & np.isfinite(result.input_forces).all(axis=1)
    quantities, notes = [], []
    if (~rows).any():
        notes.append(f"{int((~rows).sum())} sample(s) singular or unassembled: forces undefined "
                     "there (NaN), not compared")
    n = int(rows.sum())
    if isinstance(result, InverseDynamics):
        reported = "Kane's equations"
        scale = _effort_scale(result.inertia_forces, result.load_forces, rows)
        what = f"inverse dynamics of '{sol.mechanism.name}', {sol.N} samples"
        efforts = []
        if result.newton_euler_efforts is not None:
            efforts.append(Comparison("Newton-Euler (free bodies)", n, _largest(
                (result.newton_euler_efforts - result.input_forces) / scale, 1.0, rows),
                BALANCE_BOUND, _BALANCE_REASON))
    else:
        from kinelab.dynamics import inverse
        reported = "forward dynamics (applied laws)"
        what = (f"simulation of '{sol.mechanism.name}', {sol.N} outputs from t = "
                f"{result.t[0]:.6g} to {result.t[-1]:.6g} s")
        back = inverse(sol.mechanism, *_motion(sol), loads=loads, masses=masses,
                       t=np.asarray(result.t, float))
        scale = _effort_scale(back.inertia_forces, back.load_forces, rows)
        efforts = [Comparison("inverse dynamics of the motion", n, _largest(
            (back.input_forces - result.input_forces) / scale, 1.0, rows), BALANCE_BOUND,
            _BALANCE_REASON)]
        efforts.append(Comparison("Newton-Euler (free bodies)", n, _largest(
            (back.newton_euler_efforts - result.input_forces) / scale, 1.0, rows),
            BALANCE_BOUND, _BALANCE_REASON))
    power = _efforts_power(sol, result.input_forces)
    balance = power + sums.load_power - sums.energy_rate - sums.dissipation
    p_scale = _scale(sums.power_terms(power), rows=rows)
    efforts.append(Comparison("power balance", n, _largest(balance, p_scale, rows),
                              BALANCE_BOUND, _BALANCE_REASON))
    unit = ("each input's largest generalised inertia or load force over the motion "
            f"({_amounts(scale, result.input_kinds)}); the power balance: its largest term, "
            f"{p_scale:.6g} W")
    quantities.append(Quantity("effort", reported, unit, tuple(efforts)))
    e_scale = _scale(sums.kinetic, sums.potential, rows=rows)
    quantities.append(Quantity("energy", reported, f"the largest energy, {e_scale:.6g} J", (
        Comparison("kinetic energy from the bodies' speeds", n,
                   _largest(result.kinetic_energy - sums.kinetic, e_scale, rows),
                   ENERGY_BOUND, _ENERGY_REASON),
        Comparison("potential energy from heights and stretch", n,
                   _largest(result.potential_energy - sums.potential, e_scale, rows),
                   ENERGY_BOUND, _ENERGY_REASON))))
    if isinstance(result, InverseDynamics):
        quantities += _reactions(result, sums, rows, notes)
    else:
        quantities += _integration(result, rtol, notes)
    # the motion the forces come from: its positions, K, L and rates
    motion = certify_kinematics(sol)
    notes += [f"the motion: {n}" for n in motion.notes]
    return Certificate(what, motion.quantities + tuple(quantities), tuple(notes))


_BALANCE_REASON = ("rounding in sums of products of K, L and rates (1e-15 each), and the "
                   "free bodies' solve, relative to the largest term")
_ENERGY_REASON = "the same sums in another order: rounding"


def _amounts(scale: np.ndarray, kinds) -> str:
    return ", ".join(f"{v:.6g} {'N m' if k == 'angle' else 'N'}"
                     for v, k in zip(np.atleast_1d(scale), kinds))


def _effort_scale(inertia: np.ndarray, load: np.ndarray, rows) -> np.ndarray:
    """Per input: the largest |F*| or |Q| over the motion (1 where both are zero)."""
    s = np.maximum(np.max(np.abs(inertia[rows]), axis=0, initial=0.0),
                   np.max(np.abs(load[rows]), axis=0, initial=0.0))
    return np.where(s > 0, s, 1.0)


def _motion(sol: KinematicSolution):
    """q, q', q'' of a solution as analyze and inverse take them."""
    if sol.M > 1:
        return sol.q, sol.qd, sol.qdd
    return sol.q[:, 0], sol.qd[:, 0], sol.qdd[:, 0]


def _reactions(result, sums: _Sums, rows, notes: list[str]) -> list[Quantity]:
    """Each moving link's balance under the reported reactions and efforts; the shaking
    force and moment against the whole mechanism's momentum."""
    if result.reaction_forces is None:
        notes.append("reactions and shaking: not computed (reactions=False), not checked")
        return []
    m, sol = result.mechanism, result.kinematics
    N = sol.N
    force = {k: v.copy() for k, v in sums.force.items()}
    moment = {k: v.copy() for k, v in sums.moment.items()}

    def on(link, f, at, mo=None):
        if f is not None:
            force[link] += f
            moment[link] += _cross(at, f)
        if mo is not None:
            moment[link] += mo
    for c, j in enumerate(m.joints):
        first, second = j.links
        at = _acting_point(sol, j)
        f = result.reaction_forces[:, c]
        on(second, f, at, result.reaction_moments[:, c] if j.type == "P" else None)
        on(first, -f, at, -result.reaction_moments[:, c] if j.type == "P" else None)
    for k, inp in enumerate(m.inputs):
        tau = result.input_forces[:, k]
        joint = m.joint(inp.joint) if inp.joint is not None else None
        if joint is not None and joint.type == "P":
            u = sol.slide_axes(joint.name).reshape(N, 2)
            at = sol.position(joint.point).reshape(N, 2)
            on(joint.links[1], tau[:, None] * u, at)
            on(joint.links[0], -tau[:, None] * u, at)
        else:
            first, second = joint.links if joint is not None else inp.links
            on(second, None, None, tau)
            on(first, None, None, -tau)
    f_scale = max(sums.scale_force, _scale(result.reaction_forces, rows=rows))
    size = float(sol.plan.scale)
    moving = [n for n in m.link_names if n != sums.ground]
    worst_f = max((_largest(np.linalg.norm(force[n], axis=-1), f_scale, rows) for n in moving),
                  default=0.0)
    worst_m = max((_largest(_about_first_point(sol, n, force[n], moment[n]), f_scale * size, rows)
                   for n in moving), default=0.0)
    n = int(rows.sum())
    unit = (f"the largest force on a link, {f_scale:.6g} N; moments: that force times the "
            f"mechanism's size, {f_scale * size:.6g} N m")
    out = [Quantity("reaction", "Newton-Euler (free bodies)", unit, (
        Comparison("force balance of each link", n, worst_f, BALANCE_BOUND, _BALANCE_REASON),
        Comparison("moment balance of each link", n, worst_m, BALANCE_BOUND, _BALANCE_REASON)))]
    if result.shaking_force is not None:
        out.append(Quantity("shaking", "Newton-Euler (free bodies)", unit, (
            Comparison("momentum of the whole mechanism (force)", n, _largest(
                np.linalg.norm(result.shaking_force - sums.shaking_force, axis=-1), f_scale, rows),
                BALANCE_BOUND, _BALANCE_REASON),
            Comparison("momentum of the whole mechanism (moment)", n, _largest(
                result.shaking_moment - sums.shaking_moment, f_scale * size, rows),
                BALANCE_BOUND, _BALANCE_REASON))))
    return out


def _acting_point(sol, j) -> np.ndarray:
    """Where a joint's reaction acts, (N, 2): its point; a gear mesh's pitch point (on the
    line of centres, dividing it as the pitch radii do); a cam joint's contact point, the
    point of its follower's prismatic joint."""
    from kinelab.model import gear_mesh
    from kinelab.model._cams import cam_pair
    m, N = sol.mechanism, sol.N
    if j.type == "G":
        g = gear_mesh(m, j)
        oa = sol.position(g.centre_a).reshape(N, 2)
        if g.mesh == "rack":
            u = sol.slide_axes(g.slide).reshape(N, 2)
            return oa + g.k * np.stack([u[:, 1], -u[:, 0]], axis=-1)
        ob = sol.position(g.centre_b).reshape(N, 2)
        return (oa - g.k * ob) / (1.0 - g.k)
    if j.type == "C":
        return sol.position(m.joint(cam_pair(m, j).follower_joint).point).reshape(N, 2)
    return sol.position(j.point).reshape(N, 2)


def _about_first_point(sol, link, force, moment_about_origin):
    """The moment about the link's first point (it is of the size of the forces times the
    link's size, whatever the distance from the origin)."""
    r = sol.position(sol.mechanism.link(link).points[0]).reshape(sol.N, 2)
    return moment_about_origin - _cross(r, force)


def _integration(sim, rtol: float | None, notes: list[str]) -> list[Quantity]:
    """The simulation's integrated work against its change of energy."""
    if rtol is None:
        notes.append("the integrated energy balance: not checked (give the simulation's rtol)")
        return []
    scale = _scale(sim.kinetic_energy, sim.potential_energy, sim.actuator_work,
                   sim.applied_work, sim.dissipated, rows=slice(None))
    ok = np.isfinite(sim.energy_balance)
    bound = max(INTEGRATION_FACTOR * rtol, 1e3 * EPS)
    return [Quantity("energy balance", "integrated work", f"the largest energy or work, {scale:.6g} J", (
        Comparison("change of the mechanical energy", int(ok.sum()),
                   _largest(sim.energy_balance, scale, ok), bound,
                   f"{INTEGRATION_FACTOR:g} times the integration's rtol ({rtol:g})"),))]
