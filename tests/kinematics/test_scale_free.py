"""Nothing depends on the unit a mechanism is drawn in: the same mechanism scaled by s gives
the same angles, K and L of angles, the same singular flags, reachable ranges and change
points, and positions, velocities and accelerations multiplied by s (slides too; a slide
input's values, rates, and the K and L taken with respect to it, by their own powers of s).

The scaled mechanism is not the same numbers: s times a float is rounded, so every output
differs by rounding, amplified near a singular configuration as the module docstring of
``tests/kinematics/test_interpreter.py`` says.  The comparison is to 1e-9 of each output's
unit (1 rad, or the mechanism's size), and, for K and L, of their own size; L also with the
conditioning of the sample (1/s**3, at most 1/SINGULAR_TOL**3 where nothing is flagged).
"""
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl
from kinelab.kinematics._analyze import SINGULAR_TOL, plan
from tests.kinematics.scaling import input_units, scaled
from tests.kinematics.test_engine import CATALOGUE, _hydraulic_boom, _with_input

REL = 1e-9
EXAMPLES = sorted(Path(__file__).parents[2].joinpath("examples").glob("*.toml"))

# Pyslvs' own example six-bars (its example list, "Stephenson II" and "Stephenson III"),
# drawn in mm: each has a group of four links that kinelab solves by Newton-Raphson.
PYSLVS = {
    "stephenson_ii": "M[J[R, P[-45.0, -15.5], L[ground, L1]], J[R, P[-52.0, 25.5], L[L1, L2]], "
                     "J[R, P[-36.0, 76.25], L[L2, L5]], J[R, P[-4.0, 3.0], L[L2, L4]], "
                     "J[R, P[29.0, 27.5], L[L3, L4]], J[R, P[85.25, -27.25], L[ground, L3]], "
                     "J[R, P[57.5, 77.0], L[L3, L5]]]",
    "stephenson_iii": "M[J[R, P[0.25, -0.625], L[ground, L1]], J[R, P[15.375, 41.125], L[L1, L2]], "
                      "J[R, P[61.375, 95.125], L[L2, L3]], J[R, P[102.875, 84.375], L[L3, L4]], "
                      "J[R, P[117.125, 23.375], L[ground, L4]], J[R, P[134.625, 119.875], L[L3, L5]], "
                      "J[R, P[138.875, 33.125], L[ground, L5]]]",
}

MODELS = {
    **CATALOGUE,
    "fivebar": lambda: kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0),
    "piston_driven": lambda: _with_input(kl.mechanisms.slider_crank(1.0, 3.0, 0.2),
                                         kl.model.Input(joint="slide")),
    "boom": _hydraulic_boom,
    **{f"pyslvs_{name}": (lambda e=e: kl.io.from_pyslvs(e, inputs=[(0, 1)]))
       for name, e in PYSLVS.items()},
    **{f"example_{p.stem}": (lambda p=p: kl.load(p)) for p in EXAMPLES},
}


def samples(m, method):
    """Inputs over the mechanism's reach (one input), or around its sketch (two)."""
    p = plan(m, method=method)
    if len(m.inputs) > 1:
        q0 = p.q_sketch
        return q0 + np.stack(np.meshgrid(np.linspace(-0.2, 0.2, 7), np.linspace(-0.2, 0.2, 7)),
                             -1).reshape(-1, 2)
    q0 = p.q_sketch[0]
    lo, hi = next(r for r in kl.kinematics.reachable_ranges(m, method=method) if r[0] <= q0 <= r[1])
    return lo + (hi - lo) * np.linspace(0.01, 0.99, 121)


def units(sol, s):
    """Each stored item's and each input's unit at scale s: 1 for angles, s for lengths."""
    p = sol.plan
    item = np.where(p.stored_items < p.n_angles, 1.0, s * p.scale)
    inp = np.array([1.0 if kind == "angle" else s * p.scale for kind in p.input_kinds])
    return item, inp


@given(name=st.sampled_from(sorted(MODELS)), k=st.integers(-4, 4),
       mantissa=st.sampled_from([1.0, 2.54, math.pi / 3]), method=st.sampled_from(["auto", "newton"]))
