"""kinelab.gears.train: simple, compound, reverted and epicyclic trains.

Every value is checked by a route that does not go through the engine: the train value from
the numbers of teeth (the product of the drivers' over the product of the driven, the sign
(-1) to the number of external meshes), Willis' formula for the epicyclic trains (with each
of sun, ring and arm held in turn), the centre distances from the module.  The engine route
itself is checked against the example model files written by hand and analysed by kl.analyze.
"""
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.model import Input, Mechanism

EXAMPLES = Path(__file__).parents[2] / "examples"
RPM = 2 * math.pi / 60
# the engine solves a gear pair in closed form: a few roundings of the ratios
EXACT = 1e-13

PLANETARY = [("sun", "planet", 30, 20), ("planet", "ring", 20, 70, "internal")]


def by_teeth(meshes):
    """(-1)^(external meshes) prod(N_driver) / prod(N_driven): the value of a train on the frame."""
    value = 1.0
    for m in meshes:
        kind = m[4] if len(m) == 5 else "external"
        value *= (-1 if kind == "external" else 1) * m[2] / m[3]
    return value


# ------------------------------------------------------------------------------------------
# trains on the frame: the value from the teeth
# ------------------------------------------------------------------------------------------
def test_simple_train_with_an_idler():
    t = kl.gears.train([("g1", "idler", 20, 30), ("idler", "g3", 30, 40)], input="g1",
                       speed=2.0, acceleration=-3.0)
    assert t.output == "g3" and t.fixed == () and t.input == "g1"
    assert t.value == pytest.approx(20 / 40, rel=EXACT)      # the idler changes only the sense
    assert t.speeds == pytest.approx({"g1": 2.0, "idler": -2.0 * 20 / 30, "g3": 1.0}, rel=EXACT)
    assert t.accelerations == pytest.approx({"g1": -3.0, "idler": 2.0, "g3": -1.5}, rel=EXACT)


def test_compound_train_shafts_or_one_name_are_one_member():
    meshes = [("g1", "g2", 20, 50), ("g3", "g4", 15, 45)]
    t = kl.gears.train(meshes, input="g1", shafts=[("g2", "g3")], speed=1.5)
    assert t.value == pytest.approx(by_teeth(meshes), rel=EXACT)
    assert t.value == pytest.approx(2 / 15, rel=EXACT)
    assert t.speeds["g2"] == t.speeds["g3"] == pytest.approx(-1.5 * 20 / 50, rel=EXACT)
    assert t.accelerations is None
    one_name = kl.gears.train([("g1", "cluster", 20, 50), ("cluster", "g4", 15, 45)],
                              input="g1", speed=1.5)
    assert one_name.value == pytest.approx(t.value, rel=EXACT)
    assert one_name.speeds["cluster"] == pytest.approx(t.speeds["g2"], rel=EXACT)


def test_internal_mesh_on_the_frame_keeps_the_sense():
    t = kl.gears.train([("pinion", "ring", 18, 54, "internal")], input="pinion")
    assert t.value == pytest.approx(1 / 3, rel=EXACT)


MESH = st.tuples(st.integers(8, 120), st.integers(8, 120),
                 st.sampled_from(["external", "internal"]))


@given(st.lists(MESH, min_size=1, max_size=5), st.floats(-500, 500).filter(lambda w: abs(w) > 1e-3))
def test_any_compound_train_is_the_product_of_its_meshes(stages, speed):
    # stage i: gear "a{i}" drives "b{i}"; "b{i}" and "a{i+1}" share a shaft
    meshes = [(f"a{i}", f"b{i}", na, nb + (kind == "internal" and nb == na), kind)
              for i, (na, nb, kind) in enumerate(stages)]
    shafts = [(f"b{i}", f"a{i + 1}") for i in range(len(meshes) - 1)]
    t = kl.gears.train(meshes, input="a0", shafts=shafts, speed=speed)
    assert t.output == f"b{len(meshes) - 1}"
    assert t.value == pytest.approx(by_teeth(meshes), rel=1e-12)
    assert t.speeds[t.output] == pytest.approx(speed * by_teeth(meshes), rel=1e-12)


