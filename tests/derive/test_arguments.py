"""Arguments of derive, loop_equations, Derivation.evaluate and its documents: a ModelError
naming the argument and the shapes it takes."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.derive import derive, loop_equations
from kinelab.errors import ModelError

FB = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)


@pytest.fixture(scope="module")
def fourbar():
    return derive(FB, dynamics=False)


@pytest.mark.parametrize("kw, message", [
    (dict(notation=5), r"^notation: expected a mapping of keys such as \('angle', 'coupler'\) to "
                       r"symbol names, or None, got 5$"),
    (dict(notation={("input", 0): 3}), r"^notation\[\('input', 0\)\]: expected a non-empty name"),
    (dict(points=["nope"]), r"^points: expected one of 'O2', 'A', 'B', 'O4', got 'nope'$"),
    (dict(points=5), r"^points: expected a sequence of point names, got 5$"),
    (dict(points=[["A"]]), r"^points: expected one of 'O2', 'A', 'B', 'O4', got \['A'\]$"),
])
def test_loop_equations_arguments(kw, message):
    with pytest.raises(ModelError, match=message):
        loop_equations(FB, **kw)


def test_loop_equations_takes_one_point_name_or_several():
    assert set(loop_equations(FB, points="B").position) == {"B"}
    assert set(loop_equations(FB, points=["A", "B"]).position) == {"A", "B"}


@pytest.mark.parametrize("q, message", [
    ("a", r"^q: expected real numbers \(rad or m\), shape \(\) or \(N,\), got 'a'$"),
    (10 ** 400, r"^q: expected real numbers .*got a whole number of 401 digits$"),
    ([], r"^q: expected configurations of 1 input\(s\), shape \(\) or \(N,\), got shape \(0,\)$"),
    ([[0.1, 0.2]], r"^q: expected configurations of 1 input\(s\), .*got shape \(1, 2\)$"),
    (np.nan, r"^q: expected finite numbers, got nan$"),
])
def test_evaluate_arguments(fourbar, q, message):
    with pytest.raises(ModelError, match=message):
        fourbar.evaluate(q)


def test_evaluate_still_takes_n_configurations(fourbar):
    v = fourbar.evaluate([0.1, 0.2, 0.3, 0.4, 0.5])
    assert v.q.shape == (5, 1) and v.S.shape == (5, 2)
    assert np.max(np.abs(v.Phi)) < 1e-10                    # the loops close at every sample


@pytest.mark.parametrize("at, message", [
    ([1, 2, 3, 4, 5], r"^at: expected one configuration of 1 input\(s\), shape \(\), got shape \(5,\)$"),
    ("a", r"^at: expected real numbers \(rad or m\), shape \(\), got 'a'$"),
    (10 ** 400, r"^at: expected real numbers .*got a whole number of 401 digits$"),
])
def test_document_at_is_one_configuration(fourbar, at, message):
    with pytest.raises(ModelError, match=message):
        fourbar.to_markdown(at=at)


def test_document_at_one_configuration_still_works(fourbar):
    assert fourbar.to_markdown(at=0.5) == fourbar.to_markdown(at=[0.5])


def test_derive_dynamics_is_a_boolean():
    with pytest.raises(ModelError, match=r"^dynamics: expected True or False, got 'x'$"):
        derive(FB, dynamics="x")
