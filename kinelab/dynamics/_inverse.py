"""Inverse dynamics: actuator efforts (Kane), joint reactions (Newton-Euler), shaking."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.dynamics._loads import Loads, default_carrier
from kinelab.dynamics._masses import MassProperties
from kinelab.dynamics._results import MotionResult
from kinelab.dynamics._terms import System, Terms, build_system, evaluate, flag, point_block, times
from kinelab.errors import ModelError, quoted, shown, suggest
from kinelab.kinematics import KinematicSolution, analyze, plan
from kinelab.kinematics._columns import Columns
from kinelab.model import Mechanism, Units, gear_mesh
from kinelab.model._cams import cam_pair

__all__ = ["inverse", "InverseDynamics", "table_width", "GEAR_PRESSURE_ANGLE"]

GEAR_PRESSURE_ANGLE = math.radians(20.0)
"""The pressure angle of every gear joint's line of action, rad: the standard 20 deg of
involute spur gears (a gear joint declares none)."""


def _pick(names: tuple[str, ...], name: str, kind: str) -> int:
    if name in names:
        return names.index(name)
    raise ModelError(f"{kind}: expected one of {quoted(names)}, got {shown(name)}{suggest(name, names)}")


@dataclass(frozen=True, eq=False)
class InverseDynamics(MotionResult):
    """Actuator efforts, joint reactions and shaking force over a motion.

    Every array has the sample axis first, also for a single configuration (N = 1).

    Attributes
    ----------
    kinematics : KinematicSolution
        The motion the forces were computed for.
    t : ndarray, shape (N,)
        Times the loads were evaluated at, s.
    input_forces : ndarray, shape (N, M)
        Effort of each actuator: a torque (N m) for an angle input, a force (N) along the
        slide for a slide input; it acts on the input's second link and reacts on the first.
    inertia_forces, load_forces : ndarray, shape (N, M)
        The generalised inertia force F* and the generalised force Q of the loads:
        ``input_forces = inertia_forces - load_forces`` (Kane's equations).
    kinetic_energy, potential_energy : ndarray, shape (N,)
        J; the potential is that of gravity (zero at the origin) and of the springs.
    energy_rate : ndarray, shape (N,)
        d(kinetic + potential)/dt, W.
    actuator_power, applied_power, dissipation : ndarray, shape (N,)
        Power of the actuators, of the point forces and torques of the loads, and lost in
        the dampers, W.  ``actuator_power + applied_power = energy_rate + dissipation``.
    shaking_force : ndarray, shape (N, 2)
        Resultant force the mechanism exerts on the ground (through its ground joints,
        the actuators' reactions and springs or dampers anchored to the ground), N.
    shaking_moment : ndarray, shape (N,)
        Its moment about the ground origin, N m (about a point P: subtract
        ``P x shaking_force``).
    joint_names : tuple of str
    reaction_forces : ndarray, shape (N, J, 2), or None
        Force on the second link of each joint from the first, N (prefer :meth:`reactions`).
    reaction_moments : ndarray, shape (N, J), or None
        Moment a prismatic joint transmits to its slider, N m (zero for revolute joints).
    reactions_unique : bool
        False for a mechanism with redundant joints: the reactions shown are then the
        smallest (least-squares) set that balances every link.
    reactions_refused : str or None
        Why the reactions were not computed although asked for (a cam joint whose follower
        oscillates: its contact point is not declared); the efforts are still given.
    """

    kinematics: KinematicSolution
    t: np.ndarray
    input_forces: np.ndarray
    inertia_forces: np.ndarray
    load_forces: np.ndarray
    kinetic_energy: np.ndarray
    potential_energy: np.ndarray
    energy_rate: np.ndarray
    actuator_power: np.ndarray
    applied_power: np.ndarray
    dissipation: np.ndarray
    shaking_force: np.ndarray | None
    shaking_moment: np.ndarray | None
    joint_names: tuple[str, ...]
    reaction_forces: np.ndarray | None
    reaction_moments: np.ndarray | None
    reactions_unique: bool = True
    newton_euler_efforts: np.ndarray | None = None
    reactions_refused: str | None = None

    # -- the motion (t, q, qd, qdd, N: see MotionResult) -----------------------------------
    @property
    def M(self) -> int:
        return self.q.shape[1]

    @property
    def singular(self) -> np.ndarray:
        """(N,) bool: singular configurations, where every force is NaN."""
        return self.kinematics.singular

    # -- accessors ----------------------------------------------------------------------
    def input_force(self, name: str) -> np.ndarray:
        """Effort of one actuator by input name, shape (N,)."""
        return self.input_forces[:, _pick(self.input_names, name, "input")]

    def reactions(self, joint: str) -> np.ndarray:
        """Force on the second link of ``joint`` from the first, N; shape (N, 2).

        For a prismatic joint it is the constraint force, normal to the slide; the effort
        of a slide actuator is in :attr:`input_forces`.
        """
        if self.reactions_refused:
            raise ModelError(self.reactions_refused)
        if self.reaction_forces is None:
            raise ModelError("reactions: this result was computed with reactions=False; "
                             "call inverse(..., reactions=True)")
        return self.reaction_forces[:, _pick(self.joint_names, joint, "joint")]

    def reaction_moment(self, joint: str) -> np.ndarray:
        """Moment on the slider of a prismatic joint from its guide, N m; shape (N,)."""
        if self.reactions_refused:
            raise ModelError(self.reactions_refused)
        if self.reaction_moments is None:
            raise ModelError("reaction_moment: this result was computed with reactions=False")
        return self.reaction_moments[:, _pick(self.joint_names, joint, "joint")]

    # -- export -------------------------------------------------------------------------
    def _columns(self, units: Units) -> Columns:     # table_width counts these
        """Time, inputs, efforts, energies, power, shaking force and moment, and each
        joint's reaction (see :meth:`MotionResult.columns`)."""
        cols = self._motion_columns(units)
        for name, unit, values in (("kinetic_energy", "J", self.kinetic_energy),
                                   ("potential_energy", "J", self.potential_energy),
                                   ("actuator_power", "W", self.actuator_power)):
            cols.add(name, "", unit, values, convert=False)
        if self.shaking_force is not None:
            cols.add("shaking_force", "x", "N", self.shaking_force[:, 0], convert=False)
            cols.add("shaking_force", "y", "N", self.shaking_force[:, 1], convert=False)
            cols.add("shaking_moment", "", "N*m", self.shaking_moment, convert=False)
        if self.reaction_forces is not None:
            for j, name in enumerate(self.joint_names):
                cols.add(name, "reaction.x", "N", self.reaction_forces[:, j, 0], convert=False)
                cols.add(name, "reaction.y", "N", self.reaction_forces[:, j, 1], convert=False)
                if self.mechanism.joint(name).type == "P":
                    cols.add(name, "reaction_moment", "N*m", self.reaction_moments[:, j],
                             convert=False)
        return cols

    def __repr__(self) -> str:
        peak = np.nanmax(np.abs(self.input_forces), axis=0) if self.N else []
        efforts = ", ".join(f"{n}: {p:.4g}" for n, p in zip(self.input_names, peak))
        return f"InverseDynamics('{self.mechanism.name}', N={self.N}, peak |effort| {{{efforts}}})"


def inverse(model, q: ArrayLike, qd: ArrayLike = 0.0, qdd: ArrayLike = 0.0, *,
            loads: Loads | None = None, masses: MassProperties | None = None,
            t: ArrayLike = 0.0, reactions: bool = True) -> InverseDynamics:
    """Actuator efforts that produce a motion, with the joint reactions and shaking force.

    Kane's equations (the notes' ``C^T D f = 0``, *Mecanismos*, eq. 58-66) in the independent
    coordinates q: with K and L from the kinematics engine, the generalised inertia force
    is ``F* = sum K_G^T m a_G + K_theta^T I alpha`` and the loads give ``Q``; the
    actuators supply the rest, ``tau = F* - Q``.  The reactions come from the free-body
    (Newton-Euler) equations of every moving link, solved for all samples at once; they
    give the same efforts, which the tests check.

    Parameters
    ----------
    model : Mechanism
        With mass data on its links (or pass ``masses``).
    q : float or array_like, shape () or (N,); (M,) or (N, M) when M > 1
        Input coordinates, rad or m.
    qd, qdd : float or array_like, broadcast to the shape of q
        Their rates and accelerations.
    loads : Loads, optional
        Gravity, forces, torques, springs and dampers.  Default: those of the model file's
        ``[dynamics]`` section (``model.parameters["dynamics"]``), else none.
    masses : MassProperties, optional
        Default: the links' mass data, with the ``[dynamics]`` section's massless links and
        point masses; every moving link needs mass data.
    t : float or array_like, shape () or (N,)
        Time of each sample, s, for loads that depend on time (default 0).
    reactions : bool
        Also solve for the joint reactions and the shaking force (default True).

    Returns
    -------
    InverseDynamics
        ``input_forces`` (N, M), ``reactions(joint)`` (N, 2), ``shaking_force`` (N, 2) ...
        At singular configurations (``kinematics.singular``) the forces are NaN.

    Raises
    ------
    ModelError
        Missing or invalid mass data, a load naming an unknown point or link.

    References
    ----------
    *Mecanismos*, §5 (Gibbs-Appell / Kane); Kane and Levinson, *Dynamics: Theory and
    Applications* (1985), ch. 6.

    Examples
    --------
    A pendulum held still at angle theta needs ``tau = m g L cos(theta)`` (*Mecanismos*, §5):

    >>> from kinelab.model import Mechanism, Point, Link, Joint, Input
    >>> from kinelab.dynamics import Loads, inverse
    >>> pendulum = Mechanism("pendulum", (Point("O", 0, 0), Point("G", 0.5, 0)),
    ...     (Link("ground", ("O",), ground=True),
    ...      Link("arm", ("O", "G"), mass=2.0, center_of_mass="G", inertia=0.01)),
    ...     (Joint("pivot", "R", ("ground", "arm"), point="O"),), (Input(joint="pivot"),))
    >>> res = inverse(pendulum, q=[0.0, np.pi / 3], loads=Loads(gravity=(0.0, -10.0)))
    >>> res.input_forces                       # 2 kg * 10 m/s^2 * 0.5 m * cos(theta)
    array([[10.],
           [ 5.]])
    >>> res.reactions("pivot")                 # the pivot carries the weight
    array([[ 0., 20.],
           [ 0., 20.]])
    """
    reactions = flag(reactions, "reactions")
    system = build_system(model, loads, masses)
    refused = reactions_refused(model) if reactions else None
    reactions = reactions and refused is None
    sol = analyze(model, q, qd, qdd)
    if sol.N == 0:
        raise ModelError("q: expected at least one configuration, got none; give q as a number "
                         "or an array of shape (N,) or (N, M) with N >= 1")
    tt = times(t, sol.N)
    with np.errstate(over="ignore", invalid="ignore"):      # overflow is reported below
        terms = evaluate(system, sol, tt)
        tau = terms.inertia - terms.applied
        power = np.einsum("nm,nm->n", tau, sol.qd)
        ne = newton_euler(system, sol, terms) if reactions else None
    _check_finite(model, sol, tt, (tau, power, terms.kinetic, terms.potential, terms.energy_rate,
                                   terms.applied_power, terms.dissipation)
                  + ((ne["forces"], ne["shaking_force"], ne["shaking_moment"]) if ne else ()))
    return InverseDynamics(
        kinematics=sol, t=tt, input_forces=tau, inertia_forces=terms.inertia,
        load_forces=terms.applied, kinetic_energy=terms.kinetic,
        potential_energy=terms.potential, energy_rate=terms.energy_rate,
        actuator_power=power, applied_power=terms.applied_power,
        dissipation=terms.dissipation,
        shaking_force=ne["shaking_force"] if ne else None,
        shaking_moment=ne["shaking_moment"] if ne else None,
        joint_names=model.joint_names,
        reaction_forces=ne["forces"] if ne else None,
        reaction_moments=ne["moments"] if ne else None,
        reactions_unique=ne["unique"] if ne else True,
        newton_euler_efforts=ne["efforts"] if ne else None, reactions_refused=refused)


def reactions_refused(model: Mechanism) -> str | None:
    """Why the joint reactions of ``model`` cannot be computed, or None: a cam joint whose
    follower oscillates (a C joint declares no contact point, and an oscillating follower
    has no joint point to stand for its knife edge or roller centre)."""
    rocking = [j.name for j in model.joints if j.type == "C"
               and cam_pair(model, j).motion == "oscillating"]
    if rocking:
        return (f"reactions: cam joint(s) {', '.join(map(repr, rocking))} drive an oscillating "
                "follower, whose contact point is not declared, so the contact force and the "
                "joint reactions are not computed (the efforts are); use a translating follower "
                "or inverse(..., reactions=False)")
    return None


def _check_finite(model, sol: KinematicSolution, t: np.ndarray, arrays) -> None:
    """Raise when a result is not finite at a sample where the motion is defined (assembled,
    not singular): loads or masses beyond float64, which would otherwise reach a table as
    inf or NaN."""
    defined = np.atleast_1d(sol.assembled & ~sol.singular)
    bad = np.zeros(defined.shape, bool)
    for a in arrays:
        a = np.asarray(a)
        bad |= ~np.isfinite(a.reshape(len(defined), -1)).all(axis=1)
    bad &= defined
    if bad.any():
        i = int(np.argmax(bad))
        q = np.round(np.atleast_2d(sol.q)[i], 6).tolist()
        raise ModelError(f"the efforts of '{model.name}' overflow at t = {t[i]:.6g} s, q = {q}: "
                         "a load, speed or mass is too large for the forces and powers to be "
                         "numbers; check the loads (forces, torques, springs, dampers) and the "
                         "masses")


def _cross(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def newton_euler(system: System, sol: KinematicSolution, terms: Terms) -> dict:
    """Solve the free-body equations of every moving link, for all samples at once.

    Unknowns: at each revolute joint the force (x, y) on its second link; at each
    prismatic joint the normal force and the moment on its slider; each actuator's
    effort.  Equations: force (x, y) and moment balance of each moving link, moments
    about the link's first point.  What the links push on the ground gives the shaking
    force and moment.
    """
    m = system.model
    p = plan(m)
    N = sol.N
    ground = m.ground.name
    moving = [n for n in m.link_names if n != ground]
    row = {n: 3 * i for i, n in enumerate(moving)}
    J = len(m.joints)
    M = system.M
    nu = 2 * J + M
    A = np.zeros((N, 3 * len(moving), nu))
    b = np.zeros((N, 3 * len(moving)))
    G = np.zeros((N, 3, nu))        # force (x, y) and moment about the origin on the ground
    g0 = np.zeros((N, 3))

    def pos(point):
        i = p.point_item[point]
        return sol.item_jets([i, i + 1])[:, :, 0]
    ref = {n: pos(m.link(n).points[0]) for n in moving}

    def on(link, force, at, col=None, moment=None):
        """Add a force (N, 2) at a point (N, 2) and a moment (N,) acting on a link, as
        coefficients of unknown ``col`` or, with col None, as a known load."""
        if link == ground:
            target = (G[:, :, col] if col is not None else g0)
            if force is not None:
                target[:, :2] += force
                target[:, 2] += _cross(at, force)
            if moment is not None:
                target[:, 2] += moment
            return
        r = row[link]
        if col is not None:
            if force is not None:
                A[:, r:r + 2, col] += force
                A[:, r + 2, col] += _cross(at - ref[link], force)
            if moment is not None:
                A[:, r + 2, col] += moment
        else:   # a known load moves to the right-hand side
            if force is not None:
                b[:, r:r + 2] -= force
                b[:, r + 2] -= _cross(at - ref[link], force)
            if moment is not None:
                b[:, r + 2] -= moment

    ones = np.ones(N)
    ex, ey = np.tile([1.0, 0.0], (N, 1)), np.tile([0.0, 1.0], (N, 1))

    def axis(j):
        """A prismatic joint's slide direction, (N, 2) also for a single configuration."""
        return np.reshape(sol.slide_axes(j.name), (N, 2))

    def mesh(j):
        """A gear joint's pitch point (N, 2), the tangent of its pitch circles there (N, 2)
        and the unit vector from gear a's centre to the pitch point (N, 2): the tooth force
        on b is ``F_t t + |F_t| tan(pressure angle) r``, along the line of action."""
        g = gear_mesh(m, j)
        oa = pos(g.centre_a)
        if g.mesh == "rack":
            u = axis(m.joint(g.slide))
            radial = np.stack([u[:, 1], -u[:, 0]], axis=-1)
            return oa + g.k * radial, u, radial
        ob = pos(g.centre_b)
        d = (ob - oa) / np.linalg.norm(ob - oa, axis=-1)[:, None]
        at = (oa - g.k * ob) / (1.0 - g.k)
        radial = d if g.mesh == "external" else -d
        return at, np.stack([-d[:, 1], d[:, 0]], axis=-1), radial

    def contact(j):
        """A cam joint's contact point (N, 2), the follower's knife edge or roller centre: the
        point of its prismatic joint on the guide; and the common normal there (N, 2), at
        right angles to the follower's velocity relative to the cam, pointing away from the
        cam's centre."""
        c = cam_pair(m, j)
        fj, pivot = m.joint(c.follower_joint), m.joint(c.pivot)
        at, centre = pos(fj.point), pos(pivot.point)
        u = axis(fj)
        cam_item, guide_item = p.link_item[c.cam], p.link_item[c.guide]
        jets = sol.item_jets([cam_item, guide_item, p.slide_item[fj.name]])[:, :, 1:1 + M]
        k_theta = jets[:, 0] - jets[:, 1]
        # dS/dtheta of the program: K of the slide over K of the cam's angle on the guide
        slope = (np.einsum("nm,nm->n", jets[:, 2], k_theta)
                 / np.einsum("nm,nm->n", k_theta, k_theta))
        r = at - centre
        d = slope[:, None] * u - np.stack([-r[:, 1], r[:, 0]], axis=-1)
        n = np.stack([-d[:, 1], d[:, 0]], axis=-1) / np.linalg.norm(d, axis=-1)[:, None]
        return at, n * np.sign(np.einsum("ni,ni->n", n, r))[:, None]

    for c, j in enumerate(m.joints):
        a, s = j.links
        if j.type == "G":       # the tooth force, tangential and radial
            at, t, radial = mesh(j)
            on(s, t, at, 2 * c)
            on(a, -t, at, 2 * c)
            on(s, radial, at, 2 * c + 1)
            on(a, -radial, at, 2 * c + 1)
            continue
        if j.type == "C":       # one unknown, the contact force; its second column stays 0
            at, n = contact(j)
            on(s, n, at, 2 * c)
            on(a, -n, at, 2 * c)
            continue
        at = pos(j.point)
        if j.type == "R":
            for k, e in enumerate((ex, ey)):
                on(s, e, at, 2 * c + k)
                on(a, -e, at, 2 * c + k)
        else:
            u = axis(j)
            n = np.stack([-u[:, 1], u[:, 0]], axis=-1)
            on(s, n, at, 2 * c)
            on(a, -n, at, 2 * c)
            on(s, None, at, 2 * c + 1, ones)
            on(a, None, at, 2 * c + 1, -ones)
    for k, inp in enumerate(m.inputs):
        col = 2 * J + k
        if inp.joint is not None and m.joint(inp.joint).type == "P":
            j = m.joint(inp.joint)
            u = axis(j)
            at = pos(j.point)
            on(j.links[1], u, at, col)
            on(j.links[0], -u, at, col)
        else:
            a, s = m.joint(inp.joint).links if inp.joint is not None else inp.links
            on(s, None, None, col, ones)
            on(a, None, None, col, -ones)
    # inertia and gravity of every mass, on the link that carries it
    r, v, acc, _ = point_block(sol, system.t_items)
    for i, (link, mass) in enumerate(zip(system.t_links, system.t_mass)):
        if link == ground:
            continue
        rr = row[link]
        b[:, rr:rr + 2] += mass * acc[:, i]
        b[:, rr + 2] += _cross(r[:, i] - ref[link], mass * acc[:, i])
        on(link, mass * np.broadcast_to(system.gravity, (N, 2)), r[:, i])
    li = {item: name for name, item in p.link_item.items()}
    for item, inertia in zip(system.r_items, system.r_inertia):
        b[:, row[li[item]] + 2] += inertia * sol.item_rates([item])[:, 0, 1]
    # loads
    loads = system.loads
    for i, f in enumerate(loads.forces):
        link = default_carrier(m, f.point, f.link)
        if link != ground:     # a force on the ground itself does not load the linkage
            on(link, terms.forces[:, i], pos(f.point))
    for i, tq in enumerate(loads.torques):
        if tq.link != ground:
            on(tq.link, None, None, None, terms.torques[:, i])
        if tq.reacting is not None:
            on(tq.reacting, None, None, None, -terms.torques[:, i])
    for i, s in enumerate(tuple(loads.springs) + tuple(loads.dampers)):
        pull = terms.tensions[:, i, None] * terms.directions[:, i]     # on the first end
        for end, sign in ((0, 1.0), (1, -1.0)):
            link = default_carrier(m, s.points[end], s.links[end])
            on(link, sign * pull, pos(s.points[end]))
    for i, (a, s) in enumerate(system.pair_links):     # friction, torsional springs, dampers
        on(s, None, None, None, terms.pair_torques[:, i])
        on(a, None, None, None, -terms.pair_torques[:, i])
    for i, name in enumerate(system.slide_joints):
        j = m.joint(name)
        force = terms.slide_forces[:, i, None] * axis(j)
        on(j.links[1], force, pos(j.point))
        on(j.links[0], -force, pos(j.point))
    # a gear joint's radial force is tan(pressure angle) times the size of its tangential
    # one, pushing the gears apart: a row of its own says so, with the tangential force's
    # sign from a first solution (a cam joint's second column is no force: its row keeps it 0)
    pairs = [c for c, j in enumerate(m.joints) if j.type in ("G", "C")]
    slope = np.array([math.tan(GEAR_PRESSURE_ANGLE) if m.joints[c].type == "G" else 0.0
                      for c in pairs])
    if pairs:
        extra = np.zeros((N, len(pairs), nu))
        extra[:, np.arange(len(pairs)), 2 * np.array(pairs) + 1] = 1.0
        A = np.concatenate([A, extra], 1)
        b = np.concatenate([b, np.zeros((N, len(pairs)))], 1)
    # solve every sample at once; singular samples (NaN kinematics) stay NaN
    x = np.full((N, nu), np.nan)
    ok = np.isfinite(b).all(axis=1) & np.isfinite(A).all(axis=(1, 2))
    if not ok.all():            # copy out the finite samples only when there are others
        A, b = A[ok], b[ok]
    unique = A.shape[1] == nu
    if len(A):
        rows = A.shape[1] - len(pairs) + np.arange(len(pairs))
        tangential = 2 * np.array(pairs, np.int64)
        signs = np.zeros((len(A), len(pairs)))
        for _ in range(3):      # the signs settle at once but where a tooth force changes sign
            A[:, rows, tangential] = -slope * signs
            if unique:
                try:
                    xs = np.linalg.solve(A, b[..., None])[..., 0]
                except np.linalg.LinAlgError:
                    unique = False
            if not unique:
                xs = np.einsum("nij,nj->ni", np.linalg.pinv(A), b)
            new = np.sign(xs[:, tangential]) if len(pairs) else signs
            if not slope.any() or np.array_equal(new, signs):
                break
            signs = new
        x[ok] = xs
    shaking = np.einsum("nkc,nc->nk", G, x) + g0
    forces = np.zeros((N, J, 2))
    moments = np.zeros((N, J))
    for c, j in enumerate(m.joints):
        if j.type == "R":
            forces[:, c] = x[:, 2 * c:2 * c + 2]
        elif j.type == "G":
            _, t, radial = mesh(j)
            forces[:, c] = x[:, 2 * c, None] * t + x[:, 2 * c + 1, None] * radial
        elif j.type == "C":
            forces[:, c] = x[:, 2 * c, None] * contact(j)[1]
        else:
            u = axis(j)
            forces[:, c] = x[:, 2 * c, None] * np.stack([-u[:, 1], u[:, 0]], axis=-1)
            moments[:, c] = x[:, 2 * c + 1]
    return dict(forces=forces, moments=moments, efforts=x[:, 2 * J:], unique=unique,
                shaking_force=shaking[:, :2], shaking_moment=shaking[:, 2])


def table_width(model: Mechanism) -> int:
    """The columns of :meth:`InverseDynamics.columns` of ``model`` with shaking and
    reactions, known before the computation: time, each input's q, qd, qdd and effort, two
    energies and the power, the shaking force and moment, and each joint's reaction (and
    the moment of each prismatic joint)."""
    prismatic = sum(j.type == "P" for j in model.joints)
    return 1 + 4 * len(model.inputs) + 3 + 3 + 2 * len(model.joints) + prismatic
