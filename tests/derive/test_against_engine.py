"""The derivation against the numeric engine: K and L made numeric from the symbols
(sympy's lambdify) agree with kinelab.analyze at random configurations, for every catalogue
mechanism, every example model and models built for the inputs the catalogue lacks."""
import numpy as np
import pytest

from tests.derive.cases import BUILT, CATALOGUE, EXAMPLES, configurations, derivation

ALL = list(CATALOGUE) + EXAMPLES + list(BUILT)
HEAVY = {"watt6", "stephenson6", "triad6", "stephenson6.toml"}   # symbolic K of size ~100 or more


@pytest.mark.parametrize("name", ALL)
def test_K_and_L_against_analyze(name):
    d = derivation(name)
    q = configurations(d, 3 if name in HEAVY else 8, seed=len(name))
    M = len(d.q)
    v = d.evaluate(q if M > 1 else q[:, 0])
    # the loop equations hold at the engine's S (rounding of the positions: 1e-12 of the size)
    scale = max(1.0, max(abs(x) for x in d.parameters.values()))
    assert np.abs(v.Phi).max() <= 1e-12 * scale
    # exact algebra on both sides: agreement to rounding, relative to the coefficient's size
    np.testing.assert_allclose(v.K, v.K_engine, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(v.L, v.L_engine, rtol=1e-12,
                               atol=1e-12 * max(1.0, np.abs(v.L_engine).max()))
    # and the engine's values are not trivially zero: the comparison could fail
    assert np.abs(v.K_engine).max() > 1e-3


@pytest.mark.parametrize("name", ALL)
def test_det_J_vanishes_with_the_engines(name):
    """Both determinants are products of the same factors (dyad by dyad), scaled differently:
    their signs agree up to one flip for the whole model, and neither is zero here."""
    d = derivation(name)
    q = configurations(d, 3 if name in HEAVY else 6, seed=1 + len(name))
    v = d.evaluate(q if len(d.q) > 1 else q[:, 0])
    assert np.all(np.abs(v.det_J) > 1e-9) and np.all(np.abs(v.engine_det_J) > 1e-9)
    ratio_sign = np.sign(v.det_J * v.engine_det_J)
    assert np.all(ratio_sign == ratio_sign[0])


def test_K_against_finite_differences_of_the_engines_positions():
    """K from the symbols is dS/dq: a central difference of the engine's S agrees to h^2."""
    import kinelab as kl
    d = derivation("whitworth")
    q = configurations(d, 4, seed=5)[:, 0]
    h = 1e-5
    v = d.evaluate(q)
    for i, s in enumerate(d.S):
        kind, name = d.unknowns[s]
        get = (lambda sol: sol.angle(name)) if kind == "angle" else (lambda sol: sol.slide(name))
        up, down = get(kl.analyze(d.model, q + h)), get(kl.analyze(d.model, q - h))
        diff = (np.unwrap(np.stack([down, up]), axis=0)[1] - down) / (2 * h) if kind == "angle" \
            else (up - down) / (2 * h)
        np.testing.assert_allclose(v.K[:, i, 0], diff, rtol=0, atol=1e-8)


def test_the_contracts_shapes():
    import sympy as sp
    one, two = derivation("slotted_link"), derivation("fivebar")
    assert isinstance(one.Phi, sp.MatrixBase) and one.Phi.shape == (2, 1)
    assert one.K.shape == (2, 1) and isinstance(one.L, sp.MatrixBase) and one.L.shape == (2, 1)
    assert len(two.q) == 2 and two.K.shape == (2, 2) and two.Q.shape == (2, 2)
    assert isinstance(two.L, sp.NDimArray) and two.L.shape == (2, 2, 2)
    assert set(two.unknowns.values()) == {("angle", "coupler1"), ("angle", "coupler2")}
    assert list(two.inputs.values()) == ["jO2", "jO4"]
    # L of several inputs is symmetric in its input indices (a second derivative of S)
    v = two.evaluate(configurations(two, 2, seed=3))
    assert abs(v.L - v.L.transpose(0, 1, 3, 2)).max() < 1e-12
