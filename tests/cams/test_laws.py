"""Motion laws and programs: S, V, A, J against finite differences of S, the laws' boundary
values and peaks (Norton, Design of Machinery, table 8-3), continuity at the joints."""
import math

import numpy as np
import pytest

from kinelab.cams import LAWS, MotionProgram, Segment, law_values
from kinelab.errors import ModelError

d = np.radians
H, BETA = 0.03, 1.2          # a rise of 30 mm over 1.2 rad
BREAKS = (0.0, 1 / 8, 3 / 8, 5 / 8, 7 / 8, 1.0)     # where piecewise laws change piece


def rise(law, lift=H, beta=BETA):
    return MotionProgram([Segment("rise", 0.0, beta, lift, law),
                          Segment("return", beta, 2 * beta, lift, law),
                          Segment("dwell", 2 * beta, 2 * math.pi)], allow_discontinuous=True)


def samples(beta=BETA, h=0.0):
    """Cam angles inside the rise, at least 4 h from its ends and the laws' inner breaks."""
    x = np.linspace(0.01, 0.99, 97)
    keep = np.all(np.abs(x[:, None] - np.array(BREAKS)) > 4 * h / beta + 1e-3, axis=1)
    return x[keep] * beta


@pytest.mark.parametrize("law", list(LAWS))
def test_V_A_J_against_central_differences_of_S(law):
    # fourth-order central stencils on S alone; h sized so that truncation (h**4) and
    # rounding (eps / h**k) both stay well below 1e-6 of each quantity's peak
    p = rise(law)
    S = lambda t: p.svaj(t).S
    for h, k, stencil in ((1e-3, 1, lambda t, h: (-S(t + 2 * h) + 8 * S(t + h) - 8 * S(t - h)
                                                      + S(t - 2 * h)) / (12 * h)),
                          (2e-3, 2, lambda t, h: (-S(t + 2 * h) + 16 * S(t + h) - 30 * S(t)
                                                  + 16 * S(t - h) - S(t - 2 * h)) / (12 * h * h)),
                          (4e-3, 3, lambda t, h: (-S(t + 3 * h) + 8 * S(t + 2 * h) - 13 * S(t + h)
                                                  + 13 * S(t - h) - 8 * S(t - 2 * h) + S(t - 3 * h))
                                                 / (8 * h ** 3))):
        t = samples(h=3 * h)
        exact = [None, p.svaj(t).V, p.svaj(t).A, p.svaj(t).J][k]
        scale = np.abs([None, p.svaj(samples()).V, p.svaj(samples()).A, p.svaj(samples()).J][k]).max()
        assert np.abs(stencil(t, h) - exact).max() <= 1e-6 * scale, (law, "SVAJ"[k])


# peak velocity and acceleration factors, V = Cv h / beta, A = Ca h / beta**2: Norton's
# (Design of Machinery, ch. 8) for the modified trapezoid and sine; the others by hand:
# pi/2, pi**2/2; 2, 2 pi; 15/8, 10/sqrt(3); 35/16 and f'' at x = (5 - sqrt(5))/10
_X = (5 - math.sqrt(5)) / 10
PEAKS = {"harmonic": (math.pi / 2, math.pi ** 2 / 2), "cycloidal": (2.0, 2 * math.pi),
         "3-4-5": (15 / 8, 10 / math.sqrt(3)),
         "4-5-6-7": (35 / 16, 420 * _X ** 2 - 1680 * _X ** 3 + 2100 * _X ** 4 - 840 * _X ** 5),
         "modified-trapezoid": (2.0000, 4.8881), "modified-sine": (1.7596, 5.5280)}


@pytest.mark.parametrize("law", list(LAWS))
def test_boundary_values_and_peaks(law):
    f, f1, f2, f3 = law_values(law, np.array([0.0, 1.0]))
    assert f == pytest.approx([0.0, 1.0], abs=1e-12)
    assert f1 == pytest.approx([0.0, 0.0], abs=1e-12)
    if law == "harmonic":          # A jumps from 0 at both ends: pi**2 / 2
        assert f2 == pytest.approx([math.pi ** 2 / 2, -math.pi ** 2 / 2], rel=1e-12)
    else:
        assert f2 == pytest.approx([0.0, 0.0], abs=1e-12)
    if law == "4-5-6-7":           # jerk zero at the ends too
        assert f3 == pytest.approx([0.0, 0.0], abs=1e-12)
    x = np.linspace(0, 1, 200001)
    g = law_values(law, x)
    cv, ca = PEAKS[law]
    assert np.abs(g[1]).max() == pytest.approx(cv, abs=6e-5)
    assert np.abs(g[2]).max() == pytest.approx(ca, abs=6e-5)


def test_per_time_values_at_a_cam_speed():
    sv = rise("cycloidal").svaj(np.array([0.3]))
    s, v, a, j = sv.in_time(10.0)
    assert (s, v, a, j) == (sv.S, 10 * sv.V, 100 * sv.A, 1000 * sv.J)


