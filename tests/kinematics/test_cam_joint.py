"""Cam joints (``C``) in the planar engine: a translating follower, and a cam driving a rocker,
a coupler and a slider.

Every number is checked by a route that does not use the engine's cam step: the follower's
displacement against the cam program's own S (kinelab.cams), K and L against central
differences of the positions through the whole chain, the numpy form of the plan against the
compiled kernel, and the mobility counts.
"""
import dataclasses
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.cams import MotionProgram, Segment
from kinelab.errors import ModelError
from kinelab.model import Input, Joint, Link, Mechanism, Point
from tests.kinematics.checks import wrap
from tests.kinematics.test_interpreter import check

EXAMPLES = Path(__file__).parents[2] / "examples"
D = np.radians
LAWS = ("harmonic", "cycloidal", "3-4-5", "4-5-6-7", "modified-trapezoid", "modified-sine")


def load(stem):
    return kl.load(EXAMPLES / f"{stem}.toml")


def program(law="cycloidal", back="3-4-5", lift=0.02):
    return MotionProgram([Segment("rise", 0, D(120), lift, law), Segment("dwell", D(120), D(180)),
                          Segment("return", D(180), D(300), lift, back),
                          Segment("dwell", D(300), D(360))])


def translating(prog, *, theta0=0.0, guide_joint=True, cam_joint=True):
    """A disk cam on the frame at O (its line O -> M at theta0) and a follower F sliding along
    +y above it."""
    joints = []
    if cam_joint:
        joints.append(Joint("jO", "R", ("ground", "cam"), point="O"))
    if guide_joint:
        joints.append(Joint("guide", "P", ("ground", "follower"), point="F", axis=(0.0, 1.0),
                            origin="O"))
    joints.append(Joint("contact", "C", ("cam", "follower"), program=prog))
    return Mechanism(
        "cam", (Point("O", 0, 0), Point("M", 0.03 * np.cos(theta0), 0.03 * np.sin(theta0)),
                Point("E", 0, -0.1), Point("F", 0, 0.05)),
        (Link("ground", ("O", "E"), ground=True), Link("cam", ("O", "M")),
         Link("follower", ("F",))),
        tuple(joints), (Input(joint="jO"),) if cam_joint else ())


def differences(m, q, name, h=1e-3):
    """First and second derivatives of a link's angle, a point's place or a slide by central
    differences of steps h and 2h combined (Richardson): off by about h**4 and by rounding,
    eps |x| / h**2."""
    def value(s):
        if name in s.link_names:
            return s.angle(name)
        return s.position(name) if name in s.point_names else s.slide(name)

    def central(h):
        v0, vp, vm = (value(kl.analyze(m, q=q + d)) for d in (0.0, h, -h))
        if name in m.link_names:
            vp, vm = v0 + wrap(vp - v0), v0 + wrap(vm - v0)
        return (vp - vm) / (2 * h), (vp - 2 * v0 + vm) / (h * h)
    (k1, l1), (k2, l2) = central(h), central(2 * h)
    return (4 * k1 - k2) / 3, (4 * l1 - l2) / 3


# samples over a turn, none within 1e-3 rad of a joint of the programs (where the jerk jumps,
# so that central differences of L are off by O(h) there)
TURN = np.radians(np.arange(2.0, 360.0, 7.0))


# ------------------------------------------------------------------------------------------
# the follower's displacement is the program's S
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("law", LAWS)
def test_translating_follower_moves_by_S(law):
    prog = program(law, law)
    sol = kl.analyze(translating(prog), q=TURN, qd=2.0, qdd=0.5)
    svaj = prog.svaj(TURN)
    # the sketch draws the follower at S(0) = 0: its slide from O is 0.05 m + S
    np.testing.assert_allclose(sol.slide("guide"), 0.05 + svaj.S, rtol=0, atol=1e-15)
    np.testing.assert_allclose(sol.position("F")[:, 0], 0.0, rtol=0, atol=1e-15)
    # K = dS/dtheta and L = d2S/dtheta2, as the program's V and A (per radian of the cam)
    np.testing.assert_allclose(sol.K("guide"), svaj.V, rtol=0, atol=1e-14)
    np.testing.assert_allclose(sol.L("guide"), svaj.A, rtol=0, atol=1e-13)
    np.testing.assert_allclose(sol.slide_velocity("guide"), 2.0 * svaj.V, rtol=0, atol=1e-14)
    np.testing.assert_allclose(sol.slide_acceleration("guide"), 0.5 * svaj.V + 4.0 * svaj.A,
                               rtol=0, atol=1e-13)


