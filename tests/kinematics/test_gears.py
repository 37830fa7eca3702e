"""Gear pairs (joints ``G``) in the planar engine: simple, compound and epicyclic trains, a rack
and pinion, and a five-bar whose cranks are geared to each other.

Every number is checked by a route that does not use the engine's gear step: the train value
from the numbers of teeth, Willis' formula for the planetary train, loop closure measured on
the output points, K and L against central differences of the positions, and the numpy form
of the plan against the compiled kernel.
"""
import math
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.model import Input, Joint, Link, Mechanism, Point
from tests.kinematics.checks import closure_residual, wrap
from tests.kinematics.test_interpreter import check

EXAMPLES = Path(__file__).parents[2] / "examples"
TURN = np.radians(np.arange(0.0, 361.0, 1.0))


def load(stem):
    return kl.load(EXAMPLES / f"{stem}.toml")


def spur_pair(**gear):
    """Two gears on the frame: g2 about O2 (pitch radius 1 m), g3 about O4, 3 m away."""
    return Mechanism(
        name="pair",
        points=(Point("O2", 0.0, 0.0), Point("A", 1.0, 0.0), Point("O4", 3.0, 0.0),
                Point("B", 3.0, 2.0)),
        links=(Link("ground", ("O2", "O4"), ground=True), Link("g2", ("O2", "A")),
               Link("g3", ("O4", "B"))),
        joints=(Joint("p2", "R", ("ground", "g2"), point="O2"),
                Joint("p3", "R", ("ground", "g3"), point="O4"),
                Joint("mesh", "G", ("g2", "g3"), **gear)),
        inputs=(Input(joint="p2"),))


def planetary(inputs=("sun_shaft", "arm_shaft")):
    m = load("planetary")
    return Mechanism(m.name, m.points, m.links, m.joints, tuple(Input(joint=j) for j in inputs))


def rack(driven="pinion"):
    """The example's rack and pinion, driven by the pinion's angle or by the rack's slide."""
    m = load("rack_and_pinion")
    inp = Input(joint="jO") if driven == "pinion" else Input(joint="guide")
    return Mechanism(m.name, m.points, m.links, m.joints, (inp,))


def position_differences(m, q, name, h):
    """First and second central differences of a link's angle, point's place or slide."""
    def value(s):
        if name in s.link_names:
            return s.angle(name)
        return s.position(name) if name in s.point_names else s.slide(name)
    M = len(m.inputs)
    out = []
    for a in range(M):
        dq = np.zeros(M)
        dq[a] = h
        step = dq if M > 1 else h
        v0 = value(kl.analyze(m, q=q))
        vp, vm = value(kl.analyze(m, q=q + step)), value(kl.analyze(m, q=q - step))
        if name in m.link_names:
            vp, vm = v0 + wrap(vp - v0), v0 + wrap(vm - v0)
        out.append(((vp - vm) / (2 * h), (vp - 2 * v0 + vm) / (h * h)))
    return out


# ------------------------------------------------------------------------------------------
# train values
# ------------------------------------------------------------------------------------------
def test_simple_train_value_is_N1_over_N3():
    m = load("gear_train")
    sol = kl.analyze(m, q=TURN, qd=2.0, qdd=-3.0)
    # the idler turns the other way, N1/N2; gear 3 the same way as gear 1, N1/N3
    np.testing.assert_allclose(sol.K("idler"), -20 / 30, rtol=0, atol=1e-15)
    np.testing.assert_allclose(sol.K("gear3"), 20 / 40, rtol=0, atol=1e-15)
    for g in ("idler", "gear3"):
        np.testing.assert_array_equal(sol.L(g), 0.0)
        np.testing.assert_allclose(sol.omega(g), 2.0 * sol.K(g), rtol=1e-15)
        np.testing.assert_allclose(sol.alpha(g), -3.0 * sol.K(g), rtol=1e-15)
    # positions: each gear's angle from the sketch is the train value times the input's
    np.testing.assert_allclose(wrap(sol.angle("gear3") - 0.5 * TURN), 0.0, atol=1e-12)
    np.testing.assert_allclose(wrap(sol.angle("idler") - (np.pi / 2 - TURN * 2 / 3)), 0.0,
                               atol=1e-12)


