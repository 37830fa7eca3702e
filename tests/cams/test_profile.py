"""Disk cam profiles: pitch curves against an independent construction, pressure angles
against the pitch curve's numerical tangent, flat faces against the contact condition, radii
of curvature against the curves' own, the smallest base circle at its limit."""
import math

import numpy as np
import pytest

from kinelab.cams import Follower, MotionProgram, Segment, profile, smallest_base_circle
from kinelab.errors import ModelError

d = np.radians


def program(lift=0.025, law="cycloidal", second="3-4-5"):
    return MotionProgram([Segment("rise", 0, d(100), lift, law), Segment("dwell", d(100), d(160)),
                          Segment("return", d(160), d(280), lift, second),
                          Segment("dwell", d(280), d(360))])


def numerical_tangent(curve_of, theta, h=1e-6):
    """d(curve)/dtheta by central differences of the curve computed at theta -+ h."""
    return (curve_of(theta + h) - curve_of(theta - h)) / (2 * h)


def rotate(theta, xy):
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * xy[:, 0] - s * xy[:, 1], s * xy[:, 0] + c * xy[:, 1]], -1)


@pytest.mark.parametrize("e", [0.0, 0.008, -0.005])
def test_pitch_curve_is_the_follower_centre_turned_into_the_cam_frame(e):
    # the cam turns counterclockwise by theta: seen from the cam, the follower's centre
    # (e, sqrt(Rp**2 - e**2) + S) turns clockwise by theta (complex numbers, another route)
    p, rf, rb = program(), 0.012, 0.04
    theta = np.linspace(0, 2 * np.pi, 1441)
    cam = profile(p, Follower("roller", offset=e, roller_radius=rf), rb, theta=theta)
    centre = e + 1j * (math.sqrt((rb + rf) ** 2 - e ** 2) + p.svaj(theta).S)
    seen = centre * np.exp(-1j * theta)
    assert np.abs(cam.pitch[:, 0] + 1j * cam.pitch[:, 1] - seen).max() < 1e-15
    # the profile keeps the roller's radius from the pitch curve (no undercut here): the
    # nearest profile point to each pitch point is Rf away, up to the polyline's sampling
    gaps = np.hypot(*(cam.pitch[:, None, :] - cam.profile[None, :, :]).transpose(2, 0, 1))
    assert np.abs(gaps.min(axis=1) - rf).max() < 1e-6 and not cam.undercut.any()


@pytest.mark.parametrize("e", [0.0, 0.008, -0.005])
def test_translating_pressure_angle_against_the_pitch_curves_normal(e):
    p, rf, rb = program(), 0.012, 0.04
    f = Follower("roller", offset=e, roller_radius=rf)
    theta = np.linspace(0.01, 2 * np.pi - 0.01, 500)
    cam = profile(p, f, rb, theta=theta)
    t = numerical_tangent(lambda th: profile(p, f, rb, theta=th).pitch, theta)
    t_fixed = rotate(theta, t)                 # into the fixed frame
    normal = np.stack([-t_fixed[:, 1], t_fixed[:, 0]], -1)      # outward: the curve runs clockwise
    angle = np.arctan2(-normal[:, 0], normal[:, 1])     # from +y (the follower's motion), ccw
    assert np.abs(angle - cam.pressure_angle).max() < 1e-8
    sv = p.svaj(theta)
    closed = np.arctan((sv.V - e) / (sv.S + math.sqrt((rb + rf) ** 2 - e ** 2)))
    assert np.abs(closed - cam.pressure_angle).max() < 1e-14


def test_oscillating_pressure_angle_against_the_pitch_curves_normal():
    p = MotionProgram([Segment("rise", 0, d(120), d(18), "modified-sine"),
                       Segment("return", d(120), d(360), d(18), "cycloidal")])
    f = Follower("roller", "oscillating", roller_radius=0.01, pivot_distance=0.1, arm_length=0.08)
    theta = np.linspace(0.01, 2 * np.pi - 0.01, 400)
    rb = 0.03
    cam = profile(p, f, rb, theta=theta)
    pitch = lambda th: profile(p, f, rb, theta=th).pitch
    centre = lambda th: rotate(th, pitch(th))   # the roller's centre in the fixed frame
    n = rotate(theta, numerical_tangent(pitch, theta))
    n = np.stack([-n[:, 1], n[:, 0]], -1)
    # the roller centre's direction of motion as S grows: perpendicular to the arm
    arm = centre(theta) - np.array([0.1, 0.0])
    m = np.stack([arm[:, 1], -arm[:, 0]], -1)          # the arm turns clockwise as S grows
    angle = np.arctan2(m[:, 0] * n[:, 1] - m[:, 1] * n[:, 0], np.einsum("ij,ij->i", m, n))
    assert np.abs(angle - cam.pressure_angle).max() < 1e-8


