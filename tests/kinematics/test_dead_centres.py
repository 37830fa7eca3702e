"""Dead centres (K = 0 of an output) and toggles (det J = 0) against closed forms.

Slider-crank, crank r, rod l, slide line y = e (B to the right of A): the slider stops where
O2, A and B are collinear.  Crank and rod stretched out: B = (l + r)(cos q, sin q) on y = e,
so q = asin(e / (l + r)) and x = sqrt((l + r)^2 - e^2).  Folded: B = (l - r)(cos p, sin p)
with the crank pointing the other way, q = p + pi = pi + asin(e / (l - r)) and
x = sqrt((l - r)^2 - e^2).  det J = l cos(theta3) (rows: x and y loop closure; columns:
theta3, x), zero only where the rod is perpendicular to the slide, |r sin q - e| = l:
never when r + |e| < l.

Crank-rocker O2 A B O4 (ground d, crank a, coupler b, rocker c): the rocker turns back where
crank and coupler are collinear, |O2 B| = a + b or b - a; then B is where the circles about
O2 (that radius) and O4 (radius c) meet, and q is the angle of O2 B (stretched) or that plus
pi (folded).
"""
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinelab as kl
from kinelab.errors import ModelError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
RAD_TOL = 1e-9      # the brief's: refined input values agree with the closed forms to 1e-9 rad


def turn(a):
    """Angles brought to [0, 2 pi)."""
    return np.mod(a, 2 * np.pi)


def close_on_circle(a, b, tol):
    return abs(math.remainder(a - b, 2 * math.pi)) <= tol


@pytest.mark.parametrize("r, l, e", [(1.0, 3.0, 0.0), (1.0, 3.0, 0.5), (0.05, 0.18, -0.02),
                                     (40.0, 100.0, 25.0)])
def test_slider_crank_dead_centres_against_collinear_crank_and_rod(r, l, e):
    sc = kl.mechanisms.slider_crank(crank=r, rod=l, offset=e)
    dc = kl.kinematics.dead_centres(sc, "slide", 0.0, 2 * np.pi)
    stretched = (math.asin(e / (l + r)), math.sqrt((l + r) ** 2 - e * e))
    folded = (math.pi + math.asin(e / (l - r)), math.sqrt((l - r) ** 2 - e * e))
    expected = sorted([stretched, folded], key=lambda t: turn(t[0]))
    got = sorted(zip(turn(dc.q), dc.value), key=lambda t: t[0])
    assert len(got) == 2
    for (q, x), (q_ref, x_ref) in zip(got, expected):
        assert close_on_circle(q, q_ref, RAD_TOL)
        assert x == pytest.approx(x_ref, rel=1e-12, abs=1e-12 * (l + r))


def test_slider_crank_dead_centres_are_extremes_by_finite_differences():
    """The slide is largest at the stretched dead centre and smallest at the folded one:
    x(q +- h) < x(q) at the first and > x(q) at the second, by about x'' h^2 / 2."""
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0, offset=0.5)
    dc = kl.kinematics.dead_centres(sc, "slide", 0.0, 2 * np.pi)
    h = 1e-4
    for q, x in zip(dc.q, dc.value):
        side = kl.analyze(sc, np.array([q - h, q + h])).slide("slide")
        slope = (side[1] - side[0]) / (2 * h)          # central difference of x: K there
        assert abs(slope) <= 1e-7                       # O(h^2) of a K of about 1
        assert np.all(np.sign(side - x) == np.sign(side[0] - x))   # both on one side
    assert dc.value.max() == pytest.approx(math.sqrt(16 - 0.25), rel=1e-12)
    assert dc.value.min() == pytest.approx(math.sqrt(4 - 0.25), rel=1e-12)


@pytest.mark.parametrize("r, l, e", [(1.0, 3.0, 0.0), (1.0, 3.0, 1.5), (1.0, 3.0, -1.9)])
def test_slider_crank_toggle_not_reached_when_the_crank_is_short(r, l, e):
    assert r + abs(e) < l
    sc = kl.mechanisms.slider_crank(crank=r, rod=l, offset=e)
    assert kl.kinematics.toggles(sc, 0.0, 2 * np.pi) == ()


def test_slider_crank_toggles_where_the_rod_is_perpendicular_to_the_slide():
    """Crank 2, rod 1.5, offset 0.25: the crank cannot turn; it rocks between the limit
    positions where |r sin q - e| = l, i.e. sin q = (e +- l) / r."""
    r, l, e = 2.0, 1.5, 0.25
    sc = kl.mechanisms.slider_crank(crank=r, rod=l, offset=e)
    found = kl.kinematics.toggles(sc)
    assert [t.kind for t in found] == ["limit position", "limit position"]
    candidates = [math.asin((e + l) / r), math.pi - math.asin((e + l) / r),
                  math.asin((e - l) / r), math.pi - math.asin((e - l) / r)]
    for t in found:
        assert min(abs(math.remainder(t.q - c, 2 * math.pi)) for c in candidates) <= RAD_TOL
        theta3 = kl.analyze(sc, t.q, at_singular="flag").angle("rod")
        assert abs(math.cos(theta3)) <= 1e-5      # det J = l cos(theta3) = 0 (to sqrt(rounding))