def test_compound_train_value_is_the_product_of_its_meshes():
    m = load("compound_gear_train")
    sol = kl.analyze(m, q=TURN, qd=1.5)
    e = (-20 / 50) * (-15 / 45)          # (-N1/N2)(-N3/N4) = 2/15
    np.testing.assert_allclose(sol.K("gear4"), e, rtol=1e-15)
    np.testing.assert_allclose(sol.K("cluster"), -20 / 50, rtol=1e-15)
    np.testing.assert_allclose(sol.omega("gear4"), 1.5 * 2 / 15, rtol=1e-14)
    np.testing.assert_array_equal(sol.L("gear4"), 0.0)


@pytest.mark.parametrize("gear, k", [({"ratio": 2.5}, -1 / 2.5), ({"radii": (1.0, 2.0)}, -0.5),
                                     ({"teeth": (18, 54)}, -1 / 3),
                                     ({"teeth": (18, 54), "mesh": "internal"}, 1 / 3)])
def test_ratio_from_ratio_radii_or_teeth(gear, k):
    sol = kl.analyze(spur_pair(**gear), q=np.linspace(-7.0, 7.0, 29), qd=1.0)
    np.testing.assert_allclose(sol.K("g3"), k, rtol=1e-15)
    np.testing.assert_allclose(wrap(sol.angle("g3") - np.pi / 2 - k * sol.q[:, 0]), 0.0, atol=1e-12)


# ------------------------------------------------------------------------------------------
# the planetary train: Willis' formula
# ------------------------------------------------------------------------------------------
def willis_samples(n=50, seed=7):
    rng = np.random.default_rng(seed)
    return (rng.uniform(-10, 10, (n, 2)), rng.normal(size=(n, 2)) * 5, rng.normal(size=(n, 2)) * 5)


@pytest.mark.parametrize("inputs", [("sun_shaft", "arm_shaft"), ("ring_shaft", "arm_shaft"),
                                    ("arm_shaft", "planet_pin"), ("sun_shaft", "ring_shaft")])
def test_planetary_train_follows_willis(inputs):
    m = planetary(inputs)
    q, qd, qdd = willis_samples()
    sol = kl.analyze(m, q=q, qd=qd, qdd=qdd)
    w = {n: sol.omega(n) for n in ("sun", "arm", "planet", "ring")}
    a = {n: sol.alpha(n) for n in ("sun", "arm", "planet", "ring")}
    Ns, Np, Nr = 30, 20, 70
    # Willis: relative to the arm the train is a fixed-axis one
    np.testing.assert_allclose(w["ring"] - w["arm"], -Ns / Nr * (w["sun"] - w["arm"]), rtol=0,
                               atol=1e-12 * np.max(np.abs(qd)))
    np.testing.assert_allclose(w["planet"] - w["arm"], -Ns / Np * (w["sun"] - w["arm"]), rtol=0,
                               atol=1e-12 * np.max(np.abs(qd)))
    np.testing.assert_allclose(a["ring"] - a["arm"], -Ns / Nr * (a["sun"] - a["arm"]), rtol=0,
                               atol=1e-12 * np.max(np.abs(qdd)))
    for n in ("sun", "arm", "planet", "ring"):
        np.testing.assert_array_equal(sol.L(n), 0.0)      # linear in the inputs: L = 0 exactly
    if inputs == ("sun_shaft", "arm_shaft"):
        # the ring's angle itself, from the sketch (sun at 90 deg, arm at 0, ring at -90)
        d_sun, d_arm = q[:, 0] - np.pi / 2, q[:, 1]
        d_ring = sol.angle("ring") + np.pi / 2
        np.testing.assert_allclose(wrap(d_ring - d_arm + Ns / Nr * (d_sun - d_arm)), 0.0,
                                   atol=1e-12)


