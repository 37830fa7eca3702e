"""The planar engine against independent checks, on every catalogue mechanism."""
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl
from kinelab.model import Point
from tests.kinematics.checks import closure_residual, engine_difference, finite_difference_errors

CRANK = np.radians(np.arange(0.0, 360.0, 2.0)) + 0.01   # off the axes

CATALOGUE = {
    "fourbar": lambda: kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)),
    "fourbar_crossed": lambda: kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, (1.5, -0.4), "crossed"),
    "slider_crank": lambda: kl.mechanisms.slider_crank(1.0, 3.0, offset=0.5),
    "slider_crank_left": lambda: kl.mechanisms.slider_crank(1.0, 3.0, offset=-0.3, branch="left"),
    "slotted_link": lambda: kl.mechanisms.slotted_link(1.0, 2.0),
    "inverted_slider_crank": lambda: kl.mechanisms.inverted_slider_crank(2.0, 1.0, offset=0.3),
    "whitworth": lambda: kl.mechanisms.whitworth(1.0, 0.5, 1.0, 2.0),
    "watt6": kl.mechanisms.watt6,
    "stephenson6": kl.mechanisms.stephenson6,
    "triad6": kl.mechanisms.triad6,
}
FIVEBAR_Q = np.stack([np.linspace(1.2, 2.0, 40), np.linspace(1.3, 1.9, 40)], axis=-1)


def cases():
    for name, make in CATALOGUE.items():
        yield pytest.param(make, CRANK, id=name)
    yield pytest.param(lambda: kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0), FIVEBAR_Q, id="fivebar")


@pytest.mark.parametrize("make, q", list(cases()))
def test_loop_closure(make, q):
    sol = kl.analyze(make(), q=q)
    assert closure_residual(sol) < 1e-10


@pytest.mark.parametrize("make, q", list(cases()))
def test_K_and_L_against_finite_differences(make, q):
    # central differences with h = 1e-5: truncation ~h^2 = 1e-10, rounding ~1e-16/h = 1e-11
    err_K, err_L = finite_difference_errors(make(), q)
    assert err_K < 1e-6 and err_L < 1e-6


@pytest.mark.parametrize("make, q", list(cases()))
def test_closed_form_against_newton_engine(make, q):
    assert engine_difference(make(), q) < 1e-10


@pytest.mark.parametrize("make, q", list(cases()))
def test_rates_follow_K_and_L(make, q):
    m = make()
    M = len(m.inputs)
    rng = np.random.default_rng(0)
    qd = rng.normal(size=np.shape(q))
    qdd = rng.normal(size=np.shape(q))
    sol = kl.analyze(m, q=q, qd=qd, qdd=qdd)
    qd2 = qd.reshape(-1, M)
    qdd2 = qdd.reshape(-1, M)
    for link in m.link_names:
        K = sol.K(link).reshape(-1, M)
        L = sol.L(link).reshape(-1, M, M)
        np.testing.assert_allclose(sol.omega(link), np.einsum("nm,nm->n", K, qd2), rtol=0, atol=1e-12)
        expected = np.einsum("nm,nm->n", K, qdd2) + np.einsum("nab,na,nb->n", L, qd2, qd2)
        np.testing.assert_allclose(sol.alpha(link), expected, rtol=1e-12, atol=1e-12)


def test_sketch_is_reproduced():
    """At the sketch's own input the engine returns the sketch."""
    for make in CATALOGUE.values():
        m = make()
        p = kl.kinematics.plan(m)
        sol = kl.analyze(m, q=p.q_sketch[0])
        for pt in m.points:
            np.testing.assert_allclose(sol.position(pt.name), [pt.x, pt.y], rtol=0, atol=1e-12)


def test_fivebar_shapes_follow_inputs():
    fb5 = kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0)
    sol = kl.analyze(fb5, q=FIVEBAR_Q, qd=[1.0, -2.0])
    assert sol.position("P").shape == (40, 2)
    assert sol.K("coupler1").shape == (40, 2)
    assert sol.L("coupler1").shape == (40, 2, 2)
    assert sol.K("P").shape == (40, 2, 2)
    assert sol.L("P").shape == (40, 2, 2, 2)
    one = kl.analyze(fb5, q=FIVEBAR_Q[3])
    assert one.position("P").shape == (2,) and one.K("P").shape == (2, 2)
    # L is symmetric in its two input axes
    L = sol.L("P")
    np.testing.assert_allclose(L, np.swapaxes(L, -1, -2), rtol=0, atol=1e-13)


