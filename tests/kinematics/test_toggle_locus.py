"""Toggles of a mechanism of several inputs (a ToggleLocus) against the five-bar's geometry.

Five-bar O2 A P B O4 driven at both cranks (ground d along x, cranks a and b, couplers l3
and l4): with q1 and q2 given, A = a (cos q1, sin q1) and B = (d + b cos q2, b sin q2) are
fixed, and the couplers' joint P is where circles of radii l3 about A and l4 about B meet.
det J of that dyad is l3 l4 sin(theta3 - theta4): zero exactly when the two couplers are
collinear, which happens where the circles touch, |AB| = l3 + l4 (stretched) or |l3 - l4|
(folded back).  Beyond that the loops do not close, so in the (q1, q2) plane the curve
|AB| = l3 + l4 bounds the region where the five-bar assembles.  Along a grid line (q2
fixed, say) |B - A|^2 = |B|^2 + a^2 - 2 a |B| cos(q1 - phi), with phi the angle of B, so
the curve crosses it at q1 = phi +- acos((|B|^2 + a^2 - (l3 + l4)^2) / (2 a |B|)).
"""
import math
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
# the kernel takes a discriminant within 1e-12 of zero as zero (a limit position closes to
# rounding), so a limit position found by bisection lies within about 1e-11 rad of the curve
ROOT_TOL = 1e-10
SING_TOL = 1e-9     # det J and the couplers' cross product there, relative to their scale


def symmetric_fivebar(scale=1.0, coupler=1.2):
    return kl.mechanisms.fivebar(ground=1.0 * scale, crank1=1.0 * scale,
                                 coupler1=coupler * scale, coupler2=coupler * scale,
                                 crank2=1.0 * scale, q0=(np.pi / 2, np.pi / 2))


BOX = ([0.0, -np.pi], [2 * np.pi, np.pi])


def pins(q, d=1.0, a=1.0, b=1.0):
    """A and B (N, 2) from the crank angles q (N, 2), in closed form."""
    A = a * np.stack([np.cos(q[:, 0]), np.sin(q[:, 0])], axis=1)
    B = np.stack([d + b * np.cos(q[:, 1]), b * np.sin(q[:, 1])], axis=1)
    return A, B


def cross(u, v):
    return u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]


def unit(v):
    return v / np.linalg.norm(v, axis=1)[:, None]


def test_symmetric_fivebar_toggles_are_its_couplers_in_line():
    five = symmetric_fivebar()
    locus = kl.kinematics.toggles(five, *BOX)
    assert locus.reached and locus.samples == (61, 61)
    limit = locus.kind == "limit position"
    assert limit.sum() > 100 and set(locus.kind) <= {"limit position", "touch"}
    q = locus.q[limit]
    sol = kl.analyze(five, q, at_singular="flag")
    # det J = 0, relative to its scale l3 l4
    assert np.all(np.abs(sol.det_J) <= SING_TOL * 1.2 * 1.2)
    assert np.all(sol.singularity <= SING_TOL)
    # the couplers' directions, from the analysis ...
    t3, t4 = sol.angle("coupler1"), sol.angle("coupler2")
    assert np.all(np.abs(np.sin(t3 - t4)) <= SING_TOL)
    # ... and from the pins in closed form and the analysed P
    A, B = pins(q)
    P = sol.position("P")
    assert np.all(np.abs(cross(unit(P - A), unit(B - P))) <= SING_TOL)
    # stretched out: |AB| = l3 + l4
    assert np.linalg.norm(B - A, axis=1) == pytest.approx(2.4, abs=SING_TOL * 2.4)
    assert all(links == ("coupler1", "coupler2") for links, k in zip(locus.links, locus.kind)
               if k == "limit position")


def test_each_limit_position_is_the_closed_form_crossing_of_its_grid_line():
    locus = kl.kinematics.toggles(symmetric_fivebar(), *BOX)
    lo, hi = np.asarray(BOX[0]), np.asarray(BOX[1])
    grids = [np.linspace(lo[k], hi[k], 61) for k in range(2)]
    for axis in (0, 1):
        rows = (locus.kind == "limit position") & (locus.axis == axis)
        held = locus.q[rows, 1 - axis]
        # held at a grid value of the other input
        assert np.all(np.min(np.abs(held[:, None] - grids[1 - axis][None, :]), axis=1) == 0.0)
        # the circle of the moving pin's crank about its pivot, and the other pin
        if axis == 0:           # q1 moves: A on the unit circle about O2, B fixed
            c = np.stack([1.0 + np.cos(held), np.sin(held)], axis=1)
        else:                   # q2 moves: B on the unit circle about O4, A fixed (from O4)
            c = np.stack([np.cos(held) - 1.0, np.sin(held)], axis=1)
        r = np.linalg.norm(c, axis=1)
        phi = np.arctan2(c[:, 1], c[:, 0])
        half = np.arccos((r ** 2 + 1.0 - 2.4 ** 2) / (2.0 * r))
        t = locus.q[rows, axis]
        miss = np.min([np.abs(np.remainder(t - (phi + s * half) + np.pi, 2 * np.pi) - np.pi)
                       for s in (1.0, -1.0)], axis=0)
        assert np.all(miss <= ROOT_TOL)
        # every crossing of a grid line by the curve is found: count them in closed form
        moving = grids[axis]
        for v in np.unique(held):
            if axis == 0:
                A, B = pins(np.stack([moving, np.full_like(moving, v)], axis=1))
            else:
                A, B = pins(np.stack([np.full_like(moving, v), moving], axis=1))
            inside = np.linalg.norm(B - A, axis=1) <= 2.4
            assert np.count_nonzero(np.diff(inside.astype(int))) == np.count_nonzero(held == v)


