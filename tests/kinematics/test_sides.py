"""Links whose extra points are given by their sides, assembled and analysed: the same
places as the equivalent local places, and Jansen's linkage, written with lengths and sides
only, keeping every side over a full turn of its crank.

The checks measure distances and sides on the engine's output points; nothing here uses
kinelab's law of cosines."""
import math
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.kinematics import assemble
from tests.kinematics.checks import closure_residual

ROOT = Path(__file__).resolve().parents[2]
CRANK_ROCKER = (ROOT / "examples" / "crank_rocker.toml").read_text()
JANSEN = ROOT / "examples" / "jansen.toml"
LOCAL = 'local = { P = [150, 100] }'


def cross(o, p, q):
    """(p - o) x (q - o), for points of shape (..., 2): > 0 when q is left of o -> p."""
    return (p[..., 0] - o[..., 0]) * (q[..., 1] - o[..., 1]) - (p[..., 1] - o[..., 1]) * (q[..., 0] - o[..., 0])


def test_a_coupler_point_by_its_sides_is_where_its_local_place_puts_it():
    """The crank-rocker example's P = [150, 100] on A -> B (300 mm), written instead as
    180.27756377319946 mm (sqrt(150² + 100²)) from A and from B (sqrt(150² + 100²) too: P is
    over the middle of A-B), left of A -> B."""
    d = math.hypot(150, 100)
    assert repr(d) == "180.27756377319946"
    by_local = kl.io.from_toml(CRANK_ROCKER)
    by_sides = kl.io.from_toml(CRANK_ROCKER.replace(LOCAL, f'sides = {{ P = {{ A = {d!r}, B = {d!r}, side = "left" }} }}'))
    assert by_sides.link("coupler").sides and not by_sides.link("coupler").local
    # the same assembly from the same rough sketch, to the assembler's tolerance
    for p in by_local.points:
        assert by_sides.point(p.name).xy == pytest.approx(p.xy, rel=0, abs=1e-14)
    q = np.radians(np.arange(0.0, 360.0, 1.0))
    a, b = kl.analyze(by_local, q, qd=10.0), kl.analyze(by_sides, q, qd=10.0)
    np.testing.assert_allclose(b.position("P"), a.position("P"), rtol=0, atol=1e-13)
    np.testing.assert_allclose(b.acceleration("P"), a.acceleration("P"), rtol=1e-11, atol=1e-11)
    # and the place is the one written: 150 mm along A -> B, 100 mm to its left, m
    A, B, P = (b.position(n) for n in "ABP")
    e = (B - A) / 0.3
    np.testing.assert_allclose(np.einsum("ij,ij->i", P - A, e), 0.15, rtol=0, atol=1e-13)
    np.testing.assert_allclose(cross(A, A + e, P), 0.1, rtol=0, atol=1e-13)


def test_the_right_side_is_the_mirror_image_across_the_line_of_the_two():
    d = math.hypot(150, 100)
    right = kl.io.from_toml(CRANK_ROCKER.replace(LOCAL, f'sides = {{ P = {{ B = {d!r}, A = {d!r}, side = "right" }} }}')
                            .replace("P = [82, 261]", "P = [100, 40]"))
    sol = kl.analyze(right, np.radians([0.0, 90.0, 200.0]))
    A, B, P = (sol.position(n) for n in "ABP")
    np.testing.assert_allclose(cross(A, B, P) / 0.3, -0.1, rtol=0, atol=1e-13)   # m right of A -> B


# Jansen's linkage, by the letters he gives its lengths (cm)
HOLY = dict(a=38.0, b=41.5, c=39.3, d=40.1, e=55.8, f=39.4, g=36.7, h=65.7, i=49.0, j=50.0,
            k=61.9, l=7.8, m=15.0)
# every pair of points of one link and the letter of its distance
PAIRS = {("O", "A"): "m", ("A", "C"): "j", ("A", "D"): "k", ("B", "C"): "b", ("B", "E"): "d",
         ("C", "E"): "e", ("B", "D"): "c", ("E", "F"): "f", ("D", "F"): "g", ("D", "G"): "i",
         ("F", "G"): "h"}


