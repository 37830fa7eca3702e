"""Synthesis does not depend on the unit a task is written in: the same task scaled by s
gives the same linkages scaled by s, with the same angles, defects and transmission."""
import numpy as np
import pytest

import kinelab as kl

SCALES = [1e-4, 1e-2, 1e2, 1e4]
# *Mecanismos* §6.7's four positions (cm, here m): P and the coupler's angles
FOUR = (np.array([[0.0, 0.0], [5.0, 8.0], [10.0, 15.0], [18.0, 20.0]]), np.radians([0.0, 10.0, 20.0, 30.0]))
PATH = np.c_[2 + np.cos(np.linspace(0, 2 * np.pi, 10, endpoint=False)),
             1 + 0.5 * np.sin(np.linspace(0, 2 * np.pi, 10, endpoint=False))]


def pivots(solutions):
    return np.array([np.r_[s.A0, s.B0] for s in solutions if s.valid]).reshape(-1, 4)


@pytest.mark.parametrize("s", SCALES)
def test_four_positions_scale(s):
    ref = kl.synthesis.four_positions(*FOUR, a0x=-20.195, b0x=-29.167)
    got = kl.synthesis.four_positions(FOUR[0] * s, FOUR[1], a0x=-20.195 * s, b0x=-29.167 * s)
    assert len(got) == len(ref) and [g.valid for g in got] == [r.valid for r in ref]
    np.testing.assert_allclose(pivots(got) / s, pivots(ref), rtol=1e-9, atol=1e-9 * 30)
    np.testing.assert_allclose([g.min_transmission_angle for g in got],
                               [r.min_transmission_angle for r in ref], rtol=0, atol=1e-9)


@pytest.mark.parametrize("s", SCALES)
def test_path_generation_scales(s):
    ref = kl.synthesis.path_generation(PATH, runs=1, seed=3)[0]
    got = kl.synthesis.path_generation(PATH * s, runs=1, seed=3)[0]
    assert got.valid == ref.valid
    assert got.max_error / s == pytest.approx(ref.max_error, rel=1e-6, abs=1e-12)
    assert got.min_transmission_angle == pytest.approx(ref.min_transmission_angle, abs=1e-6)
