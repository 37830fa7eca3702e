"""Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades*
(Universidade do Minho, 2007):
closed-form velocities, checked.

Four-bar, loop r2 + r3 + r4 = r1 with r4 from B to O4 (eq. 4.111-4.115).  Solving
4.112-4.113 by hand (multiply the complex form by e^{-i theta3}, take the real part) gives
    omega4 = -r2 omega2 sin(theta2 - theta3) / (r4 sin(theta4' - theta3)),
theta4' = theta4 + pi in the notes' convention.  The printed eq. 4.115 lacks the minus sign;
eq. 4.114 for omega3 is right.  Slider-crank (eq. 4.58-4.60): omega3 = -r2 omega2 cos(theta2)
/ (r3 cos(theta3)) and v1 = -r2 omega2 sin(theta2) - r3 omega3 sin(theta3).
"""
import numpy as np

import kinelab as kl

Q = np.radians(np.arange(0.0, 360.0, 5.0)) + 0.01
W2 = 7.0


def test_fourbar_velocities():
    a, b, c, d = 1.0, 3.0, 2.5, 3.0
    sol = kl.analyze(kl.mechanisms.fourbar(d, a, b, c), q=Q, qd=W2)
    t3 = sol.angle("coupler")
    t4s = sol.angle("rocker") + np.pi          # the notes' r4 points from B to O4
    w3 = a * W2 / b * np.sin(Q - t4s) / np.sin(t4s - t3)                 # eq. 4.114
    w4 = -a * W2 / c * np.sin(Q - t3) / np.sin(t4s - t3)                 # eq. 4.115, corrected
    np.testing.assert_allclose(sol.omega("coupler"), w3, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(sol.omega("rocker"), w4, rtol=1e-12, atol=1e-12)
    printed = a * W2 / c * np.sin(Q - t3) / np.sin(t4s - t3)             # eq. 4.115 as printed
    np.testing.assert_allclose(printed, -sol.omega("rocker"), rtol=1e-12, atol=1e-12)


def test_slider_crank_velocities():
    r2, r3 = 1.0, 3.0
    sol = kl.analyze(kl.mechanisms.slider_crank(r2, r3), q=Q, qd=W2)
    t3 = sol.angle("rod")
    w3 = -r2 * W2 * np.cos(Q) / (r3 * np.cos(t3))                       # eq. 4.60
    v1 = -r2 * W2 * np.sin(Q) - r3 * w3 * np.sin(t3)                     # eq. 4.67
    np.testing.assert_allclose(sol.omega("rod"), w3, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(sol.slide_velocity("slide"), v1, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(sol.velocity("B")[:, 0], v1, rtol=1e-12, atol=1e-12)
