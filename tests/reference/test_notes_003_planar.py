"""*Mecanismos* worked examples for planar position analysis."""
import numpy as np
import pytest

import kinelab as kl


# *Mecanismos*, Ex. 4.2: theta3 = ±60°, theta4 = ±120° (checked by hand: B = (1.5, ±sqrt(3)/2))
@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_fourbar_notes_003_ex_4_2(branch):
    fb = kl.mechanisms.fourbar(ground=2.0, crank=1.0, coupler=1.0, rocker=1.0, branch=branch)
    sol = kl.analyze(fb, q=0.0)
    th3, th4 = sol.angle("coupler"), sol.angle("rocker")
    assert abs(th3) == pytest.approx(np.pi / 3, abs=1e-12)
    assert abs(th4) == pytest.approx(2 * np.pi / 3, abs=1e-12)
    assert np.sign(th3) == np.sign(th4)
    np.testing.assert_allclose(sol.position("B"), [1.5, np.sign(th3) * np.sqrt(3) / 2], atol=1e-12)


def test_slider_crank_notes_003_ex_4_4():
    """Ex. 4.4 (Newton-Raphson): L2 = L3 = 1, theta2 = 45° -> theta3 = -45°, l = sqrt(2)."""
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=1.0)
    sol = kl.analyze(sc, q=np.radians(45.0))
    assert sol.angle("rod") == pytest.approx(-np.pi / 4, abs=1e-12)
    assert sol.slide("slide") == pytest.approx(np.sqrt(2), abs=1e-12)


def test_slider_crank_notes_003_ex_4_6():
    """Ex. 4.6: r_A = (L3 c3 + L1, L3 s3) with theta3 from the wrist pin B to A and L1 = x_B.

    Differentiating, -L2 s2 w2 = -L3 s3 w3 + L1' and L2 c2 w2 = L3 c3 w3, so
    L1' = L2 (-s2 + c2 s3 / c3) w2: the printed "L2 (s2 + c2 s3/c3)" has a sign slip.
    The notes' acceleration system (after eq. 57) must hold as printed.
    """
    L2, L3, w2, a2 = 1.0, 3.0, 5.0, -2.0
    q = np.radians(np.arange(0.0, 360.0, 10.0)) + 0.01
    sol = kl.analyze(kl.mechanisms.slider_crank(crank=L2, rod=L3), q=q, qd=w2, qdd=a2)
    t3 = sol.angle("rod") + np.pi           # the notes measure link 3 from B to A
    s2, c2, s3, c3 = np.sin(q), np.cos(q), np.sin(t3), np.cos(t3)
    np.testing.assert_allclose(sol.K("rod"), L2 * c2 / (L3 * c3), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(sol.K("slide"), L2 * (-s2 + c2 * s3 / c3), rtol=1e-12, atol=1e-12)
    w3, a3 = sol.omega("rod"), sol.alpha("rod")
    L1dd = sol.slide_acceleration("slide")
    lhs1 = -L3 * s3 * a3 + L1dd
    lhs2 = L3 * c3 * a3
    rhs1 = L2 * (-c2 * w2 ** 2 - s2 * a2) + L3 * c3 * w3 ** 2
    rhs2 = L2 * (-s2 * w2 ** 2 + c2 * a2) + L3 * s3 * w3 ** 2
    np.testing.assert_allclose(lhs1, rhs1, rtol=1e-12, atol=1e-11)
    np.testing.assert_allclose(lhs2, rhs2, rtol=1e-12, atol=1e-11)
