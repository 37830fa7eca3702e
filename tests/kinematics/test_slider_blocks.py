"""Links with one point (slider blocks) have an angle: the direction of the axis of the
prismatic joint they slide in, turning with its guide; and omega, alpha, K, L with it."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.model import Input, Joint, Link, Mechanism, Point
from tests.kinematics.checks import wrap

Q = np.radians(np.arange(0.0, 360.0, 5.0)) + 0.01
QD, QDD = 3.0, -2.0


def test_slider_crank_slider_keeps_the_slide_direction():
    """The slide line is fixed along +x: the block does not turn."""
    sc = kl.mechanisms.slider_crank(1.0, 3.0, offset=0.4)
    for q in (Q, 0.7):
        sol = kl.analyze(sc, q=q, qd=QD, qdd=QDD)
        for f in ("angle", "omega", "alpha", "K", "L"):
            value = getattr(sol, f)("slider")
            assert np.shape(value) == np.shape(q)
            np.testing.assert_array_equal(value, 0.0)


def test_slotted_link_block_turns_with_the_lever():
    """Erthal's closed forms: A = atan2(R sin q, R cos q + C), K_A = R cos(A - q) / B, and
    L_A = -[R sin(A - q) (K_A - 1) B + R cos(A - q) K_B] / B^2 with K_B = R sin(A - q)."""
    R, C = 1.0, 2.0
    sol = kl.analyze(kl.mechanisms.slotted_link(R, C), q=Q, qd=QD, qdd=QDD)
    A = np.arctan2(R * np.sin(Q), R * np.cos(Q) + C)
    B = np.hypot(R * np.cos(Q) + C, R * np.sin(Q))
    K = R * np.cos(A - Q) / B
    L = -(R * np.sin(A - Q) * (K - 1) * B + R * np.cos(A - Q) * R * np.sin(A - Q)) / B ** 2
    np.testing.assert_allclose(sol.angle("block"), A, rtol=0, atol=1e-14)
    np.testing.assert_allclose(sol.K("block"), K, rtol=0, atol=1e-14)
    np.testing.assert_allclose(sol.L("block"), L, rtol=0, atol=1e-13)
    np.testing.assert_allclose(sol.omega("block"), K * QD, rtol=0, atol=1e-13)
    np.testing.assert_allclose(sol.alpha("block"), K * QDD + L * QD ** 2, rtol=0, atol=1e-12)


MODEL = """
schema = 1
name = "inclined slider-crank and a swivel block"
units = {length = "mm", angle = "deg"}
# B on the slide line through O2 at 30 deg, 300 mm from A; the arm O4C passes through A
points = {O2 = [0, 0], A = [0, 100], B = [259.807621135, 150], O4 = [200, 0], C = [-200, 200]}
links = [{name = "ground", points = ["O2", "O4"], ground = true},
         {name = "crank", points = ["O2", "A"]}, {name = "rod", points = ["A", "B"]},
         {name = "piston", points = ["B"]}, {name = "swivel", points = ["A"]},
         {name = "arm", points = ["O4", "C"]}]
joints = [{type = "R", links = ["ground", "crank"], point = "O2"},
          {type = "R", links = ["crank", "rod"], point = "A"},
          {type = "R", links = ["rod", "piston"], point = "B"},
          {name = "bore", type = "P", links = ["ground", "piston"], point = "B", axis = 30, origin = "O2"},
          {name = "jS", type = "R", links = ["crank", "swivel"], point = "A"},
          {type = "R", links = ["ground", "arm"], point = "O4"},
          {name = "sleeve", type = "P", links = ["arm", "swivel"], point = "A", axis = [-2, 1]}]
