"""Instant centres by the notes' construction (Kennedy's theorem on the circle diagram),
centrodes and the angular-velocity-ratio theorem, checked against the centres solved from
the velocities, the engine's angular velocities, the projections theorem and the rolling of
the centrodes (Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades*,
§4.6.3, §4.7.1)."""
import itertools

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError, SingularityError
from tests.kinematics.test_polygons import MECHANISMS, QD, H, regular

K = kl.kinematics
Q = np.radians(np.arange(0.0, 360.0, 5.0)) + 0.013


def sweep(name, q=Q):
    return kl.analyze(MECHANISMS[name](), q=q, qd=QD, at_singular="flag", unreachable="mask")


def collinearity(p, q, r):
    """|sin| of the angle at p between pq and pr."""
    a, b = q - p, r - p
    return np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]) / (
        np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))


@pytest.mark.parametrize("name", MECHANISMS)
def test_construction_agrees_with_the_velocities(name):
    """Every centre found from the joints by Kennedy's theorem is the point of equal
    velocity that instant_centers solves for, finite or at infinity."""
    sol = sweep(name)
    ok = regular(sol)
    kc = K.kennedy_construction(sol)
    ic = K.instant_centers(sol)
    n = len(sol.link_names)
    assert len(kc.centers) == n * (n - 1) // 2
    assert len(kc.primary) + len(kc.steps) + len(kc.from_velocities) == n * (n - 1) // 2
    size = 5.0
    for pair in itertools.combinations(sol.link_names, 2):
        a, b = kc.centers[pair], ic[pair]
        np.testing.assert_array_equal(a.at_infinity[ok], b.at_infinity[ok])
        fin = ok & ~b.at_infinity
        np.testing.assert_allclose(a.position[fin], b.position[fin], rtol=1e-9, atol=1e-9 * size)
        inf = ok & b.at_infinity
        cross = a.direction[inf, 0] * b.direction[inf, 1] - a.direction[inf, 1] * b.direction[inf, 0]
        assert np.all(np.abs(cross) < 1e-9), pair


@pytest.mark.parametrize("name", MECHANISMS)
def test_kennedy_collinearity_of_the_construction(name):
    """Any three links' centres lie on one line (or the finite two on a line along the
    direction of the one at infinity)."""
    sol = sweep(name)
    ok = regular(sol)
    c = K.kennedy_construction(sol).centers
    for a, b, d in itertools.combinations(sol.link_names, 3):
        three = [c[a, b], c[a, d], c[b, d]]
        inf = np.array([x.at_infinity for x in three])
        rows = ok & (inf.sum(axis=0) == 0)
        p = [x.position[rows] for x in three]
        spread = np.min([np.linalg.norm(p[i] - p[j], axis=1) for i, j in ((0, 1), (0, 2), (1, 2))], axis=0)
        keep = spread > 1e-6
        assert np.all(collinearity(*(x[keep] for x in p)) < 1e-8), (a, b, d)
        for k in range(3):
            rows = ok & inf[k] & (inf.sum(axis=0) == 1)
            f = [three[i].position[rows] for i in range(3) if i != k]
            line = f[1] - f[0]
            length = np.linalg.norm(line, axis=1)
            u = three[k].direction[rows]
            keep = length > 1e-6
            cross = np.abs(line[:, 0] * u[:, 1] - line[:, 1] * u[:, 0])[keep] / length[keep]
            assert np.all(cross < 1e-8), (a, b, d)


