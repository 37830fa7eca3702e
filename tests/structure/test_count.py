"""Kutzbach-Gruebler from counts, the pair catalogue and the counts of a model."""
import pytest
from hypothesis import given, strategies as st

from kinelab.errors import ModelError
from kinelab.model import JOINT_TYPES
from kinelab.structure import (joint_catalogue, kutzbach_gruebler, mobility, pair_counts,
                               pair_freedoms, space_dimension)

from .models import disk_cam_flat_follower, double_wishbone, sarrus, slider_crank


# *Mecanismos*, §2.1-2.2, each checked by hand with Eq. (2) or (3):
#   slider-crank   3(4-1) - 2*4          = 1
#   disk cam       3(3-1) - 2*2 - 1*1    = 1
#   suspension     6(4-1) - 5*2 - 3*2    = 2
#   RRRRRR         6(6-1) - 5*6          = 0
@pytest.mark.parametrize("links, pairs, space, expected", [
    (4, {1: 4}, "planar", 1),
    (3, {1: 2, 2: 1}, "planar", 1),
    (4, {1: 2, 3: 2}, "spatial", 2),
    (6, {1: 6}, "spatial", 0),
    (4, {1: 4}, "spherical", 1),
    (4, {1: 4}, "spatial", -2),
])
def test_notes_examples(links, pairs, space, expected):
    assert kutzbach_gruebler(links, pairs, space) == expected


@pytest.mark.parametrize("build, expected", [
    (slider_crank, 1), (disk_cam_flat_follower, 1), (double_wishbone, 2), (sarrus, 0)])
def test_count_from_the_model_matches_the_notes(build, expected):
    assert mobility(build()).kutzbach_gruebler == expected


def test_pair_counts_of_the_notes_models():
    assert pair_counts(disk_cam_flat_follower()) == {1: 2, 2: 1}
    assert pair_counts(double_wishbone()) == {1: 2, 3: 2}


def test_lambda_two_is_accepted_as_a_number():
    # two links, one P1 pair in a space of two freedoms: 2(2 - 1) - 1 = 1
    assert kutzbach_gruebler(2, {1: 1}, 2) == 1
    assert space_dimension(6) == 6


@given(st.integers(1, 12), st.dictionaries(st.integers(1, 6), st.integers(0, 10), max_size=6))
def test_general_formula(ne, pairs):
    expected = 6 * (ne - 1) - sum((6 - j) * n for j, n in pairs.items())
    assert kutzbach_gruebler(ne, pairs, "spatial") == expected


@given(st.integers(2, 10), st.integers(0, 5))
def test_adding_a_binary_link_with_two_revolutes_keeps_planar_mobility(ne, n2):
    # a dyad brings 3 freedoms and takes 2 + 2 - 1: one link and two R pairs replace one R
    before = kutzbach_gruebler(ne, {1: ne, 2: n2}, "planar")
    assert kutzbach_gruebler(ne + 1, {1: ne + 1, 2: n2}, "planar") == before + 1
    assert kutzbach_gruebler(ne + 2, {1: ne + 3, 2: n2}, "planar") == before


@pytest.mark.parametrize("space", [4, 1, "plane", 3.0, True, None])
def test_bad_lambda(space):
    with pytest.raises(ModelError, match=r"space: expected one of 'planar', 'spherical', "
                                         r"'spatial' or lambda = 2, 3 or 6, got"):
        kutzbach_gruebler(4, {1: 4}, space)


@pytest.mark.parametrize("links, pairs, message", [
    (0, {1: 4}, r"links: expected a whole number >= 1, got 0"),
    (4.5, {1: 4}, r"links: expected a whole number >= 1, got 4.5"),
    (4, {1: -1}, r"pairs\[1\]: expected a whole number >= 0, got -1"),
    (4, {4: 1}, r"pairs: a pair allows 1 to 3 freedoms when lambda = 3, got 4"),
    (4, {0: 1}, r"pairs: a pair allows 1 to 3 freedoms when lambda = 3, got 0"),
    (4, [4], r"pairs: expected a mapping \{freedoms of the pair: count\}, got list"),
])
def test_bad_counts(links, pairs, message):
    with pytest.raises(ModelError, match=message):
        kutzbach_gruebler(links, pairs, "planar")


def test_catalogue_classes():
    cat = {c.symbol: c for c in joint_catalogue()}
    assert set(cat) == set(JOINT_TYPES)
    assert {s: cat[s].pair_class for s in ("R", "P", "H", "C", "U", "S", "E")} == {
        "R": "P1", "P": "P1", "H": "P1", "C": "P2", "U": "P2", "S": "P3", "E": "P3"}
    # higher pairs: 1 or 2 freedoms in the plane, point contacts in space
    assert [(cat[s].planar, cat[s].spatial) for s in ("cam", "gear", "rolling", "pin_in_slot")] == [
        (2, 5), (2, 5), (1, 3), (2, 4)]
    assert cat["S"].planar is None and cat["P"].spherical is None and cat["U"].spherical == 2


@pytest.mark.parametrize("joint, space, message", [
    ("S", "planar", "does not exist in a planar mechanism"),
    ("C", "spherical", "has no meaning in a spherical mechanism"),
    ("X", "spatial", r"joint type: expected one of 'R', 'P'"),
    ("R", "space", r"space: expected one of 'planar', 'spherical', 'spatial', got 'space'"),
])
def test_pair_freedoms_errors(joint, space, message):
    with pytest.raises(ModelError, match=message):
        pair_freedoms(joint, space)


def test_pair_classes_by_name():
    assert kutzbach_gruebler(4, {"P1": 2, "P3": 2}, "spatial") == 2
    with pytest.raises(ModelError, match=r"a pair allows 1 to 3 freedoms when lambda = 3, got 'P5'"):
        kutzbach_gruebler(4, {"P5": 1}, "planar")
