"""Only real numbers of sizes kinelab computes with, and printable names, make a model; and
checking a model takes time linear in its size."""
import dataclasses
import datetime
import time

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.model import (MAX_LENGTH, MAX_LINKS, MAX_RATE, MAX_TURNS, Input, Joint, Link, Mechanism,
                           Point)

NOT_NUMBERS = [True, 1 + 2j, "1", datetime.datetime(2020, 1, 1), 10 ** 5000, None]


def fourbar():
    return kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)


def replace_point(m, **change):
    return dataclasses.replace(m, points=(dataclasses.replace(m.points[0], **change),) + m.points[1:])


@pytest.mark.parametrize("value", NOT_NUMBERS, ids=lambda v: type(v).__name__)
def test_a_coordinate_is_a_real_number(value):
    with pytest.raises(ModelError, match=r"point 'O2': coordinates must be finite numbers"):
        replace_point(fourbar(), x=value)


def test_a_coordinate_is_at_most_max_length():
    with pytest.raises(ModelError, match=r"point 'O2': coordinates: expected at most 1e\+09 m in size, "
                                         r"got \(1e\+300, 0, 0\) m"):
        replace_point(fourbar(), x=1e300)
    replace_point(fourbar(), x=MAX_LENGTH / 2)     # within: accepted


@pytest.mark.parametrize("field", ["mass", "inertia", "length"])
@pytest.mark.parametrize("value", [True, 1j, "2"], ids=repr)
def test_link_fields_are_real_numbers(field, value):
    m = fourbar()
    crank = dataclasses.replace(m.links[1], **{field: value})
    with pytest.raises(ModelError, match=rf"link 'crank': {field}: expected a positive number"):
        dataclasses.replace(m, links=(m.links[0], crank) + m.links[2:])


@pytest.mark.parametrize("field", ["speed", "acceleration"])
@pytest.mark.parametrize("value", [True, 1j, "2", datetime.date(2020, 1, 1)], ids=repr)
def test_input_rates_are_real_numbers(field, value):
    with pytest.raises(ModelError, match=rf"inputs\[0\]: {field}: expected a finite number"):
        dataclasses.replace(fourbar(), inputs=(Input(joint="jO2", **{field: value}),))


def test_input_rates_whose_squares_overflow_are_refused():
    # 1e300 rad/s squared is inf: the accelerations would be inf in every table
    with pytest.raises(ModelError, match=r"inputs\[0\]: speed: expected at most 1e\+100 rad/s in "
                                         r"size \(accelerations take its square\), got 1e\+300 rad/s"):
        dataclasses.replace(fourbar(), inputs=(Input(joint="jO2", speed=1e300),))
    dataclasses.replace(fourbar(), inputs=(Input(joint="jO2", speed=MAX_RATE),))
    with pytest.raises(ModelError, match=r"inputs\[0\]: acceleration: expected at most 1e\+100 "
                                         r"rad/s\^2 in size \(times a length it must stay far "
                                         r"from overflow\), got 1e\+300 rad/s\^2"):
        dataclasses.replace(fourbar(), inputs=(Input(joint="jO2", acceleration=1e300),))


def test_an_angle_range_is_within_max_turns():
    turns = 2 * np.pi * MAX_TURNS
    dataclasses.replace(fourbar(), inputs=(Input(joint="jO2", range=(-turns, turns)),))
    with pytest.raises(ModelError, match=r"inputs\[0\]: range: expected angles within 1000 "
                                         r"turns of 0 either way"):
        dataclasses.replace(fourbar(), inputs=(Input(joint="jO2", range=(0.0, 1.01 * turns)),))
    with pytest.raises(ModelError, match=r"inputs\[0\]: range: expected two finite numbers"):
        dataclasses.replace(fourbar(), inputs=(Input(joint="jO2", range=(0.0, True)),))


@pytest.mark.parametrize("name, shown", [("a\nb", r"'a\nb'"), ("\ud800", r"'\ud800'"),
                                          ("\x1b[31mP", r"'\x1b[31mP'"), ("P\x00", r"'P\x00'"),
                                          ("", "''"), (["P"], "['P']")])
def test_names_are_printable_text(name, shown):
    with pytest.raises(ModelError) as info:
        replace_point(fourbar(), name=name)
    assert f"got {shown}" in str(info.value)
    assert str(info.value).count("\n") == 0


def test_a_lookup_of_a_long_unknown_name_stays_short():
    with pytest.raises(ModelError) as info:
        fourbar().point("Q" * 100_000)
    assert len(str(info.value)) < 300


# -- linear work --------------------------------------------------------------------------
def pendulums(n: int, per_link: int = 5) -> Mechanism:
    """A ground and ``n`` pendulums pinned to it, each carrying ``per_link`` points, all used."""
    points, links, joints = [Point("g", -1.0, 0.0)], [], []
    for k in range(n):
        names = tuple(f"p{k}_{i}" for i in range(per_link))
        points += [Point(p, float(k), float(i)) for i, p in enumerate(names)]
        links.append(Link(f"l{k}", names))
        joints.append(Joint(f"j{k}", "R", ("ground", f"l{k}"), point=names[0]))
    ground = Link("ground", ("g",) + tuple(j.point for j in joints), ground=True)
    return Mechanism("pendulums", tuple(points), (ground, *links), tuple(joints))


def test_a_model_beyond_the_size_limits_is_refused_by_its_counts():
    # 100,000 points, 20,000 links: refused by the counts, before any check that walks the
    # model (which must stay linear: with sets and dictionaries it is about a second).
    start = time.perf_counter()
    with pytest.raises(ModelError) as info:
        pendulums(20_000)
    assert time.perf_counter() - start < 60.0
    assert [p.split(";")[0] for p in info.value.problems] == [
        "links: expected at most 200, got 20,001", "joints: expected at most 400, got 20,000",
        "points: expected at most 2,000, got 100,001"]
    m = pendulums(MAX_LINKS - 1)                # at the limit: the ground and 199 pendulums
    assert len(m.links) == MAX_LINKS and m.links_carrying("p198_0") == ("ground", "l198")


def test_a_slide_axis_of_absurd_size_is_refused():
    """Only its direction counts, but a component of 1e308 overflows its norm's square."""
    sc = kl.mechanisms.slider_crank(1.0, 3.0)
    joints = tuple(dataclasses.replace(j, axis=(1.79e308, 0.0)) if j.name == "slide" else j
                   for j in sc.joints)
    with pytest.raises(ModelError, match=r"joint 'slide': axis: expected a direction whose "
                                         r"components are at most 1e100 in size"):
        Mechanism("sc", sc.points, sc.links, joints, sc.inputs)