def test_rpm_in_and_out():
    meshes = [("g1", "g2", 20, 50), ("g3", "g4", 15, 45)]
    rad = kl.gears.train(meshes, input="g1", shafts=[("g2", "g3")], speed=1500 * RPM,
                         acceleration=60 * RPM)
    rpm = kl.gears.train(meshes, input="g1", shafts=[("g2", "g3")], speed=1500, acceleration=60,
                         rpm=True)
    assert rpm.rpm and not rad.rpm and rpm.value == pytest.approx(rad.value, rel=EXACT)
    assert rpm.speeds["g4"] == pytest.approx(200.0, rel=EXACT)
    assert rpm.accelerations["g4"] == pytest.approx(8.0, rel=EXACT)
    for n in rad.speeds:
        assert rpm.speeds[n] == pytest.approx(rad.speeds[n] / RPM, rel=EXACT)


# ------------------------------------------------------------------------------------------
# a reverted train: input and output on one axis
# ------------------------------------------------------------------------------------------
def test_reverted_train_with_equal_modules():
    meshes = [("g1", "g2", 20, 60), ("g3", "g4", 30, 50)]      # 20 + 60 = 30 + 50
    t = kl.gears.train(meshes, input="g1", shafts=[("g2", "g3")], coaxial=[("g1", "g4")],
                       module=0.002, speed=10.0)
    assert t.value == pytest.approx(by_teeth(meshes), rel=EXACT)
    assert t.value == pytest.approx(0.2, rel=EXACT)
    assert t.center_distances == pytest.approx({("g1", "g2"): 0.08, ("g3", "g4"): 0.08},
                                               rel=EXACT)
    # the model puts the input and the output on one axis
    m = t.mechanism
    bearing = {j.links[1]: j.point for j in m.joints if j.type == "R"}
    assert bearing["g1"] == bearing["g4"]


def test_reverted_train_with_two_modules():
    # m1 (N1 + N2) = m2 (N3 + N4): 2.5 mm (16 + 48) = 2 mm (32 + 48)
    t = kl.gears.train([("g1", "g2", 16, 48), ("g3", "g4", 32, 48)], input="g1",
                       shafts=[("g2", "g3")], coaxial=[("g1", "g4")], module=[0.0025, 0.002])
    assert t.center_distances[("g1", "g2")] == pytest.approx(0.08, rel=EXACT)
    assert t.center_distances[("g3", "g4")] == pytest.approx(0.08, rel=EXACT)
    assert t.value == pytest.approx(16 / 48 * 32 / 48, rel=EXACT)


def test_reverted_train_whose_centre_distances_differ_is_refused():
    with pytest.raises(ModelError, match=r"^module: meshes\[0\] \('g1' 20 \+ 'g2' 60\) and "
                                         r"meshes\[1\] \('g3' 30 \+ 'g4' 45\) join one pair of "
                                         r"axes at 0.04 m and 0.0375 m, m \(N_a ± N_b\) / 2; make "
                                         r"them equal: change the teeth or the modules$"):
        kl.gears.train([("g1", "g2", 20, 60), ("g3", "g4", 30, 45)], input="g1",
                       shafts=[("g2", "g3")], coaxial=[("g1", "g4")], module=0.001)
    # without a module, the speeds only: the layout is not checked
    t = kl.gears.train([("g1", "g2", 20, 60), ("g3", "g4", 30, 45)], input="g1",
                       shafts=[("g2", "g3")], coaxial=[("g1", "g4")])
    assert t.center_distances is None and t.value == pytest.approx(2 / 9, rel=EXACT)


# ------------------------------------------------------------------------------------------
# epicyclic trains: Willis' formula
# ------------------------------------------------------------------------------------------
def willis(t, a, b, arm):
    """(omega_b - omega_arm) / (omega_a - omega_arm)."""
    w = t.speeds
    return (w[b] - w[arm]) / (w[a] - w[arm])