def test_planetary_with_the_ring_held_is_a_reduction():
    """Ring and arm driven, the ring held still (qd = 0): omega_arm / omega_sun = N_s/(N_s + N_r)."""
    m = planetary(("ring_shaft", "arm_shaft"))
    sol = kl.analyze(m, q=np.zeros((5, 2)) + [0.0, 0.3], qd=[0.0, 1.0])
    np.testing.assert_allclose(sol.omega("sun"), (30 + 70) / 30, rtol=1e-14)


def test_planetary_the_points_ride_on_the_arm():
    m = planetary()
    q, qd, qdd = willis_samples()
    sol = kl.analyze(m, q=q, qd=qd, qdd=qdd)
    arm = sol.angle("arm")
    np.testing.assert_allclose(sol.position("C"), 0.05 * np.stack([np.cos(arm), np.sin(arm)], -1),
                               rtol=0, atol=1e-15)
    assert closure_residual(sol) < 1e-13


# ------------------------------------------------------------------------------------------
# rack and pinion
# ------------------------------------------------------------------------------------------
def test_rack_advances_the_pitch_radius_per_radian():
    sol = kl.analyze(rack(), q=TURN, qd=3.0, qdd=0.5)
    theta = sol.q[:, 0]
    # convention: a counter-clockwise pinion drives the rack along +axis, s = s0 + r theta
    np.testing.assert_allclose(sol.slide("guide"), 0.1 + 0.025 * (theta - np.pi / 2), rtol=0,
                               atol=1e-15)
    np.testing.assert_allclose(sol.K("guide"), 0.025, rtol=1e-14)
    np.testing.assert_allclose(sol.slide_velocity("guide"), 0.075, rtol=1e-14)
    np.testing.assert_allclose(sol.slide_acceleration("guide"), 0.0125, rtol=1e-13)
    np.testing.assert_allclose(sol.position("K")[:, 1], -0.025, rtol=0, atol=1e-15)
    assert closure_residual(sol) < 1e-14


def test_rack_driven_turns_its_pinion():
    s = np.linspace(0.0, 0.3, 31)
    sol = kl.analyze(rack("rack"), q=s, qd=0.5, qdd=0.0)
    np.testing.assert_allclose(wrap(sol.angle("pinion") - (np.pi / 2 + (s - 0.1) / 0.025)), 0.0,
                               atol=1e-12)
    np.testing.assert_allclose(sol.K("pinion"), 1 / 0.025, rtol=1e-12)
    np.testing.assert_allclose(sol.omega("pinion"), 0.5 / 0.025, rtol=1e-12)
    np.testing.assert_allclose(sol.L("pinion"), 0.0, atol=1e-9)


def test_reversed_axis_reverses_the_rack():
    m = rack()
    joints = tuple(Joint(j.name, j.type, j.links, point=j.point, axis=(-1.0, 0.0), origin=j.origin)
                   if j.name == "guide" else j for j in m.joints)
    points = tuple(Point(p.name, p.x, 0.025 if p.name in ("K", "E") else p.y) for p in m.points)
    flipped = Mechanism(m.name, points, m.links, joints, m.inputs)
    sol = kl.analyze(flipped, q=TURN[:90], qd=1.0)
    np.testing.assert_allclose(sol.K("guide"), 0.025, rtol=1e-14)   # along -x: rack above


# ------------------------------------------------------------------------------------------
# the geared five-bar: one mechanism, one input
# ------------------------------------------------------------------------------------------
def gear_residual(sol):
    """(theta_2 - theta_2s) + (theta_4 - theta_4s): 0 for equal external gears, rad."""
    m = sol.mechanism
    s2, s4 = (kl.kinematics.plan(m).sketch_angles[m.link_names.index(n)] for n in ("crank1", "crank2"))
    return np.max(np.abs(wrap(sol.angle("crank1") - s2 + sol.angle("crank2") - s4)))


