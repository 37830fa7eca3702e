"""The summary of a sweep against closed forms worked by hand."""
import math

import numpy as np
import pytest

import kinelab as kl
from kinelab.io import ModelFile, summary

# crank-rocker of examples/crank_rocker.toml: ground d = 0.3, crank a = 0.1, coupler b = 0.3,
# rocker c = 0.25 (m).  Its sketch is written to 1e-6 mm, so its lengths agree with these to
# about 1e-9 relative: the tolerances below allow for that.
d, a, b, c = 0.3, 0.1, 0.3, 0.25


@pytest.fixture(scope="module")
def crank_rocker():
    mf = ModelFile.read("examples/crank_rocker.toml")
    sol = kl.analyze(mf.mechanism, np.radians(np.arange(0.0, 360.0, 0.25)), 1.0)
    return summary(sol, report=("rocker", "P"), transmission=(("coupler", "rocker"),),
                   time_ratio="rocker")


def _rocker_angle(O2B):
    # triangle O2-O4-B: the rocker's angle from +x is pi minus the angle at O4
    cos_o4 = (d * d + c * c - O2B * O2B) / (2 * d * c)
    return math.pi - math.acos(cos_o4)


def test_grashof_class_and_lengths_from_the_sketch(crank_rocker):
    g = crank_rocker.grashof
    assert (g.kind, g.barker) == ("crank-rocker", "GCRR")
    np.testing.assert_allclose(crank_rocker.grashof_lengths, (d, a, b, c), rtol=1e-8)
    assert crank_rocker.full_turn and crank_rocker.reachable[0][1] - crank_rocker.reachable[0][0] \
        == pytest.approx(2 * math.pi, abs=1e-12)


def test_rocker_extremes_are_the_toggle_positions(crank_rocker):
    # the rocker swings between crank and coupler extended (O2B = a + b: its smallest angle
    # from +x) and folded (O2B = b - a: its largest)
    e = {x.name: x for x in crank_rocker.extremes}["rocker.angle"]
    assert e.min == pytest.approx(_rocker_angle(a + b), abs=2e-6)     # 0.25 deg grid: O(h^2)
    assert e.max == pytest.approx(_rocker_angle(b - a), abs=2e-6)
    assert not e.full_turn and e.angle
    # extended: the crank points along O2B; folded: opposite to it
    cos_ext = (d * d + (a + b) ** 2 - c * c) / (2 * d * (a + b))
    cos_fold = (d * d + (b - a) ** 2 - c * c) / (2 * d * (b - a))
    assert e.at_min[0] == pytest.approx(math.acos(cos_ext), abs=math.radians(0.25))
    assert e.at_max[0] == pytest.approx(math.pi + math.acos(cos_fold), abs=math.radians(0.25))


def test_time_ratio_from_the_toggle_angles(crank_rocker):
    cos_ext = (d * d + (a + b) ** 2 - c * c) / (2 * d * (a + b))
    cos_fold = (d * d + (b - a) ** 2 - c * c) / (2 * d * (b - a))
    slow = math.pi + math.acos(cos_fold) - math.acos(cos_ext)
    r = crank_rocker.quick_return
    assert r.output == "rocker"
    assert r.ratio == pytest.approx(slow / (2 * math.pi - slow), rel=1e-8)


def test_minimum_transmission_angle_with_the_crank_towards_o4(crank_rocker):
    # at q = 0, |A O4| = d - a: cos mu = (b^2 + c^2 - (d - a)^2) / (2 b c) = 0.75
    t = crank_rocker.transmission[0]
    assert t.links == ("coupler", "rocker") and not t.from_normal
    assert t.min == pytest.approx(math.acos(0.75), abs=1e-8)
    assert t.at_min[0] in (0.0, pytest.approx(2 * math.pi))
    assert t.max == pytest.approx(math.pi / 2, abs=3e-3)    # folded at 90 deg: a kink, O(h)


def test_no_singular_position_in_a_crank_rocker(crank_rocker):
    assert crank_rocker.singular == () and crank_rocker.unassembled == 0
    # the least distance from singularity is sin(mu_min)
    assert crank_rocker.least_singularity[0] == pytest.approx(math.sqrt(1 - 0.75 ** 2), abs=1e-8)


def test_offset_slider_crank_transmission_from_the_slide_normal():
    mf = ModelFile.read("examples/offset_slider_crank.toml")
    sol = kl.analyze(mf.mechanism, *mf.sample_inputs(1441))
    s = summary(sol)
    t = s.transmission[0]
    assert t.links == ("rod", "slider") and t.from_normal
    # the rod leans most when the crank points down: sin = (offset + crank) / rod = 70 / 200
    assert t.min == pytest.approx(math.pi / 2 - math.asin(0.35), abs=1e-9)
    assert t.at_min[0] == pytest.approx(1.5 * math.pi, abs=1e-12)
    assert s.grashof is None
    assert {e.name for e in s.extremes} >= {"rod.angle", "slide.slide", "slide.slide_velocity"}


