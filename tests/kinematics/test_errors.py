"""Bad input gets a kinelab error that says what to do; never NaN or a deep traceback."""
import math

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import AssemblyError, ModelError, SingularityError
from kinelab.model import Input, Joint, Link, Mechanism, Point
from tests.kinematics.checks import closure_residual
from tests.model.test_mechanism import fourbar_parts

NON_GRASHOF = dict(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)   # |A O4| <= 2.5: cos q >= -5/16


def test_unreachable_input_names_group_gap_and_range():
    fb = kl.mechanisms.fourbar(**NON_GRASHOF)
    with pytest.raises(AssemblyError, match=r"dyad 'coupler'-'rocker' \(RRR A-B-O4\) cannot close "
                       r"at q = 2 rad: it misses by 0\.0815\d* m; reachable q is \[-1\.88862, 1\.88862\] rad; "
                       r"narrow the input range") as info:
        kl.analyze(fb, q=np.linspace(0.0, 3.0, 7))
    lo, hi = info.value.reachable[0]
    assert hi == pytest.approx(np.arccos(-5 / 16), abs=1e-10) and lo == pytest.approx(-hi, abs=1e-10)
    # the first sample out of reach is q = 2; its gap is |A O4| - (coupler + rocker)
    gap = np.hypot(2 * np.cos(2.0) - 1.0, 2 * np.sin(2.0)) - 2.5
    assert info.value.gap == pytest.approx(gap, abs=1e-12)


def test_unreachable_mask_marks_samples():
    fb = kl.mechanisms.fourbar(**NON_GRASHOF)
    q = np.linspace(0.0, 3.0, 7)
    sol = kl.analyze(fb, q=q, unreachable="mask")
    expected = np.cos(q) >= -5 / 16
    np.testing.assert_array_equal(sol.assembled, expected)
    assert np.isnan(sol.angle("rocker")[~expected]).all()
    assert np.isfinite(sol.angle("rocker")[expected]).all()


def test_single_singular_configuration_raises():
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=1.0)    # at 90°, the rod stands upright
    with pytest.raises(SingularityError, match=r"q = 1\.5708 rad is a change point of dyad "
                                               r"'rod'-'slider'"):
        kl.analyze(sc, q=np.pi / 2, qd=1.0)


# A change point (two assembly modes cross: the motion goes on) and a limit position (a fold:
# the input's reach ends) are told apart, each with where it is; a limit position with the
# reach computed.  Non-Grashof four-bar: the crank reaches cos q >= -5/16 (the coupler and
# rocker, 1 + 1.5, just reach A from O4 when |A - O4|^2 = 1 + 4 - 4 cos q = 6.25).
@pytest.mark.parametrize("q, text", [
    (math.acos(-5 / 16), r"q = 1\.888620030723\d* rad is a limit position \(det J = [^)]*\): the input "
                         r"cannot go past it, and velocities and accelerations are unbounded there; "
                         r"q reaches \[-1\.88862003072\d*, 1\.88862003072\d*\] rad"),
    (math.acos(-5 / 16) - 1e-6, r"q = 1\.888619 rad is next to a limit position \(at 1\.88862 rad; "
                                r"det J = [^)]*\)"),
])
def test_a_limit_position_is_named_with_the_reach(q, text):
    fb = kl.mechanisms.fourbar(**NON_GRASHOF)
    with pytest.raises(SingularityError, match=text) as info:
        kl.analyze(fb, q=q, qd=1.0)
    assert info.value.kind == "limit position"
    assert info.value.reachable == kl.kinematics.reachable_ranges(fb)
    assert info.value.at == pytest.approx(math.acos(-5 / 16), abs=1e-11)


def test_a_change_point_is_not_called_a_limit_position():
    """The parallelogram at 0: two assembly modes cross; the crank turns on."""
    pg = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    with pytest.raises(SingularityError, match=r"^q = 0\.001 rad is next to a change point of dyad "
                                               r"'coupler'-'rocker' \(RRR A-B-O4\) \(at 0 rad; det J = "
                                               r"[^)]*\): two assembly modes meet and cross there") as info:
        kl.analyze(pg, q=0.001, qd=1.0)
    assert info.value.kind == "change point" and info.value.reachable is None
    assert kl.kinematics.turns_fully(pg, kl.kinematics.reachable_ranges(pg))


