"""A link's exact places: points given by their sides, against the law of cosines written
here in its angle form (the code uses the projection and Heron's height), and the model's
refusals of sides that cannot be."""
import math

import pytest

from kinelab.errors import ModelError
from kinelab.model import Input, Joint, Link, Mechanism, Point, exact_places


def by_angle(dA: float, dB: float, AB: float, side: str) -> tuple[float, float]:
    """Where a point dA from A and dB from B lies in the frame A -> B, by the angle at A:
    cos(alpha) = (dA² + AB² - dB²) / (2 dA AB)."""
    alpha = math.acos((dA ** 2 + AB ** 2 - dB ** 2) / (2 * dA * AB))
    return dA * math.cos(alpha), (1 if side == "left" else -1) * dA * math.sin(alpha)


SKETCH = {"A": (0.0, 0.0), "B": (5.0, 0.0), "P": (3.0, 2.0), "Q": (6.0, 4.0)}


@pytest.mark.parametrize("dA, dB, AB", [(4.0, 3.0, 5.0), (2.0, 4.5, 5.0), (7.0, 3.0, 5.0),
                                        (0.3, 0.3, 0.5), (1e3, 1e3 + 1e-3, 5.0)])
@pytest.mark.parametrize("side", ["left", "right"])
def test_a_point_by_its_sides_is_where_the_law_of_cosines_puts_it(dA, dB, AB, side):
    link = Link("coupler", ("A", "B", "P"), length=AB, sides={"P": {"A": dA, "B": dB, "side": side}})
    along, left = exact_places(link, SKETCH)["P"]
    assert (along, left) == pytest.approx(by_angle(dA, dB, AB, side), rel=1e-12, abs=1e-12 * dA)
    assert math.hypot(along, left) == pytest.approx(dA, rel=1e-12)
    assert math.hypot(along - AB, left) == pytest.approx(dB, rel=1e-12)


def test_the_3_4_5_triangle_by_hand():
    # along = (4² - 3² + 5²) / (2 x 5) = 3.2, left = sqrt(4² - 3.2²) = 2.4
    link = Link("coupler", ("A", "B", "P"), length=5.0, sides={"P": {"A": 4.0, "B": 3.0, "side": "right"}})
    assert exact_places(link, SKETCH) == {"P": pytest.approx((3.2, -2.4), rel=1e-15)}


def test_without_a_length_the_first_two_points_are_as_far_apart_as_the_sketch_draws_them():
    sketch = dict(SKETCH, B=(3.0, 4.0))                 # 5 from A, at 53.13 deg
    link = Link("coupler", ("A", "B", "P"), sides={"P": {"A": 4.0, "B": 3.0, "side": "left"}})
    assert exact_places(link, sketch)["P"] == pytest.approx((3.2, 2.4), rel=1e-14)


def test_the_side_follows_the_order_of_the_links_points_not_of_the_table():
    sketch = dict(SKETCH)
    one = Link("c", ("A", "B", "P"), length=5.0, sides={"P": {"A": 4.0, "B": 3.0, "side": "left"}})
    other = Link("c", ("A", "B", "P"), length=5.0, sides={"P": {"B": 3.0, "A": 4.0, "side": "left"}})
    assert exact_places(one, sketch) == exact_places(other, sketch)
    assert one == other
    # the same triangle on a link listed B first: left of B -> A, the frame turned half a turn
    flipped = Link("c", ("B", "A", "P"), length=5.0, sides={"P": {"A": 4.0, "B": 3.0, "side": "left"}})
    assert exact_places(flipped, sketch)["P"] == pytest.approx((1.8, 2.4), rel=1e-14)


def test_a_point_measured_from_points_that_are_not_the_first_two():
    """A quaternary plate A-B-P-Q: P by its sides from A and B, Q by its sides from B and P,
    right of B -> P.  Q is checked by its distances and side in the frame, not by formula."""
    link = Link("plate", ("A", "B", "P", "Q"), length=5.0,
                sides={"P": {"A": 4.0, "B": 3.0, "side": "left"},
                       "Q": {"P": 2.5, "B": 4.0, "side": "right"}})
    places = exact_places(link, SKETCH)
    B, P, Q = (5.0, 0.0), places["P"], places["Q"]
    assert math.dist(Q, P) == pytest.approx(2.5, rel=1e-13)
    assert math.dist(Q, B) == pytest.approx(4.0, rel=1e-13)
    assert (P[0] - B[0]) * (Q[1] - B[1]) - (P[1] - B[1]) * (Q[0] - B[0]) < 0      # right of B -> P


