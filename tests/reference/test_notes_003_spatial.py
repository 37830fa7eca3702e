"""Worked numbers of *Mecanismos* (§4.3, §7.3-§7.6), each checked by hand before use.

Where the notes leave the geometry to a figure that is not in the text (Ex. 6.1, Ex. 6.2),
the geometry kinelab chose is stated here and in docs/spatial.md, and the expected numbers
are derived independently (by hand or with exact sympy arithmetic) from that statement.
"""
import numpy as np
import pytest
import sympy as sym
from scipy.spatial.transform import Rotation

import kinelab.spatial as sp
from kinelab.errors import SingularityError

deg = np.radians


# -- §4.3 Ex. 4.1: RR robot ---------------------------------------------------------------------

def test_rr_ex_4_1():
    # l1 = l2 = 1, θ1 = 30°, θ2 = 60°: P = (cos 30° + cos 90°, sin 30° + sin 90°) = (√3/2, 1.5).
    P = sp.rr(1.0, 1.0).forward(deg([30.0, 60.0]))
    np.testing.assert_allclose(P, [np.sqrt(3) / 2, 1.5], rtol=0, atol=1e-15)


def test_rr_ex_4_1_inverse_gives_both_elbows():
    # By hand: the elbow at (0, 1) (θ1 = 90°, θ2 = -60°) also reaches P.
    q = sp.rr(1.0, 1.0).inverse([np.sqrt(3) / 2, 1.5])
    np.testing.assert_allclose(np.degrees(q), [[90.0, -60.0], [30.0, 60.0]], rtol=0, atol=1e-12)


# -- §7.5: RRR robot ----------------------------------------------------------------------------

P_778 = [np.sqrt(2) / 4, np.sqrt(2) / 4, 1 + np.sqrt(3) / 2]


def test_rrr_forward_eq_78():
    # θ = (-45°, 60°, 30°): ρ = cos 60° + cos 90° = 1/2, x = -sin(-45°) ρ = √2/4,
    # y = cos(-45°) ρ = √2/4, z = sin 60° + sin 90° = 1 + √3/2 (as printed).
    P = sp.rrr(1.0, 1.0).forward(deg([-45.0, 60.0, 30.0]))
    np.testing.assert_allclose(P, P_778, rtol=0, atol=1e-15)


def test_rrr_inverse_all_four_solutions():
    # The notes print (θ2, θ3) = (90°, -30°) and (60°, 30°), both with θ1 = -45° (shoulder
    # front).  Shoulder back: θ1 = 135°, θ2 -> 180° - θ2, θ3 -> -θ3, i.e. (135°, 90°, 30°) and
    # (135°, 120°, -30°); by hand, (135°, 90°, 30°) gives ρ = cos 90° + cos 120° = -1/2,
    # x = -sin 135° (-1/2) = √2/4, y = cos 135° (-1/2) = √2/4, z = sin 90° + sin 120°.
    q = sp.rrr(1.0, 1.0).inverse(P_778)
    expected = [[-45.0, 90.0, -30.0],    # front-up   (the notes' θ')
                [-45.0, 60.0, 30.0],     # front-down (the notes' θ'')
                [135.0, 90.0, 30.0],     # back-up
                [135.0, 120.0, -30.0]]   # back-down
    np.testing.assert_allclose(np.degrees(q), expected, rtol=0, atol=1e-12)


def test_rrr_eq_79_coefficients_vanish_on_the_front_solutions():
    # E = -2 √(x² + y²) L2 = -1, F = -2 z L2 = -(2 + √3), G = x² + y² + z² + L2² - L3² = 2 + √3.
    E, F, G = -1.0, -(2 + np.sqrt(3)), 2 + np.sqrt(3)
    for theta2 in deg([90.0, 60.0]):
        assert E * np.cos(theta2) + F * np.sin(theta2) + G == pytest.approx(0.0, abs=1e-15)


def test_rrr_point_on_the_base_axis_is_singular():
    with pytest.raises(SingularityError, match="θ1 is arbitrary"):
        sp.rrr(1.0, 1.0).inverse([0.0, 0.0, 1.5])


# -- §7.3: RSSR ---------------------------------------------------------------------------------