@pytest.mark.parametrize("fixed, driver, output, value", [
    ("ring", "sun", "arm", 30 / (30 + 70)),         # the usual reduction
    ("sun", "ring", "arm", 70 / (30 + 70)),
    ("arm", "sun", "ring", -30 / 70),               # a train on the frame: the arm held
    ("ring", "arm", "sun", (30 + 70) / 30),
    ("sun", "arm", "ring", (30 + 70) / 70),
])
def test_planetary_follows_willis(fixed, driver, output, value):
    t = kl.gears.train(PLANETARY, carriers={"planet": "arm"}, fixed=fixed, input=driver,
                       speed=7.0, acceleration=-2.0, module=0.002)
    assert t.output == output and t.fixed == (fixed,)
    assert t.speeds[fixed] == 0.0 and t.accelerations[fixed] == 0.0
    assert t.value == pytest.approx(value, rel=EXACT)
    assert t.speeds[driver] == pytest.approx(7.0, rel=EXACT)
    # Willis: relative to the arm, sun -> planet -> ring is a train on the frame
    assert willis(t, "sun", "ring", "arm") == pytest.approx(-30 / 70, rel=1e-12)
    assert willis(t, "sun", "planet", "arm") == pytest.approx(-30 / 20, rel=1e-12)
    a = t.accelerations
    assert (a["ring"] - a["arm"]) == pytest.approx(-30 / 70 * (a["sun"] - a["arm"]),
                                                   rel=1e-12, abs=1e-12)
    # the sun, the ring and the arm share an axis: N_ring = N_sun + 2 N_planet
    assert t.center_distances == pytest.approx({("sun", "planet"): 0.05,
                                                ("planet", "ring"): 0.05}, rel=EXACT)


@given(st.integers(12, 60), st.integers(12, 60), st.sampled_from(["sun", "ring", "arm"]),
       st.floats(-300, 300).filter(lambda w: abs(w) > 1e-3))
def test_any_planetary_follows_willis(Ns, Np, fixed, speed):
    Nr = Ns + 2 * Np
    driver = {"sun": "ring", "ring": "sun", "arm": "sun"}[fixed]
    t = kl.gears.train([("sun", "planet", Ns, Np), ("planet", "ring", Np, Nr, "internal")],
                       carriers={"planet": "arm"}, fixed=fixed, input=driver, speed=speed,
                       module=0.0015)
    assert willis(t, "sun", "ring", "arm") == pytest.approx(-Ns / Nr, rel=1e-12)
    assert willis(t, "sun", "planet", "arm") == pytest.approx(-Ns / Np, rel=1e-12)
    assert t.speeds[fixed] == 0.0


def test_compound_planetary_with_a_cluster_planet():
    # sun 20 - planet 40; planet 25 (same shaft) - ring 85, ring held.  Arm held, the train
    # value is e = (-20/40)(+25/85); Willis with the ring still: omega_arm/omega_sun = e/(e - 1)
    e = (-20 / 40) * (25 / 85)
    t = kl.gears.train([("sun", "p2", 20, 40), ("p3", "ring", 25, 85, "internal")],
                       shafts=[("p2", "p3")], carriers={"p2": "arm"}, fixed="ring", input="sun")
    assert t.output == "arm"
    assert t.value == pytest.approx(e / (e - 1), rel=1e-12)
    assert willis(t, "sun", "ring", "arm") == pytest.approx(e, rel=1e-12)
    # with unequal modules the two meshes can share the centre distance: 20+40 = 85-25
    ok = kl.gears.train([("sun", "p2", 20, 40), ("p3", "ring", 25, 85, "internal")],
                        shafts=[("p2", "p3")], carriers={"p2": "arm"}, fixed="ring",
                        input="sun", module=0.001)
    assert ok.center_distances[("sun", "p2")] == pytest.approx(0.03, rel=EXACT)


