"""Forward dynamics: the motion of a mechanism under given actuator laws and loads."""
from __future__ import annotations

import dataclasses
import math
import os
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab import _compiled
from kinelab import _memory as memory
from kinelab.dynamics._compiled import compiled_system, per_run, structure, work_arrays
from kinelab.dynamics._loads import Law, Loads
from kinelab.dynamics._masses import MassProperties
from kinelab.dynamics._results import MotionResult
from kinelab.dynamics._terms import System, build_system, evaluate
from kinelab.errors import (AssemblyError, ModelError, SingularityError, check_choice, describe,
                            shown)
from kinelab.kinematics import SINGULAR_TOL, KinematicSolution, analyze, change_points, plan
from kinelab.kinematics._columns import Columns
from kinelab.model import Mechanism, Units, is_real, real, real_array
from kinelab.solvers import wrap_angle

__all__ = ["simulate", "Simulation", "SimulationBatch"]

SINGULAR_STOP = 2 * SINGULAR_TOL   # singularity measure (a sine) at which the integration
                                   # stops: before the kinematics flags the configuration
WAIT_FOR_COMPILED_FROM = 32   # runs of a batch from which it waits for the compiled kernel
MAX_EVALUATIONS = 10 ** 8     # of the equations of motion, per run: minutes compiled, so that a
                              # t_span or max_step beyond reach ends with a message, not a hang
MAX_EVALUATIONS_PYTHON = 10 ** 6   # the same with the right-hand side in Python, 0.3-0.4 ms
                                   # an evaluation: a few minutes (a minute of an engine)
RTOL_FLOOR = 100 * np.finfo(float).eps   # below it rounding swamps the error (scipy's floor)
MAX_THREADS = 1024            # threads a batch may ask for: far beyond any machine's processors
_ACROSS = 0.02         # half-width (rad, or sizes for a slide) of the interval across a change
                       # point over which K and L are interpolated


@dataclass(frozen=True, eq=False)
class Simulation(MotionResult):
    """A motion computed by forward dynamics, with its energy balance.

    Attributes
    ----------
    t : ndarray, shape (N,)
        Output times, s.
    q, qd, qdd : ndarray, shape (N, M)
        Inputs, rates and accelerations.
    input_forces : ndarray, shape (N, M)
        The actuators' efforts that were applied (N m or N).
    kinetic_energy, potential_energy : ndarray, shape (N,)
        J.
    energy : ndarray, shape (N,)
        Mechanical energy, kinetic + potential, J.
    actuator_work, applied_work, dissipated : ndarray, shape (N,)
        Work done since ``t[0]`` by the actuators and by the loads' forces and torques,
        and energy lost in the dampers, J (integrated with the motion).
    energy_balance : ndarray, shape (N,)
        ``energy - energy[0] - actuator_work - applied_work + dissipated``: zero but for
        the integration error, J.
    drift : ndarray, shape (N,)
        Measured violation of the constraints at each output (link lengths and angles,
        slides off their lines), m or rad.  The position problem is solved at every
        step, so this stays at rounding level.
    status : {"finished", "singular"}
        "singular": stopped where the mechanism came within ``singular_stop`` of a
        singular configuration (see ``message``).
    message : str
    nfev : int
        Evaluations of the equations of motion.
    kinematics : KinematicSolution
        Every link and point at the output times.
    """

    t: np.ndarray
    input_forces: np.ndarray
    kinetic_energy: np.ndarray
    potential_energy: np.ndarray
    actuator_work: np.ndarray
    applied_work: np.ndarray
    dissipated: np.ndarray
    drift: np.ndarray
    status: str
    message: str
    nfev: int
    kinematics: KinematicSolution

    @property
    def energy(self) -> np.ndarray:
        return self.kinetic_energy + self.potential_energy

    @property
    def energy_balance(self) -> np.ndarray:
        return self.energy - self.energy[0] - self.actuator_work - self.applied_work + self.dissipated

    @property
    def energy_error(self) -> float:
        """Largest |energy_balance| relative to the largest energy involved (kinetic,
        potential, work or losses)."""
        scale = max(float(np.max(np.abs(a))) for a in (
            self.kinetic_energy, self.potential_energy, self.actuator_work, self.applied_work,
            self.dissipated, [1e-300]))
        return float(np.max(np.abs(self.energy_balance))) / scale

    def _columns(self, units: Units) -> Columns:
        """Time, inputs, efforts and the energy balance (see :meth:`MotionResult.columns`)."""
        cols = self._motion_columns(units)
        for label in ("kinetic_energy", "potential_energy", "energy", "actuator_work",
                      "applied_work", "dissipated", "energy_balance"):
            cols.add(label, "", "J", getattr(self, label), convert=False)
        cols.add("drift", "", None, self.drift)
        return cols

    def __repr__(self) -> str:
        return (f"Simulation('{self.mechanism.name}', t = {self.t[0]:.4g}..{self.t[-1]:.4g} s, "
                f"N={len(self.t)}, {self.status}, energy error {self.energy_error:.2g})")