def test_the_cam_angle_is_its_line_from_x_and_the_sketch_sets_the_follower_zero():
    """A cam drawn at 30 deg: the sketch's follower is at S(30 deg), so its place at S = 0 is
    below it by that much; the cam's angle is its line's angle however many turns."""
    prog = program()
    m = translating(prog, theta0=D(30))
    q = np.linspace(-7.0, 14.0, 61)
    sol = kl.analyze(m, q=q)
    S0 = prog.svaj(D(30)).S
    np.testing.assert_allclose(sol.slide("guide"), 0.05 - S0 + prog.svaj(q).S, rtol=0,
                               atol=1e-15)


def test_oscillating_follower_turns_by_S():
    m = load("cam_rocker_slider")
    c = m.joint("contact").program
    q = TURN
    sol = kl.analyze(m, q=q)
    theta0 = np.arctan2(60.0, 70.0)        # the rocker A -> B in the sketch, S(0) = 0
    np.testing.assert_allclose(wrap(sol.angle("rocker") - theta0 - c.svaj(q).S), 0.0, rtol=0,
                               atol=1e-14)
    np.testing.assert_allclose(sol.K("rocker"), c.svaj(q).V, rtol=0, atol=1e-14)
    assert c.svaj(D(150)).S == pytest.approx(D(20), abs=1e-15)   # the lift is in degrees


def test_translating_example_follows_its_program():
    m = load("cam_follower")
    prog = m.joint("contact").program
    q = np.radians(np.arange(0.0, 361.0, 5.0))
    sol = kl.analyze(m, q=q, qd=2 * np.pi)
    np.testing.assert_allclose(sol.slide("guide"), 0.05 + prog.svaj(q).S, rtol=0, atol=1e-15)
    # 4-5-6-7 rise of 20 mm over 120 deg at one turn a second: peak speed 35/16 h / beta omega
    # at mid-rise, 60 deg (a sample)
    assert sol.slide_velocity("guide").max() == pytest.approx(35 / 16 * 0.02 / D(120) * 2 * np.pi,
                                                             rel=1e-12)


# ------------------------------------------------------------------------------------------
# K and L through the whole chain, against differences of positions
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["rocker", "coupler", "slide", "C", "B"])
def test_K_and_L_against_finite_differences_through_the_chain(name):
    m = load("cam_rocker_slider")
    q = TURN
    sol = kl.analyze(m, q=q)
    K, L = differences(m, q, name)
    Ke, Le = sol.K(name), sol.L(name)
    # differences off by about h**4 S^(6) and by rounding, eps |x| / h**2 (|x| = 0.12 m,
    # h = 1e-3): 1e-7 of the largest value
    np.testing.assert_allclose(Ke, K, rtol=0, atol=1e-7 * np.abs(K).max())
    np.testing.assert_allclose(Le, L, rtol=0, atol=1e-7 * np.abs(L).max())



# ------------------------------------------------------------------------------------------
# the numpy form and the compiled kernel
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("law", LAWS)
def test_numpy_form_against_compiled_kernel_per_law(law):
    check(translating(program(law, law)), np.linspace(-1.0, 13.0, 301))


@pytest.mark.parametrize("stem", ["cam_follower", "cam_rocker_slider"])
def test_numpy_form_against_compiled_kernel_examples(stem):
    check(load(stem), np.linspace(-1.0, 13.0, 301))


def test_polynomial_segments_in_both_forms():
    conds = ((0.0, 0, 0.0), (0.0, 1, 0.0), (0.0, 2, 0.0), (D(180), 0, 0.01), (D(180), 1, 0.0),
             (D(180), 2, 0.0))
    prog = MotionProgram([Segment("rise", 0, D(180), law="polynomial", conditions=conds),
                          Segment("return", D(180), D(360), 0.01, "cycloidal")])
    m = translating(prog)
    q = np.linspace(0.0, 2 * np.pi, 91)
    sol = kl.analyze(m, q=q)
    np.testing.assert_allclose(sol.slide("guide"), 0.05 + prog.svaj(q).S, rtol=0, atol=1e-15)
    check(m, q)


# ------------------------------------------------------------------------------------------
# mobility
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("stem", ["cam_follower", "cam_rocker_slider"])
def test_mobility_counts_the_cam_as_a_higher_pair(stem):
    mob = kl.structure.mobility(load(stem))
    assert mob.kutzbach_gruebler == 1 and mob.exact == 1


