"""6-SPS platform: leg lengths against plain vector arithmetic, the inverse Jacobian against
finite differences, forward kinematics against the inverse."""
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import kinelab.spatial as sp
from kinelab.errors import ConvergenceError, ModelError, SingularityError


def ring(radius, degrees):
    t = np.radians(degrees)
    return radius * np.c_[np.cos(t), np.sin(t), np.zeros(len(t))]


BASE = ring(1.0, [-15, 15, 105, 135, 225, 255])
TOP = ring(0.5, [-45, 45, 75, 165, 195, 285])
HOME = np.array([0.0, 0.0, 1.0])

small = st.floats(-0.3, 0.3, allow_nan=False)
pose = st.tuples(st.tuples(small, small, small), st.tuples(small, small, small))


def lengths_by_hand(position, R):
    return np.array([np.linalg.norm(position + R @ b - a) for a, b in zip(BASE, TOP)])


@given(pose)
def test_leg_lengths_against_plain_vectors(p):
    offset, rotvec = p
    R = Rotation.from_rotvec(rotvec)
    d = sp.stewart_leg_lengths(BASE, TOP, HOME + offset, R)
    np.testing.assert_allclose(d, lengths_by_hand(HOME + np.array(offset), R.as_matrix()),
                               rtol=0, atol=1e-15)


def test_leg_lengths_batched_shapes():
    rng = np.random.default_rng(4)
    R = Rotation.from_rotvec(rng.uniform(-0.2, 0.2, (10, 3)))
    p = HOME + rng.uniform(-0.2, 0.2, (10, 3))
    d = sp.stewart_leg_lengths(BASE, TOP, p, R)
    assert d.shape == (10, 6)
    np.testing.assert_allclose(d, [lengths_by_hand(pi, Ri) for pi, Ri in zip(p, R.as_matrix())],
                               rtol=0, atol=1e-15)
    # One rotation for N positions, and N rotations for one position.
    assert sp.stewart_leg_lengths(BASE, TOP, p, Rotation.identity()).shape == (10, 6)
    assert sp.stewart_leg_lengths(BASE, TOP, HOME, R).shape == (10, 6)
    assert sp.stewart_leg_lengths(BASE, TOP, HOME, Rotation.identity()).shape == (6,)


@given(pose)
def test_inverse_jacobian_against_finite_differences(p):
    offset, rotvec = p
    R, position = Rotation.from_rotvec(rotvec), HOME + np.array(offset)
    J = sp.stewart_inverse_jacobian(BASE, TOP, position, R)
    h = 1e-6      # central difference: error ~ h² × (second derivative ~ 1) ~ 1e-12
    fd = np.empty((6, 6))
    for i, e in enumerate(np.eye(3)):
        fd[:, i] = (sp.stewart_leg_lengths(BASE, TOP, position + h * e, R)
                    - sp.stewart_leg_lengths(BASE, TOP, position - h * e, R)) / (2 * h)
        # ω in the base frame: the platform turns by h e about its origin.
        fd[:, 3 + i] = (sp.stewart_leg_lengths(BASE, TOP, position, Rotation.from_rotvec(h * e) * R)
                        - sp.stewart_leg_lengths(BASE, TOP, position,
                                                 Rotation.from_rotvec(-h * e) * R)) / (2 * h)
    np.testing.assert_allclose(J, fd, rtol=0, atol=1e-9)


@given(pose, pose)
def test_forward_inverts_the_leg_lengths(p, nudge):
    offset, rotvec = p
    R, position = Rotation.from_rotvec(rotvec), HOME + np.array(offset)
    d = sp.stewart_leg_lengths(BASE, TOP, position, R)
    # Start a little away from the pose (a tenth of the drawn range).
    guess_p = position + 0.1 * np.array(nudge[0])
    guess_R = Rotation.from_rotvec(0.1 * np.array(nudge[1])) * R
    found = sp.stewart_forward(BASE, TOP, d, guess_p, guess_R)
    assert found.residual <= 1e-12
    # Leg residual 1e-12 m through a Jacobian of condition ~10: pose to ~1e-11.
    np.testing.assert_allclose(found.position, position, rtol=0, atol=1e-10)
    assert (found.rotation * R.inv()).magnitude() < 1e-10


def test_forward_is_batched():
    rng = np.random.default_rng(5)
    R = Rotation.from_rotvec(rng.uniform(-0.2, 0.2, (25, 3)))
    p = HOME + rng.uniform(-0.2, 0.2, (25, 3))
    d = sp.stewart_leg_lengths(BASE, TOP, p, R)
    found = sp.stewart_forward(BASE, TOP, d, HOME, Rotation.identity())
    assert found.position.shape == (25, 3) and len(found.rotation) == 25
    np.testing.assert_allclose(found.position, p, rtol=0, atol=1e-10)
    assert found.iterations < 10


def test_architecturally_singular_platform_is_reported():
    # Platform similar to the base, corresponding points joined: singular at every pose.
    top = 0.5 * BASE
    with pytest.raises(SingularityError, match=r"Jacobian is singular at sample\(s\) 0"):
        sp.stewart_forward(BASE, top, np.full(6, 1.1), HOME, Rotation.identity())


def test_no_convergence_is_reported():
    d = sp.stewart_leg_lengths(BASE, TOP, HOME + [0.2, 0.1, 0.1], Rotation.from_rotvec([0.2, 0, 0]))
    with pytest.raises(ConvergenceError, match=r"no convergence in 1 steps at sample\(s\) 0"):
        sp.stewart_forward(BASE, TOP, d, HOME, Rotation.identity(), max_iter=1)


@pytest.mark.parametrize("call, message", [
    (lambda: sp.stewart_leg_lengths(BASE, TOP, HOME, np.eye(3)),
     r"rotation: expected a scipy.spatial.transform.Rotation, got ndarray"),
    (lambda: sp.stewart_leg_lengths(BASE, TOP[:5], HOME, Rotation.identity()),
     r"platform_points: expected shape \(6, 3\), got \(5, 3\)"),
    (lambda: sp.stewart_leg_lengths(BASE, TOP, [0, 1], Rotation.identity()),
     r"position: expected shape \(3,\) or \(N, 3\), got \(2,\)"),
    (lambda: sp.stewart_leg_lengths(BASE, TOP, np.zeros((4, 3)),
                                    Rotation.from_rotvec(np.zeros((3, 3)))),
     r"4 positions and 3 rotations"),
    (lambda: sp.stewart_forward(BASE[:5], TOP[:5], np.ones(5), HOME, Rotation.identity()),
     r"forward kinematics needs 6 legs, got 5"),
])
def test_bad_arguments(call, message):
    with pytest.raises(ModelError, match=message):
        call()