def actuator_laws(model: Mechanism, inputs) -> Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]:
    """The actuators' efforts as one function ``f(t, q, qd) -> (N, M)``.

    ``inputs`` is None (no actuator), a mapping from input name to law (inputs not named
    are free), a sequence of M laws (None for a free input), or one callable
    ``f(t, q, qd)`` returning every effort, shape (M,) or (N, M).
    """
    names = model.input_names
    M = len(names)
    laws: list[Law | None] = [None] * M
    problems = []
    if callable(inputs) and not isinstance(inputs, (Mapping, Law)):
        def all_at_once(t, q, qd):
            qa, qda = (q[:, 0], qd[:, 0]) if M == 1 else (q, qd)
            out = np.asarray(inputs(t, qa, qda), dtype=float)
            if M == 1 and out.ndim == 1 and out.shape == t.shape:
                out = out[:, None]
            return _finite_efforts(out, t, q)
        return all_at_once
    if isinstance(inputs, Mapping):
        for key, law in inputs.items():
            if key in names:
                try:
                    laws[names.index(key)] = Law(law, f"inputs[{shown(key)}]")
                except ModelError as exc:
                    problems.extend(exc.problems)
            elif key in model.joint_names:
                problems.append(f"inputs: joint {shown(key)} is not an input of '{model.name}', so no actuator "
                                f"can drive it; the inputs are {', '.join(map(repr, names))}; add an input "
                                f"for {shown(key)} to the model, or apply its effort as a load (Torque, PointForce)")
            else:
                problems.append(f"inputs: expected an input name, one of {', '.join(map(repr, names))}, "
                                f"got {shown(key)}")
    elif isinstance(inputs, (list, tuple)):
        if len(inputs) != M:
            problems.append(f"inputs: expected {M} law(s), one per input ({', '.join(map(repr, names))}), "
                            f"got {len(inputs)}")
        for k, law in enumerate(inputs[:M]):
            if law is not None:
                try:
                    laws[k] = Law(law, f"inputs[{k}] ('{names[k]}')")
                except ModelError as exc:
                    problems.extend(exc.problems)
    elif inputs is not None:
        problems.append(f"inputs: expected a mapping from input name to actuator law, a sequence of "
                        f"{M} law(s) or a callable f(t, q, qd), got {type(inputs).__name__}")
    if problems:
        raise ModelError(problems, source=f"mechanism '{model.name}'")

    def by_input(t, q, qd):
        out = np.zeros(q.shape)
        for k, law in enumerate(laws):
            if law is not None:
                out[:, k] = law(t, q, qd)
        return out
    by_input.laws = tuple(laws)        # what the compiled kernel runs as programs
    return by_input


def _finite_efforts(out: np.ndarray, t, q) -> np.ndarray:
    try:
        out = np.broadcast_to(out, q.shape)
    except ValueError:
        raise ModelError(f"inputs: the actuator law returned shape {out.shape}; expected ({q.shape[1]},) "
                         f"or {q.shape}") from None
    if not np.all(np.isfinite(out)):
        i = int(np.argwhere(~np.isfinite(out))[0][0])
        raise ModelError(f"inputs: the actuator law gives {out[i].tolist()} at t = {float(t[i]):.6g} s, "
                         f"q = {np.round(q[i], 6).tolist()}; an effort must be finite there")
    return np.array(out)


def _as_q(a: np.ndarray, M: int) -> np.ndarray:
    return a[:, 0] if M == 1 else a


def across_change_point(model: Mechanism, sol: KinematicSolution) -> KinematicSolution | None:
    """One sample next to a change point (flagged singular) with its K and L on the branch
    it follows, interpolated linearly between two samples a little way either side of it
    (with the sample's own positions); None when no change point is near.

    Near a change point K and L lose accuracy to rounding (see ``SINGULAR_TOL``) and at it
    they are not defined, though the motion is smooth there; an integrator that steps
    across needs finite values, and linear ones are within (0.02 rad)^2 |L'| of the truth.
    """
    if sol.M != 1:
        return None
    q = float(sol.q[0, 0])
    width = _ACROSS * (1.0 if plan(model).input_kinds[0] == "angle" else plan(model).scale)
    near = change_points(model, q - width, q + width)
    if not near:
        return None
    q_star = near[0].q
    for _ in range(4):            # widen until both sides are clear of the flagged interval
        sides = analyze(model, np.array([q_star - width, q_star + width]), unreachable="mask",
                        at_singular="flag")
        if sides.assembled.all() and not sides.singular.any():
            break
        width *= 2
    else:
        return None
    lam = (q - (q_star - width)) / (2 * width)
    jets = sol.stored_jets.copy()
    jets[:, :, 1:] = (1 - lam) * sides.stored_jets[0, :, 1:] + lam * sides.stored_jets[1, :, 1:]
    rates = np.stack([jets[:, :, 1] * sol.qd[:, :1], jets[:, :, 1] * sol.qdd[:, :1]
                      + jets[:, :, 2] * sol.qd[:, :1] ** 2], axis=-1)
    return dataclasses.replace(sol, stored_jets=jets, stored_rates=rates,
                               singular=np.zeros(1, bool))


class _Halt(Exception):
    def __init__(self, t, q, kind):
        super().__init__(kind)
        self.t, self.q, self.kind = t, q, kind


def drift(sol: KinematicSolution) -> np.ndarray:
    """Largest violation of the model's constraints at each sample, m (or rad for angles).

    Measured on the engine's output: every link keeps the distances from its first point
    to the others and the direction of its first two points; every slider keeps its
    point on the guide's line and its angle to the guide.
    """
    m = sol.mechanism
    p = plan(m)
    xy = {pt.name: np.array(pt.xy) for pt in m.points}
    pos = {n: sol.item_jets([i, i + 1])[:, :, 0] for n, i in p.point_item.items()}
    ang = {n: sol.item_jets([i])[:, 0, 0] - p.sketch_angles[i] for n, i in p.link_item.items()}
    worst = np.zeros(sol.N)

    for link in m.links:
        pts = link.points
        for b in pts[1:]:
            d = np.linalg.norm(pos[b] - pos[pts[0]], axis=-1)
            worst = np.maximum(worst, np.abs(d - np.linalg.norm(xy[b] - xy[pts[0]])))
        if len(pts) >= 2:
            v = pos[pts[1]] - pos[pts[0]]
            v0 = xy[pts[1]] - xy[pts[0]]
            turn = np.arctan2(v[:, 1], v[:, 0]) - math.atan2(v0[1], v0[0])
            worst = np.maximum(worst, np.abs(wrap_angle(turn - ang[link.name])))
    for j in m.joints:
        if j.type != "P":
            continue
        g, s = j.links
        worst = np.maximum(worst, np.abs(wrap_angle(ang[s] - ang[g])))
        th = ang[g] + math.atan2(j.axis[1], j.axis[0])
        origin = j.origin or m.link(g).points[0]
        d = pos[j.point] - pos[origin]
        normal = -np.sin(th) * d[:, 0] + np.cos(th) * d[:, 1]
        u0 = np.asarray(j.axis, float) / math.hypot(*j.axis)
        d0 = xy[j.point] - xy[origin]
        worst = np.maximum(worst, np.abs(normal - (-u0[1] * d0[0] + u0[0] * d0[1])))
    return worst