def crank_rocker_dead_centres(d, a, b, c):
    """(q, theta4) of the collinear crank-coupler configurations: for the stretched and the
    folded one, the two circle intersections (above and below the ground line)."""
    out = []
    for radius, folded in ((a + b, False), (b - a, True)):
        # B on circles |O2 B| = radius and |O4 B| = c, O4 = (d, 0)
        x = (radius ** 2 - c ** 2 + d ** 2) / (2 * d)
        y = math.sqrt(radius ** 2 - x * x)
        pair = []
        for yy in (y, -y):
            q = math.atan2(yy, x) + (math.pi if folded else 0.0)
            pair.append((q, math.atan2(yy, x - d)))
        out.append(pair)
    return out


def test_crank_rocker_extremes_against_law_of_cosines():
    d, a, b, c = 300.0, 100.0, 300.0, 250.0           # examples/crank_rocker.toml, mm
    fb = kl.mechanisms.fourbar(ground=d, crank=a, coupler=b, rocker=c)
    dc = kl.kinematics.dead_centres(fb, "rocker", 0.0, 2 * np.pi)
    assert len(dc) == 2
    pairs = crank_rocker_dead_centres(d, a, b, c)
    for q, th4 in zip(dc.q, dc.value):
        candidates = [p for pair in pairs for p in pair]
        best = min(candidates, key=lambda p: abs(math.remainder(q - p[0], 2 * math.pi)))
        assert close_on_circle(q, best[0], RAD_TOL)
        assert close_on_circle(th4, best[1], 1e-9)
    # one stretched, one folded: |O2 B| is a + b at one and b - a at the other
    B = kl.analyze(fb, dc.q).position("B")
    assert sorted(np.hypot(*B.T)) == pytest.approx([b - a, a + b], rel=1e-12)
    # and the law of cosines gives the rocker's swing
    ext = math.acos((c * c + d * d - (a + b) ** 2) / (2 * c * d))
    fold = math.acos((c * c + d * d - (b - a) ** 2) / (2 * c * d))
    assert abs(math.remainder(dc.value[1] - dc.value[0], 2 * math.pi)) == pytest.approx(
        ext - fold, abs=1e-9)
    assert kl.kinematics.toggles(fb, 0.0, 2 * np.pi) == ()      # a crank-rocker never locks


def test_triple_rocker_toggles_at_the_ends_of_its_reach():
    """Non-Grashof (ground 1, crank 2, coupler 1, rocker 1.5): coupler and rocker in line at
    |A O4| = 2.5, where 5 - 4 cos q = 6.25: q = +-acos(-0.3125)."""
    fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    found = kl.kinematics.toggles(fb)
    expected = math.acos(-0.3125)
    assert [t.kind for t in found] == ["limit position", "limit position"]
    assert [t.q for t in found] == pytest.approx([-expected, expected], abs=RAD_TOL)
    assert all(t.links == ("coupler", "rocker") for t in found)
    lo, hi = kl.kinematics.input_span(fb)
    assert (lo, hi) == pytest.approx((-expected, expected), abs=RAD_TOL)


def test_double_rocker_toggles_at_the_ends_of_its_reach():
    """Grashof with the coupler shortest (ground 3, crank 2.5, coupler 1, rocker 2.8): the
    crank's reach ends where the coupler and the rocker fall in line, |A O4| = 1 + 2.8 or
    2.8 - 1: cos q = (9 + 6.25 - |A O4|^2) / 15."""
    fb = kl.mechanisms.fourbar(ground=3.0, crank=2.5, coupler=1.0, rocker=2.8)
    found = kl.kinematics.toggles(fb)
    assert len(found) == 2 and all(t.kind == "limit position" for t in found)
    candidates = []
    for reach in (3.8, 1.8):
        c = (9 + 6.25 - reach ** 2) / 15
        if abs(c) <= 1:
            candidates += [math.acos(c), -math.acos(c)]
    for t in found:
        assert min(abs(math.remainder(t.q - v, 2 * math.pi)) for v in candidates) <= RAD_TOL
        assert t.links == ("coupler", "rocker")


def test_change_point_linkage_toggle_once_a_turn():
    """a + b = c + d (ground 3, crank 1, coupler 2, rocker 2): all four in line at q = pi,
    where |A O4| = 4 = coupler + rocker; the crank goes on (a change point)."""
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=2.0, rocker=2.0)
    found = kl.kinematics.toggles(fb, 0.0, 2 * np.pi)
    assert [t.kind for t in found] == ["change point"]
    assert found[0].q == pytest.approx(math.pi, abs=RAD_TOL)
    assert found[0].links == ("coupler", "rocker")


