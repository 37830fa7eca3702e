"""The in-line slider-crank as a test system for the solvers (*Mecanismos*, eqs. 38-39).

Unknowns x = (θ3, l), parameter θ2; L2 crank, L3 rod.
"""
import numpy as np


def equations(L2, L3):
    """fun(x, θ2), jac(x, θ2) = ∂Φ/∂x and dfun_dp(x, θ2) = ∂Φ/∂θ2, for x of shape (N, 2)."""
    def fun(x, th2):
        th3, l = x[:, 0], x[:, 1]
        return np.stack([L2 * np.cos(th2) + L3 * np.cos(th3) - l,
                         L2 * np.sin(th2) + L3 * np.sin(th3)], axis=-1)

    def jac(x, th2):
        th3 = x[:, 0]
        one = np.ones_like(th3)
        return np.stack([np.stack([-L3 * np.sin(th3), -one], -1),
                         np.stack([L3 * np.cos(th3), 0 * one], -1)], -2)

    def dfun_dp(x, th2):
        zero = np.zeros_like(x[:, 0])
        return np.stack([-L2 * np.sin(th2) + zero, L2 * np.cos(th2) + zero], -1)
    return fun, jac, dfun_dp


def closed_form(L2, L3, th2):
    """(θ3, l) on the branch with the slider to the right of the crank pivot."""
    th3 = -np.arcsin(L2 * np.sin(th2) / L3)
    return th3, L2 * np.cos(th2) + L3 * np.cos(th3)
