"""The constructions step by step, as data (kinelab.kinematics.tangent_construction,
velocity_image, kennedy_steps), each checked against an independent computation: the exact
or the numerical derivative, the engine's velocities, the centres solved from the
velocities."""
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError

ROOT = Path(__file__).resolve().parents[2]


# -- graphical differentiation ------------------------------------------------------------------
def test_chord_on_even_samples_is_within_its_truncation_error():
    # y = A sin(w t): the centred chord's error is |y'''| w^2 / 6 at most, w the half-chord
    A, w = 2.0, 5.0
    t = np.linspace(0.0, 1.2, 241)
    tc = kl.kinematics.tangent_construction(t, A * np.sin(w * t), points=11)
    half = tc.every * (t[1] - t[0])
    exact = A * w * np.cos(w * t[tc.index])
    bound = A * w ** 3 * half ** 2 / 6 * (1 + 1e-9) + 1e-12
    assert np.all(np.abs(tc.derivative - exact) <= bound)
    assert np.max(np.abs(tc.derivative - exact)) > 0.3 * bound      # and the bound is tight


def test_chord_converges_at_second_order_on_a_slider_crank_stroke():
    t = np.linspace(0.0, 2 * np.pi / 10.0, 1201)
    sol = kl.analyze(kl.mechanisms.slider_crank(crank=0.1, rod=0.3), q=10.0 * t, qd=10.0)
    s, v = sol.slide("slide"), sol.slide_velocity("slide")
    coarse = kl.kinematics.tangent_construction(t, s, points=11)       # every 100th sample
    fine = kl.kinematics.tangent_construction(t, s, points=23)         # every 50th
    assert coarse.every == 2 * fine.every
    common = np.intersect1d(coarse.index, fine.index)
    e_coarse = np.abs(coarse.derivative - v[coarse.index])[np.isin(coarse.index, common)]
    e_fine = np.abs(fine.derivative - v[fine.index])[np.isin(fine.index, common)]
    ratio = np.max(e_coarse) / np.max(e_fine)
    assert 3.5 < ratio < 4.5


def test_construction_agrees_with_the_numerical_derivative():
    t = np.linspace(0.0, 2 * np.pi / 10.0, 601)
    sol = kl.analyze(kl.mechanisms.slider_crank(crank=0.1, rod=0.3), q=10.0 * t, qd=10.0)
    s = sol.slide("slide")
    d = kl.solvers.differentiate(t, s)
    tc = kl.kinematics.tangent_construction(t, s, points=29)
    half = tc.every * (t[1] - t[0])
    # |s'''| <= crank w^3 (1 + 4 crank / rod) bounds the chord's truncation error
    third = 0.1 * 10.0 ** 3 * (1 + 4 * 0.1 / 0.3)
    bound = third * half ** 2 / 6 + d.velocity_error[tc.index]
    assert np.all(np.abs(tc.derivative - d.velocity[tc.index]) <= bound)
    fitted = kl.kinematics.tangent_construction(t, s, points=29, method="fitted")
    np.testing.assert_allclose(fitted.derivative, d.velocity[fitted.index], rtol=1e-12, atol=0)
    assert np.all(np.isnan(fitted.neighbours))


def test_uneven_samples_take_the_three_point_parabola():
    rng = np.random.default_rng(3)
    x = np.sort(rng.uniform(0.0, 2.0, 80))
    tc = kl.kinematics.tangent_construction(x, 3 * x ** 2 - 2 * x + 1, points=9)
    np.testing.assert_allclose(tc.derivative, 6 * x[tc.index] - 2, rtol=0, atol=1e-10)
    # a cubic: the three-point formula overestimates by y''' h1 h2 / 6 = h1 h2 (y''' = 6)
    tc = kl.kinematics.tangent_construction(x, x ** 3, points=9)
    h1 = x[tc.index] - x[tc.index - tc.every]
    h2 = x[tc.index + tc.every] - x[tc.index]
    np.testing.assert_allclose(tc.derivative - 3 * x[tc.index] ** 2, h1 * h2,
                               rtol=1e-8, atol=1e-12)


