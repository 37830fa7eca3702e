"""Sarrus's linkage: the closed form against the closure of both legs' chains of hinge
rotations in space (the plate reached through either leg is the same, and only rises)."""
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab.spatial as sp
from kinelab.errors import AssemblyError


def about(axis, angle, point):
    """The 4x4 transform of a rotation by ``angle`` about the line through ``point``
    along the unit ``axis`` (Rodrigues)."""
    k = np.asarray(axis, float)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    R = np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, np.asarray(point) - R @ point
    return T


UP = np.array([0.0, 0.0, 1.0])


def leg_chain(angles, base, out, lower, upper):
    """Transform of the plate through one leg: the leg sketched straight out along
    ``out`` (hinges at base, base + lower out, base + (lower + upper) out) and its hinges
    turned in order, each about its own line; the plate hinge's sketch place is then
    carried to the plate's."""
    n = np.cross(out, UP)
    p0, p1, p2 = base, base + lower * out, base + (lower + upper) * out
    T = about(n, angles[0], p0) @ about(n, angles[1], p1) @ about(n, angles[2], p2)
    return T, p2


length = st.floats(0.01, 10.0)


@given(length, length, st.floats(0.2, 1.3))
def test_both_legs_carry_the_plate_to_one_pose_that_only_rises(l1, l2, theta):
    if l2 < l1 * np.cos(theta) + 1e-6:
        return
    p = sp.sarrus(theta, (l1, l2), (l1, l2))
    size = l1 + l2
    poses = []
    for leg, (base, out) in enumerate([(np.array([1.0, 0, 0]), np.array([1.0, 0, 0])),
                                       (np.array([0, 1.0, 0]), np.array([0, 1.0, 0]))]):
        T, far = leg_chain(p.angles[leg], base * size, out, l1, l2)
        # the leg sketched straight out brings its plate hinge from `far` to right above
        # the base hinge: the plate's own motion is this transform followed by that shift
        reached = T[:3, :3] @ far + T[:3, 3]
        np.testing.assert_allclose(reached, base * size + p.height * UP, rtol=0,
                                   atol=1e-10 * size)
        np.testing.assert_allclose(T[:3, :3], np.eye(3), rtol=0, atol=1e-10)
        poses.append(reached - base * size)
    np.testing.assert_allclose(poses[0], poses[1], rtol=0, atol=1e-10 * size)


def test_unequal_legs_close_and_the_plate_rises_straight():
    theta = np.radians(np.linspace(5, 45, 41))
    p = sp.sarrus(theta, (0.05, 0.07), (0.06, 0.04))
    assert p.height.shape == (41,) and p.angles.shape == (41, 2, 3)
    np.testing.assert_allclose(p.angles.sum(axis=-1), 0.0, atol=1e-12)
    for leg, (l1, l2) in enumerate([(0.05, 0.07), (0.06, 0.04)]):
        lower = p.angles[:, leg, 0]
        elbow = l1 * np.c_[np.cos(lower), np.sin(lower)]
        top = np.c_[np.zeros_like(p.height), p.height]
        np.testing.assert_allclose(np.linalg.norm(top - elbow, axis=1), l2, rtol=1e-12)
        np.testing.assert_allclose(np.arctan2(*(top - elbow)[:, ::-1].T) - lower,
                                   p.angles[:, leg, 1], atol=1e-12)


def test_equal_links_by_hand():
    p = sp.sarrus(np.radians(30.0), (0.05, 0.05))
    assert float(p.height) == pytest.approx(0.05, rel=1e-12)


def test_out_of_reach_is_refused():
    with pytest.raises(AssemblyError, match=r"Sarrus linkage cannot close at theta = 0.959931 "
                                            r"rad \(sample\(s\) 5, 6, 7, 8\)"):
        sp.sarrus(np.radians(np.linspace(5, 85, 9)), (0.05, 0.07), (0.06, 0.04))