def test_continuity_report_names_every_acceleration_jump_of_a_harmonic_program():
    p = MotionProgram([Segment("rise", 0, d(90), 0.02, "harmonic"), Segment("dwell", d(90), d(180)),
                       Segment("return", d(180), d(270), 0.02, "cycloidal"),
                       Segment("dwell", d(270), d(360))])
    jumps = p.discontinuities
    assert [(j.quantity, round(math.degrees(j.angle))) for j in jumps] == [("A", 90), ("A", 0)]
    a = 0.02 * math.pi ** 2 / 2 / d(90) ** 2
    assert jumps[0].jump == pytest.approx(a, rel=1e-12)        # from -a to 0
    assert jumps[1].jump == pytest.approx(a, rel=1e-12)        # from 0 to a at 360 = 0 deg
    assert not any(j.error for j in jumps)
    assert "fundamental law of cam design" in str(jumps[0])


def test_cycloidal_and_3_4_5_programs_are_continuous():
    for law in ("cycloidal", "3-4-5", "modified-sine"):
        p = MotionProgram([Segment("rise", 0, d(120), 0.02, law), Segment("dwell", d(120), d(180)),
                           Segment("return", d(180), d(300), 0.02, law),
                           Segment("dwell", d(300), d(360))])
        assert p.discontinuities == ()


def test_a_jump_of_S_is_an_error_unless_allowed():
    segs = [Segment("rise", 0, d(180), 0.025, "cycloidal"),
            Segment("return", d(180), d(360), 0.020, "cycloidal")]
    with pytest.raises(ModelError, match=r"S jumps by -0.005 at 0 deg, between segments 2 and 1"):
        MotionProgram(segs)
    p = MotionProgram(segs, allow_discontinuous=True)
    assert [(j.quantity, j.error) for j in p.discontinuities] == [("S", True)]


def test_a_jump_of_V_is_an_error():
    poly = Segment("rise", d(90), d(180), law="polynomial",
                   conditions=((d(90), 0, 0.0), (d(90), 1, 0.01), (d(180), 0, 0.02),
                               (d(180), 1, 0.0)))
    segs = [Segment("dwell", 0, d(90)), poly, Segment("return", d(180), d(360), 0.02, "cycloidal")]
    with pytest.raises(ModelError, match=r"V jumps by 0.01 at 90 deg"):
        MotionProgram(segs)


def test_polynomial_meets_its_boundary_conditions():
    conds = ((d(30), 0, 0.001), (d(30), 1, 0.004), (d(30), 2, -0.01), (d(100), 0, 0.02),
             (d(100), 1, 0.0), (d(100), 2, 0.0), (d(100), 3, 0.05), (d(60), 0, 0.012))
    p = MotionProgram([Segment("dwell", 0, d(30)), Segment("rise", d(30), d(100), law="polynomial",
                                                           conditions=conds),
                       Segment("dwell", d(100), d(360))], allow_discontinuous=True)
    assert len(p.coefficients[1]) == 8
    for t, order, value in conds:
        x = (t - d(30)) / d(70)
        got = p._segment_values(1, np.array([x]))[order][0]
        assert got == pytest.approx(value, rel=1e-10, abs=1e-13)


def test_polynomial_through_the_3_4_5_conditions_is_the_3_4_5_law():
    zero = ((0.0, 1, 0.0), (0.0, 2, 0.0), (BETA, 1, 0.0), (BETA, 2, 0.0))
    poly = MotionProgram([Segment("rise", 0, BETA, law="polynomial",
                                  conditions=((0.0, 0, 0.0), (BETA, 0, H)) + zero),
                          Segment("return", BETA, 2 * math.pi, H, "3-4-5")])
    law = rise("3-4-5")
    t = np.linspace(0, BETA, 50, endpoint=False)     # BETA itself starts the return
    for q in "SVAJ":
        assert getattr(poly.svaj(t), q) == pytest.approx(getattr(law.svaj(t), q), rel=1e-9, abs=1e-12)


def test_gaps_overlaps_zero_lifts_and_unknown_laws_are_refused_at_once():
    segs = [Segment("rise", 0, d(90), 0.0, "cycloidal"), Segment("dwell", d(100), d(180)),
            Segment("return", d(170), d(350), 0.02, "cycloid")]
    with pytest.raises(ModelError) as e:
        MotionProgram(segs)
    text = str(e.value)
    assert "segments[0].lift: expected the rise's travel, above 0, got 0" in text
    assert "segments[2].law: expected one of" in text and "(did you mean 'cycloidal'?)" in text
    segs[2] = Segment("return", d(170), d(350), 0.02, "cycloidal")
    segs[0] = Segment("rise", 0, d(90), 0.02, "cycloidal")
    with pytest.raises(ModelError) as e:
        MotionProgram(segs)
    text = str(e.value)
    assert "segments[1]: a gap from 90 deg to 100 deg after segments[0]" in text
    assert "segments[2]: overlaps segments[1] from 170 deg to 180 deg" in text
    assert "segments[2]: expected to end at 360 deg, got 350 deg" in text


def test_the_lowest_level_is_zero_when_the_program_starts_with_a_return():
    p = MotionProgram([Segment("return", 0, d(120), 0.02, "cycloidal"),
                       Segment("dwell", d(120), d(200)),
                       Segment("rise", d(200), d(360), 0.02, "cycloidal")])
    sv = p.svaj(samples=361)
    assert sv.S.min() == pytest.approx(0.0, abs=1e-15) and sv.S[0] == pytest.approx(0.02)