def test_the_geometry_of_the_construction():
    t = np.linspace(1.0, 3.0, 101)
    y = np.exp(-t) * np.sin(4 * t)
    tc = kl.kinematics.tangent_construction(t, y, points=7)
    H = tc.polar_distance
    # the notes' H: twice the interval between chosen points, the width BD of the chords
    assert H == pytest.approx(2 * tc.every * 0.02, rel=1e-12)
    np.testing.assert_allclose(tc.pole, [1.0 - H, 0.0])
    np.testing.assert_allclose(tc.origin, [1.0, 0.0])
    B, C, D = (tc.triangles[:, k] for k in range(3))
    np.testing.assert_allclose(D[:, 0] - B[:, 0], H)                    # BD = H, horizontal
    np.testing.assert_allclose(D[:, 1], B[:, 1])
    np.testing.assert_allclose(C[:, 1] - D[:, 1], tc.intercepts, atol=1e-15)   # CD
    np.testing.assert_allclose(0.5 * (B + C), tc.points)                # centred on A
    ray = tc.rays[:, 1] - tc.rays[:, 0]
    tangent = C - B
    assert np.allclose(ray[:, 0] * tangent[:, 1] - ray[:, 1] * tangent[:, 0], 0.0, atol=1e-14)
    np.testing.assert_allclose(tc.rays[:, 0], np.broadcast_to(tc.pole, (7, 2)))
    np.testing.assert_allclose(tc.rays[:, 1, 0], 1.0)                   # on the ordinate axis
    np.testing.assert_allclose(tc.derived[:, 1], tc.rays[:, 1, 1])
    np.testing.assert_allclose(tc.derived[:, 0], tc.points[:, 0])
    np.testing.assert_allclose(tc.derivative, tc.intercepts / H)
    # the default H makes each intercept the chord's rise
    left, right = tc.neighbours[:, 0], tc.neighbours[:, 1]
    np.testing.assert_allclose(tc.intercepts, right[:, 1] - left[:, 1], atol=1e-15)
    # another polar distance scales the intercepts, not the derivative
    other = kl.kinematics.tangent_construction(t, y, points=7, polar_distance=0.5)
    np.testing.assert_allclose(other.intercepts, 0.5 * tc.slope)
    np.testing.assert_allclose(other.derivative, tc.derivative, rtol=1e-12)


@pytest.mark.parametrize("kwargs, match", [
    (dict(points=0), r"points: expected a whole number of points, at least 1, got 0"),
    (dict(points=True), r"points: expected a whole number"),
    (dict(points=2.5), r"points: expected a whole number"),
    (dict(points=20), r"points: expected at most 8 points for 10 samples"),
    (dict(points=3, polar_distance=0.0), r"polar_distance: expected a positive number"),
    (dict(points=3, polar_distance=float("nan")), r"polar_distance: expected a positive number"),
    (dict(points=3, polar_distance="1"), r"polar_distance: expected a positive number"),
    (dict(method="chords"), r"method: expected 'chord' or 'fitted', got 'chords'"),
])
def test_tangent_construction_refuses(kwargs, match):
    x = np.arange(10.0)
    with pytest.raises(ModelError, match=match):
        kl.kinematics.tangent_construction(x, x ** 2, **kwargs)


def test_tangent_construction_refuses_bad_samples():
    with pytest.raises(ModelError, match=r"x: expected at least 3 samples .*, got 2"):
        kl.kinematics.tangent_construction([0.0, 1.0], [0.0, 1.0])
    assert len(kl.kinematics.tangent_construction(np.arange(5.0), np.arange(5.0)).index) == 3
    with pytest.raises(ModelError, match=r"x\[2\]: expected abscissae that increase"):
        kl.kinematics.tangent_construction([0.0, 1.0, 1.0, 2.0], [0.0, 1.0, 2.0, 3.0], points=1)
    with pytest.raises(ModelError, match=r"y: expected as many samples as x \(4\), got 3"):
        kl.kinematics.tangent_construction([0.0, 1.0, 2.0, 3.0], [0.0, 1.0, 2.0], points=1)
    with pytest.raises(ModelError, match=r"y\[1\]: expected a finite number"):
        kl.kinematics.tangent_construction([0.0, 1.0, 2.0], [0.0, np.nan, 2.0], points=1)


