"""Four positions: the compatibility cubic, Burmester's curves, every linkage
(*Mecanismos*, §6.3, §6.6)."""
import numpy as np
import pytest

from kinelab.errors import ModelError
from kinelab.synthesis import (Positions, burmester_curves, center_point_cubic, center_points,
                               four_positions, moving_pivot, poles)
from kinelab.synthesis._pivots import suh_radcliffe_rows
from tests.synthesis.helpers import catalogue_poses, engine_pose_errors, travel_transmission

# a task of four positions of a catalogue crank-rocker's coupler, at crank angles 0..160 deg
POS = Positions(*catalogue_poses(np.radians([0.0, 70.0, 100.0, 160.0])))


def normalised_det(pos, A0):
    rows = suh_radcliffe_rows(pos, A0)
    return np.linalg.det(rows) / np.linalg.norm(rows, axis=-1).max(-1) ** 3


def test_cubic_coefficients_against_the_determinant():
    """The multilinear expansion against numpy's determinant at arbitrary a0y."""
    x = np.array([-2.0, 0.3, 4.0])
    c = center_point_cubic(POS, a0x=x)
    for y in (-3.0, 0.0, 1.7, 5.0):
        rows = suh_radcliffe_rows(POS, np.stack([x, np.full(3, y)], -1))
        det = np.linalg.det(rows)
        scale = np.abs(c).max(-1) * (1 + abs(y)) ** 3
        np.testing.assert_array_less(np.abs(np.polyval(c.T, y) - det), 1e-12 * scale)


def test_center_points_are_centers_of_circles():
    for x in (-1.0, 0.0, 0.5, 3.0):
        for A0 in center_points(POS, a0x=x):
            A1 = moving_pivot(POS, fixed=A0)
            r = np.linalg.norm(POS.carry(A1) - A0, axis=1)
            assert np.ptp(r) <= 1e-10 * r.max()         # |A_j - A0| all equal (eq. 69)


def test_traced_curves_against_the_determinant_and_the_linear_system():
    """Sandor-Erdman's standard form traces the curves; each centre point must satisfy eq. 71
    and its circle point must be the Suh-Radcliffe moving pivot."""
    cur = burmester_curves(POS, samples=361)
    assert cur.valid.sum() > 300
    A0 = cur.center[cur.valid]
    assert np.abs(normalised_det(POS, A0)).max() < 1e-12
    near = np.abs(A0).max(-1) < 20            # far points are ill-conditioned for eq. 70
    A1 = np.array([moving_pivot(POS, fixed=a) for a in A0[near]])
    np.testing.assert_allclose(A1, cur.circle[cur.valid][near], atol=1e-8)


def test_center_points_see_opposite_pole_sides_under_equal_angles():
    """Burmester (*Mecanismos*, §6.3, fig. 54): a centre point sees the opposite sides P13P23 and
    P14P24 of the pole quadrilateral under the same angle (mod pi)."""
    p = poles(POS)
    M = burmester_curves(POS, samples=181)
    M = M.center[M.valid]

    def seen(a, b):
        u, v = a - M, b - M
        return np.arctan2(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0], np.sum(u * v, axis=1))
    diff = seen(p[1, 3], p[2, 3]) - seen(p[1, 4], p[2, 4])
    assert np.abs(np.sin(diff)).max() < 1e-9


def test_poles_lie_on_the_center_point_curve():
    p = poles(POS)
    assert np.abs(normalised_det(POS, p.P)).max() < 1e-12


def test_every_solution_is_checked_and_valid_ones_reach_the_poses():
    sols = four_positions(POS, None, a0x=0.0, b0x=3.0)
    assert len(sols) == 9 and sols.reason == ""
    # the catalogue linkage itself is among them (O2 = (0, 0), O4 = (3, 0))
    own = [s for s in sols if np.allclose(np.r_[s.A0, s.B0], [0, 0, 3, 0], atol=1e-9)]
    assert len(own) == 1 and own[0].valid
    for s in sols:
        dpos, dang = engine_pose_errors(s.model, s.q, POS.points, POS.alpha)
        mu = travel_transmission(s)
        if s.valid:
            assert dpos.max() < 1e-9 and dang.max() < 1e-9
            assert mu >= np.radians(30)         # the default limit, kept all the way
        else:
            assert s.branch_defect or s.order_defect or s.circuit_defect or mu < np.radians(30)
        if not s.branch_defect:
            assert dpos.max() < 1e-9       # reached, possibly out of order
        if not (s.branch_defect or s.order_defect):
            # the smallest transmission angle reported is the engine's over the travel (the
            # check samples where it is smallest; the sweep here can only miss it from above)
            assert s.min_transmission_angle - 1e-12 <= mu <= s.min_transmission_angle + 1e-6
            assert s.meets_transmission_limit == (mu >= np.radians(30) - 1e-6)
            assert ("transmission angle defect" in s.state) != s.meets_transmission_limit


def test_order_defect_is_found():
    """The catalogue linkage through crank angles 0, 200, 100, 300 deg: each is reached, but
    no sense of rotation meets them in that order."""
    pos = Positions(*catalogue_poses(np.radians([0.0, 200.0, 100.0, 300.0])))
    sols = four_positions(pos, None, a0x=0.0, b0x=3.0)
    own = next(s for s in sols if np.allclose(np.r_[s.A0, s.B0], [0, 0, 3, 0], atol=1e-9))
    assert own.order_defect and not own.branch_defect
    assert own.direction == 0 and own.position_errors.max() < 1e-9


def test_no_center_point_on_a_vertical_gives_an_empty_result():
    """Turn the task until the real asymptote of the circular cubic is vertical: then a0y
    solves a quadratic, and some verticals miss the curve."""
    from scipy.optimize import brentq

    def rotated(phi):
        c, s = np.cos(phi), np.sin(phi)
        return Positions(POS.points @ np.array([[c, s], [-s, c]]), POS.alpha)

    def lead(phi):       # the a0y^3 coefficient, constant along the curve's abscissa
        return center_point_cubic(rotated(phi), a0x=0.0)[0]
    grid = np.linspace(0, np.pi, 37)
    v = np.array([lead(g) for g in grid])
    k = np.flatnonzero(np.sign(v[:-1]) != np.sign(v[1:]))[0]
    pos = rotated(brentq(lead, grid[k], grid[k + 1], xtol=1e-15))
    xs = np.linspace(-20, 20, 401)
    counts = np.array([len(center_points(pos, a0x=x)) for x in xs])
    x_empty = xs[counts == 0][0]
    sols = four_positions(pos, None, a0x=x_empty, b0x=3.0)
    assert len(sols) == 0
    assert "no centre point has a0x" in sols.reason


def test_four_positions_bad_input():
    with pytest.raises(ModelError, match=r"a0x: expected a finite number, got nan"):
        four_positions(POS, None, a0x=float("nan"), b0x=1.0)
    with pytest.raises(ModelError, match=r"points: expected four positions, got 3; use three_positions"):
        four_positions(POS.points[:3], POS.alpha[:3], 0.0, 1.0)
    with pytest.raises(ModelError, match=r"misses it by .*choose it on the centre-point curve"):
        moving_pivot(POS, fixed=(0.1, 0.1))
