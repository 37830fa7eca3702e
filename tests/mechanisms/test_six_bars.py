"""Watt and Stephenson six-bars built from their link lengths, with a mode for each dyad.

The checks use plain geometry on the built sketch (distances, the side of a line) and the
engine's own analysis of it (loop closure on the output points, and the closed form placed
at another crank angle against the engine's continuation to that angle).
"""
import itertools
import math

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from tests.kinematics.checks import closure_residual

MODES = list(itertools.product(("open", "crossed"), repeat=2))

# Lengths with which each six-bar closes at its default sketch's crank angle on all four
# modes, and whose first loop is a crank-rocker (the crank turns fully), m.  Some pairs are
# spelled backwards on purpose.
WATT = {"O2-A": 0.8, "B-A": 4.0, "O4-B": 4.2, "O4-C": 2.0, "C-B": 2.5, "C-D": 2.0, "O6-D": 2.4}
STEPHENSON = {"O2-A": 0.9, "A-B": 4.2, "A-C": 2.4, "B-C": 2.0, "B-O4": 4.5, "C-D": 3.5, "O6-D": 3.5}
CASES = {"watt6": (kl.mechanisms.watt6, WATT, ("C", "O4", "B")),
         "stephenson6": (kl.mechanisms.stephenson6, STEPHENSON, ("C", "A", "B"))}

# the constructors' default sketches, as written before lengths could be given
DEFAULTS = {
    "watt6": {"O2": (0.0, 0.0), "A": (0.5, 0.866), "B": (3.52, 3.1), "O4": (5.63, -0.76),
              "C": (4.51, 1.21), "O6": (7.07, 0.04), "D": (6.32, 2.53)},
    "stephenson6": {"O2": (0.0, 0.0), "A": (0.0, 1.0), "B": (3.68, 2.75), "O4": (5.69, -1.03),
                    "C": (2.18, 3.47), "O6": (5.92, 2.14), "D": (4.34, 5.26)},
}


def xy(m, p):
    return np.array(m.point(p).xy)


def left(m, X, Z, P):
    """Twice the signed area of X, Z, P: > 0 when P is left of the line X -> Z."""
    (x1, y1), (x2, y2) = xy(m, Z) - xy(m, X), xy(m, P) - xy(m, X)
    return x1 * y2 - y1 * x2


def sketch_lengths(m):
    return {f"{a}-{b}": math.dist(m.point(a).xy, m.point(b).xy)
            for link in m.links if not link.ground
            for i, a in enumerate(link.points) for b in link.points[i + 1:]}


def same_pair(lengths, key):
    a, b = key.split("-")
    return lengths[key] if key in lengths else lengths[f"{b}-{a}"]


# -- lengths -------------------------------------------------------------------------------
@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("modes", MODES)
def test_distances_equal_the_given_lengths(name, modes):
    make, lengths, _ = CASES[name]
    m = make(lengths=lengths, branch=modes)
    measured = sketch_lengths(m)
    assert len(measured) == len(lengths) == 7
    for key, d in measured.items():
        # exact algebra on circle intersections: a few roundings
        assert d == pytest.approx(same_pair(lengths, key), rel=1e-12, abs=0), key
    for p in ("O2", "O4", "O6"):
        assert m.point(p).xy == DEFAULTS[name][p]


@pytest.mark.parametrize("name", CASES)
def test_pairs_not_given_keep_their_sketch_distance(name):
    make = CASES[name][0]
    sketch = sketch_lengths(make())
    m = make(lengths={"O2-A": 1.2, "C-D": sketch["C-D"] * 1.1})
    measured = sketch_lengths(m)
    assert measured["O2-A"] == pytest.approx(1.2, rel=1e-12, abs=0)
    assert measured["C-D"] == pytest.approx(sketch["C-D"] * 1.1, rel=1e-12, abs=0)
    for key in set(sketch) - {"O2-A", "C-D"}:
        assert measured[key] == pytest.approx(sketch[key], rel=1e-12, abs=0), key