def test_geared_fivebar_closes_over_a_turn():
    m = load("geared_fivebar")
    q = np.radians(np.arange(90.0, 451.0, 0.5))
    sol = kl.analyze(m, q=q, qd=10.0, qdd=2.0)
    assert sol.assembled.all() and not sol.singular.any()
    assert closure_residual(sol) < 1e-10 * 0.2          # metres: 1e-10 of its size (0.2 m)
    assert gear_residual(sol) < 1e-12
    # the couplers meet at P: both see it at their length from A and from B
    for end, crank_pin in (("A", "coupler1"), ("B", "coupler2")):
        d = np.linalg.norm(sol.position("P") - sol.position(end), axis=-1)
        np.testing.assert_allclose(d, 0.15, rtol=0, atol=1e-12)
    np.testing.assert_allclose(sol.K("crank2"), -1.0, rtol=1e-15)


@pytest.mark.parametrize("name", ["P", "coupler1", "coupler2", "crank2", "B"])
def test_geared_fivebar_K_and_L_against_differences_of_positions(name):
    m = load("geared_fivebar")
    q = np.radians(np.arange(90.0, 451.0, 7.0))
    sol = kl.analyze(m, q=q)
    [(dK, dL)] = position_differences(m, q, name, 1e-5)
    [(_, dL2)] = position_differences(m, q, name, 1e-4)
    K, L = sol.K(name), sol.L(name)
    size = 1.0 if name in m.link_names else 0.2
    assert np.max(np.abs(dK - K)) < 1e-8 * size * (1 + np.max(np.abs(K)))    # h**2 and eps/h
    assert np.max(np.abs(dL2 - L)) < 1e-6 * size * (1 + np.max(np.abs(L)))   # h**2 and eps/h**2


@pytest.mark.parametrize("inputs", [("sun_shaft", "arm_shaft"), ("ring_shaft", "arm_shaft"),
                                    ("sun_shaft", "ring_shaft")])
def test_planetary_K_against_differences_of_positions(inputs):
    m = planetary(inputs)
    q, _, _ = willis_samples(12)
    sol = kl.analyze(m, q=q)
    for name in ("planet", "ring", "sun", "Q", "C"):
        for a, (dK, dL) in enumerate(position_differences(m, q, name, 1e-4)):
            K, L = sol.K(name)[..., a], sol.L(name)[..., a, a]
            assert np.max(np.abs(dK - K)) < 1e-7
            assert np.max(np.abs(dL - L)) < 1e-5


# ------------------------------------------------------------------------------------------
# the numpy form and the compiled kernel
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("make, q", [
    (lambda: load("gear_train"), TURN),
    (lambda: load("compound_gear_train"), TURN),
    (lambda: load("geared_fivebar"), np.radians(np.arange(90.0, 451.0, 1.0))),
    (rack, TURN),
    (lambda: rack("rack"), np.linspace(-0.2, 0.4, 61)),
    (lambda: spur_pair(teeth=(18, 54), mesh="internal"), TURN),
    (planetary, willis_samples()[0]),
    (lambda: planetary(("ring_shaft", "arm_shaft")), willis_samples()[0]),
    (lambda: planetary(("arm_shaft", "planet_pin")), willis_samples()[0]),
    (lambda: planetary(("sun_shaft", "ring_shaft")), willis_samples()[0]),
])
def test_numpy_form_and_compiled_kernel_agree(make, q):
    check(make(), q)


# ------------------------------------------------------------------------------------------
# mobility and the plan
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("stem, M", [("gear_train", 1), ("compound_gear_train", 1),
                                     ("planetary", 2), ("rack_and_pinion", 1),
                                     ("geared_fivebar", 1)])
def test_a_gear_pair_removes_one_freedom(stem, M):
    mob = kl.structure.mobility(load(stem))
    assert mob.kutzbach_gruebler == mob.exact == M
    assert "1·" in mob.explanation.splitlines()[0]       # the higher pairs, one freedom each


def test_the_fivebar_without_its_gears_has_two_freedoms():
    m = load("geared_fivebar")
    free = Mechanism(m.name, m.points, m.links, tuple(j for j in m.joints if j.type != "G"),
                     m.inputs)
    assert kl.structure.mobility(free).exact == 2
    assert kl.structure.mobility(m).exact == 1


