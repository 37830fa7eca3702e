"""Structural synthesis of planar chains with simple revolute joints."""
import itertools

import numpy as np
import pytest
from hypothesis import given, strategies as st

from kinelab.errors import ModelError
from kinelab.model import Joint, Link, Mechanism, Point
from kinelab.structure import chain_of, count_chains, mobility, planar_chains
from kinelab.structure._canon import canonical_form, orbits


# The classical counts of chains without rigid parts (e.g. Tsai, Mechanism Design:
# Enumeration of Kinematic Structures, 2001): 1-DOF 1, 2, 16, 230; 2-DOF 1, 4, 40.
@pytest.mark.parametrize("links, dof, expected", [
    (4, 1, 1), (6, 1, 2), (8, 1, 16), (10, 1, 230),
    (5, 2, 1), (7, 2, 4), (9, 2, 40), (6, 3, 1),
])
def test_counts(links, dof, expected):
    assert count_chains(links, mobility=dof) == expected


def test_eight_link_assortments():
    # 4 binary + 4 ternary: 9 chains; 5 binary + 2 ternary + 1 quaternary: 5; 6 + 0 + 2: 2
    by = {}
    for c in planar_chains(8):
        key = tuple(c.assortment.get(d, 0) for d in (2, 3, 4))
        by[key] = by.get(key, 0) + 1
    assert by == {(4, 4, 0): 9, (5, 2, 1): 5, (6, 0, 2): 2}


@pytest.mark.parametrize("links, mechanisms", [(4, 1), (6, 5), (8, 71)])
def test_inversions(links, mechanisms):
    # 6 links: Watt (2 inversions) and Stephenson (3); 8 links: 71 mechanisms
    assert sum(len(c.inversions()) for c in planar_chains(links)) == mechanisms


def test_watt_and_stephenson_by_hand():
    # Watt: ternaries T1, T2 joined directly, binaries a, b and c, d between them
    watt = [("T1", "T2"), ("T1", "a"), ("a", "b"), ("b", "T2"), ("T1", "c"), ("c", "d"), ("d", "T2")]
    # Stephenson: ternaries joined through a, d (one binary) and b-c (two)
    steph = [("T1", "a"), ("a", "T2"), ("T1", "d"), ("d", "T2"), ("T1", "b"), ("b", "c"), ("c", "T2")]
    names = {}
    for label, edges in (("Watt", watt), ("Stephenson", steph)):
        chain = chain_of(_model(edges))
        names[label] = chain.name
        assert chain.mobility == 1 and chain.assortment == {2: 4, 3: 2}
    assert names == {"Watt": "Watt", "Stephenson": "Stephenson"}
    inv = {c.name: sorted(len(i.equivalent) for i in c.inversions()) for c in planar_chains(6)}
    assert inv == {"Watt": [2, 4], "Stephenson": [2, 2, 2]}


def _model(edges):
    """A planar model of a chain given by its joints, drawn in general position."""
    rng = np.random.default_rng(3)
    names = sorted({n for e in edges for n in e})
    pts = [Point(f"p{k}", *rng.standard_normal(2)) for k in range(len(edges))]
    carried = {n: [f"p{k}" for k, e in enumerate(edges) if n in e] for n in names}
    links = tuple(Link(n, tuple(carried[n]), ground=(n == names[0])) for n in names)
    joints = tuple(Joint(f"j{k}", "R", e, point=f"p{k}") for k, e in enumerate(edges))
    return Mechanism("chain", tuple(pts), links, joints)


def test_no_chain_has_a_triangle_or_a_repeated_form():
    for n in (6, 8, 10):
        chains = planar_chains(n)
        forms = {canonical_form(c.adjacency.tolist())[0] for c in chains}
        assert len(forms) == len(chains)
        for c in chains:
            a = c.adjacency
            assert np.trace(a @ a @ a) == 0           # no 3-link loop (rigid triangle)
            assert min(c.degrees) >= 2 and len(c.joints) == (3 * n - 4) // 2


def test_every_eight_link_mechanism_moves_once():
    # the rank method, independent of the counting, on a sketch of every inversion
    for chain in planar_chains(8):
        for inv in chain.inversions():
            m = inv.to_mechanism()
            r = mobility(m)
            assert (r.kutzbach_gruebler, r.exact) == (1, 1)
            assert len(m.inputs) == 1 and chain_of(m).name == chain.name


def test_two_dof_sketches_get_two_inputs():
    for chain in planar_chains(7, mobility=2):
        m = chain.to_mechanism(ground=0)
        assert mobility(m).exact == 2 and len(m.inputs) == 2


@given(st.integers(0, 229), st.randoms(use_true_random=False))
def test_canonical_form_ignores_labels(k, rnd):
    chain = planar_chains(10)[k]
    perm = list(range(chain.links))
    rnd.shuffle(perm)
    a = chain.adjacency
    b = a[np.ix_(perm, perm)]
    assert canonical_form(b.tolist())[0] == canonical_form(a.tolist())[0]


def test_orbits_of_a_cycle_and_a_star():
    cycle = [[int(abs(i - j) in (1, 5)) for j in range(6)] for i in range(6)]
    assert orbits(cycle) == [list(range(6))]
    star = [[int((i == 0) != (j == 0)) for j in range(4)] for i in range(4)]
    assert orbits(star) == [[0], [1, 2, 3]]


def test_brute_force_six_links():
    # every graph with 6 vertices and 7 edges, minimum degree 2, no rigid part: 2 classes
    pairs = list(itertools.combinations(range(6), 2))
    forms = set()
    for edges in itertools.combinations(pairs, 7):
        a = np.zeros((6, 6), dtype=int)
        for u, v in edges:
            a[u, v] = a[v, u] = 1
        if a.sum(axis=1).min() < 2 or np.trace(a @ a @ a):
            continue
        # rigid parts with 6 links and 7 joints: a triangle, or 5 links with 6 joints
        if any(a[np.ix_(s, s)].sum() // 2 >= 6 for s in itertools.combinations(range(6), 5)):
            continue
        forms.add(canonical_form(a.tolist())[0])
    assert len(forms) == 2


@pytest.mark.parametrize("links, dof, message", [
    (5, 1, r"mobility 1 is impossible with 5 links: J = \(3N - 3 - F\) / 2 = 5.5"),
    (6, 4, r"mobility 4 is impossible with 6 links"),
    (7, 6, r"at most N - 3 = 4 freedoms"),
    (3, 1, r"links: expected a whole number >= 4, got 3"),
    (6, 0, r"mobility: expected a whole number >= 1, got 0"),
    (6, -1, r"mobility: expected a whole number >= 1, got -1"),
    (6.0, 1, r"links: expected a whole number >= 4, got 6.0"),
])
def test_impossible_counts(links, dof, message):
    with pytest.raises(ModelError, match=message):
        count_chains(links, mobility=dof)


def test_chain_of_refuses_other_joints():
    m = Mechanism("slider", (Point("O", 0, 0), Point("A", 1, 0)),
                  (Link("ground", ("O",), ground=True), Link("s", ("A",))),
                  (Joint("p", "P", ("ground", "s"), point="A", axis=(1.0, 0.0)),))
    with pytest.raises(ModelError, match="a kinematic chain here has revolute joints only"):
        chain_of(m)


def test_to_mechanism_checks_the_ground():
    with pytest.raises(ModelError, match=r"ground: expected a link of the chain, 0 to 3, got 4"):
        planar_chains(4)[0].to_mechanism(ground=4)