def test_a_limit_position_of_a_newton_plan_is_named():
    """The same four-bar through the Newton engine: the reach that continuation finds."""
    fb = kl.mechanisms.fourbar(**NON_GRASHOF)
    lo, hi = kl.kinematics.reachable_ranges(fb, method="newton")[0]
    with pytest.raises(SingularityError, match=r"limit position") as info:
        kl.analyze(fb, q=hi - 1e-9, qd=1.0, method="newton")
    assert info.value.kind == "limit position"
    assert hi == pytest.approx(math.acos(-5 / 16), abs=1e-8)


def test_singular_samples_are_flagged_in_a_sweep():
    fb = kl.mechanisms.fourbar(**NON_GRASHOF)
    lo, hi = kl.kinematics.reachable_ranges(fb)[0]
    sol = kl.analyze(fb, q=[0.0, hi], qd=1.0)
    np.testing.assert_array_equal(sol.singular, [False, True])
    assert np.isnan(sol.omega("rocker")[1]) and np.isfinite(sol.angle("rocker")[1])
    assert np.isfinite(sol.omega("rocker")[0])


@pytest.mark.parametrize("q, message", [
    (np.zeros((3, 2)), r"q: expected shape \(\) or \(N,\)"),
    ([0.0, np.nan], r"q: expected finite numbers, got nan at index \[1\]"),
    ("abc", r"q: expected numbers"),
])
def test_bad_inputs(q, message):
    with pytest.raises(ModelError, match=message):
        kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0), q=q)


def test_bad_option_and_names():
    sc = kl.mechanisms.slider_crank(1.0, 3.0)
    with pytest.raises(ModelError, match="unreachable: expected one of 'raise', 'mask', got 'skip'"):
        kl.analyze(sc, q=0.1, unreachable="skip")
    sol = kl.analyze(sc, q=0.1)
    with pytest.raises(ModelError, match=r"got 'rdo' \(did you mean 'rod'\?\)"):
        sol.angle("rdo")
    with pytest.raises(ModelError, match=r"got 'r\\nod\\x1b\[0m'$"):   # escaped, on one line
        sol.angle("r\nod\x1b[0m")
    with pytest.raises(ModelError, match=r"got 'a\\nb'$"):
        kl.analyze(sc, q=0.1, at_singular="a\nb")
    with pytest.raises(ModelError, match="expected the point of a prismatic joint"):
        sol.acceleration_components("A")
    with pytest.raises(TypeError):
        kl.analyze(sc, q=0.1, speed=3)


def test_branch_and_length_errors():
    with pytest.raises(ModelError, match=r"branch: expected one of 'open', 'crossed', got 'cross'"):
        kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, branch="cross")
    with pytest.raises(ModelError, match=r"crank: expected a positive length \(m\), got -1"):
        kl.mechanisms.fourbar(3.0, -1, 3.0, 2.5)
    with pytest.raises(ModelError, match="cannot be assembled at any input angle"):
        kl.mechanisms.fourbar(10.0, 1.0, 1.0, 1.0)


def test_missing_input_and_too_many_inputs():
    p, l_, j = fourbar_parts()
    with pytest.raises(ModelError, match="the mechanism has no input"):
        kl.analyze(Mechanism("fb", p, l_, j), q=0.0)
    two = Mechanism("fb", p, l_, j, (Input(joint="jO2"), Input(joint="jO4")))
    with pytest.raises(ModelError, match=r"inputs: the linkage has 1 degree\(s\) of freedom at the "
                                         r"sketch \(exact mobility; Kutzbach-Gruebler counts 1\) "
                                         r"but 2 input\(s\); give it 1 input\(s\), or fewer joints"):
        kl.analyze(two, q=[0.0, 0.0])


def test_too_few_inputs():
    p, l_, j = fourbar_parts()
    p = p + (Point("C", 5, 1),)
    l_ = l_ + (Link("arm", ("B", "C")),)
    j = j + (Joint("jB2", "R", ("rocker", "arm"), point="B"),)
    m = Mechanism("fb", p, l_, j, (Input(joint="jO2"),))
    with pytest.raises(ModelError, match=r"the linkage has 2 degree\(s\) of freedom .* counts 2\) but 1 "
                                         r"input\(s\); give it 2 input\(s\), or more joints"):
        kl.analyze(m, q=0.0)


def test_planar_engine_rejects_spatial_pairs():
    p, l_, j = fourbar_parts()
    j = j + (Joint("contact", "cam", ("rocker", "crank")),)
    with pytest.raises(ModelError, match="handles R and P joints, got 'cam'"):
        kl.analyze(Mechanism("fb", p, l_, j, (Input(joint="jO2"),)), q=0.0)


