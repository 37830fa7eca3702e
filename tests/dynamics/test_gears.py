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
    # gear 3 (pitch radius 40 mm) is turned by its mesh alone: F r3 = I3 alpha3, tangential
    f = res.reactions("mesh23")
    np.testing.assert_allclose(np.linalg.norm(f, axis=-1) * 0.040, 0.4 * 2.0 * 0.5, rtol=1e-12)
    np.testing.assert_allclose(f[:, 0], 0.0, atol=1e-12)      # the centres lie on the x axis


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
    np.testing.assert_allclose(res.reactions("mesh"), [[2.0 * 0.1, 0.0]] * 7, rtol=0, atol=1e-12)