def test_scalar_and_vector_shapes():
    sc = kl.mechanisms.slider_crank(1.0, 3.0)
    one = kl.analyze(sc, q=0.3)
    many = kl.analyze(sc, q=[0.3, 0.4])
    assert one.position("B").shape == (2,) and many.position("B").shape == (2, 2)
    assert np.shape(one.angle("rod")) == () and many.angle("rod").shape == (2,)
    assert np.shape(one.K("slide")) == () and many.L("slide").shape == (2,)
    np.testing.assert_array_equal(one.position("B"), many.position("B")[0])


@st.composite
def grashof_crank_rockers(draw):
    crank = draw(st.floats(0.2, 1.0))
    ground = draw(st.floats(1.5, 4.0))
    coupler = draw(st.floats(1.5, 4.0))
    rocker = draw(st.floats(1.5, 4.0))
    lengths = sorted([crank, ground, coupler, rocker])
    # strictly Grashof with the crank shortest, and away from the change-point limit
    if lengths[0] != crank or lengths[0] + lengths[3] > lengths[1] + lengths[2] - 0.05:
        return draw(st.nothing())
    branch = draw(st.sampled_from(["open", "crossed"]))
    cp = (draw(st.floats(-1.0, 2.0)), draw(st.floats(-1.0, 1.0)))
    return kl.mechanisms.fourbar(ground, crank, coupler, rocker, coupler_point=cp, branch=branch)


@given(grashof_crank_rockers())
def test_random_crank_rockers(fb):
    q = np.radians(np.arange(0.0, 360.0, 7.0)) + 0.01
    sol = kl.analyze(fb, q=q)
    assert closure_residual(sol) < 1e-10
    assert engine_difference(fb, q) < 1e-9
    err_K, err_L = finite_difference_errors(fb, q)
    assert err_K < 1e-6 and err_L < 1e-5


@given(st.floats(0.2, 1.0), st.floats(1.3, 3.0), st.floats(-0.5, 0.5), st.sampled_from(["right", "left"]))
def test_random_slider_cranks(crank, rod, offset, branch):
    sc = kl.mechanisms.slider_crank(crank, rod, offset=offset, branch=branch)
    q = np.radians(np.arange(0.0, 360.0, 7.0)) + 0.01
    sol = kl.analyze(sc, q=q)
    assert closure_residual(sol) < 1e-10
    # independent closed form: x_B = R cos q + s sqrt(L^2 - (R sin q - e)^2)
    s = 1.0 if branch == "right" else -1.0
    root = np.sqrt(rod ** 2 - (crank * np.sin(q) - offset) ** 2)
    x = crank * np.cos(q) + s * root
    dx = -crank * np.sin(q) - s * (crank * np.sin(q) - offset) * crank * np.cos(q) / root
    np.testing.assert_allclose(sol.slide("slide"), x, rtol=0, atol=1e-12)
    np.testing.assert_allclose(sol.K("slide"), dx, rtol=0, atol=1e-11)
    assert engine_difference(sc, q) < 1e-10


def test_time_ratio_whitworth_closed_form():
    # dead centres where the crank pin crosses the x axis: sin q = -d/R
    for d in (0.2, 0.5, 0.8):
        w = kl.mechanisms.whitworth(crank=1.0, distance=d, lever=1.2, rod=2.5)
        tr = kl.kinematics.time_ratio(w, "ram_slide")
        a = np.arcsin(d)
        assert tr.ratio == pytest.approx((np.pi + 2 * a) / (np.pi - 2 * a), rel=1e-11)
        np.testing.assert_allclose(np.sin(tr.dead_centres), -d, atol=1e-11)


def test_time_ratio_slotted_link_closed_form():
    # the lever reverses when O4A is tangent to the crank circle: q = pi -+ acos(R/C)
    R, C = 1.0, 2.0
    tr = kl.kinematics.time_ratio(kl.mechanisms.slotted_link(R, C), "lever")
    phi = np.arccos(R / C)
    assert tr.ratio == pytest.approx((2 * np.pi - 2 * phi) / (2 * phi), rel=1e-11)
    assert tr.fast == pytest.approx(2 * phi, rel=1e-11)


