"""The catalogue's spherical four-bar: the same linkage as kinelab.spatial.SphericalFourBar."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.spatial import SphericalFourBar

ARCS = [(0.4, 0.3, 1.0, 0.9), (np.pi / 6, np.pi / 2, np.pi / 2, np.pi / 2), (1.2, 0.7, 1.3, 1.1)]


@pytest.mark.parametrize("arcs", ARCS)
@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_equals_the_spatial_linkage(arcs, branch):
    made = kl.mechanisms.spherical_fourbar(*arcs, branch=branch)
    ref = SphericalFourBar(alpha1=arcs[0], alpha2=arcs[1], alpha3=arcs[2], alpha4=arcs[3],
                           branch=branch)
    assert made == ref and type(made) is SphericalFourBar
    # and it moves the same: same analysis on the same inputs
    q = np.linspace(-0.5, 0.5, 11)
    a, b = made.analyze(q, 1.0, unreachable="mask"), ref.analyze(q, 1.0, unreachable="mask")
    np.testing.assert_array_equal(a.theta4, b.theta4)
    np.testing.assert_array_equal(a.K3, b.K3)


def test_degrees_are_converted_once():
    made = kl.mechanisms.spherical_fourbar(30, 90, 90, 90, "crossed", degrees=True)
    assert made.arcs == pytest.approx(tuple(np.radians([30.0, 90.0, 90.0, 90.0])), abs=1e-15)
    assert made.branch == "crossed"


def test_keywords_as_the_class_takes_them():
    made = kl.mechanisms.spherical_fourbar(alpha1=0.4, alpha2=0.3, alpha3=1.0, alpha4=0.9)
    assert made == SphericalFourBar(alpha1=0.4, alpha2=0.3, alpha3=1.0, alpha4=0.9)


def test_hooke_joint_speed_ratio_by_hand():
    # a Cardan joint at 30 deg: the output's speed ratio swings between cos 30 and 1 / cos 30
    sol = kl.mechanisms.spherical_fourbar(30, 90, 90, 90, degrees=True).analyze(
        np.radians([0.0, 90.0]), 1.0)
    np.testing.assert_allclose(sol.omega4, [1 / np.cos(np.pi / 6), np.cos(np.pi / 6)], rtol=1e-12)


@pytest.mark.parametrize("args, kwargs, message", [
    ((0.4, 0.3, 1.0, 0.0), {}, r"^alpha4: expected an arc in \(0, π\) rad \(the great-circle angle "
     r"between two joint axes\), got 0\.0; an arc of 0 or π puts two axes on one line$"),
    ((30, 90, 200, 90), dict(degrees=True), r"^alpha3: expected an arc in \(0, 180\) deg .*got 200; "
     r"an arc of 0 or 180 deg puts two axes on one line$"),
    ((0.4, "x", 1.0, 0.9), {}, r"^alpha2: expected an arc in \(0, π\) rad \(a real number\), got 'x'$"),
    ((0.4, 0.3, 1.0, 0.9), dict(branch="cross"), r"^branch: expected one of 'open', 'crossed', got 'cross'"),
    ((0.4, 0.3, 1.0, 0.9), dict(degrees="yes"), r"^degrees: "),
])
def test_bad_input_one_line_naming_the_field(args, kwargs, message):
    with pytest.raises(ModelError, match=message) as info:
        kl.mechanisms.spherical_fourbar(*args, **kwargs)
    assert "\n" not in str(info.value)
