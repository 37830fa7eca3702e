"""Mass data, loads and the [dynamics] section: bad data gets one error listing every problem."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.dynamics import (Damper, DynamicsSetup, LinkMass, Loads, MassProperties, PointForce,
                              PointMass, Spring, Torque, inverse)
from kinelab.errors import ModelError, SingularityError
from kinelab.model import Link, Mechanism
from tests.dynamics.models import engine, fourbar, pendulum, prrrr, rp_robot


def test_missing_mass_data_names_every_link():
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)        # the catalogue gives no masses
    with pytest.raises(ModelError) as info:
        inverse(sc, 0.3)
    msg = str(info.value)
    for link in ("crank", "rod", "slider"):
        assert (f"mechanism 'slider_crank': link '{link}': mass: missing; give mass (kg), "
                "center_of_mass (one of its points) and inertia (kg m^2), or declare it massless") in msg
    assert "ground" not in msg


def test_mass_without_centre_or_inertia():
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    links = (sc.links[0], Link("crank", ("O2", "A"), mass=1.0), Link("rod", ("A", "B"), mass=1.0,
                                                                     center_of_mass="A"),
             Link("slider", ("B",), mass=1.0, center_of_mass="B"))     # a piston needs no inertia
    m = Mechanism("sc", sc.points, links, sc.joints, sc.inputs)
    with pytest.raises(ModelError) as info:
        MassProperties.from_model(m)
    assert info.value.problems == (
        "link 'crank': has a mass but no center_of_mass (one of its points 'O2', 'A') and no inertia "
        "(kg m^2, about the centre of mass); add them to the link",
        "link 'rod': has a mass but no inertia (kg m^2, about the centre of mass); add it to the link")


@pytest.mark.parametrize("field, value", [("mass", 0.0), ("mass", -1.0), ("inertia", 0.0),
                                          ("inertia", float("nan"))])
def test_non_positive_mass_or_inertia_in_the_model(field, value):
    with pytest.raises(ModelError, match=rf"mechanism 'pendulum': link 'arm': {field}: expected a "
                                         rf"positive number, got {value}"):
        pendulum(**{field: value})


def test_non_positive_masses_built_by_hand():
    with pytest.raises(ModelError, match=r"link 'arm': mass: expected a positive number \(kg\) up to "
                                         r"1e\+30, got -2"):
        LinkMass("arm", -2, "G", 0.1)
    with pytest.raises(ModelError, match=r"link 'arm': inertia: expected a number >= 0 \(kg m\^2\) up "
                                         r"to 1e\+48, got -0.1"):
        LinkMass("arm", 2.0, "G", -0.1)
    with pytest.raises(ModelError, match=r"point mass at 'P': mass: expected a positive number \(kg\) "
                                         r"up to 1e\+30, got 0"):
        PointMass("P", 0)
    with pytest.raises(ModelError, match=r"up to 1e\+30, got 1e\+300"):    # m v^2 would overflow
        PointMass("P", 1e300)
    with pytest.raises(ModelError) as info:
        MassProperties.from_model(rp_robot(), massless=("arm", "hand"), point_masses={"G2": -1.0, "Q": 1.0})
    assert info.value.problems == (
        "massless: expected a link of 'rp', got 'hand'; its links are 'ground', 'arm', 'gripper'",
        "link 'gripper': mass: missing; give mass (kg), center_of_mass (one of its points) "
        "and inertia (kg m^2), or declare it massless",
        "point mass at 'G2': mass: expected a positive number (kg) up to 1e+30, got -1.0",
        "point_masses: expected a point of 'rp', got 'Q'")


def test_loads_naming_unknown_items_are_all_reported():
    loads = Loads(forces=[PointForce("Q", (1.0, 0.0)), PointForce("A", (1.0, 0.0), link="slider")],
                  torques=[Torque("crank", 1.0, reacting="frame")],
                  springs=[Spring(("A", "Z"), 10.0)])
    with pytest.raises(ModelError) as info:
        inverse(engine(), 0.3, loads=loads)
    assert info.value.problems == (
        "forces[0]: point: expected a point of 'engine', got 'Q'; its points are 'O2', 'A', 'B', 'G2', 'G3'",
        "forces[1]: link 'slider' does not carry point 'A'; name a link that does ('crank', 'rod')",
        "torques[0].reacting: link: expected a link of 'engine', got 'frame'; its links are "
        "'ground', 'crank', 'rod', 'slider'",
        "springs[0]: point: expected a point of 'engine', got 'Z'; its points are 'O2', 'A', 'B', 'G2', 'G3'")


@pytest.mark.parametrize("build, message", [
    (lambda: Spring(("A", "A"), 1.0), r"spring A-A: points: its two ends are the same point 'A'"),
    (lambda: Spring(("A", "B"), -1.0), r"spring A-B: stiffness: expected a number >= 0 \(N/m\) up to 1e\+30, got -1.0"),
    (lambda: Damper(("A", "B"), float("inf"), name="shock"), r"damper 'shock': damping: expected a number >= 0"),
    (lambda: Damper(("A", "B"), 1e308), r"damper A-B: damping: expected a number >= 0 \(N s/m\) up to 1e\+30, got 1e\+308"),
    (lambda: Spring(("A", "B"), 1e31), r"spring A-B: stiffness: expected a number >= 0 \(N/m\) up to 1e\+30"),
    (lambda: Spring(("A", "B"), 1.0, 1e10), r"spring A-B: free_length: expected a number >= 0 \(m\) up to 1e\+09"),
    (lambda: Loads(gravity=9.81), r"gravity: expected two finite numbers \(gx, gy\) in m/s\^2, got 9.81"),
    (lambda: Loads(forces=[Torque("crank", 1.0)]), r"forces\[0\]: expected a kinelab.dynamics.PointForce, got Torque"),
    (lambda: PointForce("B", 5.0), r"force at 'B': expected 2 components \(fx, fy\)"),
    (lambda: PointForce("B", (1.0, "q +")), r"force at 'B'\[1\]: cannot parse the expression"),
    (lambda: Torque("crank", [1, 2]), r"torque on 'crank': expected a number, an expression"),
])
def test_bad_loads(build, message):
    with pytest.raises(ModelError, match=message):
        build()


def test_spring_whose_ends_meet_cannot_push():
    # the gripper's point G2 reaches the shoulder O when the reach q2 is zero
    m = rp_robot()
    masses = MassProperties(points=[PointMass("G2", 1.0)])
    loads = Loads(springs=[Spring(("O", "G2"), 10.0, name="coil")])
    assert np.isfinite(inverse(m, [0.3, 0.2], loads=loads, masses=masses).input_forces).all()
    with pytest.raises(SingularityError, match=r"coil: its two ends meet at sample 1 \(q = \[0.3, 0.0\]\), "
                                               r"so the direction of its force is undefined"):
        inverse(m, [[0.3, 0.2], [0.3, 0.0]], loads=loads, masses=masses)


def test_lumping_needs_a_binary_link_with_its_centre_on_the_line():
    m = prrrr()
    masses = MassProperties.from_model(m)
    with pytest.raises(ModelError, match=r"lumped: link 'slider' has 1 hinge point\(s\) and 1 slide\(s\); "
                                         "only a binary link hinged at two points can be lumped"):
        masses.lumped(m, ["slider"])
    lumped = masses.lumped(m, ["bar3", "crank"])     # the crank's G2 lies on O2-A
    assert lumped.total_mass == pytest.approx(masses.total_mass, abs=1e-15)
    assert [(p.point, p.link) for p in lumped.points] == [("G1", "slider"), ("P", "bar4"),
                                                          ("O2", "crank"), ("A", "bar4")]
    fb = fourbar()
    with pytest.raises(ModelError, match=r"lumped: link 'coupler': its centre of mass 'P' is not on "
                                         r"the segment A-B"):
        MassProperties.from_model(fb).lumped(fb, ["coupler"])


def test_setup_round_trip_and_use():
    data = {"gravity": [0.0, -9.81], "massless": ["arm", "gripper"], "point_masses": {"G2": 2.0},
            "actuators": {"shoulder": "1 + t", "reach": 3.0},
            "torques": [{"link": "arm", "torque": "-0.5 * qd[0]", "reacting": "ground"}],
            "springs": [{"points": ["O", "G2"], "stiffness": 100.0, "free_length": 0.5}],
            "dampers": [{"points": ["O", "G2"], "damping": 2.0, "name": "shock"}],
            "forces": [{"point": "E", "fx": {"of": "t", "x": [0, 1], "y": [0, 5]}, "fy": -1.0}]}
    setup = DynamicsSetup.from_dict(data)
    assert setup.to_dict() == {**data, "actuators": {"shoulder": "1 + t", "reach": 3.0}}
    m = rp_robot()
    setup.check(m)
    res = inverse(m, [0.3, 0.7], [1.0, 0.5], loads=setup.loads, masses=setup.masses(m), t=0.5)
    assert res.input_forces.shape == (1, 2) and np.isfinite(res.input_forces).all()
    empty = DynamicsSetup.from_model(m)
    assert empty.to_dict() == {}


def test_setup_reports_every_problem():
    data = {"gravity": [0.0], "spin": 1, "actuators": {"shoulder": "os.system('x')"},
            "forces": [{"point": "E", "fz": 1.0}], "massless": "arm", "point_masses": {"G2": -1}}
    with pytest.raises(ModelError) as info:
        DynamicsSetup.from_dict(data)
    p = info.value.problems
    assert p[0].startswith("dynamics: unknown key(s) 'spin'; expected some of 'gravity'")
    assert any(s.startswith("dynamics.forces[0]: unknown key(s) 'fz'") for s in p)
    assert any(s.startswith("dynamics.gravity: expected two finite numbers") for s in p)
    assert any(s.startswith("dynamics.actuators.shoulder: the function 'os.system' is not allowed") for s in p)
    assert "dynamics.massless: expected a list of link names, got 'arm'" in p
    assert "dynamics.point_masses.G2: expected a positive mass (kg), got -1" in p


def test_setup_check_names_an_actuator_on_a_passive_joint():
    setup = DynamicsSetup.from_dict({"actuators": {"jA": 1.0}})
    with pytest.raises(ModelError, match=r"dynamics.actuators: 'jA' is a joint but not an input; the "
                                         r"inputs are 'jO2'"):
        setup.check(engine())


def test_python_callables_cannot_be_written_to_a_file():
    loads = Loads(torques=[Torque("crank", lambda t, q, qd: 0 * t)])
    with pytest.raises(ModelError, match=r"torque on 'crank': a Python callable cannot be written"):
        loads.to_dict()


@pytest.mark.parametrize("mass", [float("inf"), float("nan"), 0.0, True])
def test_setup_refuses_a_point_mass_that_is_not_a_finite_positive_number(mass):
    with pytest.raises(ModelError, match="dynamics.point_masses.G2: expected a positive mass"):
        DynamicsSetup.from_dict({"point_masses": {"G2": mass}})
