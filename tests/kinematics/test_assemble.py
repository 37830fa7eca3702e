"""Assembly from exact lengths and a rough sketch, and re-posing a mechanism.

Checks are independent of the assembler: distances measured on the output points, the
nearest-point condition from a finite-difference Jacobian of those distances, the
catalogue's closed-form constructions for the same lengths, and the engine's analysis.
"""
import math

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import AssemblyError, ModelError, SingularityError
from kinelab.model import Input, Joint, Link, Mechanism, Point
from tests.io.bad_cases import BASE
from tests.kinematics.checks import closure_residual, wrap


def pins(*spec):
    return tuple(Joint(f"j{p}", "R", links, point=p) for p, links in spec)


def rough_fourbar(A=(0.1, 1.05), B=(2.6, 2.5), P=(1.0, 2.6), lengths=(1.0, 3.0, 2.5),
                  place=(1.5, 1.0), inputs=(Input(joint="jO2"),)):
    return Mechanism(
        "fb", (Point("O2", 0, 0), Point("A", *A), Point("B", *B), Point("O4", 3, 0), Point("P", *P)),
        (Link("ground", ("O2", "O4"), ground=True), Link("crank", ("O2", "A"), length=lengths[0]),
         Link("coupler", ("A", "B", "P"), length=lengths[1], local={"P": place}),
         Link("rocker", ("O4", "B"), length=lengths[2])),
        pins(("O2", ("ground", "crank")), ("A", ("crank", "coupler")), ("B", ("coupler", "rocker")),
             ("O4", ("ground", "rocker"))),
        inputs)


def cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


def dist(m, a, b):
    return math.dist(m.point(a).xy, m.point(b).xy)


def test_a_rough_fourbar_gets_its_lengths_and_its_coupler_point():
    a = kl.kinematics.assemble(rough_fourbar())
    m = a.mechanism
    for p, q, length in (("O2", "A", 1.0), ("A", "B", 3.0), ("O4", "B", 2.5)):
        assert dist(m, p, q) == pytest.approx(length, rel=1e-14)
    A, B, P = (np.array(m.point(n).xy) for n in "ABP")
    e = (B - A) / 3.0
    assert (P - A) @ e == pytest.approx(1.5, abs=1e-14)
    assert (P - A) @ np.array([-e[1], e[0]]) == pytest.approx(1.0, abs=1e-14)
    assert m.point("O4").xy == (3.0, 0.0) and m.point("O2").xy == (0.0, 0.0)
    assert set(a.moved) == {"A", "B", "P"}
    assert a.moved["B"] == pytest.approx(math.dist(m.point("B").xy, (2.6, 2.5)), rel=1e-12)
    # the same linkage as the catalogue's, with the crank where the assembly put it
    q = math.atan2(m.point("A").y, m.point("A").x)
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    ref = kl.analyze(fb, q)
    np.testing.assert_allclose(m.point("B").xy, ref.position("B"), rtol=0, atol=1e-13)
    np.testing.assert_allclose(m.point("P").xy, ref.position("P"), rtol=0, atol=1e-13)


def test_without_inputs_the_assembly_is_the_nearest_to_the_sketch():
    """At the nearest point x of the constraint set to the sketch x0, x - x0 is normal to the
    set: its part along every direction the constraints allow (their Jacobian's null space)
    is zero.  The Jacobian here is a central difference of the measured distances."""
    rough = rough_fourbar(inputs=())
    m = kl.kinematics.assemble(rough).mechanism
    free = ["A", "B", "P"]
    x = np.concatenate([m.point(n).xy for n in free])
    x0 = np.concatenate([rough.point(n).xy for n in free])

    def constraints(v):
        A, B, P = v[0:2], v[2:4], v[4:6]
        e = B - A
        return np.array([np.hypot(*A), np.hypot(*e), np.hypot(*(B - (3.0, 0.0))),
                         (P - A) @ e / 3.0, (e[0] * (P - A)[1] - e[1] * (P - A)[0]) / 3.0])
    h = 1e-6
    J = np.array([(constraints(x + h * d) - constraints(x - h * d)) / (2 * h) for d in np.eye(6)]).T
    null = np.linalg.svd(J)[2][J.shape[0]:]          # directions along the constraint set
    assert np.max(np.abs(null @ (x - x0))) < 1e-8
    assert np.linalg.norm(x - x0) > 1e-2              # it did move
    np.testing.assert_allclose(constraints(x), [1.0, 3.0, 2.5, 1.5, 1.0], rtol=1e-13)