@pytest.mark.parametrize("name", CASES)
def test_the_sketch_lengths_rebuild_the_sketch(name):
    """Given its own lengths and modes, the closed form puts every point back where the
    default sketch has it (the crank keeps the sketch's angle, C its side)."""
    make = CASES[name][0]
    m = make(lengths=sketch_lengths(make()), branch=("open", "open"))
    for p, ref in DEFAULTS[name].items():
        assert np.max(np.abs(xy(m, p) - ref)) < 1e-12 * 10, p     # sketch size about 10 m


# -- modes ---------------------------------------------------------------------------------
@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("modes", MODES)
def test_each_mode_puts_the_middle_joint_on_its_side(name, modes):
    make, lengths, (P, X, Z) = CASES[name]
    m = make(lengths=lengths, branch=modes)
    side = {"open": 1.0, "crossed": -1.0}
    assert np.sign(left(m, "A", "O4", "B")) == side[modes[0]]     # B left of A -> O4 when open
    assert np.sign(left(m, "C", "O6", "D")) == side[modes[1]]     # D left of C -> O6 when open
    # the ternary link's third point stays on the sketch's side of its base
    assert np.sign(left(m, X, Z, P)) == np.sign(left(make(), X, Z, P))
    # and the crank on the sketch's angle
    a = xy(m, "A")
    ref = np.array(DEFAULTS[name]["A"])
    assert math.atan2(a[1], a[0]) == pytest.approx(math.atan2(ref[1], ref[0]), abs=1e-14)


@pytest.mark.parametrize("name", CASES)
def test_the_four_mode_combinations_are_four_mechanisms(name):
    make, lengths, _ = CASES[name]
    built = [make(lengths=lengths, branch=modes) for modes in MODES]
    for m1, m2 in itertools.combinations(built, 2):
        apart = max(np.linalg.norm(xy(m1, p) - xy(m2, p)) for p in ("B", "C", "D"))
        assert apart > 0.1
    assert [m.parameters["branch"] for m in built] == MODES


@pytest.mark.parametrize("name", CASES)
def test_default_modes_are_the_sketch_modes(name):
    make, lengths, _ = CASES[name]
    m = make(lengths=lengths)
    assert m.parameters["branch"] == ("open", "open")   # both defaults sketch open dyads
    assert left(m, "A", "O4", "B") > 0 and left(m, "C", "O6", "D") > 0
    moved = {"D": (7.5, -1.0)}           # right of C -> O6 in both default sketches
    assert make(points=moved, lengths=lengths).parameters["branch"] == ("open", "crossed")


@pytest.mark.parametrize("name", CASES)
def test_without_lengths_or_branch_the_mechanism_is_the_sketch(name):
    make = CASES[name][0]
    m = make()
    assert {p.name: p.xy for p in m.points} == DEFAULTS[name]
    assert m.parameters == {"kind": name, "points": DEFAULTS[name]}
    assert set(m.joint_names) == {"jO2", "jA", "jB", "jO4", "jC", "jD", "jO6"}


# -- the analysis of the built six-bar -------------------------------------------------------
@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("modes", MODES)
def test_the_built_six_bar_closes_over_a_turn(name, modes):
    make, lengths, _ = CASES[name]
    m = make(lengths=lengths, branch=modes)
    q = np.radians(np.arange(0.0, 360.0, 2.0))
    sol = kl.analyze(m, q=q, at_singular="flag")
    assert sol.assembled.all()
    assert closure_residual(sol) < 1e-12 * 10                     # sketch size about 10 m


@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("modes", MODES)
def test_closed_form_at_another_angle_against_the_engine(name, modes):
    """The constructor placed at crank angle q (a sketch with A there) agrees with the
    engine's continuation from the default sketch angle to q, on the same modes."""
    make, lengths, _ = CASES[name]
    m = make(lengths=lengths, branch=modes)
    q0 = math.atan2(*xy(m, "A")[::-1])
    for q in (q0 + 0.4, q0 - 0.7):
        sol = kl.analyze(m, q=q)
        there = make(points={"A": (math.cos(q), math.sin(q))}, lengths=lengths, branch=modes)
        for p in ("A", "B", "C", "D"):
            assert np.max(np.abs(sol.position(p) - xy(there, p))) < 1e-10, (q, p)


