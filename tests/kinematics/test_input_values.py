"""analyze takes real numbers for q, qd and qdd: numpy would otherwise turn True into 1.0,
"3" into 3.0 and drop the imaginary part of a complex number."""
import datetime

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError


@pytest.mark.parametrize("arg", ["q", "qd", "qdd"])
@pytest.mark.parametrize("value", [True, np.array([True, False]), 1 + 2j, "1", ["0.1", "0.2"],
                                   datetime.datetime(2020, 1, 1), np.datetime64("2020-01-01"),
                                   10 ** 400], ids=lambda v: type(v).__name__)
def test_only_real_numbers_are_inputs(arg, value):
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    kwargs = {"q": 0.5, arg: value}
    with pytest.raises(ModelError, match=rf"^{arg}: expected numbers, got "):
        kl.analyze(fb, **kwargs)


def test_numpy_numbers_are_inputs():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    a = kl.analyze(fb, q=np.int64(1), qd=np.float32(2.0))
    b = kl.analyze(fb, q=1.0, qd=2.0)
    assert a.omega("coupler") == b.omega("coupler")


def test_whole_numbers_beyond_64_bits_are_numbers():
    """numpy keeps 10**30 as an object; it is a real number all the same (10**400 is not a
    float, and is refused above)."""
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    a = kl.analyze(fb, q=[0.5, 0.6], qd=[10 ** 30, 2])
    b = kl.analyze(fb, q=[0.5, 0.6], qd=[1e30, 2.0])
    np.testing.assert_array_equal(a.omega("coupler"), b.omega("coupler"))
    with pytest.raises(ModelError, match=r"^q: expected angles within 1,000,000 turns"):
        kl.analyze(fb, q=10 ** 30)


@pytest.mark.parametrize("arg", ["q", "qd"])
def test_a_boolean_among_numbers_is_not_a_number(arg):
    """numpy turns [0.1, True] into [0.1, 1.0]: the True is refused, not read as 1."""
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    with pytest.raises(ModelError, match=rf"^{arg}: expected numbers, got \[0.1, true\]$"):
        kl.analyze(fb, **{"q": [0.5, 0.6], arg: [0.1, True]})