def test_the_crank_keeps_its_drawn_angle():
    """With an input the assembly is at the sketch's input: the crank along its drawn
    direction, B where the catalogue's closed form puts it at that angle on the open branch."""
    rough = rough_fourbar()
    a = kl.kinematics.assemble(rough)
    m = a.mechanism
    q = math.atan2(1.05, 0.1)
    np.testing.assert_allclose(m.point("A").xy, (math.cos(q), math.sin(q)), rtol=0, atol=1e-15)
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    ref = kl.analyze(fb, q)
    np.testing.assert_allclose(m.point("B").xy, ref.position("B"), rtol=0, atol=1e-14)
    np.testing.assert_allclose(m.point("P").xy, ref.position("P"), rtol=0, atol=1e-14)
    assert a.switched == ()


@pytest.mark.parametrize("B, side", [((2.6, 2.5), 1.0), ((1.8, -1.2), -1.0)])
def test_the_sketch_keeps_its_branch(B, side):
    m = kl.kinematics.assemble(rough_fourbar(B=B, P=(1.0, 0.0))).mechanism
    A, Bx, O4 = (np.array(m.point(n).xy) for n in ("A", "B", "O4"))
    assert np.sign(cross(O4 - A, Bx - A)) == side         # B left of A -> O4: open


def test_a_sketch_drawn_near_the_line_of_its_dyad_keeps_its_side():
    # B drawn 0.05 from the line A -> O4 while A is 0.35 off its circle: the nearest assembly
    # (without the input held) puts B on the other side of that line; continued from the
    # sketch's own lengths at the drawn crank angle, it stays on the side drawn
    A, B = (0.56534, -0.33324), (1.82350, -0.18927)
    rough = rough_fourbar(A=A, B=B, P=(1.0, 0.0), lengths=(1.0, 2.0, 2.0), place=(1.0, 0.0))
    O4 = np.array([3.0, 0.0])
    assert -0.1 < cross(O4 - A, np.subtract(B, A)) < 0         # drawn just to the right
    m = kl.kinematics.assemble(rough).mechanism
    A1, B1 = np.array(m.point("A").xy), np.array(m.point("B").xy)
    assert cross(O4 - A1, B1 - A1) < 0
    assert math.atan2(A1[1], A1[0]) == pytest.approx(math.atan2(A[1], A[0]), abs=1e-14)
    free = kl.kinematics.assemble(rough_fourbar(A=A, B=B, P=(1.0, 0.0), lengths=(1.0, 2.0, 2.0),
                                                place=(1.0, 0.0), inputs=())).mechanism
    A2, B2 = np.array(free.point("A").xy), np.array(free.point("B").xy)
    assert cross(O4 - A2, B2 - A2) > 0


def test_lengths_that_cannot_close_say_which_inequality_fails():
    with pytest.raises(AssemblyError) as info:
        kl.kinematics.assemble(rough_fourbar(lengths=(1.0, 8.0, 2.5)))
    text = str(info.value)
    assert "cannot close" in text
    assert "coupler 8 m > ground 3 + rocker 2.5 + crank 1 = 6.5 m" in text
    assert info.value.link == "coupler" and info.value.gap > 0


def test_the_ground_is_the_frame():
    m = rough_fourbar()
    g = Link("ground", ("O2", "O4"), ground=True, length=3.2)
    with pytest.raises(ModelError, match="the ground's points are the frame and are not moved; they "
                                         "are 3 m apart but its length is 3.2 m"):
        kl.kinematics.assemble(Mechanism(m.name, m.points, (g,) + m.links[1:], m.joints, m.inputs))


def test_a_rough_sketch_is_not_analysed_as_it_is():
    with pytest.raises(kl.kinematics.SketchNotAssembled,
                       match=r"the sketch is not assembled: '\w+' misses .* assemble it "
                             r"first, with kl.kinematics.assemble") as info:
        kl.analyze(rough_fourbar(), 0.5)
    assert isinstance(info.value, ModelError)
    assert info.value.miss in str(info.value) and info.value.miss.endswith(" m")


def test_a_slider_crank_with_an_exact_offset():
    rough = Mechanism(
        "sc", (Point("O2", 0, 0), Point("A", 0.02, 0.98), Point("B", 2.9, 0.45)),
        (Link("ground", ("O2",), ground=True), Link("crank", ("O2", "A"), length=1.0),
         Link("rod", ("A", "B"), length=3.0), Link("slider", ("B",))),
        pins(("O2", ("ground", "crank")), ("A", ("crank", "rod")), ("B", ("rod", "slider")))
        + (Joint("slide", "P", ("ground", "slider"), point="B", axis=(1.0, 0.0), origin="O2",
                 offset=0.5),),
        (Input(joint="jO2"),))
    m = kl.kinematics.assemble(rough).mechanism
    assert m.point("B").y == pytest.approx(0.5, abs=1e-14)
    q = np.linspace(0.0, 2 * math.pi, 13)
    a, b = kl.analyze(m, q), kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0, offset=0.5), q)
    np.testing.assert_allclose(a.slide("slide"), b.slide("slide"), rtol=0, atol=1e-13)


