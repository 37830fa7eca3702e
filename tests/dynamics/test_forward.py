"""Forward dynamics checked by energy, by inverse dynamics and by finite differences."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.dynamics import Damper, Law, Loads, PointForce, Spring, Torque, inverse, simulate
from kinelab.errors import ModelError
from kinelab.model import Link, Mechanism
from tests.dynamics.models import engine, fourbar, pendulum, rp_robot

g = (0.0, -9.81)


def test_conservative_pendulum_keeps_its_energy_over_10_s():
    """Released at the horizontal, it swings through the bottom for 10 s (about five
    periods); with rtol = atol = 1e-12 the energy holds to 1e-8 of its swing."""
    sim = simulate(pendulum(length=0.5, mass=2.0, inertia=0.01), (0.0, 10.0), q0=0.0, qd0=0.0,
                   loads=Loads(gravity=g), rtol=1e-12, atol=1e-12, t_eval=np.linspace(0, 10, 201))
    swing = np.max(np.abs(sim.kinetic_energy))
    assert swing > 9.0                                   # m g L = 9.81 J at the bottom
    assert np.max(np.abs(sim.energy - sim.energy[0])) < 1e-8 * swing
    assert np.min(sim.q) < -3.1 and sim.status == "finished"


def test_conservative_closed_chain_with_a_spring():
    """A four-bar thrown at 5 rad/s under gravity and a spring from the ground to the coupler."""
    loads = Loads(gravity=g, springs=[Spring(("O4", "P"), stiffness=30.0, free_length=0.1)])
    sim = simulate(fourbar(), (0.0, 1.0), q0=0.3, qd0=5.0, loads=loads, rtol=1e-12, atol=1e-12)
    scale = max(np.max(np.abs(sim.kinetic_energy)), np.max(np.abs(sim.potential_energy)))
    assert np.max(np.abs(sim.energy - sim.energy[0])) < 1e-8 * scale
    assert np.max(sim.drift) < 1e-12                     # positions solved at every step


def driven_rp():
    """The RP robot with arm mass and gripper inertia under state- and time-dependent
    actuator laws, gravity, a damper and an external force."""
    m = rp_robot(arm_mass=2.0, gripper_inertia=0.02)
    laws = {"shoulder": "12 * cos(q[0]) + 3 * (0.5 - q[0]) - qd[0] + sin(3 * t)",
            "reach": lambda t, q, qd: 9.81 * np.sin(q[:, 0]) + 20 * (0.6 - q[:, 1]) - 2 * qd[:, 1]}
    loads = Loads(gravity=g, dampers=[Damper(("O", "G2"), damping=1.5)],
                  forces=[PointForce("E", ("-0.5 * t", 0.3))])
    return m, laws, loads


def test_inverse_of_forward_returns_the_applied_efforts():
    m, laws, loads = driven_rp()
    sim = simulate(m, (0.0, 2.0), q0=[0.1, 0.8], qd0=[0.5, -0.2], inputs=laws, loads=loads,
                   t_eval=np.linspace(0.0, 2.0, 81), rtol=1e-12, atol=1e-12)
    res = inverse(m, sim.q, sim.qd, sim.qdd, loads=loads, t=sim.t)
    scale = np.max(np.abs(sim.input_forces))
    # forward solves M(q) q'' = tau + Q - h; inverse sums K^T m a_G over the bodies
    np.testing.assert_allclose(res.input_forces, sim.input_forces, rtol=0, atol=1e-8 * scale)


def test_accelerations_against_finite_differences_of_the_rates():
    m, laws, loads = driven_rp()
    h = 1e-4
    t = np.sort(np.concatenate([np.linspace(0.2, 1.8, 9) + d for d in (-h, 0.0, h)]))
    sim = simulate(m, (0.0, 2.0), q0=[0.1, 0.8], qd0=[0.5, -0.2], inputs=laws, loads=loads,
                   t_eval=t, rtol=1e-12, atol=1e-12)
    qd = sim.qd.reshape(9, 3, 2)
    fd = (qd[:, 2] - qd[:, 0]) / (2 * h)
    # central difference error h^2 |q''''| / 6 ~ 1e-7 for these motions
    np.testing.assert_allclose(fd, sim.qdd.reshape(9, 3, 2)[:, 1], rtol=0, atol=1e-5)


def test_energy_balance_with_actuators_loads_and_dampers():
    m, laws, loads = driven_rp()
    sim = simulate(m, (0.0, 2.0), q0=[0.1, 0.8], qd0=[0.5, -0.2], inputs=laws, loads=loads,
                   rtol=1e-12, atol=1e-12)
    assert sim.dissipated[-1] > 0.01 and abs(sim.actuator_work[-1]) > 0.1 and abs(sim.applied_work[-1]) > 0.01
    assert sim.energy_error < 1e-8


def test_engine_spins_up_under_a_constant_torque():
    """Beyond a check of numbers: the result carries the kinematics at its output times."""
    m = engine()
    sim = simulate(m, (0.0, 0.3), q0=0.0, qd0=0.0, inputs={"jO2": 5.0},
                   loads=Loads(torques=[Torque("crank", "-0.01 * qd")]), t_eval=np.linspace(0, 0.3, 7))
    assert np.all(np.diff(sim.q[:, 0]) > 0)
    assert sim.kinematics.position("B").shape == (7, 2)
    assert sim.energy_error < 1e-8
    frame = sim.to_dataframe()
    assert {"t[s]", "jO2.torque[N*m]", "energy_balance[J]"} <= set(frame.columns)


def _with_masses(m):
    links = tuple(link if link.ground else Link(link.name, link.points, mass=1.0,
                                                center_of_mass=link.points[-1], inertia=0.1)
                  for link in m.links)
    return Mechanism(m.name, m.points, links, m.joints, m.inputs)


def test_singular_configuration_stops_the_integration():
    """Crank longer than the rod: at sin q = rod / crank the rod stands upright over the
    slide, a limit position (det J = 0) the motion cannot pass."""
    m = _with_masses(kl.mechanisms.slider_crank(crank=1.0, rod=0.8))
    sim = simulate(m, (0.0, 5.0), q0=0.3, qd0=1.0, inputs={"jO2": 3.0})
    assert sim.status == "singular" and "singular configuration" in sim.message
    assert np.sin(sim.q[-1, 0]) == pytest.approx(0.8, abs=1e-3)
    assert sim.t[-1] < 5.0


def test_a_change_point_is_crossed_on_the_smooth_branch():
    """A parallelogram coasting through 180 degrees stays a parallelogram (its rocker turns
    with its crank), and its energy is kept across the change point."""
    m = _with_masses(kl.mechanisms.fourbar(ground=1.0, crank=0.4, coupler=1.0, rocker=0.4))
    sim = simulate(m, (0.0, 1.0), q0=2.5, qd0=3.0, t_eval=np.linspace(0.0, 1.0, 21))
    assert sim.status == "finished"
    assert sim.q[-1, 0] > np.pi + 0.2
    rocker = sim.kinematics.angle("rocker")
    assert np.max(np.abs(np.angle(np.exp(1j * (rocker - sim.q[:, 0]))))) < 1e-9
    assert sim.energy_error < 1e-6


def test_actuator_on_a_joint_that_is_not_an_input():
    with pytest.raises(ModelError, match=r"inputs: joint 'jA' is not an input of 'engine', so no "
                                         r"actuator can drive it; the inputs are 'jO2'"):
        simulate(engine(), (0.0, 1.0), 0.0, inputs={"jA": 1.0})
    with pytest.raises(ModelError, match=r"inputs: expected an input name, one of 'jO2', got 'motor'"):
        simulate(engine(), (0.0, 1.0), 0.0, inputs={"motor": 1.0})


@pytest.mark.parametrize("kw, message", [
    (dict(q0=[0.0, 1.0]), r"q0: expected one value per input, shape \(\) or \(1,\), got shape \(2,\)"),
    (dict(q0=0.0, t_span=(1.0, 0.0)), r"t_span: expected finite start < end"),
    (dict(q0=0.0, t_eval=[0.0, 2.0]), r"t_eval: expected increasing times within t_span"),
    (dict(q0=0.0, inputs={"jO2": "import os"}), r"inputs\['jO2'\]: cannot parse the expression"),
])
def test_bad_arguments(kw, message):
    kw = {"t_span": (0.0, 1.0), **kw}
    with pytest.raises(ModelError, match=message):
        simulate(engine(), **kw)


def test_massless_input_cannot_be_integrated():
    m = rp_robot()           # no mass anywhere
    from kinelab.dynamics import MassProperties
    masses = MassProperties.from_model(m, massless=("arm", "gripper"))
    with pytest.raises(ModelError, match=r"mass matrix of 'rp' is singular"):
        simulate(m, (0.0, 1.0), [0.0, 0.5], masses=masses)


def test_actuator_laws_by_name_by_position_or_all_at_once():
    """Three ways to give the RP robot's efforts describe the same motion."""
    m, laws, loads = driven_rp()
    tau1, tau2 = laws["shoulder"], laws["reach"]
    shoulder = Law(tau1)

    def both(t, q, qd):
        return np.stack([shoulder(t, q, qd), tau2(t, q, qd)], axis=-1)
    runs = [simulate(m, (0.0, 0.5), q0=[0.1, 0.8], qd0=[0.5, -0.2], inputs=form, loads=loads,
                     t_eval=[0.0, 0.25, 0.5]) for form in (laws, [tau1, tau2], both)]
    for r in runs[1:]:
        np.testing.assert_allclose(r.q, runs[0].q, rtol=0, atol=1e-13)
    with pytest.raises(ModelError, match=r"inputs: expected 2 law\(s\), one per input \('shoulder', "
                                         r"'reach'\), got 1"):
        simulate(m, (0.0, 0.5), q0=[0.1, 0.8], inputs=[tau1], loads=loads)
    with pytest.raises(ModelError, match=r"inputs: the actuator law returned shape \(3,\); expected "
                                         r"\(2,\) or \(1, 2\)"):
        simulate(m, (0.0, 0.5), q0=[0.1, 0.8], inputs=lambda t, q, qd: np.zeros(3), loads=loads)
