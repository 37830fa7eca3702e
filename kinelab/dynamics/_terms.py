"""The terms of Kane's equations, vectorised over samples, from a kinematic solution.

With the velocity coefficients K (the notes' C and D matrices: the rows of K for the
centres of mass and the link angles, the identity rows being the inputs themselves) and
the accelerations a_G = K q'' + q'^T L q' that the kinematics engine returns, the
generalised inertia force of the independent coordinates is::

    F* = sum over bodies of  K_G^T m a_G + K_theta^T I alpha        (*Mecanismos*, eq. 58-66)

and each applied load contributes ``K_P^T F`` (a force at point P), ``K_theta^T T`` (a
torque), ``-T dl/dq`` (a spring or damper of tension T and length l).  Kane's equations
``C^T D f = 0`` read ``tau + Q = F*``: the actuator efforts are ``tau = F* - Q``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kinelab.dynamics._loads import Loads, default_carrier
from kinelab.dynamics._masses import MassProperties
from kinelab.errors import ModelError, SingularityError, describe
from kinelab.kinematics import KinematicSolution, plan
from kinelab.model import Mechanism, real_array


@dataclass(frozen=True, eq=False)
class System:
    """A mechanism with its masses and loads, as index arrays into the kinematic jets."""

    model: Mechanism
    masses: MassProperties
    loads: Loads
    M: int
    t_items: np.ndarray       # (nb,) x item of each translating mass (centres of mass, lumps)
    t_mass: np.ndarray        # (nb,) kg
    t_links: tuple[str, ...]  # the link whose free body carries each
    r_items: np.ndarray       # (nr,) angle item of each link with inertia
    r_inertia: np.ndarray     # (nr,) kg m^2
    gravity: np.ndarray       # (2,)
    items: np.ndarray         # (k,) every coordinate with inertia: x, y of each mass, angles
    weights: np.ndarray       # (k,) its mass or moment of inertia
    weight: np.ndarray        # (k,) the gravity force along it (zero for angles), N
    gravity_along: np.ndarray  # (k,) gravity's component along it (zero for angles), m/s^2
    force_items: np.ndarray   # (nf,) x item of each point force
    torque_items: np.ndarray  # (nt, 2) angle items of the link and the reacting link (-1: none)
    spring_items: np.ndarray  # (ns, 2) x items of the ends of springs, then dampers
    spring_k: np.ndarray      # (ns,) N/m (0 for dampers)
    spring_l0: np.ndarray     # (ns,) m
    spring_c: np.ndarray      # (ns,) N s/m (0 for springs)
    spring_names: tuple[str, ...]
    pair_links: tuple[tuple[str, str], ...] = ()   # friction in R joints, torsional springs
    pair_items: np.ndarray | None = None           # (np, 2) angle items of those links
    pair_kind: np.ndarray | None = None            # (np,) 0 friction, 1 spring, 2 damper
    pair_values: np.ndarray | None = None          # (np, 4) magnitude or k or c, smoothing,
                                                   # free angle, preload
    slide_joints: tuple[str, ...] = ()             # friction in P joints
    slide_items: np.ndarray | None = None          # (nq,) slide item of each
    slide_values: np.ndarray | None = None         # (nq, 2) magnitude, smoothing


def build_system(model: Mechanism, loads: Loads | None, masses: MassProperties | None) -> System:
    """Check loads and masses against the model (every problem at once) and index them."""
    if not isinstance(model, Mechanism):
        raise ModelError(f"model: expected a kinelab Mechanism, got {type(model).__name__}")
    if loads is None or masses is None:
        # what the model file's [dynamics] section says (nothing when there is none)
        from kinelab.dynamics._setup import DynamicsSetup
        setup = DynamicsSetup.from_model(model)
        loads = setup.loads if loads is None else loads
        masses = setup.masses(model) if masses is None else masses
    if not isinstance(loads, Loads):
        raise ModelError(f"loads: expected a kinelab.dynamics.Loads, got {type(loads).__name__}")
    if not isinstance(masses, MassProperties):
        raise ModelError(f"masses: expected a kinelab.dynamics.MassProperties, got {type(masses).__name__}")
    problems = masses.problems(model) + loads.problems(model)
    if problems:
        raise ModelError(problems, source=f"mechanism '{model.name}'")
    p = plan(model)
    pt, li = p.point_item, p.link_item
    t_items = [pt[b.center_of_mass] for b in masses.links] + [pt[m.point] for m in masses.points]
    t_mass = [b.mass for b in masses.links] + [m.mass for m in masses.points]
    t_links = tuple(b.link for b in masses.links) + tuple(
        default_carrier(model, m.point, m.link) for m in masses.points)
    rot = [(li[b.link], b.inertia) for b in masses.links if b.inertia > 0]
    gravity = np.array(loads.gravity, float)
    items = [i + d for i in t_items for d in (0, 1)] + [r[0] for r in rot]
    weights = [m for m in t_mass for _ in (0, 1)] + [r[1] for r in rot]
    along = [gravity[d] for _ in t_mass for d in (0, 1)] + [0.0] * len(rot)
    weight = [m * g for m, g in zip(weights, along)]
    ends, k, l0, c, names = [], [], [], [], []
    for kind, pairs in (("spring", loads.springs), ("damper", loads.dampers)):
        for s in pairs:
            ends.append([pt[s.points[0]], pt[s.points[1]]])
            k.append(getattr(s, "stiffness", 0.0))
            l0.append(getattr(s, "free_length", 0.0))
            c.append(getattr(s, "damping", 0.0))
            names.append(s.name or f"{kind} {s.points[0]}-{s.points[1]}")
    pairs, kinds, values, slides, slide_values = [], [], [], [], []
    for f in loads.friction:
        j = model.joint(f.joint)
        if j.type == "R":
            pairs.append(tuple(j.links))
            kinds.append(0)
            values.append([f.magnitude, f.smoothing, 0.0, 0.0])
        else:
            slides.append(j.name)
            slide_values.append([f.magnitude, f.smoothing])
    for sp in loads.torsional_springs:
        pairs.append(tuple(sp.links))
        kinds.append(1)
        values.append([sp.stiffness, 1.0, sp.free_angle, sp.preload])
    for d in loads.torsional_dampers:
        pairs.append(tuple(d.links))
        kinds.append(2)
        values.append([d.damping, 1.0, 0.0, 0.0])
    return System(
        pair_links=tuple(pairs),
        pair_items=np.array([[li[a], li[b]] for a, b in pairs], np.int64).reshape(-1, 2),
        pair_kind=np.array(kinds, np.int64), pair_values=np.array(values, float).reshape(-1, 4),
        slide_joints=tuple(slides),
        slide_items=np.array([p.slide_item[n] for n in slides], np.int64),
        slide_values=np.array(slide_values, float).reshape(-1, 2),
        model=model, masses=masses, loads=loads, M=len(model.inputs),
        t_items=np.array(t_items, np.int64), t_mass=np.array(t_mass, float), t_links=t_links,
        r_items=np.array([r[0] for r in rot], np.int64), r_inertia=np.array([r[1] for r in rot], float),
        gravity=gravity, items=np.array(items, np.int64), weights=np.array(weights, float),
        weight=np.array(weight, float), gravity_along=np.array(along, float),
        force_items=np.array([pt[f.point] for f in loads.forces], np.int64),
        torque_items=np.array([[li[tq.link], li[tq.reacting] if tq.reacting else -1]
                               for tq in loads.torques], np.int64).reshape(-1, 2),
        spring_items=np.array(ends, np.int64).reshape(-1, 2), spring_k=np.array(k, float),
        spring_l0=np.array(l0, float), spring_c=np.array(c, float), spring_names=tuple(names))


def point_block(sol: KinematicSolution, items: np.ndarray):
    """Positions, velocities, accelerations (N, n, 2) and K (N, n, 2, M) of points by x item."""
    M = sol.q.shape[1]
    xy = np.stack([items, items + 1], axis=-1).ravel()
    N, n = sol.q.shape[0], len(items)
    jets, rates = sol.item_jets(xy), sol.item_rates(xy)
    return (jets[:, :, 0].reshape(N, n, 2), rates[:, :, 0].reshape(N, n, 2),
            rates[:, :, 1].reshape(N, n, 2), jets[:, :, 1:1 + M].reshape(N, n, 2, M))


@dataclass(frozen=True, eq=False)
class Terms:
    """Kane's terms at N samples (see the module docstring); arrays over samples."""

    inertia: np.ndarray        # (N, M) generalised inertia force F*
    applied: np.ndarray        # (N, M) generalised applied force Q of the loads
    mass_matrix: np.ndarray | None   # (N, M, M)
    kinetic: np.ndarray        # (N,) J
    potential: np.ndarray      # (N,) J: gravity and springs
    energy_rate: np.ndarray    # (N,) W: d(kinetic + potential)/dt
    applied_power: np.ndarray  # (N,) W: power of the point forces and torques
    dissipation: np.ndarray    # (N,) W: power lost in the dampers
    forces: np.ndarray         # (N, nf, 2) the point forces' values
    torques: np.ndarray        # (N, nt) the torques' values
    tensions: np.ndarray       # (N, ns) tension of each spring or damper, N
    directions: np.ndarray     # (N, ns, 2) unit vector from the first end to the second
    pair_torques: np.ndarray | None = None   # (N, np) torque of each pair load on its second link
    slide_forces: np.ndarray | None = None   # (N, nq) friction force on each slider, along its axis


