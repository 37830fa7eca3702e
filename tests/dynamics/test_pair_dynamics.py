"""Dynamics through gear (G) and cam (C) joints, with springs, dampers, Coulomb friction and
torsional springs and dampers in the same model.

A gear or cam pair adds no unknown to Kane's equations: it only shapes K and L, so the
efforts and the motion follow from them as for R and P joints.  Checked here by energy
balances of free motions, the power balance of inverse dynamics, the follower train of
kl.cams.follower_forces, and the Newton-Euler reactions (tooth and contact forces) giving
Kane's efforts back."""
import dataclasses
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.dynamics import (Damper, Friction, Loads, Spring, Torque, TorsionalDamper,
                              TorsionalSpring)
from kinelab.errors import ModelError

EX = Path(__file__).parents[2] / "examples"
TAN20 = np.tan(np.radians(20.0))


def with_masses(m, data):
    """Each named link with (mass, centre of mass, inertia)."""
    return dataclasses.replace(m, links=tuple(
        dataclasses.replace(link, mass=data[link.name][0], center_of_mass=data[link.name][1],
                            inertia=data[link.name][2]) if link.name in data else link
        for link in m.links))


def gear_train():
    return with_masses(kl.load(EX / "gear_train.toml"),
                       {"gear1": (1.0, "O1", 2e-4), "idler": (1.5, "O2", 6e-4),
                        "gear3": (2.0, "O3", 1.5e-3)})


def cam_follower():
    """The cam of examples/cam_follower.toml, a 0.5 kg follower held down by a spring from E
    (on the frame, 80 mm below the follower's foot at S = 0): stiffness 2000 N/m, preload 10 N."""
    m = with_masses(kl.load(EX / "cam_follower.toml"),
                    {"cam": (1.0, "O", 1e-3), "follower": (0.5, "F", None)})
    return m, Spring(("E", "F"), stiffness=2000.0, free_length=0.08 - 10.0 / 2000.0)


def cam_rocker_slider():
    return with_masses(kl.load(EX / "cam_rocker_slider.toml"),
                       {"cam": (1.0, "O", 1e-3), "rocker": (0.4, "B", 2e-3),
                        "coupler": (0.3, "C", 1e-3), "slider": (0.6, "C", None)})


# -- forward: energy balances -------------------------------------------------------------

def test_free_gear_train_with_a_torsional_spring_keeps_its_energy():
    loads = Loads(torsional_springs=[TorsionalSpring(("ground", "gear3"), stiffness=0.5,
                                                     free_angle=0.0, preload=0.02)])
    sim = kl.dynamics.simulate(gear_train(), (0.0, 0.2), 0.0, 2.0, loads=loads,
                               t_eval=np.linspace(0.0, 0.2, 21), rtol=1e-10, atol=1e-12)
    assert sim.status == "finished"
    assert np.ptp(sim.potential_energy) > 0.1 * sim.kinetic_energy[0]    # it does swing
    energy = sim.kinetic_energy + sim.potential_energy
    np.testing.assert_allclose(energy, energy[0], rtol=1e-8)


def test_gear_train_with_a_torsional_damper_loses_the_damper_work():
    c = 2e-3
    loads = Loads(torsional_springs=[TorsionalSpring(("ground", "gear3"), stiffness=0.5)],
                  torsional_dampers=[TorsionalDamper(("idler", "gear1"), damping=c)])
    t = np.linspace(0.0, 0.5, 201)
    sim = kl.dynamics.simulate(gear_train(), (0.0, 0.5), 0.0, 2.0, loads=loads, t_eval=t,
                               rtol=1e-10, atol=1e-12)
    energy = sim.kinetic_energy + sim.potential_energy
    assert energy[0] - energy[-1] > 1e-3 * energy[0]
    np.testing.assert_allclose(energy[0] - energy, sim.dissipated, atol=1e-9 * energy[0])
    # the damper's work: c w^2 integrated, w = omega_gear1 - omega_idler = qd (1 + 2/3)
    w = sim.qd[:, 0] * (1.0 + 20.0 / 30.0)
    from scipy.integrate import cumulative_simpson
    np.testing.assert_allclose(sim.dissipated, cumulative_simpson(c * w ** 2, x=t, initial=0.0),
                               rtol=1e-5, atol=1e-9)