def test_the_plan_solves_gears_in_closed_form():
    p = kl.kinematics.plan(load("planetary"))
    assert [s.kind for s in p.steps if s.kind == "gear"] == ["gear", "gear"]
    assert p.groups is None and p.redundant == ()
    p = kl.kinematics.plan(planetary(("sun_shaft", "ring_shaft")))   # the arm from both meshes
    assert [s.links for s in p.steps if s.kind == "gear"] == [("arm",), ("planet",)]
    assert p.groups is None and p.redundant == ()
    with pytest.raises(ModelError, match=r"method: 'newton' puts every link in Newton groups, "
                                         r"which do not take gear joints \('sun_planet', "
                                         r"'planet_ring'\); use method='auto'"):
        kl.kinematics.plan(load("planetary"), method="newton")


# ------------------------------------------------------------------------------------------
# the model's checks
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("gear, message", [
    ({}, r"joint 'mesh': ratio: an external gear pair needs its ratio: give one of ratio"),
    ({"teeth": (0, 40)}, r"joint 'mesh': teeth: expected positive numbers of teeth, got \(0, 40\)"),
    ({"teeth": (-3, 40)}, r"joint 'mesh': teeth: expected positive numbers of teeth"),
    ({"teeth": (2.5, 40)}, r"joint 'mesh': teeth: expected two whole numbers of teeth"),
    ({"ratio": -2.0}, r"joint 'mesh': ratio: expected a positive number"),
    ({"radii": (1.0, 0.0)}, r"joint 'mesh': radii: expected two positive pitch radii"),
    ({"ratio": 2.0, "teeth": (1, 2)}, r"joint 'mesh': ratio and teeth: give only one of"),
    ({"ratio": 1.0, "mesh": "internal"}, r"joint 'mesh': mesh: an internal pair needs a ring larger"),
    ({"ratio": 2.0, "mesh": "helical"}, r"joint 'mesh': mesh: expected one of 'external', "
                                        r"'internal', 'rack', got 'helical'"),
    ({"ratio": 2.0, "carrier": "g2"}, r"joint 'mesh': carrier: the carrier 'g2' cannot be one of"),
    ({"ratio": 2.0, "carrier": "nope"}, r"joint 'mesh': carrier: expected a declared link"),
    ({"ratio": 2.0, "radius": 1.0}, r"joint 'mesh': radius: only a rack and pinion"),
    ({"mesh": "rack"}, r"joint 'mesh': radius: a rack and pinion needs the pinion's pitch radius"),
])
def test_bad_gear_fields_say_what_to_do(gear, message):
    with pytest.raises(ModelError, match=message):
        spur_pair(**gear)


def test_a_gear_joint_between_a_link_and_itself():
    m = spur_pair(ratio=2.0)
    with pytest.raises(ModelError, match=r"joint 'mesh': joins link 'g2' to itself"):
        Mechanism(m.name, m.points, m.links,
                  m.joints[:2] + (Joint("mesh", "G", ("g2", "g2"), ratio=2.0),), m.inputs)


def test_gears_must_turn_on_their_carrier():
    m = spur_pair(ratio=2.0)
    loose = m.joints[:1] + (Joint("p3", "R", ("g2", "g3"), point="O4"), m.joints[2])
    points = m.points
    links = (Link("ground", ("O2",), ground=True), Link("g2", ("O2", "A", "O4")), m.links[2])
    with pytest.raises(ModelError, match=r"joint 'mesh': links: gear 'g3' must turn on the carrier "
                                         r"'ground'"):
        Mechanism(m.name, points, links, loose, m.inputs)


def test_gear_fields_on_other_joints_are_refused():
    m = spur_pair(ratio=2.0)
    with pytest.raises(ModelError, match=r"joint 'p2': teeth: only a gear joint \(type 'G'\) has one"):
        Mechanism(m.name, m.points, m.links,
                  (Joint("p2", "R", ("ground", "g2"), point="O2", teeth=(1, 2)),) + m.joints[1:],
                  m.inputs)


def test_round_trip_through_a_model_file():
    for stem in ("gear_train", "compound_gear_train", "planetary", "rack_and_pinion",
                 "geared_fivebar"):
        m = load(stem)
        back = kl.io.from_toml(kl.io.to_toml(m, units={"length": "mm", "angle": "deg"}))
        assert back.joints == m.joints
        assert Mechanism.from_dict(m.to_dict()).joints == m.joints