def test_fourbar_order_and_labels_are_the_notes():
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=Q)
    kc = K.kennedy_construction(sol)
    assert kc.numbers == {"ground": 1, "crank": 2, "coupler": 3, "rocker": 4}
    assert [kc.label(p) for p in kc.primary] == ["O12", "O23", "O34", "O14"]
    assert [kc.label(s.pair) for s in kc.steps] == ["O13", "O24"]
    assert kc.from_velocities == ()
    # O13 on O12-O23 and O14-O34: the lines of the crank and the rocker, met by hand
    O2, A, B, O4 = (sol.position(p) for p in ("O2", "A", "B", "O4"))
    d1, d2 = A - O2, B - O4
    s = ((O4 - O2)[:, 0] * d2[:, 1] - (O4 - O2)[:, 1] * d2[:, 0]) / (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    np.testing.assert_allclose(kc.steps[0].center.position, O2 + s[:, None] * d1, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("name", MECHANISMS)
def test_velocity_ratio_theorem_against_the_engine(name):
    """omega_j / omega_i from the centres, for every pair of moving links and every
    reference link, is the engine's ratio to 1e-10."""
    sol = sweep(name)
    ok = regular(sol)
    sol = kl.analyze(sol.mechanism, q=Q[ok], qd=QD)
    links = sol.link_names
    checked = 0
    for i, j, r in itertools.permutations(links, 3):
        wi, wj, wr = (sol.omega(x) for x in (i, j, r))
        rows = np.abs(wi - wr) > 1e-6 * QD
        if not rows.all():
            continue
        ratio = K.velocity_ratio(sol, i, j, reference=r)
        expected = (wj - wr) / (wi - wr)
        np.testing.assert_allclose(ratio, expected, rtol=1e-10, atol=1e-10)
        checked += 1
    assert checked >= 3


@pytest.mark.parametrize("name", MECHANISMS)
def test_projections_theorem(name):
    """Two points of a rigid link have velocities of equal projection on the line joining
    them (Flores & Claro, §4.5): checked on every pair of points of every link."""
    sol = sweep(name)
    ok = regular(sol)
    for link in sol.mechanism.links:
        for p, r in itertools.combinations(link.points, 2):
            d = sol.position(p) - sol.position(r)
            d = d / np.linalg.norm(d, axis=1)[:, None]
            proj = np.einsum("ij,ij->i", sol.velocity(p) - sol.velocity(r), d)
            assert np.max(np.abs(proj[ok])) < 1e-11 * max(1.0, np.nanmax(np.abs(sol.velocity(p))))


@pytest.mark.parametrize("name, link", [("fourbar", "coupler"), ("offset_slider_crank", "rod"),
                                        ("watt6", "coupler"), ("slotted_link", "lever")])
def test_centrodes_roll_without_slipping(name, link):
    """The fixed centrode is the path of the centre on the ground; the moving one, the same
    points in the link's frame.  The centre has no velocity as a point of the link, and
    rolling without slipping makes the two centrodes equally long between any samples."""
    m = MECHANISMS[name]()
    if link not in m.link_names:
        link = [lk for lk in m.link_names if lk != m.ground.name][-1]
    q = np.linspace(0.4, 1.4, 2001)
    sol = kl.analyze(m, q=q, qd=QD)
    c = K.centrodes(sol, link)
    assert c.fixed.shape == c.moving.shape == (len(q), 2)
    assert c.defined.all()
    first = m.link(link).points[0]
    w = sol.omega(link)
    r = c.fixed - sol.position(first)
    v = sol.velocity(first) + w[:, None] * np.stack([-r[:, 1], r[:, 0]], axis=1)
    np.testing.assert_allclose(v, 0.0, atol=1e-9 * QD * 5)
    # the moving centrode placed back on the link at each sample is the fixed one
    th = sol.angle(link)
    back = sol.position(first) + np.stack([np.cos(th) * c.moving[:, 0] - np.sin(th) * c.moving[:, 1],
                                           np.sin(th) * c.moving[:, 0] + np.cos(th) * c.moving[:, 1]], axis=1)
    np.testing.assert_allclose(back, c.fixed, atol=1e-12 * 10)
    arc_fixed = np.cumsum(np.linalg.norm(np.diff(c.fixed, axis=0), axis=1))
    arc_moving = np.cumsum(np.linalg.norm(np.diff(c.moving, axis=0), axis=1))
    np.testing.assert_allclose(arc_moving, arc_fixed, rtol=1e-4, atol=1e-6)


def test_centrodes_gaps_where_the_link_translates():
    fb = kl.mechanisms.fourbar(ground=2.0, crank=1.0, coupler=2.0, rocker=1.0)
    sol = kl.analyze(fb, q=np.array([0.3, np.pi / 2, 1.2]))       # a parallelogram
    c = K.centrodes(sol, "coupler")
    assert c.at_infinity.all() and not c.defined.any() and np.isnan(c.fixed).all()


# -- bad input ---------------------------------------------------------------------------
def test_bad_links():
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=Q)
    with pytest.raises(ModelError, match=r"link: expected one of .*got 'coupling'.*did you mean 'coupler'"):
        K.centrodes(sol, "coupling")
    with pytest.raises(ModelError, match=r"expected a moving link, got the ground"):
        K.centrodes(sol, "ground")
    with pytest.raises(ModelError, match=r"expected three different links"):
        K.velocity_ratio(sol, "crank", "crank")
    with pytest.raises(ModelError, match=r"link_j: expected one of"):
        K.velocity_ratio(sol, "crank", "rockr")


def test_velocity_ratio_refuses_infinite_ratios_and_singular_samples():
    sc = kl.mechanisms.slider_crank(1.0, 3.0)
    sol = kl.analyze(sc, q=Q)
    with pytest.raises(SingularityError, match=r"'slider' translates relative to 'ground' at 72 "
                                               r"sample\(s\).*swap link_i and link_j"):
        K.velocity_ratio(sol, "slider", "crank")
    np.testing.assert_array_equal(K.velocity_ratio(sol, "crank", "slider"), 0.0)
    sc = kl.mechanisms.slider_crank(1.0, 1.0)
    sol = kl.analyze(sc, q=np.array([0.3, np.pi / 2]), at_singular="flag")
    with pytest.raises(SingularityError, match=r"the first sample 1 at q = 1.5708 rad"):
        K.velocity_ratio(sol, "crank", "rod")