def test_isolated_singular_configurations_on_the_grid_are_touches():
    """The example five-bar (ground 100, cranks 100, couplers 150 mm) has no limit curve in
    the plane: |AB| reaches l3 + l4 = 300 only at q = (180, 0) deg (A and B at the ends of
    the ground's line, the couplers stretched along it), and the crank pins meet (A = B, the
    equal couplers folded onto each other) at (60, 120) and (300, 240) deg: det J = 0 at
    these points alone, each on the grid of the model's ranges (steps of 6 deg)."""
    five = kl.load(EXAMPLES / "fivebar.toml")
    locus = kl.kinematics.toggles(five)
    assert list(locus.kind) == ["touch"] * 4 and list(locus.axis) == [-1] * 4
    expected = [(180.0, 0.0), (180.0, 360.0), (300.0, 240.0), (420.0, 120.0)]
    assert np.degrees(locus.q) == pytest.approx(np.array(expected), abs=1e-9)
    assert locus.nearest < 1e-6
    sol = kl.analyze(five, locus.q, at_singular="flag")
    assert np.all(sol.singular)


def test_a_box_away_from_the_singularities_returns_empty():
    """Near the sketch (A and B from 0.2 to 1.5 apart, the couplers 1.2 long each) the
    couplers never fall in line: nothing is found, and the grid's closest approach says
    how far they stay from it (the sine of their angle, with A and B closest)."""
    five = symmetric_fivebar()
    locus = kl.kinematics.toggles(five, [1.2, 1.2], [2.0, 2.0], samples=21)
    assert not locus.reached and len(locus) == 0 and locus.q.shape == (0, 2)
    assert locus.samples == (21, 21)
    sol = kl.analyze(five, locus.nearest_q[None, :])
    assert locus.nearest == pytest.approx(float(sol.singularity[0]), rel=1e-12)
    t3, t4 = sol.angle("coupler1")[0], sol.angle("coupler2")[0]
    assert locus.nearest == pytest.approx(abs(math.sin(t3 - t4)), rel=1e-12)
    assert locus.nearest > 0.1
    # a five-bar whose couplers cannot stretch to |AB| over the whole box: long couplers
    long = symmetric_fivebar(coupler=2.0)        # |AB| <= 3 < 4 everywhere, A = B avoided
    assert not kl.kinematics.toggles(long, [1.2, 1.2], [2.0, 2.0]).reached


@pytest.mark.parametrize("scale", [1e-4, 1e4])
def test_the_locus_is_the_same_at_any_scale(scale):
    one = kl.kinematics.toggles(symmetric_fivebar(), *BOX, samples=31)
    scaled = kl.kinematics.toggles(symmetric_fivebar(scale), *BOX, samples=31)
    assert list(scaled.kind) == list(one.kind)
    assert scaled.q == pytest.approx(one.q, abs=1e-9)


def test_samples_per_input_and_the_default_box():
    five = symmetric_fivebar()
    locus = kl.kinematics.toggles(five, *BOX, samples=(31, 41))
    assert locus.samples == (31, 41) and locus.reached
    lo, hi = kl.kinematics.input_span(five)           # a turn of each crank from the sketch
    assert lo == pytest.approx([np.pi / 2] * 2) and hi == pytest.approx([2.5 * np.pi] * 2)
    default = kl.kinematics.toggles(five)
    assert default.lo == pytest.approx(lo) and default.samples == (61, 61)
    # one input of the box given, the other by default
    part = kl.kinematics.toggles(five, [None, -np.pi], [None, np.pi])
    assert part.lo == pytest.approx([np.pi / 2, -np.pi])


def test_bad_boxes_and_grids_are_refused():
    five = symmetric_fivebar()
    with pytest.raises(ModelError, match=r"samples: expected one whole number or 2 \(one per "
                                         r"input\), got 3"):
        kl.kinematics.toggles(five, samples=(11, 11, 11))
    with pytest.raises(ModelError, match=r"samples: expected a grid of at most 1,000,000 "
                                         r"samples, got 2000 x 2000"):
        kl.kinematics.toggles(five, samples=2000)
    with pytest.raises(ModelError, match=r"lo: expected 2 input values"):
        kl.kinematics.toggles(five, 0.0, [1.0, 1.0])
    with pytest.raises(ModelError, match=r"lo, hi: expected lo < hi for every input, got "
                                         r"lo = 1, hi = 0 for 'jO4'"):
        kl.kinematics.toggles(five, [0.0, 1.0], [1.0, 0.0])