def test_free_cam_follower_with_a_spring_keeps_its_energy():
    m, spring = cam_follower()
    sim = kl.dynamics.simulate(m, (0.0, 0.5), 0.0, 60.0, loads=Loads(springs=[spring]),
                               t_eval=np.linspace(0.0, 0.5, 51), rtol=1e-10, atol=1e-12)
    assert sim.status == "finished" and sim.q[-1, 0] > 2 * np.pi     # a turn and more
    energy = sim.kinetic_energy + sim.potential_energy
    np.testing.assert_allclose(energy, energy[0], rtol=1e-8)


def test_cam_follower_with_a_damper_loses_the_damper_work():
    m, spring = cam_follower()
    loads = Loads(springs=[spring], dampers=[Damper(("E", "F"), damping=5.0)])
    sim = kl.dynamics.simulate(m, (0.0, 0.3), 0.0, 15.0, loads=loads,
                               t_eval=np.linspace(0.0, 0.3, 31), rtol=1e-10, atol=1e-12)
    energy = sim.kinetic_energy + sim.potential_energy
    assert sim.dissipated[-1] > 1e-3 * energy[0]
    np.testing.assert_allclose(energy[0] - energy, sim.dissipated, atol=1e-8 * energy[0])


def test_friction_work_is_the_energy_lost():
    """Coulomb friction at a revolute joint of the gear train and at the cam follower's
    guide: what the motion loses is what friction dissipates, f |w| away from rest."""
    loads = Loads(torsional_springs=[TorsionalSpring(("ground", "gear3"), stiffness=0.5)],
                  friction=[Friction("jO2", 2e-3, smoothing=1e-3)])
    t = np.linspace(0.0, 0.4, 161)
    sim = kl.dynamics.simulate(gear_train(), (0.0, 0.4), 0.0, 2.0, loads=loads, t_eval=t,
                               rtol=1e-10, atol=1e-12)
    energy = sim.kinetic_energy + sim.potential_energy
    assert energy[0] - energy[-1] > 1e-3 * energy[0]
    np.testing.assert_allclose(energy[0] - energy, sim.dissipated, atol=1e-8 * energy[0])
    w = sim.qd[:, 0] * 20.0 / 30.0                     # the idler's speed on its pin
    friction_power = 2e-3 * w * np.tanh(w / 1e-3)
    from scipy.integrate import cumulative_simpson
    np.testing.assert_allclose(sim.dissipated, cumulative_simpson(friction_power, x=t, initial=0.0),
                               rtol=1e-4, atol=1e-8)
    m, spring = cam_follower()
    loads = Loads(springs=[spring], friction=[Friction("guide", 0.5)])
    sim = kl.dynamics.simulate(m, (0.0, 0.2), 0.0, 15.0, loads=loads,
                               t_eval=np.linspace(0.0, 0.2, 21), rtol=1e-10, atol=1e-12)
    energy = sim.kinetic_energy + sim.potential_energy
    assert sim.dissipated[-1] > 1e-3 * energy[0]
    np.testing.assert_allclose(energy[0] - energy, sim.dissipated, atol=1e-8 * energy[0])


# -- inverse: efforts ---------------------------------------------------------------------

def test_cam_rocker_slider_power_balance_at_constant_speed():
    m = cam_rocker_slider()
    w, h = 12.0, 1e-4
    q = np.linspace(0.05, 2 * np.pi - 0.05, 37)
    res = kl.dynamics.inverse(m, q, w, 0.0, reactions=False)
    plus = kl.dynamics.inverse(m, q + h, w, 0.0, reactions=False).kinetic_energy
    minus = kl.dynamics.inverse(m, q - h, w, 0.0, reactions=False).kinetic_energy
    dT_dt = (plus - minus) / (2 * h) * w                 # central difference, error ~ h^2
    assert np.abs(res.input_forces[:, 0]).max() > 0.1
    np.testing.assert_allclose(res.input_forces[:, 0], dT_dt / w, rtol=0, atol=1e-6)
    np.testing.assert_allclose(res.input_forces[:, 0] * w, res.energy_rate, rtol=0, atol=1e-12)


@pytest.mark.parametrize("damping", [0.0, 3.0])
def test_follower_effort_against_follower_forces(damping):
    m, spring = cam_follower()
    loads = Loads(springs=[spring], dampers=[Damper(("E", "F"), damping=damping)] if damping else ())
    q = np.linspace(0.0, 2 * np.pi, 73)[:-1]
    res = kl.dynamics.inverse(m, q, 20.0, 0.0, loads=loads)
    ff = kl.cams.follower_forces(m.joint("contact").program, mass=0.5, stiffness=2000.0,
                                 preload=10.0, damping=damping, speed=20.0, theta=q)
    np.testing.assert_allclose(res.input_forces[:, 0], ff.torque, rtol=0, atol=1e-9)
    # the contact force's component along the follower's slide (+y) is the program's N
    np.testing.assert_allclose(res.reactions("contact")[:, 1], ff.contact_force, rtol=0, atol=1e-9)