inputs = [{joint = "jO2"}]
"""


def test_one_point_links_of_a_model_file(tmp_path):
    """The piston keeps the 30 deg of its bore; the swivel turns with the arm, along O4 -> A.
    Its omega and alpha against central differences of that direction (h = 1e-4:
    truncation ~h^2, rounding ~1e-16 / h^2)."""
    path = tmp_path / "blocks.toml"
    path.write_text(MODEL)
    m = kl.load(path)
    sol = kl.analyze(m, q=Q, qd=QD, qdd=QDD)
    np.testing.assert_allclose(sol.angle("piston"), np.pi / 6, rtol=0, atol=1e-15)
    for f in ("omega", "alpha", "K", "L"):
        np.testing.assert_array_equal(getattr(sol, f)("piston"), 0.0)

    def direction(s):
        d = s.position("A") - s.position("O4")
        return np.arctan2(d[:, 1], d[:, 0])
    np.testing.assert_allclose(wrap(sol.angle("swivel") - direction(sol)), 0.0, rtol=0, atol=1e-12)
    h = 1e-4
    at = {t: direction(kl.analyze(m, q=Q + QD * t + 0.5 * QDD * t * t)) for t in (-h, 0.0, h)}
    omega = wrap(at[h] - at[-h]) / (2 * h)
    alpha = wrap(at[h] - at[0.0] - (at[0.0] - at[-h])) / h ** 2
    np.testing.assert_allclose(sol.omega("swivel"), omega, rtol=0, atol=1e-6)
    np.testing.assert_allclose(sol.alpha("swivel"), alpha, rtol=0, atol=1e-4)
    np.testing.assert_allclose(sol.omega("swivel"), sol.K("swivel") * QD, rtol=0, atol=1e-13)
    one = kl.analyze(m, q=0.3, qd=QD)
    assert np.shape(one.angle("swivel")) == () and np.shape(one.L("swivel")) == ()


def yoke(order):
    """A Scotch yoke whose yoke is one point: it slides on a rail along x and guides the
    crank pin's block up and down its slot."""
    rail = Joint("rail", "P", ("ground", "yoke"), point="Y", axis=(1.0, 0.0), origin="O")
    slot = Joint("slot", "P", ("yoke", "block"), point="A", axis=(0.0, 1.0), origin="Y")
    return Mechanism(
        name="scotch yoke",
        points=(Point("O", 0, 0), Point("A", 1, 0.5), Point("Y", 1, 0)),
        links=(Link("ground", ("O",), ground=True), Link("crank", ("O", "A")),
               Link("block", ("A",)), Link("yoke", ("Y",))),
        joints=(Joint("jO", "R", ("ground", "crank"), point="O"),
                Joint("jA", "R", ("crank", "block"), point="A"))
        + ((rail, slot) if order == "rail first" else (slot, rail)),
        inputs=(Input(joint="jO"),))


@pytest.mark.parametrize("order", ["rail first", "slot first"])
def test_a_block_takes_the_axis_it_slides_in(order):
    """The yoke slides on the rail (x) and guides the slot (y): its angle is the rail's,
    whichever joint the model lists first (it took the slot's when the slot came first)."""
    sol = kl.analyze(yoke(order), q=Q, qd=QD)
    np.testing.assert_array_equal(sol.angle("yoke"), 0.0)
    np.testing.assert_allclose(sol.angle("block"), np.pi / 2, rtol=0, atol=1e-15)
    np.testing.assert_array_equal(sol.angle("ground"), 0.0)
    # the yoke carries the pin's x: x = |OA| cos(theta_crank)
    r = np.hypot(1.0, 0.5)
    np.testing.assert_allclose(sol.position("Y")[:, 0], r * np.cos(sol.angle("crank")), rtol=0, atol=1e-14)


def test_a_one_point_ground_is_the_frame():
    """The bore at 30 deg sets the piston's angle, not the ground's (it gave the ground
    30 deg too, while the crank's input is measured from +x)."""
    sc = kl.mechanisms.slider_crank(1.0, 3.0)
    bore = Joint("slide", "P", ("ground", "slider"), point="B", axis=(np.sqrt(3) / 2, 0.5),
                 origin="O2")
    pts = (Point("O2", 0.0, 0.0), Point("A", 0.0, 1.0), Point("B", 1.5 * np.sqrt(3), 1.5))
    m = Mechanism("inclined", pts, sc.links, sc.joints[:3] + (bore,), sc.inputs)
    sol = kl.analyze(m, q=Q)
    np.testing.assert_array_equal(sol.angle("ground"), 0.0)
    np.testing.assert_allclose(sol.angle("slider"), np.pi / 6, rtol=0, atol=1e-15)
    np.testing.assert_allclose(wrap(sol.angle("crank") - sol.angle("ground") - Q), 0.0, rtol=0, atol=1e-14)