@pytest.fixture(scope="module")
def jansen():
    mf = kl.io.ModelFile.read(JANSEN)
    return mf, mf.analyze(721)


def test_jansen_is_written_with_lengths_and_sides_only(jansen):
    mf, _ = jansen
    text = JANSEN.read_text()
    assert "local" not in text.split("[[links]]", 1)[1]
    m = mf.mechanism
    assert [link.name for link in m.links if link.sides] == ["top", "leg"]
    assert kl.structure.mobility(m).exact == 1
    # the ground is drawn exactly: O at the crank's centre, B a to the left and l below
    assert m.point("B").xy == pytest.approx((-0.38, -0.078), abs=1e-15)


def test_jansen_keeps_every_side_over_a_full_turn(jansen):
    mf, sol = jansen
    assert sol.N == 721 and np.all(sol.assembled) and not np.any(sol.singular)
    assert np.ptp(sol.q) == pytest.approx(2 * math.pi)
    for (p1, p2), letter in PAIRS.items():
        d = np.linalg.norm(sol.position(p1) - sol.position(p2), axis=-1)
        np.testing.assert_allclose(d, HOLY[letter] / 100, rtol=1e-12, err_msg=f"{p1}-{p2} ({letter})")
    # each triangle stays on the side its sides say: E left of B -> C, G left of D -> F
    B, C, E, D, F, G = (sol.position(p) for p in "BCEDFG")
    assert np.all(cross(B, C, E) > 0) and np.all(cross(D, F, G) > 0)
    assert closure_residual(sol) < 1e-12


def test_jansens_foot_walks(jansen):
    """The foot's path, a check that no triangle is mirrored: for about 0.43 of the crank's
    turn the foot stays within 1 cm of its lowest point (the stride, 57 cm long), and it
    lifts 22 cm on the way back (a mirrored triangle makes no such path)."""
    _, sol = jansen
    G = sol.position("G") * 100                                   # cm
    low = G[:, 1] < G[:, 1].min() + 1.0                           # within 1 cm of the ground
    assert 0.3 < low.mean() < 0.6
    assert 15 < np.ptp(G[:, 1]) < 30 and 50 < np.ptp(G[low, 0]) < 80


@pytest.mark.parametrize("scale", [1e-4, 1.0, 1e4])
def test_jansen_by_its_sides_is_scale_free(jansen, scale):
    """Every point, length and side times the scale: the same angles, flags and statuses."""
    mf, sol = jansen
    data = mf.mechanism.to_dict()
    data["points"] = {p: [c * scale for c in xy] for p, xy in data["points"].items()}
    for link in data["links"]:
        if "length" in link:
            link["length"] *= scale
        for spec in link.get("sides", {}).values():
            spec.update({k: v * scale for k, v in spec.items() if k != "side"})
    m = kl.model.Mechanism.from_dict(data)
    s = kl.analyze(m, sol.q[:, 0])
    for link in ("top", "leg", "thigh"):
        np.testing.assert_allclose(s.angle(link), sol.angle(link), rtol=0, atol=1e-10)
    np.testing.assert_array_equal(s.singular, sol.singular)
    np.testing.assert_allclose(s.position("G") / scale, sol.position("G"), rtol=0, atol=1e-10)


def test_a_rough_jansen_assembles_to_its_sides(jansen):
    """The file's sketch is by eye (G 2.6 mm off): assembled, every side holds exactly."""
    mf, _ = jansen
    assert mf.assembly is not None and max(mf.assembly.moved.values()) > 1e-3
    m = mf.mechanism
    for (p1, p2), letter in PAIRS.items():
        assert math.dist(m.point(p1).xy, m.point(p2).xy) == pytest.approx(HOLY[letter] / 100, rel=1e-12)
    again = assemble(m)
    assert again.largest_move < 1e-13