def simulate(model: Mechanism | Sequence[Mechanism], t_span: tuple[float, float], q0: ArrayLike,
             qd0: ArrayLike = 0.0, *,
             inputs=None, loads: Loads | None = None,
             masses: MassProperties | None = None, t_eval: ArrayLike | None = None,
             method: Literal["DOP853", "RK45", "Radau", "LSODA", "BDF"] = "DOP853",
             rtol: float = 1e-10, atol: float = 1e-12, max_step: float = np.inf,
             singular_stop: float = SINGULAR_STOP, threads: int | None = None,
             max_evaluations: int | None = None) -> Simulation | SimulationBatch:
    """Integrate the motion of a mechanism under actuator laws and loads: one run, or a
    batch of runs from different initial states, dimensions, masses or laws.

    The state is the independent coordinates q and their rates; at every evaluation the
    position problem is solved by the kinematics engine (so the loops always close) and
    Kane's equations give ``M(q) q'' = tau + Q - h`` with the mass matrix
    ``M = sum m K_G^T K_G + I K_theta^T K_theta`` and the velocity terms
    ``h = sum m K_G^T (q'^T L_G q') + I K_theta^T (q'^T L_theta q')``.  The actuators'
    work, the loads' work and the dampers' losses are integrated with the motion as
    quadratures that do not steer the step size (the error is measured on q and q'
    only), so the result carries its own energy balance.

    With the default method (DOP853), a model whose kinematics are in closed form and
    whose laws are numbers or expressions is integrated by a compiled kernel (scipy's
    DOP853 algorithm, step for step), a few microseconds per evaluation; a table or a
    Python callable law, a plan with Newton groups or change points, or another method
    uses :func:`scipy.integrate.solve_ivp` with the right-hand side in Python.

    Parameters
    ----------
    model : Mechanism, or a sequence of B of them
        A sequence gives each run of a batch its own mechanism: one structure (points,
        links, joints, inputs), different lengths, masses, inertias or model-file
        ``[dynamics]`` sections, e.g. built by one catalogue function.  Runs whose
        models compile alike go through the compiled kernel together.
    t_span : (float, float)
        Start and end time, s.
    q0, qd0 : float or array_like, shape () or (M,); (B, M) for a batch
        Initial inputs (rad or m) and rates.  Either of shape (B, M) makes a batch of B
        runs (the other broadcast to it), which needs ``t_eval``.
    inputs : mapping of str to law, sequence of laws, or callable, optional
        Actuator effort at each input, by input name: a number, an expression of
        ``t, q, qd``, a table or a callable ``f(t, q, qd)`` (see :class:`Law`); a torque
        for an angle input, a force for a slide; or a *list* of B such laws, one per run
        of a batch.  Inputs not named are free (no effort).
        Also accepted: a sequence of M laws in the order of the inputs (None: free), or
        one callable ``f(t, q, qd)`` returning every effort, shape (M,) or (N, M).
        Default: the model file's ``[dynamics.actuators]``, else every input free.
    loads : Loads, optional
        Default: the model file's ``[dynamics]`` loads, else none.
    masses : MassProperties, optional
        Default: the links' mass data with the ``[dynamics]`` section's massless links and
        point masses.
    t_eval : array_like, shape (N,), optional
        Output times (default: the integrator's steps; required for a batch).
    method : str
        A :func:`scipy.integrate.solve_ivp` method; DOP853 (default) for accuracy, Radau
        or BDF for stiff springs and dampers.
    rtol, atol : float
        Integration tolerances, on q and q': atol in rad (rad/s) for an angle input and in
        sizes of the mechanism (per s) for a slide, so that it means the same whatever the
        unit the mechanism is drawn in.  An rtol below 100 machine epsilons
        (2.2e-14) is raised to it, with a warning, as :func:`scipy.integrate.solve_ivp` does.
    max_step : float
        Largest step, s.
    singular_stop : float
        Stop when the distance from a singular configuration (the kinematics'
        ``singularity``, a sine) falls below this; the result says so.  A change point
        (two assembly modes meeting, e.g. a parallelogram at 180 degrees) is crossed on
        the branch that continues smoothly, as :func:`kinelab.kinematics.analyze` does.
    threads : int, optional
        Threads sharing the runs of a compiled batch (default: one per processor).
    max_evaluations : int, optional
        The most evaluations of the equations of motion a run may take; default 10^8 with
        the compiled kernel (minutes), 10^6 with the right-hand side in Python (0.3-0.4 ms
        each: a few minutes).  After 2000 evaluations a run checks its pace: one
        that at that pace would take more than ten times ``max_evaluations`` to reach the
        end of ``t_span`` stops there, with the estimate; any other stops when it has taken
        ``max_evaluations``.  Either way a ModelError says so.

    Returns
    -------
    Simulation
        For one run: ``t`` (N,), ``q``, ``qd`` (N, M), ``energy`` (N,) ...
    SimulationBatch
        For a batch: ``t`` (N,), ``q``, ``qd`` (B, N, M), ``energy`` (B, N) ...; each
        run as a :class:`Simulation` by ``batch[i]``.

    Raises
    ------
    ModelError
        Bad model data, a law for a joint that is not an input, a mass matrix that
        cannot be inverted (a coordinate without inertia), initial states of shapes that
        do not match, a motion that diverges or needs more than ``max_evaluations``.
    AssemblyError
        The motion runs into a position where the loops cannot close.

    Examples
    --------
    A pendulum released from rest at the horizontal swings to the other side:

    >>> from kinelab.model import Mechanism, Point, Link, Joint, Input
    >>> from kinelab.dynamics import Loads, simulate
    >>> pendulum = Mechanism("pendulum", (Point("O", 0, 0), Point("G", 1.0, 0)),
    ...     (Link("ground", ("O",), ground=True),
    ...      Link("arm", ("O", "G"), mass=1.0, center_of_mass="G", inertia=1e-3)),
    ...     (Joint("pivot", "R", ("ground", "arm"), point="O"),), (Input(joint="pivot"),))
    >>> sim = simulate(pendulum, (0.0, 1.0), q0=0.0, qd0=0.0,
    ...                loads=Loads(gravity=(0.0, -9.81)), t_eval=[0.0, 0.5, 1.0])
    >>> sim.q.shape, bool(sim.q[-1, 0] < 0), sim.energy_error < 1e-9
    ((3, 1), True, True)

    Released from three angles at once, one batch:

    >>> runs = simulate(pendulum, (0.0, 1.0), q0=[[0.0], [-0.5], [-1.0]], qd0=0.0,
    ...                 loads=Loads(gravity=(0.0, -9.81)), t_eval=[0.0, 0.5, 1.0])
    >>> runs.q.shape, runs.energy.shape
    ((3, 3, 1), (3, 3))
    >>> bool(abs(runs.q[0, -1, 0] - sim.q[-1, 0]) < 1e-12)
    True

    Three arms of different masses, and three motor laws, one run each:

    >>> import dataclasses
    >>> arms = [dataclasses.replace(pendulum, links=(pendulum.links[0],
    ...         dataclasses.replace(pendulum.links[1], mass=m))) for m in (1.0, 2.0, 4.0)]
    >>> runs = simulate(arms, (0.0, 1.0), q0=0.0, inputs={"pivot": ["1", "2", "4"]},
    ...                 loads=Loads(gravity=(0.0, -9.81)), t_eval=[0.0, 0.5, 1.0])
    >>> runs.q.shape, [m.links[1].mass for m in runs.mechanisms]
    ((3, 3, 1), [1.0, 2.0, 4.0])
    """
    models = _run_models(model)
    run_inputs = _run_inputs(inputs)
    first = _case(models[0], run_inputs[0] if run_inputs else inputs, loads, masses)
    M = first[0].M
    ends = ([real(v) for v in t_span] if isinstance(t_span, (Sequence, np.ndarray))
            and not isinstance(t_span, str) and len(t_span) == 2 else None)
    if ends is None:
        raise ModelError(f"t_span: expected (start, end) in s, got {describe(t_span)}")
    t0, t1 = ends
    if not (t0 is not None and t1 is not None and t1 > t0 and math.isfinite(t1 - t0)):
        raise ModelError(f"t_span: expected finite start < end, got {describe(t_span)}")
    counts = {name: len(v) for name, v in (("model", models), ("inputs", run_inputs)) if len(v) > 1}
    q_init, qd_init, batch = _initial_states(q0, qd0, M, counts)
    B = len(q_init)
    if t_eval is not None:
        given, t_eval = t_eval, real_array(t_eval)
        if t_eval is None or t_eval.ndim != 1:
            raise ModelError(f"t_eval: expected output times in s, shape (N,), got "
                             f"{describe(given)}")
        if (t_eval.size == 0 or not np.all(np.isfinite(t_eval)) or np.any(t_eval < t0)
                or np.any(t_eval > t1) or np.any(np.diff(t_eval) <= 0)):
            raise ModelError(f"t_eval: expected increasing times within t_span [{t0}, {t1}] s, all finite")
    elif batch:
        raise ModelError(f"t_eval: a batch of {B} runs (q0, qd0 of shape (B, M), or a model or "
                         "law per run) needs output times shared by every run; give t_eval")
    if t_eval is not None:      # the states, efforts and energies at every output of every run
        memory.require(8 * B * len(t_eval) * (3 * (2 * M + 3) + 4 * M + 6),
                       f"{B:,} run(s) at {len(t_eval):,} output times", "give fewer output times "
                       "(t_eval), or split the runs into several batches")
    check_choice("method", method, ("DOP853", "RK45", "Radau", "LSODA", "BDF"))
    for name, v, high in (("rtol", rtol, 1.0), ("atol", atol, math.inf)):
        if not (is_real(v) and 0 < v < high):
            below = "" if high == math.inf else f" below {high:g} (a relative error of 100 %)"
            raise ModelError(f"{name}: expected a positive number{below}, got {describe(v)}")
    if rtol < RTOL_FLOOR:
        warnings.warn(f"rtol: {rtol:g} is below 100 machine epsilons; using {RTOL_FLOOR:.3g}",
                      stacklevel=2)
        rtol = RTOL_FLOOR
    if not (isinstance(singular_stop, (int, float)) and 0 <= singular_stop < 1):
        raise ModelError(f"singular_stop: expected a number from 0 (no stop) to below 1 (a sine), "
                         f"got {describe(singular_stop)}")
    if threads is not None and not (isinstance(threads, (int, np.integer))
                                    and not isinstance(threads, bool) and 0 < threads <= MAX_THREADS):
        raise ModelError(f"threads: expected a positive whole number up to {MAX_THREADS} or None "
                         f"(one per processor), got {describe(threads)}")
    if not ((is_real(max_step) or max_step == math.inf) and max_step > 0):        # inf allowed
        raise ModelError(f"max_step: expected a positive number of s (or inf), got {describe(max_step)}")
    if max_evaluations is not None and not (
            isinstance(max_evaluations, (int, np.integer)) and not isinstance(max_evaluations, bool)
            and max_evaluations > 0):
        raise ModelError(f"max_evaluations: expected a positive whole number or None (the "
                         f"default), got {describe(max_evaluations)}")
    most = MAX_EVALUATIONS if max_evaluations is None else int(max_evaluations)
    if (t1 - t0) / max_step > most:
        raise ModelError(f"max_step: {max_step:g} s over t_span of {t1 - t0:g} s takes more than "
                         f"max_evaluations = {most:,} evaluations; raise max_step, "
                         "shorten t_span or raise max_evaluations")
    cases = _run_cases(models, run_inputs, inputs, loads, masses, B, first)
    # the compiled kernel once it is ready in this process (see kinelab._compiled); a large
    # batch waits for it, as its runs in Python would take far longer than compiling
    compilable = None
    if method == "DOP853":
        distinct = {id(case): case for case in cases}
        compilable = {key: compiled_system(*case) for key, case in distinct.items()}
        if any(c is None for c in compilable.values()):
            compilable = None
    large = batch and B >= WAIT_FOR_COMPILED_FROM
    entry = "dynamics_one_input" if M == 1 else "dynamics"
    compiled = compilable if compilable is not None and (
        _compiled.ready(entry) or (large and _compiled.wait_for(entry))) else None
    y0 = np.concatenate([q_init, qd_init, np.zeros((B, 3))], axis=1)

    def integrate() -> list:
        most = max_evaluations or (MAX_EVALUATIONS if compiled is not None
                                   else MAX_EVALUATIONS_PYTHON)
        try:
            if compiled is not None:
                return _integrate_compiled(cases, compiled, y0, (t0, t1), t_eval, rtol, atol,
                                           max_step, singular_stop, most, threads, batch)
            return [_integrate_scipy(*case, y, (t0, t1), t_eval, method, rtol, atol, max_step,
                                     singular_stop, most, f" (run {i})" if batch else "")
                    for i, (case, y) in enumerate(zip(cases, y0))]
        except _OverBudget as over:
            over.budget = most
            raise
    # A run checks its pace after 2000 evaluations (PACE_CHECK): one that at that pace would
    # take ten times its budget (PACE_MARGIN) to reach the end of t_span is refused then, not
    # after minutes or hours.
    try:
        runs = integrate()
    except _OverBudget as over:
        if (over.early and compiled is None and compilable is not None
                and _compiled.wait_for(entry)):
            compiled = compilable     # too long in Python: compiling first is the shorter way
            try:
                runs = integrate()
            except _OverBudget as again:
                raise again.error(t0, t1, max_evaluations is None, True) from None
        else:
            raise over.error(t0, t1, max_evaluations is None, compiled is not None) from None
    if not batch:
        t, y, status, message, nfev = runs[0]
        return _simulation(*cases[0], t, y, status, message, nfev)
    return _batch(cases, t_eval, runs)


