"""The certificate of velocity and acceleration polygons."""
import dataclasses
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("name, at", [("slotted_link", 1.0), ("whitworth", 2.0),
                                      ("inverted_slider_crank", 0.7), ("crank_rocker", 0.4),
                                      ("fivebar", [1.7, 1.4]), ("stephenson6", 0.3)])
def test_polygons_of_the_examples_are_verified(name, at):
    m = kl.load(ROOT / "examples" / f"{name}.toml")
    M = len(m.inputs)
    sol = kl.analyze(m, np.array(at), qd=np.full(M, 2.0) if M > 1 else 2.0,
                     qdd=np.full(M, -1.0) if M > 1 else -1.0)
    for polygon in (kl.kinematics.velocity_polygon(sol), kl.kinematics.acceleration_polygon(sol)):
        cert = kl.verify.certify(polygon, solution=sol)
        assert cert.passed, str(cert)


def test_coriolis_is_checked_independently():
    sl = kl.mechanisms.slotted_link(crank=1.0, distance=2.0)
    sol = kl.analyze(sl, q=np.pi / 2, qd=3.0)
    ap = kl.kinematics.acceleration_polygon(sol)
    cert = kl.verify.certify(ap, solution=sol)
    assert cert["Coriolis part"][0] == ("analysis", "2 omega x v_rel, v_rel independent")
    # a Coriolis part of the wrong sign fails, and so does the side's closure
    side = ap.sides["A", "A@lever"]
    parts = dict(side.parts, coriolis=-side.parts["coriolis"])
    sides = dict(ap.sides)
    sides["A", "A@lever"] = dataclasses.replace(side, parts=parts)
    bad = dataclasses.replace(ap, sides=sides)
    failed = {q.name for q in kl.verify.certify(bad, solution=sol).quantities if not q.passed}
    assert failed == {"Coriolis part", "acceleration polygon"}


def test_a_wrong_vertex_fails():
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    sol = kl.analyze(sc, q=1.0, qd=2.0)
    vp = kl.kinematics.velocity_polygon(sol)
    bad = dataclasses.replace(vp, vertices={**vp.vertices, "B": vp.vertices["B"] * (1 + 1e-6)})
    cert = kl.verify.certify(bad, solution=sol)
    assert {c.route for c in cert.quantity("velocity polygon").failures} == {
        "Newton engine (vertices)", "closure (sides, parts, pole)"}


def test_the_polygon_needs_its_solution():
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    vp = kl.kinematics.velocity_polygon(kl.analyze(sc, q=1.0, qd=2.0))
    with pytest.raises(kl.errors.ModelError, match="expected the KinematicSolution the polygon"):
        kl.verify.certify(vp)
    with pytest.raises(kl.errors.ModelError, match="not drawn from this solution"):
        kl.verify.certify(vp, solution=kl.analyze(sc, q=1.5, qd=2.0))
