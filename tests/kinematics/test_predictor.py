"""The continuation's quintic predictor (one input): through the last two solved states'
S, K and L it is exact for a quintic path, in the compiled kernel (``_hermite_terms``) and
in its numpy form (``_State.hermite_terms``) alike, and it applies only where it should."""
import types

import numpy as np
import pytest

from kinelab.kinematics import _codes as k
from kinelab.kinematics import _interpreter
from kinelab.kinematics import _kernel

RNG = np.random.default_rng(7)
COEFFS = RNG.normal(size=(3, 6))            # three unknowns, each a quintic in q


def path(q, derivative=0):
    """The unknowns' values (derivative 0), K (1) or L (2) at input q."""
    out = []
    for c in COEFFS:
        p = np.polynomial.Polynomial(c)
        out.append(p.deriv(derivative)(q) if derivative else p(q))
    return np.array(out)


def states(q0, h):
    """The kernel's state arrays with the last state at q0 and the one before at q0 - h:
    gx (2n,), gK (2n, 1), gL (2n, 1, 1), gq (2, 1) for one group of n = 3 unknowns."""
    q1 = q0 - h
    gx = np.concatenate([path(q0), path(q1)])
    gK = np.concatenate([path(q0, 1), path(q1, 1)])[:, None]
    gL = np.concatenate([path(q0, 2), path(q1, 2)])[:, None, None]
    gq = np.array([[q0], [q1]])
    return gx, gK, gL, gq


def predicted_by_kernel(q0, h, q):
    gx, gK, gL, gq = states(q0, h)
    u = _kernel._hermite_reach(np.array([q]), gq, 0, 1, 1)
    dq = q - q0
    return np.array([gx[i] + gK[i, 0] * dq + 0.5 * gL[i, 0, 0] * dq * dq
                     + (_kernel._hermite_terms(gx, gK, gL, gq, 0, 1, i, 3 + i, u) if u else 0.0)
                     for i in range(3)]), u


def predicted_by_numpy_form(q0, h, q):
    gx, gK, gL, gq = states(q0, h)
    state = _interpreter._State(gx[:3], 1, 1)
    state.x, state.K, state.L, state.q = gx[:3].copy(), gK[:3].copy(), gL[:3].copy(), gq[:1].copy()
    state.x1, state.K1, state.L1, state.q1 = gx[3:].copy(), gK[3:].copy(), gL[3:].copy(), gq[1:].copy()
    group = types.SimpleNamespace(o=0, n=3, g=0)
    dq = q - q0
    taylor = state.x + state.K[:, 0] * dq + 0.5 * state.L[:, 0, 0] * dq * dq
    terms = state.hermite_terms(group, np.array([q]), 1)
    return taylor + (0.0 if terms is None else terms), terms is not None


@pytest.mark.parametrize("u", [-0.5, 0.5, 1.0, 1.7, 1.99])
def test_a_quintic_path_is_predicted_exactly_by_both_forms(u):
    q0, h = 0.3, 0.0873
    q = q0 + u * h
    exact = path(q)
    by_kernel, reach = predicted_by_kernel(q0, h, q)
    by_numpy, applied = predicted_by_numpy_form(q0, h, q)
    assert reach == pytest.approx(u, rel=1e-12) and applied
    assert by_kernel == pytest.approx(exact, rel=1e-11, abs=1e-12)
    assert by_numpy == pytest.approx(by_kernel, rel=1e-13, abs=1e-14)
    # the parabola of the last state alone misses by the cubic and higher terms
    dq = q - q0
    parabola = path(q0) + path(q0, 1) * dq + 0.5 * path(q0, 2) * dq * dq
    assert np.abs(parabola - exact).max() > 1e3 * np.abs(by_kernel - exact).max()


def test_the_quintic_is_not_used_beyond_its_reach_or_without_a_state_before():
    q0, h = 0.3, 0.0873
    far = q0 + (k.HERMITE_REACH + 0.1) * h
    assert predicted_by_kernel(q0, h, far)[1] == 0.0
    assert not predicted_by_numpy_form(q0, h, far)[1]
    gx, gK, gL, gq = states(q0, h)
    gq[1, 0] = np.nan                       # no state before (the first step of a run)
    assert _kernel._hermite_reach(np.array([q0 + h]), gq, 0, 1, 1) == 0.0
    gq[1, 0] = q0                           # two states at one input
    assert _kernel._hermite_reach(np.array([q0 + h]), gq, 0, 1, 1) == 0.0
    two_inputs = np.zeros((2, 2))
    assert _kernel._hermite_reach(np.zeros(2), two_inputs, 0, 1, 2) == 0.0
