"""Acceleration differences, relative accelerations and the velocity and acceleration
polygons, checked against the engine's accelerations, finite differences of its positions
and velocities, and the similarity of each link's image (Flores & Claro, *Cinemática de
Mecanismos — 4. Análise de Velocidades*, §4.6; Badan (IFG), *Análise de aceleração*)."""
import itertools

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import AssemblyError, ModelError, SingularityError
from tests.kinematics.test_guide_point import swivel_guide

K = kl.kinematics
Q = np.radians(np.arange(0.0, 360.0, 5.0)) + 0.013
QD, QDD = 7.0, -2.0
H = 1e-5        # input step of the central differences, rad

MECHANISMS = {
    "fourbar": lambda: kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)),
    "offset_slider_crank": lambda: kl.mechanisms.slider_crank(1.0, 3.0, offset=0.4),
    "slotted_link": lambda: kl.mechanisms.slotted_link(1.0, 2.0),
    "inverted_slider_crank": lambda: kl.mechanisms.inverted_slider_crank(2.0, 1.0, offset=0.3),
    "whitworth": lambda: kl.mechanisms.whitworth(1.0, 0.5, 1.0, 2.0),
    "swivel_guide": swivel_guide,
    "watt6": kl.mechanisms.watt6,
    "stephenson6": kl.mechanisms.stephenson6,
}


def sweep(name, q=Q):
    m = MECHANISMS[name]()
    sol = kl.analyze(m, q=q, qd=QD, qdd=QDD, at_singular="flag", unreachable="mask")
    return m, sol


def regular(sol):
    return sol.assembled & ~sol.singular


def scale_of(a):
    return max(1.0, float(np.nanmax(np.abs(a))))


def neighbours(m, q):
    """Solutions at q - H and q + H, at constant input speed: their velocities' central
    difference is the acceleration at q (with qdd = 0)."""
    return [kl.analyze(m, q=q + s * H, qd=QD, qdd=0.0, at_singular="flag", unreachable="mask")
            for s in (-1.0, 1.0)]


@pytest.mark.parametrize("name", MECHANISMS)
def test_difference_parts_sum_to_the_engine_accelerations(name):
    """a_R + A^n_PR + A^t_PR is the engine's a_P for every ordered pair of points of every
    link, over the whole sweep at once (1e-12 of the largest acceleration)."""
    m, sol = sweep(name)
    ok = regular(sol)
    assert ok.sum() > len(Q) // 2
    for link in m.links:
        for p, r in itertools.permutations(link.points, 2):
            d = K.acceleration_difference(sol, p, r, link=link.name)
            assert d.normal.shape == d.tangential.shape == d.total.shape == (len(Q), 2)
            a_p = sol.acceleration(p)
            rebuilt = sol.acceleration(r) + d.normal + d.tangential
            assert np.max(np.abs(rebuilt - a_p)[ok]) <= 1e-12 * scale_of(a_p[ok]), (link.name, p, r)


@pytest.mark.parametrize("name", ["fourbar", "offset_slider_crank", "watt6"])
def test_difference_parts_against_finite_differences(name):
    """The normal part is omega^2 |PR| towards R and the tangential part alpha |PR| across
    PR, with omega and alpha from central differences of the engine's link angles, and
    their sum is the central difference of the velocity difference (qdd = 0)."""
    m = MECHANISMS[name]()
    sol = kl.analyze(m, q=Q, qd=QD, qdd=0.0)
    lo, hi = neighbours(m, Q)
    for link in (lk for lk in m.links if not lk.ground and len(lk.points) > 1):
        th = [np.unwrap(s.angle(link.name)) for s in (lo, hi)]
        omega = (th[1] - th[0]) / (2 * H) * QD
        for p, r in itertools.permutations(link.points, 2):
            d = K.acceleration_difference(sol, p, r)
            rv = sol.position(p) - sol.position(r)
            dist = np.linalg.norm(rv, axis=1)
            np.testing.assert_allclose(np.linalg.norm(d.normal, axis=1), omega ** 2 * dist,
                                       rtol=1e-6, atol=1e-6)
            inward = -np.einsum("ij,ij->i", d.normal, rv) / dist
            assert np.all(inward >= -1e-9)                  # towards R
            np.testing.assert_allclose(np.einsum("ij,ij->i", d.tangential, rv), 0.0, atol=1e-9)
            dv = [s.velocity(p) - s.velocity(r) for s in (lo, hi)]
            fd = (dv[1] - dv[0]) / (2 * H) * QD
            np.testing.assert_allclose(d.total, fd, rtol=0, atol=1e-5 * scale_of(fd))


@pytest.mark.parametrize("name", ["slotted_link", "inverted_slider_crank", "whitworth",
                                  "swivel_guide", "offset_slider_crank"])
