"""kl.cams.motion: S, V, A, J of a program over the cam angle, from a program, its segments or
its tables; V, A, J as derivatives of S by finite differences, and the cycloidal rise in
closed form; profile takes the motion in the program's place."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.cams import Follower, MotionProgram, Segment
from kinelab.errors import ModelError

d = np.radians
TABLES = [{"kind": "rise", "law": "cycloidal", "from": 0.0, "to": d(100), "lift": 0.03},
          {"kind": "dwell", "from": d(100), "to": d(160)},
          {"kind": "return", "law": "4-5-6-7", "from": d(160), "to": d(280), "lift": 0.03},
          {"kind": "dwell", "from": d(280), "to": d(360)}]
SEGMENTS = [Segment("rise", 0.0, d(100), 0.03, "cycloidal"), Segment("dwell", d(100), d(160)),
            Segment("return", d(160), d(280), 0.03, "4-5-6-7"), Segment("dwell", d(280), d(360))]


@pytest.mark.parametrize("given", [TABLES, SEGMENTS, MotionProgram(tuple(SEGMENTS))],
                         ids=["tables", "segments", "program"])
def test_the_same_motion_from_a_program_its_segments_or_its_tables(given):
    theta = np.linspace(0.0, 2 * np.pi, 97)
    m = kl.cams.motion(given, theta)
    ref = MotionProgram(tuple(SEGMENTS)).svaj(theta)
    for lower, upper in zip("svaj", "SVAJ"):
        np.testing.assert_array_equal(getattr(m, lower), getattr(ref, upper))
    assert isinstance(m.program, MotionProgram)


def test_derivatives_against_finite_differences_and_the_cycloid():
    h = 1e-5
    theta = np.linspace(0.01, 2 * np.pi - 0.01, 400)
    theta = theta[np.min(np.abs(theta[:, None] - d([100, 160, 280])[None]), axis=1) > 2e-3]
    m, up, down = (kl.cams.motion(TABLES, t) for t in (theta, theta + h, theta - h))
    for f, derivative in (("s", m.v), ("v", m.a), ("a", m.j)):
        central = (getattr(up, f) - getattr(down, f)) / (2 * h)
        np.testing.assert_allclose(central, derivative, atol=1e-6 * np.abs(derivative).max())
    rise = theta[theta < d(100)]
    x = rise / d(100)                       # cycloidal: h (x - sin(2 pi x) / (2 pi))
    np.testing.assert_allclose(kl.cams.motion(TABLES, rise).s,
                               0.03 * (x - np.sin(2 * np.pi * x) / (2 * np.pi)), atol=1e-15)


def test_profile_takes_the_motion_in_the_programs_place():
    f = Follower("roller", roller_radius=0.01)
    a = kl.cams.profile(kl.cams.motion(TABLES), f, 0.05, samples=73)
    b = kl.cams.profile(MotionProgram(tuple(SEGMENTS)), f, 0.05, samples=73)
    np.testing.assert_array_equal(a.profile, b.profile)
    np.testing.assert_array_equal(a.pressure_angle, b.pressure_angle)


@pytest.mark.parametrize("bad, says", [
    ("rise", "program: expected a MotionProgram"), (42, "program: expected a MotionProgram"),
    ([], "program: expected Segment objects"), ([{"kind": "rise"}], "program[0].law: expected one of"),
    (TABLES[:2], "segments[1]: expected to end at 360 deg"),
    ([SEGMENTS[0], {"kind": "dwell"}], "program: expected Segment objects")])
def test_bad_programs_are_named(bad, says):
    with pytest.raises(ModelError, match=None) as e:
        kl.cams.motion(bad)
    assert str(e.value).startswith(says) and "\n" not in str(e.value)
