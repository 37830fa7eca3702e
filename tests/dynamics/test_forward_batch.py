"""The compiled forward dynamics against the Python right-hand side, a closed form and
single runs; batches of runs: shapes, equality with single runs, messages."""
import dataclasses

import numpy as np
import pytest
from scipy.special import ellipk

import kinelab as kl
from kinelab._expressions import parse_expression, to_program
from kinelab.dynamics import Damper, Loads, PointForce, Spring, Torque, simulate
from kinelab.dynamics._kernel import run_law
from kinelab.errors import MemoryBudgetError, ModelError, SingularityError
from tests.dynamics.models import engine, fourbar, pendulum, rp_robot

g = (0.0, -9.81)
GAS = "-2000 * exp(-(((q + 2 * pi) % (4 * pi) - 2 * pi - 0.3) ** 2) / 0.2)"
ENGINE_LOADS = Loads(gravity=g, forces=[PointForce("B", (GAS, 0.0), link="slider")])
MOTOR = {"jO2": "20 - 0.2 * qd"}


def as_callable(text):
    """The same law as a Python callable: it runs through solve_ivp, not the kernel."""
    law = parse_expression(text)
    return lambda t, q, qd: law(t, np.reshape(q, (len(t), -1)), np.reshape(qd, (len(t), -1)))


@pytest.mark.parametrize("text", [
    "2 * q + 1", GAS, "20 - 0.2 * qd", "where(t > 0.5, sin(q), cos(qd)) + 3 if q < 1 else -1",
    "clip(q, -0.5, 0.5) * hypot(q, qd) - min(q, qd) + max(t, 0.2) % 0.3",
    "atan2(q, 1 + qd) + tanh(q) * sinh(0.1 * qd) / cosh(q) + sign(q - 0.2) * abs(qd) ** 1.5",
    "exp(-q ** 2) + log(1 + q ** 2) + log10(2 + qd ** 2) + sqrt(1 + t) + floor(3 * q) - ceil(qd)",
    "(q > 0) and not (qd < -1) or (t >= 2) + (q != qd) * (q == q) - (q <= 0.1)",
    "asin(0.5 * sin(q)) + acos(0.5 * cos(qd)) + atan(q) + tan(0.3 * q)",
])
def test_programs_against_the_numpy_expression(text):
    """The stack machine's value of each expression against parse_expression's, at 200
    random states (the same float64 arithmetic: agreement to rounding of libm)."""
    rng = np.random.default_rng(7)
    t, q, qd = rng.uniform(0, 3, 200), rng.uniform(-2, 2, (200, 1)), rng.uniform(-2, 2, (200, 1))
    code, constants = to_program(text, 1)
    stack = np.zeros(len(code))
    got = np.array([run_law(code, constants, 0, len(code), t[i], q[i], qd[i], stack) for i in range(200)])
    np.testing.assert_allclose(got, parse_expression(text)(t, q, qd), rtol=1e-14, atol=1e-14)


def test_program_refuses_names_that_do_not_fit_the_inputs():
    assert to_program("q", 2) is None and to_program("q[2] + 1", 2) is None
    assert to_program("q[1] * qd[0]", 2) is not None


def test_compiled_engine_against_the_python_right_hand_side():
    """The engine's laws as expressions (compiled kernel) and as Python callables
    (solve_ivp): the same DOP853 steps, so the same motion to well below the tolerance."""
    t_eval = np.linspace(0.0, 2.0, 41)
    fast = simulate(engine(), (0.0, 2.0), 0.0, 0.0, inputs=MOTOR, loads=ENGINE_LOADS,
                    rtol=1e-10, atol=1e-12, t_eval=t_eval)
    loads = Loads(gravity=g, forces=[PointForce("B", (as_callable(GAS), 0.0), link="slider")])
    slow = simulate(engine(), (0.0, 2.0), 0.0, 0.0, inputs={"jO2": as_callable(MOTOR["jO2"])},
                    loads=loads, rtol=1e-10, atol=1e-12, t_eval=t_eval)
    assert fast.q[-1, 0] > 10.0                                # it runs several turns
    np.testing.assert_allclose(fast.q, slow.q, rtol=0, atol=1e-8)
    np.testing.assert_allclose(fast.qd, slow.qd, rtol=0, atol=1e-7)
    np.testing.assert_allclose(fast.actuator_work, slow.actuator_work, rtol=1e-8, atol=1e-8)
    np.testing.assert_allclose(fast.applied_work, slow.applied_work, rtol=1e-8, atol=1e-8)
    assert abs(fast.nfev - slow.nfev) <= 0.02 * slow.nfev
    assert fast.energy_error < 1e-8 and slow.energy_error < 1e-8