def test_non_grashof_limits_and_singular_ends():
    fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    mf = ModelFile(fb)
    sol = kl.analyze(fb, *mf.sample_inputs(401), at_singular="flag")
    s = summary(sol)
    hi = math.acos(-5 / 16)
    assert s.grashof.kind == "triple-rocker" and not s.full_turn
    assert s.reachable == (pytest.approx((-hi, hi), abs=1e-10),)
    assert s.least_singularity[0] < 1e-3          # the sweep runs to the limit positions
    assert s.quick_return is None


def test_quick_return_of_the_slotted_link_is_two():
    # Erthal's slotted link, R = 100, C = 200 mm: the lever reverses where the crank is
    # perpendicular to
    # it, cos q = -R / C: strokes 240 and 120 deg
    mf = ModelFile.read("examples/slotted_link.toml")
    s = summary(kl.analyze(mf.mechanism, *mf.sample_inputs(181)), time_ratio="lever")
    assert s.quick_return.ratio == pytest.approx(2.0, rel=1e-10)
    np.testing.assert_allclose(sorted(s.quick_return.dead_centres),
                               [2 * math.pi / 3, 4 * math.pi / 3], atol=1e-10)


def test_five_bar_summary_names_both_inputs():
    mf = ModelFile.read("examples/fivebar.toml")
    s = summary(kl.analyze(mf.mechanism, *mf.sample_inputs(73)), report=("P",))
    assert s.inputs == ("jO2", "jO4") and s.reachable is None and s.quick_return is None
    assert len(s.extremes[0].at_min) == 2
    assert [e.name for e in s.extremes] == ["P.x", "P.y", "P.speed", "P.acceleration"]


def test_extremes_leave_the_singular_samples_out():
    # crank = rod: at q = 90 and 270 deg the rod stands upright over O2 and B passes O2, a
    # change point (det J = 0); on the branch the sweep follows B = (2 cos q, 0), so the
    # slide's rate -2 sin q reaches -2 m/s exactly there, which a working range must not
    # report
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=1.0)
    q = np.radians(np.arange(0.0, 361.0, 5.0))
    sol = kl.analyze(sc, q, 1.0, at_singular="flag")
    assert np.flatnonzero(sol.singular).tolist() == [18, 54]
    s = summary(sol)
    e = {x.name: x for x in s.extremes}
    ok = ~sol.singular
    assert e["rod.angle"].full_turn                         # the rod angle is -q
    assert (e["slide.slide"].min, e["slide.slide"].max) == (pytest.approx(-2.0, abs=1e-12),
                                                             pytest.approx(2.0, abs=1e-12))
    # by hand: -2 sin(85 deg) at q = 85 deg, next to the singular sample at 90 deg
    v = e["slide.slide_velocity"]
    assert v.min == pytest.approx(-2 * math.sin(math.radians(85.0)), abs=1e-12)
    assert v.at_min[0] in (pytest.approx(math.radians(85.0)), pytest.approx(math.radians(95.0)))
    for x in s.extremes:
        assert x.at_min[0] not in q[~ok] and x.at_max[0] not in q[~ok], x.name
    t = s.transmission[0]
    assert t.min == pytest.approx(math.radians(5.0), abs=1e-12)    # 90 - 85 deg, not 0
    # the singular positions are still listed
    assert s.singular == (pytest.approx((math.pi / 2,), abs=1e-12),
                          pytest.approx((3 * math.pi / 2,), abs=1e-12))


@pytest.fixture(scope="module")
def fourbar_sweep():
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    return kl.analyze(fb, q=np.radians(np.arange(0.0, 360.0, 5.0)))


@pytest.mark.parametrize("name", ["bogus", 5, "P", "ground", 2.5])
def test_a_time_ratio_output_that_is_not_a_moving_link_is_refused(fourbar_sweep, name):
    with pytest.raises(kl.errors.ModelError,
                       match=r"^time_ratio: expected one of 'crank', 'coupler', 'rocker', got "):
        summary(fourbar_sweep, time_ratio=name)


def test_a_time_ratio_output_without_one_is_none_not_an_error(fourbar_sweep):
    assert summary(fourbar_sweep, time_ratio="rocker").quick_return.output == "rocker"
    assert summary(fourbar_sweep, time_ratio="crank").quick_return is None   # it never reverses


def test_one_name_to_report_is_a_name_not_its_letters(fourbar_sweep):
    names = [e.name for e in summary(fourbar_sweep, report="rocker").extremes]
    assert names == ["rocker.angle", "rocker.omega", "rocker.alpha"]


@pytest.mark.parametrize("sol, message", [
    (None, r"^sol: expected a KinematicSolution .*got None$"),
    (kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), r"^sol: expected a KinematicSolution .*got Mechanism"),
])
def test_summary_of_something_else_is_refused(sol, message):
    with pytest.raises(kl.errors.ModelError, match=message):
        summary(sol)


def test_summary_of_no_samples_is_refused():
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=np.array([]))
    with pytest.raises(kl.errors.ModelError, match=r"^sol: expected a sweep of at least one sample, got none"):
        summary(sol)
