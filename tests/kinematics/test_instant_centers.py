"""Instant centres: the four-bar's known centres, Kennedy's theorem, the angular-velocity
ratio theorem (Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades*
(Universidade do Minho, 2007), §4.5-4.6)."""
import itertools

import numpy as np
import pytest

import kinelab as kl

Q = np.radians(np.arange(0.0, 360.0, 10.0)) + 0.01


def line_intersection(p1, d1, p2, d2):
    """Intersection of p1 + s d1 and p2 + t d2, per row."""
    cross = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    w = p2 - p1
    s = (w[:, 0] * d2[:, 1] - w[:, 1] * d2[:, 0]) / cross
    return p1 + s[:, None] * d1


def test_fourbar_centres_by_construction():
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=Q)
    ic = kl.kinematics.instant_centers(sol)
    O2, A, B, O4 = (sol.position(n) for n in ("O2", "A", "B", "O4"))
    np.testing.assert_allclose(ic["ground", "crank"].position, O2, atol=1e-12)
    np.testing.assert_allclose(ic["crank", "coupler"].position, A, atol=1e-12)
    np.testing.assert_allclose(ic["coupler", "rocker"].position, B, atol=1e-12)
    np.testing.assert_allclose(ic["ground", "rocker"].position, O4, atol=1e-12)
    # I13 on the lines O2A and O4B; I24 on the lines AB and O2O4
    np.testing.assert_allclose(ic["ground", "coupler"].position,
                               line_intersection(O2, A - O2, O4, B - O4), rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(ic["crank", "rocker"].position,
                               line_intersection(A, B - A, O2, O4 - O2), rtol=1e-9, atol=1e-9)


def collinear_error(p, q, r):
    a, b = q - p, r - p
    return np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1) + 1e-300)


@pytest.mark.parametrize("make", [kl.mechanisms.stephenson6, kl.mechanisms.watt6,
                                  lambda: kl.mechanisms.slider_crank(1.0, 3.0, offset=0.4)])
def test_kennedy_theorem(make):
    sol = kl.analyze(make(), q=Q)
    ic = kl.kinematics.instant_centers(sol)
    for a, b, c in itertools.combinations(sol.link_names, 3):
        cs = [ic[a, b], ic[a, c], ic[b, c]]
        finite = [x for x in cs if not np.any(x.at_infinity)]
        if len(finite) == 3:
            err = collinear_error(*(x.position for x in finite))
            # coincident centres make the test empty; skip rows where two coincide
            spread = np.min([np.linalg.norm(finite[i].position - finite[j].position, axis=1)
                             for i, j in ((0, 1), (0, 2), (1, 2))], axis=0)
            assert np.all(err[spread > 1e-6] < 1e-7), (a, b, c)
        elif len(finite) == 2:
            inf = next(x for x in cs if np.all(x.at_infinity))
            d = finite[1].position - finite[0].position
            n = np.linalg.norm(d, axis=1)
            cross = np.abs(d[:, 0] * inf.direction[:, 1] - d[:, 1] * inf.direction[:, 0])
            assert np.all(cross[n > 1e-6] / n[n > 1e-6] < 1e-7), (a, b, c)


def test_angular_velocity_ratio_theorem():
    """omega4 / omega2 = I12I24 / I14I24, signed along the line of centres (Flores & Claro,
    eq. 4.121)."""
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=Q, qd=1.0)
    ic = kl.kinematics.instant_centers(sol)
    I12, I14 = ic["ground", "crank"].position, ic["ground", "rocker"].position
    I24 = ic["crank", "rocker"].position
    u = (I14 - I12) / np.linalg.norm(I14 - I12, axis=1)[:, None]
    ratio = ((I24 - I12) * u).sum(1) / ((I24 - I14) * u).sum(1)
    np.testing.assert_allclose(sol.omega("rocker") / sol.omega("crank"), ratio, rtol=1e-9)


def test_slider_centre_at_infinity():
    sol = kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0), q=Q)
    ic = kl.kinematics.instant_center(sol, "ground", "slider")
    assert ic.at_infinity.all()
    np.testing.assert_allclose(np.abs(ic.direction), [[0.0, 1.0]] * len(Q), atol=1e-12)


def test_several_inputs_need_their_speeds():
    """With two inputs the centres follow from the velocities; at rest there are none."""
    fivebar = kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0)
    with pytest.raises(kl.errors.ModelError, match="qd"):
        kl.kinematics.instant_centers(kl.analyze(fivebar, q=[0.5, 2.5]))
    ic = kl.kinematics.instant_center(kl.analyze(fivebar, q=[0.5, 2.5], qd=[1.0, -2.0]),
                                      "ground", "crank1")
    np.testing.assert_allclose(ic.position, fivebar.point("O2").xy, atol=1e-12)   # its pivot


