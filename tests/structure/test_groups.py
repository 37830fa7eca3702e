"""Lie groups of displacements, connectivity along chains, and the Lie group method."""
import numpy as np
import pytest
from hypothesis import given, strategies as st

from kinelab.errors import ModelError
from kinelab.model import Joint, Link, Mechanism, Point
from kinelab.structure import (connectivity, displacement_group, generated_group, lie_mobility,
                               mobility)

from .models import bennett, fourbar, parallelogram_fivebar, sarrus, stewart


@pytest.mark.parametrize("label, kind, dim", [
    ("", "E", 0), ("Tz", "T", 1), ("Rz", "R", 1), ("Tx Ty", "T2", 2), ("Tz Rz", "C", 2),
    ("Tx Ty Tz", "T3", 3), ("Tx Ty Rz", "G", 3), ("Rx Ry Rz", "S", 3),
    ("Tx Ty Tz Rz", "X", 4), ("Tx Ty Tz Rx Ry Rz", "D", 6),
])
def test_herve_kinds(label, kind, dim):
    g = displacement_group(label)
    assert (g.kind, g.dim) == (kind, dim)


def test_notes_intersection_gives_tz():
    # *Mecanismos*, §2.2: legs 1-2-3-4 allow {Tx, Tz, Ry}, legs 1-5-6-4 {Ty, Tz, Rx}
    g = displacement_group("{Tx, Tz, Ry}") & displacement_group("{Ty, Tz, Rx}")
    assert g.label == "{Tz}" and g.kind == "T"


def test_not_a_group():
    with pytest.raises(ModelError, match=r"displacements \{Tx, Rz\} do not form a group: "
                                         r"combining them produces \{Tx, Ty, Rz\} \(G\)"):
        displacement_group("Tx Rz")
    with pytest.raises(ModelError, match="displacement 'Qx': expected Tx, Ty, Tz, Rx, Ry or Rz"):
        displacement_group("Tx Qx")


def test_where_the_axis_passes_matters_for_rotations_only():
    assert displacement_group("Rz", point=(1, 2, 0)) != displacement_group("Rz")
    assert displacement_group("Rz", point=(0, 0, 5)) == displacement_group("Rz")   # on the axis
    assert displacement_group("Tx Ty Rz", point=(1, 2, 0)) == displacement_group("Tx Ty Rz")
    assert displacement_group("Tz") <= displacement_group("Tx Tz Ry")
    assert not displacement_group("Ty") <= displacement_group("Tx Tz Ry")


def test_helical_pitch():
    g = generated_group([[0, 0, 1, 0, 0, 0.25]])
    assert g.kind == "H" and g.pitch == pytest.approx(0.25, abs=1e-12) and g.label == "{Hz}"
    # with the translations along the plane, a translating screw Y
    assert generated_group([[0, 0, 1, 0, 0, 0.25], [0, 0, 0, 1, 0, 0],
                            [0, 0, 0, 0, 1, 0]]).kind == "Y"


unit = st.lists(st.floats(-1, 1), min_size=3, max_size=3).filter(lambda v: np.linalg.norm(v) > 0.3)


@given(unit, unit, unit)
def test_two_revolutes_generate(u, p, q):
    u = np.array(u) / np.linalg.norm(u)
    p, q = np.array(p), np.array(q)
    rot = lambda axis, point: np.concatenate([axis, np.cross(point, axis)])  # noqa: E731
    # parallel axes: the planar gliding group normal to them
    assert generated_group([rot(u, p), rot(u, q)]).kind == ("G" if np.linalg.norm(np.cross(p - q, u)) > 1e-6 else "R")
    # axes through one point: the spherical group about it
    v = np.cross(u, [0.3, -0.5, 0.8])
    if np.linalg.norm(v) > 1e-3:
        assert generated_group([rot(u, p), rot(v / np.linalg.norm(v), p)]).kind == "S"


def test_sarrus_by_lie_groups():
    r = lie_mobility(sarrus(), "4")
    assert [leg.name for leg in r.legs] == ["RRR", "RRR"]
    assert [leg.group.label for leg in r.legs] == ["{Tx, Tz, Ry}", "{Ty, Tz, Rx}"]
    assert r.group.label == "{Tz}" and r.mobility == 1 and r.valid
    assert "intersection: {Tz} (T)" in r.explanation


@pytest.mark.parametrize("build, end", [(sarrus, "4"), (lambda: stewart("UPS"), "platform"),
                                        (lambda: stewart("SPS"), "platform")])
def test_lie_method_against_rank(build, end):
    # where the Lie method applies it counts every freedom, passive spins included
    model = build()
    r = lie_mobility(model, end)
    assert r.valid and r.mobility == mobility(model).freedoms


def test_lie_method_refuses_bennett():
    r = lie_mobility(bennett()[0], "l3")
    assert not r.valid and "a leg's motions are not a group" in r.explanation
    assert mobility(bennett()[0]).exact == 1


def test_fourbar_connectivity():
    c = connectivity(fourbar(), "ground", "coupler")
    assert [(ch.links, ch.freedoms, ch.connectivity) for ch in c.chains] == [
        (("ground", "crank", "coupler"), 2, 2), (("ground", "rocker", "coupler"), 2, 2)]
    assert c.overall == 1
    assert all(ch.group.label == "{Tx, Ty, Rz}" and not ch.is_group for ch in c.chains)


def test_connectivity_capped_by_the_space():
    # a planar serial arm of four R joints: 4 freedoms, but a link in the plane has 3
    xy = [(0, 0), (1, 0.2), (1.8, 0.9), (2.1, 1.9), (2.0, 2.8)]
    pts = tuple(Point(f"A{k}", *p) for k, p in enumerate(xy))
    links = (Link("ground", ("A0",), ground=True),) + tuple(
        Link(f"l{k}", (f"A{k - 1}", f"A{k}")) for k in range(1, 5))
    joints = tuple(Joint(f"j{k}", "R", (links[k].name, f"l{k + 1}"), point=f"A{k}")
                   for k in range(4))
    arm = Mechanism("RRRR arm", pts, links, joints)
    (chain,) = connectivity(arm, "ground", "l4").chains
    assert (chain.name, chain.freedoms, chain.connectivity) == ("RRRR", 4, 3)
    assert connectivity(arm, "ground", "l4").overall == 3
    assert connectivity(arm, "l1", "l3").chains[0].connectivity == 2
    assert mobility(arm).exact == 4


def test_parallelogram_connectivity():
    c = connectivity(parallelogram_fivebar(), "ground", "crank3")
    assert sorted(ch.connectivity for ch in c.chains) == [1, 3, 3]
    assert c.overall == 1


def test_sarrus_connectivity_of_the_plate():
    c = connectivity(sarrus(), "1", "4")
    assert [ch.connectivity for ch in c.chains] == [3, 3] and c.overall == 1
    assert all(ch.is_group for ch in c.chains)


@pytest.mark.parametrize("a, b, message", [
    ("ground", "nope", r"link 'nope' not found"),
    ("crank", "crank", r"links: expected two different links, got 'crank' twice"),
])
def test_connectivity_errors(a, b, message):
    with pytest.raises(ModelError, match=message):
        connectivity(fourbar(), a, b)