def test_an_arm_with_teeth_driven_by_a_pinion():
    t = kl.gears.train([("pinion", "arm", 20, 60)] + PLANETARY, carriers={"planet": "arm"},
                       fixed="ring", input="pinion", speed=3.0)
    assert t.output == "arm"                  # the last driven gear is held: the arm
    assert t.speeds["arm"] == pytest.approx(-1.0, rel=EXACT)
    assert t.speeds["sun"] == pytest.approx(-1.0 * 100 / 30, rel=EXACT)


# ------------------------------------------------------------------------------------------
# the engine route against the example models written by hand
# ------------------------------------------------------------------------------------------
def with_inputs(m, *joints):
    return Mechanism(m.name, m.points, m.links, m.joints, tuple(Input(joint=j) for j in joints))


def test_planetary_against_the_example_model():
    example = kl.load(EXAMPLES / "planetary.toml")
    q = np.array([[0.3, -1.2], [2.0, 0.5], [-4.0, 7.0]])
    # sun driven, arm held
    sol = kl.analyze(example, q=q, qd=[5.0, 0.0], qdd=[1.5, 0.0])
    t = kl.gears.train(PLANETARY, carriers={"planet": "arm"}, fixed="arm", input="sun",
                       speed=5.0, acceleration=1.5)
    for n in ("planet", "ring"):
        np.testing.assert_allclose(sol.omega(n), t.speeds[n], rtol=EXACT)
        np.testing.assert_allclose(sol.alpha(n), t.accelerations[n], rtol=EXACT)
    # arm driven, ring held
    sol = kl.analyze(with_inputs(example, "ring_shaft", "arm_shaft"), q=q, qd=[0.0, 5.0])
    t = kl.gears.train(PLANETARY, carriers={"planet": "arm"}, fixed="ring", input="arm",
                       speed=5.0)
    for n in ("sun", "planet"):
        np.testing.assert_allclose(sol.omega(n), t.speeds[n], rtol=EXACT)


def test_compound_train_against_the_example_model():
    example = kl.load(EXAMPLES / "compound_gear_train.toml")
    sol = kl.analyze(example, q=np.linspace(0, 7, 8), qd=1.5, qdd=-0.5)
    t = kl.gears.train([("gear1", "cluster", 20, 50), ("cluster", "gear4", 15, 45)],
                       input="gear1", speed=1.5, acceleration=-0.5)
    for n in ("cluster", "gear4"):
        np.testing.assert_allclose(sol.omega(n), t.speeds[n], rtol=EXACT)
        np.testing.assert_allclose(sol.alpha(n), t.accelerations[n], rtol=EXACT)
    np.testing.assert_allclose(sol.K("gear4"), t.value, rtol=EXACT)


def test_the_train_model_analyses_as_any_model():
    """The result's mechanism, re-analysed over a sweep (kl.analyze, the certified route):
    speeds that do not depend on the position, a model that checks, one degree of freedom
    per driven member."""
    t = kl.gears.train(PLANETARY, carriers={"planet": "arm"}, fixed="ring", input="sun",
                       speed=4.0)
    m = t.mechanism
    assert kl.structure.mobility(m).exact == 2 == len(m.inputs)
    sol = kl.analyze(m, q=np.stack([np.linspace(-6, 6, 13), np.zeros(13)], -1), qd=[4.0, 0.0])
    for n in ("sun", "planet", "ring", "arm"):
        np.testing.assert_allclose(sol.omega(n), t.speeds[n], rtol=EXACT, atol=1e-15)


