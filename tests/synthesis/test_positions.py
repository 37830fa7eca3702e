"""Positions of a moving plane and their poles (*Mecanismos*, §6.1)."""
import re
import warnings

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import Positions, pole, poles

coord = st.floats(-5, 5)
angle = st.floats(-3.0, 3.0)


@given(st.lists(st.tuples(coord, coord), min_size=3, max_size=3), st.lists(angle, min_size=3, max_size=3))
def test_pole_is_the_fixed_point_and_sees_every_chord_under_alpha(pts, angs):
    try:
        pos = Positions(np.array(pts), np.array(angs))
    except ModelError:          # two coincident positions: rejected, tested below
        assume(False)
    p = poles(pos)
    X = np.array([[0.3, -1.7], [2.0, 0.4]])          # two arbitrary points of the plane
    Xj = pos.carry(X)                                  # (3, 2, 2)
    for (i, j), P, a, finite in zip(p.pairs, p.P, p.alpha, p.finite):
        if not finite or abs(a) < 1e-3:
            continue
        # P_ij is in the same place in positions i and j: the displacement i -> j fixes it
        Pi_in_1 = pos.carry(np.linalg.solve(kl.synthesis._positions.rotation(pos.alpha[i - 1]),
                                            P - pos.points[i - 1]) + pos.points[0])
        size = 1.0 + np.abs(P).max()
        assert np.linalg.norm(Pi_in_1[j - 1] - P) <= 1e-9 * size   # conditioning ~ 1/sin(a/2)
        # every point is turned by alpha_ij about it
        for k in range(2):
            u, v = Xj[i - 1, k] - P, Xj[j - 1, k] - P
            assert np.linalg.norm(u) == pytest.approx(np.linalg.norm(v), rel=1e-9, abs=1e-9 * size)
            turn = np.arctan2(u[0] * v[1] - u[1] * v[0], u @ v)
            if np.linalg.norm(u) > 1e-6 * size:
                assert abs(np.angle(np.exp(1j * (turn - a)))) < 1e-7


def test_pole_of_a_quarter_turn():
    # (1, 0) turned 90 deg about the origin lands on (0, 1): the pole is the origin (by hand)
    np.testing.assert_allclose(pole([(1, 0), (0, 1)], [0, 90], degrees=True), [0, 0], atol=1e-15)
    # a half turn about (1, 1) takes (0, 0) to (2, 2)
    np.testing.assert_allclose(pole([(0, 0), (2, 2)], [0, np.pi]), [1, 1], atol=1e-15)


def test_angles_as_orientations_or_rotations():
    a = Positions([(0, 0), (1, 0), (2, 1)], [0.5, 0.7, 1.5])
    b = Positions([(0, 0), (1, 0), (2, 1)], [0.2, 1.0])
    np.testing.assert_allclose(a.alpha, b.alpha, atol=1e-15)


def test_from_two_points_matches_point_and_angle():
    pos = Positions([(1, 1), (2, 0.5), (3, 1.5)], [0, 0, 45], degrees=True)
    second = pos.carry((1.0, 3.0))                # a second point of the plane
    again = Positions.from_two_points(pos.points, second)
    np.testing.assert_allclose(again.alpha, pos.alpha, atol=1e-14)


def test_translation_has_its_pole_at_infinity():
    p = poles([(0, 0), (1, 0), (1, 1)], [0, 0, 30], degrees=True)
    assert p.finite.tolist() == [False, True, True]
    with pytest.raises(ModelError, match=r"pole P12 is at infinity: the plane does not turn"):
        p[1, 2]
    np.testing.assert_allclose(p[1, 3], p[3, 1])


@pytest.mark.parametrize("points, angles, message", [
    ([(0, 0), (1, 1), (0, 0)], [0, 0.5, 0], r"positions 1 and 3 coincide"),
    ([(0, 0)], [0], r"points: expected at least two positions, got 1"),
    ([(0, 0), (1, 1)], [0, 1, 2], r"angles: expected 2 orientations .* or 1 rotations"),
    ([(0, 0, 0), (1, 1, 1)], [0, 1], r"points: expected shape \(n, 2\), got \(2, 3\)"),
    ([(0, 0), (1, np.nan)], [0, 1], r"points\[1\]: expected two finite numbers \(x, y\), got "
                                    r"\[1\.0, nan\]"),
    ([(0, 0), (1, 1)], [0, np.inf], r"angles\[1\]: expected a finite number, got inf"),
])
def test_bad_positions(points, angles, message):
    with pytest.raises(ModelError, match=message):
        Positions(points, angles)


def test_two_points_must_keep_their_distance():
    with pytest.raises(ModelError, match=r"the distance between the two points changes"):
        Positions.from_two_points([(0, 0), (1, 0)], [(1, 0), (1, 2)])


@pytest.mark.parametrize("n", [3, 4, 5, 6, 7])
@pytest.mark.parametrize("center, radius", [((0.0, 0.0), 0.0), ((1.0, 2.0), 0.0), ((2.0, 1.0), 1.0)])
def test_positions_that_all_turn_about_one_point_are_refused(n, center, radius):
    """The plane turning about one point (identical points at different angles, or points on
    a circle turning with it): every pole is that point, so is every crank's fixed pivot.
    This gave RuntimeWarnings (divide by zero) and pivots of 1e-317 m; now one message."""
    t = np.radians(15.0 * np.arange(n))
    P = np.asarray(center) + radius * np.column_stack([np.cos(t), np.sin(t)])
    pos = kl.synthesis.Positions(P, t)
    calls = {3: [lambda: kl.synthesis.three_positions(pos, A0=(5, 0), B0=(0, 5))],
             4: [lambda: kl.synthesis.four_positions(pos, a0x=0.5, b0x=-0.5),
                 lambda: kl.synthesis.burmester_curves(pos)],
             5: [lambda: kl.synthesis.five_positions(pos), lambda: kl.synthesis.burmester_points(pos)],
             6: [lambda: kl.synthesis.approximate_positions(pos)],
             7: [lambda: kl.synthesis.fit_dyads(pos)]}[n]
    where = "(" + ", ".join(f"{c:.9g}" for c in center) + ")"
    for call in calls:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            with pytest.raises(ModelError, match=rf"^positions: every position is a turn of the "
                                                 rf"plane about the same point {re.escape(where)} m "
                                                 r"\(all the poles are there\)"):
                call()