def evaluate(system: System, sol: KinematicSolution, t: np.ndarray, *,
             mass_matrix: bool = False, weights: np.ndarray | None = None) -> Terms:
    """Kane's terms at every sample of ``sol`` (times ``t``, shape (N,)); ``weights`` (N, k),
    the masses and moments of inertia of ``system.items`` sample by sample, where they differ
    from the system's (the designs of a sweep)."""
    q, qd = sol.q, sol.qd
    N, M = q.shape
    # every x, y of a mass and every angle of a link with inertia, weighted by m or I
    jets, rates = sol.item_jets(system.items), sol.item_rates(system.items)
    K = jets[:, :, 1:1 + M]
    value, rate, accel = jets[:, :, 0], rates[:, :, 0], rates[:, :, 1]
    if weights is None:
        w, weight = system.weights, system.weight
        inertia = np.einsum("nkm,k,nk->nm", K, w, accel)
        applied = np.einsum("nkm,k->nm", K, weight)
        kinetic = 0.5 * np.einsum("k,nk,nk->n", w, rate, rate)
        potential = -(value @ weight)
        energy_rate = np.einsum("k,nk,nk->n", w, rate, accel) - rate @ weight
        MM = np.einsum("nkm,k,nkl->nml", K, w, K) if mass_matrix else None
    else:
        w, weight = weights, weights * system.gravity_along
        inertia = np.einsum("nkm,nk,nk->nm", K, w, accel)
        applied = np.einsum("nkm,nk->nm", K, weight)
        kinetic = 0.5 * np.einsum("nk,nk,nk->n", w, rate, rate)
        potential = -np.einsum("nk,nk->n", value, weight)
        energy_rate = np.einsum("nk,nk,nk->n", w, rate, accel) - np.einsum("nk,nk->n", rate, weight)
        MM = np.einsum("nkm,nk,nkl->nml", K, w, K) if mass_matrix else None
    applied_power = np.zeros(N)
    loads = system.loads
    forces = np.zeros((N, len(loads.forces), 2))
    if len(loads.forces):
        _, vf, _, Kf = point_block(sol, system.force_items)
        for i, f in enumerate(loads.forces):
            forces[:, i] = f.value(t, q, qd)
        applied = applied + np.einsum("nfim,nfi->nm", Kf, forces)
        applied_power = applied_power + np.einsum("nfi,nfi->n", vf, forces)
    torques = np.zeros((N, len(loads.torques)))
    for i, (tq, (own, other)) in enumerate(zip(loads.torques, system.torque_items)):
        torques[:, i] = tq.value(t, q, qd)
        K = sol.item_jets([own])[:, 0, 1:1 + M]
        w = sol.item_rates([own])[:, 0, 0]
        if other >= 0:
            K = K - sol.item_jets([other])[:, 0, 1:1 + M]
            w = w - sol.item_rates([other])[:, 0, 0]
        applied = applied + K * torques[:, i:i + 1]
        applied_power = applied_power + w * torques[:, i]
    dissipation = np.zeros(N)
    ns = len(system.spring_k)
    tensions, directions = np.zeros((N, ns)), np.zeros((N, ns, 2))
    if ns:
        ra, va, _, Ka = point_block(sol, system.spring_items[:, 0])
        rb, vb, _, Kb = point_block(sol, system.spring_items[:, 1])
        d = rb - ra
        length = np.linalg.norm(d, axis=-1)
        # ends closer than rounding (relative to the mechanism's size) meet: no direction
        meet = length <= 1e-12 * plan(sol.mechanism).scale
        if np.any(meet):
            n, s = np.argwhere(meet)[0]
            raise SingularityError(f"{system.spring_names[s]}: its two ends meet at sample {n} "
                                   f"(q = {np.round(q[n], 6).tolist()}), so the direction of its force "
                                   "is undefined; move an end off the other's path")
        e = d / length[..., None]
        rate = np.einsum("nsi,nsi->ns", e, vb - va)              # dl/dt
        stretch = length - system.spring_l0
        tensions = system.spring_k * stretch + system.spring_c * rate
        directions = e
        dl_dq = np.einsum("nsim,nsi->nsm", Kb - Ka, e)
        applied = applied - np.einsum("ns,nsm->nm", tensions, dl_dq)
        potential = potential + 0.5 * np.einsum("s,ns->n", system.spring_k, stretch ** 2)
        energy_rate = energy_rate + np.einsum("s,ns,ns->n", system.spring_k, stretch, rate)
        dissipation = np.einsum("s,ns->n", system.spring_c, rate ** 2)
    pair_torques = np.zeros((N, len(system.pair_links)))
    if len(system.pair_links):
        # torque on the second link of each pair (the first takes the opposite): friction
        # -F tanh(w / w_s), torsional spring -(k x + T0), torsional damper -c w
        jets = sol.item_jets(system.pair_items.ravel()).reshape(N, -1, 2, jets.shape[-1])
        rel_rates = sol.item_rates(system.pair_items.ravel()).reshape(N, -1, 2, 2)
        K_rel = jets[:, :, 1, 1:1 + M] - jets[:, :, 0, 1:1 + M]
        phi = jets[:, :, 1, 0] - jets[:, :, 0, 0]
        w = rel_rates[:, :, 1, 0] - rel_rates[:, :, 0, 0]
        size, smooth, free, preload = system.pair_values.T
        kind = system.pair_kind
        x = np.mod(phi - free + np.pi, 2 * np.pi) - np.pi     # within half a turn of free
        spring = kind == 1
        pair_torques = np.where(kind == 0, -size * np.tanh(w / smooth),
                                np.where(spring, -(size * x + preload), -size * w))
        applied = applied + np.einsum("npm,np->nm", K_rel, pair_torques)
        potential = potential + np.sum(np.where(spring, 0.5 * size * x ** 2 + preload * x, 0.0), 1)
        energy_rate = energy_rate + np.sum(np.where(spring, -pair_torques * w, 0.0), 1)
        dissipation = dissipation + np.sum(np.where(spring, 0.0, -pair_torques * w), 1)
    slide_forces = np.zeros((N, len(system.slide_joints)))
    if len(system.slide_joints):
        jets = sol.item_jets(system.slide_items)
        sd = sol.item_rates(system.slide_items)[:, :, 0]
        size, smooth = system.slide_values.T
        slide_forces = -size * np.tanh(sd / smooth)
        applied = applied + np.einsum("nqm,nq->nm", jets[:, :, 1:1 + M], slide_forces)
        dissipation = dissipation - np.sum(slide_forces * sd, 1)
    return Terms(inertia=inertia, applied=applied, mass_matrix=MM, kinetic=kinetic,
                 potential=potential, energy_rate=energy_rate, applied_power=applied_power,
                 dissipation=dissipation, forces=forces, torques=torques, tensions=tensions,
                 directions=directions, pair_torques=pair_torques, slide_forces=slide_forces)


def flag(value, name: str) -> bool:
    """``value`` as a bool, or a :class:`ModelError` naming ``name`` unless it is True or
    False (a text such as 'no' would otherwise count as true)."""
    if not isinstance(value, (bool, np.bool_)):
        raise ModelError(f"{name}: expected True or False, got {describe(value)}")
    return bool(value)


def times(t, N: int) -> np.ndarray:
    """``t`` broadcast to (N,), checked finite."""
    a = real_array(t)
    try:
        a = np.broadcast_to(a, (N,)) if a is not None else None
    except ValueError:
        a = None
    if a is None:
        raise ModelError(f"t: expected a time (s) or one per sample, shape () or ({N},), "
                         f"got {describe(t)}")
    if not np.all(np.isfinite(a)):
        raise ModelError("t: expected finite times")
    return np.array(a)
