"""Bad input: the same ModelError as analyze for a model it cannot analyse, clear messages
for bad arguments, and simplification that gives up instead of hanging."""
import time

import pytest
import sympy as sp

import kinelab as kl
from kinelab.derive import derive
from kinelab.derive._simplify import simplified
from kinelab.errors import ModelError
from kinelab.model import Input, Joint, Mechanism

FB = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)


def same_error_as_analyze(m):
    with pytest.raises(ModelError) as theirs:
        kl.analyze(m, 0.0)
    with pytest.raises(ModelError) as mine:
        derive(m)
    assert str(mine.value) == str(theirs.value)
    return str(mine.value)


def test_models_analyze_refuses_are_refused_alike():
    no_input = Mechanism("f", FB.points, FB.links, FB.joints, ())
    assert "has no input" in same_error_as_analyze(no_input)
    two_inputs = Mechanism("f", FB.points, FB.links, FB.joints,
                           (Input(joint="jO2"), Input(joint="jO4")))
    assert "1 degree(s) of freedom" in same_error_as_analyze(two_inputs)
    cam = Mechanism("c", FB.points, FB.links, FB.joints + (Joint("contact", "cam", ("rocker", "crank")),),
                    FB.inputs)
    assert "handles R and P joints" in same_error_as_analyze(cam)


def test_arguments():
    with pytest.raises(ModelError, match=r"lang: expected one of 'en', 'pt', got 'fr'"):
        derive(FB, "fr")
    with pytest.raises(ModelError, match=r"model: expected a kinelab Mechanism, got str"):
        derive("fourbar")
    d = derive(FB)
    with pytest.raises(ModelError, match=r"lang: expected one of 'en', 'pt', got 'de'"):
        d.to_markdown(lang="de")


def test_an_input_the_model_cannot_reach_is_the_engines_error():
    d = derive(kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5))
    with pytest.raises(kl.errors.AssemblyError):
        d.to_markdown(at=2.0)


def test_simplification_gives_up_beyond_its_bounds():
    x, y = sp.symbols("x y")
    big = sp.expand((sp.sin(x) + sp.cos(y) + x * y) ** 12)
    t = time.perf_counter()
    out, done = simplified(big, limit=300)
    assert (out, done) == (big, False) and time.perf_counter() - t < 1.0
    # within the size bound but past the time bound: kept as it is, flagged
    slow = sp.expand((sp.sin(x) * sp.cos(y) + sp.cos(x) * sp.sin(y) + x) ** 5)
    out, done = simplified(slow, limit=10 ** 6, seconds=0.01)
    assert (out, done) == (slow, False)
    # and what it simplifies it simplifies
    assert simplified(sp.sin(x) * sp.cos(y) + sp.cos(x) * sp.sin(y)) == (sp.sin(x + y), True)


def test_a_model_beyond_the_closed_forms_size_is_refused_at_once():
    """A crank driving five RRR dyads side by side: 10 unknowns, refused before any algebra
    (it took about 20 s; six dyads over a minute)."""
    from kinelab.model import Link, Point
    pts, links, joints = [Point("O2", 0.0, 0.0), Point("A", 0.0, 0.1)], [], []
    ground, dyads = ["O2"], 5
    for i in range(dyads):
        pts += [Point(f"C{i}", 0.3 + 0.05 * i, 0.3), Point(f"G{i}", 0.4 + 0.05 * i, 0.0)]
        ground.append(f"G{i}")
        links += [Link(f"a{i}", ("A", f"C{i}")), Link(f"b{i}", (f"C{i}", f"G{i}"))]
        joints += [Joint(f"jA{i}", "R", ("crank", f"a{i}"), point="A"),
                   Joint(f"jC{i}", "R", (f"a{i}", f"b{i}"), point=f"C{i}"),
                   Joint(f"jG{i}", "R", ("ground", f"b{i}"), point=f"G{i}")]
    m = Mechanism("five dyads", tuple(pts),
                  (Link("ground", tuple(ground), ground=True), Link("crank", ("O2", "A")), *links),
                  (Joint("jO2", "R", ("ground", "crank"), point="O2"), *joints), (Input(joint="jO2"),))
    with pytest.raises(ModelError, match=r"^model: 'five dyads' has 10 unknown coordinates; the "
                                         r"derivation in closed form .* at most 8 \(four dyads\)"):
        derive(m)


def test_gear_joints_are_not_derived():
    from pathlib import Path

    from kinelab.derive import loop_equations
    m = kl.load(Path(__file__).resolve().parents[2] / "examples" / "gear_train.toml")
    with pytest.raises(ModelError, match=r"joints 'mesh12', 'mesh23': the derivation writes the "
                                         r"loop equations of R and P joints; gear joints \(G\) are "
                                         r"not derived"):
        loop_equations(m)