def test_cam_pair_counts_as_a_two_freedom_pair():
    assert kl.structure.pair_counts(load("cam_follower")) == {1: 2, 2: 1}


# ------------------------------------------------------------------------------------------
# bad input, and what the engine does not do yet
# ------------------------------------------------------------------------------------------
def test_a_cam_joint_needs_a_program():
    m = translating(program())
    joints = tuple(dataclasses.replace(j, program=None) if j.type == "C" else j for j in m.joints)
    with pytest.raises(ModelError, match=r"joint 'contact': program: a cam joint needs its motion "
                                         r"program"):
        dataclasses.replace(m, joints=joints)


def test_a_program_is_a_motion_program():
    m = translating(program())
    joints = tuple(dataclasses.replace(j, program=3) if j.type == "C" else j for j in m.joints)
    with pytest.raises(ModelError, match=r"program: expected a kinelab.cams.MotionProgram, got 3"):
        dataclasses.replace(m, joints=joints)


def test_a_program_that_does_not_close_is_refused():
    prog = MotionProgram([Segment("rise", 0, D(180), 0.02, "cycloidal"),
                          Segment("return", D(180), D(360), 0.01, "cycloidal")],
                         allow_discontinuous=True)
    with pytest.raises(ModelError, match=r"joint 'contact': program: S jumps by .* at 0 deg.*"
                                         r"make the program close over the turn"):
        translating(prog)


def test_a_follower_without_its_own_joint_is_refused():
    with pytest.raises(ModelError, match=r"joint 'contact': links: the follower 'follower' \(the "
                                         r"second link\) must slide on the guide 'ground'"):
        translating(program(), guide_joint=False)


def test_a_cam_that_does_not_turn_on_the_guide_is_refused():
    with pytest.raises(ModelError, match=r"joint 'contact': links: the cam 'cam' \(the first "
                                         r"link\) must turn on the guide 'ground'"):
        translating(program(), cam_joint=False)


def test_a_guide_that_is_the_cam_is_refused():
    m = translating(program())
    joints = tuple(dataclasses.replace(j, carrier="cam") if j.type == "C" else j
                   for j in m.joints)
    with pytest.raises(ModelError, match=r"joint 'contact': carrier: the guide 'cam' cannot be "
                                         r"the cam or the follower"):
        dataclasses.replace(m, joints=joints)


def test_a_program_on_another_joint_is_refused():
    m = translating(program())
    joints = tuple(dataclasses.replace(j, program=program()) if j.name == "jO" else j
                   for j in m.joints)
    with pytest.raises(ModelError, match=r"joint 'jO': program: only a cam joint"):
        dataclasses.replace(m, joints=joints)


def test_bad_law_in_a_model_file(tmp_path):
    head, tail = (EXAMPLES / "cam_follower.toml").read_text().rsplit('law = "4-5-6-7"', 1)
    text = head + 'law = "3-4-6"' + tail          # the return's law
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ModelError, match=r"joints\[2\].segments\[2\].law: expected one of "
                                         r"'harmonic', .*got '3-4-6'"):
        kl.load(path)


def test_a_model_file_program_that_does_not_close(tmp_path):
    text = (EXAMPLES / "cam_follower.toml").read_text().replace("lift = 20\n\n[[joints.segments]]"
                                                                "\nkind = \"dwell\"\nfrom = 300",
                                                                "lift = 10\n\n[[joints.segments]]"
                                                                "\nkind = \"dwell\"\nfrom = 300")
    path = tmp_path / "open.toml"
    path.write_text(text)
    with pytest.raises(ModelError, match=r"joints\[2\].segments: S jumps by"):
        kl.load(path)


def test_the_newton_method_is_refused():
    with pytest.raises(ModelError, match=r"method: 'newton' puts every link in Newton groups, "
                                         r"which do not take cam joints \('contact'\)"):
        kl.analyze(load("cam_follower"), q=0.0, method="newton")


def test_dynamics_asks_for_the_links_mass_data():
    # cam joints go through dynamics (tests/dynamics/test_pair_dynamics.py); without mass
    # data the links are named
    with pytest.raises(ModelError, match=r"link 'cam': mass: missing"):
        kl.dynamics.inverse(load("cam_follower"), q=0.0)


def test_the_derivation_is_refused():
    with pytest.raises(ModelError, match=r"cam joints \(C\) are not derived yet"):
        kl.derive.derive(load("cam_follower"))