def _run_models(model) -> tuple:
    """The mechanism of every run: (model,) for one shared, else one per run."""
    if isinstance(model, Mechanism):
        return (model,)
    if isinstance(model, (list, tuple)) and model and all(isinstance(m, Mechanism) for m in model):
        return tuple(model)
    raise ModelError(f"model: expected a kinelab Mechanism, or a non-empty sequence of them (one "
                     f"per run of a batch), got {describe(model)}")


def _run_inputs(inputs) -> tuple:
    """The actuator laws of each run when ``inputs`` maps an input to a list of laws, one
    per run (a list is not a law, so this reads unambiguously); else ()."""
    if not isinstance(inputs, Mapping):
        return ()
    lists = {k: v for k, v in inputs.items() if isinstance(v, (list, tuple))}
    if not lists:
        return ()
    sizes = {len(v) for v in lists.values()}
    if len(sizes) > 1 or 0 in sizes:
        raise ModelError("inputs: a list of laws gives one law per run of a batch, and every list "
                         "must have the same, non-zero length; got lengths "
                         f"{', '.join(f'{shown(k)}: {len(v)}' for k, v in lists.items())}")
    B = sizes.pop()
    return tuple({k: (v[i] if k in lists else v) for k, v in inputs.items()} for i in range(B))


