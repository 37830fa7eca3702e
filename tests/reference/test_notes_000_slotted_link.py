"""Erthal, *Mecanismos com 1 GL: análise geral de velocidade e aceleração*:
the slotted link B cos A - R cos q - C = 0, B sin A - R sin q = 0.

The notes give K_a = R cos(A - q) / B, K_b = R sin(A - q) and det J = -B.  Differentiating
K by q once more (checked by hand, and against finite differences in the engine tests):
    L_b = R cos(A - q) (K_a - 1)
    L_a = -[R sin(A - q) (K_a - 1) B + R cos(A - q) K_b] / B^2
and the notes' acceleration equations (grouped form, slide 12) must hold with q'' != 0.
"""
import numpy as np
import pytest

import kinelab as kl

R, C = 1.0, 2.0
Q = np.radians(np.arange(0.0, 360.0, 5.0)) + 0.01


@pytest.fixture(scope="module")
def sol():
    return kl.analyze(kl.mechanisms.slotted_link(crank=R, distance=C), q=Q, qd=3.0, qdd=-2.0)


def test_positions(sol):
    A = np.arctan2(R * np.sin(Q), R * np.cos(Q) + C)
    B = np.hypot(R * np.cos(Q) + C, R * np.sin(Q))
    np.testing.assert_allclose(sol.angle("lever"), A, rtol=0, atol=1e-14)
    np.testing.assert_allclose(sol.slide("slot"), B, rtol=0, atol=1e-14)


def test_velocity_coefficients_and_det(sol):
    A, B = sol.angle("lever"), sol.slide("slot")
    np.testing.assert_allclose(sol.K("lever"), R * np.cos(A - Q) / B, rtol=0, atol=1e-14)
    np.testing.assert_allclose(sol.K("slot"), R * np.sin(A - Q), rtol=0, atol=1e-14)
    np.testing.assert_allclose(sol.det_J, -B, rtol=1e-14, atol=0)


def test_acceleration_coefficients(sol):
    A, B = sol.angle("lever"), sol.slide("slot")
    Ka, Kb = sol.K("lever"), sol.K("slot")
    Lb = R * np.cos(A - Q) * (Ka - 1)
    La = -(R * np.sin(A - Q) * (Ka - 1) * B + R * np.cos(A - Q) * Kb) / B ** 2
    np.testing.assert_allclose(sol.L("lever"), La, rtol=0, atol=1e-13)
    np.testing.assert_allclose(sol.L("slot"), Lb, rtol=0, atol=1e-13)


def test_notes_acceleration_equations(sol):
    A, B = sol.angle("lever"), sol.slide("slot")
    Ad, Bd = sol.omega("lever"), sol.slide_velocity("slot")
    Add, Bdd = sol.alpha("lever"), sol.slide_acceleration("slot")
    qd, qdd = 3.0, -2.0
    e1 = (Bdd * np.cos(A) - 2 * Ad * Bd * np.sin(A) - B * np.cos(A) * Ad ** 2 - B * np.sin(A) * Add
          + R * np.cos(Q) * qd ** 2 + R * np.sin(Q) * qdd)
    e2 = (Bdd * np.sin(A) + 2 * Ad * Bd * np.cos(A) - B * np.sin(A) * Ad ** 2 + B * np.cos(A) * Add
          + R * np.sin(Q) * qd ** 2 - R * np.cos(Q) * qdd)
    assert np.max(np.abs(e1)) < 1e-12 and np.max(np.abs(e2)) < 1e-12


def test_coriolis_component(sol):
    """Badan (after Norton, ch. 7): the Coriolis part of the pin's acceleration is
    2 omega B' along the normal."""
    parts = sol.acceleration_components("A")
    np.testing.assert_allclose(parts.total, sol.acceleration("A"), rtol=0, atol=1e-12)
    A, w, Bd = sol.angle("lever"), sol.omega("lever"), sol.slide_velocity("slot")
    n = np.stack([-np.sin(A), np.cos(A)], axis=-1)
    np.testing.assert_allclose(parts.coriolis, (2 * w * Bd)[:, None] * n, rtol=0, atol=1e-12)
    # the lever turns about the fixed O4: no origin term
    np.testing.assert_array_equal(parts.origin, 0.0)