def test_driving_the_follower_is_refused():
    m = load("cam_follower")
    with pytest.raises(ModelError, match=r"cam joint"):
        kl.analyze(dataclasses.replace(m, inputs=(Input(joint="guide"),)), q=0.05)


def test_round_trip_through_plain_data_and_toml(tmp_path):
    m = load("cam_rocker_slider")
    back = Mechanism.from_dict(m.to_dict())
    assert back.joint("contact").program == m.joint("contact").program
    mf = kl.io.ModelFile.read(EXAMPLES / "cam_rocker_slider.toml")
    path = tmp_path / "again.toml"
    mf.write(path)
    again = kl.load(path)
    q = np.linspace(0.0, 6.0, 13)
    np.testing.assert_allclose(kl.analyze(again, q=q).slide("slide"),
                               kl.analyze(m, q=q).slide("slide"), rtol=0, atol=1e-15)


# ------------------------------------------------------------------------------------------
# instant centres: the cam pair's primary centre, and Kennedy's construction from it
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("stem", ["cam_follower", "cam_rocker_slider"])
def test_kennedy_construction_from_the_cam_centre_meets_the_velocities(stem):
    """A cam joint's primary centre lies on the line of centres where S'(theta) puts it;
    Kennedy's construction from there agrees with the centres solved from the velocities
    (samples where the follower moves: at a dwell the cam turns alone)."""
    sol = kl.analyze(load(stem), q=np.radians([20.0, 75.0, 100.0, 250.0, 280.0]), qd=1.0)
    kc = kl.kinematics.kennedy_construction(sol)
    ic = kl.kinematics.instant_centers(sol)
    assert "contact" in kc.primary.values()
    for pair in ic:
        a, b = kc.centers[pair], ic[pair]
        np.testing.assert_array_equal(a.at_infinity, b.at_infinity)
        finite = ~np.asarray(b.at_infinity)
        np.testing.assert_allclose(np.asarray(a.position)[finite], np.asarray(b.position)[finite],
                                   rtol=1e-9, atol=1e-12)


# ------------------------------------------------------------------------------------------
# a cam on a moving carrier: the program reads the cam's angle relative to it
# ------------------------------------------------------------------------------------------
def on_an_arm(prog):
    """An arm turning on the frame at O (input 0) carries a cam at P (input 1, its angle on
    the arm) and a follower sliding on the arm along the arm's normal above P."""
    return Mechanism(
        "cam on an arm",
        (Point("O", 0, 0), Point("E", -0.1, 0), Point("P", 0.2, 0), Point("M", 0.23, 0),
         Point("F", 0.2, 0.05)),
        (Link("ground", ("O", "E"), ground=True), Link("arm", ("O", "P")),
         Link("cam", ("P", "M")), Link("follower", ("F",))),
        (Joint("jO", "R", ("ground", "arm"), point="O"), Joint("jP", "R", ("arm", "cam"), point="P"),
         Joint("guide", "P", ("arm", "follower"), point="F", axis=(0.0, 1.0), origin="P"),
         Joint("contact", "C", ("cam", "follower"), program=prog, carrier="arm")),
        (Input(joint="jO"), Input(joint="jP")))


def test_a_cam_on_a_moving_carrier():
    prog = program("modified-trapezoid", "harmonic")
    m = on_an_arm(prog)
    assert kl.structure.mobility(m).exact == 2
    rng = np.random.default_rng(5)
    q = rng.uniform(-4.0, 4.0, (40, 2))
    qd, qdd = rng.normal(size=q.shape), rng.normal(size=q.shape)
    sol = kl.analyze(m, q=q, qd=qd, qdd=qdd)
    svaj = prog.svaj(q[:, 1])
    np.testing.assert_allclose(sol.slide("guide"), 0.05 + svaj.S, rtol=0, atol=1e-15)
    # the slide's K is (0, S') and its L has S'' in the cam's corner: the arm does not count
    np.testing.assert_allclose(sol.K("guide"), np.stack([0 * svaj.V, svaj.V], -1), rtol=0,
                               atol=1e-14)
    np.testing.assert_allclose(sol.L("guide")[:, 1, 1], svaj.A, rtol=0, atol=1e-13)
    np.testing.assert_allclose(sol.L("guide")[:, 0], 0.0, rtol=0, atol=1e-13)
    check(m, q, qd=qd, qdd=qdd)