@pytest.mark.parametrize("follower", [Follower("roller", offset=0.005, roller_radius=0.01),
                                      Follower("knife-edge"),
                                      Follower("roller", "oscillating", roller_radius=0.01,
                                               pivot_distance=0.1, arm_length=0.09)])
def test_pitch_curvature_against_the_curves_own(follower):
    p = program() if follower.motion == "translating" else MotionProgram(
        [Segment("rise", 0, d(150), d(15), "3-4-5"), Segment("return", d(150), d(360), d(15), "3-4-5")])
    theta = np.linspace(0.05, 2 * np.pi - 0.05, 300)
    rb = 0.04
    c = lambda th: profile(p, follower, rb, theta=th).pitch
    h = 1e-4
    c1 = (c(theta + h) - c(theta - h)) / (2 * h)
    c2 = (c(theta + h) - 2 * c(theta) + c(theta - h)) / h ** 2
    kappa = -(c1[:, 0] * c2[:, 1] - c1[:, 1] * c2[:, 0]) / np.hypot(*c1.T) ** 3
    cam = profile(p, follower, rb, theta=theta)
    assert np.abs(kappa - cam.pitch_curvature).max() < 1e-5 * np.abs(kappa).max()
    if follower.motion == "oscillating":
        return
    base = profile(p, follower, rb, theta=np.array([d(330)]))      # on the base circle
    assert base.pitch_radius[0] == pytest.approx(rb + follower.roller_radius, rel=1e-12)


@pytest.mark.parametrize("follower", [Follower("flat-faced"), Follower("flat-faced", offset=0.01),
                                      Follower("flat-faced", "oscillating", offset=0.005,
                                               pivot_distance=0.15)])
def test_flat_face_envelope_touches_every_face_position_and_supports_the_cam(follower):
    osc = follower.motion == "oscillating"
    p = MotionProgram([Segment("rise", 0, d(140), d(12) if osc else 0.015, "cycloidal"),
                       Segment("return", d(140), d(360), d(12) if osc else 0.015, "4-5-6-7")])
    rb = 0.04
    theta = np.linspace(0, 2 * np.pi, 2001)
    cam = profile(p, follower, rb, theta=theta)
    sv = p.svaj(theta)
    if osc:
        C, f = 0.15, 0.005
        g = np.arcsin((rb + f) / C) + sv.S
        nf = np.stack([np.sin(g), np.cos(g)], -1)       # the face's normal, away from the cam
        level = C * np.sin(g) - f                        # nf . q on the face
    else:
        nf = np.tile([0.0, 1.0], (len(theta), 1))
        level = rb + sv.S
    # the face's line in the cam's frame: the fixed normal turned back by theta
    N = rotate(-theta, nf)
    on_face = np.einsum("ij,ij->i", N, cam.profile) - level
    assert np.abs(on_face).max() < 1e-14
    # the face is tangent there (the contact condition) and the whole cam lies behind it
    t = numerical_tangent(lambda th: profile(p, follower, rb, theta=th).profile, theta[1:-1])
    assert np.abs(np.einsum("ij,ij->i", N[1:-1], t)).max() < 1e-8
    reach = (N @ cam.profile.T).max(axis=1) - level
    assert reach.max() < 1e-12
    if not osc:
        assert cam.contact[:, 0] == pytest.approx(sv.V, abs=1e-15)
        assert cam.profile_radius == pytest.approx(rb + sv.S + sv.A, abs=1e-15)
        assert cam.face == (sv.V.min(), sv.V.max()) and not cam.pressure_angle.any()


def test_flat_face_radius_of_curvature_against_the_envelopes_own():
    p = program(0.02)
    f = Follower("flat-faced", "oscillating", offset=0.0, pivot_distance=0.12)
    pp = MotionProgram([Segment("rise", 0, d(150), d(10), "3-4-5"),
                        Segment("return", d(150), d(360), d(10), "3-4-5")])
    for prog, fol in ((p, Follower("flat-faced")), (pp, f)):
        theta = np.linspace(0.05, 2 * np.pi - 0.05, 300)
        c = lambda th: profile(prog, fol, 0.03, theta=th).profile
        h = 1e-4
        c1 = (c(theta + h) - c(theta - h)) / (2 * h)
        c2 = (c(theta + h) - 2 * c(theta) + c(theta - h)) / h ** 2
        rho = -np.hypot(*c1.T) ** 3 / (c1[:, 0] * c2[:, 1] - c1[:, 1] * c2[:, 0])
        cam = profile(prog, fol, 0.03, theta=theta)
        assert np.abs(rho - cam.profile_radius).max() < 1e-5 * np.abs(rho).max()


