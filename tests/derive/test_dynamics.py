"""The Gibbs-Appell / Kane terms in symbols (*Mecanismos*, §5) against the engine's dynamics
(kinelab.dynamics.inverse, which builds Kane's terms numerically from its K and L), for open
and closed chains, and the notes' PRRRR with lumped masses against the notes' own formulas."""
import numpy as np
import pytest
import sympy as sp

import kinelab as kl
from kinelab.derive import derive
from kinelab.dynamics import (Damper, Loads, MassProperties, PointForce, Spring, Torque,
                              equations_of_motion, inverse)
from kinelab.errors import ModelError
from tests.dynamics.models import engine, fourbar, pendulum, pr_robot, prrrr
from tests.reference.test_notes_003_dynamics import F, prrrr_motion, prrrr_notes

G = (0.0, -9.81)
rng = np.random.default_rng(7)


def motion(d, n):
    M = len(d.q)
    sketch = np.array([d.equations.sketch[s] for s in d.q])
    q = sketch + rng.uniform(-0.15, 0.15, (n, M))
    qd, qdd = rng.uniform(-4, 4, (n, M)), rng.uniform(-20, 20, (n, M))
    pick = (lambda a: a) if M > 1 else (lambda a: a[:, 0])
    return pick(q), pick(qd), pick(qdd)


CASES = {
    "engine (closed, slider-crank)": (engine, Loads(gravity=G,
                                                    forces=[PointForce("B", ("-800 * (q > 1)", 0.0))])),
    "four-bar with every kind of load": (fourbar, Loads(
        gravity=G, forces=[PointForce("P", ("3 * sin(q)", 2.0))],
        torques=[Torque("rocker", "-0.4 * qd", reacting="ground")],
        springs=[Spring(("G4", "P"), stiffness=300.0, free_length=0.1)],
        dampers=[Damper(("A", "O4"), damping=2.5)])),
    "PRRRR (closed, two inputs)": (prrrr, Loads(gravity=G, forces=[PointForce("P", F)])),
    "pendulum (open)": (pendulum, Loads(gravity=G)),
    "PR robot (open, two inputs)": (pr_robot, Loads(gravity=G, torques=[Torque("arm", "2 - t")])),
}


@pytest.mark.parametrize("case", CASES)
def test_efforts_against_inverse(case):
    build, loads = CASES[case]
    m = build()
    d = derive(m, loads=loads)
    q, qd, qdd = motion(d, 6)
    t = rng.uniform(0, 2, 6)
    mine = d.dynamics.efforts(q, qd, qdd, t=t)
    ref = inverse(m, q, qd, qdd, loads=loads, t=t, reactions=False).input_forces
    ref = np.reshape(ref, mine.shape)
    np.testing.assert_allclose(mine, ref, rtol=1e-10, atol=1e-10 * np.abs(ref).max())
    assert np.abs(ref).max() > 1e-2


def test_prrrr_of_the_notes_with_lumped_masses():
    """§5.7: bars 3 and 4 lumped at their ends, the force F at P; the notes' C, D, f and
    C^T D f = 0, re-derived by hand in tests/reference, against the symbols' efforts."""
    m = prrrr()
    lumped = MassProperties.from_model(m).lumped(m, ["bar3", "bar4"])
    loads = Loads(gravity=G, forces=[PointForce("P", F)])
    d = derive(m, loads=loads, masses=lumped)
    kd = d.dynamics
    assert kd.C.shape == (4, 2) and kd.C[:2, :] == sp.eye(2)
    assert kd.D.shape == (4, 3 * len(kd.bodies)) and kd.f.shape == (3 * len(kd.bodies), 1)
    q, qd, qdd = prrrr_motion(12)
    expected, _ = prrrr_notes(q, qd, qdd)
    np.testing.assert_allclose(kd.efforts(q, qd, qdd), expected, rtol=1e-10, atol=1e-9)


def test_open_chain_against_equations_of_motion():
    """Where both apply, the loop-based terms and equations_of_motion agree in symbols."""
    m = pendulum(length=0.5, mass=2.0, inertia=0.01)
    loads = Loads(gravity=G)
    d = derive(m, loads=loads)
    eom = equations_of_motion(m, loads=loads, lengths="symbols")
    (q,), (qdd,) = d.q, (d.ddot(d.q[0]),)
    mine = d.dynamics.equations[0].subs({**d.parameters, **d.dynamics.parameters})
    theirs = eom.input_forces[0].subs(eom.values).subs({eom.q[0]: q, eom.qdd[0]: qdd})
    assert sp.simplify(mine - theirs) == 0


def test_no_masses_no_dynamics_and_partial_masses_say_what_is_missing():
    assert derive(kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)).dynamics is None
    m = engine()
    links = tuple(kl.model.Link(li.name, li.points) if li.name == "rod" else li for li in m.links)
    half = kl.Mechanism(m.name, m.points, links, m.joints, m.inputs)
    with pytest.raises(ModelError, match=r"link 'rod': mass: missing"):
        derive(half)
    assert derive(half, dynamics=False).dynamics is None


def test_the_document_shows_the_notes_terms():
    d = derive(engine(), loads=Loads(gravity=G))
    text = d.to_markdown()
    # D, three bodies of three columns, is too wide for a page: it is given entry by entry
    for piece in ("## Dynamics: Gibbs-Appell and Kane", "C &= ", "D_{11} &= ",
                  "The entries not written are 0.", "f_{1} &= ",
                  r"\tau_{\text{jO2}} &= ", "kinelab.dynamics.inverse"):
        assert piece in text, piece
    pt = d.to_markdown(lang="pt")
    assert "## Dinâmica: Gibbs-Appell e Kane" in pt and "as notas de aula *Mecanismos*" in pt