def test_relative_acceleration_parts(name):
    """Coriolis + sliding = a_P - a_G (1e-12), with G the guide's point under P: its
    acceleration from central differences of the guide's motion (G fixed in the guide), and
    the Coriolis part 2 omega k x (s' u) from differences of the slide and the guide's angle."""
    m = MECHANISMS[name]()
    sol = kl.analyze(m, q=Q, qd=QD, qdd=0.0, at_singular="flag", unreachable="mask")
    ok = regular(sol)
    lo, hi = neighbours(m, Q)
    ok &= regular(lo) & regular(hi)
    for j in (j for j in m.joints if j.type == "P"):
        rel = K.relative_acceleration(sol, j.name)
        guide = m.link(j.links[0])
        a_p = sol.acceleration(j.point)
        assert np.max(np.abs(rel.coriolis + rel.sliding - rel.total)[ok]) <= 1e-12 * scale_of(a_p[ok])
        # G: fixed in the guide, where P is at q; followed through the guide's rigid motion
        origin = guide.points[0]
        c, s = np.cos(sol.angle(guide.name)), np.sin(sol.angle(guide.name))
        d = sol.position(j.point) - sol.position(origin)
        local = np.stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]], axis=1)

        def g_velocity(x):
            th, o = x.angle(guide.name), x.position(origin)
            w = x.omega(guide.name)
            r = np.stack([np.cos(th) * local[:, 0] - np.sin(th) * local[:, 1],
                          np.sin(th) * local[:, 0] + np.cos(th) * local[:, 1]], axis=1)
            return x.velocity(origin) + w[:, None] * np.stack([-r[:, 1], r[:, 0]], axis=1)
        a_g = (g_velocity(hi) - g_velocity(lo)) / (2 * H) * QD
        np.testing.assert_allclose((a_p - a_g)[ok], rel.total[ok], rtol=0, atol=1e-5 * scale_of(a_p[ok]))
        s_dot = (hi.slide(j.name) - lo.slide(j.name)) / (2 * H) * QD
        omega = (np.unwrap(hi.angle(guide.name)) - np.unwrap(lo.angle(guide.name))) / (2 * H) * QD
        u = sol.slide_axes(j.name)
        coriolis = 2 * (omega * s_dot)[:, None] * np.stack([-u[:, 1], u[:, 0]], axis=1)
        np.testing.assert_allclose(rel.coriolis[ok], coriolis[ok], rtol=0,
                                   atol=1e-5 * scale_of(a_p[ok]))
        if guide.ground:
            assert np.all(rel.coriolis == 0.0)


def as_complex(v):
    return v[..., 0] + 1j * v[..., 1]


@pytest.mark.parametrize("name", MECHANISMS)
@pytest.mark.parametrize("sample", [3, 40])
def test_velocity_polygon(name, sample):
    """Every vertex is the point's velocity (central differences of its position), every
    side closes between its vertices, a difference side is perpendicular to its points'
    line, a relative side is along the slide, and each link's image is the link turned
    90 deg and scaled by omega (similar to the link)."""
    m, sol = sweep(name)
    assert regular(sol)[sample], "the samples chosen are regular configurations of every sweep"
    vp = K.velocity_polygon(sol, sample)
    lo, hi = (kl.analyze(m, q=Q[sample] + s * H, qd=QD) for s in (-1.0, 1.0))
    v_scale = scale_of(np.array(list(vp.vertices.values())))
    assert set(vp.vertices) == set(m.point_names)
    np.testing.assert_allclose(vp.pole, [0.0, 0.0])
    for p, v in vp.vertices.items():
        fd = (hi.position(p) - lo.position(p)) / (2 * H) * QD
        np.testing.assert_allclose(v, fd, rtol=0, atol=1e-6 * v_scale)
    pos = {p: sol.position(p)[sample] for p in m.point_names}
    for (p, r), side in vp.sides.items():
        np.testing.assert_allclose(side.vector, vp.vertex(p) - vp.vertex(r), atol=1e-14 * v_scale)
        if side.kind == "difference":
            if p in pos and r in pos:
                assert abs(np.dot(side.vector, pos[p] - pos[r])) <= 1e-12 * v_scale * np.linalg.norm(pos[p] - pos[r])
        else:
            u = sol.slide_axes(side.link)[sample]
            assert abs(side.vector[0] * u[1] - side.vector[1] * u[0]) <= 1e-12 * v_scale
            np.testing.assert_allclose(np.dot(side.vector, u), sol.slide_velocity(side.link)[sample],
                                       atol=1e-12 * v_scale)
    for link, image in vp.images.items():
        omega = sol.omega(link)[sample]
        pts = [p for p in image.points if p in pos]
        for p, r in itertools.combinations(pts, 2):
            ratio = (as_complex(vp.vertex(p) - vp.vertex(r)) / as_complex(pos[p] - pos[r]))
            np.testing.assert_allclose(ratio, 1j * omega, atol=1e-12 * v_scale)
        assert image.scale == pytest.approx(abs(omega), rel=1e-12)
        if omega:
            assert image.turn == pytest.approx(np.sign(omega) * np.pi / 2, abs=1e-12)