def test_a_point_measured_from_a_point_as_drawn():
    """P is in neither local nor sides: it keeps its place relative to A and B as drawn,
    scaled with the link's length (here twice the sketch's), and Q is measured from it."""
    link = Link("plate", ("A", "B", "P", "Q"), length=10.0,
                sides={"Q": {"B": 5.0, "P": 5.0, "side": "left"}})
    places = exact_places(link, SKETCH)
    P = (6.0, 4.0)                                      # the sketch's (3, 2) times 10 / 5
    assert math.dist(places["Q"], (10.0, 0.0)) == pytest.approx(5.0, rel=1e-13)
    assert math.dist(places["Q"], P) == pytest.approx(5.0, rel=1e-13)


@pytest.mark.parametrize("dA, dB, place", [(2.0, 3.0, (2.0, 0.0)), (7.0, 2.0, (7.0, 0.0)),
                                           (2.0, 7.0, (-2.0, 0.0))])
def test_a_flat_triangle_needs_no_side(dA, dB, place):
    # by hand on A -> B = 5: 2 + 3 = 5 (between), 7 - 2 = 5 (beyond B), 7 - 2 = 5 (behind A)
    link = Link("bar", ("A", "B", "P"), length=5.0, sides={"P": {"A": dA, "B": dB}})
    assert exact_places(link, SKETCH)["P"] == pytest.approx(place, abs=1e-15)
    sided = Link("bar", ("A", "B", "P"), length=5.0, sides={"P": {"A": dA, "B": dB, "side": "right"}})
    assert exact_places(sided, SKETCH) == exact_places(link, SKETCH)


def test_local_places_come_through_unchanged():
    link = Link("coupler", ("A", "B", "P"), length=5.0, local={"P": (1.5, -0.25)})
    assert exact_places(link, SKETCH) == {"P": (1.5, -0.25)}
    assert exact_places(Link("coupler", ("A", "B", "P")), SKETCH) == {}


def test_exact_places_needs_the_links_points_in_the_sketch():
    link = Link("coupler", ("A", "B", "P"), sides={"P": {"A": 4.0, "B": 3.0, "side": "left"}})
    with pytest.raises(ModelError, match=r"^sketch: expected the place of every point of link "
                       r"'coupler', got none for 'P'$"):
        exact_places(link, {"A": (0, 0), "B": (5, 0)})
    with pytest.raises(ModelError, match=r"its first two points are at one place in the sketch"):
        exact_places(link, {"A": (0, 0), "B": (0, 0), "P": (1, 1)})


def fourbar(coupler: Link, P=(1.5, 2.0)) -> Mechanism:
    return Mechanism(
        "fb", (Point("O2", 0, 0), Point("A", 0, 1), Point("B", 3, 2), Point("O4", 3, 0),
               Point("P", *P), Point("Q", 2, 3)),
        (Link("ground", ("O2", "O4"), ground=True), Link("crank", ("O2", "A")), coupler,
         Link("rocker", ("O4", "B"))),
        tuple(Joint(f"j{p}", "R", ab, point=p) for p, ab in
              (("O2", ("ground", "crank")), ("A", ("crank", "coupler")),
               ("B", ("coupler", "rocker")), ("O4", ("ground", "rocker")))),
        (Input(joint="jO2"),))


def test_every_problem_of_sides_is_reported_at_once():
    coupler = Link("coupler", ("A", "B", "P", "Q"), sides={
        "P": {"A": 0.5, "B": 0.5, "side": "left"},           # A-B is sqrt(10) = 3.16228 apart
        "Q": {"A": 1.0, "O4": 1.0, "side": "up"},
        "A": {"B": 1.0, "P": 1.0, "side": "left"}})
    with pytest.raises(ModelError) as info:
        fourbar(coupler)
    assert info.value.problems == (
        "link 'coupler': sides.Q.O4: expected one of the link's points placed before 'Q' ('A', "
        "'B', 'P'), got 'O4'; points are placed in the order of the link's points",
        "link 'coupler': sides.Q.side: expected one of 'left', 'right', got 'up'",
        "link 'coupler': sides.A: expected one of the link's points after its first two ('P', "
        "'Q'), got 'A', its first point, which the link's frame places",
        "link 'coupler': sides.P: 'P' cannot be 0.5 m from 'A' and 0.5 m from 'B': 'A' and 'B' "
        "are 3.16228 m apart; the sides must satisfy |dA - dB| <= AB <= dA + dB; change a distance")