def two_idlers(r4=1.5):
    """Gear 1 drives gear 3 through two idlers at once (2 and 4): the second path repeats the
    first (each gives e = +r1/r3), so its last mesh is a redundant constraint, checked on
    every sample (idler 4 has pitch radius 1.5 in both its meshes)."""
    pts = (Point("O1", 0.0, 0.0), Point("M1", 1.0, 0.0), Point("O2", 2.0, 0.0), Point("M2", 2.0, 1.0),
           Point("O3", 4.0, 0.0), Point("M3", 5.0, 0.0), Point("O4", 2.0, -1.5), Point("M4", 2.0, -3.0))
    links = (Link("ground", ("O1", "O2", "O3", "O4"), ground=True), Link("g1", ("O1", "M1")),
             Link("g2", ("O2", "M2")), Link("g3", ("O3", "M3")), Link("g4", ("O4", "M4")))
    joints = tuple(Joint(f"p{i}", "R", ("ground", f"g{i}"), point=f"O{i}") for i in (1, 2, 3, 4))
    joints += (Joint("m12", "G", ("g1", "g2"), radii=(1.0, 1.0)),
               Joint("m23", "G", ("g2", "g3"), radii=(1.0, 1.0)),
               Joint("m14", "G", ("g1", "g4"), radii=(1.0, 1.5)),
               Joint("m43", "G", ("g4", "g3"), radii=(r4, 1.0)))
    return Mechanism("two idlers", pts, links, joints, (Input(joint="p1"),))


def test_a_redundant_gear_path_is_checked():
    m = two_idlers()
    mob = kl.structure.mobility(m)
    assert (mob.kutzbach_gruebler, mob.exact) == (0, 1)
    p = kl.kinematics.plan(m)
    assert p.redundant == ("m43",)
    sol = kl.analyze(m, q=TURN)
    np.testing.assert_allclose(sol.K("g3"), 1.0, rtol=1e-15)
    # a second path of another value jams the train: refused
    with pytest.raises(ModelError, match=r"0 degree\(s\) of freedom"):
        kl.analyze(two_idlers(r4=1.0), q=TURN)


def test_inputs_that_leave_no_gear_pair_solvable_are_refused():
    """The ring driven, and the planet relative to the arm: each mesh then has two unknown
    angles (planet and arm; sun and arm) and the arm is driven only relative to the planet."""
    with pytest.raises(ModelError, match=r"gear joints 'sun_planet', 'planet_ring': a gear pair is "
                                         r"solved once two of the angles of its gears and its "
                                         r"carrier are known"):
        kl.kinematics.plan(planetary(("ring_shaft", "planet_pin")))


@pytest.mark.parametrize("make, q", [(lambda: load("geared_fivebar"), np.radians([100.0, 200.0, 300.0])),
                                     (lambda: load("gear_train"), np.radians([10.0, 100.0])),
                                     (rack, np.radians([10.0, 100.0])),
                                     (planetary, willis_samples(3)[0])])
def test_kennedy_construction_from_pitch_points_meets_the_velocities(make, q):
    """A gear pair's primary centre is its pitch point; Kennedy's construction from there
    agrees with the centres solved from the velocities (the planetary train: sun at 1 rad/s, arm
    at 0.2 rad/s; at 0.3 rad/s the ring would stand still and its centre be undefined)."""
    sol = kl.analyze(make(), q=q, qd=np.linspace(1.0, 0.2, len(make().inputs)))
    kc = kl.kinematics.kennedy_construction(sol)
    ic = kl.kinematics.instant_centers(sol)
    assert {j for j in kc.primary.values()} >= {j.name for j in sol.mechanism.joints if j.type == "G"}
    for pair in ic:
        a, b = kc.centers[pair], ic[pair]
        np.testing.assert_array_equal(a.at_infinity, b.at_infinity)
        finite = ~np.asarray(b.at_infinity)
        np.testing.assert_allclose(np.asarray(a.position)[finite], np.asarray(b.position)[finite],
                                   rtol=1e-9, atol=1e-12)