def _case(model: Mechanism, inputs, loads, masses) -> tuple[System, Any]:
    """One run's equations: its system (masses and loads) and actuator laws; without laws,
    the model file's ``[dynamics]`` section gives them, and the loads and masses not given."""
    if inputs is None:
        from kinelab.dynamics._setup import DynamicsSetup
        setup = DynamicsSetup.from_model(model)
        inputs = setup.inputs() or None
        loads = setup.loads if loads is None else loads
        masses = setup.masses(model) if masses is None else masses
    return build_system(model, loads, masses), actuator_laws(model, inputs)


def _run_cases(models: tuple, run_inputs: tuple, inputs, loads, masses, B: int, first) -> list:
    """Every run's (system, actuators): one shared object where runs share model and laws."""
    if len(models) == 1 and not run_inputs:
        return [first] * B
    names = models[0].input_names
    cases: list = []
    for i in range(B):
        model = models[i if len(models) > 1 else 0]
        if i and model.input_names != names:
            raise ModelError(f"model: run {i}'s mechanism {shown(model.name)} has the inputs "
                             f"{list(model.input_names)} where run 0's has {list(names)}; the "
                             "runs of a batch share their inputs")
        if i and not run_inputs and model is models[i - 1]:
            cases.append(cases[-1])
            continue
        try:
            cases.append(first if i == 0 else
                         _case(model, run_inputs[i] if run_inputs else inputs, loads, masses))
        except ModelError as exc:
            raise ModelError(exc.problems, source=f"run {i}" + (f", {exc.source}" if exc.source else "")
                             ) from None
    return cases


def _initial_states(q0, qd0, M: int, counts: Mapping[str, int]) -> tuple[np.ndarray, np.ndarray, bool]:
    """q0 and q'0 as (B, M) arrays, and whether they make a batch; ``counts`` gives the
    runs that other arguments ask for (one model or law per run)."""
    q, qd = _values("q0", q0), _values("qd0", qd0)
    batch = q.ndim == 2 or qd.ndim == 2 or bool(counts)
    for name, a in (("q0", q), ("qd0", qd)):
        if not (a.ndim == 0 or a.shape == (M,) or (a.ndim == 2 and a.shape[1] == M and len(a))):
            raise ModelError(f"{name}: expected one value per input, shape () or ({M},), got shape "
                             f"{a.shape}; for a batch of B runs give shape (B, {M})")
    sizes = {**{name: len(a) for name, a in (("q0", q), ("qd0", qd)) if a.ndim == 2}, **counts}
    if len(set(sizes.values())) > 1:
        raise ModelError(f"{', '.join(sizes)}: expected the same number of runs, got "
                         f"{' and '.join(str(n) for n in sizes.values())}; give each as one per run "
                         "(q0, qd0 of shape (B, M)), or shared")
    B = max(sizes.values(), default=1)
    return np.broadcast_to(q, (B, M)).copy(), np.broadcast_to(qd, (B, M)).copy(), batch


def _values(name: str, value) -> np.ndarray:
    a = real_array(value)
    if a is None:
        raise ModelError(f"{name}: expected real numbers, got {describe(value)}")
    if not np.all(np.isfinite(a)):
        raise ModelError(f"{name}: expected finite numbers, got {describe(value)}")
    return a