# -- the velocity image -------------------------------------------------------------------------
def _polygon_scale(sol, i=0):
    vp = kl.kinematics.velocity_polygon(sol, i)
    return max(float(np.hypot(*v)) for v in vp.vertices.values())


@pytest.mark.parametrize("deg", [0.0, 37.0, 90.0, 200.0, 311.0])
def test_velocity_image_gives_the_engine_velocity(deg):
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    sol = kl.analyze(fb, q=np.radians(deg), qd=7.0)
    vi = kl.kinematics.velocity_image(sol, "coupler")
    scale = _polygon_scale(sol)
    assert np.max(np.abs(vi.vertices["P"] - sol.velocity("P"))) <= 1e-9 * scale
    np.testing.assert_allclose(vi.vertices["P"], vi.velocities["P"], rtol=0, atol=1e-9 * scale)
    # the similarity is i omega: a quarter turn in the sense of omega, scaled by |omega|
    assert abs(vi.ratio - 1j * sol.omega("coupler")) <= 1e-9 * abs(sol.omega("coupler"))

    # same orientation: abc turns the same way as ABC
    def turn(p, q, r):
        u, v = q - p, r - p
        return np.sign(u[0] * v[1] - u[1] * v[0])
    P = vi.positions
    V = vi.vertices
    assert turn(V["A"], V["B"], V["P"]) == turn(P["A"], P["B"], P["P"])
    # known from the other side: B and P known, A placed
    vi2 = kl.kinematics.velocity_image(sol, "coupler", known=("B", "P"))
    assert vi2.points == ("A",)
    assert np.max(np.abs(vi2.vertices["A"] - sol.velocity("A"))) <= 1e-9 * scale


def _example(name, samples=7):
    """An example model analysed over a few samples of its input range, at unit speed."""
    mf = kl.io.ModelFile.read(ROOT / "examples" / f"{name}.toml")
    m = mf.mechanism
    lo, hi = m.inputs[0].range or (0.0, 2 * np.pi)
    sol = kl.analyze(m, q=np.linspace(lo, hi, samples + 1)[:-1], qd=1.0)
    return m, sol


@pytest.mark.parametrize("name", ["engine", "stephenson6", "jansen", "crank_rocker"])
def test_velocity_image_of_every_example_link(name):
    m, sol = _example(name)
    links = [lk.name for lk in m.links if not lk.ground and len(lk.points) >= 3]
    assert links
    good = np.flatnonzero(np.asarray(sol.assembled) & ~np.asarray(sol.singular))
    assert good.size
    for i in good:
        scale = _polygon_scale(sol, int(i))
        for link in links:
            vi = kl.kinematics.velocity_image(sol, link, sample=int(i))
            for c in vi.points:
                assert np.max(np.abs(vi.vertices[c] - sol.velocity(c)[i])) <= 1e-9 * scale


@pytest.mark.parametrize("link, known, match", [
    ("ground", None, r"link: expected a moving link, got the ground 'ground'"),
    ("crank", None, r"link: expected a link with at least three points, got 'crank'"),
    ("coupla", None, r"link: expected one of .*did you mean 'coupler'"),
    ("coupler", ("A", "A"), r"known: expected two different points of 'coupler'"),
    ("coupler", ("A", "O2"), r"known: expected two different points of 'coupler'"),
])
def test_velocity_image_refuses(link, known, match):
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    sol = kl.analyze(fb, q=0.5, qd=1.0)
    with pytest.raises(ModelError, match=match):
        kl.kinematics.velocity_image(sol, link, known=known)