@pytest.mark.parametrize("name", MECHANISMS)
@pytest.mark.parametrize("sample", [3, 40])
def test_acceleration_polygon(name, sample):
    """Vertices are the engine's accelerations (checked against differences of its
    velocities elsewhere); every side is its parts' sum; each link's image is the link
    multiplied by -omega^2 + i alpha; the polygon's parts are those of the sweep-wide calls."""
    m, sol = sweep(name)
    assert regular(sol)[sample], "the samples chosen are regular configurations of every sweep"
    ap = K.acceleration_polygon(sol, sample)
    a_scale = scale_of(np.array(list(ap.vertices.values())))
    for p, a in ap.vertices.items():
        np.testing.assert_array_equal(a, sol.acceleration(p)[sample])
    pos = {p: sol.position(p)[sample] for p in m.point_names}
    for (p, r), parts in ap.parts.items():
        side = ap.sides[p, r]
        assert set(parts) <= {"normal", "tangential", "coriolis", "sliding"} and parts
        total = sum(parts.values())
        assert np.max(np.abs(total - side.vector)) <= 1e-12 * a_scale, (p, r)
        if side.kind == "difference":
            assert set(parts) == {"normal", "tangential"}
            if p in pos and r in pos:
                d = K.acceleration_difference(sol, p, r, link=side.link)
                np.testing.assert_allclose(parts["normal"], d.normal[sample], atol=1e-12 * a_scale)
                np.testing.assert_allclose(parts["tangential"], d.tangential[sample], atol=1e-12 * a_scale)
        else:
            rel = K.relative_acceleration(sol, side.link)
            np.testing.assert_allclose(parts["sliding"], rel.sliding[sample], atol=1e-12 * a_scale)
            assert ("coriolis" in parts) == (not m.link(m.joint(side.link).links[0]).ground)
    for link, image in ap.images.items():
        z = complex(-sol.omega(link)[sample] ** 2, sol.alpha(link)[sample])
        pts = [p for p in image.points if p in pos]
        for p, r in itertools.combinations(pts, 2):
            ratio = as_complex(ap.vertex(p) - ap.vertex(r)) / as_complex(pos[p] - pos[r])
            np.testing.assert_allclose(ratio, z, atol=1e-11 * a_scale)
        assert image.scale == pytest.approx(abs(z), rel=1e-12)


def test_polygon_of_one_configuration():
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=0.7, qd=3.0, qdd=1.0)
    vp, ap = K.velocity_polygon(sol), K.acceleration_polygon(sol, -1)
    assert vp.sample == ap.sample == 0 and vp.vertices["B"].shape == (2,)
    d = K.acceleration_difference(sol, "B", "A")
    assert d.total.shape == (2,) and d.link == "coupler"


# -- bad input ---------------------------------------------------------------------------
def test_points_on_different_links():
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=Q)
    with pytest.raises(ModelError, match=r"expected two points of one link, got 'B' and 'O2'.*"
                                         r"'B' is on 'coupler', 'rocker'"):
        K.acceleration_difference(sol, "B", "O2")
    with pytest.raises(ModelError, match=r"unknown|expected"):
        K.acceleration_difference(sol, "Z", "A")
    with pytest.raises(ModelError, match=r"link: expected a link that carries both 'B' and 'A', got 'rocker'"):
        K.acceleration_difference(sol, "B", "A", link="rocker")
    with pytest.raises(ModelError, match=r"expected a point other than 'A'"):
        K.acceleration_difference(sol, "A", "A")


def test_relative_acceleration_needs_a_prismatic_joint():
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=Q)
    with pytest.raises(ModelError):
        K.relative_acceleration(sol, "jO2")


@pytest.mark.parametrize("sample, match", [(len(Q), r"sample: expected 0 to 71 .*got 72"),
                                           (-len(Q) - 1, r"got -73"),
                                           (1.5, r"sample: expected a whole number"),
                                           (True, r"sample: expected a whole number")])
def test_sample_out_of_range(sample, match):
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=Q)
    for polygon in (K.velocity_polygon, K.acceleration_polygon):
        with pytest.raises(ModelError, match=match):
            polygon(sol, sample)


def test_singular_and_unassembled_samples_are_refused():
    sc = kl.mechanisms.slider_crank(1.0, 1.0)      # crank = rod: singular where B meets O2
    sol = kl.analyze(sc, q=np.array([0.3, np.pi / 2]), at_singular="flag")
    assert sol.singular[1]
    with pytest.raises(SingularityError, match=r"^sample 1: q = 1.5708 rad is a change point of dyad "
                                               r"'rod'-'slider' .*\(det J = 0\): .*; choose another "
                                               r"sample$") as info:
        K.velocity_polygon(sol, 1)
    assert info.value.sample == 1 and info.value.q == (np.pi / 2,)
    fb = kl.mechanisms.fourbar(3.0, 1.0, 1.5, 0.8)
    sol = kl.analyze(fb, q=np.array([0.0, np.pi]), unreachable="mask", at_singular="flag")
    bad = int(np.flatnonzero(~sol.assembled)[0])
    with pytest.raises(AssemblyError, match=rf"sample {bad}: the loops do not close"):
        K.acceleration_polygon(sol, bad)
