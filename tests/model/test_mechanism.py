import pytest

from kinelab.errors import ModelError
from kinelab.model import Input, Joint, Link, Mechanism, Point


def fourbar_parts():
    points = (Point("O2", 0, 0), Point("A", 0, 1), Point("B", 3, 2), Point("O4", 3, 0))
    links = (Link("ground", ("O2", "O4"), ground=True), Link("crank", ("O2", "A")),
             Link("coupler", ("A", "B")), Link("rocker", ("O4", "B")))
    joints = (Joint("jO2", "R", ("ground", "crank"), point="O2"),
              Joint("jA", "R", ("crank", "coupler"), point="A"),
              Joint("jB", "R", ("coupler", "rocker"), point="B"),
              Joint("jO4", "R", ("ground", "rocker"), point="O4"))
    return points, links, joints


def test_valid_fourbar_round_trips_through_dict():
    points, links, joints = fourbar_parts()
    m = Mechanism("fb", points, links, joints, (Input(joint="jO2", speed=2.0),))
    again = Mechanism.from_dict(m.to_dict())
    assert again == m
    assert m.ground.name == "ground"
    assert m.links_carrying("A") == ("crank", "coupler")


def test_all_problems_reported_at_once():
    points, links, joints = fourbar_parts()
    links = links[:2] + (Link("coupler", ("A", "Q")), links[3])
    joints = joints + (Joint("self", "R", ("rocker", "rocker"), point="B"),)
    with pytest.raises(ModelError) as info:
        Mechanism("fb", points, links, joints, (Input(joint="nope"),))
    text = str(info.value)
    assert "link 'coupler': points: expected a declared point, got 'Q'" in text
    assert "joint 'self': joins link 'rocker' to itself" in text
    assert "inputs[0]: joint: expected a declared joint, got 'nope'" in text
    assert len(info.value.problems) >= 4


@pytest.mark.parametrize("change, message", [
    (lambda p, l, j: (p, l[1:], j), "expected exactly one ground link, got 0"),
    (lambda p, l, j: (p, l + (Link("g2", ("O4",), ground=True),), j),
     "expected exactly one ground link, got 2"),
    (lambda p, l, j: (p, l[:1] + (Link("crank", ("O2",)),) + l[2:], j),
     "a moving link needs at least two points"),
    (lambda p, l, j: (p, l, j[:1] + (Joint("jA", "X", ("crank", "coupler"), point="A"),) + j[2:]),
     "type: expected one of"),
    (lambda p, l, j: (p + (Point("A", 1, 1),), l, j), "name already used"),
    (lambda p, l, j: (p, l, j[:1] + (Joint("jA", "R", ("crank", "coupler"), point="O4"),) + j[2:]),
     "must be carried by both links"),
    (lambda p, l, j: ((Point("O2", 0, 0), Point("A", 0, 0)) + p[2:], l, j), "coincide"),
    (lambda p, l, j: (p, l, j[:1] + j[2:]), "not all joined by revolute joints at 'A'"),
])
def test_bad_models_name_the_item(change, message):
    with pytest.raises(ModelError, match=message):
        Mechanism("fb", *change(*fourbar_parts()))


def test_disconnected_link_is_reported():
    points, links, joints = fourbar_parts()
    points = points + (Point("C", 5, 5), Point("D", 6, 5))
    links = links + (Link("loose", ("C", "D")),)
    with pytest.raises(ModelError, match="'loose' are not connected to the ground"):
        Mechanism("fb", points, links, joints)


def _fourbar(**change):
    points, links, joints = fourbar_parts()
    parts = {"name": "fb", "points": points, "links": links, "joints": joints,
             "inputs": (Input(joint="jO2"),), **change}
    return Mechanism(**parts)