def test_rssr_section_7_3():
    # θ1 = 0, H1 = H3 = 1, L1 = L3 = 0, L0 = L2 = 1: E = 2[(0 - 1)0 - 1] = -2,
    # F = 2[(0 - 1)1 + 0] = -2, G = 1 + 1 + 1 + 0 - 1 = 2; -2 cos θ3 - 2 sin θ3 + 2 = 0 has
    # θ3 = 0° and 90° (as printed).
    m = sp.RSSR(H1=1.0, L1=0.0, L0=1.0, L2=1.0, H3=1.0, L3=0.0)
    pos = m.positions(0.0)
    assert (float(pos.E), float(pos.F), float(pos.G)) == (-2.0, -2.0, 2.0)
    np.testing.assert_allclose(np.degrees(pos.theta3), [90.0, 0.0], rtol=0, atol=1e-12)
    # Feasibility: at θ3 = 90° the output ball joint B = (0, L0 - H3, 0) = O lies on the
    # input shaft (the y0 axis), inside the input crank's hub; at θ3 = 0°, B = (0, 1, 1),
    # a coupler of length 1 along y0 from A = (0, 0, 1).  The notes keep θ3 = 0°.
    np.testing.assert_allclose(pos.B, [[0, 0, 0], [0, 1, 1]], rtol=0, atol=1e-15)
    np.testing.assert_allclose(pos.A, [0, 0, 1], rtol=0, atol=0)
    assert m.analyze(0.0, branch=-1).theta3 == 0.0


# -- §7.4: Cardan joint -------------------------------------------------------------------------

@pytest.mark.parametrize("phi1", deg([0.0, 30.0, 60.0, 120.0, 210.0, 300.0]))
def test_cardan_eq_75(phi1):
    beta = deg(35.0)
    phi2 = sp.cardan_output(phi1, beta)
    assert np.tan(phi2) == pytest.approx(np.tan(phi1) * np.cos(beta), rel=1e-13, abs=1e-15)


def test_cardan_eq_76_by_hand():
    # β = 60°: cos β = 1/2, sin² β = 3/4.  φ1 = 0: ratio 1/2; φ1 = 90°: (1/2)/(1 - 3/4) = 2;
    # φ1 = 45°: (1/2)/(1 - 3/8) = 4/5.
    r = sp.cardan_velocity_ratio(deg([0.0, 90.0, 45.0]), deg(60.0))
    np.testing.assert_allclose(r, [0.5, 2.0, 0.8], rtol=1e-15)


def test_cardan_section_7_4_limits():
    # β = 0: φ2 = φ1.
    phi1 = np.linspace(-7, 7, 29)
    np.testing.assert_allclose(sp.cardan_output(phi1, 0.0), phi1, rtol=0, atol=0)


def test_double_cardan_fig_60():
    # Coplanar shafts, equal bends, intermediate yokes in one plane: φ3 = φ1 in both the
    # parallel (Z) and the 2β (W) arrangement.
    phi1 = np.linspace(0, 2 * np.pi, 73)
    for arrangement in ("Z", "W"):
        m = sp.double_cardan(phi1, deg(30.0), deg(30.0), arrangement=arrangement)
        np.testing.assert_allclose(m.phi3, phi1, rtol=0, atol=1e-14)


# -- §7.6 Ex. 6.1: PRR robot --------------------------------------------------------------------

def test_prr_ex_6_1():
    # kinelab's geometry (the figure is not in the text; see kinelab.spatial.prr):
    # P = (D + L1 cos θ2 + L2 cos(θ2 + θ3), L1 sin θ2 + L2 sin(θ2 + θ3), d1 + H - V).
    # (d) d1 = 0.7, θ2 = 60°, θ3 = 30°, D = H = V = 0.1, L1 = L2 = 1:
    # x = 0.1 + 0.5 + 0 = 0.6, y = √3/2 + 1, z = 0.7.
    robot = sp.prr(1.0, 1.0, D=0.1, H=0.1, V=0.1)
    q = [0.7, deg(60.0), deg(30.0)]
    np.testing.assert_allclose(robot.forward(q), [0.6, 1 + np.sqrt(3) / 2, 0.7], rtol=0,
                               atol=1e-15)
    # (e) two assembly configurations: the elbow on either side.
    solutions = robot.inverse(robot.forward(q))
    assert len(solutions) == 2
    np.testing.assert_allclose(solutions[1], q, rtol=0, atol=1e-12)      # "right": θ3 > 0