def test_a_watt_sixbar_from_its_lengths():
    """The default Watt six-bar's own distances given as lengths, with its points moved by up
    to a few per cent: the assembly gives back the same linkage."""
    exact = kl.mechanisms.watt6()
    xy = {p.name: np.array(p.xy) for p in exact.points}
    rng = np.random.default_rng(3)
    ground = set(exact.ground.points)
    points = tuple(Point(n, *(v if n in ground else v + rng.uniform(-0.1, 0.1, 2)))
                   for n, v in xy.items())
    links = []
    for link in exact.links:
        if link.ground:
            links.append(link)
            continue
        a, b = link.points[:2]
        e = xy[b] - xy[a]
        L = float(np.hypot(*e))
        local = {p: (float((xy[p] - xy[a]) @ e / L), float(cross(e, xy[p] - xy[a]) / L))
                 for p in link.points[2:]}
        links.append(Link(link.name, link.points, length=L, local=local or None))
    rough = Mechanism("watt", points, tuple(links), exact.joints, exact.inputs)
    m = kl.kinematics.assemble(rough).mechanism
    q = np.radians(np.arange(0.0, 360.0, 10.0)) + kl.kinematics.plan(exact).q_sketch[0]
    a, b = kl.analyze(m, q), kl.analyze(exact, q)
    for link in ("coupler", "rocker", "link5", "output"):
        np.testing.assert_allclose(wrap(a.angle(link) - b.angle(link)), 0.0, atol=1e-12)
    assert closure_residual(a) < 1e-12


def test_a_model_file_drawn_by_eye(tmp_path):
    path = tmp_path / "rough.toml"
    text = (BASE.replace("A = [0, 100]", "A = [5, 98]")
            .replace("B = [261.506227, 247.018682]", "B = [255, 250]")
            .replace('points = ["A", "B"]', 'points = ["A", "B"]\nlength = 300')
            .replace('points = ["O4", "B"]', 'points = ["O4", "B"]\nlength = 250'))
    assert text.count("length = ") == 4              # units.length and the three moving links
    path.write_text(text)
    m = kl.load(path)
    for a, b, length in (("O2", "A", 0.1), ("A", "B", 0.3), ("O4", "B", 0.25)):
        assert dist(m, a, b) == pytest.approx(length, rel=1e-12)
    assert cross(np.subtract(m.point("O4").xy, m.point("A").xy),
                 np.subtract(m.point("B").xy, m.point("A").xy)) > 0        # drawn open
    saved = kl.io.save(kl.io.ModelFile.read(path), tmp_path / "saved.toml")
    again = kl.io.ModelFile.read(saved)
    assert again.mechanism == m and again.assembly is None     # saved assembled, read as is


def test_at_re_poses_on_the_same_branch():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5, branch="crossed")
    moved = fb.at(2.0)
    q = np.linspace(0.0, 2 * math.pi, 25)
    a, b = kl.analyze(fb, q), kl.analyze(moved, q)
    np.testing.assert_allclose(wrap(a.angle("rocker") - b.angle("rocker")), 0.0, atol=1e-12)
    assert kl.kinematics.plan(moved).q_sketch[0] == pytest.approx(2.0, abs=1e-15)
    assert kl.mechanisms.grashof(3.0, 1.0, 3.0, 2.5).kind == "crank-rocker"


def test_at_past_a_change_point_keeps_the_smooth_branch():
    """A parallelogram re-posed at 270 degrees is still a parallelogram (its rocker parallel
    to its crank), and analyses the same from there."""
    fb = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    moved = fb.at(math.radians(270.0))
    A, B = np.array(moved.point("A").xy), np.array(moved.point("B").xy)
    np.testing.assert_allclose(B - A, (100.0, 0.0), atol=1e-12)
    q = np.radians(np.arange(0.0, 361.0, 15.0))
    np.testing.assert_allclose(wrap(kl.analyze(moved, q).angle("rocker") - q), 0.0, atol=1e-9)


def test_at_turns_a_slide_axis_with_its_guide():
    sl = kl.mechanisms.slotted_link(crank=1.0, distance=2.0)
    moved = sl.at(1.0)
    q = np.linspace(-1.0, 2.0, 7)
    a, b = kl.analyze(sl, q), kl.analyze(moved, q)
    np.testing.assert_allclose(a.slide("slot"), b.slide("slot"), rtol=0, atol=1e-13)
    np.testing.assert_allclose(wrap(a.angle("lever") - b.angle("lever")), 0.0, atol=1e-13)


def test_at_a_singular_configuration_is_refused():
    fb = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    with pytest.raises(SingularityError, match="is a singular configuration"):
        fb.at(math.pi)