def test_sketch_angle_that_does_not_close_moves_to_the_nearest_range_that_does():
    # A-B + O4-B = 4.9 m reaches O4 only when A is within 4.9 m of it: the crank must point
    # roughly at O4 (-7.7 deg), not up at the sketch's 60 deg
    m = kl.mechanisms.watt6(lengths={"A-B": 0.5})
    a = xy(m, "A")
    q = math.atan2(a[1], a[0])
    assert np.linalg.norm(xy(m, "O4") - a) < 0.5 + math.dist(m.point("O4").xy, m.point("B").xy)
    ranges = kl.kinematics.reachable_ranges(m)
    inside = [r for r in ranges if r[0] <= q <= r[1]]
    assert len(inside) == 1
    sol = kl.analyze(m, q=np.linspace(*inside[0], 50)[1:-1])
    assert sol.assembled.all()
    assert closure_residual(sol) < 1e-12 * 10


# -- bad input -----------------------------------------------------------------------------
WATT_PAIRS = "'O2-A', 'A-B', 'O4-B', 'O4-C', 'B-C', 'C-D', 'O6-D'"


@pytest.mark.parametrize("kwargs, message", [
    ({"lengths": {"O2-X": 1.0}},
     rf"^lengths\['O2-X'\]: expected a pair 'X-Y' of points of one link, one of {WATT_PAIRS}, got 'O2-X'$"),
    ({"lengths": {"A-C": 1.0}},
     rf"^lengths\['A-C'\]: A and C are not on one link; expected one of {WATT_PAIRS}$"),
    ({"lengths": {"O4-O6": 1.0}},
     r"^lengths\['O4-O6'\]: the ground pivots O2, O4, O6 come from the sketch; move them with points= "
     r"instead$"),
    ({"lengths": {"O2-A": 0.0, "C-D": -1.0}},
     r"^lengths\['O2-A'\]: expected a positive length \(m\), got 0.0\n"
     r"lengths\['C-D'\]: expected a positive length \(m\), got -1.0$"),
    ({"lengths": {"O2-A": 1.7976931348623157e308}},      # its square would overflow
     r"^lengths\['O2-A'\]: expected a length from 1e-09 m to 1e\+09 m, got 1.79769e\+308 m$"),
    ({"lengths": {"O2-A": 1.0, "A-O2": 1.0}},
     r"^lengths\['A-O2'\]: the pair O2-A is given twice \(as 'O2-A' too\); keep one$"),
    ({"lengths": [1.0]},
     r"^lengths: expected a mapping of point pairs such as 'O2-A' to lengths \(m\), got \[1.0\]$"),
    ({"lengths": {"O4-B": 2.0, "O4-C": 1.0, "B-C": 3.5}},
     r"^lengths\['B-C'\]: the triangle O4-B-C of link 'rocker' cannot close: expected B-C <= O4-B \+ "
     r"O4-C = 3 m, got 3.5 m; shorten B-C or lengthen O4-B or O4-C$"),
    # by hand: |O2 O4| = hypot(5.63, 0.76) = 5.681065, crank |O2 A| = hypot(0.5, 0.866) = 0.999978;
    # A comes within 5.681065 - 0.999978 = 4.681087 m of O4 and gets 6.681043 m from it
    ({"lengths": {"A-B": 0.5, "O4-B": 4.0}},
     r"^lengths: dyad A-B-O4 closes at no crank angle: expected A-B \+ O4-B >= 4.68109 m, the closest "
     r"A comes to O4 over a turn of the crank, got 4.5 m; lengthen A-B or O4-B$"),
    ({"lengths": {"A-B": 12.0, "O4-B": 4.0}},
     r"^lengths: dyad A-B-O4 closes at no crank angle: expected \|A-B - O4-B\| <= 6.68104 m, the "
     r"farthest A gets from O4 over a turn of the crank, got 8 m; make A-B and O4-B closer in length$"),
    ({"lengths": {"C-D": 0.5, "O6-D": 0.5}},
     r"^lengths: dyad C-D-O6 closes at no crank angle: expected C-D \+ O6-D >= [\d.]+ m, the closest "
     r"C comes to O6 where dyad A-B-O4 closes, got 1 m; lengthen C-D or O6-D$"),
    ({"branch": "open"},
     r"^branch: expected a pair of 'open'/'crossed', one per dyad \(A-B-O4, C-D-O6\), got 'open'$"),
    ({"branch": ("open", "cross")}, r"^branch\[1\]: expected one of 'open', 'crossed', got 'cross' \(did you mean 'crossed'\?\)$"),
])
def test_bad_input_says_what_and_where(kwargs, message):
    with pytest.raises(ModelError, match=message):
        kl.mechanisms.watt6(**kwargs)