# -- §7.6 Ex. 6.2: 6-SPS platform ---------------------------------------------------------------
# The figure (top view) is not in the text.  kinelab's reading, stated in docs/spatial.md:
#   base triangle side 1 m, O at the midpoint of AC, x0 from A to C, y0 towards B, z0 up:
#     A = (-1/2, 0, 0), C = (1/2, 0, 0), B = (0, √3/2, 0);
#   platform triangle side 0.2 m, frame M x1 y1 z1 at M, x1 from M to N, N over C, P over B:
#     M = (0, 0, 0), N = (0.2, 0, 0), P = (0.1, 0.1 √3, 0);
#   legs (3-3, each vertex in two legs): d1 A-M, d2 A-N, d3 C-N, d4 C-P, d5 B-P, d6 B-M;
#   pose: Trans(0.866 m, z0) Trans(0.2 m, x0), then Rot(15°) about the vertical through M,
#   then Rot(30°) about the moving x1: 0_T_1 = Trans(0.2, 0, 0.866) Rot(z, 15°) Rot(x, 30°).

EX_6_2_BASE = np.array([[-0.5, 0, 0], [-0.5, 0, 0], [0.5, 0, 0], [0.5, 0, 0],
                        [0, np.sqrt(3) / 2, 0], [0, np.sqrt(3) / 2, 0]])
EX_6_2_TOP = np.array([[0, 0, 0], [0.2, 0, 0], [0.2, 0, 0], [0.1, 0.1 * np.sqrt(3), 0],
                       [0.1, 0.1 * np.sqrt(3), 0], [0, 0, 0]])
EX_6_2_ROTATION = sp.euler_rotation("zx", [15.0, 30.0], axes="moving", degrees=True)
EX_6_2_POSITION = [0.2, 0.0, 0.866]


def ex_6_2_exact():
    """The six leg lengths in exact arithmetic (sympy), from the statement above."""
    r3, half, fifth = sym.sqrt(3), sym.Rational(1, 2), sym.Rational(1, 5)
    base = {"A": (-half, 0, 0), "B": (0, r3 / 2, 0), "C": (half, 0, 0)}
    top = {"M": (0, 0, 0), "N": (fifth, 0, 0), "P": (fifth / 2, fifth * r3 / 2, 0)}
    g, a = sym.pi / 12, sym.pi / 6
    Rz = sym.Matrix([[sym.cos(g), -sym.sin(g), 0], [sym.sin(g), sym.cos(g), 0], [0, 0, 1]])
    Rx = sym.Matrix([[1, 0, 0], [0, sym.cos(a), -sym.sin(a)], [0, sym.sin(a), sym.cos(a)]])
    p = sym.Matrix([fifth, 0, sym.Rational(866, 1000)])
    legs = ("AM", "AN", "CN", "CP", "BP", "BM")
    return [float((p + Rz * Rx * sym.Matrix(top[t]) - sym.Matrix(base[b])).norm())
            for b, t in legs]


def test_stewart_ex_6_2_leg_lengths():
    d = sp.stewart_leg_lengths(EX_6_2_BASE, EX_6_2_TOP, EX_6_2_POSITION, EX_6_2_ROTATION)
    np.testing.assert_allclose(d, ex_6_2_exact(), rtol=0, atol=1e-15)


def test_stewart_ex_6_2_platform_vertices():
    # Item (b): M, N, P in the base frame.  M is the translation itself; N = M + 0.2 (cos 15°,
    # sin 15°, 0), since Rot(x1) leaves the x1 axis in place.
    world = sp.transform_points(sp.homogeneous(EX_6_2_ROTATION, EX_6_2_POSITION), EX_6_2_TOP[[0, 1, 3]])
    np.testing.assert_allclose(world[0], [0.2, 0, 0.866], rtol=0, atol=1e-15)
    np.testing.assert_allclose(world[1], [0.2 + 0.2 * np.cos(deg(15)), 0.2 * np.sin(deg(15)),
                                          0.866], rtol=0, atol=1e-15)


def test_stewart_ex_6_2_forward_recovers_the_pose():
    d = sp.stewart_leg_lengths(EX_6_2_BASE, EX_6_2_TOP, EX_6_2_POSITION, EX_6_2_ROTATION)
    pose = sp.stewart_forward(EX_6_2_BASE, EX_6_2_TOP, d, [0.25, 0.05, 0.8],
                              Rotation.from_euler("z", 0.2))
    np.testing.assert_allclose(pose.position, EX_6_2_POSITION, rtol=0, atol=1e-10)
    assert (pose.rotation * EX_6_2_ROTATION.inv()).magnitude() < 1e-10
