"""Inverse dynamics of gear trains: the effort against the train's inertia seen from its input,
and the tooth force of each mesh from the moment balance of the gear it drives."""
import dataclasses
from pathlib import Path

import numpy as np

import kinelab as kl

EX = Path(__file__).parents[2] / "examples"


def with_inertias(m, inertias):
    """Each gear balanced (its centre of mass at its centre), with its moment of inertia."""
    return dataclasses.replace(m, links=tuple(
        dataclasses.replace(link, mass=1.0, center_of_mass=link.points[0], inertia=inertias[link.name])
        if link.name in inertias else link for link in m.links))


def test_simple_train_effort_is_its_inertia_reduced_to_the_input():
    inertia = {"gear1": 0.2, "idler": 0.3, "gear3": 0.4}
    m = with_inertias(kl.load(EX / "gear_train.toml"), inertia)
    q = np.linspace(0.0, 2 * np.pi, 13)
    res = kl.dynamics.inverse(m, q=q, qd=3.0, qdd=2.0)
    # sum of I K^2 (L = 0): 0.2 + 0.3 (2/3)^2 + 0.4 (1/2)^2
    reduced = 0.2 + 0.3 * (20 / 30) ** 2 + 0.4 * (20 / 40) ** 2
    np.testing.assert_allclose(res.input_forces[:, 0], reduced * 2.0, rtol=1e-12)
    np.testing.assert_allclose(res.newton_euler_efforts[:, 0], reduced * 2.0, rtol=1e-12)
    assert res.reactions_unique
    # gear 3 (pitch radius 40 mm) is turned by its mesh alone: F_t r3 = I3 alpha3, F_t along
    # the tangent (y: the centres lie on the x axis); along the line of action at the 20 deg
    # pressure angle the teeth also push gear 3 away from the idler (+x) by F_t tan 20 deg
    f = res.reactions("mesh23")
    np.testing.assert_allclose(np.abs(f[:, 1]) * 0.040, 0.4 * 2.0 * 0.5, rtol=1e-12)
    np.testing.assert_allclose(f[:, 0], np.abs(f[:, 1]) * np.tan(np.radians(20.0)), rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(f, axis=-1) * 0.040,
                               0.4 * 2.0 * 0.5 / np.cos(np.radians(20.0)), rtol=1e-12)


def test_rack_effort_moves_its_mass():
    m = kl.load(EX / "rack_and_pinion.toml")
    m = dataclasses.replace(m, links=tuple(
        dataclasses.replace(link, mass=2.0, center_of_mass="K") if link.name == "rack" else
        dataclasses.replace(link, mass=1.0, center_of_mass="O", inertia=1e-12)
        if link.name == "pinion" else link for link in m.links))
    res = kl.dynamics.inverse(m, q=np.linspace(0.0, 3.0, 7), qd=1.0, qdd=4.0)
    # the rack's 2 kg accelerated at r qdd = 0.1 m/s^2 by a torque r F (and the pinion's
    # 1e-12 kg m^2 turned at 4 rad/s^2)
    np.testing.assert_allclose(res.input_forces[:, 0], 0.025 * 2.0 * 0.025 * 4.0 + 4e-12, rtol=1e-12)
    # along the rack (x) the 0.2 N that accelerates it; across, the teeth's separating force
    # tan(20 deg) 0.2 N, pushing the rack away from the pinion's centre
    f = res.reactions("mesh")
    np.testing.assert_allclose(f[:, 0], 2.0 * 0.1, rtol=1e-12)
    away = np.sign(kl.analyze(m, q=0.0).position("K")[1] - kl.analyze(m, q=0.0).position("O")[1])
    np.testing.assert_allclose(f[:, 1], away * 0.2 * np.tan(np.radians(20.0)), rtol=1e-12)