def test_no_time_ratio_when_the_crank_cannot_turn():
    """Non-Grashof four-bar (ground 1, crank 2, coupler 1, rocker 1.5): A reaches O4 only
    while |A - O4|^2 = 5 - 4 cos q <= (1 + 1.5)^2, so |q| <= acos(-0.3125)."""
    fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    with pytest.raises(kl.errors.AssemblyError,
                       match=r"^time_ratio: 'rocker' has no time ratio: its input 'jO2' cannot turn "
                             r"a full turn; it reaches only \[-1.88862, 1.88862\] rad") as info:
        kl.kinematics.time_ratio(fb, "rocker")
    assert isinstance(info.value, ValueError)
    limit = np.arccos(-0.3125)
    np.testing.assert_allclose(info.value.reachable, [(-limit, limit)], rtol=0, atol=1e-9)
    # a slider-crank whose crank (3) outreaches its rod (1): |sin q| <= 1/3 near 0 and near pi
    with pytest.raises(kl.errors.AssemblyError, match="it reaches only") as info:
        kl.kinematics.time_ratio(kl.mechanisms.slider_crank(3.0, 1.0), "slide")
    a = np.arcsin(1 / 3)
    np.testing.assert_allclose(info.value.reachable, [(-np.pi - a, -np.pi + a), (-a, a)],
                               rtol=0, atol=1e-9)


def test_no_time_ratio_through_a_singular_configuration():
    """Crank = rod: at q = 90 deg the rod stands across the slide (det J = 0); the sketch at
    45 deg puts that configuration on the sweep's grid."""
    sc = kl.mechanisms.slider_crank(1.0, 1.0)
    c = np.sqrt(0.5)
    m = kl.Mechanism("equal arms", (Point("O2", 0, 0), Point("A", c, c), Point("B", 2 * c, 0)),
                     sc.links, sc.joints, sc.inputs)
    with pytest.raises(kl.errors.SingularityError,
                       match=r"passes a singular configuration near q = 1.5708 rad"):
        kl.kinematics.time_ratio(m, "slide")


def test_transmission_angle_against_law_of_cosines():
    a, b, c, d = 1.0, 3.0, 2.5, 3.0
    fb = kl.mechanisms.fourbar(d, a, b, c)
    q = np.radians(np.arange(0.0, 360.0, 5.0))
    sol = kl.analyze(fb, q=q)
    diag2 = a ** 2 + d ** 2 - 2 * a * d * np.cos(q)          # |A O4|^2
    mu = np.arccos((b ** 2 + c ** 2 - diag2) / (2 * b * c))
    np.testing.assert_allclose(kl.kinematics.transmission_angle(sol, acute=False), mu, atol=1e-12)
    np.testing.assert_allclose(kl.kinematics.transmission_angle(sol), np.minimum(mu, np.pi - mu), atol=1e-12)


def _with_input(m, inp):
    return kl.model.Mechanism(m.name, m.points, m.links, m.joints, (inp,))


def _hydraulic_boom():
    """A boom raised by a hydraulic cylinder: the input is the cylinder's extension."""
    P, L, J, I = kl.model.Point, kl.model.Link, kl.model.Joint, kl.model.Input
    axis = (2.0 - 0.8, 1.2 - 0.0)          # from the barrel pivot C to the rod end D
    return kl.model.Mechanism(
        "boom",
        points=(P("O", 0, 0), P("C", 0.8, 0.0), P("D", 2.0, 1.2), P("T", 4.0, 2.0)),
        links=(L("ground", ("O", "C"), ground=True), L("boom", ("O", "D", "T")),
               L("barrel", ("C",)), L("rod", ("D",))),
        joints=(J("jO", "R", ("ground", "boom"), point="O"),
                J("jC", "R", ("ground", "barrel"), point="C"),
                J("jD", "R", ("boom", "rod"), point="D"),
                J("cylinder", "P", ("barrel", "rod"), point="D", axis=axis, origin="C")),
        inputs=(I(joint="cylinder"),))


