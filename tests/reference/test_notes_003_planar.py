"""Seed 003 worked examples for planar position analysis."""
import numpy as np
import pytest

import kinelab as kl


# Notes 003, Ex. 4.2: theta3 = ±60°, theta4 = ±120° (checked by hand: B = (1.5, ±sqrt(3)/2))
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