def _integrate_compiled(cases: list, compiled: dict, y0: np.ndarray, span, t_eval, rtol, atol,
                        max_step, singular_stop, budget, threads, batch: bool) -> list:
    """The runs by the compiled kernel: (t, y, status, message, nfev) each.  The runs of a
    batch go to the kernel in groups of one structure, each run with its own numbers."""
    from concurrent.futures import ThreadPoolExecutor

    from kinelab.dynamics import _kernel

    M = cases[0][0].M
    B, n = y0.shape
    args = (span[0], span[1], np.zeros(0) if t_eval is None else t_eval, float(rtol), float(atol),
            float(max_step), float(singular_stop), int(budget)) + (() if M == 1 else (M,))
    integrate_run, integrate_runs = ((_kernel.integrate_run_one_input,
                                      _kernel.integrate_runs_one_input) if M == 1 else
                                     (_kernel.integrate_run, _kernel.integrate_runs))
    if not batch:
        packed, stack = compiled[id(cases[0])]
        work = work_arrays(packed, M, stack)
        status, nfev, info, t, y = integrate_run(y0[0], *args, packed, work)
        statuses, nfevs, infos, counts, ys = [status], [nfev], [info], [len(t)], [y]
    else:
        t, N = t_eval, len(t_eval)
        ys = np.full((B, N, n), np.nan)
        statuses, nfevs = np.zeros(B, np.int64), np.zeros(B, np.int64)
        infos, counts = np.zeros((B, 2 + n)), np.zeros(B, np.int64)
        groups: dict = {}
        kinds = {key: structure(packed) for key, (packed, _) in compiled.items()}
        for i, case in enumerate(cases):
            groups.setdefault(kinds[id(case)], []).append(i)
        for rows in groups.values():
            rows = np.array(rows)
            shared = all(cases[i] is cases[rows[0]] for i in rows)
            packs = [compiled[id(cases[i])][0] for i in (rows[:1] if shared else rows)]
            packed = compiled[id(cases[rows[0]])][0]
            stack = max(compiled[id(cases[i])][1] for i in rows)
            out = (np.full((len(rows), N, n), np.nan), np.zeros(len(rows), np.int64),
                   np.zeros(len(rows), np.int64), np.zeros((len(rows), 2 + n)),
                   np.zeros(len(rows), np.int64))
            numbers, y_rows = per_run(packs), np.ascontiguousarray(y0[rows])
            chunks = max(1, min(len(rows), threads or os.cpu_count() or 1))
            edges = np.linspace(0, len(rows), chunks + 1).astype(int)

            def part(c):
                integrate_runs(y_rows, *args, packed, numbers, edges[c], edges[c + 1], *out, stack)
            if chunks == 1:
                part(0)
            else:
                with ThreadPoolExecutor(chunks) as pool:
                    list(pool.map(part, range(chunks)))
            for whole, part_out in zip((ys, statuses, nfevs, infos, counts), out):
                whole[rows] = part_out
    runs = []
    for i in range(B):
        where = f" (run {i})" if batch else ""
        status, info = int(statuses[i]), infos[i]
        if status not in (_kernel.RUN_FINISHED, _kernel.RUN_SINGULAR):
            _raise_failure(*cases[i], status, info, where, int(nfevs[i]))
        message = "reached the end of t_span"
        if status == _kernel.RUN_SINGULAR:
            message = _stop_message(info[0], info[2:2 + M], singular_stop)
        runs.append((t[:counts[i]], ys[i][:counts[i]], "singular" if status else "finished",
                     message, int(nfevs[i])))
    return runs


def _stop_message(t: float, q, singular_stop: float) -> str:
    return (f"stopped at t = {t:.6g} s: within {singular_stop:g} of a singular configuration "
            f"(q = {np.round(np.asarray(q, float), 6).tolist()})")


def _raise_failure(system: System, actuators, status: int, info: np.ndarray, where: str,
                   used: int):
    """The error of a compiled run that failed, as the Python right-hand side says it."""
    from kinelab.dynamics import _kernel
    model, M = system.model, system.M
    t, q, qd = float(info[0]), info[2:2 + M], info[2 + M:2 + 2 * M]
    if status == _kernel.FAIL_ASSEMBLY:
        raise _halted(model, _Halt(t, q, "assembly"), where)
    if status == _kernel.FAIL_SINGULAR:
        raise _halted(model, _Halt(t, q, "singular"), where)
    if status == _kernel.FAIL_MASS:
        raise _singular_mass(model, q, where)
    if status == _kernel.FAIL_DIVERGED:
        raise _halted(model, _Halt(t, q, "diverged"), where)
    if status in (_kernel.FAIL_BUDGET, _kernel.FAIL_PACE):
        raise _OverBudget(model, _Halt(t, q, "budget"), where, used,
                          early=status == _kernel.FAIL_PACE)
    if status in (_kernel.FAIL_LAW, _kernel.FAIL_SPRING):
        # the same state through Python: its laws and springs say what is wrong
        tt, qq, qqd = np.array([t]), q[None, :], qd[None, :]
        actuators(tt, qq, qqd)
        sol = analyze(model, _as_q(qq, M), _as_q(qqd, M), 0.0, at_singular="flag")
        evaluate(system, sol, tt)
        raise ModelError(f"a law of '{model.name}' is not finite at t = {t:.6g} s{where}, "
                         f"q = {np.round(q, 6).tolist()}, qd = {np.round(qd, 6).tolist()}")
    raise ModelError(f"the integration of '{model.name}' failed at t = {t:.6g} s{where}: the step "
                     "size fell below the resolution of t; try method='Radau' for stiff springs "
                     "or dampers, or looser tolerances")


def _halted(model: Mechanism, h: _Halt, where: str = "") -> Exception:
    at = f"at t = {h.t:.6g} s{where} (q = {np.round(h.q, 6).tolist()})"
    if h.kind == "assembly":
        return AssemblyError(f"the motion of '{model.name}' reaches a position where its loops "
                             f"cannot close {at}: a limit position; limit the motion or check "
                             "the loads")
    if h.kind == "diverged":
        return ModelError(f"the motion of '{model.name}' diverges: q or q' is no longer finite "
                          f"after t = {h.t:.6g} s{where}; check the laws and loads, or the "
                          "tolerances (atol, rtol)")
    if h.kind == "budget":
        return ModelError(f"the motion of '{model.name}' took max_evaluations evaluations "
                          f"without reaching the end of t_span, {at}; shorten t_span, loosen "
                          "rtol and atol, or raise max_evaluations")
    return SingularityError(f"the motion of '{model.name}' reaches a singular configuration {at}; "
                            "raise singular_stop to stop before it")