def _parallelogram(dx_extra=0.0):
    """Parallelogram O2 A B O4 with an extra link E F parallel to the cranks (redundant)."""
    pts = (Point("O2", 0, 0), Point("A", 0, 1), Point("B", 2, 1), Point("O4", 2, 0),
           Point("E", 1, 1), Point("F", 1 + dx_extra, 0))
    links = (Link("ground", ("O2", "O4", "F"), ground=True), Link("crank", ("O2", "A")),
             Link("coupler", ("A", "B", "E")), Link("rocker", ("O4", "B")), Link("extra", ("F", "E")))
    joints = (Joint("jO2", "R", ("ground", "crank"), point="O2"),
              Joint("jA", "R", ("crank", "coupler"), point="A"),
              Joint("jB", "R", ("coupler", "rocker"), point="B"),
              Joint("jO4", "R", ("ground", "rocker"), point="O4"),
              Joint("jE", "R", ("coupler", "extra"), point="E"),
              Joint("jF", "R", ("ground", "extra"), point="F"))
    return Mechanism("parallelogram", pts, links, joints, (Input(joint="jO2"),))


def test_redundant_link_of_a_parallelogram_is_checked_not_needed():
    m = _parallelogram()
    assert kl.kinematics.plan(m).redundant
    sol = kl.analyze(m, q=np.linspace(0.5, 2.5, 9))
    assert closure_residual(sol) < 1e-10
    np.testing.assert_allclose(sol.angle("extra"), sol.angle("crank"), atol=1e-12)


def test_extra_link_off_the_parallelogram_locks_the_linkage():
    with pytest.raises(ModelError, match=r"the linkage has 0 degree\(s\) of freedom at the sketch "
                                         r"\(exact mobility; Kutzbach-Gruebler counts 0\) but 1 input"):
        kl.analyze(_parallelogram(dx_extra=0.3), q=np.linspace(0.5, 2.5, 9))


@pytest.mark.parametrize("q, qd, qdd, message", [
    (0.3, 1e200, 0.0, r"^qd: expected at most 1e\+100 rad/s in size, got 1e\+200$"),
    (0.3, 1.0, -1e101, r"^qdd: expected at most 1e\+100 rad/s\^2 in size, got -1e\+101$"),
    (2 * np.pi * 1e15 + 0.5, 0.0, 0.0,
     r"^q: expected angles within 1,000,000 turns of 0 either way \(beyond, float64 resolves "
     r"them to worse than 1e-9 rad\), got 6\.28319e\+15$"),
    ([0.1, -1e308], 0.0, 0.0, r"^q: expected angles within .* got -1e\+308 at index 1$"),
])
def test_input_values_beyond_the_limits_are_refused(q, qd, qdd, message):
    """Beyond them an acceleration overflows to inf, or an angle's sine keeps no digit (a
    parallelogram at 1e15 turns put its rocker 2.48 rad off its crank)."""
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    with pytest.raises(ModelError, match=message):
        kl.analyze(fb, q, qd, qdd)
    if np.ndim(q) == 0:
        with pytest.raises(ModelError, match=message):
            kl.kinematics.Tracker(fb)(q, qd, qdd)


def test_a_long_motion_within_the_limits_stays_exact():
    """A parallelogram's rocker follows its crank a hundred thousand turns on."""
    pg = kl.mechanisms.fourbar(100, 60, 100, 60)
    q = 2 * np.pi * 1e5 + np.array([0.5, 2.0])
    sol = kl.analyze(pg, q)
    np.testing.assert_allclose(sol.position("B") - sol.position("A"), [[100, 0], [100, 0]],
                               rtol=0, atol=1e-6)


@pytest.mark.parametrize("call, message", [
    (lambda s: s.angle(["crank"]), r"^link: expected one of 'ground', 'crank', 'coupler', "
                                   r"'rocker', got \['crank'\]$"),
    (lambda s: s.position({"P": 1}), r"^point: expected one of .* got a table$"),
    (lambda s: s.slide("x"), r"^prismatic joint: got 'x', but the mechanism has no prismatic joint$"),
    (lambda s: kl.kinematics.velocity_ratio(s, ["crank"], "rocker"), r"^link_i: expected one of"),
    (lambda s: kl.kinematics.acceleration_difference(s, ["a"], "B"), r"^point: expected one of"),
    (lambda s: kl.kinematics.transmission_angle(s, (["coupler"], "rocker")), r"^link: expected one of"),
    (lambda s: kl.analyze(s.mechanism, 0.1, method=["raise"]),
     r"^method: expected one of 'auto', 'newton', got \['raise'\]$"),
    (lambda s: s.acceleration_components("P\n" + "x" * 1000),
     r"^point 'P\\nx+\u2026': expected the point of a prismatic joint; prismatic joints are none;"),
])
def test_a_name_that_is_not_a_name_is_one_unknown_name(call, message):
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    with pytest.raises(ModelError, match=message):
        call(kl.analyze(fb, [0.1, 0.2]))


