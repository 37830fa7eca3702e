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