def test_friction_effort_at_constant_speed():
    """At constant speed through the train, the motor also overcomes each pin's friction,
    reduced to the input by its speed ratio."""
    loads = Loads(friction=[Friction("jO2", 0.01), Friction("jO3", 0.02)])
    q = np.linspace(0.0, 1.0, 5)
    res = kl.dynamics.inverse(gear_train(), q, 3.0, 0.0, loads=loads)
    np.testing.assert_allclose(res.input_forces[:, 0],
                               0.01 * np.tanh(2.0 / 1e-3) * 2 / 3 + 0.02 * np.tanh(1.5 / 1e-3) * 0.5,
                               rtol=1e-12)
    np.testing.assert_allclose(res.newton_euler_efforts, res.input_forces, rtol=1e-12)
    np.testing.assert_allclose(res.dissipation, res.actuator_power, rtol=1e-12)


# -- reactions ----------------------------------------------------------------------------

def test_planetary_reactions_give_kanes_efforts_with_the_pressure_angle():
    m = with_masses(kl.load(EX / "planetary.toml"),
                    {"sun": (1.0, "O", 1e-3), "arm": (0.5, "C", 2e-3), "planet": (0.3, "C", 2e-4),
                     "ring": (2.0, "O", 8e-3)})
    q = np.column_stack([np.linspace(0, 3, 7), np.linspace(0, 1, 7)])
    loads = Loads(torques=[Torque("ring", -0.2)], gravity=(0.0, -9.81))
    res = kl.dynamics.inverse(m, q, qd=[3.0, -1.0], qdd=[2.0, 0.5], loads=loads)
    np.testing.assert_allclose(res.newton_euler_efforts, res.input_forces, rtol=0, atol=1e-10)
    assert res.reactions_unique
    sol = res.kinematics
    for mesh, a in (("sun_planet", "O"), ("planet_ring", "C")):
        f = res.reactions(mesh)
        # along the line of action: the radial part is tan 20 deg of the tangential one
        centre_line = sol.position("C") - sol.position("O")
        e = centre_line / np.linalg.norm(centre_line, axis=-1)[:, None]
        radial = np.einsum("ni,ni->n", f, e)
        tangential = f[:, 0] * e[:, 1] - f[:, 1] * e[:, 0]
        np.testing.assert_allclose(np.abs(radial), TAN20 * np.abs(tangential), rtol=1e-10)


def test_cam_contact_force_along_the_common_normal():
    m, spring = cam_follower()
    q = np.linspace(0.1, 6.2, 30)
    res = kl.dynamics.inverse(m, q, 20.0, 0.0, loads=Loads(springs=[spring], gravity=(0, -9.81)))
    np.testing.assert_allclose(res.newton_euler_efforts, res.input_forces, rtol=0, atol=1e-10)
    sol = res.kinematics
    # the follower's foot F relative to the cam's point under it: v_F - omega x (F - O)
    r = sol.position("F") - sol.position("O")
    relative = sol.velocity("F") - 20.0 * np.stack([-r[:, 1], r[:, 0]], axis=-1)
    f = res.reactions("contact")
    np.testing.assert_allclose(np.einsum("ni,ni->n", f, relative), 0.0, atol=1e-9)
    assert np.all(np.einsum("ni,ni->n", f, r) > 0)        # the cam pushes the follower out


def test_oscillating_follower_reactions_are_refused_with_the_efforts_given():
    res = kl.dynamics.inverse(cam_rocker_slider(), np.linspace(0, 6, 7), 5.0)
    assert res.input_forces.shape == (7, 1) and np.isfinite(res.input_forces).all()
    assert res.reaction_forces is None and res.shaking_force is None
    with pytest.raises(ModelError, match=r"cam joint\(s\) 'contact' drive an oscillating follower"):
        res.reactions("contact")


# -- the [dynamics] section ---------------------------------------------------------------