@pytest.mark.parametrize("e", [0.0, 0.01])
def test_smallest_base_circle_meets_the_pressure_angle_with_equality(e):
    p, limit = program(), d(30)
    f = Follower("roller", offset=e, roller_radius=0.01)
    rb = smallest_base_circle(p, f, limit)
    fine = np.linspace(0, 2 * np.pi, 200001)
    reached = np.abs(profile(p, f, rb, theta=fine).pressure_angle).max()
    assert reached == pytest.approx(limit, abs=1e-9)
    assert np.abs(profile(p, f, rb * 0.99, theta=fine).pressure_angle).max() > limit + 1e-4


def test_smallest_base_circle_of_an_oscillating_roller():
    p = MotionProgram([Segment("rise", 0, d(120), d(20), "cycloidal"),
                       Segment("return", d(120), d(360), d(20), "cycloidal")])
    f = Follower("roller", "oscillating", roller_radius=0.01, pivot_distance=0.12, arm_length=0.1)
    rb = smallest_base_circle(p, f, d(30))
    theta = np.linspace(0, 2 * np.pi, 3601)
    assert np.abs(profile(p, f, rb, theta=theta).pressure_angle).max() == pytest.approx(d(30), abs=1e-9)
    assert np.abs(profile(p, f, rb * 0.99, theta=theta).pressure_angle).max() > d(30)


def test_smallest_flat_faced_base_circle_has_no_cusp():
    p = MotionProgram([Segment("rise", 0, d(60), 0.03, "cycloidal"),
                       Segment("return", d(60), d(360), 0.03, "cycloidal")])
    f = Follower("flat-faced")
    sv = p.svaj(np.linspace(0, 2 * np.pi, 200001))
    bound = -(sv.S + sv.A).min()
    rb = smallest_base_circle(p, f, min_radius=0.0)
    assert rb == pytest.approx(bound, rel=1e-8) and bound > 0     # refined below the grid's
    assert rb >= bound
    rb2 = smallest_base_circle(p, f, min_radius=0.002)
    assert profile(p, f, rb2, samples=200001).profile_radius.min() == pytest.approx(0.002, abs=1e-9)
    assert profile(p, f, 0.9 * bound, samples=3601).undercut.any()


def test_a_roller_larger_than_the_convex_radius_undercuts():
    p = MotionProgram([Segment("rise", 0, d(40), 0.03, "cycloidal"),
                       Segment("return", d(40), d(360), 0.03, "cycloidal")])
    small = profile(p, Follower("roller", roller_radius=0.002), 0.03, samples=3601)
    big = profile(p, Follower("roller", roller_radius=0.015), 0.03, samples=3601)
    rho = big.pitch_radius
    convex_min = rho[rho > 0].min()
    assert 0.002 < convex_min < 0.015
    assert not small.undercut.any() and big.undercut.any()
    assert np.all(big.undercut == ((rho > 0) & (rho <= 0.015)))
    assert (big.profile_radius[big.undercut] <= 0).all()    # the profile's radius changes sign


def test_bad_geometry_is_refused():
    p = program()
    with pytest.raises(ModelError, match="must exceed the offset"):
        profile(p, Follower("roller", offset=0.05, roller_radius=0.01), 0.02)
    with pytest.raises(ModelError, match="expected a roller's radius above 0"):
        Follower("roller")
    with pytest.raises(ModelError, match=r"follower.type: expected one of .* \(did you mean 'roller'\?\)"):
        Follower("rollr")
    with pytest.raises(ModelError, match="expected a radius above 0"):
        profile(p, Follower("knife-edge"), -1.0)


@pytest.mark.parametrize("k", [1e-4, 1e4])
def test_a_cam_scaled_has_the_same_angles_and_flags(k):
    """Scale-free: every length times k gives the same pressure angles and undercuts, and
    lengths (radii, the smallest base circle) times k."""
    def cam_of(s):
        p = MotionProgram([Segment("rise", 0, d(40), 0.03 * s, "cycloidal"),
                           Segment("return", d(40), d(360), 0.03 * s, "modified-trapezoid")])
        f = Follower("roller", offset=0.004 * s, roller_radius=0.015 * s)
        return p, f, profile(p, f, 0.03 * s, samples=1441)
    (p1, f1, a), (pk, fk, b) = cam_of(1.0), cam_of(k)
    assert b.pressure_angle == pytest.approx(a.pressure_angle, abs=1e-12)
    assert (b.undercut == a.undercut).all() and a.undercut.any()
    assert b.pitch_radius == pytest.approx(a.pitch_radius * k, rel=1e-9)
    assert smallest_base_circle(pk, fk, d(35)) == pytest.approx(
        smallest_base_circle(p1, f1, d(35)) * k, rel=1e-9)
