"""The singular flag is set from conditioning: every K and L that is not flagged is accurate
to 1e-8 relative, however close to a limit position or a change point the sample is.

References are computed independently in 60-digit arithmetic (mpmath): the closed-form
position of the dyad, differentiated numerically at that precision.
"""
import math

import mpmath as mp
import numpy as np
import pytest

import kinelab as kl

mp.mp.dps = 60
ACCURACY = 1e-8


def _fourbar_rocker(g, a, b, c, sigma):
    """theta4(q) of the four-bar O2 = 0, O4 = (g, 0), |O2A| = a, |AB| = b, |O4B| = c, with
    B = A + alpha d + sigma beta k x d and d = O4 - A (the catalogue's convention)."""
    g, a, b, c = (mp.mpf(v) for v in (g, a, b, c))

    def theta4(q):
        ax, ay = a * mp.cos(q), a * mp.sin(q)
        dx, dy = g - ax, -ay
        D2 = dx * dx + dy * dy
        alpha = (b * b - c * c + D2) / (2 * D2)
        beta = mp.sqrt(b * b / D2 - alpha * alpha)
        bx, by = ax + alpha * dx - sigma * beta * dy, ay + alpha * dy + sigma * beta * dx
        return mp.atan2(by, bx - g)
    return theta4


def _slider(crank, rod):
    """x of the wrist pin of an in-line slider-crank (right branch)."""
    r, l = mp.mpf(crank), mp.mpf(rod)
    return lambda q: r * mp.cos(q) + mp.sqrt(l * l - (r * mp.sin(q)) ** 2)


def _errors(f, q, K, L):
    qm = mp.mpf(float(q))
    K_ref, L_ref = mp.diff(f, qm, 1), mp.diff(f, qm, 2)
    scale = 1.0 + abs(float(K_ref))           # L is compared on the scale of K^2 + |L|
    return (abs(K - float(K_ref)) / max(abs(float(K_ref)), 1e-300),
            abs(L - float(L_ref)) / (abs(float(L_ref)) + scale ** 2))


def _distances():
    return [10.0 ** -k for k in range(1, 15)]


def test_unflagged_K_and_L_near_a_limit_position_of_a_non_grashof_fourbar():
    g, a, b, c = 1.0, 2.0, 1.0, 1.5                     # cos q >= -0.3125
    q_limit = float(mp.acos(mp.mpf(-0.3125)))
    fb = kl.mechanisms.fourbar(g, a, b, c)
    q = np.array([q_limit - d for d in _distances()])
    sol = kl.analyze(fb, q=q, at_singular="flag")
    f = _fourbar_rocker(g, a, b, c, sigma=1.0)
    checked = 0
    for i in np.flatnonzero(~sol.singular):
        eK, eL = _errors(f, q[i], sol.K("rocker")[i], sol.L("rocker")[i])
        assert eK < ACCURACY and eL < ACCURACY, (q_limit - q[i], eK, eL)
        checked += 1
    assert 3 <= checked < len(q)                          # the closest ones are flagged
    assert sol.singular[-1]


def test_unflagged_K_and_L_near_a_limit_of_a_slider_crank_whose_crank_outreaches_its_rod():
    crank, rod = 1.0, 0.8                                  # limit at sin q = 0.8
    q_limit = float(mp.asin(mp.mpf(0.8)))
    sc = kl.mechanisms.slider_crank(crank=crank, rod=rod)
    q = np.array([q_limit - d for d in _distances()])
    sol = kl.analyze(sc, q=q, at_singular="flag")
    f = _slider(crank, rod)
    for i in np.flatnonzero(~sol.singular):
        eK, eL = _errors(f, q[i], sol.K("slide")[i], sol.L("slide")[i])
        assert eK < ACCURACY and eL < ACCURACY, (q_limit - q[i], eK, eL)
    assert sol.singular[-1] and not sol.singular[0]


@pytest.mark.parametrize("side", [-1.0, 1.0])
def test_unflagged_K_and_L_near_a_change_point(side):
    """Parallelogram: on its smooth branch K = 1 and L = 0 for the rocker, exactly."""
    fb = kl.mechanisms.fourbar(ground=100.0, crank=60.0, coupler=100.0, rocker=60.0)
    q = np.array([math.pi + side * d for d in _distances()])
    sol = kl.analyze(fb, q=q, at_singular="flag")
    ok = ~sol.singular
    assert np.max(np.abs(sol.K("rocker")[ok] - 1.0)) < ACCURACY
    assert np.max(np.abs(sol.L("rocker")[ok])) < ACCURACY
    assert np.max(np.abs(sol.K("coupler")[ok])) < ACCURACY
    assert ok[:2].all() and not ok[-1]


def test_flag_threshold_is_the_documented_one():
    fb = kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5)
    sol = kl.analyze(fb, q=np.linspace(-1.8886, 1.8886, 2001), at_singular="flag")
    assert np.array_equal(sol.singular, sol.singularity < kl.kinematics.SINGULAR_TOL)