def test_compiled_two_inputs_with_springs_dampers_and_torques_against_python():
    """Every load the kernel forms (gravity, point force, torque between links, spring,
    damper) on a two-input robot, against the Python right-hand side."""
    m = rp_robot(arm_mass=2.0, gripper_inertia=0.02)
    laws = {"shoulder": "12 * cos(q[0]) + 3 * (0.5 - q[0]) - qd[0] + sin(3 * t)",
            "reach": "9.81 * sin(q[0]) + 20 * (0.6 - q[1]) - 2 * qd[1]"}
    loads = dict(gravity=g, dampers=[Damper(("O", "G2"), damping=1.5)],
                 springs=[Spring(("E", "G2"), stiffness=40.0, free_length=0.1)])
    force, torque = ("0.5 * sin(t)", "-2 * qd[1]"), "0.3 * cos(q[1])"
    fast = simulate(m, (0.0, 1.5), [0.3, 0.6], [0.0, 0.1], inputs=laws, t_eval=np.linspace(0, 1.5, 16),
                    loads=Loads(**loads, forces=[PointForce("G2", force)],
                                torques=[Torque("gripper", torque, reacting="arm")]))
    slow = simulate(m, (0.0, 1.5), [0.3, 0.6], [0.0, 0.1], t_eval=np.linspace(0, 1.5, 16),
                    inputs={k: as_callable(v) for k, v in laws.items()},
                    loads=Loads(**loads, forces=[PointForce("G2", tuple(map(as_callable, force)))],
                                torques=[Torque("gripper", as_callable(torque), reacting="arm")]))
    np.testing.assert_allclose(fast.q, slow.q, rtol=0, atol=1e-9)
    np.testing.assert_allclose(fast.input_forces, slow.input_forces, rtol=1e-7, atol=1e-8)
    for work in ("actuator_work", "applied_work", "dissipated"):
        np.testing.assert_allclose(getattr(fast, work), getattr(slow, work), rtol=1e-7, atol=1e-9)
    assert fast.energy_error < 1e-9


def test_pendulum_period_against_the_elliptic_integral():
    """Released from rest at the horizontal (90 degrees from the bottom), a pendulum of
    moment of inertia I_O about its pivot returns after T = 4 sqrt(I_O / (m g l)) K(sin 45°)."""
    length, mass, inertia = 0.5, 2.0, 0.01
    I_O = inertia + mass * length ** 2
    T = 4 * np.sqrt(I_O / (mass * 9.81 * length)) * ellipk(np.sin(np.pi / 4) ** 2)
    sim = simulate(pendulum(length, mass, inertia), (0.0, 3 * T), 0.0, 0.0, loads=Loads(gravity=g),
                   rtol=1e-10, atol=1e-12, t_eval=[T, 2 * T, 3 * T])
    np.testing.assert_allclose(sim.q[:, 0], 0.0, atol=3e-8)     # rtol 1e-10 over 3 periods
    np.testing.assert_allclose(sim.qd[:, 0], 0.0, atol=3e-7)


def test_tighter_tolerance_converges():
    """The engine's crank angle after 2 s at rtol 1e-8 against rtol 1e-12: within a few
    hundred times the tolerance (the error grows along the run)."""
    t_eval = np.linspace(0.0, 2.0, 11)
    runs = [simulate(engine(), (0.0, 2.0), 0.0, 0.0, inputs=MOTOR, loads=ENGINE_LOADS, rtol=rtol,
                     atol=rtol * 1e-2, t_eval=t_eval) for rtol in (1e-8, 1e-12)]
    error = np.max(np.abs(runs[0].q - runs[1].q))
    assert 1e-12 < error < 1e-6