def test_a_straight_sketch_dyad_needs_a_branch():
    # D on the line C -> O6: the sketch shows no mode for the second dyad
    pts = {"D": (4.51 + 2 * (7.07 - 4.51), 1.21 + 2 * (0.04 - 1.21))}
    with pytest.raises(ModelError, match=r"^branch: the sketch puts dyad C-D-O6 straight, so its "
                       r"assembly mode is undefined; give branch=\(\.\.\., \.\.\.\) or move a point"):
        kl.mechanisms.watt6(points=pts, lengths={"C-D": 2.0})
    m = kl.mechanisms.watt6(points=pts, lengths={"C-D": 2.0, "O6-D": 2.5}, branch=("open", "open"))
    assert left(m, "C", "O6", "D") > 0


def test_the_closest_distance_in_a_message_is_the_true_one():
    """The second dyad's message quotes the smallest |C - O6| where the first dyad closes;
    a sweep of the engine over the crank's turn finds the same (to its sampling)."""
    m = kl.mechanisms.watt6()
    sol = kl.analyze(m, q=np.radians(np.arange(0.0, 360.0, 0.05)))
    closest = float(np.min(np.linalg.norm(sol.position("C") - xy(m, "O6"), axis=1)))
    with pytest.raises(ModelError) as info:
        kl.mechanisms.watt6(lengths={"C-D": 0.5, "O6-D": 0.5})
    quoted = float(str(info.value).split(">= ")[1].split(" m")[0])
    assert quoted == pytest.approx(closest, rel=1e-5)


def test_stephenson_names_its_own_pairs_and_triangle():
    with pytest.raises(ModelError, match=r"one of 'O2-A', 'A-B', 'A-C', 'B-C', 'O4-B', 'C-D', 'O6-D'"):
        kl.mechanisms.stephenson6(lengths={"O4-C": 1.0})
    with pytest.raises(ModelError, match=r"^lengths\['A-B'\]: the triangle A-B-C of link 'coupler' "
                       r"cannot close: expected A-B <= A-C \+ B-C = 3 m, got 4 m"):
        kl.mechanisms.stephenson6(lengths={"A-B": 4.0, "A-C": 1.0, "B-C": 2.0})


def test_triad6_from_its_lengths_keeps_the_sketched_assembly():
    """The default triad six-bar's own distances, each changed a little, as lengths: the
    triad is assembled by Newton-Raphson near the sketch, the distances are the lengths,
    and the analysis from it closes."""
    base = kl.mechanisms.triad6()
    xy = {p.name: np.array(p.xy) for p in base.points}
    want = {"O2-A": 0.55, "A-C": 2.85, "C-D": 0.4, "C-E": 2.5, "D-E": 2.2, "D-O4": 2.2,
            "E-O6": 2.8}
    t6 = kl.mechanisms.triad6(lengths=want)
    for pair, length in want.items():
        a, b = pair.split("-")
        assert math.dist(t6.point(a).xy, t6.point(b).xy) == pytest.approx(length, rel=1e-12)
    # the ternary link keeps its orientation, and every point stays near its sketch
    def left(P, Q, R):
        return (Q[0] - P[0]) * (R[1] - P[1]) - (Q[1] - P[1]) * (R[0] - P[0])
    new = {p.name: np.array(p.xy) for p in t6.points}
    assert left(new["C"], new["D"], new["E"]) * left(xy["C"], xy["D"], xy["E"]) > 0
    assert max(np.hypot(*(new[p] - xy[p])) for p in xy) < 0.3
    sol = kl.analyze(t6, np.linspace(0.0, 2 * math.pi, 73))
    assert closure_residual(sol) < 1e-10


def test_triad6_lengths_that_do_not_close_near_the_sketch():
    with pytest.raises(kl.errors.ModelError, match="the triad C-D-E does not close with these lengths"):
        kl.mechanisms.triad6(lengths={"D-O4": 9.0})
