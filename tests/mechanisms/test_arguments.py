"""The catalogue's constructors take real lengths of sizes kinelab computes with, nothing else."""
import datetime
import re

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError

FOURBAR = dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
CONSTRUCTORS = [
    (kl.mechanisms.fourbar, FOURBAR),
    (kl.mechanisms.slider_crank, dict(crank=1.0, rod=3.0, offset=0.2)),
    (kl.mechanisms.inverted_slider_crank, dict(ground=2.0, crank=1.0, offset=0.2)),
    (kl.mechanisms.slotted_link, dict(crank=1.0, distance=2.0)),
    (kl.mechanisms.whitworth, dict(crank=1.0, distance=0.5, lever=1.0, rod=2.0)),
    (kl.mechanisms.fivebar, dict(ground=1.0, crank1=1.0, coupler1=1.5, coupler2=1.5, crank2=1.0)),
]


@pytest.mark.parametrize("make, kwargs", CONSTRUCTORS, ids=lambda v: getattr(v, "__name__", ""))
@pytest.mark.parametrize("value", [True, 1 + 0j, "1", datetime.date(2020, 1, 1)], ids=repr)
def test_every_argument_is_a_real_number(make, kwargs, value):
    make(**kwargs)                  # the arguments as they are build it
    for key in kwargs:
        with pytest.raises(ModelError, match=rf"^{key}: expected a (positive length \(m\)|finite "
                                             rf"number), got "):
            make(**{**kwargs, key: value})


@pytest.mark.parametrize("lengths, message", [
    # 3e300 ** 2 overflows, 1e-300 ** 2 underflows to 0: both outside 1e-9 ... 1e9 m
    (dict(ground=3e300, crank=3e300, coupler=3e300, rocker=3e300),
     "ground: expected a length from 1e-09 m to 1e+09 m, got 3e+300 m"),
    (dict(ground=1e-300, crank=1e-300, coupler=1e-300, rocker=1e-300),
     "ground: expected a length from 1e-09 m to 1e+09 m, got 1e-300 m"),
    (dict(ground=3.0, crank=1e-300, coupler=3e300, rocker=2.5),
     "crank: expected a length from 1e-09 m to 1e+09 m, got 1e-300 m\n"
     "coupler: expected a length from 1e-09 m to 1e+09 m, got 3e+300 m"),
])
def test_lengths_out_of_scale_are_refused(lengths, message):
    with pytest.raises(ModelError) as info:
        kl.mechanisms.fourbar(**lengths)
    assert str(info.value).startswith(message)


def test_a_coupler_point_and_crank_angles_are_checked():
    with pytest.raises(ModelError, match=r"^coupler_point: expected \(along, perpendicular\), got 3$"):
        kl.mechanisms.fourbar(**FOURBAR, coupler_point=3)
    with pytest.raises(ModelError, match=r"^q0: expected two crank angles"):
        kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0, q0=(True, "x"))
    with pytest.raises(ModelError, match=r"^points: expected a mapping"):
        kl.mechanisms.triad6(points="O2")


def test_a_whitworth_rod_too_short_is_said_in_its_own_lengths():
    """The catalogue assembles the Whitworth at a crank angle it picks; a rod that cannot reach
    the ram line there is refused with that angle and the distance it would have to span
    (checked here from the geometry: the lever points at the crank pin A)."""
    with pytest.raises(ModelError) as info:
        kl.mechanisms.whitworth(crank=1.0, distance=0.5, lever=1.0, rod=0.1)
    message = str(info.value)
    assert "sketch" not in message
    found = re.fullmatch(r"rod: expected more than ([\d.e+-]+) m, the distance from the lever's "
                         r"end to the ram line at crank angle ([\d.e+-]+) deg \(where the "
                         r"mechanism is first assembled\), got 0\.1 m; lengthen it \(a rod longer "
                         r"than lever \+ \|ram_height\| = 1 m reaches the ram line at every crank "
                         r"angle\)", message)
    assert found, message
    q0 = np.radians(float(found.group(2)))
    A = np.array([np.cos(q0), 0.5 + np.sin(q0)])          # O2 = (0, 0.5), crank 1
    assert float(found.group(1)) == pytest.approx(abs(A[1] / np.hypot(*A)), rel=1e-5)