def test_batch_equals_single_runs():
    """Four initial states in one batch, and each alone: the same kernel and steps."""
    q0 = np.array([[0.0], [0.5], [1.0], [-2.0]])
    qd0 = np.array([[0.0], [10.0], [-5.0], [30.0]])
    t_eval = np.linspace(0.0, 0.5, 11)
    runs = simulate(engine(), (0.0, 0.5), q0, qd0, inputs=MOTOR, loads=ENGINE_LOADS, rtol=1e-9,
                    atol=1e-11, t_eval=t_eval)
    assert runs.q.shape == runs.qd.shape == runs.qdd.shape == (4, 11, 1)
    assert runs.energy.shape == (4, 11) and runs.t.shape == (11,) and len(runs) == 4
    for i in range(4):
        one = simulate(engine(), (0.0, 0.5), q0[i], qd0[i], inputs=MOTOR, loads=ENGINE_LOADS,
                       rtol=1e-9, atol=1e-11, t_eval=t_eval)
        np.testing.assert_allclose(runs.q[i], one.q, rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(runs.qd[i], one.qd, rtol=1e-13, atol=1e-12)
        np.testing.assert_allclose(runs.energy[i], one.energy, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(runs.input_forces[i], one.input_forces, rtol=1e-12, atol=1e-12)
        assert runs.nfev[i] == one.nfev
        np.testing.assert_allclose(runs[i].q, one.q, rtol=0, atol=0)


def test_batch_through_python_equals_single_runs():
    """A Python callable law: the batch runs one solve_ivp per run, the same as alone."""
    motor = {"jO2": lambda t, q, qd: 5.0 - 0.1 * qd}
    q0 = np.array([[0.0], [1.0]])
    runs = simulate(engine(), (0.0, 0.2), q0, 0.0, inputs=motor, t_eval=[0.0, 0.1, 0.2])
    one = simulate(engine(), (0.0, 0.2), q0[1], 0.0, inputs=motor, t_eval=[0.0, 0.1, 0.2])
    np.testing.assert_allclose(runs.q[1], one.q, rtol=0, atol=0)


def test_conservative_batch_keeps_its_energy():
    """Pendulums released from five angles, under gravity only."""
    q0 = np.linspace(-1.0, 0.5, 5)[:, None]
    runs = simulate(pendulum(), (0.0, 3.0), q0, 0.0, loads=Loads(gravity=g), rtol=1e-12, atol=1e-12,
                    t_eval=np.linspace(0, 3, 31))
    swing = np.max(np.abs(runs.kinetic_energy), axis=1)
    assert np.all(swing > 1.0)
    assert np.all(np.max(np.abs(runs.energy - runs.energy[:, :1]), axis=1) < 1e-9 * swing)
    assert np.all(runs.energy_error < 1e-9) and np.all(runs.status == "finished")


def test_batch_of_two_inputs_shapes():
    m = rp_robot(arm_mass=2.0, gripper_inertia=0.02)
    q0 = np.array([[0.3, 0.6], [0.2, 0.5], [0.1, 0.7]])
    runs = simulate(m, (0.0, 0.2), q0, [0.0, 0.0], loads=Loads(gravity=g), t_eval=[0.0, 0.1, 0.2])
    assert runs.q.shape == (3, 3, 2) and runs.input_forces.shape == (3, 3, 2)
    np.testing.assert_allclose(runs.q[:, 0], q0, rtol=0, atol=0)


def test_batch_run_stopped_near_a_singular_configuration():
    """One run of two reaches the limit position: it stops there, NaN after, and says so."""
    from tests.dynamics.test_forward import _with_masses
    m = _with_masses(kl.mechanisms.slider_crank(crank=1.0, rod=0.8))
    runs = simulate(m, (0.0, 5.0), [[0.6], [-0.5]], 0.0, inputs={"jO2": "3 - 30 * qd"},
                    t_eval=np.linspace(0, 5, 51))
    assert list(runs.status) == ["singular", "finished"]
    assert "singular configuration" in runs.message[0]
    assert np.isnan(runs.q[0, -1, 0]) and np.all(np.isfinite(runs.q[1]))
    assert np.all(np.isfinite(runs.energy[1]))


@pytest.mark.parametrize("kw, message", [
    (dict(q0=np.zeros((3, 1)), qd0=np.zeros((2, 1))), r"q0, qd0: expected the same number of runs, got 3 and 2"),
    (dict(q0=np.zeros((3, 2))), r"q0: expected one value per input, shape \(\) or \(1,\), got shape \(3, 2\); for a batch of B runs give shape \(B, 1\)"),
    (dict(q0=np.zeros((3, 1)), t_eval=None), r"t_eval: a batch of 3 runs .* needs output times"),
    (dict(q0=0.0, method="Euler"), r"method: expected one of"),
    (dict(q0=0.0, rtol=-1.0), r"rtol: expected a positive number"),
])
def test_batch_bad_arguments(kw, message):
    kw = {"t_span": (0.0, 1.0), "qd0": 0.0, "t_eval": [0.0, 1.0], **kw}
    with pytest.raises(ModelError, match=message):
        simulate(engine(), inputs=MOTOR, **kw)


def test_compiled_failure_names_the_run():
    """A slider-crank driven into its limit position with no stop before it: the kernel
    halts at the stage the kinematics flags singular, and the message is the Python
    path's, with the run."""
    from tests.dynamics.test_forward import _with_masses
    m = _with_masses(kl.mechanisms.slider_crank(crank=1.0, rod=0.8))
    with pytest.raises(SingularityError, match=r"singular configuration at t = .* s \(run 1\)"):
        simulate(m, (0.0, 5.0), [[-0.5], [0.3]], [[0.0], [1.0]], inputs={"jO2": "3 * (q > 0)"},
                 t_eval=[0.0, 5.0], singular_stop=0.0)


def test_law_not_finite_in_the_kernel_is_reported_by_the_law():
    with pytest.raises(ModelError, match=r"inputs\['jO2'\]: .*gives inf"):
        simulate(engine(), (0.0, 1.0), 0.0, 1.0, inputs={"jO2": "1 / (qd - 1)"}, t_eval=[0.0, 1.0])


def _engines():
    """Three engines of one structure: crank length, flywheel inertia and piston mass differ."""
    return [engine(), engine(crank=0.06, crank_inertia=0.02), engine(piston_mass=1.5, rod=0.2)]


@pytest.mark.parametrize("motor", [MOTOR, {"jO2": lambda t, q, qd: 20 - 0.2 * qd}],
                         ids=["compiled", "python"])
def test_batch_of_different_models_equals_each_model_alone(motor):
    """A model per run: each run of the batch is the run of its model alone, and keeps
    its mechanism (the runs' motions differ, so each got its own numbers)."""
    models = _engines()
    q0 = np.array([[0.0], [0.5], [1.0]])
    t_eval = np.linspace(0.0, 0.4, 9)
    runs = simulate(models, (0.0, 0.4), q0, 5.0, inputs=motor, loads=ENGINE_LOADS, rtol=1e-9,
                    atol=1e-11, t_eval=t_eval)
    assert runs.q.shape == (3, 9, 1) and runs.mechanisms == tuple(models)
    assert np.all(np.abs(np.diff(runs.q[:, -1, 0])) > 1e-3)
    for i, m in enumerate(models):
        one = simulate(m, (0.0, 0.4), q0[i], 5.0, inputs=motor, loads=ENGINE_LOADS, rtol=1e-9,
                       atol=1e-11, t_eval=t_eval)
        np.testing.assert_array_equal(runs.q[i], one.q)
        np.testing.assert_array_equal(runs.qd[i], one.qd)
        np.testing.assert_allclose(runs.energy[i], one.energy, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(runs.input_forces[i], one.input_forces, rtol=1e-12, atol=1e-12)
        assert runs.nfev[i] == one.nfev and runs[i].mechanism is m
        np.testing.assert_array_equal(runs[i].energy, one.energy)


def test_flywheel_inertia_slows_the_speed_up():
    """The same motor on engines with growing flywheels: less speed gained in 0.5 s, and
    at the start q'' = torque / inertia exactly where the crank angle keeps the piston's
    speed zero (q = 0, from rest)."""
    inertias = np.array([0.004, 0.02, 0.1])
    models = [engine(crank_inertia=j) for j in inertias]
    runs = simulate(models, (0.0, 0.5), 0.0, 0.0, inputs={"jO2": "20"}, rtol=1e-10, atol=1e-12,
                    t_eval=[0.0, 0.5])
    assert np.all(np.diff(runs.qd[:, -1, 0]) < 0)
    for i, m in enumerate(models):
        crank, rod = m.link("crank"), m.link("rod")
        G2, G3 = np.array(m.point("G2").xy), np.array(m.point("G3").xy)
        A, B = np.array(m.point("A").xy), np.array(m.point("B").xy)
        # at q = 0 (dead centre) the piston and rod's translation do not move with q: the
        # inertia is the crank's about O2, plus the rod's turning at rate r/l about B
        r, l = np.linalg.norm(A), np.linalg.norm(B - A)
        rod_G = np.linalg.norm(G3 - B)
        inertia = (crank.inertia + crank.mass * G2 @ G2 + (rod.inertia + rod.mass * rod_G ** 2)
                   * (r / l) ** 2)
        np.testing.assert_allclose(runs.qdd[i, 0, 0], 20.0 / inertia, rtol=1e-9)


def test_batch_of_laws_one_per_run():
    """inputs maps an input to a list of laws: run i gets law i (numbers, expressions)."""
    laws = [5.0, "10", "20 - 0.2 * qd"]
    t_eval = np.linspace(0.0, 0.3, 4)
    runs = simulate(engine(), (0.0, 0.3), 0.0, 1.0, inputs={"jO2": laws}, loads=ENGINE_LOADS,
                    t_eval=t_eval)
    for i, law in enumerate(laws):
        one = simulate(engine(), (0.0, 0.3), 0.0, 1.0, inputs={"jO2": law}, loads=ENGINE_LOADS,
                       t_eval=t_eval)
        np.testing.assert_array_equal(runs.q[i], one.q)
    np.testing.assert_allclose(runs.input_forces[:2, :, 0], [[5.0] * 4, [10.0] * 4], rtol=0, atol=0)


def test_runs_of_different_structures_each_compile_apart():
    """A point mass in one model's [dynamics] section changes what the kernel carries: the
    runs go in two groups, each still equal to its model alone."""
    e = engine()
    lumped = dataclasses.replace(e, parameters={"dynamics": {"point_masses": {"A": 0.5}}})
    models = [e, lumped, engine(crank=0.055)]
    t_eval = [0.0, 0.1, 0.2]
    runs = simulate(models, (0.0, 0.2), 0.3, 2.0, inputs=MOTOR, t_eval=t_eval)
    for i, m in enumerate(models):
        one = simulate(m, (0.0, 0.2), 0.3, 2.0, inputs=MOTOR, t_eval=t_eval)
        np.testing.assert_array_equal(runs.q[i], one.q)


@pytest.mark.parametrize("kw, message", [
    (dict(model=[engine(), engine()], q0=np.zeros((3, 1))),
     r"q0, model: expected the same number of runs, got 3 and 2"),
    (dict(inputs={"jO2": ["1", "2"]}, qd0=np.zeros((3, 1))),
     r"qd0, inputs: expected the same number of runs, got 3 and 2"),
    (dict(inputs={"jO2": ["1", "2"], "x": []}), r"inputs: a list of laws gives one law per run"),
    (dict(model=[]), r"model: expected a kinelab Mechanism, or a non-empty sequence"),
    (dict(model=[engine(), "engine"]), r"model: expected a kinelab Mechanism, or a non-empty sequence"),
    (dict(model=[engine(), pendulum()]), r"model: run 1's mechanism 'pendulum' has the inputs \['pivot'\]"),
    (dict(inputs={"jO2": ["1", "1 +"]}), r"run 1.*inputs\['jO2'\]"),
    (dict(model=[engine(), dataclasses.replace(engine(), parameters={"dynamics": {"massless": ["rod"]}})]),
     r"run 1, mechanism 'engine': .*rod"),
    (dict(model=[engine(), engine()], t_eval=None), r"t_eval: a batch of 2 runs"),
])
def test_batch_of_models_or_laws_bad_arguments(kw, message):
    kw = {"model": engine(), "t_span": (0.0, 1.0), "q0": 0.0, "qd0": 0.0, "t_eval": [0.0, 1.0],
          "inputs": MOTOR, **kw}
    with pytest.raises(ModelError, match=message):
        simulate(**kw)


@pytest.mark.parametrize("method", ["DOP853", "RK45"])
@pytest.mark.parametrize("kw, error, message", [
    (dict(max_step=1e-12), ModelError, r"max_step: 1e-12 s over t_span of 1 s takes more than "
                                       r"max_evaluations = 100,000,000"),
    (dict(max_step=0.0), ModelError, r"max_step: expected a positive number"),
    (dict(max_step=float("nan")), ModelError, r"max_step: expected a positive number"),
    (dict(max_evaluations=0), ModelError, r"max_evaluations: expected a positive whole number"),
    (dict(t_span=(0.0, 1e12), t_eval=[0.0, 1e12], max_evaluations=2000), ModelError,
     r"took max_evaluations evaluations without reaching the end of t_span, at t = "),
    (dict(t_eval=[0.0, float("nan")]), ModelError,
     r"t_eval: expected increasing times within t_span \[0.0, 1.0\] s, all finite"),
    (dict(t_span=(-1e308, 1e308)), ModelError, r"t_span: expected finite start < end"),
    (dict(singular_stop=float("nan")), ModelError, r"singular_stop: expected a number from 0"),
    (dict(singular_stop="x"), ModelError, r"singular_stop: expected a number from 0"),
    (dict(q0=[[0.0], [1.0]], threads=0), ModelError, r"threads: expected a positive whole number"),
    (dict(q0=[[0.0], [1.0]], threads="2"), ModelError, r"threads: expected a positive whole number"),
    (dict(q0=np.zeros((10 ** 5, 1)), t_eval=np.linspace(0.0, 1.0, 10 ** 6)), MemoryBudgetError,
     r"100,000 run\(s\) at 1,000,000 output times would take about [\d.]+ TiB, more than the "
     r"memory budget"),
])
def test_requests_beyond_reach_end_with_a_message(method, kw, error, message):
    """Nothing hangs or runs out of memory: a step too small for t_span, a t_span too long
    for the budget of evaluations, outputs beyond the memory budget."""
    kw = {"t_span": (0.0, 1.0), "q0": 0.5, "t_eval": [0.0, 1.0], **kw}
    with pytest.raises(error, match=message):
        simulate(pendulum(), inputs={"pivot": "-0.1 * qd"}, loads=Loads(gravity=g), method=method, **kw)


def test_a_diverging_motion_is_named_as_such():
    """A law that drives q' past float64 within a step: the state, not the law, is at fault
    (the Python right-hand side meets the infinite state first)."""
    with pytest.raises(ModelError, match=r"diverges: q or q' is no longer finite after t = "):
        simulate(pendulum(), (0.0, 1.0), 0.5, 0.0, inputs={"pivot": "1e300 * exp(qd)"},
                 t_eval=[0.0, 1.0], method="RK45")


def test_a_tolerance_below_rounding_is_raised_to_scipys_floor():
    with pytest.warns(UserWarning, match=r"rtol: 1e-20 is below 100 machine epsilons; using 2.22e-14"):
        sim = simulate(pendulum(), (0.0, 0.1), 0.5, 0.0, loads=Loads(gravity=g), rtol=1e-20,
                       atol=1e-14, t_eval=[0.0, 0.1])
    floor = simulate(pendulum(), (0.0, 0.1), 0.5, 0.0, loads=Loads(gravity=g), rtol=2.220446049250313e-14,
                     atol=1e-14, t_eval=[0.0, 0.1])
    np.testing.assert_array_equal(sim.q, floor.q)


def test_a_tolerance_at_the_floor_warns_once_on_the_solve_ivp_path():
    """The Python path scales rtol for its norm over q and q' alone; at the floor it stays
    at the floor, so that scipy does not raise it again with a warning of its own."""
    import warnings
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        simulate(pendulum(), (0.0, 0.1), 0.5, 0.0, loads=Loads(gravity=g), rtol=1e-20,
                 atol=1e-14, t_eval=[0.0, 0.1], method="RK45")
    assert [str(w.message) for w in caught] == [
        "rtol: 1e-20 is below 100 machine epsilons; using 2.22e-14"]
