"""Equations of motion in symbols: against the notes' formulas and against the numbers."""
import numpy as np
import pytest
import sympy as sp

from kinelab.dynamics import (Damper, Loads, MassProperties, PointForce, Spring, Torque,
                              equations_of_motion, inverse)
from kinelab.errors import ModelError
from kinelab.model import Input, Joint, Link, Mechanism, Point
from tests.dynamics.models import engine, pendulum, pr_robot, rp_robot


def test_rp_robot_symbols_are_the_notes_formulas():
    """*Mecanismos*, §5.5, with kinelab's symbols: m_G2 the gripper, g gravity, q2 the reach."""
    m = rp_robot()
    masses = MassProperties.from_model(m, massless=("arm", "gripper"), point_masses={"G2": 2.0})
    eom = equations_of_motion(m, masses=masses, loads=Loads(gravity=(0.0, -9.81)))
    (q1, q2), (u1, u2), (du1, du2) = eom.q, eom.qd, eom.qdd
    m2, g = eom.parameters["m_G2"], eom.parameters["g"]
    notes = [q2 * m2 * (g * sp.cos(q1) + 2 * u1 * u2 + q2 * du1), m2 * (g * sp.sin(q1) + du2 - q2 * u1 ** 2)]
    assert [sp.simplify(a - b) for a, b in zip(eom.input_forces, notes)] == [0, 0]
    assert eom.values[m2] == 2.0 and eom.values[g] == pytest.approx(9.81, abs=1e-15)


def test_pr_robot_symbols_are_the_notes_formulas():
    """*Mecanismos*, §5.6 with symbolic lengths: l_SG is the notes' L."""
    eom = equations_of_motion(pr_robot(), lengths="symbols")
    (q1, q2), (u1, u2), (du1, du2) = eom.q, eom.qd, eom.qdd
    P = eom.parameters
    m1, m2, I2, L = P["m_block"], P["m_arm"], P["I_arm"], P["l_SG"]
    notes = [(m1 + m2) * du1 + m2 * L * (-sp.cos(q2) * u2 ** 2 - sp.sin(q2) * du2),
             m2 * L * (-du1 * sp.sin(q2)) + (m2 * L ** 2 + I2) * du2]
    assert [sp.simplify(a - b) for a, b in zip(eom.input_forces, notes)] == [0, 0]
    assert sp.simplify(eom.mass_matrix - sp.Matrix([[m1 + m2, -m2 * L * sp.sin(q2)],
                                                    [-m2 * L * sp.sin(q2), m2 * L ** 2 + I2]])) == sp.zeros(2, 2)


def double_pendulum():
    return Mechanism(
        "double", (Point("O", 0, 0), Point("A", 0.6, 0.2), Point("G1", 0.3, 0.1), Point("B", 1.0, 0.5),
                   Point("G2", 0.8, 0.4)),
        (Link("ground", ("O",), ground=True),
         Link("upper", ("O", "A", "G1"), mass=2.0, center_of_mass="G1", inertia=0.05),
         Link("lower", ("A", "B", "G2"), mass=1.0, center_of_mass="G2", inertia=0.02)),
        (Joint("shoulder", "R", ("ground", "upper"), point="O"),
         Joint("elbow", "R", ("upper", "lower"), point="A")),
        (Input(joint="shoulder"), Input(joint="elbow")))


def against_inverse(m, loads, lengths):
    eom = equations_of_motion(m, loads=loads, lengths=lengths)
    M = len(m.inputs)
    rng = np.random.default_rng(5)
    q, qd, qdd = (rng.uniform(-2, 2, (20, M)) for _ in range(3))
    t = rng.uniform(0, 3, 20)
    squeeze = (lambda a: a[:, 0]) if M == 1 else (lambda a: a)
    expected = inverse(m, squeeze(q), squeeze(qd), squeeze(qdd), loads=loads, t=t).input_forces
    np.testing.assert_allclose(eom.numeric()(q, qd, qdd, t), expected, rtol=1e-11, atol=1e-11)
    return eom


def test_symbols_against_numbers_with_forces_and_torques():
    loads = Loads(gravity=(0.0, -9.81), forces=[PointForce("B", ("3 * cos(t)", "-q[1]"))],
                  torques=[Torque("lower", "0.5 * qd[1]", reacting="upper")])
    eom = against_inverse(double_pendulum(), loads, "symbols")
    assert r"\ddot{q}_{2}" in eom.latex() and str(eom).startswith("tau_shoulder = ")


def test_symbols_against_numbers_with_springs_and_dampers():
    loads = Loads(gravity=(0.0, -9.81), springs=[Spring(("O", "G"), 40.0, 0.8)],
                  dampers=[Damper(("X", "G"), 1.5)])
    against_inverse(pr_robot(), loads, "numeric")


def test_closed_chains_and_passive_joints_are_refused():
    with pytest.raises(ModelError, match=r"equations_of_motion: joint\(s\) 'jA', 'jB', 'slide' are not "
                                         r"inputs; symbolic equations are derived for open chains"):
        equations_of_motion(engine())


def test_tables_and_callables_have_no_symbolic_form():
    loads = Loads(torques=[Torque("arm", lambda t, q, qd: 0 * t)])
    with pytest.raises(ModelError, match=r"torque on 'arm': a table or a Python callable has no symbolic form"):
        equations_of_motion(pendulum(), loads=loads)