@pytest.mark.parametrize("sides, message", [
    ({"P": {"A": 0.0, "B": 1.0, "side": "left"}}, "sides.P.A: expected a positive length, got 0.0"),
    ({"P": {"A": -1, "B": 3.0, "side": "left"}}, "sides.P.A: expected a positive length, got -1.0"),
    ({"P": {"A": math.inf, "B": 3.0, "side": "left"}}, "sides.P.A: expected a positive length, got inf"),
    ({"P": {"A": math.nan, "B": 3.0, "side": "left"}}, "sides.P.A: expected a positive length, got nan"),
    ({"P": {"A": "2", "B": 3.0, "side": "left"}}, "sides.P.A: expected a positive length, got '2'"),
    ({"P": {"A": 1e-12, "B": 3.0, "side": "left"}},
     "sides.P.A: expected a length from 1e-09 m to 1e+09 m, got 1e-12 m"),
    ({"P": {"A": 2.0, "B": 2.0, "side": "Left"}},
     "sides.P.side: expected one of 'left', 'right', got 'Left' (did you mean 'left'?)"),
    ({"P": {"A": 2.0, "B": 2.0}},
     "sides.P.side: missing; 'P' may lie left or right of the line A -> B; say which: side = "
     "'left' or 'right'"),
    ({"P": (2.0, 2.0, "left")},
     "sides.P: expected the distances from two points of the link placed before it and a side, "
     "such as {A = 30, B = 40, side = 'left'}, got (2.0, 2.0, 'left')"),
    ({"P": {"A": 2.0, "side": "left"}},
     "sides.P: expected the distances from two points of the link placed before 'P' ('A', 'B'), "
     "such as {A = 30, B = 40, side = 'left'}, got 1 ('A')"),
    ({"P": {"A": 2.0, "Q": 2.0, "side": "left"}},
     "sides.P.Q: expected one of the link's points placed before 'P' ('A', 'B'), got 'Q'; points "
     "are placed in the order of the link's points"),
    ({"B": {"A": 2.0, "P": 2.0, "side": "left"}},
     "sides.B: expected one of the link's points after its first two ('P', 'Q'), got 'B', its "
     "second point, which the link's frame places"),
    ({"X": {"A": 2.0, "B": 2.0, "side": "left"}},
     "sides.X: expected one of the link's points after its first two ('P', 'Q'), got 'X'"),
    ([("P", 1.0)], "sides: expected a mapping of point = {point: distance, point: distance, "
     "'side': 'left' or 'right'}, got [('P', 1.0)]"),
])
def test_a_bad_side_is_refused_naming_the_field(sides, message):
    with pytest.raises(ModelError) as info:
        fourbar(Link("coupler", ("A", "B", "P", "Q"), sides=sides))
    assert info.value.problems == (f"link 'coupler': {message}",)


def test_a_point_given_both_ways_is_refused():
    coupler = Link("coupler", ("A", "B", "P"), local={"P": (1.0, 1.0)},
                   sides={"P": {"A": 2.0, "B": 2.0, "side": "left"}})
    with pytest.raises(ModelError, match=r"^mechanism 'fb': link 'coupler': sides\.P: 'P' is given in "
                       r"local too; give its place one way: remove it from local or from sides$"):
        fourbar(coupler)


def test_two_references_at_one_place_fix_nothing():
    coupler = Link("coupler", ("A", "B", "P", "Q"),
                   local={"P": (0.0, 0.0)}, sides={"Q": {"A": 1.0, "P": 1.0, "side": "left"}})
    with pytest.raises(ModelError, match=r"sides\.Q: 'A' and 'P' are at one place on the link, so "
                       r"their distances fix no place for 'Q'; measure from two points apart"):
        fourbar(coupler)


def test_a_ground_point_off_its_sides_is_refused_and_one_on_them_is_not():
    def model(G, sides):
        return Mechanism("pendulum", (Point("O", 0, 0), Point("E", 4, 0), Point("G", *G), Point("A", 0, 1)),
                         (Link("ground", ("O", "E", "G"), ground=True, sides={"G": sides}),
                          Link("arm", ("O", "A"))),
                         (Joint("jO", "R", ("ground", "arm"), point="O"),), (Input(joint="jO"),))
    # by hand: 3 from O and sqrt(3² + 4² - 2 x 3 x 4 x cos 90°) = 5 from E: G = (0, 3), left
    model((0.0, 3.0), {"O": 3.0, "E": 5.0, "side": "left"})
    with pytest.raises(ModelError, match=r"link 'ground': sides\.G: the ground's points are the frame "
                       r"and are not moved, but the sketch puts 'G' 6 m from where its sides place "
                       r"it, \(0, -3 m\); move 'G' there or correct its sides"):
        model((0.0, 3.0), {"O": 3.0, "E": 5.0, "side": "right"})


def test_sides_round_trip_through_plain_data():
    m = fourbar(Link("coupler", ("A", "B", "P", "Q"), sides={
        "P": {"A": 1.25, "B": 2, "side": "left"}, "Q": {"P": 1.0, "B": 1.5, "side": "right"}}))
    assert m.link("coupler").sides["P"] == {"A": 1.25, "B": 2.0, "side": "left"}
    assert type(m.link("coupler").sides["P"]["B"]) is float
    assert Mechanism.from_dict(m.to_dict()) == m
    assert m.to_dict()["links"][2]["sides"] == {"P": {"A": 1.25, "B": 2.0, "side": "left"},
                                                "Q": {"P": 1.0, "B": 1.5, "side": "right"}}
    assert Link("c", ("A", "B"), sides={}).sides is None