class _OverBudget(Exception):
    """A run that used its budget of evaluations before the end of t_span (``used`` of
    ``budget``), or that at PACE_CHECK evaluations had gone too short a way to reach it
    (``early``)."""

    def __init__(self, model: Mechanism, halt: _Halt, where: str, used: int, early: bool):
        super().__init__(halt.t)
        self.model, self.halt, self.where, self.used, self.early = model, halt, where, used, early
        self.budget = used

    def error(self, t0: float, t1: float, default: bool, compiled: bool) -> ModelError:
        if not self.early:
            return _halted(self.model, self.halt, self.where)
        reached = float(self.halt.t) - t0     # Python floats: an overflow is inf, silently
        estimate = math.inf if not reached > 0 else self.used * ((t1 - t0) / reached)
        about = "more than 1e308" if math.isinf(estimate) else f"about {estimate:.2g}"
        whose = ("" if not default else " (the default with the compiled kernel)" if compiled
                 else " (the default with the right-hand side in Python)")
        return ModelError(
            f"t_span: the motion of '{self.model.name}' from {t0:g} to {t1:g} s would take "
            f"{about} evaluations of the equations of motion{self.where} (the first "
            f"{self.used:,} reached t = {float(self.halt.t):.6g} s), more than max_evaluations "
            f"= {self.budget:,}{whose}; shorten t_span, loosen rtol and atol, or raise "
            "max_evaluations")


def _singular_mass(model: Mechanism, q, where: str = "") -> ModelError:
    return ModelError(f"the mass matrix of '{model.name}' is singular at q = "
                      f"{np.round(np.asarray(q, float), 6).tolist()}{where}: some input moves no "
                      "mass; give the links it drives mass and inertia")


def _accelerations(system: System, actuators, sol: KinematicSolution, t: np.ndarray, where: str = ""):
    """q'' with the actuators' efforts and Kane's terms at the samples of ``sol``."""
    terms = evaluate(system, sol, t, mass_matrix=True)
    tau = actuators(t, sol.q, sol.qd)
    rhs = tau + terms.applied - terms.inertia     # inertia at qdd = 0 is the bias h
    try:
        qdd = np.linalg.solve(terms.mass_matrix, rhs[..., None])[..., 0]
    except np.linalg.LinAlgError:
        raise _singular_mass(system.model, sol.q[0], where) from None
    return qdd, tau, terms


def _integrate_scipy(system: System, actuators, y0: np.ndarray, span, t_eval, method, rtol, atol,
                     max_step, singular_stop, budget, where: str):
    """One run by :func:`scipy.integrate.solve_ivp` with the right-hand side in Python."""
    from scipy.integrate import solve_ivp

    from kinelab.dynamics._codes import PACE_CHECK, PACE_MARGIN

    t0, t1 = span

    model, M = system.model, system.M
    cache: dict[str, Any] = {}

    def kinematics(t, y):
        key = y[:2 * M].tobytes()
        if cache.get("key") == key:
            return cache["sol"]
        q, qd = y[None, :M], y[None, M:2 * M]
        # Newton groups continue from the last state evaluated: the motion's own branch
        sol = analyze(model, _as_q(q, M), _as_q(qd, M), 0.0, unreachable="mask", at_singular="flag",
                      start=cache.get("sol"))
        if not sol.assembled[0]:
            raise _Halt(t, q[0], "assembly")
        crossing = False
        if sol.singular[0]:
            sol = across_change_point(model, sol)
            if sol is None:
                raise _Halt(t, q[0], "singular")
            crossing = True
        cache.update(key=key, sol=sol, crossing=crossing)
        return sol

    def rhs(t, y):
        cache["evaluations"] = cache.get("evaluations", 0) + 1
        if not np.all(np.isfinite(y[:2 * M])):
            raise _Halt(t, y[:M], "diverged")
        n = cache["evaluations"]
        if n > budget:
            raise _Halt(t, y[:M], "budget")
        if n == PACE_CHECK < budget and (t - t0) * PACE_MARGIN * budget < n * (t1 - t0):
            raise _Halt(t, y[:M], "pace")           # at this pace it would take far too long
        sol = kinematics(t, y)
        qdd, tau, terms = _accelerations(system, actuators, sol, np.array([t]), where)
        return np.concatenate([y[M:2 * M], qdd[0], [tau[0] @ sol.qd[0], terms.applied_power[0],
                                                      terms.dissipation[0]]])

    def near_singular(t, y):
        sol = kinematics(t, y)      # a change point is crossed, not stopped at
        return singular_stop if cache["crossing"] else sol.singularity[0] - singular_stop
    near_singular.terminal = True
    near_singular.direction = -1

    # The works are quadratures: an infinite atol keeps them out of the error norm, and
    # the tolerances of q and q' shrink by sqrt(2M / (2M + 3)) so that solve_ivp's RMS norm
    # over 2M + 3 components equals the norm of q and q' alone (an rtol at the floor stays
    # there: scipy would raise it to the floor with a second warning).
    shrink = math.sqrt(2 * M / (2 * M + 3))
    p = plan(system.model)
    unit = np.array([1.0 if kind == "angle" else p.scale for kind in p.input_kinds] * 2)
    atols = np.concatenate([atol * shrink * unit, np.full(3, np.inf)])
    try:    # a state beyond float64 is reported by rhs (diverged), not by numpy's warnings
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            out = solve_ivp(rhs, span, y0, method=method, t_eval=t_eval, rtol=max(rtol * shrink, RTOL_FLOOR),
                            atol=atols, max_step=max_step,
                            events=near_singular if singular_stop > 0 else None)
    except _Halt as h:
        if h.kind in ("budget", "pace"):
            raise _OverBudget(model, h, where, cache["evaluations"], early=h.kind == "pace") from None
        raise _halted(model, h, where) from None
    if out.status == -1:
        raise ModelError(f"the integration of '{model.name}' failed{where}: {out.message}; try "
                         "method='Radau' for stiff springs or dampers, or looser tolerances")
    status, message = "finished", "reached the end of t_span"
    if out.status == 1:
        status = "singular"
        message = _stop_message(out.t_events[0][0], out.y_events[0][0][:M], singular_stop)
    return out.t, out.y.T, status, message, int(out.nfev)


def _motion(system: System, actuators, t: np.ndarray, y: np.ndarray):
    """The kinematics with accelerations, efforts and Kane's terms along a motion."""
    M = system.M
    q, qd = y[:, :M], y[:, M:2 * M]
    sol = analyze(system.model, _as_q(q, M), _as_q(qd, M), 0.0, at_singular="flag")
    qdd, tau, terms = _accelerations(system, actuators, sol, t)
    sol = analyze(system.model, _as_q(q, M), _as_q(qd, M), _as_q(qdd, M), at_singular="flag")
    return sol, tau, terms