def velocity_on(sol, link, point_xy):
    """Velocity (N, 2) of the point of ``link`` at ``point_xy`` (N, 2), from the solution's
    own point velocities and the link's omega (rigid-body motion)."""
    ref = sol.mechanism.link(link).points[0]
    r = point_xy - sol.position(ref)
    w = sol.omega(link)[:, None]
    return sol.velocity(ref) + w * np.stack([-r[:, 1], r[:, 0]], axis=-1)


@pytest.mark.parametrize("make", [lambda: kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5),
                                  lambda: kl.mechanisms.slider_crank(1.0, 3.0, offset=0.4),
                                  lambda: kl.mechanisms.slotted_link(1.0, 2.0)])
def test_a_pair_in_either_order_is_one_centre(make):
    sol = kl.analyze(make(), q=Q, qd=1.5)
    ic = kl.kinematics.instant_centers(sol)
    assert len(ic) == len(list(itertools.combinations(sol.link_names, 2)))
    for b, a in itertools.combinations(sol.link_names, 2):       # (a, b) against model order
        assert ic[a, b] is ic[b, a] and (a, b) in ic
        one = kl.kinematics.instant_center(sol, a, b)
        assert one.links == (b, a)
        for field in ("position", "at_infinity", "direction"):
            np.testing.assert_array_equal(getattr(one, field), getattr(ic[b, a], field))
        # the centre has the same velocity on both links (rigid-body velocities, not the
        # formula the centre came from); 1e-9: positions far out where w_a ~ w_b
        finite = ~one.at_infinity
        va, vb = velocity_on(sol, a, one.position), velocity_on(sol, b, one.position)
        np.testing.assert_allclose(va[finite], vb[finite], rtol=0, atol=1e-9)


def test_a_centre_at_infinity_has_one_direction():
    """The slider and the ground translate: the direction of I14 does not flip with the
    order of the names (it did: it followed the sign of the relative velocity)."""
    sol = kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0), q=Q)
    forward = kl.kinematics.instant_center(sol, "ground", "slider")
    backward = kl.kinematics.instant_center(sol, "slider", "ground")
    assert backward.at_infinity.all()
    np.testing.assert_array_equal(backward.direction, forward.direction)


def test_pairs_that_name_no_centre():
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=0.3)
    with pytest.raises(kl.errors.ModelError, match="expected two different links, got 'crank' twice"):
        kl.kinematics.instant_center(sol, "crank", "crank")
    with pytest.raises(kl.errors.ModelError, match=r"got 'cranc' \(did you mean 'crank'\?\)"):
        kl.kinematics.instant_center(sol, "ground", "cranc")
    ic = kl.kinematics.instant_centers(sol)
    assert ("crank", "crank") not in ic and "crank" not in ic
    with pytest.raises(KeyError, match="a pair of two different links"):
        ic["crank", "crank"]


@pytest.mark.parametrize("make, pair", [
    (lambda: kl.mechanisms.slotted_link(1.0, 2.0), ("block", "lever")),
    (lambda: kl.mechanisms.inverted_slider_crank(2.0, 1.0, offset=0.3), ("block", "rocker")),
    (lambda: kl.mechanisms.slider_crank(1.0, 3.0, offset=0.4), ("ground", "slider"))])
def test_a_centre_at_infinity_is_perpendicular_to_the_relative_velocity(make, pair):
    """A block sliding on a turning guide translates relative to it, along the slide: the
    direction of their centre at infinity is perpendicular to the slide, however the guide
    turns (it was taken across the two links' reference points, which the guide's turning
    moves apart)."""
    sol = kl.analyze(make(), q=Q, qd=1.5)
    ic = kl.kinematics.instant_center(sol, *pair)
    assert ic.at_infinity.all()
    joint = next(j for j in sol.mechanism.joints if j.type == "P" and set(j.links) == set(pair))
    u = sol.slide_axes(joint.name)
    np.testing.assert_allclose(np.abs((ic.direction * u).sum(axis=1)), 0.0, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(ic.direction, axis=1), 1.0, rtol=1e-12)
    # and the same from the rigid-body velocities at any point, the joint's own included
    xy = sol.position(joint.point) + 0.37
    rel = velocity_on(sol, pair[1], xy) - velocity_on(sol, pair[0], xy)
    np.testing.assert_allclose((ic.direction * rel).sum(axis=1), 0.0, atol=1e-9)