def test_velocity_image_refuses_a_singular_sample():
    # a crank-rocker with crank + coupler = ground + rocker... here a parallelogram folding
    # at 0: crank and coupler in line with the ground is a change point
    fb = kl.mechanisms.fourbar(2.0, 1.0, 2.0, 1.0, coupler_point=(1.0, 0.5))
    sol = kl.analyze(fb, q=np.array([0.3, 0.0]), qd=1.0)
    assert bool(np.asarray(sol.singular)[1]) or not bool(np.asarray(sol.assembled)[1])
    with pytest.raises(kl.errors.KinelabError):
        kl.kinematics.velocity_image(sol, "coupler", sample=1)
    kl.kinematics.velocity_image(sol, "coupler", sample=0)


# -- Kennedy's construction ---------------------------------------------------------------------
def _distance_to_line(point, line):
    r = point - line.point
    return abs(r[0] * line.direction[1] - r[1] * line.direction[0])


@pytest.mark.parametrize("name, at", [("crank_rocker", 30.0), ("slotted_link", 60.0),
                                      ("stephenson6", 20.0), ("engine", 30.0),
                                      ("inverted_slider_crank", 50.0)])
def test_each_step_meets_on_its_two_lines_at_the_velocity_centre(name, at):
    mf = kl.io.ModelFile.read(ROOT / "examples" / f"{name}.toml")
    m = mf.mechanism
    sol = kl.analyze(m, q=np.radians(at))
    assert bool(np.all(sol.assembled)) and not bool(np.any(sol.singular))
    ks = kl.kinematics.kennedy_steps(sol)
    ic = kl.kinematics.instant_centers(sol)
    size = float(np.ptp(np.array([p.xy for p in m.points]), axis=0).max())
    n = len(m.links)
    assert len(ks.primary) + len(ks.steps) + len(ks.from_velocities) == n * (n - 1) // 2
    assert [s.number for s in ks.steps] == list(range(1, len(ks.steps) + 1))
    known = list(ks.primary)
    for s in ks.steps:
        a, b = s.pair
        k, l = s.thirds
        # each line is through the centres of a, b with a third link: known before this step
        for line, third in zip(s.lines, (k, l)):
            assert all(p in known for p in line.through)
            assert {x for p in line.through for x in p} == {a, b, third}
        known.append(s.pair)
        assert list(s.known) == known
        c = ic[s.pair]
        assert bool(c.at_infinity) == s.at_infinity
        if s.at_infinity:
            assert abs(abs(np.dot(c.direction, s.direction)) - 1) <= 1e-9
            continue
        np.testing.assert_allclose(s.position, c.position, rtol=0, atol=1e-9 * size)
        for line in s.lines:
            if np.all(np.isfinite(line.direction)):
                assert _distance_to_line(s.position, line) <= 1e-9 * size


def test_kennedy_lines_are_the_notes_for_the_four_bar():
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    ks = kl.kinematics.kennedy_steps(kl.analyze(fb, q=np.radians(60.0)))
    assert [ks.label(p) for p in ks.primary] == ["O12", "O23", "O34", "O14"]
    assert [[[ks.label(p) for p in line.through] for line in s.lines] for s in ks.steps] == [
        [["O12", "O23"], ["O14", "O34"]], [["O12", "O14"], ["O23", "O34"]]]
    # O13 is where the crank's line meets the rocker's; O24 on the line of the pivots
    assert abs(ks.steps[1].position[1]) <= 1e-12


def test_kennedy_steps_sample_of_a_sweep():
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    sweep = kl.analyze(fb, q=np.radians([10.0, 60.0, 120.0]))
    one = kl.kinematics.kennedy_steps(kl.analyze(fb, q=np.radians(120.0)))
    ks = kl.kinematics.kennedy_steps(sweep, sample=-1)
    assert ks.sample == 2
    for s, t in zip(ks.steps, one.steps):
        np.testing.assert_allclose(s.position, t.position, rtol=1e-12, atol=1e-12)
    with pytest.raises(ModelError, match=r"sample: expected 0 to 2"):
        kl.kinematics.kennedy_steps(sweep, sample=3)