def test_dead_centres_of_a_link_of_the_in_line_engine():
    """The rod's angle of an in-line slider-crank, theta3 = -asin(r sin q / l), turns back
    at q = 90 and 270 deg, at -+asin(r / l)."""
    sc = kl.mechanisms.slider_crank(crank=0.05, rod=0.18)
    dc = kl.kinematics.dead_centres(sc, "rod", 0.0, 2 * np.pi)
    assert dc.kind == "angle"
    assert dc.q == pytest.approx([np.pi / 2, 3 * np.pi / 2], abs=RAD_TOL)
    assert dc.value == pytest.approx([-math.asin(0.05 / 0.18), math.asin(0.05 / 0.18)], abs=1e-12)


def test_dead_centres_the_same_in_mm_and_in_m():
    a = kl.kinematics.dead_centres(kl.mechanisms.slider_crank(crank=50.0, rod=180.0, offset=10.0),
                                   "slide", 0.0, 2 * np.pi)
    b = kl.kinematics.dead_centres(kl.mechanisms.slider_crank(crank=0.05, rod=0.18, offset=0.01),
                                   "slide", 0.0, 2 * np.pi)
    assert a.q == pytest.approx(b.q, abs=1e-12)
    assert a.value / 1000 == pytest.approx(b.value, rel=1e-12)


def test_dead_centres_refuse_a_point_and_an_unknown_name():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    with pytest.raises(ModelError, match=r"output: .*a point has no dead centre of its own"):
        kl.kinematics.dead_centres(fb, "B")
    with pytest.raises(ModelError, match=r"output: expected one of .*'rocker'.*got 'rockr'"):
        kl.kinematics.dead_centres(fb, "rockr")
    with pytest.raises(ModelError, match=r"output: .*got 'ground'"):
        kl.kinematics.dead_centres(fb, "ground")
    with pytest.raises(ModelError, match=r"lo, hi: expected lo < hi, got lo = 1, hi = 0"):
        kl.kinematics.dead_centres(fb, "rocker", 1.0, 0.0)


def test_dead_centres_refuse_two_inputs_and_toggles_take_them():
    five = kl.load(EXAMPLES / "fivebar.toml")
    with pytest.raises(ModelError, match=r"mechanism: expected one input, got 2"):
        kl.kinematics.dead_centres(five, "coupler1")
    assert isinstance(kl.kinematics.toggles(five), kl.kinematics.ToggleLocus)


@settings(max_examples=25)
@given(r=st.floats(0.05, 1.0), rest=st.floats(0.2, 3.0), e_frac=st.floats(-0.9, 0.9))
def test_random_slider_cranks_against_the_closed_form(r, rest, e_frac):
    """Any slider-crank whose crank turns fully (r + |e| < l): two dead centres where crank
    and rod are collinear, and no toggle."""
    e = e_frac * rest            # |e| < l - r = rest
    l = r + rest + abs(e)
    sc = kl.mechanisms.slider_crank(crank=r, rod=l, offset=e)
    dc = kl.kinematics.dead_centres(sc, "slide", 0.0, 2 * np.pi)
    expected = sorted([turn(math.asin(e / (l + r))), turn(math.pi + math.asin(e / (l - r)))])
    assert len(dc) == 2
    assert sorted(turn(dc.q)) == pytest.approx(expected, abs=RAD_TOL)
    assert sorted(dc.value) == pytest.approx(
        sorted([math.sqrt((l + r) ** 2 - e * e), math.sqrt((l - r) ** 2 - e * e)]),
        rel=1e-12)
    assert kl.kinematics.toggles(sc, 0.0, 2 * np.pi) == ()


@pytest.mark.parametrize("scale", [1e-4, 1.0, 1e4])
def test_toggles_the_same_at_any_scale(scale):
    fb = kl.mechanisms.fourbar(ground=1.0 * scale, crank=2.0 * scale, coupler=1.0 * scale,
                               rocker=1.5 * scale)
    found = kl.kinematics.toggles(fb)
    assert [t.q for t in found] == pytest.approx([-math.acos(-0.3125), math.acos(-0.3125)],
                                                 abs=RAD_TOL)
    assert all(t.links == ("coupler", "rocker") for t in found)


def test_a_translating_coupler_has_no_dead_centre():
    """A parallelogram's coupler keeps its angle (K = 0 to rounding, over 1e-12 next to its
    change points): it never turns back, and its rocker turns with the crank."""
    pg = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    assert len(kl.kinematics.dead_centres(pg, "coupler", 0.0, 2 * np.pi)) == 0
    assert len(kl.kinematics.dead_centres(pg, "rocker", 0.0, 2 * np.pi)) == 0
    double = kl.load(Path(__file__).resolve().parent / "double_parallelogram.toml")
    assert len(kl.kinematics.dead_centres(double, "coupler")) == 0