def test_a_scaled_mechanism_moves_the_same(name, k, mantissa, method):
    m = MODELS[name]()
    if any(j.type in ("G", "C") for j in m.joints):
        method = "auto"          # gear and cam joints are solved in closed form only: no Newton plan
    s = mantissa * 10.0 ** k
    ms = scaled(m, s)
    q = samples(m, method)
    u = np.array(input_units(m, s))
    rng = np.random.default_rng(7)
    qd, qdd = rng.normal(size=q.shape), rng.normal(size=q.shape)
    ref = kl.analyze(m, q, qd, qdd, method=method, at_singular="flag", unreachable="mask")
    got = kl.analyze(ms, q * u, qd * u, qdd * u, method=method, at_singular="flag",
                     unreachable="mask")
    np.testing.assert_array_equal(got.assembled, ref.assembled)
    ok = ref.assembled
    # the singularity measure is dimensionless; the flags agree but for a sample whose
    # measure is at the threshold to rounding
    measure_a, measure_b = ref.singularity[ok], got.singularity[ok]
    cond = 1.0 / np.clip(measure_a, 1e-8, 1.0)
    assert np.all(np.abs(measure_b - measure_a) <= REL * cond)
    at_threshold = np.abs(measure_a - SINGULAR_TOL) <= REL * cond
    np.testing.assert_array_equal(got.singular[ok][~at_threshold], ref.singular[ok][~at_threshold])

    # every stored coordinate: value, K and L, each in its unit at its scale
    regular = ok & ~ref.singular & ~got.singular
    ja, jb = ref.stored_jets[regular], got.stored_jets[regular]
    ia, pa = units(ref, 1.0)
    ib, pb = units(got, 1.0)
    np.testing.assert_allclose(ib / ia, np.where(ref.plan.stored_items < ref.plan.n_angles, 1.0,
                                                 got.plan.scale / ref.plan.scale), rtol=1e-12)
    angles = ref.plan.stored_items < ref.plan.n_angles
    factor = np.where(angles, 1.0, s)                          # of each item's value
    M = len(m.inputs)
    c = cond[~ref.singular[ok] & ~got.singular[ok]][:, None]
    value_a = ja[..., 0] * factor
    dv = jb[..., 0] - value_a
    dv[:, angles] = np.angle(np.exp(1j * dv[:, angles]))      # across the wrap
    assert np.all(np.abs(dv) <= REL * ib * c), f"values differ by {np.max(np.abs(dv) / (ib * c)):.2e}"
    K_factor = factor[:, None] / u[None, :]
    Ka, Kb = ja[..., 1:1 + M] * K_factor, jb[..., 1:1 + M]
    assert np.all(np.abs(Kb - Ka) <= REL * (ib[:, None] / pb[None, :] + np.abs(Ka)) * c[..., None] ** 2)
    L_factor = factor[:, None, None] / (u[None, :, None] * u[None, None, :])
    La = ja[..., 1 + M:].reshape(len(ja), -1, M, M) * L_factor
    Lb = jb[..., 1 + M:].reshape(len(jb), -1, M, M)
    tol = REL * (ib[:, None, None] / (pb[None, :, None] * pb[None, None, :]) + np.abs(La)) * c[..., None, None] ** 3
    assert np.all(np.abs(Lb - La) <= tol), f"L differs by {np.max(np.abs(Lb - La) / tol):.2e} x tol"

    if M == 1 and ref.plan.input_kinds == ("angle",):
        ra = kl.kinematics.reachable_ranges(m, method=method)
        rb = kl.kinematics.reachable_ranges(ms, method=method)
        np.testing.assert_allclose(rb, ra, rtol=0, atol=1e-9)
        if method == "auto" and ref.plan.groups is None:
            lo, hi = q.min() - 2 * np.pi, q.max() + 2 * np.pi
            ca = kl.kinematics.change_points(m, lo, hi)
            cb = kl.kinematics.change_points(ms, lo, hi)
            assert [c.links for c in cb] == [c.links for c in ca]
            np.testing.assert_allclose([c.q for c in cb], [c.q for c in ca], rtol=0, atol=1e-9)


@pytest.mark.parametrize("expression", sorted(PYSLVS))
@pytest.mark.parametrize("unit", ["mm", "cm", "m", "in"])
def test_pyslvs_six_bars_have_velocities_in_every_unit(expression, unit):
    """Pyslvs' Stephenson II and III, read in any unit: their group of four links is far from
    singular over the whole reach (its measure, the smallest singular value of its scaled
    Jacobian, stays above 0.01), so every sample has finite angular velocities and
    accelerations."""
    m = kl.io.from_pyslvs(PYSLVS[expression], inputs=[(0, 1)], length=unit)
    q = samples(m, "auto")
    sol = kl.analyze(m, q, qd=1.0, qdd=0.5)
    assert sol.assembled.all() and not sol.singular.any()
    assert sol.singularity.min() > 0.01
    for link in m.link_names:
        assert np.isfinite(sol.omega(link)).all() and np.isfinite(sol.alpha(link)).all()
    one = kl.analyze(m, float(q[len(q) // 2]), qd=1.0)        # --at: one configuration
    assert np.isfinite(one.omega("L3"))