@pytest.mark.parametrize("change, message", [
    ({"points": None}, r"^mechanism 'fb': points: expected a sequence of Point objects, got None$"),
    ({"points": 5}, r"^mechanism 'fb': points: expected a sequence of Point objects, got 5$"),
    ({"links": None}, r"^mechanism 'fb': links: expected a sequence of Link objects, got None$"),
    ({"joints": None}, r"^mechanism 'fb': joints: expected a sequence of Joint objects, got None$"),
    ({"inputs": None}, r"^mechanism 'fb': inputs: expected a sequence of Input objects, got None$"),
    ({"inputs": "jO2"}, r"^mechanism 'fb': inputs: expected a sequence of Input objects, got 'jO2'$"),
    ({"parameters": None}, r"^mechanism 'fb': parameters: expected a mapping of name = value, got None$"),
    ({"parameters": [1, 2]}, r"^mechanism 'fb': parameters: expected a mapping of name = value, got \[1, 2\]$"),
    ({"name": ""}, r"^mechanism '': name: expected a non-empty name, got ''$"),
    ({"name": "   "}, r"^mechanism '   ': name: expected a non-empty name, got '   '$"),
])
def test_fields_that_are_not_collections_or_names_are_named(change, message):
    with pytest.raises(ModelError, match=message):
        _fourbar(**change)


def _slider_crank(bore_links):
    points = (Point("O", 0.0, 0.0), Point("A", 1.0, 0.0), Point("B", 3.0, 0.0))
    links = (Link("ground", ("O",), ground=True), Link("crank", ("O", "A")),
             Link("rod", ("A", "B")), Link("piston", ("B",)))
    joints = (Joint("jO", "R", ("ground", "crank"), point="O"),
              Joint("jA", "R", ("crank", "rod"), point="A"),
              Joint("jB", "R", ("rod", "piston"), point="B"),
              Joint("bore", "P", bore_links, point="B", axis=(1.0, 0.0)))
    return Mechanism("sc", points, links, joints, (Input(joint="jO"),))


@pytest.mark.parametrize("links, message", [
    (None, r"joint 'bore': links: expected two links, got None"),
    (5, r"joint 'bore': links: expected two links, got 5"),
    ((["ground"], "piston"), r"joint 'bore': links: expected a declared link, got \['ground'\]"),
])
def test_a_prismatic_joint_with_bad_links_is_named(links, message):
    with pytest.raises(ModelError, match=message):
        _slider_crank(links)
    assert _slider_crank(("ground", "piston")).joint("bore").links == ("ground", "piston")


def test_numbers_are_kept_as_floats():
    from fractions import Fraction

    import numpy as np
    points = (Point("O2", Fraction(1, 3), 0), Point("A", np.float32(0.5), 1),
              Point("B", 3, 2), Point("O4", 3, 0))
    _, links, joints = fourbar_parts()
    links = (Link("ground", ("O2", "O4"), ground=np.True_, mass=Fraction(1, 2)),) + links[1:]
    joints = joints + (Joint("slide", "P", ("ground", "crank"), point="A",
                             axis=(Fraction(1, 2), np.int64(1)), offset=np.float16(0.25)),)
    m = Mechanism("fb", points, links, joints[:4],
                  (Input(joint="jO2", range=(0, Fraction(1, 2)), speed=np.int64(2)),),
                  parameters={"crank": Fraction(1, 4), "teeth": 3})
    numbers = [*(c for p in m.points for c in (p.x, p.y, p.z)), m.ground.mass,
               *m.inputs[0].range, m.inputs[0].speed, m.inputs[0].acceleration,
               m.parameters["crank"]]
    assert all(type(v) is float for v in numbers), [type(v) for v in numbers]
    assert m.point("O2").x == 1 / 3 and m.ground.ground is True
    assert m.parameters["teeth"] == 3 and type(m.parameters["teeth"]) is int
    joint = joints[4]
    assert joint.axis == (0.5, 1.0) and all(type(c) is float for c in joint.axis)
    assert type(joint.offset) is float


def test_a_planar_point_off_the_plane_is_named():
    points, links, joints = fourbar_parts()
    points = points[:1] + (Point("A", 0.0, 1.0, 0.5),) + points[2:]
    with pytest.raises(ModelError, match=r"point 'A': z: expected 0 in a planar mechanism, got "
                                         r"0.5 m; remove z, or use space = 'spatial'"):
        Mechanism("fb", points, links, joints)


def test_a_model_with_fraction_coordinates_is_analysed():
    from fractions import Fraction

    import kinelab as kl
    points, links, joints = fourbar_parts()
    points = (Point("O2", Fraction(0), Fraction(0)),) + points[1:]
    m = Mechanism("fb", points, links, joints, (Input(joint="jO2"),))
    assert kl.analyze(m, [0.1]).position("A").shape == (1, 2)
