"""The guide's point under a slider: its motion against the slider point's (the relative
velocity and the Coriolis law) and against finite differences of a point fixed in the guide."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.model import Input, Joint, Link, Mechanism, Point

Q = np.radians(np.arange(0.0, 360.0, 7.5)) + 0.01
QD, QDD = 2.5, -1.5


def swivel_guide():
    """A block pinned on the crank pin A guides a rod that turns about O4: the guide itself
    moves, so its point under the slider has an origin term."""
    return Mechanism(
        name="swivel guide",
        points=(Point("O2", 0, 0), Point("A", 0, 1), Point("O4", 2, 0), Point("C", -2, 2)),
        links=(Link("ground", ("O2", "O4"), ground=True), Link("crank", ("O2", "A")),
               Link("block", ("A",)), Link("rod", ("O4", "C"))),
        joints=(Joint("jO2", "R", ("ground", "crank"), point="O2"),
                Joint("jA", "R", ("crank", "block"), point="A"),
                Joint("jO4", "R", ("ground", "rod"), point="O4"),
                Joint("sleeve", "P", ("block", "rod"), point="C", axis=(-2.0, 1.0), origin="A")),
        inputs=(Input(joint="jO2"),))


CASES = {
    "slotted_link": (lambda: kl.mechanisms.slotted_link(1.0, 2.0), "slot"),
    "inverted_slider_crank": (lambda: kl.mechanisms.inverted_slider_crank(2.0, 1.0, offset=0.3), "slide"),
    "whitworth": (lambda: kl.mechanisms.whitworth(1.0, 0.5, 1.0, 2.0), "slot"),
    "swivel_guide": (swivel_guide, "sleeve"),
}


def cross_k(w, v):
    """omega k x v, per row."""
    return w[:, None] * np.stack([-v[:, 1], v[:, 0]], axis=-1)


@pytest.fixture(params=list(CASES), ids=list(CASES))
def case(request):
    make, joint = CASES[request.param]
    m = make()
    return m, joint, kl.analyze(m, q=Q, qd=QD, qdd=QDD)


def test_slider_point_moves_on_the_guide_point(case):
    """v_P = v_G + s' u and a_P = a_G + 2 omega k x (s' u) + s'' u, with the slider point's
    motion from the engine's own point rates; 1e-12: the same quantities, summed."""
    m, joint, sol = case
    j = m.joint(joint)
    g = sol.guide_point(joint)
    assert (g.joint, g.guide, g.point) == (joint, j.links[0], j.point)
    u, w = sol.slide_axes(joint), sol.omega(j.links[0])
    sd, sdd = sol.slide_velocity(joint)[:, None], sol.slide_acceleration(joint)[:, None]
    np.testing.assert_allclose(g.position, sol.position(j.point), rtol=0, atol=0)
    np.testing.assert_allclose(sol.velocity(j.point), g.velocity + sd * u, rtol=0, atol=1e-12)
    np.testing.assert_allclose(sol.acceleration(j.point),
                               g.acceleration + 2.0 * cross_k(w, sd * u) + sdd * u,
                               rtol=0, atol=1e-11)
    parts = sol.acceleration_components(j.point, joint)
    np.testing.assert_allclose(g.acceleration, parts.origin + parts.tangential + parts.normal,
                               rtol=0, atol=1e-12)


def test_guide_point_against_finite_differences(case):
    """Fix the guide's point under P at each sample, carry it with the guide (its origin O
    and angle theta, from analyses at q(t) = q + qd t + qdd t^2 / 2, t = -h, 0, h) and
    difference its path.  h = 1e-4 s: truncation ~h^2 / 6 times the third and fourth
    derivatives (up to ~400 m/s^4 here), so ~1e-6; rounding ~1e-16 / h^2 = 1e-8."""
    m, joint, sol = case
    j = m.joint(joint)
    guide = j.links[0]
    origin = j.origin or m.link(guide).points[0]
    h = 1e-4
    at = {t: kl.analyze(m, q=Q + QD * t + 0.5 * QDD * t * t) for t in (-h, 0.0, h)}
    p0, o0, th0 = sol.position(j.point), sol.position(origin), sol.angle(guide)

    def carried(s):
        d = s.angle(guide) - th0
        c, si = np.cos(d), np.sin(d)
        r = p0 - o0
        return s.position(origin) + np.stack([c * r[:, 0] - si * r[:, 1], si * r[:, 0] + c * r[:, 1]], -1)
    x = {t: carried(s) for t, s in at.items()}
    np.testing.assert_allclose(x[0.0], p0, rtol=0, atol=1e-12)
    v = (x[h] - x[-h]) / (2 * h)
    a = (x[h] - 2 * x[0.0] + x[-h]) / h ** 2
    g = sol.guide_point(joint)
    np.testing.assert_allclose(g.velocity, v, rtol=0, atol=1e-5)
    np.testing.assert_allclose(g.acceleration, a, rtol=0, atol=1e-4)


def test_guide_point_follows_the_shape_rule():
    sl = kl.mechanisms.slotted_link(1.0, 2.0)
    sweep = kl.analyze(sl, q=Q, qd=QD, qdd=QDD).guide_point("slot")
    one = kl.analyze(sl, q=Q[5], qd=QD, qdd=QDD).guide_point("slot")
    for name in ("position", "velocity", "acceleration"):
        assert getattr(one, name).shape == (2,) and getattr(sweep, name).shape == (len(Q), 2)
        np.testing.assert_array_equal(getattr(one, name), getattr(sweep, name)[5])


def test_on_a_fixed_guide_the_point_stands_still():
    """The slider-crank's guide is the ground: its point under B has no motion."""
    g = kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0, offset=0.2), q=Q, qd=QD, qdd=QDD).guide_point("slide")
    assert g.guide == "ground"
    np.testing.assert_array_equal(g.velocity, 0.0)
    np.testing.assert_array_equal(g.acceleration, 0.0)


def test_guide_point_of_a_joint_that_is_not_prismatic():
    sol = kl.analyze(kl.mechanisms.slotted_link(1.0, 2.0), q=0.3)
    with pytest.raises(kl.errors.ModelError, match="prismatic joint: expected one of 'slot', got 'jA'"):
        sol.guide_point("jA")