# ------------------------------------------------------------------------------------------
# bad input: one line naming the field and what to change
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, message", [
    (dict(meshes=[("a", "b", 0, 20)], input="a"),
     r"meshes\[0\]: teeth_driver: expected a positive number of teeth, got 0"),
    (dict(meshes=[("a", "b", 20, -3)], input="a"),
     r"meshes\[0\]: teeth_driven: expected a positive number of teeth, got -3"),
    (dict(meshes=[("a", "b", 2.5, 20)], input="a"),
     r"meshes\[0\]: teeth_driver: expected a whole number of teeth, got 2.5; round it"),
    (dict(meshes=[("a", "b", "20", 20)], input="a"),
     r"meshes\[0\]: teeth_driver: expected a whole number of teeth, got '20'"),
    (dict(meshes=[("a", "a", 20, 20)], input="a"),
     r"meshes\[0\]: member 'a' meshes with itself; a mesh joins two different members"),
    (dict(meshes=[("a", "b", 20, 30), ("c", "d", 30, 40)], input="a", shafts=[("b", "c", "d")]),
     r"meshes\[1\]: 'c' and 'd' turn on one shaft; a mesh joins two different members"),
    (dict(meshes=[("a", "b", 20, 30, "helical")], input="a"),
     r"meshes\[0\]: kind: expected one of 'external', 'internal', got 'helical'"),
    (dict(meshes=[("a", "b", 20, 20, "internal")], input="a"),
     r"meshes\[0\]: an internal mesh needs a ring with more teeth than the gear inside it"),
    (dict(meshes=[("a", "b", 20)], input="a"),
     r"meshes\[0\]: expected \(driver, driven, teeth_driver, teeth_driven\[, kind\]\)"),
    (dict(meshes=[], input="a"), r"meshes: expected a list of \(driver, driven"),
    (dict(meshes=[("a", "b", 20, 30)], input="x"),
     r"input: expected one of 'a', 'b', got 'x'"),
    (dict(meshes=[("a", "b", 20, 30)], input="a", fixed="a"),
     r"fixed: 'a' is the input \(or on its shaft\); hold another member"),
    (dict(meshes=[("frame", "b", 20, 30)], input="b"),
     r"meshes\[0\]: driver: 'frame' names the frame"),
    (dict(meshes=[("a", "b", 20, 30), ("c", "d", 30, 40)], input="a"),
     r"meshes: 'c', 'd' not geared to the input 'a'; add the mesh that joins them"),
    # two members held in a planetary train: it locks
    (dict(meshes=PLANETARY, carriers={"planet": "arm"}, input="sun", fixed=["ring", "arm"]),
     r"fixed: the train has 2 degree\(s\) of freedom, and 3 members are driven or held \(the "
     r"input 'sun', the fixed 'ring', 'arm'\): it locks; hold 1 member\(s\) fewer"),
    # a member held in a train on the frame: it locks
    (dict(meshes=[("a", "b", 20, 30), ("b", "c", 30, 40)], input="a", fixed="c"),
     r"fixed: the train has 1 degree\(s\) of freedom, and 2 members are driven or held"),
    # nothing held in a planetary train: not determined
    (dict(meshes=PLANETARY, carriers={"planet": "arm"}, input="sun"),
     r"fixed: the train has 2 degrees of freedom, and only 1 member\(s\) are driven or held "
     r"\(the input 'sun'\): it is not determined; hold 1 more member\(s\) still with fixed=, "
     r"e.g. one of 'ring', 'arm'"),
    # three external gears in a ring of meshes: nothing can turn
    (dict(meshes=[("a", "b", 20, 30), ("b", "c", 30, 40), ("c", "a", 40, 20)], input="a"),
     r"meshes: the train locks: its meshes close a loop whose ratios disagree"),
    (dict(meshes=PLANETARY + [("sun", "ring", 30, 70, "internal")],
          carriers={"planet": "arm"}, input="sun", fixed="arm"),
     r"meshes\[2\]: 'sun' and 'ring' turn about one axis; gears in mesh turn about different "
     r"centres"),
    (dict(meshes=[PLANETARY[0], ("planet", "ring", 20, 80, "internal")],
          carriers={"planet": "arm"}, input="sun", fixed="ring", module=0.002),
     r"module: meshes\[0\] \('sun' 30 \+ 'planet' 20\) and meshes\[1\] \('planet' 20 - 'ring' "
     r"80\) join one pair of axes at 0.05 m and 0.06 m"),
    (dict(meshes=[("a", "b", 20, 30)], input="a", module=-1.0),
     r"module: expected positive modules \(m\), got -1.0"),
    (dict(meshes=[("a", "b", 20, 30)], input="a", speed=float("nan")),
     r"speed: expected a finite number, got nan"),
    (dict(meshes=PLANETARY, carriers={"planet": "planet"}, input="sun", fixed="ring"),
     r"carriers\['planet'\]: a gear cannot carry its own axis; name the arm"),
    (dict(meshes=[("a", "b", 20, 30)], input="a", output="c"),
     r"output: expected one of 'a', 'b', got 'c'"),
    (dict(meshes=[("a", "b", 20, 30)], input="a", shafts=[("b", "x")]),
     r"shafts\[0\]: expected one of 'a', 'b', got 'x'"),
    (dict(meshes=PLANETARY, carriers={"planet": "arm", "arm2": "x"}, input="sun", fixed="ring"),
     r"carriers: expected one of 'sun', 'planet', 'ring', got 'arm2'"),
    (dict(meshes=[("s", "p", 20, 20), ("p", "q", 20, 20)], carriers={"p": "arm", "q": "arm2"},
          input="s", fixed="arm"),
     r"meshes\[1\]: 'p' is carried by 'arm' and 'q' by 'arm2'; gears in mesh have their axes "
     r"on one member"),
    (dict(meshes=PLANETARY, carriers={"planet": "arm"}, input="sun", fixed=["ring", "ring"]),
     r"fixed: 'ring', 'ring' name one member twice; name each once"),
])
def test_bad_trains_say_what_to_change(kwargs, message):
    meshes = kwargs.pop("meshes")
    with pytest.raises(ModelError, match=message) as err:
        kl.gears.train(meshes, **kwargs)
    assert "\n" not in str(err.value)


