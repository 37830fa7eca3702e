"""Bennett's linkage: the closed-form relation against the closure of its loop of
Denavit-Hartenberg transforms, typed out here with plain matrices."""
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl
import kinelab.spatial as sp
from kinelab.errors import ModelError
from kinelab.model import Joint, Link, Mechanism, Point


def dh(theta, a, alpha):
    ct, st_, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array([[ct, -st_ * ca, st_ * sa, a * ct], [st_, ct * ca, -ct * sa, a * st_],
                     [0, sa, ca, 0], [0, 0, 0, 1.0]])


def loop(theta, a, b, alpha, beta):
    T = np.eye(4)
    for t, length, twist in zip(theta, (a, b, a, b), (alpha, beta, alpha, beta)):
        T = T @ dh(t, length, twist)
    return T


twist = st.floats(0.1, np.pi - 0.1)


@given(twist, twist, st.floats(0.01, 100.0))
def test_the_loop_closes_over_a_turn(alpha, beta, a):
    # 1e-10 relative to the links: the closed form against the 4x4 transforms' product
    if abs(np.sin((beta - alpha) / 2)) < 0.05:
        return
    b = a * np.sin(beta) / np.sin(alpha)
    theta1 = np.linspace(0.0, 2 * np.pi, 181)
    p = sp.bennett(theta1, a, b, alpha, beta)
    size = max(a, b)
    for th in p.theta:
        gap = loop(th, a, b, alpha, beta) - np.eye(4)
        assert np.abs(gap[:3, :3]).max() < 1e-10 and np.abs(gap[:3, 3]).max() < 1e-10 * size
    # and by the result's own transforms, batched
    T = p.transforms()
    product = T[:, 0] @ T[:, 1] @ T[:, 2] @ T[:, 3]
    assert np.abs(product[:, :3, :3] - np.eye(3)).max() < 1e-10


def test_the_output_turns_once_continuously_as_the_input_turns_once():
    p = sp.bennett(np.linspace(0.0, 2 * np.pi, 3601), 1.0, np.sqrt(3.0), np.pi / 6, np.pi / 3)
    theta2 = p.theta[:, 1]
    assert np.abs(np.diff(theta2)).max() < 0.01
    assert theta2[0] == pytest.approx(np.pi, abs=1e-12)
    assert abs(theta2[-1] - theta2[0]) == pytest.approx(2 * np.pi, abs=1e-12)
    np.testing.assert_allclose(p.theta[:, 2], -p.theta[:, 0], atol=0)
    np.testing.assert_allclose(p.theta[:, 3], -p.theta[:, 1], atol=0)


def test_relation_by_hand():
    # a = 1, b = √3, alpha = 30°, beta = 60°: tan(45°) tan(theta2 / 2) = sin 45° / sin 15°
    p = sp.bennett(np.pi / 2, 1.0, np.sqrt(3.0), np.pi / 6, np.pi / 3)
    assert np.tan(p.theta[1] / 2) == pytest.approx(1 + np.sqrt(3.0), rel=1e-12)
    assert p.theta.shape == (4,) and p.joints()[0].shape == (4, 3)


def test_a_loop_built_from_its_joints_moves_with_one_freedom():
    # the joints' places and axes at any input make a model that Kutzbach-Gruebler counts
    # at -2 and the exact rank finds mobile
    points, axes = sp.bennett(1.2, 1.0, np.sqrt(3.0), np.pi / 6, np.pi / 3).joints()
    pts = tuple(Point(f"J{k + 1}", *points[k]) for k in range(4))
    links = (Link("ground", ("J4", "J1"), ground=True), Link("l2", ("J1", "J2")),
             Link("l3", ("J2", "J3")), Link("l4", ("J3", "J4")))
    pairs = [("ground", "l2"), ("l2", "l3"), ("l3", "l4"), ("l4", "ground")]
    joints = tuple(Joint(f"j{k + 1}", "R", pairs[k], point=f"J{k + 1}", axis=tuple(axes[k]))
                   for k in range(4))
    m = kl.structure.mobility(Mechanism("bennett", pts, links, joints, space="spatial"))
    assert (m.kutzbach_gruebler, m.exact) == (-2, 1)


@pytest.mark.parametrize("args, message", [
    ((1.0, 1.0, np.pi / 6, np.pi / 3), r"expected Bennett's condition a / sin\(alpha\) = "
                                       r"b / sin\(beta\), got 2 and 1.15470054 m; choose b = "
                                       r"1.73205081 m"),
    ((1.0, 1.0, 0.5, 0.5), r"alpha, beta: expected unequal twists"),
    ((1.0, 1.0, 0.0, 0.5), r"alpha: expected a twist in \(0, π\) rad, got 0 rad"),
    ((-1.0, 1.0, 0.3, 0.5), r"a: "),
])
def test_bad_geometry_is_refused(args, message):
    with pytest.raises(ModelError, match=message):
        sp.bennett(0.3, *args)
