"""A mechanism's equations of motion packed for the compiled kernel (``_kernel.py``):
which stored items carry mass and loads, and every law as a program."""
from __future__ import annotations

import numpy as np

from kinelab.dynamics._loads import Law
from kinelab.dynamics._terms import System
from kinelab.kinematics import _codes as kin
from kinelab.kinematics import plan
from kinelab.kinematics._analyze import _branch_map


def compiled_system(system: System, actuators) -> tuple | None:
    """The arrays of the compiled right-hand side of ``system`` under the actuator laws
    ``actuators`` (:func:`actuator_laws`), with the size of its law stack; None when a part
    needs Python: a plan with Newton groups, change points or redundant joints, a law
    given as a table or a Python callable, friction or a torsional spring or damper."""
    model, M = system.model, system.M
    p = plan(model)
    laws = getattr(actuators, "laws", None)
    if system.loads.pair_loads or p.uses_newton or p.redundant or laws is None or _branch_map(p, M, "smooth") is not None:
        return None
    programs: list[tuple[np.ndarray, np.ndarray]] = []

    def index(law: Law | None) -> int:
        if law is None:
            return -1
        program = law.program(M)
        if program is None:
            raise LookupError
        programs.append(program)
        return len(programs) - 1

    loads = system.loads
    try:
        actuator_laws = [index(law) for law in laws]
        force_laws = []
        for f in loads.forces:
            if isinstance(f._law, Law):          # one callable for both components
                return None
            force_laws.append([index(c) for c in f._law])
        torque_laws = [index(tq._law) for tq in loads.torques]
    except LookupError:
        return None
    points = lambda items: [i + d for i in items for d in (0, 1)]   # noqa: E731
    needed = np.concatenate([system.items, points(system.force_items),
                             system.torque_items[system.torque_items >= 0],
                             points(system.spring_items.ravel())]).astype(np.int64)
    stored = np.unique(needed)
    row = {int(item): r for r, item in enumerate(stored)}
    rows = lambda items: np.array([row[int(i)] for i in items], np.int64)   # noqa: E731
    plan_i, plan_f = kin.pack_plan(p.ops_i, p.ops_f, p.const_items, p.const_values, p.n_items,
                                   p.n_angles, stored)
    code = np.concatenate([c for c, _ in programs] or [np.zeros((0, 2), np.int64)])
    code = code.copy()
    starts, offset, at = [0], 0, 0
    for c, constants in programs:                # constant indices become global
        constant_rows = c[:, 0] == 0
        code[at:at + len(c)][constant_rows, 1] += offset
        offset += len(constants)
        at += len(c)
        starts.append(at)
    constants = np.concatenate([k for _, k in programs] or [np.zeros(0)]).astype(np.float64)
    torque_rows = np.array([[row[int(a)], row[int(b)] if b >= 0 else -1]
                            for a, b in system.torque_items], np.int64).reshape(-1, 2)
    packed = (plan_i, plan_f, len(stored), float(p.scale), rows(system.items),
              np.ascontiguousarray(system.weights, float), np.ascontiguousarray(system.weight, float),
              rows(system.force_items), np.array(force_laws, np.int64).reshape(-1, 2),
              torque_rows, np.array(torque_laws, np.int64),
              rows(system.spring_items.ravel()).reshape(-1, 2),
              np.ascontiguousarray(system.spring_k, float), np.ascontiguousarray(system.spring_l0, float),
              np.ascontiguousarray(system.spring_c, float), code.astype(np.int64), constants,
              np.array(starts, np.int64), np.array(actuator_laws, np.int64))
    stack = max([len(c) for c, _ in programs] + [1])
    return packed, stack


# the entries of a packed system that are numbers of one run's model and laws (plan_f, scale,
# masses, weights, springs, law constants): the runs of a batch may differ in them alone
PER_RUN = (1, 3, 5, 6, 12, 13, 14, 16)


def structure(packed: tuple) -> tuple:
    """What runs compiled together must share: every entry of ``packed`` but the numbers
    ``PER_RUN`` (of which only the shapes)."""
    return tuple(np.shape(a) if i in PER_RUN else
                 (a.dtype.str, a.shape, a.tobytes()) if isinstance(a, np.ndarray) else a
                 for i, a in enumerate(packed))


def per_run(packs: list[tuple]) -> tuple:
    """The numbers ``PER_RUN`` of packs of one structure, a row per pack."""
    return tuple(np.ascontiguousarray(np.stack([np.asarray(p[i], np.float64) for p in packs]))
                 for i in PER_RUN)


def work_arrays(packed: tuple, M: int, stack: int) -> tuple:
    """Scratch space of one run (see ``_kernel._rhs``)."""
    ns = packed[2]
    return (np.zeros((3, M)), np.zeros(kin.one_sample_layout(ns, M)[-1]), np.zeros((M, M)),
            np.zeros(M, np.int64), np.zeros(M), np.zeros(stack))


def warm_up(name: str) -> None:
    """Run the compiled forward dynamics once, one run and a batch, with laws written as
    expressions: on a pendulum for ``dynamics_one_input``, on a double pendulum (two
    inputs) for ``dynamics`` (see ``kinelab._compiled``)."""
    from kinelab.dynamics._forward import _integrate_compiled, actuator_laws
    from kinelab.dynamics._loads import Loads
    from kinelab.dynamics._terms import build_system
    from kinelab.model import Input, Joint, Link, Mechanism, Point

    def arm(name, a, b):
        return Link(name, (a, b), mass=1.0, center_of_mass=b, inertia=1e-3)
    model = Mechanism(
        "double pendulum", (Point("O", 0.0, 0.0), Point("A", 1.0, 0.0), Point("B", 2.0, 0.0)),
        (Link("ground", ("O",), ground=True), arm("upper", "O", "A"), arm("lower", "A", "B")),
        (Joint("shoulder", "R", ("ground", "upper"), point="O"),
         Joint("elbow", "R", ("upper", "lower"), point="A")),
        (Input(joint="shoulder"), Input(joint="elbow")))
    if name == "dynamics_one_input":
        model = Mechanism("pendulum", model.points[:2], model.links[:2], model.joints[:1],
                          model.inputs[:1])
    M = len(model.inputs)
    system = build_system(model, Loads(gravity=(0.0, -9.81)), None)
    laws = ["-0.1*qd"] if M == 1 else [f"-0.1*qd[{m}]" for m in range(M)]
    case = (system, actuator_laws(model, dict(zip((j.joint for j in model.inputs), laws))))
    compiled = {id(case): compiled_system(*case)}
    y0 = np.zeros((2, 2 * M + 3))
    y0[:, 0] = 0.5, 0.6
    for runs, t_eval in ((y0[:1], None), (y0, np.array([0.0, 0.01]))):
        _integrate_compiled([case] * len(runs), compiled, runs, (0.0, 0.01), t_eval, 1e-8, 1e-10,
                            np.inf, 1e-6, 10 ** 6, 1, t_eval is not None)
