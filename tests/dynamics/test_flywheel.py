"""Flywheel sizing, checked by simulating the flywheel it gives."""
import numpy as np
import pytest

from kinelab.dynamics import flywheel, simulate
from kinelab.errors import ModelError
from kinelab.model import Input, Joint, Link, Mechanism, Point


def rotor(inertia):
    """A flywheel alone: a disc turning about O, its centre of mass on the axis."""
    return Mechanism("rotor", (Point("O", 0, 0), Point("E", 1, 0)),
                     (Link("ground", ("O",), ground=True),
                      Link("disc", ("O", "E"), mass=1.0, center_of_mass="O", inertia=inertia)),
                     (Joint("shaft", "R", ("ground", "disc"), point="O"),), (Input(joint="shaft"),))


def test_flywheel_keeps_the_speed_within_the_coefficient():
    """A load T = 10 + 4 sin 2q against a steady motor torque of 10 N m: started at the
    fastest angle with w_max = w (1 + Cs/2), the flywheel should slow to w (1 - Cs/2)."""
    theta = np.linspace(0.0, 2 * np.pi, 2001)
    speed, cs = 20.0, 0.05
    fw = flywheel(theta, 10 + 4 * np.sin(2 * theta), speed=speed, fluctuation=cs)
    # E = integral (10 - T) = 2 (cos 2q - 1): highest at q = 0 (and pi), lowest at pi/2
    assert np.cos(2 * fw.theta_fastest) == pytest.approx(1.0, abs=1e-12)
    assert fw.theta_slowest == pytest.approx(np.pi / 2, abs=2e-3)
    assert fw.energy_fluctuation == pytest.approx(4.0, rel=1e-5)   # trapezoid: h^2 / 12 * 16 ~ 1.3e-5
    sim = simulate(rotor(fw.inertia), (0.0, 2 * np.pi / speed), q0=fw.theta_fastest,
                   qd0=speed * (1 + cs / 2), inputs={"shaft": "-4 * sin(2 * q)"},
                   t_eval=np.linspace(0.0, 2 * np.pi / speed, 2001), rtol=1e-12, atol=1e-12)
    w = sim.qd[:, 0]
    assert w.max() == pytest.approx(speed * (1 + cs / 2), rel=1e-9)
    assert w.min() == pytest.approx(speed * (1 - cs / 2), rel=1e-6)


@pytest.mark.parametrize("args, message", [
    (([0.0, 1.0], [1.0, 2.0]), r"expected two arrays of the same shape \(N,\), N >= 3"),
    (([0.0, 2.0, 1.0], [1.0, 2.0, 3.0]), r"theta: expected increasing crank angles"),
    (([0.0, 1.0, 2.0], [1.0, np.nan, 3.0]), r"expected finite numbers \(a singular sample"),
])
def test_bad_curves(args, message):
    with pytest.raises(ModelError, match=message):
        flywheel(*args, speed=10.0, fluctuation=0.01)
    with pytest.raises(ModelError, match=r"fluctuation: expected a positive number below 2 .*, got 0$"):
        flywheel([0.0, 1.0, 2.0], [1.0, 2.0, 3.0], speed=10.0, fluctuation=0)