def _simulation(system: System, actuators, t, y, status, message, nfev) -> Simulation:
    sol, tau, terms = _motion(system, actuators, t, y)
    M = system.M
    return Simulation(
        t=t, input_forces=tau, kinetic_energy=terms.kinetic,
        potential_energy=terms.potential, actuator_work=y[:, 2 * M], applied_work=y[:, 2 * M + 1],
        dissipated=y[:, 2 * M + 2], drift=drift(sol), status=status, message=message,
        nfev=nfev, kinematics=sol)


@dataclass(frozen=True, eq=False)
class SimulationBatch:
    """B runs of a mechanism, at shared output times: from different initial states, or
    with a model or actuator laws of their own (one structure, different numbers).

    A run stopped near a singular configuration (``status[i] == "singular"``) has NaN
    after the stop, and its ``message`` says where.

    Attributes
    ----------
    mechanism : Mechanism
        The mechanism of the first run (:attr:`mechanisms`: of each).
    t : ndarray, shape (N,)
        Output times, s.
    q, qd, qdd : ndarray, shape (B, N, M)
        Inputs, rates and accelerations of each run.
    input_forces : ndarray, shape (B, N, M)
        The actuators' efforts, N m or N.
    kinetic_energy, potential_energy, actuator_work, applied_work, dissipated : ndarray, shape (B, N)
        J, as in :class:`Simulation`.
    status : ndarray of str, shape (B,)
        "finished" or "singular".
    message : tuple of str
    nfev : ndarray of int, shape (B,)
        Evaluations of the equations of motion of each run.
    """

    mechanism: Mechanism
    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    input_forces: np.ndarray
    kinetic_energy: np.ndarray
    potential_energy: np.ndarray
    actuator_work: np.ndarray
    applied_work: np.ndarray
    dissipated: np.ndarray
    status: np.ndarray
    message: tuple[str, ...]
    nfev: np.ndarray
    _cases: tuple = dataclasses.field(repr=False)     # each run's (system, actuators)

    @property
    def mechanisms(self) -> tuple[Mechanism, ...]:
        """The mechanism of each run, (B,)."""
        return tuple(system.model for system, _ in self._cases)

    @property
    def energy(self) -> np.ndarray:
        """Mechanical energy of each run, kinetic + potential, J, shape (B, N)."""
        return self.kinetic_energy + self.potential_energy

    @property
    def energy_balance(self) -> np.ndarray:
        """As :attr:`Simulation.energy_balance`, shape (B, N)."""
        return (self.energy - self.energy[:, :1] - self.actuator_work - self.applied_work
                + self.dissipated)

    @property
    def energy_error(self) -> np.ndarray:
        """Each run's largest |energy_balance| relative to the largest energy involved, (B,)."""
        parts = np.stack([self.kinetic_energy, self.potential_energy, self.actuator_work,
                          self.applied_work, self.dissipated])
        scale = np.maximum(np.nanmax(np.abs(parts), axis=(0, 2)), 1e-300)
        return np.nanmax(np.abs(self.energy_balance), axis=1) / scale

    def __len__(self) -> int:
        return self.q.shape[0]

    def __getitem__(self, i: int) -> Simulation:
        """Run i as a :class:`Simulation` (with its kinematics)."""
        n = int(np.sum(np.isfinite(self.q[i, :, 0])))
        y = np.concatenate([self.q[i, :n], self.qd[i, :n], self.actuator_work[i, :n, None],
                            self.applied_work[i, :n, None], self.dissipated[i, :n, None]], axis=1)
        return _simulation(*self._cases[i], self.t[:n], y, str(self.status[i]),
                           self.message[i], int(self.nfev[i]))

    def __repr__(self) -> str:
        return (f"SimulationBatch('{self.mechanism.name}', B={len(self)}, t = {self.t[0]:.4g}.."
                f"{self.t[-1]:.4g} s, N={len(self.t)}, {int(np.sum(self.status == 'finished'))} finished)")


_CHUNK = 50_000      # samples per post-processing pass over a batch: bounded memory


def _batch(cases: list, t_eval: np.ndarray, runs: list) -> SimulationBatch:
    """The runs' outputs as one result: efforts and energies from the kinematics of every
    sample, a chunk of samples of the runs that share a model and laws at a time."""
    M, B, N = cases[0][0].M, len(runs), len(t_eval)
    y = np.full((B, N, 2 * M + 3), np.nan)
    for i, (_, yi, *_rest) in enumerate(runs):
        y[i, :len(yi)] = yi
    valid = np.isfinite(y[:, :, 0]).ravel()
    flat = y.reshape(B * N, -1)
    tt = np.broadcast_to(t_eval, (B, N)).ravel()
    qdd, tau = np.full((B * N, M), np.nan), np.full((B * N, M), np.nan)
    kinetic, potential = np.full(B * N, np.nan), np.full(B * N, np.nan)
    sharing: dict = {}
    for i, case in enumerate(cases):
        sharing.setdefault(id(case), (case, []))[1].append(i)
    for case, members in sharing.values():
        rows = (np.array(members)[:, None] * N + np.arange(N)).ravel()
        rows = rows[valid[rows]]
        for lo in range(0, len(rows), _CHUNK):
            r = rows[lo:lo + _CHUNK]
            sol, tau_r, terms = _motion(*case, tt[r], flat[r])
            qdd[r], tau[r], kinetic[r], potential[r] = sol.qdd, tau_r, terms.kinetic, terms.potential
    shape = (B, N, M)
    return SimulationBatch(
        mechanism=cases[0][0].model, t=t_eval, q=y[:, :, :M], qd=y[:, :, M:2 * M],
        qdd=qdd.reshape(shape), input_forces=tau.reshape(shape),
        kinetic_energy=kinetic.reshape(B, N), potential_energy=potential.reshape(B, N),
        actuator_work=y[:, :, 2 * M], applied_work=y[:, :, 2 * M + 1], dissipated=y[:, :, 2 * M + 2],
        status=np.array([r[2] for r in runs]), message=tuple(r[3] for r in runs),
        nfev=np.array([r[4] for r in runs], np.int64), _cases=tuple(cases))