PARALLELOGRAM = dict(ground=100, crank=60, coupler=100, rocker=60)


@pytest.mark.parametrize("call, message", [
    (lambda fb, s: kl.kinematics.instant_centers(None),
     r"^sol: expected a KinematicSolution, got None; get one from kinelab.analyze$"),
    (lambda fb, s: kl.kinematics.velocity_ratio(fb, "crank", "rocker"),
     r"^sol: expected a KinematicSolution, got a Mechanism; analyze it first"),
    (lambda fb, s: kl.kinematics.velocity_polygon("s"), r"^sol: expected a KinematicSolution"),
    (lambda fb, s: kl.kinematics.transmission_angle(s, links="coupler"),
     r"^links: expected two links, the coupler and the output, got 'coupler'$"),
    (lambda fb, s: kl.kinematics.transmission_angle(s, links=("coupler", "coupler")),
     r"^links: expected two different links"),
    (lambda fb, s: kl.kinematics.turns_fully(fb, None), r"^ranges: expected input intervals"),
    (lambda fb, s: kl.kinematics.reachable_ranges(fb, samples=2),
     r"^samples: expected a whole number from 3 to 1,000,000, got 2$"),
    (lambda fb, s: kl.kinematics.time_ratio(fb, "rocker", samples=1.5),
     r"^samples: expected a whole number from 3 to 1,000,000, got 1.5$"),
    (lambda fb, s: kl.kinematics.time_ratio(kl.mechanisms.slider_crank(1, 3, offset=0.5), "B"),
     r"^time_ratio: output: expected one of .* got 'B'; a point has no time ratio of its own"),
    (lambda fb, s: kl.kinematics.change_points(kl.mechanisms.fourbar(**PARALLELOGRAM), np.nan, 1),
     r"^lo: expected a finite number, got nan$"),
    (lambda fb, s: kl.kinematics.change_points(kl.mechanisms.fourbar(**PARALLELOGRAM), 0, 10**400),
     r"^hi: expected a finite number, got a whole number of 401 digits$"),
    (lambda fb, s: kl.kinematics.change_points(kl.mechanisms.fourbar(**PARALLELOGRAM), 0, 1e5),
     r"^lo, hi: a range of 15,916 turns of the change points' pattern; ask for at most 10,000"),
    (lambda fb, s: kl.analyze(fb, q=[[0.1], [0.2, 0.3]]), r"^q: expected numbers"),
    (lambda fb, s: kl.kinematics.pose(fb, []), r"^q: expected one configuration, shape \(\), got "
                                               r"shape \(0,\)"),
    (lambda fb, s: kl.KinematicSolution.concatenate([]), r"^parts: expected a list of KinematicSolution"),
    (lambda fb, s: kl.KinematicSolution.concatenate(
        [s, kl.analyze(kl.mechanisms.slider_crank(1, 3), [0.1])]),
     r"^parts: expected analyses of one mechanism by one method"),
    (lambda fb, s: s.to_csv(None), r"^path: expected a file's path \(text or pathlib.Path\), got None$"),
    (lambda fb, s: s.to_csv("results.parquet"), r"^path: results.parquet names a Parquet file"),
    (lambda fb, s: s.columns(degrees="yes"), r"^degrees: expected True or False, got 'yes'$"),
])
def test_arguments_of_the_kinematics_functions_are_checked(call, message):
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    with pytest.raises(ModelError, match=message):
        call(fb, kl.analyze(fb, [0.1, 0.2]))


def test_change_points_over_ten_thousand_turns_are_still_listed_exactly():
    pg = kl.mechanisms.fourbar(**PARALLELOGRAM)
    cps = kl.kinematics.change_points(pg, 0.0, 2 * np.pi * 9_999)
    assert len(cps) == 2 * 9_999 + 1          # at 0 and pi each turn, and at the end
    np.testing.assert_allclose([c.q for c in cps[-3:]], np.pi * np.arange(19_996, 19_999),
                               rtol=1e-12)


def test_a_huge_q_is_refused_before_any_copy():
    """The memory budget is asked before q is copied, whatever else is wrong with it."""
    from kinelab.errors import MemoryBudgetError
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    with pytest.raises(MemoryBudgetError, match=r"would take about 284 GiB"):
        kl.analyze(fb, np.broadcast_to(0.5, (10**9,)), qd=np.broadcast_to(1e300, (10**9,)))