@pytest.mark.parametrize("make, q", [
    # the four-bar driven by the angle at B between coupler and rocker (a Newton group)
    (lambda: _with_input(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), kl.model.Input(joint="jB")), None),
    # the slider-crank driven by its piston (a driven slide, then an RRR dyad)
    (lambda: _with_input(kl.mechanisms.slider_crank(1.0, 3.0, 0.2), kl.model.Input(joint="slide")),
     np.linspace(2.3, 3.8, 25)),
    # the four-bar driven by the coupler's absolute angle (links = ground, coupler)
    (lambda: _with_input(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5),
                         kl.model.Input(links=("ground", "coupler"))), None),
    (_hydraulic_boom, None),
], ids=["relative-angle", "piston", "coupler-angle", "cylinder"])
def test_other_kinds_of_input(make, q):
    m = make()
    if q is None:     # inside the reachable range, away from its limits
        lo, hi = kl.kinematics.reachable_ranges(m)[0]
        q = lo + (hi - lo) * np.linspace(0.05, 0.95, 25)
    sol = kl.analyze(m, q=q)
    assert closure_residual(sol) < 1e-10
    err_K, err_L = finite_difference_errors(m, q)
    assert err_K < 1e-6 and err_L < 1e-6
    assert engine_difference(m, q) < 1e-9


def test_cylinder_reach_is_the_triangle_inequality():
    """The boom's cylinder reaches |OD| -+ |OC| (Newton plan: continuation and bisection)."""
    lo, hi = kl.kinematics.reachable_ranges(_hydraulic_boom())[0]
    OD, OC = np.hypot(2.0, 1.2), 0.8
    # the bound is where continuation, halving its step, stops converging: at a limit
    # position Newton converges slowly, and the bound is good to about 1e-9
    assert lo == pytest.approx(OD - OC, abs=2e-9) and hi == pytest.approx(OD + OC, abs=2e-9)


def test_reach_of_a_newton_plan_limited_by_one_of_its_dyads():
    """triad6 (a Newton group; the crank turns fully) with a dyad A-F-O8 added on the crank
    pin: F closes while |A - O8| <= 1.8, i.e. 2.5 - 1.5 sin q <= 1.8^2, so the reach is
    sin q >= -0.74 / 1.5, bounded by the dyad (closed form) and not by the triad."""
    d = kl.mechanisms.triad6().to_dict()
    d.pop("parameters")
    d["points"].update({"F": [math.sqrt(0.9 ** 2 - 0.5 ** 2), 1.0], "O8": [0.0, 1.5]})
    d["links"][0]["points"].append("O8")
    d["links"] += [{"name": "link6", "points": ["A", "F"]}, {"name": "link7", "points": ["F", "O8"]}]
    d["joints"] += [{"name": "jA6", "type": "R", "links": ["crank", "link6"], "point": "A"},
                    {"name": "jF", "type": "R", "links": ["link6", "link7"], "point": "F"},
                    {"name": "jO8", "type": "R", "links": ["ground", "link7"], "point": "O8"}]
    m = kl.model.Mechanism.from_dict(d)
    assert [s.kind for s in kl.kinematics.plan(m).steps] == ["driven", "placed", "RRR", "newton"]
    lo = math.asin((2.5 - 1.8 ** 2) / 1.5)
    (a, b), = kl.kinematics.reachable_ranges(m)
    assert a == pytest.approx(lo, abs=1e-10) and b == pytest.approx(math.pi - lo, abs=1e-10)


def test_continuing_a_newton_sweep_in_pieces():
    """A sweep run in two pieces, the second starting where the first ended, equals the whole."""
    t6 = kl.mechanisms.triad6()
    q = np.linspace(0.0, 4 * np.pi, 400)          # two full turns
    whole = kl.analyze(t6, q=q)
    first = kl.analyze(t6, q=q[:150])
    second = kl.analyze(t6, q=q[150:], start=first)
    for name in ("triad", "link4"):
        np.testing.assert_allclose(second.angle(name), whole.angle(name)[150:], atol=1e-12)
        np.testing.assert_allclose(second.L(name), whole.L(name)[150:], atol=1e-9)
    with pytest.raises(kl.errors.ModelError, match="start: expected an earlier KinematicSolution"):
        kl.analyze(t6, q=q[:3], start=kl.analyze(kl.mechanisms.stephenson6(), q=0.1))