# ------------------------------------------------------------------------------------------
# two planets in series: the engine is driven by the arm, the speeds combined to the inputs
# ------------------------------------------------------------------------------------------
DOUBLE = [("sun", "p1", 30, 15), ("p1", "p2", 15, 15), ("p2", "ring", 15, 90, "internal")]
ON_ARM = {"p1": "arm", "p2": "arm"}


def test_two_planets_in_series_follow_willis():
    t = kl.gears.train(DOUBLE, carriers=ON_ARM, fixed="ring", input="sun", speed=2.0,
                       acceleration=1.0)
    e = (-30 / 15) * (-15 / 15) * (15 / 90)           # arm held: +N_s / N_r
    assert willis(t, "sun", "ring", "arm") == pytest.approx(e, rel=1e-12)
    assert willis(t, "sun", "p2", "arm") == pytest.approx(30 / 15, rel=1e-12)
    assert t.output == "arm" and t.value == pytest.approx(e / (e - 1), rel=1e-12)
    assert t.speeds["sun"] == 2.0 and t.speeds["ring"] == 0.0
    assert t.accelerations["arm"] == pytest.approx(1.0 * t.value, rel=1e-12)


def test_two_planets_driven_by_the_arm_agree_with_driven_by_the_sun():
    """The arm driven is the engine's own route; the sun driven goes through the
    combination of the arm's and the sun's velocity coefficients: inverse values."""
    by_arm = kl.gears.train(DOUBLE, carriers=ON_ARM, fixed="ring", input="arm")
    by_sun = kl.gears.train(DOUBLE, carriers=ON_ARM, fixed="ring", input="sun", output="arm")
    assert by_arm.output == "sun"
    assert by_sun.value == pytest.approx(1 / by_arm.value, rel=1e-12)
    for n in ("p1", "p2"):
        assert by_sun.speeds[n] == pytest.approx(by_arm.speeds[n] / by_arm.value, rel=1e-12)
