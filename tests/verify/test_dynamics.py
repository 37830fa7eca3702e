"""The certificate of dynamics: power balance (the kinetic energy's rate from the bodies'
motion), Newton-Euler, each link's balance, the whole mechanism's momentum; for a
simulation, its inverse dynamics and integrated energy.  It passes on the example engine
with every kind of load, and fails when an effort, a reaction or the shaking is wrong."""
import dataclasses
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.dynamics import Damper, Loads, PointForce, Spring, Torque, inverse, simulate
from kinelab.io import ModelFile

ROOT = Path(__file__).resolve().parents[2]
LOADS = Loads(gravity=(0.0, -9.81),
              forces=(PointForce("B", ("-100 * cos(q)", "5")),),
              torques=(Torque("rod", "0.3 * qd", reacting="crank"),
                       Torque("crank", 2.0, reacting="ground"), Torque("rod", "sin(t)")),
              springs=(Spring(("A", "B"), 1000.0, 0.1), Spring(("O2", "G3"), 500.0, 0.05)),
              dampers=(Damper(("O2", "B"), 3.0),))


@pytest.fixture(scope="module")
def engine():
    mf = ModelFile.read(ROOT / "examples" / "engine.toml")
    return mf.mechanism, *mf.sample_inputs(73)


@pytest.mark.parametrize("loads", [None, LOADS], ids=["file's gravity", "every load"])
def test_inverse_dynamics_are_verified(engine, loads):
    m, q, qd, _ = engine
    res = inverse(m, q, qd, 40.0, loads=loads, t=np.linspace(0, 0.2, len(q)))
    cert = kl.verify.certify(res, loads=loads)
    assert cert.passed, str(cert)
    assert {"effort", "energy", "reaction", "shaking", "K", "acceleration"} <= set(cert)
    assert cert["effort"][0] == ("Kane's equations", "Newton-Euler (free bodies)", "power balance")


def test_a_simulation_is_verified(engine):
    m = engine[0]
    sim = simulate(m, (0.0, 0.3), q0=0.3, qd0=20.0, loads=LOADS,
                   inputs={"crank angle": "5 - 0.1 * qd"}, t_eval=np.linspace(0.0, 0.3, 61),
                   rtol=1e-10)
    cert = kl.verify.certify(sim, loads=LOADS, rtol=1e-10)
    assert cert.passed, str(cert)
    assert cert["effort"][0][:2] == ("forward dynamics (applied laws)",
                                     "inverse dynamics of the motion")
    balance = cert.quantity("energy balance").comparisons[0]
    assert balance.bound == pytest.approx(1e-8) and balance.disagreement > 0
    # without its rtol the integration is not judged, and the certificate says so
    assert "energy balance" not in kl.verify.certify(sim, loads=LOADS)


def test_a_batch_of_simulations_is_verified(engine):
    m = engine[0]
    runs = simulate(m, (0.0, 0.1), q0=[[0.2], [1.0], [2.0]], qd0=15.0,
                    t_eval=np.linspace(0.0, 0.1, 11))
    cert = kl.verify.certify(runs, rtol=1e-10)
    assert cert.passed, str(cert)
    assert cert.quantity("effort").comparisons[0].samples == 33


def test_wrong_efforts_reactions_and_shaking_fail(engine):
    m, q, qd, qdd = engine
    res = inverse(m, q, qd, qdd, loads=LOADS)
    tau = res.input_forces.copy()
    tau[10] *= 1 + 1e-6
    cert = kl.verify.certify(dataclasses.replace(res, input_forces=tau), loads=LOADS)
    failed = {(q.name, c.route) for q in cert.quantities for c in q.failures}
    assert failed == {("effort", "Newton-Euler (free bodies)"), ("effort", "power balance"),
                      ("reaction", "moment balance of each link")}
    forces = res.reaction_forces.copy()
    forces[5, 1] += 1e-4                         # jA pushes a little more on the rod
    cert = kl.verify.certify(dataclasses.replace(res, reaction_forces=forces), loads=LOADS)
    assert cert.verdict().startswith("NOT verified: reaction by force balance of each link")
    shaking = res.shaking_moment.copy()
    shaking[3] += 1e-3
    cert = kl.verify.certify(dataclasses.replace(res, shaking_moment=shaking), loads=LOADS)
    assert [c.route for c in cert.quantity("shaking").failures] == [
        "momentum of the whole mechanism (moment)"]
    # loads other than the result's make the balance fail: the check is against the loads
    assert not kl.verify.certify(res).passed


def test_a_simulation_with_other_loads_fails(engine):
    m = engine[0]
    sim = simulate(m, (0.0, 0.1), q0=0.3, qd0=20.0, loads=LOADS, t_eval=np.linspace(0, 0.1, 11))
    cert = kl.verify.certify(sim)                # the file's loads, not those simulated
    assert {"effort", "energy"} <= {q.name for q in cert.quantities if not q.passed}