def test_pair_loads_from_a_model_file_section_round_trip():
    from kinelab.dynamics import DynamicsSetup
    data = {"friction": [{"joint": "jO2", "magnitude": 0.01, "smoothing": 0.01}],
            "torsional_springs": [{"links": ["ground", "gear3"], "stiffness": 0.5,
                                   "free_angle": 0.1, "preload": 0.02}],
            "torsional_dampers": [{"links": ["idler", "gear1"], "damping": 0.002}]}
    setup = DynamicsSetup.from_dict(data)
    assert setup.to_dict() == data
    setup.check(gear_train())


@pytest.mark.parametrize("data, message", [
    ({"friction": [{"joint": "jO2", "magnitude": -1.0}]},
     r"friction 'jO2': magnitude: expected a number >= 0"),
    ({"friction": [{"joint": "jO2", "magnitude": 1.0, "smoothing": 0.0}]},
     r"smoothing: expected a speed > 0"),
    ({"friction": [{"joint": "jO2", "force": 1.0}]}, r"unknown key\(s\) 'force'"),
    ({"torsional_springs": [{"links": ["gear3", "gear3"], "stiffness": 1.0}]},
     r"its two ends are the same link 'gear3'"),
    ({"torsional_springs": [{"links": ["ground", "gear3"], "stiffness": "stiff"}]},
     r"stiffness: expected a number >= 0 \(N m/rad\)"),
    ({"torsional_dampers": [{"links": ["ground"], "damping": 1.0}]},
     r"links: expected two link names"),
])
def test_bad_pair_load_fields_are_one_line_errors(data, message):
    from kinelab.dynamics import DynamicsSetup
    with pytest.raises(ModelError, match=message) as info:
        DynamicsSetup.from_dict(data)
    assert "\n" not in str(info.value)


def test_friction_names_a_joint_of_the_model():
    for loads, message in ((Loads(friction=[Friction("mesh12", 1.0)]),
                            r"friction\[0\]: joint 'mesh12' is a G joint"),
                           (Loads(friction=[Friction("jX", 1.0)]), r"expected a joint of"),
                           (Loads(torsional_dampers=[TorsionalDamper(("ground", "arm"), 1.0)]),
                            r"torsional_dampers\[0\]: link: expected a link")):
        with pytest.raises(ModelError, match=message):
            kl.dynamics.inverse(gear_train(), 0.0, loads=loads)


# -- the command --------------------------------------------------------------------------

@pytest.mark.parametrize("example, columns", [
    ("cam_follower_dynamics", ["jO.torque[N*m]", "contact.reaction.x[N]", "contact.reaction.y[N]",
                               "guide.reaction_moment[N*m]"]),
    ("gear_train_dynamics", ["jO1.torque[N*m]", "mesh12.reaction.x[N]", "mesh23.reaction.y[N]"]),
])
def test_dynamics_command_on_the_cam_and_gear_examples(tmp_path, example, columns):
    import pandas as pd
    from click.testing import CliRunner

    from kinelab.cli import main
    run = CliRunner().invoke(main, ["dynamics", str(EX / f"{example}.toml"), "--out",
                                    str(tmp_path), "--no-plots"])
    assert run.exit_code == 0, run.output
    table = pd.read_csv(tmp_path / f"{example}_dynamics.csv")
    assert set(columns) <= set(table.columns) and np.isfinite(table[columns].to_numpy()).all()


def test_cam_example_effort_against_follower_forces_with_guide_friction():
    """examples/cam_follower_dynamics.toml: the follower_forces train (spring, preload,
    damper) plus the guide's friction, 0.5 N tanh(v / 1 mm/s) against the slide."""
    mf = kl.io.ModelFile.read(EX / "cam_follower_dynamics.toml")
    res = mf.inverse_dynamics(73)
    q = res.q[:, 0]
    ff = kl.cams.follower_forces(mf.mechanism.joint("contact").program, mass=0.5,
                                 stiffness=2000.0, preload=10.0, damping=3.0, speed=2 * np.pi,
                                 theta=q)
    v = ff.V * 2 * np.pi
    N = ff.contact_force + 0.5 * np.tanh(v / 1e-3)
    np.testing.assert_allclose(res.reactions("contact")[:, 1], N, rtol=0, atol=1e-9)
    np.testing.assert_allclose(res.input_forces[:, 0], N * ff.V, rtol=0, atol=1e-9)


def test_symbolic_equations_refuse_the_pair_loads():
    loads = Loads(torsional_dampers=[TorsionalDamper(("ground", "gear1"), 1.0)])
    with pytest.raises(ModelError, match=r"friction in joints and torsional springs and dampers "
                                         r"have no symbolic form here yet"):
        kl.dynamics.equations_of_motion(gear_train(), loads=loads)
